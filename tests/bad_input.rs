//! The library's answers to bad input: typed errors that name the problem and the place.

mod common;

use geotracks::mesh::{MeshError, TriMesh};
use geotracks::{
    Density, Error, Euclidean, FacePoint, Metric, MetricError, Options, Solver, Tensor,
};

fn square() -> TriMesh {
    TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap()
}

#[test]
fn nan_coordinate_names_the_vertex() {
    let e = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, f64::NAN, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap_err();
    assert!(
        matches!(e, MeshError::NonFiniteVertex { vertex: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("vertex 1"));
    let e = TriMesh::new(
        vec![[0.0, 0.0, f64::INFINITY], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap_err();
    assert!(
        matches!(e, MeshError::NonFiniteVertex { vertex: 0, .. }),
        "{e}"
    );
}

#[test]
fn index_out_of_range_names_the_face() {
    let e = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2], [0, 2, 7]],
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            MeshError::IndexOutOfRange {
                face: 1,
                vertex: 7,
                vertex_count: 3
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("face 1") && e.to_string().contains("vertex 7"));
}

#[test]
fn degenerate_faces_are_dropped_and_counted() {
    let mesh = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
        ],
        // A good face, a repeated vertex, a zero-area (collinear) face.
        vec![[0, 1, 2], [0, 0, 2], [0, 1, 3]],
    )
    .unwrap();
    assert_eq!(mesh.report().faces, 1);
    assert_eq!(mesh.report().degenerate_faces, 2);
    let dropped = mesh.dropped_faces();
    assert_eq!(
        (dropped[0].input_index, dropped[0].repeated_vertex),
        (1, true)
    );
    assert_eq!(
        (dropped[1].input_index, dropped[1].repeated_vertex),
        (2, false)
    );
    assert_eq!(mesh.input_face(0), 0);
}

#[test]
fn no_usable_face() {
    let e = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            MeshError::NoUsableFace {
                faces: 1,
                degenerate: 1
            }
        ),
        "{e}"
    );
    let e = TriMesh::new(vec![[0.0; 3]], vec![]).unwrap_err();
    assert!(matches!(e, MeshError::NoUsableFace { faces: 0, .. }), "{e}");
}

#[test]
fn sources_and_k_are_checked() {
    let mesh = square();
    let e = Solver::new(&mesh, &Euclidean, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[] as &[u32]))
        .unwrap_err();
    assert!(matches!(e, Error::NoSource), "{e}");
    let e = Solver::new(&mesh, &Euclidean, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[0, 4]))
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::SourceOutOfRange {
                vertex: 4,
                vertex_count: 4
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("source vertex 4"));
    for k in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = Solver::new(&mesh, &Euclidean, &Options::DEFAULT.with_k(k))
            .and_then(|solver| solver.field(&[0]))
            .unwrap_err();
        assert!(matches!(e, Error::InvalidK { .. }), "{e}");
    }
    let e = Solver::new(&mesh, &Euclidean, &Options::DEFAULT.with_fixed_count(0))
        .and_then(|solver| solver.field(&[0]))
        .unwrap_err();
    assert!(matches!(e, Error::InvalidK { .. }), "{e}");
}

#[test]
fn density_must_be_finite_and_positive() {
    let mesh = square();
    for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
        let e = Density::new(&mesh, vec![1.0, 1.0, bad, 1.0]).unwrap_err();
        assert!(
            matches!(e, MetricError::InvalidDensity { vertex: 2, .. }),
            "{e}"
        );
        assert!(e.to_string().contains("vertex 2"));
    }
    let e = Density::new(&mesh, vec![1.0; 3]).unwrap_err();
    assert!(
        matches!(
            e,
            MetricError::CountMismatch {
                expected: 4,
                found: 3,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn tensor_must_be_spd_in_the_face_plane() {
    let mesh = square();
    // Indefinite.
    let e = Tensor::from_world(
        &mesh,
        &[
            [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
            [1.0, 3.0, 0.0, 1.0, 0.0, 1.0],
        ],
    )
    .unwrap_err();
    assert!(
        matches!(e, MetricError::NotPositiveDefinite { face: 1, .. }),
        "{e}"
    );
    // Positive only along z, which the faces (z = 0) do not see.
    let e = Tensor::uniform_world(&mesh, [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]).unwrap_err();
    assert!(
        matches!(e, MetricError::NotPositiveDefinite { face: 0, .. }),
        "{e}"
    );
    let e = Tensor::uniform_world(&mesh, [f64::NAN, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap_err();
    assert!(matches!(e, MetricError::NotFinite { face: 0 }), "{e}");
    let e = Tensor::from_world(&mesh, &[[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]]).unwrap_err();
    assert!(
        matches!(
            e,
            MetricError::CountMismatch {
                expected: 2,
                found: 1,
                ..
            }
        ),
        "{e}"
    );
    let e = Tensor::from_principal(&mesh, &[(1.0, 2.0, [0.0, 0.0, 1.0]); 2]).unwrap_err();
    assert!(
        matches!(e, MetricError::DegenerateDirection { face: 0 }),
        "{e}"
    );
    let e = Tensor::from_principal(&mesh, &[(1.0, 0.0, [1.0, 0.0, 0.0]); 2]).unwrap_err();
    assert!(matches!(e, MetricError::NotPositiveDefinite { .. }), "{e}");
}

/// A broken custom metric: NaN on one face.
struct Broken;

impl Metric for Broken {
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        if face == 1 {
            f64::NAN
        } else {
            a.distance(b)
        }
    }
    fn name(&self) -> &str {
        "broken"
    }
}

#[test]
fn a_metric_that_returns_nan_is_reported() {
    let e = Solver::new(square(), &Broken, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[0]))
        .unwrap_err();
    assert!(matches!(e, Error::InvalidCost { face: 1, .. }), "{e}");
    assert!(e.to_string().contains("broken"));
}

/// Numbers in messages are never hundreds of digits: `1e300` printed as 301.
#[test]
fn huge_numbers_in_messages_print_in_exponent_notation() {
    let mesh = square();
    let err = Density::new(&mesh, vec![-1e300; mesh.vertex_count()]).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("-1e300"), "{message}");
    assert!(message.len() < 100, "{message}");
    let point: geotracks::SurfacePoint = "e:0:1e300".parse().unwrap();
    let message = point.validated(&mesh).unwrap_err().to_string();
    assert!(message.contains("1e300"), "{message}");
    assert!(message.len() < 200, "{message}");
}
