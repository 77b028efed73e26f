//! Where a medial-axis skeleton's points go once thinned: each branch's folds taken
//! out, resampled evenly along each polyline, smoothed at the scale of the shape's
//! thickness (through junctions), then kept on the axis or moved to the centre of the
//! shape's cross-section, and last thinned to the points the curve needs.

use super::balls::Balls;
use super::geometry::{least_edges, lengths_along, nearby_faces, share_a_face, vertex_of, Rebuild};
use super::thinning::Ordered;
use super::{Skeleton, SkeletonPoint};
use crate::mesh::io::MedialAxis;
use crate::mesh::{DisjointSets, TriMesh};
use crate::surface::SurfacePoint;
use glam::DVec3;
use rstar::primitives::GeomWithData;
use rstar::RTree;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Where a medial-axis skeleton's points lie.
///
/// Centred is the default, for an axis given as such and one computed from a surface
/// mesh alike: on the shared axes and meshes it comes closer to the mean-curvature-flow
/// skeletons on every target but Spot's length (`eval --skeletons [--from-meshes]
/// [--on-axis]`, on the guide's Accuracy page). A computed axis is the Voronoi diagram
/// of samples of the surface: round a limb only a few samples across it zig-zags by up
/// to half the limb's radius, and a curve on it follows; the cross-section is the cut
/// of the union of the balls, which that noise hardly moves. On a given axis, a wide
/// sheet's curve runs along the ridge where the fires met, which can lie anywhere
/// across the solid's section (on the cow's body, up its back).
///
/// ```
/// use geotracks::skeleton::Placement;
/// assert_eq!(Placement::default(), Placement::Centred);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Placement {
    /// On the medial axis: every point is a point of the axis's sheets or curves, the
    /// curve smoothed at the shape's thickness and put back on the axis.
    OnAxis,
    /// At the centre of the shape's cross-section (the default): each point moves to the
    /// centroid of the cut of the medial balls by the plane across the curve there (the
    /// piece of the cut around the point), as a mean-curvature-flow skeleton lies.
    /// Points leave the axis (a wide sheet's curve moves to the middle of the solid's
    /// section); the radius is then that of the largest ball centred there inside the
    /// shape, and [`SkeletonPoint::on`] the point of the axis it was placed from. An
    /// axis of curves only has no cross-sections to centre in: its points stay on its
    /// curves.
    #[default]
    Centred,
}

impl Skeleton {
    /// Even steps along the polylines, in fractions of the axis's diagonal.
    pub const RESAMPLING: f64 = 0.005;
    /// The Gaussian's width along the curve, in medial radii at the point.
    pub const SMOOTHING_RADII: f64 = 1.0;

