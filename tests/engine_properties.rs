//! The engines' contracts under random input, thousands of cases per run: the classes of
//! mesh that break geometry code (multi-scale coordinates, needles, holes, books, lifted
//! and flat patches, several components) × random metrics (per-face SPD tensors up to
//! 1e6 anisotropy) × random sources (vertices, points on edges and in faces, with
//! start values), each against an oracle:
//!
//! - the wavefront engine never above the Steiner graph at the same k where faces do not
//!   glue (per-face tensors: waves restart at every edge, and its points include the
//!   graph's);
//! - several sources give the minimum of their single-source fields (the Steiner graph
//!   and the tracks engine to rounding; the wavefront engine within its stated bounds);
//! - the wavefront engine exact on flat meshes from one vertex (multi-scale Delaunay
//!   patches, needles);
//! - every valid mesh accepted by every engine (the metric's floor check allows for the
//!   rounding of an edge's own length).
//!
//! Case counts are set so that the file runs about 10⁴ cases in well under a minute
//! (release build); `PROPTEST_CASES=N` runs N cases of each property instead.

mod common;

use common::{
    holey_grid, multiscale_mesh, needle_square, random_book, random_face_point, random_mesh,
    sphere, Rng,
};
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{Method, Metric, Options, Solver, Source, Stop, SurfacePoint, Tensor};
use proptest::prelude::*;

/// `n` cases for a property (about 10⁴ in all across this file; `PROPTEST_CASES` in
/// the environment sets another count for every property), new random ones each run.
fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A random mesh of one of the classes: 0 lifted jittered grids with holes, fins,
/// degenerate faces and a second component; 1 non-manifold books; 2 spheres; 3
/// multi-scale meshes (lengths from 1e-9 to 1e9, slivers, nearly collinear faces); 4
/// planar grids with holes; 5 needle squares (aspect ratios up to 10 n).
fn random_class(class: u8, seed: u64) -> TriMesh {
    let n = (seed % 5) as usize;
    match class {
        0 => random_mesh(seed, 2 + n).unwrap(),
        1 => random_book(seed, 3 + n % 4, 1 + n % 4),
        2 => sphere(n % 2, 0.4, seed),
        3 => multiscale_mesh(seed, 2 + n),
        4 => holey_grid(seed, 4 + n, 0.2, 2),
        _ => needle_square(seed, 4 + 5 * n),
    }
}

/// One to three random sources: vertices, points on edges or inside faces, with start
/// values 0, negative or positive.
fn random_sources(mesh: &TriMesh, rng: &mut Rng) -> Vec<Source> {
    (0..1 + rng.below(3))
        .map(|_| Source::new(random_point(mesh, rng)).with_start(random_start(rng)))
        .collect()
}

fn random_point(mesh: &TriMesh, rng: &mut Rng) -> SurfacePoint {
    match rng.below(3) {
        0 => SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32),
        1 => SurfacePoint::Edge {
            edge: rng.below(mesh.edge_count()) as u32,
            t: 0.1 + 0.8 * rng.next(),
        },
        _ => random_face_point(mesh, rng),
    }
}

fn random_start(rng: &mut Rng) -> f64 {
    match rng.below(3) {
        0 => 0.0,
        1 => -rng.next(),
        _ => rng.next(),
    }
}

/// Random SPD tensors, one per face: the cost factor along a random direction is
/// `10^(u · log10 anisotropy)` for a uniform `u`, across it 0.1 to 1.1; `None` where a
/// face has no plane to restrict to.
fn random_tensor(mesh: &TriMesh, rng: &mut Rng, anisotropy: f64) -> Option<Tensor> {
    let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
        .map(|_| {
            (
                10f64.powf(rng.next() * anisotropy.log10()),
                0.1 + rng.next(),
                [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5],
            )
        })
        .collect();
    Tensor::from_principal(mesh, &principal).ok()
}

fn solve<M: Metric>(
    mesh: &TriMesh,
    metric: M,
    sources: &[Source],
    options: Options,
) -> geotracks::Field<M> {
    Solver::new(mesh, metric, &options)
        .unwrap()
        .field(Sources::from(sources).until(&Stop::NONE))
        .unwrap()
}

