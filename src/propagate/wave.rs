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
//! and the polyline value `d(q) + |q t|` (bending at the node) otherwise. A target that
//! takes the straight value inherits `S` and `σ`, with the window projected from `S`
//! onto its own edge; one that takes the polyline value gets a fresh wave: a source at
//! the node, `σ = d(q)`, the whole edge as window.
//!
//! Vertices do not carry waves: a geodesic bends at a saddle vertex and never passes
//! through a convex one, so a vertex always starts a fresh wave (a point source). Waves
//! do not cross an edge whose faces do not glue isometrically (two tensors that give it
//! different lengths: a refraction), nor go back into the face they came from.
//!
//! # Why values are never below the true distance
//! Every value is the length of a real path: a polyline value is a node's value plus a
//! straight segment inside one face; a straight value is `σ` plus a straight line from
//! `S` that crosses the entering node's window, and by induction every line from `S`
//! through a window is a path that exists: the window of a node that inherited a wave
//! is the set of points of its edge that lines from `S` reach through its parent's
//! window and across the face between them. So the engine can only overestimate
//! (where a wave was lost), never take a shortcut off the surface. Windows are closed
//! intervals widened by `1e-9` of the edge's length against rounding, which bounds any
//! shortcut by that much.
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
//! per edge this engine needs, a face has a handful of targets). Values, parents and
//! the bucket queue are the other engines'; each Steiner node adds a 40-byte wave.

use super::frontier::{Frontier, Queue, Seed};
use super::tracks::{FaceRecord, TrackTables};
use crate::mesh::{FaceFrame, TriMesh, NONE};
use crate::surface::Source;
use geotracks_metrics::{FacePoint, Metric};

/// The wave a Steiner node carries, in the frame of its edge: `x` along the edge from
/// its lower vertex, `y` across it towards the interior of the face the wave came from
/// (`face`). Lengths are in the metric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Wave {
    /// The virtual source.
    pub sx: f64,
    pub sy: f64,
    /// The path length up to the source.
    pub sigma: f64,
    /// The window, as fractions of the edge's length from its lower vertex.
    pub w0: f32,
    pub w1: f32,
    /// The face the wave came through (mesh id; `NONE`: from a source on the edge's
    /// own line, valid in every face around it).
    pub face: u32,
}

impl Wave {
    /// No wave (vertices, unreached nodes).
    pub const NONE: Wave = Wave {
        sx: 0.0,
        sy: 0.0,
        sigma: f64::INFINITY,
        w0: 1.0,
        w1: 0.0,
        face: NONE,
    };

    fn is_some(&self) -> bool {
        self.w0 <= self.w1
    }
}

/// Slack on window tests, as a fraction of the edge. Window ends are rounded inwards to
/// `f32`, and a line through a vertex (common on regular grids) crosses its edges at
/// their very ends, so the slack must cover a few `f32` units. A line that passes a
/// vertex on the wrong side by `δ` is shorter than the real path bending there by
/// about `δ² / ℓ` only: with `δ = 1e-6` of an edge, 1e-12 relative.
const WINDOW_SLACK: f64 = 1e-6;
/// Two values this close (relative) are a tie.
const TIE: f64 = 1e-12;
/// Two windows of one wave are joined when they meet to this fraction of the edge:
/// their ends are rounded inwards to `f32` (a few units in the last place apart where
/// they meet), and a real gap between them (the shadow of a vertex) is far wider.
const TOUCH: f32 = 1e-6;
/// Two waves are the same when their sources and σ agree to this, relative to the
/// edge's length and the source's distance.
const SAME_SOURCE: f64 = 1e-9;

/// A point of the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
struct P(f64, f64);

