//! PLY: ascii, binary little- and big-endian. Vertices need scalar `x y z` (any numeric
//! type). Faces come from an element `face` with an integer list `vertex_indices` (or
//! `vertex_index`), polygons fan-triangulated, and/or from an element `tristrips` with
//! an integer list `vertex_indices` holding triangle strips separated by `-1` (as in the
//! classic scanned models, e.g. `igea.ply`). Other elements and properties are skipped;
//! elements after the last one needed are not read at all.
//!
//! Hand-written rather than through a PLY crate, for three reasons: every message names
//! the element, its index, the property and (ascii) the line in plain words; every count
//! the header gives is checked against the bytes that follow before anything is sized
//! by it; and triangle strips need their own decoding anyway.

mod header;
mod records;

use super::sniff;
use super::text::{at_line, parse_error, Lines};
use crate::mesh::{MeshError, TriMesh};
use header::{check_counts, read_header, Element, Format, Header, Kind, Property};
use records::{Binary, Place, Records};
use std::path::Path;

/// The names a face's index list goes by in the wild.
const INDEX_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// Refuses a file whose first line is not `ply`, and a binary payload too short for the
/// counts its header declares, before the rest of the file is read (when the header
/// lies within the start read so far; a longer header is checked once read).
pub(super) fn check(path: &Path, head: &[u8], size: u64) -> Result<u64, MeshError> {
    let start = sniff::without_bom(head);
    let first = start.split(|&b| b == b'\n').next().unwrap_or(start);
    let cut = first.len() == start.len();
    let first_is_ply = match std::str::from_utf8(first) {
        Ok(text) => text.trim() == "ply" || (cut && text.trim().is_empty()),
        Err(_) => false,
    };
    if !first_is_ply {
        return Err(sniff::wrong_format(path, "a PLY file", head));
    }
    if let Ok(header) = read_header(path, head) {
        let needed = ["vertex", "face", "tristrips"]
            .iter()
            .filter_map(|name| header.elements.iter().position(|e| e.name == *name))
            .max();
        if let Some(last_needed) = needed {
            let data_len = usize::try_from(size).unwrap_or(usize::MAX) - header.data_start;
            check_counts(path, data_len, &header, last_needed)?;
        }
    }
    Ok(size)
}

pub(super) fn read(path: &Path, bytes: &[u8], weld: bool) -> Result<TriMesh, MeshError> {
    let header = read_header(path, bytes)?;
    let layout = Layout::of(path, &header)?;
    check_counts(
        path,
        bytes.len() - header.data_start,
        &header,
        layout.last_needed,
    )?;

    let nv = header.elements[layout.vertex_at].count as usize;
    let data = &bytes[header.data_start..];
    let mut records = match header.format {
        Format::Ascii => Records::Ascii {
            lines: Lines::starting_after(path, data, header.end_line),
            tokens: "".split_whitespace(),
        },
        Format::Binary { big_endian } => Records::Binary(Binary {
            data,
            at: 0,
            big_endian,
            offset: header.data_start,
        }),
    };
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut faces = Faces {
        nv,
        triangles: Vec::new(),
        count: 0,
        list: Vec::new(),
    };
    for (at, element) in header
        .elements
        .iter()
        .enumerate()
        .take(layout.last_needed + 1)
    {
        let role = layout.role(at);
        if element.properties.is_empty() {
            continue; // records of nothing take no bytes and no lines
        }
        if role == Role::Vertex {
            // Checked against the payload's size (binary), or bounded by its lines.
            let room = nv.min(data.len() / 2 + 1);
            crate::mesh::try_reserve(&mut positions, room, || format!("{nv} vertices"))
                .map_err(|e| e.in_file(path))?;
        }
        for index in 0..element.count {
            let line = records.start_record(path, element, index)?;
            let record = Record {
                path,
                element,
                index,
                line,
            };
            match role {
                Role::Vertex => {
                    let p = record.vertex(&mut records, &layout.axis_slot)?;
                    crate::mesh::try_grow(&mut positions, 1, "vertices")
                        .map_err(|e| e.in_file(path))?;
                    positions.push(p);
                }
                Role::Faces(which) => record.polygon(&mut records, which, false, &mut faces)?,
                Role::Strips(which) => record.polygon(&mut records, which, true, &mut faces)?,
                Role::Skip => record.skip(&mut records)?,
            }
            records.end_record(path, element, index, line)?;
        }
    }
    super::build(path, positions, faces.triangles, weld)
}

