//! The wavefront engine (`Method::Wave`) against exact distances: planar
//! meshes of any triangulation (needles, fans, jittered grids, holes), developable
//! strips (cylinder and cone sections, unrolled analytically), constant 3D tensors (the
//! linearly mapped mesh), the Spot model against exact (MMP) references; property tests
//! on random meshes (the Steiner graph as a reference: reachability, and the wave never
//! worse than the graph); queries and paths on wave fields.
//!
//! Exact distances in a plane region are computed here, independently of the library:
//! the region is the union of the mesh's (unrolled) triangles; a segment lies in it when
//! the triangles cover it; the shortest path from the sources is a polyline through
//! reflex boundary vertices (the visibility graph, Dijkstra over the sources and the
//! reflex vertices).

// Tests aside from the function-length rule (clippy.toml): a scenario reads best whole.
#![allow(clippy::too_many_lines)]

mod common;

use common::plane::{
    cones, convex_planar_meshes, deviation, holey_meshes, random_edge_point, random_vertex,
    several_sources, single_sources, Deviation, Region,
};

use common::{
    cylinder_strip, grid, holey_grid, multiscale_mesh, needle_square, random_book,
    random_face_point, random_mesh, read_reference, relative_error, sphere, Rng,
};
use geotracks::glam::{DVec2, DVec3};
use geotracks::mesh::{io::read_mesh, TriMesh};
use geotracks::steiner::NodeKind;
use geotracks::Sources;
use geotracks::{
    Density, Euclidean, FieldData, Method, Metric, Options, Solver, Source, Stop, SurfacePoint,
    Tensor,
};
use proptest::prelude::*;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

fn wave(k: f64) -> Options {
    Options::DEFAULT.with_k(k).with_method(Method::Wave)
}

/// Runs the wave engine and compares it with the exact distances.
fn wave_deviation(mesh: &TriMesh, region: &Region, k: f64, sources: &[Source]) -> Deviation {
    let solver = Solver::new(mesh, Euclidean, &wave(k)).unwrap();
    let field = solver
        .field(Sources::from(sources).until(&Stop::NONE))
        .unwrap();
    assert_eq!(field.stats().method, Method::Wave);
    deviation(mesh, region, field.data(), sources)
}

/// Runs the wave engine on `mesh` from each of `sets` at k = 1, 2, 3 and returns the
/// worst deviation from the exact distances in `region`, after asserting that no node
/// is below the exact distance (1e-9 relative) and, when `exact`, that every node that
/// sees its nearest source has the exact distance (1e-9 relative).
fn check_planar(
    name: &str,
    mesh: &TriMesh,
    region: &Region,
    sets: &[Vec<Source>],
    exact: bool,
) -> Deviation {
    let mut all = Deviation::default();
    for k in [1.0, 2.0, 3.0] {
        for sources in sets {
            let dev = wave_deviation(mesh, region, k, sources);
            assert!(
                dev.below <= 1e-9,
                "{name}, k = {k}, sources {sources:?}: a node {:e} below the exact distance",
                dev.below
            );
            if exact {
                assert!(
                    dev.direct <= 1e-9,
                    "{name}, k = {k}, sources {sources:?}: relative error {:e}",
                    dev.direct
                );
            }
            all = all.merge(dev);
        }
    }
    println!(
        "{name}: {} nodes in all; worst relative error where the source is seen {:e}, behind \
         (in {} nodes) {:e}; worst below the exact distance {:e}",
        all.nodes, all.direct, all.behind_count, all.behind_excess, all.below
    );
    all
}

/// The largest ratio of a triangle's longest edge to its height on it.
fn max_aspect(mesh: &TriMesh) -> f64 {
    mesh.triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.position(v));
            let area2 = (b - a).cross(c - a).length();
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            longest * longest / area2
        })
        .fold(0.0, f64::max)
}

/// Exactness claim 1: on a planar mesh of any triangulation (here needles with aspect
/// ratios of 1000 and more, fans, jittered grids), from one source of any kind and any
/// start value, every node (vertex and Steiner point) has the exact distance.
#[test]
fn planar_meshes_are_exact_from_one_source() {
    let meshes = convex_planar_meshes();
    assert!(
        max_aspect(&meshes[0].1) > 1000.0,
        "{}",
        max_aspect(&meshes[0].1)
    );
    assert!(
        max_aspect(&meshes[1].1) > 1000.0,
        "{}",
        max_aspect(&meshes[1].1)
    );
    assert!(
        max_aspect(&meshes[2].1) > 1000.0,
        "{}",
        max_aspect(&meshes[2].1)
    );
    for (seed, (name, mesh)) in meshes.iter().enumerate() {
        let region = Region::flat(mesh);
        assert!(region.reflex.is_empty());
        let dev = check_planar(
            name,
            mesh,
            &region,
            &single_sources(mesh, seed as u64),
            true,
        );
        assert_eq!(dev.behind_count, 0);
    }
}

/// Exactness claim 1 with several sources: the distance is the least over the sources
/// (start values included) of the straight distance, and should be exact too.
#[test]
#[ignore = "bug: one wave per node: where the waves of two sources meet, lines of one \
            wave through the part of an edge whose nodes carry the other are lost \
            (0.36 % above exact at the first failing node, k = 1)"]
fn planar_meshes_are_exact_from_several_sources() {
    for (seed, (name, mesh)) in convex_planar_meshes().iter().enumerate() {
        let region = Region::flat(mesh);
        check_planar(
            name,
            mesh,
            &region,
            &several_sources(mesh, seed as u64),
            true,
        );
    }
}

/// The largest `(wave − graph) / scale` over the nodes of a wave run and a graph run on
/// the same Steiner points (exactly `count` per edge), asserting that both reach the
/// same nodes.
fn wave_over_graph<M: Metric>(mesh: &TriMesh, metric: &M, sources: &[Source], count: u32) -> f64 {
    let options = Options::DEFAULT.with_fixed_count(count);
    let run = |method| {
        Solver::new(mesh, metric, &options.with_method(method))
            .unwrap()
            .field(Sources::from(sources).until(&Stop::NONE))
            .unwrap()
    };
    let (w, g) = (run(Method::Wave), run(Method::Graph));
    assert_eq!(w.stats().method, Method::Wave);
    assert_eq!(w.node_distances().len(), g.node_distances().len());
    let lowest = sources.iter().map(|s| s.start.abs()).fold(0.0, f64::max);
    let mut worst = f64::NEG_INFINITY;
    for (node, (&a, &b)) in w
        .node_distances()
        .iter()
        .zip(g.node_distances())
        .enumerate()
    {
        assert_eq!(
            a.is_finite(),
            b.is_finite(),
            "node {node}: wave {a}, graph {b}"
        );
        if b.is_finite() {
            worst = worst.max((a - b) / b.abs().max(lowest).max(f64::MIN_POSITIVE));
        }
    }
    worst
}

