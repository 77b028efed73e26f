//! The exact engine (`Method::Exact`) against exact distances computed independently:
//! planar regions with holes and several sources (shortest paths through reflex
//! corners), developable strips (cylinders and cones, unrolled), a non-manifold book
//! (pages unfolded about their spine), a cube (geodesics over its edges), constant
//! tensors (the linearly mapped mesh), and the shared meshes' MMP references; paths
//! that are as long as the value they explain; property tests on random meshes against
//! the Steiner graph; and the errors it gives instead of a wrong answer.

// Tests aside from the function-length rule (clippy.toml): a scenario reads best whole.
#![allow(clippy::too_many_lines)]

mod common;

use common::plane::{
    cones, convex_planar_meshes, deviation, holey_meshes, several_sources, single_sources,
    Deviation, Region,
};
use common::{
    book, cylinder_strip, grid, multiscale_mesh, random_book, random_face_point, random_mesh,
    read_reference, Rng,
};
use geotracks::glam::{DVec2, DVec3};
use geotracks::mesh::{io::read_mesh, Topology, TriMesh};
use geotracks::{
    Density, Error, Euclidean, Field, FieldData, Method, Metric, Options, Solver, Source, Sources,
    Stop, SurfacePoint, Tensor,
};
use proptest::prelude::*;
use std::path::Path;

const EXACT: Options = Options::DEFAULT.with_method(Method::Exact);

fn exact_field<M: Metric>(mesh: &TriMesh, metric: M, sources: &[Source]) -> Field<M> {
    let solver = Solver::new(mesh, metric, &EXACT).unwrap();
    assert_eq!(solver.method(), Method::Exact);
    solver
        .field(Sources::from(sources).until(&Stop::NONE))
        .unwrap()
}

/// Every vertex against the region's exact distances, wherever the source is seen or
/// not (behind holes and reflex corners): asserts 1e-9 relative.
fn check_region(name: &str, mesh: &TriMesh, region: &Region, sets: &[Vec<Source>]) -> Deviation {
    let mut all = Deviation::default();
    for sources in sets {
        let field = exact_field(mesh, Euclidean, sources);
        let dev = deviation(mesh, region, field.data(), sources);
        let worst = dev.direct.max(dev.behind_excess).max(dev.below);
        assert!(
            worst <= 1e-9,
            "{name}, sources {sources:?}: {dev:?} (relative to the exact distance)"
        );
        check_paths(name, &field, 7);
        // The values alone (the run forgets each window once carried) are the
        // field's, to the bit, and so are the labels.
        let values = field
            .solver()
            .vertex_values(Sources::from(sources.as_slice()))
            .unwrap();
        assert_eq!(
            values.distances,
            field.vertex_distances(),
            "{name}: values alone"
        );
        assert_eq!(values.labels, field.vertex_labels(), "{name}: labels alone");
        all = all.merge(dev);
    }
    println!(
        "{name}: {} vertices; worst relative error {:e} (seen), {:e} (behind), {:e} below",
        all.nodes, all.direct, all.behind_excess, all.below
    );
    all
}

/// Paths from a spread of vertices and face points: as long as the value at their
/// start (1e-9 relative), ending at their source, each segment inside its face.
fn check_paths<M: Metric>(name: &str, field: &Field<M>, seed: u64) {
    let mesh = field.mesh();
    let mut rng = Rng(seed | 1);
    let mut points: Vec<SurfacePoint> = (0..6)
        .map(|_| SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32))
        .collect();
    points.extend((0..6).map(|_| random_face_point(mesh, &mut rng)));
    for point in points {
        let value = field.distance_at(point).unwrap();
        if !value.is_finite() {
            continue;
        }
        let path = field.path(point).unwrap();
        let length = path.metric_length(mesh, field.metric());
        let start = field.sources()[path.source as usize].start;
        let scale = value.abs().max(start.abs()).max(1e-12);
        assert!(
            (start + length - value).abs() <= 1e-9 * scale,
            "{name}: the path from {point:?} is {length} long from a start of {start}, the value is {value}"
        );
        assert_eq!(
            *path.points.last().unwrap(),
            field.sources()[path.source as usize].point,
            "{name}: the path from {point:?} ends at its source"
        );
    }
}

