//! Isolines of a distance field: polylines of surface points at given levels.
//!
//! # How they are drawn
//! Each face is cut into `n²` sub-triangles by a barycentric grid (`n` =
//! [`IsolineOptions::subdivisions`]); the field is evaluated at the grid points with
//! [`Field::distance_at`](crate::Field::distance_at), the engine's own value at any point (from the waves where
//! the wavefront engine ran), not an interpolation of vertex values. In every
//! sub-triangle that a level crosses, the crossings on its two sides are solved on the
//! field itself (a root of `distance_at − level` along the side), so **every point of an
//! isoline lies at its level**, to 1e-12 of the level (of the mean edge length near
//! level 0) where the field is continuous. A segment
//! whose middle is off the level by more than the tolerance (a circle arc's sagitta, or a
//! ridge where two regions of the field meet and the isoline bends) gets a point on the
//! level across its middle, recursively: isolines bend at ridges instead of cutting the
//! corner as linear interpolation of vertex values does.
//!
//! Grid points and crossings on a mesh edge are the same points from every face around
//! it (the edge's own parameter, evaluated on the edge, where the value is the least
//! over its faces), so isolines continue across edges, non-manifold ones included:
//! where `m` faces share an edge, `m` polylines meet at the same point of it.
//!
//! # Cost
//! `(n + 1)(n + 2) / 2` evaluations per face, each O(k) metric costs, plus a few dozen
//! per crossing; faces are processed in parallel (rayon).

mod faces;
mod link;

use crate::mesh::Topology;
use faces::FaceGrid;
use link::link;

use super::query::FaceFields;
use super::Query;
use crate::error::ValueRole;
use crate::flat::flat_frame;
use crate::surface::SurfacePoint;
use crate::Error;
use geotracks_metrics::Metric;
use rayon::prelude::*;
use std::cell::RefCell;

/// One isoline: a polyline of surface points at one level of a field.
///
/// Consecutive points lie on a common face (the segment between them is inside it).
/// A closed isoline's last point is its first. An open one ends on the mesh's boundary,
/// at the edge of the reached region (a stop's maximum distance, an unreached
/// component), or where it meets other isolines of its level on a non-manifold edge.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Isoline {
    /// The level.
    pub level: f64,
    /// The points, in order along the line.
    pub points: Vec<SurfacePoint>,
    /// Whether the line closes on itself.
    pub closed: bool,
}

/// How finely isolines are drawn ([`Field::isolines`](crate::Field::isolines)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct IsolineOptions {
    /// Each face is cut into `subdivisions²` sub-triangles (at least 1): a level set
    /// smaller than a sub-triangle (a small loop around a local maximum) can be missed.
    pub subdivisions: u32,
    /// How far the middle of a segment may lie from the level, as a fraction of the
    /// segment's length, before the segment gets a point on the level across it. (The
    /// points themselves are solved to 1e-12 of the level, whatever this is.)
    pub tolerance: f64,
    /// How many times a segment may be split in two (at most `2^max_splits` pieces).
    pub max_splits: u32,
}

impl IsolineOptions {
    /// Four subdivisions per edge, tolerance 1e-3, up to 5 splits.
    pub const DEFAULT: IsolineOptions = IsolineOptions {
        subdivisions: 4,
        tolerance: 1e-3,
        max_splits: 5,
    };

    /// These options with `subdivisions` per edge.
    pub const fn with_subdivisions(mut self, subdivisions: u32) -> Self {
        self.subdivisions = subdivisions;
        self
    }
}

impl Default for IsolineOptions {
    fn default() -> Self {
        IsolineOptions::DEFAULT
    }
}

/// The most levels one call of [`Field::isolines`](crate::Field::isolines) draws. Each level costs a pass over
/// the faces its range crosses and writes its lines: a thousand levels draw a contour
/// every 0.1 % of the range, finer than any picture or map shows, while a mistyped
/// count (10⁸) would run for hours and fill the memory. Draw more in several calls.
pub const MAX_LEVELS: usize = 1000;

