//! What every engine shares: per-node distances and parents, the work counters, the
//! metric call with its sanity check, and relaxation along edges.

use crate::mesh::{Topology, TriMesh, NONE};
use crate::steiner::{NodeKind, SteinerLayout};
use geotracks_metrics::{FacePoint, Metric};

/// A priority queue of nodes keyed by their current distance.
pub(super) trait Queue {
    /// Queues `node` whose distance just dropped from `previous` to `value`; returns
    /// whether an entry was added.
    fn push(&mut self, node: u32, value: f64, previous: f64) -> bool;
    /// The next node to settle, skipping stale entries (`distance` is the live state).
    fn pop(&mut self, distance: &[f64]) -> Option<u32>;
}

impl<Q: Queue> Queue for &mut Q {
    #[inline(always)]
    fn push(&mut self, node: u32, value: f64, previous: f64) -> bool {
        (**self).push(node, value, previous)
    }
    #[inline]
    fn pop(&mut self, distance: &[f64]) -> Option<u32> {
        (**self).pop(distance)
    }
}

/// Per-node state (borrowed from a workspace) and counters of one run, generic over the
/// metric and the queue.
pub(super) struct Frontier<'a, M, Q> {
    pub mesh: &'a TriMesh,
    pub metric: &'a M,
    pub layout: &'a SteinerLayout,
    /// Cost between consecutive nodes of each edge, when the metric allows caching it.
    pub edge_steps: Option<&'a [f64]>,
    pub distance: &'a mut [f64],
    pub parent: &'a mut [u32],
    pub parent_face: &'a mut [u32],
    pub queue: Q,
    pub pushes: u64,
    pub tests: u64,
    /// The first NaN or negative cost the metric returned, with its face.
    pub bad_cost: Option<(u32, f64)>,
}

impl<'a, M: Metric> Frontier<'a, M, ()> {
    /// Attaches `queue`, seeds it with `sources` (start value 0), runs `engine`, and
    /// returns the counters and the first bad cost.
    pub fn run<Q: Queue>(
        self,
        queue: Q,
        sources: &[u32],
        engine: impl FnOnce(&mut Frontier<'a, M, Q>),
    ) -> (u64, u64, Option<(u32, f64)>) {
        let mut search = Frontier {
            mesh: self.mesh,
            metric: self.metric,
            layout: self.layout,
            edge_steps: self.edge_steps,
            distance: self.distance,
            parent: self.parent,
            parent_face: self.parent_face,
            queue,
            pushes: 0,
            tests: 0,
            bad_cost: None,
        };
        for &s in sources {
            search.relax(s, 0.0, NONE, NONE);
        }
        engine(&mut search);
        (search.pushes, search.tests, search.bad_cost)
    }
}

impl<M: Metric, Q: Queue> Frontier<'_, M, Q> {
    /// The metric's cost of a segment in face `face`, counted as one distance test.
    #[inline(always)]
    pub fn cost(&mut self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        self.tests += 1;
        let c = self.metric.cost(face, a, b);
        if (c.is_nan() || c < 0.0) && self.bad_cost.is_none() {
            self.bad_cost = Some((face, c));
        }
        c
    }

    /// Lowers `node`'s distance to `value` if that is an improvement, recording that it
    /// came from `from` through `face` (`NONE`: along an edge, or a source).
    #[inline(always)]
    pub fn relax(&mut self, node: u32, value: f64, from: u32, face: u32) {
        let previous = self.distance[node as usize];
        if value < previous {
            self.distance[node as usize] = value;
            self.parent[node as usize] = from;
            self.parent_face[node as usize] = face;
            self.pushes += self.queue.push(node, value, previous) as u64;
        }
    }

    /// Relaxes `q`'s neighbours along its edges (for a vertex, the first node of every
    /// edge around it; for a Steiner point, the nodes before and after it). Straight
    /// segments add up along an edge, so the next neighbour is enough; the segment costs
    /// what it costs in the cheapest face around the edge.
    pub fn relax_along_edges(&mut self, q: u32, kind: NodeKind, d: f64) {
        let (mesh, layout) = (self.mesh, self.layout);
        match kind {
            NodeKind::Vertex(v) => {
                for &e in mesh.vertex_edges(v) {
                    let nodes = layout.edge_nodes(e);
                    let [lo, hi] = mesh.edge_vertices(e);
                    let next = match (nodes.is_empty(), v == lo) {
                        (true, true) => hi,
                        (true, false) => lo,
                        (false, true) => nodes.start,
                        (false, false) => nodes.end - 1,
                    };
                    self.relax_along_edge(e, q, next, d);
                }
            }
            NodeKind::Steiner { edge, index } => {
                let [lo, hi] = mesh.edge_vertices(edge);
                let nodes = layout.edge_nodes(edge);
                let prev = if index == 0 { lo } else { q - 1 };
                let next = if q + 1 == nodes.end { hi } else { q + 1 };
                self.relax_along_edge(edge, q, prev, d);
                self.relax_along_edge(edge, q, next, d);
            }
        }
    }

    fn relax_along_edge(&mut self, e: u32, from: u32, to: u32, d: f64) {
        if let Some(steps) = self.edge_steps {
            self.relax(to, d + steps[e as usize], from, NONE);
            return;
        }
        let mut best = f64::INFINITY;
        for &f in self.mesh.edge_faces(e) {
            let a = self.layout.point_in_face(self.mesh, from, f);
            let b = self.layout.point_in_face(self.mesh, to, f);
            best = best.min(self.cost(f, &a, &b));
        }
        self.relax(to, d + best, from, NONE);
    }
}

/// The cost between consecutive nodes of each edge, in the cheapest face around it, or
/// `None` when the metric is not a norm on each face. For a norm the cost of a piece of
/// an edge is its fraction of the whole edge's cost, so one evaluation per (edge, face)
/// serves every step; the evaluations are returned as the second value.
pub(super) fn edge_steps<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    layout: &SteinerLayout,
) -> Option<(Vec<f64>, u64)> {
    if !metric.is_face_norm() {
        return None;
    }
    // Face by face, so that the mesh is read in order: each slot's whole edge, from the
    // edge's lower vertex to its higher one as a node-by-node walk would measure it.
    let mut whole = vec![f64::INFINITY; mesh.edge_count()];
    for f in 0..mesh.face_count() as u32 {
        let frame = mesh.frame(f);
        for (s, e) in mesh.face_edges(f).into_iter().enumerate() {
            let (from, to) = (frame.corner(s), frame.corner((s + 1) % 3));
            let cost = if mesh.slot_is_reversed(f, s) {
                metric.cost(f, &to, &from)
            } else {
                metric.cost(f, &from, &to)
            };
            whole[e as usize] = whole[e as usize].min(cost);
        }
    }
    let steps = whole
        .into_iter()
        .enumerate()
        .map(|(e, whole)| whole / (layout.count(e as u32) + 1) as f64)
        .collect();
    Some((steps, 3 * mesh.face_count() as u64))
}
