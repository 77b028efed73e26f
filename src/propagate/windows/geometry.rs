//! The plane geometry of one window: its value along its edge, the part of it that
//! beats the paths through the edge's ends, and its lines' way across a face onto the
//! face's two other edges.
//!
//! Everything here is in the *entry frame* of the window's edge seen from the face
//! the window enters: the edge's lower vertex `A` at the origin, its higher vertex `B`
//! at `(len, 0)`, the face's third corner `C` above the axis (`y > 0`), and the virtual
//! source below it, at `(sx, −sy)` with `sy ≥ 0`.

use crate::flat::P;
use std::cmp::Ordering;

/// The straight lines of a window: from the virtual source at `(sx, −sy)` (`σ` up
/// to it) through the part `[b0, b1]` of the edge's axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lines {
    pub sx: f64,
    pub sy: f64,
    pub sigma: f64,
    pub b0: f64,
    pub b1: f64,
}

/// The plain length of `(x, y)`: coordinates here are metric lengths of one mesh,
/// far from the range where the squares over- or underflow.
#[inline(always)]
pub(crate) fn norm(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

impl Lines {
    /// The value at point `x` of the edge: `σ` plus the straight line from the source.
    #[inline]
    pub fn value_at(&self, x: f64) -> f64 {
        self.sigma + norm(x - self.sx, self.sy)
    }

    /// The least value over the window: at the point of `[b0, b1]` nearest the source.
    #[inline]
    pub fn least(&self) -> f64 {
        self.value_at(self.sx.clamp(self.b0, self.b1))
    }

    /// Shrinks the window to where it is no longer than the paths through the edge's
    /// ends: `d_lo` plus the way along the edge from the lower end, `d_hi` plus the
    /// way from the higher one (`len` away), each allowed `tolerance` more. Returns
    /// whether anything is left.
    ///
    /// Along the edge, the window's value less the way from an end only falls
    /// moving away from that end (the triangle inequality: a line from the source
    /// lengthens by at most the step), so the part where the window is no longer is
    /// one interval at the far side, found in closed form.
    #[inline]
    pub fn trim(&mut self, len: f64, d_lo: f64, d_hi: f64, tolerance: f64) -> bool {
        let Some(b0) = keep_beyond(
            self.sx,
            self.sy,
            (self.b0, self.b1),
            d_lo - self.sigma + tolerance,
        ) else {
            return false;
        };
        // The higher end, mirrored: x' = len − x.
        let Some(b1) = keep_beyond(
            len - self.sx,
            self.sy,
            (len - self.b1, len - b0),
            d_hi - self.sigma + tolerance,
        ) else {
            return false;
        };
        self.b0 = b0;
        self.b1 = len - b1;
        self.b0 <= self.b1
    }
}

/// The least `x` of `[b0, b1]` from which the line from `(sx, ±sy)` is no longer than
/// `delta` plus the way from the origin (`|S − x| − x ≤ delta`, a falling function of
/// `x`); `None` when there is none.
#[inline]
fn keep_beyond(sx: f64, sy: f64, (b0, b1): (f64, f64), delta: f64) -> Option<f64> {
    if delta == f64::INFINITY {
        return Some(b0);
    }
    let excess = |x: f64| norm(x - sx, sy) - x;
    if excess(b1) > delta {
        return None;
    }
    if excess(b0) <= delta {
        return Some(b0);
    }
    // |S − x| = x + δ, squared: linear in x. The excess falls from above δ to at most
    // δ over [b0, b1], so it is not constant, and its limit −sx is below δ.
    let den = 2.0 * (sx + delta);
    if den <= 0.0 {
        return Some(b0);
    }
    let x = (sx * sx + sy * sy - delta * delta) / den;
    Some(x.clamp(b0, b1))
}

/// Where two windows of one edge overlap, cuts each back from its ends to where the
/// other is not shorter by more than `tolerance`: a point of an edge needs only the
/// shortest lines through it (whichever side they come from: the others, bending
/// there, would be longer). Where the shorter one lies inside the other's interval,
/// the other is left whole (cutting it in two would need a second window); what is
/// kept is never less than what is needed.
///
/// Along the edge, the two values differ by `σa − σb + |Sa − x| − |Sb − x|`, which
/// changes sign at most twice (a hyperbola meets a line in two points): the overlap is
/// cut at those roots and each piece compared at its middle.
pub(crate) fn trim_pair(a: &mut Lines, b: &mut Lines, tolerance: f64) {
    let (lo, hi) = (a.b0.max(b.b0), a.b1.min(b.b1));
    if lo.partial_cmp(&hi) != Some(Ordering::Less) {
        return;
    }
    // Most pairs are settled by their ranges over the overlap (a value along the edge
    // is convex: least at the point nearest its source, greatest at an end).
    let ends = |w: &Lines| [w.value_at(lo), w.value_at(hi)];
    let range = |w: &Lines, [at_lo, at_hi]: [f64; 2]| {
        let least = if w.sx > lo && w.sx < hi {
            w.sigma + w.sy
        } else {
            at_lo.min(at_hi)
        };
        (least, at_lo.max(at_hi))
    };
    let (a_ends, b_ends) = (ends(a), ends(b));
    let ((a_least, a_most), (b_least, b_most)) = (range(a, a_ends), range(b, b_ends));
    let side = |diff: f64| -> i8 {
        if diff > tolerance {
            1
        } else if diff < -tolerance {
            -1
        } else {
            0
        }
    };
    let whole = if a_least > b_most + tolerance {
        1
    } else if b_least > a_most + tolerance {
        -1
    } else {
        // The difference of the two values is monotone on either side of the one
        // point of the edge's line where both sources lie in the same direction (on
        // the line through them): its derivative, the difference of the cosines of
        // the two lines' angles with the edge, vanishes only there. So where it has
        // one sign at both ends of the overlap, and at that point too if it lies
        // inside, it has that sign over the whole overlap, and no crossing is sought.
        let at_lo = side(a_ends[0] - b_ends[0]);
        if at_lo != 0
            && at_lo == side(a_ends[1] - b_ends[1])
            && same_side_within(a, b, lo, hi, at_lo, &side)
        {
            at_lo
        } else {
            0
        }
    };
    if whole != 0 {
        let pieces = [lo, hi];
        cut_back(a, &pieces, &[whole], 1);
        cut_back(b, &pieces, &[whole], -1);
        return;
    }
    let mut cuts = [lo, hi, hi, hi];
    let mut n = 1;
    for root in crossings(a, b) {
        if root > lo && root < hi {
            cuts[n] = root;
            n += 1;
        }
    }
    cuts[n] = hi;
    let cuts = &mut cuts[..=n];
    cuts.sort_unstable_by(f64::total_cmp);
    // Per piece: +1 where b is shorter (a's lines not needed), −1 where a is, 0 tie
    // or unsure. A piece is judged at its middle. Between its roots the difference
    // keeps its sign; a root lost to rounding lies where the two values touch, and
    // the lines it would have spared are shorter by no more than rounding, so a
    // middle beyond the tolerance decides the whole piece. A tie at the middle is
    // checked at the quarter points: a whole piece of tie is one source's lines
    // grazing the other's (decided by σ, below), a tie at the middle alone is left
    // whole. (Judging every piece at three points as well gave the same values on
    // the shared meshes, to the bit but for 8 of bunny_loop2's 556 051 vertices,
    // 5e-16 apart, for 4 % more instructions.)
    let mut better = [0i8; 3];
    for i in 0..n {
        let judge = |t: f64| {
            let x = cuts[i] + t * (cuts[i + 1] - cuts[i]);
            side(a.value_at(x) - b.value_at(x))
        };
        let mid = judge(0.5);
        let agree = mid != 0 || (judge(0.25) == 0 && judge(0.75) == 0);
        better[i] = match (agree, mid) {
            (false, _) => 0,
            // A tie along a whole piece: two distance functions agree on an interval
            // only where one source's lines graze the other's (a vertex on a ray of
            // the wave, which started its own windows): the one with the greater σ,
            // the vertex's, is only a stop on the other's lines.
            (true, 0) => (a.sigma > b.sigma) as i8 - (b.sigma > a.sigma) as i8,
            (true, side) => side,
        };
    }
    let (pieces, better) = (&cuts[..], &better[..n]);
    cut_back(a, pieces, better, 1);
    cut_back(b, pieces, better, -1);
}

/// Whether the difference `a − b` of two windows' values keeps side `at_ends` (as
/// `side` judges it) at the one point strictly inside `(lo, hi)` where it can turn,
/// the point of the edge's line on the line through both sources; `true` when there
/// is none. Two sources on the edge's line itself (where the values have kinks, and
/// the difference two turning points) are left to the crossings.
fn same_side_within(
    a: &Lines,
    b: &Lines,
    lo: f64,
    hi: f64,
    at_ends: i8,
    side: &impl Fn(f64) -> i8,
) -> bool {
    if a.sy == b.sy {
        // The line through the sources is parallel to the edge (no turning point),
        // or both lie on the edge's line.
        return a.sy > 0.0 || a.sx == b.sx;
    }
    let turn = a.sx + a.sy * (b.sx - a.sx) / (a.sy - b.sy);
    !(turn > lo && turn < hi) || side(a.value_at(turn) - b.value_at(turn)) == at_ends
}

/// Cuts `w` back from each end over the consecutive pieces (bounded by `pieces`)
/// where `better` is `loser` (the other window shorter), if the overlap reaches
/// that end of `w`; `w` is left empty (`b0 > b1`) when every piece of it goes.
fn cut_back(w: &mut Lines, pieces: &[f64], better: &[i8], loser: i8) {
    let n = better.len();
    let (start, end) = (pieces[0], pieces[n]);
    let losing_from_start = better.iter().take_while(|&&s| s == loser).count();
    if losing_from_start == n && start <= w.b0 && end >= w.b1 {
        w.b0 = f64::INFINITY;
        w.b1 = f64::NEG_INFINITY;
        return;
    }
    if start <= w.b0 && losing_from_start > 0 {
        w.b0 = pieces[losing_from_start];
    }
    let losing_from_end = better.iter().rev().take_while(|&&s| s == loser).count();
    if end >= w.b1 && losing_from_end > 0 {
        w.b1 = pieces[n - losing_from_end];
    }
}

/// The points of the edge's line where `a` and `b` give the same value (at most two,
/// `NaN` where there are fewer).
fn crossings(a: &Lines, b: &Lines) -> [f64; 2] {
    // |Sa − x| = |Sb − x| + c, with c = σb − σa. Squared once:
    // αx + β = 2c|Sb − x|; squared again, a quadratic in x.
    let c = b.sigma - a.sigma;
    let alpha = 2.0 * (b.sx - a.sx);
    let beta = a.sx * a.sx + a.sy * a.sy - b.sx * b.sx - b.sy * b.sy - c * c;
    if c == 0.0 {
        // The same σ: the perpendicular bisector of the two sources, once (squaring
        // would make it a double root, lost to rounding).
        return [-beta / alpha, f64::NAN];
    }
    let c2 = 4.0 * c * c;
    let qa = alpha * alpha - c2;
    let qb = 2.0 * alpha * beta + 2.0 * c2 * b.sx;
    let qc = beta * beta - c2 * (b.sx * b.sx + b.sy * b.sy);
    let scale = qa.abs().max(qb.abs()).max(qc.abs());
    if scale == 0.0 {
        return [f64::NAN; 2];
    }
    if qa.abs() <= 1e-12 * scale {
        return [-qc / qb, f64::NAN];
    }
    let mut disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        // A double root (the values touch) can come out slightly negative.
        if disc < -1e-10 * qb * qb {
            return [f64::NAN; 2];
        }
        disc = 0.0;
    }
    // The stable pair of roots.
    let q = -0.5 * (qb + qb.signum() * disc.sqrt());
    let r1 = q / qa;
    let r2 = if q != 0.0 { qc / q } else { f64::NAN };
    [r1, r2]
}

