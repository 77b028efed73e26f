//! Headers that lie: every mesh reader that sizes something from a count in a header
//! (PLY element counts, OFF and `.ma` counts) refuses a count the file cannot hold with an error naming where it was
//! declared, and allocates nothing for it.
//!
//! The fixtures are in `tests/data/io/lying_*`. Each is read twice: here, for the error
//! and its message, and in a child process under `ulimit -v` (2 GiB of address space),
//! where a reader that reserved room for the claim (gigabytes) would abort with
//! "memory allocation failed" instead of returning the error.

use geotracks::mesh::io::{read_medial_axis, read_mesh};
use geotracks::mesh::MeshError;
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

const LYING: [&str; 3] = ["lying_header.ply", "lying_header.off", "lying_header.ma"];

/// Reads a fixture with the reader its extension calls for; the error as text.
fn read_error(path: &Path) -> String {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    match ext {
        "ma" => read_medial_axis(path).err().map(|e| e.to_string()),
        _ => read_mesh(path).err().map(|e| e.to_string()),
    }
    .unwrap_or_else(|| panic!("{} was read, but its header lies", path.display()))
}

#[test]
fn binary_ply_element_count_beyond_the_file_is_refused() {
    let err = read_mesh(fixture("lying_header.ply")).unwrap_err();
    match &err {
        MeshError::ImplausibleCount {
            line,
            declared,
            at_most,
            ..
        } => {
            assert_eq!((*line, *declared), (3, 1_800_000_000));
            assert_eq!(*at_most, 4); // 49 bytes after the header, 12 per vertex
        }
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("lying_header.ply:3:"), "{err}");
}

#[test]
fn off_and_ma_counts_name_their_header_line() {
    let err = read_error(&fixture("lying_header.off"));
    assert!(
        err.contains("of the 1800000000 that line 2 declares"),
        "{err}"
    );
    let err = read_error(&fixture("lying_header.ma"));
    assert!(err.contains("lying_header.ma:1:"), "{err}");
    assert!(err.contains("declares 1800000000 vertices"), "{err}");
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

/// Huge files, sparse on disk (`File::set_len` costs no space), each read in a child
/// process under an address-space limit:
/// - under 1 GiB, a binary STL whose header claims 12 million triangles, its size
///   matching (600 MB): the file fits, and the process aborted on the per-face tables
///   ("memory allocation of … bytes failed"; 43 million under 4 GiB did the same); it
///   now gets an out-of-memory error;
/// - under 1 GiB, a binary PLY declaring 30 million vertices over 720 MB: the same, on
///   the vertices;
/// - under 2 GiB, 2 GB of NUL bytes named `.obj`, `.ply`, `.off`, `.ma`: read
///   whole before their first byte was looked at (the read failed under the limit),
///   now refused from their start as not the format; named `.stl`, the header's
///   triangle count (0) says that nothing after it is needed.
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
    let triangles: u64 = 12_000_000;
    let mut stl_header = vec![0u8; 80];
    stl_header.extend((triangles as u32).to_le_bytes());
    let ply_header = b"ply\nformat binary_little_endian 1.0\nelement vertex 30000000\n\
property float x\nproperty float y\nproperty float z\nelement face 0\n\
property list uchar int vertex_indices\nend_header\n";
    let two_gb = 2_000_000_000;
    let (one_gib, two_gib) = ("1048576", "2097152");
    let cases = [
        (
            sparse("big.stl", &stl_header, 84 + 50 * triangles),
            one_gib,
            "not enough memory",
        ),
        (
            sparse("big.ply", ply_header, 720_000_000),
            one_gib,
            "not enough memory",
        ),
        (sparse("nul.obj", &[], two_gb), two_gib, "not an OBJ file"),
        (sparse("nul.ply", &[], two_gb), two_gib, "not a PLY file"),
        (sparse("nul.off", &[], two_gb), two_gib, "not an OFF file"),
        (sparse("nul.ma", &[], two_gb), two_gib, "not a medial axis"),
        (sparse("nul.stl", &[], two_gb), two_gib, "no usable face"),
    ];
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
