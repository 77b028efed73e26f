//! [`FieldData`]: what a propagation leaves, as plain data: per node its value and
//! parent, the sources, and the run's [`Stats`]; and the small types a run and its
//! queries share (the goal estimate, the horizon of an early stop, the waves).
//!
//! The data knows nothing of the engine or of paths: the [`Field`](crate::Field) that
//! holds it with its solver answers the queries that need the mesh and the metric.

use super::WindowField;
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::options::Method;
use crate::steiner::SteinerLayout;
use crate::surface::Source;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// Counters and timings of one run.
///
/// `distance_tests` counts every metric evaluation made during propagation, whatever the
/// method, so it measures the work done independently of the machine.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Stats {
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Faces of the mesh.
    pub faces: usize,
    /// Steiner points laid out (0 for Dijkstra on edges).
    pub steiner_points: usize,
    /// The requested mean number of Steiner points per edge.
    pub k: f64,
    /// The method that ran.
    pub method: Method,
    /// Seconds spent laying out Steiner points and allocating state.
    pub setup_seconds: f64,
    /// Seconds spent propagating.
    pub propagate_seconds: f64,
    /// Queue insertions: a node is queued again when it improves into another bucket
    /// (or improves at all, for the heap), so this grows with the improvements.
    pub pushes: u64,
    /// Nodes taken from the queue and settled. At most `3 · nodes` plus a small slack
    /// per bucket for the tracks engine whatever the costs (see the bucket queue), and
    /// once per reached node for the exact heap of the graph and Dijkstra.
    pub settles: u64,
    /// Metric evaluations made while propagating.
    pub distance_tests: u64,
    /// Metric evaluations made once by the solver's setup (the per-edge step costs of
    /// a norm metric; for other metrics, one per edge to size the tracks engine's
    /// bucket queue), shared by all its runs.
    pub setup_distance_tests: u64,
    /// The run ended at its targets, before the queue ran out (see [`crate::Stop`]).
    pub stopped_early: bool,
    /// Windows the exact engine made (0 for the other engines).
    pub windows_created: u64,
    /// Windows the exact engine carried across faces, which the field keeps (0 for
    /// the other engines).
    pub windows_kept: u64,
    /// The run was a path's search from both ends ([`crate::Stop::both_ends`]): the
    /// counters are the two sides' sums, `propagate_seconds` the longer side's (waits
    /// for the other included), `setup_seconds` the forward side's (and the reversed
    /// metric's setup, for a directed metric).
    pub both_ends: bool,
}

/// A goal-directed run's estimate of what is left to a node (A*): `per_length` times
/// its straight-line distance to the box around the targets. No path from the node to
/// a target costs less (`per_length` is the metric's
/// [`min_cost_per_length`](geotracks_metrics::Metric::min_cost_per_length)), and the
/// estimate drops by at most what a step costs (the distance to a convex set is
/// 1-Lipschitz): ordered by value plus estimate, nodes still settle with costs ≥ 0.
///
/// One side of a search between two points from both ends (`away`: the other
/// side's target, this side's source) takes the *average* of the two ends' estimates
/// instead, `(h_to(p) − h_from(p) + offset) / 2` with `offset = per_length · |to −
/// from|`: the two sides' estimates then add up to `offset` everywhere, so that a
/// node's two keys add up to the cost of the path through it plus `offset`, and each
/// side settles about half of what one A* would (Ikeda et al. 1994; Goldberg and
/// Harrelson 2005). It is still ≥ 0 and at most `h_to` (triangle inequality), and
/// drops by at most what a step costs (each half is half as steep), so the engine
/// treats it as any estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Goal {
    /// The box around the targets.
    pub lo: glam::DVec3,
    pub hi: glam::DVec3,
    pub per_length: f64,
    /// For one side of a search from both ends (the box is then its target, a
    /// point): its source, and `per_length · |to − from|`, which the two sides'
    /// estimates add up to.
    pub away: Option<(glam::DVec3, f64)>,
}

impl Goal {
    /// The estimate towards the targets at `[lo, hi]`, with `per_length`.
    pub fn toward(lo: glam::DVec3, hi: glam::DVec3, per_length: f64) -> Goal {
        Goal {
            lo,
            hi,
            per_length,
            away: None,
        }
    }

    /// One side of a search from both ends: from `from`, towards `to`.
    pub fn between(from: glam::DVec3, to: glam::DVec3, per_length: f64) -> Goal {
        Goal {
            lo: to,
            hi: to,
            per_length,
            away: Some((from, per_length * from.distance(to))),
        }
    }

