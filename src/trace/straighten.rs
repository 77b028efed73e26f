//! Local shortening of a path on the surface, for any metric and any topology.
//!
//! The path is a chain of segments, each inside one face; the points between them lie on
//! edges shared by the two faces (or at vertices). Three moves, repeated while they gain:
//! - *merge*: drop a repeated point, and a point between two segments of the same face
//!   when the straight segment is no longer;
//! - *unpin*: a path through a vertex that turns by less than π on one side (Euclidean
//!   angles) is given a crossing on each edge of that side, all at the vertex, so that
//!   sliding can move it off;
//! - *slide*: each crossing moves along its edge to the point that minimises the metric
//!   cost of its two segments (Brent's method: convex for a norm), and only
//!   when that lowers the cost. Sweeps alternate direction until they stop gaining.
//!
//! Each round merges, unpins and runs Newton's method on all crossings at once
//! (`newton`); crossings it leaves pressed against an end of their edge become that
//! vertex, so that unpinning can take them round its other side. Within a round, a few
//! *hops* (`hop`) do that at once where it happens, with Newton's method on the stretch
//! around them only; the next round does it everywhere. Sliding polishes the result
//! once, at the end.
//!
//! For the Euclidean metric on a fixed strip of faces, the length is a convex function of
//! the crossing parameters, whose minimum is the path a funnel finds in the unfolded
//! strip. Both moves only ever lower the length, but they are not proved to reach that
//! minimum. The tests check that they do on a flat grid (a straight line, to 1e-6) and
//! across a book's spine.

use super::{segment_cost, GeodesicPath};
use crate::mesh::{TriMesh, NONE};
use crate::surface::SurfacePoint;
use geotracks_metrics::{FacePoint, Metric, Reversed, SlidingCost};
use glam::DVec3;

/// Rounds of merge, unpin and Newton at most. A route whose Steiner-graph path lies some
/// cells beside the geodesic (a coarse graph on a regular grid: the guide's Terrain page) moves
/// a vertex sideways per round and per hop ([`HOPS`]), so this bounds both the work and
/// how far it goes. 16 rounds with hops straighten the 1000 × 1000 terrain bench's
/// routes further than 48 rounds without hops did (13 333.9 against 13 346.3 corner to
/// corner, `slope:4`) for a few hundredths of a second more; fewer rounds leave a
/// 20-square strip's diagonal more than 1e-6 off (the `shortest_path_with` doc test).
const ROUNDS: usize = 16;
/// Sliding sweeps at most (after Newton's method, they polish).
const SWEEPS: usize = 30;
/// A sliding sweep that gains less than this fraction of the length ends them: sweeps
/// converge linearly, a crossing a sweep (like Gauss–Seidel on a chain), and what the
/// rounds leave them is small. On the terrain bench's corner route (`slope:4`, 2 700
/// crossings) all 30 gained 7e-7 of the length together, 2e-7 the first and under 6e-8
/// each after it, for 0.04 s (a scratch print of each sweep's gain, and `geotracks
/// terrain -v`); `examples/eval --paths 100` read the same with this bound as with
/// [`GAIN`].
const SWEEP_GAIN: f64 = 1e-7;
/// A sweep or a round that gains less than this fraction of the length ends the work.
const GAIN: f64 = 1e-13;
/// How closely [`brent_min`] places a crossing, relative to its parameter (plus a
/// quarter of this absolute): about the square root of the f64 precision, below which
/// a cost, flat at its minimum, no longer tells points apart.
const BRENT_TOLERANCE: f64 = 2e-8;
/// [`brent_min`]'s steps at most: golden sections alone reach the tolerance in 40.
const BRENT_STEPS: usize = 100;

/// Crossings within this (in edge parameter) of an end of their edge are taken as
/// pressed against it. Newton's method stops short of the end when its last line
/// search does; a crossing snapped by mistake loses little, as unpinning puts it
/// back on the straight segment next round, and a round that ends longer is undone.
const SNAP: f64 = 1e-3;

