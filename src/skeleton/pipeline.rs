//! The pipeline from a medial axis to a placed skeleton: burnt, thinned, pruned, its
//! loops the balls fill opened, placed, and its tips' ends settled.

use super::balls::Balls;
use super::grassfire::burn_from_border;
use super::{Burn, Placement, Pruning, Skeleton};
use crate::mesh::io::MedialAxis;
use crate::options::Options;
use crate::surface::SurfacePoint;
use crate::{Error, Euclidean, Field};
use glam::DVec3;

/// The skeleton of a medial axis read from a `.ma` file, ready to use:
/// [`Skeleton::of_medial_axis`] pruned as `pruning` says (erosion thickness, then
/// tubularity, then protrusion), with the loops whose disc the medial balls fill opened
/// (holes of the axis that are no tunnel of the solid, see
/// [`medial_axis_skeleton_with_cycles`]), its points placed on the axis
/// ([`Skeleton::placed`], [`Placement::OnAxis`]) and given the medial radii. Also
/// returns the grassfire's distance field for [`Burn::Boundary`] on an axis with sheets
/// and a border.
///
/// # Errors
/// As [`Skeleton::of_medial_axis`].
pub fn medial_axis_skeleton(
    axis: &MedialAxis,
    burn: Burn,
    options: &Options,
    pruning: Pruning,
) -> Result<(Skeleton, Option<Field<Euclidean>>), Error> {
    medial_axis_skeleton_with_cycles(axis, burn, options, pruning, usize::MAX, Placement::OnAxis)
}

/// [`medial_axis_skeleton`] with at most `max_cycles` independent cycles, placed as
/// `placement` says. In order:
/// 1. pruned by erosion thickness, tubularity and protrusion (loops never open);
///    tubularity keeps each tree's trunk as the tree will be once its loops open, so
///    that a stubby solid whose axis has a small hole keeps its length;
/// 2. the loops beyond `max_cycles`, and every loop whose disc the medial balls fill
///    (sampled every eighth of the median radius round it: a tunnel narrower than about
///    a sixth of that radius may pass unseen), opened ([`Skeleton::with_cycles_cut`]): a strand the hole split
///    from the body goes whole, a limb the hole joined to another part is cut where the
///    loop is narrowest, and what the cuts leave is pruned by erosion thickness;
/// 3. pruned by protrusion again (the pieces the cuts left), placed
///    ([`Skeleton::placed`]), rid of branches from tips shorter than the threshold
///    ([`Skeleton::without_short_tips`]), and its tips cut back to the last ball that
///    holds them if `pruning` says so ([`Skeleton::tips_trimmed`]).
///
/// The thinned axis has the axis's b₁ cycles; the solid has a tunnel only where the
/// balls leave a hole open. Approximate axes have holes where a sheet is thin (where a
/// tail lies against a rump, say), and an axis computed from a sampled surface
/// ([`crate::skeleton::medial::medial_axis`]) more: `max_cycles` is then the solid's
/// genus.
///
/// # Errors
/// As [`Skeleton::of_medial_axis`].
pub fn medial_axis_skeleton_with_cycles(
    axis: &MedialAxis,
    burn: Burn,
    options: &Options,
    pruning: Pruning,
    max_cycles: usize,
    placement: Placement,
) -> Result<(Skeleton, Option<Field<Euclidean>>), Error> {
    let (skeleton, field) = Skeleton::of_medial_axis(axis, burn, options)?;
    let prune = pruning.erosion_thickness;
    // Thinning leaves its points on the axis's vertices.
    let radius_at = |on: SurfacePoint| match on {
        SurfacePoint::Vertex(v) => axis.radii[v as usize],
        _ => 0.0,
    };
    let skeleton = skeleton.pruned(prune);
    let balls = (skeleton.cycle_count() > 0).then(|| {
        Balls::all(
            axis.positions
                .iter()
                .copied()
                .zip(axis.radii.iter().copied()),
        )
    });
    let open = |skeleton: Skeleton, protrusion: f64, prune: f64| {
        let radius: Vec<f64> = skeleton.points.iter().map(|p| radius_at(p.on)).collect();
        let at: Vec<DVec3> = skeleton.points.iter().map(|p| p.position.into()).collect();
        // A loop whose disc the balls fill goes round no tunnel of the solid: a hole of
        // the axis where a sheet is thin, which approximate axes have.
        let filled = |ring: &[u32]| {
            let points: Vec<DVec3> = ring.iter().map(|&i| at[i as usize]).collect();
            let radii = ring.iter().map(|&i| radius[i as usize]).collect();
            balls
                .as_ref()
                .is_some_and(|balls| balls.fill_loop(&points, radii))
        };
        skeleton.with_cycles_cut(max_cycles, |i| radius[i], filled, protrusion, prune)
    };
    // The trunk is the tree's as it will be once its loops open (cut where narrowest,
    // nothing pruned): a stubby solid whose axis has a small hole where the fires met
    // keeps it.
    let trunk = trunk_once_opened(&skeleton, open(skeleton.clone(), 0.0, 0.0));
    let skeleton = skeleton.pruned_tubular_but(pruning.tubularity, &trunk);
    let skeleton =
        skeleton.pruned_protruding(pruning.protrusion, |i| radius_at(skeleton.points[i].on));
    let skeleton = open(skeleton, pruning.protrusion, prune);
    let skeleton =
        skeleton.pruned_protruding(pruning.protrusion, |i| radius_at(skeleton.points[i].on));
    // Placed, a branch that zig-zagged (or ends a longer one) is shorter than it stood.
    let placed = skeleton.placed(axis, placement).without_short_tips(prune);
    // On the axis, a new end goes on it too.
    let on_axis = placement == Placement::OnAxis;
    let surface = axis.surface.as_ref().filter(|_| on_axis);
    let trimmed = pruning.trim_tips.then(|| placed.tips_trimmed(surface));
    Ok((trimmed.unwrap_or(placed), field))
}

