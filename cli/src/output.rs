//! A command's outputs, all or nothing.
//!
//! Every output is checked before the work starts ([`Outputs::declare`]): not one of
//! the command's inputs, not twice the same file, in a directory that exists, and not a
//! file the user could not write (a read-only file is refused, not replaced). After the
//! work, each output is written to a temporary file beside its target
//! ([`Outputs::write`]); only when all are written does [`Outputs::commit`] rename them
//! over their targets. Any failure before that leaves every target as it was, and the
//! temporary files are removed, also when the process is interrupted (SIGINT, SIGTERM,
//! SIGHUP: [`remove_on_signal`]). Errors name the target, never the temporary file.
//!
//! `-` as a target is standard output: its content is kept in memory and written at the
//! commit, before the renames, so a reader that fails (a closed pipe) also keeps the
//! files from being replaced.

use crate::CliResult;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use tempfile::TempPath;

/// Temporary files that exist now, for the signal handler to remove.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    // A panic while holding the lock leaves the list as it was: still usable.
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes the temporary files of uncommitted outputs when the process is interrupted
/// or terminated, then exits with status 130 (128 + SIGINT).
///
/// `ctrlc` (with its `termination` feature) rather than `signal-hook`: it covers SIGINT,
/// SIGTERM and SIGHUP on Unix and Ctrl-C and console close on Windows with one call,
/// and runs the handler on its own thread, where taking a lock and removing files is
/// safe. It cannot say which signal came, so every one exits with 130.
pub fn remove_on_signal() {
    // Failing to install the handler (another one is installed) only loses the cleanup.
    let _ = ctrlc::set_handler(|| {
        // Holding the lock waits for a commit in progress to finish: its outputs are
        // then all in place, and nothing is left to remove.
        let mut files = pending();
        for file in files.drain(..) {
            let _ = std::fs::remove_file(file);
        }
        eprintln!("interrupted: no output written");
        std::process::exit(130);
    });
}

/// Where an output goes.
#[derive(Clone, Debug, PartialEq)]
enum Target {
    File(PathBuf),
    Stdout,
}

/// One output: its target and, once written, its content.
struct Entry {
    target: Target,
    /// The file's temporary twin, or standard output's bytes.
    written: Option<Written>,
}

enum Written {
    File(TempPath),
    Stdout(Vec<u8>),
}

/// The outputs of one command.
pub struct Outputs {
    inputs: Vec<PathBuf>,
    entries: Vec<Entry>,
}

impl Outputs {
    /// Outputs of a command that reads `inputs` (which no output may overwrite).
    pub fn new<'a>(inputs: impl IntoIterator<Item = &'a Path>) -> Outputs {
        Outputs {
            inputs: inputs.into_iter().map(Path::to_path_buf).collect(),
            entries: Vec::new(),
        }
    }

    /// Checks `path` as an output (`-` is standard output) before any work is done.
    pub fn declare(&mut self, path: &Path) -> CliResult {
        let target = if path.as_os_str() == "-" {
            Target::Stdout
        } else {
            Target::File(path.to_path_buf())
        };
        if self.entries.iter().any(|e| e.target == target) {
            return Err(match target {
                Target::Stdout => "standard output (-) is given for two outputs".into(),
                Target::File(_) => format!("{}: given for two outputs", path.display()).into(),
            });
        }
        if let Target::File(file) = &target {
            check_file(file, &self.inputs)?;
        }
        self.entries.push(Entry {
            target,
            written: None,
        });
        Ok(())
    }

    /// As [`Outputs::declare`], for an optional output.
    pub fn declare_some(&mut self, path: Option<&PathBuf>) -> CliResult {
        path.map_or(Ok(()), |p| self.declare(p))
    }

    /// Writes the content of declared output `path` with `write`: into a temporary file
    /// beside it, or into memory for standard output.
    ///
    /// # Panics
    /// If `path` was not declared.
    pub fn write(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> CliResult {
        let entry = self
            .entries
            .iter_mut()
            .find(|e| match &e.target {
                Target::Stdout => path.as_os_str() == "-",
                Target::File(f) => f == path,
            })
            .expect("outputs are declared before they are written");
        let fail = |e: std::io::Error| format!("{}: {e}", path.display());
        match &entry.target {
            Target::Stdout => {
                let mut bytes = Vec::new();
                write(&mut bytes).map_err(fail)?;
                entry.written = Some(Written::Stdout(bytes));
            }
            Target::File(file) => {
                let temp = temp_file_beside(file).map_err(fail)?;
                let written = (|| {
                    let file = std::fs::OpenOptions::new().write(true).open(&temp)?;
                    let mut out = std::io::BufWriter::new(file);
                    write(&mut out)?;
                    out.flush()
                })();
                match written {
                    Ok(()) => entry.written = Some(Written::File(temp)),
                    Err(e) => {
                        discard(temp);
                        return Err(fail(e).into());
                    }
                }
            }
        }
        Ok(())
    }

    /// Puts every output in place: standard output first, then one rename per file. A
    /// file that already existed keeps its permissions. If a rename fails, the files
    /// renamed before it are put back as they were.
    ///
    /// # Panics
    /// If a declared output was not written.
    pub fn commit(mut self) -> CliResult {
        let entries = std::mem::take(&mut self.entries);
        let mut stdout_bytes = None;
        let mut renames = Vec::new();
        for entry in entries {
            match (entry.target, entry.written) {
                (_, Some(Written::Stdout(bytes))) => stdout_bytes = Some(bytes),
                (Target::File(target), Some(Written::File(temp))) => renames.push((temp, target)),
                _ => panic!("every declared output is written before the commit"),
            }
        }
        let names: Vec<PathBuf> = renames.iter().map(|(t, _)| t.to_path_buf()).collect();
        // Standard output first, without the lock: a reader that does not read blocks
        // the write, and a signal must still find the temporary files and exit.
        let written = match stdout_bytes {
            Some(bytes) => {
                let mut out = std::io::stdout().lock();
                out.write_all(&bytes)
                    .and_then(|()| out.flush())
                    .map_err(|e| format!("standard output: {e}").into())
            }
            None => Ok(()),
        };
        // Held until every file is in place: a signal handler waits for it.
        let mut files = pending();
        let result = written.and_then(|()| rename_all(renames));
        files.retain(|f| !names.contains(f));
        result
    }
}

