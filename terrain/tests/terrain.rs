//! Terrain: grid readers, meshing, costs, walls in every engine, and the analytic
//! checks (flat grid, tilted plane, Snell's law at a density interface, a wall with a
//! gap). Measured errors are printed (`cargo test --release --test terrain --
//! --nocapture`); the guide's Terrain page quotes them.

#[path = "../../tests/common/mod.rs"]
mod common;

use common::{random_mesh, Rng, DIJKSTRA, GRAPH, TRACKS};
use geotracks::glam::DVec3;
use geotracks::mesh::TriMesh;
use geotracks::Sources;
use geotracks::{
    Density, Error, Euclidean, GeodesicPath, Method, Metric, Options, Solver, Source, Stop, Tensor,
};
use geotracks_terrain::{
    incline_tensor, read_asc, read_geotiff, read_grid, slope_density, steeper_than, DirectedCost,
    DirectedModel, ElevationGrid, GridGeometry, Impassable, TerrainCost, TerrainError, TerrainMesh,
};
use proptest::prelude::*;
use std::path::Path;

fn geometry(ncols: usize, nrows: usize, lower_left: [f64; 2], spacing: f64) -> GridGeometry {
    GridGeometry {
        ncols,
        nrows,
        lower_left,
        spacing: [spacing, spacing],
    }
}

