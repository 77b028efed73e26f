//! `geotracks terrain` end to end: GeoJSON, CSV and PNG outputs, costs, walls, GeoTIFF
//! input, and bad input that fails with one line and no file.

// Tests aside from the function-length rule (clippy.toml): a scenario reads best whole.
#![allow(clippy::too_many_lines)]

#[path = "../../tests/common/relief.rs"]
mod relief;
mod support;

use relief::RoughRelief;
use std::path::Path;
use support::{assert_fails, geotracks, geotracks_ok, last_value};

fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

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

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A 30 × 20 grid, 10 m apart, with a hill and a NODATA hole, as an ESRI ASCII grid.
fn hill_asc(dir: &Path) -> std::path::PathBuf {
    let mut text = String::from(
        "ncols 30\nnrows 20\nxllcorner 1000\nyllcorner 5000\ncellsize 10\nnodata_value -9999\n",
    );
    for r in 0..20 {
        let y = 5005.0 + (19 - r) as f64 * 10.0;
        let row: Vec<String> = (0..30)
            .map(|c| {
                let x = 1005.0 + c as f64 * 10.0;
                if (x - 1100.0).abs() < 15.0 && (y - 5170.0).abs() < 15.0 {
                    "-9999".to_string()
                } else {
                    let d2 = (x - 1150.0).powi(2) + (y - 5100.0).powi(2);
                    format!("{:.3}", 40.0 * (-d2 / 5000.0).exp())
                }
            })
            .collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    write(dir, "hill.asc", &text)
}

#[test]
fn cli_writes_geojson_csv_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let dem = dem.to_str().unwrap();
    let json = dir.path().join("route.geojson");
    let png = dir.path().join("map.png");
    let out = geotracks_ok(&[
        "terrain",
        dem,
        "--from",
        "1010,5010",
        "--to",
        "1290,5180",
        "--cost",
        "slope:3",
        "-o",
        json.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
    ]);
    let cost = last_value(&out);
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let feature = &value["features"][0];
    assert_eq!(feature["geometry"]["type"], "LineString");
    let coords = feature["geometry"]["coordinates"].as_array().unwrap();
    let xyz = |i: usize| -> Vec<f64> {
        coords[i]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    assert_eq!(xyz(0).len(), 3);
    assert!((xyz(0)[0] - 1010.0).abs() < 1e-9 && (xyz(0)[1] - 5010.0).abs() < 1e-9);
    let last = xyz(coords.len() - 1);
    assert!((last[0] - 1290.0).abs() < 1e-9 && (last[1] - 5180.0).abs() < 1e-9);
    let props = &feature["properties"];
    assert!((props["cost"].as_f64().unwrap() - cost).abs() <= 1e-9 * cost);
    let length = props["length"].as_f64().unwrap();
    let straight = (280f64).hypot(170.0);
    assert!(length >= straight && props["length_2d"].as_f64().unwrap() <= length);
    assert!(cost >= length, "a slope density is at least 1");
    assert_eq!(props["cost_model"], "slope:3");
    // The PNG: 30 × 20 samples upsampled to a long side of 512.
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let height = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((width, height), (512, 341));

    // CSV: x,y,z,cost,length per point, cumulative; the same route.
    let csv = dir.path().join("route.csv");
    let out = geotracks_ok(&[
        "terrain",
        dem,
        "--from",
        "1010,5010",
        "--to",
        "1290,5180",
        "--cost",
        "slope:3",
        "-o",
        csv.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,cost,length"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), coords.len());
    let end = &rows[rows.len() - 1];
    assert!((end[3] - cost).abs() <= 1e-9 * cost, "{} vs {cost}", end[3]);
    // Without the map the route is found on a window of the grid (goal-directed): it
    // costs the same, and straightens to the same length within the straightener's
    // tolerance (measured: 3e-8).
    assert!(
        (end[4] - length).abs() <= 1e-6 * length,
        "{} vs {length}",
        end[4]
    );
    assert!(rows.windows(2).all(|w| w[1][3] >= w[0][3]));
    // Without the map the run stops at the target: the same cost.
    assert!((last_value(&out) - cost).abs() <= 1e-9 * cost);
}

#[test]
fn cli_costs_order_as_expected_and_max_slope_walls_off() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let dem = dem.to_str().unwrap();
    let out_path = dir.path().join("r.json");
    let out = out_path.to_str().unwrap();
    let run = |options: &[&str]| {
        let mut args = vec!["terrain", dem, "--from", "1010,5100", "--to", "1290,5100"];
        args.extend_from_slice(options);
        args.extend_from_slice(&["-o", out]);
        last_value(&geotracks_ok(&args))
    };
    let cost = |cost: &str| run(&["--cost", cost]);
    let none = cost("none");
    assert!(none >= 280.0);
    assert!(cost("slope:2") > none);
    assert!(cost("incline:5") > none);
    assert!(cost("uphill:5") > none);
    // The Steiner graph, goal-directed, at a k where it routes as well: the same route
    // to within its straightening.
    let tracks = run(&["--method", "tracks", "--k", "4"]);
    assert!(relative(tracks, none) < 5e-3, "{tracks} against {none}");
    // The hill's flanks reach about 25°: a 5° limit walls the route off.
    let walled = dir.path().join("walled.json");
    assert_fails(
        &[
            "terrain",
            dem,
            "--from",
            "1010,5100",
            "--to",
            "1290,5100",
            "--cost",
            "slope:1,max:5",
            "-o",
            walled.to_str().unwrap(),
        ],
        &walled,
        "error: no route",
    );
}

/// A directed cost charges the way travelled: from the hill's foot to a point higher up
/// and back differ, and the GeoJSON says the cost is directed, in seconds for times.
#[test]
fn cli_directed_costs_differ_up_and_down() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let dem = dem.to_str().unwrap();
    let out_path = dir.path().join("r.geojson");
    let out = out_path.to_str().unwrap();
    let run = |from: &str, to: &str, cost: &str| {
        let printed = geotracks_ok(&[
            "terrain", dem, "--from", from, "--to", to, "--cost", cost, "-o", out,
        ]);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out_path).unwrap()).unwrap();
        (last_value(&printed), json)
    };
    for cost in ["uphill:5", "naismith", "rwalk", "tobler"] {
        let (up, json) = run("1010,5100", "1150,5150", cost);
        let (down, _) = run("1150,5150", "1010,5100", cost);
        assert!(up > 1.02 * down, "{cost}: up {up}, down {down}");
        let properties = &json["features"][0]["properties"];
        assert_eq!(properties["directed"], true);
        assert_eq!(properties["cost_model"], cost);
        let unit = if cost == "uphill:5" { "m" } else { "s" };
        assert_eq!(properties["cost_unit"], unit);
    }
    std::fs::remove_file(&out_path).unwrap();
    let args = [
        "terrain",
        dem,
        "--from",
        "1010,5100",
        "--to",
        "1150,5150",
        "--cost",
        "rwalk:1,2,3",
        "-o",
        out,
    ];
    assert_fails(&args, &out_path, "rwalk takes a,b,c,d");
}

