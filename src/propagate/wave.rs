//! The wavefront engine: Steiner nodes that carry the wave that reached them.
//!
//! # Idea
//! For a *face-flat* metric (one that is a constant norm on each face and gives its
//! flattening, [`Metric::face_gram`]: `Euclidean`, `Tensor`), each face maps
//! isometrically onto a plane, and a shortest path is a straight line wherever it
//! crosses faces whose flattenings glue isometrically along their shared edges. A
//! Steiner node then keeps, besides its value, the *wave* that gave it: a virtual
//! source `S` (the start of the straight piece, unfolded into the plane of the node's
//! edge), `σ` (the path length up to `S`), and a *window*: the part of the node's edge
//! through which every straight line from `S` is a real path on the surface. When the
//! node enters a face across its edge, a target `t` of the face gets
//! `σ + |S t|` if the straight line from `S` to `t` crosses the edge inside the window,
//! and the polyline value `d(q) + |q t|` (bending at the node) otherwise; a vertex
//! target gets, instead of the polyline, the shortest way through the window: bending at
//! the window's end on the line's side (a *hinge*, see `flat::hinge`), `σ + |S w| + |w t|`.
//! A target that takes the straight value inherits `S` and `σ`, with the window
//! projected from `S` onto its own edge; one that takes the polyline value gets a fresh
//! wave: a source at the node, `σ = d(q)`, the whole edge as window.
//!
//! Vertices do not carry waves: a geodesic bends at a saddle vertex and never passes
//! through a convex one, so a vertex always starts a fresh wave (a point source). Waves
//! do not cross an edge whose faces do not glue isometrically (two tensors that give it
//! different lengths: a refraction), nor go back into the face they came from.
//!
//! # Why values are never below the true distance
//! Every value is the length of a real path: a polyline value is a node's value plus a
//! straight segment inside one face; a hinge's is a line from `S` to the end of the
//! window (which the window holds) plus a segment inside one face; a straight value is
//! `σ` plus a straight line from `S` that crosses the entering node's window, and by
//! induction every line from `S`
//! through a window is a path that exists: the window of a node that inherited a wave
//! is the set of points of its edge that lines from `S` reach through its parent's
//! window and across the face between them. So the engine can only overestimate
//! (where a wave was lost), never take a shortcut off the surface. Windows are tested
//! with a slack of `1e-6` of the edge's length (their ends are stored as `f32`, and a
//! line through a vertex crosses its edges at their very ends): a line that passes a
//! vertex by that much on the wrong side is shorter than the real path by about
//! `δ² / ℓ`, 1e-12 relative (measured on the shared meshes: at most 4.7e-10 below the
//! exact references). A straight offer whose source would land beyond the target's
//! edge (a sliver) is refused rather than clamped.
//!
//! # Where windows meet
//! A node keeps one wave: the one that gave its best value. A face entered by a wave
//! through two of its edges splits the third edge between the two entries at the line
//! from `S` through their shared corner; each node on the third edge has the window of
//! its own entry. Where a part holds no node, the lines through it would be lost, so
//! windows of one wave are merged: when a node's wave reaches a target whose own wave
//! has the same source (same `S` and `σ`, to 1e-9) but through another entry, the two
//! windows are joined if they touch. Both parts are real paths, so the union is too.
//! On a plane, waves from one source then cover every edge whole, and the engine is
//! exact (tests: planar meshes, needles, holes, developable strips).
//!
//! # Cost
//! Every entry tests every target of the face (no track pruning: with the few points
//! per edge this engine needs, a face has a handful of targets). Each test first takes
//! the unconstrained straight value, a lower bound on every offer the entry can make
//! (a bent way is longer); most tests end there, before the window is looked at.
//! Values, parents and the bucket queue are the other engines'; each Steiner node adds a
//! 32-byte wave. A straight or hinge offer can lie below the offering node's value (its
//! source, or its bend, is nearer the source than the node), by at most an edge's
//! length: the solver's `reach` widens finality by that much.

