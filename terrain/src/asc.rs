//! ESRI ASCII grids (`.asc`, also called Arc/Info ASCII grids).
//!
//! A header of `key value` lines, keys in any case and any order:
//! `ncols`, `nrows`, `xllcorner` or `xllcenter`, `yllcorner` or `yllcenter`,
//! `cellsize` (or `dx` and `dy`, as GDAL writes for non-square cells), and optionally
//! `nodata_value`. Then `nrows × ncols` numbers separated by white space, the
//! northernmost row first. `xllcorner`/`yllcorner` give the lower-left corner of the
//! lower-left *cell*, so sample centres sit half a cell in; `xllcenter`/`yllcenter` give
//! the lower-left sample's centre.

use super::grid::{ElevationGrid, GridGeometry};
use super::TerrainError;
use std::path::Path;

/// Reads an ESRI ASCII grid.
///
/// # Errors
/// [`TerrainError::Io`] if the file cannot be read; [`TerrainError::MissingKey`],
/// [`TerrainError::Parse`] (unknown or repeated key, a token that is not a number, a
/// sample that is not finite and not NODATA), [`TerrainError::ValueCount`],
/// [`TerrainError::CellSize`], each naming the file and the line, and the row and
/// column of a bad sample.
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("hill.asc");
/// std::fs::write(&path, "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n\
///                        NODATA_value -9999\n1 2 -9999\n3 4 5\n")?;
/// let grid = geotracks_terrain::read_asc(&path)?;
/// assert_eq!(grid.geometry().lower_left, [5.0, 5.0]); // corner + half a cell
/// assert_eq!(grid.elevation(0, 0), Some(1.0));        // the northern row first
/// assert_eq!(grid.elevation(2, 0), None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_asc(path: impl AsRef<Path>) -> Result<ElevationGrid, TerrainError> {
    let path = path.as_ref();
    let bytes = read_checked(path)?;
    // GDAL writes an ESRI grid's CRS beside it, as WKT in a `.prj` of the same name.
    // Only a regular file: a FIFO of that name would block the read.
    let prj = path.with_extension("prj");
    let epsg = matches!(geotracks::mesh::io::not_a_file(&prj), Ok(None))
        .then(|| std::fs::read_to_string(&prj).ok())
        .flatten()
        .and_then(|wkt| epsg_of_wkt(&wkt));
    Ok(read_asc_bytes(path, &bytes)?.with_epsg(epsg))
}

/// The file, refused from its first bytes when they are not text (a binary file is
/// not read whole to find out), with memory for the rest reserved before it is read.
fn read_checked(path: &Path) -> Result<Vec<u8>, TerrainError> {
    use std::io::Read;
    let io = |source| TerrainError::Io {
        path: path.to_path_buf(),
        source,
    };
    super::refuse_non_file(path)?;
    let mut file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let mut bytes = Vec::new();
    (&mut file).take(4096).read_to_end(&mut bytes).map_err(io)?;
    refuse_binary(path, &bytes)?;
    let rest = usize::try_from(size.saturating_sub(bytes.len() as u64)).unwrap_or(usize::MAX);
    geotracks::mesh::try_reserve(&mut bytes, rest, || {
        format!("reading the file ({size} bytes)")
    })
    .map_err(|e| e.in_file(path))?;
    file.read_to_end(&mut bytes).map_err(io)?;
    Ok(bytes)
}

/// [`TerrainError::WrongFormat`] when the start of the file is not text.
fn refuse_binary(path: &Path, bytes: &[u8]) -> Result<(), TerrainError> {
    if geotracks::mesh::io::sniff::binary(bytes).is_some() {
        return Err(TerrainError::WrongFormat {
            path: path.to_path_buf(),
            expected: "an ESRI ASCII grid",
            found: geotracks::mesh::io::sniff::describe(bytes),
        });
    }
    Ok(())
}