/// A window's lines continued across the face onto one of its other edges: the new
/// window in the frame of that edge seen from the face just crossed (origin at the
/// edge's lower vertex, `y` into the face crossed, where the source lies).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Child {
    pub lines: Lines,
    /// The edge's length in this face's plane.
    pub len: f64,
}

/// One of the two other edges of a face crossed from an edge `A B` (entry frame, see
/// the module), from its first corner `p` to its second `q`: its frame, worked out
/// once for every window that crosses the face.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side {
    p: P,
    pq: P,
    len: f64,
    /// Whether `p` is the side's lower vertex (its frame's origin).
    p_is_lower: bool,
    origin: P,
    /// Along the side from its origin, and across it towards the face's third corner.
    u: P,
    n: P,
}

impl Side {
    fn new((p, q, third): (P, P, P), p_is_lower: bool) -> Side {
        let pq = q.sub(p);
        let len = norm(pq.0, pq.1);
        let (origin, u) = if p_is_lower {
            (p, pq.scale(1.0 / len))
        } else {
            (q, pq.scale(-1.0 / len))
        };
        let mut n = P(-u.1, u.0);
        if third.sub(origin).dot(n) < 0.0 {
            n = n.scale(-1.0);
        }
        Side {
            p,
            pq,
            len,
            p_is_lower,
            origin,
            u,
            n,
        }
    }
}

