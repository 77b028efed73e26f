//! Terrain costs, all [`Metric`]s: a slope density, impassable faces, an anisotropic
//! cost that makes crossing the slope dearer than following a contour, and (in
//! [`DirectedCost`]) costs that make climbing dearer than descending.
//!
//! They work on any terrain-like mesh (z up), not only on grids.

use super::TerrainError;
use super::{DirectedCost, DirectedModel, ElevationGrid, GridSurface, TerrainMesh};
use geotracks::mesh::Topology;
use geotracks::metrics::{Density, FacePoint, Metric, Tensor};
use glam::DVec3;
use rayon::prelude::*;
use std::fmt;
use std::str::FromStr;

/// `value` as a cost factor: finite and ≥ 0.
fn check_factor(what: &'static str, value: f64) -> Result<(), TerrainError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(TerrainError::Parameter {
            what,
            value,
            expected: "it must be a finite number ≥ 0",
        })
    }
}

/// `degrees` as a maximum slope: above 0 and at most 90.
fn check_max_slope(degrees: f64) -> Result<(), TerrainError> {
    if degrees > 0.0 && degrees <= 90.0 {
        Ok(())
    } else {
        Err(TerrainError::Parameter {
            what: "the maximum slope",
            value: degrees,
            expected: "it must be in degrees, above 0 and at most 90",
        })
    }
}

/// The unnormalised normal of face `f` (twice its area long), turned to point up.
pub(super) fn face_normal_up<T: Topology>(mesh: &T, f: u32) -> DVec3 {
    let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
    normal_up(a, b, c)
}

/// The unnormalised normal of triangle `a b c` (twice its area long), turned to point
/// up.
pub(super) fn normal_up(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let n = (b - a).cross(c - a);
    if n.z < 0.0 {
        -n
    } else {
        n
    }
}

/// `tan²(slope)` of a vertex whose faces' upward normals sum to `n`; 0 for a vertex of
/// no face.
fn vertex_tan2(n: DVec3) -> f64 {
    if n == DVec3::ZERO {
        0.0
    } else {
        tan2(n)
    }
}

/// `tan²` of the angle between a normal and the vertical (infinite for a horizontal
/// normal).
pub(super) fn tan2(n: DVec3) -> f64 {
    (n.x * n.x + n.y * n.y) / (n.z * n.z)
}

/// The slope of every face, in degrees from the horizontal.
pub fn face_slopes<T: Topology>(mesh: &T) -> Vec<f64> {
    (0..mesh.face_count() as u32)
        .map(|f| {
            let n = face_normal_up(mesh, f);
            n.x.hypot(n.y).atan2(n.z).to_degrees()
        })
        .collect()
}

/// `tan²(slope)` at every vertex, from its area-weighted normal: the sum of its faces'
/// normals, each turned to point up and as long as twice the face's area. A vertex of
/// no face gets 0.
pub fn vertex_slope_tan2<T: Topology>(mesh: &T) -> Vec<f64> {
    let mut normals = vec![DVec3::ZERO; mesh.vertex_count()];
    for f in 0..mesh.face_count() as u32 {
        let n = face_normal_up(mesh, f);
        for v in mesh.face_vertices(f) {
            normals[v as usize] += n;
        }
    }
    normals.into_iter().map(vertex_tan2).collect()
}

/// [`vertex_slope_tan2`] of the vertices of `terrain`, a mesh of `grid` or of a window
/// of it ([`ElevationGrid::to_mesh_within`]), from all the grid's triangles around each
/// vertex: a window's vertices on its border get the slope they have on the whole grid
/// (to rounding), not that of the faces the window kept.
fn grid_vertex_slope_tan2(grid: &ElevationGrid, vertex_samples: Vec<usize>) -> Vec<f64> {
    let g = grid.geometry();
    let last = (g.ncols - 1, g.nrows - 1);
    // (On all cores: a vertex's slope reads only the grid; collected in vertex order.)
    vertex_samples
        .into_par_iter()
        .map(|s| {
            let (col, row) = (s % g.ncols, s / g.ncols);
            // The (up to) four cells around the sample.
            let mut n = DVec3::ZERO;
            for (dc, dr) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (c, r) = (col.wrapping_sub(dc), row.wrapping_sub(dr));
                if c >= last.0 || r >= last.1 {
                    continue;
                }
                for t in grid.cell_triangles(c, r).into_iter().flatten() {
                    if t.contains(&s) {
                        let [a, b, c] = t.map(|s| grid.sample_point(s));
                        n += normal_up(a, b, c);
                    }
                }
            }
            vertex_tan2(n)
        })
        .collect()
}

