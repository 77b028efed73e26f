//! The medial-axis `.ma` format: a counts line `nv ne nf`, then `v x y z r`, `e i j` and
//! `f i j k` lines (0-based), in any order.
//!
//! The `e` lines list every edge, those of faces included; only edges that belong to no
//! kept face become line elements, so a medial axis's curve parts survive without
//! duplicating its sheets' edges.

use super::sniff;
use super::text::{at_line, capacity, next_number, parse_error, reserved, Lines};
use super::MedialAxis;
use crate::mesh::{MeshError, TriMesh};
use std::path::Path;

/// Refuses a file whose start is not text before the rest is read; the reader needs
/// all of it.
pub(super) fn check(path: &Path, head: &[u8], size: u64) -> Result<u64, MeshError> {
    sniff::expect_text(path, "a medial axis (.ma) file", head)?;
    Ok(size)
}

/// Reads a medial axis; one of curves only (no usable face) is an error unless
/// `allow_curves_only`. `weld` merges vertices at identical positions (the first one's
/// radius is kept).
pub(super) fn read(
    path: &Path,
    bytes: &[u8],
    allow_curves_only: bool,
    weld: bool,
) -> Result<MedialAxis, MeshError> {
    sniff::expect_text(path, "a medial axis (.ma) file", bytes)?;
    let mut lines = Lines::new(path, bytes);
    let counts = read_counts(path, bytes, &mut lines)?;
    let mut records = read_records(path, &mut lines, &counts)?;
    counts.check_found(path, &records)?;
    if weld {
        records.weld();
    }
    records.into_axis(path, allow_curves_only)
}

/// The counts line `nv ne nf`, and where it is.
struct Counts {
    line: usize,
    vertices: usize,
    edges: usize,
    faces: usize,
}

