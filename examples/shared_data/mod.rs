//! Reading the shared data directory (`manifest.json`, exact references) and comparing
//! against it, and measuring a configuration in a child process; used by the `eval`
//! and `bench` examples and by the tests.
#![allow(dead_code)] // each user takes what it needs

use std::path::Path;
use std::process::{Command, Stdio};

/// One mesh of `data/manifest.json`.
pub struct MeshEntry {
    pub name: String,
    /// The mesh file, relative to the data directory.
    pub file: String,
    pub faces: u64,
    /// Exact references (relative paths named `…/<mesh>.src<v>.f64`); may be empty.
    pub references: Vec<String>,
}

/// The entries of `data/manifest.json`: objects with `name`, `file`, `faces` and
/// `references`; an entry without a name or a file is an error.
pub fn manifest(data: &Path) -> Result<Vec<MeshEntry>, String> {
    let path = data.join("manifest.json");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let value: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let serde_json::Value::Array(entries) = value else {
        return Err(format!("{}: not a list", path.display()));
    };
    entries
        .iter()
        .map(|m| {
            let text = |key: &str| {
                m[key]
                    .as_str()
                    .map(str::to_string)
                    .ok_or_else(|| format!("{}: an entry without '{key}'", path.display()))
            };
            Ok(MeshEntry {
                name: text("name")?,
                file: text("file")?,
                faces: m["faces"].as_u64().unwrap_or(0),
                references: m["references"]
                    .as_array()
                    .map(|r| {
                        r.iter()
                            .filter_map(|x| x.as_str().map(str::to_string))
                            .collect()
                    })
                    .unwrap_or_default(),
            })
        })
        .collect()
}

/// An exact reference: one little-endian f64 per vertex.
pub fn read_reference(path: &Path) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// The source vertex of a reference named `…/<mesh>.src<v>.f64`.
pub fn source_of(reference: &str) -> Result<u32, String> {
    reference
        .rsplit_once(".src")
        .and_then(|(_, s)| s.strip_suffix(".f64"))
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("cannot read the source vertex from '{reference}'"))
}

/// Mean and max of |d − d*| / d* over the vertices where d* > 0.
pub fn relative_error(d: &[f64], exact: &[f64]) -> (f64, f64) {
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

/// Runs `exe --one ARGS...` (the example itself, measuring one configuration, so that
/// its peak memory is its own) and returns what follows `tag` on the line of its
/// output that starts with it.
pub fn run_child(exe: &Path, args: &[String], tag: &str) -> Result<String, String> {
    let out = Command::new(exe)
        .arg("--one")
        .args(args)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot start {}: {e}", exe.display()))?;
    if !out.status.success() {
        return Err(format!("child exited with {}", out.status));
    }
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .find_map(|l| l.strip_prefix(tag))
        .map(str::to_string)
        .ok_or_else(|| "the child printed no result line".into())
}

/// This process's peak resident set (`VmHWM`), in kB.
pub fn peak_rss_kb() -> Result<f64, String> {
    let status = std::fs::read_to_string("/proc/self/status")
        .map_err(|e| format!("/proc/self/status: {e}"))?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .ok_or_else(|| "no VmHWM in /proc/self/status".into())
}
