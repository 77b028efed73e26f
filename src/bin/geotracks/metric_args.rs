//! The options every propagating command shares: Steiner points, engine, and the metric
//! (Euclidean, or a density or tensor file), dispatched to code generic over `Metric`.

use crate::inputs::{read_density, read_tensor};
use crate::CliResult;
use geotracks::mesh::TriMesh;
use geotracks::{Euclidean, Method, Metric, Options};
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

/// Work to run with whichever metric the arguments select.
pub trait WithMetric {
    /// What the work returns.
    type Output;
    /// Runs the work with `metric`.
    fn run<M: Metric>(
        self,
        mesh: &TriMesh,
        metric: &M,
        options: &Options,
    ) -> CliResult<Self::Output>;
}

impl MetricArgs {
    /// Reads the metric's file (if any) and runs `work` with it.
    pub fn dispatch<W: WithMetric>(&self, mesh: &TriMesh, work: W) -> CliResult<W::Output> {
        let options = Options::DEFAULT.with_k(self.k).with_method(self.method);
        match (&self.density, &self.tensor) {
            (Some(path), _) => work.run(mesh, &read_density(path, mesh)?, &options),
            (None, Some(path)) => work.run(mesh, &read_tensor(path, mesh)?, &options),
            (None, None) => work.run(mesh, &Euclidean, &options),
        }
    }
}
