//! Gradients and regions of a distance field (paper §5.1–5.2).
//!
//! Inside a face the field is the least of its candidates (see [`ValueSource`]), each
//! `σ` plus the length of a straight line from a site: a node, a source, or the virtual
//! source of a wave unfolded into the face's plane. A face's **regions** are where one
//! candidate gives the value. In a region the distance is exactly `σ + |x − site|` in
//! the metric's flattening, so its gradient points straight away from the site and the
//! geodesic arriving at `x` comes straight from it: no fitting is needed (the paper fits
//! a plane to the values at a region's corners; here the candidate *is* the region's
//! formula).
//!
//! # How the regions are drawn
//! The face is cut by a barycentric grid of `subdivisions` per edge; each grid point is
//! labelled with the candidate giving its value; where a sub-triangle's corners differ,
//! the switch along each of its sides is found by bisection (to 2⁻⁴⁰ of the side), and
//! the sub-triangle is cut there (a corner's piece, and a centre point where three
//! labels meet). Pieces with one label are merged, and points where the boundary runs
//! straight are dropped. So a region's sides on the face's edges and straight
//! boundaries are exact, its curved boundaries (hyperbola arcs between two point
//! sources) are chords between points on the true boundary, and a region thinner
//! than a sub-triangle that covers no grid point is missed.

use super::face_field::{flat_to_bary, Candidate, FaceField, Site, ValueSource};
use super::Query;
use crate::flat::same_source;
use crate::mesh::Topology;
use crate::surface::SurfacePoint;
use crate::{Error, PointRole};
use geotracks_metrics::{FacePoint, Metric};
use glam::DVec3;
use std::collections::HashMap;

/// The gradient of a distance field at a point ([`Field::gradient_at`](crate::Field::gradient_at)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Gradient {
    /// The distance at the point.
    pub distance: f64,
    /// ∇d in world coordinates, in the plane of [`Gradient::face`]: moving the point by
    /// a small `v` in that plane changes the distance by about `vector · v`. A unit
    /// vector under the Euclidean metric; longer where the metric makes lengths cost
    /// more.
    pub vector: DVec3,
    /// The unit direction (world, in the face's plane) in which the geodesic that
    /// reaches the point travels there, away from its source: a path back to the
    /// source leaves along `−direction`. Under the Euclidean metric and a constant
    /// density, the direction of `vector`; under an anisotropic tensor, `vector` turned
    /// by the metric; under a density that varies, the straight segment from the node
    /// the engine models (while `vector` also feels the density change across it).
    pub direction: DVec3,
    /// The face it was computed in: one holding the point whose candidate gives the
    /// distance.
    pub face: u32,
    /// The candidate that gives the distance there.
    pub source: ValueSource,
    /// For a candidate of the face across an edge (wavefront engine; see
    /// [`Field::distance_at`](crate::Field::distance_at)), that edge: its lines cross it.
    pub across: Option<u32>,
}

/// One region of a face: where one candidate gives the distance ([`Field::regions`](crate::Field::regions)),
/// or several with the same formula (the waves of neighbouring nodes that carry one
/// virtual source: the region is named after the first).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Region {
    /// The face.
    pub face: u32,
    /// What gives the distance in the region.
    pub source: ValueSource,
    /// For a candidate of the face across an edge, that edge (see [`Gradient::across`]).
    pub across: Option<u32>,
    /// Where its straight lines come from, in world coordinates: the node, the source,
    /// or a wave's virtual source unfolded into the face's plane (then usually outside
    /// the face). The distance at a point `x` of the region is
    /// [`Region::offset`] plus the metric length of the straight segment from here to
    /// `x` in the face's plane.
    pub virtual_source: DVec3,
    /// The distance at [`Region::virtual_source`] (the node's value, the source's
    /// start, the wave's `σ`).
    pub offset: f64,
    /// The region's boundary, counter-clockwise seen from the side the face's corners
    /// turn counter-clockwise (vertices, edge points and face points of the face; not
    /// repeated at the end).
    pub polygon: Vec<SurfacePoint>,
    /// Other regions inside this one, each a clockwise loop of the same kind of
    /// points (usually none).
    pub holes: Vec<Vec<SurfacePoint>>,
    /// The region's area (world units), holes excluded.
    pub area: f64,
    /// A point inside the region (its polygon's mean point where that lies inside,
    /// else one nearer a corner of it); `None` for a sliver too thin to find one in.
    pub inside: Option<SurfacePoint>,
    /// The gradient at [`Region::inside`] (see [`Field::gradient_at`](crate::Field::gradient_at); inside a region
    /// it turns, pointing away from the virtual source everywhere).
    pub gradient: Option<Gradient>,
}