/// The straightened route between two map points, and the field's stats.
fn route<M: Metric>(
    terrain: &TerrainMesh,
    metric: &M,
    options: &Options,
    from: [f64; 2],
    to: [f64; 2],
) -> Result<GeodesicPath, Error> {
    let from = terrain.locate(from[0], from[1]).unwrap();
    let to = terrain.locate(to[0], to[1]).unwrap();
    Ok(Solver::new(&terrain.mesh, metric, options)?
        .shortest_path(&[Source::new(from)], to)?
        .0)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

// ---------------------------------------------------------------------------------
// Readers and meshing

fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn asc_corner_and_centre_origins_place_samples() {
    let dir = tempfile::tempdir().unwrap();
    let corner = write(
        dir.path(),
        "c.asc",
        "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 10\n1 2 3\n4 5 6\n",
    );
    let grid = read_asc(&corner).unwrap();
    assert_eq!(grid.geometry().lower_left, [105.0, 205.0]);
    assert_eq!(grid.geometry().position(0, 0), [105.0, 215.0]);
    assert_eq!(
        grid.elevation(0, 0),
        Some(1.0),
        "the first row is the northern one"
    );
    let terrain = grid.to_mesh().unwrap();
    // Sample (0, 0) is at the north-west: vertex 0 has z = 1 there.
    assert_eq!(terrain.mesh.position(0).to_array(), [105.0, 215.0, 1.0]);
    let p = terrain.locate(105.0, 205.0).unwrap();
    assert!((p.position(&terrain.mesh).z - 4.0).abs() < 1e-12);

    let centre = write(
        dir.path(),
        "m.asc",
        "NCOLS 3\nNRows 2\nyllcenter 200\nXLLCENTER 100\nNODATA_VALUE -1\ncellsize 10\n1 2 3\n4 5 6\n",
    );
    let grid = read_grid(&centre).unwrap();
    assert_eq!(grid.geometry().lower_left, [100.0, 200.0]);
    assert_eq!(grid.geometry().bounds(), [100.0, 200.0, 120.0, 210.0]);
}

#[test]
fn nodata_holes_and_islands_are_kept() {
    // 7 × 7 samples: a NODATA ring around an island in the middle.
    let g = geometry(7, 7, [0.0, 0.0], 1.0);
    let grid = ElevationGrid::from_fn(g, |x, y| {
        let r = (x - 3.0).abs().max((y - 3.0).abs());
        (r != 2.0).then_some(x + y)
    })
    .unwrap();
    let terrain = grid.to_mesh().unwrap();
    let mesh = &terrain.mesh;
    let (labels, components) = mesh.vertex_components();
    // The island (3 × 3 samples), the outer ring, and no faces in the NODATA ring.
    let centre = terrain.sample_vertex(3, 3).unwrap();
    let corner = terrain.sample_vertex(0, 0).unwrap();
    assert_ne!(labels[centre as usize], labels[corner as usize]);
    assert!(components >= 2);
    assert_eq!(grid.valid_count(), 49 - 16);
    // The island: 2 × 2 cells → 8 faces; the outer ring of cells: 24 cells, of which
    // only those with ≥ 3 valid samples make faces.
    let island: usize = (2..4)
        .flat_map(|r| (2..4).map(move |c| (c, r)))
        .map(|(c, r)| terrain.cell_faces(c, r).count())
        .sum();
    assert_eq!(island, 8);
    // A point in the hole is on NODATA; a point beyond the grid is outside.
    assert!(matches!(
        terrain.locate(1.5, 1.5),
        Err(TerrainError::NoData { .. })
    ));
    assert!(matches!(
        terrain.locate(-0.5, 1.0),
        Err(TerrainError::Outside { .. })
    ));
    // Every face lies on valid samples and is counter-clockwise from above.
    for f in 0..mesh.face_count() as u32 {
        let [a, b, c] = mesh.face_vertices(f).map(|v| mesh.position(v));
        assert!((b - a).cross(c - a).z > 0.0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A grid's mesh numbers its edges without sorting them (its own table, row by
    /// row): the same table as the general mesh builder's, with NODATA holes, ragged
    /// borders and single-triangle cells.
    #[test]
    fn a_grids_edge_table_is_the_general_builders(seed in any::<u64>(), ncols in 2usize..9, nrows in 2usize..9, holes in 0.0f64..0.4) {
        let mut rng = Rng(seed | 1);
        let values: Vec<Option<f64>> = (0..ncols * nrows)
            .map(|_| (rng.next() >= holes).then(|| 3.0 * rng.next()))
            .collect();
        let g = geometry(ncols, nrows, [0.0, 0.0], 1.0);
        let grid = ElevationGrid::from_fn(g, |x, y| values[(nrows - 1 - y as usize) * ncols + x as usize]).unwrap();
        let Ok(terrain) = grid.to_mesh() else {
            return Ok(());
        };
        let mesh = &terrain.mesh;
        let positions = mesh.positions().iter().map(|p| p.to_array()).collect();
        let general = TriMesh::new(positions, mesh.triangles().to_vec()).unwrap();
        prop_assert_eq!(mesh.edge_count(), general.edge_count());
        for e in 0..mesh.edge_count() as u32 {
            prop_assert_eq!(mesh.edge_vertices(e), general.edge_vertices(e));
            prop_assert_eq!(mesh.edge_faces(e), general.edge_faces(e));
        }
        for f in 0..mesh.face_count() as u32 {
            prop_assert_eq!(mesh.face_edges(f), general.face_edges(f));
        }
        for v in 0..mesh.vertex_count() as u32 {
            prop_assert_eq!(mesh.vertex_edges(v), general.vertex_edges(v));
            prop_assert_eq!(mesh.vertex_faces(v), general.vertex_faces(v));
        }
    }
}

#[test]
fn three_valid_samples_make_one_triangle_and_locate_finds_it() {
    let g = geometry(2, 2, [0.0, 0.0], 2.0);
    // The north-east sample is missing.
    let grid = ElevationGrid::new(g, vec![1.0, f64::NAN, 3.0, 4.0]).unwrap();
    let terrain = grid.to_mesh().unwrap();
    assert_eq!(terrain.mesh.face_count(), 1);
    let p = terrain.locate(0.5, 0.5).unwrap();
    assert!((p.position(&terrain.mesh) - DVec3::new(0.5, 0.5, 2.75)).length() < 1e-12);
    assert!(matches!(
        terrain.locate(1.5, 1.5),
        Err(TerrainError::NoData { .. })
    ));
    // Corners and edges come back in canonical form.
    let v = terrain.locate(0.0, 0.0).unwrap();
    assert_eq!(
        v,
        geotracks::SurfacePoint::Vertex(terrain.sample_vertex(0, 1).unwrap())
    );
}

#[test]
fn the_diagonal_follows_the_smaller_elevation_difference() {
    let g = geometry(2, 2, [0.0, 0.0], 1.0);
    // nw = 5, ne = 0, sw = 2, se = 4: a ridge from north-west to south-east.
    let grid = ElevationGrid::new(g, vec![5.0, 0.0, 2.0, 4.0]).unwrap();
    let mesh = grid.to_mesh().unwrap().mesh;
    let ridge = [0u32, 3];
    assert!(mesh
        .triangles()
        .iter()
        .all(|t| ridge.iter().all(|v| t.contains(v))));
    let grid = ElevationGrid::new(g, vec![0.0, 5.0, 4.0, 2.0]).unwrap();
    let mesh = grid.to_mesh().unwrap().mesh;
    let ridge = [1u32, 2];
    assert!(mesh
        .triangles()
        .iter()
        .all(|t| ridge.iter().all(|v| t.contains(v))));
}

#[test]
fn grids_without_a_triangle_are_refused() {
    let e = ElevationGrid::new(geometry(1, 3, [0.0, 0.0], 1.0), vec![1.0, 2.0, 3.0])
        .unwrap()
        .to_mesh()
        .unwrap_err();
    assert!(matches!(e, TerrainError::TooSmall { .. }), "{e}");
    let nan = f64::NAN;
    let e = ElevationGrid::new(
        geometry(3, 2, [0.0, 0.0], 1.0),
        vec![1.0, nan, 1.0, nan, 1.0, nan],
    )
    .unwrap()
    .to_mesh()
    .unwrap_err();
    assert!(e.to_string().contains("3 of them valid"), "{e}");
    assert!(ElevationGrid::new(geometry(2, 2, [0.0, 0.0], 1.0), vec![1.0; 3]).is_err());
    assert!(ElevationGrid::new(geometry(2, 2, [0.0, 0.0], -1.0), vec![1.0; 4]).is_err());
    assert!(ElevationGrid::new(
        geometry(2, 2, [0.0, 0.0], 1.0),
        vec![1.0, f64::INFINITY, 1.0, 1.0]
    )
    .is_err());
}

#[test]
fn asc_errors_name_the_file_and_place() {
    let dir = tempfile::tempdir().unwrap();
    let head = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    let cases = [
        (
            "nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
            "no 'ncols'",
        ),
        (
            "ncols 3\nnrows 2\nxllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
            "no 'yllcorner'",
        ),
        (
            "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3\n4 5 6\n",
            "no 'cellsize'",
        ),
        (
            "ncols x\nnrows 2\n",
            ":1: ncols: 'x' is not a positive whole number",
        ),
        (
            &format!("{head}1 2 3\n4 five 6\n"),
            ":7: row 1, column 1: 'five' is not a number",
        ),
        (
            &format!("{head}1 2 3\n4 5\n"),
            "expected 6 values (3 columns × 2 rows, as the header's lines 1 and 2 declare), found 5",
        ),
        (&format!("{head}1 2 3\n4 5 6\n7\n"), ":8: expected 6 values"),
        (
            &format!("{head}1 2 3\nnan 5 6\n"),
            "row 1, column 0: the value 'nan' is not finite",
        ),
        (
            "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -2\n1 2 3\n4 5 6\n",
            "cell size -2",
        ),
        (
            "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
            "makes no triangle",
        ),
        ("", "no 'ncols'"),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        let path = write(dir.path(), &format!("bad{i}.asc"), text);
        let e = geotracks_terrain::read_terrain(&path)
            .unwrap_err()
            .to_string();
        assert!(e.contains(&format!("bad{i}.asc")), "{e}");
        assert!(e.contains(expected), "case {i}: {e:?} lacks {expected:?}");
    }
    let e = read_grid(dir.path().join("x.xyz")).unwrap_err();
    assert!(matches!(e, TerrainError::UnknownFormat { .. }));
    let e = read_grid(dir.path().join("missing.asc")).unwrap_err();
    assert!(matches!(e, TerrainError::Io { .. }));
}

// ---------------------------------------------------------------------------------
// GeoTIFF

/// Writes a single-band GeoTIFF with the given georeference tags.
fn write_tiff<C>(
    path: &Path,
    (w, h): (u32, u32),
    data: &[C::Inner],
    scale: Option<[f64; 3]>,
    tie: Option<[f64; 6]>,
    geo_keys: Option<&[u16]>,
    nodata: Option<&str>,
) where
    C: tiff::encoder::colortype::ColorType,
    [C::Inner]: tiff::encoder::TiffValue,
{
    use tiff::tags::Tag;
    let file = std::fs::File::create(path).unwrap();
    let mut tiff = tiff::encoder::TiffEncoder::new(file).unwrap();
    let mut image = tiff.new_image::<C>(w, h).unwrap();
    let enc = image.encoder();
    if let Some(s) = scale {
        enc.write_tag(Tag::ModelPixelScaleTag, &s[..]).unwrap();
    }
    if let Some(t) = tie {
        enc.write_tag(Tag::ModelTiepointTag, &t[..]).unwrap();
    }
    if let Some(k) = geo_keys {
        enc.write_tag(Tag::GeoKeyDirectoryTag, k).unwrap();
    }
    if let Some(n) = nodata {
        enc.write_tag(Tag::GdalNodata, n).unwrap();
    }
    image.write_data(data).unwrap();
}

/// A GeoKey directory with the raster type (1 area, 2 point) and projected model type.
fn geo_keys(raster_type: u16) -> [u16; 12] {
    [1, 1, 0, 2, 1024, 0, 1, 1, 1025, 0, 1, raster_type]
}

#[test]
fn geotiff_f32_with_nodata_and_pixel_is_area() {
    use tiff::encoder::colortype::Gray32Float;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dem.tif");
    // 3 × 2 pixels of 10 m; the tie point puts raster (0, 0) at (1000, 2000).
    let data = [1.0f32, 2.0, -9999.0, 4.0, 5.0, 6.0];
    write_tiff::<Gray32Float>(
        &path,
        (3, 2),
        &data,
        Some([10.0, 10.0, 0.0]),
        Some([0.0, 0.0, 0.0, 1000.0, 2000.0, 0.0]),
        Some(&geo_keys(1)),
        Some("-9999"),
    );
    let grid = read_grid(&path).unwrap();
    // PixelIsArea: the first sample's centre is half a pixel in.
    assert_eq!(grid.geometry().position(0, 0), [1005.0, 1995.0]);
    assert_eq!(grid.geometry().lower_left, [1005.0, 1985.0]);
    assert_eq!(grid.elevation(2, 0), None);
    assert_eq!(grid.elevation(1, 1), Some(5.0));
    let terrain = grid.to_mesh().unwrap();
    assert_eq!(terrain.mesh.face_count(), 3);
}

/// The grid's CRS, as an EPSG code: a GeoTIFF's `ProjectedCSTypeGeoKey` (not the
/// user-defined 32767), or the authority at the end of the WKT in an ESRI grid's `.prj`
/// (WKT1 and WKT2; none in ESRI's own WKT).
#[test]
fn the_crs_is_read_from_geotiff_keys_and_prj_files() {
    use tiff::encoder::colortype::Gray32Float;
    let dir = tempfile::tempdir().unwrap();
    let data = [1.0f32, 2.0, 3.0, 4.0];
    let tiff_with = |name: &str, code: Option<u16>| {
        let path = dir.path().join(name);
        let mut keys = vec![1u16, 1, 0, 2, 1024, 0, 1, 1, 1025, 0, 1, 1];
        if let Some(code) = code {
            keys[3] = 3;
            keys.extend([3072, 0, 1, code]);
        }
        write_tiff::<Gray32Float>(
            &path,
            (2, 2),
            &data,
            Some([10.0, 10.0, 0.0]),
            Some([0.0, 0.0, 0.0, 500000.0, 4600000.0, 0.0]),
            Some(&keys),
            None,
        );
        read_grid(&path).unwrap().epsg()
    };
    assert_eq!(tiff_with("utm.tif", Some(32633)), Some(32633));
    assert_eq!(tiff_with("user.tif", Some(32767)), None);
    assert_eq!(tiff_with("none.tif", None), None);

    let asc = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
    let asc_with = |name: &str, prj: Option<&str>| {
        let path = write(dir.path(), &format!("{name}.asc"), asc);
        if let Some(prj) = prj {
            write(dir.path(), &format!("{name}.prj"), prj);
        }
        read_grid(&path).unwrap().epsg()
    };
    let wkt1 = r#"PROJCS["WGS 84 / UTM zone 33N",GEOGCS["WGS 84",DATUM["WGS_1984",
        SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],
        AUTHORITY["EPSG","4326"]],PROJECTION["Transverse_Mercator"],UNIT["metre",1],
        AUTHORITY["EPSG","32633"]]"#;
    let wkt2 = r#"PROJCRS["ETRS89 / UTM zone 32N", BASEGEOGCRS["ETRS89", ID["EPSG",4258]],
        CONVERSION["UTM zone 32N", ID["EPSG",16032]], ID["EPSG",25832]]"#;
    let esri = r#"PROJCS["WGS_1984_UTM_Zone_33N",GEOGCS["GCS_WGS_1984"],PROJECTION["Transverse_Mercator"]]"#;
    assert_eq!(asc_with("wkt1", Some(wkt1)), Some(32633));
    assert_eq!(asc_with("wkt2", Some(wkt2)), Some(25832));
    assert_eq!(asc_with("esri", Some(esri)), None);
    assert_eq!(asc_with("bare", None), None);
}

