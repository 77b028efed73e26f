//! Medial axes of closed surfaces from the Voronoi diagram of their samples: where the
//! axis lies and how wide its balls are on shapes whose medial axis is known, the
//! skeletons built on it, and the surfaces that bound no solid.

mod common;

use common::plate_meshes::{boxes, l_plate};
use common::{along_edges, grid, sphere, torus};
use geotracks::mesh::io::{read_medial_axis, write_medial_axis, MedialAxis};
use geotracks::mesh::TriMesh;
use geotracks::skeleton::medial::solid_cycles;
use geotracks::skeleton::medial::{medial_axis, MedialAxisError, MedialAxisOptions};
use geotracks::skeleton::{medial_axis_skeleton_with_cycles, Burn, Placement, Pruning, Skeleton};
use geotracks::{Error, Options};
use std::collections::HashMap;

const K5: Options = Options::DEFAULT.with_k(5.0);

/// The closed surface of a union of unit voxels (quads between a filled voxel and an
/// empty one, wound outward), vertices shared on the integer grid.
fn voxels(filled: &[[i32; 3]]) -> TriMesh {
    let set: std::collections::HashSet<[i32; 3]> = filled.iter().copied().collect();
    let mut ids: HashMap<[i32; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut id = |p: [i32; 3]| {
        *ids.entry(p).or_insert_with(|| {
            positions.push(p.map(f64::from));
            positions.len() as u32 - 1
        })
    };
    let mut triangles = Vec::new();
    for &v in filled {
        for a in 0..3 {
            for s in [1, -1] {
                let mut n = v;
                n[a] += s;
                if set.contains(&n) {
                    continue;
                }
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                let mut base = v;
                base[a] += i32::from(s > 0);
                let corner = |db: i32, dc: i32| {
                    let mut p = base;
                    p[b] += db;
                    p[c] += dc;
                    p
                };
                let mut q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                if s < 0 {
                    q.reverse();
                }
                let q = q.map(&mut id);
                triangles.push([q[0], q[1], q[2]]);
                triangles.push([q[0], q[2], q[3]]);
            }
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A T of voxels: a bar 9 long across the top, a stem 5 long down from its middle,
/// both 1 × 1 thick.
fn t_shape() -> Vec<[i32; 3]> {
    let mut v: Vec<[i32; 3]> = (-4..=4).map(|x| [x, 5, 0]).collect();
    v.extend((0..5).map(|y| [0, y, 0]));
    v
}

/// The skeleton at the defaults (5 % pruning, tubularity 1, protrusion 0.5) with at
/// most `cycles`.
fn skeleton_of(axis: &MedialAxis, cycles: usize, placement: Placement) -> Skeleton {
    let pruning = Pruning::default_for(axis.diagonal());
    medial_axis_skeleton_with_cycles(axis, Burn::Boundary, &K5, pruning, cycles, placement)
        .unwrap()
        .0
}

/// The axis of a solid with one piece and no handle, at `spacing`, and its skeleton at
/// the defaults: both checked to be one piece without cycles.
fn one_tree(mesh: &TriMesh, spacing: f64) -> (MedialAxis, Skeleton) {
    let axis = axis(mesh, spacing);
    let betti = axis.betti_numbers();
    assert_eq!((betti.b0, betti.b1), (1, 0));
    assert_eq!(solid_cycles(mesh), 0);
    let skeleton = skeleton_of(&axis, 0, Placement::OnAxis);
    assert_eq!((skeleton.component_count(), skeleton.cycle_count()), (1, 0));
    (axis, skeleton)
}

/// Checks that some tip of `skeleton` lies within `within` of each of `ends` (x, y).
fn assert_tip_near_each(skeleton: &Skeleton, ends: &[[f64; 2]], within: f64) {
    let tips = tip_positions(skeleton);
    for end in ends {
        let near = tips
            .iter()
            .any(|t| (t[0] - end[0]).hypot(t[1] - end[1]) < within);
        assert!(near, "no tip near the arm's end {end:?}: tips {tips:?}");
    }
}

/// Where the skeleton's tips are.
fn tip_positions(skeleton: &Skeleton) -> Vec<[f64; 3]> {
    skeleton
        .degrees()
        .iter()
        .zip(&skeleton.points)
        .filter(|(d, _)| **d == 1)
        .map(|(_, p)| p.position)
        .collect()
}

fn axis(mesh: &TriMesh, spacing: f64) -> MedialAxis {
    medial_axis(
        mesh,
        &MedialAxisOptions::default().with_spacing(Some(spacing)),
    )
    .unwrap()
}

/// A closed rod along x from 0 to `length`: a prism of `sides` around, radius
/// `radius`, in rings `step` apart, each end closed by a fan to its centre.
fn rod(length: f64, radius: f64, sides: u32, step: f64) -> TriMesh {
    let rings = (length / step).round() as u32;
    let mut positions = Vec::new();
    for i in 0..=rings {
        let x = length * f64::from(i) / f64::from(rings);
        for k in 0..sides {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(sides);
            positions.push([x, radius * a.cos(), radius * a.sin()]);
        }
    }
    positions.push([0.0, 0.0, 0.0]);
    positions.push([length, 0.0, 0.0]);
    let id = |i: u32, k: u32| i * sides + k % sides;
    let (start, end) = ((rings + 1) * sides, (rings + 1) * sides + 1);
    let mut triangles = Vec::new();
    for i in 0..rings {
        for k in 0..sides {
            triangles.push([id(i, k), id(i, k + 1), id(i + 1, k + 1)]);
            triangles.push([id(i, k), id(i + 1, k + 1), id(i + 1, k)]);
        }
    }
    for k in 0..sides {
        triangles.push([start, id(0, k + 1), id(0, k)]);
        triangles.push([end, id(rings, k), id(rings, k + 1)]);
    }
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn a_rod_about_a_spacing_thick_keeps_its_axis() {
    // A rod 0.3 across sampled every 0.3 (a horn or a tail as thick as the mesh's
    // edges are long): the samples on its two sides are as close as neighbours along
    // it, but they face each other, and the facets between them are its axis. Taken
    // for the sampling's spikes, they went from the ends in, and nothing was left.
    let mesh = rod(3.0, 0.15, 8, 0.3);
    let (_, skeleton) = one_tree(&mesh, 0.3);
    for p in &skeleton.points {
        let [_, y, z] = p.position;
        assert!(
            y.hypot(z) < 0.15,
            "skeleton point {:?} outside the rod",
            p.position
        );
    }
    let xs = skeleton.points.iter().map(|p| p.position[0]);
    let (lo, hi) = xs.fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
    assert!(
        lo < 0.5 && hi > 2.5,
        "the skeleton runs from x = {lo} to {hi} of 0 to 3"
    );
}

#[test]
fn a_jittered_sphere_has_its_axis_at_the_centre() {
    let mesh = sphere(3, 0.01, 7);
    let axis = axis(&mesh, 1.0);
    for (p, r) in axis.positions.iter().zip(&axis.radii) {
        let d = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!(d < 0.15 && (0.85..1.01).contains(r), "{p:?} radius {r}");
    }
}

#[test]
fn a_spheroid_sampled_finer_than_its_faces_keeps_its_axis_straight() {
    // A prolate spheroid 6 × 2 × 2 of 320 faces: its medial axis is the segment of its
    // long axis between the centres of curvature of its ends, x = ±8/3. Sampled at a
    // fifth of its edges' length, the creases between its faces have axis sheets of
    // their own near the surface, which the spikes' test must leave out: a skeleton
    // through them wanders 0.6 off the axis and is three times as long.
    let unit = sphere(2, 0.0, 0);
    let positions: Vec<[f64; 3]> = unit
        .positions()
        .iter()
        .map(|p| [3.0 * p.x, p.y, p.z])
        .collect();
    let mesh = TriMesh::new(positions, unit.triangles().to_vec()).unwrap();
    // Its axis keeps a few small holes there (the solid has none): they are cut.
    // Untrimmed, the skeleton is the axis's extent; trimmed (the default), its ends
    // come in by no more than their radii.
    let axis = axis(&mesh, 0.04);
    let pruning = Pruning {
        trim_tips: false,
        ..Pruning::default_for(axis.diagonal())
    };
    let untrimmed =
        medial_axis_skeleton_with_cycles(&axis, Burn::Boundary, &K5, pruning, 0, Placement::OnAxis)
            .unwrap()
            .0;
    let skeleton = skeleton_of(&axis, 0, Placement::OnAxis);
    for skeleton in [&untrimmed, &skeleton] {
        assert_eq!((skeleton.component_count(), skeleton.cycle_count()), (1, 0));
    }
    let axis_length = 2.0 * 8.0 / 3.0;
    let length = untrimmed.length();
    assert!(
        length > 0.8 * axis_length && length < 2.0 * axis_length,
        "length {length} against the axis's {axis_length}"
    );
    let degrees = untrimmed.degrees();
    let ends: f64 = (0..untrimmed.points.len())
        .filter(|&i| degrees[i] == 1)
        .map(|i| untrimmed.points[i].radius.unwrap())
        .sum();
    let trimmed = skeleton.length();
    assert!(
        trimmed < length && trimmed >= length - ends - 1e-9,
        "trimmed {trimmed}, untrimmed {length}, the ends' radii {ends}"
    );
    for p in &skeleton.points {
        let off = p.position[1].hypot(p.position[2]);
        assert!(off < 0.35, "{:?} {off} off the axis", p.position);
    }
}

#[test]
fn a_stubby_box_keeps_its_axis() {
    // A box 3 × 2 × 2: its medial axis is a segment along its length (x from 1 to 2)
    // with sheets to its edges. Its skeleton's two halves are short next to its
    // thickness (tubularity below 1), but they are its trunk: it runs along its length
    // rather than shrinking to a point.
    let mesh = boxes(&[([0.0, 0.0, 0.0], [3.0, 2.0, 2.0])]);
    let (_, skeleton) = one_tree(&mesh, 0.1);
    assert_eq!(skeleton.tip_count(), 2);
    assert!(skeleton.length() > 2.0, "length {}", skeleton.length());
    // Through the middle (smoothed at its thickness, 1, it leans toward the corners
    // its ends run to), out to both ends: some edge passes within 0.25 of the box's
    // middle line at x (a straight run keeps only the points it needs).
    let curve = along_edges(&skeleton, 0.05);
    let near = |x: f64| {
        curve
            .iter()
            .any(|p| (p.x - x).abs() < 0.1 && (p.y - 1.0).hypot(p.z - 1.0) < 0.25)
    };
    assert!(near(1.2) && near(1.5) && near(1.8));
    let tips = tip_positions(&skeleton);
    assert!(
        tips.iter().any(|t| t[0] < 0.8) && tips.iter().any(|t| t[0] > 2.2),
        "{tips:?}"
    );
}

#[test]
fn a_torus_has_its_core_circle_as_axis_and_skeleton() {
    let (big, small) = (2.0, 0.5);
    let mesh = torus(64, 16, big, small);
    let axis = axis(&mesh, 0.1);
    for (p, r) in axis.positions.iter().zip(&axis.radii) {
        let off = ((p[0].hypot(p[1]) - big).powi(2) + p[2] * p[2]).sqrt();
        // Every ball lies in the tube. The cross-sections are regular 16-gons, all on
        // spheres about the core: their Voronoi vertices spread across the tube (the
        // skeleton below is what lies on the core), and a ball empty of samples bulges
        // out between them (by up to 10 % here, where they are 0.25 apart on the
        // outer side).
        assert!(
            r + off <= small * 1.15,
            "ball of radius {r} at {p:?} leaves the tube"
        );
    }
    assert_eq!(axis.betti_numbers().b0, 1);
    assert_eq!(solid_cycles(&mesh), 1);
    let skeleton = skeleton_of(&axis, 1, Placement::OnAxis);
    // The core loop, with the few short branches the star-shaped axis leaves.
    assert_eq!((skeleton.cycle_count(), skeleton.component_count()), (1, 1));
    assert!(skeleton.tip_count() <= 8, "{} tips", skeleton.tip_count());
    // The loop (what never burns) follows the core.
    let core_offset = |q: [f64; 3]| ((q[0].hypot(q[1]) - big).powi(2) + q[2] * q[2]).sqrt();
    let on_loop: Vec<f64> = skeleton
        .points
        .iter()
        .filter(|p| p.significance.is_infinite())
        .map(|p| core_offset(p.position))
        .collect();
    assert!(on_loop.len() > 20);
    let mean = on_loop.iter().sum::<f64>() / on_loop.len() as f64;
    let max = on_loop.iter().copied().fold(0.0, f64::max);
    assert!(
        mean < 0.1 * small && max < 0.3 * small,
        "loop off the core by {mean} on average, {max} at most"
    );
}

#[test]
fn a_boxs_axis_stays_inside_with_balls_at_most_half_its_thickness() {
    let mesh = voxels(&(0..4).map(|x| [x, 0, 0]).collect::<Vec<_>>());
    let axis = axis(&mesh, 0.2);
    for (p, r) in axis.positions.iter().zip(&axis.radii) {
        // A ball empty of samples 0.2 apart bulges out between them by a little.
        assert!(*r <= 0.5 + 0.02, "radius {r} at {p:?}");
        let inside = p[0] > 0.0 && p[0] < 4.0 && (0..3).skip(1).all(|c| p[c] > 0.0 && p[c] < 1.0);
        assert!(inside, "{p:?}");
    }
    // The middle of the box is covered: its centre line lies on the axis.
    for x in [1.0, 2.0, 3.0] {
        let near = axis.positions.iter().any(|p| {
            (p[0] - x).abs() < 0.2 && (p[1] - 0.5).abs() < 0.05 && (p[2] - 0.5).abs() < 0.05
        });
        assert!(near, "no axis point near the centre line at x = {x}");
    }
}

#[test]
fn every_arm_of_a_t_gets_a_branch() {
    let (_, skeleton) = one_tree(&voxels(&t_shape()), 0.25);
    // A square bar's medial axis is two diagonal sheets that reach its four edges, so
    // tips along the bars are the axis's own; what matters is that each arm's end
    // has one.
    // The arms end at x = ±4.5 (the bar) and y = 0 (the stem).
    assert_tip_near_each(&skeleton, &[[-4.0, 5.5], [5.0, 5.5], [0.5, 0.0]], 1.2);
}

#[test]
fn a_voxel_plates_axis_has_no_holes_and_a_branch_along_every_arm() {
    // A plus of voxels one thick: arms 3 wide reaching 4 past the middle square. Its
    // flat faces are sampled on a grid, so many samples lie on one sphere (each box of
    // 8 samples across the plate); the merged circumcentres' facets must still fit.
    let mut cells: Vec<[i32; 3]> = Vec::new();
    for a in -5..=5 {
        for b in -1..=1 {
            cells.push([a, b, 0]);
            if !(-1..=1).contains(&a) {
                cells.push([b, a, 0]);
            }
        }
    }
    let (_, skeleton) = one_tree(&voxels(&cells), 0.25);
    // The arms end at 6 and -5 (cells -5..=5) along x and y, their middles at 0.5.
    let ends = [[6.0, 0.5], [-5.0, 0.5], [0.5, 6.0], [0.5, -5.0]];
    assert_tip_near_each(&skeleton, &ends, 1.5);
    assert!(skeleton.tip_count() <= 8, "{} tips", skeleton.tip_count());
}

#[test]
fn a_part_of_few_large_faces_names_the_spacing_it_needs_and_gets_its_arms_at_one() {
    // An L-shaped plate, 4 × 3 with arms 1 wide, 0.5 thick, in 20 triangles (a machined
    // part's mesh): the mean edge length (the default spacing) is longer than the plate
    // is thick.
    let mesh = l_plate();
    match medial_axis(&mesh, &MedialAxisOptions::default()) {
        Err(Error::MedialAxis(e @ MedialAxisError::Empty { spacing, .. })) => {
            assert!((spacing - mesh.mean_edge_length()).abs() < 1e-12);
            let message = e.to_string();
            assert!(message.contains("smaller spacing"), "{message}");
            assert!(message.contains(&spacing.to_string()), "{message}");
        }
        other => panic!("expected an empty axis at the default spacing, got {other:?}"),
    }
    let (_, skeleton) = one_tree(&mesh, 0.1);
    assert_tip_near_each(&skeleton, &[[4.0, 0.5], [0.5, 3.0]], 0.6);
}

#[test]
fn plates_of_large_faces_get_a_branch_per_arm_and_no_comb() {
    // Each large face is sampled on its plane's lattice, so the two sides of a plate
    // have their samples in pairs straight across it (on each face's own barycentric
    // grid, the board had 19 tips at 0.05 and the L-shaped plate 19, a comb across
    // their middle sheets).
    let board = boxes(&[([-1.0, 0.9, -0.6], [1.0, 1.1, 0.6])]);
    for spacing in [0.05, 0.03] {
        let (_, skeleton) = one_tree(&board, spacing);
        let tips = skeleton.tip_count();
        assert!((2..=4).contains(&tips), "{tips} tips at spacing {spacing}");
        // Its middle sheet's medial axis: a segment along x at z = 0 (x within ±0.4),
        // on to corners of the sheet at its ends.
        for p in &skeleton.points {
            assert!((p.position[1] - 1.0).abs() < 0.1, "{:?}", p.position);
        }
        let curve = along_edges(&skeleton, 0.02);
        for k in -4..=4 {
            let x = 0.1 * f64::from(k);
            assert!(
                curve
                    .iter()
                    .any(|p| (p.x - x).abs() < 0.05 && p.z.abs() < 0.15),
                "no skeleton near the board's middle at x = {x}, spacing {spacing}"
            );
        }
        for t in tip_positions(&skeleton) {
            assert!(t[0].abs() > 0.6, "tip {t:?} short of the board's ends");
        }
    }
    for spacing in [0.1, 0.05] {
        let (_, skeleton) = one_tree(&l_plate(), spacing);
        assert_eq!(skeleton.tip_count(), 2, "at spacing {spacing}");
        assert_tip_near_each(&skeleton, &[[4.0, 0.5], [0.5, 3.0]], 0.6);
    }
}

#[test]
fn a_plate_far_from_the_origin_is_refused_where_its_coordinates_cannot_place_the_samples() {
    // At x = 10^15 a spacing of 0.05 is finer than the coordinates can tell apart (the
    // sampling looped for ever, then gave an axis of noise whose pruning panicked):
    // refused, naming the finest spacing they allow.
    let far = boxes(&[([1e15 - 1.0, 0.9, -0.6], [1e15 + 1.0, 1.1, 0.6])]);
    let options = MedialAxisOptions::default().with_spacing(Some(0.05));
    match medial_axis(&far, &options) {
        Err(Error::MedialAxis(e @ MedialAxisError::SpacingBelowResolution { least, .. })) => {
            assert!(least > 1e5 && least < 1e6, "{least}");
            let message = e.to_string();
            assert!(
                message.contains("0.05") && message.contains("origin"),
                "{message}"
            );
        }
        other => panic!("expected the spacing refused, got {other:?}"),
    }
    // A million units out, the same board gets the skeleton it gets at the origin.
    let near = boxes(&[([1e6 - 1.0, 0.9, -0.6], [1e6 + 1.0, 1.1, 0.6])]);
    let skeleton = skeleton_of(&axis(&near, 0.05), solid_cycles(&near), Placement::OnAxis);
    assert_eq!(skeleton.component_count(), 1);
    assert!(
        (2..=4).contains(&skeleton.tip_count()),
        "{} tips",
        skeleton.tip_count()
    );
}

#[test]
fn parts_that_run_through_each_other_give_the_axis_of_their_union() {
    // A cross of two bars, each a closed box of its own: the faces of each run through
    // the other's inside. The solid is their union, one piece with four arms.
    let bars = [
        ([0.0, 0.0, 0.0], [4.0, 1.0, 1.0]),
        ([1.5, -1.5, 0.2], [2.5, 2.5, 0.8]),
    ];
    let mesh = boxes(&bars);
    let axis = axis(&mesh, 0.1);
    assert_eq!(axis.betti_numbers().b0, 1);
    let inside = |p: &[f64; 3]| {
        bars.iter()
            .any(|(lo, hi)| (0..3).all(|k| p[k] > lo[k] - 1e-9 && p[k] < hi[k] + 1e-9))
    };
    for (p, r) in axis.positions.iter().zip(&axis.radii) {
        assert!(inside(p), "axis point {p:?} outside the solid");
        // No ball is walled in by a face inside the solid: where the bars cross, the
        // balls are as wide as the thinner bar allows, not cut in two by its faces.
        assert!(*r <= 0.5 + 0.02, "ball of radius {r} at {p:?}");
    }
    let crossing = axis
        .positions
        .iter()
        .zip(&axis.radii)
        .filter(|(p, _)| (p[0] - 2.0).abs() < 0.3 && (p[1] - 0.5).abs() < 0.3)
        .map(|(_, &r)| r)
        .fold(0.0, f64::max);
    assert!(
        crossing > 0.45,
        "the largest ball where the bars cross is {crossing}"
    );
    let skeleton = skeleton_of(&axis, solid_cycles(&mesh), Placement::OnAxis);
    assert_eq!((skeleton.component_count(), skeleton.cycle_count()), (1, 0));
}

#[test]
fn the_winding_of_the_file_does_not_matter() {
    let mesh = torus(48, 12, 2.0, 0.5);
    let tris = mesh.triangles();
    let positions: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let inward: Vec<[u32; 3]> = tris.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let mixed: Vec<[u32; 3]> = tris
        .iter()
        .enumerate()
        .map(|(i, &[a, b, c])| if i % 3 == 0 { [a, c, b] } else { [a, b, c] })
        .collect();
    let reference = axis(&mesh, 0.15);
    for triangles in [inward, mixed] {
        let other = axis(&TriMesh::new(positions.clone(), triangles).unwrap(), 0.15);
        assert_eq!(other.positions, reference.positions);
        assert_eq!(other.radii, reference.radii);
    }
}

#[test]
fn the_written_axis_reads_back_the_same() {
    let axis = axis(&torus(32, 10, 2.0, 0.5), 0.2);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("torus.ma");
    write_medial_axis(&path, &axis).unwrap();
    let back = read_medial_axis(&path).unwrap();
    assert_eq!(back.positions, axis.positions);
    assert_eq!(back.radii, axis.radii);
    let faces = |a: &MedialAxis| a.surface.as_ref().unwrap().triangles().to_vec();
    assert_eq!(faces(&back), faces(&axis));
    assert_eq!(back.betti_numbers(), axis.betti_numbers());
}

#[test]
fn surfaces_that_bound_no_solid_are_refused() {
    let open = grid(4, 1.0);
    let err = medial_axis(&open, &MedialAxisOptions::default()).unwrap_err();
    assert!(
        matches!(err, Error::MedialAxis(MedialAxisError::OpenSurface { .. })),
        "{err}"
    );
    // Three sheets on one edge: a tetrahedron's surface with a fin.
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, -1.0, 0.0],
    ];
    let mut triangles = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    triangles.push([0, 1, 4]);
    let fin = TriMesh::new(positions, triangles).unwrap();
    let err = medial_axis(&fin, &MedialAxisOptions::default()).unwrap_err();
    assert!(
        matches!(
            err,
            Error::MedialAxis(
                MedialAxisError::OpenSurface { .. } | MedialAxisError::NonManifoldSurface { .. }
            )
        ),
        "{err}"
    );
    // Two triangles back to back: closed, but no volume.
    let flat = TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2], [0, 2, 1]],
    );
    if let Ok(flat) = flat {
        let err = medial_axis(&flat, &MedialAxisOptions::default()).unwrap_err();
        assert!(
            matches!(
                err,
                Error::MedialAxis(MedialAxisError::Flat(_) | MedialAxisError::Empty { .. })
            ),
            "{err}"
        );
    }
}

