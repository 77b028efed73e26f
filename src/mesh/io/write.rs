//! Writers. Each writes a temporary file beside the target and renames it over the
//! target only once everything was written, so a failure leaves no partial file and an
//! existing file is replaced whole or not at all.
//!
//! Each has a twin ending in `_to` that writes into any [`Write`] (a file of the
//! caller's, standard output, memory), for callers that commit several files together.

use crate::mesh::{MeshError, TriMesh};
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes a file atomically: `write` fills a buffered temporary file in the target's
/// directory, which then replaces `path` in one rename. If `write` (or anything after it)
/// fails, the temporary file is removed and `path` is untouched.
///
/// The command-line tool writes its `.txt` and `.csv` outputs through this too.
///
/// # Errors
/// [`MeshError::Io`] naming `path` if the temporary file cannot be created (for example
/// the directory does not exist), if `write` returns an error, or if the rename fails.
///
/// # Example
/// ```
/// use std::io::Write;
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("hello.txt");
/// geotracks::mesh::io::write_atomically(&path, |w| writeln!(w, "hello"))?;
/// assert_eq!(std::fs::read_to_string(&path)?, "hello\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), MeshError> {
    let io = |source: std::io::Error| MeshError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".geotracks-").suffix(".tmp");
    // A NamedTempFile is created 0600; asking for 0666 lets the umask decide, so the
    // result gets the permissions any other newly created file would.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut temp = builder
        .tempfile_in(dir)
        .map_err(|e| io(without_temp_path(e)))?;
    {
        let mut out = BufWriter::new(temp.as_file_mut());
        write(&mut out).map_err(io)?;
        out.flush().map_err(io)?;
    }
    // No fsync: the guarantee is against failures of this process (no partial file),
    // not against power loss, and syncing large outputs would cost more than the write.
    temp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}

/// The error of creating a temporary file, without the temporary file's name (tempfile
/// appends "at path …/.geotracks-XXXX.tmp", a name the user never asked for): the
/// operating system's error alone, reported against the target.
pub(crate) fn without_temp_path(e: std::io::Error) -> std::io::Error {
    if e.raw_os_error().is_some() {
        return e;
    }
    let kind = e.kind();
    let inner = e.into_inner();
    let os = inner
        .as_deref()
        .and_then(std::error::Error::source)
        .and_then(|s| s.downcast_ref::<std::io::Error>())
        .and_then(std::io::Error::raw_os_error);
    match os {
        Some(code) => std::io::Error::from_raw_os_error(code),
        None => std::io::Error::from(kind),
    }
}

/// Writes `mesh` as binary little-endian PLY with a per-vertex `distance` (f64) and a
/// colour from the perceptual Viridis map over the finite distances (unreached vertices,
/// whose distance is infinite or NaN, are grey). Only kept faces are written; vertex ids
/// are the mesh's.
///
/// # Errors
/// [`MeshError::AttributeLength`] if `distance` does not have one value per vertex;
/// [`MeshError::Io`] if the file cannot be written, and nothing is left behind then.
pub fn write_ply_with_distance(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    distance: &[f64],
) -> Result<(), MeshError> {
    let n = mesh.vertex_count();
    if distance.len() != n {
        return Err(MeshError::AttributeLength {
            what: "distance",
            expected: n,
            found: distance.len(),
        });
    }
    write_atomically(path.as_ref(), |w| {
        write_ply_with_distance_to(w, mesh, distance)
    })
}

/// As [`write_ply_with_distance`], into `w`.
///
/// # Errors
/// What `w` returns; an error of kind [`std::io::ErrorKind::InvalidInput`] if
/// `distance` does not have one value per vertex or a vertex id does not fit a PLY
/// `int`.
pub fn write_ply_with_distance_to(
    w: &mut dyn Write,
    mesh: &TriMesh,
    distance: &[f64],
) -> std::io::Result<()> {
    let n = mesh.vertex_count();
    if distance.len() != n {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{} distances for {n} vertices", distance.len()),
        ));
    }
    let (lo, hi) = distance
        .iter()
        .filter(|d| d.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &d| {
            (lo.min(d), hi.max(d))
        });
    let colour = |d: f64| -> [u8; 3] {
        if !d.is_finite() {
            return [128; 3];
        }
        let t = if hi > lo { (d - lo) / (hi - lo) } else { 0.0 };
        let c = colorous::VIRIDIS.eval_continuous(t);
        [c.r, c.g, c.b]
    };
    // Written by hand rather than with ply-rs-bw's writer, which wants a map or a
    // property-getter object per element: the records here are fixed-size and the whole
    // format is a ten-line header plus `to_le_bytes`.
    {
        write!(
            w,
            "ply\nformat binary_little_endian 1.0\ncomment written by geotracks\n\
             element vertex {n}\nproperty double x\nproperty double y\nproperty double z\n\
             property double distance\nproperty uchar red\nproperty uchar green\n\
             property uchar blue\nelement face {}\nproperty list uchar int vertex_indices\n\
             end_header\n",
            mesh.triangles().len()
        )?;
        for (p, &d) in mesh.positions().iter().zip(distance) {
            for c in [p.x, p.y, p.z, d] {
                w.write_all(&c.to_le_bytes())?;
            }
            w.write_all(&colour(d))?;
        }
        for t in mesh.triangles() {
            w.write_all(&[3])?;
            for &v in t {
                // Vertex ids are u32 by construction but PLY's usual index type is int.
                let v = i32::try_from(v).map_err(|_| {
                    std::io::Error::new(
                        std::io::ErrorKind::InvalidInput,
                        format!("vertex id {v} does not fit a PLY int"),
                    )
                })?;
                w.write_all(&v.to_le_bytes())?;
            }
        }
        Ok(())
    }
}

