//! `geotracks skeleton`: the skeleton of a medial axis, burnt from its boundary.

use crate::output::Outputs;
use crate::{ui, CliResult, Short};
use geotracks::mesh::io::{read_medial_axis, write_obj_lines_to, write_ply_with_distance_to};
use geotracks::skeleton::medial_axis_skeleton;
use geotracks::{Method, Options};
use std::path::PathBuf;
use std::time::Instant;

/// How fast the grassfire burns.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum Speed {
    /// The same everywhere (Euclidean distance on the sheets).
    Uniform,
    /// Faster where medial balls are larger (density mean(r) / r per vertex).
    Radius,
}

/// Arguments of `geotracks skeleton`.
#[derive(clap::Args)]
pub struct SkeletonArgs {
    /// The medial axis (.ma: vertices with radius, edges, faces).
    axis: PathBuf,
    /// Mean number of Steiner points per edge.
    #[arg(long, default_value_t = 5.0)]
    k: f64,
    /// Propagation method.
    #[arg(long, default_value = "tracks")]
    method: Method,
    /// Prune branch points whose two sides are less than T apart along the boundary:
    /// a length in the axis's units, or a percentage of its bounding box diagonal
    /// (`2%`); 0 keeps everything.
    #[arg(long, value_name = "T", default_value = "0")]
    prune: String,
    /// Grassfire speed.
    #[arg(long, value_enum, default_value = "uniform")]
    speed: Speed,
    /// Output: the skeleton as OBJ polylines (`v` and `l` lines; junctions shared).
    #[arg(short, long)]
    output: PathBuf,
    /// Also write the grassfire field as a coloured PLY of the sheets.
    #[arg(long, value_name = "FIELD.ply")]
    field: Option<PathBuf>,
}

pub fn run(args: &SkeletonArgs) -> CliResult {
    crate::text_output_format(&args.output, &[("obj", ())], ())?;
    if let Some(field) = &args.field {
        crate::output_format(field, &[("ply", ())])?;
    }
    let (value, percent) = match args.prune.strip_suffix('%') {
        Some(p) => (p.trim().parse::<f64>(), true),
        None => (args.prune.trim().parse::<f64>(), false),
    };
    let prune = match value {
        Ok(v) if v >= 0.0 && v.is_finite() => v,
        _ => {
            return Err(format!(
                "--prune {}: expected a length >= 0 or a percentage such as 2%",
                args.prune
            )
            .into())
        }
    };
    let mut outputs = Outputs::new([args.axis.as_path()]);
    outputs.declare(&args.output)?;
    outputs.declare_some(args.field.as_ref())?;
    let start = Instant::now();
    let spinner = ui::Spinner::start("reading the medial axis, burning and tracing ridges");
    let axis = read_medial_axis(&args.axis)?;
    let prune = if percent {
        prune / 100.0 * diagonal(&axis.positions)
    } else {
        prune
    };
    let options = Options::DEFAULT.with_k(args.k).with_method(args.method);
    let radius_aware = matches!(args.speed, Speed::Radius);
    let (skeleton, fire) = medial_axis_skeleton(&axis, radius_aware, &options, prune)?;
    drop(spinner);
    if skeleton.closed_components > 0 {
        eprintln!(
            "warning: {} closed part(s) of the medial axis have no boundary to burn from and no skeleton",
            skeleton.closed_components
        );
    }
    let points: Vec<[f64; 3]> = skeleton.points.iter().map(|p| p.position).collect();
    let lines = skeleton.polylines();
    match (&args.field, &fire, &axis.surface) {
        (Some(path), Some(fire), Some(mesh)) => {
            let d = fire.vertex_distances();
            outputs.write(path, |w| write_ply_with_distance_to(w, mesh, d))?;
        }
        (Some(path), ..) => {
            return Err(format!(
                "{}: the medial axis has no sheet, so no grassfire field to write",
                path.display()
            )
            .into())
        }
        (None, ..) => {}
    }
    outputs.write(&args.output, |w| write_obj_lines_to(w, &points, &lines))?;
    outputs.commit()?;
    ui::info!(
        "{}: {} skeleton points, {} polylines, {} component(s), length {}, {:.3} s; wrote {}",
        args.axis.display(),
        skeleton.points.len(),
        lines.len(),
        skeleton.component_count(),
        Short(skeleton.length()),
        start.elapsed().as_secs_f64(),
        crate::shown(&args.output)
    );
    Ok(())
}

/// Length of the diagonal of the points' bounding box.
fn diagonal(points: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}