/// Each flat mesh from one source of every kind, then from several at once.
fn check_flat_meshes(meshes: &[(String, TriMesh)]) {
    for (seed, (name, mesh)) in meshes.iter().enumerate() {
        let region = Region::flat(mesh);
        check_region(name, mesh, &region, &single_sources(mesh, seed as u64));
        check_region(name, mesh, &region, &several_sources(mesh, seed as u64));
    }
}

#[test]
fn planar_meshes_are_exact_from_one_and_several_sources() {
    check_flat_meshes(&convex_planar_meshes());
}

#[test]
fn holes_are_exact_in_their_shadows_too() {
    check_flat_meshes(&holey_meshes());
}

#[test]
fn developable_strips_are_exact() {
    let mut strips = vec![
        ("cylinder 40 × 12", cylinder_strip(3, 40, 12, 1.0, 4.5, 1.0)),
        (
            "cylinder 200 × 6 (needles)",
            cylinder_strip(5, 200, 6, 2.0, 5.5, 0.3),
        ),
    ];
    strips.extend(cones());
    for (seed, (name, (mesh, unrolled))) in strips.iter().enumerate() {
        let region = Region::new(mesh, unrolled.iter().map(|&p| DVec2::from(p)).collect());
        check_region(name, mesh, &region, &single_sources(mesh, seed as u64));
        check_region(name, mesh, &region, &several_sources(mesh, seed as u64));
    }
}

/// A book of four pages (squares hinged on one spine, at any angles): a non-manifold
/// edge on every spine segment. From a point on one page, the distance to a point on
/// another is the straight line across the spine with the two pages unfolded into one
/// plane, or around an end of the spine when that line misses it.
#[test]
fn a_book_is_unfolded_across_its_spine() {
    let n = 6;
    let (mesh, id) = book(4, 1.0, 1.0, n);
    // Page p's point (i, j) unfolded: page 0 to the left of the spine (x < 0), the
    // others to its right.
    let unfolded = |p: usize, i: usize, j: usize| {
        let x = i as f64 / n as f64;
        DVec2::new(if p == 0 { -x } else { x }, j as f64 / n as f64)
    };
    let source = (0, 3, 2);
    let field = exact_field(
        &mesh,
        Euclidean,
        &[Source::new(id(source.0, source.1, source.2))],
    );
    let s = unfolded(source.0, source.1, source.2);
    let (spine_lo, spine_hi) = (DVec2::new(0.0, 0.0), DVec2::new(0.0, 1.0));
    for p in 1..4 {
        for i in 0..=n {
            for j in 0..=n {
                let x = unfolded(p, i, j);
                // The segment from s to x crosses the spine (x = 0) at height y.
                let t = s.x.abs() / (s.x.abs() + x.x);
                let y = s.y + t * (x.y - s.y);
                let exact = if (0.0..=1.0).contains(&y) {
                    s.distance(x)
                } else {
                    let end = if y < 0.0 { spine_lo } else { spine_hi };
                    s.distance(end) + end.distance(x)
                };
                let d = field.distance(id(p, i, j));
                assert!(
                    (d - exact).abs() <= 1e-9 * exact.max(1e-9),
                    "page {p} ({i}, {j}): {d}, exact {exact}"
                );
            }
        }
    }
    check_paths("book", &field, 3);
}

/// A unit cube, each face a 4 × 4 grid: from a corner, the opposite corner is √5 away
/// (over two faces, unfolded into a 1 × 2 rectangle); from the centre of the bottom,
/// the centre of the top is 2 away (up a side); and every point of a face adjacent to
/// the source's face is its unfolded straight distance.
#[test]
fn a_cube_is_unfolded_over_its_edges() {
    let mesh = cube(4);
    let corner = nearest(&mesh, DVec3::ZERO);
    let field = exact_field(&mesh, Euclidean, &[Source::new(corner)]);
    let far = nearest(&mesh, DVec3::ONE);
    assert!((field.distance(far) - 5f64.sqrt()).abs() <= 1e-12);
    let bottom = nearest(&mesh, DVec3::new(0.5, 0.5, 0.0));
    let field = exact_field(&mesh, Euclidean, &[Source::new(bottom)]);
    let top = nearest(&mesh, DVec3::new(0.5, 0.5, 1.0));
    assert!(
        (field.distance(top) - 2.0).abs() <= 1e-12,
        "{}",
        field.distance(top)
    );
    // On the side x = 0, the point (0, y, z) unfolds to (−z, y) beside the bottom.
    for (v, p) in mesh.positions().iter().enumerate() {
        if p.x == 0.0 && p.z > 0.0 {
            let exact = DVec2::new(0.5, 0.5).distance(DVec2::new(-p.z, p.y));
            let d = field.distance(v as u32);
            assert!(
                (d - exact).abs() <= 1e-12,
                "vertex {v} at {p}: {d}, exact {exact}"
            );
        }
    }
    check_paths("cube", &field, 5);
}