use super::frontier::{settle_all, Frontier, Queue, Seed, Settle};
use super::tracks::{FaceRecord, TrackTables};
use crate::field::Wave;
use crate::flat::{
    hinge, hinge_end, in_window, project, same_source, same_source_slack, uv, wave_value_on_edge,
    windows_touch, EdgeFrame, P, TIE,
};
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::surface::Source;
use geotracks_metrics::Metric;

/// What the engine knows of each edge block besides its nodes.
#[derive(Default)]
pub(in crate::propagate) struct WaveEdges {
    /// Whether every face around the edge gives it the same length (waves cross it).
    pub isometric: Vec<bool>,
    /// The most (radians) any edge's direction turns, by rounding, from one face's
    /// frame to another's ([`crate::flat::EdgeGlue::turn`]). A source carried across
    /// such an edge moves by that much times its distance, and every comparison of
    /// two copies of a source downstream inherits it, so the bound is the mesh's, not
    /// the edge's at hand (measured: copies 6e-9 apart met at edges whose own faces
    /// are well shaped, after coming in by a face 1.4e7 times longer than its short
    /// edge). Two sources that near are one to within what the frames can tell.
    pub turn: f64,
}

/// Settles nodes until the run is over ([`settle_all`]). `waves` holds one
/// [`Wave`] per Steiner node (reset by the caller); `seeds` are the sources' offers,
/// already given to their nodes; `sources` the run's (validated) sources.
pub(super) fn propagate<M: Metric, T: Topology, Q: Queue>(
    search: &mut Frontier<'_, M, T, Q>,
    tables: &TrackTables,
    edges: &WaveEdges,
    waves: &mut [Wave],
    seeds: &[Seed],
    sources: &[Source],
) {
    let vertex_count = search.layout.vertex_count();
    let mut run = Waves {
        search,
        tables,
        edges,
        waves,
        vertex_count,
    };
    run.seed_waves(seeds, sources);
    settle_all(&mut run);
}

impl<M: Metric, T: Topology, Q: Queue> Settle for Waves<'_, '_, M, T, Q> {
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

struct Waves<'r, 'a, M, T, Q> {
    search: &'r mut Frontier<'a, M, T, Q>,
    tables: &'r TrackTables,
    edges: &'r WaveEdges,
    waves: &'r mut [Wave],
    vertex_count: u32,
}

impl<M: Metric, T: Topology, Q: Queue> Waves<'_, '_, M, T, Q> {
    #[inline(always)]
    fn wave(&self, node: u32) -> &Wave {
        &self.waves[(node - self.vertex_count) as usize]
    }

    #[inline(always)]
    fn wave_mut(&mut self, node: u32) -> &mut Wave {
        if self.search.records && self.search.distance[node as usize] == f64::INFINITY {
            // A wave kept by a node beyond the maximum distance (its value was refused):
            // touched all the same, so that the next reset clears it.
            self.search.touched.push(node);
        }
        &mut self.waves[(node - self.vertex_count) as usize]
    }

    /// The waves of nodes that a source reached directly: a source inside a face (or
    /// on an edge) is the virtual source of every node around it.
    fn seed_waves(&mut self, seeds: &[Seed], sources: &[Source]) {
        let mesh = self.search.mesh;
        for seed in seeds {
            if seed.node < self.vertex_count || seed.face == NONE {
                continue;
            }
            // Only the seed that the node kept.
            if self.search.distance[seed.node as usize] != seed.value
                || self.search.parent_face[seed.node as usize] != seed.face
            {
                continue;
            }
            let Some(point) = sources[seed.source as usize].point.in_face(mesh, seed.face) else {
                continue;
            };
            let r = &self.tables.faces[self.tables.record_of(seed.face) as usize];
            let Some(s) = slot_of(r, seed.node) else {
                continue;
            };
            let frame = EdgeFrame::new(&r.frame, s, r.is_reversed(s));
            let (sx, sy) = frame.edge_coords(uv(&r.frame.point(point.bary)));
            *self.wave_mut(seed.node) = Wave {
                sx,
                sy: sy.max(0.0),
                sigma: sources[seed.source as usize].start,
                w0: 0.0,
                w1: 1.0,
            };
        }
    }

