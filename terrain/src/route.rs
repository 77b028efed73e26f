//! [`route`]: the cheapest route between two points of a terrain, start first, with its
//! cumulative cost and lengths.

use super::{ElevationGrid, GridSurface, TerrainCost, TerrainError};
use geotracks::field::{Field, Stats};
use geotracks::mesh::Topology;
use geotracks::metrics::Metric;
use geotracks::options::{Method, Options, Sources, Stop};
use geotracks::propagate::Solver;
use geotracks::surface::SurfacePoint;
use geotracks::Error;
use glam::DVec3;
use std::time::Instant;

/// A route across a terrain, from its start to its end (the reverse of a
/// [`GeodesicPath`](geotracks::GeodesicPath), which runs from its query point back to the
/// source).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Route {
    /// World positions (map x, y and elevation z), start first.
    pub points: Vec<DVec3>,
    /// The same points on the surface.
    pub surface_points: Vec<SurfacePoint>,
    /// The metric cost from the start to each point (0 at the start).
    pub cumulative_cost: Vec<f64>,
    /// The Steiner graph's cost to the end, before straightening.
    pub traced_cost: f64,
    /// The cost from the start at every vertex, when asked for (the whole field, for
    /// maps and contours: a run of its own, which does not change the route); `None`
    /// otherwise.
    pub vertex_costs: Option<Vec<f64>>,
    /// The counters and timings of the propagation that found the route (the path
    /// query's, not the whole field's).
    pub stats: Stats,
    /// Seconds spent tracing and straightening the route, after the propagation.
    pub path_seconds: f64,
}

impl Route {
    /// The route's metric cost.
    pub fn cost(&self) -> f64 {
        self.cumulative_cost.last().copied().unwrap_or(0.0)
    }

    /// Its 3D length.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| w[0].distance(w[1])).sum()
    }

    /// Its length on the map (x, y only).
    pub fn length_2d(&self) -> f64 {
        self.points
            .windows(2)
            .map(|w| w[0].truncate().distance(w[1].truncate()))
            .sum()
    }
}

/// The cheapest route from `from` to `to` under the solver's metric, as a path query
/// finds it ([`Solver::shortest_path`]: from both ends at once where it can, else
/// a run from `from` that stops once `to` is final), straightened and reversed so that
/// it starts at `from`; with `whole_field`, also the cost from `from` at every vertex
/// (a second run, over the whole surface, for maps and contours).
///
/// The route is the path query's whatever `whole_field` says: what else is asked never
/// changes it. (Many Steiner-graph paths can cost the same to the last bit, on a
/// regular grid with rounded elevations above all; which one a search keeps depends on
/// the order it settles nodes in, and each straightens to its own local optimum, so a
/// route traced from the whole field could differ from the query's by a few percent
/// after straightening, at the same graph cost.)
///
/// ```
/// use geotracks_terrain::{route, ElevationGrid, GridGeometry, TerrainCost};
/// use geotracks::{Options, Solver};
/// let geometry = GridGeometry { ncols: 11, nrows: 11, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let terrain = ElevationGrid::from_fn(geometry, |_, _| Some(0.0))?.to_mesh()?;
/// let metric = TerrainCost::None.metric(&terrain.mesh)?;
/// let solver = Solver::new(&terrain.mesh, &metric, &Options::DEFAULT.with_k(2.0))?;
/// let (from, to) = (terrain.locate(1.0, 1.0)?, terrain.locate(9.0, 7.0)?);
/// let r = route(&solver, from, to, false)?;
/// assert!((r.cost() - 10.0).abs() < 1e-6); // flat: the straight line, 8 by 6
/// assert_eq!(r.points[0].x, 1.0);
/// let with_costs = route(&solver, from, to, true)?;
/// assert_eq!(with_costs.points, r.points);
/// assert!(with_costs.vertex_costs.is_some());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The engine's error alone (nothing of the grid is read here; `?` turns it into a
/// [`TerrainError::Engine`]): [`Error::Unreachable`] when no route joins the two points
/// (walls, NODATA, separate islands); as [`Solver::field`] otherwise.
pub fn route<M: Metric, T: Topology>(
    solver: &Solver<M, T>,
    from: SurfacePoint,
    to: SurfacePoint,
    whole_field: bool,
) -> Result<Route, Error> {
    if !whole_field {
        return route_within(solver, from, to, f64::INFINITY);
    }
    Ok(route_and_field(solver, from, to)?.0)
}

