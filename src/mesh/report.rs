use super::{DisjointSets, TriMesh};
use std::fmt;

/// What a mesh is made of, and what in it may surprise an algorithm.
#[derive(Clone, Debug, PartialEq, Eq)]
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
    /// Connected components of the faces (faces that share a vertex are connected).
    pub components: usize,
    /// Vertices that no kept face uses.
    pub unreferenced_vertices: usize,
    /// Line elements (free edges) carried along, e.g. from a medial axis.
    pub line_edges: usize,
}

impl MeshReport {
    pub(super) fn of(mesh: &TriMesh) -> MeshReport {
        let valences = (0..mesh.edge_count() as u32).map(|e| mesh.edge_faces(e).len());
        let unreferenced_vertices = (0..mesh.vertex_count() as u32)
            .filter(|&v| mesh.vertex_faces(v).is_empty())
            .count();
        MeshReport {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            edges: mesh.edge_count(),
            boundary_edges: valences.clone().filter(|&n| n == 1).count(),
            non_manifold_edges: valences.clone().filter(|&n| n > 2).count(),
            max_edge_valence: valences.max().unwrap_or(0),
            degenerate_faces: mesh.dropped_faces().len(),
            components: vertex_components(mesh).1 - unreferenced_vertices,
            unreferenced_vertices,
            line_edges: mesh.line_edges().len(),
        }
    }
}

/// Labels each vertex with its component (vertices joined by face edges) and counts the
/// components, unreferenced vertices counting as one each.
pub(crate) fn vertex_components(mesh: &TriMesh) -> (Vec<u32>, usize) {
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
        write!(f, "line elements         {}", self.line_edges)
    }
}
