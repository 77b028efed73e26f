//! Reading and writing mesh files.
//!
//! Readers: OBJ, PLY (ascii and binary; faces and triangle strips), OFF, STL (ascii and
//! binary, vertices welded) and the medial-axis `.ma` format. Writers: PLY with a per-vertex `distance` and colours,
//! OBJ polylines, `.ma` medial axes ([`write_medial_axis`]), and [`write_atomically`] for anything else. Every writer writes to a
//! temporary file beside the target and renames it at the end, so a failure never leaves
//! a partial file.
//!
//! Vertex ids are the file's: the *i*-th vertex of the file is vertex *i* of the mesh,
//! whether or not a face uses it, so per-vertex data kept beside a mesh file (reference
//! distances, source vertices) stays valid. Polygons are fan-triangulated.
//!
//! Every error names the file, and the line (text formats) or the element index (binary
//! formats) where it can. Counts a header declares are checked against the size of the
//! file before anything is allocated for them, so a corrupt or hostile header is refused
//! with an error instead of exhausting memory.
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
pub mod sniff;
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

impl MedialAxis {
    /// What the axis is made of ([`TriMesh::report`] of its sheets and free edges, or,
    /// for an axis of curves only, the same report with no faces), with its Betti
    /// numbers over GF(2).
    pub fn report(&self) -> super::MeshReport {
        match &self.surface {
            Some(mesh) => mesh.report(),
            None => super::MeshReport::of_curves(&self.positions, &self.free_edges),
        }
    }

    /// The length of the diagonal of the bounding box of all its vertices: the scale
    /// that percentages of a skeleton's pruning threshold refer to.
    pub fn diagonal(&self) -> f64 {
        let [lo, hi] = super::report::bounding_box(self.positions.iter().copied());
        (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
    }

    /// A medial axis built in memory: sheets (`triangles`, indices into `positions`),
    /// curves (`edges`; an edge of a kept triangle is no curve) and the medial ball
    /// radius of each vertex. Vertices at identical positions are merged (the first
    /// one's radius is kept) and degenerate triangles dropped, as when a `.ma` file is
    /// read with welding.
    ///
    /// # Errors
    /// [`MeshError::IndexOutOfRange`] for an index past `positions`,
    /// [`MeshError::NonFiniteVertex`] for a position that is not finite,
    /// [`MeshError::NoUsableFace`] when neither a usable triangle nor a curve is left.
    ///
    /// # Panics
    /// If `radii` and `positions` differ in length.
    ///
    /// ```
    /// use geotracks::mesh::io::MedialAxis;
    /// // Two triangles of a unit square, the second one naming a copy of vertex 1.
    /// let positions = vec![
    ///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0],
    /// ];
    /// let axis = MedialAxis::from_parts(
    ///     positions,
    ///     vec![0.5, 0.4, 0.3, 0.2, 0.1],
    ///     vec![[0, 1, 2], [4, 3, 2]],
    ///     vec![],
    /// )?;
    /// // The copy was merged (keeping the first radius): the triangles share an edge.
    /// assert_eq!(axis.positions.len(), 4);
    /// assert_eq!(axis.radii[1], 0.4);
    /// assert_eq!(axis.surface.as_ref().map(|m| m.edge_count()), Some(5));
    /// # Ok::<(), geotracks::mesh::MeshError>(())
    /// ```
    pub fn from_parts(
        positions: Vec<[f64; 3]>,
        radii: Vec<f64>,
        triangles: Vec<[u32; 3]>,
        edges: Vec<[u32; 2]>,
    ) -> Result<MedialAxis, MeshError> {
        assert_eq!(positions.len(), radii.len(), "one radius per position");
        ma::from_parts(positions, radii, triangles, edges)
    }

    /// Betti numbers over GF(2) of the sheets and free edges together: what a skeleton
    /// of the axis keeps (components b₀, independent cycles b₁).
    pub fn betti_numbers(&self) -> super::Betti {
        match &self.surface {
            Some(mesh) => mesh.betti_numbers(),
            None => super::graph_betti_numbers(self.positions.len(), &self.free_edges),
        }
    }
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
/// - [`MeshError::IsDirectory`] for a directory, [`MeshError::NotAFile`] for a named
///   pipe, socket or device (refused before it is opened), [`MeshError::UnknownFormat`]
///   for another extension, [`MeshError::Io`] if the file cannot be read,
///   [`MeshError::EmptyFile`] if it holds no data (only blanks or comments).
/// - [`MeshError::OutOfMemory`] (in [`MeshError::InFile`]) if the memory the file needs
///   cannot be had.
/// - [`MeshError::WrongFormat`] if the content is not the extension's format (binary
///   data as OBJ, OFF or `.ma`; a PLY file named `.obj`; text that is no STL named
///   `.stl`).
/// - [`MeshError::ImplausibleCount`] if a count in the header (PLY elements, OFF and
///   `.ma` counts, binary STL triangles) is more than the rest of the file can hold;
///   nothing is allocated for it.
/// - [`MeshError::Parse`] for a malformed or truncated file, with the line (0 in binary
///   data, whose message names the element instead).
/// - A content error ([`MeshError::IndexOutOfRange`], [`MeshError::EdgeIndexOutOfRange`],
///   [`MeshError::NonFiniteVertex`], [`MeshError::NoUsableFace`]) wrapped in
///   [`MeshError::AtLine`] where the line is known, else in [`MeshError::InFile`].
pub fn read_mesh(path: impl AsRef<Path>) -> Result<TriMesh, MeshError> {
    let path = path.as_ref();
    refuse_directory(path)?;
    read_mesh_with(path, &ReadOptions::DEFAULT)
}

/// How [`read_mesh_with`] reads a mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// Merge vertices at exactly the same position (bit for bit; `-0.0` and `0.0` are
    /// one), for files whose seams split the surface: texture or normal seams often
    /// duplicate vertices, so faces on either side share no edge and distances cannot
    /// cross. The welded vertices are numbered in the order of their first copy in the
    /// file, so vertex ids (sources, per-vertex densities, output rows) then refer to
    /// the welded mesh, not the file; `geotracks info --weld` prints its vertex count.
    /// Faces keep the file's numbering (a per-face tensor file stays valid); a face
    /// that welding collapses is dropped as degenerate. STL is always welded. Default:
    /// `false`.
    pub weld: bool,
}

impl ReadOptions {
    /// No welding: vertices are the file's.
    pub const DEFAULT: ReadOptions = ReadOptions { weld: false };

