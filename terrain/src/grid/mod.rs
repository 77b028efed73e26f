//! [`ElevationGrid`]: samples on a regular grid, and the triangle mesh made from them
//! ([`TerrainMesh`]), which also finds the triangle under any map point in O(1).

mod mesh;
mod surface;

use super::cost::{normal_up, tan2};
use super::TerrainError;
use rayon::prelude::*;
use std::ops::Range;

pub use mesh::TerrainMesh;
pub use surface::GridSurface;

/// A triangulation of a grid's samples that says which vertex a sample is: a
/// [`TerrainMesh`] or a [`GridSurface`]. What a map needs to read per-vertex values
/// per sample ([`map::render`](crate::map::render)).
pub trait SampleVertices {
    /// The vertex of sample `(col, row)`, if it is one.
    fn sample_vertex(&self, col: usize, row: usize) -> Option<u32>;
}

impl SampleVertices for TerrainMesh {
    fn sample_vertex(&self, col: usize, row: usize) -> Option<u32> {
        TerrainMesh::sample_vertex(self, col, row)
    }
}

impl SampleVertices for GridSurface {
    fn sample_vertex(&self, col: usize, row: usize) -> Option<u32> {
        GridSurface::sample_vertex(self, col, row)
    }
}

/// How far beyond the outermost sample centres, in cells, a map point still counts as on
/// the grid (rounding in the caller's coordinates).
const INSIDE: f64 = 1e-9;

/// Where a grid's samples are: how many, where the first one is and how far apart.
///
/// Rows run from north to south (row 0 is the northernmost, as in image files and ESRI
/// ASCII grids), columns from west to east. Positions are *sample centres*, in the
/// grid's own units (those of its coordinate system; elevations should be in the same
/// unit, or slopes mean nothing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridGeometry {
    /// Samples per row (west to east).
    pub ncols: usize,
    /// Rows (north to south).
    pub nrows: usize,
    /// Map position `[x, y]` of the centre of the south-west sample (column 0, last row).
    pub lower_left: [f64; 2],
    /// Distance between neighbouring samples along x (east) and y (north), both > 0.
    pub spacing: [f64; 2],
}

impl GridGeometry {
    /// Map position of the centre of sample `(col, row)`.
    #[inline]
    pub fn position(&self, col: usize, row: usize) -> [f64; 2] {
        [
            self.lower_left[0] + col as f64 * self.spacing[0],
            self.lower_left[1] + (self.nrows - 1 - row) as f64 * self.spacing[1],
        ]
    }

    /// Row-major index of sample `(col, row)`; `None` outside the grid.
    #[inline]
    pub fn sample_index(&self, col: usize, row: usize) -> Option<usize> {
        (col < self.ncols && row < self.nrows).then(|| row * self.ncols + col)
    }

    /// The extent of the sample centres: `[x_min, y_min, x_max, y_max]`.
    pub fn bounds(&self) -> [f64; 4] {
        let [x, y] = self.lower_left;
        [
            x,
            y,
            x + (self.ncols.max(1) - 1) as f64 * self.spacing[0],
            y + (self.nrows.max(1) - 1) as f64 * self.spacing[1],
        ]
    }

    /// Fractional `(column, row)` of map point `(x, y)`: 0 at the first sample centre,
    /// 1 at the next.
    #[inline]
    pub fn to_grid(&self, x: f64, y: f64) -> (f64, f64) {
        let [_, _, _, y_max] = self.bounds();
        (
            (x - self.lower_left[0]) / self.spacing[0],
            (y_max - y) / self.spacing[1],
        )
    }

    /// Map point `(x, y)` in fractional columns and rows ([`to_grid`](Self::to_grid)),
    /// when it lies within the outermost sample centres (to 1e-9 of a
    /// cell).
    ///
    /// # Errors
    /// [`TerrainError::Outside`] beyond them.
    pub fn inside(&self, x: f64, y: f64) -> Result<(f64, f64), TerrainError> {
        let (fc, fr) = self.to_grid(x, y);
        let (last_c, last_r) = ((self.ncols - 1) as f64, (self.nrows - 1) as f64);
        if fc >= -INSIDE && fc <= last_c + INSIDE && fr >= -INSIDE && fr <= last_r + INSIDE {
            return Ok((fc, fr));
        }
        let [x_min, y_min, x_max, y_max] = self.bounds();
        Err(TerrainError::Outside {
            x,
            y,
            x_min,
            x_max,
            y_min,
            y_max,
        })
    }

