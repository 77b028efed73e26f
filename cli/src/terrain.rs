//! `geotracks terrain`: the cheapest route between two map points of an elevation grid.

use crate::isolines;
use crate::output::Outputs;
use crate::{ui, CliResult, Value};
use geotracks::trace::{Isoline, IsolineOptions};
use geotracks::Sources;
use geotracks::{Error, Method, Options, Solver, Source, Stop};
use geotracks_terrain::{self as terrain, map, Route, TerrainCost, TerrainError};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Arguments of `geotracks terrain`.
#[derive(clap::Args)]
pub struct TerrainArgs {
    /// The elevation grid: ESRI ASCII (.asc) or single-band GeoTIFF (.tif, .tiff), in a
    /// projected coordinate system whose unit is the elevations' (e.g. metres).
    dem: PathBuf,
    /// Where the route starts, in the grid's coordinates.
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    from: [f64; 2],
    /// Where the route ends, in the grid's coordinates.
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    to: [f64; 2],
    /// What a route costs: none (its 3D length); slope:A[,max:DEG] (density
    /// 1 + A·tan²(slope); faces steeper than DEG degrees impassable); incline:B
    /// (crossing the slope costs sqrt(1 + B·sin²(slope)) per unit along the steepest
    /// line, either way). Directed (climbing and descending differ): uphill:B (3D
    /// length + B per metre climbed); naismith (0.72 s/m + 6 s per metre climbed);
    /// rwalk[:a,b,c,d[,slope_factor]] (GRASS r.walk's walking time in seconds, its
    /// defaults 0.72,6,1.9998,-1.9998,-0.2125); tobler[:offpath] (Tobler's hiking
    /// function, seconds). Times assume metres.
    #[arg(long, default_value = "none", value_name = "COST")]
    cost: TerrainCost,
    /// Mean number of Steiner points per edge. 2 by default: the straightened route is
    /// exact on the analytic tests at k = 2, and on a hilly grid it costs 0.03–0.9 %
    /// more than the same route at k = 6 (the guide's Terrain page, docs/src/terrain.md), where a finer graph finds a
    /// better corridor; larger k costs time and memory in proportion.
    #[arg(long, default_value_t = 2.0)]
    k: f64,
    /// The most distance tests one run may be estimated to make (a number such as 1e10,
    /// or `none`): a k that needs more is refused before any work, with the estimate
    /// and the largest k that fits [default: 4e9, a few minutes of one core].
    #[arg(long, value_name = "TESTS", value_parser = crate::metric::parse_work_limit)]
    work_limit: Option<crate::metric::WorkLimit>,
    /// Propagation method: wave (Steiner points that carry their wavefront: exact on
    /// planes, the best route at a given k; for none and incline:B, the others run
    /// tracks), or tracks (the track-pruned Steiner graph, which a route runs
    /// goal-directed, A*: it settles a corridor around the route rather than a disc;
    /// on the guide's 1000 × 1000 grid (docs/src/terrain.md), none at k = 4 routes as well as wave at
    /// k = 2, in less time).
    #[arg(long, default_value = "wave")]
    method: Method,
    /// Output: .geojson or .json (a LineString of [x, y, z] with the cost and lengths as
    /// properties) or .csv (x,y,z,cost,length per point, cumulative from the start).
    #[arg(short, long)]
    output: PathBuf,
    /// Also draw a map: hillshade, cost contours from the start, the route (.png).
    #[arg(long, value_name = "MAP.png")]
    png: Option<PathBuf>,
    /// Also write the cost contours from the start as GeoJSON: a LineString per contour
    /// ([x, y, z] points on the terrain, each exactly at its cost), with its cost.
    #[arg(long, value_name = "CONTOURS.geojson")]
    contours: Option<PathBuf>,
    /// N contours spread evenly between 0 and the largest cost reached (both excluded).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 10,
        conflicts_with = "contour_at"
    )]
    contour_levels: usize,
    /// The contours' costs, listed: C1,C2,...
    #[arg(long, value_name = "C1,C2,...", value_delimiter = ',')]
    contour_at: Vec<f64>,
}