/// The slope density `ρ = 1 + a·tan²(slope)` per vertex (see [`vertex_slope_tan2`]): a
/// route pays more where the ground is steep, whichever way it goes there. `a = 0` is
/// the 3D length.
///
/// The density is built with a pruning tolerance of [`SLOPE_PRUNING_TOLERANCE`]: on
/// faces where it varies by at most 20 % the tracks engine prunes as for a norm. That
/// keeps slope routes as fast as before the exact margin (which costs 42 % more
/// instructions on a 400 × 400 grid at k = 2), and on the terrain tests it still gives
/// the graph's distances (a property test with random walls, and routes whose traced
/// cost is unchanged). Call `.with_pruning_tolerance(0.0)` on the result for the exact
/// rule.
///
/// # Errors
/// [`TerrainError::Parameter`] unless `a` is finite and ≥ 0; [`TerrainError::Vertical`]
/// for a vertex whose normal is horizontal.
pub fn slope_density<T: Topology>(mesh: &T, a: f64) -> Result<Density, TerrainError> {
    slope_density_from(mesh, a, vertex_slope_tan2(mesh))
}

/// [`slope_density`] from the vertices' `tan²(slope)`.
fn slope_density_from<T: Topology>(
    mesh: &T,
    a: f64,
    tan2: Vec<f64>,
) -> Result<Density, TerrainError> {
    check_factor("the slope factor a", a)?;
    let rho = tan2
        .into_iter()
        .enumerate()
        .map(|(v, t)| {
            let rho = 1.0 + a * t;
            if rho.is_finite() {
                Ok(rho)
            } else {
                Err(TerrainError::Vertical { vertex: v as u32 })
            }
        })
        .collect::<Result<Vec<f64>, _>>()?;
    Ok(Density::new(mesh, rho)?.with_pruning_tolerance(SLOPE_PRUNING_TOLERANCE))
}

/// The pruning tolerance of [`slope_density`] (see `Density::with_pruning_tolerance`).
pub const SLOPE_PRUNING_TOLERANCE: f64 = 0.2;

/// Faces steeper than `max_degrees`, as a per-face mask for [`Impassable`].
///
/// # Errors
/// [`TerrainError::Parameter`] unless `max_degrees` is in (0, 90].
pub fn steeper_than<T: Topology>(mesh: &T, max_degrees: f64) -> Result<Vec<bool>, TerrainError> {
    check_max_slope(max_degrees)?;
    Ok(face_slopes(mesh)
        .into_iter()
        .map(|s| s > max_degrees)
        .collect())
}

/// The anisotropic "incline" tensor: per face, `M = I + b·g gᵀ` in the face's frame,
/// with `g` the projection of the vertical onto the face (the steepest direction, with
/// `|g| = sin(slope)`). Moving along the steepest line costs `sqrt(1 + b·sin²(slope))`
/// per unit length, along a contour 1, in between `sqrt(1 + b·sin²(slope)·cos²φ)` with
/// φ the angle from the steepest line.
///
/// The cost is the same going up or down: it charges the *effort of crossing the
/// slope* either way. For climbing dearer than descending, see [`DirectedCost`] (the
/// cost `uphill:B`).
///
/// # Errors
/// [`TerrainError::Parameter`] unless `b` is finite and ≥ 0.
pub fn incline_tensor<T: Topology>(mesh: &T, b: f64) -> Result<Tensor, TerrainError> {
    check_factor("the incline factor b", b)?;
    let local = (0..mesh.face_count() as u32)
        .map(|f| {
            let [u, v] = geotracks::metrics::FaceGeometry::face_axes(mesh, f);
            // World z in the face's (u, v) frame.
            let (gu, gv) = (u[2], v[2]);
            [1.0 + b * gu * gu, b * gu * gv, 1.0 + b * gv * gv]
        })
        .collect();
    Ok(Tensor::from_local(local)?)
}