#[test]
fn options_out_of_range_are_refused_before_any_work() {
    let mesh = torus(16, 8, 2.0, 0.5);
    for options in [
        MedialAxisOptions::default().with_spacing(Some(0.0)),
        MedialAxisOptions::default().with_spacing(Some(f64::NAN)),
        MedialAxisOptions::default().with_min_angle_degrees(0.0),
        MedialAxisOptions::default().with_min_angle_degrees(180.0),
    ] {
        let err = medial_axis(&mesh, &options).unwrap_err();
        assert!(
            matches!(
                err,
                Error::MedialAxis(MedialAxisError::InvalidOption { .. })
            ),
            "{err}"
        );
    }
    let err = medial_axis(
        &mesh,
        &MedialAxisOptions::default().with_spacing(Some(1e-4)),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            Error::MedialAxis(MedialAxisError::TooManySamples { .. })
        ),
        "{err}"
    );
}

#[test]
fn spot_gives_one_tree_along_its_body() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj");
    let mesh = geotracks::mesh::io::read_mesh(path).unwrap();
    let axis = medial_axis(&mesh, &MedialAxisOptions::default()).unwrap();
    let skeleton = skeleton_of(&axis, 0, Placement::OnAxis);
    assert_eq!(skeleton.component_count(), 1);
    assert_eq!(skeleton.cycle_count(), 0);
    let tips = skeleton.tip_count();
    assert!((4..=20).contains(&tips), "{tips} tips");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// Bumpy closed surfaces (a sphere's vertices moved in and out at random, up to
    /// folding it): an axis or a typed error, never a panic; an axis's balls are finite
    /// and no wider than the shape, and it is one piece where the surface is.
    #[test]
    fn bumpy_spheres_give_an_axis_or_an_error(
        seed in 1u64..1_000_000,
        jitter in 0.0f64..0.8,
        spacing in 0.15f64..0.6,
        angle in 20.0f64..120.0,
        span in 0.0f64..3.0,
    ) {
        let mesh = sphere(2, jitter, seed);
        let options = MedialAxisOptions::default()
            .with_spacing(Some(spacing))
            .with_min_angle_degrees(angle)
            .with_min_span(span);
        match medial_axis(&mesh, &options) {
            Ok(axis) => {
                let [lo, hi] = mesh.report().bounding_box;
                let diagonal = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
                proptest::prop_assert!(axis
                    .radii
                    .iter()
                    .all(|&r| r.is_finite() && r > 0.0 && r <= diagonal));
                proptest::prop_assert!(axis.betti_numbers().b0 >= 1);
            }
            Err(Error::MedialAxis(_)) => {}
            Err(e) => proptest::prop_assert!(false, "unexpected error {e}"),
        }
    }
}
