//! [`Solver`]: everything about a (mesh, metric, options) triple that does not depend on
//! the sources, built once; and [`Workspace`]: the per-run buffers, reused across runs.

use super::budget;
use super::frontier::{edge_steps, Frontier, Seed};
use super::meet::{Meeting, Side};
use super::queue::{BucketQueue, HeapQueue};
use super::tracks::{Track, TrackTables};
use super::wave;
use super::{graph, tracks, Method, Options, Stop};
use crate::field::{FieldView, GeodesicField, Goal, Horizon, Root, SolverId, Stats, Wave};
use crate::flat;
use crate::mesh::{bounding_box, Csr, FaceFrame, TriMesh, NONE};
use crate::steiner::SteinerLayout;
use crate::surface::{PointError, Source, SurfacePoint};
use crate::trace::Query;
use crate::{Error, PointRole, ValueRole};
use geotracks_metrics::Metric;
use geotracks_metrics::Reversed;
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

/// Answers distance queries on one mesh under one metric, many times.
///
/// Building a solver lays out Steiner points and the engine's per-face tables (the
/// *setup*); each [`Solver::run`] then propagates from a set of sources into a
/// [`Workspace`] whose buffers are reused, so a warm run allocates nothing. A solver is
/// `Sync`: threads can share it, each with its own workspace (see
/// [`Solver::distance_rows`]).
///
/// Queries that need the mesh and the metric (the distance at any surface point, paths,
/// labels) go through the solver that computed the field: [`Solver::query`] and
/// [`Solver::query_workspace`].
///
/// ```
/// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
/// let mut workspace = solver.workspace();
/// for source in 0..4 {
///     solver.run(&mut workspace, &[source])?;
///     assert_eq!(workspace.vertex_distances()[source as usize], 0.0);
/// }
/// # Ok::<(), geotracks::Error>(())
/// ```
pub struct Solver<'m, M> {
    /// Who this solver is, recorded in the fields it computes.
    id: SolverId,
    mesh: &'m TriMesh,
    metric: M,
    method: Method,
    k: f64,
    layout: Arc<SteinerLayout>,
    edge_steps: Option<Vec<f64>>,
    setup_tests: u64,
    tables: Option<Arc<TrackTables>>,
    /// Per edge block, for the wavefront engine: whether its faces glue isometrically.
    isometric: Vec<bool>,
    /// How far below a node's value its offers can reach (see `Frontier::reach`).
    reach: f64,
    bucket_width: f64,
    /// The sum of the edges' and wires' finite costs: no run's value exceeds a start
    /// plus this.
    cost_total: f64,
    /// The metric's least cost per unit of length, checked on the edges and wires
    /// (0: runs are never goal-directed).
    per_length: f64,
    /// The diagonal of the vertices' bounding box.
    extent: f64,
    /// Per vertex, its wires: the vertex at the other end and the wire's cost.
    wires: Csr<(u32, f64)>,
    setup_seconds: f64,
    /// Workspaces path queries ran in, kept for the next ones (at most two): a path's
    /// run records the nodes it touched, so the next one clears only those (and the
    /// track table), instead of allocating buffers the size of the mesh.
    path_workspaces: std::sync::Mutex<Vec<Workspace>>,
    /// [`Options::memory_limit`], and what the solver and one run were budgeted: a
    /// path searched from both ends needs a second run's buffers.
    memory_limit: Option<u64>,
    budgeted: u64,
}

/// The per-run buffers of a [`Solver`]: per-node distances and parents, per-instance
/// tracks and the queue. After a run it holds that run's result.
#[derive(Default)]
pub struct Workspace {
    vertex_count: usize,
    distance: Vec<f64>,
    parent: Vec<u32>,
    parent_face: Vec<u32>,
    tracks: Vec<Track>,
    /// Per Steiner node, the wave it carries (wavefront engine).
    waves: Vec<Wave>,
    /// Per node, its goal estimate in a goal-directed run (see `Frontier::estimate`).
    estimate: Vec<f64>,
    /// The nodes the last run touched (see `Frontier::touched`), if it recorded them.
    touched: Vec<u32>,
    /// Whether `touched` lists every node the last run set (else it is empty and the
    /// next reset clears everything).
    recorded: bool,
    heap: HeapQueue,
    buckets: BucketQueue,
    /// The last run's sources, validated.
    sources: Vec<Source>,
    /// The sources' offers to nodes; after a run, one per node that a source reached
    /// directly, sorted by node (the *roots* paths end at).
    seeds: Vec<Seed>,
    /// Nodes whose values decide when the last run could stop.
    targets: Vec<u32>,
    /// After a run, per node that a source reached directly, its source (from `seeds`).
    roots: Vec<Root>,
    /// The solver whose run the buffers hold; `None` before the first run and after a
    /// run that failed.
    solver: Option<SolverId>,
    /// The engine of the last run.
    method: Option<Method>,
    /// The last run's horizon (see [`FieldView::horizon`]).
    horizon: Horizon,
}

impl Workspace {
    /// Distance at every vertex after the last run (`inf` where unreached).
    pub fn vertex_distances(&self) -> &[f64] {
        &self.distance[..self.vertex_count.min(self.distance.len())]
    }

    /// The vertices the last run reached and their distances, each once. After a run
    /// that could stop early (at a maximum distance or at targets) this costs what the
    /// run touched, not the mesh, in the order the vertices were first reached; after a
    /// full run, it scans [`Workspace::vertex_distances`] in vertex order.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source, Stop};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let mut workspace = solver.workspace();
    /// let stop = Stop::NONE.with_max_distance(1.2);
    /// solver.run_from(&mut workspace, &[Source::new(0)], &stop)?;
    /// let mut reached: Vec<u32> = workspace.reached_vertices().map(|(v, _)| v).collect();
    /// reached.sort();
    /// assert_eq!(reached, [0, 1, 3]); // vertex 2 is √2 away
    /// solver.run(&mut workspace, &[0])?; // a full run
    /// assert_eq!(workspace.reached_vertices().count(), 4);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    pub fn reached_vertices(&self) -> impl Iterator<Item = (u32, f64)> + '_ {
        // A vertex enters `touched` once (when its value first drops from ∞; vertices
        // carry no wave); values forgotten after the run are ∞ again.
        let listed = self.recorded.then(|| {
            self.touched.iter().filter_map(|&node| {
                let d = self.distance[node as usize];
                ((node as usize) < self.vertex_count && d.is_finite()).then_some((node, d))
            })
        });
        let scanned = (!self.recorded).then(|| {
            let d = self.vertex_distances().iter().enumerate();
            d.filter(|(_, d)| d.is_finite())
                .map(|(v, &d)| (v as u32, d))
        });
        listed
            .into_iter()
            .flatten()
            .chain(scanned.into_iter().flatten())
    }

    /// Distance at every node (vertices, then Steiner points) after the last run.
    pub fn node_distances(&self) -> &[f64] {
        &self.distance
    }

    /// The last run's state, borrowed.
    fn view<'a>(&'a self, layout: &'a SteinerLayout) -> FieldView<'a> {
        FieldView {
            layout,
            distance: &self.distance,
            parent: &self.parent,
            parent_face: &self.parent_face,
            sources: &self.sources,
            roots: &self.roots,
            waves: &self.waves,
            method: self.method.unwrap_or(Method::Wave),
            horizon: self.horizon,
        }
    }

    /// Sizes and clears the buffers for a run over `nodes` nodes, `instances` tracks
    /// and `waves` waves; allocates only when they must grow.
    ///
    /// Only the nodes the last run touched hold anything but reset values, so when
    /// the sizes match and those are few (a run stopped at a maximum distance, as
    /// when a local distance matrix runs once per vertex), only they are cleared: a
    /// local run costs what it reaches, not the mesh. Tracks are cleared whole: the
    /// tracks engine writes those of targets it does not reach.
    fn reset(&mut self, vertex_count: usize, nodes: usize, instances: usize, waves: usize) {
        let partial = self.recorded
            && self.touched.len() < nodes / 4
            && self.distance.len() == nodes
            && self.vertex_count == vertex_count;
        if partial {
            for &node in &self.touched {
                let node = node as usize;
                self.distance[node] = f64::INFINITY;
                self.parent[node] = NONE;
                self.parent_face[node] = NONE;
            }
        } else {
            fill(&mut self.distance, nodes, f64::INFINITY);
            fill(&mut self.parent, nodes, NONE);
            fill(&mut self.parent_face, nodes, NONE);
        }
        // Waves sit at node − vertex_count; none were kept if the last run had none.
        if partial && waves > 0 && self.waves.len() == waves {
            for &node in &self.touched {
                if let Some(w) = (node as usize).checked_sub(vertex_count) {
                    self.waves[w] = Wave::NONE;
                }
            }
        } else {
            fill(&mut self.waves, waves, Wave::NONE);
        }
        debug_assert!(
            !partial
                || (self.distance.iter().all(|d| *d == f64::INFINITY)
                    && self
                        .parent
                        .iter()
                        .chain(&self.parent_face)
                        .all(|&p| p == NONE)
                    && self.waves.iter().all(|w| !w.is_some())),
            "a node the last run set was not recorded as touched"
        );
        self.touched.clear();
        self.vertex_count = vertex_count;
        fill(&mut self.tracks, instances, Track::NONE);
    }
}