/// A metric with walls: faces that no route may cross.
///
/// A segment of positive length in a blocked face costs `+inf`, which every engine
/// treats as "no way through" (a zero-length segment costs 0). Elsewhere the inner
/// metric decides. The edges of a blocked face that it shares with a free face stay
/// walkable (walking *along* a wall is allowed); an edge between two blocked faces is
/// not. So a wall is watertight where its faces share edges; two blocked faces that
/// only touch at a vertex leave a gap there.
///
/// ```
/// use geotracks_terrain::Impassable;
/// use geotracks::{mesh::TriMesh, Euclidean, Options, Solver};
/// // Two triangles of a unit square; block the upper one.
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let walls = Impassable::new(&mesh, Euclidean, vec![false, true])?;
/// let field = Solver::new(mesh, walls, &Options::DEFAULT)?.field(1)?;
/// // The diagonal 0–2 is shared with the free face: walkable, along the wall.
/// assert!((field.distance(2) - 1.0).abs() < 1e-12);
/// // Vertex 3 belongs to the blocked face only: no route reaches it.
/// assert!(field.distance(3).is_infinite());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Impassable<M> {
    inner: M,
    blocked: Vec<bool>,
}

impl<M: Metric> Impassable<M> {
    /// `inner`, with the faces whose entry in `blocked` is true made impassable.
    ///
    /// # Errors
    /// [`TerrainError::CountMismatch`] unless `blocked` has one entry per face.
    pub fn new<G: geotracks::metrics::FaceGeometry + ?Sized>(
        mesh: &G,
        inner: M,
        blocked: Vec<bool>,
    ) -> Result<Self, TerrainError> {
        if blocked.len() != mesh.face_count() {
            return Err(TerrainError::CountMismatch {
                what: "the blocked-face mask",
                per: "faces",
                expected: mesh.face_count(),
                found: blocked.len(),
            });
        }
        Ok(Impassable { inner, blocked })
    }

    /// `inner`, with every face around a blocked vertex made impassable (the outer edges
    /// of those faces stay walkable, see the type's docs).
    ///
    /// # Errors
    /// [`TerrainError::CountMismatch`] unless `blocked_vertices` has one entry per
    /// vertex.
    pub fn from_vertices<T: Topology>(
        mesh: &T,
        inner: M,
        blocked_vertices: &[bool],
    ) -> Result<Self, TerrainError> {
        if blocked_vertices.len() != mesh.vertex_count() {
            return Err(TerrainError::CountMismatch {
                what: "the blocked-vertex mask",
                per: "vertices",
                expected: mesh.vertex_count(),
                found: blocked_vertices.len(),
            });
        }
        let blocked = (0..mesh.face_count() as u32)
            .map(|f| {
                mesh.face_vertices(f)
                    .iter()
                    .any(|&v| blocked_vertices[v as usize])
            })
            .collect();
        Ok(Impassable { inner, blocked })
    }

    /// Whether face `f` is blocked.
    pub fn is_blocked(&self, f: u32) -> bool {
        self.blocked[f as usize]
    }

    /// How many faces are blocked.
    pub fn blocked_count(&self) -> usize {
        self.blocked.iter().filter(|&&b| b).count()
    }

    /// The metric on free faces.
    pub fn inner(&self) -> &M {
        &self.inner
    }
}

impl<M: Metric> Metric for Impassable<M> {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        if self.blocked[face as usize] {
            if a.uv == b.uv {
                0.0
            } else {
                f64::INFINITY
            }
        } else {
            self.inner.cost(face, a, b)
        }
    }
    fn is_symmetric(&self) -> bool {
        self.inner.is_symmetric()
    }
    // An infinite cost on a blocked face keeps the triangle inequality there, so the
    // inner metric's pruning stays valid (the engines test every target of a blocked
    // face and all of them lose).
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
        // A blocked face has no flattening (it cannot be crossed at all).
        if self.blocked[face as usize] {
            None
        } else {
            self.inner.face_gram(face)
        }
    }
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        self.inner.wire_cost(a, b, length)
    }
    // Walls cost more than anything.
    fn min_cost_per_length(&self) -> f64 {
        self.inner.min_cost_per_length()
    }
    fn name(&self) -> &str {
        "impassable"
    }
    // (A blocked face's costs are infinite: no formula.)
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<geotracks::metrics::SlidingCost> {
        if self.blocked[face as usize] {
            None
        } else {
            self.inner.sliding_cost(face, a, da, b, db)
        }
    }
}

