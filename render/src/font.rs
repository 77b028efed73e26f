//! A 5 × 7 bitmap font for the labels of pictures: digits, `.`, `-`, `+`, and the few
//! letters that units and map labels need (`e`, `k`, `m`, `N`, `r`, `s`, `v`, `y`).

use super::raster::put;
use super::Picture;

/// Rows of a glyph, top first; bit 4 is the leftmost column. `None` for a character
/// the font lacks (a space, say: drawn as a gap).
fn glyph(c: char) -> Option<[u8; 7]> {
    Some(match c {
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C],
        '-' => [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00],
        '+' => [0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00],
        'e' => [0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E],
        'k' => [0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12],
        'm' => [0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11],
        'N' => [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11],
        'r' => [0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10],
        's' => [0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E],
        'v' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04],
        'y' => [0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E],
        _ => return None,
    })
}

/// `value` in at most 4 significant digits: `0`, `0.1234`, `12.35`, `1.235e6`.
pub fn number(value: f64) -> String {
    if value == 0.0 {
        return "0".into();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if (-3..5).contains(&magnitude) {
        let decimals = (3 - magnitude).max(0) as usize;
        let text = format!("{value:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        format!("{value:.3e}")
    }
}

/// The inked font pixels of `text` as `(column, row)`, from its top-left corner: each
/// character 6 columns on from the last (5 of glyph, 1 of gap), 7 rows. Characters the
/// font lacks leave a gap.
pub fn cells(text: &str) -> impl Iterator<Item = (i64, i64)> + '_ {
    text.chars().enumerate().flat_map(|(k, c)| {
        let rows = glyph(c).unwrap_or([0; 7]);
        (0..7i64).flat_map(move |r| {
            (0..5i64)
                .filter(move |col| rows[r as usize] & (0x10 >> col) != 0)
                .map(move |col| (6 * k as i64 + col, r))
        })
    })
}

/// Writes `text` with its top-left corner at `(x, y)`, each font pixel `scale` pixels.
/// Characters the font lacks are skipped.
pub(super) fn draw(
    picture: &mut Picture,
    text: &str,
    x: i64,
    y: i64,
    scale: i64,
    colour: [f64; 3],
) {
    for (col, row) in cells(text) {
        for dy in 0..scale {
            for dx in 0..scale {
                put(picture, x + col * scale + dx, y + row * scale + dy, colour);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.123456), "0.1235");
        assert_eq!(number(12.3456), "12.35");
        assert_eq!(number(2.0), "2");
        assert_eq!(number(1234567.0), "1.235e6");
        assert_eq!(number(-0.5), "-0.5");
    }

    #[test]
    fn a_digit_draws_its_pixels() {
        let mut picture = Picture {
            width: 20,
            height: 10,
            rgba: vec![255; 20 * 10 * 4],
        };
        draw(&mut picture, "1", 0, 0, 1, [0.0; 3]);
        let dark = |x: usize, y: usize| picture.rgba[(y * 20 + x) * 4] == 0;
        // "1": the stem in column 2 on every row, the foot across row 6.
        assert!((0..7).all(|y| dark(2, y)));
        assert!((1..4).all(|x| dark(x, 6)));
        assert!(!dark(0, 0) && !dark(4, 3));
        // Nothing drawn for a character the font lacks.
        let before = picture.clone();
        draw(&mut picture, "x", 10, 0, 1, [0.0; 3]);
        assert_eq!(picture, before);
    }
}
