//! The moves that change which points a path has: merging points that add nothing, and
//! unpinning a path from a vertex it turns round by less than π on one side.

use super::canonicalise;
use crate::mesh::Topology;
use crate::surface::SurfacePoint;
use crate::trace::{segment_cost, GeodesicPath};
use geotracks_metrics::Metric;
use glam::DVec3;

/// Drops a repeated point, and a point between two segments of the same face when the
/// straight segment is no longer.
pub(super) fn merge<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
    canonicalise(path, mesh);
    let mut i = 1;
    while i + 1 < path.points.len() {
        let (a, p, b) = (path.points[i - 1], path.points[i], path.points[i + 1]);
        let (f, g) = (path.faces[i - 1], path.faces[i]);
        if p == a {
            // A zero-length segment: `a` lies on `g` too.
            path.points.remove(i);
            path.faces.remove(i - 1);
            i = i.saturating_sub(1).max(1);
            continue;
        }
        // One face holding all three points (the same face twice, or points along one
        // edge whose segments name different faces of it): the straight segment there.
        let shared = [f, g]
            .into_iter()
            .find(|&h| [a, p, b].iter().all(|x| x.bary_in(mesh, h).is_some()));
        if let Some(h) = shared {
            let bent = segment_cost(mesh, metric, f, a, p) + segment_cost(mesh, metric, g, p, b);
            if segment_cost(mesh, metric, h, a, b) <= bent {
                path.points.remove(i);
                path.faces[i - 1] = h;
                path.faces.remove(i);
                i = i.saturating_sub(1).max(1);
                continue;
            }
        }
        i += 1;
    }
    // The last point may repeat the one before it (a source on the path's last node).
    let n = path.points.len();
    if n > 2 && path.points[n - 1] == path.points[n - 2] {
        path.points.remove(n - 2);
        path.faces.remove(n - 2);
    }
}

/// Gives every vertex the path may cut the corner at a crossing on each edge of the
/// side it turns around, all placed at the vertex.
pub(super) fn unpin<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
    let mut i = 1;
    while i + 1 < path.points.len() {
        let SurfacePoint::Vertex(v) = path.points[i] else {
            i += 1;
            continue;
        };
        let (f, g) = (path.faces[i - 1], path.faces[i]);
        let before = path.points[i - 1].position(mesh);
        let after = path.points[i + 1].position(mesh);
        let Some((turn, route)) = fan_route(mesh, metric, v, f, g, before, after) else {
            i += 1;
            continue;
        };
        if route.is_empty() || turn >= std::f64::consts::PI - 1e-9 {
            i += 1;
            continue;
        }
        // Unfolded around `v`, the faces of the route lie side by side, and the points
        // before and after `v` at angles 0 and `turn` (< π): the straight segment between
        // them crosses each edge of the route, where the crossing goes.
        let pv = mesh.position(v);
        let b = DVec3::new((before - pv).length(), 0.0, 0.0);
        let r = (after - pv).length();
        let a = DVec3::new(r * turn.cos(), r * turn.sin(), 0.0);
        let d = a - b;
        let crossings: Vec<SurfacePoint> = route
            .iter()
            .map(|&(e, _, theta)| {
                let u = DVec3::new(theta.cos(), theta.sin(), 0.0);
                let rho = b.cross(d).z / u.cross(d).z;
                let along = (rho / mesh.edge_length(e)).clamp(0.0, 1.0);
                let along = if along.is_finite() { along } else { 0.0 };
                let t = if mesh.edge_vertices(e)[0] == v {
                    along
                } else {
                    1.0 - along
                };
                SurfacePoint::Edge { edge: e, t }
            })
            .collect();
        let between: Vec<u32> = route[..route.len() - 1]
            .iter()
            .map(|&(_, h, _)| h)
            .collect();
        let m = crossings.len();
        path.points.splice(i..=i, crossings);
        path.faces.splice(i..i, between);
        i += m;
    }
}

/// One step of a way around a vertex: the edge crossed, the face entered through it, and
/// the angle swept up to the edge.
type FanStep = (u32, u32, f64);

/// The way around vertex `v` from face `f` to face `g` through faces that share edges at
/// `v`, turning least: returns the angle swept (from the direction towards `before`,
/// around `v`, to the direction towards `after`, Euclidean, summed face by face) and
/// the route as `(edge crossed, face entered, angle swept up to the edge)`, the last
/// face being `g`. `None` when no such way exists (the faces meet only at `v`). Faces
/// the metric cannot be crossed in (infinite cost: walls) are no way around.
fn fan_route<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    v: u32,
    f: u32,
    g: u32,
    before: DVec3,
    after: DVec3,
) -> Option<(f64, Vec<FanStep>)> {
    let pv = mesh.position(v);
    let angle = |a: DVec3, b: DVec3| (a - pv).angle_between(b - pv);
    let other_end = |e: u32| {
        let [a, b] = mesh.edge_vertices(e);
        mesh.position(if a == v { b } else { a })
    };
    let edges_at = |h: u32| -> [u32; 2] {
        let mut at = [0; 2];
        let mut n = 0;
        for e in mesh.face_edges(h) {
            if mesh.edge_vertices(e).contains(&v) && n < 2 {
                at[n] = e;
                n += 1;
            }
        }
        at
    };
    let passable = |h: u32| {
        let frame = mesh.frame(h);
        metric
            .cost(h, &frame.corner(0), &frame.corner(1))
            .is_finite()
    };
    // Dijkstra over (edge, face entered through it) states: a fan is a few faces.
    let mut states: Vec<(f64, u32, u32, usize)> = Vec::new(); // (angle, edge, face, previous)
    let mut done: Vec<bool> = Vec::new();
    for e in edges_at(f) {
        for &h in mesh.edge_faces(e).iter() {
            if h != f && passable(h) {
                states.push((angle(before, other_end(e)), e, h, usize::MAX));
                done.push(false);
            }
        }
    }
    let mut best: Option<(f64, usize)> = None;
    loop {
        let next = (0..states.len())
            .filter(|&s| !done[s])
            .min_by(|&a, &b| states[a].0.total_cmp(&states[b].0));
        let Some(s) = next else { break };
        done[s] = true;
        let (swept, e, h, _) = states[s];
        if best.is_some_and(|(b, _)| swept >= b) {
            break;
        }
        if h == g {
            let total = swept + angle(other_end(e), after);
            if best.is_none_or(|(b, _)| total < b) {
                best = Some((total, s));
            }
            continue;
        }
        if states.len() > 4 * mesh.vertex_faces(v).len() + 8 {
            continue;
        }
        for e2 in edges_at(h) {
            if e2 == e {
                continue;
            }
            let through = swept + angle(other_end(e), other_end(e2));
            for &h2 in mesh.edge_faces(e2).iter() {
                let seen = states.iter().any(|&(_, se, sh, _)| se == e2 && sh == h2);
                if h2 != h && !seen && passable(h2) {
                    states.push((through, e2, h2, s));
                    done.push(false);
                }
            }
        }
    }
    let (turn, mut s) = best?;
    let mut route = Vec::new();
    while s != usize::MAX {
        let (swept, e, h, previous) = states[s];
        route.push((e, h, swept));
        s = previous;
    }
    route.reverse();
    Some((turn, route))
}
