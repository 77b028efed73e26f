//! Unit tests of `trimesh.rs` (a file of their own, so that the module stays short).

use super::TriMesh;

/// The edges of `mesh`, as its faces name them and as it lists them.
fn table(mesh: &TriMesh) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
    let faces = (0..mesh.face_count() as u32)
        .map(|f| mesh.face_edges(f))
        .collect();
    let edges = (0..mesh.edge_count() as u32)
        .map(|e| mesh.edge_vertices(e))
        .collect();
    (faces, edges)
}

/// A table given to `with_edge_table` that is not the one `TriMesh::new` builds
/// (wrong corners, unsorted, an edge missing, one no face names, an index out of
/// range) is rebuilt: the mesh comes out as `TriMesh::new` makes it, never wrong.
#[test]
fn a_wrong_edge_table_is_rebuilt() {
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    let expected = TriMesh::new(positions.clone(), triangles.clone()).unwrap();
    let (faces, edges) = table(&expected);
    assert_eq!(edges, vec![[0, 1], [0, 2], [0, 3], [1, 2], [2, 3]]);
    let mut swapped = faces.clone();
    swapped[0].swap(0, 1);
    let mut unsorted = edges.clone();
    unsorted.swap(0, 1);
    let mut extra = edges.clone();
    extra.push([2, 9]);
    let mut out_of_range = faces.clone();
    out_of_range[1][2] = 40;
    let wrong = [
        (faces.clone(), edges.clone()),
        (swapped, edges.clone()),
        (faces.clone(), unsorted),
        (faces.clone(), edges[..4].to_vec()),
        (faces.clone(), extra),
        (out_of_range, edges.clone()),
        (faces[..1].to_vec(), edges.clone()),
    ];
    for (i, (face_edges, edge_vertices)) in wrong.into_iter().enumerate() {
        let mesh = TriMesh::with_edge_table(
            positions.clone(),
            triangles.clone(),
            face_edges,
            edge_vertices,
            i == 0,
        )
        .unwrap();
        assert_eq!(table(&mesh), (faces.clone(), edges.clone()), "table {i}");
    }
}