    /// The skeleton of a medial axis with its points placed (thinning leaves them on the
    /// axis's vertices, and the ridge where its fires met wanders across a wide sheet):
    /// 1. branches that leave a junction side by side joined into one strand
    ///    ([`Skeleton::with_strands_joined`]): the junction moves to where they part;
    /// 2. each branch's folds taken out: where the branch runs away and back, by at
    ///    least [`Skeleton::FOLD`] times the distance across, it steps across instead,
    ///    within the medial ball it steps from, on the axis's sheets;
    /// 3. resampled every [`Skeleton::RESAMPLING`] of the diagonal
    ///    ([`Skeleton::resampled`]);
    /// 4. smoothed through junctions: each point moves to the Gaussian-weighted mean of
    ///    the points near it along the graph, σ = [`Skeleton::SMOOTHING_RADII`] medial
    ///    radii there (a curve cannot say more about a shape than its thickness);
    /// 5. for [`Placement::OnAxis`], put back on the nearest point of the axis and
    ///    smoothed on it ([`Skeleton::smoothed`], [`Skeleton::SMOOTHING`] rounds), with
    ///    the radius interpolated there; for [`Placement::Centred`], moved to the centre
    ///    of the shape's cross-section and smoothed again, with the radius of the largest
    ///    ball centred there inside the shape;
    /// 6. thinned to the points the curve needs ([`Skeleton::simplified`]): a point
    ///    within [`Skeleton::SIMPLIFYING_RADII`] medial radii, and one resampling step,
    ///    of the polyline without it goes, and with it the zig-zag that the axis's
    ///    roughness leaves between points so close together.
    ///
    /// An axis of curves only keeps its points (they lie on its curves) and gets radii.
    pub fn placed(self, axis: &MedialAxis, placement: Placement) -> Skeleton {
        let Some(mesh) = &axis.surface else {
            return self.with_radii(None, &axis.radii);
        };
        let lookup = AxisLookup::new(mesh, axis);
        let spacing = Skeleton::RESAMPLING * axis.diagonal();
        let skeleton = self
            .with_radii(Some(mesh), &axis.radii)
            .with_strands_joined()
            .straightened(mesh, &lookup, spacing)
            .resampled(mesh, spacing)
            .with_radii(Some(mesh), &axis.radii);
        let at: Vec<DVec3> = skeleton.points.iter().map(|p| p.position.into()).collect();
        // On the axis, points on its curves and at their ends stay; centred, they move.
        let movable: Vec<bool> = match placement {
            Placement::OnAxis => skeleton
                .held_by_curves(mesh)
                .iter()
                .map(|held| !held)
                .collect(),
            Placement::Centred => vec![true; at.len()],
        };
        let smooth = skeleton.smoothed_by_radius(&at, &movable);
        let placed = match placement {
            Placement::OnAxis => skeleton
                .moved_onto(mesh, &lookup, &smooth)
                .smoothed(mesh, Skeleton::SMOOTHING)
                .with_radii(Some(mesh), &axis.radii),
            Placement::Centred => {
                let centred = skeleton.centred(&lookup, &smooth);
                let smooth = skeleton.smoothed_by_radius(&centred, &movable);
                let points = skeleton
                    .points
                    .iter()
                    .zip(&smooth)
                    .map(|(p, &at)| {
                        let reach = 3.0 * p.radius.unwrap_or(0.0);
                        // A point of a curve away from every sheet (its balls are not
                        // the sheets') keeps the radius the axis gives it there.
                        let radius = match inscribed_radius(axis, &lookup, at, reach) {
                            r if r > 0.0 => Some(r),
                            _ => p.radius,
                        };
                        SkeletonPoint {
                            position: at.to_array(),
                            radius,
                            ..*p
                        }
                    })
                    .collect();
                skeleton.with_points(points)
            }
        };
        placed.simplified(Skeleton::SIMPLIFYING_RADII, spacing)
    }

    /// The skeleton with every polyline between tips and junctions resampled at even
    /// steps of about `spacing` along its length (tips, junctions and the polylines
    /// that run along line elements keep their points). Thinning leaves points on the
    /// axis's vertices, as unevenly spaced as its sampling, and a curve's direction
    /// between two points a hair apart is noise: even steps make the smoothing that
    /// follows act the same everywhere. Each new point takes the lower significance
    /// and tubularity of the two points it lies between, and is put on the nearest
    /// point of the faces near the nearer of them.
    pub fn resampled(&self, mesh: &TriMesh, spacing: f64) -> Skeleton {
        if spacing.is_nan() || spacing <= 0.0 {
            return self.clone();
        }
        let mut rebuilt = Rebuild::new(self);
        for line in self.polylines() {
            rebuilt.start(line[0]);
            if line.len() < 2 {
                continue;
            }
            let at = self.line_positions(&line);
            let along = lengths_along(&at);
            let length = along[along.len() - 1];
            let steps = ((length / spacing).round() as usize).max(least_edges(line.len()));
            let on = |k: usize| self.points[line[k] as usize].on;
            if (1..line.len()).any(|k| !share_a_face(mesh, on(k - 1), on(k))) {
                // Along line elements: the points as they are.
                rebuilt.then_olds(&line[1..]);
                continue;
            }
            let faces: Vec<Vec<u32>> = line
                .iter()
                .map(|&i| nearby_faces(mesh, self.points[i as usize].on))
                .collect();
            let mut segment = 0;
            for step in 1..steps {
                let s = length * step as f64 / steps as f64;
                while segment + 2 < along.len() && along[segment + 1] < s {
                    segment += 1;
                }
                let span = along[segment + 1] - along[segment];
                let t = if span > 0.0 {
                    (s - along[segment]) / span
                } else {
                    0.0
                };
                let near = segment + usize::from(t >= 0.5);
                let (a, b) = (
                    &self.points[line[segment] as usize],
                    &self.points[line[segment + 1] as usize],
                );
                let (on, position) = SurfacePoint::nearest_among(
                    mesh,
                    faces[near].iter().copied(),
                    at[segment].lerp(at[segment + 1], t),
                )
                .unwrap_or((self.points[line[near] as usize].on, at[near]));
                rebuilt.then_new(SkeletonPoint::between(a, b, position, on, None));
            }
            rebuilt.then_old(line[line.len() - 1]);
        }
        rebuilt.finish()
    }

