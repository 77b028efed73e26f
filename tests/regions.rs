//! Gradients and regions (`Query::gradient_at`, `Query::regions`): exact on planes
//! (Euclidean and a constant tensor), the paper's prism (Fig. 9: a backtracking
//! direction on the top face, where vertex values are all but equal), regions that
//! tile their face and agree with `distance_at`.

use approx::{abs_diff_eq, assert_abs_diff_eq};
mod common;

use geotracks::mesh::TriMesh;
use geotracks::trace::DEFAULT_REGION_SUBDIVISIONS;
use geotracks::Sources;
use geotracks::{Error, Euclidean, Metric, Options, Solver, Source, SurfacePoint, Tensor};
use glam::DVec3;

fn bary_points(count: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let (a, b) = (next(), next());
            let (a, b) = if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            [1.0 - a - b, a, b]
        })
        .collect()
}

#[test]
fn gradients_on_a_plane_point_straight_away_from_the_source() {
    let mesh = common::grid(8, 1.0);
    let source = SurfacePoint::Face {
        face: 37,
        bary: [0.2, 0.3, 0.5],
    };
    let at = source.position(&mesh);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver
        .field(Sources::from(&[Source::new(source)]).until(&geotracks::Stop::NONE))
        .unwrap();
    let query = &field;
    let mut worst = 0.0f64;
    for f in 0..mesh.face_count() as u32 {
        for bary in bary_points(5, f as u64) {
            let point = SurfacePoint::Face { face: f, bary };
            let g = query.gradient_at(point).unwrap().expect("reached");
            let away = (point.position(&mesh) - at).normalize();
            worst = worst
                .max((g.direction - away).length())
                .max((g.vector - away).length());
        }
    }
    println!("plane, worst gradient error {worst:.1e}");
    assert!(worst < 1e-9, "{worst}");
    // At the source itself there is no gradient; at a vertex there is one.
    assert!(query.gradient_at(source).unwrap().is_none());
    let v = query.gradient_at(SurfacePoint::Vertex(0)).unwrap().unwrap();
    assert!((v.direction - (mesh.position(0) - at).normalize()).length() < 1e-9);
}

