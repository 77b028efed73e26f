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

use super::sniff;
use super::text::{at_line, parse_error, Lines};
use crate::mesh::{MeshError, TriMesh};
use std::path::Path;

/// The names a face's index list goes by in the wild.
const INDEX_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

struct Property {
    name: String,
    kind: Kind,
}

struct Element {
    name: String,
    count: u64,
    /// The header line that declares it.
    line: usize,
    properties: Vec<Property>,
}

impl Element {
    /// The fewest bytes one binary record can take (lists empty).
    fn min_binary_size(&self) -> u64 {
        self.properties
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(t) | Kind::List { count: t, .. } => t.size() as u64,
            })
            .sum()
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    Binary { big_endian: bool },
}

struct Header {
    format: Format,
    elements: Vec<Element>,
    /// Byte offset where the data starts (after `end_header`'s newline).
    data_start: usize,
    /// Number of the `end_header` line.
    end_line: usize,
}

/// The element, property and place a value is read for, to name it in messages.
#[derive(Clone, Copy)]
struct Place<'a> {
    element: &'a str,
    index: u64,
    property: &'a str,
}

impl std::fmt::Display for Place<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {}, property `{}`",
            self.element, self.index, self.property
        )
    }
}

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
    check_counts(path, bytes.len() - header.data_start, &header, last_needed)?;

    let nv = vertex.count as usize;
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
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut face_count = 0usize;
    let mut list: Vec<i64> = Vec::new();
    for (at, element) in header.elements.iter().enumerate().take(last_needed + 1) {
        let role = if at == vertex_at {
            Role::Vertex
        } else if Some(at) == face_at {
            Role::Faces(face_list.unwrap_or(0))
        } else if Some(at) == strips_at {
            Role::Strips(strip_list.unwrap_or(0))
        } else {
            Role::Skip
        };
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
            match role {
                Role::Vertex => {
                    let mut p = [0.0; 3];
                    for (k, property) in element.properties.iter().enumerate() {
                        let place = Place {
                            element: &element.name,
                            index,
                            property: &property.name,
                        };
                        match (property.kind, axis_slot[k]) {
                            (Kind::Scalar(t), Some(axis)) => {
                                p[axis] = records.scalar(path, t, place, line)?;
                            }
                            (kind, _) => records.skip(path, kind, place, line)?,
                        }
                    }
                    crate::mesh::try_grow(&mut positions, 1, "vertices")
                        .map_err(|e| e.in_file(path))?;
                    positions.push(p);
                }
                Role::Faces(which) | Role::Strips(which) => {
                    for (k, property) in element.properties.iter().enumerate() {
                        let place = Place {
                            element: &element.name,
                            index,
                            property: &property.name,
                        };
                        match property.kind {
                            Kind::List { count, item } if k == which => {
                                records.list(path, count, item, place, line, &mut list)?
                            }
                            kind => records.skip(path, kind, place, line)?,
                        }
                    }
                    crate::mesh::try_grow(&mut triangles, list.len(), "triangles")
                        .map_err(|e| e.in_file(path))?;
                    let wrap = |e: MeshError| match line {
                        Some(line) => at_line(path, line, e),
                        None => e.in_file(path),
                    };
                    if matches!(role, Role::Faces(_)) {
                        fan(&list, nv, face_count, &mut triangles).map_err(|e| match e {
                            Bad::Index(e) => wrap(e),
                            Bad::Message(m) => located(path, line, place_of(element, index), m),
                        })?;
                        face_count += 1;
                    } else {
                        strips(&list, nv, &mut triangles)
                            .map_err(|m| located(path, line, place_of(element, index), m))?;
                    }
                }
                Role::Skip => {
                    for property in &element.properties {
                        let place = Place {
                            element: &element.name,
                            index,
                            property: &property.name,
                        };
                        records.skip(path, property.kind, place, line)?;
                    }
                }
            }
            records.end_record(path, element, index, line)?;
        }
    }
    super::build(path, positions, triangles, weld)
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

