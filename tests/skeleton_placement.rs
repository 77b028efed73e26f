//! Where a medial-axis skeleton's points go: smooth curves on the axis, or at the centre
//! of the shape's cross-section (`Placement`), on synthetic axes whose answer is known.

mod common;

use common::{along_edges, rectangle};
use geotracks::glam::DVec3;
use geotracks::mesh::io::MedialAxis;
use geotracks::skeleton::{
    medial_axis_skeleton_with_cycles, turning_per_length, Burn, Placement, Pruning, Skeleton,
};
use geotracks::{Options, SurfacePoint};
use std::collections::HashMap;

const K5: Options = Options::DEFAULT.with_k(5.0);

/// How much the skeleton's polylines turn per unit of length, times `scale`.
fn turning(skeleton: &Skeleton, scale: f64) -> f64 {
    turning_per_length(&skeleton.polyline_positions()) * scale
}

/// A deterministic wobble in [-1, 1]: three incommensurate waves.
fn wobble(x: f64, seed: f64) -> f64 {
    ((1.7 * x + seed).sin() + (4.3 * x + 2.0 * seed).sin() + (9.1 * x + 3.0 * seed).sin()) / 3.0
}

/// The middle sheet of a slab `w` long and `h` wide, `thickness` thick (its balls'
/// radius), with ragged long borders (moved by up to `ragged` across, in waves a few
/// cells long, as a sampled surface's axis has them) and a bumpy sheet (by `bumps` out
/// of its plane).
fn ragged_strip(w: f64, h: f64, thickness: f64, ragged: f64, bumps: f64) -> MedialAxis {
    let (nx, ny) = (160, 20);
    let flat = rectangle(nx, ny, w, h);
    let positions: Vec<[f64; 3]> = flat
        .positions()
        .iter()
        .map(|p| {
            let across = if p.y == 0.0 {
                -ragged * (1.0 + wobble(p.x * 6.0, 0.3)) / 2.0
            } else if p.y == h {
                ragged * (1.0 + wobble(p.x * 6.0, 1.9)) / 2.0
            } else {
                0.0
            };
            [
                p.x,
                p.y + across,
                bumps * wobble(p.x * 13.0 + p.y * 7.0, 0.7),
            ]
        })
        .collect();
    let radii = vec![thickness / 2.0; positions.len()];
    MedialAxis::from_parts(positions, radii, flat.triangles().to_vec(), Vec::new()).unwrap()
}

fn skeleton(axis: &MedialAxis, placement: Placement) -> Skeleton {
    let pruning = Pruning {
        tubularity: 0.0,
        protrusion: 0.0,
        ..Pruning::default_for(axis.diagonal())
    };
    let (skeleton, _) =
        medial_axis_skeleton_with_cycles(axis, Burn::Boundary, &K5, pruning, 0, placement).unwrap();
    skeleton
}

/// Where the fires meet on a sheet with ragged borders wanders from side to side; placed,
/// the trunk is a smooth curve on the axis (what turning is left: its ends bending into
/// the corners, and the sheet's bumps), where the thinned points zig-zag by more than
/// five times as much.
#[test]
fn a_wandering_ridge_comes_out_smooth_and_on_the_axis() {
    let axis = ragged_strip(8.0, 1.0, 0.8, 0.25, 0.002);
    let mesh = axis.surface.as_ref().unwrap();
    let diagonal = axis.diagonal();
    let (thinned, _) = Skeleton::of_medial_axis(&axis, Burn::Boundary, &K5).unwrap();
    let thinned = thinned.pruned(0.05 * diagonal);
    for placement in [Placement::OnAxis, Placement::Centred] {
        let placed = skeleton(&axis, placement);
        assert_eq!(
            (placed.cycle_count(), placed.component_count()),
            (0, 1),
            "{placement:?}"
        );
        assert_eq!(placed.tip_count(), thinned.tip_count(), "{placement:?}");
        let (before, after) = (turning(&thinned, diagonal), turning(&placed, diagonal));
        assert!(after < 10.0, "{placement:?}: turning {after}");
        assert!(
            before > 5.0 * after,
            "{placement:?}: turning {before} thinned"
        );
        for p in &placed.points {
            let at = DVec3::from(p.position);
            let r = p.radius.expect("a radius");
            assert!((0.0..=0.4 + 1e-9).contains(&r), "{placement:?}: radius {r}");
            if placement == Placement::OnAxis {
                let on = p.on.position(mesh);
                assert!(on.distance(at) < 1e-9, "off its surface point");
                let nearest = SurfacePoint::nearest(mesh, p.position).unwrap();
                assert!(nearest.position(mesh).distance(at) < 1e-9, "off the axis");
            }
        }
    }
}