/// Checks a number of levels against [`MAX_LEVELS`] (and that there is at least one),
/// before any level is computed or allocated; [`Field::isolines`](crate::Field::isolines) makes the same
/// check.
///
/// # Errors
/// [`Error::InvalidIsolineOption`] naming `levels`.
pub fn check_level_count(count: usize) -> Result<(), Error> {
    if count == 0 || count > MAX_LEVELS {
        return Err(Error::InvalidIsolineOption {
            option: "number of levels",
            value: count as f64,
            expected: "between 1 and 1000 (draw more in several calls)",
        });
    }
    Ok(())
}

/// `count` levels spread evenly over `(0, max)`, excluding both ends: the level at 0
/// is the sources themselves and the one at the maximum a point.
pub fn spread_levels(max: f64, count: usize) -> Vec<f64> {
    (1..=count)
        .map(|i| max * i as f64 / (count + 1) as f64)
        .collect()
}

/// What identifies a point across faces: grid points and crossings on mesh edges are
/// named by the edge, so every face around it finds the same one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Key {
    Vertex(u32),
    /// Grid point `m` (of `n + 1`, from the lower vertex) of an edge.
    EdgeGrid(u32, u32),
    /// Grid point `(i, j)` inside a face.
    FaceGrid(u32, u32, u32),
    /// The crossing on the edge's piece `m` (between grid points `m` and `m + 1`).
    EdgeCross(u32, u32),
    /// The crossing on a side between two grid points of a face (by their indices in
    /// its grid) that is not on a mesh edge: only that face holds it.
    FaceCross(u32, u32, u32),
}

/// One sub-triangle's piece of an isoline: its two ends (keyed) and the points that
/// split it, in order from the first end.
struct Segment {
    level: usize,
    a: (Key, SurfacePoint),
    b: (Key, SurfacePoint),
    inner: Vec<SurfacePoint>,
}

