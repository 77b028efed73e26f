//! STL through `stl_io`, ascii and binary, with corners that have bit-identical
//! coordinates welded into one vertex (STL stores each triangle's corners separately).
//!
//! The format is chosen here rather than by `stl_io`, which calls any file starting with
//! `solid ` ascii: many binary writers put exactly that in their 80-byte header. A file
//! whose size matches its binary triangle count is binary whatever its first bytes say.

use crate::mesh::{MeshError, TriMesh};
use std::borrow::Cow;
use std::collections::HashMap;
use std::io::Cursor;
use std::path::Path;

const HEADER: usize = 84;
const RECORD: usize = 50;

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<TriMesh, MeshError> {
    let parse = |line: usize, message: String| MeshError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let declared = bytes
        .get(80..HEADER)
        .and_then(|b| <[u8; 4]>::try_from(b).ok())
        .map(|b| u32::from_le_bytes(b) as u64);
    let binary_size = declared.map(|n| HEADER as u64 + RECORD as u64 * n);
    let first_line_end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .unwrap_or(bytes.len());
    let first_line = String::from_utf8_lossy(&bytes[..first_line_end]);
    let ascii = binary_size != Some(bytes.len() as u64) && first_line.trim().starts_with("solid");

    let data: Cow<[u8]> = if ascii {
        // stl_io wants the file to start with exactly `solid ` (a space), which an
        // unnamed solid (`solid` alone) or leading blanks would fail.
        let mut fixed = b"solid ".to_vec();
        fixed.extend_from_slice(&bytes[first_line_end..]);
        Cow::Owned(fixed)
    } else {
        let (Some(n), Some(size)) = (declared, binary_size) else {
            return Err(parse(
                0,
                format!(
                    "not an ascii STL (no `solid` line) and too short for a binary one: \
                     {} bytes, the binary header alone has {HEADER}",
                    bytes.len()
                ),
            ));
        };
        if (bytes.len() as u64) < size {
            let complete = (bytes.len() - HEADER) / RECORD;
            return Err(parse(
                0,
                format!(
                    "the binary STL is truncated: its header declares {n} triangles \
                     ({size} bytes) but the file has {} bytes; triangle {complete} is incomplete",
                    bytes.len()
                ),
            ));
        }
        if bytes.starts_with(b"solid") {
            // Hide the misleading word from stl_io's ascii probe.
            let mut fixed = bytes.to_vec();
            fixed[0] = 0;
            Cow::Owned(fixed)
        } else {
            Cow::Borrowed(bytes)
        }
    };

    let mut cursor = Cursor::new(data.as_ref());
    let triangles_in =
        stl_io::create_stl_reader(&mut cursor).map_err(|e| parse(1, e.to_string()))?;
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut index_of: HashMap<[u32; 3], u32> = HashMap::new();
    for (t, triangle) in triangles_in.enumerate() {
        let triangle = triangle.map_err(|e| {
            if ascii {
                let line = facet_line(bytes, t);
                parse(line, format!("facet {t} (starting at line {line}): {e}"))
            } else {
                parse(0, format!("triangle {t}: {e}"))
            }
        })?;
        let mut corners = [0u32; 3];
        for (corner, vertex) in corners.iter_mut().zip(triangle.vertices) {
            // `+ 0.0` turns -0.0 into 0.0, so the two zeros weld as the same point.
            let p = vertex.0.map(|c| c + 0.0);
            *corner = *index_of.entry(p.map(f32::to_bits)).or_insert_with(|| {
                positions.push(p.map(f64::from));
                positions.len() as u32 - 1
            });
        }
        triangles.push(corners);
    }
    TriMesh::new(positions, triangles).map_err(|e| e.in_file(path))
}

/// The 1-based line where ascii facet `t` starts (or the line after the last, if the file
/// ends before it), so an error inside the facet can be found.
fn facet_line(bytes: &[u8], t: usize) -> usize {
    let mut seen = 0;
    let mut lines = 0;
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        lines = i + 1;
        if String::from_utf8_lossy(line).split_whitespace().next() == Some("facet") {
            if seen == t {
                return i + 1;
            }
            seen += 1;
        }
    }
    lines + 1
}
