//! One face's part of the isolines: its barycentric grid, evaluated; the crossings of
//! each level on the sides of its sub-triangles, solved on the field; and the points
//! that split a segment whose middle is off the level.

use super::{IsolineOptions, Key, Query, Segment};
use crate::mesh::Topology;
use crate::surface::SurfacePoint;
use crate::trace::query::FaceFields;
use geotracks_metrics::Metric;
use std::cell::RefCell;

/// Points are solved to this fraction of their level.
const POINT_TOLERANCE: f64 = 1e-12;

/// One face's grid: its points (keys, surface points, values), indexed `(i, j)` with
/// `i + j ≤ n`, barycentric `((n − i − j), i, j) / n`.
pub(super) struct FaceGrid<'q, 'a, M, T> {
    query: &'q Query<'a, M, T>,
    /// The candidates of the face and its neighbours (edge points are evaluated on
    /// every face around them).
    cache: &'q RefCell<FaceFields>,
    face: u32,
    n: u32,
    keys: Vec<Key>,
    points: Vec<SurfacePoint>,
    values: Vec<f64>,
    options: &'q IsolineOptions,
    /// Absolute tolerance floor (near level 0).
    scale: f64,
}

impl<'q, 'a, M: Metric, T: Topology> FaceGrid<'q, 'a, M, T> {
    pub(super) fn new(
        query: &'q Query<'a, M, T>,
        face: u32,
        options: &'q IsolineOptions,
        scale: f64,
        cache: &'q RefCell<FaceFields>,
    ) -> Self {
        let n = options.subdivisions;
        let mesh = query.mesh();
        let count = ((n + 1) * (n + 2) / 2) as usize;
        let (mut keys, mut points) = (Vec::with_capacity(count), Vec::with_capacity(count));
        for j in 0..=n {
            for i in 0..=n - j {
                let (key, point) = grid_point(mesh, face, n, i, j);
                keys.push(key);
                points.push(point);
            }
        }
        let values = points.iter().map(|&p| value(query, cache, p)).collect();
        FaceGrid {
            query,
            cache,
            face,
            n,
            keys,
            points,
            values,
            options,
            scale,
        }
    }

    fn index(&self, i: u32, j: u32) -> usize {
        // Rows of j: row j holds n + 1 − j points.
        let n = self.n as usize;
        let (i, j) = (i as usize, j as usize);
        j * (n + 1) - j * (j.saturating_sub(1)) / 2 + i
    }

    pub(super) fn segments(&self, levels: &[f64]) -> Vec<Segment> {
        let n = self.n;
        let mut out = Vec::new();
        let mut triangles = Vec::with_capacity((n * n) as usize);
        for j in 0..n {
            for i in 0..n - j {
                // Upward sub-triangle, and the downward one beside it.
                let a = self.index(i, j);
                let b = self.index(i + 1, j);
                let c = self.index(i, j + 1);
                triangles.push([a, b, c]);
                if i + j + 1 < n {
                    let d = self.index(i + 1, j + 1);
                    triangles.push([b, d, c]);
                }
            }
        }
        let (lo, hi) = self
            .values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        for (li, &level) in levels.iter().enumerate() {
            // A level outside the face's grid values crosses none of its sub-triangles.
            if !(level >= lo && level < hi) {
                continue;
            }
            for t in &triangles {
                self.march(li, level, *t, &mut out);
            }
        }
        out
    }

    /// The piece of the isoline at `level` in sub-triangle `t` (grid indices), if the
    /// level crosses it: a grid point is *below* when its value is below the level.
    fn march(&self, li: usize, level: f64, t: [usize; 3], out: &mut Vec<Segment>) {
        let below = t.map(|g| self.values[g] < level);
        if below[0] == below[1] && below[1] == below[2] {
            return;
        }
        // The two sides joining a below point to one that is not.
        let mut sides = (0..3)
            .filter(|&s| below[s] != below[(s + 1) % 3])
            .map(|s| self.crossing(level, t[s], t[(s + 1) % 3]));
        let (Some(a), Some(b)) = (sides.next(), sides.next()) else {
            return;
        };
        if a.0 == b.0 {
            return;
        }
        let mut inner = Vec::new();
        self.split(level, a.1, b.1, self.options.max_splits, &mut inner);
        out.push(Segment {
            level: li,
            a,
            b,
            inner,
        });
    }

