//! What [`Solver::new`](super::Solver::new) works out once: the Steiner layout, the
//! engine's state ([`Engine`]: its tables, one variant per engine), and the checks of
//! the metric's costs on edges and wires.

use super::{Setup, Workspace};
use crate::field::SolverId;
use crate::flat::{self, EdgeGlue};
use crate::mesh::Topology;
use crate::mesh::{Csr, FaceFrame};
use crate::propagate::budget;
use crate::propagate::frontier::edge_steps;
use crate::propagate::tracks::TrackTables;
use crate::propagate::wave::WaveEdges;
use crate::propagate::windows::ExactTables;
use crate::propagate::{Method, Options};
use crate::steiner::{SteinerLayout, SteinerScheme};
use crate::Error;
use geotracks_metrics::{Metric, Reversed};
use rayon::prelude::*;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The engine that runs, with the state only it needs.
pub(in crate::propagate) enum Engine {
    /// Steiner nodes that carry their wavefront ([`Method::Wave`]).
    Wave {
        /// The per-face records, with the vertices' rows.
        tables: Arc<TrackTables>,
        /// Per edge block: whether its faces glue, and how far its frames may turn.
        edges: WaveEdges,
        /// How far below a node's value its offers can reach (see `Frontier::reach`).
        reach: f64,
        /// The bucket queue's width ([`bucket_width`]).
        bucket_width: f64,
    },
    /// Track-pruned propagation ([`Method::Tracks`]).
    Tracks {
        /// The per-face records and track instances (steps along edges included).
        tables: Arc<TrackTables>,
        /// The bucket queue's width ([`bucket_width`]).
        bucket_width: f64,
    },
    /// The complete Steiner graph on a binary heap ([`Method::Graph`]), and Dijkstra on
    /// edges ([`Method::Dijkstra`]: the same graph without Steiner points).
    Graph {
        /// The cost between consecutive nodes of each edge, for a metric flat on each
        /// face (else asked of the metric as nodes settle).
        edge_steps: Option<Vec<f64>>,
    },
    /// Windows carried face to face ([`Method::Exact`]).
    Exact {
        /// The flattened faces and the vertices where paths bend.
        tables: Arc<ExactTables>,
    },
}

/// What the Steiner layout was made from: the layout, the wavefront engine's flattened
/// edges and reach, and the budget checked.
struct Planned {
    layout: SteinerLayout,
    flat: Option<FlatEdges>,
    reach: f64,
    budgeted: u64,
}

impl<M: Metric, T: Topology> Setup<M, T> {
    /// How far apart, relative to their distance, two copies of one wave's source may
    /// lie and still be one (the wavefront engine's frames' rounding: `WaveEdges::turn`;
    /// 0 for the other engines). Queries that follow waves compare to it as the engine
    /// did.
    pub(crate) fn wave_turn(&self) -> f64 {
        match &self.engine {
            Engine::Wave { edges, .. } => edges.turn,
            _ => 0.0,
        }
    }

