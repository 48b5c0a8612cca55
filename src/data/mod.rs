//! Files: club TOML, shots CSV, predictions CSV, and the one place that writes files.
//!
//! Readers return typed values with errors that name the file, line, column or key, what was
//! wrong and what is allowed. Exporters build bytes; [`write_atomic`] writes them through a
//! temporary file and a rename, so a failed run never leaves a half-written file behind.

pub mod club_file;
pub mod columns;
pub mod datetime;
pub mod effect_defs;
pub mod flight_files;
pub mod flight_measured;
pub(crate) mod flight_output;
pub mod flight_summary;
pub mod import;
pub mod launch_read;
pub mod left_out;
pub mod noise_file;
pub mod number;
pub mod output_plan;
pub mod predictions;
pub mod safe_write;
pub mod sessions;
pub mod shots;
mod shots_left;
pub mod temporaries;
pub mod toml_check;

pub use toml_check::{parse_toml, toml_key_error, TomlDoc};

use crate::line_index::csv_message;

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};

/// An error in an input or output file, with as precise a location as is known.
#[derive(Debug, Clone, PartialEq)]
pub struct DataError {
    /// The file.
    pub path: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// Where on the line: `column 7`, `column 'club_speed_mph'`, `key club.mass_g`, …
    pub place: Option<String>,
    /// What was wrong and what is allowed.
    pub message: String,
}

impl DataError {
    /// An error about a whole file.
    pub fn file(path: &Path, message: impl std::fmt::Display) -> Self {
        Self {
            path: path.to_owned(),
            line: None,
            place: None,
            message: message.to_string(),
        }
    }

    /// An error at a line (and optional place on it).
    pub fn at(
        path: &Path,
        line: Option<usize>,
        place: Option<String>,
        message: impl std::fmt::Display,
    ) -> Self {
        Self {
            path: path.to_owned(),
            line,
            place,
            message: message.to_string(),
        }
    }
}

impl fmt::Display for DataError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(place) = &self.place {
            write!(f, ": {place}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for DataError {}

/// A `csv` crate error in `path` as one file error: the line from `lines` (a [`LineIndex`] or a
/// [`LineTracker`]: the crate's own count is off for CRLF and CR-only line ends), the wording of
/// [`csv_message`] (field counts, a field that is not UTF-8). Every CSV reader of the library
/// reports its `csv` errors through here (the flight's coefficient tables, below this module,
/// through the same two pieces).
///
/// [`LineIndex`]: crate::line_index::LineIndex
/// [`LineTracker`]: crate::line_index::LineTracker
pub fn csv_error_at(
    lines: &impl crate::line_index::RecordLines,
    path: &Path,
    e: &csv::Error,
) -> DataError {
    let line = e.position().map(|p| lines.line_of(p));
    DataError::at(path, line, None, escape(&csv_message(e)).into_owned())
}

/// Characters of a cell an error message quotes in full; a longer cell is cut.
const QUOTED_CHARS: usize = 48;

/// A cell as an error message quotes it: in single quotes, control characters escaped, and cut
/// after [`QUOTED_CHARS`] characters with its length given (a 100 kB cell once made a 100 kB
/// error line).
pub fn quote_cell(text: &str) -> String {
    let n = text.chars().count();
    if n <= QUOTED_CHARS {
        return format!("'{}'", escape(text));
    }
    let head: String = text.chars().take(QUOTED_CHARS).collect();
    format!("'{}…' ({n} characters)", escape(&head))
}

/// Read a whole text file, mapping I/O errors to a [`DataError`].
pub fn read_text(path: &Path) -> Result<String, DataError> {
    safe_write::note_input(path);
    let bytes =
        std::fs::read(path).map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    crate::line_index::utf8_text(bytes)
        .map_err(|(line, m)| DataError::at(path, Some(line), None, m))
}

/// Write `bytes` to `path` atomically: a temporary file beside it, flushed, then renamed.
/// Creates the parent folder if needed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), DataError> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent).map_err(|e| {
        DataError::file(
            path,
            format!("cannot create folder {}: {e}", parent.display()),
        )
    })?;
    let file_name = path
        .file_name()
        .ok_or_else(|| DataError::file(path, "not a file path"))?
        .to_string_lossy()
        .into_owned();
    safe_write::check_output(path, false)?;
    safe_write::clean_stale_temporaries(path);
    let tmp = parent.join(format!(".{file_name}.{}.tmp", std::process::id()));
    output_plan::register_temporary(&tmp);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    output_plan::forget_temporary(&tmp);
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        DataError::file(path, format!("cannot write: {e}"))
    })
}

