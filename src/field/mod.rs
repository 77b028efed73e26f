//! [`Field`]: a finished run with the solver that computed it, which answers every
//! question about it; [`FieldData`]: the same run as plain data.
//!
//! A field is tied to its solver by type: it holds it (a shared reference count), so
//! the mesh, the metric and the Steiner layout its queries use are always the ones it
//! was computed with, and none of them is passed again.

mod data;
mod windows;

pub use data::{FieldData, Stats};
pub(crate) use data::{FieldView, Goal, Horizon, Root, SolverId, Wave};
pub(crate) use windows::{Origin, Window, WindowField};

use crate::mesh::{Topology, TriMesh};
use crate::options::Method;
use crate::propagate::Workspace;
use crate::steiner::SteinerLayout;
use crate::surface::{Source, SurfacePoint};
use crate::trace::{GeodesicPath, Gradient, Isoline, IsolineOptions, Query, Region};
use crate::{Error, Solver};
use geotracks_metrics::Metric;

/// A finished run and the solver that computed it: the distance at every vertex and at
/// any surface point, gradients, paths (straightened, with their length under the
/// solver's metric), isolines, regions and the nearest source of each vertex.
///
/// Made by [`Solver::field`] (owning its data, `Field<M>`) or [`Solver::run`] (borrowing
/// a [`Workspace`]'s buffers until the next run, `Field<M, &Workspace>`); every query is
/// a method, and none re-runs the engine. [`Field::into_data`] keeps the plain data;
/// [`Solver::attach`] gives it its queries back.
///
/// ```
/// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, SurfacePoint};
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
/// let field = solver.field(0)?;
/// let centre = SurfacePoint::Face { face: 0, bary: [1.0 / 3.0; 3] };
/// let d = field.distance_at(centre)?;
/// assert!((d - 5f64.sqrt() / 3.0).abs() < 1e-12); // straight from vertex 0
/// let path = field.path(centre)?; // from the point to its source, straightened
/// assert!((path.length - d).abs() < 1e-12);
/// # Ok::<(), geotracks::Error>(())
/// ```
pub struct Field<M, D = FieldData, T = TriMesh> {
    solver: Solver<M, T>,
    data: D,
}

impl<M: Metric, D: FieldStorage, T: Topology> std::fmt::Debug for Field<M, D, T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Field")
            .field("method", &self.method())
            .field("sources", &self.sources().len())
            .field("nodes", &self.node_distances().len())
            .field("stats", self.stats())
            .finish_non_exhaustive()
    }
}

/// Where a [`Field`] keeps its per-node state: its own [`FieldData`], or a
/// [`Workspace`]'s buffers (`&Workspace`). Sealed: nothing else can be one.
pub trait FieldStorage: private::Storage {}

impl FieldStorage for FieldData {}
impl FieldStorage for &Workspace {}

mod private {
    use super::{FieldData, FieldView, Stats, Workspace};
    use crate::steiner::SteinerLayout;

    /// The state a field's queries read (see `FieldStorage`).
    pub trait Storage {
        fn view<'a>(&'a self, layout: &'a SteinerLayout) -> FieldView<'a>;
        fn stats(&self) -> &Stats;
    }

    impl Storage for FieldData {
        fn view<'a>(&'a self, _: &'a SteinerLayout) -> FieldView<'a> {
            FieldData::view(self)
        }
        fn stats(&self) -> &Stats {
            FieldData::stats(self)
        }
    }

    impl Storage for &Workspace {
        fn view<'a>(&'a self, layout: &'a SteinerLayout) -> FieldView<'a> {
            Workspace::view(self, layout)
        }
        fn stats(&self) -> &Stats {
            self.stats
                .as_ref()
                .expect("a field is made after a finished run")
        }
    }
}

impl<M, D, T: Topology> Field<M, D, T> {
    /// Pairs a run's state with the solver that computed it (the solver's runs only).
    pub(crate) fn new(solver: Solver<M, T>, data: D) -> Self {
        Field { solver, data }
    }

    /// The solver that computed the field.
    pub fn solver(&self) -> &Solver<M, T> {
        &self.solver
    }

    /// The mesh the field was computed on.
    pub fn mesh(&self) -> &T {
        self.solver.mesh()
    }

    /// The metric the field was computed under.
    pub fn metric(&self) -> &M {
        self.solver.metric()
    }

    /// The Steiner layout the field was computed on.
    pub fn layout(&self) -> &SteinerLayout {
        self.solver.layout()
    }
}

impl<M, T> Field<M, FieldData, T> {
    /// The field's plain data, without its solver (to keep, send or store;
    /// [`Solver::attach`] gives it its queries back).
    pub fn into_data(self) -> FieldData {
        self.data
    }

    /// The field's plain data, borrowed.
    pub fn data(&self) -> &FieldData {
        &self.data
    }
}