    /// Where the field crosses `level` on the side between grid points `g` and `h`
    /// (one below, one not): solved the same way from every face that holds the side,
    /// from its lower key to its higher one.
    fn crossing(&self, level: f64, g: usize, h: usize) -> (Key, SurfacePoint) {
        let (g, h) = if self.keys[g] <= self.keys[h] {
            (g, h)
        } else {
            (h, g)
        };
        let (kg, kh) = (self.keys[g], self.keys[h]);
        let (pg, ph) = (self.points[g], self.points[h]);
        let mesh = self.query.mesh();
        let key = match shared_edge(mesh, pg, ph) {
            // The piece of the edge between its grid points m and m + 1.
            Some((edge, tg, th)) => {
                Key::EdgeCross(edge, (tg.min(th) * self.n as f64).round() as u32)
            }
            None => Key::FaceCross(self.face, g.min(h) as u32, g.max(h) as u32),
        };
        let (vg, vh) = (self.values[g], self.values[h]);
        let along = |s: f64| lerp_point(mesh, self.face, pg, ph, s);
        // The grid point is on the level itself: the crossing is that point, whichever
        // side it is met from.
        if vg == level {
            return (kg, pg);
        }
        if vh == level {
            return (kh, ph);
        }
        let s = solve(
            |s| value(self.query, self.cache, along(s)) - level,
            vg - level,
            vh - level,
            self.tol(level),
        );
        (key, along(s))
    }

    /// How close to the level a point is solved.
    fn tol(&self, level: f64) -> f64 {
        POINT_TOLERANCE * level.abs().max(self.scale)
    }

    /// Splits the segment `a`–`b` (inside the face) while its middle is off the level:
    /// the point on the level across the middle, found along the perpendicular to the
    /// segment (in the face's plane), goes between them.
    fn split(
        &self,
        level: f64,
        a: SurfacePoint,
        b: SurfacePoint,
        depth: u32,
        out: &mut Vec<SurfacePoint>,
    ) {
        if depth == 0 {
            return;
        }
        let mesh = self.query.mesh();
        let (Some(ba), Some(bb)) = (a.bary_in(mesh, self.face), b.bary_in(mesh, self.face)) else {
            return;
        };
        let mid = [0, 1, 2].map(|k| 0.5 * (ba[k] + bb[k]));
        let face_point = |bary: [f64; 3]| SurfacePoint::Face {
            face: self.face,
            bary,
        };
        let off = value(self.query, self.cache, face_point(mid)) - level;
        let (pa, pb) = (a.position(mesh), b.position(mesh));
        let length = (pb - pa).length();
        // A segment of a rounding's length (both ends at one vertex, where a level
        // passes through it) has nothing to follow, and no perpendicular to search.
        let tiny = 1e-9 * mesh.frame(self.face).diameter();
        if off.abs() <= self.options.tolerance * length || off.is_nan() || length <= tiny {
            return;
        }
        let Some(m) = self.across_middle(level, mid, off, pb - pa) else {
            return;
        };
        self.split(level, a, m, depth - 1, out);
        out.push(m);
        self.split(level, m, b, depth - 1, out);
    }