/// With several sources the wave engine is not exact (see the ignored test above), but
/// keeps the contract: never below the exact distance, never worse than the Steiner
/// graph on the same points.
#[test]
fn planar_meshes_from_several_sources_never_below_exact_nor_above_the_graph() {
    let mut worst_excess = 0.0f64;
    let mut worst_ratio = f64::NEG_INFINITY;
    for (seed, (name, mesh)) in convex_planar_meshes().iter().enumerate() {
        let region = Region::flat(mesh);
        let sets = several_sources(mesh, seed as u64);
        let dev = check_planar(name, mesh, &region, &sets, false);
        worst_excess = worst_excess.max(dev.direct);
        for sources in &sets {
            for count in [1, 2] {
                let r = wave_over_graph(mesh, &Euclidean, sources, count);
                assert!(
                    r <= 1e-9,
                    "{name}, {count} per edge, {sources:?}: wave above graph by {r:e}"
                );
                worst_ratio = worst_ratio.max(r);
            }
        }
    }
    println!(
        "several sources: worst relative excess over the exact distance {worst_excess:e}; \
         worst (wave − graph) / graph {worst_ratio:e}"
    );
}

/// The region outside a square hole, by hand: `[0, 3]²` minus `(1, 2)²`, a 12 × 12 grid.
/// From `(0, 1.5)`, the point `(3, 1.5)` is reached around the hole through its corners
/// `(1, 1)` and `(2, 1)` (or the mirror images): `2·√1.25 + 1`; `(2.5, 1.5)` through `(1,
/// 2)` and `(2, 2)`: `√1.25 + 1 + √0.5`; `(2, 3)` and `(1, 1.5)` see the source. Checks
/// the exact-distance code on them, and the engine against them.
#[test]
fn square_hole_by_hand() {
    let ticks: Vec<f64> = (0..=12).map(|i| i as f64 / 4.0).collect();
    let mesh = common::xy_grid(&ticks, &ticks, Some([4, 4, 8, 8]), |i, j| (i + j) % 2 == 0);
    let region = Region::flat(&mesh);
    assert_eq!(region.reflex.len(), 4);
    let vertex_at = |x: f64, y: f64| {
        (0..mesh.vertex_count() as u32)
            .find(|&v| mesh.position(v).distance(DVec3::new(x, y, 0.0)) < 1e-12)
            .unwrap()
    };
    let source = vertex_at(0.0, 1.5);
    let exact = region.exact(&[(DVec2::new(0.0, 1.5), 0.0)]);
    let by_hand = [
        ((3.0, 1.5), 2.0 * 1.25f64.sqrt() + 1.0, false),
        ((2.5, 1.5), 1.25f64.sqrt() + 1.0 + 0.5f64.sqrt(), false),
        ((2.0, 3.0), (4.0f64 + 2.25).sqrt(), true),
        ((1.0, 1.5), 1.0, true), // on the hole's edge
    ];
    for ((x, y), d, direct) in by_hand {
        let (e, seen) = exact.at(DVec2::new(x, y));
        assert!((e - d).abs() < 1e-12, "({x}, {y}): {e} vs {d}");
        assert_eq!(seen, direct, "({x}, {y})");
    }
    for k in [1.0, 2.0, 3.0] {
        let field = Solver::new(&mesh, Euclidean, &wave(k))
            .unwrap()
            .field(&[source])
            .unwrap();
        for ((x, y), d, _) in &by_hand {
            let got = field.distance(vertex_at(*x, *y));
            assert!(got >= d * (1.0 - 1e-9), "k = {k}, ({x}, {y}): {got} < {d}");
            println!(
                "square hole, k = {k}: ({x}, {y}) {got} (exact {d}, {:+e})",
                got / d - 1.0
            );
        }
        let dev = deviation(&mesh, &region, field.data(), &[Source::new(source)]);
        assert!(dev.below <= 1e-9, "k = {k}: {dev:?}");
    }
}

/// Around holes: no node ever below the true (shortest-path) distance, nor above the
/// Steiner graph's on the same points; the error is measured.
#[test]
fn holes_never_below_the_true_distance_nor_above_the_graph() {
    let mut worst_ratio = f64::NEG_INFINITY;
    for (seed, (name, mesh)) in holey_meshes().iter().enumerate() {
        let region = Region::flat(mesh);
        assert!(!region.reflex.is_empty());
        let mut sets = single_sources(mesh, seed as u64);
        sets.extend(several_sources(mesh, seed as u64));
        check_planar(name, mesh, &region, &sets, false);
        for sources in &sets {
            let r = wave_over_graph(mesh, &Euclidean, sources, 1);
            assert!(r <= 1e-9, "{name}, {sources:?}: wave above graph by {r:e}");
            worst_ratio = worst_ratio.max(r);
        }
    }
    println!("holes: worst (wave − graph) / graph {worst_ratio:e}");
}

/// Exactness claim 1 with holes: where the straight segment from the source stays on
/// the mesh, the distance is exact.
#[test]
#[ignore = "bug: one wave per node: the lit and the shadow side of a hole's corner \
            split edges between the source's wave and the corner's, and lines of the \
            source's wave through the shadow side's nodes are lost (0.11 % above exact at \
            the first failing node that sees the source, k = 1)"]
fn holes_exact_where_the_source_is_seen() {
    for (seed, (name, mesh)) in holey_meshes().iter().enumerate() {
        let region = Region::flat(mesh);
        check_planar(
            name,
            mesh,
            &region,
            &single_sources(mesh, seed as u64),
            true,
        );
    }
}

/// Exactness claim 2: a developable strip (a cylinder section, unrolled: a rectangle) is
/// exact from one source of any kind; several sources keep the contract (never below
/// exact, never above the graph).
#[test]
fn cylinder_strips_are_exact() {
    let strips = [
        ("cylinder 40 × 12", cylinder_strip(3, 40, 12, 1.0, 4.5, 1.0)),
        (
            "cylinder 200 × 6 (needles)",
            cylinder_strip(5, 200, 6, 2.0, 5.5, 0.3),
        ),
    ];
    for (seed, (name, (mesh, unrolled))) in strips.iter().enumerate() {
        let region = Region::new(mesh, unrolled.iter().map(|&p| DVec2::from(p)).collect());
        assert!(region.reflex.is_empty());
        check_planar(
            name,
            mesh,
            &region,
            &single_sources(mesh, seed as u64),
            true,
        );
        let sets = several_sources(mesh, seed as u64);
        check_planar(name, mesh, &region, &sets, false);
        for sources in &sets {
            let r = wave_over_graph(mesh, &Euclidean, sources, 1);
            assert!(r <= 1e-9, "{name}, {sources:?}: wave above graph by {r:e}");
        }
    }
}

/// A cone section unrolls to an annulus sector: its inner boundary is reflex, so lines
/// may leave the strip there. Never below the exact distance, never above the graph.
#[test]
fn cone_strips_never_below_exact() {
    for (seed, (name, (mesh, unrolled))) in cones().iter().enumerate() {
        let region = Region::new(mesh, unrolled.iter().map(|&p| DVec2::from(p)).collect());
        assert!(!region.reflex.is_empty());
        let mut sets = single_sources(mesh, seed as u64);
        sets.extend(several_sources(mesh, seed as u64));
        check_planar(name, mesh, &region, &sets, false);
        for sources in &sets {
            let r = wave_over_graph(mesh, &Euclidean, sources, 1);
            assert!(r <= 1e-9, "{name}, {sources:?}: wave above graph by {r:e}");
        }
    }
}

