//! The grassfire: a distance field burnt into a surface from its whole boundary.

use super::boundary::BoundaryArcs;
use crate::mesh::{TriMesh, NONE};
use crate::options::{Method, Options, Stop};
use crate::propagate::Solver;
use crate::surface::Source;
use crate::trace::Query;
use crate::{Density, Error, GeodesicField, Metric, MetricError};

/// A distance field from every boundary edge (edges with one face) of a surface, all at
/// start value 0, with each node's nearest boundary origin.
///
/// Burning a medial axis from its boundary is the classical *grassfire*: where fronts
/// from boundary points far apart along the boundary meet, the surface has a ridge (see
/// [`crate::skeleton::Skeleton`]).
///
/// It keeps the solver it burnt with, so the skeleton's later questions (paths, a second
/// field for bridges) use the same mesh, metric and Steiner points.
///
/// ```
/// use geotracks::{mesh::TriMesh, skeleton::Grassfire, Euclidean, Options};
///
/// // A 2 × 1 rectangle in four triangles around its centre (vertex 4).
/// let mesh = TriMesh::new(
///     vec![[0., 0., 0.], [2., 0., 0.], [2., 1., 0.], [0., 1., 0.], [1., 0.5, 0.]],
///     vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
/// )?;
/// let fire = Grassfire::burn(&mesh, &Euclidean, &Options::DEFAULT.with_k(3.0))?;
/// // Half the width: a Steiner point sits right below the centre.
/// assert!((fire.field().distance(4) - 0.5).abs() < 1e-12);
/// # Ok::<(), geotracks::Error>(())
/// ```
pub struct Grassfire<'m, M> {
    solver: Solver<'m, M>,
    field: GeodesicField,
    /// The boundary; source `i` is its node number `i`.
    boundary: BoundaryArcs,
    /// Per node, the source it burnt from (`NONE` if unreached).
    origins: Vec<u32>,
}

impl<'m, M: Metric> Grassfire<'m, M> {
    /// Burns `mesh` from its boundary under `metric` (a metric or a reference to one).
    /// Every node on a boundary edge is a source at 0; components without a boundary
    /// stay unreached (`inf`).
    ///
    /// The ridges are found where the Steiner graph's fronts meet, and every node's
    /// origin follows the graph's parents, so the fire burns with the track-pruned
    /// Steiner graph: `Method::Wave` in `options` runs [`Method::Tracks`] here (the
    /// wavefront engine's nodes keep one wave each, and their parents do not follow
    /// the fronts the ridge test reads).
    ///
    /// # Errors
    /// [`Error::NoBoundary`] if no edge has exactly one face; as [`Solver::new`] and
    /// [`Solver::solve_from`] otherwise.
    pub fn burn(mesh: &'m TriMesh, metric: M, options: &Options) -> Result<Self, Error> {
        let options = match options.method {
            Method::Wave => options.with_method(Method::Tracks),
            _ => *options,
        };
        let solver = Solver::new(mesh, metric, &options)?;
        let layout = solver.layout();
        let boundary = BoundaryArcs::new(mesh, layout, solver.metric());
        if boundary.nodes().is_empty() {
            return Err(Error::NoBoundary);
        }
        let sources: Vec<Source> = boundary
            .nodes()
            .iter()
            .map(|&node| Source::new(layout.surface_point(node)))
            .collect();
        let field = solver.solve_from(&sources, &Stop::NONE)?;
        let origins = solver.query(&field)?.node_labels();
        Ok(Grassfire {
            solver,
            field,
            boundary,
            origins,
        })
    }

    /// The distance field (every boundary node a source at 0).
    pub fn field(&self) -> &GeodesicField {
        &self.field
    }

    /// The distance field, given up.
    pub fn into_field(self) -> GeodesicField {
        self.field
    }

    /// The solver the fire burnt with (its mesh, metric and Steiner layout).
    pub fn solver(&self) -> &Solver<'m, M> {
        &self.solver
    }

    /// Queries on the field: distances at any point, paths back to the boundary.
    pub fn query(&self) -> Query<'_, M> {
        self.solver
            .query(&self.field)
            .expect("the fire's own solver computed its field")
    }

    /// The boundary source `node` burnt from, as an index into the field's sources
    /// ([`GeodesicField::sources`]); `None` if unreached.
    pub fn origin(&self, node: u32) -> Option<u32> {
        let o = self.origins[node as usize];
        (o != NONE).then_some(o)
    }

    /// How far apart sources `a` and `b` are along the boundary (metric length of the
    /// shortest walk on boundary edges only); `inf` if no such walk joins them, as
    /// between two holes of a sheet.
    pub fn boundary_distance(&self, a: u32, b: u32) -> f64 {
        self.boundary.distance(a as usize, b as usize)
    }

    /// The larger metric length of the boundary segments on either side of source `a`.
    pub(crate) fn boundary_step(&self, a: u32) -> f64 {
        self.boundary.step(a as usize)
    }
}

/// A density for a radius-aware grassfire on a medial axis: `mean(r) / max(r, floor)`
/// per vertex, with `floor` 1 % of the mean radius, so the fire runs fast where medial
/// balls are large and slowly where the shape is thin.
///
/// # Errors
/// [`MetricError::CountMismatch`] unless there is one radius per vertex; every radius
/// must be finite and ≥ 0 ([`MetricError::InvalidDensity`] otherwise, or when all are 0).
pub fn radius_speed(mesh: &TriMesh, radii: &[f64]) -> Result<Density, MetricError> {
    if let Some((vertex, &r)) = radii
        .iter()
        .enumerate()
        .find(|(_, r)| !(r.is_finite() && **r >= 0.0))
    {
        return Err(MetricError::InvalidDensity { vertex, value: r });
    }
    let mean = radii.iter().sum::<f64>() / radii.len().max(1) as f64;
    let floor = 0.01 * mean;
    Density::new(mesh, radii.iter().map(|&r| mean / r.max(floor)).collect())
}
