//! The commands: each fills its settings type from the keyword arguments' dict (an unknown
//! value is refused with the setting's name), runs the library's command ([`smash::app`]) with
//! the GIL released, and returns its report as Python objects.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyFloat, PyList};
use serde::de::DeserializeOwned;
use serde::Serialize;

use smash::app::inputs::NamedClub;
use smash::app::{self, CollectedNotes};
use smash::cancel::Cancel;

use crate::progress::PyProgress;
use crate::{bytes, shots_input, to_py, Club, SmashError};

/// Register the commands in the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_function(wrap_pyfunction!(flight, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(read_export, m)?)?;
    m.add_function(wrap_pyfunction!(run_study, m)?)?;
    m.add_function(wrap_pyfunction!(synth, m)?)?;
    Ok(())
}

/// A command's settings from the keyword arguments' dict (`None`: the defaults).
fn settings<T: DeserializeOwned + Default>(dict: Option<&Bound<'_, PyDict>>) -> PyResult<T> {
    match dict {
        None => Ok(T::default()),
        Some(d) => pythonize::depythonize(d.as_any())
            .map_err(|e| SmashError::new_err(format!("invalid setting: {e}"))),
    }
}

/// A report as Python objects: its serde form with the keys in the order its `--json` prints
/// them, lists, dicts, numbers and strings; a number that is not finite is `None`, as in the
/// JSON.
fn to_python<T: Serialize>(py: Python<'_>, report: &T) -> PyResult<Py<PyAny>> {
    let obj = pythonize::pythonize(py, report).map_err(|e| SmashError::new_err(e.to_string()))?;
    Ok(finite_or_none(obj)?.unbind())
}

/// `obj` with every float that is not finite, at any depth of its dicts and lists, made `None`.
fn finite_or_none(obj: Bound<'_, PyAny>) -> PyResult<Bound<'_, PyAny>> {
    let py = obj.py();
    if let Ok(f) = obj.cast::<PyFloat>() {
        return Ok(if f.value().is_finite() {
            obj
        } else {
            py.None().into_bound(py)
        });
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let items: Vec<_> = d.iter().collect();
        for (k, v) in items {
            d.set_item(k, finite_or_none(v)?)?;
        }
    } else if let Ok(l) = obj.cast::<PyList>() {
        for i in 0..l.len() {
            l.set_item(i, finite_or_none(l.get_item(i)?)?)?;
        }
    }
    Ok(obj)
}

fn named(club: &Club) -> NamedClub<'_> {
    NamedClub {
        spec: &club.spec,
        path: &club.label,
    }
}

/// `smash predict --shots … --out …`: the predictions file's bytes, warnings, and the line of
/// the input where each predicted shot's row starts (1-based, the header on line 1), so that
/// the caller can give each prediction its input row's index when the reader left rows out.
#[pyfunction]
#[pyo3(signature = (club, settings = None, shots_path = None, shots_csv = None, label = None))]
fn predict(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    settings: Option<&Bound<'_, PyDict>>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<(Py<PyBytes>, Vec<String>, Vec<usize>)> {
    let input = shots_input(shots_path, shots_csv, label)?;
    let s: app::predict::PredictSettings = self::settings(settings)?;
    let club: &Club = &club;
    let (csv, warnings, lines) = py
        .detach(|| -> anyhow::Result<_> {
            let mut notes = CollectedNotes::default();
            let p = app::predict::run(&s, named(club), &input, &mut notes)?;
            Ok((p.csv, notes.0, p.table.lines))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), warnings, lines))
}

/// `smash flight --shots … --out …`: the flight file's bytes.
#[pyfunction]
#[pyo3(signature = (settings = None, shots_path = None, shots_csv = None, label = None))]
fn flight(
    py: Python<'_>,
    settings: Option<&Bound<'_, PyDict>>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<Py<PyBytes>> {
    let input = shots_input(shots_path, shots_csv, label)?;
    let s: app::flight::FlyTableSettings = self::settings(settings)?;
    let csv = py
        .detach(|| app::flight::fly_input(&s, &input))
        .map_err(to_py)?;
    Ok(bytes(py, &csv))
}

