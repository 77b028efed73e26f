//! The cost model of [geotracks](https://github.com/geotracks/geotracks): how long a straight
//! segment inside one triangle is.
//!
//! The propagation engine of geotracks never measures anything itself. Every time it
//! needs the cost of going from one point of a face to another point of the *same* face
//! (both on the face's closure), it asks a [`Metric`]. That is the whole contract, and
//! it is why this crate depends on nothing of the engine: a user who plugs a custom cost
//! implements one method on one struct.
//!
//! Built-ins:
//! - [`Euclidean`]: the length of the segment.
//! - [`Density`]: a positive scalar per vertex, linear on each face; a segment costs its
//!   exact integral, `|b − a| · (ρ(a) + ρ(b)) / 2`.
//! - [`Tensor`]: a symmetric positive-definite 2×2 tensor per face, in the face's plane;
//!   a segment costs `sqrt(vᵀ M v)` with `v = b − a`.
//! - [`TensorField`]: an SPD tensor per vertex, linear across each face (a smooth
//!   Riemannian metric); a segment costs the exact integral of `sqrt(vᵀ M v)` along it.
//!
//! Euclidean and Tensor are norms on each face (the triangle inequality holds inside a
//! face), so the track pruning of geotracks is exact for them. Density is not a norm:
//! pruning is then a very good heuristic, not a proof.
//!
//! # Points and frames
//! A [`FacePoint`] carries both its position in the face's local 2D frame (`uv`) and its
//! barycentric coordinates (`bary`, in the face's vertex order). The local frame puts
//! corner 0 at the origin, corner 1 on the positive u axis and corner 2 in the upper
//! half plane; [`FaceGeometry::face_axes`] gives the world directions of u and v.
//!
//! # A custom metric
//! ```
//! use geotracks_metrics::{FacePoint, Metric};
//!
//! /// Moving costs twice as much in the v direction of every face's frame.
//! struct Stretched;
//!
//! impl Metric for Stretched {
//!     fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
//!         let (du, dv) = (b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]);
//!         (du * du + 4.0 * dv * dv).sqrt()
//!     }
//! }
//!
//! let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
//! let b = FacePoint { uv: [0.0, 1.0], bary: [0.0, 0.0, 1.0] };
//! assert_eq!(Stretched.cost(0, &a, &b), 2.0);
//! ```
#![forbid(unsafe_code)]

mod builtin;
mod density;
mod error;
mod euclidean;
mod num;
mod tensor;
mod tensor_field;

pub use builtin::BuiltinMetric;
pub use density::Density;
pub use error::MetricError;
pub use euclidean::Euclidean;
pub use num::Num;
pub use tensor::Tensor;
pub use tensor_field::TensorField;

/// A point on the closure of one face, as the engine hands it to a [`Metric`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePoint {
    /// Position in the face's local 2D frame (corner 0 at the origin, corner 1 on the
    /// positive u axis, corner 2 in the upper half plane).
    pub uv: [f64; 2],
    /// Barycentric coordinates with respect to the face's corners, in the face's vertex
    /// order; they sum to 1.
    pub bary: [f64; 3],
}

impl FacePoint {
    /// Euclidean length of the segment from `self` to `other` (both in one face's frame).
    #[inline]
    pub fn distance(&self, other: &FacePoint) -> f64 {
        let (du, dv) = (other.uv[0] - self.uv[0], other.uv[1] - self.uv[1]);
        let squared = du * du + dv * dv;
        // `hypot` only where the square over- or underflows (lengths beyond 1e154 or
        // below 1e-154), or is 0: its care costs several times a square root, and the
        // branch is all but always taken the same way. One integer comparison tells a
        // normal square (≥ 0 here) from the rest: below the least normal, the
        // subtraction wraps around; ∞ and NaN lie above the range.
        const MIN: u64 = f64::MIN_POSITIVE.to_bits();
        const RANGE: u64 = f64::INFINITY.to_bits() - MIN;
        if squared.to_bits().wrapping_sub(MIN) < RANGE {
            squared.sqrt()
        } else {
            du.hypot(dv)
        }
    }
}

