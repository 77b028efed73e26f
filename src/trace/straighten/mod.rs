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

mod brent;
mod moves;
mod newton;

use super::GeodesicPath;
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::surface::SurfacePoint;
use brent::brent_min;
use geotracks_metrics::{FacePoint, Metric, Reversed};
use moves::merge;
use moves::unpin;
use newton::newton;

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
pub fn straighten<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
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
fn straighten_in_faces<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
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
fn hop<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M) {
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
fn newton_between<M: Metric, T: Topology>(
    path: &mut GeodesicPath,
    mesh: &T,
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
fn snap_to_vertices<T: Topology>(path: &mut GeodesicPath, mesh: &T) {
    let n = path.points.len();
    for p in path.points.iter_mut().take(n.saturating_sub(1)).skip(1) {
        if let Some(v) = pressed_vertex(mesh, p) {
            *p = SurfacePoint::Vertex(v);
        }
    }
}

/// The vertex a crossing is pressed against (within [`SNAP`] of it along its edge).
fn pressed_vertex<T: Topology>(mesh: &T, p: &SurfacePoint) -> Option<u32> {
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
fn canonicalise<T: Topology>(path: &mut GeodesicPath, mesh: &T) {
    for p in &mut path.points {
        *p = p.validated(mesh).unwrap_or(*p);
    }
}

/// Sweeps of crossing moves until a sweep gains less than [`SWEEP_GAIN`] of `length`.
fn slide<M: Metric, T: Topology>(path: &mut GeodesicPath, mesh: &T, metric: &M, length: f64) {
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
fn slide_one<M: Metric, T: Topology>(
    path: &mut GeodesicPath,
    mesh: &T,
    metric: &M,
    i: usize,
) -> f64 {
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
fn edge_ends<T: Topology>(mesh: &T, f: u32, edge: u32) -> (FacePoint, FacePoint) {
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
