//! Curve skeletons of medial axes, and of any surface with a boundary: burn the
//! surface from its boundary ([`Grassfire`]), thin it in the order it burns without
//! changing its topology, and keep the curves that stood long enough ([`Skeleton`]).
//!
//! The skeleton is homotopy equivalent to the surface with its line elements (one
//! component per component, as many independent cycles as the surface's b₁, see
//! [`TriMesh::betti_numbers`]) at every pruning threshold: thinning removes only
//! simplices that a collapse may remove, and pruning removes only branches from their
//! tips. How it works is in the `thinning` module's notes.
//!
//! A medial axis can have holes that are no tunnel of the solid (its balls fill them),
//! and a closed surface mesh gets its medial axis from [`medial`] first, which has a
//! few small holes the solid does not: [`medial_axis_skeleton_with_cycles`] opens the
//! loops round them.
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
//! // Keep the branches that stood on curves for at least 1 (the strip is 4 × 1): one
//! // trunk from end to end, along the middle line away from the ends.
//! let core = skeleton.pruned(1.0);
//! assert_eq!((core.component_count(), core.cycle_count(), core.tip_count()), (1, 0, 2));
//! let middle = core.points.iter().filter(|p| (0.75..3.25).contains(&p.position[0]));
//! assert!(middle.clone().count() >= 10);
//! assert!(middle.clone().all(|p| (p.position[1] - 0.5).abs() < 0.26));
//! // At any threshold, one point is left of a disc.
//! assert_eq!(skeleton.pruned(f64::INFINITY).points.len(), 1);
//! # Ok::<(), geotracks::Error>(())
//! ```

mod balls;
mod cycles;
mod geometry;
mod grassfire;
pub mod medial;
mod pipeline;
mod placement;
mod protrusion;
mod simplify;
mod straighten;
mod strands;
mod thinning;
mod tips;
mod trunk;

pub use geometry::turning_per_length;
pub use grassfire::Grassfire;
pub use pipeline::{medial_axis_skeleton, medial_axis_skeleton_with_cycles};
pub use placement::Placement;

use crate::mesh::{unique_edges, DisjointSets, TriMesh, NONE};
use crate::options::Options;
use crate::surface::SurfacePoint;
use crate::{Error, Metric};
use grassfire::{burn_from_border, curves_reached_at_once};

/// The pruning threshold the command line uses by default, in % of the bounding-box
/// diagonal of what is skeletonized: branches whose erosion thickness is less go. It is
/// chosen on the shared medial axes against mean-curvature-flow skeletons (the guide's
/// Skeletons page).
pub const DEFAULT_PRUNE_PERCENT: f64 = 5.0;

/// The least tubularity the command line keeps by default ([`Skeleton::pruned_tubular`]):
/// a branch must stand, in erosion thickness, at least as long as the shape is thick
/// where it joins. Chosen, with [`DEFAULT_PRUNE_PERCENT`], on the shared medial axes
/// against mean-curvature-flow skeletons (the guide's Skeletons page): bumps there stand
/// at 0.46–0.93, limbs at 1.12 and more.
pub const DEFAULT_MIN_TUBULARITY: f64 = 1.0;

/// The least protrusion the command line keeps by default
/// ([`Skeleton::pruned_protruding`]): a branch must reach out of the rest of the
/// skeleton's balls by at least half the radius where it joins. Chosen, with the other
/// two defaults, on the shared medial axes and meshes against mean-curvature-flow
/// skeletons (the guide's Skeletons page): spurs into a body stand at 0.1–0.27 there,
/// bumps (a cow's hip bones, its udder) at 0.25–0.73, and limbs at 0.82 and more.
pub const DEFAULT_MIN_PROTRUSION: f64 = 0.5;

/// How [`medial_axis_skeleton`] prunes a skeleton: three thresholds, each removing whole
/// branches from their tips and never opening a loop (0 turns one off), and whether the
/// placed tips are cut back to the last ball that holds them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pruning {
    /// The least erosion thickness a branch keeps, a length ([`Skeleton::pruned`]), and
    /// the least length of a placed branch from a tip ([`Skeleton::without_short_tips`]).
    pub erosion_thickness: f64,
    /// The least tubularity ([`Skeleton::pruned_tubular`]).
    pub tubularity: f64,
    /// The least protrusion ([`Skeleton::pruned_protruding`]).
    pub protrusion: f64,
    /// Whether each placed branch from a tip is cut back to the innermost ball that
    /// holds its end, by no more than the end's radius ([`Skeleton::tips_trimmed`]),
    /// near where a mean-curvature-flow skeleton's tips lie, rather than running out to
    /// where the axis meets the surface. On in the defaults.
    pub trim_tips: bool,
}