impl<M: Metric, T: Topology> Query<'_, M, T> {
    /// The isolines of the field at `levels` (any finite values; a level no point
    /// reaches gives none), each as polylines of surface points; see the module docs
    /// for how they are drawn and what they guarantee.
    ///
    /// # Errors
    /// [`Error::InvalidValue`] for a level that is not finite,
    /// [`Error::InvalidIsolineOption`] for options out of range or more than
    /// [`MAX_LEVELS`] levels.
    pub fn isolines(
        &self,
        levels: &[f64],
        options: &IsolineOptions,
    ) -> Result<Vec<Isoline>, Error> {
        check_options(levels, options)?;
        Ok(self.isolines_gated(levels, options, true))
    }

    /// The isolines, with `gate`: faces whose values bound away from every level are
    /// skipped before their grid is evaluated (see [`Field::may_cross`](crate::Field::may_cross)), so the work
    /// follows the faces the lines cross, not the mesh. Without it (the tests compare
    /// both), every face's grid is evaluated.
    pub(crate) fn isolines_gated(
        &self,
        levels: &[f64],
        options: &IsolineOptions,
        gate: bool,
    ) -> Vec<Isoline> {
        let mesh = self.mesh();
        let scale = mesh.mean_edge_length();
        let mut sorted = levels.to_vec();
        sorted.sort_by(f64::total_cmp);
        let starts = gate.then(|| self.least_starts());
        let segments: Vec<Segment> = (0..mesh.face_count() as u32)
            .into_par_iter()
            // One cache of candidates per worker's run of faces: neighbouring faces
            // (mostly near in id) share their candidates instead of building them
            // again.
            .map_init(
                || RefCell::new(FaceFields::default()),
                |cache, f| match &starts {
                    Some(starts) if !self.may_cross(f, &sorted, starts, cache) => Vec::new(),
                    _ => FaceGrid::new(self, f, options, scale, cache).segments(levels),
                },
            )
            .flatten_iter()
            .collect();
        link(levels, segments)
    }

    /// Per face, the least start of the run's sources on its closure (`inf`: none).
    fn least_starts(&self) -> Vec<f64> {
        let mesh = self.mesh();
        let mut least = vec![f64::INFINITY; mesh.face_count()];
        for source in self.field.sources {
            for &f in source.point.faces(mesh).iter() {
                least[f as usize] = least[f as usize].min(source.start);
            }
        }
        least
    }

    /// Whether a level of `sorted` may lie within face `f`'s grid values, from bounds
    /// on every value in the face that cost no evaluation of them (a face whose
    /// bounds hold no level has no grid value below a level and another not below
    /// it, so [`FaceGrid::segments`] would draw nothing there):
    ///
    /// - from below: a value in the face (on its edges, the least over the faces
    ///   around) is a candidate's, never below its floor; for the Steiner-graph
    ///   engines the candidates are the nodes of the face (value plus a cost ≥ 0) and
    ///   the sources on it (start plus a cost), so the least node value and start over
    ///   the face and the faces across its edges bound it. The wavefront engine's
    ///   waves give less than their nodes, by at most the distance from the node: a
    ///   first, cheap bound allows for that; where it holds a level, the face's
    ///   candidates are built and their floors read.
    /// - from above, where the metric flattens the face and the run did not stop
    ///   early: every reached vertex of the face is a candidate, giving its value plus
    ///   the flattened distance, at most the face's longest flattened edge; a vertex's
    ///   own grid value is the run's value there.
    fn may_cross(
        &self,
        f: u32,
        sorted: &[f64],
        starts: &[f64],
        cache: &RefCell<FaceFields>,
    ) -> bool {
        let mesh = self.mesh();
        let field = &self.field;
        let mut around = vec![f];
        for e in mesh.face_edges(f) {
            around.extend(mesh.edge_faces(e).iter().filter(|&&g| g != f));
        }
        let vertices = mesh.face_vertices(f).map(|v| field.distance[v as usize]);
        let hi = match flat_frame(self.metric, f, &mesh.frame(f)) {
            Some(frame) if !field.horizon.is_bounded() => {
                let nearest = vertices.iter().copied().fold(f64::INFINITY, f64::min);
                let farthest = vertices.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                (nearest + frame.diameter()).max(farthest)
            }
            _ => f64::INFINITY,
        };
        // Whether a level lies in `[lo, hi)`: the least level at or above `lo`, if
        // below `hi`.
        let holds = |lo: f64| {
            let first = sorted.partition_point(|&level| level < lo);
            sorted.get(first).is_some_and(|&level| level < hi)
        };
        // The nodes' values (and the starts) bound the Steiner-graph engines'
        // candidates from below. A wave gives a point `x` its value at its node `n`
        // less at most the distance from `n` to `x` (its lines are straight), so for
        // the wavefront engine the bound is lowered by twice the largest flattened
        // face diameter around (`x` in the face, `n` on it or on a face across).
        let mut lo = vertices.iter().copied().fold(f64::INFINITY, f64::min);
        let mut reach = 0.0f64;
        for &g in &around {
            lo = lo.min(starts[g as usize]);
            for (node, _) in field.layout.face_nodes(mesh, g) {
                lo = lo.min(field.distance[node as usize]);
            }
            if self.has_waves() {
                let diameter = flat_frame(self.metric, g, &mesh.frame(g))
                    .map_or(f64::INFINITY, |frame| frame.diameter());
                reach = reach.max(2.0 * diameter);
            }
        }
        if !holds(lo - reach) {
            return false;
        }
        if !self.has_waves() {
            return true;
        }
        // The wavefront engine's candidates, built (the grid would build them anyway):
        // none is below its floor, on the face and on the faces across its edges.
        let mut lo = vertices.iter().copied().fold(f64::INFINITY, f64::min);
        let mut cache = cache.borrow_mut();
        for &g in &around {
            lo = lo.min(starts[g as usize]);
            let least = cache.get(self, g).candidates.first();
            lo = lo.min(least.map_or(f64::INFINITY, |c| c.floor));
        }
        holds(lo)
    }
}

