//! Points anywhere on a mesh's surface, and sources made of them.
//!
//! A [`SurfacePoint`] is a vertex, a point on an edge (a parameter from the edge's
//! lower-id vertex) or a point in a face (barycentric coordinates in the face's vertex
//! order). It is what sources, targets, distance queries and paths are made of.
//!
//! ```
//! use geotracks::{mesh::TriMesh, SurfacePoint};
//! let mesh = TriMesh::new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     vec![[0, 1, 2], [0, 2, 3]],
//! )?;
//! let p: SurfacePoint = "f:0:0.5,0.25,0.25".parse()?;
//! let p = p.validated(&mesh)?;
//! assert_eq!(p.position(&mesh).to_array(), [0.5, 0.25, 0.0]);
//! // The nearest point of the surface to a point above it.
//! let q = SurfacePoint::nearest(&mesh, [0.5, 0.25, 3.0]).expect("the mesh has faces");
//! assert!((q.position(&mesh) - p.position(&mesh)).length() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::mesh::Topology;
use geotracks_metrics::FacePoint;
use geotracks_metrics::Num;
use glam::DVec3;
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// How far barycentric coordinates may stray (below 0, or their sum from 1) and an edge
/// parameter outside `[0, 1]` before a point is rejected; within it they are clamped.
pub const TOLERANCE: f64 = 1e-6;

/// A point on the surface of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfacePoint {
    /// A vertex.
    Vertex(u32),
    /// The point at parameter `t` ∈ [0, 1] along edge `edge`, from its lower-id vertex.
    Edge {
        /// The edge's id in the mesh.
        edge: u32,
        /// 0 at the lower-id vertex, 1 at the other.
        t: f64,
    },
    /// A point of face `face` with barycentric coordinates `bary` (in the face's vertex
    /// order; non-negative, summing to 1).
    Face {
        /// The face's id in the mesh.
        face: u32,
        /// Barycentric coordinates.
        bary: [f64; 3],
    },
}

/// Why a [`SurfacePoint`] is not a point of a mesh, or could not be parsed.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum PointError {
    /// The vertex does not exist.
    #[error("vertex {vertex} does not exist: the mesh has {count} vertices")]
    NoSuchVertex {
        /// The vertex asked for.
        vertex: u32,
        /// Vertices in the mesh.
        count: usize,
    },
    /// The edge does not exist.
    #[error("edge {edge} does not exist: the mesh has {count} edges")]
    NoSuchEdge {
        /// The edge asked for.
        edge: u32,
        /// Edges in the mesh.
        count: usize,
    },
    /// The face does not exist.
    #[error("face {face} does not exist: the mesh has {count} faces")]
    NoSuchFace {
        /// The face asked for.
        face: u32,
        /// Faces in the mesh.
        count: usize,
    },
    /// The edge parameter is outside `[0, 1]` (or not finite).
    #[error("edge parameter t = {} is outside [0, 1]", Num(*t))]
    ParameterOutOfRange {
        /// The parameter given.
        t: f64,
    },
    /// The barycentric coordinates do not sum to 1 (or are not finite).
    #[error("barycentric coordinates {bary:?} sum to {}, not 1 (tolerance {TOLERANCE:e})", Num(*sum))]
    BarycentricSum {
        /// The coordinates given.
        bary: [f64; 3],
        /// Their sum.
        sum: f64,
    },
    /// A barycentric coordinate is negative: the point is outside the face.
    #[error(
        "barycentric coordinates {bary:?} have a negative entry: the point is outside the face"
    )]
    NegativeBarycentric {
        /// The coordinates given.
        bary: [f64; 3],
    },
    /// The text is not a surface point.
    #[error(
        "cannot read '{text}' as a surface point: {reason} (expected V, e:E:t or f:F:b0,b1,b2)"
    )]
    Parse {
        /// The text given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
}

