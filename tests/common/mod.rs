//! Mesh generators shared by the integration tests.
#![allow(dead_code)]

use geotracks::mesh::TriMesh;
use geotracks::{Method, Options};

/// The naive Steiner graph, the oracle.
pub const GRAPH: Options = Options::DEFAULT.with_method(Method::Graph).with_k(5.0);
/// The track-pruned engine at its usual k (the library's default is the wavefront
/// engine at k = 2).
pub const TRACKS: Options = Options::DEFAULT.with_method(Method::Tracks).with_k(5.0);
/// Dijkstra on mesh edges.
pub const DIJKSTRA: Options = Options::DEFAULT.with_method(Method::Dijkstra);

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

#[path = "../../examples/shared_data/mod.rs"]
mod shared_data;
#[allow(unused_imports)] // not every test binary uses both
pub use shared_data::{read_reference, relative_error};

/// A small deterministic generator, so a failing case is reproducible from its seed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next() * n as f64) as usize).min(n - 1)
    }
}

/// A jittered grid with holes, extra "fin" faces on existing edges (non-manifold),
/// degenerate faces (repeated vertex, collinear), an unreferenced vertex, and sometimes
/// a second disconnected component.
pub fn random_mesh(seed: u64, n: usize) -> Result<TriMesh, geotracks::mesh::MeshError> {
    let mut rng = Rng(seed | 1);
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push([
                i as f64 + 0.35 * (rng.next() - 0.5),
                j as f64 + 0.35 * (rng.next() - 0.5),
                0.8 * rng.next(),
            ]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if rng.next() < 0.08 {
                continue; // a hole
            }
            if rng.next() < 0.5 {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            } else {
                triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    // Fins: new faces on existing edges, making them non-manifold.
    for _ in 0..rng.below(4) + 1 {
        // Two fins on one edge: it then has at least three faces.
        let t = triangles[rng.below(triangles.len())];
        let a = positions[t[0] as usize];
        for _ in 0..2 {
            let apex = positions.len() as u32;
            positions.push([
                a[0] + rng.next(),
                a[1] + rng.next(),
                a[2] + 1.0 + rng.next(),
            ]);
            triangles.push([t[0], t[1], apex]);
        }
    }
    // Degenerate faces: a repeated vertex, and three collinear vertices.
    triangles.push([id(0, 0), id(0, 0), id(1, 1)]);
    let c = positions.len() as u32;
    positions.push([-5.0, 0.0, 0.0]);
    positions.push([-4.0, 0.0, 0.0]);
    positions.push([-3.0, 0.0, 0.0]);
    triangles.push([c, c + 1, c + 2]);
    // An unreferenced vertex.
    positions.push([9.0, 9.0, 9.0]);
    // Sometimes a second component.
    if rng.next() < 0.5 {
        let b = positions.len() as u32;
        positions.extend([[20.0, 0.0, 0.0], [21.0, 0.0, 0.0], [20.0, 1.0, 0.0]]);
        triangles.push([b, b + 1, b + 2]);
    }
    TriMesh::new(positions, triangles)
}

/// An icosahedron subdivided `levels` times, projected on the unit sphere, with each
/// vertex's radius jittered by up to `jitter` (relative).
pub fn sphere(levels: usize, jitter: f64, seed: u64) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut midpoint = std::collections::HashMap::new();
        let mut next = Vec::new();
        for t in &triangles {
            let mut mid = [0u32; 3];
            for i in 0..3 {
                let (a, b) = (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]));
                mid[i] = *midpoint.entry((a, b)).or_insert_with(|| {
                    let (pa, pb) = (positions[a as usize], positions[b as usize]);
                    positions.push([
                        (pa[0] + pb[0]) / 2.0,
                        (pa[1] + pb[1]) / 2.0,
                        (pa[2] + pb[2]) / 2.0,
                    ]);
                    positions.len() as u32 - 1
                });
            }
            next.push([t[0], mid[0], mid[2]]);
            next.push([t[1], mid[1], mid[0]]);
            next.push([t[2], mid[2], mid[1]]);
            next.push(mid);
        }
        triangles = next;
    }
    let mut rng = Rng(seed | 1);
    for p in &mut positions {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let s = (1.0 + jitter * (rng.next() - 0.5)) / r;
        *p = [p[0] * s, p[1] * s, p[2] * s];
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A random non-manifold fan: `pages` triangulated strips of random widths and
/// directions hinged on one spine (the z axis), plus single triangles on the spine's
/// end vertices (an hourglass-like pinch).
pub fn random_book(seed: u64, pages: usize, n: usize) -> TriMesh {
    let mut rng = Rng(seed | 1);
    let mut positions = Vec::new();
    for j in 0..=n {
        positions.push([0.0, 0.0, j as f64 / n as f64 + 0.02 * rng.next()]);
    }
    let mut triangles = Vec::new();
    for _ in 0..pages {
        let angle = std::f64::consts::TAU * rng.next();
        let width = 0.3 + rng.next();
        let cols = 1 + rng.below(3);
        let first = positions.len() as u32;
        for j in 0..=n {
            for i in 1..=cols {
                let r = width * i as f64 / cols as f64;
                positions.push([
                    r * angle.cos() + 0.05 * rng.next(),
                    r * angle.sin() + 0.05 * rng.next(),
                    j as f64 / n as f64 + 0.05 * (rng.next() - 0.5),
                ]);
            }
        }
        let id = |i: usize, j: usize| -> u32 {
            if i == 0 {
                j as u32
            } else {
                first + (j * cols + i - 1) as u32
            }
        };
        for j in 0..n {
            for i in 0..cols {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    // A pinch: a triangle touching the spine's top vertex only.
    let top = n as u32;
    let b = positions.len() as u32;
    positions.push([0.5, 0.5, 1.5]);
    positions.push([-0.5, 0.5, 1.6]);
    triangles.push([top, b, b + 1]);
    TriMesh::new(positions, triangles).unwrap()
}

/// A flat `w × h` rectangle on `[0, w] × [0, h]` (z = 0) of `nx × ny` cells, each split
/// along alternating diagonals so that no direction is favoured. Vertex `(i, j)` has id
/// `j * (nx + 1) + i`.
pub fn rectangle(nx: usize, ny: usize, w: f64, h: f64) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push([w * i as f64 / nx as f64, h * j as f64 / ny as f64, 0.0]);
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A mesh whose edge lengths span many orders of magnitude: a grid whose column widths
/// and row heights are drawn from `10^[-9, 0]` (sliver columns and rows beside wide
/// ones), some cells cut by nearly collinear faces (apex 1e-12 off the diagonal), fins
/// on a few edges, plus small grids at scales from 1e-9 to 1e9 as further components.
pub fn multiscale_mesh(seed: u64, n: usize) -> TriMesh {
    let mut rng = Rng(seed | 1);
    let widths = |rng: &mut Rng| -> Vec<f64> {
        let mut at = 0.0;
        let mut out = vec![0.0];
        for _ in 0..n {
            at += 10f64.powf(-9.0 * rng.next() * (rng.next() < 0.5) as u8 as f64);
            out.push(at);
        }
        out
    };
    let xs = widths(&mut rng);
    let ys = widths(&mut rng);
    let mut positions = Vec::new();
    for y in &ys {
        for x in &xs {
            positions.push([*x, *y, 0.3 * rng.next() * xs[n].min(ys[n])]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rng.next() < 0.15 {
                // A nearly collinear face along the diagonal, and the cell's two halves
                // through its apex.
                let (pa, pc) = (positions[a as usize], positions[c as usize]);
                let apex = positions.len() as u32;
                positions.push([
                    0.5 * (pa[0] + pc[0]) + 1e-12,
                    0.5 * (pa[1] + pc[1]),
                    0.5 * (pa[2] + pc[2]),
                ]);
                triangles.extend([[a, b, c], [a, apex, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, c], [a, c, d]]);
            }
        }
    }
    for _ in 0..rng.below(3) {
        let t = triangles[rng.below(triangles.len())];
        let p = positions[t[0] as usize];
        let apex = positions.len() as u32;
        positions.push([p[0], p[1], p[2] + 10f64.powf(-9.0 * rng.next())]);
        triangles.push([t[0], t[1], apex]);
    }
    for _ in 0..rng.below(3) {
        let scale = 10f64.powf(18.0 * rng.next() - 9.0);
        let first = positions.len() as u32;
        for j in 0..3 {
            for i in 0..3 {
                positions.push([
                    scale * (i as f64 + 0.3 * rng.next() + 5.0),
                    scale * (j as f64 + 0.3 * rng.next()),
                    scale * rng.next(),
                ]);
            }
        }
        for j in 0..2u32 {
            for i in 0..2u32 {
                let v = |i: u32, j: u32| first + j * 3 + i;
                triangles.extend([
                    [v(i, j), v(i + 1, j), v(i + 1, j + 1)],
                    [v(i, j), v(i + 1, j + 1), v(i, j + 1)],
                ]);
            }
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}
