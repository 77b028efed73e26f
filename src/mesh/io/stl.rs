//! STL, ascii and binary, with corners that have bit-identical coordinates welded into
//! one vertex (STL stores each triangle's corners separately).
//!
//! Which of the two a file is: a file whose size matches the triangle count at bytes
//! 80–84 (`84 + 50 × count`) is binary whatever its first bytes say (many binary writers
//! start the 80-byte header with `solid`); otherwise a text file starting with `solid` is
//! ascii, and other text is refused as not STL (an OBJ given the wrong extension, say).
//!
//! Hand-written rather than through a crate, so that an ascii error names its line and
//! a binary one its triangle, in plain words, and the binary triangle count is checked
//! against the file's size before anything is sized by it. Coordinates are read as
//! `f32`, the format's precision, and widened.

use super::sniff;
use super::text::{parse_error, Lines};
use crate::mesh::{MeshError, TriMesh};
use std::collections::HashMap;
use std::path::Path;

const HEADER: usize = 84;
const RECORD: usize = 50;

/// Which of the two an STL file is.
enum Layout {
    /// Binary, with this many triangles (a file longer than they need has its trailing
    /// bytes ignored, as other readers do).
    Binary(u64),
    Ascii,
}

/// Tells binary from ascii by the file's start (at least its first 84 bytes when it
/// has them) and its size, and refuses what is neither: text that does not start with
/// `solid`, binary data too short for its header or its triangle count.
fn layout(path: &Path, start: &[u8], size: u64) -> Result<Layout, MeshError> {
    let declared = start
        .get(80..HEADER)
        .and_then(|b| <[u8; 4]>::try_from(b).ok())
        .map(|b| u64::from(u32::from_le_bytes(b)));
    let binary_size = declared.map(|n| HEADER as u64 + RECORD as u64 * n);
    if binary_size == Some(size) {
        return Ok(Layout::Binary(declared.unwrap_or(0)));
    }
    if sniff::binary(start).is_none() {
        let starts_solid = first_word(start).is_some_and(|w| w.eq_ignore_ascii_case("solid"));
        if !starts_solid {
            return Err(MeshError::WrongFormat {
                path: path.to_path_buf(),
                expected: "an STL file",
                found: format!(
                    "{}; an ascii STL starts with `solid`, and the file is too short or too \
                     long for a binary STL",
                    sniff::describe(start)
                ),
            });
        }
        return Ok(Layout::Ascii);
    }
    let (Some(n), Some(binary_size)) = (declared, binary_size) else {
        return Err(parse_error(
            path,
            0,
            format!(
                "too short for a binary STL: {size} bytes, where the header alone has {HEADER}"
            ),
        ));
    };
    if size < binary_size {
        let complete = (size - HEADER as u64) / RECORD as u64;
        return Err(parse_error(
            path,
            0,
            format!(
                "the binary STL is truncated: its header declares {n} triangles \
                 ({binary_size} bytes) but the file has {size} bytes; triangle {complete} is incomplete"
            ),
        ));
    }
    Ok(Layout::Binary(n))
}

/// Decides the layout from the file's start and size, before the rest is read: a binary
/// STL needs only the bytes of its declared triangles.
pub(super) fn check(path: &Path, head: &[u8], size: u64) -> Result<u64, MeshError> {
    Ok(match layout(path, head, size)? {
        Layout::Binary(n) => HEADER as u64 + RECORD as u64 * n,
        Layout::Ascii => size,
    })
}

/// Reads an STL; its corners are always welded (`_weld` changes nothing).
pub(super) fn read(path: &Path, bytes: &[u8], _weld: bool) -> Result<TriMesh, MeshError> {
    let mut welder = Welder::default();
    match layout(path, bytes, bytes.len() as u64)? {
        Layout::Binary(n) => read_binary(path, bytes, n, &mut welder)?,
        Layout::Ascii => read_ascii(path, bytes, &mut welder)?,
    }
    let Welder {
        positions,
        triangles,
        ..
    } = welder;
    TriMesh::new(positions, triangles).map_err(|e| e.in_file(path))
}

