//! The rasterizer: an orthographic camera, a z-buffered canvas (triangles, segments,
//! discs) drawn at a multiple of the picture's size and averaged down.

use super::{Picture, PictureOptions, View, SUPERSAMPLE};
use geotracks::mesh::TriMesh;
use glam::DVec3;

/// An orthographic camera fitted to a scene: screen `x` along `right`, `y` down along
/// `−up`, depth along `towards` (from the scene to the eye: larger is nearer).
pub(super) struct Camera {
    centre: DVec3,
    right: DVec3,
    up: DVec3,
    towards: DVec3,
    /// Pixels (of the supersampled canvas) per world unit.
    scale: f64,
    /// Where `centre` lands on the canvas.
    origin: (f64, f64),
    /// Depth tolerance for lines on the surface (world units).
    pub bias: f64,
}

impl Camera {
    /// The camera of `options.view` fitted to `mesh` in the picture less `bar` pixels on
    /// the right, `source` (if any) facing it in the automatic view.
    pub fn fit(
        mesh: &TriMesh,
        options: &PictureOptions,
        source: Option<DVec3>,
        bar: u32,
    ) -> Camera {
        Camera::fit_points(mesh.positions(), Some(mesh), options, source, bar)
    }

    /// As [`Camera::fit`], fitted to `positions`; the automatic view looks onto the
    /// faces of `surface` if it has area, else across the points' thinnest spread.
    pub fn fit_points(
        positions: &[DVec3],
        surface: Option<&TriMesh>,
        options: &PictureOptions,
        source: Option<DVec3>,
        bar: u32,
    ) -> Camera {
        let n = positions.len().max(1) as f64;
        let centroid = positions.iter().fold(DVec3::ZERO, |s, &p| s + p) / n;
        let (right, up, towards) = axes(options.view, positions, surface, centroid, source);
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        let mut depth = (f64::INFINITY, f64::NEG_INFINITY);
        for &p in positions {
            let d = p - centroid;
            let (x, y, z) = (d.dot(right), d.dot(up), d.dot(towards));
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
            depth = (depth.0.min(z), depth.1.max(z));
        }
        if positions.is_empty() {
            (lo, hi, depth) = ((-1.0, -1.0), (1.0, 1.0), (-1.0, 1.0));
        }
        let ss = SUPERSAMPLE as f64;
        let plot_w = (options.width.saturating_sub(bar)).max(16) as f64 * ss;
        let plot_h = options.height as f64 * ss;
        let margin = 0.06;
        let (span_x, span_y) = (hi.0 - lo.0, hi.1 - lo.1);
        let fit = |span: f64, room: f64| {
            if span > 0.0 {
                room * (1.0 - 2.0 * margin) / span
            } else {
                f64::INFINITY
            }
        };
        let mut scale = fit(span_x, plot_w).min(fit(span_y, plot_h));
        if !scale.is_finite() {
            scale = 1.0; // a single point
        }
        let middle = ((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0);
        let origin = (
            plot_w / 2.0 - middle.0 * scale,
            plot_h / 2.0 + middle.1 * scale,
        );
        let diameter = (span_x.max(span_y)).max(depth.1 - depth.0).max(1e-300);
        Camera {
            centre: centroid,
            right,
            up,
            towards,
            scale,
            origin,
            bias: 0.004 * diameter,
        }
    }

    /// Canvas position and depth of world point `p`.
    pub fn project(&self, p: DVec3) -> (f64, f64, f64) {
        let d = p - self.centre;
        (
            self.origin.0 + d.dot(self.right) * self.scale,
            self.origin.1 - d.dot(self.up) * self.scale,
            d.dot(self.towards),
        )
    }

    /// The light: from the eye, a little above and to the left.
    fn light(&self) -> DVec3 {
        (self.towards + 0.45 * self.up - 0.3 * self.right).normalize()
    }

    /// How lit the triangle `p` is, from `ambient` (edge-on) to 1 (facing the light):
    /// Lambert, two-sided (medial axes and non-manifold meshes have no consistent
    /// orientation), plus ambient light.
    pub fn shade(&self, p: [DVec3; 3], ambient: f64) -> f64 {
        let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        ambient + (1.0 - ambient) * normal.dot(self.light()).abs()
    }
}

/// `(right, up, towards)`, right-handed (`right × up = towards`).
fn axes(
    view: View,
    positions: &[DVec3],
    surface: Option<&TriMesh>,
    centroid: DVec3,
    source: Option<DVec3>,
) -> (DVec3, DVec3, DVec3) {
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    let orbit = |azimuth: f64, elevation: f64| {
        let (a, e) = (azimuth.to_radians(), elevation.to_radians());
        let towards = DVec3::new(a.sin() * e.cos(), e.sin(), a.cos() * e.cos());
        let mut right = y.cross(towards);
        if right.length() < 1e-9 {
            // Straight above or below: keep the azimuth's right.
            right = DVec3::new(a.cos(), 0.0, -a.sin());
        }
        let right = right.normalize();
        (right, towards.cross(right), towards)
    };
    match view {
        View::Front => (x, y, z),
        View::Back => (-x, y, -z),
        View::Left => (z, y, -x),
        View::Right => (-z, y, x),
        View::Top => (x, -z, y),
        View::Bottom => (x, z, -y),
        View::Orbit { azimuth, elevation } => orbit(azimuth, elevation),
        View::Auto => auto_axes(positions, surface, centroid, source).unwrap_or((x, y, z)),
    }
}

/// The automatic view: towards the eye, the direction the faces show the most area to
/// (the top eigenvector of `Σ area · n nᵀ`; for a closed surface, across its thinnest
/// extent; for a sheet or a book of sheets, onto them rather than edge-on), with the
/// vertex cloud's widest direction across the picture, up as the world's up where it
/// can be, and the first source on the eye's side. Without a surface with area (curves
/// only), towards the eye is the points' thinnest spread. `None` for a single point.
fn auto_axes(
    positions: &[DVec3],
    surface: Option<&TriMesh>,
    centroid: DVec3,
    source: Option<DVec3>,
) -> Option<(DVec3, DVec3, DVec3)> {
    use nalgebra::{Matrix3, SymmetricEigen, Vector3};
    let v3 = |d: DVec3| Vector3::new(d.x, d.y, d.z);
    // The unit eigenvector of the largest (or smallest) eigenvalue of a covariance-like
    // matrix that is not all zero.
    let principal = |m: Matrix3<f64>, largest: bool| -> Option<DVec3> {
        let eigen = SymmetricEigen::new(m);
        let values = &eigen.eigenvalues;
        let i = if largest {
            values.imax()
        } else {
            values.imin()
        };
        let c = eigen.eigenvectors.column(i);
        let d = DVec3::new(c[0], c[1], c[2]);
        (d.is_finite() && d.length() > 0.5 && values.max() > 0.0).then(|| d.normalize())
    };
    let mut shown = Matrix3::<f64>::zeros();
    if let Some(mesh) = surface {
        for f in 0..mesh.face_count() as u32 {
            let p = mesh.face_vertices(f).map(|v| mesh.position(v));
            let n = (p[1] - p[0]).cross(p[2] - p[0]); // length: twice the area
            let len = n.length();
            if len > 0.0 {
                shown += v3(n) * v3(n).transpose() / len;
            }
        }
    }
    let mut towards = match principal(shown, true) {
        Some(towards) => towards,
        None => {
            // Curves only: look along the points' least spread.
            let mut cloud = Matrix3::<f64>::zeros();
            for &p in positions {
                cloud += v3(p - centroid) * v3(p - centroid).transpose();
            }
            principal(cloud, false)?
        }
    };
    // The widest spread of the vertices across the view.
    let mut spread = Matrix3::<f64>::zeros();
    for &p in positions {
        let d = p - centroid;
        let d = d - towards * d.dot(towards);
        spread += v3(d) * v3(d).transpose();
    }
    let mut right = principal(spread, true).unwrap_or_else(|| towards.any_orthonormal_vector());
    let mut up = towards.cross(right);
    let world_up = if up.dot(DVec3::Y).abs() > 1e-6 {
        DVec3::Y
    } else {
        DVec3::Z
    };
    if up.dot(world_up) < 0.0 {
        up = -up;
        right = -right;
    }
    towards = right.cross(up);
    if let Some(s) = source {
        if (s - centroid).dot(towards) < 0.0 {
            towards = -towards;
            right = -right;
        }
    }
    Some((right, up, towards))
}

/// A z-buffered RGB canvas.
///
/// Colours are kept as the picture's bytes and depths in single precision: 11 bytes
/// a pixel with a surface kept under lines, 35 MB for a 1024 × 768 picture drawn at
/// twice its size (in `f64`, 57 bytes and 180 MB). Rounding each sample to a byte
/// before the samples are averaged moves a channel of the picture by at most one.
/// Depths are measured from the scene's centre, so `f32` resolves about 1e-7 of the
/// scene's size, far below the bias that lines on the surface are drawn with.
pub(super) struct Canvas {
    width: u32,
    height: u32,
    colour: Vec<[u8; 3]>,
    depth: Vec<f32>,
    /// The surface's colours under lines drawn through it ([`Canvas::line`]), kept
    /// from the first such line on, so that a line seen through the surface is mixed
    /// with the surface once, however many times it is drawn over a pixel.
    surface: Vec<[u8; 3]>,
    /// Per pixel: 0 nothing over the surface, 1 a line seen through it, 2 a line in
    /// front of it (which one seen through does not cover).
    line: Vec<u8>,
}

impl Canvas {
    /// White, with nothing drawn.
    pub fn new(width: u32, height: u32) -> Canvas {
        let n = width as usize * height as usize;
        Canvas {
            width,
            height,
            colour: vec![[255; 3]; n],
            depth: vec![f32::NEG_INFINITY; n],
            surface: Vec::new(),
            line: vec![0; n],
        }
    }

