//! The Spot model (CC0, Keenan Crane) against exact geodesic distances from vertex 0
//! (Kirsanov's MMP via tvb-gdist, see tests/data/spot.src0.json).

mod common;

use common::{read_reference, relative_error, DIJKSTRA, GRAPH};
use geotracks::mesh::io::read_mesh;
use geotracks::{Euclidean, Solver};

// These tests are about the Steiner graph itself (the tracks engine is checked
// against it in tracks_oracle.rs).

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

fn exact() -> Vec<f64> {
    read_reference(std::path::Path::new(&format!("{DATA}/spot.src0.f64"))).unwrap()
}

#[test]
fn steiner_graph_at_k5_is_within_0_35_percent() {
    let mesh = read_mesh(format!("{DATA}/spot.obj")).unwrap();
    let exact = exact();
    assert_eq!(exact.len(), mesh.positions().len());
    let graph = Solver::new(&mesh, &Euclidean, &GRAPH.with_k(5.0))
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let (mean, max) = relative_error(graph.vertex_distances(), &exact);
    println!(
        "graph k=5: mean {:.4} %, max {:.4} %",
        100.0 * mean,
        100.0 * max
    );
    assert!(mean <= 0.0035, "mean relative error {mean}");
    // A graph path is a path on the surface: never shorter than the exact geodesic.
    for (d, e) in graph.vertex_distances().iter().zip(&exact) {
        assert!(*d >= e * (1.0 - 1e-9), "{d} < exact {e}");
    }

    let dijkstra = Solver::new(&mesh, &Euclidean, &DIJKSTRA)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let (dmean, _) = relative_error(dijkstra.vertex_distances(), &exact);
    println!("dijkstra: mean {:.4} %", 100.0 * dmean);
    assert!(dmean > 0.02, "Dijkstra on edges mean error {dmean}");
}

#[test]
fn more_steiner_points_cost_more_tests_and_err_less() {
    let mesh = read_mesh(format!("{DATA}/spot.obj")).unwrap();
    let exact = exact();
    let runs: Vec<(u64, f64)> = [2.0, 4.0, 8.0]
        .iter()
        .map(|&k| {
            let f = Solver::new(&mesh, &Euclidean, &GRAPH.with_k(k))
                .and_then(|solver| solver.field(&[0]))
                .unwrap();
            (
                f.stats().distance_tests,
                relative_error(f.vertex_distances(), &exact).0,
            )
        })
        .collect();
    println!("{runs:?}");
    assert!(
        runs.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 > w[1].1),
        "{runs:?}"
    );
}