    /// Where each point at `at` goes when the skeleton is smoothed at the scale of the
    /// shape's thickness: the Gaussian-weighted mean of the points within 2.5 σ of it
    /// along the graph (through junctions, so a junction moves into the middle of its
    /// branches and a branch bends smoothly into the next), σ =
    /// [`Skeleton::SMOOTHING_RADII`] times the point's medial radius. A curve cannot say
    /// more about the shape than its thickness, and the ridge thinning leaves wanders
    /// across a wide sheet by about that much. Near a tip σ shrinks so that the window
    /// ends at the tip (an average that reached past it would pull the branch's end
    /// inwards); tips, points without a radius and points not `movable` stay.
    fn smoothed_by_radius(&self, at: &[DVec3], movable: &[bool]) -> Vec<DVec3> {
        let neighbours = self.weighted_adjacency(at);
        let degree = self.degrees();
        let tips: Vec<u32> = (0..self.points.len() as u32)
            .filter(|&i| degree[i as usize] == 1)
            .collect();
        let to_tip = graph_distances(&neighbours, &tips, f64::INFINITY);
        let mut search = Search::new(self.points.len());
        (0..self.points.len())
            .map(|i| {
                let r = self.points[i].radius.unwrap_or(0.0);
                let sigma = (Skeleton::SMOOTHING_RADII * r).min(to_tip[i] / 2.5);
                if degree[i] < 2 || !movable[i] || sigma.is_nan() || sigma <= 0.0 {
                    return at[i];
                }
                let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
                search.run(&neighbours, i as u32, 2.5 * sigma, |j, d| {
                    let w = (-0.5 * (d / sigma).powi(2)).exp();
                    sum += w * at[j as usize];
                    weight += w;
                });
                sum / weight
            })
            .collect()
    }

