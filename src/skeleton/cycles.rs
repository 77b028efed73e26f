//! Cutting a skeleton's extra cycles: a medial axis computed from a sampled surface has
//! small holes where its sheets are thin (see [`crate::skeleton::medial`]), and thinning keeps a
//! cycle around each; the solid has as many independent cycles as its genus.

use super::protrusion::Peel;
use super::{Skeleton, SkeletonPoint};
use crate::mesh::{unique_edges, DisjointSets};
use crate::surface::SurfacePoint;
use glam::DVec3;

impl Skeleton {
    /// The skeleton with at most `max_cycles` independent cycles, none of them `filled`.
    ///
    /// Which cycles stay: take the graph's spanning forest of widest edges (an edge's
    /// width: the smaller `width` of its two points, their medial radius), and of the
    /// edges outside it, keep the `max_cycles` whose cycles through the forest are the
    /// longest, of those whose cycle (its points in order, as indices) is not `filled`
    /// (such as a loop whose disc the medial balls fill: it goes round no tunnel of the
    /// solid). A cycle around a small hole in the axis is short; a handle of the shape
    /// is a long loop, and kept.
    ///
    /// How the others open, one at a time, shortest first, at the cycle's edge outside
    /// the forest (its narrowest): the branch that edge lies on (the path between the
    /// points of three or more edges either side of it) goes whole when its balls reach
    /// out of the rest's by less than `protrusion` times the larger `width` at its ends
    /// (see [`Skeleton::pruned_protruding`]): a strand that a hole split from the body
    /// adds nothing to it. Otherwise only that edge goes, and the two branches the cut
    /// leaves are burnt again from their new tips along the graph
    /// (their significance: the length burnt, as [`Skeleton::from_curves`] gives it;
    /// tubularity `inf`), then pruned at `prune` ([`Skeleton::pruned`]): a limb that a
    /// hole joined to another part keeps its length. Other points keep their
    /// significance and tubularity. A skeleton with nothing to cut is returned as it is.
    ///
    /// # Panics
    /// If `width` panics for a point index below `self.points.len()`.
    #[must_use]
    pub fn with_cycles_cut(
        self,
        max_cycles: usize,
        width: impl Fn(usize) -> f64,
        mut filled: impl FnMut(&[u32]) -> bool,
        protrusion: f64,
        prune: f64,
    ) -> Skeleton {
        if self.cycle_count() == 0 {
            return self;
        }
        let n = self.points.len();
        let position = |i: u32| DVec3::from(self.points[i as usize].position);
        let length = |[a, b]: [u32; 2]| position(a).distance(position(b));
        let edge_width = |[a, b]: [u32; 2]| width(a as usize).min(width(b as usize));
        let mut order: Vec<usize> = (0..self.edges.len()).collect();
        order.sort_by(|&x, &y| edge_width(self.edges[y]).total_cmp(&edge_width(self.edges[x])));
        let mut sets = DisjointSets::new(n);
        let mut tree = vec![Vec::new(); n];
        let mut outside = Vec::new();
        for e in order {
            let [a, b] = self.edges[e];
            if a == b {
                continue;
            }
            if sets.join(a, b) {
                tree[a as usize].push(b);
                tree[b as usize].push(a);
            } else {
                outside.push([a, b]);
            }
        }
        let forest = Forest::new(&tree, |a, b| length([a, b]));
        let mut loops: Vec<(f64, [u32; 2])> = outside
            .iter()
            .map(|&e| (forest.path_length(e[0], e[1]) + length(e), e))
            .collect();
        loops.sort_by(|x, y| y.0.total_cmp(&x.0));
        let mut kept = 0;
        let mut cuts = Vec::new();
        for &(_, [a, b]) in &loops {
            if kept < max_cycles && !filled(&forest.path(a, b)) {
                kept += 1;
            } else {
                cuts.push([a, b]);
            }
        }
        if cuts.is_empty() {
            return self;
        }
        cuts.reverse();
        let (mut edges, mut dropped) = self.opened(&cuts, &width, protrusion);
        // Each opening takes one cycle and leaves the graph in one piece; should the
        // branches of different cycles have overlapped, cut edges only.
        let trial = self.on_edges(edges.clone()).keep(|i| !dropped[i]);
        if trial.cycle_count() != kept || trial.component_count() != self.component_count() {
            let cut: Vec<[u32; 2]> = cuts.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
            edges = unique_edges(&self.edges)
                .into_iter()
                .filter(|e| !cut.contains(e))
                .collect();
            dropped = vec![false; n];
        }
        let mut cut = self.reburnt(edges);
        cut.raise_towards_the_core();
        cut.opened_cycles += cuts.len();
        cut.keep(|i| !dropped[i]).pruned(prune)
    }