impl P {
    #[inline(always)]
    fn sub(self, o: P) -> P {
        P(self.0 - o.0, self.1 - o.1)
    }
    #[inline(always)]
    fn add(self, o: P) -> P {
        P(self.0 + o.0, self.1 + o.1)
    }
    #[inline(always)]
    fn scale(self, k: f64) -> P {
        P(self.0 * k, self.1 * k)
    }
    #[inline(always)]
    fn dot(self, o: P) -> f64 {
        self.0 * o.0 + self.1 * o.1
    }
    #[inline(always)]
    fn cross(self, o: P) -> f64 {
        self.0 * o.1 - self.1 * o.0
    }
    #[inline(always)]
    fn length(self) -> f64 {
        FacePoint {
            uv: [0.0, 0.0],
            bary: [0.0; 3],
        }
        .distance(&FacePoint {
            uv: [self.0, self.1],
            bary: [0.0; 3],
        })
    }
}

fn uv(p: &FacePoint) -> P {
    P(p.uv[0], p.uv[1])
}

/// An edge seen from one face (in the face's flattened frame): its lower vertex `lo`,
/// unit direction `u` towards its higher vertex, length `len`, and unit normal `n`
/// pointing into the face.
#[derive(Clone, Copy, Debug)]
struct EdgeFrame {
    lo: P,
    u: P,
    n: P,
    len: f64,
}

impl EdgeFrame {
    /// Slot `s` of `frame`; `reversed` when the slot runs from the edge's higher vertex.
    #[inline]
    fn new(frame: &FaceFrame, s: usize, reversed: bool) -> EdgeFrame {
        let c = frame.corners();
        let (a, b) = (P(c[s][0], c[s][1]), P(c[(s + 1) % 3][0], c[(s + 1) % 3][1]));
        let opposite = P(c[(s + 2) % 3][0], c[(s + 2) % 3][1]);
        let (lo, hi) = if reversed { (b, a) } else { (a, b) };
        let d = hi.sub(lo);
        let len = d.length();
        let u = d.scale(1.0 / len);
        let mut n = P(-u.1, u.0);
        if opposite.sub(lo).dot(n) < 0.0 {
            n = n.scale(-1.0);
        }
        EdgeFrame { lo, u, n, len }
    }

    /// The face point of `p` in edge coordinates (`y` into the face).
    #[inline]
    fn edge_coords(&self, p: P) -> (f64, f64) {
        let d = p.sub(self.lo);
        (d.dot(self.u), d.dot(self.n))
    }

    /// The point at edge coordinates `(x, y)`, `y` into the face.
    #[inline]
    fn at_edge_coords(&self, x: f64, y: f64) -> P {
        self.lo.add(self.u.scale(x)).add(self.n.scale(y))
    }

    /// Where the line from `s` through `t` crosses the edge's line, as a fraction of
    /// the edge from its lower vertex (`NaN` when parallel).
    #[inline]
    fn crossing(&self, s: P, t: P) -> f64 {
        let (sx, sy) = self.edge_coords(s);
        let (tx, ty) = self.edge_coords(t);
        // y goes from sy to ty; it is 0 at λ = sy / (sy − ty).
        let lambda = sy / (sy - ty);
        (sx + lambda * (tx - sx)) / self.len
    }
}

/// Settles nodes until the run is over ([`Frontier::next`]). `waves` holds one
/// [`Wave`] per Steiner node (reset by the caller); `seeds` are the sources' offers,
/// already given to their nodes; `sources` the run's (validated) sources.
pub(super) fn propagate<M: Metric, Q: Queue>(
    search: &mut Frontier<'_, M, Q>,
    tables: &TrackTables,
    isometric: &[bool],
    waves: &mut [Wave],
    seeds: &[Seed],
    sources: &[Source],
) {
    let vertex_count = search.layout.vertex_count();
    let mut run = Waves {
        search,
        tables,
        isometric,
        waves,
        vertex_count,
    };
    run.seed_waves(seeds, sources);
    while let Some((q, d)) = run.search.next() {
        if q < vertex_count {
            run.settle_vertex(q, d);
        } else {
            run.settle_steiner(q, d);
        }
    }
}

struct Waves<'r, 'a, M, Q> {
    search: &'r mut Frontier<'a, M, Q>,
    tables: &'r TrackTables,
    /// Per edge block: whether every face around the edge gives it the same length.
    isometric: &'r [bool],
    waves: &'r mut [Wave],
    vertex_count: u32,
}

