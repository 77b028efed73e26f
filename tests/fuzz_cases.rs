//! The engine cases a fuzzer found (`tests/data/fuzz/`, copied from the shared data's
//! `fuzz/`; its README describes them): multi-scale meshes, sliver columns, collinear
//! faces, densities spanning hundreds of orders of magnitude. Before the queue was made
//! robust the tracks engine did 10⁴–10⁵ times the graph's work on them, or hung; `path`
//! panicked on the `path_panic/` ones.
//!
//! Each case must run with both engines (the graph only where its O(k²) faces stay
//! small), with the work bounded by the number of nodes, the two engines agreeing where
//! the metric is a norm, and every query of the case answered without a panic.

mod common;

use geotracks::mesh::io::read_mesh;
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{
    Density, Euclidean, Method, Metric, Options, Solver, Source, Stats, Stop, SurfacePoint, Tensor,
};
use std::path::{Path, PathBuf};

/// What a `.case.txt` file says.
struct Case {
    name: String,
    mesh: TriMesh,
    k: f64,
    sources: Vec<Source>,
    max_distance: f64,
    queries: Vec<SurfacePoint>,
    metric: CaseMetric,
}

enum CaseMetric {
    Euclidean,
    Density(Density),
    Tensor(Tensor),
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/fuzz")
        .join(name)
}

fn numbers(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

fn read_case(dir: &Path, stem: &str) -> Case {
    let text = std::fs::read_to_string(dir.join(format!("{stem}.case.txt"))).unwrap();
    let mesh = read_mesh(dir.join(format!("{stem}.obj"))).unwrap();
    let (mut k, mut sources, mut max_distance, mut queries) = (5.0, vec![], f64::INFINITY, vec![]);
    let mut metric = CaseMetric::Euclidean;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["k", v, ..] => k = v.parse().unwrap(),
            ["source", point, "start", start, ..] => {
                let point: SurfacePoint = point.parse().unwrap();
                sources.push(Source::new(point).with_start(start.parse().unwrap()));
            }
            ["max_distance", v, ..] => max_distance = v.parse().unwrap(),
            ["query", point, ..] => queries.push(point.parse().unwrap()),
            ["metric", "density"] => {
                let values = numbers(&dir.join(format!("{stem}.density.txt")));
                let values = values.into_iter().map(|r| r[0]).collect();
                metric = CaseMetric::Density(Density::new(&mesh, values).unwrap());
            }
            ["metric", "tensor"] => {
                // One row per face as read (degenerate faces dropped), or per face of
                // the file as the CLI reads them.
                let rows = numbers(&dir.join(format!("{stem}.tensor.txt")));
                let faces = mesh.triangles().len();
                let kept: Vec<[f64; 6]> = (0..faces as u32)
                    .map(|f| {
                        let row = if rows.len() == faces {
                            f as usize
                        } else {
                            mesh.input_face(f)
                        };
                        let r = &rows[row];
                        [r[0], r[1], r[2], r[3], r[4], r[5]]
                    })
                    .collect();
                metric = CaseMetric::Tensor(Tensor::from_world(&mesh, &kept).unwrap());
            }
            _ => {}
        }
    }
    Case {
        name: stem.to_string(),
        mesh,
        k,
        sources,
        max_distance,
        queries,
        metric,
    }
}

/// Every case under `dir`, by the stems of its `.case.txt` files.
fn cases(dir: &Path) -> Vec<Case> {
    let mut stems: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.strip_suffix(".case.txt").map(str::to_string)
        })
        .collect();
    stems.sort();
    // `FUZZ_CASE=seed5217` runs one case (to look at it with `--nocapture`).
    if let Ok(only) = std::env::var("FUZZ_CASE") {
        stems.retain(|s| *s == only);
    }
    stems.iter().map(|s| read_case(dir, s)).collect()
}

/// The cases are run at most at this k: the k = 1000 ones exercise the same multi-scale
/// structure at k = 100, where the graph's O(k²) faces stay affordable for a test. (At
/// their own k they finish too: `FUZZ_FULL_K=1` runs them so, with `--nocapture` to see
/// the figures.)
const MAX_K: f64 = 100.0;