    /// The graph's edges once each of `cuts` (an edge on a cycle) has opened its cycle,
    /// in turn, as [`Skeleton::with_cycles_cut`] says; and the points of the branches
    /// that went.
    fn opened(
        &self,
        cuts: &[[u32; 2]],
        width: &impl Fn(usize) -> f64,
        protrusion: f64,
    ) -> (Vec<[u32; 2]>, Vec<bool>) {
        let mut around: Vec<Vec<u32>> = vec![Vec::new(); self.points.len()];
        for [a, b] in unique_edges(&self.edges) {
            if a != b {
                around[a as usize].push(b);
                around[b as usize].push(a);
            }
        }
        let mut peel = Peel::new(self, width);
        let mut dropped = vec![false; self.points.len()];
        for &[a, b] in cuts {
            // The branch the cut lies on: from each end of the cut edge, away from the
            // other, to the first point of other than two edges (none on a loop
            // without one, which only opens).
            let mut inner = Vec::new();
            let mut ring = false;
            let mut base = 0.0_f64;
            for (start, other) in [(a, b), (b, a)] {
                let (mut previous, mut at) = (other, start);
                while around[at as usize].len() == 2 {
                    inner.push(at);
                    let next = around[at as usize][usize::from(around[at as usize][0] == previous)];
                    (previous, at) = (at, next);
                    // Back where it started: a loop without a junction.
                    ring |= at == start;
                    if ring {
                        break;
                    }
                }
                if ring {
                    break;
                }
                base = base.max(width(at as usize));
            }
            if !ring && !inner.is_empty() && peel.reach_out(&inner) < protrusion * base {
                peel.forget(&inner);
                for &p in &inner {
                    dropped[p as usize] = true;
                    for w in std::mem::take(&mut around[p as usize]) {
                        around[w as usize].retain(|&x| x != p);
                    }
                }
            } else {
                around[a as usize].retain(|&x| x != b);
                around[b as usize].retain(|&x| x != a);
            }
        }
        let edges = (0..self.points.len() as u32)
            .flat_map(|a| {
                around[a as usize]
                    .iter()
                    .filter(move |&&b| a < b)
                    .map(move |&b| [a, b])
            })
            .collect();
        (edges, dropped)
    }

    /// The same points on `edges`.
    fn on_edges(&self, edges: Vec<[u32; 2]>) -> Skeleton {
        Skeleton {
            points: self.points.clone(),
            edges,
            ..*self
        }
    }

    /// Raises each point's significance to at least that of every point beyond it, seen
    /// from the most significant point of its component, so that pruning takes branches
    /// from their tips and never cuts a component in two. The cuts can leave a branch
    /// of the thinning (with its erosion thickness) hanging from a piece of a former
    /// cycle that the new burn finds less significant; the piece must stay while the
    /// branch does.
    fn raise_towards_the_core(&mut self) {
        let n = self.points.len();
        let around = self.adjacency();
        let mut by_significance: Vec<u32> = (0..n as u32).collect();
        by_significance.sort_by(|&a, &b| {
            let s = |i: u32| self.points[i as usize].significance;
            s(b).total_cmp(&s(a))
        });
        // Breadth first from each component's most significant point; then from the
        // last point reached back to the first, each raises its parent.
        let mut parent = vec![u32::MAX; n];
        let mut order = Vec::with_capacity(n);
        let mut seen = vec![false; n];
        for root in by_significance {
            if seen[root as usize] {
                continue;
            }
            seen[root as usize] = true;
            let start = order.len();
            order.push(root);
            let mut next = start;
            while next < order.len() {
                let a = order[next];
                next += 1;
                for &b in &around[a as usize] {
                    if !seen[b as usize] {
                        seen[b as usize] = true;
                        parent[b as usize] = a;
                        order.push(b);
                    }
                }
            }
        }
        for &i in order.iter().rev() {
            let p = parent[i as usize];
            if p != u32::MAX {
                let s = self.points[i as usize].significance;
                let up = &mut self.points[p as usize].significance;
                *up = up.max(s);
            }
        }
    }

    /// The skeleton on `edges` (a subgraph of its own), with the points that were on
    /// cycles (significance `inf`) burnt again along the new graph from its tips.
    fn reburnt(&self, edges: Vec<[u32; 2]>) -> Skeleton {
        let positions: Vec<[f64; 3]> = self.points.iter().map(|p| p.position).collect();
        let graph = Skeleton::from_curves(&positions, &edges, None);
        let mut points = self.points.clone();
        for p in &graph.points {
            let SurfacePoint::Vertex(i) = p.on else {
                continue;
            };
            let old: &mut SkeletonPoint = &mut points[i as usize];
            if old.significance.is_infinite() {
                old.significance = p.significance;
                old.tubularity = f64::INFINITY;
            }
        }
        Skeleton {
            points,
            edges,
            ..*self
        }
    }
}

