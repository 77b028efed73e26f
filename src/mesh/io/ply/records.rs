//! The payload, read record by record: ascii (one record a line) or binary (little- or
//! big-endian), behind one interface so the reader walks both the same way.

use super::header::{Element, Kind, Scalar};
use crate::mesh::io::text::{parse_error, Lines};
use crate::mesh::MeshError;
use std::path::Path;

/// The element, property and place a value is read for, to name it in messages.
#[derive(Clone, Copy)]
pub(super) struct Place<'a> {
    pub(super) element: &'a str,
    pub(super) index: u64,
    pub(super) property: &'a str,
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

/// The payload, read record by record.
pub(super) enum Records<'a> {
    Ascii {
        lines: Lines<'a>,
        /// The values of the current record's line.
        tokens: std::str::SplitWhitespace<'a>,
    },
    Binary(Binary<'a>),
}

pub(super) struct Binary<'a> {
    pub(super) data: &'a [u8],
    pub(super) at: usize,
    pub(super) big_endian: bool,
    /// Offset of `data` in the file, for messages.
    pub(super) offset: usize,
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
    pub(super) fn start_record(
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
    pub(super) fn end_record(
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

    pub(super) fn scalar(
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
    pub(super) fn list(
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
    pub(super) fn skip(
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
