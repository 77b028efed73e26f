//! Speed, work, memory and accuracy of the three engines across mesh sizes.
//!
//! ```text
//! cargo run --release --example bench -- DATA_DIR [--meshes a,b,c] [--k 3,5,8]
//!     [--methods tracks,graph,dijkstra] [--threads-demo] [--early-stops]
//! ```
//!
//! `DATA_DIR` holds `manifest.json` (meshes with `name`, `file`, `faces`, `references`)
//! and the exact references `reference/<mesh>.src<v>.f64` (little-endian f64 per vertex).
//! Defaults: meshes alligator, bunny, horse, bunny_loop1, bunny_loop2; k = 3, 5, 8;
//! methods tracks, graph, dijkstra (Dijkstra has no k).
//!
//! Prints Markdown: a machine line, then one row per (mesh, method, k) with setup and
//! propagation seconds from one source (the first reference's vertex, one thread, best of
//! 3 repetitions below 200K faces, else 1), distance tests, pushes, mean / max relative
//! error |d − d*| / d* against that reference, peak RSS, and the tracks speed-up over the
//! graph. Each configuration runs in a child process (this program with the hidden flag
//! `--one`) so its peak RSS (`VmHWM`) is its own, mesh included.
//!
//! `--threads-demo` adds: 8 sources on one mesh (default bunny_loop1, else the first of
//! `--meshes`), tracks k = 5, one solver, `Solver::distance_rows` in a rayon pool of 1
//! then 2 threads, wall time, CPU time and speed-up. (`--methods ''` skips the main
//! table.)
//!
//! `--early-stops` adds: on the last mesh of the list (default bunny_loop2), tracks k = 5
//! from the first reference's vertex, a full run against runs that stop at a maximum
//! distance (10 %, 25 %, 50 % of the farthest) or at one target vertex (at those
//! fractions): propagation seconds, distance tests, and a check that every value they
//! keep is the full run's.

// The function-length rule (clippy.toml) is for the crates' code; an example's report
// loops are allowed to run long.
#![allow(clippy::too_many_lines)]

