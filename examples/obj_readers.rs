//! Our OBJ reader against `tobj`, the crate the design card names: speed, what each
//! reads from the same files, and what each does with bad input. The evidence behind
//! the choice written in the module docs of `src/mesh/io/obj.rs`.
//!
//! ```text
//! cargo run --release --example obj_readers -- [PATH ...] [--reps N]
//! ```
//!
//! Each `PATH` is an OBJ file or a directory searched recursively for `*.obj` (default:
//! `../shared/data`, the shared meshes, curve skeletons and fuzz meshes). `--reps`: how
//! many times each file is read by each reader (default 5); the median is printed.
//!
//! Both readers parse the same bytes from memory, so disk speed plays no part:
//! - `ours`: `read_mesh_bytes` (parse, then `TriMesh::new`: edge table, degenerate faces);
//! - `tobj`: `tobj::load_obj_buf` alone, with the card's options (`triangulate: true`,
//!   `single_index: false`) and `ignore_points`/`ignore_lines` (without them an `l` or `p`
//!   element becomes a zero-area triangle), positions as `f64` (feature `use_f64`);
//! - `ours parse`: the same less the time `TriMesh::new` takes on its output (measured
//!   apart), to set against tobj's parse;
//! - `tobj+build`: what adopting it would cost: tobj, its models concatenated with index
//!   offsets, then the same `TriMesh::new`.
//!
//! Then, per file: vertices and triangles from each, how many of tobj's vertices keep
//! their file index (sources, densities and reference distances are given per file
//! vertex), and how many triangles differ in their corners' positions. Last, a table of
//! hostile and tricky inputs (the cases of `tests/io.rs`, the fuzz seeds of
//! `fuzz/seeds/obj/`): each reader's answer, and whether tobj panicked.

// The function-length rule (clippy.toml) is for the crates' code; an example's report
// loops are allowed to run long.
#![allow(clippy::too_many_lines)]

use geotracks::mesh::io::read_mesh_bytes;
use geotracks::mesh::TriMesh;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The options the design card gives for tobj, and no `l`/`p` elements as triangles.
const TOBJ_OPTIONS: tobj::LoadOptions = tobj::LoadOptions {
    single_index: false,
    triangulate: true,
    ignore_points: true,
    ignore_lines: true,
};

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let mut paths = Vec::new();
    let mut reps = 5usize;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--reps" {
            let value = args.next().ok_or("--reps needs a number")?;
            reps = value.parse().ok().filter(|&n| n > 0).ok_or(format!(
                "--reps: expected a positive whole number, found `{value}`"
            ))?;
        } else {
            paths.push(PathBuf::from(arg));
        }
    }
    if paths.is_empty() {
        paths.push(PathBuf::from("../shared/data"));
    }
    let mut files = Vec::new();
    for p in &paths {
        collect_obj(p, &mut files)?;
    }
    files.sort();
    if files.is_empty() {
        return Err(format!("no .obj file under {paths:?}"));
    }

    println!("reps: {reps} (median), both readers from memory\n");
    println!(
        "| file | MB | ours ms | ours parse ms | tobj ms | tobj+build ms | tobj+build / ours | ours V / T | \
         tobj models / V / T | V at file index | T differing |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut total_ours, mut total_tobj_build) = (0.0, 0.0);
    for file in &files {
        let bytes = std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
        let name = file
            .strip_prefix(common_root(&paths))
            .unwrap_or(file)
            .display()
            .to_string();
        // The readers take turns within each repetition, so a load that comes and goes
        // on the machine weighs on all of them alike.
        let our_copy = read_mesh_bytes(file, &bytes).ok().map(|m| {
            (
                m.positions()
                    .iter()
                    .map(|p| p.to_array())
                    .collect::<Vec<_>>(),
                m.triangles().to_vec(),
            )
        });
        let mut samples = [const { Vec::new() }; 4];
        for _ in 0..reps {
            samples[0].push(time_ms(|| {
                let _ = read_mesh_bytes(file, &bytes);
            }));
            samples[1].push(time_ms(|| {
                let _ = tobj_load(&bytes);
            }));
            samples[2].push(time_ms(|| {
                let _ = tobj_load(&bytes).map(|m| TriMesh::new(m.positions, m.triangles));
            }));
            // Our parse alone: our whole read less the `TriMesh::new` it ends with.
            if let Some((positions, triangles)) = &our_copy {
                let (positions, triangles) = (positions.clone(), triangles.clone());
                samples[3].push(time_ms(|| {
                    let _ = TriMesh::new(positions, triangles);
                }));
            }
        }
        let [ours_ms, tobj_ms, build_ms, our_build_ms] = samples.map(|mut t| median(&mut t));
        total_ours += ours_ms;
        total_tobj_build += build_ms;
        let ours = read_mesh_bytes(file, &bytes);
        let theirs = tobj_load(&bytes);
        let ours_cell = match &ours {
            Ok(m) => format!("{} / {}", m.vertex_count(), m.face_count()),
            Err(e) => format!("error: {}", first_line(&e.to_string(), "")),
        };
        let theirs_cell = match &theirs {
            Ok(m) => format!(
                "{} / {} / {}",
                m.models,
                m.positions.len(),
                m.triangles.len()
            ),
            Err(e) => format!("error: {e}"),
        };
        let (kept, differing) = match (&ours, &theirs) {
            (Ok(o), Ok(t)) => {
                let kept = t
                    .positions
                    .iter()
                    .enumerate()
                    .take_while(|&(i, _)| i < o.vertex_count())
                    .filter(|&(i, p)| o.position(i as u32).to_array() == *p)
                    .count();
                (
                    format!("{kept} of {}", o.vertex_count()),
                    differing_triangles(o, t).to_string(),
                )
            }
            _ => ("–".into(), "–".into()),
        };
        println!(
            "| {name} | {:.1} | {ours_ms:.1} | {:.1} | {tobj_ms:.1} | {build_ms:.1} | {:.2} | {ours_cell} | \
             {theirs_cell} | {kept} | {differing} |",
            bytes.len() as f64 / 1e6,
            ours_ms - our_build_ms,
            build_ms / ours_ms,
        );
    }
    println!(
        "\nall files: ours {total_ours:.0} ms, tobj+build {total_tobj_build:.0} ms \
         (ratio {:.2})",
        total_tobj_build / total_ours
    );
    println!("(`ours` counts T after dropping degenerate faces; tobj keeps them.)\n");

    hostile_table();
    Ok(())
}

