//! The geodesic tracks engine (paper §4): Steiner-point propagation whose broadcasts
//! are pruned along non-crossing tracks.
//!
//! # State
//! Each face's boundary is a cycle of positions: corner 0, the points of edge slot 0
//! (corner 0 → corner 1), corner 1, slot 1, corner 2, slot 2. An *instance* is a
//! (face, position) pair, stored face-major, and holds the best value that reached that
//! node *through that face* and the position of the node it came from (its parent in
//! the face: together they are the face's tracks). The read-only per-face and per-edge
//! records live in [`tables`].
//!
//! # Entering a face
//! When node `q` settles with value `d`, it enters every face around it except those
//! through which it already has `d` (a value that improved through `f` is never sent
//! back into `f`: the straight segment from its parent does better there). Its targets
//! in the face are the positions not on its own edge: one contiguous arc of the cycle.
//! `q` tests a first target found by binary search where the tracks of its neighbours
//! meet, then walks outward in both directions while it wins.
//!
//! # When a walk may stop (the crossing lemma, paper Theorem 1)
//! If `p` gave target `t` a value `val(t) ≤ d + |q t|`, then for every target `s` such
//! that the segment `q→s` crosses `p→t`, `val(s) ≤ d + |q s|`: with `x` the crossing,
//! `val(s) ≤ g(p) + |p s| ≤ g(p) + |p x| + |x s| ≤ d + |q x| + |x s|` (triangle
//! inequality twice, and the first step is the invariant that every target of an
//! entered node holds at most that node's offer). The chord `p t` cuts the cycle in
//! two arcs; the targets on the arc that does not hold `q` are exactly those `s`. So a
//! loss proves the rest of a walk only when that arc covers it; a corner-cutting track
//! (its parent on another target edge) proves only the targets it spans, and the walk
//! jumps over them or goes on, never stops there.
//!
//! The lemma needs the triangle inequality inside a face, so for metrics that are not
//! norms ([`Metric::is_face_norm`] false, e.g. `Density`) the pruning is a heuristic.

mod tables;

use super::frontier::{settle_all, Frontier, Queue, Seed, Settle};
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::steiner::SlotPoints;
use geotracks_metrics::{FacePoint, Metric};
use tables::EdgeRecord;

pub(super) use tables::{FaceRecord, TrackTables};

/// One instance's track: the best value that reached a boundary node through a face,
/// and the position (in that face) of the node it came from.
///
/// The value is an `f32` rounded *up* from the exact `f64` offer, so it is never below
/// the truth: a loss against it (`stored ≤ offer`) is a real loss, which keeps every
/// pruning proof valid, and a spurious win within one `f32` step only costs an extra
/// update. Node distances themselves stay exact `f64`. Eight bytes per instance instead
/// of twelve, in one array, so a face's tracks come in one or two cache lines.
#[derive(Clone, Copy, Debug)]
pub(super) struct Track {
    value: f32,
    from: u32,
}

impl Track {
    /// No value yet.
    pub const NONE: Track = Track {
        value: f32::INFINITY,
        from: NONE,
    };

    #[inline]
    fn value(self) -> f64 {
        self.value as f64
    }
}

/// `value` as an `f32` no smaller than it (start values may be negative).
#[inline]
fn round_up(value: f64) -> f32 {
    let v = value as f32;
    // The next float up is the next bit pattern for a value ≥ 0 and the previous one
    // below 0 (`next_up` spends a dozen instructions on NaN and infinity); added
    // without a branch, which would be a coin toss. Rounding to nearest never gives
    // −0 below a value, so −0 needs no care; `v` is never NaN (offers are compared
    // with `<` first, and a NaN cost stops the run).
    let below = ((v as f64) < value) as u32;
    let step = if v.is_sign_negative() {
        below.wrapping_neg()
    } else {
        below
    };
    f32::from_bits(v.to_bits().wrapping_add(step))
}

/// What a lost test proves about the other targets (indices along the target arc).
enum Shadow {
    /// Every target after the lost one.
    After,
    /// Every target before the lost one.
    Before,
    /// The targets strictly between the lost one and this index.
    Between(u32),
    /// Nothing.
    None,
}

