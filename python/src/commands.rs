//! The commands: each parses its options with the CLI's parser (so every option is checked and
//! refused with the CLI's message), then runs what the CLI's command runs, with the GIL
//! released, and returns what the command prints or writes.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyBytes;

use smash::cancel::Cancel;
use smash::data::shots::ShotTable;
use smash_cli::Command;

use crate::progress::PyProgress;
use crate::{bytes, parse_cli, to_py, Club, Shots};

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

/// The command line `smash SUB --club CLUB --shots SHOTS EXTRA… ARGS…` (club and shots by their
/// names: the files are not read again).
fn argv(
    sub: &str,
    club: Option<&Club>,
    shots: &Shots,
    extra: &[&str],
    args: Vec<String>,
) -> Vec<String> {
    let mut v = vec![sub.to_owned()];
    if let Some(c) = club {
        v.push("--club".into());
        v.push(c.label.display().to_string());
    }
    v.push("--shots".into());
    v.push(shots.label().display().to_string());
    v.extend(extra.iter().map(|s| (*s).to_owned()));
    v.extend(args);
    v
}

/// The shots table and the CLI's warning about groups without effects (if any).
fn table_and_warnings(
    club: &Club,
    shots: &Shots,
    format: &smash_cli::ShotsFormatArgs,
    fit: bool,
) -> anyhow::Result<(
    ShotTable,
    Vec<String>,
    smash::conventions::ConventionSummary,
)> {
    let mut table = shots.read(format)?;
    // Rows a DataFrame's reader left out (an empty or NaN delivery cell), which the CLI names
    // on stderr: a warning each reason (a path's reader has printed them already).
    let left_out: Vec<String> = match shots {
        Shots::Csv { .. } => table
            .left_out_notes()
            .into_iter()
            .map(|n| format!("shots: {n}"))
            .collect(),
        Shots::File(_) => Vec::new(),
    };
    // As the CLI: each shot in the model's own delivery convention, converted once (`fit`:
    // shots whose face angle the monitor derived from the launch are left out).
    let conventions = smash_cli::to_model_convention(&club.spec, &mut table, false, fit)?;
    let warnings = left_out
        .into_iter()
        .chain(conventions.lines())
        .chain(smash_cli::groups_without_effects(
            &club.label,
            &club.spec,
            &table.shots,
        ))
        .collect();
    Ok((table, warnings, conventions))
}

/// `smash predict --shots … --out …`: the predictions file's bytes, warnings, and the line of
/// the input where each predicted shot's row starts (1-based, the header on line 1), so that
/// the caller can give each prediction its input row's index when the reader left rows out.
#[pyfunction]
#[pyo3(signature = (club, args, shots_path = None, shots_csv = None, label = None))]
fn predict(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    args: Vec<String>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<(Py<PyBytes>, Vec<String>, Vec<usize>)> {
    let shots = Shots::new(shots_path, shots_csv, label)?;
    let club: &Club = &club;
    let (csv, warnings, lines) = py
        .detach(|| -> anyhow::Result<_> {
            let Command::Predict(a) = parse_cli(argv(
                "predict",
                Some(club),
                &shots,
                &["--out", "<memory>"],
                args,
            ))?
            else {
                unreachable!("parsed as predict")
            };
            let (table, warnings, _) = table_and_warnings(club, &shots, &a.shots_format, false)?;
            let outcomes = smash_cli::predict::predict_checked(
                &club.label,
                &club.spec,
                shots.label(),
                &table,
            )?;
            Ok((
                smash::data::predictions::predictions_csv(&table, &outcomes),
                warnings,
                table.lines.clone(),
            ))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), warnings, lines))
}