    fn check(&self, path: Option<&std::path::Path>) -> Result<(), TerrainError> {
        for value in self.spacing {
            if !(value.is_finite() && value > 0.0) {
                return Err(TerrainError::CellSize {
                    path: path.map(|p| p.to_path_buf()),
                    value,
                });
            }
        }
        if !(self.lower_left[0].is_finite() && self.lower_left[1].is_finite()) {
            return Err(TerrainError::InvalidGrid {
                message: format!("the grid's origin {:?} is not finite", self.lower_left),
            });
        }
        Ok(())
    }
}

/// Elevations on a regular grid, with missing samples (NODATA).
///
/// ```
/// use geotracks_terrain::{ElevationGrid, GridGeometry};
/// // 3 × 2 samples 10 m apart; the south-west sample centre at (100, 200).
/// let geometry = GridGeometry { ncols: 3, nrows: 2, lower_left: [100.0, 200.0], spacing: [10.0, 10.0] };
/// let grid = ElevationGrid::new(geometry, vec![
///     5.0, 6.0, f64::NAN, // the northern row (y = 210); NaN: no data
///     4.0, 5.0, 6.0,      // the southern row (y = 200)
/// ])?;
/// assert_eq!(grid.elevation(0, 1), Some(4.0));
/// assert_eq!(grid.elevation(2, 0), None);
/// let terrain = grid.to_mesh()?;
/// assert_eq!(terrain.mesh.face_count(), 3); // two in the full cell, one in the other
/// let p = terrain.locate(105.0, 205.0)?;    // the middle of the first cell
/// assert!((p.position(&terrain.mesh).z - 5.0).abs() < 1e-12);
/// # Ok::<(), geotracks_terrain::TerrainError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ElevationGrid {
    geometry: GridGeometry,
    /// Row-major from the northern row; NaN where missing.
    values: Vec<f64>,
    /// The EPSG code of the coordinate reference system, when the file names one.
    epsg: Option<u32>,
    /// [`mean_edge_length`](Self::mean_edge_length), once asked (a command line and
    /// the router it calls both need it: a pass over every sample).
    mean_edge: Memo<Option<f64>>,
}

/// A value worked out from the rest of its struct on first use, and kept: it adds
/// nothing to what the struct is, so two structs compare equal whatever their memos
/// hold.
#[derive(Clone, Debug, Default)]
struct Memo<T>(std::sync::OnceLock<T>);

impl<T> PartialEq for Memo<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl ElevationGrid {
    /// A grid from its geometry and `ncols × nrows` values, row by row from the northern
    /// row, each row west to east. NaN marks a missing sample (NODATA).
    ///
    /// # Errors
    /// [`TerrainError::InvalidGrid`] if the count is wrong or a value is ±inf;
    /// [`TerrainError::CellSize`] for a spacing that is not finite and > 0.
    pub fn new(geometry: GridGeometry, values: Vec<f64>) -> Result<Self, TerrainError> {
        geometry.check(None)?;
        Self::checked(geometry, values)
    }

    /// As [`ElevationGrid::new`] for a geometry the caller has checked.
    pub(crate) fn checked(geometry: GridGeometry, values: Vec<f64>) -> Result<Self, TerrainError> {
        let expected = geometry.ncols.checked_mul(geometry.nrows);
        if expected != Some(values.len()) {
            return Err(TerrainError::InvalidGrid {
                message: format!(
                    "{} × {} samples need {} values, found {}",
                    geometry.ncols,
                    geometry.nrows,
                    expected.map_or("too many".to_string(), |n| n.to_string()),
                    values.len()
                ),
            });
        }
        if let Some(i) = values.iter().position(|v| v.is_infinite()) {
            return Err(TerrainError::InvalidGrid {
                message: format!(
                    "the sample at row {}, column {} is {}",
                    i / geometry.ncols,
                    i % geometry.ncols,
                    values[i]
                ),
            });
        }
        Ok(ElevationGrid {
            geometry,
            values,
            epsg: None,
            mean_edge: Memo::default(),
        })
    }

    /// A grid whose elevation at each sample centre `(x, y)` is `f(x, y)` (`None`: no
    /// data).
    ///
    /// # Errors
    /// As [`ElevationGrid::new`].
    pub fn from_fn(
        geometry: GridGeometry,
        mut f: impl FnMut(f64, f64) -> Option<f64>,
    ) -> Result<Self, TerrainError> {
        geometry.check(None)?;
        let mut values = Vec::with_capacity(geometry.ncols * geometry.nrows);
        for row in 0..geometry.nrows {
            for col in 0..geometry.ncols {
                let [x, y] = geometry.position(col, row);
                values.push(f(x, y).unwrap_or(f64::NAN));
            }
        }
        Self::checked(geometry, values)
    }

