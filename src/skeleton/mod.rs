//! Skeletons of medial axes: burn the surface from its boundary ([`Grassfire`]), trace
//! the ridges where fronts from far-apart boundary origins meet, join them with the
//! medial axis's free edges into one graph ([`Skeleton`]) and prune short branches.
//!
//! ```
//! use geotracks::{mesh::TriMesh, skeleton::Skeleton, Euclidean, Options};
//!
//! // A flat 4 × 1 strip, 16 × 4 squares each cut in two.
//! let (nx, ny) = (16, 4);
//! let mut positions = Vec::new();
//! for j in 0..=ny {
//!     for i in 0..=nx {
//!         positions.push([i as f64 * 0.25, j as f64 * 0.25, 0.0]);
//!     }
//! }
//! let id = |i: u32, j: u32| j * (nx + 1) + i;
//! let mut triangles = Vec::new();
//! for j in 0..ny {
//!     for i in 0..nx {
//!         triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
//!         triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
//!     }
//! }
//! let mesh = TriMesh::new(positions, triangles)?;
//! let skeleton = Skeleton::extract(&mesh, &Euclidean, &Options::DEFAULT.with_k(4.0))?;
//! // Drop what lies between boundary points less than 1.5 apart along the boundary:
//! // the corner branches (at most the strip's width, 1).
//! let core = skeleton.pruned(1.5);
//! assert_eq!(core.component_count(), 1);
//! // What is left runs along the strip's middle line.
//! assert!(core.points.iter().all(|p| (p.position[1] - 0.5).abs() < 0.05));
//! assert!(core.length() > 2.5 && core.length() < skeleton.length());
//! # Ok::<(), geotracks::Error>(())
//! ```

mod boundary;
mod grassfire;
mod ridges;

pub use grassfire::{radius_speed, Grassfire};

use crate::mesh::io::MedialAxis;
use crate::mesh::{DisjointSets, TriMesh, NONE};
use crate::options::{Options, Stop};
use crate::steiner::SteinerLayout;
use crate::surface::{Source, SurfacePoint};
use crate::{Error, Euclidean, GeodesicField, Metric};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A point of a [`Skeleton`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SkeletonPoint {
    /// World position.
    pub position: [f64; 3],
    /// Where it lies on the surface (a vertex for the ends of free edges).
    pub on: SurfacePoint,
    /// How far apart, along the boundary, the two origins whose fronts meet here are
    /// (metric length), or, for origins on two boundary curves that no walk along the
    /// boundary joins, their straight distance; `inf` for points of free edges, and for
    /// the one point of a surface where no ridge was found; bridge points take the
    /// smaller of their ends'. [`Skeleton::pruned`] removes points below a threshold.
    pub significance: f64,
}

/// A skeleton: a graph of points on a surface (and on its free edges), with straight
/// edges that each lie in one face or along one free edge.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Skeleton {
    /// The graph's points.
    pub points: Vec<SkeletonPoint>,
    /// Its edges, as pairs of indices into `points`.
    pub edges: Vec<[u32; 2]>,
    /// Components of the surface that have no boundary, so no grassfire and no
    /// skeleton (a closed sheet, say).
    pub closed_components: usize,
}

impl Skeleton {
    /// The unpruned skeleton of `mesh` burnt from its boundary under `metric`, joined
    /// with the mesh's line elements (free edges); see [`Skeleton::from_grassfire`].
    ///
    /// # Errors
    /// As [`Grassfire::burn`].
    pub fn extract<M: Metric>(
        mesh: &TriMesh,
        metric: &M,
        options: &Options,
    ) -> Result<Skeleton, Error> {
        let fire = Grassfire::burn(mesh, metric, options)?;
        Skeleton::from_grassfire(&fire)
    }

