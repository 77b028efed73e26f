//! How a [`Field`](crate::Field) answers its queries (the distance at any surface point,
//! nearest sources, isolines, regions) and geodesic paths: traced back from any surface point to its nearest source
//! through the parents the propagation recorded, then straightened.
//!
//! A traced path is a polyline whose every segment lies inside one face (from a node to
//! its parent, or along an edge), so its length in the metric is the distance the
//! Steiner graph gives the point. [`straighten`] then shortens it locally: it slides
//! each edge crossing along its edge, and lets the path leave a vertex where it can cut
//! the corner, never making it longer.

mod face_field;
mod isolines;
mod query;
mod regions;
mod straighten;
mod wave;
mod windows;

use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::surface::SurfacePoint;
use crate::Error;
use geotracks_metrics::Metric;
use glam::DVec3;

pub use face_field::ValueSource;
pub use isolines::{check_level_count, spread_levels, Isoline, IsolineOptions, MAX_LEVELS};
use query::Origin;
pub(crate) use query::Query;
pub use regions::{Gradient, Region, DEFAULT_REGION_SUBDIVISIONS};
pub use straighten::straighten;

/// A path on the surface, from a query point to a source.
///
/// `points[0]` is the query point and the last point the source's; segment `i` joins
/// `points[i]` and `points[i + 1]` inside face `faces[i]` (a segment along an edge lies
/// in each face of the edge; it names the one where it costs least).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct GeodesicPath {
    /// The polyline's points, each a vertex, an edge point or a face point.
    pub points: Vec<SurfacePoint>,
    /// The face each segment lies in (one fewer than the points); [`NONE`] for a
    /// segment along a wire, between the wire's two vertices
    /// ([`Topology::vertex_wires`]).
    pub faces: Vec<u32>,
    /// The index of the source the path ends at, in the run's sources.
    pub source: u32,
    /// The metric length of the path.
    pub length: f64,
    /// The metric length as traced, before any straightening (the Steiner graph's
    /// distance at the query point).
    pub traced_length: f64,
}

impl GeodesicPath {
    /// World positions of the points.
    pub fn positions<T: Topology>(&self, mesh: &T) -> Vec<DVec3> {
        self.points.iter().map(|p| p.position(mesh)).collect()
    }

    /// The metric cost of each segment, travelled from the source: segment `i` from
    /// `points[i + 1]` to `points[i]` (the direction matters for a directed metric).
    pub fn segment_costs<M: Metric, T: Topology>(&self, mesh: &T, metric: &M) -> Vec<f64> {
        (0..self.faces.len())
            .map(|i| {
                segment_cost(
                    mesh,
                    metric,
                    self.faces[i],
                    self.points[i + 1],
                    self.points[i],
                )
            })
            .collect()
    }

    /// The metric length: the sum of [`GeodesicPath::segment_costs`].
    pub fn metric_length<M: Metric, T: Topology>(&self, mesh: &T, metric: &M) -> f64 {
        // Folded from +0: an empty sum would be −0.
        self.segment_costs(mesh, metric)
            .iter()
            .fold(0.0, |sum, c| sum + c)
    }
}

/// The cost of the straight segment `a`–`b` inside face `f`, whose closure holds both;
/// for `f` = [`NONE`], of the wire between vertices `a` and `b` (`inf` if they are not
/// two vertices: no such segment).
pub(crate) fn segment_cost<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    f: u32,
    a: SurfacePoint,
    b: SurfacePoint,
) -> f64 {
    if f == NONE {
        let (SurfacePoint::Vertex(u), SurfacePoint::Vertex(v)) = (a, b) else {
            return f64::INFINITY;
        };
        return metric.wire_cost(u, v, mesh.position(u).distance(mesh.position(v)));
    }
    let pa = a.in_face(mesh, f).expect("segment end on its face");
    let pb = b.in_face(mesh, f).expect("segment end on its face");
    metric.cost(f, &pa, &pb)
}

