//! Point-to-point routes ([`Solver::shortest_path`]): a run that stops once the target
//! is final, then its path; from one source, a search from both ends at once, on two
//! threads, until the two sides meet. Above the engines (it runs them) and the traces
//! (it reads and joins their parents).

use crate::field::{Goal, Stats};
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::options::{Method, Sources, Stop};
use crate::propagate::meet::Meeting;
use crate::propagate::solver::{Setup, Workspace};
use crate::surface::{Source, SurfacePoint};
use crate::trace::{self, GeodesicPath};
use crate::{Error, PointRole, Solver};
use geotracks_metrics::Metric;

impl<M: Metric, T: Topology> Solver<M, T> {
    /// The straightened path from `target` to the nearest of `sources`, with the run's
    /// counters, in one call: a run that stops once the target's value is final, then
    /// [`Field::path`](crate::Field::path).
    ///
    /// The stop given with the sources ([`Sources::until`]) applies: its maximum
    /// distance (a target farther is [`Error::Unreachable`]) and its search strategy
    /// ([`Stop::goal_directed`], [`Stop::both_ends`]); its targets are replaced by
    /// `target`. From one source, with [`Stop::both_ends`] (the default), a
    /// Steiner-graph engine and two threads or more in rayon's pool, the search runs
    /// from both ends at once (`Stats::both_ends`; a directed metric's backward side on
    /// a reversed-metric solver built for the query): the path's traced cost is the
    /// Steiner graph's, as a one-ended run's, to rounding.
    ///
    /// The solver keeps the (up to two) workspaces a path query ran in for the next
    /// one, which then clears only the nodes the last one touched (and the tracks
    /// engine's track table, whole) instead of allocating buffers the size of the mesh
    /// (memory: two workspaces' buffers, held as long as the solver).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Method, Options, Solver, Sources, Stop};
    /// // A strip of 20 unit squares.
    /// let positions = (0..42).map(|i| [(i / 2) as f64, (i % 2) as f64, 0.0]).collect();
    /// let faces = (0..20u32)
    ///     .flat_map(|i| [[2 * i, 2 * i + 2, 2 * i + 3], [2 * i, 2 * i + 3, 2 * i + 1]])
    ///     .collect();
    /// let mesh = TriMesh::new(positions, faces)?;
    /// let solver = Solver::new(mesh, Euclidean, &Options::DEFAULT.with_method(Method::Tracks))?;
    /// let (both, _) = solver.shortest_path(0, 41)?;
    /// let one_end = Stop::NONE.with_both_ends(false);
    /// let (one, _) = solver.shortest_path(Sources::from(0).until(one_end), 41)?;
    /// assert!((both.traced_length - one.traced_length).abs() < 1e-9);
    /// assert!((both.length - 401f64.sqrt()).abs() < 1e-6); // straightened: the diagonal
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// As [`Solver::field`] and [`Field::path`](crate::Field::path) ([`Error::Unreachable`] when no source
    /// reaches the target).
    pub fn shortest_path<'a>(
        &self,
        sources: impl Into<Sources<'a>>,
        target: impl Into<SurfacePoint>,
    ) -> Result<(GeodesicPath, Stats), Error> {
        let (sources, target) = (sources.into(), target.into());
        let setup = self.setup();
        let stop = sources.stop();
        let both_ends = stop.both_ends
            && stop.goal_directed
            && sources.len() == 1
            && !matches!(setup.method, Method::Wave | Method::Exact)
            && rayon::current_num_threads() >= 2
            && setup.second_run_fits();
        if both_ends {
            let source = sources.to_vec()[0];
            let mut workspaces = [setup.path_workspace(), setup.path_workspace()];
            let ends = Ends {
                source,
                target,
                max_distance: stop.max_distance,
            };
            let found = if setup.metric.is_symmetric() {
                ends.search(setup, setup, &mut workspaces)
            } else {
                // The backward side travels against the metric: the reversed metric's
                // setup, on the same Steiner points and tables.
                setup.reversed().and_then(|back| {
                    let (path, mut stats) = ends.search(setup, &back, &mut workspaces)?;
                    // (Its setup is this query's.)
                    stats.setup_seconds += back.setup_seconds;
                    Ok((path, stats))
                })
            };
            for workspace in workspaces {
                setup.keep_path_workspace(workspace);
            }
            return found;
        }
        let mut workspace = setup.path_workspace();
        let stop = stop.clone().with_targets(vec![target]);
        let found = self
            .run(&mut workspace, sources.until(stop))
            .and_then(|run| Ok((run.path(target)?, run.stats().clone())));
        setup.keep_path_workspace(workspace);
        found
    }
}

