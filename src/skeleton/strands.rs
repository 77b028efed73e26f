//! Branches that leave a junction side by side, joined into one strand. Thinning a
//! pleated or ragged sheet can leave two ridges a fraction of the shape's thickness
//! apart where one curve belongs: a leg's branch that runs along the body's trunk for a
//! while before it meets it. Their junction then lies where the strands happen to touch
//! rather than where the parts of the solid merge, and once the branches are
//! straightened a limb cuts across the body to it.

use super::Skeleton;
use glam::DVec3;

impl Skeleton {
    /// How close a branch must stay to another to run with it, in its medial radii:
    /// 1, the other branch passes through each of its balls. Two limbs side by side
    /// whose surfaces touch lie two radii apart, and stay apart.
    pub const STRAND_RADII: f64 = 1.0;

    /// How far, in medial radii, a branch must run with another to be joined to it: 2.
    /// Two branches that part at a junction at an angle θ stay within
    /// [`Skeleton::STRAND_RADII`] of each other for 1 / sin θ radii, so only branches
    /// that part at less than 30° are joined; wider ones are left as they are.
    pub const STRAND_RUN_RADII: f64 = 2.0;

    /// The skeleton with the branches that leave a junction side by side joined: where
    /// every point of a branch, from the junction on, lies within
    /// [`Skeleton::STRAND_RADII`] of its medial radius of another branch from the same
    /// junction, over a run of at least [`Skeleton::STRAND_RUN_RADII`], the run goes and
    /// the rest of the branch joins the other one where the run ends: the junction moves
    /// to where the two part. Of the two, the one whose points have the smaller mean
    /// radius over the run goes (it lies off the middle of the shape). The longest run
    /// goes first, and the polylines are taken again after each.
    ///
    /// Components and cycles are unchanged: a run of `n` edges and `n − 1` points gives
    /// way to one edge, and the branch's rest is still joined to the junction, through
    /// the other branch. A closed branch is left as it is. Needs radii
    /// ([`Skeleton::with_radii`]); a point without one has none to judge by, and its
    /// branch is never joined.
    pub fn with_strands_joined(&self) -> Skeleton {
        let radius: Vec<f64> = self
            .points
            .iter()
            .map(|p| p.radius.unwrap_or(0.0))
            .collect();
        let at: Vec<DVec3> = self.points.iter().map(|p| p.position.into()).collect();
        let mut skeleton = self.clone();
        // Bounded by the edge count: a join never adds an edge (a run of one long edge
        // swaps it for another, the junction moving out along the other branch).
        for _ in 0..self.edges.len() {
            let Some(join) = longest_run(&skeleton, &at, &radius) else {
                break;
            };
            let gone: std::collections::HashSet<[u32; 2]> = join
                .run
                .windows(2)
                .map(|w| [w[0].min(w[1]), w[0].max(w[1])])
                .collect();
            skeleton
                .edges
                .retain(|&[a, b]| !gone.contains(&[a.min(b), a.max(b)]));
            let rest = join.run[join.run.len() - 1];
            skeleton.edges.push([join.onto, rest]);
        }
        // The runs' inner points lost their edges.
        let degree = skeleton.degrees();
        let isolated_before = self.degrees();
        skeleton.keep(|i| degree[i] > 0 || isolated_before[i] == 0)
    }
}

/// A run to take out: the points of a branch from its junction to where it parts from
/// the other (`run`; the last one stays, and the rest of the branch hangs from it), and
/// the point of the other branch that it joins (`onto`).
struct Join {
    run: Vec<u32>,
    onto: u32,
    length: f64,
}

/// Of every pair of branches from a junction, the longest run that one of them makes
/// along the other within [`Skeleton::STRAND_RADII`], if any is long enough.
fn longest_run(skeleton: &Skeleton, at: &[DVec3], radius: &[f64]) -> Option<Join> {
    let lines = skeleton.polylines();
    let degree = skeleton.degrees();
    // Per junction, its branches as they leave it; in the junctions' order, so that of
    // two runs equally long (a symmetric shape's) the same one goes on every run.
    let mut leaving: std::collections::BTreeMap<u32, Vec<Vec<u32>>> =
        std::collections::BTreeMap::new();
    for line in lines
        .iter()
        .filter(|l| l.len() > 2 && l[0] != l[l.len() - 1])
    {
        for oriented in [line.clone(), line.iter().rev().copied().collect()] {
            if degree[oriented[0] as usize] > 2 {
                leaving.entry(oriented[0]).or_default().push(oriented);
            }
        }
    }
    let mut best: Option<Join> = None;
    for branches in leaving.values() {
        for (a, along) in branches.iter().enumerate() {
            for (b, branch) in branches.iter().enumerate() {
                if a == b {
                    continue;
                }
                let Some(join) = run_along(along, branch, at, radius) else {
                    continue;
                };
                if best.as_ref().is_none_or(|best| join.length > best.length) {
                    best = Some(join);
                }
            }
        }
    }
    best
}

