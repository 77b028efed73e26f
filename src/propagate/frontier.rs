//! What every engine shares: per-node distances and parents, the work counters, the
//! metric call with its sanity check, and relaxation along edges.

use super::meet::Side;
use crate::field::Goal;
use crate::mesh::Topology;
use crate::mesh::{Csr, NONE};
use crate::steiner::{NodeKind, SteinerLayout};
use geotracks_metrics::{FacePoint, Metric};
use rayon::prelude::*;

/// A priority queue of nodes by key: their current distance, or in a goal-directed run
/// their distance plus their heuristic (see [`Goal`]).
pub(super) trait Queue {
    /// Queues `node` whose key just dropped from `previous` to `key`; returns whether
    /// an entry was added.
    fn push(&mut self, node: u32, key: f64, previous: f64) -> bool;
    /// The next node to settle, skipping stale entries (`key` gives each node's live
    /// key).
    fn pop(&mut self, key: impl Fn(u32) -> f64 + Copy) -> Option<u32>;
    /// Whether a node with key `key` now keeps its value: nothing queued, or queued
    /// later, can improve on it. Asked between a pop and the settling of the popped
    /// node.
    fn is_final(&self, key: f64) -> bool;
    /// The least key still queued, or a lower bound on it: settling what is queued
    /// offers nothing below it, less the engine's reach.
    fn level(&self) -> f64;
}

impl<Q: Queue> Queue for &mut Q {
    #[inline(always)]
    fn push(&mut self, node: u32, key: f64, previous: f64) -> bool {
        (**self).push(node, key, previous)
    }
    #[inline]
    fn pop(&mut self, key: impl Fn(u32) -> f64 + Copy) -> Option<u32> {
        (**self).pop(key)
    }
    #[inline]
    fn is_final(&self, key: f64) -> bool {
        (**self).is_final(key)
    }
    #[inline]
    fn level(&self) -> f64 {
        (**self).level()
    }
}

/// Per-node state (borrowed from a workspace) and counters of one run, generic over the
/// metric and the queue.
pub(super) struct Frontier<'a, M, T, Q> {
    pub mesh: &'a T,
    pub metric: &'a M,
    pub layout: &'a SteinerLayout,
    /// Cost between consecutive nodes of each edge, when the metric allows caching it.
    pub edge_steps: Option<&'a [f64]>,
    /// Per vertex, its wires: the other end and the wire's cost.
    pub wires: &'a Csr<(u32, f64)>,
    pub distance: &'a mut [f64],
    pub parent: &'a mut [u32],
    pub parent_face: &'a mut [u32],
    /// When `records` holds: every node whose distance, parent or wave this run set
    /// (a node may appear twice). All others keep their reset values, so that
    /// forgetting after an early stop and the next run's reset visit only these (see
    /// `Workspace::reset`).
    pub touched: &'a mut Vec<u32>,
    /// Whether the run records `touched`: only runs that may stop early (at a maximum
    /// distance or at targets), the ones that can reach little. A full run reaches
    /// everything, so its next reset clears everything anyway, and it saves the
    /// record's cost (about 5 % of a tracks run).
    pub records: bool,
    pub queue: Q,
    /// Values above this are not taken: their nodes stay unreached.
    pub max_distance: f64,
    /// A goal-directed run's estimate: the queue orders nodes by value plus estimate
    /// (their *key*); `None`: by value.
    pub goal: Option<Goal>,
    /// Per node, its goal estimate, written when the node is first reached (read only
    /// for reached nodes, so never reset); empty without a goal.
    pub estimate: &'a mut [f64],
    /// How far below a node's value an offer it makes can be (0 for the Steiner-graph
    /// engines, whose offers add a cost ≥ 0; the longest edge for the wavefront engine,
    /// whose straight offers come from a source behind the node: a node lies within an
    /// edge of where the line crosses its edge). Finality and the maximum distance
    /// are judged with this much margin, so that early stops keep exact values.
    pub reach: f64,
    /// Nodes whose final values end the run once all are final (none: run to the end).
    pub targets: &'a [u32],
    /// `targets[..target_cursor]` are known final.
    pub target_cursor: usize,
    /// For one side of a search from both ends: its part in the meeting, which ends
    /// the run (see `meet`).
    pub meet: Option<Side<'a>>,
    pub pushes: u64,
    /// Nodes popped from the queue to be settled (a node may settle more than once).
    pub settles: u64,
    pub tests: u64,
    /// The first NaN or negative cost the metric returned, with its face.
    pub bad_cost: Option<(u32, f64)>,
}

