use super::{try_reserve, Csr, MeshError, MeshReport};
use geotracks_metrics::{FaceGeometry, FacePoint};
use glam::DVec3;
use rayon::prelude::*;

/// A face's local 2D frame: corner 0 at the origin, corner 1 at `(l01, 0)`, corner 2 at
/// `(x2, y2)` with `y2 > 0`. Segment costs are computed in this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceFrame {
    /// Length of the edge from corner 0 to corner 1.
    pub l01: f64,
    /// u coordinate of corner 2.
    pub x2: f64,
    /// v coordinate of corner 2 (> 0 for a face that was kept).
    pub y2: f64,
}

impl FaceFrame {
    /// The length of the face's longest edge.
    #[inline]
    pub fn diameter(&self) -> f64 {
        // The longest edge's square, then one square root: the tracks engine asks for
        // the diameter at every settle under a metric that is not a norm, and `hypot`
        // costs several square roots. Where the squares leave the normal range (lengths
        // beyond 1e154 or below 1e-154) the exact `hypot`s instead.
        let (dx, y) = (self.x2 - self.l01, self.y2);
        let squared = (self.l01 * self.l01)
            .max(self.x2 * self.x2 + y * y)
            .max(dx * dx + y * y);
        if squared.is_normal() {
            squared.sqrt()
        } else {
            self.l01.max(self.x2.hypot(y)).max(dx.hypot(y))
        }
    }

    /// The three corners in the frame.
    #[inline]
    pub fn corners(&self) -> [[f64; 2]; 3] {
        [[0.0, 0.0], [self.l01, 0.0], [self.x2, self.y2]]
    }

    /// The point at parameter `t` from corner `i` towards corner `(i + 1) % 3`.
    #[inline]
    pub fn point_on_edge(&self, i: usize, t: f64) -> FacePoint {
        self.edge_line(i).point(t)
    }

    /// The edge from corner `i` to corner `(i + 1) % 3`, ready to place many points on
    /// it: [`FaceFrame::point_on_edge`] is `edge_line(i).point(t)`.
    #[inline]
    pub fn edge_line(&self, i: usize) -> EdgeLine {
        let c = self.corners();
        let (a, b) = (c[i], c[(i + 1) % 3]);
        EdgeLine {
            origin: a,
            delta: [b[0] - a[0], b[1] - a[1]],
            corners: [i, (i + 1) % 3],
        }
    }

    /// Corner `c` as a face point.
    #[inline]
    pub fn corner(&self, c: usize) -> FacePoint {
        let mut bary = [0.0; 3];
        bary[c] = 1.0;
        self.point(bary)
    }

    /// The point with barycentric coordinates `bary`.
    #[inline]
    pub fn point(&self, bary: [f64; 3]) -> FacePoint {
        FacePoint {
            uv: [bary[1] * self.l01 + bary[2] * self.x2, bary[2] * self.y2],
            bary,
        }
    }
}

/// One edge of a face in the face's frame (see [`FaceFrame::edge_line`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeLine {
    origin: [f64; 2],
    delta: [f64; 2],
    /// The corners it runs from and to.
    corners: [usize; 2],
}

impl EdgeLine {
    /// The point at parameter `t` from the edge's first corner.
    #[inline(always)]
    pub fn point(&self, t: f64) -> FacePoint {
        // Each weight chosen by comparisons rather than stored at a computed index: the
        // engines read the point back as a whole at once, and a store at a computed
        // index stalls that load (store forwarding fails).
        let [from, to] = self.corners;
        let weight = |c: usize| {
            if c == from {
                1.0 - t
            } else if c == to {
                t
            } else {
                0.0
            }
        };
        let bary = [weight(0), weight(1), weight(2)];
        FacePoint {
            uv: [
                self.origin[0] + t * self.delta[0],
                self.origin[1] + t * self.delta[1],
            ],
            bary,
        }
    }
}

/// A face that was left out because it is degenerate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct DroppedFace {
    /// Its index in the input.
    pub input_index: usize,
    /// `true` if two of its corners are the same vertex, `false` if it has zero area.
    pub repeated_vertex: bool,
}

