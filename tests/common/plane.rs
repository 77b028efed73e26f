//! Exact distances in a plane region, computed independently of the library (the
//! union of a mesh's triangles, flat or unrolled; shortest paths through its reflex
//! boundary vertices), and the planar test meshes and sources the engines are checked
//! on against them.

use super::{
    cone_strip, corner_fan, holey_grid, needle_square, random_face_point, rectangle, square_fan,
    Rng,
};
use geotracks::glam::DVec2;
use geotracks::mesh::TriMesh;
use geotracks::{FieldData, Source, SurfacePoint};

// ---------------------------------------------------------------------------------
// Exact distances in a plane region.

/// A plane region given as the union of a mesh's triangles in 2D coordinates (the
/// mesh's own x, y when it is flat, or an unrolling).
pub struct Region {
    /// Per mesh vertex.
    pub coords: Vec<DVec2>,
    /// Triangles, counter-clockwise, with their bounding boxes.
    pub triangles: Vec<[DVec2; 3]>,
    pub boxes: Vec<[f64; 4]>,
    /// Boundary vertices where the region's angle exceeds π: where shortest paths bend.
    pub reflex: Vec<DVec2>,
    /// The region's size (for tolerances).
    pub size: f64,
}

impl Region {
    /// A mesh lying in the plane z = 0.
    pub fn flat(mesh: &TriMesh) -> Region {
        assert!(mesh.positions().iter().all(|p| p.z == 0.0));
        Region::new(
            mesh,
            mesh.positions().iter().map(|p| p.truncate()).collect(),
        )
    }

    /// A mesh lying in any plane (e.g. a flat mesh mapped by a linear map): coordinates
    /// in an orthonormal frame of that plane.
    pub fn in_plane(mesh: &TriMesh) -> Region {
        let p = mesh.positions();
        let t = mesh.triangles()[0].map(|v| p[v as usize]);
        let u = (t[1] - t[0]).normalize();
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
        let w = n.cross(u);
        let scale = p.iter().map(|q| q.length()).fold(0.0, f64::max);
        for q in p {
            assert!((*q - p[0]).dot(n).abs() <= 1e-12 * scale, "not planar");
        }
        let coords = p
            .iter()
            .map(|q| DVec2::new((*q - p[0]).dot(u), (*q - p[0]).dot(w)))
            .collect();
        Region::new(mesh, coords)
    }