/// A node's start value from a source: the cost from the source point to the node
/// inside `face`, plus the source's start (`face` is [`NONE`] when the node is the
/// source vertex itself).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Seed {
    pub node: u32,
    pub face: u32,
    pub value: f64,
    /// Index of the source.
    pub source: u32,
}

/// How a run ended.
pub(super) struct Outcome {
    pub pushes: u64,
    pub settles: u64,
    pub tests: u64,
    pub bad_cost: Option<(u32, f64)>,
    /// The targets were all final before the queue ran out.
    pub stopped_early: bool,
    /// After a stop at the targets, the least key anything left could still get (see
    /// [`Horizon`](crate::field::Horizon)); `inf` otherwise.
    pub level: f64,
}

/// How an engine settles the node its frontier hands it; the loop around it,
/// [`settle_all`], is written once for every engine.
pub(super) trait Settle {
    /// The run's next node and its value ([`Frontier::next`]).
    fn next(&mut self) -> Option<(u32, f64)>;
    /// The mesh's vertex count (nodes below it are vertices).
    fn vertex_count(&self) -> u32;
    /// Settles vertex `v` at value `d`.
    fn settle_vertex(&mut self, v: u32, d: f64);
    /// Settles Steiner node `q` at value `d`.
    fn settle_steiner(&mut self, q: u32, d: f64);
}

/// Settles nodes in the frontier's order until the run is over ([`Frontier::next`]).
#[inline(always)]
pub(super) fn settle_all(engine: &mut impl Settle) {
    let vertex_count = engine.vertex_count();
    while let Some((q, d)) = engine.next() {
        if q < vertex_count {
            engine.settle_vertex(q, d);
        } else {
            engine.settle_steiner(q, d);
        }
    }
}

impl<'a, M: Metric, T: Topology> Frontier<'a, M, T, ()> {
    /// Attaches `queue`, gives the seeds their values, runs `engine`, and returns the
    /// counters. A run stopped by its targets then forgets every value that was not
    /// final yet, so that a finite value is always the exact one.
    pub fn run<Q: Queue>(
        self,
        queue: Q,
        seeds: &[Seed],
        engine: impl FnOnce(&mut Frontier<'a, M, T, Q>),
    ) -> Outcome {
        let mut search = Frontier {
            mesh: self.mesh,
            metric: self.metric,
            layout: self.layout,
            edge_steps: self.edge_steps,
            wires: self.wires,
            distance: self.distance,
            parent: self.parent,
            parent_face: self.parent_face,
            touched: self.touched,
            records: self.records,
            queue,
            max_distance: self.max_distance,
            goal: self.goal,
            estimate: self.estimate,
            reach: self.reach,
            targets: self.targets,
            target_cursor: 0,
            meet: self.meet,
            pushes: 0,
            settles: 0,
            tests: self.tests,
            bad_cost: self.bad_cost,
        };
        for seed in seeds {
            search.relax(seed.node, seed.value, NONE, seed.face);
        }
        engine(&mut search);
        let stopped_early = !search.targets.is_empty()
            && search.target_cursor == search.targets.len()
            && search.bad_cost.is_none();
        let (reach, max) = (search.reach, search.max_distance);
        // After a stop at the targets, what is still queued (at `level` or later) offers
        // no key below `level - reach` (a goal-directed run is a Steiner-graph engine's,
        // with no reach: its offers add at least what the estimate drops), and a node is
        // kept only if its key is below that too.
        let level = if stopped_early {
            search.queue.level() - reach
        } else {
            f64::INFINITY
        };
        // (With a margin, values up to `max + reach` were taken: only a finite maximum
        // leaves some to forget.)
        if stopped_early || (reach > 0.0 && max < f64::INFINITY) {
            // Only touched nodes hold values (and this run recorded them: it could
            // stop early): a local run pays for what it reached.
            for &node in search.touched.iter() {
                let key = search.key(node);
                let node = node as usize;
                let d = &mut search.distance[node];
                // Values beyond the maximum distance were only kept for the margin
                // (keys: a goal-directed run keeps none whose key is beyond).
                let beyond = d.is_finite() && key > max;
                let not_final =
                    stopped_early && d.is_finite() && !search.queue.is_final(key + reach);
                if beyond || not_final {
                    *d = f64::INFINITY;
                    search.parent[node] = NONE;
                    search.parent_face[node] = NONE;
                }
            }
        }
        Outcome {
            pushes: search.pushes,
            settles: search.settles,
            tests: search.tests,
            bad_cost: search.bad_cost,
            stopped_early,
            level,
        }
    }
}

impl<M: Metric, T: Topology, Q: Queue> Frontier<'_, M, T, Q> {
    /// The key the queue orders `node` by: its value, plus its estimate in a
    /// goal-directed run (`inf` for an unreached node).
    #[inline(always)]
    pub fn key(&self, node: u32) -> f64 {
        self.distance[node as usize] + self.estimate_of(node)
    }