/// A terrain cost as the command line names it: `none`, `slope:A[,max:DEG]`,
/// `incline:B`, or a directed cost: `uphill:B`, `naismith`, `rwalk[:a,b,c,d[,sf]]`,
/// `tobler[:offpath]`.
///
/// ```
/// use geotracks_terrain::{DirectedModel, TerrainCost};
/// let cost: TerrainCost = "slope:4,max:35".parse()?;
/// assert_eq!(cost, TerrainCost::Slope { a: 4.0, max_degrees: Some(35.0) });
/// assert_eq!(cost.to_string(), "slope:4,max:35");
/// assert!("slope:-1".parse::<TerrainCost>().is_err());
/// let walk: TerrainCost = "rwalk".parse()?;
/// assert_eq!(walk, TerrainCost::Directed(DirectedModel::RWALK));
/// assert!(walk.is_directed());
/// # Ok::<(), geotracks_terrain::TerrainError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum TerrainCost {
    /// The 3D length ([`geotracks::metrics::Euclidean`]).
    #[default]
    None,
    /// [`slope_density`] with factor `a`, and faces steeper than `max_degrees`
    /// impassable ([`steeper_than`], [`Impassable`]).
    Slope {
        /// The factor of `tan²(slope)`.
        a: f64,
        /// The steepest passable slope, in degrees.
        max_degrees: Option<f64>,
    },
    /// [`incline_tensor`] with factor `b` (the same up and down).
    Incline {
        /// The factor of `sin²(slope)` along the steepest line.
        b: f64,
    },
    /// A [`DirectedCost`]: `uphill:B` (3D length + B per unit climbed), `naismith`,
    /// `rwalk` (GRASS r.walk's walking time, seconds), `tobler` (Tobler's hiking
    /// function, seconds).
    Directed(DirectedModel),
}

impl fmt::Display for TerrainCost {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            TerrainCost::None => f.write_str("none"),
            TerrainCost::Slope { a, max_degrees } => {
                write!(f, "slope:{a}")?;
                if let Some(m) = max_degrees {
                    write!(f, ",max:{m}")?;
                }
                Ok(())
            }
            TerrainCost::Incline { b } => write!(f, "incline:{b}"),
            TerrainCost::Directed(model) => match model {
                DirectedModel::Uphill { b } => write!(f, "uphill:{b}"),
                _ if model == DirectedModel::NAISMITH => f.write_str("naismith"),
                _ if model == DirectedModel::RWALK => f.write_str("rwalk"),
                DirectedModel::Walk {
                    a,
                    b,
                    c,
                    d,
                    slope_factor,
                } => write!(f, "rwalk:{a},{b},{c},{d},{slope_factor}"),
                DirectedModel::Tobler { off_path: false } => f.write_str("tobler"),
                DirectedModel::Tobler { off_path: true } => f.write_str("tobler:offpath"),
            },
        }
    }
}

impl FromStr for TerrainCost {
    type Err = TerrainError;
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let fail = |reason: String| TerrainError::CostSpec {
            text: text.to_string(),
            reason,
        };
        let number = |s: &str, what: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| fail(format!("{what} '{s}' is not a finite number")))
        };
        let (kind, rest) = text.trim().split_once(':').unwrap_or((text.trim(), ""));
        let cost = match kind {
            "none" if rest.is_empty() => TerrainCost::None,
            "slope" => {
                let mut parts = rest.split(',');
                let a = number(parts.next().unwrap_or(""), "the factor")?;
                let max_degrees = match parts.next() {
                    None => None,
                    Some(m) => match m.trim().split_once(':') {
                        Some(("max", deg)) => Some(number(deg, "the maximum slope")?),
                        _ => return Err(fail(format!("'{m}' is not max:DEG"))),
                    },
                };
                if let Some(extra) = parts.next() {
                    return Err(fail(format!("unexpected '{extra}'")));
                }
                TerrainCost::Slope { a, max_degrees }
            }
            "incline" => TerrainCost::Incline {
                b: number(rest, "the factor")?,
            },
            "uphill" => TerrainCost::Directed(DirectedModel::Uphill {
                b: number(rest, "the factor")?,
            }),
            "naismith" if rest.is_empty() => TerrainCost::Directed(DirectedModel::NAISMITH),
            "rwalk" if rest.is_empty() => TerrainCost::Directed(DirectedModel::RWALK),
            "rwalk" => {
                let values = rest
                    .split(',')
                    .map(|x| number(x, "a coefficient"))
                    .collect::<Result<Vec<f64>, _>>()?;
                let slope_factor = match values.len() {
                    4 => -0.2125,
                    5 => values[4],
                    n => {
                        return Err(fail(format!(
                            "rwalk takes a,b,c,d or a,b,c,d,slope_factor, not {n} numbers"
                        )))
                    }
                };
                TerrainCost::Directed(DirectedModel::Walk {
                    a: values[0],
                    b: values[1],
                    c: values[2],
                    d: values[3],
                    slope_factor,
                })
            }
            "tobler" if rest.is_empty() => {
                TerrainCost::Directed(DirectedModel::Tobler { off_path: false })
            }
            "tobler" if rest.trim() == "offpath" => {
                TerrainCost::Directed(DirectedModel::Tobler { off_path: true })
            }
            _ => return Err(fail("unknown cost".into())),
        };
        cost.check().map_err(|e| fail(e.to_string()))?;
        Ok(cost)
    }
}