fn parse_xy(text: &str) -> Result<[f64; 2], String> {
    let values: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("'{text}' is not X,Y (two finite numbers)"))?;
    values
        .try_into()
        .map_err(|_| format!("'{text}' is not X,Y (two finite numbers)"))
}

/// The formats `-o` accepts.
#[derive(Clone, Copy)]
enum OutputFormat {
    GeoJson,
    Csv,
}

pub fn run(args: &TerrainArgs) -> CliResult {
    let format = check_args(args)?;
    let mut outputs = Outputs::new([args.dem.as_path()]);
    outputs.declare(&args.output)?;
    outputs.declare_some(args.png.as_ref())?;
    outputs.declare_some(args.contours.as_ref())?;
    let spinner = ui::Spinner::start("reading the grid and routing");
    let reading = std::time::Instant::now();
    let grid = terrain::read_grid(&args.dem)?;
    let read_seconds = reading.elapsed().as_secs_f64();
    let mut options = crate::metric::WorkLimit::apply(
        args.work_limit,
        Options::DEFAULT.with_k(args.k).with_method(args.method),
    );
    match grid.mean_edge_length() {
        // Points spaced as on the whole grid, whatever part of it is meshed.
        Some(mean) => options = options.with_mean_edge_length(mean),
        // No triangle: the meshing error, naming the file.
        None => drop(grid.to_mesh_named(Some(&args.dem))?),
    }
    // The route: on the window of the grid it needs, the same search whatever else is
    // asked (a map or contours never change it).
    let routed = routing_error(
        terrain::route_on_grid(&grid, &args.cost, &options, args.from, args.to),
        args,
    )?;
    let (route, window) = (routed.route, routed.window);
    drop(routed.surface);
    // The map and the contours need the cost from the start everywhere: a run of its
    // own over the whole grid.
    let field_start = std::time::Instant::now();
    let whole = if args.png.is_some() || args.contours.is_some() {
        Some(whole_grid_field(args, &grid, &options)?)
    } else {
        None
    };
    let field_seconds = field_start.elapsed().as_secs_f64();
    let picture = match (&args.png, &whole) {
        (Some(_), Some((terrain, costs, _))) => {
            let xy: Vec<[f64; 2]> = route.points.iter().map(|p| [p.x, p.y]).collect();
            Some(map::render(
                &grid,
                terrain.as_ref(),
                Some(costs),
                &xy,
                &map::MapOptions::DEFAULT.with_cost_unit(args.cost.unit()),
            ))
        }
        _ => None,
    };
    let contours = whole
        .as_ref()
        .and_then(|(terrain, _, lines)| Some((terrain, lines.as_ref()?)));

    drop(spinner);
    let map_coordinates = MapCoordinates::of(&grid);
    match format {
        OutputFormat::GeoJson => write_geojson(&mut outputs, args, &route, &map_coordinates)?,
        OutputFormat::Csv => write_csv(&mut outputs, &args.output, &route, &map_coordinates)?,
    }
    if let (Some(path), Some(picture)) = (&args.png, &picture) {
        outputs.write(path, |w| picture.write_png_to(w))?;
    }
    if let (Some(path), Some((terrain, lines))) = (&args.contours, &contours) {
        let (mesh, crs) = (terrain.as_ref(), map_coordinates.crs());
        outputs.write(path, |w| {
            let position = |p: &geotracks::SurfacePoint| map_coordinates.point(p.position(mesh));
            isolines::write_geojson(w, lines, &position, crs.as_ref())
        })?;
    }
    outputs.commit()?;

    say_route(args, &route, contours.map(|(_, lines)| lines.len()))?;
    let timings = Timings {
        read_seconds,
        field_seconds,
        whole_field: whole.is_some(),
    };
    report_run(args, &grid, &route, &window, picture.as_ref(), &timings);
    Ok(())
}