/// A slab's middle sheet whose balls grow across it (radius 0.2 at one long border, 0.6
/// at the other): the fires from the borders meet half-way across, where the skeleton
/// stays on the axis; centred, it moves to the centroid of the balls' cut by the plane
/// across the strip, computed here on a fine raster, and its radius is the largest ball
/// centred there inside the shape.
#[test]
fn centred_points_sit_at_the_centre_of_the_cross_section() {
    let (w, h) = (8.0, 1.0);
    let flat = rectangle(160, 20, w, h);
    let radius = |y: f64| 0.2 + 0.4 * y;
    let positions: Vec<[f64; 3]> = flat.positions().iter().map(|p| p.to_array()).collect();
    let radii = positions.iter().map(|p| radius(p[1])).collect();
    let axis =
        MedialAxis::from_parts(positions, radii, flat.triangles().to_vec(), Vec::new()).unwrap();
    // The cross-section: discs centred (s, 0) of radius r(s) in the (y, z) plane.
    let centres: Vec<f64> = (0..=400).map(|i| i as f64 / 400.0).collect();
    let inside = |y: f64, z: f64| {
        centres
            .iter()
            .any(|&s| (y - s).powi(2) + z * z < radius(s).powi(2))
    };
    let (mut sum, mut count) = (0.0, 0.0);
    for i in 0..400 {
        for j in 0..400 {
            let (y, z) = (
                -0.5 + 2.5 * (i as f64 + 0.5) / 400.0,
                -1.0 + 2.0 * (j as f64 + 0.5) / 400.0,
            );
            if inside(y, z) {
                sum += y;
                count += 1.0;
            }
        }
    }
    let centroid = sum / count;
    let inscribed = centres
        .iter()
        .map(|&s| radius(s) - (centroid - s).abs())
        .fold(0.0, f64::max);
    assert!(
        centroid > 0.6,
        "the section leans to the thick side: {centroid}"
    );
    let middle = |skeleton: &Skeleton| -> Vec<DVec3> {
        along_edges(skeleton, 0.05)
            .into_iter()
            .filter(|p| (2.0..=6.0).contains(&p.x))
            .collect()
    };
    let on_axis = skeleton(&axis, Placement::OnAxis);
    let centred = skeleton(&axis, Placement::Centred);
    for (name, placed, y) in [
        ("on the axis", &on_axis, 0.5),
        ("centred", &centred, centroid),
    ] {
        let points = middle(placed);
        assert!(points.len() > 50, "{name}: {} points", points.len());
        for p in points {
            assert!((p.y - y).abs() < 0.03, "{name}: {p} off y = {y}");
            assert!(p.z.abs() < 0.02, "{name}: {p} out of the sheet's plane");
        }
    }
    // The points the straight run keeps (its ends bend towards the corners).
    let kept: Vec<_> = centred
        .points
        .iter()
        .filter(|p| (1.0..=7.0).contains(&p.position[0]) && (p.position[1] - centroid).abs() < 0.03)
        .collect();
    assert!(!kept.is_empty());
    for p in kept {
        let r = p.radius.unwrap();
        assert!(
            (r - inscribed).abs() < 0.04,
            "radius {r}, inscribed {inscribed}"
        );
    }
}
/// A plate's outline: an 8 × 8 square with four arms of different widths (3–5, three
/// to five times the plate's thickness, 1) and lengths, as unit cells. Each arm: the
/// rectangle it covers (x and y ranges) and where it ends.
struct Arm {
    x: [f64; 2],
    y: [f64; 2],
    end: [f64; 2],
}