/// tobj's models merged into one mesh, as adopting it would do.
struct TobjMesh {
    models: usize,
    positions: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

/// Loads with tobj from memory and concatenates its models with index offsets.
fn tobj_load(bytes: &[u8]) -> Result<TobjMesh, tobj::LoadError> {
    let (models, _) = tobj::load_obj_buf(&mut &bytes[..], &TOBJ_OPTIONS, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })?;
    let mut out = TobjMesh {
        models: models.len(),
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    for model in models {
        let offset = out.positions.len() as u32;
        out.positions.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]]),
        );
        out.triangles.extend(
            model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
        );
    }
    Ok(out)
}

/// Our triangles whose corners are not at the same positions as tobj's triangle of the
/// same input face (ours drops degenerate faces but keeps each face's input index, and
/// tobj's models, concatenated, keep the file's face order).
fn differing_triangles(ours: &TriMesh, theirs: &TobjMesh) -> usize {
    (0..ours.face_count() as u32)
        .filter(|&f| {
            let t = ours.triangles()[f as usize];
            let input = ours.input_face(f);
            theirs.triangles.get(input).is_none_or(|u| {
                t.map(|v| ours.position(v).to_array()) != u.map(|v| theirs.positions[v as usize])
            })
        })
        .count()
}

/// Hostile and tricky inputs: what each reader answers.
fn hostile_table() {
    let seeds = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/seeds/obj");
    let mut cases: Vec<(String, Vec<u8>)> = vec![
        (
            "index out of range (line 5)",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n",
        ),
        (
            "relative index before the first vertex",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n",
        ),
        (
            "forward reference, vertex comes later",
            "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
        ),
        (
            "forward reference across groups",
            "v 0 0 0\nv 1 0 0\ng a\nf 1 2 3\ng b\nv 0 1 0\nf 1 3 2\n",
        ),
        (
            "forward reference never met (line 5)",
            "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\nf 1 2 5\n",
        ),
        ("index 0 (line 4)", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
        ("word as a coordinate (line 2)", "v 0 0 0\nv 1 zero 0\n"),
        ("vertex with two coordinates (line 1)", "v 0 0\n"),
        ("face of two vertices (line 3)", "v 0 0 0\nv 1 0 0\nf 1 2\n"),
        (
            "word as an index (line 4)",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
        ),
        (
            "NaN coordinate (vertex 2)",
            "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n",
        ),
        (
            "infinite coordinate (vertex 2)",
            "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n",
        ),
        ("empty file", ""),
        ("comments only", "# nothing here\n\n# at all\n"),
        (
            "lines only (a curve skeleton)",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n",
        ),
        (
            "repeated vertex in a face",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n",
        ),
        (
            "huge index",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
        ),
        (
            "texture index out of range",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/3\n",
        ),
        (
            "normal index out of range",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//3\n",
        ),
        (
            "vertex with a weight `v 2 2 2 2`",
            "v 0 0 0\nv 1 0 0\nv 2 2 2 2\nf 1 2 3\n",
        ),
        (
            "`fo` face (old keyword)",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nfo 1 2 3\n",
        ),
        (
            "pentagon",
            "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n",
        ),
    ]
    .into_iter()
    .map(|(n, t)| (n.to_string(), t.as_bytes().to_vec()))
    .collect();
    cases.push((
        "Latin-1 comment".into(),
        b"v 0 0 0\n# caf\xe9\nv 1 0 0\n".to_vec(),
    ));
    cases.push((
        "binary data".into(),
        (0u8..=255).cycle().take(4096).collect(),
    ));
    if let Ok(dir) = std::fs::read_dir(&seeds) {
        let mut entries: Vec<_> = dir.flatten().map(|e| e.path()).collect();
        entries.sort();
        for p in entries {
            if let Ok(b) = std::fs::read(&p) {
                let name = p.file_name().unwrap_or_default().to_string_lossy();
                cases.push((format!("fuzz seed {name}"), b));
            }
        }
    }

    println!("| input | ours | tobj | tobj+build |");
    println!("|---|---|---|---|");
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for (name, bytes) in &cases {
        let ours = match read_mesh_bytes("case.obj", bytes) {
            Ok(m) => format!("{} V, {} T", m.vertex_count(), m.face_count()),
            Err(e) => format!("`{}`", first_line(&e.to_string(), "")),
        };
        let (theirs, built) = match catch_unwind(AssertUnwindSafe(|| tobj_load(bytes))) {
            Err(_) => ("PANIC".to_string(), "–".to_string()),
            Ok(Err(e)) => (format!("`{e}` ({e:?})"), "–".to_string()),
            Ok(Ok(m)) => {
                let summary = format!(
                    "{} model(s), {} V, {} T",
                    m.models,
                    m.positions.len(),
                    m.triangles.len()
                );
                let built = match TriMesh::new(m.positions, m.triangles) {
                    Ok(t) => format!("{} V, {} T", t.vertex_count(), t.face_count()),
                    Err(e) => format!("`{}`", first_line(&e.to_string(), "")),
                };
                (summary, built)
            }
        };
        println!("| {name} | {ours} | {theirs} | {built} |");
    }
    std::panic::set_hook(hook);
}

/// The first line of a message, without a leading path (tables stay narrow).
fn first_line(message: &str, root: &str) -> String {
    let line = message.lines().next().unwrap_or("");
    line.strip_prefix(root).unwrap_or(line).replace('|', "/")
}

/// The longest directory the given paths share, to print file names short.
fn common_root(paths: &[PathBuf]) -> &Path {
    match paths {
        [one] if one.is_dir() => one,
        _ => Path::new(""),
    }
}

/// Wall time of one call, in milliseconds.
fn time_ms(f: impl FnOnce()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_secs_f64() * 1e3
}

/// The median of some times (0 for none).
fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(0.0)
}

/// Every `*.obj` file at `path` (a file, or a directory searched recursively).
fn collect_obj(path: &Path, out: &mut Vec<PathBuf>) -> Result<(), String> {
    if path.is_file() {
        out.push(path.to_path_buf());
        return Ok(());
    }
    let dir = std::fs::read_dir(path).map_err(|e| format!("{}: {e}", path.display()))?;
    for entry in dir {
        let p = entry
            .map_err(|e| format!("{}: {e}", path.display()))?
            .path();
        if p.is_dir() {
            collect_obj(&p, out)?;
        } else if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")) {
            out.push(p);
        }
    }
    Ok(())
}
