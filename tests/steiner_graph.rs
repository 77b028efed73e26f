//! The Steiner graph against analytic distances: flat grids, a non-manifold book,
//! constant densities and constant tensors.

use approx::{abs_diff_eq, assert_abs_diff_eq};
mod common;

use common::{book, grid, relative_error, DIJKSTRA, GRAPH};
use geotracks::{Density, Euclidean, Metric, Solver, Tensor};

// These tests are about the Steiner graph itself (the tracks engine is checked
// against it in tracks_oracle.rs).

fn euclid_on_grid(mesh: &geotracks::mesh::TriMesh, s: u32) -> Vec<f64> {
    let p = mesh.position(s);
    mesh.positions().iter().map(|q| q.distance(p)).collect()
}

#[test]
fn flat_grid_error_falls_with_k() {
    let mesh = grid(16, 1.0);
    let source = 8 * 17 + 3;
    let exact = euclid_on_grid(&mesh, source);
    let errors: Vec<(f64, f64)> = [1.0, 3.0, 8.0]
        .iter()
        .map(|&k| {
            let f = Solver::new(&mesh, &Euclidean, &GRAPH.with_k(k))
                .and_then(|solver| solver.field(&[source]))
                .unwrap();
            relative_error(f.vertex_distances(), &exact)
        })
        .collect();
    println!("{errors:?}");
    assert!(
        errors[0].0 > errors[1].0 && errors[1].0 > errors[2].0,
        "{errors:?}"
    );
    assert!(errors[2].0 < 2e-3, "{errors:?}");
    // Never shorter than the straight line (a graph path is a path on the surface).
    let f = Solver::new(&mesh, &Euclidean, &GRAPH)
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    for (d, e) in f.vertex_distances().iter().zip(&exact) {
        assert!(*d >= e - 1e-12);
    }
}

#[test]
fn dijkstra_on_edges_is_much_worse_than_the_graph() {
    let mesh = grid(16, 1.0);
    let exact = euclid_on_grid(&mesh, 0);
    let dijkstra = Solver::new(&mesh, &Euclidean, &DIJKSTRA)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let graph = Solver::new(&mesh, &Euclidean, &GRAPH)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let (dm, _) = relative_error(dijkstra.vertex_distances(), &exact);
    let (gm, _) = relative_error(graph.vertex_distances(), &exact);
    assert!(dm > 10.0 * gm, "dijkstra {dm}, graph {gm}");
    assert_eq!(dijkstra.stats().steiner_points, 0);
    // Along an axis Dijkstra is exact.
    assert_abs_diff_eq!(dijkstra.distance(16), 1.0, epsilon = 1e-12);
}

#[test]
fn book_pages_unfold() {
    let (mesh, id) = book(3, 1.0, 1.0, 8);
    assert_eq!(mesh.report().non_manifold_edges, 8);
    assert_eq!(mesh.report().max_edge_valence, 3);
    let source = id(0, 4, 2); // r = 0.5, z = 0.25 on page 0
    let f = Solver::new(&mesh, &Euclidean, &GRAPH.with_k(8.0))
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    let mut worst = 0.0f64;
    for page in 1..3 {
        for j in 0..=8 {
            for i in 1..=8 {
                let (r, z) = (i as f64 / 8.0, j as f64 / 8.0);
                let unfolded = ((0.5 + r).powi(2) + (0.25 - z).powi(2)).sqrt();
                let d = f.distance(id(page, i, j));
                assert!(
                    d >= unfolded - 1e-12,
                    "page {page} ({i},{j}): {d} < {unfolded}"
                );
                worst = worst.max((d - unfolded) / unfolded);
            }
        }
    }
    println!("book: worst relative excess {worst}");
    assert!(worst < 5e-3, "{worst}");
    // The two other pages are mirror images of each other.
    for j in 0..=8 {
        for i in 1..=8 {
            let (a, b) = (f.distance(id(1, i, j)), f.distance(id(2, i, j)));
            assert!(abs_diff_eq!(a, b, epsilon = 1e-9 * a), "{a} vs {b}");
        }
    }
}

#[test]
fn constant_density_scales_distances() {
    let (mesh, _) = book(4, 1.0, 2.0, 5);
    let base = Solver::new(&mesh, &Euclidean, &GRAPH)
        .and_then(|solver| solver.field(&[7]))
        .unwrap();
    for c in [0.25, 3.0] {
        let density = Density::constant(&mesh, c).unwrap();
        let f = Solver::new(&mesh, &density, &GRAPH)
            .and_then(|solver| solver.field(&[7]))
            .unwrap();
        for (a, b) in f.vertex_distances().iter().zip(base.vertex_distances()) {
            assert!(
                abs_diff_eq!(*a, c * b, epsilon = 1e-12 * (1.0 + c * b)),
                "{a} vs {c} × {b}"
            );
        }
    }
}

#[test]
fn constant_tensor_approaches_the_analytic_norm() {
    let mesh = grid(12, 1.0);
    // World-space SPD tensor (xx xy xz yy yz zz); z does not matter on a flat grid.
    let m = [4.0, 1.0, 0.0, 2.0, 0.0, 1.0];
    let tensor = Tensor::uniform_world(&mesh, m).unwrap();
    assert!(tensor.is_face_norm());
    let source = 6 * 13 + 6;
    let s = mesh.position(source);
    let exact: Vec<f64> = mesh
        .positions()
        .iter()
        .map(|p| {
            let (x, y) = (p.x - s.x, p.y - s.y);
            (m[0] * x * x + 2.0 * m[1] * x * y + m[3] * y * y).sqrt()
        })
        .collect();
    let errors: Vec<f64> = [1.0, 3.0, 8.0]
        .iter()
        .map(|&k| {
            let f = Solver::new(&mesh, &tensor, &GRAPH.with_k(k))
                .and_then(|solver| solver.field(&[source]))
                .unwrap();
            relative_error(f.vertex_distances(), &exact).0
        })
        .collect();
    println!("tensor errors {errors:?}");
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    assert!(errors[2] < 5e-3, "{errors:?}");
}
