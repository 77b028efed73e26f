//! Tests of the Delaunay tetrahedralization: exact checks by brute force on small sets
//! (random, and degenerate ones: grids, cube corners, cospherical points, many points on
//! one plane), local checks that scale on larger sets, the errors, the predicates' sign
//! conventions, and timings (ignored; run them in release).

use super::*;
use glam::DVec3;
use proptest::prelude::*;
use std::collections::{HashMap, HashSet};

/// A point as the predicates take it.
fn c(p: [f64; 3]) -> Coord3D<f64> {
    coord(p)
}

/// `orient3d` of four points by index.
fn orient_of(points: &[[f64; 3]], v: [u32; 4]) -> f64 {
    let p = |i: usize| c(points[v[i] as usize]);
    robust::orient3d(p(0), p(1), p(2), p(3))
}

/// The facet opposite slot `i`, sorted.
fn facet(v: [u32; 4], i: usize) -> [u32; 3] {
    let mut f = [0; 3];
    let mut k = 0;
    for (j, &x) in v.iter().enumerate() {
        if j != i {
            f[k] = x;
            k += 1;
        }
    }
    f.sort_unstable();
    f
}

/// The checks that cost O(tetrahedra): tetrahedra positively oriented with distinct,
/// representative vertices; neighbours symmetric across the same facet; every distinct
/// point a vertex; each interior facet locally Delaunay (the neighbour's far vertex not
/// strictly inside the circumsphere, which for a triangulation of the hull makes it
/// Delaunay); the hull surface closed and the complex a ball (Euler characteristic 1);
/// the tetrahedra's volume equal to the volume the hull facets enclose. Returns the
/// total volume.
fn check_local(points: &[[f64; 3]], d: &Delaunay) -> f64 {
    let n = points.len();
    assert_eq!(d.representative.len(), n);
    assert_eq!(d.tets.len(), d.neighbours.len());
    let mut used = vec![false; n];
    let (mut volume, mut hull_volume) = (0.0, 0.0);
    let (mut edges, mut facets) = (HashSet::new(), HashSet::new());
    let mut hull_edges: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, &v) in d.tets.iter().enumerate() {
        for (k, &x) in v.iter().enumerate() {
            assert_eq!(d.representative[x as usize], x, "tet {t} uses a duplicate");
            assert!(!v[..k].contains(&x), "tet {t} repeats a vertex: {v:?}");
            used[x as usize] = true;
            for &y in &v[..k] {
                edges.insert((x.min(y), x.max(y)));
            }
        }
        let o = orient_of(points, v);
        assert!(o > 0.0, "tet {t} {v:?} is not positively oriented: {o}");
        volume += o / 6.0;
        for i in 0..4 {
            facets.insert(facet(v, i));
            let u = d.neighbours[t][i];
            if u == OUTSIDE {
                // Its cone to the origin's volume, signed (the hull facets enclose their
                // sum); outward facets are clockwise in the right-handed sense.
                let f = outward_facet(v, i).map(|x| DVec3::from_array(points[x as usize]));
                hull_volume -= f[0].dot(f[1].cross(f[2])) / 6.0;
                let f = facet(v, i);
                for (a, b) in [(f[0], f[1]), (f[0], f[2]), (f[1], f[2])] {
                    *hull_edges.entry((a, b)).or_default() += 1;
                }
                continue;
            }
            let w = d.tets[u as usize];
            let j = d.neighbours[u as usize]
                .iter()
                .position(|&x| x as usize == t);
            let j = j.unwrap_or_else(|| panic!("tet {u} does not point back to {t}"));
            assert_eq!(
                facet(v, i),
                facet(w, j),
                "tets {t} and {u}: not the same facet"
            );
            assert!(!v.contains(&w[j]), "tets {t} and {u} share 4 vertices");
            let p = |x: u32| c(points[x as usize]);
            let s = robust::insphere(p(v[0]), p(v[1]), p(v[2]), p(v[3]), p(w[j]));
            assert!(
                s <= 0.0,
                "tet {u}'s vertex {} is inside tet {t}'s sphere",
                w[j]
            );
        }
    }
    for (i, &vertex) in used.iter().enumerate() {
        let is_rep = d.representative[i] as usize == i;
        assert_eq!(
            vertex, is_rep,
            "point {i}: vertex {vertex}, distinct {is_rep}"
        );
    }
    assert!(
        hull_edges.values().all(|&k| k == 2),
        "the hull surface is not closed"
    );
    let vertices = used.iter().filter(|&&u| u).count();
    let euler = vertices as i64 - edges.len() as i64 + facets.len() as i64 - d.tets.len() as i64;
    assert_eq!(euler, 1, "the tetrahedra do not form a ball");
    let scale = volume.abs().max(1e-300);
    assert!(
        (volume - hull_volume).abs() <= 1e-9 * scale,
        "{volume} vs {hull_volume}"
    );
    volume
}