fn fill<T: Copy>(v: &mut Vec<T>, len: usize, value: T) {
    v.clear();
    v.resize(len, value);
}

impl<'m, M: Metric> Solver<'m, M> {
    /// Prepares `mesh` for queries under `metric` with `options`.
    ///
    /// # Errors
    /// [`Error::InvalidK`] for a scheme with no points, [`Error::InvalidMeanEdgeLength`]
    /// for a mean edge length that is not a length; [`Error::KTooLarge`] when an edge
    /// would carry more than 65535 points (tracks), the nodes would exceed 32-bit ids,
    /// the run would not fit [`Options::memory_limit`], or it would make more distance
    /// tests than [`Options::work_limit`] (checked before allocating, with the largest
    /// k that fits); [`Error::TooLarge`] when the tracks engine's
    /// instances exceed 32-bit ids.
    pub fn new(mesh: &'m TriMesh, metric: M, options: &Options) -> Result<Self, Error> {
        let start = Instant::now();
        // The wavefront engine needs every face's flattening; other metrics run the
        // tracks engine.
        let flat_frames = (options.method == Method::Wave)
            .then(|| flat_frames(mesh, &metric))
            .flatten();
        let method = match (options.method, &flat_frames) {
            (Method::Wave, None) => Method::Tracks,
            (method, _) => method,
        };
        let options = &options.with_method(method);
        let mut reach = 0.0;
        // The edges' lengths in the faces' flattenings, for the wavefront engine.
        let mut flat = None;
        // What the budget check found the solver and a run need (0: not checked).
        let mut budgeted = 0;
        let layout = if options.method == Method::Dijkstra {
            SteinerLayout::vertices_only(mesh)
        } else {
            if !options.steiner.is_valid() {
                return Err(Error::InvalidK {
                    k: options.steiner.k(),
                });
            }
            if let Some(length) = options.mean_edge_length {
                if !(length.is_finite() && length > 0.0) {
                    return Err(Error::InvalidMeanEdgeLength { length });
                }
            }
            // The wavefront engine spaces points by the metric's lengths, puts at least
            // one on every edge (a wave crosses an edge only through its points), and
            // keeps every point the Steiner graph has at the same k (spaced by the
            // lengths in space), so that it holds at least the graph's paths: where
            // faces do not glue (per-face tensors) waves restart at every edge, and its
            // values are then the graph's or better.
            let in_space = edge_lengths(mesh, None);
            flat = flat_frames
                .as_deref()
                .map(|frames| FlatEdges::new(mesh, frames, &in_space));
            let lengths = flat.as_ref().map_or(&in_space[..], |f| &f.lengths);
            let spacing = budget::Spacing {
                lengths,
                min: (options.method == Method::Wave) as u32,
                mean: options.mean_edge_length,
                containing: flat.as_ref().map(|f| (&in_space[..], &f.refracting[..])),
            };
            let limits = budget::Limits {
                memory: options.memory_limit.or_else(budget::available_memory),
                work: options.work_limit,
            };
            budgeted = budget::check(mesh, options.steiner, spacing, options.method, limits)?;
            let counts = spacing.counts(options.steiner);
            if options.method == Method::Wave {
                reach = lengths.iter().fold(0.0f64, |m, &l| m.max(l));
            }
            SteinerLayout::with_counts(mesh, options.steiner, counts)?
        };
        let (edge_steps, mut setup_tests) =
            match edge_steps(mesh, &metric, &layout, flat_frames.is_some()) {
                Some((steps, tests)) => (Some(steps), tests),
                None => (None, 0),
            };
        // The cost between consecutive nodes of each edge: the cached steps, or the
        // metric asked once per edge (in its first face).
        let steps = match &edge_steps {
            Some(steps) => std::borrow::Cow::Borrowed(steps.as_slice()),
            None => {
                setup_tests += mesh.edge_count() as u64;
                std::borrow::Cow::Owned(first_face_steps(mesh, &metric, &layout))
            }
        };
        let (wires, cost_total, per_length) = checked_costs(mesh, &metric, &layout, &steps)?;
        setup_tests += wires.len() as u64 / 2;
        // Only the tracks engine uses a bucket queue (the baselines keep a heap).
        let (tables, bucket_width) = match options.method {
            Method::Tracks | Method::Wave => {
                let width = bucket_width(&steps);
                let mut tables =
                    TrackTables::new(mesh, &layout, edge_steps.as_deref(), flat_frames.as_deref())?;
                if options.method == Method::Wave {
                    tables = tables.with_vertex_rows(mesh, &layout);
                }
                (Some(Arc::new(tables)), width)
            }
            _ => (None, 1.0),
        };
        let isometric = match (&flat, options.method) {
            (Some(flat), Method::Wave) => flat.isometric_blocks(&layout),
            _ => Vec::new(),
        };
        // The tracks engine keeps its steps in its edge records.
        let edge_steps = edge_steps.filter(|_| tables.is_none());
        Ok(Solver {
            id: SolverId::fresh(),
            mesh,
            metric,
            method: options.method,
            k: match options.method {
                Method::Dijkstra => 0.0,
                _ => options.steiner.k(),
            },
            layout: Arc::new(layout),
            edge_steps,
            setup_tests,
            tables,
            isometric,
            reach,
            bucket_width,
            cost_total,
            per_length,
            extent: {
                let [lo, hi] = bounding_box(mesh.positions().iter().map(|p| p.to_array()));
                glam::DVec3::from(hi).distance(glam::DVec3::from(lo))
            },
            wires,
            setup_seconds: start.elapsed().as_secs_f64(),
            path_workspaces: std::sync::Mutex::default(),
            memory_limit: options.memory_limit,
            budgeted,
        })
    }