/// Runs the case with `method`; returns the node distances and the stats, or `None`
/// when the solver refuses the metric because its costs overflow.
fn run<M: Metric>(case: &Case, metric: &M, method: Method) -> Option<(Vec<f64>, Stats)> {
    let k = if std::env::var("FUZZ_FULL_K").is_ok() {
        case.k
    } else {
        case.k.min(MAX_K)
    };
    let options = Options::DEFAULT.with_k(k).with_method(method);
    let solver = match Solver::new(&case.mesh, metric, &options) {
        Err(geotracks::Error::CostOverflow { .. }) => return None,
        solver => solver.unwrap(),
    };
    // A NaN maximum distance is refused; the case then runs without one.
    let stop = Stop::NONE.with_max_distance(if case.max_distance.is_nan() {
        f64::INFINITY
    } else {
        case.max_distance
    });
    let field = solver
        .field(Sources::from(&case.sources).until(&stop))
        .unwrap();
    let nodes = solver.layout().node_count() as u64;
    let stats = field.stats().clone();
    eprintln!(
        "{} {method} k = {k}: {nodes} nodes, {} settles, {} pushes, {} tests, {:.3} s",
        case.name, stats.settles, stats.pushes, stats.distance_tests, stats.propagate_seconds
    );
    // Before the queue was bounded, tracks settled nodes 10³–10⁵ times each here.
    assert!(
        stats.settles <= 3 * nodes + 64,
        "{}: {method} settled {} times for {nodes} nodes",
        case.name,
        stats.settles
    );
    let query = &field;
    for &q in &case.queries {
        let d = query.distance_at(q).unwrap();
        assert!(!d.is_nan(), "{}: distance at {q} is NaN", case.name);
        match query.path(q) {
            Ok(path) => {
                assert!(
                    path.length <= path.traced_length * (1.0 + 1e-9) || path.length.is_nan(),
                    "{}: straightened path to {q} is longer than traced",
                    case.name
                );
                assert!(
                    !path.length.is_nan(),
                    "{}: path to {q} has NaN length",
                    case.name
                );
            }
            Err(geotracks::Error::Unreachable { .. }) => assert!(d.is_infinite()),
            Err(e) => panic!("{}: path to {q}: {e}", case.name),
        }
    }
    Some((field.node_distances().to_vec(), stats))
}

/// Checks the case; returns whether it ran (`false`: every engine refused its costs).
fn check_case(case: &Case) -> bool {
    let check = |metric: &dyn Fn(Method) -> Option<(Vec<f64>, Stats)>| {
        let Some((tracks, stats)) = metric(Method::Tracks) else {
            // Refused: the other engines must refuse it too.
            assert!(metric(Method::Graph).is_none() && metric(Method::Dijkstra).is_none());
            return false;
        };
        // The graph tests every pair of boundary nodes of a face: keep it to cases
        // whose faces hold a few hundred nodes at most.
        if stats.steiner_points as f64 / (stats.faces as f64).max(1.0) > 200.0 {
            return true;
        }
        let (graph, _) = metric(Method::Graph).expect("the graph refuses what tracks runs");
        for (node, (t, g)) in tracks.iter().zip(&graph).enumerate() {
            let same = (t.is_infinite() && g.is_infinite())
                || (t - g).abs() <= 1e-9 * g.abs().max(f64::MIN_POSITIVE);
            assert!(same, "{}: node {node}: tracks {t}, graph {g}", case.name);
        }
        true
    };
    match &case.metric {
        CaseMetric::Euclidean => check(&|m| run(case, &Euclidean, m)),
        CaseMetric::Tensor(t) => check(&|m| run(case, t, m)),
        CaseMetric::Density(d) => check(&|m| run(case, d, m)),
    }
}

#[test]
fn fuzz_cases_run_with_bounded_work_and_agree() {
    let cases = cases(&data(""));
    assert!(cases.len() >= 7 || std::env::var("FUZZ_CASE").is_ok());
    for case in &cases {
        check_case(case);
    }
}

