//! Accuracy against exact geodesics: Dijkstra on edges and the Steiner graph at
//! k = 3, 5, 8 on every mesh of a data directory that has exact references (default), or
//! every engine with its time, work and memory (`--engines`).
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data [--max-faces N] [--k 3,5,8]
//! ```
//!
//! With `--equality` it checks instead that the tracks engine returns the Steiner
//! graph's distances at every node (relative 1e-9) for each k, from every reference's
//! source, and exits non-zero otherwise (CI runs it on two shared meshes):
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data --equality [--meshes a,ma/b.ma] [--max-faces 100000] [--k 3,5]
//! ```
//!
//! With `--paths N` it measures paths instead: on every mesh with references, from each
//! reference's source at each k (default 5), the paths from N vertices spread over the
//! mesh, traced and straightened, against the exact distance (relative excess
//! (length − d*) / d*, mean and max):
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data --paths 100 [--max-faces N] [--k 5]
//! ```
//!
//! With `--isolines N` it measures isolines (N levels per source): how far their points
//! lie from their level, ours against a linear interpolation of the exact vertex values,
//! each point's distance estimated by a straightened path at k = 8 (see
//! `isolines.rs`; the guide's Isolines table, docs/src/isolines.md):
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data --isolines 10 [--max-faces N]
//! ```
//!
//! With `--skeletons [PRUNE_PERCENT]` it skeletonizes every `DATA_DIR/ma/*.ma`: cycles,
//! components and tips at each pruning level against the axis's Betti numbers (exit 1 if
//! they differ), the end-to-end time, and, where `DATA_DIR/skeleton/<name>.mcf.obj` has a
//! mean-curvature-flow skeleton, the distances between the two (the guide's Skeletons page
//! table; `--radius` burns by the medial radius; `--from-meshes` computes the axes
//! from `DATA_DIR/meshes/<name>.obj` instead, at that angle and span):
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data --skeletons [7] [--k 5] [--radius] [--tubular 1] [--protrusion 0.5] [--keep-tips] [--from-meshes [ANGLE] [--span S]]
//! ```
//!
//! With `--plates` (no data needed) it builds plates of a few large faces (a board, an
//! L-shaped plate, a table of boxes) and counts their skeletons' tips and length from
//! their meshes at spacings 0.15 to 0.03, against what each should have (the guide's
//! Plates section):
//!
//! ```text
//! cargo run --release --example eval -- --plates
//! ```
//!
//! With `--engines` it measures each engine against every exact reference, with its time,
//! work and memory (the wave engine's tables in the guide's Accuracy page):
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data --engines --plot bunny_loop1:doc/wave_error_vs_time.png
//! ```
//!
//! Options: `--methods LIST`, `--meshes a,b`, `--max-faces N`, `--reps N`,
//! `--reps-below FACES`, `--no-aniso`, `--plot MESH:FILE.png`, `--plot-methods LIST`.
//!
//! - `--methods`: `method:k` items (`wave`, `tracks`, `graph`) and `dijkstra`; default
//!   wave at k = 1, 2, 3, 5, tracks at k = 5 (the Steiner graph's distances, faster than
//!   `graph:5`), dijkstra. There is no `wave:0`: the wave engine puts at least one point
//!   on every edge (a wave crosses an edge only through its points); vertices only is
//!   `dijkstra`.
//! - Cases: every mesh of the manifest with references, Euclidean, from each reference's
//!   source; then each `reference/aniso/<mesh>.aniso.src<v>.f64` under the tensor of its
//!   `.tensor` file (`xx xy xz yy yz zz` per face of the mesh file, as the CLI's
//!   `--tensor` reads it). `--meshes` and `--max-faces` (default: no limit) filter both.
//! - Each (case, method) runs in a child process (this program with the hidden flag
//!   `--one`), so its peak RSS (`VmHWM`) is its own: mesh, solver, workspace and one
//!   reference at a time. The child builds one solver and runs each source `--reps`
//!   times (default 3; once on meshes of `--reps-below` faces or more, default: no such
//!   limit) and keeps the best propagate time.
//! - Prints Markdown: a caption line (date, machine, commit, command, total time, load
//!   average at the start and the end); per case and method the mean error (mean over
//!   the references of each one's mean of |d − d*| / d* over vertices with d* > 0), the
//!   max error, the most below exact (max of (d* − d) / d*: a shortcut off the surface
//!   would show), propagate seconds (`Stats::propagate_seconds`, best repetition per
//!   source, mean over the sources), setup seconds, nodes (vertices + Steiner points),
//!   distance tests, settles and propagate ns per node, peak RSS; checks (the wave engine
//!   worse than the graph at the same k, a value more than 1e-6 below exact, an engine that
//!   fell back to another); and for the meshes `DATA_DIR/peers.md` covers, our rows beside
//!   the peers' own figures copied from it (another machine: labelled so).
//! - `--plot MESH:FILE.png` also runs `--plot-methods` on that mesh (default wave k = 1 to
//!   5, tracks k = 1, 2, 3, 5, 8, dijkstra), prints their table and draws mean error
//!   against propagate time, log-log, one curve per method, with the peers' points from
//!   `peers.md` hollow.
//!
//! The directory holds `manifest.json` (a list of meshes with `name`, `file`, `faces`
//! and `references`), the meshes, and `reference/<mesh>.src<v>.f64` files (exact
//! distances from vertex `v`, little-endian f64 per vertex). The default mode prints a
//! Markdown table: mean and max relative error over the references of each mesh
//! (|d − d*| / d* over vertices with d* > 0).

