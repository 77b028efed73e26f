//! Pruning by protrusion: how far a branch's medial balls reach out of the balls of the
//! rest of the skeleton, over the radius where the branch joins it.
//!
//! Erosion thickness and tubularity say how long a branch stood while the axis burnt.
//! An axis from samples also has spurs that stand long and add no shape: a second
//! strand along a pleated sheet, a spur into a hip bone, an udder or the inside of a
//! head. A branch adds to the shape only where its balls leave the others', and that is
//! what is measured here. The test is single-ball containment: the ball at `p` lies in
//! the ball at `q` when |p − q| + r_p ≤ r_q, so a point sticks out by
//! min over q of (|p − q| + r_p − r_q). A ball covered by two others together, and by
//! neither alone, still counts as sticking out: the measure never says a branch is
//! covered when it is not, so what it prunes the rest's balls do cover.
//!
//! Branches go one at a time, least protrusive first, and each one's value is taken
//! again once others are gone: two strands that run side by side cover each other, and
//! pruning both at once would leave neither.

use super::thinning::Ordered;
use super::Skeleton;
use crate::mesh::{unique_edges, NONE};
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

impl Skeleton {
    /// The skeleton with the branches that protrude less than `min` removed: a branch
    /// (from a tip to the first point where three or more branches meet) protrudes by
    /// how far its medial balls reach out of the balls of the rest of the skeleton,
    /// taken over `radius` where it joins (one radius per point; see the module's
    /// notes). A spur that runs inside the body's balls, or a bump that reaches out by
    /// less than half the thickness of what it stands on (at `min` = 0.5), goes; a limb
    /// that reaches out by more stays, however thin it is.
    ///
    /// Branches go from their tips, the least protrusive first, each value taken again
    /// after every removal; loops never open, and a component that is one path keeps
    /// it. The order does not depend on `min`, so a larger `min` removes a superset. A
    /// branch that joins where the radius is 0 (curves without radii) stays. `min` ≤ 0
    /// (or NaN) removes nothing.
    ///
    /// ```
    /// use geotracks::skeleton::Skeleton;
    /// // A trunk of radius 1 along x, with a spur 0.3 long that stays inside it and a
    /// // limb of radius 0.2 reaching 2 out.
    /// let trunk = [[-2.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    /// let spur = [[0.0, 0.3, 0.0]];
    /// let limb = [[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
    /// let points: Vec<[f64; 3]> = [&trunk[..], &spur, &limb].concat();
    /// let radii = [1.0, 1.0, 1.0, 0.7, 0.2, 0.2];
    /// let edges = [[0, 1], [1, 2], [1, 3], [1, 4], [4, 5]];
    /// let skeleton = Skeleton::from_curves(&points, &edges, None);
    /// let pruned = skeleton.pruned_protruding(0.5, |i| radii[i]);
    /// assert_eq!(pruned.points.len(), 5); // the spur is gone, the limb stays
    /// ```
    pub fn pruned_protruding(&self, min: f64, radius: impl Fn(usize) -> f64) -> Skeleton {
        if min.is_nan() || min <= 0.0 {
            return self.clone();
        }
        let mut peel = Peel::new(self, &radius);
        // A branch's value only rises while it keeps its points and its joint (the rest
        // it is measured against only loses points), so values in the heap are lower
        // bounds: one that is still right when it comes up is the least. A branch that
        // grows through a joint another's removal left with two branches is pushed anew.
        let mut heap: BinaryHeap<Reverse<(Ordered, u32)>> = (0..self.points.len() as u32)
            .filter_map(|tip| Some(Reverse((Ordered(peel.value(tip)?), tip))))
            .collect();
        while let Some(Reverse((Ordered(bound), tip))) = heap.pop() {
            let Some(value) = peel.value(tip) else {
                continue;
            };
            if value > bound {
                heap.push(Reverse((Ordered(value), tip)));
                continue;
            }
            if value >= min {
                break;
            }
            let joint = peel.remove_branch(tip);
            for tip in peel.tips_through(joint) {
                if let Some(value) = peel.value(tip) {
                    heap.push(Reverse((Ordered(value), tip)));
                }
            }
        }
        self.keep(|i| peel.alive[i])
    }
}

/// The skeleton's graph as branches are peeled off it, with each point's nearest cover.
pub(super) struct Peel {
    position: Vec<DVec3>,
    radius: Vec<f64>,
    significance: Vec<f64>,
    neighbours: Vec<Vec<u32>>,
    degree: Vec<u32>,
    alive: Vec<bool>,
    /// Per point, min over the rest of (|p − q| − r_q) and the q that gives it (`NONE`
    /// until first needed). It stays right while that q is alive and outside the
    /// point's own branch: the rest only loses points.
    cover: Vec<(f64, u32)>,
    /// Which walk last marked the point as part of the branch being measured.
    in_branch: Vec<u32>,
    walk: u32,
    branch: Vec<u32>,
}

