//! The options every propagating command shares: Steiner points, engine, and the metric
//! (Euclidean, or a density, tensor or tensor-field file), read into one
//! [`BuiltinMetric`] (the library's enum of them).

use crate::inputs::{read_density, read_tensor, read_tensor_field};
use crate::CliResult;
use geotracks::mesh::TriMesh;
use geotracks::{BuiltinMetric, Euclidean, Method, Options};
use std::path::PathBuf;

/// Steiner points, engine and metric.
#[derive(clap::Args)]
pub struct MetricArgs {
    /// Mean number of Steiner points per edge [default: 2, or 5 with --density, with a
    /// --tensor-field that varies across a face, or with --method tracks or graph: the
    /// Steiner graph needs more points than the wavefront engine for the same
    /// accuracy].
    #[arg(long)]
    pub k: Option<f64>,
    /// Propagation method: wave (Steiner points that carry their wavefront: exact on
    /// planes, the most accurate; with --density it runs tracks), tracks (the
    /// track-pruned Steiner graph), graph (the complete Steiner graph, naive),
    /// dijkstra (mesh edges only) or exact (exact geodesics: windows carried face to
    /// face; Euclidean or a constant --tensor, refused for a metric whose faces do not
    /// glue).
    #[arg(long, default_value = "wave")]
    pub method: Method,
    /// Per-vertex density file: one positive number per vertex.
    #[arg(long, conflicts_with_all = ["tensor", "tensor_field"])]
    pub density: Option<PathBuf>,
    /// Per-face tensor file: one line `xx xy xz yy yz zz` per face of the mesh file.
    #[arg(long, conflicts_with = "tensor_field")]
    pub tensor: Option<PathBuf>,
    /// Per-vertex tensor file: one line `xx xy xz yy yz zz` per vertex, interpolated
    /// linearly across each face (a smooth Riemannian metric; runs tracks, unless the
    /// field is constant on every face).
    #[arg(long)]
    pub tensor_field: Option<PathBuf>,
    /// The most distance tests one run may be estimated to make (a number such as 1e10,
    /// or `none`): a k that needs more is refused before any work, with the estimate
    /// and the largest k that fits [default: 4e9, a few minutes of one core].
    #[arg(long, value_name = "TESTS", value_parser = parse_work_limit)]
    pub work_limit: Option<WorkLimit>,
}

/// `--work-limit`: a number of distance tests, or none.
#[derive(Clone, Copy, Debug)]
pub struct WorkLimit(Option<u64>);

impl WorkLimit {
    /// `options` with this limit, or as they are without one given.
    pub fn apply(limit: Option<WorkLimit>, options: Options) -> Options {
        match limit {
            Some(WorkLimit(limit)) => options.with_work_limit(limit),
            None => options,
        }
    }
}

/// Parses `--work-limit`.
pub fn parse_work_limit(text: &str) -> Result<WorkLimit, String> {
    if text == "none" {
        return Ok(WorkLimit(None));
    }
    match text.parse::<f64>() {
        Ok(tests) if tests >= 1.0 && tests < u64::MAX as f64 => Ok(WorkLimit(Some(tests as u64))),
        _ => Err(format!(
            "'{text}' is not a work limit: give a number of distance tests >= 1 (such as 1e10), or none"
        )),
    }
}

impl MetricArgs {
    /// The run options: the method and work limit asked for, and `--k` if given (else
    /// the engine that runs picks its own: `Method::default_k`).
    pub fn options(&self) -> Options {
        let options = Options::DEFAULT.with_method(self.method);
        let options = match self.k {
            Some(k) => options.with_k(k),
            None => options,
        };
        WorkLimit::apply(self.work_limit, options)
    }

    /// The files the metric reads (none, or its density or tensor file): inputs that no
    /// output may overwrite.
    pub fn files(&self) -> impl Iterator<Item = &std::path::Path> {
        [&self.density, &self.tensor, &self.tensor_field]
            .into_iter()
            .flatten()
            .map(PathBuf::as_path)
    }

    /// Reads the metric's file, if any.
    pub fn metric(&self, mesh: &TriMesh) -> CliResult<BuiltinMetric> {
        Ok(match (&self.density, &self.tensor, &self.tensor_field) {
            (Some(path), _, _) => BuiltinMetric::Density(read_density(path, mesh)?),
            (None, Some(path), _) => BuiltinMetric::Tensor(read_tensor(path, mesh)?),
            (None, None, Some(path)) => BuiltinMetric::TensorField(read_tensor_field(path, mesh)?),
            (None, None, None) => BuiltinMetric::Euclidean(Euclidean),
        })
    }
}