// The function-length rule (clippy.toml) is for the crates' code; an example's report
// loops are allowed to run long.
#![allow(clippy::too_many_lines)]

use geotracks::mesh::{io::read_mesh, TriMesh};
use geotracks::{Euclidean, Method, Options, Solver, SurfacePoint};
use std::path::PathBuf;
use std::time::Instant;

mod engines;
mod isolines;
mod plates;
mod plot;
#[path = "../shared_data/mod.rs"]
mod shared_data;
mod skeletons;
use shared_data::{manifest, read_reference, relative_error, source_of, MeshEntry};

fn main() {
    let argv: Vec<String> = std::env::args().collect();
    let result = if argv.get(1).map(String::as_str) == Some("--one") {
        engines::child(&argv[2..])
    } else if argv.iter().any(|a| a == "--engines") {
        engines::main(&argv)
    } else if argv.iter().any(|a| a == "--plates") {
        plates::plates()
    } else if let Some(at) = argv.iter().position(|a| a == "--skeletons") {
        skeletons_main(&argv, at)
    } else {
        run()
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

/// The number after `flag` in `argv`, or `default` when the flag is absent.
fn number_after(argv: &[String], flag: &str, default: f64) -> Result<f64, String> {
    match argv.iter().position(|a| a == flag) {
        Some(i) => argv
            .get(i + 1)
            .and_then(|v| v.parse().ok())
            .ok_or(format!("{flag} takes a number")),
        None => Ok(default),
    }
}

/// `eval DATA_DIR --skeletons [PRUNE_PERCENT] [--k K] [--radius] [--tubular T]
/// [--protrusion P] [--keep-tips] [--from-meshes [ANGLE] [--span S]] [--centred | --on-axis]`.
fn skeletons_main(argv: &[String], at: usize) -> Result<(), String> {
    let data = argv
        .get(1)
        .filter(|a| !a.starts_with("--"))
        .ok_or("usage: eval DATA_DIR --skeletons [PRUNE_PERCENT] [--k K] [--tubular T]")?;
    let prune = match argv.get(at + 1) {
        Some(p) if !p.starts_with("--") => p
            .trim_end_matches('%')
            .parse()
            .map_err(|_| format!("bad prune '{p}'"))?,
        _ => geotracks::skeleton::DEFAULT_PRUNE_PERCENT,
    };
    let k = number_after(argv, "--k", 5.0)?;
    let burn = if argv.iter().any(|a| a == "--radius") {
        geotracks::skeleton::Burn::Radius
    } else {
        geotracks::skeleton::Burn::Boundary
    };
    let tubular = number_after(
        argv,
        "--tubular",
        geotracks::skeleton::DEFAULT_MIN_TUBULARITY,
    )?;
    let protrusion = number_after(
        argv,
        "--protrusion",
        geotracks::skeleton::DEFAULT_MIN_PROTRUSION,
    )?;
    let axes = match argv.iter().position(|a| a == "--from-meshes") {
        Some(i) => {
            let angle = match argv.get(i + 1) {
                Some(a) if !a.starts_with("--") => {
                    a.parse().map_err(|_| format!("bad angle '{a}'"))?
                }
                _ => geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_ANGLE_DEGREES,
            };
            let span = number_after(
                argv,
                "--span",
                geotracks::skeleton::medial::MedialAxisOptions::DEFAULT_MIN_SPAN,
            )?;
            skeletons::Axes::FromMeshes(
                geotracks::skeleton::medial::MedialAxisOptions::default()
                    .with_min_angle_degrees(angle)
                    .with_min_span(span),
            )
        }
        None => skeletons::Axes::Files,
    };
    // As the command line places them: centred unless told otherwise.
    let placement = if argv.iter().any(|a| a == "--on-axis") {
        geotracks::skeleton::Placement::OnAxis
    } else {
        geotracks::skeleton::Placement::default()
    };
    skeletons::skeletons(
        std::path::Path::new(data),
        skeletons::Thresholds {
            prune_percent: prune,
            tubular,
            protrusion,
            trim_tips: !argv.iter().any(|a| a == "--keep-tips"),
        },
        k,
        burn,
        axes,
        placement,
    )
}

struct Args {
    data: PathBuf,
    max_faces: u64,
    ks: Vec<f64>,
    equality: bool,
    paths: Option<usize>,
    isolines: Option<usize>,
    meshes: Option<Vec<String>>,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut data = None;
    let mut max_faces = None;
    let mut ks = None;
    let mut equality = false;
    let mut paths = None;
    let mut isolines = None;
    let mut meshes = None;
    while let Some(a) = it.next() {
        match a.as_str() {
            "--max-faces" => {
                max_faces = Some(
                    it.next()
                        .and_then(|v| v.parse().ok())
                        .ok_or("--max-faces takes a number")?,
                )
            }
            "--k" => {
                ks = Some(
                    it.next()
                        .ok_or("--k takes a list like 3,5,8")?
                        .split(',')
                        .map(|s| s.parse::<f64>().map_err(|_| format!("bad k '{s}'")))
                        .collect::<Result<_, _>>()?,
                )
            }
            "--meshes" => {
                meshes = Some(
                    it.next()
                        .ok_or("--meshes takes a list like spot,bunny")?
                        .split(',')
                        .map(String::from)
                        .collect(),
                )
            }
            "--equality" => equality = true,
            "--paths" => {
                paths = Some(
                    it.next()
                        .and_then(|v| v.parse().ok())
                        .ok_or("--paths takes a number of paths per source")?,
                )
            }
            "--isolines" => {
                isolines = Some(
                    it.next()
                        .and_then(|v| v.parse().ok())
                        .ok_or("--isolines takes a number of levels per source")?,
                )
            }
            _ if data.is_none() => data = Some(PathBuf::from(a)),
            other => return Err(format!("unexpected argument '{other}'")),
        }
    }
    Ok(Args {
        data: data.ok_or(
            "usage: eval DATA_DIR [--equality | --paths N | --isolines N] [--meshes a,b] [--max-faces N] [--k 3,5,8]",
        )?,
        max_faces: max_faces.unwrap_or(if equality { 100_000 } else { 400_000 }),
        ks: ks.unwrap_or(if equality {
            vec![3.0, 5.0]
        } else if paths.is_some() {
            vec![5.0]
        } else {
            vec![3.0, 5.0, 8.0]
        }),
        equality,
        paths,
        isolines,
        meshes,
    })
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let manifest = manifest(&args.data)?;
    let meshes: Vec<&MeshEntry> = manifest
        .iter()
        .filter(|m| match &args.meshes {
            Some(names) => names.contains(&m.name),
            None => true,
        })
        .collect();
    if args.equality {
        return equality(&args, &meshes);
    }
    if meshes.is_empty() {
        return Err("no mesh of the manifest matches --meshes".into());
    }
    if let Some(count) = args.paths {
        return paths(&args, &meshes, count);
    }
    if let Some(levels) = args.isolines {
        return isolines::isolines(&args, &meshes, levels);
    }

    let mut header = String::from("| mesh | faces | Dijkstra mean / max |");
    let mut rule = String::from("|---|---:|---:|");
    for k in &args.ks {
        header += &format!(" graph k={k} mean / max |");
        rule += "---:|";
    }
    println!("{header}\n{rule}");
    for entry in meshes {
        let Some(mesh) = load(&args, entry, true)? else {
            continue;
        };
        let MeshEntry {
            name,
            faces,
            references,
            ..
        } = entry;
        let mut methods = vec![Options::DEFAULT.with_method(Method::Dijkstra)];
        methods.extend(
            args.ks
                .iter()
                .map(|&k| Options::DEFAULT.with_k(k).with_method(Method::Graph)),
        );
        let mut row = format!("| {name} | {faces} |");
        for options in &methods {
            let (mut mean, mut max) = (0.0, 0.0f64);
            for reference in references {
                let exact = read_reference(&args.data.join(reference))?;
                let source = source_of(reference)?;
                let field = Solver::new(&mesh, &Euclidean, options)
                    .and_then(|solver| solver.field(source))
                    .map_err(|e| e.to_string())?;
                let (m, x) = relative_error(field.vertex_distances(), &exact);
                mean += m / references.len() as f64;
                max = max.max(x);
            }
            row += &format!(" {:.3} % / {:.2} % |", 100.0 * mean, 100.0 * max);
        }
        println!("{row}");
    }
    Ok(())
}

/// The entry's mesh, or `None` (said on stderr) when it has more faces than
/// `--max-faces` or, for a mode that needs exact distances, no reference.
fn load(args: &Args, entry: &MeshEntry, needs_references: bool) -> Result<Option<TriMesh>, String> {
    if entry.faces > args.max_faces {
        eprintln!(
            "skipping {} ({} faces > --max-faces)",
            entry.name, entry.faces
        );
        return Ok(None);
    }
    if needs_references && entry.references.is_empty() {
        eprintln!("skipping {} (no exact reference)", entry.name);
        return Ok(None);
    }
    read_mesh(args.data.join(&entry.file))
        .map(Some)
        .map_err(|e| e.to_string())
}

/// Largest relative difference between the tracks engine and the Steiner graph over all
/// nodes, per (mesh, k), from every reference's source (for the medial axes in `ma/`,
/// which are non-manifold: the first vertex on a face and the middle vertex); an error
/// if any exceeds 1e-9.
fn equality(args: &Args, meshes: &[&MeshEntry]) -> Result<(), String> {
    println!("| mesh | faces | k | sources | max relative deviation (all nodes) | graph tests / tracks tests |");
    println!("|---|---:|---:|---:|---:|---:|");
    let mut cases: Vec<(String, TriMesh, Vec<u32>)> = Vec::new();
    for entry in meshes {
        let Some(mesh) = load(args, entry, false)? else {
            continue;
        };
        let sources: Vec<u32> = entry
            .references
            .iter()
            .map(|r| source_of(r))
            .collect::<Result<_, _>>()?;
        let sources = if sources.is_empty() { vec![0] } else { sources };
        cases.push((entry.name.clone(), mesh, sources));
    }
    {
        let mut medial: Vec<PathBuf> = std::fs::read_dir(args.data.join("ma"))
            .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).collect())
            .unwrap_or_default();
        medial.sort();
        for path in medial {
            // A medial axis with edges only has no surface to measure on.
            let Ok(mesh) = read_mesh(&path) else { continue };
            let first = (0..mesh.vertex_count() as u32)
                .find(|&v| !mesh.vertex_faces(v).is_empty())
                .unwrap_or(0);
            let name = format!(
                "ma/{}",
                path.file_name().unwrap_or_default().to_string_lossy()
            );
            if let Some(names) = &args.meshes {
                if !names.contains(&name) {
                    continue;
                }
            }
            let middle = mesh.vertex_count() as u32 / 2;
            cases.push((name, mesh, vec![first, middle]));
        }
    }
    let mut failures = 0;
    for (name, mesh, sources) in &cases {
        let faces = mesh.face_count();
        for &k in &args.ks {
            let (mut worst, mut graph_tests, mut tracks_tests) = (0.0f64, 0u64, 0u64);
            for &source in sources {
                let run = |method| {
                    Solver::new(
                        mesh,
                        &Euclidean,
                        &Options::DEFAULT.with_k(k).with_method(method),
                    )
                    .and_then(|solver| solver.field(&[source]))
                    .map_err(|e| e.to_string())
                };
                let (graph, tracks) = (run(Method::Graph)?, run(Method::Tracks)?);
                graph_tests += graph.stats().distance_tests;
                tracks_tests += tracks.stats().distance_tests;
                for (g, t) in graph.node_distances().iter().zip(tracks.node_distances()) {
                    let deviation = if g == t { 0.0 } else { (g - t).abs() / g.abs() };
                    worst = worst.max(deviation);
                }
            }
            let ok = worst <= 1e-9;
            failures += usize::from(!ok);
            println!(
                "| {name} | {faces} | {k} | {} | {worst:.1e}{} | {:.2} |",
                sources.len(),
                if ok { "" } else { " FAIL" },
                graph_tests as f64 / tracks_tests.max(1) as f64
            );
        }
    }
    if failures > 0 {
        return Err(format!(
            "{failures} (mesh, k) pairs where tracks differs from the graph"
        ));
    }
    Ok(())
}

