//! Placed polylines thinned to the points their shape needs (Ramer–Douglas–Peucker,
//! with a tolerance in medial radii).
//!
//! Once placed, a branch has a point every [`Skeleton::RESAMPLING`] of the diagonal,
//! and each point lies on the axis (or on the centre of the cross-section there). Both
//! are sampled surfaces with their own roughness: an axis computed from a mesh is a
//! tangle of small sheets around the true one, and even a good axis is crumpled at
//! the scale of its faces. Points that close together on a rough surface zig-zag by
//! the roughness, which turns the curve's tangent by tens of degrees from one point to
//! the next while the curve as a whole runs straight. Dropping the points that lie
//! within a small fraction of the medial radius of the polyline without them takes the
//! zig-zag out and moves the curve by less than that fraction anywhere: the points
//! kept are points of the placed curve, with their radii.
//!
//! Hand-written rather than taken from a crate: the kept geometry crates simplify 2D
//! line strings (`geo`) with one tolerance, and here the tolerance varies along the
//! curve with the radius, in 3D.

use super::geometry::{least_edges, Rebuild};
use super::Skeleton;
use glam::DVec3;

impl Skeleton {
    /// The largest distance, in medial radii at the point, by which dropping a point
    /// may move the polyline there ([`Skeleton::simplified`]): a tenth, well below the
    /// one radius the smoothing already averages over.
    pub const SIMPLIFYING_RADII: f64 = 0.1;

    /// The skeleton with each polyline between tips and junctions thinned to the points
    /// it needs: a point is dropped where it lies within `radii` times its medial radius,
    /// and within `most`, of the segment between the points kept on either side
    /// (Ramer–Douglas–Peucker, the tolerance scaled by the radius at each point; a
    /// point without a radius is kept unless it lies on the segment). Tips, junctions
    /// and the graph's topology are unchanged; each polyline keeps at least as many
    /// edges as it had, up to 3, so that a loop stays a loop and two branches between
    /// the same two points stay apart.
    ///
    /// [`Skeleton::placed`] passes [`Skeleton::SIMPLIFYING_RADII`] and its resampling
    /// step: a point moves by no more than the step the curve was sampled at, which
    /// matters where the shape is thick (a tenth of a body's radius can be a few
    /// percent of its diagonal).
    pub fn simplified(&self, radii: f64, most: f64) -> Skeleton {
        let mut rebuilt = Rebuild::new(self);
        for line in self.polylines() {
            rebuilt.start(line[0]);
            let at = self.line_positions(&line);
            let tolerance: Vec<f64> = line
                .iter()
                .map(|&i| (radii * self.points[i as usize].radius.unwrap_or(0.0)).min(most))
                .collect();
            for (k, keep) in kept(&at, &tolerance).into_iter().enumerate().skip(1) {
                if keep {
                    rebuilt.then_old(line[k]);
                }
            }
        }
        rebuilt.finish()
    }
}

/// Per point of a polyline, whether the simplified polyline keeps it: its ends, every
/// point farther than its `tolerance` from the segment between the points kept around
/// it, and enough others that it keeps [`least_edges`].
fn kept(at: &[DVec3], tolerance: &[f64]) -> Vec<bool> {
    let n = at.len();
    let mut keep = vec![false; n];
    if n == 0 {
        return keep;
    }
    keep[0] = true;
    keep[n - 1] = true;
    let mut ranges = vec![(0, n - 1)];
    while let Some((a, b)) = ranges.pop() {
        // The point that stands out most for its tolerance, if any stands out.
        let farthest = (a + 1..b)
            .map(|k| {
                (
                    k,
                    excess(distance_to_segment(at[k], at[a], at[b]), tolerance[k]),
                )
            })
            .filter(|&(_, excess)| excess > 1.0)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((k, _)) = farthest {
            keep[k] = true;
            ranges.push((a, k));
            ranges.push((k, b));
        }
    }
    let edges = least_edges(n);
    if keep.iter().filter(|&&k| k).count() < edges + 1 {
        for j in 1..edges {
            keep[j * (n - 1) / edges] = true;
        }
    }
    keep
}

