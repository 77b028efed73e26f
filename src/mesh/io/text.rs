//! Line splitting and number parsing shared by the text readers (OBJ, OFF, `.ma`).

use crate::mesh::MeshError;
use std::path::Path;

/// The non-blank lines of a text file with their 1-based numbers, `#` comments removed.
///
/// Works on bytes rather than `str::lines` so that one bad byte is reported at its line
/// instead of failing the whole file up front.
pub(super) struct Lines<'a> {
    path: &'a Path,
    rest: &'a [u8],
    line: usize,
}

impl<'a> Lines<'a> {
    /// Lines of a whole file; a leading UTF-8 byte-order mark is skipped.
    pub(super) fn new(path: &'a Path, bytes: &'a [u8]) -> Self {
        Lines {
            path,
            rest: super::sniff::without_bom(bytes),
            line: 0,
        }
    }

    /// Lines of `bytes`, numbered as if `bytes` came after line `before` of the file (the
    /// data after a PLY header).
    pub(super) fn starting_after(path: &'a Path, bytes: &'a [u8], before: usize) -> Self {
        Lines {
            path,
            rest: bytes,
            line: before,
        }
    }

    /// Bytes not read yet (after the last line returned).
    pub(super) fn rest_len(&self) -> usize {
        self.rest.len()
    }

    /// The number of the line a reader would have wanted next once the file has run out:
    /// truncation errors point there.
    pub(super) fn end_line(&self) -> usize {
        self.line + 1
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Result<(usize, &'a str), MeshError>;

    fn next(&mut self) -> Option<Self::Item> {
        while !self.rest.is_empty() {
            let (raw, rest) = match self.rest.iter().position(|&b| b == b'\n') {
                Some(i) => (&self.rest[..i], &self.rest[i + 1..]),
                None => (self.rest, &[][..]),
            };
            self.rest = rest;
            self.line += 1;
            let data = match raw.iter().position(|&b| b == b'#') {
                Some(i) => &raw[..i],
                None => raw,
            };
            let text = match std::str::from_utf8(data) {
                Ok(t) => t.trim(),
                Err(_) => {
                    return Some(Err(parse_error(
                        self.path,
                        self.line,
                        "the line is not valid UTF-8 text",
                    )))
                }
            };
            if !text.is_empty() {
                return Some(Ok((self.line, text)));
            }
        }
        None
    }
}

/// A [`MeshError::Parse`] at `line` of `path`.
pub(super) fn parse_error(path: &Path, line: usize, message: impl Into<String>) -> MeshError {
    MeshError::Parse {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Wraps a content error (index out of range and so on) with its file and line.
pub(super) fn at_line(path: &Path, line: usize, error: MeshError) -> MeshError {
    MeshError::AtLine {
        path: path.to_path_buf(),
        line,
        error: Box::new(error),
    }
}

/// Parses the next whitespace-separated token as a number; `what` names the value in the
/// message ("x coordinate of vertex 3").
pub(super) fn next_number<T: std::str::FromStr>(
    tokens: &mut std::str::SplitWhitespace<'_>,
    path: &Path,
    line: usize,
    what: impl FnOnce() -> String,
) -> Result<T, MeshError> {
    match tokens.next() {
        Some(token) => token.parse().map_err(|_| {
            parse_error(
                path,
                line,
                format!("expected a number for the {}, found `{token}`", what()),
            )
        }),
        None => Err(parse_error(
            path,
            line,
            format!("the {} is missing", what()),
        )),
    }
}

/// `true` if the bytes hold nothing but whitespace: such a file is reported as
/// [`MeshError::EmptyFile`] whatever its format.
pub(super) fn is_blank(bytes: &[u8]) -> bool {
    super::sniff::without_bom(bytes)
        .iter()
        .all(u8::is_ascii_whitespace)
}

/// How many elements to reserve room for when a header declares `declared` and each
/// takes a line of at least `per_line` bytes: never more than the `rest` bytes of the
/// file can hold, so a count that lies allocates nothing beyond the file's own size (the
/// reader then grows as it reads, and reports the truncation where the data ends).
pub(super) fn capacity(declared: usize, rest: usize, per_line: usize) -> usize {
    declared.min(rest / per_line + 1)
}

/// An empty vector with room for `n` elements (named `what` in the error), or
/// [`MeshError::OutOfMemory`] for the file `path`.
pub(super) fn reserved<T>(path: &Path, n: usize, what: &str) -> Result<Vec<T>, MeshError> {
    let mut vec = Vec::new();
    crate::mesh::try_reserve(&mut vec, n, || format!("{n} {what}")).map_err(|e| e.in_file(path))?;
    Ok(vec)
}