/// Shortens `path` locally (see the module docs) and updates its `length`, which never
/// grows.
///
/// Crossings cannot move past the end of their edge, so a path that passes a vertex on
/// the wrong side ends a round with crossings pressed against it; the next round puts
/// them at the vertex, where unpinning can take the other side. A round that ends
/// longer than it began is undone, and unpinning stops.
///
/// A path that runs along wires (segments with face [`NONE`]) is straightened piece by
/// piece between them: a wire is a fixed curve, and its ends stay where they are.
pub fn straighten<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
    if !path.faces.contains(&NONE) {
        straighten_in_faces(path, mesh, metric);
        return;
    }
    let mut points = Vec::with_capacity(path.points.len());
    let mut faces = Vec::with_capacity(path.faces.len());
    let mut start = 0;
    for end in 0..=path.faces.len() {
        if end < path.faces.len() && path.faces[end] != NONE {
            continue;
        }
        // Points start..=end lie in faces: straighten them as a path of their own.
        let mut piece = stretch(path, start, end);
        if !piece.faces.is_empty() {
            straighten_in_faces(&mut piece, mesh, metric);
        }
        if !points.is_empty() {
            faces.push(NONE); // the wire from the last piece's end to this one's start
        }
        points.extend(piece.points);
        faces.extend(piece.faces);
        start = end + 1;
    }
    path.points = points;
    path.faces = faces;
    path.length = path.metric_length(mesh, metric);
}

/// [`straighten`] for a path whose segments all lie in faces.
fn straighten_in_faces<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
    let mut length = path.metric_length(mesh, metric);
    // The moves measure each segment from the point before it in the list to the one
    // after; the list runs from the query point back to the source, against travel, so
    // they measure under the reversed metric (a directed metric's travel costs).
    let travel = &Reversed(metric);
    let mut unpinning = true;
    // What the round before gained (none before the first: no hops in it).
    let mut gained = 0.0;
    for round in 0..ROUNDS {
        let before = length;
        let saved = unpinning.then(|| path.clone());
        if unpinning && round > 0 {
            snap_to_vertices(path, mesh);
        }
        merge(path, mesh, travel);
        if unpinning {
            unpin(path, mesh, travel);
        }
        newton(path, mesh, travel);
        if unpinning && gained > HOP_WHEN * before {
            hop(path, mesh, travel);
        }
        length = path.metric_length(mesh, metric);
        gained = before - length;
        if let (Some(saved), true) = (saved, length > before) {
            // Leaving the vertices did not pay (a metric unlike the Euclidean angles
            // that chose the sides): back, and on without it.
            *path = saved;
            length = before;
            unpinning = false;
            continue;
        }
        if before - length <= GAIN * before {
            break;
        }
    }
    slide(path, mesh, travel, length);
    merge(path, mesh, travel);
    path.length = path.metric_length(mesh, metric);
}

/// Local rounds after a round's Newton steps, at most this many (see [`ROUNDS`]).
/// Without them, 16 rounds leave a route across a density interface short of Snell's
/// law (the test `snell_law_at_a_density_interface`).
const HOPS: usize = 4;
/// Points on each side of a hop's crossings that its Newton steps move: enough for the
/// bend a vertex's crossings leave to settle, few enough that a hop costs a fraction
/// of a round on a long path.
const HOP_REACH: usize = 32;
/// A hop that gains less than this fraction of the length ends the round's hops.
const HOP_GAIN: f64 = 1e-7;
/// Hops run from the second round on, while the round before gained more than this
/// fraction of the length: a path still moving off its corridor (a terrain route
/// gains about 1e-5 a round), not one being polished. A hop costs about a round
/// (passes over the whole path): after every round (a scratch build) it made the
/// shared meshes' paths 25–55 % slower for a mean excess of 0.0001 % instead of
/// 0.0002 %; gated, 0–27 % slower, as accurate as before (`examples/eval --paths 100`).
const HOP_WHEN: f64 = 1e-6;

