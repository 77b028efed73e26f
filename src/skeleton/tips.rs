//! Where branches end once the skeleton is placed: which short ones go, and how far in
//! from where the axis ran out each tip ends.

use super::geometry::{lengths_along, nearby_faces, Rebuild};
use super::{Skeleton, SkeletonPoint};
use crate::mesh::TriMesh;
use crate::surface::SurfacePoint;
use glam::DVec3;

/// Where a polyline is cut: on its edge from point `edge` to the next, at `t` of the way.
#[derive(Clone, Copy)]
struct Cut {
    edge: usize,
    t: f64,
}

impl Skeleton {
    /// The placed skeleton with each branch from a tip ending a little inside where it
    /// ran out: at the innermost point whose medial ball (the points' radii, linear
    /// along each edge) still holds the old end, walking in while the balls do, and
    /// never more than the end's own radius in. Thinning runs a branch out to where the
    /// axis meets the surface (a flat foot's rim, an ear's edge), where a
    /// mean-curvature-flow skeleton's tip lies inside the shape by about its thickness
    /// there. A ball on a thin stalk keeps its centre (the stalk's balls do not reach
    /// it), and a limb tapering to a point loses at most the radius its tip has.
    ///
    /// A branch from a tip to a junction keeps at least half its length, and a
    /// component that is one path a tenth of it, in its middle; no point goes but those
    /// cut off, so the graph keeps its tips, junctions and cycles. Points without a
    /// radius cut nothing. With `surface` (a skeleton placed on it, as on a medial
    /// axis's sheets), a new end is put on the nearest point of the faces near the
    /// point it was cut next to (at that point, on a curve away from every face);
    /// without, it keeps that point's `on`.
    ///
    /// ```
    /// use geotracks::skeleton::Skeleton;
    /// // A limb of radius 0.3 up to y = 2 from the middle of a trunk of radius 1.
    /// let points = [[-2.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    /// let edges = [[0, 1], [1, 2], [1, 3]];
    /// let radii = [1.0, 1.0, 1.0, 0.3];
    /// let skeleton = Skeleton::from_curves(&points, &edges, None).with_radii(None, &radii);
    /// let trimmed = skeleton.tips_trimmed(None);
    /// assert_eq!(trimmed.tip_count(), 3);
    /// // The limb's end moves in by its radius; the trunk's ends by 1.
    /// assert!((trimmed.length() - (1.0 + 1.0 + 1.7)).abs() < 1e-9);
    /// ```
    #[must_use]
    pub fn tips_trimmed(&self, surface: Option<&TriMesh>) -> Skeleton {
        let degree = self.degrees();
        let mut rebuilt = Rebuild::new(self);
        for line in self.polylines() {
            let tip = |i: u32| degree[i as usize] == 1;
            let (first, last) = (line[0], line[line.len() - 1]);
            if line.len() < 2 || !(tip(first) || tip(last)) {
                rebuilt.start(first);
                rebuilt.then_olds(&line[1..]);
                continue;
            }
            let at = self.line_positions(&line);
            let radius: Vec<f64> = line
                .iter()
                .map(|&i| self.points[i as usize].radius.unwrap_or(0.0))
                .collect();
            let both = tip(first) && tip(last);
            let most = if both { 0.45 } else { 0.5 };
            let start = tip(first).then(|| ball_cut(&at, &radius, most)).flatten();
            // The end's cut seen from the start: on edge n - 2 - edge, at 1 - t.
            let end = tip(last)
                .then(|| {
                    let reversed_at: Vec<DVec3> = at.iter().rev().copied().collect();
                    let reversed_radius: Vec<f64> = radius.iter().rev().copied().collect();
                    ball_cut(&reversed_at, &reversed_radius, most)
                })
                .flatten()
                .map(|cut| Cut {
                    edge: line.len() - 2 - cut.edge,
                    t: 1.0 - cut.t,
                });
            let point_at = |cut: Cut| {
                let (a, b) = (
                    &self.points[line[cut.edge] as usize],
                    &self.points[line[cut.edge + 1] as usize],
                );
                let near = if cut.t < 0.5 { a } else { b };
                let position = at[cut.edge].lerp(at[cut.edge + 1], cut.t);
                let (on, position) = match surface {
                    Some(mesh) => {
                        SurfacePoint::nearest_among(mesh, nearby_faces(mesh, near.on), position)
                            .unwrap_or((near.on, DVec3::from(near.position)))
                    }
                    None => (near.on, position),
                };
                let r = radius[cut.edge] + cut.t * (radius[cut.edge + 1] - radius[cut.edge]);
                SkeletonPoint::between(a, b, position, on, Some(r))
            };
            // Then the old points after the start (or its cut) up to the end's cut (or
            // the end).
            let from = start.map_or(1, |c| c.edge + 1);
            let to = end.map_or(line.len() - 1, |c| c.edge);
            match start {
                Some(cut) => rebuilt.start_new(point_at(cut)),
                None => rebuilt.start(first),
            }
            rebuilt.then_olds(&line[from..=to]);
            if let Some(cut) = end {
                rebuilt.then_new(point_at(cut));
            }
        }
        rebuilt.finish()
    }