    fn settle_vertex(&mut self, v: u32, d: f64) {
        let tables = self.tables;
        let layout = self.search.layout;
        for &spoke in tables.spokes.row(v) {
            let (b, high) = (spoke >> 1, spoke & 1 == 1);
            let nodes = layout.block_nodes(b);
            let step = tables.edges[b as usize].step;
            let len = step * (nodes.len() + 1) as f64;
            let next = match (nodes.is_empty(), high) {
                (true, false) => tables.ends[b as usize][1],
                (true, true) => tables.ends[b as usize][0],
                (false, false) => nodes.start,
                (false, true) => nodes.end - 1,
            };
            let at = high as u32 as f64;
            self.along_edge(v, d, next, step, None, (at, 0.0), len, NONE);
        }
        // A vertex reached along a wire is a point source for its faces, as every
        // vertex is: nothing more to carry.
        self.search.relax_along_wires(v, d);
        let parent_face = self.search.parent_face[v as usize];
        for &inc in tables.corners.row(v) {
            let r = &tables.faces[inc.record() as usize];
            let f = r.face;
            if f == parent_face {
                continue;
            }
            let c = inc.side();
            let opposite = (c + 1) % 3;
            let slot = r.slot(opposite);
            if slot.count == 0 {
                continue;
            }
            let pq = uv(&r.corner_point(c));
            for i in 0..slot.count {
                let (t, pt) = slot.at(i);
                self.search.tests += 1;
                let value = d + uv(&pt).sub(pq).length();
                if value < self.search.distance[t as usize] {
                    self.offer_polyline(t, value, v, f, r, opposite, pq, d);
                }
            }
        }
    }

    fn settle_steiner(&mut self, q: u32, d: f64) {
        let (tables, layout) = (self.tables, self.search.layout);
        let block = layout.block(q);
        let edge = &tables.edges[block as usize];
        let nodes = layout.block_nodes(block);
        let count = nodes.len() as u32;
        let index = q - nodes.start;
        let parent_face = self.search.parent_face[q as usize];
        let mut wave = *self.wave(q);
        // The same wave may reach this node's edge through the parent face's two other
        // edges as well: join what they see, once, now that the node goes on.
        if wave.is_some() && (wave.w0 > 0.0 || wave.w1 < 1.0) && parent_face != NONE {
            let r = &tables.faces[tables.record_of(parent_face) as usize];
            if let Some(s) = slot_of(r, q) {
                let tf = EdgeFrame::new(&r.frame, s, r.is_reversed(s));
                self.join_edges(q, r, parent_face, s, &tf);
                wave = *self.wave(q);
            }
        }
        // Along the edge: the next nodes, straight from the wave where they are in it.
        let ends = || tables.ends[block as usize];
        let prev = if index == 0 { ends()[0] } else { q - 1 };
        let next = if index + 1 == count { ends()[1] } else { q + 1 };
        let spacing = 1.0 / (count + 1) as f64;
        let own = (index + 1) as f64 * spacing;
        let len = edge.step * (count + 1) as f64;
        let iso = self.edges.isometric[block as usize];
        // Along an edge whose faces give it different lengths the wave's frame is its
        // face's alone: it is not carried (a fresh wave starts).
        let carried = iso.then_some(&wave);
        self.along_edge(
            q,
            d,
            prev,
            edge.step,
            carried,
            (own, own - spacing),
            len,
            parent_face,
        );
        self.along_edge(
            q,
            d,
            next,
            edge.step,
            carried,
            (own, own + spacing),
            len,
            parent_face,
        );

        let has_wave = wave.is_some() && iso;
        for &inc in tables.edge_faces(edge) {
            let r = &tables.faces[inc.record() as usize];
            let f = r.face;
            // Never back into the face the value (and the wave) came through.
            if f == parent_face {
                continue;
            }
            let s = inc.side();
            let frame = EdgeFrame::new(&r.frame, s, r.is_reversed(s));
            let pq = frame.at_edge_coords(own * frame.len, 0.0);
            // Targets: the points of the two other slots and the opposite corner.
            let entry = Entry {
                q,
                d,
                wave,
                has_wave,
                frame,
                pq,
                f,
                same_source_slack: same_source_slack(
                    P(wave.sx, wave.sy),
                    wave.sigma,
                    frame.len,
                    self.edges.turn,
                ),
            };
            for step in 1..3 {
                let ts = (s + step) % 3;
                let slot = r.slot(ts);
                for i in 0..slot.count {
                    let (t, pt) = slot.at(i);
                    self.offer(&entry, t, uv(&pt), r, ts);
                }
                if step == 1 {
                    let c = (s + 2) % 3;
                    self.offer(&entry, r.vertex[c], uv(&r.corner_point(c)), r, 3);
                }
            }
        }
    }

