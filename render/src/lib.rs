//! # geotracks-render
//!
//! Pictures for [`geotracks`]: distance fields ([`render_field`]: the mesh shaded and
//! coloured by distance, isolines drawn on it, sources marked, a colour bar with the
//! range written on it) and curve skeletons over their medial axis
//! ([`render_skeleton`]).
//!
//! ## How it layers
//! Built on the core crate, which knows nothing of it: it draws a
//! [`TriMesh`] and values on it, and a
//! [`Skeleton`](geotracks::skeleton::Skeleton) over its
//! [`MedialAxis`](geotracks::mesh::io::MedialAxis). Its error is [`RenderError`]. Its
//! bitmap font ([`font`]) and PNG encoder ([`write_png_file`], [`encode_png`]) serve
//! pictures drawn elsewhere too: the terrain crate's maps.
//!
//! A small software rasterizer, here rather than a rendering crate: a picture is one
//! orthographic view of one triangle mesh, flat-shaded, with lines and discs on top —
//! a z-buffer and edge functions, about 300 lines — while the rendering crates bring a
//! GPU context or a scene graph and large dependency trees, and do not run headless in
//! CI. The `png` feature writes pictures as PNGs (the `image` crate's encoder).
//!
//! - **Camera**: orthographic, fitted to the mesh with a margin. [`View::Auto`] looks
//!   from the direction the faces show the most area to (the top eigenvector of
//!   `Σ area · n nᵀ`, with nalgebra: across a closed surface's thinnest extent, onto a
//!   sheet or the pages of a book rather than edge-on), with the vertices' widest
//!   spread across the picture, from the side where the first source lies; the named
//!   views look along the world axes (front: from +z with +y up, the convention of
//!   most OBJ models), and [`View::Orbit`] from an azimuth and an elevation.
//! - **Colour**: distance through viridis (perceptually uniform, readable in grey and
//!   by most colour-blind readers), from 0 to the largest finite vertex value;
//!   unreached parts grey. Shading is Lambert, two-sided (medial axes and non-manifold
//!   meshes have no consistent orientation), plus ambient light.
//! - **Overlays**: isolines (dark, depth-tested with a small bias, so hidden parts are
//!   not drawn), sources (red discs with a white ring, on top), and a colour bar on the
//!   right with `0`, the middle and the maximum written with a built-in 5 × 7 font.
//! - **Skeletons**: the axis's sheets pale and a little transparent (curves behind a
//!   sheet show through it, mixed with its colour), the skeleton coloured by medial
//!   radius, tips and junctions as dots.
//! - Drawn at twice the size and averaged down (anti-aliasing).

#![forbid(unsafe_code)]

pub mod font;
mod raster;
mod skeleton;

pub use skeleton::render_skeleton;

/// Why a picture could not be drawn.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A picture option is out of range ([`render_field`], [`render_skeleton`]).
    #[error("picture option {option} is {}; it must be {expected}", geotracks::metrics::Num(*value))]
    InvalidPictureOption {
        /// The option's name.
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
}

use geotracks::mesh::TriMesh;
use glam::DVec3;
use raster::Canvas;

/// Where the camera looks from ([`PictureOptions::view`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum View {
    /// From where the faces show the most area, the first source's side.
    Auto,
    /// From +z, +y up.
    Front,
    /// From −z, +y up.
    Back,
    /// From −x, +y up.
    Left,
    /// From +x, +y up.
    Right,
    /// From +y, −z up.
    Top,
    /// From −y, +z up.
    Bottom,
    /// From azimuth `azimuth` (degrees about +y, 0 = front, 90 = right) and elevation
    /// `elevation` (degrees above the horizontal plane, −90 to 90).
    Orbit {
        /// Degrees about +y from the front.
        azimuth: f64,
        /// Degrees above the horizontal plane.
        elevation: f64,
    },
}

impl std::str::FromStr for View {
    type Err = String;

    /// `auto`, `front`, `back`, `left`, `right`, `top`, `bottom`, or `AZ,EL` in degrees.
    fn from_str(text: &str) -> Result<View, String> {
        Ok(match text.trim() {
            "auto" => View::Auto,
            "front" => View::Front,
            "back" => View::Back,
            "left" => View::Left,
            "right" => View::Right,
            "top" => View::Top,
            "bottom" => View::Bottom,
            other => {
                let parts: Vec<f64> = other
                    .split(',')
                    .map(|s| s.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
                    .collect::<Option<_>>()
                    .ok_or_else(|| view_error(text))?;
                match parts[..] {
                    [azimuth, elevation] if (-90.0..=90.0).contains(&elevation) => {
                        View::Orbit { azimuth, elevation }
                    }
                    _ => return Err(view_error(text)),
                }
            }
        })
    }
}

fn view_error(text: &str) -> String {
    format!(
        "'{text}' is not a view: auto, front, back, left, right, top, bottom, or AZ,EL \
         (degrees; elevation from -90 to 90)"
    )
}

/// How a picture is drawn ([`render_field`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PictureOptions {
    /// Width in pixels (64 to 8192). Default 1024.
    pub width: u32,
    /// Height in pixels (64 to 8192). Default 768.
    pub height: u32,
    /// Where the camera looks from. Default [`View::Auto`].
    pub view: View,
}

