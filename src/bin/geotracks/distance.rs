//! `geotracks distance` and `geotracks demo`.

use crate::inputs::load_mesh;
use crate::metric_args::{MetricArgs, WithMetric};
use crate::{CliResult, Value};
use geotracks::mesh::{io, TriMesh};
use geotracks::{distance_field, Euclidean, GeodesicField, Metric, Options};
use std::path::{Path, PathBuf};

/// Arguments of `geotracks distance`.
#[derive(clap::Args)]
pub struct DistanceArgs {
    /// The mesh (OBJ, PLY, OFF, STL or .ma).
    mesh: PathBuf,
    /// A source vertex (0-based); repeat for several sources.
    #[arg(long = "source", required = true)]
    sources: Vec<u32>,
    #[command(flatten)]
    metric: MetricArgs,
    /// Output: .txt (one distance per line), .csv (vertex,distance) or .ply (coloured).
    #[arg(short, long)]
    output: PathBuf,
    /// Also write the run's statistics as JSON.
    #[arg(long)]
    stats: Option<PathBuf>,
}

/// The formats `-o` accepts.
#[derive(Clone, Copy)]
enum OutputFormat {
    Txt,
    Csv,
    Ply,
}

fn output_format(path: &Path) -> CliResult<OutputFormat> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("txt") => Ok(OutputFormat::Txt),
        Some("csv") => Ok(OutputFormat::Csv),
        Some("ply") => Ok(OutputFormat::Ply),
        _ => Err(format!(
            "{}: unknown output format (expected .txt, .csv or .ply)",
            path.display()
        )
        .into()),
    }
}

pub fn run(args: &DistanceArgs) -> CliResult {
    // Check everything that can be checked before the (possibly long) computation.
    let format = output_format(&args.output)?;
    if let Some(stats) = &args.stats {
        if stats.extension().and_then(|e| e.to_str()) != Some("json") {
            return Err(format!("{}: the stats file must end in .json", stats.display()).into());
        }
    }
    let mesh = load_mesh(&args.mesh)?;
    let field = args.metric.dispatch(&mesh, Field(&args.sources))?;
    write_field(&args.output, format, &mesh, &field)?;
    if let Some(stats) = &args.stats {
        write_stats(stats, &field)?;
    }
    let s = field.stats();
    eprintln!(
        "{}: {} vertices, method {}, {} Steiner points, {:.3} s; wrote {}",
        args.mesh.display(),
        s.vertices,
        s.method,
        s.steiner_points,
        s.setup_seconds + s.propagate_seconds,
        args.output.display()
    );
    Ok(())
}

/// A distance field from these sources.
struct Field<'s>(&'s [u32]);

impl WithMetric for Field<'_> {
    type Output = GeodesicField;
    fn run<M: Metric>(
        self,
        mesh: &TriMesh,
        metric: &M,
        options: &Options,
    ) -> CliResult<GeodesicField> {
        compute(mesh, metric, self.0, options)
    }
}

fn compute<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    sources: &[u32],
    options: &Options,
) -> CliResult<GeodesicField> {
    let field = distance_field(mesh, metric, sources, options)?;
    let unreachable = field.unreachable_vertices();
    if unreachable > 0 {
        eprintln!(
            "warning: {unreachable} vertices are not reachable from the sources (another component or unreferenced); their distance is inf"
        );
    }
    Ok(field)
}

fn write_field(
    path: &Path,
    format: OutputFormat,
    mesh: &TriMesh,
    field: &GeodesicField,
) -> CliResult {
    let d = field.vertex_distances();
    match format {
        OutputFormat::Ply => io::write_ply_with_distance(path, mesh, d)?,
        OutputFormat::Txt => io::write_atomically(path, |w| {
            for x in d {
                writeln!(w, "{}", Value(*x))?;
            }
            Ok(())
        })?,
        OutputFormat::Csv => io::write_atomically(path, |w| {
            writeln!(w, "vertex,distance")?;
            for (v, x) in d.iter().enumerate() {
                writeln!(w, "{v},{}", Value(*x))?;
            }
            Ok(())
        })?,
    }
    Ok(())
}

fn write_stats(path: &Path, field: &GeodesicField) -> CliResult {
    let s = field.stats();
    let json = serde_json::json!({
        "vertices": s.vertices,
        "faces": s.faces,
        "steiner_points": s.steiner_points,
        "k": s.k,
        "method": s.method.name(),
        "setup_seconds": s.setup_seconds,
        "propagate_seconds": s.propagate_seconds,
        "pushes": s.pushes,
        "distance_tests": s.distance_tests,
        "setup_distance_tests": s.setup_distance_tests,
        "unreachable_vertices": field.unreachable_vertices(),
    });
    io::write_atomically(path, |w| {
        serde_json::to_writer_pretty(&mut *w, &json)?;
        writeln!(w)
    })?;
    Ok(())
}

/// The bundled default mesh: Spot by Keenan Crane (CC0), also used by the tests.
const SPOT_OBJ: &[u8] = include_bytes!("../../../tests/data/spot.obj");

pub fn demo(output: &Path) -> CliResult {
    let format = output_format(output)?;
    let mesh = io::read_obj_bytes(SPOT_OBJ)?;
    let source = 0;
    let options = Options::DEFAULT;
    let field = compute(&mesh, &Euclidean, &[source], &options)?;
    write_field(output, format, &mesh, &field)?;
    let s = field.stats();
    let far = field
        .vertex_distances()
        .iter()
        .cloned()
        .fold(0.0f64, f64::max);
    println!(
        "Spot (CC0, Keenan Crane): {} vertices, {} faces; geodesic distance from vertex {source}",
        s.vertices, s.faces
    );
    println!(
        "method {}, k = {}, {} Steiner points, {} distance tests, {:.3} s; farthest vertex at {far:.4}",
        s.method,
        s.k,
        s.steiner_points,
        s.distance_tests,
        s.setup_seconds + s.propagate_seconds
    );
    println!("wrote {}", output.display());
    if matches!(format, OutputFormat::Ply) {
        println!(
            "view it with any PLY viewer that shows vertex colours, e.g. `meshlab {0}`, `f3d {0}` or Blender (File > Import > PLY)",
            output.display()
        );
    }
    Ok(())
}
