//! Where branches end: at the centre of the last medial ball that reaches a tip (an
//! option), and which short ones go once the skeleton is placed.

use super::geometry::lengths_along;
use super::Skeleton;
use glam::DVec3;

impl Skeleton {
    /// The skeleton with each branch from a tip cut back to the innermost point whose
    /// medial ball (`radius` per point) still holds the tip, walking in from the tip while
    /// the balls do: thinning leaves a branch running out to where the axis meets the
    /// surface, with balls shrinking to nothing, and the last ball that reaches that
    /// far is where the shape's end is centred (as a mean-curvature-flow skeleton's
    /// tip lies). A branch keeps at least one point besides the one it joins, and a
    /// component that is one path is cut from both ends, never past its middle.
    ///
    /// The rule takes the tip for the shape's end: on an axis whose branch stops short
    /// of the surface it cuts up to a radius more than the shape has there, and where
    /// the balls shrink faster than the branch runs (a pointed end) it cuts nothing.
    #[must_use]
    pub fn tips_trimmed(&self, radius: impl Fn(usize) -> f64) -> Skeleton {
        let degree = self.degrees();
        let mut removed = vec![false; self.points.len()];
        let position = |i: u32| DVec3::from(self.points[i as usize].position);
        for mut line in self.polylines() {
            let tip = |i: u32| degree[i as usize] == 1;
            let (first, last) = (line[0], line[line.len() - 1]);
            // A component that is one path is cut from both ends, to its middle at most.
            let both = tip(first) && tip(last);
            for from_tip in [tip(first), tip(last)] {
                if from_tip {
                    // The branch from the tip, less the point it joins.
                    let branch = &line[..line.len() - 1];
                    let most = if both {
                        branch.len().div_ceil(2)
                    } else {
                        branch.len()
                    };
                    let end = position(branch[0]);
                    let held = branch
                        .iter()
                        .take_while(|&&p| position(p).distance(end) <= radius(p as usize))
                        .count();
                    let cut = held.saturating_sub(1).min(most - 1);
                    for &p in &branch[..cut] {
                        removed[p as usize] = true;
                    }
                }
                line.reverse();
            }
        }
        self.keep(|i| !removed[i])
    }
}

impl Skeleton {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A trunk along x from -2 to 2 (radius 1) with a limb of radius 0.3 up y from its
    /// middle to y = 2.5; points every 0.05.
    fn trunk_and_limb() -> (Skeleton, Vec<f64>) {
        let mut points: Vec<[f64; 3]> = (-40..=40)
            .map(|i| [f64::from(i) * 0.05, 0.0, 0.0])
            .collect();
        let mut radii = vec![1.0; points.len()];
        let mut edges: Vec<[u32; 2]> = (0..80).map(|i| [i, i + 1]).collect();
        let mut previous = 40;
        for j in 1..=50 {
            let y = f64::from(j) * 0.05;
            points.push([0.0, y, 0.0]);
            radii.push(0.3);
            edges.push([previous, points.len() as u32 - 1]);
            previous = points.len() as u32 - 1;
        }
        (Skeleton::from_curves(&points, &edges, None), radii)
    }

    #[test]
    fn a_limb_ends_where_its_last_ball_reaches_the_tip() {
        let (skeleton, radii) = trunk_and_limb();
        let trimmed = skeleton.tips_trimmed(|i| radii[i]);
        assert_eq!((trimmed.tip_count(), trimmed.component_count()), (3, 1));
        let top = trimmed
            .points
            .iter()
            .map(|p| p.position[1])
            .fold(0.0, f64::max);
        // The ball at y = 2.2 is the last that reaches the tip at 2.5 …
        assert!((top - 2.2).abs() < 0.06, "the limb ends at {top}");
        // … and the trunk's ends, whose balls reach 1 past them, keep at least half of
        // it each: a path is never cut past its middle, and here joins the limb.
        let xs = trimmed.points.iter().map(|p| p.position[0]);
        let (lo, hi) = xs.fold((0.0, 0.0), |(lo, hi): (f64, f64), x| (lo.min(x), hi.max(x)));
        assert!(lo < -0.9 && hi > 0.9 && lo > -1.1 && hi < 1.1, "{lo} {hi}");
    }

    #[test]
    fn a_path_is_cut_from_both_ends_to_its_middle_at_most() {
        let points: Vec<[f64; 3]> = (0..=10).map(|i| [f64::from(i), 0.0, 0.0]).collect();
        let edges: Vec<[u32; 2]> = (0..10).map(|i| [i, i + 1]).collect();
        let skeleton = Skeleton::from_curves(&points, &edges, None);
        let trimmed = skeleton.tips_trimmed(|_| 100.0);
        assert_eq!(trimmed.component_count(), 1);
        assert!(!trimmed.points.is_empty() && trimmed.points.len() <= 3);
        assert!(trimmed
            .points
            .iter()
            .all(|p| (4.0..=6.0).contains(&p.position[0])));
        assert_eq!(
            skeleton.tips_trimmed(|_| 0.5),
            skeleton,
            "balls that reach no point"
        );
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