impl PictureOptions {
    /// 1024 × 768, automatic view.
    pub const DEFAULT: PictureOptions = PictureOptions {
        width: 1024,
        height: 768,
        view: View::Auto,
    };

    /// These options at `width × height`.
    pub const fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// These options with `view`.
    pub const fn with_view(mut self, view: View) -> Self {
        self.view = view;
        self
    }
}

impl Default for PictureOptions {
    fn default() -> Self {
        PictureOptions::DEFAULT
    }
}

/// An RGBA picture, row-major from the top, 4 bytes per pixel.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Picture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes: red, green, blue, alpha.
    pub rgba: Vec<u8>,
}

/// The smallest and largest picture side accepted.
const SIDES: std::ops::RangeInclusive<u32> = 64..=8192;
/// Drawn at this many times the size, then averaged down.
const SUPERSAMPLE: u32 = 2;

/// Draws `mesh` coloured by `vertex_values` (one per vertex; `inf` unreached), with
/// `isolines` (polylines of world points on the surface) and `sources` (world points)
/// on top, as `options` say; see the module docs.
///
/// ```
/// use geotracks::mesh::TriMesh;
/// use geotracks_render::{render_field, PictureOptions};
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let d = [0.0, 1.0, 2f64.sqrt(), 1.0];
/// let picture = render_field(&mesh, &d, &[], &[mesh.position(0)], &PictureOptions::DEFAULT)?;
/// assert_eq!((picture.width, picture.height), (1024, 768));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`RenderError::InvalidPictureOption`] for a size outside 64–8192 pixels, or
/// `vertex_values` not one per vertex.
pub fn render_field(
    mesh: &TriMesh,
    vertex_values: &[f64],
    isolines: &[Vec<DVec3>],
    sources: &[DVec3],
    options: &PictureOptions,
) -> Result<Picture, RenderError> {
    check_size(options)?;
    if vertex_values.len() != mesh.vertex_count() {
        return Err(RenderError::InvalidPictureOption {
            option: "vertex values",
            value: vertex_values.len() as f64,
            expected: "one per vertex of the mesh",
        });
    }
    let camera = raster::Camera::fit(mesh, options, sources.first().copied(), BAR_WIDTH);
    let max = vertex_values
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    let (w, h) = (options.width * SUPERSAMPLE, options.height * SUPERSAMPLE);
    let mut canvas = Canvas::new(w, h);
    for f in 0..mesh.face_count() as u32 {
        let corners = mesh.face_vertices(f);
        let p = corners.map(|v| mesh.position(v));
        let shade = camera.shade(p, 0.35);
        let values = corners.map(|v| vertex_values[v as usize]);
        canvas.triangle(&camera, p, |b| {
            let d = b[0] * values[0] + b[1] * values[1] + b[2] * values[2];
            let base = if d.is_finite() {
                viridis(if max > 0.0 { d / max } else { 0.0 })
            } else {
                UNREACHED
            };
            base.map(|c| c * shade)
        });
    }
    let line_radius = 0.9 * SUPERSAMPLE as f64;
    for line in isolines {
        for pair in line.windows(2) {
            canvas.segment(&camera, pair[0], pair[1], line_radius, ISOLINE);
        }
    }
    for &s in sources {
        let r = 5.0 * SUPERSAMPLE as f64;
        canvas.disc(&camera, s, r + 1.5 * SUPERSAMPLE as f64, [255.0; 3]);
        canvas.disc(&camera, s, r, SOURCE);
    }
    let mut picture = canvas.downsample(SUPERSAMPLE);
    colour_bar(&mut picture, max);
    Ok(picture)
}

/// [`RenderError::InvalidPictureOption`] unless both sides are 64 to 8192 pixels.
fn check_size(options: &PictureOptions) -> Result<(), RenderError> {
    for (option, value) in [("width", options.width), ("height", options.height)] {
        if !SIDES.contains(&value) {
            return Err(RenderError::InvalidPictureOption {
                option,
                value: value as f64,
                expected: "between 64 and 8192 pixels",
            });
        }
    }
    Ok(())
}

