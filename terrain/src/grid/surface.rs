//! [`GridSurface`]: a grid's cells as a [`Topology`], triangles computed from rows and
//! columns rather than stored, so that a route on a grid builds no mesh.

use super::{ElevationGrid, GridGeometry};
use crate::TerrainError;
use geotracks::mesh::{FaceFrame, InlineIds, Topology, NONE};
use geotracks::metrics::FaceGeometry;
use geotracks::surface::SurfacePoint;
use glam::DVec3;
use rayon::prelude::*;
use std::ops::Range;

/// Samples and cells are numbered tile by tile, as a grid's mesh numbers them (see
/// `TILE` in the mesh module): what a wavefront settles together lies close in memory.
const TILE: usize = 32;

/// The corners of a cell, as bits: north-west, north-east, south-west, south-east.
const NW: u8 = 1;
const NE: u8 = 2;
const SW: u8 = 4;
const SE: u8 = 8;

/// A cell's code: bit 0 (`FIRST`) and bit 1 (`SECOND`) say which of its two triangles
/// the surface has, bit 2 (`SPLIT_NE_SW`) which diagonal splits it.
const FIRST: u8 = 1;
const SECOND: u8 = 2;
const SPLIT_NE_SW: u8 = 4;

/// The edge kinds of a sample, as bits of its edge mask: the edge to the east, the
/// edge to the south, and the diagonal of the cell it is the north-west corner of.
const EAST: u8 = 0;
const SOUTH: u8 = 1;
const DIAGONAL: u8 = 2;

/// The triangles of a cell by its split: corners in cyclic order, counter-clockwise
/// from above (as [`ElevationGrid::cell_triangles`] gives them).
const TRIANGLES: [[[u8; 3]; 2]; 2] = [
    // Split north-west–south-east.
    [[SW, SE, NW], [SE, NE, NW]],
    // Split north-east–south-west.
    [[SW, SE, NE], [SW, NE, NW]],
];

/// Per cell code and corner bits, how many of the cell's faces have those corners and
/// their offsets from its first face: what [`GridSurface::cell_faces_at`] looks up
/// rather than works out at every call.
const FACES_AT: [[(u8, [u8; 2]); 16]; 8] = faces_at();

const fn faces_at() -> [[(u8, [u8; 2]); 16]; 8] {
    let mut table = [[(0u8, [0u8; 2]); 16]; 8];
    let mut code = 0;
    while code < 8 {
        let split = (code & SPLIT_NE_SW as usize != 0) as usize;
        let mut corners = 0;
        while corners < 16 {
            let (mut count, mut offset, mut t) = (0u8, 0u8, 0);
            while t < 2 {
                if code & (1 << t) != 0 {
                    let [a, b, c] = TRIANGLES[split][t];
                    if (a | b | c) & corners as u8 == corners as u8 {
                        table[code][corners].1[count as usize] = offset;
                        count += 1;
                    }
                    offset += 1;
                }
                t += 1;
            }
            table[code][corners].0 = count;
            corners += 1;
        }
        code += 1;
    }
    table
}

/// Per split and triangle, its edges as (columns east, rows south) of their first
/// sample from the cell's north-west one, and kind: edge `i` from corner `i` to
/// `i + 1` (a diagonal belongs to the cell's north-west sample).
const EDGE_KEYS: [[[(usize, usize, u8); 3]; 2]; 2] = edge_keys();

const fn edge_keys() -> [[[(usize, usize, u8); 3]; 2]; 2] {
    let mut table = [[[(0, 0, 0); 3]; 2]; 2];
    let mut split = 0;
    while split < 2 {
        let mut t = 0;
        while t < 2 {
            let mut i = 0;
            while i < 3 {
                let pair = TRIANGLES[split][t][i] | TRIANGLES[split][t][(i + 1) % 3];
                table[split][t][i] = if pair == NW | NE {
                    (0, 0, EAST)
                } else if pair == SW | SE {
                    (0, 1, EAST)
                } else if pair == NW | SW {
                    (0, 0, SOUTH)
                } else if pair == NE | SE {
                    (1, 0, SOUTH)
                } else {
                    (0, 0, DIAGONAL)
                };
                i += 1;
            }
            t += 1;
        }
        split += 1;
    }
    table
}