use geotracks::Sources;
use geotracks::{
    mesh::io::read_mesh, Euclidean, Method, Options, Solver, Source, Stop, SurfacePoint,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

mod shared_data;
use shared_data::{manifest, peak_rss_kb, read_reference, relative_error, run_child, source_of};

const DEFAULT_MESHES: &str = "alligator,bunny,horse,bunny_loop1,bunny_loop2";
const USAGE: &str = "usage: bench DATA_DIR [--meshes a,b,c] [--k 3,5,8] \
                     [--methods tracks,graph,dijkstra] [--threads-demo] [--early-stops]";
/// Meshes with fewer faces than this are timed as the best of `REPS` runs.
const REPS_BELOW_FACES: u64 = 200_000;
const REPS: u32 = 3;

fn main() {
    let argv: Vec<String> = std::env::args().collect();
    let result = if argv.get(1).map(String::as_str) == Some("--one") {
        child(&argv[2..])
    } else {
        parent(&argv)
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

/// A mesh of the manifest: its file, face count and first reference.
struct Entry {
    name: String,
    file: PathBuf,
    faces: u64,
    reference: PathBuf,
    source: u32,
}

/// What a child measured for one configuration.
struct Row {
    mesh: String,
    method: Method,
    k: f64,
    faces: u64,
    fields: [f64; FIELDS],
}

/// Values on the child's result line (after the "BENCH" tag), in the order of
/// `Row::fields`: Steiner points, setup s, propagate s, distance tests, setup tests,
/// pushes, mean and max relative error, peak RSS MB, repetitions.
const FIELDS: usize = 10;

fn list<T>(s: &str, what: &str, f: impl Fn(&str) -> Option<T>) -> Result<Vec<T>, String> {
    s.split(',')
        .filter(|x| !x.is_empty())
        .map(|x| f(x).ok_or_else(|| format!("bad {what} '{x}'")))
        .collect()
}

fn parent(argv: &[String]) -> Result<(), String> {
    let mut it = argv.iter().skip(1);
    let (mut data, mut meshes, mut demo, mut stops) = (None, None, false, false);
    let mut ks = vec![3.0, 5.0, 8.0];
    let mut methods = vec![Method::Tracks, Method::Graph, Method::Dijkstra];
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or(format!("{a} needs a value\n{USAGE}"));
        match a.as_str() {
            "--meshes" => meshes = Some(list(value()?, "mesh", |s| Some(s.to_string()))?),
            "--k" => ks = list(value()?, "k", |s| s.parse().ok().filter(|k: &f64| *k > 0.0))?,
            "--methods" => methods = list(value()?, "method", |s| s.parse().ok())?,
            "--threads-demo" => demo = true,
            "--early-stops" => stops = true,
            "-h" | "--help" => return Err(USAGE.into()),
            _ if data.is_none() && !a.starts_with("--") => data = Some(PathBuf::from(a)),
            other => return Err(format!("unexpected argument '{other}'\n{USAGE}")),
        }
    }
    let data = data.ok_or(USAGE)?;
    let explicit = meshes.is_some();
    let names = meshes.unwrap_or_else(|| DEFAULT_MESHES.split(',').map(String::from).collect());
    let entries = names
        .iter()
        .map(|n| entry(&data, n))
        .collect::<Result<Vec<_>, _>>()?;

    let cpu = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpu
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")
                .map(|r| r.trim_start_matches([' ', '\t', ':']))
        })
        .unwrap_or("unknown CPU");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Machine: {model}, {cores} cores. Command: `{}`\n",
        argv.iter()
            .map(|a| match a.is_empty() || a.contains(char::is_whitespace) {
                true => format!("'{a}'"),
                false => a.clone(),
            })
            .collect::<Vec<_>>()
            .join(" ")
    );

    let mut configs = Vec::new();
    for e in &entries {
        for &m in &methods {
            match m {
                Method::Dijkstra => configs.push((e, m, 0.0)),
                _ => configs.extend(ks.iter().map(|&k| (e, m, k))),
            }
        }
    }
    // On Linux, /proc/self/exe runs this very binary even if a rebuild replaces the file.
    let proc_exe = Path::new("/proc/self/exe");
    let exe = match proc_exe.exists() {
        true => proc_exe.to_path_buf(),
        false => std::env::current_exe().map_err(|e| format!("current_exe: {e}"))?,
    };
    let (mut rows, mut failed) = (Vec::new(), 0);
    let start = Instant::now();
    for (i, &(e, m, k)) in configs.iter().enumerate() {
        let reps = if e.faces < REPS_BELOW_FACES { REPS } else { 1 };
        let kk = if m == Method::Dijkstra {
            "—".into()
        } else {
            k.to_string()
        };
        eprint!(
            "[{}/{}] {} {m} k={kk} x{reps} ... ",
            i + 1,
            configs.len(),
            e.name
        );
        let t = Instant::now();
        match measure_in_child(&exe, e, m, k, reps) {
            Ok(fields) => {
                eprintln!("{:.1} s", t.elapsed().as_secs_f64());
                rows.push(Row {
                    mesh: e.name.clone(),
                    method: m,
                    k,
                    faces: e.faces,
                    fields,
                });
            }
            Err(err) => {
                eprintln!("FAILED: {err}");
                failed += 1;
            }
        }
    }
    eprintln!("all configurations: {:.1} s", start.elapsed().as_secs_f64());
    if !rows.is_empty() {
        print_table(&rows);
    }

    if demo {
        let name = if explicit {
            names[0].as_str()
        } else {
            "bunny_loop1"
        };
        threads_demo(&entry(&data, name)?)?;
    }
    if stops {
        let last = entries.last().ok_or("no mesh")?;
        early_stops(last)?;
    }
    if failed > 0 {
        return Err(format!("{failed} configuration(s) failed (see above)"));
    }
    Ok(())
}

/// Looks `name` up in `data/manifest.json` and checks that its files exist.
fn entry(data: &Path, name: &str) -> Result<Entry, String> {
    let list = manifest(data)?;
    let m = list.iter().find(|m| m.name == name).ok_or_else(|| {
        format!(
            "mesh '{name}' is not in {}",
            data.join("manifest.json").display()
        )
    })?;
    let file = data.join(&m.file);
    let reference = m
        .references
        .first()
        .ok_or(format!("{name}: no reference in manifest"))?;
    let source = source_of(reference)?;
    let reference = data.join(reference);
    for p in [&file, &reference] {
        if !p.is_file() {
            return Err(format!("{name}: missing file {}", p.display()));
        }
    }
    Ok(Entry {
        name: name.to_string(),
        file,
        faces: m.faces,
        reference,
        source,
    })
}

fn measure_in_child(
    exe: &Path,
    e: &Entry,
    m: Method,
    k: f64,
    reps: u32,
) -> Result<[f64; FIELDS], String> {
    let args = [
        e.file.display().to_string(),
        e.reference.display().to_string(),
        e.source.to_string(),
        m.to_string(),
        k.to_string(),
        reps.to_string(),
    ];
    let line = run_child(exe, &args, "BENCH\t")?;
    let fields: Vec<f64> = list(&line.replace('\t', ","), "field", |s| s.parse().ok())?;
    let n = fields.len();
    fields
        .try_into()
        .map_err(|_| format!("child printed {n} fields, expected {FIELDS}"))
}

