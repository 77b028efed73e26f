//! The engines that turn sources into a [`GeodesicField`].
//!
//! - [`Method::Graph`]: the complete Steiner graph per face, run with Dijkstra's
//!   algorithm on a binary heap. The graph is implicit: when a node is settled it tests
//!   every node on the boundary of each face around it (O(k) tests per face entry,
//!   O(k²) per face). This is the reference the fast engine must agree with.
//! - [`Method::Dijkstra`]: Dijkstra on mesh edges only: the same graph with no Steiner
//!   points. Fast, and several percent too long.
//! - [`Method::Tracks`] (the default): the track-pruned engine of the geodesic tracks
//!   paper. Same distances as the graph for norms (Euclidean, Tensor: relative 1e-9, by
//!   test), with far fewer distance tests, growing about linearly in k:
//!   tests(k = 8) / tests(k = 2) is 5.6 on the shared bunny against 13 for the graph
//!   (`cargo test --release --test solver -- --nocapture` prints both).
//!
//! All are generic over the [`Metric`] (monomorphised: no dynamic dispatch in the loop).
//!
//! A path between two points ([`Solver::shortest_path_with`]) runs a Steiner-graph
//! engine from both ends at once, on two threads, until the two searches meet
//! (`meet`).

mod budget;
mod frontier;
mod graph;
mod meet;
mod queue;
mod solver;
mod tracks;
mod wave;

pub use solver::{Solver, Workspace};

// The run options live in their own module (a field records its method, and must not
// import the engine); the engine's files keep naming them through this one.
pub(crate) use crate::options::{Method, Options, Stop};

use crate::field::GeodesicField;
use crate::mesh::TriMesh;
use crate::Error;
use geotracks_metrics::Metric;

/// Computes the distance from the nearest of `sources` (vertex ids) to every vertex.
///
/// # Errors
/// [`Error::NoSource`], [`Error::SourceOutOfRange`], [`Error::InvalidK`],
/// [`Error::InvalidCost`] if the metric returns NaN or a negative cost.
///
/// # Example
/// ```
/// use geotracks::{distance_field, mesh::TriMesh, Euclidean, Options};
/// // A unit square in two triangles.
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// ).unwrap();
/// let field = distance_field(&mesh, &Euclidean, &[0], &Options::DEFAULT).unwrap();
/// assert!((field.distance(2) - 2f64.sqrt()).abs() < 1e-12);
/// ```
pub fn distance_field<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    sources: &[u32],
    options: &Options,
) -> Result<GeodesicField, Error> {
    Solver::new(mesh, metric, options)?.solve(sources)
}
