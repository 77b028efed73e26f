//! The engine on small random meshes: no panic, and for the norm metrics (Euclidean,
//! Tensor) the track-pruned engine returns the Steiner graph's distances at every vertex
//! to a relative 1e-9 whenever both finish; the exact engine, where it runs (a metric
//! whose faces glue), reaches the same vertices and is never above the graph.
//!
//! Bytes → mesh: 3–10 vertices with small integer coordinates (so faces are often
//! degenerate, coplanar, folded or non-manifold), 1–16 faces with indices mod n, a
//! metric (Euclidean, a per-vertex density, a per-face SPD tensor), k from 1 to 4 (or a
//! fixed count up to 3), and a source vertex.
#![no_main]

use geotracks::mesh::TriMesh;
use geotracks::{Density, Euclidean, Method, Metric, Options, Solver, Tensor};
use libfuzzer_sys::fuzz_target;

#[path = "common/bytes.rs"]
mod bytes;
use bytes::Bytes;

/// Runs both engines; compares them when `exact` (a norm metric).
fn check<M: Metric>(mesh: &TriMesh, metric: &M, source: u32, options: Options, exact: bool) {
    let run = |method| Solver::new(mesh, metric, &options.with_method(method))?.field(source);
    let (tracks, graph) = (run(Method::Tracks), run(Method::Graph));
    let exact_run = run(Method::Exact);
    let (Ok(tracks), Ok(graph)) = (tracks, graph) else {
        return;
    };
    if let Ok(exact_field) = exact_run {
        for v in 0..mesh.positions().len() as u32 {
            let (e, g) = (exact_field.distance(v), graph.distance(v));
            assert_eq!(
                e.is_finite(),
                g.is_finite(),
                "vertex {v}: exact {e}, graph {g}"
            );
            if g.is_finite() {
                assert!(
                    e <= g + 1e-9 * g.max(1e-12),
                    "vertex {v}: exact {e} above the graph's {g}"
                );
            }
        }
    }
    if !exact {
        return;
    }
    for v in 0..mesh.positions().len() as u32 {
        let (t, g) = (tracks.distance(v), graph.distance(v));
        if t.is_infinite() || g.is_infinite() {
            assert_eq!(t, g, "vertex {v}: tracks {t}, graph {g}");
        } else {
            assert!(
                (t - g).abs() <= 1e-9 * g.max(1e-12),
                "vertex {v}: tracks {t}, graph {g}"
            );
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut bytes = Bytes(data);
    let n = 3 + (bytes.next() % 8) as u32;
    let positions: Vec<[f64; 3]> = (0..n)
        .map(|_| [0; 3].map(|_: i32| f64::from(bytes.next() as i8 % 5)))
        .collect();
    let face_count = 1 + (bytes.next() % 16) as usize;
    let triangles: Vec<[u32; 3]> = (0..face_count)
        .map(|_| [0; 3].map(|_: i32| u32::from(bytes.next()) % n))
        .collect();
    let Ok(mesh) = TriMesh::new(positions, triangles) else {
        return;
    };
    let source = u32::from(bytes.next()) % n;
    let scheme = bytes.next();
    let options = if scheme & 0x80 == 0 {
        Options::DEFAULT.with_k(f64::from(1 + scheme % 4))
    } else {
        Options::DEFAULT.with_fixed_count(u32::from(scheme % 4))
    };
    match bytes.next() % 3 {
        0 => check(&mesh, &Euclidean, source, options, true),
        1 => {
            let rho: Vec<f64> = (0..n)
                .map(|_| 0.25 + f64::from(bytes.next() % 16) / 4.0)
                .collect();
            if let Ok(density) = Density::new(&mesh, rho) {
                check(&mesh, &density, source, options, false);
            }
        }
        _ => {
            let local: Vec<[f64; 3]> = (0..mesh.triangles().len())
                .map(|_| {
                    let a = 0.25 + f64::from(bytes.next() % 16) / 4.0;
                    let c = 0.25 + f64::from(bytes.next() % 16) / 4.0;
                    let b = (f64::from(bytes.next() as i8) / 128.0) * 0.9 * (a * c).sqrt();
                    [a, b, c]
                })
                .collect();
            if let Ok(tensor) = Tensor::from_local(local) {
                check(&mesh, &tensor, source, options, true);
            }
        }
    }
});
