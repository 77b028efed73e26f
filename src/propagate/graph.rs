//! Dijkstra on the implicit complete Steiner graph: the baseline and the oracle.
//!
//! Arcs: inside each face, every node to every node of the face's boundary that is not
//! on its own edge (points on the same edge are joined along the edge instead, to their
//! next neighbours; straight segments add up, so the next neighbour is enough). Nothing
//! is stored per arc: costs are asked of the metric when a node is settled.
//! With no Steiner points this is Dijkstra on mesh edges.

use super::Method;
use crate::field::{GeodesicField, Stats};
use crate::mesh::{Topology, TriMesh, NONE};
use crate::steiner::{NodeKind, SteinerLayout};
use crate::Error;
use geotracks_metrics::{FacePoint, Metric};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

/// A heap entry ordered so that the smallest distance pops first.
#[derive(Clone, Copy, PartialEq)]
struct Entry(f64, u32);

impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

struct Search<'a, M> {
    mesh: &'a TriMesh,
    metric: &'a M,
    layout: &'a SteinerLayout,
    distance: Vec<f64>,
    parent: Vec<u32>,
    parent_face: Vec<u32>,
    heap: BinaryHeap<Entry>,
    pushes: u64,
    tests: u64,
    bad_cost: Option<(u32, f64)>,
}

impl<M: Metric> Search<'_, M> {
    #[inline]
    fn cost(&mut self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        self.tests += 1;
        let c = self.metric.cost(face, a, b);
        if (c.is_nan() || c < 0.0) && self.bad_cost.is_none() {
            self.bad_cost = Some((face, c));
        }
        c
    }

    #[inline]
    fn relax(&mut self, node: u32, value: f64, from: u32, face: u32) {
        if value < self.distance[node as usize] {
            self.distance[node as usize] = value;
            self.parent[node as usize] = from;
            self.parent_face[node as usize] = face;
            self.heap.push(Entry(value, node));
            self.pushes += 1;
        }
    }

    /// Relaxes `to` from `from` along edge `e`, at the cheapest of the faces around it.
    fn relax_along_edge(&mut self, e: u32, from: u32, to: u32, d: f64) {
        let mut best = f64::INFINITY;
        for &f in self.mesh.edge_faces(e) {
            let a = self.layout.point_in_face(self.mesh, from, f);
            let b = self.layout.point_in_face(self.mesh, to, f);
            best = best.min(self.cost(f, &a, &b));
        }
        self.relax(to, d + best, from, NONE);
    }

    /// Relaxes every interior point of the edge in `slot` of face `f` from `q` at `pq`.
    fn relax_slot(&mut self, f: u32, slot: usize, q: u32, pq: &FacePoint, d: f64) {
        let e = self.mesh.face_edges(f)[slot];
        for (index, node) in self.layout.edge_nodes(e).enumerate() {
            let p = self.layout.point_on_slot(self.mesh, f, slot, index as u32);
            let c = self.cost(f, pq, &p);
            self.relax(node, d + c, q, f);
        }
    }

    fn settle(&mut self, q: u32, d: f64) {
        let (mesh, layout) = (self.mesh, self.layout);
        match layout.kind(q) {
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
                for &f in mesh.vertex_faces(v) {
                    let corner = mesh
                        .corner_of(f, v)
                        .expect("vertex is a corner of its face");
                    let pq = layout.point_in_face(mesh, q, f);
                    self.relax_slot(f, (corner + 1) % 3, q, &pq, d);
                }
            }
            NodeKind::Steiner { edge, index } => {
                let [lo, hi] = mesh.edge_vertices(edge);
                let nodes = layout.edge_nodes(edge);
                let prev = if index == 0 { lo } else { q - 1 };
                let next = if q + 1 == nodes.end { hi } else { q + 1 };
                self.relax_along_edge(edge, q, prev, d);
                self.relax_along_edge(edge, q, next, d);
                for &f in mesh.edge_faces(edge) {
                    let slot = mesh.edge_slot(f, edge).expect("edge lies on its face");
                    let pq = layout.point_on_slot(mesh, f, slot, index);
                    self.relax_slot(f, (slot + 1) % 3, q, &pq, d);
                    self.relax_slot(f, (slot + 2) % 3, q, &pq, d);
                    let opposite = mesh.face_vertices(f)[(slot + 2) % 3];
                    let po = layout.point_in_face(mesh, opposite, f);
                    let c = self.cost(f, &pq, &po);
                    self.relax(opposite, d + c, q, f);
                }
            }
        }
    }
}

pub(super) fn run<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    layout: Arc<SteinerLayout>,
    sources: &[u32],
    method: Method,
    start: Instant,
) -> Result<GeodesicField, Error> {
    let n = layout.node_count();
    let mut search = Search {
        mesh,
        metric,
        layout: &layout,
        distance: vec![f64::INFINITY; n],
        parent: vec![NONE; n],
        parent_face: vec![NONE; n],
        heap: BinaryHeap::new(),
        pushes: 0,
        tests: 0,
        bad_cost: None,
    };
    let setup_seconds = start.elapsed().as_secs_f64();
    let propagate_start = Instant::now();
    for &s in sources {
        search.relax(s, 0.0, NONE, NONE);
    }
    while let Some(Entry(d, q)) = search.heap.pop() {
        if d > search.distance[q as usize] {
            continue; // stale entry: q was improved after this push
        }
        search.settle(q, d);
        if let Some((face, value)) = search.bad_cost {
            return Err(Error::InvalidCost {
                metric: metric.name().to_string(),
                face,
                value,
            });
        }
    }
    let stats = Stats {
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        steiner_points: layout.steiner_count(),
        k: if method == Method::Dijkstra {
            0.0
        } else {
            layout.scheme().k()
        },
        method,
        setup_seconds,
        propagate_seconds: propagate_start.elapsed().as_secs_f64(),
        pushes: search.pushes,
        distance_tests: search.tests,
    };
    let Search {
        distance,
        parent,
        parent_face,
        ..
    } = search;
    Ok(GeodesicField::new(
        layout,
        distance,
        parent,
        parent_face,
        stats,
    ))
}