fn plate_with_arms() -> (Vec<[i32; 2]>, Vec<Arm>) {
    let mut v: Vec<[i32; 2]> = Vec::new();
    let mut fill = |x: std::ops::Range<i32>, y: std::ops::Range<i32>| {
        for i in x {
            for j in y.clone() {
                v.push([i, j]);
            }
        }
    };
    fill(0..8, 0..8);
    fill(8..15, 3..6); // +x: 3 wide, 7 long
    fill(-6..0, 1..6); // -x: 5 wide, 6 long
    fill(2..5, 8..13); // +y: 3 wide, 5 long
    fill(2..6, -9..0); // -y: 4 wide, 9 long
    let arms = vec![
        Arm {
            x: [8.0, 15.0],
            y: [3.0, 6.0],
            end: [15.0, 4.5],
        },
        Arm {
            x: [-6.0, 0.0],
            y: [1.0, 6.0],
            end: [-6.0, 3.5],
        },
        Arm {
            x: [2.0, 5.0],
            y: [8.0, 13.0],
            end: [3.5, 13.0],
        },
        Arm {
            x: [2.0, 6.0],
            y: [-9.0, 0.0],
            end: [4.0, -9.0],
        },
    ];
    (v, arms)
}

/// The middle sheet of the plate (what its medial axis mostly is, the fins out to its
/// edges left out): the outline's unit cells cut into `n` × `n` squares of two
/// triangles each, every ball of radius one half (the plate's half thickness).
fn plate_sheet(cells: &[[i32; 2]], n: i32) -> MedialAxis {
    let mut ids: HashMap<[i32; 2], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut id = |p: [i32; 2]| {
        *ids.entry(p).or_insert_with(|| {
            positions.push([
                f64::from(p[0]) / f64::from(n),
                f64::from(p[1]) / f64::from(n),
                0.0,
            ]);
            positions.len() as u32 - 1
        })
    };
    let mut triangles = Vec::new();
    for &[x, y] in cells {
        for i in 0..n {
            for j in 0..n {
                let (u, v) = (x * n + i, y * n + j);
                let q = [[u, v], [u + 1, v], [u + 1, v + 1], [u, v + 1]].map(&mut id);
                triangles.push([q[0], q[1], q[2]]);
                triangles.push([q[0], q[2], q[3]]);
            }
        }
    }
    let radii = vec![0.5; positions.len()];
    MedialAxis::from_parts(positions, radii, triangles, Vec::new()).unwrap()
}

