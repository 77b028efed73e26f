//! Brent's method for the minimum of a function on [0, 1]: where one crossing slides to.

/// How closely [`brent_min`] places a crossing, relative to its parameter (plus a
/// quarter of this absolute): about the square root of the f64 precision, below which
/// a cost, flat at its minimum, no longer tells points apart.
const BRENT_TOLERANCE: f64 = 2e-8;
/// [`brent_min`]'s steps at most: golden sections alone reach the tolerance in 40.
const BRENT_STEPS: usize = 100;

/// The minimum of `h` on [0, 1] by Brent's method (parabolic steps through the three
/// best points where they behave, golden-section steps where not; Brent 1973, ch. 5),
/// the ends included: exact for a convex `h` to [`BRENT_TOLERANCE`], a local minimum
/// for another. A smooth `h` takes a dozen calls where golden sections alone take
/// sixty, and a crossing's cost is smooth but where a segment shrinks to nothing.
pub(super) fn brent_min(h: impl Fn(f64) -> f64) -> (f64, f64) {
    // The golden section's smaller part, 1 − 0.618….
    const GOLD: f64 = 0.381_966_011_250_105_1;
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    // The best point so far, the second best, and the one before it.
    let mut x = lo + GOLD * (hi - lo);
    let (mut w, mut v) = (x, x);
    let mut fx = h(x);
    let (mut fw, mut fv) = (fx, fx);
    // The last step, and the one before it.
    let (mut step, mut previous) = (0.0f64, 0.0f64);
    for _ in 0..BRENT_STEPS {
        let middle = 0.5 * (lo + hi);
        let tol = BRENT_TOLERANCE * x.abs() + 0.25 * BRENT_TOLERANCE;
        if (x - middle).abs() <= 2.0 * tol - 0.5 * (hi - lo) {
            break;
        }
        let mut golden = true;
        if previous.abs() > tol {
            // The parabola through x, w and v: its vertex at x + p / q.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            // Taken when it falls inside the bracket and moves less than half the step
            // before last (else the steps would not shrink).
            if p.abs() < (0.5 * q * previous).abs() && p > q * (lo - x) && p < q * (hi - x) {
                previous = step;
                step = p / q;
                let u = x + step;
                if u - lo < 2.0 * tol || hi - u < 2.0 * tol {
                    step = tol.copysign(middle - x);
                }
                golden = false;
            }
        }
        if golden {
            previous = if x >= middle { lo - x } else { hi - x };
            step = GOLD * previous;
        }
        let u = if step.abs() >= tol {
            x + step
        } else {
            x + tol.copysign(step)
        };
        let fu = h(u);
        if fu <= fx {
            if u >= x {
                lo = x;
            } else {
                hi = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    let mut best = (x, fx);
    for end in [0.0, 1.0] {
        let value = h(end);
        if value < best.1 {
            best = (end, value);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::brent_min;
    use std::cell::Cell;

    #[test]
    fn brent_finds_interior_and_end_minima() {
        let calls = Cell::new(0);
        let (t, v) = brent_min(|t| {
            calls.set(calls.get() + 1);
            (t - 0.3).powi(2) + 1.0
        });
        assert!((t - 0.3).abs() < 1e-7 && (v - 1.0).abs() < 1e-14);
        // Parabolic steps: a parabola in a few calls, not golden sections' sixty.
        assert!(calls.get() < 12, "{} calls", calls.get());
        // Smooth and not a parabola: a segment's length to a point off the edge.
        let (t, _) = brent_min(|t| (t - 0.7).hypot(0.2) + 0.5 * t.hypot(1.0));
        let slope = |t: f64| (t - 0.7) / (t - 0.7).hypot(0.2) + 0.5 * t / t.hypot(1.0);
        assert!(slope(t).abs() < 1e-6, "{t}");
        // Not smooth at the minimum, or minimal at an end.
        let (t, _) = brent_min(|t| (t - 0.123).abs());
        assert!((t - 0.123).abs() < 1e-7, "{t}");
        let (t, _) = brent_min(|t| (t + 0.5).abs());
        assert_eq!(t, 0.0);
        let (t, _) = brent_min(|t| (2.0 - t).abs());
        assert_eq!(t, 1.0);
    }
}
