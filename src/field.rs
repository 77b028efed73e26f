//! [`GeodesicField`]: what a propagation returns, and queries on it: the distance at any
//! surface point, the nearest source of each vertex (geodesic Voronoi), and paths
//! ([`crate::trace`]).

use crate::mesh::{Topology, TriMesh, NONE};
use crate::propagate::{Method, Seed};
use crate::steiner::SteinerLayout;
use crate::surface::{Source, SurfacePoint};
use crate::trace::GeodesicPath;
use crate::Error;
use geotracks_metrics::Metric;
use std::sync::Arc;

/// Counters and timings of one run.
///
/// `distance_tests` counts every metric evaluation made during propagation, whatever the
/// method, so it measures the work done independently of the machine.
#[derive(Clone, Debug, PartialEq)]
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
}

/// A distance field over a mesh's nodes (vertices and Steiner points), with the parent of
/// each node for tracing paths back to a source.
#[derive(Clone, Debug)]
pub struct GeodesicField {
    layout: Arc<SteinerLayout>,
    distance: Vec<f64>,
    parent: Vec<u32>,
    parent_face: Vec<u32>,
    sources: Vec<Source>,
    roots: Vec<Seed>,
    stats: Stats,
}

impl GeodesicField {
    /// Assembles a field from per-node state (used by the propagation engines).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        layout: Arc<SteinerLayout>,
        distance: Vec<f64>,
        parent: Vec<u32>,
        parent_face: Vec<u32>,
        sources: Vec<Source>,
        roots: Vec<Seed>,
        stats: Stats,
    ) -> GeodesicField {
        debug_assert_eq!(distance.len(), layout.node_count());
        GeodesicField {
            layout,
            distance,
            parent,
            parent_face,
            sources,
            roots,
            stats,
        }
    }

    /// The field as a borrowed view, which answers the queries.
    pub fn view(&self) -> FieldView<'_> {
        FieldView {
            layout: &self.layout,
            distance: &self.distance,
            parent: &self.parent,
            parent_face: &self.parent_face,
            sources: &self.sources,
            roots: &self.roots,
        }
    }

    /// The distance at any surface point: see [`FieldView::distance_at`].
    ///
    /// # Errors
    /// As [`FieldView::distance_at`].
    pub fn distance_at<M: Metric>(
        &self,
        mesh: &TriMesh,
        metric: &M,
        point: SurfacePoint,
    ) -> Result<f64, Error> {
        self.view().distance_at(mesh, metric, point)
    }

    /// The straightened path from `point` to its nearest source: see
    /// [`FieldView::path`].
    ///
    /// # Errors
    /// As [`FieldView::path`].
    pub fn path<M: Metric>(
        &self,
        mesh: &TriMesh,
        metric: &M,
        point: SurfacePoint,
    ) -> Result<GeodesicPath, Error> {
        self.view().path(mesh, metric, point)
    }

    /// The nearest source of every vertex: see [`FieldView::vertex_labels`].
    pub fn vertex_labels(&self) -> Vec<u32> {
        self.view().vertex_labels()
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

/// A borrowed distance field: per-node values and parents, and the sources they came
/// from. Made by [`GeodesicField::view`] or [`crate::Workspace::view`]; it answers the
/// queries on a field without copying it.
#[derive(Clone, Copy, Debug)]
pub struct FieldView<'a> {
    pub(crate) layout: &'a SteinerLayout,
    pub(crate) distance: &'a [f64],
    pub(crate) parent: &'a [u32],
    pub(crate) parent_face: &'a [u32],
    pub(crate) sources: &'a [Source],
    /// Per node that a source reached directly, the seed it kept, sorted by node.
    pub(crate) roots: &'a [Seed],
}

/// Where the value at a surface point comes from: a node of one of its faces, or a
/// source that shares a face with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Origin {
    /// The point is this node.
    Node(u32),
    /// A straight segment in `face` from this node.
    NodeInFace(u32, u32),
    /// A straight segment in `face` from this source.
    SourceInFace(u32, u32),
}

