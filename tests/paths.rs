//! Surface-point sources, early stops, distances at any point and geodesic paths.

// Tests aside from the function-length rule (clippy.toml): a scenario reads best whole.
#![allow(clippy::too_many_lines)]

mod common;

use common::{book, grid, random_book, random_face_point, random_mesh, sphere, Rng, GRAPH, TRACKS};
use geotracks::glam::DVec3;
use geotracks::mesh::{io::read_mesh, TriMesh};
use geotracks::Sources;
use geotracks::{
    Density, Error, Euclidean, Field, GeodesicPath, Method, Metric, Options, PointError, PointRole,
    Solver, Source, Stop, SurfacePoint, Tensor, ValueRole,
};

fn spot() -> TriMesh {
    read_mesh(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj")).unwrap()
}

fn random_edge_point(mesh: &TriMesh, rng: &mut Rng) -> SurfacePoint {
    SurfacePoint::Edge {
        edge: rng.below(mesh.edge_count()) as u32,
        t: 0.05 + 0.9 * rng.next(),
    }
}

/// Everything a path must satisfy, whatever the mesh and metric.
fn check_path<M: Metric>(query: &Field<M>, target: SurfacePoint, path: &GeodesicPath) {
    let (mesh, metric) = (query.mesh(), query.metric());
    let target = target.validated(mesh).unwrap();
    assert_eq!(path.points[0], target, "the path starts at the target");
    let source = query.sources()[path.source as usize].point;
    let end = path.points.last().unwrap();
    assert!(
        (end.position(mesh) - source.position(mesh)).length() < 1e-12,
        "the path ends at its source: {end} vs {source}"
    );
    assert_eq!(path.faces.len() + 1, path.points.len());
    for (i, &f) in path.faces.iter().enumerate() {
        for p in [path.points[i], path.points[i + 1]] {
            assert!(
                p.bary_in(mesh, f).is_some(),
                "segment {i}: {p} is not on face {f}"
            );
        }
    }
    let sum: f64 = path.segment_costs(mesh, metric).iter().sum();
    assert!((sum - path.length).abs() <= 1e-12 * sum.max(1.0));
    assert!(path.length <= path.traced_length * (1.0 + 1e-12));
    let d = query.distance_at(target).unwrap();
    let start = query.sources()[path.source as usize].start;
    if query.method() == Method::Wave {
        // A traced path follows the waves' straight lines: as long as the value it
        // explains, or longer where the wave that gave a vertex its value was since
        // replaced by an equal one that does not reach it, or shorter where it passes a
        // vertex whose own value beats the wave's there (a real path: the value
        // overestimates by that much, within the engine's error); straightening then
        // takes it to the geodesic.
        assert!(
            start + path.traced_length >= d * (1.0 - 1e-2),
            "traced {} far below distance {d}, straightened {}, target {target}",
            path.traced_length,
            path.length
        );
        assert!(
            start + path.length <= d * (1.0 + 1e-4),
            "straightened {} vs distance {d}",
            path.length
        );
    } else {
        assert!(
            (start + path.traced_length - d).abs() <= 1e-9 * d.max(1e-300),
            "traced {} vs distance {d}",
            path.traced_length
        );
    }
}

#[test]
fn paths_from_any_point_to_any_source_are_consistent() {
    let mesh = spot();
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let mut rng = Rng(7);
    for round in 0..6 {
        let sources = [
            Source::new(random_face_point(&mesh, &mut rng)),
            Source::new(random_edge_point(&mesh, &mut rng)).with_start(0.05),
            Source::new(rng.below(mesh.vertex_count()) as u32),
        ];
        let field = solver
            .field(Sources::from(&sources[..1 + round % 3]).until(&Stop::NONE))
            .unwrap();
        let query = &field;
        for _ in 0..8 {
            let target = match rng.below(3) {
                0 => random_face_point(&mesh, &mut rng),
                1 => random_edge_point(&mesh, &mut rng),
                _ => SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32),
            };
            let path = query.path(target).unwrap();
            check_path(query, target, &path);
            let traced = query.trace(target).unwrap();
            assert_eq!(traced.length, path.traced_length);
        }
    }
}