#[test]
fn geotiff_i16_pixel_is_point_and_no_geokeys() {
    use tiff::encoder::colortype::GrayI16;
    let dir = tempfile::tempdir().unwrap();
    let data = [-5i16, 0, 7, 300, 301, 302];
    let point = dir.path().join("point.tif");
    write_tiff::<GrayI16>(
        &point,
        (3, 2),
        &data,
        Some([2.0, 4.0, 0.0]),
        Some([0.0, 0.0, 0.0, 50.0, 80.0, 0.0]),
        Some(&geo_keys(2)),
        None,
    );
    let grid = read_geotiff(&point).unwrap();
    // PixelIsPoint: raster (0, 0) is the first sample's centre; dx ≠ dy.
    assert_eq!(grid.geometry().position(0, 0), [50.0, 80.0]);
    assert_eq!(grid.geometry().spacing, [2.0, 4.0]);
    assert_eq!(grid.elevation(0, 0), Some(-5.0));
    assert_eq!(grid.elevation(2, 1), Some(302.0));
    // No GeoKey directory: PixelIsArea, the default.
    let area = dir.path().join("area.tif");
    write_tiff::<GrayI16>(
        &area,
        (3, 2),
        &data,
        Some([2.0, 4.0, 0.0]),
        Some([0.0, 0.0, 0.0, 50.0, 80.0, 0.0]),
        None,
        None,
    );
    assert_eq!(
        read_geotiff(&area).unwrap().geometry().position(0, 0),
        [51.0, 78.0]
    );
}