/// Grid resolution of [`Field::regions`](crate::Field::regions).
pub const DEFAULT_REGION_SUBDIVISIONS: u32 = 16;
/// Above this a face's grid is refused as a mistake (as for isolines).
const MAX_REGION_SUBDIVISIONS: u32 = 1024;
/// Candidates whose values at a point differ by less than this (of the face's
/// diameter plus the value) tie there: the point goes to the one farthest upstream
/// ([`FaceField::best_upstream`]).
const TIE: f64 = 1e-10;
/// Bisection steps for a switch point along a sub-triangle's side.
const BISECTIONS: u32 = 40;

impl<M: Metric, T: Topology> Query<'_, M, T> {
    /// The gradient of the field at `point`, from the candidate that gives its
    /// distance: the derivative of `σ + |x − site|` there. `None` where the gradient is
    /// undefined: unreached points, and points whose value only they explain (a source,
    /// a node whose value comes from nowhere else in its faces). At a vertex or edge
    /// point, the face (of those around it) whose candidate gives the least value.
    ///
    /// # Complexity
    /// As [`Field::distance_at`](crate::Field::distance_at): the candidates of the faces around the point.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] if `point` is not a point of the mesh.
    pub fn gradient_at(&self, point: SurfacePoint) -> Result<Option<Gradient>, Error> {
        let distance = self.distance_at(point)?;
        if !distance.is_finite() {
            return Ok(None);
        }
        let (mesh, metric) = (self.mesh, self.metric);
        let point = point.validated(mesh).map_err(|error| Error::InvalidPoint {
            which: PointRole::Query,
            error,
        })?;
        let mut best: Option<(f64, u32, FaceField, usize, FacePoint)> = None;
        for &f in point.faces(mesh).iter() {
            let x = point.in_face(mesh, f).expect("the point lies on its faces");
            let face = self.face_field(f);
            let px = face.flat_point(&x);
            let near = 1e-9 * mesh.frame(f).diameter();
            // Not the point's own node or source: it explains nothing of the slope.
            let at_point = |c: &Candidate| match (c.site, px) {
                (Site::Flat(s), Some(px)) | (Site::Windowed { at: s, .. }, Some(px)) => {
                    px.sub(s).length() <= near
                }
                (Site::Metric(p), _) => p.distance(&x) <= near,
                _ => false,
            };
            if let Some((v, c)) = face.best(metric, &x, at_point) {
                if best.as_ref().is_none_or(|b| v < b.0) {
                    best = Some((v, f, face, c, x));
                }
            }
        }
        let Some((value, f, face, c, x)) = best else {
            return Ok(None);
        };
        let slack = 1e-9 * (distance.abs() + mesh.frame(f).diameter());
        if value > distance + slack {
            return Ok(None);
        }
        let candidate = face.candidates[c];
        let (vector, direction) = slope(mesh, metric, &face, &candidate, &x);
        Ok(Some(Gradient {
            distance,
            vector,
            direction,
            face: f,
            source: candidate.source,
            across: candidate.across.map(|(e, _)| e),
        }))
    }

    /// Face `face`'s regions: where each of its candidates gives the distance, as
    /// polygons (see the module docs for how they are drawn, to `subdivisions` grid
    /// steps per edge; [`DEFAULT_REGION_SUBDIVISIONS`] is a good start). Sorted by
    /// candidate (nodes, sources, waves); a candidate whose region is cut in two gives
    /// two. Unreached parts of the face belong to no region.
    ///
    /// # Complexity
    /// `(n + 1)(n + 2) / 2` evaluations of the face's candidates, plus 40 per side where
    /// the candidate changes.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] for a face not in the mesh, [`Error::InvalidRegionOption`]
    /// for `subdivisions` outside `1..=1024`.
    pub fn regions(&self, face: u32, subdivisions: u32) -> Result<Vec<Region>, Error> {
        let mesh = self.mesh;
        let centre = SurfacePoint::Face {
            face,
            bary: [1.0 / 3.0; 3],
        };
        if let Err(error) = centre.validated(mesh) {
            return Err(Error::InvalidPoint {
                which: PointRole::Query,
                error,
            });
        }
        if subdivisions == 0 || subdivisions > MAX_REGION_SUBDIVISIONS {
            return Err(Error::InvalidRegionOption {
                option: "subdivisions",
                value: subdivisions as f64,
                expected: "between 1 and 1024",
            });
        }
        let field = self.face_field(face);
        let grid = LabelGrid::new(self, &field, subdivisions);
        let face_area = polygon_area(
            mesh,
            face,
            &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        );
        let mut out = Vec::new();
        for (label, loops) in grid.boundaries() {
            let candidate = field.candidates[label];
            // Counter-clockwise loops are outlines, clockwise ones holes (another
            // region inside this one); loops of no area only touch a grid side.
            let signed: Vec<(f64, Vec<[f64; 3]>)> = loops
                .into_iter()
                .map(|l| (polygon_area(mesh, face, &l), l))
                .filter(|(a, _)| a.abs() > 1e-12 * face_area)
                .collect();
            let (outlines, holes): (Vec<_>, Vec<_>) =
                signed.into_iter().partition(|(a, _)| *a > 0.0);
            let mut holes_of: Vec<Vec<(f64, Vec<[f64; 3]>)>> = vec![Vec::new(); outlines.len()];
            for hole in holes {
                let probe = hole.1[0];
                if let Some(k) = outlines.iter().position(|(_, o)| contains(o, probe)) {
                    holes_of[k].push(hole);
                }
            }
            for ((outline_area, polygon), holes) in outlines.into_iter().zip(holes_of) {
                let area = outline_area + holes.iter().map(|(a, _)| a).sum::<f64>();
                let inside = grid.inside(label, &polygon);
                let gradient = inside.map(|bary| {
                    let x = mesh.frame(face).point(bary);
                    let (vector, direction) = slope(mesh, self.metric, &field, &candidate, &x);
                    Gradient {
                        distance: grid.value_at(bary),
                        vector,
                        direction,
                        face,
                        source: candidate.source,
                        across: candidate.across.map(|(e, _)| e),
                    }
                });
                let to_points =
                    |l: &[[f64; 3]]| l.iter().map(|&b| on_face(mesh, face, b)).collect();
                out.push(Region {
                    face,
                    source: candidate.source,
                    across: candidate.across.map(|(e, _)| e),
                    virtual_source: field.site_position(mesh, &candidate),
                    offset: candidate.sigma,
                    polygon: to_points(&polygon),
                    holes: holes.iter().map(|(_, h)| to_points(h)).collect(),
                    area,
                    inside: inside.map(|bary| SurfacePoint::Face { face, bary }),
                    gradient,
                });
            }
        }
        Ok(out)
    }
}

