//! Goal-directed runs (A*): a run with targets orders nodes by their value plus the
//! metric's least cost per unit length times their distance to the targets. The
//! Steiner-graph engines must still give the targets the complete graph's values (the
//! oracle, to 1e-9); the wavefront engine, whose values depend on the order waves
//! arrive in, is never goal-directed.

mod common;

use common::{oracle, oracle_mesh, random_metric, sphere, Rng};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{
    Error, Euclidean, FacePoint, Method, Metric, Options, Solver, Source, Stop, SurfacePoint,
};
use proptest::prelude::*;

/// The value at `target` from `source` after a goal-directed run stopped there, with
/// the run's settles.
fn goal_directed<M: Metric>(
    solver: &Solver<M>,
    source: SurfacePoint,
    target: SurfacePoint,
) -> (f64, u64) {
    let stop = Stop::NONE.with_targets(vec![target]);
    let field = solver
        .field(Sources::from(&[Source::new(source)]).until(&stop))
        .unwrap();
    let value = field.distance_at(target).unwrap();
    (value, field.stats().settles)
}

fn random_point(mesh: &TriMesh, rng: &mut Rng) -> SurfacePoint {
    match rng.below(3) {
        0 => SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32),
        _ => common::random_face_point(mesh, rng),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// The oracle: a goal-directed run of the tracks engine and of the graph gives the
    /// target the complete Steiner graph's value (a full run), under every kind of
    /// metric, on meshes with holes, fins and non-manifold books.
    #[test]
    fn goal_directed_routes_cost_what_the_steiner_graph_gives(
        seed in any::<u64>(),
        shape in 0u8..3,
        kind in 0u8..4,
        k in 1u32..5,
    ) {
        let Some(mesh) = oracle_mesh(shape, seed) else {
            return Ok(());
        };
        let metric = random_metric(&mesh, kind, seed);
        let mut rng = Rng(seed ^ 0x90a1);
        let (from, to) = (random_point(&mesh, &mut rng), random_point(&mesh, &mut rng));
        let expected = oracle(&mesh, &metric, k as f64, from, to);
        for method in [Method::Tracks, Method::Graph] {
            let options = Options::DEFAULT.with_method(method).with_k(k as f64);
            let solver = Solver::new(&mesh, &metric, &options).unwrap();
            let (value, _) = goal_directed(&solver, from, to);
            prop_assert!(
                value == expected || (value - expected).abs() <= 1e-9 * expected,
                "{:?} {}: {} against the graph's {}", method, metric.name(), value, expected
            );
        }
    }

    /// The wavefront engine is never goal-directed (its values depend on the order
    /// waves arrive in): a stop asking for it gives what a plain stop gives, to the bit.
    #[test]
    fn wavefront_runs_ignore_goal_direction(seed in any::<u64>(), k in 1u32..4) {
        let mesh = sphere(2, 0.2, seed);
        let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(k as f64)).unwrap();
        prop_assert_eq!(solver.method(), Method::Wave);
        let mut rng = Rng(seed | 1);
        let (from, to) = (random_point(&mesh, &mut rng), random_point(&mesh, &mut rng));
        let (value, settles) = goal_directed(&solver, from, to);
        let plain = Stop::NONE.with_targets(vec![to]).with_goal_directed(false);
        let field = solver.field(Sources::from(&[Source::new(from)]).until(&plain)).unwrap();
        prop_assert_eq!(value, field.distance_at(to).unwrap());
        prop_assert_eq!(settles, field.stats().settles);
    }
}

/// On a terrain-like grid (hills, a route corner to corner) the goal-directed tracks
/// engine settles a fraction of what a plain early stop settles, for the same value.
#[test]
fn goal_direction_settles_a_corridor() {
    let n = 60;
    let mesh = common::grid_with(n, n as f64, |x, y| {
        [x, y, (0.3 * x).sin() * (0.2 * y).cos()]
    });
    let solver = Solver::new(
        &mesh,
        Euclidean,
        &Options::DEFAULT.with_method(Method::Tracks).with_k(2.0),
    )
    .unwrap();
    let (from, to) = (
        SurfacePoint::Vertex(0),
        SurfacePoint::Vertex((n * (n + 1) + n) as u32),
    );
    let (value, settles) = goal_directed(&solver, from, to);
    let plain = Stop::NONE.with_targets(vec![to]).with_goal_directed(false);
    let field = solver
        .field(Sources::from(&[Source::new(from)]).until(&plain))
        .unwrap();
    let expected = field.distance_at(to).unwrap();
    println!(
        "{n} × {n} hills, corner to corner: {settles} settles against {}",
        field.stats().settles
    );
    assert!(
        (value - expected).abs() <= 1e-9 * expected,
        "{value} {expected}"
    );
    assert!(3 * settles < field.stats().settles);
}

