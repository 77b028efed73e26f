//! `eval --engines`: each engine against every exact reference of a data directory, with
//! its time, work and memory, the anisotropic references, the peers' figures from
//! `peers.md` beside ours, and optionally a plot. What it prints is described in the
//! doc comment of `main.rs`.

use super::shared_data::{manifest, peak_rss_kb, read_reference, run_child, source_of};
use geotracks::mesh::{io::read_mesh, TriMesh};
use geotracks::{Euclidean, Method, Metric, Options, Solver, Stats, Tensor};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const USAGE: &str =
    "usage: eval DATA_DIR --engines [--methods wave:1,wave:2,wave:3,wave:5,tracks:5,dijkstra] \
     [--meshes a,b] [--max-faces N] [--reps N] [--reps-below FACES] [--no-aniso] \
     [--plot MESH:FILE.png] [--plot-methods LIST]";
const DEFAULT_METHODS: &str = "wave:1,wave:2,wave:3,wave:5,tracks:5,dijkstra";
const DEFAULT_PLOT_METHODS: &str =
    "wave:1,wave:2,wave:3,wave:4,wave:5,tracks:1,tracks:2,tracks:3,tracks:5,tracks:8,dijkstra";

/// One engine at one k (`k` is unused for Dijkstra).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    pub method: Method,
    pub k: f64,
}

impl Config {
    fn parse(s: &str) -> Result<Config, String> {
        let (name, k) = match s.split_once(':') {
            Some((name, k)) => (name, Some(k)),
            None => (s, None),
        };
        let method: Method = name.parse()?;
        match (method, k) {
            (Method::Dijkstra, None) => Ok(Config { method, k: 0.0 }),
            (Method::Dijkstra, Some(_)) => {
                Err("dijkstra takes no k (it has no Steiner points)".into())
            }
            (_, None) => Err(format!("'{s}': give a k, as in {name}:5")),
            (_, Some(k)) => {
                let k: f64 = k.parse().map_err(|_| format!("'{s}': bad k '{k}'"))?;
                if k > 0.0 && k.is_finite() {
                    Ok(Config { method, k })
                } else if method == Method::Wave {
                    Err(format!(
                        "'{s}': k must be > 0; the wave engine puts at least one point on \
                         every edge, so there is no wave at k = 0 (vertices only is `dijkstra`)"
                    ))
                } else {
                    Err(format!(
                        "'{s}': k must be > 0 (vertices only is `dijkstra`)"
                    ))
                }
            }
        }
    }

    /// `wave:5`, `dijkstra`: what `--methods` takes and the child receives.
    fn spec(&self) -> String {
        match self.method {
            Method::Dijkstra => "dijkstra".into(),
            m => format!("{m}:{}", self.k),
        }
    }

    fn k_text(&self) -> String {
        match self.method {
            Method::Dijkstra => "—".into(),
            _ => self.k.to_string(),
        }
    }
}

fn configs(list: &str) -> Result<Vec<Config>, String> {
    list.split(',')
        .filter(|s| !s.is_empty())
        .map(Config::parse)
        .collect()
}

/// One mesh under one metric with its exact references.
struct Case {
    mesh: String,
    faces: u64,
    file: PathBuf,
    /// The per-face tensor file (`xx xy xz yy yz zz` per input face); `None`: Euclidean.
    tensor: Option<PathBuf>,
    /// (source vertex, exact distances file).
    references: Vec<(u32, PathBuf)>,
}

/// What a child measured for one (case, config).
#[derive(Clone, Debug, Default)]
struct Measured {
    /// The method that ran (the wave engine falls back to tracks for a metric that is
    /// not face-flat).
    ran: String,
    vertices: f64,
    steiner: f64,
    setup: f64,
    /// Mean over the references of the best propagate time of each.
    propagate: f64,
    /// Means over the references (counts are the same in every repetition).
    tests: f64,
    settles: f64,
    pushes: f64,
    /// Mean over the references of the per-reference mean relative error.
    mean: f64,
    /// Max over the references of the max relative error.
    max: f64,
    /// Max over the references and vertices of (d* − d) / d*.
    below: f64,
    rss_mb: f64,
    reps: f64,
    sources: f64,
}

impl Measured {
    fn nodes(&self) -> f64 {
        self.vertices + self.steiner
    }

    fn to_line(&self) -> String {
        let fields = [
            ("ran", self.ran.clone()),
            ("vertices", self.vertices.to_string()),
            ("steiner", self.steiner.to_string()),
            ("setup", self.setup.to_string()),
            ("propagate", self.propagate.to_string()),
            ("tests", self.tests.to_string()),
            ("settles", self.settles.to_string()),
            ("pushes", self.pushes.to_string()),
            ("mean", self.mean.to_string()),
            ("max", self.max.to_string()),
            ("below", self.below.to_string()),
            ("rss_mb", self.rss_mb.to_string()),
            ("reps", self.reps.to_string()),
            ("sources", self.sources.to_string()),
        ];
        let fields: Vec<String> = fields.iter().map(|(k, v)| format!("{k}={v}")).collect();
        format!("EVAL\t{}", fields.join("\t"))
    }