/// A triangle mesh of any topology, with its edge table and per-face frames.
///
/// Build one with [`TriMesh::new`] (or read a file with [`crate::mesh::io::read_mesh`]).
/// Degenerate faces (a repeated vertex, or zero area) are dropped and listed in
/// [`TriMesh::dropped_faces`]; kept faces are renumbered densely, and
/// [`TriMesh::input_face`] maps them back. Vertices are never renumbered.
///
/// ```
/// use geotracks::mesh::TriMesh;
/// // Three faces sharing the edge 0–1: a non-manifold "book".
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
///     vec![[0, 1, 2], [0, 1, 3], [0, 1, 4]],
/// ).unwrap();
/// let spine = mesh.face_edges(0)[0];
/// assert_eq!(mesh.edge_faces(spine).len(), 3);
/// assert_eq!(mesh.report().max_edge_valence, 3);
/// ```
#[derive(Clone, Debug)]
pub struct TriMesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    frames: Vec<FaceFrame>,
    face_edges: Vec<[u32; 3]>,
    edge_vertices: Vec<[u32; 2]>,
    edge_faces: Csr,
    vertex_faces: Csr,
    vertex_edges: Csr,
    line_edges: Vec<[u32; 2]>,
    /// Per vertex, the vertices joined to it by a wire (a line element that is no face
    /// edge): the 1-skeleton that distances also travel.
    vertex_wires: Csr,
    input_faces: Vec<u32>,
    dropped: Vec<DroppedFace>,
    /// Faces and edges are numbered in a spatially coherent order (see
    /// [`TriMesh::with_edge_table`]).
    spatially_ordered: bool,
}

/// A `&TriMesh` where a shared mesh is wanted ([`Solver::new`](crate::Solver::new)) is
/// copied: pass the mesh itself, or an `Arc` of it, to share it without a copy.
impl From<&TriMesh> for std::sync::Arc<TriMesh> {
    fn from(mesh: &TriMesh) -> Self {
        std::sync::Arc::new(mesh.clone())
    }
}