    /// This solver under the metric reversed, on the same Steiner points and tables:
    /// the backward side of a path searched from both ends under a directed metric.
    /// Only what depends on the metric's direction is worked out again (the steps
    /// along edges, the wires, the checks); the tables do not depend on it for a
    /// directed metric, which has no cached steps.
    fn reversed(&self) -> Result<Solver<'m, Reversed<&M>>, Error> {
        let start = Instant::now();
        let (mesh, metric) = (self.mesh, Reversed(&self.metric));
        debug_assert!(self.edge_steps.is_none() && self.isometric.is_empty());
        let steps = first_face_steps(mesh, &metric, &self.layout);
        let (wires, cost_total, per_length) = checked_costs(mesh, &metric, &self.layout, &steps)?;
        Ok(Solver {
            id: SolverId::fresh(),
            mesh,
            metric,
            method: self.method,
            k: self.k,
            layout: Arc::clone(&self.layout),
            edge_steps: None,
            setup_tests: (mesh.edge_count() + wires.len() / 2) as u64,
            tables: self.tables.clone(),
            isometric: Vec::new(),
            reach: self.reach,
            bucket_width: bucket_width(&steps),
            cost_total,
            per_length,
            extent: self.extent,
            wires,
            setup_seconds: start.elapsed().as_secs_f64(),
            path_workspaces: std::sync::Mutex::default(),
            memory_limit: self.memory_limit,
            budgeted: self.budgeted,
        })
    }

    /// A workspace for this solver's runs (buffers are sized on first use).
    pub fn workspace(&self) -> Workspace {
        Workspace::default()
    }

    /// The Steiner layout runs use.
    pub fn layout(&self) -> &SteinerLayout {
        &self.layout
    }

    /// The mesh.
    pub fn mesh(&self) -> &'m TriMesh {
        self.mesh
    }

    /// The metric.
    pub fn metric(&self) -> &M {
        &self.metric
    }

    /// The engine that runs: the one asked for, except that the wavefront engine gives
    /// way to the track-pruned one for a metric that is not flat on each face.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Queries on `field` (the distance at any surface point, paths, labels) with this
    /// solver's mesh, metric and layout.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Error, Euclidean, Options, Solver, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let field = solver.solve(&[0])?;
    /// let path = solver.query(&field)?.path(SurfacePoint::Vertex(2))?;
    /// assert!((path.length - 2f64.sqrt()).abs() < 1e-12);
    /// // Another solver, even on the same mesh and metric, refuses the field.
    /// let other = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(2.0))?;
    /// assert!(matches!(other.query(&field), Err(Error::ForeignField)));
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ForeignField`] if another solver computed `field`.
    pub fn query<'a>(&'a self, field: &'a GeodesicField) -> Result<Query<'a, M>, Error> {
        if field.solver() != self.id {
            return Err(Error::ForeignField);
        }
        Ok(Query::new(self.mesh, &self.metric, field.view()))
    }

    /// Queries on the last run in `workspace`, without copying it out (see
    /// [`Solver::query`]).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let mut workspace = solver.workspace();
    /// solver.run(&mut workspace, &[0])?;
    /// let query = solver.query_workspace(&workspace)?;
    /// let path = query.path(SurfacePoint::Vertex(2))?;
    /// assert!((path.length - 2f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoRun`] if the workspace holds no finished run (none yet, or the last
    /// one failed); [`Error::ForeignField`] if another solver made its last run.
    pub fn query_workspace<'a>(&'a self, workspace: &'a Workspace) -> Result<Query<'a, M>, Error> {
        match workspace.solver {
            None => Err(Error::NoRun),
            Some(id) if id != self.id => Err(Error::ForeignField),
            Some(_) => Ok(Query::new(
                self.mesh,
                &self.metric,
                workspace.view(&self.layout),
            )),
        }
    }

    /// Propagates from `sources` (vertex ids, start value 0) into `workspace`.
    ///
    /// # Errors
    /// [`Error::NoSource`], [`Error::SourceOutOfRange`], [`Error::InvalidCost`] if the
    /// metric returns NaN or a negative cost.
    pub fn run(&self, workspace: &mut Workspace, sources: &[u32]) -> Result<Stats, Error> {
        workspace.sources.clear();
        workspace
            .sources
            .extend(sources.iter().map(|&v| Source::new(v)));
        self.execute(workspace, &Stop::NONE)
    }

    /// Propagates from `sources` (any surface points, each with its start value) into
    /// `workspace`, stopping early as `stop` allows.
    ///
    /// A source inside a face (or on an edge) offers every node on the boundary of its
    /// face (of each face around the edge) the metric's cost of the straight segment
    /// to it: the source is one more node of the Steiner graph.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source, Stop, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let mut workspace = solver.workspace();
    /// let centre = SurfacePoint::Face { face: 0, bary: [1.0 / 3.0; 3] };
    /// let sources = [Source::new(centre), Source::new(3).with_start(0.25)];
    /// solver.run_from(&mut workspace, &sources, &Stop::NONE.with_max_distance(0.6))?;
    /// let d = workspace.vertex_distances();
    /// assert!((d[1] - 2f64.sqrt() / 3.0).abs() < 1e-12); // straight from the centroid
    /// assert_eq!(d[3], 0.25);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoSource`]; [`Error::SourceOutOfRange`] for a source vertex that does not
    /// exist; [`Error::InvalidPoint`] for any other source or target that is not a point
    /// of the mesh; [`Error::InvalidValue`] for a start value that is not finite or a
    /// maximum distance that is negative or NaN ([`Stop::check`]); [`Error::InvalidCost`] if the metric returns NaN or a
    /// negative cost.
    pub fn run_from(
        &self,
        workspace: &mut Workspace,
        sources: &[Source],
        stop: &Stop,
    ) -> Result<Stats, Error> {
        workspace.sources.clear();
        workspace.sources.extend_from_slice(sources);
        self.execute(workspace, stop)
    }

    /// Runs from `workspace.sources`.
    fn execute(&self, workspace: &mut Workspace, stop: &Stop) -> Result<Stats, Error> {
        self.execute_side(workspace, stop, None)
    }

    /// Runs from `workspace.sources`; with `both`, as one side of a search from both
    /// ends (its goal replaces the targets', and the meeting ends the run).
    fn execute_side(
        &self,
        workspace: &mut Workspace,
        stop: &Stop,
        both: Option<(Option<Goal>, Side<'_>)>,
    ) -> Result<Stats, Error> {
        let start = Instant::now();
        let mesh = self.mesh;
        workspace.solver = None;
        if workspace.sources.is_empty() {
            return Err(Error::NoSource);
        }
        self.validate_sources(&mut workspace.sources)?;
        let lowest_start = workspace
            .sources
            .iter()
            .map(|s| s.start)
            .fold(f64::INFINITY, f64::min);
        stop.check_from(lowest_start)?;
        workspace.targets.clear();
        for (i, target) in stop.targets.iter().enumerate() {
            let point = target
                .validated(mesh)
                .map_err(|error| Error::InvalidPoint {
                    which: PointRole::Target(i),
                    error,
                })?;
            match (point, self.method) {
                (SurfacePoint::Vertex(v), Method::Tracks | Method::Graph | Method::Dijkstra) => {
                    workspace.targets.push(v)
                }
                (_, Method::Wave) => {
                    // A query on a wave field reads the point's faces and those across
                    // their edges (see `trace::face_field`): all their nodes must be
                    // final for its value to be the full run's.
                    for &f in point.faces(mesh).iter() {
                        for e in mesh.face_edges(f) {
                            for &g in mesh.edge_faces(e) {
                                let nodes = self.layout.face_nodes(mesh, g).map(|(node, _)| node);
                                workspace.targets.extend(nodes);
                            }
                        }
                    }
                }
                _ => {
                    for &f in point.faces(mesh).iter() {
                        let nodes = self.layout.face_nodes(mesh, f).map(|(node, _)| node);
                        workspace.targets.extend(nodes);
                    }
                }
            }
        }
        workspace.targets.sort_unstable();
        workspace.targets.dedup();
        let (goal, meet) = match both {
            Some((goal, side)) => (goal, Some(side)),
            None => (self.goal(&workspace.targets, stop), None),
        };
        if goal.is_some() {
            // Written when a node is first reached, before it is read: never cleared.
            workspace.estimate.resize(self.layout.node_count(), 0.0);
        }

        // Tracks are the tracks engine's alone.
        let instances = match (&self.tables, self.method) {
            (Some(tables), Method::Tracks) => tables.instances,
            _ => 0,
        };
        let waves = match (&self.tables, self.method) {
            (Some(_), Method::Wave) => self.layout.steiner_count(),
            _ => 0,
        };
        workspace.reset(
            mesh.vertex_count(),
            self.layout.node_count(),
            instances,
            waves,
        );
        // Only a run that may stop early can reach little (see `Frontier::records`).
        // (A side of a search from both ends stops early too, and the touched nodes
        // are where the two sides' values are compared.)
        workspace.recorded =
            stop.max_distance < f64::INFINITY || !workspace.targets.is_empty() || meet.is_some();
        let seed_tests = self.seed(workspace)?;
        let reset_seconds = start.elapsed().as_secs_f64();
        let propagate_start = Instant::now();
        let Workspace {
            distance,
            parent,
            parent_face,
            tracks,
            waves,
            estimate,
            touched,
            recorded,
            heap,
            buckets,
            seeds,
            targets,
            sources,
            roots,
            solver,
            method: last_method,
            horizon,
            ..
        } = workspace;
        let search = Frontier {
            mesh,
            metric: &self.metric,
            layout: &self.layout,
            edge_steps: self.edge_steps.as_deref(),
            wires: &self.wires,
            distance,
            parent,
            parent_face,
            touched,
            records: *recorded,
            queue: (),
            max_distance: stop.max_distance,
            goal,
            estimate,
            reach: self.reach,
            targets,
            target_cursor: 0,
            meet,
            pushes: 0,
            settles: 0,
            tests: seed_tests,
            bad_cost: None,
        };
        let outcome = match &self.tables {
            Some(tables) if self.method == Method::Wave => {
                buckets.reset(self.layout.node_count(), self.bucket_width);
                let isometric = &self.isometric;
                search.run(buckets, seeds, |s| {
                    wave::propagate(s, tables, isometric, waves, seeds, sources)
                })
            }
            Some(tables) => {
                buckets.reset(self.layout.node_count(), self.bucket_width);
                search.run(buckets, seeds, |s| {
                    tracks::propagate(s, tables, tracks, seeds)
                })
            }
            None => {
                heap.reset();
                search.run(heap, seeds, graph::propagate)
            }
        };
        if let Some((face, value)) = outcome.bad_cost {
            return Err(Error::InvalidCost {
                metric: self.metric.name().to_string(),
                face,
                value,
            });
        }
        // Keep, per node, the seed that gave it its start value (the first of the
        // least ones, as relaxation took them): paths and labels end there.
        // (Seeds were made in source order, so among equal values the lowest source
        // index came first.)
        seeds.sort_unstable_by(|a, b| {
            a.node
                .cmp(&b.node)
                .then(a.value.total_cmp(&b.value))
                .then(a.source.cmp(&b.source))
        });
        seeds.dedup_by_key(|s| s.node);
        roots.clear();
        roots.extend(seeds.iter().map(|s| Root {
            node: s.node,
            source: s.source,
        }));
        *horizon = Horizon {
            max_distance: stop.max_distance,
            level: outcome.level,
            goal,
        };
        if self.method == Method::Wave && horizon.is_bounded() {
            // The waves of nodes the stop left unreached are not the run's (and only
            // touched nodes have any).
            let vertex_count = self.layout.vertex_count() as usize;
            for &node in touched.iter() {
                let node = node as usize;
                if node >= vertex_count && distance[node].is_infinite() {
                    waves[node - vertex_count] = Wave::NONE;
                }
            }
        }
        *solver = Some(self.id);
        *last_method = Some(self.method);
        Ok(Stats {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            steiner_points: self.layout.steiner_count(),
            k: self.k,
            method: self.method,
            setup_seconds: self.setup_seconds + reset_seconds,
            propagate_seconds: propagate_start.elapsed().as_secs_f64(),
            pushes: outcome.pushes,
            settles: outcome.settles,
            distance_tests: outcome.tests,
            setup_distance_tests: self.setup_tests,
            stopped_early: outcome.stopped_early,
            both_ends: false,
        })
    }

    /// The estimate a run stopping at `targets` (nodes) orders nodes by: the metric's
    /// least cost per unit length times the distance to the box around them; `None`
    /// for a run without targets, a metric that gives no bound, a stop that asks for
    /// no goal direction, targets spread over more than half the mesh's extent, or the
    /// wavefront engine.
    ///
    /// Why not the wavefront engine: its values depend on the order waves arrive in.
    /// A node that improves after it offered keeps its new wave only, and a value it
    /// gave through its old wave can no longer be traced back. Settled by value, such
    /// improvements stay within a bucket; settled by value plus estimate, nodes behind
    /// the front (nearer the sources, farther from the goal) settle after nodes beside
    /// it, and on Spot at k = 2 the traced path of 38 routes in 60 came out longer than
    /// the value at its end (up to 9 %; straightened, within 1e-4 of the plain run's).
    fn goal(&self, targets: &[u32], stop: &Stop) -> Option<Goal> {
        let graph_engine = self.method != Method::Wave;
        if targets.is_empty() || !stop.goal_directed || self.per_length <= 0.0 || !graph_engine {
            return None;
        }
        let positions = targets.iter().map(|&t| self.layout.position(self.mesh, t));
        let [lo, hi] = bounding_box(positions.map(|p| p.to_array())).map(glam::DVec3::from);
        // Targets spread over much of the mesh leave the estimate zero nearly
        // everywhere: it would cost without saving (README, Library: `goal_bench`).
        if (hi - lo).length() > 0.5 * self.extent {
            return None;
        }
        Some(Goal::toward(lo, hi, self.per_length))
    }

    /// Checks the sources against the mesh and puts their points in canonical form.
    fn validate_sources(&self, sources: &mut [Source]) -> Result<(), Error> {
        for (i, source) in sources.iter_mut().enumerate() {
            source.point = source
                .point
                .validated(self.mesh)
                .map_err(|error| match error {
                    PointError::NoSuchVertex { vertex, count } => Error::SourceOutOfRange {
                        vertex: vertex as u64,
                        vertex_count: count,
                    },
                    error => Error::InvalidPoint {
                        which: PointRole::Source(i),
                        error,
                    },
                })?;
            if !source.start.is_finite() {
                return Err(Error::InvalidValue {
                    which: ValueRole::Start { source: i },
                    value: source.start,
                });
            }
            // Values only grow from a start, by at most the mesh's total cost: a start
            // so large that they could overflow would leave nodes silently unreached.
            if !(source.start + self.cost_total).is_finite() {
                return Err(Error::StartTooLarge {
                    index: i,
                    start: source.start,
                    cost_total: self.cost_total,
                });
            }
        }
        Ok(())
    }

    /// Fills `workspace.seeds` from its (valid) sources; returns the metric evaluations.
    fn seed(&self, workspace: &mut Workspace) -> Result<u64, Error> {
        let (mesh, layout) = (self.mesh, &self.layout);
        let mut tests = 0;
        workspace.seeds.clear();
        for (i, source) in workspace.sources.iter().enumerate() {
            let source_index = i as u32;
            if let SurfacePoint::Vertex(v) = source.point {
                workspace.seeds.push(Seed {
                    node: v,
                    face: NONE,
                    value: source.start,
                    source: source_index,
                });
                continue;
            }
            for &f in source.point.faces(mesh).iter() {
                let Some(x) = source.point.in_face(mesh, f) else {
                    continue;
                };
                for (node, p) in layout.face_nodes(mesh, f) {
                    tests += 1;
                    let cost = self.metric.cost(f, &x, &p);
                    if cost.is_nan() || cost < 0.0 {
                        return Err(Error::InvalidCost {
                            metric: self.metric.name().to_string(),
                            face: f,
                            value: cost,
                        });
                    }
                    workspace.seeds.push(Seed {
                        node,
                        face: f,
                        value: source.start + cost,
                        source: source_index,
                    });
                }
            }
        }
        Ok(tests)
    }

    /// One row of distances per source, computed on all cores (rayon; workspaces are
    /// pooled, at most one per worker thread, and reused across sources): row `i` holds
    /// the distance from `sources[i]` to each of `targets`, or to every vertex when
    /// `targets` is `None`. With targets, each row's run stops once its targets are
    /// final ([`Stop::with_targets`]), so near targets cost little.
    ///
    /// # Complexity
    /// One run per source; with targets, each run settles only the nodes closer than
    /// its farthest target.
    ///
    /// # Errors
    /// As [`Solver::run`], plus [`Error::TargetOutOfRange`] for a target that is not a
    /// vertex and [`Error::OutputTooLarge`] when the rows (8 bytes a value) would not
    /// fit [`Options::memory_limit`], by default what the system reports available
    /// (both checked first, before any work).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let rows = solver.distance_rows(&[0, 2], Some(&[1, 3]))?;
    /// assert!((rows[0][0] - 1.0).abs() < 1e-12 && (rows[1][1] - 1.0).abs() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    pub fn distance_rows(
        &self,
        sources: &[u32],
        targets: Option<&[u32]>,
    ) -> Result<Vec<Vec<f64>>, Error> {
        let rows = self.distance_rows_with_stats(sources, targets)?;
        Ok(rows.into_iter().map(|(row, _)| row).collect())
    }

    /// As [`Solver::distance_rows`], with each row's [`Stats`] (whether it stopped
    /// early, how much work it did).
    ///
    /// # Errors
    /// As [`Solver::distance_rows`].
    pub fn distance_rows_with_stats(
        &self,
        sources: &[u32],
        targets: Option<&[u32]>,
    ) -> Result<Vec<(Vec<f64>, Stats)>, Error> {
        use rayon::prelude::*;
        let vertex_count = self.mesh.vertex_count();
        if let Some(&vertex) = targets
            .unwrap_or(&[])
            .iter()
            .find(|&&v| v as usize >= vertex_count)
        {
            return Err(Error::TargetOutOfRange {
                vertex: vertex as u64,
                vertex_count,
            });
        }
        // The rows are kept in memory: refuse before any run what cannot fit.
        let columns = targets.map_or(vertex_count, <[u32]>::len);
        self.check_rows_fit(sources.len(), columns, 8)?;
        let stop = match targets {
            Some(t) => {
                Stop::NONE.with_targets(t.iter().map(|&v| SurfacePoint::Vertex(v)).collect())
            }
            None => Stop::NONE,
        };
        // Workspaces are taken from and returned to a pool, so there are never more
        // than there are worker threads (rayon's map_init may create one per split).
        let pool = std::sync::Mutex::new(Vec::<Workspace>::new());
        let take = || {
            pool.lock()
                .ok()
                .and_then(|mut p| p.pop())
                .unwrap_or_default()
        };
        sources
            .par_iter()
            .map(|&source| {
                let mut ws = take();
                let row = self
                    .run_from(&mut ws, &[Source::new(source)], &stop)
                    .map(|stats| {
                        let d = ws.vertex_distances();
                        let row = match targets {
                            Some(t) => t.iter().map(|&v| d[v as usize]).collect(),
                            None => d.to_vec(),
                        };
                        (row, stats)
                    });
                if let Ok(mut p) = pool.lock() {
                    p.push(ws);
                }
                row
            })
            .collect()
    }

    /// Checks, before any run, that `rows` rows of `columns` values fit in memory at
    /// `bytes_per_value` bytes a value: within [`Options::memory_limit`], by default what
    /// the system reports available. [`Solver::distance_rows`] checks its rows at 8
    /// bytes a value; a caller that copies them into another array (the Python
    /// package's matrix) checks at 16.
    ///
    /// # Errors
    /// [`Error::OutputTooLarge`], with the bytes needed and available.
    pub fn check_rows_fit(
        &self,
        rows: usize,
        columns: usize,
        bytes_per_value: u64,
    ) -> Result<(), Error> {
        let bytes = (rows as u64)
            .saturating_mul(columns as u64)
            .saturating_mul(bytes_per_value);
        match self.memory_limit.or_else(budget::available_memory) {
            Some(available) if bytes > available => Err(Error::OutputTooLarge {
                rows,
                columns,
                bytes,
                available,
            }),
            _ => Ok(()),
        }
    }

    /// For each of `sources` (vertices), the vertices within `max_distance` of it and
    /// their distances, sorted by vertex: one run per source stopped at
    /// `max_distance`, on all cores (rayon), each costing what it reaches. The rows
    /// are kept in memory: their size is not known before the runs, so it is counted
    /// as they finish, and the call stops as soon as they would exceed
    /// [`Options::memory_limit`] (by default what the system reports available).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let rows = solver.local_distance_rows(&[0], 1.2)?;
    /// assert_eq!(rows[0].iter().map(|&(v, _)| v).collect::<Vec<_>>(), [0, 1, 3]);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::run`] (a negative or NaN `max_distance` is refused before any
    /// run), plus [`Error::LocalRowsTooLarge`] when the rows outgrow the memory.
    pub fn local_distance_rows(
        &self,
        sources: &[u32],
        max_distance: f64,
    ) -> Result<Vec<Vec<(u32, f64)>>, Error> {
        use std::sync::atomic::{AtomicU64, Ordering};
        let stop = Stop::NONE.with_max_distance(max_distance);
        stop.check()?;
        let available = self.memory_limit.or_else(budget::available_memory);
        let pair = std::mem::size_of::<(u32, f64)>() as u64;
        let pairs = AtomicU64::new(0);
        sources
            .par_iter()
            .map_init(
                || self.workspace(),
                |workspace, &v| {
                    self.run_from(workspace, &[Source::new(v)], &stop)?;
                    // What the run reached, not a scan of the mesh: with a small radius
                    // that is most of the saving.
                    let mut row: Vec<(u32, f64)> = workspace.reached_vertices().collect();
                    row.sort_unstable_by_key(|&(j, _)| j);
                    let total =
                        pairs.fetch_add(row.len() as u64, Ordering::Relaxed) + row.len() as u64;
                    match available {
                        Some(available) if total.saturating_mul(pair) > available => {
                            Err(Error::LocalRowsTooLarge {
                                max_distance,
                                sources: sources.len(),
                                pairs: total,
                                available,
                            })
                        }
                        _ => Ok(row),
                    }
                },
            )
            .collect()
    }

    /// Propagates from `sources` into a fresh workspace and returns the whole field.
    ///
    /// # Errors
    /// As [`Solver::run`].
    pub fn solve(&self, sources: &[u32]) -> Result<GeodesicField, Error> {
        let sources: Vec<Source> = sources.iter().map(|&v| Source::new(v)).collect();
        self.solve_from(&sources, &Stop::NONE)
    }

    /// Propagates from `sources` (any surface points, with start values) into a fresh
    /// workspace, stopping as `stop` allows, and returns the whole field.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source, Stop, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let source = Source::new("e:0:0.5".parse::<SurfacePoint>()?);
    /// let field = solver.solve_from(&[source], &Stop::NONE)?;
    /// let target = SurfacePoint::Face { face: 1, bary: [0.2, 0.3, 0.5] };
    /// let path = solver.query(&field)?.path(target)?;
    /// assert_eq!(path.points[0], target);
    /// assert!(path.length <= path.traced_length);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::run_from`].
    pub fn solve_from(&self, sources: &[Source], stop: &Stop) -> Result<GeodesicField, Error> {
        let mut ws = self.workspace();
        let stats = self.run_from(&mut ws, sources, stop)?;
        Ok(GeodesicField::new(
            Arc::clone(&self.layout),
            self.id,
            ws.distance,
            ws.parent,
            ws.parent_face,
            ws.sources,
            ws.roots,
            ws.waves,
            ws.horizon,
            stats,
        ))
    }
}

