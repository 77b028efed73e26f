//! Queries on a field of the wavefront engine: the distance at any point from the waves
//! of the nodes around it, and paths that follow the waves back along their straight
//! lines (through each window, across each face, bending where the engine did: at a
//! window's end, a hinge) instead of from node to node, so that a traced path is as
//! long as the distance it explains.

use super::face_field::{Candidate, ValueSource};
use super::Query;
use crate::field::Wave;
use crate::flat::{
    flat_frame, frame_sides, hinge_end, in_window, same_source, same_source_slack, uv, EdgeFrame,
    EdgeGlue, P,
};
use crate::mesh::Topology;
use crate::mesh::{FaceFrame, NONE};
use crate::steiner::NodeKind;
use crate::surface::SurfacePoint;
use geotracks_metrics::{FacePoint, Metric};

/// How a traced path goes on from a node: where the node's value came from.
pub(super) enum Step {
    /// Along a straight line from a wave's source, crossing node `q`'s edge at fraction
    /// `at` (from its lower vertex), in `q`'s wave's face.
    Wave { q: u32, at: f64 },
    /// Straight to node `p` (the parent), inside `face` (`NONE`: along their edge).
    Node { p: u32, face: u32 },
    /// The node is a root: straight to the source (inside `face`, `NONE`: none).
    Source { source: u32, face: u32 },
}

