//! The command-line tool end to end: outputs, and bad input that must fail with one
//! clear line, a non-zero exit, and no output file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SPOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj");

fn geotracks(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .args(args)
        .output()
        .expect("run geotracks")
}

/// Runs a command that must succeed; returns its output.
fn geotracks_ok(args: &[&str]) -> Output {
    let out = geotracks(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    out
}

/// One number per line.
fn read_values(path: &Path) -> Vec<f64> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect()
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

/// Runs a command that must fail: exit code non-zero, one line on stderr that contains
/// `expected`, no panic or backtrace, and no output file.
fn assert_fails(args: &[&str], output: &Path, expected: &str) {
    let out = geotracks(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert!(
        stderr.contains(expected),
        "{args:?}: stderr {stderr:?} lacks {expected:?}"
    );
    assert!(
        !stderr.contains("panicked") && !stderr.contains("RUST_BACKTRACE"),
        "{stderr}"
    );
    // One error line (clap may add a usage hint after it for argument errors).
    let errors = stderr.lines().filter(|l| l.starts_with("error:")).count();
    assert_eq!(errors, 1, "{stderr}");
    assert!(
        stderr.lines().next().unwrap_or("").starts_with("error:"),
        "{stderr}"
    );
    assert!(!output.exists(), "{} was written", output.display());
    let leftovers: Vec<_> = std::fs::read_dir(output.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
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
    assert_eq!(json["method"], "tracks");
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
    let options: [(&[&str], &str); 8] = [
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
        "written as .csv",
    );
}