impl TerrainCost {
    /// Checks the parameters' ranges (as the builders do, without a mesh).
    ///
    /// # Errors
    /// [`TerrainError::Parameter`] for a negative or non-finite factor, or a maximum
    /// slope outside (0, 90].
    pub fn check(&self) -> Result<(), TerrainError> {
        match *self {
            TerrainCost::None => Ok(()),
            TerrainCost::Slope { a, max_degrees } => {
                check_factor("the slope factor a", a)?;
                max_degrees.map_or(Ok(()), check_max_slope)
            }
            TerrainCost::Incline { b } => check_factor("the incline factor b", b),
            TerrainCost::Directed(model) => model.check(),
        }
    }

    /// Whether the cost is directed (climbing and descending differ): a field is then
    /// the cost *from* its sources.
    pub fn is_directed(&self) -> bool {
        matches!(self, TerrainCost::Directed(_))
    }

    /// What a route costs at least per unit of 3D length, anywhere on `grid`'s mesh and
    /// in any direction: the least of [`Metric::min_cost_per_length`] over the
    /// metrics [`metric`](Self::metric) would build on any part of the grid, known
    /// from the grid without meshing it. A route through a point `x` then costs at
    /// least this times `|s − x| + |x − t|` (3D distances to its ends), which is what
    /// [`route_on_grid`](super::route_on_grid) cuts its window by.
    ///
    /// 1 for `none`, `slope` (a density ≥ 1) and `incline` (whose least eigenvalue is
    /// 1); for a directed cost, the model's bound at the grid's steepest triangle
    /// ([`ElevationGrid::steepest_tangent`], which gives the least bound of all its
    /// faces). Shaded by 1e-9 against rounding (a face's computed bound can come out
    /// an ulp below the exact one).
    ///
    /// [`Metric::min_cost_per_length`]: geotracks::metrics::Metric::min_cost_per_length
    pub fn least_cost_per_length(&self, grid: &ElevationGrid) -> f64 {
        let exact = match self {
            TerrainCost::None | TerrainCost::Slope { .. } | TerrainCost::Incline { .. } => 1.0,
            TerrainCost::Directed(model) => {
                model.min_cost_per_length(grid.steepest_tangent() * (1.0 + 1e-9))
            }
        };
        (exact * (1.0 - 1e-9)).max(0.0)
    }