/// Exactness claim 2 on a cone section: exact where the unrolled segment from the
/// source stays on the strip.
#[test]
#[ignore = "bug: as holes_exact_where_the_source_is_seen: the cone's inner boundary \
            vertices are reflex, their waves and the source's split edges (2.1 % above \
            exact at the first failing node that sees the source, k = 1)"]
fn cone_strips_exact_where_the_source_is_seen() {
    for (seed, (name, (mesh, unrolled))) in cones().iter().enumerate() {
        let region = Region::new(mesh, unrolled.iter().map(|&p| DVec2::from(p)).collect());
        check_planar(
            name,
            mesh,
            &region,
            &single_sources(mesh, seed as u64),
            true,
        );
    }
}

/// Sliver cells (a column 1e-7 to 1e-10 wide, as real meshes and `multiscale_mesh`
/// have): no value below the exact distance. Minimal case: columns at x = 0, ε, 0.5, 1
/// and rows at y = 0, 0.5, 1, cells split along their rising diagonals, k = 1, source
/// vertex 4 = (0, 0.5): with ε = 1e-7 vertex 5 = (ε, 0.5) gets 1.1e-16 instead of 1e-7,
/// vertex 6 = (0.5, 0.5) 0.4999999 instead of 0.5 (and vertices 5, 16, 21 are each
/// other's parents: a cycle); a cylinder strip with a column 7.9e-10 wide gets 2.2 %
/// below the exact distance.
#[test]
fn slivers_never_below_exact() {
    let mut worst = 0.0f64;
    for eps in [1e-3, 1e-5, 1e-7, 1e-8, 1e-9, 1e-10] {
        for rising in [false, true] {
            let mesh =
                common::xy_grid(&[0.0, eps, 0.5, 1.0], &[0.0, 0.5, 1.0], None, |_, _| rising);
            let region = Region::flat(&mesh);
            for v in 0..mesh.vertex_count() as u32 {
                for k in [1.0, 2.0] {
                    let dev = wave_deviation(&mesh, &region, k, &[Source::new(v)]);
                    worst = worst.max(dev.below);
                    assert!(
                        dev.below <= 1e-6,
                        "ε = {eps}, rising {rising}, k = {k}, source {v}: {:e} below exact",
                        dev.below
                    );
                }
            }
            for face in 0..mesh.face_count() as u32 {
                let source = Source::new(SurfacePoint::Face {
                    face,
                    bary: [0.3, 0.3, 0.4],
                });
                let dev = wave_deviation(&mesh, &region, 1.0, &[source]);
                assert!(
                    dev.below <= 1e-6,
                    "ε = {eps}, rising {rising}, {source:?}: {:e}",
                    dev.below
                );
            }
        }
    }
    // Random column widths and row heights (the first column of this one is 7.9e-10
    // wide).
    let mut rng = Rng(3);
    let thetas: Vec<f64> = common::random_partition(&mut rng, 40)
        .iter()
        .map(|t| t * 4.5)
        .collect();
    let zs = common::random_partition(&mut rng, 12);
    let mut xs = vec![0.0];
    for w in thetas.windows(2) {
        xs.push(xs.last().unwrap() + 2.0 * ((w[1] - w[0]) / 2.0).sin());
    }
    let mesh = common::xy_grid(&xs, &zs, None, |i, j| (i * 7 + j * 3) % 5 < 2);
    let region = Region::flat(&mesh);
    for (seed, sources) in single_sources(&mesh, 5).iter().enumerate() {
        let dev = wave_deviation(&mesh, &region, 1.0, sources);
        assert!(
            dev.below <= 1e-6,
            "random slivers, set {seed}: {:e} below",
            dev.below
        );
    }
    println!("slivers: worst {worst:e} below the exact distance");
}

// ---------------------------------------------------------------------------------
// Constant 3D tensors: the mapped mesh.

/// A random invertible 3×3 matrix (rows), well conditioned enough.
fn random_matrix(rng: &mut Rng) -> [[f64; 3]; 3] {
    loop {
        let a: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (i == j) as u8 as f64 + 1.5 * (rng.next() - 0.5))
        });
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        if det.abs() > 0.2 {
            return a;
        }
    }
}

/// `M = AᵀA` as `[xx, xy, xz, yy, yz, zz]`: `sqrt(vᵀ M v) = |A v|`.
fn gram(a: &[[f64; 3]; 3]) -> [f64; 6] {
    let m = |i: usize, j: usize| (0..3).map(|r| a[r][i] * a[r][j]).sum::<f64>();
    [m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2)]
}

/// The mesh with every vertex mapped by `a`.
fn mapped(mesh: &TriMesh, a: &[[f64; 3]; 3]) -> TriMesh {
    let positions = mesh
        .positions()
        .iter()
        .map(|p| {
            let p = p.to_array();
            std::array::from_fn(|i| (0..3).map(|j| a[i][j] * p[j]).sum())
        })
        .collect();
    let mapped = TriMesh::new(positions, mesh.triangles().to_vec()).unwrap();
    assert_eq!(mapped.triangles(), mesh.triangles());
    assert_eq!(mapped.edge_count(), mesh.edge_count());
    mapped
}

/// Exactness claim 3 on flat meshes: under `Tensor::from_world(M = AᵀA)` on every face,
/// the distance on mesh X is the Euclidean distance on A·X, a plane region; from one
/// source of any kind, every node is exact.
#[test]
fn constant_tensor_on_flat_meshes_is_the_mapped_plane() {
    let meshes = [
        ("grid", grid(10, 1.0)),
        ("jittered grid", holey_grid(9, 10, 0.2, 0)),
        ("needle square", needle_square(9, 200)),
    ];
    let mut worst = 0.0f64;
    for (seed, (name, mesh)) in meshes.iter().enumerate() {
        for trial in 0..3u64 {
            let mut rng = Rng(101 + 2 * (seed as u64 * 3 + trial));
            let a = random_matrix(&mut rng);
            let tensor = Tensor::uniform_world(mesh, gram(&a)).unwrap();
            let image = mapped(mesh, &a);
            let region = Region::in_plane(&image);
            for k in [1.0, 2.0, 3.0] {
                for sources in single_sources(mesh, 7 * seed as u64 + trial) {
                    let solver = Solver::new(mesh, &tensor, &wave(k)).unwrap();
                    let field = solver
                        .field(Sources::from(&sources).until(&Stop::NONE))
                        .unwrap();
                    assert_eq!(field.stats().method, Method::Wave);
                    let dev = deviation(&image, &region, field.data(), &sources);
                    assert!(
                        dev.direct <= 1e-9 && dev.below <= 1e-9,
                        "{name}, A = {a:?}, k = {k}, {sources:?}: {dev:?}"
                    );
                    worst = worst.max(dev.direct);
                }
            }
        }
    }
    println!("constant tensor on flat meshes: worst relative error {worst:e}");
}

fn spot() -> TriMesh {
    read_mesh(format!("{DATA}/spot.obj")).unwrap()
}

/// The map of `tests/data/spot.aniso.src0.json` (a stretch by 3 along (1, 1, 0) and a
/// shear of 0.5), whose exact (MMP) distances on the mapped Spot are
/// `tests/data/spot.aniso.src0.f64`.
const SPOT_A: [[f64; 3]; 3] = [
    [2.25, 1.2499999999999998, 0.0],
    [0.7499999999999998, 1.7499999999999998, 0.0],
    [0.0, 0.0, 1.0],
];