/// The cost of straight segments inside faces: what the engine asks of a metric (and,
/// for the rare meshes with wires, their cost: [`Metric::wire_cost`]).
///
/// Implementations must be deterministic, non-negative, and zero only for `a == b`.
/// They are called in the engine's innermost loop, so keep them cheap: precompute
/// per-face data in the constructor.
///
/// # Direction
/// `cost(f, a, b)` is the cost of travelling from `a` to `b`. Most metrics are
/// symmetric, `cost(f, a, b) == cost(f, b, a)` (the default of
/// [`Metric::is_symmetric`]). A *directed* metric (climbing dearer than descending,
/// a current, a wind: a Finsler metric) says so with `is_symmetric() == false`; the
/// engine then measures every segment in the direction it is travelled, away from the
/// sources, so a field is the cost *from* the sources. The cost of reaching the
/// sources (a field *to* them) is a run under [`Reversed`].
///
/// ```
/// use geotracks_metrics::{FacePoint, Metric, Reversed};
///
/// /// Moving in +u costs half what moving in −u does (a tail wind along u).
/// struct Wind;
///
/// impl Metric for Wind {
///     fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
///         let du = b.uv[0] - a.uv[0];
///         // A Randers norm: |v| + w·v with |w| < 1 stays positive and convex.
///         a.distance(b) - 0.5 * du
///     }
///     fn is_symmetric(&self) -> bool {
///         false
///     }
///     fn is_face_norm(&self) -> bool {
///         true // an asymmetric norm: the triangle inequality holds one way round
///     }
/// }
///
/// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
/// let b = FacePoint { uv: [1.0, 0.0], bary: [0.0, 1.0, 0.0] };
/// assert_eq!(Wind.cost(0, &a, &b), 0.5);
/// assert_eq!(Wind.cost(0, &b, &a), 1.5);
/// assert_eq!(Reversed(Wind).cost(0, &a, &b), 1.5);
/// ```
pub trait Metric: Sync {
    /// Cost of the straight segment from `a` to `b`, both on the closure of face `face`.
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64;

    /// Whether `cost(f, a, b) == cost(f, b, a)` for all faces and points (the default),
    /// and `wire_cost(a, b, l) == wire_cost(b, a, l)`. A directed metric returns
    /// `false` (see the trait's docs); the engine then caches no step costs along
    /// edges, since they differ by direction. Saying `true` of a directed metric gives
    /// wrong distances.
    fn is_symmetric(&self) -> bool {
        true
    }

    /// Whether the cost is a norm of `b − a` on each face, or for a directed metric an
    /// asymmetric norm (positively homogeneous, convex: the triangle inequality
    /// `cost(a, c) ≤ cost(a, b) + cost(b, c)` holds for points in that order). Track
    /// pruning is exact for such metrics: its crossing lemma adds costs along straight
    /// segments in their direction of travel only. Defaults to `false`.
    fn is_face_norm(&self) -> bool {
        false
    }

    /// Whether the engine may prune by the crossing lemma inside `face`: true where the
    /// cost is a norm of `b − a` there, or close enough that pruning stays accurate.
    /// Defaults to [`Metric::is_face_norm`]; a metric that is a norm on some faces only
    /// (a density that is constant on them, say) can say so face by face.
    fn prunes_on(&self, face: u32) -> bool {
        let _ = face;
        self.is_face_norm()
    }

