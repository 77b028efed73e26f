//! Pictures (`render_field`): non-manifold meshes and medial axes render, the
//! source is marked where it is, degenerate input draws without panicking, bad options
//! are refused.

#[path = "../../tests/common/mod.rs"]
mod common;

use geotracks::mesh::TriMesh;
use geotracks::{Euclidean, Options, Solver};
use geotracks_render::{render_field, Picture, PictureOptions, RenderError, View};

/// Pixels that are not the white background.
fn drawn(p: &Picture) -> usize {
    p.rgba
        .chunks(4)
        .filter(|c| c[..3] != [255, 255, 255])
        .count()
}

fn picture(mesh: &TriMesh, source: u32, options: &PictureOptions) -> Picture {
    let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver.field(&[source]).unwrap();
    let query = &field;
    let levels = geotracks::trace::spread_levels(query.max_reached_distance(), 5);
    let lines: Vec<Vec<_>> = query
        .isolines(&levels, &Default::default())
        .unwrap()
        .iter()
        .map(|l| l.points.iter().map(|p| p.position(mesh)).collect())
        .collect();
    render_field(
        mesh,
        field.vertex_distances(),
        &lines,
        &[mesh.position(source)],
        options,
    )
    .unwrap()
}

#[test]
fn a_book_and_a_medial_axis_render() {
    let (book, _) = common::book(3, 1.0, 1.0, 6);
    let axis = geotracks::mesh::io::read_mesh("../tests/data/ma/sheet_fins.ma").unwrap();
    for (name, mesh) in [("book", &book), ("sheet_fins.ma", &axis)] {
        for view in [
            View::Auto,
            View::Top,
            View::Orbit {
                azimuth: 40.0,
                elevation: 30.0,
            },
        ] {
            let p = picture(
                mesh,
                0,
                &PictureOptions::DEFAULT.with_size(320, 240).with_view(view),
            );
            assert_eq!(p.rgba.len(), 320 * 240 * 4);
            // The mesh covers a good part of the picture (seen edge-on, the pages of
            // the book would be three lines: under 1 %).
            assert!(
                drawn(&p) > 170 * 240 / 10,
                "{name}, {view:?}: {} pixels drawn",
                drawn(&p)
            );
        }
    }
}

#[test]
fn the_source_is_marked_red() {
    let mesh = common::grid(6, 1.0);
    let p = picture(
        &mesh,
        0,
        &PictureOptions::DEFAULT
            .with_size(200, 200)
            .with_view(View::Front),
    );
    let red = p
        .rgba
        .chunks(4)
        .filter(|c| c[0] > 180 && c[1] < 80 && c[2] < 80)
        .count();
    assert!(red > 20, "{red} red pixels");
}

#[test]
fn degenerate_input_draws_without_panicking() {
    // One triangle, values all unreached; a mesh seen edge-on; all values 0.
    let one = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let options = PictureOptions::DEFAULT.with_size(64, 64);
    for values in [[f64::INFINITY; 3], [0.0; 3], [0.0, 1.0, f64::INFINITY]] {
        for view in [View::Auto, View::Left, View::Top] {
            let p = render_field(&one, &values, &[], &[], &options.with_view(view)).unwrap();
            assert_eq!((p.width, p.height), (64, 64));
        }
    }
}

#[test]
fn bad_sizes_and_value_counts_are_refused() {
    let mesh = common::grid(2, 1.0);
    let values = vec![0.0; mesh.vertex_count()];
    for (w, h) in [(10, 100), (100, 9000)] {
        let err = render_field(
            &mesh,
            &values,
            &[],
            &[],
            &PictureOptions::DEFAULT.with_size(w, h),
        );
        assert!(
            matches!(err, Err(RenderError::InvalidPictureOption { .. })),
            "{w}x{h}"
        );
    }
    let err = render_field(&mesh, &values[1..], &[], &[], &PictureOptions::DEFAULT);
    assert!(matches!(
        err,
        Err(RenderError::InvalidPictureOption {
            option: "vertex values",
            ..
        })
    ));
}
