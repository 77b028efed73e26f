//! The triangle mesh of a grid's cells ([`TerrainMesh`]): its vertices and faces in
//! tiled order, its edge table built without sorting, and the maps between samples,
//! cells and the mesh.

use super::{ElevationGrid, GridGeometry};
use crate::TerrainError;
use geotracks::mesh::{TriMesh, NONE};
use geotracks::surface::SurfacePoint;
use std::ops::Range;

impl ElevationGrid {
    /// The mesh of the kept cells (`None`: all, and every valid sample a vertex).
    #[allow(clippy::type_complexity)] // the window: its cells' ranges and the filter
    pub(super) fn mesh_cells(
        &self,
        path: Option<&std::path::Path>,
        window: Option<(Range<usize>, Range<usize>, &dyn Fn(usize, usize) -> bool)>,
    ) -> Result<TerrainMesh, TerrainError> {
        let g = self.geometry;
        let (ncols, nrows) = (g.ncols, g.nrows);
        let too_small = || TerrainError::TooSmall {
            path: path.map(|p| p.to_path_buf()),
            ncols,
            nrows,
            valid: self.valid_count(),
        };
        if ncols < 2 || nrows < 2 {
            return Err(too_small());
        }
        if ncols * nrows > NONE as usize {
            return Err(TerrainError::InvalidGrid {
                message: format!("{ncols} × {nrows} samples exceed the 32-bit vertex ids"),
            });
        }
        // The cells asked, and the samples at their corners.
        let (cols, rows) = match &window {
            Some((cols, rows, _)) => (cols.clone(), rows.clone()),
            None => (0..ncols - 1, 0..nrows - 1),
        };
        let keep = window.as_ref().map(|w| w.2);
        // The maps from samples and cells to the mesh cover the window's box only: a
        // small window of a large grid is meshed in time for its size.
        let cell_box = GridBox {
            col0: cols.start,
            row0: rows.start,
            cols: cols.len(),
            rows: rows.len(),
        };
        let samples = cell_box.corners();
        let (sample_vertex, vertex_sample, positions) =
            self.window_vertices(cols.clone(), rows.clone(), samples, keep);
        let (triangles, mut cell_faces) =
            self.window_faces(cols, rows, cell_box, samples, keep, &sample_vertex);
        if triangles.is_empty() {
            return Err(too_small());
        }
        let input_faces = triangles.len();
        let (face_edges, edge_vertices) =
            grid_edges(samples.cols, &sample_vertex, &vertex_sample, &triangles);
        let mesh = TriMesh::with_edge_table(positions, triangles, face_edges, edge_vertices, true)?;
        if mesh.face_count() != input_faces {
            // Not expected (grid cells have area), but a dropped face renumbers the rest.
            let mut kept = vec![NONE; input_faces];
            for f in 0..mesh.face_count() as u32 {
                kept[mesh.input_face(f)] = f;
            }
            for pair in &mut cell_faces {
                for f in pair.iter_mut().filter(|f| **f != NONE) {
                    *f = kept[*f as usize];
                }
            }
        }
        Ok(TerrainMesh {
            mesh,
            geometry: g,
            sample_vertex,
            cells: cell_box,
            cell_faces,
        })
    }

    /// The vertices of a window's mesh (cells in `cols` × `rows` that `keep` holds, all
    /// for `None`), whose corner samples are the box `samples`: per sample of the box
    /// its vertex or `NONE`, per vertex its sample (in the box), and the positions.
    fn window_vertices(
        &self,
        cols: Range<usize>,
        rows: Range<usize>,
        samples: GridBox,
        keep: Option<&dyn Fn(usize, usize) -> bool>,
    ) -> (Vec<u32>, Vec<u32>, Vec<[f64; 3]>) {
        let g = self.geometry;
        let ncols = g.ncols;
        let sample_range = (cols.start..cols.end + 1, rows.start..rows.end + 1);
        // The samples that become vertices: every valid one for the whole grid, the
        // corners of the kept cells' triangles for a window.
        let used = keep.map(|keep| {
            let mut used = vec![false; samples.len()];
            for (col, row) in tiled(cols.clone(), rows.clone()).filter(|&(c, r)| keep(c, r)) {
                for t in self.cell_triangles(col, row).into_iter().flatten() {
                    for s in t {
                        used[samples.of_cell_corner(s, row, ncols)] = true;
                    }
                }
            }
            used
        });
        let mut sample_vertex = vec![NONE; samples.len()];
        let mut vertex_sample = Vec::new();
        let mut positions = Vec::new();
        for (col, row) in tiled(sample_range.0, sample_range.1) {
            let z = self.values[row * ncols + col];
            let i = samples.offset(col, row);
            if !z.is_nan() && used.as_ref().is_none_or(|u| u[i]) {
                sample_vertex[i] = positions.len() as u32;
                vertex_sample.push(i as u32);
                let [x, y] = g.position(col, row);
                positions.push([x, y, z]);
            }
        }
        (sample_vertex, vertex_sample, positions)
    }

