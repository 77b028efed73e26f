//! Branches that fold back on themselves, straightened: each polyline between tips and
//! junctions replaced by the shortest path through its own points that may step across
//! a fold, from a point to another inside its medial ball.

use super::geometry::{lengths_along, Rebuild};
use super::placement::{AxisLookup, Search};
use super::{Skeleton, SkeletonPoint};
use crate::mesh::TriMesh;
use glam::DVec3;
use rstar::primitives::GeomWithData;
use rstar::RTree;
use std::collections::HashSet;

impl Skeleton {
    /// How many times longer than a step across it the way round a fold must be for the
    /// step to take it out: 2, a branch that comes back at least as far as it went. A
    /// bend (at most √2 round a right angle) stays.
    pub const FOLD: f64 = 2.0;

    /// The skeleton with its branches' folds taken out: each branch (a polyline between
    /// tips and junctions) becomes the shortest path from its first point to its last
    /// that goes from point to point along it or steps across a fold: from a point to
    /// one inside its medial ball (the point's radius: the step stays inside the solid)
    /// that the branch reaches only after at least [`Skeleton::FOLD`] times the step's
    /// length. A step that skips points is filled every `spacing` or so with the points
    /// of the axis's sheets (`mesh`, through `lookup`) nearest the segment.
    ///
    /// Why: the ridge where the fires met wanders, and on the tangle of thin sheets and
    /// curves that an axis sampled from a surface has along a thin limb, it runs up and
    /// down the limb. Smoothing along the branch cannot take out a fold longer than its
    /// window, and the branch comes out longer than the limb. A closed branch, or one
    /// that shares both ends with another (the two arcs of a loop would fold onto one
    /// path), is left as it is. Tips, junctions and the graph's topology are unchanged.
    pub(super) fn straightened(
        &self,
        mesh: &TriMesh,
        lookup: &AxisLookup,
        spacing: f64,
    ) -> Skeleton {
        let lines = self.polylines();
        let mut ends: Vec<[u32; 2]> = lines
            .iter()
            .filter(|line| line.len() > 1)
            .map(|line| end_pair(line))
            .collect();
        ends.sort_unstable();
        let shared: HashSet<[u32; 2]> = ends
            .windows(2)
            .filter(|w| w[0] == w[1])
            .map(|w| w[0])
            .collect();
        let mut rebuilt = Rebuild::new(self);
        for line in &lines {
            rebuilt.start(line[0]);
            let straight = line.len() > 2
                && line[0] != line[line.len() - 1]
                && !shared.contains(&end_pair(line));
            let at = self.line_positions(line);
            let steps = if straight {
                let reach: Vec<f64> = line
                    .iter()
                    .map(|&i| self.points[i as usize].radius.unwrap_or(0.0))
                    .collect();
                shortest_steps(&at, &reach)
            } else {
                (0..line.len()).collect()
            };
            for pair in steps.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                // Points along a step that skips some, on the axis near the segment (a
                // step is at most a ball long: a few hundred spacings at the most).
                let fill = if b > a + 1 && spacing > 0.0 {
                    ((at[a].distance(at[b]) / spacing).ceil() as usize).max(1)
                } else {
                    1
                };
                for k in 1..fill {
                    let t = k as f64 / fill as f64;
                    let near = if t < 0.5 { a } else { b };
                    let from = &self.points[line[near] as usize];
                    let target = at[a].lerp(at[b], t);
                    let Some((on, position)) = lookup.onto_sheets(mesh, from.on, target) else {
                        continue;
                    };
                    rebuilt.then_new(SkeletonPoint {
                        position: position.to_array(),
                        on,
                        radius: None,
                        ..*from
                    });
                }
                rebuilt.then_old(line[b]);
            }
        }
        rebuilt.finish()
    }
}

/// A polyline's two ends, lower first.
fn end_pair(line: &[u32]) -> [u32; 2] {
    let (a, b) = (line[0], line[line.len() - 1]);
    [a.min(b), a.max(b)]
}

