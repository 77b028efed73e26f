//! The command-line tool end to end: outputs, and bad input that must fail with one
//! clear line, a non-zero exit, and no output file.

// Tests aside from the function-length rule (clippy.toml): a scenario reads best whole.
#![allow(clippy::too_many_lines)]

mod support;

use std::path::{Path, PathBuf};
use support::{assert_fails, geotracks, geotracks_ok, last_value};

const SPOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/spot.obj");

/// One number per line.
fn read_values(path: &Path) -> Vec<f64> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect()
}

/// The JSON file at `path`.
fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

fn square_obj(dir: &Path) -> PathBuf {
    let path = dir.join("square.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    path
}

#[test]
fn writes_txt_csv_ply_and_stats() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let mesh = mesh.to_str().unwrap();
    let txt = dir.path().join("d.txt");
    let stats = dir.path().join("stats.json");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--k",
        "3",
        "-o",
        txt.to_str().unwrap(),
        "--stats",
        stats.to_str().unwrap(),
    ]);
    let values = read_values(&txt);
    assert_eq!(values.len(), 4);
    assert_eq!(values[0], 0.0);
    assert!((values[2] - 2f64.sqrt()).abs() < 1e-12);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    for key in [
        "vertices",
        "faces",
        "steiner_points",
        "k",
        "method",
        "setup_seconds",
        "propagate_seconds",
        "pushes",
        "distance_tests",
        "setup_distance_tests",
    ] {
        assert!(json.get(key).is_some(), "stats lack {key}: {json}");
    }
    assert_eq!(json["method"], "wave");
    assert_eq!(json["vertices"], 4);

    let csv = dir.path().join("d.csv");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "1",
        "--source",
        "3",
        "-o",
        csv.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("vertex,distance"));
    let row = |line: Option<&str>| {
        let (v, d) = line.unwrap().split_once(',').unwrap();
        (v.parse::<u32>().unwrap(), d.parse::<f64>().unwrap())
    };
    let (v, d) = row(lines.next());
    assert!(v == 0 && (d - 1.0).abs() < 1e-12, "{v},{d}");
    assert_eq!(row(lines.next()), (1, 0.0));

    let ply = dir.path().join("d.ply");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--method",
        "dijkstra",
        "-o",
        ply.to_str().unwrap(),
    ]);
    let back = geotracks::mesh::io::read_mesh(&ply).unwrap();
    assert_eq!(back.positions().len(), 4);
}

#[test]
fn unreachable_vertices_are_inf_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("two.obj");
    std::fs::write(
        &mesh,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let txt = dir.path().join("d.txt");
    let out = geotracks_ok(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "-o",
        txt.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning: 3 vertices are not reachable"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&txt).unwrap();
    assert_eq!(text.lines().filter(|l| *l == "inf").count(), 3);

    let sources = dir.path().join("s.txt");
    std::fs::write(
        &sources, "0 3
",
    )
    .unwrap();
    let csv = dir.path().join("m.csv");
    let out = geotracks_ok(&[
        "matrix",
        mesh.to_str().unwrap(),
        "--sources",
        sources.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning: 6 (source, target) pairs are not connected"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.matches("inf").count(), 6);
}

#[test]
fn density_and_tensor_files() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let mesh = mesh.to_str().unwrap();
    let density = dir.path().join("rho.txt");
    std::fs::write(&density, "2\n2\n2\n2\n").unwrap();
    let out_path = dir.path().join("d.txt");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--density",
        density.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
    ]);
    let d = read_values(&out_path);
    assert!((d[1] - 2.0).abs() < 1e-12);

    let tensor = dir.path().join("m.txt");
    std::fs::write(&tensor, "4 0 0 1 0 1\n4 0 0 1 0 1\n").unwrap();
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--tensor",
        tensor.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
    ]);
    let d = read_values(&out_path);
    assert!((d[1] - 2.0).abs() < 1e-12, "{d:?}"); // along x: sqrt(4)
    assert!((d[3] - 1.0).abs() < 1e-12, "{d:?}"); // along y: sqrt(1)

    // Per vertex: 1 at the left edge, 9 along x at the right (vertices 1 and 2).
    let field = dir.path().join("f.txt");
    std::fs::write(
        &field,
        "1 0 0 1 0 1\n9 0 0 1 0 1\n9 0 0 1 0 1\n1 0 0 1 0 1\n",
    )
    .unwrap();
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--tensor-field",
        field.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
    ]);
    let d = read_values(&out_path);
    // Along the bottom edge: ∫₀¹ sqrt(1 + 8t) dt = 26 / 12.
    assert!((d[1] - 26.0 / 12.0).abs() < 1e-12, "{d:?}");
    assert!((d[3] - 1.0).abs() < 1e-12, "{d:?}"); // along the left edge: 1

    // A field that is constant on every face flattens them: the wavefront engine runs,
    // at its default k (as Python's MeshSolver picks it); one that varies, the
    // Steiner graph at its own.
    let constant = dir.path().join("c.txt");
    std::fs::write(&constant, "4 0 0 1 0 1\n".repeat(4)).unwrap();
    for (file, expected) in [(&constant, "method wave"), (&field, "method tracks")] {
        let out = geotracks_ok(&[
            "distance",
            mesh,
            "--source",
            "0",
            "--tensor-field",
            file.to_str().unwrap(),
            "-o",
            out_path.to_str().unwrap(),
            "-v",
        ]);
        let text = String::from_utf8_lossy(&out.stderr).to_string()
            + &String::from_utf8_lossy(&out.stdout);
        let k = if expected == "method wave" {
            "k = 2;"
        } else {
            "k = 5;"
        };
        assert!(text.contains(expected) && text.contains(k), "{text}");
    }
}

#[test]
fn bad_input_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let mesh = mesh.to_str().unwrap();
    let out = dir.path().join("out.txt");
    let o = out.to_str().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    // Bad mesh files: (file, what the error must say).
    let meshes = [
        ("/nonexistent/m.obj".to_string(), "/nonexistent/m.obj"),
        (write("empty.obj", ""), "empty"),
        (write("mesh.xyz", "1 2 3\n"), "unknown mesh format"),
        (write("t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n"), "t.off:"),
        (
            write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
            "vertex 1",
        ),
        (
            write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
            "range.obj",
        ),
        (
            write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"),
            "no usable face",
        ),
    ];
    for (file, expected) in &meshes {
        assert_fails(
            &["distance", file, "--source", "0", "-o", o],
            &out,
            expected,
        );
    }
    // Bad options and metric files on a good mesh: (extra arguments, expected).
    let zero = write("zero.txt", "1\n1\n0\n1\n");
    let short = write("short.txt", "1\n1\n1\n");
    let word = write("word.txt", "1\n1\nabc\n1\n");
    let indefinite = write("ind.txt", "1 0 0 1 0 1\n1 5 0 1 0 1\n");
    let one = write("one.txt", "1 0 0 1 0 1\n");
    let field = write(
        "field.txt",
        "1 0 0 1 0 1\n1 0 0 1 0 1\n1 0 0 -1 0 1\n1 0 0 1 0 1\n",
    );
    let options: [(&[&str], &str); 11] = [
        (&["--source", "9"], "source vertex 9 is out of range"),
        (&["--source", "0", "--k", "0"], "k = 0"),
        (
            &["--source", "0", "--method", "fast"],
            "unknown method 'fast'",
        ),
        (&["--source", "0", "--density", &zero], "zero.txt:3"),
        (&["--source", "0", "--density", &short], "expected 4 values"),
        (&["--source", "0", "--density", &word], "word.txt:3"),
        (&["--source", "0", "--tensor", &indefinite], "ind.txt:2"),
        (&["--source", "0", "--tensor", &one], "expected 2 tensors"),
        (&["--source", "0", "--tensor-field", &field], "field.txt:3"),
        (
            &["--source", "0", "--tensor-field", &one],
            "expected 4 values (one per vertex)",
        ),
        (
            &["--source", "0", "--tensor", &one, "--tensor-field", &one],
            "cannot be used with",
        ),
    ];
    for (extra, expected) in options {
        let mut args = vec!["distance", mesh];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", o]);
        assert_fails(&args, &out, expected);
    }
    let bad_out = dir.path().join("out.vtk");
    assert_fails(
        &[
            "distance",
            mesh,
            "--source",
            "0",
            "-o",
            bad_out.to_str().unwrap(),
        ],
        &bad_out,
        "unknown output format",
    );
}

