//! Where Steiner points go on each edge, and how nodes are numbered.
//!
//! A *node* is a vertex or a Steiner point. Node ids are dense `u32`: vertices keep their
//! ids `0..V`, then the Steiner points in one block per edge, each edge's points
//! numbered from its lower-id vertex. The blocks follow a space-filling curve through
//! the edges' midpoints, not the edge ids, so that nodes near each other on the surface
//! are near each other in memory; [`SteinerLayout::edge_nodes`] gives an edge's block.
//! Points are implicit: a node is an edge and an index, and its position in a face is
//! computed when needed, never stored per face.

use crate::mesh::Topology;
use crate::mesh::{EdgeLine, NONE};
use crate::surface::SurfacePoint;
use crate::Error;
use geotracks_metrics::FacePoint;
use std::ops::Range;

/// How many Steiner points each edge gets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SteinerScheme {
    /// The paper's default: one spacing `h` for the whole mesh, chosen so that edges
    /// carry `k` points on average; an edge of length `L` gets `round(L / h)` evenly
    /// spaced points (none on edges shorter than `h / 2`).
    Interval {
        /// Target mean number of points per edge (> 0).
        k: f64,
    },
    /// Exactly `count` evenly spaced points on every edge.
    Fixed {
        /// Points per edge (≥ 1).
        count: u32,
    },
}

impl SteinerScheme {
    /// The mean points per edge this scheme aims for.
    pub fn k(&self) -> f64 {
        match *self {
            SteinerScheme::Interval { k } => k,
            SteinerScheme::Fixed { count } => count as f64,
        }
    }

    /// How many points each edge of `mesh` gets (saturating at `u32::MAX`), spaced by
    /// the edges' lengths.
    pub fn counts<T: Topology>(&self, mesh: &T) -> Vec<u32> {
        let lengths: Vec<f64> = (0..mesh.edge_count() as u32)
            .map(|e| mesh.edge_length(e))
            .collect();
        self.counts_for(&lengths, 0)
    }

    /// How many points edges of the given `lengths` get (in any unit: a metric's
    /// lengths place points evenly in the metric), at least `min` each.
    pub fn counts_for(&self, lengths: &[f64], min: u32) -> Vec<u32> {
        self.counts_relative_to(lengths, min, None)
    }

    /// As [`counts_for`](Self::counts_for), with the interval scheme's spacing taken
    /// from `mean` (`mean / k`) instead of the mean of `lengths` when it is given: a
    /// part of a mesh then gets the points the whole mesh would.
    pub fn counts_relative_to(&self, lengths: &[f64], min: u32, mean: Option<f64>) -> Vec<u32> {
        match *self {
            SteinerScheme::Fixed { count } => vec![count.max(min); lengths.len()],
            SteinerScheme::Interval { k } => {
                // Each length divided first, so that no sum of lengths overflows.
                let n = lengths.len().max(1) as f64;
                let mean = mean.unwrap_or_else(|| lengths.iter().map(|l| l / n).sum());
                let h = mean / k;
                lengths
                    .iter()
                    .map(|&l| ((l / h).round().min(u32::MAX as f64) as u32).max(min))
                    .collect()
            }
        }
    }

    /// The same scheme with another `k` (a point count, rounded down, for `Fixed`).
    pub fn with_k(self, k: f64) -> SteinerScheme {
        match self {
            SteinerScheme::Fixed { .. } => SteinerScheme::Fixed {
                count: k.min(u32::MAX as f64) as u32,
            },
            SteinerScheme::Interval { .. } => SteinerScheme::Interval { k },
        }
    }

    /// Whether the scheme is usable: `k` finite and > 0, or `count` ≥ 1.
    pub fn is_valid(&self) -> bool {
        match *self {
            SteinerScheme::Interval { k } => k.is_finite() && k > 0.0,
            SteinerScheme::Fixed { count } => count >= 1,
        }
    }
}