#[test]
fn paths_under_a_tensor_metric_and_on_non_manifold_meshes() {
    let mut rng = Rng(11);
    for seed in 0..6u64 {
        let mesh = if seed % 2 == 0 {
            random_book(seed, 4, 3)
        } else {
            random_mesh(seed, 6).unwrap()
        };
        let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
            .map(|f| {
                let angle = f as f64 * 0.7;
                (1.0 + (f % 5) as f64, 1.0, [angle.cos(), angle.sin(), 0.3])
            })
            .collect();
        let metric = Tensor::from_principal(&mesh, &principal).unwrap();
        let solver = Solver::new(&mesh, &metric, &Options::DEFAULT.with_k(3.0)).unwrap();
        let source = Source::new(random_face_point(&mesh, &mut rng));
        let field = solver
            .field(Sources::from(&[source]).until(&Stop::NONE))
            .unwrap();
        let query = &field;
        for _ in 0..10 {
            let target = random_face_point(&mesh, &mut rng);
            match query.path(target) {
                Ok(path) => check_path(query, target, &path),
                Err(Error::Unreachable { .. }) => {
                    assert!(query.distance_at(target).unwrap().is_infinite())
                }
                Err(e) => panic!("{e}"),
            }
        }
    }
}

#[test]
fn a_path_on_a_flat_grid_is_a_straight_line() {
    let mesh = grid(12, 1.0);
    let solver = Solver::new(&mesh, Euclidean, &TRACKS.with_k(3.0)).unwrap();
    let field = solver
        .field(
            Sources::from(&[Source::new(
                SurfacePoint::nearest(&mesh, [0.07, 0.11, 0.0]).unwrap(),
            )])
            .until(&Stop::NONE),
        )
        .unwrap();
    let mut rng = Rng(3);
    for _ in 0..10 {
        let xyz = [0.1 + 0.85 * rng.next(), 0.1 + 0.85 * rng.next(), 0.0];
        let target = SurfacePoint::nearest(&mesh, xyz).unwrap();
        let path = field.path(target).unwrap();
        let (a, b) = (DVec3::new(0.07, 0.11, 0.0), DVec3::from(xyz));
        if std::env::var("DUMP").is_ok() {
            for (i, p) in path.points.iter().enumerate() {
                eprintln!("{p} {:?} {:?}", p.position(&mesh), path.faces.get(i));
            }
        }
        let straight = a.distance(b);
        assert!(
            (path.length - straight).abs() <= 1e-6 * straight,
            "length {} vs {straight}",
            path.length
        );
        for p in path.positions(&mesh) {
            let off_line = (p - a).cross((b - a).normalize()).length();
            assert!(off_line < 1e-6, "{p} is {off_line} off the line");
        }
        assert!(
            path.traced_length > path.length,
            "the traced path zigzags a little"
        );
    }
}

#[test]
fn a_path_between_pages_crosses_the_spine_where_the_unfolding_says() {
    // Three pages of a book; two of them are 90° apart... unfolded flat, the path from a
    // point on page 0 to a point on page 1 is a straight line across the spine.
    let (mesh, _) = book(3, 1.0, 1.0, 6);
    let on_page = |page: usize, r: f64, z: f64| {
        let angle = std::f64::consts::TAU * page as f64 / 3.0;
        SurfacePoint::nearest(&mesh, [r * angle.cos(), r * angle.sin(), z]).unwrap()
    };
    let (source, target) = ((0.6, 0.2), (0.3, 0.85));
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver
        .field(Sources::from(&[Source::new(on_page(0, source.0, source.1))]).until(&Stop::NONE))
        .unwrap();
    let path = field.path(on_page(1, target.0, target.1)).unwrap();
    // Unfolded: source at (−0.6, 0.2), target at (0.3, 0.85); the spine is x = 0.
    let z_cross = source.1 + (target.1 - source.1) * source.0 / (source.0 + target.0);
    let exact = ((source.0 + target.0).powi(2) + (target.1 - source.1).powi(2)).sqrt();
    assert!(
        (path.length - exact).abs() < 1e-6 * exact,
        "{} vs {exact}",
        path.length
    );
    let on_spine: Vec<DVec3> = path
        .positions(&mesh)
        .into_iter()
        .filter(|p| p.x.hypot(p.y) < 1e-9)
        .collect();
    assert!(!on_spine.is_empty(), "the path crosses the spine");
    for p in on_spine {
        assert!(
            (p.z - z_cross).abs() < 1e-6,
            "crosses at z = {}, not {z_cross}",
            p.z
        );
    }
}