/// The child: `--one MESH REFERENCE SOURCE METHOD K REPS`; prints one `BENCH` line.
fn child(args: &[String]) -> Result<(), String> {
    let [mesh, reference, source, method, k, reps] = args else {
        return Err("--one takes MESH REFERENCE SOURCE METHOD K REPS".into());
    };
    let source: u32 = source
        .parse()
        .map_err(|_| format!("bad source '{source}'"))?;
    let method: Method = method.parse()?;
    let k: f64 = k.parse().map_err(|_| format!("bad k '{k}'"))?;
    let reps: u32 = reps.parse().map_err(|_| format!("bad reps '{reps}'"))?;
    let mesh = read_mesh(mesh).map_err(|e| e.to_string())?;
    let exact = read_reference(Path::new(reference))?;
    let mut options = Options::DEFAULT.with_method(method);
    if method != Method::Dijkstra {
        options = options.with_k(k);
    }
    let mut best: Option<(geotracks::Stats, Vec<f64>)> = None;
    for _ in 0..reps.max(1) {
        let solver = Solver::new(&mesh, Euclidean, &options).map_err(|e| e.to_string())?;
        let mut ws = solver.workspace();
        let stats = solver
            .run(&mut ws, &[source])
            .map_err(|e| e.to_string())?
            .stats()
            .clone();
        let total = stats.setup_seconds + stats.propagate_seconds;
        if best
            .as_ref()
            .is_none_or(|(b, _)| total < b.setup_seconds + b.propagate_seconds)
        {
            best = Some((stats, ws.vertex_distances().to_vec()));
        }
    }
    let (s, d) = best.ok_or("no repetition ran")?;
    if d.len() != exact.len() {
        return Err(format!(
            "{reference}: {} values for a mesh of {} vertices",
            exact.len(),
            d.len()
        ));
    }
    let (mean, max) = relative_error(&d, &exact);
    let rss_mb = peak_rss_kb()? / 1024.0;
    let f = [
        s.steiner_points as f64,
        s.setup_seconds,
        s.propagate_seconds,
        s.distance_tests as f64,
        s.setup_distance_tests as f64,
        s.pushes as f64,
        mean,
        max,
        rss_mb,
        reps as f64,
    ];
    let line: Vec<String> = f.iter().map(|x| x.to_string()).collect();
    println!("BENCH\t{}", line.join("\t"));
    Ok(())
}

fn secs(x: f64) -> String {
    if x < 0.1 {
        format!("{x:.4}")
    } else {
        format!("{x:.3}")
    }
}

fn print_table(rows: &[Row]) {
    println!(
        "Single source (the first reference's vertex), one thread, Euclidean metric. Times are \
         the best of {REPS} runs (by setup + propagate) for meshes under {REPS_BELOW_FACES} \
         faces, else of 1; setup = Solver::new (Steiner layout, tables) + workspace sizing; \
         mesh reading excluded. Distance tests: during propagation (+ once in setup). Peak \
         RSS: VmHWM of a child process per row (mesh, reference and all repetitions \
         included). Speed-up: graph propagate / tracks propagate at the same mesh and k.\n"
    );
    println!(
        "| mesh | faces | method | k | Steiner pts | setup s | propagate s | total s | \
         distance tests (+ setup) | pushes | mean rel err | max rel err | peak RSS MB | \
         tracks speed-up | runs |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let [steiner, setup, prop, tests, setup_tests, pushes, mean, max, rss, reps] = r.fields;
        let k = if r.method == Method::Dijkstra {
            "—".to_string()
        } else {
            r.k.to_string()
        };
        let speedup = (r.method == Method::Tracks)
            .then(|| {
                rows.iter()
                    .find(|g| g.mesh == r.mesh && g.method == Method::Graph && g.k == r.k)
            })
            .flatten()
            .map_or("—".to_string(), |g| format!("{:.2}×", g.fields[2] / prop));
        println!(
            "| {} | {} | {} | {k} | {steiner} | {} | {} | {} | {tests} (+{setup_tests}) | \
             {pushes} | {:.3} % | {:.2} % | {rss:.0} | {speedup} | {reps} |",
            r.mesh,
            r.faces,
            r.method,
            secs(setup),
            secs(prop),
            secs(setup + prop),
            100.0 * mean,
            100.0 * max,
        );
    }
}

