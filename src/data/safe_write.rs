//! Guards that keep a user's files safe from the commands' outputs.
//!
//! - An output folder records what it holds in a manifest ([`MANIFEST`]); a folder is replaced
//!   only if every file in it is one the manifest lists, so a user's `notes.md` beside a study's
//!   outputs is never deleted.
//! - No output may be one of the command's inputs, or a folder holding one ([`refuse_inputs`]).
//! - Every file a command reads is recorded ([`note_input`]); every write goes through
//!   [`check_output`], which refuses a path that is one of those inputs (or a folder holding
//!   one), so a new input flag cannot forget the check; it also refuses an existing output that
//!   is not a regular file (a FIFO, device, socket or symbolic link would be replaced by a file).
//! - Temporaries of a killed run (`.NAME.tmp-PID`) are removed by the next run, but only ours
//!   and only when that process is gone ([`clean_stale_temporaries`]).

use std::path::Path;

use super::DataError;

/// Name of the manifest in every output folder: one relative path per line, the files the
/// command wrote.
pub const MANIFEST: &str = ".smash-outputs";

/// Relative paths (with `/`) of every file under `dir` (symbolic links are not followed).
fn files_under(dir: &Path) -> std::io::Result<Vec<String>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d)? {
            let entry = entry?;
            let path = entry.path();
            if entry.file_type()?.is_dir() {
                stack.push(path);
            } else if let Ok(rel) = path.strip_prefix(dir) {
                let parts: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                out.push(parts.join("/"));
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Write the manifest of every file now under `dir` (the temporary folder of a finished run).
pub fn write_manifest(dir: &Path) -> std::io::Result<()> {
    let files = files_under(dir)?;
    let text = manifest_text(files.iter().map(Path::new));
    std::fs::write(dir.join(MANIFEST), text)
}

/// The manifest's text for `files` (relative paths).
pub fn manifest_text<'a>(files: impl IntoIterator<Item = &'a Path>) -> String {
    let mut lines: Vec<String> = files
        .into_iter()
        .map(|p| {
            p.components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/")
        })
        .collect();
    lines.sort();
    let mut s = format!(
        "# Files written by smash {} into this folder; the next run may replace them.\n",
        env!("CARGO_PKG_VERSION")
    );
    for l in lines {
        s.push_str(&l);
        s.push('\n');
    }
    s
}

/// Check that `dir` may be replaced by a command's new outputs: it does not exist, is empty, or
/// holds only files its manifest lists (an earlier output of a smash command).
pub fn check_replaceable(dir: &Path) -> Result<(), DataError> {
    let err = |m: String| DataError::file(dir, m);
    let meta = match std::fs::symlink_metadata(dir) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(err(format!("cannot read: {e}"))),
    };
    if !meta.is_dir() {
        return Err(err(
            "exists and is not a folder; choose a new or empty folder for the outputs".into(),
        ));
    }
    let present = files_under(dir).map_err(|e| err(format!("cannot read folder: {e}")))?;
    if present.is_empty() {
        return Ok(());
    }
    let listed: Vec<String> = match std::fs::read_to_string(dir.join(MANIFEST)) {
        Ok(text) => text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.is_empty())
            .map(str::to_owned)
            .collect(),
        Err(_) => {
            return Err(err(format!(
                "the folder holds files smash did not write (e.g. {}; no {MANIFEST} list of \
                 earlier outputs); choose a new or empty folder, or move those files away",
                super::escape(&present[0])
            )))
        }
    };
    if let Some(foreign) = present
        .iter()
        .find(|f| f.as_str() != MANIFEST && !listed.contains(f))
    {
        return Err(err(format!(
            "the folder holds {}, which smash did not write; the outputs replace the whole \
             folder, so choose a new or empty folder, or move that file away",
            super::escape(foreign)
        )));
    }
    Ok(())
}

pub use crate::inputs::{canonical, note_input, note_input_named};