impl<M: Metric, T: Topology> Query<'_, M, T> {
    /// Whether the field carries waves (it came from the wavefront engine).
    pub(super) fn has_waves(&self) -> bool {
        !self.field.waves.is_empty()
    }

    pub(super) fn wave(&self, node: u32) -> Option<&Wave> {
        let v = self.field.layout.vertex_count();
        let w = self.field.waves.get(node.checked_sub(v)? as usize)?;
        w.is_some().then_some(w)
    }

    /// Face `f`'s frame in the metric's flattening.
    pub(super) fn flat(&self, f: u32) -> Option<FaceFrame> {
        flat_frame(self.metric, f, &self.mesh.frame(f))
    }

    /// Edge `slot` of face `f` seen from `f` (flattened), and the edge's id.
    pub(super) fn edge_frame(&self, frame: &FaceFrame, f: u32, slot: usize) -> EdgeFrame {
        EdgeFrame::new(frame, slot, self.mesh.slot_is_reversed(f, slot))
    }

    /// Whether waves cross `edge` unbent: every face around it gives it the same
    /// flattened length, to rounding (as the engine decides: [`EdgeGlue::glues`]; a wave never
    /// crosses any other edge).
    pub(super) fn glues(&self, edge: u32) -> bool {
        self.edge_glue(edge).is_some_and(|g| g.glues())
    }

    /// How the flattened faces around `edge` see it; `None` where one has no
    /// flattening.
    pub(super) fn edge_glue(&self, edge: u32) -> Option<EdgeGlue> {
        let mut glue = EdgeGlue::NONE;
        for &f in self.mesh.edge_faces(edge).iter() {
            let frame = self.flat(f)?;
            let s = self.mesh.edge_slot(f, edge)?;
            let sides = frame_sides(&frame);
            glue = glue.with(sides[s], sides.iter().fold(0.0f64, |m, &l| m.max(l)));
        }
        (glue.longest > 0.0).then_some(glue)
    }

    /// Node `q`'s wave unfolded into face `f` (flattened frame `frame`, `q` on `slot`):
    /// the source, or `None` when it does not cross into `f`.
    pub(super) fn unfolded(
        &self,
        q: u32,
        f: u32,
        frame: &FaceFrame,
        slot: usize,
    ) -> Option<(P, EdgeFrame)> {
        let wave = self.wave(q)?;
        let from = self.field.parent_face[q as usize];
        let NodeKind::Steiner { edge, .. } = self.field.layout.kind(q) else {
            return None;
        };
        if from == f || !self.glues(edge) {
            return None;
        }
        let ef = self.edge_frame(frame, f, slot);
        Some((ef.at_edge_coords(wave.sx, -wave.sy), ef))
    }

    /// The best value at point `x` of face `f` from the waves of the Steiner nodes on
    /// `f`'s boundary that cross into it (straight or bending at a window's end; not
    /// the neighbours' waves), and the node.
    pub(super) fn wave_value(&self, f: u32, x: &FacePoint) -> Option<(f64, u32)> {
        let face = self.face_field(f);
        let is_wave =
            |c: &Candidate| matches!(c.source, ValueSource::Wave(_) | ValueSource::WaveBend(_));
        let (value, c) = face.best(self.metric, x, |c| !is_wave(c) || c.across.is_some())?;
        match face.candidates[c].source {
            ValueSource::Wave(q) | ValueSource::WaveBend(q) => Some((value, q)),
            _ => None,
        }
    }

    /// Appends to `points` and `faces` the path from point `x` of face `f` back along
    /// the wave of node `q` (on `f`'s boundary) and on to a source; returns the source.
    pub(super) fn trace_wave(
        &self,
        x: &FacePoint,
        f: u32,
        q: u32,
        points: &mut Vec<SurfacePoint>,
        faces: &mut Vec<u32>,
    ) -> Option<u32> {
        let at = self.enter_from(x, f, q, points, faces)?;
        self.follow(Step::Wave { q, at }, points, faces)
    }

    /// From point `x` in face `f`, straight towards `q`'s wave's source: pushes the
    /// crossing with `q`'s edge and returns it as a fraction of the edge.
    fn enter_from(
        &self,
        x: &FacePoint,
        f: u32,
        q: u32,
        points: &mut Vec<SurfacePoint>,
        faces: &mut Vec<u32>,
    ) -> Option<f64> {
        let NodeKind::Steiner { edge, .. } = self.field.layout.kind(q) else {
            return None;
        };
        let frame = self.flat(f)?;
        let slot = self.mesh.edge_slot(f, edge)?;
        let (s, ef) = self.unfolded(q, f, &frame, slot)?;
        let px = uv(&frame.point(x.bary));
        // Where the line crosses the window, or the window's end it bends at.
        let wave = self.wave(q)?;
        let crossing = ef.crossing(s, px);
        let at = match hinge_end(wave, crossing) {
            Some(w) if !in_window(wave, crossing) => w,
            _ => crossing.clamp(0.0, 1.0),
        };
        points.push(SurfacePoint::Edge { edge, t: at });
        faces.push(f);
        Some(at)
    }

    /// Follows the path from `step` to a source, pushing its points and faces.
    pub(super) fn follow(
        &self,
        mut step: Step,
        points: &mut Vec<SurfacePoint>,
        faces: &mut Vec<u32>,
    ) -> Option<u32> {
        let layout = self.field.layout;
        for _ in 0..4 * self.field.distance.len() + 4 {
            step = match step {
                Step::Source { source, face } => {
                    if face != NONE {
                        points.push(self.field.sources[source as usize].point);
                        faces.push(face);
                    }
                    return Some(source);
                }
                Step::Node { p, face } => {
                    let n = *points.last()?;
                    points.push(layout.surface_point(p));
                    faces.push(if face != NONE {
                        face
                    } else {
                        self.cheapest_face(n, layout.surface_point(p))
                    });
                    self.step_from(p)?
                }
                Step::Wave { q, at } => self.across(q, at, points, faces)?,
            };
        }
        None
    }

    /// How the path goes on from node `n`, which it has reached.
    pub(super) fn step_from(&self, n: u32) -> Option<Step> {
        let field = &self.field;
        let layout = field.layout;
        // A Steiner node's own wave is the straight line that reached it.
        if let (NodeKind::Steiner { edge, index }, Some(_)) = (layout.kind(n), self.wave(n)) {
            let _ = edge;
            let at = layout.param(edge, index);
            return Some(Step::Wave { q: n, at });
        }
        let (p, pf) = (field.parent[n as usize], field.parent_face[n as usize]);
        if p == NONE {
            let source = field.root_source(n)?;
            return Some(Step::Source { source, face: pf });
        }
        if pf == NONE {
            return Some(Step::Node { p, face: NONE });
        }
        // A vertex: straight from a wave that crosses into one of its faces, where one
        // gives its value (waves are unchanged since, but a parent's may have been
        // replaced by a tie, so all are asked), or bending at its parent.
        let d = field.distance[n as usize];
        let vertex_faces = match layout.kind(n) {
            NodeKind::Vertex(v) => Some(self.mesh.vertex_faces(v)),
            NodeKind::Steiner { .. } => None,
        };
        for &f in vertex_faces.as_deref().unwrap_or(&[]) {
            let x = layout.point_in_face(self.mesh, n, f);
            if let Some((value, q)) = self.wave_value(f, &x) {
                // (Not a wave that starts at the vertex itself.)
                let starts_before = self.wave(q)?.sigma < d - 1e-12 * d.abs();
                if value <= d + 1e-12 * d.abs() && starts_before {
                    let mut scratch = Vec::new();
                    let mut scratch_faces = Vec::new();
                    let at = self.enter_from(&x, f, q, &mut scratch, &mut scratch_faces)?;
                    return Some(Step::Wave { q, at });
                }
            }
        }
        Some(Step::Node { p, face: pf })
    }

    /// On `q`'s edge at fraction `at` (pushed already, or about to be), following `q`'s
    /// wave back into the face it came through: on to the next crossing, or to the
    /// wave's start.
    fn across(
        &self,
        q: u32,
        at: f64,
        points: &mut Vec<SurfacePoint>,
        faces: &mut Vec<u32>,
    ) -> Option<Step> {
        let field = &self.field;
        let layout = field.layout;
        let NodeKind::Steiner { edge, .. } = layout.kind(q) else {
            return None;
        };
        // The crossing itself, unless it is the last point already.
        let here = SurfacePoint::Edge { edge, t: at };
        if points.last() != Some(&here) {
            let last = *points.last()?;
            points.push(here);
            faces.push(self.face_between(last, here)?);
        }
        let wave = *self.wave(q)?;
        let h = field.parent_face[q as usize];
        if h == NONE {
            // A wave from a point of the edge itself (reached along it): its source is
            // the parent, on this edge.
            let p = field.parent[q as usize];
            return Some(Step::Node { p, face: NONE });
        }
        let frame = self.flat(h)?;
        let slot = self.mesh.edge_slot(h, edge)?;
        let eh = self.edge_frame(&frame, h, slot);
        let s = eh.at_edge_coords(wave.sx, wave.sy);
        let c = eh.at_edge_coords(at * eh.len, 0.0);
        // Where the line from the crossing to the source leaves face h, if it does.
        for other in [(slot + 1) % 3, (slot + 2) % 3] {
            let of = self.edge_frame(&frame, h, other);
            let (cx, cy) = of.edge_coords(c);
            let (sx, sy) = of.edge_coords(s);
            // `y` is ≥ 0 inside h; the line leaves through this edge if the source lies
            // strictly outside it.
            if sy >= -1e-12 * of.len || cy < sy {
                continue;
            }
            let lambda = cy / (cy - sy);
            let x = (cx + lambda * (sx - cx)) / of.len;
            if !(-1e-9..=1.0 + 1e-9).contains(&x) {
                continue;
            }
            // The node on that edge that carries the same wave into h through it.
            let e2 = self.mesh.face_edges(h)[other];
            for q2 in layout.edge_nodes(e2) {
                let Some((s2, _)) = self.unfolded(q2, h, &frame, other) else {
                    continue;
                };
                let w2 = self.wave(q2)?;
                if same_source(s, wave.sigma, s2, w2.sigma, of.len, self.turn) && in_window(w2, x) {
                    let at2 = x.clamp(0.0, 1.0);
                    points.push(SurfacePoint::Edge { edge: e2, t: at2 });
                    faces.push(h);
                    return Some(Step::Wave { q: q2, at: at2 });
                }
            }
            // No node carries it on: the line may pass the vertex that ends a window.
            // Elsewhere (should not happen) it bends at the parent, below.
            let near = 1e-5 * eh.len.max(of.len);
            if let Some((v, pv)) = self.window_end_vertex(h, &frame, e2, x * of.len, of.len, near) {
                let wave_there = wave.sigma + pv.sub(s).length();
                // Going on from `v` explains no more than the wave does there; not from
                // the vertex itself (a line that starts there goes no nearer the source
                // through it).
                if field.distance[v as usize] <= wave_there + 1e-12 * wave_there.abs()
                    && pv.sub(c).length() > near
                {
                    points.push(SurfacePoint::Vertex(v));
                    faces.push(h);
                    return self.step_from(v);
                }
            }
            break;
        }
        // The wave starts in h: at the parent (a fresh wave there) or at a source.
        let p = field.parent[q as usize];
        if p == NONE {
            let source = field.root_source(q)?;
            return Some(Step::Source { source, face: h });
        }
        // A wave that starts at a source on h's closure (a source vertex or edge point,
        // whose wave a node of another edge passed on, with a tie) goes straight there,
        // not round by the parent.
        if let Some(source) = self.source_at(h, &frame, s, wave.sigma) {
            return Some(Step::Source { source, face: h });
        }
        let last = *points.last()?;
        points.push(layout.surface_point(p));
        faces.push(
            self.face_between(last, layout.surface_point(p))
                .unwrap_or(h),
        );
        self.step_from(p)
    }

    /// The end of edge `e2` of face `h` (length `len` in its flattened `frame`) that a
    /// crossing `at` along it (from its lower vertex) lies within `near` of, and the
    /// vertex's point in `frame`. A line through the end of a window passes (to the
    /// window's slack) through the vertex that ends it, as a hinge's line does.
    fn window_end_vertex(
        &self,
        h: u32,
        frame: &FaceFrame,
        e2: u32,
        at: f64,
        len: f64,
        near: f64,
    ) -> Option<(u32, P)> {
        let [lo, hi] = self.mesh.edge_vertices(e2);
        let v = if at <= near {
            lo
        } else if len - at <= near {
            hi
        } else {
            return None;
        };
        let corner = self.mesh.face_vertices(h).iter().position(|&u| u == v)?;
        let [x, y] = frame.corners()[corner];
        Some((v, P(x, y)))
    }

    /// The source that lies at `s` (a point of face `h`, flattened `frame`) with start
    /// `sigma`, both to [`SAME_SOURCE`](crate::flat::SAME_SOURCE) of their scale and the
    /// engine's frames' turn.
    fn source_at(&self, h: u32, frame: &FaceFrame, s: P, sigma: f64) -> Option<u32> {
        let near = same_source_slack(s, sigma, frame.l01, self.turn);
        self.field
            .sources
            .iter()
            .enumerate()
            .filter(|(_, source)| (source.start - sigma).abs() <= near)
            .find_map(|(i, source)| {
                let x = source.point.in_face(self.mesh, h)?;
                let at = uv(&frame.point(x.bary));
                (at.sub(s).length() <= near).then_some(i as u32)
            })
    }

    /// A face whose closure holds both points.
    fn face_between(&self, a: SurfacePoint, b: SurfacePoint) -> Option<u32> {
        let fa = a.faces(self.mesh);
        let fb = b.faces(self.mesh);
        fa.iter().copied().find(|f| fb.contains(f))
    }
}