fn threads_demo(e: &Entry) -> Result<(), String> {
    const SOURCES: u32 = 8;
    eprintln!("threads demo on {} ...", e.name);
    let mesh = read_mesh(&e.file).map_err(|err| err.to_string())?;
    let t = Instant::now();
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(5.0);
    let solver = Solver::new(&mesh, Euclidean, &options).map_err(|err| err.to_string())?;
    let setup = t.elapsed().as_secs_f64();
    let nv = mesh.positions().len() as u64;
    let sources: Vec<u32> = (0..SOURCES as u64)
        .map(|i| (i * nv / SOURCES as u64) as u32)
        .collect();
    let mut times: Vec<(f64, f64)> = Vec::new();
    let mut first: Option<Vec<Vec<f64>>> = None;
    for threads in [1, 2] {
        let (t, cpu) = (Instant::now(), cpu_seconds());
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|err| err.to_string())?;
        let rows = pool
            .install(|| solver.distance_rows(&sources, None))
            .map_err(|err| err.to_string())?
            .into_iter()
            .map(|row| row.distances)
            .collect::<Vec<_>>();
        times.push((t.elapsed().as_secs_f64(), cpu_seconds() - cpu));
        match &first {
            None => first = Some(rows),
            Some(f) if *f != rows => return Err("1- and 2-thread results differ".into()),
            Some(_) => {}
        }
    }
    println!(
        "\n## Many sources in parallel\n\n{} ({} faces), tracks k = 5, {SOURCES} sources \
         (vertices {sources:?}), one shared solver (setup {setup:.3} s, not in the times), \
         `Solver::distance_rows(&sources, None)` (full vertex rows) inside a rayon pool of n threads; CPU s = user + system time of \
         the process during the call.\n",
        e.name, e.faces
    );
    println!("| threads | wall s | CPU s | s per source | speed-up |\n|---:|---:|---:|---:|---:|");
    for (n, (t, cpu)) in times.iter().enumerate() {
        println!(
            "| {} | {t:.3} | {cpu:.2} | {:.3} | {:.2}× |",
            n + 1,
            t / SOURCES as f64,
            times[0].0 / t
        );
    }
    Ok(())
}

/// Early stops against a full run on one mesh: what they save, and that they agree.
fn early_stops(e: &Entry) -> Result<(), String> {
    eprintln!("early stops on {} ...", e.name);
    let mesh = read_mesh(&e.file).map_err(|err| err.to_string())?;
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(5.0))
        .map_err(|err| err.to_string())?;
    let source = [Source::new(e.source)];
    let mut ws = solver.workspace();
    let full = solver
        .run(&mut ws, Sources::from(&source).until(&Stop::NONE))
        .map_err(|err| err.to_string())?
        .stats()
        .clone();
    let reference: Vec<f64> = ws.node_distances().to_vec();
    let far = ws
        .vertex_distances()
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    println!(
        "\n## Early stops\n\n{} ({} faces), tracks k = 5, source vertex {}; farthest vertex at \
         {far:.4}. Every value a stopped run keeps equals the full run's (checked).\n",
        e.name, e.faces, e.source
    );
    println!(
        "| run | propagate s | distance tests | of the full run's tests |\n|---|---:|---:|---:|"
    );
    println!(
        "| full | {:.3} | {} | 100 % |",
        full.propagate_seconds, full.distance_tests
    );
    for fraction in [0.1, 0.25, 0.5] {
        let target = (0..mesh.positions().len() as u32)
            .min_by(|&a, &b| {
                let off = |v: u32| (reference[v as usize] - fraction * far).abs();
                off(a).total_cmp(&off(b))
            })
            .ok_or("empty mesh")?;
        let stops = [
            (
                format!("max distance {:.0} % of farthest", 100.0 * fraction),
                Stop::NONE.with_max_distance(fraction * far),
            ),
            (
                format!("target vertex {target} at {:.0} %", 100.0 * fraction),
                Stop::NONE.with_targets(vec![SurfacePoint::Vertex(target)]),
            ),
        ];
        for (name, stop) in stops {
            let stats = solver
                .run(&mut ws, Sources::from(&source).until(&stop))
                .map_err(|err| err.to_string())?
                .stats()
                .clone();
            let agree = ws
                .node_distances()
                .iter()
                .zip(&reference)
                .all(|(a, b)| a.is_infinite() || a == b);
            let missed =
                name.starts_with("target") && ws.node_distances()[target as usize].is_infinite();
            if !agree || missed {
                return Err(format!("{name}: values differ from the full run"));
            }
            println!(
                "| {name} | {:.3} | {} | {:.1} % |",
                stats.propagate_seconds,
                stats.distance_tests,
                100.0 * stats.distance_tests as f64 / full.distance_tests as f64
            );
        }
    }
    Ok(())
}

/// CPU seconds (user + system, all threads) of this process so far, from
/// `/proc/self/stat` in clock ticks of 1/100 s (Linux's usual `CLK_TCK`); 0 if unreadable.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after_name = stat.rsplit_once(')').map_or("", |(_, r)| r);
    // Fields after the name start at field 3 (state); utime and stime are fields 14, 15.
    let ticks: f64 = after_name
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|x| x.parse::<f64>().ok())
        .sum();
    ticks / 100.0
}
