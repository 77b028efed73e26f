//! Where a skeleton's points sit: smoothed along its polylines and kept on the surface,
//! and the medial radius there.

use super::{Skeleton, SkeletonPoint};
use crate::mesh::TriMesh;
use crate::surface::SurfacePoint;
use glam::DVec3;

impl Skeleton {
    /// Rounds of smoothing [`medial_axis_skeleton`](super::medial_axis_skeleton) gives.
    pub const SMOOTHING: usize = 10;

    /// The skeleton with its polylines smoothed on the surface: each point of degree 2
    /// moves towards its neighbours' mean and back (Taubin's λ|μ smoothing, which does
    /// not shrink the curve), then onto the nearest point of the faces near where it
    /// was, `rounds` times. Tips, junctions and points on line elements or at their ends
    /// (with an edge along one) stay. Thinning leaves points on vertices, so a
    /// curve zig-zags along edges by up to a face; this takes the zig-zag out while
    /// every point stays on the surface.
    pub fn smoothed(&self, mesh: &TriMesh, rounds: usize) -> Skeleton {
        const LAMBDA: f64 = 0.5;
        const MU: f64 = -0.53;
        let neighbours = self.adjacency();
        let held = self.held_by_curves(mesh);
        let home: Vec<Option<Vec<u32>>> = self
            .points
            .iter()
            .zip(&neighbours)
            .zip(held)
            .map(|((p, around), held)| {
                let faces = nearby_faces(mesh, p.on);
                (around.len() == 2 && !held && !faces.is_empty()).then_some(faces)
            })
            .collect();
        let mut at: Vec<DVec3> = self.points.iter().map(|p| p.position.into()).collect();
        let mut on: Vec<SurfacePoint> = self.points.iter().map(|p| p.on).collect();
        for _ in 0..rounds {
            for step in [LAMBDA, MU] {
                let before = at.clone();
                for (i, around) in neighbours.iter().enumerate() {
                    if home[i].is_some() {
                        let mean = around.iter().map(|&j| before[j as usize]).sum::<DVec3>()
                            / around.len() as f64;
                        at[i] = before[i] + step * (mean - before[i]);
                    }
                }
            }
            for (i, faces) in home.iter().enumerate() {
                let nearest = faces.as_ref().and_then(|faces| {
                    SurfacePoint::nearest_among(mesh, faces.iter().copied(), at[i])
                });
                if let Some((point, position)) = nearest {
                    on[i] = point;
                    at[i] = position;
                }
            }
        }
        let points = self
            .points
            .iter()
            .enumerate()
            .map(|(i, p)| SkeletonPoint {
                position: at[i].to_array(),
                on: on[i],
                ..*p
            })
            .collect();
        self.with_points(points)
    }

    /// Per point, whether it has an edge along a line element of `mesh` (see
    /// [`share_a_face`]): such a point lies on a curve of the axis or where one meets a
    /// sheet, and smoothing it along the sheets would take the skeleton off the curve.
    pub(super) fn held_by_curves(&self, mesh: &TriMesh) -> Vec<bool> {
        let mut held = vec![false; self.points.len()];
        for &[a, b] in &self.edges {
            if !share_a_face(mesh, self.points[a as usize].on, self.points[b as usize].on) {
                held[a as usize] = true;
                held[b as usize] = true;
            }
        }
        held
    }

    /// The same graph with new points (one per point).
    pub(super) fn with_points(&self, points: Vec<SkeletonPoint>) -> Skeleton {
        debug_assert_eq!(points.len(), self.points.len());
        Skeleton {
            points,
            edges: self.edges.clone(),
            ..*self
        }
    }