/// Local rounds: the crossings left pressed against a vertex go round it at once, and
/// Newton's method runs again on the stretch of path around them only, so that a path
/// far off its best corridor moves several vertices a round (a round's work is all the
/// path's, a hop's only where it moves). A hop that ends longer is undone.
fn hop<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
    // The length before the hop: the one before measured it last.
    let mut length = None;
    for _ in 0..HOPS {
        let n = path.points.len();
        if n < 3 {
            return;
        }
        let mut pressed: Vec<u32> = path.points[1..n - 1]
            .iter()
            .filter_map(|p| pressed_vertex(mesh, p))
            .collect();
        if pressed.is_empty() {
            return;
        }
        pressed.sort_unstable();
        let saved = path.clone();
        let before = *length.get_or_insert_with(|| path.metric_length(mesh, metric));
        snap_to_vertices(path, mesh);
        merge(path, mesh, metric);
        unpin(path, mesh, metric);
        let near = |p: &SurfacePoint| match *p {
            SurfacePoint::Vertex(v) => pressed.binary_search(&v).is_ok(),
            SurfacePoint::Edge { edge, .. } => mesh
                .edge_vertices(edge)
                .iter()
                .any(|v| pressed.binary_search(v).is_ok()),
            SurfacePoint::Face { .. } => false,
        };
        let n = path.points.len();
        let mut i = 0;
        while i < n {
            if !near(&path.points[i]) {
                i += 1;
                continue;
            }
            // The stretch: this point's reach, and on while near points follow.
            let lo = i.saturating_sub(HOP_REACH);
            let mut hi = (i + HOP_REACH).min(n - 1);
            let mut j = i + 1;
            while j <= hi {
                if near(&path.points[j]) {
                    hi = (j + HOP_REACH).min(n - 1);
                }
                j += 1;
            }
            newton_between(path, mesh, metric, lo, hi);
            i = hi + 1;
        }
        let after = path.metric_length(mesh, metric);
        if after > before {
            *path = saved;
            return;
        }
        if before - after <= HOP_GAIN * before {
            return;
        }
        length = Some(after);
    }
}

/// [`newton`] on points `lo..=hi` of `path` alone (the two ends stay).
fn newton_between<M: Metric>(
    path: &mut GeodesicPath,
    mesh: &TriMesh,
    metric: &M,
    lo: usize,
    hi: usize,
) {
    if hi < lo + 2 {
        return;
    }
    let mut part = stretch(path, lo, hi);
    newton(&mut part, mesh, metric);
    path.points[lo..=hi].copy_from_slice(&part.points);
}

/// Points `lo..=hi` of `path` and the segments between them, as a path of their own.
fn stretch(path: &GeodesicPath, lo: usize, hi: usize) -> GeodesicPath {
    GeodesicPath {
        points: path.points[lo..=hi].to_vec(),
        faces: path.faces[lo..hi].to_vec(),
        source: path.source,
        length: 0.0,
        traced_length: path.traced_length,
    }
}

/// Crossings pressed against an end of their edge (within [`SNAP`]) become that vertex.
fn snap_to_vertices(path: &mut GeodesicPath, mesh: &TriMesh) {
    let n = path.points.len();
    for p in path.points.iter_mut().take(n.saturating_sub(1)).skip(1) {
        if let Some(v) = pressed_vertex(mesh, p) {
            *p = SurfacePoint::Vertex(v);
        }
    }
}

/// The vertex a crossing is pressed against (within [`SNAP`] of it along its edge).
fn pressed_vertex(mesh: &TriMesh, p: &SurfacePoint) -> Option<u32> {
    let SurfacePoint::Edge { edge, t } = *p else {
        return None;
    };
    let [lo, hi] = mesh.edge_vertices(edge);
    if t <= SNAP {
        Some(lo)
    } else if t >= 1.0 - SNAP {
        Some(hi)
    } else {
        None
    }
}

