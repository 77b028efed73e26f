//! Cutting a skeleton's extra cycles: a medial axis computed from a sampled surface has
//! small holes where its sheets are thin (see [`crate::skeleton::medial`]), and thinning keeps a
//! cycle around each; the solid has as many independent cycles as its genus.

use super::{Skeleton, SkeletonPoint};
use crate::mesh::DisjointSets;
use crate::surface::SurfacePoint;
use glam::DVec3;

impl Skeleton {
    /// The skeleton with at most `max_cycles` independent cycles: the graph's spanning
    /// forest of widest edges (an edge's width: the smaller `width` of its two points,
    /// such as their medial radius), plus the `max_cycles` edges outside it whose cycles
    /// through the forest are the longest. A cycle around a small hole in the axis is
    /// short and cut where it is narrowest; a handle of the shape is a long loop, and
    /// kept. The branches the cuts leave are burnt again from their new tips along the
    /// graph (their significance: the length burnt, as [`Skeleton::from_curves`]
    /// gives it; tubularity `inf`), then pruned at `prune` ([`Skeleton::pruned`]); other
    /// points keep their significance and tubularity. A skeleton with no more cycles
    /// than `max_cycles` is returned as it is.
    ///
    /// # Panics
    /// If `width` panics for a point index below `self.points.len()`.
    #[must_use]
    pub fn with_cycles_cut(
        self,
        max_cycles: usize,
        width: impl Fn(usize) -> f64,
        prune: f64,
    ) -> Skeleton {
        if self.cycle_count() <= max_cycles {
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
            .into_iter()
            .map(|e| (forest.path_length(e[0], e[1]) + length(e), e))
            .collect();
        loops.sort_by(|x, y| y.0.total_cmp(&x.0));
        let mut edges: Vec<[u32; 2]> = (0..n as u32)
            .flat_map(|a| {
                tree[a as usize]
                    .iter()
                    .filter(move |&&b| a < b)
                    .map(move |&b| [a, b])
            })
            .collect();
        edges.extend(loops.iter().take(max_cycles).map(|&(_, e)| e));
        let mut cut = self.reburnt(edges);
        cut.raise_towards_the_core();
        cut.pruned(prune)
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
        let cut = skeleton.with_cycles_cut(0, |_| 1.0, 20.0);
        assert_eq!((cut.component_count(), cut.cycle_count()), (1, 0));
        assert!(
            cut.points.len() >= 20,
            "the branches stay: {}",
            cut.points.len()
        );
    }
}
