//! [`Solver`]: everything about a (mesh, metric, options) triple that does not depend on
//! the sources, built once and shared; [`Workspace`]: the per-run buffers, reused across
//! runs.
//!
//! - `setup`: what [`Solver::new`] works out (Steiner layout, the engine's tables, the
//!   checks of the metric's costs), and the engine state ([`Engine`]), one variant per
//!   engine.
//! - `run`: one run, whichever the engine: sources and targets checked, seeds, the
//!   engine's settle loop, the field's roots.
//! - `rows`: many runs on all cores (distance matrices, local rows).
//! - `workspace`: the buffers a run fills.

mod rows;
mod run;
mod setup;
mod workspace;

pub use rows::{DistanceRow, VertexValues};
pub(in crate::propagate) use setup::Engine;
pub use workspace::Workspace;

use super::budget;
use crate::field::{Field, FieldData, SolverId};
use crate::mesh::{Csr, Topology, TriMesh};
use crate::options::Sources;
use crate::steiner::SteinerLayout;
use crate::{Error, Method, Options};
use geotracks_metrics::Metric;
use std::sync::{Arc, Mutex};

/// Answers distance queries on one mesh under one metric, many times.
///
/// Building a solver lays out Steiner points and the engine's per-face tables (the
/// *setup*). Each run then propagates from a set of sources: [`Solver::field`] returns
/// a [`Field`] you ask everything else (the distance at any surface point, gradients,
/// paths, isolines, regions, nearest sources); [`Solver::run`] does the same in a
/// [`Workspace`] whose buffers are reused, so a warm run allocates nothing.
///
/// A solver owns its mesh (shared: pass the mesh, an `Arc<TriMesh>`, or a `&TriMesh`,
/// which is copied once) and its metric. Cloning it is cheap (one reference count), and
/// it is `Send + Sync` for a metric that is: threads share it, each with its own
/// workspace (see [`Solver::distance_rows`]). A field keeps its solver, so it can never
/// be asked with another mesh or metric than the ones it was computed with.
///
/// ```
/// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
/// let field = solver.field(0)?;
/// assert!((field.distance(2) - 2f64.sqrt()).abs() < 1e-12);
/// let path = field.path(2)?; // straightened, back to vertex 0
/// assert!((path.length - 2f64.sqrt()).abs() < 1e-12);
///
/// // Many runs: one workspace, reused.
/// let mut workspace = solver.workspace();
/// for source in 0..4 {
///     let run = solver.run(&mut workspace, source)?;
///     assert_eq!(run.distance(source), 0.0);
/// }
/// # Ok::<(), geotracks::Error>(())
/// ```
pub struct Solver<M, T = TriMesh> {
    setup: Arc<Setup<M, T>>,
}

impl<M, T> Clone for Solver<M, T> {
    fn clone(&self) -> Self {
        Solver {
            setup: Arc::clone(&self.setup),
        }
    }
}

impl<M, T: Topology> std::fmt::Debug for Solver<M, T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solver")
            .field("method", &self.setup.method)
            .field("k", &self.setup.k)
            .field("vertices", &self.setup.mesh.vertex_count())
            .field("nodes", &self.setup.layout.node_count())
            .finish_non_exhaustive()
    }
}

