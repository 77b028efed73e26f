//! What a field answers, as plain values: the work (done with the GIL released) is
//! apart from the conversion to Python objects, so that a `FieldCore` and the one-call
//! methods of `MeshSolverCore` give the same answers from the same code.

use crate::{error, matrix3, Matrix, Vector};
use geotracks::mesh::TriMesh;
use geotracks::{BuiltinMetric, Field, SurfacePoint};
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// The distance at each of `points`.
pub(crate) fn distances_at(
    field: &Field<BuiltinMetric>,
    points: &[SurfacePoint],
) -> Result<Vec<f64>, geotracks::Error> {
    points.iter().map(|&p| field.distance_at(p)).collect()
}

/// Per vertex, the index of its nearest source, -1 where unreached.
pub(crate) fn labels(field: &Field<BuiltinMetric>) -> Vec<i64> {
    label_ids(field.vertex_labels())
}

/// Labels as Python sees them: `-1` where unreached.
pub(crate) fn label_ids(labels: Vec<u32>) -> Vec<i64> {
    labels
        .into_iter()
        .map(|l| if l == u32::MAX { -1 } else { l as i64 })
        .collect()
}

/// Per point: distance, gradient and geodesic direction (`inf` and NaN where
/// unreached, NaN vectors where there is no gradient).
pub(crate) type Gradients = (Vec<f64>, Array2<f64>, Array2<f64>);

/// The distance, gradient and geodesic direction at each of `points`.
pub(crate) fn gradients(
    field: &Field<BuiltinMetric>,
    points: &[SurfacePoint],
) -> Result<Gradients, geotracks::Error> {
    let n = points.len();
    let (mut d, mut g, mut t) = (
        vec![f64::INFINITY; n],
        Array2::from_elem((n, 3), f64::NAN),
        Array2::from_elem((n, 3), f64::NAN),
    );
    for (i, &p) in points.iter().enumerate() {
        d[i] = field.distance_at(p)?;
        if let Some(gradient) = field.gradient_at(p)? {
            for c in 0..3 {
                g[[i, c]] = gradient.vector[c];
                t[[i, c]] = gradient.direction[c];
            }
        }
    }
    Ok((d, g, t))
}

/// The library's bound on the number of levels, checked before a one-call method runs
/// (no level at all draws nothing, as the library does).
pub(crate) fn check_levels(levels: &[f64]) -> PyResult<()> {
    if !levels.is_empty() {
        geotracks::trace::check_level_count(levels.len()).map_err(error)?;
    }
    Ok(())
}

/// The isolines at `levels`, drawn with `subdivisions` sub-triangles per face edge
/// (the library's default if `None`).
pub(crate) fn isolines(
    field: &Field<BuiltinMetric>,
    levels: &[f64],
    subdivisions: Option<u32>,
) -> Result<Vec<geotracks::trace::Isoline>, geotracks::Error> {
    use geotracks::trace::IsolineOptions;
    let mut options = IsolineOptions::DEFAULT;
    if let Some(n) = subdivisions {
        options = options.with_subdivisions(n);
    }
    field.isolines(levels, &options)
}

/// The regions of `faces`, `subdivisions` grid steps per face edge (the library's
/// default if `None`), worked on all cores.
pub(crate) fn regions(
    field: &Field<BuiltinMetric>,
    faces: &[u32],
    subdivisions: Option<u32>,
) -> Result<Vec<geotracks::trace::Region>, geotracks::Error> {
    use geotracks::trace::DEFAULT_REGION_SUBDIVISIONS;
    use rayon::prelude::*;
    let n = subdivisions.unwrap_or(DEFAULT_REGION_SUBDIVISIONS);
    let per_face: Result<Vec<_>, _> = faces.par_iter().map(|&f| field.regions(f, n)).collect();
    Ok(per_face?.into_iter().flatten().collect())
}

// Conversions to what Python is given.

/// A path as `(points (p, 3), surface points, length)`, from the target to the source.
pub(crate) type PyPath<'py> = (Matrix<'py, f64>, Vec<String>, f64);

/// A path as Python is given it.
pub(crate) fn py_path<'py>(
    py: Python<'py>,
    mesh: &TriMesh,
    path: &geotracks::trace::GeodesicPath,
) -> PyPath<'py> {
    let points = matrix3(&path.points, |p| p.position(mesh).to_array());
    let names = path.points.iter().map(|p| p.to_string()).collect();
    (points.into_pyarray(py), names, path.length)
}

/// `(distances, gradients, directions)` as numpy arrays.
pub(crate) type PyGradients<'py> = (Vector<'py, f64>, Matrix<'py, f64>, Matrix<'py, f64>);

/// Gradients as Python is given them.
pub(crate) fn py_gradients(py: Python<'_>, (d, g, t): Gradients) -> PyGradients<'_> {
    (d.into_pyarray(py), g.into_pyarray(py), t.into_pyarray(py))
}

/// Per line: its level, its points (p, 3) and whether it closes on itself.
pub(crate) type PyIsolines<'py> = Vec<(f64, Matrix<'py, f64>, bool)>;

/// Isolines as Python is given them.
pub(crate) fn py_isolines<'py>(
    py: Python<'py>,
    mesh: &TriMesh,
    lines: Vec<geotracks::trace::Isoline>,
) -> PyIsolines<'py> {
    lines
        .into_iter()
        .map(|line| {
            let points = matrix3(&line.points, |p| p.position(mesh).to_array());
            (line.level, points.into_pyarray(py), line.closed)
        })
        .collect()
}

/// Per region: its face, what gives the distance there (`(kind, id)`), the edge its
/// lines cross (-1: none), its virtual source (3,), offset, polygon (p, 3) with its
/// surface points, holes and area.
pub(crate) fn py_regions<'py>(
    py: Python<'py>,
    mesh: &TriMesh,
    regions: Vec<geotracks::trace::Region>,
) -> PyResult<Vec<Bound<'py, PyTuple>>> {
    use geotracks::trace::ValueSource;
    let position = |p: &SurfacePoint| p.position(mesh).to_array();
    regions
        .into_iter()
        .map(|r| {
            let (kind, id) = match r.source {
                ValueSource::Node(id) => ("node", id),
                ValueSource::Source(id) => ("source", id),
                ValueSource::Wave(id) => ("wave", id),
                ValueSource::WaveBend(id) => ("wave_bend", id),
                ValueSource::Window(id) => ("window", id),
                // The enum is non-exhaustive: a kind added later is refused by name
                // rather than mislabelled.
                other => return Err(error(format!("unknown region source {other:?}"))),
            };
            let polygon = matrix3(&r.polygon, position).into_pyarray(py);
            let names: Vec<String> = r.polygon.iter().map(|p| p.to_string()).collect();
            let holes: Vec<_> = r
                .holes
                .iter()
                .map(|h| matrix3(h, position).into_pyarray(py))
                .collect();
            let across = r.across.map_or(-1, i64::from);
            (
                r.face,
                (kind, id),
                across,
                r.virtual_source.to_array().to_vec().into_pyarray(py),
                r.offset,
                polygon,
                names,
                holes,
                r.area,
            )
                .into_pyobject(py)
        })
        .collect()
}
