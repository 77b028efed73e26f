//! A solver's set-up for `slope:4` at k = 2 on a whole grid, on its `GridSurface` and
//! on its mesh: seconds for the surface or mesh, the metric and the solver, a line per
//! run. Under `valgrind --tool=callgrind --toggle-collect='*Solver*with_topology*'`
//! (and `RAYON_NUM_THREADS=1`), it counts the set-up's instructions alone.
//!
//! ```text
//! cargo run --release -p geotracks-terrain --example surface_setup -- GRID.asc surface|mesh [RUNS]
//! ```
//!
//! GRID.asc: the terrain bench's grid (`--example terrain_bench -- DIR 400` writes
//! `DIR/terrain400.asc` first).

use geotracks::{Options, Solver};
use geotracks_terrain::{read_grid, GridSurface, TerrainCost};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path, which, rest @ ..] = args.as_slice() else {
        return Err("usage: surface_setup GRID.asc surface|mesh [RUNS]".into());
    };
    let runs: usize = rest.first().map_or(Ok(3), |r| r.parse())?;
    let grid = read_grid(path)?;
    let cost: TerrainCost = "slope:4".parse()?;
    let mean = grid.mean_edge_length().ok_or("the grid has no triangle")?;
    let options = Options::DEFAULT.with_k(2.0).with_mean_edge_length(mean);
    for _ in 0..runs {
        let start = Instant::now();
        let (built, metric_done, solver) = match which.as_str() {
            "surface" => {
                let surface = GridSurface::new(&grid)?;
                let built = start.elapsed().as_secs_f64();
                let metric = cost.metric_on_surface(&grid, &surface)?;
                let metric_done = start.elapsed().as_secs_f64();
                let solver = Solver::with_topology(surface, metric, &options)?;
                (built, metric_done, solver.k())
            }
            "mesh" => {
                let terrain = grid.to_mesh()?;
                let built = start.elapsed().as_secs_f64();
                let metric = cost.metric_on_grid(&grid, &terrain)?;
                let metric_done = start.elapsed().as_secs_f64();
                let solver = Solver::new(&terrain.mesh, metric, &options)?;
                (built, metric_done, solver.k())
            }
            other => return Err(format!("{other}: say surface or mesh").into()),
        };
        let all = start.elapsed().as_secs_f64();
        println!(
            "{which}: built {built:.3} s, metric {:.3} s, solver {:.3} s (k = {solver})",
            metric_done - built,
            all - metric_done
        );
    }
    Ok(())
}
