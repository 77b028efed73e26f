//! A picture of a terrain route: the grid hillshaded over a light elevation ramp, the
//! cost-distance contours from the start, and the route on top; a scale bar, a north
//! arrow and the contour interval in the corners.
//!
//! Drawn pixel by pixel here (no plotting crate: the picture is a raster of the grid,
//! so one pixel per sample is the natural scale, and a plotting library would add axes
//! and a dependency tree for no gain). The `png` feature writes it as a PNG.

use super::grid::{ElevationGrid, GridGeometry, SampleVertices};
use glam::DVec2;

/// An RGBA picture, row-major from the top (north), 4 bytes per pixel.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MapImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes: red, green, blue, alpha (0 on NODATA).
    pub rgba: Vec<u8>,
    /// Map units between two cost contours (`None` without a field).
    pub contour_interval: Option<f64>,
}

/// How a map is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct MapOptions {
    /// The longest side of the picture is at most this many pixels (big grids are
    /// downsampled). Default: 2048.
    pub max_side: u32,
    /// The longest side is at least this many pixels (small grids are upsampled).
    /// Default: 512.
    pub min_side: u32,
    /// About how many cost contours to draw (the interval is rounded to 1, 2 or 5 times
    /// a power of ten). Default: 10.
    pub contours: u32,
    /// Sun azimuth, degrees clockwise from north. Default: 315 (north-west).
    pub azimuth: f64,
    /// Sun altitude above the horizon, degrees. Default: 45.
    pub altitude: f64,
    /// The cost's unit, written after the contour interval (`"s"` for walking times).
    /// Default: `"m"`.
    pub cost_unit: &'static str,
    /// The map's unit, written on the scale bar (`"m"`: and `"km"` from 1000 on).
    /// Default: `"m"`.
    pub map_unit: &'static str,
}

impl MapOptions {
    /// The defaults.
    pub const DEFAULT: MapOptions = MapOptions {
        max_side: 2048,
        min_side: 512,
        contours: 10,
        azimuth: 315.0,
        altitude: 45.0,
        cost_unit: "m",
        map_unit: "m",
    };

    /// These options with the cost's unit `unit` (see [`MapOptions::cost_unit`]).
    pub const fn with_cost_unit(mut self, unit: &'static str) -> Self {
        self.cost_unit = unit;
        self
    }
}

impl Default for MapOptions {
    fn default() -> Self {
        MapOptions::DEFAULT
    }
}

/// Light hypsometric ramp: low green, sand, light brown, grey, white at the top.
const RAMP: [(f64, [f64; 3]); 5] = [
    (0.0, [168.0, 205.0, 160.0]),
    (0.3, [228.0, 224.0, 180.0]),
    (0.6, [214.0, 190.0, 152.0]),
    (0.85, [205.0, 200.0, 196.0]),
    (1.0, [255.0, 255.0, 255.0]),
];
const CONTOUR: [f64; 3] = [25.0, 55.0, 140.0];
const ROUTE: [f64; 3] = [215.0, 25.0, 30.0];
const HALO: [f64; 3] = [255.0, 255.0, 255.0];
const START: [f64; 3] = [30.0, 150.0, 60.0];
const END: [f64; 3] = [40.0, 80.0, 210.0];

