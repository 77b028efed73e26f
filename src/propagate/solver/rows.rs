//! Many runs on all cores: a row of distances per source (distance matrices) and local
//! rows (every vertex within a radius).

use super::{budget, Solver, Workspace};
use crate::field::Stats;
use crate::mesh::Topology;
use crate::options::{Sources, Stop};
use crate::surface::SurfacePoint;
use crate::Error;
use geotracks_metrics::Metric;
use rayon::prelude::*;
use std::sync::Mutex;

/// One source's row of a distance matrix ([`Solver::distance_rows`]).
#[derive(Clone, Debug)]
pub struct DistanceRow {
    /// The distance to each target, or to every vertex.
    pub distances: Vec<f64>,
    /// The run's counters (whether it stopped early, how much work it did).
    pub stats: Stats,
}

/// The values at the vertices of one run, without the field around them
/// ([`Solver::vertex_values`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct VertexValues {
    /// Per vertex, the distance from the nearest source (`inf` where unreached).
    pub distances: Vec<f64>,
    /// Per vertex, the index of its nearest source among the run's sources
    /// ([`NONE`](crate::mesh::NONE) where unreached), as [`Field::vertex_labels`].
    ///
    /// [`Field::vertex_labels`]: crate::Field::vertex_labels
    pub labels: Vec<u32>,
    /// The run's counters.
    pub stats: Stats,
}

impl VertexValues {
    /// How many vertices the run did not reach (`inf`), as
    /// [`Field::unreachable_vertices`](crate::Field::unreachable_vertices).
    pub fn unreachable_vertices(&self) -> usize {
        self.distances.iter().filter(|d| d.is_infinite()).count()
    }
}