    fn from_line(line: &str) -> Result<Measured, String> {
        let map: BTreeMap<&str, &str> =
            line.split('\t').filter_map(|f| f.split_once('=')).collect();
        let num = |key: &str| -> Result<f64, String> {
            map.get(key)
                .and_then(|v| v.parse().ok())
                .ok_or_else(|| format!("the child's line has no number '{key}'"))
        };
        Ok(Measured {
            ran: map.get("ran").unwrap_or(&"?").to_string(),
            vertices: num("vertices")?,
            steiner: num("steiner")?,
            setup: num("setup")?,
            propagate: num("propagate")?,
            tests: num("tests")?,
            settles: num("settles")?,
            pushes: num("pushes")?,
            mean: num("mean")?,
            max: num("max")?,
            below: num("below")?,
            rss_mb: num("rss_mb")?,
            reps: num("reps")?,
            sources: num("sources")?,
        })
    }
}

struct Row {
    case: usize,
    config: Config,
    /// In the main table (else measured for the plot only).
    main: bool,
    m: Measured,
}

struct Args {
    data: PathBuf,
    methods: Vec<Config>,
    meshes: Option<Vec<String>>,
    max_faces: u64,
    reps: u32,
    reps_below: u64,
    aniso: bool,
    plot: Option<(String, PathBuf)>,
    plot_methods: Vec<Config>,
}

fn parse_args(argv: &[String]) -> Result<Args, String> {
    let mut it = argv.iter().skip(1);
    let mut data = None;
    let mut args = Args {
        data: PathBuf::new(),
        methods: configs(DEFAULT_METHODS)?,
        meshes: None,
        max_faces: u64::MAX,
        reps: 3,
        reps_below: u64::MAX,
        aniso: true,
        plot: None,
        plot_methods: configs(DEFAULT_PLOT_METHODS)?,
    };
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or(format!("{a} needs a value\n{USAGE}"));
        let number = |v: &str| {
            v.parse::<u64>()
                .map_err(|_| format!("{a} takes a number, not '{v}'"))
        };
        match a.as_str() {
            "--engines" => {}
            "--methods" => args.methods = configs(value()?)?,
            "--plot-methods" => args.plot_methods = configs(value()?)?,
            "--meshes" => {
                args.meshes = Some(value()?.split(',').map(String::from).collect());
            }
            "--max-faces" => args.max_faces = number(value()?)?,
            "--reps" => args.reps = number(value()?)?.max(1) as u32,
            "--reps-below" => args.reps_below = number(value()?)?,
            "--no-aniso" => args.aniso = false,
            "--plot" => {
                let v = value()?;
                let (mesh, file) = v
                    .split_once(':')
                    .ok_or(format!("--plot takes MESH:FILE.png, not '{v}'"))?;
                args.plot = Some((mesh.to_string(), PathBuf::from(file)));
            }
            "-h" | "--help" => return Err(USAGE.into()),
            _ if data.is_none() && !a.starts_with("--") => data = Some(PathBuf::from(a)),
            other => return Err(format!("unexpected argument '{other}'\n{USAGE}")),
        }
    }
    args.data = data.ok_or(USAGE)?;
    if args.methods.is_empty() {
        return Err("--methods is empty".into());
    }
    Ok(args)
}

/// The Euclidean cases (manifest meshes with references), then the anisotropic ones
/// (`reference/aniso/<mesh>.aniso.src<v>.f64` with its `.tensor`), filtered.
fn cases(args: &Args) -> Result<Vec<Case>, String> {
    let entries = manifest(&args.data)?;
    let wanted = |name: &str, faces: u64| {
        let listed = args
            .meshes
            .as_ref()
            .is_none_or(|m| m.iter().any(|x| x == name));
        if listed && faces > args.max_faces {
            eprintln!("skipping {name} ({faces} faces > --max-faces)");
        }
        listed && faces <= args.max_faces
    };
    let mut out = Vec::new();
    for e in &entries {
        if e.references.is_empty() || !wanted(&e.name, e.faces) {
            continue;
        }
        let references = e
            .references
            .iter()
            .map(|r| Ok((source_of(r)?, args.data.join(r))))
            .collect::<Result<_, String>>()?;
        out.push(Case {
            mesh: e.name.clone(),
            faces: e.faces,
            file: args.data.join(&e.file),
            tensor: None,
            references,
        });
    }
    if !args.aniso {
        return Ok(out);
    }
    let dir = args.data.join("reference").join("aniso");
    let mut files: Vec<PathBuf> = match std::fs::read_dir(&dir) {
        Ok(d) => d.filter_map(|e| e.ok()).map(|e| e.path()).collect(),
        Err(_) => {
            eprintln!("no {}: no anisotropic cases", dir.display());
            Vec::new()
        }
    };
    files.sort();
    for f in files {
        let name = f
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .to_string();
        let Some((mesh, rest)) = name.split_once(".aniso.") else {
            continue;
        };
        if !rest.ends_with(".f64") {
            continue;
        }
        let source = source_of(&name)?;
        let tensor = f.with_extension("tensor");
        if !tensor.is_file() {
            return Err(format!(
                "{}: no {} beside it",
                f.display(),
                tensor.display()
            ));
        }
        let e = entries.iter().find(|e| e.name == mesh).ok_or(format!(
            "{}: mesh '{mesh}' is not in the manifest",
            f.display()
        ))?;
        if !wanted(mesh, e.faces) {
            continue;
        }
        out.push(Case {
            mesh: mesh.to_string(),
            faces: e.faces,
            file: args.data.join(&e.file),
            tensor: Some(tensor),
            references: vec![(source, f)],
        });
    }
    Ok(out)
}

