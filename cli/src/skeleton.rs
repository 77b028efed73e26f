//! `geotracks skeleton`: the skeleton of a medial axis (read, or computed from a closed
//! surface), burnt from its boundary.

use crate::output::Outputs;
use crate::picture::CameraArgs;
use crate::{ui, CliResult, Short};
use geotracks::mesh::io::{write_obj_lines_to, write_ply_with_distance_to};
use geotracks::skeleton::{
    medial_axis_skeleton_with_cycles, Burn, Placement, Prune, Pruning, DEFAULT_MIN_PROTRUSION,
    DEFAULT_MIN_TUBULARITY, DEFAULT_PRUNE_PERCENT,
};
use geotracks::{Method, Options};
use geotracks_render::render_skeleton;
use std::path::PathBuf;
use std::time::Instant;

/// When each point of the axis may burn.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum BurnArg {
    /// At its grassfire distance from the axis's border: curves along each sheet's middle.
    Boundary,
    /// At its medial radius: curves through the largest balls (faster, smoother).
    Radius,
}

/// Arguments of `geotracks skeleton`.
#[derive(clap::Args)]
pub struct SkeletonArgs {
    /// The medial axis (.ma: vertices with radius, edges, faces), or a closed surface
    /// mesh (OBJ, PLY, OFF, STL) whose medial axis is computed first.
    axis: PathBuf,
    #[command(flatten)]
    sampling: crate::medial::SamplingArgs,
    /// Mean number of Steiner points per edge.
    #[arg(long, default_value_t = 5.0)]
    k: f64,
    /// The most distance tests one run may be estimated to make (a number such as 1e10,
    /// or `none`): a k that needs more is refused before any work, with the estimate
    /// and the largest k that fits [default: 4e9, a few minutes of one core].
    #[arg(long, value_name = "TESTS", value_parser = crate::metric::parse_work_limit)]
    work_limit: Option<crate::metric::WorkLimit>,
    /// Propagation method.
    #[arg(long, default_value = "tracks")]
    method: Method,
    /// Prune branches that stood less than T as curves after the fire reached them
    /// (their erosion thickness), and, once placed, branches from tips shorter than T: a
    /// length in the axis's units, or a percentage of its bounding box diagonal (`2%`);
    /// 0 keeps everything, `inf` only what never burns.
    #[arg(long, value_name = "T", default_value_t = format!("{DEFAULT_PRUNE_PERCENT}%"))]
    prune: String,
    /// Also prune branches whose erosion thickness is less than R times the medial
    /// radius where they join the rest (their tubularity): a bump short for its
    /// thickness goes before a long thin limb of the same length; 0 keeps everything.
    #[arg(long, value_name = "R", default_value_t = DEFAULT_MIN_TUBULARITY, value_parser = parse_ratio)]
    tubular: f64,
    /// Then prune branches whose medial balls reach out of the rest of the skeleton's
    /// balls by less than P times the medial radius where they join (their
    /// protrusion), least protrusive first: spurs that run inside the body and bumps
    /// that stand out less than P of its thickness go, limbs stay; 0 keeps everything.
    #[arg(long, value_name = "P", default_value_t = DEFAULT_MIN_PROTRUSION, value_parser = parse_ratio)]
    protrusion: f64,
    /// Cut each placed branch from a tip back to the innermost medial ball that holds
    /// its end, by no more than the end's radius, near where a mean-curvature-flow
    /// skeleton's tips lie: the default.
    #[arg(long, conflicts_with = "keep_tips")]
    trim_tips: bool,
    /// Let the branches from tips run out to where the axis meets the surface.
    #[arg(long)]
    keep_tips: bool,
    /// When each point may burn.
    #[arg(long, value_enum, default_value = "boundary")]
    burn: BurnArg,
    /// Move the skeleton's points off the axis to the centre of the shape's
    /// cross-section there (the cut of the medial balls by the plane across the curve),
    /// as a mean-curvature-flow skeleton lies: the default. An axis of curves only (no
    /// sheets) keeps its points on its curves either way.
    #[arg(long, conflicts_with = "on_axis")]
    centred: bool,
    /// Keep the skeleton's points on the medial axis: a .ma file's, or the one computed
    /// from a surface mesh (which zig-zags round the true one where a limb is only a
    /// few samples across).
    #[arg(long)]
    on_axis: bool,
    /// Output: OBJ polylines (`v` and `l` lines; junctions shared) or a JSON graph
    /// (points with position, medial radius, significance and tubularity; edges;
    /// polylines).
    #[arg(short, long, value_name = "SKELETON.obj|.json")]
    output: PathBuf,
    /// Also write the grassfire field as a coloured PLY of the sheets.
    #[arg(long, value_name = "FIELD.ply")]
    field: Option<PathBuf>,
    /// Also draw a picture (.png): the skeleton coloured by medial radius over the
    /// pale, semi-transparent axis, tips and junctions as dots.
    #[arg(long, value_name = "PICTURE.png")]
    png: Option<PathBuf>,
    #[command(flatten)]
    camera: CameraArgs,
}