    /// The EPSG code of the grid's coordinate reference system, when its file names
    /// one: a GeoTIFF's `ProjectedCSTypeGeoKey`, or the authority code at the end of
    /// the WKT in an ESRI ASCII grid's `.prj` beside it. `None` when it is unknown.
    pub fn epsg(&self) -> Option<u32> {
        self.epsg
    }

    /// The grid with its coordinate reference system named by EPSG code `code`.
    pub fn with_epsg(mut self, code: Option<u32>) -> Self {
        self.epsg = code;
        self
    }

    /// Where the samples are.
    pub fn geometry(&self) -> &GridGeometry {
        &self.geometry
    }

    /// The elevation at sample `(col, row)` (row 0 the northernmost); `None` where the
    /// sample is missing or out of range.
    #[inline]
    pub fn elevation(&self, col: usize, row: usize) -> Option<f64> {
        let z = self.values[self.geometry.sample_index(col, row)?];
        (!z.is_nan()).then_some(z)
    }

    /// All samples, row by row from the north, NaN where missing.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// How many samples are not missing.
    pub fn valid_count(&self) -> usize {
        self.values.iter().filter(|v| !v.is_nan()).count()
    }

    /// The lowest and highest elevation (`None` if every sample is missing).
    pub fn elevation_range(&self) -> Option<(f64, f64)> {
        self.values
            .iter()
            .filter(|v| !v.is_nan())
            .fold(None, |acc, &z| match acc {
                None => Some((z, z)),
                Some((lo, hi)) => Some((z.min(lo), z.max(hi))),
            })
    }

    /// The triangle mesh of the grid: a vertex at each valid sample centre (`z` the
    /// elevation, positions in the grid's units), two triangles per cell of four valid
    /// samples, and the one triangle three valid samples of a cell make. Cells with
    /// fewer valid samples are left out, so NODATA holes stay holes and islands stay
    /// islands. Triangles are counter-clockwise seen from above.
    ///
    /// A cell is split along the diagonal whose two ends differ less in elevation (the
    /// shorter diagonal in 3D, so the triangles follow ridges and valleys that run along
    /// it instead of cutting across them), the north-west–south-east one on a tie, so
    /// that a flat grid or a plane tilted along an axis is split the same way in every
    /// cell.
    ///
    /// # Errors
    /// [`TerrainError::TooSmall`] when no cell has three valid samples.
    pub fn to_mesh(&self) -> Result<TerrainMesh, TerrainError> {
        self.to_mesh_named(None)
    }

    /// As [`to_mesh`](Self::to_mesh), with errors naming the file the grid came from.
    ///
    /// # Errors
    /// As [`to_mesh`](Self::to_mesh).
    pub fn to_mesh_named(
        &self,
        path: Option<&std::path::Path>,
    ) -> Result<TerrainMesh, TerrainError> {
        self.mesh_cells(path, None)
    }

    /// The mesh of the cells `keep(col, row)` holds only (with their samples as its
    /// vertices): a window of the grid, as [`to_mesh`](Self::to_mesh) meshes those
    /// cells (same triangles, same positions). Cells and samples outside it get no
    /// faces and no vertices ([`TerrainMesh::cell_faces`] and
    /// [`TerrainMesh::sample_vertex`] say none), so [`TerrainMesh::locate`] finds only
    /// points inside it.
    ///
    /// Only cells in columns `cols` and rows `rows` are asked (the ranges are clipped to
    /// the grid), so a small window costs what it holds, not the grid.
    ///
    /// # Errors
    /// [`TerrainError::TooSmall`] when no kept cell has three valid samples.
    pub fn to_mesh_within(
        &self,
        cols: Range<usize>,
        rows: Range<usize>,
        keep: impl Fn(usize, usize) -> bool,
    ) -> Result<TerrainMesh, TerrainError> {
        let g = self.geometry;
        let (last_col, last_row) = (g.ncols.saturating_sub(1), g.nrows.saturating_sub(1));
        let cols = cols.start.min(last_col)..cols.end.min(last_col);
        let rows = rows.start.min(last_row)..rows.end.min(last_row);
        self.mesh_cells(None, Some((cols, rows, &keep)))
    }

