//! Reading the CLI's input files: the mesh (with a warning for dropped faces) and the
//! per-vertex density or per-face tensor files.

use crate::CliResult;
use geotracks::mesh::{io, TriMesh};
use std::fmt;
use std::path::{Path, PathBuf};

/// A line of a numeric input file that could not be used.
#[derive(Debug)]
pub struct InputError {
    path: PathBuf,
    line: usize,
    message: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.path.display(), self.message)
        } else {
            write!(f, "{}:{}: {}", self.path.display(), self.line, self.message)
        }
    }
}

impl std::error::Error for InputError {}

fn input_error(path: &Path, line: usize, message: impl Into<String>) -> InputError {
    InputError {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Reads a mesh (welding vertices at identical positions if `weld`) and warns on stderr
/// about degenerate faces that were dropped.
pub fn load_mesh(path: &Path, weld: bool) -> CliResult<TriMesh> {
    let mesh = io::read_mesh_with(path, &io::ReadOptions::DEFAULT.with_weld(weld))?;
    let dropped = mesh.dropped_faces().len();
    if dropped > 0 {
        eprintln!(
            "warning: {}: dropped {dropped} degenerate face(s) (zero area or a repeated vertex)",
            path.display()
        );
    }
    Ok(mesh)
}

/// The whole file as text; a file that is not UTF-8 text (binary data, a mesh given by
/// mistake) is named as such, with the first offending byte and its line.
///
/// Only regular files are read: a named pipe or a device is refused before it is
/// opened (opening a FIFO blocks until a writer comes). A leading UTF-8 byte-order mark
/// is skipped.
fn read_text(path: &Path) -> Result<String, InputError> {
    match io::not_a_file(path) {
        Ok(None) => {}
        Ok(Some(kind)) => {
            return Err(input_error(
                path,
                0,
                format!("is {kind}, not a regular file; save the data to a file and read that"),
            ))
        }
        Err(e) => return Err(input_error(path, 0, e.to_string())),
    }
    let bytes = std::fs::read(path).map_err(|e| input_error(path, 0, e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let bytes = e.as_bytes();
        let at = e.utf8_error().valid_up_to();
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        input_error(
            path,
            line,
            format!(
                "not a text file of numbers: byte 0x{:02x} at offset {at} is not text \
                 (a binary file?)",
                bytes[at]
            ),
        )
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

/// Reads rows of `width` floats, one row per non-empty line (`#` starts a comment);
/// returns each row with its 1-based line number.
fn read_rows(path: &Path, width: usize) -> Result<Vec<(usize, Vec<f64>)>, InputError> {
    let text = read_text(path)?;
    let mut rows = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let values = line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .map(|s| {
                s.parse::<f64>()
                    .map_err(|_| input_error(path, i + 1, format!("'{s}' is not a number")))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        if values.len() != width {
            return Err(input_error(
                path,
                i + 1,
                format!("expected {width} value(s), found {}", values.len()),
            ));
        }
        rows.push((i + 1, values));
    }
    if rows.is_empty() {
        return Err(input_error(path, 0, "the file is empty"));
    }
    Ok(rows)
}

/// One density per vertex, in vertex order.
pub fn read_density(path: &Path, mesh: &TriMesh) -> CliResult<geotracks::Density> {
    let rows = read_rows(path, 1)?;
    let values: Vec<f64> = rows.iter().map(|(_, r)| r[0]).collect();
    geotracks::Density::new(mesh, values).map_err(|e| {
        let line = match e {
            geotracks::MetricError::InvalidDensity { vertex, .. } => rows[vertex].0,
            _ => 0,
        };
        input_error(path, line, e.to_string()).into()
    })
}

/// One world-space tensor `xx xy xz yy yz zz` per face of the input file (faces that
/// were dropped as degenerate skip their line).
pub fn read_tensor(path: &Path, mesh: &TriMesh) -> CliResult<geotracks::Tensor> {
    let rows = read_rows(path, 6)?;
    if rows.len() != mesh.input_face_count() {
        return Err(input_error(
            path,
            0,
            format!(
                "expected {} tensors (one per face of the mesh file), found {}",
                mesh.input_face_count(),
                rows.len()
            ),
        )
        .into());
    }
    let kept: Vec<[f64; 6]> = (0..mesh.triangles().len() as u32)
        .map(|f| {
            let r = &rows[mesh.input_face(f)].1;
            [r[0], r[1], r[2], r[3], r[4], r[5]]
        })
        .collect();
    geotracks::Tensor::from_world(mesh, &kept).map_err(|e| {
        let line = match e {
            geotracks::MetricError::NotPositiveDefinite { face, .. }
            | geotracks::MetricError::NotFinite { face } => rows[mesh.input_face(face as u32)].0,
            _ => 0,
        };
        input_error(path, line, e.to_string()).into()
    })
}

/// One world-space tensor `xx xy xz yy yz zz` per vertex.
pub fn read_tensor_field(path: &Path, mesh: &TriMesh) -> CliResult<geotracks::TensorField> {
    let rows = read_rows(path, 6)?;
    let values: Vec<[f64; 6]> = rows
        .iter()
        .map(|(_, r)| [r[0], r[1], r[2], r[3], r[4], r[5]])
        .collect();
    geotracks::TensorField::from_world(mesh, &values).map_err(|e| {
        let line = match e {
            geotracks::MetricError::VertexTensor { vertex, .. } => rows[vertex].0,
            _ => 0,
        };
        input_error(path, line, e.to_string()).into()
    })
}

/// Vertex ids, separated by white space or commas (`#` starts a comment), each below
/// `vertex_count`.
pub fn read_vertex_ids(path: &Path, vertex_count: usize) -> CliResult<Vec<u32>> {
    let text = read_text(path)?;
    let mut ids = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("");
        for token in line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
        {
            let id: u32 = token
                .parse()
                .map_err(|_| input_error(path, i + 1, format!("'{token}' is not a vertex id")))?;
            if id as usize >= vertex_count {
                return Err(input_error(
                    path,
                    i + 1,
                    format!("vertex {id} is out of range: the mesh has {vertex_count} vertices"),
                )
                .into());
            }
            ids.push(id);
        }
    }
    if ids.is_empty() {
        return Err(input_error(path, 0, "the file holds no vertex id").into());
    }
    Ok(ids)
}
