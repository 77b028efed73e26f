//! Directed terrain costs: climbing and descending cost differently (Finsler metrics,
//! see [`Metric::is_symmetric`]).
//!
//! Each is a function of a segment's horizontal length `h` and its rise `Δz` (negative
//! going down), positively homogeneous: twice the segment, twice the cost. On a planar
//! face the rise is linear in the segment, so the cost is a function of the direction
//! only, scaled by the length.
//!
//! - [`DirectedModel::Uphill`]: the 3D length plus `b` per unit climbed. Convex in
//!   every direction (a norm plus a positive part of a linear form): the tracks engine
//!   prunes everywhere.
//! - [`DirectedModel::Walk`]: the time model of GRASS `r.walk` (Aitken 1977, Langmuir
//!   1984, after Naismith's rule), in seconds for metres: `a·h + b·Δz` climbing, `c·Δz`
//!   on moderate descents and `d·Δz` on steep ones (steeper than the slope factor, a
//!   tangent). [`DirectedModel::NAISMITH`] is `a = 0.72` s/m (5 km/h) and `b = 6` s/m
//!   (an hour per 600 m of ascent), descents free; [`DirectedModel::RWALK`] is
//!   r.walk's defaults. The switch to steep descents makes the cost jump, so it is
//!   not convex on faces steep enough to descend steeply: the engine tests every target
//!   there (no pruning), and prunes on the other faces.
//! - [`DirectedModel::Tobler`]: walking time by Tobler's hiking function, speed
//!   `6·exp(−3.5·|s + 0.05|)` km/h at the slope `s = Δz/h` along the walk (fastest
//!   slightly downhill), times 0.6 off paths: `0.6·h·exp(3.5·|s + 0.05|)` seconds per
//!   metre on a path. In polar form the cost per unit of horizontal run in direction θ
//!   from the fall line is `f(m cos θ)`, with `m` the face's gradient; it is convex
//!   exactly where `f + ∂²f/∂θ² ≥ 0`, which for `f = exp(3.5|s + 0.05|)` is
//!   `3.5·m ≤ 1`: slopes up to 15.9°. Steeper, zig-zagging up or down costs less than
//!   the straight fall line (switchbacks); the Steiner graph finds such zig-zags at its
//!   own resolution, and the engine does not prune on those faces.
//!
//! Lengths and elevations must be in metres for the time models' seconds.

use super::cost::{face_normal_up, tan2};
use super::TerrainError;
use geotracks::mesh::Topology;
use geotracks::metrics::{FacePoint, Metric, SlidingCost};

/// How a [`DirectedCost`] charges a segment (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DirectedModel {
    /// 3D length + `b` × metres climbed.
    Uphill {
        /// Extra cost per unit of climb.
        b: f64,
    },
    /// GRASS r.walk's walking time (seconds): `a·h + b·Δz` up, `c·Δz` for a descent
    /// no steeper than `slope_factor` (a negative tangent), `d·Δz` steeper.
    Walk {
        /// Seconds per metre on the flat (1 / speed).
        a: f64,
        /// Seconds per metre climbed.
        b: f64,
        /// Seconds per metre descended on moderate descents (positive: they are
        /// faster).
        c: f64,
        /// Seconds per metre descended on steep descents (negative: they are slower).
        d: f64,
        /// The tangent where descents turn steep (negative).
        slope_factor: f64,
    },
    /// Tobler's hiking function (seconds); `off_path` walks at 0.6 times the speed.
    Tobler {
        /// Off paths: 0.6 times the speed.
        off_path: bool,
    },
}

impl DirectedModel {
    /// Naismith's rule as r.walk writes it: 0.72 s/m, 6 s per metre climbed.
    pub const NAISMITH: DirectedModel = DirectedModel::Walk {
        a: 0.72,
        b: 6.0,
        c: 0.0,
        d: 0.0,
        slope_factor: -0.2125,
    };
    /// GRASS r.walk's defaults (Langmuir 1984): `walk_coeff=0.72,6.0,1.9998,-1.9998`,
    /// `slope_factor=-0.2125` (tan 12°).
    pub const RWALK: DirectedModel = DirectedModel::Walk {
        a: 0.72,
        b: 6.0,
        c: 1.9998,
        d: -1.9998,
        slope_factor: -0.2125,
    };