/// The length, with a chosen least cost per unit length and wires at a chosen fraction
/// of their length: a metric that keeps or breaks its promise.
struct Claimed {
    per_length: f64,
    wire_fraction: f64,
}

impl Metric for Claimed {
    fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        a.distance(b)
    }
    fn is_face_norm(&self) -> bool {
        true
    }
    fn wire_cost(&self, _a: u32, _b: u32, length: f64) -> f64 {
        self.wire_fraction * length
    }
    fn min_cost_per_length(&self) -> f64 {
        self.per_length
    }
}

/// A metric whose promised least cost per unit length exceeds what an edge costs is
/// refused when the solver is built, naming the edge.
#[test]
fn a_metric_that_promises_too_much_is_refused() {
    let boastful = Claimed {
        per_length: 1.5,
        wire_fraction: 1.0,
    };
    let mesh = common::grid(2, 2.0);
    let error = Solver::new(&mesh, boastful, &Options::DEFAULT).expect_err("refused");
    assert!(
        matches!(error, Error::CostBelowBound { per_length, .. } if per_length == 1.5),
        "{error}"
    );
    assert!(error.to_string().contains("edge"), "{error}");

    // A wire too: the bound holds on faces, but the wire charges its length / 2.
    let cheap_wires = Claimed {
        per_length: 1.0,
        wire_fraction: 0.5,
    };
    let mesh = TriMesh::with_line_elements(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 3.0, 0.0],
        ],
        vec![[0, 1, 2]],
        vec![[2, 3]],
    )
    .unwrap();
    let error = Solver::new(&mesh, cheap_wires, &Options::DEFAULT).expect_err("refused");
    assert!(matches!(error, Error::WireBelowBound { .. }), "{error}");
}

/// A bound that is not a positive finite number promises nothing: the run is plain.
#[test]
fn no_bound_no_goal_direction() {
    let unsure = Claimed {
        per_length: f64::NAN,
        wire_fraction: 1.0,
    };
    let mesh = common::grid(20, 20.0);
    let target = SurfacePoint::Vertex(22);
    let unsure = Solver::new(&mesh, unsure, &Options::DEFAULT.with_method(Method::Tracks)).unwrap();
    let sure = Solver::new(
        &mesh,
        Euclidean,
        &Options::DEFAULT.with_method(Method::Tracks),
    )
    .unwrap();
    let (a, unsure_settles) = goal_directed(&unsure, SurfacePoint::Vertex(0), target);
    let (b, sure_settles) = goal_directed(&sure, SurfacePoint::Vertex(0), target);
    assert!((a - b).abs() < 1e-12, "{a} {b}");
    assert!(sure_settles < unsure_settles);
}

/// Targets spread over most of the mesh leave the estimate zero nearly everywhere: the
/// run is plain, settling what a plain run settles.
#[test]
fn targets_all_over_the_mesh_run_plain() {
    let n = 30;
    let mesh = common::grid(n, n as f64);
    let solver = Solver::new(
        &mesh,
        Euclidean,
        &Options::DEFAULT.with_method(Method::Tracks),
    )
    .unwrap();
    let corners = vec![
        SurfacePoint::Vertex(n as u32),
        SurfacePoint::Vertex((n * (n + 1)) as u32),
    ];
    let source = [Source::new((n / 2) as u32)];
    let settles = |stop: Stop| {
        solver
            .field(Sources::from(&source).until(&stop))
            .unwrap()
            .stats()
            .settles
    };
    let spread = Stop::NONE.with_targets(corners);
    assert_eq!(
        settles(spread.clone()),
        settles(spread.with_goal_directed(false))
    );
    // One of them alone is goal-directed.
    let one = Stop::NONE.with_targets(vec![SurfacePoint::Vertex(n as u32)]);
    assert!(settles(one.clone()) < settles(one.with_goal_directed(false)));
}