/// As [`route`] stopping at the end, going no farther than `max_cost` (`inf`: no
/// limit): [`Error::Unreachable`] when the route would cost more.
fn route_within<M: Metric, T: Topology>(
    solver: &Solver<M, T>,
    from: SurfacePoint,
    to: SurfacePoint,
    max_cost: f64,
) -> Result<Route, Error> {
    let started = Instant::now();
    let (path, stats) = solver.shortest_path(
        Sources::from(from).until(Stop::NONE.with_max_distance(max_cost)),
        to,
    )?;
    let mut route = path_route(solver, path, stats, None, started);
    // (The path was traced and straightened after the propagation, in the call.)
    route.path_seconds = (route.path_seconds - route.stats.propagate_seconds).max(0.0);
    Ok(route)
}

/// As [`route`] with the whole field, also handing back the field (the cost from
/// `from` everywhere): for queries on it, such as cost contours with
/// [`Field::isolines`]. The route is the path query's, as [`route`] finds it without the
/// field (its [`stats`](Route::stats) are that query's; the field's are
/// [`Field::stats`]).
///
/// # Errors
/// As [`route`].
pub fn route_and_field<M: Metric, T: Topology>(
    solver: &Solver<M, T>,
    from: SurfacePoint,
    to: SurfacePoint,
) -> Result<(Route, Field<M, geotracks::FieldData, T>), Error> {
    let mut route = route_within(solver, from, to, f64::INFINITY)?;
    let field = solver.field(from)?;
    route.vertex_costs = Some(field.vertex_distances().to_vec());
    Ok((route, field))
}

/// `path` (from the end back to the start) as a route from the start, with the run's
/// `stats` and the vertex costs; the path's seconds counted from `start`.
fn path_route<M: Metric, T: Topology>(
    solver: &Solver<M, T>,
    path: geotracks::GeodesicPath,
    stats: Stats,
    vertex_costs: Option<Vec<f64>>,
    start: Instant,
) -> Route {
    let (mesh, metric) = (solver.mesh(), solver.metric());
    let mut points = path.positions(mesh);
    points.reverse();
    let mut surface_points = path.points.clone();
    surface_points.reverse();
    let mut costs = path.segment_costs(mesh, metric);
    costs.reverse();
    let mut cumulative_cost = Vec::with_capacity(costs.len() + 1);
    cumulative_cost.push(0.0);
    for c in costs {
        cumulative_cost.push(cumulative_cost[cumulative_cost.len() - 1] + c);
    }
    Route {
        points,
        surface_points,
        cumulative_cost,
        traced_cost: path.traced_length,
        vertex_costs,
        stats,
        path_seconds: start.elapsed().as_secs_f64(),
    }
}

/// A route found on a window of an elevation grid ([`route_on_grid`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct GridRoute {
    /// The route. Its [`surface_points`](Route::surface_points) lie on
    /// [`surface`](Self::surface), the window's (its points, costs and lengths are the
    /// grid's).
    pub route: Route,
    /// The window of the grid the route was found on, as a surface (shared with the
    /// solver that found it).
    pub surface: std::sync::Arc<GridSurface>,
    /// How the window was cut.
    pub window: RouteWindow,
}

/// The part of the grid a route was found on ([`route_on_grid`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RouteWindow {
    /// Cells the last run's window held.
    pub cells: usize,
    /// Cells of the whole grid.
    pub grid_cells: usize,
    /// Runs: 1 when the first window held the route, more when it had to be widened.
    pub runs: u32,
    /// The cost the last window was cut for: every cell left out lies where a route
    /// through it costs more.
    pub bound: f64,
    /// The least cost per unit of 3D length it was cut with
    /// ([`TerrainCost::least_cost_per_length`]).
    pub per_length: f64,
    /// Seconds spent cutting the windows and building the metrics and solvers (all
    /// runs); the propagation's are in the route's [`stats`](Route::stats) (last run).
    pub setup_seconds: f64,
    /// Of `setup_seconds`, those spent cutting the windows (and numbering their
    /// cells' triangles: no mesh is built).
    pub window_seconds: f64,
    /// Of `setup_seconds`, those spent building the metrics.
    pub metric_seconds: f64,
    /// Of `setup_seconds`, those spent building the solvers ([`Solver::new`]: Steiner
    /// points, edge steps, the engine's tables).
    pub solver_seconds: f64,
}

