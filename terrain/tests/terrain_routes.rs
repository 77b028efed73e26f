//! Routes on rough terrain (fractal noise, ridges, cliffs, elevations rounded to whole
//! metres as real elevation models store them) under every terrain cost: searched from
//! both ends, a route's traced cost is the one-ended run's value at its end (the
//! Steiner graph's optimum, to 1e-9), and its straightened cost is never much above
//! that of the one-ended run's path, straightened; and a route does not depend on what
//! else is asked of the run ([`route`] with or without the whole field).
//!
//! Many graph paths can cost the same to the last bit (a walking time charges the map
//! length and the climb, which sum alike along shifted paths on a regular grid; rounded
//! elevations make flats where 3D lengths do too): which of them a search keeps depends
//! on the order it settles nodes in, and each straightens to its own local optimum. The measured spread is printed
//! (`cargo test --release --test terrain_routes -- --nocapture`).

#[path = "../../tests/common/mod.rs"]
mod common;

use common::relief::RoughRelief;
use common::Rng;
use geotracks::Sources;
use geotracks::{Error, Method, Options, Solver, Source, Stop};
use geotracks_terrain::{
    route, route_and_field, route_on_grid, ElevationGrid, GridGeometry, TerrainCost,
};
use proptest::prelude::*;

/// Every terrain cost model, with its parameters.
const COSTS: [&str; 9] = [
    "none",
    "slope:4",
    "slope:3,max:30",
    "incline:6",
    "tobler",
    "tobler:offpath",
    "naismith",
    "uphill:10",
    "rwalk",
];

/// How much dearer the straightened route may be than the one-ended runs' paths
/// straightened: all are Steiner-graph paths of the same cost, each straightened to
/// its own local optimum (see the module docs). Measured over 6 000 cases of this
/// test: the route from both ends came out dearer or cheaper about equally often, by
/// more than 1e-9 in 2.8 % of the cases, by more than 1 % in 0.5 %, by more than 5 %
/// in 0.17 %; at worst 24 % dearer and 15 % cheaper (`rwalk` and `naismith`, at
/// k = 1 and 2 on grids of 10 to 25 cells with up to 150 m of relief per 30 m cell,
/// and cliffs; one case: two graph paths of 528.7 s that straighten to 499.2 s and
/// 429.0 s, on either side of a cliff). The two one-ended runs' paths differ as much
/// (up to 6 %). On 200 × 170 grids of 90 m cells at k = 2: 0.7 % at worst.
const STRAIGHTENED_SPREAD: f64 = 0.3;

/// A rough elevation grid of `ncols` × `nrows` samples `spacing` apart: value noise
/// of five octaves (two of them folded into ridges), a few cliffs (steps of 20 to 60
/// along random lines), rounded to multiples of `quantum` (0: not rounded).
fn rough_grid(seed: u64, ncols: usize, nrows: usize, spacing: f64, quantum: f64) -> ElevationGrid {
    let mut rng = Rng(seed | 1);
    let relief = RoughRelief::new(|| rng.next(), 2, (20.0, 40.0));
    let height = spacing * (1.0 + 4.0 * rng.next());
    let geometry = GridGeometry {
        ncols,
        nrows,
        lower_left: [0.0, 0.0],
        spacing: [spacing, spacing],
    };
    let (w, h) = ((ncols - 1) as f64 * spacing, (nrows - 1) as f64 * spacing);
    ElevationGrid::from_fn(geometry, |x, y| {
        let z = relief.height(x / w, y / h, height);
        Some(if quantum > 0.0 {
            (z / quantum).round() * quantum
        } else {
            z
        })
    })
    .unwrap()
}