impl<M: Metric, T: Topology> Query<'_, M, T> {
    /// The path from `point` to its nearest source, as the propagation found it: from
    /// the point to the best node of its faces (or straight to a source in one of
    /// them), then from parent to parent. Its length is the distance at `point`.
    ///
    /// # Complexity
    /// O(k) metric evaluations per face around the point, then one step per node on
    /// the path.
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] for a point not on the mesh, [`Error::Unreachable`] when
    /// no source reaches the point.
    pub fn trace(&self, point: SurfacePoint) -> Result<GeodesicPath, Error> {
        let (mesh, metric, field) = (self.mesh, self.metric, &self.field);
        let (_, origin) = self.origin(point)?;
        let Some(origin) = origin else {
            return Err(Error::Unreachable { point });
        };
        let mut points = vec![point.validated(mesh).expect("checked by origin")];
        let mut faces = Vec::new();
        let mut origin = origin;
        let node = loop {
            match origin {
                Origin::Node(v) => break v,
                Origin::NodeInFace(n, f) => {
                    points.push(field.layout.surface_point(n));
                    faces.push(f);
                    break n;
                }
                Origin::SourceInFace(s, f) => {
                    points.push(field.sources[s as usize].point);
                    faces.push(f);
                    return Ok(finish(mesh, metric, points, faces, s));
                }
                Origin::WindowInFace(id, f) => {
                    let source = self
                        .trace_window(f, id, &mut points, &mut faces)
                        .ok_or(Error::ParentCycle { point })?;
                    return Ok(finish(mesh, metric, points, faces, source));
                }
                Origin::WaveInFace(q, f) => {
                    let x = points
                        .last()
                        .and_then(|p| p.in_face(mesh, f))
                        .expect("the point lies on its face");
                    let source = self
                        .trace_wave(&x, f, q, &mut points, &mut faces)
                        .ok_or(Error::ParentCycle { point })?;
                    return Ok(finish(mesh, metric, points, faces, source));
                }
                Origin::Across {
                    edge,
                    t,
                    face,
                    source,
                    then,
                } => {
                    // Through the shared edge, then as the neighbour's candidate.
                    points.push(SurfacePoint::Edge { edge, t });
                    faces.push(face);
                    origin = Origin::from_source(source, then);
                }
            }
        };
        if self.has_windows() {
            // Along the windows' straight lines, back to where they started.
            let source = self
                .trace_from_vertex(node, &mut points, &mut faces)
                .ok_or(Error::ParentCycle { point })?;
            return Ok(finish(mesh, metric, points, faces, source));
        }
        if self.has_waves() {
            // Along the waves' straight lines, not from node to node.
            let source = self
                .step_from(node)
                .and_then(|step| self.follow(step, &mut points, &mut faces))
                .ok_or(Error::ParentCycle { point })?;
            return Ok(finish(mesh, metric, points, faces, source));
        }
        let source = self
            .follow_parents(node, &mut points, &mut faces)
            .ok_or(Error::ParentCycle { point })?;
        Ok(finish(mesh, metric, points, faces, source))
    }

    /// Follows parents from `node` (whose point ends `points`) to the source that
    /// reached it, adding each parent's point and the face of each segment; returns
    /// the source (`None` on a cycle).
    pub(crate) fn follow_parents(
        &self,
        mut node: u32,
        points: &mut Vec<SurfacePoint>,
        faces: &mut Vec<u32>,
    ) -> Option<u32> {
        let field = &self.field;
        // Parents have lower values, so the walk ends at a root; the cap guards against
        // a metric that returns zero costs between distinct points.
        for _ in 0..field.distance.len() {
            let (p, pf) = (
                field.parent[node as usize],
                field.parent_face[node as usize],
            );
            if p == NONE {
                let s = field
                    .root_source(node)
                    .expect("a reached node without a parent was reached by a source");
                if pf != NONE {
                    points.push(field.sources[s as usize].point);
                    faces.push(pf);
                }
                return Some(s);
            }
            let (from, to) = (
                field.layout.surface_point(node),
                field.layout.surface_point(p),
            );
            points.push(to);
            faces.push(if pf != NONE {
                pf
            } else {
                self.cheapest_face(from, to)
            });
            node = p;
        }
        None
    }

    /// The traced path from `point`, straightened ([`straighten`]): the path users
    /// want, at most as long as the traced one.
    ///
    /// # Complexity
    /// As [`Field::trace`](crate::Field::trace), then a few rounds of Newton's method on the path's edge
    /// crossings (tridiagonal: linear in the path's length per step).
    ///
    /// # Errors
    /// As [`Field::trace`](crate::Field::trace).
    pub fn path(&self, point: SurfacePoint) -> Result<GeodesicPath, Error> {
        let mut path = self.trace(point)?;
        if !self.has_windows() {
            // (An exact field's paths are straight already: geodesics.)
            straighten(&mut path, self.mesh, self.metric);
        }
        Ok(path)
    }

    /// The face around the edge that holds `a` and `b` (two points of one edge, such as
    /// a node and its parent along it) in which the segment from `b` to `a` (as a path
    /// travels it, from the source) costs least; [`NONE`] for two vertices that share
    /// no face edge: the engines join such vertices only along a wire. A segment with a
    /// point inside a face (a source there) lies in that face.
    pub(super) fn cheapest_face(&self, a: SurfacePoint, b: SurfacePoint) -> u32 {
        let (mesh, metric) = (self.mesh, self.metric);
        let edge = match (a, b) {
            (SurfacePoint::Face { face, .. }, _) | (_, SurfacePoint::Face { face, .. }) => {
                return face
            }
            (SurfacePoint::Edge { edge, .. }, _) | (_, SurfacePoint::Edge { edge, .. }) => edge,
            (SurfacePoint::Vertex(u), SurfacePoint::Vertex(v)) => match mesh
                .vertex_edges(u)
                .iter()
                .copied()
                .find(|&e| mesh.edge_vertices(e).contains(&v))
            {
                Some(e) => e,
                None => return NONE,
            },
        };
        let faces = mesh.edge_faces(edge);
        faces
            .iter()
            .map(|&f| (segment_cost(mesh, metric, f, b, a), f))
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map_or(faces[0], |(_, f)| f)
    }
}

