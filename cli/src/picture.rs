//! `--png`, `--view`, `--size`: a picture of a distance field (library:
//! `geotracks_render`), for `distance`, `isolines` and `demo`; `skeleton` shares the
//! camera arguments.

use crate::output::Outputs;
use crate::CliResult;
use geotracks::trace::{spread_levels, Isoline, IsolineOptions};
use geotracks::{Field, Metric, Source};
use geotracks_render::{render_field, PictureOptions, View};
use std::path::{Path, PathBuf};

/// Isolines drawn on a `distance` picture.
const LEVELS: usize = 10;

/// The picture options of a command.
#[derive(clap::Args)]
pub struct PictureArgs {
    /// Also draw a picture (.png): the mesh shaded and coloured by distance (viridis),
    /// isolines, the sources marked in red, and a colour bar with the range.
    #[arg(long, value_name = "PICTURE.png")]
    pub png: Option<PathBuf>,
    #[command(flatten)]
    pub camera: CameraArgs,
}

/// Where a picture looks from and how large it is (`--view`, `--size`; they need
/// `--png`).
#[derive(clap::Args)]
pub struct CameraArgs {
    /// Where the picture looks from: auto (from where the faces show the most area; for
    /// a field, the first source facing the eye), front (+z, y up), back, left, right,
    /// top, bottom, or AZ,EL (degrees about +y from the front, and above the horizon).
    #[arg(
        long,
        value_name = "VIEW",
        default_value = "auto",
        requires = "png",
        allow_hyphen_values = true
    )]
    pub view: View,
    /// The picture's size in pixels: WxH (64 to 8192 each).
    #[arg(long, value_name = "WxH", default_value = "1024x768", value_parser = parse_size, requires = "png")]
    pub size: (u32, u32),
}

impl CameraArgs {
    /// The picture options these arguments ask for.
    pub fn options(&self) -> PictureOptions {
        PictureOptions::DEFAULT
            .with_size(self.size.0, self.size.1)
            .with_view(self.view)
    }
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not WxH (two whole numbers of pixels, e.g. 1024x768)");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    for side in [w, h] {
        if !(64..=8192).contains(&side) {
            return Err(format!("'{text}': each side must be 64 to 8192 pixels"));
        }
    }
    Ok((w, h))
}

impl PictureArgs {
    /// Checks the picture's file name and declares it as an output.
    pub fn declare(&self, outputs: &mut Outputs) -> CliResult {
        if let Some(png) = &self.png {
            crate::output_format(png, &[("png", ())])?;
        }
        outputs.declare_some(self.png.as_ref())
    }

    /// Draws the field of `query` with `lines` (or, if `None`, ten isolines spread over
    /// the field) into the picture, if one was asked for.
    pub fn draw<M: Metric>(
        &self,
        outputs: &mut Outputs,
        query: &Field<M>,
        sources: &[Source],
        lines: Option<&[Isoline]>,
    ) -> CliResult {
        let Some(path) = &self.png else {
            return Ok(());
        };
        draw(outputs, path, query, sources, lines, &self.camera.options())
    }
}

/// Draws the field of `query` into `path` (see [`PictureArgs::draw`]).
pub fn draw<M: Metric>(
    outputs: &mut Outputs,
    path: &Path,
    query: &Field<M>,
    sources: &[Source],
    lines: Option<&[Isoline]>,
    options: &PictureOptions,
) -> CliResult {
    let mesh = query.mesh();
    let own;
    let lines = match lines {
        Some(lines) => lines,
        None => {
            let levels = spread_levels(query.max_reached_distance(), LEVELS);
            own = query.isolines(&levels, &IsolineOptions::DEFAULT)?;
            &own
        }
    };
    let polylines: Vec<_> = lines
        .iter()
        .map(|l| l.points.iter().map(|p| p.position(mesh)).collect())
        .collect();
    let at: Vec<_> = sources.iter().map(|s| s.point.position(mesh)).collect();
    let picture = render_field(mesh, query.vertex_distances(), &polylines, &at, options)?;
    outputs.write(path, |w| picture.write_png_to(w))
}
