//! Wavefront OBJ: `v` and `f` statements; everything else (normals, texture
//! coordinates, groups, materials, `l` and `p` elements) is ignored.
//!
//! # Why not `tobj`
//!
//! The design card names `tobj`; this reader stays, for what tobj does to our contracts
//! more than for speed. `examples/obj_readers.rs` reads every OBJ of the shared data
//! with both (tobj 4.0.5 with `use_f64`, since its default stores `f32`; the card's
//! `triangulate: true` without `single_index`, plus `ignore_points`/`ignore_lines`) and
//! runs the hostile inputs of `tests/io.rs` and the fuzz seeds through both:
//!
//! ```text
//! cargo run --release --example obj_readers -- ../shared/data --reps 21
//! ```
//!
//! - **Vertex ids.** tobj renumbers vertices per model in order of first use by a face
//!   and drops unreferenced ones: on the 14 shared meshes 0–1042 vertices keep their
//!   file index (0 of 2930 on spot, 4 of 139,122 on bunny_loop1). Sources, per-vertex
//!   densities and reference distances are given per file vertex. Each group or object
//!   is a model with its own vertices, so two groups that share a vertex no longer share
//!   an edge (`quad_groups.obj`: 7 vertices instead of 6, its shared edge cut). No
//!   option gives the file's numbering back.
//! - **Errors.** tobj's `LoadError` is a bare kind (`FaceVertexOutOfBounds`,
//!   `PositionParseError`, `ReadError` …) with no line, face or vertex: every case of
//!   `tests/io.rs` that names its line would lose it. It accepts what we refuse — `f 1 2`
//!   (read as a line, so silently dropped), an empty file (0 vertices, no error) — and
//!   refuses what we read: a texture or normal index out of range, where we only need
//!   positions, and a face before the group that holds its vertex (forward references
//!   are resolved per model).
//! - **Silent wrong answers.** `l` with 3 or more points becomes triangles even with
//!   `ignore_lines` (only 2-point lines are lines to it): the curve skeletons
//!   `skeleton/{cow,spot}.mcf.obj`, which we refuse as having no face, read as 277 and
//!   221 triangles. `v x y z w` divides the point by `w` (`w = 0` is an error); a weight
//!   belongs to rational curves and we ignore it. `fo` faces are dropped.
//! - **Speed.** Median of 21, both from memory, the readers taking turns, on a shared
//!   2-core AMD EPYC (load average about 10): tobj's parse alone is slower than ours (our
//!   whole read less its `TriMesh::new`, timed apart) on every file above 1 MB
//!   (bunny_loop1, 14 MB: 246 ms against 148; horse 84 against 60; bunny 50 against 33;
//!   sphere 53 against 41; plane_grid 47 against 33; plane_irregular 25 against 19), and
//!   tobj plus `TriMesh::new` takes 1.13–1.33× our whole read on them, 1.28× summed over
//!   all 32 files (824 ms against 643).
//! - **Where they agree.** Fan triangulation of polygons, `f v/vt/vn`, `f v//vn` and
//!   negative indices: every triangle we keep has tobj's corners for the same input face
//!   on all 30 files with faces. Neither panicked on any input or fuzz seed.
//!
//! Adopting tobj behind our errors would need a second pass over the file to find the
//! line of each error and its own vertex map, that is, this reader again.

use super::sniff;
use super::text::{at_line, next_number, parse_error, Lines};
use crate::mesh::{MeshError, TriMesh};
use std::path::Path;
use std::str::SplitWhitespace;

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
                let p = vertex_line(path, line, &mut tokens, positions.len())?;
                crate::mesh::try_grow(&mut positions, 1, "vertices")
                    .map_err(|e| e.in_file(path))?;
                positions.push(p);
            }
            Some("f") | Some("fo") => {
                let max_given =
                    face_line(path, line, tokens, faces, positions.len(), &mut polygon)?;
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
    check_read(path, bytes, any_statement, &positions, faces, &forward)?;
    super::build(path, positions, triangles, weld)
}

/// The point of a `v` statement (vertex `v`, 0-based), from the values after `v`.
#[inline]
fn vertex_line(
    path: &Path,
    line: usize,
    tokens: &mut SplitWhitespace<'_>,
    v: usize,
) -> Result<[f64; 3], MeshError> {
    let mut p = [0.0; 3];
    for (axis, c) in p.iter_mut().enumerate() {
        *c = next_number(tokens, path, line, || {
            format!("{} coordinate of vertex {}", ["x", "y", "z"][axis], v + 1)
        })?;
    }
    // A fourth value is a weight (rational curves only) or an RGB colour:
    // neither moves the point of a polygonal mesh.
    Ok(p)
}

/// The vertices of an `f` statement (face number `faces`, read when `nv` vertices have
/// been), 0-based, into `polygon`; the largest index given beyond the vertices read so
/// far, if any (a forward reference, checked at the end of the file).
#[inline]
fn face_line(
    path: &Path,
    line: usize,
    tokens: SplitWhitespace<'_>,
    faces: usize,
    nv: usize,
    polygon: &mut Vec<u32>,
) -> Result<Option<i64>, MeshError> {
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
                    vertex_count: nv,
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
            i if i < 0 => nv as i64 + i,
            i => i - 1,
        };
        let Ok(v) = u32::try_from(zero_based) else {
            return Err(out_of_range());
        };
        if zero_based >= nv as i64 {
            max_given = Some(max_given.map_or(index, |m: i64| m.max(index)));
        }
        polygon.push(v);
    }
    Ok(max_given)
}

/// Once every line is read: refuses a file with no statement, one with no vertex and
/// no face, and a face that named a vertex that never came.
fn check_read(
    path: &Path,
    bytes: &[u8],
    any_statement: bool,
    positions: &[[f64; 3]],
    faces: usize,
    forward: &[ForwardRef],
) -> Result<(), MeshError> {
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
    Ok(())
}
