//! Mesh generators shared by the integration tests.
#![allow(dead_code)]

use geotracks::mesh::TriMesh;

/// A flat `n × n`-cell grid on `[0, size]²` (z = 0), each cell split along the same
/// diagonal. Vertex `(i, j)` (column i, row j) has id `j * (n + 1) + i`.
pub fn grid(n: usize, size: f64) -> TriMesh {
    grid_with(n, size, |x, y| [x, y, 0.0])
}

/// A grid whose vertex positions come from `place(x, y)`.
pub fn grid_with(n: usize, size: f64, place: impl Fn(f64, f64) -> [f64; 3]) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(place(
                size * i as f64 / n as f64,
                size * j as f64 / n as f64,
            ));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A non-manifold "book": `pages` rectangular pages of width `width` (away from the
/// spine) and height `height` (along the spine, the z axis), all sharing the spine.
/// Each page is an `n × n` grid. Returns the mesh and a function giving the vertex id of
/// `(page, i, j)` (i across, 0 on the spine; j along the spine).
pub fn book(
    pages: usize,
    width: f64,
    height: f64,
    n: usize,
) -> (TriMesh, impl Fn(usize, usize, usize) -> u32) {
    let spine = n + 1;
    let per_page = n * (n + 1); // columns 1..=n, rows 0..=n
    let id = move |page: usize, i: usize, j: usize| -> u32 {
        if i == 0 {
            j as u32
        } else {
            (spine + page * per_page + j * n + (i - 1)) as u32
        }
    };
    let mut positions = Vec::new();
    for j in 0..=n {
        positions.push([0.0, 0.0, height * j as f64 / n as f64]);
    }
    for p in 0..pages {
        let angle = std::f64::consts::TAU * p as f64 / pages as f64;
        for j in 0..=n {
            for i in 1..=n {
                let r = width * i as f64 / n as f64;
                positions.push([
                    r * angle.cos(),
                    r * angle.sin(),
                    height * j as f64 / n as f64,
                ]);
            }
        }
    }
    let mut triangles = Vec::new();
    for p in 0..pages {
        for j in 0..n {
            for i in 0..n {
                triangles.push([id(p, i, j), id(p, i + 1, j), id(p, i + 1, j + 1)]);
                triangles.push([id(p, i, j), id(p, i + 1, j + 1), id(p, i, j + 1)]);
            }
        }
    }
    (TriMesh::new(positions, triangles).unwrap(), id)
}

/// Mean and max of |d − exact| / exact over entries with exact > 0.
pub fn relative_error(d: &[f64], exact: &[f64]) -> (f64, f64) {
    let (mut sum, mut max, mut n) = (0.0, 0.0f64, 0usize);
    for (a, b) in d.iter().zip(exact) {
        if *b > 0.0 {
            let e = (a - b).abs() / b;
            sum += e;
            max = max.max(e);
            n += 1;
        }
    }
    (sum / n as f64, max)
}