#[test]
fn a_failed_run_keeps_an_existing_output() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let out = dir.path().join("keep.txt");
    std::fs::write(&out, "old\n").unwrap();
    let o = geotracks(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "7",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
}

/// A command's outputs are all or nothing: a bad second output (here `--stats` naming
/// a directory) used to fail after the main output had replaced the old file.
#[test]
fn a_bad_second_output_keeps_the_first_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let out = dir.path().join("keep.txt");
    std::fs::write(&out, "old\n").unwrap();
    let stats = dir.path().join("stats.json");
    std::fs::create_dir(&stats).unwrap();
    let o = geotracks(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "-o",
        out.to_str().unwrap(),
        "--stats",
        stats.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("stats.json: exists and is not a file"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
    assert_no_temporary_files(dir.path());
}

/// `-o` naming an input overwrote it.
#[test]
fn an_output_that_is_an_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let density = dir.path().join("rho.txt");
    std::fs::write(&density, "1\n1\n1\n1\n").unwrap();
    let sources = dir.path().join("s.csv");
    std::fs::write(&sources, "0\n").unwrap();
    let d = density.to_str().unwrap();
    let s = sources.to_str().unwrap();
    let m = mesh.to_str().unwrap();
    for args in [
        vec!["distance", m, "--source", "0", "--density", d, "-o", d],
        vec!["matrix", m, "--sources", s, "-o", s],
    ] {
        let o = geotracks(&args);
        assert!(!o.status.success(), "{args:?}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains("is also an input"), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read_to_string(&density).unwrap(), "1\n1\n1\n1\n");
    assert_eq!(std::fs::read_to_string(&sources).unwrap(), "0\n");
}

/// A read-only output file was replaced by the rename, whatever its mode.
#[test]
fn a_read_only_output_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let out = dir.path().join("locked.txt");
    std::fs::write(&out, "old\n").unwrap();
    let mut perms = std::fs::metadata(&out).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&out, perms).unwrap();
    let o = geotracks(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("locked.txt: the file is read-only"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
}

/// An output that cannot be created is reported by its own name: the error used to
/// end with `at path "…/.geotracks-XXXX.tmp"`.
#[test]
fn errors_name_the_target_not_the_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let out = dir.path().join("missing").join("d.txt");
    let o = geotracks(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("d.txt"), "{stderr}");
    assert!(!stderr.contains(".geotracks-"), "{stderr}");
}

/// Costs print as floats, never as 300-digit integers (a density of 1e300 made every
/// distance a line of 301 digits).
#[test]
fn huge_costs_print_in_scientific_notation() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let density = dir.path().join("rho.txt");
    std::fs::write(&density, "1e300\n1e300\n1e300\n1e300\n").unwrap();
    let out = dir.path().join("d.txt");
    let o = geotracks_ok(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "--density",
        density.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--stats",
        dir.path().join("S.JSON").to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let values = read_values(&out);
    assert_eq!(values[1], 1e300);
    for line in std::fs::read_to_string(&out).unwrap().lines() {
        assert!(line.len() < 30, "{line}");
    }
    let path = dir.path().join("p.csv");
    let o = geotracks_ok(&[
        "path",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "--target",
        "2",
        "--density",
        density.to_str().unwrap(),
        "-o",
        path.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.lines().all(|l| l.len() < 120), "{stdout}");
    assert!((last_value(&o) / (2f64.sqrt() * 1e300) - 1.0).abs() < 1e-12);
}

/// A tensor with a NaN entry is "not finite", on its line, not "not positive-definite
/// [NaN …]".
#[test]
fn a_nan_tensor_is_reported_as_not_finite() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let tensor = dir.path().join("m.txt");
    std::fs::write(&tensor, "1 0 0 1 0 1\nNaN 0 0 1 0 1\n").unwrap();
    let out = dir.path().join("d.txt");
    assert_fails(
        &[
            "distance",
            mesh.to_str().unwrap(),
            "--source",
            "0",
            "--tensor",
            tensor.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        &out,
        "m.txt:2: tensor of face 1 is not finite",
    );
}

/// Usage errors (clap) exit with 2, every other error with 1, as the guide's Command line page says.
#[test]
fn usage_errors_exit_2_and_other_errors_1() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let m = mesh.to_str().unwrap();
    let usage = geotracks(&["distance", m, "-o", "d.txt"]); // no --source
    assert_eq!(usage.status.code(), Some(2));
    let usage = geotracks(&["distance", m, "--source", "0", "--bogus", "-o", "d.txt"]);
    assert_eq!(usage.status.code(), Some(2));
    let out = dir.path().join("d.txt");
    let bad = geotracks(&["distance", m, "--source", "99", "-o", out.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(1));
}

/// No `.geotracks-*` file (temporary output or backup) in `dir`.
fn assert_no_temporary_files(dir: &Path) {
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".geotracks-"))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn info_reports_non_manifold_edges() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("book.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 0 0 1\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 9 9 9\nf 1 2 3\nf 1 2 4\nf 1 2 5\nf 1 3 3\n",
    )
    .unwrap();
    let out = geotracks_ok(&["info", path.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("non-manifold edges    1 (max faces on one edge: 3)"),
        "{text}"
    );
    assert!(text.contains("degenerate faces      1"), "{text}");
    assert!(text.contains("unreferenced vertices 1"), "{text}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("dropped 1 degenerate face"));
}

#[test]
fn demo_writes_a_coloured_ply() {
    let dir = tempfile::tempdir().unwrap();
    let out_path = dir.path().join("spot.ply");
    let out = geotracks_ok(&["demo", "-o", out_path.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("wrote"), "{stdout}");
    let mesh = geotracks::mesh::io::read_mesh(&out_path).unwrap();
    let spot = geotracks::mesh::io::read_mesh(SPOT).unwrap();
    assert_eq!(mesh.positions().len(), spot.positions().len());
    // And its picture beside it, said where.
    let png = dir.path().join("spot.png");
    assert!(stdout.contains(&png.display().to_string()), "{stdout}");
    assert_eq!(png_size(&png), (1024, 768));
}

/// The demo's copy of Spot (inside the CLI crate, so that it can be published) is the
/// library's test mesh.
#[test]
fn the_demo_mesh_is_the_tests_spot() {
    let library = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/spot.obj");
    match std::fs::read(library) {
        Ok(bytes) => assert!(
            bytes == std::fs::read(SPOT).unwrap(),
            "cli/data/spot.obj differs"
        ),
        // A published crate has no library tests beside it.
        Err(_) => println!("skipped: {library} not found"),
    }
}

#[test]
fn matrix_writes_rows_per_source() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let mesh = mesh.to_str().unwrap();
    let sources = dir.path().join("sources.txt");
    std::fs::write(&sources, "0, 2\n# comment\n1\n").unwrap();
    let targets = dir.path().join("targets.txt");
    std::fs::write(&targets, "3 1\n").unwrap();
    let out = dir.path().join("m.csv");
    geotracks_ok(&[
        "matrix",
        mesh,
        "--sources",
        sources.to_str().unwrap(),
        "--targets",
        targets.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "source,3,1");
    let row = |l: &str| -> Vec<f64> { l.split(',').map(|x| x.parse().unwrap()).collect() };
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    assert!(close(&row(lines[1]), &[0.0, 1.0, 1.0]), "{}", lines[1]);
    assert!(close(&row(lines[2]), &[2.0, 1.0, 1.0]), "{}", lines[2]);
    assert!(
        close(&row(lines[3]), &[1.0, 2f64.sqrt(), 0.0]),
        "{}",
        lines[3]
    );
    assert_eq!(lines.len(), 4);

    // Every vertex as a column when no targets are given.
    geotracks_ok(&[
        "matrix",
        mesh,
        "--sources",
        sources.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .starts_with("source,0,1,2,3\n"));

    let bad = dir.path().join("bad.txt");
    std::fs::write(&bad, "0\n7\n").unwrap();
    let out2 = dir.path().join("m2.csv");
    assert_fails(
        &[
            "matrix",
            mesh,
            "--sources",
            bad.to_str().unwrap(),
            "-o",
            out2.to_str().unwrap(),
        ],
        &out2,
        "bad.txt:2: vertex 7 is out of range",
    );
    let out3 = dir.path().join("m3.txt");
    assert_fails(
        &[
            "matrix",
            mesh,
            "--sources",
            sources.to_str().unwrap(),
            "-o",
            out3.to_str().unwrap(),
        ],
        &out3,
        "m3.txt: unknown output format (expected .csv)",
    );
    // The extension in any case: `OUT.CSV` was refused.
    let upper = dir.path().join("M.CSV");
    geotracks_ok(&[
        "matrix",
        mesh,
        "--sources",
        sources.to_str().unwrap(),
        "-o",
        upper.to_str().unwrap(),
    ]);
    assert!(upper.exists());
}

/// A flat `n` × `n` grid of unit squares in the plane z = 0: vertex `j * (n + 1) + i` is
/// at (i, j), and square (i, j) is faces `2 (j n + i)` (corners (i, j), (i + 1, j),
/// (i + 1, j + 1)) and `2 (j n + i) + 1` (corners (i, j), (i + 1, j + 1), (i, j + 1)).
fn grid_obj(dir: &Path, n: usize) -> PathBuf {
    let id = |i: usize, j: usize| j * (n + 1) + i + 1; // 1-based, as OBJ counts
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            text += &format!("v {i} {j} 0\n");
        }
    }
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    let path = dir.join("grid.obj");
    std::fs::write(&path, text).unwrap();
    path
}

/// The points of an OBJ polyline, checking its shape: `v` lines, then one `l` line
/// through all of them in order.
fn read_obj_polyline(path: &Path) -> Vec<[f64; 3]> {
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let (l, vs) = lines.split_last().unwrap();
    let points: Vec<[f64; 3]> = vs
        .iter()
        .map(|line| {
            let xyz: Vec<f64> = line
                .strip_prefix("v ")
                .unwrap_or_else(|| panic!("not a v line: {line:?}"))
                .split(' ')
                .map(|x| x.parse().unwrap())
                .collect();
            xyz.try_into().unwrap()
        })
        .collect();
    assert!(points.len() >= 2, "{text}");
    let order: Vec<String> = (1..=points.len()).map(|i| i.to_string()).collect();
    assert_eq!(*l, format!("l {}", order.join(" ")), "{text}");
    points
}

/// The rows of a path CSV: position and surface point; checks the header.
fn read_csv_path(path: &Path) -> Vec<([f64; 3], geotracks::SurfacePoint)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,point"));
    lines
        .map(|line| {
            let mut fields = line.splitn(4, ',');
            let xyz = [0; 3].map(|_| fields.next().unwrap().parse::<f64>().unwrap());
            // A face point's commas are quoted.
            let point = fields.next().unwrap().trim_matches('"');
            (xyz, point.parse().unwrap())
        })
        .collect()
}

fn polyline_length(points: &[[f64; 3]]) -> f64 {
    points
        .windows(2)
        .map(|w| {
            let d = [0, 1, 2].map(|i| w[1][i] - w[0][i]);
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .sum()
}

fn close_to(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
}

#[test]
fn path_writes_obj_and_csv_from_target_to_source() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = grid_obj(dir.path(), 4);
    let mesh = mesh.to_str().unwrap();
    let obj = dir.path().join("p.obj");
    // From vertex 9 at (4, 1) to vertex 0 at the origin: the path crosses faces.
    let out = geotracks_ok(&[
        "path",
        mesh,
        "--source",
        "0",
        "--target",
        "9",
        "-o",
        obj.to_str().unwrap(),
    ]);
    let length = last_value(&out);
    let points = read_obj_polyline(&obj);
    assert!(close_to(points[0], [4.0, 1.0, 0.0]), "{points:?}");
    assert!(close_to(*points.last().unwrap(), [0.0; 3]), "{points:?}");
    assert!((length - polyline_length(&points)).abs() < 1e-9, "{length}");
    // Flat and convex: the geodesic is the straight segment.
    assert!((length - 17f64.sqrt()).abs() < 1e-6, "{length}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    // The default engine traces along its waves, not through the Steiner graph.
    assert!(
        stdout.contains("traced length") && stdout.contains("along the waves"),
        "{stdout}"
    );

    let csv = dir.path().join("p.csv");
    let out = geotracks_ok(&[
        "path",
        mesh,
        "--source",
        "0",
        "--target",
        "9",
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(last_value(&out), length);
    let rows = read_csv_path(&csv);
    assert_eq!(rows.len(), points.len());
    let grid = geotracks::mesh::io::read_mesh(mesh).unwrap();
    for ((xyz, point), p) in rows.iter().zip(&points) {
        assert_eq!(xyz, p);
        let at = point.position(&grid).to_array();
        assert!(close_to(*xyz, at), "{point}: {xyz:?} vs {at:?}");
    }
    assert_eq!(rows[0].1, geotracks::SurfacePoint::Vertex(9));
    assert_eq!(rows.last().unwrap().1, geotracks::SurfacePoint::Vertex(0));

    // A target that is a source: one point, a zero-length polyline, length 0 (not -0).
    let out = geotracks_ok(&[
        "path",
        mesh,
        "--source",
        "9",
        "--source",
        "0",
        "--target",
        "0",
        "-o",
        obj.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(stdout.lines().last(), Some("0"), "{stdout}");
    assert_eq!(std::fs::read_to_string(&obj).unwrap(), "v 0 0 0\nl 1 1\n");
}

#[test]
fn path_from_a_face_point_to_an_edge_point() {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = grid_obj(dir.path(), 4);
    let mesh = mesh_path.to_str().unwrap();
    let grid = geotracks::mesh::io::read_mesh(&mesh_path).unwrap();
    // The boundary edge from (4, 2) (vertex 14) to (4, 3) (vertex 19).
    let edge = (0..grid.edge_count() as u32)
        .find(|&e| grid.edge_vertices(e) == [14, 19])
        .unwrap();
    let target = format!("e:{edge}:0.25"); // at (4, 2.25)
    let source = "f:0:0.2,0.3,0.5"; // at (0.8, 0.5)
    let csv = dir.path().join("p.csv");
    let out = geotracks_ok(&[
        "path",
        mesh,
        "--source",
        source,
        "--target",
        &target,
        "-o",
        csv.to_str().unwrap(),
    ]);
    let rows = read_csv_path(&csv);
    assert_eq!(rows[0].1.to_string(), target);
    assert!(close_to(rows[0].0, [4.0, 2.25, 0.0]), "{rows:?}");
    let (xyz, point) = rows.last().unwrap();
    assert_eq!(point.to_string(), source);
    assert!(close_to(*xyz, [0.8, 0.5, 0.0]), "{rows:?}");
    let points: Vec<[f64; 3]> = rows.iter().map(|(xyz, _)| *xyz).collect();
    let length = last_value(&out);
    assert!((length - polyline_length(&points)).abs() < 1e-9, "{length}");
    let straight = (3.2f64 * 3.2 + 1.75 * 1.75).sqrt();
    assert!((length - straight).abs() < 1e-6, "{length} vs {straight}");
}

#[test]
fn distance_from_a_face_point() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let txt = dir.path().join("d.txt");
    geotracks_ok(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "f:0:0.5,0.25,0.25", // at (0.5, 0.25); face 0 is vertices 0, 1, 2
        "-o",
        txt.to_str().unwrap(),
    ]);
    let d = read_values(&txt);
    let exact = |x: f64, y: f64| ((x - 0.5f64).powi(2) + (y - 0.25f64).powi(2)).sqrt();
    // Straight within face 0.
    assert!((d[0] - exact(0.0, 0.0)).abs() < 1e-12, "{d:?}");
    assert!((d[1] - exact(1.0, 0.0)).abs() < 1e-12, "{d:?}");
    assert!((d[2] - exact(1.0, 1.0)).abs() < 1e-12, "{d:?}");
    // Through a Steiner point of the diagonal: never shorter, close.
    let e3 = exact(0.0, 1.0);
    assert!(d[3] >= e3 - 1e-12 && d[3] < e3 * 1.01, "{d:?}");
}

#[test]
fn max_distance_leaves_far_vertices_inf() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = grid_obj(dir.path(), 4);
    let mesh = mesh.to_str().unwrap();
    let full = dir.path().join("full.txt");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "-o",
        full.to_str().unwrap(),
    ]);
    let capped = dir.path().join("capped.txt");
    let out = geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--max-distance",
        "2.5",
        "-o",
        capped.to_str().unwrap(),
    ]);
    let (full, capped) = (read_values(&full), read_values(&capped));
    assert_eq!(full.len(), 25);
    let far = full.iter().filter(|&&d| d > 2.5).count();
    assert!(far > 0 && far < 25);
    for (v, (&f, &c)) in full.iter().zip(&capped).enumerate() {
        if f <= 2.5 {
            assert_eq!(c, f, "vertex {v}");
        } else {
            assert!(c.is_infinite(), "vertex {v}: {c}");
        }
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!(
            "{far} vertices are farther than --max-distance 2.5"
        )),
        "{stderr}"
    );
}