    /// Fills the triangle `p` (world points), nearer than what is drawn, with
    /// `colour(barycentric)` at each pixel centre.
    pub fn triangle(
        &mut self,
        camera: &Camera,
        p: [DVec3; 3],
        colour: impl Fn([f64; 3]) -> [f64; 3],
    ) {
        let q = p.map(|x| camera.project(x));
        let area = (q[1].0 - q[0].0) * (q[2].1 - q[0].1) - (q[2].0 - q[0].0) * (q[1].1 - q[0].1);
        if area.abs() <= 1e-12 || area.is_nan() {
            return; // seen edge-on (or degenerate): no pixel centre inside
        }
        let (w, h) = (self.width as f64, self.height as f64);
        // The pixels the triangle's bounding box covers, clipped to the canvas.
        let span = |coord: fn(&(f64, f64, f64)) -> f64, size: f64| {
            let lo = q.iter().map(coord).fold(f64::INFINITY, f64::min);
            let hi = q.iter().map(coord).fold(f64::NEG_INFINITY, f64::max);
            (lo.max(0.0).floor() as usize, hi.min(size - 1.0).ceil())
        };
        let (x0, x1) = span(|a| a.0, w);
        let (y0, y1) = span(|a| a.1, h);
        if !(x1 >= 0.0 && y1 >= 0.0) {
            return;
        }
        let edge = |a: (f64, f64, f64), b: (f64, f64, f64), x: f64, y: f64| {
            (b.0 - a.0) * (y - a.1) - (x - a.0) * (b.1 - a.1)
        };
        for y in y0..=y1 as usize {
            for x in x0..=x1 as usize {
                let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                let b = [
                    edge(q[1], q[2], cx, cy) / area,
                    edge(q[2], q[0], cx, cy) / area,
                    edge(q[0], q[1], cx, cy) / area,
                ];
                if b.iter().any(|&t| t < -1e-9) {
                    continue;
                }
                let z = (b[0] * q[0].2 + b[1] * q[1].2 + b[2] * q[2].2) as f32;
                let i = y * self.width as usize + x;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.colour[i] = bytes(colour(b));
                }
            }
        }
    }

