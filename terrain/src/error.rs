use geotracks::metrics::Num;
use std::path::PathBuf;
use thiserror::Error;

/// Why an elevation grid could not be read or meshed, a terrain cost built, or a route
/// found: the error of this crate (the engine's own errors come wrapped, as
/// [`TerrainError::Engine`]).
///
/// File errors name the file, and the line (1-based), row and column (0-based, row 0 the
/// northernmost) where that means something.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// The file could not be opened or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file's extension names no grid format geotracks reads.
    #[error("{path}: unknown elevation grid format (expected .asc, .tif or .tiff)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A required key of an ESRI ASCII grid header is missing. Fix: add it (`ncols`,
    /// `nrows`, `xllcorner` or `xllcenter`, `yllcorner` or `yllcenter`, `cellsize`).
    #[error("{path}: the header has no '{key}'")]
    MissingKey {
        /// The file.
        path: PathBuf,
        /// The key.
        key: &'static str,
    },
    /// The file does not follow its format: an unknown or repeated header key, a token
    /// that is not a number, a value that is not finite. `line` is 1-based (0 when the
    /// format has no lines).
    #[error("{path}{}: {message}", line_suffix(*line))]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line, 0 if none.
        line: usize,
        /// What is wrong, and at which row and column for a sample.
        message: String,
    },
    /// The data holds more or fewer samples than `ncols × nrows`.
    #[error("{path}{}: expected {expected} values ({ncols} columns × {nrows} rows, as the header's lines {} and {} declare), found {found}", line_suffix(*line), header_lines[0], header_lines[1])]
    ValueCount {
        /// The file.
        path: PathBuf,
        /// Columns.
        ncols: usize,
        /// Rows.
        nrows: usize,
        /// `ncols × nrows`.
        expected: usize,
        /// Values found.
        found: usize,
        /// The line of the first value too many, 0 when values are missing.
        line: usize,
        /// The header lines of `ncols` and `nrows`.
        header_lines: [usize; 2],
    },
    /// A size the file's header declares (a GeoTIFF's samples or tag values) is more than
    /// the file can hold, even compressed: the file is corrupt or hostile. It is refused
    /// before anything is allocated for it.
    #[error("{path}: {what}: {declared} declared, but a file of {bytes} bytes can hold at most {at_most}")]
    ImplausibleSize {
        /// The file.
        path: PathBuf,
        /// What is counted, and where the count is declared.
        what: String,
        /// The size or count declared.
        declared: u64,
        /// The file's size in bytes.
        bytes: u64,
        /// The most the file can hold.
        at_most: u64,
    },
    /// The file is not of the format its extension names (binary data as an ESRI ASCII
    /// grid, say). Fix: give it its right extension, or convert it.
    #[error("{path}: not {expected}: {found}")]
    WrongFormat {
        /// The file.
        path: PathBuf,
        /// The format the extension named.
        expected: &'static str,
        /// What the file looks like instead.
        found: String,
    },
    /// The path names a directory.
    #[error("{path}: is a directory, not an elevation grid file")]
    IsDirectory {
        /// The directory.
        path: PathBuf,
    },
    /// The sample spacing is not a finite positive number.
    #[error(
        "{}cell size {} is not a finite positive number",
        path_prefix(path),
        Num(*value)
    )]
    CellSize {
        /// The file, if the grid came from one.
        path: Option<PathBuf>,
        /// The value given.
        value: f64,
    },
    /// A GeoTIFF that geotracks cannot read as an elevation grid: several bands, an
    /// unsupported sample type, a rotated or missing georeference, geographic
    /// (degree) coordinates.
    #[error("{path}: {message}")]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// What is not supported, and what to do about it.
        message: String,
    },
    /// The TIFF decoder failed (a corrupt or truncated file).
    #[error("{path}: {context}: {source}")]
    Tiff {
        /// The file.
        path: PathBuf,
        /// What was being read: the header, a tag (by name and number), or the image
        /// and the strip or tile that failed, with its offset and size in the file.
        context: String,
        /// The decoder's error.
        source: tiff::TiffError,
    },
    /// The path names something that is not a regular file: a named pipe (FIFO), a
    /// socket or a device, refused before it is opened (reading it could block forever).
    /// Fix: save the data to a file and name that file.
    #[error("{path}: is {kind}, not a regular file; save the data to a file and read that")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is ("a named pipe (FIFO)").
        kind: &'static str,
    },
    /// The grid's shape and its values do not match, or a value is ±inf (in-memory
    /// grids; NaN marks a missing sample there).
    #[error("invalid grid: {message}")]
    InvalidGrid {
        /// What is wrong.
        message: String,
    },
    /// No cell has three valid samples, so the grid makes no triangle. A grid needs at
    /// least 2 × 2 samples, and valid samples next to each other.
    #[error("{}the grid makes no triangle: it has {ncols} × {nrows} samples, {valid} of them valid; at least three valid samples of one cell are needed", path_prefix(path))]
    TooSmall {
        /// The file, if the grid came from one.
        path: Option<PathBuf>,
        /// Columns.
        ncols: usize,
        /// Rows.
        nrows: usize,
        /// Samples that are not NODATA.
        valid: usize,
    },
    /// A map point lies outside the grid (beyond the outermost sample centres).
    #[error("point ({}, {}) is outside the grid (x from {} to {}, y from {} to {})", Num(*x), Num(*y), Num(*x_min), Num(*x_max), Num(*y_min), Num(*y_max))]
    Outside {
        /// x.
        x: f64,
        /// y.
        y: f64,
        /// Westmost sample centre.
        x_min: f64,
        /// Eastmost sample centre.
        x_max: f64,
        /// Southmost sample centre.
        y_min: f64,
        /// Northmost sample centre.
        y_max: f64,
    },
    /// A map point lies in a cell with NODATA samples: no triangle covers it.
    #[error("point ({}, {}) lies on NODATA (no elevation there)", Num(*x), Num(*y))]
    NoData {
        /// x.
        x: f64,
        /// y.
        y: f64,
    },
    /// A cost parameter is out of range.
    #[error("{what} is {}; {expected}", Num(*value))]
    Parameter {
        /// Which parameter.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A per-face or per-vertex mask does not have one entry per face or vertex.
    #[error("{what} has {found} entries, but the mesh has {expected} {per}")]
    CountMismatch {
        /// The mask.
        what: &'static str,
        /// "faces" or "vertices".
        per: &'static str,
        /// Entries expected.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// A vertex whose surface normal is horizontal (a vertical wall): its slope has no
    /// finite tangent, so a slope density is undefined there.
    #[error("vertex {vertex} is on a vertical part of the surface: its slope is 90°")]
    Vertical {
        /// The vertex.
        vertex: u32,
    },
    /// A cost specification (`none`, `slope:A[,max:DEG]`, `incline:B`, `uphill:B`,
    /// `naismith`, `rwalk[:a,b,c,d[,sf]]`, `tobler[:offpath]`) could not be read.
    #[error(
        "cannot read cost '{text}': {reason} (expected none, slope:A[,max:DEG], incline:B, uphill:B, naismith, rwalk[:a,b,c,d[,sf]] or tobler[:offpath])"
    )]
    CostSpec {
        /// The text given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The mesh could not be built.
    #[error(transparent)]
    Mesh(#[from] geotracks::mesh::MeshError),
    /// A metric could not be built.
    #[error(transparent)]
    Metric(#[from] geotracks::metrics::MetricError),
    /// The engine refused a run or a query: no route joins the two points
    /// ([`geotracks::Error::Unreachable`]: walls, NODATA or separate islands between
    /// them), or the options or the run's size are out of range.
    #[error(transparent)]
    Engine(#[from] geotracks::Error),
}

fn line_suffix(line: usize) -> String {
    if line == 0 {
        String::new()
    } else {
        format!(":{line}")
    }
}

fn path_prefix(path: &Option<PathBuf>) -> String {
    path.as_ref()
        .map(|p| format!("{}: ", p.display()))
        .unwrap_or_default()
}
