//! Directed metrics (Finsler: `cost(a → b) ≠ cost(b → a)`): the track-pruned engine
//! still returns the Steiner graph's distances under random asymmetric norms, a run
//! under `Reversed` gives the cost *to* the sources, and paths are measured and
//! straightened in the direction they are travelled.

mod common;

use common::{random_book, random_mesh, random_randers, sphere, Randers, Rng};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{
    Euclidean, Method, Metric, Options, Reversed, Solver, Source, Stop, SurfacePoint, Tensor,
};
use glam::DVec3;
use proptest::prelude::*;

fn pick(mesh: &TriMesh, picks: &[u32]) -> Vec<u32> {
    picks
        .iter()
        .map(|p| p % mesh.vertex_count() as u32)
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    // The crossing lemma adds costs along straight segments in their direction of
    // travel only, so it holds for asymmetric norms: tracks = graph.
    #[test]
    fn tracks_equal_the_graph_on_perturbed_grids(seed in any::<u64>(), n in 2usize..8, k in 1u32..7, strength in 0.0f64..0.9, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = random_mesh(seed, n).unwrap();
        let metric = random_randers(&mesh, seed ^ 0x5eed, strength);
        let max = common::tracks_vs_graph(&mesh, &metric, &pick(&mesh, &picks), k as f64);
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }

    #[test]
    fn tracks_equal_the_graph_on_spheres_and_books(seed in any::<u64>(), book in any::<bool>(), k in 1u32..6, strength in 0.0f64..0.9, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = if book { random_book(seed, 4, 4) } else { sphere(1, 0.3, seed) };
        let metric = random_randers(&mesh, seed ^ 0xb00c, strength);
        let max = common::tracks_vs_graph(&mesh, &metric, &pick(&mesh, &picks), k as f64);
        prop_assert!(max <= 1e-9, "relative deviation {}", max);
    }

    // The cost from s to t is the cost to s from t under the reversed metric (the
    // graph reversed): a field *to* the sources.
    #[test]
    fn reversed_runs_give_the_cost_to_the_sources(seed in any::<u64>(), n in 2usize..7, tracks in any::<bool>(), s in any::<u32>(), t in any::<u32>()) {
        let mesh = random_mesh(seed, n).unwrap();
        let metric = random_randers(&mesh, seed ^ 0x7e7e, 0.8);
        let method = if tracks { Method::Tracks } else { Method::Graph };
        let options = Options::DEFAULT.with_k(3.0).with_method(method);
        let [s, t] = [s, t].map(|v| v % mesh.vertex_count() as u32);
        let from_s = Solver::new(&mesh, &metric, &options).and_then(|solver| solver.field(&[s])).unwrap();
        let to_s = Solver::new(&mesh, Reversed(&metric), &options).and_then(|solver| solver.field(&[s])).unwrap();
        let (there, back) = (from_s.distance(t), to_s.distance(t));
        let from_t = Solver::new(&mesh, &metric, &options).and_then(|solver| solver.field(&[t])).unwrap();
        // Under the reversed metric, from s to t costs what t to s costs.
        let expected = from_t.distance(s);
        prop_assert!(back == expected || (back - expected).abs() <= 1e-12 * expected, "{} vs {}", back, expected);
        prop_assert!(there.is_finite() == back.is_finite());
    }
}