    /// The triangles of a window's mesh (cells in `cols` × `rows`, the box `cell_box`,
    /// that `keep` holds, all for `None`), on the vertices `sample_vertex` gives the
    /// box `samples`, and per cell of the box its faces or `NONE`.
    fn window_faces(
        &self,
        cols: Range<usize>,
        rows: Range<usize>,
        cell_box: GridBox,
        samples: GridBox,
        keep: Option<&dyn Fn(usize, usize) -> bool>,
        sample_vertex: &[u32],
    ) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
        let ncols = self.geometry.ncols;
        let mut cell_faces = vec![[NONE; 2]; cell_box.len()];
        let mut triangles = Vec::with_capacity(if keep.is_none() {
            cell_box.len() * 2
        } else {
            0
        });
        for (col, row) in tiled(cols, rows) {
            if keep.is_some_and(|keep| !keep(col, row)) {
                continue;
            }
            let cell = cell_box.offset(col, row);
            for (k, t) in self.cell_triangles(col, row).into_iter().enumerate() {
                if let Some(t) = t {
                    cell_faces[cell][k] = triangles.len() as u32;
                    triangles.push(t.map(|s| sample_vertex[samples.of_cell_corner(s, row, ncols)]));
                }
            }
        }
        (triangles, cell_faces)
    }
}

/// Samples and cells are numbered tile by tile (`TILE` × `TILE` blocks, the blocks row
/// by row, and row by row inside each), so that what a wavefront settles together lies
/// close in memory (row by row, the sample below is a whole grid row away), with no
/// sort (a Morton order along a curve needs one). The guide's Terrain page has the timings of
/// the three orders that chose it.
const TILE: usize = 32;

/// `(col, row)` over columns `cols` and rows `rows` in tiled order (see [`TILE`]; tiles
/// start at the ranges' starts).
fn tiled(cols: Range<usize>, rows: Range<usize>) -> impl Iterator<Item = (usize, usize)> {
    let (c0, r0) = (cols.start, rows.start);
    let (ncols, nrows) = (cols.len(), rows.len());
    (0..nrows.div_ceil(TILE)).flat_map(move |tile_row| {
        (0..ncols.div_ceil(TILE)).flat_map(move |tile_col| {
            let rows = r0 + tile_row * TILE..r0 + ((tile_row + 1) * TILE).min(nrows);
            let cols = c0 + tile_col * TILE..c0 + ((tile_col + 1) * TILE).min(ncols);
            rows.flat_map(move |row| cols.clone().map(move |col| (col, row)))
        })
    })
}

/// The edge table of a grid's faces, numbered as [`TriMesh::new`] numbers edges (by
/// lower vertex, then higher) without sorting them: each face edge joins two
/// neighbouring samples, so it is one of eight directions at its lower vertex; a table
/// of eight slots per vertex marks the edges used, and numbering a vertex's edges only
/// orders its (at most eight) higher neighbours. Samples are numbered row-major in a
/// box `ncols` wide.
fn grid_edges(
    ncols: usize,
    sample_vertex: &[u32],
    vertex_sample: &[u32],
    triangles: &[[u32; 3]],
) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
    // The neighbour in direction `d` (0..8: columns −1, 0, 1 by rows −1, 0, 1, the
    // sample itself left out) of sample `s`, as an offset in samples.
    let offset = |d: usize| -> isize {
        let d = if d >= 4 { d + 1 } else { d };
        (d / 3) as isize * ncols as isize - ncols as isize + (d % 3) as isize - 1
    };
    let slot = |a: u32, b: u32| -> usize {
        let (lo, hi) = (a.min(b), a.max(b));
        let (s, t) = (
            vertex_sample[lo as usize] as isize,
            vertex_sample[hi as usize] as isize,
        );
        // The rows and columns apart (each −1, 0 or 1), as `offset` numbers them.
        let delta = t - s;
        let rows = if delta > 1 {
            1
        } else if delta < -1 {
            -1
        } else {
            0
        };
        let cols = delta - rows * ncols as isize;
        let d = ((rows + 1) * 3 + cols + 1) as usize;
        let direction = d - (d > 4) as usize;
        debug_assert!(cols.abs() <= 1 && d != 4 && s + offset(direction) == t);
        8 * lo as usize + direction
    };
    let mut edge_of = vec![NONE; 8 * vertex_sample.len()];
    for t in triangles {
        for i in 0..3 {
            edge_of[slot(t[i], t[(i + 1) % 3])] = 0;
        }
    }
    let mut edge_vertices = Vec::new();
    for (v, &s) in vertex_sample.iter().enumerate() {
        let mut higher = [(NONE, 0); 8];
        let mut count = 0;
        for d in (0..8).filter(|&d| edge_of[8 * v + d] != NONE) {
            higher[count] = (sample_vertex[(s as isize + offset(d)) as usize], d);
            count += 1;
        }
        higher[..count].sort_unstable();
        for &(w, d) in &higher[..count] {
            edge_of[8 * v + d] = edge_vertices.len() as u32;
            edge_vertices.push([v as u32, w]);
        }
    }
    let face_edges = triangles
        .iter()
        .map(|t| std::array::from_fn(|i| edge_of[slot(t[i], t[(i + 1) % 3])]))
        .collect();
    (face_edges, edge_vertices)
}