impl SurfacePoint {
    /// Checks the point against `mesh` and returns it in canonical form: parameters and
    /// barycentrics within [`TOLERANCE`] of valid are clamped (and renormalised); a face
    /// point with a zero coordinate becomes the edge or vertex point it is, and an edge
    /// point at `t = 0` or `1` the vertex, so that it names every face it lies on.
    ///
    /// # Errors
    /// The [`PointError`] that says what is wrong.
    pub fn validated<T: Topology>(self, mesh: &T) -> Result<SurfacePoint, PointError> {
        match self {
            SurfacePoint::Vertex(vertex) => {
                if vertex as usize >= mesh.vertex_count() {
                    return Err(PointError::NoSuchVertex {
                        vertex,
                        count: mesh.vertex_count(),
                    });
                }
                Ok(self)
            }
            SurfacePoint::Edge { edge, t } => {
                if edge as usize >= mesh.edge_count() {
                    return Err(PointError::NoSuchEdge {
                        edge,
                        count: mesh.edge_count(),
                    });
                }
                if !(-TOLERANCE..=1.0 + TOLERANCE).contains(&t) {
                    return Err(PointError::ParameterOutOfRange { t });
                }
                let [lo, hi] = mesh.edge_vertices(edge);
                Ok(match t {
                    t if t <= 0.0 => SurfacePoint::Vertex(lo),
                    t if t >= 1.0 => SurfacePoint::Vertex(hi),
                    t => SurfacePoint::Edge { edge, t },
                })
            }
            SurfacePoint::Face { face, bary } => {
                if face as usize >= mesh.face_count() {
                    return Err(PointError::NoSuchFace {
                        face,
                        count: mesh.face_count(),
                    });
                }
                let sum: f64 = bary.iter().sum();
                if (sum - 1.0).abs().is_nan() || (sum - 1.0).abs() > TOLERANCE {
                    return Err(PointError::BarycentricSum { bary, sum });
                }
                if bary.iter().any(|&b| b < -TOLERANCE) {
                    return Err(PointError::NegativeBarycentric { bary });
                }
                let clamped = bary.map(|b| b.max(0.0));
                let total: f64 = clamped.iter().sum();
                Ok(Self::in_face_closure(
                    mesh,
                    face,
                    clamped.map(|b| b / total),
                ))
            }
        }
    }

    /// The canonical point with barycentrics `bary` (valid) in face `face`.
    fn in_face_closure<T: Topology>(mesh: &T, face: u32, bary: [f64; 3]) -> SurfacePoint {
        let corners = mesh.face_vertices(face);
        let zeros = bary.iter().filter(|&&b| b == 0.0).count();
        match zeros {
            0 => SurfacePoint::Face { face, bary },
            1 => {
                // On the edge opposite the zero: slot s joins corners s and s + 1.
                let zero = bary.iter().position(|&b| b == 0.0).unwrap_or(0);
                let s = (zero + 1) % 3;
                let edge = mesh.face_edges(face)[s];
                let lo = mesh.edge_vertices(edge)[0];
                let c = if corners[s] == lo { s } else { (s + 1) % 3 };
                // The weight of the higher vertex is the parameter from the lower one.
                SurfacePoint::Edge {
                    edge,
                    t: 1.0 - bary[c],
                }
            }
            _ => {
                let c = bary.iter().position(|&b| b != 0.0).unwrap_or(0);
                SurfacePoint::Vertex(corners[c])
            }
        }
    }

    /// World position of a valid point.
    pub fn position<T: Topology>(&self, mesh: &T) -> DVec3 {
        match *self {
            SurfacePoint::Vertex(v) => mesh.position(v),
            SurfacePoint::Edge { edge, t } => {
                let [a, b] = mesh.edge_vertices(edge);
                mesh.position(a).lerp(mesh.position(b), t)
            }
            SurfacePoint::Face { face, bary } => mesh.point(face, bary),
        }
    }

