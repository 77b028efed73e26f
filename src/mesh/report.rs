use super::{Betti, DisjointSets, Topology, TriMesh};
use std::collections::HashMap;
use std::fmt;

/// What a mesh is made of, and what in it may surprise an algorithm.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MeshReport {
    /// Vertices, unreferenced ones included.
    pub vertices: usize,
    /// Kept faces.
    pub faces: usize,
    /// Edges that belong to at least one face.
    pub edges: usize,
    /// Edges with exactly one face.
    pub boundary_edges: usize,
    /// Edges with three or more faces.
    pub non_manifold_edges: usize,
    /// The most faces any edge has.
    pub max_edge_valence: usize,
    /// Faces dropped as degenerate (zero area or a repeated vertex).
    pub degenerate_faces: usize,
    /// Connected components of the faces and line elements together (faces that share
    /// a vertex are connected, and so are the ends of a line element).
    pub components: usize,
    /// Vertices that no kept face and no line element uses.
    pub unreferenced_vertices: usize,
    /// Line elements (free edges) carried along, e.g. from a medial axis.
    pub line_edges: usize,
    /// Vertices at exactly the position of an earlier vertex (`-0.0` and `0.0` equal):
    /// seams that split a surface, which reading with `weld` merges.
    pub duplicate_positions: usize,
    /// The smallest and largest coordinates of all vertices, unreferenced ones included.
    pub bounding_box: [[f64; 3]; 2],
    /// Mean Euclidean length of the face edges.
    pub mean_edge_length: f64,
    /// Euler characteristic χ = V − E + F of the faces (vertices that no face uses left
    /// out): the sum of the components' χ.
    pub euler_characteristic: i64,
    /// Betti numbers over GF(2) of the faces and line elements together: components,
    /// independent cycles (tunnels, loops), closed surfaces (cavities).
    pub betti: Betti,
    /// One entry per connected component of the faces, largest (most faces) first.
    pub surfaces: Vec<SurfaceReport>,
}

/// The topology of one connected component of a mesh's faces.
///
/// Its genus is defined only where the usual formula means something: a component that
/// is a *manifold* surface (every edge on one or two faces, the faces around every
/// vertex one fan) and *orientable* has genus g = (2 − χ − b) / 2, with b its boundary
/// loops (a sphere 0, a torus 1, a disc 0, an annulus 0). A non-manifold component (a
/// medial axis's junction curves, a pinched vertex) has no genus in this sense, nor does
/// a non-orientable one (a Möbius strip); χ is reported for every component.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SurfaceReport {
    /// Vertices used by its faces.
    pub vertices: usize,
    /// Its edges.
    pub edges: usize,
    /// Its faces.
    pub faces: usize,
    /// χ = V − E + F.
    pub euler_characteristic: i64,
    /// Whether every edge has one or two faces and every vertex one fan of faces.
    pub manifold: bool,
    /// Whether its faces can be oriented consistently (`None` if not manifold).
    pub orientable: Option<bool>,
    /// Closed loops of boundary edges (`None` if not manifold).
    pub boundary_loops: Option<usize>,
    /// (2 − χ − b) / 2, for an orientable manifold component; `None` otherwise.
    pub genus: Option<i64>,
}

impl MeshReport {
    /// The report of a graph with no faces (a medial axis of curves only): its edges are
    /// line elements.
    pub(crate) fn of_curves(positions: &[[f64; 3]], edges: &[[u32; 2]]) -> MeshReport {
        let mut used = vec![false; positions.len()];
        for &[a, b] in edges {
            used[a as usize] = true;
            used[b as usize] = true;
        }
        let betti = super::graph_betti_numbers(positions.len(), edges);
        MeshReport {
            vertices: positions.len(),
            faces: 0,
            edges: 0,
            boundary_edges: 0,
            non_manifold_edges: 0,
            max_edge_valence: 0,
            degenerate_faces: 0,
            components: betti.b0,
            unreferenced_vertices: used.iter().filter(|&&u| !u).count(),
            line_edges: edges.len(),
            duplicate_positions: 0,
            bounding_box: bounding_box(positions.iter().copied()),
            mean_edge_length: 0.0,
            euler_characteristic: 0,
            betti,
            surfaces: Vec::new(),
        }
    }

