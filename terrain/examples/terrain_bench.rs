//! Terrain routes on a 1000 × 1000 grid (2M faces), end to end from the file.
//!
//! ```text
//! cargo run --release --example terrain_bench [-- DIR [N [--routes]]]
//! ```
//!
//! Writes a synthetic N × N ESRI ASCII grid (default 1000; 10 m cells, Gaussian hills on
//! rolling sines, deterministic) to DIR (default: a temporary directory, removed after),
//! then for each cost, method and k times what `geotracks terrain --method M --k K`
//! does: read, mesh, build the metric, set up the solver, propagate until the target
//! is final, trace and straighten the route. Two routes: corner to corner (a plain
//! run propagates nearly the whole grid before the end is final) and across a quarter
//! of the grid. The Steiner-graph engine (tracks) runs goal-directed (A*); the
//! wavefront engine does not (see `Stop::goal_directed`). Each route runs twice: on the
//! window of the grid it needs (`route_on_grid`, what the command line runs) and on the
//! whole grid's mesh. Peak memory is the process's high-water mark during the row
//! (Linux, reset before each row; what the grid itself holds, 8 MB, included).
//!
//! `--routes` measures accuracy instead: four routes across the grid, three costs, each
//! straightened at k = 1 and 2 and compared with the same route at k = 6 (a finer graph
//! finds a better corridor; there is no exact reference on a hilly grid). Minutes.

use geotracks::{mesh::TriMesh, Method, Options, Solver, SurfacePoint};
use geotracks_terrain::{read_terrain, route, route_on_grid, TerrainCost};
use std::io::Write;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let temp = tempfile::tempdir()?;
    let dir = args.next().map_or(temp.path().to_path_buf(), Into::into);
    let n: usize = args.next().map_or(Ok(1000), |s| s.parse())?;
    let routes = args.next().as_deref() == Some("--routes");
    let path = dir.join(format!("terrain{n}.asc"));
    let start = Instant::now();
    write_grid(&path, n)?;
    println!(
        "wrote {} ({:.1} MB) in {:.2} s",
        path.display(),
        std::fs::metadata(&path)?.len() as f64 / 1e6,
        start.elapsed().as_secs_f64()
    );
    let extent = 10.0 * (n - 1) as f64;
    if routes {
        return route_accuracy(&path, extent);
    }
    // Corner to corner (nearly the whole grid lies within the route's cost of the
    // start), and across a quarter of the grid (one quadrant, corner to corner).
    let routes = [
        ("corner to corner", [0.05, 0.05], [0.95, 0.93]),
        ("a quarter", [0.05, 0.05], [0.5, 0.47]),
    ];
    println!("| route | cost | method | k | meshed | read | mesh, metric, setup | propagate | settles | path | total | route cost | peak memory |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, a, b) in routes {
        let (from, to) = (
            [a[0] * extent, a[1] * extent],
            [b[0] * extent, b[1] * extent],
        );
        let quarter = name == "a quarter";
        for (cost, method, k) in [
            ("none", Method::Wave, 2.0),
            ("none", Method::Tracks, 2.0),
            ("none", Method::Tracks, 4.0),
            ("slope:4", Method::Tracks, 2.0),
            ("slope:4,max:30", Method::Tracks, 2.0),
            ("incline:8", Method::Wave, 2.0),
            ("incline:8", Method::Tracks, 4.0),
            ("uphill:8", Method::Tracks, 2.0),
            ("naismith", Method::Tracks, 2.0),
            ("tobler", Method::Tracks, 2.0),
            ("slope:4", Method::Tracks, 5.0),
        ] {
            if quarter && !matches!(cost, "none" | "slope:4") {
                continue;
            }
            // The window (`route_on_grid`), end to end from the file, then the whole grid.
            reset_peak_memory();
            let t0 = Instant::now();
            let grid = geotracks_terrain::read_grid(&path)?;
            let read = t0.elapsed().as_secs_f64();
            let options = Options::DEFAULT.with_k(k).with_method(method);
            let w = route_on_grid(&grid, &cost.parse()?, &options, from, to)?;
            let total = t0.elapsed().as_secs_f64();
            let (r, window) = (&w.route, &w.window);
            println!(
                "| {name} | {cost} | {} | {k} | window: {:.0} % of the cells, {} run{} | {read:.2} s | {:.2} s | {:.2} s | {:.2} M | {:.2} s | {total:.2} s | {:.1} | {} |",
                r.stats.method.name(),
                100.0 * window.cells as f64 / window.grid_cells as f64,
                window.runs,
                if window.runs == 1 { "" } else { "s" },
                window.setup_seconds,
                r.stats.propagate_seconds,
                r.stats.settles as f64 / 1e6,
                r.path_seconds,
                r.cost(),
                peak_memory().unwrap_or_else(|| "n/a".into())
            );
            reset_peak_memory();
            let t0 = Instant::now();
            let grid = geotracks_terrain::read_grid(&path)?;
            let read = t0.elapsed().as_secs_f64();
            let t = Instant::now();
            let terrain = grid.to_mesh()?;
            let mesh = t.elapsed().as_secs_f64();
            let a = terrain.locate(from[0], from[1])?;
            let b = terrain.locate(to[0], to[1])?;
            let times = time_route(&terrain.mesh, cost.parse()?, a, b, method, k)?;
            let total = t0.elapsed().as_secs_f64();
            println!(
                "| {name} | {cost} | {} | {k} | whole grid | {read:.2} s | {:.2} s | {:.2} s | {:.2} M | {:.2} s | {total:.2} s | {:.1} | {} |",
                times.method.name(),
                mesh + times.metric + times.setup,
                times.propagate,
                times.settles as f64 / 1e6,
                times.path,
                times.cost,
                peak_memory().unwrap_or_else(|| "n/a".into())
            );
        }
    }
    // Checks the file reads the same way the CLI reads it.
    let _ = read_terrain(&path)?;
    Ok(())
}

