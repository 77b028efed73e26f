//! The compiled part of the `geotracks` Python package (`geotracks._geotracks`).
//!
//! The Python layer (`python/geotracks/__init__.py`) checks the arrays' shapes and kinds
//! and hands them here as C-contiguous `float64` / `int64`; this layer builds the
//! library's types, runs them with the GIL released, and returns numpy arrays that own
//! the library's buffers (no copy). Errors become `geotracks.GeotracksError` (a
//! `ValueError`) with the library's message.
//!
//! A run is a `FieldCore`: it holds the library's [`Field`] (which holds its solver),
//! so every question about one run is answered from it without running the engine
//! again, and it outlives the `MeshSolverCore` that made it. The one-call methods of
//! `MeshSolverCore` are one run each, answered by the same functions as a field's;
//! `path` is the library's one-path search (stopped at its target, from both ends where
//! that pays), which no field computed from the sources alone can be.

use geotracks::mesh::io::read_mesh as read_mesh_file;
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{
    BuiltinMetric, Density, Euclidean, Field, Method, Options, Solver, Source, Stop, SurfacePoint,
    Tensor, TensorField, VertexValues,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use std::sync::atomic::{AtomicU64, Ordering};

mod field;
mod queries;

use field::FieldCore;
use queries::*;

pyo3::create_exception!(
    geotracks,
    GeotracksError,
    pyo3::exceptions::PyValueError,
    "What the geotracks library refused, with its message (bad mesh, bad source, bad metric…)."
);

/// The library's error as a Python exception.
fn error(e: impl std::fmt::Display) -> PyErr {
    GeotracksError::new_err(e.to_string())
}

/// `v` as a vertex id (`what` names it in the error), refusing negative or too large
/// values; whether the vertex exists is the library's to check.
fn vertex_id(v: i64, what: impl std::fmt::Display) -> PyResult<u32> {
    u32::try_from(v).map_err(|_| error(format!("{what} {v} is not a vertex id")))
}

/// The vertex ids of a numpy vector.
fn vertex_ids(ids: &PyReadonlyArray1<'_, i64>, what: &str) -> PyResult<Vec<u32>> {
    ids.as_array().iter().map(|&v| vertex_id(v, what)).collect()
}

/// One row `xyz(item)` per item: points as an (n, 3) matrix.
fn matrix3<T>(items: &[T], xyz: impl Fn(&T) -> [f64; 3]) -> Array2<f64> {
    let flat: Vec<f64> = items.iter().flat_map(xyz).collect();
    Array2::from_shape_vec((items.len(), 3), flat).expect("three coordinates per row")
}

/// A numpy vector owned by Python.
type Vector<'py, T> = Bound<'py, PyArray1<T>>;
/// A numpy matrix owned by Python.
type Matrix<'py, T> = Bound<'py, PyArray2<T>>;

/// A source or target as Python gives it: a vertex id, or a surface point in the
/// command line's form (`"e:E:t"`, `"f:F:b0,b1,b2"`).
#[derive(FromPyObject)]
enum PointArg {
    Vertex(i64),
    Text(String),
}

impl PointArg {
    fn point(&self) -> PyResult<SurfacePoint> {
        match self {
            PointArg::Vertex(v) => vertex_id(*v, "vertex").map(SurfacePoint::Vertex),
            PointArg::Text(text) => text
                .parse()
                .map_err(|e| error(format!("'{text}' is not a surface point: {e}"))),
        }
    }
}

fn sources_of(points: &[PointArg]) -> PyResult<Vec<Source>> {
    points.iter().map(|p| Ok(Source::new(p.point()?))).collect()
}

/// The triangles as `u32` ids, refusing negative or too large ones.
fn triangles(faces: &PyReadonlyArray2<'_, i64>) -> PyResult<Vec<[u32; 3]>> {
    let f = faces.as_array();
    let id = |i: usize, c: usize| vertex_id(f[[i, c]], format!("F[{i}, {c}] ="));
    (0..f.nrows())
        .map(|i| Ok([id(i, 0)?, id(i, 1)?, id(i, 2)?]))
        .collect()
}

fn positions(vertices: &PyReadonlyArray2<'_, f64>) -> Vec<[f64; 3]> {
    let v = vertices.as_array();
    (0..v.nrows())
        .map(|i| [v[[i, 0]], v[[i, 1]], v[[i, 2]]])
        .collect()
}

/// `points` as surface points, refusing any that is not one (before any work).
fn surface_points(points: &[PointArg]) -> PyResult<Vec<SurfacePoint>> {
    points.iter().map(PointArg::point).collect()
}

/// The face ids of a numpy vector (all faces of `mesh` if `None`), refusing negative
/// or too large values; whether the face exists is the library's to check.
fn face_ids(mesh: &TriMesh, faces: Option<PyReadonlyArray1<'_, i64>>) -> PyResult<Vec<u32>> {
    match faces {
        Some(ids) => ids
            .as_array()
            .iter()
            .map(|&f| u32::try_from(f).map_err(|_| error(format!("face {f} is not a face id"))))
            .collect(),
        None => Ok((0..mesh.face_count() as u32).collect()),
    }
}

/// The run's stop for `max_distance` and `targets`, checked as the command line checks
/// it (the library checks it again against the sources' start values).
fn stop_of(max_distance: f64, targets: Option<Vec<PointArg>>) -> PyResult<Stop> {
    Stop::NONE
        .with_max_distance(max_distance)
        .check()
        .map_err(|e| error(format!("max_distance = {max_distance}: {e}")))?;
    let targets = surface_points(&targets.unwrap_or_default())?;
    Ok(Stop::NONE
        .with_max_distance(max_distance)
        .with_targets(targets))
}

/// The mesh and a solver on it, reused by every query (`geotracks.MeshSolver` wraps it).
#[pyclass(module = "geotracks._geotracks", frozen)]
struct MeshSolverCore {
    solver: Solver<BuiltinMetric>,
    /// How many times this solver's engine was started (see `runs`).
    runs: AtomicU64,
}

#[pymethods]
impl MeshSolverCore {
    /// `V` (n, 3) float64, `F` (m, 3) int64; `metric`: "euclidean", "density" (with
    /// `data` one value per vertex), "tensor" (with `data` (m, 6): xx, xy, xz, yy, yz,
    /// zz per face) or "tensor_field" (`data` (n, 6), per vertex).
    #[new]
    /// `work_limit`: the most distance tests a run may be estimated to make (`None`: no
    /// limit; `Options::work_limit`).
    #[pyo3(signature = (vertices, faces, k, method, metric, data=None, work_limit=Some(Options::DEFAULT_WORK_LIMIT)))]
    #[allow(clippy::too_many_arguments)] // the Python constructor's arguments, as given
    fn new(
        py: Python<'_>,
        vertices: PyReadonlyArray2<'_, f64>,
        faces: PyReadonlyArray2<'_, i64>,
        k: Option<f64>,
        method: &str,
        metric: &str,
        data: Option<PyReadonlyArray2<'_, f64>>,
        work_limit: Option<u64>,
    ) -> PyResult<Self> {
        let method: Method = method.parse().map_err(error)?;
        let mesh = TriMesh::new(positions(&vertices), triangles(&faces)?).map_err(error)?;
        let metric = match (metric, &data) {
            ("euclidean", _) => BuiltinMetric::Euclidean(Euclidean),
            ("density", Some(data)) => {
                let rho = data.as_array().iter().copied().collect();
                BuiltinMetric::Density(Density::new(&mesh, rho).map_err(error)?)
            }
            ("tensor" | "tensor_field", Some(data)) => {
                let t = data.as_array();
                let world: Vec<[f64; 6]> = (0..t.nrows())
                    .map(|i| std::array::from_fn(|c| t[[i, c]]))
                    .collect();
                if metric == "tensor" {
                    BuiltinMetric::Tensor(Tensor::from_world(&mesh, &world).map_err(error)?)
                } else {
                    let field = TensorField::from_world(&mesh, &world).map_err(error)?;
                    BuiltinMetric::TensorField(field)
                }
            }
            (other, _) => return Err(error(format!("unknown metric '{other}'"))),
        };
        // Without a k, the engine that runs picks its own (`Method::default_k`).
        let options = Options::DEFAULT
            .with_method(method)
            .with_work_limit(work_limit);
        let options = match k {
            Some(k) => options.with_k(k),
            None => options,
        };
        let solver = py.detach(|| Solver::new(mesh, metric, &options));
        Ok(MeshSolverCore {
            solver: solver.map_err(error)?,
            runs: AtomicU64::new(0),
        })
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.solver.mesh().vertex_count()
    }

    /// Number of faces kept (degenerate ones are dropped).
    #[getter]
    fn face_count(&self) -> usize {
        self.solver.mesh().face_count()
    }

    /// The engine that runs (a metric that is not flat on each face runs "tracks").
    #[getter]
    fn method(&self) -> String {
        self.solver.method().to_string()
    }

    /// How many times this solver's engine has been started: one per field and per
    /// one-call method, one per row of a distance matrix or of local rows. Queries on
    /// a field add nothing.
    #[getter]
    fn runs(&self) -> u64 {
        self.runs.load(Ordering::Relaxed)
    }

    /// One run from `sources`, stopped at `max_distance` or once the values at
    /// `targets` are final: the field that answers every question about it.
    #[pyo3(signature = (sources, max_distance=f64::INFINITY, targets=None))]
    fn field(
        &self,
        py: Python<'_>,
        sources: Vec<PointArg>,
        max_distance: f64,
        targets: Option<Vec<PointArg>>,
    ) -> PyResult<FieldCore> {
        let stop = stop_of(max_distance, targets)?;
        let field = self.run(py, &sources, stop)?;
        Ok(FieldCore { field })
    }

    /// Distance to every vertex from the nearest source; `inf` where unreached.
    #[pyo3(signature = (sources, max_distance=f64::INFINITY, targets=None))]
    fn distance<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
        max_distance: f64,
        targets: Option<Vec<PointArg>>,
    ) -> PyResult<Vector<'py, f64>> {
        let stop = stop_of(max_distance, targets)?;
        let values = self.vertex_values(py, &sources, stop)?;
        Ok(values.distances.into_pyarray(py))
    }

    /// Distance to every vertex and, per vertex, the index of its nearest source (-1
    /// where unreached).
    fn voronoi<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
    ) -> PyResult<(Vector<'py, f64>, Vector<'py, i64>)> {
        let values = self.vertex_values(py, &sources, Stop::NONE)?;
        let labels = queries::label_ids(values.labels);
        Ok((values.distances.into_pyarray(py), labels.into_pyarray(py)))
    }

    /// The shortest path from `target` to the nearest of `sources`, straightened:
    /// `(points (p, 3), surface points, length)`, from the target to the source. One
    /// run that stops once the target's value is final; from one source, with the
    /// Steiner-graph engines, it is searched from both ends at once on two threads
    /// (which no field from the sources alone can do); the solver keeps its buffers for
    /// the next path.
    fn path<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
        target: PointArg,
    ) -> PyResult<PyPath<'py>> {
        let sources = sources_of(&sources)?;
        let target = target.point()?;
        let solver = &self.solver;
        self.runs.fetch_add(1, Ordering::Relaxed);
        let path = py
            .detach(|| solver.shortest_path(&sources, target))
            .map_err(error)?
            .0;
        Ok(py_path(py, solver.mesh(), &path))
    }

    /// The field from `sources` at surface points: per point its distance, the
    /// gradient of the distance and the direction the geodesic travels there (world
    /// vectors in the point's face plane; `inf` and NaN where unreached, NaN vectors
    /// where there is no gradient, as at a source).
    fn gradient<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
        points: Vec<PointArg>,
    ) -> PyResult<PyGradients<'py>> {
        let points = surface_points(&points)?;
        let field = self.run(py, &sources, Stop::NONE)?;
        let found = py.detach(|| gradients(&field, &points)).map_err(error)?;
        Ok(py_gradients(py, found))
    }

    /// The isolines of the field from `sources` at `levels`: per line, its level,
    /// its points (p, 3) and whether it closes on itself.
    #[pyo3(signature = (sources, levels, subdivisions=None))]
    fn isolines<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
        levels: Vec<f64>,
        subdivisions: Option<u32>,
    ) -> PyResult<PyIsolines<'py>> {
        // The library's bound on levels, before the field is computed.
        check_levels(&levels)?;
        let field = self.run(py, &sources, Stop::NONE)?;
        FieldCore { field }.isolines(py, levels, subdivisions)
    }

    /// The regions of `faces` (all faces if `None`) in the field from `sources`: per
    /// region its face, what gives the distance there (`(kind, id)`), the edge its
    /// lines cross (-1: none), its virtual source (3,), offset, polygon (p, 3) with its
    /// surface points, holes and area. Faces are worked on all cores.
    #[pyo3(signature = (sources, faces=None, subdivisions=None))]
    fn regions<'py>(
        &self,
        py: Python<'py>,
        sources: Vec<PointArg>,
        faces: Option<PyReadonlyArray1<'_, i64>>,
        subdivisions: Option<u32>,
    ) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        let faces = face_ids(self.solver.mesh(), faces)?;
        let field = self.run(py, &sources, Stop::NONE)?;
        let found = py
            .detach(|| regions(&field, &faces, subdivisions))
            .map_err(error)?;
        py_regions(py, field.mesh(), found)
    }

    /// One row per source vertex: its distance to every vertex, or to `targets`; rows
    /// computed on all cores.
    #[pyo3(signature = (sources, targets=None))]
    fn distance_matrix<'py>(
        &self,
        py: Python<'py>,
        sources: PyReadonlyArray1<'_, i64>,
        targets: Option<PyReadonlyArray1<'_, i64>>,
    ) -> PyResult<Matrix<'py, f64>> {
        let sources = vertex_ids(&sources, "source")?;
        let targets = targets.map(|t| vertex_ids(&t, "target")).transpose()?;
        let solver = &self.solver;
        let width = targets.as_ref().map_or(self.vertex_count(), |t| t.len());
        // The rows, then the array they are copied into: twice the values at once.
        solver
            .check_rows_fit(sources.len(), width, 16)
            .map_err(error)?;
        self.runs.fetch_add(sources.len() as u64, Ordering::Relaxed);
        let rows = py
            .detach(|| solver.distance_rows(&sources, targets.as_deref()))
            .map_err(error)?;
        let matrix = Array2::from_shape_fn((rows.len(), width), |(i, j)| rows[i].distances[j]);
        Ok(matrix.into_pyarray(py))
    }

    /// Every pair (source, vertex) within `max_distance` of each other, for each vertex
    /// of `sources`, as `(rows, columns, distances)` (row: the source's vertex id), one
    /// run per source stopped at `max_distance`, on all cores.
    fn local_distance_rows<'py>(
        &self,
        py: Python<'py>,
        sources: PyReadonlyArray1<'_, i64>,
        max_distance: f64,
    ) -> PyResult<(Vector<'py, i64>, Vector<'py, i64>, Vector<'py, f64>)> {
        // The library's check, as every run and the command line make it.
        Stop::NONE
            .with_max_distance(max_distance)
            .check()
            .map_err(|e| error(format!("max_distance = {max_distance}: {e}")))?;
        let sources = vertex_ids(&sources, "source")?;
        let solver = &self.solver;
        self.runs.fetch_add(sources.len() as u64, Ordering::Relaxed);
        let rows = py.detach(|| solver.local_distance_rows(&sources, max_distance));
        let rows = rows.map_err(error)?;
        let total: usize = rows.iter().map(Vec::len).sum();
        let (mut r, mut c, mut d) = (
            Vec::with_capacity(total),
            Vec::with_capacity(total),
            Vec::with_capacity(total),
        );
        for (&source, row) in sources.iter().zip(&rows) {
            for &(j, value) in row {
                r.push(source as i64);
                c.push(j as i64);
                d.push(value);
            }
        }
        Ok((r.into_pyarray(py), c.into_pyarray(py), d.into_pyarray(py)))
    }
}

