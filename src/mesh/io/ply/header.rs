//! The PLY header: its format, its elements and their properties, read line by line up
//! to `end_header`, and the check of its counts against the payload's size.

use crate::mesh::io::sniff;
use crate::mesh::io::text::parse_error;
use crate::mesh::MeshError;
use std::path::Path;
use std::str::SplitWhitespace;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
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

    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

pub(super) struct Property {
    pub(super) name: String,
    pub(super) kind: Kind,
}

pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    /// The header line that declares it.
    pub(super) line: usize,
    pub(super) properties: Vec<Property>,
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
pub(super) enum Format {
    Ascii,
    Binary { big_endian: bool },
}

pub(super) struct Header {
    pub(super) format: Format,
    pub(super) elements: Vec<Element>,
    /// Byte offset where the data starts (after `end_header`'s newline).
    pub(super) data_start: usize,
    /// Number of the `end_header` line.
    pub(super) end_line: usize,
}

/// Reads the header: its lines up to `end_header`.
pub(super) fn read_header(path: &Path, bytes: &[u8]) -> Result<Header, MeshError> {
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
            Some("format") => format = Some(format_line(words.next()).map_err(error)?),
            Some("element") => elements.push(element_line(&mut words, line_no).map_err(error)?),
            Some("property") => {
                let Some(element) = elements.last_mut() else {
                    return Err(error("a property comes before any `element` line".into()));
                };
                let property = property_line(&mut words).map_err(error)?;
                element.properties.push(property);
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

/// The format a `format` line names (`word`, the one after `format`); the message of
/// an error, which the caller places on its line.
fn format_line(word: Option<&str>) -> Result<Format, String> {
    Ok(match word {
        Some("ascii") => Format::Ascii,
        Some("binary_little_endian") => Format::Binary { big_endian: false },
        Some("binary_big_endian") => Format::Binary { big_endian: true },
        other => {
            return Err(format!(
                "unknown PLY format `{}` (expected ascii, binary_little_endian \
                 or binary_big_endian)",
                other.unwrap_or("")
            ))
        }
    })
}

/// The element an `element NAME COUNT` line (number `line`) declares, with no
/// properties yet; `words` follow `element`.
fn element_line(words: &mut SplitWhitespace<'_>, line: usize) -> Result<Element, String> {
    let (Some(name), Some(count)) = (words.next(), words.next()) else {
        return Err("an element needs a name and a count: `element NAME COUNT`".into());
    };
    let count: u64 = count
        .parse()
        .map_err(|_| format!("the count of element `{name}` is `{count}`, not a whole number"))?;
    Ok(Element {
        name: name.to_string(),
        count,
        line,
        properties: Vec::new(),
    })
}

/// The property a `property [list COUNT] TYPE NAME` line declares; `words` follow
/// `property`.
fn property_line(words: &mut SplitWhitespace<'_>) -> Result<Property, String> {
    let scalar = |name: Option<&str>| -> Result<Scalar, String> {
        let name = name.unwrap_or("");
        Scalar::from_name(name).ok_or_else(|| {
            format!(
                "unknown property type `{name}` (expected char, uchar, short, \
                 ushort, int, uint, float or double, or int8 … float64)"
            )
        })
    };
    let kind = match words.next() {
        Some("list") => {
            let count = scalar(words.next())?;
            if !count.is_integer() {
                return Err("a list's count type must be an integer type".into());
            }
            Kind::List {
                count,
                item: scalar(words.next())?,
            }
        }
        other => Kind::Scalar(scalar(other)?),
    };
    let Some(name) = words.next() else {
        return Err("the property has no name".into());
    };
    Ok(Property {
        name: name.to_string(),
        kind,
    })
}

/// Refuses counts a binary payload cannot hold, before anything is sized by them: a
/// record takes at least its scalars' and list counts' bytes. An ascii payload is read
/// line by line instead, and a short one reported as truncated where it ends.
pub(super) fn check_counts(
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
