//! What routes cost under one cost model, on one grid: each route a file of map
//! points (`x y` or `x,y` per line; other lines are skipped, so a GeoJSON route's
//! coordinates, one per line, or GRASS's `v.out.ascii` output both read), costed by
//! [`map_path_cost`]. For comparing routes from other tools with ours on equal terms.
//!
//! ```text
//! cargo run --release -p geotracks-terrain --example path_cost -- DEM.asc COST ROUTE...
//! ```

use geotracks_terrain::{map_path_cost, read_grid, TerrainCost};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [dem, cost, routes @ ..] = args.as_slice() else {
        return Err("usage: path_cost DEM COST ROUTE...".into());
    };
    let grid = read_grid(dem)?;
    let cost: TerrainCost = cost.parse()?;
    for route in routes {
        let points: Vec<[f64; 2]> = std::fs::read_to_string(route)?
            .lines()
            .filter_map(|line| {
                let numbers: Vec<f64> = line
                    .split(|c: char| {
                        c == ',' || c == '|' || c.is_whitespace() || c == '[' || c == ']'
                    })
                    .filter_map(|w| w.parse().ok())
                    .collect();
                (numbers.len() >= 2).then(|| [numbers[0], numbers[1]])
            })
            .collect();
        match map_path_cost(&grid, &cost, &points) {
            Some(c) => println!("{route}: {} points, cost {c:.4}", points.len()),
            None => println!("{route}: {} points, off the grid or blocked", points.len()),
        }
    }
    Ok(())
}