impl TriMesh {
    /// Builds a mesh from positions and triangles (0-based vertex ids).
    ///
    /// # Errors
    /// [`MeshError::NonFiniteVertex`] for a NaN or infinite coordinate,
    /// [`MeshError::CoordinateOutOfRange`] for one beyond ±1e300,
    /// [`MeshError::IndexOutOfRange`] for a face that names a missing vertex,
    /// [`MeshError::NoUsableFace`] if no face is left after dropping degenerate ones.
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        Self::with_line_elements(positions, triangles, Vec::new())
    }

    /// As [`TriMesh::new`], also keeping line elements: edges that may belong to no face
    /// (a medial axis has them). Those that are no face edge are *wires*
    /// ([`TriMesh::vertex_wires`]): curves without area that distances travel along,
    /// vertex to vertex, at the metric's [`wire_cost`](geotracks_metrics::Metric::wire_cost);
    /// line elements that are also face edges are kept as given and change nothing.
    ///
    /// # Errors
    /// As [`TriMesh::new`], plus [`MeshError::EdgeIndexOutOfRange`].
    pub fn with_line_elements(
        positions: Vec<[f64; 3]>,
        triangles: Vec<[u32; 3]>,
        line_edges: Vec<[u32; 2]>,
    ) -> Result<Self, MeshError> {
        let faces = Faces::new(positions, triangles)?;
        check_line_edges(&line_edges, faces.positions.len())?;
        let (face_edges, edge_vertices) = build_edges(&faces.kept);
        let mut mesh = faces.assemble(face_edges, edge_vertices, false);
        mesh.set_line_elements(line_edges)?;
        Ok(mesh)
    }

    /// As [`TriMesh::new`], with the edge table given, for meshes whose structure is
    /// known (an elevation grid): `edge_vertices` lists every edge of the faces once,
    /// lower vertex first, sorted, as [`TriMesh::new`] numbers them, and
    /// `face_edges[f][i]` is the edge from corner `i` of face `f` to corner `i + 1`.
    /// This skips the sort that numbers edges. `spatially_ordered`: faces and edges
    /// are numbered in a spatially coherent order already (a grid's tiles), so solvers
    /// keep that order instead of sorting them along a space-filling curve.
    ///
    /// A face that turns out degenerate would renumber the faces after it: the edges
    /// are then numbered as [`TriMesh::new`] does, and so they are for a table that is
    /// not the one [`TriMesh::new`] would build (checked in one pass over the faces, far
    /// cheaper than the sort): a wrong table costs the time saved, never a wrong mesh.
    ///
    /// Public for the sibling crates whose meshes have a known structure (elevation
    /// grids, which number their edges tile by tile).
    ///
    /// # Errors
    /// As [`TriMesh::new`].
    pub fn with_edge_table(
        positions: Vec<[f64; 3]>,
        triangles: Vec<[u32; 3]>,
        face_edges: Vec<[u32; 3]>,
        edge_vertices: Vec<[u32; 2]>,
        spatially_ordered: bool,
    ) -> Result<Self, MeshError> {
        let faces = Faces::new(positions, triangles)?;
        // A degenerate face renumbers the faces after it: the table no longer fits.
        if !faces.dropped.is_empty() || !edge_table_fits(&faces.kept, &face_edges, &edge_vertices) {
            let (face_edges, edge_vertices) = build_edges(&faces.kept);
            return Ok(faces.assemble(face_edges, edge_vertices, false));
        }
        Ok(faces.assemble(face_edges, edge_vertices, spatially_ordered))
    }

    /// Replaces the line elements (see [`TriMesh::with_line_elements`]); useful when which
    /// edges are free is only known once the faces are built.
    ///
    /// # Errors
    /// [`MeshError::EdgeIndexOutOfRange`] for an edge that names a missing vertex; the
    /// mesh is left unchanged then.
    pub fn set_line_elements(&mut self, line_edges: Vec<[u32; 2]>) -> Result<(), MeshError> {
        check_line_edges(&line_edges, self.positions.len())?;
        let mut wires = super::unique_edges(&line_edges);
        wires.retain(|&[a, b]| {
            !self
                .vertex_edges(a)
                .iter()
                .any(|&e| self.edge_vertices(e).contains(&b))
        });
        self.vertex_wires = Csr::from_pairs(
            self.positions.len(),
            wires.iter().flat_map(|&[a, b]| [(a, b), (b, a)]),
        );
        self.line_edges = line_edges;
        Ok(())
    }

    /// The vertices joined to `v` by a wire: a line element that is no edge of a face
    /// (each wire once, whichever way and however often the line elements list it).
    ///
    /// ```
    /// use geotracks::mesh::TriMesh;
    /// // A triangle with a tail: the wire 2–3, and the face edge 0–1 listed again.
    /// let mesh = TriMesh::with_line_elements(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 2.0, 0.0]],
    ///     vec![[0, 1, 2]],
    ///     vec![[3, 2], [0, 1], [2, 3]],
    /// )?;
    /// assert_eq!(mesh.vertex_wires(2), &[3]);
    /// assert_eq!(mesh.vertex_wires(3), &[2]);
    /// assert!(mesh.vertex_wires(0).is_empty());
    /// # Ok::<(), geotracks::mesh::MeshError>(())
    /// ```
    ///
    /// # Panics
    /// If `v` is not a vertex of the mesh.
    #[inline]
    pub fn vertex_wires(&self, v: u32) -> &[u32] {
        self.vertex_wires.row(v)
    }

    /// The wires ([`TriMesh::vertex_wires`]), each once as `[lower, higher]`, sorted.
    pub fn wires(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        (0..self.positions.len() as u32).flat_map(move |a| {
            self.vertex_wires(a)
                .iter()
                .filter(move |&&b| a < b)
                .map(move |&b| [a, b])
        })
    }

    /// Whether faces and edges are numbered in a spatially coherent order already (a
    /// grid's tiles; see [`TriMesh::with_edge_table`]): solvers then keep it.
    pub(crate) fn is_spatially_ordered(&self) -> bool {
        self.spatially_ordered
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The position of vertex `v`.
    #[inline]
    pub fn position(&self, v: u32) -> DVec3 {
        self.positions[v as usize]
    }

    /// The kept triangles.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The local 2D frame of face `f`.
    #[inline]
    pub fn frame(&self, f: u32) -> &FaceFrame {
        &self.frames[f as usize]
    }

    /// Euclidean length of edge `e`.
    pub fn edge_length(&self, e: u32) -> f64 {
        let [a, b] = self.edge_vertices[e as usize];
        length(self.position(b) - self.position(a))
    }

    /// Line elements (free edges) given at construction.
    pub fn line_edges(&self) -> &[[u32; 2]] {
        &self.line_edges
    }

    /// The faces that were dropped as degenerate.
    pub fn dropped_faces(&self) -> &[DroppedFace] {
        &self.dropped
    }

    /// The input index of kept face `f` (differs from `f` once faces were dropped).
    pub fn input_face(&self, f: u32) -> usize {
        self.input_faces[f as usize] as usize
    }

    /// Number of faces in the input, dropped ones included.
    pub fn input_face_count(&self) -> usize {
        self.triangles.len() + self.dropped.len()
    }

    /// Which corner of face `f` vertex `v` is, if any.
    #[inline]
    pub fn corner_of(&self, f: u32, v: u32) -> Option<usize> {
        self.triangles[f as usize].iter().position(|&c| c == v)
    }

    /// Which of face `f`'s edges `e` is, if any.
    #[inline]
    pub fn edge_slot(&self, f: u32, e: u32) -> Option<usize> {
        self.face_edges[f as usize].iter().position(|&c| c == e)
    }

    /// Whether slot `s` of face `f` (from corner `s` to corner `s + 1`) runs from its
    /// edge's higher vertex, so that the edge's points, numbered from its lower vertex,
    /// come in reverse order along the slot.
    #[inline]
    pub fn slot_is_reversed(&self, f: u32, s: usize) -> bool {
        let e = self.face_edges[f as usize][s];
        self.triangles[f as usize][s] != self.edge_vertices[e as usize][0]
    }

    /// The world position of barycentric point `bary` of face `f`.
    pub fn point(&self, f: u32, bary: [f64; 3]) -> DVec3 {
        let t = self.triangles[f as usize];
        bary[0] * self.position(t[0])
            + bary[1] * self.position(t[1])
            + bary[2] * self.position(t[2])
    }

    /// Mean Euclidean edge length (0 for a mesh without edges).
    pub fn mean_edge_length(&self) -> f64 {
        let n = self.edge_vertices.len();
        if n == 0 {
            return 0.0;
        }
        // Each length divided first, so that no sum of lengths near 1e300 overflows.
        (0..n as u32)
            .map(|e| self.edge_length(e) / n as f64)
            .sum::<f64>()
    }

    /// Labels each vertex with its connected component (vertices joined by face edges
    /// or wires; an unreferenced vertex is a component of its own) and returns the
    /// labels and the number of components. Distances propagate only within a
    /// component.
    pub fn vertex_components(&self) -> (Vec<u32>, usize) {
        let mut sets = super::DisjointSets::new(self.vertex_count());
        for [a, b] in self.edge_vertices.iter().copied().chain(self.wires()) {
            sets.join(a, b);
        }
        sets.labels()
    }

    /// Counts of elements, boundary and non-manifold edges, components and so on.
    pub fn report(&self) -> MeshReport {
        MeshReport::of(self)
    }
}