    /// The unpruned skeleton from a grassfire already burnt (on its mesh, under its
    /// metric and Steiner points):
    /// - the ridges: crossings on edges where fronts from origins far apart along the
    ///   boundary meet head-on, joined across each face;
    /// - the mesh's line elements (a medial axis's free edges), whole;
    /// - bridges: where this graph falls into pieces on one connected surface (a ridge
    ///   too weak to see, or a free edge hanging off a sheet), the pieces are joined by
    ///   shortest paths on the surface, cheapest first (a spanning tree of the
    ///   pieces), so each connected surface gives one connected skeleton. A connected
    ///   surface on which no ridge is found still gets one point: where the fire burnt
    ///   last.
    ///
    /// The bridges' distance field is computed by the fire's solver.
    ///
    /// # Errors
    /// As [`Solver::solve_from`](crate::Solver::solve_from), for the bridges.
    pub fn from_grassfire<M: Metric>(fire: &Grassfire<'_, M>) -> Result<Skeleton, Error> {
        let (mesh, metric) = (fire.solver().mesh(), fire.solver().metric());
        let mut skeleton = ridges::ridges(mesh, metric, fire);
        skeleton.drop_isolated();
        skeleton.add_free_edges(mesh, mesh.line_edges());
        let (component, count) = mesh.vertex_components();
        let mut burnt = vec![false; count];
        let mut last = vec![(f64::NEG_INFINITY, NONE); count];
        let distances = fire.field().vertex_distances();
        for (v, &d) in distances.iter().enumerate() {
            let c = component[v] as usize;
            if d.is_finite() && !mesh.vertex_faces(v as u32).is_empty() {
                burnt[c] = true;
                if d > last[c].0 {
                    last[c] = (d, v as u32);
                }
            }
        }
        // Surfaces without any ridge point get their last-burnt vertex.
        let mut has_point = vec![false; count];
        for point in &skeleton.points {
            if let Some(v) = any_vertex(mesh, point.on) {
                has_point[component[v as usize] as usize] = true;
            }
        }
        for c in 0..count {
            if burnt[c] && !has_point[c] {
                skeleton.push(mesh, SurfacePoint::Vertex(last[c].1), f64::INFINITY);
            }
        }
        let mut has_faces = vec![false; count];
        for t in mesh.triangles() {
            has_faces[component[t[0] as usize] as usize] = true;
        }
        skeleton.closed_components = (0..count).filter(|&c| !burnt[c] && has_faces[c]).count();
        skeleton.bridge(fire.solver())?;
        Ok(skeleton)
    }

    /// The skeleton of a medial axis of curves only: its free edges.
    pub fn from_curves(positions: &[[f64; 3]], free_edges: &[[u32; 2]]) -> Skeleton {
        let mut skeleton = Skeleton::default();
        let mut node_of = vec![NONE; positions.len()];
        for &[a, b] in free_edges {
            let mut node = |v: u32| {
                if node_of[v as usize] == NONE {
                    node_of[v as usize] = skeleton.points.len() as u32;
                    skeleton.points.push(SkeletonPoint {
                        position: positions[v as usize],
                        on: SurfacePoint::Vertex(v),
                        significance: f64::INFINITY,
                    });
                }
                node_of[v as usize]
            };
            let edge = [node(a), node(b)];
            skeleton.edges.push(edge);
        }
        skeleton
    }

    /// The skeleton with its points of significance below `threshold` removed, least
    /// significant first, as long as removing one does not cut its piece of the graph
    /// apart: branches shrink from their tips, small loops left by the discretisation
    /// open up, and each component keeps at least one point.
    /// `threshold` ≤ 0 removes nothing.
    ///
    /// A loop whose points are all below the threshold opens (a ridge around a small
    /// hole); it shrinks like a branch from there. Whether a point cuts the graph is checked near it (its neighbours must stay
    /// joined within [`Skeleton::LOCAL_HOPS`] hops), so a point on a long loop of low
    /// significance stays.
    pub fn pruned(&self, threshold: f64) -> Skeleton {
        let n = self.points.len();
        let neighbours = self.adjacency();
        let (component, count) = self.components();
        let mut left_in = vec![0usize; count];
        for &c in &component {
            left_in[c as usize] += 1;
        }
        let mut removed = vec![false; n];
        let mut search = LocalSearch::new(n);
        let mut queue = BinaryHeap::new();
        let weak = |i: usize| self.points[i].significance < threshold;
        for i in (0..n).filter(|&i| weak(i)) {
            queue.push(Reverse((Ordered(self.points[i].significance), i as u32)));
        }
        while let Some(Reverse((_, i))) = queue.pop() {
            let i = i as usize;
            let c = component[i] as usize;
            if removed[i] || left_in[c] == 1 || !search.removable(i as u32, &neighbours, &removed) {
                continue;
            }
            removed[i] = true;
            left_in[c] -= 1;
            // A neighbour that was kept to hold the graph together may be free now.
            for &j in &neighbours[i] {
                if !removed[j as usize] && weak(j as usize) {
                    queue.push(Reverse((Ordered(self.points[j as usize].significance), j)));
                }
            }
        }
        self.keep(|i| !removed[i])
    }

