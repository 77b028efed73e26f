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
        self.reburnt(edges).pruned(prune)
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
