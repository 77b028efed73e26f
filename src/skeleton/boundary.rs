//! The boundary of a surface as a metric graph: where each grassfire source sits along
//! it, and how far apart two sources are when one walks along the boundary only.
//!
//! The boundary (edges with exactly one face) of a non-manifold surface is a graph, not
//! a set of loops: several boundary curves may meet at a vertex where sheets touch. It
//! is cut into *chains* (maximal runs through vertices with two boundary edges) between
//! *junctions* (boundary vertices with another count), and closed *loops* without any
//! junction. A point's position is its chain and arc length along it; two points are
//! as far apart as the shorter way along their chain, or out through a chain's ends and
//! across the junction graph, whose distances are found once per junction asked about.

use super::Ordered;
use crate::mesh::{TriMesh, NONE};
use crate::steiner::SteinerLayout;
use geotracks_metrics::Metric;
use std::cell::OnceCell;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

/// Where a boundary node sits.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    /// A vertex where the count of boundary edges is not two.
    Junction(u32),
    /// Arc length `s` (metric units) along chain `chain`.
    Chain { chain: u32, s: f64 },
}

/// A point's ways out to junctions along its chain: `(junction, cost)`, `NONE` unused.
type Exits = [(u32, f64); 2];

/// A maximal run of boundary edges through vertices with two boundary edges.
#[derive(Clone, Copy, Debug)]
struct Chain {
    /// Its junctions at the start and the end; `NONE` for a closed loop.
    ends: [u32; 2],
    /// Its metric length.
    length: f64,
}

/// Distances along the boundary between boundary nodes of a Steiner layout.
pub(crate) struct BoundaryArcs {
    /// Every node on a boundary edge, sorted, with its place and local step.
    nodes: Vec<u32>,
    places: Vec<Place>,
    /// The larger metric length of the two boundary segments at the node.
    steps: Vec<f64>,
    chains: Vec<Chain>,
    /// Per junction, the chains that start or end there (a chain from a junction back to
    /// itself appears twice).
    junction_chains: Vec<Vec<u32>>,
    /// Per junction, distances to every junction, found on first use.
    junction_distances: Vec<OnceCell<Vec<f64>>>,
}

/// Is edge `e` on the boundary (exactly one face)?
pub(crate) fn is_boundary_edge(mesh: &TriMesh, e: u32) -> bool {
    mesh.edge_faces(e).len() == 1
}

impl BoundaryArcs {
    /// Builds the boundary of `mesh` with the nodes of `layout` on it, measuring along
    /// boundary edges with `metric` (in the edge's one face).
    pub fn new<M: Metric>(mesh: &TriMesh, layout: &SteinerLayout, metric: &M) -> BoundaryArcs {
        let boundary_edges: Vec<u32> = (0..mesh.edge_count() as u32)
            .filter(|&e| is_boundary_edge(mesh, e))
            .collect();
        let mut around: HashMap<u32, Vec<u32>> = HashMap::new();
        for &e in &boundary_edges {
            for v in mesh.edge_vertices(e) {
                around.entry(v).or_default().push(e);
            }
        }
        let mut junctions: Vec<u32> = around
            .iter()
            .filter(|(_, edges)| edges.len() != 2)
            .map(|(&v, _)| v)
            .collect();
        junctions.sort_unstable();

        let mut builder = Builder {
            mesh,
            layout,
            metric,
            around,
            junction_of: junctions
                .iter()
                .enumerate()
                .map(|(j, &v)| (v, j as u32))
                .collect(),
            place_of: junctions
                .iter()
                .enumerate()
                .map(|(j, &v)| (v, (Place::Junction(j as u32), 0.0)))
                .collect(),
            visited: vec![false; mesh.edge_count()],
            chains: Vec::new(),
            junction_chains: vec![Vec::new(); junctions.len()],
        };
        for &v in &junctions {
            for e in builder.around[&v].clone() {
                if !builder.visited[e as usize] {
                    builder.walk(v, e);
                }
            }
        }
        // What is left are closed loops through vertices with two boundary edges.
        for &e in &boundary_edges {
            if !builder.visited[e as usize] {
                let start = mesh.edge_vertices(e)[0];
                let chain = builder.chains.len() as u32;
                builder
                    .place_of
                    .insert(start, (Place::Chain { chain, s: 0.0 }, 0.0));
                builder.walk(start, e);
            }
        }

        let mut entries: Vec<(u32, (Place, f64))> = builder.place_of.into_iter().collect();
        entries.sort_unstable_by_key(|(node, _)| *node);
        BoundaryArcs {
            nodes: entries.iter().map(|(node, _)| *node).collect(),
            places: entries.iter().map(|(_, (place, _))| *place).collect(),
            steps: entries.iter().map(|(_, (_, step))| *step).collect(),
            chains: builder.chains,
            junction_distances: (0..junctions.len()).map(|_| OnceCell::new()).collect(),
            junction_chains: builder.junction_chains,
        }
    }