/// The worst `(a − b) / scale` over the vertices, where both are finite; asserts that
/// both reach the same vertices. `scale` is the value, or the largest |start| of the
/// sources where that is larger (a value near 0 compares absolutely).
fn worst_excess(a: &[f64], b: &[f64], sources: &[Source]) -> f64 {
    let lowest = sources.iter().map(|s| s.start.abs()).fold(0.0, f64::max);
    let mut worst = f64::NEG_INFINITY;
    for (v, (&x, &y)) in a.iter().zip(b).enumerate() {
        assert_eq!(x.is_finite(), y.is_finite(), "vertex {v}: {x} against {y}");
        if y.is_finite() {
            worst = worst.max((x - y) / y.abs().max(lowest).max(f64::MIN_POSITIVE));
        }
    }
    worst
}

/// The wavefront engine's worst excess over the Steiner graph at the vertices, at the
/// same k, under random per-face tensors of up to `10^decades` anisotropy (`None` when
/// the mesh has a face the tensor cannot be restricted to).
fn wave_over_graph_under_tensors(seed: u64, class: u8, k: u32, decades: f64) -> Option<f64> {
    let mesh = random_class(class, seed);
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let sources = random_sources(&mesh, &mut rng);
    let tensor = random_tensor(&mesh, &mut rng, 10f64.powf(decades))?;
    let options = Options::DEFAULT.with_k(k as f64);
    let wave = solve(&mesh, &tensor, &sources, options.with_method(Method::Wave));
    let graph = solve(&mesh, &tensor, &sources, options.with_method(Method::Graph));
    assert_eq!(wave.stats().method, Method::Wave);
    Some(worst_excess(
        wave.vertex_distances(),
        graph.vertex_distances(),
        &sources,
    ))
}

proptest! {
    #![proptest_config(cases(2000))]

    /// Per-face tensors up to 1e6 anisotropy (no two faces glue, so waves restart at
    /// every edge), the same k, every class of mesh, random sources: the wavefront
    /// engine is never above the Steiner graph at a vertex (to rounding).
    #[test]
    fn wave_never_above_the_graph_where_faces_do_not_glue(
        seed in any::<u64>(), class in 0u8..6, k in 1u32..5, decades in 0.0f64..6.0,
    ) {
        if let Some(excess) = wave_over_graph_under_tensors(seed, class, k, decades) {
            prop_assert!(excess <= 1e-9, "wave above the graph by {:e}", excess);
        }
    }
}

/// A case the property found when the wavefront engine spaced its points by the
/// metric's lengths alone: most edges then carried one point where the graph had
/// several, and a vertex ended 8.6 % above the graph.
#[test]
fn wave_keeps_the_graphs_points_where_faces_do_not_glue() {
    let excess = wave_over_graph_under_tensors(2856946878332503535, 0, 1, 5.709916924400502);
    assert!(excess.unwrap() <= 1e-9, "{excess:?}");
}

/// A triangle with one far vertex and two close ones (a needle whose short edge is
/// measured next to large coordinates), moved to a random place: lengths from
/// `10^-far_decades` … `10^far_decades` apart in one face.
fn needle_triangle(seed: u64, far_decades: f64, near_decades: f64) -> Option<TriMesh> {
    let mut rng = Rng(seed | 1);
    let far = 10f64.powf(far_decades * rng.next());
    let near = 10f64.powf(-near_decades * rng.next());
    let angle = std::f64::consts::TAU * rng.next();
    let offset = [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5].map(|c| c * far);
    let corners = [
        [far * angle.cos(), far * angle.sin(), 0.0],
        [near * rng.next(), near * rng.next(), 0.0],
        [near * rng.next(), near * rng.next(), near * rng.next()],
    ];
    let positions = corners
        .iter()
        .map(|c| [c[0] + offset[0], c[1] + offset[1], c[2] + offset[2]])
        .collect();
    // `None` where the face is too thin to be a face (refused as degenerate).
    TriMesh::new(positions, vec![[0, 1, 2]]).ok()
}

