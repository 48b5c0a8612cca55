//! `smash flight --diagnose`: which aerodynamic term do the measured flights ask for?

use smash::app::flight::stream::Flown;
use smash::data::launch_read::{read_launches, LaunchRead};
use smash::flight::diagnose::{diagnose, DiagnoseInput, FlightDiagnosis};
use smash::flight::FlightConfig;

use super::measured::{ball_types, fit_flights, sessions};
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
    let fit = fit_flights(&table);
    for note in &fit.notes {
        crate::text::print_note("flight", note);
    }
    let shots = fit.shots;
    if !shots
        .iter()
        .any(|s| s.carry_m.is_some() || s.apex_m.is_some() || s.land_angle_rad.is_some())
    {
        anyhow::bail!(
            "--diagnose: {} has no measured carry_yd, apex_yd or land_angle_deg to diagnose \
             the flight with",
            args.shots.display()
        );
    }
    let balls = ball_types(&table);
    let sessions = sessions(&table);
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
