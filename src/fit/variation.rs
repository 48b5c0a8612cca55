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

use crate::effects::EffectKind;
use crate::model::Shot;

use super::{EffectRequest, FitError};

/// A delivery variable by its shots-file column and its value in file units.
type Getter = fn(&Shot) -> f64;

/// The delivery variables a model responds to, file units.
const DELIVERY: [(&str, Getter); 11] = [
    ("club_speed_mph", |s| {
        s.delivery.club_speed_m_s / crate::units::M_S_PER_MPH
    }),
    ("attack_angle_deg", |s| {
        s.delivery.attack_angle_rad.to_degrees()
    }),
    ("club_path_deg", |s| s.delivery.club_path_rad.to_degrees()),
    ("dynamic_loft_deg", |s| {
        s.delivery.dynamic_loft_rad.to_degrees()
    }),
    ("face_angle_deg", |s| s.delivery.face_angle_rad.to_degrees()),
    ("lie_tilt_deg", |s| s.delivery.lie_tilt_rad.to_degrees()),
    ("club_omega_x_rad_s", |s| s.delivery.club_omega_rad_s.x),
    ("club_omega_y_rad_s", |s| s.delivery.club_omega_rad_s.y),
    ("club_omega_z_rad_s", |s| s.delivery.club_omega_rad_s.z),
    ("impact_y_mm", |s| s.delivery.impact_y_m * 1e3),
    ("impact_z_mm", |s| s.delivery.impact_z_m * 1e3),
];

fn varies(shots: &[Shot], get: Getter) -> bool {
    let first = get(&shots[0]);
    shots.iter().any(|s| get(s) != first)
}

fn column(name: &str) -> Getter {
    DELIVERY
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, g)| *g)
        .expect("a delivery column")
}

/// The delivery variables an effect's parameters are slopes against: without variation in
/// at least one of them the effect is a constant offset, indistinguishable from others.
fn needs(kind: EffectKind) -> Option<(&'static [&'static str], &'static str)> {
    match kind {
        EffectKind::CorSpeed => Some((
            &["club_speed_mph"],
            "its COR slope is against approach speed, so the club speed must vary",
        )),
        EffectKind::CorRadial => Some((
            &["impact_y_mm", "impact_z_mm"],
            "its COR falloff is with distance from the face centre, so the impact location \
             must vary",
        )),
        _ => None,
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
    if !DELIVERY.iter().any(|(_, g)| varies(shots, *g)) {
        return Err(FitError::Degenerate(format!(
            "all {n} shots have the same delivery (club speed, angles, spin and impact \
             location): nothing varies for a model to explain, so no effect can be told from \
             another; use shots whose deliveries differ"
        )));
    }
    let mut groups: Vec<String> = shots.iter().map(|s| s.group.clone()).collect();
    groups.sort();
    groups.dedup();
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
            if !vars.iter().any(|v| varies(shots, column(v))) {
                let values: Vec<String> = vars
                    .iter()
                    .map(|v| format!("{v} = {}", column(v)(&shots[0])))
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
