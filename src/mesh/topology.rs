//! [`Topology`]: what the engines, fields and queries ask of a surface, so that they run
//! on any triangulated surface that can answer it: a [`TriMesh`](super::TriMesh) with
//! its edge table, or a surface whose adjacency is computed rather than stored (a
//! terrain raster's cells, split into triangles, in `geotracks-terrain`).

use super::FaceFrame;
use geotracks_metrics::FaceGeometry;
use glam::DVec3;
use std::ops::Deref;

/// A triangulated surface of any topology, as the engines see it: faces, edges and
/// vertices with dense `u32` ids, the adjacency between them, positions, and each
/// face's flat frame.
///
/// The contract an implementor keeps:
///
/// - **Dense ids.** Faces are `0..face_count()`, edges `0..edge_count()`, vertices
///   `0..vertex_count()`. Every face has area (a frame with `y2 > 0`); every edge
///   belongs to at least one face; a vertex may belong to none (it is then reached by
///   nothing but a wire).
/// - **Faces in cyclic order.** [`face_vertices`](FaceGeometry::face_vertices) lists a
///   face's corners in a fixed order, and [`face_edges`](Topology::face_edges) its
///   edges in the same order: edge `i` joins corner `i` to corner `(i + 1) % 3`.
/// - **Edges between any number of faces.** [`edge_faces`](Topology::edge_faces) may
///   list one face (a boundary), two, or more (a non-manifold edge, as on a medial
///   axis): the engines carry distances from an edge into every face around it.
///   [`edge_vertices`](Topology::edge_vertices) lists the lower vertex id first;
///   Steiner points on an edge are numbered from that end.
/// - **Wires.** [`vertex_wires`](Topology::vertex_wires) lists, per vertex, the
///   vertices joined to it by a curve without area (a medial axis's free edges), which
///   distances travel vertex to vertex. Both ends list each other.
/// - **Frames agree with positions.** [`frame`](Topology::frame) is the face's
///   triangle laid flat: corner 0 at the origin, corner 1 on the positive u axis at the
///   length of edge 0, corner 2 above it. The default computes it from the positions;
///   an implementor may store it.
///
/// Lists of neighbours come back as [`Topology::Ids`]: a borrowed slice for a mesh that
/// stores them, a small array for one that computes them. Either reads as a `&[u32]`.
///
/// Every engine, the Steiner layout, fields, paths, isolines and regions are generic
/// over it and monomorphised: nothing is looked up through a pointer in their loops,
/// and a solver on a [`TriMesh`](super::TriMesh) does the same work as before the trait
/// existed (the same counts, within 1 % of the instructions: the guide's Performance
/// page).
///
/// ```
/// use geotracks::mesh::{Topology, TriMesh};
/// use geotracks::metrics::FaceGeometry;
///
/// /// The number of boundary edges of any surface.
/// fn boundary_edges<T: Topology>(surface: &T) -> usize {
///     (0..surface.edge_count() as u32).filter(|&e| surface.edge_faces(e).len() == 1).count()
/// }
/// let square = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// assert_eq!(boundary_edges(&square), 4);
/// assert_eq!(square.face_vertices(1), [0, 2, 3]);
/// # Ok::<(), geotracks::mesh::MeshError>(())
/// ```
pub trait Topology: FaceGeometry + Send + Sync {
    /// A list of ids (faces around an edge or a vertex, edges around a vertex, wires):
    /// anything that reads as a slice.
    type Ids<'a>: Deref<Target = [u32]>
    where
        Self: 'a;

    /// Number of edges that belong to at least one face.
    fn edge_count(&self) -> usize;
    /// The edges of face `f`: edge `i` joins corner `i` to corner `(i + 1) % 3`.
    fn face_edges(&self, f: u32) -> [u32; 3];
    /// The two vertices of edge `e`, lower id first.
    fn edge_vertices(&self, e: u32) -> [u32; 2];
    /// The faces around edge `e`: one, two or more.
    fn edge_faces(&self, e: u32) -> Self::Ids<'_>;
    /// The faces around vertex `v` (none for a vertex that no face uses).
    fn vertex_faces(&self, v: u32) -> Self::Ids<'_>;
    /// The face edges around vertex `v`.
    fn vertex_edges(&self, v: u32) -> Self::Ids<'_>;
    /// The vertices joined to `v` by a wire (a line element that is no face edge).
    fn vertex_wires(&self, v: u32) -> Self::Ids<'_>;
    /// The position of vertex `v`.
    fn position(&self, v: u32) -> DVec3;

    /// Face `f` laid flat ([`FaceFrame`]). The default computes it from the
    /// positions of its corners, as [`FaceFrame::of_triangle`] does.
    #[inline]
    fn frame(&self, f: u32) -> FaceFrame {
        FaceFrame::of_triangle(self.face_vertices(f).map(|v| self.position(v))).unwrap_or(
            FaceFrame {
                l01: 0.0,
                x2: 0.0,
                y2: 0.0,
            },
        )
    }

    /// Whether faces and edges are numbered in a spatially coherent order already (a
    /// grid's tiles): solvers then keep the order rather than sort them along a
    /// space-filling curve.
    fn is_spatially_ordered(&self) -> bool {
        false
    }

