//! Every output of one command, resolved and checked together before any work, then written all
//! or nothing.
//!
//! A command names its outputs once ([`OutputPlan`]: `--out-club` a file, `--out-dir` a folder,
//! …) beside its inputs. [`OutputPlan::check`] refuses, before anything is computed, two outputs
//! that are the same path or one inside the other (a `--report` inside an `--out-dir` the run
//! replaces as a whole), an output that is an input or holds one, an output whose parent cannot
//! be written, and a previous output folder that could not be removed (write-protected). The
//! bytes are then staged ([`Staging`]) as temporaries beside their targets; only when every
//! output is staged does [`Staging::commit`] move them in, taking back the ones already moved if
//! a later one fails. A failure at any step leaves every earlier output as it was.
//!
//! The temporaries of this process are registered ([`remove_live_temporaries`]), so a handler of
//! SIGINT or SIGTERM removes them before the process ends.

use super::temporaries::live;
pub use super::temporaries::{forget_temporary, register_temporary, remove_live_temporaries};
use super::{safe_write, DataError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// One planned output.
#[derive(Debug, Clone)]
struct Planned {
    flag: String,
    path: PathBuf,
    folder: bool,
}

/// The outputs and inputs of one command (see the module documentation).
#[derive(Debug, Clone, Default)]
pub struct OutputPlan {
    outputs: Vec<Planned>,
    inputs: Vec<(String, PathBuf)>,
}

/// The folder holding `path` (`.` for a bare name) and its last component.
fn parent_and_name(path: &Path) -> Result<(PathBuf, String), DataError> {
    let name = path
        .file_name()
        .ok_or_else(|| DataError::file(path, "not a file path"))?
        .to_string_lossy()
        .into_owned();
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

impl OutputPlan {
    /// A plan with these inputs (`(flag, path)`, e.g. `("--shots", …)`).
    pub fn new(inputs: &[(&str, &Path)]) -> Self {
        Self {
            outputs: Vec::new(),
            inputs: inputs
                .iter()
                .map(|(f, p)| ((*f).to_owned(), p.to_path_buf()))
                .collect(),
        }
    }

    /// Add an input.
    pub fn input(mut self, flag: &str, path: Option<&Path>) -> Self {
        if let Some(p) = path {
            self.inputs.push((flag.to_owned(), p.to_owned()));
        }
        self
    }

    /// Add a file output (nothing when `path` is `None`: the option was not given).
    pub fn file(mut self, flag: &str, path: Option<&Path>) -> Self {
        if let Some(p) = path {
            self.outputs.push(Planned {
                flag: flag.to_owned(),
                path: p.to_owned(),
                folder: false,
            });
        }
        self
    }

    /// Add a folder output, replaced as a whole.
    pub fn folder(mut self, flag: &str, path: Option<&Path>) -> Self {
        if let Some(p) = path {
            self.outputs.push(Planned {
                flag: flag.to_owned(),
                path: p.to_owned(),
                folder: true,
            });
        }
        self
    }

    /// Check every output against every input and every other output, and that each can be
    /// written (see the module documentation). Call before any work.
    pub fn check(&self) -> Result<(), DataError> {
        let outs: Vec<(&str, &Path, bool)> = self
            .outputs
            .iter()
            .map(|o| (o.flag.as_str(), o.path.as_path(), o.folder))
            .collect();
        let ins: Vec<(&str, &Path)> = self
            .inputs
            .iter()
            .map(|(f, p)| (f.as_str(), p.as_path()))
            .collect();
        safe_write::refuse_inputs(&outs, &ins)?;
        for a in &self.outputs {
            let ca = safe_write::canonical(&a.path);
            for b in self.outputs.iter().filter(|b| b.folder) {
                let cb = safe_write::canonical(&b.path);
                if ca != cb && ca.starts_with(&cb) {
                    return Err(DataError::file(
                        &a.path,
                        format!(
                            "{} is inside {} ({}), which is replaced as a whole; write it beside \
                             that folder",
                            a.flag,
                            b.flag,
                            b.path.display()
                        ),
                    ));
                }
            }
        }
        for o in &self.outputs {
            let flagged =
                |e: DataError| DataError::file(&o.path, format!("{}: {}", o.flag, e.message));
            if o.folder {
                safe_write::clean_stale_temporaries(&o.path);
                safe_write::check_replaceable(&o.path).map_err(flagged)?;
                safe_write::check_folder_writable(&o.path).map_err(flagged)?;
                check_removable(&o.path).map_err(flagged)?;
            } else {
                check_file_writable(&o.path).map_err(flagged)?;
            }
        }
        Ok(())
    }

    /// Start writing the planned outputs.
    pub fn stage(&self) -> Staging {
        Staging {
            planned: self.outputs.clone(),
            staged: Vec::new(),
            committed: false,
        }
    }
}

/// Can a file be written at `path`: its parent is made if missing, and a temporary file is
/// created in it and removed again.
fn check_file_writable(path: &Path) -> Result<(), DataError> {
    let (parent, name) = parent_and_name(path)?;
    std::fs::create_dir_all(&parent).map_err(|e| {
        DataError::file(
            path,
            format!(
                "cannot create the folder {} to hold it: {e}",
                parent.display()
            ),
        )
    })?;
    safe_write::clean_stale_temporaries(path);
    let probe = parent.join(format!(".{name}.{}.tmp", std::process::id()));
    register_temporary(&probe);
    let created = std::fs::File::create(&probe);
    let _ = std::fs::remove_file(&probe);
    forget_temporary(&probe);
    created.map_err(|e| {
        DataError::file(
            path,
            format!(
                "cannot write in {}: {e}; choose a folder you can write to",
                parent.display()
            ),
        )
    })?;
    Ok(())
}

/// Can the previous outputs in folder `dir` be removed once the new ones replace them: every
/// folder in it must be writable (a write-protected one was once moved aside to a hidden
/// `.NAME.old-PID` that stayed for good). A probe file is made and removed in each.
pub fn check_removable(dir: &Path) -> Result<(), DataError> {
    if !dir.is_dir() {
        return Ok(());
    }
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        let probe = d.join(format!(".smash-probe.{}.tmp", std::process::id()));
        register_temporary(&probe);
        let created = std::fs::File::create(&probe);
        let _ = std::fs::remove_file(&probe);
        forget_temporary(&probe);
        if let Err(e) = created {
            return Err(DataError::file(
                dir,
                format!(
                    "the previous outputs in it cannot be removed ({}: {e}); make the folder \
                     writable (chmod -R u+w) or choose another",
                    d.display()
                ),
            ));
        }
        if let Ok(entries) = std::fs::read_dir(&d) {
            for entry in entries.flatten() {
                if entry.file_type().is_ok_and(|t| t.is_dir()) {
                    stack.push(entry.path());
                }
            }
        }
    }
    Ok(())
}

/// One staged output: its temporary beside the target.
#[derive(Debug)]
struct Staged {
    target: PathBuf,
    tmp: PathBuf,
    folder: bool,
}

/// The outputs being written: temporaries beside their targets, moved in by
/// [`Staging::commit`]; dropped without a commit, every temporary is removed.
#[derive(Debug)]
pub struct Staging {
    planned: Vec<Planned>,
    staged: Vec<Staged>,
    committed: bool,
}

impl Staging {
    fn planned(&self, path: &Path, folder: bool) -> Result<(), DataError> {
        if self
            .planned
            .iter()
            .any(|p| p.path == path && p.folder == folder)
        {
            Ok(())
        } else {
            Err(DataError::file(
                path,
                "internal error: an output that was not planned (and checked) before the work",
            ))
        }
    }

    /// Stage the file `path` with `bytes`.
    pub fn file(&mut self, path: &Path, bytes: &[u8]) -> Result<(), DataError> {
        self.planned(path, false)?;
        let (parent, name) = parent_and_name(path)?;
        let tmp = parent.join(format!(".{name}.{}.tmp", std::process::id()));
        register_temporary(&tmp);
        let written = (|| {
            std::fs::create_dir_all(&parent)?;
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(bytes)?;
            f.sync_all()
        })();
        self.staged.push(Staged {
            target: path.to_owned(),
            tmp,
            folder: false,
        });
        written.map_err(|e| {
            DataError::file(path, format!("cannot write: {e} (no output was written)"))
        })
    }

    /// Stage the folder `dir`: `write` fills the temporary folder it is given (and syncs what
    /// it writes); a manifest of what it holds is added ([`safe_write::MANIFEST`]).
    pub fn folder_with<T>(
        &mut self,
        dir: &Path,
        write: impl FnOnce(&Path) -> std::io::Result<T>,
    ) -> Result<T, DataError> {
        self.planned(dir, true)?;
        let (parent, name) = parent_and_name(dir)?;
        let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        register_temporary(&tmp);
        let _ = std::fs::remove_dir_all(&tmp);
        let written = std::fs::create_dir_all(&tmp)
            .and_then(|()| write(&tmp))
            .and_then(|v| safe_write::write_manifest(&tmp).map(|()| v));
        self.staged.push(Staged {
            target: dir.to_owned(),
            tmp: tmp.clone(),
            folder: true,
        });
        written.map_err(|e| {
            // Name the output folder, not the hidden temporary the error may mention.
            let text = e
                .to_string()
                .replace(&tmp.display().to_string(), &dir.display().to_string());
            DataError::file(dir, format!("cannot write: {text} (no output was written)"))
        })
    }

    /// Stage the folder `dir` holding `files` (relative paths and bytes).
    pub fn folder(&mut self, dir: &Path, files: &[(PathBuf, Vec<u8>)]) -> Result<(), DataError> {
        self.folder_with(dir, |tmp| {
            for (rel, bytes) in files {
                let path = tmp.join(rel);
                if let Some(p) = path.parent() {
                    std::fs::create_dir_all(p)?;
                }
                let mut f = std::fs::File::create(&path)?;
                f.write_all(bytes)?;
                f.sync_all()?;
            }
            Ok(())
        })
    }

    /// Where the staged output `target` is being written (to read it back before the commit).
    pub fn staged(&self, target: &Path) -> Option<&Path> {
        self.staged
            .iter()
            .find(|s| s.target == target)
            .map(|s| s.tmp.as_path())
    }

    /// Move every staged output into place. If one cannot be moved, the ones already moved are
    /// taken back (the previous files and folders restored) and nothing of this run remains.
    pub fn commit(mut self) -> Result<(), DataError> {
        // Hold the registry while moving, so that a signal's handler waits for the whole
        // commit instead of cutting it in half.
        let mut live = live();
        let mut done: Vec<(&Staged, Option<PathBuf>)> = Vec::new();
        let mut failure = None;
        for s in &self.staged {
            match move_in(s) {
                Ok(old) => done.push((s, old)),
                Err(e) => {
                    failure = Some((s, e));
                    break;
                }
            }
        }
        if let Some((s, e)) = failure {
            for (d, old) in done.into_iter().rev() {
                take_back(d, old.as_deref());
            }
            drop(live);
            return Err(DataError::file(
                &s.target,
                format!("cannot write: {e} (no output was written; the previous ones are kept)"),
            ));
        }
        for (s, old) in &done {
            live.retain(|t| *t != s.tmp);
            if let Some(old) = old {
                let removed = if s.folder {
                    std::fs::remove_dir_all(old)
                } else {
                    std::fs::remove_file(old)
                };
                if let Err(e) = removed {
                    eprintln!(
                        "warning: {}: the previous outputs, moved to {}, could not be removed: {e}",
                        s.target.display(),
                        old.display()
                    );
                }
            }
        }
        self.committed = true;
        Ok(())
    }
}

/// The hidden name the previous output at `target` is kept under during a commit.
fn old_path(target: &Path) -> PathBuf {
    let (parent, name) =
        parent_and_name(target).unwrap_or_else(|_| (PathBuf::from("."), "out".into()));
    parent.join(format!(".{name}.old-{}", std::process::id()))
}

/// Move one staged output in; returns where the previous one was kept, if there was one.
fn move_in(s: &Staged) -> std::io::Result<Option<PathBuf>> {
    let old = old_path(&s.target);
    let had = std::fs::symlink_metadata(&s.target).is_ok();
    if had {
        if s.folder {
            std::fs::rename(&s.target, &old)?;
        } else {
            // A link keeps the target in place until the rename replaces it atomically.
            let _ = std::fs::remove_file(&old);
            if std::fs::hard_link(&s.target, &old).is_err() {
                std::fs::copy(&s.target, &old)?;
            }
        }
    }
    if let Err(e) = std::fs::rename(&s.tmp, &s.target) {
        if had && s.folder {
            let _ = std::fs::rename(&old, &s.target);
        } else if had {
            let _ = std::fs::remove_file(&old);
        }
        return Err(e);
    }
    Ok(had.then_some(old))
}

/// Undo [`move_in`]: put the previous output back, or remove the new one.
fn take_back(s: &Staged, old: Option<&Path>) {
    match old {
        Some(old) => {
            if s.folder {
                let _ = std::fs::remove_dir_all(&s.target);
            }
            let _ = std::fs::rename(old, &s.target);
        }
        None if s.folder => {
            let _ = std::fs::remove_dir_all(&s.target);
        }
        None => {
            let _ = std::fs::remove_file(&s.target);
        }
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if self.committed {
            return;
        }
        for s in &self.staged {
            if s.folder {
                let _ = std::fs::remove_dir_all(&s.tmp);
            } else {
                let _ = std::fs::remove_file(&s.tmp);
            }
            forget_temporary(&s.tmp);
        }
    }
}