    /// Sets [`ReadOptions::weld`].
    pub const fn with_weld(mut self, weld: bool) -> Self {
        self.weld = weld;
        self
    }
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions::DEFAULT
    }
}

/// [`read_mesh`] with options (welding vertices at identical positions).
///
/// # Errors
/// As [`read_mesh`].
///
/// ```
/// use geotracks::mesh::io::{read_mesh_with, ReadOptions};
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("seam.obj");
/// // Two triangles that meet along x = 1, each with its own copies of the seam.
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 0 0\nv 2 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 6\n")?;
/// let split = read_mesh_with(&path, &ReadOptions::DEFAULT)?;
/// assert_eq!(split.report().components, 2);
/// let welded = read_mesh_with(&path, &ReadOptions::DEFAULT.with_weld(true))?;
/// assert_eq!((welded.vertex_count(), welded.report().components), (4, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_mesh_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<TriMesh, MeshError> {
    let path = path.as_ref();
    refuse_directory(path)?;
    let (reader, check) = reader_for(path)?;
    reader(path, &read_bytes(path, check)?, options.weld)
}

/// Builds a reader's mesh, welding first if asked; errors name the file.
fn build(
    path: &Path,
    mut positions: Vec<[f64; 3]>,
    mut triangles: Vec<[u32; 3]>,
    weld: bool,
) -> Result<TriMesh, MeshError> {
    if weld {
        if let Some(map) = weld_positions(&mut positions) {
            for t in &mut triangles {
                *t = t.map(|v| map.get(v as usize).copied().unwrap_or(v));
            }
        }
    }
    TriMesh::new(positions, triangles).map_err(|e| e.in_file(path))
}

/// Merges positions that are bit-identical (`-0.0` as `0.0`), keeping the first copy
/// of each in file order; returns the map from old to new vertex ids, or `None` when
/// nothing merges or a position is not finite (left for [`TriMesh::new`] to report by
/// its file index).
fn weld_positions(positions: &mut Vec<[f64; 3]>) -> Option<Vec<u32>> {
    if positions.iter().flatten().any(|c| !c.is_finite()) {
        return None;
    }
    let first = first_copies(positions);
    let mut new_id = vec![0u32; positions.len()];
    let mut welded = Vec::with_capacity(positions.len());
    for (i, &f) in first.iter().enumerate() {
        if f as usize == i {
            new_id[i] = welded.len() as u32;
            welded.push(positions[i]);
        }
    }
    if welded.len() == positions.len() {
        return None;
    }
    *positions = welded;
    Some(first.iter().map(|&f| new_id[f as usize]).collect())
}