/// Exactness claim 3 on Spot: `Method::Wave` under `M = AᵀA` on Spot is
/// `Method::Wave` with `Euclidean` on A·Spot (the same geometry after the map), at every
/// node; with the reference's A and with a random one.
#[test]
fn constant_tensor_on_spot_is_euclidean_on_the_mapped_spot() {
    let mesh = spot();
    let mut rng = Rng(77);
    for a in [SPOT_A, random_matrix(&mut rng)] {
        let tensor = Tensor::uniform_world(&mesh, gram(&a)).unwrap();
        let image = mapped(&mesh, &a);
        for k in [1.0, 2.0] {
            let sources = [
                Source::new(0),
                Source::new(random_face_point(&mesh, &mut rng)),
            ];
            for sources in [&sources[..1], &sources[1..]] {
                let t = Solver::new(&mesh, &tensor, &wave(k))
                    .unwrap()
                    .field(Sources::from(sources).until(&Stop::NONE))
                    .unwrap();
                let e = Solver::new(&image, Euclidean, &wave(k))
                    .unwrap()
                    .field(Sources::from(sources).until(&Stop::NONE))
                    .unwrap();
                assert_eq!(
                    (t.stats().method, e.stats().method),
                    (Method::Wave, Method::Wave)
                );
                assert_eq!(
                    t.node_distances().len(),
                    e.node_distances().len(),
                    "the same Steiner points"
                );
                let mut worst = 0.0f64;
                for (node, &x) in t.node_distances().iter().enumerate() {
                    // Steiner nodes are numbered along a space-filling curve: match them
                    // by edge and index.
                    let other = match t.layout().kind(node as u32) {
                        NodeKind::Vertex(v) => v,
                        NodeKind::Steiner { edge, index } => {
                            assert_eq!(t.layout().count(edge), e.layout().count(edge));
                            e.layout().edge_nodes(edge).start + index
                        }
                    };
                    let y = e.node_distances()[other as usize];
                    let r = (x - y).abs() / y.max(1e-300);
                    assert!(
                        r <= 1e-9,
                        "A = {a:?}, k = {k}, {sources:?}, node {node}: tensor {x}, mapped {y}"
                    );
                    worst = worst.max(r);
                }
                println!(
                    "spot, A = {a:?}, k = {k}, {sources:?}: worst relative difference {worst:e}"
                );
            }
        }
    }
}

/// Under the reference's tensor, Spot against the exact distances on the mapped mesh.
#[test]
fn constant_tensor_on_spot_against_the_exact_reference() {
    let mesh = spot();
    let exact =
        read_reference(std::path::Path::new(&format!("{DATA}/spot.aniso.src0.f64"))).unwrap();
    assert_eq!(exact.len(), mesh.vertex_count());
    let tensor = Tensor::uniform_world(&mesh, gram(&SPOT_A)).unwrap();
    for (k, bound) in [(2.0, 0.0010), (3.0, 0.0010)] {
        let field = Solver::new(&mesh, &tensor, &wave(k))
            .unwrap()
            .field(&[0])
            .unwrap();
        let (mean, max) = relative_error(field.vertex_distances(), &exact);
        let below = below_exact(field.vertex_distances(), &exact);
        println!(
            "spot aniso, wave k = {k}: mean {:.4} %, max {:.4} %, worst below exact {below:e}",
            100.0 * mean,
            100.0 * max
        );
        assert!(mean <= bound, "k = {k}: mean relative error {mean}");
        assert!(below <= 1e-6, "k = {k}: {below:e} below the exact distance");
    }
}

/// The worst `(exact − d) / exact` (how far below the exact distance a value is).
fn below_exact(d: &[f64], exact: &[f64]) -> f64 {
    d.iter()
        .zip(exact)
        .filter(|(_, e)| **e > 0.0)
        .map(|(d, e)| (e - d) / e)
        .fold(f64::NEG_INFINITY, f64::max)
}

// ---------------------------------------------------------------------------------
// Spot against exact geodesics.

fn spot_error(options: &Options) -> (f64, f64, f64, Method) {
    let mesh = spot();
    let exact = read_reference(std::path::Path::new(&format!("{DATA}/spot.src0.f64"))).unwrap();
    let field = Solver::new(&mesh, Euclidean, options)
        .unwrap()
        .field(&[0])
        .unwrap();
    let (mean, max) = relative_error(field.vertex_distances(), &exact);
    let below = below_exact(field.vertex_distances(), &exact);
    println!(
        "spot, {} k = {}: mean {:.4} %, max {:.4} %, worst below exact {below:e}",
        field.stats().method,
        field.stats().k,
        100.0 * mean,
        100.0 * max
    );
    (mean, max, below, field.stats().method)
}

/// The wave engine at k = 2 on Spot: mean error at most 0.10 %, no vertex more than
/// 1e-6 below the exact distance.
#[test]
fn spot_wave_at_k2_within_0_10_percent() {
    let (mean, _, below, method) = spot_error(&wave(2.0));
    assert_eq!(method, Method::Wave);
    assert!(mean <= 0.0010, "mean relative error {mean}");
    assert!(below <= 1e-6, "{below:e} below the exact distance");
}

/// The default settings (the wavefront engine at k = 2) on Spot: mean error at most
/// 0.10 %.
#[test]
fn spot_default_within_0_10_percent() {
    let (mean, _, below, _) = spot_error(&Options::DEFAULT);
    assert!(mean <= 0.0010, "mean relative error {mean}");
    assert!(below <= 1e-6, "{below:e} below the exact distance");
}

/// A metric that is not face-flat (a density) runs the tracks engine instead, and says
/// so.
#[test]
fn wave_falls_back_to_tracks_without_a_flat_metric() {
    let mesh = holey_grid(5, 6, 0.2, 1);
    let density = Density::constant(&mesh, 2.0).unwrap();
    let field = geotracks::Solver::new(&mesh, &density, &wave(3.0))
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    assert_eq!(field.stats().method, Method::Tracks);
    let tracks = geotracks::Solver::new(&mesh, &density, &Options::DEFAULT.with_k(3.0))
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    assert_eq!(field.node_distances(), tracks.node_distances());
    let euclidean = geotracks::Solver::new(&mesh, &Euclidean, &wave(3.0))
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    assert_eq!(euclidean.stats().method, Method::Wave);
}

// ---------------------------------------------------------------------------------
// Property tests on random meshes.

/// One to three random sources (vertices, edge points, face points) with random start
/// values, some negative.
fn random_sources(mesh: &TriMesh, rng: &mut Rng) -> Vec<Source> {
    (0..1 + rng.below(3))
        .map(|_| {
            let point = match rng.below(3) {
                0 => random_vertex(mesh, rng),
                1 => random_edge_point(mesh, rng),
                _ => random_face_point(mesh, rng),
            };
            let start = match rng.below(3) {
                0 => 0.0,
                1 => -rng.next(),
                _ => rng.next(),
            };
            Source::new(point).with_start(start)
        })
        .collect()
}

/// Random SPD tensors: λ₁ up to `anisotropy`, λ₂ up to 1.1, random directions.
fn random_tensor(mesh: &TriMesh, rng: &mut Rng, anisotropy: f64) -> Option<Tensor> {
    let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
        .map(|_| {
            (
                0.1 + anisotropy * rng.next(),
                0.1 + rng.next(),
                [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5],
            )
        })
        .collect();
    Tensor::from_principal(mesh, &principal).ok()
}