/// Checks everything that can be checked before reading the grid: the output files'
/// formats, the contour levels, k. Returns the route's format.
fn check_args(args: &TerrainArgs) -> CliResult<OutputFormat> {
    let format = crate::text_output_format(
        &args.output,
        &[
            ("geojson", OutputFormat::GeoJson),
            ("json", OutputFormat::GeoJson),
            ("csv", OutputFormat::Csv),
        ],
        OutputFormat::GeoJson,
    )?;
    if let Some(png) = &args.png {
        crate::output_format(png, &[("png", ())])?;
    }
    if let Some(contours) = &args.contours {
        crate::output_format(contours, &[("geojson", ()), ("json", ())])?;
        isolines::check_levels(
            args.contour_levels,
            &args.contour_at,
            ("--contour-levels", "--contour-at"),
        )?;
    }
    if !(args.k.is_finite() && args.k > 0.0) {
        return Err(Error::InvalidK { k: args.k }.into());
    }
    Ok(format)
}

/// The grid as a surface, the cost from the start at each of its vertices, and the
/// contours if asked ([`whole_grid_field`]).
type WholeGridField = (Arc<terrain::GridSurface>, Vec<f64>, Option<Vec<Isoline>>);

/// The cost from the start over the whole grid (for a map or contours): the grid as a
/// surface (no mesh is built), the cost at each of its vertices, and the contours if
/// asked.
fn whole_grid_field(
    args: &TerrainArgs,
    grid: &terrain::ElevationGrid,
    options: &Options,
) -> CliResult<WholeGridField> {
    let surface = Arc::new(terrain::GridSurface::new(grid)?);
    let locate = |[x, y]: [f64; 2]| routing_error(surface.locate(x, y), args);
    let from = locate(args.from)?;
    let metric = args.cost.metric_on_surface(grid, &surface)?;
    let solver: Solver<_, terrain::GridSurface> =
        Solver::with_topology(Arc::clone(&surface), metric, options)?;
    let field = solver.field(Sources::from(&[Source::new(from)]).until(&Stop::NONE))?;
    let contours = match &args.contours {
        Some(_) => {
            let levels = isolines::levels_of(&field, args.contour_levels, &args.contour_at);
            Some(field.isolines(&levels, &IsolineOptions::DEFAULT)?)
        }
        None => None,
    };
    let costs = field.vertex_distances().to_vec();
    drop((field, solver));
    Ok((surface, costs, contours))
}

/// Says what the route is: its ends, cost model, points, lengths and traced cost, how
/// many contours were written (`contour_lines`), then its cost (on standard output,
/// alone on the last line, unless the route itself goes there).
fn say_route(args: &TerrainArgs, route: &Route, contour_lines: Option<usize>) -> CliResult {
    let (cost, length, length_2d) = (route.cost(), route.length(), route.length_2d());
    let elevation = |p: Option<&geotracks::glam::DVec3>| p.map_or(f64::NAN, |p| p.z);
    let (first, last) = (route.points.first(), route.points.last());
    let [x0, y0] = args.from;
    let [x1, y1] = args.to;
    let mut summary = vec![
        format!("from: {x0},{y0} (elevation {})", Value(elevation(first))),
        format!("to: {x1},{y1} (elevation {})", Value(elevation(last))),
        format!("cost model: {}", args.cost),
        format!("points: {}", route.points.len()),
        format!("length: {} (3D), {} (map)", Value(length), Value(length_2d)),
        format!(
            "traced cost: {} (the Steiner graph's, before straightening)",
            Value(route.traced_cost)
        ),
    ];
    if let (Some(path), Some(lines)) = (&args.contours, contour_lines) {
        summary.push(format!("contours: {lines} lines, in {}", path.display()));
    }
    if args.output.as_os_str() == "-" {
        // Standard output holds the route: the summary and the cost go to stderr.
        for line in summary {
            ui::info!("{line}");
        }
        ui::info!("cost: {}", Value(cost));
    } else {
        for line in summary {
            ui::say!("{line}");
        }
        // The result, alone on the last line (also with --quiet).
        crate::print_out(format_args!("{}", Value(cost)))?;
    }
    Ok(())
}

