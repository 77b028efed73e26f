use crate::mesh::MeshError;
use crate::surface::{PointError, SurfacePoint};
use geotracks_metrics::MetricError;
use std::fmt;
use thiserror::Error;

/// Which point of a run or a query an [`Error::InvalidPoint`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PointRole {
    /// A run's source, by its index in the sources given.
    Source(usize),
    /// A target of a [`Stop`](crate::Stop), by its index in `Stop::targets`.
    Target(usize),
    /// The point given to a [`Field`](crate::Field).
    Query,
}

impl fmt::Display for PointRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PointRole::Source(i) => write!(f, "source {i}"),
            PointRole::Target(i) => write!(f, "target {i}"),
            PointRole::Query => f.write_str("the query point"),
        }
    }
}

/// Which number an [`Error::InvalidValue`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ValueRole {
    /// [`Stop::max_distance`](crate::Stop::max_distance).
    MaxDistance,
    /// The start value of a run's source, by its index in the sources given.
    Start {
        /// The source's index.
        source: usize,
    },
    /// An isoline level, by its index in the levels given.
    IsolineLevel {
        /// The level's index.
        index: usize,
    },
}

impl ValueRole {
    /// What the value must be: a maximum distance any number ≥ 0 (`inf`: no limit),
    /// the others any finite number.
    pub fn expected(self) -> &'static str {
        match self {
            ValueRole::MaxDistance => {
                "a number >= 0, or >= the least start value of the sources (inf: no limit)"
            }
            ValueRole::Start { .. } | ValueRole::IsolineLevel { .. } => "a finite number",
        }
    }
}