fn check_line_edges(line_edges: &[[u32; 2]], vertex_count: usize) -> Result<(), MeshError> {
    for (edge, l) in line_edges.iter().enumerate() {
        if let Some(&v) = l.iter().find(|&&v| v as usize >= vertex_count) {
            return Err(MeshError::EdgeIndexOutOfRange {
                edge,
                vertex: v as i64,
                vertex_count,
            });
        }
    }
    Ok(())
}

/// The largest coordinate magnitude a mesh may have: differences of coordinates then
/// stay finite, and every length is computed without overflow or underflow (in
/// units of each face's size), so any mesh within it, at any scale, gets accurate frames.
pub const MAX_COORDINATE: f64 = 1e300;

/// The length of `v`, accurate at any scale: computed in units of its largest
/// component, so that no square over- or underflows (`DVec3::length` is off by 100 %
/// below 1e-154 and infinite above 1e154).
pub(super) fn length(v: DVec3) -> f64 {
    let scale = v.abs().max_element();
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    (v / scale).length() * scale
}

fn frame_of(corners: [DVec3; 3]) -> Option<FaceFrame> {
    FaceFrame::of_triangle(corners)
}

impl FaceFrame {
    /// The frame of the triangle with corners `p0, p1, p2`, or `None` if it has
    /// (numerically) zero area.
    ///
    /// Computed in units of the face's largest coordinate difference, so that a face of
    /// size 1e-200 or 1e200 gets the same relative accuracy as one of size 1.
    pub fn of_triangle([p0, p1, p2]: [DVec3; 3]) -> Option<FaceFrame> {
        let (e01, e02) = (p1 - p0, p2 - p0);
        let scale = e01.abs().max_element().max(e02.abs().max_element());
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        let (e01, e02, e12) = (e01 / scale, e02 / scale, (p2 - p1) / scale);
        let l01 = e01.length();
        let longest = l01.max(e02.length()).max(e12.length());
        let twice_area = e01.cross(e02).length();
        // Relative test: a sliver with aspect 1e6 is kept, an exactly flat one is not.
        if !(longest > 0.0 && twice_area > 1e-12 * longest * longest) || l01 == 0.0 {
            return None;
        }
        let u = e01 / l01;
        let x2 = e02.dot(u);
        let y2 = twice_area / l01;
        Some(FaceFrame {
            l01: l01 * scale,
            x2: x2 * scale,
            y2: y2 * scale,
        })
    }
}