/// Every check: [`check_local`], the representatives against a brute-force search, no
/// point strictly beyond a hull facet, and no point strictly inside any circumsphere.
fn check(points: &[[f64; 3]], d: &Delaunay) -> f64 {
    let volume = check_local(points, d);
    for (i, p) in points.iter().enumerate() {
        let first = points.iter().position(|q| q == p).unwrap_or(i);
        assert_eq!(d.representative[i] as usize, first, "representative of {i}");
    }
    for (t, &v) in d.tets.iter().enumerate() {
        let pv = v.map(|x| c(points[x as usize]));
        for (q, &point) in points.iter().enumerate() {
            let s = robust::insphere(pv[0], pv[1], pv[2], pv[3], c(point));
            assert!(
                s <= 0.0,
                "point {q} is strictly inside tet {t}'s sphere {v:?}"
            );
            for i in (0..4).filter(|&i| d.neighbours[t][i] == OUTSIDE) {
                let mut w = v;
                w[i] = q as u32;
                assert!(
                    orient_of(points, w) >= 0.0,
                    "point {q} is beyond a hull facet"
                );
            }
        }
    }
    volume
}

/// Tetrahedralizes and runs every check; returns the volume.
fn checked(points: &[[f64; 3]]) -> f64 {
    let d = tetrahedralize(points).unwrap_or_else(|e| panic!("{e}"));
    check(points, &d)
}

/// The points of an `n × n × n` grid over the unit cube.
fn grid(n: usize) -> Vec<[f64; 3]> {
    let s = 1.0 / (n - 1) as f64;
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                points.push([i as f64 * s, j as f64 * s, k as f64 * s]);
            }
        }
    }
    points
}

/// `n` points uniformly at random in the unit cube, reproducibly.
fn random_cube(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut state = seed;
    let mut unit = move || (splitmix64(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
    (0..n).map(|_| [unit(), unit(), unit()]).collect()
}

/// `n` points on the unit sphere (a Fibonacci spiral): cospherical up to rounding.
fn sphere(n: usize) -> Vec<[f64; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            [r * a.cos(), r * a.sin(), z]
        })
        .collect()
}

#[test]
fn predicate_sign_conventions() {
    // Shewchuk's orient3d is positive for this tetrahedron, the mirror image of the
    // right-handed (0, x, y, z): the convention the tetrahedra follow.
    let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert!(robust::orient3d(c(o), c(y), c(x), c(z)) > 0.0);
    assert!(robust::orient3d(c(o), c(x), c(y), c(z)) < 0.0);
    assert_eq!(robust::orient3d(c(o), c(x), c(y), c([3.0, 5.0, 0.0])), 0.0);
    // insphere is positive inside the sphere of a positively oriented tetrahedron.
    let inside = c([0.25, 0.25, 0.25]);
    let far = c([2.0, 2.0, 2.0]);
    assert!(robust::insphere(c(o), c(y), c(x), c(z), inside) > 0.0);
    assert!(robust::insphere(c(o), c(y), c(x), c(z), far) < 0.0);
    assert!(robust::insphere(c(o), c(x), c(y), c(z), inside) < 0.0);
    assert_eq!(
        robust::insphere(c(o), c(y), c(x), c(z), c([1.0, 1.0, 0.0])),
        0.0
    );
    // The tetrahedralization of those four points is that one tetrahedron, positive.
    let d = tetrahedralize(&[o, x, y, z]).unwrap();
    assert_eq!(d.tets.len(), 1);
    assert!(orient_of(&[o, x, y, z], d.tets[0]) > 0.0);
    assert_eq!(d.neighbours, vec![[OUTSIDE; 4]]);
}

