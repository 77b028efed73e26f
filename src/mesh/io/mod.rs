//! Reading and writing mesh files.
//!
//! Readers: OBJ, PLY (ascii and binary), OFF, STL (ascii and binary, vertices welded) and
//! the medial-axis `.ma` format. Writers: PLY with a per-vertex `distance` and colours,
//! OBJ polylines, and [`write_atomically`] for anything else. Every writer writes to a
//! temporary file beside the target and renames it at the end, so a failure never leaves
//! a partial file.
//!
//! Vertex ids are the file's: the *i*-th vertex of the file is vertex *i* of the mesh,
//! whether or not a face uses it, so per-vertex data kept beside a mesh file (reference
//! distances, source vertices) stays valid. Polygons are fan-triangulated.
//!
//! Every error names the file, and the line (text formats) or the element index (binary
//! formats, and PLY faces) where it can.
//!
//! ```
//! use geotracks::mesh::{io};
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("square.off");
//! std::fs::write(&path, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")?;
//! let mesh = io::read_mesh(&path)?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 2));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod ma;
mod obj;
mod off;
mod ply;
mod stl;
mod text;
mod write;

pub use write::{
    write_atomically, write_obj_lines, write_obj_lines_to, write_obj_polylines,
    write_ply_with_distance, write_ply_with_distance_to,
};

use super::{MeshError, TriMesh};
use std::path::Path;

/// A medial axis read from a `.ma` file: its sheets (faces), its curves (free edges) and
/// the medial ball radius at each vertex.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct MedialAxis {
    /// The sheets, with the free edges as line elements; `None` when no face is usable
    /// (a medial axis made only of curves).
    pub surface: Option<TriMesh>,
    /// Every vertex position in file order (the surface's positions, when there is one).
    pub positions: Vec<[f64; 3]>,
    /// Free edges: listed edges that are no edge of a kept face, each once, as
    /// `[lower, higher]` vertex pairs, sorted.
    pub free_edges: Vec<[u32; 2]>,
    /// Medial ball radius per vertex.
    pub radii: Vec<f64>,
}

/// The extensions [`read_mesh`] knows, for [`MeshError::UnknownFormat`].
const READABLE: &str = "obj, ply, off, stl, ma";

/// Reads a mesh, choosing the format by the file's extension (`obj`, `ply`, `off`,
/// `stl`, `ma`; any case). For `.ma` the medial ball radii are dropped; use
/// [`read_medial_axis`] to keep them.
///
/// Degenerate faces are dropped (see [`TriMesh::dropped_faces`]); vertices keep their file
/// order.
///
/// # Errors
/// - [`MeshError::UnknownFormat`] for another extension, [`MeshError::Io`] if the file
///   cannot be read, [`MeshError::EmptyFile`] if it holds no data (only blanks or
///   comments).
/// - [`MeshError::Parse`] for a malformed or truncated file, with the line (0 in binary
///   data, whose message names the element instead).
/// - A content error ([`MeshError::IndexOutOfRange`], [`MeshError::EdgeIndexOutOfRange`],
///   [`MeshError::NonFiniteVertex`], [`MeshError::NoUsableFace`]) wrapped in
///   [`MeshError::AtLine`] where the line is known, else in [`MeshError::InFile`].
pub fn read_mesh(path: impl AsRef<Path>) -> Result<TriMesh, MeshError> {
    let path = path.as_ref();
    let extension = lowercase_extension(path);
    let reader: fn(&Path, &[u8]) -> Result<TriMesh, MeshError> = match extension.as_deref() {
        Some("obj") => obj::read,
        Some("ply") => ply::read,
        Some("off") => off::read,
        Some("stl") => stl::read,
        Some("ma") => ma::read_surface,
        _ => {
            return Err(MeshError::UnknownFormat {
                path: path.to_path_buf(),
                expected: READABLE,
            })
        }
    };
    reader(path, &read_bytes(path)?)
}

/// A file's extension in lower case, for choosing a format (`None` without one).
pub(crate) fn lowercase_extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Reads an OBJ held in memory (a mesh bundled with `include_bytes!`, say). Errors name
/// the file `<memory>`.
///
/// # Errors
/// As [`read_mesh`] for an OBJ file, except that there is no I/O.
pub fn read_obj_bytes(bytes: &[u8]) -> Result<TriMesh, MeshError> {
    let path = Path::new("<memory>");
    if text::is_blank(bytes) {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    obj::read(path, bytes)
}

/// Reads a `.ma` medial axis with its radii (whatever the file's extension).
///
/// # Errors
/// As [`read_mesh`]; also [`MeshError::Parse`] if the counts in the header do not match
/// the `v`, `e` and `f` lines, or a radius is negative or not finite;
/// [`MeshError::NoUsableFace`] if it has neither a usable face nor a free edge. A medial
/// axis of curves only is read with [`MedialAxis::surface`] `None` (whereas
/// [`read_mesh`] refuses it: there is no surface to measure on).
pub fn read_medial_axis(path: impl AsRef<Path>) -> Result<MedialAxis, MeshError> {
    let path = path.as_ref();
    ma::read(path, &read_bytes(path)?, true)
}

/// The whole file: every format is parsed from memory, which also lets STL be told apart
/// by its size. A file of only whitespace is empty whatever its format.
fn read_bytes(path: &Path) -> Result<Vec<u8>, MeshError> {
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if text::is_blank(&bytes) {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    Ok(bytes)
}
