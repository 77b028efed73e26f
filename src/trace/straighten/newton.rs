//! Newton's method on all of a path's crossings at once.

use super::{edge_ends, lerp, GAIN};
use crate::mesh::Topology;
use crate::surface::SurfacePoint;
use crate::trace::GeodesicPath;
use geotracks_metrics::{FacePoint, Metric, SlidingCost};

/// Newton iterations at most per round: the next round goes on from where it stops,
/// after moving pressed crossings to the vertex, which gains more than iterating on.
const NEWTON_STEPS: usize = 10;
/// Finite-difference step in edge parameters; derivatives are taken this far inside
/// an edge at most (see [`Chain::derivatives`]).
const FD_STEP: f64 = 1e-5;
/// The widest band (in edge parameter) next to an end of its edge where a crossing can
/// be held by the gradient (see [`newton`]).
const ACTIVE_BAND: f64 = 1e-2;

/// The crossings' parameters as one vector, the path's points as functions of it.
struct Chain {
    /// Per point: the edge ends in the frames of the faces before and after it (for a
    /// crossing), or its fixed positions there.
    before: Vec<Place>,
    after: Vec<Place>,
    /// The crossing's parameter, or `None` for a fixed point.
    t: Vec<Option<f64>>,
}

#[derive(Clone, Copy)]
enum Place {
    Fixed(FacePoint),
    On(FacePoint, FacePoint),
    Unused,
}

impl Place {
    /// How the point moves with its parameter (nowhere, for a fixed point).
    fn velocity(&self) -> FacePoint {
        match *self {
            Place::On(a, b) => FacePoint {
                uv: [b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]],
                bary: [0, 1, 2].map(|i| b.bary[i] - a.bary[i]),
            },
            _ => FacePoint {
                uv: [0.0; 2],
                bary: [0.0; 3],
            },
        }
    }

    fn at(&self, t: Option<f64>) -> FacePoint {
        match (*self, t) {
            (Place::Fixed(p), _) => p,
            (Place::On(a, b), Some(t)) => lerp(&a, &b, t),
            (Place::On(a, _), None) => a,
            (Place::Unused, _) => unreachable!("a segment's end has a place in its face"),
        }
    }
}

impl Chain {
    fn new<T: Topology>(path: &GeodesicPath, mesh: &T) -> Chain {
        let n = path.points.len();
        let mut chain = Chain {
            before: vec![Place::Unused; n],
            after: vec![Place::Unused; n],
            t: vec![None; n],
        };
        for i in 0..n {
            let p = path.points[i];
            let movable = i > 0 && i + 1 < n && path.faces[i - 1] != path.faces[i];
            let place = |f: u32| match p {
                SurfacePoint::Edge { edge, .. } if movable => {
                    let (lo, hi) = edge_ends(mesh, f, edge);
                    Place::On(lo, hi)
                }
                _ => Place::Fixed(p.in_face(mesh, f).expect("on its face")),
            };
            if i > 0 {
                chain.before[i] = place(path.faces[i - 1]);
            }
            if i + 1 < n {
                chain.after[i] = place(path.faces[i]);
            }
            if let (true, SurfacePoint::Edge { t, .. }) = (movable, p) {
                chain.t[i] = Some(t);
            }
        }
        chain
    }

    /// Cost of segment `j` with its ends' parameters `a` and `b`.
    fn segment<M: Metric>(
        &self,
        metric: &M,
        faces: &[u32],
        j: usize,
        a: Option<f64>,
        b: Option<f64>,
    ) -> f64 {
        metric.cost(faces[j], &self.after[j].at(a), &self.before[j + 1].at(b))
    }