    /// The point on the level nearest the middle `mid` (barycentric, off the level by
    /// `off`) of a segment along `segment` (its end minus its start), searched along the
    /// perpendicular to it in the face's plane; `None` where the face holds none.
    /// (Apart from `split`, which decides whether a segment needs it.)
    fn across_middle(
        &self,
        level: f64,
        mid: [f64; 3],
        off: f64,
        segment: glam::DVec3,
    ) -> Option<SurfacePoint> {
        let mesh = self.query.mesh();
        let length = segment.length();
        let face_point = |bary: [f64; 3]| SurfacePoint::Face {
            face: self.face,
            bary,
        };
        // The perpendicular in barycentric terms: the face's normal crossed with the
        // segment gives a direction in the plane; its barycentric change solves the
        // 3-D offset on the face's two edge vectors.
        let [v0, v1, v2] = mesh.face_vertices(self.face).map(|v| mesh.position(v));
        let (e1, e2) = (v1 - v0, v2 - v0);
        let normal = e1.cross(e2);
        let dir = normal.cross(segment).normalize() * length;
        let (d1, d2) = solve_2x2(e1, e2, dir)?;
        let delta = [-d1 - d2, d1, d2];
        // How far along ±delta the face allows (barycentrics stay ≥ 0).
        // (Up to the face's side: the level may lie several segment lengths away, where
        // a line turns sharply on a ridge.)
        let reach = |sign: f64| {
            (0..3).fold(f64::INFINITY, |r, k| {
                let step = sign * delta[k];
                if step < 0.0 {
                    r.min(mid[k] / -step)
                } else {
                    r
                }
            })
        };
        let at = |s: f64| {
            let mut bary = [0, 1, 2].map(|k| (mid[k] + s * delta[k]).max(0.0));
            let sum = bary[0] + bary[1] + bary[2];
            bary.iter_mut().for_each(|x| *x /= sum);
            face_point(bary)
        };
        // The nearest point on the level along the perpendicular: stepping out from the
        // middle (an eighth of the segment, doubling, up to the face's side), the first
        // step whose value lies across the level from the middle's brackets it. (One
        // bracket over the whole reach fails where the level is met twice along it, as
        // on a ridge line that rises to a peak and falls again.)
        let bracket = |sign: f64, limit: f64| -> Option<(f64, f64, f64, f64)> {
            let reach = reach(sign).min(limit);
            let (mut s0, mut f0) = (0.0, off);
            let mut step = 0.125f64;
            loop {
                let s1 = step.min(reach);
                let f1 = value(self.query, self.cache, at(sign * s1)) - level;
                if (off > 0.0) == (f1 < 0.0) {
                    return Some((sign * s0, f0, sign * s1, f1));
                }
                if s1 >= reach || !f1.is_finite() {
                    return None;
                }
                (s0, f0) = (s1, f1);
                step *= 2.0;
            }
        };
        // The other way only as far as the first found: the nearer is wanted. With
        // neither, the middle is kept off the level (within a ridge sharper than the
        // search, a rare case) rather than guessed.
        let ahead = bracket(1.0, f64::INFINITY);
        let behind = bracket(-1.0, ahead.map_or(f64::INFINITY, |p| p.2.abs()));
        let (s0, f0, s1, f1) = behind.or(ahead)?;
        let s = solve(
            |s| value(self.query, self.cache, at(s0 + s * (s1 - s0))) - level,
            f0,
            f1,
            self.tol(level),
        );
        let m = at(s0 + s * (s1 - s0));
        if !m
            .bary_in(mesh, self.face)
            .is_some_and(|b| b.iter().all(|x| x.is_finite()))
        {
            return None;
        }
        Some(m)
    }
}

/// The field's value at `point`, `inf` where unreached (points are built on the mesh,
/// so they are valid).
fn value<M: Metric, T: Topology>(
    query: &Query<'_, M, T>,
    cache: &RefCell<FaceFields>,
    point: SurfacePoint,
) -> f64 {
    query
        .origin_cached(point, &mut cache.borrow_mut())
        .map_or(f64::INFINITY, |(d, _)| d)
}