    /// The map position and elevation of sample `s` (row-major index from the north).
    pub(crate) fn sample_point(&self, s: usize) -> glam::DVec3 {
        let g = &self.geometry;
        let [x, y] = g.position(s % g.ncols, s / g.ncols);
        glam::DVec3::new(x, y, self.values[s])
    }

    /// The triangles of cell `(col, row)` (the cell whose north-west sample is
    /// `(col, row)`), as sample indices, counter-clockwise from above: two for four
    /// valid samples, split along the diagonal whose ends differ less in elevation (the
    /// north-west–south-east one on a tie), the one that avoids the missing corner for
    /// three, none for fewer.
    pub(crate) fn cell_triangles(&self, col: usize, row: usize) -> [Option<[usize; 3]>; 2] {
        let ncols = self.geometry.ncols;
        let (nw, ne, sw, se) = (
            row * ncols + col,
            row * ncols + col + 1,
            (row + 1) * ncols + col,
            (row + 1) * ncols + col + 1,
        );
        let z = |s: usize| self.values[s];
        let split_nw_se = [[sw, se, nw], [se, ne, nw]];
        let split_ne_sw = [[sw, se, ne], [sw, ne, nw]];
        let missing = |s: usize| z(s).is_nan();
        match [nw, ne, sw, se].iter().filter(|&&s| !missing(s)).count() {
            4 => {
                let along_nw_se = (z(nw) - z(se)).abs();
                let along_ne_sw = (z(ne) - z(sw)).abs();
                if along_ne_sw < along_nw_se {
                    [Some(split_ne_sw[0]), Some(split_ne_sw[1])]
                } else {
                    [Some(split_nw_se[0]), Some(split_nw_se[1])]
                }
            }
            3 if missing(nw) => [Some(split_ne_sw[0]), None],
            3 if missing(se) => [None, Some(split_ne_sw[1])],
            3 if missing(ne) => [Some(split_nw_se[0]), None],
            3 => [None, Some(split_nw_se[1])],
            _ => [None, None],
        }
    }

    /// The mean 3D length of the edges of [`to_mesh`](Self::to_mesh)'s mesh, found from
    /// the samples without meshing: what the interval Steiner scheme's `k` is relative
    /// to on the whole grid, which a window of it ([`to_mesh_within`](Self::to_mesh_within))
    /// must be given to get the same points ([`Options::mean_edge_length`]). `None`
    /// when the grid has no triangle.
    ///
    /// [`Options::mean_edge_length`]: geotracks::Options::mean_edge_length
    pub fn mean_edge_length(&self) -> Option<f64> {
        *self
            .mean_edge
            .0
            .get_or_init(|| self.measure_mean_edge_length())
    }

    /// [`mean_edge_length`](Self::mean_edge_length), worked out.
    fn measure_mean_edge_length(&self) -> Option<f64> {
        let g = self.geometry;
        let (ncols, nrows) = (g.ncols, g.nrows);
        if ncols < 2 || nrows < 2 {
            return None;
        }
        // Per cell, the sides its triangles use (bits: north, south, west, east, the
        // north-west–south-east diagonal, the other one); each edge is then counted
        // once, by the row of its northern (or only) sample.
        const N: u8 = 1;
        const S: u8 = 2;
        const W: u8 = 4;
        const E: u8 = 8;
        const NW_SE: u8 = 16;
        const NE_SW: u8 = 32;
        let sides: Vec<u8> = (0..nrows - 1)
            .into_par_iter()
            .flat_map_iter(|row| {
                (0..ncols - 1).map(move |col| {
                    let mut bits = 0;
                    for t in self.cell_triangles(col, row).into_iter().flatten() {
                        for i in 0..3 {
                            let (a, b) = (t[i], t[(i + 1) % 3]);
                            let (ca, ra) = (a % ncols, a / ncols);
                            let (cb, rb) = (b % ncols, b / ncols);
                            bits |= match (ra == rb, ca == cb) {
                                (true, _) if ra == row => N,
                                (true, _) => S,
                                (_, true) if ca == col => W,
                                (_, true) => E,
                                // A diagonal: north-west–south-east when the northern
                                // end is the western one.
                                _ if (ra < rb) == (ca < cb) => NW_SE,
                                _ => NE_SW,
                            };
                        }
                    }
                    bits
                })
            })
            .collect();
        let cell = |col: usize, row: usize| sides[row * (ncols - 1) + col];
        let point = |col: usize, row: usize| self.sample_point(row * ncols + col);
        // Per row of samples (in order, so that the sum does not depend on threads).
        let rows: Vec<(f64, u64)> = (0..nrows)
            .into_par_iter()
            .map(|row| {
                let (mut sum, mut count) = (0.0, 0);
                let mut add = |a: glam::DVec3, b: glam::DVec3| {
                    sum += a.distance(b);
                    count += 1;
                };
                for col in 0..ncols {
                    let below = row + 1 < nrows;
                    if col + 1 < ncols
                        && ((below && cell(col, row) & N != 0)
                            || (row > 0 && cell(col, row - 1) & S != 0))
                    {
                        add(point(col, row), point(col + 1, row));
                    }
                    if below
                        && ((col + 1 < ncols && cell(col, row) & W != 0)
                            || (col > 0 && cell(col - 1, row) & E != 0))
                    {
                        add(point(col, row), point(col, row + 1));
                    }
                    if below && col + 1 < ncols {
                        if cell(col, row) & NW_SE != 0 {
                            add(point(col, row), point(col + 1, row + 1));
                        }
                        if cell(col, row) & NE_SW != 0 {
                            add(point(col + 1, row), point(col, row + 1));
                        }
                    }
                }
                (sum, count)
            })
            .collect();
        let (sum, count) = rows
            .iter()
            .fold((0.0, 0), |(s, n), &(rs, rn)| (s + rs, n + rn));
        (count > 0).then(|| sum / count as f64)
    }