    /// The skeleton without the branches from a tip shorter than `threshold` (placed
    /// length, polyline by polyline), shortest first, each branch's length taken again
    /// once its neighbour went (two branches that met at a junction become one). A
    /// component that is one path keeps it, and no cycle opens (a branch from a tip is
    /// on none).
    #[must_use]
    pub fn without_short_tips(&self, threshold: f64) -> Skeleton {
        let mut skeleton = self.clone();
        loop {
            let degree = skeleton.degrees();
            let shortest = skeleton
                .polylines()
                .into_iter()
                .filter(|line| {
                    let (a, b) = (line[0] as usize, line[line.len() - 1] as usize);
                    line.len() > 1 && (degree[a] == 1) != (degree[b] == 1)
                })
                .map(|line| {
                    let along = lengths_along(&skeleton.line_positions(&line));
                    (along[along.len() - 1], line)
                })
                .filter(|(length, _)| *length < threshold)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let Some((_, mut line)) = shortest else {
                return skeleton;
            };
            if degree[line[0] as usize] != 1 {
                line.reverse();
            }
            // The branch less the junction it joins.
            let gone: std::collections::HashSet<u32> =
                line[..line.len() - 1].iter().copied().collect();
            skeleton = skeleton.keep(|i| !gone.contains(&(i as u32)));
        }
    }
}

