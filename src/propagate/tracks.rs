//! The geodesic tracks engine (paper §4): Steiner-point propagation whose broadcasts
//! are pruned along non-crossing tracks.
//!
//! # State
//! Each face's boundary is a cycle of positions: corner 0, the points of edge slot 0
//! (corner 0 → corner 1), corner 1, slot 1, corner 2, slot 2. An *instance* is a
//! (face, position) pair, stored face-major, and holds the best value that reached that
//! node *through that face* and the position of the node it came from (its parent in
//! the face: together they are the face's tracks).
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

use super::frontier::{Frontier, Queue};
use crate::mesh::{FaceFrame, Topology, TriMesh, NONE};
use crate::steiner::{slot_param, slot_spacing, NodeKind, SteinerLayout};
use crate::Error;
use geotracks_metrics::{FacePoint, Metric};

/// Everything the engine reads about one face, in one 64-byte record, so that entering
/// a face costs one cache line instead of a dozen scattered lookups.
#[derive(Clone, Copy, Debug)]
struct FaceRecord {
    /// The face's local frame.
    frame: FaceFrame,
    /// Node id of the first point (from the lower vertex) of each slot's edge.
    lo: [u32; 3],
    vertex: [u32; 3],
    /// Offset of the face's instances in the flat per-instance arrays.
    base: u32,
    /// Points on each slot.
    count: [u16; 3],
    /// Bit `s`: slot `s` runs from its edge's higher vertex (points in reverse order).
    reversed: u8,
}

// The record is meant to fill exactly one cache line.
const _: () = assert!(std::mem::size_of::<FaceRecord>() == 64);

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

/// `value` as an `f32` no smaller than it.
#[inline]
fn round_up(value: f64) -> f32 {
    let v = value as f32;
    if (v as f64) < value {
        v.next_up()
    } else {
        v
    }
}

/// The per-face tables of the tracks engine for one mesh and Steiner layout; built once
/// by a `Solver` and shared by all its runs.
pub(super) struct TrackFaces {
    records: Vec<FaceRecord>,
    instances: usize,
}

impl TrackFaces {
    pub fn new(mesh: &TriMesh, layout: &SteinerLayout) -> Result<TrackFaces, Error> {
        let mut total: u64 = 0;
        let mut records = Vec::with_capacity(mesh.face_count());
        for f in 0..mesh.face_count() as u32 {
            let vertex = mesh.face_vertices(f);
            let edges = mesh.face_edges(f);
            let mut count = [0u16; 3];
            let mut reversed = 0u8;
            for s in 0..3 {
                let c = layout.count(edges[s]);
                count[s] = u16::try_from(c).map_err(|_| Error::TooLarge {
                    what: "Steiner points on one edge",
                    count: c as u64,
                })?;
                if vertex[s] != mesh.edge_vertices(edges[s])[0] {
                    reversed |= 1 << s;
                }
            }
            records.push(FaceRecord {
                frame: *mesh.frame(f),
                lo: edges.map(|e| layout.edge_nodes(e).start),
                vertex,
                base: total as u32,
                count,
                reversed,
            });
            total += 3 + count.iter().map(|&c| c as u64).sum::<u64>();
            if total >= u32::MAX as u64 {
                return Err(Error::TooLarge {
                    what: "face-node instances",
                    count: total,
                });
            }
        }
        Ok(TrackFaces {
            records,
            instances: total as usize,
        })
    }

    /// Total number of (face, position) instances.
    pub fn instances(&self) -> usize {
        self.instances
    }
}

/// The boundary cycle of one face, decoded from its record once per entry.
struct Boundary {
    face: u32,
    base: u32,
    /// Number of positions.
    n: u32,
    /// Position of corner `c`.
    corner: [u32; 3],
    count: [u32; 3],
    lo: [u32; 3],
    reversed: [bool; 3],
    vertex: [u32; 3],
    frame: FaceFrame,
    /// [`slot_spacing`] of each slot.
    spacing: [f64; 3],
}

impl Boundary {
    #[inline]
    fn new(face: u32, r: &FaceRecord) -> Boundary {
        let count = r.count.map(u32::from);
        let corner = [0, count[0] + 1, count[0] + count[1] + 2];
        Boundary {
            face,
            base: r.base,
            n: corner[2] + count[2] + 1,
            corner,
            count,
            lo: r.lo,
            reversed: [0, 1, 2].map(|s| r.reversed & (1 << s) != 0),
            vertex: r.vertex,
            frame: r.frame,
            spacing: count.map(slot_spacing),
        }
    }