    /// Checks the parameters: every segment must cost ≥ 0 and more than 0 on the flat,
    /// whatever the slope.
    ///
    /// # Errors
    /// [`TerrainError::Parameter`] naming the first one out of range.
    pub fn check(&self) -> Result<(), TerrainError> {
        let bad = |what, value, expected| {
            Err(TerrainError::Parameter {
                what,
                value,
                expected,
            })
        };
        match *self {
            DirectedModel::Uphill { b } if !(b.is_finite() && b >= 0.0) => {
                bad("the uphill factor b", b, "it must be a finite number ≥ 0")
            }
            DirectedModel::Walk {
                a,
                b,
                c,
                d,
                slope_factor,
            } => {
                if !(a.is_finite() && a > 0.0) {
                    return bad("r.walk's a", a, "it must be a finite number > 0 (s/m)");
                }
                if !(b.is_finite() && b >= 0.0) {
                    return bad("r.walk's b", b, "it must be a finite number ≥ 0 (s/m)");
                }
                if !(slope_factor.is_finite() && slope_factor < 0.0) {
                    return bad(
                        "r.walk's slope factor",
                        slope_factor,
                        "it must be a negative tangent",
                    );
                }
                // Moderate descents save c per metre down, at most down to the slope
                // factor: a·h + c·Δz ≥ 0 there.
                if !(c.is_finite() && a + c * slope_factor >= 0.0) {
                    return bad(
                        "r.walk's c",
                        c,
                        "a moderate descent would take negative time: c must be at most a / |slope factor|",
                    );
                }
                if !(d.is_finite() && d <= 0.0) {
                    return bad(
                        "r.walk's d",
                        d,
                        "it must be ≤ 0: a steep descent cannot save time in proportion to its drop",
                    );
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }

    /// The cost of a segment with horizontal length `h` and rise `dz`.
    #[inline(always)]
    fn cost(&self, h: f64, dz: f64) -> f64 {
        match *self {
            DirectedModel::Uphill { b } => h.hypot(dz) + b * dz.max(0.0),
            DirectedModel::Walk {
                a,
                b,
                c,
                d,
                slope_factor,
            } => {
                let per_rise = if dz >= 0.0 {
                    b
                } else if dz < slope_factor * h {
                    d
                } else {
                    c
                };
                a * h + per_rise * dz
            }
            DirectedModel::Tobler { off_path } => {
                if h == 0.0 {
                    // Straight up or down a vertical face: no walking speed.
                    return if dz == 0.0 { 0.0 } else { f64::INFINITY };
                }
                // 3.6 s/m at 1 km/h; 6 km/h at best.
                let seconds = 0.6 * h * (3.5 * (dz / h + 0.05).abs()).exp();
                if off_path {
                    seconds / 0.6
                } else {
                    seconds
                }
            }
        }
    }

    /// The cost of a step `h` long on the map rising `dz`, with its first and second
    /// derivatives in `h` and `dz`: `[f, f_h, f_z, f_hh, f_hz, f_zz]`. `None` on a
    /// kink (level ground for `uphill` and r.walk, r.walk's steep-descent edge,
    /// Tobler's fastest slope), for Tobler straight up or down, and where the step
    /// has no length.
    fn derivatives(&self, h: f64, dz: f64) -> Option<[f64; 6]> {
        match *self {
            DirectedModel::Uphill { b } => {
                let r = h.hypot(dz);
                if dz == 0.0 || !r.is_normal() {
                    return None;
                }
                let r3 = r * r * r;
                let climb = if dz > 0.0 { b } else { 0.0 };
                Some([
                    r + climb * dz,
                    h / r,
                    dz / r + climb,
                    dz * dz / r3,
                    -h * dz / r3,
                    h * h / r3,
                ])
            }
            DirectedModel::Walk {
                a,
                b,
                c,
                d,
                slope_factor,
            } => {
                if dz == 0.0 || dz == slope_factor * h {
                    return None;
                }
                let per_rise = if dz > 0.0 {
                    b
                } else if dz < slope_factor * h {
                    d
                } else {
                    c
                };
                Some([a * h + per_rise * dz, a, per_rise, 0.0, 0.0, 0.0])
            }
            DirectedModel::Tobler { off_path } => {
                let tangent = dz / h + 0.05;
                if h == 0.0 || tangent == 0.0 || !tangent.is_finite() {
                    return None;
                }
                // 0.6 h e^{g (dz/h + 0.05)}, g = ±3.5 on either side of the kink.
                let g = 3.5f64.copysign(tangent);
                let scale = if off_path { 1.0 } else { 0.6 };
                let e = scale * (g * tangent).exp();
                Some([
                    h * e,
                    e * (1.0 - g * dz / h),
                    g * e,
                    e * g * g * dz * dz / (h * h * h),
                    -e * g * g * dz / (h * h),
                    e * g * g / h,
                ])
            }
        }
    }

    /// Whether the cost is convex (an asymmetric norm) on a face whose steepest
    /// tangent is `m`.
    fn convex_at(&self, m: f64) -> bool {
        match *self {
            DirectedModel::Uphill { .. } => true,
            // No steep descent on the face, and climbing dearer than descending saves.
            DirectedModel::Walk {
                b, c, slope_factor, ..
            } => -m >= slope_factor && c <= b,
            // A margin of 1e-9 for the rounding of m.
            DirectedModel::Tobler { .. } => 3.5 * m <= 1.0 - 1e-9,
        }
    }

    /// The least cost per unit of 3D length on a face whose steepest tangent is `m`
    /// (see [`Metric::min_cost_per_length`]).
    ///
    /// Along a direction of tangent `t` (rise per unit of run, `|t| ≤ m` on the face)
    /// a unit of 3D length costs `cost(1, t) / sqrt(1 + t²)`. For the walking times
    /// `cost(1, t)` is linear in `t` on each range of slopes, `α + β t` with `α > 0`,
    /// whose one critical point divided by `sqrt(1 + t²)` is a maximum: the least
    /// value lies at the ends of the ranges. Tobler's cost per unit falls towards
    /// `t = −0.05` and rises beyond (its exponent's slope, 3.5, exceeds that of
    /// `ln sqrt(1 + t²)`, at most ½).
    pub(crate) fn min_cost_per_length(&self, m: f64) -> f64 {
        // (α + β t) / sqrt(1 + t²), and its limit β·sign(t) at t = ±∞.
        let per_length = |alpha: f64, beta: f64, t: f64| {
            if t.is_infinite() {
                beta * t.signum()
            } else {
                (alpha + beta * t) / t.hypot(1.0)
            }
        };
        match *self {
            DirectedModel::Uphill { .. } => 1.0,
            DirectedModel::Walk {
                a,
                b,
                c,
                d,
                slope_factor,
            } => {
                let mut least = a.min(per_length(a, b, m));
                // Moderate descents, down to the slope factor or the face's steepest.
                let moderate = slope_factor.max(-m);
                least = least.min(per_length(a, c, moderate));
                if -m < slope_factor {
                    // Steep descents, from just beyond the slope factor to the steepest.
                    least = least
                        .min(per_length(a, d, slope_factor))
                        .min(per_length(a, d, -m));
                }
                least.max(0.0)
            }
            DirectedModel::Tobler { off_path } => {
                let t = (-0.05f64).max(-m);
                let on_path = 0.6 * (3.5 * (t + 0.05).abs()).exp() / t.hypot(1.0);
                if off_path {
                    on_path / 0.6
                } else {
                    on_path
                }
            }
        }
    }

    /// Whether the cost is convex on every face, whatever its slope.
    fn convex_everywhere(&self) -> bool {
        match *self {
            DirectedModel::Uphill { .. } => true,
            DirectedModel::Walk { .. } => self.convex_at(f64::INFINITY),
            DirectedModel::Tobler { .. } => false,
        }
    }
}

/// A directed terrain cost on a mesh (z up): [`DirectedModel`] applied to each
/// segment's horizontal length and rise. Going up and down cost differently, so a
/// field is the cost *from* its sources ([`geotracks::Reversed`] gives the cost *to* them).
///
/// ```
/// use geotracks_terrain::{DirectedCost, DirectedModel, ElevationGrid, GridGeometry};
/// use geotracks::{Options, Solver};
/// // A plane rising 0.1 m per metre eastwards, 1 m cells.
/// let geometry = GridGeometry { ncols: 11, nrows: 3, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let terrain = ElevationGrid::from_fn(geometry, |x, _| Some(0.1 * x))?.to_mesh()?;
/// let naismith = DirectedCost::new(&terrain.mesh, DirectedModel::NAISMITH)?;
/// let solver = Solver::new(&terrain.mesh, &naismith, &Options::DEFAULT)?;
/// let (west, east) = (terrain.locate(0.0, 1.0)?, terrain.locate(10.0, 1.0)?);
/// let time = |from, to| -> Result<f64, geotracks::Error> {
///     solver.field(from)?.distance_at(to)
/// };
/// // 10 m east and 1 m up: 0.72 s/m × 10 + 6 s per metre climbed.
/// assert!((time(west, east)? - 13.2).abs() < 1e-9);
/// assert!((time(east, west)? - 7.2).abs() < 1e-9); // descents are free
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct DirectedCost {
    model: DirectedModel,
    /// Per face, the world x, y, z of its frame's u and v axes: a segment `(du, dv)`
    /// moves `du·u + dv·v`.
    axes: Vec<[f64; 6]>,
    /// Per face, whether the cost is convex there (the engine prunes only there).
    convex: Vec<bool>,
    /// The least cost per unit of 3D length over the faces.
    per_length: f64,
}

impl DirectedCost {
    /// `model` on `mesh`.
    ///
    /// # Errors
    /// [`TerrainError::Parameter`] for a parameter out of range
    /// ([`DirectedModel::check`]).
    pub fn new<T: Topology>(mesh: &T, model: DirectedModel) -> Result<Self, TerrainError> {
        model.check()?;
        let faces = mesh.face_count() as u32;
        let axes: Vec<[f64; 6]> = (0..faces)
            .map(|f| {
                let [u, v] = mesh.face_axes(f);
                [u[0], u[1], u[2], v[0], v[1], v[2]]
            })
            .collect();
        // The steepest tangent of each face: its normal's tilt.
        let steepest: Vec<f64> = (0..faces)
            .map(|f| tan2(face_normal_up(mesh, f)).sqrt())
            .collect();
        let convex = steepest.iter().map(|&m| model.convex_at(m)).collect();
        let per_length = steepest
            .iter()
            .map(|&m| model.min_cost_per_length(m))
            .fold(f64::INFINITY, f64::min);
        Ok(DirectedCost {
            model,
            axes,
            convex,
            per_length,
        })
    }

    /// The model.
    pub fn model(&self) -> DirectedModel {
        self.model
    }

    /// On how many faces the cost is not convex (where the engine cannot prune).
    pub fn nonconvex_faces(&self) -> usize {
        self.convex.iter().filter(|&&c| !c).count()
    }
}

impl Metric for DirectedCost {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let [ux, uy, uz, vx, vy, vz] = self.axes[face as usize];
        let (du, dv) = (b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]);
        let (x, y, z) = (du * ux + dv * vx, du * uy + dv * vy, du * uz + dv * vz);
        self.model.cost(x.hypot(y), z)
    }
    fn is_symmetric(&self) -> bool {
        false
    }
    fn is_face_norm(&self) -> bool {
        self.model.convex_everywhere()
    }
    fn prunes_on(&self, face: u32) -> bool {
        self.convex[face as usize]
    }
    fn min_cost_per_length(&self) -> f64 {
        self.per_length
    }
    /// The model's cost of the step's map length `h` and rise `z` (chain rule): `h` is
    /// the norm of the step in the face's frame under the Gram matrix of its axes'
    /// map parts, `z` is linear in the step.
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        let [ux, uy, uz, vx, vy, vz] = self.axes[face as usize];
        let gram = [ux * ux + uy * uy, ux * vx + uy * vy, vx * vx + vy * vy];
        let h = SlidingCost::norm(gram, a, da, b, db)?;
        let rise = |p: [f64; 2]| p[0] * uz + p[1] * vz;
        let z = rise([b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]]);
        let (zs, zt) = (-rise(da.uv), rise(db.uv));
        let [f, fh, fz, fhh, fhz, fzz] = self.model.derivatives(h.cost, z)?;
        let ([hs, ht], [hss, hst, htt]) = (h.gradient, h.hessian);
        SlidingCost {
            cost: f,
            gradient: [fh * hs + fz * zs, fh * ht + fz * zt],
            hessian: [
                fhh * hs * hs + 2.0 * fhz * hs * zs + fzz * zs * zs + fh * hss,
                fhh * hs * ht + fhz * (hs * zt + ht * zs) + fzz * zs * zt + fh * hst,
                fhh * ht * ht + 2.0 * fhz * ht * zt + fzz * zt * zt + fh * htt,
            ],
        }
        .finite()
    }
    fn name(&self) -> &str {
        match self.model {
            DirectedModel::Uphill { .. } => "uphill",
            DirectedModel::Walk { .. } if self.model == DirectedModel::NAISMITH => "naismith",
            DirectedModel::Walk { .. } => "rwalk",
            DirectedModel::Tobler { .. } => "tobler",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{DirectedCost, DirectedModel};
    use geotracks::mesh::TriMesh;
    use geotracks::metrics::{FacePoint, Metric, SlidingCost};
    use geotracks::surface::SurfacePoint;

    /// The models' formulas for a segment's derivatives against central differences of
    /// its cost (step 1e-4), on a tilted face, for segments between interior and edge
    /// points whose ends slide along the face's edges or stay; segments whose rise over
    /// run lies within 0.02 of a kink are left out (the differences straddle it).
    #[test]
    fn sliding_costs_are_the_derivatives_of_cost() {
        let mesh = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [10.0, 0.0, 2.0], [0.0, 10.0, -3.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let frame = mesh.frame(0);
        let point = |bary: [f64; 3]| frame.point(bary);
        let velocity = |from: usize, to: usize| {
            let (p, q) = (frame.corner(from), frame.corner(to));
            FacePoint {
                uv: [q.uv[0] - p.uv[0], q.uv[1] - p.uv[1]],
                bary: [0, 1, 2].map(|i| q.bary[i] - p.bary[i]),
            }
        };
        let still = FacePoint {
            uv: [0.0; 2],
            bary: [0.0; 3],
        };
        let slide = |p: &FacePoint, dp: &FacePoint, s: f64| FacePoint {
            uv: [0, 1].map(|i| p.uv[i] + s * dp.uv[i]),
            bary: [0, 1, 2].map(|i| p.bary[i] + s * dp.bary[i]),
        };
        let points = [
            point([0.2, 0.3, 0.5]),
            point([0.0, 0.4, 0.6]),
            point([0.7, 0.3, 0.0]),
            point([0.1, 0.8, 0.1]),
            point([0.5, 0.0, 0.5]),
        ];
        let velocities = [velocity(0, 1), velocity(1, 2), velocity(2, 0), still];
        let models = [
            DirectedModel::Uphill { b: 8.0 },
            DirectedModel::NAISMITH,
            DirectedModel::RWALK,
            DirectedModel::Tobler { off_path: false },
            DirectedModel::Tobler { off_path: true },
        ];
        let mut checked = 0;
        for model in models {
            let cost = DirectedCost::new(&mesh, model).unwrap();
            for a in &points {
                for b in &points {
                    let on = |p: &FacePoint| {
                        SurfacePoint::Face {
                            face: 0,
                            bary: p.bary,
                        }
                        .position(&mesh)
                    };
                    let (pa, pb) = (on(a), on(b));
                    let run = (pb.x - pa.x).hypot(pb.y - pa.y);
                    if run == 0.0 {
                        continue;
                    }
                    let grade = (pb.z - pa.z) / run;
                    let kinks = [0.0, -0.2125, -0.3, -0.05];
                    if kinks.iter().any(|k| (grade - k).abs() < 0.02) {
                        continue;
                    }
                    for da in &velocities {
                        for db in &velocities {
                            let c =
                                |s: f64, t: f64| cost.cost(0, &slide(a, da, s), &slide(b, db, t));
                            let parts = |d: SlidingCost| {
                                let ([gs, gt], [hss, hst, htt]) = (d.gradient, d.hessian);
                                [d.cost, gs, gt, hss, hst, htt]
                            };
                            let found =
                                parts(cost.sliding_cost(0, a, da, b, db).expect("a formula"));
                            let expected =
                                parts(SlidingCost::by_differences(c, 1e-4, [true, true]));
                            // (A Hessian entry against the Hessian's scale: a mixed
                            // derivative can be 0 where the differences read 1e-5.)
                            let hessian = expected[3..].iter().fold(0.0f64, |m, y| m.max(y.abs()));
                            for (k, (x, y)) in found.iter().zip(expected).enumerate() {
                                let scale = if k >= 3 { hessian } else { y.abs() };
                                assert!(
                                    (x - y).abs() <= 1e-5 * (1.0 + scale),
                                    "{model:?} part {k}: {x} against {y}"
                                );
                            }
                            checked += 1;
                        }
                    }
                }
            }
        }
        assert!(checked > 200, "only {checked} cases away from the kinks");
    }

    /// The least cost per unit of 3D length is a lower bound on every direction of a
    /// face with the given steepest tangent, and a tight one (some direction costs
    /// within 0.1 % of it).
    #[test]
    fn the_least_cost_per_length_bounds_every_direction_tightly() {
        let models = [
            DirectedModel::Uphill { b: 8.0 },
            DirectedModel::NAISMITH,
            DirectedModel::RWALK,
            DirectedModel::Walk {
                a: 0.5,
                b: 3.0,
                c: 1.0,
                d: -0.5,
                slope_factor: -0.3,
            },
            DirectedModel::Tobler { off_path: false },
            DirectedModel::Tobler { off_path: true },
        ];
        for model in models {
            for m in [0.0, 0.02, 0.1, 0.2125, 0.3, 1.0, 5.0, 1e3] {
                let bound = model.min_cost_per_length(m);
                let mut least = f64::INFINITY;
                // Tangents from −m to m, the ends included, and where the models
                // turn: r.walk's slope factors, Tobler's fastest slope.
                let turns = [-0.2125, -0.3, -0.05]
                    .into_iter()
                    .filter(|t: &f64| t.abs() <= m);
                let steps = (0..=20_000).map(|i| m * (2.0 * i as f64 / 20_000.0 - 1.0));
                for t in steps.chain(turns) {
                    let per_length = model.cost(1.0, t) / t.hypot(1.0);
                    assert!(
                        per_length >= bound * (1.0 - 1e-12),
                        "{model:?}, m = {m}: {per_length} at tangent {t}, below {bound}"
                    );
                    least = least.min(per_length);
                }
                assert!(
                    least <= bound * (1.0 + 1e-3) + 1e-12,
                    "{model:?}, m = {m}: the bound {bound} is loose (least {least})"
                );
            }
            // A vertical face: straight up or down costs the limit (or, for Tobler,
            // nothing walks there).
            let vertical = model.min_cost_per_length(f64::INFINITY);
            assert!(
                vertical >= 0.0 && vertical <= model.min_cost_per_length(1e3),
                "{model:?}"
            );
        }
    }
}
