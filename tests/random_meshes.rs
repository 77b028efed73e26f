//! Property tests over random meshes, including degenerate and non-manifold ones.

mod common;

use common::{random_mesh, Rng, DIJKSTRA, GRAPH};
use geotracks::{Euclidean, Solver, Tensor};
use proptest::prelude::*;

// These tests are about the Steiner graph itself (the tracks engine is checked
// against it in tracks_oracle.rs).

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn graph_distances_are_sane_and_symmetric(seed in any::<u64>(), n in 2usize..7, k in 1u32..6, pick in any::<(u32, u32)>()) {
        let mesh = random_mesh(seed, n).unwrap();
        let report = mesh.report();
        prop_assert_eq!(report.degenerate_faces, 2);
        prop_assert!(report.max_edge_valence >= 3);
        let (labels, _) = mesh.vertex_components();
        let a = pick.0 % mesh.vertex_count() as u32;
        let b = pick.1 % mesh.vertex_count() as u32;
        let options = GRAPH.with_k(k as f64);
        let from_a = Solver::new(&mesh, &Euclidean, &options).and_then(|solver| solver.field(&[a])).unwrap();
        let from_b = Solver::new(&mesh, &Euclidean, &options).and_then(|solver| solver.field(&[b])).unwrap();
        for (v, &d) in from_a.vertex_distances().iter().enumerate() {
            if labels[v] == labels[a as usize] {
                prop_assert!(d.is_finite() && d >= 0.0, "vertex {} distance {}", v, d);
            } else {
                prop_assert!(d.is_infinite());
            }
        }
        prop_assert_eq!(from_a.distance(a), 0.0);
        let (ab, ba) = (from_a.distance(b), from_b.distance(a));
        if ab.is_finite() || ba.is_finite() {
            prop_assert!((ab - ba).abs() <= 1e-9 * ab.max(ba), "{} vs {}", ab, ba);
        }
        // Dijkstra on edges is a path in the graph too: never shorter than the graph.
        let dijkstra = Solver::new(&mesh, &Euclidean, &DIJKSTRA.with_k(1.0)).and_then(|solver| solver.field(&[a])).unwrap();
        for (g, d) in from_a.vertex_distances().iter().zip(dijkstra.vertex_distances()) {
            prop_assert!(*g <= *d + 1e-12 * d.abs().min(1e300));
        }
    }

    #[test]
    fn random_tensors_give_symmetric_finite_distances(seed in any::<u64>(), pick in any::<(u32, u32)>()) {
        let mesh = random_mesh(seed, 4).unwrap();
        let mut rng = Rng(seed.wrapping_mul(31) | 1);
        let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
            .map(|_| (0.2 + 3.0 * rng.next(), 0.2 + 3.0 * rng.next(), [rng.next() + 0.1, rng.next(), rng.next()]))
            .collect();
        let tensor = match Tensor::from_principal(&mesh, &principal) {
            Ok(t) => t,
            Err(_) => return Ok(()), // a direction normal to its face: rejected, fine
        };
        let a = pick.0 % mesh.vertex_count() as u32;
        let b = pick.1 % mesh.vertex_count() as u32;
        let from_a = Solver::new(&mesh, &tensor, &GRAPH.with_k(3.0)).and_then(|solver| solver.field(&[a])).unwrap();
        let from_b = Solver::new(&mesh, &tensor, &GRAPH.with_k(3.0)).and_then(|solver| solver.field(&[b])).unwrap();
        let (ab, ba) = (from_a.distance(b), from_b.distance(a));
        if ab.is_finite() || ba.is_finite() {
            prop_assert!((ab - ba).abs() <= 1e-9 * ab.max(ba), "{} vs {}", ab, ba);
        }
        prop_assert!(from_a.vertex_distances().iter().all(|d| *d >= 0.0));
    }
}