#[test]
fn cli_errors_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let dem = dem.to_str().unwrap();
    let out = dir.path().join("route.geojson");
    let o = out.to_str().unwrap();
    let png = dir.path().join("map.png");
    let bad_dem = write(dir.path(), "bad.asc", "ncols 2\nnrows 2\nxllcorner 0\n");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "--from",
                "1010,5010",
                "--to",
                "1290,5180",
                "--cost",
                "steep:2",
            ],
            "cannot read cost 'steep:2'",
        ),
        (
            vec![
                "--from",
                "1010,5010",
                "--to",
                "1290,5180",
                "--cost",
                "slope:1,max:120",
            ],
            "maximum slope",
        ),
        (
            vec!["--from", "10,10", "--to", "1290,5180"],
            "--from 10,10: point (10, 10) is outside the grid",
        ),
        (
            vec!["--from", "1010,5010", "--to", "1100,5170"],
            "--to 1100,5170: point (1100, 5170) lies on NODATA",
        ),
        (vec!["--from", "1010", "--to", "1290,5180"], "is not X,Y"),
        (
            vec!["--from", "1010,5010", "--to", "1290,5180", "--k", "0"],
            "k = 0",
        ),
    ];
    for (extra, expected) in cases {
        let mut args = vec!["terrain", dem];
        args.extend(extra);
        args.extend(["-o", o, "--png", png.to_str().unwrap()]);
        assert_fails(&args, &out, expected);
        assert!(!png.exists(), "{args:?} left the map");
    }
    for (args, expected) in [
        (
            vec![
                "terrain",
                bad_dem.to_str().unwrap(),
                "--from",
                "0,0",
                "--to",
                "1,1",
                "-o",
                o,
            ],
            "bad.asc: the header has no 'yllcorner'",
        ),
        (
            vec![
                "terrain",
                dem,
                "--from",
                "1010,5010",
                "--to",
                "1290,5180",
                "-o",
                "x.shp",
            ],
            "unknown output format",
        ),
        (
            vec![
                "terrain",
                dem,
                "--from",
                "1010,5010",
                "--to",
                "1290,5180",
                "-o",
                o,
                "--png",
                "m.jpg",
            ],
            "m.jpg: unknown output format",
        ),
        (
            vec![
                "terrain", "dem.xyz", "--from", "0,0", "--to", "1,1", "-o", o,
            ],
            "unknown elevation grid format",
        ),
    ] {
        let result = geotracks(&args);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(!result.status.success());
        assert!(
            stderr.contains(expected),
            "{args:?}: {stderr:?} lacks {expected:?}"
        );
        assert!(!out.exists());
    }
    let leftovers = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .count();
    assert_eq!(leftovers, 0);
}