impl<M: Metric, T: Topology> Solver<M, T> {
    /// The distance from `sources` at every vertex, and each vertex's nearest source:
    /// what [`Solver::field`] gives at the vertices, for a caller who needs nothing
    /// else. The engines give the same values either way; the exact engine
    /// ([`Method::Exact`](crate::Method::Exact)) then forgets each window once it is
    /// carried on, so the run holds only the wavefront's windows, where a field keeps
    /// every window to answer queries at points and trace paths (on a mesh of a
    /// million faces, a few hundred megabytes instead of several gigabytes).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Method, Options, Solver};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT.with_method(Method::Exact))?;
    /// let values = solver.vertex_values(0)?;
    /// assert_eq!(values.distances[..2], [0.0, 1.0]);
    /// assert!((values.distances[2] - 2f64.sqrt()).abs() < 1e-15);
    /// assert_eq!(values.labels, [0; 4]);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::field`].
    pub fn vertex_values<'a>(
        &self,
        sources: impl Into<Sources<'a>>,
    ) -> Result<VertexValues, Error> {
        let mut workspace = Workspace::values_only();
        self.setup().run(&mut workspace, &sources.into())?;
        Ok(crate::Field::new(self.clone(), &workspace).vertex_values())
    }

    /// One row of distances per source, computed on all cores (rayon; workspaces are
    /// pooled, at most one per worker thread, and reused across sources): row `i` holds
    /// the distance from `sources[i]` to each of `targets`, or to every vertex when
    /// `targets` is `None`. With targets, each row's run stops once its targets are
    /// final ([`Stop::with_targets`]), so near targets cost little.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
    /// let rows = solver.distance_rows(&[0, 2], Some(&[1, 3]))?;
    /// assert!((rows[0].distances[0] - 1.0).abs() < 1e-12);
    /// assert!((rows[1].distances[1] - 1.0).abs() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Complexity
    /// One run per source; with targets, each run settles only the nodes closer than
    /// its farthest target.
    ///
    /// # Errors
    /// As [`Solver::field`], plus [`Error::TargetOutOfRange`] for a target that is not
    /// a vertex and [`Error::OutputTooLarge`] when the rows (8 bytes a value) would not
    /// fit [`Options::memory_limit`](crate::Options::memory_limit), by default what the
    /// system reports available (both checked first, before any work).
    pub fn distance_rows(
        &self,
        sources: &[u32],
        targets: Option<&[u32]>,
    ) -> Result<Vec<DistanceRow>, Error> {
        let vertex_count = self.mesh().vertex_count();
        if let Some(&vertex) = targets
            .unwrap_or(&[])
            .iter()
            .find(|&&v| v as usize >= vertex_count)
        {
            return Err(Error::TargetOutOfRange {
                vertex: vertex as u64,
                vertex_count,
            });
        }
        // The rows are kept in memory: refuse before any run what cannot fit.
        let columns = targets.map_or(vertex_count, <[u32]>::len);
        self.check_rows_fit(sources.len(), columns, 8)?;
        let stop = match targets {
            Some(t) => {
                Stop::NONE.with_targets(t.iter().map(|&v| SurfacePoint::Vertex(v)).collect())
            }
            None => Stop::NONE,
        };
        // Workspaces are taken from and returned to a pool, so there are never more
        // than there are worker threads (rayon's map_init may create one per split).
        let pool = Mutex::new(Vec::<Workspace>::new());
        let take = || {
            pool.lock()
                .ok()
                .and_then(|mut p| p.pop())
                .unwrap_or_else(Workspace::values_only)
        };
        // (Runs on the setup, shared by reference: the metric need only be `Sync`.)
        let setup = self.setup();
        sources
            .par_iter()
            .map(|&source| {
                let mut ws = take();
                let row = setup
                    .run(&mut ws, &Sources::from(source).until(&stop))
                    .map(|stats| {
                        let d = ws.vertex_distances();
                        let distances = match targets {
                            Some(t) => t.iter().map(|&v| d[v as usize]).collect(),
                            None => d.to_vec(),
                        };
                        DistanceRow { distances, stats }
                    });
                if let Ok(mut p) = pool.lock() {
                    p.push(ws);
                }
                row
            })
            .collect()
    }

    /// Checks, before any run, that `rows` rows of `columns` values fit in memory at
    /// `bytes_per_value` bytes a value: within
    /// [`Options::memory_limit`](crate::Options::memory_limit), by default what the
    /// system reports available. [`Solver::distance_rows`] checks its rows at 8 bytes a
    /// value; a caller that copies them into another array (the Python package's
    /// matrix) checks at 16.
    ///
    /// # Errors
    /// [`Error::OutputTooLarge`], with the bytes needed and available.
    pub fn check_rows_fit(
        &self,
        rows: usize,
        columns: usize,
        bytes_per_value: u64,
    ) -> Result<(), Error> {
        let bytes = (rows as u64)
            .saturating_mul(columns as u64)
            .saturating_mul(bytes_per_value);
        match self.setup().memory_limit.or_else(budget::available_memory) {
            Some(available) if bytes > available => Err(Error::OutputTooLarge {
                rows,
                columns,
                bytes,
                available,
            }),
            _ => Ok(()),
        }
    }

    /// For each of `sources` (vertices), the vertices within `max_distance` of it and
    /// their distances, sorted by vertex: one run per source stopped at
    /// `max_distance`, on all cores (rayon), each costing what it reaches. The rows
    /// are kept in memory: their size is not known before the runs, so it is counted
    /// as they finish, and the call stops as soon as they would exceed
    /// [`Options::memory_limit`](crate::Options::memory_limit) (by default what the
    /// system reports available).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT)?;
    /// let rows = solver.local_distance_rows(&[0], 1.2)?;
    /// assert_eq!(rows[0].iter().map(|&(v, _)| v).collect::<Vec<_>>(), [0, 1, 3]);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::field`] (a negative or NaN `max_distance` is refused before any
    /// run), plus [`Error::LocalRowsTooLarge`] when the rows outgrow the memory.
    pub fn local_distance_rows(
        &self,
        sources: &[u32],
        max_distance: f64,
    ) -> Result<Vec<Vec<(u32, f64)>>, Error> {
        use std::sync::atomic::{AtomicU64, Ordering};
        let stop = Stop::NONE.with_max_distance(max_distance);
        stop.check()?;
        let available = self.setup().memory_limit.or_else(budget::available_memory);
        let pair = std::mem::size_of::<(u32, f64)>() as u64;
        let pairs = AtomicU64::new(0);
        let setup = self.setup();
        sources
            .par_iter()
            .map_init(Workspace::values_only, |workspace, &v| {
                setup.run(workspace, &Sources::from(v).until(&stop))?;
                // What the run reached, not a scan of the mesh: with a small radius
                // that is most of the saving.
                let mut row: Vec<(u32, f64)> = workspace.reached_vertices().collect();
                row.sort_unstable_by_key(|&(j, _)| j);
                let total = pairs.fetch_add(row.len() as u64, Ordering::Relaxed) + row.len() as u64;
                match available {
                    Some(available) if total.saturating_mul(pair) > available => {
                        Err(Error::LocalRowsTooLarge {
                            max_distance,
                            sources: sources.len(),
                            pairs: total,
                            available,
                        })
                    }
                    _ => Ok(row),
                }
            })
            .collect()
    }
}
