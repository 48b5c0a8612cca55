//! The head parameters `smash infer-club` estimates, each mapped onto a library effect (no
//! physics of its own), with its prior width and the club-file key it is reported under.
//!
//! | club-file key | effect parameter | value in the club file | prior 1σ |
//! |---|---|---|---|
//! | `com_mm[0]`, `com_mm[1]`, `com_mm[2]` | `com_offset.dx_mm`, `dy_mm`, `dz_mm` | start + offset | 6, 3, 3 mm |
//! | `inertia_gcm2[1][1]`, `inertia_gcm2[2][2]` | `inertia_axes.sy`, `sz` | start × factor | 25 % of the start's |
//! | `bulge_mm`, `roll_mm` | `face_curvature.d_bulge_mm`, `d_roll_mm` | start + change (a `face_curvature` effect when roll > bulge, which a club file's fields do not allow) | 130 mm |
//! | `cor` | `cor_level.dcor` | start + change | 0.035 |
//! | `cor_radial.c_per_mm2` | `cor_radial.c_per_mm2` | start's global one + fitted | 1.5e-4 1/mm² |
//! | `loft_bias.deg`, `face_bias.deg` | the same | start's global one + fitted | 3 deg |
//!
//! The widths and their reasons are in `docs/plausible-ranges.md` ("infer-club's prior").

use nalgebra::DVector;

use crate::club::ClubSpec;
use crate::effects::{Effect, EffectId, EffectKind};
use crate::fit::{EffectRequest, FreeEffect, ParamLayout};

/// How a fitted effect value becomes the reported head value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mapping {
    /// Start value + fitted value (same unit).
    Add,
    /// Start value × fitted factor.
    Scale,
}

/// One head parameter: where it sits in the fit vector and how it is reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadParam {
    /// The club file's key (`com_mm[0]`, `inertia_gcm2[1][1]`, `bulge_mm`, `cor`,
    /// `cor_radial.c_per_mm2`, …).
    pub key: &'static str,
    /// In words, for reports.
    pub words: &'static str,
    /// Unit of the reported value.
    pub unit: &'static str,
    /// The effect whose parameter carries it.
    pub effect: EffectKind,
    /// Index of the parameter within the effect.
    pub index: usize,
    /// How the fitted value maps to the reported one.
    pub mapping: Mapping,
    /// Prior 1σ in the effect parameter's own unit (for [`Mapping::Scale`], a fraction).
    pub prior_sd: f64,
}

const fn hp(
    key: &'static str,
    words: &'static str,
    unit: &'static str,
    effect: EffectKind,
    index: usize,
    mapping: Mapping,
    prior_sd: f64,
) -> HeadParam {
    HeadParam {
        key,
        words,
        unit,
        effect,
        index,
        mapping,
        prior_sd,
    }
}

/// The head parameters, in fit order (the order of [`head_layout`]).
pub const HEAD_PARAMS: [HeadParam; 11] = [
    hp(
        "com_mm[0]",
        "CoM depth",
        "mm",
        EffectKind::ComOffset,
        0,
        Mapping::Add,
        6.0,
    ),
    hp(
        "com_mm[1]",
        "CoM height",
        "mm",
        EffectKind::ComOffset,
        1,
        Mapping::Add,
        3.0,
    ),
    hp(
        "com_mm[2]",
        "CoM heel-toe",
        "mm",
        EffectKind::ComOffset,
        2,
        Mapping::Add,
        3.0,
    ),
    hp(
        "inertia_gcm2[1][1]",
        "vertical-axis MOI",
        "g cm2",
        EffectKind::InertiaAxes,
        0,
        Mapping::Scale,
        0.25,
    ),
    hp(
        "inertia_gcm2[2][2]",
        "heel-toe-axis MOI",
        "g cm2",
        EffectKind::InertiaAxes,
        1,
        Mapping::Scale,
        0.25,
    ),
    hp(
        "bulge_mm",
        "bulge radius",
        "mm",
        EffectKind::FaceCurvature,
        0,
        Mapping::Add,
        130.0,
    ),
    hp(
        "roll_mm",
        "roll radius",
        "mm",
        EffectKind::FaceCurvature,
        1,
        Mapping::Add,
        130.0,
    ),
    hp(
        "cor",
        "COR at the centre",
        "1",
        EffectKind::CorLevel,
        0,
        Mapping::Add,
        0.035,
    ),
    hp(
        "cor_radial.c_per_mm2",
        "COR falloff",
        "1/mm2",
        EffectKind::CorRadial,
        0,
        Mapping::Add,
        1.5e-4,
    ),
    hp(
        "loft_bias.deg",
        "loft bias",
        "deg",
        EffectKind::LoftBias,
        0,
        Mapping::Add,
        3.0,
    ),
    hp(
        "face_bias.deg",
        "face-angle bias",
        "deg",
        EffectKind::FaceBias,
        0,
        Mapping::Add,
        3.0,
    ),
];