/// The renames of [`Outputs::commit`]; if one fails, the files renamed before it are
/// put back. The temporary files not renamed are removed on return.
fn rename_all(renames: Vec<(TempPath, PathBuf)>) -> CliResult {
    // What each target was, to put it back if a later rename fails.
    let mut done: Vec<(PathBuf, Option<TempPath>)> = Vec::new();
    for (temp, target) in renames {
        let backup = match std::fs::metadata(&target) {
            Ok(meta) => {
                // The new file takes the old one's permissions.
                let _ = std::fs::set_permissions(&temp, meta.permissions());
                backup_of(&target)
            }
            Err(_) => None,
        };
        if let Err(e) = temp.persist(&target) {
            for (earlier, backup) in done.into_iter().rev() {
                match backup {
                    Some(b) => {
                        let _ = b.persist(&earlier);
                    }
                    None => {
                        let _ = std::fs::remove_file(&earlier);
                    }
                }
            }
            return Err(format!("{}: {}", target.display(), e.error).into());
        }
        done.push((target, backup));
    }
    // The backups are removed with `done`.
    Ok(())
}

impl Drop for Outputs {
    fn drop(&mut self) {
        // Uncommitted outputs: their temporary files go.
        for entry in std::mem::take(&mut self.entries) {
            if let Some(Written::File(temp)) = entry.written {
                discard(temp);
            }
        }
    }
}

/// Removes a temporary file and forgets it.
fn discard(temp: TempPath) {
    let name = temp.to_path_buf();
    let mut files = pending();
    let _ = temp.close();
    files.retain(|f| f != &name);
}

/// Checks that `file` can be an output: not an input, not a directory, not read-only,
/// in a directory that exists.
fn check_file(file: &Path, inputs: &[PathBuf]) -> CliResult {
    let shown = file.display();
    let dir = match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(format!("{shown}: the directory {} does not exist", dir.display()).into());
    }
    let Ok(meta) = std::fs::metadata(file) else {
        return Ok(()); // a new file
    };
    if !meta.is_file() {
        return Err(format!("{shown}: exists and is not a file; not replaced").into());
    }
    // The same file, whatever the path's spelling (relative, symbolic links).
    let canonical = std::fs::canonicalize(file).ok();
    for input in inputs {
        let same = match (&canonical, std::fs::canonicalize(input)) {
            (Some(a), Ok(b)) => *a == b,
            _ => false,
        };
        if same {
            return Err(format!(
                "{shown}: is also an input of this command; write the output to another file"
            )
            .into());
        }
    }
    let writable = !meta.permissions().readonly()
        && std::fs::OpenOptions::new().write(true).open(file).is_ok();
    if !writable {
        return Err(format!(
            "{shown}: the file is read-only; not replaced (make it writable or choose another output)"
        )
        .into());
    }
    Ok(())
}