/// How much dearer than the straight line between its ends (what it costs on the
/// terrain) the first window lets a route be: the Steiner graph's values lie up to a
/// few percent above the continuous cost at k = 2 (the guide's Accuracy page). A
/// route that does not fit costs another run, on a window three times as slack above
/// the least cost, or the whole grid.
const FIRST_WINDOW_SLACK: f64 = 0.05;

/// The same for the wavefront engine, whose values lie within 0.1 % of the continuous
/// cost on the guide's grids (Terrain page): a route never costs much more than the straight line's
/// cost but where the line climbs what the route goes round.
const FIRST_WINDOW_SLACK_WAVE: f64 = 0.01;

/// Steps of a quarter cell per piece of the straight line that [`straight_line_cost`]
/// meshes at once (64 cells).
const LINE_PIECE_STEPS: usize = 256;

/// A window of more than this fraction of the grid's cells is not cut: the whole grid
/// runs instead (meshing it costs little more, and it needs no second run).
const WHOLE_GRID_ABOVE: f64 = 0.75;

/// The cheapest route from map point `from` to map point `to` of `grid` under `cost`,
/// meshing only the window of cells a route as cheap could cross, rather than the whole
/// grid: the route is the one [`route`] finds on the whole grid's mesh, in a fraction
/// of the time and memory.
///
/// A route through a point `x` costs at least `m · (|s − x| + |x − t|)`, with `s`, `t`
/// its ends and `m` the cost's least cost per unit of 3D length
/// ([`TerrainCost::least_cost_per_length`]). The window holds the cells whose 3D
/// bounding box lies within that of a bound `C`, and the run on it goes no farther
/// than `C` (goal-directed, and from both ends, it settles a corridor): a route found
/// costs at most `C`,
/// and no route that leaves the window is cheaper. The first window has `C` 5 % (1 %
/// for the wavefront engine) above what the straight line between the ends costs on
/// the terrain (a guess at the route's cost; four times that above `m · |s − t|` where
/// the line is blocked); when no route
/// fits, the next is three times as far above `m · |s − t|`, and a window that would
/// hold more than three quarters of the grid is the whole grid (which also says whether
/// there is a route at all). Steiner points are
/// spaced as on the whole grid ([`ElevationGrid::mean_edge_length`],
/// [`Options::mean_edge_length`]), so for the Steiner-graph engines (tracks, graph) the
/// window's graph is the grid's, cut down to the window, and the route costs the same
/// (tests: `tests/terrain_window.rs`). The wavefront engine's values depend on which
/// waves meet first, so its route may differ in the last digits.
///
/// `options` as for a [`Solver`]; its `mean_edge_length` is replaced by the grid's.
/// Maps and cost contours need the whole field: a run from the start over the whole
/// grid's mesh ([`Solver::field`]) besides this route, which stays the one to
/// draw (a route found on the whole grid's mesh costs the same in the Steiner graph,
/// but among paths of equal cost it may keep another, which straightens differently).
///
/// ```
/// use geotracks_terrain::{route_on_grid, ElevationGrid, GridGeometry, TerrainCost};
/// use geotracks::Options;
/// let geometry = GridGeometry { ncols: 101, nrows: 101, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let grid = ElevationGrid::from_fn(geometry, |_, _| Some(0.0))?;
/// let options = Options::DEFAULT.with_k(2.0);
/// let r = route_on_grid(&grid, &TerrainCost::None, &options, [10.0, 10.0], [40.0, 50.0])?;
/// assert!((r.route.cost() - 50.0).abs() < 1e-6); // flat: the straight line
/// assert!(r.window.cells < r.window.grid_cells / 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`TerrainError::Outside`] or [`TerrainError::NoData`] when a point lies outside the
/// grid or on NODATA; the cost's errors when it cannot be built;
/// [`TerrainError::Engine`] wrapping [`Error::Unreachable`] when no route joins the
/// two points, or [`Solver::new`]'s and [`route`]'s errors otherwise.
pub fn route_on_grid(
    grid: &ElevationGrid,
    cost: &TerrainCost,
    options: &Options,
    from: [f64; 2],
    to: [f64; 2],
) -> Result<GridRoute, TerrainError> {
    let g = *grid.geometry();
    let grid_cells = g.ncols.saturating_sub(1) * g.nrows.saturating_sub(1);
    let options = match grid.mean_edge_length() {
        Some(mean) => options.with_mean_edge_length(mean),
        None => *options,
    };
    let per_length = cost.least_cost_per_length(grid);
    // The ends on the surface (the grid's errors for points off it, or on NODATA).
    let (s, t) = (
        surface_position(grid, from[0], from[1])?,
        surface_position(grid, to[0], to[1])?,
    );
    let straight = per_length * s.distance(t);
    let mut bound = first_bound(grid, cost, &options, from, to, straight);
    // Whether `bound` is the cost of a route found (on a narrower window).
    let mut found = false;
    let mut runs = 0;
    let [mut window_seconds, mut metric_seconds, mut solver_seconds] = [0.0; 3];
    loop {
        runs += 1;
        let setup = Instant::now();
        let (surface, cells, whole) = window_surface(grid, s, t, bound, per_length)?;
        let (a, b) = (
            surface.locate(from[0], from[1])?,
            surface.locate(to[0], to[1])?,
        );
        window_seconds += setup.elapsed().as_secs_f64();
        let metric_start = Instant::now();
        let metric = cost.metric_on_surface(grid, &surface)?;
        metric_seconds += metric_start.elapsed().as_secs_f64();
        let solver_start = Instant::now();
        let solver = Solver::with_topology(surface, metric, &options)?;
        solver_seconds += solver_start.elapsed().as_secs_f64();
        // A run within the bound: a goal-directed one that finds no route as cheap
        // stops as soon as it knows, having settled a corridor.
        let routed = route_within(&solver, a, b, if whole { f64::INFINITY } else { bound });
        match routed {
            // No route that leaves the window is cheaper: every cell left out costs
            // more than the bound. When the bound is a route's cost, the best route
            // costs no more, so lies inside.
            Ok(route) if whole || found || route.traced_cost <= bound => {
                return Ok(GridRoute {
                    route,
                    surface: std::sync::Arc::clone(solver.shared_mesh()),
                    window: RouteWindow {
                        cells,
                        grid_cells,
                        runs,
                        bound,
                        per_length,
                        setup_seconds: window_seconds + metric_seconds + solver_seconds,
                        window_seconds,
                        metric_seconds,
                        solver_seconds,
                    },
                })
            }
            // (The wavefront engine takes values up to an edge beyond the bound.)
            Ok(route) => {
                bound = route.traced_cost;
                found = true;
            }
            // None within the bound: a wider window (the whole grid, in the end, which
            // says whether there is a route at all).
            Err(Error::Unreachable { .. }) if !whole => {
                let wider = straight + 3.0 * (bound - straight);
                // (A bound that would not grow, at a zero straight cost: the whole.)
                bound = if wider > bound { wider } else { f64::INFINITY };
            }
            Err(e) => return Err(e.into()),
        }
    }
}