/// The triangle mesh of an [`ElevationGrid`] ([`ElevationGrid::to_mesh`]), with the
/// maps between samples, cells and the mesh.
#[derive(Clone, Debug)]
pub struct TerrainMesh {
    /// The mesh: vertices at valid sample centres, in the grid's units.
    pub mesh: TriMesh,
    geometry: GridGeometry,
    /// Per sample of the cells' box's corners ([`GridBox::corners`], row-major from the
    /// north), its vertex or `NONE`.
    sample_vertex: Vec<u32>,
    /// The box of cells `cell_faces` covers (the meshed cells).
    cells: GridBox,
    /// Per cell of the box (row-major from the north), its faces or `NONE`.
    cell_faces: Vec<[u32; 2]>,
}

/// A box of a grid's samples or cells: `cols × rows` of them from `(col0, row0)`,
/// numbered row-major.
#[derive(Clone, Copy, Debug)]
struct GridBox {
    col0: usize,
    row0: usize,
    cols: usize,
    rows: usize,
}

impl GridBox {
    fn len(&self) -> usize {
        self.cols * self.rows
    }

    /// The number of `(col, row)` in the box, if it lies in it.
    #[inline]
    fn index(&self, col: usize, row: usize) -> Option<usize> {
        let (c, r) = (col.checked_sub(self.col0)?, row.checked_sub(self.row0)?);
        (c < self.cols && r < self.rows).then_some(r * self.cols + c)
    }

    /// The number of `(col, row)`, which lies in the box.
    #[inline]
    fn offset(&self, col: usize, row: usize) -> usize {
        (row - self.row0) * self.cols + (col - self.col0)
    }

    /// Sample `s` (a grid index, of a cell in row `row`: no division) in the box, for a
    /// grid `ncols` samples wide.
    #[inline]
    fn of_cell_corner(&self, s: usize, row: usize, ncols: usize) -> usize {
        let r = if s >= (row + 1) * ncols { row + 1 } else { row };
        self.offset(s - r * ncols, r)
    }

    /// The box of the samples at the corners of these cells.
    fn corners(&self) -> GridBox {
        GridBox {
            cols: self.cols + 1,
            rows: self.rows + 1,
            ..*self
        }
    }
}

impl TerrainMesh {
    /// The grid's geometry.
    pub fn geometry(&self) -> &GridGeometry {
        &self.geometry
    }

    /// Per vertex, its sample (row-major index from the north).
    pub(crate) fn vertex_samples(&self) -> Vec<usize> {
        let (b, ncols) = (self.cells.corners(), self.geometry.ncols);
        let mut samples = vec![0; self.mesh.vertex_count()];
        for (i, &v) in self.sample_vertex.iter().enumerate() {
            if v != NONE {
                samples[v as usize] = (b.row0 + i / b.cols) * ncols + b.col0 + i % b.cols;
            }
        }
        samples
    }

    /// The vertex of sample `(col, row)`, if the sample is valid.
    #[inline]
    pub fn sample_vertex(&self, col: usize, row: usize) -> Option<u32> {
        // (The box lies in the grid: a sample outside it has no vertex.)
        let v = self.sample_vertex[self.cells.corners().index(col, row)?];
        (v != NONE).then_some(v)
    }

    /// The faces of cell `(col, row)` (the cell whose north-west sample is `(col, row)`):
    /// none, one or two.
    pub fn cell_faces(&self, col: usize, row: usize) -> impl Iterator<Item = u32> + '_ {
        let pair = self
            .cells
            .index(col, row)
            .map_or([NONE; 2], |i| self.cell_faces[i]);
        pair.into_iter().filter(|&f| f != NONE)
    }

    /// The surface point under map point `(x, y)`: the point of the triangle that covers
    /// it (in canonical form: a vertex or edge point when it lies on one), found in O(1)
    /// from the cell the point falls in.
    ///
    /// # Errors
    /// [`TerrainError::Outside`] beyond the outermost sample centres (to a relative
    /// 1e-9 of a cell), [`TerrainError::NoData`] where no triangle covers the point.
    pub fn locate(&self, x: f64, y: f64) -> Result<SurfacePoint, TerrainError> {
        let (face, bary) = self.covering(x, y)?;
        let point = SurfacePoint::Face { face, bary };
        Ok(point.validated(&self.mesh).unwrap_or(point))
    }

    /// The face that covers map point `(x, y)` and the point's barycentric coordinates
    /// in it (in the map plane, clamped to the face), as [`locate`](Self::locate).
    pub(crate) fn covering(&self, x: f64, y: f64) -> Result<(u32, [f64; 3]), TerrainError> {
        super::covering(
            &self.geometry,
            x,
            y,
            |c, r| self.cell_faces(c, r),
            |f| self.mesh.face_vertices(f).map(|v| self.mesh.position(v)),
        )
    }
}