/// A box of an [`ElevationGrid`]'s cells, split into triangles as
/// [`ElevationGrid::to_mesh`] splits them, as a [`Topology`]: the engines run on it
/// directly, with no [`TriMesh`](geotracks::mesh::TriMesh) and no edge table.
///
/// - **Vertices** are the samples of the box, numbered tile by tile (32 × 32 blocks,
///   the blocks row by row: what a wavefront settles together lies close in memory,
///   and ties between equal values break as on the grid's mesh, so routes are the
///   mesh's to the bit). Per vertex its position and its sample, and per sample its
///   vertex (32 bytes in all). A sample no kept face uses (NODATA, or outside the
///   window) is a vertex of no face, which no run reaches; a NODATA sample sits at
///   elevation 0.
/// - **Faces** are the kept cells' triangles, in the cells' tiled order, two per cell
///   at most (one where a corner is NODATA). What is stored per
///   face is the cell it lies in and its frame (28 bytes: the engines and the path's
///   straightening ask for frames often, and laying a face flat costs a few square
///   roots), and per cell its first face and its split (5 bytes).
/// - **Edges** are numbered by their first sample, with at most three per sample (east,
///   south, and the diagonal of the cell south-east of it): per sample its first edge
///   and which of the three it has (5 bytes), per edge its sample and kind (4 bytes).
///   The faces around an edge, and the faces and edges around a vertex, are computed
///   from the cells around them.
///
/// That is about 110 bytes per cell (two faces, three edges, one sample), counted from
/// the fields; a [`TriMesh`](geotracks::mesh::TriMesh) of the same cells stores about
/// 250 (its triangles, frames, edge table and the lists of faces and edges around
/// every edge and vertex), and its build holds more while it sorts them out.
///
/// ```
/// use geotracks_terrain::{ElevationGrid, GridGeometry, GridSurface};
/// use geotracks::{mesh::Topology, Euclidean, Options, Solver};
/// use geotracks::metrics::FaceGeometry; // face_count
/// let geometry = GridGeometry { ncols: 11, nrows: 11, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
/// let grid = ElevationGrid::from_fn(geometry, |x, y| Some(0.1 * x + 0.2 * y))?;
/// let surface = GridSurface::new(&grid)?;
/// assert_eq!(surface.face_count(), 200);
/// let (from, to) = (surface.locate(1.0, 1.0)?, surface.locate(9.0, 7.0)?);
/// let solver = Solver::with_topology(surface, Euclidean, &Options::DEFAULT)?;
/// let field = solver.field(from)?;
/// // A plane: the straight line (in 3D), to the engine's accuracy.
/// let d = (64.0f64 + 36.0 + (0.8f64 + 1.2).powi(2)).sqrt();
/// assert!((field.distance_at(to)? - d).abs() < 1e-9 * d);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct GridSurface {
    geometry: GridGeometry,
    /// The samples of the box: `cols × rows` from `(col0, row0)`.
    col0: usize,
    row0: usize,
    cols: usize,
    rows: usize,
    /// Per vertex, its position (a NODATA sample at elevation 0).
    positions: Vec<DVec3>,
    /// Per vertex, its sample (row-major in the box), and per sample its vertex.
    vertex_sample: Vec<u32>,
    sample_vertex: Vec<u32>,
    /// Per cell, its code (see `FIRST`): cells are numbered by their north-west sample
    /// (row-major in the box), so that no id is ever divided into a row and a column;
    /// the last column and row of samples have no cell (code 0).
    cell_code: Vec<u8>,
    /// Per cell, its first face.
    cell_face: Vec<u32>,
    /// Per face, its cell times two plus which triangle.
    face_cell: Vec<u32>,
    /// Per face, its frame.
    frames: Vec<FaceFrame>,
    /// Per sample of the box (row-major), its edges: bit `EAST`, `SOUTH`, `DIAGONAL`.
    sample_mask: Vec<u8>,
    /// Per sample of the box (row-major), its first edge.
    sample_edge: Vec<u32>,
    /// Per edge, its sample (row-major in the box) times four plus its kind.
    edge_key: Vec<u32>,
}