/// A map that cannot be written used to delete the route file, even one that was there
/// before the command.
#[test]
fn a_failing_map_keeps_an_existing_route() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let route = dir.path().join("route.geojson");
    std::fs::write(&route, "old route\n").unwrap();
    let png = dir.path().join("no_such_dir").join("map.png");
    let result = geotracks(&[
        "terrain",
        dem.to_str().unwrap(),
        "--from",
        "1010,5010",
        "--to",
        "1290,5180",
        "-o",
        route.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("map.png"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&route).unwrap(), "old route\n");
}

#[test]
fn cli_reads_a_geotiff() {
    use tiff::encoder::colortype::Gray32Float;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plane.tif");
    // 20 × 20 pixels of 5 m, a plane rising 1 m per 5 m eastwards (11.3°).
    let data: Vec<f32> = (0..400).map(|i| (i % 20) as f32).collect();
    write_tiff::<Gray32Float>(
        &path,
        (20, 20),
        &data,
        Some([5.0, 5.0, 0.0]),
        Some([0.0, 0.0, 0.0, 0.0, 100.0, 0.0]),
        Some(&geo_keys(1)),
        None,
    );
    let out = dir.path().join("r.csv");
    // Sample centres: x from 2.5 to 97.5; along the slope from x = 10 to 90.
    let result = geotracks_ok(&[
        "terrain",
        path.to_str().unwrap(),
        "--from",
        "10,50",
        "--to",
        "90,50",
        "--cost",
        "slope:2",
        "-o",
        out.to_str().unwrap(),
    ]);
    let tan = 0.2f64;
    let expected = (1.0 + 2.0 * tan * tan) * 80.0 * (1.0 + tan * tan).sqrt();
    let cost = last_value(&result);
    assert!(relative(cost, expected) < 1e-6, "{cost} vs {expected}");
}