/// A vertex where two fans of faces meet and nothing else (a pinch: here each fan is a
/// triangle given twice, a closed pillow) is where paths from one fan go on into the
/// other, bending. Every edge at it has two faces and its angles sum to less than a
/// turn, so it looked like a flat vertex and started no windows: the far corner of the
/// second pillow came out by the long way round (10.47, not 3.16 + 5.10). Found by the
/// engine fuzz target.
#[test]
fn a_pinch_between_two_fans_is_where_paths_go_on() {
    let positions = vec![
        [0.0, 0.0, 0.0],
        [0.0, 4.0, 0.0],
        [4.0, 0.0, 0.0],
        [0.0, 4.0, 2.0],
        [0.0, 1.0, 3.0],
    ];
    let triangles = vec![[1, 4, 2], [3, 0, 4], [2, 3, 1], [1, 4, 2], [4, 3, 0]];
    let mesh = TriMesh::new(positions, triangles).unwrap();
    let field = exact_field(&mesh, Euclidean, &[Source::new(0)]);
    let p = |v: usize| DVec3::from_array(mesh.positions()[v].to_array());
    let through_the_pinch = p(0).distance(p(4)) + p(4).distance(p(2));
    assert!(
        (field.distance(2) - through_the_pinch).abs() <= 1e-12,
        "{} against {through_the_pinch}",
        field.distance(2)
    );
}