/// Write several files as one unit: all are written to temporaries first, then renamed into
/// place; if any step fails, none of the new files is left behind.
pub fn write_files_atomic(files: &[(&Path, &[u8])]) -> Result<(), DataError> {
    let mut staged: Vec<(PathBuf, &Path)> = Vec::new();
    let cleanup = |staged: &[(PathBuf, &Path)]| {
        for (tmp, _) in staged {
            let _ = std::fs::remove_file(tmp);
            output_plan::forget_temporary(tmp);
        }
    };
    for (path, bytes) in files {
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
            _ => PathBuf::from("."),
        };
        let file_name = match path.file_name() {
            Some(n) => n.to_string_lossy().into_owned(),
            None => {
                cleanup(&staged);
                return Err(DataError::file(path, "not a file path"));
            }
        };
        if let Err(e) = safe_write::check_output(path, false) {
            cleanup(&staged);
            return Err(e);
        }
        safe_write::clean_stale_temporaries(path);
        let tmp = parent.join(format!(".{file_name}.{}.tmp", std::process::id()));
        output_plan::register_temporary(&tmp);
        let written = (|| {
            std::fs::create_dir_all(&parent)?;
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(bytes)?;
            f.sync_all()
        })();
        if let Err(e) = written {
            let _ = std::fs::remove_file(&tmp);
            cleanup(&staged);
            return Err(DataError::file(path, format!("cannot write: {e}")));
        }
        staged.push((tmp, path));
    }
    if let Some((_, path)) = staged.iter().find(|(_, p)| p.is_dir()) {
        cleanup(&staged);
        return Err(DataError::file(
            path,
            "is a folder; give a file path (nothing was written)",
        ));
    }
    for (i, (tmp, path)) in staged.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            // Take back the files already moved in, so that none of this run's outputs remains.
            for (_, done) in &staged[..i] {
                let _ = std::fs::remove_file(done);
            }
            cleanup(&staged[i..]);
            return Err(DataError::file(
                path,
                format!("cannot write: {e} (no output was written)"),
            ));
        }
        output_plan::forget_temporary(tmp);
    }
    Ok(())
}

/// Write a whole folder of outputs as one unit: every file goes into a temporary sibling folder,
/// which then replaces `dir`. A failure leaves `dir` as it was; a success leaves exactly `files`
/// (no stale files of an earlier run) and a manifest of them ([`safe_write::MANIFEST`]). An
/// existing non-empty `dir` is replaced only if every file in it is listed in its manifest, so a
/// user's file in it is never removed (`marker`, a file every such output folder has, is kept
/// for the callers' documentation). Temporaries of killed earlier runs are cleaned up first.
pub fn write_folder_atomic(
    dir: &Path,
    files: &[(PathBuf, Vec<u8>)],
    marker: &str,
) -> Result<(), DataError> {
    write_folder_atomic_with(dir, marker, |tmp| {
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

/// [`write_folder_atomic`] for outputs written as they are made: `write` fills the temporary
/// folder it is given (and syncs what it writes); then that folder replaces `dir` as a unit.
pub fn write_folder_atomic_with<T>(
    dir: &Path,
    marker: &str,
    write: impl FnOnce(&Path) -> std::io::Result<T>,
) -> Result<T, DataError> {
    let err = |m: String| DataError::file(dir, m);
    let _ = marker;
    safe_write::check_output(dir, true)?;
    safe_write::clean_stale_temporaries(dir);
    safe_write::check_replaceable(dir)?;
    output_plan::check_removable(dir)?;
    let (name, parent) = safe_write::folder_name_and_parent(dir)?;
    std::fs::create_dir_all(&parent)
        .map_err(|e| err(format!("cannot create {}: {e}", parent.display())))?;
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let old = parent.join(format!(".{name}.old-{}", std::process::id()));
    output_plan::register_temporary(&tmp);
    let _ = std::fs::remove_dir_all(&tmp);
    let written = std::fs::create_dir_all(&tmp)
        .and_then(|()| write(&tmp))
        .and_then(|v| safe_write::write_manifest(&tmp).map(|()| v));
    let value = match written {
        Ok(v) => v,
        Err(e) => {
            let _ = std::fs::remove_dir_all(&tmp);
            output_plan::forget_temporary(&tmp);
            // Name the output folder, not the hidden temporary the error may mention.
            let text = e
                .to_string()
                .replace(&tmp.display().to_string(), &dir.display().to_string());
            return Err(err(format!("cannot write: {text}")));
        }
    };
    let swapped = (|| -> std::io::Result<()> {
        if dir.exists() {
            std::fs::rename(dir, &old)?;
        }
        if let Err(e) = std::fs::rename(&tmp, dir) {
            if old.exists() {
                let _ = std::fs::rename(&old, dir);
            }
            return Err(e);
        }
        Ok(())
    })();
    output_plan::forget_temporary(&tmp);
    if let Err(e) = swapped {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(err(format!("cannot replace the folder: {e}")));
    }
    if let Err(e) = std::fs::remove_dir_all(&old) {
        eprintln!(
            "warning: {}: the previous outputs, moved to {}, could not be removed: {e}",
            dir.display(),
            old.display()
        );
    }
    Ok(value)
}

pub use crate::units::Num;

/// `text` with every control character (ESC, CR, LF, DEL, …) written as a visible escape
/// (`\u{1b}`, `\r`, …), so that text taken from an input file cannot act on the terminal when a
/// message repeats it.
pub fn escape(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// Byte offset to 1-based (line, column).
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(before.chars().count(), |nl| {
        before[nl + 1..].chars().count()
    }) + 1;
    (line, col)
}

/// Format a float for an output file: shortest representation that reads back to the same value.
/// A non-finite value (a bug upstream: solvers reject them) becomes an empty cell, never `NaN`.
pub fn fmt_f64(v: f64) -> String {
    debug_assert!(v.is_finite(), "non-finite value written to a file");
    let mut out = Vec::with_capacity(24);
    number::push_cell(&mut out, v);
    String::from_utf8(out).expect("digits are ASCII")
}