    /// `from` (value `d`, at fraction `at.0` of the edge) offers `to` (at `at.1`), its
    /// neighbour along an edge of length `len`, `step` away. A Steiner point passes its
    /// wave on (which came through `face`) where `to` lies in its window; otherwise
    /// `to` gets a fresh wave from `from`, on the edge's own line.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn along_edge(
        &mut self,
        from: u32,
        d: f64,
        to: u32,
        step: f64,
        wave: Option<&Wave>,
        (from_at, at): (f64, f64),
        len: f64,
        face: u32,
    ) {
        self.search.tests += 1;
        let mut value = d + step;
        let mut carried = None;
        if let Some(w) = wave.filter(|w| w.is_some()) {
            if in_window(w, at) {
                let straight = w.sigma + P(w.sx - at * len, w.sy).length();
                if straight < value {
                    value = straight;
                    carried = Some(*w);
                }
            } else if to < self.vertex_count {
                // A vertex beyond the window's end (inside the edge): the bend there,
                // as in `offer` (see `flat::hinge`).
                if let Some(x) = hinge_end(w, at) {
                    value = value.min(wave_value_on_edge(w, len, x) + (at - x).abs() * len);
                }
            }
        }
        let previous = self.search.distance[to as usize];
        if value >= previous || self.keeps_wave(to, value, carried.map_or(d, |w| w.sigma)) {
            return;
        }
        self.search
            .relax(to, value, from, if carried.is_some() { face } else { NONE });
        if to >= self.vertex_count && self.search.distance[to as usize] < previous {
            *self.wave_mut(to) = carried.unwrap_or(Wave {
                sx: from_at * len,
                sy: 0.0,
                sigma: d,
                w0: 0.0,
                w1: 1.0,
            });
        }
    }

    /// Whether Steiner node `t` keeps its wave against an offer of `value` from a wave
    /// that started at `sigma`: when the offer ties with its value (within rounding)
    /// and its own wave started no later. On a line through a vertex from a source,
    /// the vertex's fresh wave gives the same value as the source's, and may come a
    /// unit in the last place lower; taking it would bend every line beyond.
    #[inline]
    fn keeps_wave(&self, t: u32, value: f64, sigma: f64) -> bool {
        let previous = self.search.distance[t as usize];
        if t < self.vertex_count {
            // A vertex keeps its value against a tie: a node that got its value from
            // the vertex, along its edge, may offer it back a unit in the last place
            // lower, and taking it would make each the other's parent.
            return value >= previous - TIE * previous.abs();
        }
        let current = self.wave(t);
        value >= previous - TIE * previous.abs() && current.is_some() && current.sigma <= sigma
    }