impl MeshSolverCore {
    /// One run from `sources` until `stop`, with the GIL released: the field.
    fn run(
        &self,
        py: Python<'_>,
        sources: &[PointArg],
        stop: Stop,
    ) -> PyResult<Field<BuiltinMetric>> {
        self.counted(py, sources, stop, Solver::field)
    }

    /// The values and labels at vertices of one run: no field is kept (the exact
    /// engine then holds only its wavefront's windows).
    fn vertex_values(
        &self,
        py: Python<'_>,
        sources: &[PointArg],
        stop: Stop,
    ) -> PyResult<VertexValues> {
        self.counted(py, sources, stop, Solver::vertex_values)
    }

    /// `ask` of the solver for one run from `sources` until `stop`, with the GIL
    /// released: the only place runs are made for the one-call methods and fields,
    /// so `runs` counts every one.
    fn counted<R: Send>(
        &self,
        py: Python<'_>,
        sources: &[PointArg],
        stop: Stop,
        ask: impl FnOnce(&Solver<BuiltinMetric>, Sources<'static>) -> Result<R, geotracks::Error> + Send,
    ) -> PyResult<R> {
        let sources = sources_of(sources)?;
        let solver = &self.solver;
        self.runs.fetch_add(1, Ordering::Relaxed);
        py.detach(|| ask(solver, Sources::from(sources).until(stop)))
            .map_err(error)
    }
}

/// Reads a mesh file (OBJ, PLY, OFF, STL, `.ma`): `(V (n, 3) float64, F (m, 3) int64)`.
#[pyfunction]
fn read_mesh<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
) -> PyResult<(Matrix<'py, f64>, Matrix<'py, i64>)> {
    let mesh = py.detach(|| read_mesh_file(&path)).map_err(error)?;
    let vertices = matrix3(mesh.positions(), |p| p.to_array());
    let t = mesh.triangles();
    let faces = Array2::from_shape_fn((t.len(), 3), |(i, c)| t[i][c] as i64);
    Ok((vertices.into_pyarray(py), faces.into_pyarray(py)))
}