impl GridSurface {
    /// The whole grid.
    ///
    /// # Errors
    /// As [`ElevationGrid::to_mesh`]: [`TerrainError::TooSmall`] when no cell has three
    /// valid samples, [`TerrainError::InvalidGrid`] beyond 32-bit ids.
    pub fn new(grid: &ElevationGrid) -> Result<Self, TerrainError> {
        let g = grid.geometry();
        Self::within(
            grid,
            0..g.ncols.saturating_sub(1),
            0..g.nrows.saturating_sub(1),
            |_, _| true,
        )
    }

    /// The cells in columns `cols` and rows `rows` (clipped to the grid) that `keep`
    /// holds: a window of the grid, with the same triangles and positions as the whole
    /// grid's surface (and mesh) there. A small window costs what its box holds.
    ///
    /// # Errors
    /// As [`GridSurface::new`], for the window's cells.
    pub fn within(
        grid: &ElevationGrid,
        cols: Range<usize>,
        rows: Range<usize>,
        keep: impl Fn(usize, usize) -> bool,
    ) -> Result<Self, TerrainError> {
        let g = *grid.geometry();
        let too_small = || TerrainError::TooSmall {
            path: None,
            ncols: g.ncols,
            nrows: g.nrows,
            valid: grid.valid_count(),
        };
        if g.ncols < 2 || g.nrows < 2 {
            return Err(too_small());
        }
        let (last_col, last_row) = (g.ncols - 1, g.nrows - 1);
        let cols = cols.start.min(last_col)..cols.end.min(last_col);
        let rows = rows.start.min(last_row)..rows.end.min(last_row);
        if cols.is_empty() || rows.is_empty() {
            return Err(too_small());
        }
        // The samples of the box: the cells' corners.
        let (samples_wide, samples_high) = (cols.len() + 1, rows.len() + 1);
        if samples_wide * samples_high >= (NONE as usize) / 4 {
            return Err(TerrainError::InvalidGrid {
                message: format!(
                    "{samples_wide} × {samples_high} samples exceed the 32-bit edge ids"
                ),
            });
        }
        let samples = samples_wide * samples_high;
        let vertex_sample: Vec<u32> = tiled(samples_wide, samples_high)
            .map(|(c, r)| (r * samples_wide + c) as u32)
            .collect();
        let mut sample_vertex = vec![0; samples];
        for (v, &s) in vertex_sample.iter().enumerate() {
            sample_vertex[s as usize] = v as u32;
        }
        let positions = tiled(samples_wide, samples_high)
            .map(|(c, r)| {
                let (col, row) = (cols.start + c, rows.start + r);
                let [x, y] = g.position(col, row);
                let z = grid.values()[row * g.ncols + col];
                DVec3::new(x, y, if z.is_nan() { 0.0 } else { z })
            })
            .collect();
        let mut surface = GridSurface {
            geometry: g,
            col0: cols.start,
            row0: rows.start,
            cols: samples_wide,
            rows: samples_high,
            positions,
            vertex_sample,
            sample_vertex,
            cell_code: vec![0; samples],
            cell_face: vec![NONE; samples],
            face_cell: Vec::new(),
            frames: Vec::new(),
            sample_mask: vec![0; samples_wide * samples_high],
            sample_edge: vec![NONE; samples_wide * samples_high],
            edge_key: Vec::new(),
        };
        surface.number_faces(grid, &keep);
        if surface.face_cell.is_empty() {
            return Err(too_small());
        }
        surface.number_edges();
        // A triangle the grid's mesh would drop as flat (elevations so far apart that
        // rounding leaves it no area) is refused here, naming its cell, rather than
        // renumbering the faces around it.
        let frames: Vec<Option<FaceFrame>> = (0..surface.face_cell.len() as u32)
            .into_par_iter()
            .map(|f| surface.computed_frame(f))
            .collect();
        if let Some(f) = frames.iter().position(Option::is_none) {
            let cell = (surface.face_cell[f] / 2) as usize;
            let (col, row) = (
                cols.start + cell % samples_wide,
                rows.start + cell / samples_wide,
            );
            return Err(TerrainError::InvalidGrid {
                message: format!(
                    "the cell at column {col}, row {row} has a triangle too steep to lay flat"
                ),
            });
        }
        surface.frames = frames.into_iter().flatten().collect();
        Ok(surface)
    }