/// Draws the map of `grid` (triangulated as `terrain`: its mesh, or a surface of it):
/// hillshade (sun at `options.azimuth`/`altitude`) over an elevation ramp, NODATA
/// transparent; contours of `vertex_distance` (one value per vertex of `terrain`, `inf`
/// where unreached) if given; and `route` (map positions, from start to end) drawn thick with
/// a marker at each end.
pub fn render(
    grid: &ElevationGrid,
    terrain: &impl SampleVertices,
    vertex_distance: Option<&[f64]>,
    route: &[[f64; 2]],
    options: &MapOptions,
) -> MapImage {
    let g = *grid.geometry();
    let (ncols, nrows) = (g.ncols, g.nrows);
    let long = ncols.max(nrows).max(1) as f64;
    let side = long.clamp(options.min_side as f64, options.max_side.max(1) as f64);
    let scale = side / long;
    let width = ((ncols as f64 * scale).round() as u32).max(1);
    let height = ((nrows as f64 * scale).round() as u32).max(1);

    let shade = hillshade(grid, options.azimuth, options.altitude);
    let (z_lo, z_hi) = grid.elevation_range().unwrap_or((0.0, 1.0));
    let z_span = if z_hi > z_lo { z_hi - z_lo } else { 1.0 };
    // Per-sample distance (NaN: unreached or no sample).
    let sample_distance: Option<Vec<f64>> = vertex_distance.map(|d| {
        (0..nrows)
            .flat_map(|r| (0..ncols).map(move |c| (c, r)))
            .map(|(c, r)| {
                terrain
                    .sample_vertex(c, r)
                    .and_then(|v| d.get(v as usize).copied())
                    .filter(|x| x.is_finite())
                    .unwrap_or(f64::NAN)
            })
            .collect()
    });
    let interval = sample_distance.as_ref().and_then(|d| {
        let max = d
            .iter()
            .copied()
            .filter(|x| !x.is_nan())
            .fold(0.0, f64::max);
        (max > 0.0).then(|| nice_interval(max / options.contours.max(1) as f64))
    });

    let (w, h) = (width as usize, height as usize);
    let mut rgba = vec![0u8; w * h * 4];
    let mut level = vec![f64::NAN; w * h];
    for py in 0..h {
        let fr = ((py as f64 + 0.5) / scale - 0.5).clamp(0.0, (nrows - 1) as f64);
        for px in 0..w {
            let fc = ((px as f64 + 0.5) / scale - 0.5).clamp(0.0, (ncols - 1) as f64);
            let Some(z) = sample(grid.values(), ncols, nrows, fc, fr) else {
                continue;
            };
            let s = sample(&shade, ncols, nrows, fc, fr).unwrap_or(0.7);
            let t = ((z - z_lo) / z_span).clamp(0.0, 1.0);
            let base = ramp(t);
            // Multiply blend, kept light: shadows darken to 40 %.
            let k = 0.4 + 0.6 * s.clamp(0.0, 1.0);
            put(&mut rgba, w, px, py, base.map(|c| c * k), 1.0);
            if let (Some(d), Some(step)) = (&sample_distance, interval) {
                if let Some(value) = sample(d, ncols, nrows, fc, fr) {
                    level[py * w + px] = (value / step).floor();
                }
            }
        }
    }
    if interval.is_some() {
        draw_contours(&mut rgba, &level, w, h);
    }
    draw_route(&mut rgba, w, h, &g, scale, route);
    let map_width = ncols as f64 * g.spacing[0];
    decorate(
        &mut rgba,
        w,
        h,
        scale / g.spacing[0],
        map_width,
        interval,
        options,
    );
    MapImage {
        width,
        height,
        rgba,
        contour_interval: interval,
    }
}

/// Marks the contours on `rgba` (`w` × `h` pixels): a contour passes between two pixels
/// whose levels (`level`, the distance in contour intervals, NaN where none) differ.
fn draw_contours(rgba: &mut [u8], level: &[f64], w: usize, h: usize) {
    for py in 0..h {
        for px in 0..w {
            let l = level[py * w + px];
            if l.is_nan() {
                continue;
            }
            let differs = |x: usize, y: usize| {
                let m = level[y * w + x];
                !m.is_nan() && m != l
            };
            if (px + 1 < w && differs(px + 1, py)) || (py + 1 < h && differs(px, py + 1)) {
                put(rgba, w, px, py, CONTOUR, 0.75);
            }
        }
    }
}

/// Draws `route` (map positions, from start to end) on `rgba` (`w` × `h` pixels, `scale`
/// pixels a cell of the grid `g`), thick with a halo, and a marker at each end.
fn draw_route(
    rgba: &mut [u8],
    w: usize,
    h: usize,
    g: &GridGeometry,
    scale: f64,
    route: &[[f64; 2]],
) {
    // The route, in pixel coordinates.
    let [x_min, _, _, y_max] = g.bounds();
    let to_pixel = |p: &[f64; 2]| {
        DVec2::new(
            ((p[0] - x_min) / g.spacing[0] + 0.5) * scale,
            ((y_max - p[1]) / g.spacing[1] + 0.5) * scale,
        )
    };
    let points: Vec<DVec2> = route.iter().map(to_pixel).collect();
    let radius = (w.max(h) as f64 / 400.0).max(1.5);
    for (colour, r) in [(HALO, radius + 1.5), (ROUTE, radius)] {
        for pair in points.windows(2) {
            stroke(rgba, w, h, pair[0], pair[1], r, colour);
        }
        if points.len() == 1 {
            stroke(rgba, w, h, points[0], points[0], r, colour);
        }
    }
    if let (Some(&a), Some(&b)) = (points.first(), points.last()) {
        for (p, colour) in [(a, START), (b, END)] {
            stroke(rgba, w, h, p, p, 3.0 * radius + 1.5, [0.0; 3]);
            stroke(rgba, w, h, p, p, 3.0 * radius, colour);
        }
    }
}