/// The targets of one node entering one face: the arc of boundary positions not on the
/// node's own edges. For a corner, the opposite slot's points; for a Steiner point on
/// slot `s`, the points of slot `s + 1`, the opposite corner, then the points of slot
/// `s + 2`. Target `i` is the `i`-th position of the arc going forward around the cycle.
struct Arc {
    face: u32,
    /// Instance offset of the face.
    base: u32,
    /// Positions on the cycle.
    n: u32,
    /// First target position and number of targets.
    start: u32,
    m: u32,
    first: SlotPoints,
    /// The opposite corner (node and point) when the arc passes one.
    corner: Option<(u32, FacePoint)>,
    second: SlotPoints,
    /// The entering node: id, position, point and value.
    q: u32,
    q_pos: u32,
    pq: FacePoint,
    d: f64,
    /// Rank of `q`'s position in the complement of the arc (see `offset`).
    q_rank: u32,
    /// How much a loss must be by to prove anything: twice the metric's triangle slack
    /// in the face (the lemma uses the inequality twice); 0 for norms.
    margin: f64,
}

impl Arc {
    /// The arc of `q`, at position `q_pos` on the boundary of `face` and at point `pq`
    /// there. `side` is its corner when `corner` holds, else the slot it lies on.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn new(
        face: u32,
        r: &FaceRecord,
        side: usize,
        corner: bool,
        q: u32,
        q_pos: u32,
        pq: FacePoint,
        d: f64,
        slack: f64,
    ) -> Arc {
        let (s1, s2) = (NEXT[side], NEXT[NEXT[side]]);
        let first = r.slot(s1);
        let (corner, second) = if corner {
            (None, first.empty())
        } else {
            (Some((r.vertex[s2], r.corner_point(s2))), r.slot(s2))
        };
        let m = first.count + corner.is_some() as u32 + second.count;
        let mut arc = Arc {
            face,
            base: r.base,
            n: r.cycle_len(),
            start: r.corner(s1) + 1,
            m,
            first,
            corner,
            second,
            q,
            q_pos,
            pq,
            d,
            q_rank: 0,
            margin: 2.0 * slack,
        };
        // `q` lies outside the arc: its offset from the arc's start is at least `m`.
        arc.q_rank = arc.offset(q_pos) - m + 1;
        arc
    }

    /// Position of target `i`.
    #[inline]
    fn pos(&self, i: u32) -> u32 {
        let p = self.start + i;
        if p >= self.n {
            p - self.n
        } else {
            p
        }
    }

    /// Node id and point of target `i`.
    #[inline(always)]
    fn target(&self, i: u32) -> (u32, FacePoint) {
        if i < self.first.count {
            return self.first.at(i);
        }
        let i = i - self.first.count;
        match self.corner {
            Some(corner) if i == 0 => corner,
            Some(_) => self.second.at(i - 1),
            None => self.second.at(i),
        }
    }

    /// Offset of position `p` from the arc's start, going forward around the cycle.
    #[inline]
    fn offset(&self, p: u32) -> u32 {
        if p >= self.start {
            p - self.start
        } else {
            p + self.n - self.start
        }
    }

    /// What losing target `i` to parent position `p` proves (see the module docs).
    #[inline]
    fn shadow(&self, i: u32, p: u32) -> Shadow {
        if p == NONE {
            return Shadow::None;
        }
        let off = self.offset(p);
        if off < self.m {
            return if off == i {
                Shadow::None
            } else {
                Shadow::Between(off)
            };
        }
        // p is outside the arc, like q: going forward from the arc's end, meeting p
        // before q means the chord p–t separates q from every target after t.
        let rank = off - self.m + 1;
        match rank.cmp(&self.q_rank) {
            std::cmp::Ordering::Less => Shadow::After,
            std::cmp::Ordering::Greater => Shadow::Before,
            std::cmp::Ordering::Equal => Shadow::None,
        }
    }
}

/// Settles nodes until the run is over ([`settle_all`]). `tracks` holds one
/// [`Track`] per instance, reset by the caller; `seeds` are the sources' offers, already
/// given to their nodes.
pub(super) fn propagate<M: Metric, T: Topology, Q: Queue>(
    search: &mut Frontier<'_, M, T, Q>,
    tables: &TrackTables,
    tracks: &mut [Track],
    seeds: &[Seed],
) {
    // A seed through a face is that face's track at its node: the source is a parent
    // that no walk can prove anything with, and which beats whatever it beats.
    for seed in seeds {
        if seed.face != NONE && seed.value <= search.max_distance {
            let instance = tables.instance(seed.face, seed.node);
            let track = &mut tracks[instance as usize];
            if seed.value < track.value() {
                *track = Track {
                    value: round_up(seed.value),
                    from: NONE,
                };
            }
        }
    }
    let mut run = Tracks {
        search,
        tables,
        tracks,
    };
    settle_all(&mut run);
}

