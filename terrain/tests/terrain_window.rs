//! Routes on a window of the grid (`route_on_grid`) against routes on the whole grid's
//! mesh: the Steiner-graph engines must give the same cost (the window's graph is the
//! grid's, cut down to where a cheaper route could go), under every terrain cost, with
//! NODATA holes, walls and detours that make the first window too narrow.

#[path = "../../tests/common/mod.rs"]
mod common;

use common::Rng;
use geotracks::Sources;
use geotracks::{Error, Method, Metric, Options, Solver, Source, Stop};
use geotracks_terrain::{
    route_on_grid, ElevationGrid, GridGeometry, TerrainCost, TerrainError, TerrainMesh,
};
use proptest::prelude::*;

fn geometry(n: usize) -> GridGeometry {
    GridGeometry {
        ncols: n,
        nrows: n,
        lower_left: [0.0, 0.0],
        spacing: [1.0, 1.0],
    }
}

/// Rolling hills with bumps, `relief` high, and a fraction `holes` of NODATA samples.
fn hilly(n: usize, seed: u64, relief: f64, holes: f64) -> ElevationGrid {
    let mut rng = Rng(seed | 1);
    let (a, b, c) = (rng.next() * 0.5, rng.next() * 0.5, rng.next() * 6.0);
    let noise: Vec<(f64, bool)> = (0..n * n)
        .map(|_| (rng.next(), rng.next() < holes))
        .collect();
    ElevationGrid::from_fn(geometry(n), |x, y| {
        let (i, j) = (x.round() as usize, y.round() as usize);
        let (bump, hole) = noise[(j * n + i).min(n * n - 1)];
        (!hole).then(|| relief * ((a * x).sin() * (b * y + c).cos() + 0.3 * bump))
    })
    .unwrap()
}

/// The route's Steiner-graph cost on the whole grid's mesh, with the grid's spacing: a
/// full run from the start (one-ended, whatever the window's run does).
fn whole_grid_cost(
    grid: &ElevationGrid,
    cost: &TerrainCost,
    options: &Options,
    from: [f64; 2],
    to: [f64; 2],
) -> Result<f64, TerrainError> {
    let terrain = grid.to_mesh()?;
    let metric = cost.metric(&terrain.mesh)?;
    let options = options.with_mean_edge_length(grid.mean_edge_length().unwrap());
    let solver = Solver::new(&terrain.mesh, metric, &options)?;
    let (a, b) = (
        terrain.locate(from[0], from[1])?,
        terrain.locate(to[0], to[1])?,
    );
    let field = solver.field(Sources::from(&[Source::new(a)]).until(&Stop::NONE))?;
    Ok(field.trace(b)?.traced_length)
}

const COSTS: [&str; 8] = [
    "none",
    "slope:4",
    "slope:2,max:25",
    "incline:3",
    "uphill:5",
    "naismith",
    "tobler",
    "rwalk",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn a_windows_route_costs_what_the_whole_grids_does(
        seed in any::<u64>(),
        n in 12usize..40,
        relief in 0.0f64..6.0,
        holes in 0.0f64..0.08,
        which in 0usize..8,
        graph in any::<bool>(),
        k in 1u32..4,
        ends in prop::array::uniform4(0.0f64..1.0),
    ) {
        let grid = hilly(n, seed, relief, holes);
        let cost: TerrainCost = COSTS[which].parse().unwrap();
        let method = if graph { Method::Graph } else { Method::Tracks };
        let options = Options::DEFAULT.with_k(k as f64).with_method(method);
        // Routes over a third of the grid at most, so that windows cut.
        let at = |u: f64, v: f64| [0.1 + (n - 1) as f64 * (0.3 + 0.3 * u), (n - 1) as f64 * (0.2 + 0.3 * v)];
        let (from, to) = (at(ends[0], ends[1]), at(ends[2], ends[3]));
        let whole = whole_grid_cost(&grid, &cost, &options, from, to);
        match (route_on_grid(&grid, &cost, &options, from, to), whole) {
            (Ok(w), Ok(c)) => {
                let deviation = (w.route.traced_cost - c).abs() / c.max(1e-300);
                prop_assert!(deviation <= 1e-9, "{}: window {} ({:?}) against {}", COSTS[which], w.route.traced_cost, w.window, c);
                prop_assert!(w.window.cells <= w.window.grid_cells);
            }
            (Err(TerrainError::Engine(Error::Unreachable { .. })), Err(TerrainError::Engine(Error::Unreachable { .. }))) => {}
            (Err(TerrainError::NoData { .. }), Err(TerrainError::NoData { .. })) => {}
            (w, c) => prop_assert!(false, "window {:?} against whole {:?}", w.map(|w| w.route.traced_cost), c),
        }
    }
}

