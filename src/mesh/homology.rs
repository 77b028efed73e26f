//! Homology over GF(2) of a mesh seen as a simplicial complex: its faces, their edges
//! and vertices, and its line elements (free edges).
//!
//! A medial axis is such a complex (sheets glued along junction curves, free curves),
//! and a skeleton of it must keep its topology: one component per component, as many
//! independent cycles as it has (b₁). With χ = V − E + F = b₀ − b₁ + b₂, the Betti
//! numbers follow from b₀ (union–find over the edges) and b₂, the dimension of the space
//! of 2-cycles (sets of faces in which every edge has an even number of faces).
//!
//! b₂ is found without a matrix of all faces: faces glued across an edge that has
//! exactly two of them are in a 2-cycle together or not at all, so they form one
//! *sheet*; a sheet with an edge of one face is in no 2-cycle; what is left is a small
//! system over the edges with three or more faces (junctions), solved by Gaussian
//! elimination over GF(2).

use super::{DisjointSets, TriMesh, NONE};
use std::collections::HashMap;

/// Betti numbers over GF(2) of a complex of vertices, edges and triangles.
///
/// ```
/// use geotracks::mesh::TriMesh;
///
/// // Three triangles sharing one edge (a book of three pages): contractible.
/// let book = TriMesh::new(
///     vec![[0., 0., 0.], [0., 0., 1.], [1., 0., 0.], [-1., 0., 0.], [0., 1., 0.]],
///     vec![[0, 1, 2], [0, 1, 3], [0, 1, 4]],
/// )?;
/// let betti = book.betti_numbers();
/// assert_eq!((betti.b0, betti.b1, betti.b2), (1, 0, 0));
/// # Ok::<(), geotracks::mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Betti {
    /// Connected components.
    pub b0: usize,
    /// Independent cycles (tunnels, loops of curves, holes in sheets that are not
    /// filled).
    pub b1: usize,
    /// Independent closed surfaces (2-cycles: cavities).
    pub b2: usize,
}

impl TriMesh {
    /// The Betti numbers over GF(2) of the mesh's kept faces together with its line
    /// elements: vertices that neither uses do not count. Degenerate faces that were
    /// dropped do not count either (see [`TriMesh::dropped_faces`]).
    ///
    /// Cost: near-linear in the mesh's size, plus an elimination over the sheets and
    /// junction edges (small for a medial axis).
    pub fn betti_numbers(&self) -> Betti {
        let wires: Vec<[u32; 2]> = self.wires().collect();
        let mut edges: Vec<[u32; 2]> = (0..self.edge_count() as u32)
            .map(|e| self.edge_vertices(e))
            .collect();
        edges.extend_from_slice(&wires);
        let (b0, vertices) = components_of_edges(self.vertex_count(), &edges);
        let b2 = CycleSheets::new(self, |_| true).count();
        // χ = V − E + F = b0 − b1 + b2.
        let b1 = edges.len() + b0 + b2 - vertices - self.face_count();
        Betti { b0, b1, b2 }
    }
}

/// The Betti numbers of a graph (a medial axis of curves only): `vertex_count` vertices,
/// of which those that no edge uses do not count, and `edges` (repeated edges and loops
/// at one vertex are ignored).
pub fn graph_betti_numbers(vertex_count: usize, edges: &[[u32; 2]]) -> Betti {
    let unique = unique_edges(edges);
    let (b0, vertices) = components_of_edges(vertex_count, &unique);
    Betti {
        b0,
        b1: unique.len() + b0 - vertices,
        b2: 0,
    }
}

/// The edges as `[lower, higher]`, each once, sorted; loops at one vertex left out.
pub(crate) fn unique_edges(edges: &[[u32; 2]]) -> Vec<[u32; 2]> {
    let mut unique: Vec<[u32; 2]> = edges
        .iter()
        .filter(|e| e[0] != e[1])
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .collect();
    unique.sort_unstable();
    unique.dedup();
    unique
}

/// Components among the vertices that some edge uses, and how many vertices that is.
fn components_of_edges(vertex_count: usize, edges: &[[u32; 2]]) -> (usize, usize) {
    let mut sets = DisjointSets::new(vertex_count);
    let mut used = vec![false; vertex_count];
    for &[a, b] in edges {
        sets.join(a, b);
        used[a as usize] = true;
        used[b as usize] = true;
    }
    let vertices = used.iter().filter(|&&u| u).count();
    let components = (0..vertex_count as u32)
        .filter(|&v| used[v as usize] && sets.find(v) == v)
        .count();
    (components, vertices)
}

/// The sheets of a set of faces and which of them lie on 2-cycles: a basis of the
/// 2-cycles has one sheet of its own per cycle, so [`CycleSheets::count`] is b₂ of the
/// faces.
pub(crate) struct CycleSheets {
    /// Per face, its sheet (`NONE` for faces left out).
    pub sheet_of: Vec<u32>,
    /// Per sheet, whether it is the last sheet of a 2-cycle found by the elimination
    /// (so removing one of its faces breaks that cycle and no other homology).
    pub closes_cycle: Vec<bool>,
}