impl fmt::Display for ValueRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ValueRole::MaxDistance => f.write_str("the maximum distance"),
            ValueRole::Start { source } => write!(f, "the start value of source {source}"),
            ValueRole::IsolineLevel { index } => write!(f, "isoline level {index}"),
        }
    }
}

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
    /// A medial axis could not be computed from a surface.
    #[error(transparent)]
    MedialAxis(#[from] crate::skeleton::medial::MedialAxisError),
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
    /// A source, target or query point is not a point of the mesh (no such vertex,
    /// edge or face; a parameter or barycentrics out of range). Fix the point; its
    /// error says what is wrong.
    #[error("{which}: {error}")]
    InvalidPoint {
        /// Which point.
        which: PointRole,
        /// What is wrong with it.
        error: PointError,
    },
    /// A number given as input is not usable: NaN, infinite where a finite value is
    /// needed, or negative where it must not be ([`ValueRole::expected`] says what it
    /// must be).
    #[error("{which} is {}; it must be {}", geotracks_metrics::Num(*value), which.expected())]
    InvalidValue {
        /// Which value.
        which: ValueRole,
        /// The value given.
        value: f64,
    },
    /// An isoline option is out of range ([`IsolineOptions`](crate::trace::IsolineOptions)).
    #[error("isoline option {option} is {}; it must be {expected}", geotracks_metrics::Num(*value))]
    InvalidIsolineOption {
        /// The option's name.
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A region option is out of range ([`Field::regions`](crate::Field::regions)).
    #[error("region option {option} is {}; it must be {expected}", geotracks_metrics::Num(*value))]
    InvalidRegionOption {
        /// The option's name.
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// No source reaches the point a path was asked for: it lies on another component,
    /// beyond the maximum distance, or past an early stop (a run that stopped at other
    /// targets). Run without the stop, or with the point among the targets.
    #[error("point {point} is not reached from any source (another component, beyond the maximum distance, or past an early stop)")]
    Unreachable {
        /// The point.
        point: SurfacePoint,
    },
    /// Following parents back from a point loops: the metric returned zero costs
    /// between distinct points, so values do not decrease along the path. Metrics must
    /// be zero only for a segment of length zero.
    #[error("the path from point {point} loops: its parents form a cycle (the metric returned zero costs between distinct points)")]
    ParentCycle {
        /// The point the path was asked from.
        point: SurfacePoint,
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
    /// [`Options::mean_edge_length`](crate::Options::mean_edge_length) is not a finite
    /// length > 0.
    #[error(
        "invalid mean edge length for the Steiner spacing: {length} (it must be finite and > 0)"
    )]
    InvalidMeanEdgeLength {
        /// The length given.
        length: f64,
    },
    /// A metric returned a NaN or negative cost. Metrics must return costs ≥ 0
    /// (`+inf` is allowed and means the segment cannot be crossed).
    #[error("metric '{metric}' returned {} for a segment in face {face}; costs must be ≥ 0 and not NaN", geotracks_metrics::Num(*value))]
    InvalidCost {
        /// The metric's name.
        metric: String,
        /// The face of the segment.
        face: u32,
        /// The cost returned.
        value: f64,
    },
    /// A metric returned a NaN or negative cost for a wire (a line element that is no
    /// face edge, [`TriMesh::vertex_wires`](crate::mesh::TriMesh::vertex_wires)).
    #[error("metric '{metric}' returned {} for the wire from vertex {} to vertex {}; costs must be ≥ 0 and not NaN", geotracks_metrics::Num(*value), wire[0], wire[1])]
    InvalidWireCost {
        /// The metric's name.
        metric: String,
        /// The wire's vertices, lower first.
        wire: [u32; 2],
        /// The cost returned.
        value: f64,
    },
    /// The metric's costs on this mesh add up beyond the f64 range, so distances could
    /// overflow (a density of 1e300 over long edges, say). Scale the metric or the
    /// mesh down.
    #[error("metric '{metric}': the costs of the mesh's edges add up beyond the f64 range (about 1.8e308), so distances could overflow; scale the metric or the mesh down")]
    CostOverflow {
        /// The metric's name.
        metric: String,
    },
    /// The metric's [`min_cost_per_length`](geotracks_metrics::Metric::min_cost_per_length)
    /// promises more than an edge costs: goal-directed runs would stop with wrong
    /// values.
    #[error("metric '{metric}' says every unit of length costs at least {per_length:e}, but edge {edge} ({length:e} long) costs {cost:e} ({per_unit:e} per unit)")]
    CostBelowBound {
        /// The metric's name.
        metric: String,
        /// The bound the metric gave.
        per_length: f64,
        /// The edge that costs less.
        edge: u32,
        /// Its length.
        length: f64,
        /// Its cost (along it, in its cheapest face).
        cost: f64,
        /// Its cost per unit of length.
        per_unit: f64,
    },
    /// A wire costs less than the metric's
    /// [`min_cost_per_length`](geotracks_metrics::Metric::min_cost_per_length) promises.
    #[error("metric '{metric}' says every unit of length costs at least {per_length:e}, but the wire from vertex {} to vertex {} ({length:e} long) costs {cost:e}", wire[0], wire[1])]
    WireBelowBound {
        /// The metric's name.
        metric: String,
        /// The bound the metric gave.
        per_length: f64,
        /// The wire's two vertices, in the direction that costs less.
        wire: [u32; 2],
        /// Its length.
        length: f64,
        /// Its cost.
        cost: f64,
    },
    /// A source's start value is so large that distances from it could leave the f64
    /// range (a start plus the mesh's total cost must stay below about 1.8e308).
    #[error("the start value of source {index} is {start:e}: with the mesh's costs (up to {cost_total:e} in all) distances could overflow; start values must stay below about 1.8e308 minus that")]
    StartTooLarge {
        /// The source's index in the sources given.
        index: usize,
        /// The start value given.
        start: f64,
        /// The sum of the mesh's finite edge costs under the metric.
        cost_total: f64,
    },
    /// A grassfire needs a boundary to start from, and the surface has none.
    #[error("the surface has no boundary (no edge with exactly one face): a grassfire has nowhere to start")]
    NoBoundary,
    /// The Steiner points asked for cannot be laid out, the run would not fit in
    /// memory, or it would do more work than the work limit allows; checked before
    /// anything is allocated. Lower k to `largest_k` or below (or raise the limit).
    #[error("k = {k} is too large: {limit}; the largest k that fits is {largest_k}")]
    KTooLarge {
        /// The k asked for (points per edge for the fixed scheme).
        k: f64,
        /// The limit it breaks.
        limit: SizeLimit,
        /// The largest k (of the same scheme) that fits; 0 if none does.
        largest_k: f64,
    },
    /// A distance matrix ([`Solver::distance_rows`](crate::Solver::distance_rows))
    /// would not fit in memory: checked before any row is computed. Ask for fewer
    /// sources or targets at a time.
    #[error("a distance matrix of {rows} rows × {columns} columns needs {:.3} GB, more than the {:.3} GB available; ask for fewer sources or targets at a time", *bytes as f64 / 1e9, *available as f64 / 1e9)]
    OutputTooLarge {
        /// Rows asked for (one per source).
        rows: usize,
        /// Columns per row (targets, or every vertex).
        columns: usize,
        /// Bytes the rows would take.
        bytes: u64,
        /// Bytes available: `Options::memory_limit`, or what the system reports.
        available: u64,
    },
    /// The vertices within a maximum distance of each source
    /// ([`Solver::local_distance_rows`](crate::Solver::local_distance_rows)) outgrew
    /// the memory while the rows were computed. Lower the maximum distance, or ask for
    /// fewer sources at a time.
    #[error("the pairs within {max_distance} of {sources} sources outgrew the memory: {pairs} pairs so far, more than the {:.3} GB available; lower the maximum distance or ask for fewer sources at a time", *available as f64 / 1e9)]
    LocalRowsTooLarge {
        /// The maximum distance asked for.
        max_distance: f64,
        /// Sources asked for.
        sources: usize,
        /// Pairs found when the limit was passed.
        pairs: u64,
        /// Bytes available: `Options::memory_limit`, or what the system reports.
        available: u64,
    },
    /// The exact engine ([`Method::Exact`](crate::Method::Exact)) cannot give exact
    /// distances under this metric: it is not a constant norm on some face, or two
    /// faces give a shared edge different lengths (per-face tensors that disagree:
    /// shortest paths refract there, and no finite set of windows holds them). Run
    /// the wavefront engine (`Method::Wave`), which handles both approximately.
    #[error("the exact engine cannot run under metric '{metric}': {reason}; the wavefront engine (method wave) handles it approximately")]
    NotExact {
        /// The metric's name.
        metric: String,
        /// Which face or edge, and why.
        reason: String,
    },
    /// The exact engine's windows outgrew the memory (or the work limit) during a
    /// run: window counts can grow faster than the faces on meshes with many saddle
    /// vertices. Raise [`Options::memory_limit`](crate::Options::memory_limit) (or
    /// the work limit), stop the run earlier (a maximum distance, targets), or use an
    /// approximate engine.
    #[error("the exact engine's windows outgrew the limit: {windows} windows ({:.3} GB); raise the memory or work limit, stop the run earlier, or use an approximate method", *bytes as f64 / 1e9)]
    ExactTooLarge {
        /// Windows when the limit was reached: those made, for the work limit; those
        /// held at once, for the memory limit (waiting on their edges, and carried
        /// into a field; a run that wants only values at vertices,
        /// [`Solver::vertex_values`](crate::Solver::vertex_values), keeps none once
        /// carried).
        windows: u64,
        /// The bytes they took (held) or would take (made).
        bytes: u64,
    },
    /// The mesh needs more state than 32-bit ids can address.
    #[error("the mesh is too large: {count} {what} exceed the 32-bit id range; lower k")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
        /// How many were needed.
        count: u64,
    },
}