    /// How far [`Skeleton::pruned`] looks for another way between a point's neighbours.
    pub const LOCAL_HOPS: u32 = 24;

    /// The graph cut into polylines (point indices) between points whose degree is not
    /// 2; a cycle of degree-2 points is one closed polyline (first point repeated last).
    /// An isolated point is a polyline of one point.
    pub fn polylines(&self) -> Vec<Vec<u32>> {
        let neighbours = self.adjacency();
        let mut used = vec![false; self.edges.len()];
        let mut edge_ids: Vec<Vec<(u32, usize)>> = vec![Vec::new(); self.points.len()];
        for (k, &[a, b]) in self.edges.iter().enumerate() {
            edge_ids[a as usize].push((b, k));
            edge_ids[b as usize].push((a, k));
        }
        let mut lines = Vec::new();
        let follow = |start: u32, first: (u32, usize), used: &mut Vec<bool>| {
            let mut line = vec![start];
            let (mut at, mut via) = first;
            loop {
                used[via] = true;
                line.push(at);
                if neighbours[at as usize].len() != 2 || at == start {
                    break;
                }
                match edge_ids[at as usize].iter().find(|(_, k)| !used[*k]) {
                    Some(&(next, k)) => (at, via) = (next, k),
                    None => break,
                }
            }
            line
        };
        for i in 0..self.points.len() as u32 {
            match neighbours[i as usize].len() {
                0 => lines.push(vec![i]),
                2 => {}
                _ => {
                    for &(j, k) in &edge_ids[i as usize] {
                        if !used[k] {
                            lines.push(follow(i, (j, k), &mut used));
                        }
                    }
                }
            }
        }
        // Cycles of degree-2 points.
        for i in 0..self.points.len() as u32 {
            if let Some(&(j, k)) = edge_ids[i as usize].iter().find(|(_, k)| !used[*k]) {
                lines.push(follow(i, (j, k), &mut used));
            }
        }
        lines
    }

    /// The polylines as world positions, ready for
    /// [`write_obj_polylines`](crate::mesh::io::write_obj_polylines).
    pub fn polyline_positions(&self) -> Vec<Vec<[f64; 3]>> {
        self.polylines()
            .iter()
            .map(|line| {
                line.iter()
                    .map(|&i| self.points[i as usize].position)
                    .collect()
            })
            .collect()
    }

    /// Connected components of the graph: a label per point and their count.
    pub fn components(&self) -> (Vec<u32>, usize) {
        let mut sets = DisjointSets::new(self.points.len());
        for &[a, b] in &self.edges {
            sets.join(a, b);
        }
        sets.labels()
    }

    /// Number of connected components of the graph.
    pub fn component_count(&self) -> usize {
        self.components().1
    }

    /// Total Euclidean length of the edges.
    pub fn length(&self) -> f64 {
        self.edges
            .iter()
            .map(|&[a, b]| {
                let (p, q) = (self.points[a as usize], self.points[b as usize]);
                glam::DVec3::from(p.position).distance(glam::DVec3::from(q.position))
            })
            .sum()
    }

    /// The sub-graph of the points `keep` accepts (edges between two kept points).
    pub fn keep_where(&self, keep: impl Fn(&SkeletonPoint) -> bool) -> Skeleton {
        self.keep(|i| keep(&self.points[i]))
    }

    fn adjacency(&self) -> Vec<Vec<u32>> {
        let mut neighbours = vec![Vec::new(); self.points.len()];
        for &[a, b] in &self.edges {
            neighbours[a as usize].push(b);
            neighbours[b as usize].push(a);
        }
        neighbours
    }

    /// The sub-graph of the points `keep` accepts, renumbered in order.
    fn keep(&self, keep: impl Fn(usize) -> bool) -> Skeleton {
        let mut new_id = vec![NONE; self.points.len()];
        let mut points = Vec::new();
        for (i, point) in self.points.iter().enumerate() {
            if keep(i) {
                new_id[i] = points.len() as u32;
                points.push(*point);
            }
        }
        let edges = self
            .edges
            .iter()
            .map(|&[a, b]| [new_id[a as usize], new_id[b as usize]])
            .filter(|e| e[0] != NONE && e[1] != NONE)
            .collect();
        Skeleton {
            points,
            edges,
            closed_components: self.closed_components,
        }
    }