fn check_options(levels: &[f64], options: &IsolineOptions) -> Result<(), Error> {
    if levels.len() > MAX_LEVELS {
        check_level_count(levels.len())?;
    }
    if let Some((index, &value)) = levels.iter().enumerate().find(|(_, l)| !l.is_finite()) {
        return Err(Error::InvalidValue {
            which: ValueRole::IsolineLevel { index },
            value,
        });
    }
    if options.subdivisions == 0 || options.subdivisions > MAX_SUBDIVISIONS {
        return Err(Error::InvalidIsolineOption {
            option: "subdivisions",
            value: options.subdivisions as f64,
            expected: "between 1 and 1024",
        });
    }
    if !(options.tolerance > 0.0 && options.tolerance < 1.0) {
        return Err(Error::InvalidIsolineOption {
            option: "tolerance",
            value: options.tolerance,
            expected: "above 0 and below 1",
        });
    }
    if options.max_splits > MAX_SPLITS {
        return Err(Error::InvalidIsolineOption {
            option: "max_splits",
            value: options.max_splits as f64,
            expected: "at most 20",
        });
    }
    Ok(())
}

/// A face's grid is `(n + 1)(n + 2) / 2` points, each evaluated: beyond this a run
/// would take hours on any mesh, so it is refused as a mistake.
const MAX_SUBDIVISIONS: u32 = 1024;
/// A segment splits into at most `2^MAX_SPLITS` pieces.
const MAX_SPLITS: u32 = 20;

#[cfg(test)]
mod tests {
    use super::IsolineOptions;
    use crate::mesh::TriMesh;
    use crate::{Density, Euclidean, Method, Options, Solver, Source, Sources, Stop, Tensor};
    use geotracks_metrics::{FacePoint, Metric, SlidingCost};

    /// Walls: `inner` with some faces that no path crosses (an infinite cost for any
    /// segment of positive length on them), the way a terrain cost blocks its steepest
    /// faces.
    struct Walled<M> {
        inner: M,
        blocked: Vec<bool>,
    }

