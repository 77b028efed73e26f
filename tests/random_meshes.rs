//! Property tests over random meshes, including degenerate and non-manifold ones.

use geotracks::mesh::{Topology, TriMesh};
use geotracks::{distance_field, Euclidean, Method, Options, Tensor};
use proptest::prelude::*;

/// A small deterministic generator, so a failing case is reproducible from its seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        ((self.next() * n as f64) as usize).min(n - 1)
    }
}

/// A jittered grid with holes, extra "fin" faces on existing edges (non-manifold),
/// degenerate faces (repeated vertex, collinear), an unreferenced vertex, and sometimes
/// a second disconnected component.
fn random_mesh(seed: u64, n: usize) -> Result<TriMesh, geotracks::mesh::MeshError> {
    let mut rng = Rng(seed | 1);
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push([
                i as f64 + 0.35 * (rng.next() - 0.5),
                j as f64 + 0.35 * (rng.next() - 0.5),
                0.8 * rng.next(),
            ]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if rng.next() < 0.08 {
                continue; // a hole
            }
            if rng.next() < 0.5 {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            } else {
                triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    // Fins: new faces on existing edges, making them non-manifold.
    for _ in 0..rng.below(4) + 1 {
        // Two fins on one edge: it then has at least three faces.
        let t = triangles[rng.below(triangles.len())];
        let a = positions[t[0] as usize];
        for _ in 0..2 {
            let apex = positions.len() as u32;
            positions.push([
                a[0] + rng.next(),
                a[1] + rng.next(),
                a[2] + 1.0 + rng.next(),
            ]);
            triangles.push([t[0], t[1], apex]);
        }
    }
    // Degenerate faces: a repeated vertex, and three collinear vertices.
    triangles.push([id(0, 0), id(0, 0), id(1, 1)]);
    let c = positions.len() as u32;
    positions.push([-5.0, 0.0, 0.0]);
    positions.push([-4.0, 0.0, 0.0]);
    positions.push([-3.0, 0.0, 0.0]);
    triangles.push([c, c + 1, c + 2]);
    // An unreferenced vertex.
    positions.push([9.0, 9.0, 9.0]);
    // Sometimes a second component.
    if rng.next() < 0.5 {
        let b = positions.len() as u32;
        positions.extend([[20.0, 0.0, 0.0], [21.0, 0.0, 0.0], [20.0, 1.0, 0.0]]);
        triangles.push([b, b + 1, b + 2]);
    }
    TriMesh::new(positions, triangles)
}

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
        let options = Options::DEFAULT.with_k(k as f64);
        let from_a = distance_field(&mesh, &Euclidean, &[a], &options).unwrap();
        let from_b = distance_field(&mesh, &Euclidean, &[b], &options).unwrap();
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
        let dijkstra = distance_field(&mesh, &Euclidean, &[a], &options.with_method(Method::Dijkstra)).unwrap();
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
        let from_a = distance_field(&mesh, &tensor, &[a], &Options::DEFAULT.with_k(3.0)).unwrap();
        let from_b = distance_field(&mesh, &tensor, &[b], &Options::DEFAULT.with_k(3.0)).unwrap();
        let (ab, ba) = (from_a.distance(b), from_b.distance(a));
        if ab.is_finite() || ba.is_finite() {
            prop_assert!((ab - ba).abs() <= 1e-9 * ab.max(ba), "{} vs {}", ab, ba);
        }
        prop_assert!(from_a.vertex_distances().iter().all(|d| *d >= 0.0));
    }
}
