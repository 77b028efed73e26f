//! A log-log scatter plot with lines, drawn pixel by pixel and written as a PNG with the
//! `image` crate the pictures already use (no plotting dependency: a plotting crate needs
//! a font file or the system's fonts for its text; a 5×7 bitmap font is enough here).

use std::path::Path;

/// A point's shape.
#[derive(Clone, Copy, Debug)]
pub enum Marker {
    Circle,
    Square,
    Diamond,
    TriangleUp,
    TriangleDown,
}

/// Points joined by a line, in order; filled or hollow markers, each with a small tag.
pub struct Series {
    pub name: String,
    pub colour: [u8; 3],
    pub marker: Marker,
    pub filled: bool,
    /// (x, y, tag).
    pub points: Vec<(f64, f64, String)>,
}

impl Series {
    pub fn new(
        name: &str,
        colour: [u8; 3],
        marker: Marker,
        filled: bool,
        points: Vec<(f64, f64, String)>,
    ) -> Series {
        Series {
            name: name.to_string(),
            colour,
            marker,
            filled,
            points,
        }
    }
}

pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub caption: Vec<String>,
    pub series: Vec<Series>,
}

const W: usize = 1300;
const H: usize = 850;
/// The plot area.
const LEFT: f64 = 110.0;
const RIGHT: f64 = 930.0;
const TOP: f64 = 60.0;
const BOTTOM: f64 = 640.0;
/// Glyph scale: 5×7 glyphs drawn as 2×2 blocks.
const SCALE: usize = 2;
/// Points with a y below this are off any useful scale (an exact method): they are
/// drawn on the bottom axis and leave the range alone.
const Y_FLOOR: f64 = 1e-6;

impl Plot {
    pub fn write_png(&self, path: &Path) -> Result<(), String> {
        let mut c = Canvas::new(W, H);
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let xs: Vec<f64> = points().map(|p| p.0).filter(|x| *x > 0.0).collect();
        let ys: Vec<f64> = points().map(|p| p.1).filter(|y| *y >= Y_FLOOR).collect();
        if xs.is_empty() || ys.is_empty() {
            return Err("nothing to plot".into());
        }
        let range = |v: &[f64]| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let (lo, hi) = (lo.log10().floor(), hi.log10().ceil());
            (lo, if hi > lo { hi } else { lo + 1.0 })
        };
        let (x0, x1) = range(&xs);
        let (y0, y1) = range(&ys);
        let px = |x: f64| LEFT + (x.log10() - x0) / (x1 - x0) * (RIGHT - LEFT);
        let py = |y: f64| {
            let y = y.max(10f64.powf(y0));
            BOTTOM - (y.log10() - y0) / (y1 - y0) * (BOTTOM - TOP)
        };
        let grid = [225, 225, 225];
        let minor = [242, 242, 242];
        let ink = [30, 30, 30];
        // Grid: decades, and 2..9 within them.
        for e in x0 as i32..x1 as i32 {
            for m in 2..10 {
                let x = px(m as f64 * 10f64.powi(e));
                c.line((x, TOP), (x, BOTTOM), 1.0, minor, None);
            }
        }
        for e in y0 as i32..y1 as i32 {
            for m in 2..10 {
                let y = py(m as f64 * 10f64.powi(e));
                c.line((LEFT, y), (RIGHT, y), 1.0, minor, None);
            }
        }
        for e in x0 as i32..=x1 as i32 {
            let x = px(10f64.powi(e));
            c.line((x, TOP), (x, BOTTOM), 1.0, grid, None);
            let t = decade(e);
            c.text(x - text_width(&t) as f64 / 2.0, BOTTOM + 10.0, &t, ink);
        }
        for e in y0 as i32..=y1 as i32 {
            let y = py(10f64.powi(e));
            c.line((LEFT, y), (RIGHT, y), 1.0, grid, None);
            let t = decade(e);
            c.text(LEFT - 10.0 - text_width(&t) as f64, y - 7.0, &t, ink);
        }
        c.line((LEFT, TOP), (LEFT, BOTTOM), 1.5, ink, None);
        c.line((LEFT, BOTTOM), (RIGHT, BOTTOM), 1.5, ink, None);
        c.line((RIGHT, TOP), (RIGHT, BOTTOM), 1.0, ink, None);
        c.line((LEFT, TOP), (RIGHT, TOP), 1.0, ink, None);
        let mid = (LEFT + RIGHT) / 2.0;
        c.text(
            mid - text_width(&self.x_label) as f64 / 2.0,
            BOTTOM + 36.0,
            &self.x_label,
            ink,
        );
        c.text_up(
            22.0,
            (TOP + BOTTOM) / 2.0 + text_width(&self.y_label) as f64 / 2.0,
            &self.y_label,
            ink,
        );
        c.text(LEFT, 20.0, &self.title, ink);
        let lines = self
            .caption
            .iter()
            .flat_map(|p| wrap(p, (W - 40) / (6 * SCALE)));
        for (n, line) in lines.enumerate() {
            c.text(20.0, BOTTOM + 76.0 + 24.0 * n as f64, &line, [70, 70, 70]);
        }