impl Counts {
    /// Refuses a file whose records are fewer than its header declares (more are
    /// refused as they come).
    fn check_found(&self, path: &Path, records: &Records) -> Result<(), MeshError> {
        for (what, found, declared) in [
            (
                "vertices (`v` lines)",
                records.positions.len(),
                self.vertices,
            ),
            ("edges (`e` lines)", records.edges.len(), self.edges),
            ("faces (`f` lines)", records.triangles.len(), self.faces),
        ] {
            if found != declared {
                return Err(parse_error(
                    path,
                    self.line,
                    format!(
                        "the header declares {declared} {what} but the file has {found}: {} missing",
                        declared - found
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Reads the counts line, the first one; a file whose first word is no count is not
/// a medial axis.
fn read_counts(path: &Path, bytes: &[u8], lines: &mut Lines<'_>) -> Result<Counts, MeshError> {
    let Some(first) = lines.next() else {
        return Err(MeshError::EmptyFile {
            path: path.to_path_buf(),
        });
    };
    let (header_line, text) = first?;
    if text
        .split_whitespace()
        .next()
        .is_some_and(|w| w.parse::<usize>().is_err())
    {
        return Err(sniff::wrong_format(path, "a medial axis (.ma) file", bytes));
    }
    let mut tokens = text.split_whitespace();
    let mut count = |what: &str| -> Result<usize, MeshError> {
        next_number(&mut tokens, path, header_line, || {
            format!("{what} count in the header `vertices edges faces`")
        })
    };
    let (nv, ne, nf) = (count("vertex")?, count("edge")?, count("face")?);
    Ok(Counts {
        line: header_line,
        vertices: nv,
        edges: ne,
        faces: nf,
    })
}

/// What the `v`, `e` and `f` lines hold, in file order.
struct Records {
    positions: Vec<[f64; 3]>,
    radii: Vec<f64>,
    edges: Vec<[u32; 2]>,
    triangles: Vec<[u32; 3]>,
}

/// Reads the `v`, `e` and `f` lines after the counts line, no more of each than
/// `counts` declares.
fn read_records(path: &Path, lines: &mut Lines<'_>, counts: &Counts) -> Result<Records, MeshError> {
    let Counts {
        line: header_line,
        vertices: nv,
        edges: ne,
        faces: nf,
    } = *counts;
    // Room is reserved for no more than the file can hold (the shortest lines are
    // `v 0 0 0 0`, `e 0 1` and `f 0 1 2` with their newlines); a count that lies is
    // reported against the lines found once the file has been read.
    let rest = lines.rest_len();
    let mut positions: Vec<[f64; 3]> = reserved(path, capacity(nv, rest, 10), "vertices")?;
    let mut radii: Vec<f64> = reserved(path, capacity(nv, rest, 10), "radii")?;
    let mut edges: Vec<[u32; 2]> = reserved(path, capacity(ne, rest, 6), "edges")?;
    let mut triangles: Vec<[u32; 3]> = reserved(path, capacity(nf, rest, 8), "triangles")?;

    // Vertices may come after the edges and faces that use them, so indices are checked
    // against the header's count, which the end of the file then confirms.
    let index = |token: Option<&str>, line: usize, error: &dyn Fn(i64) -> MeshError| {
        vertex_index(path, nv, token, line, error)
    };
    let too_many = |line: usize, what: &str, n: usize| {
        parse_error(
            path,
            line,
            format!("more {what} than the {n} the header (line {header_line}) declares"),
        )
    };

    for item in lines {
        let (line, text) = item?;
        let mut tokens = text.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let v = positions.len();
                if v == nv {
                    return Err(too_many(line, "vertices", nv));
                }
                let (p, r) = vertex_line(path, line, &mut tokens, v)?;
                crate::mesh::try_grow(&mut positions, 1, "vertices")
                    .map_err(|e| e.in_file(path))?;
                positions.push(p);
                radii.push(r);
            }
            Some("e") => {
                let e = edges.len();
                if e == ne {
                    return Err(too_many(line, "edges", ne));
                }
                let error = |vertex| MeshError::EdgeIndexOutOfRange {
                    edge: e,
                    vertex,
                    vertex_count: nv,
                };
                edges.push([
                    index(tokens.next(), line, &error)?,
                    index(tokens.next(), line, &error)?,
                ]);
            }
            Some("f") => {
                let face = triangles.len();
                if face == nf {
                    return Err(too_many(line, "faces", nf));
                }
                let error = |vertex| MeshError::IndexOutOfRange {
                    face,
                    vertex,
                    vertex_count: nv,
                };
                crate::mesh::try_grow(&mut triangles, 1, "triangles")
                    .map_err(|e| e.in_file(path))?;
                triangles.push([
                    index(tokens.next(), line, &error)?,
                    index(tokens.next(), line, &error)?,
                    index(tokens.next(), line, &error)?,
                ]);
            }
            Some(other) => {
                return Err(parse_error(
                    path,
                    line,
                    format!("unknown record `{other}` (expected `v`, `e` or `f`)"),
                ))
            }
            None => {}
        }
    }
    Ok(Records {
        positions,
        radii,
        edges,
        triangles,
    })
}

/// The vertex index `token` (of a line `line`) names, checked against the `nv` vertices
/// the header declares; `error` is the error for an index out of range.
fn vertex_index(
    path: &Path,
    nv: usize,
    token: Option<&str>,
    line: usize,
    error: &dyn Fn(i64) -> MeshError,
) -> Result<u32, MeshError> {
    let token = token.ok_or_else(|| parse_error(path, line, "a vertex index is missing"))?;
    let i: i64 = token.parse().map_err(|_| {
        parse_error(
            path,
            line,
            format!("expected a vertex index, found `{token}`"),
        )
    })?;
    match u32::try_from(i) {
        Ok(v) if (v as usize) < nv => Ok(v),
        _ => Err(at_line(path, line, error(i))),
    }
}

/// The position and radius of vertex `v`, from the rest of its `v` line.
fn vertex_line(
    path: &Path,
    line: usize,
    tokens: &mut std::str::SplitWhitespace<'_>,
    v: usize,
) -> Result<([f64; 3], f64), MeshError> {
    let mut p = [0.0f64; 4];
    for (k, c) in p.iter_mut().enumerate() {
        *c = next_number(tokens, path, line, || {
            format!("{} of vertex {v}", ["x", "y", "z", "radius"][k])
        })?;
    }
    let r = p[3];
    if !(r.is_finite() && r >= 0.0) {
        return Err(parse_error(
            path,
            line,
            format!("vertex {v} has radius {r}; a radius is finite and >= 0"),
        ));
    }
    Ok(([p[0], p[1], p[2]], r))
}

impl Records {
    /// Merges vertices at identical positions; the first one's radius is kept.
    fn weld(&mut self) {
        if let Some(map) = super::weld_positions(&mut self.positions) {
            let mut kept = vec![false; self.positions.len()];
            let mut welded_radii = vec![0.0; self.positions.len()];
            for (old, &new) in map.iter().enumerate() {
                if !kept[new as usize] {
                    kept[new as usize] = true;
                    welded_radii[new as usize] = self.radii[old];
                }
            }
            self.radii = welded_radii;
            for t in &mut self.triangles {
                *t = t.map(|v| map[v as usize]);
            }
            for e in &mut self.edges {
                *e = e.map(|v| map[v as usize]);
            }
        }
    }

    /// The medial axis: its sheets (if any face is usable) with the free edges attached.
    fn into_axis(self, path: &Path, allow_curves_only: bool) -> Result<MedialAxis, MeshError> {
        self.into_unnamed_axis(allow_curves_only)
            .map_err(|e| e.in_file(path))
    }

    /// [`Records::into_axis`] with errors that name no file (an axis built in memory).
    fn into_unnamed_axis(self, allow_curves_only: bool) -> Result<MedialAxis, MeshError> {
        let Records {
            positions,
            radii,
            edges,
            triangles,
        } = self;
        // Which edges are free depends on which faces survive (degenerate ones are dropped),
        // so they are attached once the faces are built.
        let surface = match TriMesh::new(positions.clone(), triangles) {
            Ok(mesh) => Some(mesh),
            Err(MeshError::NoUsableFace { .. })
                if allow_curves_only && edges.iter().any(|[a, b]| a != b) =>
            {
                None
            }
            Err(e) => return Err(e),
        };
        let free_edges = free_edges(surface.as_ref(), &edges);
        let surface = match surface {
            Some(mut mesh) => {
                mesh.set_line_elements(free_edges.clone())?;
                Some(mesh)
            }
            None => None,
        };
        Ok(MedialAxis {
            surface,
            positions,
            free_edges,
            radii,
        })
    }
}

/// [`read`] for a caller that needs a surface.
pub(super) fn read_surface(path: &Path, bytes: &[u8], weld: bool) -> Result<TriMesh, MeshError> {
    let axis = read(path, bytes, false, weld)?;
    Ok(axis.surface.expect("a surface, or read fails"))
}

/// The listed edges that are no edge of a kept face, each once, self-loops left out.
fn free_edges(mesh: Option<&TriMesh>, edges: &[[u32; 2]]) -> Vec<[u32; 2]> {
    let is_face_edge = |[a, b]: [u32; 2]| {
        mesh.is_some_and(|mesh| {
            mesh.vertex_edges(a)
                .iter()
                .any(|&e| mesh.edge_vertices(e) == [a, b])
        })
    };
    let mut free: Vec<[u32; 2]> = edges
        .iter()
        .filter(|[a, b]| a != b)
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .filter(|&e| !is_face_edge(e))
        .collect();
    free.sort_unstable();
    free.dedup();
    free
}

/// A medial axis built in memory from its sheets' triangles (indices into `positions`)
/// and curves (`edges`; those of a kept triangle are not curves): vertices at identical
/// positions are merged first (the first one's radius is kept), so triangles that meet
/// at a copy of a vertex share it.
pub(super) fn from_parts(
    positions: Vec<[f64; 3]>,
    radii: Vec<f64>,
    triangles: Vec<[u32; 3]>,
    edges: Vec<[u32; 2]>,
) -> Result<MedialAxis, MeshError> {
    let mut records = Records {
        positions,
        radii,
        edges,
        triangles,
    };
    records.weld();
    records.into_unnamed_axis(true)
}

/// Writes `axis` in the `.ma` format: every vertex with its radius, every edge (those of
/// the sheets' faces and the free ones, each once, as readers of the format expect)
/// and every face, indices 0-based; numbers in shortest round-trip form.
pub(super) fn write_to(w: &mut dyn std::io::Write, axis: &MedialAxis) -> std::io::Result<()> {
    let triangles: &[[u32; 3]] = axis.surface.as_ref().map_or(&[], |m| m.triangles());
    let mut edges: Vec<[u32; 2]> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .chain(axis.free_edges.iter().copied())
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    writeln!(
        w,
        "{} {} {}",
        axis.positions.len(),
        edges.len(),
        triangles.len()
    )?;
    for (p, r) in axis.positions.iter().zip(&axis.radii) {
        writeln!(w, "v {} {} {} {r}", p[0], p[1], p[2])?;
    }
    for [a, b] in &edges {
        writeln!(w, "e {a} {b}")?;
    }
    for [a, b, c] in triangles {
        writeln!(w, "f {a} {b} {c}")?;
    }
    Ok(())
}