#[test]
fn geotiff_refusals_say_why() {
    use tiff::encoder::colortype::{Gray16, RGB8};
    let dir = tempfile::tempdir().unwrap();
    let bare = dir.path().join("bare.tif");
    write_tiff::<Gray16>(&bare, (2, 2), &[1, 2, 3, 4], None, None, None, None);
    let e = read_geotiff(&bare).unwrap_err().to_string();
    assert!(e.contains("no georeference"), "{e}");
    let rgb = dir.path().join("rgb.tif");
    write_tiff::<RGB8>(
        &rgb,
        (2, 2),
        &[0; 12],
        Some([1.0, 1.0, 0.0]),
        Some([0.0; 6]),
        None,
        None,
    );
    let e = read_geotiff(&rgb).unwrap_err().to_string();
    assert!(e.contains("not a single band"), "{e}");
    let geographic = dir.path().join("geo.tif");
    write_tiff::<Gray16>(
        &geographic,
        (2, 2),
        &[1, 2, 3, 4],
        Some([0.001, 0.001, 0.0]),
        Some([0.0, 0.0, 0.0, 7.0, 45.0, 0.0]),
        Some(&[1, 1, 0, 1, 1024, 0, 1, 2]),
        None,
    );
    let e = read_geotiff(&geographic).unwrap_err().to_string();
    assert!(e.contains("geographic"), "{e}");
    let truncated = dir.path().join("cut.tif");
    let bytes = std::fs::read(&bare).unwrap();
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    assert!(read_geotiff(&truncated).is_err());
    std::fs::write(&truncated, b"not a tiff at all").unwrap();
    assert!(matches!(
        read_geotiff(&truncated),
        Err(TerrainError::Tiff { .. })
    ));
}

// ---------------------------------------------------------------------------------
// Costs

#[test]
fn cost_specs_parse_and_check() {
    for (text, cost) in [
        ("none", TerrainCost::None),
        (
            "slope:2.5",
            TerrainCost::Slope {
                a: 2.5,
                max_degrees: None,
            },
        ),
        (
            "slope:0,max:30",
            TerrainCost::Slope {
                a: 0.0,
                max_degrees: Some(30.0),
            },
        ),
        ("incline:4", TerrainCost::Incline { b: 4.0 }),
        (
            "uphill:4",
            TerrainCost::Directed(DirectedModel::Uphill { b: 4.0 }),
        ),
        ("naismith", TerrainCost::Directed(DirectedModel::NAISMITH)),
        ("rwalk", TerrainCost::Directed(DirectedModel::RWALK)),
        (
            "rwalk:1,5,0.5,-1,-0.3",
            TerrainCost::Directed(DirectedModel::Walk {
                a: 1.0,
                b: 5.0,
                c: 0.5,
                d: -1.0,
                slope_factor: -0.3,
            }),
        ),
        (
            "tobler",
            TerrainCost::Directed(DirectedModel::Tobler { off_path: false }),
        ),
        (
            "tobler:offpath",
            TerrainCost::Directed(DirectedModel::Tobler { off_path: true }),
        ),
    ] {
        assert_eq!(text.parse::<TerrainCost>().unwrap(), cost);
        assert_eq!(cost.to_string(), text);
    }
    for bad in [
        "",
        "slope",
        "slope:x",
        "slope:-1",
        "slope:1,max:0",
        "slope:1,max:91",
        "slope:1,min:3",
        "uphill:nan",
        "uphill:-2",
        "incline:-2",
        "naismith:1",
        "rwalk:1,2,3",
        "rwalk:0,6,1,-1",
        "rwalk:0.72,6,4,-2",
        "rwalk:0.72,6,2,1",
        "rwalk:0.72,6,2,-2,0.1",
        "tobler:onpath",
        "none:3",
        "steep:1",
    ] {
        let e = bad.parse::<TerrainCost>().unwrap_err();
        assert!(matches!(e, TerrainError::CostSpec { .. }), "{bad}: {e}");
    }
}

/// A `ncols × ncols` grid of spacing `h` on a plane of slope `alpha` (radians) rising
/// towards direction `beta` (radians from the x axis).
fn tilted(ncols: usize, h: f64, alpha: f64, beta: f64) -> TerrainMesh {
    let g = geometry(ncols, ncols, [0.0, 0.0], h);
    ElevationGrid::from_fn(g, |x, y| {
        Some(alpha.tan() * (x * beta.cos() + y * beta.sin()))
    })
    .unwrap()
    .to_mesh()
    .unwrap()
}

#[test]
fn on_a_flat_grid_every_cost_is_euclidean() {
    let terrain = tilted(21, 0.5, 0.0, 0.0);
    let mesh = &terrain.mesh;
    let (from, to): ([f64; 2], [f64; 2]) = ([1.3, 0.7], [8.6, 9.1]);
    let straight = (to[0] - from[0]).hypot(to[1] - from[1]);
    let options = TRACKS;
    let euclid = Solver::new(mesh, &Euclidean, &options)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    let mut worst: f64 = 0.0;
    for cost in ["none", "slope:5", "slope:5,max:10", "incline:7", "uphill:7"] {
        let cost: TerrainCost = cost.parse().unwrap();
        let metric = cost.metric(mesh).unwrap();
        let field = Solver::new(mesh, &metric, &options)
            .and_then(|solver| solver.field(&[0]))
            .unwrap();
        let field_dev = field
            .vertex_distances()
            .iter()
            .zip(euclid.vertex_distances())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let length = route(&terrain, &metric, &options, from, to).unwrap().length;
        assert!(field_dev <= 1e-12, "{cost}: field differs by {field_dev}");
        let err = relative(length, straight);
        worst = worst.max(err);
        assert!(err < 1e-5, "{cost}: route {length} vs straight {straight}");
    }
    println!("flat grid: route vs straight line, worst relative error {worst:.1e}");
}

#[test]
fn tilted_plane_slope_density_and_uphill_match_the_analytic_costs() {
    let (alpha, beta) = (30f64.to_radians(), 25f64.to_radians());
    let terrain = tilted(41, 1.0, alpha, beta);
    let mesh = &terrain.mesh;
    let centre = [20.0, 20.0];
    let along = [beta.cos(), beta.sin()];
    let across = [-beta.sin(), beta.cos()];
    let l = 14.0; // map length of each route
    let ends = |d: [f64; 2]| {
        (
            [centre[0] - d[0] * l / 2.0, centre[1] - d[1] * l / 2.0],
            [centre[0] + d[0] * l / 2.0, centre[1] + d[1] * l / 2.0],
        )
    };
    let a = 2.0;
    let rho = 1.0 + a * alpha.tan().powi(2);
    let density = slope_density(mesh, a).unwrap();
    assert!(density
        .per_vertex()
        .iter()
        .all(|r| relative(*r, rho) < 1e-12));
    let b = 3.0;
    let tensor = incline_tensor(mesh, b).unwrap();
    let mut report = Vec::new();
    for (name, dir, slope_cost, uphill_cost) in [
        (
            "along the slope",
            along,
            rho * l / alpha.cos(),
            (1.0 + b * alpha.sin().powi(2)).sqrt() * l / alpha.cos(),
        ),
        ("across the slope", across, rho * l, l),
    ] {
        let (from, to) = ends(dir);
        for k in [2.0, 5.0] {
            let options = TRACKS.with_k(k);
            let s = route(&terrain, &density, &options, from, to).unwrap();
            let u = route(&terrain, &tensor, &options, from, to).unwrap();
            let (es, eu) = (
                relative(s.length, slope_cost),
                relative(u.length, uphill_cost),
            );
            let (gs, gu) = (
                relative(s.traced_length, slope_cost),
                relative(u.traced_length, uphill_cost),
            );
            report.push(format!(
                "{name}, k = {k}: slope density {es:.1e} (graph {gs:.1e}), incline {eu:.1e} (graph {gu:.1e})"
            ));
            assert!(es < 1e-6, "slope {name}: {} vs {slope_cost}", s.length);
            assert!(eu < 1e-6, "incline {name}: {} vs {uphill_cost}", u.length);
        }
    }
    println!("tilted plane (30°, a = {a}, b = {b}), relative error of the route cost:");
    for line in report {
        println!("  {line}");
    }
}