/// What a solver worked out once, shared by its clones and the fields it made.
pub(crate) struct Setup<M, T> {
    /// Who this solver is, recorded in the fields it computes.
    pub id: SolverId,
    pub mesh: Arc<T>,
    pub metric: M,
    /// The engine that runs (see [`Solver::method`]).
    pub method: Method,
    /// The mean Steiner points per edge the layout was made with (0 for Dijkstra).
    pub k: f64,
    pub layout: Arc<SteinerLayout>,
    /// The engine's own state.
    pub(in crate::propagate) engine: Engine,
    /// Metric evaluations the setup made.
    pub setup_tests: u64,
    /// The sum of the edges' and wires' finite costs: no run's value exceeds a start
    /// plus this.
    pub cost_total: f64,
    /// The metric's least cost per unit of length, checked on the edges and wires
    /// (0: runs are never goal-directed).
    pub per_length: f64,
    /// The diagonal of the vertices' bounding box.
    pub extent: f64,
    /// Per vertex, its wires: the vertex at the other end and the wire's cost.
    pub wires: Csr<(u32, f64)>,
    pub setup_seconds: f64,
    /// Workspaces path queries ran in, kept for the next ones (at most two): a path's
    /// run records the nodes it touched, so the next one clears only those (and the
    /// track table), instead of allocating buffers the size of the mesh.
    pub path_workspaces: Mutex<Vec<Workspace>>,
    /// [`Options::memory_limit`], and what the solver and one run were budgeted: a
    /// path searched from both ends needs a second run's buffers.
    pub memory_limit: Option<u64>,
    /// [`Options::work_limit`]: for the exact engine, the most windows a run makes.
    pub work_limit: Option<u64>,
    pub budgeted: u64,
}

impl<M: Metric> Solver<M> {
    /// Prepares `mesh` for queries under `metric` with `options`. The mesh is taken by
    /// value, as an `Arc` (shared with the caller), or by reference (copied).
    ///
    /// With no Steiner scheme in `options` (the default), the engine that runs picks
    /// its own ([`Method::default_k`]): 2 points per edge for the wavefront engine, 5
    /// for the Steiner-graph engines, which need more for the same accuracy (they run
    /// when asked, and instead of the wavefront engine for a metric that is not flat on
    /// each face).
    ///
    /// # Errors
    /// [`Error::InvalidK`] for a scheme with no points, [`Error::InvalidMeanEdgeLength`]
    /// for a mean edge length that is not a length; [`Error::KTooLarge`] when an edge
    /// would carry more than 65535 points (tracks), the nodes would exceed 32-bit ids,
    /// the run would not fit [`Options::memory_limit`], or it would make more distance
    /// tests than [`Options::work_limit`] (checked before allocating, with the largest
    /// k that fits); [`Error::TooLarge`] when the tracks engine's
    /// instances exceed 32-bit ids; [`Error::InvalidCost`] and the other cost checks
    /// when the metric gives an edge or a wire a cost that is not one.
    pub fn new(mesh: impl Into<Arc<TriMesh>>, metric: M, options: &Options) -> Result<Self, Error> {
        Self::with_topology(mesh, metric, options)
    }
}

impl<M: Metric, T: Topology> Solver<M, T> {
    /// As [`Solver::new`], on any surface that implements [`Topology`]: a
    /// [`TriMesh`], or one whose adjacency is computed rather than stored (a terrain
    /// grid's cells). Runs on it are monomorphised: nothing is looked up through a
    /// pointer in the engines' loops.
    ///
    /// # Errors
    /// As [`Solver::new`].
    pub fn with_topology(
        surface: impl Into<Arc<T>>,
        metric: M,
        options: &Options,
    ) -> Result<Self, Error> {
        Ok(Solver {
            setup: Arc::new(Setup::new(surface.into(), metric, options)?),
        })
    }

