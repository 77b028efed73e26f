//! The kept Voronoi facets as triangles, once the circumcentres that coincide are one
//! vertex.
//!
//! Samples on one sphere (a grid on a flat face, the corners of a box) make several
//! tetrahedra with one circumcentre; merged, their facets are convex polygons with
//! vertices in a row along their sides, and a side of one facet can run straight past
//! a vertex that its neighbour has on that side (the perturbed tetrahedralization went
//! round it on one side and not on the other). Fanned as they were, the polygons made
//! flat triangles, and the neighbours' sides did not match: each such place left a
//! cycle in the axis that the solid does not have (a voxel plate's axis had hundreds).
//! So each facet's sides are first split at the vertices along them
//! ([`split_at_vertices_along_sides`]), then the polygon is cut into triangles that are
//! never flat ([`triangulate`]).

use crate::mesh::FaceFrame;
use glam::DVec3;

/// Where `v` lies along the segment `a c`: its parameter in (0, 1) when it lies on the
/// segment, strictly between its ends (a triangle `a v c` too flat for a mesh to keep).
fn along(positions: &[[f64; 3]], a: u32, c: u32, v: u32) -> Option<f64> {
    let [pa, pc, pv] = [a, c, v].map(|i| DVec3::from_array(positions[i as usize]));
    if v == a || v == c || pv == pa || pv == pc || FaceFrame::of_triangle([pa, pv, pc]).is_some() {
        return None;
    }
    let t = (pv - pa).dot(pc - pa) / (pc - pa).length_squared();
    (t > 0.0 && t < 1.0).then_some(t)
}

/// Whether the corner `b` between `a` and `c` is flat (the three in a row).
fn flat(positions: &[[f64; 3]], [a, b, c]: [u32; 3]) -> bool {
    FaceFrame::of_triangle([a, b, c].map(|i| DVec3::from_array(positions[i as usize]))).is_none()
}

/// Every facet's ring with each side `a c` split at the vertices that other facets have
/// along it: the chain of neighbours (by the facets' sides) from `a` that lie on the
/// segment, each farther along than the one before.
pub(super) fn split_at_vertices_along_sides(rings: &mut [Vec<u32>], positions: &[[f64; 3]]) {
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); positions.len()];
    for ring in rings.iter() {
        for (i, &a) in ring.iter().enumerate() {
            let b = ring[(i + 1) % ring.len()];
            for (x, y) in [(a, b), (b, a)] {
                if !neighbours[x as usize].contains(&y) {
                    neighbours[x as usize].push(y);
                }
            }
        }
    }
    let mut split = Vec::new();
    for ring in rings.iter_mut() {
        // Most rings have no vertex along a side: they stay as they are.
        let (mut changed, n) = (false, ring.len());
        split.clear();
        for i in 0..n {
            let (a, c) = (ring[i], ring[(i + 1) % n]);
            split.push(a);
            let (mut at, mut t) = (a, 0.0);
            while let Some((next, s)) = neighbours[at as usize]
                .iter()
                .filter_map(|&v| along(positions, a, c, v).map(|s| (v, s)))
                .filter(|&(_, s)| s > t)
                .min_by(|x, y| x.1.total_cmp(&y.1))
            {
                split.push(next);
                changed = true;
                (at, t) = (next, s);
            }
        }
        if changed {
            ring.clone_from(&split);
        }
    }
}

