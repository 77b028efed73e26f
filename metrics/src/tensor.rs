use crate::{FaceGeometry, FacePoint, Metric, MetricError, SlidingCost};

/// A symmetric positive-definite tensor per face (anisotropic, direction-dependent cost).
///
/// Each face holds a 2×2 SPD matrix `M` in its local frame; a segment `v = b − a` costs
/// `sqrt(vᵀ M v)`. With eigenvalues λ₁, λ₂ and θ the angle between `v` and the first
/// principal direction that is `|v| · sqrt(λ₁ cos²θ + λ₂ sin²θ)`.
///
/// Three ways to build one:
/// - [`Tensor::from_world`]: a 3×3 world-space symmetric matrix per face, restricted to
///   the face's plane (`Mᶠ = Aᵀ M A`, `A` the face's two world axes);
/// - [`Tensor::from_principal`]: λ₁, λ₂ and a world-space principal direction per face
///   (projected onto the face's plane);
/// - [`Tensor::from_local`]: the 2×2 matrices in the faces' own frames.
///
/// ```
/// use geotracks_metrics::{FaceGeometry, FacePoint, Metric, Tensor};
///
/// struct OneFace; // a triangle in the z = 0 plane
/// impl FaceGeometry for OneFace {
///     fn vertex_count(&self) -> usize { 3 }
///     fn face_count(&self) -> usize { 1 }
///     fn face_vertices(&self, _: u32) -> [u32; 3] { [0, 1, 2] }
///     fn face_axes(&self, _: u32) -> [[f64; 3]; 2] { [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] }
/// }
/// // Moving along world y costs 3 per unit, along x 1 per unit (λ = 9 and 1).
/// let t = Tensor::from_principal(&OneFace, &[(9.0, 1.0, [0.0, 1.0, 0.0])]).unwrap();
/// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
/// let b = FacePoint { uv: [0.0, 2.0], bary: [0.0, 0.0, 1.0] };
/// assert!((t.cost(0, &a, &b) - 6.0).abs() < 1e-12);
///
/// // The same metric from a world-space matrix: xx xy xz yy yz zz.
/// let w = Tensor::from_world(&OneFace, &[[1.0, 0.0, 0.0, 9.0, 0.0, 5.0]]).unwrap();
/// assert!((w.cost(0, &a, &b) - 6.0).abs() < 1e-12);
/// // Not positive-definite in the face plane: rejected.
/// assert!(Tensor::from_world(&OneFace, &[[1.0, 0.0, 0.0, -1.0, 0.0, 1.0]]).is_err());
/// ```
#[derive(Clone, Debug)]
pub struct Tensor {
    /// `[m11, m12, m22]` in each face's local frame.
    local: Vec<[f64; 3]>,
}

impl Tensor {
    /// Builds from the 2×2 matrices `[m11, m12, m22]` in each face's local frame.
    ///
    /// # Errors
    /// [`MetricError::NotFinite`] for a matrix with a NaN or infinite entry;
    /// [`MetricError::NotPositiveDefinite`] for one that is not SPD.
    pub fn from_local(local: Vec<[f64; 3]>) -> Result<Self, MetricError> {
        for (face, m) in local.iter().enumerate() {
            check_spd(face, *m)?;
        }
        Ok(Tensor { local })
    }

    /// Builds from a world-space symmetric 3×3 matrix per face, given as its six upper
    /// entries `[xx, xy, xz, yy, yz, zz]`, restricted to each face's plane.
    ///
    /// # Errors
    /// [`MetricError::CountMismatch`] unless there is one matrix per face;
    /// [`MetricError::NotFinite`] if an entry (or a restriction's) is NaN or infinite;
    /// [`MetricError::NotPositiveDefinite`] if a restriction is not SPD.
    pub fn from_world<G: FaceGeometry + ?Sized>(
        mesh: &G,
        world: &[[f64; 6]],
    ) -> Result<Self, MetricError> {
        check_count(mesh, world.len())?;
        let local = world
            .iter()
            .enumerate()
            .map(|(face, w)| {
                let r = restrict(w, mesh.face_axes(face as u32));
                check_spd(face, r).map(|()| r)
            })
            .collect::<Result<_, _>>()?;
        Ok(Tensor { local })
    }