/// A rooted spanning forest, for lengths of paths between its points.
struct Forest {
    parent: Vec<u32>,
    depth: Vec<u32>,
    /// Length from the root.
    height: Vec<f64>,
}

impl Forest {
    /// Roots every tree of `adjacent` at its lowest point; `length` of each edge.
    fn new(adjacent: &[Vec<u32>], length: impl Fn(u32, u32) -> f64) -> Forest {
        let n = adjacent.len();
        let mut forest = Forest {
            parent: vec![u32::MAX; n],
            depth: vec![0; n],
            height: vec![0.0; n],
        };
        let mut seen = vec![false; n];
        let mut stack = Vec::new();
        for root in 0..n as u32 {
            if seen[root as usize] {
                continue;
            }
            seen[root as usize] = true;
            stack.push(root);
            while let Some(a) = stack.pop() {
                for &b in &adjacent[a as usize] {
                    if !seen[b as usize] {
                        seen[b as usize] = true;
                        forest.parent[b as usize] = a;
                        forest.depth[b as usize] = forest.depth[a as usize] + 1;
                        forest.height[b as usize] = forest.height[a as usize] + length(a, b);
                        stack.push(b);
                    }
                }
            }
        }
        forest
    }

    /// The points of the forest's path from `a` to `b` (of one tree), in order.
    fn path(&self, mut a: u32, mut b: u32) -> Vec<u32> {
        let (mut from_a, mut from_b) = (Vec::new(), Vec::new());
        while self.depth[a as usize] > self.depth[b as usize] {
            from_a.push(a);
            a = self.parent[a as usize];
        }
        while self.depth[b as usize] > self.depth[a as usize] {
            from_b.push(b);
            b = self.parent[b as usize];
        }
        while a != b {
            from_a.push(a);
            from_b.push(b);
            a = self.parent[a as usize];
            b = self.parent[b as usize];
        }
        from_a.push(a);
        from_a.extend(from_b.into_iter().rev());
        from_a
    }

