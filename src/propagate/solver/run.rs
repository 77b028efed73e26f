//! One run, whichever the engine: the sources and targets checked, the seeds, the
//! engine's settle loop on its queue, then the roots paths and labels end at.

use super::setup::Engine;
use super::{Setup, Workspace};
use crate::field::{Goal, Horizon, Root, Stats, Wave};
use crate::mesh::Topology;
use crate::mesh::{bounding_box, NONE};
use crate::options::Sources;
use crate::propagate::frontier::{Frontier, Outcome, Seed};
use crate::propagate::meet::Side;
use crate::propagate::windows::{Bounds, Counts, ExactRun, ExactTables, BYTES_PER_WINDOW};
use crate::propagate::{budget, graph, tracks, wave, Method, Stop};
use crate::surface::{PointError, Source, SurfacePoint};
use crate::{Error, PointRole, ValueRole};
use geotracks_metrics::Metric;
use std::time::Instant;

impl<M: Metric, T: Topology> Setup<M, T> {
    /// Runs from `sources` into `workspace` (see [`Solver::run`](super::Solver::run)).
    pub(crate) fn run(
        &self,
        workspace: &mut Workspace,
        sources: &Sources<'_>,
    ) -> Result<Stats, Error> {
        workspace.sources.clear();
        sources.append_to(&mut workspace.sources);
        self.execute(workspace, sources.stop(), None)
    }

