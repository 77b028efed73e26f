//! The `geotracks` command-line tool: a thin layer that parses arguments, calls the
//! library and writes files.

// Doc comments on the argument structs are clap's help text, written for a terminal
// (`slope:A[,max:DEG]`), not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod distance;
mod inputs;
mod isolines;
mod matrix;
mod medial;
mod metric;
mod output;
mod path;
mod picture;
mod points;
mod skeleton;
mod terrain;
mod ui;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// Geodesic distances on triangle meshes (geodesic tracks method).
#[derive(Parser)]
#[command(name = "geotracks", version, about, after_help = MAIN_HELP)]
struct Cli {
    /// Print only warnings and errors: no summaries, no progress.
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    quiet: bool,
    /// Also print the run's counters and timings.
    #[arg(short, long, global = true)]
    verbose: bool,
    #[command(subcommand)]
    command: Command,
}

const MAIN_HELP: &str = "\
Outputs are written all or nothing: checked before the work, replaced only when all of
them are written. `-o -` writes a text output to standard output.

Exit status: 0 on success, 1 on an error (bad input, failed output), 2 when the command
line cannot be parsed, 130 when interrupted.

Examples:
  geotracks demo
  geotracks distance mesh.obj --source 0 -o distance.ply
  geotracks path mesh.obj --source 0 --target 100 -o path.obj
  geotracks <COMMAND> --help";

#[derive(Subcommand)]
enum Command {
    /// Compute a distance field from one or more sources (vertices, or any surface
    /// points).
    #[command(after_help = with_examples(points::SP_HELP, DISTANCE_EXAMPLES))]
    Distance(distance::DistanceArgs),
    /// Trace the shortest path from a target point to the nearest source and write it as
    /// a polyline (.obj or .csv); print its length on the last line.
    #[command(after_help = with_examples(points::SP_HELP, PATH_EXAMPLES))]
    Path(path::PathArgs),
    /// Distances from many sources (rows) to every vertex or to listed targets
    /// (columns), computed on all cores.
    #[command(after_help = with_examples("", MATRIX_EXAMPLES))]
    Matrix(matrix::MatrixArgs),
    /// Draw the isolines of a distance field (points on their level, bending where the
    /// field's regions meet) as polylines: .obj, .csv or .geojson.
    #[command(after_help = with_examples(points::SP_HELP, ISOLINES_EXAMPLES))]
    Isolines(isolines::IsolinesArgs),
    /// The medial axis of a closed surface mesh, from the Voronoi diagram of points
    /// sampled on it: its sheets with the medial radius at each vertex, as .ma.
    #[command(name = "medial-axis", after_help = with_examples("", MEDIAL_AXIS_EXAMPLES))]
    MedialAxis(medial::MedialAxisArgs),
    /// The curve skeleton of a medial axis (.ma), or of a closed surface mesh through its
    /// medial axis: burnt, thinned without changing its topology, pruned by erosion
    /// thickness; OBJ polylines or a JSON graph with radii.
    #[command(after_help = with_examples("", SKELETON_EXAMPLES))]
    Skeleton(skeleton::SkeletonArgs),
    /// The cheapest route between two map points of an elevation grid (ESRI .asc or
    /// GeoTIFF) under a terrain cost, written as GeoJSON or CSV, with an optional map
    /// (.png); print its cost on the last line.
    #[command(after_help = with_examples("", TERRAIN_EXAMPLES))]
    Terrain(terrain::TerrainArgs),
    /// Print what a mesh is made of: counts, boundary, non-manifold edges, duplicate
    /// positions, bounding box, mean edge length, and per component the Euler
    /// characteristic and (for orientable manifold components) the genus.
    #[command(after_help = with_examples("", INFO_EXAMPLES))]
    Info {
        /// The mesh (OBJ, PLY, OFF, STL or .ma).
        mesh: PathBuf,
        /// Merge vertices at identical positions first, and report the welded mesh.
        #[arg(long)]
        weld: bool,
    },
    /// Compute a distance field on the bundled Spot model and write a coloured PLY and a
    /// picture of it (PNG, beside the PLY).
    #[command(after_help = with_examples("", DEMO_EXAMPLES))]
    Demo {
        /// Where to write the mesh: .ply (coloured), .txt or .csv; by default into
        /// geotracks-out/ (created if needed; git ignores it).
        #[arg(short, long, default_value = distance::DEMO_OUTPUT)]
        output: PathBuf,
    },
}

/// A subcommand's text after its options: `before` (if any), then its examples.
fn with_examples(before: &str, examples: &str) -> String {
    match before {
        "" => format!("Examples:\n{examples}"),
        _ => format!("{before}\n\nExamples:\n{examples}"),
    }
}