impl<M: Metric, Q: Queue> Waves<'_, '_, M, Q> {
    fn wave(&self, node: u32) -> &Wave {
        &self.waves[(node - self.vertex_count) as usize]
    }

    fn wave_mut(&mut self, node: u32) -> &mut Wave {
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
            if self.search.distance[seed.node as usize] != seed.value {
                continue;
            }
            let Some(point) = sources[seed.source as usize].point.in_face(mesh, seed.face) else {
                continue;
            };
            let r = &self.tables.faces[self.tables.record_of(seed.face) as usize];
            let Some(s) = (0..3).find(|&s| seed.node.wrapping_sub(r.lo[s]) < r.count(s)) else {
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
                // A source on the edge's line is valid in every face around it.
                face: if sy > 0.0 { seed.face } else { NONE },
            };
        }
    }

    fn settle_vertex(&mut self, v: u32, d: f64) {
        let tables = self.tables;
        let mesh = self.search.mesh;
        let layout = self.search.layout;
        for &e in mesh.vertex_edges(v) {
            let nodes = layout.edge_nodes(e);
            let ends = mesh.edge_vertices(e);
            let step = tables.edges[layout.block_of_edge(e) as usize].step;
            let next = match (nodes.is_empty(), v == ends[0]) {
                (true, true) => ends[1],
                (true, false) => ends[0],
                (false, true) => nodes.start,
                (false, false) => nodes.end - 1,
            };
            self.along_edge(v, d, next, step, None);
        }
        let parent_face = self.search.parent_face[v as usize];
        for &f in mesh.vertex_faces(v) {
            if f == parent_face {
                continue;
            }
            let r = &tables.faces[tables.record_of(f) as usize];
            let c = (0..3).find(|&c| r.vertex[c] == v).unwrap_or(0);
            let opposite = (c + 1) % 3;
            let slot = r.slot(opposite);
            if slot.count == 0 {
                continue;
            }
            let pq = uv(&r.corner_point(c));
            for i in 0..slot.count {
                let (t, pt) = slot.at(i);
                let pt = uv(&pt);
                self.search.tests += 1;
                let value = d + pt.sub(pq).length();
                self.offer_polyline(t, value, v, f, r, opposite, pq, d);
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
        let mesh = self.search.mesh;
        let ends = || mesh.edge_vertices(layout.edge_of_block(block));
        let wave = *self.wave(q);
        // Along the edge: the next nodes, straight from the wave where they are in it.
        let prev = if index == 0 { ends()[0] } else { q - 1 };
        let next = if index + 1 == count { ends()[1] } else { q + 1 };
        let spacing = 1.0 / (count + 1) as f64;
        let own = (index + 1) as f64 * spacing;
        self.along_edge(q, d, prev, edge.step, Some((wave, own - spacing)));
        self.along_edge(q, d, next, edge.step, Some((wave, own + spacing)));

        let parent_face = self.search.parent_face[q as usize];
        let iso = self.isometric[block as usize];
        for &inc in tables.edge_faces(edge) {
            let r = &tables.faces[inc.record() as usize];
            let f = r.face;
            if f == parent_face || (wave.is_some() && f == wave.face && wave.face != NONE) {
                continue;
            }
            let s = inc.side();
            let frame = EdgeFrame::new(&r.frame, s, r.is_reversed(s));
            let pq = frame.at_edge_coords(own * frame.len, 0.0);
            // The wave unfolded into this face: behind the edge.
            let source = (wave.is_some() && iso).then(|| frame.at_edge_coords(wave.sx, -wave.sy));
            // Targets: the points of the two other slots and the opposite corner.
            for step in 1..3 {
                let ts = (s + step) % 3;
                let slot = r.slot(ts);
                for i in 0..slot.count {
                    let (t, pt) = slot.at(i);
                    self.offer(q, d, &wave, source, &frame, pq, t, uv(&pt), r, ts, f);
                }
                if step == 1 {
                    let c = (s + 2) % 3;
                    let t = r.vertex[c];
                    self.offer(
                        q,
                        d,
                        &wave,
                        source,
                        &frame,
                        pq,
                        t,
                        uv(&r.corner_point(c)),
                        r,
                        3,
                        f,
                    );
                }
            }
        }
    }

    /// `from` (at value `d`) offers `to`, its neighbour along an edge `step` away; with
    /// `from`'s wave and `to`'s position on the edge (as a fraction) when `from` is a
    /// Steiner point, which passes the wave on where `to` lies in its window.
    fn along_edge(&mut self, from: u32, d: f64, to: u32, step: f64, wave: Option<(Wave, f64)>) {
        let mut value = d + step;
        let mut carried = None;
        if let Some((w, at)) = wave {
            if w.is_some() && in_window(&w, at) {
                // The edge's length: the spacing is `step`, `at` moves by one spacing.
                let block = self.search.layout.block(from);
                let count = self.search.layout.block_nodes(block).len() as f64;
                let len = step * (count + 1.0);
                let straight = w.sigma + P(w.sx - at * len, w.sy).length();
                if straight < value {
                    value = straight;
                    carried = Some(w);
                }
            }
        }
        self.search.tests += 1;
        let previous = self.search.distance[to as usize];
        let sigma = carried.map_or(d, |w| w.sigma);
        if self.keeps_wave(to, value, sigma) {
            return;
        }
        self.search.relax(to, value, from, NONE);
        if to >= self.vertex_count && self.search.distance[to as usize] < previous {
            *self.wave_mut(to) = match carried {
                Some(w) => w,
                None => {
                    // A fresh wave from `from`, on the edge's own line.
                    let block = self.search.layout.block(to);
                    let count = self.search.layout.block_nodes(block).len() as f64;
                    let len = self.tables.edges[block as usize].step * (count + 1.0);
                    let from_at = self.position_on_edge(from, to) * len;
                    Wave {
                        sx: from_at,
                        sy: 0.0,
                        sigma: d,
                        w0: 0.0,
                        w1: 1.0,
                        face: NONE,
                    }
                }
            };
        }
    }

    /// Whether Steiner node `t` keeps its wave against an offer of `value` from a wave
    /// that started at `sigma`: when the offer ties with its value (within rounding)
    /// and its own wave started no later. On a line through a vertex from a source,
    /// the vertex's fresh wave gives the same value as the source's, and may come a
    /// unit in the last place lower; taking it would bend every line beyond.
    #[inline]
    fn keeps_wave(&self, t: u32, value: f64, sigma: f64) -> bool {
        if t < self.vertex_count {
            return false;
        }
        let previous = self.search.distance[t as usize];
        let current = self.wave(t);
        value >= previous - TIE * previous.abs() && current.is_some() && current.sigma <= sigma
    }

    /// Where node `node` (a neighbour of Steiner node `on` along its edge, or one of the
    /// edge's vertices) lies along `on`'s edge, as a fraction from its lower vertex.
    fn position_on_edge(&self, node: u32, on: u32) -> f64 {
        let layout = self.search.layout;
        let block = layout.block(on);
        let nodes = layout.block_nodes(block);
        let count = nodes.len() as f64;
        if nodes.contains(&node) {
            (node - nodes.start + 1) as f64 / (count + 1.0)
        } else {
            let lo = self.search.mesh.edge_vertices(layout.edge_of_block(block))[0];
            if node == lo {
                0.0
            } else {
                1.0
            }
        }
    }

    /// Steiner node `q` (value `d`, wave `wave`, unfolded here as `source`; its edge
    /// `frame`, its point `pq`) offers target `t` at `pt` in the face of record `r`,
    /// on slot `ts` (3: the opposite corner).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn offer(
        &mut self,
        q: u32,
        d: f64,
        wave: &Wave,
        source: Option<P>,
        frame: &EdgeFrame,
        pq: P,
        t: u32,
        pt: P,
        r: &FaceRecord,
        ts: usize,
        f: u32,
    ) {
        self.search.tests += 1;
        let polyline = d + pt.sub(pq).length();
        let Some(s) = source else {
            self.offer_polyline(t, polyline, q, f, r, ts, pq, d);
            return;
        };
        let x = frame.crossing(s, pt);
        if in_window(wave, x) {
            let straight = wave.sigma + pt.sub(s).length();
            if straight <= polyline {
                self.offer_straight(t, straight, q, f, r, ts, s, wave, frame);
                return;
            }
        } else if t >= self.vertex_count && ts < 3 {
            self.merge(t, wave, s, frame, r, ts, f);
        }
        self.offer_polyline(t, polyline, q, f, r, ts, pq, d);
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
        let previous = self.search.distance[t as usize];
        if value >= previous || value.is_nan() || self.keeps_wave(t, value, d) {
            return;
        }
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
                face: f,
            };
        }
    }

    /// A straight offer from `wave`, whose source is `s` in this face, through the
    /// window on the entering edge `frame`.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn offer_straight(
        &mut self,
        t: u32,
        value: f64,
        from: u32,
        f: u32,
        r: &FaceRecord,
        ts: usize,
        s: P,
        wave: &Wave,
        frame: &EdgeFrame,
    ) {
        let previous = self.search.distance[t as usize];
        let steiner = t >= self.vertex_count && ts < 3;
        if steiner && value >= previous - TIE * previous.abs() {
            // A tie (within rounding): the same wave through another entry joins its
            // window; a wave that started earlier replaces the node's (a vertex on the
            // line from a source gives the same value, but a new wave that bends
            // there: the earlier one is the one to carry on).
            if value > previous + TIE * previous.abs() {
                return;
            }
            let current = *self.wave(t);
            if current.is_some() && wave.sigma >= current.sigma - TIE * previous.abs() {
                self.merge(t, wave, s, frame, r, ts, f);
                return;
            }
            let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
            let (w0, w1) = project(wave, s, frame, &tf);
            let (sx, sy) = tf.edge_coords(s);
            *self.wave_mut(t) = Wave {
                sx,
                sy: sy.max(0.0),
                sigma: wave.sigma,
                w0,
                w1,
                face: f,
            };
            self.join_edges(t, r, f, ts, &tf);
            if value < previous {
                self.search.relax(t, value, from, f);
            } else {
                self.search.requeue(t);
            }
            return;
        }
        if value >= previous || value.is_nan() {
            return;
        }
        self.search.relax(t, value, from, f);
        if t >= self.vertex_count && self.search.distance[t as usize] < previous {
            let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
            let (w0, w1) = project(wave, s, frame, &tf);
            let (sx, sy) = tf.edge_coords(s);
            *self.wave_mut(t) = Wave {
                sx,
                sy: sy.max(0.0),
                sigma: wave.sigma,
                w0,
                w1,
                face: f,
            };
            // The same wave may also enter this face through its third edge, and see
            // the rest of `t`'s edge from there.
            self.join_edges(t, r, f, ts, &tf);
        }
    }

    /// Joins to `t`'s window (on slot `ts` of record `r`, seen as `tf`) the parts of its
    /// edge that the nodes of the face's two other slots see through their windows,
    /// where they carry the same wave into this face. Called whenever `t`'s window
    /// changes, so that joins do not depend on the order nodes settle in.
    fn join_edges(&mut self, t: u32, r: &FaceRecord, f: u32, ts: usize, tf: &EdgeFrame) {
        let tw = *self.wave(t);
        if !tw.is_some() {
            return;
        }
        let st = tf.at_edge_coords(tw.sx, tw.sy);
        let (mut w0, mut w1) = (tw.w0, tw.w1);
        for other in [(ts + 1) % 3, (ts + 2) % 3] {
            let slot = r.slot(other);
            if slot.count == 0 {
                continue;
            }
            let of = EdgeFrame::new(&r.frame, other, r.is_reversed(other));
            for i in 0..slot.count {
                let (o, _) = slot.at(i);
                let ow = *self.wave(o);
                if !ow.is_some()
                    || ow.face == f
                    || !self.isometric[self.search.layout.block(o) as usize]
                {
                    continue;
                }
                let so = of.at_edge_coords(ow.sx, -ow.sy);
                if !same_source(st, tw.sigma, so, ow.sigma, tf.len) {
                    continue;
                }
                let (o0, o1) = project(&ow, so, &of, tf);
                if o0 <= o1 && o0 <= w1 + TOUCH && w0 <= o1 + TOUCH {
                    w0 = w0.min(o0);
                    w1 = w1.max(o1);
                }
            }
        }
        let wave = self.wave_mut(t);
        wave.w0 = w0;
        wave.w1 = w1;
    }

    /// Joins to target `t`'s window the part of its edge that `wave` (source `s` here)
    /// reaches through the window on `frame`, when `t` carries the same wave through
    /// this face and the two parts touch; a settled `t` is queued again so that it
    /// offers through the wider window.
    #[allow(clippy::too_many_arguments)]
    fn merge(
        &mut self,
        t: u32,
        wave: &Wave,
        s: P,
        frame: &EdgeFrame,
        r: &FaceRecord,
        ts: usize,
        f: u32,
    ) {
        let current = *self.wave(t);
        if !current.is_some() || current.face != f {
            return;
        }
        let tf = EdgeFrame::new(&r.frame, ts, r.is_reversed(ts));
        let st = tf.at_edge_coords(current.sx, current.sy);
        if !same_source(st, current.sigma, s, wave.sigma, tf.len) {
            return;
        }
        let (w0, w1) = project(wave, s, frame, &tf);
        if w0 > w1 {
            return;
        }
        let touch = w0 <= current.w1 + TOUCH && current.w0 <= w1 + TOUCH;
        let (n0, n1) = (w0.min(current.w0), w1.max(current.w1));
        if touch && (n0 < current.w0 || n1 > current.w1) {
            let wave = self.wave_mut(t);
            wave.w0 = n0;
            wave.w1 = n1;
            self.join_edges(t, r, f, ts, &tf);
            self.search.requeue(t);
        }
    }
}

