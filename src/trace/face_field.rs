//! The field inside one face, as the engine defines it: the least of a few *candidates*,
//! each a real path's length — a node's value plus the straight segment from it, a
//! source's start plus its segment, or (wavefront engine) a wave's `σ` plus the straight
//! line from its virtual source through its window, or bending at the window's end.
//!
//! Every query at a point of the face reads this one list: the distance
//! ([`Field::distance_at`](crate::Field::distance_at)), which candidate gives it ([`ValueSource`]), the gradient
//! ([`Field::gradient_at`](crate::Field::gradient_at)) and the face's regions ([`Field::regions`](crate::Field::regions)), so they agree
//! by construction.

use super::Query;
use crate::flat::{flat_frame, hinge_end, uv, wave_value_on_edge, EdgeFrame, P, WINDOW_SLACK};
use crate::mesh::FaceFrame;
use crate::mesh::Topology;
use geotracks_metrics::{FacePoint, Metric};
use glam::DVec3;

/// What gives the distance at a point: one candidate of the face it lies in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ValueSource {
    /// Straight from this node (a vertex or Steiner point on the face's boundary): the
    /// node's value plus the metric length of the segment.
    Node(u32),
    /// Straight from this source of the run (an index into its sources), which lies on
    /// the face's closure: its start plus the segment.
    Source(u32),
    /// Straight from the virtual source of this Steiner node's wave (wavefront engine):
    /// the wave's `σ` plus the straight line from its source, which crosses the node's
    /// edge inside the node's window.
    Wave(u32),
    /// This Steiner node's wave bending at an end of its window (where the straight line
    /// from its source would miss the window): the path to the window's end plus the
    /// segment from there.
    WaveBend(u32),
    /// Straight from the virtual source of this window of the exact engine (an id of
    /// the run's): its `σ` plus the straight line from its source, which crosses the
    /// window's part of its edge.
    Window(u32),
}

/// Where a candidate's paths come from.
#[derive(Clone, Copy, Debug)]
pub(super) enum Site {
    /// A point of the face's flattened plane, seen from all of the face.
    Flat(P),
    /// A point of the flattened plane (behind an edge) whose lines count only where they
    /// cross the window (and, unfolded from a neighbour, also the shared edge).
    Windowed {
        at: P,
        window: Window,
        also: Option<Window>,
    },
    /// A point of the face under a metric that does not flatten faces: the segment's
    /// cost is the metric's.
    Metric(FacePoint),
}

/// Part of an edge (fractions `w0..=w1` from its lower end) that a candidate's lines
/// must cross, the edge seen in the plane of the face the candidate serves.
#[derive(Clone, Copy, Debug)]
pub(super) struct Window {
    pub edge: EdgeFrame,
    pub w0: f64,
    pub w1: f64,
}

impl Window {
    /// Whether the line from `s` through `x` crosses the window (widened by the slack).
    #[inline]
    fn passes(&self, s: P, x: P) -> bool {
        let cross = self.edge.crossing(s, x);
        cross >= self.w0 - WINDOW_SLACK && cross <= self.w1 + WINDOW_SLACK
    }

    /// The window seen through `map` (a rigid motion of the plane, given as the images
    /// of a point and of two vectors).
    fn mapped(&self, map: &Unfold) -> Window {
        let e = &self.edge;
        Window {
            edge: EdgeFrame {
                lo: map.point(e.lo),
                u: map.vector(e.u),
                n: map.vector(e.n),
                len: e.len,
            },
            ..*self
        }
    }
}

/// The unfolding of a neighbour's plane onto a face's across their shared edge: a
/// point at edge coordinates `(x, y)` seen from the neighbour (`y` into it) is at
/// `(x, −y)` seen from the face.
struct Unfold {
    from: EdgeFrame,
    to: EdgeFrame,
}

impl Unfold {
    fn point(&self, p: P) -> P {
        let (x, y) = self.from.edge_coords(p);
        self.to.at_edge_coords(x, -y)
    }

    fn vector(&self, v: P) -> P {
        let (x, y) = (v.dot(self.from.u), v.dot(self.from.n));
        self.to.u.scale(x).sub(self.to.n.scale(y))
    }
}