/// Validated positions and the faces kept (degenerate ones dropped), with their
/// frames: what both ways of building a mesh share.
struct Faces {
    positions: Vec<DVec3>,
    kept: Vec<[u32; 3]>,
    frames: Vec<FaceFrame>,
    input_faces: Vec<u32>,
    dropped: Vec<DroppedFace>,
}

impl Faces {
    /// Checks the input and drops degenerate faces.
    ///
    /// # Errors
    /// As [`TriMesh::new`].
    fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Faces, MeshError> {
        let n = positions.len();
        if let Some((vertex, p)) = positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
        {
            return Err(MeshError::NonFiniteVertex {
                vertex,
                position: *p,
            });
        }
        if let Some((vertex, p)) = positions
            .iter()
            .enumerate()
            .find(|(_, p)| p.iter().any(|c| c.abs() > MAX_COORDINATE))
        {
            return Err(MeshError::CoordinateOutOfRange {
                vertex,
                position: *p,
                limit: MAX_COORDINATE,
            });
        }
        for (face, t) in triangles.iter().enumerate() {
            if let Some(&v) = t.iter().find(|&&v| v as usize >= n) {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    vertex: v as i64,
                    vertex_count: n,
                });
            }
        }
        // The tables sized by the input are reserved with an error, not an abort, when
        // memory runs out (a file's counts can ask for more than the process may use).
        let mut converted: Vec<DVec3> = Vec::new();
        try_reserve(&mut converted, n, || format!("{n} vertices"))?;
        converted.extend(positions.into_iter().map(DVec3::from_array));
        let positions = converted;

        let input_count = triangles.len();
        let faces = || format!("{input_count} faces");
        let repeats = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
        // The frames on all cores (a square root and a division or two per face, the
        // most of the work here), kept in face order.
        let mut all_frames: Vec<Option<FaceFrame>> = Vec::new();
        try_reserve(&mut all_frames, input_count, faces)?;
        all_frames.par_extend(triangles.par_iter().map(|t| {
            (!repeats(t))
                .then(|| frame_of(t.map(|v| positions[v as usize])))
                .flatten()
        }));
        let kept_count = all_frames.iter().filter(|f| f.is_some()).count();
        let mut kept = Vec::new();
        let mut frames = Vec::new();
        let mut input_faces = Vec::new();
        let mut dropped = Vec::new();
        try_reserve(&mut kept, kept_count, faces)?;
        try_reserve(&mut frames, kept_count, faces)?;
        try_reserve(&mut input_faces, kept_count, faces)?;
        try_reserve(&mut dropped, input_count - kept_count, || {
            format!("{} degenerate faces", input_count - kept_count)
        })?;
        for (i, (t, frame)) in triangles.into_iter().zip(all_frames).enumerate() {
            let repeated_vertex = repeats(&t);
            match frame {
                Some(frame) => {
                    kept.push(t);
                    frames.push(frame);
                    input_faces.push(i as u32);
                }
                None => dropped.push(DroppedFace {
                    input_index: i,
                    repeated_vertex,
                }),
            }
        }
        if kept.is_empty() {
            return Err(MeshError::NoUsableFace {
                faces: input_count,
                degenerate: dropped.len(),
            });
        }

        Ok(Faces {
            positions,
            kept,
            frames,
            input_faces,
            dropped,
        })
    }

    /// The mesh of these faces with their edge table (see [`TriMesh::with_edge_table`]),
    /// and no line elements.
    fn assemble(
        self,
        face_edges: Vec<[u32; 3]>,
        edge_vertices: Vec<[u32; 2]>,
        spatially_ordered: bool,
    ) -> TriMesh {
        let n = self.positions.len();
        // The three tables at once, on the cores there are.
        let edge_faces = || {
            Csr::from_pairs(
                edge_vertices.len(),
                face_edges
                    .iter()
                    .enumerate()
                    .flat_map(|(f, es)| es.iter().map(move |&e| (e, f as u32))),
            )
        };
        let vertex_faces = || {
            Csr::from_pairs(
                n,
                self.kept
                    .iter()
                    .enumerate()
                    .flat_map(|(f, t)| t.iter().map(move |&v| (v, f as u32))),
            )
        };
        let vertex_edges = || {
            Csr::from_pairs(
                n,
                edge_vertices
                    .iter()
                    .enumerate()
                    .flat_map(|(e, ev)| ev.iter().map(move |&v| (v, e as u32))),
            )
        };
        let (edge_faces, (vertex_faces, vertex_edges)) =
            rayon::join(edge_faces, || rayon::join(vertex_faces, vertex_edges));
        TriMesh {
            positions: self.positions,
            triangles: self.kept,
            frames: self.frames,
            face_edges,
            edge_vertices,
            edge_faces,
            vertex_faces,
            vertex_edges,
            line_edges: Vec::new(),
            vertex_wires: Csr::from_pairs(n, std::iter::empty()),
            input_faces: self.input_faces,
            dropped: self.dropped,
            spatially_ordered,
        }
    }
}