impl CycleSheets {
    /// The sheets of the faces `alive` accepts, and the 2-cycles among them.
    pub fn new(mesh: &TriMesh, alive: impl Fn(u32) -> bool) -> CycleSheets {
        let faces = mesh.face_count();
        let mut sets = DisjointSets::new(faces);
        let mut around = Vec::new();
        let alive_faces = |e: u32, around: &mut Vec<u32>| {
            around.clear();
            around.extend(mesh.edge_faces(e).iter().copied().filter(|&f| alive(f)));
        };
        for e in 0..mesh.edge_count() as u32 {
            alive_faces(e, &mut around);
            if around.len() == 2 {
                sets.join(around[0], around[1]);
            }
        }
        let (label, count) = sets.labels();
        let mut sheet_of = vec![NONE; faces];
        for f in 0..faces as u32 {
            if alive(f) {
                sheet_of[f as usize] = label[f as usize];
            }
        }
        // A sheet with an edge of one face, or with no face at all, is in no cycle.
        let mut open = vec![true; count];
        for &s in &sheet_of {
            if s != NONE {
                open[s as usize] = false;
            }
        }
        // Per sheet, the junction edges on which it has an odd number of faces.
        let mut columns: Vec<Vec<u32>> = vec![Vec::new(); count];
        let mut sheets = Vec::new();
        for e in 0..mesh.edge_count() as u32 {
            alive_faces(e, &mut around);
            match around.len() {
                1 => open[sheet_of[around[0] as usize] as usize] = true,
                n if n >= 3 => {
                    sheets.clear();
                    sheets.extend(around.iter().map(|&f| sheet_of[f as usize]));
                    sheets.sort_unstable();
                    for run in sheets.chunk_by(|a, b| a == b) {
                        if run.len() % 2 == 1 {
                            columns[run[0] as usize].push(e);
                        }
                    }
                }
                _ => {}
            }
        }
        // Column reduction over GF(2), lowest row = pivot (columns are sorted).
        let mut closes_cycle = vec![false; count];
        let mut owner: HashMap<u32, usize> = HashMap::new();
        for s in 0..count {
            if open[s] {
                continue;
            }
            let mut column = std::mem::take(&mut columns[s]);
            while let Some(&low) = column.last() {
                match owner.get(&low) {
                    Some(&other) => column = symmetric_difference(&column, &columns[other]),
                    None => {
                        owner.insert(low, s);
                        break;
                    }
                }
            }
            closes_cycle[s] = column.is_empty();
            columns[s] = column;
        }
        CycleSheets {
            sheet_of,
            closes_cycle,
        }
    }

    /// How many independent 2-cycles the faces have (b₂).
    pub fn count(&self) -> usize {
        self.closes_cycle.iter().filter(|&&c| c).count()
    }
}

/// The sorted symmetric difference of two sorted lists (sum over GF(2)).
fn symmetric_difference(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed octahedron, optionally without its last face.
    fn octahedron(drop_last: bool) -> TriMesh {
        let positions = vec![
            [1., 0., 0.],
            [-1., 0., 0.],
            [0., 1., 0.],
            [0., -1., 0.],
            [0., 0., 1.],
            [0., 0., -1.],
        ];
        let mut faces = vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        if drop_last {
            faces.pop();
        }
        TriMesh::new(positions, faces).unwrap()
    }

    #[test]
    fn sphere_and_disc() {
        assert_eq!(
            octahedron(false).betti_numbers(),
            Betti {
                b0: 1,
                b1: 0,
                b2: 1
            }
        );
        assert_eq!(
            octahedron(true).betti_numbers(),
            Betti {
                b0: 1,
                b1: 0,
                b2: 0
            }
        );
    }

    #[test]
    fn two_spheres_glued_on_an_edge_and_a_wire_loop() {
        // A second octahedron whose equator starts with vertices 0 and 2 of the first,
        // so edge 0–2 has four faces; then a triangle of wires hanging off vertex 1.
        let mut positions: Vec<[f64; 3]> = octahedron(false)
            .positions()
            .iter()
            .map(|p| p.to_array())
            .collect();
        positions.extend_from_slice(&[
            [1.5, 2.5, 0.],
            [2.5, 1.5, 0.],
            [1.2, 1.2, 1.],
            [1.2, 1.2, -1.],
            [-2., 0., 0.],
            [-2., 1., 0.],
        ]);
        let [e0, e1, e2, e3, up, down] = [0, 2, 6, 7, 8, 9];
        let mut faces: Vec<[u32; 3]> = octahedron(false).triangles().to_vec();
        faces.extend_from_slice(&[
            [e0, e1, up],
            [e1, e2, up],
            [e2, e3, up],
            [e3, e0, up],
            [e1, e0, down],
            [e2, e1, down],
            [e3, e2, down],
            [e0, e3, down],
        ]);
        let wires = vec![[1, 10], [10, 11], [11, 1]];
        let mesh = TriMesh::with_line_elements(positions, faces, wires).unwrap();
        assert_eq!(mesh.report().max_edge_valence, 4);
        assert_eq!(
            mesh.betti_numbers(),
            Betti {
                b0: 1,
                b1: 1,
                b2: 2
            }
        );
    }

    #[test]
    fn annulus_and_graph() {
        // A square annulus: 8 outer/inner vertices, 8 faces.
        let positions = vec![
            [0., 0., 0.],
            [3., 0., 0.],
            [3., 3., 0.],
            [0., 3., 0.],
            [1., 1., 0.],
            [2., 1., 0.],
            [2., 2., 0.],
            [1., 2., 0.],
        ];
        let mut faces = Vec::new();
        for i in 0..4u32 {
            let j = (i + 1) % 4;
            faces.push([i, j, 4 + j]);
            faces.push([i, 4 + j, 4 + i]);
        }
        let mesh = TriMesh::new(positions, faces).unwrap();
        assert_eq!(
            mesh.betti_numbers(),
            Betti {
                b0: 1,
                b1: 1,
                b2: 0
            }
        );
        // Two triangles of curves and a lone edge; vertex 9 unused.
        let edges = [
            [0, 1],
            [1, 2],
            [2, 0],
            [3, 4],
            [4, 5],
            [5, 3],
            [6, 7],
            [7, 6],
        ];
        assert_eq!(
            graph_betti_numbers(10, &edges),
            Betti {
                b0: 3,
                b1: 2,
                b2: 0
            }
        );
    }
}
