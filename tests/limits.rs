//! A k that cannot fit is refused before anything big is allocated, with the limit it
//! breaks and the largest k that fits (one triangle with k = 1e9 used to take
//! 22 s and 11.7 GB before failing; k = 1e5 on a 12K-face mesh failed after 7 GB with
//! the wrong reason).

mod common;

use geotracks::mesh::io::read_mesh;
use geotracks::mesh::TriMesh;
use geotracks::{Error, Euclidean, Method, Options, SizeLimit, Solver};

fn triangle() -> TriMesh {
    TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap()
}

fn spot() -> TriMesh {
    read_mesh(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj")).unwrap()
}

fn refused(mesh: &TriMesh, options: Options) -> (SizeLimit, f64) {
    match Solver::new(mesh, Euclidean, &options) {
        Err(Error::KTooLarge {
            limit, largest_k, ..
        }) => (limit, largest_k),
        Err(e) => panic!("wrong error: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn too_many_points_on_one_edge_is_refused_with_the_largest_k() {
    let (limit, largest) = refused(&triangle(), Options::DEFAULT.with_k(1e9));
    assert!(
        matches!(limit, SizeLimit::PointsOnEdge { points, limit: 65535, .. } if points > 65535)
    );
    // The largest k fits, and the message says so.
    Solver::new(triangle(), Euclidean, &Options::DEFAULT.with_k(largest)).unwrap();
    let message = Solver::new(triangle(), Euclidean, &Options::DEFAULT.with_k(1e5))
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("65535") && message.contains("largest k"),
        "{message}"
    );

    // (Without the work limit, which would bound k first.)
    let unbounded = Options::DEFAULT.with_work_limit(None);
    let (limit, largest) = refused(&spot(), unbounded.with_k(1e5));
    assert!(matches!(limit, SizeLimit::PointsOnEdge { .. }));
    assert!(largest > 1000.0 && largest < 1e5, "{largest}");
    // Memory is not what limits here (spot at 65535 points per edge needs ~70 GB).
    let unlimited = unbounded.with_memory_limit(u64::MAX);
    let fixed = refused(&spot(), unlimited.with_fixed_count(70_000));
    assert_eq!(fixed.1, 65535.0);
}

/// A flat grid of 3 × 3 squares: 18 faces.
fn grid18() -> TriMesh {
    common::grid(3, 3.0)
}

/// The work a k asks for is estimated before anything is laid out: a k that would
/// run for minutes or hours on a tiny mesh (k = 5000 on 18 faces took 59 s, and
/// k = 51,500 was accepted) is refused at once, with the estimate, the limit and the
/// largest k that fits, for every Steiner engine; the limit can be raised or lifted.
#[test]
fn a_k_whose_work_breaks_the_limit_is_refused_before_any_work() {
    let mesh = grid18();
    for method in [Method::Wave, Method::Tracks, Method::Graph] {
        let options = Options::DEFAULT.with_method(method).with_k(51_500.0);
        let start = std::time::Instant::now();
        let (limit, largest) = refused(&mesh, options);
        assert!(
            start.elapsed().as_secs_f64() < 2.0,
            "{method}: {:?}",
            start.elapsed()
        );
        match limit {
            SizeLimit::Work { tests, limit } => {
                assert_eq!(limit, Options::DEFAULT_WORK_LIMIT);
                assert!(tests > limit as f64, "{method}: {tests}");
            }
            // The tracks engine's edges hold 65535 points at most: that breaks first.
            SizeLimit::PointsOnEdge { .. } if method != Method::Graph => {}
            other => panic!("{method}: {other:?}"),
        }
        // The largest k is bounded by the work, not only by the layout.
        assert!(largest > 100.0 && largest < 40_000.0, "{method}: {largest}");
    }
    let message = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(20_000.0))
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("distance tests")
            && message.contains("work limit of 4.00e9")
            && message.contains("largest k"),
        "{message}"
    );
    // The estimate is the run's work within 2×: a k just within a small limit runs
    // and reports about as many tests.
    let options = Options::DEFAULT
        .with_k(300.0)
        .with_work_limit(Some(10_000_000));
    for method in [Method::Wave, Method::Graph] {
        let solver = Solver::new(&mesh, Euclidean, &options.with_method(method)).unwrap();
        let tests = solver.field(&[0]).unwrap().stats().distance_tests as f64;
        let (limit, _) = refused(&mesh, options.with_method(method).with_work_limit(Some(1)));
        let SizeLimit::Work {
            tests: estimate, ..
        } = limit
        else {
            panic!("{limit:?}")
        };
        assert!(
            estimate > 0.5 * tests && estimate < 2.0 * tests,
            "{method}: estimated {estimate}, ran {tests}"
        );
    }
    // Lifted: the layout's own limits remain.
    let lifted = Options::DEFAULT.with_k(20_000.0).with_work_limit(None);
    let _ = Solver::new(triangle(), Euclidean, &lifted).unwrap();
}

