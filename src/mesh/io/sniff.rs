//! What a file looks like from its first bytes, for the message when it is not what its
//! extension says (binary data given as OBJ, an OBJ named `.stl`, a PLY named `.off`).
//!
//! Public (its three functions [`binary`], [`describe`] and [`without_bom`]) so that
//! the readers of the sibling crates (elevation grids) refuse and describe a file the
//! same way the mesh readers do.

use crate::mesh::MeshError;
use std::path::Path;

/// How much of the file's start is looked at.
const PROBE: usize = 1024;

/// If the start of the file is not text (a NUL byte, or bytes that are not UTF-8), what
/// it is, as a phrase ("binary data (byte 0x00 at offset 80)").
pub fn binary(bytes: &[u8]) -> Option<String> {
    let head = &bytes[..bytes.len().min(PROBE)];
    if let Some(at) = head.iter().position(|&b| b == 0) {
        return Some(format!("binary data (a NUL byte at offset {at})"));
    }
    match std::str::from_utf8(head) {
        Ok(_) => None,
        // A character cut by the probe's end is not an error.
        Err(e) if e.error_len().is_none() => None,
        Err(e) => {
            let at = e.valid_up_to();
            Some(format!(
                "binary data or text that is not UTF-8 (byte 0x{:02x} at offset {at})",
                head[at]
            ))
        }
    }
}

/// What the file looks like, as a phrase for "not an OBJ file: {phrase}": a known
/// format's signature, binary data, or the text its first line starts with.
pub fn describe(bytes: &[u8]) -> String {
    let first = first_line(bytes);
    let word = first.split_whitespace().next().unwrap_or("");
    if bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*") {
        return "it is a TIFF image".into();
    }
    if word == "ply" && first.trim() == "ply" {
        return "it is a PLY file (its first line is `ply`)".into();
    }
    if matches!(word, "OFF" | "COFF" | "NOFF" | "CNOFF" | "STOFF") {
        return format!(
            "it looks like an OFF file (its first line is `{}`)",
            clip(first)
        );
    }
    if word.eq_ignore_ascii_case("solid") && binary(bytes).is_none() {
        return "it looks like an ascii STL file (its first line starts with `solid`)".into();
    }
    if let Some(what) = binary(bytes) {
        return format!("the file is {what}");
    }
    if matches!(
        word,
        "v" | "vn" | "vt" | "f" | "o" | "g" | "mtllib" | "usemtl"
    ) {
        return format!(
            "the file looks like an OBJ (its first line is `{}`)",
            clip(first)
        );
    }
    format!("the file is text starting with `{}`", clip(first))
}

/// [`MeshError::WrongFormat`] for `path`, with [`describe`] as what it looks like.
pub(crate) fn wrong_format(path: &Path, expected: &'static str, bytes: &[u8]) -> MeshError {
    MeshError::WrongFormat {
        path: path.to_path_buf(),
        expected,
        found: describe(bytes),
    }
}

/// Refuses a file whose start is not text, for the text formats (OBJ, OFF, `.ma`).
pub(crate) fn expect_text(
    path: &Path,
    expected: &'static str,
    bytes: &[u8],
) -> Result<(), MeshError> {
    match binary(bytes) {
        Some(_) => Err(wrong_format(path, expected, bytes)),
        None => Ok(()),
    }
}

/// The UTF-8 byte-order mark some editors (Windows Notepad, Excel's CSV) put at the
/// start of a text file.
pub(crate) const BOM: &[u8] = b"\xEF\xBB\xBF";

/// `bytes` without a leading UTF-8 byte-order mark: every text format skips it, as
/// the editors that write it do, instead of reading it as part of the first line.
pub fn without_bom(bytes: &[u8]) -> &[u8] {
    bytes.strip_prefix(BOM).unwrap_or(bytes)
}

/// The first non-blank line, lossily decoded (for messages only).
fn first_line(bytes: &[u8]) -> String {
    let bytes = without_bom(bytes);
    let head = &bytes[..bytes.len().min(PROBE)];
    String::from_utf8_lossy(head)
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("")
        .to_string()
}

/// At most 40 characters of `text`, with `…` if cut.
fn clip(text: String) -> String {
    match text.char_indices().nth(40) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text,
    }
}
