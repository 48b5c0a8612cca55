//! Degenerate data, named before any fit: shots that cannot tell one effect from another.
//!
//! A fit explains how the launch changes with the delivery. Shots whose deliveries are all the
//! same leave nothing to explain: every effect then amounts to the same constant offset of the
//! five launch components, any of them fits "perfectly", the robust noise scale of the errors
//! is zero and a cross-validated χ² divides by it (60 identical shots once gave a χ² of 2.5e30
//! and selected a 17.7 mm CoM offset). Some effects also need one variable to vary: a COR
//! slope against approach speed needs different club speeds, a COR falloff from the face
//! centre needs different impact locations. [`check_variation`] finds these cases so
//! `calibrate` and `diagnose` can say so instead of reporting a fit.

use crate::effects::{EffectKind, Needs};
use crate::model::{DeliveryVar, Shot};

use super::{EffectRequest, FitError};

fn varies(shots: &[Shot], v: DeliveryVar) -> bool {
    let first = v.file_value(&shots[0].delivery);
    shots.iter().any(|s| v.file_value(&s.delivery) != first)
}

/// The delivery variables an effect's parameters are slopes against (`NEEDS` in the effect's
/// file): without variation in at least one of them the effect is a constant offset,
/// indistinguishable from others.
fn needs(kind: EffectKind) -> Option<(&'static [DeliveryVar], &'static str)> {
    match kind.needs() {
        Needs::AnyOf(vars, why) => Some((vars, why)),
        Needs::Nothing(_) => None,
    }
}

/// Check that `shots` can identify the effects `requests` (parameters counted over the groups
/// present). Whole-data degeneracy (no measurements, identical deliveries, identical
/// measurements, fewer shots than parameters) is an error; requests the data cannot identify (more parameters than shots, or a
/// variable they need is constant) are returned, each with the reason, for the caller to refuse or leave out.
pub fn check_variation(
    shots: &[Shot],
    requests: &[EffectRequest],
) -> Result<Vec<(EffectRequest, String)>, FitError> {
    let n = shots.len();
    if n < 2 {
        return Err(FitError::Degenerate(format!(
            "{n} shot: a fit needs shots that differ, and at least one more than its parameters"
        )));
    }
    if !DeliveryVar::ALL.into_iter().any(|v| varies(shots, v)) {
        return Err(FitError::Degenerate(format!(
            "all {n} shots have the same delivery (club speed, angles, spin and impact \
             location): nothing varies for a model to explain, so no effect can be told from \
             another; use shots whose deliveries differ"
        )));
    }
    let groups = super::data::distinct_groups(shots);
    let mut out = Vec::new();
    for r in requests {
        let params: usize = r
            .expand(&groups)
            .map(|fs| fs.iter().map(|f| f.kind.params().len()).sum())
            .unwrap_or(0);
        if params >= n {
            out.push((
                r.clone(),
                format!(
                    "{} has {params} parameter(s) but there are only {n} shots",
                    r.label()
                ),
            ));
            continue;
        }
        if let Some((vars, why)) = r.kind().library().and_then(needs) {
            if !vars.iter().any(|v| varies(shots, *v)) {
                let values: Vec<String> = vars
                    .iter()
                    .map(|v| format!("{} = {}", v.column(), v.file_value(&shots[0].delivery)))
                    .collect();
                out.push((
                    r.clone(),
                    format!(
                        "{}: {why}, but {} in every shot",
                        r.label(),
                        values.join(", ")
                    ),
                ));
            }
        }
    }
    Ok(out)
}