/// The EPSG code a WKT string ends with: the last `AUTHORITY["EPSG","code"]` (WKT1,
/// whose outermost CRS names its authority last) or `ID["EPSG",code]` (WKT2). `None`
/// for a WKT without one (ESRI's `.prj` files often have none).
pub(crate) fn epsg_of_wkt(wkt: &str) -> Option<u32> {
    let compact: String = wkt.chars().filter(|c| !c.is_whitespace()).collect();
    let upper = compact.to_ascii_uppercase();
    ["AUTHORITY[\"EPSG\",", "ID[\"EPSG\","]
        .iter()
        .filter_map(|key| upper.rfind(key).map(|at| at + key.len()))
        .max()
        .and_then(|at| {
            let code: String = upper[at..]
                .trim_start_matches('"')
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            code.parse().ok().filter(|&c| c > 0)
        })
}

/// [`read_asc`] on a grid held in memory; errors name `path`.
///
/// # Errors
/// As [`read_asc`].
pub fn read_asc_bytes(path: impl AsRef<Path>, bytes: &[u8]) -> Result<ElevationGrid, TerrainError> {
    let path = path.as_ref();
    refuse_binary(path, bytes)?;
    // A leading byte-order mark is skipped, as the editors that write it do.
    let bytes = geotracks::mesh::io::sniff::without_bom(bytes);
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        TerrainError::Parse {
            path: path.to_path_buf(),
            line,
            message: format!(
                "the line is not text (byte 0x{:02x} at offset {at} is not UTF-8)",
                bytes[at]
            ),
        }
    })?;
    parse_asc(path, text)
}

#[derive(Default)]
struct Header {
    ncols: Option<(usize, usize)>,
    nrows: Option<(usize, usize)>,
    x: Option<(f64, bool)>,
    y: Option<(f64, bool)>,
    cellsize: Option<f64>,
    dx: Option<f64>,
    dy: Option<f64>,
    nodata: Option<f64>,
}

/// The file's lines, numbered from 0, with a look at the next one (where the header
/// ends is known only from the first data line).
type AscLines<'a> = std::iter::Peekable<std::iter::Enumerate<std::str::Lines<'a>>>;

fn parse_asc(path: &Path, text: &str) -> Result<ElevationGrid, TerrainError> {
    let mut lines = text.lines().enumerate().peekable();
    let header = read_header(path, &mut lines)?;
    let (geometry, header_lines) = header.geometry(path)?;
    let values = read_values(path, text, lines, &geometry, header.nodata, header_lines)?;
    ElevationGrid::checked(geometry, values)
}

/// A [`TerrainError::Parse`] at line `line` (1-based; 0 for the file as a whole).
fn parse_error(path: &Path, line: usize, message: String) -> TerrainError {
    TerrainError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    }
}

/// Reads the header's `key value` lines, up to the first line that starts with a
/// number (left in `lines`).
fn read_header(path: &Path, lines: &mut AscLines<'_>) -> Result<Header, TerrainError> {
    let parse_error = |line: usize, message: String| parse_error(path, line, message);
    let mut header = Header::default();
    // Header lines start with a key (a letter); the data with a number.
    while let Some(&(i, line)) = lines.peek() {
        let mut tokens = line.split_whitespace();
        let Some(key) = tokens.next() else {
            lines.next();
            continue;
        };
        if !key.starts_with(|c: char| c.is_ascii_alphabetic()) || is_number(key) {
            break;
        }
        lines.next();
        let line_no = i + 1;
        let value_text = tokens
            .next()
            .ok_or_else(|| parse_error(line_no, format!("header key '{key}' has no value")))?;
        if let Some(extra) = tokens.next() {
            return Err(parse_error(
                line_no,
                format!("unexpected '{extra}' after '{key} {value_text}'"),
            ));
        }
        let number = || {
            value_text
                .parse::<f64>()
                .map_err(|_| parse_error(line_no, format!("{key}: '{value_text}' is not a number")))
        };
        let count = || {
            value_text
                .parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .map(|n| (n, line_no))
                .ok_or_else(|| {
                    parse_error(
                        line_no,
                        format!("{key}: '{value_text}' is not a positive whole number"),
                    )
                })
        };
        let lower = key.to_ascii_lowercase();
        let repeated = match lower.as_str() {
            "ncols" => header.ncols.replace(count()?).is_some(),
            "nrows" => header.nrows.replace(count()?).is_some(),
            "xllcorner" => header.x.replace((number()?, true)).is_some(),
            "xllcenter" | "xllcentre" => header.x.replace((number()?, false)).is_some(),
            "yllcorner" => header.y.replace((number()?, true)).is_some(),
            "yllcenter" | "yllcentre" => header.y.replace((number()?, false)).is_some(),
            "cellsize" => header.cellsize.replace(number()?).is_some(),
            "dx" => header.dx.replace(number()?).is_some(),
            "dy" => header.dy.replace(number()?).is_some(),
            "nodata_value" => header.nodata.replace(number()?).is_some(),
            _ => return Err(parse_error(line_no, format!("unknown header key '{key}'"))),
        };
        if repeated {
            return Err(parse_error(
                line_no,
                format!("'{key}' is given twice (or with its corner/center twin)"),
            ));
        }
    }
    Ok(header)
}

