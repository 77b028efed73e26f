//! Mesh readers and writers: one small hand-made fixture per format (in `tests/data/io/`),
//! bad input of every kind (written into a temporary directory), and the writers'
//! round trip and atomicity.

use approx::assert_abs_diff_eq;
use geotracks::mesh::io::{
    read_medial_axis, read_mesh, read_obj_bytes, write_atomically, write_obj_polylines,
    write_ply_with_distance,
};
use geotracks::mesh::{MeshError, TriMesh};
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

/// Writes `bytes` to `name` in a fresh temporary directory (kept alive by the guard).
fn temp_file(name: &str, bytes: impl AsRef<[u8]>) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write temporary file");
    (dir, path)
}

/// The error under the `InFile` / `AtLine` wrappers that say where it happened.
fn root(e: &MeshError) -> &MeshError {
    match e {
        MeshError::InFile { error, .. } | MeshError::AtLine { error, .. } => root(error),
        other => other,
    }
}

/// Reads `bytes` as a file called `name` and returns the error, checking that its message
/// names the file.
fn read_error(name: &str, bytes: impl AsRef<[u8]>) -> MeshError {
    let (_dir, path) = temp_file(name, bytes);
    let err = read_mesh(&path).expect_err("the file is bad");
    let message = err.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "`{message}` does not name {}",
        path.display()
    );
    err
}

fn positions(mesh: &TriMesh) -> Vec<[f64; 3]> {
    mesh.positions().iter().map(|p| p.to_array()).collect()
}

/// The edge joining `a` and `b`, if some face has it.
fn edge(mesh: &TriMesh, a: u32, b: u32) -> Option<u32> {
    let key = [a.min(b), a.max(b)];
    mesh.vertex_edges(a)
        .iter()
        .copied()
        .find(|&e| mesh.edge_vertices(e) == key)
}

const UNIT_SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

/// A unit square as two triangles: 4 vertices, 5 edges, the diagonal 0–2 shared.
fn assert_square(mesh: &TriMesh) {
    assert_eq!(positions(mesh), UNIT_SQUARE);
    assert_eq!(mesh.face_count(), 2);
    assert_eq!(mesh.edge_count(), 5);
    let diagonal = edge(mesh, 0, 2).expect("fan triangulation from corner 0");
    assert_eq!(mesh.edge_faces(diagonal).len(), 2);
    assert_eq!(mesh.report().boundary_edges, 4);
}

// ---------------------------------------------------------------------------------------
// Valid files, one per format

#[test]
fn obj_tetrahedron_is_closed() {
    let mesh = read_mesh(fixture("tetrahedron.obj")).unwrap();
    assert_eq!(
        positions(&mesh),
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0]
        ]
    );
    assert_eq!(
        mesh.triangles(),
        [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    );
    let report = mesh.report();
    assert_eq!((report.edges, report.boundary_edges), (6, 0));
    assert_eq!((report.non_manifold_edges, report.components), (0, 1));
}

#[test]
fn obj_keeps_file_vertex_order_across_groups() {
    // The quad is triangulated, the two groups share vertices 2 and 3 (1-based) through
    // the file's global vertex list, and the unreferenced vertex keeps its index.
    let mesh = read_mesh(fixture("quad_groups.obj")).unwrap();
    assert_eq!(mesh.vertex_count(), 6);
    assert_eq!(mesh.position(4).to_array(), [2.0, 0.5, 0.0]);
    assert_eq!(mesh.position(5).to_array(), [9.0, 9.0, 9.0]);
    assert_eq!(mesh.triangles(), [[0, 1, 2], [0, 2, 3], [1, 4, 2]]);
    let shared = edge(&mesh, 1, 2).unwrap();
    assert_eq!(mesh.edge_faces(shared).len(), 2);
    let report = mesh.report();
    assert_eq!((report.components, report.unreferenced_vertices), (1, 1));
}

#[test]
fn obj_from_memory() {
    let bytes = std::fs::read(fixture("tetrahedron.obj")).unwrap();
    let mesh = read_obj_bytes(&bytes).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 4));
}

#[test]
fn extension_is_case_insensitive() {
    let bytes = std::fs::read(fixture("tetrahedron.obj")).unwrap();
    let (_dir, path) = temp_file("TETRAHEDRON.Obj", bytes);
    assert_eq!(read_mesh(&path).unwrap().face_count(), 4);
}

#[test]
fn ply_ascii_quad_is_triangulated() {
    assert_square(&read_mesh(fixture("square.ply")).unwrap());
}

/// A binary PLY of the unit square: float coordinates, an extra `double` property, a quad
/// face with a `uint` index list. `big` picks the byte order.
fn binary_square_ply(big: bool) -> Vec<u8> {
    let order = if big { "big" } else { "little" };
    let mut bytes = format!(
        "ply\nformat binary_{order}_endian 1.0\nelement vertex 4\nproperty float x\n\
         property float y\nproperty float z\nproperty double quality\nelement face 1\n\
         property list uchar uint vertex_indices\nend_header\n"
    )
    .into_bytes();
    let f32s = |x: f32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let u32s = |x: u32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    for p in UNIT_SQUARE {
        for c in p {
            bytes.extend(f32s(c as f32));
        }
        bytes.extend(if big {
            7.5f64.to_be_bytes()
        } else {
            7.5f64.to_le_bytes()
        });
    }
    bytes.push(4);
    for v in 0..4 {
        bytes.extend(u32s(v));
    }
    bytes
}