/// A flat square under a constant Randers norm: straight lines are geodesics, so the
/// cost from `s` to `x` is `F(x − s)`, and the wind makes it differ from `F(s − x)`.
fn windy_square(n: usize, wind: [f64; 2]) -> (TriMesh, Randers) {
    let mesh = common::grid(n, 1.0);
    let tensor = Tensor::uniform_world(&mesh, [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
    let metric = Randers::new(&mesh, tensor, 1.0, |_| DVec3::new(wind[0], wind[1], 0.0));
    (mesh, metric)
}

fn randers_norm(v: DVec3, wind: [f64; 2]) -> f64 {
    v.length() + wind[0] * v.x + wind[1] * v.y
}

#[test]
fn on_a_windy_plane_the_field_approaches_the_norm_and_is_directed() {
    let wind = [0.6, 0.2];
    let (mesh, metric) = windy_square(8, wind);
    let source = 40; // the centre
    let centre = mesh.position(source);
    let mut worst = [0.0f64; 2];
    for (i, k) in [2.0, 8.0].into_iter().enumerate() {
        let field = Solver::new(&mesh, &metric, &Options::DEFAULT.with_k(k))
            .and_then(|solver| solver.field(&[source]))
            .unwrap();
        assert_eq!(field.stats().method, Method::Tracks);
        for v in 0..mesh.vertex_count() as u32 {
            let exact = randers_norm(mesh.position(v) - centre, wind);
            let d = field.distance(v);
            // Every graph path is a real path: never below the exact cost.
            assert!(d >= exact - 1e-12, "vertex {v}: {d} < {exact}");
            if exact > 0.0 {
                worst[i] = worst[i].max((d - exact) / exact);
            }
        }
    }
    println!(
        "windy plane: worst relative excess {:.2e} at k = 2, {:.2e} at k = 8",
        worst[0], worst[1]
    );
    assert!(worst[1] < worst[0] && worst[1] < 0.01, "{worst:?}");
    // Along ω (+x) costs more than against it: 0.5 along the edges, times 1 ± 0.6.
    let field = Solver::new(&mesh, &metric, &Options::DEFAULT.with_k(4.0))
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    let (east, west) = (field.distance(44), field.distance(36));
    assert!((east - 0.5 * 1.6).abs() < 1e-12, "{east}");
    assert!((west - 0.5 * 0.4).abs() < 1e-12, "{west}");
}

/// The traced and the straightened path from `s` to `t`, after checking that the
/// traced path's cost, segment by segment from the source, is the field's value at `t`.
fn traced_and_straightened<M: Metric>(
    solver: &Solver<M>,
    s: SurfacePoint,
    t: SurfacePoint,
) -> (geotracks::GeodesicPath, geotracks::GeodesicPath) {
    let field = solver
        .field(Sources::from(&[Source::new(s)]).until(&Stop::NONE))
        .unwrap();
    let query = &field;
    let traced = query.trace(t).unwrap();
    let at_t = query.distance_at(t).unwrap();
    assert!(
        (traced.length - at_t).abs() <= 1e-9 * at_t,
        "{} vs {}",
        traced.length,
        at_t
    );
    (traced, query.path(t).unwrap())
}

#[test]
fn paths_are_measured_and_straightened_the_way_they_are_travelled() {
    let wind = [0.5, -0.3];
    let (mesh, metric) = windy_square(10, wind);
    let solver = Solver::new(&mesh, &metric, &Options::DEFAULT.with_k(3.0)).unwrap();
    let mut rng = Rng(7);
    for _ in 0..20 {
        let (s, t) = (
            common::random_face_point(&mesh, &mut rng),
            common::random_face_point(&mesh, &mut rng),
        );
        let (traced, path) = traced_and_straightened(&solver, s, t);
        let exact = randers_norm(t.position(&mesh) - s.position(&mesh), wind);
        // Straightened, it is the straight segment from s to t: its cost that way.
        assert!(
            (path.length - exact).abs() <= 1e-6 * exact,
            "{} vs {}",
            path.length,
            exact
        );
        assert!(path.length <= traced.length + 1e-12);
        let backwards = randers_norm(s.position(&mesh) - t.position(&mesh), wind);
        assert!((path.length - backwards).abs() > 1e-3 * exact || (exact - backwards).abs() < 1e-3);
    }
}

/// Two winds, one per half of the square (x < ½, x > ½): a path from the left half to
/// the right is straight in each and bends on the line x = ½ where the cost *from the
/// source* is least. Straightened the other way round it would bend elsewhere.
#[test]
fn a_path_bends_where_travelling_it_costs_least() {
    let (left, right) = ([0.6, 0.0], [-0.5, 0.6]);
    let mesh = common::grid(10, 1.0);
    let tensor = Tensor::uniform_world(&mesh, [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
    let centroid_x = |f: u32| {
        let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
        (a.x + b.x + c.x) / 3.0
    };
    let metric = Randers::new(&mesh, tensor, 1.0, |f| {
        let w = if centroid_x(f) < 0.5 { left } else { right };
        DVec3::new(w[0], w[1], 0.0)
    });
    let solver = Solver::new(&mesh, &metric, &Options::DEFAULT.with_k(3.0)).unwrap();
    let mut rng = Rng(99);
    let (mut worst, mut exact_ones) = (0.0f64, 0);
    for _ in 0..20 {
        let point = |rng: &mut Rng, x0: f64| {
            let (x, y) = (x0 + 0.35 * rng.next(), 0.05 + 0.9 * rng.next());
            let p = DVec3::new(x, y, 0.0);
            (p, locate(&mesh, p))
        };
        let ((ps, s), (pt, t)) = (point(&mut rng, 0.05), point(&mut rng, 0.6));
        // The exact cost: the best crossing of x = ½, by golden section (convex in y).
        let through = |y: f64| {
            let m = DVec3::new(0.5, y, 0.0);
            randers_norm(m - ps, left) + randers_norm(pt - m, right)
        };
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..100 {
            let (a, b) = (lo + 0.382 * (hi - lo), hi - 0.382 * (hi - lo));
            if through(a) < through(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        let exact = through(0.5 * (lo + hi));
        let (_, path) = traced_and_straightened(&solver, s, t);
        assert!(
            path.length >= exact - 1e-9,
            "{} below the exact {}",
            path.length,
            exact
        );
        let excess = (path.length - exact) / exact;
        worst = worst.max(excess);
        exact_ones += (excess < 1e-6) as usize;
    }
    // Down the line x = ½ itself: its edges lie in a face of each wind, and a path
    // along them is charged in the face where its direction costs least (down: the
    // right face, 1 − 0.6; up: the left one, 1).
    let (top, bottom) = (9 * 11 + 5, 11 + 5);
    for (from, to, per_unit) in [(top, bottom, 0.4), (bottom, top, 1.0)] {
        let field = solver.field(&[from]).unwrap();
        let query = &field;
        let path = query.trace(SurfacePoint::Vertex(to)).unwrap();
        assert!((field.distance(to) - 0.8 * per_unit).abs() < 1e-12);
        assert!(
            (path.length - 0.8 * per_unit).abs() < 1e-12,
            "{}",
            path.length
        );
    }
    println!("two winds: {exact_ones} of 20 straightened paths within 1e-6 of the exact cost, all within {worst:.1e}");
    // A path that the graph led through a vertex on x = ½ can stay pinned there:
    // unpinning picks the side by Euclidean angles, which a strong wind can make the
    // wrong one (as a strongly anisotropic tensor can). The rest bend where they must.
    assert!(exact_ones >= 15 && worst < 0.01, "{exact_ones}, {worst}");
}

/// The face point of the flat unit grid at `p` (z = 0).
fn locate(mesh: &TriMesh, p: DVec3) -> SurfacePoint {
    for f in 0..mesh.face_count() as u32 {
        let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
        let (v0, v1, v2) = (b - a, c - a, p - a);
        let det = v0.x * v1.y - v0.y * v1.x;
        let l1 = (v2.x * v1.y - v2.y * v1.x) / det;
        let l2 = (v0.x * v2.y - v0.y * v2.x) / det;
        if l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0 {
            return SurfacePoint::Face {
                face: f,
                bary: [1.0 - l1 - l2, l1, l2],
            };
        }
    }
    panic!("{p} is off the grid");
}

#[test]
fn symmetric_metrics_say_so_and_reversing_them_changes_nothing() {
    let mesh = sphere(2, 0.2, 3);
    assert!(Euclidean.is_symmetric() && Reversed(Euclidean).face_gram(0).is_some());
    let a = Solver::new(&mesh, &Euclidean, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let b = Solver::new(&mesh, &Reversed(Euclidean), &Options::DEFAULT)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    assert_eq!(a.stats().method, Method::Wave);
    assert_eq!(a.node_distances(), b.node_distances());
    let point = SurfacePoint::Face {
        face: 3,
        bary: [0.2, 0.3, 0.5],
    };
    let metric = random_randers(&mesh, 11, 0.5);
    assert!(!metric.is_symmetric() && !Reversed(&metric).is_symmetric());
    // A directed metric has no flattening: it runs the tracks engine.
    let solver = Solver::new(&mesh, &metric, &Options::DEFAULT).unwrap();
    assert_eq!(solver.method(), Method::Tracks);
    assert!(solver.shortest_path(&[Source::new(0)], point).is_ok());
}
