//! `geotracks distance` and `geotracks demo`.

use crate::inputs::load_mesh;
use crate::metric::MetricArgs;
use crate::output::Outputs;
use crate::picture::{self, PictureArgs};
use crate::{points, ui, CliResult, Short, Value};
use geotracks::mesh::{io, TriMesh, NONE};
use geotracks::Sources;
use geotracks::{
    Euclidean, Field, Metric, Options, Solver, Source, Stop, SurfacePoint, VertexValues,
};
use geotracks_render::PictureOptions;
use std::path::{Path, PathBuf};

/// Arguments of `geotracks distance`.
#[derive(clap::Args)]
pub struct DistanceArgs {
    /// The mesh (OBJ, PLY, OFF, STL or .ma).
    mesh: PathBuf,
    /// Merge vertices at identical positions (files whose seams split vertices); vertex
    /// ids (sources, density lines, output rows) then refer to the welded mesh.
    #[arg(long)]
    weld: bool,
    /// A source: a surface point SP (a vertex id, e:E:t or f:F:b0,b1,b2; see below);
    /// repeat for several sources (the distance is to the nearest).
    #[arg(long = "source", value_name = "SP", required = true)]
    sources: Vec<SurfacePoint>,
    #[command(flatten)]
    metric: MetricArgs,
    /// Stop at distance D: vertices farther away stay unreached (inf in the outputs).
    #[arg(long, value_name = "D", allow_negative_numbers = true)]
    max_distance: Option<f64>,
    /// Also write each vertex's nearest source (geodesic Voronoi diagram): one line per
    /// vertex, the 0-based index of the source in the order of the --source options, or
    /// -1 where no source reaches it.
    #[arg(long, value_name = "OUT.txt")]
    voronoi: Option<PathBuf>,
    /// Output: .txt (one distance per line), .csv (vertex,distance) or .ply (coloured).
    #[arg(short, long)]
    output: PathBuf,
    /// Also write the run's statistics as JSON.
    #[arg(long)]
    stats: Option<PathBuf>,
    #[command(flatten)]
    picture: PictureArgs,
}

/// The formats `-o` accepts.
#[derive(Clone, Copy)]
enum OutputFormat {
    Txt,
    Csv,
    Ply,
}

fn output_format(path: &Path) -> CliResult<OutputFormat> {
    crate::text_output_format(
        path,
        &[
            ("txt", OutputFormat::Txt),
            ("csv", OutputFormat::Csv),
            ("ply", OutputFormat::Ply),
        ],
        OutputFormat::Csv,
    )
}

pub fn run(args: &DistanceArgs) -> CliResult {
    // Check everything that can be checked before the (possibly long) computation.
    let format = output_format(&args.output)?;
    if let Some(stats) = &args.stats {
        crate::text_output_format(stats, &[("json", ())], ())?;
    }
    if let Some(voronoi) = &args.voronoi {
        crate::text_output_format(voronoi, &[("txt", ())], ())?;
    }
    let max_distance = args.max_distance.unwrap_or(f64::INFINITY);
    // The library's check, as every run (and the Python package) makes it.
    let stop = Stop::NONE.with_max_distance(max_distance);
    stop.check()
        .map_err(|e| format!("--max-distance {}: {e}", crate::Value(max_distance)))?;
    let mut outputs = Outputs::new(std::iter::once(args.mesh.as_path()).chain(args.metric.files()));
    for path in [
        Some(&args.output),
        args.voronoi.as_ref(),
        args.stats.as_ref(),
    ] {
        outputs.declare_some(path)?;
    }
    args.picture.declare(&mut outputs)?;
    let spinner = ui::Spinner::start("reading the mesh and propagating");
    let mesh = load_mesh(&args.mesh, args.weld)?;
    let sources = points::sources(&mesh, &args.sources)?;
    let metric = args.metric.metric(&mesh)?;
    let options = args.metric.options();
    let solver = Solver::new(&mesh, metric, &options)?;
    // A picture reads the whole field; the values alone cost less (the exact engine
    // then keeps only its wavefront's windows).
    let (values, field) = if args.picture.png.is_some() {
        let field = compute(&solver, &sources, &stop)?;
        let values = field.vertex_values();
        (values, Some(field))
    } else {
        let values = solver.vertex_values(Sources::from(&sources).until(&stop))?;
        report_unreached(values.unreachable_vertices(), &stop);
        (values, None)
    };
    drop(spinner);
    write_field(&mut outputs, &args.output, format, &mesh, &values.distances)?;
    if let Some(voronoi) = &args.voronoi {
        write_labels(&mut outputs, voronoi, &values.labels)?;
    }
    if let Some(stats) = &args.stats {
        write_stats(&mut outputs, stats, &values)?;
    }
    if let Some(field) = &field {
        args.picture.draw(&mut outputs, field, &sources, None)?;
    }
    outputs.commit()?;
    crate::report_run(&args.mesh, &values.stats, &args.output);
    Ok(())
}

/// The field from `sources`, with a line on stderr about the vertices it does not reach.
fn compute<M: Metric>(solver: &Solver<M>, sources: &[Source], stop: &Stop) -> CliResult<Field<M>> {
    let field = solver.field(Sources::from(sources).until(stop))?;
    report_unreached(field.unreachable_vertices(), stop);
    Ok(field)
}

