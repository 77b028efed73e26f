//! `FieldCore`: one finished run, answering every question without running again.

use crate::queries::*;
use crate::*;

/// One finished run (`geotracks.Field` wraps it): the library's field, which holds its
/// solver (shared), so it answers every question about the run without running the
/// engine again, from any thread, and outlives the `MeshSolverCore` that made it.
#[pyclass(module = "geotracks._geotracks", frozen)]
pub(crate) struct FieldCore {
    pub(crate) field: Field<BuiltinMetric>,
}

#[pymethods]
impl FieldCore {
    /// Distance at every vertex; `inf` where unreached.
    pub(crate) fn distance<'py>(&self, py: Python<'py>) -> Vector<'py, f64> {
        let field = &self.field;
        py.detach(|| field.vertex_distances().to_vec())
            .into_pyarray(py)
    }

    /// The distance at each of `points` (vertex ids or surface points); `inf` where
    /// unreached.
    pub(crate) fn distance_at<'py>(
        &self,
        py: Python<'py>,
        points: Vec<PointArg>,
    ) -> PyResult<Vector<'py, f64>> {
        let points = surface_points(&points)?;
        let field = &self.field;
        let found = py.detach(|| distances_at(field, &points)).map_err(error)?;
        Ok(found.into_pyarray(py))
    }

    /// The path from `target` to the nearest source, straightened: `(points (p, 3),
    /// surface points, length)`, from the target to the source.
    pub(crate) fn path<'py>(&self, py: Python<'py>, target: PointArg) -> PyResult<PyPath<'py>> {
        let target = target.point()?;
        let field = &self.field;
        let path = py.detach(|| field.path(target)).map_err(error)?;
        Ok(py_path(py, field.mesh(), &path))
    }

    /// At each of `points`: its distance, the gradient of the distance and the
    /// direction the geodesic travels there (as `MeshSolverCore.gradient`).
    pub(crate) fn gradient<'py>(
        &self,
        py: Python<'py>,
        points: Vec<PointArg>,
    ) -> PyResult<PyGradients<'py>> {
        let points = surface_points(&points)?;
        let field = &self.field;
        let found = py.detach(|| gradients(field, &points)).map_err(error)?;
        Ok(py_gradients(py, found))
    }

    /// The isolines at `levels`: per line, its level, its points (p, 3) and whether it
    /// closes on itself.
    #[pyo3(signature = (levels, subdivisions=None))]
    pub(crate) fn isolines<'py>(
        &self,
        py: Python<'py>,
        levels: Vec<f64>,
        subdivisions: Option<u32>,
    ) -> PyResult<PyIsolines<'py>> {
        check_levels(&levels)?;
        let field = &self.field;
        let lines = py
            .detach(|| isolines(field, &levels, subdivisions))
            .map_err(error)?;
        Ok(py_isolines(py, field.mesh(), lines))
    }

    /// The regions of `faces` (all faces if `None`), as `MeshSolverCore.regions`; faces
    /// are worked on all cores.
    #[pyo3(signature = (faces=None, subdivisions=None))]
    pub(crate) fn regions<'py>(
        &self,
        py: Python<'py>,
        faces: Option<PyReadonlyArray1<'_, i64>>,
        subdivisions: Option<u32>,
    ) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        let field = &self.field;
        let faces = face_ids(field.mesh(), faces)?;
        let found = py
            .detach(|| regions(field, &faces, subdivisions))
            .map_err(error)?;
        py_regions(py, field.mesh(), found)
    }

    /// Per vertex, the index of its nearest source; -1 where unreached.
    pub(crate) fn voronoi<'py>(&self, py: Python<'py>) -> Vector<'py, i64> {
        let field = &self.field;
        py.detach(|| labels(field)).into_pyarray(py)
    }

    /// The run's sources, in the command line's form (`"V"`, `"e:E:t"`,
    /// `"f:F:b0,b1,b2"`), in the order given.
    #[getter]
    pub(crate) fn sources(&self) -> Vec<String> {
        self.field
            .sources()
            .iter()
            .map(|s| s.point.to_string())
            .collect()
    }

    /// The run's counters: engine, mean Steiner points per edge, nodes settled, queue
    /// insertions, distance tests, seconds propagating, whether it stopped early, and
    /// the exact engine's windows (made, and carried across faces; 0 otherwise).
    #[getter]
    pub(crate) fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let stats = self.field.stats();
        let dict = PyDict::new(py);
        dict.set_item("method", stats.method.to_string())?;
        dict.set_item("k", stats.k)?;
        dict.set_item("settles", stats.settles)?;
        dict.set_item("pushes", stats.pushes)?;
        dict.set_item("distance_tests", stats.distance_tests)?;
        dict.set_item("propagate_seconds", stats.propagate_seconds)?;
        dict.set_item("stopped_early", stats.stopped_early)?;
        dict.set_item("windows_created", stats.windows_created)?;
        dict.set_item("windows_kept", stats.windows_kept)?;
        Ok(dict)
    }

    /// Number of vertices of the field's mesh.
    #[getter]
    pub(crate) fn vertex_count(&self) -> usize {
        self.field.mesh().vertex_count()
    }
}
