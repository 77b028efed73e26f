//! `geotracks matrix`: distances from many sources, computed in parallel.

use crate::inputs::{load_mesh, read_vertex_ids};
use crate::metric::MetricArgs;
use crate::output::Outputs;
use crate::{ui, CliResult, Value};
use geotracks::Solver;
use std::path::PathBuf;

/// Arguments of `geotracks matrix`.
#[derive(clap::Args)]
pub struct MatrixArgs {
    /// The mesh (OBJ, PLY, OFF, STL or .ma).
    mesh: PathBuf,
    /// Merge vertices at identical positions (files whose seams split vertices); vertex
    /// ids (sources, density lines, output rows) then refer to the welded mesh.
    #[arg(long)]
    weld: bool,
    /// Source vertex ids, separated by spaces, commas or new lines.
    #[arg(long)]
    sources: PathBuf,
    /// Only these target vertices as columns (default: every vertex).
    #[arg(long)]
    targets: Option<PathBuf>,
    #[command(flatten)]
    metric: MetricArgs,
    /// Output CSV: a header `source,<target ids>`, then one row per source.
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(args: &MatrixArgs) -> CliResult {
    crate::text_output_format(&args.output, &[("csv", ())], ())?;
    let inputs = [Some(&args.mesh), Some(&args.sources), args.targets.as_ref()];
    let mut outputs = Outputs::new(
        inputs
            .into_iter()
            .flatten()
            .map(PathBuf::as_path)
            .chain(args.metric.files()),
    );
    outputs.declare(&args.output)?;
    let spinner = ui::Spinner::start("reading the mesh and computing the rows");
    let mesh = load_mesh(&args.mesh, args.weld)?;
    let sources = read_vertex_ids(&args.sources, mesh.vertex_count())?;
    let targets = match &args.targets {
        Some(path) => Some(read_vertex_ids(path, mesh.vertex_count())?),
        None => None,
    };
    let start = std::time::Instant::now();
    let metric = args.metric.metric(&mesh)?;
    let options = args.metric.options();
    let solver = Solver::new(&mesh, metric, &options)?;
    // With targets, each row stops once they are final.
    let rows = solver.distance_rows(&sources, targets.as_deref())?;
    let stopped = rows.iter().filter(|r| r.stats.stopped_early).count();
    if ui::verbose() {
        let tests: u64 = rows.iter().map(|r| r.stats.distance_tests).sum();
        let pushes: u64 = rows.iter().map(|r| r.stats.pushes).sum();
        eprintln!("  {pushes} pushes and {tests} distance tests over all rows");
    }
    let rows: Vec<Vec<f64>> = rows.into_iter().map(|r| r.distances).collect();
    drop(spinner);
    let unreachable = rows.iter().flatten().filter(|d| d.is_infinite()).count();
    if unreachable > 0 {
        eprintln!(
            "warning: {unreachable} (source, target) pairs are not connected (another component or an unreferenced vertex); written as inf"
        );
    }
    let columns: Vec<u32> = targets.unwrap_or_else(|| (0..mesh.vertex_count() as u32).collect());
    outputs.write(&args.output, |w| {
        write!(w, "source")?;
        for c in &columns {
            write!(w, ",{c}")?;
        }
        writeln!(w)?;
        for (s, row) in sources.iter().zip(&rows) {
            write!(w, "{s}")?;
            for &d in row {
                write!(w, ",{}", Value(d))?;
            }
            writeln!(w)?;
        }
        Ok(())
    })?;
    outputs.commit()?;
    ui::info!(
        "{}: {} sources × {} columns on {} threads in {:.3} s{}; wrote {}",
        args.mesh.display(),
        sources.len(),
        columns.len(),
        rayon::current_num_threads(),
        start.elapsed().as_secs_f64(),
        match stopped {
            0 => String::new(),
            n => format!(", {n} row(s) stopped at their targets"),
        },
        crate::shown(&args.output)
    );
    Ok(())
}