/// Reads the header: its lines up to `end_header`.
fn read_header(path: &Path, bytes: &[u8]) -> Result<Header, MeshError> {
    // A byte-order mark before `ply` is skipped; offsets stay the file's.
    let mut at = bytes.len() - sniff::without_bom(bytes).len();
    let mut line_no = 0usize;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if at >= bytes.len() {
            return Err(parse_error(
                path,
                line_no,
                "the header has no `end_header` line (the file ends inside the header)",
            ));
        }
        let end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |i| at + i);
        let raw = &bytes[at..end];
        at = (end + 1).min(bytes.len());
        line_no += 1;
        let Ok(text) = std::str::from_utf8(raw) else {
            if line_no == 1 {
                return Err(sniff::wrong_format(path, "a PLY file", bytes));
            }
            return Err(parse_error(
                path,
                line_no,
                "the header line is not text (is the file cut or damaged?)",
            ));
        };
        let text = text.trim();
        if line_no == 1 {
            if text != "ply" {
                return Err(sniff::wrong_format(path, "a PLY file", bytes));
            }
            continue;
        }
        let mut words = text.split_whitespace();
        let error = |message: String| parse_error(path, line_no, message);
        match words.next() {
            None | Some("comment") | Some("obj_info") => {}
            Some("format") => {
                format = Some(match words.next() {
                    Some("ascii") => Format::Ascii,
                    Some("binary_little_endian") => Format::Binary { big_endian: false },
                    Some("binary_big_endian") => Format::Binary { big_endian: true },
                    other => {
                        return Err(error(format!(
                            "unknown PLY format `{}` (expected ascii, binary_little_endian \
                             or binary_big_endian)",
                            other.unwrap_or("")
                        )))
                    }
                })
            }
            Some("element") => {
                let (Some(name), Some(count)) = (words.next(), words.next()) else {
                    return Err(error(
                        "an element needs a name and a count: `element NAME COUNT`".into(),
                    ));
                };
                let count: u64 = count.parse().map_err(|_| {
                    error(format!(
                        "the count of element `{name}` is `{count}`, not a whole number"
                    ))
                })?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    line: line_no,
                    properties: Vec::new(),
                });
            }
            Some("property") => {
                let Some(element) = elements.last_mut() else {
                    return Err(error("a property comes before any `element` line".into()));
                };
                let scalar = |name: Option<&str>| -> Result<Scalar, MeshError> {
                    let name = name.unwrap_or("");
                    Scalar::from_name(name).ok_or_else(|| {
                        error(format!(
                            "unknown property type `{name}` (expected char, uchar, short, \
                             ushort, int, uint, float or double, or int8 … float64)"
                        ))
                    })
                };
                let kind = match words.next() {
                    Some("list") => {
                        let count = scalar(words.next())?;
                        if !count.is_integer() {
                            return Err(error(
                                "a list's count type must be an integer type".into(),
                            ));
                        }
                        Kind::List {
                            count,
                            item: scalar(words.next())?,
                        }
                    }
                    other => Kind::Scalar(scalar(other)?),
                };
                let Some(name) = words.next() else {
                    return Err(error("the property has no name".into()));
                };
                element.properties.push(Property {
                    name: name.to_string(),
                    kind,
                });
            }
            Some("end_header") => {
                let Some(format) = format else {
                    return Err(error("the header ends without a `format` line".into()));
                };
                return Ok(Header {
                    format,
                    elements,
                    data_start: at,
                    end_line: line_no,
                });
            }
            Some(other) => {
                return Err(error(format!(
                    "unknown header line `{other}` (expected format, element, property, \
                     comment or end_header)"
                )))
            }
        }
    }
}