    /// The skeleton with each point's medial radius, interpolated from `radii` (one per
    /// vertex) where it lies on `mesh` (without a mesh, only points on vertices get one).
    ///
    /// # Panics
    /// If a point lies on a vertex that `radii` has no entry for.
    pub fn with_radii(&self, mesh: Option<&TriMesh>, radii: &[f64]) -> Skeleton {
        let radius_at = |on: SurfacePoint| -> Option<f64> {
            match (on, mesh) {
                (SurfacePoint::Vertex(v), _) => Some(radii[v as usize]),
                (SurfacePoint::Edge { edge, t }, Some(mesh)) => {
                    let [a, b] = mesh.edge_vertices(edge);
                    Some((1.0 - t) * radii[a as usize] + t * radii[b as usize])
                }
                (SurfacePoint::Face { face, bary }, Some(mesh)) => Some(
                    mesh.face_vertices(face)
                        .iter()
                        .zip(bary)
                        .map(|(&v, w)| w * radii[v as usize])
                        .sum(),
                ),
                _ => None,
            }
        };
        let points = self
            .points
            .iter()
            .map(|p| SkeletonPoint {
                radius: radius_at(p.on),
                ..*p
            })
            .collect();
        self.with_points(points)
    }
}

/// A vertex of the simplex `on` lies in.
pub(super) fn vertex_of(mesh: &TriMesh, on: SurfacePoint) -> u32 {
    match on {
        SurfacePoint::Vertex(v) => v,
        SurfacePoint::Edge { edge, .. } => mesh.edge_vertices(edge)[0],
        SurfacePoint::Face { face, .. } => mesh.face_vertices(face)[0],
    }
}

/// The faces within two rings of the vertex nearest `on`.
pub(super) fn nearby_faces(mesh: &TriMesh, on: SurfacePoint) -> Vec<u32> {
    let centre = vertex_of(mesh, on);
    let mut faces: Vec<u32> = Vec::new();
    for &f in mesh.vertex_faces(centre) {
        for v in mesh.face_vertices(f) {
            faces.extend_from_slice(mesh.vertex_faces(v));
        }
    }
    faces.sort_unstable();
    faces.dedup();
    faces
}

/// Whether the skeleton's segment between `a` and `b` lies on the sheets: not along a
/// line element, which joins two vertices that share no face (thinning leaves points
/// on vertices; a point that placing or smoothing put inside a face or an edge is on
/// the sheets).
pub(super) fn share_a_face(mesh: &TriMesh, a: SurfacePoint, b: SurfacePoint) -> bool {
    match (a, b) {
        (SurfacePoint::Vertex(u), SurfacePoint::Vertex(v)) => {
            let around = mesh.vertex_faces(v);
            mesh.vertex_faces(u).iter().any(|f| around.contains(f))
        }
        _ => true,
    }
}

/// How much polylines turn per unit of their length: the sum of the angles between
/// consecutive segments over their total length (radians per unit; times a shape's
/// size, scale-free). A smooth curve gives the same however finely it is sampled;
/// zig-zags add to it. Segments of no length are skipped.
///
/// ```
/// use geotracks::skeleton::turning_per_length;
/// // A right angle over a length of 2.
/// let turn = turning_per_length(&[vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]]);
/// assert!((turn - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
/// ```
pub fn turning_per_length(lines: &[Vec<[f64; 3]>]) -> f64 {
    let (mut angle, mut length) = (0.0, 0.0);
    for line in lines {
        let points: Vec<DVec3> = line.iter().map(|&p| DVec3::from(p)).collect();
        length += points.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>();
        for w in points.windows(3) {
            let (u, v) = (w[1] - w[0], w[2] - w[1]);
            if u.length() > 0.0 && v.length() > 0.0 {
                angle += u.angle_between(v);
            }
        }
    }
    angle / length.max(f64::MIN_POSITIVE)
}

impl Skeleton {
    /// The positions of the points of `line` (a polyline of [`Skeleton::polylines`]).
    pub(super) fn line_positions(&self, line: &[u32]) -> Vec<DVec3> {
        line.iter()
            .map(|&i| self.points[i as usize].position.into())
            .collect()
    }
}

/// The length along the polyline `at` to each of its points (0 at the first).
pub(super) fn lengths_along(at: &[DVec3]) -> Vec<f64> {
    let mut along = Vec::with_capacity(at.len());
    along.push(0.0);
    for w in at.windows(2) {
        along.push(along[along.len() - 1] + w[0].distance(w[1]));
    }
    along
}

/// The fewest edges a polyline of `points` points keeps when it is rebuilt (resampled
/// or simplified): as many as it had, up to 3, so that a loop stays a loop and two
/// branches between the same two points stay apart.
pub(super) fn least_edges(points: usize) -> usize {
    points.saturating_sub(1).min(3)
}