    /// Codes the kept cells and numbers their triangles, tile by tile.
    fn number_faces(&mut self, grid: &ElevationGrid, keep: &impl Fn(usize, usize) -> bool) {
        let ncols = self.geometry.ncols;
        for (c, r) in tiled(self.cols - 1, self.rows - 1) {
            let (col, row) = (self.col0 + c, self.row0 + r);
            if !keep(col, row) {
                continue;
            }
            let [first, second] = grid.cell_triangles(col, row);
            let (ne, sw) = (row * ncols + col + 1, (row + 1) * ncols + col);
            // The north-east–south-west split's first triangle ends at the north-east
            // corner, its second starts at the south-west one.
            let split = if first.is_some_and(|t| t[2] == ne) || second.is_some_and(|t| t[0] == sw) {
                SPLIT_NE_SW
            } else {
                0
            };
            let code =
                split | (u8::from(first.is_some()) * FIRST) | (u8::from(second.is_some()) * SECOND);
            let cell = r * self.cols + c;
            self.cell_code[cell] = code;
            if code & (FIRST | SECOND) != 0 {
                self.cell_face[cell] = self.face_cell.len() as u32;
            }
            for t in 0..2 {
                if code & (1 << t) != 0 {
                    self.face_cell.push(2 * cell as u32 + t);
                }
            }
        }
    }

    /// Marks and numbers the edges the faces use, sample by sample in tiled order.
    fn number_edges(&mut self) {
        for f in 0..self.face_cell.len() as u32 {
            for (s, kind) in self.face_edge_keys(f) {
                self.sample_mask[s] |= 1 << kind;
            }
        }
        for (c, r) in tiled(self.cols, self.rows) {
            let s = r * self.cols + c;
            let mask = self.sample_mask[s];
            if mask != 0 {
                self.sample_edge[s] = self.edge_key.len() as u32;
            }
            for kind in [EAST, SOUTH, DIAGONAL] {
                if mask & (1 << kind) != 0 {
                    self.edge_key.push(4 * s as u32 + kind as u32);
                }
            }
        }
    }

    /// The grid's geometry.
    pub fn geometry(&self) -> &GridGeometry {
        &self.geometry
    }

    /// The sample (row-major in the box) at corner `corner` of cell `cell` (numbered by
    /// its north-west sample).
    #[inline]
    fn corner_sample(&self, cell: usize, corner: u8) -> usize {
        match corner {
            NW => cell,
            NE => cell + 1,
            SW => cell + self.cols,
            _ => cell + self.cols + 1,
        }
    }

    /// The corners of face `f`, as corner bits of its cell, and the cell.
    #[inline]
    fn face_corners(&self, f: u32) -> ([u8; 3], usize) {
        let key = self.face_cell[f as usize];
        let cell = (key / 2) as usize;
        let split = (self.cell_code[cell] & SPLIT_NE_SW != 0) as usize;
        (TRIANGLES[split][(key % 2) as usize], cell)
    }

