//! `TensorField`, an SPD tensor per vertex interpolated across faces: constant fields
//! are the constant tensor, varying ones keep tracks = graph (the slack of the
//! triangle inequality), and a field linear in space gives its closed-form distance
//! where the geodesic is known and converges elsewhere as faces shrink.

mod common;

use common::{random_mesh, sphere, Rng};
use geotracks::{
    FacePoint, Method, Metric, Options, Solver, Source, SurfacePoint, Tensor, TensorField,
};
use proptest::prelude::*;

/// A random SPD world tensor `[xx, xy, xz, yy, yz, zz]`: `AᵀA + 0.1 I`.
fn random_world(rng: &mut Rng, spread: f64) -> [f64; 6] {
    let a: [[f64; 3]; 3] =
        std::array::from_fn(|_| std::array::from_fn(|_| spread * (rng.next() - 0.5)));
    let m = |i: usize, j: usize| (0..3).map(|k| a[k][i] * a[k][j]).sum::<f64>();
    [
        1.0 + m(0, 0),
        m(0, 1),
        m(0, 2),
        1.0 + m(1, 1),
        m(1, 2),
        1.0 + m(2, 2),
    ]
}

#[test]
fn a_constant_field_is_the_constant_tensor() {
    let mesh = sphere(2, 0.3, 5);
    let w = [2.0, 0.3, -0.2, 1.0, 0.1, 1.5];
    let field = TensorField::from_world(&mesh, &vec![w; mesh.vertex_count()]).unwrap();
    let tensor = Tensor::uniform_world(&mesh, w).unwrap();
    assert!(field.spread().iter().all(|&e| e == 0.0));
    // Segment by segment, to the last bit.
    let mut rng = Rng(3);
    for _ in 0..1000 {
        let f = rng.below(mesh.face_count()) as u32;
        let point = |rng: &mut Rng| {
            let frame = mesh.frame(f);
            let (s, t) = (rng.next(), rng.next());
            let (s, t) = if s + t > 1.0 {
                (1.0 - s, 1.0 - t)
            } else {
                (s, t)
            };
            frame.point([1.0 - s - t, s, t])
        };
        let (a, b): (FacePoint, FacePoint) = (point(&mut rng), point(&mut rng));
        assert_eq!(field.cost(f, &a, &b), tensor.cost(f, &a, &b));
    }
    // And so every distance, engine for engine: constant on each face, the field is
    // flat there and runs the wavefront engine by default, as the tensor does.
    for method in [Method::Tracks, Method::Wave] {
        let options = Options::DEFAULT.with_k(3.0).with_method(method);
        let a = Solver::new(&mesh, &field, &options)
            .and_then(|solver| solver.field(&[0]))
            .unwrap();
        let b = Solver::new(&mesh, &tensor, &options)
            .and_then(|solver| solver.field(&[0]))
            .unwrap();
        assert_eq!(a.stats().method, method);
        for (x, y) in a.node_distances().iter().zip(b.node_distances()) {
            assert!((x - y).abs() <= 1e-12 * y.max(1.0), "{method}: {x} vs {y}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    // The triangle inequality fails by at most the stated slack inside a face, so the
    // pruning with that margin keeps the Steiner graph's distances.
    #[test]
    fn tracks_equal_the_graph_under_varying_fields(seed in any::<u64>(), n in 2usize..8, k in 1u32..6, spread in 0.0f64..3.0, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = random_mesh(seed, n).unwrap();
        let mut rng = Rng(seed ^ 0x7e45 | 1);
        let per_vertex: Vec<[f64; 6]> = (0..mesh.vertex_count()).map(|_| random_world(&mut rng, spread)).collect();
        // Fins and a far component can make a vertex's restriction singular: skip.
        let Ok(field) = TensorField::from_world(&mesh, &per_vertex) else { return Ok(()) };
        let sources: Vec<u32> = picks.iter().map(|p| p % mesh.vertex_count() as u32).collect();
        let max = common::tracks_vs_graph(&mesh, &field, &sources, k as f64);
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }
}

/// An isotropic field linear in x, `M = (1 + c·x) I`, on the unit square: the line
/// along x is a geodesic and costs `∫ sqrt(1 + c x) dx`. Interpolation reproduces a
/// linear field exactly and segments cost their exact integrals, so that distance is
/// exact at any resolution; off that line, distances converge as the cells shrink.
#[test]
fn a_linear_field_gives_its_closed_form_and_converges() {
    let c = 3.0;
    let exact_along_x = |x0: f64, x1: f64| {
        (2.0 / (3.0 * c)) * ((1.0 + c * x1).powf(1.5) - (1.0 + c * x0).powf(1.5))
    };
    let mut diagonal = Vec::new();
    for n in [4usize, 8, 16, 32] {
        let mesh = common::grid(n, 1.0);
        let per_vertex: Vec<[f64; 6]> = mesh
            .positions()
            .iter()
            .map(|p| {
                let s = 1.0 + c * p.x;
                [s, 0.0, 0.0, s, 0.0, s]
            })
            .collect();
        let field = TensorField::from_world(&mesh, &per_vertex).unwrap();
        let solver = Solver::new(&mesh, &field, &Options::DEFAULT.with_k(3.0)).unwrap();
        assert_eq!(solver.method(), Method::Tracks);
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let along = solver.field(&[id(0, n / 2)]).unwrap();
        let d = along.distance(id(n, n / 2));
        let exact = exact_along_x(0.0, 1.0);
        assert!(
            (d - exact).abs() <= 1e-12 * exact,
            "n = {n}: {d} vs {exact}"
        );
        // Corner to corner: the straightened path's cost.
        let path = solver
            .shortest_path(&[Source::new(id(0, 0))], SurfacePoint::Vertex(id(n, n)))
            .unwrap()
            .0;
        diagonal.push(path.length);
    }
    let steps: Vec<f64> = diagonal.windows(2).map(|w| (w[0] - w[1]).abs()).collect();
    println!("linear field, corner to corner: {diagonal:?}, successive changes {steps:?}");
    // Converging: finer grids cost no more (their graphs hold the coarser paths'
    // shapes more closely), and the last refinement changes the cost least, by less
    // than 1e-4 of it (2.15801, 2.15732, 2.15600, 2.15592 when written).
    assert!(
        diagonal.windows(2).all(|d| d[1] <= d[0] * (1.0 + 1e-12)),
        "{diagonal:?}"
    );
    let last = steps[steps.len() - 1];
    assert!(steps.iter().all(|&s| s >= last), "{steps:?}");
    assert!(last < 1e-4 * diagonal[diagonal.len() - 1], "{steps:?}");
}

#[test]
fn bad_fields_are_refused_naming_the_vertex() {
    let mesh = common::grid(2, 1.0);
    let mut per_vertex = vec![[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]; mesh.vertex_count()];
    assert!(TensorField::from_world(&mesh, &per_vertex[1..]).is_err());
    per_vertex[4] = [1.0, 0.0, 0.0, -1.0, 0.0, 1.0];
    let e = TensorField::from_world(&mesh, &per_vertex).unwrap_err();
    assert!(e.to_string().contains("vertex 4"), "{e}");
    per_vertex[4] = [f64::NAN, 0.0, 0.0, 1.0, 0.0, 1.0];
    assert!(TensorField::from_world(&mesh, &per_vertex).is_err());
}