impl<'a> FieldView<'a> {
    /// Distance at every vertex.
    pub fn vertex_distances(&self) -> &'a [f64] {
        &self.distance[..self.layout.vertex_count() as usize]
    }

    /// Errors unless `mesh` is the mesh the field was computed on (by its counts).
    pub(crate) fn check_mesh(&self, mesh: &TriMesh) -> Result<(), Error> {
        if mesh.vertex_count() != self.layout.vertex_count() as usize
            || mesh.edge_count() != self.layout.edge_count()
        {
            return Err(Error::MeshMismatch {
                vertices: mesh.vertex_count(),
                edges: mesh.edge_count(),
                field_vertices: self.layout.vertex_count() as usize,
                field_edges: self.layout.edge_count(),
            });
        }
        Ok(())
    }

    /// The distance at any surface point, as the Steiner graph defines it: at a node,
    /// its value; elsewhere, the least over the nodes on the boundary of the faces
    /// holding the point of the node's value plus the metric's cost of the straight
    /// segment to the point (and, from a source sharing one of those faces, the
    /// source's start plus its segment). Not an interpolation of vertex values. `inf`
    /// when no source reaches the point.
    ///
    /// Cost: O(k) metric evaluations per face around the point.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] if `point` is not a point of `mesh`;
    /// [`Error::MeshMismatch`] if `mesh` is not the field's mesh.
    pub fn distance_at<M: Metric>(
        &self,
        mesh: &TriMesh,
        metric: &M,
        point: SurfacePoint,
    ) -> Result<f64, Error> {
        Ok(self.origin(mesh, metric, point)?.0)
    }

    /// The value at `point` and where it comes from (`None` when unreached).
    pub(crate) fn origin<M: Metric>(
        &self,
        mesh: &TriMesh,
        metric: &M,
        point: SurfacePoint,
    ) -> Result<(f64, Option<Origin>), Error> {
        self.check_mesh(mesh)?;
        let point = point.validated(mesh).map_err(|error| Error::InvalidPoint {
            what: "the query point".into(),
            error,
        })?;
        if let SurfacePoint::Vertex(v) = point {
            let d = self.distance[v as usize];
            return Ok((d, d.is_finite().then_some(Origin::Node(v))));
        }
        let mut best = (f64::INFINITY, None);
        for &f in point.faces(mesh).iter() {
            let x = point.in_face(mesh, f).expect("the point lies on its faces");
            for (node, p) in self.layout.face_nodes(mesh, f) {
                let g = self.distance[node as usize];
                if g < best.0 {
                    let d = g + metric.cost(f, &p, &x);
                    if d < best.0 {
                        best = (d, Some(Origin::NodeInFace(node, f)));
                    }
                }
            }
            for (i, source) in self.sources.iter().enumerate() {
                if let Some(s) = source.point.in_face(mesh, f) {
                    let d = source.start + metric.cost(f, &s, &x);
                    if d < best.0 {
                        best = (d, Some(Origin::SourceInFace(i as u32, f)));
                    }
                }
            }
        }
        Ok(best)
    }

    /// The source (index into the run's sources) that gave a root node its value.
    pub(crate) fn root_source(&self, node: u32) -> Option<u32> {
        let at = self.roots.binary_search_by_key(&node, |s| s.node).ok()?;
        Some(self.roots[at].source)
    }

    /// The index of the nearest source of every vertex (the geodesic Voronoi diagram of
    /// the sources, start values included), [`NONE`] where unreached.
    ///
    /// Found by following parents to the source that started each chain, with every
    /// node labelled once: O(nodes).
    pub fn vertex_labels(&self) -> Vec<u32> {
        let mut label = self.labels(self.layout.vertex_count());
        label.truncate(self.layout.vertex_count() as usize);
        label
    }

    /// As [`FieldView::vertex_labels`], for every node (vertices, then Steiner points in
    /// [`SteinerLayout`] order).
    pub fn node_labels(&self) -> Vec<u32> {
        self.labels(self.distance.len() as u32)
    }

    /// Labels of nodes `0..count` (and of the nodes their chains pass through).
    fn labels(&self, count: u32) -> Vec<u32> {
        let n = self.distance.len();
        let mut label = vec![NONE; n];
        let mut known = vec![false; n];
        let mut chain = Vec::new();
        for start in 0..count {
            let mut node = start;
            // Walk up to a labelled node or a root; parents have lower values, so the
            // walk ends (a step cap guards against a metric with zero costs).
            let found = loop {
                if known[node as usize] {
                    break label[node as usize];
                }
                if self.distance[node as usize].is_infinite() {
                    break NONE;
                }
                chain.push(node);
                let p = self.parent[node as usize];
                if p == NONE {
                    break self.root_source(node).unwrap_or(NONE);
                }
                if chain.len() > n {
                    break NONE;
                }
                node = p;
            };
            for &c in &chain {
                label[c as usize] = found;
                known[c as usize] = true;
            }
            chain.clear();
        }
        label
    }
}