/// The gradient vector and the unit direction of candidate `c`'s value at face point
/// `x` (world coordinates).
fn slope<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    face: &FaceField,
    c: &Candidate,
    x: &FacePoint,
) -> (DVec3, DVec3) {
    let f = face.face;
    let [p0, p1, p2] = mesh.face_vertices(f).map(|v| mesh.position(v));
    let (e1, e2) = (p1 - p0, p2 - p0);
    // A world vector y = a·e1 + b·e2 of the plane from its dot products with e1, e2:
    // (a, b) = G⁻¹ (e1·y, e2·y), G the Gram matrix. A gradient ∇ with ∇·e1 = da and
    // ∇·e2 = db is ∇ = m1·e1 + m2·e2 with (m1, m2) = G⁻¹ (da, db).
    let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let det = g11 * g22 - g12 * g12;
    let from_derivatives = |da: f64, db: f64| {
        let m1 = (g22 * da - g12 * db) / det;
        let m2 = (g11 * db - g12 * da) / det;
        e1 * m1 + e2 * m2
    };
    match (c.site, face.flat, face.flat_point(x)) {
        (Site::Flat(s) | Site::Windowed { at: s, .. }, Some(frame), Some(px)) => {
            let d = px.sub(s);
            let unit = d.scale(1.0 / d.length());
            // Flattened coordinates are linear in (a, b): corner 1 at (l01, 0), corner
            // 2 at (x2, y2); so ∂d/∂a = unit·c1 and ∂d/∂b = unit·c2.
            let da = unit.0 * frame.l01;
            let db = unit.0 * frame.x2 + unit.1 * frame.y2;
            let [b1, b2] = flat_to_bary(&frame, unit);
            (from_derivatives(da, db), (e1 * b1 + e2 * b2).normalize())
        }
        (Site::Metric(p), _, _) => {
            // The metric's segment cost, differentiated numerically in (a, b) towards
            // the inside of the face (the cost is only defined there).
            let h = 1e-6;
            let cost = |b: [f64; 3]| metric.cost(f, &p, &mesh.frame(f).point(b));
            let step = |axis: usize| -> f64 {
                let mut plus = x.bary;
                let sign = if x.bary[axis] + h <= 1.0 && x.bary[0] - h >= 0.0 {
                    1.0
                } else {
                    -1.0
                };
                plus[axis] += sign * h;
                plus[0] -= sign * h;
                (cost(plus) - cost(x.bary)) / (sign * h)
            };
            let direction = (mesh.point(f, x.bary) - mesh.point(f, p.bary)).normalize();
            (from_derivatives(step(1), step(2)), direction)
        }
        _ => (DVec3::NAN, DVec3::NAN),
    }
}

