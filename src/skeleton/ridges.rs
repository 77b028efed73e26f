//! Ridges of a grassfire: where fronts from boundary points far apart meet.
//!
//! Every segment between neighbouring nodes along an edge is tested once. Its two nodes
//! came from boundary origins `A` and `B`; if they are far apart along the boundary
//! (more than `SPREAD` times the distance at the meeting point, and more than
//! `FLOOR_STEPS` boundary steps), the fronts met head-on between the nodes. The meeting
//! point is where both fronts, running along the segment towards each other, arrive at
//! once. A face then joins the crossings on its edges: two by a segment, three or more
//! at their centroid.

use super::boundary::is_boundary_edge;
use super::{cost_along, edge_sequence, Grassfire, Skeleton, SkeletonPoint};
use crate::mesh::{TriMesh, NONE};
use crate::surface::SurfacePoint;
use geotracks_metrics::Metric;

/// The fronts count as meeting head-on where the origins are farther apart along the
/// boundary than this times the distance at the meeting point. For fronts at angle φ
/// the straight chord between the origins is `2·d·sin(φ/2)`, so 0.5 keeps fronts that
/// meet at ≥ 29° (corners of the boundary up to about 150°).
pub(crate) const SPREAD: f64 = 0.5;

/// Neighbouring origins are never a ridge: the origins must be more than this many
/// boundary steps apart, which absorbs the few-step jitter of discrete origins.
pub(crate) const FLOOR_STEPS: f64 = 3.0;

/// The ridge crossings of every edge and their joins in every face, as an unpruned
/// skeleton (line elements not yet added).
pub(crate) fn ridges<M: Metric>(mesh: &TriMesh, metric: &M, fire: &Grassfire<'_, M>) -> Skeleton {
    let layout = fire.field().layout();
    let mut skeleton = Skeleton::default();
    // Per edge, the crossing node of each segment between neighbouring nodes.
    let mut first_segment = Vec::with_capacity(mesh.edge_count() + 1);
    let mut crossing = Vec::new();
    for e in 0..mesh.edge_count() as u32 {
        first_segment.push(crossing.len());
        let nodes = edge_sequence(mesh, layout, e);
        for (j, pair) in nodes.windows(2).enumerate() {
            let found = if is_boundary_edge(mesh, e) {
                None
            } else {
                meeting(mesh, metric, fire, e, pair, j)
            };
            crossing.push(match found {
                Some(point) => {
                    skeleton.points.push(point);
                    skeleton.points.len() as u32 - 1
                }
                None => NONE,
            });
        }
    }
    first_segment.push(crossing.len());

    let mut here = Vec::new();
    for f in 0..mesh.face_count() as u32 {
        here.clear();
        for &e in &mesh.face_edges(f) {
            let range = first_segment[e as usize]..first_segment[e as usize + 1];
            here.extend(crossing[range].iter().copied().filter(|&c| c != NONE));
        }
        match here.len() {
            0 | 1 => {}
            2 => skeleton.edges.push([here[0], here[1]]),
            n => {
                let mut bary = [0.0; 3];
                let mut significance = 0.0f64;
                for &c in &here {
                    let point = &skeleton.points[c as usize];
                    let b = point.on.bary_in(mesh, f).expect("a crossing on the face");
                    for (sum, x) in bary.iter_mut().zip(b) {
                        *sum += x / n as f64;
                    }
                    significance = significance.max(point.significance);
                }
                let on = SurfacePoint::Face { face: f, bary };
                let centre = skeleton.points.len() as u32;
                skeleton.points.push(SkeletonPoint {
                    position: on.position(mesh).to_array(),
                    on,
                    significance,
                });
                skeleton.edges.extend(here.iter().map(|&c| [centre, c]));
            }
        }
    }
    skeleton
}

/// Where the fronts of neighbouring nodes `pair` (segment `j` of edge `e`) meet, if they
/// meet head-on from origins far apart.
fn meeting<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    fire: &Grassfire<'_, M>,
    e: u32,
    pair: &[u32],
    j: usize,
) -> Option<SkeletonPoint> {
    let field = fire.field();
    let layout = field.layout();
    let (p, q) = (pair[0], pair[1]);
    let distances = field.node_distances();
    let (dp, dq) = (distances[p as usize], distances[q as usize]);
    let (a, b) = (fire.origin(p)?, fire.origin(q)?);
    if a == b || !(dp.is_finite() && dq.is_finite()) {
        return None;
    }
    let cost = cost_along(mesh, layout, metric, e, p, q);
    // One front running through the other node (|dq − dp| = cost) does not meet the
    // other inside the segment.
    if !(cost.is_finite() && cost > 0.0 && (dq - dp).abs() < cost * (1.0 - 1e-9)) {
        return None;
    }
    let t = (dq - dp + cost) / (2.0 * cost);
    let meet = dp + t * cost;
    let apart = match fire.boundary_distance(a, b) {
        // Origins on two different boundary curves (the rim of a hole and the outer
        // rim, say): no walk along the boundary joins them, so the straight distance
        // between them stands in; it keeps tiny holes from making loops that can never
        // be pruned.
        d if d.is_infinite() => {
            let sources = fire.field().sources();
            sources[a as usize]
                .point
                .position(mesh)
                .distance(sources[b as usize].point.position(mesh))
        }
        d => d,
    };
    let floor = FLOOR_STEPS * fire.boundary_step(a).max(fire.boundary_step(b));
    if !(apart > floor && apart > SPREAD * meet) {
        return None;
    }
    let count = layout.count(e);
    let param = |i: usize| -> f64 {
        match i {
            0 => 0.0,
            i if i == count as usize + 1 => 1.0,
            i => layout.param(e, i as u32 - 1),
        }
    };
    let (tp, tq) = (param(j), param(j + 1));
    let on = SurfacePoint::Edge {
        edge: e,
        t: tp + t * (tq - tp),
    };
    Some(SkeletonPoint {
        position: on.position(mesh).to_array(),
        on,
        significance: apart,
    })
}