    /// The face's flattening: the Gram matrix `[g11, g12, g22]` of the metric in the
    /// face's local frame, such that a segment `v = b − a` costs `sqrt(vᵀ G v)`, if the
    /// cost is such a constant norm on the face; `None` (the default) otherwise.
    ///
    /// A metric that gives it for every face is *face-flat*: each face maps isometrically
    /// onto a plane, and the wavefront engine of geotracks then lets every Steiner node
    /// carry the wave that reached it (a virtual source in the flattened plane), which
    /// makes it exact on planar and developable meshes and far more accurate elsewhere.
    /// `Euclidean` gives the identity, `Tensor` its matrix. The engine trusts the
    /// answer: `cost` must agree with it.
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        let _ = face;
        None
    }

    /// How far the triangle inequality may fail inside `face`, whose longest edge is
    /// `diameter` long: a bound `s` with `cost(a, b) ≤ cost(a, x) + cost(x, b) + s` for
    /// all points `a`, `b`, `x` of the face. The engine prunes on faces where
    /// [`Metric::prunes_on`] holds, and there keeps exactly the complete Steiner graph's
    /// distances by accepting a proof only with a margin of this slack (twice it where
    /// the proof uses the inequality twice). 0 for a norm (the default); `Density`
    /// gives `(ρmax − ρmin) · diameter`. A larger slack prunes less, never wrongly.
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        let _ = (face, diameter);
        0.0
    }

    /// Cost of the wire from vertex `a` to vertex `b`, `length` long (Euclidean): a
    /// line element that is no edge of a face (a medial axis's free curves), which
    /// distances travel from end to end. The default is `length`: a wire has no face
    /// whose cost could weigh it (so `Tensor` and custom metrics charge its length).
    /// A metric with per-vertex data can do better; `Density` charges
    /// `length · (ρ(a) + ρ(b)) / 2`. The same rules as for [`Metric::cost`] hold: ≥ 0,
    /// `+inf` for a wire that cannot be crossed, from `a` to `b` for a directed metric.
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        let _ = (a, b);
        length
    }

    /// A lower bound `m ≥ 0` on the cost per unit of Euclidean length: every segment
    /// costs at least `m · |b − a|` (in each direction, for a directed metric), and
    /// every wire at least `m` times its length. The default, 0, promises nothing.
    ///
    /// A positive bound makes runs that stop at targets *goal-directed* (A*): a node
    /// is ordered by its value plus `m` times its straight-line distance to the
    /// targets, which no path from it can undercut, so a route between two points
    /// settles a corridor around it rather than a disc. The engine checks the bound on
    /// every edge when a solver is built ([`Metric::cost`] of each edge against `m`
    /// times its length, allowing for the rounding of a length next to large
    /// coordinates, 1e-13 of them, and then lowering `m` to the cheapest edge it
    /// found); a bound that holds on edges but not inside faces gives wrong
    /// early-stopped distances. `Euclidean` gives 1, `Density` its least density,
    /// `Tensor` the square root of its least eigenvalue.
    fn min_cost_per_length(&self) -> f64 {
        0.0
    }

    /// A short name for reports, e.g. `"euclidean"`.
    fn name(&self) -> &str {
        "custom"
    }

    /// The cost of a segment of face `face` whose ends slide along lines, from
    /// `a + s·da` to `b + t·db`, at `s = t = 0`, with its first and second derivatives
    /// in `s` and `t` ([`SlidingCost`]): exactly what finite differences of
    /// [`Metric::cost`] estimate. `da` and `db` are the ends' velocities, in the face's
    /// frame and in barycentric coordinates (which then sum to 0); a zero velocity
    /// holds an end still.
    ///
    /// geotracks' path straightener takes Newton steps on the crossings of a path,
    /// each sliding along its edge, and asks this of every segment at every step; nine
    /// calls of [`Metric::cost`] estimate the same by central differences, several
    /// times slower. `None` (the default) where the metric gives no formula, or where
    /// its formula breaks down (a segment of length 0, a cost beyond the f64 range):
    /// the differences stand in. `Euclidean`, `Density` and `Tensor` give it, and so
    /// do geotracks' directed terrain costs (`DirectedCost`).
    ///
    /// ```
    /// use geotracks_metrics::{Euclidean, FacePoint, Metric};
    /// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
    /// let b = FacePoint { uv: [3.0, 4.0], bary: [0.0, 0.0, 1.0] };
    /// // `b` slides along u.
    /// let db = FacePoint { uv: [1.0, 0.0], bary: [0.0, 0.0, 0.0] };
    /// let still = FacePoint { uv: [0.0, 0.0], bary: [0.0, 0.0, 0.0] };
    /// let d = Euclidean.sliding_cost(0, &a, &still, &b, &db).unwrap();
    /// assert_eq!(d.cost, 5.0);
    /// assert!((d.gradient[1] - 0.6).abs() < 1e-15); // d|b − a|/dt = u / |b − a|
    /// assert!((d.hessian[2] - 0.128).abs() < 1e-15); // v² / |b − a|³
    /// assert_eq!(d.gradient[0], 0.0); // `a` holds still
    /// ```
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        let _ = (face, a, da, b, db);
        None
    }
}