/// Whether two waves have the same source (points `a`, `b` of one face's plane, path
/// lengths `sa`, `sb` up to them), to [`SAME_SOURCE`] of their scale.
#[inline]
fn same_source(a: P, sa: f64, b: P, sb: f64, len: f64) -> bool {
    let scale = len + a.0.abs() + a.1.abs() + sa.abs();
    (a.0 - b.0).abs() <= SAME_SOURCE * scale
        && (a.1 - b.1).abs() <= SAME_SOURCE * scale
        && (sa - sb).abs() <= SAME_SOURCE * scale
}

/// Whether fraction `x` of the edge lies in `wave`'s window (widened by the slack).
#[inline(always)]
fn in_window(wave: &Wave, x: f64) -> bool {
    x >= wave.w0 as f64 - WINDOW_SLACK && x <= wave.w1 as f64 + WINDOW_SLACK
}

/// The window on the edge `to` of the lines from `s` through `wave`'s window on the
/// edge `from` (both seen in one face, which `s` lies behind `from` of): fractions of
/// `to`, rounded inwards to `f32`; empty (`w0 > w1`) when no such line reaches `to`.
fn project(wave: &Wave, s: P, from: &EdgeFrame, to: &EdgeFrame) -> (f32, f32) {
    const EMPTY: (f32, f32) = (1.0, 0.0);
    if wave.sy == 0.0 {
        // A source on the edge itself (a point of it, reached along it): it lies on
        // the closure of every face around the edge, which it sees whole.
        return (0.0, 1.0);
    }
    // Where the lines from s to the ends of `to` cross `from`'s line: the crossing is
    // monotone along `to` (s is behind `from`, `to` in front of it), so the window's
    // preimage is the interval between the points of `to` whose lines cross at its ends.
    let (a, b) = (to.lo, to.lo.add(to.u.scale(to.len)));
    let (xa, xb) = (from.crossing(s, a), from.crossing(s, b));
    if xa.is_nan() || xb.is_nan() {
        return EMPTY;
    }
    let (lo_x, hi_x) = (xa.min(xb), xa.max(xb));
    let (w0, w1) = ((wave.w0 as f64).max(lo_x), (wave.w1 as f64).min(hi_x));
    if w0 > w1 {
        return EMPTY;
    }
    let increasing = xa <= xb;
    // The fraction of `to` whose line from s crosses `from` at x.
    let y = |x: f64| -> f64 {
        if x <= lo_x {
            return if increasing { 0.0 } else { 1.0 };
        }
        if x >= hi_x {
            return if increasing { 1.0 } else { 0.0 };
        }
        let dir = from.lo.add(from.u.scale(x * from.len)).sub(s);
        // s + μ·dir = to.lo + y·len·u; crossed with dir: (s − lo) × dir = y·len·(u × dir).
        let denom = to.u.cross(dir) * to.len;
        (s.sub(to.lo).cross(dir) / denom).clamp(0.0, 1.0)
    };
    let (ya, yb) = (y(w0), y(w1));
    // Rounded outwards: a window end that is a unit in the last place of an `f32` too
    // tight would, through a needle, grow into a gap where two windows should meet,
    // and a line that passes a vertex by that much on the wrong side is shorter than
    // the real path by a negligible amount (see WINDOW_SLACK).
    (round_down(ya.min(yb)), round_up(ya.max(yb)))
}