/// How far `branch` runs along `along` from their junction: each next point within
/// [`Skeleton::STRAND_RADII`] of its radius of `along`, matched to a point of `along`
/// that never goes back. A join if the run is long enough and lies off the middle of
/// the shape more than the part of `along` it runs with.
fn run_along(along: &[u32], branch: &[u32], at: &[DVec3], radius: &[f64]) -> Option<Join> {
    let point = |k: u32| at[k as usize];
    let (mut matched, mut end, mut length) = (0usize, 0usize, 0.0);
    // The branch keeps its last edge: its far end stays joined through it.
    while end + 2 < branch.len() {
        let p = point(branch[end + 1]);
        let r = radius[branch[end + 1] as usize];
        if r <= 0.0 {
            break;
        }
        let tolerance = Skeleton::STRAND_RADII * r;
        let Some((distance, to)) = nearest_ahead(along, matched, p, tolerance, at) else {
            break;
        };
        if distance > tolerance {
            break;
        }
        length += point(branch[end]).distance(p);
        (matched, end) = (to, end + 1);
    }
    let r = radius[branch[end] as usize];
    if end == 0 || matched == 0 || length < Skeleton::STRAND_RUN_RADII * r {
        return None;
    }
    let mean = |points: &[u32]| {
        points.iter().map(|&k| radius[k as usize]).sum::<f64>() / points.len() as f64
    };
    if mean(&branch[..=end]) > mean(&along[..=matched]) {
        return None;
    }
    Some(Join {
        run: branch[..=end].to_vec(),
        onto: along[matched],
        length,
    })
}

