//! The `geotracks` command-line tool: a thin layer that parses arguments, calls the
//! library and writes files.

// Doc comments on the argument structs are clap's help text, written for a terminal
// (`slope:A[,max:DEG]`), not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod distance;
mod inputs;
mod matrix;
mod metric;
mod output;
mod path;
mod points;
mod skeleton;
mod terrain;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// Geodesic distances on triangle meshes (geodesic tracks method).
#[derive(Parser)]
#[command(name = "geotracks", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Compute a distance field from one or more sources (vertices, or any surface
    /// points).
    #[command(after_help = points::SP_HELP)]
    Distance(distance::DistanceArgs),
    /// Trace the shortest path from a target point to the nearest source and write it as
    /// a polyline (.obj or .csv); print its length on the last line.
    #[command(after_help = points::SP_HELP)]
    Path(path::PathArgs),
    /// Distances from many sources (rows) to every vertex or to listed targets
    /// (columns), computed on all cores.
    Matrix(matrix::MatrixArgs),
    /// Burn a medial axis (.ma) from its boundary and write the skeleton of its ridges,
    /// joined with its free edges, as OBJ polylines.
    Skeleton(skeleton::SkeletonArgs),
    /// The cheapest route between two map points of an elevation grid (ESRI .asc or
    /// GeoTIFF) under a terrain cost, written as GeoJSON or CSV, with an optional map
    /// (.png); print its cost on the last line.
    Terrain(terrain::TerrainArgs),
    /// Print what a mesh is made of: counts, boundary, non-manifold edges, components.
    Info {
        /// The mesh (OBJ, PLY, OFF, STL or .ma).
        mesh: PathBuf,
    },
    /// Compute a distance field on the bundled Spot model and write a coloured PLY.
    Demo {
        /// Where to write the coloured mesh.
        #[arg(short, long, default_value = "spot_distance.ply")]
        output: PathBuf,
    },
}

fn main() -> ExitCode {
    output::remove_on_signal();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Distance(args) => distance::run(&args),
        Command::Path(args) => path::run(&args),
        Command::Matrix(args) => matrix::run(&args),
        Command::Skeleton(args) => skeleton::run(&args),
        Command::Terrain(args) => terrain::run(&args),
        Command::Info { mesh } => info(&mesh),
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

/// A distance as text: shortest round-trip form, `inf` when unreachable, `0` for -0.
pub(crate) struct Value(pub f64);

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_infinite() {
            f.write_str("inf")
        } else {
            // An empty sum of floats is -0 (a path of one point); adding 0 makes it 0
            // and leaves every other value as it is.
            write!(f, "{}", self.0 + 0.0)
        }
    }
}

/// Errors of the CLI: the library's, plus the CLI's own input files.
pub(crate) type CliResult<T = ()> = Result<T, Box<dyn std::error::Error>>;

/// The end of a run's summary line: Steiner points, seconds, and whether it stopped at
/// its target.
pub(crate) fn run_summary(s: &geotracks::Stats) -> String {
    format!(
        "{} Steiner points, {:.3} s{}",
        s.steiner_points,
        s.setup_seconds + s.propagate_seconds,
        if s.stopped_early {
            ", stopped at the target"
        } else {
            ""
        }
    )
}

/// The run's line on stderr for a command on a mesh: the mesh, its size, the method,
/// [`run_summary`], and the file written.
pub(crate) fn report_run(mesh: &std::path::Path, s: &geotracks::Stats, output: &std::path::Path) {
    eprintln!(
        "{}: {} vertices, method {}, {}; wrote {}",
        mesh.display(),
        s.vertices,
        s.method,
        run_summary(s),
        output.display()
    );
}

/// The format of output file `path`, by its extension (any case), among `formats`
/// (extension, format); the error lists the extensions accepted.
pub(crate) fn output_format<F: Copy>(
    path: &std::path::Path,
    formats: &[(&str, F)],
) -> CliResult<F> {
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

fn info(path: &std::path::Path) -> CliResult {
    let mesh = inputs::load_mesh(path)?;
    println!("{}", path.display());
    println!("{}", mesh.report());
    Ok(())
}