    /// The nodes on the boundary, sorted.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes
    }

    /// The larger metric length of the boundary segments at boundary node number `i`
    /// (an index into [`BoundaryArcs::nodes`]).
    pub fn step(&self, i: usize) -> f64 {
        self.steps[i]
    }

    /// Distance along the boundary between boundary nodes number `a` and `b` (indices
    /// into [`BoundaryArcs::nodes`]); `inf` when no boundary path joins them.
    pub fn distance(&self, a: usize, b: usize) -> f64 {
        if a == b {
            return 0.0;
        }
        // Each point's ways out to junctions: (junction, cost), and its chain position.
        let exits = |p: Place| -> (Exits, Option<(u32, f64)>) {
            match p {
                Place::Junction(j) => ([(j, 0.0), (NONE, 0.0)], None),
                Place::Chain { chain, s } => {
                    let c = self.chains[chain as usize];
                    (
                        [(c.ends[0], s), (c.ends[1], c.length - s)],
                        Some((chain, s)),
                    )
                }
            }
        };
        let (ea, ca) = exits(self.places[a]);
        let (eb, cb) = exits(self.places[b]);
        let mut best = f64::INFINITY;
        if let (Some((chain_a, sa)), Some((chain_b, sb))) = (ca, cb) {
            if chain_a == chain_b {
                let c = self.chains[chain_a as usize];
                let direct = (sa - sb).abs();
                best = if c.ends[0] == NONE {
                    direct.min(c.length - direct)
                } else {
                    direct
                };
            }
        }
        for &(ja, ca) in &ea {
            if ja == NONE {
                continue;
            }
            let from_a = self.junction_distances(ja);
            for &(jb, cb) in &eb {
                if jb != NONE {
                    best = best.min(ca + from_a[jb as usize] + cb);
                }
            }
        }
        best
    }

    /// Distances from junction `j` to every junction across the chains (Dijkstra).
    fn junction_distances(&self, j: u32) -> &[f64] {
        self.junction_distances[j as usize].get_or_init(|| {
            let mut distance = vec![f64::INFINITY; self.junction_chains.len()];
            let mut heap = BinaryHeap::new();
            distance[j as usize] = 0.0;
            heap.push(Reverse((Ordered(0.0), j)));
            while let Some(Reverse((Ordered(d), u))) = heap.pop() {
                if d > distance[u as usize] {
                    continue;
                }
                for &c in &self.junction_chains[u as usize] {
                    let chain = self.chains[c as usize];
                    let other = if chain.ends[0] == u {
                        chain.ends[1]
                    } else {
                        chain.ends[0]
                    };
                    let value = d + chain.length;
                    if value < distance[other as usize] {
                        distance[other as usize] = value;
                        heap.push(Reverse((Ordered(value), other)));
                    }
                }
            }
            distance
        })
    }
}

/// The state of [`BoundaryArcs::new`] while it walks the chains.
struct Builder<'a, M> {
    mesh: &'a TriMesh,
    layout: &'a SteinerLayout,
    metric: &'a M,
    /// Boundary edges around each vertex that has some.
    around: HashMap<u32, Vec<u32>>,
    junction_of: HashMap<u32, u32>,
    /// Each boundary node's place and the longest boundary segment touching it.
    place_of: HashMap<u32, (Place, f64)>,
    visited: Vec<bool>,
    chains: Vec<Chain>,
    junction_chains: Vec<Vec<u32>>,
}

impl<M: Metric> Builder<'_, M> {
    /// Walks a new chain from vertex `start` along boundary edge `first` to a junction,
    /// or back to `start` around a loop, placing the nodes it passes.
    fn walk(&mut self, start: u32, first: u32) {
        let (mesh, layout) = (self.mesh, self.layout);
        let chain = self.chains.len() as u32;
        let (mut v, mut e, mut s) = (start, first, 0.0);
        loop {
            self.visited[e as usize] = true;
            let face = mesh.edge_faces(e)[0];
            let [lo, hi] = mesh.edge_vertices(e);
            let next = if v == lo { hi } else { lo };
            let mut steiner: Vec<u32> = layout.edge_nodes(e).collect();
            if v == hi {
                steiner.reverse();
            }
            let mut previous = (v, layout.point_in_face(mesh, v, face));
            for node in steiner.into_iter().chain(std::iter::once(next)) {
                let point = layout.point_in_face(mesh, node, face);
                let step = self.metric.cost(face, &previous.1, &point);
                s += step;
                self.widen(previous.0, step);
                if self.junction_of.contains_key(&node) || node == start {
                    self.widen(node, step);
                } else {
                    self.place_of
                        .insert(node, (Place::Chain { chain, s }, step));
                }
                previous = (node, point);
            }
            v = next;
            if let Some(&j) = self.junction_of.get(&v) {
                let from = self.junction_of[&start];
                self.chains.push(Chain {
                    ends: [from, j],
                    length: s,
                });
                self.junction_chains[from as usize].push(chain);
                self.junction_chains[j as usize].push(chain);
                return;
            }
            if v == start {
                self.chains.push(Chain {
                    ends: [NONE, NONE],
                    length: s,
                });
                return;
            }
            let edges = &self.around[&v];
            e = if edges[0] == e { edges[1] } else { edges[0] };
        }
    }

    /// Records that a boundary segment of metric length `step` touches `node`.
    fn widen(&mut self, node: u32, step: f64) {
        if let Some((_, s)) = self.place_of.get_mut(&node) {
            *s = s.max(step);
        }
    }
}
