//! The files this process has read as inputs, so that no output is written over one of them
//! ([`crate::data::safe_write`] checks every write against this record). A bottom layer: any
//! module that opens a user's file (the data readers, an aerodynamic table in `flight`) records
//! it here without depending on the writers.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// Canonical form of a path that may not exist yet: its existing ancestor canonicalised, the
/// rest appended.
pub fn canonical(path: &Path) -> PathBuf {
    if let Ok(c) = std::fs::canonicalize(path) {
        return c;
    }
    let abs = if path.is_absolute() {
        path.to_owned()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    let mut tail = Vec::new();
    let mut head = abs.as_path();
    loop {
        if let Ok(c) = std::fs::canonicalize(head) {
            let mut out = c;
            for t in tail.iter().rev() {
                out.push(t);
            }
            return out;
        }
        match (head.file_name(), head.parent()) {
            (Some(name), Some(parent)) => {
                tail.push(name.to_owned());
                head = parent;
            }
            _ => return abs,
        }
    }
}

/// Canonical paths of every file this process has read as an input.
static INPUTS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Record that `path` is an input of this run: no output may then be written over it.
pub fn note_input(path: &Path) {
    let c = canonical(path);
    let mut inputs = INPUTS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if !inputs.contains(&c) {
        inputs.push(c);
    }
}

/// What some inputs are, for messages (`the project file`), by canonical path.
static NAMES: Mutex<Vec<(PathBuf, &'static str)>> = Mutex::new(Vec::new());

/// [`note_input`], with what the file is (`the project file`) for the message that refuses an
/// output over it.
pub fn note_input_named(path: &Path, name: &'static str) {
    note_input(path);
    let c = canonical(path);
    let mut names = NAMES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if !names.iter().any(|(p, _)| *p == c) {
        names.push((c, name));
    }
}

/// What the recorded input at the canonical path `c` is, when [`note_input_named`] said.
pub fn name_of(c: &Path) -> Option<&'static str> {
    NAMES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .iter()
        .find(|(p, _)| p == c)
        .map(|(_, n)| *n)
}

/// The recorded inputs (canonical paths), locked for the caller's look.
pub fn recorded() -> MutexGuard<'static, Vec<PathBuf>> {
    INPUTS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}