/// A ridge of faces too steep to cross, with a gap far from the straight line: the
/// first window (10 % above the straight line's cost) holds no route as cheap as its
/// bound, nor do the next ones, until one holds the gap; its route is the grid's.
#[test]
fn a_detour_widens_the_window_and_still_finds_the_grids_route() {
    let n = 61;
    // A wall along x = 30, but for a gap near the top (y ≈ 55).
    let grid = ElevationGrid::from_fn(geometry(n), |x, y| {
        let wall = (x - 30.0).abs() < 0.6 && !(53.0..=57.0).contains(&y);
        Some(if wall { 40.0 } else { 0.0 })
    })
    .unwrap();
    let cost: TerrainCost = "slope:1,max:45".parse().unwrap();
    let options = Options::DEFAULT.with_k(2.0).with_method(Method::Tracks);
    let (from, to) = ([20.0, 10.0], [40.0, 10.0]);
    let w = route_on_grid(&grid, &cost, &options, from, to).unwrap();
    let whole = whole_grid_cost(&grid, &cost, &options, from, to).unwrap();
    assert!(w.window.runs > 2, "{:?}", w.window);
    assert!((w.route.traced_cost - whole).abs() <= 1e-9 * whole);
    // Around the gap: far more than the 20 m straight line.
    assert!(w.route.cost() > 80.0, "{}", w.route.cost());
    // On open ground one run does, over a small part of the grid.
    let w = route_on_grid(&grid, &cost, &options, [5.0, 10.0], [20.0, 30.0]).unwrap();
    assert_eq!(w.window.runs, 1);
    assert!(w.window.cells < w.window.grid_cells / 3, "{:?}", w.window);
}

/// The wavefront engine (the default for `none`): values depend on the order waves
/// meet in, so the window's route may differ from the whole grid's in the last digits;
/// on hills it agrees to 1e-9 here.
#[test]
fn the_wave_engines_window_route_agrees_with_the_whole_grids() {
    let grid = hilly(50, 7, 4.0, 0.0);
    let options = Options::DEFAULT.with_k(2.0);
    for (from, to) in [([5.0, 5.0], [30.0, 22.0]), ([40.0, 8.0], [12.0, 30.5])] {
        let w = route_on_grid(&grid, &TerrainCost::None, &options, from, to).unwrap();
        assert_eq!(w.route.stats.method, Method::Wave);
        let whole = whole_grid_cost(&grid, &TerrainCost::None, &options, from, to).unwrap();
        assert!(
            (w.route.traced_cost - whole).abs() <= 1e-9 * whole,
            "{} against {whole}",
            w.route.traced_cost
        );
        assert!(w.window.cells < w.window.grid_cells / 2, "{:?}", w.window);
    }
}

/// What the window is cut by, found from the samples alone, is what the whole grid's
/// mesh says: the mean edge length (the Steiner spacing) and the least cost per unit
/// length (every face's bound, at least).
#[test]
fn the_grids_mean_edge_and_least_cost_match_its_mesh() {
    for (seed, holes) in [(3, 0.0), (5, 0.1), (9, 0.3)] {
        let grid = hilly(23, seed, 5.0, holes);
        let mesh = grid.to_mesh().unwrap().mesh;
        let edges = mesh.edge_count() as u32;
        let mean = (0..edges).map(|e| mesh.edge_length(e)).sum::<f64>() / edges as f64;
        let from_grid = grid.mean_edge_length().unwrap();
        assert!(
            (from_grid - mean).abs() <= 1e-12 * mean,
            "{from_grid} against {mean}"
        );
        // Kept for the next call; a grid that kept it is still the same grid (one
        // without NODATA: NaN equals nothing).
        assert_eq!(grid.mean_edge_length(), Some(from_grid));
        if holes == 0.0 {
            assert_eq!(grid, hilly(23, seed, 5.0, holes));
        }
        for name in COSTS {
            let cost: TerrainCost = name.parse().unwrap();
            let least = cost.least_cost_per_length(&grid);
            let metric = cost.metric(&mesh).unwrap();
            let faces = metric.min_cost_per_length();
            assert!(least <= faces, "{name}: {least} above the faces' {faces}");
            if name.starts_with("uphill") || matches!(name, "naismith" | "tobler" | "rwalk") {
                // The bound at the steepest face is the least of all faces'.
                assert!(
                    least >= faces * (1.0 - 1e-8),
                    "{name}: {least} against {faces}"
                );
            }
        }
    }
}