/// The effects a head fit frees, global, in the order of [`HEAD_PARAMS`].
pub const HEAD_EFFECTS: [EffectKind; 7] = [
    EffectKind::ComOffset,
    EffectKind::InertiaAxes,
    EffectKind::FaceCurvature,
    EffectKind::CorLevel,
    EffectKind::CorRadial,
    EffectKind::LoftBias,
    EffectKind::FaceBias,
];

/// Effects a start club may carry as global `[[effect]]` tables that the written club merges
/// with the fitted ones (the head's COR falloff and the monitor's biases).
const MERGED: [EffectKind; 3] = [
    EffectKind::CorRadial,
    EffectKind::LoftBias,
    EffectKind::FaceBias,
];

/// The fit layout of the head parameters (every effect global).
pub fn head_layout() -> ParamLayout {
    ParamLayout::new(
        HEAD_EFFECTS
            .iter()
            .map(|&k| FreeEffect {
                kind: k.into(),
                group: None,
            })
            .collect(),
    )
    .expect("the head effects are distinct")
}

/// How far behind the face plane the CoM must stay, mm: the club file's rule is only that it
/// lie behind the face (`x < 0`); 1 µm keeps a fit that stops there writable.
pub const FACE_CLEARANCE_MM: f64 = 1e-3;

/// The fit's upper bounds for start club `club`: [`head_layout`]'s, with the CoM depth offset
/// stopped where the CoM would reach the face (`com_offset`'s own range allows any head's
/// CoM to pass it, and a club with its CoM at or in front of the face is not a club).
pub fn upper_bounds(club: &ClubSpec) -> DVector<f64> {
    let mut upper = head_layout().upper();
    let to_face_mm = -club.nominal.club_com_m.x * 1e3 - FACE_CLEARANCE_MM;
    upper[0] = upper[0].min(to_face_mm);
    upper
}

/// The requests of [`head_layout`] (for the variation check and reports).
pub fn head_requests() -> Vec<EffectRequest> {
    HEAD_EFFECTS
        .iter()
        .map(|&k| EffectRequest::Global(k.into()))
        .collect()
}

/// The sum of the start club's global effects of `kind`, parameter `index` (0 without one).
fn global_effect_value(club: &ClubSpec, kind: EffectKind, index: usize) -> f64 {
    club.effects
        .iter()
        .filter(|e| e.kind() == EffectId::from(kind) && e.group().is_none())
        .map(|e| e.values()[index])
        .sum()
}

/// The start club's value of each head parameter, in its reported unit.
pub fn start_values(club: &ClubSpec) -> [f64; 11] {
    let p = &club.nominal;
    let i = &p.club_inertia_kgm2;
    [
        p.club_com_m.x * 1e3,
        p.club_com_m.y * 1e3,
        p.club_com_m.z * 1e3,
        i[(1, 1)] * 1e7,
        i[(2, 2)] * 1e7,
        p.bulge_m * 1e3,
        p.roll_m * 1e3,
        p.cor,
        global_effect_value(club, EffectKind::CorRadial, 0),
        global_effect_value(club, EffectKind::LoftBias, 0),
        global_effect_value(club, EffectKind::FaceBias, 0),
    ]
}

