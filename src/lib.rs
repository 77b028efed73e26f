//! # geotracks
//!
//! Geodesic distances on triangle meshes of any topology, under pluggable metrics:
//! Steiner points on edges, and engines that propagate between them (the default
//! carries a wavefront on each Steiner point, exact on developable meshes).
//!
//! Build a [`Solver`] once per mesh, metric and [`Options`]; each run
//! ([`Solver::field`]) returns a [`Field`] that answers everything else as methods —
//! the distance at any surface point, gradients, paths, isolines, regions, nearest
//! sources — without running the engine again.
//!
//! ## Map of the crate
//! - [`mesh`]: the [`Topology`](mesh::Topology) trait the engines and queries are
//!   written against (faces of an edge, edges of a face, …, on any surface that can
//!   answer them; [`Solver::with_topology`]), and [`TriMesh`](mesh::TriMesh), its
//!   implementor with tables (an edge may have any number of faces; line elements
//!   that are no face edge are wires, which distances travel too); readers and
//!   writers ([`mesh::io`]).
//! - [`metrics`] (re-exported crate `geotracks-metrics`): the [`Metric`] trait and the
//!   built-ins [`Euclidean`], [`Density`], [`Tensor`], [`TensorField`].
//! - [`steiner`]: where Steiner points go on each edge and how nodes are numbered.
//! - [`options`]: how a run goes: [`Method`] (the wavefront engine `Wave` by default,
//!   the track-pruned `Tracks`, the complete Steiner graph `Graph` they are checked
//!   against, `Dijkstra` on edges), [`Options`] (engine and Steiner points; without a
//!   k the engine that runs picks its own), [`Sources`] (where a run starts) and
//!   [`Stop`] (early stops).
//! - [`propagate`]: the engines side by side, and the [`Solver`] that runs them (one
//!   field, or many in a reused [`Workspace`], or rows on every core).
//! - [`field`]: [`Field`], a run with its solver, which every query is a method of;
//!   [`FieldData`], the same as plain data.
//! - [`trace`]: what the queries return and how they are computed: paths
//!   ([`GeodesicPath`], straightened), isolines, regions and gradients.
//! - point-to-point routes ([`Solver::shortest_path`]): a run stopped at the target,
//!   searched from both ends at once where it can.
//! - [`skeleton`]: curve skeletons of medial axes with the axis's topology: burnt from
//!   the border or by radius, thinned by collapses in burn order, pruned by erosion
//!   thickness; and ([`skeleton::medial`]) the medial axis of a closed surface mesh,
//!   from the Voronoi diagram of points sampled on it.
//!
//! Dependencies point one way: applications ([`skeleton`], routes) run the engines in
//! [`propagate`], which make fields; [`field`] answers its queries with [`trace`];
//! [`steiner`] and [`mesh`] are below them; the metrics know nothing of the rest.
//!
//! ## Sibling crates
//! Built on this one, which knows nothing of them:
//! - `geotracks-terrain`: elevation grids (ESRI ASCII, GeoTIFF) as meshes or as
//!   surfaces computed from rows and columns (a second `Topology`), terrain
//!   costs (slope density, impassable faces, uphill and walking-time costs), routes
//!   and maps;
//! - `geotracks-render`: pictures of fields (the mesh coloured by distance, isolines,
//!   sources) and of skeletons over their medial axis;
//! - `geotracks-cli`: the command-line tool `geotracks`.
//!
//! ## Example
//! ```
//! use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, SurfacePoint};
//!
//! // A flat 1 × 1 square made of two triangles.
//! let mesh = TriMesh::new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     vec![[0, 1, 2], [0, 2, 3]],
//! )?;
//! let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
//! let field = solver.field(0)?; // one run from vertex 0
//! assert!((field.distance(2) - 2f64.sqrt()).abs() < 1e-12);
//! // Every query is a method on the field: no run again, no mesh passed again.
//! let middle = SurfacePoint::Edge { edge: 1, t: 0.5 };
//! let path = field.path(middle)?; // from the point back to vertex 0, straightened
//! assert!((path.length - field.distance_at(middle)?).abs() < 1e-12);
//! println!("{} distance tests", field.stats().distance_tests);
//! # Ok::<(), geotracks::Error>(())
//! ```
#![forbid(unsafe_code)]

mod error;
pub mod field;
mod flat;
pub mod mesh;
pub mod options;
pub mod propagate;
mod route;
pub mod skeleton;
pub mod steiner;
pub mod surface;
pub mod trace;

/// The metric crate, `geotracks-metrics`.
pub use geotracks_metrics as metrics;

/// The vector library of the public API: positions come back as `glam::DVec3` (e.g.
/// [`TriMesh::position`](mesh::TriMesh::position), [`GeodesicPath::positions`]), so
/// callers can name the type without depending on the same `glam` version themselves.
pub use glam;

pub use error::{Error, PointRole, SizeLimit, ValueRole};
pub use field::{Field, FieldData, FieldStorage, Stats};
pub use geotracks_metrics::{
    BuiltinMetric, Density, Euclidean, FacePoint, Metric, MetricError, Reversed, Tensor,
    TensorField,
};
pub use options::{Method, Options, Sources, Stop};
pub use propagate::{DistanceRow, Solver, VertexValues, Workspace};
pub use steiner::{SteinerLayout, SteinerScheme};
pub use surface::{PointError, Source, SurfacePoint};
pub use trace::GeodesicPath;

/// The README's code blocks, compiled and run as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The user guide's pages (`docs/src/`, an mdBook): their Rust code blocks are compiled
/// and run as doctests, as the README's are, so the guide stays true to the API.
#[cfg(doctest)]
mod guide {
    /// Introduction and installation.
    #[doc = include_str!("../docs/src/introduction.md")]
    struct Introduction;
    /// Distances and engines.
    #[doc = include_str!("../docs/src/distances.md")]
    struct Distances;
    /// Paths.
    #[doc = include_str!("../docs/src/paths.md")]
    struct Paths;
    /// Isolines, regions and gradients.
    #[doc = include_str!("../docs/src/isolines.md")]
    struct Isolines;
    /// Pictures.
    #[doc = include_str!("../docs/src/pictures.md")]
    struct Pictures;
    /// Skeletons of medial axes.
    #[doc = include_str!("../docs/src/skeletons.md")]
    struct Skeletons;
    // Terrain: its code needs the terrain crate, whose doctests run it.
    /// Python.
    #[doc = include_str!("../docs/src/python.md")]
    struct Python;
    /// Metrics: built-in, custom and directed.
    #[doc = include_str!("../docs/src/metrics.md")]
    struct Metrics;
    /// The command line.
    #[doc = include_str!("../docs/src/command-line.md")]
    struct CommandLine;
    /// Accuracy.
    #[doc = include_str!("../docs/src/accuracy.md")]
    struct Accuracy;
    /// Performance.
    #[doc = include_str!("../docs/src/performance.md")]
    struct Performance;
    /// Fuzzing.
    #[doc = include_str!("../docs/src/fuzzing.md")]
    struct Fuzzing;
}
