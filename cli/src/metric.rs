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
    /// Mean number of Steiner points per edge [default: 2, or 5 with --density or with
    /// --method tracks or graph: the Steiner graph needs more points than the
    /// wavefront engine for the same accuracy].
    #[arg(long)]
    pub k: Option<f64>,
    /// Propagation method: wave (Steiner points that carry their wavefront: exact on
    /// planes, the most accurate; with --density it runs tracks), tracks (the
    /// track-pruned Steiner graph), graph (the complete Steiner graph, naive) or
    /// dijkstra (mesh edges only).
    #[arg(long, default_value = "wave")]
    pub method: Method,
    /// Per-vertex density file: one positive number per vertex.
    #[arg(long, conflicts_with = "tensor")]
    pub density: Option<PathBuf>,
    /// Per-face tensor file: one line `xx xy xz yy yz zz` per face of the mesh file.
    #[arg(long)]
    pub tensor: Option<PathBuf>,
}

impl MetricArgs {
    /// The k to run with: as given, else 2 for the wavefront engine, 5 where the
    /// Steiner graph runs (a density, or `--method tracks|graph`).
    pub fn k(&self) -> f64 {
        self.k.unwrap_or(
            if self.density.is_some() || matches!(self.method, Method::Tracks | Method::Graph) {
                5.0
            } else {
                2.0
            },
        )
    }

    /// The run options.
    pub fn options(&self) -> Options {
        Options::DEFAULT.with_k(self.k()).with_method(self.method)
    }

    /// The files the metric reads (none, or its density or tensor file): inputs that no
    /// output may overwrite.
    pub fn files(&self) -> impl Iterator<Item = &std::path::Path> {
        [&self.density, &self.tensor]
            .into_iter()
            .flatten()
            .map(PathBuf::as_path)
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

/// `each!(self, m => expr)`: `expr` with `m` bound to the metric inside, for each
/// variant: one match, the variants' bodies inlined.
macro_rules! each {
    ($self:ident, $m:ident => $e:expr) => {
        match $self {
            MeshMetric::Euclidean($m) => $e,
            MeshMetric::Density($m) => $e,
            MeshMetric::Tensor($m) => $e,
        }
    };
}

impl Metric for MeshMetric {
    // Always: left to itself the compiler keeps the match with the three metrics'
    // bodies out of line, and a run costs 12–13 % more instructions instead of 6–8 %.
    #[inline(always)]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        each!(self, m => m.cost(face, a, b))
    }
    fn is_face_norm(&self) -> bool {
        each!(self, m => m.is_face_norm())
    }
    #[inline(always)]
    fn prunes_on(&self, face: u32) -> bool {
        each!(self, m => m.prunes_on(face))
    }
    #[inline(always)]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        each!(self, m => m.triangle_slack(face, diameter))
    }
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        each!(self, m => m.face_gram(face))
    }
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        each!(self, m => m.wire_cost(a, b, length))
    }
    fn name(&self) -> &str {
        each!(self, m => m.name())
    }
}