/// A random mesh of one of the kinds the engines are tested on. (In debug builds the
/// multiscale meshes are replaced by perturbed grids: the wave engine trips the queue's
/// overflow check on them, see `wave_queue_counts_do_not_overflow`.)
fn random_kind(kind: u8, seed: u64) -> TriMesh {
    let n = (seed % 5) as usize;
    let kind = if kind == 3 && cfg!(debug_assertions) {
        0
    } else {
        kind
    };
    match kind {
        0 => random_mesh(seed, 2 + n).unwrap(),
        1 => random_book(seed, 3 + n % 4, 1 + n % 4),
        2 => sphere(n % 3, 0.4, seed),
        3 => multiscale_mesh(seed, 2 + n),
        _ => holey_grid(seed, 4 + n, 0.2, 2),
    }
}

/// The wave engine against the Steiner graph, on the same points (a fixed count per
/// edge) at every node, or at the same k (interval scheme: the wave engine puts at least
/// one point on every edge and, under a tensor, spaces them by the metric's lengths,
/// keeping the graph's points only on edges whose faces do not glue, so the points
/// differ) at the vertices. Asserts that both reach the same nodes and returns
/// the worst `(wave − graph) / scale`.
fn wave_versus_graph<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    sources: &[Source],
    options: Options,
) -> f64 {
    let run = |method| {
        Solver::new(mesh, metric, &options.with_method(method))
            .unwrap()
            .field(Sources::from(sources).until(&Stop::NONE))
            .unwrap()
    };
    let (w, g) = (run(Method::Wave), run(Method::Graph));
    assert_eq!(w.stats().method, Method::Wave);
    let same_points =
        (0..mesh.edge_count() as u32).all(|e| w.layout().count(e) == g.layout().count(e));
    if let Some(geotracks::SteinerScheme::Fixed { .. }) = options.steiner {
        assert!(same_points);
    }
    let compared = if same_points {
        w.node_distances().len()
    } else {
        mesh.vertex_count()
    };
    let lowest = sources.iter().map(|s| s.start.abs()).fold(0.0, f64::max);
    let mut worst = f64::NEG_INFINITY;
    for node in 0..compared {
        let (a, b) = (w.node_distances()[node], g.node_distances()[node]);
        assert_eq!(
            a.is_finite(),
            b.is_finite(),
            "node {node}: wave {a}, graph {b}"
        );
        assert!(!a.is_nan());
        if b.is_finite() {
            worst = worst.max((a - b) / b.abs().max(lowest).max(f64::MIN_POSITIVE));
        }
    }
    worst
}

/// The tolerance of "never worse than the graph". Measured (`wave_versus_graph_measured`,
/// 400 random meshes): under Euclidean the wave engine is never above the graph by more
/// than rounding (5e-16 relative), on the same points at every node and at the same k
/// at the vertices; under per-face tensors by at most 1e-13 (multiscale meshes; 1e-15
/// on the others). `tests/engine_properties.rs` holds it at the same k for tensors up
/// to 1e6 anisotropy.
const OVER_GRAPH_SAME_POINTS: f64 = 1e-9;

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Random meshes (perturbed grids with holes and fins, non-manifold books and fans,
    /// spheres, multiscale meshes, planar grids with holes), Euclidean or a random SPD
    /// tensor, random sources: no panic, the wave engine reaches exactly the nodes the
    /// graph reaches (the sources' components), with finite values there; under
    /// Euclidean it is never above the graph on the same points.
    #[test]
    fn random_meshes_wave_reaches_what_the_graph_reaches_and_never_exceeds_it(
        seed in any::<u64>(), kind in 0u8..5, count in 1u32..4, tensor in any::<bool>(),
        anisotropy in 1.0f64..30.0,
    ) {
        let mesh = random_kind(kind, seed);
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let sources = random_sources(&mesh, &mut rng);
        let options = Options::DEFAULT.with_fixed_count(count);
        match random_tensor(&mesh, &mut rng, anisotropy).filter(|_| tensor) {
            // Reachability only: see random_tensors_never_above_the_graph.
            Some(t) => {
                wave_versus_graph(&mesh, &t, &sources, options);
            }
            None => {
                let r = wave_versus_graph(&mesh, &Euclidean, &sources, options);
                prop_assert!(r <= OVER_GRAPH_SAME_POINTS, "wave above graph by {:e}", r);
            }
        }
    }

    /// Under random per-face tensors, never above the graph on the same points. Minimal
    /// case: `random_mesh(245, 2)`, `random_tensor(.., Rng(245 * 31), 10.0)`, source
    /// vertex 0, 2 points per edge: Steiner node 56 (edge 16, index 1) gets 3.03970 where
    /// the graph gives 3.03415: its graph parent, node 60 (edge 18 between faces 4 and 5,
    /// value 2.10615, itself far below the graph's 2.60481) never offers it across
    /// face 4.
    #[test]
        fn random_tensors_never_above_the_graph(
        seed in any::<u64>(), kind in 0u8..5, count in 1u32..4, anisotropy in 1.0f64..30.0,
    ) {
        let mesh = random_kind(kind, seed);
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let sources = random_sources(&mesh, &mut rng);
        if let Some(t) = random_tensor(&mesh, &mut rng, anisotropy) {
            let r = wave_versus_graph(&mesh, &t, &sources, Options::DEFAULT.with_fixed_count(count));
            prop_assert!(r <= OVER_GRAPH_SAME_POINTS, "wave above graph by {:e}", r);
        }
    }

    /// As above at the same k (interval scheme), compared at the vertices: no panic,
    /// the same reachability (the wave engine's extra points change no component).
    #[test]
    fn random_meshes_at_the_same_k_reach_the_same_vertices(
        seed in any::<u64>(), kind in 0u8..5, k in 1u32..5, tensor in any::<bool>(),
    ) {
        let mesh = random_kind(kind, seed);
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let sources = random_sources(&mesh, &mut rng);
        let options = Options::DEFAULT.with_k(k as f64);
        match random_tensor(&mesh, &mut rng, 10.0).filter(|_| tensor) {
            Some(t) => wave_versus_graph(&mesh, &t, &sources, options),
            None => wave_versus_graph(&mesh, &Euclidean, &sources, options),
        };
    }

    /// Planar random meshes (z = 0: jittered grids with holes), Euclidean, random
    /// sources: no node more than 1e-6 relative below the exact distance (the contract;
    /// measured: rounding only).
    #[test]
    fn planar_random_meshes_never_below_exact(
        seed in any::<u64>(), n in 3usize..11, jitter in 0.0f64..0.24, holes in 0usize..4,
        k in 1u32..4,
    ) {
        let mesh = holey_grid(seed, n, jitter, holes);
        let region = Region::flat(&mesh);
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let sources = random_sources(&mesh, &mut rng);
        let dev = wave_deviation(&mesh, &region, k as f64, &sources);
        prop_assert!(dev.below <= 1e-6, "{:e} below the exact distance", dev.below);
    }
}