#[test]
fn voronoi_labels_each_vertex_with_its_nearest_source() {
    let dir = tempfile::tempdir().unwrap();
    let n = 4;
    let mesh = grid_obj(dir.path(), n);
    let mesh = mesh.to_str().unwrap();
    let txt = dir.path().join("d.txt");
    let voronoi = dir.path().join("v.txt");
    // Vertex 0 at the origin, and a point at (3.75, 3.5) in the far corner's square.
    let sources = [[0.0, 0.0], [3.75, 3.5]];
    let last_face = 2 * n * n - 2; // corners (3, 3), (4, 3), (4, 4)
    let face_point = format!("f:{last_face}:0.25,0.25,0.5");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "--source",
        &face_point,
        "--voronoi",
        voronoi.to_str().unwrap(),
        "-o",
        txt.to_str().unwrap(),
    ]);
    let labels: Vec<i64> = std::fs::read_to_string(&voronoi)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    assert_eq!(labels.len(), (n + 1) * (n + 1));
    assert_eq!(labels[0], 0);
    assert_eq!(labels[labels.len() - 1], 1);
    // Flat and convex: distances are Euclidean; check where one source is clearly nearer.
    for (v, &label) in labels.iter().enumerate() {
        let (x, y) = ((v % (n + 1)) as f64, (v / (n + 1)) as f64);
        let d = sources.map(|[sx, sy]| ((x - sx).powi(2) + (y - sy).powi(2)).sqrt());
        if (d[0] - d[1]).abs() > 0.1 {
            let nearest = if d[0] < d[1] { 0 } else { 1 };
            assert_eq!(label, nearest, "vertex {v} at ({x}, {y}): {d:?}");
        } else {
            assert!(label == 0 || label == 1, "vertex {v}: {label}");
        }
    }

    // Vertices no source reaches are -1.
    let two = dir.path().join("two.obj");
    std::fs::write(
        &two,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    geotracks_ok(&[
        "distance",
        two.to_str().unwrap(),
        "--source",
        "e:0:0.5",
        "--voronoi",
        voronoi.to_str().unwrap(),
        "-o",
        txt.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&voronoi).unwrap(),
        "0\n0\n0\n-1\n-1\n-1\n"
    );
}