/// `smash flight --shots … --out …`: the flight file's bytes.
#[pyfunction]
#[pyo3(signature = (args, shots_path = None, shots_csv = None, label = None))]
fn flight(
    py: Python<'_>,
    args: Vec<String>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<Py<PyBytes>> {
    use smash::data::flight_files::LaunchSource;
    let shots = Shots::new(shots_path, shots_csv, label)?;
    let csv = py
        .detach(|| -> anyhow::Result<Vec<u8>> {
            let Command::Flight(a) =
                parse_cli(argv("flight", None, &shots, &["--out", "<memory>"], args))?
            else {
                unreachable!("parsed as flight")
            };
            let cfg = a.flight.config()?;
            let source = a.launch.as_deref().map(|s| match s {
                "predicted" => LaunchSource::Predicted,
                _ => LaunchSource::Measured,
            });
            let text;
            let input: &[u8] = match &shots {
                Shots::File(p) => {
                    smash::data::safe_write::note_input(p);
                    text = smash::data::read_text(p)?;
                    text.as_bytes()
                }
                Shots::Csv { bytes, .. } => bytes,
            };
            let (csv, _) = smash::data::flight_stream::fly_csv_bytes(
                shots.label(),
                input,
                &cfg,
                smash::data::launch_read::LaunchRead {
                    source,
                    ..Default::default()
                },
            )?;
            Ok(csv)
        })
        .map_err(to_py)?;
    Ok(bytes(py, &csv))
}

/// `smash compare --json`: the JSON report, the text report and warnings.
#[pyfunction]
#[pyo3(signature = (club, args, shots_path = None, shots_csv = None, label = None))]
fn compare(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    args: Vec<String>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
) -> PyResult<(String, String, Vec<String>)> {
    let shots = Shots::new(shots_path, shots_csv, label)?;
    let club: &Club = &club;
    py.detach(|| -> anyhow::Result<_> {
        let Command::Compare(a) =
            parse_cli(argv("compare", Some(club), &shots, &["--json"], args))?
        else {
            unreachable!("parsed as compare")
        };
        smash_cli::compare::check_options(&a)?;
        let (table, warnings, conventions) =
            table_and_warnings(club, &shots, &a.inputs.shots_format, false)?;
        let (mut report, _) = smash_cli::compare::compute(&a, &club.spec, &table)?;
        if conventions.derived_face > 0 {
            smash::conventions::drop_derived_findings(&mut report.findings);
        }
        let title = format!(
            "{} vs {} ({})",
            club.spec.name,
            shots.label().display(),
            smash_cli::counted(table.groups().len(), "group")
        );
        Ok((
            smash::report::compare::compare_json(&report),
            smash_cli::compare::text(&report, &title, false),
            warnings,
        ))
    })
    .map_err(to_py)
}

/// `smash calibrate --json`: the JSON report, the calibrated club and warnings. `progress`
/// (optional) receives the solver's iterations.
#[pyfunction]
#[pyo3(signature = (club, args, shots_path = None, shots_csv = None, label = None, progress = None))]
fn calibrate(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    args: Vec<String>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, Club, Vec<String>)> {
    let shots = Shots::new(shots_path, shots_csv, label)?;
    let club: &Club = &club;
    let progress = progress.map(|p| Arc::new(PyProgress(p, None)) as Arc<dyn smash::fit::Progress>);
    let (json, spec, warnings) = py
        .detach(|| -> anyhow::Result<_> {
            let Command::Calibrate(a) =
                parse_cli(argv("calibrate", Some(club), &shots, &["--json"], args))?
            else {
                unreachable!("parsed as calibrate")
            };
            let (table, warnings, _) =
                table_and_warnings(club, &shots, &a.inputs.shots_format, true)?;
            // As `smash calibrate`: shots of another club are refused (or, with the flag,
            // reported with the mismatch) before anything is fitted.
            let mismatch = a.inputs.club_check.check(
                &a.inputs.club,
                &club.spec,
                &a.inputs.shots,
                &table.shots,
            )?;
            let report = smash_cli::calibrate::compute(&a, &club.spec, &table, mismatch, progress)?;
            let json = serde_json::to_string_pretty(&report)?;
            Ok((json, report.calibration.club, warnings))
        })
        .map_err(to_py)?;
    let calibrated = Club {
        spec,
        label: club.label.clone(),
    };
    Ok((json, calibrated, warnings))
}

/// `smash diagnose --json`: the JSON report, the club with the selected effects (what
/// `--out-club` writes) and warnings (the CLI's `warning:` lines). `progress` (optional)
/// receives the steps and finished fits.
#[pyfunction]
#[pyo3(signature = (club, args, shots_path = None, shots_csv = None, label = None, progress = None))]
fn diagnose(
    py: Python<'_>,
    club: PyRef<'_, Club>,
    args: Vec<String>,
    shots_path: Option<PathBuf>,
    shots_csv: Option<Vec<u8>>,
    label: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, Club, Vec<String>)> {
    let shots = Shots::new(shots_path, shots_csv, label)?;
    let club: &Club = &club;
    // The signal poller of `interruptible` is this thread: woken after every job.
    let progress = progress.map(|p| PyProgress(p, Some(std::thread::current())));
    let cancel = Cancel::new();
    let (json, spec, warnings) = interruptible(py, &cancel, || -> anyhow::Result<_> {
        let Command::Diagnose(a) =
            parse_cli(argv("diagnose", Some(club), &shots, &["--json"], args))?
        else {
            unreachable!("parsed as diagnose")
        };
        let (table, mut warnings, _) =
            table_and_warnings(club, &shots, &a.inputs.shots_format, true)?;
        let p = progress
            .as_ref()
            .map(|p| p as &dyn smash::diagnose::DiagnoseProgress);
        let report =
            smash_cli::diagnose::compute_cancellable(&a, &club.spec, &table, p, Some(&cancel))?;
        warnings.extend(report.diagnosis.warnings.iter().cloned());
        let json = serde_json::to_string_pretty(&report)?;
        Ok((json, report.diagnosis.club, warnings))
    })?;
    let selected = Club {
        spec,
        label: club.label.clone(),
    };
    Ok((json, selected, warnings))
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
                .stack_size(smash_cli::WORKER_STACK_BYTES)
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

/// `smash import`: the shots file's bytes converted from the export at `path` with `format`
/// (a preset or a mapping file), and the import's notes (skipped rows, assumed units).
#[pyfunction]
#[pyo3(signature = (path, format, impact_offset_positive = None, ignore_unknown_columns = false))]
fn read_export(
    py: Python<'_>,
    path: PathBuf,
    format: String,
    impact_offset_positive: Option<String>,
    ignore_unknown_columns: bool,
) -> PyResult<(Py<PyBytes>, Vec<String>)> {
    let (csv, notes) = py
        .detach(|| -> anyhow::Result<_> {
            let mut v = vec![
                "import".to_owned(),
                path.display().to_string(),
                "--out".into(),
                "<memory>".into(),
                "--format".into(),
                format,
            ];
            if let Some(side) = impact_offset_positive {
                v.extend(["--impact-offset-positive".to_owned(), side]);
            }
            if ignore_unknown_columns {
                v.push("--ignore-unknown-columns".into());
            }
            let Command::Import(a) = parse_cli(v)? else {
                unreachable!("parsed as import")
            };
            let format = a.format.format.as_deref().unwrap_or_default();
            if format == "shots" {
                anyhow::bail!(
                    "format 'shots': `shots` is the shots-file format itself, so there is \
                     nothing to convert; give the export's format: a preset (trackman, \
                     flightscope, foresight, uneekor, garmin-r10, rapsodo, skytrak, gspro) or a \
                     mapping file NAME.toml"
                );
            }
            let mapping = smash::data::import::load_mapping(format)?;
            let bytes = std::fs::read(&a.input)
                .map_err(|e| smash::data::DataError::file(&a.input, format!("cannot read: {e}")))?;
            let opts = smash::data::import::ImportOptions {
                impact_offset_positive: a.format.impact_offset_positive.map(Into::into),
                ignore_unknown_columns: a.format.ignore_unknown_columns,
                strict: a.format.strict,
            };
            let imported = smash::data::import::import(&a.input, &bytes, &mapping, &opts)?;
            imported.checked_read_back(&a.input, a.format.strict)?;
            let notes = imported
                .notes
                .iter()
                .map(|n| format!("import ({}): {n}", mapping.export.name))
                .collect::<Vec<_>>();
            Ok((imported.csv, notes))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), notes))
}

/// `smash run STUDY --out DIR ARGS…`: the study's files written to `out` (the Python half
/// reads them back into DataFrames). The CLI's summary goes to the process's standard output.
#[pyfunction]
fn run_study(py: Python<'_>, study: PathBuf, out: PathBuf, args: Vec<String>) -> PyResult<()> {
    py.detach(|| -> anyhow::Result<()> {
        let mut v = vec![
            "run".to_owned(),
            study.display().to_string(),
            "--out".into(),
            out.display().to_string(),
        ];
        v.extend(args);
        let Command::Run(a) = parse_cli(v)? else {
            unreachable!("parsed as run")
        };
        smash_cli::run::run(a)
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
            let (cfg, run) = smash_cli::synth::generate_world(&config, seed)?;
            let truth = smash::synth::files::truth_toml(&cfg, &run, &config.display().to_string());
            Ok((smash::synth::files::synth_shots_csv(&run), truth))
        })
        .map_err(to_py)?;
    Ok((bytes(py, &csv), truth))
}