    /// Which corner of face `f` vertex `v` is, if any.
    #[inline]
    fn corner_of(&self, f: u32, v: u32) -> Option<usize> {
        self.face_vertices(f).iter().position(|&c| c == v)
    }

    /// Which of face `f`'s edges `e` is, if any.
    #[inline]
    fn edge_slot(&self, f: u32, e: u32) -> Option<usize> {
        self.face_edges(f).iter().position(|&c| c == e)
    }

    /// Whether slot `s` of face `f` (from corner `s` to corner `s + 1`) runs from its
    /// edge's higher vertex, so that the edge's points, numbered from its lower vertex,
    /// come in reverse order along the slot.
    #[inline]
    fn slot_is_reversed(&self, f: u32, s: usize) -> bool {
        // Edges list their lower vertex first: the slot runs from the higher one.
        let t = self.face_vertices(f);
        t[s] > t[(s + 1) % 3]
    }

    /// The world position of barycentric point `bary` of face `f`.
    #[inline]
    fn point(&self, f: u32, bary: [f64; 3]) -> DVec3 {
        let [a, b, c] = self.face_vertices(f).map(|v| self.position(v));
        bary[0] * a + bary[1] * b + bary[2] * c
    }

    /// The Euclidean length of edge `e`.
    #[inline]
    fn edge_length(&self, e: u32) -> f64 {
        let [a, b] = self.edge_vertices(e);
        super::trimesh::length(self.position(b) - self.position(a))
    }

    /// The wires, each once as `[lower, higher]`.
    fn wires(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        (0..self.vertex_count() as u32).flat_map(move |a| {
            let around = self.vertex_wires(a);
            (0..around.len()).filter_map(move |i| (a < around[i]).then_some([a, around[i]]))
        })
    }

    /// Mean Euclidean edge length (0 without edges).
    fn mean_edge_length(&self) -> f64 {
        let n = self.edge_count();
        if n == 0 {
            return 0.0;
        }
        // Each length divided first, so that no sum of lengths near 1e300 overflows.
        (0..n as u32)
            .map(|e| self.edge_length(e) / n as f64)
            .sum::<f64>()
    }

    /// The corners of the box around the vertices that faces use, lowest first
    /// (a vertex no face uses may have any position: a grid's missing samples do).
    fn bounding_box(&self) -> [DVec3; 2] {
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for v in 0..self.vertex_count() as u32 {
            if !self.vertex_faces(v).is_empty() || !self.vertex_wires(v).is_empty() {
                let p = self.position(v);
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
        [lo, hi]
    }
}

/// Up to eight ids held inline: the lists a computed topology hands out
/// ([`Topology::Ids`]) without allocating.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InlineIds {
    len: u8,
    ids: [u32; 8],
}

impl InlineIds {
    /// An empty list.
    pub const EMPTY: Self = Self {
        len: 0,
        ids: [0; 8],
    };

    /// Appends `id`.
    ///
    /// # Panics
    /// If the list holds eight ids already.
    #[inline]
    pub fn push(&mut self, id: u32) {
        self.ids[self.len as usize] = id;
        self.len += 1;
    }
}

impl Deref for InlineIds {
    type Target = [u32];
    #[inline]
    fn deref(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }
}

/// A mesh answers from its tables: the lists are slices of them, the frames stored.
/// (Slots, corners, points and lengths come from the trait's own methods, on these.)
impl Topology for super::TriMesh {
    type Ids<'a> = &'a [u32];

    #[inline]
    fn edge_count(&self) -> usize {
        self.edge_count()
    }
    #[inline]
    fn face_edges(&self, f: u32) -> [u32; 3] {
        self.face_edges(f)
    }
    #[inline]
    fn edge_vertices(&self, e: u32) -> [u32; 2] {
        self.edge_vertices(e)
    }
    #[inline]
    fn edge_faces(&self, e: u32) -> &[u32] {
        self.edge_faces(e)
    }
    #[inline]
    fn vertex_faces(&self, v: u32) -> &[u32] {
        self.vertex_faces(v)
    }
    #[inline]
    fn vertex_edges(&self, v: u32) -> &[u32] {
        self.vertex_edges(v)
    }
    #[inline]
    fn vertex_wires(&self, v: u32) -> &[u32] {
        self.vertex_wires(v)
    }
    #[inline]
    fn position(&self, v: u32) -> DVec3 {
        self.position(v)
    }
    #[inline]
    fn frame(&self, f: u32) -> FaceFrame {
        *self.frame(f)
    }
    fn is_spatially_ordered(&self) -> bool {
        self.is_spatially_ordered()
    }
    /// Around every vertex, used or not (a mesh's unreferenced vertices are points the
    /// caller gave).
    fn bounding_box(&self) -> [DVec3; 2] {
        super::bounding_box(self.positions().iter().map(|p| p.to_array())).map(DVec3::from)
    }
}

impl IntoIterator for InlineIds {
    type Item = u32;
    type IntoIter = std::iter::Take<std::array::IntoIter<u32, 8>>;
    fn into_iter(self) -> Self::IntoIter {
        self.ids.into_iter().take(self.len as usize)
    }
}