/// Which limit a Steiner layout breaks ([`Error::KTooLarge`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SizeLimit {
    /// One edge would carry more points than the tracks engine's face records hold.
    PointsOnEdge {
        /// The edge.
        edge: u32,
        /// Points it would carry.
        points: u64,
        /// The most an edge may carry (65535).
        limit: u64,
    },
    /// Vertices and Steiner points together would exceed 32-bit node ids.
    Nodes {
        /// Nodes needed.
        nodes: u64,
    },
    /// A run would make more distance tests than the work limit allows
    /// ([`Options::work_limit`](crate::Options::work_limit); an estimate, see the
    /// guide's Distances page, docs/src/distances.md).
    Work {
        /// The estimated distance tests of one full run.
        tests: f64,
        /// The limit.
        limit: u64,
    },
    /// The run's state would need more memory than is available.
    Memory {
        /// Bytes the layout, the engine's tables and one run's buffers would take
        /// (an estimate, within about 20 %).
        needed: u64,
        /// Bytes available: `Options::memory_limit`, or what the system reports.
        available: u64,
    },
}

impl std::fmt::Display for SizeLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            SizeLimit::PointsOnEdge {
                edge,
                points,
                limit,
            } => write!(
                f,
                "edge {edge} would carry {points} Steiner points, more than the {limit} one edge can hold"
            ),
            SizeLimit::Nodes { nodes } => write!(
                f,
                "{nodes} nodes (vertices and Steiner points) exceed the 32-bit id range"
            ),
            SizeLimit::Work { tests, limit } => write!(
                f,
                "one run would make about {tests:.2e} distance tests, more than the work limit of {:.2e} (raise the work limit to run it anyway)",
                limit as f64
            ),
            SizeLimit::Memory { needed, available } => write!(
                f,
                "the run would need about {:.3} GB, more than the {:.3} GB available",
                needed as f64 / 1e9,
                available as f64 / 1e9
            ),
        }
    }
}