const UNREACHED: [f64; 3] = [170.0, 170.0, 170.0];
const ISOLINE: [f64; 3] = [25.0, 25.0, 25.0];
const SOURCE: [f64; 3] = [220.0, 30.0, 35.0];
/// Pixels kept free on the right for the colour bar.
const BAR_WIDTH: u32 = 150;

/// Viridis (the `colorous` crate's, as the coloured PLY output uses): `t` in [0, 1].
fn viridis(t: f64) -> [f64; 3] {
    let c = colorous::VIRIDIS.eval_continuous(t.clamp(0.0, 1.0));
    [c.r as f64, c.g as f64, c.b as f64]
}

/// The colour bar at the picture's right edge, with 0, the middle and `max` written.
fn colour_bar(picture: &mut Picture, max: f64) {
    let (w, h) = (picture.width as i64, picture.height as i64);
    let (x0, x1) = (w - BAR_WIDTH as i64 + 10, w - BAR_WIDTH as i64 + 30);
    let (top, bottom) = (h / 8, h - h / 8);
    for y in top..=bottom {
        let t = (bottom - y) as f64 / (bottom - top) as f64;
        let c = viridis(t);
        for x in x0..=x1 {
            raster::put(picture, x, y, c);
        }
    }
    for x in x0 - 1..=x1 + 1 {
        raster::put(picture, x, top - 1, ISOLINE);
        raster::put(picture, x, bottom + 1, ISOLINE);
    }
    for y in top - 1..=bottom + 1 {
        raster::put(picture, x0 - 1, y, ISOLINE);
        raster::put(picture, x1 + 1, y, ISOLINE);
    }
    let scale = if h >= 400 { 2 } else { 1 };
    for (t, value) in [(0.0, 0.0), (0.5, 0.5 * max), (1.0, max)] {
        let y = bottom - (t * (bottom - top) as f64).round() as i64;
        let text = font::number(value);
        font::draw(picture, &text, x1 + 6, y - 3 * scale, scale, ISOLINE);
    }
}

#[cfg(feature = "png")]
impl Picture {
    /// Writes the picture as an 8-bit RGBA PNG, atomically (no partial file on error).
    ///
    /// # Errors
    /// [`geotracks::mesh::MeshError::Io`] naming `path` if it cannot be written.
    pub fn write_png(
        &self,
        path: impl AsRef<std::path::Path>,
    ) -> Result<(), geotracks::mesh::MeshError> {
        write_png_file(path.as_ref(), self.width, self.height, &self.rgba)
    }

    /// As [`Picture::write_png`], into `w`.
    ///
    /// # Errors
    /// What `w` or the PNG encoder returns.
    pub fn write_png_to(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        encode_png(w, self.width, self.height, &self.rgba)
    }
}

/// Writes an RGBA buffer (`width × height` pixels, row-major from the top) as an 8-bit
/// PNG file, atomically (no partial file on error): for pictures drawn outside this
/// crate, such as terrain maps.
///
/// # Errors
/// [`MeshError::Io`](geotracks::mesh::MeshError::Io) naming `path` if it cannot be
/// written.
#[cfg(feature = "png")]
pub fn write_png_file(
    path: &std::path::Path,
    width: u32,
    height: u32,
    rgba: &[u8],
) -> Result<(), geotracks::mesh::MeshError> {
    geotracks::mesh::io::write_atomically(path, |w| encode_png(w, width, height, rgba))
}

/// Encodes an RGBA buffer (`width × height` pixels, row-major from the top) as an
/// 8-bit PNG into `w`: for pictures drawn outside this crate, such as terrain maps.
///
/// # Errors
/// What `w` or the PNG encoder returns.
#[cfg(feature = "png")]
pub fn encode_png(
    w: &mut dyn std::io::Write,
    width: u32,
    height: u32,
    rgba: &[u8],
) -> std::io::Result<()> {
    use image::ImageEncoder;
    image::codecs::png::PngEncoder::new(w)
        .write_image(rgba, width, height, image::ExtendedColorType::Rgba8)
        .map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_grows_lighter() {
        let lightness = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        let mut last = -1.0;
        for i in 0..=100 {
            let l = lightness(viridis(i as f64 / 100.0));
            assert!(l > last, "{i}: {l} after {last}");
            last = l;
        }
    }

    #[test]
    fn views_parse_and_bad_ones_are_refused() {
        assert_eq!("front".parse::<View>(), Ok(View::Front));
        assert_eq!(
            "30,-45".parse::<View>(),
            Ok(View::Orbit {
                azimuth: 30.0,
                elevation: -45.0
            })
        );
        for bad in ["sideways", "30", "30,100", "a,b", "1,2,3", "nan,0"] {
            assert!(bad.parse::<View>().is_err(), "{bad}");
        }
    }
}

/// The README's code blocks, compiled and run as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