/// One candidate: `sigma` plus the length of the path from its site.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub source: ValueSource,
    pub sigma: f64,
    pub site: Site,
    /// For a neighbour's candidate unfolded onto the face: the edge its lines cross
    /// and the neighbour.
    pub across: Option<(u32, u32)>,
    /// No value of the candidate in the face is below this (σ, plus the distance from
    /// the site to the face where the metric flattens it).
    pub floor: f64,
}

/// A face's candidates, ready to be evaluated at many points.
pub(super) struct FaceField {
    pub face: u32,
    /// The face's frame in the metric's flattening (`None`: the metric does not flatten).
    pub flat: Option<FaceFrame>,
    pub candidates: Vec<Candidate>,
    /// Nodes of the face (and, unfolded, of the faces across its edges) that the run
    /// left unreached when it stopped early: a point they might give less than its
    /// value is unreached too.
    pub unreached: Vec<Site>,
    /// Whether the field's nodes carry waves (the wavefront engine's), whose values at
    /// a point can be less than the node's.
    pub waves: bool,
}

impl FaceField {
    /// The flattened position of face point `x` (`None` without a flattening).
    pub fn flat_point(&self, x: &FacePoint) -> Option<P> {
        self.flat.map(|frame| uv(&frame.point(x.bary)))
    }

    /// Candidate `c`'s value at face point `x` (flattened `px`), or `None` where its
    /// paths do not reach (outside its window).
    #[inline]
    pub fn value_of<M: Metric>(
        &self,
        metric: &M,
        c: &Candidate,
        x: &FacePoint,
        px: Option<P>,
    ) -> Option<f64> {
        match (c.site, px) {
            (Site::Flat(s), Some(px)) => Some(c.sigma + px.sub(s).length()),
            (Site::Windowed { at, window, also }, Some(px)) => {
                let inside = window.passes(at, px) && also.is_none_or(|w| w.passes(at, px));
                inside.then(|| c.sigma + px.sub(at).length())
            }
            (Site::Metric(p), _) => Some(c.sigma + metric.cost(self.face, &p, x)),
            _ => None,
        }
    }

    /// The least value at face point `x` and the candidate giving it (ties to the
    /// first), skipping candidates for which `skip` holds.
    pub fn best<M: Metric>(
        &self,
        metric: &M,
        x: &FacePoint,
        skip: impl Fn(&Candidate) -> bool,
    ) -> Option<(f64, usize)> {
        let px = self.flat_point(x);
        let mut best: Option<(f64, usize)> = None;
        for (i, c) in self.candidates.iter().enumerate() {
            if best.is_some_and(|(b, _)| c.floor >= b) {
                // Sorted by floor: no later candidate can do better.
                break;
            }
            if skip(c) {
                continue;
            }
            if let Some(v) = self.value_of(metric, c, x, px) {
                if best.is_none_or(|(b, _)| v < b) {
                    best = Some((v, i));
                }
            }
        }
        best
    }

    /// As [`FaceField::best`] (skipping none), but of the candidates within
    /// `tolerance(least value)` of the least value, the one with the least `σ`: the
    /// farthest upstream. Where a node lies on the straight line from a source (or
    /// another node) to `x`, both give the same value, and the node is only a stop on
    /// the other's line; naming the source keeps such exact ties from cutting slivers
    /// into a face's regions.
    pub fn best_upstream<M: Metric>(
        &self,
        metric: &M,
        x: &FacePoint,
        tolerance: impl Fn(f64) -> f64,
    ) -> Option<(f64, usize)> {
        let (value, mut chosen) = self.best(metric, x, |_| false)?;
        let tolerance = tolerance(value);
        let px = self.flat_point(x);
        for (i, c) in self.candidates.iter().enumerate() {
            if c.floor > value + tolerance {
                break;
            }
            if c.sigma < self.candidates[chosen].sigma
                && self
                    .value_of(metric, c, x, px)
                    .is_some_and(|v| v <= value + tolerance)
            {
                chosen = i;
            }
        }
        Some((value, chosen))
    }