/// Whether searches from both ends can run here (two threads in rayon's pool).
fn two_threads() -> bool {
    rayon::current_num_threads() >= 2
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// From both ends (the route's search, on the whole grid and on the window the
    /// command line cuts), from one end goal-directed, and from one end over the whole
    /// grid: the same Steiner-graph value at the route's end, under every cost, and the
    /// straightened routes within [`STRAIGHTENED_SPREAD`] of one another.
    #[test]
    fn from_both_ends_a_route_costs_what_one_end_gives(
        seed in any::<u64>(),
        ncols in 10usize..26,
        nrows in 10usize..26,
        which in 0..COSTS.len(),
        k in 1u32..4,
        graph in any::<bool>(),
        rounded in any::<bool>(),
        ends in prop::array::uniform4(0.0f64..1.0),
    ) {
        let grid = rough_grid(seed, ncols, nrows, 30.0, if rounded { 1.0 } else { 0.0 });
        let terrain = grid.to_mesh().unwrap();
        let cost: TerrainCost = COSTS[which].parse().unwrap();
        let method = if graph { Method::Graph } else { Method::Tracks };
        let options = Options::DEFAULT
            .with_k(k as f64)
            .with_method(method)
            .with_mean_edge_length(grid.mean_edge_length().unwrap());
        let solver = Solver::new(&terrain.mesh, cost.metric(&terrain.mesh).unwrap(), &options).unwrap();
        let [w, h] = [(ncols - 1) as f64 * 30.0, (nrows - 1) as f64 * 30.0];
        let (a, b) = ([ends[0] * w, ends[1] * h], [ends[2] * w, ends[3] * h]);
        let (from, to) = (terrain.locate(a[0], a[1]).unwrap(), terrain.locate(b[0], b[1]).unwrap());
        let source = [Source::new(from)];
        let field = solver.field(Sources::from(&source).until(&Stop::NONE)).unwrap();
        let expected = field.distance_at(to).unwrap();
        let both = solver.shortest_path(Sources::from(&source).until(&Stop::NONE), to);
        let one_end = Stop::NONE.with_both_ends(false);
        let one = solver.shortest_path(Sources::from(&source).until(&one_end), to);
        let ((both, stats), (one, _)) = match (both, one) {
            (Ok(both), Ok(one)) => (both, one),
            (Err(Error::Unreachable { .. }), Err(Error::Unreachable { .. })) => {
                prop_assert!(expected.is_infinite());
                return Ok(());
            }
            (both, one) => {
                return Err(TestCaseError::fail(format!(
                    "{:?} against {:?}",
                    both.map(|p| p.0.traced_length),
                    one.map(|p| p.0.traced_length)
                )));
            }
        };
        prop_assert_eq!(stats.both_ends, two_threads());
        // The command line's route: on the window of the grid it needs, from both ends.
        let window = route_on_grid(&grid, &cost, &options, a, b).unwrap().route;
        for (how, traced) in [
            ("both ends", both.traced_length),
            ("one end", one.traced_length),
            ("the window", window.traced_cost),
        ] {
            prop_assert!(
                (traced - expected).abs() <= 1e-9 * expected,
                "{} {:?} k {}: {} traced {} against the full run's {}",
                COSTS[which], method, k, how, traced, expected
            );
        }
        prop_assert!(both.length <= both.traced_length * (1.0 + 1e-12));
        // The one-ended runs' paths, straightened (the full run's is the map's).
        let full = field.path(to).unwrap();
        for (how, other) in [("one end", one.length), ("the full run", full.length)] {
            let spread = both.length / other - 1.0;
            if spread.abs() > 1e-9 {
                println!("{} {:?} k {}: straightened {:+.2e} against {}", COSTS[which], method, k, spread, how);
            }
            prop_assert!(
                both.length <= other * (1.0 + STRAIGHTENED_SPREAD),
                "{} {:?} k {}: straightened {} against {} from {}",
                COSTS[which], method, k, both.length, other, how
            );
        }
    }

    /// A route is the same whether or not the whole field is asked for (a map or cost
    /// contours need it): [`route`] with and without it, and [`route_and_field`], give
    /// the same points, to the bit.
    #[test]
    fn a_route_does_not_depend_on_the_field_asked_for(
        seed in any::<u64>(),
        which in 0..COSTS.len(),
        ends in prop::array::uniform4(0.0f64..1.0),
    ) {
        let (ncols, nrows) = (40, 34);
        let grid = rough_grid(seed, ncols, nrows, 90.0, 1.0);
        let terrain = grid.to_mesh().unwrap();
        let cost: TerrainCost = COSTS[which].parse().unwrap();
        let options = Options::DEFAULT.with_k(2.0).with_method(Method::Tracks);
        let solver = Solver::new(&terrain.mesh, cost.metric(&terrain.mesh).unwrap(), &options).unwrap();
        let [w, h] = [(ncols - 1) as f64 * 90.0, (nrows - 1) as f64 * 90.0];
        let at = |u: f64, v: f64| terrain.locate(u * w, v * h).unwrap();
        let (from, to) = (at(ends[0], ends[1]), at(ends[2], ends[3]));
        match (route(&solver, from, to, false), route(&solver, from, to, true), route_and_field(&solver, from, to)) {
            (Ok(alone), Ok(whole), Ok((with_field, field))) => {
                prop_assert_eq!(&alone.points, &whole.points, "{}", COSTS[which]);
                prop_assert_eq!(&alone.points, &with_field.points, "{}", COSTS[which]);
                prop_assert_eq!(alone.traced_cost, whole.traced_cost);
                prop_assert!(alone.vertex_costs.is_none() && whole.vertex_costs.is_some());
                let costs = whole.vertex_costs.unwrap();
                prop_assert_eq!(costs.as_slice(), field.vertex_distances());
            }
            (Err(Error::Unreachable { .. }), Err(Error::Unreachable { .. }), Err(Error::Unreachable { .. })) => {}
            (a, b, c) => prop_assert!(false, "{:?} {:?} {:?}", a.map(|r| r.cost()), b.map(|r| r.cost()), c.map(|r| r.0.cost())),
        }
    }
}