/// Parses `--tubular` and `--protrusion`: a number ≥ 0.
fn parse_ratio(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(r) if r >= 0.0 => Ok(r),
        _ => Err(format!("'{text}': expected a number >= 0 (such as 1.5)")),
    }
}

pub fn run(args: &SkeletonArgs) -> CliResult {
    let format = crate::text_output_format(
        &args.output,
        &[("obj", Format::Obj), ("json", Format::Json)],
        Format::Obj,
    )?;
    if let Some(field) = &args.field {
        crate::output_format(field, &[("ply", ())])?;
    }
    if let Some(png) = &args.png {
        crate::output_format(png, &[("png", ())])?;
    }
    let prune: Prune = args.prune.parse().map_err(|e| format!("--prune {e}"))?;
    let mut outputs = Outputs::new([args.axis.as_path()]);
    outputs.declare(&args.output)?;
    outputs.declare_some(args.field.as_ref())?;
    outputs.declare_some(args.png.as_ref())?;
    let start = Instant::now();
    let spinner = ui::Spinner::start("reading the medial axis, burning and thinning it");
    let (axis, solid_cycles) = crate::medial::load_axis(&args.axis, &args.sampling)?;
    let prune = prune.threshold(axis.diagonal());
    let options = crate::metric::WorkLimit::apply(
        args.work_limit,
        Options::DEFAULT.with_k(args.k).with_method(args.method),
    );
    let burn = match args.burn {
        BurnArg::Radius => Burn::Radius,
        BurnArg::Boundary => Burn::Boundary,
    };
    let (skeleton, fire) = medial_axis_skeleton_with_cycles(
        &axis,
        burn,
        &options,
        Pruning {
            erosion_thickness: prune,
            tubularity: args.tubular,
            protrusion: args.protrusion,
            trim_tips: !args.keep_tips,
        },
        solid_cycles.unwrap_or(usize::MAX),
        match (args.centred, args.on_axis) {
            (true, _) => Placement::Centred,
            (_, true) => Placement::OnAxis,
            _ => Placement::default(),
        },
    )?;
    drop(spinner);
    if skeleton.added_cycles > 0 {
        eprintln!(
            "warning: {} part(s) of the medial axis cannot be thinned without opening a cycle; the skeleton has {} cycle(s) the axis does not",
            skeleton.added_cycles, skeleton.added_cycles
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
                "{}: no grassfire field to write (the medial axis has no sheet with a border to burn from, or --burn radius)",
                path.display()
            )
            .into())
        }
        (None, ..) => {}
    }
    if let Some(path) = &args.png {
        let picture = render_skeleton(&axis, &skeleton, &args.camera.options())?;
        outputs.write(path, |w| picture.write_png_to(w))?;
    }
    match format {
        Format::Obj => outputs.write(&args.output, |w| write_obj_lines_to(w, &points, &lines))?,
        Format::Json => outputs.write(&args.output, |w| write_json(w, &skeleton, &lines))?,
    }
    outputs.commit()?;
    ui::info!(
        "{}: {} skeleton points, {} polylines, {} component(s), {} cycle(s) ({} has b1 = {}{}), {} tips, length {}, {:.3} s; wrote {}",
        args.axis.display(),
        skeleton.points.len(),
        lines.len(),
        skeleton.component_count(),
        skeleton.cycle_count(),
        if solid_cycles.is_some() { "the solid" } else { "the axis" },
        solid_cycles.unwrap_or(axis.betti_numbers().b1),
        match skeleton.opened_cycles {
            0 => String::new(),
            n => format!("; {n} hole(s) of the axis opened, no tunnel of the solid"),
        },
        skeleton.tip_count(),
        Short(skeleton.length()),
        start.elapsed().as_secs_f64(),
        crate::shown(&args.output)
    );
    Ok(())
}

#[derive(Clone, Copy)]
enum Format {
    Obj,
    Json,
}

/// The skeleton as a JSON graph; a significance or tubularity of `inf` (what never
/// burns) is `null`.
fn write_json(
    w: &mut dyn std::io::Write,
    skeleton: &geotracks::skeleton::Skeleton,
    lines: &[Vec<u32>],
) -> std::io::Result<()> {
    let finite = |x: f64| x.is_finite().then_some(x);
    let points: Vec<serde_json::Value> = skeleton
        .points
        .iter()
        .map(|p| {
            serde_json::json!({
                "position": p.position,
                "radius": p.radius,
                "significance": finite(p.significance),
                "tubularity": finite(p.tubularity),
            })
        })
        .collect();
    let json = serde_json::json!({
        "points": points,
        "edges": skeleton.edges,
        "polylines": lines,
        "components": skeleton.component_count(),
        "cycles": skeleton.cycle_count(),
        "opened_cycles": skeleton.opened_cycles,
        "tips": skeleton.tip_count(),
    });
    serde_json::to_writer(&mut *w, &json).map_err(std::io::Error::other)?;
    writeln!(w)
}