/// Refuses counts a binary payload cannot hold, before anything is sized by them: a
/// record takes at least its scalars' and list counts' bytes. An ascii payload is read
/// line by line instead, and a short one reported as truncated where it ends.
fn check_counts(
    path: &Path,
    data_len: usize,
    header: &Header,
    last_needed: usize,
) -> Result<(), MeshError> {
    if header.format == Format::Ascii {
        return Ok(());
    }
    let mut left = data_len as u64;
    for element in header.elements.iter().take(last_needed + 1) {
        let per_record = element.min_binary_size();
        let at_most = left.checked_div(per_record).unwrap_or(u64::MAX);
        if element.count > at_most {
            return Err(MeshError::ImplausibleCount {
                path: path.to_path_buf(),
                line: element.line,
                what: format!(
                    "`{}` elements (`element {} {}`, at least {per_record} bytes each)",
                    element.name, element.name, element.count
                ),
                declared: element.count,
                bytes: data_len as u64,
                at_most,
            });
        }
        left -= element.count * per_record;
    }
    Ok(())
}

/// The payload, read record by record.
enum Records<'a> {
    Ascii {
        lines: Lines<'a>,
        /// The values of the current record's line.
        tokens: std::str::SplitWhitespace<'a>,
    },
    Binary(Binary<'a>),
}

struct Binary<'a> {
    data: &'a [u8],
    at: usize,
    big_endian: bool,
    /// Offset of `data` in the file, for messages.
    offset: usize,
}

impl Binary<'_> {
    /// The next `n` bytes, or an error naming what was being read.
    fn take(&mut self, path: &Path, n: usize, place: Place<'_>) -> Result<&[u8], MeshError> {
        match self
            .at
            .checked_add(n)
            .and_then(|end| self.data.get(self.at..end))
        {
            Some(b) => {
                self.at += n;
                Ok(b)
            }
            None => Err(parse_error(
                path,
                0,
                format!(
                    "the file is truncated: it ends at byte {} inside {place}",
                    self.offset + self.data.len()
                ),
            )),
        }
    }

    fn number(&mut self, path: &Path, t: Scalar, place: Place<'_>) -> Result<Number, MeshError> {
        let big = self.big_endian;
        let b = self.take(path, t.size(), place)?;
        macro_rules! get {
            ($ty:ty) => {{
                let a = b.try_into().expect("take returned the type's size");
                if big {
                    <$ty>::from_be_bytes(a)
                } else {
                    <$ty>::from_le_bytes(a)
                }
            }};
        }
        Ok(match t {
            Scalar::I8 => Number::Int(i64::from(get!(i8))),
            Scalar::U8 => Number::Int(i64::from(get!(u8))),
            Scalar::I16 => Number::Int(i64::from(get!(i16))),
            Scalar::U16 => Number::Int(i64::from(get!(u16))),
            Scalar::I32 => Number::Int(i64::from(get!(i32))),
            Scalar::U32 => Number::Int(i64::from(get!(u32))),
            Scalar::F32 => Number::Float(f64::from(get!(f32))),
            Scalar::F64 => Number::Float(get!(f64)),
        })
    }
}

#[derive(Clone, Copy)]
enum Number {
    Int(i64),
    Float(f64),
}

impl Number {
    fn to_f64(self) -> f64 {
        match self {
            Number::Int(i) => i as f64,
            Number::Float(x) => x,
        }
    }
}

impl<'a> Records<'a> {
    /// Starts a record: in ascii, takes its line and returns its number.
    fn start_record(
        &mut self,
        path: &Path,
        element: &Element,
        index: u64,
    ) -> Result<Option<usize>, MeshError> {
        let Records::Ascii { lines, tokens } = self else {
            return Ok(None);
        };
        match lines.next() {
            Some(item) => {
                let (line, text) = item?;
                *tokens = text.split_whitespace();
                Ok(Some(line))
            }
            None => Err(parse_error(
                path,
                lines.end_line(),
                format!(
                    "the file is truncated: expected {} {index} of the {} that \
                     `element {} {}` (line {}) declares, found the end of the file",
                    element.name, element.count, element.name, element.count, element.line
                ),
            )),
        }
    }

    /// Ends a record: in ascii, its line must hold nothing more.
    fn end_record(
        &mut self,
        path: &Path,
        element: &Element,
        index: u64,
        line: Option<usize>,
    ) -> Result<(), MeshError> {
        if let Records::Ascii { tokens, .. } = self {
            if let Some(extra) = tokens.next() {
                return Err(parse_error(
                    path,
                    line.unwrap_or(0),
                    format!(
                        "{} {index} has more values than the header declares for it \
                         (`{extra}` is one too many)",
                        element.name
                    ),
                ));
            }
        }
        Ok(())
    }