    /// The faces whose closure holds a valid point: around the vertex, around the edge,
    /// or the face.
    pub fn faces<'m, T: Topology>(&self, mesh: &'m T) -> Faces<T::Ids<'m>> {
        match *self {
            SurfacePoint::Vertex(v) => Faces::Many(mesh.vertex_faces(v)),
            SurfacePoint::Edge { edge, .. } => Faces::Many(mesh.edge_faces(edge)),
            SurfacePoint::Face { face, .. } => Faces::One([face]),
        }
    }

    /// Barycentric coordinates of a valid point in face `f`, if `f`'s closure holds it.
    pub fn bary_in<T: Topology>(&self, mesh: &T, f: u32) -> Option<[f64; 3]> {
        let mut bary = [0.0; 3];
        match *self {
            SurfacePoint::Vertex(v) => bary[mesh.corner_of(f, v)?] = 1.0,
            SurfacePoint::Edge { edge, t } => {
                let s = mesh.edge_slot(f, edge)?;
                let lo = mesh.edge_vertices(edge)[0];
                let c = mesh.face_vertices(f)[s];
                let (from_lo, to_hi) = if c == lo {
                    (s, (s + 1) % 3)
                } else {
                    ((s + 1) % 3, s)
                };
                bary[from_lo] = 1.0 - t;
                bary[to_hi] = t;
            }
            SurfacePoint::Face { face, bary: b } => {
                if face != f {
                    return None;
                }
                bary = b;
            }
        }
        Some(bary)
    }

    /// The point in face `f`'s frame, as a metric sees it, if `f`'s closure holds it.
    pub fn in_face<T: Topology>(&self, mesh: &T, f: u32) -> Option<FacePoint> {
        if let SurfacePoint::Vertex(v) = *self {
            // Exactly the corner the engines use.
            return Some(mesh.frame(f).corner(mesh.corner_of(f, v)?));
        }
        Some(mesh.frame(f).point(self.bary_in(mesh, f)?))
    }

    /// The point of the surface nearest to `xyz` (Euclidean, in space), in canonical
    /// form; `None` for a mesh without faces.
    ///
    /// Cost: a brute-force scan of every face, O(faces) per call;
    /// for many queries on a large mesh, a spatial index would be the thing to add.
    pub fn nearest<T: Topology>(mesh: &T, xyz: [f64; 3]) -> Option<SurfacePoint> {
        Self::nearest_among(mesh, 0..mesh.face_count() as u32, DVec3::from(xyz)).map(|(on, _)| on)
    }

    /// The point of `faces` nearest to `p` (Euclidean, in space), in canonical form,
    /// and its position; `None` for no face.
    pub(crate) fn nearest_among<T: Topology>(
        mesh: &T,
        faces: impl IntoIterator<Item = u32>,
        p: DVec3,
    ) -> Option<(SurfacePoint, DVec3)> {
        let mut best: Option<(f64, u32, [f64; 3], DVec3)> = None;
        for f in faces {
            let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
            let bary = closest_on_triangle(p, a, b, c);
            let q = a * bary[0] + b * bary[1] + c * bary[2];
            let d = q.distance_squared(p);
            if best.is_none_or(|(bd, ..)| d < bd) {
                best = Some((d, f, bary, q));
            }
        }
        best.map(|(_, f, bary, q)| (Self::in_face_closure(mesh, f, bary), q))
    }
}

/// The faces around a surface point ([`SurfacePoint::faces`]), as a slice.
#[derive(Clone, Copy, Debug)]
pub enum Faces<I> {
    /// Faces around a vertex or an edge, as the surface lists them
    /// ([`Topology::Ids`]: borrowed from a mesh's tables).
    Many(I),
    /// The one face of a point inside it.
    One([u32; 1]),
}

impl<I: std::ops::Deref<Target = [u32]>> std::ops::Deref for Faces<I> {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        match self {
            Faces::Many(faces) => faces,
            Faces::One(face) => face,
        }
    }
}

