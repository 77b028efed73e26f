//! Unit tests of `output.rs` (a file of their own, so that the module stays short).

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
    assert!(!progress()
        .temporary
        .iter()
        .any(|f| f.starts_with(dir.path())));
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

/// Two outputs that are one file under two spellings: `./`, `..`, a symbolic link,
/// a hard link. The second was compared as text and accepted, and the first
/// output was lost.
#[test]
fn one_file_under_two_names_is_refused_as_two_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("d.txt");
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    for other in [
        dir.path().join(".").join("d.txt"),
        dir.path().join("sub").join("..").join("d.txt"),
    ] {
        let mut outputs = Outputs::new([]);
        outputs.declare(&d).unwrap();
        let err = outputs.declare(&other).unwrap_err().to_string();
        assert!(err.contains("the same file as"), "{err}");
        assert!(err.contains("two outputs"), "{err}");
    }
    // Through links, to an existing file.
    std::fs::write(&d, "old\n").unwrap();
    let link = dir.path().join("link.txt");
    let hard = dir.path().join("hard.txt");
    #[cfg(unix)]
    std::os::unix::fs::symlink(&d, &link).unwrap();
    std::fs::hard_link(&d, &hard).unwrap();
    for other in [&link, &hard] {
        if !other.exists() {
            continue;
        }
        let mut outputs = Outputs::new([]);
        outputs.declare(other).unwrap();
        let err = outputs.declare(&d).unwrap_err().to_string();
        assert!(err.contains("two outputs"), "{other:?}: {err}");
        // And as an input.
        let mut outputs = Outputs::new([d.as_path()]);
        let err = outputs.declare(other).unwrap_err().to_string();
        assert!(err.contains("is also an input"), "{other:?}: {err}");
    }
}

/// A symbolic link as an output is written through: the file it points to gets the
/// content, and the link stays a link.
#[cfg(unix)]
#[test]
fn an_output_that_is_a_symbolic_link_is_written_through_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("real")).unwrap();
    let target = dir.path().join("real").join("d.txt");
    std::fs::write(&target, "old\n").unwrap();
    let link = dir.path().join("link.txt");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let mut outputs = Outputs::new([]);
    outputs.declare(&link).unwrap();
    outputs.write(&link, |w| w.write_all(b"new\n")).unwrap();
    outputs.commit().unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "new\n");
    assert!(temps(dir.path()).is_empty());
    assert!(temps(&dir.path().join("real")).is_empty());
    // A link to nothing is refused rather than replaced by a file.
    let dangling = dir.path().join("dangling.txt");
    std::os::unix::fs::symlink(dir.path().join("nowhere.txt"), &dangling).unwrap();
    let err = Outputs::new([]).declare(&dangling).unwrap_err().to_string();
    assert!(
        err.contains("symbolic link to a file that does not exist"),
        "{err}"
    );
}

/// What an interrupted run says follows what the commit did: nothing, standard
/// output only started, or every file in place. It said "no output written" after
/// the renames too.
#[test]
fn the_interruption_message_says_what_was_written() {
    let mut p = Progress {
        temporary: Vec::new(),
        stdout: false,
        replaced: Vec::new(),
    };
    assert_eq!(interrupted(&p), "interrupted: no output written");
    p.stdout = true;
    assert!(interrupted(&p).contains("standard output may be incomplete"));
    p.replaced = vec!["big.ply".into(), "run.json".into()];
    assert_eq!(
        interrupted(&p),
        "interrupted after the outputs were complete: wrote standard output, big.ply, run.json"
    );
    // A commit records its targets, as the user named them, under the lock the
    // signal handler takes.
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
    let mut outputs = Outputs::new([]);
    outputs.declare(&a).unwrap();
    outputs.declare(&b).unwrap();
    outputs.write(&a, |w| w.write_all(b"a\n")).unwrap();
    outputs.write(&b, |w| w.write_all(b"b\n")).unwrap();
    let before = progress().replaced.len();
    assert!(!progress().replaced.contains(&a.display().to_string()));
    outputs.commit().unwrap();
    let replaced = progress().replaced.clone();
    assert!(replaced.len() >= before + 2);
    for name in [&a, &b] {
        assert!(
            replaced.contains(&name.display().to_string()),
            "{replaced:?}"
        );
    }
}

/// Temporary files a killed run left (unlocked, of our naming) go; those of a
/// live run (locked) and files of other names stay.
#[test]
fn stale_temporary_files_are_removed_and_live_ones_kept() {
    let dir = tempfile::tempdir().unwrap();
    let stale = dir.path().join(".geotracks-AbC123.tmp");
    let stale_backup = dir.path().join(".geotracks-x9y8z7.bak");
    let other = [
        ".geotracks-notours.tmp",
        "keep.tmp",
        ".geotracks-abcdef.txt",
    ];
    for name in [&stale, &stale_backup] {
        std::fs::write(name, "left by a killed run").unwrap();
    }
    for name in other {
        std::fs::write(dir.path().join(name), "not ours").unwrap();
    }
    let live = dir.path().join("live.txt");
    let mut outputs = Outputs::new([]);
    outputs.declare(&live).unwrap();
    outputs.write(&live, |w| w.write_all(b"live\n")).unwrap();
    let live_temp: Vec<String> = temps(dir.path())
        .into_iter()
        .filter(|n| n.ends_with(".tmp") && is_our_temporary(n) && !n.contains("AbC123"))
        .collect();
    assert_eq!(live_temp.len(), 1, "{live_temp:?}");
    // Fresh files are left alone at the run's age limit.
    remove_stale_temporaries(dir.path(), STALE_AFTER);
    assert!(stale.exists() && stale_backup.exists());
    remove_stale_temporaries(dir.path(), Duration::ZERO);
    assert!(!stale.exists() && !stale_backup.exists());
    assert!(
        dir.path().join(&live_temp[0]).exists(),
        "a live run's file was removed"
    );
    for name in other {
        assert!(dir.path().join(name).exists(), "{name}");
    }
    outputs.commit().unwrap();
    assert_eq!(std::fs::read_to_string(&live).unwrap(), "live\n");
}