/// A route across an elevation grid (ESRI ASCII or GeoTIFF) from map point `start` to
/// `end` under the terrain cost `cost` (as `geotracks terrain --cost`; a directed one
/// from `start`):
/// `(points (p, 3) map x, y and elevation, cumulative cost (p,), cost)`.
#[pyfunction]
#[pyo3(signature = (dem, start, end, cost="none", k=2.0, method="wave"))]
fn terrain_route<'py>(
    py: Python<'py>,
    dem: std::path::PathBuf,
    start: [f64; 2],
    end: [f64; 2],
    cost: &str,
    k: f64,
    method: &str,
) -> PyResult<(Matrix<'py, f64>, Vector<'py, f64>, f64)> {
    use geotracks_terrain::{read_grid, route_on_grid, TerrainCost, TerrainError};
    let cost: TerrainCost = cost.parse().map_err(error)?;
    let method: geotracks::Method = method.parse().map_err(error)?;
    let route = py
        .detach(|| {
            let grid = read_grid(&dem).map_err(|e| e.to_string())?;
            let options = Options::DEFAULT.with_k(k).with_method(method);
            // Only the window of the grid the route needs is routed on (no mesh is built).
            route_on_grid(&grid, &cost, &options, start, end)
                .map(|r| r.route)
                .map_err(|e| match e {
                    TerrainError::Engine(geotracks::Error::Unreachable { .. }) => {
                        "no route: the end cannot be reached from the start (impassable \
                         faces or NODATA separate them)"
                            .to_string()
                    }
                    ref
                    t @ (TerrainError::Outside { x, y, .. } | TerrainError::NoData { x, y }) => {
                        let which = if [x, y] == start { "start" } else { "end" };
                        format!("{which} ({x}, {y}): {t}")
                    }
                    e => e.to_string(),
                })
        })
        .map_err(error)?;
    let points = matrix3(&route.points, |p| p.to_array());
    let total = route.cost();
    Ok((
        points.into_pyarray(py),
        route.cumulative_cost.into_pyarray(py),
        total,
    ))
}

