//! Object File Format: an optional `OFF` header (also `COFF`, `NOFF`, `CNOFF`, `STOFF`),
//! a counts line `nv nf [ne]`, one vertex per line, one face `n i j k …` per line.
//!
//! Line-based rather than a token stream: values after a vertex's `x y z` or after a
//! face's `n` indices (colours, normals, texture coordinates) can then be skipped without
//! knowing which variant of the format wrote them.

use super::sniff;
use super::text::{at_line, capacity, next_number, parse_error, reserved, Lines};
use crate::mesh::{MeshError, TriMesh};
use std::path::Path;

/// Refuses a file whose start is not text before the rest is read; the reader needs
/// all of it.
pub(super) fn check(path: &Path, head: &[u8], size: u64) -> Result<u64, MeshError> {
    sniff::expect_text(path, "an OFF file", head)?;
    Ok(size)
}

pub(super) fn read(path: &Path, bytes: &[u8], weld: bool) -> Result<TriMesh, MeshError> {
    sniff::expect_text(path, "an OFF file", bytes)?;
    let mut lines = Lines::new(path, bytes);
    let (counts_line, nv, nf) = read_counts(path, bytes, &mut lines)?;
    // Room is reserved for no more than the file can hold: a vertex line takes at least
    // 6 bytes (`0 0 0` and its newline), a face line 8 (`3 0 1 2`).
    let rest = lines.rest_len();
    let positions = read_vertices(path, &mut lines, counts_line, nv, capacity(nv, rest, 6))?;
    let room = capacity(nf, rest, 8);
    let triangles = read_faces(path, &mut lines, counts_line, nv, nf, room)?;
    super::build(path, positions, triangles, weld)
}

/// Reads the header keyword (if any) and the counts line: the line of the counts, the
/// vertex count and the face count.
fn read_counts(
    path: &Path,
    bytes: &[u8],
    lines: &mut Lines<'_>,
) -> Result<(usize, usize, usize), MeshError> {
    let Some(first) = lines.next() else {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    };
    let (mut line, mut text) = first?;

    // The header keyword, possibly followed by the counts on the same line.
    let keyword = text.split_whitespace().next().unwrap_or("");
    if !keyword.ends_with("OFF") && keyword.parse::<usize>().is_err() {
        return Err(sniff::wrong_format(path, "an OFF file", bytes));
    }
    if keyword.ends_with("OFF") {
        if keyword.contains('4') || keyword.contains('n') {
            return Err(parse_error(
                path,
                line,
                format!("`{keyword}`: only 3D OFF files are supported"),
            ));
        }
        let after = text[keyword.len()..].trim();
        if after.is_empty() {
            match lines.next() {
                Some(item) => (line, text) = item?,
                None => return Err(parse_error(
                    path,
                    lines.end_line(),
                    "expected the counts line `vertices faces edges`, found the end of the file",
                )),
            }
        } else {
            text = after;
        }
    }
    let mut tokens = text.split_whitespace();
    let nv: usize = next_number(&mut tokens, path, line, || "vertex count".into())?;
    let nf: usize = next_number(&mut tokens, path, line, || "face count".into())?;
    Ok((line, nv, nf))
}

/// Reads the `nv` vertex lines (room for `room` reserved first).
fn read_vertices(
    path: &Path,
    lines: &mut Lines<'_>,
    counts_line: usize,
    nv: usize,
    room: usize,
) -> Result<Vec<[f64; 3]>, MeshError> {
    let mut positions: Vec<[f64; 3]> = reserved(path, room, "vertices")?;
    for v in 0..nv {
        let (line, text) = expect_line(lines, path, || {
            format!("vertex {v} of the {nv} that line {counts_line} declares")
        })?;
        let mut tokens = text.split_whitespace();
        let mut p = [0.0; 3];
        for (axis, c) in p.iter_mut().enumerate() {
            *c = next_number(&mut tokens, path, line, || {
                format!("{} coordinate of vertex {v}", ["x", "y", "z"][axis])
            })?;
        }
        crate::mesh::try_grow(&mut positions, 1, "vertices").map_err(|e| e.in_file(path))?;
        positions.push(p);
    }
    Ok(positions)
}

/// Reads the `nf` face lines, fan-triangulated (room for `room` triangles reserved
/// first); indices are checked against the `nv` vertices.
fn read_faces(
    path: &Path,
    lines: &mut Lines<'_>,
    counts_line: usize,
    nv: usize,
    nf: usize,
    room: usize,
) -> Result<Vec<[u32; 3]>, MeshError> {
    let mut triangles: Vec<[u32; 3]> = reserved(path, room, "triangles")?;
    let mut polygon: Vec<u32> = Vec::new();
    for f in 0..nf {
        let (line, text) = expect_line(lines, path, || {
            format!("face {f} of the {nf} that line {counts_line} declares")
        })?;
        let mut tokens = text.split_whitespace();
        let n: usize = next_number(&mut tokens, path, line, || {
            format!("vertex count of face {f}")
        })?;
        if n < 3 {
            return Err(parse_error(
                path,
                line,
                format!("face {f} has {n} vertices; a face needs at least 3"),
            ));
        }
        polygon.clear();
        for k in 0..n {
            let index: i64 = next_number(&mut tokens, path, line, || {
                format!("vertex {k} of face {f} (it declares {n})")
            })?;
            match u32::try_from(index) {
                Ok(v) if (v as usize) < nv => polygon.push(v),
                _ => {
                    return Err(at_line(
                        path,
                        line,
                        MeshError::IndexOutOfRange {
                            face: f,
                            vertex: index,
                            vertex_count: nv,
                        },
                    ))
                }
            }
        }
        // Fan triangulation: exact for the convex polygons mesh files hold.
        for k in 1..n - 1 {
            crate::mesh::try_grow(&mut triangles, 1, "triangles").map_err(|e| e.in_file(path))?;
            triangles.push([polygon[0], polygon[k], polygon[k + 1]]);
        }
    }
    Ok(triangles)
}

/// The next data line, or a truncation error naming what was expected and where.
fn expect_line<'a>(
    lines: &mut Lines<'a>,
    path: &Path,
    what: impl FnOnce() -> String,
) -> Result<(usize, &'a str), MeshError> {
    match lines.next() {
        Some(item) => item,
        None => Err(parse_error(
            path,
            lines.end_line(),
            format!(
                "the file is truncated: expected {}, found the end of the file",
                what()
            ),
        )),
    }
}