    /// `node`'s goal estimate (0 without a goal). An unreached node's may be stale from
    /// an earlier run, but is finite: its key stays `inf`.
    #[inline(always)]
    fn estimate_of(&self, node: u32) -> f64 {
        match self.goal {
            Some(_) => self.estimate[node as usize],
            None => 0.0,
        }
    }

    /// The next node to settle and its value; `None` when the run is over: the queue is
    /// empty, the metric returned a bad cost, or every target's value is final.
    ///
    /// Targets become final in no particular order, but stay final, so a cursor over
    /// them makes all the checks of a run cost O(targets + pops).
    #[inline]
    pub fn next(&mut self) -> Option<(u32, f64)> {
        if self.bad_cost.is_some() {
            return self.over();
        }
        let distance = &*self.distance;
        let popped = if self.goal.is_some() {
            let estimate = &*self.estimate;
            self.queue
                .pop(|q| distance[q as usize] + estimate[q as usize])
        } else {
            self.queue.pop(|q| distance[q as usize])
        };
        let Some(q) = popped else {
            return self.over();
        };
        self.settles += 1;
        if let Some(side) = &mut self.meet {
            // Everything below the level is settled; `q` is not yet.
            if side.round_over(self.pushes)
                && side.end_round(self.queue.level(), self.distance, self.pushes)
            {
                return None;
            }
            side.settle(q, self.distance[q as usize]);
        }
        if !self.targets.is_empty() {
            while let Some(&t) = self.targets.get(self.target_cursor) {
                if !self.queue.is_final(self.key(t) + self.reach) {
                    return Some((q, self.distance[q as usize]));
                }
                self.target_cursor += 1;
            }
            return None;
        }
        Some((q, self.distance[q as usize]))
    }