/// The medial axis options of `spacing` (None: the default), `angle` (degrees) and
/// `span` (spacings), checked (also for a `.ma` file, which does not use them).
fn medial_options(
    spacing: Option<f64>,
    angle: f64,
    span: f64,
) -> PyResult<geotracks::skeleton::medial::MedialAxisOptions> {
    let options = geotracks::skeleton::medial::MedialAxisOptions::default()
        .with_spacing(spacing)
        .with_min_angle_degrees(angle)
        .with_min_span(span);
    options.validate().map_err(|e| error(e.to_string()))?;
    Ok(options)
}

/// A library error for `path`: a reader's names the file already, others get it.
fn named(path: &std::path::Path, e: geotracks::Error) -> String {
    match e {
        geotracks::Error::Mesh(e) => e.to_string(),
        e => format!("{}: {e}", path.display()),
    }
}

/// The medial axis of a file: read from `.ma`, or computed from a closed surface mesh.
fn axis_of_file(
    path: &std::path::Path,
    weld: bool,
    options: &geotracks::skeleton::medial::MedialAxisOptions,
) -> Result<(geotracks::mesh::io::MedialAxis, Option<usize>), String> {
    geotracks::skeleton::medial::medial_axis_of_file(path, weld, options)
        .map_err(|e| named(path, e))
}