/// Numbers the undirected edges of the faces (sorted by their vertex pair): each face's
/// edges, and each edge's vertices.
/// Whether `face_edges` and `edge_vertices` are the table [`build_edges`] makes for
/// `triangles`: the edges sorted by their vertices (lower first) without repeats, each
/// one some face's, and each face's edge `i` the one from its corner `i` to corner
/// `i + 1`. (The edges a face names are then exactly the sorted set of the faces'
/// edges, which is how `build_edges` numbers them.)
fn edge_table_fits(
    triangles: &[[u32; 3]],
    face_edges: &[[u32; 3]],
    edge_vertices: &[[u32; 2]],
) -> bool {
    if face_edges.len() != triangles.len()
        || !edge_vertices.iter().all(|&[a, b]| a < b)
        || !edge_vertices.windows(2).all(|w| w[0] < w[1])
    {
        return false;
    }
    let mut used = vec![false; edge_vertices.len()];
    for (t, edges) in triangles.iter().zip(face_edges) {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            match edge_vertices.get(edges[i] as usize) {
                Some(&e) if e == [a.min(b), a.max(b)] => used[edges[i] as usize] = true,
                _ => return false,
            }
        }
    }
    used.into_iter().all(|u| u)
}

fn build_edges(triangles: &[[u32; 3]]) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
    let key = |a: u32, b: u32| ((a.min(b) as u64) << 32) | a.max(b) as u64;
    let mut slots: Vec<(u64, u32)> = triangles
        .iter()
        .enumerate()
        .flat_map(|(f, t)| (0..3).map(move |i| (key(t[i], t[(i + 1) % 3]), (f * 3 + i) as u32)))
        .collect();
    // Keys are distinct (the slot is in them), so the parallel sort is deterministic.
    slots.par_sort_unstable();
    let mut face_edges = vec![[0u32; 3]; triangles.len()];
    let mut edge_vertices: Vec<[u32; 2]> = Vec::new();
    let mut last = u64::MAX;
    for &(k, slot) in &slots {
        if k != last {
            edge_vertices.push([(k >> 32) as u32, k as u32]);
            last = k;
        }
        face_edges[slot as usize / 3][slot as usize % 3] = edge_vertices.len() as u32 - 1;
    }
    (face_edges, edge_vertices)
}