/// Per point of `skeleton`, whether it lies on the trunk of `opened`, the same skeleton
/// with its loops cut. A cut takes out whole branches, so `opened`'s points are some of
/// `skeleton`'s, at the same positions, but numbered afresh: they are found by position.
fn trunk_once_opened(skeleton: &Skeleton, opened: Skeleton) -> Vec<bool> {
    let index: std::collections::HashMap<[u64; 3], usize> = skeleton
        .points
        .iter()
        .enumerate()
        .map(|(i, p)| (p.position.map(f64::to_bits), i))
        .collect();
    let mut trunk = vec![false; skeleton.points.len()];
    for (p, on) in opened.points.iter().zip(opened.trunk()) {
        if let (true, Some(&i)) = (on, index.get(&p.position.map(f64::to_bits))) {
            trunk[i] = true;
        }
    }
    trunk
}

impl Skeleton {
    /// The unpruned skeleton of a medial axis: its sheets and free edges thinned by the
    /// fire `burn` chooses ([`Skeleton::from_reach`], or [`Skeleton::from_curves`] for
    /// an axis of curves only). Also returns the grassfire's distance field for
    /// [`Burn::Boundary`] on an axis with sheets and a border.
    ///
    /// # Errors
    /// As [`Skeleton::extract`] for [`Burn::Boundary`]; none otherwise.
    pub fn of_medial_axis(
        axis: &MedialAxis,
        burn: Burn,
        options: &Options,
    ) -> Result<(Skeleton, Option<Field<Euclidean>>), Error> {
        let Some(mesh) = &axis.surface else {
            let reach = matches!(burn, Burn::Radius).then_some(axis.radii.as_slice());
            let skeleton = Skeleton::from_curves(&axis.positions, &axis.free_edges, reach);
            return Ok((skeleton, None));
        };
        Ok(match burn {
            Burn::Radius => (Skeleton::from_reach(mesh, &Euclidean, &axis.radii), None),
            Burn::Boundary => burn_from_border(mesh, Euclidean, options, Some(&axis.radii))?,
        })
    }
}