/// For each position, the index of the first one bit-identical to it (`-0.0` as `0.0`,
/// so that the two zeros are one point): itself for a first copy.
pub(crate) fn first_copies(positions: &[[f64; 3]]) -> Vec<u32> {
    let mut first: std::collections::HashMap<[u64; 3], u32> =
        std::collections::HashMap::with_capacity(positions.len());
    (0..positions.len() as u32)
        .map(|i| {
            *first
                .entry(positions[i as usize].map(|c| (c + 0.0).to_bits()))
                .or_insert(i)
        })
        .collect()
}

/// Whether `path` names a medial axis file: its extension is `ma`, in any case.
pub fn is_medial_axis_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ma"))
}

/// [`read_mesh`] on a file held in memory: `path` chooses the format by its extension
/// and names the file in errors; nothing is read from disk.
///
/// # Errors
/// As [`read_mesh`], without [`MeshError::Io`] and [`MeshError::IsDirectory`].
///
/// ```
/// use geotracks::mesh::io;
/// let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let mesh = io::read_mesh_bytes("triangle.off", off)?;
/// assert_eq!(mesh.face_count(), 1);
/// # Ok::<(), geotracks::mesh::MeshError>(())
/// ```
pub fn read_mesh_bytes(path: impl AsRef<Path>, bytes: &[u8]) -> Result<TriMesh, MeshError> {
    let path = path.as_ref();
    let (reader, _) = reader_for(path)?;
    if text::is_blank(bytes) {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    reader(path, bytes, false)
}

/// A reader of bytes into a mesh, for one format; the flag asks it to weld.
type Reader = fn(&Path, &[u8], bool) -> Result<TriMesh, MeshError>;

/// What a format checks from the start of a file (at most [`HEAD`] bytes) and the
/// file's size before the rest is read: the start's signature, counts a header declares
/// against the size. Returns how many bytes of the file the reader needs (a binary STL
/// ignores bytes after its triangles).
type Check = fn(&Path, &[u8], u64) -> Result<u64, MeshError>;

/// The reader for `path`'s extension, and its check of the file's start.
fn reader_for(path: &Path) -> Result<(Reader, Check), MeshError> {
    Ok(match lowercase_extension(path).as_deref() {
        Some("obj") => (obj::read, obj::check),
        Some("ply") => (ply::read, ply::check),
        Some("off") => (off::read, off::check),
        Some("stl") => (stl::read, stl::check),
        Some("ma") => (ma::read_surface, ma::check),
        _ => {
            return Err(MeshError::UnknownFormat {
                path: path.to_path_buf(),
                expected: READABLE,
            })
        }
    })
}

/// A file's extension in lower case, for choosing a format (`None` without one).
/// Public so that the readers of the sibling crates choose by extension as the mesh
/// readers do.
pub fn lowercase_extension(path: &Path) -> Option<String> {
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
    obj::read(path, bytes, false)
}

/// Writes a medial axis as a `.ma` file (see [`read_medial_axis`]): every vertex with
/// its radius, every edge (the sheets' and the free ones) and every face. Written to a
/// temporary file and renamed, so a failure leaves nothing behind.
///
/// # Errors
/// [`MeshError::NonFiniteVertex`] for a position or radius that is not finite;
/// [`MeshError::Io`] if the file cannot be written.
pub fn write_medial_axis(path: impl AsRef<Path>, axis: &MedialAxis) -> Result<(), MeshError> {
    if let Some(vertex) = first_non_finite(axis) {
        let position = axis.positions[vertex];
        return Err(MeshError::NonFiniteVertex { vertex, position });
    }
    write_atomically(path.as_ref(), |w| ma::write_to(w, axis))
}

/// As [`write_medial_axis`], into `w`.
///
/// # Errors
/// What `w` returns; an error of kind [`std::io::ErrorKind::InvalidInput`] for a
/// position or radius that is not finite.
pub fn write_medial_axis_to(w: &mut dyn std::io::Write, axis: &MedialAxis) -> std::io::Result<()> {
    if let Some(i) = first_non_finite(axis) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("medial axis vertex {i} is not finite"),
        ));
    }
    ma::write_to(w, axis)
}