/// A point of a face's region grid: a grid point, a switch point on the side between
/// two grid points (by index, lower first), or the centre of a sub-triangle where three
/// labels meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Key {
    Grid(usize),
    Side(usize, usize),
    Centre(usize, usize, usize),
}

/// A face's grid labelled with the candidate giving each point's value.
struct LabelGrid<'f, 'q, 'a, M, T> {
    query: &'q Query<'a, M, T>,
    field: &'f FaceField,
    n: usize,
    bary: Vec<[f64; 3]>,
    label: Vec<Option<usize>>,
    /// The face's diameter: the scale of [`TIE`].
    scale: f64,
    /// Per candidate, the first candidate with the same formula (site and σ): the
    /// waves of neighbouring nodes on an edge often carry one virtual source, and
    /// where they take over from each other the field does not change.
    same: Vec<usize>,
}

impl<'f, 'q, 'a, M: Metric, T: Topology> LabelGrid<'f, 'q, 'a, M, T> {
    fn new(query: &'q Query<'a, M, T>, field: &'f FaceField, n: u32) -> Self {
        let n = n as usize;
        let mut bary = Vec::with_capacity((n + 1) * (n + 2) / 2);
        for j in 0..=n {
            for i in 0..=n - j {
                let (bi, bj) = (i as f64 / n as f64, j as f64 / n as f64);
                bary.push([1.0 - bi - bj, bi, bj]);
            }
        }
        let scale = query.mesh.frame(field.face).diameter();
        let site = |c: &Candidate| match c.site {
            Site::Flat(s) | Site::Windowed { at: s, .. } => Some(s),
            Site::Metric(_) => None,
        };
        let same = (0..field.candidates.len())
            .map(|i| {
                let ci = &field.candidates[i];
                (0..i)
                    .find(|&j| {
                        let cj = &field.candidates[j];
                        match (site(ci), site(cj)) {
                            (Some(a), Some(b)) => {
                                same_source(a, ci.sigma, b, cj.sigma, scale, query.turn)
                            }
                            _ => false,
                        }
                    })
                    .unwrap_or(i)
            })
            .collect();
        let mut grid = LabelGrid {
            query,
            field,
            n,
            bary,
            label: Vec::new(),
            scale,
            same,
        };
        grid.label = grid.bary.iter().map(|&b| grid.label_at(b)).collect();
        grid
    }

    fn index(&self, i: usize, j: usize) -> usize {
        j * (self.n + 1) - j * j.saturating_sub(1) / 2 + i
    }

    /// The candidate giving the value at `bary` (`None`: unreached).
    fn label_at(&self, bary: [f64; 3]) -> Option<usize> {
        let x = self.query.mesh.frame(self.field.face).point(bary);
        let tolerance = |value: f64| TIE * (self.scale + value.abs());
        let (value, c) = self.field.best_upstream(self.query.metric, &x, tolerance)?;
        let c = self.same[c];
        let horizon = self.query.field.horizon;
        let unreached = value > self.query.field.horizon.max_distance
            || (horizon.is_bounded() && {
                let horizon = horizon.in_face(self.query.mesh, self.field.face);
                value > self.field.unsettled(self.query.metric, horizon, &x)
            });
        (!unreached).then_some(c)
    }

    /// The value at `bary`.
    fn value_at(&self, bary: [f64; 3]) -> f64 {
        let x = self.query.mesh.frame(self.field.face).point(bary);
        self.field
            .best(self.query.metric, &x, |_| false)
            .map_or(f64::INFINITY, |(v, _)| v)
    }

