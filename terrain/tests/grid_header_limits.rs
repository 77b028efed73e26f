//! Headers that lie: every grid reader that sizes something from a count in a header
//! (ESRI ASCII `ncols`/`nrows`, GeoTIFF image size and tag counts) refuses a count the file cannot hold with an error naming where it was
//! declared, and allocates nothing for it.
//!
//! The fixtures are in `tests/data/lying_*`. Each is read twice: here, for the error
//! and its message, and in a child process under `ulimit -v` (2 GiB of address space),
//! where a reader that reserved room for the claim (gigabytes) would abort with
//! "memory allocation failed" instead of returning the error.

use geotracks_terrain::{read_grid, TerrainError};
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

const LYING: [&str; 3] = ["lying_header.asc", "lying_size.tif", "lying_tag.tif"];

/// Reads a grid fixture; the error as text.
fn read_error(path: &Path) -> String {
    read_grid(path)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_else(|| panic!("{} was read, but its header lies", path.display()))
}

#[test]
fn esri_ascii_names_the_header_lines() {
    let path = fixture("lying_header.asc");
    let err = read_grid(&path).unwrap_err();
    assert!(
        matches!(
            err,
            TerrainError::ValueCount {
                expected: 1_800_000_000,
                found: 3,
                header_lines: [1, 2],
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("header's lines 1 and 2"), "{err}");
}

#[test]
fn geotiff_image_size_beyond_the_file_is_refused() {
    let err = read_grid(fixture("lying_size.tif")).unwrap_err();
    match &err {
        TerrainError::ImplausibleSize {
            declared, bytes, ..
        } => {
            assert_eq!(*declared, 32768 * 32768);
            assert_eq!(*bytes, 242);
        }
        other => panic!("{other:?}"),
    }
    let message = err.to_string();
    assert!(
        message.contains("ImageWidth 32768 × ImageLength 32768"),
        "{message}"
    );
}

#[test]
fn geotiff_tag_count_beyond_the_file_is_refused() {
    let err = read_grid(fixture("lying_tag.tif")).unwrap_err();
    assert!(
        matches!(
            &err,
            TerrainError::ImplausibleSize {
                declared: 4_000_000_000,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("tag 42113"), "{err}");
}

/// The child's side of [`lying_headers_allocate_nothing`]: reads the file named by
/// `GEOTRACKS_LYING_FILE` and prints the error.
#[test]
#[ignore = "run by lying_headers_allocate_nothing in a child process under a memory limit"]
fn read_one_lying_file() {
    let Some(path) = std::env::var_os("GEOTRACKS_LYING_FILE") else {
        return;
    };
    println!("clean error: {}", read_error(Path::new(&path)));
}

#[test]
fn lying_headers_allocate_nothing() {
    let exe = std::env::current_exe().expect("the test binary");
    for name in LYING {
        let output = Command::new("sh")
            .arg("-c")
            .arg(r#"ulimit -v 2097152 && exec "$0" "$@""#)
            .arg(&exe)
            .args([
                "read_one_lying_file",
                "--exact",
                "--ignored",
                "--nocapture",
                "--test-threads=1",
            ])
            .env("GEOTRACKS_LYING_FILE", fixture(name))
            .output()
            .expect("run the test binary under ulimit");
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            output.status.success() && stdout.contains("clean error:"),
            "{name} under a 2 GiB address-space limit: {}\n{stdout}\n{stderr}",
            output.status
        );
    }
}

/// A huge file, sparse on disk (`File::set_len` costs no space), read in a child
/// process under a 2 GiB address-space limit: 2 GB of NUL bytes named `.asc` was read
/// whole before its first byte was looked at (the read failed under the limit); it is
/// now refused from its start as not the format.
#[cfg(unix)]
#[test]
fn huge_files_are_refused_from_their_start_or_fail_with_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let sparse = |name: &str, start: &[u8], len: u64| {
        let path = dir.path().join(name);
        let mut file = std::fs::File::create(&path).unwrap();
        std::io::Write::write_all(&mut file, start).unwrap();
        file.set_len(len).unwrap();
        path
    };
    let two_gb = 2_000_000_000;
    let two_gib = "2097152";
    let cases = [(
        sparse("nul.asc", &[], two_gb),
        two_gib,
        "not an ESRI ASCII grid",
    )];
    let exe = std::env::current_exe().expect("the test binary");
    for (path, kib, expected) in cases {
        let output = Command::new("sh")
            .arg("-c")
            .arg(r#"ulimit -v "$GEOTRACKS_LIMIT_KIB" && exec "$0" "$@""#)
            .arg(&exe)
            .args([
                "read_one_lying_file",
                "--exact",
                "--ignored",
                "--nocapture",
                "--test-threads=1",
            ])
            .env("GEOTRACKS_LYING_FILE", &path)
            .env("GEOTRACKS_LIMIT_KIB", kib)
            .output()
            .expect("run the test binary under ulimit");
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            output.status.success() && stdout.contains("clean error:") && stdout.contains(expected),
            "{} under a {kib} KiB address-space limit (expected {expected:?}): {}\n{stdout}\n{stderr}",
            path.display(),
            output.status
        );
    }
}