/// The spacing of a slot with `count` points, as a fraction of the edge: `1 / (count + 1)`.
#[inline]
pub fn slot_spacing(count: u32) -> f64 {
    1.0 / (count + 1) as f64
}

/// The parameter, from the slot's first corner, of point `i` (in slot order) of a slot
/// whose spacing is `spacing` (see [`slot_spacing`]). Every engine places points with
/// this one formula, so they all see bit-identical coordinates; the tracks engine
/// computes the spacing once per face entry, which keeps a division out of each test.
#[inline]
pub fn slot_param(i: u32, spacing: f64) -> f64 {
    (i + 1) as f64 * spacing
}

/// The Steiner points of one edge as seen along one face's slot (from corner `s` to
/// corner `s + 1`): node ids and positions in the face's frame, by index in slot order.
/// Every engine places points through it, so all see bit-identical coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlotPoints {
    line: EdgeLine,
    /// Node id of the edge's first point (from its lower vertex).
    first: u32,
    pub count: u32,
    /// The slot runs from the edge's higher vertex.
    reversed: bool,
    /// [`slot_spacing`] of the slot.
    spacing: f64,
}

impl SlotPoints {
    #[inline]
    pub fn new(line: EdgeLine, first: u32, count: u32, reversed: bool) -> SlotPoints {
        SlotPoints {
            line,
            first,
            count,
            reversed,
            spacing: slot_spacing(count),
        }
    }

    /// The same slot with no points (for a target arc that has only one slot).
    #[inline]
    pub fn empty(self) -> SlotPoints {
        SlotPoints { count: 0, ..self }
    }

    /// Slot-order index of the point numbered `index` from the edge's lower vertex (the
    /// map is its own inverse).
    #[inline(always)]
    pub fn slot_index(&self, index: u32) -> u32 {
        if self.reversed {
            self.count - 1 - index
        } else {
            index
        }
    }

    /// Node id and face point of point `i` in slot order.
    #[inline(always)]
    pub fn at(&self, i: u32) -> (u32, FacePoint) {
        let node = self.first + self.slot_index(i);
        (node, self.line.point(slot_param(i, self.spacing)))
    }
}

/// What a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// A mesh vertex.
    Vertex(u32),
    /// Steiner point `index` (from the edge's lower-id vertex) of `edge`.
    Steiner {
        /// The edge it lies on.
        edge: u32,
        /// Its index along the edge, 0-based from the lower-id vertex.
        index: u32,
    },
}

/// The Steiner points of a mesh: how many on each edge, and the node numbering.
#[derive(Clone, Debug)]
pub struct SteinerLayout {
    vertex_count: u32,
    /// Block `b` holds node ids `vertex_count + first[b] .. vertex_count + first[b + 1]`.
    first: Vec<u32>,
    /// The block of each edge, and the edge of each block.
    block_of_edge: Vec<u32>,
    edge_of_block: Vec<u32>,
    /// The block of each Steiner node (indexed by `node - vertex_count`).
    block_of: Vec<u32>,
    scheme: SteinerScheme,
}

impl SteinerLayout {
    /// Lays out Steiner points on `mesh` with `scheme`.
    ///
    /// # Errors
    /// [`Error::InvalidK`] for a scheme with no points (see [`SteinerScheme::is_valid`]);
    /// [`Error::TooLarge`] when vertices and Steiner points together would not fit
    /// 32-bit node ids.
    pub fn new<T: Topology>(mesh: &T, scheme: SteinerScheme) -> Result<SteinerLayout, Error> {
        if !scheme.is_valid() {
            return Err(Error::InvalidK { k: scheme.k() });
        }
        Self::with_counts(mesh, scheme, scheme.counts(mesh))
    }