    /// Prepares `mesh` for runs under `metric` with `options` (see
    /// [`Solver::new`](super::Solver::new)).
    pub(super) fn new(mesh: Arc<T>, metric: M, options: &Options) -> Result<Self, Error> {
        let start = Instant::now();
        let shared = mesh;
        let mesh: &T = &shared;
        // The wavefront engine needs every face's flattening; other metrics run the
        // tracks engine.
        let flat_frames = (options.method == Method::Wave)
            .then(|| flat_frames(mesh, &metric))
            .flatten();
        // The exact engine refuses a metric it cannot be exact under (before the
        // layout: it has no Steiner points).
        let exact = match options.method {
            Method::Exact => Some(Arc::new(ExactTables::new(mesh, &metric)?)),
            _ => None,
        };
        let method = match (options.method, &flat_frames) {
            (Method::Wave, None) => Method::Tracks,
            (method, _) => method,
        };
        // The engine that runs picks its own k when none is asked for.
        let steiner = options.steiner_for(method);
        let options = &options.with_method(method);
        let planned = plan(mesh, options, steiner, flat_frames.as_deref())?;
        let layout = planned.layout;
        let (edge_steps, mut setup_tests) =
            match edge_steps(mesh, &metric, &layout, flat_frames.is_some()) {
                Some((steps, tests)) => (Some(steps), tests),
                None => (None, 0),
            };
        // The cost between consecutive nodes of each edge: the cached steps, or the
        // metric asked once per edge (in its first face).
        let steps = match &edge_steps {
            Some(steps) => std::borrow::Cow::Borrowed(steps.as_slice()),
            None => {
                setup_tests += mesh.edge_count() as u64;
                std::borrow::Cow::Owned(first_face_steps(mesh, &metric, &layout))
            }
        };
        let (wires, cost_total, per_length) = checked_costs(mesh, &metric, &layout, &steps)?;
        setup_tests += wires.len() as u64 / 2;
        // The per-face tables of the two engines that have them (the wavefront engine's
        // with the vertices' rows).
        let tables =
            || TrackTables::new(mesh, &layout, edge_steps.as_deref(), flat_frames.as_deref());
        let engine = match method {
            Method::Wave => Engine::Wave {
                tables: Arc::new(tables()?.with_vertex_rows(mesh, &layout)),
                edges: planned
                    .flat
                    .as_ref()
                    .map_or_else(WaveEdges::default, |flat| flat.wave_edges(&layout)),
                reach: planned.reach,
                bucket_width: bucket_width(&steps),
            },
            Method::Tracks => Engine::Tracks {
                tables: Arc::new(tables()?),
                bucket_width: bucket_width(&steps),
            },
            Method::Graph | Method::Dijkstra => Engine::Graph { edge_steps },
            Method::Exact => Engine::Exact {
                tables: exact.expect("made for the exact engine"),
            },
        };
        let extent = {
            let [lo, hi] = mesh.bounding_box().map(|p| p.to_array());
            glam::DVec3::from(hi).distance(glam::DVec3::from(lo))
        };
        Ok(Setup {
            id: SolverId::fresh(),
            mesh: shared,
            metric,
            method,
            k: match method {
                Method::Dijkstra | Method::Exact => 0.0,
                _ => steiner.k(),
            },
            layout: Arc::new(layout),
            engine,
            setup_tests,
            cost_total,
            per_length,
            extent,
            wires,
            setup_seconds: start.elapsed().as_secs_f64(),
            path_workspaces: Mutex::default(),
            memory_limit: options.memory_limit,
            work_limit: options.work_limit,
            budgeted: planned.budgeted,
        })
    }

    /// This solver under the metric reversed, on the same Steiner points and tables:
    /// the backward side of a path searched from both ends under a directed metric.
    /// Only what depends on the metric's direction is worked out again (the steps
    /// along edges, the wires, the checks); the tables do not depend on it for a
    /// directed metric, which has no cached steps (nor runs the wavefront engine: it is
    /// not flat on each face).
    pub(crate) fn reversed(&self) -> Result<Setup<Reversed<&M>, T>, Error> {
        let start = Instant::now();
        let (mesh, metric) = (&*self.mesh, Reversed(&self.metric));
        let steps = first_face_steps(mesh, &metric, &self.layout);
        let (wires, cost_total, per_length) = checked_costs(mesh, &metric, &self.layout, &steps)?;
        let engine = match &self.engine {
            Engine::Tracks { tables, .. } => Engine::Tracks {
                tables: Arc::clone(tables),
                bucket_width: bucket_width(&steps),
            },
            Engine::Graph { edge_steps: None } => Engine::Graph { edge_steps: None },
            Engine::Wave { .. }
            | Engine::Exact { .. }
            | Engine::Graph {
                edge_steps: Some(_),
            } => {
                unreachable!("a directed metric is not flat on each face")
            }
        };
        Ok(Setup {
            id: SolverId::fresh(),
            mesh: Arc::clone(&self.mesh),
            metric,
            method: self.method,
            k: self.k,
            layout: Arc::clone(&self.layout),
            engine,
            setup_tests: (mesh.edge_count() + wires.len() / 2) as u64,
            cost_total,
            per_length,
            extent: self.extent,
            wires,
            setup_seconds: start.elapsed().as_secs_f64(),
            path_workspaces: Mutex::default(),
            memory_limit: self.memory_limit,
            work_limit: self.work_limit,
            budgeted: self.budgeted,
        })
    }