    /// What `entry`'s node offers target `t` at `pt` in the face of record `r`, on slot
    /// `ts` (3: the opposite corner): the straight value from its wave where the line
    /// crosses its window (a polyline through it is never shorter then), else the
    /// polyline value.
    #[inline]
    fn offer(&mut self, entry: &Entry, t: u32, pt: P, r: &FaceRecord, ts: usize) {
        self.search.tests += 1;
        let current = self.search.distance[t as usize];
        let wave = &entry.wave;
        if entry.has_wave {
            // In the entering edge's frame: the source at (sx, −sy), behind the edge.
            let (tx, ty) = entry.frame.edge_coords(pt);
            let (dx, dy) = (tx - wave.sx, ty + wave.sy);
            let straight = wave.sigma + P(dx, dy).length();
            // Every offer of this entry is at least the straight line's (a hinge or a
            // bend at the node is a longer way from the source), and `t` carries the
            // same wave (to merge windows with) only with that value: beyond it, the
            // offer is over before the window is looked at. Most offers end here.
            if straight > current + 4.0 * entry.same_source_slack + TIE * current.abs() {
                return;
            }
            let x = (wave.sx + wave.sy / dy * dx) / entry.frame.len;
            if in_window(wave, x) {
                if straight > current + TIE * current.abs()
                    || self.offer_straight(t, straight, entry, r, ts)
                {
                    return;
                }
            } else {
                if t >= self.vertex_count
                    && ts < 3
                    && (self.wave(t).sigma - wave.sigma).abs() <= entry.same_source_slack
                {
                    // Outside the window: the same wave may have reached `t` another way.
                    self.merge(t, entry, r, ts);
                }
                // Outside the window, the shortest path through it bends at the
                // window's end on that side (see `flat::hinge`): never longer than bending
                // at the node, which lies inside it. Only for a vertex, which carries
                // no wave: a Steiner node that took the hinge's value would carry the
                // hinge's fresh wave, which can then keep out a straight wave that comes
                // later with a value between the two and serves the nodes beyond better
                // (measured: lower means, but higher maxima under tensors).
                if t < self.vertex_count {
                    if let Some((ph, sigma)) = hinge(wave, &entry.frame, x) {
                        let value = sigma + pt.sub(ph).length();
                        if value < current {
                            self.offer_polyline(t, value, entry.q, entry.f, r, ts, ph, sigma);
                        }
                        return;
                    }
                }
            }
        }
        let polyline = entry.d + pt.sub(entry.pq).length();
        if polyline < current {
            self.offer_polyline(t, polyline, entry.q, entry.f, r, ts, entry.pq, entry.d);
        }
    }

