use crate::{FacePoint, Metric, SlidingCost};

/// The plain length of a segment: geodesic distance on the surface as it is.
///
/// ```
/// use geotracks_metrics::{Euclidean, FacePoint, Metric};
/// let a = FacePoint { uv: [0.0, 0.0], bary: [1.0, 0.0, 0.0] };
/// let b = FacePoint { uv: [3.0, 4.0], bary: [0.0, 0.0, 1.0] };
/// assert_eq!(Euclidean.cost(0, &a, &b), 5.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Euclidean;

impl Metric for Euclidean {
    #[inline]
    fn cost(&self, _face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        a.distance(b)
    }
    fn is_face_norm(&self) -> bool {
        true
    }
    #[inline]
    fn face_gram(&self, _face: u32) -> Option<[f64; 3]> {
        Some([1.0, 0.0, 1.0])
    }
    fn min_cost_per_length(&self) -> f64 {
        1.0
    }
    fn name(&self) -> &str {
        "euclidean"
    }
    #[inline]
    fn sliding_cost(
        &self,
        _face: u32,
        a: &FacePoint,
        da: &FacePoint,
        b: &FacePoint,
        db: &FacePoint,
    ) -> Option<SlidingCost> {
        SlidingCost::norm([1.0, 0.0, 1.0], a, da, b, db)
    }
}
