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
use super::queue::BucketQueue;
use crate::mesh::{FaceFrame, Topology, TriMesh, NONE};
use crate::steiner::{NodeKind, SteinerLayout};
use crate::Error;
use geotracks_metrics::{FacePoint, Metric};

/// Per-face instance storage: offsets of each face's positions in the flat arrays.
pub(super) struct Instances {
    /// `base[f]..base[f + 1]` are face `f`'s positions.
    base: Vec<u32>,
}

impl Instances {
    pub fn new(mesh: &TriMesh, layout: &SteinerLayout) -> Result<Instances, Error> {
        let mut base = Vec::with_capacity(mesh.face_count() + 1);
        let mut total: u64 = 0;
        base.push(0);
        for f in 0..mesh.face_count() as u32 {
            total += 3 + mesh
                .face_edges(f)
                .iter()
                .map(|&e| layout.count(e) as u64)
                .sum::<u64>();
            if total >= u32::MAX as u64 {
                return Err(Error::TooLarge {
                    what: "face-node instances",
                    count: total,
                });
            }
            base.push(total as u32);
        }
        Ok(Instances { base })
    }

    /// Total number of (face, position) instances.
    pub fn len(&self) -> usize {
        *self.base.last().expect("base has F + 1 entries") as usize
    }
}

/// The boundary cycle of one face, decoded once per entry.
struct Boundary {
    face: u32,
    frame: FaceFrame,
    /// Number of positions.
    n: u32,
    /// Position of corner `c`.
    corner: [u32; 3],
    /// Points on slot `s`.
    count: [u32; 3],
    /// Node id of the slot edge's point 0 (numbered from the edge's lower vertex).
    first_node: [u32; 3],
    /// Whether slot `s` runs from its edge's lower vertex.
    from_lower: [bool; 3],
    vertex: [u32; 3],
    /// The slot's edge.
    edge: [u32; 3],
}

