//! `geotracks isolines`: the isolines of a distance field, as polylines.

use crate::inputs::load_mesh;
use crate::metric::MetricArgs;
use crate::output::Outputs;
use crate::picture::PictureArgs;
use crate::{points, ui, CliResult, Value};
use geotracks::mesh::TriMesh;
use geotracks::trace::{spread_levels, Isoline, IsolineOptions};
use geotracks::Sources;
use geotracks::{Field, Solver, Stop, SurfacePoint};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Arguments of `geotracks isolines`.
#[derive(clap::Args)]
pub struct IsolinesArgs {
    /// The mesh (OBJ, PLY, OFF, STL or .ma).
    mesh: PathBuf,
    /// Merge vertices at identical positions (files whose seams split vertices); vertex
    /// ids (sources, density lines) then refer to the welded mesh.
    #[arg(long)]
    weld: bool,
    /// A source: a surface point SP (a vertex id, e:E:t or f:F:b0,b1,b2; see below);
    /// repeat for several sources (the distance is to the nearest).
    #[arg(long = "source", value_name = "SP", required = true)]
    sources: Vec<SurfacePoint>,
    #[command(flatten)]
    metric: MetricArgs,
    /// N levels spread evenly between 0 and the largest distance reached (both
    /// excluded).
    #[arg(long, value_name = "N", default_value_t = 10, conflicts_with = "at")]
    levels: usize,
    /// The levels, listed: D1,D2,... (distances, in the metric's units).
    #[arg(
        long,
        value_name = "D1,D2,...",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    at: Vec<f64>,
    /// Sub-triangles per face edge: finer finds smaller loops (points lie on their level
    /// whatever this is).
    #[arg(long, value_name = "N", default_value_t = IsolineOptions::DEFAULT.subdivisions)]
    subdivisions: u32,
    /// Output: .obj (`v` lines, one `l` line per isoline), .csv
    /// (`level,line,closed,x,y,z,point`) or .geojson (a LineString feature per isoline,
    /// with its level; coordinates x, y, z).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    picture: PictureArgs,
}

#[derive(Clone, Copy)]
pub enum OutputFormat {
    Obj,
    Csv,
    GeoJson,
}

fn output_format(path: &Path) -> CliResult<OutputFormat> {
    crate::text_output_format(
        path,
        &[
            ("obj", OutputFormat::Obj),
            ("csv", OutputFormat::Csv),
            ("geojson", OutputFormat::GeoJson),
        ],
        OutputFormat::Csv,
    )
}