    /// Per point at `at`, the centroid of the shape's cross-section across the curve
    /// there (see [`Placement::Centred`]); tips, junctions, points without a radius and
    /// points whose cross-section is wider than eight radii stay.
    fn centred(&self, lookup: &AxisLookup, at: &[DVec3]) -> Vec<DVec3> {
        let neighbours = self.adjacency();
        let degree = self.degrees();
        let tips: Vec<u32> = (0..self.points.len() as u32)
            .filter(|&i| degree[i as usize] == 1)
            .collect();
        let to_tip = graph_distances(&self.weighted_adjacency(at), &tips, f64::INFINITY);
        let mut section = Section::new();
        // The tangent spans two steps along the curve either way (one at a tip or a
        // junction): the point two steps from `from` through `first`.
        let two_steps = |from: usize, first: u32| {
            let second = match *neighbours[first as usize].as_slice() {
                [a, b] if a as usize == from => b,
                [a, _] => a,
                _ => first,
            };
            at[second as usize]
        };
        (0..self.points.len())
            .map(|i| {
                let r = self.points[i].radius.unwrap_or(0.0);
                let around = &neighbours[i];
                if around.len() != 2 || r.is_nan() || r <= 0.0 {
                    return at[i];
                }
                let tangent =
                    (two_steps(i, around[1]) - two_steps(i, around[0])).normalize_or_zero();
                if tangent == DVec3::ZERO {
                    return at[i];
                }
                let centre = [2.0, 4.0, 8.0]
                    .iter()
                    .find_map(|&half| section.centroid(lookup, at[i], tangent, half * r))
                    .unwrap_or(at[i]);
                // A section that reaches a neighbouring part pulls its centroid out of
                // the branch: the move is kept within the point's own ball. It fades in
                // over two radii from the tips, which stay. Near a junction the plane
                // across the curve cuts the other branches too, and the pull towards
                // them is kept: it brings the branches together where the solid's
                // parts merge, as a mean-curvature-flow skeleton's junctions lie, and
                // lets a thick trunk between junctions less than four of its radii
                // apart reach the centre of its section (it stayed on the sheet).
                let fade = (to_tip[i] / (2.0 * r)).min(1.0);
                let moved = centre - at[i];
                if moved.length() > r {
                    at[i]
                } else {
                    at[i] + fade * moved
                }
            })
            .collect()
    }

    /// The skeleton with each point moved to `to` and then onto the nearest point of
    /// its own part of the axis near there; points on line elements stay (smoothing left
    /// them where they were).
    fn moved_onto(&self, mesh: &TriMesh, lookup: &AxisLookup, to: &[DVec3]) -> Skeleton {
        let points = self
            .points
            .iter()
            .zip(to)
            .map(|(p, &to)| match lookup.onto_sheets(mesh, p.on, to) {
                Some((on, position)) => SkeletonPoint {
                    position: position.to_array(),
                    on,
                    ..*p
                },
                None => *p,
            })
            .collect();
        self.with_points(points)
    }

    /// Per point, its neighbours and the edge's length at `at`.
    fn weighted_adjacency(&self, at: &[DVec3]) -> Vec<Vec<(u32, f64)>> {
        let mut neighbours = vec![Vec::new(); self.points.len()];
        for &[a, b] in &self.edges {
            let length = at[a as usize].distance(at[b as usize]);
            neighbours[a as usize].push((b, length));
            neighbours[b as usize].push((a, length));
        }
        neighbours
    }
}

/// The axis's vertices in an R-tree (`rstar`: a kept crate, bulk-loaded, for nearest
/// queries): where a point that smoothing moved off the axis finds the axis again; and
/// the medial balls of its sheets, thinned, for cross-sections.
pub(super) struct AxisLookup {
    tree: RTree<GeomWithData<[f64; 3], u32>>,
    balls: Balls,
    /// Per vertex, the connected part of the axis (sheets and curves) it belongs to: a
    /// point is put back on its own part, never on another one that passes near.
    part: Vec<u32>,
}

impl AxisLookup {
    pub(super) fn new(mesh: &TriMesh, axis: &MedialAxis) -> AxisLookup {
        let mut sets = DisjointSets::new(mesh.vertex_count());
        for t in mesh.triangles() {
            sets.join(t[0], t[1]);
            sets.join(t[1], t[2]);
        }
        for &[a, b] in &axis.free_edges {
            sets.join(a, b);
        }
        let vertices: Vec<_> = (0..mesh.vertex_count() as u32)
            .filter(|&v| !mesh.vertex_faces(v).is_empty())
            .map(|v| GeomWithData::new(mesh.position(v).to_array(), v))
            .collect();
        let balls = Balls::thinned(
            vertices
                .iter()
                .map(|v| (*v.geom(), axis.radii[v.data as usize])),
        );
        AxisLookup {
            tree: RTree::bulk_load(vertices),
            balls,
            part: sets.labels().0,
        }
    }