/// A root of `f` on [0, 1] given its values at the ends (of opposite signs, the second
/// possibly infinite), by the Illinois variant of regula falsi with bisection where an
/// end is infinite; stops when `|f| ≤ tol` or the bracket stops shrinking.
fn solve(f: impl Fn(f64) -> f64, mut fa: f64, mut fb: f64, tol: f64) -> f64 {
    let (mut a, mut b) = (0.0f64, 1.0f64);
    let mut side = 0i8;
    for _ in 0..100 {
        let s = if fa.is_finite() && fb.is_finite() {
            let s = (a * fb - b * fa) / (fb - fa);
            if s > a && s < b {
                s
            } else {
                0.5 * (a + b)
            }
        } else {
            0.5 * (a + b)
        };
        if s <= a || s >= b {
            return s;
        }
        let fs = f(s);
        if fs.abs() <= tol {
            return s;
        }
        if (fs < 0.0) == (fa < 0.0) {
            a = s;
            fa = fs;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = s;
            fb = fs;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// `(x, y)` with `x·e1 + y·e2 = d` in the least-squares sense (d lies in their plane).
fn solve_2x2(e1: glam::DVec3, e2: glam::DVec3, d: glam::DVec3) -> Option<(f64, f64)> {
    let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (p, q) = (e1.dot(d), e2.dot(d));
    let det = a * c - b * b;
    if det.abs() <= 1e-300 {
        return None;
    }
    Some(((p * c - q * b) / det, (a * q - b * p) / det))
}

/// The grid point `(i, j)` of face `f`: its key and its surface point (a vertex, an
/// edge point by the edge's own parameter, or a face point).
fn grid_point<T: Topology>(mesh: &T, f: u32, n: u32, i: u32, j: u32) -> (Key, SurfacePoint) {
    let corners = mesh.face_vertices(f);
    let k = n - i - j;
    if i == 0 && j == 0 {
        return (Key::Vertex(corners[0]), SurfacePoint::Vertex(corners[0]));
    }
    if i == n {
        return (Key::Vertex(corners[1]), SurfacePoint::Vertex(corners[1]));
    }
    if j == n {
        return (Key::Vertex(corners[2]), SurfacePoint::Vertex(corners[2]));
    }
    // On slot s (from corner s to corner s + 1), `at` steps of n from corner s.
    let on_slot = if j == 0 {
        Some((0, i))
    } else if k == 0 {
        Some((1, j))
    } else if i == 0 {
        Some((2, n - j))
    } else {
        None
    };
    match on_slot {
        Some((s, at)) => {
            let edge = mesh.face_edges(f)[s];
            let m = if mesh.slot_is_reversed(f, s) {
                n - at
            } else {
                at
            };
            (
                Key::EdgeGrid(edge, m),
                SurfacePoint::Edge {
                    edge,
                    t: m as f64 / n as f64,
                },
            )
        }
        None => {
            let nf = n as f64;
            (
                Key::FaceGrid(f, i, j),
                SurfacePoint::Face {
                    face: f,
                    bary: [k as f64 / nf, i as f64 / nf, j as f64 / nf],
                },
            )
        }
    }
}

/// The mesh edge that points `a` and `b` both lie on (vertices or points of it), with
/// their parameters along it (from its lower vertex).
fn shared_edge<T: Topology>(mesh: &T, a: SurfacePoint, b: SurfacePoint) -> Option<(u32, f64, f64)> {
    let at = |p: SurfacePoint, e: u32| -> Option<f64> {
        match p {
            SurfacePoint::Edge { edge, t } if edge == e => Some(t),
            SurfacePoint::Vertex(v) => {
                let [lo, hi] = mesh.edge_vertices(e);
                (v == lo).then_some(0.0).or((v == hi).then_some(1.0))
            }
            _ => None,
        }
    };
    let edge = match (a, b) {
        (SurfacePoint::Edge { edge, .. }, _) | (_, SurfacePoint::Edge { edge, .. }) => edge,
        (SurfacePoint::Vertex(u), SurfacePoint::Vertex(v)) => mesh
            .vertex_edges(u)
            .iter()
            .copied()
            .find(|&e| mesh.edge_vertices(e).contains(&v))?,
        _ => return None,
    };
    Some((edge, at(a, edge)?, at(b, edge)?))
}

/// The point at fraction `s` from `a` to `b`, both on face `f`'s closure: on their
/// shared edge when they have one (so that every face finds the same point), else a
/// face point.
fn lerp_point<T: Topology>(
    mesh: &T,
    f: u32,
    a: SurfacePoint,
    b: SurfacePoint,
    s: f64,
) -> SurfacePoint {
    if let Some((edge, ta, tb)) = shared_edge(mesh, a, b) {
        return SurfacePoint::Edge {
            edge,
            t: ta + s * (tb - ta),
        };
    }
    let ba = a.bary_in(mesh, f).expect("grid point on its face");
    let bb = b.bary_in(mesh, f).expect("grid point on its face");
    SurfacePoint::Face {
        face: f,
        bary: [0, 1, 2].map(|k| ba[k] + s * (bb[k] - ba[k])),
    }
}
