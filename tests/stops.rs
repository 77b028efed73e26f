//! The stop rules at every surface point, not only at nodes: after a run stopped at a
//! maximum distance or at its targets, the distance at any point is either `inf` or
//! the value a full run gives there, and never beyond the maximum; the targets' values
//! are final; and a point well inside the maximum is reached. Goal-directed runs (the
//! default with targets, for the Steiner-graph engines) settle in another order: the
//! same values to rounding (1e-9 relative).

mod common;

use common::{random_mesh, random_surface_point, sphere, Rng};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{Euclidean, Method, Options, Solver, Source, Stop, SurfacePoint};
use proptest::prelude::*;

/// Runs `sources` on `mesh` with a full run and with `stop`, and checks `queries`.
fn check(
    mesh: &TriMesh,
    method: Method,
    k: f64,
    sources: &[Source],
    stop: &Stop,
    queries: &[SurfacePoint],
) -> Result<(), TestCaseError> {
    // Values that may differ by rounding (a goal-directed run adds costs up along
    // the same paths in another order, and may take another of two equal paths).
    let rounding = if stop.goal_directed && !stop.targets.is_empty() {
        1e-9
    } else {
        0.0
    };
    let same = |a: f64, b: f64| a == b || (a - b).abs() <= rounding * b.abs().max(1.0);
    let options = Options::DEFAULT.with_method(method).with_k(k);
    let solver = Solver::new(mesh, Euclidean, &options).unwrap();
    let full = solver
        .field(Sources::from(sources).until(&Stop::NONE))
        .unwrap();
    let stopped = solver.field(Sources::from(sources).until(stop)).unwrap();
    let (full, stopped) = (full, stopped);
    let longest = (0..mesh.edge_count() as u32)
        .map(|e| mesh.edge_length(e))
        .fold(0.0, f64::max);
    for &point in queries.iter().chain(&stop.targets) {
        let (a, b) = (
            stopped.distance_at(point).unwrap(),
            full.distance_at(point).unwrap(),
        );
        if a.is_finite() {
            prop_assert!(
                same(a, b),
                "{:?} at {}: stopped {}, full {}",
                method,
                point,
                a,
                b
            );
            prop_assert!(
                a <= stop.max_distance,
                "{:?} at {}: {} beyond",
                method,
                point,
                a
            );
        } else if stop.targets.is_empty() {
            // Only the points within about an edge of the maximum may be left out (the
            // wavefront engine's: a node beyond it may carry a wave that gives less);
            // the Steiner-graph engines' values at a point come from its face's nodes,
            // each adding a cost ≥ 0, so none within it.
            let margin = if method == Method::Wave {
                2.0 * longest
            } else {
                0.0
            };
            prop_assert!(
                b > stop.max_distance - margin,
                "{:?} at {}: unreached, full {} (max {})",
                method,
                point,
                b,
                stop.max_distance
            );
        }
    }
    for &target in &stop.targets {
        let (a, b) = (
            stopped.distance_at(target).unwrap(),
            full.distance_at(target).unwrap(),
        );
        // (A target whose faces reach beyond the maximum may need nodes beyond it.)
        if b <= stop.max_distance - 2.0 * longest {
            prop_assert!(
                same(a, b),
                "{:?}: target {} not final: {} against {}",
                method,
                target,
                a,
                b
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn stopped_runs_agree_with_full_runs_at_every_point(
        seed in any::<u64>(),
        shape in 0u8..2,
        k in 1u32..5,
        stop in 0u8..4,
    ) {
        let mut rng = Rng(seed | 1);
        let mesh = match shape {
            0 => sphere(2, 0.1, seed),
            _ => match random_mesh(seed, 6) {
                Ok(mesh) => mesh,
                Err(_) => return Ok(()),
            },
        };
        let sources: Vec<Source> = (0..1 + rng.below(2))
            .map(|_| Source::new(random_surface_point(&mesh, &mut rng)).with_start(rng.next() - 0.5))
            .collect();
        let queries: Vec<SurfacePoint> = (0..60).map(|_| random_surface_point(&mesh, &mut rng)).collect();
        let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
        let far = solver
            .field(Sources::from(&sources).until(&Stop::NONE))
            .unwrap()
            .node_distances()
            .iter()
            .copied()
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max);
        // A maximum below every source's start is refused (nothing would be reached):
        // draw maxima between the least start and the farthest value.
        let lowest = sources.iter().map(|s| s.start).fold(f64::INFINITY, f64::min);
        let within = |t: f64| lowest + t * (far - lowest).max(0.0);
        let stop = match stop {
            0 => Stop::NONE.with_max_distance(within(rng.next())),
            1 => Stop::NONE.with_targets((0..1 + rng.below(3)).map(|_| random_surface_point(&mesh, &mut rng)).collect()),
            2 => Stop::NONE
                .with_max_distance(((0.5 + rng.next()) * far).max(lowest))
                .with_targets(vec![random_surface_point(&mesh, &mut rng)]),
            // Targets that may lie beyond the maximum: a goal-directed run leaves out
            // the nodes whose key (value plus estimate) is beyond it.
            _ => Stop::NONE
                .with_max_distance(within(rng.next()))
                .with_targets((0..1 + rng.below(2)).map(|_| random_surface_point(&mesh, &mut rng)).collect()),
        };
        for method in [Method::Wave, Method::Tracks, Method::Graph] {
            let plain = stop.clone().with_goal_directed(false);
            check(&mesh, method, k as f64, &sources, &plain, &queries)?;
            check(&mesh, method, k as f64, &sources, &stop, &queries)?;
        }
    }
}

/// A case found while hardening the input checks: with a maximum distance, a point of a face
/// that the maximum cuts, next to its vertex beyond the maximum, was given the value
/// through a node within it: a value beyond the maximum.
/// A negative maximum distance is refused (it used to leave every node unreached,
/// the sources included), by every engine, as is NaN; 0 reaches the sources only.
#[test]
fn a_negative_maximum_distance_is_refused() {
    let mesh = common::grid(2, 1.0);
    for method in [
        Method::Wave,
        Method::Tracks,
        Method::Graph,
        Method::Dijkstra,
    ] {
        let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_method(method)).unwrap();
        for bad in [-1.0, -1e-300, f64::NEG_INFINITY, f64::NAN] {
            let err = solver
                .field(Sources::from(&[Source::new(0)]).until(Stop::NONE.with_max_distance(bad)))
                .err()
                .unwrap_or_else(|| panic!("{method}: max distance {bad} accepted"));
            assert!(
                matches!(
                    err,
                    geotracks::Error::InvalidValue {
                        which: geotracks::ValueRole::MaxDistance,
                        ..
                    }
                ) && err.to_string().contains("must be a number >= 0"),
                "{method}: {err}"
            );
        }
        let field = solver
            .field(Sources::from(&[Source::new(0)]).until(Stop::NONE.with_max_distance(0.0)))
            .unwrap();
        assert_eq!(field.vertex_distances()[0], 0.0, "{method}");
    }
}

#[test]
fn a_point_beyond_the_maximum_is_unreached() {
    let mesh = common::grid(4, 4.0);
    for method in [Method::Wave, Method::Tracks, Method::Graph] {
        let options = Options::DEFAULT.with_method(method).with_k(1.0);
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let full = solver.field(&[0]).unwrap();
        let query = &full;
        let max = 2.5;
        let bounded = solver
            .field(Sources::from(&[Source::new(0)]).until(Stop::NONE.with_max_distance(max)))
            .unwrap();
        let bounded_query = bounded;
        let mut cut_faces = 0;
        for (face, triangle) in mesh.triangles().iter().enumerate() {
            let values = triangle.map(|v| full.distance(v));
            let Some(far) = (0..3).find(|&i| values[i] > max) else {
                continue;
            };
            if values.iter().all(|&d| d > max) {
                continue;
            }
            cut_faces += 1;
            let mut bary = [0.01; 3];
            bary[far] = 0.98;
            let point = SurfacePoint::Face {
                face: face as u32,
                bary,
            };
            let value = query.distance_at(point).unwrap();
            let bounded_value = bounded_query.distance_at(point).unwrap();
            assert!(value > max, "{method:?}: {value} at {point}");
            assert_eq!(bounded_value, f64::INFINITY, "{method:?} at {point}");
            assert!(bounded_query.trace(point).is_err());
        }
        assert!(cut_faces > 0);
    }
}