/// A GeoTIFF in UTM (EPSG:32633, 10 m pixels near x = 505 000): the route and the
/// contours name its CRS as GDAL's GeoJSON driver reads it, and print coordinates
/// without float noise (sample centres exactly; elsewhere no more than 15 significant
/// digits: 8 decimals at y = 4 600 000).
#[test]
fn routes_carry_the_grids_crs_and_tidy_coordinates() {
    use tiff::encoder::colortype::Gray32Float;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("utm.tif");
    let data: Vec<f32> = (0..400).map(|i| 100.0 + 0.3 * (i % 20) as f32).collect();
    // A GeoKey directory naming the projected CRS `code`.
    let write_utm = |code: u16| {
        let keys = [
            1u16, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, code,
        ];
        write_tiff::<Gray32Float>(
            &path,
            (20, 20),
            &data,
            Some([10.0, 10.0, 0.0]),
            Some([0.0, 0.0, 0.0, 504900.1, 4600200.7, 0.0]),
            Some(&keys),
            None,
        );
    };
    let (route, contours) = (dir.path().join("r.geojson"), dir.path().join("c.geojson"));
    let (tif, r, c) = (
        path.to_str().unwrap(),
        route.to_str().unwrap(),
        contours.to_str().unwrap(),
    );
    // Sample centres: x = 504905.1 + 10 i, y = 4600195.7 − 10 j.
    let ends = ["--from", "504905.1,4600195.7", "--to", "505085.1,4600025.7"];
    let read = |file: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap()
    };
    write_utm(32633);
    let mut args = vec!["terrain", tif];
    args.extend(ends);
    args.extend(["--cost", "tobler", "-o", r, "--contours", c]);
    geotracks_ok(&args);
    for file in [&route, &contours] {
        let json = read(file);
        assert_eq!(
            json["crs"]["properties"]["name"],
            "urn:ogc:def:crs:EPSG::32633",
            "{}",
            file.display()
        );
        for feature in json["features"].as_array().unwrap() {
            for point in feature["geometry"]["coordinates"].as_array().unwrap() {
                for c in point.as_array().unwrap() {
                    let printed = c.to_string();
                    let decimals = printed.split('.').nth(1).map_or(0, str::len);
                    assert!(decimals <= 8, "{printed} in {}", file.display());
                }
            }
        }
    }
    let first = &read(&route)["features"][0]["geometry"]["coordinates"][0];
    assert_eq!(first[0].to_string(), "504905.1");
    assert_eq!(first[1].to_string(), "4600195.7");
    // Without a code (user-defined CRS), no crs member.
    write_utm(32767);
    let mut args = vec!["terrain", tif];
    args.extend(ends);
    args.extend(["-o", r]);
    geotracks_ok(&args);
    assert!(read(&route).get("crs").is_none());
}

#[test]
fn contours_lie_at_their_cost_on_a_flat_grid_and_bad_levels_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    // Flat: the cost from the start is the map distance, so each contour is a circle.
    let mut text = String::from(
        "ncols 21\nnrows 21\nxllcorner 0\nyllcorner 0\ncellsize 1\nnodata_value -9999\n",
    );
    for _ in 0..21 {
        text.push_str(&vec!["5"; 21].join(" "));
        text.push('\n');
    }
    let dem = write(dir.path(), "flat.asc", &text);
    let dem = dem.to_str().unwrap();
    let route = dir.path().join("route.geojson");
    let contours = dir.path().join("contours.geojson");
    geotracks_ok(&[
        "terrain",
        dem,
        "--from",
        "10.5,10.5",
        "--to",
        "18.5,3.5",
        "-o",
        route.to_str().unwrap(),
        "--contours",
        contours.to_str().unwrap(),
        "--contour-at",
        "2,5.5,8",
    ]);
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&contours).unwrap()).unwrap();
    let features = value["features"].as_array().unwrap();
    let mut levels = Vec::new();
    for feature in features {
        let level = feature["properties"]["level"].as_f64().unwrap();
        levels.push(level);
        for p in feature["geometry"]["coordinates"].as_array().unwrap() {
            let p: Vec<f64> = p
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let r = (p[0] - 10.5).hypot(p[1] - 10.5);
            assert!(
                (r - level).abs() < 1e-9 * level,
                "{p:?} at {r}, level {level}"
            );
            assert!((p[2] - 5.0).abs() < 1e-12);
        }
    }
    // Inside the grid every circle closes: one line per level.
    levels.sort_by(f64::total_cmp);
    assert_eq!(levels, [2.0, 5.5, 8.0]);
    assert!(features.iter().all(|f| f["properties"]["closed"] == true));

    for (args, message) in [
        (vec!["--contour-at", "1,nan"], "levels must be finite"),
        (vec!["--contour-levels", "0"], "at least one level"),
    ] {
        let fresh = dir.path().join("fresh.geojson");
        let c = dir.path().join("c.geojson");
        let mut all = vec![
            "terrain",
            dem,
            "--from",
            "10.5,10.5",
            "--to",
            "18.5,3.5",
            "-o",
            fresh.to_str().unwrap(),
            "--contours",
            c.to_str().unwrap(),
        ];
        all.extend(args);
        assert_fails(&all, &fresh, message);
        assert!(!c.exists());
    }
}

