//! A command's outputs, all or nothing.
//!
//! Every output is checked before the work starts ([`Outputs::declare`]): not one of
//! the command's inputs and not twice the same file, whatever the paths' spelling (`./`,
//! `..`, symbolic links, hard links: paths are compared by where they lead and existing
//! files by identity), in a directory that exists, and not a file the user could not
//! write (a read-only file is refused, not replaced). An output that is a symbolic link
//! is written through it: the file it points to is replaced and the link stays a link.
//!
//! After the work, each output is written to a temporary file beside its target
//! ([`Outputs::write`]); only when all are written does [`Outputs::commit`] rename them
//! over their targets, one rename after the other with everything else prepared first,
//! so that the window in which some targets are new and others old is as short as the
//! file system allows. Any failure before that leaves every target as it was, and the
//! temporary files are removed, also when the process is interrupted (SIGINT, SIGTERM,
//! SIGHUP: [`remove_on_signal`]); an interruption after the renames says which files
//! were replaced. Errors name the target, never the temporary file.
//!
//! A process killed outright (SIGKILL, a power cut) cannot remove its temporary files
//! (`.geotracks-XXXXXX.tmp`, and `.geotracks-XXXXXX.bak` during a commit). Each
//! temporary file is locked while its process lives; the next run that writes into
//! the same directory removes those of our naming that no process holds and that are
//! more than a minute old ([`remove_stale_temporaries`]).
//!
//! `-` as a target is standard output: its content is kept in memory and written at the
//! commit, before the renames, so a reader that fails (a closed pipe) also keeps the
//! files from being replaced.

use crate::CliResult;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, SystemTime};
use tempfile::TempPath;

/// What the signal handler needs to know: the temporary files to remove, and what a
/// commit has put in place.
struct Progress {
    /// Temporary files that exist now.
    temporary: Vec<PathBuf>,
    /// Standard output has been (or is being) written.
    stdout: bool,
    /// The files a commit has put in place, as the user named them.
    replaced: Vec<String>,
}

static PROGRESS: Mutex<Progress> = Mutex::new(Progress {
    temporary: Vec::new(),
    stdout: false,
    replaced: Vec::new(),
});

fn progress() -> MutexGuard<'static, Progress> {
    // A panic while holding the lock leaves the lists as they were: still usable.
    PROGRESS.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes the temporary files of uncommitted outputs when the process is interrupted
/// or terminated, says which outputs (if any) were already written, then exits with
/// status 130 (128 + SIGINT).
///
/// `ctrlc` (with its `termination` feature) rather than `signal-hook`: it covers SIGINT,
/// SIGTERM and SIGHUP on Unix and Ctrl-C and console close on Windows with one call,
/// and runs the handler on its own thread, where taking a lock and removing files is
/// safe. It cannot say which signal came, so every one exits with 130.
pub fn remove_on_signal() {
    // Failing to install the handler (another one is installed) only loses the cleanup.
    let _ = ctrlc::set_handler(|| {
        // Holding the lock waits for a commit in progress to finish its renames: the
        // outputs are then all in place (or all as they were), never half.
        let mut progress = progress();
        for file in progress.temporary.drain(..) {
            let _ = std::fs::remove_file(file);
        }
        eprintln!("{}", interrupted(&progress));
        std::process::exit(130);
    });
}

/// The message of an interrupted run: what it wrote.
fn interrupted(progress: &Progress) -> String {
    match (progress.replaced.as_slice(), progress.stdout) {
        ([], false) => "interrupted: no output written".into(),
        ([], true) => "interrupted: no file written; standard output may be incomplete".into(),
        (files, stdout) => format!(
            "interrupted after the outputs were complete: wrote {}{}",
            if stdout { "standard output, " } else { "" },
            files.join(", ")
        ),
    }
}

/// Where an output goes.
#[derive(Clone, Debug)]
enum Target {
    /// A file: `given` as the user wrote it (for messages, and to find it again), `real`
    /// where it leads (its directory canonical, a symbolic link followed): the temporary
    /// file is made beside `real` and renamed to it.
    File {
        given: PathBuf,
        real: PathBuf,
    },
    Stdout,
}

/// One output: its target and, once written, its content.
struct Entry {
    target: Target,
    /// The existing file's identity, to recognise it under another name.
    identity: Option<Identity>,
    /// The file's temporary twin, or standard output's bytes.
    written: Option<Written>,
}

