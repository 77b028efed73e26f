//! Mesh generators shared by the integration tests.
#![allow(dead_code)]

pub mod plane;

use geotracks::mesh::TriMesh;
use geotracks::metrics::FaceGeometry;
use geotracks::Sources;
use geotracks::{FacePoint, Method, Metric, Options, Solver, Tensor};
use glam::DVec3;

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
    let triangles = split_quads(n, n, |i, j| (j * (n + 1) + i) as u32);
    TriMesh::new(positions, triangles).unwrap()
}

/// The triangles of a `cols × rows` grid of quads whose corner `(i, j)` is vertex
/// `id(i, j)` (`i` in `0..=cols`, `j` in `0..=rows`), each quad cut along the same
/// diagonal, from `(i, j)` to `(i + 1, j + 1)`.
pub fn split_quads(cols: usize, rows: usize, id: impl Fn(usize, usize) -> u32) -> Vec<[u32; 3]> {
    let mut triangles = Vec::with_capacity(2 * cols * rows);
    for j in 0..rows {
        for i in 0..cols {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    triangles
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

/// Plates of a few large faces (also measured by `eval --plates`).
#[path = "../../examples/plate_meshes/mod.rs"]
pub mod plate_meshes;
/// Rough relief for terrain tests.
pub mod relief;
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

/// A uniformly random point inside a random face of `mesh`.
pub fn random_face_point(
    mesh: &geotracks::mesh::TriMesh,
    rng: &mut Rng,
) -> geotracks::SurfacePoint {
    let (a, b) = (rng.next(), rng.next());
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    geotracks::SurfacePoint::Face {
        face: rng.below(mesh.face_count()) as u32,
        bary: [1.0 - a - b, a, b],
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
    // Never all holes (a 2 × 2 grid is, one time in 25 000): the first cell stays.
    if triangles.is_empty() {
        triangles.push([id(0, 0), id(1, 0), id(1, 1)]);
        triangles.push([id(0, 0), id(1, 1), id(0, 1)]);
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

// ---------------------------------------------------------------------------------
// Planar and developable meshes with known exact distances (tests/wave.rs).

/// Asserts that every triangle of a planar mesh (given by 2D coordinates) is
/// counter-clockwise with positive area: the triangulation is an embedding, so that
/// distances on it are distances in the plane region it covers.
pub fn assert_embedded(coords: &[[f64; 2]], triangles: &[[u32; 3]]) {
    for t in triangles {
        let [a, b, c] = t.map(|v| coords[v as usize]);
        let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert!(
            cross > 0.0,
            "triangle {t:?} is not counter-clockwise: {cross}"
        );
    }
}

fn planar(coords: Vec<[f64; 2]>, triangles: Vec<[u32; 3]>) -> TriMesh {
    assert_embedded(&coords, &triangles);
    TriMesh::new(
        coords.iter().map(|p| [p[0], p[1], 0.0]).collect(),
        triangles,
    )
    .unwrap()
}

/// `0 = x₀ < x₁ < … < xₙ = 1`: each inner point `i / n` moved by up to `jitter / 2`
/// of a spacing (`jitter` < 1), so intervals are `(1 − jitter) / n` long at least.
pub fn jittered_partition(rng: &mut Rng, n: usize, jitter: f64) -> Vec<f64> {
    assert!((0.0..1.0).contains(&jitter));
    (0..=n)
        .map(|i| match i {
            0 => 0.0,
            i if i == n => 1.0,
            i => (i as f64 + jitter * (rng.next() - 0.5)) / n as f64,
        })
        .collect()
}

/// Sorted uniform random points of (0, 1) with 0 and 1 added: `n` intervals of random
/// lengths, some far shorter than others (with many points, slivers of 1e-9 and less).
pub fn random_partition(rng: &mut Rng, n: usize) -> Vec<f64> {
    let mut cuts: Vec<f64> = (0..n - 1).map(|_| rng.next()).collect();
    cuts.push(0.0);
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts
}

/// A flat grid (z = 0) with columns at `xs` and rows at `ys` (increasing), cells in
/// `hole` (`[i0, j0, i1, j1]`, cells `i0..i1 × j0..j1`) left out, each other cell split
/// along its rising diagonal where `rising(i, j)`, else along the other one. Vertex
/// `(i, j)` has id `j * xs.len() + i` when there is no hole (unreferenced vertices are
/// removed).
pub fn xy_grid(
    xs: &[f64],
    ys: &[f64],
    hole: Option<[usize; 4]>,
    rising: impl Fn(usize, usize) -> bool,
) -> TriMesh {
    let mut coords = Vec::new();
    for &y in ys {
        for &x in xs {
            coords.push([x, y]);
        }
    }
    let id = |i: usize, j: usize| (j * xs.len() + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..ys.len() - 1 {
        for i in 0..xs.len() - 1 {
            if let Some([i0, j0, i1, j1]) = hole {
                if (i0..i1).contains(&i) && (j0..j1).contains(&j) {
                    continue;
                }
            }
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rising(i, j) {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    let (coords, triangles) = compact(coords, triangles);
    planar(coords, triangles)
}

/// The unit square cut into needles: `n − 1` jittered points on each of its left and
/// right sides (plus the corners), joined by a random zigzag. Triangles span the
/// square's width (1) and are about `1 / n` high (down to `0.1 / n`): aspect ratios of
/// `n` to `10 n`.
pub fn needle_square(seed: u64, n: usize) -> TriMesh {
    let mut rng = Rng(seed | 1);
    let left = jittered_partition(&mut rng, n, 0.9);
    let right = jittered_partition(&mut rng, n, 0.9);
    let mut coords: Vec<[f64; 2]> = left.iter().map(|&y| [0.0, y]).collect();
    let r0 = coords.len() as u32;
    coords.extend(right.iter().map(|&y| [1.0, y]));
    let (mut i, mut j) = (0usize, 0usize);
    let mut triangles = Vec::new();
    while i + 1 < left.len() || j + 1 < right.len() {
        // Advance on the left or the right chain: any choice is a valid triangulation of
        // the strip between two parallel lines.
        let take_left = j + 1 == right.len() || (i + 1 < left.len() && rng.next() < 0.5);
        let (l, r) = (i as u32, r0 + j as u32);
        if take_left {
            triangles.push([l, r, l + 1]);
            i += 1;
        } else {
            triangles.push([l, r, r + 1]);
            j += 1;
        }
    }
    planar(coords, triangles)
}

/// The unit square as a fan of needles around the interior vertex `centre` (id 0):
/// `n` points on each side of the square, each boundary segment a triangle with the
/// centre. Returns the mesh (aspect ratios about `n`).
pub fn square_fan(n: usize, centre: [f64; 2]) -> TriMesh {
    let mut coords = vec![centre];
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    for s in 0..4 {
        let (a, b): ([f64; 2], [f64; 2]) = (corners[s], corners[(s + 1) % 4]);
        for i in 0..n {
            let t = i as f64 / n as f64;
            coords.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    let m = 4 * n as u32;
    let triangles = (0..m).map(|i| [0, 1 + i, 1 + (i + 1) % m]).collect();
    planar(coords, triangles)
}

/// The unit square as a fan of needles from its corner (0, 0) (vertex 0) to `n` points
/// on each of the two far sides: triangles √2 long and down to 1/n wide.
pub fn corner_fan(n: usize) -> TriMesh {
    let mut coords = vec![[0.0, 0.0]];
    for i in 0..=n {
        coords.push([1.0, i as f64 / n as f64]);
    }
    for i in (0..n).rev() {
        coords.push([i as f64 / n as f64, 1.0]);
    }
    let m = coords.len() as u32;
    let triangles = (1..m - 1).map(|i| [0, i, i + 1]).collect();
    planar(coords, triangles)
}

/// A jittered `n × n` grid on the unit square (z = 0), each cell split along a random
/// diagonal, with up to `holes` rectangular holes (whole cells removed, at least one
/// cell from the boundary and from each other). Interior vertices move by up to
/// `jitter` (< 0.25) cells in x and y (hole outlines then are non-convex); boundary
/// vertices move along the boundary only and the corners stay, so the outer boundary is
/// the square. Unreferenced vertices are removed.
pub fn holey_grid(seed: u64, n: usize, jitter: f64, holes: usize) -> TriMesh {
    assert!(jitter < 0.25, "a larger jitter may fold triangles");
    let mut rng = Rng(seed | 1);
    let mut removed = vec![false; n * n];
    let mut placed: Vec<[usize; 4]> = Vec::new();
    for _ in 0..holes * 20 {
        if placed.len() == holes || n < 3 {
            break;
        }
        let (w, h) = (1 + rng.below((n / 3).max(1)), 1 + rng.below((n / 3).max(1)));
        if w + 2 > n || h + 2 > n {
            continue;
        }
        let (i0, j0) = (1 + rng.below(n - 1 - w), 1 + rng.below(n - 1 - h));
        let hole = [i0, j0, i0 + w, j0 + h];
        // At least one cell of mesh between two holes.
        let apart =
            |o: &[usize; 4]| hole[0] > o[2] || o[0] > hole[2] || hole[1] > o[3] || o[1] > hole[3];
        if placed.iter().all(apart) {
            placed.push(hole);
            for j in j0..j0 + h {
                for i in i0..i0 + w {
                    removed[j * n + i] = true;
                }
            }
        }
    }
    let mut coords = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (bi, bj) = (i == 0 || i == n, j == 0 || j == n);
            let mut dx = jitter * (2.0 * rng.next() - 1.0);
            let mut dy = jitter * (2.0 * rng.next() - 1.0);
            if bi {
                dx = 0.0;
            }
            if bj {
                dy = 0.0;
            }
            if bi && bj {
                (dx, dy) = (0.0, 0.0);
            }
            coords.push([(i as f64 + dx) / n as f64, (j as f64 + dy) / n as f64]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if removed[j * n + i] {
                continue;
            }
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rng.next() < 0.5 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    let (coords, triangles) = compact(coords, triangles);
    planar(coords, triangles)
}

/// Drops the vertices no triangle uses, renumbering the rest in order.
fn compact<P: Copy>(coords: Vec<P>, triangles: Vec<[u32; 3]>) -> (Vec<P>, Vec<[u32; 3]>) {
    let mut new_id = vec![u32::MAX; coords.len()];
    for t in &triangles {
        for &v in t {
            new_id[v as usize] = 0;
        }
    }
    let mut kept = Vec::new();
    for (v, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len() as u32;
            kept.push(coords[v]);
        }
    }
    let triangles = triangles
        .iter()
        .map(|t| t.map(|v| new_id[v as usize]))
        .collect();
    (kept, triangles)
}

/// A section of a cylinder of radius `radius` over the angles `[0, angle]` and heights
/// `[0, height]`: `cols` columns and `rows` rows at jittered angles and heights, each
/// quad (a planar rectangle) split along a random diagonal. Returns the mesh and its
/// exact unrolling (x: the arc length along the polygon's chords, y: the height), a
/// rectangle.
pub fn cylinder_strip(
    seed: u64,
    cols: usize,
    rows: usize,
    radius: f64,
    angle: f64,
    height: f64,
) -> (TriMesh, Vec<[f64; 2]>) {
    let mut rng = Rng(seed | 1);
    let thetas: Vec<f64> = jittered_partition(&mut rng, cols, 0.8)
        .iter()
        .map(|t| t * angle)
        .collect();
    let zs: Vec<f64> = jittered_partition(&mut rng, rows, 0.8)
        .iter()
        .map(|z| z * height)
        .collect();
    let mut unrolled_x = vec![0.0];
    for w in thetas.windows(2) {
        let chord = 2.0 * radius * ((w[1] - w[0]) / 2.0).sin();
        unrolled_x.push(unrolled_x.last().unwrap() + chord);
    }
    strip(&mut rng, thetas.len(), zs.len(), |i, j| {
        (
            [radius * thetas[i].cos(), radius * thetas[i].sin(), zs[j]],
            [unrolled_x[i], zs[j]],
        )
    })
}

/// A section of a cone (apex at the origin, axis z, half-angle `half_angle`) between
/// the distances `r0` and `r1` from the apex, over the azimuths `[0, azimuth]`: `cols`
/// generators and `rows` rings at jittered azimuths and distances, each quad
/// (planar: it lies in the plane of two generators) split along a random diagonal.
/// Returns the mesh and its exact unrolling: generator `i` at the angle that adds up the
/// angles between consecutive generators. The unrolled strip is an annulus sector whose
/// inner boundary is reflex: lines may leave it there.
pub fn cone_strip(
    seed: u64,
    cols: usize,
    rows: usize,
    half_angle: f64,
    azimuth: f64,
    r0: f64,
    r1: f64,
) -> (TriMesh, Vec<[f64; 2]>) {
    let mut rng = Rng(seed | 1);
    let phis: Vec<f64> = jittered_partition(&mut rng, cols, 0.8)
        .iter()
        .map(|t| t * azimuth)
        .collect();
    let rs: Vec<f64> = jittered_partition(&mut rng, rows, 0.8)
        .iter()
        .map(|r| r0 + r * (r1 - r0))
        .collect();
    let generator = |phi: f64| {
        [
            half_angle.sin() * phi.cos(),
            half_angle.sin() * phi.sin(),
            half_angle.cos(),
        ]
    };
    let mut unrolled_angle = vec![0.0];
    for w in phis.windows(2) {
        let (a, b) = (generator(w[0]), generator(w[1]));
        // The angle between two unit vectors, accurately for small angles.
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let chord = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        unrolled_angle.push(unrolled_angle.last().unwrap() + 2.0 * (chord / 2.0).asin());
    }
    assert!(*unrolled_angle.last().unwrap() < std::f64::consts::PI * 1.9);
    strip(&mut rng, phis.len(), rs.len(), |i, j| {
        let g = generator(phis[i]);
        let r = rs[j];
        let a = unrolled_angle[i];
        ([r * g[0], r * g[1], r * g[2]], [r * a.cos(), r * a.sin()])
    })
}

/// A `cols × rows` vertex strip whose vertex `(i, j)` is at `place(i, j)` = (3D, 2D
/// unrolled); quads split along random diagonals, triangles counter-clockwise in 2D.
fn strip(
    rng: &mut Rng,
    cols: usize,
    rows: usize,
    place: impl Fn(usize, usize) -> ([f64; 3], [f64; 2]),
) -> (TriMesh, Vec<[f64; 2]>) {
    let mut positions = Vec::new();
    let mut unrolled = Vec::new();
    for j in 0..rows {
        for i in 0..cols {
            let (p, u) = place(i, j);
            positions.push(p);
            unrolled.push(u);
        }
    }
    let id = |i: usize, j: usize| (j * cols + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..rows - 1 {
        for i in 0..cols - 1 {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rng.next() < 0.5 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    // Orient counter-clockwise in the unrolled plane.
    for t in &mut triangles {
        let [a, b, c] = t.map(|v| unrolled[v as usize]);
        if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) < 0.0 {
            t.swap(1, 2);
        }
    }
    assert_embedded(&unrolled, &triangles);
    (TriMesh::new(positions, triangles).unwrap(), unrolled)
}

/// A closed torus around the z axis: `around` × `across` quads (radii `big` and
/// `small`), each split in two.
pub fn torus(around: usize, across: usize, big: f64, small: f64) -> TriMesh {
    let mut positions = Vec::new();
    for i in 0..around {
        let u = std::f64::consts::TAU * i as f64 / around as f64;
        for j in 0..across {
            let v = std::f64::consts::TAU * j as f64 / across as f64;
            let r = big + small * v.cos();
            positions.push([r * u.cos(), r * u.sin(), small * v.sin()]);
        }
    }
    // Quad (i, j) spans i..i+1 around and j..j+1 across, wrapping both ways.
    let id = |i: usize, j: usize| ((i % around) * across + j % across) as u32;
    let triangles = split_quads(around, across, id);
    TriMesh::new(positions, triangles).unwrap()
}

/// The largest relative difference between the tracks engine and the complete Steiner
/// graph (the oracle) over every node, at mean k `k`, from `sources`; both engines must
/// reach the same nodes.
pub fn tracks_vs_graph<M: Metric>(mesh: &TriMesh, metric: &M, sources: &[u32], k: f64) -> f64 {
    let options = TRACKS.with_k(k);
    let graph = Solver::new(mesh, metric, &options.with_method(Method::Graph))
        .and_then(|solver| solver.field(sources))
        .unwrap();
    let tracks = Solver::new(mesh, metric, &options)
        .and_then(|solver| solver.field(sources))
        .unwrap();
    assert_eq!(tracks.stats().method, Method::Tracks);
    let mut max: f64 = 0.0;
    for (g, t) in graph.node_distances().iter().zip(tracks.node_distances()) {
        assert!(!g.is_nan() && !t.is_nan());
        assert_eq!(g.is_finite(), t.is_finite(), "reached by one engine only");
        if g.is_finite() {
            max = max.max((g - t).abs() / g.max(f64::MIN_POSITIVE));
        }
    }
    max
}

/// A Randers metric: per face, a symmetric norm `sqrt(vᵀ G v)` (a tensor) plus a drift
/// term `ω · v`, with `|ω|` under `G⁻¹` below 1 so that every direction costs > 0. The
/// textbook asymmetric norm: convex, positively homogeneous, dearer along ω than
/// against it.
pub struct Randers {
    tensor: Tensor,
    /// Per face, ω in the face's (u, v) frame.
    wind: Vec<[f64; 2]>,
    /// The largest `|ω|` under `G⁻¹`.
    strength: f64,
}

impl Randers {
    /// `wind(f)` (world) projected on each face, scaled so that its `G⁻¹` norm is
    /// `strength` times what it was capped to (at most `strength` < 1).
    pub fn new(mesh: &TriMesh, tensor: Tensor, strength: f64, wind: impl Fn(u32) -> DVec3) -> Self {
        let wind = (0..mesh.face_count() as u32)
            .map(|f| {
                let [u, v] = mesh.face_axes(f);
                let w = wind(f);
                let omega = [w.dot(DVec3::from(u)), w.dot(DVec3::from(v))];
                let [g11, g12, g22] = tensor.face_gram(f).expect("a tensor is face-flat");
                // ωᵀ G⁻¹ ω, G⁻¹ = [g22, −g12; −g12, g11] / det.
                let det = g11 * g22 - g12 * g12;
                let dual = ((g22 * omega[0] * omega[0] - 2.0 * g12 * omega[0] * omega[1]
                    + g11 * omega[1] * omega[1])
                    / det)
                    .sqrt();
                let scale = if dual > 1.0 {
                    strength / dual
                } else {
                    strength
                };
                [omega[0] * scale, omega[1] * scale]
            })
            .collect();
        Randers {
            tensor,
            wind,
            strength,
        }
    }
}

impl Metric for Randers {
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let w = self.wind[face as usize];
        let drift = w[0] * (b.uv[0] - a.uv[0]) + w[1] * (b.uv[1] - a.uv[1]);
        // Never below 0 by rounding, for a zero-length segment.
        (self.tensor.cost(face, a, b) + drift).max(0.0)
    }
    fn is_symmetric(&self) -> bool {
        false
    }
    fn is_face_norm(&self) -> bool {
        true
    }
    /// `sqrt(vᵀ G v) + ω · v ≥ (1 − |ω|) sqrt(vᵀ G v)` (`|ω|` under `G⁻¹`, Cauchy–Schwarz).
    fn min_cost_per_length(&self) -> f64 {
        (1.0 - self.strength) * self.tensor.min_cost_per_length()
    }
    fn name(&self) -> &str {
        "randers"
    }
}

pub fn random_randers(mesh: &TriMesh, seed: u64, strength: f64) -> Randers {
    let mut rng = Rng(seed | 1);
    let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
        .map(|_| {
            let r = |rng: &mut Rng| rng.next() - 0.5;
            (
                0.2 + rng.next(),
                0.2 + rng.next(),
                [r(&mut rng), r(&mut rng), r(&mut rng)],
            )
        })
        .collect();
    let tensor = Tensor::from_principal(mesh, &principal).unwrap();
    let winds: Vec<DVec3> = (0..mesh.face_count())
        .map(|_| DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 4.0)
        .collect();
    Randers::new(mesh, tensor, strength, |f| winds[f as usize])
}

/// The complete Steiner graph's value at `target` from `source` (a full run): the
/// oracle for paths between two points.
pub fn oracle<M: Metric>(
    mesh: &TriMesh,
    metric: &M,
    k: f64,
    source: geotracks::SurfacePoint,
    target: geotracks::SurfacePoint,
) -> f64 {
    let solver = geotracks::Solver::new(mesh, metric, &GRAPH.with_k(k)).unwrap();
    let field = solver
        .field(Sources::from(&[geotracks::Source::new(source)]).until(&geotracks::Stop::NONE))
        .unwrap();
    field.distance_at(target).unwrap()
}

/// A random point of `mesh`: a vertex, an edge point or a face point.
pub fn random_surface_point(mesh: &TriMesh, rng: &mut Rng) -> geotracks::SurfacePoint {
    match rng.below(4) {
        0 => geotracks::SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32),
        1 => geotracks::SurfacePoint::Edge {
            edge: rng.below(mesh.edge_count()) as u32,
            t: rng.next(),
        },
        _ => random_face_point(mesh, rng),
    }
}

/// A random metric of each kind: Euclidean (0), a density (1), a tensor (2), a
/// directed one (3: [`random_randers`]).
pub fn random_metric(mesh: &TriMesh, kind: u8, seed: u64) -> Box<dyn Metric> {
    let mut rng = Rng(seed | 1);
    match kind {
        0 => Box::new(geotracks::Euclidean),
        1 => {
            let rho: Vec<f64> = (0..mesh.vertex_count())
                .map(|_| 0.2 + 3.0 * rng.next())
                .collect();
            Box::new(geotracks::Density::new(mesh, rho).unwrap())
        }
        2 => {
            let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
                .map(|_| {
                    let mut r = || rng.next() - 0.5;
                    (0.1 + r().abs() * 4.0, 0.1 + r().abs(), [r(), r(), r()])
                })
                .collect();
            Box::new(Tensor::from_principal(mesh, &principal).unwrap())
        }
        _ => Box::new(random_randers(mesh, seed, 0.7)),
    }
}

/// A mesh of shape `shape` (0: a jittered sphere, 1: a non-manifold book of three
/// pages, else a random mesh with holes and fins), `None` when the random mesh's
/// generator gives up: the meshes the path oracles run on.
pub fn oracle_mesh(shape: u8, seed: u64) -> Option<TriMesh> {
    match shape {
        0 => Some(sphere(2, 0.2, seed)),
        1 => Some(random_book(seed, 3, 4)),
        _ => random_mesh(seed, 7).ok(),
    }
}

/// Two triangles far apart: two islands, no path between them.
pub fn two_islands() -> TriMesh {
    TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [5.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [5.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    )
    .unwrap()
}

/// Points along the skeleton's edges, at most `step` apart: the curves themselves, for
/// checks that must not depend on how many points a straight run keeps.
pub fn along_edges(skeleton: &geotracks::skeleton::Skeleton, step: f64) -> Vec<DVec3> {
    let mut along = Vec::new();
    for &[a, b] in &skeleton.edges {
        let p = DVec3::from(skeleton.points[a as usize].position);
        let q = DVec3::from(skeleton.points[b as usize].position);
        let n = ((p.distance(q) / step).ceil() as usize).max(1);
        along.extend((0..=n).map(|k| p.lerp(q, k as f64 / n as f64)));
    }
    along
}