/// A unit cube's surface, each face an `n × n` grid split along its diagonals.
fn cube(n: usize) -> TriMesh {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut triangles = Vec::new();
    let mut id = |p: [f64; 3], positions: &mut Vec<[f64; 3]>| {
        let key = p.map(|c| (c * n as f64).round() as i64);
        *index.entry(key).or_insert_with(|| {
            positions.push(p);
            positions.len() as u32 - 1
        })
    };
    // Each face: a corner and two edge directions, outward by the right hand.
    let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
        ([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
    ];
    for (o, u, v) in faces {
        let at = |i: usize, j: usize| {
            let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
            [0, 1, 2].map(|k| o[k] + a * u[k] + b * v[k])
        };
        for i in 0..n {
            for j in 0..n {
                let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                    .map(|p| id(p, &mut positions));
                triangles.push([q[0], q[1], q[2]]);
                triangles.push([q[0], q[2], q[3]]);
            }
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

fn nearest(mesh: &TriMesh, p: DVec3) -> u32 {
    (0..mesh.vertex_count() as u32)
        .min_by(|&a, &b| {
            let (da, db) = (mesh.position(a).distance(p), mesh.position(b).distance(p));
            da.total_cmp(&db)
        })
        .unwrap()
}

/// Under a constant tensor `M = AᵀA`, the distance is the Euclidean distance on the
/// mesh mapped by `A`: exact on both.
#[test]
fn a_constant_tensor_is_the_mapped_mesh() {
    let mesh = common::sphere(3, 0.1, 7);
    let a = [[2.25, 1.25, 0.0], [0.75, 1.75, 0.0], [0.0, 0.0, 1.0]];
    let m = gram(&a);
    let mapped = TriMesh::new(
        mesh.positions()
            .iter()
            .map(|p| {
                let p = p.to_array();
                [0, 1, 2].map(|r| a[r][0] * p[0] + a[r][1] * p[1] + a[r][2] * p[2])
            })
            .collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap();
    let tensor = Tensor::uniform_world(&mesh, m).unwrap();
    let sources = [
        Source::new(0),
        Source::new(random_face_point(&mesh, &mut Rng(5))),
    ];
    let ours = exact_field(&mesh, &tensor, &sources);
    let mapped_field = exact_field(&mapped, Euclidean, &sources);
    for v in 0..mesh.vertex_count() as u32 {
        let (a, b) = (ours.distance(v), mapped_field.distance(v));
        assert!(
            (a - b).abs() <= 1e-9 * b.max(1e-9),
            "vertex {v}: {a} against {b}"
        );
    }
    check_paths("constant tensor", &ours, 11);
}

/// `AᵀA` as `[xx, xy, xz, yy, yz, zz]`.
fn gram(a: &[[f64; 3]; 3]) -> [f64; 6] {
    let m = |i: usize, j: usize| (0..3).map(|k| a[k][i] * a[k][j]).sum::<f64>();
    [m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2)]
}

/// Every exact reference of the shared data (MMP, and the constant-tensor ones), on
/// every mesh (the values alone past 500 000 faces, where a field's windows take
/// gigabytes): every vertex within 1e-9 relative; where a value lies below its reference by more,
/// the path traced from it is a real path that short (the reference overestimates
/// there: horse's MMP reference has such vertices, where VTP agrees with us).
#[test]
#[ignore = "needs ../shared/data beside the clone; .ci/run runs it with --ignored shared"]
fn exact_references_of_the_shared_meshes() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    let references = data.join("reference");
    assert!(references.is_dir(), "{} not found", references.display());
    let mut names: Vec<_> = std::fs::read_dir(&references)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "f64"))
        .collect();
    names.sort();
    assert!(names.len() >= 40, "{} references", names.len());
    for path in names {
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path.with_extension("json")).unwrap())
                .unwrap();
        let mesh = read_mesh(data.join(json["mesh_file"].as_str().unwrap())).unwrap();
        let source = json["source"].as_u64().unwrap() as u32;
        let reference = read_reference(&path).unwrap();
        if json["F"].as_u64().unwrap() > 500_000 {
            // bunny_loop2: the values alone (the run holds its wavefront's windows,
            // about 450 MB; a field would keep every window carried, over 5 GB).
            let solver = Solver::new(&mesh, Euclidean, &EXACT).unwrap();
            let values = solver.vertex_values(source).unwrap();
            compare(
                &path,
                &values.distances,
                &reference,
                None::<&Field<Euclidean>>,
            );
            continue;
        }
        let field = exact_field(&mesh, Euclidean, &[Source::new(source)]);
        compare(&path, field.vertex_distances(), &reference, Some(&field));
    }
    let aniso = references.join("aniso");
    let mut names: Vec<_> = std::fs::read_dir(&aniso)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "f64"))
        .collect();
    names.sort();
    assert!(!names.is_empty());
    for path in names {
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path.with_extension("json")).unwrap())
                .unwrap();
        let mesh = read_mesh(data.join("meshes").join(json["mesh"].as_str().unwrap())).unwrap();
        let m = &json["M"];
        let at = |i: usize, j: usize| m[i][j].as_f64().unwrap();
        let world = [at(0, 0), at(0, 1), at(0, 2), at(1, 1), at(1, 2), at(2, 2)];
        let tensor = Tensor::uniform_world(&mesh, world).unwrap();
        let source = json["source"].as_u64().unwrap() as u32;
        let field = exact_field(&mesh, &tensor, &[Source::new(source)]);
        let reference = read_reference(&path).unwrap();
        compare(&path, field.vertex_distances(), &reference, Some(&field));
    }
}

/// Distances `d` against `reference`, each within 1e-9 relative or below it by a real
/// path (traced in `field`; without a field none may be below).
fn compare<M: Metric>(path: &Path, d: &[f64], reference: &[f64], field: Option<&Field<M>>) {
    assert_eq!(d.len(), reference.len(), "{}", path.display());
    let (mut worst, mut shorter) = (0.0f64, 0);
    for (v, (&ours, &exact)) in d.iter().zip(reference).enumerate() {
        let r = (ours - exact) / exact.max(1e-300);
        if exact == 0.0 {
            assert_eq!(ours, 0.0);
            continue;
        }
        if r < -1e-9 {
            // Below the reference: the path must prove it.
            let field = field.unwrap_or_else(|| {
                panic!(
                    "{}: vertex {v} is {ours}, {r:e} below the reference",
                    path.display()
                )
            });
            let path_found = field.path(v as u32).unwrap();
            let length = path_found.metric_length(field.mesh(), field.metric());
            assert!(
                (length - ours).abs() <= 1e-12 * ours,
                "{}: vertex {v} is {ours}, {r:e} below the reference, but its path is {length}",
                path.display()
            );
            shorter += 1;
            continue;
        }
        assert!(
            r <= 1e-9,
            "{}: vertex {v} is {ours}, the reference {exact} ({r:e})",
            path.display()
        );
        worst = worst.max(r.abs());
    }
    println!(
        "{}: worst {worst:e}; {shorter} vertices below the reference, each by a real path",
        path.display()
    );
}