/// Cuts the convex polygon `ring` into triangles that are not flat, every side of it a
/// side of one of them: an ear is cut at a corner that is not flat, and not at one whose
/// cut would leave the rest of the polygon in a row (that row would then be a side
/// with vertices along it that no triangle has). What has no area at all (every corner
/// flat) becomes a path of curves along it.
pub(super) fn triangulate(
    ring: &[u32],
    positions: &[[f64; 3]],
    triangles: &mut Vec<[u32; 3]>,
    curves: &mut Vec<[u32; 2]>,
) {
    let corner = |r: &[u32], i: usize| {
        let n = r.len();
        [r[(i + n - 1) % n], r[i], r[(i + 1) % n]]
    };
    if (0..ring.len()).all(|i| !flat(positions, corner(ring, i))) {
        // No corner flat: the fan from the first vertex.
        for w in ring[1..].windows(2) {
            triangles.push([ring[0], w[0], w[1]]);
        }
        return;
    }
    let has_area = |r: &[u32]| (0..r.len()).any(|i| !flat(positions, corner(r, i)));
    let mut ring = ring.to_vec();
    let mut rest = Vec::with_capacity(ring.len());
    while ring.len() > 3 {
        let ear = (0..ring.len()).find(|&i| {
            if flat(positions, corner(&ring, i)) {
                return false;
            }
            rest.clear();
            rest.extend(
                ring.iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, &v)| v),
            );
            has_area(&rest)
        });
        let Some(i) = ear else { break };
        triangles.push(corner(&ring, i));
        ring.remove(i);
    }
    if ring.len() == 3 && has_area(&ring) {
        triangles.push([ring[0], ring[1], ring[2]]);
    } else {
        // In a row: its closing side runs back over the others.
        curves.extend(ring.windows(2).map(|w| [w[0], w[1]]));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The area covered by `triangles`, and whether each is non-flat.
    fn area(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> f64 {
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| DVec3::from_array(positions[i as usize]));
                assert!(FaceFrame::of_triangle([a, b, c]).is_some(), "flat {t:?}");
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Points of the plane z = 0.
    fn in_the_plane(xy: &[(f64, f64)]) -> Vec<[f64; 3]> {
        xy.iter().map(|&(x, y)| [x, y, 0.0]).collect()
    }

    /// `ring` cut into triangles, and the curves left.
    fn triangulated(ring: &[u32], positions: &[[f64; 3]]) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
        let (mut triangles, mut curves) = (Vec::new(), Vec::new());
        triangulate(ring, positions, &mut triangles, &mut curves);
        (triangles, curves)
    }

    /// Each side of `ring` is a side of exactly one triangle.
    fn sides_covered(ring: &[u32], triangles: &[[u32; 3]]) {
        for (i, &a) in ring.iter().enumerate() {
            let b = ring[(i + 1) % ring.len()];
            let uses = triangles
                .iter()
                .filter(|t| (0..3).any(|k| [t[k], t[(k + 1) % 3]] == [a, b]))
                .count();
            assert_eq!(uses, 1, "side {a}-{b} in {triangles:?}");
        }
    }

    #[test]
    fn a_square_with_vertices_along_its_sides_gets_no_flat_triangle() {
        // 3 × 3 points on a square's border, counter-clockwise: the corners and the
        // middles of the sides.
        let positions = in_the_plane(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (2.0, 2.0),
            (1.0, 2.0),
            (0.0, 2.0),
            (0.0, 1.0),
        ]);
        let ring: Vec<u32> = (0..8).collect();
        let (triangles, curves) = triangulated(&ring, &positions);
        assert!(curves.is_empty());
        assert!((area(&positions, &triangles) - 4.0).abs() < 1e-12);
        sides_covered(&ring, &triangles);
    }

    #[test]
    fn a_triangle_with_its_vertices_along_one_side_is_fanned_from_the_far_corner() {
        // Cutting the ear at 0 or 4 first would be fine; cutting it at the apex (5)
        // would leave 0..4 in a row.
        let positions = in_the_plane(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (4.0, 0.0),
            (2.0, 1.0),
        ]);
        let ring: Vec<u32> = vec![5, 0, 1, 2, 3, 4];
        let (triangles, curves) = triangulated(&ring, &positions);
        assert!(curves.is_empty());
        assert_eq!(triangles.len(), 4);
        assert!((area(&positions, &triangles) - 2.0).abs() < 1e-12);
        sides_covered(&ring, &triangles);
    }

    #[test]
    fn a_polygon_in_a_row_becomes_a_path() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let (triangles, curves) = triangulated(&[0, 1, 2], &positions);
        assert!(triangles.is_empty());
        assert_eq!(curves, vec![[0, 1], [1, 2]]);
    }

    #[test]
    fn a_side_that_runs_past_its_neighbours_vertices_is_split_there() {
        // Two squares side by side, sharing the segment from (1, 0) to (1, 2); the
        // right one has (1, 1) on it, and a vertex past it too, (1, 1.5); the left
        // one goes straight from (1, 0) to (1, 2).
        let positions = in_the_plane(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 2.0),
            (0.0, 2.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (1.0, 1.0),
            (1.0, 1.5),
        ]);
        let mut rings = vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2, 7, 6]];
        split_at_vertices_along_sides(&mut rings, &positions);
        assert_eq!(rings[0], vec![0, 1, 6, 7, 2, 3]);
        assert_eq!(rings[1], vec![1, 4, 5, 2, 7, 6]);
        // Triangulated, the two share their sides along the segment: every edge of
        // the union is in one triangle (border) or two (inside).
        let (mut triangles, mut curves) = (Vec::new(), Vec::new());
        for ring in &rings {
            let (t, c) = triangulated(ring, &positions);
            triangles.extend(t);
            curves.extend(c);
        }
        assert!(curves.is_empty());
        assert!((area(&positions, &triangles) - 4.0).abs() < 1e-12);
        let mut uses = std::collections::HashMap::new();
        for t in &triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        let border = uses.values().filter(|&&u| u == 1).count();
        assert_eq!(border, 6, "{uses:?}");
        assert!(uses.values().all(|&u| u <= 2));
    }
}
