//! Running the `geotracks` binary from the CLI's integration tests (`cli.rs`,
//! `terrain.rs`).
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// Runs `geotracks` with `args`.
pub fn geotracks(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_geotracks"))
        .args(args)
        .output()
        .expect("run geotracks")
}

/// Runs a command that must succeed; returns its output.
pub fn geotracks_ok(args: &[&str]) -> Output {
    let out = geotracks(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    out
}

/// Runs a command that must fail: exit code non-zero, one line on stderr that contains
/// `expected`, no panic or backtrace, and no output file.
pub fn assert_fails(args: &[&str], output: &Path, expected: &str) {
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

/// The last line of a command's standard output, as a number.
pub fn last_value(out: &Output) -> f64 {
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().last().unwrap_or("");
    last.parse()
        .unwrap_or_else(|_| panic!("last line {last:?} is not a number: {stdout}"))
}