/// `0 = x₀ < … < xₙ = 1` with about a third of the intervals slivers (1e-5 to 1e-10 of
/// the others).
fn sliver_partition(rng: &mut Rng, n: usize) -> Vec<f64> {
    let widths: Vec<f64> = (0..n)
        .map(|_| {
            if rng.next() < 0.3 {
                10f64.powf(-5.0 - 5.0 * rng.next())
            } else {
                0.5 + rng.next()
            }
        })
        .collect();
    let total: f64 = widths.iter().sum();
    let mut xs = vec![0.0];
    for w in &widths {
        xs.push(xs.last().unwrap() + w / total);
    }
    *xs.last_mut().unwrap() = 1.0;
    xs
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Planar grids with sliver columns and rows (1e-5 to 1e-10 of the others),
    /// Euclidean, random sources: no node more than 1e-6 relative below the exact
    /// distance.
    #[test]
        fn planar_sliver_grids_never_below_exact(seed in any::<u64>(), n in 2usize..12, k in 1u32..3) {
        let mut rng = Rng(seed | 1);
        let xs = sliver_partition(&mut rng, n);
        let ys = sliver_partition(&mut rng, n);
        let mesh = common::xy_grid(&xs, &ys, None, |i, j| (i * 7 + j * 3 + seed as usize) % 5 < 2);
        let region = Region::flat(&mesh);
        let sources = random_sources(&mesh, &mut rng);
        let dev = wave_deviation(&mesh, &region, k as f64, &sources);
        prop_assert!(dev.below <= 1e-6, "{:e} below the exact distance", dev.below);
    }
}

/// The measured margins of the properties above over a fixed set of random meshes:
/// wave − graph on the same points (every node) and at the same k (vertices), per kind
/// of mesh and metric.
#[test]
fn wave_versus_graph_measured() {
    // [kind][tensor]: (worst, seed) on the same points; (worst, seed), best at k = 3.
    let mut same_points = [[(f64::NEG_INFINITY, 0u64); 2]; 5];
    let mut same_k = [[(f64::NEG_INFINITY, 0u64, f64::INFINITY); 2]; 5];
    for seed in 1..41u64 {
        for kind in 0..5u8 {
            let mesh = random_kind(kind, seed * 7919);
            let mut rng = Rng(seed * 31 + kind as u64);
            let sources = random_sources(&mesh, &mut rng);
            let tensor = random_tensor(&mesh, &mut rng, 10.0).filter(|_| seed % 2 == 0);
            let m = tensor.is_some() as usize;
            let compare = |options| match &tensor {
                Some(t) => wave_versus_graph(&mesh, t, &sources, options),
                None => wave_versus_graph(&mesh, &Euclidean, &sources, options),
            };
            for count in [1, 2] {
                let r = compare(Options::DEFAULT.with_fixed_count(count));
                let w = &mut same_points[kind as usize][m];
                if r > w.0 {
                    *w = (r, seed);
                }
            }
            let r = compare(Options::DEFAULT.with_k(3.0));
            let w = &mut same_k[kind as usize][m];
            if r > w.0 {
                (w.0, w.1) = (r, seed);
            }
            w.2 = w.2.min(r);
        }
    }
    let kinds = [
        "perturbed grids",
        "books",
        "spheres",
        "multiscale (release builds; debug builds: perturbed grids)",
        "planar with holes",
    ];
    for (kind, name) in kinds.iter().enumerate() {
        for (m, metric) in ["euclidean", "tensor"].iter().enumerate() {
            let (p, ps) = same_points[kind][m];
            let (k, ks, kb) = same_k[kind][m];
            println!(
                "{name}, {metric}: (wave − graph) / graph on the same points {p:e} (seed {ps}); \
                 at k = 3 (vertices) worst {k:e} (seed {ks}), best {kb:e}"
            );
        }
    }
    // Under Euclidean (tensors: see random_tensors_never_above_the_graph).
    let worst = same_points
        .iter()
        .map(|w| w[0].0)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(worst <= OVER_GRAPH_SAME_POINTS, "{worst:e}");
}

/// Every value is a real path's length, so never below the true distance: on small
/// curved meshes (no exact reference) the true distance is at most the Steiner graph's
/// with 256 points per edge, which is within 1e-4 of it; the wave engine (1 or 3 points
/// per edge) must not be more than 1e-3 below that. Returns the worst.
fn converged_sweep(tensor: bool) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for seed in 1..13u64 {
        for kind in [0u8, 1, 2, 4] {
            let mesh = random_kind(kind, seed * 104_729);
            if mesh.face_count() > 80 {
                continue;
            }
            let mut rng = Rng(seed * 17 + kind as u64);
            let sources = [Source::new(random_vertex(&mesh, &mut rng))];
            let t = random_tensor(&mesh, &mut rng, 10.0).unwrap();
            for count in [1, 3] {
                let options = Options::DEFAULT.with_fixed_count(count);
                let below = if tensor {
                    below_converged(&mesh, &t, &sources, options)
                } else {
                    below_converged(&mesh, &Euclidean, &sources, options)
                };
                worst = worst.max(below);
                assert!(
                    below <= 1e-3,
                    "kind {kind}, seed {}, {count} per edge, {sources:?}: {below:e} below the \
                     graph with 256 per edge",
                    seed * 104_729
                );
            }
        }
    }
    println!("tensor {tensor}: worst {worst:e} below the graph with 256 per edge");
    worst
}

#[test]
fn euclidean_never_below_the_converged_graph() {
    converged_sweep(false);
}

/// As above under random per-face tensors. Minimal case found: `random_mesh(245, 2)` (a
/// 2 × 2 grid with fins), `random_tensor(.., Rng(245 * 31), 10.0)`, source vertex 0, 2
/// points per edge: vertex 4 gets 46 % less than the converged graph (0.536 × it), and
/// Steiner nodes 59 and 60 (edge 18) are each other's parents along the edge.
#[test]
fn tensor_never_below_the_converged_graph() {
    converged_sweep(true);
}

/// The worst `(fine − wave) / fine` over the vertices, `fine` the graph with 256 points
/// per edge.
fn below_converged<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    sources: &[Source],
    options: Options,
) -> f64 {
    let solve = |options: Options| {
        Solver::new(mesh, metric, &options)
            .unwrap()
            .field(Sources::from(sources).until(&Stop::NONE))
            .unwrap()
    };
    let w = solve(options.with_method(Method::Wave));
    // The tracks engine returns the graph's distances (tests/tracks_oracle.rs), faster.
    let fine = solve(
        Options::DEFAULT
            .with_fixed_count(256)
            .with_method(Method::Tracks),
    );
    (0..mesh.vertex_count() as u32)
        .filter(|&v| fine.distance(v).is_finite() && fine.distance(v) > 0.0)
        .map(|v| (fine.distance(v) - w.distance(v)) / fine.distance(v))
        .fold(f64::NEG_INFINITY, f64::max)
}
// ---------------------------------------------------------------------------------
// Queries and paths on wave fields.

