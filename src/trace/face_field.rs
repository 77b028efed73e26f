//! The field inside one face, as the engine defines it: the least of a few *candidates*,
//! each a real path's length — a node's value plus the straight segment from it, a
//! source's start plus its segment, or (wavefront engine) a wave's `σ` plus the straight
//! line from its virtual source through its window, or bending at the window's end.
//!
//! Every query at a point of the face reads this one list: the distance
//! ([`Query::distance_at`]), which candidate gives it ([`ValueSource`]), the gradient
//! ([`Query::gradient_at`]) and the face's regions ([`Query::regions`]), so they agree
//! by construction.

use super::Query;
use crate::flat::{hinge_end, uv, wave_value_on_edge, EdgeFrame, P};
use crate::mesh::FaceFrame;
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
}

/// Where a candidate's paths come from.
#[derive(Clone, Copy, Debug)]
pub(super) enum Site {
    /// A point of the face's flattened plane, seen from all of the face.
    Flat(P),
    /// A point of the flattened plane (behind an edge) whose lines count only where they
    /// cross the edge inside a window (fractions `w0..=w1` of it, from its lower end).
    Windowed {
        at: P,
        edge: EdgeFrame,
        w0: f64,
        w1: f64,
    },
    /// A point of the face under a metric that does not flatten faces: the segment's
    /// cost is the metric's.
    Metric(FacePoint),
}

/// One candidate: `sigma` plus the length of the path from its site.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub source: ValueSource,
    pub sigma: f64,
    pub site: Site,
}

/// A face's candidates, ready to be evaluated at many points.
pub(super) struct FaceField {
    pub face: u32,
    /// The face's frame in the metric's flattening (`None`: the metric does not flatten).
    pub flat: Option<FaceFrame>,
    pub candidates: Vec<Candidate>,
    /// Nodes of the face the run left unreached, when it stopped early: a point they
    /// might give less than its value is unreached too.
    pub unreached: Vec<FacePoint>,
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
            (Site::Windowed { at, edge, w0, w1 }, Some(px)) => {
                let cross = edge.crossing(at, px);
                let inside = cross >= w0 - crate::flat::WINDOW_SLACK
                    && cross <= w1 + crate::flat::WINDOW_SLACK;
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
            if best.is_some_and(|(b, _)| c.sigma >= b) {
                // Sorted by σ: no later candidate can do better.
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

    /// The least value an unreached node of the face could give `x` (`inf` when the
    /// run did not stop early).
    pub fn unsettled<M: Metric>(&self, metric: &M, horizon: f64, x: &FacePoint) -> f64 {
        self.unreached
            .iter()
            .map(|p| horizon - metric.cost(self.face, p, x))
            .fold(f64::INFINITY, f64::min)
    }

    /// Where candidate `c`'s paths come from, as a point of the face's plane (unfolded
    /// there from the faces the wave crossed), in world coordinates.
    pub fn site_position(&self, mesh: &crate::mesh::TriMesh, c: &Candidate) -> DVec3 {
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

impl<M: Metric> Query<'_, M> {
    /// Face `f`'s candidates: the nodes on its boundary, the sources on its closure and
    /// (wavefront engine) the waves that cross into it, with their bends.
    pub(super) fn face_field(&self, f: u32) -> FaceField {
        let (mesh, metric, field) = (self.mesh, self.metric, &self.field);
        let flat = crate::flat::flat_frame(metric, f, mesh.frame(f));
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
                });
            } else if field.horizon < f64::INFINITY {
                unreached.push(p);
            }
        }
        for (i, source) in field.sources.iter().enumerate() {
            if let Some(s) = source.point.in_face(mesh, f) {
                candidates.push(Candidate {
                    source: ValueSource::Source(i as u32),
                    sigma: source.start,
                    site: to_site(&s),
                });
            }
        }
        if let (true, Some(frame)) = (self.has_waves(), flat) {
            self.push_waves(f, &frame, &mut candidates);
        }
        // Cheapest first: `best` stops looking at a candidate whose σ alone is no less
        // than the best value found.
        candidates.sort_by(|a, b| a.sigma.total_cmp(&b.sigma));
        FaceField {
            face: f,
            flat,
            candidates,
            unreached,
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
                        edge: ef,
                        w0: wave.w0 as f64,
                        w1: wave.w1 as f64,
                    },
                });
                for x in [-1.0, 2.0] {
                    // The end a line missing the window on that side bends at.
                    if let Some(w) = hinge_end(wave, x) {
                        out.push(Candidate {
                            source: ValueSource::WaveBend(q),
                            sigma: wave_value_on_edge(wave, ef.len, w),
                            site: Site::Flat(ef.at_edge_coords(w * ef.len, 0.0)),
                        });
                    }
                }
            }
        }
    }
}
