//! What a run will need, checked before anything big is allocated: the points one
//! edge may carry, 32-bit node ids, memory, and the work a run would do. A k that
//! breaks a limit is refused with the numbers and the largest k that would fit, instead
//! of failing late (or being killed) after gigabytes were allocated, or running for
//! hours.
//!
//! # The work estimate
//! Every Steiner engine tests distances between the nodes of each face (its vertices
//! and the points on its three edges): the complete Steiner graph all of their pairs,
//! the wavefront engine each wave against the nodes across its face, the tracks
//! engine the pairs its tracks leave. A face with `p` nodes costs about `c · p²`
//! distance tests, with `c` measured per engine on flat grids from k = 100 to 1000
//! (where the estimate is within 2× of the `distance_tests` a run reports): 0.6 for the
//! complete graph, 0.25 for the wavefront engine, 0.03 for the tracks engine. The sum
//! over the faces is checked against [`Options::work_limit`](crate::Options::work_limit)
//! before the layout is built.

use super::Method;
use crate::error::SizeLimit;
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::steiner::SteinerScheme;
use crate::Error;

/// The most Steiner points one edge may carry in the tracks engine (its face records
/// keep per-slot counts in 16 bits).
pub(super) const MAX_POINTS_PER_EDGE: u64 = u16::MAX as u64;

/// What decides the points per edge: the edges' lengths (in the metric the points are
/// spaced by) and the least number of points on any edge.
#[derive(Clone, Copy)]
pub(super) struct Spacing<'a> {
    pub lengths: &'a [f64],
    pub min: u32,
    /// The length the interval scheme's k is relative to (`None`: the lengths' mean).
    pub mean: Option<f64>,
    /// Lengths whose points the marked edges must also hold (`None`: no such
    /// constraint): the wavefront engine keeps the Steiner graph's points at the same k
    /// (spaced by the edges' lengths in space) on the edges where waves restart, and
    /// refines them by the metric's lengths.
    pub containing: Option<(&'a [f64], &'a [bool])>,
}

impl Spacing<'_> {
    /// The points per edge under `scheme`: spaced by `lengths`, at least `min`, and on
    /// the edges `containing` marks, the smallest count at least that dense whose points
    /// include the ones its lengths space (an evenly spaced edge of `c` points holds
    /// those of `g` when `c + 1` is a multiple of `g + 1`).
    pub fn counts(&self, scheme: SteinerScheme) -> Vec<u32> {
        let mut counts = scheme.counts_relative_to(self.lengths, self.min, self.mean);
        let Some((lengths, marked)) = self.containing else {
            return counts;
        };
        let base = scheme.counts_relative_to(lengths, 0, self.mean);
        for ((c, &g), _) in counts.iter_mut().zip(&base).zip(marked).filter(|(_, &m)| m) {
            let (n, g) = (*c as u64 + 1, g as u64 + 1);
            *c = (n.div_ceil(g) * g - 1).min(u32::MAX as u64) as u32;
        }
        counts
    }
}

/// The budgets a layout is checked against: bytes (`None`: no memory check) and
/// estimated distance tests (`None`: no work check).
#[derive(Clone, Copy)]
pub(super) struct Limits {
    pub memory: Option<u64>,
    pub work: Option<u64>,
}

/// Checks `scheme` on `mesh` for `method` against the limits.
pub(super) fn check<T: Topology>(
    mesh: &T,
    scheme: SteinerScheme,
    spacing: Spacing,
    method: Method,
    limits: Limits,
) -> Result<u64, Error> {
    let limit = match breaks(mesh, scheme, spacing, method, limits) {
        Ok(needed) => return Ok(needed),
        Err(limit) => limit,
    };
    // The limits grow with k: bisect for the largest k that keeps within them.
    let (mut lo, mut hi) = (0.0, scheme.k());
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if breaks(mesh, scheme.with_k(mid), spacing, method, limits).is_ok() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let largest_k = match scheme {
        SteinerScheme::Fixed { .. } => lo.floor(),
        // Three significant digits, rounded down so that it still fits.
        SteinerScheme::Interval { .. } if lo > 0.0 => {
            let unit = 10f64.powf(lo.log10().floor() - 2.0);
            (lo / unit).floor() * unit
        }
        SteinerScheme::Interval { .. } => 0.0,
    };
    Err(Error::KTooLarge {
        k: scheme.k(),
        limit,
        largest_k,
    })
}