    /// A workspace for a path query: one a path query ran in before, or a new one.
    pub(crate) fn path_workspace(&self) -> Workspace {
        let kept = self
            .path_workspaces
            .lock()
            .map(|mut kept| kept.pop())
            .unwrap_or_default();
        kept.unwrap_or_default()
    }

    /// Keeps `workspace` for the next path query (two at most).
    pub(crate) fn keep_path_workspace(&self, workspace: Workspace) {
        if let Ok(mut kept) = self.path_workspaces.lock() {
            if kept.len() < 2 {
                kept.push(workspace);
            }
        }
    }

    /// Whether a second run's buffers fit the memory budget (see
    /// [`Options::memory_limit`]): a search from both ends needs them.
    pub(crate) fn second_run_fits(&self) -> bool {
        let instances = match &self.engine {
            Engine::Tracks { tables, .. } => tables.instances,
            _ => 0,
        };
        let extra = budget::run_bytes(self.layout.node_count(), instances);
        budget::second_run_fits(extra, self.budgeted, self.memory_limit)
    }
}

/// The Steiner layout with `steiner` for `options` (whose method is the one that runs),
/// checked against the memory and work budgets before anything is allocated.
fn plan<T: Topology>(
    mesh: &T,
    options: &Options,
    steiner: SteinerScheme,
    flat_frames: Option<&[FaceFrame]>,
) -> Result<Planned, Error> {
    if matches!(options.method, Method::Dijkstra | Method::Exact) {
        return Ok(Planned {
            layout: SteinerLayout::vertices_only(mesh),
            flat: None,
            reach: 0.0,
            budgeted: 0,
        });
    }
    if !steiner.is_valid() {
        return Err(Error::InvalidK { k: steiner.k() });
    }
    if let Some(length) = options.mean_edge_length {
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::InvalidMeanEdgeLength { length });
        }
    }
    // The wavefront engine spaces points by the metric's lengths, puts at least one on
    // every edge (a wave crosses an edge only through its points), and keeps every
    // point the Steiner graph has at the same k (spaced by the lengths in space), so
    // that it holds at least the graph's paths: where faces do not glue (per-face
    // tensors) waves restart at every edge, and its values are then the graph's or
    // better.
    let in_space = edge_lengths(mesh, None);
    let flat = flat_frames.map(|frames| FlatEdges::new(mesh, frames, &in_space));
    let lengths = flat.as_ref().map_or(&in_space[..], |f| &f.lengths);
    let spacing = budget::Spacing {
        lengths,
        min: (options.method == Method::Wave) as u32,
        mean: options.mean_edge_length,
        containing: flat.as_ref().map(|f| (&in_space[..], &f.refracting[..])),
    };
    let limits = budget::Limits {
        memory: options.memory_limit.or_else(budget::available_memory),
        work: options.work_limit,
    };
    let budgeted = budget::check(mesh, steiner, spacing, options.method, limits)?;
    let counts = spacing.counts(steiner);
    let reach = match options.method {
        Method::Wave => lengths.iter().fold(0.0f64, |m, &l| m.max(l)),
        _ => 0.0,
    };
    let layout = SteinerLayout::with_counts(mesh, steiner, counts)?;
    Ok(Planned {
        layout,
        flat,
        reach,
        budgeted,
    })
}
/// Per vertex, its wires: the vertex at the other end and the wire's cost.
type Wires = Csr<(u32, f64)>;