/// A line on stderr about the `unreachable` vertices a run did not reach.
fn report_unreached(unreachable: usize, stop: &Stop) {
    if unreachable > 0 {
        if stop.max_distance.is_finite() {
            ui::info!(
                "{unreachable} vertices are farther than --max-distance {} or not reachable from the sources; their distance is inf",
                Value(stop.max_distance)
            );
        } else {
            eprintln!(
                "warning: {unreachable} vertices are not reachable from the sources (another component or unreferenced); their distance is inf"
            );
        }
    }
}

/// Writes the index of each vertex's nearest source, `-1` where unreached.
fn write_labels(outputs: &mut Outputs, path: &Path, labels: &[u32]) -> CliResult {
    outputs.write(path, |w| {
        for &label in labels {
            if label == NONE {
                writeln!(w, "-1")?;
            } else {
                writeln!(w, "{label}")?;
            }
        }
        Ok(())
    })?;
    Ok(())
}

fn write_field(
    outputs: &mut Outputs,
    path: &Path,
    format: OutputFormat,
    mesh: &TriMesh,
    d: &[f64],
) -> CliResult {
    match format {
        OutputFormat::Ply => outputs.write(path, |w| io::write_ply_with_distance_to(w, mesh, d))?,
        OutputFormat::Txt => outputs.write(path, |w| {
            for x in d {
                writeln!(w, "{}", Value(*x))?;
            }
            Ok(())
        })?,
        OutputFormat::Csv => outputs.write(path, |w| {
            writeln!(w, "vertex,distance")?;
            for (v, x) in d.iter().enumerate() {
                writeln!(w, "{v},{}", Value(*x))?;
            }
            Ok(())
        })?,
    }
    Ok(())
}

fn write_stats(outputs: &mut Outputs, path: &Path, values: &VertexValues) -> CliResult {
    let s = &values.stats;
    let json = serde_json::json!({
        "vertices": s.vertices,
        "faces": s.faces,
        "steiner_points": s.steiner_points,
        "k": s.k,
        "method": s.method.name(),
        "setup_seconds": s.setup_seconds,
        "propagate_seconds": s.propagate_seconds,
        "pushes": s.pushes,
        "settles": s.settles,
        "distance_tests": s.distance_tests,
        "setup_distance_tests": s.setup_distance_tests,
        "windows_created": s.windows_created,
        "windows_kept": s.windows_kept,
        "unreachable_vertices": values.unreachable_vertices(),
    });
    outputs.write(path, |w| {
        serde_json::to_writer_pretty(&mut *w, &json)?;
        writeln!(w)
    })?;
    Ok(())
}

/// The bundled default mesh: Spot by Keenan Crane (CC0), also used by the tests.
const SPOT_OBJ: &[u8] = include_bytes!("../data/spot.obj");

/// Where `geotracks demo` writes by default: a folder that git ignores.
pub const DEMO_OUTPUT: &str = "geotracks-out/spot_distance.ply";

pub fn demo(output: &Path) -> CliResult {
    let format = output_format(output)?;
    if output == Path::new(DEMO_OUTPUT) {
        let dir = Path::new(DEMO_OUTPUT).parent().expect("a folder");
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let mut outputs = Outputs::new([]);
    outputs.declare(output)?;
    // The picture beside the field (none when the field goes to standard output).
    let png = (output.as_os_str() != "-").then(|| output.with_extension("png"));
    if let Some(png) = &png {
        outputs.declare(png)?;
    }
    let mesh = io::read_obj_bytes(SPOT_OBJ)?;
    let source = 0;
    let options = Options::DEFAULT;
    let solver = Solver::new(&mesh, Euclidean, &options)?;
    let field = compute(&solver, &[Source::new(source)], &Stop::NONE)?;
    write_field(
        &mut outputs,
        output,
        format,
        &mesh,
        field.vertex_distances(),
    )?;
    if let Some(png) = &png {
        let options = PictureOptions::DEFAULT;
        picture::draw(
            &mut outputs,
            png,
            &field,
            &[Source::new(source)],
            None,
            &options,
        )?;
    }
    outputs.commit()?;
    let s = field.stats();
    let far = field
        .vertex_distances()
        .iter()
        .cloned()
        .fold(0.0f64, f64::max);
    let lines = [
        format!(
            "Spot (CC0, Keenan Crane): {} vertices, {} faces; geodesic distance from vertex {source}",
            s.vertices, s.faces
        ),
        format!(
            "method {}, k = {}, {} Steiner points, {} distance tests, {:.3} s; farthest vertex at {}",
            s.method,
            s.k,
            s.steiner_points,
            s.distance_tests,
            s.setup_seconds + s.propagate_seconds,
            Short(far)
        ),
        match &png {
            Some(png) => format!("wrote {} and {}", crate::shown(output), png.display()),
            None => format!("wrote {}", crate::shown(output)),
        },
    ];
    for line in lines {
        // Standard output holds the data when it is the output.
        if output.as_os_str() == "-" {
            ui::info!("{line}");
        } else {
            ui::say!("{line}");
        }
    }
    if matches!(format, OutputFormat::Ply) {
        ui::say!(
            "view it with any PLY viewer that shows vertex colours, e.g. `meshlab {0}`, `f3d {0}` or Blender (File > Import > PLY)",
            output.display()
        );
    }
    crate::report_stats(s);
    Ok(())
}
