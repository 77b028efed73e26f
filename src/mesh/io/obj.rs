//! Wavefront OBJ: `v` and `f` statements; everything else (normals, texture
//! coordinates, groups, materials, `l` and `p` elements) is ignored.
//!
//! Hand-written rather than `tobj`: with default features tobj stores positions as `f32`,
//! and in both its index modes it renumbers vertices in order of first use by a face and
//! drops unreferenced ones (on the shared meshes, 0–1042 of the vertices keep their file
//! index). Vertex ids must be the file's, because reference distances and sources are
//! given per file vertex; and the reader must name the line of a bad statement, which
//! tobj cannot.

use super::sniff;
use super::text::{at_line, next_number, parse_error, Lines};
use crate::mesh::{MeshError, TriMesh};
use std::path::Path;

/// A face that named a vertex beyond those read so far. OBJ allows forward references,
/// so it is only an error if the vertex never comes; kept to report the first such face.
struct ForwardRef {
    line: usize,
    face: usize,
    vertex: i64,
}

/// Refuses a file whose start is not text before the rest is read; the reader needs
/// all of it.
pub(super) fn check(path: &Path, head: &[u8], size: u64) -> Result<u64, MeshError> {
    sniff::expect_text(path, "an OBJ file", head)?;
    Ok(size)
}

pub(super) fn read(path: &Path, bytes: &[u8], weld: bool) -> Result<TriMesh, MeshError> {
    sniff::expect_text(path, "an OBJ file", bytes)?;
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut forward: Vec<ForwardRef> = Vec::new();
    let mut faces = 0usize;
    let mut polygon: Vec<u32> = Vec::new();
    let mut any_statement = false;

    let mut lines = Lines::new(path, bytes);
    for item in &mut lines {
        let (line, text) = item?;
        any_statement = true;
        let mut tokens = text.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let v = positions.len();
                let mut p = [0.0; 3];
                for (axis, c) in p.iter_mut().enumerate() {
                    *c = next_number(&mut tokens, path, line, || {
                        format!("{} coordinate of vertex {}", ["x", "y", "z"][axis], v + 1)
                    })?;
                }
                // A fourth value is a weight (rational curves only) or an RGB colour:
                // neither moves the point of a polygonal mesh.
                crate::mesh::try_grow(&mut positions, 1, "vertices")
                    .map_err(|e| e.in_file(path))?;
                positions.push(p);
            }
            Some("f") | Some("fo") => {
                polygon.clear();
                let mut max_given: Option<i64> = None;
                for token in tokens {
                    let given = token.split('/').next().unwrap_or("");
                    let index: i64 = given.parse().map_err(|_| {
                        parse_error(
                            path,
                            line,
                            format!("expected a vertex index, found `{token}`"),
                        )
                    })?;
                    let out_of_range = || {
                        at_line(
                            path,
                            line,
                            MeshError::IndexOutOfRange {
                                face: faces,
                                vertex: index,
                                vertex_count: positions.len(),
                            },
                        )
                    };
                    // 1-based; negative counts back from the last vertex read so far.
                    let zero_based = match index {
                        0 => {
                            return Err(parse_error(
                                path,
                                line,
                                format!(
                                    "face {faces} gives vertex index 0, but OBJ indices start \
                                     at 1 (and negative ones count back from the last vertex)"
                                ),
                            ))
                        }
                        i if i < 0 => positions.len() as i64 + i,
                        i => i - 1,
                    };
                    let Ok(v) = u32::try_from(zero_based) else {
                        return Err(out_of_range());
                    };
                    if zero_based >= positions.len() as i64 {
                        max_given = Some(max_given.map_or(index, |m: i64| m.max(index)));
                    }
                    polygon.push(v);
                }
                if polygon.len() < 3 {
                    return Err(parse_error(
                        path,
                        line,
                        format!(
                            "a face needs at least 3 vertices, this one has {}",
                            polygon.len()
                        ),
                    ));
                }
                if let Some(vertex) = max_given {
                    forward.push(ForwardRef {
                        line,
                        face: faces,
                        vertex,
                    });
                }
                // Fan triangulation, as tobj and most readers do: exact for convex
                // polygons, which is what faces in mesh files are.
                for k in 1..polygon.len() - 1 {
                    crate::mesh::try_grow(&mut triangles, 1, "triangles")
                        .map_err(|e| e.in_file(path))?;
                    triangles.push([polygon[0], polygon[k], polygon[k + 1]]);
                }
                faces += 1;
            }
            _ => {}
        }
    }
    if !any_statement {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    if positions.is_empty() && faces == 0 {
        // Statements, but none of a mesh: most likely another format's file.
        return Err(sniff::wrong_format(path, "an OBJ file", bytes));
    }
    if let Some(f) = forward.iter().find(|f| f.vertex > positions.len() as i64) {
        return Err(at_line(
            path,
            f.line,
            MeshError::IndexOutOfRange {
                face: f.face,
                vertex: f.vertex,
                vertex_count: positions.len(),
            },
        ));
    }
    super::build(path, positions, triangles, weld)
}