    /// The same world-space matrix `[xx, xy, xz, yy, yz, zz]` on every face.
    ///
    /// # Errors
    /// As [`Tensor::from_world`].
    pub fn uniform_world<G: FaceGeometry + ?Sized>(
        mesh: &G,
        world: [f64; 6],
    ) -> Result<Self, MetricError> {
        Self::from_world(mesh, &vec![world; mesh.face_count()])
    }

    /// Builds from `(λ₁, λ₂, d)` per face: cost factor λ₁ along the world direction `d`
    /// projected onto the face, λ₂ across it.
    ///
    /// # Errors
    /// [`MetricError::CountMismatch`] unless there is one entry per face;
    /// [`MetricError::DegenerateDirection`] if `d` projects to zero;
    /// [`MetricError::NotFinite`] for a NaN or infinite λ;
    /// [`MetricError::NotPositiveDefinite`] unless λ₁, λ₂ are > 0.
    pub fn from_principal<G: FaceGeometry + ?Sized>(
        mesh: &G,
        principal: &[(f64, f64, [f64; 3])],
    ) -> Result<Self, MetricError> {
        check_count(mesh, principal.len())?;
        let local = principal
            .iter()
            .enumerate()
            .map(|(face, &(l1, l2, d))| {
                let [u, v] = mesh.face_axes(face as u32);
                let (du, dv) = (dot(d, u), dot(d, v));
                let norm = du.hypot(dv);
                let scale = d.iter().map(|x| x * x).sum::<f64>().sqrt();
                if !(norm.is_finite() && norm > 1e-12 * scale) {
                    return Err(MetricError::DegenerateDirection { face });
                }
                let (c, s) = (du / norm, dv / norm);
                // λ₁ d dᵀ + λ₂ d⊥ d⊥ᵀ
                let r = [
                    l1 * c * c + l2 * s * s,
                    (l1 - l2) * c * s,
                    l1 * s * s + l2 * c * c,
                ];
                if !(l1.is_finite() && l2.is_finite()) {
                    return Err(MetricError::NotFinite { face });
                }
                if !(l1 > 0.0 && l2 > 0.0) {
                    return Err(MetricError::NotPositiveDefinite {
                        face,
                        m11: r[0],
                        m12: r[1],
                        m22: r[2],
                    });
                }
                Ok(r)
            })
            .collect::<Result<_, _>>()?;
        Ok(Tensor { local })
    }

    /// The 2×2 matrices `[m11, m12, m22]` in each face's local frame.
    pub fn local(&self) -> &[[f64; 3]] {
        &self.local
    }
}

