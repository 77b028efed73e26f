use super::*;
use crate::GridGeometry;
use geotracks::mesh::TriMesh;
use proptest::prelude::*;
use std::collections::{BTreeSet, HashMap};

/// A `wide × high` grid of random elevations (to 0.5), `holes` of its samples NODATA
/// (drawn from `seed`).
fn grid(wide: usize, high: usize, seed: u64, holes: f64) -> ElevationGrid {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let geometry = GridGeometry {
        ncols: wide,
        nrows: high,
        lower_left: [100.0, -50.0],
        spacing: [2.0, 3.0],
    };
    let values = (0..wide * high)
        .map(|_| {
            let z = (next() * 4.0).round() / 8.0;
            if next() < holes {
                f64::NAN
            } else {
                z
            }
        })
        .collect();
    ElevationGrid::new(geometry, values).unwrap()
}

/// Everything the contract of [`Topology`] says, checked on `s`.
fn check_contract<T: Topology>(s: &T) {
    let mut faces_of_vertex = vec![BTreeSet::new(); s.vertex_count()];
    let mut edges_of_vertex = vec![BTreeSet::new(); s.vertex_count()];
    let mut faces_of_edge = vec![BTreeSet::new(); s.edge_count()];
    for f in 0..s.face_count() as u32 {
        let (t, edges) = (s.face_vertices(f), s.face_edges(f));
        assert!(s.frame(f).y2 > 0.0, "face {f} has area");
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            assert_eq!(
                s.edge_vertices(edges[i]),
                [a.min(b), a.max(b)],
                "face {f} edge {i}"
            );
            assert_eq!(s.edge_slot(f, edges[i]), Some(i));
            faces_of_vertex[a as usize].insert(f);
            faces_of_edge[edges[i] as usize].insert(f);
            edges_of_vertex[a as usize].insert(edges[i]);
            edges_of_vertex[b as usize].insert(edges[i]);
        }
    }
    for e in 0..s.edge_count() as u32 {
        let listed: BTreeSet<u32> = s.edge_faces(e).iter().copied().collect();
        assert_eq!(
            listed.len(),
            s.edge_faces(e).len(),
            "edge {e} lists a face twice"
        );
        assert!(!listed.is_empty(), "edge {e} has a face");
        assert_eq!(listed, faces_of_edge[e as usize], "faces of edge {e}");
    }
    for v in 0..s.vertex_count() as u32 {
        let faces: BTreeSet<u32> = s.vertex_faces(v).iter().copied().collect();
        assert_eq!(faces, faces_of_vertex[v as usize], "faces of vertex {v}");
        let edges: BTreeSet<u32> = s.vertex_edges(v).iter().copied().collect();
        assert_eq!(edges.len(), s.vertex_edges(v).len());
        assert_eq!(edges, edges_of_vertex[v as usize], "edges of vertex {v}");
        assert!(s.vertex_wires(v).is_empty());
    }
}

/// The triangles of a surface as their corners' positions, in cyclic order from the
/// least, with each one's frame.
fn triangles<T: Topology>(s: &T) -> HashMap<[[u64; 3]; 3], FaceFrame> {
    (0..s.face_count() as u32)
        .map(|f| {
            let p = s
                .face_vertices(f)
                .map(|v| Topology::position(s, v).to_array().map(f64::to_bits));
            let first = (0..3).min_by_key(|&i| p[i]).unwrap();
            (std::array::from_fn(|i| p[(first + i) % 3]), s.frame(f))
        })
        .collect()
}

/// The surface's faces are the mesh's, corner for corner and frame for frame (to the
/// bit), and it keeps the contract.
fn same_as_mesh(surface: &GridSurface, mesh: &TriMesh) {
    check_contract(surface);
    assert_eq!(surface.face_count(), mesh.face_count());
    assert_eq!(surface.edge_count(), mesh.edge_count());
    let (ours, theirs) = (triangles(surface), triangles(mesh));
    for (corners, frame) in &ours {
        assert_eq!(theirs.get(corners), Some(frame), "triangle {corners:?}");
    }
    assert_eq!(ours.len(), theirs.len());
}