    /// A polyline offer: bending at `from` (at `pf`, value `d`).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn offer_polyline(
        &mut self,
        t: u32,
        value: f64,
        from: u32,
        f: u32,
        r: &FaceRecord,
        ts: usize,
        pf: P,
        d: f64,
    ) {
        if self.keeps_wave(t, value, d) {
            return;
        }
        let previous = self.search.distance[t as usize];
        self.search.relax(t, value, from, f);
        if t >= self.vertex_count && self.search.distance[t as usize] < previous {
            let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
            let (sx, sy) = tf.edge_coords(pf);
            *self.wave_mut(t) = Wave {
                sx,
                sy: sy.max(0.0),
                sigma: d,
                w0: 0.0,
                w1: 1.0,
            };
        }
    }

    /// A straight offer of `value` from `entry`'s wave, an improvement or a tie;
    /// `false` when the line does not reach the target's edge from inside the face
    /// (within rounding, on a sliver): the offer is then not straight.
    #[inline]
    fn offer_straight(
        &mut self,
        t: u32,
        value: f64,
        entry: &Entry,
        r: &FaceRecord,
        ts: usize,
    ) -> bool {
        let previous = self.search.distance[t as usize];
        let wave = &entry.wave;
        let steiner = t >= self.vertex_count && ts < 3;
        if !steiner {
            if value < previous {
                self.search.relax(t, value, entry.q, entry.f);
            }
            return true;
        }
        let tie = value >= previous - TIE * previous.abs();
        if tie {
            // The same wave through another entry joins its window; a wave that
            // started earlier replaces the node's (a vertex on the line from a source
            // gives the same value, but a new wave that bends there: the earlier one is
            // the one to carry on).
            let current = *self.wave(t);
            if current.is_some() && wave.sigma >= current.sigma - TIE * previous.abs() {
                self.merge(t, entry, r, ts);
                return true;
            }
        }
        let s = entry.frame.at_edge_coords(wave.sx, -wave.sy);
        let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
        let (sx, sy) = tf.edge_coords(s);
        // The source lies on the face's side of the target's edge: the line came
        // through the face. A line accepted within the window's slack on a sliver can
        // put it beyond; moving it onto the edge would be a shortcut, so the offer is
        // refused (the polyline one stands).
        if sy < -TIE * (tf.len + sx.abs()) {
            return false;
        }
        let (w0, w1) = project(wave, s, &entry.frame, &tf);
        if value < previous {
            self.search.relax(t, value, entry.q, entry.f);
        } else {
            let (parent, parent_face) = (&mut self.search.parent, &mut self.search.parent_face);
            parent[t as usize] = entry.q;
            parent_face[t as usize] = entry.f;
            self.search.requeue(t);
        }
        *self.wave_mut(t) = Wave {
            sx,
            sy: sy.max(0.0),
            sigma: wave.sigma,
            w0,
            w1,
        };
        true
    }

    /// Joins to `t`'s window (on slot `ts` of record `r`, seen as `tf`) the parts of its
    /// edge that the nodes of the face's two other slots see through their windows,
    /// where they carry the same wave into this face. Called when `t` settles and
    /// whenever a merge widens its window, so that joins do not depend on the order
    /// nodes settle in.
    fn join_edges(&mut self, t: u32, r: &FaceRecord, f: u32, ts: usize, tf: &EdgeFrame) {
        let tw = *self.wave(t);
        if !tw.is_some() {
            return;
        }
        let st = tf.at_edge_coords(tw.sx, tw.sy);
        let (mut w0, mut w1) = (tw.w0, tw.w1);
        // The same wave has the same σ: a node whose σ differs (most) is passed over
        // before anything is computed for it (`same_source` checks σ to this too).
        let turn = self.edges.turn;
        let sigma_slack = same_source_slack(st, tw.sigma, tf.len, turn);
        for other in [(ts + 1) % 3, (ts + 2) % 3] {
            let count = r.count(other);
            let lo = r.lo[other];
            let mut of = None;
            for o in lo..lo + count {
                let ow = *self.wave(o);
                if (ow.sigma - tw.sigma).abs() > sigma_slack
                    || !ow.is_some()
                    || self.search.parent_face[o as usize] == f
                    || !self.edges.isometric[self.search.layout.block(o) as usize]
                {
                    continue;
                }
                let of = *of
                    .get_or_insert_with(|| EdgeFrame::new(&r.frame, other, r.is_reversed(other)));
                let so = of.at_edge_coords(ow.sx, -ow.sy);
                if !same_source(st, tw.sigma, so, ow.sigma, tf.len, turn) {
                    continue;
                }
                let (o0, o1) = project(&ow, so, &of, tf);
                if o0 <= o1 && windows_touch((w0, w1), (o0, o1), st, tf, turn) {
                    w0 = w0.min(o0);
                    w1 = w1.max(o1);
                }
            }
        }
        let wave = self.wave_mut(t);
        wave.w0 = w0;
        wave.w1 = w1;
    }

    /// Joins to target `t`'s window the part of its edge that `entry`'s wave reaches
    /// through its window, when `t` carries the same wave through this face and the two
    /// parts touch; a settled `t` is queued again so that it offers through the wider
    /// window.
    fn merge(&mut self, t: u32, entry: &Entry, r: &FaceRecord, ts: usize) {
        let current = *self.wave(t);
        let full = current.w0 <= 0.0 && current.w1 >= 1.0;
        if full || !current.is_some() || self.search.parent_face[t as usize] != entry.f {
            return;
        }
        let wave = &entry.wave;
        let s = entry.frame.at_edge_coords(wave.sx, -wave.sy);
        let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
        let st = tf.at_edge_coords(current.sx, current.sy);
        if !same_source(st, current.sigma, s, wave.sigma, tf.len, self.edges.turn) {
            return;
        }
        let (w0, w1) = project(wave, s, &entry.frame, &tf);
        if w0 > w1 {
            return;
        }
        let touch = windows_touch((current.w0, current.w1), (w0, w1), st, &tf, self.edges.turn);
        let (n0, n1) = (w0.min(current.w0), w1.max(current.w1));
        if touch && (n0 < current.w0 || n1 > current.w1) {
            let wave = self.wave_mut(t);
            wave.w0 = n0;
            wave.w1 = n1;
            self.join_edges(t, r, entry.f, ts, &tf);
            self.search.requeue(t);
        }
    }
}

