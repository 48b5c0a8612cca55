//! `smash flight --diagnose`: which aerodynamic term do the measured flights ask for?

use smash::app::flight::stream::Flown;
use smash::data::launch_read::{read_launches, LaunchRead};
use smash::flight::diagnose::{diagnose, DiagnoseInput, FlightDiagnosis};
use smash::flight::FlightConfig;

use super::measured::{ball_types, fit_flights, measured_flights, sessions};
use super::FlightArgs;

/// Cross-validation folds (fewer when there are fewer sessions).
const FOLDS: usize = 5;

/// Diagnose the model of `cfg` on the file's measured flights (the vendor's modelled flights
/// beside tracked ones left out, [`fit_flights`]), print the ranking (stderr, unless
/// `--json`), and write the flights with the selected terms. Also the notes on what was
/// diagnosed against (printed here).
pub fn diagnose_and_fly(
    args: &FlightArgs,
    cfg: &FlightConfig,
    read: LaunchRead,
) -> anyhow::Result<(Flown, FlightDiagnosis, Vec<String>)> {
    let table = read_launches(&args.shots, read)?;
    let all = measured_flights(&table);
    let every: Vec<usize> = (0..all.len()).collect();
    // Only the rows fitted to are diagnosed on (folds, penalty and counts are theirs); every
    // row is flown with the terms selected.
    let fit = fit_flights(&table, &all, &every, ("", &args.shots, args.strict))?;
    for note in &fit.notes {
        crate::text::print_note("flight", note);
    }
    if fit.rows.is_empty() {
        anyhow::bail!(
            "--diagnose: {} has no {}carry_yd, apex_yd or land_angle_deg to diagnose the flight \
             with",
            args.shots.display(),
            if fit.notes.is_empty() {
                "measured "
            } else {
                "usable (see the note above) "
            }
        );
    }
    let shots: Vec<_> = fit.rows.iter().map(|&i| all[i]).collect();
    let pick = |v: Vec<String>| fit.rows.iter().map(|&i| v[i].clone()).collect::<Vec<_>>();
    let balls = ball_types(&table).map(pick);
    let sessions = sessions(&table).map(|(col, keys)| (col, pick(keys)));
    let d = diagnose(
        cfg,
        DiagnoseInput {
            shots: &shots,
            balls: balls.as_deref(),
            sessions: sessions.as_ref().map(|s| s.1.as_slice()),
            folds: FOLDS,
        },
    )
    .map_err(|e| anyhow::anyhow!("--diagnose: {e}"))?;
    if !args.json {
        let from = match (&sessions, d.folds_by) {
            (Some((col, _)), "session") => format!(" (sessions from column '{col}')"),
            (Some((col, keys)), _) if keys.len() >= 2 && distinct(keys) == keys.len() => {
                format!(" (column '{col}' names a session of its own for every shot)")
            }
            _ => " (no session or date column with two or more sessions)".to_string(),
        };
        eprint!("{}", d.text());
        eprintln!("folds by {}{from}", d.folds_by);
    }
    let results = d.fly(cfg, &table.launches);
    Ok((super::write_flown(args, cfg, table, results)?, d, fit.notes))
}

fn distinct(keys: &[String]) -> usize {
    keys.iter().collect::<std::collections::BTreeSet<_>>().len()
}