    /// The edges of face `f` as (sample, kind), edge `i` from corner `i` to `i + 1`.
    #[inline]
    fn face_edge_keys(&self, f: u32) -> [(usize, u8); 3] {
        let key = self.face_cell[f as usize] as usize;
        let cell = key / 2;
        let split = (self.cell_code[cell] & SPLIT_NE_SW != 0) as usize;
        EDGE_KEYS[split][key % 2].map(|(dx, dy, kind)| (cell + dx + dy * self.cols, kind))
    }

    /// The edge id of (sample, kind), which the surface has.
    #[inline]
    fn edge_id(&self, s: usize, kind: u8) -> u32 {
        let below = self.sample_mask[s] & ((1 << kind) - 1);
        self.sample_edge[s] + below.count_ones()
    }

    /// The vertex id of the box sample `s` (row-major).
    #[inline]
    fn vertex_of(&self, s: usize) -> u32 {
        self.sample_vertex[s]
    }

    /// The box sample (row-major) of vertex `v`.
    #[inline]
    fn sample_of(&self, v: u32) -> usize {
        self.vertex_sample[v as usize] as usize
    }

    /// The faces of cell `cell` (its north-west sample; a wrapped-around id, past the
    /// box, is no cell), if it has any: its first face and its code. (A cell to the
    /// west of the first column is a last-column sample, which has no cell: no
    /// bounds check is needed on the columns.)
    #[inline]
    fn cell_at(&self, cell: usize) -> Option<(u32, u8)> {
        let code = *self.cell_code.get(cell)?;
        (code & (FIRST | SECOND) != 0).then(|| (self.cell_face[cell], code))
    }

    /// The kept cell's diagonal, as corner bits.
    #[inline]
    fn diagonal(code: u8) -> u8 {
        if code & SPLIT_NE_SW != 0 {
            NE | SW
        } else {
            NW | SE
        }
    }

    /// The cells around sample `s` (row-major in the box), and which of their corners
    /// it is.
    #[inline]
    fn cells_around(&self, s: usize) -> [(usize, u8); 4] {
        let cols = self.cols;
        [
            (s.wrapping_sub(cols + 1), SE),
            (s.wrapping_sub(cols), SW),
            (s.wrapping_sub(1), NE),
            (s, NW),
        ]
    }

    /// The faces of a cell (`first`, `code`) that have every corner bit of `corners`
    /// (one bit: the faces at that corner; none: all), from [`FACES_AT`].
    #[inline]
    fn cell_faces_at(first: u32, code: u8, corners: u8, out: &mut InlineIds) {
        let (count, offsets) = FACES_AT[code as usize][corners as usize];
        for &offset in &offsets[..count as usize] {
            out.push(first + offset as u32);
        }
    }

    /// The vertex of sample `(col, row)` of the grid, if the sample lies in the box and a
    /// kept face uses it.
    pub fn sample_vertex(&self, col: usize, row: usize) -> Option<u32> {
        let (c, r) = (col.wrapping_sub(self.col0), row.wrapping_sub(self.row0));
        if c >= self.cols || r >= self.rows {
            return None;
        }
        let v = self.sample_vertex[r * self.cols + c];
        (!self.vertex_faces(v).is_empty()).then_some(v)
    }

    /// The faces of kept cell `(col, row)` of the grid: none, one or two.
    pub fn cell_faces(&self, col: usize, row: usize) -> InlineIds {
        let mut out = InlineIds::EMPTY;
        let (c, r) = (col.wrapping_sub(self.col0), row.wrapping_sub(self.row0));
        if c + 1 < self.cols && r + 1 < self.rows {
            if let Some((first, code)) = self.cell_at(r * self.cols + c) {
                Self::cell_faces_at(first, code, 0, &mut out);
            }
        }
        out
    }