    /// The estimate at world position `p`.
    #[inline]
    pub fn estimate(&self, p: glam::DVec3) -> f64 {
        let to = self.per_length * p.distance(p.clamp(self.lo, self.hi));
        match self.away {
            None => to,
            Some((source, offset)) => {
                let from = self.per_length * p.distance(source);
                // (≥ 0 but for rounding: the clamp keeps it an estimate.)
                (0.5 * (to - from + offset)).max(0.0)
            }
        }
    }

    /// The most the estimate reaches on face `f`: at a corner for the distance to a
    /// box (convex); for the average of two ends' (not convex), at most a corner's
    /// plus `per_length` times the face's longest edge (it is `per_length`-Lipschitz).
    fn max_in_face<T: Topology>(&self, mesh: &T, f: u32) -> f64 {
        let corners = mesh.face_vertices(f).map(|v| mesh.position(v));
        let at = corners.map(|p| self.estimate(p));
        let most = at[0].max(at[1]).max(at[2]);
        match self.away {
            None => most,
            Some(_) => {
                let longest = corners[0]
                    .distance(corners[1])
                    .max(corners[1].distance(corners[2]))
                    .max(corners[2].distance(corners[0]));
                most + self.per_length * longest
            }
        }
    }
}

/// Where an early stop left a field: every node whose value in a full run is below
/// [`Horizon::in_face`] of its faces has that value here, and every node the stop left
/// unreached would have at least that.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Horizon {
    /// The run's [`Stop::max_distance`](crate::Stop::max_distance): a point farther is
    /// unreached, as a node is.
    pub max_distance: f64,
    /// The queue's level when the run stopped at its targets, less the engine's reach
    /// (`inf` when it did not): a node left queued or unreached has a key at least
    /// this.
    pub level: f64,
    /// The estimate a goal-directed run added to values to make keys.
    pub goal: Option<Goal>,
}

impl Default for Horizon {
    fn default() -> Self {
        Horizon::NONE
    }
}

impl Horizon {
    /// A full run's: nothing left unreached that could be reached.
    pub const NONE: Horizon = Horizon {
        max_distance: f64::INFINITY,
        level: f64::INFINITY,
        goal: None,
    };

    /// Whether the run stopped early (some nodes may be unreached).
    #[inline]
    pub fn is_bounded(&self) -> bool {
        self.max_distance.min(self.level) < f64::INFINITY
    }

    /// The horizon of the nodes of face `f`: a key at least `level` (or beyond the
    /// maximum distance, which a goal-directed run cuts keys at) is a value at least
    /// that less the estimate's most on the face (see `Goal::max_in_face`).
    pub fn in_face<T: Topology>(&self, mesh: &T, f: u32) -> f64 {
        let limit = self.max_distance.min(self.level);
        let estimate = match self.goal {
            Some(goal) if limit < f64::INFINITY => goal.max_in_face(mesh, f),
            _ => 0.0,
        };
        limit - estimate
    }
}

/// The identity of the [`Solver`](crate::Solver) that computed a field: unique per
/// `Solver::new` in a process, so a field can be matched with its mesh, metric and
/// layout without comparing them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct SolverId(u64);

impl SolverId {
    /// A fresh id, never handed out before in this process.
    pub(crate) fn fresh() -> SolverId {
        static NEXT: AtomicU64 = AtomicU64::new(0);
        SolverId(NEXT.fetch_add(1, Ordering::Relaxed))
    }
}

/// A node that a source reached directly (not through a parent), and which source:
/// where paths and labels end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Root {
    /// The node.
    pub node: u32,
    /// Its source, as an index into the run's sources.
    pub source: u32,
}

/// A distance field over a mesh's nodes (vertices and Steiner points), with the parent of
/// each node for tracing paths back to a source: plain data (values at vertices and
/// nodes, parents, sources and the run's [`Stats`]), without its solver.
///
/// [`Field::into_data`](crate::Field::into_data) makes one, to keep or send;
/// [`Solver::attach`](crate::Solver::attach) gives it back its queries (the distance at
/// any surface point, paths, isolines, ...), on the solver that computed it.
#[derive(Clone, Debug)]
pub struct FieldData {
    layout: Arc<SteinerLayout>,
    solver: SolverId,
    distance: Vec<f64>,
    parent: Vec<u32>,
    parent_face: Vec<u32>,
    sources: Vec<Source>,
    roots: Vec<Root>,
    /// Per Steiner node, the wave it carries (wavefront engine; empty otherwise).
    waves: Vec<Wave>,
    /// The exact engine's windows and vertex origins (empty otherwise).
    windows: WindowField,
    /// See [`FieldView::horizon`].
    horizon: Horizon,
    stats: Stats,
}