    /// A point strictly inside `label`'s region bounded by `polygon`: its mean point if
    /// that has the label, else one between the mean and a corner.
    fn inside(&self, label: usize, polygon: &[[f64; 3]]) -> Option<[f64; 3]> {
        let mean = polygon_centroid(polygon);
        let mix = |p: [f64; 3], w: f64| [0, 1, 2].map(|k| w * p[k] + (1.0 - w) * mean[k]);
        std::iter::once(mean)
            .chain(polygon.iter().map(|&p| mix(p, 0.5)))
            .chain(polygon.iter().map(|&p| mix(p, 0.9)))
            .find(|&b| self.label_at(b) == Some(label))
    }

    /// Where the label changes along the side from grid point `g` to `h` (`g < h`):
    /// the last point still labelled as `g`, by bisection.
    fn switch(&self, g: usize, h: usize) -> [f64; 3] {
        let (a, b) = (self.bary[g], self.bary[h]);
        let at = |t: f64| [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if self.label_at(at(mid)) == self.label[g] {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        at(0.5 * (lo + hi))
    }

    /// Each label's boundary loops, as barycentric points (counter-clockwise).
    fn boundaries(&self) -> Vec<(usize, Vec<Vec<[f64; 3]>>)> {
        let n = self.n;
        let mut points: HashMap<Key, [f64; 3]> = HashMap::new();
        // Per label, its directed boundary edges: an edge met both ways is inside.
        let mut edges: HashMap<usize, HashMap<(Key, Key), ()>> = HashMap::new();
        let mut add_piece = |label: Option<usize>, piece: &[Key]| {
            let Some(label) = label else { return };
            let set = edges.entry(label).or_default();
            for (k, &a) in piece.iter().enumerate() {
                let b = piece[(k + 1) % piece.len()];
                if set.remove(&(b, a)).is_none() {
                    set.insert((a, b), ());
                }
            }
        };
        for j in 0..n {
            for i in 0..n - j {
                let up = [self.index(i, j), self.index(i + 1, j), self.index(i, j + 1)];
                self.cut(up, &mut points, &mut add_piece);
                if i + j + 1 < n {
                    let down = [
                        self.index(i + 1, j),
                        self.index(i + 1, j + 1),
                        self.index(i, j + 1),
                    ];
                    self.cut(down, &mut points, &mut add_piece);
                }
            }
        }
        for (g, &b) in self.bary.iter().enumerate() {
            points.insert(Key::Grid(g), b);
        }
        let mut labels: Vec<_> = edges.into_iter().collect();
        labels.sort_by_key(|(label, _)| *label);
        labels
            .into_iter()
            .map(|(label, set)| {
                // In a fixed order (the set's is a hash's, random per process): the
                // same field gives the same polygons, starting at the same point.
                let mut edges: Vec<(Key, Key)> = set.into_keys().collect();
                edges.sort_unstable();
                let loops = chain(edges)
                    .into_iter()
                    .map(|l| simplify(l.iter().map(|k| points[k]).collect()))
                    .filter(|l| l.len() >= 3)
                    .collect();
                (label, loops)
            })
            .collect()
    }

    /// Cuts sub-triangle `t` (grid indices, counter-clockwise) into pieces of one label
    /// each, handing each piece to `add`.
    fn cut(
        &self,
        t: [usize; 3],
        points: &mut HashMap<Key, [f64; 3]>,
        add: &mut impl FnMut(Option<usize>, &[Key]),
    ) {
        let l = t.map(|g| self.label[g]);
        if l[0] == l[1] && l[1] == l[2] {
            add(l[0], &t.map(Key::Grid));
            return;
        }
        let mut side = |g: usize, h: usize| -> Key {
            let (g, h) = (g.min(h), g.max(h));
            let key = Key::Side(g, h);
            points.entry(key).or_insert_with(|| self.switch(g, h));
            key
        };
        // The corner whose label differs from both others, if there is one.
        let odd = (0..3).find(|&k| l[(k + 1) % 3] == l[(k + 2) % 3]);
        match odd {
            Some(k) => {
                let (o, p, q) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let (sop, sqo) = (side(o, p), side(q, o));
                add(l[k], &[Key::Grid(o), sop, sqo]);
                add(l[(k + 1) % 3], &[sop, Key::Grid(p), Key::Grid(q), sqo]);
            }
            None => {
                let s = [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])];
                let centre = Key::Centre(t[0], t[1], t[2]);
                let mid = [0, 1, 2]
                    .map(|k| (points[&s[0]][k] + points[&s[1]][k] + points[&s[2]][k]) / 3.0);
                points.insert(centre, mid);
                for k in 0..3 {
                    add(l[k], &[Key::Grid(t[k]), s[k], centre, s[(k + 2) % 3]]);
                }
            }
        }
    }
}