/// Barycentric coordinates of the point of triangle `abc` closest to `p` (Ericson,
/// *Real-Time Collision Detection*, 5.1.5: which Voronoi region of the triangle holds p).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    [1.0 - v - w, v, w]
}

impl fmt::Display for SurfacePoint {
    /// The command-line form: `V`, `e:E:t` or `f:F:b0,b1,b2`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SurfacePoint::Vertex(v) => write!(f, "{v}"),
            // `Num`: the shortest text that reads back, never hundreds of digits.
            SurfacePoint::Edge { edge, t } => write!(f, "e:{edge}:{}", Num(*t)),
            SurfacePoint::Face { face, bary } => {
                let [a, b, c] = bary.map(Num);
                write!(f, "f:{face}:{a},{b},{c}")
            }
        }
    }
}

impl FromStr for SurfacePoint {
    type Err = PointError;

    /// Reads `V` (a vertex id), `e:E:t` (edge `E` at parameter `t` from its lower-id
    /// vertex) or `f:F:b0,b1,b2` (face `F`, barycentrics in its vertex order).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let fail = |reason: &str| PointError::Parse {
            text: text.to_string(),
            reason: reason.to_string(),
        };
        let id = |s: &str, what: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| fail(&format!("'{s}' is not a {what} id")))
        };
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| fail(&format!("'{s}' is not a finite number")))
        };
        let parts: Vec<&str> = text.trim().split(':').collect();
        match parts.as_slice() {
            [v] => Ok(SurfacePoint::Vertex(id(v, "vertex")?)),
            ["e", e, t] => Ok(SurfacePoint::Edge {
                edge: id(e, "edge")?,
                t: number(t)?,
            }),
            ["f", f, b] => {
                let values = b.split(',').map(number).collect::<Result<Vec<_>, _>>()?;
                let bary: [f64; 3] = values
                    .try_into()
                    .map_err(|_| fail("a face point needs three barycentric coordinates"))?;
                Ok(SurfacePoint::Face {
                    face: id(f, "face")?,
                    bary,
                })
            }
            _ => Err(fail("unknown form")),
        }
    }
}

impl From<u32> for SurfacePoint {
    fn from(vertex: u32) -> Self {
        SurfacePoint::Vertex(vertex)
    }
}

/// A source of a propagation: a surface point and the value the distance starts from
/// there (0 by default; offsets give weighted Voronoi diagrams and grassfire fronts).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Source {
    /// Where.
    pub point: SurfacePoint,
    /// The distance at `point` itself. Any finite value, negative ones too (values
    /// then grow from it along every path). A run refuses a NaN or infinite start
    /// ([`Error::InvalidValue`](crate::Error::InvalidValue)) and one so large that a
    /// distance could overflow ([`Error::StartTooLarge`](crate::Error::StartTooLarge)).
    pub start: f64,
}

impl Source {
    /// A source at `point` starting from 0.
    pub fn new(point: impl Into<SurfacePoint>) -> Source {
        Source {
            point: point.into(),
            start: 0.0,
        }
    }

    /// The same source starting from `start` (see [`Source::start`] for what a run
    /// accepts).
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver, Source};
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2]],
    /// )?;
    /// let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT)?;
    /// let sources = [Source::new(0).with_start(-0.5), Source::new(1).with_start(0.25)];
    /// let field = solver.field(&sources)?;
    /// assert_eq!(field.distance(0), -0.5);
    /// assert_eq!(field.distance(1), 0.25); // 0.25 < -0.5 + 1
    /// assert!((field.distance(2) - 0.5).abs() < 1e-12);
    /// # Ok::<(), geotracks::Error>(())
    /// ```
    pub fn with_start(self, start: f64) -> Source {
        Source { start, ..self }
    }
}

impl From<u32> for Source {
    fn from(vertex: u32) -> Self {
        Source::new(vertex)
    }
}