/// The first limit `scheme` breaks, or the bytes it needs.
fn breaks<T: Topology>(
    mesh: &T,
    scheme: SteinerScheme,
    spacing: Spacing,
    method: Method,
    limits: Limits,
) -> Result<u64, SizeLimit> {
    if !scheme.is_valid() {
        // Below any point at all: nothing to lay out, nothing to break.
        return Ok(0);
    }
    let counts = spacing.counts(scheme);
    if matches!(method, Method::Tracks | Method::Wave) {
        let Some((edge, &points)) = counts.iter().enumerate().max_by_key(|(_, &c)| c) else {
            return Ok(0);
        };
        if points as u64 > MAX_POINTS_PER_EDGE {
            return Err(SizeLimit::PointsOnEdge {
                edge: edge as u32,
                points: points as u64,
                limit: MAX_POINTS_PER_EDGE,
            });
        }
    }
    let steiner: u64 = counts.iter().map(|&c| c as u64).sum();
    let nodes = mesh.vertex_count() as u64 + steiner;
    if nodes >= NONE as u64 {
        return Err(SizeLimit::Nodes { nodes });
    }
    let needed = bytes(mesh, &counts, steiner, nodes, method);
    if let Some(available) = limits.memory {
        if needed > available {
            return Err(SizeLimit::Memory { needed, available });
        }
    }
    if let Some(limit) = limits.work {
        let tests = distance_tests(mesh, &counts, method);
        if tests > limit as f64 {
            return Err(SizeLimit::Work { tests, limit });
        }
    }
    Ok(needed)
}

/// About how many distance tests one full run makes (see the module's docs): per face,
/// the engine's share of the pairs of its nodes.
pub(super) fn distance_tests<T: Topology>(mesh: &T, counts: &[u32], method: Method) -> f64 {
    let share = match method {
        Method::Graph => 0.6,
        Method::Wave => 0.25,
        Method::Tracks => 0.03,
        // Edges only: a few tests per edge, never a concern. (The exact engine's
        // windows are bounded while it runs, not estimated.)
        Method::Dijkstra | Method::Exact => return 2.0 * counts.len() as f64,
    };
    let pairs: f64 = (0..mesh.face_count() as u32)
        .map(|f| {
            let points: u64 = mesh
                .face_edges(f)
                .iter()
                .map(|&e| counts[e as usize] as u64)
                .sum();
            let nodes = (3 + points) as f64;
            nodes * nodes
        })
        .sum();
    share * pairs
}

/// The bytes one more run's buffers take (a workspace: per node its distance, parent,
/// parent face, queue flag and goal estimate, about two queue entries, and a track per
/// instance): what a path searched from both ends needs beyond a one-ended run.
pub(super) fn run_bytes(nodes: usize, instances: usize) -> u64 {
    (RUN_BYTES_PER_NODE + 8) * nodes as u64 + 8 * instances as u64
}

/// A run's bytes per node: distance, parent, parent face, queue flag, and about two
/// queue entries (a goal-directed run adds its estimate).
const RUN_BYTES_PER_NODE: u64 = 8 + 4 + 4 + 1 + 2 * 4;

/// Whether a second run's buffers (`run_bytes`) fit: within `limit` beside what the
/// solver and its first run were budgeted (`budgeted`), or without a limit within what
/// the system says is available now (or where it says nothing).
pub(super) fn second_run_fits(extra: u64, budgeted: u64, limit: Option<u64>) -> bool {
    match limit {
        Some(limit) => budgeted.saturating_add(extra) <= limit,
        None => available_memory().is_none_or(|available| extra <= available),
    }
}

/// The bytes a solver and one run take (the mesh itself excluded): per node its
/// distance, parent, parent face and queue flag, with about two queue entries; per
/// Steiner point its block; for the tracks engine a record per face and edge and a
/// track per (face, boundary node).
fn bytes<T: Topology>(mesh: &T, counts: &[u32], steiner: u64, nodes: u64, method: Method) -> u64 {
    let layout = 4 * steiner + 12 * counts.len() as u64;
    let engine = match method {
        Method::Tracks => {
            let instances: u64 = 3 * mesh.face_count() as u64
                + (0..counts.len() as u32)
                    .map(|e| counts[e as usize] as u64 * mesh.edge_faces(e).len() as u64)
                    .sum::<u64>();
            8 * instances + 64 * mesh.face_count() as u64 + 16 * counts.len() as u64
        }
        // A wave per Steiner point, and the face and edge records.
        Method::Wave => 40 * steiner + 64 * mesh.face_count() as u64 + 17 * counts.len() as u64,
        // The heap holds about two entries of 16 bytes per node.
        Method::Graph | Method::Dijkstra | Method::Exact => 2 * 16 * nodes,
    };
    RUN_BYTES_PER_NODE * nodes + layout + engine
}

/// Memory the system says is available (Linux: `MemAvailable`), if it says.
pub(super) fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}