    /// The nearest point to `to` of the sheets of the part of the axis that `from` lies
    /// on, and where it is; `None` if that part has no sheets near `from`.
    pub(super) fn onto_sheets(
        &self,
        mesh: &TriMesh,
        from: SurfacePoint,
        to: DVec3,
    ) -> Option<(SurfacePoint, DVec3)> {
        let own = vertex_of(mesh, from);
        if mesh.vertex_faces(own).is_empty() {
            return None;
        }
        let near = self.nearest_vertex(to, own)?;
        SurfacePoint::nearest_among(mesh, nearby_faces(mesh, SurfacePoint::Vertex(near)), to)
    }

    /// The vertex with faces nearest `p` on the same part of the axis as `of`.
    fn nearest_vertex(&self, p: DVec3, of: u32) -> Option<u32> {
        let part = self.part[of as usize];
        self.tree
            .nearest_neighbor_iter(&p.to_array())
            .find(|v| self.part[v.data as usize] == part)
            .map(|v| v.data)
    }
}

/// Graph distances from `sources` (0 there), up to `limit` (`inf` beyond).
fn graph_distances(neighbours: &[Vec<(u32, f64)>], sources: &[u32], limit: f64) -> Vec<f64> {
    let mut search = Search::new(neighbours.len());
    let mut distance = vec![f64::INFINITY; neighbours.len()];
    search.run_from(neighbours, sources, limit, |j, d| distance[j as usize] = d);
    distance
}

/// A bounded Dijkstra search over a graph given as weighted adjacency lists (a
/// skeleton's, or a branch's steps), its buffers kept between runs.
pub(super) struct Search {
    distance: Vec<f64>,
    /// Per point reached, the one it was reached from (`u32::MAX` at a source).
    previous: Vec<u32>,
    touched: Vec<u32>,
    heap: BinaryHeap<Reverse<(Ordered, u32)>>,
}

impl Search {
    pub(super) fn new(points: usize) -> Search {
        Search {
            distance: vec![f64::INFINITY; points],
            previous: vec![u32::MAX; points],
            touched: Vec::new(),
            heap: BinaryHeap::new(),
        }
    }

    /// The shortest path the last run found from its sources to `to` (reached), as
    /// points from a source to `to`.
    pub(super) fn path_to(&self, to: u32) -> Vec<u32> {
        let mut path = vec![to];
        let mut at = to;
        while self.previous[at as usize] != u32::MAX {
            at = self.previous[at as usize];
            path.push(at);
        }
        path.reverse();
        path
    }

    /// Calls `visit(point, distance)` once for every point within `limit` of `from`.
    pub(super) fn run(
        &mut self,
        neighbours: &[Vec<(u32, f64)>],
        from: u32,
        limit: f64,
        visit: impl FnMut(u32, f64),
    ) {
        self.run_from(neighbours, &[from], limit, visit);
    }

    fn run_from(
        &mut self,
        neighbours: &[Vec<(u32, f64)>],
        sources: &[u32],
        limit: f64,
        mut visit: impl FnMut(u32, f64),
    ) {
        for &i in &self.touched {
            self.distance[i as usize] = f64::INFINITY;
            self.previous[i as usize] = u32::MAX;
        }
        self.touched.clear();
        for &s in sources {
            self.distance[s as usize] = 0.0;
            self.touched.push(s);
            self.heap.push(Reverse((Ordered(0.0), s)));
        }
        while let Some(Reverse((Ordered(d), i))) = self.heap.pop() {
            if d > self.distance[i as usize] {
                continue;
            }
            visit(i, d);
            for &(j, length) in &neighbours[i as usize] {
                let dj = d + length;
                if dj <= limit && dj < self.distance[j as usize] {
                    if self.distance[j as usize].is_infinite() {
                        self.touched.push(j);
                    }
                    self.distance[j as usize] = dj;
                    self.previous[j as usize] = i;
                    self.heap.push(Reverse((Ordered(dj), j)));
                }
            }
        }
    }
}