#[test]
fn under_a_constant_tensor_the_gradient_is_the_metric_one() {
    // d(x) = sqrt((x − s)ᵀ M (x − s)) on the plane z = 0: ∇d = M (x − s) / d, and the
    // geodesic runs straight, along x − s.
    let mesh = common::grid(6, 1.0);
    let world = [4.0, 1.0, 0.0, 2.0, 0.0, 1.0];
    let metric = Tensor::uniform_world(&mesh, world).unwrap();
    let solver = Solver::new(&mesh, metric, &Options::DEFAULT).unwrap();
    let field = solver.field(&[0]).unwrap();
    let query = &field;
    let m = |v: DVec3| DVec3::new(4.0 * v.x + v.y, v.x + 2.0 * v.y, v.z);
    let mut worst = 0.0f64;
    for f in 0..mesh.face_count() as u32 {
        for bary in bary_points(4, 100 + f as u64) {
            let point = SurfacePoint::Face { face: f, bary };
            let x = point.position(&mesh) - mesh.position(0);
            let d = x.dot(m(x)).sqrt();
            let g = query.gradient_at(point).unwrap().expect("reached");
            worst = worst
                .max((g.distance - d).abs())
                .max((g.vector - m(x) / d).length())
                .max((g.direction - x.normalize()).length());
        }
    }
    println!("tensor plane, worst error {worst:.1e}");
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn under_a_density_the_gradient_is_the_derivative_of_the_distance() {
    // A density that does not flatten faces: the gradient is the segment cost's
    // derivative (numerical), checked against distance_at moved along two directions.
    let mesh = common::grid(6, 1.0);
    let density: Vec<f64> = mesh
        .positions()
        .iter()
        .map(|p| 1.0 + 0.5 * p.x + 0.25 * p.y * p.y)
        .collect();
    let metric = geotracks::Density::new(&mesh, density).unwrap();
    let solver = Solver::new(&mesh, metric, &Options::DEFAULT).unwrap();
    let field = solver.field(&[0]).unwrap();
    let query = &field;
    let mut worst = 0.0f64;
    for f in (0..mesh.face_count() as u32).step_by(5) {
        for bary in bary_points(3, 300 + f as u64) {
            let point = SurfacePoint::Face { face: f, bary };
            let g = query.gradient_at(point).unwrap().expect("reached");
            let d = query.distance_at(point).unwrap();
            // Small moves along the face's two sides, inside the face.
            for (k, sign) in [(1usize, 1.0), (2, 1.0)] {
                let h = 1e-7;
                let mut moved = bary;
                let s = if moved[0] >= h { sign } else { -sign };
                moved[k] += s * h;
                moved[0] -= s * h;
                let q = SurfacePoint::Face {
                    face: f,
                    bary: moved,
                };
                let dq = query.distance_at(q).unwrap();
                let v = q.position(&mesh) - point.position(&mesh);
                // Where another candidate takes over in between, skip.
                let q_source = query.gradient_at(q).unwrap().unwrap().source;
                if q_source == g.source {
                    worst = worst.max(((dq - d) - g.vector.dot(v)).abs() / v.length());
                }
            }
        }
    }
    println!("density: worst directional-derivative error {worst:.1e}");
    assert!(worst < 1e-4, "{worst}");
}

/// A regular triangular prism (side 1, height `h`): bottom face 0, top face 1, each
/// side a rectangle of two triangles.
fn prism(h: f64) -> TriMesh {
    let s3 = 3f64.sqrt();
    let base = [[0.0, 0.0], [1.0, 0.0], [0.5, s3 / 2.0]];
    let mut positions = Vec::new();
    for z in [0.0, h] {
        for [x, y] in base {
            positions.push([x, y, z]);
        }
    }
    let mut faces = vec![[0, 2, 1], [3, 4, 5]];
    for a in 0..3u32 {
        let b = (a + 1) % 3;
        faces.push([a, b, b + 3]);
        faces.push([a, b + 3, a + 3]);
    }
    TriMesh::new(positions, faces).unwrap()
}

/// The source of the prism tests: the bottom face's centroid.
fn prism_source() -> Source {
    Source::new(SurfacePoint::Face {
        face: 0,
        bary: [1.0 / 3.0; 3],
    })
}

/// The exact geodesic from the bottom face's centroid to point `x` of the top face of
/// `prism(h)`: over each side, the straight line in the unfolding of bottom, side and
/// top (it must cross both of the side's horizontal edges inside them); the distance
/// the unit direction (world, in the top face) in which the geodesic arrives, and how
/// much longer the next route is. Paths over two sides are longer on this prism: the
/// test checks that too, by asking the engine's value to match.
fn prism_exact(mesh: &TriMesh, h: f64, x: DVec3) -> (f64, DVec3, f64) {
    let r = 1.0 / (2.0 * 3f64.sqrt()); // the centroid's distance to each side
    let mut routes = Vec::new();
    for a in 0..3u32 {
        let b = (a + 1) % 3;
        let (pa, pb) = (mesh.position(a + 3), mesh.position(b + 3));
        let e = (pb - pa).normalize();
        let centre = DVec3::new(0.5, 3f64.sqrt() / 6.0, h);
        let mut n_in = (centre - pa) - e * (centre - pa).dot(e);
        n_in = n_in.normalize();
        let (u, t) = ((x - pa).dot(e), (x - pa).dot(n_in));
        // Unfolded: the source at (0.5, −r), the point at (u, h + t).
        let (du, dv) = (u - 0.5, h + t + r);
        let d = (du * du + dv * dv).sqrt();
        // Crossings of v = 0 and v = h must lie on [0, 1].
        let cross = |v: f64| 0.5 + du * (v + r) / dv;
        if (0.0..=1.0).contains(&cross(0.0)) && (0.0..=1.0).contains(&cross(h)) {
            // On the top face, +v is into the face (n_in) and +u along e.
            routes.push((d, (e * du + n_in * dv).normalize()));
        }
    }
    routes.sort_by(|p, q| p.0.total_cmp(&q.0));
    let (d, arrive) = routes[0];
    let gap = routes.get(1).map_or(f64::INFINITY, |r| r.0 - d);
    (d, arrive, gap)
}

#[test]
fn on_the_prism_the_gradient_backtracks_along_the_true_geodesic() {
    let h = 0.6;
    let mesh = prism(h);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver
        .field(Sources::from(&[prism_source()]).until(&geotracks::Stop::NONE))
        .unwrap();
    let query = &field;
    // The top's corners are all but equally far: interpolated vertex values give no
    // direction there (the paper's point).
    let top: Vec<f64> = (3..6).map(|v| query.vertex_distances()[v]).collect();
    let spread = top.iter().fold(0.0f64, |m, &d| m.max((d - top[0]).abs()));
    assert!(spread < 1e-9, "{top:?}");
    let (mut worst_angle, mut worst_value, mut near_ridge) = (0.0f64, 0.0f64, 0);
    for bary in bary_points(400, 7) {
        let point = SurfacePoint::Face { face: 1, bary };
        let x = point.position(&mesh);
        let (d, arrive, gap) = prism_exact(&mesh, h, x);
        let g = query.gradient_at(point).unwrap().expect("reached");
        worst_value = worst_value.max((g.distance - d).abs() / d);
        if gap < 1e-9 {
            continue; // on the ridge itself, either side is right
        }
        if gap < 0.02 {
            near_ridge += 1;
        }
        let angle = g.direction.dot(arrive).clamp(-1.0, 1.0).acos();
        worst_angle = worst_angle.max(angle);
    }
    println!(
        "prism: worst value error {worst_value:.1e}, worst angle {worst_angle:.1e} rad ({near_ridge} points within 0.02 of the ridge)"
    );
    assert!(near_ridge > 10);
    assert!(worst_value < 1e-9, "{worst_value}");
    assert!(worst_angle < 1e-6, "{worst_angle}");
}

#[test]
fn isolines_on_the_prism_top_follow_the_ridge() {
    // Levels that cross the top face: every point at its exact distance (to 1e-9),
    // including where a line turns on the ridge between two sides' geodesics; lines
    // continue from the sides onto the top.
    use geotracks::trace::IsolineOptions;
    let h = 0.6;
    let mesh = prism(h);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver
        .field(Sources::from(&[prism_source()]).until(&geotracks::Stop::NONE))
        .unwrap();
    let query = &field;
    let top_corner = query.vertex_distances()[3];
    let top_centre = prism_exact(&mesh, h, DVec3::new(0.5, 3f64.sqrt() / 6.0, h)).0;
    // Between the corners' distance and the centre's: closed loops round the top (the
    // last a small one round the centre, the field's maximum, which 4 or 8
    // subdivisions miss: no grid point lies inside it).
    let levels: Vec<f64> = (1..=3)
        .map(|i| top_corner + (top_centre - top_corner) * i as f64 / 5.0)
        .collect();
    let options = IsolineOptions::DEFAULT.with_subdivisions(16);
    let lines = query.isolines(&levels, &options).unwrap();
    assert_eq!(lines.len(), levels.len());
    let (mut on_top, mut worst, mut bends) = (0, 0.0f64, 0);
    for line in &lines {
        assert!(line.closed, "level {} is not closed", line.level);
        let mut sharpest = 0.0f64;
        for w in line.points.windows(3) {
            let x = w[1].position(&mesh);
            if (x.z - h).abs() > 1e-12 {
                continue;
            }
            on_top += 1;
            let (d, _, gap) = prism_exact(&mesh, h, x);
            worst = worst.max((d - line.level).abs() / line.level);
            // Where the line turns sharply, it is on the ridge (two sides' geodesics
            // equally long), not cutting across it.
            let (a, c) = (w[0].position(&mesh), w[2].position(&mesh));
            if (x - a).length().min((c - x).length()) < 1e-4 {
                continue; // too short a segment to tell a direction
            }
            let turn = (x - a)
                .normalize()
                .dot((c - x).normalize())
                .clamp(-1.0, 1.0)
                .acos();
            sharpest = sharpest.max(turn);
            if turn > 0.2 {
                bends += 1;
                assert!(
                    gap < 1e-6 * d,
                    "a turn of {turn} rad off the ridge ({gap}) at {:?}",
                    w[1]
                );
            }
        }
        println!(
            "  level {:.4}: sharpest turn on the top {sharpest:.2} rad",
            line.level
        );
    }
    println!("prism top: {on_top} isoline points, worst {worst:.1e} off their exact level, {bends} sharp turns, all on the ridge");
    assert!(on_top > 50);
    assert!(worst < 1e-9, "{worst}");
    // Three ridge crossings per loop round the top.
    assert!(bends >= 3 * levels.len(), "{bends}");
}

#[test]
fn the_prism_top_splits_into_three_regions_along_the_ridge() {
    let h = 0.6;
    let mesh = prism(h);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver
        .field(Sources::from(&[prism_source()]).until(&geotracks::Stop::NONE))
        .unwrap();
    let query = &field;
    let regions = query.regions(1, DEFAULT_REGION_SUBDIVISIONS).unwrap();
    let area: f64 = regions.iter().map(|r| r.area).sum();
    let face_area = 3f64.sqrt() / 4.0;
    assert_abs_diff_eq!(area, face_area, epsilon = 1e-12);
    // By symmetry, the three largest regions (one per side) hold equal shares: each
    // a third of the face, up to the chords of the grid.
    let mut areas: Vec<f64> = regions.iter().map(|r| r.area).collect();
    areas.sort_by(|a, b| b.total_cmp(a));
    println!("prism top: {} regions, areas {areas:?}", regions.len());
    for a in &areas[..3] {
        assert!(
            abs_diff_eq!(*a, face_area / 3.0, epsilon = 0.02 * face_area),
            "{areas:?}"
        );
    }
    // The ridge meets at the centre: each big region's polygon comes within a grid
    // step of it.
    let centre = DVec3::new(0.5, 3f64.sqrt() / 6.0, h);
    for r in regions.iter().filter(|r| r.area > 0.2 * face_area) {
        let nearest = r
            .polygon
            .iter()
            .map(|p| (p.position(&mesh) - centre).length())
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest < 1.0 / DEFAULT_REGION_SUBDIVISIONS as f64,
            "{nearest}"
        );
    }
}

