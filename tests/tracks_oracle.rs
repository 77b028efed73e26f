//! The main test of the engine: the track-pruned propagation returns the naive Steiner
//! graph's distances, at every node, on random meshes of every kind.

mod common;

use common::{random_book, random_mesh, sphere, Rng};
use geotracks::mesh::TriMesh;
use geotracks::{Density, Euclidean, Method, Metric, Options, Solver, Tensor};
use proptest::prelude::*;

/// Largest relative difference between the two engines over all nodes.
fn deviation<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    sources: &[u32],
    options: Options,
) -> (f64, f64) {
    let graph = Solver::new(mesh, metric, &options.with_method(Method::Graph))
        .and_then(|solver| solver.field(sources))
        .unwrap();
    let tracks = Solver::new(mesh, metric, &options.with_method(Method::Tracks))
        .and_then(|solver| solver.field(sources))
        .unwrap();
    assert_eq!(tracks.stats().method, Method::Tracks);
    let (mut max, mut sum) = (0.0f64, 0.0);
    for (g, t) in graph.node_distances().iter().zip(tracks.node_distances()) {
        let r = if g.is_finite() {
            (g - t).abs() / g.max(f64::MIN_POSITIVE)
        } else if t.is_finite() {
            f64::INFINITY
        } else {
            0.0
        };
        max = max.max(r);
        sum += r;
    }
    (max, sum / graph.node_distances().len() as f64)
}

fn random_tensor(mesh: &TriMesh, seed: u64, anisotropy: f64) -> Option<Tensor> {
    let mut rng = Rng(seed | 1);
    let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
        .map(|_| {
            (
                0.1 + anisotropy * rng.next(),
                0.1 + rng.next(),
                [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5],
            )
        })
        .collect();
    Tensor::from_principal(mesh, &principal).ok()
}

fn options(k: u32, fixed: bool) -> Options {
    if fixed {
        Options::DEFAULT.with_fixed_count(k)
    } else {
        Options::DEFAULT.with_k(k as f64)
    }
}

fn pick_sources(mesh: &TriMesh, picks: &[u32]) -> Vec<u32> {
    picks
        .iter()
        .map(|p| p % mesh.vertex_count() as u32)
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn equals_graph_on_perturbed_grids(seed in any::<u64>(), n in 2usize..9, k in 1u32..9, fixed in any::<bool>(), picks in prop::collection::vec(any::<u32>(), 1..4)) {
        let mesh = random_mesh(seed, n).unwrap();
        let (max, _) = deviation(&mesh, &Euclidean, &pick_sources(&mesh, &picks), options(k, fixed));
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }

    #[test]
    fn equals_graph_on_spheres(seed in any::<u64>(), levels in 0usize..3, jitter in 0.0f64..0.6, k in 1u32..9, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = sphere(levels, jitter, seed);
        let (max, _) = deviation(&mesh, &Euclidean, &pick_sources(&mesh, &picks), options(k, false));
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }

    #[test]
    fn equals_graph_on_books_and_fans(seed in any::<u64>(), pages in 3usize..7, n in 1usize..5, k in 1u32..8, fixed in any::<bool>(), picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = random_book(seed, pages, n);
        prop_assert!(mesh.report().max_edge_valence >= 3);
        let (max, _) = deviation(&mesh, &Euclidean, &pick_sources(&mesh, &picks), options(k, fixed));
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }

    #[test]
    fn equals_graph_under_random_tensors(seed in any::<u64>(), kind in 0usize..3, anisotropy in 1.0f64..30.0, k in 1u32..7, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = match kind {
            0 => random_mesh(seed, 5).unwrap(),
            1 => sphere(1, 0.3, seed),
            _ => random_book(seed, 4, 3),
        };
        if let Some(tensor) = random_tensor(&mesh, seed.rotate_left(7), anisotropy) {
            let (max, _) = deviation(&mesh, &tensor, &pick_sources(&mesh, &picks), options(k, false));
            prop_assert!(max <= 1e-9, "relative deviation {}", max);
        }
    }
}

/// Worst (mean, max) relative deviation from the graph over random meshes with rough
/// random densities (neighbouring values up to 26× apart), at a pruning tolerance.
fn density_deviation(tolerance: f64) -> (f64, f64) {
    let mut worst_mean = 0.0f64;
    let mut worst_max = 0.0f64;
    for seed in 1..40u64 {
        let mesh = match seed % 3 {
            0 => random_mesh(seed, 7).unwrap(),
            1 => sphere(2, 0.3, seed),
            _ => random_book(seed, 4, 4),
        };
        let mut rng = Rng(seed * 977 + 1);
        let rho: Vec<f64> = (0..mesh.vertex_count())
            .map(|_| 0.2 + 5.0 * rng.next())
            .collect();
        let density = Density::new(&mesh, rho)
            .unwrap()
            .with_pruning_tolerance(tolerance);
        let (max, mean) = deviation(
            &mesh,
            &density,
            &[(seed as u32 * 13) % mesh.vertex_count() as u32],
            Options::DEFAULT,
        );
        worst_mean = worst_mean.max(mean);
        worst_max = worst_max.max(max);
    }
    println!("density, tolerance {tolerance}: worst mean relative deviation {worst_mean:e}, worst max {worst_max:e}");
    (worst_mean, worst_max)
}

/// Density is not a norm, but its pruning keeps the margin of its triangle slack, so
/// by default the tracks engine returns the graph's distances exactly. A positive
/// pruning tolerance treats nearly constant faces as norms (the terrain's slope cost
/// uses 0.2): its deviation from the graph is measured here (the numbers
/// `Density::with_pruning_tolerance` quotes:
/// `cargo test --release --test tracks_oracle density -- --nocapture`).
#[test]
fn density_deviation_is_zero_by_default_and_tiny_with_a_tolerance() {
    let (mean, max) = density_deviation(Density::DEFAULT_PRUNING_TOLERANCE);
    assert!(max <= 1e-9, "{max}");
    assert!(mean <= 1e-9, "{mean}");
    let (mean, max) = density_deviation(0.2);
    assert!(mean <= 1e-6, "{mean}");
    assert!(max <= 1e-6, "{max}");
    // Pruning on every face with a ratio up to 2 deviates, but little.
    let (mean, _) = density_deviation(1.0);
    assert!(mean <= 1e-5, "{mean}");
}

#[test]
fn equals_graph_on_spot() {
    let mesh =
        geotracks::mesh::io::read_mesh(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj"))
            .unwrap();
    for k in [3.0, 5.0] {
        let (max, _) = deviation(&mesh, &Euclidean, &[0, 1500], Options::DEFAULT.with_k(k));
        assert!(max <= 1e-9, "k = {k}: {max}");
    }
}
