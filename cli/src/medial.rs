//! `geotracks medial-axis`: the medial axis of a closed surface mesh, written as `.ma`;
//! and the axis that `geotracks skeleton` starts from (a `.ma` file as it is, any other
//! mesh through its medial axis).

use crate::output::Outputs;
use crate::picture::CameraArgs;
use crate::{ui, CliResult, Short};
use geotracks::mesh::io::MedialAxis;
use geotracks::skeleton::medial::{medial_axis, medial_axis_of_file, MedialAxisOptions};
use geotracks_render::render_field;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How a surface mesh's medial axis is sampled and filtered.
#[derive(clap::Args)]
pub struct SamplingArgs {
    /// For a surface mesh: the largest distance between samples on its faces (points are
    /// added on faces larger than that) [default: the mesh's mean edge length].
    #[arg(long, value_name = "LENGTH", value_parser = parse_spacing)]
    spacing: Option<f64>,
    /// For a surface mesh: keep the Voronoi facets whose two samples are seen under at
    /// least this angle (degrees) from the facet, and half of it from its deepest
    /// point; larger drops more spikes toward the surface.
    #[arg(long, value_name = "DEGREES", default_value_t = MedialAxisOptions::DEFAULT_MIN_ANGLE_DEGREES, value_parser = parse_angle)]
    angle: f64,
    /// For a surface mesh: keep the Voronoi facets whose two samples lie at least this
    /// many spacings apart; larger drops more of the sampling's spikes and eats the
    /// axis back more at the tips of limbs.
    #[arg(long, value_name = "SPACINGS", default_value_t = MedialAxisOptions::DEFAULT_MIN_SPAN, value_parser = parse_span)]
    span: f64,
    /// Merge the surface's vertices at identical positions first (files whose seams split
    /// vertices, which would otherwise leave it open).
    #[arg(long)]
    weld: bool,
}

impl SamplingArgs {
    fn options(&self) -> MedialAxisOptions {
        MedialAxisOptions::default()
            .with_spacing(self.spacing)
            .with_min_angle_degrees(self.angle)
            .with_min_span(self.span)
    }
}

/// Parses `--spacing`: a positive, finite length.
fn parse_spacing(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s > 0.0 && s.is_finite() => Ok(s),
        _ => Err(format!(
            "'{text}': expected a positive length (such as 0.01)"
        )),
    }
}

/// Parses `--span`: a finite number >= 0.
fn parse_span(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s >= 0.0 && s.is_finite() => Ok(s),
        _ => Err(format!("'{text}': expected a number >= 0 (such as 1.5)")),
    }
}

/// Parses `--angle`: degrees strictly between 0 and 180.
fn parse_angle(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(a) if a > 0.0 && a < 180.0 => Ok(a),
        _ => Err(format!(
            "'{text}': expected an angle in degrees between 0 and 180 (such as 60)"
        )),
    }
}

/// The medial axis of `path`: read from a `.ma` file, or computed from any other mesh
/// (which must be a closed surface), with the solid's number of cycles then.
pub fn load_axis(path: &Path, sampling: &SamplingArgs) -> CliResult<(MedialAxis, Option<usize>)> {
    medial_axis_of_file(path, sampling.weld, &sampling.options()).map_err(|e| named(path, e))
}

/// A library error for the file at `path`: a reader's names the file already, others
/// get it.
fn named(path: &Path, e: geotracks::Error) -> Box<dyn std::error::Error> {
    match e {
        geotracks::Error::Mesh(e) => e.into(),
        e => format!("{}: {e}", path.display()).into(),
    }
}

/// Arguments of `geotracks medial-axis`.
#[derive(clap::Args)]
pub struct MedialAxisArgs {
    /// The closed surface (OBJ, PLY, OFF or STL).
    mesh: PathBuf,
    #[command(flatten)]
    sampling: SamplingArgs,
    /// Output: the medial axis (.ma: vertices with medial radius, edges, faces).
    #[arg(short, long, value_name = "AXIS.ma")]
    output: PathBuf,
    /// Also draw a picture (.png): the axis coloured by medial radius.
    #[arg(long, value_name = "PICTURE.png")]
    png: Option<PathBuf>,
    #[command(flatten)]
    camera: CameraArgs,
}

pub fn run(args: &MedialAxisArgs) -> CliResult {
    crate::output_format(&args.output, &[("ma", ())])?;
    if let Some(png) = &args.png {
        crate::output_format(png, &[("png", ())])?;
    }
    let mut outputs = Outputs::new([args.mesh.as_path()]);
    outputs.declare(&args.output)?;
    outputs.declare_some(args.png.as_ref())?;
    let start = Instant::now();
    let spinner = ui::Spinner::start("sampling the surface, building its Voronoi diagram");
    let mesh = crate::inputs::load_mesh(&args.mesh, args.sampling.weld)?;
    let axis = medial_axis(&mesh, &args.sampling.options()).map_err(|e| named(&args.mesh, e))?;
    drop(spinner);
    if let (Some(path), Some(sheets)) = (&args.png, &axis.surface) {
        let picture = render_field(sheets, &axis.radii, &[], &[], &args.camera.options())?;
        outputs.write(path, |w| picture.write_png_to(w))?;
    }
    outputs.write(&args.output, |w| {
        geotracks::mesh::io::write_medial_axis_to(w, &axis)
    })?;
    outputs.commit()?;
    let report = axis.report();
    let betti = axis.betti_numbers();
    ui::info!(
        "{}: medial axis of {} vertices, {} faces, {} component(s), b1 = {}, radius {}..{}, {:.3} s; wrote {}",
        args.mesh.display(),
        axis.positions.len(),
        report.faces,
        betti.b0,
        betti.b1,
        Short(axis.radii.iter().copied().fold(f64::INFINITY, f64::min)),
        Short(axis.radii.iter().copied().fold(0.0, f64::max)),
        start.elapsed().as_secs_f64(),
        crate::shown(&args.output)
    );
    Ok(())
}