/// The point of `along`, from `from` on, nearest `p`, and its distance. The search stops
/// where the way along has gone several times as far as `p` lies from where it starts
/// (the strands zig-zag, so the way along is longer than the distance).
fn nearest_ahead(
    along: &[u32],
    from: usize,
    p: DVec3,
    tolerance: f64,
    at: &[DVec3],
) -> Option<(f64, usize)> {
    let start = at[along[from] as usize];
    let reach = 4.0 * (start.distance(p) + tolerance);
    let mut way = 0.0;
    let mut best: Option<(f64, usize)> = None;
    // Not the far end: a tip there would vanish.
    for k in from..along.len() - 1 {
        let q = at[along[k] as usize];
        if k > from {
            way += at[along[k - 1] as usize].distance(q);
        }
        if way > reach {
            break;
        }
        let d = q.distance(p);
        if best.is_none_or(|(b, _)| d < b) {
            best = Some((d, k));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::geometry::graph_of_paths;

    /// Points every 0.05 from `a` to `b`, both included, all of radius `r`.
    fn segment(a: [f64; 3], b: [f64; 3], r: f64) -> Vec<([f64; 3], f64)> {
        let (a, b) = (DVec3::from(a), DVec3::from(b));
        let n = (a.distance(b) / 0.05).round().max(1.0) as usize;
        (0..=n)
            .map(|k| (a.lerp(b, k as f64 / n as f64).to_array(), r))
            .collect()
    }

    fn chain(pieces: &[Vec<([f64; 3], f64)>]) -> Vec<([f64; 3], f64)> {
        let mut line: Vec<([f64; 3], f64)> = Vec::new();
        for piece in pieces {
            let skip = usize::from(!line.is_empty());
            line.extend(piece.iter().skip(skip));
        }
        line
    }

    fn junctions(skeleton: &Skeleton) -> Vec<DVec3> {
        let degree = skeleton.degrees();
        (0..skeleton.points.len())
            .filter(|&i| degree[i] > 2)
            .map(|i| skeleton.points[i].position.into())
            .collect()
    }

    /// A trunk along x from -3 to 3 (radius 1) and a limb that leaves it at x = -1,
    /// runs along it 0.2 off its side to x = `along`, and turns up y to 3.
    fn trunk_with_strand(along: f64) -> Skeleton {
        let trunk = segment([-3.0, 0.0, 0.0], [3.0, 0.0, 0.0], 1.0);
        let limb = chain(&[
            segment([-1.0, 0.0, 0.0], [-1.0, 0.2, 0.0], 0.9),
            segment([-1.0, 0.2, 0.0], [along, 0.2, 0.0], 0.9),
            segment([along, 0.2, 0.0], [along, 3.0, 0.0], 0.3),
        ]);
        graph_of_paths(&[trunk, limb])
    }

    #[test]
    fn a_limb_that_runs_along_the_trunk_joins_it_where_it_turns_away() {
        let before = trunk_with_strand(1.0);
        let joined = before.with_strands_joined();
        assert_eq!(joined.tip_count(), 3);
        assert_eq!(joined.component_count(), 1);
        assert_eq!(joined.cycle_count(), 0);
        let at = junctions(&joined);
        assert_eq!(at.len(), 1, "{at:?}");
        // The junction moved from x = -1 to where the limb leaves the trunk.
        assert!(
            at[0].x > 0.7 && at[0].x < 1.05 && at[0].y.abs() < 0.01,
            "{at:?}"
        );
        // The strand alongside is gone: 2 of the limb's length, less the step across.
        let shorter = before.length() - joined.length();
        assert!(shorter > 1.7 && shorter < 2.05, "{shorter}");
        assert!(joined
            .points
            .iter()
            .all(|p| !(p.position[1] > 0.1 && p.position[1] < 0.3 && p.position[0] < 0.6)));
    }

    #[test]
    fn branches_that_part_at_a_junction_stay_as_they_are() {
        // A limb up y from the trunk's middle (a right angle), one at 45°, and a thick
        // limb that runs along the trunk for less than two of its radii before it
        // turns away.
        let trunk = segment([-3.0, 0.0, 0.0], [3.0, 0.0, 0.0], 1.0);
        let up = segment([0.0, 0.0, 0.0], [0.0, 3.0, 0.0], 0.3);
        let slanted = segment([-2.0, 0.0, 0.0], [0.0, 0.0, 2.0], 0.3);
        let short = chain(&[
            segment([1.0, 0.0, 0.0], [1.0, 0.2, 0.0], 0.9),
            segment([1.0, 0.2, 0.0], [1.4, 0.2, 0.0], 0.9),
            segment([1.4, 0.2, 0.0], [1.4, 3.0, 0.0], 0.9),
        ]);
        let before = graph_of_paths(&[trunk, up, slanted, short]);
        let joined = before.with_strands_joined();
        assert!(joined == before, "{:?}", junctions(&joined));
    }

    #[test]
    fn two_strands_of_a_loop_keep_the_loop() {
        // Two arcs between the same two junctions, 0.2 apart for their whole length,
        // each junction on a stem.
        let stems = [
            segment([-3.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 1.0),
            segment([1.0, 0.0, 0.0], [3.0, 0.0, 0.0], 1.0),
        ];
        let straight = segment([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0);
        let beside = chain(&[
            segment([-1.0, 0.0, 0.0], [-1.0, 0.2, 0.0], 0.9),
            segment([-1.0, 0.2, 0.0], [1.0, 0.2, 0.0], 0.9),
            segment([1.0, 0.2, 0.0], [1.0, 0.0, 0.0], 0.9),
        ]);
        let before = graph_of_paths(&[stems[0].clone(), stems[1].clone(), straight, beside]);
        let joined = before.with_strands_joined();
        assert_eq!(joined.cycle_count(), 1);
        assert_eq!((joined.tip_count(), joined.component_count()), (2, 1));
        let mut seen = std::collections::HashSet::new();
        assert!(joined
            .edges
            .iter()
            .all(|&[a, b]| a != b && seen.insert([a.min(b), a.max(b)])));
    }

    #[test]
    fn without_radii_nothing_is_joined() {
        let mut before = trunk_with_strand(1.0);
        for p in &mut before.points {
            p.radius = None;
        }
        assert!(before.with_strands_joined() == before);
    }
}