/// The directed costs on a plane tilted 10° (gentle enough for every model to be
/// convex, so the straight route is the cheapest), up the fall line, down it and
/// across, against their formulas written out here: the route's cost and the field's
/// value at its end.
#[test]
fn directed_costs_up_down_and_across_a_tilted_plane_match_their_formulas() {
    let (alpha, beta) = (10f64.to_radians(), 25f64.to_radians());
    let terrain = tilted(41, 1.0, alpha, beta);
    let mesh = &terrain.mesh;
    let (t, l) = (alpha.tan(), 14.0); // tangent, map length
    let centre = [20.0, 20.0];
    let line = |d: [f64; 2]| {
        (
            [centre[0] - d[0] * l / 2.0, centre[1] - d[1] * l / 2.0],
            [centre[0] + d[0] * l / 2.0, centre[1] + d[1] * l / 2.0],
        )
    };
    let (up, down, across) = (
        line([beta.cos(), beta.sin()]),
        line([-beta.cos(), -beta.sin()]),
        line([-beta.sin(), beta.cos()]),
    );
    // Horizontal run h and rise dz of each route.
    let legs = [
        ("up", up, t * l),
        ("down", down, -t * l),
        ("across", across, 0.0),
    ];
    let tobler = |dz: f64| 0.6 * l * (3.5 * (dz / l + 0.05).abs()).exp();
    type Formula<'a> = Box<dyn Fn(f64) -> f64 + 'a>; // the cost from the rise
    let models: [(&str, Formula); 6] = [
        (
            "uphill:3",
            Box::new(|dz: f64| l.hypot(dz) + 3.0 * dz.max(0.0)),
        ),
        ("naismith", Box::new(|dz: f64| 0.72 * l + 6.0 * dz.max(0.0))),
        // tan 10° = 0.176: a moderate descent (above −0.2125), 1.9998 s per metre saved.
        (
            "rwalk",
            Box::new(|dz: f64| 0.72 * l + if dz >= 0.0 { 6.0 * dz } else { 1.9998 * dz }),
        ),
        (
            "rwalk:1,4,0.5,-0.5,-0.1",
            // Past the slope factor −0.1: a steep descent, 0.5 s per metre lost.
            Box::new(|dz: f64| l + if dz >= 0.0 { 4.0 * dz } else { -0.5 * dz }),
        ),
        ("tobler", Box::new(tobler)),
        ("tobler:offpath", Box::new(move |dz: f64| tobler(dz) / 0.6)),
    ];
    let (mut worst, mut worst_across) = (0.0f64, 0.0f64);
    for (name, formula) in &models {
        let cost: TerrainCost = name.parse().unwrap();
        assert!(cost.is_directed());
        let metric = cost.metric(mesh).unwrap();
        let solver = Solver::new(mesh, &metric, &Options::DEFAULT.with_k(2.0)).unwrap();
        for (leg, (from, to), dz) in legs {
            let expected = formula(dz);
            let (a, b) = (
                terrain.locate(from[0], from[1]).unwrap(),
                terrain.locate(to[0], to[1]).unwrap(),
            );
            let path = solver.shortest_path(&[Source::new(a)], b).unwrap().0;
            let error = relative(path.length, expected);
            // Across, the route follows a contour, where uphill, Naismith and r.walk
            // have a kink (climbing starts to cost): straightening moves one crossing
            // at a time and can stall a little above the contour there (up to 1.9e-4).
            let tolerance = if leg == "across" { 1e-3 } else { 1e-9 };
            assert!(
                error < tolerance,
                "{name} {leg}: {} vs {expected}",
                path.length
            );
            if leg != "across" {
                worst = worst.max(error);
            } else {
                worst_across = worst_across.max(error);
            }
            assert!(path.traced_length >= path.length);
        }
        // Up and down differ (across is symmetric).
        let (u, d) = (formula(t * l), formula(-t * l));
        assert!((u - d).abs() > 0.01 * u, "{name}");
    }
    println!(
        "tilted plane (10°): directed route costs within {worst:.1e} of their formulas up and down, {worst_across:.1e} across"
    );
}

/// On flat ground the walking times are distance over speed: 0.72 s/m for Naismith
/// and r.walk, 0.6·e^0.175 s/m for Tobler (5.04 km/h: its 6 km/h is for a slight
/// descent), 1/0.6 of that off paths; `uphill` is the length.
#[test]
fn on_a_flat_grid_the_walking_times_are_distance_over_speed() {
    let terrain = tilted(15, 1.0, 0.0, 0.0);
    let mesh = &terrain.mesh;
    let euclid = Solver::new(mesh, &Euclidean, &TRACKS)
        .and_then(|solver| solver.field(&[7]))
        .unwrap();
    let flat = 0.6 * 0.175f64.exp();
    for (cost, per_metre) in [
        ("uphill:5", 1.0),
        ("naismith", 0.72),
        ("rwalk", 0.72),
        ("tobler", flat),
        ("tobler:offpath", flat / 0.6),
    ] {
        let metric = cost.parse::<TerrainCost>().unwrap().metric(mesh).unwrap();
        let field = Solver::new(mesh, &metric, &TRACKS)
            .and_then(|solver| solver.field(&[7]))
            .unwrap();
        for (d, e) in field
            .vertex_distances()
            .iter()
            .zip(euclid.vertex_distances())
        {
            assert!(
                (d - per_metre * e).abs() <= 1e-12 * (1.0 + e),
                "{cost}: {d} vs {}",
                per_metre * e
            );
        }
    }
}