    pub(super) fn of(mesh: &TriMesh) -> MeshReport {
        let valences = (0..mesh.edge_count() as u32).map(|e| mesh.edge_faces(e).len());
        let mut on_lines = vec![false; mesh.vertex_count()];
        for &[a, b] in mesh.line_edges() {
            on_lines[a as usize] = true;
            on_lines[b as usize] = true;
        }
        let unreferenced_vertices = (0..mesh.vertex_count() as u32)
            .filter(|&v| mesh.vertex_faces(v).is_empty() && !on_lines[v as usize])
            .count();
        let face_vertices = (0..mesh.vertex_count() as u32)
            .filter(|&v| !mesh.vertex_faces(v).is_empty())
            .count();
        let betti = mesh.betti_numbers();
        MeshReport {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            edges: mesh.edge_count(),
            boundary_edges: valences.clone().filter(|&n| n == 1).count(),
            non_manifold_edges: valences.clone().filter(|&n| n > 2).count(),
            max_edge_valence: valences.max().unwrap_or(0),
            degenerate_faces: mesh.dropped_faces().len(),
            components: betti.b0,
            unreferenced_vertices,
            line_edges: mesh.line_edges().len(),
            duplicate_positions: duplicate_positions(mesh),
            bounding_box: bounding_box(mesh.positions().iter().map(|p| p.to_array())),
            mean_edge_length: mesh.mean_edge_length(),
            euler_characteristic: face_vertices as i64 - mesh.edge_count() as i64
                + mesh.face_count() as i64,
            betti,
            surfaces: surfaces(mesh),
        }
    }
}

/// Vertices whose position (bit for bit, `-0.0` as `0.0`) an earlier vertex has.
pub(crate) fn duplicate_positions(mesh: &TriMesh) -> usize {
    let mut seen: HashMap<[u64; 3], ()> = HashMap::with_capacity(mesh.vertex_count());
    mesh.positions()
        .iter()
        .filter(|p| {
            seen.insert(p.to_array().map(|c| (c + 0.0).to_bits()), ())
                .is_some()
        })
        .count()
}

/// The smallest and largest coordinates of `points` (infinite bounds for none).
pub(crate) fn bounding_box(points: impl IntoIterator<Item = [f64; 3]>) -> [[f64; 3]; 2] {
    let mut bounds = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for p in points {
        for (axis, c) in p.into_iter().enumerate() {
            bounds[0][axis] = bounds[0][axis].min(c);
            bounds[1][axis] = bounds[1][axis].max(c);
        }
    }
    bounds
}

/// The topology of each connected component of the faces.
fn surfaces(mesh: &TriMesh) -> Vec<SurfaceReport> {
    let (labels, count) = face_components(mesh);
    let mut reports = vec![
        SurfaceReport {
            vertices: 0,
            edges: 0,
            faces: 0,
            euler_characteristic: 0,
            manifold: true,
            orientable: None,
            boundary_loops: None,
            genus: None,
        };
        count
    ];
    let component_of_edge = |e: u32| labels[mesh.edge_vertices(e)[0] as usize] as usize;
    for v in 0..mesh.vertex_count() as u32 {
        if !mesh.vertex_faces(v).is_empty() {
            let r = &mut reports[labels[v as usize] as usize];
            r.vertices += 1;
            r.manifold &= vertex_is_manifold(mesh, v);
        }
    }
    for e in 0..mesh.edge_count() as u32 {
        let r = &mut reports[component_of_edge(e)];
        r.edges += 1;
        r.manifold &= mesh.edge_faces(e).len() <= 2;
    }
    for f in 0..mesh.face_count() as u32 {
        reports[labels[mesh.face_vertices(f)[0] as usize] as usize].faces += 1;
    }
    let orientable = orientability(mesh, &labels, count);
    let loops = boundary_loops(mesh, &labels, count);
    for (c, r) in reports.iter_mut().enumerate() {
        r.euler_characteristic = r.vertices as i64 - r.edges as i64 + r.faces as i64;
        if r.manifold {
            r.orientable = Some(orientable[c]);
            r.boundary_loops = Some(loops[c]);
            if orientable[c] {
                r.genus = Some((2 - r.euler_characteristic - loops[c] as i64) / 2);
            }
        }
    }
    reports.retain(|r| r.faces > 0);
    reports.sort_by_key(|r| std::cmp::Reverse(r.faces));
    reports
}

/// Whether the faces around `v` form one fan: joined through edges at `v` that have
/// exactly two faces, they make one group. A vertex where two fans meet and nothing
/// else (a pinch) is not, even when every edge at it has two faces.
pub(crate) fn vertex_is_manifold<T: Topology>(mesh: &T, v: u32) -> bool {
    let faces = mesh.vertex_faces(v);
    if faces.len() <= 1 {
        return true;
    }
    let mut sets = DisjointSets::new(faces.len());
    let local = |f: u32| faces.iter().position(|&g| g == f);
    for &e in mesh.vertex_edges(v).iter() {
        if let [a, b] = *mesh.edge_faces(e) {
            if let (Some(i), Some(j)) = (local(a), local(b)) {
                sets.join(i as u32, j as u32);
            }
        }
    }
    sets.labels().1 == 1
}