    /// A segment of world points `a`–`b`, `radius` pixels wide each side, where it is
    /// not behind the surface (to the camera's bias).
    pub fn segment(&mut self, camera: &Camera, a: DVec3, b: DVec3, radius: f64, colour: [f64; 3]) {
        self.line(camera, a, b, radius, colour, 0.0);
    }

    /// As [`Canvas::segment`], and where the segment is behind the surface, seen
    /// through it: `colour` mixed into the surface's at `through` (0 to 1), as if the
    /// surface let `through` of the light behind it pass.
    pub fn line(
        &mut self,
        camera: &Camera,
        a: DVec3,
        b: DVec3,
        radius: f64,
        colour: [f64; 3],
        through: f64,
    ) {
        if through > 0.0 && self.surface.is_empty() {
            self.surface = self.colour.clone();
        }
        let (pa, pb) = (camera.project(a), camera.project(b));
        let length = (pb.0 - pa.0).hypot(pb.1 - pa.1);
        if !length.is_finite() {
            return;
        }
        let steps = (length / 0.5).ceil().min(1e6) as usize + 1;
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let (x, y, z) = (
                pa.0 + t * (pb.0 - pa.0),
                pa.1 + t * (pb.1 - pa.1),
                pa.2 + t * (pb.2 - pa.2),
            );
            for i in self.pixels_within(x, y, radius) {
                if z >= f64::from(self.depth[i]) - camera.bias {
                    self.colour[i] = bytes(colour);
                    self.line[i] = 2;
                } else if through > 0.0 && self.line[i] < 2 {
                    let under = self.surface[i].map(f64::from);
                    self.colour[i] = bytes(std::array::from_fn(|k| {
                        under[k] + through * (colour[k] - under[k])
                    }));
                    self.line[i] = 1;
                }
            }
        }
    }

    /// A disc of `radius` pixels round world point `p`, on top of everything.
    pub fn disc(&mut self, camera: &Camera, p: DVec3, radius: f64, colour: [f64; 3]) {
        let (x, y, _) = camera.project(p);
        for i in self.pixels_within(x, y, radius) {
            self.colour[i] = bytes(colour);
        }
    }

    /// The canvas indices of the pixels whose centres lie within `radius` of `(x, y)`.
    fn pixels_within(&self, x: f64, y: f64, radius: f64) -> impl Iterator<Item = usize> {
        let (w, h) = (self.width as i64, self.height as i64);
        let r = radius.ceil() as i64;
        let (x0, y0) = (x.floor() as i64, y.floor() as i64);
        (-r..=r)
            .flat_map(move |dy| (-r..=r).map(move |dx| (x0 + dx, y0 + dy)))
            .filter(move |&(px, py)| {
                let (cx, cy) = (px as f64 + 0.5 - x, py as f64 + 0.5 - y);
                px >= 0 && py >= 0 && px < w && py < h && cx * cx + cy * cy <= radius * radius
            })
            .map(move |(px, py)| py as usize * w as usize + px as usize)
    }

    /// The canvas averaged over `k × k` blocks.
    pub fn downsample(&self, k: u32) -> Picture {
        let (w, h) = (self.width / k, self.height / k);
        let mut rgba = Vec::with_capacity(w as usize * h as usize * 4);
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0u32; 3];
                for dy in 0..k {
                    for dx in 0..k {
                        let c = self.colour[((y * k + dy) * self.width + x * k + dx) as usize];
                        (0..3).for_each(|i| sum[i] += u32::from(c[i]));
                    }
                }
                let n = (k * k) as f64;
                rgba.extend(sum.map(|s| (f64::from(s) / n).round() as u8));
                rgba.push(255);
            }
        }
        Picture {
            width: w,
            height: h,
            rgba,
        }
    }
}

