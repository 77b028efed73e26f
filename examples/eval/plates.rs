//! `eval --plates`: the skeletons of plates made of a few large faces, built here, from
//! their meshes at several sampling spacings, as `geotracks skeleton MESH --spacing S`
//! makes them (axis computed, skeleton centred, default pruning). Sampled on grids,
//! such plates' skeletons grew a comb of extra branches (the guide's "Plates"
//! section): the tips counted here against what each shape's skeleton should have are
//! the measure of it.

#[path = "../plate_meshes/mod.rs"]
mod plate_meshes;

use geotracks::mesh::TriMesh;
use geotracks::skeleton::medial::{medial_axis, solid_cycles, MedialAxisOptions};
use geotracks::skeleton::{medial_axis_skeleton_with_cycles, Burn, Placement, Pruning};
use geotracks::Options;
use plate_meshes::{boxes, l_plate};
use std::time::Instant;

/// The sampling spacings measured, from a plate's thickness over 1.3 (0.15 for the
/// 0.2-thick ones) down to a seventh of it.
const SPACINGS: [f64; 5] = [0.15, 0.1, 0.07, 0.05, 0.03];

/// The plates measured: name, what the skeleton should have, mesh.
fn shapes() -> Vec<(&'static str, &'static str, TriMesh)> {
    let top = ([-1.0, 0.9, -0.6], [1.0, 1.1, 0.6]);
    let leg = |x: f64, z: f64| ([x - 0.035, 0.0, z - 0.035], [x + 0.035, 0.95, z + 0.035]);
    vec![
        (
            "board 2 × 0.2 × 1.2",
            "its middle sheet's medial axis: a middle segment, 2 to 4 tips",
            boxes(&[top]),
        ),
        (
            "L-shaped plate",
            "a branch along each arm: 2 tips (up to 7 with its convex corners)",
            l_plate(),
        ),
        (
            "table: the board on 4 legs 0.07 thick",
            "4 legs' feet, up to 4 more at the board's corners",
            boxes(&[
                top,
                leg(-0.85, -0.45),
                leg(0.85, -0.45),
                leg(-0.85, 0.45),
                leg(0.85, 0.45),
            ]),
        ),
    ]
}

/// Prints, per plate and spacing, the skeleton's tips and length (and the run's time),
/// or why there is none.
pub fn plates() -> Result<(), String> {
    let options = Options::DEFAULT.with_k(5.0);
    println!("Plates of few large faces, from their meshes (`geotracks skeleton MESH --spacing S`: axis computed, skeleton centred, default pruning): tips / length, and the time of axis and skeleton.\n");
    print!("| plate | its skeleton should have |");
    for s in SPACINGS {
        print!(" spacing {s} |");
    }
    println!();
    println!("|---|---|{}", "---:|".repeat(SPACINGS.len()));
    for (name, expected, mesh) in shapes() {
        print!("| {name} | {expected} |");
        let cycles = solid_cycles(&mesh);
        for spacing in SPACINGS {
            let start = Instant::now();
            let axis_options = MedialAxisOptions::default().with_spacing(Some(spacing));
            let cell = match medial_axis(&mesh, &axis_options) {
                Err(e) => format!("no axis: {e}"),
                Ok(axis) => {
                    let pruning = Pruning::default_for(axis.diagonal());
                    let skeleton = medial_axis_skeleton_with_cycles(
                        &axis,
                        Burn::Boundary,
                        &options,
                        pruning,
                        cycles,
                        Placement::Centred,
                    )
                    .map_err(|e| format!("{name} at spacing {spacing}: {e}"))?
                    .0;
                    format!(
                        "{} / {:.1} ({:.2} s)",
                        skeleton.tip_count(),
                        skeleton.length(),
                        start.elapsed().as_secs_f64()
                    )
                }
            };
            print!(" {cell} |");
        }
        println!();
    }
    Ok(())
}