/// A segment's cost with its derivatives as its ends slide ([`Metric::sliding_cost`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlidingCost {
    /// The cost at `s = t = 0`.
    pub cost: f64,
    /// `[∂/∂s, ∂/∂t]`.
    pub gradient: [f64; 2],
    /// `[∂²/∂s², ∂²/∂s∂t, ∂²/∂t²]`.
    pub hessian: [f64; 3],
}

impl SlidingCost {
    /// [`Metric::sliding_cost`] for the norm `sqrt(vᵀ G v)` of `v = b − a` (`G`:
    /// `[g11, g12, g22]`, symmetric positive-semidefinite, in the face's frame): with
    /// `n = sqrt(vᵀ G v)`, its gradient in `v` is `G v / n` and its Hessian
    /// `(G − (G v)(G v)ᵀ / n²) / n`, and `v` moves by `db − da`. `None` for a segment
    /// whose squared norm is not a normal number (0, or beyond the f64 range). What
    /// `Euclidean` (`G = I`) and `Tensor` give, and a start for metrics built on a
    /// norm.
    ///
    /// ```
    /// use geotracks_metrics::{FacePoint, SlidingCost};
    /// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
    /// let b = FacePoint { uv: [1.0, 1.0], bary: [0.0, 0.0, 1.0] };
    /// let still = FacePoint { uv: [0.0, 0.0], bary: [0.0, 0.0, 0.0] };
    /// // Twice the cost along u: sqrt(4 du² + dv²).
    /// let d = SlidingCost::norm([4.0, 0.0, 1.0], &a, &still, &b, &still).unwrap();
    /// assert_eq!(d.cost, 5f64.sqrt());
    /// ```
    pub fn norm(
        g: [f64; 3],
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        let [g11, g12, g22] = g;
        let v = [b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]];
        let gv = [g11 * v[0] + g12 * v[1], g12 * v[0] + g22 * v[1]];
        let squared = v[0] * gv[0] + v[1] * gv[1];
        if !squared.is_normal() {
            return None;
        }
        let n = squared.sqrt();
        // How `v` moves with `s` (`a` moves forward, so `v` back) and with `t`.
        let (vs, vt) = ([-da.uv[0], -da.uv[1]], db.uv);
        let dot = |x: [f64; 2], y: [f64; 2]| x[0] * y[0] + x[1] * y[1];
        let (gs, gt) = (dot(gv, vs) / n, dot(gv, vt) / n);
        // xᵀ G y, less the rank-one part, over n.
        let second = |x: [f64; 2], y: [f64; 2], gx: f64, gy: f64| {
            let gxy = g11 * x[0] * y[0] + g12 * (x[0] * y[1] + x[1] * y[0]) + g22 * x[1] * y[1];
            (gxy - gx * gy) / n
        };
        SlidingCost {
            cost: n,
            gradient: [gs, gt],
            hessian: [
                second(vs, vs, gs, gs),
                second(vs, vt, gs, gt),
                second(vt, vt, gt, gt),
            ],
        }
        .finite()
    }

    /// The same segment travelled the other way (its ends and their parameters
    /// swapped): what [`Reversed`] gives.
    fn swapped(self) -> SlidingCost {
        let [s, t] = self.gradient;
        let [ss, st, tt] = self.hessian;
        SlidingCost {
            cost: self.cost,
            gradient: [t, s],
            hessian: [tt, st, ss],
        }
    }

    /// The same by central differences of `cost(s, t)` with step `h` (nine calls; a
    /// still end, `moving[i] == false`, gets derivatives 0 and costs no calls): what
    /// stands in for [`Metric::sliding_cost`] where a metric gives no formula, and the
    /// check of those that do.
    ///
    /// ```
    /// use geotracks_metrics::SlidingCost;
    /// let d = SlidingCost::by_differences(|s, t| s * s * t, 1e-3, [true, true]);
    /// assert!((d.hessian[2]).abs() < 1e-9 && d.gradient[0].abs() < 1e-9);
    /// ```
    pub fn by_differences(
        cost: impl Fn(f64, f64) -> f64,
        h: f64,
        moving: [bool; 2],
    ) -> SlidingCost {
        let c0 = cost(0.0, 0.0);
        let mut d = SlidingCost {
            cost: c0,
            ..SlidingCost::default()
        };
        if moving[0] {
            let (p, m) = (cost(h, 0.0), cost(-h, 0.0));
            d.gradient[0] = (p - m) / (2.0 * h);
            d.hessian[0] = (p - 2.0 * c0 + m) / (h * h);
        }
        if moving[1] {
            let (p, m) = (cost(0.0, h), cost(0.0, -h));
            d.gradient[1] = (p - m) / (2.0 * h);
            d.hessian[2] = (p - 2.0 * c0 + m) / (h * h);
        }
        if moving[0] && moving[1] {
            d.hessian[1] = (cost(h, h) - cost(h, -h) - cost(-h, h) + cost(-h, -h)) / (4.0 * h * h);
        }
        d
    }

    /// `Some(self)` if all its numbers are finite (the cost, its gradient and its
    /// Hessian), `None` otherwise: what [`Metric::sliding_cost`] returns where a
    /// formula overflows.
    pub fn finite(self) -> Option<SlidingCost> {
        let all = [self.cost]
            .iter()
            .chain(&self.gradient)
            .chain(&self.hessian)
            .all(|x| x.is_finite());
        all.then_some(self)
    }
}

