//! [`GeodesicField`]: what a propagation returns, and queries on it.

use crate::mesh::NONE;
use crate::propagate::Method;
use crate::steiner::SteinerLayout;
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
    /// Queue insertions.
    pub pushes: u64,
    /// Metric evaluations made while propagating.
    pub distance_tests: u64,
    /// Metric evaluations made once by the solver's setup (the per-edge step costs of
    /// a norm metric; for other metrics, one per edge to size the tracks engine's
    /// bucket queue), shared by all its runs.
    pub setup_distance_tests: u64,
}

/// A distance field over a mesh's nodes (vertices and Steiner points), with the parent of
/// each node for tracing paths back to a source.
#[derive(Clone, Debug)]
pub struct GeodesicField {
    layout: Arc<SteinerLayout>,
    distance: Vec<f64>,
    parent: Vec<u32>,
    parent_face: Vec<u32>,
    stats: Stats,
}

impl GeodesicField {
    /// Assembles a field from per-node state (used by the propagation engines).
    pub(crate) fn new(
        layout: Arc<SteinerLayout>,
        distance: Vec<f64>,
        parent: Vec<u32>,
        parent_face: Vec<u32>,
        stats: Stats,
    ) -> GeodesicField {
        debug_assert_eq!(distance.len(), layout.node_count());
        GeodesicField {
            layout,
            distance,
            parent,
            parent_face,
            stats,
        }
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