#[test]
fn ply_binary_little_endian() {
    let (_dir, path) = temp_file("square.ply", binary_square_ply(false));
    assert_square(&read_mesh(&path).unwrap());
}

#[test]
fn ply_binary_big_endian() {
    let (_dir, path) = temp_file("square.ply", binary_square_ply(true));
    assert_square(&read_mesh(&path).unwrap());
}

#[test]
fn off_quad_with_colour_is_triangulated() {
    assert_square(&read_mesh(fixture("square.off")).unwrap());
}

#[test]
fn off_without_header_and_counts_on_header_line() {
    let body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    for text in [format!("4 2 0\n{body}"), format!("OFF 4 2 0\n{body}")] {
        let (_dir, path) = temp_file("square.off", text);
        assert_square(&read_mesh(&path).unwrap());
    }
}

#[test]
fn stl_ascii_is_welded() {
    assert_square(&read_mesh(fixture("square.stl")).unwrap());
}

/// A binary STL of `triangles`, with `header` at the start of its 80-byte header.
fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes[..header.len()].copy_from_slice(header);
    bytes.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        bytes.extend([0u8; 12]); // normal
        for c in t.iter().flatten() {
            bytes.extend(c.to_le_bytes());
        }
        bytes.extend([0u8; 2]); // attribute byte count
    }
    bytes
}

const SQUARE_TRIANGLES: [[[f32; 3]; 3]; 2] = [
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
    [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
];

#[test]
fn stl_binary_two_triangles_weld_to_four_vertices() {
    let (_dir, path) = temp_file("square.stl", binary_stl(b"binary", &SQUARE_TRIANGLES));
    assert_square(&read_mesh(&path).unwrap());
}

#[test]
fn stl_binary_whose_header_says_solid() {
    // Many exporters start the binary header with "solid"; the size decides.
    let (_dir, path) = temp_file(
        "square.stl",
        binary_stl(b"solid exported", &SQUARE_TRIANGLES),
    );
    assert_square(&read_mesh(&path).unwrap());
}

#[test]
fn ma_book_has_three_pages_on_its_spine_and_a_free_edge() {
    let axis = read_medial_axis(fixture("book.ma")).unwrap();
    let mesh = axis.surface.as_ref().unwrap();
    assert_eq!(axis.free_edges, [[2, 5]]);
    assert_eq!(axis.positions.len(), 6);
    assert_eq!(axis.radii, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]);
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (6, 3));
    let spine = edge(mesh, 0, 1).unwrap();
    assert_eq!(mesh.edge_faces(spine).len(), 3);
    // The 7 listed face edges are not repeated as line elements; the free one is.
    assert_eq!(mesh.line_edges(), [[2, 5]]);
    let report = mesh.report();
    assert_eq!(report.non_manifold_edges, 1);
    assert_eq!(report.max_edge_valence, 3);
    assert_eq!(report.line_edges, 1);
    // Vertex 5 is only on the free edge: no face uses it, but it is part of the axis,
    // one component with the pages.
    assert_eq!(report.unreferenced_vertices, 0);
    assert_eq!(report.components, 1);
    assert_eq!(
        (report.betti.b0, report.betti.b1, report.betti.b2),
        (1, 0, 0)
    );

    let same = read_mesh(fixture("book.ma")).unwrap();
    assert_eq!(same.triangles(), mesh.triangles());
}

#[test]
fn ma_with_only_edges_is_a_curve_axis_but_no_mesh() {
    let text = "3 3 1\nv 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\ne 0 1\ne 2 1\ne 1 1\nf 0 1 1\n";
    let err = read_error("edges.ma", text);
    assert!(matches!(err, MeshError::InFile { .. }), "{err:?}");
    assert!(
        matches!(
            root(&err),
            MeshError::NoUsableFace {
                faces: 1,
                degenerate: 1
            }
        ),
        "{err:?}"
    );
    let (_dir, path) = temp_file("edges.ma", text);
    let axis = read_medial_axis(&path).unwrap();
    assert!(axis.surface.is_none());
    assert_eq!(axis.free_edges, [[0, 1], [1, 2]]);
    assert_eq!(axis.radii, [1.0; 3]);
    // Neither a face nor an edge: nothing at all to work on.
    let (_dir, path) = temp_file("points.ma", "2 0 0\nv 0 0 0 1\nv 1 0 0 1\n");
    let err = read_medial_axis(&path).unwrap_err();
    assert!(
        matches!(root(&err), MeshError::NoUsableFace { .. }),
        "{err:?}"
    );
}

// ---------------------------------------------------------------------------------------
// Bad input: each gives its own error, naming the file and the line or element.

#[test]
fn empty_file() {
    for (name, text) in [
        ("empty.obj", ""),
        ("blank.ply", " \n\n"),
        ("comments.obj", "# nothing here\n\n# at all\n"),
        ("comments.off", "# nothing\n"),
        ("comments.ma", "# nothing\n"),
    ] {
        let err = read_error(name, text);
        assert!(
            matches!(err, MeshError::EmptyFile { .. }),
            "{name}: {err:?}"
        );
    }
}

#[test]
fn unknown_extension() {
    let err = read_error("mesh.xyz", "v 0 0 0\n");
    assert!(matches!(err, MeshError::UnknownFormat { .. }), "{err:?}");
    let err = read_error("no_extension", "v 0 0 0\n");
    assert!(matches!(err, MeshError::UnknownFormat { .. }), "{err:?}");
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("missing.obj");
    let err = read_mesh(&path).unwrap_err();
    assert!(matches!(err, MeshError::Io { .. }), "{err:?}");
    assert!(err.to_string().contains("missing.obj"), "{err}");
}