/// Per vertex, its wires: the vertex at the other end and the wire's cost.
type Wires = Csr<(u32, f64)>;

/// The wires' costs, and the run-wide bounds checked against them and the steps
/// along edges: the total cost (`check_cost_range`) and the least cost per unit of
/// length (`check_per_length`).
fn checked_costs<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
) -> Result<(Wires, f64, f64), Error> {
    let wires = wire_costs(mesh, metric)?;
    let cost_total = check_cost_range(metric, layout, steps, &wires)?;
    let per_length = check_per_length(mesh, metric, layout, steps, &wires)?;
    Ok((wires, cost_total, per_length))
}

/// Every face's frame in the metric's flattening ([`flat::flat_frame`]), or `None`
/// unless the metric gives every face's.
fn flat_frames<M: Metric>(mesh: &TriMesh, metric: &M) -> Option<Vec<FaceFrame>> {
    (0..mesh.face_count() as u32)
        .map(|f| flat::flat_frame(metric, f, mesh.frame(f)))
        .collect()
}

/// Each edge's length: in the flattened frames when given (the longest over the faces
/// around it: the same for edges whose faces glue isometrically), else in space.
fn edge_lengths(mesh: &TriMesh, flat_frames: Option<&[FaceFrame]>) -> Vec<f64> {
    let Some(frames) = flat_frames else {
        return (0..mesh.edge_count() as u32)
            .into_par_iter()
            .map(|e| mesh.edge_length(e))
            .collect();
    };
    let mut lengths = vec![0.0f64; mesh.edge_count()];
    for (f, frame) in frames.iter().enumerate() {
        let c = frame.corners();
        for (s, e) in mesh.face_edges(f as u32).into_iter().enumerate() {
            let (a, b) = (c[s], c[(s + 1) % 3]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            lengths[e as usize] = lengths[e as usize].max(l);
        }
    }
    lengths
}

/// The edges' lengths in the faces' flattenings (the wavefront engine's), and which
/// edges refract.
struct FlatEdges {
    /// Per edge, the longest of its lengths in the faces around it; a length that
    /// agrees with the edge's length in space to rounding (`1e-12` relative) is taken
    /// as that one: under a metric that is Euclidean on a part of the mesh, the points
    /// there are then exactly the Steiner graph's (a length a unit in the last place
    /// apart could round the count the other way).
    lengths: Vec<f64>,
    /// Per edge, whether two faces around it give it different lengths (beyond `1e-9`
    /// of it and rounding): waves do not cross it.
    refracting: Vec<bool>,
}

impl FlatEdges {
    fn new(mesh: &TriMesh, frames: &[FaceFrame], in_space: &[f64]) -> FlatEdges {
        // Per edge: its shortest and longest length over the faces around it, and the
        // longest edge of those faces (what the lengths' rounding is relative to).
        let mut range = vec![[f64::INFINITY, 0.0f64, 0.0f64]; mesh.edge_count()];
        for (f, frame) in frames.iter().enumerate() {
            let c = frame.corners();
            let sides = [0, 1, 2].map(|s| {
                let (a, b) = (c[s], c[(s + 1) % 3]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            });
            let longest = sides.iter().fold(0.0f64, |m, &l| m.max(l));
            for (l, e) in sides.into_iter().zip(mesh.face_edges(f as u32)) {
                let r = &mut range[e as usize];
                *r = [r[0].min(l), r[1].max(l), r[2].max(longest)];
            }
        }
        let mut lengths = Vec::with_capacity(range.len());
        let mut refracting = Vec::with_capacity(range.len());
        for (&[shortest, longest, scale], &e) in range.iter().zip(in_space) {
            // Two faces glue where they give the edge one length, to 1e-9 of it, or to
            // rounding of the face's own size: a short edge of a face with a far corner
            // is measured to 1e-16 of that corner's distance, not of its own length.
            refracting.push(longest - shortest > 1e-9 * longest + 1e-12 * scale);
            lengths.push(if shortest > longest || (longest - e).abs() <= 1e-12 * e {
                e
            } else {
                longest
            });
        }
        FlatEdges {
            lengths,
            refracting,
        }
    }

    /// Per edge block of `layout`: whether waves cross it (its faces glue).
    fn isometric_blocks(&self, layout: &SteinerLayout) -> Vec<bool> {
        let mut iso = vec![true; self.refracting.len()];
        for (e, &r) in self.refracting.iter().enumerate() {
            iso[layout.block_of_edge(e as u32) as usize] = !r;
        }
        iso
    }
}

/// The cost between consecutive nodes of each edge in its first face (for a directed
/// metric, in the dearer direction: these bound what a path along edges costs), on all
/// cores.
fn first_face_steps<M: Metric>(mesh: &TriMesh, metric: &M, layout: &SteinerLayout) -> Vec<f64> {
    let directed = !metric.is_symmetric();
    (0..mesh.edge_count() as u32)
        .into_par_iter()
        .map(|e| {
            let f = mesh.edge_faces(e)[0];
            let [a, b] = mesh
                .edge_vertices(e)
                .map(|v| layout.point_in_face(mesh, v, f));
            let mut whole = metric.cost(f, &a, &b);
            if directed {
                whole = whole.max(metric.cost(f, &b, &a));
            }
            whole / (layout.count(e) + 1) as f64
        })
        .collect()
}

/// Refuses a metric whose costs leave the f64 range on this mesh: every distance a run
/// can give is at most the sum of the edges' finite costs (a path along edges), so
/// that sum must be finite. (`+inf` edges are walls, allowed.) Returns the sum.
fn check_cost_range<M: Metric>(
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
    wires: &Csr<(u32, f64)>,
) -> Result<f64, Error> {
    let edges: f64 = steps
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_finite())
        .map(|(e, s)| s * (layout.count(e as u32) + 1) as f64)
        .sum();
    // Each wire is listed from both ends, each way's cost: both count, a bound on its
    // dearer way (which a directed metric may charge).
    let wires: f64 = (0..wires.rows() as u32)
        .flat_map(|v| wires.row(v).iter())
        .map(|&(_, c)| c)
        .filter(|c| c.is_finite())
        .sum();
    let total = edges + wires;
    if total.is_finite() {
        return Ok(total);
    }
    Err(Error::CostOverflow {
        metric: metric.name().to_string(),
    })
}

/// The metric's [`min_cost_per_length`](Metric::min_cost_per_length), checked against
/// every edge as the solver charges a step along it (`steps`: the cheapest face for a
/// norm, else the first face, the dearer way for a directed metric) and every wire
/// both ways, and shaded by 1e-9 of itself so that rounding never makes an estimate
/// exceed what is left. 0 when the metric gives no positive finite bound.
///
/// An edge's cost and its length in space are each computed with a rounding error
/// relative to the coordinates around it, not to the edge: a short edge of a face with
/// a far vertex (multi-scale meshes) can cost a part in 10⁶ less than its length by
/// rounding alone. Such a shortfall, within [`rounding_allowance`], is no broken
/// bound: the bound returned is lowered to the cheapest cost per unit found, so that
/// estimates stay below every charge.
///
/// # Errors
/// [`Error::CostBelowBound`], [`Error::WireBelowBound`].
fn check_per_length<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
    wires: &Csr<(u32, f64)>,
) -> Result<f64, Error> {
    let per_length = metric.min_cost_per_length();
    if !(per_length > 0.0 && per_length.is_finite()) {
        return Ok(0.0);
    }
    let tolerance = 1.0 - 1e-9;
    let mut bound = per_length * tolerance;
    // Each edge's cost and length: the first edge below the bound by more than
    // rounding, on all cores, and the cheapest cost per unit among the others.
    let edges = (0..steps.len() as u32).into_par_iter().map(|e| {
        let length = mesh.edge_length(e);
        let cost = steps[e as usize] * (layout.count(e) + 1) as f64;
        // The allowance is only worked out for an edge below the bound.
        let short = |allowance: f64| cost < per_length * (length - allowance) * tolerance;
        if short(0.0)
            && short(rounding_allowance(
                mesh,
                mesh.edge_faces(e),
                mesh.edge_vertices(e),
            ))
        {
            Err((e, length, cost))
        } else {
            Ok(if length > 0.0 {
                cost / length
            } else {
                f64::INFINITY
            })
        }
    });
    match edges.try_reduce(|| f64::INFINITY, |a, b| Ok(a.min(b))) {
        Ok(cheapest) => bound = bound.min(cheapest),
        Err((e, length, cost)) => {
            return Err(Error::CostBelowBound {
                metric: metric.name().to_string(),
                per_length,
                edge: e,
                length,
                cost,
                per_unit: cost / length,
            })
        }
    }
    for a in 0..wires.rows() as u32 {
        for &(b, cost) in wires.row(a) {
            let length = mesh.position(a).distance(mesh.position(b));
            let short = |allowance: f64| cost < per_length * (length - allowance) * tolerance;
            if short(0.0) && short(rounding_allowance(mesh, &[], [a, b])) {
                return Err(Error::WireBelowBound {
                    metric: metric.name().to_string(),
                    per_length,
                    wire: [a, b],
                    length,
                    cost,
                });
            }
            if length > 0.0 {
                bound = bound.min(cost / length);
            }
        }
    }
    Ok(bound)
}