/// The bound of the first window: what the straight line from `from` to `to` costs
/// (at least `straight`, the least cost per length times its length), with the engine's
/// slack; four times that above `straight` where the line is blocked.
fn first_bound(
    grid: &ElevationGrid,
    cost: &TerrainCost,
    options: &Options,
    from: [f64; 2],
    to: [f64; 2],
    straight: f64,
) -> f64 {
    // The first window: for what the straight line costs, with the engine's slack;
    // four times that above the least cost where the line is blocked. (The wavefront
    // engine runs for the face-flat costs.)
    let wave = options.method == Method::Wave
        && matches!(cost, TerrainCost::None | TerrainCost::Incline { .. });
    let slack = if wave {
        FIRST_WINDOW_SLACK_WAVE
    } else {
        FIRST_WINDOW_SLACK
    };
    match straight_line_cost(grid, cost, from, to) {
        Some(line) => line.max(straight) * (1.0 + slack),
        None => straight * (1.0 + 4.0 * slack),
    }
}

/// The window a route from `s` to `t` that costs at most `bound` may cross
/// (`per_length`: the least cost per length), with its number of cells and whether it
/// is the whole grid.
fn window_surface(
    grid: &ElevationGrid,
    s: DVec3,
    t: DVec3,
    bound: f64,
    per_length: f64,
) -> Result<(GridSurface, usize, bool), TerrainError> {
    let g = *grid.geometry();
    let grid_cells = g.ncols.saturating_sub(1) * g.nrows.saturating_sub(1);
    // The cells a route within the bound may cross; all of them where the window
    // would hold most of the grid anyway (or the bound cuts nothing): that run
    // costs little more than the window's, and needs no other.
    let cuts = bound.is_finite() && per_length > 0.0;
    let (cols, rows) = if cuts {
        ellipse_cells(&g, s, t, bound / per_length)
    } else {
        (0..g.ncols - 1, 0..g.nrows - 1)
    };
    let width = cols.len();
    let mut window: Vec<bool> = rows
        .clone()
        .flat_map(|row| cols.clone().map(move |col| (col, row)))
        .map(|(col, row)| per_length * ends_distance(grid, col, row, s, t) <= bound)
        .collect();
    let mut cells = window.iter().filter(|&&k| k).count();
    let whole = !cuts || cells as f64 > WHOLE_GRID_ABOVE * grid_cells as f64;
    let surface = if whole {
        cells = grid_cells;
        window.clear();
        GridSurface::new(grid)?
    } else {
        let (c0, r0) = (cols.start, rows.start);
        GridSurface::within(grid, cols, rows, |col, row| {
            window[(row - r0) * width + (col - c0)]
        })?
    };
    Ok((surface, cells, whole))
}