#[test]
fn filtered_insphere_agrees_with_robust() {
    // Nearly cospherical points (where the double-double stage decides) and random ones.
    let round = sphere(1000);
    let random = random_cube(1000, 5);
    let mut state = 9u64;
    let (mut settled, mut unsettled_in_double) = (0, 0);
    for points in [&round, &random] {
        for _ in 0..20_000 {
            let pick = |s: &mut u64| points[(splitmix64(s) % 1000) as usize];
            let [a, b, c, d, e] = [0; 5].map(|_| pick(&mut state));
            let (a, b) = if orient_of(&[a, b, c, d], [0, 1, 2, 3]) < 0.0 {
                (b, a)
            } else {
                (a, b)
            };
            let exact = robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(e));
            assert_eq!(
                sign(insphere(a, b, c, d, e)),
                sign(exact),
                "{:?}",
                [a, b, c, d, e]
            );
            // The double-double stage alone, where the first stage fails.
            let diff = [a, b, c, d].map(|p| [0, 1, 2].map(|k| p[k] - e[k]));
            let det = lifted_det(diff, |x, y| x - y);
            let permanent = lifted_det(diff.map(|p| p.map(f64::abs)), |x, y| x + y);
            if det.abs() <= 1e-15 * permanent {
                unsettled_in_double += 1;
                if let Some(det) = insphere_double_double([a, b, c, d], e, permanent) {
                    assert_eq!(sign(det), sign(exact), "{:?}", [a, b, c, d, e]);
                    settled += 1;
                }
            }
        }
    }
    assert!(unsettled_in_double > 1000, "{unsettled_in_double}");
    assert!(
        settled > unsettled_in_double * 9 / 10,
        "{settled} of {unsettled_in_double}"
    );
}

#[test]
fn circumcentre_of_known_tetrahedra() {
    let centre = circumcentre([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]);
    assert_eq!(centre, [1.0, 1.0, 1.0]);
    // Far from the origin, the answer is as good as the coordinates allow.
    let a = [1e6, -2e6, 3e6];
    let shift = |p: [f64; 3]| [p[0] + a[0], p[1] + a[1], p[2] + a[2]];
    let centre = circumcentre(a, shift([2.0, 0.0, 0.0]), shift([0.0, 2.0, 0.0]), a);
    assert!(centre.iter().all(|x| !x.is_finite()), "flat: {centre:?}");
    let centre = circumcentre(
        a,
        shift([2.0, 0.0, 0.0]),
        shift([0.0, 2.0, 0.0]),
        shift([0.0, 0.0, 2.0]),
    );
    for k in 0..3 {
        assert!((centre[k] - (a[k] + 1.0)).abs() < 1e-9, "{centre:?}");
    }
    // A sliver: four points a hair off one circle and one plane. Its centre lies on the
    // circle's axis at h = ε/δ + (ε² + δ²)/(2δ); a float numerator loses the δ/2 term
    // (h off by 5e-10, against 1e-15 here).
    let (eps, delta) = (2f64.powi(-45), 2f64.powi(-30));
    let h = eps / delta + (eps * eps + delta * delta) / (2.0 * delta);
    let centre = circumcentre(
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0 - eps, delta],
    );
    let off = DVec3::from_array(centre).distance(DVec3::new(0.0, 0.0, h));
    assert!(off < 1e-15, "{centre:?} is {off} off");
    // Random tetrahedra: the centre is as far from all four vertices.
    let points = random_cube(400, 7);
    for t in points.as_chunks::<4>().0 {
        let centre = DVec3::from_array(circumcentre(t[0], t[1], t[2], t[3]));
        let r = t.map(|p| (DVec3::from_array(p) - centre).length());
        for k in 1..4 {
            assert!((r[k] - r[0]).abs() <= 1e-9 * r[0].max(1.0), "{r:?}");
        }
    }
}