fn quote(argv: &[String]) -> String {
    argv.iter()
        .map(|a| match a.is_empty() || a.contains(char::is_whitespace) {
            true => format!("'{a}'"),
            false => a.clone(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The output of a shell command, trimmed; `None` if it fails.
fn shell(program: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The 1-, 5- and 15-minute load averages.
fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// The machine, the commit and the date, for the caption.
struct Context {
    machine: String,
    commit: String,
    date: String,
    command: String,
    load_start: String,
    load_end: String,
    seconds: f64,
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpu
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")
                .map(|r| r.trim_start_matches([' ', '\t', ':']).to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let mhz = cpu
        .lines()
        .find_map(|l| l.strip_prefix("cpu MHz"))
        .and_then(|r| r.trim_start_matches([' ', '\t', ':']).parse::<f64>().ok());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mem = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|m| {
            m.lines()
                .find_map(|l| l.strip_prefix("MemTotal:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        })
        .map_or(String::new(), |kb| {
            format!(", {:.0} GiB", kb / 1024.0 / 1024.0)
        });
    match mhz {
        Some(mhz) => format!("{model} @ {:.2} GHz, {cores} cores{mem}", mhz / 1000.0),
        None => format!("{model}, {cores} cores{mem}"),
    }
}

/// The parent: runs every (case, config) in a child, then prints the tables.
pub fn main(argv: &[String]) -> Result<(), String> {
    let args = parse_args(argv)?;
    let cases = cases(&args)?;
    if cases.is_empty() {
        return Err("no mesh with references matches".into());
    }
    let plot_case = match &args.plot {
        Some((mesh, _)) => Some(
            cases
                .iter()
                .position(|c| c.tensor.is_none() && &c.mesh == mesh)
                .ok_or(format!("--plot: '{mesh}' is not among the measured meshes"))?,
        ),
        None => None,
    };
    let commit = shell("git", &["rev-parse", "--short", "HEAD"]).unwrap_or("unknown".into());
    let dirty = shell("git", &["status", "--porcelain", "--untracked-files=no"])
        .is_some_and(|s| !s.is_empty());
    let mut context = Context {
        machine: machine(),
        commit: if dirty {
            format!("{commit}+changes")
        } else {
            commit
        },
        date: shell("date", &["-u", "+%Y-%m-%d %H:%M UTC"]).unwrap_or("unknown".into()),
        command: quote(argv),
        load_start: load(),
        load_end: String::new(),
        seconds: 0.0,
    };

    let mut jobs: Vec<(usize, Config, bool)> = Vec::new();
    for i in 0..cases.len() {
        for &c in &args.methods {
            jobs.push((i, c, true));
        }
        if plot_case == Some(i) {
            for &c in &args.plot_methods {
                if !args.methods.contains(&c) {
                    jobs.push((i, c, false));
                }
            }
        }
    }
    // On Linux, /proc/self/exe runs this very binary even if a rebuild replaces the file.
    let proc_exe = Path::new("/proc/self/exe");
    let exe = match proc_exe.exists() {
        true => proc_exe.to_path_buf(),
        false => std::env::current_exe().map_err(|e| format!("current_exe: {e}"))?,
    };
    let start = Instant::now();
    let (mut rows, mut failed) = (Vec::new(), 0);
    for (n, &(i, config, main)) in jobs.iter().enumerate() {
        let case = &cases[i];
        let reps = if case.faces < args.reps_below {
            args.reps
        } else {
            1
        };
        eprint!(
            "[{}/{}] {}{} {} x{reps} × {} source(s) ... ",
            n + 1,
            jobs.len(),
            case.mesh,
            if case.tensor.is_some() {
                " (aniso)"
            } else {
                ""
            },
            config.spec(),
            case.references.len()
        );
        let t = Instant::now();
        match measure_in_child(&exe, case, config, reps) {
            Ok(m) => {
                eprintln!("{:.1} s", t.elapsed().as_secs_f64());
                rows.push(Row {
                    case: i,
                    config,
                    main,
                    m,
                });
            }
            Err(e) => {
                eprintln!("FAILED: {e}");
                failed += 1;
            }
        }
    }
    context.seconds = start.elapsed().as_secs_f64();
    context.load_end = load();
    eprintln!("all configurations: {:.1} s", context.seconds);

    print_tables(&args, &context, &cases, &rows);
    let peers = std::fs::read_to_string(args.data.join("peers.md"))
        .ok()
        .map(|text| Peers::parse(&text));
    if let Some(peers) = &peers {
        print_peers(peers, &context, &cases, &rows);
    }
    if let (Some((_, file)), Some(i)) = (&args.plot, plot_case) {
        print_plot_data(&cases[i], &rows, i);
        plot(file, &context, &cases[i], &rows, i, peers.as_ref())?;
        eprintln!("wrote {}", file.display());
    }
    if failed > 0 {
        return Err(format!("{failed} configuration(s) failed (see above)"));
    }
    Ok(())
}

fn measure_in_child(
    exe: &Path,
    case: &Case,
    config: Config,
    reps: u32,
) -> Result<Measured, String> {
    let metric = match &case.tensor {
        Some(t) => format!("tensor={}", t.display()),
        None => "euclidean".into(),
    };
    let mut args = vec![case.file.display().to_string(), metric];
    args.extend([config.spec(), reps.to_string()]);
    args.extend(
        case.references
            .iter()
            .map(|(s, p)| format!("{s}={}", p.display())),
    );
    Measured::from_line(&run_child(exe, &args, "EVAL\t")?)
}

/// The child: `--one MESH METRIC CONFIG REPS SOURCE=REFERENCE...`, where METRIC is
/// `euclidean` or `tensor=FILE`; prints one `EVAL` line.
pub fn child(args: &[String]) -> Result<(), String> {
    let [mesh, metric, config, reps, references @ ..] = args else {
        return Err("--one takes MESH METRIC CONFIG REPS SOURCE=REFERENCE...".into());
    };
    let config = Config::parse(config)?;
    let reps: u32 = reps.parse().map_err(|_| format!("bad reps '{reps}'"))?;
    let references: Vec<(u32, PathBuf)> = references
        .iter()
        .map(|r| {
            let (s, p) = r.split_once('=').ok_or(format!("bad reference '{r}'"))?;
            let s = s.parse().map_err(|_| format!("bad source '{s}'"))?;
            Ok((s, PathBuf::from(p)))
        })
        .collect::<Result<_, String>>()?;
    let mesh = read_mesh(mesh).map_err(|e| format!("{mesh}: {e}"))?;
    let mut options = Options::DEFAULT.with_method(config.method);
    if config.method != Method::Dijkstra {
        options = options.with_k(config.k);
    }
    let mut m = match metric.strip_prefix("tensor=") {
        Some(file) => {
            let tensor = read_tensor(Path::new(file), &mesh)?;
            measure(&mesh, tensor, &options, &references, reps)?
        }
        None if metric == "euclidean" => measure(&mesh, Euclidean, &options, &references, reps)?,
        None => return Err(format!("unknown metric '{metric}'")),
    };
    m.rss_mb = peak_rss_kb()? / 1024.0;
    println!("{}", m.to_line());
    Ok(())
}

/// `M` once per face of the mesh file, `xx xy xz yy yz zz` per line (`#` comments), as
/// the CLI's `--tensor` reads it: rows of dropped faces are skipped.
fn read_tensor(path: &Path, mesh: &TriMesh) -> Result<Tensor, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let v: Vec<f64> = line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .map(|s| s.parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("{}:{}: {e}", path.display(), i + 1))?;
        let row: [f64; 6] = v
            .try_into()
            .map_err(|_| format!("{}:{}: expected 6 values", path.display(), i + 1))?;
        rows.push(row);
    }
    if rows.len() != mesh.input_face_count() {
        return Err(format!(
            "{}: {} tensors for {} faces in the mesh file",
            path.display(),
            rows.len(),
            mesh.input_face_count()
        ));
    }
    let kept: Vec<[f64; 6]> = (0..mesh.face_count() as u32)
        .map(|f| rows[mesh.input_face(f)])
        .collect();
    Tensor::from_world(mesh, &kept).map_err(|e| format!("{}: {e}", path.display()))
}

/// Mean and max of |d − d*| / d*, and max of (d* − d) / d*, over vertices with d* > 0.
fn errors(d: &[f64], exact: &[f64]) -> (f64, f64, f64) {
    let (mut sum, mut max, mut below, mut n) = (0.0, 0.0f64, f64::NEG_INFINITY, 0usize);
    for (a, b) in d.iter().zip(exact) {
        if *b > 0.0 {
            let e = (a - b) / b;
            sum += e.abs();
            max = max.max(e.abs());
            below = below.max(-e);
            n += 1;
        }
    }
    (sum / n.max(1) as f64, max, below)
}

fn measure<M: Metric>(
    mesh: &TriMesh,
    metric: M,
    options: &Options,
    references: &[(u32, PathBuf)],
    reps: u32,
) -> Result<Measured, String> {
    let solver = Solver::new(mesh, metric, options).map_err(|e| e.to_string())?;
    let mut ws = solver.workspace();
    let n = references.len() as f64;
    let mut m = Measured {
        below: f64::NEG_INFINITY,
        reps: reps as f64,
        sources: n,
        ..Measured::default()
    };
    for (source, path) in references {
        let exact = read_reference(path)?;
        if exact.len() != mesh.vertex_count() {
            return Err(format!(
                "{}: {} values for a mesh of {} vertices",
                path.display(),
                exact.len(),
                mesh.vertex_count()
            ));
        }
        let mut best: Option<Stats> = None;
        for _ in 0..reps.max(1) {
            let s = solver
                .run(&mut ws, &[*source])
                .map_err(|e| e.to_string())?
                .stats()
                .clone();
            if let Some(b) = &best {
                let counts = |s: &Stats| (s.distance_tests, s.settles, s.pushes);
                if counts(b) != counts(&s) {
                    eprintln!(
                        "warning: source {source}: counts differ between repetitions: {:?} then {:?}",
                        counts(b),
                        counts(&s)
                    );
                }
            }
            if m.ran.is_empty() {
                m.ran = s.method.to_string();
                m.vertices = s.vertices as f64;
                m.steiner = s.steiner_points as f64;
                m.setup = s.setup_seconds;
            }
            if best
                .as_ref()
                .is_none_or(|b| s.propagate_seconds < b.propagate_seconds)
            {
                best = Some(s);
            }
        }
        let s = best.ok_or("no repetition ran")?;
        let (mean, max, below) = errors(ws.vertex_distances(), &exact);
        m.propagate += s.propagate_seconds / n;
        m.tests += s.distance_tests as f64 / n;
        m.settles += s.settles as f64 / n;
        m.pushes += s.pushes as f64 / n;
        m.mean += mean / n;
        m.max = m.max.max(max);
        m.below = m.below.max(below);
    }
    Ok(m)
}

/// A relative error (a fraction) in %, to 3 significant digits.
pub fn pct(x: f64) -> String {
    let p = 100.0 * x;
    if !p.is_finite() {
        return format!("{p} %");
    }
    if p == 0.0 {
        return "0 %".into();
    }
    if p < 1e-3 {
        return format!("{p:.1e} %");
    }
    let digits = (2 - p.log10().floor() as i32).max(0) as usize;
    format!("{p:.digits$} %")
}

/// "source" or "sources" after a count.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        "source"
    } else {
        "sources"
    }
}

/// How far below exact the lowest value is (a fraction), or "none" if none is.
fn below(x: f64) -> String {
    if x > 0.0 {
        format!("{x:.1e}")
    } else {
        "none".into()
    }
}

pub fn secs(x: f64) -> String {
    if x < 0.01 {
        format!("{x:.5}")
    } else if x < 0.1 {
        format!("{x:.4}")
    } else {
        format!("{x:.3}")
    }
}

fn label(config: &Config) -> String {
    match config.method {
        Method::Tracks | Method::Graph => format!("{} (= graph)", config.method),
        m => m.to_string(),
    }
}

fn print_tables(args: &Args, c: &Context, cases: &[Case], rows: &[Row]) {
    let reps = match args.reps_below {
        u64::MAX => format!("best of {} runs per source", args.reps),
        f => format!(
            "best of {} runs per source below {f} faces, else 1",
            args.reps
        ),
    };
    println!(
        "Measured {} on {} at commit {}, `{}`, {:.0} s in all; load average (1, 5, 15 min) \
         {} at the start, {} at the end.\n",
        c.date, c.machine, c.commit, c.command, c.seconds, c.load_start, c.load_end
    );
    summary(args, cases, rows);
    for (aniso, title) in [
        (
            false,
            "Euclidean metric, exact references `reference/<mesh>.src<v>.f64`",
        ),
        (
            true,
            "Constant anisotropic tensor, exact references `reference/aniso/<mesh>.aniso.src0.f64`",
        ),
    ] {
        let rows: Vec<&Row> = rows
            .iter()
            .filter(|r| r.main && cases[r.case].tensor.is_some() == aniso)
            .collect();
        if rows.is_empty() {
            continue;
        }
        println!(
            "### {title}\n\nErrors |d − d*| / d* over vertices with d* > 0: mean = mean over \
             the references of each one's mean, max = max over them; most below = max of \
             (d* − d) / d* (\"none\": no value below exact). Propagate s: `Stats::propagate_seconds`, \
             {reps}, averaged over the sources; setup s: `Solver::new` + workspace sizing (once). \
             Nodes: vertices + Steiner points. Per node: distance tests, settles, propagate ns. \
             Peak RSS: `VmHWM` of one child process per row (mesh, solver, workspace, one \
             reference at a time). One thread.\n"
        );
        println!(
            "| mesh | faces | srcs | method | k | nodes | mean err | max err | most below \
             exact | propagate s | setup s | tests / node | settles / node | ns / node | \
             peak RSS MB | runs |"
        );
        println!("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
        for r in rows {
            let case = &cases[r.case];
            let m = &r.m;
            let nodes = m.nodes();
            let ran = if m.ran == r.config.method.to_string() {
                String::new()
            } else {
                format!(" (ran {})", m.ran)
            };
            println!(
                "| {} | {} | {} | {}{ran} | {} | {} | {} | {} | {} | {} | {} | {:.2} | {:.2} | \
                 {:.0} | {:.0} | {} |",
                case.mesh,
                case.faces,
                m.sources,
                label(&r.config),
                r.config.k_text(),
                nodes,
                pct(m.mean),
                pct(m.max),
                below(m.below),
                secs(m.propagate),
                secs(m.setup),
                m.tests / nodes,
                m.settles / nodes,
                1e9 * m.propagate / nodes,
                m.rss_mb,
                m.reps
            );
        }
        println!();
    }
    notes(cases, rows);
}

/// One line per case: mean / max error of each configuration of `--methods`.
fn summary(args: &Args, cases: &[Case], rows: &[Row]) {
    println!("### Summary: mean / max relative error\n");
    let mut header = String::from("| mesh | metric | faces | srcs |");
    let mut rule = String::from("|---|---|---:|---:|");
    for c in &args.methods {
        header += &match c.method {
            Method::Dijkstra => " dijkstra |".to_string(),
            m => format!(" {m} k={} |", c.k),
        };
        rule += "---:|";
    }
    println!("{header}\n{rule}");
    for (i, case) in cases.iter().enumerate() {
        let mut line = format!(
            "| {} | {} | {} | {} |",
            case.mesh,
            if case.tensor.is_some() {
                "tensor"
            } else {
                "Euclidean"
            },
            case.faces,
            case.references.len()
        );
        for c in &args.methods {
            line += &match rows.iter().find(|r| r.case == i && r.config == *c) {
                Some(r) => format!(" {} / {} |", pct(r.m.mean), pct(r.m.max)),
                None => " failed |".to_string(),
            };
        }
        println!("{line}");
    }
    println!();
}

/// What a reader should not miss: the wave engine worse than the graph at the same k,
/// values below exact, a method that fell back to another.
fn notes(cases: &[Case], rows: &[Row]) {
    let mut notes = Vec::new();
    for w in rows.iter().filter(|r| r.config.method == Method::Wave) {
        let graph = rows.iter().find(|g| {
            g.case == w.case
                && matches!(g.config.method, Method::Tracks | Method::Graph)
                && g.config.k == w.config.k
        });
        if let Some(g) = graph {
            if w.m.mean > g.m.mean || w.m.max > g.m.max {
                notes.push(format!(
                    "wave is worse than the graph on {}{} at k = {}: mean {} vs {}, max {} vs {}",
                    cases[w.case].mesh,
                    if cases[w.case].tensor.is_some() {
                        " (aniso)"
                    } else {
                        ""
                    },
                    w.config.k,
                    pct(w.m.mean),
                    pct(g.m.mean),
                    pct(w.m.max),
                    pct(g.m.max)
                ));
            }
        }
    }
    for r in rows {
        if r.m.ran != r.config.method.to_string() {
            notes.push(format!(
                "{} {}: {} ran instead",
                cases[r.case].mesh,
                r.config.spec(),
                r.m.ran
            ));
        }
        if r.m.below > 1e-6 {
            notes.push(format!(
                "{} {}: a value {} (relative) below exact, over the 1e-6 the contract allows",
                cases[r.case].mesh,
                r.config.spec(),
                below(r.m.below)
            ));
        }
    }
    let mut lowest: BTreeMap<String, (f64, String)> = BTreeMap::new();
    for r in rows {
        let e = lowest
            .entry(r.config.method.to_string())
            .or_insert((f64::NEG_INFINITY, String::new()));
        if r.m.below > e.0 {
            *e = (
                r.m.below,
                format!("{} {}", cases[r.case].mesh, r.config.spec()),
            );
        }
    }
    for (method, (b, at)) in lowest {
        notes.push(format!(
            "{method}: most below exact over all rows {} ({at})",
            below(b)
        ));
    }
    println!("Checks:\n");
    for n in notes {
        println!("- {n}");
    }
    println!();
}

/// `peers.md`: per mesh, rows of named columns.
pub struct Peers {
    /// The geotracks commit the peers' table measured.
    pub commit: String,
    pub meshes: Vec<(String, Vec<BTreeMap<String, String>>)>,
}

impl Peers {
    fn parse(text: &str) -> Peers {
        let commit = text
            .split("geotracks at commit ")
            .nth(1)
            .and_then(|r| r.split(|c: char| !c.is_ascii_alphanumeric()).next())
            .unwrap_or("?")
            .to_string();
        let mut meshes: Vec<(String, Vec<BTreeMap<String, String>>)> = Vec::new();
        let mut header: Option<Vec<String>> = None;
        for line in text.lines() {
            if let Some(title) = line.strip_prefix("### ") {
                let name = title.split_whitespace().next().unwrap_or("").to_string();
                meshes.push((name, Vec::new()));
                header = None;
            } else if line.starts_with('|') {
                let cells: Vec<String> = line
                    .trim()
                    .trim_matches('|')
                    .split('|')
                    .map(|c| c.trim().to_string())
                    .collect();
                if cells.iter().all(|c| c.chars().all(|x| "-:".contains(x))) {
                    continue;
                }
                match (&header, meshes.last_mut()) {
                    (None, _) => header = Some(cells),
                    (Some(h), Some((_, rows))) => {
                        rows.push(h.iter().cloned().zip(cells).collect());
                    }
                    _ => {}
                }
            }
        }
        Peers { commit, meshes }
    }

    pub fn rows(&self, mesh: &str) -> Option<&[BTreeMap<String, String>]> {
        self.meshes
            .iter()
            .find(|(m, _)| m == mesh)
            .map(|(_, r)| r.as_slice())
    }
}

fn get<'a>(row: &'a BTreeMap<String, String>, key: &str) -> &'a str {
    row.get(key).map_or("?", String::as_str)
}

fn print_peers(peers: &Peers, c: &Context, cases: &[Case], rows: &[Row]) {
    let measured: Vec<usize> = (0..cases.len())
        .filter(|&i| cases[i].tensor.is_none() && peers.rows(&cases[i].mesh).is_some())
        .collect();
    if measured.is_empty() {
        return;
    }
    println!(
        "### Beside the peers (`peers.md`)\n\nRows marked *peers.md* are the peers' own \
         measurements, copied from `peers.md`: another 2-core machine (AMD EPYC VM) shared \
         with other jobs (their load column), geotracks at commit {} (its `geotracks` rows \
         are the tracks engine then), solve s = median of 3, peak RSS of the whole process \
         (`/usr/bin/time -v`, OBJ reading included). Rows marked *this run* are the table \
         above (commit {}, {}, load {} at the start): propagate s, best of the runs per \
         source and averaged over the sources; peak RSS of the child process. Errors: mean \
         over the same references of the per-source mean, max over them.\n",
        peers.commit, c.commit, c.machine, c.load_start
    );
    for i in measured {
        let case = &cases[i];
        println!(
            "#### {} ({} faces, {} {})\n",
            case.mesh,
            case.faces,
            case.references.len(),
            plural(case.references.len())
        );
        println!("| tool | figures | solve s | peak RSS MB | mean err | max err | load |");
        println!("|---|---|---:|---:|---:|---:|---:|");
        let load1 = c.load_start.split_whitespace().next().unwrap_or("?");
        for r in rows.iter().filter(|r| r.case == i && r.main) {
            let k = match r.config.method {
                Method::Dijkstra => String::new(),
                _ => format!(" k={}", r.config.k),
            };
            println!(
                "| geotracks {}{k} | this run | {} | {:.0} | {} | {} | {load1} |",
                label(&r.config),
                secs(r.m.propagate),
                r.m.rss_mb,
                pct(r.m.mean),
                pct(r.m.max),
            );
        }
        for p in peers.rows(&case.mesh).unwrap_or_default() {
            let tool = get(p, "tool");
            let tool = match tool.strip_prefix("geotracks") {
                Some(rest) => format!("geotracks{rest} (@{})", peers.commit),
                None => tool.to_string(),
            };
            println!(
                "| {tool} | *peers.md* | {} | {} | {} % | {} % | {} |",
                get(p, "solve s"),
                get(p, "peak RSS MB"),
                get(p, "mean err % all"),
                get(p, "max err % all"),
                get(p, "load"),
            );
        }
        println!();
    }
}

fn print_plot_data(case: &Case, rows: &[Row], i: usize) {
    println!(
        "### Plot data: {} ({} faces, {} {})\n",
        case.mesh,
        case.faces,
        case.references.len(),
        plural(case.references.len())
    );
    println!("| method | k | mean err | max err | propagate s | tests / node | ns / node | peak RSS MB |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut these: Vec<&Row> = rows.iter().filter(|r| r.case == i).collect();
    these.sort_by(|a, b| {
        (a.config.method.to_string(), a.config.k)
            .partial_cmp(&(b.config.method.to_string(), b.config.k))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for r in these {
        let nodes = r.m.nodes();
        println!(
            "| {} | {} | {} | {} | {} | {:.2} | {:.0} | {:.0} |",
            label(&r.config),
            r.config.k_text(),
            pct(r.m.mean),
            pct(r.m.max),
            secs(r.m.propagate),
            r.m.tests / nodes,
            1e9 * r.m.propagate / nodes,
            r.m.rss_mb
        );
    }
    println!();
}

fn plot(
    file: &Path,
    c: &Context,
    case: &Case,
    rows: &[Row],
    i: usize,
    peers: Option<&Peers>,
) -> Result<(), String> {
    use super::plot::{Marker, Plot, Series};
    let ours = |method: Method| -> Vec<(f64, f64, String)> {
        let mut v: Vec<(f64, f64, String)> = rows
            .iter()
            .filter(|r| r.case == i && r.config.method == method)
            .map(|r| (r.m.propagate, 100.0 * r.m.mean, format!("{}", r.config.k)))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let mut series = vec![
        Series::new(
            "wave",
            [30, 90, 200],
            Marker::Circle,
            true,
            ours(Method::Wave),
        ),
        Series::new(
            "tracks = Steiner graph",
            [230, 120, 20],
            Marker::Square,
            true,
            ours(Method::Tracks)
                .into_iter()
                .chain(ours(Method::Graph))
                .collect(),
        ),
        Series::new(
            "Dijkstra on edges",
            [90, 90, 90],
            Marker::Diamond,
            true,
            ours(Method::Dijkstra)
                .into_iter()
                .map(|(t, e, _)| (t, e, String::new()))
                .collect(),
        ),
    ];
    if let Some(rows) = peers.and_then(|p| p.rows(&case.mesh)) {
        let number = |r: &BTreeMap<String, String>, key: &str| get(r, key).parse::<f64>().ok();
        let point = |r: &BTreeMap<String, String>| {
            Some((number(r, "solve s")?, number(r, "mean err % all")?))
        };
        let commit = peers.map_or("?", |p| p.commit.as_str());
        let mut tracks: Vec<(f64, f64, String)> = rows
            .iter()
            .filter_map(|r| {
                let k = get(r, "tool").strip_prefix("geotracks k=")?;
                let (t, e) = point(r)?;
                Some((t, e, k.to_string()))
            })
            .collect();
        tracks.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series::new(
            &format!("tracks @{commit}"),
            [230, 120, 20],
            Marker::Square,
            false,
            tracks,
        ));
        let peer = |prefix: &str, name: &str, colour, marker| {
            let points: Vec<(f64, f64, String)> = rows
                .iter()
                .filter(|r| get(r, "tool").starts_with(prefix))
                .filter_map(|r| {
                    let (t, e) = point(r)?;
                    let tag = get(r, "tool").strip_prefix(prefix).unwrap_or("").trim();
                    Some((t, e, tag.to_string()))
                })
                .collect();
            Series::new(name, colour, marker, false, points)
        };
        series.push(peer("VSP", "VSP", [20, 150, 60], Marker::TriangleUp));
        series.push(peer("AVTP", "AVTP", [140, 60, 170], Marker::TriangleDown));
        series.push(peer(
            "geodesic graph",
            "geodesic graph",
            [150, 90, 40],
            Marker::Diamond,
        ));
        let mut vtp = peer("VTP", "VTP (exact)", [200, 30, 30], Marker::Circle);
        vtp.points.iter_mut().for_each(|p| p.2.clear());
        series.push(vtp);
    }
    let title = format!(
        "{}: mean relative error vs propagate time, {} faces, {} {}, one thread",
        case.mesh,
        case.faces,
        case.references.len(),
        plural(case.references.len())
    );
    let caption = vec![
        format!(
            "Filled: this run, {} at {}, {}, load {}.",
            c.date, c.commit, c.machine, c.load_start
        ),
        "Hollow: the peers' own figures from peers.md (another 2-core VM, load 2.5-3.8, solve s, \
         median of 3). Labels: k for geotracks, λ for AVTP. VTP's error (1e-14 %) is below the \
         axis: drawn on it."
            .to_string(),
    ];
    Plot {
        title,
        x_label: "propagate (solve) time, s".into(),
        y_label: "mean relative error, %".into(),
        caption,
        series,
    }
    .write_png(file)
}