/// What a polyline in the map (`points`, map x and y: a route from another tool, say)
/// costs on the terrain under `cost`, as the first window's guess costs a straight
/// line: each piece in steps of a quarter cell, each step in the face under its
/// middle. An estimate for comparing routes under one cost model (exact where each
/// step stays in one face, as on a flat grid); `None` where the polyline leaves the
/// grid or crosses NODATA or walls.
///
/// ```
/// use geotracks_terrain::{map_path_cost, ElevationGrid, GridGeometry, TerrainCost};
/// let geometry = GridGeometry { ncols: 11, nrows: 11, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let grid = ElevationGrid::from_fn(geometry, |_, _| Some(0.0))?;
/// let cost = map_path_cost(&grid, &TerrainCost::None, &[[1.0, 1.0], [4.0, 5.0], [4.0, 9.0]]);
/// assert!((cost.unwrap() - 9.0).abs() < 1e-9); // 5 + 4 on a flat grid
/// assert_eq!(map_path_cost(&grid, &TerrainCost::None, &[[1.0, 1.0], [20.0, 1.0]]), None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn map_path_cost(grid: &ElevationGrid, cost: &TerrainCost, points: &[[f64; 2]]) -> Option<f64> {
    let g = grid.geometry();
    if points.iter().any(|p| g.inside(p[0], p[1]).is_err()) {
        return None;
    }
    points
        .windows(2)
        .map(|w| straight_line_cost(grid, cost, w[0], w[1]))
        .sum()
}

/// What the straight line (in the map) from `from` to `to` costs on the terrain, in
/// steps of a quarter cell: a guess at what a route costs, which sizes the first
/// window (the window is cut by a bound, whatever the guess). `None` where the line
/// crosses NODATA or walls.
fn straight_line_cost(
    grid: &ElevationGrid,
    cost: &TerrainCost,
    from: [f64; 2],
    to: [f64; 2],
) -> Option<f64> {
    let g = grid.geometry();
    let (a, b) = (g.to_grid(from[0], from[1]), g.to_grid(to[0], to[1]));
    let (dc, dr) = (b.0 - a.0, b.1 - a.1);
    let cells = dc.hypot(dr);
    // The cells within two of the line (in cells).
    let near = |col: usize, row: usize| {
        let (pc, pr) = (col as f64 + 0.5 - a.0, row as f64 + 0.5 - a.1);
        let t = if cells > 0.0 {
            ((pc * dc + pr * dr) / (cells * cells)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (pc - t * dc).hypot(pr - t * dr) <= 2.0
    };
    let steps = (4.0 * cells).ceil().max(1.0) as usize;
    let at = |i: usize| {
        let t = i as f64 / steps as f64;
        [
            from[0] + t * (to[0] - from[0]),
            from[1] + t * (to[1] - from[1]),
        ]
    };
    let mut total = 0.0;
    // In pieces, each meshed on its own: the box around a long diagonal line holds
    // most of the grid.
    for first in (0..steps).step_by(LINE_PIECE_STEPS) {
        let last = (first + LINE_PIECE_STEPS).min(steps);
        let (p, q) = (
            g.to_grid(at(first)[0], at(first)[1]),
            g.to_grid(at(last)[0], at(last)[1]),
        );
        let cols = cell_span(p.0.min(q.0), p.0.max(q.0), 3.0, g.ncols - 1);
        let rows = cell_span(p.1.min(q.1), p.1.max(q.1), 3.0, g.nrows - 1);
        let surface = GridSurface::within(grid, cols, rows, near).ok()?;
        let metric = cost.metric_on_surface(grid, &surface).ok()?;
        for i in first..last {
            let (p, q) = (at(i), at(i + 1));
            // Each step in the face under its middle (a step that crosses an edge is
            // costed in one of its faces: a guess).
            let (face, _) = surface
                .covering(0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]))
                .ok()?;
            let frame = surface.frame(face);
            let point = |[x, y]: [f64; 2]| frame.point(surface.bary_2d(face, x, y));
            total += metric.cost(face, &point(p), &point(q));
        }
    }
    total.is_finite().then_some(total)
}