/// Where the mesh is in a header: which elements hold the vertices, the polygons and
/// the strips, and which of their properties hold the coordinates and the index lists.
/// Found (and checked) once, before any record is read.
struct Layout {
    vertex_at: usize,
    /// For each property of the vertex element, the axis it gives, if any.
    axis_slot: Vec<Option<usize>>,
    face_at: Option<usize>,
    strips_at: Option<usize>,
    /// The index of the index list among `face`'s properties.
    face_list: Option<usize>,
    /// The index of the index list among `tristrips`' properties.
    strip_list: Option<usize>,
    /// The last element read; those after it are not needed.
    last_needed: usize,
}

impl Layout {
    /// Finds the vertex element and its `x y z`, and the face and strip elements and
    /// their index lists, or says what the header lacks.
    fn of(path: &Path, header: &Header) -> Result<Layout, MeshError> {
        let find = |name: &str| header.elements.iter().position(|e| e.name == name);
        let Some(vertex_at) = find("vertex") else {
            return Err(parse_error(
                path,
                header.end_line,
                "the header has no `element vertex`",
            ));
        };
        let vertex = &header.elements[vertex_at];
        let mut axis_slot = vec![None; vertex.properties.len()];
        for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
            match vertex.properties.iter().position(|p| p.name == name) {
                Some(k) if matches!(vertex.properties[k].kind, Kind::Scalar(_)) => {
                    axis_slot[k] = Some(axis)
                }
                _ => {
                    return Err(parse_error(
                        path,
                        vertex.line,
                        format!("element `vertex` has no scalar property `{name}`"),
                    ))
                }
            }
        }
        // The index list of `face` or `tristrips`, if the element is there.
        let index_list = |at: usize| -> Result<usize, MeshError> {
            let e = &header.elements[at];
            e.properties
                .iter()
                .position(|p| {
                    INDEX_LISTS.contains(&p.name.as_str())
                        && matches!(p.kind, Kind::List { item, .. } if item.is_integer())
                })
                .ok_or_else(|| {
                    parse_error(
                        path,
                        e.line,
                        format!(
                            "element `{}` has no integer list property `vertex_indices` \
                             (or `vertex_index`)",
                            e.name
                        ),
                    )
                })
        };
        let face_at = find("face");
        let strips_at = find("tristrips");
        if face_at.is_none() && strips_at.is_none() {
            return Err(parse_error(
                path,
                header.end_line,
                "the header has no `element face` (nor `element tristrips`)",
            ));
        }
        let face_list = face_at.map(index_list).transpose()?;
        let strip_list = strips_at.map(index_list).transpose()?;
        let last_needed = [Some(vertex_at), face_at, strips_at]
            .into_iter()
            .flatten()
            .max()
            .unwrap_or(vertex_at);
        Ok(Layout {
            vertex_at,
            axis_slot,
            face_at,
            strips_at,
            face_list,
            strip_list,
            last_needed,
        })
    }

    /// What the element at `at` is read for.
    fn role(&self, at: usize) -> Role {
        if at == self.vertex_at {
            Role::Vertex
        } else if Some(at) == self.face_at {
            Role::Faces(self.face_list.unwrap_or(0))
        } else if Some(at) == self.strips_at {
            Role::Strips(self.strip_list.unwrap_or(0))
        } else {
            Role::Skip
        }
    }
}

/// The triangles read so far, with what reading more of them needs: the vertex count
/// (to check indices), the number of polygons read (to name one in an error) and the
/// buffer one index list is read into (reused from record to record).
struct Faces {
    nv: usize,
    triangles: Vec<[u32; 3]>,
    count: usize,
    list: Vec<i64>,
}

/// One record being read: its element, its index and (ascii) its line, to name it in
/// messages.
#[derive(Clone, Copy)]
struct Record<'a> {
    path: &'a Path,
    element: &'a Element,
    index: u64,
    line: Option<usize>,
}