/// The medial axis of a closed surface mesh file: `(positions (n, 3), radii (n,), faces
/// (f, 3))`.
#[pyfunction]
#[pyo3(signature = (mesh, spacing=None, angle=geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_ANGLE_DEGREES, span=geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_SPAN, weld=false))]
fn medial_axis<'py>(
    py: Python<'py>,
    mesh: std::path::PathBuf,
    spacing: Option<f64>,
    angle: f64,
    span: f64,
    weld: bool,
) -> PyResult<(Matrix<'py, f64>, Vector<'py, f64>, Matrix<'py, i64>)> {
    let options = medial_options(spacing, angle, span)?;
    let axis = py
        .detach(|| {
            let read = geotracks::mesh::io::ReadOptions::DEFAULT.with_weld(weld);
            let surface =
                geotracks::mesh::io::read_mesh_with(&mesh, &read).map_err(|e| e.to_string())?;
            geotracks::skeleton::medial::medial_axis(&surface, &options)
                .map_err(|e| named(&mesh, e))
        })
        .map_err(error)?;
    let triangles: &[[u32; 3]] = axis.surface.as_ref().map_or(&[], |m| m.triangles());
    let faces = Array2::from_shape_fn((triangles.len(), 3), |(i, c)| triangles[i][c] as i64);
    Ok((
        matrix3(&axis.positions, |p| *p).into_pyarray(py),
        axis.radii.clone().into_pyarray(py),
        faces.into_pyarray(py),
    ))
}