/// How a path from `target` must look: it starts at the target, ends at its source, its
/// segments lie on their faces, its length is its segments' sum and at most the traced
/// length. Returns its length.
fn check_path<M: Metric>(
    query: &geotracks::Field<M>,
    target: SurfacePoint,
    path: &geotracks::GeodesicPath,
) -> f64 {
    let mesh = query.mesh();
    let target = target.validated(mesh).unwrap();
    assert_eq!(path.points[0], target, "the path starts at the target");
    let source = query.sources()[path.source as usize].point;
    let end = path.points.last().unwrap();
    assert!(
        (end.position(mesh) - source.position(mesh)).length() < 1e-12,
        "the path from {target} ends at {end}, not at its source {source}"
    );
    assert_eq!(path.faces.len() + 1, path.points.len());
    for (i, &f) in path.faces.iter().enumerate() {
        for p in [path.points[i], path.points[i + 1]] {
            assert!(
                p.bary_in(mesh, f).is_some(),
                "segment {i}: {p} is not on face {f}"
            );
        }
    }
    let sum = path.metric_length(mesh, query.metric());
    assert!(
        (sum - path.length).abs() <= 1e-12 * sum.max(1.0),
        "{sum} vs {}",
        path.length
    );
    assert!(path.length.is_finite() && path.traced_length.is_finite());
    assert!(
        path.length <= path.traced_length * (1.0 + 1e-12) + 1e-300,
        "straightened {} > traced {}",
        path.length,
        path.traced_length
    );
    path.length
}

/// `distance_at` and `path` through `Ok::<_, geotracks::Error>(&field)` on wave fields: at a vertex
/// `distance_at` is the node's value; at any point it is finite where reached and never
/// below the exact distance (planar meshes); every path ends at its source, is no longer
/// than traced, and (planar) no shorter than the exact distance. Paths from every vertex
/// (no parent cycle) and labels of every reached vertex.
#[test]
fn queries_and_paths_on_wave_fields() {
    let planar: Vec<(String, TriMesh)> = vec![
        ("grid with holes".to_string(), holey_grid(11, 10, 0.2, 2)),
        ("needle square".to_string(), needle_square(11, 100)),
        ("jittered grid".to_string(), holey_grid(13, 8, 0.2, 0)),
    ];
    let (mut worst_at, mut worst_path, mut worst_traced) = (0.0f64, 0.0f64, 0.0f64);
    let (mut sum_at, mut sum_path, mut far_points) = (0.0, 0.0, 0usize);
    let mut cycles = 0;
    for (seed, (name, mesh)) in planar.iter().enumerate() {
        let region = Region::flat(mesh);
        let mut sets = single_sources(mesh, 100 + seed as u64);
        sets.extend(several_sources(mesh, 100 + seed as u64));
        for sources in &sets {
            let solver = Solver::new(mesh, Euclidean, &wave(2.0)).unwrap();
            let field = solver
                .field(Sources::from(sources).until(&Stop::NONE))
                .unwrap();
            let query = &field;
            let points: Vec<(DVec2, f64)> = sources
                .iter()
                .map(|s| (region.point(mesh, s.point), s.start))
                .collect();
            let exact = region.exact(&points);
            let lowest = sources.iter().map(|s| s.start.abs()).fold(0.0, f64::max);
            let mut rng = Rng(7 + seed as u64);
            let mut targets: Vec<SurfacePoint> = (0..mesh.vertex_count() as u32)
                .map(SurfacePoint::Vertex)
                .collect();
            for _ in 0..60 {
                targets.push(random_face_point(mesh, &mut rng));
                targets.push(random_edge_point(mesh, &mut rng));
            }
            for target in targets {
                let d = query.distance_at(target).unwrap();
                if let SurfacePoint::Vertex(v) = target {
                    assert_eq!(d, field.distance(v));
                }
                let (e, _) = exact.at(region.point(mesh, target));
                let scale = e.abs().max(lowest).max(1e-9);
                assert!(d.is_finite(), "{name}, {sources:?}: {target} unreached");
                assert!(
                    d >= e - 1e-9 * scale,
                    "{name}, {sources:?}: {target}: {d} < exact {e}"
                );
                // Margins relative to the exact distance, away from the sources.
                let far = e > 0.05 + lowest;
                if far {
                    worst_at = worst_at.max((d - e) / e);
                    sum_at += (d - e) / e;
                    far_points += 1;
                }
                let path = match query.path(target) {
                    Ok(path) => path,
                    Err(err) => panic!("{name}, {sources:?}: path from {target}: {err}"),
                };
                let length = check_path(query, target, &path);
                let start = sources[path.source as usize].start;
                assert!(
                    start + length >= e - 1e-9 * scale,
                    "{name}, {sources:?}: path from {target} {} < exact {e}",
                    start + length
                );
                if far {
                    worst_path = worst_path.max((start + length - e) / e);
                    sum_path += (start + length - e) / e;
                    worst_traced = worst_traced.max((start + path.traced_length - e) / e);
                }
            }
            let labels = query.vertex_labels();
            for (v, &l) in labels.iter().enumerate() {
                assert!(
                    (l as usize) < sources.len(),
                    "{name}, {sources:?}: vertex {v} label {l}"
                );
            }
        }
    }
    let n = far_points.max(1) as f64;
    println!(
        "queries on planar wave fields (k = 2), relative to the exact distance at {far_points} \
         points 0.05 or more from the sources: distance_at mean {:e}, worst {worst_at:e} \
         above; straightened paths mean {:e}, worst {worst_path:e} above; traced paths worst \
         {worst_traced:e} above; {cycles} paths refused (parent cycles)",
        sum_at / n,
        sum_path / n
    );
    // Spot, from vertex 0 and from a face point: paths from every vertex.
    let mesh = spot();
    let reference = read_reference(std::path::Path::new(&format!("{DATA}/spot.src0.f64"))).unwrap();
    let solver = Solver::new(&mesh, Euclidean, &wave(2.0)).unwrap();
    for source in [
        SurfacePoint::Vertex(0),
        SurfacePoint::Face {
            face: 100,
            bary: [0.2, 0.3, 0.5],
        },
    ] {
        let field = solver
            .field(Sources::from(&[Source::new(source)]).until(&Stop::NONE))
            .unwrap();
        let query = &field;
        let mut worst = 0.0f64;
        for v in 0..mesh.vertex_count() as u32 {
            let target = SurfacePoint::Vertex(v);
            let path = match query.path(target) {
                Ok(path) => path,
                Err(geotracks::Error::ParentCycle { .. }) => {
                    cycles += 1;
                    continue;
                }
                Err(err) => panic!("spot, path from {v}: {err}"),
            };
            let length = check_path(query, target, &path);
            if source == SurfacePoint::Vertex(0) {
                let e = reference[v as usize];
                assert!(
                    length >= e * (1.0 - 1e-6),
                    "spot: path from {v} {length} < exact {e}"
                );
                worst = worst.max((length - e) / e.max(1e-300));
            }
        }
        assert!(query
            .vertex_labels()
            .iter()
            .all(|&l| l == 0 || l == geotracks::mesh::NONE));
        println!(
            "spot, wave k = 2, source {source}: straightened paths at most {worst:e} above \
             exact; {cycles} paths refused so far (parent cycles)"
        );
    }
}
/// The nodes whose parent chain loops (never reaches a root).
fn looping_nodes(field: &FieldData) -> Vec<u32> {
    let count = field.node_distances().len();
    (0..count as u32)
        .filter(|&start| {
            let mut node = start;
            for _ in 0..=count {
                match field.parent(node) {
                    Some((p, _)) => node = p,
                    None => return false,
                }
            }
            true
        })
        .collect()
}