/// The connectivity the engine needs, and nothing more: no half-edges, so an edge may
/// have one face (boundary), two (manifold) or any number (non-manifold).
///
/// Face `f` with vertices `[a, b, c]` has edges `[ab, bc, ca]` in that fixed cyclic
/// order: edge `i` joins corner `i` to corner `(i + 1) % 3`. An edge's two vertices are
/// stored lower id first, and Steiner points on it are numbered from that end.
impl TriMesh {
    /// Number of vertices (including unreferenced ones).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }
    /// Number of faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.triangles.len()
    }
    /// Number of edges that belong to at least one face.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.edge_vertices.len()
    }
    /// The vertices of face `f`, in its cyclic order.
    ///
    /// # Panics
    /// If `f` is not a face of the mesh.
    #[inline]
    pub fn face_vertices(&self, f: u32) -> [u32; 3] {
        self.triangles[f as usize]
    }
    /// The edges of face `f`: edge `i` joins corner `i` to corner `(i + 1) % 3`.
    ///
    /// # Panics
    /// If `f` is not a face of the mesh.
    #[inline]
    pub fn face_edges(&self, f: u32) -> [u32; 3] {
        self.face_edges[f as usize]
    }
    /// The two vertices of edge `e`, lower id first.
    ///
    /// # Panics
    /// If `e` is not an edge of the mesh.
    #[inline]
    pub fn edge_vertices(&self, e: u32) -> [u32; 2] {
        self.edge_vertices[e as usize]
    }
    /// The faces around edge `e` (1, 2 or more).
    ///
    /// # Panics
    /// If `e` is not an edge of the mesh.
    #[inline]
    pub fn edge_faces(&self, e: u32) -> &[u32] {
        self.edge_faces.row(e)
    }
    /// The faces around vertex `v` (empty for an unreferenced vertex).
    ///
    /// # Panics
    /// If `v` is not a vertex of the mesh.
    #[inline]
    pub fn vertex_faces(&self, v: u32) -> &[u32] {
        self.vertex_faces.row(v)
    }
    /// The face edges around vertex `v`.
    ///
    /// # Panics
    /// If `v` is not a vertex of the mesh.
    #[inline]
    pub fn vertex_edges(&self, v: u32) -> &[u32] {
        self.vertex_edges.row(v)
    }
}

impl FaceGeometry for TriMesh {
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }
    fn face_count(&self) -> usize {
        self.triangles.len()
    }
    fn face_vertices(&self, face: u32) -> [u32; 3] {
        self.triangles[face as usize]
    }
    fn face_axes(&self, face: u32) -> [[f64; 3]; 2] {
        face_axes(self.triangles[face as usize].map(|v| self.position(v)))
    }
}

/// World-space unit vectors of the u and v axes of the frame of the triangle with
/// corners `p0, p1, p2` ([`FaceFrame::of_triangle`]): u along its first edge, v
/// towards its third corner. For implementors of
/// [`FaceGeometry::face_axes`](geotracks_metrics::FaceGeometry::face_axes).
pub fn face_axes([p0, p1, p2]: [DVec3; 3]) -> [[f64; 3]; 2] {
    // In units of the face's size, so that normalising neither over- nor underflows.
    let (e1, w) = (p1 - p0, p2 - p0);
    let scale = e1.abs().max_element().max(w.abs().max_element());
    let (e1, w) = (e1 / scale, w / scale);
    let u = e1.normalize();
    let v = (w - w.dot(u) * u).normalize();
    [u.to_array(), v.to_array()]
}

#[cfg(test)]
#[path = "trimesh_tests.rs"]
mod tests;