/// A regular triangular prism (unit edges, height `h`): bottom and top triangles, and
/// each side a rectangle of two triangles.
fn prism(h: f64) -> (TriMesh, [DVec3; 3]) {
    let base = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0),
    ];
    let mut positions: Vec<[f64; 3]> = base.iter().map(|p| p.to_array()).collect();
    positions.extend(base.iter().map(|p| [p.x, p.y, h]));
    let mut triangles = vec![[0, 2, 1], [3, 4, 5]];
    for i in 0..3u32 {
        let j = (i + 1) % 3;
        triangles.push([i, j, j + 3]);
        triangles.push([i, j + 3, i + 3]);
    }
    (TriMesh::new(positions, triangles).unwrap(), base)
}

/// The paper's Fig. 9: a source inside the bottom face, targets on the top face near a
/// ridge. The exact path crosses the side under the ridge: unfolded, a straight line.
#[test]
fn prism_paths_match_the_unfolding() {
    let h = 0.8;
    let (mesh, base) = prism(h);
    let source_xy = (base[0] + base[1] + base[2]) / 3.0;
    let source = SurfacePoint::nearest(&mesh, [source_xy.x, source_xy.y, 0.0]).unwrap();
    assert!(matches!(source, SurfacePoint::Face { .. }));
    let solvers =
        [Options::DEFAULT, common::DIJKSTRA].map(|o| Solver::new(&mesh, Euclidean, &o).unwrap());
    let fields: Vec<geotracks::Field<Euclidean>> = solvers
        .iter()
        .map(|s| {
            s.field(Sources::from(&[Source::new(source)]).until(&Stop::NONE))
                .unwrap()
        })
        .collect();
    let tracks = &fields[0];
    let dijkstra = &fields[1];
    let mut worst_dijkstra: f64 = 0.0;
    for (u, e) in [(0.5, 0.05), (0.3, 0.08), (0.65, 0.03), (0.45, 0.12)] {
        // Near the ridge over the edge from base[0] to base[1] (y = 0), `e` inside.
        let target = SurfacePoint::nearest(&mesh, [u, e, h]).unwrap();
        // Unfolded across the side y = 0: the top face lies beyond it.
        let exact = ((u - source_xy.x).powi(2) + (source_xy.y + h + e).powi(2)).sqrt();
        let path = tracks.path(target).unwrap();
        check_path(tracks, target, &path);
        assert!(
            (path.length - exact).abs() <= 0.005 * exact,
            "tracks path {} vs exact {exact}",
            path.length
        );
        let vertex_path = dijkstra.trace(target).unwrap();
        worst_dijkstra = worst_dijkstra.max((vertex_path.length - exact) / exact);
    }
    // Following vertex values alone goes astray.
    assert!(
        worst_dijkstra > 0.05,
        "dijkstra path excess {worst_dijkstra}"
    );
}

