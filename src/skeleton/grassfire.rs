//! The grassfire: a distance field burnt into a surface from its whole boundary, and
//! the skeleton thinned in the order it burns.

use super::Skeleton;
use crate::mesh::TriMesh;
use crate::options::Options;
use crate::propagate::Solver;
use crate::surface::Source;
use crate::{Error, Field, Metric};
use std::sync::Arc;

/// A distance field from every boundary edge (edges with one face) of a surface, all at
/// start value 0.
///
/// Burning a medial axis from its boundary is the classical *grassfire*: where the
/// fronts meet, the surface has its ridges, which [`crate::skeleton::Skeleton`] keeps
/// as it thins the surface in the order it burns.
///
/// Its field keeps the solver it burnt with ([`Grassfire::field`]), so later questions
/// (paths back to the border, distances at any point) use the same mesh, metric and
/// Steiner points.
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
pub struct Grassfire<M> {
    field: Field<M>,
}

impl<M: Metric> Grassfire<M> {
    /// Burns `mesh` from its boundary under `metric` (a metric or a reference to one).
    /// Every node on a boundary edge (its vertices and Steiner points) is a source at 0;
    /// components without a boundary stay unreached (`inf`).
    ///
    /// # Errors
    /// [`Error::NoBoundary`] if no edge has exactly one face; as [`Solver::new`] and
    /// [`Solver::field`] otherwise.
    pub fn burn(
        mesh: impl Into<Arc<TriMesh>>,
        metric: M,
        options: &Options,
    ) -> Result<Self, Error> {
        let solver = Solver::new(mesh, metric, options)?;
        let mesh = solver.mesh();
        let layout = solver.layout();
        let mut nodes: Vec<u32> = (0..mesh.edge_count() as u32)
            .filter(|&e| mesh.edge_faces(e).len() == 1)
            .flat_map(|e| {
                let [a, b] = mesh.edge_vertices(e);
                [a, b].into_iter().chain(layout.edge_nodes(e))
            })
            .collect();
        if nodes.is_empty() {
            return Err(Error::NoBoundary);
        }
        nodes.sort_unstable();
        nodes.dedup();
        let sources: Vec<Source> = nodes
            .iter()
            .map(|&node| Source::new(layout.surface_point(node)))
            .collect();
        let field = solver.field(sources)?;
        Ok(Grassfire { field })
    }

    /// The distance field (every boundary node a source at 0): distances at any
    /// point, paths back to the boundary.
    pub fn field(&self) -> &Field<M> {
        &self.field
    }

    /// The distance field, given up.
    pub fn into_field(self) -> Field<M> {
        self.field
    }

    /// The solver the fire burnt with (its mesh, metric and Steiner layout).
    pub fn solver(&self) -> &Solver<M> {
        self.field.solver()
    }
}

/// Per vertex, when the fire from the sheets' border may take it: `distance` on the
/// sheets, 0 at a vertex of curves only. A curve has no width: it is all border, and
/// burns from its free ends along its length, so that its significance is the length
/// burnt (as on an axis of curves alone). Were it reached by the grassfire that runs
/// along it, every point of a curve would be taken as soon as the fire passed, and a
/// limb that an axis has as curves (a thin tube sampled coarsely) would be pruned
/// away, however long.
pub(super) fn curves_reached_at_once(mesh: &TriMesh, distance: &[f64]) -> Vec<f64> {
    distance
        .iter()
        .enumerate()
        .map(|(v, &d)| {
            if mesh.vertex_faces(v as u32).is_empty() {
                0.0
            } else {
                d
            }
        })
        .collect()
}

/// The unpruned skeleton of `mesh` burnt from its border, with the grassfire's field;
/// without a border, punctured (no fire reaches the sheets: their reach is `inf`; the
/// curves burn from their free ends at once) and no field.
/// Tubularity against `radius` (one per vertex; `None`: the grassfire's distances).
pub(super) fn burn_from_border<M: Metric + Clone>(
    mesh: &TriMesh,
    metric: M,
    options: &Options,
    radius: Option<&[f64]>,
) -> Result<(Skeleton, Option<Field<M>>), Error> {
    match Grassfire::burn(mesh, metric.clone(), options) {
        Ok(fire) => Ok((Skeleton::of_fire(&fire, radius), Some(fire.into_field()))),
        Err(Error::NoBoundary) => {
            let unreached = vec![f64::INFINITY; mesh.vertex_count()];
            let reach = curves_reached_at_once(mesh, &unreached);
            let radius = radius.unwrap_or(&unreached);
            Ok((Skeleton::thinned(mesh, &metric, &reach, radius), None))
        }
        Err(e) => Err(e),
    }
}