    /// The surface point under map point `(x, y)` (in canonical form: a vertex or edge
    /// point when it lies on one), found in O(1) from the cell it falls in, as
    /// [`TerrainMesh::locate`](crate::TerrainMesh::locate) finds it.
    ///
    /// # Errors
    /// [`TerrainError::Outside`] beyond the outermost sample centres,
    /// [`TerrainError::NoData`] where no kept triangle covers the point.
    pub fn locate(&self, x: f64, y: f64) -> Result<SurfacePoint, TerrainError> {
        let (face, bary) = self.covering(x, y)?;
        let point = SurfacePoint::Face { face, bary };
        Ok(point.validated(self).unwrap_or(point))
    }

    /// The face that covers map point `(x, y)` and the point's barycentric coordinates
    /// in it (see [`locate`](Self::locate)).
    pub(crate) fn covering(&self, x: f64, y: f64) -> Result<(u32, [f64; 3]), TerrainError> {
        super::covering(
            &self.geometry,
            x,
            y,
            |c, r| self.cell_faces(c, r),
            |f| self.face_vertices(f).map(|v| Topology::position(self, v)),
        )
    }

    /// Barycentric coordinates of map point `(x, y)` in face `f`, in the map plane.
    pub(crate) fn bary_2d(&self, f: u32, x: f64, y: f64) -> [f64; 3] {
        super::bary_2d(
            self.face_vertices(f).map(|v| Topology::position(self, v)),
            x,
            y,
        )
    }

    /// Per vertex, its sample in the whole grid (row-major from the north).
    pub(crate) fn vertex_grid_samples(&self) -> Vec<usize> {
        (0..self.vertex_count() as u32)
            .map(|v| {
                let s = self.sample_of(v);
                (self.row0 + s / self.cols) * self.geometry.ncols + self.col0 + s % self.cols
            })
            .collect()
    }
}

impl FaceGeometry for GridSurface {
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }
    fn face_count(&self) -> usize {
        self.face_cell.len()
    }
    #[inline]
    fn face_vertices(&self, face: u32) -> [u32; 3] {
        let (corners, cell) = self.face_corners(face);
        corners.map(|c| self.vertex_of(self.corner_sample(cell, c)))
    }
    fn face_axes(&self, face: u32) -> [[f64; 3]; 2] {
        geotracks::mesh::face_axes(
            self.face_vertices(face)
                .map(|v| Topology::position(self, v)),
        )
    }
}

impl Topology for GridSurface {
    type Ids<'a> = InlineIds;

    fn edge_count(&self) -> usize {
        self.edge_key.len()
    }

    #[inline]
    fn face_edges(&self, f: u32) -> [u32; 3] {
        self.face_edge_keys(f)
            .map(|(s, kind)| self.edge_id(s, kind))
    }

    #[inline]
    fn edge_slot(&self, f: u32, e: u32) -> Option<usize> {
        // Compared by sample and kind: no edge id worked out.
        let key = self.edge_key[e as usize];
        let wanted = ((key / 4) as usize, (key % 4) as u8);
        self.face_edge_keys(f).iter().position(|&k| k == wanted)
    }

    #[inline]
    fn edge_vertices(&self, e: u32) -> [u32; 2] {
        let [a, b] = self.edge_samples(e);
        let (a, b) = (self.vertex_of(a), self.vertex_of(b));
        [a.min(b), a.max(b)]
    }