/// Where a run's time went, for the report.
struct Timings {
    read_seconds: f64,
    /// The whole grid's cost field, for a map or contours (if `whole_field`).
    field_seconds: f64,
    whole_field: bool,
}

/// The run's report: the grid, the window, the engine's numbers and the files written;
/// with `-v`, where the time went.
fn report_run(
    args: &TerrainArgs,
    grid: &terrain::ElevationGrid,
    route: &Route,
    window: &terrain::RouteWindow,
    picture: Option<&map::MapImage>,
    timings: &Timings,
) {
    let s = &route.stats;
    let g = grid.geometry();
    ui::info!(
        "{}: {} × {} samples, {} faces{}, {}; wrote {}{}",
        args.dem.display(),
        g.ncols,
        g.nrows,
        s.faces,
        format!(
            " (a window of {:.0} % of the cells, {} run{})",
            100.0 * window.cells as f64 / window.grid_cells.max(1) as f64,
            window.runs,
            if window.runs == 1 { "" } else { "s" }
        ),
        crate::run_summary(s),
        crate::shown(&args.output),
        match (&args.png, picture) {
            (Some(p), Some(m)) => format!(
                " and {} ({} × {} px{})",
                p.display(),
                m.width,
                m.height,
                m.contour_interval
                    .map(|i| format!(", contours every {}", Value(i)))
                    .unwrap_or_default()
            ),
            _ => String::new(),
        }
    );
    crate::report_stats(s);
    if ui::verbose() {
        // Where the rest of the time went: the route's window, its path, and the
        // whole grid's field for a map or contours.
        let field = if timings.whole_field {
            format!(
                "; whole grid's cost field (map, contours) {:.4} s",
                timings.field_seconds
            )
        } else {
            String::new()
        };
        eprintln!(
            "  grid read {:.4} s; window cut {:.4} s, metric {:.4} s, \
             solver {:.4} s; path traced and straightened {:.4} s{field}",
            timings.read_seconds,
            window.window_seconds,
            window.metric_seconds,
            window.solver_seconds,
            route.path_seconds
        );
    }
}

/// A routing error in the command line's words: which end lies off the grid or on
/// NODATA, or that no route joins them.
fn routing_error<T>(routed: Result<T, TerrainError>, args: &TerrainArgs) -> Result<T, String> {
    let end = |x: f64, y: f64| {
        if [x, y] == args.from {
            "--from"
        } else {
            "--to"
        }
    };
    routed.map_err(|e| match e {
        TerrainError::Engine(Error::Unreachable { .. }) => {
            "no route: --to cannot be reached from --from \
             (impassable faces or NODATA separate them)"
                .to_string()
        }
        ref t @ (TerrainError::Outside { x, y, .. } | TerrainError::NoData { x, y }) => {
            format!("{} {},{}: {t}", end(x, y), Value(x), Value(y))
        }
        e => e.to_string(),
    })
}

/// How map coordinates are written: rounded to a fixed number of decimals (so that a
/// sample centre at 505000 prints as `505000`, not `504999.99999999994`), and the
/// grid's CRS, when its file names one, as GeoJSON's `crs` member.
struct MapCoordinates {
    epsg: Option<u32>,
    decimals: usize,
}