fn round_up(x: f64) -> f32 {
    let v = x as f32;
    if (v as f64) < x {
        v.next_up()
    } else {
        v
    }
}

fn round_down(x: f64) -> f32 {
    let v = x as f32;
    if (v as f64) > x {
        v.next_down()
    } else {
        v
    }
}

/// Per edge (in the layout's block order): whether every face around it gives it the
/// same flattened length (to 1e-9), so that waves cross it unbent.
pub(super) fn isometric_edges(
    mesh: &TriMesh,
    layout: &crate::steiner::SteinerLayout,
    tables: &TrackTables,
) -> Vec<bool> {
    let layout_blocks = tables.edges.len();
    let mut iso = vec![true; layout_blocks];
    let mut first = vec![f64::NAN; layout_blocks];
    for r in &tables.faces {
        let edges = mesh.face_edges(r.face);
        let c = r.frame.corners();
        for s in 0..3 {
            let b = layout.block_of_edge(edges[s]) as usize;
            let (a, z) = (c[s], c[(s + 1) % 3]);
            let len = P(z[0] - a[0], z[1] - a[1]).length();
            if first[b].is_nan() {
                first[b] = len;
            } else if (len - first[b]).abs() > 1e-9 * first[b] {
                iso[b] = false;
            }
        }
    }
    iso
}