pub fn run(args: &IsolinesArgs) -> CliResult {
    let format = output_format(&args.output)?;
    check_levels(args.levels, &args.at, ("--levels", "--at"))?;
    let options = IsolineOptions::DEFAULT.with_subdivisions(args.subdivisions);
    let mut outputs = Outputs::new(std::iter::once(args.mesh.as_path()).chain(args.metric.files()));
    outputs.declare(&args.output)?;
    args.picture.declare(&mut outputs)?;
    let spinner = ui::Spinner::start("reading the mesh, propagating and drawing isolines");
    let mesh = load_mesh(&args.mesh, args.weld)?;
    let sources = points::sources(&mesh, &args.sources)?;
    let metric = args.metric.metric(&mesh)?;
    let run = args.metric.options();
    let solver = Solver::new(&mesh, metric, &run)?;
    let field = solver.field(Sources::from(&sources).until(&Stop::NONE))?;
    let levels = levels_of(&field, args.levels, &args.at);
    let lines = field.isolines(&levels, &options)?;
    drop(spinner);
    write_isolines(&mut outputs, &args.output, format, &mesh, &lines)?;
    args.picture
        .draw(&mut outputs, &field, &sources, Some(&lines))?;
    outputs.commit()?;
    let closed = lines.iter().filter(|l| l.closed).count();
    let points: usize = lines.iter().map(|l| l.points.len()).sum();
    let say = |line: String| {
        if args.output.as_os_str() == "-" {
            ui::info!("{line}");
        } else {
            ui::say!("{line}");
        }
    };
    say(format!(
        "levels: {} (from {} to {})",
        levels.len(),
        Value(levels.iter().copied().fold(f64::INFINITY, f64::min)),
        Value(levels.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
    ));
    say(format!(
        "isolines: {} ({closed} closed), {points} points",
        lines.len()
    ));
    crate::report_run(&args.mesh, field.stats(), &args.output);
    Ok(())
}

/// A surface point as text, quoted where it holds commas (RFC 4180).
fn csv_point(point: &SurfacePoint) -> String {
    let text = point.to_string();
    if text.contains(',') {
        format!("\"{text}\"")
    } else {
        text
    }
}

/// Checks a count of levels and a list of them (named `flags` on the command line).
pub fn check_levels(count: usize, at: &[f64], flags: (&str, &str)) -> CliResult {
    if let Some(bad) = at.iter().find(|d| !d.is_finite()) {
        return Err(format!("{} {bad}: levels must be finite numbers", flags.1).into());
    }
    if at.is_empty() && count == 0 {
        return Err(format!("{} 0: ask for at least one level", flags.0).into());
    }
    // The library's bound, before the field is computed.
    let (flag, count) = match at.len() {
        0 => (flags.0, count),
        listed => (flags.1, listed),
    };
    geotracks::trace::check_level_count(count).map_err(|e| format!("{flag} {count}: {e}"))?;
    Ok(())
}

/// The levels `at`, or else `count` levels spread over the field's range.
pub fn levels_of<M: geotracks::Metric, T: geotracks::mesh::Topology>(
    query: &Field<M, geotracks::FieldData, T>,
    count: usize,
    at: &[f64],
) -> Vec<f64> {
    if at.is_empty() {
        spread_levels(query.max_reached_distance(), count)
    } else {
        at.to_vec()
    }
}

pub fn write_isolines(
    outputs: &mut Outputs,
    file: &Path,
    format: OutputFormat,
    mesh: &TriMesh,
    lines: &[Isoline],
) -> CliResult {
    match format {
        OutputFormat::Obj => outputs.write(file, |w| {
            writeln!(w, "# geotracks isolines: one `l` line per isoline")?;
            let mut base = 1usize;
            for line in lines {
                writeln!(w, "# level {}", line.level)?;
                for p in &line.points {
                    let x = p.position(mesh);
                    writeln!(w, "v {} {} {}", x.x, x.y, x.z)?;
                }
                write!(w, "l")?;
                for i in 0..line.points.len() {
                    write!(w, " {}", base + i)?;
                }
                writeln!(w)?;
                base += line.points.len();
            }
            Ok(())
        })?,
        OutputFormat::Csv => outputs.write(file, |w| {
            writeln!(w, "level,line,closed,x,y,z,point")?;
            for (i, line) in lines.iter().enumerate() {
                for p in &line.points {
                    let x = p.position(mesh);
                    writeln!(
                        w,
                        "{},{i},{},{},{},{},{}",
                        line.level,
                        line.closed,
                        x.x,
                        x.y,
                        x.z,
                        csv_point(p)
                    )?;
                }
            }
            Ok(())
        })?,
        OutputFormat::GeoJson => outputs.write(file, |w| {
            write_geojson(w, lines, &|p| p.position(mesh).to_array(), None)
        })?,
    }
    Ok(())
}

/// The isolines as a GeoJSON FeatureCollection: a LineString per line, with its `level`
/// and whether it is `closed`; each point written as `position` gives it, and the
/// collection's `crs` member if one is given.
pub fn write_geojson(
    w: &mut dyn Write,
    lines: &[Isoline],
    position: &dyn Fn(&SurfacePoint) -> [f64; 3],
    crs: Option<&serde_json::Value>,
) -> std::io::Result<()> {
    write!(w, "{{\"type\": \"FeatureCollection\", ")?;
    if let Some(crs) = crs {
        write!(w, "\"crs\": {crs}, ")?;
    }
    writeln!(w, "\"features\": [")?;
    for (i, line) in lines.iter().enumerate() {
        write!(
            w,
            "{{\"type\": \"Feature\", \"properties\": {{\"level\": {}, \"closed\": {}}}, \
             \"geometry\": {{\"type\": \"LineString\", \"coordinates\": [",
            line.level, line.closed
        )?;
        for (j, p) in line.points.iter().enumerate() {
            let [x, y, z] = position(p);
            let sep = if j == 0 { "" } else { ", " };
            write!(w, "{sep}[{x}, {y}, {z}]")?;
        }
        let sep = if i + 1 == lines.len() { "" } else { "," };
        writeln!(w, "]}}}}{sep}")?;
    }
    writeln!(w, "]}}")
}
