//! [`route`]: the cheapest route between two points of a terrain, start first, with its
//! cumulative cost and lengths.

use crate::field::{GeodesicField, Stats};
use crate::options::Stop;
use crate::propagate::Solver;
use crate::surface::{Source, SurfacePoint};
use crate::Error;
use geotracks_metrics::Metric;
use glam::DVec3;
use std::time::Instant;

/// A route across a terrain, from its start to its end (the reverse of a
/// [`GeodesicPath`](crate::GeodesicPath), which runs from its query point back to the
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
    /// maps and contours); `None` when the run stopped at the end.
    pub vertex_costs: Option<Vec<f64>>,
    /// The propagation's counters and timings.
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

/// The cheapest route from `from` to `to` under the solver's metric: a run from `from`
/// that stops once `to` is final (or, with `whole_field`, covers the whole surface and
/// keeps every vertex's cost), then the straightened path, reversed so that it starts
/// at `from`.
///
/// ```
/// use geotracks::terrain::{route, ElevationGrid, GridGeometry, TerrainCost};
/// use geotracks::{Options, Solver};
/// let geometry = GridGeometry { ncols: 11, nrows: 11, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let terrain = ElevationGrid::from_fn(geometry, |_, _| Some(0.0))?.to_mesh()?;
/// let metric = TerrainCost::None.metric(&terrain.mesh)?;
/// let solver = Solver::new(&terrain.mesh, &metric, &Options::DEFAULT.with_k(2.0))?;
/// let (from, to) = (terrain.locate(1.0, 1.0)?, terrain.locate(9.0, 7.0)?);
/// let r = route(&solver, from, to, false)?;
/// assert!((r.cost() - 10.0).abs() < 1e-6); // flat: the straight line, 8 by 6
/// assert_eq!(r.points[0].x, 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`Error::Unreachable`] when no route joins the two points (walls, NODATA, separate
/// islands); as [`Solver::solve_from`] otherwise.
pub fn route<M: Metric>(
    solver: &Solver<'_, M>,
    from: SurfacePoint,
    to: SurfacePoint,
    whole_field: bool,
) -> Result<Route, Error> {
    let stop = if whole_field {
        Stop::NONE
    } else {
        Stop::NONE.with_targets(vec![to])
    };
    let field = solver.solve_from(&[Source::new(from)], &stop)?;
    route_in(solver, &field, to, whole_field)
}

/// As [`route`] over the whole surface, also handing back the field (the cost from
/// `from` everywhere): for queries on it, such as cost contours with
/// [`Query::isolines`](crate::Query::isolines).
///
/// # Errors
/// As [`route`].
pub fn route_and_field<M: Metric>(
    solver: &Solver<'_, M>,
    from: SurfacePoint,
    to: SurfacePoint,
) -> Result<(Route, GeodesicField), Error> {
    let field = solver.solve_from(&[Source::new(from)], &Stop::NONE)?;
    let route = route_in(solver, &field, to, true)?;
    Ok((route, field))
}

/// The route to `to` in `field` (a run from the start), with the vertex costs if
/// `keep_costs`.
fn route_in<M: Metric>(
    solver: &Solver<'_, M>,
    field: &GeodesicField,
    to: SurfacePoint,
    keep_costs: bool,
) -> Result<Route, Error> {
    let start = Instant::now();
    let path = solver.query(field)?.path(to)?;
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
    Ok(Route {
        points,
        surface_points,
        cumulative_cost,
        traced_cost: path.traced_length,
        vertex_costs: keep_costs.then(|| field.vertex_distances().to_vec()),
        stats: field.stats().clone(),
        path_seconds: start.elapsed().as_secs_f64(),
    })
}