    /// Segment `j`'s cost with its derivatives in its ends' parameters `a` and `b`
    /// (`None`: an end that does not move, whose derivatives are 0), about the ends
    /// each kept a step inside its edge: the metric's formula
    /// ([`Metric::sliding_cost`]) where it has one, else central differences (nine
    /// costs).
    fn derivatives<M: Metric>(
        &self,
        metric: &M,
        faces: &[u32],
        j: usize,
        a: Option<f64>,
        b: Option<f64>,
    ) -> SlidingCost {
        // About points kept a step inside their edges: at a vertex, where the path
        // turns, segments shrink to nothing and their curvature blows up. (Taken at
        // the ends themselves, the metrics' formulas left the terrain bench's corner
        // route 0.18 % costlier after 16 rounds, against 0.003 % cheaper here: a
        // scratch build, `geotracks terrain terrain1000.asc --from 499.5,499.5 --to
        // 9490.5,9290.7 --cost slope:4`.)
        let centre = |x: Option<f64>| x.map(|x| x.clamp(FD_STEP, 1.0 - FD_STEP));
        let (ca, cb) = (centre(a), centre(b));
        let (from, to) = (&self.after[j], &self.before[j + 1]);
        let exact = metric.sliding_cost(
            faces[j],
            &from.at(ca),
            &from.velocity(),
            &to.at(cb),
            &to.velocity(),
        );
        if let Some(exact) = exact {
            return exact;
        }
        let c = |da: f64, db: f64| {
            self.segment(metric, faces, j, ca.map(|x| x + da), cb.map(|x| x + db))
        };
        SlidingCost::by_differences(c, FD_STEP, [a.is_some(), b.is_some()])
    }

    fn length<M: Metric>(&self, metric: &M, faces: &[u32], t: &[Option<f64>]) -> f64 {
        (0..faces.len())
            .map(|j| self.segment(metric, faces, j, t[j], t[j + 1]))
            .sum()
    }
}

/// Newton's method on all crossings at once. The length is a sum of segment costs, each
/// depending on two neighbouring parameters, so the Hessian is tridiagonal; each
/// segment's block comes from the metric's formula where it has one
/// ([`Metric::sliding_cost`]; Euclidean, density and tensor metrics: the shared
/// meshes' paths 30–40 % faster, `examples/eval --paths 100`, as accurate) and from
/// finite differences otherwise (any metric), made
/// positive-semidefinite and the pivots floored so that the step descends, and each
/// step is taken only as far as it shortens the path, crossings kept on their edges.
/// Coordinate sweeps alone move information one crossing per sweep, like Gauss–Seidel
/// on a chain, so a long path needs very many of them; Newton's method moves the whole
/// chain at once.
pub(super) fn newton<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
    let n = path.points.len();
    if n < 3 {
        return;
    }
    let chain = Chain::new(path, mesh);
    let faces = &path.faces;
    let mut t = chain.t.clone();
    let mut length = chain.length(metric, faces, &t);
    let (mut grad, mut diag, mut off) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut step = vec![0.0; n];
    let mut free = vec![false; n];
    let mut sweep = vec![(0.0, 0.0); n];
    let mut trial = t.clone();
    for _ in 0..NEWTON_STEPS {
        grad.fill(0.0);
        diag.fill(0.0);
        off.fill(0.0);
        for j in 0..n - 1 {
            let (a, b) = (t[j], t[j + 1]);
            // The segment's cost, gradient and Hessian in its ends' parameters.
            let d = chain.derivatives(metric, faces, j, a, b);
            // The segment's 2 × 2 Hessian, made positive-semidefinite: where the cost
            // is not smooth (a segment shrunk to nothing, both ends on one spot) the
            // differences are wild, and one indefinite block spoils the whole step.
            // Where a difference leaves the f64 range (costs near 1e308, say) the
            // segment adds nothing to the step: `finite` keeps NaN and ∞ out of it.
            let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
            let (mut haa, mut hbb, mut hab) = (0.0, 0.0, 0.0);
            if a.is_some() {
                grad[j] += finite(d.gradient[0]);
                haa = finite(d.hessian[0]).max(0.0);
            }
            if b.is_some() {
                grad[j + 1] += finite(d.gradient[1]);
                hbb = finite(d.hessian[2]).max(0.0);
            }
            if a.is_some() && b.is_some() {
                let bound = finite((haa * hbb).sqrt());
                hab = finite(d.hessian[1]).clamp(-bound, bound);
            }
            diag[j] += haa;
            diag[j + 1] += hbb;
            off[j] = hab;
        }
        // Bertsekas's projected Newton method: a crossing within `eps` of an end of its
        // edge that the gradient pushes towards that end is *held*: it moves by its
        // scaled gradient (onto the end) and stays out of the Newton system, which the
        // others solve. Left in the system, such a crossing is clamped by the step,
        // which then need not descend, and the line search stalls.
        let scale = diag.iter().fold(f64::MIN_POSITIVE, |m, &d| m.max(d.abs()));
        let floor = 1e-9 * scale;
        let residual = (0..n)
            .filter_map(|i| t[i].map(|x| x - (x - grad[i] / scale).clamp(0.0, 1.0)))
            .map(|r| r * r)
            .sum::<f64>()
            .sqrt();
        let eps = residual.min(ACTIVE_BAND);
        for i in 0..n {
            free[i] = match t[i] {
                None => false,
                Some(x) => !((x <= eps && grad[i] > 0.0) || (x >= 1.0 - eps && grad[i] < 0.0)),
            };
        }
        solve_tridiagonal(&free, &grad, &diag, &off, floor, &mut step, &mut sweep);
        for i in 0..n {
            if t[i].is_some() && !free[i] {
                step[i] = grad[i] / diag[i].max(floor);
            }
        }
        let mut improved = false;
        let mut alpha = 1.0;
        while alpha > 1e-6 {
            for i in 0..n {
                trial[i] = t[i].map(|x| (x - alpha * step[i]).clamp(0.0, 1.0));
            }
            let l = chain.length(metric, faces, &trial);
            if l < length {
                improved = length - l > GAIN * length;
                length = l;
                t.copy_from_slice(&trial);
                break;
            }
            alpha *= 0.25;
        }
        if !improved {
            break;
        }
    }
    for (i, x) in t.iter().enumerate() {
        if let (Some(x), SurfacePoint::Edge { edge, .. }) = (*x, path.points[i]) {
            path.points[i] = SurfacePoint::Edge { edge, t: x };
        }
    }
}