impl Header {
    /// The grid's geometry, and the lines of `ncols` and `nrows` (for messages), or the
    /// key that is missing or the value that is wrong.
    fn geometry(&self, path: &Path) -> Result<(GridGeometry, [usize; 2]), TerrainError> {
        let missing = |key| TerrainError::MissingKey {
            path: path.to_path_buf(),
            key,
        };
        let (ncols, ncols_line) = self.ncols.ok_or_else(|| missing("ncols"))?;
        let (nrows, nrows_line) = self.nrows.ok_or_else(|| missing("nrows"))?;
        let header_lines = [ncols_line, nrows_line];
        let (x, x_corner) = self.x.ok_or_else(|| missing("xllcorner"))?;
        let (y, y_corner) = self.y.ok_or_else(|| missing("yllcorner"))?;
        let (dx, dy) = match (self.cellsize, self.dx, self.dy) {
            (Some(c), _, _) => (c, c),
            (None, Some(dx), Some(dy)) => (dx, dy),
            (None, Some(_), None) => return Err(missing("dy")),
            (None, _, _) => return Err(missing("cellsize")),
        };
        for value in [dx, dy] {
            if !(value.is_finite() && value > 0.0) {
                return Err(TerrainError::CellSize {
                    path: Some(path.to_path_buf()),
                    value,
                });
            }
        }
        if !(x.is_finite() && y.is_finite()) {
            return Err(parse_error(
                path,
                0,
                format!("the origin ({x}, {y}) is not finite"),
            ));
        }
        let geometry = GridGeometry {
            ncols,
            nrows,
            lower_left: [
                if x_corner { x + dx / 2.0 } else { x },
                if y_corner { y + dy / 2.0 } else { y },
            ],
            spacing: [dx, dy],
        };
        Ok((geometry, header_lines))
    }
}