/// `smash compare --json`: the report, the text report and warnings.
#[pyfunction]
#[pyo3(signature = (club, settings = None, shots_path = None, shots_csv = None, label = None))]
fn compare(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    settings: Option<&Bound<'_, PyDict>>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<(Py<PyAny>, String, Vec<String>)> {
    let input = shots_input(shots_path, shots_csv, label)?;
    let s: app::compare::CompareSettings = self::settings(settings)?;
    let club: &Club = &club;
    let (report, text, warnings) = py
        .detach(|| -> anyhow::Result<_> {
            let mut notes = CollectedNotes::default();
            let (run, prepared) = app::compare::run(&s, named(club), &input, &mut notes)?;
            let title = app::compare::title(
                &club.spec.name,
                input.label(),
                prepared.table.groups().len(),
            );
            let text = app::compare::text(&run.report, &title, false);
            Ok((run.report, text, notes.0))
        })
        .map_err(to_py)?;
    let report = smash::report::compare::versioned(&report);
    Ok((to_python(py, &report)?, text, warnings))
}

/// `smash calibrate --json`: the report, the calibrated club and warnings. `progress`
/// (optional) receives the solver's iterations.
#[pyfunction]
#[pyo3(signature = (club, settings = None, shots_path = None, shots_csv = None, label = None, progress = None))]
fn calibrate(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    settings: Option<&Bound<'_, PyDict>>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Py<PyAny>, Club, Vec<String>)> {
    let input = shots_input(shots_path, shots_csv, label)?;
    let s: app::calibrate::CalibrateSettings = self::settings(settings)?;
    let club: &Club = &club;
    let progress = progress.map(|p| Arc::new(PyProgress(p, None)) as Arc<dyn smash::fit::Progress>);
    let (report, warnings) = py
        .detach(|| -> anyhow::Result<_> {
            let mut notes = CollectedNotes::default();
            let (report, _) = app::calibrate::run(&s, named(club), &input, &mut notes, progress)?;
            Ok((report, notes.0))
        })
        .map_err(to_py)?;
    let calibrated = Club {
        spec: report.calibration.club.clone(),
        label: club.label.clone(),
    };
    Ok((to_python(py, &report)?, calibrated, warnings))
}

/// `smash diagnose --json`: the report, the club with the selected effects (what `--out-club`
/// writes) and warnings (the CLI's `warning:` lines). `progress` (optional) receives the steps
/// and finished fits.
#[pyfunction]
#[pyo3(signature = (club, settings = None, shots_path = None, shots_csv = None, label = None, progress = None))]
fn diagnose(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    settings: Option<&Bound<'_, PyDict>>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Py<PyAny>, Club, Vec<String>)> {
    let input = shots_input(shots_path, shots_csv, label)?;
    let s: app::diagnose::DiagnoseSettings = self::settings(settings)?;
    let club: &Club = &club;
    // The signal poller of `interruptible` is this thread: woken after every job.
    let progress = progress.map(|p| PyProgress(p, Some(std::thread::current())));
    let cancel = Cancel::new();
    let (report, warnings) = interruptible(py, &cancel, || -> anyhow::Result<_> {
        let mut notes = CollectedNotes::default();
        let p = progress
            .as_ref()
            .map(|p| p as &dyn smash::diagnose::DiagnoseProgress);
        let (report, _) =
            app::diagnose::run(&s, named(club), &input, &mut notes, (p, Some(&cancel)))?;
        let mut warnings = notes.0;
        warnings.extend(report.diagnosis.warnings.iter().cloned());
        Ok((report, warnings))
    })?;
    let selected = Club {
        spec: report.diagnosis.club.clone(),
        label: club.label.clone(),
    };
    Ok((to_python(py, &report)?, selected, warnings))
}

/// How often a command that can be interrupted looks for Python's signals: Ctrl-C takes
/// effect within this, plus the fit running when it came.
const SIGNAL_POLL: std::time::Duration = std::time::Duration::from_millis(50);

