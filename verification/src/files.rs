//! Writing result files so that an error leaves nothing half-done.
//!
//! Every file beltcheck writes (`solve --json`, `converge --json`, the pages, plots and
//! study JSON of `report`, the three files of `sweep`) goes through [`write_all`]: each
//! text is written to a temporary file beside its target (`.NAME.PID.partial`) and the
//! targets are replaced by renames only once every temporary file was written, so a
//! full disk or a missing directory leaves neither a truncated result nor a temporary
//! file. An existing target that is not a regular file — a symbolic link, a directory,
//! a FIFO, a device or a socket — is refused before anything is written: renaming over
//! it would replace the link or the device node (as root, `/dev/full` would become a
//! regular file).

use std::path::{Path, PathBuf};

/// Why a set of files was not written (nothing of the set is left behind).
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// An existing target that is not a regular file.
    #[error("`{}` exists and is {kind}: refusing to replace it (beltcheck writes regular files only); give the path of a new or a regular file", .path.display())]
    NotRegularFile {
        /// The target.
        path: PathBuf,
        /// What it is ("a symbolic link", "a directory", …).
        kind: &'static str,
    },
    /// A target path without a file name (`/`, `..`).
    #[error("`{}` names no file", .path.display())]
    NoFileName {
        /// The target.
        path: PathBuf,
    },
    /// Creating a directory, writing or renaming failed.
    #[error("writing `{}`", .path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// What an existing path is, if it is not a regular file (`None`: absent or regular).
fn not_regular(path: &Path) -> Option<&'static str> {
    let t = std::fs::symlink_metadata(path).ok()?.file_type();
    if t.is_file() {
        None
    } else if t.is_symlink() {
        Some("a symbolic link")
    } else if t.is_dir() {
        Some("a directory")
    } else {
        Some("not a regular file (a FIFO, device or socket)")
    }
}

/// The temporary file beside `path` that [`write_all`] writes first.
fn partial(path: &Path) -> Result<PathBuf, WriteError> {
    let file = path.file_name().ok_or_else(|| WriteError::NoFileName { path: path.to_path_buf() })?;
    Ok(path.with_file_name(format!(".{}.{}.partial", file.to_string_lossy(), std::process::id())))
}

/// Writes every `(path, text)`: all targets are checked, all texts written to temporary
/// files, and only then renamed onto their targets (module docs). On an error the
/// temporary files are removed; a rename that fails after others succeeded leaves the
/// earlier targets replaced (renames within one directory are atomic one by one, not as
/// a set).
///
/// # Errors
/// [`WriteError`], naming the path.
pub fn write_all(files: &[(PathBuf, &str)]) -> Result<(), WriteError> {
    let mut staged: Vec<(PathBuf, &Path)> = Vec::with_capacity(files.len());
    let unstage = |staged: &[(PathBuf, &Path)]| {
        for (tmp, _) in staged {
            let _ = std::fs::remove_file(tmp);
        }
    };
    for (path, _) in files {
        if let Some(kind) = not_regular(path) {
            return Err(WriteError::NotRegularFile { path: path.clone(), kind });
        }
    }
    for (path, text) in files {
        let tmp = match partial(path) {
            Ok(tmp) => tmp,
            Err(e) => {
                unstage(&staged);
                return Err(e);
            }
        };
        if let Err(source) = std::fs::write(&tmp, text) {
            let _ = std::fs::remove_file(&tmp);
            unstage(&staged);
            return Err(WriteError::Io { path: path.clone(), source });
        }
        staged.push((tmp, path));
    }
    for (i, (tmp, path)) in staged.iter().enumerate() {
        if let Err(source) = std::fs::rename(tmp, path) {
            unstage(&staged[i..]);
            return Err(WriteError::Io { path: path.to_path_buf(), source });
        }
    }
    Ok(())
}

/// [`write_all`] of one file.
///
/// # Errors
/// [`WriteError`], naming the path.
pub fn write_file(path: &Path, text: &str) -> Result<(), WriteError> {
    write_all(&[(path.to_path_buf(), text)])
}

/// `std::fs::create_dir_all` with the error of this module.
///
/// # Errors
/// [`WriteError::Io`] naming the directory (also when it exists as a file).
pub fn create_dir(dir: &Path) -> Result<(), WriteError> {
    std::fs::create_dir_all(dir).map_err(|source| WriteError::Io { path: dir.to_path_buf(), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("beltcheck-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn partials(dir: &Path) -> usize {
        std::fs::read_dir(dir).unwrap().filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".partial")).count()
    }

    /// A set whose second target is a directory: refused before anything is written,
    /// the first target keeps its old content, no temporary file is left.
    #[test]
    fn a_refused_target_leaves_the_whole_set_unwritten() {
        let d = scratch("refused");
        let a = d.join("a.md");
        std::fs::write(&a, "old").unwrap();
        let b = d.join("b.json");
        std::fs::create_dir(&b).unwrap();
        let e = write_all(&[(a.clone(), "new"), (b.clone(), "{}")]).unwrap_err();
        assert!(matches!(e, WriteError::NotRegularFile { kind: "a directory", .. }), "{e}");
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old");
        assert_eq!(partials(&d), 0);
        let _ = std::fs::remove_dir_all(&d);
    }

    /// A target in a missing directory: an I/O error naming it, the other target of the
    /// set not replaced, no temporary file left.
    #[test]
    fn a_failed_write_removes_the_staged_files() {
        let d = scratch("failed");
        let a = d.join("a.md");
        std::fs::write(&a, "old").unwrap();
        let missing = d.join("no-such-dir").join("b.json");
        let e = write_all(&[(a.clone(), "new"), (missing.clone(), "{}")]).unwrap_err();
        assert!(matches!(&e, WriteError::Io { path, .. } if *path == missing), "{e}");
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old");
        assert_eq!(partials(&d), 0);
        let _ = std::fs::remove_dir_all(&d);
    }

    /// The ordinary case: every file written with its text, nothing else in the directory.
    #[test]
    fn a_set_is_written_whole() {
        let d = scratch("whole");
        let (a, b) = (d.join("a.md"), d.join("b.json"));
        std::fs::write(&a, "old").unwrap();
        write_all(&[(a.clone(), "new"), (b.clone(), "{}")]).unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "{}");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 2);
        let _ = std::fs::remove_dir_all(&d);
    }
}