impl<M: Metric + ?Sized> Metric for &M {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        (**self).cost(face, a, b)
    }
    fn is_symmetric(&self) -> bool {
        (**self).is_symmetric()
    }
    fn is_face_norm(&self) -> bool {
        (**self).is_face_norm()
    }
    fn prunes_on(&self, face: u32) -> bool {
        (**self).prunes_on(face)
    }
    #[inline]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        (**self).triangle_slack(face, diameter)
    }
    #[inline]
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        (**self).face_gram(face)
    }
    #[inline]
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        (**self).wire_cost(a, b, length)
    }
    fn min_cost_per_length(&self) -> f64 {
        (**self).min_cost_per_length()
    }
    #[inline]
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        (**self).sliding_cost(face, a, da, b, db)
    }
    fn name(&self) -> &str {
        (**self).name()
    }
}

impl<M: Metric + ?Sized> Metric for Box<M> {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        (**self).cost(face, a, b)
    }
    fn is_symmetric(&self) -> bool {
        (**self).is_symmetric()
    }
    fn is_face_norm(&self) -> bool {
        (**self).is_face_norm()
    }
    fn prunes_on(&self, face: u32) -> bool {
        (**self).prunes_on(face)
    }
    #[inline]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        (**self).triangle_slack(face, diameter)
    }
    #[inline]
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        (**self).face_gram(face)
    }
    #[inline]
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        (**self).wire_cost(a, b, length)
    }
    fn min_cost_per_length(&self) -> f64 {
        (**self).min_cost_per_length()
    }
    #[inline]
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        (**self).sliding_cost(face, a, da, b, db)
    }
    fn name(&self) -> &str {
        (**self).name()
    }
}