impl Peel {
    pub(super) fn new(skeleton: &Skeleton, radius: &impl Fn(usize) -> f64) -> Peel {
        let n = skeleton.points.len();
        let mut neighbours = vec![Vec::new(); n];
        for [a, b] in unique_edges(&skeleton.edges) {
            if a != b {
                neighbours[a as usize].push(b);
                neighbours[b as usize].push(a);
            }
        }
        Peel {
            position: skeleton.points.iter().map(|p| p.position.into()).collect(),
            radius: (0..n).map(radius).collect(),
            significance: skeleton.points.iter().map(|p| p.significance).collect(),
            degree: neighbours.iter().map(|n| n.len() as u32).collect(),
            neighbours,
            alive: vec![true; n],
            cover: vec![(f64::INFINITY, NONE); n],
            in_branch: vec![0; n],
            walk: 0,
            branch: Vec::new(),
        }
    }

    /// The branch from `tip` into `self.branch` (tip first, the point it joins last).
    /// False when it joins nothing: the whole component is one path.
    fn walk_branch(&mut self, tip: u32) -> bool {
        self.branch.clear();
        self.branch.push(tip);
        let (mut previous, mut at) = (NONE, tip);
        loop {
            let Some(next) = self.next_along(at, previous) else {
                return false;
            };
            self.branch.push(next);
            if self.degree[next as usize] != 2 {
                return self.degree[next as usize] > 2;
            }
            (previous, at) = (at, next);
        }
    }

    /// The live neighbour of `at` other than `previous` (the first, at a junction).
    fn next_along(&self, at: u32, previous: u32) -> Option<u32> {
        self.neighbours[at as usize]
            .iter()
            .copied()
            .find(|&w| w != previous && self.alive[w as usize])
    }

    /// The protrusion of the branch from `tip` over the radius where it joins; `None`
    /// when it cannot go: not a tip, the whole component one path, the trunk's end, or
    /// joined where the radius is 0.
    fn value(&mut self, tip: u32) -> Option<f64> {
        if !self.alive[tip as usize] || self.degree[tip as usize] != 1 {
            return None;
        }
        if !self.walk_branch(tip) || self.is_trunk() {
            return None;
        }
        let base = self.radius[*self.branch.last().expect("a branch has two points") as usize];
        (base > 0.0 && base.is_finite()).then(|| self.protrusion() / base)
    }

    /// The tips whose branches run through `joint` (none unless two branches are
    /// left there, which then make one).
    fn tips_through(&self, joint: u32) -> Vec<u32> {
        if self.degree[joint as usize] != 2 {
            return Vec::new();
        }
        let mut tips = Vec::new();
        for &first in &self.neighbours[joint as usize] {
            if !self.alive[first as usize] {
                continue;
            }
            let (mut previous, mut at) = (joint, first);
            while self.degree[at as usize] == 2 {
                let Some(next) = self.next_along(at, previous) else {
                    break;
                };
                if next == joint {
                    break;
                }
                (previous, at) = (at, next);
            }
            if self.degree[at as usize] == 1 {
                tips.push(at);
            }
        }
        tips
    }

    /// Whether `self.branch` is where its trunk goes on: no other branch at the point
    /// it joins stood longer. A thin limb that lies along the body (a tail against a
    /// rump) adds little to the balls, yet it is where the body's longest curve ends.
    fn is_trunk(&self) -> bool {
        let &[.., last, joint] = &self.branch[..] else {
            return false;
        };
        let own = self.significance[last as usize];
        self.neighbours[joint as usize]
            .iter()
            .filter(|&&w| w != last && self.alive[w as usize])
            .all(|&w| self.significance[w as usize] <= own)
    }

    /// How far the balls of `self.branch` (less the point it joins) reach out of the
    /// balls of the rest.
    fn protrusion(&mut self) -> f64 {
        let branch = std::mem::take(&mut self.branch);
        let reach = self.reach_out(&branch[..branch.len() - 1]);
        self.branch = branch;
        reach
    }

    /// How far the balls of the live `points` reach out of the balls of the other live
    /// points: max over p of min over q of (|p − q| + r_p − r_q).
    pub(super) fn reach_out(&mut self, points: &[u32]) -> f64 {
        self.walk += 1;
        for &p in points {
            self.in_branch[p as usize] = self.walk;
        }
        let mut reach = f64::NEG_INFINITY;
        for &p in points {
            let p = p as usize;
            let (_, q) = self.cover[p];
            if q == NONE || !self.alive[q as usize] || self.in_branch[q as usize] == self.walk {
                self.cover[p] = self.nearest_cover(p);
            }
            reach = reach.max(self.radius[p] + self.cover[p].0);
        }
        reach
    }

