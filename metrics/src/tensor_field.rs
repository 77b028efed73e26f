use crate::tensor::{check_spd, restrict};
use crate::{FaceGeometry, FacePoint, Metric, MetricError};

/// A symmetric positive-definite tensor per vertex, interpolated linearly across each
/// face: a Riemannian metric that varies smoothly over the surface, rather than
/// [`crate::Tensor`]'s constant per face.
///
/// Each vertex holds a world-space 3×3 symmetric matrix `W`; on each face around it,
/// `W` restricted to the face's plane gives a 2×2 tensor `Gᵢ` at that corner, and at a
/// face point with barycentric coordinates `β` the tensor is `M = Σ βᵢ Gᵢ`. (A 2×2
/// tensor in a terrain's map frame is the 3×3 with zeros in its z row and column.)
///
/// # The cost of a segment
/// Along a segment `v = b − a` the quadratic form `vᵀ M v` is linear in the parameter
/// (the tensor is linear along it), from `q_a` at `a` to `q_b` at `b`, so the segment's
/// length `∫₀¹ sqrt(vᵀ M(a + t v) v) dt` has the closed form
/// `(2/3) (q_a + sqrt(q_a q_b) + q_b) / (sqrt(q_a) + sqrt(q_b))`: exact, no quadrature
/// error. A constant field gives exactly [`crate::Tensor`]'s cost.
///
/// # Pruning
/// The metric is not a norm on a face whose corners differ. If every corner tensor lies
/// between `(1 − ε)²` and `(1 + ε)²` times their mean `Ḡ` (generalized eigenvalues), so
/// does every tensor of the face, and the triangle inequality fails by at most
/// `4 ε (1 + ε) / (1 − ε) · sqrt(λmax(Ḡ)) · diameter` ([`Metric::triangle_slack`]):
/// the track pruning of geotracks accepts proofs only with that margin and stays exact.
/// [`TensorField::with_pruning_tolerance`] prunes faces with `ε ≤ tolerance` without it,
/// as [`crate::Density`] does. A field constant on every face (the same tensor at a
/// face's three corners) is flat there ([`Metric::face_gram`]) and runs the wavefront
/// engine, as [`crate::Tensor`] does; any other runs the track-pruned one.
///
/// ```
/// use geotracks_metrics::{FaceGeometry, FacePoint, Metric, Tensor, TensorField};
///
/// struct OneFace; // a right triangle in the z = 0 plane
/// impl FaceGeometry for OneFace {
///     fn vertex_count(&self) -> usize { 3 }
///     fn face_count(&self) -> usize { 1 }
///     fn face_vertices(&self, _: u32) -> [u32; 3] { [0, 1, 2] }
///     fn face_axes(&self, _: u32) -> [[f64; 3]; 2] { [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] }
/// }
/// // Moving along x costs 1 per unit at vertex 0 and 3 at vertex 1 (xx = 1 and 9).
/// let field = TensorField::from_world(&OneFace, &[
///     [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
///     [9.0, 0.0, 0.0, 1.0, 0.0, 1.0],
///     [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
/// ])?;
/// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
/// let b = FacePoint { uv: [1.0, 0.0], bary: [0.0, 1.0, 0.0] };
/// // ∫₀¹ sqrt(1 + 8t) dt = (27 − 1) / 12
/// assert!((field.cost(0, &a, &b) - 26.0 / 12.0).abs() < 1e-15);
/// // A constant field is the constant tensor.
/// let w = [2.0, 0.5, 0.0, 1.0, 0.0, 1.0];
/// let constant = TensorField::from_world(&OneFace, &[w; 3])?;
/// let tensor = Tensor::from_world(&OneFace, &[w])?;
/// assert_eq!(constant.cost(0, &a, &b), tensor.cost(0, &a, &b));
/// # Ok::<(), geotracks_metrics::MetricError>(())
/// ```
#[derive(Clone, Debug)]
pub struct TensorField {
    /// Per face, its corners' 2×2 tensors `[m11, m12, m22]` in the face's frame.
    corners: Vec<[[f64; 3]; 3]>,
    /// Per face, ε (see the type's docs).
    spread: Vec<f64>,
    /// Per face, the slack per unit of diameter: `4 ε (1 + ε) / (1 − ε) · sqrt(λmax(Ḡ))`
    /// (∞ from ε ≥ 1).
    slack: Vec<f64>,
    pruning_tolerance: f64,
    /// Per face, whether its three corners hold one tensor (the field is constant, a
    /// norm, there).
    constant: Vec<bool>,
    /// Whether `constant` holds on every face: kept, as the engine asks
    /// [`Metric::is_face_norm`] in its inner loop.
    constant_everywhere: bool,
}