/// The curve skeleton of a medial axis file (`.ma`), or of a closed surface mesh file
/// through its medial axis (`spacing`, `angle`, `span`, `weld` as in [`medial_axis`]), pruned at
/// `prune` (a length, or a percentage of the bounding-box diagonal such as `"5%"`) and
/// at `tubular` (the least erosion thickness over the medial radius where a branch
/// joins) and at `protrusion` (the least reach out of the rest's medial balls over that
/// radius), burnt from the border (`burn="boundary"`) or by medial radius (`"radius"`),
/// its points at the centre of the shape's cross-section or, with `centred=False`, on
/// the axis (`None`: `Placement::default()`, centred): `(points (p, 3), radii (p,), significance (p,),
/// edges (e, 2), b1)`.
#[pyfunction]
#[pyo3(signature = (axis, prune="5%", burn="boundary", k=5.0, tubular=geotracks::skeleton::DEFAULT_MIN_TUBULARITY, spacing=None, angle=geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_ANGLE_DEGREES, span=geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_SPAN, weld=false, centred=None, protrusion=geotracks::skeleton::DEFAULT_MIN_PROTRUSION, trim_tips=true))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)] // five named arrays, as the Python wrapper documents; the keywords are Python's
fn skeleton<'py>(
    py: Python<'py>,
    axis: std::path::PathBuf,
    prune: &str,
    burn: &str,
    k: f64,
    tubular: f64,
    spacing: Option<f64>,
    angle: f64,
    span: f64,
    weld: bool,
    centred: Option<bool>,
    protrusion: f64,
    trim_tips: bool,
) -> PyResult<(
    Matrix<'py, f64>,
    Vector<'py, f64>,
    Vector<'py, f64>,
    Matrix<'py, i64>,
    usize,
)> {
    use geotracks::skeleton::{medial_axis_skeleton_with_cycles, Burn, Placement, Prune, Pruning};
    let burn = match burn {
        "boundary" => Burn::Boundary,
        "radius" => Burn::Radius,
        other => {
            return Err(error(format!(
                "burn '{other}': expected 'boundary' or 'radius'"
            )))
        }
    };
    let prune: Prune = prune.parse().map_err(|e| error(format!("prune {e}")))?;
    if tubular.is_nan() || tubular < 0.0 {
        return Err(error(format!("tubular {tubular}: expected a number >= 0")));
    }
    if protrusion.is_nan() || protrusion < 0.0 {
        return Err(error(format!(
            "protrusion {protrusion}: expected a number >= 0"
        )));
    }
    let medial = medial_options(spacing, angle, span)?;
    let (skeleton, b1) = py
        .detach(|| {
            let (axis, solid_cycles) = axis_of_file(&axis, weld, &medial)?;
            let pruning = Pruning {
                erosion_thickness: prune.threshold(axis.diagonal()),
                tubularity: tubular,
                protrusion,
                trim_tips,
            };
            let options = Options::DEFAULT.with_k(k).with_method(Method::Tracks);
            let max_cycles = solid_cycles.unwrap_or(usize::MAX);
            let placement = match centred {
                Some(true) => Placement::Centred,
                Some(false) => Placement::OnAxis,
                None => Placement::default(),
            };
            let (skeleton, _) = medial_axis_skeleton_with_cycles(
                &axis, burn, &options, pruning, max_cycles, placement,
            )
            .map_err(|e| e.to_string())?;
            Ok::<_, String>((skeleton, solid_cycles.unwrap_or(axis.betti_numbers().b1)))
        })
        .map_err(error)?;
    let p = &skeleton.points;
    let points = matrix3(p, |q| q.position);
    let radii: Vec<f64> = p.iter().map(|q| q.radius.unwrap_or(f64::NAN)).collect();
    let significance: Vec<f64> = p.iter().map(|q| q.significance).collect();
    let e = &skeleton.edges;
    let edges = Array2::from_shape_fn((e.len(), 2), |(i, c)| e[i][c] as i64);
    Ok((
        points.into_pyarray(py),
        radii.into_pyarray(py),
        significance.into_pyarray(py),
        edges.into_pyarray(py),
        b1,
    ))
}

/// The compiled part of the `geotracks` Python package.
#[pymodule]
fn _geotracks(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<MeshSolverCore>()?;
    m.add_class::<FieldCore>()?;
    m.add_function(wrap_pyfunction!(read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(terrain_route, m)?)?;
    m.add_function(wrap_pyfunction!(skeleton, m)?)?;
    m.add_function(wrap_pyfunction!(medial_axis, m)?)?;
    m.add("GeotracksError", m.py().get_type::<GeotracksError>())?;
    m.add("DEFAULT_WORK_LIMIT", Options::DEFAULT_WORK_LIMIT)?;
    Ok(())
}
