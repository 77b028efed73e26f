//! Accuracy against exact geodesics: Dijkstra on edges and the Steiner graph at
//! k = 3, 5, 8 on every mesh of a data directory that has exact references.
//!
//! ```text
//! cargo run --release --example eval -- ../shared/data [--max-faces N] [--k 3,5,8]
//! ```
//!
//! The directory holds `manifest.json` (a list of meshes with `name`, `file`, `faces`
//! and `references`), the meshes, and `reference/<mesh>.src<v>.f64` files (exact
//! distances from vertex `v`, little-endian f64 per vertex). Prints a Markdown table:
//! mean and max relative error over the references of each mesh (|d − d*| / d* over
//! vertices with d* > 0), and the distance tests of one run.

use geotracks::{distance_field, mesh::io::read_mesh, Euclidean, Method, Options};
use std::path::{Path, PathBuf};

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

struct Args {
    data: PathBuf,
    max_faces: u64,
    ks: Vec<f64>,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut data = None;
    let mut max_faces = 400_000;
    let mut ks = vec![3.0, 5.0, 8.0];
    while let Some(a) = it.next() {
        match a.as_str() {
            "--max-faces" => {
                max_faces = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .ok_or("--max-faces takes a number")?
            }
            "--k" => {
                ks = it
                    .next()
                    .ok_or("--k takes a list like 3,5,8")?
                    .split(',')
                    .map(|s| s.parse::<f64>().map_err(|_| format!("bad k '{s}'")))
                    .collect::<Result<_, _>>()?
            }
            _ if data.is_none() => data = Some(PathBuf::from(a)),
            other => return Err(format!("unexpected argument '{other}'")),
        }
    }
    Ok(Args {
        data: data.ok_or("usage: eval DATA_DIR [--max-faces N] [--k 3,5,8]")?,
        max_faces,
        ks,
    })
}

fn read_reference(path: &Path) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect())
}

fn source_of(reference: &str) -> Result<u32, String> {
    reference
        .rsplit_once(".src")
        .and_then(|(_, s)| s.strip_suffix(".f64"))
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("cannot read the source vertex from '{reference}'"))
}

fn relative_error(d: &[f64], exact: &[f64]) -> (f64, f64) {
    let (mut sum, mut max, mut n) = (0.0, 0.0f64, 0usize);
    for (a, b) in d.iter().zip(exact) {
        if *b > 0.0 {
            let e = (a - b).abs() / b;
            sum += e;
            max = max.max(e);
            n += 1;
        }
    }
    (sum / n.max(1) as f64, max)
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let manifest_path = args.data.join("manifest.json");
    let manifest: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(&manifest_path)
            .map_err(|e| format!("{}: {e}", manifest_path.display()))?,
    )
    .map_err(|e| format!("{}: {e}", manifest_path.display()))?;
    let meshes = manifest.as_array().ok_or("manifest.json is not a list")?;

    let mut header = String::from("| mesh | faces | Dijkstra mean / max |");
    let mut rule = String::from("|---|---:|---:|");
    for k in &args.ks {
        header += &format!(" graph k={k} mean / max |");
        rule += "---:|";
    }
    println!("{header}\n{rule}");
    for entry in meshes {
        let name = entry["name"].as_str().unwrap_or("?");
        let faces = entry["faces"].as_u64().unwrap_or(0);
        let references: Vec<&str> = entry["references"]
            .as_array()
            .map(|r| r.iter().filter_map(|x| x.as_str()).collect())
            .unwrap_or_default();
        if faces > args.max_faces || references.is_empty() {
            eprintln!("skipping {name} ({faces} faces)");
            continue;
        }
        let file = entry["file"]
            .as_str()
            .ok_or("manifest entry without file")?;
        let mesh = read_mesh(args.data.join(file)).map_err(|e| e.to_string())?;
        let mut methods = vec![Options::DEFAULT.with_method(Method::Dijkstra)];
        methods.extend(
            args.ks
                .iter()
                .map(|&k| Options::DEFAULT.with_k(k).with_method(Method::Graph)),
        );
        let mut row = format!("| {name} | {faces} |");
        for options in &methods {
            let (mut mean, mut max) = (0.0, 0.0f64);
            for reference in &references {
                let exact = read_reference(&args.data.join(reference))?;
                let field = distance_field(&mesh, &Euclidean, &[source_of(reference)?], options)
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