/// The default work limit keeps every shared benchmark mesh runnable at k = 20 with
/// every engine (the largest shared mesh has 1.1M faces; Spot stands in for them here
/// at the same faces' worth of work: the estimate is a sum over faces).
#[test]
fn the_default_work_limit_admits_k_20_on_a_million_faces() {
    // Spot's estimate at k = 20, scaled to 1.1M faces of the same shape, fits.
    let mesh = spot();
    for method in [Method::Wave, Method::Tracks, Method::Graph] {
        let options = Options::DEFAULT.with_method(method).with_k(20.0);
        let (limit, _) = refused(&mesh, options.with_work_limit(Some(1)));
        let SizeLimit::Work { tests, .. } = limit else {
            panic!("{limit:?}")
        };
        let scaled = tests * 1.1e6 / mesh.face_count() as f64;
        assert!(
            scaled < Options::DEFAULT_WORK_LIMIT as f64,
            "{method}: {scaled:e}"
        );
    }
}

#[test]
fn the_graph_is_refused_past_32_bit_nodes_or_the_memory_budget() {
    // The graph has no per-edge limit, but 2e9 points on each of three edges exceed
    // 32-bit node ids.
    let graph = Options::DEFAULT.with_method(Method::Graph);
    let (limit, _) = refused(&triangle(), graph.with_k(2e9));
    assert!(matches!(limit, SizeLimit::Nodes { .. }), "{limit:?}");
    // A memory budget: Spot at k = 2000 needs about 1 GB.
    let (limit, largest) = refused(&spot(), graph.with_k(2000.0).with_memory_limit(100_000_000));
    assert!(
        matches!(limit, SizeLimit::Memory { needed, available: 100_000_000 } if needed > 100_000_000)
    );
    Solver::new(
        spot(),
        Euclidean,
        &graph.with_k(largest).with_memory_limit(100_000_000),
    )
    .unwrap();
    assert!(largest > 50.0 && largest < 2000.0, "{largest}");
}

#[test]
fn the_tracks_engine_keeps_to_the_memory_budget() {
    let options = Options::DEFAULT.with_k(500.0).with_memory_limit(50_000_000);
    let mesh = spot();
    let (limit, largest) = refused(&mesh, options);
    assert!(matches!(limit, SizeLimit::Memory { .. }));
    let solver = Solver::new(&mesh, Euclidean, &options.with_k(largest)).unwrap();
    assert!(solver.layout().node_count() > 100_000);
}