/// What an existing non-regular path is, in words (`None` for a regular file or a folder).
fn special_kind(meta: &std::fs::Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_symlink() {
        return Some("a symbolic link (writing would replace the link itself, not its target)");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_char_device() || t.is_block_device() {
            return Some("a device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    (!t.is_file() && !t.is_dir()).then_some("not a regular file")
}

/// The one check before any output is written to `out` (a file, or a folder when `folder`):
/// it must not be one of the inputs this run has read ([`note_input`]) nor, for a folder, hold
/// one; an existing path must be a regular file (a folder when `folder`).
pub fn check_output(out: &Path, folder: bool) -> Result<(), DataError> {
    if let Ok(meta) = std::fs::symlink_metadata(out) {
        if let Some(kind) = special_kind(&meta) {
            return Err(DataError::file(
                out,
                format!(
                    "the output exists and is {kind}; outputs replace a regular file only: give a new path"
                ),
            ));
        }
        if meta.is_dir() && !folder {
            return Err(DataError::file(
                out,
                "the output is a folder; give a file path",
            ));
        }
    }
    let o = canonical(out);
    let named = crate::inputs::name_of(&o);
    for input in crate::inputs::recorded().iter() {
        if *input == o {
            let what = named.map_or(String::new(), |n| format!(" ({n})"));
            return Err(DataError::file(
                out,
                format!(
                    "the output is the same file as one of this command's inputs{what}: writing \
                     it would replace the input; give the output a new path"
                ),
            ));
        }
        if folder && input.starts_with(&o) {
            return Err(DataError::file(
                out,
                format!(
                    "the output folder holds an input of this command ({}): writing the outputs would replace it; give another folder",
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuse outputs that are inputs. `outputs` and `inputs` are `(flag, path)` pairs (e.g.
/// `("--out", …)`, `("--shots", …)`); an output folder (`folder = true` in `outputs`) is also
/// refused when an input lies inside it, since the outputs replace the whole folder. Two
/// outputs may not be the same path either. Every input read so far is checked too
/// ([`check_output`]).
pub fn refuse_inputs(
    outputs: &[(&str, &Path, bool)],
    inputs: &[(&str, &Path)],
) -> Result<(), DataError> {
    for (i, (oflag, out, folder)) in outputs.iter().enumerate() {
        let o = canonical(out);
        for (iflag, input) in inputs {
            let c = canonical(input);
            if c == o {
                return Err(DataError::file(
                    out,
                    format!(
                        "{oflag} is the same file as {iflag}: writing it would replace the input; \
                         give {oflag} a new path"
                    ),
                ));
            }
            if *folder && c.starts_with(&o) {
                return Err(DataError::file(
                    out,
                    format!(
                        "{oflag} is a folder holding the input {iflag} ({}): writing the outputs \
                         would replace it; give {oflag} another folder",
                        input.display()
                    ),
                ));
            }
        }
        for (oflag2, out2, _) in &outputs[..i] {
            if canonical(out2) == o {
                return Err(DataError::file(
                    out,
                    format!("{oflag} and {oflag2} are the same path; give each its own"),
                ));
            }
        }
        check_output(out, *folder)
            .map_err(|e| DataError::file(out, format!("{oflag}: {}", e.message)))?;
    }
    Ok(())
}

/// The last component of the outputs folder `dir` and the folder that holds it (`.` for a bare
/// name), where [`super::write_folder_atomic`] makes its temporary sibling.
pub fn folder_name_and_parent(dir: &Path) -> Result<(String, std::path::PathBuf), DataError> {
    let name = dir
        .file_name()
        .ok_or_else(|| DataError::file(dir, "not a folder path"))?
        .to_string_lossy()
        .into_owned();
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => Path::new(".").to_owned(),
    };
    Ok((name, parent))
}

/// Before any work: can the outputs folder `dir` be written where [`super::write_folder_atomic`]
/// writes it? Its parent is created if missing, and the temporary sibling folder it fills first
/// is made and removed again, so a read-only or pseudo-file-system location (`/proc/x`) fails
/// here, with one line, rather than after the command has printed its report.
pub fn check_folder_writable(dir: &Path) -> Result<(), DataError> {
    let err = |m: String| DataError::file(dir, m);
    let (name, parent) = folder_name_and_parent(dir)?;
    std::fs::create_dir_all(&parent).map_err(|e| {
        err(format!(
            "cannot create the folder {} to hold it: {e}",
            parent.display()
        ))
    })?;
    let probe = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&probe);
    super::temporaries::register_temporary(&probe);
    let created = std::fs::create_dir(&probe);
    let _ = std::fs::remove_dir(&probe);
    super::temporaries::forget_temporary(&probe);
    created.map_err(|e| {
        err(format!(
            "cannot write in {}: {e}; choose a folder you can write to",
            parent.display()
        ))
    })?;
    Ok(())
}

/// Whether process `pid` is certainly gone (Linux `/proc`); `false` where that cannot be known.
fn process_gone(pid: u32) -> bool {
    Path::new("/proc/self").exists() && !Path::new("/proc").join(pid.to_string()).exists()
}

/// Remove the temporaries a killed run of ours left beside `target` (`.NAME.tmp-PID` folders,
/// `.NAME.PID.tmp` files), only when process PID is gone. A `.NAME.old-PID` folder or file (a
/// run killed between keeping the previous output aside and moving the new one in) is put back
/// when `target` is missing, else removed.
pub fn clean_stale_temporaries(target: &Path) {
    let (Some(name), parent) = (target.file_name(), target.parent()) else {
        return;
    };
    let name = name.to_string_lossy();
    let parent = match parent {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let me = std::process::id();
    let folder_tmp = format!(".{name}.tmp-");
    let folder_old = format!(".{name}.old-");
    let file_tmp = format!(".{name}.");
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let pid_of = |digits: &str| -> Option<u32> {
            (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
                .then(|| digits.parse().ok())
                .flatten()
        };
        let path = entry.path();
        if let Some(pid) = file.strip_prefix(&folder_tmp).and_then(pid_of) {
            if pid != me && process_gone(pid) {
                let _ = std::fs::remove_dir_all(&path);
            }
        } else if let Some(pid) = file.strip_prefix(&folder_old).and_then(pid_of) {
            if pid != me && process_gone(pid) {
                if target.exists() && path.is_dir() {
                    let _ = std::fs::remove_dir_all(&path);
                } else if target.exists() {
                    let _ = std::fs::remove_file(&path);
                } else {
                    let _ = std::fs::rename(&path, target);
                }
            }
        } else if let Some(pid) = file
            .strip_prefix(&file_tmp)
            .and_then(|rest| rest.strip_suffix(".tmp"))
            .and_then(pid_of)
        {
            if pid != me && process_gone(pid) && path.is_file() {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
}
