use thiserror::Error;

/// Why a built-in metric could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MetricError {
    /// A per-vertex or per-face array does not have one entry per vertex or face.
    /// Fix: give exactly one value per element, in the mesh's order.
    #[error("{what}: expected {expected} values (one per {per}), found {found}")]
    CountMismatch {
        /// What was being read, e.g. `"density"`.
        what: &'static str,
        /// `"vertex"` or `"face"`.
        per: &'static str,
        /// How many the mesh needs.
        expected: usize,
        /// How many were given.
        found: usize,
    },
    /// A density is zero, negative, NaN or infinite. Densities must be finite and > 0.
    #[error("density at vertex {vertex} is {}; it must be finite and > 0", crate::Num(*value))]
    InvalidDensity {
        /// The vertex index.
        vertex: usize,
        /// The offending value.
        value: f64,
    },
    /// A tensor has a NaN or infinite entry (given, or once restricted to its face's
    /// plane). Fix: give finite numbers.
    #[error("tensor of face {face} is not finite: a NaN or infinite entry")]
    NotFinite {
        /// The face index.
        face: usize,
    },
    /// A tensor, once restricted to its face's plane, is not symmetric positive-definite.
    /// Fix: give a matrix whose restriction to the face has positive eigenvalues.
    #[error("tensor of face {face} is not positive-definite in the face plane (restricted to [{}, {}; {}, {}])", crate::Num(*m11), crate::Num(*m12), crate::Num(*m12), crate::Num(*m22))]
    NotPositiveDefinite {
        /// The face index.
        face: usize,
        /// Restricted tensor, uu entry.
        m11: f64,
        /// Restricted tensor, uv entry.
        m12: f64,
        /// Restricted tensor, vv entry.
        m22: f64,
    },
    /// A vertex's tensor ([`crate::TensorField`]), restricted to the plane of a face
    /// around the vertex, is not finite and symmetric positive-definite. Fix: give a
    /// matrix whose restriction to every face of the vertex has positive eigenvalues
    /// (a 2×2 map-frame tensor with a zero z row and column works on every face that
    /// is not vertical).
    #[error("tensor of vertex {vertex} is not finite and positive-definite in the plane of face {face} (restricted to [{}, {}; {}, {}])", crate::Num(*m11), crate::Num(*m12), crate::Num(*m12), crate::Num(*m22))]
    VertexTensor {
        /// The vertex index.
        vertex: usize,
        /// The face whose plane it was restricted to.
        face: usize,
        /// Restricted tensor, uu entry.
        m11: f64,
        /// Restricted tensor, uv entry.
        m12: f64,
        /// Restricted tensor, vv entry.
        m22: f64,
    },
    /// A principal direction is zero, not finite, or perpendicular to its face's plane.
    #[error("principal direction of face {face} is zero, not finite or normal to the face")]
    DegenerateDirection {
        /// The face index.
        face: usize,
    },
}