#[test]
fn bad_surface_points_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let mesh = mesh.to_str().unwrap();
    let txt = dir.path().join("out.txt");
    let obj = dir.path().join("out.obj");
    // (--source, expected) for both commands.
    let sources = [
        ("x", "invalid value 'x' for '--source <SP>'"),
        ("f:0:1,0", "needs three barycentric coordinates"),
        ("f:2:1,0,0", "--source f:2:1,0,0: face 2 does not exist"),
        ("f:0:0.5,0.5,0.5", "--source f:0:0.5,0.5,0.5: barycentric"),
        ("e:9:0.5", "--source e:9:0.5: edge 9 does not exist"),
        ("e:0:1.5", "edge parameter t = 1.5 is outside [0, 1]"),
        ("4", "source vertex 4 is out of range"),
    ];
    for (source, expected) in sources {
        let args = ["distance", mesh, "--source", source];
        assert_fails(
            &[&args[..], &["-o", txt.to_str().unwrap()]].concat(),
            &txt,
            expected,
        );
        let args = ["path", mesh, "--source", source, "--target", "2"];
        assert_fails(
            &[&args[..], &["-o", obj.to_str().unwrap()]].concat(),
            &obj,
            expected,
        );
    }
    let targets = [
        ("f:0:0.2", "invalid value 'f:0:0.2' for '--target <SP>'"),
        ("f:7:1,0,0", "--target f:7:1,0,0: face 7 does not exist"),
        ("f:1:0.2,0.2,0.2", "--target f:1:0.2,0.2,0.2: barycentric"),
        ("9", "--target 9: vertex 9 does not exist"),
    ];
    for (target, expected) in targets {
        let args = ["path", mesh, "--source", "0", "--target", target];
        assert_fails(
            &[&args[..], &["-o", obj.to_str().unwrap()]].concat(),
            &obj,
            expected,
        );
    }
    let vtk = dir.path().join("out.vtk");
    assert_fails(
        &[
            "path",
            mesh,
            "--source",
            "0",
            "--target",
            "2",
            "-o",
            vtk.to_str().unwrap(),
        ],
        &vtk,
        "unknown output format (expected .obj or .csv)",
    );

    // A target on another component than every source.
    let two = dir.path().join("two.obj");
    std::fs::write(
        &two,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let two = two.to_str().unwrap();
    for target in ["4", "f:1:0.2,0.3,0.5"] {
        for out in [&obj, &dir.path().join("out.csv")] {
            let args = ["path", two, "--source", "0", "--source", "e:0:0.5"];
            assert_fails(
                &[
                    &args[..],
                    &["--target", target, "-o", out.to_str().unwrap()],
                ]
                .concat(),
                out,
                &format!("point {target} is not reached from any source"),
            );
        }
    }

    // --max-distance and --voronoi.
    let voronoi = dir.path().join("v.txt");
    let v = voronoi.to_str().unwrap();
    let o = txt.to_str().unwrap();
    for (extra, expected) in [
        (
            ["--max-distance", "-1"],
            "--max-distance -1: the maximum distance is -1; it must be a number >= 0",
        ),
        (["--max-distance", "nan"], "--max-distance NaN"),
        (
            ["--max-distance", "far"],
            "invalid value 'far' for '--max-distance <D>'",
        ),
    ] {
        let args = ["distance", mesh, "--source", "0", "--voronoi", v, "-o", o];
        assert_fails(&[&args[..], &extra[..]].concat(), &txt, expected);
        assert!(!voronoi.exists());
    }
    let bad = dir.path().join("v.csv");
    let args = ["distance", mesh, "--source", "f:0:0.5,0.5,0.5", "-o", o];
    assert_fails(
        &[&args[..], &["--voronoi", v]].concat(),
        &voronoi,
        "barycentric",
    );
    assert!(!txt.exists());
    let args = ["distance", mesh, "--source", "0", "-o", o];
    assert_fails(
        &[&args[..], &["--voronoi", bad.to_str().unwrap()]].concat(),
        &bad,
        "v.csv: unknown output format (expected .txt)",
    );
    assert!(!txt.exists());
}