/// `path` panicked on these (a NaN bound in straightening) with densities spanning
/// 1e-300 … 1e300 on edges up to 1e30 long. As given, their costs add up beyond the
/// f64 range and every engine refuses them (`CostOverflow`); scaled down until the
/// costs fit, their paths are straightened without a panic.
#[test]
fn path_panic_cases_are_refused_or_give_paths() {
    let cases = cases(&data("path_panic"));
    assert_eq!(cases.len(), 3);
    for mut case in cases {
        let mut ran = check_case(&case);
        for _ in 0..40 {
            if ran {
                break;
            }
            // 1e-10 at a time, until the costs fit (the densities stay as they were).
            let positions = case
                .mesh
                .positions()
                .iter()
                .map(|p| (*p * 1e-10).to_array())
                .collect();
            let mesh = TriMesh::new(positions, case.mesh.triangles().to_vec()).unwrap();
            if let CaseMetric::Density(d) = &case.metric {
                case.metric =
                    CaseMetric::Density(Density::new(&mesh, d.per_vertex().to_vec()).unwrap());
            }
            case.mesh = mesh;
            ran = check_case(&case);
        }
        assert!(ran, "{}", case.name);
    }
}

#[test]
fn sliver_columns_run_with_bounded_work() {
    for name in ["sliver_20x20_w1e-9.obj", "sliver_10x10_w1e-12.obj"] {
        let case = Case {
            name: name.into(),
            mesh: read_mesh(data(name)).unwrap(),
            k: 5.0,
            sources: vec![Source::new(0)],
            max_distance: f64::INFINITY,
            queries: vec![],
            metric: CaseMetric::Euclidean,
        };
        assert!(check_case(&case));
    }
}

#[test]
fn spot_with_a_density_of_1e_minus_9_on_a_quarter_runs_with_bounded_work() {
    let mesh =
        read_mesh(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/spot.obj")).unwrap();
    let values = numbers(&data("spot.density_quarter_1e-9.txt"));
    let density = Density::new(&mesh, values.into_iter().map(|r| r[0]).collect()).unwrap();
    let case = Case {
        name: "spot density".into(),
        mesh,
        k: 5.0,
        sources: vec![Source::new(2000)],
        max_distance: f64::INFINITY,
        queries: vec![SurfacePoint::Vertex(10), SurfacePoint::Vertex(2900)],
        metric: CaseMetric::Density(density),
    };
    assert!(check_case(&case));
}

/// A metric may return `+inf` (a wall): straightening beside a thin wall, whose finite
/// differences can see ∞ (the guard that keeps NaN out of its clamp bound), gives paths
/// no longer than traced.
#[test]
fn straightening_beside_a_wall_does_not_panic() {
    /// Euclidean, but a segment with an end within 0.05 of the line x = 0.5 costs +inf
    /// unless it is vertical there.
    struct Wall(TriMesh);
    impl Metric for Wall {
        fn cost(&self, face: u32, a: &geotracks::FacePoint, b: &geotracks::FacePoint) -> f64 {
            let corners = self.0.triangles()[face as usize].map(|v| self.0.positions()[v as usize]);
            let x =
                |p: &geotracks::FacePoint| (0..3).map(|i| p.bary[i] * corners[i].x).sum::<f64>();
            let near = |p: &geotracks::FacePoint| (x(p) - 0.53).abs() < 0.005;
            if (near(a) || near(b)) && (x(a) - x(b)).abs() > 1e-9 {
                f64::INFINITY
            } else {
                a.distance(b)
            }
        }
    }
    let mesh = common::rectangle(10, 10, 1.0, 1.0);
    let wall = Wall(mesh.clone());
    for target in [
        SurfacePoint::Vertex(120),
        SurfacePoint::Vertex(10),
        "e:100:0.3".parse().unwrap(),
    ] {
        let solver = Solver::new(&mesh, &wall, &Options::DEFAULT.with_k(3.0)).unwrap();
        let field = solver
            .field(Sources::from(&[Source::new(0)]).until(&Stop::NONE))
            .unwrap();
        match field.path(target) {
            Ok(path) => assert!(
                path.length <= path.traced_length * (1.0 + 1e-12),
                "{target}: {} > {}",
                path.length,
                path.traced_length
            ),
            Err(geotracks::Error::Unreachable { .. }) => {}
            Err(e) => panic!("{e}"),
        }
    }
}