impl SkeletonPoint {
    /// A new point at `position` (`on` the surface there) between the points `a` and `b`
    /// of a polyline: it takes the lower significance and tubularity of the two, so that
    /// a threshold that keeps it keeps both.
    pub(super) fn between(
        a: &SkeletonPoint,
        b: &SkeletonPoint,
        position: DVec3,
        on: SurfacePoint,
        radius: Option<f64>,
    ) -> SkeletonPoint {
        SkeletonPoint {
            position: position.to_array(),
            on,
            significance: a.significance.min(b.significance),
            tubularity: a.tubularity.min(b.tubularity),
            radius,
        }
    }
}

/// A skeleton rebuilt polyline by polyline (see [`Skeleton::polylines`]): each point of
/// the old one kept at most once (polylines share their tips and junctions), new points
/// added between them, and each polyline's edges chained as it is walked.
pub(super) struct Rebuild<'s> {
    from: &'s Skeleton,
    points: Vec<SkeletonPoint>,
    /// Per old point, its index in `points` once kept.
    new_id: Vec<u32>,
    edges: Vec<[u32; 2]>,
    /// Where the polyline being walked has come to.
    last: u32,
}

impl<'s> Rebuild<'s> {
    pub(super) fn new(from: &'s Skeleton) -> Rebuild<'s> {
        Rebuild {
            from,
            points: Vec::new(),
            new_id: vec![u32::MAX; from.points.len()],
            edges: Vec::new(),
            last: u32::MAX,
        }
    }

    fn keep(&mut self, i: u32) -> u32 {
        if self.new_id[i as usize] == u32::MAX {
            self.new_id[i as usize] = self.points.len() as u32;
            self.points.push(self.from.points[i as usize]);
        }
        self.new_id[i as usize]
    }

    /// Starts a polyline at the old point `i`.
    pub(super) fn start(&mut self, i: u32) {
        self.last = self.keep(i);
    }

    /// Starts a polyline at a new point.
    pub(super) fn start_new(&mut self, point: SkeletonPoint) {
        self.last = self.points.len() as u32;
        self.points.push(point);
    }

    /// Continues the polyline to the old point `i`.
    pub(super) fn then_old(&mut self, i: u32) {
        let id = self.keep(i);
        self.edges.push([self.last, id]);
        self.last = id;
    }

    /// Continues the polyline through the old `points`, in order.
    pub(super) fn then_olds(&mut self, points: &[u32]) {
        for &i in points {
            self.then_old(i);
        }
    }

    /// Continues the polyline to a new point.
    pub(super) fn then_new(&mut self, point: SkeletonPoint) {
        let id = self.points.len() as u32;
        self.points.push(point);
        self.edges.push([self.last, id]);
        self.last = id;
    }

    /// The skeleton rebuilt (its counts of punctured faces and cycles as the old one's).
    pub(super) fn finish(self) -> Skeleton {
        Skeleton {
            points: self.points,
            edges: self.edges,
            ..*self.from
        }
    }
}

/// For tests: a skeleton of straight edges along `paths` of `(position, radius)`; a
/// position given twice (bit for bit) is one point, so paths join where they meet.
#[cfg(test)]
pub(super) fn graph_of_paths<P: AsRef<[([f64; 3], f64)]>>(paths: &[P]) -> Skeleton {
    let mut points: Vec<SkeletonPoint> = Vec::new();
    let mut edges = Vec::new();
    for path in paths {
        let ids: Vec<u32> = path
            .as_ref()
            .iter()
            .map(
                |&(position, radius)| match points.iter().position(|q| q.position == position) {
                    Some(i) => i as u32,
                    None => {
                        points.push(SkeletonPoint {
                            position,
                            on: SurfacePoint::Vertex(0),
                            significance: 1.0,
                            tubularity: 1.0,
                            radius: Some(radius),
                        });
                        points.len() as u32 - 1
                    }
                },
            )
            .collect();
        edges.extend(ids.windows(2).map(|w| [w[0], w[1]]));
    }
    Skeleton {
        points,
        edges,
        ..Skeleton::default()
    }
}
