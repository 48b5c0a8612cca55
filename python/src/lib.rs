//! `smash_golf._native`: the compiled half of the Python package. Every function here takes
//! what the `smash` command line takes (a club, a shots table as a path or as CSV text, the
//! command's own options as command-line arguments, parsed by the CLI's own parser) and
//! returns what the command writes (predictions or flight CSV bytes, the `--json` report),
//! computed by the same library calls. The Python half (`python/smash_golf/__init__.py`)
//! turns DataFrames into CSV text and CSV bytes and JSON back into DataFrames and dicts.
//!
//! Numbers survive the CSV round trip bit for bit: the library writes the shortest decimal
//! that reads back to the same `f64`, and the Python half writes with `repr` and reads with
//! pandas' round-trip parser.
//!
//! Long work runs with the GIL released (`Python::detach`) on rayon's threads.

use std::path::{Path, PathBuf};

use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

mod club;
mod commands;
mod progress;

pub use club::Club;

pyo3::create_exception!(
    _native,
    SmashError,
    PyException,
    "An error of smash: the same one-line message as the command line's (file, line, column \
     or key, what was wrong, what is allowed)."
);

/// An error as the command line prints it (without its `error: ` prefix).
pub(crate) fn to_py(e: anyhow::Error) -> PyErr {
    SmashError::new_err(smash_cli::error_chain(&e))
}

/// Where a shots table comes from: a file (read exactly as the CLI reads `--shots`) or CSV text
/// made from a DataFrame, named `label` in messages.
pub(crate) enum Shots {
    File(PathBuf),
    Csv { label: PathBuf, bytes: Vec<u8> },
}

impl Shots {
    fn new(path: Option<PathBuf>, csv: Option<Vec<u8>>, label: Option<String>) -> PyResult<Self> {
        match (path, csv) {
            (Some(p), None) => Ok(Self::File(p)),
            (None, Some(bytes)) => Ok(Self::Csv {
                label: PathBuf::from(label.unwrap_or_else(|| "<DataFrame>".to_owned())),
                bytes,
            }),
            _ => Err(SmashError::new_err(
                "give the shots either as a path or as CSV text, not both or neither",
            )),
        }
    }

    /// The name of the shots in messages and on the command line.
    pub(crate) fn label(&self) -> &Path {
        match self {
            Self::File(p) => p,
            Self::Csv { label, .. } => label,
        }
    }

    /// The shot table, read as the CLI reads `--shots` with `format` (CSV text is a shots
    /// file; an export must be a path).
    pub(crate) fn read(
        &self,
        format: &smash_cli::ShotsFormatArgs,
    ) -> anyhow::Result<smash::data::shots::ShotTable> {
        match self {
            Self::File(p) => format.read(p),
            Self::Csv { label, bytes } => match format.format.as_deref() {
                None | Some("shots") => Ok(smash::data::shots::parse_shots(label, &bytes[..])?),
                Some(f) => anyhow::bail!(
                    "format '{f}': a launch-monitor export is read from its file; give its path \
                     (or convert it first with read_export)"
                ),
            },
        }
    }
}

/// Parse a command line of `smash` (`args` without the program name) with the CLI's parser;
/// a usage error becomes its first line, as the CLI prints it.
pub(crate) fn parse_cli(args: Vec<String>) -> anyhow::Result<smash_cli::Command> {
    use clap::Parser;
    let argv = std::iter::once("smash".to_owned()).chain(args);
    match smash_cli::Cli::try_parse_from(argv) {
        Ok(cli) => Ok(cli.command),
        Err(e) => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("invalid arguments");
            anyhow::bail!("{}", first.trim_start_matches("error: ").to_owned())
        }
    }
}

/// Read and register user-defined effects (`[[define_effect]]` tables) from a TOML file, as
/// `--effect-defs` does; afterwards clubs, effect lists and studies may name them.
#[pyfunction]
fn load_effect_defs(path: PathBuf) -> PyResult<Vec<String>> {
    smash::data::effect_defs::read_effect_defs(&path)
        .map(|defs| defs.iter().map(|d| d.name.to_owned()).collect())
        .map_err(|e| to_py(e.into()))
}

/// The effect library: name and parameters (key, unit, neutral value, physical bounds).
#[pyfunction]
fn effect_library(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for kind in smash::effects::EffectKind::ALL {
        let id: smash::effects::EffectId = kind.into();
        let d = PyDict::new(py);
        d.set_item("name", id.name())?;
        d.set_item("params", club::param_specs(py, id)?)?;
        out.append(d)?;
    }
    Ok(out)
}

/// Bytes for Python.
pub(crate) fn bytes(py: Python<'_>, b: &[u8]) -> Py<PyBytes> {
    PyBytes::new(py, b).unbind()
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The CLI's worker threads (their stack holds the unoptimised face-map kernel); fails only
    // if a pool was already installed.
    let _ = smash_cli::thread_pool().build_global();
    m.add("SmashError", m.py().get_type::<SmashError>())?;
    m.add_class::<Club>()?;
    m.add_function(wrap_pyfunction!(load_effect_defs, m)?)?;
    m.add_function(wrap_pyfunction!(effect_library, m)?)?;
    commands::register(m)?;
    Ok(())
}