#[test]
fn face_and_edge_sources_give_the_graphs_distances() {
    let mut rng = Rng(5);
    for seed in 0..12u64 {
        let mesh = match seed % 3 {
            0 => random_mesh(seed, 5).unwrap(),
            1 => sphere(1, 0.3, seed),
            _ => random_book(seed, 5, 3),
        };
        let sources = [
            Source::new(random_face_point(&mesh, &mut rng)),
            Source::new(random_edge_point(&mesh, &mut rng)).with_start(0.3 * rng.next()),
        ];
        let options = TRACKS.with_k(1.0 + (seed % 5) as f64);
        let [tracks, graph] = [options, GRAPH.with_k(options.steiner.unwrap().k())].map(|o| {
            Solver::new(&mesh, Euclidean, &o)
                .unwrap()
                .field(Sources::from(&sources).until(&Stop::NONE))
                .unwrap()
        });
        for (a, b) in tracks.node_distances().iter().zip(graph.node_distances()) {
            assert!(
                a == b || (a - b).abs() <= 1e-9 * b,
                "seed {seed}: tracks {a} vs graph {b}"
            );
        }
    }
}

#[test]
fn many_sources_with_start_values_are_the_minimum_and_label_vertices() {
    let mesh = spot();
    // The Steiner graph's distances from several sources are the least of each one's
    // (the wavefront engine keeps one wave per node, so near where two sources' waves
    // meet it is only close to that: tests/wave.rs).
    let solver = Solver::new(&mesh, Euclidean, &TRACKS).unwrap();
    let sources = [
        Source::new(10),
        Source::new(SurfacePoint::Face {
            face: 500,
            bary: [0.2, 0.3, 0.5],
        })
        .with_start(0.1),
        Source::new(SurfacePoint::Edge { edge: 900, t: 0.4 }).with_start(0.05),
    ];
    let together = solver
        .field(Sources::from(&sources).until(&Stop::NONE))
        .unwrap();
    let alone: Vec<geotracks::Field<Euclidean>> = sources
        .iter()
        .map(|s| {
            solver
                .field(Sources::from(&[*s]).until(&Stop::NONE))
                .unwrap()
        })
        .collect();
    let query = &together;
    let labels = query.vertex_labels();
    let mut seen = [false; 3];
    for (v, &label) in labels.iter().enumerate() {
        let each: Vec<f64> = alone.iter().map(|f| f.distance(v as u32)).collect();
        let best = each.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((together.distance(v as u32) - best).abs() <= 1e-12 * best.max(1.0));
        let label = label as usize;
        assert!(
            (each[label] - best).abs() <= 1e-9 * best.max(1.0),
            "vertex {v} labelled {label}"
        );
        seen[label] = true;
    }
    assert_eq!(seen, [true; 3], "every source owns some vertices");
    // A path ends at the source that labels its start.
    let v = (0..mesh.vertex_count() as u32)
        .find(|&v| labels[v as usize] == 1)
        .unwrap();
    let path = query.path(v).unwrap();
    assert_eq!(path.source, 1);
}