/// Cells across the raster a cross-section is measured on.
const SECTION_CELLS: usize = 32;

/// A cross-section of the shape: the union of the medial balls cut by a plane, drawn on
/// a square raster around a point, and the piece of it that holds the point.
struct Section {
    covered: Vec<bool>,
    piece: Vec<u32>,
}

impl Section {
    fn new() -> Section {
        Section {
            covered: vec![false; SECTION_CELLS * SECTION_CELLS],
            piece: Vec::new(),
        }
    }

    /// The centroid of the piece of the cross-section through `p` across `tangent`
    /// that holds `p`, drawn over `half` either side of `p`; `None` if that piece
    /// reaches the raster's edge (the section is wider than the window: a wide sheet or
    /// where branches meet) or `p` is in no ball.
    fn centroid(
        &mut self,
        lookup: &AxisLookup,
        p: DVec3,
        tangent: DVec3,
        half: f64,
    ) -> Option<DVec3> {
        let (u, v) = tangent.any_orthonormal_pair();
        let n = SECTION_CELLS;
        let cell = 2.0 * half / n as f64;
        self.covered.fill(false);
        // A ball that reaches into the window but whose centre lies farther than this
        // is (on a medial axis, whose balls overlap their neighbours') covered by
        // nearer ones.
        let reach = 2.0 * half;
        for (centre, r) in lookup.balls.near(p, reach) {
            let c = centre - p;
            let d = c.dot(tangent);
            if d.abs() >= r {
                continue;
            }
            let rho = (r * r - d * d).sqrt();
            let (x, y) = (c.dot(u) + half, c.dot(v) + half);
            // Row by row, the span of cells whose centre the disc covers.
            let rows = ((y - rho) / cell - 0.5).ceil().max(0.0) as usize
                ..(((y + rho) / cell - 0.5).floor() + 1.0).clamp(0.0, n as f64) as usize;
            for j in rows {
                let dy = (j as f64 + 0.5) * cell - y;
                let dx = (rho * rho - dy * dy).max(0.0).sqrt();
                let lo = ((x - dx) / cell - 0.5).ceil().max(0.0) as usize;
                let hi = (((x + dx) / cell - 0.5).floor() + 1.0).clamp(0.0, n as f64) as usize;
                if lo < hi {
                    self.covered[j * n + lo..j * n + hi].fill(true);
                }
            }
        }
        let start = n / 2 * n + n / 2;
        if !self.covered[start] {
            return None;
        }
        // The piece around `p`: a flood fill over covered cells.
        self.piece.clear();
        self.piece.push(start as u32);
        self.covered[start] = false;
        let (mut sum, mut at) = ((0.0, 0.0), 0);
        while at < self.piece.len() {
            let k = self.piece[at] as usize;
            at += 1;
            let (i, j) = (k % n, k / n);
            if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
                return None;
            }
            sum.0 += (i as f64 + 0.5) * cell - half;
            sum.1 += (j as f64 + 0.5) * cell - half;
            for next in [k - 1, k + 1, k - n, k + n] {
                if self.covered[next] {
                    self.covered[next] = false;
                    self.piece.push(next as u32);
                }
            }
        }
        let count = self.piece.len() as f64;
        Some(p + u * (sum.0 / count) + v * (sum.1 / count))
    }
}

/// The radius of the largest ball centred at `p` inside the union of the medial balls
/// near it (`p` itself lies within `reach` of one's centre).
fn inscribed_radius(axis: &MedialAxis, lookup: &AxisLookup, p: DVec3, reach: f64) -> f64 {
    lookup
        .tree
        .locate_within_distance(p.to_array(), reach * reach)
        .map(|ball| axis.radii[ball.data as usize] - DVec3::from(*ball.geom()).distance(p))
        .fold(0.0, f64::max)
}