const INK: [f64; 3] = [20.0, 20.0, 20.0];

/// The corners: a scale bar (bottom left), a north arrow (top right; the grid is
/// north up) and the contour interval with a stroke of the contours' colour (bottom
/// right). `pixels_per_unit` converts map units to pixels.
fn decorate(
    rgba: &mut [u8],
    w: usize,
    h: usize,
    pixels_per_unit: f64,
    map_width: f64,
    interval: Option<f64>,
    options: &MapOptions,
) {
    // Font pixels of 2 at 512 pixels across, more on bigger pictures.
    let font = ((w.max(h) as f64 / 400.0).round() as usize).max(2);
    let margin = 4.0 * font as f64;
    let text_height = 7.0 * font as f64;
    // Scale bar: a round length near a fifth of the map.
    let length = round_down(map_width / 5.0);
    let bar = length * pixels_per_unit;
    let (x0, y0) = (margin, h as f64 - margin);
    let thick = font as f64 * 0.75;
    for (colour, r) in [(HALO, thick + 1.5), (INK, thick)] {
        let (a, b) = (DVec2::new(x0, y0), DVec2::new(x0 + bar, y0));
        stroke(rgba, w, h, a, b, r, colour);
        for x in [x0, x0 + bar] {
            let tick = DVec2::new(x, y0 - 2.5 * font as f64);
            stroke(rgba, w, h, tick, DVec2::new(x, y0), r, colour);
        }
    }
    let label = match options.map_unit {
        "m" if length >= 1000.0 => {
            format!("{} km", geotracks_render::font::number(length / 1000.0))
        }
        unit => format!("{} {unit}", geotracks_render::font::number(length)),
    };
    text(
        rgba,
        w,
        h,
        &label,
        x0,
        y0 - 4.0 * font as f64 - text_height,
        font,
        INK,
    );
    // North arrow: a filled triangle with an N under it.
    let (cx, top) = (w as f64 - margin - 3.0 * font as f64, margin);
    let tip = DVec2::new(cx, top);
    let base = top + 8.0 * font as f64;
    for (colour, grow) in [(HALO, 1.5), (INK, 0.0)] {
        for i in 0..=(8 * font) {
            let y = top + i as f64;
            let half = 3.0 * font as f64 * (y - top) / (base - top) + grow;
            stroke(
                rgba,
                w,
                h,
                DVec2::new(cx - half, y),
                DVec2::new(cx + half, y),
                0.5,
                colour,
            );
        }
        stroke(rgba, w, h, tip, tip, grow, colour);
    }
    text(
        rgba,
        w,
        h,
        "N",
        cx - 2.5 * font as f64,
        base + 2.0 * font as f64,
        font,
        INK,
    );
    // The contour interval.
    if let Some(step) = interval {
        let label = format!(
            "every {} {}",
            geotracks_render::font::number(step),
            options.cost_unit
        );
        let width = 6.0 * font as f64 * label.chars().count() as f64;
        let x = w as f64 - margin - width;
        let y = h as f64 - margin - text_height;
        text(rgba, w, h, &label, x, y, font, INK);
        let (a, b) = (
            DVec2::new(x - 9.0 * font as f64, y + text_height / 2.0),
            DVec2::new(x - 2.0 * font as f64, y + text_height / 2.0),
        );
        stroke(rgba, w, h, a, b, 1.5, HALO);
        stroke(rgba, w, h, a, b, 0.75, CONTOUR);
    }
}

/// 1, 2 or 5 times a power of ten, the nearest at or below `x` (> 0).
fn round_down(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v <= x * (1.0 + 1e-12))
        .unwrap_or(p)
}

/// Writes `text` with its top-left corner at `(x, y)`, each font pixel `font` pixels,
/// over a white halo one font pixel wide so that it reads on any ground.
#[allow(clippy::too_many_arguments)]
fn text(
    rgba: &mut [u8],
    w: usize,
    h: usize,
    text: &str,
    x: f64,
    y: f64,
    font: usize,
    colour: [f64; 3],
) {
    let f = font as f64;
    for (ink, grow) in [(HALO, f), (colour, 0.0)] {
        for (col, row) in geotracks_render::font::cells(text) {
            let (x0, y0) = (x + col as f64 * f - grow, y + row as f64 * f - grow);
            let (x1, y1) = (x0 + f + 2.0 * grow, y0 + f + 2.0 * grow);
            for py in y0.max(0.0) as usize..(y1.max(0.0) as usize).min(h) {
                for px in x0.max(0.0) as usize..(x1.max(0.0) as usize).min(w) {
                    put(rgba, w, px, py, ink, 1.0);
                }
            }
        }
    }
}