/// The shortest path from the first of the points `at` (a polyline) to the last, as
/// indices: steps go between consecutive points, or across a fold, from a point to any
/// within its `reach` that the polyline reaches only after [`Skeleton::FOLD`] times as
/// long a way.
fn shortest_steps(at: &[DVec3], reach: &[f64]) -> Vec<usize> {
    let along = lengths_along(at);
    let tree = RTree::bulk_load(
        at.iter()
            .enumerate()
            .map(|(i, p)| GeomWithData::new(p.to_array(), i))
            .collect(),
    );
    let n = at.len();
    let mut steps: Vec<Vec<(u32, f64)>> = vec![Vec::new(); n];
    for i in 0..n {
        if i + 1 < n {
            let length = at[i].distance(at[i + 1]);
            steps[i].push((i as u32 + 1, length));
            steps[i + 1].push((i as u32, length));
        }
        if reach[i] > 0.0 {
            for near in tree.locate_within_distance(at[i].to_array(), reach[i] * reach[i]) {
                let (j, step) = (near.data, at[i].distance(at[near.data]));
                if j != i && (along[j] - along[i]).abs() >= Skeleton::FOLD * step {
                    steps[i].push((j as u32, step));
                }
            }
        }
    }
    let mut search = Search::new(n);
    search.run(&steps, 0, f64::INFINITY, |_, _| {});
    search
        .path_to(n as u32 - 1)
        .into_iter()
        .map(|i| i as usize)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::io::MedialAxis;
    use crate::surface::SurfacePoint;

    const STEP: f64 = 0.25;

    /// A grid of squares `STEP` wide over [0, w] × [0, h] in the plane z = 0, without the
    /// squares whose centre `hole` holds, as the sheet of an axis whose balls all have
    /// radius `r`; and a vertex's index from its grid coordinates.
    fn sheet(
        w: f64,
        h: f64,
        r: f64,
        hole: impl Fn(f64, f64) -> bool,
    ) -> (MedialAxis, impl Fn(f64, f64) -> u32) {
        let (nx, ny) = ((w / STEP) as u32, (h / STEP) as u32);
        let id =
            move |x: f64, y: f64| (y / STEP).round() as u32 * (nx + 1) + (x / STEP).round() as u32;
        let positions: Vec<[f64; 3]> = (0..=ny)
            .flat_map(|j| (0..=nx).map(move |i| [f64::from(i) * STEP, f64::from(j) * STEP, 0.0]))
            .collect();
        let mut triangles = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (f64::from(i) * STEP, f64::from(j) * STEP);
                if hole(x + STEP / 2.0, y + STEP / 2.0) {
                    continue;
                }
                let (a, b) = (id(x, y), id(x + STEP, y));
                let (c, d) = (id(x + STEP, y + STEP), id(x, y + STEP));
                triangles.extend([[a, b, c], [a, c, d]]);
            }
        }
        let radii = vec![r; positions.len()];
        (
            MedialAxis::from_parts(positions, radii, triangles, Vec::new()).unwrap(),
            id,
        )
    }

    /// A path from tip to tip through the grid points `corners` (steps of `STEP` along
    /// rows and columns between them), each point on its vertex with radius `r`.
    fn path(
        axis: &MedialAxis,
        id: impl Fn(f64, f64) -> u32,
        corners: &[[f64; 2]],
        r: f64,
    ) -> Skeleton {
        let mut at = vec![corners[0]];
        for w in corners.windows(2) {
            let ([x0, y0], [x1, y1]) = (w[0], w[1]);
            let steps = ((x1 - x0).abs().max((y1 - y0).abs()) / STEP).round() as u32;
            for k in 1..=steps {
                let t = f64::from(k) / f64::from(steps);
                at.push([x0 + t * (x1 - x0), y0 + t * (y1 - y0)]);
            }
        }
        let points = at
            .iter()
            .map(|&[x, y]| {
                let v = id(x, y);
                SkeletonPoint {
                    position: axis.positions[v as usize],
                    on: SurfacePoint::Vertex(v),
                    significance: 1.0,
                    tubularity: f64::INFINITY,
                    radius: Some(r),
                }
            })
            .collect();
        let edges = (1..at.len() as u32).map(|i| [i - 1, i]).collect();
        Skeleton {
            points,
            edges,
            punctured_faces: 0,
            added_cycles: 0,
            opened_cycles: 0,
        }
    }

    fn straightened(axis: &MedialAxis, skeleton: &Skeleton) -> Skeleton {
        let mesh = axis.surface.as_ref().unwrap();
        skeleton.straightened(mesh, &AxisLookup::new(mesh, axis), 0.1)
    }

    fn length(skeleton: &Skeleton) -> f64 {
        skeleton
            .edges
            .iter()
            .map(|&[a, b]| {
                DVec3::from(skeleton.points[a as usize].position)
                    .distance(skeleton.points[b as usize].position.into())
            })
            .sum()
    }

    #[test]
    fn a_branch_that_runs_up_and_down_its_limb_goes_straight() {
        let (axis, id) = sheet(8.0, 1.0, 0.5, |_, _| false);
        // Forward to x = 3, back to 2 along another row, then forward to the end.
        let folded = path(
            &axis,
            &id,
            &[
                [0.0, 0.5],
                [0.0, 0.25],
                [3.0, 0.25],
                [3.0, 0.75],
                [2.0, 0.75],
                [2.0, 0.5],
                [8.0, 0.5],
            ],
            0.5,
        );
        assert!(length(&folded) > 10.9);
        let straight = straightened(&axis, &folded);
        assert_eq!(
            (
                straight.tip_count(),
                straight.cycle_count(),
                straight.component_count()
            ),
            (2, 0, 1)
        );
        let line = &straight.polylines()[0];
        let x: Vec<f64> = line
            .iter()
            .map(|&i| straight.points[i as usize].position[0])
            .collect();
        let (first, last) = (line[0] as usize, line[line.len() - 1] as usize);
        assert_eq!(straight.points[first].position, [0.0, 0.5, 0.0]);
        assert_eq!(straight.points[last].position, [8.0, 0.5, 0.0]);
        assert!(
            x.windows(2).all(|w| w[1] >= w[0] - 1e-9),
            "not monotone: {x:?}"
        );
        assert!(length(&straight) < 8.5, "length {}", length(&straight));
        // Every point on the sheet, with its surface point where it is.
        let mesh = axis.surface.as_ref().unwrap();
        for p in &straight.points {
            assert!(p.position[2].abs() < 1e-12);
            assert!(p.on.position(mesh).distance(p.position.into()) < 1e-9);
        }
    }

    #[test]
    fn a_right_angle_stays() {
        // An L on a sheet whose balls (radius 0.5) reach round the corner: the way
        // round is at most √2 times a step across, short of a fold.
        let (axis, id) = sheet(4.0, 4.0, 0.5, |_, _| false);
        let l = path(&axis, &id, &[[0.5, 0.5], [3.5, 0.5], [3.5, 3.5]], 0.5);
        let kept = straightened(&axis, &l);
        assert_eq!(kept.points.len(), l.points.len());
        assert!((length(&kept) - length(&l)).abs() < 1e-12);
    }

    #[test]
    fn steps_stay_within_the_balls_round_a_bend() {
        // A U: two arms 1 wide, 1 apart, joined at x > 8; balls of radius 0.4.
        let (axis, id) = sheet(9.0, 3.0, 0.4, |x, y| x < 8.0 && (1.0..2.0).contains(&y));
        let u = path(
            &axis,
            &id,
            &[[0.0, 0.5], [8.5, 0.5], [8.5, 2.5], [0.0, 2.5]],
            0.4,
        );
        let straight = straightened(&axis, &u);
        let reach = straight
            .points
            .iter()
            .map(|p| p.position[0])
            .fold(0.0, f64::max);
        assert!(
            reach >= 8.5 - 0.4,
            "cut across the gap: reaches x = {reach}"
        );
        assert!(
            length(&straight) > 2.0 * 8.0 + 1.0,
            "length {}",
            length(&straight)
        );
        // The two arms of a loop between the same two points stay as they were.
        let mut ring = path(
            &axis,
            &id,
            &[[0.0, 0.5], [8.5, 0.5], [8.5, 2.5], [0.0, 2.5], [0.0, 0.5]],
            0.4,
        );
        let closing = ring.points.len() as u32 - 1;
        ring.edges.last_mut().unwrap()[1] = 0;
        ring.points.pop();
        assert_eq!(ring.edges[ring.edges.len() - 1], [closing - 1, 0]);
        let kept = straightened(&axis, &ring);
        assert_eq!(kept.points.len(), ring.points.len());
        assert_eq!(kept.cycle_count(), 1);
    }
}