#[test]
fn errors() {
    assert_eq!(
        tetrahedralize(&[]),
        Err(DelaunayError::TooFewPoints { distinct: 0 })
    );
    let three = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    assert_eq!(
        tetrahedralize(&three),
        Err(DelaunayError::TooFewPoints { distinct: 3 })
    );
    let repeated = [three, three, [[-0.0, 0.0, -0.0]; 3]].concat();
    assert_eq!(
        tetrahedralize(&repeated),
        Err(DelaunayError::TooFewPoints { distinct: 3 })
    );
    let plane: Vec<_> = grid(5).into_iter().filter(|p| p[2] == 0.0).collect();
    assert_eq!(
        tetrahedralize(&plane),
        Err(DelaunayError::Coplanar { distinct: 25 })
    );
    // A tilted plane, exactly: integer combinations of two integer vectors.
    let tilted: Vec<_> = (0..40)
        .map(|k| {
            let (i, j) = (f64::from(k % 7), f64::from(k / 7));
            [i * 3.0 + j, i * -2.0 + j * 5.0, i + j * 7.0]
        })
        .collect();
    assert_eq!(
        tetrahedralize(&tilted),
        Err(DelaunayError::Coplanar { distinct: 40 })
    );
    let line: Vec<_> = (0..10).map(|i| [f64::from(i); 3]).collect();
    assert_eq!(
        tetrahedralize(&line),
        Err(DelaunayError::Coplanar { distinct: 10 })
    );
    let mut bad = grid(3);
    bad[5][1] = f64::NAN;
    assert_eq!(
        tetrahedralize(&bad),
        Err(DelaunayError::NonFinite { index: 5 })
    );
    bad[2][2] = f64::NEG_INFINITY;
    assert_eq!(
        tetrahedralize(&bad),
        Err(DelaunayError::NonFinite { index: 2 })
    );
    assert!(DelaunayError::NonFinite { index: 2 }
        .to_string()
        .contains("point 2"));
}

#[test]
fn cube_corners_and_grids() {
    for n in [2, 3, 4, 6] {
        let volume = checked(&grid(n));
        assert!((volume - 1.0).abs() < 1e-12, "grid {n}: volume {volume}");
    }
    let mut corners = grid(2);
    corners.push([0.5; 3]);
    assert!((checked(&corners) - 1.0).abs() < 1e-12);
    // A larger grid, with the checks that scale.
    let points = grid(13);
    let d = tetrahedralize(&points).unwrap();
    assert!((check_local(&points, &d) - 1.0).abs() < 1e-12);
}

#[test]
fn cospherical_points() {
    // Every integer point at squared distance 50 from the origin: exactly cospherical,
    // with many coplanar and cocircular subsets.
    let mut points = Vec::new();
    for x in -7i32..=7 {
        for y in -7i32..=7 {
            for z in -7i32..=7 {
                if x * x + y * y + z * z == 50 {
                    points.push([x, y, z].map(f64::from));
                }
            }
        }
    }
    assert!(points.len() > 50, "{}", points.len());
    checked(&points);
    // With the centre, strictly inside every circumsphere of the sphere's points.
    points.push([0.0; 3]);
    checked(&points);
    checked(&sphere(300));
}

#[test]
fn points_on_one_plane_and_a_few_off() {
    let mut points: Vec<_> = grid(15).into_iter().filter(|p| p[2] == 0.0).collect();
    points.extend([
        [0.3, 0.3, 0.2],
        [0.7, 0.2, -0.1],
        [0.1, 0.9, 0.25],
        [0.5, 0.5, 0.1],
    ]);
    checked(&points);
    // One apex over a grid (a pyramid), and two parallel grids (a prism).
    let mut pyramid: Vec<_> = grid(9).into_iter().filter(|p| p[2] == 0.0).collect();
    pyramid.push([0.5, 0.5, 1.0]);
    let volume = checked(&pyramid);
    assert!((volume - 1.0 / 3.0).abs() < 1e-12, "{volume}");
    let prism: Vec<_> = grid(7)
        .into_iter()
        .filter(|p| p[2] == 0.0 || p[2] == 1.0)
        .collect();
    assert!((checked(&prism) - 1.0).abs() < 1e-12);
}

