//! Triangle meshes of any topology: [`TriMesh`] (an edge table where an edge may have any
//! number of faces; no half-edges), per-face local 2D frames, a [`MeshReport`], [`Betti`]
//! numbers over GF(2), and the file readers and writers in [`io`].

mod csr;
mod error;
mod homology;
pub mod io;
mod order;
mod report;
mod sets;
mod topology;
mod trimesh;

pub use csr::Csr;
pub(crate) use error::try_grow;
pub use error::try_reserve;
pub use error::MeshError;
pub use homology::{graph_betti_numbers, Betti};
pub(crate) use homology::{unique_edges, CycleSheets};
pub(crate) use order::{spatial_edge_order, spatial_face_order};
pub(crate) use report::bounding_box;
pub(crate) use report::vertex_is_manifold;
pub use report::{MeshReport, SurfaceReport};
pub(crate) use sets::DisjointSets;
pub use topology::{InlineIds, Topology};
pub use trimesh::{face_axes, DroppedFace, EdgeLine, FaceFrame, TriMesh, MAX_COORDINATE};

/// Ids are dense `u32`; this marks "none" (no parent, no face).
pub const NONE: u32 = u32::MAX;
