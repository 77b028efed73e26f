//! # geotracks-terrain
//!
//! Terrain for [`geotracks`]: elevation grids (ESRI ASCII, GeoTIFF) turned into meshes,
//! terrain costs as metrics, the cheapest routes between map points, and maps.
//!
//! ## How it layers
//! An application of the core crate, beside its skeletons: it builds
//! [`TriMesh`](geotracks::mesh::TriMesh)es, grid surfaces and [`Metric`](geotracks::Metric)s, and
//! routes with the core's [`Solver`](geotracks::Solver) as any caller would; the core
//! knows nothing of it. Its error is [`TerrainError`], which wraps the engine's
//! ([`TerrainError::Engine`]).
//!
//! Maps ([`map`]) depend on the picture crate, `geotracks-render`, always: their labels
//! use its bitmap font (a map's scale bar reads as a picture's colour bar does) and
//! their PNGs its encoder, so both stay written once. Maps are part of what a route is
//! for (the command line draws them), so they are not behind a feature of their own:
//! without `png` the picture crate brings no image codec, only its rasterizer and
//! nalgebra (for its automatic camera). This crate's `png` feature (on by default)
//! turns on the picture crate's.
//!
//! - [`read_grid`] (by extension), [`read_asc`], [`read_geotiff`]: an
//!   [`ElevationGrid`] of sample centres in the grid's own units, NODATA kept as holes.
//! - [`ElevationGrid::to_mesh`]: a [`TerrainMesh`], two triangles per cell, which also
//!   finds the surface point under a map point ([`TerrainMesh::locate`]).
//! - [`GridSurface`]: the same triangles as a [`Topology`](geotracks::mesh::Topology)
//!   computed from rows and columns, which the engines run on with no mesh built
//!   ([`Solver::with_topology`](geotracks::Solver::with_topology)); routes use it.
//! - Costs ([`cost`]): [`slope_density`] (`ρ = 1 + a·tan²(slope)`), [`Impassable`]
//!   (walls: faces no route crosses), [`incline_tensor`] (crossing the slope costs more
//!   than following a contour, either way), and the directed costs of [`DirectedCost`]
//!   (climbing dearer than descending: `uphill`, Naismith's rule and GRASS r.walk's
//!   walking time, Tobler's hiking function); [`TerrainCost`] names them as the
//!   command line does, and [`TerrainCost::metric`] builds it ([`TerrainMetric`], one
//!   type for all of them).
//! - [`route`]: the cheapest route between two points, start first, with its
//!   cumulative cost.
//! - [`map`]: a hillshaded picture of the grid with cost contours and a route.
//!
//! ```
//! use geotracks_terrain::{ElevationGrid, GridGeometry, slope_density};
//! use geotracks::{Options, Solver, Sources, Stop};
//!
//! // A 21 × 21 grid, 1 m apart, on a plane rising 0.5 m per metre eastwards.
//! let geometry = GridGeometry { ncols: 21, nrows: 21, lower_left: [0.0, 0.0], spacing: [1.0, 1.0] };
//! let grid = ElevationGrid::from_fn(geometry, |x, _| Some(0.5 * x))?;
//! let terrain = grid.to_mesh()?;
//! let (from, to) = (terrain.locate(2.0, 10.0)?, terrain.locate(18.0, 10.0)?);
//! let density = slope_density(&terrain.mesh, 4.0)?; // ρ = 1 + 4 · 0.5² = 2
//! let solver = Solver::new(&terrain.mesh, &density, &Options::DEFAULT.with_k(2.0))?;
//! // One run that stops once the value at `to` is final, then the path from there.
//! let field = solver.field(Sources::from(from).until(Stop::NONE.with_targets(vec![to])))?;
//! let route = field.path(to)?;
//! let expected = 2.0 * 16.0 * 1.25f64.sqrt(); // ρ × the 3D length
//! assert!((route.length - expected).abs() < 1e-6 * expected);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![forbid(unsafe_code)]

mod asc;
pub mod cost;
mod directed;
mod error;
mod geotiff;
mod grid;
pub mod map;
mod route;

pub use asc::{read_asc, read_asc_bytes};
pub use cost::{
    face_slopes, incline_tensor, slope_density, steeper_than, vertex_slope_tan2, Impassable,
    TerrainCost, TerrainMetric,
};
pub use directed::{DirectedCost, DirectedModel};
pub use error::TerrainError;
pub use geotiff::{read_geotiff, read_geotiff_bytes};
pub use grid::{ElevationGrid, GridGeometry, GridSurface, SampleVertices, TerrainMesh};
pub use route::{
    map_path_cost, route, route_and_field, route_on_grid, GridRoute, Route, RouteWindow,
};

use std::path::Path;

/// Reads an elevation grid by its extension (any case): `.asc` (ESRI ASCII grid) or
/// `.tif`/`.tiff` (single-band GeoTIFF).
///
/// # Errors
/// [`TerrainError::IsDirectory`], [`TerrainError::NotAFile`],
/// [`TerrainError::UnknownFormat`] for another extension,
/// or what the reader returns.
pub fn read_grid(path: impl AsRef<Path>) -> Result<ElevationGrid, TerrainError> {
    let path = path.as_ref();
    refuse_non_file(path)?;
    match geotracks::mesh::io::lowercase_extension(path).as_deref() {
        Some("asc") => read_asc(path),
        Some("tif" | "tiff") => read_geotiff(path),
        _ => Err(TerrainError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// [`TerrainError::IsDirectory`] for a directory, [`TerrainError::NotAFile`] for a named
/// pipe, a socket or a device (refused before it is opened: opening a FIFO blocks until
/// a writer comes). A path that cannot be looked at passes: the reader reports it.
fn refuse_non_file(path: &Path) -> Result<(), TerrainError> {
    match geotracks::mesh::io::not_a_file(path) {
        Ok(None) => Ok(()),
        Ok(Some("a directory")) => Err(TerrainError::IsDirectory {
            path: path.to_path_buf(),
        }),
        Ok(Some(kind)) => Err(TerrainError::NotAFile {
            path: path.to_path_buf(),
            kind,
        }),
        // A path that cannot be looked at (missing, say) is the reader's to report,
        // after the extension.
        Err(_) => Ok(()),
    }
}

/// Reads a grid and meshes it; errors name the file.
///
/// # Errors
/// As [`read_grid`] and [`ElevationGrid::to_mesh`].
pub fn read_terrain(path: impl AsRef<Path>) -> Result<(ElevationGrid, TerrainMesh), TerrainError> {
    let path = path.as_ref();
    let grid = read_grid(path)?;
    let mesh = grid.to_mesh_named(Some(path))?;
    Ok((grid, mesh))
}

/// The README's code blocks, compiled and run as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The guide's Terrain page (`docs/src/terrain.md`): its code blocks, compiled and run as
/// doctests here, where the terrain crate is in reach.
#[cfg(doctest)]
#[doc = include_str!("../../docs/src/terrain.md")]
struct GuideTerrainDoctests;