    #[inline]
    fn corner_at(&self, pos: u32) -> Option<usize> {
        self.corner.iter().position(|&p| p == pos)
    }

    /// The slot of a non-corner position, and the point's index in slot order.
    #[inline]
    fn slot_of(&self, pos: u32) -> (usize, u32) {
        let s = if pos < self.corner[1] {
            0
        } else if pos < self.corner[2] {
            1
        } else {
            2
        };
        (s, pos - self.corner[s] - 1)
    }

    /// Node id and face point of boundary position `pos`, placed by the face frame with
    /// the same calls as `SteinerLayout::point_in_face`, so the tracks and the graph
    /// engines see bit-identical coordinates.
    #[inline]
    fn at(&self, pos: u32) -> (u32, FacePoint) {
        if let Some(c) = self.corner_at(pos) {
            let mut bary = [0.0; 3];
            bary[c] = 1.0;
            return (self.vertex[c], self.frame.point(bary));
        }
        let (s, i) = self.slot_of(pos);
        let n = self.count[s];
        let node = self.lo[s] + if self.reversed[s] { n - 1 - i } else { i };
        let point = self.frame.point_on_edge(s, slot_param(i, self.spacing[s]));
        (node, point)
    }

    /// Position of `node` (of kind `kind`), which lies on this face's boundary.
    #[inline]
    fn position_of(&self, node: u32, kind: NodeKind) -> u32 {
        match kind {
            NodeKind::Vertex(v) => {
                let c = self.vertex.iter().position(|&x| x == v).expect("corner");
                self.corner[c]
            }
            NodeKind::Steiner { index, .. } => {
                let s = (0..3)
                    .find(|&s| node >= self.lo[s] && node - self.lo[s] < self.count[s])
                    .expect("node lies on a slot of the face");
                let i = if self.reversed[s] {
                    self.count[s] - 1 - index
                } else {
                    index
                };
                self.corner[s] + 1 + i
            }
        }
    }

    /// The targets of the node at `pos`: the arc of positions not on its own edges, as
    /// (first position, length). A corner's targets are the opposite slot's points; a
    /// Steiner point's run from the next slot through the opposite corner to the slot
    /// after.
    #[inline]
    fn targets(&self, pos: u32) -> (u32, u32) {
        if let Some(c) = self.corner_at(pos) {
            let s = (c + 1) % 3;
            (self.corner[s] + 1, self.count[s])
        } else {
            let (s, _) = self.slot_of(pos);
            let (s1, s2) = ((s + 1) % 3, (s + 2) % 3);
            (self.corner[s1] + 1, self.count[s1] + 1 + self.count[s2])
        }
    }
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

struct Entry<'b> {
    b: &'b Boundary,
    /// First target position and number of targets.
    start: u32,
    m: u32,
    q: u32,
    q_pos: u32,
    pq: FacePoint,
    d: f64,
    /// Rank of `q`'s position in the complement of the target arc (see `offset`).
    q_rank: u32,
}