/// 1, 2 or 5 times a power of ten, the nearest at or above `x` (> 0).
fn nice_interval(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// Value at fractional sample `(fc, fr)`: bilinear over the valid samples of the cell,
/// `None` when the nearest sample is missing (so NODATA keeps its outline).
fn sample(values: &[f64], ncols: usize, nrows: usize, fc: f64, fr: f64) -> Option<f64> {
    let (c0, r0) = (fc.floor() as usize, fr.floor() as usize);
    let (c1, r1) = ((c0 + 1).min(ncols - 1), (r0 + 1).min(nrows - 1));
    let (tc, tr) = (fc - c0 as f64, fr - r0 as f64);
    let nearest = values[fr.round() as usize * ncols + fc.round() as usize];
    if nearest.is_nan() {
        return None;
    }
    let mut sum = 0.0;
    let mut weight = 0.0;
    for (c, r, wgt) in [
        (c0, r0, (1.0 - tc) * (1.0 - tr)),
        (c1, r0, tc * (1.0 - tr)),
        (c0, r1, (1.0 - tc) * tr),
        (c1, r1, tc * tr),
    ] {
        let v = values[r * ncols + c];
        if !v.is_nan() && wgt > 0.0 {
            sum += wgt * v;
            weight += wgt;
        }
    }
    Some(if weight > 0.0 { sum / weight } else { nearest })
}

/// Per sample: the cosine of the angle between the surface normal and the sun (0 in
/// shadow), from central differences (one-sided next to a missing sample or an edge).
fn hillshade(grid: &ElevationGrid, azimuth: f64, altitude: f64) -> Vec<f64> {
    let g = grid.geometry();
    let (ncols, nrows) = (g.ncols, g.nrows);
    let (az, alt) = (azimuth.to_radians(), altitude.to_radians());
    // x east, y north, z up; azimuth clockwise from north.
    let sun = glam::DVec3::new(alt.cos() * az.sin(), alt.cos() * az.cos(), alt.sin());
    let z = |c: usize, r: usize| grid.elevation(c, r);
    let derivative =
        |here: f64, before: Option<f64>, after: Option<f64>, step: f64| match (before, after) {
            (Some(a), Some(b)) => (b - a) / (2.0 * step),
            (Some(a), None) => (here - a) / step,
            (None, Some(b)) => (b - here) / step,
            (None, None) => 0.0,
        };
    let mut out = vec![f64::NAN; ncols * nrows];
    for r in 0..nrows {
        for c in 0..ncols {
            let Some(here) = z(c, r) else { continue };
            let west = c.checked_sub(1).and_then(|c| z(c, r));
            let north = r.checked_sub(1).and_then(|r| z(c, r));
            let dzdx = derivative(here, west, z(c + 1, r), g.spacing[0]);
            // Rows run south, y north: the row after is the one to the south.
            let dzdy = derivative(here, z(c, r + 1), north, g.spacing[1]);
            let n = glam::DVec3::new(-dzdx, -dzdy, 1.0).normalize();
            out[r * ncols + c] = n.dot(sun).max(0.0);
        }
    }
    out
}

fn ramp(t: f64) -> [f64; 3] {
    for pair in RAMP.windows(2) {
        let ((t0, c0), (t1, c1)) = (pair[0], pair[1]);
        if t <= t1 {
            let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
            return [0, 1, 2].map(|i| c0[i] + s * (c1[i] - c0[i]));
        }
    }
    RAMP[RAMP.len() - 1].1
}

/// Blends `colour` over pixel `(x, y)` with opacity `alpha`, making it opaque.
fn put(rgba: &mut [u8], w: usize, x: usize, y: usize, colour: [f64; 3], alpha: f64) {
    let i = 4 * (y * w + x);
    let under_alpha = rgba[i + 3] as f64 / 255.0;
    for k in 0..3 {
        let under = rgba[i + k] as f64 * under_alpha;
        rgba[i + k] = (alpha * colour[k] + (1.0 - alpha) * under)
            .round()
            .clamp(0.0, 255.0) as u8;
    }
    let a = alpha + (1.0 - alpha) * under_alpha;
    rgba[i + 3] = (255.0 * a).round() as u8;
}

/// Paints the pixels within `radius` of segment `a`–`b` (a disc when `a == b`), with a
/// one-pixel antialiased rim.
fn stroke(rgba: &mut [u8], w: usize, h: usize, a: DVec2, b: DVec2, radius: f64, colour: [f64; 3]) {
    let lo = a.min(b) - DVec2::splat(radius + 1.0);
    let hi = a.max(b) + DVec2::splat(radius + 1.0);
    let (x0, y0) = (lo.x.max(0.0) as usize, lo.y.max(0.0) as usize);
    let (x1, y1) = (
        (hi.x.max(0.0) as usize).min(w.saturating_sub(1)),
        (hi.y.max(0.0) as usize).min(h.saturating_sub(1)),
    );
    if lo.x > w as f64 || lo.y > h as f64 {
        return;
    }
    let ab = b - a;
    let len2 = ab.length_squared();
    for y in y0..=y1 {
        for x in x0..=x1 {
            let p = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
            let t = if len2 > 0.0 {
                ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (p - (a + t * ab)).length();
            let coverage = (radius + 0.5 - d).clamp(0.0, 1.0);
            if coverage > 0.0 {
                put(rgba, w, x, y, colour, coverage);
            }
        }
    }
}

#[cfg(feature = "png")]
impl MapImage {
    /// Writes the picture as an 8-bit RGBA PNG, atomically (no partial file on error).
    ///
    /// # Errors
    /// [`geotracks::mesh::MeshError::Io`] naming `path` if it cannot be written.
    pub fn write_png(
        &self,
        path: impl AsRef<std::path::Path>,
    ) -> Result<(), geotracks::mesh::MeshError> {
        geotracks_render::write_png_file(path.as_ref(), self.width, self.height, &self.rgba)
    }

    /// As [`MapImage::write_png`], into `w`.
    ///
    /// # Errors
    /// What `w` or the PNG encoder returns.
    pub fn write_png_to(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        geotracks_render::encode_png(w, self.width, self.height, &self.rgba)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_are_round() {
        assert_eq!(nice_interval(0.9), 1.0);
        assert_eq!(nice_interval(1.3), 2.0);
        assert_eq!(nice_interval(3.0), 5.0);
        assert_eq!(nice_interval(70.0), 100.0);
        assert_eq!(nice_interval(200.0), 200.0);
        assert_eq!(round_down(60.0), 50.0);
        assert_eq!(round_down(1999.0), 1000.0);
        assert_eq!(round_down(0.3), 0.2);
    }

    /// Dark pixels (the labels' ink) in a box of the picture.
    fn ink(map: &MapImage, xs: std::ops::Range<usize>, ys: std::ops::Range<usize>) -> usize {
        let w = map.width as usize;
        ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
            .filter(|&(x, y)| map.rgba[4 * (y * w + x)..][..3].iter().all(|&c| c < 60))
            .count()
    }

    #[test]
    fn the_corners_hold_a_scale_bar_a_north_arrow_and_the_interval() {
        use crate::{ElevationGrid, GridGeometry};
        // 100 × 50 samples 10 m apart: 1000 m across, a 200 m bar (a fifth).
        let geometry = GridGeometry {
            ncols: 100,
            nrows: 50,
            lower_left: [0.0, 0.0],
            spacing: [10.0, 10.0],
        };
        let grid = ElevationGrid::from_fn(geometry, |x, _| Some(0.01 * x)).unwrap();
        let terrain = grid.to_mesh().unwrap();
        let costs: Vec<f64> = terrain.mesh.positions().iter().map(|p| p.x).collect();
        let options = MapOptions::DEFAULT.with_cost_unit("s");
        let map = render(&grid, &terrain, Some(&costs), &[], &options);
        let (w, h) = (map.width as usize, map.height as usize);
        assert_eq!((w, h), (512, 256));
        // The bar: 200 m at 0.512 px/m is 102 px, on the row `margin` above the bottom.
        let font = 2;
        let (x0, y0) = (4 * font, h - 4 * font);
        let bar = ink(&map, x0..x0 + 102, y0..y0 + 1);
        assert!(bar >= 95, "{bar} dark pixels along the bar");
        assert_eq!(ink(&map, x0 + 110..x0 + 140, y0..y0 + 1), 0);
        // The arrow and its N, top right; the interval's label, bottom right.
        assert!(ink(&map, w - 40..w, 0..50) > 40);
        assert!(ink(&map, w - 150..w, h - 30..h) > 60);
        assert_eq!(map.contour_interval, Some(100.0));
        // No field, no interval label; the bar and the arrow stay.
        let bare = render(&grid, &terrain, None, &[], &options);
        assert_eq!(ink(&bare, w - 150..w - 40, h - 30..h), 0);
        assert!(ink(&bare, x0..x0 + 102, y0..y0 + 1) >= 95);
    }
}