    /// Lays out `counts[e]` points on each edge `e` of `mesh` (see
    /// [`SteinerScheme::counts_for`]); `scheme` is recorded as the one they came from.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when vertices and Steiner points together would not fit
    /// 32-bit node ids.
    pub(crate) fn with_counts<T: Topology>(
        mesh: &T,
        scheme: SteinerScheme,
        counts: Vec<u32>,
    ) -> Result<SteinerLayout, Error> {
        // Blocks in a spatial order, so that a wavefront finds its nodes close in memory.
        let order = crate::mesh::spatial_edge_order(mesh);
        Self::from_counts(mesh.vertex_count(), &counts, order, scheme)
    }

    /// No Steiner points at all: the nodes are the vertices.
    pub fn vertices_only<T: Topology>(mesh: &T) -> SteinerLayout {
        Self::from_counts(
            mesh.vertex_count(),
            &vec![0; mesh.edge_count()],
            (0..mesh.edge_count() as u32).collect(),
            SteinerScheme::Fixed { count: 0 },
        )
        .expect("a mesh's vertices fit its own u32 ids")
    }

    /// Lays out `counts[e]` points on each edge `e`, the edges' blocks in `order`.
    fn from_counts(
        vertex_count: usize,
        counts: &[u32],
        order: Vec<u32>,
        scheme: SteinerScheme,
    ) -> Result<SteinerLayout, Error> {
        // Node ids are u32 and NONE = u32::MAX is reserved: check before allocating.
        let total = vertex_count as u64 + counts.iter().map(|&c| c as u64).sum::<u64>();
        if total >= NONE as u64 {
            return Err(Error::TooLarge {
                what: "nodes (vertices and Steiner points)",
                count: total,
            });
        }
        let mut first = Vec::with_capacity(counts.len() + 1);
        let mut block_of_edge = vec![0; counts.len()];
        let mut offset = 0u32;
        first.push(0);
        for (block, &e) in order.iter().enumerate() {
            block_of_edge[e as usize] = block as u32;
            offset += counts[e as usize];
            first.push(offset);
        }
        let block_of = order
            .iter()
            .enumerate()
            .flat_map(|(b, &e)| std::iter::repeat_n(b as u32, counts[e as usize] as usize))
            .collect();
        Ok(SteinerLayout {
            vertex_count: vertex_count as u32,
            first,
            block_of_edge,
            edge_of_block: order,
            block_of,
            scheme,
        })
    }

    /// The scheme it was built with.
    pub fn scheme(&self) -> SteinerScheme {
        self.scheme
    }