        // Lines under markers, then markers, then tags.
        for s in &self.series {
            let dash = (!s.filled).then_some((8.0, 6.0));
            for w in s.points.windows(2) {
                let (a, b) = ((px(w[0].0), py(w[0].1)), (px(w[1].0), py(w[1].1)));
                c.line(a, b, 2.0, s.colour, dash);
            }
        }
        for s in &self.series {
            for p in &s.points {
                c.marker((px(p.0), py(p.1)), 7.0, s.marker, s.filled, s.colour);
            }
        }
        for s in &self.series {
            for p in &s.points {
                // Tags of filled markers above right, of hollow ones below right, so
                // that two curves through nearby points keep their tags apart.
                let dy = if s.filled { -18.0 } else { 4.0 };
                if !p.2.is_empty() {
                    c.text(px(p.0) + 9.0, py(p.1) + dy, &p.2, s.colour);
                }
            }
        }

        // Legend, right of the plot area.
        let (lx, mut ly) = (RIGHT + 30.0, TOP + 6.0);
        c.text(lx, ly, "filled: this run", ink);
        ly += 24.0;
        c.text(lx, ly, "hollow: peers.md", ink);
        ly += 36.0;
        for s in &self.series {
            if s.points.is_empty() {
                continue;
            }
            let dash = (!s.filled).then_some((8.0, 6.0));
            c.line((lx, ly + 7.0), (lx + 36.0, ly + 7.0), 2.0, s.colour, dash);
            c.marker((lx + 18.0, ly + 7.0), 7.0, s.marker, s.filled, s.colour);
            c.text(lx + 48.0, ly, &s.name, ink);
            ly += 30.0;
        }
        c.save(path)
    }
}

/// `text` cut at spaces into lines of at most `width` characters.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let line = lines.last_mut().expect("never empty");
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_string());
        } else {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
    }
    lines
}

/// 10^e as a plain decimal.
fn decade(e: i32) -> String {
    if e >= 0 {
        format!("{}", 10u64.pow(e as u32))
    } else if e >= -5 {
        format!("{:.*}", (-e) as usize, 10f64.powi(e))
    } else {
        format!("1e{e}")
    }
}

fn text_width(s: &str) -> usize {
    s.chars().count() * 6 * SCALE
}

struct Canvas {
    w: usize,
    h: usize,
    rgb: Vec<[f64; 3]>,
}

impl Canvas {
    fn new(w: usize, h: usize) -> Canvas {
        Canvas {
            w,
            h,
            rgb: vec![[1.0; 3]; w * h],
        }
    }

    fn blend(&mut self, x: i64, y: i64, c: [u8; 3], a: f64) {
        if x < 0 || y < 0 || x >= self.w as i64 || y >= self.h as i64 || a <= 0.0 {
            return;
        }
        let p = &mut self.rgb[y as usize * self.w + x as usize];
        for i in 0..3 {
            p[i] = p[i] * (1.0 - a) + a * c[i] as f64 / 255.0;
        }
    }

