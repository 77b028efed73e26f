//! Paths searched from both ends at once (`Stop::both_ends`, the default for a path
//! between two points under a symmetric metric with the Steiner-graph engines): the
//! path's traced cost is the complete Steiner graph's value at the target (the
//! oracle, a full run, to 1e-9), whatever the points, metric, mesh and k; a maximum
//! leaves the same targets unreached as a one-ended run; the same query gives the same
//! path every time; and one thread, or a directed metric, searches from one end.

mod common;

use common::{
    oracle, oracle_mesh, random_metric, random_randers, random_surface_point, sphere, Rng,
};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{Error, Euclidean, Method, Metric, Options, Solver, Source, Stop, SurfacePoint};
use proptest::prelude::*;

/// Whether searches from both ends can run here (two threads in rayon's pool).
fn two_threads() -> bool {
    rayon::current_num_threads() >= 2
}

/// A hilly grid of `n` × `n` unit cells.
fn hills(n: usize) -> TriMesh {
    common::grid_with(n, n as f64, |x, y| {
        [x, y, 2.0 * (0.3 * x).sin() * (0.2 * y).cos()]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// The oracle: from both ends, the tracks engine and the graph trace the path the
    /// complete Steiner graph gives the target, under every kind of metric (Euclidean,
    /// density, tensor, and directed: Randers, whose backward side runs reversed),
    /// between vertices, edge points and face points, on meshes with holes, fins and
    /// non-manifold books. The small meshes run rounds of a few dozen settles, so the
    /// searches meet after many rounds.
    #[test]
    fn both_ends_trace_what_the_steiner_graph_gives(
        seed in any::<u64>(),
        shape in 0u8..3,
        kind in 0u8..4,
        k in 1u32..5,
    ) {
        let Some(mesh) = oracle_mesh(shape, seed) else {
            return Ok(());
        };
        let metric = random_metric(&mesh, kind, seed);
        let mut rng = Rng(seed ^ 0xb07e);
        let (from, to) = (random_surface_point(&mesh, &mut rng), random_surface_point(&mesh, &mut rng));
        let expected = oracle(&mesh, &metric, k as f64, from, to);
        for method in [Method::Tracks, Method::Graph] {
            let options = Options::DEFAULT.with_method(method).with_k(k as f64);
            let solver = Solver::new(&mesh, &metric, &options).unwrap();
            match solver.shortest_path(Sources::from(&[Source::new(from)]).until(&Stop::NONE), to) {
                Ok((path, stats)) => {
                    prop_assert_eq!(stats.both_ends, two_threads());
                    let traced = path.traced_length;
                    prop_assert!(
                        (traced - expected).abs() <= 1e-9 * expected.max(1e-12),
                        "{:?} {} {} → {}: {} against the graph's {}",
                        method, metric.name(), from, to, traced, expected
                    );
                    prop_assert!(path.length <= traced * (1.0 + 1e-12));
                    prop_assert_eq!(path.points[0], to.validated(&mesh).unwrap());
                }
                Err(Error::Unreachable { .. }) => prop_assert!(expected.is_infinite()),
                Err(e) => prop_assert!(false, "{e}"),
            }
        }
    }

    /// A maximum distance: a target beyond it is unreached, one within it is found.
    /// (A one-ended run may also leave unreached a point inside a face whose nodes
    /// around lie beyond the maximum, as its early stop cannot tell what they would
    /// give it; from both ends the two sides' values say.)
    #[test]
    fn both_ends_keep_to_the_maximum(seed in any::<u64>(), k in 1u32..4) {
        let mesh = sphere(2, 0.2, seed);
        let mut rng = Rng(seed | 1);
        let (from, to) = (random_surface_point(&mesh, &mut rng), random_surface_point(&mesh, &mut rng));
        let expected = oracle(&mesh, &Euclidean, k as f64, from, to);
        let options = Options::DEFAULT.with_method(Method::Tracks).with_k(k as f64);
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        for max in [0.999 * expected, 1.001 * expected + 1e-12] {
            let stop = Stop::NONE.with_max_distance(max);
            match solver.shortest_path(Sources::from(&[Source::new(from)]).until(&stop), to) {
                Ok((path, _)) => {
                    prop_assert!(max >= expected, "{} found beyond {}", path.traced_length, max);
                    prop_assert!((path.traced_length - expected).abs() <= 1e-9 * expected);
                }
                Err(Error::Unreachable { .. }) => prop_assert!(max < expected),
                Err(e) => prop_assert!(false, "{e}"),
            }
        }
    }
}

/// The sides work in lock step, so the path does not depend on how the threads ran:
/// the same query gives the same path, to the bit, every time (a route across hills
/// with some thousand settles a round).
#[test]
fn the_same_query_gives_the_same_path() {
    let mesh = hills(80);
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(3.0);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let (from, to) = (SurfacePoint::Vertex(0), SurfacePoint::Vertex(80 * 81 + 57));
    let first = solver
        .shortest_path(Sources::from(&[Source::new(from)]).until(&Stop::NONE), to)
        .unwrap();
    for _ in 0..6 {
        let again = solver
            .shortest_path(Sources::from(&[Source::new(from)]).until(&Stop::NONE), to)
            .unwrap();
        assert_eq!(again.0.points, first.0.points);
        assert_eq!(again.1.settles, first.1.settles);
    }
    let expected = oracle(&mesh, &Euclidean, 3.0, from, to);
    assert!((first.0.traced_length - expected).abs() <= 1e-9 * expected);
}

/// Each side settles about half of what one goal-directed run settles: together about
/// as much (the average of the two ends' estimates is weaker than one end's).
#[test]
fn together_the_sides_settle_about_what_one_run_settles() {
    if !two_threads() {
        return;
    }
    let mesh = hills(80);
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(3.0);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let (from, to) = (SurfacePoint::Vertex(0), SurfacePoint::Vertex(80 * 81 + 57));
    let source = [Source::new(from)];
    let (both, both_stats) = solver
        .shortest_path(Sources::from(&source).until(&Stop::NONE), to)
        .unwrap();
    let one_end = Stop::NONE.with_both_ends(false);
    let (one, one_stats) = solver
        .shortest_path(Sources::from(&source).until(&one_end), to)
        .unwrap();
    assert!(both_stats.both_ends && !one_stats.both_ends);
    assert!((both.traced_length - one.traced_length).abs() <= 1e-9 * one.traced_length);
    let ratio = both_stats.settles as f64 / one_stats.settles as f64;
    assert!((0.8..1.4).contains(&ratio), "{ratio}");
}

/// One thread in rayon's pool, or several sources: a one-ended run, for the same
/// path. A directed metric searches from both ends too (its backward side on the
/// reversed metric), for the graph's path.
#[test]
fn one_thread_or_sources_search_from_one_end() {
    let mesh = hills(30);
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(2.0);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let (from, to) = (SurfacePoint::Vertex(3), SurfacePoint::Vertex(30 * 31 + 20));
    let expected = oracle(&mesh, &Euclidean, 2.0, from, to);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (path, stats) = pool
        .install(|| {
            solver.shortest_path(Sources::from(&[Source::new(from)]).until(&Stop::NONE), to)
        })
        .unwrap();
    assert!(!stats.both_ends);
    assert!((path.traced_length - expected).abs() <= 1e-9 * expected);

    let sources = [Source::new(from), Source::new(SurfacePoint::Vertex(500))];
    let (_, stats) = solver
        .shortest_path(Sources::from(&sources).until(&Stop::NONE), to)
        .unwrap();
    assert!(!stats.both_ends);

    // Against the wind one way, with it the other: the two directions differ.
    let wind = random_randers(&mesh, 7, 0.5);
    let solver = Solver::new(&mesh, &wind, &options).unwrap();
    for (a, b) in [(from, to), (to, from)] {
        let (path, stats) = solver
            .shortest_path(Sources::from(&[Source::new(a)]).until(&Stop::NONE), b)
            .unwrap();
        assert_eq!(stats.both_ends, two_threads());
        let expected = oracle(&mesh, &wind, 2.0, a, b);
        assert!(
            (path.traced_length - expected).abs() <= 1e-9 * expected,
            "{} against {expected}",
            path.traced_length
        );
        // The path's cost, travelled from the source, is the traced value.
        let travelled = path.segment_costs(&mesh, &wind).iter().sum::<f64>();
        assert!(travelled <= path.traced_length * (1.0 + 1e-9));
    }
    let there = oracle(&mesh, &wind, 2.0, from, to);
    let back = oracle(&mesh, &wind, 2.0, to, from);
    assert!((there - back).abs() > 1e-3 * there, "{there} {back}");
}

/// A memory budget that fits the solver and one run, but not a second run's buffers:
/// one-ended; with room for them, from both ends.
#[test]
fn a_second_run_must_fit_the_memory_budget() {
    if !two_threads() {
        return;
    }
    let mesh = hills(30);
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(3.0);
    // The least limit the solver accepts (what it and one run need), by bisection.
    let (mut lo, mut hi) = (0u64, 1u64 << 40);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        match Solver::new(&mesh, Euclidean, &options.with_memory_limit(mid)) {
            Ok(_) => hi = mid,
            Err(Error::KTooLarge { .. }) => lo = mid,
            Err(e) => panic!("{e}"),
        }
    }
    let (from, to) = (SurfacePoint::Vertex(3), SurfacePoint::Vertex(30 * 31 + 20));
    for (limit, both) in [(hi, false), (3 * hi, true)] {
        let solver = Solver::new(&mesh, Euclidean, &options.with_memory_limit(limit)).unwrap();
        let (_, stats) = solver
            .shortest_path(Sources::from(&[Source::new(from)]).until(&Stop::NONE), to)
            .unwrap();
        assert_eq!(stats.both_ends, both, "limit {limit}");
    }
}

/// Two islands: no path, from both ends as from one; and a path from a point to
/// itself, or across one face, is the point or the straight segment.
#[test]
fn islands_and_short_paths() {
    let mesh = common::two_islands();
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(2.0);
    let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
    let far = solver.shortest_path(
        Sources::from(&[Source::new(0)]).until(&Stop::NONE),
        SurfacePoint::Vertex(4),
    );
    assert!(matches!(far, Err(Error::Unreachable { .. })), "{far:?}");
    let nan = Stop::NONE.with_max_distance(f64::NAN);
    let refused = solver.shortest_path(
        Sources::from(&[Source::new(0)]).until(&nan),
        SurfacePoint::Vertex(1),
    );
    assert!(
        matches!(refused, Err(Error::InvalidValue { .. })),
        "{refused:?}"
    );
    let (same, _) = solver
        .shortest_path(
            Sources::from(&[Source::new(1)]).until(&Stop::NONE),
            SurfacePoint::Vertex(1),
        )
        .unwrap();
    assert_eq!(same.points, [SurfacePoint::Vertex(1)]);
    let (a, b) = (
        SurfacePoint::Face {
            face: 0,
            bary: [0.6, 0.2, 0.2],
        },
        SurfacePoint::Face {
            face: 0,
            bary: [0.2, 0.2, 0.6],
        },
    );
    let (straight, _) = solver
        .shortest_path(Sources::from(&[Source::new(a)]).until(&Stop::NONE), b)
        .unwrap();
    assert_eq!(straight.points, [b, a]);
    assert!((straight.length - 0.4).abs() < 1e-12);
}