    pub fn new(mesh: &TriMesh, coords: Vec<DVec2>) -> Region {
        let mut triangles = Vec::new();
        let mut boxes = Vec::new();
        for t in mesh.triangles() {
            let [a, b, c] = t.map(|v| coords[v as usize]);
            let [a, b, c] = if (b - a).perp_dot(c - a) > 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            };
            triangles.push([a, b, c]);
            boxes.push([
                a.x.min(b.x).min(c.x),
                a.y.min(b.y).min(c.y),
                a.x.max(b.x).max(c.x),
                a.y.max(b.y).max(c.y),
            ]);
        }
        // Angle sums at boundary vertices.
        let mut angle = vec![0.0; coords.len()];
        for t in mesh.triangles() {
            for c in 0..3 {
                let (v, a, b) = (t[c], t[(c + 1) % 3], t[(c + 2) % 3]);
                let (pv, pa, pb) = (coords[v as usize], coords[a as usize], coords[b as usize]);
                angle[v as usize] += (pa - pv).angle_to(pb - pv).abs();
            }
        }
        let mut boundary = vec![false; coords.len()];
        for e in 0..mesh.edge_count() as u32 {
            if mesh.edge_faces(e).len() == 1 {
                for v in mesh.edge_vertices(e) {
                    boundary[v as usize] = true;
                }
            }
        }
        let reflex = (0..coords.len())
            .filter(|&v| boundary[v] && angle[v] > std::f64::consts::PI * (1.0 + 1e-9))
            .map(|v| coords[v])
            .collect();
        let size = boxes
            .iter()
            .fold(0.0f64, |s, b| s.max(b[2] - b[0]).max(b[3] - b[1]));
        Region {
            coords,
            triangles,
            boxes,
            reflex,
            size,
        }
    }

    /// The 2D coordinates of a surface point of the mesh.
    pub fn point(&self, mesh: &TriMesh, p: SurfacePoint) -> DVec2 {
        match p.validated(mesh).unwrap() {
            SurfacePoint::Vertex(v) => self.coords[v as usize],
            SurfacePoint::Edge { edge, t } => {
                let [a, b] = mesh.edge_vertices(edge);
                self.coords[a as usize].lerp(self.coords[b as usize], t)
            }
            SurfacePoint::Face { face, bary } => {
                let vs = mesh.face_vertices(face);
                (0..3).map(|i| bary[i] * self.coords[vs[i] as usize]).sum()
            }
        }
    }

    /// Whether the segment `a`–`b` lies in the region: the triangles cover it (to 1e-9
    /// of its length; a segment through a vertex or along an edge is covered).
    pub fn covers(&self, a: DVec2, b: DVec2) -> bool {
        if self.reflex.is_empty() {
            // No reflex vertex: the region is convex (a hole always has some).
            return true;
        }
        let d = b - a;
        if d.length() <= 1e-15 * self.size {
            return true;
        }
        let eps = 1e-12 * self.size;
        let (lo, hi) = (a.min(b), a.max(b));
        let mut spans: Vec<(f64, f64)> = Vec::new();
        for (t, bx) in self.triangles.iter().zip(&self.boxes) {
            if bx[0] > hi.x + eps || bx[2] < lo.x - eps || bx[1] > hi.y + eps || bx[3] < lo.y - eps
            {
                continue;
            }
            let (mut t0, mut t1) = (0.0f64, 1.0f64);
            for i in 0..3 {
                let (u, v) = (t[i], t[(i + 1) % 3]);
                let e = v - u;
                let len = e.length();
                // Signed distance from the edge's line, positive inside: f0 + s·f1.
                let f0 = e.perp_dot(a - u) / len;
                let f1 = e.perp_dot(d) / len;
                if f1 == 0.0 {
                    if f0 < -eps {
                        t1 = -1.0;
                    }
                } else {
                    let s = (-eps - f0) / f1;
                    if f1 > 0.0 {
                        t0 = t0.max(s);
                    } else {
                        t1 = t1.min(s);
                    }
                }
            }
            if t0 <= t1 {
                spans.push((t0, t1));
            }
        }
        spans.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut covered = 0.0f64;
        for (s, e) in spans {
            if s > covered + 1e-9 {
                return false;
            }
            covered = covered.max(e);
        }
        covered >= 1.0 - 1e-9
    }

    /// Exact distances from `sources` (points of the region with start values).
    pub fn exact(&self, sources: &[(DVec2, f64)]) -> Exact<'_> {
        // Dijkstra over the sources and the reflex vertices, on visibility.
        let mut nodes: Vec<(DVec2, f64, bool)> =
            sources.iter().map(|&(p, s)| (p, s, true)).collect();
        nodes.extend(self.reflex.iter().map(|&p| (p, f64::INFINITY, false)));
        let mut done = vec![false; nodes.len()];
        let next = |nodes: &[(DVec2, f64, bool)], done: &[bool]| {
            (0..nodes.len())
                .filter(|&i| !done[i] && nodes[i].1.is_finite())
                .min_by(|&i, &j| nodes[i].1.total_cmp(&nodes[j].1))
        };
        while let Some(i) = next(&nodes, &done) {
            done[i] = true;
            for j in sources.len()..nodes.len() {
                if done[j] {
                    continue;
                }
                let d = nodes[i].1 + nodes[i].0.distance(nodes[j].0);
                if d < nodes[j].1 && self.covers(nodes[i].0, nodes[j].0) {
                    nodes[j].1 = d;
                }
            }
        }
        Exact {
            region: self,
            nodes,
        }
    }
}

/// Exact distances from some sources in a [`Region`].
pub struct Exact<'r> {
    pub region: &'r Region,
    /// Sources and reflex vertices: position, exact distance, whether a source.
    pub nodes: Vec<(DVec2, f64, bool)>,
}

impl Exact<'_> {
    /// The exact distance at `x`, and whether a straight segment from a source gives it
    /// (the point sees its nearest source).
    pub fn at(&self, x: DVec2) -> (f64, bool) {
        let mut offers: Vec<(f64, bool, DVec2)> = self
            .nodes
            .iter()
            .filter(|n| n.1.is_finite())
            .map(|n| (n.1 + n.0.distance(x), n.2, n.0))
            .collect();
        offers.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::INFINITY;
        for &(d, is_source, p) in &offers {
            if d > best + 1e-12 * self.region.size {
                break;
            }
            if self.region.covers(p, x) {
                if best.is_infinite() {
                    best = d;
                }
                if is_source {
                    return (best, true);
                }
            }
        }
        (best, false)
    }
}

/// How a run's node values compare with the exact distances.
#[derive(Debug, Default, Clone, Copy)]
pub struct Deviation {
    /// Worst |d − exact| / scale over the nodes that see their nearest source.
    pub direct: f64,
    /// Over the other nodes (behind a hole): worst (d − exact) / scale, and worst
    /// (exact − d) / scale (how far below the true distance).
    pub behind_excess: f64,
    pub below: f64,
    pub behind_count: usize,
    pub nodes: usize,
}

impl Deviation {
    pub fn merge(self, o: Deviation) -> Deviation {
        Deviation {
            direct: self.direct.max(o.direct),
            behind_excess: self.behind_excess.max(o.behind_excess),
            below: self.below.max(o.below),
            behind_count: self.behind_count + o.behind_count,
            nodes: self.nodes + o.nodes,
        }
    }
}

