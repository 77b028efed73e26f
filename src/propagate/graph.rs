//! Dijkstra on the implicit complete Steiner graph: the baseline and the oracle.
//!
//! Arcs: inside each face, every node to every node of the face's boundary that is not
//! on its own edge (points on the same edge are joined along the edge instead, to their
//! next neighbours). Nothing is stored per arc: costs are asked of the metric when a
//! node is settled. With no Steiner points this is Dijkstra on mesh edges.

use super::frontier::{settle_all, Frontier, Queue, Settle};
use crate::mesh::Topology;
use crate::steiner::NodeKind;
use geotracks_metrics::{FacePoint, Metric};

/// Settles nodes until the run is over ([`settle_all`]).
pub(super) fn propagate<M: Metric, T: Topology, Q: Queue>(search: &mut Frontier<'_, M, T, Q>) {
    settle_all(&mut Graph(search));
}

/// The complete graph's settling: the same for vertices and Steiner points.
struct Graph<'r, 'a, M, T, Q>(&'r mut Frontier<'a, M, T, Q>);

impl<M: Metric, T: Topology, Q: Queue> Settle for Graph<'_, '_, M, T, Q> {
    #[inline(always)]
    fn next(&mut self) -> Option<(u32, f64)> {
        self.0.next()
    }
    #[inline(always)]
    fn vertex_count(&self) -> u32 {
        self.0.layout.vertex_count()
    }
    #[inline(always)]
    fn settle_vertex(&mut self, v: u32, d: f64) {
        self.settle_steiner(v, d);
    }
    #[inline(always)]
    fn settle_steiner(&mut self, q: u32, d: f64) {
        let search = &mut *self.0;
        let kind = search.layout.kind(q);
        search.relax_along_edges(q, kind, d);
        settle_in_faces(search, q, kind, d);
    }
}

/// Relaxes every node of every face around `q` that is not on `q`'s own edges.
fn settle_in_faces<M: Metric, T: Topology, Q: Queue>(
    search: &mut Frontier<'_, M, T, Q>,
    q: u32,
    kind: NodeKind,
    d: f64,
) {
    let (mesh, layout) = (search.mesh, search.layout);
    match kind {
        NodeKind::Vertex(v) => {
            for &f in mesh.vertex_faces(v).iter() {
                let corner = mesh
                    .corner_of(f, v)
                    .expect("vertex is a corner of its face");
                let pq = layout.point_in_face(mesh, q, f);
                relax_slot(search, f, (corner + 1) % 3, q, &pq, d);
            }
        }
        NodeKind::Steiner { edge, index } => {
            for &f in mesh.edge_faces(edge).iter() {
                let slot = mesh.edge_slot(f, edge).expect("edge lies on its face");
                let pq = layout.point_on_slot(mesh, f, slot, index);
                relax_slot(search, f, (slot + 1) % 3, q, &pq, d);
                relax_slot(search, f, (slot + 2) % 3, q, &pq, d);
                let opposite = mesh.face_vertices(f)[(slot + 2) % 3];
                let po = layout.point_in_face(mesh, opposite, f);
                let c = search.cost(f, &pq, &po);
                search.relax(opposite, d + c, q, f);
            }
        }
    }
}

/// Relaxes every interior point of the edge in `slot` of face `f` from `q` at `pq`.
fn relax_slot<M: Metric, T: Topology, Q: Queue>(
    search: &mut Frontier<'_, M, T, Q>,
    f: u32,
    slot: usize,
    q: u32,
    pq: &FacePoint,
    d: f64,
) {
    let points = search.layout.slot_points(search.mesh, f, slot);
    for i in 0..points.count {
        let (node, p) = points.at(i);
        let c = search.cost(f, pq, &p);
        search.relax(node, d + c, q, f);
    }
}