    /// Vertices plus Steiner points.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.vertex_count as usize + self.block_of.len()
    }

    /// Number of Steiner points (all edges).
    pub fn steiner_count(&self) -> usize {
        self.block_of.len()
    }

    /// Number of mesh vertices (node ids below this are vertices).
    #[inline]
    pub fn vertex_count(&self) -> u32 {
        self.vertex_count
    }

    /// How many points edge `e` carries.
    #[inline]
    pub fn count(&self, e: u32) -> u32 {
        self.edge_nodes(e).len() as u32
    }

    /// The node ids of edge `e`'s points, from its lower-id vertex.
    #[inline]
    pub fn edge_nodes(&self, e: u32) -> Range<u32> {
        self.block_nodes(self.block_of_edge(e))
    }

    /// The block of Steiner node `node` (which must not be a vertex).
    #[inline]
    pub(crate) fn block(&self, node: u32) -> u32 {
        self.block_of[(node - self.vertex_count) as usize]
    }

    /// The node ids of block `b`.
    #[inline]
    pub(crate) fn block_nodes(&self, b: u32) -> Range<u32> {
        self.vertex_count + self.first[b as usize]..self.vertex_count + self.first[b as usize + 1]
    }

    /// The edge whose points are block `b`.
    #[inline]
    pub(crate) fn edge_of_block(&self, b: u32) -> u32 {
        self.edge_of_block[b as usize]
    }

    /// The block of edge `e`'s points.
    #[inline]
    pub(crate) fn block_of_edge(&self, e: u32) -> u32 {
        self.block_of_edge[e as usize]
    }

    /// What node `node` is.
    #[inline]
    pub fn kind(&self, node: u32) -> NodeKind {
        if node < self.vertex_count {
            NodeKind::Vertex(node)
        } else {
            let block = self.block(node);
            NodeKind::Steiner {
                edge: self.edge_of_block[block as usize],
                index: node - self.vertex_count - self.first[block as usize],
            }
        }
    }

    /// The parameter of point `index` of edge `e`, from its lower-id vertex (the formula
    /// the engines place points with, [`slot_param`]).
    #[inline]
    pub fn param(&self, e: u32, index: u32) -> f64 {
        slot_param(index, slot_spacing(self.count(e)))
    }

    /// Position of `node` in the frame of face `f`; the node must lie on `f`'s closure.
    #[inline]
    pub fn point_in_face<T: Topology>(&self, mesh: &T, node: u32, f: u32) -> FacePoint {
        match self.kind(node) {
            NodeKind::Vertex(v) => {
                let c = mesh
                    .corner_of(f, v)
                    .expect("vertex node is a corner of the face");
                mesh.frame(f).corner(c)
            }
            NodeKind::Steiner { edge, index } => {
                let slot = mesh
                    .edge_slot(f, edge)
                    .expect("Steiner node lies on the face");
                self.point_on_slot(mesh, f, slot, index)
            }
        }
    }

    /// Position of point `index` (numbered from the edge's lower vertex) of the edge in
    /// slot `slot` of face `f`.
    #[inline]
    pub fn point_on_slot<T: Topology>(
        &self,
        mesh: &T,
        f: u32,
        slot: usize,
        index: u32,
    ) -> FacePoint {
        let points = self.slot_points(mesh, f, slot);
        points.at(points.slot_index(index)).1
    }

    /// The points of the edge in slot `slot` of face `f`, as seen along the slot.
    #[inline]
    pub(crate) fn slot_points<T: Topology>(&self, mesh: &T, f: u32, slot: usize) -> SlotPoints {
        let e = mesh.face_edges(f)[slot];
        SlotPoints::new(
            mesh.frame(f).edge_line(slot),
            self.edge_nodes(e).start,
            self.count(e),
            mesh.slot_is_reversed(f, slot),
        )
    }

    /// Every node on the boundary of face `f` with its point in the face's frame: the
    /// three corners, then each slot's Steiner points.
    pub fn face_nodes<'s, T: Topology>(
        &'s self,
        mesh: &'s T,
        f: u32,
    ) -> impl Iterator<Item = (u32, FacePoint)> + 's {
        let frame = mesh.frame(f);
        let corners = mesh.face_vertices(f);
        (0..3)
            .map(move |c| (corners[c], frame.corner(c)))
            .chain((0..3).flat_map(move |s| {
                let points = self.slot_points(mesh, f, s);
                (0..points.count).map(move |i| points.at(i))
            }))
    }

    /// Edges of the mesh the layout was made for.
    pub fn edge_count(&self) -> usize {
        self.block_of_edge.len()
    }

    /// `node` as a point of the surface: its vertex, or its edge and parameter.
    pub fn surface_point(&self, node: u32) -> SurfacePoint {
        match self.kind(node) {
            NodeKind::Vertex(v) => SurfacePoint::Vertex(v),
            NodeKind::Steiner { edge, index } => SurfacePoint::Edge {
                edge,
                t: self.param(edge, index),
            },
        }
    }

    /// World position of `node`.
    pub fn position<T: Topology>(&self, mesh: &T, node: u32) -> glam::DVec3 {
        match self.kind(node) {
            NodeKind::Vertex(v) => mesh.position(v),
            NodeKind::Steiner { edge, index } => {
                let [a, b] = mesh.edge_vertices(edge);
                mesh.position(a)
                    .lerp(mesh.position(b), self.param(edge, index))
            }
        }
    }
}