/// The 3D point of the grid's surface under map point `(x, y)`, as
/// [`TerrainMesh::locate`] finds it, from the cells around it alone: the grid's errors
/// for a point outside it or on NODATA.
fn surface_position(grid: &ElevationGrid, x: f64, y: f64) -> Result<DVec3, TerrainError> {
    let g = grid.geometry();
    let (fc, fr) = g.inside(x, y)?;
    // The cells around it: a point on a cell's border may lie in a neighbour's
    // triangle only.
    let (cols, rows) = (
        cell_span(fc, fc, 2.0, g.ncols - 1),
        cell_span(fr, fr, 2.0, g.nrows - 1),
    );
    let surface = GridSurface::within(grid, cols, rows, |_, _| true)
        .map_err(|_| TerrainError::NoData { x, y })?;
    Ok(surface.locate(x, y)?.position(&surface))
}

/// The columns and rows of the cells that meet the ellipse of the map points `x` with
/// `|x − s| + |x − t| ≤ length` (horizontal distances, which are at most the 3D ones:
/// every cell whose box lies within `length` of both ends in 3D meets it), a cell more
/// on each side against rounding; clipped to the grid.
fn ellipse_cells(
    g: &super::GridGeometry,
    s: DVec3,
    t: DVec3,
    length: f64,
) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
    let (s, t) = (s.truncate(), t.truncate());
    let (a, c) = (0.5 * length, 0.5 * s.distance(t));
    let b = (a * a - c * c).max(0.0).sqrt();
    let u = (t - s).try_normalize().unwrap_or(glam::DVec2::X);
    let centre = 0.5 * (s + t);
    let half = glam::DVec2::new(
        (a * a * u.x * u.x + b * b * u.y * u.y).sqrt(),
        (a * a * u.y * u.y + b * b * u.x * u.x).sqrt(),
    );
    // Rows count from the north: the box's top is its least row.
    let (c0, r0) = g.to_grid(centre.x - half.x, centre.y + half.y);
    let (c1, r1) = g.to_grid(centre.x + half.x, centre.y - half.y);
    (
        cell_span(c0, c1, 1.0, g.ncols - 1),
        cell_span(r0, r1, 1.0, g.nrows - 1),
    )
}

/// The cells (columns or rows, of `cells`) from fractional position `lo` to `hi`,
/// `pad` more on each side, clipped to the grid.
fn cell_span(lo: f64, hi: f64, pad: f64, cells: usize) -> std::ops::Range<usize> {
    let clip = |x: f64| x.clamp(0.0, cells as f64) as usize;
    let lo = clip(lo.floor() - pad);
    lo..clip(hi.ceil() + pad).max(lo)
}

/// The 3D distance from `s` to the bounding box of cell `(col, row)` (its four
/// samples' map square, and their elevations' range) plus that from `t`: a lower bound
/// on the length of any path from `s` to `t` through the cell's triangles, which lie
/// in the box. Infinite for a cell with no valid sample.
fn ends_distance(grid: &ElevationGrid, col: usize, row: usize, s: DVec3, t: DVec3) -> f64 {
    let g = grid.geometry();
    let ([x0, y0], [x1, y1]) = (g.position(col, row + 1), g.position(col + 1, row));
    let (mut z0, mut z1) = (f64::INFINITY, f64::NEG_INFINITY);
    for (c, r) in [
        (col, row),
        (col + 1, row),
        (col, row + 1),
        (col + 1, row + 1),
    ] {
        if let Some(z) = grid.elevation(c, r) {
            z0 = z0.min(z);
            z1 = z1.max(z);
        }
    }
    if z0 > z1 {
        return f64::INFINITY;
    }
    let (lo, hi) = (
        DVec3::new(x0.min(x1), y0.min(y1), z0),
        DVec3::new(x0.max(x1), y0.max(y1), z1),
    );
    let to_box = |p: DVec3| p.distance(p.clamp(lo, hi));
    to_box(s) + to_box(t)
}