/// How many times its tolerance a distance is: `inf` for any distance past a tolerance
/// of 0.
fn excess(distance: f64, tolerance: f64) -> f64 {
    if tolerance > 0.0 {
        distance / tolerance
    } else if distance > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// The distance from `p` to the segment from `a` to `b` (to `a` if they coincide).
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let length2 = ab.length_squared();
    let t = if length2 > 0.0 {
        ((p - a).dot(ab) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::SkeletonPoint;
    use crate::surface::SurfacePoint;

    fn point(position: [f64; 3], radius: f64) -> SkeletonPoint {
        SkeletonPoint {
            position,
            on: SurfacePoint::Vertex(0),
            significance: 1.0,
            tubularity: 1.0,
            radius: Some(radius),
        }
    }

    /// A path of `points`, with the radius `radius` everywhere.
    fn path(points: &[[f64; 3]], radius: f64) -> Skeleton {
        Skeleton {
            points: points.iter().map(|&p| point(p, radius)).collect(),
            edges: (1..points.len() as u32).map(|i| [i - 1, i]).collect(),
            ..Skeleton::default()
        }
    }

    #[test]
    fn a_zig_zag_within_the_tolerance_goes_and_a_bend_stays() {
        // 0 → 10 along x with a zig-zag of ±0.05, then a right angle up to y = 10.
        let mut points: Vec<[f64; 3]> = (0..=20)
            .map(|i| {
                [
                    0.5 * f64::from(i),
                    if i % 2 == 1 { 0.05 } else { -0.05 },
                    0.0,
                ]
            })
            .collect();
        points.extend((1..=20).map(|i| [10.0, 0.5 * f64::from(i), 0.0]));
        let simplified = path(&points, 1.0).simplified(0.1, f64::INFINITY);
        assert_eq!(simplified.tip_count(), 2);
        assert_eq!(simplified.polylines().len(), 1);
        // The ends, the corner and the points that keep at least three edges.
        assert!(simplified.points.len() <= 5, "{}", simplified.points.len());
        assert!(simplified
            .points
            .iter()
            .any(|p| (DVec3::from(p.position) - DVec3::new(10.0, -0.05, 0.0)).length() < 0.11));
        // Where the radius is too small to hide it, the zig-zag's 21 points stay; the
        // straight leg keeps only its end.
        assert_eq!(
            path(&points, 0.1)
                .simplified(0.1, f64::INFINITY)
                .points
                .len(),
            22
        );
    }

    #[test]
    fn a_loop_stays_a_loop_and_two_branches_stay_apart() {
        // A square loop of 8 points on a stem; and two straight paths between the same
        // two junctions, each a branch with points on a line.
        let mut points = vec![[-1.0, 0.0, 0.0]];
        let ring = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        points.extend(ring);
        let mut edges = vec![[0, 1]];
        edges.extend((0..8).map(|k| [1 + k, 1 + (k + 1) % 8]));
        let skeleton = Skeleton {
            points: points.iter().map(|&p| point(p, 5.0)).collect(),
            edges,
            ..Skeleton::default()
        };
        let simplified = skeleton.simplified(0.1, f64::INFINITY);
        assert_eq!(simplified.cycle_count(), 1);
        assert_eq!(simplified.tip_count(), 1);
        assert!(simplified.points.len() < points.len());
        assert_no_doubled_edge(&simplified);
        // Two nearly straight paths from (0, 0, 0) to (4, 0, 0), 0.02 apart, each
        // junction on a stem.
        let mut points = vec![
            [-1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [5.0, 0.0, 0.0],
        ];
        let mut edges = vec![[0, 1], [2, 3]];
        for side in [0.01, -0.01] {
            let first = points.len() as u32;
            points.extend((1..4).map(|x| [f64::from(x), side, 0.0]));
            edges.extend([
                [1, first],
                [first, first + 1],
                [first + 1, first + 2],
                [first + 2, 2],
            ]);
        }
        let skeleton = Skeleton {
            points: points.iter().map(|&p| point(p, 5.0)).collect(),
            edges,
            ..Skeleton::default()
        };
        let simplified = skeleton.simplified(0.1, f64::INFINITY);
        assert_eq!((simplified.cycle_count(), simplified.tip_count()), (1, 2));
        assert_no_doubled_edge(&simplified);
    }

    fn assert_no_doubled_edge(skeleton: &Skeleton) {
        let mut seen = std::collections::HashSet::new();
        for &[a, b] in &skeleton.edges {
            assert!(
                a != b && seen.insert([a.min(b), a.max(b)]),
                "a doubled edge"
            );
        }
    }

    #[test]
    fn dropped_points_stay_within_the_tolerance_of_the_polyline() {
        // A gentle arc, sampled finely: what goes lies within a tenth of the radius.
        let points: Vec<[f64; 3]> = (0..=200)
            .map(|i| {
                let angle = f64::from(i) / 200.0;
                [10.0 * angle.cos(), 10.0 * angle.sin(), 0.0]
            })
            .collect();
        let simplified = path(&points, 0.5).simplified(0.1, f64::INFINITY);
        assert!(simplified.points.len() < 40, "{}", simplified.points.len());
        let line: Vec<DVec3> = simplified.polyline_positions()[0]
            .iter()
            .map(|&p| DVec3::from(p))
            .collect();
        for p in &points {
            let d = line
                .windows(2)
                .map(|w| distance_to_segment(DVec3::from(*p), w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.05 + 1e-12, "{d}");
        }
    }
}