/// The first word of the file, if its start is text.
fn first_word(bytes: &[u8]) -> Option<&str> {
    let bytes = sniff::without_bom(bytes);
    let end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .unwrap_or(bytes.len());
    let line = &bytes[..end];
    // A first line cut by the end of the file's start read so far is still text.
    let valid = match std::str::from_utf8(line) {
        Ok(text) => text,
        Err(e) => std::str::from_utf8(&line[..e.valid_up_to()]).ok()?,
    };
    valid.split_whitespace().next()
}

/// Corners welded by their exact coordinates.
#[derive(Default)]
struct Welder {
    positions: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
    index_of: HashMap<[u32; 3], u32>,
}

impl Welder {
    fn corner(&mut self, p: [f32; 3]) -> Result<u32, MeshError> {
        // `+ 0.0` turns -0.0 into 0.0, so the two zeros weld as the same point.
        let p = p.map(|c| c + 0.0);
        let key = p.map(f32::to_bits);
        if let Some(&v) = self.index_of.get(&key) {
            return Ok(v);
        }
        if self.positions.len() == self.positions.capacity() {
            // Grown by doubling, as `push` would, but failing with an error.
            let more = self.positions.len().max(1024);
            let total = self.positions.len() + more;
            crate::mesh::try_reserve(&mut self.positions, more, || {
                format!("{total} welded vertices")
            })?;
            self.index_of
                .try_reserve(more)
                .map_err(|_| MeshError::OutOfMemory {
                    what: format!("the index of {total} welded vertices"),
                    bytes: (more as u64).saturating_mul(16),
                })?;
        }
        self.positions.push(p.map(f64::from));
        let v = self.positions.len() as u32 - 1;
        self.index_of.insert(key, v);
        Ok(v)
    }

    fn triangle(&mut self, corners: [[f32; 3]; 3]) -> Result<(), MeshError> {
        let t = [
            self.corner(corners[0])?,
            self.corner(corners[1])?,
            self.corner(corners[2])?,
        ];
        if self.triangles.len() == self.triangles.capacity() {
            let more = self.triangles.len().max(1024);
            let total = self.triangles.len() + more;
            crate::mesh::try_reserve(&mut self.triangles, more, || format!("{total} triangles"))?;
        }
        self.triangles.push(t);
        Ok(())
    }
}

fn read_binary(path: &Path, bytes: &[u8], n: u64, welder: &mut Welder) -> Result<(), MeshError> {
    // The caller checked that the file holds every record the count declares.
    let records = bytes[HEADER..].chunks_exact(RECORD);
    let n = usize::try_from(n).unwrap_or(usize::MAX);
    crate::mesh::try_reserve(&mut welder.triangles, n, || format!("{n} triangles"))
        .map_err(|e| e.in_file(path))?;
    for (t, record) in records.take(n).enumerate() {
        let mut corners = [[0f32; 3]; 3];
        for (k, c) in corners.iter_mut().flatten().enumerate() {
            let at = 12 + 4 * k;
            *c = f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]);
        }
        if corners.iter().flatten().any(|c| !c.is_finite()) {
            return Err(parse_error(
                path,
                0,
                format!(
                    "triangle {t} (byte {}) has a coordinate that is not finite: {}",
                    HEADER + t * RECORD,
                    Coords(corners)
                ),
            ));
        }
        welder.triangle(corners).map_err(|e| e.in_file(path))?;
    }
    Ok(())
}

/// Corners printed as `(x, y, z), …` for messages.
struct Coords([[f32; 3]; 3]);

impl std::fmt::Display for Coords {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, [x, y, z]) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "({x:?}, {y:?}, {z:?})")?;
        }
        Ok(())
    }
}