/// Compares every node of `field` (vertices and Steiner points) with the exact distance
/// in `region` from `sources`.
pub fn deviation(
    mesh: &TriMesh,
    region: &Region,
    field: &FieldData,
    sources: &[Source],
) -> Deviation {
    let points: Vec<(DVec2, f64)> = sources
        .iter()
        .map(|s| (region.point(mesh, s.point), s.start))
        .collect();
    let exact = region.exact(&points);
    let start_scale = sources.iter().map(|s| s.start.abs()).fold(0.0, f64::max);
    let layout = field.layout();
    let mut dev = Deviation::default();
    for (node, &d) in field.node_distances().iter().enumerate() {
        let x = region.point(mesh, layout.surface_point(node as u32));
        let (e, direct) = exact.at(x);
        assert!(
            e.is_finite() && d.is_finite(),
            "node {node} at {x}: {d}, exact {e}"
        );
        let scale = e.abs().max(start_scale).max(1e-9 * region.size);
        let r = (d - e) / scale;
        dev.nodes += 1;
        dev.below = dev.below.max(-r);
        if direct {
            dev.direct = dev.direct.max(r.abs());
        } else {
            dev.behind_count += 1;
            dev.behind_excess = dev.behind_excess.max(r);
        }
    }
    dev
}

pub fn random_edge_point(mesh: &TriMesh, rng: &mut Rng) -> SurfacePoint {
    SurfacePoint::Edge {
        edge: rng.below(mesh.edge_count()) as u32,
        t: 0.1 + 0.8 * rng.next(),
    }
}

pub fn random_vertex(mesh: &TriMesh, rng: &mut Rng) -> SurfacePoint {
    SurfacePoint::Vertex(rng.below(mesh.vertex_count()) as u32)
}

/// One source of every kind: a vertex, a point inside a face, a point on an edge, and a
/// face point with a negative start value.
pub fn single_sources(mesh: &TriMesh, seed: u64) -> Vec<Vec<Source>> {
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    vec![
        vec![Source::new(random_vertex(mesh, &mut rng))],
        vec![Source::new(random_face_point(mesh, &mut rng))],
        vec![Source::new(random_edge_point(mesh, &mut rng))],
        vec![Source::new(random_face_point(mesh, &mut rng)).with_start(-0.25)],
    ]
}

/// Several sources at once: a vertex and a face point (start 0), and one of every kind
/// with start values (one negative).
pub fn several_sources(mesh: &TriMesh, seed: u64) -> Vec<Vec<Source>> {
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    vec![
        vec![
            Source::new(random_vertex(mesh, &mut rng)),
            Source::new(random_face_point(mesh, &mut rng)),
        ],
        vec![
            Source::new(random_vertex(mesh, &mut rng)).with_start(0.1),
            Source::new(random_face_point(mesh, &mut rng)).with_start(-0.05),
            Source::new(random_edge_point(mesh, &mut rng)).with_start(0.05),
        ],
    ]
}

/// The planar meshes with no hole: needles, fans, jittered grids.
pub fn convex_planar_meshes() -> Vec<(String, TriMesh)> {
    let mut meshes = vec![
        (
            "needle square (1000 needles a side)".to_string(),
            needle_square(3, 1000),
        ),
        (
            "fan around an interior vertex".to_string(),
            square_fan(1000, [0.3, 0.6]),
        ),
        ("fan from a corner".to_string(), corner_fan(1000)),
        (
            "2 × 2000 rectangle".to_string(),
            rectangle(2, 2000, 1.0, 1.0),
        ),
    ];
    for seed in [1, 3, 5] {
        meshes.push((
            format!("jittered grid {seed}"),
            holey_grid(seed, 10, 0.2, 0),
        ));
    }
    meshes
}

/// Planar meshes with holes: the square hole above and jittered grids with holes of
/// non-convex outline.
pub fn holey_meshes() -> Vec<(String, TriMesh)> {
    let ticks: Vec<f64> = (0..=12).map(|i| i as f64 / 4.0).collect();
    let mut meshes = vec![(
        "square hole".to_string(),
        super::xy_grid(&ticks, &ticks, Some([4, 4, 8, 8]), |i, j| (i + j) % 2 == 0),
    )];
    for seed in [1, 3, 5] {
        meshes.push((
            format!("grid with holes {seed}"),
            holey_grid(seed, 12, 0.2, 3),
        ));
    }
    meshes.push((
        "unjittered grid with holes".to_string(),
        holey_grid(7, 12, 0.0, 3),
    ));
    meshes
}

/// A mesh and its unrolling.
pub type Unrolled = (TriMesh, Vec<[f64; 2]>);

pub fn cones() -> Vec<(&'static str, Unrolled)> {
    vec![
        ("cone 40 × 12", cone_strip(3, 40, 12, 0.5, 5.5, 0.4, 1.5)),
        (
            "narrow cone 60 × 8",
            cone_strip(7, 60, 8, 0.5, 5.5, 1.2, 1.5),
        ),
    ]
}