const SHEET_FINS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/data/ma/sheet_fins.ma"
);

/// The `v` points and `l`/`p` polylines of an OBJ graph.
fn read_obj_graph(path: &Path) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let (mut points, mut lines) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let mut t = line.split_whitespace();
        match t.next() {
            Some("v") => {
                let c: Vec<f64> = t.map(|x| x.parse().unwrap()).collect();
                points.push([c[0], c[1], c[2]]);
            }
            Some("l") | Some("p") => {
                lines.push(t.map(|x| x.parse::<usize>().unwrap() - 1).collect());
            }
            _ => {}
        }
    }
    (points, lines)
}

#[test]
fn skeleton_writes_a_connected_obj_graph_and_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let (obj, ply) = (dir.path().join("skeleton.obj"), dir.path().join("fire.ply"));
    let out = geotracks_ok(&[
        "skeleton",
        SHEET_FINS,
        "--prune",
        "2%",
        "-o",
        obj.to_str().unwrap(),
        "--field",
        ply.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // The sheet with its fins and tail is one part, the separate curve another.
    assert!(stderr.contains("2 component(s)"), "{stderr}");
    let (points, lines) = read_obj_graph(&obj);
    assert!(points.len() > 10 && !lines.is_empty());
    // Polylines share their junction points: joined, they make two components.
    let mut part: Vec<usize> = (0..points.len()).collect();
    fn root(part: &mut [usize], mut v: usize) -> usize {
        while part[v] != v {
            v = part[v];
        }
        v
    }
    for line in &lines {
        for w in line.windows(2) {
            let (a, b) = (root(&mut part, w[0]), root(&mut part, w[1]));
            part[a] = b;
        }
    }
    let mut roots: Vec<usize> = (0..points.len()).map(|v| root(&mut part, v)).collect();
    roots.sort_unstable();
    roots.dedup();
    assert_eq!(roots.len(), 2);
    // The separate curve keeps at least its most significant point …
    assert!(points.iter().any(|p| p[0] >= 3.0));
    let ply_bytes = std::fs::read(&ply).unwrap();
    assert!(ply_bytes.starts_with(b"ply\n"));
    // … and, unpruned (by length, tubularity and protrusion), is in the skeleton whole;
    // the JSON graph says so (its points where the axis has them: on the axis).
    let json = dir.path().join("skeleton.json");
    let length_and_tubularity_off = |more: &[&str]| {
        let mut args = vec!["skeleton", SHEET_FINS, "--prune", "0", "--tubular", "0"];
        args.extend_from_slice(more);
        args.extend(["-o", json.to_str().unwrap()]);
        geotracks_ok(&args);
        read_json(&json)
    };
    let unpruned =
        |more: &[&str]| length_and_tubularity_off(&[&["--protrusion", "0"], more].concat());
    let graph = unpruned(&["--on-axis"]);
    let positions: Vec<Vec<f64>> = graph["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| serde_json::from_value(p["position"].clone()).unwrap())
        .collect();
    for p in [[3.0, 0.0, 0.0], [3.2, 0.0, 0.0], [3.4, 0.1, 0.0]] {
        assert!(positions.contains(&p.to_vec()), "{p:?} missing");
    }
    assert_eq!(graph["components"], 2);
    assert_eq!(graph["cycles"], 0);
    // Pruned by protrusion alone, branches go and the pieces and cycles stay.
    let covered = length_and_tubularity_off(&["--protrusion", "1e9"]);
    assert!(
        covered["points"].as_array().unwrap().len() < graph["points"].as_array().unwrap().len()
    );
    assert_eq!(covered["components"], 2);
    assert_eq!(covered["cycles"], 0);
    // Centred (the default), every point has a radius, the separate curve's too (its
    // balls are not the sheets': they gave it 0).
    for p in covered["points"].as_array().unwrap() {
        assert!(p["radius"].as_f64().unwrap() > 0.0, "{p}");
    }
    // A picture of it, of the size asked for; a bad view leaves no file.
    let png = dir.path().join("skeleton.png");
    geotracks_ok(&[
        "skeleton",
        SHEET_FINS,
        "-o",
        json.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
        "--size",
        "400x300",
    ]);
    assert_eq!(png_size(&png), (400, 300));
    std::fs::remove_file(&png).unwrap();
    assert_fails(
        &[
            "skeleton",
            SHEET_FINS,
            "-o",
            json.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
            "--view",
            "sideways",
        ],
        &png,
        "not a view",
    );
    assert!(graph["points"][0]["radius"].as_f64().unwrap() > 0.0);
    assert_eq!(
        graph["edges"].as_array().unwrap().len() + 2,
        positions.len()
    );
    // Centred: the same graph's shape, its points at the centre of the cross-section.
    let centred = unpruned(&["--centred"]);
    assert_eq!(centred["components"], 2);
    assert_eq!(centred["cycles"], 0);
    assert_eq!(centred["tips"], graph["tips"]);
}

#[test]
fn skeleton_bad_input_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("skeleton.obj");
    let o = obj.to_str().unwrap();
    let curves = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/ma/curves.ma");
    let ply = dir.path().join("fire.ply");
    let txt = dir.path().join("skeleton.txt");
    assert_fails(
        &["skeleton", SHEET_FINS, "-o", txt.to_str().unwrap()],
        &txt,
        "unknown output format",
    );
    assert_fails(
        &["skeleton", SHEET_FINS, "--prune=-1", "-o", o],
        &obj,
        "--prune",
    );
    assert_fails(
        &["skeleton", SHEET_FINS, "--tubular=-0.5", "-o", o],
        &obj,
        "--tubular",
    );
    for bad in ["--protrusion=-0.5", "--protrusion=nan"] {
        assert_fails(
            &["skeleton", SHEET_FINS, bad, "-o", o],
            &obj,
            "--protrusion",
        );
    }
    assert_fails(
        &["skeleton", SHEET_FINS, "--k", "0", "-o", o],
        &obj,
        "k = 0",
    );
    assert_fails(
        &[
            "skeleton",
            curves,
            "-o",
            o,
            "--field",
            ply.to_str().unwrap(),
        ],
        &obj,
        "no sheet",
    );
    assert!(!ply.exists());
    let closed = dir.path().join("closed.ma");
    std::fs::write(
        &closed,
        "4 0 4\nv 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nv 0 0 1 1\nf 0 2 1\nf 0 1 3\nf 1 2 3\nf 0 3 2\n",
    )
    .unwrap();
    // A closed axis (a cavity's sheet) has no border to burn from: punctured, it
    // thins to one point, but has no grassfire field to write.
    assert_fails(
        &[
            "skeleton",
            closed.to_str().unwrap(),
            "-o",
            o,
            "--field",
            ply.to_str().unwrap(),
        ],
        &obj,
        "no grassfire field",
    );
    geotracks_ok(&["skeleton", closed.to_str().unwrap(), "-o", o]);
    let (points, _) = read_obj_graph(&obj);
    assert_eq!(points.len(), 1);
    // Curves alone are their own skeleton, unpruned; pruned, they burn from their tips
    // (at 5 % of the diagonal, a star of short branches burns to its longest path).
    geotracks_ok(&["skeleton", curves, "--prune", "0", "-o", o]);
    let (points, lines) = read_obj_graph(&obj);
    assert_eq!((points.len(), lines.len()), (4, 3));
    geotracks_ok(&["skeleton", curves, "--prune", "inf", "-o", o]);
    let (points, _) = read_obj_graph(&obj);
    assert_eq!(points.len(), 1);
}

/// A square sheet 3 × 3 with its middle cell cut out: the hole is a tunnel of the solid
/// when the balls are small, and no tunnel when they fill it, which the JSON and the
/// summary say.
#[test]
fn skeleton_opens_a_hole_its_balls_fill() {
    let dir = tempfile::tempdir().unwrap();
    let id = |i: u32, j: u32| j * 4 + i;
    let cells: Vec<(u32, u32)> = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .filter(|&c| c != (1, 1))
        .collect();
    for (radius, cycles, opened) in [(1.0, 0, 1), (0.2, 1, 0)] {
        let mut text = format!("16 0 {}\n", 2 * cells.len());
        for j in 0..4 {
            for i in 0..4 {
                text += &format!("v {i} {j} 0 {radius}\n");
            }
        }
        for &(i, j) in &cells {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
        let axis = dir.path().join("ring.ma");
        std::fs::write(&axis, text).unwrap();
        let json = dir.path().join("ring.json");
        let out = geotracks_ok(&[
            "skeleton",
            axis.to_str().unwrap(),
            "-o",
            json.to_str().unwrap(),
        ]);
        let graph = read_json(&json);
        assert_eq!(
            (graph["cycles"].clone(), graph["opened_cycles"].clone()),
            (cycles.into(), opened.into()),
            "balls of radius {radius}"
        );
        let said = String::from_utf8_lossy(&out.stderr) + String::from_utf8_lossy(&out.stdout);
        assert_eq!(said.contains("opened, no tunnel"), opened > 0, "{said}");
    }
}

/// Trimmed tips (the default, `--trim-tips` too) are branches cut back from their tips
/// that keep the graph's shape: the same components, cycles and tips as with
/// `--keep-tips`, a shorter skeleton; the two options exclude each other.
#[test]
fn skeleton_trim_tips_shortens_and_keeps_the_graph() {
    let dir = tempfile::tempdir().unwrap();
    let axis = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/ma/sheet_fins.ma"
    );
    let run = |extra: &[&str]| {
        let json = dir.path().join("s.json");
        let mut args = vec!["skeleton", axis, "-o", json.to_str().unwrap()];
        args.extend_from_slice(extra);
        geotracks_ok(&args);
        let graph = read_json(&json);
        let position = |i: &serde_json::Value| -> Vec<f64> {
            serde_json::from_value(
                graph["points"][i.as_u64().unwrap() as usize]["position"].clone(),
            )
            .unwrap()
        };
        let length: f64 = graph["edges"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| {
                let (a, b) = (position(&e[0]), position(&e[1]));
                a.iter()
                    .zip(&b)
                    .map(|(x, y)| (x - y).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum();
        let counts = ["components", "cycles", "tips"].map(|k| graph[k].clone());
        (counts, length)
    };
    let (counts, length) = run(&["--keep-tips"]);
    let (trimmed_counts, trimmed) = run(&["--trim-tips"]);
    assert_eq!(trimmed_counts, counts);
    assert!(trimmed < length - 0.05, "{trimmed} against {length}");
    assert_eq!(run(&[]), (trimmed_counts, trimmed), "trimmed by default");
    let both = dir.path().join("both.obj");
    let args = ["skeleton", axis, "--trim-tips", "--keep-tips", "-o"];
    assert_fails(
        &[&args[..], &[both.to_str().unwrap()]].concat(),
        &both,
        "cannot be used with",
    );
}

/// Every command's `--help` ends with examples (and so does the tool's).
#[test]
fn every_help_ends_with_examples() {
    for command in [
        None,
        Some("distance"),
        Some("path"),
        Some("matrix"),
        Some("skeleton"),
        Some("terrain"),
        Some("info"),
        Some("demo"),
    ] {
        let mut args: Vec<&str> = command.into_iter().collect();
        args.push("--help");
        let out = geotracks_ok(&args);
        let help = String::from_utf8_lossy(&out.stdout);
        let (_, examples) = help
            .rsplit_once("Examples:\n")
            .unwrap_or_else(|| panic!("{args:?}: no examples in {help}"));
        let lines: Vec<&str> = examples.lines().filter(|l| !l.trim().is_empty()).collect();
        assert!(!lines.is_empty(), "{args:?}");
        assert!(
            lines.iter().all(|l| l.starts_with("  geotracks ")),
            "{args:?}: {lines:?}"
        );
    }
}

/// `--quiet` leaves stderr empty on success; `--verbose` adds the counters.
#[test]
fn quiet_and_verbose() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let out = dir.path().join("d.txt");
    let args = [
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "-o",
        out.to_str().unwrap(),
    ];
    let normal = geotracks_ok(&args);
    assert!(String::from_utf8_lossy(&normal.stderr).contains("wrote"));
    let quiet = geotracks_ok(&[&args[..], &["--quiet"]].concat());
    assert_eq!(String::from_utf8_lossy(&quiet.stderr), "");
    let verbose = geotracks_ok(&[&["-v"], &args[..]].concat());
    let stderr = String::from_utf8_lossy(&verbose.stderr);
    assert!(stderr.contains("distance tests"), "{stderr}");
    // `path` keeps its result, the length, on stdout with --quiet.
    let p = dir.path().join("p.obj");
    let m = mesh.to_str().unwrap();
    let quiet = geotracks_ok(&[
        "path",
        m,
        "--source",
        "0",
        "--target",
        "2",
        "-o",
        p.to_str().unwrap(),
        "-q",
    ]);
    let stdout = String::from_utf8_lossy(&quiet.stdout);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    assert!((last_value(&quiet) - 2f64.sqrt()).abs() < 1e-12);
}

/// `-o -` writes a text output to standard output, and the summary goes to stderr.
#[test]
fn dash_writes_to_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let m = mesh.to_str().unwrap();
    let out = geotracks_ok(&["distance", m, "--source", "0", "-o", "-"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("vertex,distance\n0,0\n"), "{stdout}");
    assert_eq!(stdout.lines().count(), 5);
    assert!(String::from_utf8_lossy(&out.stderr).contains("wrote standard output"));
    let out = geotracks_ok(&["path", m, "--source", "0", "--target", "2", "-o", "-"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("x,y,z,point\n"), "{stdout}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("length: "));
    // Binary outputs need a file; two outputs cannot share standard output.
    let out = geotracks(&["skeleton", "x.ma", "-o", "s.obj", "--field", "-"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("text outputs only"));
    let out = geotracks(&["distance", m, "--source", "0", "-o", "-", "--stats", "-"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("two outputs"));
}

/// The demo writes into geotracks-out/ (which git ignores) and says so.
#[test]
fn the_demo_writes_into_an_ignored_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .arg("demo")
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("wrote geotracks-out/spot_distance.ply"),
        "{stdout}"
    );
    assert!(dir.path().join("geotracks-out/spot_distance.ply").is_file());
    let ignore = concat!(env!("CARGO_MANIFEST_DIR"), "/../.gitignore");
    if let Ok(text) = std::fs::read_to_string(ignore) {
        assert!(text.lines().any(|l| l == "/geotracks-out/"), "{text}");
    }
}

/// An interrupted run removes its temporary files and exits 130: here a run whose
/// standard output nobody reads, caught with `--voronoi`'s temporary file written.
#[cfg(unix)]
#[test]
fn an_interrupted_run_leaves_no_temporary_file() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    // 22K vertices: the CSV (≈ 600 KB) outgrows the pipe's buffer.
    let mesh = grid_obj(dir.path(), 150);
    let voronoi = dir.path().join("v.txt");
    let mut child = Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .args([
            "distance",
            mesh.to_str().unwrap(),
            "--source",
            "0",
            "--k",
            "1",
            "--voronoi",
            voronoi.to_str().unwrap(),
            "-o",
            "-",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let temporary = || {
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .any(|e| e.file_name().to_string_lossy().starts_with(".geotracks-"))
    };
    let start = Instant::now();
    while !temporary() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no temporary file"
        );
        assert!(child.try_wait().unwrap().is_none(), "the run ended");
        std::thread::sleep(Duration::from_millis(20));
    }
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert_no_temporary_files(dir.path());
    assert!(!voronoi.exists());
}

#[test]
fn info_reports_topology_and_weld_merges_seams() {
    let dir = tempfile::tempdir().unwrap();
    let seam = dir.path().join("seam.obj");
    std::fs::write(
        &seam,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 0 0\nv 2 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let seam_arg = seam.to_str().unwrap();
    let out = geotracks_ok(&["info", seam_arg]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("duplicate positions   2"), "{text}");
    assert!(text.contains("components            2"), "{text}");
    assert!(text.contains("genus 0"), "{text}");
    let out = geotracks_ok(&["info", "--weld", seam_arg]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("vertices              4"), "{text}");
    assert!(text.contains("components            1"), "{text}");
    // Distances cross the seam only when welded; ids are then the welded mesh's.
    let txt = dir.path().join("d.txt");
    let txt_arg = txt.to_str().unwrap();
    geotracks_ok(&["distance", seam_arg, "--source", "0", "-o", txt_arg]);
    assert!(read_values(&txt)[4].is_infinite());
    geotracks_ok(&[
        "distance", "--weld", seam_arg, "--source", "0", "-o", txt_arg,
    ]);
    let welded = read_values(&txt);
    assert_eq!(welded.len(), 4);
    assert!((welded[3] - 2.0).abs() < 1e-9, "{welded:?}");
}

#[test]
fn a_binary_density_file_is_named_as_not_text() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let density = dir.path().join("density.txt");
    std::fs::write(&density, b"1\n2\n\xff\xfe\x00\x01\n4\n").unwrap();
    let out = dir.path().join("d.txt");
    assert_fails(
        &[
            "distance",
            mesh.to_str().unwrap(),
            "--source",
            "0",
            "--density",
            density.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        &out,
        "density.txt:3: not a text file of numbers: byte 0xff at offset 4",
    );
}

#[test]
fn isolines_write_obj_csv_and_geojson_on_their_levels() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = grid_obj(dir.path(), 4);
    let mesh = mesh.to_str().unwrap();
    // Source at the origin of the flat 4 × 4 grid: quarter circles of radius 1 and 2.
    let csv = dir.path().join("iso.csv");
    let out = geotracks_ok(&[
        "isolines",
        mesh,
        "--source",
        "0",
        "--at",
        "1,2",
        "-o",
        csv.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("isolines: 2 (0 closed)"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut rows = 0;
    for row in text.lines().skip(1) {
        let cells: Vec<&str> = row.split(',').collect();
        let level: f64 = cells[0].parse().unwrap();
        let (x, y): (f64, f64) = (cells[3].parse().unwrap(), cells[4].parse().unwrap());
        assert!(((x * x + y * y).sqrt() - level).abs() < 1e-9, "{row}");
        rows += 1;
    }
    assert!(rows > 8, "{text}");
    let obj = dir.path().join("iso.obj");
    geotracks_ok(&[
        "isolines",
        mesh,
        "--source",
        "0",
        "--levels",
        "3",
        "-o",
        obj.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(
        text.lines().filter(|l| l.starts_with("l ")).count(),
        3,
        "{text}"
    );
    let geojson = dir.path().join("iso.geojson");
    geotracks_ok(&[
        "isolines",
        mesh,
        "--source",
        "0",
        "--at",
        "1",
        "-o",
        geojson.to_str().unwrap(),
    ]);
    let json = read_json(&geojson);
    let features = json["features"].as_array().unwrap();
    assert_eq!(features.len(), 1);
    assert_eq!(features[0]["properties"]["level"], 1.0);
    // A bad level fails before anything is written.
    let bad = dir.path().join("bad.csv");
    assert_fails(
        &[
            "isolines",
            mesh,
            "--source",
            "0",
            "--at",
            "1,NaN",
            "-o",
            bad.to_str().unwrap(),
        ],
        &bad,
        "--at NaN",
    );
}

/// The width and height a PNG's header gives.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG", "{} is not a PNG", path.display());
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

#[test]
fn pictures_of_distance_and_isolines_at_their_size_and_bad_options_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = grid_obj(dir.path(), 4);
    let mesh = mesh.to_str().unwrap();
    let d = dir.path().join("d.txt");
    let png = dir.path().join("d.png");
    geotracks_ok(&[
        "distance",
        mesh,
        "--source",
        "0",
        "-o",
        d.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
    ]);
    assert_eq!(png_size(&png), (1024, 768));
    let iso = dir.path().join("iso.obj");
    let png2 = dir.path().join("iso.png");
    geotracks_ok(&[
        "isolines",
        mesh,
        "--source",
        "0",
        "--at",
        "1,2",
        "-o",
        iso.to_str().unwrap(),
        "--png",
        png2.to_str().unwrap(),
        "--size",
        "300x200",
        "--view",
        "30,45",
    ]);
    assert_eq!(png_size(&png2), (300, 200));
    // Bad options: one error line, exit non-zero, no output at all.
    for (extra, message) in [
        (vec!["--view", "sideways"], "is not a view"),
        (vec!["--view", "0,120"], "is not a view"),
        (vec!["--size", "10x10"], "64 to 8192"),
        (vec!["--size", "big"], "is not WxH"),
    ] {
        let out = dir.path().join("fresh.txt");
        let pic = dir.path().join("fresh.png");
        let mut args = vec![
            "distance",
            mesh,
            "--source",
            "0",
            "-o",
            out.to_str().unwrap(),
            "--png",
            pic.to_str().unwrap(),
        ];
        args.extend(extra);
        let result = geotracks(&args);
        assert!(!result.status.success(), "{args:?}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!out.exists() && !pic.exists());
    }
    // --view without --png is refused too (it would draw nothing).
    let result = geotracks(&[
        "distance",
        mesh,
        "--source",
        "0",
        "-o",
        d.to_str().unwrap(),
        "--view",
        "top",
    ]);
    assert!(!result.status.success());
}

/// Two outputs that are one file under another name (`./`, `..`, a symbolic link) are
/// refused before the work; they were compared as text, and the run exited 0 with the
/// labels alone in the file. An output that is an input under another name likewise.
#[test]
fn one_file_under_two_names_is_refused_as_two_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let m = mesh.to_str().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let d = dir.path().join("d.txt");
    let spellings = [
        dir.path().join(".").join("d.txt"),
        dir.path().join("sub").join("..").join("d.txt"),
    ];
    for other in &spellings {
        assert_fails(
            &[
                "distance",
                m,
                "--source",
                "0",
                "--source",
                "2",
                "-o",
                d.to_str().unwrap(),
                "--voronoi",
                other.to_str().unwrap(),
            ],
            &d,
            "given for two outputs",
        );
    }
    #[cfg(unix)]
    {
        std::fs::write(&d, "old\n").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(&d, &link).unwrap();
        let o = geotracks(&[
            "distance",
            m,
            "--source",
            "0",
            "--source",
            "2",
            "-o",
            link.to_str().unwrap(),
            "--voronoi",
            d.to_str().unwrap(),
        ]);
        assert!(!o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains("two outputs"));
        assert_eq!(std::fs::read_to_string(&d).unwrap(), "old\n");
        // The mesh through a link, as an output.
        let mesh_link = dir.path().join("sub").join("mesh.txt");
        std::os::unix::fs::symlink(&mesh, &mesh_link).unwrap();
        let o = geotracks(&[
            "distance",
            m,
            "--source",
            "0",
            "-o",
            mesh_link.to_str().unwrap(),
        ]);
        assert!(!o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains("is also an input"));
        // A link to one output is written through, and stays a link.
        geotracks_ok(&["distance", m, "--source", "0", "-o", link.to_str().unwrap()]);
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(read_values(&d).len(), 4);
    }
    assert_no_temporary_files(dir.path());
}

/// A FIFO as the mesh or as a density file hung the command (and the blocked process
/// ignored SIGINT and SIGTERM); it is refused at once, with no output.
#[cfg(unix)]
#[test]
fn a_fifo_as_an_input_is_refused_at_once() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let pipe_mesh = dir.path().join("pipe.obj");
    let pipe_density = dir.path().join("rho.txt");
    for pipe in [&pipe_mesh, &pipe_density] {
        assert!(Command::new("mkfifo").arg(pipe).status().unwrap().success());
    }
    let out = dir.path().join("d.txt");
    for (mesh, density) in [(&pipe_mesh, None), (&mesh, Some(&pipe_density))] {
        let mut args = vec![
            "distance".to_string(),
            mesh.display().to_string(),
            "--source".into(),
            "0".into(),
            "-o".into(),
            out.display().to_string(),
        ];
        if let Some(d) = density {
            args.extend(["--density".into(), d.display().to_string()]);
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_geotracks"))
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if start.elapsed() > Duration::from_secs(20) {
                let _ = child.kill();
                panic!("{args:?}: still running after 20 s (blocked on the FIFO)");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut stderr = String::new();
        std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
        assert_eq!(status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains("named pipe (FIFO)"), "{stderr}");
        assert!(!out.exists());
    }
}

/// A density file saved with a UTF-8 byte-order mark reads as without one.
#[test]
fn a_density_file_with_a_byte_order_mark() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square_obj(dir.path());
    let density = dir.path().join("rho.txt");
    std::fs::write(&density, "\u{feff}2\n2\n2\n2\n").unwrap();
    let out = dir.path().join("d.txt");
    geotracks_ok(&[
        "distance",
        mesh.to_str().unwrap(),
        "--source",
        "0",
        "--density",
        density.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(read_values(&out)[1], 2.0);
}

/// Runs `args`, which must fail within `seconds` (killed and failed otherwise: before
/// the bounds, these ran for minutes or hours) with `expected` on stderr.
fn fails_quickly(args: &[&str], seconds: u64, output: &Path, expected: &str) {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() >= seconds {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("{args:?} still ran after {seconds} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    // It ended: now check its message and that it wrote nothing.
    assert_fails(args, output, expected);
}

/// Every knob that scales the work or the output is bounded before the work starts:
/// levels (10⁸ on 18 faces never ended), k (51,500 on 18 faces was accepted, for
/// hours of work), the rows of a matrix (a million rows of Spot: 23 GB).
#[test]
fn knobs_that_scale_work_are_refused_before_the_work() {
    let dir = tempfile::tempdir().unwrap();
    let grid = grid_obj(dir.path(), 3);
    let g = grid.to_str().unwrap();
    let out = dir.path().join("lines.csv");
    let o = out.to_str().unwrap();
    for levels in [["--levels", "100000000"], ["--levels", "1001"]] {
        let mut args = vec!["isolines", g, "--source", "0", "-o", o];
        args.extend(levels);
        fails_quickly(&args, 10, &out, "between 1 and 1000");
    }
    let at: Vec<String> = (1..=1001).map(|i| format!("{}", i as f64 * 1e-3)).collect();
    let at = at.join(",");
    fails_quickly(
        &["isolines", g, "--source", "0", "-o", o, "--at", &at],
        10,
        &out,
        "--at 1001",
    );
    let d = dir.path().join("d.txt");
    let dt = d.to_str().unwrap();
    for method in ["wave", "tracks", "graph"] {
        fails_quickly(
            &[
                "distance", g, "--source", "0", "--k", "51500", "--method", method, "-o", dt,
            ],
            10,
            &d,
            "largest k that fits",
        );
    }
    fails_quickly(
        &["distance", g, "--source", "0", "--k", "20000", "-o", dt],
        10,
        &d,
        "distance tests, more than the work limit of 4.00e9",
    );
    // The limit can be set, or lifted.
    fails_quickly(
        &[
            "distance",
            g,
            "--source",
            "0",
            "--k",
            "50",
            "--work-limit",
            "1000",
            "-o",
            dt,
        ],
        10,
        &d,
        "work limit of 1.00e3",
    );
    geotracks_ok(&[
        "distance",
        g,
        "--source",
        "0",
        "--k",
        "50",
        "--work-limit",
        "none",
        "-o",
        dt,
    ]);
    assert_fails(
        &[
            "distance",
            g,
            "--source",
            "0",
            "--work-limit",
            "lots",
            "-o",
            dt,
        ],
        &dir.path().join("nothing.txt"),
        "is not a work limit",
    );
    // Terrain routes take the same limit.
    let dem = dir.path().join("dem.asc");
    let mut text = String::from("ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 10\n");
    for row in 0..4 {
        let values: Vec<String> = (0..4).map(|c| format!("{}", row * c)).collect();
        text += &(values.join(" ") + "\n");
    }
    std::fs::write(&dem, text).unwrap();
    let route = dir.path().join("route.geojson");
    let (dm, r) = (dem.to_str().unwrap(), route.to_str().unwrap());
    let terrain = ["terrain", dm, "--from", "5,5", "--to", "25,25", "-o", r];
    let limited = [&terrain[..], &["--work-limit", "10"]].concat();
    fails_quickly(&limited, 10, &route, "work limit of 1.00e1");
    let huge = [&terrain[..], &["--k", "20000"]].concat();
    fails_quickly(&huge, 10, &route, "largest k that fits");
    geotracks_ok(&terrain);
    // A million rows of Spot's 2,930 columns (23 GB) are refused before any row runs
    // on a machine with less memory than that available (this test's), the ids file
    // aside.
    let sources = dir.path().join("sources.txt");
    std::fs::write(&sources, "0\n".repeat(10_000_000)).unwrap();
    let csv = dir.path().join("m.csv");
    fails_quickly(
        &[
            "matrix",
            SPOT,
            "--sources",
            sources.to_str().unwrap(),
            "-o",
            csv.to_str().unwrap(),
        ],
        30,
        &csv,
        "a distance matrix of 10000000 rows",
    );
}

#[test]
fn a_reader_that_stops_reading_is_no_panic() {
    use std::process::{Command, Stdio};
    // `geotracks info mesh | head -1`: the pipe closes after the first line.
    let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/spot.obj");
    let mut child = Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .args(["info", mesh])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.status.success(), "{stderr}");
}