/// `M` travelled the other way: `Reversed(m).cost(f, a, b) == m.cost(f, b, a)`.
///
/// Under a directed metric a run gives the cost of travelling *from* its sources; a run
/// under `Reversed` gives the cost of travelling *to* them (the time to reach a
/// shelter from everywhere, say), and its paths run backwards. For a symmetric metric
/// it changes nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reversed<M>(pub M);

impl<M: Metric> Metric for Reversed<M> {
    #[inline(always)]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        self.0.cost(face, b, a)
    }
    fn is_symmetric(&self) -> bool {
        self.0.is_symmetric()
    }
    // The reverse of a (asymmetric) norm is one, the triangle inequality's slack is the
    // same bound read backwards, and a flattening is symmetric.
    fn is_face_norm(&self) -> bool {
        self.0.is_face_norm()
    }
    #[inline(always)]
    fn prunes_on(&self, face: u32) -> bool {
        self.0.prunes_on(face)
    }
    #[inline(always)]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        self.0.triangle_slack(face, diameter)
    }
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        self.0.face_gram(face)
    }
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        self.0.wire_cost(b, a, length)
    }
    fn min_cost_per_length(&self) -> f64 {
        self.0.min_cost_per_length()
    }
    #[inline]
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        self.0
            .sliding_cost(face, b, db, a, da)
            .map(SlidingCost::swapped)
    }
    fn name(&self) -> &str {
        self.0.name()
    }
}

/// What the built-in metrics need to know about the mesh they are built for.
///
/// geotracks' `TriMesh` implements it; a user with another mesh type can too.
pub trait FaceGeometry {
    /// Number of vertices.
    fn vertex_count(&self) -> usize;
    /// Number of faces.
    fn face_count(&self) -> usize;
    /// The three vertex ids of a face, in the face's order.
    fn face_vertices(&self, face: u32) -> [u32; 3];
    /// World-space unit vectors of the face's local u and v axes.
    fn face_axes(&self, face: u32) -> [[f64; 3]; 2];
}

#[cfg(test)]
mod sliding_tests {
    use super::*;

    /// One face: corners (0, 0), (2, 0), (0.5, 1.5) in its frame.
    struct OneFace;

    impl FaceGeometry for OneFace {
        fn vertex_count(&self) -> usize {
            3
        }
        fn face_count(&self) -> usize {
            1
        }
        fn face_vertices(&self, _face: u32) -> [u32; 3] {
            [0, 1, 2]
        }
        fn face_axes(&self, _face: u32) -> [[f64; 3]; 2] {
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        }
    }

    const CORNERS: [[f64; 2]; 3] = [[0.0, 0.0], [2.0, 0.0], [0.5, 1.5]];

    /// The point with barycentric coordinates `bary` (a velocity when they sum to 0).
    fn point(bary: [f64; 3]) -> FacePoint {
        let uv = [0, 1].map(|i| (0..3).map(|c| bary[c] * CORNERS[c][i]).sum());
        FacePoint { uv, bary }
    }

    /// The cost, gradient and Hessian in a row.
    fn parts(d: &SlidingCost) -> [f64; 6] {
        let ([gs, gt], [hss, hst, htt]) = (d.gradient, d.hessian);
        [d.cost, gs, gt, hss, hst, htt]
    }

    fn slide(p: &FacePoint, dp: &FacePoint, s: f64) -> FacePoint {
        FacePoint {
            uv: [0, 1].map(|i| p.uv[i] + s * dp.uv[i]),
            bary: [0, 1, 2].map(|i| p.bary[i] + s * dp.bary[i]),
        }
    }