    /// Runs from `workspace.sources` as `stop` allows, leaving the run's field (and its
    /// stats) in the workspace; with `both`, as one side of a search from both ends
    /// (its goal replaces the targets', and the meeting ends the run).
    pub(crate) fn execute(
        &self,
        workspace: &mut Workspace,
        stop: &Stop,
        both: Option<(Option<Goal>, Side<'_>)>,
    ) -> Result<Stats, Error> {
        let start = Instant::now();
        workspace.stats = None;
        if workspace.sources.is_empty() {
            return Err(Error::NoSource);
        }
        self.validate_sources(&mut workspace.sources)?;
        let lowest_start = workspace
            .sources
            .iter()
            .map(|s| s.start)
            .fold(f64::INFINITY, f64::min);
        stop.check_from(lowest_start)?;
        self.collect_targets(stop, &mut workspace.targets)?;
        let (goal, meet) = match both {
            Some((goal, side)) => (goal, Some(side)),
            None => (self.goal(&workspace.targets, stop), None),
        };
        if goal.is_some() {
            // Written when a node is first reached, before it is read: never cleared.
            workspace.estimate.resize(self.layout.node_count(), 0.0);
        }
        let (instances, waves) = match &self.engine {
            // Tracks are the tracks engine's alone, waves the wavefront engine's.
            Engine::Tracks { tables, .. } => (tables.instances, 0),
            Engine::Wave { .. } => (0, self.layout.steiner_count()),
            Engine::Graph { .. } | Engine::Exact { .. } => (0, 0),
        };
        let exact = matches!(self.engine, Engine::Exact { .. });
        workspace.reset(
            self.mesh.vertex_count(),
            self.layout.node_count(),
            instances,
            waves,
            exact,
        );
        // Only a run that may stop early can reach little (see `Frontier::records`).
        // (A side of a search from both ends stops early too, and the touched nodes
        // are where the two sides' values are compared.)
        workspace.recorded =
            stop.max_distance < f64::INFINITY || !workspace.targets.is_empty() || meet.is_some();
        let seed_tests = if exact {
            // (The exact engine starts its windows from the sources themselves.)
            workspace.seeds.clear();
            0
        } else {
            self.seed(workspace)?
        };
        let reset_seconds = start.elapsed().as_secs_f64();
        let propagate_start = Instant::now();
        let outcome = match &self.engine {
            Engine::Exact { tables } => self.propagate_exact(workspace, stop, tables)?,
            _ => self.propagate(workspace, stop, goal, meet, seed_tests),
        };
        if let Some((face, value)) = outcome.bad_cost {
            return Err(Error::InvalidCost {
                metric: self.metric.name().to_string(),
                face,
                value,
            });
        }
        self.finish(workspace, stop, goal, outcome.level);
        let stats = Stats {
            vertices: self.mesh.vertex_count(),
            faces: self.mesh.face_count(),
            steiner_points: self.layout.steiner_count(),
            k: self.k,
            method: self.method,
            setup_seconds: self.setup_seconds + reset_seconds,
            propagate_seconds: propagate_start.elapsed().as_secs_f64(),
            pushes: outcome.pushes,
            settles: outcome.settles,
            distance_tests: outcome.tests,
            setup_distance_tests: self.setup_tests,
            stopped_early: outcome.stopped_early,
            // (The exact engine's pushes are the windows it made, its settles those
            // it carried.)
            windows_created: if exact { outcome.pushes } else { 0 },
            windows_kept: if exact { outcome.settles } else { 0 },
            both_ends: false,
        };
        workspace.stats = Some(stats.clone());
        Ok(stats)
    }

    /// The nodes whose values must be final for `stop`'s targets to be: the target
    /// vertices themselves for a Steiner-graph engine, else the nodes of the faces a
    /// query at each target reads. Sorted, each once.
    fn collect_targets(&self, stop: &Stop, targets: &mut Vec<u32>) -> Result<(), Error> {
        let (mesh, layout) = (&*self.mesh, &*self.layout);
        targets.clear();
        for (i, target) in stop.targets.iter().enumerate() {
            let point = target
                .validated(mesh)
                .map_err(|error| Error::InvalidPoint {
                    which: PointRole::Target(i),
                    error,
                })?;
            match (point, self.method) {
                (
                    SurfacePoint::Vertex(v),
                    Method::Tracks | Method::Graph | Method::Dijkstra | Method::Exact,
                ) => targets.push(v),
                (_, Method::Wave) => {
                    // A query on a wave field reads the point's faces and those across
                    // their edges (see `trace::face_field`): all their nodes must be
                    // final for its value to be the full run's.
                    for &f in point.faces(mesh).iter() {
                        for e in mesh.face_edges(f) {
                            for &g in mesh.edge_faces(e).iter() {
                                targets.extend(layout.face_nodes(mesh, g).map(|(node, _)| node));
                            }
                        }
                    }
                }
                _ => {
                    for &f in point.faces(mesh).iter() {
                        targets.extend(layout.face_nodes(mesh, f).map(|(node, _)| node));
                    }
                }
            }
        }
        targets.sort_unstable();
        targets.dedup();
        Ok(())
    }

    /// The engine's settle loop over the workspace's (reset, seeded) buffers.
    fn propagate(
        &self,
        workspace: &mut Workspace,
        stop: &Stop,
        goal: Option<Goal>,
        meet: Option<Side<'_>>,
        seed_tests: u64,
    ) -> Outcome {
        let Workspace {
            distance,
            parent,
            parent_face,
            tracks,
            waves,
            estimate,
            touched,
            recorded,
            heap,
            buckets,
            seeds,
            targets,
            sources,
            ..
        } = workspace;
        let search = Frontier {
            mesh: &*self.mesh,
            metric: &self.metric,
            layout: &self.layout,
            edge_steps: match &self.engine {
                Engine::Graph { edge_steps } => edge_steps.as_deref(),
                // (The tracks engine keeps its steps in its edge records.)
                _ => None,
            },
            wires: &self.wires,
            distance,
            parent,
            parent_face,
            touched,
            records: *recorded,
            queue: (),
            max_distance: stop.max_distance,
            goal,
            estimate,
            reach: match &self.engine {
                Engine::Wave { reach, .. } => *reach,
                _ => 0.0,
            },
            targets,
            target_cursor: 0,
            meet,
            pushes: 0,
            settles: 0,
            tests: seed_tests,
            bad_cost: None,
        };
        let nodes = self.layout.node_count();
        match &self.engine {
            Engine::Wave {
                tables,
                edges,
                bucket_width,
                ..
            } => {
                buckets.reset(nodes, *bucket_width);
                search.run(buckets, seeds, |s| {
                    wave::propagate(s, tables, edges, waves, seeds, sources)
                })
            }
            Engine::Tracks {
                tables,
                bucket_width,
            } => {
                buckets.reset(nodes, *bucket_width);
                search.run(buckets, seeds, |s| {
                    tracks::propagate(s, tables, tracks, seeds)
                })
            }
            Engine::Graph { .. } => {
                heap.reset();
                search.run(heap, seeds, graph::propagate)
            }
            Engine::Exact { .. } => unreachable!("the exact engine runs in propagate_exact"),
        }
    }

    /// The exact engine's run over the workspace's (reset) buffers.
    fn propagate_exact(
        &self,
        workspace: &mut Workspace,
        stop: &Stop,
        tables: &ExactTables,
    ) -> Result<Outcome, Error> {
        let point_targets = stop
            .targets
            .iter()
            .any(|t| !matches!(t, SurfacePoint::Vertex(_)));
        let Workspace {
            distance,
            touched,
            recorded,
            targets,
            sources,
            exact,
            exact_buffers,
            values_only,
            ..
        } = workspace;
        let mut run = ExactRun {
            mesh: &*self.mesh,
            tables,
            wires: &self.wires,
            distance,
            field: exact,
            buffers: exact_buffers,
            touched,
            records: *recorded,
            keeps_windows: !*values_only,
            bounds: Bounds {
                max_distance: stop.max_distance,
                targets,
                point_targets,
                max_windows: self.window_budget(),
                max_made: self.work_limit.unwrap_or(u64::MAX),
            },
            counts: Counts::default(),
        };
        let counts = run.run(sources)?;
        Ok(Outcome {
            pushes: counts.created,
            settles: counts.carried,
            tests: counts.crossings,
            bad_cost: None,
            stopped_early: counts.stopped_early,
            level: counts.level,
        })
    }

    /// The most windows one exact run may hold: what the memory limit (or, without
    /// one, the memory available now) leaves beside the solver.
    fn window_budget(&self) -> usize {
        let memory = self
            .memory_limit
            .map(|limit| limit.saturating_sub(self.budgeted))
            .or_else(budget::available_memory)
            .unwrap_or(u64::MAX);
        let by_memory = memory / BYTES_PER_WINDOW as u64;
        // Ids keep their top bit free (the heap marks vertex events with it).
        by_memory.min((1 << 31) - 1) as usize
    }

    /// After the settle loop: the roots (per node a source reached directly, the seed
    /// that gave its start value), the horizon, and the waves a stop left behind.
    fn finish(&self, workspace: &mut Workspace, stop: &Stop, goal: Option<Goal>, level: f64) {
        let Workspace {
            seeds,
            roots,
            horizon,
            touched,
            distance,
            waves,
            ..
        } = workspace;
        // Keep, per node, the seed that gave it its start value (the first of the
        // least ones, as relaxation took them): paths and labels end there.
        // (Seeds were made in source order, so among equal values the lowest source
        // index came first.)
        seeds.sort_unstable_by(|a, b| {
            a.node
                .cmp(&b.node)
                .then(a.value.total_cmp(&b.value))
                .then(a.source.cmp(&b.source))
        });
        seeds.dedup_by_key(|s| s.node);
        roots.clear();
        roots.extend(seeds.iter().map(|s| Root {
            node: s.node,
            source: s.source,
        }));
        *horizon = Horizon {
            max_distance: stop.max_distance,
            level,
            goal,
        };
        if self.method == Method::Wave && horizon.is_bounded() {
            // The waves of nodes the stop left unreached are not the run's (and only
            // touched nodes have any).
            let vertex_count = self.layout.vertex_count() as usize;
            for &node in touched.iter() {
                let node = node as usize;
                if node >= vertex_count && distance[node].is_infinite() {
                    waves[node - vertex_count] = Wave::NONE;
                }
            }
        }
    }

    /// The estimate a run stopping at `targets` (nodes) orders nodes by: the metric's
    /// least cost per unit length times the distance to the box around them; `None`
    /// for a run without targets, a metric that gives no bound, a stop that asks for
    /// no goal direction, targets spread over more than half the mesh's extent, or the
    /// wavefront engine.
    ///
    /// Why not the wavefront engine: its values depend on the order waves arrive in.
    /// A node that improves after it offered keeps its new wave only, and a value it
    /// gave through its old wave can no longer be traced back. Settled by value, such
    /// improvements stay within a bucket; settled by value plus estimate, nodes behind
    /// the front (nearer the sources, farther from the goal) settle after nodes beside
    /// it, and on Spot at k = 2 the traced path of 38 routes in 60 came out longer than
    /// the value at its end (up to 9 %; straightened, within 1e-4 of the plain run's).
    fn goal(&self, targets: &[u32], stop: &Stop) -> Option<Goal> {
        let graph_engine = !matches!(self.engine, Engine::Wave { .. });
        if targets.is_empty() || !stop.goal_directed || self.per_length <= 0.0 || !graph_engine {
            return None;
        }
        let positions = targets
            .iter()
            .map(|&t| self.layout.position(&*self.mesh, t));
        let [lo, hi] = bounding_box(positions.map(|p| p.to_array())).map(glam::DVec3::from);
        // Targets spread over much of the mesh leave the estimate zero nearly
        // everywhere: it would cost without saving (the guide's Paths page: `goal_bench`).
        if (hi - lo).length() > 0.5 * self.extent {
            return None;
        }
        Some(Goal::toward(lo, hi, self.per_length))
    }

    /// Checks the sources against the mesh and puts their points in canonical form.
    pub(crate) fn validate_sources(&self, sources: &mut [Source]) -> Result<(), Error> {
        for (i, source) in sources.iter_mut().enumerate() {
            source.point = source
                .point
                .validated(&*self.mesh)
                .map_err(|error| match error {
                    PointError::NoSuchVertex { vertex, count } => Error::SourceOutOfRange {
                        vertex: vertex as u64,
                        vertex_count: count,
                    },
                    error => Error::InvalidPoint {
                        which: PointRole::Source(i),
                        error,
                    },
                })?;
            if !source.start.is_finite() {
                return Err(Error::InvalidValue {
                    which: ValueRole::Start { source: i },
                    value: source.start,
                });
            }
            // Values only grow from a start, by at most the mesh's total cost: a start
            // so large that they could overflow would leave nodes silently unreached.
            if !(source.start + self.cost_total).is_finite() {
                return Err(Error::StartTooLarge {
                    index: i,
                    start: source.start,
                    cost_total: self.cost_total,
                });
            }
        }
        Ok(())
    }

    /// Fills `workspace.seeds` from its (valid) sources; returns the metric evaluations.
    fn seed(&self, workspace: &mut Workspace) -> Result<u64, Error> {
        let (mesh, layout) = (&*self.mesh, &*self.layout);
        let mut tests = 0;
        workspace.seeds.clear();
        for (i, source) in workspace.sources.iter().enumerate() {
            let source_index = i as u32;
            if let SurfacePoint::Vertex(v) = source.point {
                workspace.seeds.push(Seed {
                    node: v,
                    face: NONE,
                    value: source.start,
                    source: source_index,
                });
                continue;
            }
            for &f in source.point.faces(mesh).iter() {
                let Some(x) = source.point.in_face(mesh, f) else {
                    continue;
                };
                for (node, p) in layout.face_nodes(mesh, f) {
                    tests += 1;
                    let cost = self.metric.cost(f, &x, &p);
                    if cost.is_nan() || cost < 0.0 {
                        return Err(Error::InvalidCost {
                            metric: self.metric.name().to_string(),
                            face: f,
                            value: cost,
                        });
                    }
                    workspace.seeds.push(Seed {
                        node,
                        face: f,
                        value: source.start + cost,
                        source: source_index,
                    });
                }
            }
        }
        Ok(tests)
    }
}