/// A flat square of side `side` in two triangles.
fn square(side: f64) -> Result<TriMesh, geotracks::mesh::MeshError> {
    TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [side, 0.0, 0.0],
            [side, side, 0.0],
            [0.0, side, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// Any finite mesh within ±1e300 works at any scale, with every engine: frames and
/// lengths are computed in units of each face's size, and squares that over- or
/// underflow fall back to `hypot`. (A side of 1e78 gave "metric returned NaN", 1e154
/// "degenerate", and 1e-80 a diagonal 2.8e-6 off.)
#[test]
fn squares_from_1e_minus_300_to_1e300_give_exact_distances() {
    for exponent in [-300, -200, -160, -80, -1, 0, 1, 78, 154, 200, 299] {
        let side = 10f64.powi(exponent);
        let mesh = square(side).unwrap();
        for method in [Method::Tracks, Method::Graph, Method::Dijkstra] {
            let options = Options::DEFAULT.with_k(3.0).with_method(method);
            let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
            let field = solver.field(&[0]).unwrap();
            let expected = [0.0, side, side * 2f64.sqrt(), side];
            for (v, (&d, &e)) in field.vertex_distances().iter().zip(&expected).enumerate() {
                assert!(
                    (d - e).abs() <= 1e-12 * e,
                    "side 1e{exponent}, {method}, vertex {v}: {d} vs {e}"
                );
            }
        }
        let density = geotracks::Density::constant(&mesh, 2.0).unwrap();
        let field = Solver::new(&mesh, &density, &Options::DEFAULT)
            .unwrap()
            .field(&[0])
            .unwrap();
        let d = field.distance(2);
        assert!(
            (d - 2.0 * side * 2f64.sqrt()).abs() <= 1e-12 * d,
            "side 1e{exponent}: {d}"
        );
    }
}

#[test]
fn coordinates_beyond_1e300_are_refused() {
    match square(1e301) {
        Err(geotracks::mesh::MeshError::CoordinateOutOfRange { vertex: 1, .. }) => {}
        other => panic!("{other:?}"),
    }
}

/// A density of 1e300 over edges 1e10 long: distances would overflow. Every engine
/// refuses it up front, instead of taking the overflow for a wall and calling the
/// vertices unreachable.
#[test]
fn costs_beyond_the_f64_range_are_refused_by_every_engine() {
    let mesh = square(1e10).unwrap();
    let density = geotracks::Density::constant(&mesh, 1e300).unwrap();
    for method in [Method::Tracks, Method::Graph, Method::Dijkstra] {
        let options = Options::DEFAULT.with_method(method);
        match Solver::new(&mesh, &density, &options) {
            Err(Error::CostOverflow { metric }) => assert_eq!(metric, "density"),
            Err(e) => panic!("{method}: {e}"),
            Ok(_) => panic!("{method}: accepted"),
        }
    }
    // Within range it runs: 1e290 over the same edges.
    let density = geotracks::Density::constant(&mesh, 1e290).unwrap();
    let field = Solver::new(&mesh, &density, &Options::DEFAULT)
        .unwrap()
        .field(&[0])
        .unwrap();
    assert!((field.distance(2) - 1e300 * 2f64.sqrt()).abs() < 1e-12 * 1e300);
}

/// A distance matrix is kept in memory: one that cannot fit (a million rows of
/// Spot's 2,930 vertices need 23 GB) is refused before any row is computed, with its
/// size, instead of running for minutes and failing (or being killed).
#[test]
fn a_distance_matrix_beyond_the_memory_is_refused_before_any_row() {
    let mesh = spot();
    let options = Options::DEFAULT.with_memory_limit(1_000_000_000);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let sources = vec![0u32; 1_000_000];
    let start = std::time::Instant::now();
    let err = solver.distance_rows(&sources, None).unwrap_err();
    assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    match err {
        Error::OutputTooLarge {
            rows: 1_000_000,
            columns,
            bytes,
            available: 1_000_000_000,
        } => {
            assert_eq!(columns, mesh.vertex_count());
            assert_eq!(bytes, 8 * 1_000_000 * columns as u64);
        }
        other => panic!("{other}"),
    }
    // With targets the rows are as wide as the targets: these fit.
    let rows = solver
        .distance_rows(&sources[..1000], Some(&[1, 2]))
        .unwrap();
    assert_eq!(rows.len(), 1000);
    // Without a limit, what the system reports available decides (16.7M rows of
    // Spot, 393 GB, fit on no machine this runs on).
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let huge = vec![0u32; 1 << 24];
    assert!(matches!(
        solver.distance_rows(&huge, None),
        Err(Error::OutputTooLarge { .. })
    ));
}

/// The pairs within a maximum distance of each source are counted as the runs finish:
/// rows that outgrow the memory budget stop the call (everything within `inf` of
/// every vertex of Spot is 8.6M pairs, 137 MB, against a 20 MB budget), while rows
/// within a small radius fit and hold every pair a full run finds there.
#[test]
fn local_rows_that_outgrow_the_memory_stop_the_call() {
    let mesh = spot();
    let options = Options::DEFAULT.with_memory_limit(20_000_000);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let all: Vec<u32> = (0..mesh.vertex_count() as u32).collect();
    match solver.local_distance_rows(&all, f64::INFINITY) {
        Err(Error::LocalRowsTooLarge {
            pairs, available, ..
        }) => {
            assert_eq!(available, 20_000_000);
            assert!(pairs * 16 > available, "{pairs}");
        }
        Err(e) => panic!("{e}"),
        Ok(rows) => panic!("{} rows accepted", rows.len()),
    }
    let radius = 0.05;
    let rows = solver.local_distance_rows(&all[..50], radius).unwrap();
    for (&source, row) in all.iter().zip(&rows) {
        let full = solver.field(&[source]).unwrap();
        let within: Vec<u32> = (0..mesh.vertex_count() as u32)
            .filter(|&v| full.distance(v) <= radius)
            .collect();
        let listed: Vec<u32> = row.iter().map(|&(v, _)| v).collect();
        assert_eq!(listed, within, "source {source}");
    }
    assert!(matches!(
        solver.local_distance_rows(&all, -1.0),
        Err(Error::InvalidValue { .. })
    ));
}