    /// Drops points without any edge (a ridge seen on one edge only).
    fn drop_isolated(&mut self) {
        let mut touched = vec![false; self.points.len()];
        for &[a, b] in &self.edges {
            touched[a as usize] = true;
            touched[b as usize] = true;
        }
        *self = self.keep(|i| touched[i]);
    }

    fn push(&mut self, mesh: &TriMesh, on: SurfacePoint, significance: f64) -> u32 {
        self.points.push(SkeletonPoint {
            position: on.position(mesh).to_array(),
            on,
            significance,
        });
        self.points.len() as u32 - 1
    }

    fn add_free_edges(&mut self, mesh: &TriMesh, free_edges: &[[u32; 2]]) {
        let positions: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
        let curves = Skeleton::from_curves(&positions, free_edges);
        let offset = self.points.len() as u32;
        self.points.extend(curves.points);
        self.edges
            .extend(curves.edges.iter().map(|&[a, b]| [a + offset, b + offset]));
    }

    /// Joins the pieces of the graph that lie on one connected surface by shortest
    /// paths, cheapest first.
    fn bridge<M: Metric>(&mut self, solver: &crate::Solver<'_, M>) -> Result<(), Error> {
        let (mesh, metric) = (solver.mesh(), solver.metric());
        let (piece, _) = self.components();
        let (surface, _) = mesh.vertex_components();
        // A piece may touch several surfaces (through free edges): count each pair once.
        let mut touching: Vec<(u32, u32)> = self
            .points
            .iter()
            .enumerate()
            .filter_map(|(i, p)| any_vertex(mesh, p.on).map(|v| (surface[v as usize], piece[i])))
            .collect();
        touching.sort_unstable();
        touching.dedup();
        if touching.windows(2).all(|w| w[0].0 != w[1].0) {
            return Ok(());
        }
        // A distance field from every point of the graph that lies on a face.
        let on_faces: Vec<u32> = (0..self.points.len() as u32)
            .filter(|&i| !self.points[i as usize].on.faces(mesh).is_empty())
            .collect();
        let sources: Vec<Source> = on_faces
            .iter()
            .map(|&i| Source::new(self.points[i as usize].on))
            .collect();
        let field = solver.solve_from(&sources, &Stop::NONE)?;
        let query = solver.query(&field)?;
        let labels = query.node_labels();
        let layout = field.layout();
        let distances = field.node_distances();
        // Neighbouring nodes along an edge from two different pieces: a candidate bridge.
        let mut candidates = Vec::new();
        for e in 0..mesh.edge_count() as u32 {
            for pair in edge_sequence(mesh, layout, e).windows(2) {
                let (p, q) = (pair[0], pair[1]);
                let (lp, lq) = (labels[p as usize], labels[q as usize]);
                if lp == NONE || lq == NONE {
                    continue;
                }
                let (a, b) = (on_faces[lp as usize], on_faces[lq as usize]);
                if piece[a as usize] == piece[b as usize] {
                    continue;
                }
                let step = cost_along(mesh, layout, metric, e, p, q);
                let cost = distances[p as usize] + step + distances[q as usize];
                if cost.is_finite() {
                    candidates.push((Ordered(cost), p, q));
                }
            }
        }
        candidates.sort_unstable_by_key(|c| c.0);
        let mut sets = DisjointSets::new(self.points.len());
        for &[a, b] in &self.edges {
            sets.join(a, b);
        }
        for (_, p, q) in candidates {
            let (a, b) = (
                on_faces[labels[p as usize] as usize],
                on_faces[labels[q as usize] as usize],
            );
            if !sets.join(a, b) {
                continue;
            }
            // Paths end at the sources their labels name: a and b.
            let from_p = query.path(layout.surface_point(p))?;
            let from_q = query.path(layout.surface_point(q))?;
            let significance = self.points[a as usize]
                .significance
                .min(self.points[b as usize].significance);
            // a ← … ← p — q → … → b; the paths end at their sources, which are a and b.
            let mut chain = vec![a];
            for &point in from_p.points[..from_p.points.len() - 1].iter().rev() {
                chain.push(self.push(mesh, point, significance));
            }
            for &point in &from_q.points[..from_q.points.len() - 1] {
                chain.push(self.push(mesh, point, significance));
            }
            chain.push(b);
            self.edges.extend(chain.windows(2).map(|w| [w[0], w[1]]));
        }
        Ok(())
    }
}