    /// For a neighbour's candidate (see [`Candidate::across`]), where the line from its
    /// site to face point `x` crosses the shared edge: a fraction from its lower end.
    pub fn crossing(&self, c: &Candidate, x: &FacePoint) -> Option<f64> {
        let px = self.flat_point(x)?;
        match c.site {
            Site::Windowed { at, window, also } => {
                let shared = also.unwrap_or(window);
                Some(shared.edge.crossing(at, px).clamp(0.0, 1.0))
            }
            _ => None,
        }
    }

    /// The least value an unreached node of the face could give `x` (`inf` when the
    /// run did not stop early), where `horizon` bounds such a node's value from below.
    ///
    /// A Steiner-graph node gives `x` its value plus the cost from it to `x`; a node's
    /// wave (the wavefront engine) may give less than the node's value, by up to that
    /// cost (its source lies behind the node, on the line through `x`).
    pub fn unsettled<M: Metric>(&self, metric: &M, horizon: f64, x: &FacePoint) -> f64 {
        let px = self.flat_point(x);
        let sign = if self.waves { -1.0 } else { 1.0 };
        self.unreached
            .iter()
            .map(|site| match (site, px) {
                (Site::Flat(p), Some(px)) => horizon + sign * px.sub(*p).length(),
                (Site::Metric(p), _) => horizon + sign * metric.cost(self.face, p, x),
                _ => f64::NEG_INFINITY,
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Where candidate `c`'s paths come from, as a point of the face's plane (unfolded
    /// there from the faces the wave crossed), in world coordinates.
    pub fn site_position<T: crate::mesh::Topology>(&self, mesh: &T, c: &Candidate) -> DVec3 {
        match (c.site, self.flat) {
            (Site::Flat(s) | Site::Windowed { at: s, .. }, Some(frame)) => {
                let [a, b] = flat_to_bary(&frame, s);
                let [p0, p1, p2] = mesh.face_vertices(self.face).map(|v| mesh.position(v));
                p0 + (p1 - p0) * a + (p2 - p0) * b
            }
            (Site::Metric(p), _) => mesh.point(self.face, p.bary),
            // A flat site without a flattening is never built.
            (_, None) => DVec3::NAN,
        }
    }
}

/// The barycentric weights `(b1, b2)` of corners 1 and 2 of the flattened point `s`
/// (any point of the plane; outside the face they leave `[0, 1]`).
pub(super) fn flat_to_bary(frame: &FaceFrame, s: P) -> [f64; 2] {
    // s = b1·c1 + b2·c2 with c1 = (l01, 0), c2 = (x2, y2).
    let b2 = s.1 / frame.y2;
    let b1 = (s.0 - b2 * frame.x2) / frame.l01;
    [b1, b2]
}

impl<M: Metric, T: Topology> Query<'_, M, T> {
    /// Face `f`'s candidates: its own (the nodes on its boundary, the sources on its
    /// closure and, wavefront engine, the waves that cross into it), and, for the
    /// wavefront engine, those of the faces across its edges, unfolded onto it (their
    /// lines through the shared edge). The latter make the field continuous
    /// across edges: at a point of an edge, every face around it sees what its
    /// neighbours see there.
    pub(super) fn face_field(&self, f: u32) -> FaceField {
        self.face_field_using(f, &mut Vec::new())
    }

    /// As [`Field::face_field`](crate::Field::face_field), taking the neighbours' own candidates from `own` (and
    /// adding those it lacks): a face's own candidates serve it and three neighbours.
    pub(super) fn face_field_using(&self, f: u32, own: &mut Vec<FaceField>) -> FaceField {
        let mut field = self.own_candidates(f);
        if let Some(frame) = field.flat {
            let triangle = frame.corners().map(|[x, y]| P(x, y));
            // Neighbours' candidates are windowed, so they leave this bound as it is.
            let bound = upper_bound(&field.candidates, &triangle);
            // Not for the other engines: their fields are the Steiner graph's, extended
            // into faces from their own nodes.
            if self.has_waves() && bound.is_finite() {
                self.push_neighbours(f, &frame, (&triangle, bound), &mut field, own);
            }
            // Only candidates that can give the least value somewhere in the face: no
            // less than σ plus the distance from the site to the face.
            for c in &mut field.candidates {
                if let Site::Flat(s) | Site::Windowed { at: s, .. } = c.site {
                    c.floor = c.sigma + distance_to_triangle(s, &triangle);
                }
            }
            field.candidates.retain(|c| c.floor <= bound);
        }
        // Cheapest first: `best` stops looking at a candidate whose floor is no less
        // than the best value found.
        field.candidates.sort_by(|a, b| a.floor.total_cmp(&b.floor));
        field
    }

    /// Face `f`'s own candidates (see [`Field::face_field`](crate::Field::face_field)), unsorted.
    fn own_candidates(&self, f: u32) -> FaceField {
        let (mesh, metric, field) = (self.mesh, self.metric, &self.field);
        let flat = flat_frame(metric, f, &mesh.frame(f));
        let to_site = |p: &FacePoint| match flat {
            Some(frame) => Site::Flat(uv(&frame.point(p.bary))),
            None => Site::Metric(*p),
        };
        let mut candidates = Vec::new();
        let mut unreached = Vec::new();
        for (node, p) in field.layout.face_nodes(mesh, f) {
            let g = field.distance[node as usize];
            if g < f64::INFINITY {
                candidates.push(Candidate {
                    source: ValueSource::Node(node),
                    sigma: g,
                    site: to_site(&p),
                    across: None,
                    floor: g,
                });
            } else if field.horizon.is_bounded() {
                unreached.push(to_site(&p));
            }
        }
        for (i, source) in field.sources.iter().enumerate() {
            if let Some(s) = source.point.in_face(mesh, f) {
                candidates.push(Candidate {
                    source: ValueSource::Source(i as u32),
                    sigma: source.start,
                    site: to_site(&s),
                    across: None,
                    floor: source.start,
                });
            }
        }
        if let (true, Some(frame)) = (self.has_waves(), flat) {
            self.push_waves(f, &frame, &mut candidates);
        }
        if let (true, Some(frame)) = (self.has_windows(), flat) {
            self.push_windows(f, &frame, &mut candidates);
        }
        FaceField {
            face: f,
            flat,
            candidates,
            unreached,
            waves: self.has_waves(),
        }
    }

    /// The own candidates of the faces across `f`'s edges (where waves cross unbent:
    /// the edge has one length in every face's flattening), unfolded onto `f`: lines
    /// from their sites that cross the shared edge. Sites on the edge or on `f`'s side
    /// of it are left out (`f` has them, or their lines do not cross), and so are those
    /// that cannot beat `bound`, the face's upper bound ([`upper_bound`]), anywhere in
    /// `triangle` (its flattened corners).
    fn push_neighbours(
        &self,
        f: u32,
        frame: &FaceFrame,
        (triangle, bound): (&[P; 3], f64),
        out: &mut FaceField,
        own: &mut Vec<FaceField>,
    ) {
        let mesh = self.mesh;
        for (slot, &edge) in mesh.face_edges(f).iter().enumerate() {
            if !self.glues(edge) {
                continue;
            }
            let to = self.edge_frame(frame, f, slot);
            let behind = -1e-12 * to.len;
            for &g in mesh.edge_faces(edge).iter() {
                if g == f {
                    continue;
                }
                let theirs = own_cached(self, g, own);
                let (Some(g_frame), Some(g_slot)) = (theirs.flat, mesh.edge_slot(g, edge)) else {
                    continue;
                };
                let map = Unfold {
                    from: self.edge_frame(&g_frame, g, g_slot),
                    to,
                };
                for site in &theirs.unreached {
                    if let Site::Flat(p) = site {
                        out.unreached.push(Site::Flat(map.point(*p)));
                    }
                }
                let shared = Window {
                    edge: to,
                    w0: 0.0,
                    w1: 1.0,
                };
                for c in &theirs.candidates {
                    let (at, window) = match c.site {
                        Site::Flat(s) => (map.point(s), shared),
                        Site::Windowed { at, window, .. } => (map.point(at), window.mapped(&map)),
                        Site::Metric(_) => continue,
                    };
                    if to.edge_coords(at).1 > behind
                        || c.sigma + distance_to_triangle(at, triangle) > bound
                    {
                        continue;
                    }
                    let also = matches!(c.site, Site::Windowed { .. }).then_some(shared);
                    out.candidates.push(Candidate {
                        source: c.source,
                        sigma: c.sigma,
                        site: Site::Windowed { at, window, also },
                        across: Some((edge, g)),
                        floor: c.sigma,
                    });
                }
            }
        }
    }

    /// The waves of the Steiner nodes on `f`'s boundary that cross into `f`: each a
    /// windowed candidate, and a bend at each end of its window inside the edge (an end
    /// at a vertex is the vertex's own candidate). A bend, offered everywhere, is never
    /// below what the engine gives (through the window, the straight line is shorter;
    /// beyond it, the nearer end is: the path's length is convex along the edge).
    fn push_waves(&self, f: u32, frame: &FaceFrame, out: &mut Vec<Candidate>) {
        for (slot, &edge) in self.mesh.face_edges(f).iter().enumerate() {
            for q in self.field.layout.edge_nodes(edge) {
                let Some((s, ef)) = self.unfolded(q, f, frame, slot) else {
                    continue;
                };
                let wave = self.wave(q).expect("unfolded has one");
                out.push(Candidate {
                    source: ValueSource::Wave(q),
                    sigma: wave.sigma,
                    site: Site::Windowed {
                        at: s,
                        window: Window {
                            edge: ef,
                            w0: wave.w0 as f64,
                            w1: wave.w1 as f64,
                        },
                        also: None,
                    },
                    across: None,
                    floor: wave.sigma,
                });
                for x in [-1.0, 2.0] {
                    // The end a line missing the window on that side bends at.
                    if let Some(w) = hinge_end(wave, x) {
                        out.push(Candidate {
                            source: ValueSource::WaveBend(q),
                            sigma: wave_value_on_edge(wave, ef.len, w),
                            site: Site::Flat(ef.at_edge_coords(w * ef.len, 0.0)),
                            across: None,
                            floor: wave_value_on_edge(wave, ef.len, w),
                        });
                    }
                }
            }
        }
    }
}

/// Face `g`'s own candidates from `cache`, built if missing (the oldest dropped when
/// full: a face's neighbours and theirs, with room to spare).
fn own_cached<'c, M: Metric, T: Topology>(
    query: &Query<'_, M, T>,
    g: u32,
    cache: &'c mut Vec<FaceField>,
) -> &'c FaceField {
    const CAPACITY: usize = 32;
    match cache.iter().position(|c| c.face == g) {
        Some(i) => &cache[i],
        None => {
            if cache.len() == CAPACITY {
                cache.remove(0);
            }
            cache.push(query.own_candidates(g));
            cache.last().expect("just pushed")
        }
    }
}

/// An upper bound on a face's field (flattened corners `t`): over the candidates seen
/// from all of the face (not windowed), the least of σ plus the farthest corner (a
/// distance from a point is greatest at a corner of a triangle). Infinite when there
/// is none.
fn upper_bound(candidates: &[Candidate], t: &[P; 3]) -> f64 {
    candidates
        .iter()
        .filter_map(|c| match c.site {
            Site::Flat(s) => {
                let far = t
                    .iter()
                    .map(|&corner| corner.sub(s).length())
                    .fold(0.0, f64::max);
                Some(c.sigma + far)
            }
            _ => None,
        })
        .fold(f64::INFINITY, f64::min)
}

/// The distance from `p` to the triangle `t` (0 inside it).
fn distance_to_triangle(p: P, t: &[P; 3]) -> f64 {
    let side = |a: P, b: P| (b.sub(a)).cross(p.sub(a));
    let signs = [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])];
    if signs.iter().all(|&s| s >= 0.0) || signs.iter().all(|&s| s <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let d = b.sub(a);
            let along = (p.sub(a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
            p.sub(a.add(d.scale(along))).length()
        })
        .fold(f64::INFINITY, f64::min)
}