proptest! {
    #![proptest_config(cases(2000))]

    /// A valid mesh is accepted by every engine, whatever its scales: the metric's
    /// floor check allows for the rounding of a short edge's length next to large
    /// coordinates, and every vertex gets a finite value at least the straight line's.
    #[test]
    fn needles_next_to_large_coordinates_are_accepted(
        seed in any::<u64>(), far in 0.0f64..9.0, near in 0.0f64..9.0, method in 0usize..4,
    ) {
        let Some(mesh) = needle_triangle(seed, far, near) else {
            return Ok(());
        };
        let method = [Method::Wave, Method::Tracks, Method::Graph, Method::Dijkstra][method];
        let source = [Source::new(SurfacePoint::Vertex((seed % 3) as u32))];
        let field = Solver::new(&mesh, geotracks::Euclidean, &Options::DEFAULT.with_method(method))
            .map_err(|e| TestCaseError::fail(format!("refused: {e}")))?
            .field(Sources::from(&source).until(&Stop::NONE))
            .map_err(|e| TestCaseError::fail(format!("refused: {e}")))?;
        // Lengths are computed to rounding of the coordinates, not of the length.
        let scale = mesh.positions().iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
        let from = mesh.position((seed % 3) as u32);
        for (v, &d) in field.vertex_distances().iter().enumerate() {
            let straight = from.distance(mesh.position(v as u32));
            prop_assert!(
                d.is_finite() && d >= straight * (1.0 - 1e-9) - 1e-13 * scale,
                "vertex {v}: {d} < {straight}"
            );
        }
    }
}

