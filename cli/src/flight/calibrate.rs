//! `smash flight --calibrate TERMS [--calibrate-by ball|session]`: scalings of the model's
//! drag, lift and spin decay fitted to the measured flights, for all shots or per ball or
//! session, then the shots flown with them.

use smash::app::flight::stream::Flown;
use smash::data::launch_read::{read_launches, LaunchRead};
use smash::flight::calibrate::{calibrate, Calibration, MeasuredFlight, Term};
use smash::flight::{Flight, FlightConfig, FlightError};
use smash::report::flight::{CalibratedPart, CalibratedTerm};

use super::measured::{ball_types, fit_flights, measured_flights, sessions};
use super::FlightArgs;

/// Fit the scalings of `names` to the file's measured flights (per part with
/// `--calibrate-by`; the vendor's modelled flights beside tracked ones left out,
/// [`fit_flights`]), report them on stderr, and write the flights of the calibrated model(s).
/// Also the notes on what was fitted to (printed here) and each part's scalings.
pub fn calibrate_and_fly(
    args: &FlightArgs,
    cfg: &FlightConfig,
    read: LaunchRead,
    names: &str,
) -> anyhow::Result<(Flown, Vec<String>, Vec<CalibratedPart>)> {
    let terms = names
        .split(',')
        .map(|n| Term::from_name(n.trim()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| anyhow::anyhow!("--calibrate: {e}"))?;
    let table = read_launches(&args.shots, read)?;
    let shots = measured_flights(&table);
    let parts = match args.calibrate_by.as_deref() {
        None => vec![(None, (0..shots.len()).collect())],
        Some(by) => parts_by(by, &table, &args.shots)?,
    };
    let mut results: Vec<Option<Result<Flight, FlightError>>> =
        (0..shots.len()).map(|_| None).collect();
    let (mut notes, mut fitted) = (Vec::new(), Vec::new());
    for (key, idx) in parts {
        let what = key
            .as_deref()
            .map_or(String::new(), |k| format!(" for {k}"));
        // Which of the part's flights are fitted to (the vendor's modelled ones beside tracked
        // ones are not), decided part by part.
        let fit = fit_flights(&table, &shots, &idx, (&what, &args.shots, args.strict))?;
        for note in &fit.notes {
            crate::text::print_note("flight", note);
        }
        notes.extend(fit.notes);
        let part: Vec<MeasuredFlight> = fit.rows.iter().map(|&i| shots[i]).collect();
        let cal =
            calibrate(cfg, &part, &terms).map_err(|e| anyhow::anyhow!("--calibrate{what}: {e}"))?;
        eprintln!(
            "{}",
            crate::text::wrap_long(&calibration_line(cfg, &what, &cal, fit.all_modelled))
        );
        fitted.push(CalibratedPart::new(key.clone(), &cal, fit.all_modelled));
        let launches: Vec<_> = idx.iter().map(|&i| table.launches[i]).collect();
        let flown = smash::flight::integrate::fly_with(cfg, &cal.model(&cfg.aero), &launches);
        for (&i, f) in idx.iter().zip(flown) {
            results[i] = Some(f);
        }
    }
    let results = results
        .into_iter()
        .map(|r| r.expect("every shot is in one part"))
        .collect();
    Ok((
        super::write_flown(args, cfg, table, results)?,
        notes,
        fitted,
    ))
}

/// "calibrated fmm2022 for ball_type 'range' on 90 measured value(s): drag x1.0800 ± 0.0011
/// (weighted RMS residual 3.210 -> 0.000)"; "value(s) of the vendor's flight model" when every
/// one is (`modelled`).
fn calibration_line(cfg: &FlightConfig, what: &str, cal: &Calibration, modelled: bool) -> String {
    let scales: Vec<String> = CalibratedPart::new(None, cal, modelled)
        .terms
        .iter()
        .map(CalibratedTerm::text)
        .collect();
    format!(
        "calibrated {}{what} on {} {}: {} (weighted RMS residual {:.3} -> {:.3})",
        cfg.aero.name(),
        cal.residuals,
        if modelled {
            "value(s) of the vendor's flight model (flight_modelled = 1)"
        } else {
            "measured value(s)"
        },
        scales.join(", "),
        cal.rms_before,
        cal.rms_after
    )
}

/// The shots' parts by ball or session, in the order each first appears: a label such as
/// `ball_type 'range'` and the indices of its shots.
type Parts = Vec<(Option<String>, Vec<usize>)>;

fn parts_by(
    by: &str,
    table: &smash::data::flight_files::LaunchTable,
    path: &std::path::Path,
) -> anyhow::Result<Parts> {
    let (column, keys) = match by {
        "ball" => ("ball_type".to_string(), ball_types(table)),
        _ => match sessions(table) {
            Some((column, keys)) => (column, Some(keys)),
            None => (String::new(), None),
        },
    };
    let Some(keys) = keys else {
        anyhow::bail!(
            "--calibrate-by {by}: {} has no {} naming every shot's {by}",
            path.display(),
            if by == "ball" {
                "ball_type column"
            } else {
                "session, date, datetime, date_time or timestamp column"
            }
        );
    };
    let mut parts: Parts = Vec::new();
    for (i, k) in keys.iter().enumerate() {
        let label = format!("{column} '{k}'");
        match parts
            .iter_mut()
            .find(|(l, _)| l.as_deref() == Some(label.as_str()))
        {
            Some((_, idx)) => idx.push(i),
            None => parts.push((Some(label), vec![i])),
        }
    }
    let single: Vec<&str> = parts
        .iter()
        .filter(|(_, idx)| idx.len() < MIN_SHOTS_PER_PART)
        .filter_map(|(l, _)| l.as_deref())
        .collect();
    if let Some(first) = single.first() {
        anyhow::bail!(
            "--calibrate-by {by}: {} of the {} {by}s hold a single shot (the first: {first}); \
             a scaling fitted to one shot fits that shot's own errors (its carry, apex and land \
             angle set up to three scalings exactly): each {by} needs at least \
             {MIN_SHOTS_PER_PART} shots, or leave out --calibrate-by to fit all shots together",
            single.len(),
            parts.len()
        );
    }
    Ok(parts)
}

/// Fewest shots a part of `--calibrate-by` is fitted on: one shot's three measured values
/// (carry, apex, land angle) are matched exactly by up to three scalings, so its fit says
/// nothing of the ball or the session, only of that shot's errors.
const MIN_SHOTS_PER_PART: usize = 2;