/// The skeleton of a medial axis read from a `.ma` file, with `prune` as in
/// [`Skeleton::pruned`]: its sheets burnt from their boundary (with a
/// [`radius_speed`] density when `radius_aware`, else Euclidean) and joined with its
/// free edges; for a medial axis of curves only, its free edges. Also returns the
/// grassfire's distance field, if there were sheets.
///
/// # Errors
/// As [`Skeleton::extract`]; [`Error::Metric`] if a radius is unusable for the
/// radius-aware speed.
pub fn medial_axis_skeleton(
    axis: &MedialAxis,
    radius_aware: bool,
    options: &Options,
    prune: f64,
) -> Result<(Skeleton, Option<GeodesicField>), Error> {
    let Some(mesh) = &axis.surface else {
        let skeleton = Skeleton::from_curves(&axis.positions, &axis.free_edges);
        return Ok((skeleton.pruned(prune), None));
    };
    let (skeleton, field) = if radius_aware {
        let fire = Grassfire::burn(mesh, radius_speed(mesh, &axis.radii)?, options)?;
        (Skeleton::from_grassfire(&fire)?, fire.into_field())
    } else {
        let fire = Grassfire::burn(mesh, Euclidean, options)?;
        (Skeleton::from_grassfire(&fire)?, fire.into_field())
    };
    Ok((skeleton.pruned(prune), Some(field)))
}

/// The nodes along edge `e` from its lower vertex to its higher one.
fn edge_sequence(mesh: &TriMesh, layout: &SteinerLayout, e: u32) -> Vec<u32> {
    let [lo, hi] = mesh.edge_vertices(e);
    std::iter::once(lo)
        .chain(layout.edge_nodes(e))
        .chain(std::iter::once(hi))
        .collect()
}

/// The cost between neighbouring nodes `p` and `q` of edge `e`, in the cheapest face
/// around it, as the engines charge a step along an edge.
fn cost_along<M: Metric>(
    mesh: &TriMesh,
    layout: &SteinerLayout,
    metric: &M,
    e: u32,
    p: u32,
    q: u32,
) -> f64 {
    mesh.edge_faces(e)
        .iter()
        .map(|&g| {
            metric.cost(
                g,
                &layout.point_in_face(mesh, p, g),
                &layout.point_in_face(mesh, q, g),
            )
        })
        .fold(f64::INFINITY, f64::min)
}

/// A vertex of the face, edge or vertex `on` lies on.
fn any_vertex(mesh: &TriMesh, on: SurfacePoint) -> Option<u32> {
    match on {
        SurfacePoint::Vertex(v) => Some(v),
        SurfacePoint::Edge { edge, .. } => Some(mesh.edge_vertices(edge)[0]),
        SurfacePoint::Face { face, .. } => Some(mesh.face_vertices(face)[0]),
    }
}

/// An f64 with a total order, for sorting and heaps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ordered(pub f64);

impl Eq for Ordered {}

impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// A breadth-first search limited to [`Skeleton::LOCAL_HOPS`] hops, reusing its
/// buffers between calls.
struct LocalSearch {
    /// The call that last reached each point.
    seen: Vec<u32>,
    call: u32,
    frontier: Vec<(u32, u32)>,
}

impl LocalSearch {
    fn new(n: usize) -> LocalSearch {
        LocalSearch {
            seen: vec![0; n],
            call: 0,
            frontier: Vec::new(),
        }
    }

    /// Can point `i` go without cutting its neighbours apart (near `i`)?
    fn removable(&mut self, i: u32, neighbours: &[Vec<u32>], removed: &[bool]) -> bool {
        let around: Vec<u32> = neighbours[i as usize]
            .iter()
            .copied()
            .filter(|&j| !removed[j as usize])
            .collect();
        if around.len() <= 1 {
            return true;
        }
        self.call += 1;
        let call = self.call;
        self.seen[i as usize] = call;
        self.seen[around[0] as usize] = call;
        self.frontier.clear();
        self.frontier.push((around[0], 0));
        let mut at = 0;
        while at < self.frontier.len() {
            let (u, hops) = self.frontier[at];
            at += 1;
            if hops == Skeleton::LOCAL_HOPS {
                continue;
            }
            for &v in &neighbours[u as usize] {
                if !removed[v as usize] && self.seen[v as usize] != call {
                    self.seen[v as usize] = call;
                    self.frontier.push((v, hops + 1));
                }
            }
        }
        around.iter().all(|&j| self.seen[j as usize] == call)
    }
}