/// Steeper than 15.9°, Tobler's cost is not convex: zig-zagging up the fall line costs
/// less than walking straight up it (switchbacks). The Steiner graph finds zig-zags at
/// its resolution: the field lies below the straight walk, never below the best
/// zig-zag (the convex envelope).
#[test]
fn tobler_zigzags_up_a_steep_slope() {
    let alpha = 30f64.to_radians();
    let terrain = tilted(31, 1.0, alpha, 0.0);
    let mesh = &terrain.mesh;
    let metric = DirectedCost::new(mesh, DirectedModel::Tobler { off_path: false }).unwrap();
    assert_eq!(metric.nonconvex_faces(), mesh.face_count());
    let t = alpha.tan();
    let l = 20.0;
    let straight = 0.6 * l * (3.5 * (t + 0.05)).exp();
    // Two legs at ±φ from the fall line: each climbs t cos φ per unit of run.
    let zigzag = |phi: f64| 0.6 * l * (3.5 * (t * phi.cos() + 0.05)).exp() / phi.cos();
    let best = (0..9000)
        .map(|i| zigzag(i as f64 * 1e-4 * std::f64::consts::FRAC_PI_2))
        .fold(f64::INFINITY, f64::min);
    let (from, to) = (
        terrain.locate(5.5, 15.5).unwrap(),
        terrain.locate(25.5, 15.5).unwrap(),
    );
    for k in [2.0, 6.0] {
        let options = Options::DEFAULT.with_k(k);
        let solver = Solver::new(mesh, &metric, &options).unwrap();
        let field = solver
            .field(Sources::from(&[Source::new(from)]).until(&Stop::NONE))
            .unwrap();
        let up = field.distance_at(to).unwrap();
        println!(
            "tobler up 30°, k = {k}: {up:.2} s; straight {straight:.2} s, best zig-zag {best:.2} s"
        );
        assert!(up < 0.95 * straight && up >= best * (1.0 - 1e-9), "{up}");
    }
}

#[test]
fn max_slope_blocks_steep_faces_only() {
    let terrain = tilted(5, 1.0, 40f64.to_radians(), 0.0);
    assert!(steeper_than(&terrain.mesh, 45.0)
        .unwrap()
        .iter()
        .all(|b| !b));
    assert!(steeper_than(&terrain.mesh, 35.0)
        .unwrap()
        .iter()
        .all(|&b| b));
    assert!(steeper_than(&terrain.mesh, 0.0).is_err());
    assert!(slope_density(&terrain.mesh, -1.0).is_err());
    assert!(incline_tensor(&terrain.mesh, f64::NAN).is_err());
}

/// The exact least-cost route from `a` to `b` (west to east) through the medium of
/// `snell_law_at_a_density_interface`: density ρ1 up to x = -h, then linear in x up to
/// ρ2 at x = 0, ρ2 beyond. Returns its cost and its angles from the x axis in the two
/// uniform layers. In a medium layered in x, ρ sin θ is the same all along the route
/// (Snell's law, continuously through the ramp), so the route is found by bisection on
/// that invariant p; across the ramp, where dx = h dρ / (ρ2 - ρ1), the height gained
/// and the cost have closed forms:
///   ∫ p / √(ρ² - p²) dρ = p acosh(ρ / p),
///   ∫ ρ² / √(ρ² - p²) dρ = (ρ √(ρ² - p²) + p² acosh(ρ / p)) / 2.
fn refracted_route(a: [f64; 2], b: [f64; 2], h: f64, rho1: f64, rho2: f64) -> (f64, f64, f64) {
    let (west, east) = (-h - a[0], b[0]);
    let ramp = |f: &dyn Fn(f64) -> f64| h / (rho2 - rho1) * (f(rho2) - f(rho1));
    let rise = |p: f64| {
        let (s1, s2) = (p / rho1, p / rho2);
        west * s1 / (1.0 - s1 * s1).sqrt()
            + east * s2 / (1.0 - s2 * s2).sqrt()
            + ramp(&|r| p * (r / p).acosh())
    };
    let (mut lo, mut hi) = (0.0, rho1.min(rho2));
    for _ in 0..200 {
        let p = 0.5 * (lo + hi);
        if rise(p) < (b[1] - a[1]).abs() {
            lo = p;
        } else {
            hi = p;
        }
    }
    let p = 0.5 * (lo + hi);
    let (s1, s2) = (p / rho1, p / rho2);
    let cost = west * rho1 / (1.0 - s1 * s1).sqrt()
        + east * rho2 / (1.0 - s2 * s2).sqrt()
        + ramp(&|r| 0.5 * (r * (r * r - p * p).sqrt() + p * p * (r / p).acosh()));
    (cost, s1.asin(), s2.asin())
}

#[test]
fn snell_law_at_a_density_interface() {
    // Flat grid on [-1, 1] × [0, 2]; ρ1 west of x = 0, ρ2 from x = 0 on: the density
    // ramps over the one column of cells between x = -h and 0.
    let h = 0.02;
    let n = (2.0 / h) as usize + 1;
    let terrain = ElevationGrid::from_fn(geometry(n, n, [-1.0, 0.0], h), |_, _| Some(0.0))
        .unwrap()
        .to_mesh()
        .unwrap();
    let mesh = &terrain.mesh;
    let mut worst: f64 = 0.0;
    let mut worst_cost: f64 = 0.0;
    for (rho1, rho2, from, to) in [
        (1.0, 1.5, [-0.9, 0.1], [0.9, 1.5]),
        (2.0, 1.0, [-0.95, 0.2], [0.85, 1.9]),
        (1.0, 3.0, [-0.8, 0.05], [0.9, 1.2]),
    ] {
        let rho: Vec<f64> = mesh
            .positions()
            .iter()
            .map(|p| if p.x < -1e-9 { rho1 } else { rho2 })
            .collect();
        let density = Density::new(mesh, rho).unwrap();
        let path = route(&terrain, &density, &TRACKS, from, to).unwrap();
        let points = path.positions(mesh);
        // The route's direction on each side, from 3 to 10 cells away from the ramp:
        // from the first to the last of its points there.
        let direction = |lo: f64, hi: f64| -> f64 {
            let inside: Vec<DVec3> = points
                .iter()
                .copied()
                .filter(|p| p.x > lo && p.x < hi)
                .collect();
            assert!(inside.len() >= 2, "too few points in ({lo}, {hi})");
            let d = inside[inside.len() - 1] - inside[0];
            d.y.abs().atan2(d.x.abs())
        };
        let theta1 = direction(-h - 10.0 * h, -h - 3.0 * h);
        let theta2 = direction(3.0 * h, 10.0 * h);
        let (optimum, exact1, exact2) = refracted_route(from, to, h, rho1, rho2);
        let error = (theta1 - exact1)
            .abs()
            .max((theta2 - exact2).abs())
            .to_degrees();
        // Predicting one measured angle from the other magnifies the first one's error
        // by ρ1 cos θ1 / (ρ2 cos θ2) (3.3 for the second case): shown, not checked.
        let predicted = (rho1 * theta1.sin() / rho2).asin();
        let excess = (path.length - optimum) / optimum;
        println!(
            "snell ρ1 = {rho1}, ρ2 = {rho2}: θ1 = {:.3}° (exact {:.3}°), θ2 = {:.3}° \
             (exact {:.3}°, from θ1 by Snell {:.3}°); route cost {:.7} vs exact {optimum:.7} \
             ({excess:+.1e})",
            theta1.to_degrees(),
            exact1.to_degrees(),
            theta2.to_degrees(),
            exact2.to_degrees(),
            predicted.to_degrees(),
            path.length,
        );
        worst = worst.max(error);
        worst_cost = worst_cost.max(excess);
        assert!(
            error < 1.0,
            "the route's angles are {error}° off the refracted ray"
        );
        // A route on the surface is a route of the medium, its cost exact: it cannot
        // beat the optimum.
        assert!(
            (-1e-12..1e-4).contains(&excess),
            "cost {} vs optimum {optimum}",
            path.length
        );
    }
    println!("snell: worst angle error {worst:.3}°, worst cost excess {worst_cost:.1e}");
}

