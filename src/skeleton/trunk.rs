//! A tree's trunk: the two branches that stood longest where it burnt last. However
//! short for its thickness, a trunk is the shape's own length, and pruning by
//! tubularity keeps it: without this, a stubby solid (a box 3 × 2 × 2) would keep a
//! point and no axis.

use super::thinning::Thinning;
use super::Skeleton;
use crate::mesh::{unique_edges, DisjointSets, NONE};
use std::collections::VecDeque;

/// Per vertex of a thinning, whether it lies on a tree's trunk: the two branches that
/// stood longest where the tree burnt last (what never burns there is a point, or a
/// few joined without a cycle where the fires met at once, unlike a loop). However
/// short for its thickness, a trunk is the shape's own length: without this, a stubby
/// solid (a box 3 × 2 × 2) would keep a point and no axis.
pub(super) fn of_thinning(thinning: &Thinning) -> Vec<bool> {
    let (significance, ends) = (&thinning.significance, &thinning.ends);
    let never = |v: u32| significance[v as usize] == f64::INFINITY;
    // What never burns, in pieces joined by curves; a piece with fewer edges than
    // points is a tree's last remnant, not a loop.
    let mut pieces = DisjointSets::new(significance.len());
    let joined: Vec<[u32; 2]> = unique_edges(&thinning.curves)
        .into_iter()
        .filter(|&[a, b]| a != b && never(a) && never(b))
        .collect();
    for &[a, b] in &joined {
        pieces.join(a, b);
    }
    let (piece, count) = pieces.labels();
    let mut points_less_edges = vec![0i64; count];
    for v in (0..significance.len() as u32).filter(|&v| never(v)) {
        points_less_edges[piece[v as usize] as usize] += 1;
    }
    for &[a, _] in &joined {
        points_less_edges[piece[a as usize] as usize] -= 1;
    }
    let remnant = |v: u32| never(v) && points_less_edges[piece[v as usize] as usize] > 0;
    // Per remnant, the two largest significances of the branches ending on it (each
    // branch met once, at the point next to it).
    let mut longest = vec![[f64::NEG_INFINITY; 2]; count];
    for &[a, b] in &thinning.curves {
        for (u, end) in [(a, b), (b, a)] {
            if ends[u as usize] != end || never(u) || !remnant(end) {
                continue;
            }
            let top = &mut longest[piece[end as usize] as usize];
            let s = significance[u as usize];
            if s > top[0] {
                *top = [s, top[0]];
            } else if s > top[1] {
                top[1] = s;
            }
        }
    }
    ends.iter()
        .enumerate()
        .map(|(u, &end)| {
            end != NONE && remnant(end) && {
                let [first, second] = longest[piece[end as usize] as usize];
                significance[u] >= second.min(first)
            }
        })
        .collect()
}

impl Skeleton {
    /// Per point, whether it lies on its tree's trunk, on the graph as it is: the path
    /// between the two tips whose branches stood longest (the highest significance;
    /// every other branch ends on something that stood longer, so in a tree as thinning
    /// leaves it these are the two branches at the point that burnt last). Points of a
    /// component with a cycle are on none: loops never burn, and what hangs from them
    /// is judged as it is.
    pub(super) fn trunk(&self) -> Vec<bool> {
        let n = self.points.len();
        let around = self.adjacency();
        let (component, count) = self.components();
        let mut points = vec![0usize; count];
        for &c in &component {
            points[c as usize] += 1;
        }
        let mut edges = vec![0usize; count];
        for [a, _] in unique_edges(&self.edges)
            .into_iter()
            .filter(|&[a, b]| a != b)
        {
            edges[component[a as usize] as usize] += 1;
        }
        // Per component, its two most significant tips.
        let mut top: Vec<[Option<u32>; 2]> = vec![[None; 2]; count];
        let significance = |i: u32| self.points[i as usize].significance;
        for tip in (0..n as u32).filter(|&i| around[i as usize].len() == 1) {
            let best = &mut top[component[tip as usize] as usize];
            if best[0].is_none_or(|b| significance(tip) > significance(b)) {
                *best = [Some(tip), best[0]];
            } else if best[1].is_none_or(|b| significance(tip) > significance(b)) {
                best[1] = Some(tip);
            }
        }
        let mut on = vec![false; n];
        let mut parent = vec![NONE; n];
        for c in 0..count {
            let [Some(from), Some(to)] = top[c] else {
                continue;
            };
            if edges[c] + 1 != points[c] {
                continue;
            }
            // The tree's path from `to` back to `from`.
            parent[from as usize] = from;
            let mut queue = VecDeque::from([from]);
            while let Some(u) = queue.pop_front() {
                for &w in &around[u as usize] {
                    if parent[w as usize] == NONE {
                        parent[w as usize] = u;
                        queue.push_back(w);
                    }
                }
            }
            let mut at = to;
            on[at as usize] = true;
            while at != from {
                at = parent[at as usize];
                on[at as usize] = true;
            }
        }
        on
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Polylines from the origin along x, y and -x, of lengths 3, 2 and 1, in steps
    /// of 0.5; and, apart, a square loop with a tail.
    fn tripod_and_loop() -> (Skeleton, [u32; 3]) {
        let mut points = vec![[0.0, 0.0, 0.0]];
        let mut edges = Vec::new();
        let mut tips = [0; 3];
        for (k, (direction, length)) in [([1.0, 0.0], 3.0), ([0.0, 1.0], 2.0), ([-1.0, 0.0], 1.0)]
            .into_iter()
            .enumerate()
        {
            let mut previous = 0;
            for step in 1..=(2.0 * length) as u32 {
                let t = 0.5 * f64::from(step);
                points.push([direction[0] * t, direction[1] * t, 0.0]);
                edges.push([previous, points.len() as u32 - 1]);
                previous = points.len() as u32 - 1;
            }
            tips[k] = previous;
        }
        let base = points.len() as u32;
        points.extend([
            [10.0, 0.0, 0.0],
            [11.0, 0.0, 0.0],
            [11.0, 1.0, 0.0],
            [10.0, 1.0, 0.0],
            [9.0, 0.0, 0.0],
        ]);
        edges.extend([[0, 1], [1, 2], [2, 3], [3, 0], [0, 4]].map(|e| e.map(|i| base + i)));
        (Skeleton::from_curves(&points, &edges, None), tips)
    }

    #[test]
    fn a_trees_trunk_joins_its_two_longest_branches_and_a_loop_has_none() {
        let (skeleton, [long, middle, short]) = tripod_and_loop();
        let trunk = skeleton.trunk();
        assert!(trunk[long as usize] && trunk[middle as usize] && trunk[0]);
        assert!(!trunk[short as usize]);
        // The path from the tip of 3 to the tip of 2: 6 + 4 steps and the origin.
        assert_eq!(trunk[..13].iter().filter(|&&t| t).count(), 11);
        assert!(
            trunk[13..].iter().all(|&t| !t),
            "the loop's component has no trunk"
        );
    }
}