impl Pruning {
    /// Nothing pruned: every branch the thinning leaves.
    pub const NONE: Pruning = Pruning {
        erosion_thickness: 0.0,
        tubularity: 0.0,
        protrusion: 0.0,
        trim_tips: false,
    };

    /// The command line's defaults ([`DEFAULT_PRUNE_PERCENT`] of `diagonal`,
    /// [`DEFAULT_MIN_TUBULARITY`], [`DEFAULT_MIN_PROTRUSION`], tips trimmed) for an axis
    /// whose bounding box has that diagonal.
    pub fn default_for(diagonal: f64) -> Pruning {
        Pruning {
            erosion_thickness: DEFAULT_PRUNE_PERCENT / 100.0 * diagonal,
            tubularity: DEFAULT_MIN_TUBULARITY,
            protrusion: DEFAULT_MIN_PROTRUSION,
            trim_tips: true,
        }
    }
}

/// A pruning threshold as people write it: a length in the axis's units (`0.05`,
/// `inf`), or a percentage of its bounding-box diagonal (`7%`), so that the same value
/// means the same on a small and a large shape.
///
/// ```
/// use geotracks::skeleton::Prune;
/// let p: Prune = "7%".parse()?;
/// assert_eq!(p, Prune::Percent(7.0));
/// assert!((p.threshold(200.0) - 14.0).abs() < 1e-12);
/// assert_eq!("0.5".parse::<Prune>()?.threshold(200.0), 0.5);
/// assert!("-1".parse::<Prune>().is_err() && "much".parse::<Prune>().is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Prune {
    /// A length (≥ 0; `inf` keeps only what never burns).
    Length(f64),
    /// A percentage of the bounding-box diagonal (≥ 0).
    Percent(f64),
}

impl Prune {
    /// The threshold for a shape whose bounding-box diagonal is `diagonal`.
    pub fn threshold(self, diagonal: f64) -> f64 {
        match self {
            Prune::Length(length) => length,
            Prune::Percent(percent) => percent / 100.0 * diagonal,
        }
    }
}

impl std::str::FromStr for Prune {
    type Err = String;

    /// `T` (a length) or `P%`; refuses negative values, NaN and anything else.
    fn from_str(text: &str) -> Result<Prune, String> {
        let text = text.trim();
        let (number, make): (&str, fn(f64) -> Prune) = match text.strip_suffix('%') {
            Some(p) => (p.trim(), Prune::Percent),
            None => (text, Prune::Length),
        };
        match number.parse::<f64>() {
            Ok(v) if v >= 0.0 => Ok(make(v)),
            _ => Err(format!(
                "'{text}': expected a length >= 0 or a percentage such as 2%"
            )),
        }
    }
}

/// A point of a [`Skeleton`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SkeletonPoint {
    /// World position.
    pub position: [f64; 3],
    /// Where it lies on the surface: a vertex as thinning leaves it, a point in a face
    /// once [`Skeleton::smoothed`] or [`Skeleton::placed`] on the axis; for a skeleton
    /// [`Placement::Centred`], the point of the axis it was placed from.
    pub on: SurfacePoint,
    /// The erosion thickness of the point's branch (in the metric's length): how long
    /// the branch stood on curves only before the fire burnt it from its tip, the same
    /// for every point of the branch; `inf` for points that never burn (the loops that
    /// carry the surface's cycles, and one point per component that burns away
    /// entirely). [`Skeleton::pruned`] keeps the points at or above a threshold.
    pub significance: f64,
    /// How long the point's branch is for its thickness: its erosion thickness over
    /// the radius where the branch joins a more significant one (the medial radius on
    /// a medial axis, the grassfire's distance on another surface), and no more than
    /// that one's tubularity. A bump whose branch is short next to the body it stands
    /// on is below 1; a limb many times longer than it is thick, well above. Scale-free,
    /// never larger towards a tip than where the branch ends, `inf` where the branch
    /// never burns or joins where the radius is 0 (a graph of curves without radii), and
    /// on a tree's trunk: the two branches that stood longest where it burnt last, so
    /// that a stubby solid keeps its axis.
    /// [`Skeleton::pruned_tubular`] keeps the points at or above a threshold.
    pub tubularity: f64,
    /// The medial ball's radius there, once [`Skeleton::with_radii`] gave them.
    pub radius: Option<f64>,
}