impl From<SurfacePoint> for Source {
    fn from(point: SurfacePoint) -> Self {
        Source::new(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriMesh;

    fn square() -> TriMesh {
        TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap()
    }

    #[test]
    fn parses_and_prints_every_form() {
        for text in ["7", "e:3:0.25", "f:1:0.5,0.25,0.25"] {
            let p: SurfacePoint = text.parse().unwrap();
            assert_eq!(p.to_string(), text);
        }
        for bad in ["", "x", "e:1", "e:a:0.5", "f:0:1,2", "f:0:1,nan,0", "q:1:2"] {
            assert!(matches!(
                bad.parse::<SurfacePoint>(),
                Err(PointError::Parse { .. })
            ));
        }
    }

    #[test]
    fn validation_names_the_problem() {
        let mesh = square();
        let check = |p: SurfacePoint| p.validated(&mesh).unwrap_err();
        assert!(matches!(
            check(SurfacePoint::Vertex(4)),
            PointError::NoSuchVertex { .. }
        ));
        assert!(matches!(
            check(SurfacePoint::Edge { edge: 9, t: 0.5 }),
            PointError::NoSuchEdge { .. }
        ));
        assert!(matches!(
            check(SurfacePoint::Edge { edge: 0, t: 1.5 }),
            PointError::ParameterOutOfRange { .. }
        ));
        let face = |face, bary| SurfacePoint::Face { face, bary };
        assert!(matches!(
            check(face(2, [1.0, 0.0, 0.0])),
            PointError::NoSuchFace { .. }
        ));
        assert!(matches!(
            check(face(0, [0.5, 0.5, 0.5])),
            PointError::BarycentricSum { .. }
        ));
        assert!(matches!(
            check(face(0, [1.5, -0.5, 0.0])),
            PointError::NegativeBarycentric { .. }
        ));
        assert!(matches!(
            check(face(0, [f64::NAN, 0.5, 0.5])),
            PointError::BarycentricSum { .. }
        ));
    }

    #[test]
    fn canonical_form_names_every_face_it_lies_on() {
        let mesh = square();
        // On the diagonal 0–2, shared by both faces.
        let p = SurfacePoint::Face {
            face: 0,
            bary: [0.5, 0.0, 0.5],
        }
        .validated(&mesh)
        .unwrap();
        assert!(matches!(p, SurfacePoint::Edge { .. }));
        assert_eq!(p.faces(&mesh).len(), 2);
        assert!((p.position(&mesh) - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
        for &f in p.faces(&mesh).iter() {
            let b = p.bary_in(&mesh, f).unwrap();
            assert!((mesh.point(f, b) - p.position(&mesh)).length() < 1e-15);
        }
        let v = SurfacePoint::Face {
            face: 1,
            bary: [0.0, 1.0 + 1e-9, -1e-9],
        }
        .validated(&mesh)
        .unwrap();
        assert_eq!(v, SurfacePoint::Vertex(2));
        let e = SurfacePoint::Edge { edge: 0, t: 0.0 }
            .validated(&mesh)
            .unwrap();
        assert_eq!(e, SurfacePoint::Vertex(mesh.edge_vertices(0)[0]));
    }

    #[test]
    fn nearest_point_projects_onto_the_surface() {
        let mesh = square();
        let p = SurfacePoint::nearest(&mesh, [0.25, 0.75, -2.0]).unwrap();
        assert!((p.position(&mesh) - DVec3::new(0.25, 0.75, 0.0)).length() < 1e-15);
        // Outside the square, the nearest point is on its boundary.
        let q = SurfacePoint::nearest(&mesh, [2.0, 0.5, 0.0]).unwrap();
        assert!(matches!(q, SurfacePoint::Edge { .. }));
        assert!((q.position(&mesh) - DVec3::new(1.0, 0.5, 0.0)).length() < 1e-15);
        let v = SurfacePoint::nearest(&mesh, [-1.0, -1.0, 1.0]).unwrap();
        assert_eq!(v, SurfacePoint::Vertex(0));
    }
}