#[test]
fn early_stops_keep_the_full_runs_values() {
    let mesh = spot();
    let source = [Source::new(SurfacePoint::Face {
        face: 100,
        bary: [0.3, 0.3, 0.4],
    })];
    for options in [Options::DEFAULT, GRAPH] {
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let full = solver
            .field(Sources::from(&source).until(&Stop::NONE))
            .unwrap();
        let far = full.node_distances().iter().copied().fold(0.0f64, f64::max);
        let max = 0.3 * far;
        let mut ws = solver.workspace();
        let bounded = solver
            .run(
                &mut ws,
                Sources::from(&source).until(Stop::NONE.with_max_distance(max)),
            )
            .unwrap();
        let mut reached = 0;
        for (a, b) in bounded.node_distances().iter().zip(full.node_distances()) {
            if *b <= max {
                assert_eq!(a, b);
                reached += 1;
            } else {
                assert!(a.is_infinite());
            }
        }
        assert!(reached > 0);
        assert!(bounded.stats().distance_tests < full.stats().distance_tests / 2);

        // Targets at about a fifth of the farthest distance.
        let near = (0..mesh.vertex_count() as u32)
            .find(|&v| (full.distance(v) - 0.2 * far).abs() < 0.02 * far)
            .unwrap();
        let targets = vec![
            SurfacePoint::Vertex(near),
            SurfacePoint::Face {
                face: mesh.vertex_faces(near)[0],
                bary: [0.1, 0.1, 0.8],
            },
        ];
        let stats = solver
            .run(
                &mut ws,
                Sources::from(&source).until(Stop::NONE.with_targets(targets.clone())),
            )
            .unwrap()
            .stats()
            .clone();
        assert!(stats.stopped_early);
        assert!(stats.distance_tests < full.stats().distance_tests);
        let mut finite = 0;
        for (a, b) in ws.node_distances().iter().zip(full.node_distances()) {
            if a.is_finite() {
                assert_eq!(a, b);
                finite += 1;
            }
        }
        assert!(finite < ws.node_distances().len() / 2);
        let stopped = solver
            .run(
                &mut ws,
                Sources::from(&source).until(Stop::NONE.with_targets(targets.clone())),
            )
            .unwrap();
        for t in targets {
            assert_eq!(
                stopped.distance_at(t).unwrap(),
                full.distance_at(t).unwrap()
            );
            assert_eq!(stopped.path(t).unwrap(), full.path(t).unwrap());
        }
    }
}

#[test]
fn bad_points_and_unreachable_targets_are_errors() {
    let mesh = spot();
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let mut ws = solver.workspace();
    let run = |ws: &mut geotracks::Workspace, point: SurfacePoint| {
        solver
            .run(ws, Sources::from(&[Source::new(point)]).until(&Stop::NONE))
            .map(|run| run.stats().clone())
    };
    let faces = mesh.face_count() as u32;
    match run(
        &mut ws,
        SurfacePoint::Face {
            face: faces,
            bary: [1.0, 0.0, 0.0],
        },
    ) {
        Err(Error::InvalidPoint {
            which: PointRole::Source(0),
            error: PointError::NoSuchFace { face, .. },
        }) => assert_eq!(face, faces),
        other => panic!("{other:?}"),
    }
    let err = run(
        &mut ws,
        SurfacePoint::Face {
            face: 0,
            bary: [0.5, 0.5, 0.5],
        },
    )
    .unwrap_err();
    assert!(err.to_string().contains("sum to 1.5"), "{err}");
    let err = run(&mut ws, SurfacePoint::Vertex(u32::MAX)).unwrap_err();
    assert!(matches!(err, Error::SourceOutOfRange { .. }));
    let start = solver
        .run(
            &mut ws,
            Sources::from(&[Source::new(0).with_start(f64::NAN)]).until(&Stop::NONE),
        )
        .unwrap_err();
    assert!(matches!(
        start,
        Error::InvalidValue {
            which: ValueRole::Start { source: 0 },
            ..
        }
    ));
    // A start so large that distances could overflow (a start plus the mesh's costs
    // beyond the f64 range), on a second source: refused. A huge negative start, or a
    // start that rounding keeps finite, is a start like any other.
    let huge = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1e300, 0.0, 0.0], [0.0, 1e300, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let huge_solver = Solver::new(&huge, Euclidean, &Options::DEFAULT).unwrap();
    let mut huge_ws = huge_solver.workspace();
    let sources = [Source::new(0), Source::new(1).with_start(f64::MAX)];
    match huge_solver.run(&mut huge_ws, Sources::from(&sources).until(&Stop::NONE)) {
        Err(Error::StartTooLarge {
            index: 1,
            cost_total,
            ..
        }) => assert!(cost_total > 1e300 && cost_total.is_finite()),
        other => panic!("{other:?}"),
    }
    for start in [-f64::MAX, 1e307] {
        let sources = [Source::new(0).with_start(start)];
        huge_solver
            .run(&mut huge_ws, Sources::from(&sources).until(&Stop::NONE))
            .unwrap();
        assert_eq!(huge_ws.vertex_distances()[0], start);
        assert!(huge_ws.vertex_distances().iter().all(|d| d.is_finite()));
    }
    let top = [Source::new(0).with_start(f64::MAX)];
    solver
        .run(&mut ws, Sources::from(&top).until(&Stop::NONE))
        .unwrap();
    assert!(ws.vertex_distances().iter().all(|&d| d == f64::MAX));
    let stop = Stop::NONE.with_targets(vec![SurfacePoint::Edge { edge: 0, t: 2.0 }]);
    let err = solver
        .run(&mut ws, Sources::from(&[Source::new(0)]).until(&stop))
        .unwrap_err();
    assert!(err.to_string().starts_with("target 0:"), "{err}");
    assert!(matches!(
        err,
        Error::InvalidPoint {
            which: PointRole::Target(0),
            ..
        }
    ));

    // Two components: the second is unreachable, by distance and by path.
    let two = common::two_islands();
    let two_solver = Solver::new(&two, Euclidean, &Options::DEFAULT).unwrap();
    let field = two_solver.field(&[0]).unwrap();
    let query = &field;
    let far = SurfacePoint::Face {
        face: 1,
        bary: [0.3, 0.3, 0.4],
    };
    assert!(query.distance_at(far).unwrap().is_infinite());
    assert!(matches!(query.path(far), Err(Error::Unreachable { point }) if point == far));
    // A field's data given to a solver on another mesh.
    let other = Solver::new(spot(), Euclidean, &Options::DEFAULT).unwrap();
    assert!(matches!(
        other.attach(field.into_data()),
        Err(Error::ForeignField)
    ));
}