/// A plate's medial axis is mostly one sheet, its middle surface (with fins out to its
/// edges); its curve skeleton is that sheet's own medial axis, pruned: one branch along
/// the middle of every arm, out to the arm's end, joined on the plate.
#[test]
fn every_arm_of_a_plate_gets_a_branch_along_its_middle() {
    let (cells, arms) = plate_with_arms();
    let axis = plate_sheet(&cells, 4);
    assert_eq!((axis.betti_numbers().b0, axis.betti_numbers().b1), (1, 0));
    let pruning = Pruning::default_for(axis.diagonal());
    for placement in [Placement::OnAxis, Placement::Centred] {
        // At the defaults: by length, by tubularity (an arm is long for the plate's
        // thickness) and by protrusion (an arm reaches out of the plate's middle).
        let (skeleton, _) =
            medial_axis_skeleton_with_cycles(&axis, Burn::Boundary, &K5, pruning, 0, placement)
                .unwrap();
        assert_eq!(
            (skeleton.component_count(), skeleton.cycle_count()),
            (1, 0),
            "{placement:?}"
        );
        let degree = skeleton.degrees();
        let tips: Vec<[f64; 3]> = (0..skeleton.points.len())
            .filter(|&i| degree[i] == 1)
            .map(|i| skeleton.points[i].position)
            .collect();
        for arm in &arms {
            let width = (arm.x[1] - arm.x[0]).min(arm.y[1] - arm.y[0]);
            let along_x = arm.x[1] - arm.x[0] > width;
            let tip = tips
                .iter()
                .any(|t| (t[0] - arm.end[0]).hypot(t[1] - arm.end[1]) < width / 2.0 + 1.0);
            assert!(tip, "{placement:?}: no tip at {:?}: {tips:?}", arm.end);
            // Away from the plate and the arm's end, the branch runs along the arm's
            // middle, and it runs all the way.
            let [lo, hi] = if along_x { arm.x } else { arm.y };
            let middle = if along_x {
                (arm.y[0] + arm.y[1]) / 2.0
            } else {
                (arm.x[0] + arm.x[1]) / 2.0
            };
            let (from, to) = (lo + width / 2.0 + 1.0, hi - width / 2.0 - 0.5);
            let inside: Vec<[f64; 2]> = along_edges(&skeleton, 0.25)
                .iter()
                .map(|p| {
                    let [x, y, _] = p.to_array();
                    if along_x {
                        [x, y]
                    } else {
                        [y, x]
                    }
                })
                .filter(|&[s, across]| {
                    (from..=to).contains(&s) && (across - middle).abs() < width / 2.0
                })
                .collect();
            for &[s, across] in &inside {
                assert!(
                    (across - middle).abs() < 0.5,
                    "{placement:?}: {s}, {across}: off the middle of the arm ending at {:?}",
                    arm.end
                );
            }
            let mut s = from;
            while s <= to {
                assert!(
                    inside.iter().any(|q| (q[0] - s).abs() < 0.5),
                    "{placement:?}: a gap at {s} in the arm ending at {:?}",
                    arm.end
                );
                s += 0.5;
            }
        }
    }
}

/// Two sheets joined by one curve of the axis (a line element from a corner of one to
/// a corner of the other): placed on the axis, the skeleton crosses between them along
/// the curve, from end to end (no points put on the sheets near its ends, and its ends
/// not smoothed away from it).
#[test]
fn points_along_a_curve_of_the_axis_stay_on_it() {
    let square = rectangle(4, 4, 1.0, 1.0);
    let mut positions: Vec<[f64; 3]> = square.positions().iter().map(|p| p.to_array()).collect();
    let n = positions.len() as u32;
    positions.extend(square.positions().iter().map(|p| [p.x + 3.0, p.y, 0.0]));
    let mut triangles = square.triangles().to_vec();
    triangles.extend(square.triangles().iter().map(|t| t.map(|v| v + n)));
    // From the corner (1, 1) of the first square to the corner (3, 0) of the second.
    let (a, b) = (4 * 5 + 4, n);
    let radii = vec![0.1; positions.len()];
    let axis = MedialAxis::from_parts(positions, radii, triangles, vec![[a, b]]).unwrap();
    let (skeleton, _) = medial_axis_skeleton_with_cycles(
        &axis,
        Burn::Boundary,
        &K5,
        Pruning::NONE,
        0,
        Placement::OnAxis,
    )
    .unwrap();
    // The gap is crossed by the curve itself, from end to end.
    let at = |i: u32| DVec3::from(skeleton.points[i as usize].position);
    let crossing: Vec<(DVec3, DVec3)> = skeleton
        .edges
        .iter()
        .map(|&[a, b]| (at(a), at(b)))
        .filter(|(p, q)| p.x.min(q.x) < 1.5 && p.x.max(q.x) > 2.5)
        .collect();
    assert_eq!(crossing.len(), 1, "{crossing:?}");
    let (p, q) = crossing[0];
    let (p, q) = if p.x < q.x { (p, q) } else { (q, p) };
    assert!(p.distance(DVec3::new(1.0, 1.0, 0.0)) < 1e-9, "{p}");
    assert!(q.distance(DVec3::new(3.0, 0.0, 0.0)) < 1e-9, "{q}");
}