impl TensorField {
    /// Builds from a world-space symmetric 3×3 matrix per vertex, given as its six
    /// upper entries `[xx, xy, xz, yy, yz, zz]`.
    ///
    /// # Errors
    /// [`MetricError::CountMismatch`] unless there is one matrix per vertex;
    /// [`MetricError::VertexTensor`] for a matrix whose restriction to the plane of a
    /// face around its vertex is not finite and SPD.
    pub fn from_world<G: FaceGeometry + ?Sized>(
        mesh: &G,
        per_vertex: &[[f64; 6]],
    ) -> Result<Self, MetricError> {
        if per_vertex.len() != mesh.vertex_count() {
            return Err(MetricError::CountMismatch {
                what: "tensor field",
                per: "vertex",
                expected: mesh.vertex_count(),
                found: per_vertex.len(),
            });
        }
        let faces = mesh.face_count();
        let mut corners = Vec::with_capacity(faces);
        for face in 0..faces {
            let axes = mesh.face_axes(face as u32);
            let mut g = [[0.0; 3]; 3];
            for (corner, &vertex) in mesh.face_vertices(face as u32).iter().enumerate() {
                let r = restrict(&per_vertex[vertex as usize], axes);
                check_spd(face, r).map_err(|_| MetricError::VertexTensor {
                    vertex: vertex as usize,
                    face,
                    m11: r[0],
                    m12: r[1],
                    m22: r[2],
                })?;
                g[corner] = r;
            }
            corners.push(g);
        }
        let constant: Vec<bool> = corners
            .iter()
            .map(|g| g[0] == g[1] && g[1] == g[2])
            .collect();
        let (spread, slack) = corners
            .iter()
            .zip(&constant)
            .map(|(g, &constant)| {
                if constant {
                    (0.0, 0.0)
                } else {
                    spread_and_slack(g)
                }
            })
            .unzip();
        Ok(TensorField {
            corners,
            spread,
            slack,
            pruning_tolerance: 0.0,
            constant_everywhere: constant.iter().all(|&c| c),
            constant,
        })
    }

    /// Prunes as for a norm (no margin) on faces whose corner tensors lie within
    /// `(1 ± tolerance)²` of their mean. 0 (the default) keeps the exact rule; a positive
    /// tolerance prunes more and may then deviate from the Steiner graph where the field
    /// varies within a face.
    pub fn with_pruning_tolerance(mut self, tolerance: f64) -> Self {
        self.pruning_tolerance = tolerance.max(0.0);
        self
    }

    /// Per face, ε: its corner tensors lie between `(1 − ε)²` and `(1 + ε)²` times their
    /// mean (0 where the field is constant on the face).
    pub fn spread(&self) -> &[f64] {
        &self.spread
    }
}

/// ε and the slack per unit diameter of a face with corner tensors `g`, not all equal.
fn spread_and_slack(g: &[[f64; 3]; 3]) -> (f64, f64) {
    let mean: [f64; 3] = std::array::from_fn(|k| (g[0][k] + g[1][k] + g[2][k]) / 3.0);
    let [a_, b_, c_] = mean;
    let det_mean = a_ * c_ - b_ * b_;
    let mut epsilon = 0.0f64;
    for &[a, b, c] in g.iter() {
        // det(G − μ Ḡ) = μ² det Ḡ − μ (a C + c A − 2 b B) + det G = 0.
        let p = a * c_ + c * a_ - 2.0 * b * b_;
        let q = a * c - b * b;
        let disc = (p * p - 4.0 * det_mean * q).max(0.0).sqrt();
        let (lo, hi) = ((p - disc) / (2.0 * det_mean), (p + disc) / (2.0 * det_mean));
        epsilon = epsilon.max(1.0 - lo.max(0.0).sqrt()).max(hi.sqrt() - 1.0);
    }
    let lambda_max = 0.5 * (a_ + c_ + ((a_ - c_).powi(2) + 4.0 * b_ * b_).sqrt());
    let slack = if epsilon >= 1.0 {
        f64::INFINITY
    } else {
        4.0 * epsilon * (1.0 + epsilon) / (1.0 - epsilon) * lambda_max.sqrt()
    };
    (epsilon, slack)
}

impl Metric for TensorField {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let g = &self.corners[face as usize];
        let (x, y) = (b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]);
        let q = |[m11, m12, m22]: [f64; 3]| m11 * x * x + 2.0 * m12 * x * y + m22 * y * y;
        if self.constant[face as usize] {
            // Constant on the face: the constant tensor's cost, to the last bit.
            return q(g[0]).max(0.0).sqrt();
        }
        let corner = [q(g[0]), q(g[1]), q(g[2])];
        let at = |p: &FacePoint| {
            (p.bary[0] * corner[0] + p.bary[1] * corner[1] + p.bary[2] * corner[2]).max(0.0)
        };
        let (qa, qb) = (at(a), at(b));
        let (ra, rb) = (qa.sqrt(), qb.sqrt());
        if ra + rb == 0.0 {
            return 0.0;
        }
        // (2/3)(q_b^{3/2} − q_a^{3/2}) / (q_b − q_a), without the cancellation.
        (2.0 / 3.0) * (qa + ra * rb + qb) / (ra + rb)
    }
    fn is_face_norm(&self) -> bool {
        self.constant_everywhere
    }
    fn prunes_on(&self, face: u32) -> bool {
        self.spread[face as usize] < 1.0
    }
    // A face whose corners hold one tensor is flat under it; a field that is so on
    // every face (constant per face) runs the wavefront engine, as `Tensor` does.
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        let face = face as usize;
        self.constant[face].then_some(self.corners[face][0])
    }
    #[inline]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        if self.spread[face as usize] <= self.pruning_tolerance {
            0.0
        } else {
            self.slack[face as usize] * diameter
        }
    }
    /// `sqrt(λmin)` over the corner tensors: along a segment the tensor is a convex
    /// combination of its face's corners, whose least eigenvalue is at least theirs
    /// (λmin is concave).
    fn min_cost_per_length(&self) -> f64 {
        self.corners
            .iter()
            .flatten()
            .map(|&m| crate::tensor::least_eigenvalue(m))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }
    fn name(&self) -> &str {
        "tensor field"
    }
}