impl MapCoordinates {
    fn of(grid: &terrain::ElevationGrid) -> Self {
        // A ten-billionth of the grid's spacing (9 decimals for 10 m cells), far below
        // any elevation model's precision, but no more than 15 significant digits at
        // the largest coordinate, which every f64 holds exactly: the noise of a sum
        // like `xll + 0.5 · cellsize` lies in the 16th and 17th digits.
        let g = grid.geometry();
        let [sx, sy] = g.spacing;
        let (zmin, zmax) = grid.elevation_range().unwrap_or((0.0, 0.0));
        let largest = [
            g.lower_left[0].abs() + g.ncols as f64 * sx,
            g.lower_left[1].abs() + g.nrows as f64 * sy,
            zmin.abs(),
            zmax.abs(),
            1.0,
        ]
        .into_iter()
        .fold(0.0, f64::max);
        let fine = 10.0 - sx.min(sy).log10().floor();
        let exact = 14.0 - largest.log10().floor();
        MapCoordinates {
            epsg: grid.epsg(),
            decimals: fine.min(exact).clamp(0.0, 15.0) as usize,
        }
    }

    /// `x` rounded to the decimals: the f64 nearest that decimal, which serde_json
    /// and `{}` then print as written.
    fn tidy(&self, x: f64) -> f64 {
        format!("{x:.*}", self.decimals).parse().unwrap_or(x)
    }

    fn point(&self, p: geotracks::glam::DVec3) -> [f64; 3] {
        [self.tidy(p.x), self.tidy(p.y), self.tidy(p.z)]
    }

    /// The GeoJSON `crs` member that GDAL's GeoJSON driver (and so QGIS) reads and
    /// writes for a layer that is not WGS 84 (RFC 7946 dropped it, but for a projected
    /// grid it is what those tools understand; a `.prj` beside a GeoJSON file is
    /// ignored by them), when the grid's EPSG code is known.
    fn crs(&self) -> Option<serde_json::Value> {
        self.epsg.map(|code| {
            serde_json::json!({
                "type": "name",
                "properties": { "name": format!("urn:ogc:def:crs:EPSG::{code}") }
            })
        })
    }
}

fn write_geojson(
    outputs: &mut Outputs,
    args: &TerrainArgs,
    route: &Route,
    map: &MapCoordinates,
) -> CliResult {
    let mut coordinates: Vec<[f64; 3]> = route.points.iter().map(|&p| map.point(p)).collect();
    // A LineString needs two positions: a route of one point (start = end) repeats it.
    if coordinates.len() == 1 {
        coordinates.push(coordinates[0]);
    }
    let mut json = serde_json::json!({
        "type": "FeatureCollection",
        "features": [{
            "type": "Feature",
            "geometry": { "type": "LineString", "coordinates": coordinates },
            "properties": {
                "cost": route.cost(),
                "length": route.length(),
                "length_2d": route.length_2d(),
                "traced_cost": route.traced_cost,
                "cost_model": args.cost.to_string(),
                "cost_unit": args.cost.unit(),
                "directed": args.cost.is_directed(),
                "k": args.k,
                "from": args.from,
                "to": args.to,
                "dem": args.dem.display().to_string(),
            }
        }]
    });
    if let Some(crs) = map.crs() {
        json["crs"] = crs;
    }
    outputs.write(&args.output, |w| {
        serde_json::to_writer_pretty(&mut *w, &json).map_err(std::io::Error::other)?;
        writeln!(w)
    })?;
    Ok(())
}

fn write_csv(outputs: &mut Outputs, file: &Path, route: &Route, map: &MapCoordinates) -> CliResult {
    outputs.write(file, |w| {
        writeln!(w, "x,y,z,cost,length")?;
        let mut length = 0.0;
        for (i, p) in route.points.iter().enumerate() {
            if i > 0 {
                length += route.points[i - 1].distance(*p);
            }
            writeln!(
                w,
                "{},{},{},{},{}",
                map.tidy(p.x),
                map.tidy(p.y),
                map.tidy(p.z),
                Value(route.cumulative_cost[i]),
                Value(length)
            )?;
        }
        Ok(())
    })?;
    Ok(())
}