impl Entry<'_> {
    /// Position of target `i`.
    #[inline]
    fn pos(&self, i: u32) -> u32 {
        let p = self.start + i;
        if p >= self.b.n {
            p - self.b.n
        } else {
            p
        }
    }

    /// Offset of position `p` from the arc's start, going forward around the cycle.
    #[inline]
    fn offset(&self, p: u32) -> u32 {
        if p >= self.start {
            p - self.start
        } else {
            p + self.b.n - self.start
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

/// Settles nodes until the queue is empty (or the metric misbehaves). `tracks` holds
/// one [`Track`] per instance, reset by the caller.
pub(super) fn propagate<M: Metric, Q: Queue>(
    search: &mut Frontier<'_, M, Q>,
    faces: &TrackFaces,
    tracks: &mut [Track],
) {
    let mut run = Tracks {
        search,
        records: &faces.records,
        tracks,
    };
    while let Some(q) = run.search.queue.pop(run.search.distance) {
        let d = run.search.distance[q as usize];
        let kind = run.search.layout.kind(q);
        run.search.relax_along_edges(q, kind, d);
        run.enter_faces(q, kind, d);
        if run.search.bad_cost.is_some() {
            break;
        }
    }
}

struct Tracks<'r, 'a, M, Q> {
    search: &'r mut Frontier<'a, M, Q>,
    records: &'r [FaceRecord],
    /// Per instance: best value through the face and where it came from.
    tracks: &'r mut [Track],
}

impl<M: Metric, Q: Queue> Tracks<'_, '_, M, Q> {
    fn enter_faces(&mut self, q: u32, kind: NodeKind, d: f64) {
        let mesh = self.search.mesh;
        let faces = match kind {
            NodeKind::Vertex(v) => mesh.vertex_faces(v),
            NodeKind::Steiner { edge, .. } => mesh.edge_faces(edge),
        };
        // A Steiner point whose value came along its edge from its neighbour `p` is
        // dominated by `p` in every face where the step from `p` costs what the edge
        // relaxation charged (the cheapest face; every face for isotropic metrics): `p`
        // entered those faces with `d − step` and, by the triangle inequality, offers
        // every target at most what `q` would.
        let along = match (kind, self.search.edge_steps) {
            (NodeKind::Steiner { edge, .. }, Some(steps))
                if self.search.parent_face[q as usize] == NONE
                    && self.search.parent[q as usize] != NONE =>
            {
                let p = self.search.parent[q as usize];
                // `p` is a neighbour on the same edge, or one of its vertices.
                let p_kind = if p < self.search.layout.vertex_count() {
                    NodeKind::Vertex(p)
                } else {
                    NodeKind::Steiner {
                        edge,
                        index: p - self.search.layout.edge_nodes(edge).start,
                    }
                };
                Some((p, p_kind, steps[edge as usize]))
            }
            _ => None,
        };
        let parent_face = self.search.parent_face[q as usize];
        for &f in faces {
            let prunes = self.search.metric.prunes_on(f);
            // Never back into the face the value came through.
            if prunes && parent_face == f {
                continue;
            }
            let b = Boundary::new(f, &self.records[f as usize]);
            let q_pos = b.position_of(q, kind);
            if prunes {
                // A tie through another face: its track already offers `d` or less.
                if self.tracks[(b.base + q_pos) as usize].value() <= d {
                    continue;
                }
                if let Some((p, p_kind, step)) = along {
                    let (_, pp) = b.at(b.position_of(p, p_kind));
                    let (_, pq) = b.at(q_pos);
                    if self.search.cost(f, &pp, &pq) <= step * (1.0 + 1e-12) {
                        continue;
                    }
                }
            }
            self.enter(&b, q, q_pos, d);
        }
    }

    fn enter(&mut self, b: &Boundary, q: u32, q_pos: u32, d: f64) {
        let (start, m) = b.targets(q_pos);
        if m == 0 {
            return;
        }
        let (_, pq) = b.at(q_pos);
        let mut e = Entry {
            b,
            start,
            m,
            q,
            q_pos,
            pq,
            d,
            q_rank: 0,
        };
        e.q_rank = e.offset(q_pos) - m + 1;
        let first = self.first_guess(&e);
        let prune = self.search.metric.prunes_on(b.face);

        // Forward walk. A loss there may also prove targets below `first`; the
        // backward walk then starts below them (or has nothing left to test).
        let mut back_from = first;
        let mut i = first;
        while i < m {
            match self.test(&e, i) {
                None => i += 1,
                Some(p) => match e.shadow(i, p) {
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
            match self.test(&e, i) {
                None => {}
                Some(p) => match e.shadow(i, p) {
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
    fn first_guess(&self, e: &Entry<'_>) -> u32 {
        let key = |i: u32| -> u32 {
            let p = self.tracks[(e.b.base + e.pos(i)) as usize].from;
            if p == NONE {
                return e.q_rank;
            }
            let off = e.offset(p);
            if off < e.m {
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
                off - e.m + 1
            }
        };
        let (mut lo, mut hi) = (0u32, e.m);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if key(mid) >= e.q_rank {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        lo.saturating_sub(1).min(e.m - 1)
    }

    /// Offers `q`'s value to target `i`; `None` if `q` won, else the position of the
    /// parent that beat it.
    #[inline]
    fn test(&mut self, e: &Entry<'_>, i: u32) -> Option<u32> {
        let pos = e.pos(i);
        let slot = (e.b.base + pos) as usize;
        let (node, p) = e.b.at(pos);
        let value = e.d + self.search.cost(e.b.face, &e.pq, &p);
        let track = &mut self.tracks[slot];
        if value < track.value() {
            *track = Track {
                value: round_up(value),
                from: e.q_pos,
            };
            self.search.relax(node, value, e.q, e.b.face);
            None
        } else {
            Some(track.from)
        }
    }
}
