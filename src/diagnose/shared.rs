//! A finding must not share its signal with structure the final model leaves (issue 29,
//! check (b)).
//!
//! A stand-in is an effect that reduces the errors because its signal resembles that of physics
//! the library lacks: fitted, it takes the part of the missing physics its signal can reach and
//! leaves the rest. What it leaves shows in the noise floor ([`super::noise_floor`]): a
//! component whose errors scatter beyond the instruments' noise and trend with a delivery
//! variable. If the effect's own signal in that component trends with the same variable, the
//! effect is reaching for the structure that remains, and its value is a compromise with
//! physics it does not describe: *provisional*, not a finding.
//!
//! The signal of a parameter is the change of each shot's modelled launch per unit of the
//! parameter, by central differences at the final club ([`Diagnosis::club`]), with the final
//! model's impact- and delivery-noise treatment. The test, per (component with structure,
//! estimate): the structure's trend `|r| ≥` [`MIN_STRUCTURE_TREND_R`] with variable `x`, and
//! the signal's correlation with `x` over the shots `|r| ≥` [`MIN_SIGNAL_TREND_R`]. Both
//! thresholds are conventional effect sizes (Cohen 1988: 0.3 "medium", 0.5 "large"), fixed
//! before the check was run on any world.
//!
//! Example (`configs/synth/twisted_face_world.toml`, a face whose loft and face angle change
//! toward the toe): `inertia_scale` fitted to it leaves azimuth errors trending with
//! `impact_z_mm`, and its own azimuth signal (gear effect, proportional to the heel–toe
//! offset) trends with `impact_z_mm` too.

use crate::club::ClubSpec;
use crate::effects::Effect;
use crate::fit::{FitData, FitError, ParamEstimate};
use crate::model::{DeliveryVar, Shot};
use crate::physics::LaunchComponent;
use crate::stats;

use super::noise_floor::{delivery_to_file_units, final_model_data, launch_errors_of, NoiseFloor};
use super::Diagnosis;

/// Smallest |r| of a component's remaining structure with a delivery variable for the check
/// to look at it (Cohen's "medium" correlation).
pub const MIN_STRUCTURE_TREND_R: f64 = 0.3;
/// Smallest |r| of an estimate's signal with that variable to call the signal shared (Cohen's
/// "large" correlation).
pub const MIN_SIGNAL_TREND_R: f64 = 0.5;

/// An estimate whose signal trends with the variable that remaining structure trends with.
#[derive(Debug, Clone, PartialEq)]
pub struct SharedSignal {
    /// The estimate (`effect@group.param`).
    pub label: String,
    /// The component where structure remains.
    pub component: LaunchComponent,
    /// The delivery variable the structure and the signal both trend with.
    pub variable: DeliveryVar,
    /// Correlation of the remaining (standardised) errors with `variable`.
    pub structure_r: f64,
    /// Correlation of the estimate's signal with `variable`.
    pub signal_r: f64,
}

impl SharedSignal {
    /// "structure left in azimuth_deg trends with impact_z_mm (r = -0.42), as the signal of
    /// inertia_scale.s there does (r = 0.97)".
    pub fn text(&self) -> String {
        let (c, v) = (self.component.column(), self.variable.column());
        format!(
            "structure left in {c} trends with {v} (r = {:.2}), as its own signal there does \
             (r = {:.2}): it may stand in for physics the library lacks",
            self.structure_r, self.signal_r
        )
    }
}

/// Every estimate of `d` whose signal shares the trend of structure `floor` finds (empty when
/// no component has structure with a trend).
pub fn shared_signals(
    d: &Diagnosis,
    shots: &[Shot],
    floor: &NoiseFloor,
) -> Result<Vec<SharedSignal>, FitError> {
    let trends: Vec<(LaunchComponent, DeliveryVar, f64)> = floor
        .components
        .iter()
        .filter(|c| c.structure)
        .filter_map(|c| c.trend.map(|(v, r)| (c.component, v, r)))
        .filter(|(_, _, r)| r.abs() >= MIN_STRUCTURE_TREND_R)
        .collect();
    if trends.is_empty() || d.estimates.is_empty() {
        return Ok(Vec::new());
    }
    let data = final_model_data(d, shots)?;
    let deliveries: Vec<_> = shots
        .iter()
        .map(|s| delivery_to_file_units(&s.delivery))
        .collect();
    let mut out = Vec::new();
    for p in &d.estimates {
        let Some(signal) = signal_of(&d.club, &data, p)? else {
            continue;
        };
        for &(component, variable, structure_r) in &trends {
            let x: Vec<f64> = deliveries.iter().map(|d| d[variable.index()]).collect();
            let s: Vec<f64> = signal.iter().map(|s| s[component.index()]).collect();
            let Some(k) = stats::pearson(&x, &s) else {
                continue;
            };
            if k.r.abs() >= MIN_SIGNAL_TREND_R {
                out.push(SharedSignal {
                    label: p.label(),
                    component,
                    variable,
                    structure_r,
                    signal_r: k.r,
                });
            }
        }
    }
    Ok(out)
}

/// The launch change per unit of `p` for every shot (file units per parameter unit), by
/// central differences of the final club with `p` moved (one-sided at a bound); `None` when
/// the club holds no effect for `p`.
pub(super) fn signal_of(
    club: &ClubSpec,
    data: &FitData,
    p: &ParamEstimate,
) -> Result<Option<Vec<[f64; 5]>>, FitError> {
    let label = p.label();
    let Some((k, e)) = club
        .effects
        .iter()
        .enumerate()
        .rev()
        .find(|(_, e)| label.starts_with(&format!("{}.", e.label())))
    else {
        return Ok(None);
    };
    let specs = e.kind().params();
    let Some(j) = specs.iter().position(|s| s.key == p.param) else {
        return Ok(None);
    };
    let (lo, hi) = (specs[j].lower, specs[j].upper);
    let h = 1e-4 * (hi - lo).min(1.0 + e.values()[j].abs());
    let (a, b) = ((e.values()[j] - h).max(lo), (e.values()[j] + h).min(hi));
    let at = |v: f64| -> Result<Vec<[f64; 5]>, FitError> {
        let mut values = e.values().to_vec();
        values[j] = v;
        let mut moved = club.clone();
        moved.effects[k] = Effect::new(e.kind(), &values, e.group().map(str::to_owned))?;
        launch_errors_of(&moved, data)
    };
    let (ea, eb) = (at(a)?, at(b)?);
    Ok(Some(
        ea.iter()
            .zip(&eb)
            .map(|(x, y)| std::array::from_fn(|c| (y[c] - x[c]) / (b - a)))
            .collect(),
    ))
}