/// Straightened route costs at k = 1 and 2 against k = 6, for four routes and three costs.
fn route_accuracy(path: &std::path::Path, extent: f64) -> Result<(), Box<dyn std::error::Error>> {
    let terrain = geotracks_terrain::read_grid(path)?.to_mesh()?;
    println!("| route (fractions of the extent) | cost | k = 6 | k = 1 | k = 2 |");
    println!("|---|---|---:|---:|---:|");
    for r in [
        [0.05, 0.05, 0.95, 0.93],
        [0.1, 0.5, 0.9, 0.6],
        [0.5, 0.05, 0.55, 0.95],
        [0.9, 0.1, 0.1, 0.7],
    ] {
        let from = terrain.locate(r[0] * extent, r[1] * extent)?;
        let to = terrain.locate(r[2] * extent, r[3] * extent)?;
        for cost in ["none", "slope:4", "incline:8"] {
            let cost_model: TerrainCost = cost.parse()?;
            let mut costs = [0.0; 3];
            for (i, k) in [6.0, 1.0, 2.0].into_iter().enumerate() {
                costs[i] = time_route(&terrain.mesh, cost_model, from, to, Method::Wave, k)?.cost;
            }
            let excess = |c: f64| format!("{:+.2} %", 100.0 * (c - costs[0]) / costs[0]);
            println!(
                "| ({}, {}) → ({}, {}) | {cost} | {:.1} | {} | {} |",
                r[0],
                r[1],
                r[2],
                r[3],
                costs[0],
                excess(costs[1]),
                excess(costs[2])
            );
        }
    }
    Ok(())
}

struct Times {
    /// The engine that ran (a metric that is not face-flat runs tracks).
    method: Method,
    metric: f64,
    setup: f64,
    propagate: f64,
    settles: u64,
    path: f64,
    cost: f64,
}

/// Builds the metric and the solver, and routes from `from` to `to` (stopping at `to`).
fn time_route(
    mesh: &TriMesh,
    cost: TerrainCost,
    from: SurfacePoint,
    to: SurfacePoint,
    method: Method,
    k: f64,
) -> Result<Times, Box<dyn std::error::Error>> {
    let t = Instant::now();
    let metric = cost.metric(mesh)?;
    let metric_time = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let solver = Solver::new(
        mesh,
        &metric,
        &Options::DEFAULT.with_k(k).with_method(method),
    )?;
    let setup = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let r = route(&solver, from, to, false)?;
    let total = t.elapsed().as_secs_f64();
    Ok(Times {
        method: solver.method(),
        metric: metric_time,
        setup,
        propagate: total - r.path_seconds,
        settles: r.stats.settles,
        path: r.path_seconds,
        cost: r.cost(),
    })
}

/// Gaussian hills on rolling sines, 10 m cells, lower-left sample centre at (0, 0).
fn write_grid(path: &std::path::Path, n: usize) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        out,
        "ncols {n}\nnrows {n}\nxllcenter 0\nyllcenter 0\ncellsize 10\nNODATA_value -9999"
    )?;
    let extent = 10.0 * (n - 1) as f64;
    let hills = [
        (0.3, 0.6, 0.08, 400.0),
        (0.6, 0.35, 0.12, 600.0),
        (0.75, 0.75, 0.06, 300.0),
        (0.45, 0.2, 0.05, 250.0),
    ];
    let mut line = String::new();
    for row in 0..n {
        line.clear();
        let y = (n - 1 - row) as f64 * 10.0;
        for col in 0..n {
            let x = col as f64 * 10.0;
            let (u, v) = (x / extent, y / extent);
            let mut z = 30.0 * (u * 23.0).sin() * (v * 17.0).cos() + 50.0 * u;
            for (cx, cy, s, h) in hills {
                z += h * (-((u - cx).powi(2) + (v - cy).powi(2)) / (2.0 * s * s)).exp();
            }
            if col > 0 {
                line.push(' ');
            }
            line.push_str(&format!("{z:.2}"));
        }
        writeln!(out, "{line}")?;
    }
    out.flush()
}

/// Starts the process's peak resident memory afresh (Linux: `clear_refs` 5), so that
/// each row's peak is its own.
fn reset_peak_memory() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// The process's peak resident memory (`VmHWM`), on Linux.
fn peak_memory() -> Option<String> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb: f64 = status
        .lines()
        .find(|l| l.starts_with("VmHWM:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()?;
    Some(format!("{:.0} MB", kb / 1024.0))
}
