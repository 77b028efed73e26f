//! PLY through `ply-rs-bw`: ascii, binary little- and big-endian. Vertices need scalar
//! `x y z` (any numeric type); faces a list `vertex_indices` (or `vertex_index`) of any
//! integer type. Other elements and properties are skipped.

use crate::mesh::{MeshError, TriMesh};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};
use std::io::Cursor;
use std::path::Path;

/// The names a face's index list goes by in the wild.
const FACE_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// One vertex record: only the position is kept.
struct VertexRow([f64; 3]);

impl PropertyAccess for VertexRow {
    fn new() -> Self {
        VertexRow([0.0; 3])
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let value = match property {
            Property::Char(v) => f64::from(v),
            Property::UChar(v) => f64::from(v),
            Property::Short(v) => f64::from(v),
            Property::UShort(v) => f64::from(v),
            Property::Int(v) => f64::from(v),
            Property::UInt(v) => f64::from(v),
            Property::Float(v) => f64::from(v),
            Property::Double(v) => v,
            _ => return PropertyAccessResult::Ignored,
        };
        self.set(name, value)
    }

    // The two float setters skip the `Property` detour: they are the hot path.
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }

    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.set(name, value)
    }
}

impl VertexRow {
    fn set(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.0[axis] = value;
        PropertyAccessResult::Set
    }
}

/// One face record: its vertex indices, widened to `i64` so negative ones can be reported
/// as given.
struct FaceRow(Vec<i64>);

impl PropertyAccess for FaceRow {
    fn new() -> Self {
        FaceRow(Vec::new())
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if !FACE_LISTS.contains(&name) {
            return PropertyAccessResult::Ignored;
        }
        fn widen<T: Copy + Into<i64>>(v: Vec<T>) -> Vec<i64> {
            v.into_iter().map(Into::into).collect()
        }
        self.0 = match property {
            Property::ListChar(v) => widen(v),
            Property::ListUChar(v) => widen(v),
            Property::ListShort(v) => widen(v),
            Property::ListUShort(v) => widen(v),
            Property::ListInt(v) => widen(v),
            Property::ListUInt(v) => widen(v),
            _ => return PropertyAccessResult::UnsupportedType,
        };
        PropertyAccessResult::Set
    }
}

/// Elements the mesh does not use; read only to move past them.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<TriMesh, MeshError> {
    let parse = |line: usize, message: String| MeshError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut reader = Reader::new(Cursor::new(bytes));
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| from_ply_error(path, e, true))?;
    let ascii = matches!(header.encoding, Encoding::Ascii);
    let element = |name: &str| {
        header.elements.get(name).ok_or_else(|| {
            parse(
                header_line(bytes, name),
                format!("the header has no `element {name}`"),
            )
        })
    };
    let vertex_def = element("vertex")?;
    for axis in ["x", "y", "z"] {
        if !matches!(
            vertex_def.properties.get(axis).map(|p| &p.data_type),
            Some(PropertyType::Scalar(_))
        ) {
            return Err(parse(
                header_line(bytes, "vertex"),
                format!("element `vertex` has no scalar property `{axis}`"),
            ));
        }
    }
    let face_def = element("face")?;
    if !face_def.properties.iter().any(|(name, p)| {
        FACE_LISTS.contains(&name.as_str())
            && matches!(&p.data_type, PropertyType::List(_, t) if is_integer(t))
    }) {
        return Err(parse(
            header_line(bytes, "face"),
            "element `face` has no integer list property `vertex_indices` (or `vertex_index`)"
                .into(),
        ));
    }

    let mut vertices: Vec<VertexRow> = Vec::new();
    let mut faces: Vec<FaceRow> = Vec::new();
    let mut seen = 0;
    // Elements must be read in header order; whatever follows vertex and face is left
    // unread, so a damaged trailing element we would ignore anyway cannot fail the read.
    for (name, def) in &header.elements {
        let result = match name.as_str() {
            "vertex" => read_element(&mut reader, def, &header).map(|v| vertices = v),
            "face" => read_element(&mut reader, def, &header).map(|f| faces = f),
            _ => read_element::<Skip>(&mut reader, def, &header).map(drop),
        };
        result.map_err(|e| from_ply_error(path, e, ascii))?;
        if name == "vertex" || name == "face" {
            seen += 1;
            if seen == 2 {
                break;
            }
        }
    }

    let n = vertices.len();
    let positions: Vec<[f64; 3]> = vertices.into_iter().map(|v| v.0).collect();
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(faces.len());
    for (f, FaceRow(indices)) in faces.iter().enumerate() {
        if indices.len() < 3 {
            return Err(parse(
                0,
                format!(
                    "face {f} has {} vertices; a face needs at least 3",
                    indices.len()
                ),
            ));
        }
        let mut polygon = [0u32; 3];
        for (k, &i) in indices.iter().enumerate() {
            let v = match u32::try_from(i) {
                Ok(v) if (v as usize) < n => v,
                _ => {
                    return Err(MeshError::IndexOutOfRange {
                        face: f,
                        vertex: i,
                        vertex_count: n,
                    }
                    .in_file(path))
                }
            };
            // Fan triangulation, streamed: corner 0, the previous corner, this one.
            match k {
                0 | 1 => polygon[k] = v,
                _ => {
                    polygon[2] = v;
                    triangles.push(polygon);
                    polygon[1] = v;
                }
            }
        }
    }
    TriMesh::new(positions, triangles).map_err(|e| e.in_file(path))
}

fn read_element<E: PropertyAccess>(
    reader: &mut Reader<Cursor<&[u8]>>,
    def: &ElementDef,
    header: &Header,
) -> Result<Vec<E>, ParseError> {
    Parser::<E>::new().read_payload_for_element(reader, def, header)
}

fn is_integer(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// Converts the crate's error, keeping its line for text (header, ascii payload). In a
/// binary payload the crate counts elements as "lines", which would mislead: the line is
/// dropped there and its message, which names the element and its index, kept.
fn from_ply_error(path: &Path, e: ParseError, has_lines: bool) -> MeshError {
    let text = e.to_string();
    let (line, message) = match e.line() {
        Some(line) => {
            let message = text
                .strip_prefix(&format!("Line {line}: "))
                .unwrap_or(&text)
                .to_string();
            (if has_lines { line } else { 0 }, message)
        }
        None => (0, text),
    };
    MeshError::Parse {
        path: path.to_path_buf(),
        line,
        // The crate's messages span lines ("\n\tString: …"); one line reads better after
        // `path:line:`.
        message: message.replace("\n\t", "; "),
    }
}

/// The 1-based header line declaring `element <name>`; if there is none, the line of
/// `end_header`, where the declaration was due at the latest.
fn header_line(bytes: &[u8], name: &str) -> usize {
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = String::from_utf8_lossy(line);
        let mut words = line.split_whitespace();
        match (words.next(), words.next()) {
            (Some("element"), Some(n)) if n == name => return i + 1,
            (Some("end_header"), _) => return i + 1,
            _ => {}
        }
    }
    0
}