enum Written {
    /// The temporary file, and its handle, which holds its lock.
    File(TempPath, std::fs::File),
    Stdout(Vec<u8>),
}

/// The outputs of one command.
pub struct Outputs {
    /// The inputs, where they lead, and their identity.
    inputs: Vec<(PathBuf, Option<Identity>)>,
    entries: Vec<Entry>,
    /// Directories already cleaned of stale temporary files.
    cleaned: Vec<PathBuf>,
}

impl Outputs {
    /// Outputs of a command that reads `inputs` (which no output may overwrite).
    pub fn new<'a>(inputs: impl IntoIterator<Item = &'a Path>) -> Outputs {
        Outputs {
            inputs: inputs
                .into_iter()
                .filter_map(|p| {
                    let real = std::fs::canonicalize(p).ok()?;
                    Some((real, Identity::of(p)))
                })
                .collect(),
            entries: Vec::new(),
            cleaned: Vec::new(),
        }
    }

    /// Checks `path` as an output (`-` is standard output) before any work is done.
    pub fn declare(&mut self, path: &Path) -> CliResult {
        if path.as_os_str() == "-" {
            if self
                .entries
                .iter()
                .any(|e| matches!(e.target, Target::Stdout))
            {
                return Err("standard output (-) is given for two outputs".into());
            }
            self.entries.push(Entry {
                target: Target::Stdout,
                identity: None,
                written: None,
            });
            return Ok(());
        }
        let real = check_file(path)?;
        let identity = Identity::of(&real);
        let same = |other: &Path, other_identity: &Option<Identity>| {
            other == real || (identity.is_some() && *other_identity == identity)
        };
        if self.inputs.iter().any(|(input, id)| same(input, id)) {
            return Err(format!(
                "{}: is also an input of this command; write the output to another file",
                path.display()
            )
            .into());
        }
        for entry in &self.entries {
            if let Target::File { given, real } = &entry.target {
                if same(real, &entry.identity) {
                    return Err(if given.as_os_str() == path.as_os_str() {
                        format!("{}: given for two outputs", path.display())
                    } else {
                        format!(
                            "{}: the same file as {}, given for two outputs",
                            path.display(),
                            given.display()
                        )
                    }
                    .into());
                }
            }
        }
        if let Some(dir) = real.parent() {
            if !self.cleaned.iter().any(|d| d == dir) {
                remove_stale_temporaries(dir, STALE_AFTER);
                self.cleaned.push(dir.to_path_buf());
            }
        }
        self.entries.push(Entry {
            target: Target::File {
                given: path.to_path_buf(),
                real,
            },
            identity,
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
                Target::File { given, .. } => given == path,
            })
            .expect("outputs are declared before they are written");
        let fail = |e: std::io::Error| format!("{}: {e}", path.display());
        match &entry.target {
            Target::Stdout => {
                let mut bytes = Vec::new();
                write(&mut bytes).map_err(fail)?;
                entry.written = Some(Written::Stdout(bytes));
            }
            Target::File { real, .. } => {
                let (file, temp) = temp_file_beside(real).map_err(fail)?;
                let written = (|| {
                    let mut out = std::io::BufWriter::new(&file);
                    write(&mut out)?;
                    out.flush()
                })();
                match written {
                    Ok(()) => entry.written = Some(Written::File(temp, file)),
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
                (Target::File { given, real }, Some(Written::File(temp, file))) => {
                    renames.push(Rename {
                        temp,
                        lock: file,
                        given,
                        real,
                    })
                }
                _ => panic!("every declared output is written before the commit"),
            }
        }
        let names: Vec<PathBuf> = renames.iter().map(|r| r.temp.to_path_buf()).collect();
        // Standard output first, without the lock: a reader that does not read blocks
        // the write, and a signal must still find the temporary files and exit.
        let written = match stdout_bytes {
            Some(bytes) => {
                progress().stdout = true;
                let mut out = std::io::stdout().lock();
                out.write_all(&bytes)
                    .and_then(|()| out.flush())
                    .map_err(|e| format!("standard output: {e}").into())
            }
            None => Ok(()),
        };
        // Held until every file is in place: a signal handler waits for it.
        let mut progress = progress();
        let result = written.and_then(|()| rename_all(renames));
        progress.temporary.retain(|f| !names.contains(f));
        if let Ok(replaced) = &result {
            progress.replaced.extend(replaced.iter().cloned());
        }
        result.map(|_| ())
    }
}