#[test]
fn verbose_routes_say_where_the_time_went() {
    let dir = tempfile::tempdir().unwrap();
    let dem = hill_asc(dir.path());
    let (dem, json) = (dem.to_str().unwrap(), dir.path().join("route.geojson"));
    let route = |extra: &[&str]| {
        let mut args = vec![
            "terrain",
            dem,
            "--from",
            "1010,5010",
            "--to",
            "1290,5180",
            "-v",
            "-o",
        ];
        args.push(json.to_str().unwrap());
        args.extend_from_slice(extra);
        String::from_utf8_lossy(&geotracks_ok(&args).stderr).into_owned()
    };
    // A route alone runs on a window: its meshing, metric and solver are timed.
    let window = route(&[]);
    let line = window
        .lines()
        .find(|l| l.trim_start().starts_with("grid read"))
        .unwrap_or_else(|| panic!("no timing line in {window:?}"));
    let seconds: Vec<f64> = line
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect();
    assert_eq!(seconds.len(), 5, "{line}");
    assert!(seconds.iter().all(|s| *s >= 0.0 && s.is_finite()), "{line}");
    for part in [
        "window cut",
        "metric",
        "solver",
        "path traced and straightened",
    ] {
        assert!(line.contains(part), "{line} lacks {part}");
    }
    // With a map the route still runs on its window, and the whole grid's cost field
    // (which the map draws) is timed too.
    let png = dir.path().join("map.png");
    let whole = route(&["--png", png.to_str().unwrap()]);
    let line = whole
        .lines()
        .find(|l| l.trim_start().starts_with("grid read"))
        .unwrap_or_else(|| panic!("no timing line in {whole:?}"));
    assert!(
        line.contains("window") && line.contains("path traced") && line.contains("cost field"),
        "{line}"
    );
}

/// A rough `ncols` × `nrows` grid, 90 m apart, as an ESRI ASCII grid: value noise of
/// five octaves (two folded into ridges) and three cliffs, in whole metres as real
/// elevation models store them (which makes many graph paths cost the same to the bit
/// under the walking times).
fn rough_asc(dir: &Path, ncols: usize, nrows: usize, seed: u64) -> std::path::PathBuf {
    let mut state = seed | 1;
    let next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let relief = RoughRelief::new(next, 4, (30.0, 60.0));
    let mut text = format!(
        "ncols {ncols}\nnrows {nrows}\nxllcorner 0\nyllcorner 0\ncellsize 90\nnodata_value -9999\n"
    );
    for r in 0..nrows {
        let v = (nrows - 1 - r) as f64 / (nrows - 1) as f64;
        let row: Vec<String> = (0..ncols)
            .map(|c| {
                let u = c as f64 / (ncols - 1) as f64;
                let z = relief.height(u, v, 400.0);
                format!("{}", z.round())
            })
            .collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    write(dir, "rough.asc", &text)
}

/// The route file is the same, to the byte, with or without a map or contours: they
/// need the cost from the start over the whole grid, a run of its own that never
/// changes the route (the route's search once depended on them, and among the graph
/// paths of equal cost kept another, which straightened up to 0.1 % dearer or cheaper
/// here).
#[test]
fn a_map_or_contours_never_change_the_route() {
    let dir = tempfile::tempdir().unwrap();
    let dem = rough_asc(dir.path(), 200, 170, 17);
    let dem = dem.to_str().unwrap();
    let (png, contours) = (dir.path().join("map.png"), dir.path().join("c.geojson"));
    let (png, contours) = (png.to_str().unwrap(), contours.to_str().unwrap());
    let map = ["--png", png];
    let lines = ["--contours", contours, "--contour-at", "5000"];
    let cases = [
        ("naismith", "1000,2000", "16500,13000", &lines[..]),
        ("uphill:10", "17000,1500", "2500,14000", &map[..]),
        ("rwalk", "1000,2000", "16500,13000", &map[..]),
        ("tobler", "17000,1500", "2500,14000", &map[..]),
    ];
    for (cost, from, to, extra) in cases {
        let route = |name: &str, extra: &[&str]| {
            let file = dir.path().join(name);
            let mut args = vec![
                "terrain",
                dem,
                "--from",
                from,
                "--to",
                to,
                "--cost",
                cost,
                "-o",
                file.to_str().unwrap(),
            ];
            args.extend_from_slice(extra);
            geotracks_ok(&args);
            std::fs::read_to_string(file).unwrap()
        };
        let alone = route("alone.geojson", &[]);
        let with_more = route("more.geojson", extra);
        assert!(
            alone == with_more,
            "{cost} {from} → {to}: {extra:?} changed the route"
        );
    }
}