/// Joins directed edges into closed loops (at a point where a region touches itself,
/// any continuation closes a loop).
fn chain(edges: Vec<(Key, Key)>) -> Vec<Vec<Key>> {
    let mut next: HashMap<Key, Vec<Key>> = HashMap::new();
    for &(a, b) in &edges {
        next.entry(a).or_default().push(b);
    }
    let mut loops = Vec::new();
    for (start, _) in edges {
        let Some(first) = next.get_mut(&start).and_then(|v| v.pop()) else {
            continue;
        };
        let mut l = vec![start];
        let mut at = first;
        while at != start {
            l.push(at);
            match next.get_mut(&at).and_then(|v| v.pop()) {
                Some(b) => at = b,
                None => break,
            }
        }
        loops.push(l);
    }
    loops
}

/// Drops the points where a loop runs straight on (to 1e-12 of the face, in
/// barycentric coordinates), and points repeated in a row.
fn simplify(mut l: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    loop {
        let n = l.len();
        if n < 3 {
            return l;
        }
        let straight = (0..n).find(|&k| {
            let (a, b, c) = (l[(k + n - 1) % n], l[k], l[(k + 1) % n]);
            let (u, v) = ([b[1] - a[1], b[2] - a[2]], [c[1] - b[1], c[2] - b[2]]);
            let cross = u[0] * v[1] - u[1] * v[0];
            cross.abs() <= 1e-12 && u[0] * v[0] + u[1] * v[1] >= 0.0
        });
        match straight {
            Some(k) => {
                l.remove(k);
            }
            None => return l,
        }
    }
}

/// A barycentric point of face `f` as a surface point: a vertex, an edge point or a
/// face point.
fn on_face<T: Topology>(mesh: &T, f: u32, bary: [f64; 3]) -> SurfacePoint {
    let zero = bary.map(|b| b.abs() <= 1e-14);
    let corners = mesh.face_vertices(f);
    match zero {
        [false, true, true] => SurfacePoint::Vertex(corners[0]),
        [true, false, true] => SurfacePoint::Vertex(corners[1]),
        [true, true, false] => SurfacePoint::Vertex(corners[2]),
        _ => match (0..3).find(|&k| zero[k]) {
            // On the side opposite corner k: from corner k + 1 to corner k + 2.
            Some(k) => {
                let slot = (k + 1) % 3;
                let edge = mesh.face_edges(f)[slot];
                let along = bary[(k + 2) % 3] / (bary[(k + 1) % 3] + bary[(k + 2) % 3]);
                let t = if mesh.slot_is_reversed(f, slot) {
                    1.0 - along
                } else {
                    along
                };
                SurfacePoint::Edge { edge, t }
            }
            None => SurfacePoint::Face { face: f, bary },
        },
    }
}

/// A polygon's area in world units.
fn polygon_area<T: Topology>(mesh: &T, f: u32, polygon: &[[f64; 3]]) -> f64 {
    let frame = mesh.frame(f);
    let p: Vec<[f64; 2]> = polygon.iter().map(|&b| frame.point(b).uv).collect();
    let n = p.len();
    0.5 * (0..n)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
}

/// Whether barycentric point `p` lies inside `polygon` (crossings of a ray in the
/// `(b1, b2)` plane).
fn contains(polygon: &[[f64; 3]], p: [f64; 3]) -> bool {
    let n = polygon.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (polygon[k], polygon[(k + 1) % n]);
        if (a[2] > p[2]) != (b[2] > p[2]) {
            let x = a[1] + (p[2] - a[2]) / (b[2] - a[2]) * (b[1] - a[1]);
            if p[1] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// A polygon's mean point.
fn polygon_centroid(polygon: &[[f64; 3]]) -> [f64; 3] {
    let n = polygon.len() as f64;
    [0, 1, 2].map(|k| polygon.iter().map(|b| b[k]).sum::<f64>() / n)
}
