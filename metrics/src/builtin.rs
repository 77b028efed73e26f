//! [`BuiltinMetric`]: the built-in metrics as one type.

use crate::{Density, Euclidean, FacePoint, Metric, Tensor};

/// One of the built-in metrics, chosen at run time (a command-line option, a Python
/// argument). One type for the three, so a caller builds one solver; the engine is
/// monomorphised on it, and the `match` below takes the same arm at every call.
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
}

/// `each!(self, m => expr)`: `expr` with `m` bound to the metric inside, for each
/// variant: one match, the variants' bodies inlined.
macro_rules! each {
    ($self:ident, $m:ident => $e:expr) => {
        match $self {
            BuiltinMetric::Euclidean($m) => $e,
            BuiltinMetric::Density($m) => $e,
            BuiltinMetric::Tensor($m) => $e,
        }
    };
}

impl Metric for BuiltinMetric {
    // Always: left to itself the compiler keeps the match with the three metrics'
    // bodies out of line, and a run costs 12–13 % more instructions instead of 6–8 %.
    #[inline(always)]
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        each!(self, m => m.cost(face, a, b))
    }
    fn is_face_norm(&self) -> bool {
        each!(self, m => m.is_face_norm())
    }
    #[inline(always)]
    fn prunes_on(&self, face: u32) -> bool {
        each!(self, m => m.prunes_on(face))
    }
    #[inline(always)]
    fn triangle_slack(&self, face: u32, diameter: f64) -> f64 {
        each!(self, m => m.triangle_slack(face, diameter))
    }
    fn face_gram(&self, face: u32) -> Option<[f64; 3]> {
        each!(self, m => m.face_gram(face))
    }
    fn wire_cost(&self, a: u32, b: u32, length: f64) -> f64 {
        each!(self, m => m.wire_cost(a, b, length))
    }
    fn name(&self) -> &str {
        each!(self, m => m.name())
    }
}