    /// The steepest slope of any triangle of [`to_mesh`](Self::to_mesh)'s mesh, as a
    /// tangent (rise per unit of run; `inf` for a vertical one), found from the
    /// samples; 0 when the grid has no triangle.
    pub fn steepest_tangent(&self) -> f64 {
        let g = self.geometry;
        if g.ncols < 2 || g.nrows < 2 {
            return 0.0;
        }
        let mut steepest = 0.0f64;
        for row in 0..g.nrows - 1 {
            for col in 0..g.ncols - 1 {
                for t in self.cell_triangles(col, row).into_iter().flatten() {
                    // As `DirectedCost` measures its faces.
                    let [a, b, c] = t.map(|s| self.sample_point(s));
                    steepest = steepest.max(tan2(normal_up(a, b, c)).sqrt());
                }
            }
        }
        steepest
    }
}

/// The face that covers map point `(x, y)` of a grid and the point's barycentric
/// coordinates in it (in the map plane, clamped to the face), for a surface whose
/// kept faces in cell `(col, row)` are `cell_faces(col, row)` and whose face corners
/// are `corners(f)`: the cell the point falls in first, its neighbours for a point on
/// a cell's border whose own cell lacks the covering triangle.
fn covering<I: IntoIterator<Item = u32>>(
    g: &GridGeometry,
    x: f64,
    y: f64,
    cell_faces: impl Fn(usize, usize) -> I,
    corners: impl Fn(u32) -> [glam::DVec3; 3],
) -> Result<(u32, [f64; 3]), TerrainError> {
    let (fc, fr) = g.inside(x, y)?;
    let (last_c, last_r) = ((g.ncols - 1) as f64, (g.nrows - 1) as f64);
    let c0 = (fc.clamp(0.0, last_c).floor() as usize).min(g.ncols - 2);
    let r0 = (fr.clamp(0.0, last_r).floor() as usize).min(g.nrows - 2);
    let neighbours = [
        (0, 0),
        (-1, 0),
        (1, 0),
        (0, -1),
        (0, 1),
        (-1, -1),
        (1, -1),
        (-1, 1),
        (1, 1),
    ];
    for (dc, dr) in neighbours {
        let (c, r) = (c0 as isize + dc, r0 as isize + dr);
        if c < 0 || r < 0 || c as usize + 1 >= g.ncols || r as usize + 1 >= g.nrows {
            continue;
        }
        for f in cell_faces(c as usize, r as usize) {
            let bary = bary_2d(corners(f), x, y);
            if bary.iter().all(|&b| b >= -INSIDE) {
                let clamped = bary.map(|b| b.max(0.0));
                let sum: f64 = clamped.iter().sum();
                return Ok((f, clamped.map(|b| b / sum)));
            }
        }
    }
    Err(TerrainError::NoData { x, y })
}

/// Barycentric coordinates of map point `(x, y)` in the triangle `[a, b, c]`, in the
/// map plane.
fn bary_2d([a, b, c]: [glam::DVec3; 3], x: f64, y: f64) -> [f64; 3] {
    let det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    let l1 = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
    let l2 = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
    [1.0 - l1 - l2, l1, l2]
}