/// The two ends of a search from both ends, and its limit.
struct Ends {
    source: Source,
    target: SurfacePoint,
    max_distance: f64,
}

impl Ends {
    /// The path from the target to the source no costlier than the maximum distance,
    /// searched from both ends at once on two threads (see `meet`): forward with
    /// `ahead`, backward with `back` (the same setup for a symmetric metric, else the
    /// reversed metric's, on the same Steiner points).
    fn search<M: Metric, B: Metric, T: Topology>(
        &self,
        ahead: &Setup<M, T>,
        back: &Setup<B, T>,
        [forward, backward]: &mut [Workspace; 2],
    ) -> Result<(GeodesicPath, Stats), Error> {
        let mesh = &*ahead.mesh;
        let target = self
            .target
            .validated(mesh)
            .map_err(|error| Error::InvalidPoint {
                which: PointRole::Target(0),
                error,
            })?;
        let mut sources = [self.source];
        ahead.validate_sources(&mut sources)?;
        let [source] = sources;
        let (from, to) = (source.point.position(mesh), target.position(mesh));
        let goals = (ahead.per_length > 0.0).then(|| {
            (
                Goal::between(from, to, ahead.per_length),
                Goal::between(to, from, ahead.per_length),
            )
        });
        // (What the two sides' estimates add up to; 0 without estimates.)
        let offset = goals
            .and_then(|(forward, _)| forward.away)
            .map_or(0.0, |(_, offset)| offset);
        let round = WORK_PER_SETTLE
            * (ahead.layout.node_count() / ROUNDS_PER_MESH).clamp(ROUND_LEAST, ROUND_MOST) as u64;
        let meeting = Meeting::new(offset, round);
        forward.sources.clear();
        forward.sources.push(source);
        backward.sources.clear();
        backward.sources.push(Source::new(target));
        let stop = Stop::NONE.with_max_distance(self.max_distance);
        let (forward_stats, backward_stats) = std::thread::scope(|scope| {
            let behind = scope.spawn(|| {
                back.execute(backward, &stop, Some((goals.map(|g| g.1), meeting.side(1))))
            });
            let ahead = ahead.execute(forward, &stop, Some((goals.map(|g| g.0), meeting.side(0))));
            let behind = behind
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (ahead, behind)
        });
        let (forward_stats, backward_stats) = (forward_stats?, backward_stats?);
        let stats = Stats {
            setup_seconds: forward_stats.setup_seconds,
            // (Each side's includes its waits for the other: the longer is the search's.)
            propagate_seconds: forward_stats
                .propagate_seconds
                .max(backward_stats.propagate_seconds),
            pushes: forward_stats.pushes + backward_stats.pushes,
            settles: forward_stats.settles + backward_stats.settles,
            distance_tests: forward_stats.distance_tests + backward_stats.distance_tests,
            stopped_early: true,
            both_ends: true,
            ..forward_stats
        };
        let path = self.join(ahead, back, [forward, backward], source, target)?;
        Ok((path, stats))
    }