/// The errors the engine gives instead of an approximation: a metric that is not a
/// norm on each face, faces that do not glue, and windows beyond the memory limit.
#[test]
fn what_cannot_be_exact_is_refused() {
    let mesh = grid(4, 1.0);
    let density = Density::constant(&mesh, 2.0).unwrap();
    let refused = Solver::new(&mesh, density, &EXACT).unwrap_err();
    assert!(matches!(refused, Error::NotExact { .. }), "{refused}");
    assert!(refused.to_string().contains("face 0"), "{refused}");
    // Two per-face tensors that give shared edges different lengths.
    let local: Vec<[f64; 3]> = (0..mesh.face_count())
        .map(|f| {
            if f % 2 == 0 {
                [1.0, 0.0, 1.0]
            } else {
                [4.0, 0.0, 1.0]
            }
        })
        .collect();
    let tensor = Tensor::from_local(local).unwrap();
    let refused = Solver::new(&mesh, tensor, &EXACT).unwrap_err();
    assert!(refused.to_string().contains("do not glue"), "{refused}");
    // A memory limit a few windows wide.
    let bunny = common::sphere(3, 0.2, 3);
    let solver = Solver::new(&bunny, Euclidean, &EXACT.with_memory_limit(100_000)).unwrap();
    let refused = solver.field(0).unwrap_err();
    assert!(matches!(refused, Error::ExactTooLarge { .. }), "{refused}");
    // The same under the work limit, counted in windows; a workspace that saw the
    // refusal runs the next source as a fresh one would.
    let solver = Solver::new(&bunny, Euclidean, &EXACT.with_work_limit(Some(50))).unwrap();
    let mut workspace = solver.workspace();
    assert!(matches!(
        solver.run(&mut workspace, 0),
        Err(Error::ExactTooLarge { .. })
    ));
    // The work limit counts windows made, also where only values are wanted (and the
    // run holds few at once).
    assert!(matches!(
        solver.vertex_values(0),
        Err(Error::ExactTooLarge { .. })
    ));
    let roomy = Solver::new(&bunny, Euclidean, &EXACT).unwrap();
    let fresh = roomy.field(5).unwrap();
    let again = roomy.run(&mut workspace, 5).unwrap();
    let differ = (0..bunny.vertex_count() as u32)
        .filter(|&v| again.distance(v) != fresh.distance(v))
        .count();
    assert_eq!(
        differ, 0,
        "vertices that differ from a fresh workspace's run"
    );
    let path = again.path(40).unwrap();
    assert!((path.length - again.distance(40)).abs() <= 1e-9 * again.distance(40));
}

/// Early stops: within a maximum distance the values are the full run's and beyond it
/// unreached; stopped at targets, the targets' values are the full run's.
#[test]
fn early_stops_keep_the_full_runs_values() {
    let mesh = multiscale_mesh(3, 12);
    let solver = Solver::new(&mesh, Euclidean, &EXACT).unwrap();
    let full = solver.field(0).unwrap();
    let max = full.vertex_distances().iter().copied().fold(0.0, f64::max);
    let stop = Stop::NONE.with_max_distance(0.5 * max);
    let near = solver.field(Sources::from(0).until(&stop)).unwrap();
    for v in 0..mesh.vertex_count() as u32 {
        let (a, b) = (near.distance(v), full.distance(v));
        if b <= 0.5 * max {
            assert_eq!(a, b, "vertex {v}");
        } else {
            assert!(a.is_infinite(), "vertex {v}: {a} beyond the stop");
        }
    }
    let targets = [
        SurfacePoint::Vertex(7),
        random_face_point(&mesh, &mut Rng(9)),
    ];
    let stop = Stop::NONE.with_targets(targets.to_vec());
    let at = solver.field(Sources::from(0).until(&stop)).unwrap();
    for t in targets {
        let (a, b) = (at.distance_at(t).unwrap(), full.distance_at(t).unwrap());
        assert!((a - b).abs() <= 1e-12 * b, "{t:?}: {a} against {b}");
    }
    // Rows stopped at vertex targets (values only, in workspaces reused from row to
    // row after each early stop) against full fields.
    let sources = [0, 5, 0, 17, 5];
    // The vertices nearest source 0: its rows stop early.
    let mut columns: Vec<u32> = (1..mesh.vertex_count() as u32).collect();
    columns.sort_by(|&a, &b| full.distance(a).total_cmp(&full.distance(b)));
    columns.truncate(3);
    let rows = solver.distance_rows(&sources, Some(&columns)).unwrap();
    assert!(rows.iter().any(|row| row.stats.stopped_early));
    for (row, &source) in rows.iter().zip(&sources) {
        let full = solver.field(source).unwrap();
        for (&d, &v) in row.distances.iter().zip(&columns) {
            assert_eq!(d, full.distance(v), "from {source} to {v}");
        }
    }
}