impl Boundary {
    #[inline]
    fn new(mesh: &TriMesh, layout: &SteinerLayout, f: u32) -> Boundary {
        let vertex = mesh.face_vertices(f);
        let edge = mesh.face_edges(f);
        let count = edge.map(|e| layout.count(e));
        let first_node = edge.map(|e| layout.edge_nodes(e).start);
        let from_lower = [0, 1, 2].map(|s| vertex[s] == mesh.edge_vertices(edge[s])[0]);
        let corner = [0, count[0] + 1, count[0] + count[1] + 2];
        Boundary {
            face: f,
            frame: *mesh.frame(f),
            n: count[0] + count[1] + count[2] + 3,
            corner,
            count,
            first_node,
            from_lower,
            vertex,
            edge,
        }
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

    /// The edge index (from the lower vertex) of point `i` in slot order of slot `s`.
    #[inline]
    fn edge_index(&self, s: usize, i: u32) -> u32 {
        if self.from_lower[s] {
            i
        } else {
            self.count[s] - 1 - i
        }
    }

    /// Node id and position in the face's frame of boundary position `pos`.
    #[inline]
    fn at(&self, layout: &SteinerLayout, pos: u32) -> (u32, FacePoint) {
        if let Some(c) = self.corner.iter().position(|&p| p == pos) {
            let mut bary = [0.0; 3];
            bary[c] = 1.0;
            return (self.vertex[c], self.frame.point(bary));
        }
        let (s, i) = self.slot_of(pos);
        let index = self.edge_index(s, i);
        // Same arithmetic as SteinerLayout::point_on_slot, so both engines see the very
        // same coordinates.
        let t = layout.param(self.edge[s], index);
        let point = self
            .frame
            .point_on_edge(s, if self.from_lower[s] { t } else { 1.0 - t });
        (self.first_node[s] + index, point)
    }

    /// Position of `node`, which lies on this face's boundary.
    #[inline]
    fn position_of(&self, layout: &SteinerLayout, node: u32) -> u32 {
        match layout.kind(node) {
            NodeKind::Vertex(v) => {
                let c = self.vertex.iter().position(|&x| x == v).expect("corner");
                self.corner[c]
            }
            NodeKind::Steiner { edge, index } => {
                let s = self.edge.iter().position(|&e| e == edge).expect("slot");
                let i = if self.from_lower[s] {
                    index
                } else {
                    self.count[s] - 1 - index
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
        if let Some(c) = self.corner.iter().position(|&p| p == pos) {
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
    base: u32,
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

/// Runs the track-pruned propagation from `sources` (start value 0) to the end.
pub(super) fn propagate<'a, M: Metric>(
    mesh: &'a TriMesh,
    metric: &'a M,
    layout: &'a SteinerLayout,
    edge_steps: Option<&'a [f64]>,
    instances: &Instances,
    bucket_width: f64,
    sources: &[u32],
) -> Frontier<'a, M, BucketQueue> {
    let queue = BucketQueue::new(layout.node_count(), bucket_width);
    let mut run = Tracks {
        search: Frontier::new(mesh, metric, layout, edge_steps, queue),
        base: &instances.base,
        value: vec![f64::INFINITY; instances.len()],
        from: vec![NONE; instances.len()],
    };
    for &s in sources {
        run.search.relax(s, 0.0, NONE, NONE);
    }
    while let Some(q) = run.search.queue.pop(&run.search.distance) {
        let d = run.search.distance[q as usize];
        run.search.relax_along_edges(q, d);
        run.enter_faces(q, d);
        if run.search.bad_cost.is_some() {
            break;
        }
    }
    run.search
}

struct Tracks<'a, 'i, M> {
    search: Frontier<'a, M, BucketQueue>,
    base: &'i [u32],
    /// Best value through the face, per instance.
    value: Vec<f64>,
    /// Position (in the same face) of the node that gave `value`; `NONE` if none.
    from: Vec<u32>,
}

impl<M: Metric> Tracks<'_, '_, M> {
    fn enter_faces(&mut self, q: u32, d: f64) {
        let (mesh, layout) = (self.search.mesh, self.search.layout);
        let faces = match layout.kind(q) {
            NodeKind::Vertex(v) => mesh.vertex_faces(v),
            NodeKind::Steiner { edge, .. } => mesh.edge_faces(edge),
        };
        for &f in faces {
            let b = Boundary::new(mesh, layout, f);
            let q_pos = b.position_of(layout, q);
            let base = self.base[f as usize];
            // Never back into the face the value came through.
            if self.search.metric.prunes_on(f) && self.value[(base + q_pos) as usize] <= d {
                continue;
            }
            self.enter(&b, base, q, q_pos, d);
        }
    }

    fn enter(&mut self, b: &Boundary, base: u32, q: u32, q_pos: u32, d: f64) {
        let (start, m) = b.targets(q_pos);
        if m == 0 {
            return;
        }
        let layout = self.search.layout;
        let (_, pq) = b.at(layout, q_pos);
        let mut e = Entry {
            b,
            base,
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

        // Forward walk.
        let mut i = first;
        while i < m {
            match self.test(&e, i) {
                None => i += 1,
                Some(p) => match e.shadow(i, p) {
                    Shadow::After if prune => break,
                    Shadow::Between(j) if prune && j > i => i = j,
                    _ => i += 1,
                },
            }
        }
        // Backward walk.
        let mut i = first;
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
            let p = self.from[(e.base + e.pos(i)) as usize];
            if p == NONE {
                return e.q_rank;
            }
            let off = e.offset(p);
            if off < e.m {
                e.q_rank
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
        let slot = (e.base + pos) as usize;
        let (node, p) = e.b.at(self.search.layout, pos);
        let value = e.d + self.search.cost(e.b.face, &e.pq, &p);
        if value < self.value[slot] {
            self.value[slot] = value;
            self.from[slot] = e.q_pos;
            self.search.relax(node, value, e.q, e.b.face);
            None
        } else {
            Some(self.from[slot])
        }
    }
}