impl<M: Clone, T: Topology> Field<M, &Workspace, T> {
    /// The field with its own copy of the workspace's buffers, which the next run may
    /// then reuse.
    pub fn to_owned(&self) -> Field<M, FieldData, T> {
        let data = self.data.to_data(&self.solver);
        Field::new(self.solver.clone(), data)
    }
}

impl<M: Metric, D: FieldStorage, T: Topology> Field<M, D, T> {
    /// The borrowed query the methods below delegate to.
    pub(crate) fn query(&self) -> Query<'_, M, T> {
        let layout = self.solver.layout();
        Query::new(
            self.solver.mesh(),
            self.solver.metric(),
            self.data.view(layout),
            self.solver.setup().wave_turn(),
        )
    }

    /// The engine that computed the field.
    pub fn method(&self) -> Method {
        self.data.view(self.solver.layout()).method
    }

    /// Counters and timings of the run.
    pub fn stats(&self) -> &Stats {
        self.data.stats()
    }

    /// The sources of the run, validated (in canonical form).
    pub fn sources(&self) -> &[Source] {
        self.data.view(self.solver.layout()).sources
    }

    /// Distance at every vertex, in vertex order; `f64::INFINITY` where unreached.
    pub fn vertex_distances(&self) -> &[f64] {
        let layout = self.solver.layout();
        &self.data.view(layout).distance[..layout.vertex_count() as usize]
    }

    /// Distance at every node (vertices first, then Steiner points; see
    /// [`SteinerLayout`]).
    pub fn node_distances(&self) -> &[f64] {
        self.data.view(self.solver.layout()).distance
    }

    /// Distance at vertex `v`.
    ///
    /// # Panics
    /// If `v` is not a vertex of the mesh.
    pub fn distance(&self, v: u32) -> f64 {
        let count = self.solver.layout().vertex_count();
        assert!(v < count, "vertex {v} out of range (the mesh has {count})");
        self.vertex_distances()[v as usize]
    }

    /// The node and face through which `node` got its distance; `None` for a source or
    /// an unreached node. The face is [`NONE`](crate::mesh::NONE) when the parent lies
    /// on the same edge. An exact field ([`Method::Exact`]) has no parent nodes (its
    /// vertices are reached along windows' lines, which [`Field::path`] follows):
    /// `None` for every node.
    pub fn parent(&self, node: u32) -> Option<(u32, u32)> {
        let view = self.data.view(self.solver.layout());
        let p = *view.parent.get(node as usize)?;
        (p != crate::mesh::NONE).then(|| (p, view.parent_face[node as usize]))
    }

    /// How many vertices no source reaches (they lie on another component, or beyond
    /// a stop).
    pub fn unreachable_vertices(&self) -> usize {
        self.vertex_distances()
            .iter()
            .filter(|d| d.is_infinite())
            .count()
    }

    /// The distance at any surface point, as the engine defines it: at a vertex, its
    /// value; elsewhere, the least over the *candidates* of the faces holding the point
    /// ([`ValueSource`](crate::trace::ValueSource)): each node on a face's boundary,
    /// its value plus the metric's cost of the straight segment to the point; each
    /// source sharing the face, its start plus its segment; for a field of the
    /// wavefront engine also each node's wave that crosses into the face, `σ` plus the
    /// straight line from its source where it passes the node's window (or bends at the
    /// window's end), and the candidates of the faces across the face's edges, unfolded
    /// onto it, whose lines cross the shared edge (so that the field is continuous
    /// across edges but where a neighbour's neighbour gives less, by the engine's
    /// error). Each candidate is a real path's length. Not an interpolation of vertex
    /// values. `inf` when no source reaches the point, or when its value would exceed
    /// the run's [`Stop::max_distance`](crate::Stop::max_distance).
    ///
    /// # Complexity
    /// O(k) metric evaluations per face around the point (for the wavefront engine,
    /// and its neighbours).
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] if `point` is not a point of the mesh.
    pub fn distance_at(&self, point: impl Into<SurfacePoint>) -> Result<f64, Error> {
        self.query().distance_at(point.into())
    }

    /// The gradient of the field at `point`, from the candidate that gives its
    /// distance: the derivative of `σ + |x − site|` there. `None` where the gradient is
    /// undefined: unreached points, and points whose value only they explain (a source,
    /// a node whose value comes from nowhere else in its faces). At a vertex or edge
    /// point, the face (of those around it) whose candidate gives the least value.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, SurfacePoint};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let field = solver.field(0)?;
    /// let g = field
    ///     .gradient_at(SurfacePoint::Face { face: 0, bary: [0.2, 0.5, 0.3] })?
    ///     .expect("a reached point");
    /// // Straight away from the source at the origin: the point is (0.8, 0.3, 0).
    /// let away = glam::DVec3::new(0.8, 0.3, 0.0).normalize();
    /// assert!((g.direction - away).length() < 1e-12);
    /// assert!((g.vector - away).length() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Complexity
    /// As [`Field::distance_at`]: the candidates of the faces around the point.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] if `point` is not a point of the mesh.
    pub fn gradient_at(&self, point: impl Into<SurfacePoint>) -> Result<Option<Gradient>, Error> {
        self.query().gradient_at(point.into())
    }

    /// The traced path from `point`, straightened ([`straighten`](crate::trace::straighten)): the path users
    /// want, at most as long as the traced one.
    ///
    /// # Complexity
    /// As [`Field::trace`], then a few rounds of Newton's method on the path's edge
    /// crossings (tridiagonal: linear in the path's length per step).
    ///
    /// # Errors
    /// As [`Field::trace`].
    pub fn path(&self, point: impl Into<SurfacePoint>) -> Result<GeodesicPath, Error> {
        self.query().path(point.into())
    }

    /// The path from `point` to its nearest source, as the propagation found it: from
    /// the point to the best node of its faces (or straight to a source in one of
    /// them), then from parent to parent. Its length is the distance at `point`.
    ///
    /// # Complexity
    /// O(k) metric evaluations per face around the point, then one step per node on
    /// the path.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] for a point not on the mesh, [`Error::Unreachable`] when
    /// no source reaches the point.
    pub fn trace(&self, point: impl Into<SurfacePoint>) -> Result<GeodesicPath, Error> {
        self.query().trace(point.into())
    }

    /// The isolines of the field at `levels` (any finite values; a level no point
    /// reaches gives none), each as polylines of surface points; see the module docs
    /// for how they are drawn and what they guarantee.
    ///
    /// ```
    /// use geotracks::mesh::TriMesh;
    /// use geotracks::trace::IsolineOptions;
    /// use geotracks::{Euclidean, Options, Solver};
    ///
    /// // A unit square of two triangles, source at corner 0.
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let field = solver.field(0)?;
    /// let lines = field.isolines(&[0.5], &IsolineOptions::DEFAULT)?;
    /// // One quarter circle of radius 0.5 from edge to edge, every point on it.
    /// assert_eq!(lines.len(), 1);
    /// assert!(!lines[0].closed);
    /// for p in &lines[0].points {
    ///     assert!((p.position(&mesh).length() - 0.5).abs() < 1e-9);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidValue`] for a level that is not finite,
    /// [`Error::InvalidIsolineOption`] for options out of range or more than
    /// [`MAX_LEVELS`](crate::trace::MAX_LEVELS) levels.
    pub fn isolines(
        &self,
        levels: &[f64],
        options: &IsolineOptions,
    ) -> Result<Vec<Isoline>, Error> {
        self.query().isolines(levels, options)
    }

    /// Face `face`'s regions: where each of its candidates gives the distance, as
    /// polygons (see the module docs for how they are drawn, to `subdivisions` grid
    /// steps per edge; [`DEFAULT_REGION_SUBDIVISIONS`](crate::trace::DEFAULT_REGION_SUBDIVISIONS) is a good start). Sorted by
    /// candidate (nodes, sources, waves); a candidate whose region is cut in two gives
    /// two. Unreached parts of the face belong to no region.
    ///
    /// # Complexity
    /// `(n + 1)(n + 2) / 2` evaluations of the face's candidates, plus 40 per side where
    /// the candidate changes.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] for a face not in the mesh, [`Error::InvalidRegionOption`]
    /// for `subdivisions` outside `1..=1024`.
    pub fn regions(&self, face: u32, subdivisions: u32) -> Result<Vec<Region>, Error> {
        self.query().regions(face, subdivisions)
    }

    /// The index of the nearest source of every vertex (the geodesic Voronoi diagram of
    /// the sources, start values included), [`NONE`](crate::mesh::NONE) where unreached.
    ///
    /// # Complexity
    /// O(nodes): parents are followed to the source that started each chain, and every
    /// node is labelled once.
    pub fn vertex_labels(&self) -> Vec<u32> {
        self.query().vertex_labels()
    }

    /// The field's values and labels at the vertices, with its counters: what
    /// [`Solver::vertex_values`] gives, copied out of a field.
    pub fn vertex_values(&self) -> crate::VertexValues {
        crate::VertexValues {
            distances: self.vertex_distances().to_vec(),
            labels: self.vertex_labels(),
            stats: self.stats().clone(),
        }
    }

    /// As [`Field::vertex_labels`], for every node (vertices, then Steiner points in
    /// [`SteinerLayout`] order).
    pub fn node_labels(&self) -> Vec<u32> {
        self.query().node_labels()
    }

    /// The largest finite distance over the nodes (vertices and Steiner points): the
    /// top of the field's range, to spread isoline levels over
    /// ([`spread_levels`](crate::trace::spread_levels)); 0 when nothing is reached.
    pub fn max_reached_distance(&self) -> f64 {
        self.query().max_reached_distance()
    }
}
