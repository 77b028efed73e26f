//! Meshes of plates made of a few large faces, shared by the `eval` example (`--plates`)
//! and the integration tests.

use geotracks::mesh::TriMesh;

/// The closed surface of each box `lo`..`hi` (12 triangles), wound outward, as one
/// mesh: boxes that overlap give a surface whose parts run through each other (the
/// solid is their union).
pub fn boxes(boxes: &[([f64; 3], [f64; 3])]) -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (lo, hi) in boxes {
        let base = positions.len() as u32;
        positions
            .extend((0..8).map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 1 { hi[k] } else { lo[k] })));
        for q in [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ] {
            let [a, b, c, d] = q.map(|i| base + i);
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    TriMesh::new(positions, triangles).expect("boxes make a valid mesh")
}

/// An L-shaped plate 4 × 3 with arms 1 wide, 0.5 thick, in 20 triangles (a machined
/// part's mesh: its mean edge length is longer than the plate is thick).
pub fn l_plate() -> TriMesh {
    let outline = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 1.0],
        [1.0, 1.0],
        [1.0, 3.0],
        [0.0, 3.0],
    ];
    let mut positions: Vec<[f64; 3]> = outline.iter().map(|p| [p[0], p[1], 0.0]).collect();
    positions.extend(outline.iter().map(|p| [p[0], p[1], 0.5]));
    let mut triangles = vec![[0, 2, 1], [0, 3, 2], [0, 5, 4], [0, 4, 3]];
    triangles.extend([[6, 7, 8], [6, 8, 9], [6, 10, 11], [6, 9, 10]]);
    for i in 0..6 {
        let j = (i + 1) % 6;
        triangles.extend([[i, j, j + 6], [i, j + 6, i + 6]]);
    }
    TriMesh::new(positions, triangles).expect("the plate is a valid mesh")
}