/// Where a branch from its tip (`at[0]`) is cut: at the innermost point whose ball
/// (`radius`, linear along each edge) holds the tip, walking in while the balls do, no
/// further in than the tip's own radius nor than `most` (below 1) of the branch's
/// length; `None` where that is the tip itself. A cut at an inner point is given as the
/// start of the edge after it, so that the point it falls on is the cut's.
fn ball_cut(at: &[DVec3], radius: &[f64], most: f64) -> Option<Cut> {
    let along = lengths_along(at);
    let limit = (most * along[along.len() - 1]).min(radius[0]);
    if limit.is_nan() || limit <= 0.0 {
        return None;
    }
    let tip = at[0];
    // How far the ball at point k reaches past the tip (held while not negative).
    let past = |k: usize| radius[k] - at[k].distance(tip);
    let cut = |edge: usize, t: f64| {
        let cut = if t >= 1.0 {
            Cut {
                edge: edge + 1,
                t: 0.0,
            }
        } else {
            Cut { edge, t }
        };
        (cut.edge > 0 || cut.t > 0.0).then_some(cut)
    };
    for k in 1..at.len() {
        let (before, now) = (past(k - 1), past(k));
        let span = along[k] - along[k - 1];
        if along[k] >= limit {
            // The limit falls on this edge: cut there, or where the balls let go first.
            let at_limit = if span > 0.0 {
                (limit - along[k - 1]) / span
            } else {
                0.0
            };
            let let_go = if now >= 0.0 {
                1.0
            } else {
                before.max(0.0) / (before - now)
            };
            return cut(k - 1, at_limit.min(let_go));
        }
        if now < 0.0 {
            // Along this edge the balls hold the tip up to where their reach, linear,
            // crosses zero.
            return cut(k - 1, before.max(0.0) / (before - now));
        }
    }
    // Only where lengths are not numbers.
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points every `step` from `from` to `to`, their radius linear from `r0` to `r1`.
    fn run(from: [f64; 3], to: [f64; 3], r0: f64, r1: f64, step: f64) -> Vec<([f64; 3], f64)> {
        let (a, b) = (DVec3::from(from), DVec3::from(to));
        let n = (a.distance(b) / step).round() as usize;
        (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                let at = if i == n { b } else { a.lerp(b, t) };
                (at.to_array(), r0 + t * (r1 - r0))
            })
            .collect()
    }

    #[test]
    fn a_limb_ends_a_radius_in_and_the_graph_keeps_its_shape() {
        // A trunk along x from -2 to 2 (radius 1) with a limb of radius 0.3 up y from
        // its middle to y = 2.5.
        let skeleton = crate::skeleton::geometry::graph_of_paths(&[
            run([-2.0, 0.0, 0.0], [0.0, 0.0, 0.0], 1.0, 1.0, 0.05),
            run([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], 1.0, 1.0, 0.05),
            run([0.0, 0.0, 0.0], [0.0, 2.5, 0.0], 1.0, 0.3, 0.05),
        ]);
        let trimmed = skeleton.tips_trimmed(None);
        assert_eq!(
            (trimmed.tip_count(), trimmed.component_count()),
            (3, 1),
            "the same graph"
        );
        let top = trimmed
            .points
            .iter()
            .map(|p| p.position[1])
            .fold(0.0, f64::max);
        assert!((top - 2.2).abs() < 1e-9, "the limb ends at {top}");
        // The trunk's ends, radius 1, go in by 1: its halves keep half their length.
        let xs = trimmed.points.iter().map(|p| p.position[0]);
        let (lo, hi) = xs.fold((0.0, 0.0), |(lo, hi): (f64, f64), x| (lo.min(x), hi.max(x)));
        assert!(
            (lo + 1.0).abs() < 1e-9 && (hi - 1.0).abs() < 1e-9,
            "{lo} {hi}"
        );
        // A cut on a point takes its place: no edge of length 0.
        let length = |&[a, b]: &[u32; 2]| {
            DVec3::from(trimmed.points[a as usize].position)
                .distance(trimmed.points[b as usize].position.into())
        };
        assert!(trimmed.edges.iter().all(|e| length(e) > 1e-9));
        // The new ends carry the radius there.
        let end = trimmed
            .points
            .iter()
            .find(|p| p.position[1] == top)
            .unwrap();
        assert!(
            end.radius.is_some_and(|r| r > 0.3 && r < 0.4),
            "{:?}",
            end.radius
        );
    }

    #[test]
    fn a_ball_on_a_stalk_keeps_its_centre() {
        // A stalk of radius 0.1 from x = 0 to 3, ending in a ball of radius 1.
        let mut stalk = run([0.0, 0.0, 0.0], [2.9, 0.0, 0.0], 0.1, 0.1, 0.1);
        stalk.push(([3.0, 0.0, 0.0], 1.0));
        let skeleton = crate::skeleton::geometry::graph_of_paths(&[
            run([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 0.1, 0.1, 0.1),
            stalk,
        ]);
        let far = |s: &Skeleton| s.points.iter().map(|p| p.position[0]).fold(0.0, f64::max);
        let trimmed = skeleton.tips_trimmed(None);
        assert!(far(&trimmed) > 2.85, "the stalk ends at {}", far(&trimmed));
        assert_eq!(trimmed.tip_count(), 3);
    }

    #[test]
    fn a_path_keeps_its_middle_and_no_radius_cuts_nothing() {
        let thick = crate::skeleton::geometry::graph_of_paths(&[run(
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            100.0,
            100.0,
            1.0,
        )]);
        let trimmed = thick.tips_trimmed(None);
        assert_eq!((trimmed.tip_count(), trimmed.component_count()), (2, 1));
        assert!(
            (trimmed.length() - 1.0).abs() < 1e-9,
            "{}",
            trimmed.length()
        );
        let points: Vec<[f64; 3]> = (0..=10).map(|i| [f64::from(i), 0.0, 0.0]).collect();
        let edges: Vec<[u32; 2]> = (0..10).map(|i| [i, i + 1]).collect();
        let bare = Skeleton::from_curves(&points, &edges, None);
        assert_eq!(bare.tips_trimmed(None), bare);
    }

    /// Straight edges along `paths`, which join where they meet (radius 1: the lengths
    /// are what counts).
    fn with_branches(paths: &[&[[f64; 3]]]) -> Skeleton {
        let paths: Vec<Vec<([f64; 3], f64)>> = paths
            .iter()
            .map(|path| path.iter().map(|&p| (p, 1.0)).collect())
            .collect();
        crate::skeleton::geometry::graph_of_paths(&paths)
    }

    #[test]
    fn short_branches_from_tips_go_shortest_first_and_the_rest_stays() {
        // A trunk from x = 0 to 10; at x = 5 a limb 3 long and a spur 0.4 long; at the
        // trunk's end two prongs, 0.3 and 0.45 long.
        let skeleton = with_branches(&[
            &[[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [10.0, 0.0, 0.0]],
            &[[5.0, 0.0, 0.0], [5.0, 3.0, 0.0]],
            &[[5.0, 0.0, 0.0], [5.0, -0.4, 0.0]],
            &[[10.0, 0.0, 0.0], [10.3, 0.0, 0.0]],
            &[[10.0, 0.0, 0.0], [10.0, 0.45, 0.0]],
        ]);
        assert_eq!(skeleton.tip_count(), 5);
        let pruned = skeleton.without_short_tips(0.5);
        // The spur and the shorter prong go; the longer prong then continues the trunk,
        // which is long, and stays.
        assert_eq!(pruned.tip_count(), 3);
        assert!(
            (pruned.length() - (10.0 + 3.0 + 0.45)).abs() < 1e-9,
            "{}",
            pruned.length()
        );
        assert_eq!(pruned.component_count(), 1);
        assert_eq!(skeleton.without_short_tips(0.0), skeleton);
    }

    #[test]
    fn a_short_path_and_a_loop_stay() {
        let path = with_branches(&[&[[0.0, 0.0, 0.0], [0.2, 0.0, 0.0]]]);
        assert_eq!(path.without_short_tips(1.0), path);
        // A square loop with a short spur: the spur goes, the loop stays.
        let looped = with_branches(&[
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0],
            ],
            &[[1.0, 0.0, 0.0], [1.2, -0.1, 0.0]],
        ]);
        let pruned = looped.without_short_tips(1.0);
        assert_eq!((pruned.cycle_count(), pruned.tip_count()), (1, 0));
        assert!((pruned.length() - 4.0).abs() < 1e-9);
    }
}
