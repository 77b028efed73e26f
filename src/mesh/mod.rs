//! Triangle meshes of any topology: the [`Topology`] trait the engine is written against,
//! [`TriMesh`] (an edge table where an edge may have any number of faces), per-face local
//! 2D frames, a [`MeshReport`], and the file readers and writers in [`io`].

mod csr;
mod error;
pub mod io;
mod order;
mod report;
mod sets;
mod trimesh;

pub use csr::Csr;
pub use error::MeshError;
pub(crate) use order::morton_order;
pub use report::{MeshReport, SurfaceReport};
pub(crate) use sets::DisjointSets;
pub use trimesh::{DroppedFace, EdgeLine, FaceFrame, TriMesh, MAX_COORDINATE};

/// Ids are dense `u32`; this marks "none" (no parent, no face).
pub const NONE: u32 = u32::MAX;

/// The connectivity the engine needs, and nothing more: no half-edges, so an edge may
/// have one face (boundary), two (manifold) or any number (non-manifold).
///
/// Face `f` with vertices `[a, b, c]` has edges `[ab, bc, ca]` in that fixed cyclic
/// order: edge `i` joins corner `i` to corner `(i + 1) % 3`. An edge's two vertices are
/// stored lower id first, and Steiner points on it are numbered from that end.
pub trait Topology {
    /// Number of vertices (including unreferenced ones).
    fn vertex_count(&self) -> usize;
    /// Number of faces.
    fn face_count(&self) -> usize;
    /// Number of edges that belong to at least one face.
    fn edge_count(&self) -> usize;
    /// The vertices of face `f`, in its cyclic order.
    fn face_vertices(&self, f: u32) -> [u32; 3];
    /// The edges of face `f`: edge `i` joins corner `i` to corner `(i + 1) % 3`.
    fn face_edges(&self, f: u32) -> [u32; 3];
    /// The two vertices of edge `e`, lower id first.
    fn edge_vertices(&self, e: u32) -> [u32; 2];
    /// The faces around edge `e` (1, 2 or more).
    fn edge_faces(&self, e: u32) -> &[u32];
    /// The faces around vertex `v` (empty for an unreferenced vertex).
    fn vertex_faces(&self, v: u32) -> &[u32];
    /// The face edges around vertex `v`.
    fn vertex_edges(&self, v: u32) -> &[u32];
}