/// The wires' costs, and the run-wide bounds checked against them and the steps
/// along edges: the total cost (`check_cost_range`) and the least cost per unit of
/// length (`check_per_length`).
fn checked_costs<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
) -> Result<(Wires, f64, f64), Error> {
    let wires = wire_costs(mesh, metric)?;
    let cost_total = check_cost_range(metric, layout, steps, &wires)?;
    let per_length = check_per_length(mesh, metric, layout, steps, &wires)?;
    Ok((wires, cost_total, per_length))
}

/// Every face's frame in the metric's flattening ([`flat::flat_frame`]), or `None`
/// unless the metric gives every face's.
fn flat_frames<M: Metric, T: Topology>(mesh: &T, metric: &M) -> Option<Vec<FaceFrame>> {
    (0..mesh.face_count() as u32)
        .map(|f| flat::flat_frame(metric, f, &mesh.frame(f)))
        .collect()
}

/// Each edge's length: in the flattened frames when given (the longest over the faces
/// around it: the same for edges whose faces glue isometrically), else in space.
fn edge_lengths<T: Topology>(mesh: &T, flat_frames: Option<&[FaceFrame]>) -> Vec<f64> {
    let Some(frames) = flat_frames else {
        return (0..mesh.edge_count() as u32)
            .into_par_iter()
            .map(|e| mesh.edge_length(e))
            .collect();
    };
    let mut lengths = vec![0.0f64; mesh.edge_count()];
    for (f, frame) in frames.iter().enumerate() {
        let c = frame.corners();
        for (s, e) in mesh.face_edges(f as u32).into_iter().enumerate() {
            let (a, b) = (c[s], c[(s + 1) % 3]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            lengths[e as usize] = lengths[e as usize].max(l);
        }
    }
    lengths
}

/// The edges' lengths in the faces' flattenings (the wavefront engine's), which edges
/// refract, and how far their frames may turn.
struct FlatEdges {
    /// Per edge, the longest of its lengths in the faces around it; a length that
    /// agrees with the edge's length in space to rounding (`1e-12` relative) is taken
    /// as that one: under a metric that is Euclidean on a part of the mesh, the points
    /// there are then exactly the Steiner graph's (a length a unit in the last place
    /// apart could round the count the other way).
    lengths: Vec<f64>,
    /// Per edge, whether its faces do not glue ([`EdgeGlue::glues`]): waves do not
    /// cross it.
    refracting: Vec<bool>,
    /// The most any edge's direction turns from one face's frame to another's
    /// ([`EdgeGlue::turn`]).
    turn: f64,
}

impl FlatEdges {
    fn new<T: Topology>(mesh: &T, frames: &[FaceFrame], in_space: &[f64]) -> FlatEdges {
        let glue = EdgeGlue::of_edges(mesh, frames);
        let lengths = glue
            .iter()
            .zip(in_space)
            .map(|(g, &e)| {
                if g.shortest > g.longest || (g.longest - e).abs() <= 1e-12 * e {
                    e
                } else {
                    g.longest
                }
            })
            .collect();
        FlatEdges {
            lengths,
            refracting: glue.iter().map(|g| !g.glues()).collect(),
            turn: glue.iter().fold(0.0f64, |m, g| m.max(g.turn())),
        }
    }

    /// Per edge block of `layout`, whether waves cross it (its faces glue), and the
    /// most any edge's frames turn ([`EdgeGlue::turn`]).
    fn wave_edges(&self, layout: &SteinerLayout) -> WaveEdges {
        let mut isometric = vec![true; self.refracting.len()];
        for (e, &r) in self.refracting.iter().enumerate() {
            isometric[layout.block_of_edge(e as u32) as usize] = !r;
        }
        WaveEdges {
            isometric,
            turn: self.turn,
        }
    }
}

/// The cost between consecutive nodes of each edge in its first face (for a directed
/// metric, in the dearer direction: these bound what a path along edges costs), on all
/// cores.
fn first_face_steps<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    layout: &SteinerLayout,
) -> Vec<f64> {
    let directed = !metric.is_symmetric();
    (0..mesh.edge_count() as u32)
        .into_par_iter()
        .map(|e| {
            let f = mesh.edge_faces(e)[0];
            let [a, b] = mesh
                .edge_vertices(e)
                .map(|v| layout.point_in_face(mesh, v, f));
            let mut whole = metric.cost(f, &a, &b);
            if directed {
                whole = whole.max(metric.cost(f, &b, &a));
            }
            whole / (layout.count(e) + 1) as f64
        })
        .collect()
}