    /// The path through where the two sides' values add up to least (see `meet`), or
    /// the straight segment between the ends where they share a face and it is
    /// shorter.
    fn join<M: Metric, B: Metric, T: Topology>(
        &self,
        ahead: &Setup<M, T>,
        back: &Setup<B, T>,
        [forward, backward]: [&Workspace; 2],
        source: Source,
        target: SurfacePoint,
    ) -> Result<GeodesicPath, Error> {
        let (mesh, metric) = (&*ahead.mesh, &ahead.metric);
        // In the order the forward side reached them, the first node of least sum.
        let (mut cost, mut meet) = (f64::INFINITY, NONE);
        for &node in &forward.touched {
            let sum =
                forward.node_distances()[node as usize] + backward.node_distances()[node as usize];
            if sum < cost {
                (cost, meet) = (sum, node);
            }
        }
        // Ends in one face: also the straight segment between them there, which is
        // no path through nodes (as a query at the target takes it from a source in
        // its face).
        let direct = target
            .faces(mesh)
            .iter()
            .filter(|&&f| source.point.bary_in(mesh, f).is_some())
            .map(|&f| {
                let cost = trace::segment_cost(mesh, metric, f, source.point, target);
                (source.start + cost, f)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((straight, f)) = direct.filter(|&(straight, _)| straight < cost) {
            if straight > self.max_distance {
                return Err(Error::Unreachable { point: target });
            }
            return Ok(trace::finish(
                mesh,
                metric,
                vec![target, source.point],
                vec![f],
                0,
            ));
        }
        if meet == NONE || cost > self.max_distance {
            return Err(Error::Unreachable { point: target });
        }
        // From the target to the meeting node along the backward side's parents, then
        // on to the source along the forward side's.
        let cycle = || Error::ParentCycle { point: target };
        let (mut points, mut faces, _) = back.chain(backward, meet).ok_or_else(cycle)?;
        let (ahead_points, ahead_faces, source) = ahead.chain(forward, meet).ok_or_else(cycle)?;
        points.reverse();
        faces.reverse();
        points.extend_from_slice(&ahead_points[1..]);
        faces.extend(ahead_faces);
        let mut path = trace::finish(mesh, metric, points, faces, source);
        trace::straighten(&mut path, mesh, metric);
        Ok(path)
    }
}

impl<M: Metric, T: Topology> Setup<M, T> {
    /// The points and faces from `node` back to its source along the parents of the
    /// run in `workspace`, and the source (`None` on a cycle).
    fn chain(
        &self,
        workspace: &Workspace,
        node: u32,
    ) -> Option<(Vec<SurfacePoint>, Vec<u32>, u32)> {
        let query = trace::Query::new(
            &*self.mesh,
            &self.metric,
            workspace.view(&self.layout),
            self.wave_turn(),
        );
        let mut points = vec![self.layout.surface_point(node)];
        let mut faces = Vec::new();
        let source = query.follow_parents(node, &mut points, &mut faces)?;
        Some((points, faces, source))
    }
}

/// About how many nodes each side of a search from both ends settles in a round (see
/// `meet`): the mesh's nodes over this, within [`ROUND_LEAST`] and [`ROUND_MOST`].
/// The same work on both sides ([`WORK_PER_SETTLE`]), so that neither waits long for
/// the other; enough that the rounds' rendezvous cost nothing next to their work, few
/// enough that a side settles little beyond where the search could have stopped.
const ROUNDS_PER_MESH: usize = 256;
/// See [`ROUNDS_PER_MESH`].
const ROUND_LEAST: usize = 32;
/// See [`ROUNDS_PER_MESH`]: on the 1000 × 1000 terrain bench's corner route (1.9 M
/// settles a side) 111 rounds. A side still waits for the other: with rounds of equal
/// settles, `perf record` on the CLI's `slope:4` corner route put 10 % of the samples
/// in `sched_yield`, the backward side waiting 0.2–0.3 s and the forward side
/// 0.01–0.06 s (scratch timers); counting pushes too, each waits 0.06–0.15 s, and the
/// propagation is about 5 % faster (1.27–1.39 s against 1.36–1.45 s, five runs of
/// `geotracks terrain terrain1000.asc --from 499.5,499.5 --to 9490.5,9290.7 --cost
/// slope:4 -v` alternating builds). Balancing by metric evaluations did no better than
/// by settles.
const ROUND_MOST: usize = 1 << 14;
/// A round's work is counted in settles plus pushes (see `meet`), a settle making about
/// two pushes: rounds of this many times the nodes above.
const WORK_PER_SETTLE: u64 = 3;
