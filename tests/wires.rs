//! Distances and paths along wires: line elements that are no face edge (a medial
//! axis's free curves) are travelled from end to end at the metric's wire cost, by
//! every engine, and paths run along them.

use approx::{abs_diff_eq, assert_abs_diff_eq};
mod common;

use common::{random_mesh, Rng, DIJKSTRA, GRAPH, TRACKS};
use geotracks::mesh::{TriMesh, NONE};
use geotracks::Sources;
use geotracks::{
    Density, Error, Euclidean, FacePoint, Method, Metric, Options, Solver, Source, Stop,
    SurfacePoint,
};

/// Two flat `n × n` grids of side 1: A on [0, 1]², B on [3, 4] × [0, 1], both at
/// z = 0, and a wire from A's corner (1, 1) to B's corner (3, 1) through two vertices
/// of no face, at (2, 1.5) and (2.5, 1.5). Returns the mesh and the grid size.
fn two_squares_and_a_wire(n: usize) -> (TriMesh, usize) {
    let side = n + 1;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for offset in [0.0, 3.0] {
        let base = positions.len() as u32;
        for j in 0..side {
            for i in 0..side {
                positions.push([offset + i as f64 / n as f64, j as f64 / n as f64, 0.0]);
            }
        }
        let id = |i: usize, j: usize| base + (j * side + i) as u32;
        for j in 0..n {
            for i in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    let a_corner = (side * side - 1) as u32; // (1, 1)
    let b_corner = (side * side + (side - 1) * side) as u32; // (3, 1)
    let p = positions.len() as u32;
    positions.push([2.0, 1.5, 0.0]);
    positions.push([2.5, 1.5, 0.0]);
    // Listed in any direction, one twice, and a face edge that changes nothing.
    let wires = vec![
        [a_corner, p],
        [p + 1, p],
        [b_corner, p + 1],
        [p, a_corner],
        [0, 1],
    ];
    (
        TriMesh::with_line_elements(positions, triangles, wires).unwrap(),
        side,
    )
}

fn wire_length() -> f64 {
    let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    d([1.0, 1.0], [2.0, 1.5]) + d([2.0, 1.5], [2.5, 1.5]) + d([2.5, 1.5], [3.0, 1.0])
}

#[test]
fn the_mesh_knows_its_wires_and_one_component() {
    let (mesh, side) = two_squares_and_a_wire(4);
    let a_corner = (side * side - 1) as u32;
    let wires: Vec<[u32; 2]> = mesh.wires().collect();
    assert_eq!(wires.len(), 3, "{wires:?}");
    assert!(mesh.vertex_wires(a_corner).len() == 1);
    assert!(mesh.vertex_wires(0).is_empty(), "a face edge is no wire");
    assert_eq!(mesh.vertex_components().1, 1);
    assert_eq!(mesh.report().components, 1);
    // Without the wires: two squares and two loose vertices.
    let bare = TriMesh::new(
        mesh.positions().iter().map(|p| p.to_array()).collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap();
    assert_eq!(bare.vertex_components().1, 4);
}

/// On two flat squares joined by a wire, from a vertex of A, every engine reaches B:
/// a vertex of B is as far as A's corner, the wire, then straight across B. The
/// wavefront engine gives that exactly (straight lines on a plane); the Steiner graph
/// and the track-pruned engine agree with each other to 1e-9; Dijkstra on edges is
/// longer, never shorter; the exact engine gives the exact values too.
#[test]
fn every_engine_crosses_the_wire() {
    let (mesh, side) = two_squares_and_a_wire(6);
    let source = 0u32; // (0, 0)
    let exact = |v: u32| -> f64 {
        let p = mesh.position(v);
        if p.x <= 1.0 {
            p.truncate().length()
        } else if p.x >= 3.0 {
            2f64.sqrt() + wire_length() + (p.x - 3.0).hypot(p.y - 1.0)
        } else if p.x < 2.25 {
            2f64.sqrt() + (p.x - 1.0).hypot(p.y - 1.0)
        } else {
            2f64.sqrt() + 0.5f64.hypot(1.0) + (p.x - 2.0)
        }
    };
    let wave = Solver::new(&mesh, &Euclidean, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    assert_eq!(wave.stats().method, Method::Wave);
    let graph = Solver::new(&mesh, &Euclidean, &GRAPH)
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    let tracks = Solver::new(&mesh, &Euclidean, &TRACKS)
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    let dijkstra = Solver::new(&mesh, &Euclidean, &DIJKSTRA)
        .and_then(|solver| solver.field(&[source]))
        .unwrap();
    // The exact engine: the same exact values (and, below, a path from B as long as
    // its value, along the wire).
    let exact_field = Solver::new(
        &mesh,
        &Euclidean,
        &Options::DEFAULT.with_method(Method::Exact),
    )
    .and_then(|solver| solver.field(&[source]))
    .unwrap();
    for v in 0..mesh.vertex_count() as u32 {
        let e = exact(v);
        for (name, field) in [("wave", &wave), ("exact", &exact_field)] {
            assert!(
                abs_diff_eq!(field.distance(v), e, epsilon = 1e-9),
                "{name} at {v}: {} vs {e}",
                field.distance(v)
            );
        }
        let g = graph.distance(v);
        assert!(g >= e - 1e-9 && g <= e * 1.02, "graph at {v}: {g} vs {e}");
        assert!(
            abs_diff_eq!(tracks.distance(v), g, epsilon = 1e-9 * g),
            "tracks at {v}"
        );
        assert!(dijkstra.distance(v) >= g - 1e-9, "dijkstra at {v}");
    }
    // Every node agrees too (the oracle relation, not only at vertices).
    for (g, t) in graph.node_distances().iter().zip(tracks.node_distances()) {
        assert!(
            abs_diff_eq!(*g, *t, epsilon = 1e-9 * g.max(1.0)),
            "{g} vs {t}"
        );
    }
    let far_corner = (2 * side * side - 1) as u32;
    let path = exact_field.path(far_corner).unwrap();
    assert_abs_diff_eq!(
        path.length,
        exact_field.distance(far_corner),
        epsilon = 1e-9
    );
    assert!(
        path.faces.contains(&geotracks::mesh::NONE),
        "along the wire"
    );
    for field in [&wave, &graph, &tracks, &dijkstra, &exact_field] {
        assert_eq!(field.unreachable_vertices(), 0);
    }
    // From B's far corner, A is reached the other way.
    let far = (2 * side * side - 1) as u32; // (4, 1)
    let back = Solver::new(&mesh, &Euclidean, &Options::DEFAULT)
        .and_then(|solver| solver.field(&[far]))
        .unwrap();
    assert_abs_diff_eq!(
        back.distance(0),
        1.0 + wire_length() + 2f64.sqrt(),
        epsilon = 1e-9
    );
}

/// A density charges a wire its length times the mean of its ends' densities.
#[test]
fn a_density_weighs_the_wire() {
    let (mesh, side) = two_squares_and_a_wire(4);
    let p = (2 * side * side) as u32; // (2, 1.5)
    let mut rho = vec![1.0; mesh.vertex_count()];
    rho[p as usize] = 3.0;
    let density = Density::new(&mesh, rho).unwrap();
    let a_corner = (side * side - 1) as u32;
    let field = Solver::new(&mesh, &density, &TRACKS)
        .and_then(|solver| solver.field(&[a_corner]))
        .unwrap();
    let first = 1.0f64.hypot(0.5) * (1.0 + 3.0) / 2.0;
    assert_abs_diff_eq!(field.distance(p), first, epsilon = 1e-12);
    assert_abs_diff_eq!(field.distance(p + 1), first + 0.5 * 2.0, epsilon = 1e-12);
}

/// A source on a vertex of no face (the free end of a curve) reaches the sheets.
#[test]
fn a_source_on_a_curve_reaches_the_faces() {
    let (mesh, side) = two_squares_and_a_wire(4);
    let p = (2 * side * side) as u32;
    for options in [Options::DEFAULT, GRAPH, TRACKS, DIJKSTRA] {
        let field = Solver::new(&mesh, &Euclidean, &options)
            .and_then(|solver| solver.field(&[p]))
            .unwrap();
        assert_eq!(field.unreachable_vertices(), 0);
        assert_abs_diff_eq!(
            field.distance(0),
            1.0f64.hypot(0.5) + 2f64.sqrt(),
            epsilon = 1e-9
        );
    }
}

/// A path from B to a source in A runs along the wire: its segments there have no
/// face, it is as long as the distance, and straightening keeps the wire whole while
/// it straightens the pieces in A and B.
#[test]
fn paths_run_along_wires() {
    let (mesh, side) = two_squares_and_a_wire(6);
    let a_corner = (side * side - 1) as u32;
    let b_corner = (side * side + (side - 1) * side) as u32;
    for options in [Options::DEFAULT, TRACKS, GRAPH] {
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let source = Source::new(0);
        // B's vertex (4, 0): straight across B to the wire, then straight in A.
        let target = SurfacePoint::Vertex((side * side + side - 1) as u32);
        let path = solver.shortest_path(&[source], target).unwrap().0;
        let wire_segments = path.faces.iter().filter(|&&f| f == NONE).count();
        assert_eq!(wire_segments, 3, "{:?}", path.faces);
        let expected = 2f64.sqrt() + wire_length() + 2f64.sqrt();
        assert!(
            abs_diff_eq!(path.length, expected, epsilon = 1e-6),
            "{:?}: {} vs {expected}",
            options.method,
            path.length
        );
        assert!(path.length <= path.traced_length + 1e-12);
        // The wire's vertices are on the path, in order.
        let at = |v: u32| {
            path.points
                .iter()
                .position(|&p| p == SurfacePoint::Vertex(v))
        };
        let (b, a) = (at(b_corner).unwrap(), at(a_corner).unwrap());
        assert_eq!(a, b + 3);
        assert_eq!(path.metric_length(&mesh, &Euclidean), path.length);
    }
}

/// Early stops see the wire: a target across it gets its full-run value.
#[test]
fn early_stops_across_a_wire_keep_exact_values() {
    let (mesh, side) = two_squares_and_a_wire(4);
    // (3.25, 1), just past the wire's end in B: far nearer than B's far side.
    let target = (side * side + (side - 1) * side + 1) as u32;
    for options in [Options::DEFAULT, TRACKS, GRAPH] {
        let solver = Solver::new(&mesh, Euclidean, &options).unwrap();
        let full = solver.field(&[0]).unwrap();
        let stop = Stop::NONE.with_targets(vec![SurfacePoint::Vertex(target)]);
        let stopped = solver
            .field(Sources::from(&[Source::new(0)]).until(&stop))
            .unwrap();
        assert!(stopped.stats().stopped_early, "{:?}", options.method);
        assert_eq!(stopped.distance(target), full.distance(target));
    }
}

/// Random meshes with random wires between random vertices (some of them new vertices
/// of no face): the track-pruned engine keeps the Steiner graph's distances.
#[test]
fn tracks_equal_the_graph_with_random_wires() {
    for seed in 1..=12u64 {
        let Ok(mesh) = random_mesh(seed, 6) else {
            continue;
        };
        let mut rng = Rng((seed * 7919) | 1);
        let mut positions: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
        let n = positions.len();
        for _ in 0..3 {
            positions.push([rng.next() * 2.0, rng.next() * 2.0, rng.next()]);
        }
        let mut wires = Vec::new();
        for _ in 0..6 {
            let a = rng.below(positions.len()) as u32;
            let b = rng.below(positions.len()) as u32;
            wires.push([a, b]);
        }
        wires.push([n as u32, 0]);
        let mesh =
            TriMesh::with_line_elements(positions, mesh.triangles().to_vec(), wires).unwrap();
        let sources = [rng.below(n) as u32];
        let graph = Solver::new(&mesh, &Euclidean, &GRAPH)
            .and_then(|solver| solver.field(&sources))
            .unwrap();
        let tracks = Solver::new(&mesh, &Euclidean, &TRACKS)
            .and_then(|solver| solver.field(&sources))
            .unwrap();
        for (g, t) in graph.node_distances().iter().zip(tracks.node_distances()) {
            assert!(
                abs_diff_eq!(*g, *t, epsilon = 1e-9 * g.max(1.0))
                    || (g.is_infinite() && t.is_infinite()),
                "seed {seed}: {g} vs {t}"
            );
        }
    }
}

/// A metric whose wires cost NaN is refused when the solver is built, naming the wire.
#[test]
fn a_bad_wire_cost_is_a_typed_error() {
    struct BadWires;
    impl Metric for BadWires {
        fn cost(&self, _: u32, a: &FacePoint, b: &FacePoint) -> f64 {
            a.distance(b)
        }
        fn wire_cost(&self, _: u32, _: u32, _: f64) -> f64 {
            f64::NAN
        }
    }
    let (mesh, _) = two_squares_and_a_wire(2);
    let error = Solver::new(&mesh, BadWires, &Options::DEFAULT)
        .err()
        .unwrap();
    assert!(matches!(error, Error::InvalidWireCost { .. }), "{error}");
    assert!(error.to_string().contains("wire from vertex"), "{error}");
}