/// A window's mesh is the whole grid's cut to the kept cells: each kept cell has the
/// same triangles at the same places, every other cell none; a sample is a vertex
/// exactly when a kept cell's triangle has it; points in kept cells are located on
/// the same spot. Also for windows one cell wide, or along the grid's edges, whose
/// maps cover their own box only.
#[test]
fn a_windows_mesh_is_the_grids_cut_to_its_cells() {
    let grid = hilly(17, 7, 4.0, 0.15);
    let g = *grid.geometry();
    let whole = grid.to_mesh().unwrap();
    let corners = |m: &TerrainMesh, f: u32| m.mesh.face_vertices(f).map(|v| m.mesh.position(v));
    let mut rng = Rng(11);
    let windows = [
        (0..16, 0..16),
        (3..4, 0..16),
        (0..16, 15..16),
        (5..9, 2..12),
        (15..16, 14..16),
    ];
    for (cols, rows) in windows {
        let kept: Vec<bool> = (0..16 * 16).map(|_| rng.next() < 0.8).collect();
        let keep = |c: usize, r: usize| kept[r * 16 + c];
        let in_window = |c: usize, r: usize| cols.contains(&c) && rows.contains(&r) && keep(c, r);
        let window = grid
            .to_mesh_within(cols.clone(), rows.clone(), keep)
            .unwrap();
        for r in 0..g.nrows - 1 {
            for c in 0..g.ncols - 1 {
                let faces: Vec<u32> = window.cell_faces(c, r).collect();
                if !in_window(c, r) {
                    assert!(faces.is_empty(), "cell ({c}, {r}) outside the window");
                    continue;
                }
                let expected: Vec<u32> = whole.cell_faces(c, r).collect();
                assert_eq!(faces.len(), expected.len(), "cell ({c}, {r})");
                for (&f, &e) in faces.iter().zip(&expected) {
                    assert_eq!(corners(&window, f), corners(&whole, e));
                }
                if let Some(&f) = expected.first() {
                    // Its first triangle's centroid, located in both meshes.
                    let [a, b, d] = corners(&whole, f);
                    let p = (a + b + d) / 3.0;
                    let at = |m: &TerrainMesh| m.locate(p.x, p.y).unwrap().position(&m.mesh);
                    assert!(at(&window).distance(at(&whole)) < 1e-9);
                }
            }
        }
        for r in 0..g.nrows {
            for c in 0..g.ncols {
                // Whether a kept cell's triangle has the sample as a corner.
                let used = whole.sample_vertex(c, r).is_some_and(|v| {
                    [(0, 0), (1, 0), (0, 1), (1, 1)].iter().any(|&(dc, dr)| {
                        c >= dc
                            && r >= dr
                            && in_window(c - dc, r - dr)
                            && whole
                                .cell_faces(c - dc, r - dr)
                                .any(|f| whole.mesh.face_vertices(f).contains(&v))
                    })
                });
                match window.sample_vertex(c, r) {
                    Some(v) => {
                        assert!(used, "sample ({c}, {r}) is no kept triangle's corner");
                        let w = whole.sample_vertex(c, r).unwrap();
                        assert_eq!(window.mesh.position(v), whole.mesh.position(w));
                    }
                    None => assert!(!used, "sample ({c}, {r}) left out"),
                }
            }
        }
        assert!(window.sample_vertex(g.ncols, 0).is_none());
        assert_eq!(window.cell_faces(g.ncols - 1, 0).count(), 0);
    }
}

#[test]
fn points_off_the_grid_or_on_nodata_and_unreachable_ends_are_errors() {
    let grid = ElevationGrid::from_fn(geometry(30), |x, y| {
        ((x - 20.0).abs() > 3.0 || (y - 20.0).abs() > 3.0).then_some(0.0)
    })
    .unwrap();
    let options = Options::DEFAULT;
    let none = TerrainCost::None;
    match route_on_grid(&grid, &none, &options, [-5.0, 3.0], [10.0, 10.0]) {
        Err(TerrainError::Outside { x, .. }) => assert_eq!(x, -5.0),
        other => panic!("{:?}", other.map(|r| r.window)),
    }
    match route_on_grid(&grid, &none, &options, [3.0, 3.0], [20.0, 20.0]) {
        Err(TerrainError::NoData { x, y }) => assert_eq!((x, y), (20.0, 20.0)),
        other => panic!("{:?}", other.map(|r| r.window)),
    }
    // A wall all around the corner the route starts in: no route.
    let walled = ElevationGrid::from_fn(geometry(30), |x, y| {
        Some(if (x - 8.0).abs() < 0.6 || (y - 8.0).abs() < 0.6 {
            30.0
        } else {
            0.0
        })
    })
    .unwrap();
    let steep: TerrainCost = "slope:1,max:45".parse().unwrap();
    assert!(matches!(
        route_on_grid(&walled, &steep, &options, [3.0, 3.0], [20.0, 20.0]),
        Err(TerrainError::Engine(Error::Unreachable { .. }))
    ));
}