const DISTANCE_EXAMPLES: &str = "  geotracks distance mesh.obj --source 0 -o distance.ply --png distance.png
  geotracks distance mesh.obj --source 0 -o d.txt --png d.png --view 30,20 --size 800x800
  geotracks distance mesh.obj --source 0 --source f:12:0.2,0.3,0.5 --voronoi cells.txt -o d.csv
  geotracks distance mesh.obj --source 0 --density rho.txt --max-distance 2.5 -o d.txt --stats run.json
  geotracks distance mesh.obj --source 0 -o - | head   # vertex,distance on standard output";

const PATH_EXAMPLES: &str = "  geotracks path mesh.obj --source 0 --target 100 -o path.obj
  geotracks path mesh.obj --source e:40:0.25 --target f:12:0.2,0.3,0.5 --tensor m.txt -o path.csv
  geotracks path mesh.obj --source 0 --target 100 -o -   # x,y,z,point on standard output";

const MATRIX_EXAMPLES: &str = "  geotracks matrix mesh.obj --sources sources.txt -o all.csv
  geotracks matrix mesh.obj --sources sources.txt --targets targets.txt -o pairs.csv";

const ISOLINES_EXAMPLES: &str = "  geotracks isolines mesh.obj --source 0 -o iso.obj --png iso.png
  geotracks isolines mesh.obj --source 0 --at 0.5,1,1.5 -o iso.geojson
  geotracks isolines mesh.obj --source f:12:0.2,0.3,0.5 --levels 20 --tensor m.txt -o iso.csv";

const SKELETON_EXAMPLES: &str =
    "  geotracks skeleton cow.ma --prune 5% --tubular 1 -o cow_skeleton.obj --field cow_fire.ply
  geotracks skeleton axis.ma --burn radius --prune 0.05 -o skeleton.json
  geotracks skeleton cow.ma -o cow.obj --png cow.png --view 30,20
  geotracks skeleton spot.obj -o spot_skeleton.obj   # a closed surface: its medial axis first, points centred
  geotracks skeleton spot.obj --on-axis -o spot_on_axis.obj";

const MEDIAL_AXIS_EXAMPLES: &str = "  geotracks medial-axis spot.obj -o spot.ma --png spot_axis.png
  geotracks medial-axis part.stl --spacing 0.5 --angle 75 -o part.ma
  geotracks skeleton spot.ma -o spot_skeleton.obj";

const TERRAIN_EXAMPLES: &str = "  geotracks terrain dem.tif --from 499.5,499.5 --to 9490.5,9290.7 -o route.geojson
  geotracks terrain dem.asc --from 1010,5010 --to 1290,5180 --cost slope:4,max:30 -o route.csv --png map.png";

const INFO_EXAMPLES: &str = "  geotracks info mesh.obj
  geotracks info axis.ma";

const DEMO_EXAMPLES: &str = "  geotracks demo
  geotracks demo -o spot.csv";