/// The first vertex of `axis` whose position or radius is not finite, which `.ma`
/// cannot hold.
fn first_non_finite(axis: &MedialAxis) -> Option<usize> {
    (0..axis.positions.len())
        .find(|&i| !axis.positions[i].iter().all(|c| c.is_finite()) || !axis.radii[i].is_finite())
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
    refuse_directory(path)?;
    ma::read(path, &read_bytes(path, ma::check)?, true, false)
}

/// [`read_medial_axis`] on a `.ma` file held in memory; errors name `path`.
///
/// # Errors
/// As [`read_medial_axis`], without [`MeshError::Io`] and [`MeshError::IsDirectory`].
pub fn read_medial_axis_bytes(
    path: impl AsRef<Path>,
    bytes: &[u8],
) -> Result<MedialAxis, MeshError> {
    let path = path.as_ref();
    if text::is_blank(bytes) {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    ma::read(path, bytes, true, false)
}

/// [`MeshError::IsDirectory`] for a directory (whose "extension" would otherwise be
/// reported as an unknown format, or whose read fail with the system's words), and
/// [`MeshError::NotAFile`] for a named pipe, a socket or a device, which are refused
/// before they are opened: opening a FIFO blocks until a writer comes, and reading a
/// device may never end. Symbolic links are followed.
pub(crate) fn refuse_directory(path: &Path) -> Result<(), MeshError> {
    match not_a_file(path) {
        Ok(None) => Ok(()),
        Ok(Some("a directory")) => Err(MeshError::IsDirectory {
            path: path.to_path_buf(),
        }),
        Ok(Some(kind)) => Err(MeshError::NotAFile {
            path: path.to_path_buf(),
            kind,
        }),
        // A path that cannot be looked at (missing, say) is the reader's to report,
        // after the extension.
        Err(_) => Ok(()),
    }
}

/// What `path` is when it is not a regular file (after following symbolic links), as
/// a phrase ("a named pipe (FIFO)"); `None` for a regular file.
pub fn not_a_file(path: &Path) -> std::io::Result<Option<&'static str>> {
    let kind = std::fs::metadata(path)?.file_type();
    if kind.is_file() {
        return Ok(None);
    }
    if kind.is_dir() {
        return Ok(Some("a directory"));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Ok(Some("a named pipe (FIFO)"));
        }
        if kind.is_socket() {
            return Ok(Some("a socket"));
        }
        if kind.is_char_device() {
            return Ok(Some("a character device"));
        }
        if kind.is_block_device() {
            return Ok(Some("a block device"));
        }
    }
    Ok(Some("not a regular file"))
}

/// How much of a file's start is read first, for the format's [`Check`]: the first
/// line of every format, and the whole header of all but unusual PLY files.
const HEAD: u64 = 64 * 1024;

/// The file, as much of it as the format needs: its start is read first and checked
/// with the file's size (`check`), so that a file that is not the format, or whose
/// header claims more than the file holds, is refused without reading the rest. Memory
/// for the rest is reserved before it is read, and a failure is
/// [`MeshError::OutOfMemory`]. A file of only whitespace is empty whatever its format.
pub(crate) fn read_bytes(path: &Path, check: Check) -> Result<Vec<u8>, MeshError> {
    use std::io::Read;
    let io = |source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    };
    refuse_directory(path)?;
    let mut file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let mut bytes = Vec::new();
    (&mut file).take(HEAD).read_to_end(&mut bytes).map_err(io)?;
    let read = bytes.len() as u64;
    if read < size {
        let needed = match text::is_blank(&bytes) {
            true => size,
            false => check(path, &bytes, size)?,
        };
        if needed > read {
            let rest = usize::try_from(needed - read).unwrap_or(usize::MAX);
            super::try_reserve(&mut bytes, rest, || {
                format!("reading the file ({size} bytes)")
            })
            .map_err(|e| e.in_file(path))?;
            (&mut file)
                .take(needed - read)
                .read_to_end(&mut bytes)
                .map_err(io)?;
        }
    }
    if text::is_blank(&bytes) {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    Ok(bytes)
}