/// A curve skeleton: a graph of points on a surface (and on its line elements), with
/// straight edges.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Skeleton {
    /// The graph's points.
    pub points: Vec<SkeletonPoint>,
    /// Its edges, as pairs of indices into `points`.
    pub edges: Vec<[u32; 2]>,
    /// Faces that thinning had to remove without a free edge: one per closed sheet (a
    /// 2-cycle, which a graph cannot carry), and one per extra cycle below.
    pub punctured_faces: usize,
    /// Cycles the skeleton has that the surface does not: parts that are contractible
    /// but cannot be collapsed (Bing's house); 0 on every medial axis we know of.
    pub added_cycles: usize,
    /// Cycles of the thinned graph that [`Skeleton::with_cycles_cut`] opened: holes of
    /// the axis that its balls fill (no tunnel of the solid), and cycles beyond the
    /// solid's own.
    pub opened_cycles: usize,
}

impl Skeleton {
    /// The unpruned skeleton of `mesh` (its faces and line elements) thinned in the
    /// order of its grassfire from the boundary under `metric`
    /// ([`Skeleton::from_grassfire`]); a surface without a boundary (a closed sheet) is
    /// punctured and burnt from there.
    ///
    /// # Errors
    /// As [`Grassfire::burn`], except that no boundary is not an error.
    pub fn extract<M: Metric>(
        mesh: &TriMesh,
        metric: &M,
        options: &Options,
    ) -> Result<Skeleton, Error> {
        Ok(burn_from_border(mesh, metric, options, None)?.0)
    }

    /// The unpruned skeleton of a grassfire's surface, each vertex reached when the
    /// grassfire reaches it: [`Skeleton::from_reach`] with its vertex distances, under
    /// its metric; a vertex of line elements only, at once (a curve is all border; see
    /// [`Burn::Boundary`]).
    pub fn from_grassfire<M: Metric>(fire: &Grassfire<M>) -> Skeleton {
        Skeleton::of_fire(fire, None)
    }

    /// [`Skeleton::from_grassfire`], with the tubularity measured against `radius` (one
    /// per vertex; `None`: the grassfire's distances).
    fn of_fire<M: Metric>(fire: &Grassfire<M>, radius: Option<&[f64]>) -> Skeleton {
        let solver = fire.solver();
        let distance = fire.field().vertex_distances();
        let reach = curves_reached_at_once(solver.mesh(), distance);
        Skeleton::thinned(
            solver.mesh(),
            solver.metric(),
            &reach,
            radius.unwrap_or(distance),
        )
    }

    /// The unpruned skeleton of `mesh`'s faces and line elements, thinned by the
    /// extended grassfire: each vertex may burn from its `reach` time on (a medial axis's
    /// radii, a grassfire's distances, or any function whose ridges the skeleton should
    /// follow; `inf` where no fire comes), the fire then moving at `metric`'s speed
    /// (along wires, at [`Metric::wire_cost`]). Every vertex of a face or line
    /// element is a point; the edges are every curve thinning left on the way, and each
    /// point's significance is its erosion thickness.
    ///
    /// # Panics
    /// If `reach` does not have one value per vertex.
    pub fn from_reach<M: Metric>(mesh: &TriMesh, metric: &M, reach: &[f64]) -> Skeleton {
        Skeleton::thinned(mesh, metric, reach, reach)
    }

    /// [`Skeleton::from_reach`], with the tubularity measured against `radius` (one per
    /// vertex).
    fn thinned<M: Metric>(mesh: &TriMesh, metric: &M, reach: &[f64], radius: &[f64]) -> Skeleton {
        assert_eq!(
            reach.len(),
            mesh.vertex_count(),
            "one reach time per vertex"
        );
        let wires: Vec<[u32; 2]> = mesh.wires().collect();
        let lengths = edge_costs(mesh, metric, &wires);
        // Crossing a face from an edge: from the edge's middle to the opposite corner.
        let cross = |f: u32, e: u32| {
            let [a, b] = mesh.edge_vertices(e);
            let corner = mesh
                .face_vertices(f)
                .into_iter()
                .find(|&v| v != a && v != b);
            let middle = SurfacePoint::Edge { edge: e, t: 0.5 }.in_face(mesh, f);
            match (
                corner.and_then(|c| SurfacePoint::Vertex(c).in_face(mesh, f)),
                middle,
            ) {
                (Some(c), Some(m)) => metric.cost(f, &m, &c),
                _ => 0.0,
            }
        };
        let thinning = thinning::thin(
            Some(mesh),
            mesh.vertex_count(),
            &wires,
            reach,
            |e| lengths[e as usize],
            cross,
        );
        let positions: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
        Skeleton::from_thinning(&positions, thinning, radius)
    }