fn main() -> ExitCode {
    output::remove_on_signal();
    let cli = Cli::parse();
    ui::set_level(cli.quiet, cli.verbose);
    let result = match cli.command {
        Command::Distance(args) => distance::run(&args),
        Command::Path(args) => path::run(&args),
        Command::Matrix(args) => matrix::run(&args),
        Command::Isolines(args) => isolines::run(&args),
        Command::MedialAxis(args) => medial::run(&args),
        Command::Skeleton(args) => skeleton::run(&args),
        Command::Terrain(args) => terrain::run(&args),
        Command::Info { mesh, weld } => info(&mesh, weld),
        Command::Demo { output } => distance::demo(&output),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A number as data (distances, costs, lengths): the shortest text that reads back as
/// the same f64, in scientific notation (`1.5e300`) when its magnitude is at least 1e16
/// or below 1e-5, so that no value prints as hundreds of digits; `inf` when
/// unreachable, `0` for -0.
pub(crate) struct Value(pub f64);

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // An empty sum of floats is -0 (a path of one point); adding 0 makes it 0 and
        // leaves every other value as it is.
        let x = self.0 + 0.0;
        let a = x.abs();
        if x.is_infinite() {
            f.write_str(if x > 0.0 { "inf" } else { "-inf" })
        } else if x == 0.0 || x.is_nan() || (1e-5..1e16).contains(&a) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// A number for people (summaries on the terminal): 6 significant digits, trailing
/// zeros dropped, scientific notation outside [1e-4, 1e6).
pub(crate) struct Short(pub f64);

impl std::fmt::Display for Short {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0 + 0.0;
        let a = x.abs();
        if !x.is_finite() || x == 0.0 {
            return Value(x).fmt(f);
        }
        if !(1e-4..1e6).contains(&a) {
            return write!(f, "{x:.5e}");
        }
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        let text = format!("{x:.decimals$}");
        let text = match text.contains('.') {
            true => text.trim_end_matches('0').trim_end_matches('.'),
            false => &text,
        };
        f.write_str(text)
    }
}

/// Errors of the CLI: the library's, plus the CLI's own input files.
pub(crate) type CliResult<T = ()> = Result<T, Box<dyn std::error::Error>>;

/// The end of a run's summary line: Steiner points, seconds, and whether it stopped at
/// its target (or met it, searched from both ends).
pub(crate) fn run_summary(s: &geotracks::Stats) -> String {
    format!(
        "{} Steiner points, {:.3} s{}",
        s.steiner_points,
        s.setup_seconds + s.propagate_seconds,
        match (s.stopped_early, s.both_ends) {
            (true, true) => ", searched from both ends",
            (true, false) => ", stopped at the target",
            _ => "",
        }
    )
}

/// The run's line on stderr for a command on a mesh: the mesh, its size, the method,
/// [`run_summary`], and the file written.
pub(crate) fn report_run(mesh: &std::path::Path, s: &geotracks::Stats, output: &std::path::Path) {
    ui::info!(
        "{}: {} vertices, method {}, {}; wrote {}",
        mesh.display(),
        s.vertices,
        s.method,
        run_summary(s),
        shown(output)
    );
    report_stats(s);
}

/// With `--verbose`, the run's counters and timings.
pub(crate) fn report_stats(s: &geotracks::Stats) {
    if ui::verbose() {
        eprintln!(
            "  {} faces, k = {}; setup {:.4} s, propagation {:.4} s; {} pushes, {} distance tests (+ {} in setup)",
            s.faces,
            s.k,
            s.setup_seconds,
            s.propagate_seconds,
            s.pushes,
            s.distance_tests,
            s.setup_distance_tests
        );
        if s.method == geotracks::Method::Exact {
            eprintln!(
                "  {} windows made, {} carried across faces",
                s.windows_created, s.windows_kept
            );
        }
    }
}

/// An output's name in messages: `standard output` for `-`.
pub(crate) fn shown(path: &std::path::Path) -> String {
    if path.as_os_str() == "-" {
        "standard output".into()
    } else {
        path.display().to_string()
    }
}

/// The format of an output that may go to standard output (`-`): there, `on_stdout`
/// (a text format); elsewhere as [`output_format`].
pub(crate) fn text_output_format<F: Copy>(
    path: &std::path::Path,
    formats: &[(&str, F)],
    on_stdout: F,
) -> CliResult<F> {
    if path.as_os_str() == "-" {
        return Ok(on_stdout);
    }
    output_format(path, formats)
}

/// The format of output file `path`, by its extension (any case), among `formats`
/// (extension, format); the error lists the extensions accepted.
pub(crate) fn output_format<F: Copy>(
    path: &std::path::Path,
    formats: &[(&str, F)],
) -> CliResult<F> {
    if path.as_os_str() == "-" {
        return Err(
            "standard output (-) takes text outputs only; give this one a file name".into(),
        );
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if let Some(&(_, format)) = formats.iter().find(|(e, _)| ext.as_deref() == Some(*e)) {
        return Ok(format);
    }
    let names: Vec<String> = formats.iter().map(|(e, _)| format!(".{e}")).collect();
    let expected = match names.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    };
    Err(format!(
        "{}: unknown output format (expected {expected})",
        path.display()
    )
    .into())
}

fn info(path: &std::path::Path, weld: bool) -> CliResult {
    let is_axis = geotracks::mesh::io::is_medial_axis_path(path);
    // A medial axis may be made of curves only, which a mesh reader refuses.
    let report = if is_axis && !weld {
        geotracks::mesh::io::read_medial_axis(path)?.report()
    } else {
        inputs::load_mesh(path, weld)?.report()
    };
    print_out(format_args!("{}\n{report}", path.display()))
}

/// Writes a line to standard output; a reader that stopped reading (`| head`) is no
/// error, and no panic (which `println!` would be).
pub(crate) fn print_out(text: std::fmt::Arguments<'_>) -> CliResult {
    use std::io::Write;
    match writeln!(std::io::stdout().lock(), "{text}") {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.map_err(|e| format!("standard output: {e}").into()),
    }
}

#[cfg(test)]
mod tests {
    use super::{Short, Value};

    #[test]
    fn numbers_are_never_hundreds_of_digits() {
        assert_eq!(Value(1e300).to_string(), "1e300");
        assert_eq!(Value(-2.5e-300).to_string(), "-2.5e-300");
        assert_eq!(Value(1.25).to_string(), "1.25");
        assert_eq!(Value(0.1 + 0.2).to_string(), "0.30000000000000004");
        assert_eq!(Value(123456789.0).to_string(), "123456789");
        assert_eq!(Value(1e16).to_string(), "1e16");
        assert_eq!(Value(-0.0).to_string(), "0");
        assert_eq!(Value(f64::INFINITY).to_string(), "inf");
        for x in [1e300, 3.0e-7, 0.1 + 0.2, 7e15, 123.456] {
            assert_eq!(Value(x).to_string().parse::<f64>().unwrap(), x);
        }
        assert_eq!(Short(1.5697123).to_string(), "1.56971");
        assert_eq!(Short(2.0).to_string(), "2");
        assert_eq!(Short(1e300).to_string(), "1.00000e300");
        assert_eq!(Short(12345.678).to_string(), "12345.7");
    }
}
