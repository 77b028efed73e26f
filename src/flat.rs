//! Face-flat geometry: a metric that is a constant norm on each face maps each face
//! isometrically onto a plane (its *flattening*), where straight lines are geodesics.
//! The wavefront engine propagates [`Wave`]s in these planes, and queries on its fields
//! (distances at any point, paths) read them back; both use the frames here.

use crate::field::Wave;
use crate::mesh::{FaceFrame, Topology};
use geotracks_metrics::{FacePoint, Metric};

/// Slack on window tests, as a fraction of the edge. Window ends are rounded inwards to
/// `f32`, and a line through a vertex (common on regular grids) crosses its edges at
/// their very ends, so the slack must cover a few `f32` units. A line that passes a
/// vertex on the wrong side by `δ` is shorter than the real path bending there by
/// about `δ² / ℓ` only: with `δ = 1e-6` of an edge, 1e-12 relative.
pub(crate) const WINDOW_SLACK: f64 = 1e-6;
/// Two values this close (relative) are a tie.
pub(crate) const TIE: f64 = 1e-12;
/// Two windows of one wave are joined when they meet to this fraction of the edge:
/// their ends are rounded inwards to `f32` (a few units in the last place apart where
/// they meet), and a real gap between them (the shadow of a vertex) is far wider.
pub(crate) const TOUCH: f32 = 1e-6;
/// ... or when the gap between them, seen from the source, is narrower than this angle
/// (radians; plus the frames' turn). Two windows of one wave meet on the line from the
/// source through a vertex, and where that line grazes the edge they end on, rounding
/// of its direction moves their ends far along the edge (measured: 8e-6 of a 15-long
/// edge crossed at 7e-7 rad) while the angle between them stays at rounding (2e-11).
/// A gap that narrow that is real (a hole's corner seen from far) costs a line through
/// it about `(α ℓ)² / ℓ`: 1e-18 relative.
const ANGLE_TOUCH: f64 = 1e-9;

/// Two waves are the same when their sources and σ agree to this, relative to the
/// edge's length and the source's distance.
pub(crate) const SAME_SOURCE: f64 = 1e-9;
/// How many units in the last place of its faces' longest edge an edge's corners may
/// be off in a face's frame (measured: a little over one): the edge's direction, and
/// with it a source seen from the edge, turns by up to this many `f64::EPSILON` times
/// that longest edge over the edge's own length ([`EdgeGlue::turn`]).
const FRAME_ROUNDING: f64 = 4.0;

/// An edge as the flattenings of the faces around it see it: its shortest and longest
/// length over them, and the longest edge of those faces (what the lengths' rounding
/// is relative to). One decision for every engine and query on whether faces glue.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EdgeGlue {
    pub shortest: f64,
    pub longest: f64,
    pub scale: f64,
}

impl EdgeGlue {
    /// No face seen yet.
    pub const NONE: EdgeGlue = EdgeGlue {
        shortest: f64::INFINITY,
        longest: 0.0,
        scale: 0.0,
    };

    /// Also seen at length `len` in a face whose longest edge is `face_longest`.
    pub fn with(self, len: f64, face_longest: f64) -> EdgeGlue {
        EdgeGlue {
            shortest: self.shortest.min(len),
            longest: self.longest.max(len),
            scale: self.scale.max(face_longest),
        }
    }

    /// Per edge of `mesh`, as the flattened `frames` (one per face) see it.
    pub fn of_edges<T: Topology>(mesh: &T, frames: &[FaceFrame]) -> Vec<EdgeGlue> {
        let mut glue = vec![EdgeGlue::NONE; mesh.edge_count()];
        for (f, frame) in frames.iter().enumerate() {
            let sides = frame_sides(frame);
            let longest = sides.iter().fold(0.0f64, |m, &l| m.max(l));
            for (l, e) in sides.into_iter().zip(mesh.face_edges(f as u32)) {
                glue[e as usize] = glue[e as usize].with(l, longest);
            }
        }
        glue
    }

    /// Whether the faces glue isometrically along the edge: they give it one length, to
    /// 1e-9 of it, or to rounding of the faces' own size (a short edge of a face with a
    /// far corner is measured to `ε` of that corner's distance, not of its own length).
    pub fn glues(&self) -> bool {
        self.longest - self.shortest <= 1e-9 * self.longest + 1e-12 * self.scale
    }