/// Refuses a metric whose costs leave the f64 range on this mesh: every distance a run
/// can give is at most the sum of the edges' finite costs (a path along edges), so
/// that sum must be finite. (`+inf` edges are walls, allowed.) Returns the sum.
fn check_cost_range<M: Metric>(
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
    wires: &Csr<(u32, f64)>,
) -> Result<f64, Error> {
    let edges: f64 = steps
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_finite())
        .map(|(e, s)| s * (layout.count(e as u32) + 1) as f64)
        .sum();
    // Each wire is listed from both ends, each way's cost: both count, a bound on its
    // dearer way (which a directed metric may charge).
    let wires: f64 = (0..wires.rows() as u32)
        .flat_map(|v| wires.row(v).iter())
        .map(|&(_, c)| c)
        .filter(|c| c.is_finite())
        .sum();
    let total = edges + wires;
    if total.is_finite() {
        return Ok(total);
    }
    Err(Error::CostOverflow {
        metric: metric.name().to_string(),
    })
}

/// The metric's [`min_cost_per_length`](Metric::min_cost_per_length), checked against
/// every edge as the solver charges a step along it (`steps`: the cheapest face for a
/// norm, else the first face, the dearer way for a directed metric) and every wire
/// both ways, and shaded by 1e-9 of itself so that rounding never makes an estimate
/// exceed what is left. 0 when the metric gives no positive finite bound.
///
/// An edge's cost and its length in space are each computed with a rounding error
/// relative to the coordinates around it, not to the edge: a short edge of a face with
/// a far vertex (multi-scale meshes) can cost a part in 10⁶ less than its length by
/// rounding alone. Such a shortfall, within [`rounding_allowance`], is no broken
/// bound: the bound returned is lowered to the cheapest cost per unit found, so that
/// estimates stay below every charge.
///
/// # Errors
/// [`Error::CostBelowBound`], [`Error::WireBelowBound`].
fn check_per_length<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    layout: &SteinerLayout,
    steps: &[f64],
    wires: &Csr<(u32, f64)>,
) -> Result<f64, Error> {
    let per_length = metric.min_cost_per_length();
    if !(per_length > 0.0 && per_length.is_finite()) {
        return Ok(0.0);
    }
    let tolerance = 1.0 - 1e-9;
    let mut bound = per_length * tolerance;
    // Each edge's cost and length: the first edge below the bound by more than
    // rounding, on all cores, and the cheapest cost per unit among the others.
    let edges = (0..steps.len() as u32).into_par_iter().map(|e| {
        let length = mesh.edge_length(e);
        let cost = steps[e as usize] * (layout.count(e) + 1) as f64;
        // The allowance is only worked out for an edge below the bound.
        let short = |allowance: f64| cost < per_length * (length - allowance) * tolerance;
        if short(0.0)
            && short(rounding_allowance(
                mesh,
                &mesh.edge_faces(e),
                mesh.edge_vertices(e),
            ))
        {
            Err((e, length, cost))
        } else {
            Ok(if length > 0.0 {
                cost / length
            } else {
                f64::INFINITY
            })
        }
    });
    match edges.try_reduce(|| f64::INFINITY, |a, b| Ok(a.min(b))) {
        Ok(cheapest) => bound = bound.min(cheapest),
        Err((e, length, cost)) => {
            return Err(Error::CostBelowBound {
                metric: metric.name().to_string(),
                per_length,
                edge: e,
                length,
                cost,
                per_unit: cost / length,
            })
        }
    }
    for a in 0..wires.rows() as u32 {
        for &(b, cost) in wires.row(a) {
            let length = mesh.position(a).distance(mesh.position(b));
            let short = |allowance: f64| cost < per_length * (length - allowance) * tolerance;
            if short(0.0) && short(rounding_allowance(mesh, &[], [a, b])) {
                return Err(Error::WireBelowBound {
                    metric: metric.name().to_string(),
                    per_length,
                    wire: [a, b],
                    length,
                    cost,
                });
            }
            if length > 0.0 {
                bound = bound.min(cost / length);
            }
        }
    }
    Ok(bound)
}