fn random_kind(kind: u8, seed: u64) -> Option<TriMesh> {
    match kind {
        0 => random_mesh(seed, 12).ok(),
        1 => Some(random_book(seed, 4, 5)),
        2 => Some(common::holey_grid(seed, 8, 0.2, 2)),
        3 => Some(multiscale_mesh(seed, 8)),
        _ => Some(common::sphere(2, 0.3, seed)),
    }
}

/// The Steiner graph with `count` points on every edge (at `i / (count + 1)`: the
/// points of count 1 are among those of count 3).
fn graph(mesh: &TriMesh, sources: &[Source], count: u32) -> FieldData {
    let options = Options::DEFAULT
        .with_method(Method::Graph)
        .with_fixed_count(count);
    Solver::new(mesh, Euclidean, &options)
        .unwrap()
        .field(Sources::from(sources).until(&Stop::NONE))
        .unwrap()
        .into_data()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// On random meshes (non-manifold books, holes, multi-scale slivers, bumpy
    /// spheres), from random sources: never below the straight line in space (no
    /// shortcut off the surface), never above the Steiner graph, the graph coming down
    /// towards it as its points multiply (nested: 1, then 3 per edge); no panic, and bounded work.
    #[test]
    fn never_below_the_chord_nor_above_the_graph(seed in any::<u64>(), kind in 0u8..5) {
        let Some(mesh) = random_kind(kind, seed) else { return Ok(()); };
        let mut rng = Rng(seed | 1);
        let sources = [Source::new(rng.below(mesh.vertex_count()) as u32), Source::new(random_face_point(&mesh, &mut rng))];
        let solver = Solver::new(&mesh, Euclidean, &EXACT.with_work_limit(Some(2_000_000))).unwrap();
        let field = match solver.field(Sources::from(&sources[..]).until(&Stop::NONE)) {
            Ok(field) => field,
            Err(Error::ExactTooLarge { .. }) => return Ok(()),
            Err(e) => panic!("{e}"),
        };
        let at = |p: SurfacePoint| p.position(&mesh);
        let coarse = graph(&mesh, &sources, 1);
        let fine = graph(&mesh, &sources, 3);
        // Values agree to 1e-9 of themselves, and to rounding of the coordinates: a
        // vertex a few nanometres from a source on a mesh a unit wide is measured in
        // face frames to about 1e-16 of the unit, not of its distance.
        let [lo, hi] = mesh.bounding_box();
        let rounding = 1e-12 * lo.distance(hi);
        for v in 0..mesh.vertex_count() as u32 {
            let d = field.distance(v);
            let chord = sources.iter().map(|s| at(s.point).distance(mesh.position(v))).fold(f64::INFINITY, f64::min);
            let (g1, g3) = (coarse.distance(v), fine.distance(v));
            prop_assert_eq!(d.is_finite(), g1.is_finite(), "vertex {}: {} against the graph's {}", v, d, g1);
            if !d.is_finite() { continue; }
            let slack = 1e-9 * d + rounding;
            prop_assert!(d >= chord - slack, "vertex {}: {} below the chord {}", v, d, chord);
            prop_assert!(d <= g3 + slack, "vertex {}: {} above the graph with 3 points per edge ({})", v, d, g3);
            prop_assert!(g3 <= g1 + slack, "vertex {}: the graph with 3 points per edge ({}) above 1 ({})", v, g3, g1);
        }
    }
}