    fn number(
        &mut self,
        path: &Path,
        t: Scalar,
        place: Place<'_>,
        line: Option<usize>,
    ) -> Result<Number, MeshError> {
        match self {
            Records::Binary(b) => b.number(path, t, place),
            Records::Ascii { tokens, .. } => {
                let line = line.unwrap_or(0);
                let Some(token) = tokens.next() else {
                    return Err(parse_error(
                        path,
                        line,
                        format!("{place}: the value is missing (the line ends before it)"),
                    ));
                };
                let parsed = if t.is_integer() {
                    token.parse().ok().map(Number::Int)
                } else {
                    token.parse().ok().map(Number::Float)
                };
                parsed.ok_or_else(|| {
                    let kind = if t.is_integer() {
                        "an integer"
                    } else {
                        "a number"
                    };
                    parse_error(
                        path,
                        line,
                        format!("{place}: expected {kind}, found `{token}`"),
                    )
                })
            }
        }
    }

    /// An integer value (list counts and indices, whose types the header check made
    /// integer types).
    fn integer(
        &mut self,
        path: &Path,
        t: Scalar,
        place: Place<'_>,
        line: Option<usize>,
    ) -> Result<i64, MeshError> {
        match self.number(path, t, place, line)? {
            Number::Int(i) => Ok(i),
            Number::Float(_) => Err(parse_error(
                path,
                line.unwrap_or(0),
                format!("{place}: expected an integer type"),
            )),
        }
    }

    fn scalar(
        &mut self,
        path: &Path,
        t: Scalar,
        place: Place<'_>,
        line: Option<usize>,
    ) -> Result<f64, MeshError> {
        Ok(self.number(path, t, place, line)?.to_f64())
    }

    /// A list's length, checked against what the rest of a binary file can hold.
    fn list_len(
        &mut self,
        path: &Path,
        count: Scalar,
        item: Scalar,
        place: Place<'_>,
        line: Option<usize>,
    ) -> Result<usize, MeshError> {
        let n = self.integer(path, count, place, line)?;
        let n = u64::try_from(n).map_err(|_| {
            parse_error(
                path,
                line.unwrap_or(0),
                format!("{place}: the list has a negative length {n}"),
            )
        })?;
        if let Records::Binary(b) = self {
            let left = (b.data.len() - b.at) as u64;
            if n.saturating_mul(item.size() as u64) > left {
                return Err(parse_error(
                    path,
                    0,
                    format!(
                        "{place}: the list declares {n} entries of {} bytes, but only {left} \
                         bytes are left in the file (byte {})",
                        item.size(),
                        b.offset + b.at
                    ),
                ));
            }
        }
        // In ascii the line holds at most one entry per two bytes.
        Ok(n.min(usize::MAX as u64) as usize)
    }

    /// Reads an integer list into `out`.
    fn list(
        &mut self,
        path: &Path,
        count: Scalar,
        item: Scalar,
        place: Place<'_>,
        line: Option<usize>,
        out: &mut Vec<i64>,
    ) -> Result<(), MeshError> {
        let n = self.list_len(path, count, item, place, line)?;
        out.clear();
        for _ in 0..n {
            out.push(self.integer(path, item, place, line)?);
        }
        Ok(())
    }

    /// Moves past a value that is not used.
    fn skip(
        &mut self,
        path: &Path,
        kind: Kind,
        place: Place<'_>,
        line: Option<usize>,
    ) -> Result<(), MeshError> {
        match kind {
            Kind::Scalar(t) => self.number(path, t, place, line).map(drop),
            Kind::List { count, item } => {
                let n = self.list_len(path, count, item, place, line)?;
                match self {
                    Records::Binary(b) => b.take(path, n * item.size(), place).map(drop),
                    Records::Ascii { .. } => {
                        for _ in 0..n {
                            self.number(path, item, place, line)?;
                        }
                        Ok(())
                    }
                }
            }
        }
    }
}