    /// Removes `points` from the graph.
    pub(super) fn forget(&mut self, points: &[u32]) {
        for &p in points {
            let p = p as usize;
            self.alive[p] = false;
            for &w in &self.neighbours[p] {
                if self.alive[w as usize] {
                    self.degree[w as usize] -= 1;
                }
            }
        }
    }

    /// Min over the live points outside the current branch of (|p − q| − r_q).
    fn nearest_cover(&self, p: usize) -> (f64, u32) {
        let at = self.position[p];
        let mut best = (f64::INFINITY, NONE);
        for (q, &position) in self.position.iter().enumerate() {
            if self.alive[q] && self.in_branch[q] != self.walk {
                let gap = at.distance(position) - self.radius[q];
                if gap < best.0 {
                    best = (gap, q as u32);
                }
            }
        }
        best
    }

    /// Removes the branch from `tip`, keeping the point it joins, which it returns.
    fn remove_branch(&mut self, tip: u32) -> u32 {
        self.walk_branch(tip);
        let branch = std::mem::take(&mut self.branch);
        let (&joint, inner) = branch.split_last().expect("a branch has two points");
        self.forget(inner);
        self.branch = branch;
        joint
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A trunk of radius 1 along x from -4 to 4 (points every 1), with branches
    /// hung from its middle (index 4): each a polyline with its radii.
    fn trunk_with(branches: &[(&[[f64; 3]], &[f64])]) -> (Skeleton, Vec<f64>) {
        let mut points: Vec<[f64; 3]> = (-4..=4).map(|x| [f64::from(x), 0.0, 0.0]).collect();
        let mut radii = vec![1.0; points.len()];
        let mut edges: Vec<[u32; 2]> = (0..8).map(|i| [i, i + 1]).collect();
        for (line, r) in branches {
            let mut previous = 4;
            for (p, &radius) in line.iter().zip(*r) {
                edges.push([previous, points.len() as u32]);
                previous = points.len() as u32;
                points.push(*p);
                radii.push(radius);
            }
        }
        (Skeleton::from_curves(&points, &edges, None), radii)
    }

    fn kept(skeleton: &Skeleton, radii: &[f64], min: f64) -> usize {
        skeleton.pruned_protruding(min, |i| radii[i]).points.len()
    }

    #[test]
    fn a_spur_inside_the_trunk_goes_and_a_limb_stays() {
        let spur: &[[f64; 3]] = &[[0.0, 0.3, 0.0], [0.0, 0.5, 0.1]];
        let limb: &[[f64; 3]] = &[[0.0, 0.0, 1.0], [0.0, 0.0, 2.0], [0.0, 0.0, 3.0]];
        let (skeleton, radii) = trunk_with(&[(spur, &[0.6, 0.4]), (limb, &[0.3, 0.3, 0.3])]);
        // The spur's balls lie in the trunk's (it reaches out by 0.1 at most); the limb
        // reaches 2.3 out.
        assert_eq!(kept(&skeleton, &radii, 0.5), 9 + 3);
        assert_eq!(kept(&skeleton, &radii, 2.0), 9 + 3);
        assert_eq!(kept(&skeleton, &radii, 2.5), 9);
        assert_eq!(kept(&skeleton, &radii, 0.0), 9 + 2 + 3);
        assert_eq!(kept(&skeleton, &radii, f64::NAN), 9 + 2 + 3);
    }

    #[test]
    fn of_two_strands_side_by_side_one_stays() {
        // Two strands from the middle out to z = 3, 0.1 apart: each lies in the
        // other's balls, but not both may go.
        let a: &[[f64; 3]] = &[[0.0, 0.0, 1.0], [0.0, 0.0, 2.0], [0.0, 0.0, 3.0]];
        let b: &[[f64; 3]] = &[[0.1, 0.0, 1.0], [0.1, 0.0, 2.0], [0.1, 0.0, 3.0]];
        let r: &[f64] = &[0.5, 0.5, 0.5];
        let (skeleton, radii) = trunk_with(&[(a, r), (b, r)]);
        assert_eq!(kept(&skeleton, &radii, 0.5), 9 + 3);
    }

    #[test]
    fn a_larger_threshold_keeps_a_subset_and_loops_never_open() {
        let limb: &[[f64; 3]] = &[[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
        let bump: &[[f64; 3]] = &[[0.0, 1.2, 0.0]];
        let (mut skeleton, mut radii) = trunk_with(&[(limb, &[0.4, 0.4]), (bump, &[0.5])]);
        // A loop from the trunk's end: a square of points at radius 0.2.
        let first = skeleton.points.len() as u32;
        let ring = [[-4.0, 1.0, 0.0], [-5.0, 1.0, 0.0], [-5.0, 0.0, 0.0]];
        let mut points: Vec<[f64; 3]> = skeleton.points.iter().map(|p| p.position).collect();
        points.extend(ring);
        radii.extend([0.2; 3]);
        let mut edges = skeleton.edges.clone();
        edges.extend([
            [0, first],
            [first, first + 1],
            [first + 1, first + 2],
            [first + 2, 0],
        ]);
        skeleton = Skeleton::from_curves(&points, &edges, None);
        let mut last: Option<Skeleton> = None;
        for min in [0.0, 0.2, 0.5, 1.0, 1.5, 3.0, 1e9] {
            let pruned = skeleton.pruned_protruding(min, |i| radii[i]);
            assert_eq!(pruned.cycle_count(), 1, "at {min}");
            assert_eq!(pruned.component_count(), 1, "at {min}");
            if let Some(last) = &last {
                let positions: Vec<[f64; 3]> = last.points.iter().map(|p| p.position).collect();
                assert!(
                    pruned
                        .points
                        .iter()
                        .all(|p| positions.contains(&p.position)),
                    "at {min}"
                );
            }
            last = Some(pruned);
        }
        // At the end, only the loop and what joins it to the trunk's far end stay.
        assert!(last.expect("pruned").points.len() < 9 + 3);
    }

    #[test]
    fn the_trunks_own_end_stays_even_when_it_adds_little() {
        // A branch that stood longer than everything else at its joint (here, the
        // only significance is each branch's length burnt in from its tip) is where
        // the trunk goes on: a thin tail lying along a body. It reaches 4.5 along the trunk's balls of radius 1, 0.9 off its line, and
        // out of them by 0.13 at its end.
        let tail: Vec<[f64; 3]> = (0..10).map(|i| [-0.5 * f64::from(i), 0.9, 0.0]).collect();
        let (skeleton, radii) = trunk_with(&[(&tail, &[0.1; 10])]);
        let with_tail = skeleton.pruned_protruding(0.5, |i| radii[i]);
        assert!(with_tail
            .points
            .iter()
            .any(|p| p.position == [-4.5, 0.9, 0.0]));
        // A shorter one (3.4 long, the trunk's halves 4), that stood less, goes.
        let (skeleton, radii) = trunk_with(&[(&tail[..6], &[0.1; 6])]);
        assert_eq!(kept(&skeleton, &radii, 0.5), 9);
    }

    /// The peel done the plain way: every value taken afresh each round, the least
    /// (lowest tip on ties) removed while below `min`.
    fn peeled_plainly(skeleton: &Skeleton, radii: &[f64], min: f64) -> Vec<bool> {
        let mut peel = Peel::new(skeleton, &|i| radii[i]);
        loop {
            let mut least: Option<(f64, u32)> = None;
            for tip in 0..radii.len() as u32 {
                peel.cover.fill((f64::INFINITY, NONE));
                if let Some(value) = peel.value(tip) {
                    if least.is_none_or(|(v, _)| value < v) {
                        least = Some((value, tip));
                    }
                }
            }
            match least {
                Some((value, tip)) if value < min => {
                    peel.remove_branch(tip);
                }
                _ => return peel.alive,
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// Random trees (each point hung from an earlier one): the heap with its cached
        /// covers removes what the plain peel removes.
        #[test]
        fn the_heap_peels_as_the_plain_way_does(
            points in proptest::collection::vec(
                (proptest::array::uniform3(-1.0f64..1.0), 0.05f64..1.0, 0usize..1000),
                3..60,
            ),
        ) {
            let positions: Vec<[f64; 3]> = points.iter().map(|p| p.0).collect();
            let radii: Vec<f64> = points.iter().map(|p| p.1).collect();
            let edges: Vec<[u32; 2]> = (1..points.len())
                .map(|i| [(points[i].2 % i) as u32, i as u32])
                .collect();
            let skeleton = Skeleton::from_curves(&positions, &edges, None);
            for min in [0.2, 0.6, 1.5] {
                let plain = peeled_plainly(&skeleton, &radii, min);
                let kept: Vec<[f64; 3]> = skeleton
                    .pruned_protruding(min, |i| radii[i])
                    .points
                    .iter()
                    .map(|p| p.position)
                    .collect();
                let expected: Vec<[f64; 3]> = (0..positions.len())
                    .filter(|&i| plain[i])
                    .map(|i| skeleton.points[i].position)
                    .collect();
                proptest::prop_assert_eq!(kept, expected, "at {}", min);
            }
        }
    }
}