/// A colour (channels 0 to 255) as bytes, rounded and clamped.
fn bytes(colour: [f64; 3]) -> [u8; 3] {
    colour.map(|c| c.round().clamp(0.0, 255.0) as u8)
}

/// Sets pixel `(x, y)` of `picture` (ignored outside it).
pub(super) fn put(picture: &mut Picture, x: i64, y: i64, colour: [f64; 3]) {
    if x < 0 || y < 0 || x >= picture.width as i64 || y >= picture.height as i64 {
        return;
    }
    let i = (y as usize * picture.width as usize + x as usize) * 4;
    picture.rgba[i..i + 3].copy_from_slice(&bytes(colour));
    picture.rgba[i + 3] = 255;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_triangle() -> TriMesh {
        TriMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap()
    }

    #[test]
    fn a_triangle_covers_its_pixels_and_no_others() {
        let mesh = one_triangle();
        let options = PictureOptions::DEFAULT
            .with_size(200, 200)
            .with_view(View::Front);
        let camera = Camera::fit(&mesh, &options, None, 0);
        let mut canvas = Canvas::new(400, 400);
        canvas.triangle(&camera, [0, 1, 2].map(|v| mesh.position(v)), |_| [0.0; 3]);
        // Inside the triangle (in world terms) black, outside white.
        let mut checked = 0;
        for y in 0..400u32 {
            for x in 0..400u32 {
                // Back from the canvas to the world plane z = 0.
                let wx = (x as f64 + 0.5 - camera.origin.0) / camera.scale + camera.centre.x;
                let wy = (camera.origin.1 - (y as f64 + 0.5)) / camera.scale + camera.centre.y;
                let margin = 2.0 / camera.scale;
                let inside = wx > margin && wy > margin && wx + wy < 1.0 - 2.0 * margin;
                let outside = wx < -margin || wy < -margin || wx + wy > 1.0 + 2.0 * margin;
                let c = canvas.colour[(y * 400 + x) as usize];
                if inside {
                    assert_eq!(c, [0; 3], "({x}, {y}) should be drawn");
                    checked += 1;
                } else if outside {
                    assert_eq!(c, [255; 3], "({x}, {y}) should be blank");
                }
            }
        }
        assert!(checked > 10_000);
    }

    #[test]
    fn the_nearer_face_hides_the_farther() {
        // Two parallel triangles, z = 0 and z = 1, seen from the front (+z): the one at
        // z = 1 wins whichever is drawn first.
        let mesh = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 1.0],
                [0.0, 1.0, 1.0],
            ],
            vec![[0, 1, 2], [3, 4, 5]],
        )
        .unwrap();
        let options = PictureOptions::DEFAULT
            .with_size(100, 100)
            .with_view(View::Front);
        let camera = Camera::fit(&mesh, &options, None, 0);
        for order in [[0u32, 1], [1, 0]] {
            let mut canvas = Canvas::new(200, 200);
            for f in order {
                let colour = if f == 1 { [1.0; 3] } else { [2.0; 3] };
                let p = mesh.face_vertices(f).map(|v| mesh.position(v));
                canvas.triangle(&camera, p, |_| colour);
            }
            let (x, y, _) = camera.project(DVec3::new(0.25, 0.25, 0.0));
            assert_eq!(canvas.colour[y as usize * 200 + x as usize], [1; 3]);
        }
    }

    #[test]
    fn a_supersampled_default_picture_fits_in_forty_megabytes() {
        // The default picture (1024 × 768) drawn at twice its size, with the surface
        // kept under a line seen through it: every buffer at its full length.
        let mesh = one_triangle();
        let camera = Camera::fit(&mesh, &PictureOptions::DEFAULT, None, 0);
        let (w, h) = (1024 * SUPERSAMPLE, 768 * SUPERSAMPLE);
        let mut canvas = Canvas::new(w, h);
        canvas.triangle(&camera, [0, 1, 2].map(|v| mesh.position(v)), |_| [9.0; 3]);
        let behind = DVec3::new(0.3, 0.3, -1.0);
        canvas.line(&camera, behind, behind + DVec3::X * 0.2, 2.0, [0.0; 3], 0.5);
        assert_eq!(canvas.surface.len(), (w * h) as usize);
        let bytes = canvas.colour.capacity() * std::mem::size_of::<[u8; 3]>()
            + canvas.depth.capacity() * std::mem::size_of::<f32>()
            + canvas.surface.capacity() * std::mem::size_of::<[u8; 3]>()
            + canvas.line.capacity();
        assert!(bytes <= 40_000_000, "{bytes} bytes");
        // And a line seen through the surface is mixed with it, not drawn over it.
        let (x, y, _) = camera.project(behind + DVec3::X * 0.1);
        let mixed = canvas.colour[y as usize * w as usize + x as usize];
        assert_eq!(mixed, [5; 3], "half of 9 over 0, rounded");
    }

    #[test]
    fn the_automatic_camera_frames_every_vertex_and_faces_the_source() {
        // A flat, wide, tilted slab: the view looks across its thin axis.
        let mut positions = Vec::new();
        for i in 0..20 {
            for j in 0..5 {
                let (u, v) = (i as f64, j as f64 * 0.5);
                positions.push([u, v * 0.8, v * 0.6 + 0.01 * (i * j) as f64]);
            }
        }
        let mut faces = Vec::new();
        for i in 0..19u32 {
            for j in 0..4u32 {
                let a = i * 5 + j;
                faces.push([a, a + 5, a + 6]);
                faces.push([a, a + 6, a + 1]);
            }
        }
        let mesh = TriMesh::new(positions, faces).unwrap();
        let options = PictureOptions::DEFAULT.with_size(300, 200);
        for source in [DVec3::new(0.0, -0.6, 0.8), DVec3::new(0.0, 0.6, -0.8)] {
            let camera = Camera::fit(&mesh, &options, Some(source), 50);
            for &p in mesh.positions() {
                let (x, y, _) = camera.project(p);
                assert!(
                    x >= 0.0
                        && x <= 250.0 * SUPERSAMPLE as f64
                        && y >= 0.0
                        && y <= 200.0 * SUPERSAMPLE as f64
                );
            }
            // The thin axis (the slab's normal, ±(0, −0.6, 0.8)) points at the eye, on
            // the source's side.
            assert!(
                camera.towards.dot(source.normalize()) > 0.9,
                "{:?}",
                camera.towards
            );
            assert!((camera.right.cross(camera.up) - camera.towards).length() < 1e-9);
        }
    }
}