    /// The end of the run: for one side of a search from both ends, once the other
    /// side agrees (it takes part in rounds with nothing left to settle).
    #[cold]
    fn over(&mut self) -> Option<(u32, f64)> {
        if let Some(side) = &mut self.meet {
            side.finish(self.distance);
        }
        None
    }

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
        if value >= previous {
            return;
        }
        // The estimate, worked out when the node is first reached.
        let estimate = match &self.goal {
            Some(goal) if previous == f64::INFINITY => {
                let e = goal.estimate(self.layout.position(self.mesh, node));
                self.estimate[node as usize] = e;
                e
            }
            _ => self.estimate_of(node),
        };
        // A goal-directed run takes no node whose key is beyond the maximum distance:
        // no target lies within it through that node.
        if value + estimate <= self.max_distance + self.reach {
            if previous == f64::INFINITY && self.records {
                self.touched.push(node);
            }
            self.distance[node as usize] = value;
            self.parent[node as usize] = from;
            self.parent_face[node as usize] = face;
            self.pushes += self.queue.push(node, value + estimate, previous + estimate) as u64;
        }
    }

    /// Queues `node` again at its current key (its value stays, but what it offers
    /// changed: the wavefront engine widened its window).
    #[inline]
    pub fn requeue(&mut self, node: u32) {
        let key = self.key(node);
        self.pushes += self.queue.push(node, key, key) as u64;
    }

    /// Relaxes the vertices at the other ends of vertex `v`'s wires (a vertex's node is
    /// its id): a wire is travelled whole, at its cost.
    #[inline]
    pub fn relax_along_wires(&mut self, v: u32, d: f64) {
        let wires = self.wires;
        for &(w, cost) in wires.row(v) {
            self.relax(w, d + cost, v, NONE);
        }
    }

    /// Relaxes `q`'s neighbours along its edges (for a vertex, the first node of every
    /// edge around it, and the other end of every wire; for a Steiner point, the nodes
    /// before and after it). Straight
    /// segments add up along an edge, so the next neighbour is enough; the segment costs
    /// what it costs in the cheapest face around the edge.
    pub fn relax_along_edges(&mut self, q: u32, kind: NodeKind, d: f64) {
        let (mesh, layout) = (self.mesh, self.layout);
        match kind {
            NodeKind::Vertex(v) => {
                for &e in mesh.vertex_edges(v).iter() {
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
                self.relax_along_wires(v, d);
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
        for &f in self.mesh.edge_faces(e).iter() {
            let a = self.layout.point_in_face(self.mesh, from, f);
            let b = self.layout.point_in_face(self.mesh, to, f);
            best = best.min(self.cost(f, &a, &b));
        }
        self.relax(to, d + best, from, NONE);
    }
}

/// The cost between consecutive nodes of each edge, in the cheapest face around it, or
/// `None` when the metric is not a norm on each face, or is directed (a step then costs
/// what it costs in its direction). For a norm the cost of a piece of an edge is its
/// fraction of the whole edge's cost, so one evaluation per (edge, face) serves every
/// step; the evaluations are returned as the second value. `flat`: every face has a
/// flattening ([`Metric::face_gram`]), which makes the metric a norm on each face
/// whatever `is_face_norm` says (the wavefront engine needs these steps).
pub(super) fn edge_steps<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    layout: &SteinerLayout,
    flat: bool,
) -> Option<(Vec<f64>, u64)> {
    if !(metric.is_face_norm() || flat) || !metric.is_symmetric() {
        return None;
    }
    // Face by face (on all cores, kept in face order), so that the mesh is read in
    // order: each slot's whole edge, from the edge's lower vertex to its higher one as
    // a node-by-node walk would measure it, with the face's longest side (what the
    // cost's rounding is relative to); then per edge the least, or the one measured
    // most precisely where the faces agree to rounding.
    let slots: Vec<([f64; 3], f64)> = (0..mesh.face_count() as u32)
        .into_par_iter()
        .map(|f| {
            let frame = mesh.frame(f);
            let costs = std::array::from_fn(|s| {
                let (from, to) = (frame.corner(s), frame.corner((s + 1) % 3));
                if mesh.slot_is_reversed(f, s) {
                    metric.cost(f, &to, &from)
                } else {
                    metric.cost(f, &from, &to)
                }
            });
            (costs, costs.iter().fold(0.0f64, |m, &c| m.max(c)))
        })
        .collect();
    // Per edge: the least cost and its face's scale, and the cost in the face of least
    // scale.
    let mut least = vec![(f64::INFINITY, 0.0f64); mesh.edge_count()];
    let mut precise = vec![(f64::INFINITY, f64::INFINITY); mesh.edge_count()];
    for (f, (costs, scale)) in slots.iter().enumerate() {
        for (e, &cost) in mesh.face_edges(f as u32).into_iter().zip(costs) {
            let e = e as usize;
            if cost < least[e].0 {
                least[e] = (cost, *scale);
            }
            if *scale < precise[e].1 {
                precise[e] = (cost, *scale);
            }
        }
    }
    // A short edge of a face with a far corner is measured there to rounding of that
    // corner's distance: where that is all that sets the faces apart, the precise cost
    // is the edge's (a wave carried along it then agrees with the faces around it).
    let whole = least
        .iter()
        .zip(&precise)
        .map(|(&(low, scale), &(cost, _))| {
            if cost - low <= 1e-12 * scale {
                cost
            } else {
                low
            }
        });
    let steps = whole
        .enumerate()
        .map(|(e, whole)| whole / (layout.count(e as u32) + 1) as f64)
        .collect();
    Some((steps, 3 * mesh.face_count() as u64))
}