// ---------------------------------------------------------------------------------
// Walls

/// A 41 × 41 flat grid of unit cells, with the cells of row band y ∈ [20, 21] blocked
/// except those whose x lies in `gap`.
fn walled(gap: Option<(f64, f64)>) -> (TerrainMesh, Vec<bool>) {
    let terrain = tilted(41, 1.0, 0.0, 0.0);
    let mesh = &terrain.mesh;
    let blocked = (0..mesh.face_count() as u32)
        .map(|f| {
            let c = mesh
                .face_vertices(f)
                .iter()
                .fold(DVec3::ZERO, |s, &v| s + mesh.position(v))
                / 3.0;
            let in_gap = gap.is_some_and(|(lo, hi)| c.x > lo && c.x < hi);
            c.y > 20.0 && c.y < 21.0 && !in_gap
        })
        .collect();
    (terrain, blocked)
}

#[test]
fn a_wall_with_one_gap_routes_through_the_gap() {
    let (terrain, blocked) = walled(Some((30.0, 32.0)));
    let walls = Impassable::new(&terrain.mesh, Euclidean, blocked).unwrap();
    let (from, to) = ([10.0, 5.0], [10.0, 35.0]);
    // Around the gap's west side: to its corner (30, 20), along the wall's edge to
    // (30, 21), then straight to the target.
    let exact = 25.0 + 1.0 + (20f64 * 20.0 + 14.0 * 14.0).sqrt();
    for options in [TRACKS, GRAPH, DIJKSTRA] {
        let path = route(&terrain, &walls, &options, from, to).unwrap();
        let points = path.positions(&terrain.mesh);
        let through = points
            .iter()
            .any(|p| p.y >= 20.0 && p.y <= 21.0 && p.x >= 30.0 - 1e-9 && p.x <= 32.0 + 1e-9);
        assert!(
            through,
            "{:?}: the route does not pass the gap",
            options.method
        );
        for (i, &f) in path.faces.iter().enumerate() {
            let seg = (points[i + 1] - points[i]).length();
            assert!(
                !walls.is_blocked(f) || seg == 0.0,
                "a segment crosses the wall"
            );
        }
        assert!(path.length.is_finite() && path.length >= exact * (1.0 - 1e-9));
        let err = relative(path.length, exact);
        println!(
            "wall with a gap, {}: route {:.6} vs exact {exact:.6} (relative {err:.1e})",
            options.method, path.length
        );
        if options.method != Method::Dijkstra {
            assert!(
                err < 1e-6,
                "{:?}: {} vs {exact}",
                options.method,
                path.length
            );
        }
    }
}

