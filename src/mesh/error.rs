use std::path::PathBuf;
use thiserror::Error;

/// Why a mesh could not be read or built.
///
/// Every variant names the place: a file and line, a face or a vertex index.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The file could not be opened or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The path names a directory. Fix: name a mesh file inside it.
    #[error("{path}: is a directory, not a mesh file")]
    IsDirectory {
        /// The directory.
        path: PathBuf,
    },
    /// The path names something that is not a regular file: a named pipe (FIFO), a
    /// socket or a device. Reading one could block forever or never end, so it is
    /// refused before it is opened. Fix: save the data to a file and name that file.
    #[error("{path}: is {kind}, not a regular file; save the data to a file and read that")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is ("a named pipe (FIFO)").
        kind: &'static str,
    },
    /// Memory for the data could not be allocated (the file is larger than the memory
    /// the process may use). Nothing was half-built. Fix: more memory, or a smaller
    /// mesh.
    #[error("not enough memory for {what} ({bytes} bytes)")]
    OutOfMemory {
        /// What the memory was for ("the file's 2147483648 bytes").
        what: String,
        /// How many bytes were asked for.
        bytes: u64,
    },
    /// The file's content is not the format its extension names: binary data given as a
    /// text format, another format's file under this extension, text under a binary
    /// format's extension. Fix: give the file its right extension, or convert it.
    #[error("{path}: not {expected}: {found}")]
    WrongFormat {
        /// The file.
        path: PathBuf,
        /// The format the extension named ("an OBJ file").
        expected: &'static str,
        /// What the file looks like instead.
        found: String,
    },
    /// An element count in a binary PLY header is larger than the payload after it could
    /// hold (each record takes at least its scalars' bytes), so the header lies: the file
    /// is corrupt, truncated or hostile. Nothing is allocated for such a claim. (Text
    /// formats reserve no more than their bytes can hold and report a short file as
    /// truncated, naming the header line that declared the count.)
    #[error("{path}{}: the header declares {declared} {what}, but the {bytes} bytes after it can hold at most {at_most}", LineSuffix(*line))]
    ImplausibleCount {
        /// The file.
        path: PathBuf,
        /// 1-based line of the header statement, 0 in a binary header.
        line: usize,
        /// What it counts, as the format names it ("vertices (`element vertex`)").
        what: String,
        /// The count it gives.
        declared: u64,
        /// Bytes of the file after the header.
        bytes: u64,
        /// The most that many bytes can hold.
        at_most: u64,
    },
    /// The file is empty (or holds only comments and blank lines).
    #[error("{path}: the file is empty")]
    EmptyFile {
        /// The file.
        path: PathBuf,
    },
    /// The file's extension names no format geotracks reads or writes.
    #[error("{path}: unknown mesh format (expected one of {expected})")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// The extensions that would have been accepted.
        expected: &'static str,
    },
    /// The file does not follow its format: bad number, missing field, truncated data.
    /// `line` is 1-based, or 0 where the format has no lines (binary files).
    #[error("{path}{}: {message}", LineSuffix(*line))]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number, 0 if unknown.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {vertex}, but the mesh has {vertex_count} vertices")]
    IndexOutOfRange {
        /// The face's index in the input.
        face: usize,
        /// The vertex index it gave.
        vertex: i64,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A line element (a free edge) refers to a vertex that does not exist.
    #[error("edge {edge} refers to vertex {vertex}, but the mesh has {vertex_count} vertices")]
    EdgeIndexOutOfRange {
        /// The edge's index in the input.
        edge: usize,
        /// The vertex index it gave.
        vertex: i64,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate {position:?}")]
    NonFiniteVertex {
        /// The vertex index.
        vertex: usize,
        /// Its coordinates as read.
        position: [f64; 3],
    },
    /// A vertex lies so far from the origin that differences of coordinates, and the
    /// lengths and distances built on them, could overflow. Scale the mesh down.
    #[error("vertex {vertex} has a coordinate beyond ±{limit:e} ({position:?}): lengths and distances could overflow; scale the mesh down")]
    CoordinateOutOfRange {
        /// The vertex index.
        vertex: usize,
        /// Its coordinates.
        position: [f64; 3],
        /// The largest magnitude accepted.
        limit: f64,
    },
    /// Every face is degenerate (zero area or a repeated vertex), or there is none.
    #[error("the mesh has no usable face ({faces} faces read, {degenerate} degenerate)")]
    NoUsableFace {
        /// Faces in the input.
        faces: usize,
        /// How many of them were degenerate.
        degenerate: usize,
    },
    /// Wraps an error of the mesh's content with the file it came from.
    #[error("{path}: {error}")]
    InFile {
        /// The file.
        path: PathBuf,
        /// What is wrong in it.
        error: Box<MeshError>,
    },
    /// Wraps an error of the mesh's content with the file and the 1-based line it came
    /// from, for text formats where the line is known (an index out of range in an OBJ,
    /// OFF or `.ma` file).
    #[error("{path}:{line}: {error}")]
    AtLine {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong there.
        error: Box<MeshError>,
    },
    /// A per-vertex (or per-element) attribute given to a writer has the wrong length.
    /// Pass one value per vertex.
    #[error("{what}: expected {expected} values (one per vertex), got {found}")]
    AttributeLength {
        /// Which attribute.
        what: &'static str,
        /// How many values the mesh needs.
        expected: usize,
        /// How many were given.
        found: usize,
    },
}

impl MeshError {
    /// Attaches the file name to a content error (no-op for errors that already name it).
    pub fn in_file(self, path: impl Into<PathBuf>) -> MeshError {
        match self {
            MeshError::IndexOutOfRange { .. }
            | MeshError::EdgeIndexOutOfRange { .. }
            | MeshError::NonFiniteVertex { .. }
            | MeshError::CoordinateOutOfRange { .. }
            | MeshError::OutOfMemory { .. }
            | MeshError::NoUsableFace { .. } => MeshError::InFile {
                path: path.into(),
                error: Box::new(self),
            },
            other => other,
        }
    }
}

/// Room for `additional` more elements in `vec`, or [`MeshError::OutOfMemory`] naming
/// `what` (`Vec::reserve` aborts the process when memory runs out).
///
/// Public for the readers of the sibling crates (elevation grids), which size their
/// buffers from untrusted headers the same way the mesh readers do.
///
/// # Errors
/// [`MeshError::OutOfMemory`] when the allocator refuses the room.
pub fn try_reserve<T>(
    vec: &mut Vec<T>,
    additional: usize,
    what: impl FnOnce() -> String,
) -> Result<(), MeshError> {
    vec.try_reserve_exact(additional)
        .map_err(|_| MeshError::OutOfMemory {
            what: what(),
            bytes: (additional as u64).saturating_mul(std::mem::size_of::<T>() as u64),
        })
}

/// Room for `needed` more elements in `vec`, grown by doubling as `Vec::push` grows it,
/// but with [`MeshError::OutOfMemory`] (naming `what` the elements are) instead of an
/// abort when memory runs out.
pub(crate) fn try_grow<T>(vec: &mut Vec<T>, needed: usize, what: &str) -> Result<(), MeshError> {
    if vec.capacity() - vec.len() >= needed {
        return Ok(());
    }
    let more = vec.len().max(needed).max(1024);
    let total = vec.len() + more;
    try_reserve(vec, more, || format!("{total} {what}"))
}

/// `:line` for a known line, nothing for line 0 (binary data has no lines).
struct LineSuffix(usize);

impl std::fmt::Display for LineSuffix {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            0 => Ok(()),
            line => write!(f, ":{line}"),
        }
    }
}