/// Solves `H' x = g` for the free unknowns (the others get 0), where `H'` is the
/// tridiagonal `H` (diagonal `diag`, `off[j]` between `j` and `j + 1`) with every pivot
/// raised to at least `floor` (> 0): positive-definite, so `x` is a descent direction
/// even where the length is not convex (or not smooth: at a vertex, where segments
/// shrink to nothing, the finite differences are wild). `sweep` is scratch, one entry
/// per unknown.
fn solve_tridiagonal(
    free: &[bool],
    g: &[f64],
    diag: &[f64],
    off: &[f64],
    floor: f64,
    x: &mut [f64],
    sweep: &mut [(f64, f64)],
) {
    let n = g.len();
    // Thomas algorithm; a fixed unknown splits the system. `sweep[i]` holds the
    // eliminated row's (upper / pivot, right-hand side / pivot).
    for i in 0..n {
        if !free[i] {
            continue;
        }
        let (lower, (prev_c, prev_d)) = if i > 0 && free[i - 1] {
            (off[i - 1], sweep[i - 1])
        } else {
            (0.0, (0.0, 0.0))
        };
        let pivot = diag[i] - lower * prev_c;
        let pivot = if pivot.is_finite() && pivot > floor {
            pivot
        } else {
            diag[i].abs().max(floor)
        };
        let upper = if i + 1 < n && free[i + 1] {
            off[i]
        } else {
            0.0
        };
        sweep[i] = (upper / pivot, (g[i] - lower * prev_d) / pivot);
    }
    for i in (0..n).rev() {
        let (c, d) = sweep[i];
        x[i] = if !free[i] {
            0.0
        } else if i + 1 < n && free[i + 1] {
            d - c * x[i + 1]
        } else {
            d
        };
        if !x[i].is_finite() {
            x[i] = 0.0;
        }
    }
}
