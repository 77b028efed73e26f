//! Pictures of curve skeletons over their medial axis.

use super::raster::{Camera, Canvas};
use super::{check_size, colour_bar, viridis, Picture, PictureOptions, BAR_WIDTH, SUPERSAMPLE};
use crate::RenderError;
use geotracks::mesh::io::MedialAxis;
use geotracks::skeleton::Skeleton;
use glam::DVec3;

/// The axis's sheets: pale, so the skeleton stands out, and a little transparent.
const SHEET: [f64; 3] = [200.0, 207.0, 220.0];
/// How much of the sheets' colour is white (how pale they are).
const PALE: f64 = 0.35;
/// How much of a skeleton curve shows through a sheet in front of it.
const THROUGH: f64 = 0.45;
/// The axis's free edges (curves without a sheet).
const WIRE: [f64; 3] = [120.0, 125.0, 135.0];
/// The skeleton where it has no radius.
const CURVE: [f64; 3] = [200.0, 30.0, 40.0];
/// Branch tips and junctions.
const NODE: [f64; 3] = [25.0, 25.0, 25.0];

/// Draws `skeleton` over the medial axis it was made of: the sheets pale and shaded,
/// the axis's free edges as thin grey lines, the skeleton as thick curves coloured by
/// the medial radius at each point (viridis, from 0 to the largest radius, with a
/// colour bar; red where a point carries no radius), drawn through the sheets in front
/// of them as if these were semi-transparent, with dark dots at tips and junctions.
/// The camera is fitted to the whole axis; [`View::Auto`](super::View::Auto) looks
/// onto the sheets (for an axis of curves only, across its thinnest spread).
///
/// ```
/// use geotracks::mesh::io::read_medial_axis_bytes;
/// use geotracks_render::{render_skeleton, PictureOptions};
/// use geotracks::skeleton::{medial_axis_skeleton, Burn, Pruning};
/// use geotracks::Options;
/// // Two sheets sharing an edge, each with two triangles.
/// let text = "6 2 4\n\
///     v 0 0 0 0.1\nv 1 0 0 0.1\nv 0 1 0 0.3\nv 1 1 0 0.3\nv 0 2 0.5 0.1\nv 1 2 0.5 0.1\n\
///     e 0 1\ne 2 3\n\
///     f 0 1 3\nf 0 3 2\nf 2 3 5\nf 2 5 4\n";
/// let axis = read_medial_axis_bytes("two_sheets.ma", text.as_bytes())?;
/// let (skeleton, _) = medial_axis_skeleton(&axis, Burn::Boundary, &Options::DEFAULT, Pruning::NONE)?;
/// let picture = render_skeleton(&axis, &skeleton, &PictureOptions::DEFAULT)?;
/// assert_eq!((picture.width, picture.height), (1024, 768));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`RenderError::InvalidPictureOption`] for a size outside 64–8192 pixels.
pub fn render_skeleton(
    axis: &MedialAxis,
    skeleton: &Skeleton,
    options: &PictureOptions,
) -> Result<Picture, RenderError> {
    check_size(options)?;
    let positions: Vec<DVec3> = axis.positions.iter().map(|&p| p.into()).collect();
    let camera = Camera::fit_points(&positions, axis.surface.as_ref(), options, None, BAR_WIDTH);
    let mut canvas = Canvas::new(options.width * SUPERSAMPLE, options.height * SUPERSAMPLE);
    if let Some(mesh) = &axis.surface {
        for f in 0..mesh.face_count() as u32 {
            let p = mesh.face_vertices(f).map(|v| mesh.position(v));
            let shade = camera.shade(p, 0.55);
            let colour = SHEET.map(|c| PALE * 255.0 + (1.0 - PALE) * c * shade);
            canvas.triangle(&camera, p, |_| colour);
        }
    }
    let ss = SUPERSAMPLE as f64;
    for &[a, b] in &axis.free_edges {
        canvas.segment(
            &camera,
            positions[a as usize],
            positions[b as usize],
            0.6 * ss,
            WIRE,
        );
    }
    let max_radius = skeleton
        .points
        .iter()
        .filter_map(|p| p.radius)
        .filter(|r| r.is_finite())
        .fold(0.0, f64::max);
    let colour_of = |i: u32| match skeleton.points[i as usize].radius {
        Some(r) if r.is_finite() => viridis(if max_radius > 0.0 {
            r / max_radius
        } else {
            0.0
        }),
        _ => CURVE,
    };
    let at = |i: u32| DVec3::from(skeleton.points[i as usize].position);
    for &[a, b] in &skeleton.edges {
        // Each half in its end's colour: radii change along a curve.
        let middle = (at(a) + at(b)) / 2.0;
        for (end, c) in [(at(a), colour_of(a)), (at(b), colour_of(b))] {
            canvas.line(&camera, end, middle, 2.2 * ss, c, THROUGH);
        }
    }
    for (i, &d) in skeleton.degrees().iter().enumerate() {
        if d != 2 {
            canvas.disc(&camera, at(i as u32), 3.5 * ss, NODE);
        }
    }
    let mut picture = canvas.downsample(SUPERSAMPLE);
    colour_bar(&mut picture, max_radius);
    Ok(picture)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::View;
    use geotracks::mesh::io::read_medial_axis_bytes;

    /// Two unit squares, at z = 0 and z = −1, and a skeleton of two straight curves:
    /// one on the front square, along y = 0.3, and one on the back square, along
    /// y = 0.7, each with radius `r` (front 1, back 0.5).
    fn scene() -> (MedialAxis, Skeleton) {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, -1.0],
            [1.0, 1.0, -1.0],
            [0.0, 1.0, -1.0],
        ];
        // (The core's types are built through its public API: the `.ma` reader and
        // the skeleton of curves.)
        let mut text = String::from("8 0 4\n");
        for p in &positions {
            text += &format!("v {} {} {} 0.5\n", p[0], p[1], p[2]);
        }
        text += "f 0 1 2\nf 0 2 3\nf 4 5 6\nf 4 6 7\n";
        let axis = read_medial_axis_bytes("scene.ma", text.as_bytes()).unwrap();
        assert!(axis.surface.is_some() && axis.positions == positions);
        let curves = [
            [0.1, 0.3, 0.0],
            [0.9, 0.3, 0.0],
            [0.1, 0.7, -1.0],
            [0.9, 0.7, -1.0],
        ];
        let radii = [1.0, 1.0, 0.5, 0.5];
        let skeleton = Skeleton::from_curves(&curves, &[[0, 1], [2, 3]], Some(&radii))
            .with_radii(None, &radii);
        assert_eq!(skeleton.points.len(), 4);
        (axis, skeleton)
    }

    fn pixel(picture: &Picture, camera: &Camera, p: DVec3) -> [f64; 3] {
        let (x, y, _) = camera.project(p);
        let (x, y) = (
            x as usize / SUPERSAMPLE as usize,
            y as usize / SUPERSAMPLE as usize,
        );
        let i = (y * picture.width as usize + x) * 4;
        std::array::from_fn(|k| picture.rgba[i + k] as f64)
    }

    #[test]
    fn curves_in_front_are_drawn_and_curves_behind_show_through() {
        let (axis, skeleton) = scene();
        let options = PictureOptions::DEFAULT
            .with_size(300, 200)
            .with_view(View::Front);
        let picture = render_skeleton(&axis, &skeleton, &options).unwrap();
        let positions: Vec<DVec3> = axis.positions.iter().map(|&p| p.into()).collect();
        let camera =
            Camera::fit_points(&positions, axis.surface.as_ref(), &options, None, BAR_WIDTH);
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= 2.0);
        // The front curve, at the largest radius: the top of viridis.
        let front = pixel(&picture, &camera, DVec3::new(0.5, 0.3, 0.0));
        assert!(close(front, viridis(1.0)), "{front:?}");
        // The back curve: half way up the scale, mixed with the sheet in front of it.
        let sheet = pixel(&picture, &camera, DVec3::new(0.5, 0.5, 0.0));
        let behind = pixel(&picture, &camera, DVec3::new(0.5, 0.7, -1.0));
        let expected: [f64; 3] =
            std::array::from_fn(|k| sheet[k] + THROUGH * (viridis(0.5)[k] - sheet[k]));
        assert!(close(behind, expected), "{behind:?}, expected {expected:?}");
        assert!(!close(behind, sheet) && !close(behind, viridis(0.5)));
        // Tips as dark dots.
        assert!(close(
            pixel(&picture, &camera, DVec3::new(0.1, 0.3, 0.0)),
            NODE
        ));
    }

    #[test]
    fn an_axis_of_curves_only_is_framed_and_drawn() {
        let positions = vec![[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [4.0, 3.0, 0.0]];
        let text = "3 2 0\nv 0 0 0 0.1\nv 4 0 0 0.2\nv 4 3 0 0.1\ne 0 1\ne 1 2\n";
        let axis = read_medial_axis_bytes("curves.ma", text.as_bytes()).unwrap();
        assert!(axis.surface.is_none() && axis.positions == positions);
        assert_eq!(axis.free_edges, vec![[0, 1], [1, 2]]);
        let skeleton = Skeleton::from_curves(&positions, &axis.free_edges, Some(&axis.radii))
            .with_radii(None, &axis.radii);
        let options = PictureOptions::DEFAULT.with_size(320, 240);
        let picture = render_skeleton(&axis, &skeleton, &options).unwrap();
        let points: Vec<DVec3> = positions.iter().map(|&p| p.into()).collect();
        let camera = Camera::fit_points(&points, None, &options, None, BAR_WIDTH);
        for p in [DVec3::new(2.0, 0.0, 0.0), DVec3::new(4.0, 1.5, 0.0)] {
            let (x, y, _) = camera.project(p);
            let inside = |v: f64, side: u32| v >= 0.0 && v < (side * SUPERSAMPLE) as f64;
            assert!(
                inside(x, 320 - BAR_WIDTH) && inside(y, 240),
                "{p} at {x}, {y}"
            );
            let c = pixel(&picture, &camera, p);
            assert!(c.iter().any(|&v| v < 200.0), "{p} not drawn: {c:?}");
        }
    }

    #[test]
    fn a_bad_size_is_refused() {
        let (axis, skeleton) = scene();
        let options = PictureOptions::DEFAULT.with_size(10, 200);
        assert!(matches!(
            render_skeleton(&axis, &skeleton, &options),
            Err(RenderError::InvalidPictureOption {
                option: "width",
                ..
            })
        ));
    }
}