/// A new, empty temporary file in `target`'s directory, registered for removal on a
/// signal. Its error names no temporary path.
fn temp_file_beside(target: &Path) -> std::io::Result<TempPath> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut files = pending();
    let mut builder = tempfile::Builder::new();
    builder.prefix(".geotracks-").suffix(".tmp");
    // Created 0600 by default; 0666 lets the umask decide, as for any new file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let temp = builder
        .tempfile_in(dir)
        .map_err(without_temp_path)?
        .into_temp_path();
    files.push(temp.to_path_buf());
    Ok(temp)
}

/// A hard link to `target` under a temporary name, to restore it from; `None` where
/// links are not supported (the restore then cannot happen, which only matters if a
/// rename fails half-way through a commit).
fn backup_of(target: &Path) -> Option<TempPath> {
    let dir = target.parent().filter(|d| !d.as_os_str().is_empty())?;
    let name = tempfile::Builder::new()
        .prefix(".geotracks-")
        .suffix(".bak")
        .make_in(dir, |path| std::fs::hard_link(target, path))
        .ok()?;
    Some(name.into_temp_path())
}

/// The operating system's error of creating a temporary file, without tempfile's
/// "at path …" (the temporary name, which the user never asked for).
fn without_temp_path(e: std::io::Error) -> std::io::Error {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn temps(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".geotracks-"))
            .collect()
    }

    #[test]
    fn a_failing_write_replaces_nothing_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        std::fs::write(&a, "old a\n").unwrap();
        let mut outputs = Outputs::new([]);
        outputs.declare(&a).unwrap();
        outputs.declare(&b).unwrap();
        outputs.write(&a, |w| w.write_all(b"new a\n")).unwrap();
        let err = outputs
            .write(&b, |_| Err(std::io::Error::other("disk full")))
            .unwrap_err();
        assert_eq!(err.to_string(), format!("{}: disk full", b.display()));
        drop(outputs);
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a\n");
        assert!(!b.exists());
        assert!(temps(dir.path()).is_empty(), "{:?}", temps(dir.path()));
        assert!(!pending().iter().any(|f| f.starts_with(dir.path())));
    }

    #[test]
    fn a_commit_puts_every_output_in_place_with_the_old_permissions() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        std::fs::write(&a, "old a\n").unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&a, std::fs::Permissions::from_mode(0o640)).unwrap();
        }
        let mut outputs = Outputs::new([]);
        outputs.declare(&a).unwrap();
        outputs.declare(&b).unwrap();
        outputs.write(&a, |w| w.write_all(b"new a\n")).unwrap();
        outputs.write(&b, |w| w.write_all(b"new b\n")).unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a\n");
        outputs.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a\n");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b\n");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&a).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o640);
        }
        assert!(temps(dir.path()).is_empty(), "{:?}", temps(dir.path()));
    }

    #[test]
    fn a_failing_rename_puts_back_the_files_renamed_before_it() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        std::fs::write(&a, "old a\n").unwrap();
        let mut outputs = Outputs::new([]);
        outputs.declare(&a).unwrap();
        outputs.declare(&b).unwrap();
        outputs.write(&a, |w| w.write_all(b"new a\n")).unwrap();
        outputs.write(&b, |w| w.write_all(b"new b\n")).unwrap();
        // Between the checks and the commit, b became a non-empty directory: its
        // rename fails.
        std::fs::create_dir(&b).unwrap();
        std::fs::write(b.join("x"), "x").unwrap();
        let err = outputs.commit().unwrap_err().to_string();
        assert!(err.starts_with(&b.display().to_string()), "{err}");
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a\n");
        assert!(temps(dir.path()).is_empty(), "{:?}", temps(dir.path()));
    }

    #[test]
    fn outputs_that_are_inputs_read_only_or_twice_the_same_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("in.txt");
        std::fs::write(&input, "1\n").unwrap();
        let mut outputs = Outputs::new([input.as_path()]);
        // The same file by another spelling.
        let spelled = dir.path().join(".").join("in.txt");
        let err = outputs.declare(&spelled).unwrap_err().to_string();
        assert!(err.contains("is also an input"), "{err}");
        let ro = dir.path().join("ro.txt");
        std::fs::write(&ro, "keep\n").unwrap();
        let mut perms = std::fs::metadata(&ro).unwrap().permissions();
        perms.set_readonly(true);
        std::fs::set_permissions(&ro, perms).unwrap();
        let err = outputs.declare(&ro).unwrap_err().to_string();
        assert!(err.contains("read-only"), "{err}");
        let out = dir.path().join("out.txt");
        outputs.declare(&out).unwrap();
        let err = outputs.declare(&out).unwrap_err().to_string();
        assert!(err.contains("two outputs"), "{err}");
        let err = outputs
            .declare(&dir.path().join("no/such/dir/out.txt"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("does not exist"), "{err}");
        assert!(!err.contains(".geotracks-"), "{err}");
    }
}