/// One file of a commit: its temporary file (and the handle that locks it), the target
/// as the user named it and where it leads.
struct Rename {
    temp: TempPath,
    lock: std::fs::File,
    given: PathBuf,
    real: PathBuf,
}

/// The renames of [`Outputs::commit`]: first everything that can be done before a
/// target changes (permissions, backups), then the renames back to back; if one fails,
/// the files renamed before it are put back. Returns the targets replaced, as named.
/// The temporary files not renamed are removed on return.
fn rename_all(renames: Vec<Rename>) -> CliResult<Vec<String>> {
    // What each target was, to put it back if a later rename fails.
    let prepared: Vec<(Rename, Option<TempPath>)> = renames
        .into_iter()
        .map(|rename| {
            let backup = match std::fs::metadata(&rename.real) {
                Ok(meta) => {
                    // The new file takes the old one's permissions.
                    let _ = std::fs::set_permissions(&rename.temp, meta.permissions());
                    backup_of(&rename.real)
                }
                Err(_) => None,
            };
            (rename, backup)
        })
        .collect();
    let mut done: Vec<(PathBuf, Option<TempPath>)> = Vec::new();
    let mut replaced = Vec::new();
    for (rename, backup) in prepared {
        let Rename {
            temp,
            lock,
            given,
            real,
        } = rename;
        if let Err(e) = temp.persist(&real) {
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
            return Err(format!("{}: {}", given.display(), e.error).into());
        }
        drop(lock);
        done.push((real, backup));
        replaced.push(given.display().to_string());
    }
    // The backups are removed with `done`.
    Ok(replaced)
}

impl Drop for Outputs {
    fn drop(&mut self) {
        // Uncommitted outputs: their temporary files go.
        for entry in std::mem::take(&mut self.entries) {
            if let Some(Written::File(temp, _lock)) = entry.written {
                discard(temp);
            }
        }
    }
}

/// Removes a temporary file and forgets it.
fn discard(temp: TempPath) {
    let name = temp.to_path_buf();
    let mut progress = progress();
    let _ = temp.close();
    progress.temporary.retain(|f| f != &name);
}

/// A file's identity (device and inode on Unix), to recognise an existing file under
/// another name (a hard link); `None` where there is no such notion or no file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Identity(u64, u64);

impl Identity {
    fn of(path: &Path) -> Option<Identity> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            let meta = std::fs::metadata(path).ok()?;
            Some(Identity(meta.dev(), meta.ino()))
        }
        #[cfg(not(unix))]
        {
            let _ = path;
            None
        }
    }
}