/// A face crossed from an edge `A B` (entry frame, see the module), worked out once
/// for every window that crosses it: the edge's length, the third corner `C` and the
/// sides `A C` and `C B`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Across {
    pub len: f64,
    /// `C`, on the side `y > 0`.
    pub apex: P,
    sides: [Side; 2],
}

impl Across {
    /// `lower_first[i]` says, for side `i`, whether its lower vertex is its first
    /// corner as named (`A` of `A C`, `C` of `C B`).
    pub fn new(len: f64, apex: P, lower_first: [bool; 2]) -> Across {
        let (a, b) = (P(0.0, 0.0), P(len, 0.0));
        Across {
            len,
            apex,
            sides: [
                Side::new((a, apex, b), lower_first[0]),
                Side::new((apex, b, a), lower_first[1]),
            ],
        }
    }
}

/// Where `lines` reach across the face `across`: its children on the edges `A C` and
/// `C B`, and whether the line from the source to `C` crosses the window (then `C`
/// gets `σ + |S C|`).
pub(crate) fn project(lines: &Lines, across: &Across) -> ([Option<Child>; 2], bool) {
    let Across { len, apex, sides } = *across;
    let (sx, sy) = (lines.sx, lines.sy);
    // Where the line from the source through the apex crosses the axis.
    let through_apex = sx + (apex.0 - sx) * sy / (apex.1 + sy);
    let sees_apex = lines.b0 <= through_apex && through_apex <= lines.b1;
    let source = P(sx, -sy);
    // Lines through [b0, min(b1, x_C)] leave by A C, those through [max(b0, x_C), b1]
    // by C B. An end at the apex, or at A or B, is put there exactly.
    let left = (lines.b0 < through_apex).then(|| {
        let hi = if lines.b1 < through_apex {
            Hit::Line(lines.b1)
        } else {
            Hit::Corner(1.0)
        };
        let lo = if lines.b0 <= 0.0 {
            Hit::Corner(0.0)
        } else {
            Hit::Line(lines.b0)
        };
        child(lines, source, &sides[0], (lo, hi))
    });
    let right = (through_apex < lines.b1).then(|| {
        let lo = if lines.b0 > through_apex {
            Hit::Line(lines.b0)
        } else {
            Hit::Corner(0.0)
        };
        let hi = if lines.b1 >= len {
            Hit::Corner(1.0)
        } else {
            Hit::Line(lines.b1)
        };
        child(lines, source, &sides[1], (lo, hi))
    });
    ([left.flatten(), right.flatten()], sees_apex)
}