#[test]
fn truncated_off() {
    // Declares 3 faces, has 1: the second face was expected on line 8.
    let err = read_error(
        "cut.off",
        "OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n",
    );
    match &err {
        MeshError::Parse { line, message, .. } => {
            assert_eq!(*line, 8);
            assert!(
                message.contains("face 1 of the 3 that line 2 declares"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("cut.off:8:"), "{err}");

    // Truncated inside the vertices.
    let err = read_error("cut.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n");
    assert!(
        matches!(&err, MeshError::Parse { line: 5, message, .. } if message.contains("vertex 2 of the 4")),
        "{err:?}"
    );
    // A face line shorter than its declared count.
    let err = read_error("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1\n");
    assert!(matches!(err, MeshError::Parse { line: 6, .. }), "{err:?}");
}

#[test]
fn truncated_binary_stl() {
    let mut bytes = binary_stl(b"binary", &SQUARE_TRIANGLES);
    bytes.truncate(bytes.len() - 10);
    let err = read_error("cut.stl", bytes);
    match &err {
        MeshError::Parse {
            line: 0, message, ..
        } => {
            assert!(message.contains("truncated"), "{message}");
            assert!(message.contains("triangle 1"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn truncated_ascii_stl_names_the_facet_line() {
    let text = std::fs::read_to_string(fixture("square.stl")).unwrap();
    let cut: String = text.lines().take(11).map(|l| format!("{l}\n")).collect();
    let err = read_error("cut.stl", cut);
    assert!(matches!(err, MeshError::Parse { line: 9, .. }), "{err:?}");
}

#[test]
fn obj_face_index_out_of_range() {
    let err = read_error("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    match &err {
        MeshError::AtLine { line: 5, error, .. } => assert!(
            matches!(
                **error,
                MeshError::IndexOutOfRange {
                    face: 1,
                    vertex: 9,
                    vertex_count: 3
                }
            ),
            "{error:?}"
        ),
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("bad.obj:5:"), "{err}");
    assert!(err.to_string().contains("face 1"), "{err}");

    // A relative index reaching before the first vertex.
    let err = read_error("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n");
    assert!(
        matches!(&err, MeshError::AtLine { line: 4, .. })
            && matches!(root(&err), MeshError::IndexOutOfRange { vertex: -4, .. }),
        "{err:?}"
    );
    // A forward reference is fine if the vertex comes later...
    let (_dir, path) = temp_file("fwd.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n");
    assert_eq!(read_mesh(&path).unwrap().face_count(), 1);
    // ...and an error on the face's line if it never does.
    let err = read_error("fwd.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\nf 1 2 5\n");
    assert!(matches!(err, MeshError::AtLine { line: 5, .. }), "{err:?}");
}

#[test]
fn obj_malformed_statements() {
    let err = read_error("bad.obj", "v 0 0 0\nv 1 zero 0\n");
    assert!(matches!(err, MeshError::Parse { line: 2, .. }), "{err:?}");
    let err = read_error("bad.obj", "v 0 0\n");
    assert!(matches!(err, MeshError::Parse { line: 1, .. }), "{err:?}");
    let err = read_error("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    assert!(matches!(err, MeshError::Parse { line: 3, .. }), "{err:?}");
    let err = read_error("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    assert!(matches!(err, MeshError::Parse { line: 4, .. }), "{err:?}");
}

#[test]
fn ply_face_index_out_of_range() {
    let text = std::fs::read_to_string(fixture("square.ply")).unwrap();
    for bad in ["4 0 1 2 4 7", "4 0 1 -1 3 7"] {
        let err = read_error("bad.ply", text.replace("4 0 1 2 3 7", bad));
        match &err {
            MeshError::AtLine {
                line: 17, error, ..
            } => assert!(
                matches!(
                    **error,
                    MeshError::IndexOutOfRange {
                        face: 0,
                        vertex_count: 4,
                        ..
                    }
                ),
                "{error:?}"
            ),
            other => panic!("{other:?}"),
        }
        assert!(err.to_string().contains("face 0"), "{err}");
    }
}

#[test]
fn ply_missing_property_or_element() {
    let text = std::fs::read_to_string(fixture("square.ply")).unwrap();
    let err = read_error(
        "bad.ply",
        text.replace("property float z\n", "property float w\n"),
    );
    assert!(
        matches!(&err, MeshError::Parse { line: 4, message, .. } if message.contains("`z`")),
        "{err:?}"
    );
    let err = read_error("bad.ply", text.replace("vertex_indices", "corner_list"));
    assert!(matches!(err, MeshError::Parse { line: 9, .. }), "{err:?}");
    let err = read_error("bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n");
    assert!(matches!(err, MeshError::Parse { line: 7, .. }), "{err:?}");
}

#[test]
fn ply_truncated_and_garbage() {
    let text = std::fs::read_to_string(fixture("square.ply")).unwrap();
    let cut: String = text.lines().take(14).map(|l| format!("{l}\n")).collect();
    let err = read_error("cut.ply", cut);
    assert!(matches!(err, MeshError::Parse { .. }), "{err:?}");

    let mut bytes = binary_square_ply(false);
    bytes.truncate(bytes.len() - 3);
    let err = read_error("cut.ply", bytes);
    assert!(matches!(err, MeshError::Parse { line: 0, .. }), "{err:?}");

    let err = read_error("garbage.ply", "this is not a ply file\n");
    assert!(matches!(err, MeshError::WrongFormat { .. }), "{err:?}");
}

#[test]
fn nan_coordinate_off_and_obj() {
    for (name, text) in [
        ("nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n"),
        ("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
        ("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"),
    ] {
        let err = read_error(name, text);
        assert!(matches!(err, MeshError::InFile { .. }), "{name}: {err:?}");
        assert!(
            matches!(root(&err), MeshError::NonFiniteVertex { vertex: 1, .. }),
            "{name}: {err:?}"
        );
        assert!(err.to_string().contains("vertex 1"), "{err}");
    }
}

#[test]
fn off_face_index_out_of_range() {
    let err = read_error("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
    assert!(matches!(err, MeshError::AtLine { line: 6, .. }), "{err:?}");
    assert!(
        matches!(
            root(&err),
            MeshError::IndexOutOfRange {
                face: 0,
                vertex: 3,
                vertex_count: 3
            }
        ),
        "{err:?}"
    );
}

#[test]
fn ma_edge_index_out_of_range() {
    let text = std::fs::read_to_string(fixture("book.ma")).unwrap();
    let bad = text.replace("e 2 5", "e 2 6");
    let line = 1 + bad.lines().position(|l| l == "e 2 6").unwrap();
    let err = read_error("bad.ma", bad);
    match &err {
        MeshError::AtLine { line: l, error, .. } => {
            assert_eq!(*l, line);
            assert!(
                matches!(
                    **error,
                    MeshError::EdgeIndexOutOfRange {
                        edge: 7,
                        vertex: 6,
                        vertex_count: 6
                    }
                ),
                "{error:?}"
            );
        }
        other => panic!("{other:?}"),
    }
    assert!(
        err.to_string().contains(&format!("bad.ma:{line}: edge 7")),
        "{err}"
    );
}

#[test]
fn ma_face_index_out_of_range() {
    let err = read_error(
        "bad.ma",
        "3 0 1\nv 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 0 1 -2\n",
    );
    assert!(matches!(err, MeshError::AtLine { line: 5, .. }), "{err:?}");
    assert!(
        matches!(
            root(&err),
            MeshError::IndexOutOfRange {
                face: 0,
                vertex: -2,
                ..
            }
        ),
        "{err:?}"
    );
}

#[test]
fn ma_count_mismatch() {
    let text = std::fs::read_to_string(fixture("book.ma")).unwrap();
    // One edge fewer than the header's 8.
    let err = read_error("short.ma", text.replace("e 2 5\n", ""));
    match &err {
        MeshError::Parse {
            line: 1, message, ..
        } => {
            assert!(message.contains("8 edges"), "{message}");
            assert!(message.contains("1 missing"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // One vertex more than the header's 6: the line of the extra one.
    let err = read_error("long.ma", format!("{text}v 5 5 5 1\n"));
    assert!(matches!(err, MeshError::Parse { line: 22, .. }), "{err:?}");
    // A negative radius.
    let err = read_error("radius.ma", text.replace("0 0 1 0.2", "0 0 1 -0.2"));
    assert!(matches!(err, MeshError::Parse { line: 6, .. }), "{err:?}");
}

// ---------------------------------------------------------------------------------------
// Writers

#[test]
fn ply_with_distance_round_trips() {
    let mesh = read_mesh(fixture("tetrahedron.obj")).unwrap();
    let distance = [0.0, 1.0, f64::INFINITY, 0.5];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.ply");
    write_ply_with_distance(&path, &mesh, &distance).unwrap();

    let back = read_mesh(&path).unwrap();
    assert_eq!(positions(&back), positions(&mesh));
    assert_eq!(back.triangles(), mesh.triangles());

    // The extra properties, read with the PLY crate itself.
    use ply_rs_bw::ply::{DefaultElement, Property};
    let mut file = std::fs::File::open(&path).unwrap();
    let ply = ply_rs_bw::parser::Parser::<DefaultElement>::new()
        .read_ply(&mut file)
        .unwrap();
    let vertices = &ply.payload["vertex"];
    let get = |v: usize, name: &str| vertices[v][name].clone();
    for (v, &d) in distance.iter().enumerate() {
        assert_eq!(get(v, "distance"), Property::Double(d));
    }
    let rgb = |v: usize| ["red", "green", "blue"].map(|c| get(v, c));
    let viridis = |t: f64| {
        let c = colorous::VIRIDIS.eval_continuous(t);
        [c.r, c.g, c.b].map(Property::UChar)
    };
    assert_eq!(rgb(0), viridis(0.0));
    assert_eq!(rgb(1), viridis(1.0));
    assert_eq!(rgb(2), [128u8; 3].map(Property::UChar)); // unreached
    assert_eq!(rgb(3), viridis(0.5));
}

#[test]
fn ply_with_distance_of_wrong_length_writes_nothing() {
    let mesh = read_mesh(fixture("tetrahedron.obj")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.ply");
    let err = write_ply_with_distance(&path, &mesh, &[0.0; 3]).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::AttributeLength {
                expected: 4,
                found: 3,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn failed_write_leaves_no_file() {
    let mesh = read_mesh(fixture("tetrahedron.obj")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no/such/dir/out.ply");
    let err = write_ply_with_distance(&path, &mesh, &[0.0; 4]).unwrap_err();
    assert!(matches!(err, MeshError::Io { .. }), "{err:?}");
    assert!(err.to_string().contains("out.ply"), "{err}");
    // The temporary file's name is not the user's business (it used to be appended).
    assert!(!err.to_string().contains(".geotracks-"), "{err}");
    assert!(!path.exists());

    // A writer that fails half-way: no target and no temporary file remain.
    let path = dir.path().join("out.txt");
    let err = write_atomically(&path, |w| {
        w.write_all(b"partial")?;
        Err(std::io::Error::other("disk full"))
    })
    .unwrap_err();
    assert!(err.to_string().contains("disk full"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn atomic_write_replaces_the_whole_file() {
    let (dir, path) = temp_file("out.txt", "old content that is longer\n");
    write_atomically(&path, |w| w.write_all(b"new\n")).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
    // A failed rewrite keeps the previous file as it was.
    write_atomically(&path, |_| Err(std::io::Error::other("no"))).unwrap_err();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn obj_polylines_content() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("paths.obj");
    let polylines = vec![
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        vec![],
        vec![[0.1, 0.2, -0.3]],
        vec![[2.0, 0.0, 0.0], [3.0, 0.0, 0.5]],
    ];
    write_obj_polylines(&path, &polylines).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let data: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        data,
        [
            "v 0 0 0",
            "v 1 0 0",
            "v 1 1 0",
            "v 0.1 0.2 -0.3",
            "v 2 0 0",
            "v 3 0 0.5",
            "l 1 2 3",
            "p 4",
            "l 5 6",
        ]
    );

    let err = write_obj_polylines(&path, &[vec![[0.0, f64::NAN, 0.0]]]).unwrap_err();
    assert!(
        matches!(err, MeshError::NonFiniteVertex { vertex: 0, .. }),
        "{err:?}"
    );
}

#[test]
fn written_ply_of_a_book_reads_back_non_manifold() {
    let mesh = read_mesh(fixture("book.ma")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("book.ply");
    write_ply_with_distance(&path, &mesh, &[1.0; 6]).unwrap();
    let back = read_mesh(&path).unwrap();
    assert_eq!(back.report().max_edge_valence, 3);
    assert_eq!(positions(&back), positions(&mesh));
}

// ---------------------------------------------------------------------------------------
// Messages that say what is wrong

/// No message shows the inside of a Rust value: braces, quotes around lists, the names
/// of library types, or several lines.
fn assert_plain(message: &str) {
    for debug in [
        "{",
        "[\"",
        "Scalar(",
        "List(",
        "Error:",
        "ParseIntError",
        "\n",
        "\t",
    ] {
        assert!(
            !message.contains(debug),
            "`{debug}` in the message: {message}"
        );
    }
}

#[test]
fn obj_index_zero_says_obj_indices_start_at_1() {
    let err = read_error("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    assert!(matches!(err, MeshError::Parse { line: 4, .. }), "{err:?}");
    let message = err.to_string();
    assert!(message.contains("OBJ indices start at 1"), "{message}");
    assert!(!message.contains("refers to vertex 0"), "{message}");
}

#[test]
fn a_directory_is_named_as_one() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["meshes", "looks_like.obj"] {
        let path = dir.path().join(name);
        std::fs::create_dir(&path).unwrap();
        let err = read_mesh(&path).unwrap_err();
        assert!(matches!(err, MeshError::IsDirectory { .. }), "{err:?}");
        assert!(err.to_string().contains("is a directory"), "{err}");
        let err = read_medial_axis(&path).unwrap_err();
        assert!(matches!(err, MeshError::IsDirectory { .. }), "{err:?}");
    }
}

#[test]
fn binary_data_as_a_text_format_is_not_that_format() {
    let bytes = std::fs::read(fixture("binary.obj")).unwrap();
    for (name, format) in [
        ("binary.obj", "not an OBJ file"),
        ("binary.off", "not an OFF file"),
        ("binary.ma", "not a medial axis (.ma) file"),
        ("binary.ply", "not a PLY file"),
    ] {
        let err = read_error(name, &bytes);
        assert!(
            matches!(err, MeshError::WrongFormat { .. }),
            "{name}: {err:?}"
        );
        let message = err.to_string();
        assert!(message.contains(format), "{message}");
        assert!(message.contains("binary data"), "{message}");
        assert!(!message.contains("UTF-8"), "{message}");
    }
    // Text that is not UTF-8 (Latin-1) is named by its byte, not by a stream error.
    let err = read_error("latin1.obj", b"v 0 0 0\n# caf\xe9\nv 1 0 0\n");
    assert!(err.to_string().contains("byte 0xe9"), "{err}");
}

#[test]
fn another_format_under_the_wrong_extension() {
    // An OBJ named .stl: text, not `solid`, no binary STL's size.
    let err = read_mesh(fixture("triangle_obj.stl")).unwrap_err();
    assert!(matches!(err, MeshError::WrongFormat { .. }), "{err:?}");
    let message = err.to_string();
    assert!(message.contains("not an STL file"), "{message}");
    assert!(message.contains("looks like an OBJ"), "{message}");
    assert!(!message.contains("truncated"), "{message}");
    // A PLY named .obj or .off.
    let ply = std::fs::read(fixture("square.ply")).unwrap();
    for name in ["square.obj", "square.off", "square.ma"] {
        let err = read_error(name, &ply);
        assert!(
            matches!(err, MeshError::WrongFormat { .. }),
            "{name}: {err:?}"
        );
        assert!(err.to_string().contains("it is a PLY file"), "{err}");
    }
    // An OFF named .ply.
    let off = std::fs::read(fixture("square.off")).unwrap();
    let err = read_error("square.ply", off);
    assert!(
        err.to_string()
            .contains("not a PLY file: it looks like an OFF file"),
        "{err}"
    );
}

#[test]
fn ply_messages_are_sentences_naming_element_property_and_line() {
    let text = std::fs::read_to_string(fixture("square.ply")).unwrap();
    let cases: [(&str, String, usize, &str); 6] = [
        (
            "a word for a number",
            text.replace("1 1 0 255", "1 one 0 255"),
            15,
            "vertex 2, property `y`: expected a number, found `one`",
        ),
        (
            "a short vertex line",
            text.replace("1 1 0 255", "1 1"),
            15,
            "vertex 2, property `z`: the value is missing",
        ),
        (
            "a long face line",
            text.replace("4 0 1 2 3 7", "4 0 1 2 3 7 8"),
            17,
            "face 0 has more values than the header declares",
        ),
        (
            "an unknown type",
            text.replace("property uchar red", "property colour red"),
            8,
            "unknown property type `colour`",
        ),
        (
            "an unknown format",
            text.replace("format ascii 1.0", "format utf8 1.0"),
            2,
            "unknown PLY format `utf8`",
        ),
        (
            "a float index list",
            text.replace(
                "list uchar int vertex_indices",
                "list uchar float vertex_indices",
            ),
            9,
            "element `face` has no integer list property `vertex_indices`",
        ),
    ];
    for (what, bad, line, expected) in cases {
        let err = read_error("bad.ply", bad);
        let message = err.to_string();
        assert!(
            matches!(&err, MeshError::Parse { line: l, .. } if *l == line),
            "{what}: {err:?}"
        );
        assert!(message.contains(expected), "{what}: {message}");
        assert_plain(&message);
    }
    // Binary: the element, its index and the property, and the byte where the file ends.
    let mut bytes = binary_square_ply(false);
    bytes.truncate(bytes.len() - 3);
    let err = read_error("cut.ply", bytes);
    let message = err.to_string();
    assert!(
        message.contains("face 0, property `vertex_indices`: the list declares 4 entries"),
        "{message}"
    );
    assert_plain(&message);
    let mut bytes = binary_square_ply(false);
    bytes.truncate(bytes.len() - 70);
    let err = read_error("cut.ply", bytes);
    assert!(
        matches!(
            err,
            MeshError::ImplausibleCount {
                line: 3,
                declared: 4,
                at_most: 1,
                ..
            }
        ),
        "{err:?}"
    );
    assert_plain(&err.to_string());
    // A binary list longer than the file.
    let mut bytes = binary_square_ply(false);
    let at = bytes.len() - 17;
    bytes[at] = 255;
    let message = read_error("long_list.ply", bytes).to_string();
    assert!(message.contains("declares 255 entries"), "{message}");
    assert_plain(&message);
}

#[test]
fn stl_messages_name_the_line_in_words() {
    let text = std::fs::read_to_string(fixture("square.stl")).unwrap();
    for (bad, line, expected) in [
        (
            text.replace("vertex 1 0 0", "vertex 1 0"),
            5,
            "the z coordinate is missing",
        ),
        (
            text.replace("vertex 1 0 0", "vertex 1 zero 0"),
            5,
            "`zero` is not a finite number",
        ),
        (
            text.replacen("endloop", "endloops", 1),
            7,
            "expected `endloop`",
        ),
        (
            text.replace("endsolid square\n", ""),
            16,
            "ends before `endsolid`",
        ),
    ] {
        let err = read_error("bad.stl", bad);
        assert!(
            matches!(&err, MeshError::Parse { line: l, .. } if *l == line),
            "{err:?}"
        );
        let message = err.to_string();
        assert!(message.contains(expected), "{message}");
        assert_plain(&message);
    }
}

// ---------------------------------------------------------------------------------------
// Triangle strips

/// The z component of face `f`'s normal (its orientation on a flat mesh in the xy plane).
fn normal_z(mesh: &TriMesh, f: usize) -> f64 {
    let [a, b, c] = mesh.triangles()[f].map(|v| mesh.position(v));
    (b - a).cross(c - a).z
}

#[test]
fn ply_tristrips_alternate_winding_and_skip_stitches() {
    let mesh = read_mesh(fixture("strips.ply")).unwrap();
    assert_eq!(
        mesh.triangles(),
        [[0, 1, 2], [2, 1, 3], [2, 3, 4], [4, 3, 5], [4, 5, 6]]
    );
    // One orientation throughout, and the stitching triangles are not counted as
    // degenerate faces of the file.
    assert!((0..5).all(|f| normal_z(&mesh, f) < 0.0));
    assert!(mesh.dropped_faces().is_empty());
    let report = mesh.report();
    assert_eq!((report.components, report.non_manifold_edges), (1, 0));
}

/// A binary big-endian PLY laid out as `igea.ply` is: float x y z confidence intensity,
/// one `tristrips` element with an `int int` list.
fn igea_like(strip: &[i32]) -> Vec<u8> {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 5\nproperty float x\n\
        property float y\nproperty float z\nproperty float confidence\nproperty float intensity\n\
        element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
        .to_vec();
    for (x, y) in [
        (0.0f32, 0.0f32),
        (0.0, 1.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (2.0, 0.0),
    ] {
        for c in [x, y, 0.0, 0.5, 0.7] {
            bytes.extend(c.to_be_bytes());
        }
    }
    bytes.extend((strip.len() as i32).to_be_bytes());
    for i in strip {
        bytes.extend(i.to_be_bytes());
    }
    bytes
}

#[test]
fn binary_big_endian_tristrips_as_in_igea() {
    let (_dir, path) = temp_file("igea_like.ply", igea_like(&[0, 1, 2, 3, 4]));
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.triangles(), [[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
    assert!((0..3).all(|f| normal_z(&mesh, f) < 0.0));
    // An index past the vertices, named in the strip list.
    let err = read_error("igea_like.ply", igea_like(&[0, 1, 2, -1, 3, 9, 4]));
    let message = err.to_string();
    assert!(
        message.contains("tristrips 0: entry 5 of the strip list is vertex 9"),
        "{message}"
    );
    assert_plain(&message);
}

// ---------------------------------------------------------------------------------------
// What `info` reports, and welding

/// A torus of `n × m` quads (two triangles each), consistently oriented.
fn torus(n: u32, m: u32) -> TriMesh {
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                std::f64::consts::TAU * f64::from(i) / f64::from(n),
                std::f64::consts::TAU * f64::from(j) / f64::from(m),
            );
            let r = 2.0 + v.cos();
            positions.push([r * u.cos(), r * u.sin(), v.sin()]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut triangles = Vec::new();
    for i in 0..n {
        for j in 0..m {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A strip of `n` quads along x, its ends glued (`twist`: as a Möbius strip).
fn closed_strip(n: u32, twist: bool) -> TriMesh {
    let mut positions = Vec::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        positions.push([3.0 * a.cos(), 3.0 * a.sin(), -1.0]);
        positions.push([3.0 * a.cos(), 3.0 * a.sin(), 1.0]);
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let (b0, t0) = (2 * i, 2 * i + 1);
        let (b1, t1) = if i + 1 < n {
            (2 * i + 2, 2 * i + 3)
        } else if twist {
            (1, 0)
        } else {
            (0, 1)
        };
        triangles.push([b0, b1, t1]);
        triangles.push([b0, t1, t0]);
    }
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn report_gives_euler_characteristic_and_genus_where_defined() {
    let surface = |mesh: &TriMesh| {
        let report = mesh.report();
        assert_eq!(report.surfaces.len(), 1);
        report.surfaces[0].clone()
    };
    let tetra = surface(&read_mesh(fixture("tetrahedron.obj")).unwrap());
    assert_eq!(
        (
            tetra.euler_characteristic,
            tetra.boundary_loops,
            tetra.genus
        ),
        (2, Some(0), Some(0))
    );
    let torus = surface(&torus(8, 6));
    assert_eq!((torus.euler_characteristic, torus.genus), (0, Some(1)));
    assert_eq!(torus.orientable, Some(true));
    let annulus = surface(&closed_strip(8, false));
    assert_eq!(
        (
            annulus.euler_characteristic,
            annulus.boundary_loops,
            annulus.genus
        ),
        (0, Some(2), Some(0))
    );
    let mobius = surface(&closed_strip(8, true));
    assert_eq!(
        (mobius.orientable, mobius.boundary_loops),
        (Some(false), Some(1))
    );
    assert_eq!(mobius.genus, None);
    // A disc (the square) and a non-manifold book.
    let square = surface(&read_mesh(fixture("square.off")).unwrap());
    assert_eq!((square.euler_characteristic, square.genus), (1, Some(0)));
    let book = surface(
        read_medial_axis(fixture("book.ma"))
            .unwrap()
            .surface
            .as_ref()
            .unwrap(),
    );
    assert!(!book.manifold);
    assert_eq!((book.orientable, book.genus), (None, None));
    // Two tetrahedra sharing one vertex: every edge has two faces, but the vertex
    // joins two fans, so the component is not a manifold.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n\
                f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 5 6\nf 1 7 5\nf 1 6 7\nf 5 7 6\n";
    let (_dir, path) = temp_file("pinched.obj", text);
    let pinched = read_mesh(&path).unwrap();
    let report = pinched.report();
    assert_eq!((report.non_manifold_edges, report.surfaces.len()), (0, 1));
    assert!(!report.surfaces[0].manifold);
    assert_eq!(report.surfaces[0].euler_characteristic, 3);
}

const SEAM: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 -0 0\nv 2 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 6\n";

#[test]
fn report_gives_duplicates_bounding_box_and_mean_edge_length() {
    let (_dir, path) = temp_file("seam.obj", SEAM);
    let report = read_mesh(&path).unwrap().report();
    // Vertex 4 repeats vertex 2 (with -0 for 0), vertex 6 repeats vertex 3.
    assert_eq!(report.duplicate_positions, 2);
    assert_eq!(report.bounding_box, [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]]);
    let mean = (4.0 + 2.0 * 2f64.sqrt()) / 6.0;
    assert_abs_diff_eq!(report.mean_edge_length, mean, epsilon = 1e-15);
    assert_eq!(report.components, 2);
    let text = report.to_string();
    for line in [
        "duplicate positions   2",
        "bounding box          [0, 2] x [0, 1] x [0, 0]",
        "Euler characteristic  2",
        "component 1: 1 faces, 3 vertices, 3 edges, chi 1, manifold, orientable, 1 boundary loop(s), genus 0",
    ] {
        assert!(text.contains(line), "{line}\n{text}");
    }
}

#[test]
fn weld_merges_identical_positions_and_keeps_face_numbering() {
    use geotracks::mesh::io::{read_mesh_with, ReadOptions};
    let weld = ReadOptions::DEFAULT.with_weld(true);
    // A face that welding collapses is dropped as degenerate, under its file index.
    let text = format!("{SEAM}f 2 4 5\n");
    let (_dir, path) = temp_file("seam.obj", text);
    let mesh = read_mesh_with(&path, &weld).unwrap();
    assert_eq!(mesh.vertex_count(), 4);
    assert_eq!(mesh.triangles(), [[0, 1, 2], [1, 3, 2]]);
    assert_eq!(mesh.input_face_count(), 3);
    assert_eq!(mesh.dropped_faces()[0].input_index, 2);
    let report = mesh.report();
    assert_eq!((report.components, report.duplicate_positions), (1, 0));
    // Unwelded, the same file has two pieces and keeps its six vertices.
    let split = read_mesh(&path).unwrap();
    assert_eq!((split.vertex_count(), split.report().components), (6, 2));
    // Every format takes the option; a .ma keeps its first copy's radius.
    let (_dir, path) = temp_file(
        "seam.ma",
        "6 0 2\nv 0 0 0 1\nv 1 0 0 2\nv 1 1 0 3\nv 1 0 0 4\nv 2 0 0 5\nv 1 1 0 6\n\
         f 0 1 2\nf 3 4 5\n",
    );
    assert_eq!(read_mesh_with(&path, &weld).unwrap().report().components, 1);
    // A non-finite vertex is reported by its file index, welded or not.
    let (_dir, path) = temp_file("nan.obj", "v 0 0 0\nv 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 3 4\n");
    let err = read_mesh_with(&path, &weld).unwrap_err();
    assert!(
        matches!(root(&err), MeshError::NonFiniteVertex { vertex: 2, .. }),
        "{err:?}"
    );
}

/// A UTF-8 byte-order mark at the start of a text file is skipped by every text format:
/// it made an OBJ's first vertex disappear silently (its line read as an unknown
/// statement), and the other formats refuse the file as not theirs.
#[test]
fn a_byte_order_mark_is_skipped_in_every_text_format() {
    const BOM: &str = "\u{feff}";
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let off = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let stl = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
               vertex 1 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n\
               vertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    let ma = "4 0 2\nv 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nv 0 1 0 1\nf 0 1 2\nf 0 2 3\n";
    for (name, text) in [
        ("square.obj", square),
        ("square.ply", ply),
        ("square.off", off),
        ("square.stl", stl),
        ("square.ma", ma),
    ] {
        let (_dir, path) = temp_file(name, format!("{BOM}{text}"));
        let mesh = read_mesh(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            (mesh.vertex_count(), mesh.face_count()),
            (4, 2),
            "{name}: a vertex or face lost to the byte-order mark"
        );
    }
    let (_dir, path) = temp_file("axis.ma", format!("{BOM}{ma}"));
    assert_eq!(read_medial_axis(&path).unwrap().radii.len(), 4);
    // Binary PLY: the header after the mark, the payload as before.
    let mut bytes = BOM.as_bytes().to_vec();
    bytes.extend(binary_square_ply(false));
    let (_dir, path) = temp_file("binary.ply", bytes);
    assert_eq!(read_mesh(&path).unwrap().vertex_count(), 4);
}

/// Runs `read` on another thread; `None` if it has not returned within `seconds` (a
/// reader blocked on a FIFO never returns, and ignores signals while blocked).
fn within<T: Send + 'static>(seconds: u64, read: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(read());
    });
    receive
        .recv_timeout(std::time::Duration::from_secs(seconds))
        .ok()
}

/// A named pipe (FIFO) given as a mesh blocked the reader forever (opening it waits
/// for a writer); every reader now refuses it, and anything that is not a regular file,
/// before opening it.
#[cfg(unix)]
#[test]
fn a_fifo_or_a_device_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["pipe.obj", "pipe.ply", "pipe.stl", "pipe.off", "pipe.ma"] {
        let path = dir.path().join(name);
        let made = std::process::Command::new("mkfifo")
            .arg(&path)
            .status()
            .expect("mkfifo");
        assert!(made.success());
        let shown = path.clone();
        let result = within(10, move || read_mesh(&shown).map(|_| ()))
            .unwrap_or_else(|| panic!("{name}: the reader blocked on the FIFO"));
        let err = result.expect_err("a FIFO is not a mesh file");
        assert!(matches!(err, MeshError::NotAFile { .. }), "{name}: {err:?}");
        let message = err.to_string();
        assert!(message.contains("named pipe (FIFO)"), "{message}");
        assert!(message.contains(name), "{message}");
    }
    let ma = dir.path().join("pipe.ma");
    let result = within(10, move || read_medial_axis(&ma).map(|_| ())).expect("blocked");
    assert!(
        matches!(result, Err(MeshError::NotAFile { .. })),
        "{result:?}"
    );
    // A character device: reading /dev/zero would never end.
    if Path::new("/dev/zero").exists() {
        let err = within(10, || read_mesh("/dev/zero").map(|_| ()))
            .expect("blocked")
            .unwrap_err();
        assert!(matches!(err, MeshError::NotAFile { .. }), "{err:?}");
    }
}