/// Writes polylines (geodesic paths, isolines) as OBJ: all points as `v` lines, then one
/// `l` line per polyline with 1-based indices. A polyline of a single point is written as
/// a `p` point element and an empty one is skipped, so every element is valid OBJ.
/// Coordinates are written in full precision (shortest round-trip form).
///
/// # Errors
/// [`MeshError::NonFiniteVertex`] (numbering the points across all polylines) if a point
/// has a NaN or infinite coordinate, which OBJ cannot hold; [`MeshError::Io`] if the file
/// cannot be written, and nothing is left behind then.
pub fn write_obj_polylines(
    path: impl AsRef<Path>,
    polylines: &[Vec<[f64; 3]>],
) -> Result<(), MeshError> {
    let points: Vec<[f64; 3]> = polylines.iter().flatten().copied().collect();
    let mut next = 0u32;
    let lines: Vec<Vec<u32>> = polylines
        .iter()
        .map(|line| {
            let ids = (next..next + line.len() as u32).collect();
            next += line.len() as u32;
            ids
        })
        .collect();
    write_obj_lines(path, &points, &lines)
}

/// Writes a graph of polylines over shared points as OBJ: every point once as a `v`
/// line, then each polyline (indices into `points`) as an `l` line (a `p` line for a
/// single point), so polylines that meet share their vertex.
///
/// # Errors
/// [`MeshError::NonFiniteVertex`] for a point with a NaN or infinite coordinate;
/// [`MeshError::IndexOutOfRange`] (face = polyline) for an index past `points`;
/// [`MeshError::Io`] if the file cannot be written, and nothing is left behind then.
pub fn write_obj_lines(
    path: impl AsRef<Path>,
    points: &[[f64; 3]],
    lines: &[Vec<u32>],
) -> Result<(), MeshError> {
    if let Some((vertex, &position)) = points
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
    {
        return Err(MeshError::NonFiniteVertex { vertex, position });
    }
    for (face, line) in lines.iter().enumerate() {
        if let Some(&vertex) = line.iter().find(|&&i| i as usize >= points.len()) {
            return Err(MeshError::IndexOutOfRange {
                face,
                vertex: vertex.into(),
                vertex_count: points.len(),
            });
        }
    }
    write_atomically(path.as_ref(), |w| write_obj_lines_to(w, points, lines))
}

/// As [`write_obj_lines`], into `w`.
///
/// # Errors
/// What `w` returns; an error of kind [`std::io::ErrorKind::InvalidInput`] for a point
/// with a NaN or infinite coordinate or an index past `points`.
pub fn write_obj_lines_to(
    w: &mut dyn Write,
    points: &[[f64; 3]],
    lines: &[Vec<u32>],
) -> std::io::Result<()> {
    let invalid = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, m);
    if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(invalid(format!("point {i} is not finite: {:?}", points[i])));
    }
    if let Some(i) = lines
        .iter()
        .flatten()
        .find(|&&i| i as usize >= points.len())
    {
        return Err(invalid(format!("index {i} past {} points", points.len())));
    }
    {
        writeln!(w, "# {} polylines written by geotracks", lines.len())?;
        for [x, y, z] in points {
            writeln!(w, "v {x} {y} {z}")?;
        }
        for line in lines {
            match line.as_slice() {
                [] => {}
                [i] => writeln!(w, "p {}", i + 1)?,
                ids => {
                    w.write_all(b"l")?;
                    for i in ids {
                        write!(w, " {}", i + 1)?;
                    }
                    w.write_all(b"\n")?;
                }
            }
        }
        Ok(())
    }
}