/// The triangle a fuzzer found refused by every engine ("edge 2 costs 9.999987e-1 per
/// unit"): a vertex at (6.07e5, 1.66e5, 0) and two vertices 8.6e-5 apart near the
/// origin.
#[test]
fn a_needle_next_to_a_far_vertex_is_accepted() {
    let mesh = TriMesh::new(
        vec![
            [606555.1002761879, 165514.35398437196, 0.0],
            [9.054179724671717e-05, 4.297565703312921e-05, 0.0],
            [1.3985733911443288e-05, 3.565712964532375e-06, 0.0],
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    for method in [
        Method::Wave,
        Method::Tracks,
        Method::Graph,
        Method::Dijkstra,
    ] {
        let field = solve(
            &mesh,
            geotracks::Euclidean,
            &[Source::new(SurfacePoint::Vertex(0))],
            Options::DEFAULT.with_method(method),
        );
        let straight = mesh.position(0).distance(mesh.position(2));
        assert!(
            (field.distance(2) - straight).abs() <= 1e-9 * straight,
            "{method:?}"
        );
    }
}

/// Twice the signed area of `a, b, c` (positive counter-clockwise).
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// A flat convex patch with coordinates over ten orders of magnitude: `n` points, each
/// `10^u` times a point of the unit square (`u` uniform in [-7, -4] or [0, 3]), triangulated by a
/// sweep (each point in x order joined to the hull edges it sees: fans of needles),
/// each face starting at a random corner.
/// `None` when rounding makes the triangulation doubtful (a face not clearly
/// counter-clockwise, or faces whose areas do not add up to the hull's).
fn multiscale_flat_patch(seed: u64, n: usize) -> Option<TriMesh> {
    let mut rng = Rng(seed | 1);
    let mut points: Vec<[f64; 2]> = (0..n)
        .map(|_| {
            // Half in a cluster 1e-7 to 1e-6 wide at the origin, half from 1 to 1e3 out:
            // short edges measured in faces with far corners.
            let decade = if rng.next() < 0.5 { -7.0 } else { 0.0 };
            let scale = 10f64.powf(decade + 3.0 * rng.next());
            [scale * rng.next(), scale * rng.next()]
        })
        .collect();
    points.sort_by(|a, b| a.partial_cmp(b).unwrap());
    points.dedup();
    let o = orient(points[0], points[1], points[2]);
    if o == 0.0 {
        return None;
    }
    // The hull, counter-clockwise.
    let mut hull: Vec<usize> = if o > 0.0 {
        vec![0, 1, 2]
    } else {
        vec![0, 2, 1]
    };
    let mut triangles = vec![[hull[0] as u32, hull[1] as u32, hull[2] as u32]];
    for p in 3..points.len() {
        let m = hull.len();
        let sees = |i: usize| orient(points[hull[i]], points[hull[(i + 1) % m]], points[p]) < 0.0;
        // The hull edges p sees form one chain: find its first edge.
        let first = (0..m).find(|&i| sees(i) && !sees((i + m - 1) % m))?;
        let mut last = first;
        while sees((last + 1) % m) && (last + 1) % m != first {
            last = (last + 1) % m;
        }
        let mut i = first;
        loop {
            let (a, b) = (hull[i], hull[(i + 1) % m]);
            // Any corner first: a face's frame measures its first side exactly and the
            // others through the far corner.
            let mut t = [b as u32, a as u32, p as u32];
            t.rotate_left(rng.below(3));
            triangles.push(t);
            if i == last {
                break;
            }
            i = (i + 1) % m;
        }
        // Replace the seen chain's inner vertices by p: the hull from the chain's end
        // round to its start, then p.
        let mut next = Vec::with_capacity(m + 1);
        let mut j = (last + 1) % m;
        loop {
            next.push(hull[j]);
            if j == first {
                break;
            }
            j = (j + 1) % m;
        }
        next.push(p);
        hull = next;
    }
    let area = |t: [usize; 3]| orient(points[t[0]], points[t[1]], points[t[2]]);
    let total: f64 = triangles.iter().map(|t| area(t.map(|v| v as usize))).sum();
    let hull_area: f64 = (1..hull.len() - 1)
        .map(|i| area([hull[0], hull[i], hull[i + 1]]))
        .sum();
    let clear = triangles.iter().all(|t| {
        let [a, b, c] = t.map(|v| points[v as usize]);
        let longest = [(a, b), (b, c), (c, a)]
            .iter()
            .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(0.0, f64::max);
        orient(a, b, c) > 1e-13 * longest * longest
    });
    if !clear || (total - hull_area).abs() > 1e-9 * hull_area {
        return None;
    }
    let positions = points.iter().map(|p| [p[0], p[1], 0.0]).collect();
    let mesh = TriMesh::new(positions, triangles).ok()?;
    mesh.dropped_faces().is_empty().then_some(mesh)
}

/// How far from exact (relative, beside rounding of the coordinates) the wavefront
/// engine may be on a flat patch whose edges span ten orders of magnitude. Copies of
/// the one source that came in by different faces count as one wave to the rounding
/// of the mesh's frames (a face with a far corner measures its short edges to rounding
/// of that corner), and two of its windows join where they meet as seen from the
/// source: measured over 4·10⁵ patches (`MEASURE=1 PROPTEST_CASES=400000 cargo test
/// --release --test engine_properties wave_is_exact_on_multiscale -- --nocapture`, the
/// largest figure printed), no vertex beyond rounding of the coordinates.
const EXACT_MULTISCALE: f64 = 1e-9;

proptest! {
    #![proptest_config(cases(2500))]

    /// A flat convex patch with coordinates from 1e-7 to 1e3, one vertex source: the
    /// wavefront engine is exact (the straight line, to 1e-9 of it and to rounding of
    /// the coordinates, see `EXACT_MULTISCALE`) at every vertex, at any k. Set
    /// `MEASURE=1` to print every vertex's relative deviation instead of checking it.
    #[test]
    fn wave_is_exact_on_multiscale_flat_patches(
        seed in any::<u64>(), n in 4usize..40, k in 1u32..5, source in any::<u32>(),
    ) {
        let Some(mesh) = multiscale_flat_patch(seed, n) else {
            return Ok(());
        };
        let source = source % mesh.vertex_count() as u32;
        let field = solve(
            &mesh,
            geotracks::Euclidean,
            &[Source::new(SurfacePoint::Vertex(source))],
            Options::DEFAULT.with_k(k as f64).with_method(Method::Wave),
        );
        let scale = mesh.positions().iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
        let from = mesh.position(source);
        for (v, &d) in field.vertex_distances().iter().enumerate() {
            let straight = from.distance(mesh.position(v as u32));
            let slack = EXACT_MULTISCALE * straight + 1e-12 * scale;
            if std::env::var("MEASURE").is_ok() {
                let off = ((d - straight).abs() - 1e-12 * scale).max(0.0) / straight.max(f64::MIN_POSITIVE);
                eprintln!("flat patch: {off:e} (seed {seed}, n {n}, k {k}, vertex {v})");
                continue;
            }
            prop_assert!((d - straight).abs() <= slack, "vertex {v}: {d}, straight line {straight}");
        }
    }
}

/// The flat convex patch a fuzzer found (30 vertices, 5 unused, coordinates from 1e-7
/// to 1e3): from vertex 19 the wavefront engine gave vertex 9 3.6 % above the straight
/// line. A short edge measured in a face with a far corner was taken for a refraction
/// (its lengths in the two faces differed by more than 1e-9 of it, by rounding), so
/// waves could not cross it.
#[test]
fn wave_crosses_short_edges_next_to_far_corners() {
    let mesh = geotracks::mesh::io::read_mesh(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/multiscale_flat_patch.obj"
    ))
    .unwrap();
    for k in [1.0, 2.0, 4.0] {
        for source in [0, 5, 12, 19, 25] {
            let field = solve(
                &mesh,
                geotracks::Euclidean,
                &[Source::new(SurfacePoint::Vertex(source))],
                Options::DEFAULT.with_k(k).with_method(Method::Wave),
            );
            let from = mesh.position(source);
            for v in 0..mesh.vertex_count() as u32 {
                let (d, straight) = (field.distance(v), from.distance(mesh.position(v)));
                // Vertices no face uses are not reached.
                if d.is_finite() {
                    assert!(
                        (d - straight).abs() <= 1e-9 * straight + 1e-12 * 1e3,
                        "k {k}, source {source}, vertex {v}: {d} against {straight}"
                    );
                }
            }
        }
    }
}

/// The worst `(d(S) − min over s of d({s})) / scale` at the vertices for `method`, and
/// the worst the other way round (`d(S)` below the minimum), over random meshes of the
/// classes, random sources (two or three) and k, Euclidean or a per-face tensor.
fn several_against_single(
    seed: u64,
    class: u8,
    k: u32,
    tensor: bool,
    method: Method,
) -> (f64, f64) {
    let mesh = random_class(class, seed);
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let sources: Vec<Source> = (0..2 + rng.below(2))
        .map(|_| Source::new(random_point(&mesh, &mut rng)).with_start(random_start(&mut rng)))
        .collect();
    let options = Options::DEFAULT.with_k(k as f64).with_method(method);
    let run = |sources: &[Source]| -> Vec<f64> {
        match random_tensor(&mesh, &mut Rng(seed | 1), 1e3).filter(|_| tensor) {
            Some(t) => solve(&mesh, &t, sources, options)
                .vertex_distances()
                .to_vec(),
            None => solve(&mesh, geotracks::Euclidean, sources, options)
                .vertex_distances()
                .to_vec(),
        }
    };
    let all = run(&sources);
    let mut least = vec![f64::INFINITY; mesh.vertex_count()];
    for s in &sources {
        for (l, d) in least.iter_mut().zip(run(std::slice::from_ref(s))) {
            *l = l.min(d);
        }
    }
    (
        worst_excess(&all, &least, &sources),
        worst_excess(&least, &all, &sources),
    )
}

proptest! {
    #![proptest_config(cases(1500))]

    /// Several sources give the minimum of their single-source fields: exactly (to
    /// rounding) on the Steiner graph and the tracks engine, which find the graph's
    /// shortest paths.
    #[test]
    fn several_sources_are_the_minimum_of_single_ones_on_the_graph(
        seed in any::<u64>(), class in 0u8..6, k in 1u32..5, tensor in any::<bool>(),
        tracks in any::<bool>(),
    ) {
        let method = if tracks { Method::Tracks } else { Method::Graph };
        let (above, below) = several_against_single(seed, class, k, tensor, method);
        prop_assert!(above <= 1e-9 && below <= 1e-9, "above {:e}, below {:e}", above, below);
    }

    /// The same for the wavefront engine, within its stated bounds: it keeps one wave
    /// per point, so where the waves of two sources meet a point keeps the one that
    /// gave it the lower value, and the other's lines beyond it are lost (the field
    /// is then above the least single-source field); and a single-source run loses
    /// waves of its own that several sources can make up for (below it). Set
    /// `MEASURE=1` to print every case's figures instead of checking them.
    #[test]
    fn several_sources_are_near_the_minimum_of_single_ones_on_the_wave_engine(
        seed in any::<u64>(), class in 0u8..6, k in 1u32..5, tensor in any::<bool>(),
    ) {
        let (above, below) = several_against_single(seed, class, k, tensor, Method::Wave);
        if std::env::var("MEASURE").is_ok() {
            eprintln!("several sources: above {above:e} below {below:e} (seed {seed}, class {class}, k {k}, tensor {tensor})");
            return Ok(());
        }
        prop_assert!(
            above <= SEVERAL_SOURCES_WAVE_ABOVE && below <= SEVERAL_SOURCES_WAVE_BELOW,
            "above {:e}, below {:e}", above, below
        );
    }
}

/// How far above the least of its single-source fields the wavefront engine's field
/// from several sources may lie at a vertex (relative). Measured over 10⁵ random cases
/// (`MEASURE=1 PROPTEST_CASES=100000`): above it by more than 10 % in 0.14 % of cases;
/// at most 60 % at k = 1 (needle squares), 22 % at k = 2, 50 % at k = 3, 40 % at
/// k = 4. The tail is long: another run of 2·10⁴ met 185 % (a multi-scale mesh at
/// k = 1), and a fuzzer reported 12× on a flat needle patch at k = 1. The bound only
/// catches a runaway; the exact engine is what removes the error.
const SEVERAL_SOURCES_WAVE_ABOVE: f64 = 20.0;
/// How far below it (measured over 10⁵ cases: 10 % at most, at k = 1).
const SEVERAL_SOURCES_WAVE_BELOW: f64 = 0.5;

/// Flat convex patches the property above found, where the wavefront engine was not
/// exact. `multiscale_far_corner_patch`: a cluster edge 7.6e-6 long in a face with a
/// corner 90 away is measured there to rounding of 90, so its direction turns by 1e-9
/// from that face's frame to the next; the source, 2.5 away, came in by two ways
/// 3.5e-9 apart and was taken for two waves whose windows were not joined (vertex 8
/// 1.3e-6 above the straight line), and the exact engine refused the patch (its faces
/// did not glue to 1e-9 of the edge). `multiscale_fan_patch`: the same, the copies
/// meeting only deep inside the cluster, at edges whose own faces are well shaped
/// (6.8e-7 above). `multiscale_collinear_patch`: the source and an edge 15 long lie on
/// one line to 1e-12 of it; the two windows of one wave that meet on the line through
/// the edge's near end were 8e-6 of another edge apart there (crossed at 7e-7 rad), and
/// not joined (2e-7 above). Both engines are now exact from every vertex.
#[test]
fn waves_from_far_corners_are_one_wave() {
    for name in ["far_corner", "fan", "collinear"] {
        let path = format!(
            "{}/tests/data/multiscale_{name}_patch.obj",
            env!("CARGO_MANIFEST_DIR")
        );
        exact_from_every_vertex(&geotracks::mesh::io::read_mesh(path).unwrap());
    }
}

/// Asserts that the wavefront engine (k = 1, 2, 3, 4) and the exact engine give every
/// vertex of the flat `mesh` its straight-line distance from every vertex.
fn exact_from_every_vertex(mesh: &TriMesh) {
    let scale = mesh
        .positions()
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    let runs = [1.0, 2.0, 3.0, 4.0]
        .map(|k| Options::DEFAULT.with_k(k).with_method(Method::Wave))
        .into_iter()
        .chain([Options::DEFAULT.with_method(Method::Exact)]);
    for options in runs {
        for source in 0..mesh.vertex_count() as u32 {
            let field = solve(
                mesh,
                geotracks::Euclidean,
                &[Source::new(SurfacePoint::Vertex(source))],
                options,
            );
            let from = mesh.position(source);
            for v in 0..mesh.vertex_count() as u32 {
                let (d, straight) = (field.distance(v), from.distance(mesh.position(v)));
                assert!(
                    (d - straight).abs() <= 1e-9 * straight + 1e-12 * scale,
                    "{:?} ({:?}), source {source}, vertex {v}: {d} against {straight}",
                    options.method,
                    options.steiner
                );
            }
        }
    }
}