    /// Propagates from `sources` and returns the field, which answers every query
    /// (see [`Field`]).
    ///
    /// `sources` is anything that converts into [`Sources`]: a vertex id, a
    /// [`SurfacePoint`](crate::SurfacePoint), a [`Source`](crate::Source) (a point
    /// with a start value), or a slice, array or `Vec` of them; with
    /// [`Sources::until`], a [`Stop`](crate::Stop) (a maximum distance, targets).
    ///
    /// A source inside a face (or on an edge) offers every node on the boundary of its
    /// face (of each face around the edge) the metric's cost of the straight segment
    /// to it: the source is one more node of the Steiner graph.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source, Sources, Stop, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
    /// let centre = SurfacePoint::Face { face: 0, bary: [1.0 / 3.0; 3] };
    /// let sources = [Source::new(centre), Source::new(3).with_start(0.25)];
    /// let stop = Stop::NONE.with_max_distance(0.6);
    /// let field = solver.field(Sources::from(&sources).until(&stop))?;
    /// assert!((field.distance(1) - 2f64.sqrt() / 3.0).abs() < 1e-12); // from the centroid
    /// assert_eq!(field.distance(3), 0.25);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoSource`]; [`Error::SourceOutOfRange`] for a source vertex that does not
    /// exist; [`Error::InvalidPoint`] for any other source or target that is not a point
    /// of the mesh; [`Error::InvalidValue`] for a start value that is not finite or a
    /// maximum distance below the least start, or NaN ([`Stop::check_from`]);
    /// [`Error::StartTooLarge`]; [`Error::InvalidCost`] if the metric returns NaN or a
    /// negative cost.
    ///
    /// [`Stop::check_from`]: crate::Stop::check_from
    pub fn field<'a>(
        &self,
        sources: impl Into<Sources<'a>>,
    ) -> Result<Field<M, FieldData, T>, Error> {
        let mut workspace = self.workspace();
        self.run(&mut workspace, sources)?;
        Ok(Field::new(self.clone(), workspace.into_data(self)))
    }

    /// As [`Solver::field`], in `workspace`: its buffers are reused (a warm run
    /// allocates nothing), and the field returned borrows them until the next run.
    /// For hot loops: many sources one after the other, a thread each.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Sources, Stop};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
    /// let mut workspace = solver.workspace();
    /// let near = Stop::NONE.with_max_distance(1.2);
    /// for v in 0..4 {
    ///     let run = solver.run(&mut workspace, Sources::from(v).until(&near))?;
    ///     assert_eq!(run.distance(v), 0.0);
    ///     // The opposite corner is √2 away: beyond the stop.
    ///     assert_eq!(run.unreachable_vertices(), 1);
    /// }
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::field`].
    pub fn run<'w, 'a>(
        &self,
        workspace: &'w mut Workspace,
        sources: impl Into<Sources<'a>>,
    ) -> Result<Field<M, &'w Workspace, T>, Error> {
        self.setup.run(workspace, &sources.into())?;
        Ok(Field::new(self.clone(), &*workspace))
    }

    /// Gives back its queries to a field's plain data ([`Field::into_data`]), if this
    /// solver (or a clone of it) computed it.
    ///
    /// # Errors
    /// [`Error::ForeignField`] for data another solver computed.
    pub fn attach(&self, data: FieldData) -> Result<Field<M, FieldData, T>, Error> {
        if data.solver() != self.setup.id {
            return Err(Error::ForeignField);
        }
        Ok(Field::new(self.clone(), data))
    }

    /// A workspace for this solver's runs (buffers are sized on first use).
    pub fn workspace(&self) -> Workspace {
        Workspace::default()
    }
}

impl<M, T> Solver<M, T> {
    /// The Steiner layout runs use.
    pub fn layout(&self) -> &SteinerLayout {
        &self.setup.layout
    }

    /// The mesh.
    pub fn mesh(&self) -> &T {
        &self.setup.mesh
    }

    /// The mesh, shared.
    pub fn shared_mesh(&self) -> &Arc<T> {
        &self.setup.mesh
    }

    /// The metric.
    pub fn metric(&self) -> &M {
        &self.setup.metric
    }

    /// The engine that runs: the one asked for, except that the wavefront engine gives
    /// way to the track-pruned one for a metric that is not flat on each face.
    pub fn method(&self) -> Method {
        self.setup.method
    }

    /// The mean number of Steiner points per edge the layout was made with: the
    /// options' or, without one, the engine's own default (0 for Dijkstra).
    pub fn k(&self) -> f64 {
        self.setup.k
    }

    /// What the solver worked out, for the modules that run and query it.
    pub(crate) fn setup(&self) -> &Setup<M, T> {
        &self.setup
    }
}