/// Reported value (and the factor from a fitted-parameter SE to the reported SE) of head
/// parameter `j` at fitted value `theta_j`, given its start value.
pub fn reported(j: usize, start: f64, theta_j: f64) -> (f64, f64) {
    match HEAD_PARAMS[j].mapping {
        Mapping::Add => (start + theta_j, 1.0),
        Mapping::Scale => (start * theta_j, start.abs()),
    }
}

/// Prior 1σ of head parameter `j` in its reported unit.
pub fn prior_sd_reported(j: usize, start: f64) -> f64 {
    HEAD_PARAMS[j].prior_sd * reported(j, start, 1.0).1
}

/// The club with the head values of fit vector `theta`: the nominal fields set to the inferred
/// CoM, moments, radii and COR; the start club's global COR-falloff and bias effects replaced by
/// one each holding the total; its other effects kept as they were (the fit ran on top of them).
pub fn inferred_club(start: &ClubSpec, theta: &DVector<f64>) -> Result<ClubSpec, ClubError> {
    let mut p = start.nominal.clone();
    p.club_com_m.x += theta[0] * 1e-3;
    p.club_com_m.y += theta[1] * 1e-3;
    p.club_com_m.z += theta[2] * 1e-3;
    // The moments as the fit moved them (`inertia_axes`: mass moved, `I_xx` following).
    EffectKind::InertiaAxes.apply(&[theta[3], theta[4]], &mut p);
    // A club file's face has bulge >= roll (its reader's rule); a face the shots find rounder
    // crown to sole than heel to toe keeps the start's radii and carries the change as a
    // `face_curvature` effect, which the model takes either way.
    let radii_in_effect =
        start.nominal.bulge_m + theta[5] * 1e-3 < start.nominal.roll_m + theta[6] * 1e-3;
    if !radii_in_effect {
        p.bulge_m += theta[5] * 1e-3;
        p.roll_m += theta[6] * 1e-3;
    }
    p.cor += theta[7];
    let s = start_values(start);
    let mut effects: Vec<Effect> = start
        .effects
        .iter()
        .filter(|e| !(e.group().is_none() && MERGED.iter().any(|&k| e.kind() == EffectId::from(k))))
        .cloned()
        .collect();
    if radii_in_effect {
        effects.push(Effect::new(
            EffectKind::FaceCurvature,
            &[theta[5], theta[6]],
            None,
        )?);
    }
    for (j, kind) in [
        (8, EffectKind::CorRadial),
        (9, EffectKind::LoftBias),
        (10, EffectKind::FaceBias),
    ] {
        let v = s[j] + theta[j];
        effects.push(Effect::new(kind, &[v], None)?);
    }
    let name = format!("{} (inferred by infer-club)", start.name);
    Ok(ClubSpec::new(name, start.static_loft_rad, p, effects)?)
}

/// Why the inferred head is not a club ([`inferred_club`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ClubError {
    /// An effect holding part of the head is outside its bounds.
    #[error(transparent)]
    Effect(#[from] crate::effects::EffectError),
    /// The head's parameters are not physical.
    #[error(transparent)]
    Params(#[from] crate::physics::ParamError),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_com_depth_offset_stops_short_of_the_face() {
        let mut p = crate::ModelParams::paper_driver();
        p.club_com_m.x = -5e-3;
        let club = ClubSpec::new("iron-like".into(), None, p, vec![]).unwrap();
        let upper = upper_bounds(&club);
        assert!(
            (upper[0] - (5.0 - FACE_CLEARANCE_MM)).abs() < 1e-12,
            "{}",
            upper[0]
        );
        // The other bounds are the layout's.
        let layout = head_layout().upper();
        assert!((1..upper.len()).all(|j| upper[j] == layout[j]));
    }
}