impl<M: Metric, T: Topology, Q: Queue> Settle for Tracks<'_, '_, M, T, Q> {
    #[inline(always)]
    fn next(&mut self) -> Option<(u32, f64)> {
        self.search.next()
    }
    #[inline(always)]
    fn vertex_count(&self) -> u32 {
        self.search.layout.vertex_count()
    }
    #[inline(always)]
    fn settle_vertex(&mut self, v: u32, d: f64) {
        Self::settle_vertex(self, v, d);
    }
    #[inline(always)]
    fn settle_steiner(&mut self, q: u32, d: f64) {
        Self::settle_steiner(self, q, d);
    }
}

struct Tracks<'r, 'a, M, T, Q> {
    search: &'r mut Frontier<'a, M, T, Q>,
    tables: &'r TrackTables,
    /// Per instance: best value through the face and where it came from.
    tracks: &'r mut [Track],
}

impl<M: Metric, T: Topology, Q: Queue> Tracks<'_, '_, M, T, Q> {
    fn settle_vertex(&mut self, v: u32, d: f64) {
        let tables = self.tables;
        let (mesh, layout) = (self.search.mesh, self.search.layout);
        let parent = self.search.parent[v as usize];
        let parent_face = self.search.parent_face[v as usize];
        // The neighbour the value came from along an edge, and the step charged.
        let mut along = None;
        for &e in mesh.vertex_edges(v).iter() {
            let edge = &tables.edges[layout.block_of_edge(e) as usize];
            let ends = mesh.edge_vertices(e);
            let nodes = layout.edge_nodes(e);
            let count = nodes.len() as u32;
            let (next, index) = match (count, v == ends[0]) {
                (0, true) => (ends[1], 1),
                (0, false) => (ends[0], 0),
                (_, true) => (nodes.start, 1),
                (_, false) => (nodes.end - 1, count),
            };
            let at = if v == ends[0] { 0 } else { count + 1 };
            let step = self.step(edge, at, index);
            if parent_face == NONE && next == parent && !edge.step.is_nan() {
                along = Some((parent, step));
            }
            self.search.relax(next, d + step, v, NONE);
        }
        self.search.relax_along_wires(v, d);
        for &f in mesh.vertex_faces(v).iter() {
            let prunes = self.search.metric.prunes_on(f);
            let r = &tables.faces[tables.record_of(f) as usize];
            let slack = self.slack(r);
            // Never back into the face the value came through (for a norm: the
            // straight segment from the parent does better there).
            if prunes && parent_face == f && slack == 0.0 {
                continue;
            }
            let c = if r.vertex[0] == v {
                0
            } else if r.vertex[1] == v {
                1
            } else {
                2
            };
            let q_pos = r.corner(c);
            if r.count(NEXT[c]) == 0 {
                continue;
            }
            let pq = r.corner_point(c);
            if prunes {
                // A tie through another face: its track already offers `d` or less.
                if self.tracks[(r.base + q_pos) as usize].value() <= d - slack {
                    continue;
                }
                // Dominated by the along-edge parent, as for Steiner points: every
                // target of a corner is a target of the points of its two edges.
                let parent = along.and_then(|(p, step)| Some((along_parent_point(r, c, p)?, step)));
                if let Some((pp, step)) = parent {
                    if self.dominated(f, &pp, &pq, step, slack) {
                        continue;
                    }
                }
            }
            self.enter(Arc::new(f, r, c, true, v, q_pos, pq, d, slack), prunes);
        }
    }

