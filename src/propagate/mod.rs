//! The engines that turn sources into a [`Field`](crate::Field), and the [`Solver`]
//! that runs them.
//!
//! - [`Method::Wave`] (the default): Steiner nodes that carry their wavefront (a
//!   virtual source and a window): exact on planar and developable meshes, far more
//!   accurate than the Steiner graph elsewhere. It needs a metric flat on each face
//!   (`Metric::face_gram`); with any other metric the tracks engine runs instead.
//! - [`Method::Tracks`]: the track-pruned engine of the geodesic tracks paper. Same
//!   distances as the graph for norms (Euclidean, Tensor: relative 1e-9, by test), with
//!   far fewer distance tests, growing about linearly in k.
//! - [`Method::Graph`]: the complete Steiner graph per face, run with Dijkstra's
//!   algorithm on a binary heap. The graph is implicit: when a node is settled it tests
//!   every node on the boundary of each face around it (O(k) tests per face entry,
//!   O(k²) per face). This is the reference the fast engines must agree with.
//! - [`Method::Dijkstra`]: Dijkstra on mesh edges only: the same graph with no Steiner
//!   points. Fast, and several percent too long.
//!
//! All are generic over the [`Metric`](geotracks_metrics::Metric) (monomorphised: no
//! dynamic dispatch in the loop), share one settle loop and queue front
//! (`frontier`), and differ only in how a settled node offers values to others. The
//! solver's engine state is one enum with a variant per engine (`solver::Engine`).
//!
//! Point-to-point routes, which run an engine from both ends at once, live above the
//! engines ([`Solver::shortest_path`], in `route`); `meet` is the engines' side of it.
//!
//! **Scalars.** Every coordinate, length and distance is `f64`, and nothing is generic
//! over the scalar (no `num-traits`), because the engines' error budgets are set in
//! `f64` units: the wavefront engine is exact to 1e-9 on planar meshes, faces glue to
//! 1e-9 of an edge plus 1e-12 of their size, ties are 1e-12 relative (`flat`). An
//! `f32` rounds at 6e-8 relative: a distance, a virtual source or σ stored in it would
//! spend the whole budget in one rounding. Where `f32` pays, it is a concrete choice
//! with its slack argued: the wavefront engine stores window ends as `f32` fractions of
//! the edge, rounded inwards (`flat::WINDOW_SLACK` covers them), and the tracks engine
//! its track values, rounded up. A scalar parameter (`S: num_traits::Float`) comes with
//! the bounded window engine, whose per-edge windows are worth storing in `f32` on
//! meshes of millions of faces while σ and settled values stay `f64`, run at `f64`
//! against the exact engine as its oracle; until there is that second instantiation a
//! type parameter would have one type and hide the budget instead of stating it.

mod budget;
mod frontier;
mod graph;
pub(crate) mod meet;
mod queue;
pub(crate) mod solver;
mod tracks;
mod wave;
pub(crate) mod windows;

pub use solver::{DistanceRow, Solver, VertexValues, Workspace};

// The run options live in their own module (a field records its method, and must not
// import the engine); the engine's files keep naming them through this one.
pub(crate) use crate::options::{Method, Options, Stop};