/// A field is queried only with the solver that computed it: it carries it, so another
/// metric on the same mesh cannot be used (before, `field.distance_at(&mesh,
/// &other_metric, p)` gave a silently wrong value, and only the mesh's counts were
/// compared); its plain data is given back its queries only by that solver (or a clone).
#[test]
fn a_field_is_queried_only_through_its_own_solver() {
    let mesh = spot();
    let euclidean = Solver::new(&mesh, Euclidean, &TRACKS).unwrap();
    let doubled = Density::constant(&mesh, 2.0).unwrap();
    let dense = Solver::new(&mesh, &doubled, &TRACKS).unwrap();
    let target = SurfacePoint::Face {
        face: 7,
        bary: [0.2, 0.3, 0.5],
    };
    let field = euclidean.field(0).unwrap();
    let d = field.distance_at(target).unwrap();
    let d2 = dense.field(0).unwrap().distance_at(target).unwrap();
    assert!((d2 - 2.0 * d).abs() < 1e-9 * d);
    // Plain data: refused by another metric's solver on the same mesh and layout, and
    // by another solver with the same mesh, metric and options (it cannot tell);
    // given back by its own solver and by a clone of it.
    let data = field.into_data();
    assert!(matches!(
        dense.attach(data.clone()),
        Err(Error::ForeignField)
    ));
    let twin = Solver::new(&mesh, Euclidean, &TRACKS).unwrap();
    assert!(matches!(
        twin.attach(data.clone()),
        Err(Error::ForeignField)
    ));
    let back = euclidean.clone().attach(data).unwrap();
    assert_eq!(back.distance_at(target).unwrap(), d);

    // A workspace's field: the last run's, whichever solver ran in it before.
    let mut ws = euclidean.workspace();
    dense.run(&mut ws, 0).unwrap();
    assert!(dense.run(&mut ws, u32::MAX).is_err());
    let from_ws = euclidean
        .run(&mut ws, 0)
        .unwrap()
        .distance_at(target)
        .unwrap();
    assert_eq!(from_ws, d);
    assert_eq!(
        euclidean
            .run(&mut ws, 0)
            .unwrap()
            .to_owned()
            .distance_at(target)
            .unwrap(),
        d
    );
}