    fn settle_steiner(&mut self, q: u32, d: f64) {
        let (tables, mesh, layout) = (self.tables, self.search.mesh, self.search.layout);
        let block = layout.block(q);
        let edge = &tables.edges[block as usize];
        let nodes = layout.block_nodes(block);
        let count = nodes.len() as u32;
        let index = q - nodes.start;
        // The edge's vertices, read from the mesh only at its end points.
        let ends = || mesh.edge_vertices(layout.edge_of_block(block));
        // Along the edge, to the neighbours (numbered 0..=count+1 from the lower end).
        let prev = if index == 0 { ends()[0] } else { q - 1 };
        let next = if index + 1 == count { ends()[1] } else { q + 1 };
        // (From `q`, at position index + 1, to each neighbour: the direction counts
        // for a directed metric.)
        let step = self.step(edge, index + 1, index);
        self.search.relax(prev, d + step, q, NONE);
        let step = self.step(edge, index + 1, index + 2);
        self.search.relax(next, d + step, q, NONE);

        // A Steiner point whose value came along its edge from its neighbour `p` is
        // dominated by `p` in every face where the step from `p` costs what the edge
        // relaxation charged (the cheapest face; every face for isotropic metrics): `p`
        // entered those faces with `d − step` and, by the triangle inequality, offers
        // every target at most what `q` would.
        let parent_face = self.search.parent_face[q as usize];
        let parent = self.search.parent[q as usize];
        let along = (parent_face == NONE && parent != NONE && !edge.step.is_nan()).then(|| {
            if nodes.contains(&parent) {
                parent - nodes.start + 1
            } else if parent == ends()[0] {
                0
            } else {
                count + 1
            }
        });
        for &inc in tables.edge_faces(edge) {
            let r = &tables.faces[inc.record() as usize];
            let f = r.face;
            let prunes = self.search.metric.prunes_on(f);
            let slack = self.slack(r);
            // Never back into the face the value came through (for a norm).
            if prunes && parent_face == f && slack == 0.0 {
                continue;
            }
            let s = inc.side();
            let q_pos = r.slot_position(s, index);
            if prunes && self.tracks[(r.base + q_pos) as usize].value() <= d - slack {
                // A tie through another face: its track already offers `d` or less.
                continue;
            }
            let slot = r.slot(s);
            let pq = slot.at(slot.slot_index(index)).1;
            if let (true, Some(p_at)) = (prunes, along) {
                if self.dominated(f, &r.edge_point(s, p_at), &pq, edge.step, slack) {
                    continue;
                }
            }
            self.enter(Arc::new(f, r, s, false, q, q_pos, pq, d, slack), prunes);
        }
    }

    /// Whether the along-edge parent at `pp`, which settled `step` before the node at
    /// `pq`, offers every target in face `f` at most what that node would: true when the
    /// step costs no more in `f` than the edge relaxation charged (to 1e-12), by the
    /// triangle inequality.
    #[inline]
    fn dominated(&mut self, f: u32, pp: &FacePoint, pq: &FacePoint, step: f64, slack: f64) -> bool {
        self.search.cost(f, pp, pq) + slack <= step * (1.0 + 1e-12)
    }

    /// The metric's triangle slack in the face of record `r` (0 for norms, whose
    /// diameter is then never computed: `is_face_norm` is a constant of the metric).
    #[inline(always)]
    fn slack(&self, r: &FaceRecord) -> f64 {
        let metric = self.search.metric;
        if metric.is_face_norm() {
            0.0
        } else {
            metric.triangle_slack(r.face, r.frame.diameter())
        }
    }

    /// The cost from the point at `a` to the one at `b` (numbered from the edge's lower
    /// end, consecutive) along `edge`: the cached step, or the cheapest over its faces.
    #[inline(always)]
    fn step(&mut self, edge: &EdgeRecord, a: u32, b: u32) -> f64 {
        if !edge.step.is_nan() {
            return edge.step;
        }
        let mut best = f64::INFINITY;
        for &inc in self.tables.edge_faces(edge) {
            let r = &self.tables.faces[inc.record() as usize];
            let s = inc.side();
            let (pa, pb) = r.edge_points(s, a, b);
            best = best.min(self.search.cost(r.face, &pa, &pb));
        }
        best
    }

    fn enter(&mut self, arc: Arc, prune: bool) {
        let m = arc.m;
        let first = self.first_guess(&arc);

        // Forward walk. A loss there may also prove targets below `first`; the
        // backward walk then starts below them (or has nothing left to test).
        let mut back_from = first;
        let mut i = first;
        while i < m {
            match self.test(&arc, i) {
                None => i += 1,
                Some(p) => match arc.shadow(i, p) {
                    Shadow::After if prune => break,
                    Shadow::Between(j) if prune && j > i => i = j,
                    Shadow::Before if prune => {
                        back_from = 0;
                        i += 1;
                    }
                    Shadow::Between(j) if prune && j < back_from => {
                        back_from = j + 1;
                        i += 1;
                    }
                    _ => i += 1,
                },
            }
        }
        // Backward walk.
        let mut i = back_from;
        while i > 0 {
            i -= 1;
            match self.test(&arc, i) {
                None => {}
                Some(p) => match arc.shadow(i, p) {
                    Shadow::Before if prune => break,
                    Shadow::Between(j) if prune && j < i => i = j + 1,
                    _ => {}
                },
            }
        }
    }

