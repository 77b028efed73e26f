//! Joining the segments drawn in each sub-triangle into polylines.

use super::{Isoline, Key, Segment};
use crate::surface::SurfacePoint;
use std::collections::HashMap;

/// Joins the sub-triangles' segments into polylines, per level: through every point
/// shared by exactly two segments; a point with one segment ends a line (the boundary,
/// or the edge of the reached region), one with three or more (a non-manifold edge)
/// ends each line that meets there.
pub(super) fn link(levels: &[f64], segments: Vec<Segment>) -> Vec<Isoline> {
    let mut ids: HashMap<(usize, Key), usize> = HashMap::new();
    let mut points: Vec<SurfacePoint> = Vec::new();
    let mut id = |level: usize, (key, p): (Key, SurfacePoint)| -> usize {
        *ids.entry((level, key)).or_insert_with(|| {
            points.push(p);
            points.len() - 1
        })
    };
    let ends: Vec<(usize, usize)> = segments
        .iter()
        .map(|s| (id(s.level, s.a), id(s.level, s.b)))
        .collect();
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); points.len()];
    for (si, &(a, b)) in ends.iter().enumerate() {
        incident[a].push(si);
        incident[b].push(si);
    }
    let mut used = vec![false; segments.len()];
    let mut lines = Vec::new();
    // Walks from point `start` along segment `si` until a point that is not shared by
    // exactly two segments, or back to the start.
    let walk = |start: usize, mut si: usize, used: &mut Vec<bool>| -> Isoline {
        let mut line = vec![points[start]];
        let mut at = start;
        loop {
            used[si] = true;
            let s = &segments[si];
            let (a, b) = ends[si];
            let next = if a == at { b } else { a };
            if a == at {
                line.extend_from_slice(&s.inner);
            } else {
                line.extend(s.inner.iter().rev());
            }
            line.push(points[next]);
            at = next;
            if at == start || incident[at].len() != 2 {
                break;
            }
            match incident[at].iter().copied().find(|&o| !used[o]) {
                Some(o) => si = o,
                None => break,
            }
        }
        Isoline {
            level: levels[segments[si].level],
            closed: at == start,
            points: line,
        }
    };
    // Open lines first, from their ends; what is left are loops.
    for (p, around) in incident.iter().enumerate() {
        if around.len() == 2 {
            continue;
        }
        for &si in around {
            if !used[si] {
                lines.push(walk(p, si, &mut used));
            }
        }
    }
    for si in 0..segments.len() {
        if !used[si] {
            let start = ends[si].0;
            lines.push(walk(start, si, &mut used));
        }
    }
    lines.sort_by(|a, b| a.level.total_cmp(&b.level));
    lines
}
