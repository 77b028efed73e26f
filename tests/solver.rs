//! The Solver: reusable workspaces, parallel rows, and the distance-test count that
//! must grow about linearly in k for the tracks engine.

mod common;

use geotracks::mesh::io::read_mesh;
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{Error, Euclidean, Method, Options, Solver, Source, Stop, SurfacePoint, Tensor};
use std::path::Path;

fn spot() -> TriMesh {
    read_mesh(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj")).unwrap()
}

#[test]
fn a_reused_workspace_gives_the_same_fields_as_fresh_ones() {
    let mesh = spot();
    let tensor = Tensor::uniform_world(&mesh, [2.0, 0.3, 0.1, 1.0, 0.2, 1.5]).unwrap();
    let solver = Solver::new(&mesh, &tensor, &Options::DEFAULT.with_k(4.0)).unwrap();
    let mut ws = solver.workspace();
    for source in [0, 1000, 2000, 0] {
        solver.run(&mut ws, &[source]).unwrap();
        let fresh = solver.field(&[source]).unwrap();
        assert_eq!(ws.vertex_distances(), fresh.vertex_distances());
        assert_eq!(ws.node_distances(), fresh.node_distances());
    }
}

/// A workspace is cleared by what its last run touched when that is little: local
/// runs, target stops, full runs and sources inside faces, one after another in one
/// workspace, give what fresh workspaces give, node for node and at surface points
/// (whose values read the waves), for every engine. (Debug builds also check that a
/// partial clear leaves nothing behind.)
#[test]
fn local_and_full_runs_share_a_workspace() {
    let mesh = spot();
    let (lo, hi) = mesh.positions().iter().fold(
        (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let d = (hi - lo).length();
    let inside = SurfacePoint::Face {
        face: 700,
        bary: [0.2, 0.3, 0.5],
    };
    let runs: Vec<(Vec<Source>, Stop)> = vec![
        (vec![Source::new(0)], Stop::NONE.with_max_distance(0.05 * d)),
        (vec![Source::new(1000)], Stop::NONE),
        (
            vec![Source::new(inside)],
            Stop::NONE.with_max_distance(0.1 * d),
        ),
        (
            vec![Source::new(2000)],
            Stop::NONE.with_targets(vec![SurfacePoint::Vertex(2010)]),
        ),
        (
            vec![Source::new(2000)],
            Stop::NONE.with_max_distance(0.02 * d),
        ),
        (vec![Source::new(5), Source::new(inside)], Stop::NONE),
        (vec![Source::new(5)], Stop::NONE.with_max_distance(0.0)),
    ];
    let probes: Vec<SurfacePoint> = (0..mesh.face_count() as u32)
        .step_by(97)
        .map(|face| SurfacePoint::Face {
            face,
            bary: [0.6, 0.3, 0.1],
        })
        .collect();
    for options in [Options::DEFAULT, common::TRACKS, common::GRAPH] {
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let mut ws = solver.workspace();
        for (sources, stop) in runs.iter().chain(runs.iter().rev()) {
            let fresh = solver.field(Sources::from(sources).until(stop)).unwrap();
            let reused = solver
                .run(&mut ws, Sources::from(sources).until(stop))
                .unwrap();
            assert_eq!(reused.node_distances(), fresh.node_distances(), "{stop:?}");
            for &p in &probes {
                assert_eq!(
                    reused.distance_at(p).unwrap(),
                    fresh.distance_at(p).unwrap()
                );
            }
        }
    }
}

/// Rows with targets stop once their targets are final, like `path` does: the same
/// values as full rows, for far less work. (1 source and 3 nearby targets used to cost
/// a whole run per row.)
#[test]
fn rows_with_targets_stop_early_with_the_full_rows_values() {
    let mesh = spot();
    for options in [Options::DEFAULT, common::GRAPH] {
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let sources = [0, 1500];
        let full = solver.distance_rows(&sources, None).unwrap();
        for (i, &s) in sources.iter().enumerate() {
            // The three vertices nearest the source (itself excluded).
            let mut order: Vec<u32> = (0..mesh.vertex_count() as u32)
                .filter(|&v| v != s)
                .collect();
            order.sort_by(|&a, &b| {
                full[i].distances[a as usize].total_cmp(&full[i].distances[b as usize])
            });
            let targets = &order[..3];
            let stopped = solver.distance_rows(&[s], Some(targets)).unwrap();
            let (row, stats) = (&stopped[0].distances, &stopped[0].stats);
            let expected: Vec<f64> = targets
                .iter()
                .map(|&t| full[i].distances[t as usize])
                .collect();
            assert_eq!(*row, expected, "source {s}");
            assert!(stats.stopped_early, "source {s}");
            let whole = &full[i].stats;
            assert!(!whole.stopped_early);
            assert!(
                stats.pushes * 10 < whole.pushes
                    && stats.distance_tests * 10 < whole.distance_tests,
                "source {s}: {} pushes and {} tests against {} and {}",
                stats.pushes,
                stats.distance_tests,
                whole.pushes,
                whole.distance_tests
            );
        }
        // Every vertex a target: the row is the full row.
        let all: Vec<u32> = (0..mesh.vertex_count() as u32).collect();
        let rows = solver.distance_rows(&sources, Some(&all)).unwrap();
        assert_eq!(rows[0].distances, full[0].distances);
    }
}

#[test]
fn parallel_rows_equal_single_runs() {
    let mesh = spot();
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let sources = [0, 17, 400, 1500, 2900, 2929];
    let targets = [5, 0, 2929, 1234];
    let rows = solver.distance_rows(&sources, Some(&targets)).unwrap();
    let full = solver.distance_rows(&sources, None).unwrap();
    for (i, &s) in sources.iter().enumerate() {
        let field = solver.field(&[s]).unwrap();
        assert_eq!(full[i].distances, field.vertex_distances());
        for (j, &t) in targets.iter().enumerate() {
            assert_eq!(rows[i].distances[j], field.distance(t));
        }
    }
    // The Steiner graph is symmetric: d(a, b) = d(b, a). (The wavefront engine's
    // values are each a real path's length, within its error of the geodesic, so
    // both directions agree only to about that.)
    let (ab, ba) = (full[0].distances[2929], full[5].distances[0]);
    assert!((ab - ba).abs() <= 1e-2 * ab, "{ab} {ba}");
    let tracks = Solver::new(
        &mesh,
        Euclidean,
        &Options::DEFAULT.with_method(geotracks::Method::Tracks),
    )
    .unwrap();
    let rows = tracks.distance_rows(&[0, 2929], None).unwrap();
    let (ab, ba) = (rows[0].distances[2929], rows[1].distances[0]);
    assert!((ab - ba).abs() <= 1e-9 * ab);
    let e = solver.distance_rows(&[0], Some(&[3000])).unwrap_err();
    assert!(
        matches!(e, Error::TargetOutOfRange { vertex: 3000, .. }),
        "{e}"
    );
    let e = solver.distance_rows(&[3000], None).unwrap_err();
    assert!(
        matches!(e, Error::SourceOutOfRange { vertex: 3000, .. }),
        "{e}"
    );
}

/// Distance tests of one run from vertex 0 at `k`, with `method`.
fn tests_at(mesh: &TriMesh, method: Method, k: f64) -> u64 {
    let solver = Solver::new(
        mesh,
        Euclidean,
        &Options::DEFAULT.with_k(k).with_method(method),
    )
    .unwrap();
    solver.field(&[0]).unwrap().stats().distance_tests
}

fn check_linear_work(mesh: &TriMesh, name: &str) {
    let tracks =
        tests_at(mesh, Method::Tracks, 8.0) as f64 / tests_at(mesh, Method::Tracks, 2.0) as f64;
    let graph =
        tests_at(mesh, Method::Graph, 8.0) as f64 / tests_at(mesh, Method::Graph, 2.0) as f64;
    println!("{name}: tests(k=8)/tests(k=2): tracks {tracks:.2}, graph {graph:.2}");
    assert!(tracks <= 6.0, "{name}: tracks ratio {tracks}");
    assert!(
        graph > 10.0,
        "{name}: graph ratio {graph} (should be about 16)"
    );
}

#[test]
fn tracks_work_grows_about_linearly_in_k_on_spot() {
    check_linear_work(&spot(), "spot");
}

/// The target is set on the shared bunny, which a fresh clone does not have:
/// ignored by `cargo test` (which says so), run by `.ci/run` with `--ignored` where
/// ../shared/data is beside the clone. Without the data it fails rather than pass
/// having checked nothing.
#[test]
#[ignore = "needs ../shared/data beside the clone; .ci/run runs it with --ignored shared"]
fn tracks_work_grows_about_linearly_in_k_on_the_shared_bunny() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes/bunny.obj");
    assert!(path.exists(), "{} not found", path.display());
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.face_count(), 69451);
    check_linear_work(&mesh, "bunny");
}