    /// The unit of the cost for a grid in metres: `"s"` for the walking times
    /// (`naismith`, `rwalk`, `tobler`), `"m"` (of the cost's length) otherwise.
    pub fn unit(&self) -> &'static str {
        match self {
            TerrainCost::Directed(DirectedModel::Walk { .. } | DirectedModel::Tobler { .. }) => "s",
            _ => "m",
        }
    }

    /// Builds the metric on `mesh`.
    ///
    /// ```
    /// use geotracks_terrain::{ElevationGrid, GridGeometry, TerrainCost};
    /// use geotracks::Metric;
    /// let geometry = GridGeometry { ncols: 3, nrows: 3, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
    /// let terrain = ElevationGrid::from_fn(geometry, |x, _| Some(x))?.to_mesh()?;
    /// let metric = "slope:4,max:60".parse::<TerrainCost>()?.metric(&terrain.mesh)?;
    /// assert_eq!(metric.name(), "impassable");
    /// # Ok::<(), geotracks_terrain::TerrainError>(())
    /// ```
    ///
    /// # Errors
    /// What building the metric returns ([`TerrainError::Parameter`] for a parameter
    /// out of range).
    pub fn metric<T: Topology>(&self, mesh: &T) -> Result<TerrainMetric, TerrainError> {
        self.metric_with(mesh, vertex_slope_tan2)
    }

    /// As [`metric`](Self::metric) on `terrain`, a mesh of `grid` or of a window of it
    /// ([`ElevationGrid::to_mesh_within`]), with each vertex's slope (which the slope
    /// density uses) taken from all the grid's triangles around it: a window's metric
    /// is then the whole grid's, on the faces it kept (to rounding).
    ///
    /// # Errors
    /// As [`metric`](Self::metric).
    pub fn metric_on_grid(
        &self,
        grid: &ElevationGrid,
        terrain: &TerrainMesh,
    ) -> Result<TerrainMetric, TerrainError> {
        self.metric_with(&terrain.mesh, |_| {
            grid_vertex_slope_tan2(grid, terrain.vertex_samples())
        })
    }

    /// As [`metric_on_grid`](Self::metric_on_grid) on a [`GridSurface`] of `grid` (or
    /// of a window of it): the costs read the grid's samples, and no mesh is built.
    ///
    /// # Errors
    /// As [`metric`](Self::metric).
    pub fn metric_on_surface(
        &self,
        grid: &ElevationGrid,
        surface: &GridSurface,
    ) -> Result<TerrainMetric, TerrainError> {
        self.metric_with(surface, |_| {
            grid_vertex_slope_tan2(grid, surface.vertex_grid_samples())
        })
    }

    /// The metric, with the vertices' `tan²(slope)` from `slopes`.
    fn metric_with<T: Topology>(
        &self,
        mesh: &T,
        slopes: impl FnOnce(&T) -> Vec<f64>,
    ) -> Result<TerrainMetric, TerrainError> {
        Ok(match *self {
            TerrainCost::None => TerrainMetric::Length(geotracks::metrics::Euclidean),
            TerrainCost::Slope {
                a,
                max_degrees: None,
            } => TerrainMetric::Slope(slope_density_from(mesh, a, slopes(mesh))?),
            TerrainCost::Slope {
                a,
                max_degrees: Some(m),
            } => {
                let density = slope_density_from(mesh, a, slopes(mesh))?;
                TerrainMetric::WalledSlope(Impassable::new(mesh, density, steeper_than(mesh, m)?)?)
            }
            TerrainCost::Incline { b } => TerrainMetric::Incline(incline_tensor(mesh, b)?),
            TerrainCost::Directed(model) => {
                TerrainMetric::Directed(DirectedCost::new(mesh, model)?)
            }
        })
    }
}

/// The metric a [`TerrainCost`] builds ([`TerrainCost::metric`]): one type for all the
/// costs, so a caller builds one solver whatever the cost.
///
/// The engine is generic over its metric, so it runs on this enum monomorphised; the
/// `match` in [`Metric::cost`] picks the same arm at every call. That is cheap, not
/// free: the command line's equivalent enum measured 6–8 % more instructions per run
/// than each metric's own type. Code that runs one cost many times can use the cost's
/// own type ([`slope_density`], [`Impassable`], [`incline_tensor`], [`DirectedCost`]).
#[derive(Clone, Debug)]
pub enum TerrainMetric {
    /// `none`: the 3D length.
    Length(geotracks::metrics::Euclidean),
    /// `slope:A`: [`slope_density`].
    Slope(Density),
    /// `slope:A,max:DEG`: [`slope_density`] with faces steeper than DEG impassable.
    WalledSlope(Impassable<Density>),
    /// `incline:B`: [`incline_tensor`].
    Incline(Tensor),
    /// `uphill:B`, `naismith`, `rwalk…`, `tobler…`: a [`DirectedCost`].
    Directed(DirectedCost),
}

geotracks::metrics::metric_enum!(TerrainMetric {
    Length,
    Slope,
    WalledSlope,
    Incline,
    Directed
});