    /// The unpruned skeleton of a graph (a medial axis of curves only), burnt from its
    /// tips along the edges at their Euclidean length, each vertex from its `reach` on
    /// (its medial radius; `None`: 0, so a point's significance is the length of the
    /// branch burnt into it).
    ///
    /// # Panics
    /// If `reach` is given without one value per position.
    pub fn from_curves(
        positions: &[[f64; 3]],
        free_edges: &[[u32; 2]],
        reach: Option<&[f64]>,
    ) -> Skeleton {
        let edges = unique_edges(free_edges);
        let length = |e: u32| {
            let [a, b] = edges[e as usize];
            glam::DVec3::from(positions[a as usize]).distance(positions[b as usize].into())
        };
        let zeros = vec![0.0; positions.len()];
        let reach = reach.unwrap_or(&zeros);
        assert_eq!(reach.len(), positions.len(), "one reach time per vertex");
        let thinning = thinning::thin(None, positions.len(), &edges, reach, length, |_, _| 0.0);
        Skeleton::from_thinning(positions, thinning, reach)
    }

    fn from_thinning(
        positions: &[[f64; 3]],
        thinning: thinning::Thinning,
        radius: &[f64],
    ) -> Skeleton {
        let tubularity = tubularity(&thinning, radius);
        let mut point_of = vec![NONE; positions.len()];
        let mut points = Vec::new();
        for (v, &significance) in thinning.significance.iter().enumerate() {
            if significance.is_nan() {
                continue;
            }
            point_of[v] = points.len() as u32;
            points.push(SkeletonPoint {
                position: positions[v],
                on: SurfacePoint::Vertex(v as u32),
                significance,
                tubularity: tubularity[v],
                radius: None,
            });
        }
        let edges = thinning
            .curves
            .iter()
            .map(|&[a, b]| [point_of[a as usize], point_of[b as usize]])
            .collect();
        Skeleton {
            points,
            edges,
            punctured_faces: thinning.punctured,
            added_cycles: thinning.opened,
            opened_cycles: 0,
        }
    }

    /// The skeleton with the points of significance below `threshold` removed (and their
    /// edges). A branch's significance is never above the one it ends on, so whole
    /// branches go, least significant first, as the threshold rises; loops never open,
    /// and each component keeps at least one point: at `f64::INFINITY`, what never burns
    /// (one point of a contractible surface). `threshold` ≤ 0 removes nothing.
    pub fn pruned(&self, threshold: f64) -> Skeleton {
        // A NaN threshold removes nothing, as 0 does.
        let threshold = if threshold.is_nan() { 0.0 } else { threshold };
        self.keep(|i| self.points[i].significance >= threshold)
    }

    /// The skeleton with the points of tubularity below `min` removed (and their
    /// edges; see [`SkeletonPoint::tubularity`]): as for [`Skeleton::pruned`], whole
    /// branches go from their tips, loops never open, and each component keeps a point.
    /// Both prunings together keep a branch that is long both in length and for its
    /// thickness. `min` ≤ 0 (or NaN) removes nothing.
    pub fn pruned_tubular(&self, min: f64) -> Skeleton {
        self.pruned_tubular_but(min, &[])
    }

    /// [`Skeleton::pruned_tubular`], keeping the points `kept` marks (one flag per
    /// point, or none), unless that would leave the graph in more pieces.
    fn pruned_tubular_but(&self, min: f64, kept: &[bool]) -> Skeleton {
        let min = if min.is_nan() { 0.0 } else { min };
        let tubular = |i: usize| self.points[i].tubularity >= min;
        if kept.is_empty() {
            return self.keep(tubular);
        }
        let with_kept = self.keep(|i| tubular(i) || kept[i]);
        if with_kept.component_count() != self.component_count() {
            return self.keep(tubular);
        }
        with_kept
    }

    /// Independent cycles of the graph: edges − points + components.
    pub fn cycle_count(&self) -> usize {
        unique_edges(&self.edges).len() + self.component_count() - self.points.len()
    }