    /// `sliding_cost` against central differences of `cost` (step 1e-4: the mixed
    /// difference on a short segment is off by about 1e-6 of itself), at segments between points inside the face
    /// and on its edges, each end sliding along an edge direction or held.
    fn agrees_with_differences<M: Metric>(metric: &M) {
        let points = [
            point([0.2, 0.3, 0.5]),
            point([0.0, 0.4, 0.6]),
            point([0.7, 0.3, 0.0]),
            point([0.1, 0.8, 0.1]),
        ];
        let still = point([0.0, 0.0, 0.0]);
        let velocities = [point([1.0, -1.0, 0.0]), point([0.0, -0.5, 0.5]), still];
        let h = 1e-4;
        for (i, a) in points.iter().enumerate() {
            for b in points.iter().skip(i + 1) {
                for da in &velocities {
                    for db in &velocities {
                        let c = |s: f64, t: f64| metric.cost(0, &slide(a, da, s), &slide(b, db, t));
                        let found = metric.sliding_cost(0, a, da, b, db).expect("a formula");
                        let expected = SlidingCost::by_differences(c, h, [true, true]);
                        for (k, (x, y)) in parts(&found).iter().zip(parts(&expected)).enumerate() {
                            assert!(
                                (x - y).abs() <= 1e-5 * (1.0 + y.abs()),
                                "{} part {k}: {x} against {y} ({a:?} → {b:?})",
                                metric.name()
                            );
                        }
                    }
                }
            }
        }
    }

    /// A directed metric with a formula: a Randers norm `|v| + w·v`, to check that
    /// `Reversed` swaps the ends.
    struct Current;

    impl Metric for Current {
        fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
            a.distance(b) + 0.3 * (b.uv[0] - a.uv[0]) - 0.2 * (b.uv[1] - a.uv[1])
        }
        fn is_symmetric(&self) -> bool {
            false
        }
        fn sliding_cost(
            &self,
            face: u32,
            a: &FacePoint,
            da: &FacePoint,
            b: &FacePoint,
            db: &FacePoint,
        ) -> Option<SlidingCost> {
            let mut d = Euclidean.sliding_cost(face, a, da, b, db)?;
            let w = |p: &FacePoint| 0.3 * p.uv[0] - 0.2 * p.uv[1];
            d.cost += w(b) - w(a);
            d.gradient[0] -= w(da);
            d.gradient[1] += w(db);
            Some(d)
        }
    }

    #[test]
    fn sliding_costs_are_the_derivatives_of_cost() {
        agrees_with_differences(&Euclidean);
        agrees_with_differences(&Tensor::from_local(vec![[2.0, 0.7, 0.5]]).unwrap());
        agrees_with_differences(&Density::new(&OneFace, vec![1.0, 3.0, 0.2]).unwrap());
        agrees_with_differences(&Current);
        agrees_with_differences(&Reversed(Current));
        agrees_with_differences(&&Reversed(
            &Density::new(&OneFace, vec![0.5, 2.0, 7.0]).unwrap(),
        ));
        agrees_with_differences(&BuiltinMetric::Euclidean(Euclidean));
    }

    #[test]
    fn no_sliding_cost_where_the_formula_breaks_down() {
        let a = point([0.2, 0.3, 0.5]);
        let still = point([0.0, 0.0, 0.0]);
        // A segment of length 0: the norm has no derivative there.
        assert_eq!(Euclidean.sliding_cost(0, &a, &still, &a, &still), None);
        // A cost beyond the f64 range.
        let far = FacePoint {
            uv: [1e200, 1e200],
            bary: a.bary,
        };
        let huge = Density::new(&OneFace, vec![1e300, 1e300, 1e300]).unwrap();
        assert_eq!(huge.sliding_cost(0, &a, &still, &far, &still), None);
        // A metric without a formula.
        struct Plain;
        impl Metric for Plain {
            fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
                a.distance(b)
            }
        }
        assert_eq!(Plain.sliding_cost(0, &a, &still, &a, &still), None);
    }
}
