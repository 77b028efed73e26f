//! Skeletons of small random medial axes: a skeleton or an error, never a panic; the
//! skeleton has no more components than the axis and, once its extra loops are opened,
//! no more cycles than allowed.
//!
//! Bytes → axis: 3–12 vertices with small integer coordinates (so faces are often
//! degenerate, coplanar, folded or non-manifold) and radii from 0 to 3, 0–16 faces and
//! 0–6 free edges with indices mod n; then the fire (from the border or by radius), the
//! pruning (none, the defaults, or thresholds from the bytes), how many cycles may stay
//! (0, 1 or all) and where the points go.
#![no_main]

use geotracks::mesh::io::MedialAxis;
use geotracks::skeleton::{medial_axis_skeleton_with_cycles, Burn, Placement, Pruning};
use geotracks::Options;
use libfuzzer_sys::fuzz_target;

#[path = "common/bytes.rs"]
mod bytes;
use bytes::Bytes;

fuzz_target!(|data: &[u8]| {
    let mut bytes = Bytes(data);
    let n = 3 + u32::from(bytes.next()) % 10;
    let positions: Vec<[f64; 3]> = (0..n)
        .map(|_| [0; 3].map(|_| f64::from(bytes.next() % 5)))
        .collect();
    let radii: Vec<f64> = (0..n).map(|_| f64::from(bytes.next() % 7) * 0.5).collect();
    let faces = bytes.next() % 17;
    let triangles: Vec<[u32; 3]> = (0..faces)
        .map(|_| [0; 3].map(|_| u32::from(bytes.next()) % n))
        .collect();
    let wires = bytes.next() % 7;
    let edges: Vec<[u32; 2]> = (0..wires)
        .map(|_| [0; 2].map(|_| u32::from(bytes.next()) % n))
        .collect();
    let Ok(axis) = MedialAxis::from_parts(positions, radii, triangles, edges) else {
        return;
    };
    let burn = if bytes.next() % 2 == 0 {
        Burn::Boundary
    } else {
        Burn::Radius
    };
    let diagonal = axis.diagonal();
    let pruning = match bytes.next() % 3 {
        0 => Pruning::NONE,
        1 => Pruning::default_for(diagonal),
        _ => Pruning {
            erosion_thickness: f64::from(bytes.next() % 8) * 0.25,
            tubularity: f64::from(bytes.next() % 8) * 0.25,
            protrusion: f64::from(bytes.next() % 8) * 0.25,
            trim_tips: bytes.next() % 2 == 0,
        },
    };
    let max_cycles = [0, 1, usize::MAX][usize::from(bytes.next() % 3)];
    let placement = if bytes.next() % 2 == 0 {
        Placement::OnAxis
    } else {
        Placement::Centred
    };
    let options = Options::DEFAULT.with_k(f64::from(1 + bytes.next() % 3));
    let Ok((skeleton, _)) =
        medial_axis_skeleton_with_cycles(&axis, burn, &options, pruning, max_cycles, placement)
    else {
        return;
    };
    let betti = axis.betti_numbers();
    assert!(
        skeleton.component_count() <= betti.b0.max(1),
        "{skeleton:?}"
    );
    assert!(
        skeleton.cycle_count() <= max_cycles.min(betti.b1) + skeleton.added_cycles,
        "{} cycles, at most {max_cycles} of b1 = {}",
        skeleton.cycle_count(),
        betti.b1
    );
});