    /// Points with exactly one edge (branch tips).
    pub fn tip_count(&self) -> usize {
        self.degrees().iter().filter(|&&d| d == 1).count()
    }

    /// Per point, how many edges it has: 1 at a tip, 2 along a curve, 3 or more at a
    /// junction.
    pub fn degrees(&self) -> Vec<u32> {
        let mut degree = vec![0; self.points.len()];
        for &[a, b] in &self.edges {
            degree[a as usize] += 1;
            degree[b as usize] += 1;
        }
        degree
    }

    /// The graph cut into polylines (point indices) between points whose degree is not
    /// 2; a cycle of degree-2 points is one closed polyline (first point repeated last).
    /// An isolated point is a polyline of one point.
    pub fn polylines(&self) -> Vec<Vec<u32>> {
        let degree = self.degrees();
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
                if degree[at as usize] != 2 || at == start {
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
            match degree[i as usize] {
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
            ..*self
        }
    }
}

/// Per vertex of a thinning, its branch's tubularity (see
/// [`SkeletonPoint::tubularity`]) against `radius` (one per vertex): its erosion
/// thickness over the radius where the branch ends, and no more than the branch it ends
/// on (resolved from what never burns outwards, so that it never rises towards a tip);
/// NaN for vertices the thinning did not use.
fn tubularity(thinning: &thinning::Thinning, radius: &[f64]) -> Vec<f64> {
    let (significance, ends) = (&thinning.significance, &thinning.ends);
    let trunk = trunk::of_thinning(thinning);
    let mut out = vec![f64::NAN; significance.len()];
    let mut chain = Vec::new();
    for v in 0..significance.len() {
        if significance[v].is_nan() || !out[v].is_nan() {
            continue;
        }
        // Up to a vertex already resolved, or to a branch that never burns (a branch
        // ends on a vertex burnt later, so the walk ends).
        let mut u = v;
        loop {
            chain.push(u);
            let end = ends[u];
            if end == NONE || !out[end as usize].is_nan() {
                break;
            }
            u = end as usize;
        }
        while let Some(u) = chain.pop() {
            let end = ends[u];
            out[u] = if end == NONE {
                f64::INFINITY
            } else {
                let base = radius[end as usize];
                // A radius of 0 (curves without radii) or none (no fire came) says
                // nothing of thickness.
                let own = if base > 0.0 && base.is_finite() && !trunk[u] {
                    significance[u] / base
                } else {
                    f64::INFINITY
                };
                own.min(out[end as usize])
            };
        }
    }
    out
}

/// Per edge of the complex (the mesh's edges, then `wires`), what a tip pays to burn
/// along it: `metric`'s cost between its ends in the cheapest face around it, or
/// [`Metric::wire_cost`] for a wire.
fn edge_costs<M: Metric>(mesh: &TriMesh, metric: &M, wires: &[[u32; 2]]) -> Vec<f64> {
    let mut costs: Vec<f64> = (0..mesh.edge_count() as u32)
        .map(|e| {
            let [a, b] = mesh.edge_vertices(e).map(SurfacePoint::Vertex);
            mesh.edge_faces(e)
                .iter()
                .filter_map(|&g| Some(metric.cost(g, &a.in_face(mesh, g)?, &b.in_face(mesh, g)?)))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    costs.extend(
        wires
            .iter()
            .map(|&[a, b]| metric.wire_cost(a, b, mesh.position(a).distance(mesh.position(b)))),
    );
    costs
}

/// What decides when each point of a medial axis may burn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Burn {
    /// Its grassfire distance from the axis's own border, on the sheets (geodesic, by
    /// the engine of the [`Options`]): the curves follow the middle of each sheet. A
    /// vertex of the axis's curves only may burn at once (a curve is all border): a
    /// curve burns from its free ends along its length, and its significance is the
    /// length burnt. The default: the closest to mean-curvature-flow skeletons on the
    /// shared axes.
    #[default]
    Boundary,
    /// Its medial radius: the time eroding the shape from its surface takes to reach
    /// the ball's centre (as in erosion thickness, Yan et al. 2016). Sheets are eaten
    /// from where the shape is thin, and the curves left follow the ridges of the
    /// radius, through the largest balls. About four times faster (no propagation);
    /// farther from mean-curvature-flow skeletons at their worst point on the shared
    /// axes (the guide's Skeletons page).
    Radius,
}