/// A Steiner node entering a face: what every target's offer needs.
struct Entry {
    q: u32,
    d: f64,
    wave: Wave,
    /// Whether the wave may cross into this face (it has one, and the edge's faces glue
    /// isometrically).
    has_wave: bool,
    /// The node's edge, seen from the face entered.
    frame: EdgeFrame,
    /// The node's point in the face.
    pq: P,
    f: u32,
    /// How far apart the sources and `σ`s of two waves that are this one may lie
    /// ([`same_source_slack`] in the entering edge's frame); a target that carries the
    /// same wave lies at most four times this above its straight value.
    same_source_slack: f64,
}

/// The slot of face record `r` that Steiner node `node` lies on.
fn slot_of(r: &FaceRecord, node: u32) -> Option<usize> {
    (0..3).find(|&s| node.wrapping_sub(r.lo[s]) < r.count(s))
}

#[cfg(test)]
mod tests {
    use crate::field::Wave;
    use crate::flat::{hinge, EdgeFrame, P};
    use crate::mesh::FaceFrame;

    /// The edge from (0, 0) to (2, 0) of the face with corner (0.5, 1.5), seen from it; a
    /// wave from S = (0.8, −1) (in the edge's frame: x = 0.8, y = 1 behind the edge) with
    /// the window [w0, w1] of the edge.
    fn setup(w0: f32, w1: f32) -> (Wave, EdgeFrame) {
        let face = FaceFrame {
            l01: 2.0,
            x2: 0.5,
            y2: 1.5,
        };
        let frame = EdgeFrame::new(&face, 0, false);
        let wave = Wave {
            sx: 0.8,
            sy: 1.0,
            sigma: 0.3,
            w0,
            w1,
        };
        (wave, frame)
    }

    #[test]
    fn a_line_that_misses_the_window_bends_at_its_nearest_end() {
        let (wave, frame) = setup(0.25, 0.75);
        let source = P(0.8, -1.0);
        // Inside the window: no hinge; outside on either side: that side's end.
        assert!(hinge(&wave, &frame, 0.5).is_none());
        let (lo, lo_sigma) = hinge(&wave, &frame, 0.1).unwrap();
        assert_eq!(lo, P(0.5, 0.0));
        assert!((lo_sigma - (0.3 + lo.sub(source).length())).abs() < 1e-15);
        assert_eq!(hinge(&wave, &frame, 0.9).unwrap().0, P(1.5, 0.0));
        assert!(hinge(&wave, &frame, f64::NAN).is_none());
        // The bend at the end is the shortest path through the window to a target whose
        // line crosses outside it: shorter than through any other point of the window
        // (the node's among them), never shorter than the straight line.
        let target = P(1.8, 0.15);
        let x = frame.crossing(source, target);
        assert!(x > 0.75, "{x}");
        let (h, sigma) = hinge(&wave, &frame, x).unwrap();
        let bent = sigma + target.sub(h).length();
        for i in 0..=100 {
            let w = P(0.5 + i as f64 / 100.0, 0.0);
            let through = 0.3 + w.sub(source).length() + target.sub(w).length();
            assert!(bent <= through + 1e-15, "{bent} > {through} through {w:?}");
        }
        assert!(bent > 0.3 + target.sub(source).length());
    }

    #[test]
    fn window_ends_at_vertices_are_no_hinges() {
        // A window that reaches a vertex: the vertex offers that bend itself.
        let (wave, frame) = setup(0.0, 1.0);
        assert!(hinge(&wave, &frame, -0.5).is_none() && hinge(&wave, &frame, 1.5).is_none());
        let (wave, frame) = setup(0.0, 0.5);
        assert!(hinge(&wave, &frame, -0.5).is_none());
        assert_eq!(hinge(&wave, &frame, 0.9).unwrap().0, P(1.0, 0.0));
    }
}