    /// The length of the forest's path between `a` and `b` (of one tree).
    fn path_length(&self, mut a: u32, mut b: u32) -> f64 {
        let total = self.height[a as usize] + self.height[b as usize];
        while self.depth[a as usize] > self.depth[b as usize] {
            a = self.parent[a as usize];
        }
        while self.depth[b as usize] > self.depth[a as usize] {
            b = self.parent[b as usize];
        }
        while a != b {
            a = self.parent[a as usize];
            b = self.parent[b as usize];
        }
        total - 2.0 * self.height[a as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(x: f64, y: f64, significance: f64) -> SkeletonPoint {
        SkeletonPoint {
            position: [x, y, 0.0],
            on: SurfacePoint::Vertex(0),
            significance,
            tubularity: f64::INFINITY,
            radius: None,
        }
    }

    /// A small square loop (what never burns) with a branch of the thinning hanging
    /// from each of two opposite corners, each with an erosion thickness larger than its
    /// length (as a branch that stood long on curves has): cutting the loop leaves a
    /// path whose new burn (by length) finds the loop's pieces less significant than
    /// the branches, and pruning between the two must keep the corners the branches
    /// hang from and the path between them, or the skeleton falls in two.
    #[test]
    fn cutting_a_cycle_never_splits_the_skeleton() {
        let mut points = vec![
            point(0.0, 0.0, f64::INFINITY),
            point(1.0, 0.0, f64::INFINITY),
            point(1.0, 1.0, f64::INFINITY),
            point(0.0, 1.0, f64::INFINITY),
        ];
        let mut edges = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
        for (corner, direction) in [(0u32, -1.0), (2, 1.0)] {
            let (x, y) = (f64::from(corner / 2), f64::from(corner / 2));
            let mut previous = corner;
            for i in 1..=10 {
                let id = points.len() as u32;
                points.push(point(x + direction * f64::from(i), y, 100.0));
                edges.push([previous, id]);
                previous = id;
            }
        }
        let skeleton = Skeleton {
            points,
            edges,
            ..Skeleton::default()
        };
        let cut = skeleton.with_cycles_cut(0, |_| 1.0, |_| false, 0.0, 20.0);
        assert_eq!((cut.component_count(), cut.cycle_count()), (1, 0));
        assert!(
            cut.points.len() >= 20,
            "the branches stay: {}",
            cut.points.len()
        );
    }

    /// A graph of polylines through the given corners, each with one radius, joined
    /// where they share a corner: a trunk of radius 1 along x from -5 to 5 (points every
    /// 0.25), and `others`.
    fn trunk_and(others: &[(&[[f64; 2]], f64)]) -> (Skeleton, Vec<f64>) {
        let mut points: Vec<[f64; 3]> = Vec::new();
        let mut radii = Vec::new();
        let mut edges = Vec::new();
        let mut id = |p: [f64; 2], r: f64, points: &mut Vec<[f64; 3]>| {
            let at = [p[0], p[1], 0.0];
            if let Some(i) = points
                .iter()
                .position(|&q| DVec3::from(q).distance(at.into()) < 1e-9)
            {
                return i as u32;
            }
            points.push(at);
            radii.push(r);
            points.len() as u32 - 1
        };
        let trunk: &[[f64; 2]] = &[[-5.0, 0.0], [-1.0, 0.0], [1.0, 0.0], [5.0, 0.0]];
        for &(corners, r) in std::iter::once(&(trunk, 1.0)).chain(others) {
            for pair in corners.windows(2) {
                let (a, b) = (
                    DVec3::new(pair[0][0], pair[0][1], 0.0),
                    DVec3::new(pair[1][0], pair[1][1], 0.0),
                );
                let steps = (a.distance(b) / 0.25).round().max(1.0) as usize;
                let mut previous = id(pair[0], r, &mut points);
                for k in 1..=steps {
                    let q = a.lerp(b, k as f64 / steps as f64);
                    let next = id([q.x, q.y], r, &mut points);
                    edges.push([previous, next]);
                    previous = next;
                }
            }
        }
        (Skeleton::from_curves(&points, &edges, None), radii)
    }

    /// A second strand beside the trunk (a hole in a sheet split it off), its balls
    /// inside the trunk's: the cycle opens by taking the strand whole, with no stubs
    /// left; told to keep every branch (protrusion 0), the cut leaves two.
    #[test]
    fn a_strand_inside_the_body_goes_whole() {
        let strand: &[[f64; 2]] = &[[-1.0, 0.0], [-0.75, 0.3], [0.75, 0.3], [1.0, 0.0]];
        let (skeleton, radii) = trunk_and(&[(strand, 0.8)]);
        assert_eq!(skeleton.cycle_count(), 1);
        let width = |i: usize| radii[i];
        let opened = skeleton
            .clone()
            .with_cycles_cut(0, width, |_| false, 0.5, 0.0);
        assert_eq!((opened.cycle_count(), opened.component_count()), (0, 1));
        assert_eq!(opened.tip_count(), 2);
        assert!(
            opened.points.iter().all(|p| p.position[1] == 0.0),
            "the trunk is left"
        );
        // Filled, the cycle opens though one could stay.
        let filled = skeleton
            .clone()
            .with_cycles_cut(1, width, |_| true, 0.5, 0.0);
        assert_eq!(filled, opened);
        assert_eq!(
            skeleton
                .clone()
                .with_cycles_cut(1, width, |_| false, 0.5, 0.0),
            skeleton
        );
        let cut = skeleton.with_cycles_cut(0, width, |_| false, 0.0, 0.0);
        assert_eq!((cut.cycle_count(), cut.tip_count()), (0, 4));
    }

    /// A limb that a hole joined back to the trunk through a narrow neck: it reaches far
    /// out of the trunk's balls, so the cycle is cut at the neck (its narrowest point) and
    /// the limb keeps its length; the stub on the trunk side is shorter than the pruning
    /// threshold.
    #[test]
    fn a_limb_joined_back_opens_at_its_neck() {
        let limb: &[[f64; 2]] = &[[-1.0, 0.0], [-1.0, 3.0], [1.0, 3.0], [1.0, 1.0]];
        let neck: &[[f64; 2]] = &[[1.0, 1.0], [1.0, 0.0]];
        let (skeleton, mut radii) = trunk_and(&[(limb, 0.4), (neck, 0.3)]);
        let narrowest = skeleton
            .points
            .iter()
            .position(|p| p.position == [1.0, 0.75, 0.0]);
        radii[narrowest.expect("on the neck")] = 0.05;
        let opened = skeleton.with_cycles_cut(0, |i| radii[i], |_| false, 0.5, 1.5);
        assert_eq!((opened.cycle_count(), opened.component_count()), (0, 1));
        assert_eq!(opened.tip_count(), 3, "the trunk's ends and the limb's");
        assert!(opened.points.iter().any(|p| p.position == [1.0, 1.5, 0.0]));
        let neck_left =
            |p: &SkeletonPoint| p.position[0] == 1.0 && (0.1..0.7).contains(&p.position[1]);
        assert!(
            !opened.points.iter().any(neck_left),
            "the stub below the neck is pruned"
        );
    }
}