pub(crate) fn finish<M: Metric, T: Topology>(
    mesh: &T,
    metric: &M,
    points: Vec<SurfacePoint>,
    faces: Vec<u32>,
    source: u32,
) -> GeodesicPath {
    let mut path = GeodesicPath {
        points,
        faces,
        source,
        length: 0.0,
        traced_length: 0.0,
    };
    path.length = path.metric_length(mesh, metric);
    path.traced_length = path.length;
    path
}

#[cfg(test)]
mod tests {
    use crate::mesh::{TriMesh, NONE};
    use crate::{Euclidean, Options, Solver, SurfacePoint};

    /// Two points of one edge go in the cheaper face around it; a point inside a face
    /// keeps its segment there; two vertices without a shared edge have none (a wire).
    #[test]
    fn the_face_of_a_segment_is_one_that_holds_both_ends() {
        // A unit square split along 0–2, and a vertex (4) off it.
        let mesh = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [3.0, 3.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3], [2, 4, 3]],
        )
        .unwrap();
        let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
        let field = solver.field(&[0]).unwrap();
        let query = field.query();
        let inside = SurfacePoint::Face {
            face: 1,
            bary: [0.2, 0.3, 0.5],
        };
        assert_eq!(query.cheapest_face(inside, SurfacePoint::Vertex(3)), 1);
        assert_eq!(query.cheapest_face(SurfacePoint::Vertex(0), inside), 1);
        let f = query.cheapest_face(SurfacePoint::Vertex(0), SurfacePoint::Vertex(2));
        assert!(f == 0 || f == 1, "{f}");
        assert_eq!(
            query.cheapest_face(SurfacePoint::Vertex(1), SurfacePoint::Vertex(3)),
            NONE
        );
    }
}