/// Parents must lead to a source: paths and labels follow them. Minimal case found:
/// `needle_square(11, 100)` (a test generator), wave k = 2, source vertex 65: vertex 85
/// (at (0, 0.8484), value 0.201762821724310) has parent Steiner node 941 (edge 261, the
/// boundary edge above it, value 0.209544185764176) and 941 has parent 85; both values
/// are exact. `path(Vertex(85))` fails with `ParentCycle`, and `vertex_labels` gives
/// vertex 85 no label.
#[test]
fn no_parent_cycles() {
    let mut found = Vec::new();
    let mut meshes: Vec<(String, TriMesh)> = convex_planar_meshes();
    meshes.extend(holey_meshes());
    meshes.push(("needle square 100".to_string(), needle_square(11, 100)));
    meshes.push(("spot".to_string(), spot()));
    for (seed, (name, mesh)) in meshes.iter().enumerate() {
        for sources in single_sources(mesh, seed as u64) {
            for k in [1.0, 2.0, 3.0] {
                let field = Solver::new(mesh, Euclidean, &wave(k))
                    .unwrap()
                    .field(Sources::from(&sources).until(&Stop::NONE))
                    .unwrap();
                let looping = looping_nodes(field.data());
                if !looping.is_empty() {
                    found.push(format!(
                        "{name}, k = {k}, {sources:?}: {} nodes, e.g. {:?}",
                        looping.len(),
                        &looping[..looping.len().min(4)]
                    ));
                }
            }
        }
    }
    assert!(found.is_empty(), "parent cycles:\n{}", found.join("\n"));
}
/// `BucketQueue` keeps a count of the live entries of its far heap (`far_live`), checked
/// for overflow in debug builds (`cargo test`). `Frontier::requeue` (which the wave
/// engine calls when a window grows or a tie changes a node's wave) pushes a node with
/// its unchanged value; when the node already waits in the far heap, `push` adds a second
/// far entry without counting it (`was_far`), and `refill` then counts both down:
/// "attempt to subtract with overflow" at src/propagate/queue.rs:244 (or :289) in debug
/// builds; in release builds the count wraps and the far heap is never compacted
/// (line 314). Found on `multiscale_mesh` (about one run in ten, Euclidean or tensor);
/// minimal case: `multiscale_mesh(384 * 7919, 3)` (20 vertices), source vertex 2 with
/// start −0.7818, k = 2. (Passes in release builds, where the count wraps silently.)
#[test]
fn wave_queue_counts_do_not_overflow() {
    let mesh = multiscale_mesh(384 * 7919, 3);
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (20, 20));
    let source = Source::new(2).with_start(-0.7817997580942447);
    let field = Solver::new(&mesh, Euclidean, &wave(2.0))
        .unwrap()
        .field(Sources::from(&[source]).until(&Stop::NONE))
        .unwrap();
    assert_eq!(field.stats().method, Method::Wave);
}

/// A traced path (before straightening) is as long as the value it explains, also where
/// a value came from a bend at the end of a window (a hinge, `src/propagate/wave.rs`):
/// the trace bends there and follows the window's wave on, and where a line through a
/// window's end passes the vertex that ends it, goes on from that vertex. Around holes
/// (the shadows of their corners end windows inside edges) and on Spot, from every
/// vertex: a traced path is a real path (never below the exact distance), and it differs
/// from its value on at most 1 in 12 of the vertices (longer where a tie replaced the
/// wave that gave the value, documented; shorter where the vertex it passes has a better
/// value than the wave there). Measured: around holes none at k = 2 (a wave that starts
/// at the source vertex, passed on by a node of another edge, once went round by that
/// node: up to 63 % longer) and at most 3 of about 165 at k = 1; on Spot 4.3 % at k = 1
/// and 3.2 % at k = 2. The trace from before hinges (it bent at the parent node) made
/// 15 % of Spot's paths at k = 1 longer.
#[test]
fn traced_paths_are_as_long_as_their_values() {
    let mut cases: Vec<(String, TriMesh, Vec<f64>)> = holey_meshes()
        .into_iter()
        .map(|(name, mesh)| {
            let region = Region::flat(&mesh);
            let origin = region.point(&mesh, SurfacePoint::Vertex(0));
            let exact = region.exact(&[(origin, 0.0)]);
            let e = (0..mesh.vertex_count() as u32)
                .map(|v| exact.at(region.point(&mesh, SurfacePoint::Vertex(v))).0)
                .collect();
            (name, mesh, e)
        })
        .collect();
    let reference = read_reference(std::path::Path::new(&format!("{DATA}/spot.src0.f64"))).unwrap();
    cases.push(("spot".to_string(), spot(), reference));
    for (name, mesh, exact) in &cases {
        for k in [1.0, 2.0] {
            let solver = Solver::new(mesh, Euclidean, &wave(k)).unwrap();
            let field = solver.field(&[0]).unwrap();
            let query = &field;
            let (mut longer, mut shorter, mut worst) = (0usize, 0usize, 0.0f64);
            let count = mesh.vertex_count() as u32;
            for v in 1..count {
                let d = field.distance(v);
                let traced = query.trace(SurfacePoint::Vertex(v)).unwrap().traced_length;
                let e = exact[v as usize];
                assert!(
                    traced >= e * (1.0 - 1e-9),
                    "{name}, k = {k}: vertex {v}: traced {traced} < exact {e}"
                );
                let excess = (traced - d) / d;
                if excess > 1e-9 {
                    longer += 1;
                } else if excess < -1e-9 {
                    shorter += 1;
                }
                worst = worst.max(excess.abs());
            }
            println!(
                "{name}, k = {k}: of {count} traced paths {longer} longer and {shorter} \
                 shorter than their value (worst {worst:e} relative)"
            );
            if k == 2.0 && name != "spot" {
                assert_eq!(
                    longer + shorter,
                    0,
                    "{name}, k = 2: traced paths that differ from their value"
                );
            }
            assert!(
                (longer + shorter) * 12 <= count as usize,
                "{name}, k = {k}: {longer} + {shorter} of {count} traced paths differ from \
                 their value"
            );
        }
    }
}

/// A metric that gives every face's flattening runs the wavefront engine, which needs
/// the cached steps along edges, even when it does not also say it is a norm (the
/// flattening makes it one): the same distances as the Euclidean metric's.
#[test]
fn a_flattening_without_is_face_norm_still_runs_the_wave_exactly() {
    struct FlatOnly;
    impl geotracks::Metric for FlatOnly {
        fn cost(&self, _: u32, a: &geotracks::FacePoint, b: &geotracks::FacePoint) -> f64 {
            a.distance(b)
        }
        fn face_gram(&self, _: u32) -> Option<[f64; 3]> {
            Some([1.0, 0.0, 1.0])
        }
    }
    let mesh = common::sphere(2, 0.2, 9);
    let options = geotracks::Options::DEFAULT;
    let flat = geotracks::Solver::new(&mesh, &FlatOnly, &options)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let euclid = geotracks::Solver::new(&mesh, &geotracks::Euclidean, &options)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    assert_eq!(flat.stats().method, geotracks::Method::Wave);
    assert_eq!(flat.node_distances(), euclid.node_distances());
}