/// How much shorter than its length an edge (or wire) between `ends` may come out by
/// rounding alone where it is measured in the faces `faces`: 1e-13 of the largest
/// coordinate or edge there (a few hundred units in the last place of the numbers the
/// length is computed from; measured: 1.1e-10 on a face with a vertex 6e5 away).
fn rounding_allowance(mesh: &TriMesh, faces: &[u32], ends: [u32; 2]) -> f64 {
    let corners = faces
        .iter()
        .flat_map(|&f| mesh.triangles()[f as usize])
        .chain(ends);
    let mut scale = 0.0f64;
    let (lo, hi) = corners.fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), v| {
            let p = mesh.position(v);
            scale = scale.max(p.abs().max_element());
            (lo.min(p), hi.max(p))
        },
    );
    1e-13 * scale.max((hi - lo).max_element())
}

/// The metric's cost of every wire of `mesh`, listed from both ends.
///
/// # Errors
/// [`Error::InvalidWireCost`] for a NaN or negative cost.
fn wire_costs<M: Metric>(mesh: &TriMesh, metric: &M) -> Result<Csr<(u32, f64)>, Error> {
    let directed = !metric.is_symmetric();
    let mut costs = Vec::new();
    for [a, b] in mesh.wires() {
        let length = mesh.position(a).distance(mesh.position(b));
        let check = |[a, b]: [u32; 2]| {
            let cost = metric.wire_cost(a, b, length);
            if cost.is_nan() || cost < 0.0 {
                return Err(Error::InvalidWireCost {
                    metric: metric.name().to_string(),
                    wire: [a, b],
                    value: cost,
                });
            }
            Ok(cost)
        };
        let forward = check([a, b])?;
        // From b to a: the same, unless the metric is directed.
        let backward = if directed { check([b, a])? } else { forward };
        costs.push(([a, b], forward, backward));
    }
    Ok(Csr::from_pairs(
        mesh.vertex_count(),
        costs
            .iter()
            .flat_map(|&([a, b], forward, backward)| [(a, (b, forward)), (b, (a, backward))]),
    ))
}