/// Per component, whether its faces can be oriented consistently across every edge
/// with two faces (only meaningful for manifold components).
fn orientability(mesh: &TriMesh, labels: &[u32], count: usize) -> Vec<bool> {
    let mut orientable = vec![true; count];
    // 0 unset, 1 as stored, -1 flipped.
    let mut sign = vec![0i8; mesh.face_count()];
    let mut stack = Vec::new();
    // Whether face f runs along edge e from its lower to its higher vertex.
    let forward = |f: u32, e: u32| {
        let s = mesh.edge_slot(f, e).unwrap_or(0);
        !mesh.slot_is_reversed(f, s)
    };
    for start in 0..mesh.face_count() as u32 {
        if sign[start as usize] != 0 {
            continue;
        }
        sign[start as usize] = 1;
        stack.push(start);
        while let Some(f) = stack.pop() {
            for e in mesh.face_edges(f) {
                let [a, b] = *mesh.edge_faces(e) else {
                    continue;
                };
                let g = if a == f { b } else { a };
                // Consistent neighbours run along their shared edge in opposite directions.
                let want = if forward(f, e) == forward(g, e) {
                    -sign[f as usize]
                } else {
                    sign[f as usize]
                };
                match sign[g as usize] {
                    0 => {
                        sign[g as usize] = want;
                        stack.push(g);
                    }
                    s if s != want => {
                        orientable[labels[mesh.face_vertices(f)[0] as usize] as usize] = false
                    }
                    _ => {}
                }
            }
        }
    }
    orientable
}

/// Per component, the loops of boundary edges (edges with one face), counted as
/// connected pieces of the boundary-edge graph (exact for manifold components, where
/// every boundary vertex has two boundary edges).
fn boundary_loops(mesh: &TriMesh, labels: &[u32], count: usize) -> Vec<usize> {
    let mut sets = DisjointSets::new(mesh.vertex_count());
    let mut on_boundary = vec![false; mesh.vertex_count()];
    for e in 0..mesh.edge_count() as u32 {
        if mesh.edge_faces(e).len() == 1 {
            let [a, b] = mesh.edge_vertices(e);
            sets.join(a, b);
            on_boundary[a as usize] = true;
            on_boundary[b as usize] = true;
        }
    }
    let mut loops = vec![0; count];
    for v in 0..mesh.vertex_count() as u32 {
        if on_boundary[v as usize] && sets.find(v) == v {
            loops[labels[v as usize] as usize] += 1;
        }
    }
    loops
}

/// Labels each vertex with its component of the faces (vertices joined by face edges)
/// and counts the components, vertices of no face counting as one each.
fn face_components(mesh: &TriMesh) -> (Vec<u32>, usize) {
    let mut sets = DisjointSets::new(mesh.vertex_count());
    for e in 0..mesh.edge_count() as u32 {
        let [a, b] = mesh.edge_vertices(e);
        sets.join(a, b);
    }
    sets.labels()
}

impl fmt::Display for MeshReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "vertices              {}", self.vertices)?;
        writeln!(f, "faces                 {}", self.faces)?;
        writeln!(f, "edges                 {}", self.edges)?;
        writeln!(f, "boundary edges        {}", self.boundary_edges)?;
        writeln!(
            f,
            "non-manifold edges    {} (max faces on one edge: {})",
            self.non_manifold_edges, self.max_edge_valence
        )?;
        writeln!(
            f,
            "degenerate faces      {} (dropped)",
            self.degenerate_faces
        )?;
        writeln!(f, "components            {}", self.components)?;
        writeln!(f, "unreferenced vertices {}", self.unreferenced_vertices)?;
        writeln!(f, "line elements         {}", self.line_edges)?;
        writeln!(
            f,
            "duplicate positions   {}{}",
            self.duplicate_positions,
            if self.duplicate_positions > 0 {
                " (vertices at an earlier vertex's position; --weld merges them)"
            } else {
                ""
            }
        )?;
        let [lo, hi] = self.bounding_box;
        writeln!(
            f,
            "bounding box          [{}, {}] x [{}, {}] x [{}, {}]",
            lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
        )?;
        writeln!(f, "mean edge length      {}", self.mean_edge_length)?;
        writeln!(
            f,
            "Euler characteristic  {} (V - E + F of the faces)",
            self.euler_characteristic
        )?;
        write!(
            f,
            "Betti numbers         b0 {}, b1 {}, b2 {} (over GF(2): components, independent cycles, closed surfaces; faces and line elements)",
            self.betti.b0, self.betti.b1, self.betti.b2
        )?;
        const SHOWN: usize = 10;
        for (i, s) in self.surfaces.iter().take(SHOWN).enumerate() {
            write!(
                f,
                "\ncomponent {i}: {} faces, {} vertices, {} edges, chi {}, ",
                s.faces, s.vertices, s.edges, s.euler_characteristic
            )?;
            match (s.manifold, s.orientable, s.boundary_loops, s.genus) {
                (true, Some(true), Some(b), Some(g)) => {
                    write!(f, "manifold, orientable, {b} boundary loop(s), genus {g}")?
                }
                (true, _, Some(b), _) => write!(
                    f,
                    "manifold, non-orientable, {b} boundary loop(s), genus not defined"
                )?,
                _ => write!(f, "non-manifold, genus not defined")?,
            }
        }
        if self.surfaces.len() > SHOWN {
            write!(
                f,
                "\n… and {} smaller components",
                self.surfaces.len() - SHOWN
            )?;
        }
        Ok(())
    }
}