impl<'a> Record<'a> {
    /// Where the value of `property` is read, for messages.
    fn place(&self, property: &'a Property) -> Place<'a> {
        Place {
            element: &self.element.name,
            index: self.index,
            property: &property.name,
        }
    }

    /// A vertex record: its `x y z` (placed by `axis_slot`), the other values skipped.
    fn vertex(
        &self,
        records: &mut Records<'_>,
        axis_slot: &[Option<usize>],
    ) -> Result<[f64; 3], MeshError> {
        let mut p = [0.0; 3];
        for (k, property) in self.element.properties.iter().enumerate() {
            let place = self.place(property);
            match (property.kind, axis_slot[k]) {
                (Kind::Scalar(t), Some(axis)) => {
                    p[axis] = records.scalar(self.path, t, place, self.line)?;
                }
                (kind, _) => records.skip(self.path, kind, place, self.line)?,
            }
        }
        Ok(p)
    }

    /// A polygon record (fan-triangulated) or a strips record (`strip`), whose index
    /// list is property `which`: its triangles go into `faces`.
    fn polygon(
        &self,
        records: &mut Records<'_>,
        which: usize,
        strip: bool,
        faces: &mut Faces,
    ) -> Result<(), MeshError> {
        let (path, line) = (self.path, self.line);
        for (k, property) in self.element.properties.iter().enumerate() {
            let place = self.place(property);
            match property.kind {
                Kind::List { count, item } if k == which => {
                    records.list(path, count, item, place, line, &mut faces.list)?
                }
                kind => records.skip(path, kind, place, line)?,
            }
        }
        crate::mesh::try_grow(&mut faces.triangles, faces.list.len(), "triangles")
            .map_err(|e| e.in_file(path))?;
        let wrap = |e: MeshError| match line {
            Some(line) => at_line(path, line, e),
            None => e.in_file(path),
        };
        let element = self.element;
        let index = self.index;
        if !strip {
            fan(&faces.list, faces.nv, faces.count, &mut faces.triangles).map_err(|e| match e {
                Bad::Index(e) => wrap(e),
                Bad::Message(m) => located(path, line, place_of(element, index), m),
            })?;
            faces.count += 1;
        } else {
            strips(&faces.list, faces.nv, &mut faces.triangles)
                .map_err(|m| located(path, line, place_of(element, index), m))?;
        }
        Ok(())
    }

    /// A record of an element that is not used: every value skipped.
    fn skip(&self, records: &mut Records<'_>) -> Result<(), MeshError> {
        for property in &self.element.properties {
            records.skip(self.path, property.kind, self.place(property), self.line)?;
        }
        Ok(())
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Vertex,
    /// Polygons; the index of the index list among the properties.
    Faces(usize),
    /// Triangle strips; the index of the index list.
    Strips(usize),
    Skip,
}

fn place_of(element: &Element, index: u64) -> String {
    format!("{} {index}", element.name)
}

/// A [`MeshError::Parse`] at `line` (ascii) or naming the binary record.
fn located(path: &Path, line: Option<usize>, place: String, message: String) -> MeshError {
    parse_error(path, line.unwrap_or(0), format!("{place}: {message}"))
}

enum Bad {
    Index(MeshError),
    Message(String),
}

/// Fan-triangulates polygon `list` (face number `face`) into `out`.
fn fan(list: &[i64], nv: usize, face: usize, out: &mut Vec<[u32; 3]>) -> Result<(), Bad> {
    if list.len() < 3 {
        return Err(Bad::Message(format!(
            "the face has {} vertices; a face needs at least 3",
            list.len()
        )));
    }
    let vertex = |i: i64| match u32::try_from(i) {
        Ok(v) if (v as usize) < nv => Ok(v),
        _ => Err(Bad::Index(MeshError::IndexOutOfRange {
            face,
            vertex: i,
            vertex_count: nv,
        })),
    };
    let first = vertex(list[0])?;
    let mut previous = vertex(list[1])?;
    for &i in &list[2..] {
        let v = vertex(i)?;
        out.push([first, previous, v]);
        previous = v;
    }
    Ok(())
}

/// Decodes triangle strips (separated by `-1`) into `out`. Triangle `k` of a strip is
/// `(s[k], s[k+1], s[k+2])` for even `k` and `(s[k+1], s[k], s[k+2])` for odd `k`, so all
/// keep the strip's orientation. Triangles with a repeated vertex only stitch strips
/// together and are left out.
fn strips(list: &[i64], nv: usize, out: &mut Vec<[u32; 3]>) -> Result<(), String> {
    let mut strip_start = 0;
    for (k, &i) in list.iter().enumerate() {
        if i == -1 {
            strip_start = k + 1;
            continue;
        }
        let v = match u32::try_from(i) {
            Ok(v) if (v as usize) < nv => v,
            _ => {
                return Err(format!(
                    "entry {k} of the strip list is vertex {i}, but the mesh has {nv} \
                     vertices (-1 separates strips)"
                ))
            }
        };
        let in_strip = k - strip_start;
        if in_strip >= 2 {
            let (a, b) = (list[k - 2] as u32, list[k - 1] as u32);
            let t = if in_strip % 2 == 0 {
                [a, b, v]
            } else {
                [b, a, v]
            };
            if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
                out.push(t);
            }
        }
    }
    Ok(())
}