    fn edge_faces(&self, e: u32) -> InlineIds {
        let key = self.edge_key[e as usize];
        let s = (key / 4) as usize;
        let mut out = InlineIds::EMPTY;
        // The cells on either side, and the corners of each the edge joins.
        let sides: [(usize, u8); 2] = match (key % 4) as u8 {
            EAST => [(s.wrapping_sub(self.cols), SW | SE), (s, NW | NE)],
            SOUTH => [(s.wrapping_sub(1), NE | SE), (s, NW | SW)],
            _ => {
                // Both triangles of the cell share its diagonal.
                if let Some((first, code)) = self.cell_at(s) {
                    Self::cell_faces_at(first, code, Self::diagonal(code), &mut out);
                }
                return out;
            }
        };
        for (cell, corners) in sides {
            if let Some((first, code)) = self.cell_at(cell) {
                Self::cell_faces_at(first, code, corners, &mut out);
            }
        }
        out
    }

    fn vertex_faces(&self, v: u32) -> InlineIds {
        let mut out = InlineIds::EMPTY;
        for (cell, corner) in self.cells_around(self.sample_of(v)) {
            if let Some((first, code)) = self.cell_at(cell) {
                Self::cell_faces_at(first, code, corner, &mut out);
            }
        }
        out
    }

    fn vertex_edges(&self, v: u32) -> InlineIds {
        let s = self.sample_of(v);
        let mut out = InlineIds::EMPTY;
        // (A wrapped-around sample is past the box; the west neighbour of the first
        // column is a last-column sample, which has no east edge.)
        let mut add = |t: usize, kind: u8| {
            if self
                .sample_mask
                .get(t)
                .is_some_and(|m| m & (1 << kind) != 0)
            {
                out.push(self.edge_id(t, kind));
            }
        };
        // Its own east and south edges, its west and north neighbours' (the edges
        // that end here).
        add(s, EAST);
        add(s, SOUTH);
        add(s.wrapping_sub(1), EAST);
        add(s.wrapping_sub(self.cols), SOUTH);
        // The diagonals of the four cells around it that touch it.
        for (cell, corner) in self.cells_around(s) {
            if let Some((_, code)) = self.cell_at(cell) {
                if Self::diagonal(code) & corner != 0 {
                    add(cell, DIAGONAL);
                }
            }
        }
        out
    }

    fn vertex_wires(&self, _: u32) -> InlineIds {
        InlineIds::EMPTY
    }

    #[inline]
    fn position(&self, v: u32) -> DVec3 {
        self.positions[v as usize]
    }

    #[inline]
    fn frame(&self, f: u32) -> FaceFrame {
        self.frames[f as usize]
    }

    fn is_spatially_ordered(&self) -> bool {
        true
    }
}

impl GridSurface {
    /// Face `f` laid flat, from its corners' positions; `None` where rounding leaves it
    /// no area.
    fn computed_frame(&self, f: u32) -> Option<FaceFrame> {
        FaceFrame::of_triangle(self.face_vertices(f).map(|v| self.positions[v as usize]))
    }

    /// The two samples (row-major in the box) of edge `e`, in no order.
    #[inline]
    fn edge_samples(&self, e: u32) -> [usize; 2] {
        let key = self.edge_key[e as usize];
        let s = (key / 4) as usize;
        match (key % 4) as u8 {
            EAST => [s, s + 1],
            SOUTH => [s, s + self.cols],
            _ => {
                if self.cell_code[s] & SPLIT_NE_SW != 0 {
                    [s + 1, s + self.cols]
                } else {
                    [s, s + self.cols + 1]
                }
            }
        }
    }
}

/// `(c, r)` over a `wide × high` box in tiled order (see [`TILE`]).
fn tiled(wide: usize, high: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..high.div_ceil(TILE)).flat_map(move |tile_row| {
        (0..wide.div_ceil(TILE)).flat_map(move |tile_col| {
            let rows = tile_row * TILE..((tile_row + 1) * TILE).min(high);
            let cols = tile_col * TILE..((tile_col + 1) * TILE).min(wide);
            rows.flat_map(move |r| cols.clone().map(move |c| (c, r)))
        })
    })
}

#[cfg(test)]
#[path = "surface_tests.rs"]
mod tests;