    /// By how much (in radians) its direction may differ from one face's frame to
    /// another's by rounding. Negligible on a well-shaped mesh (`4 ε`); a short edge of
    /// a face with a far corner is measured to `ε` of that corner's distance, not of
    /// its own length, and a source 2.5 away seen across a 7.6e-6 edge of a face 90
    /// long moves by 3.5e-9 from one frame to the other: more than [`SAME_SOURCE`] of
    /// it.
    pub fn turn(&self) -> f64 {
        FRAME_ROUNDING * f64::EPSILON * (self.scale / self.longest).max(1.0)
    }
}

/// The lengths of a flattened face's sides, side `s` from corner `s` to `s + 1`.
pub(crate) fn frame_sides(frame: &FaceFrame) -> [f64; 3] {
    let c = frame.corners();
    [0, 1, 2].map(|s| {
        let (a, b) = (c[s], c[(s + 1) % 3]);
        (b[0] - a[0]).hypot(b[1] - a[1])
    })
}

/// A point of the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct P(pub f64, pub f64);

impl P {
    #[inline(always)]
    pub(crate) fn sub(self, o: P) -> P {
        P(self.0 - o.0, self.1 - o.1)
    }
    #[inline(always)]
    pub(crate) fn add(self, o: P) -> P {
        P(self.0 + o.0, self.1 + o.1)
    }
    #[inline(always)]
    pub(crate) fn scale(self, k: f64) -> P {
        P(self.0 * k, self.1 * k)
    }
    #[inline(always)]
    pub(crate) fn dot(self, o: P) -> f64 {
        self.0 * o.0 + self.1 * o.1
    }
    #[inline(always)]
    pub(crate) fn cross(self, o: P) -> f64 {
        self.0 * o.1 - self.1 * o.0
    }
    #[inline(always)]
    pub(crate) fn length(self) -> f64 {
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

pub(crate) fn uv(p: &FacePoint) -> P {
    P(p.uv[0], p.uv[1])
}

/// An edge seen from one face (in the face's flattened frame): its lower vertex `lo`,
/// unit direction `u` towards its higher vertex, length `len`, and unit normal `n`
/// pointing into the face.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EdgeFrame {
    pub lo: P,
    pub u: P,
    pub n: P,
    pub len: f64,
}

impl EdgeFrame {
    /// Slot `s` of `frame`; `reversed` when the slot runs from the edge's higher vertex.
    #[inline]
    pub(crate) fn new(frame: &FaceFrame, s: usize, reversed: bool) -> EdgeFrame {
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
    pub(crate) fn edge_coords(&self, p: P) -> (f64, f64) {
        let d = p.sub(self.lo);
        (d.dot(self.u), d.dot(self.n))
    }

    /// The point at edge coordinates `(x, y)`, `y` into the face.
    #[inline]
    pub(crate) fn at_edge_coords(&self, x: f64, y: f64) -> P {
        self.lo.add(self.u.scale(x)).add(self.n.scale(y))
    }

    /// Where the line from `s` through `t` crosses the edge's line, as a fraction of
    /// the edge from its lower vertex (`NaN` when parallel).
    #[inline]
    pub(crate) fn crossing(&self, s: P, t: P) -> f64 {
        let (sx, sy) = self.edge_coords(s);
        let (tx, ty) = self.edge_coords(t);
        // y goes from sy to ty; it is 0 at λ = sy / (sy − ty).
        let lambda = sy / (sy - ty);
        (sx + lambda * (tx - sx)) / self.len
    }
}

/// How far apart two waves' sources (and `σ`s) may lie and still be the same wave, for
/// a wave with source `a` and `σ = sa` seen from an edge of length `len`, whose frames
/// may turn by `turn` radians ([`EdgeGlue::turn`], 0 where the frames are not in doubt).
#[inline]
pub(crate) fn same_source_slack(a: P, sa: f64, len: f64, turn: f64) -> f64 {
    let reach = len + a.0.abs() + a.1.abs();
    SAME_SOURCE * (reach + sa.abs()) + turn * reach
}

/// Whether two waves have the same source (points `a`, `b` of one face's plane, path
/// lengths `sa`, `sb` up to them), to [`SAME_SOURCE`] of their scale and the frames'
/// `turn` ([`same_source_slack`]).
#[inline]
pub(crate) fn same_source(a: P, sa: f64, b: P, sb: f64, len: f64, turn: f64) -> bool {
    let slack = same_source_slack(a, sa, len, turn);
    (a.0 - b.0).abs() <= slack && (a.1 - b.1).abs() <= slack && (sa - sb).abs() <= slack
}

/// Whether fraction `x` of the edge lies in `wave`'s window (widened by the slack).
#[inline(always)]
pub(crate) fn in_window(wave: &Wave, x: f64) -> bool {
    x >= wave.w0 as f64 - WINDOW_SLACK && x <= wave.w1 as f64 + WINDOW_SLACK
}

/// Whether windows `a` and `b` (fractions of the edge `frame`) of one wave with source
/// `s` (a point of the frame's plane) overlap or meet: to [`TOUCH`] of the edge, or to
/// [`ANGLE_TOUCH`] plus `turn` as seen from `s`.
pub(crate) fn windows_touch(
    a: (f32, f32),
    b: (f32, f32),
    s: P,
    frame: &EdgeFrame,
    turn: f64,
) -> bool {
    if b.0 <= a.1 + TOUCH && a.0 <= b.1 + TOUCH {
        return true;
    }
    // The gap's ends, in order along the edge.
    let (g0, g1) = if b.0 > a.1 { (a.1, b.0) } else { (b.1, a.0) };
    let at = |w: f32| frame.at_edge_coords(w as f64 * frame.len, 0.0).sub(s);
    let (p, q) = (at(g0), at(g1));
    p.cross(q).abs() <= (ANGLE_TOUCH + turn) * p.length() * q.length()
}

/// The end of `wave`'s window (a fraction of its edge) at which a line that crosses the
/// edge's line at fraction `x`, outside the window, bends on its way through it: the
/// end on that side, where that end lies inside the edge. An end at a vertex is none:
/// the vertex is a node of its own and offers that bend itself. `None` also inside the
/// window and for a `NaN` crossing (a line along the edge).
#[inline]
pub(crate) fn hinge_end(wave: &Wave, x: f64) -> Option<f64> {
    let w = if x < wave.w0 as f64 {
        wave.w0
    } else if x > wave.w1 as f64 {
        wave.w1
    } else {
        return None;
    };
    (w > 0.0 && w < 1.0).then_some(w as f64)
}

/// The length of the path up to the point at fraction `w` of `wave`'s edge (of length
/// `len`) straight from the wave's source: `σ + |S w|`.
#[inline]
pub(crate) fn wave_value_on_edge(wave: &Wave, len: f64, w: f64) -> f64 {
    wave.sigma + P(w * len - wave.sx, wave.sy).length()
}

/// Where a line from `wave`'s source that crosses its edge's line at fraction `x`,
/// outside the window, reaches its target through the window at best: bending at the
/// window's end on that side (the *hinge*, [`hinge_end`]), whose point in `frame` (the
/// edge seen from the face entered) and path length `σ + |S w|` are returned. The
/// length `|S w| + |w t|` is convex in `w` along the edge and least where the line
/// crosses, so over the window it is least at the end nearest the crossing. That path
/// is real (a line through the window, then a segment in the face), so the value it
/// gives is never below the true distance, and it is never longer than the path that
/// bends at the node (which lies in its own window). The engine offers hinges to
/// vertices; queries and traces on its fields take them the same way.
#[inline]
pub(crate) fn hinge(wave: &Wave, frame: &EdgeFrame, x: f64) -> Option<(P, f64)> {
    let w = hinge_end(wave, x)?;
    let sigma = wave_value_on_edge(wave, frame.len, w);
    Some((frame.at_edge_coords(w * frame.len, 0.0), sigma))
}

/// The window on the edge `to` of the lines from `s` through `wave`'s window on the
/// edge `from` (both seen in one face, which `s` lies behind `from` of): fractions of
/// `to`, rounded inwards to `f32`; empty (`w0 > w1`) when no such line reaches `to`.
pub(crate) fn project(wave: &Wave, s: P, from: &EdgeFrame, to: &EdgeFrame) -> (f32, f32) {
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

/// Face `f`'s frame in `metric`'s flattening, if the metric gives it (see
/// [`Metric::face_gram`]): with `G = RᵀR` (Cholesky, `R` upper triangular), the point
/// `uv` maps to `R·uv`, so the frame keeps its shape: corner 0 at the origin, corner 1
/// on the u axis, corner 2 above it.
pub(crate) fn flat_frame<M: Metric>(metric: &M, f: u32, frame: &FaceFrame) -> Option<FaceFrame> {
    let [g11, g12, g22] = metric.face_gram(f)?;
    let r11 = g11.sqrt();
    let r12 = g12 / r11;
    let r22 = (g22 - r12 * r12).sqrt();
    if !(r11 > 0.0 && r22 > 0.0 && r12.is_finite()) {
        return None;
    }
    Some(FaceFrame {
        l01: r11 * frame.l01,
        x2: r11 * frame.x2 + r12 * frame.y2,
        y2: r22 * frame.y2,
    })
}

#[cfg(test)]
mod tests {

    use super::{project, EdgeFrame, P};
    use crate::field::Wave;

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
