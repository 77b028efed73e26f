//! The options every propagating command shares: Steiner points, engine, and the metric
//! (Euclidean, or a density or tensor file), read into one [`MeshMetric`].

use crate::inputs::{read_density, read_tensor};
use crate::CliResult;
use geotracks::mesh::TriMesh;
use geotracks::{Density, Euclidean, FacePoint, Method, Metric, Options, Tensor};
use std::path::PathBuf;

/// Steiner points, engine and metric.
#[derive(clap::Args)]
pub struct MetricArgs {
    /// Mean number of Steiner points per edge.
    #[arg(long, default_value_t = 5.0)]
    pub k: f64,
    /// Propagation method: tracks (fast), graph (complete Steiner graph) or dijkstra
    /// (mesh edges only).
    #[arg(long, default_value = "tracks")]
    pub method: Method,
    /// Per-vertex density file: one positive number per vertex.
    #[arg(long, conflicts_with = "tensor")]
    pub density: Option<PathBuf>,
    /// Per-face tensor file: one line `xx xy xz yy yz zz` per face of the mesh file.
    #[arg(long)]
    pub tensor: Option<PathBuf>,
}

impl MetricArgs {
    /// The run options.
    pub fn options(&self) -> Options {
        Options::DEFAULT.with_k(self.k).with_method(self.method)
    }

    /// Reads the metric's file, if any.
    pub fn metric(&self, mesh: &TriMesh) -> CliResult<MeshMetric> {
        Ok(match (&self.density, &self.tensor) {
            (Some(path), _) => MeshMetric::Density(read_density(path, mesh)?),
            (None, Some(path)) => MeshMetric::Tensor(read_tensor(path, mesh)?),
            (None, None) => MeshMetric::Euclidean(Euclidean),
        })
    }
}

/// The metric chosen on the command line. One type for the three, so each command
/// builds one solver; the engine is monomorphised on it, and the `match` below takes the
/// same arm at every call. Not free: on the bunny (69K faces, k = 5, tracks) a run
/// executes 8 % (Euclidean), 6 % (density) and 7 % (tensor) more instructions than on
/// each metric's own type (callgrind); in time, Euclidean ran about 5 % slower and the
/// others within noise (commit message of the CLI crate split).
pub enum MeshMetric {
    /// No file: the length.
    Euclidean(Euclidean),
    /// `--density`.
    Density(Density),
    /// `--tensor`.
    Tensor(Tensor),
}

impl Metric for MeshMetric {
    // Always: left to itself the compiler keeps the match with the three metrics'
    // bodies out of line, and a run costs 12–13 % more instructions instead of 6–8 %.
    #[inline(always)]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        match self {
            MeshMetric::Euclidean(m) => m.cost(face, a, b),
            MeshMetric::Density(m) => m.cost(face, a, b),
            MeshMetric::Tensor(m) => m.cost(face, a, b),
        }
    }
    fn is_face_norm(&self) -> bool {
        match self {
            MeshMetric::Euclidean(m) => m.is_face_norm(),
            MeshMetric::Density(m) => m.is_face_norm(),
            MeshMetric::Tensor(m) => m.is_face_norm(),
        }
    }
    #[inline(always)]
    fn prunes_on(&self, face: u32) -> bool {
        match self {
            MeshMetric::Euclidean(m) => m.prunes_on(face),
            MeshMetric::Density(m) => m.prunes_on(face),
            MeshMetric::Tensor(m) => m.prunes_on(face),
        }
    }
    fn name(&self) -> &str {
        match self {
            MeshMetric::Euclidean(m) => m.name(),
            MeshMetric::Density(m) => m.name(),
            MeshMetric::Tensor(m) => m.name(),
        }
    }
}
