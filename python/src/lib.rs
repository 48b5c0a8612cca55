//! `smash_golf._native`: the compiled half of the Python package. Every function binds a
//! command of the library's application layer ([`smash::app`]): its settings come from a dict
//! of keyword arguments (deserialised into the command's settings type, so an option has one
//! name and one check), the shots from a path or from CSV text, and it returns the command's
//! report as Python objects (the report's serde form), with the predictions or flight tables as
//! CSV bytes. The Python half (`python/smash_golf/__init__.py`) turns DataFrames into CSV text
//! and those bytes back into DataFrames.
//!
//! Numbers survive the CSV round trip bit for bit: the library writes the shortest decimal
//! that reads back to the same `f64`, and the Python half writes with `repr` and reads with
//! pandas' round-trip parser.
//!
//! Long work runs with the GIL released (`Python::detach`) on rayon's threads.

use std::path::PathBuf;

use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

mod club;
mod commands;
mod progress;

pub use club::Club;
use smash::app::inputs::ShotsInput;

pyo3::create_exception!(
    _native,
    SmashError,
    PyException,
    "An error of smash: the same one-line message as the command line's (file, line, column \
     or key, what was wrong, what is allowed)."
);

/// An error as the command line prints it (without its `error: ` prefix).
pub(crate) fn to_py(e: anyhow::Error) -> PyErr {
    SmashError::new_err(smash::app::error_chain(&e))
}

/// Where a shots table comes from: a file (read exactly as the CLI reads `--shots`) or CSV text
/// made from a DataFrame, named `label` in messages.
pub(crate) fn shots_input(
    path: Option<PathBuf>,
    csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<ShotsInput> {
    match (path, csv) {
        (Some(p), None) => Ok(ShotsInput::File(p)),
        (None, Some(bytes)) => Ok(ShotsInput::Csv {
            label: PathBuf::from(label.unwrap_or_else(|| "<DataFrame>".to_owned())),
            bytes,
        }),
        _ => Err(SmashError::new_err(
            "give the shots either as a path or as CSV text, not both or neither",
        )),
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
    let _ = smash::app::thread_pool().build_global();
    m.add("SmashError", m.py().get_type::<SmashError>())?;
    m.add_class::<Club>()?;
    m.add_function(wrap_pyfunction!(load_effect_defs, m)?)?;
    m.add_function(wrap_pyfunction!(effect_library, m)?)?;
    commands::register(m)?;
    Ok(())
}