#[test]
fn a_closed_wall_makes_the_target_unreachable() {
    let (terrain, blocked) = walled(None);
    for inner_density in [false, true] {
        for options in [TRACKS, GRAPH, DIJKSTRA] {
            let result = if inner_density {
                let d = Density::constant(&terrain.mesh, 2.0).unwrap();
                route(
                    &terrain,
                    &Impassable::new(&terrain.mesh, d, blocked.clone()).unwrap(),
                    &options,
                    [10.0, 5.0],
                    [10.0, 35.0],
                )
            } else {
                route(
                    &terrain,
                    &Impassable::new(&terrain.mesh, Euclidean, blocked.clone()).unwrap(),
                    &options,
                    [10.0, 5.0],
                    [10.0, 35.0],
                )
            };
            assert!(
                matches!(result, Err(Error::Unreachable { .. })),
                "{:?}",
                result.map(|p| p.length)
            );
        }
    }
    // Blocked vertices: the faces around them are walls.
    let mesh = &terrain.mesh;
    let row: Vec<bool> = mesh.positions().iter().map(|p| p.y == 20.0).collect();
    let walls = Impassable::from_vertices(mesh, Euclidean, &row).unwrap();
    let field = Solver::new(mesh, &walls, &TRACKS)
        .and_then(|solver| solver.field(&[0]))
        .unwrap();
    for (v, p) in mesh.positions().iter().enumerate() {
        let d = field.distance(v as u32);
        assert!(!d.is_nan());
        assert_eq!(d.is_finite(), p.y > 20.0, "vertex at {p}: {d}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    // The directed costs on bumpy terrain: convex faces pruned, the others tested in
    // full, tracks = graph all the same.
    #[test]
    fn tracks_equals_graph_under_directed_costs(seed in any::<u64>(), n in 3usize..9, k in 1u32..6, relief in 0.0f64..3.0, which in 0usize..5, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mut rng = Rng(seed | 1);
        let bumps: Vec<f64> = (0..(n + 1) * (n + 1)).map(|_| relief * rng.next()).collect();
        let g = geometry(n + 1, n + 1, [0.0, 0.0], 1.0);
        let grid = ElevationGrid::from_fn(g, |x, y| {
            let (i, j) = (x.floor() as usize, y.floor() as usize);
            Some(bumps[(j * (n + 1) + i).min(bumps.len() - 1)])
        })
        .unwrap();
        let mesh = grid.to_mesh().unwrap().mesh;
        let cost = ["uphill:3", "naismith", "rwalk", "tobler", "tobler:offpath"][which];
        let metric = cost.parse::<TerrainCost>().unwrap().metric(&mesh).unwrap();
        let sources: Vec<u32> = picks.iter().map(|s| s % mesh.vertex_count() as u32).collect();
        let max = common::tracks_vs_graph(&mesh, &metric, &sources, k as f64);
        prop_assert!(max <= 1e-9, "{}: relative deviation {}", cost, max);
    }

    #[test]
    fn tracks_equals_graph_with_random_walls(seed in any::<u64>(), n in 3usize..9, k in 1u32..7, p in 0.0f64..0.5, picks in prop::collection::vec(any::<u32>(), 1..3)) {
        let mesh = random_mesh(seed, n).unwrap();
        let mut rng = Rng(seed.rotate_left(17) | 1);
        let blocked: Vec<bool> = (0..mesh.face_count()).map(|_| rng.next() < p).collect();
        let sources: Vec<u32> = picks.iter().map(|s| s % mesh.vertex_count() as u32).collect();
        let walls = Impassable::new(&mesh, Euclidean, blocked.clone()).unwrap();
        let max = common::tracks_vs_graph(&mesh, &walls, &sources, k as f64);
        prop_assert!(max <= 1e-9, "euclidean walls: relative deviation {}", max);
        let principal: Vec<(f64, f64, [f64; 3])> = (0..mesh.face_count())
            .map(|_| (0.2 + 4.0 * rng.next(), 0.2 + rng.next(), [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5]))
            .collect();
        if let Ok(tensor) = Tensor::from_principal(&mesh, &principal) {
            let walls = Impassable::new(&mesh, tensor, blocked.clone()).unwrap();
            let max = common::tracks_vs_graph(&mesh, &walls, &sources, k as f64);
            prop_assert!(max <= 1e-9, "tensor walls: relative deviation {}", max);
        }
        // A constant density is a norm on every face: exact too.
        let walls = Impassable::new(&mesh, Density::constant(&mesh, 1.7).unwrap(), blocked).unwrap();
        let max = common::tracks_vs_graph(&mesh, &walls, &sources, k as f64);
        prop_assert!(max <= 1e-9, "density walls: relative deviation {}", max);
    }

    #[test]
    fn paths_never_cross_walls(seed in any::<u64>(), p in 0.0f64..0.4) {
        let terrain = tilted(12, 1.0, 0.0, 0.0);
        let mesh = &terrain.mesh;
        let mut rng = Rng(seed | 1);
        let blocked: Vec<bool> = (0..mesh.face_count()).map(|_| rng.next() < p).collect();
        let walls = Impassable::new(mesh, Euclidean, blocked).unwrap();
        let from = [0.5 + 10.0 * rng.next(), 0.5 + 10.0 * rng.next()];
        let to = [0.5 + 10.0 * rng.next(), 0.5 + 10.0 * rng.next()];
        match route(&terrain, &walls, &TRACKS.with_k(3.0), from, to) {
            Ok(path) => {
                prop_assert!(path.length.is_finite() && path.length <= path.traced_length * (1.0 + 1e-12));
                let points = path.positions(mesh);
                for (i, &f) in path.faces.iter().enumerate() {
                    let seg = (points[i + 1] - points[i]).length();
                    prop_assert!(!walls.is_blocked(f) || seg == 0.0, "segment {} crosses face {}", i, f);
                }
            }
            Err(Error::Unreachable { .. }) => {}
            Err(e) => prop_assert!(false, "{}", e),
        }
    }
}

/// Grids are refused when they are not regular files: a FIFO blocked the reader.
#[cfg(unix)]
#[test]
fn a_fifo_as_a_grid_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["pipe.asc", "pipe.tif"] {
        let path = dir.path().join(name);
        let made = std::process::Command::new("mkfifo")
            .arg(&path)
            .status()
            .expect("mkfifo");
        assert!(made.success());
        let (send, receive) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = send.send(read_grid(&path).map(|_| ()));
        });
        let result = receive
            .recv_timeout(std::time::Duration::from_secs(10))
            .unwrap_or_else(|_| panic!("{name}: the reader blocked on the FIFO"));
        let err = result.expect_err("a FIFO is not a grid");
        assert!(matches!(err, TerrainError::NotAFile { .. }), "{err:?}");
        assert!(err.to_string().contains("named pipe"), "{err}");
    }
}

/// An ESRI grid saved with a UTF-8 byte-order mark (Windows editors) reads as without
/// one; the mark made its first header key unknown.
#[test]
fn esri_grid_with_a_byte_order_mark() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bom.asc");
    std::fs::write(
        &path,
        "\u{feff}ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
    )
    .unwrap();
    let grid = read_grid(&path).unwrap();
    assert_eq!(grid.elevation(0, 0), Some(1.0));
}

/// A corrupt strip is named with its index and offset; the decoder alone said "no lzw
/// end code found" (or "failed to fill whole buffer") and nothing of where.
#[test]
fn a_corrupt_geotiff_strip_is_named_with_its_offset() {
    use tiff::encoder::{colortype::Gray16, Compression, TiffEncoder};
    use tiff::tags::Tag;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("corrupt.tif");
    let (w, h) = (64u32, 64u32);
    let data: Vec<u16> = (0..w * h).map(|i| (i % 251) as u16).collect();
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut tiff = TiffEncoder::new(file)
            .unwrap()
            .with_compression(Compression::Lzw);
        let mut image = tiff.new_image::<Gray16>(w, h).unwrap();
        let enc = image.encoder();
        enc.write_tag(Tag::ModelPixelScaleTag, &[1.0, 1.0, 0.0][..])
            .unwrap();
        enc.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, 0.0, 64.0, 0.0][..])
            .unwrap();
        image.write_data(&data).unwrap();
    }
    assert!(read_geotiff(&path).is_ok());
    let (offsets, sizes) = {
        let mut decoder = tiff::decoder::Decoder::new(std::fs::File::open(&path).unwrap()).unwrap();
        (
            decoder.get_tag_u64_vec(Tag::StripOffsets).unwrap(),
            decoder.get_tag_u64_vec(Tag::StripByteCounts).unwrap(),
        )
    };
    // Garbage in the last strip: LZW cannot decode it.
    let last = offsets.len() - 1;
    let mut bytes = std::fs::read(&path).unwrap();
    let (at, size) = (offsets[last] as usize, sizes[last] as usize);
    for b in &mut bytes[at..at + size] {
        *b = 0xff;
    }
    std::fs::write(&path, &bytes).unwrap();
    let err = read_geotiff(&path).unwrap_err();
    assert!(matches!(err, TerrainError::Tiff { .. }), "{err:?}");
    let message = err.to_string();
    assert!(
        message.contains(&format!("strip {last} of {}", offsets.len()))
            && message.contains(&format!("at byte {at}")),
        "{message}"
    );
    assert!(message.contains("corrupt.tif"), "{message}");
}