/// Run `work` with the GIL released on a thread of its own while this thread looks for
/// Python's signals every [`SIGNAL_POLL`] (`Python::check_signals`: Ctrl-C raises
/// `KeyboardInterrupt` there). On a signal `cancel` is cancelled, the work (which checks it
/// between its fits) is waited for, and the signal's exception is returned; otherwise the
/// work's result, an error as [`SmashError`](crate::SmashError).
fn interruptible<T: Send>(
    py: Python<'_>,
    cancel: &Cancel,
    work: impl FnOnce() -> anyhow::Result<T> + Send,
) -> PyResult<T> {
    py.detach(|| {
        std::thread::scope(|scope| {
            let worker = std::thread::Builder::new()
                .name("smash-interruptible".into())
                .stack_size(app::WORKER_STACK_BYTES)
                .spawn_scoped(scope, work)
                .map_err(|e| to_py(e.into()))?;
            while !worker.is_finished() {
                std::thread::park_timeout(SIGNAL_POLL);
                if let Err(signal) = Python::attach(|py| py.check_signals()) {
                    cancel.cancel();
                    let _ = worker.join();
                    return Err(signal);
                }
            }
            match worker.join() {
                Ok(result) => result.map_err(to_py),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        })
    })
}

/// `smash import`: the shots file's bytes converted from the export at `path` (settings: its
/// `format`, a preset or a mapping file, and how to read it), and the import's notes (skipped
/// rows, assumed units).
#[pyfunction]
#[pyo3(signature = (path, settings = None))]
fn read_export(
    py: Python<'_>,
    path: PathBuf,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<(Py<PyBytes>, Vec<String>)> {
    let s: app::import::ImportSettings = self::settings(settings)?;
    let (csv, notes) = py
        .detach(|| -> anyhow::Result<_> {
            let mut notes = CollectedNotes::default();
            let converted = app::import::run(&s, &path, &mut notes)?;
            Ok((converted.imported.csv, notes.0))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), notes))
}

/// `smash run STUDY --out DIR`: the study's files written to `out` (the Python half reads them
/// back into DataFrames); returns the summary the CLI prints on stdout (the yard part's summary
/// and the closing line go to stderr, as the CLI's).
#[pyfunction]
#[pyo3(signature = (study, out, format = None))]
fn run_study(
    py: Python<'_>,
    study: PathBuf,
    out: PathBuf,
    format: Option<&Bound<'_, PyAny>>,
) -> PyResult<String> {
    let format = match format {
        None => Default::default(),
        Some(f) => pythonize::depythonize(f)
            .map_err(|e| SmashError::new_err(format!("invalid setting: format: {e}")))?,
    };
    let settings = app::study::StudySettings {
        study,
        out: Some(out),
        shard: None,
        format,
        report: None,
    };
    py.detach(|| -> anyhow::Result<String> {
        match app::study::run(&settings, false, &app::study::Quiet)? {
            app::study::StudyRun::Whole {
                report,
                dir,
                n_files,
                yards_summary,
                timing,
            } => {
                if let Some(text) = yards_summary {
                    eprint!("{text}");
                }
                let text = app::study::summary_text(&report, &dir, n_files, false);
                eprint!("{timing}");
                Ok(text)
            }
            app::study::StudyRun::Shard { lines } => Ok(lines),
        }
    })
    .map_err(to_py)
}

/// `smash synth --config CONFIG [--seed N] --out … --truth …`: the shots file's bytes and the
/// truth file's text (the hidden effects and world physics).
#[pyfunction]
#[pyo3(signature = (config, seed = None))]
fn synth(py: Python<'_>, config: PathBuf, seed: Option<u64>) -> PyResult<(Py<PyBytes>, String)> {
    let (csv, truth) = py
        .detach(|| -> anyhow::Result<_> {
            let (cfg, run) = app::synth::generate_world(&config, seed)?;
            let truth = smash::synth::files::truth_toml(&cfg, &run, &config.display().to_string());
            Ok((smash::synth::files::synth_shots_csv(&run), truth))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), truth))
}