    /// Where to start: the first target whose parent lies after `q` (going forward from
    /// the arc's end), found by binary search on the parents' ranks, which decrease
    /// along the arc when tracks do not cross. Only speed depends on this guess.
    #[inline]
    fn first_guess(&self, arc: &Arc) -> u32 {
        let key = |i: u32| -> u32 {
            let p = self.tracks[(arc.base + arc.pos(i)) as usize].from;
            if p == NONE {
                return arc.q_rank;
            }
            let off = arc.offset(p);
            if off < arc.m {
                // A corner-cutting track inside the arc: one going forward sorts with
                // the parents ahead of q, one going backward with those behind. Only the
                // start depends on it; on the shared bunny it cut the tests at k = 8 by
                // about a fifth against treating such tracks as neutral (an A/B run when
                // it was introduced; `tests/solver.rs` prints the counts).
                if off > i {
                    0
                } else {
                    u32::MAX
                }
            } else {
                off - arc.m + 1
            }
        };
        // The first index whose key is below q's rank. The steps depend only on `m`, and
        // each one selects instead of branching: the comparison is data, unpredictable.
        let (mut lo, mut size) = (0u32, arc.m);
        while size > 0 {
            let half = size / 2;
            let mid = lo + half;
            let right = key(mid) >= arc.q_rank;
            lo = if right { mid + 1 } else { lo };
            size = if right { size - half - 1 } else { half };
        }
        lo.saturating_sub(1).min(arc.m - 1)
    }

    /// Offers `q`'s value to target `i`; `None` if `q` won, else the position of the
    /// parent that beat it.
    #[inline(always)]
    fn test(&mut self, arc: &Arc, i: u32) -> Option<u32> {
        let slot = (arc.base + arc.pos(i)) as usize;
        let (node, p) = arc.target(i);
        let value = arc.d + self.search.cost(arc.face, &arc.pq, &p);
        let track = &mut self.tracks[slot];
        if value < track.value() {
            *track = Track {
                value: round_up(value),
                from: arc.q_pos,
            };
            self.search.relax(node, value, arc.q, arc.face);
            None
        } else if self.search.metric.is_face_norm() || value - track.value() >= arc.margin {
            Some(track.from)
        } else {
            // Lost, but by less than the metric's slack: it proves nothing.
            Some(NONE)
        }
    }
}

/// The point of node `p` in face `r` if it lies on one of the two edges at corner `c`
/// (slot `c`, from `c`, or slot `c + 2`, into `c`), its other end included.
fn along_parent_point(r: &FaceRecord, c: usize, p: u32) -> Option<FacePoint> {
    for s in [c, NEXT[NEXT[c]]] {
        if p.wrapping_sub(r.lo[s]) < r.count(s) {
            return Some(r.edge_point(s, p - r.lo[s] + 1));
        }
    }
    [NEXT[c], NEXT[NEXT[c]]]
        .into_iter()
        .find(|&o| r.vertex[o] == p)
        .map(|o| r.corner_point(o))
}

/// The next corner (or slot) around a face.
const NEXT: [usize; 3] = [1, 2, 0];

#[cfg(test)]
mod tests {
    use super::round_up;

    #[test]
    fn round_up_is_the_least_f32_not_below() {
        for value in [
            0.0,
            1e-300,
            0.1,
            1.0,
            1.0 + 1e-12,
            3.3e38,
            12345.678901234,
            -1e-300,
            -0.1,
            -1.0 - 1e-12,
            -17.255449916905274,
            -3.3e38,
        ] {
            let up = round_up(value);
            assert!(up as f64 >= value, "{value}");
            assert!((up.next_down() as f64) < value || up == 0.0, "{value}");
            assert!(up.is_finite(), "{value}");
            let nearest = value as f32;
            let expected = if nearest as f64 >= value {
                nearest
            } else {
                nearest.next_up()
            };
            assert_eq!(up, expected, "{value}");
        }
    }
}