#[test]
fn duplicates_are_merged() {
    let mut points = grid(3);
    points.extend(grid(3).into_iter().rev());
    points.push([-0.0, 0.0, -0.0]);
    let d = tetrahedralize(&points).unwrap();
    check(&points, &d);
    assert_eq!(d.representative[27], 26);
    assert_eq!(d.representative[points.len() - 1], 0);
}

#[test]
fn scaling_changes_nothing() {
    let points = random_cube(200, 3);
    let d = tetrahedralize(&points).unwrap();
    // Powers of two are exact, so the points and the answer are the same.
    for factor in [
        2f64.powi(700),
        2f64.powi(1000),
        2f64.powi(-700),
        2f64.powi(-1000),
    ] {
        let scaled: Vec<_> = points.iter().map(|p| p.map(|x| x * factor)).collect();
        assert_eq!(tetrahedralize(&scaled).unwrap(), d, "factor {factor}");
    }
}

#[test]
fn larger_sets_hold_locally() {
    let mut points = random_cube(6000, 11);
    points.extend(grid(2));
    let d = tetrahedralize(&points).unwrap();
    assert!((check_local(&points, &d) - 1.0).abs() < 1e-9);
    let points = sphere(6000);
    let d = tetrahedralize(&points).unwrap();
    check_local(&points, &d);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random points in the unit cube with its corners: the Delaunay tetrahedralization
    /// of a cube, volume 1.
    #[test]
    fn random_points(points in prop::collection::vec(prop::array::uniform3(0.0f64..1.0), 10..500)) {
        let mut points = points;
        points.extend(grid(2));
        let volume = checked(&points);
        prop_assert!((volume - 1.0).abs() < 1e-9, "volume {}", volume);
    }

    /// Random points with small integer coordinates: duplicates, coplanar, cocircular and
    /// cospherical subsets everywhere; or no tetrahedralization, for the right reason.
    #[test]
    fn random_lattice_points(points in prop::collection::vec(prop::array::uniform3(0i8..4), 4..300)) {
        let points: Vec<[f64; 3]> = points.iter().map(|p| p.map(f64::from)).collect();
        match tetrahedralize(&points) {
            Ok(d) => { check(&points, &d); }
            Err(DelaunayError::TooFewPoints { distinct }) => {
                let set: HashSet<_> = points.iter().map(|p| p.map(f64::to_bits)).collect();
                prop_assert_eq!(set.len(), distinct);
                prop_assert!(distinct < 4);
            }
            Err(DelaunayError::Coplanar { .. }) => {
                // Coplanar: with two points and a third off their line, all in one plane.
                let v: Vec<DVec3> = points.iter().map(|&p| DVec3::from_array(p)).collect();
                let b = v.iter().find(|&&b| b != v[0]).copied().unwrap_or(v[0]);
                let normal = v.iter().map(|&x| (b - v[0]).cross(x - v[0])).find(|n| *n != DVec3::ZERO);
                let flat = normal.is_none_or(|n| v.iter().all(|&x| n.dot(x - v[0]) == 0.0));
                prop_assert!(flat);
            }
            Err(e) => prop_assert!(false, "{}", e),
        }
    }
}

/// Timings, in release: `cargo test --release --lib medial -- --ignored --nocapture`.
#[test]
#[ignore = "a timing, to run in release"]
fn timings() {
    let cases = [
        ("100K random points in a cube", random_cube(100_000, 1)),
        ("200K points on a sphere", sphere(200_000)),
        ("1M random points in a cube", random_cube(1_000_000, 2)),
    ];
    for (name, points) in cases {
        let start = std::time::Instant::now();
        let d = tetrahedralize(&points).unwrap();
        let elapsed = start.elapsed();
        println!("{name}: {} tetrahedra in {elapsed:.3?}", d.tets.len());
        check_local(&points, &d);
    }
}