/// The world matrix `w` (`[xx, xy, xz, yy, yz, zz]`) restricted to the plane of the
/// axes `[u, v]`: `[uᵀWu, uᵀWv, vᵀWv]`.
pub(crate) fn restrict(w: &[f64; 6], [u, v]: [[f64; 3]; 2]) -> [f64; 3] {
    let m = [[w[0], w[1], w[2]], [w[1], w[3], w[4]], [w[2], w[4], w[5]]];
    let quad = |a: [f64; 3], b: [f64; 3]| {
        (0..3)
            .map(|i| a[i] * (0..3).map(|j| m[i][j] * b[j]).sum::<f64>())
            .sum::<f64>()
    };
    [quad(u, u), quad(u, v), quad(v, v)]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn check_count<G: FaceGeometry + ?Sized>(mesh: &G, found: usize) -> Result<(), MetricError> {
    if found == mesh.face_count() {
        Ok(())
    } else {
        Err(MetricError::CountMismatch {
            what: "tensor",
            per: "face",
            expected: mesh.face_count(),
            found,
        })
    }
}

/// The least eigenvalue of the symmetric 2×2 matrix `[m11, m12, m22]` (SPD), as
/// `det / λmax`: no cancellation when the two eigenvalues are far apart.
pub(crate) fn least_eigenvalue([m11, m12, m22]: [f64; 3]) -> f64 {
    let largest = 0.5 * (m11 + m22 + (m11 - m22).hypot(2.0 * m12));
    ((m11 * m22 - m12 * m12) / largest).max(0.0)
}

pub(crate) fn check_spd(face: usize, [m11, m12, m22]: [f64; 3]) -> Result<(), MetricError> {
    if !(m11.is_finite() && m12.is_finite() && m22.is_finite()) {
        return Err(MetricError::NotFinite { face });
    }
    // Relative test so that a nearly singular tensor counts as not positive-definite.
    let det = m11 * m22 - m12 * m12;
    if m11 > 0.0 && m22 > 0.0 && det > 1e-12 * (m11 * m22) {
        Ok(())
    } else {
        Err(MetricError::NotPositiveDefinite {
            face,
            m11,
            m12,
            m22,
        })
    }
}

impl Metric for Tensor {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let [m11, m12, m22] = self.local[face as usize];
        let (x, y) = (b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]);
        let squared = m11 * x * x + 2.0 * m12 * x * y + m22 * y * y;
        if squared.is_normal() {
            return squared.sqrt();
        }
        // Over- or underflow (or zero): the same in units of the larger component.
        let scale = x.abs().max(y.abs());
        if scale == 0.0 || !scale.is_finite() {
            return if scale == 0.0 { 0.0 } else { f64::INFINITY };
        }
        let (x, y) = (x / scale, y / scale);
        (m11 * x * x + 2.0 * m12 * x * y + m22 * y * y)
            .max(0.0)
            .sqrt()
            * scale
    }
    fn is_face_norm(&self) -> bool {
        true
    }
    #[inline]
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        Some(self.local[face as usize])
    }
    /// `sqrt(λmin)` over the faces: `vᵀ M v ≥ λmin |v|²`.
    fn min_cost_per_length(&self) -> f64 {
        self.local
            .iter()
            .map(|&m| least_eigenvalue(m))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }
    fn name(&self) -> &str {
        "tensor"
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
        SlidingCost::norm(self.local[face as usize], a, da, b, db)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sqrt(λmin)` over the faces bounds every direction's cost per unit length, and
    /// the least eigenvector attains it.
    #[test]
    fn the_least_cost_per_length_is_the_root_of_the_least_eigenvalue() {
        // Eigenvalues 9 and 0.25 (at 30°), and a nearly isotropic one.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let rotated = [
            9.0 * c * c + 0.25 * s * s,
            (9.0 - 0.25) * c * s,
            9.0 * s * s + 0.25 * c * c,
        ];
        let t = Tensor::from_local(vec![rotated, [2.0, 0.1, 2.0]]).unwrap();
        assert!((least_eigenvalue(rotated) - 0.25).abs() < 1e-12);
        assert!((t.min_cost_per_length() - 0.5).abs() < 1e-12);
        let origin = FacePoint {
            uv: [0.0, 0.0],
            bary: [1.0, 0.0, 0.0],
        };
        for i in 0..360 {
            let a = (i as f64).to_radians();
            let p = FacePoint {
                uv: [a.cos(), a.sin()],
                bary: [0.0, 1.0, 0.0],
            };
            for f in 0..2 {
                assert!(t.cost(f, &origin, &p) >= 0.5 * (1.0 - 1e-12));
            }
        }
        // Along the least eigenvector, (−sin 30°, cos 30°): exactly the bound.
        let p = FacePoint {
            uv: [-s, c],
            bary: [0.0, 1.0, 0.0],
        };
        assert!((t.cost(0, &origin, &p) - 0.5).abs() < 1e-12);
    }

    /// A NaN entry was reported as "not positive-definite … [NaN, …]".
    #[test]
    fn a_nan_tensor_is_not_finite_rather_than_not_positive_definite() {
        let e = Tensor::from_local(vec![[1.0, 0.0, 1.0], [f64::NAN, 0.0, 1.0]]).unwrap_err();
        assert_eq!(e, MetricError::NotFinite { face: 1 });
        assert!(e.to_string().contains("not finite"), "{e}");
        assert!(!e.to_string().contains("positive-definite"), "{e}");
        let e = Tensor::from_local(vec![[1.0, f64::INFINITY, 1.0]]).unwrap_err();
        assert_eq!(e, MetricError::NotFinite { face: 0 });
        let e = Tensor::from_local(vec![[1.0, 2.0, 1.0]]).unwrap_err();
        assert!(matches!(
            e,
            MetricError::NotPositiveDefinite { face: 0, .. }
        ));
    }
}