/// Where a line of the window meets a side: through the axis at `x`, or exactly at a
/// corner of the side (`0` its first, `1` its second).
#[derive(Clone, Copy, Debug)]
enum Hit {
    Line(f64),
    Corner(f64),
}

/// The child of `lines` on `side`, reached by the lines through `hits`; `None` when it
/// is empty or the source lies on the side's line (the lines only graze it).
fn child(lines: &Lines, source: P, side: &Side, hits: (Hit, Hit)) -> Option<Child> {
    let Side {
        p,
        pq,
        len,
        p_is_lower,
        origin,
        u,
        n,
    } = *side;
    // The fraction along p → q where the line from the source through (x, 0) meets it.
    let fraction = |hit: Hit| match hit {
        Hit::Corner(t) => t,
        Hit::Line(x) => {
            let d = P(x - lines.sx, lines.sy);
            let den = pq.cross(d);
            if den == 0.0 {
                return f64::NAN;
            }
            (source.sub(p).cross(d) / den).clamp(0.0, 1.0)
        }
    };
    let (t0, t1) = (fraction(hits.0), fraction(hits.1));
    if t0.partial_cmp(&t1).is_none_or(Ordering::is_gt) {
        return None;
    }
    let (b0, b1) = if p_is_lower {
        (t0 * len, t1 * len)
    } else {
        ((1.0 - t1) * len, (1.0 - t0) * len)
    };
    let s = source.sub(origin);
    let sy = s.dot(n);
    if sy.partial_cmp(&(1e-14 * len)) != Some(Ordering::Greater) {
        return None;
    }
    Some(Child {
        lines: Lines {
            sx: s.dot(u),
            sy,
            sigma: lines.sigma,
            b0,
            b1,
        },
        len,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn value_and_least() {
        let w = Lines {
            sx: 0.5,
            sy: 1.0,
            sigma: 2.0,
            b0: 0.0,
            b1: 1.0,
        };
        assert!(close(w.value_at(0.5), 3.0));
        assert!(close(w.least(), 3.0));
        let off = Lines { b0: 0.8, ..w };
        assert!(close(off.least(), 2.0 + 0.3f64.hypot(1.0)));
    }

    #[test]
    fn trim_keeps_what_beats_the_ends() {
        // Source straight below x = 0.5 at depth 1, σ = 0; the lower end reached at
        // 1.0, the higher not at all.
        let mut w = Lines {
            sx: 0.5,
            sy: 1.0,
            sigma: 0.0,
            b0: 0.0,
            b1: 1.0,
        };
        assert!(w.trim(1.0, 1.0, f64::INFINITY, 0.0));
        // |S − x| = 1 + x at x = (0.25 + 1 − 1) / (2 · 1.5) = 1/12.
        assert!(close(w.b0, 1.0 / 12.0), "{}", w.b0);
        assert!(close(w.value_at(w.b0), 1.0 + w.b0));
        assert_eq!(w.b1, 1.0);
        // Both ends far shorter: nothing left.
        let mut gone = Lines {
            b0: 0.0,
            b1: 1.0,
            ..w
        };
        assert!(!gone.trim(1.0, 0.0, 0.0, 0.0));
        // The higher end alone, mirrored.
        let mut hi = Lines {
            b0: 0.0,
            b1: 1.0,
            ..w
        };
        assert!(hi.trim(1.0, f64::INFINITY, 1.0, 0.0));
        assert!(close(hi.b1, 1.0 - 1.0 / 12.0));
    }

    #[test]
    fn a_pair_is_settled_whole_only_where_its_difference_cannot_turn() {
        // a: a near source (a V along the edge), b: a far one (nearly flat). a is
        // longer at both ends of [0, 1] but shorter in the middle, where the line
        // through both sources meets the edge (x = 0.5): a keeps its middle.
        let mut a = Lines {
            sx: 0.5,
            sy: 0.1,
            sigma: 9.7,
            b0: 0.0,
            b1: 1.0,
        };
        let mut b = Lines {
            sx: 0.5,
            sy: 10.0,
            sigma: 0.0,
            ..a
        };
        trim_pair(&mut a, &mut b, 1e-13);
        // a = b where (x − 0.5)² + 0.01 and (x − 0.5)² + 100 differ by 0.3 in root.
        let root = |x: f64| a.value_at(x) - b.value_at(x);
        assert!(a.b0 > 0.0 && a.b1 < 1.0 && a.b0 < a.b1, "{a:?}");
        assert!(root(a.b0).abs() < 1e-12 && root(a.b1).abs() < 1e-12);
        assert_eq!(
            (b.b0, b.b1),
            (0.0, 1.0),
            "b is shorter at both ends: kept whole"
        );
        // Beyond the roots (0.5 ± 0.28), on an overlap [0.8, 1] that the turning
        // point (0.5) lies outside of: a is longer throughout, and goes.
        let mut a = Lines {
            b0: 0.8,
            b1: 1.0,
            ..a
        };
        let mut b = Lines { b0: 0.8, ..b };
        trim_pair(&mut a, &mut b, 1e-13);
        let shorter_at = |x: f64| a.value_at(x) < b.value_at(x);
        assert!(!shorter_at(0.8) && !shorter_at(1.0));
        assert!(a.b0 > a.b1, "a is longer over the whole overlap: {a:?}");
    }

    #[test]
    fn projection_splits_at_the_apex() {
        // Unit right triangle above the edge [0, 1]; apex at (0.5, 0.5); source
        // straight below the middle.
        let w = Lines {
            sx: 0.5,
            sy: 0.5,
            sigma: 0.0,
            b0: 0.0,
            b1: 1.0,
        };
        let apex = P(0.5, 0.5);
        let ([left, right], sees) = project(&w, &Across::new(1.0, apex, [true, true]));
        assert!(sees);
        let (left, right) = (left.unwrap(), right.unwrap());
        let side = 0.5f64.hypot(0.5);
        assert!(close(left.len, side) && close(right.len, side));
        // Lines through [0, 0.5] reach all of A C; from A to the apex.
        assert!(close(left.lines.b0, 0.0) && close(left.lines.b1, side));
        assert!(close(right.lines.b0, 0.0) && close(right.lines.b1, side));
        // The source seen from A C (lower end A): the same distances as in the plane.
        let s = left.lines;
        assert!(close(s.value_at(0.0), 0.5f64.hypot(0.5)));
        assert!(close(s.value_at(side), 1.0));
        // Seen from C B with its lower end at B (reversed).
        let ([_, r], _) = project(&w, &Across::new(1.0, apex, [true, false]));
        let r = r.unwrap().lines;
        assert!(close(r.value_at(0.0), 0.5f64.hypot(0.5)) && close(r.value_at(side), 1.0));
        // A window left of the apex's line only reaches A C, and not the apex.
        let narrow = Lines { b1: 0.25, ..w };
        let ([l, r], sees) = project(&narrow, &Across::new(1.0, apex, [true, true]));
        assert!(!sees && l.is_some() && r.is_none());
        let l = l.unwrap().lines;
        // The line from (0.5, −0.5) through (0.25, 0) meets A C (y = x) at (1/6, 1/6).
        assert!(close(l.b1, (2.0f64).sqrt() / 6.0), "{}", l.b1);
    }
}