    impl<M: Metric> Metric for Walled<M> {
        fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
            if !self.blocked[face as usize] {
                self.inner.cost(face, a, b)
            } else if a.uv == b.uv {
                0.0
            } else {
                f64::INFINITY
            }
        }
        fn is_symmetric(&self) -> bool {
            self.inner.is_symmetric()
        }
        // Infinite costs keep the triangle inequality: the inner metric's pruning
        // stays valid.
        fn is_face_norm(&self) -> bool {
            self.inner.is_face_norm()
        }
        fn prunes_on(&self, face: u32) -> bool {
            self.inner.prunes_on(face)
        }
        fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
            self.inner.triangle_slack(face, diameter)
        }
        fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
            (!self.blocked[face as usize])
                .then(|| self.inner.face_gram(face))
                .flatten()
        }
        fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
            self.inner.wire_cost(a, b, length)
        }
        fn min_cost_per_length(&self) -> f64 {
            self.inner.min_cost_per_length()
        }
        fn name(&self) -> &str {
            "walled"
        }
        fn sliding_cost(
            &self,
            face: u32,
            a: &FacePoint,
            da: &FacePoint,
            b: &FacePoint,
            db: &FacePoint,
        ) -> Option<SlidingCost> {
            (!self.blocked[face as usize])
                .then(|| self.inner.sliding_cost(face, a, da, b, db))
                .flatten()
        }
    }

    /// A small deterministic generator (xorshift).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// An `n` × `n` grid, jittered in the plane and lifted by `lift` (0: flat), with
    /// random diagonals.
    fn mesh(rng: &mut Rng, n: usize, lift: f64) -> TriMesh {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let jitter = |rng: &mut Rng| 0.3 * (rng.next() - 0.5);
                let (x, y) = (i as f64 + jitter(rng), j as f64 + jitter(rng));
                positions.push([x, y, lift * (rng.next() - 0.5)]);
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if rng.next() < 0.5 {
                    faces.extend([[a, b, c], [a, c, d]]);
                } else {
                    faces.extend([[a, b, d], [b, c, d]]);
                }
            }
        }
        TriMesh::new(positions, faces).unwrap()
    }

    /// Skipping the faces whose bounds hold no level draws exactly what evaluating
    /// every face draws: same lines, same points, bit for bit, for every engine, flat
    /// and non-flat metrics, walls, several sources (point sources, start values), and
    /// stopped runs.
    fn same_with_and_without_the_gate<M: Metric>(
        mesh: &TriMesh,
        metric: M,
        method: Method,
        rng: &mut Rng,
    ) -> usize {
        let options = Options::DEFAULT.with_method(method).with_k(3.0);
        let solver = Solver::new(mesh, metric, &options).unwrap();
        let n = mesh.vertex_count() as u32;
        let mut sources = vec![Source::new((rng.next() * n as f64) as u32)];
        if rng.next() < 0.5 {
            let f = (rng.next() * mesh.face_count() as f64) as u32;
            let point: crate::SurfacePoint = format!("f:{f}:0.2,0.3,0.5").parse().unwrap();
            sources.push(Source::new(point).with_start(rng.next()));
        }
        let mut drawn = 0;
        for stop in [Stop::NONE, Stop::NONE.with_max_distance(3.0)] {
            let field = solver.field(Sources::from(&sources).until(&stop)).unwrap();
            let query = field.query();
            let max = query.max_reached_distance();
            let mut levels = super::spread_levels(max, 7);
            levels.push(0.0);
            levels.push(max * 0.999);
            let options = IsolineOptions::DEFAULT;
            let gated = query.isolines_gated(&levels, &options, true);
            let every = query.isolines_gated(&levels, &options, false);
            // (Compared whole; reported by the first line that differs.)
            if gated != every {
                let first = gated.iter().zip(&every).position(|(a, b)| a != b);
                panic!(
                    "{method}, {}: {} lines gated against {} ungated, first difference at line {first:?}",
                    solver.metric().name(),
                    gated.len(),
                    every.len()
                );
            }
            drawn += every.len();
        }
        drawn
    }

    #[test]
    fn the_gate_skips_only_faces_that_draw_nothing() {
        let mut rng = Rng(0x9e3779b97f4a7c15);
        let mut drawn = 0;
        for case in 0..4 {
            let lift = [0.0, 0.5, 2.0][case % 3];
            let mesh = mesh(&mut rng, 6, lift);
            let rho: Vec<f64> = (0..mesh.vertex_count()).map(|_| 0.5 + rng.next()).collect();
            let tensors: Vec<[f64; 6]> = (0..mesh.face_count())
                .map(|_| [1.0 + 3.0 * rng.next(), 0.3, 0.0, 1.0 + rng.next(), 0.0, 1.0])
                .collect();
            let walls: Vec<bool> = (0..mesh.face_count()).map(|_| rng.next() < 0.15).collect();
            for method in [
                Method::Wave,
                Method::Tracks,
                Method::Graph,
                Method::Dijkstra,
            ] {
                drawn += same_with_and_without_the_gate(&mesh, Euclidean, method, &mut rng);
                let density = Density::new(&mesh, rho.clone()).unwrap();
                drawn += same_with_and_without_the_gate(&mesh, density, method, &mut rng);
                let tensor = Tensor::from_world(&mesh, &tensors).unwrap();
                drawn += same_with_and_without_the_gate(&mesh, tensor, method, &mut rng);
                let walled = Walled {
                    inner: Euclidean,
                    blocked: walls.clone(),
                };
                drawn += same_with_and_without_the_gate(&mesh, walled, method, &mut rng);
            }
        }
        assert!(drawn > 300, "{drawn} lines: the comparison compared little");
    }
}