/// Points at an edge's end become the vertex, so that repeated points are seen.
fn canonicalise(path: &mut GeodesicPath, mesh: &TriMesh) {
    for p in &mut path.points {
        *p = p.validated(mesh).unwrap_or(*p);
    }
}

fn merge<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
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
fn unpin<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
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
fn fan_route<M: Metric>(
    mesh: &TriMesh,
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
        for &h in mesh.edge_faces(e) {
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
            for &h2 in mesh.edge_faces(e2) {
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
    fn new(path: &GeodesicPath, mesh: &TriMesh) -> Chain {
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
fn newton<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M) {
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

/// Sweeps of crossing moves until a sweep gains less than [`SWEEP_GAIN`] of `length`.
fn slide<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M, length: f64) {
    let n = path.points.len();
    if n < 3 {
        return;
    }
    for sweep in 0..SWEEPS {
        let mut gain = 0.0;
        let forward = sweep % 2 == 0;
        for j in 1..n - 1 {
            let i = if forward { j } else { n - 1 - j };
            gain += slide_one(path, mesh, metric, i);
        }
        if gain <= SWEEP_GAIN * length {
            break;
        }
    }
}

/// Moves crossing `i` along its edge to where its two segments cost least; returns the
/// cost saved (0 when it stays).
fn slide_one<M: Metric>(path: &mut GeodesicPath, mesh: &TriMesh, metric: &M, i: usize) -> f64 {
    let SurfacePoint::Edge { edge, t } = path.points[i] else {
        return 0.0;
    };
    let (f, g) = (path.faces[i - 1], path.faces[i]);
    if f == g {
        return 0.0;
    }
    let (ef, eg) = (edge_ends(mesh, f, edge), edge_ends(mesh, g, edge));
    let a = path.points[i - 1].in_face(mesh, f).expect("on its face");
    let b = path.points[i + 1].in_face(mesh, g).expect("on its face");
    let cost = |t: f64| {
        metric.cost(f, &a, &lerp(&ef.0, &ef.1, t)) + metric.cost(g, &lerp(&eg.0, &eg.1, t), &b)
    };
    let now = cost(t);
    let (best_t, best) = brent_min(cost);
    if best < now {
        path.points[i] = SurfacePoint::Edge { edge, t: best_t };
        now - best
    } else {
        0.0
    }
}

/// The ends of `edge` (lower-id vertex first, as its parameter runs) in the frame of
/// face `f`, one of its faces.
fn edge_ends(mesh: &TriMesh, f: u32, edge: u32) -> (FacePoint, FacePoint) {
    let corner = |v: u32| {
        mesh.frame(f)
            .corner(mesh.corner_of(f, v).expect("edge of its face"))
    };
    let [lo, hi] = mesh.edge_vertices(edge);
    (corner(lo), corner(hi))
}

/// The point at `t` on the segment `a`–`b` of one face's frame.
fn lerp(a: &FacePoint, b: &FacePoint, t: f64) -> FacePoint {
    let s = 1.0 - t;
    FacePoint {
        uv: [s * a.uv[0] + t * b.uv[0], s * a.uv[1] + t * b.uv[1]],
        bary: [
            s * a.bary[0] + t * b.bary[0],
            s * a.bary[1] + t * b.bary[1],
            s * a.bary[2] + t * b.bary[2],
        ],
    }
}

/// The minimum of `h` on [0, 1] by Brent's method (parabolic steps through the three
/// best points where they behave, golden-section steps where not; Brent 1973, ch. 5),
/// the ends included: exact for a convex `h` to [`BRENT_TOLERANCE`], a local minimum
/// for another. A smooth `h` takes a dozen calls where golden sections alone take
/// sixty, and a crossing's cost is smooth but where a segment shrinks to nothing.
fn brent_min(h: impl Fn(f64) -> f64) -> (f64, f64) {
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
