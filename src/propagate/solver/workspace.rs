//! [`Workspace`]: the buffers one run fills, reused by the next.

use super::Solver;
use crate::field::Wave;
use crate::field::{FieldData, FieldView, Horizon, Origin, Root, Stats, WindowField};
use crate::mesh::NONE;
use crate::options::Method;
use crate::propagate::frontier::Seed;
use crate::propagate::queue::{BucketQueue, HeapQueue};
use crate::propagate::tracks::Track;
use crate::propagate::windows::ExactBuffers;
use crate::steiner::SteinerLayout;
use crate::surface::Source;
use std::sync::Arc;

/// The per-run buffers of a [`Solver`]: per-node distances and parents, per-instance
/// tracks and the queue. After a run it holds that run's result, which
/// [`Solver::run`] returns as a [`Field`](crate::Field) borrowing it.
#[derive(Default)]
pub struct Workspace {
    pub(crate) vertex_count: usize,
    pub(crate) distance: Vec<f64>,
    pub(crate) parent: Vec<u32>,
    pub(crate) parent_face: Vec<u32>,
    pub(in crate::propagate) tracks: Vec<Track>,
    /// Per Steiner node, the wave it carries (wavefront engine).
    pub(crate) waves: Vec<Wave>,
    /// Per node, its goal estimate in a goal-directed run (see `Frontier::estimate`).
    pub(crate) estimate: Vec<f64>,
    /// The nodes the last run touched (see `Frontier::touched`), if it recorded them.
    pub(crate) touched: Vec<u32>,
    /// Whether `touched` lists every node the last run set (else it is empty and the
    /// next reset clears everything).
    pub(crate) recorded: bool,
    pub(in crate::propagate) heap: HeapQueue,
    pub(in crate::propagate) buckets: BucketQueue,
    /// The last run's sources, validated.
    pub(crate) sources: Vec<Source>,
    /// The sources' offers to nodes; after a run, one per node that a source reached
    /// directly, sorted by node (the *roots* paths end at).
    pub(in crate::propagate) seeds: Vec<Seed>,
    /// Nodes whose values decide when the last run could stop.
    pub(crate) targets: Vec<u32>,
    /// After a run, per node that a source reached directly, its source (from `seeds`).
    pub(crate) roots: Vec<Root>,
    /// The last run's horizon (see [`FieldView::horizon`]).
    pub(crate) horizon: Horizon,
    /// The last run's counters.
    pub(crate) stats: Option<Stats>,
    /// The exact engine's windows and vertex origins (see [`WindowField`]).
    pub(crate) exact: WindowField,
    /// The exact engine's heap and per-vertex flags.
    pub(in crate::propagate) exact_buffers: ExactBuffers,
    /// Whether the runs in this workspace need only the values at vertices (as
    /// [`Solver::vertex_values`] and the many-source rows do): the exact engine then
    /// forgets each window once carried, and holds only the wavefront's, where a field
    /// keeps every window for its queries. Never set for a workspace a field is read
    /// from.
    pub(crate) values_only: bool,
}

impl Workspace {
    /// A workspace for runs that need only the values at vertices.
    pub(crate) fn values_only() -> Workspace {
        Workspace {
            values_only: true,
            ..Workspace::default()
        }
    }

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
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Sources, Stop};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
    /// let mut workspace = solver.workspace();
    /// let stop = Stop::NONE.with_max_distance(1.2);
    /// solver.run(&mut workspace, Sources::from(0).until(&stop))?;
    /// let mut reached: Vec<u32> = workspace.reached_vertices().map(|(v, _)| v).collect();
    /// reached.sort();
    /// assert_eq!(reached, [0, 1, 3]); // vertex 2 is √2 away
    /// solver.run(&mut workspace, 0)?; // a full run
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
    pub(crate) fn view<'a>(&'a self, layout: &'a SteinerLayout) -> FieldView<'a> {
        FieldView {
            layout,
            distance: &self.distance,
            parent: &self.parent,
            parent_face: &self.parent_face,
            sources: &self.sources,
            roots: &self.roots,
            waves: &self.waves,
            windows: &self.exact,
            // (The engine of the last run is in its stats.)
            method: self.stats.as_ref().map_or(Method::Wave, |s| s.method),
            horizon: self.horizon,
        }
    }

    /// The last run as plain data, the buffers moved out.
    pub(crate) fn into_data<M, T>(self, solver: &Solver<M, T>) -> FieldData {
        let setup = solver.setup();
        FieldData::new(
            Arc::clone(&setup.layout),
            setup.id,
            self.distance,
            self.parent,
            self.parent_face,
            self.sources,
            self.roots,
            self.waves,
            self.exact,
            self.horizon,
            self.stats.expect("a finished run"),
        )
    }

    /// A copy of the last run as plain data.
    pub(crate) fn to_data<M, T>(&self, solver: &Solver<M, T>) -> FieldData {
        let setup = solver.setup();
        FieldData::new(
            Arc::clone(&setup.layout),
            setup.id,
            self.distance.clone(),
            self.parent.clone(),
            self.parent_face.clone(),
            self.sources.clone(),
            self.roots.clone(),
            self.waves.clone(),
            self.exact.clone(),
            self.horizon,
            self.stats.clone().expect("a finished run"),
        )
    }

    /// Sizes and clears the buffers for a run over `nodes` nodes, `instances` tracks
    /// and `waves` waves (and, with `exact`, the exact engine's per-vertex state);
    /// allocates only when they must grow.
    ///
    /// Only the nodes the last run touched hold anything but reset values, so when
    /// the sizes match and those are few (a run stopped at a maximum distance, as
    /// when a local distance matrix runs once per vertex), only they are cleared: a
    /// local run costs what it reaches, not the mesh. Tracks are cleared whole: the
    /// tracks engine writes those of targets it does not reach.
    pub(crate) fn reset(
        &mut self,
        vertex_count: usize,
        nodes: usize,
        instances: usize,
        waves: usize,
        exact: bool,
    ) {
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
        let exact_len = if exact { vertex_count } else { 0 };
        if partial && exact && self.exact.origin.len() == exact_len {
            for &node in &self.touched {
                if (node as usize) < vertex_count {
                    self.exact.origin[node as usize] = Origin::None;
                    self.exact.label[node as usize] = NONE;
                    self.exact_buffers.started[node as usize] = false;
                }
            }
        } else {
            fill(&mut self.exact.origin, exact_len, Origin::None);
            fill(&mut self.exact.label, exact_len, NONE);
            fill(&mut self.exact_buffers.started, exact_len, false);
        }
        self.exact.clear();
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
