//! [`BuiltinMetric`], the built-in metrics as one type, and
//! [`metric_enum!`](crate::metric_enum), which makes such a type of any metrics.

use crate::{Density, Euclidean, Tensor, TensorField};

/// One of the built-in metrics, chosen at run time (a command-line option, a Python
/// argument). One type for them all, so a caller builds one solver; the engine is
/// monomorphised on it, and the `match` ([`metric_enum!`](crate::metric_enum)) takes the
/// same arm at every call.
///
/// Not free: on the bunny (69K faces, k = 5, tracks) a run executes 8 % (Euclidean),
/// 6 % (density) and 7 % (tensor) more instructions than on each metric's own type
/// (callgrind); in time, Euclidean ran about 5 % slower and the others within noise
/// (commit message of the command-line crate split, where this type was born).
#[derive(Clone, Debug)]
pub enum BuiltinMetric {
    /// The length.
    Euclidean(Euclidean),
    /// A density per vertex.
    Density(Density),
    /// A tensor per face.
    Tensor(Tensor),
    /// A tensor per vertex, linear across faces.
    TensorField(TensorField),
}

crate::metric_enum!(BuiltinMetric {
    Euclidean,
    Density,
    Tensor,
    TensorField
});

/// Implements [`Metric`](crate::Metric) for an enum whose variants each hold one metric
/// (`Variant(metric)`), every method delegated to the variant's metric by one `match`.
/// For a metric chosen at run time among a few (a command-line option, a Python
/// argument): one type, so one solver, the engine monomorphised on it.
///
/// `cost`, `prunes_on` and `triangle_slack` are `#[inline(always)]`: left to itself the
/// compiler keeps the match with the metrics' bodies out of line, and a run costs
/// 12–13 % more instructions than on each metric's own type instead of 6–8 %.
///
/// ```
/// use geotracks_metrics::{metric_enum, Density, Euclidean, Metric};
///
/// enum MyMetric {
///     Plain(Euclidean),
///     Weighted(Density),
/// }
/// metric_enum!(MyMetric { Plain, Weighted });
///
/// assert_eq!(MyMetric::Plain(Euclidean).name(), "euclidean");
/// ```
#[macro_export]
macro_rules! metric_enum {
    ($name:ident { $($variant:ident),+ $(,)? }) => {
        impl $crate::Metric for $name {
            #[inline(always)]
            fn cost(&self, face: u32, a: &$crate::FacePoint, b: &$crate::FacePoint) -> f64 {
                match self { $($name::$variant(m) => m.cost(face, a, b)),+ }
            }
            fn is_symmetric(&self) -> bool {
                match self { $($name::$variant(m) => m.is_symmetric()),+ }
            }
            fn is_face_norm(&self) -> bool {
                match self { $($name::$variant(m) => m.is_face_norm()),+ }
            }
            #[inline(always)]
            fn prunes_on(&self, face: u32) -> bool {
                match self { $($name::$variant(m) => m.prunes_on(face)),+ }
            }
            #[inline(always)]
            fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
                match self { $($name::$variant(m) => m.triangle_slack(face, diameter)),+ }
            }
            fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
                match self { $($name::$variant(m) => m.face_gram(face)),+ }
            }
            fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
                match self { $($name::$variant(m) => m.wire_cost(a, b, length)),+ }
            }
            fn min_cost_per_length(&self) -> f64 {
                match self { $($name::$variant(m) => m.min_cost_per_length()),+ }
            }
            fn name(&self) -> &str {
                match self { $($name::$variant(m) => m.name()),+ }
            }
            #[inline(always)]
            fn sliding_cost(
                &self,
                face: u32,
                a: &$crate::FacePoint,
                da: &$crate::FacePoint,
                b: &$crate::FacePoint,
                db: &$crate::FacePoint,
            ) -> Option<$crate::SlidingCost> {
                match self { $($name::$variant(m) => m.sliding_cost(face, a, da, b, db)),+ }
            }
        }
    };
}
