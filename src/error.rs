use crate::mesh::MeshError;
use geotracks_metrics::MetricError;
use thiserror::Error;

/// Everything that can go wrong in geotracks, each variant naming the problem and where.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum Error {
    /// The mesh could not be read or built.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A metric could not be built from its data.
    #[error(transparent)]
    Metric(#[from] MetricError),
    /// No source was given.
    #[error("no source given: at least one source vertex is needed")]
    NoSource,
    /// A source names a vertex that does not exist.
    #[error("source vertex {vertex} is out of range: the mesh has {vertex_count} vertices")]
    SourceOutOfRange {
        /// The vertex asked for.
        vertex: u64,
        /// How many vertices the mesh has.
        vertex_count: usize,
    },
    /// A target names a vertex that does not exist.
    #[error("target vertex {vertex} is out of range: the mesh has {vertex_count} vertices")]
    TargetOutOfRange {
        /// The vertex asked for.
        vertex: u64,
        /// How many vertices the mesh has.
        vertex_count: usize,
    },
    /// A source, target or query point is not a point of the mesh.
    #[error("{what}: {error}")]
    InvalidPoint {
        /// Which point: "source 2", "target 0", "the query point".
        what: String,
        /// What is wrong with it.
        error: crate::surface::PointError,
    },
    /// A number given as input is not usable (NaN, or infinite where a finite value is
    /// needed).
    #[error("{what} is {value}; it must be a finite number")]
    InvalidValue {
        /// Which value.
        what: String,
        /// The value given.
        value: f64,
    },
    /// No source reaches the point a path or a distance was asked for.
    #[error("{what} is not reached from any source (another component, beyond the maximum distance, or past an early stop)")]
    Unreachable {
        /// Which point.
        what: String,
    },
    /// A field (or a workspace's last run) was given to a solver other than the one that
    /// computed it. Queries need the mesh, metric and Steiner layout of the run, and
    /// only its own solver has them: query a field with the solver that made it (two
    /// solvers built from the same mesh and metric are still two solvers).
    #[error("the field was computed by another solver: query it with the solver that made it")]
    ForeignField,
    /// A workspace was queried before any run finished in it (no run yet, or the last
    /// one failed). Run the solver into it first.
    #[error("the workspace holds no finished run: run the solver into it first")]
    NoRun,
    /// The Steiner scheme asks for no points (k = 0), or a non-finite number of them.
    #[error("invalid number of Steiner points per edge: k = {k} (it must be finite and > 0)")]
    InvalidK {
        /// The k asked for.
        k: f64,
    },
    /// A metric returned a NaN or negative cost. Metrics must return costs ≥ 0
    /// (`+inf` is allowed and means the segment cannot be crossed).
    #[error("metric '{metric}' returned {value} for a segment in face {face}; costs must be ≥ 0 and not NaN")]
    InvalidCost {
        /// The metric's name.
        metric: String,
        /// The face of the segment.
        face: u32,
        /// The cost returned.
        value: f64,
    },
    /// A grassfire needs a boundary to start from, and the surface has none.
    #[error("the surface has no boundary (no edge with exactly one face): a grassfire has nowhere to start")]
    NoBoundary,
    /// The mesh needs more state than 32-bit ids can address.
    #[error("the mesh is too large: {count} {what} exceed the 32-bit id range; lower k")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
        /// How many were needed.
        count: u64,
    },
}