#[test]
fn regions_tile_their_face_and_give_its_values() {
    let mesh = common::sphere(3, 0.2, 5);
    for metric_is_tensor in [false, true] {
        let (areas, worst, direction) = if metric_is_tensor {
            let m = Tensor::uniform_world(&mesh, [1.0, 0.3, 0.0, 2.0, 0.1, 1.5]).unwrap();
            check_regions(&mesh, m)
        } else {
            check_regions(&mesh, Euclidean)
        };
        println!(
            "sphere, tensor {metric_is_tensor}: worst relative gaps: area {areas:.1e}, value {worst:.1e}, direction {direction:.1e}"
        );
        assert!(areas < 1e-9, "{areas}");
        assert!(worst < 1e-9, "{worst}");
        // Candidates that tie carry the same line, unfolded along different chains of
        // faces: their directions agree to their rounding.
        assert!(direction < 1e-6, "{direction}");
    }
}

#[test]
fn nodes_on_a_sources_line_cut_no_slivers() {
    // Two sources at opposite corners of a flat grid: every node on a row or column
    // through a source, and every node downstream of the source on a diagonal, ties
    // with the source along that line. Such ties go to the source: each face has one
    // region per source that reaches it, and the bisector x + y = 1 splits the 16
    // faces it crosses in two.
    let n = 8;
    let mesh = common::grid(n, 1.0);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let corners = [0, ((n + 1) * (n + 1) - 1) as u32];
    let field = solver.field(&corners).unwrap();
    let query = &field;
    let mut split = 0;
    for f in 0..mesh.face_count() as u32 {
        let regions = query.regions(f, DEFAULT_REGION_SUBDIVISIONS).unwrap();
        for r in &regions {
            let nearest = corners
                .iter()
                .map(|&c| (r.virtual_source - mesh.position(c)).length())
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 1e-12 && r.offset.abs() < 1e-12, "face {f}: {r:?}");
        }
        match regions.len() {
            1 => {}
            2 => split += 1,
            count => panic!("face {f}: {count} regions: {regions:?}"),
        }
    }
    assert_eq!(split, 2 * n);
}

