//! The medial balls of an axis as one shape: their union is the solid the axis stands
//! for, which says what the sheets alone cannot (whether a hole in the axis is a tunnel
//! of the solid, how wide its cross-section is).

use glam::DVec3;
use rstar::primitives::GeomWithData;
use rstar::RTree;

/// Samples per medial radius (the median round a loop) when a loop's disc is tested
/// against the balls: a tunnel narrower than about a sixth of the balls round it could
/// pass between the samples.
const FILL_STEPS_PER_RADIUS: f64 = 8.0;

/// Medial balls in an R-tree (`rstar`: a kept crate, for the balls near a point).
pub(super) struct Balls {
    tree: RTree<GeomWithData<[f64; 3], f64>>,
    largest: f64,
}

impl Balls {
    /// Every ball of the centres and radii given; balls of no radius (or NaN) are left
    /// out.
    pub(super) fn all(balls: impl IntoIterator<Item = ([f64; 3], f64)>) -> Balls {
        let balls: Vec<_> = balls
            .into_iter()
            .filter(|&(_, r)| r > 0.0)
            .map(|(centre, r)| GeomWithData::new(centre, r))
            .collect();
        let largest = balls.iter().map(|b| b.data).fold(0.0, f64::max);
        Balls {
            tree: RTree::bulk_load(balls),
            largest,
        }
    }

    /// The balls given, thinned: largest first, none whose centre lies within a quarter
    /// of its radius of a larger kept one's. Neighbouring balls of a medial axis are
    /// nearly the same ball, and the union of the kept ones differs from the whole union
    /// by at most a quarter radius at its rim (and lies inside it): fewer balls to draw
    /// where the rim does not matter much.
    pub(super) fn thinned(balls: impl IntoIterator<Item = ([f64; 3], f64)>) -> Balls {
        let mut by_size: Vec<([f64; 3], f64)> =
            balls.into_iter().filter(|&(_, r)| r > 0.0).collect();
        by_size.sort_by(|a, b| b.1.total_cmp(&a.1));
        let mut tree = RTree::new();
        for (centre, r) in by_size {
            if tree
                .locate_within_distance(centre, 0.0625 * r * r)
                .next()
                .is_none()
            {
                tree.insert(GeomWithData::new(centre, r));
            }
        }
        let largest = tree.iter().map(|b| b.data).fold(0.0, f64::max);
        Balls { tree, largest }
    }

    /// The balls whose centre lies within `reach` of `p`, as centre and radius.
    pub(super) fn near(&self, p: DVec3, reach: f64) -> impl Iterator<Item = (DVec3, f64)> + '_ {
        self.tree
            .locate_within_distance(p.to_array(), reach * reach)
            .map(|b| (DVec3::from(*b.geom()), b.data))
    }

    /// Whether `p` lies in a ball.
    pub(super) fn contain(&self, p: DVec3) -> bool {
        // Nearest centres first: deep inside, the nearest ball holds the point.
        self.tree
            .nearest_neighbor_iter_with_distance_2(&p.to_array())
            .take_while(|(_, d2)| *d2 <= self.largest * self.largest)
            .any(|(ball, d2)| d2 <= ball.data * ball.data)
    }

    /// Whether the balls fill a disc spanned by the closed polyline `ring`: the fan of
    /// triangles from its centroid to each of its segments, sampled every `step`. A
    /// loop of a skeleton whose disc the balls fill goes round no tunnel of the solid
    /// (the disc contracts it inside the shape): a hole of the axis that the balls
    /// cover, as approximate axes have where a sheet is thin. The converse is not
    /// claimed: a bent loop whose fan leaves the balls is kept, though another disc
    /// might lie inside. A `step` of no length (or NaN) fills nothing.
    pub(super) fn fill(&self, ring: &[DVec3], step: f64) -> bool {
        if ring.is_empty() || step.is_nan() || step <= 0.0 {
            return false;
        }
        let centre = ring.iter().sum::<DVec3>() / ring.len() as f64;
        let samples = |a: DVec3, b: DVec3| (a.distance(b) / step).ceil().max(1.0) as usize;
        (0..ring.len()).all(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let across = samples(a, b);
            (0..across).all(|k| {
                let rim = a.lerp(b, k as f64 / across as f64);
                let along = samples(centre, rim);
                (0..=along).all(|j| self.contain(centre.lerp(rim, j as f64 / along as f64)))
            })
        })
    }

    /// Whether the balls fill a disc spanned by the loop through `points`, whose medial
    /// radii are `radii`: [`Balls::fill`] sampled every eighth of the median radius.
    pub(super) fn fill_loop(&self, points: &[DVec3], mut radii: Vec<f64>) -> bool {
        if radii.is_empty() {
            return false;
        }
        radii.sort_by(f64::total_cmp);
        self.fill(points, radii[radii.len() / 2] / FILL_STEPS_PER_RADIUS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Balls of radius `r` every `r / 2` round a circle of radius `big`.
    fn ring_of_balls(big: f64, r: f64) -> (Balls, Vec<DVec3>) {
        let count = (std::f64::consts::TAU * big / (0.5 * r)).ceil() as usize;
        let ring: Vec<DVec3> = (0..count)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / count as f64;
                DVec3::new(big * t.cos(), big * t.sin(), 0.0)
            })
            .collect();
        (Balls::all(ring.iter().map(|c| (c.to_array(), r))), ring)
    }

    #[test]
    fn a_torus_loop_goes_round_a_tunnel_and_a_small_hole_is_filled() {
        // A torus: the loop round its tube's centre line spans the hole in the middle.
        let (torus, ring) = ring_of_balls(2.0, 0.5);
        assert!(!torus.fill(&ring, 0.1));
        // The same loop where the balls are wider than the hole: no tunnel.
        let (solid, ring) = ring_of_balls(0.4, 0.5);
        assert!(solid.fill(&ring, 0.1));
        assert!(solid.contain(DVec3::ZERO) && !torus.contain(DVec3::ZERO));
        // Just too narrow to close the hole: the centre is out by 0.05.
        let (almost, ring) = ring_of_balls(0.55, 0.5);
        assert!(!almost.fill(&ring, 0.02));
    }

    #[test]
    fn thinning_keeps_the_largest_and_drops_near_copies() {
        let balls = Balls::thinned([
            ([0.0, 0.0, 0.0], 1.0),
            ([0.2, 0.0, 0.0], 0.9),
            ([0.0, 0.0, 5.0], 0.0),
            ([3.0, 0.0, 0.0], 0.5),
        ]);
        let kept: Vec<f64> = balls.near(DVec3::ZERO, 10.0).map(|(_, r)| r).collect();
        assert_eq!(kept.len(), 2);
        assert!(kept.contains(&1.0) && kept.contains(&0.5));
        assert!(!balls.contain(DVec3::new(0.0, 0.0, 5.0)));
    }
}