/// Reads the samples (the rest of `lines`, of the file `text`), NODATA ones as NaN:
/// exactly as many as `geometry` has.
fn read_values(
    path: &Path,
    text: &str,
    mut lines: AscLines<'_>,
    geometry: &GridGeometry,
    nodata: Option<f64>,
    header_lines: [usize; 2],
) -> Result<Vec<f64>, TerrainError> {
    let parse_error = |line: usize, message: String| parse_error(path, line, message);
    let (ncols, nrows) = (geometry.ncols, geometry.nrows);
    let expected = ncols
        .checked_mul(nrows)
        .filter(|&n| n <= 1 << 32)
        .ok_or_else(|| parse_error(0, format!("{ncols} × {nrows} samples are too many")))?;
    // Room for no more samples than the rest of the file can hold (a number and a
    // separator take at least 2 bytes): a header that lies about its size allocates
    // nothing beyond the file's own size, and is reported against its lines once the
    // values run out.
    let data_bytes = lines.peek().map_or(0, |&(_, line)| {
        text.len() - (line.as_ptr() as usize - text.as_ptr() as usize)
    });
    let room = expected.min(data_bytes / 2 + 1);
    let mut values = Vec::new();
    geotracks::mesh::try_reserve(&mut values, room, || format!("{room} samples"))
        .map_err(|e| e.in_file(path))?;
    for (i, line) in lines {
        for token in line.split_whitespace() {
            if values.len() == expected {
                return Err(TerrainError::ValueCount {
                    path: path.to_path_buf(),
                    ncols,
                    nrows,
                    expected,
                    found: expected + 1 + count_rest(token, line, text, i),
                    line: i + 1,
                    header_lines,
                });
            }
            let at = values.len();
            let place = || format!("row {}, column {}", at / ncols, at % ncols);
            let value: f64 = token.parse().map_err(|_| {
                parse_error(i + 1, format!("{}: '{token}' is not a number", place()))
            })?;
            let missing = match nodata {
                Some(n) if n.is_nan() => value.is_nan(),
                Some(n) => value == n,
                None => false,
            };
            if missing {
                values.push(f64::NAN);
            } else if value.is_finite() {
                values.push(value);
            } else {
                return Err(parse_error(
                    i + 1,
                    format!("{}: the value '{token}' is not finite", place()),
                ));
            }
        }
    }
    if values.len() != expected {
        return Err(TerrainError::ValueCount {
            path: path.to_path_buf(),
            ncols,
            nrows,
            expected,
            found: values.len(),
            line: 0,
            header_lines,
        });
    }
    Ok(values)
}

/// Whether a token is a number (a header key never is; `nan` and `inf` are).
fn is_number(token: &str) -> bool {
    token.parse::<f64>().is_ok()
}

/// Tokens after `token` on its line and on the lines after it (for the count in an
/// error message only).
fn count_rest(token: &str, line: &str, text: &str, line_index: usize) -> usize {
    let on_line = line
        .split_whitespace()
        .skip_while(|t| !std::ptr::eq(*t, token))
        .skip(1)
        .count();
    on_line
        + text
            .lines()
            .skip(line_index + 1)
            .map(|l| l.split_whitespace().count())
            .sum::<usize>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ElevationGrid, TerrainError> {
        parse_asc(Path::new("t.asc"), text)
    }

    #[test]
    fn centre_and_corner_origins() {
        let corner =
            parse("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 10\ncellsize 2\n1 2\n3 4\n").unwrap();
        assert_eq!(corner.geometry().lower_left, [1.0, 11.0]);
        let centre =
            parse("NCOLS 2\nNROWS 2\nXLLCENTER 0\nYLLCENTER 10\nCELLSIZE 2\n1 2\n3 4\n").unwrap();
        assert_eq!(centre.geometry().lower_left, [0.0, 10.0]);
        assert_eq!(centre.elevation(0, 0), Some(1.0));
        assert_eq!(centre.elevation(1, 1), Some(4.0));
        assert_eq!(centre.geometry().position(0, 0), [0.0, 12.0]);
    }

    #[test]
    fn bad_input_names_file_line_row_and_column() {
        let err = |t: &str| parse(t).unwrap_err().to_string();
        let head = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
        assert!(
            err("nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n").contains("no 'ncols'")
        );
        let e = err(&format!("{head}1 2\n3 x\n"));
        assert!(
            e.contains("t.asc:7") && e.contains("row 1, column 1"),
            "{e}"
        );
        let e = err(&format!("{head}1 2\n3\n"));
        assert!(
            e.contains("expected 4 values") && e.contains("found 3"),
            "{e}"
        );
        let e = err(&format!("{head}1 2\n3 4 5 6\n"));
        assert!(e.contains("t.asc:7") && e.contains("found 6"), "{e}");
        let e = err(&format!("{head}1 2\n3 inf\n"));
        assert!(e.contains("not finite"), "{e}");
        let e = err("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n1 2\n3 4\n");
        assert!(e.contains("cell size 0"), "{e}");
        let e = err("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nfoo 3\n1 2\n3 4\n");
        assert!(e.contains("unknown header key 'foo'"), "{e}");
        let e = err("ncols 2\nncols 2\n");
        assert!(e.contains("twice"), "{e}");
    }
}