/// The directory a path's file is in (`.` for a bare name).
fn directory_of(file: &Path) -> &Path {
    match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Checks that `file` can be an output: not a directory, not read-only, in a directory
/// that exists; returns where it leads (its directory canonical, a symbolic link
/// followed to its file).
fn check_file(file: &Path) -> CliResult<PathBuf> {
    let shown = file.display();
    let dir = directory_of(file);
    if !dir.is_dir() {
        return Err(format!("{shown}: the directory {} does not exist", dir.display()).into());
    }
    let is_link = std::fs::symlink_metadata(file).is_ok_and(|m| m.file_type().is_symlink());
    let meta = std::fs::metadata(file);
    let real = match (&meta, is_link) {
        (Ok(_), true) => std::fs::canonicalize(file).map_err(|e| format!("{shown}: {e}"))?,
        (Err(_), true) => {
            return Err(format!(
                "{shown}: is a symbolic link to a file that does not exist; not replaced \
                 (give the file it should point to, or remove the link)"
            )
            .into())
        }
        _ => {
            let Some(name) = file.file_name() else {
                return Err(format!("{shown}: is not a file name").into());
            };
            let dir = std::fs::canonicalize(dir).map_err(|e| format!("{shown}: {e}"))?;
            dir.join(name)
        }
    };
    let Ok(meta) = meta else {
        return Ok(real); // a new file
    };
    if !meta.is_file() {
        return Err(format!("{shown}: exists and is not a file; not replaced").into());
    }
    let writable = !meta.permissions().readonly()
        && std::fs::OpenOptions::new().write(true).open(file).is_ok();
    if !writable {
        return Err(format!(
            "{shown}: the file is read-only; not replaced (make it writable or choose another output)"
        )
        .into());
    }
    Ok(real)
}

/// How long a temporary file of our naming must have been left alone (and unlocked)
/// before another run removes it: a file is locked an instant after it is created, and
/// this leaves that instant a wide margin.
const STALE_AFTER: Duration = Duration::from_secs(60);

/// Removes from `dir` the temporary files a killed run left: names of our pattern
/// (`.geotracks-` + 6 letters or digits + `.tmp` or `.bak`), regular files, not locked
/// by a running process, unchanged for `age` ([`STALE_AFTER`] in a run). Failures are
/// ignored: this is housekeeping, and the run's own outputs do not depend on it.
fn remove_stale_temporaries(dir: &Path, age: Duration) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let now = SystemTime::now();
    for entry in entries.flatten() {
        let name = entry.file_name();
        if !is_our_temporary(&name.to_string_lossy()) {
            continue;
        }
        let path = entry.path();
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        let old = last_change(&meta)
            .is_some_and(|t| now.duration_since(t).map_or(age.is_zero(), |a| a >= age));
        if !meta.is_file() || !old {
            continue;
        }
        // A running process holds a lock on its temporary files.
        let Ok(file) = std::fs::File::open(&path) else {
            continue;
        };
        if file.try_lock().is_ok() {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// When a file last changed: its status-change time on Unix (a backup is a new hard link
/// to an old file, whose modification time says nothing of the link), else its
/// modification time.
fn last_change(meta: &std::fs::Metadata) -> Option<SystemTime> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let changed = SystemTime::UNIX_EPOCH
            + Duration::from_secs(u64::try_from(meta.ctime()).ok()?)
            + Duration::from_nanos(u64::try_from(meta.ctime_nsec()).ok()?);
        Some(changed.max(meta.modified().ok()?))
    }
    #[cfg(not(unix))]
    {
        meta.modified().ok()
    }
}

/// `true` for the names [`temp_file_beside`] and [`backup_of`] make.
fn is_our_temporary(name: &str) -> bool {
    let Some(rest) = name.strip_prefix(TEMP_PREFIX) else {
        return false;
    };
    let Some(random) = rest
        .strip_suffix(TEMP_SUFFIX)
        .or_else(|| rest.strip_suffix(BACKUP_SUFFIX))
    else {
        return false;
    };
    random.len() == RANDOM_LEN && random.bytes().all(|b| b.is_ascii_alphanumeric())
}

const TEMP_PREFIX: &str = ".geotracks-";
const TEMP_SUFFIX: &str = ".tmp";
const BACKUP_SUFFIX: &str = ".bak";
/// Random characters in a temporary name (tempfile's default, set explicitly so the
/// names stay recognisable).
const RANDOM_LEN: usize = 6;

/// A new, empty temporary file in `target`'s directory, locked for as long as the
/// returned handle lives and registered for removal on a signal. Its error names no
/// temporary path.
fn temp_file_beside(target: &Path) -> std::io::Result<(std::fs::File, TempPath)> {
    let dir = directory_of(target);
    let mut progress = progress();
    let mut builder = tempfile::Builder::new();
    builder
        .prefix(TEMP_PREFIX)
        .suffix(TEMP_SUFFIX)
        .rand_bytes(RANDOM_LEN);
    // Created 0600 by default; 0666 lets the umask decide, as for any new file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let temp = builder.tempfile_in(dir).map_err(without_temp_path)?;
    // Where locks are not supported, stale files are only recognised by their age.
    let _ = temp.as_file().lock();
    let (file, temp) = temp.into_parts();
    progress.temporary.push(temp.to_path_buf());
    Ok((file, temp))
}

/// A hard link to `target` under a temporary name, to restore it from; `None` where
/// links are not supported (the restore then cannot happen, which only matters if a
/// rename fails half-way through a commit).
fn backup_of(target: &Path) -> Option<TempPath> {
    let dir = target.parent().filter(|d| !d.as_os_str().is_empty())?;
    let name = tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .suffix(BACKUP_SUFFIX)
        .rand_bytes(RANDOM_LEN)
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
#[path = "output_tests.rs"]
mod tests;