/// The per-node state of a finished run, borrowed: what [`FieldData`] owns and a
/// [`Workspace`](crate::Workspace) holds after a run.
#[derive(Clone, Copy, Debug)]
pub struct FieldView<'a> {
    pub(crate) layout: &'a SteinerLayout,
    pub(crate) distance: &'a [f64],
    pub(crate) parent: &'a [u32],
    pub(crate) parent_face: &'a [u32],
    pub(crate) sources: &'a [Source],
    /// Per node that a source reached directly, its source, sorted by node.
    pub(crate) roots: &'a [Root],
    /// Per Steiner node, the wave it carries (empty unless the wavefront engine ran).
    pub(crate) waves: &'a [Wave],
    /// The exact engine's windows (empty unless it ran).
    pub(crate) windows: &'a WindowField,
    /// The engine that ran.
    pub(crate) method: Method,
    /// Where an early stop left the field: below it every value is the full run's,
    /// beyond it nodes may be unreached; it holds the run's maximum distance.
    pub(crate) horizon: Horizon,
}

impl<'a> FieldView<'a> {
    /// The source (index into the run's sources) that gave a root node its value.
    pub(crate) fn root_source(&self, node: u32) -> Option<u32> {
        let at = self.roots.binary_search_by_key(&node, |r| r.node).ok()?;
        Some(self.roots[at].source)
    }
}

impl FieldData {
    /// Assembles a field from per-node state (used by the solver).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        layout: Arc<SteinerLayout>,
        solver: SolverId,
        distance: Vec<f64>,
        parent: Vec<u32>,
        parent_face: Vec<u32>,
        sources: Vec<Source>,
        roots: Vec<Root>,
        waves: Vec<Wave>,
        windows: WindowField,
        horizon: Horizon,
        stats: Stats,
    ) -> FieldData {
        debug_assert_eq!(distance.len(), layout.node_count());
        FieldData {
            layout,
            solver,
            distance,
            parent,
            parent_face,
            sources,
            roots,
            waves,
            windows,
            horizon,
            stats,
        }
    }

    /// The solver that computed the field.
    pub(crate) fn solver(&self) -> SolverId {
        self.solver
    }

    /// The field's state, borrowed.
    pub(crate) fn view(&self) -> FieldView<'_> {
        FieldView {
            layout: &self.layout,
            distance: &self.distance,
            parent: &self.parent,
            parent_face: &self.parent_face,
            sources: &self.sources,
            roots: &self.roots,
            waves: &self.waves,
            windows: &self.windows,
            method: self.stats.method,
            horizon: self.horizon,
        }
    }

    /// The sources of the run, validated (in canonical form).
    pub fn sources(&self) -> &[Source] {
        &self.sources
    }

    /// Distance at every vertex, in vertex order; `f64::INFINITY` where unreachable.
    pub fn vertex_distances(&self) -> &[f64] {
        &self.distance[..self.layout.vertex_count() as usize]
    }

    /// Distance at vertex `v`.
    ///
    /// # Panics
    /// If `v` is not a vertex of the mesh.
    pub fn distance(&self, v: u32) -> f64 {
        assert!(v < self.layout.vertex_count(), "vertex {v} out of range");
        self.distance[v as usize]
    }

    /// Distance at every node (vertices first, then Steiner points; see
    /// [`SteinerLayout`]).
    pub fn node_distances(&self) -> &[f64] {
        &self.distance
    }

    /// The node and face through which `node` got its distance; `None` for a source or
    /// an unreached node. The face is [`NONE`] when the parent lies on the same edge.
    pub fn parent(&self, node: u32) -> Option<(u32, u32)> {
        let p = *self.parent.get(node as usize)?;
        (p != NONE).then(|| (p, self.parent_face[node as usize]))
    }

    /// How many vertices no source reaches (they lie on another component).
    pub fn unreachable_vertices(&self) -> usize {
        self.vertex_distances()
            .iter()
            .filter(|d| d.is_infinite())
            .count()
    }

    /// The Steiner layout the field was computed on.
    pub fn layout(&self) -> &SteinerLayout {
        &self.layout
    }

    /// Counters and timings of the run.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }
}

/// The wave a Steiner node carries, in the frame of its edge: `x` along the edge from
/// its lower vertex, `y` across it towards the interior of the face the wave came from
/// (the node's parent face; `NONE` for a source on the edge's own line, `y = 0`, valid
/// in every face around it). Lengths are in the metric. 32 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Wave {
    /// The virtual source.
    pub sx: f64,
    pub sy: f64,
    /// The path length up to the source.
    pub sigma: f64,
    /// The window, as fractions of the edge's length from its lower vertex.
    pub w0: f32,
    pub w1: f32,
}

impl Wave {
    /// No wave (vertices, unreached nodes).
    pub const NONE: Wave = Wave {
        sx: 0.0,
        sy: 0.0,
        sigma: f64::INFINITY,
        w0: 1.0,
        w1: 0.0,
    };

    pub fn is_some(&self) -> bool {
        self.w0 <= self.w1
    }
}