#[test]
fn tiled_order_visits_every_cell_once() {
    for (wide, high) in [(1, 1), (5, 3), (32, 32), (33, 65), (100, 7), (64, 31)] {
        let mut seen = vec![false; wide * high];
        for (c, r) in tiled(wide, high) {
            assert!(!seen[r * wide + c], "({c}, {r}) twice");
            seen[r * wide + c] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
}

#[test]
fn a_whole_grid_is_its_mesh() {
    let g = grid(70, 41, 7, 0.0);
    same_as_mesh(&GridSurface::new(&g).unwrap(), &g.to_mesh().unwrap().mesh);
}

#[test]
fn nodata_and_windows_leave_the_same_faces_as_the_mesh() {
    let g = grid(45, 38, 11, 0.08);
    same_as_mesh(&GridSurface::new(&g).unwrap(), &g.to_mesh().unwrap().mesh);
    let keep = |c: usize, r: usize| (c as f64 - 20.0).hypot(r as f64 - 15.0) < 12.0;
    let surface = GridSurface::within(&g, 5..40, 3..30, keep).unwrap();
    same_as_mesh(
        &surface,
        &g.to_mesh_within(5..40, 3..30, keep).unwrap().mesh,
    );
}

#[test]
fn a_grid_without_a_triangle_is_refused() {
    let g = grid(4, 4, 3, 1.0);
    assert!(matches!(
        GridSurface::new(&g),
        Err(TerrainError::TooSmall { .. })
    ));
    let g = grid(10, 10, 3, 0.0);
    let nothing = GridSurface::within(&g, 0..9, 0..9, |_, _| false);
    assert!(matches!(nothing, Err(TerrainError::TooSmall { .. })));
}

#[test]
fn points_are_located_as_on_the_mesh() {
    let g = grid(30, 20, 5, 0.05);
    let (surface, terrain) = (GridSurface::new(&g).unwrap(), g.to_mesh().unwrap());
    for i in 0..200 {
        let (x, y) = (100.0 + 0.29 * i as f64, -50.0 + 0.283 * i as f64);
        match (surface.locate(x, y), terrain.locate(x, y)) {
            (Ok(a), Ok(b)) => {
                let (p, q) = (a.position(&surface), b.position(&terrain.mesh));
                assert!(p.distance(q) < 1e-9, "{x} {y}: {p} against {q}");
            }
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            (a, b) => panic!("{x} {y}: {a:?} against {b:?}"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random grids, NODATA and round windows: the contract holds and the triangles
    /// are the mesh's.
    #[test]
    fn every_window_is_its_mesh(
        wide in 2usize..80,
        high in 2usize..80,
        seed in any::<u64>(),
        holes in prop_oneof![Just(0.0), 0.0..0.3],
        centre in (0.0..1.0f64, 0.0..1.0f64),
        radius in 0.5..60.0f64,
    ) {
        let g = grid(wide, high, seed, holes);
        let (cx, cy) = (centre.0 * wide as f64, centre.1 * high as f64);
        let keep = |c: usize, r: usize| (c as f64 - cx).hypot(r as f64 - cy) < radius;
        let (cols, rows) = (0..wide, 0..high);
        match (
            GridSurface::within(&g, cols.clone(), rows.clone(), keep),
            g.to_mesh_within(cols, rows, keep),
        ) {
            (Ok(surface), Ok(terrain)) => same_as_mesh(&surface, &terrain.mesh),
            (Err(_), Err(_)) => {}
            (a, b) => panic!("{:?} against {:?}", a.map(|_| ()), b.map(|_| ())),
        }
    }
}

#[test]
fn a_triangle_too_steep_to_lay_flat_is_refused_by_its_cell() {
    // One sample 1e14 above its neighbours, a unit apart: rounding leaves the triangles
    // around it no area (the grid's mesh drops them).
    let geometry = GridGeometry {
        ncols: 4,
        nrows: 4,
        lower_left: [0.0, 0.0],
        spacing: [1.0, 1.0],
    };
    let grid = ElevationGrid::from_fn(geometry, |x, y| {
        Some(if x == 1.0 && y == 2.0 { 1e14 } else { 0.0 })
    })
    .unwrap();
    match GridSurface::new(&grid) {
        Err(TerrainError::InvalidGrid { message }) => {
            assert!(message.contains("too steep to lay flat"), "{message}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
}