/// Where the ascii reader is in the grammar
/// `solid [name] { facet … outer loop vertex×3 endloop endfacet } endsolid [name]`,
/// repeated for files that hold several solids.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    /// Before `solid`.
    Start,
    /// Inside a solid, between facets.
    Solid,
    /// After `facet`, expecting `outer loop`.
    Facet,
    /// Inside the loop, after `n` vertices.
    Loop(usize),
    /// After `endloop`, expecting `endfacet`.
    EndLoop,
    /// After `endsolid`: another solid may follow.
    End,
}

fn read_ascii(path: &Path, bytes: &[u8], welder: &mut Welder) -> Result<(), MeshError> {
    let mut state = State::Start;
    let mut facet = 0usize;
    let mut facet_line = 0usize;
    let mut corners = [[0f32; 3]; 3];
    let mut lines = Lines::new(path, bytes);
    for item in &mut lines {
        let (line, text) = item?;
        let mut words = text.split_whitespace();
        let word = words.next().unwrap_or("").to_ascii_lowercase();
        let unexpected = |expected: &str| {
            parse_error(path, line, format!("expected {expected}, found `{text}`"))
        };
        state = match (state, word.as_str()) {
            (State::Start | State::End, "solid") => State::Solid,
            (State::Start, _) => return Err(unexpected("`solid`")),
            (State::End, _) => return Err(unexpected("`solid` or the end of the file")),
            (State::Solid, "facet") => {
                facet_line = line;
                State::Facet
            }
            (State::Solid, "endsolid") => State::End,
            (State::Solid, _) => return Err(unexpected("`facet` or `endsolid`")),
            (State::Facet, "outer") => State::Loop(0),
            (State::Facet, _) => {
                return Err(unexpected(&format!(
                    "`outer loop` (facet {facet} starts at line {facet_line})"
                )))
            }
            (State::Loop(n), "vertex") if n < 3 => {
                for (axis, c) in corners[n].iter_mut().enumerate() {
                    let token = words.next().ok_or_else(|| {
                        parse_error(
                            path,
                            line,
                            format!(
                                "vertex {n} of facet {facet}: the {} coordinate is missing",
                                ["x", "y", "z"][axis]
                            ),
                        )
                    })?;
                    *c = token
                        .parse::<f32>()
                        .ok()
                        .filter(|c| c.is_finite())
                        .ok_or_else(|| {
                            parse_error(
                                path,
                                line,
                                format!(
                                    "vertex {n} of facet {facet}: the {} coordinate `{token}` \
                                     is not a finite number",
                                    ["x", "y", "z"][axis]
                                ),
                            )
                        })?;
                }
                State::Loop(n + 1)
            }
            (State::Loop(3), "endloop") => State::EndLoop,
            (State::Loop(n), _) if n < 3 => {
                return Err(unexpected(&format!(
                    "`vertex x y z` (facet {facet}, which starts at line {facet_line}, has {n} \
                     of its 3 vertices)"
                )))
            }
            (State::Loop(_), _) => {
                return Err(unexpected(&format!(
                    "`endloop` (facet {facet}, which starts at line {facet_line}, has its 3 \
                     vertices; STL facets are triangles)"
                )))
            }
            (State::EndLoop, "endfacet") => {
                welder.triangle(corners).map_err(|e| e.in_file(path))?;
                facet += 1;
                State::Solid
            }
            (State::EndLoop, _) => return Err(unexpected("`endfacet`")),
        };
    }
    match state {
        State::End => Ok(()),
        State::Start | State::Solid => Err(parse_error(
            path,
            lines.end_line(),
            "the file ends before `endsolid`: it may be truncated",
        )),
        _ => Err(parse_error(
            path,
            facet_line,
            format!(
                "facet {facet}, which starts here, is cut off: the file ends before its \
                 `endfacet`"
            ),
        )),
    }
}
