//! The fits stay on the lanes: in a diagnose over every library effect (each one fitted as a
//! candidate, `shaft_fraction` among them, and those searched only when named) the lanes refuse no evaluation for want of a lane
//! form (`smash::fit::scalar_path_counts`), and neither do they in a calibration with
//! user-defined effects of every kind the lanes take. (Shots the lanes cannot compute at a
//! trial parameter value, off the face say, still go one at a time so that the first is named;
//! they are counted and printed, not refused.) A count, not a time: it
//! cannot flake on a busy machine, and it fails the day an effect's law leaves the lanes.
//!
//! One test binary of its own: the counts are process-wide, so no other test may run beside it.

#[path = "../benches/support/worlds.rs"]
mod worlds;

use std::path::Path;

use smash::data::effect_defs::read_effect_defs;
use smash::diagnose::{default_candidates_without, diagnose, DiagnoseOptions, OPT_IN_CANDIDATES};
use smash::effects::EffectKind;
use smash::fit::{
    calibrate, parse_effect_list, scalar_path_counts, CalibrateOptions, EffectRequest,
};

#[test]
fn fits_never_leave_the_lanes() {
    let club = worlds::paper_club();
    let shots = worlds::paper_world(20);
    let before = scalar_path_counts();
    // The default candidates and those searched only when named (`OPT_IN_CANDIDATES`).
    let mut candidates = default_candidates_without(&shots, &[]).expect("defaults");
    candidates.extend(
        OPT_IN_CANDIDATES
            .iter()
            .map(|&k| EffectRequest::Global(k.into())),
    );
    let opts = DiagnoseOptions {
        max_steps: 3,
        max_iters: 30,
        candidates: Some(candidates),
        ..DiagnoseOptions::default()
    };
    let d = diagnose(&club, &shots, &opts, None).expect("diagnose runs");
    // Every library effect was a candidate and fitted.
    let tried: Vec<&str> = d.steps[0]
        .candidates
        .iter()
        .map(|c| c.label.as_str())
        .collect();
    for kind in EffectKind::ALL {
        assert!(
            tried.iter().any(|t| t.starts_with(kind.name())),
            "{} was not fitted: {tried:?}",
            kind.name()
        );
    }
    let after = scalar_path_counts();
    assert_eq!(
        after.refusals, before.refusals,
        "a library effect has no lane form"
    );
    eprintln!(
        "shots the lanes could not compute: {}",
        after.shots - before.shots
    );

    // User-defined effects: a COR law, a mass law reading the shaft mass, a CoM shift reading
    // the impact location and a friction law, fitted together.
    let defs = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/lane_path_effects.toml");
    read_effect_defs(&defs).expect("definitions read");
    let effects = parse_effect_list("my_cor_power,my_shaft_mass,my_com_shift,my_friction")
        .expect("effects parse");
    let cal = calibrate(&club, &shots, &effects, &CalibrateOptions::default(), None).expect("fits");
    assert!(cal.chi2.is_finite());
    assert_eq!(
        scalar_path_counts(),
        before,
        "user-defined effects left the lanes"
    );
}
