use crate::{FaceGeometry, FacePoint, Metric, MetricError, SlidingCost};

/// A positive scalar cost per vertex, linear on each face (weighted geodesics).
///
/// A segment from `a` to `b` costs the exact integral of the linear density along it:
/// `|b − a| · (ρ(a) + ρ(b)) / 2`. A constant density `c` scales every distance by `c`.
///
/// Density is not a norm on a face: the triangle inequality can fail by up to
/// `(ρmax − ρmin) · diameter` inside a face ([`Metric::triangle_slack`]), and the track
/// pruning of geotracks accepts a proof only with that margin, so it stays exact.
///
/// ```
/// use geotracks_metrics::{Density, FaceGeometry, FacePoint, Metric};
///
/// // One right triangle with densities 1, 3, 1 at its corners.
/// struct OneFace;
/// impl FaceGeometry for OneFace {
///     fn vertex_count(&self) -> usize { 3 }
///     fn face_count(&self) -> usize { 1 }
///     fn face_vertices(&self, _: u32) -> [u32; 3] { [0, 1, 2] }
///     fn face_axes(&self, _: u32) -> [[f64; 3]; 2] { [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] }
/// }
/// let density = Density::new(&OneFace, vec![1.0, 3.0, 1.0]).unwrap();
/// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
/// let b = FacePoint { uv: [1.0, 0.0], bary: [0.0, 1.0, 0.0] };
/// assert_eq!(density.cost(0, &a, &b), 2.0); // length 1, mean density 2
/// assert!(Density::new(&OneFace, vec![1.0, 0.0, 1.0]).is_err());
/// ```
#[derive(Clone, Debug)]
pub struct Density {
    per_vertex: Vec<f64>,
    /// The densities at each face's corners, so a cost needs no vertex lookup.
    per_corner: Vec<[f64; 3]>,
    pruning_tolerance: f64,
}

impl Density {
    /// Builds a density from one value per vertex.
    ///
    /// # Errors
    /// [`MetricError::CountMismatch`] if `per_vertex` does not have one value per vertex;
    /// [`MetricError::InvalidDensity`] for a value that is not finite and > 0.
    pub fn new<G: FaceGeometry + ?Sized>(
        mesh: &G,
        per_vertex: Vec<f64>,
    ) -> Result<Self, MetricError> {
        if per_vertex.len() != mesh.vertex_count() {
            return Err(MetricError::CountMismatch {
                what: "density",
                per: "vertex",
                expected: mesh.vertex_count(),
                found: per_vertex.len(),
            });
        }
        if let Some((vertex, &value)) = per_vertex
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v > 0.0))
        {
            return Err(MetricError::InvalidDensity { vertex, value });
        }
        let per_corner = (0..mesh.face_count() as u32)
            .map(|f| mesh.face_vertices(f).map(|v| per_vertex[v as usize]))
            .collect();
        Ok(Density {
            per_vertex,
            per_corner,
            pruning_tolerance: Self::DEFAULT_PRUNING_TOLERANCE,
        })
    }

    /// A constant density `value` on every vertex.
    ///
    /// # Errors
    /// [`MetricError::InvalidDensity`] if `value` is not finite and > 0.
    pub fn constant<G: FaceGeometry + ?Sized>(mesh: &G, value: f64) -> Result<Self, MetricError> {
        Self::new(mesh, vec![value; mesh.vertex_count()])
    }

    /// The default of [`Density::with_pruning_tolerance`]: 0, exact.
    pub const DEFAULT_PRUNING_TOLERANCE: f64 = 0.0;

    /// Lets the engine treat a face as a norm (prune with no margin) where its density
    /// varies by at most a factor `1 + tolerance` (max / min). Elsewhere, and everywhere
    /// with the default 0, pruning keeps the margin of [`Metric::triangle_slack`] and
    /// the tracks engine returns exactly the complete Steiner graph's distances. A
    /// positive tolerance prunes more, and may then deviate from the graph: on random
    /// densities whose neighbouring values differ up to 26×, 0.2 gave no deviation and
    /// 1.0 a mean relative deviation of 1e-6 and a max of 8e-4 (geotracks'
    /// `tracks_oracle` test); on sliver faces deviations up to 1 % were seen.
    pub fn with_pruning_tolerance(mut self, tolerance: f64) -> Self {
        self.pruning_tolerance = tolerance.max(0.0);
        self
    }

    /// The density at each vertex.
    pub fn per_vertex(&self) -> &[f64] {
        &self.per_vertex
    }

    #[inline]
    fn at(&self, face: u32, p: &FacePoint) -> f64 {
        let c = &self.per_corner[face as usize];
        c[0] * p.bary[0] + c[1] * p.bary[1] + c[2] * p.bary[2]
    }
}

impl Metric for Density {
    #[inline]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        // A density never means "impassable": a product beyond the f64 range is kept
        // finite, so that the solver's check reports the overflow instead of the
        // engine taking it for a wall.
        (a.distance(b) * 0.5 * (self.at(face, a) + self.at(face, b))).min(f64::MAX)
    }
    fn prunes_on(&self, _face: u32) -> bool {
        true
    }
    /// `(ρmax − ρmin) · diameter`: a segment costs at most `ρmax · |ab|`, and any detour
    /// through the face at least `ρmin · |ab|`. 0 where the density varies by at most
    /// `1 + tolerance` ([`Density::with_pruning_tolerance`]).
    #[inline]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        let [a, b, c] = self.per_corner[face as usize];
        let (max, min) = (a.max(b).max(c), a.min(b).min(c));
        if max <= (1.0 + self.pruning_tolerance) * min {
            0.0
        } else {
            (max - min) * diameter
        }
    }
    /// `length · (ρ(a) + ρ(b)) / 2`: the density linear along the wire, as on an edge.
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        let (ra, rb) = (self.per_vertex[a as usize], self.per_vertex[b as usize]);
        (length * 0.5 * (ra + rb)).min(f64::MAX)
    }
    /// The least density: a segment costs its length times the mean density along it.
    fn min_cost_per_length(&self) -> f64 {
        self.per_vertex
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }
    fn name(&self) -> &str {
        "density"
    }
    /// The segment's length `L` (a norm: [`Metric::sliding_cost`] of `Euclidean`)
    /// times the mean density `m` of its ends, which is linear in `s` and `t`: the
    /// product rule, with `m`'s second derivatives 0.
    #[inline]
    fn sliding_cost(
        &self,
        face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        let length = SlidingCost::norm([1.0, 0.0, 1.0], a, da, b, db)?;
        // (`at` is linear in the barycentric coordinates: on a velocity it gives the
        // density's rate.)
        let along = |p: &FacePoint| 0.5 * self.at(face, p);
        let (m, ms, mt) = (along(a) + along(b), along(da), along(db));
        let (l, [ls, lt], [lss, lst, ltt]) = (length.cost, length.gradient, length.hessian);
        let cost = l * m;
        if cost >= f64::MAX {
            return None; // (`cost` clamps it there.)
        }
        SlidingCost {
            cost,
            gradient: [ls * m + l * ms, lt * m + l * mt],
            hessian: [
                lss * m + 2.0 * ls * ms,
                lst * m + ls * mt + lt * ms,
                ltt * m + 2.0 * lt * mt,
            ],
        }
        .finite()
    }
}