/// How much shorter than its length an edge (or wire) between `ends` may come out by
/// rounding alone where it is measured in the faces `faces`: 1e-13 of the largest
/// coordinate or edge there (a few hundred units in the last place of the numbers the
/// length is computed from; measured: 1.1e-10 on a face with a vertex 6e5 away).
fn rounding_allowance<T: Topology>(mesh: &T, faces: &[u32], ends: [u32; 2]) -> f64 {
    let corners = faces
        .iter()
        .flat_map(|&f| mesh.face_vertices(f))
        .chain(ends);
    let mut scale = 0.0f64;
    let (lo, hi) = corners.fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), v| {
            let p = mesh.position(v);
            scale = scale.max(p.abs().max_element());
            (lo.min(p), hi.max(p))
        },
    );
    1e-13 * scale.max((hi - lo).max_element())
}

/// The metric's cost of every wire of `mesh`, listed from both ends.
///
/// # Errors
/// [`Error::InvalidWireCost`] for a NaN or negative cost.
fn wire_costs<M: Metric, T: Topology>(mesh: &T, metric: &M) -> Result<Csr<(u32, f64)>, Error> {
    let directed = !metric.is_symmetric();
    let mut costs = Vec::new();
    for [a, b] in mesh.wires() {
        let length = mesh.position(a).distance(mesh.position(b));
        let check = |[a, b]: [u32; 2]| {
            let cost = metric.wire_cost(a, b, length);
            if cost.is_nan() || cost < 0.0 {
                return Err(Error::InvalidWireCost {
                    metric: metric.name().to_string(),
                    wire: [a, b],
                    value: cost,
                });
            }
            Ok(cost)
        };
        let forward = check([a, b])?;
        // From b to a: the same, unless the metric is directed.
        let backward = if directed { check([b, a])? } else { forward };
        costs.push(([a, b], forward, backward));
    }
    Ok(Csr::from_pairs(
        mesh.vertex_count(),
        costs
            .iter()
            .flat_map(|&([a, b], forward, backward)| [(a, (b, forward)), (b, (a, backward))]),
    ))
}

/// The bucket queue's width: a low quantile of the cost between consecutive nodes on an
/// edge. Nodes in one bucket are settled in no particular order, so a bucket much wider
/// than the local spacing of nodes makes many nodes settle early and propagate again;
/// the low quantile keeps buckets narrow where costs are low (low density, short edges).
/// (The queue bounds the work whatever the width; the width only sets the speed.)
fn bucket_width(steps: &[f64]) -> f64 {
    let mut steps: Vec<f64> = steps
        .iter()
        .copied()
        .filter(|s| s.is_finite() && *s > 0.0)
        .collect();
    if steps.is_empty() {
        return 1.0;
    }
    let at = steps.len() / 10;
    let (_, width, _) = steps.select_nth_unstable_by(at, f64::total_cmp);
    *width
}