impl<M: Metric> Solver<'_, M> {
    /// The straightened path from `target` to the nearest of `sources`, in one call: a
    /// run that stops once the target's value is final, then [`Query::path`]; from one
    /// source, a search from both ends at once where it can ([`Stop::both_ends`]).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let path = solver.shortest_path(&[Source::new(1)], SurfacePoint::Vertex(3))?;
    /// assert!((path.length - 2f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::run_from`] and [`Query::path`] ([`Error::Unreachable`] when no source
    /// reaches the target).
    pub fn shortest_path(
        &self,
        sources: &[Source],
        target: SurfacePoint,
    ) -> Result<crate::GeodesicPath, Error> {
        Ok(self.shortest_path_with(sources, target, &Stop::NONE)?.0)
    }

    /// As [`Solver::shortest_path`], stopping as `stop` says (its maximum distance: a
    /// target farther is [`Error::Unreachable`]; its targets are replaced by `target`),
    /// with the run's counters.
    ///
    /// The solver keeps the (up to two) workspaces a path query ran in for the next
    /// one, which then clears only the nodes the last one touched (and the tracks
    /// engine's track table, whole) instead of allocating buffers the size of the mesh
    /// (memory: two workspaces' buffers, held as long as the solver).
    ///
    /// From one source, with [`Stop::both_ends`] (the default), a Steiner-graph engine
    /// and two threads or more in rayon's pool, the search runs from both ends at once
    /// (`Stats::both_ends`; a directed metric's backward side on a reversed-metric
    /// solver built for the query): the path's traced cost is the Steiner graph's, as a
    /// one-ended run's, to rounding.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Method, Options, Solver, Source, Stop, SurfacePoint};
    /// // A strip of 20 unit squares.
    /// let positions = (0..42).map(|i| [(i / 2) as f64, (i % 2) as f64, 0.0]).collect();
    /// let faces = (0..20u32).flat_map(|i| [[2 * i, 2 * i + 2, 2 * i + 3], [2 * i, 2 * i + 3, 2 * i + 1]]).collect();
    /// let mesh = TriMesh::new(positions, faces)?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_method(Method::Tracks))?;
    /// let (both, _) = solver.shortest_path_with(&[Source::new(0)], SurfacePoint::Vertex(41), &Stop::NONE)?;
    /// let one_end = Stop::NONE.with_both_ends(false);
    /// let (one, _) = solver.shortest_path_with(&[Source::new(0)], SurfacePoint::Vertex(41), &one_end)?;
    /// assert!((both.traced_length - one.traced_length).abs() < 1e-9);
    /// assert!((both.length - 401f64.sqrt()).abs() < 1e-6); // straightened: the diagonal
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::shortest_path`].
    pub fn shortest_path_with(
        &self,
        sources: &[Source],
        target: SurfacePoint,
        stop: &Stop,
    ) -> Result<(crate::GeodesicPath, Stats), Error> {
        let both_ends = stop.both_ends
            && stop.goal_directed
            && sources.len() == 1
            && self.method != Method::Wave
            && rayon::current_num_threads() >= 2
            && self.second_run_fits();
        if both_ends {
            let mut workspaces = [self.path_workspace(), self.path_workspace()];
            let (source, max) = (sources[0], stop.max_distance);
            let found = if self.metric.is_symmetric() {
                self.path_from_both_ends(self, &mut workspaces, source, target, max)
            } else {
                // The backward side travels against the metric: the reversed metric's
                // solver, on the same Steiner points and tables.
                self.reversed().and_then(|back| {
                    let (path, mut stats) =
                        self.path_from_both_ends(&back, &mut workspaces, source, target, max)?;
                    // (Its setup is this query's.)
                    stats.setup_seconds += back.setup_seconds;
                    Ok((path, stats))
                })
            };
            for workspace in workspaces {
                self.keep_path_workspace(workspace);
            }
            return found;
        }
        let mut workspace = self.path_workspace();
        let found = self
            .run_from(
                &mut workspace,
                sources,
                &stop.clone().with_targets(vec![target]),
            )
            .and_then(|stats| {
                let path = self.query_workspace(&workspace)?.path(target)?;
                Ok((path, stats))
            });
        self.keep_path_workspace(workspace);
        found
    }

    /// Whether a second run's buffers fit the memory budget (see
    /// [`Options::memory_limit`]): a search from both ends needs them.
    fn second_run_fits(&self) -> bool {
        let instances = self.tables.as_ref().map_or(0, |t| t.instances);
        let extra = budget::run_bytes(self.layout.node_count(), instances);
        budget::second_run_fits(extra, self.budgeted, self.memory_limit)
    }

    /// A workspace for a path query: one a path query ran in before, or a new one.
    fn path_workspace(&self) -> Workspace {
        let kept = self
            .path_workspaces
            .lock()
            .map(|mut kept| kept.pop())
            .unwrap_or_default();
        kept.unwrap_or_else(|| self.workspace())
    }

    /// Keeps `workspace` for the next path query (two at most).
    fn keep_path_workspace(&self, workspace: Workspace) {
        if let Ok(mut kept) = self.path_workspaces.lock() {
            if kept.len() < 2 {
                kept.push(workspace);
            }
        }
    }

    /// The path from `target` to `source` no costlier than `max_distance`, searched
    /// from both ends at once on two threads (see `meet`): forward with this solver,
    /// backward with `back` (this solver for a symmetric metric, else the reversed
    /// metric's, on the same Steiner points).
    fn path_from_both_ends<B: Metric>(
        &self,
        back: &Solver<'_, B>,
        [forward, backward]: &mut [Workspace; 2],
        source: Source,
        target: SurfacePoint,
        max_distance: f64,
    ) -> Result<(crate::GeodesicPath, Stats), Error> {
        let (mesh, layout) = (self.mesh, &*self.layout);
        let target = target
            .validated(mesh)
            .map_err(|error| Error::InvalidPoint {
                which: PointRole::Target(0),
                error,
            })?;
        let mut sources = [source];
        self.validate_sources(&mut sources)?;
        let [source] = sources;
        let (from, to) = (source.point.position(mesh), target.position(mesh));
        let (forward_goal, backward_goal) = if self.per_length > 0.0 {
            let forward = Goal::between(from, to, self.per_length);
            (
                Some(forward),
                Some(Goal::between(to, from, self.per_length)),
            )
        } else {
            (None, None)
        };
        // (What the two sides' estimates add up to; 0 without estimates.)
        let offset = forward_goal
            .and_then(|g| g.away)
            .map_or(0.0, |(_, offset)| offset);
        let round = WORK_PER_SETTLE
            * (layout.node_count() / ROUNDS_PER_MESH).clamp(ROUND_LEAST, ROUND_MOST) as u64;
        let meeting = Meeting::new(offset, round);
        forward.sources.clear();
        forward.sources.push(source);
        backward.sources.clear();
        backward.sources.push(Source::new(target));
        let stop = Stop::NONE.with_max_distance(max_distance);
        let (forward_stats, backward_stats) = std::thread::scope(|scope| {
            let back = scope.spawn(|| {
                back.execute_side(backward, &stop, Some((backward_goal, meeting.side(1))))
            });
            let ahead = self.execute_side(forward, &stop, Some((forward_goal, meeting.side(0))));
            let back = back
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (ahead, back)
        });
        let (forward_stats, backward_stats) = (forward_stats?, backward_stats?);
        // Where the two sides' values add up to least: the path goes through it (see
        // `meet`). In the order the forward side reached them, the first such node.
        let (mut cost, mut meet) = (f64::INFINITY, NONE);
        for &node in &forward.touched {
            let sum = forward.distance[node as usize] + backward.distance[node as usize];
            if sum < cost {
                (cost, meet) = (sum, node);
            }
        }
        // Ends in one face: also the straight segment between them there, which is
        // no path through nodes (as a query at the target takes it from a source in
        // its face).
        let direct = target
            .faces(mesh)
            .iter()
            .filter(|&&f| source.point.bary_in(mesh, f).is_some())
            .map(|&f| {
                let cost = crate::trace::segment_cost(mesh, &self.metric, f, source.point, target);
                (source.start + cost, f)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let stats = Stats {
            setup_seconds: forward_stats.setup_seconds,
            // (Each side's includes its waits for the other: the longer is the search's.)
            propagate_seconds: forward_stats
                .propagate_seconds
                .max(backward_stats.propagate_seconds),
            pushes: forward_stats.pushes + backward_stats.pushes,
            settles: forward_stats.settles + backward_stats.settles,
            distance_tests: forward_stats.distance_tests + backward_stats.distance_tests,
            stopped_early: true,
            both_ends: true,
            ..forward_stats
        };
        if let Some((straight, f)) = direct.filter(|&(straight, _)| straight < cost) {
            if straight > max_distance {
                return Err(Error::Unreachable { point: target });
            }
            let path =
                crate::trace::finish(mesh, &self.metric, vec![target, source.point], vec![f], 0);
            return Ok((path, stats));
        }
        if meet == NONE || cost > max_distance {
            return Err(Error::Unreachable { point: target });
        }
        // From the target to the meeting node along the backward side's parents, then
        // on to the source along the forward side's.
        let cycle = || Error::ParentCycle { point: target };
        let (mut points, mut faces, _) =
            chain(&back.query_workspace(backward)?, meet).ok_or_else(cycle)?;
        let (ahead_points, ahead_faces, source) =
            chain(&self.query_workspace(forward)?, meet).ok_or_else(cycle)?;
        points.reverse();
        faces.reverse();
        points.extend_from_slice(&ahead_points[1..]);
        faces.extend(ahead_faces);
        let mut path = crate::trace::finish(mesh, &self.metric, points, faces, source);
        crate::trace::straighten(&mut path, mesh, &self.metric);
        Ok((path, stats))
    }
}

/// The points and faces from `node` back to its source along `query`'s parents, and
/// the source (`None` on a cycle).
fn chain<M: Metric>(
    query: &crate::trace::Query<'_, M>,
    node: u32,
) -> Option<(Vec<SurfacePoint>, Vec<u32>, u32)> {
    let mut points = vec![query.layout().surface_point(node)];
    let mut faces = Vec::new();
    let source = query.follow_parents(node, &mut points, &mut faces)?;
    Some((points, faces, source))
}

/// About how many nodes each side of a search from both ends settles in a round (see
/// `meet`): the mesh's nodes over this, within [`ROUND_LEAST`] and [`ROUND_MOST`].
/// The same work on both sides ([`WORK_PER_SETTLE`]), so that neither waits long for
/// the other; enough that the rounds' rendezvous cost nothing next to their work, few
/// enough that a side settles little beyond where the search could have stopped.
const ROUNDS_PER_MESH: usize = 256;
/// See [`ROUNDS_PER_MESH`].
const ROUND_LEAST: usize = 32;
/// See [`ROUNDS_PER_MESH`]: on the 1000 × 1000 terrain bench's corner route (1.9 M
/// settles a side) 111 rounds. A side still waits for the other: with rounds of equal
/// settles, `perf record` on the CLI's `slope:4` corner route put 10 % of the samples
/// in `sched_yield`, the backward side waiting 0.2–0.3 s and the forward side
/// 0.01–0.06 s (scratch timers); counting pushes too, each waits 0.06–0.15 s, and the
/// propagation is about 5 % faster (1.27–1.39 s against 1.36–1.45 s, five runs of
/// `geotracks terrain terrain1000.asc --from 499.5,499.5 --to 9490.5,9290.7 --cost
/// slope:4 -v` alternating 7819a5e with b9a7ea3). Balancing by metric evaluations did
/// no better than by settles.
const ROUND_MOST: usize = 1 << 14;
/// A round's work is counted in settles plus pushes (see `meet`), a settle making about
/// two pushes: rounds of this many times the nodes above.
const WORK_PER_SETTLE: u64 = 3;

/// The bucket queue's width: a low quantile of the cost between consecutive nodes on an
/// edge. Nodes in one bucket are settled in no particular order, so a bucket much wider
/// than the local spacing of nodes makes many nodes settle early and propagate again;
/// the low quantile keeps buckets narrow where costs are low (low density, short edges).
/// (The queue bounds the work whatever the width; the width only sets the speed.)
fn bucket_width(steps: &[f64]) -> f64 {
    let mut steps: Vec<f64> = steps
        .iter()
        .copied()
        .filter(|s| s.is_finite() && *s > 0.0)
        .collect();
    if steps.is_empty() {
        return 1.0;
    }
    let at = steps.len() / 10;
    let (_, width, _) = steps.select_nth_unstable_by(at, f64::total_cmp);
    *width
}
