//! A spatial order for mesh elements: sorting them along a Morton (Z-order) curve keeps
//! elements that are close on the surface close in memory, which is what a wavefront
//! sweeping the surface needs from its caches, whatever order the file had.

use super::Topology;
use glam::DVec3;
use rayon::slice::ParallelSliceMut;

/// The indices `0..points.len()` sorted along a Morton curve through the points' bounding
/// box, on a 1024³ grid (ties keep index order). Key and index share one `u64`, so the
/// sort compares plain integers.
fn morton_order(points: &[DVec3]) -> Vec<u32> {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let extent = (hi - lo).max_element();
    let scale = if extent > 0.0 {
        (GRID - 1) as f64 / extent
    } else {
        0.0
    };
    let mut keyed: Vec<u64> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let q = (*p - lo) * scale;
            let code = spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2;
            code << 32 | i as u64
        })
        .collect();
    // Keys are distinct (the index is in them), so the parallel sort is deterministic.
    keyed.par_sort_unstable();
    keyed.into_iter().map(|k| k as u32).collect()
}

/// The edges of `mesh` in a spatial order (see the module docs): as numbered where the
/// numbering is spatial already (a grid's tiles, see
/// [`Topology::is_spatially_ordered`]), else along a Morton curve through their
/// midpoints.
pub(crate) fn spatial_edge_order<T: Topology>(mesh: &T) -> Vec<u32> {
    spatial_order(mesh, mesh.edge_count(), |e| {
        let [a, b] = mesh.edge_vertices(e);
        (mesh.position(a) + mesh.position(b)) * 0.5
    })
}

/// The faces in a spatial order, as [`spatial_edge_order`] orders edges (through their
/// centroids).
pub(crate) fn spatial_face_order<T: Topology>(mesh: &T) -> Vec<u32> {
    spatial_order(mesh, mesh.face_count(), |f| mesh.point(f, [1.0 / 3.0; 3]))
}

fn spatial_order<T: Topology>(mesh: &T, count: usize, point: impl Fn(u32) -> DVec3) -> Vec<u32> {
    if mesh.is_spatially_ordered() {
        (0..count as u32).collect()
    } else {
        let points: Vec<DVec3> = (0..count as u32).map(point).collect();
        morton_order(&points)
    }
}

/// Cells per axis of the grid the curve runs through.
const GRID: u64 = 1 << 10;

/// The low 10 bits of `x`, spread to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & (GRID - 1);
    x = (x | x << 16) & 0x30000ff;
    x = (x | x << 8) & 0x300f00f;
    x = (x | x << 4) & 0x30c30c3;
    (x | x << 2) & 0x9249249
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_interleaves_bits() {
        assert_eq!(spread(0b111), 0b1001001);
        assert_eq!(spread(0b1000000001), 1 << 27 | 1);
        assert_eq!(spread(GRID - 1).count_ones(), 10);
    }

    #[test]
    fn order_is_a_permutation_that_groups_near_points() {
        // Points on a line, given shuffled: the order sorts them.
        let xs = [5.0, 0.0, 3.0, 1.0, 4.0, 2.0];
        let points: Vec<DVec3> = xs.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect();
        let order = morton_order(&points);
        let sorted: Vec<f64> = order.iter().map(|&i| xs[i as usize]).collect();
        assert_eq!(sorted, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
        // Coincident points are fine.
        assert_eq!(morton_order(&[DVec3::ONE; 3]), [0, 1, 2]);
    }
}