#[cfg(test)]
mod tests {

    use super::{project, EdgeFrame, Wave, P};

    fn edge(lo: P, hi: P, inside: P) -> EdgeFrame {
        let d = hi.sub(lo);
        let len = d.length();
        let u = d.scale(1.0 / len);
        let mut n = P(-u.1, u.0);
        if inside.sub(lo).dot(n) < 0.0 {
            n = n.scale(-1.0);
        }
        EdgeFrame { lo, u, n, len }
    }

    #[test]
    fn projection_of_a_full_window() {
        let (a, b, c) = (P(0.0, 0.0), P(1.0, 0.0), P(0.5, 1.0));
        let from = edge(a, b, c);
        let to = edge(b, c, a);
        let wave = Wave {
            sx: 0.5,
            sy: 1.0,
            sigma: 0.0,
            w0: 0.0,
            w1: 1.0,
            face: 0,
        };
        assert_eq!(project(&wave, P(0.5, -1.0), &from, &to), (0.0, 1.0));
        // Half the window: the lines through [0.5, 1] reach all of `to`, [0, 0.5] none.
        let half = Wave {
            w0: 0.5,
            w1: 1.0,
            ..wave
        };
        assert_eq!(project(&half, P(0.5, -1.0), &from, &to), (0.0, 1.0));
        let other = Wave {
            w0: 0.0,
            w1: 0.5,
            ..wave
        };
        let (w0, w1) = project(&other, P(0.5, -1.0), &from, &to);
        assert!(w1 - w0 < 1e-6, "{w0} {w1}");
        // A source far to the left: lines through [0, 0.5] reach part of `to`.
        let s = P(-3.0, -1.0);
        let (w0, w1) = project(&wave, s, &from, &to);
        assert!(w0 == 0.0 && w1 > 0.0 && w1 <= 1.0, "{w0} {w1}");
    }
}