/// Path lengths against exact distances: traced (the Steiner graph's) and straightened.
fn paths(args: &Args, meshes: &[&MeshEntry], count: usize) -> Result<(), String> {
    println!("| mesh | faces | k | paths | traced: mean / max excess | straightened: mean / max excess | ms per path |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut all = (0usize, 0.0, 0.0);
    for entry in meshes {
        let Some(mesh) = load(args, entry, true)? else {
            continue;
        };
        for &k in &args.ks {
            let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(k))
                .map_err(|e| e.to_string())?;
            let (mut n, mut traced, mut straight) = (0usize, 0.0, 0.0);
            let (mut traced_max, mut straight_max) = (0.0f64, 0.0f64);
            let mut seconds = 0.0;
            for reference in &entry.references {
                let exact = read_reference(&args.data.join(reference))?;
                let field = solver
                    .field(&[source_of(reference)?])
                    .map_err(|e| e.to_string())?;
                let query = Ok::<_, geotracks::Error>(&field).map_err(|e| e.to_string())?;
                // Vertices spread over the mesh by a multiplicative hash of 0, 1, 2, …
                let vertices = mesh.vertex_count() as u64;
                for i in 0..count as u64 {
                    let v = ((i * 2_654_435_761) % vertices) as u32;
                    let d = exact[v as usize];
                    if d.is_nan() || d <= 0.0 {
                        continue;
                    }
                    let start = Instant::now();
                    let path = query
                        .path(SurfacePoint::Vertex(v))
                        .map_err(|e| e.to_string())?;
                    seconds += start.elapsed().as_secs_f64();
                    let (t, s) = ((path.traced_length - d) / d, (path.length - d) / d);
                    traced += t;
                    straight += s;
                    traced_max = traced_max.max(t);
                    straight_max = straight_max.max(s);
                    n += 1;
                }
            }
            let per = |x: f64| 100.0 * x / n.max(1) as f64;
            println!(
                "| {} | {} | {k} | {n} | {:.3} % / {:.2} % | {:.4} % / {:.3} % | {:.1} |",
                entry.name,
                entry.faces,
                per(traced),
                100.0 * traced_max,
                per(straight),
                100.0 * straight_max,
                1e3 * seconds / n.max(1) as f64
            );
            all = (all.0 + n, all.1 + traced, all.2 + straight);
        }
    }
    let per = |x: f64| 100.0 * x / all.0.max(1) as f64;
    println!(
        "| all | | | {} | {:.3} % | {:.4} % | |",
        all.0,
        per(all.1),
        per(all.2)
    );
    Ok(())
}