    /// An anti-aliased segment of the given width; `dash` = (on, off) in pixels.
    fn line(
        &mut self,
        a: (f64, f64),
        b: (f64, f64),
        width: f64,
        c: [u8; 3],
        dash: Option<(f64, f64)>,
    ) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let len = len2.sqrt();
        let r = width / 2.0;
        let (xmin, xmax) = (a.0.min(b.0) - r - 1.0, a.0.max(b.0) + r + 1.0);
        let (ymin, ymax) = (a.1.min(b.1) - r - 1.0, a.1.max(b.1) + r + 1.0);
        for y in ymin.floor() as i64..=ymax.ceil() as i64 {
            for x in xmin.floor() as i64..=xmax.ceil() as i64 {
                let (qx, qy) = (x as f64 + 0.5 - a.0, y as f64 + 0.5 - a.1);
                let t = if len2 > 0.0 {
                    ((qx * dx + qy * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                if let Some((on, off)) = dash {
                    if (t * len) % (on + off) > on {
                        continue;
                    }
                }
                let d = ((qx - t * dx).powi(2) + (qy - t * dy).powi(2)).sqrt();
                self.blend(x, y, c, (r + 0.5 - d).clamp(0.0, 1.0));
            }
        }
    }

    /// A marker of radius `r` centred at `p`; hollow ones are a 2-pixel outline on white.
    fn marker(&mut self, p: (f64, f64), r: f64, m: Marker, filled: bool, c: [u8; 3]) {
        let inside = |x: f64, y: f64| -> bool {
            let poly = |pts: &[(f64, f64)]| {
                (0..pts.len()).all(|i| {
                    let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
                    (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0) >= 0.0
                })
            };
            match m {
                Marker::Circle => x * x + y * y <= 1.0,
                Marker::Square => x.abs().max(y.abs()) <= 0.85,
                Marker::Diamond => x.abs() + y.abs() <= 1.2,
                Marker::TriangleUp => poly(&[(0.0, -1.2), (1.1, 0.8), (-1.1, 0.8)]),
                Marker::TriangleDown => poly(&[(0.0, 1.2), (-1.1, -0.8), (1.1, -0.8)]),
            }
        };
        const SS: usize = 4;
        let n = (r * 1.4).ceil() as i64 + 1;
        for y in -n..=n {
            for x in -n..=n {
                let (cx, cy) = ((p.0).floor() as i64 + x, (p.1).floor() as i64 + y);
                let (mut on, mut hole) = (0, 0);
                for sy in 0..SS {
                    for sx in 0..SS {
                        let qx = cx as f64 + (sx as f64 + 0.5) / SS as f64 - p.0;
                        let qy = cy as f64 + (sy as f64 + 0.5) / SS as f64 - p.1;
                        if inside(qx / r, qy / r) {
                            on += 1;
                            if !filled && inside(qx / (r - 2.5), qy / (r - 2.5)) {
                                hole += 1;
                            }
                        }
                    }
                }
                let total = (SS * SS) as f64;
                self.blend(cx, cy, c, (on - hole) as f64 / total);
                self.blend(cx, cy, [255, 255, 255], hole as f64 / total);
            }
        }
    }

    fn glyph_pixels(s: &str) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        s.chars().enumerate().flat_map(|(i, ch)| {
            let rows = glyph(ch);
            (0..8).flat_map(move |gy| {
                (0..5)
                    .filter_map(move |gx| (rows[gy].as_bytes()[gx] == b'#').then_some((i, gx, gy)))
            })
        })
    }

    /// Text with its top-left corner at (x, y).
    fn text(&mut self, x: f64, y: f64, s: &str, c: [u8; 3]) {
        let (x, y) = (x.round() as i64, y.round() as i64);
        let pixels: Vec<_> = Self::glyph_pixels(s).collect();
        for (i, gx, gy) in pixels {
            for dy in 0..SCALE {
                for dx in 0..SCALE {
                    let px = x + ((i * 6 + gx) * SCALE + dx) as i64;
                    let py = y + (gy * SCALE + dy) as i64;
                    self.blend(px, py, c, 1.0);
                }
            }
        }
    }

    /// Text rotated a quarter turn anticlockwise, starting at (x, y) and going up.
    fn text_up(&mut self, x: f64, y: f64, s: &str, c: [u8; 3]) {
        let (x, y) = (x.round() as i64, y.round() as i64);
        let pixels: Vec<_> = Self::glyph_pixels(s).collect();
        for (i, gx, gy) in pixels {
            for dy in 0..SCALE {
                for dx in 0..SCALE {
                    let along = ((i * 6 + gx) * SCALE + dx) as i64;
                    let across = (gy * SCALE + dy) as i64;
                    self.blend(x + across, y - along, c, 1.0);
                }
            }
        }
    }

    fn save(&self, path: &Path) -> Result<(), String> {
        let bytes: Vec<u8> = self
            .rgb
            .iter()
            .flat_map(|p| p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
            .collect();
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        image::save_buffer(
            path,
            &bytes,
            self.w as u32,
            self.h as u32,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// The 5×7 glyph of `ch` (an 8th row for descenders); a box for characters it lacks.
fn glyph(ch: char) -> [&'static str; 8] {
    GLYPHS
        .iter()
        .find(|(c, _)| *c == ch)
        .map_or(BOX, |(_, g)| *g)
}

const BOX: [&str; 8] = [
    "#####", "#...#", "#...#", "#...#", "#...#", "#...#", "#####", ".....",
];

#[rustfmt::skip]
const GLYPHS: &[(char, [&str; 8])] = &[
    (' ', [".....", ".....", ".....", ".....", ".....", ".....", ".....", "....."]),
    ('0', [".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###.", "....."]),
    ('1', ["..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###.", "....."]),
    ('2', [".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####", "....."]),
    ('3', ["####.", "....#", "....#", ".###.", "....#", "....#", "####.", "....."]),
    ('4', ["...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#.", "....."]),
    ('5', ["#####", "#....", "####.", "....#", "....#", "#...#", ".###.", "....."]),
    ('6', ["..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###.", "....."]),
    ('7', ["#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#...", "....."]),
    ('8', [".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###.", "....."]),
    ('9', [".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##..", "....."]),
    ('A', [".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#", "....."]),
    ('B', ["####.", "#...#", "#...#", "####.", "#...#", "#...#", "####.", "....."]),
    ('C', [".###.", "#...#", "#....", "#....", "#....", "#...#", ".###.", "....."]),
    ('D', ["####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####.", "....."]),
    ('E', ["#####", "#....", "#....", "####.", "#....", "#....", "#####", "....."]),
    ('F', ["#####", "#....", "#....", "####.", "#....", "#....", "#....", "....."]),
    ('G', [".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####", "....."]),
    ('H', ["#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#", "....."]),
    ('I', [".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.", "....."]),
    ('J', ["..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##..", "....."]),
    ('K', ["#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#", "....."]),
    ('L', ["#....", "#....", "#....", "#....", "#....", "#....", "#####", "....."]),
    ('M', ["#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#", "....."]),
    ('N', ["#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#", "....."]),
    ('O', [".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###.", "....."]),
    ('P', ["####.", "#...#", "#...#", "####.", "#....", "#....", "#....", "....."]),
    ('Q', [".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#", "....."]),
    ('R', ["####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#", "....."]),
    ('S', [".####", "#....", "#....", ".###.", "....#", "....#", "####.", "....."]),
    ('T', ["#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#..", "....."]),
    ('U', ["#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###.", "....."]),
    ('V', ["#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#..", "....."]),
    ('W', ["#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#.", "....."]),
    ('X', ["#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#", "....."]),
    ('Y', ["#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#..", "....."]),
    ('Z', ["#####", "....#", "...#.", "..#..", ".#...", "#....", "#####", "....."]),
    ('a', [".....", ".....", ".###.", "....#", ".####", "#...#", ".####", "....."]),
    ('b', ["#....", "#....", "####.", "#...#", "#...#", "#...#", "####.", "....."]),
    ('c', [".....", ".....", ".###.", "#....", "#....", "#....", ".###.", "....."]),
    ('d', ["....#", "....#", ".####", "#...#", "#...#", "#...#", ".####", "....."]),
    ('e', [".....", ".....", ".###.", "#...#", "#####", "#....", ".###.", "....."]),
    ('f', ["..##.", ".#...", "####.", ".#...", ".#...", ".#...", ".#...", "....."]),
    ('g', [".....", ".....", ".####", "#...#", "#...#", ".####", "....#", ".###."]),
    ('h', ["#....", "#....", "####.", "#...#", "#...#", "#...#", "#...#", "....."]),
    ('i', ["..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###.", "....."]),
    ('j', ["...#.", ".....", "..##.", "...#.", "...#.", "...#.", "#..#.", ".##.."]),
    ('k', ["#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "....."]),
    ('l', [".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.", "....."]),
    ('m', [".....", ".....", "##.#.", "#.#.#", "#.#.#", "#.#.#", "#.#.#", "....."]),
    ('n', [".....", ".....", "####.", "#...#", "#...#", "#...#", "#...#", "....."]),
    ('o', [".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###.", "....."]),
    ('p', [".....", ".....", "####.", "#...#", "#...#", "####.", "#....", "#...."]),
    ('q', [".....", ".....", ".####", "#...#", "#...#", ".####", "....#", "....#"]),
    ('r', [".....", ".....", "#.##.", "##..#", "#....", "#....", "#....", "....."]),
    ('s', [".....", ".....", ".####", "#....", ".###.", "....#", "####.", "....."]),
    ('t', [".#...", ".#...", "####.", ".#...", ".#...", ".#..#", "..##.", "....."]),
    ('u', [".....", ".....", "#...#", "#...#", "#...#", "#..##", ".##.#", "....."]),
    ('v', [".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#..", "....."]),
    ('w', [".....", ".....", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#.", "....."]),
    ('x', [".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "....."]),
    ('y', [".....", ".....", "#...#", "#...#", "#...#", ".####", "....#", ".###."]),
    ('z', [".....", ".....", "#####", "...#.", "..#..", ".#...", "#####", "....."]),
    ('.', [".....", ".....", ".....", ".....", ".....", ".##..", ".##..", "....."]),
    (',', [".....", ".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."]),
    (':', [".....", ".##..", ".##..", ".....", ".##..", ".##..", ".....", "....."]),
    (';', [".....", ".##..", ".##..", ".....", ".##..", "..#..", ".#...", "....."]),
    ('%', ["##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##", "....."]),
    ('-', [".....", ".....", ".....", "#####", ".....", ".....", ".....", "....."]),
    ('+', [".....", "..#..", "..#..", "#####", "..#..", "..#..", ".....", "....."]),
    ('=', [".....", ".....", "#####", ".....", "#####", ".....", ".....", "....."]),
    ('(', ["...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#.", "....."]),
    (')', [".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#...", "....."]),
    ('/', ["....#", "....#", "...#.", "..#..", ".#...", "#....", "#....", "....."]),
    ('_', [".....", ".....", ".....", ".....", ".....", ".....", ".....", "#####"]),
    ('@', [".###.", "#...#", "#.###", "#.#.#", "#.###", "#....", ".###.", "....."]),
    ('<', ["...#.", "..#..", ".#...", "#....", ".#...", "..#..", "...#.", "....."]),
    ('>', [".#...", "..#..", "...#.", "....#", "...#.", "..#..", ".#...", "....."]),
    ('\'', ["..#..", "..#..", ".#...", ".....", ".....", ".....", ".....", "....."]),
    ('*', [".....", "#.#.#", ".###.", "#####", ".###.", "#.#.#", ".....", "....."]),
    ('λ', [".#...", "..#..", "..#..", ".#.#.", ".#.#.", "#...#", "#...#", "....."]),
    ('×', [".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", ".....", "....."]),
    ('—', [".....", ".....", ".....", "#####", ".....", ".....", ".....", "....."]),
];