/// Over every face: the regions' areas add up to the face's, their points lie on it,
/// and at each region's inner point its formula gives `distance_at` and its gradient
/// `gradient_at`'s direction. Returns the worst gaps (area and value relative).
fn check_regions<M: Metric + Clone>(mesh: &TriMesh, metric: M) -> (f64, f64, f64) {
    let solver = Solver::new(mesh, metric, &Options::DEFAULT).unwrap();
    let field = solver.field(&[0]).unwrap();
    let query = &field;
    let (mut worst_area, mut worst_value, mut worst_direction) = (0.0f64, 0.0f64, 0.0f64);
    for f in 0..mesh.face_count() as u32 {
        let regions = query.regions(f, 8).unwrap();
        let area: f64 = regions.iter().map(|r| r.area).sum();
        let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
        let face_area = 0.5 * (b - a).cross(c - a).length();
        worst_area = worst_area.max((area - face_area).abs() / face_area);
        for r in &regions {
            assert!(r.area > 0.0, "face {f}: {r:?}");
            for p in &r.polygon {
                assert!(p.faces(mesh).contains(&f), "{p:?} not on face {f}");
            }
            // The region's own formula at its inner point is the field's value there.
            let (Some(inside), Some(g)) = (r.inside, r.gradient) else {
                continue;
            };
            assert_eq!(g.source, r.source);
            let d = query.distance_at(inside).unwrap();
            worst_value = worst_value.max((d - g.distance).abs() / d);
            // gradient_at may name another candidate with the same line (a node and
            // the waves from it tie), but not another direction.
            let at = query.gradient_at(inside).unwrap().unwrap();
            worst_direction = worst_direction.max((at.direction - g.direction).length());
        }
    }
    (worst_area, worst_value, worst_direction)
}

