//! `geotracks path`: the shortest path from a surface point to the nearest source.

use crate::inputs::load_mesh;
use crate::metric::MetricArgs;
use crate::output::Outputs;
use crate::{points, ui, CliResult, Value};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{GeodesicPath, Solver, Stop, SurfacePoint};
use std::path::{Path, PathBuf};

/// Arguments of `geotracks path`.
#[derive(clap::Args)]
pub struct PathArgs {
    /// The mesh (OBJ, PLY, OFF, STL or .ma).
    mesh: PathBuf,
    /// Merge vertices at identical positions (files whose seams split vertices); vertex
    /// ids (sources, density lines, output rows) then refer to the welded mesh.
    #[arg(long)]
    weld: bool,
    /// A source: a surface point SP (a vertex id, e:E:t or f:F:b0,b1,b2; see below);
    /// repeat for several sources (the path goes to the nearest).
    #[arg(long = "source", value_name = "SP", required = true)]
    sources: Vec<SurfacePoint>,
    /// Where the path starts: a surface point SP.
    #[arg(long, value_name = "SP")]
    target: SurfacePoint,
    #[command(flatten)]
    metric: MetricArgs,
    /// Output: .obj (the polyline as `v` lines and one `l` line) or .csv (`x,y,z,point`),
    /// from the target to the source.
    #[arg(short, long)]
    output: PathBuf,
}

/// The formats `-o` accepts.
#[derive(Clone, Copy)]
enum OutputFormat {
    Obj,
    Csv,
}

fn output_format(path: &Path) -> CliResult<OutputFormat> {
    crate::text_output_format(
        path,
        &[("obj", OutputFormat::Obj), ("csv", OutputFormat::Csv)],
        OutputFormat::Csv,
    )
}

pub fn run(args: &PathArgs) -> CliResult {
    // Check everything that can be checked before the computation.
    let format = output_format(&args.output)?;
    let mut outputs = Outputs::new(std::iter::once(args.mesh.as_path()).chain(args.metric.files()));
    outputs.declare(&args.output)?;
    let spinner = ui::Spinner::start("reading the mesh, propagating and tracing");
    let mesh = load_mesh(&args.mesh, args.weld)?;
    let sources = points::sources(&mesh, &args.sources)?;
    let target = points::check(&mesh, "target", args.target)?;
    let metric = args.metric.metric(&mesh)?;
    let options = args.metric.options();
    let solver = Solver::new(&mesh, metric, &options)?;
    // The run stops once the target's value is final.
    let field =
        solver.field(Sources::from(&sources).until(Stop::NONE.with_targets(vec![target])))?;
    let path = field.path(target)?;
    drop(spinner);
    write_path(&mut outputs, &args.output, format, &mesh, &path)?;
    outputs.commit()?;

    let source = path.source as usize;
    let summary = [
        format!("target: {}", args.target),
        format!("source: {source} ({})", args.sources[source]),
        format!("points: {}", path.points.len()),
        format!(
            "traced length: {} ({}, before straightening)",
            Value(path.traced_length),
            match field.stats().method {
                geotracks::Method::Wave => "along the waves that gave the value",
                _ => "the Steiner graph's distance",
            }
        ),
    ];
    if args.output.as_os_str() == "-" {
        // Standard output holds the path: the summary and the length go to stderr.
        for line in summary {
            ui::info!("{line}");
        }
        ui::info!("length: {}", Value(path.length));
    } else {
        for line in summary {
            ui::say!("{line}");
        }
        // The result, alone on the last line (also with --quiet).
        crate::print_out(format_args!("{}", Value(path.length)))?;
    }
    crate::report_run(&args.mesh, field.stats(), &args.output);
    Ok(())
}

/// Writes the polyline, target first.
fn write_path(
    outputs: &mut Outputs,
    file: &Path,
    format: OutputFormat,
    mesh: &TriMesh,
    path: &GeodesicPath,
) -> CliResult {
    let positions = path.positions(mesh);
    match format {
        OutputFormat::Obj => outputs.write(file, |w| {
            for p in &positions {
                writeln!(w, "v {} {} {}", p.x, p.y, p.z)?;
            }
            // A polyline needs two vertices: a path of one point (the target is a
            // source) is written as a zero-length segment.
            write!(w, "l")?;
            for i in 1..=positions.len().max(2) {
                write!(w, " {}", i.min(positions.len()))?;
            }
            writeln!(w)
        })?,
        OutputFormat::Csv => outputs.write(file, |w| {
            writeln!(w, "x,y,z,point")?;
            for (p, point) in positions.iter().zip(&path.points) {
                let text = point.to_string();
                // A face point's barycentrics hold commas: quote it (RFC 4180).
                if text.contains(',') {
                    writeln!(w, "{},{},{},\"{text}\"", p.x, p.y, p.z)?;
                } else {
                    writeln!(w, "{},{},{},{text}", p.x, p.y, p.z)?;
                }
            }
            Ok(())
        })?,
    }
    Ok(())
}