#[test]
fn bad_faces_and_options_are_refused() {
    let mesh = common::grid(2, 1.0);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver.field(&[0]).unwrap();
    let query = &field;
    let faces = mesh.face_count() as u32;
    assert!(matches!(
        query.regions(faces, 8),
        Err(Error::InvalidPoint { .. })
    ));
    for bad in [0, 1025] {
        assert!(matches!(
            query.regions(0, bad),
            Err(Error::InvalidRegionOption {
                option: "subdivisions",
                ..
            })
        ));
    }
    assert!(matches!(
        query.gradient_at(SurfacePoint::Vertex(1000)),
        Err(Error::InvalidPoint { .. })
    ));
}

/// The same field gives the same regions, to the bit and starting at the same point,
/// every time it is asked (their boundaries used to be chained in a hash set's order,
/// which is random per set: polygons started at another point, and areas summed in
/// another order differed in their last bits).
#[test]
fn regions_are_the_same_every_time() {
    let mesh = common::sphere(3, 0.2, 5);
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    let field = solver.field(&[0, 40, 90]).unwrap();
    for face in (0..mesh.face_count() as u32).step_by(7) {
        let first = field.regions(face, 16).unwrap();
        for _ in 0..4 {
            assert_eq!(field.regions(face, 16).unwrap(), first, "face {face}");
        }
    }
}
