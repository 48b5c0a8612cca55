//! What `smash diagnose` reports, as one value: [`DiagnoseReport`]. Its text is [`text`], its
//! JSON its `Serialize` (the schema: `docs/json.md`), its HTML page
//! [`crate::report::html::diagnose_page`].

pub mod face_map;
pub mod text;
mod view;

use view::view;

use serde::{Serialize, Serializer};

use crate::diagnose::honest;
use crate::diagnose::noise_floor::{ComponentFloor, NoiseFloor, SpreadBand, STRUCTURE_ALPHA};
use crate::diagnose::Diagnosis;
use crate::fit::ParamEstimate;
use crate::report::location_mm;

/// The version of diagnose's JSON schema (`schema_version`); raised when a key changes meaning
/// or goes away (a new key does not raise it).
pub const SCHEMA_VERSION: u32 = 1;

/// What `smash diagnose` reports: the diagnosis and the noise floor its errors were judged
/// against. Text, JSON and HTML all render this one value.
#[derive(Debug, Clone)]
pub struct DiagnoseReport {
    /// The selection, its steps and its final model.
    pub diagnosis: Diagnosis,
    /// The instruments' noise floor of the final model's errors.
    pub floor: NoiseFloor,
}

impl Serialize for DiagnoseReport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        super::json::canonical(&view(&self.diagnosis, &self.floor), s)
    }
}

impl DiagnoseReport {
    /// What the diagnosis concludes about the structure left in the errors and, when the
    /// instrument noise was assumed, what that verdict rests on.
    pub fn conclusion(&self) -> String {
        conclusion(&self.diagnosis, &self.floor)
    }
}

/// `finding`, `stand_in`, `absent` (on its no-effect bound), `unchanged` (not significantly
/// different from its no-effect value), `provisional` (its value differs
/// across strata of the shots) or `ambiguous` (a plausible value with a plausible rival, or
/// aliased with another effect).
fn status(d: &Diagnosis, p: &ParamEstimate) -> &'static str {
    if d.club_mismatch.is_some() {
        "wrong_club"
    } else if honest::is_plausible(p) == Some(false) {
        "stand_in"
    } else if honest::is_absent(p) {
        "absent"
    } else if honest::is_unchanged(p, d.estimates.len()) {
        "unchanged"
    } else if d.is_finding(p) {
        "finding"
    } else if d.provisional(p).is_some() {
        "provisional"
    } else {
        "ambiguous"
    }
}

/// What the diagnosis concludes about the structure left in the errors, and, when the
/// instrument noise was assumed, what the verdict rests on ([`assumed_note`]).
fn conclusion(d: &Diagnosis, floor: &NoiseFloor) -> String {
    format!(
        "{}{}{}",
        verdict(d, floor),
        shape_note(floor),
        assumed_note(floor)
    )
}

/// The components whose spread the noise explains but whose errors follow a shape the noise
/// floor's search found ([`ComponentFloor::quiet_shape`]), in one clause (empty when none).
fn shape_note(floor: &NoiseFloor) -> String {
    let quiet: Vec<&str> = floor
        .components
        .iter()
        .filter(|c| c.quiet_shape().is_some())
        .map(|c| c.component.column())
        .collect();
    if quiet.is_empty() {
        return String::new();
    }
    format!(
        "; but {} follow(s) a shape the spread test does not see (see the verdicts and face \
         map): structure may remain that the spread alone does not show",
        quiet.join(", ")
    )
}

/// Without `--noise` or `--instrument`: the verdict rests on the assumed class's noise; the
/// observed-to-expected spread ratio per component, and what a ratio well below or well above
/// 1 means (empty when the noise was given).
fn assumed_note(floor: &NoiseFloor) -> String {
    if !floor.assumed {
        return String::new();
    }
    let ratios: Vec<String> = floor
        .components
        .iter()
        .map(|c| format!("{} {:.2}", c.component.column(), c.ratio))
        .collect();
    let band = |b: SpreadBand| -> Vec<&str> {
        floor
            .components
            .iter()
            .filter(|c| floor.spread_band(c) == b)
            .map(|c| c.component.column())
            .collect()
    };
    let h = floor.band_half_width();
    let mut s = format!(
        ". This verdict rests on the ASSUMED {} instrument noise (no --noise or --instrument \
         given); observed/expected spread: {}",
        floor.instrument.name,
        ratios.join(", ")
    );
    let below = band(SpreadBand::WellBelow);
    if !below.is_empty() {
        s.push_str(&format!(
            "; well below 1 (under {:.2}) in {}: the assumed noise is too large for these \
             errors, so the test cannot see structure there",
            1.0 - h,
            below.join(", ")
        ));
    }
    let above = band(SpreadBand::WellAbove);
    if !above.is_empty() {
        s.push_str(&format!(
            "; well above 1 (over {:.2}) in {}: structure remains there, or the instruments \
             are noisier than assumed",
            1.0 + h,
            above.join(", ")
        ));
    }
    if below.is_empty() && above.is_empty() {
        s.push_str(&format!("; each within {h:.2} of 1"));
    }
    s.push_str("; give the instruments' noise with --noise to test it");
    s
}

/// With the instruments' noise assumed and no structure found: the component that scatters
/// beyond the assumed noise at the 1 % level ([`STRUCTURE_ALPHA`], the ratio above 1), the most
/// significant when several do. "What remains is noise" is then not the headline: the
/// structure test's level is a tenth of that (ten tests), and with assumed noise a ratio
/// above 1 is as likely noise underestimated as structure.
fn beyond_assumed_noise(floor: &NoiseFloor) -> Option<&ComponentFloor> {
    if !floor.assumed || floor.structure_remains() {
        return None;
    }
    floor
        .components
        .iter()
        .filter(|c| c.ratio > 1.0 && c.p_value < STRUCTURE_ALPHA)
        .min_by(|a, b| a.p_value.total_cmp(&b.p_value))
}

/// The verdict on the structure left in the errors.
fn verdict(d: &Diagnosis, floor: &NoiseFloor) -> String {
    let stand_ins: Vec<String> = d
        .estimates
        .iter()
        .filter(|p| honest::is_plausible(p) == Some(false))
        .map(|p| p.label())
        .collect();
    let mut stand_in_note = String::new();
    if !stand_ins.is_empty() {
        stand_in_note = format!(
            "; {} stand(s) in for physics the library lacks and is not a finding",
            stand_ins.join(", ")
        );
    }
    // Each kind of value that is not a finding, with why, when there is any.
    let mut not_findings = |why: &str, labels: Vec<String>, sep: &str| {
        if !labels.is_empty() {
            stand_in_note.push_str(&format!("; {why}: {}", labels.join(sep)));
        }
    };
    not_findings(
        "ambiguous, not findings (each has a plausible alternative the data cannot tell apart \
         from it)",
        d.ambiguities
            .iter()
            .filter(|a| a.is_ambiguous())
            .map(|a| a.selected.clone())
            .collect(),
        ", ",
    );
    not_findings(
        "aliased, not findings (the data cannot tell which effect carries the signal)",
        d.aliases
            .iter()
            .filter(|a| a.across_effects())
            .map(|a| format!("{} and {}", a.a, a.b))
            .collect(),
        "; ",
    );
    not_findings(
        "provisional, not findings (the value differs between parts of the shots beyond its \
         uncertainty, or its signal shares the trend of structure left)",
        d.estimates
            .iter()
            .filter(|p| d.provisional(p).is_some())
            .map(|p| p.label())
            .collect(),
        ", ",
    );
    if let Some(c) = beyond_assumed_noise(floor) {
        return format!(
            "{col} scatters {ratio:.2}× the assumed noise (p = {p:.1e}): short of the structure \
             test (p < {alpha} for each of its ten tests), but more than the assumed noise \
             explains, so structure may remain there or the instruments are noisier than \
             assumed; the other components scatter as the instruments alone explain{stand_in_note}",
            col = c.component.column(),
            ratio = c.ratio,
            p = c.p_value,
            alpha = STRUCTURE_ALPHA / 10.0,
        );
    }
    if !floor.structure_remains() {
        return format!(
            "what remains is noise: the errors scatter as the instruments alone explain{stand_in_note}"
        );
    }
    let structured: Vec<&str> = floor
        .components
        .iter()
        .filter(|c| c.structure)
        .map(|c| c.component.column())
        .collect();
    // The last forward step (swap steps follow forward selection).
    let last = d.steps.iter().rfind(|s| s.swap.is_none());
    let stopped_by_limit = last.is_none_or(|s| s.selected.is_some());
    if stopped_by_limit {
        format!(
            "unexplained structure remains in {}, and the step limit was reached: raise \
             --max-steps to keep looking{stand_in_note}",
            structured.join(", ")
        )
    } else {
        let best = last
            .and_then(|s| s.candidates.first())
            .map_or(String::new(), |c| {
                format!(" (best: {}, margin {:.1})", c.label, c.margin())
            });
        format!(
            "unexplained structure remains in {}; no library candidate reduces it by more than \
             its penalty{best}: the data contain physics the library lacks (or the instrument \
             noise given is too small){stand_in_note}",
            structured.join(", ")
        )
    }
}

/// The `smash calibrate` flags that fit the diagnosis's final model (its effects and its
/// measurement model), each with its value.
fn calibrate_flag_pairs(d: &Diagnosis) -> Vec<(&'static str, String)> {
    let mut flags = Vec::new();
    if !d.selected.is_empty() {
        flags.push(("--effects", d.selected.join(",")));
    }
    if let Some(n) = d.impact_noise {
        flags.push((
            "--impact-noise-mm",
            format!("{},{}", location_mm(n.sigma_y_m), location_mm(n.sigma_z_m)),
        ));
    }
    if let Some(spec) = d
        .delivery_noise
        .as_ref()
        .and_then(crate::report::delivery_noise::spec)
    {
        flags.push(("--delivery-noise", spec));
    }
    flags
}

/// [`calibrate_flag_pairs`] as one string (JSON's `calibrate_flags`).
fn calibrate_flags(d: &Diagnosis) -> String {
    calibrate_flag_pairs(d)
        .into_iter()
        .map(|(f, v)| format!("{f} {v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::noise_floor::InstrumentNoise;
    use crate::physics::LaunchComponent;

    fn floor(assumed: bool, ratios_p: [(f64, f64); 5]) -> NoiseFloor {
        NoiseFloor {
            instrument: InstrumentNoise {
                name: "camera".into(),
                launch_sd: [1.0; 5],
                delivery_sd: [1.0; crate::model::N_DELIVERY],
            },
            components: LaunchComponent::ALL
                .iter()
                .zip(ratios_p)
                .map(|(&component, (ratio, p_value))| ComponentFloor {
                    component,
                    mean: 0.0,
                    mean_in_sd: 0.0,
                    expected_sd: 1.0,
                    observed_sd: ratio,
                    ratio,
                    p_value,
                    mean_p_value: 0.5,
                    structure: p_value < STRUCTURE_ALPHA / 10.0,
                    trend: None,
                    shape: Default::default(),
                })
                .collect(),
            n_shots: 600,
            assumed,
        }
    }

    /// The case: with the noise assumed, one component at 1.08× (p = 0.003) and the
    /// others below 1 is the headline, not "noise"; the most significant of two leads; with
    /// the noise given, or no component beyond it at 1 %, or a ratio below 1, it is not.
    #[test]
    fn a_component_beyond_assumed_noise_leads_the_headline() {
        let calm = (0.8, 0.9);
        let f = floor(true, [calm, calm, (1.08, 0.003), calm, calm]);
        assert_eq!(
            beyond_assumed_noise(&f).map(|c| c.component),
            Some(LaunchComponent::Azimuth)
        );
        let f = floor(true, [(1.05, 0.008), calm, (1.08, 0.003), calm, calm]);
        assert_eq!(
            beyond_assumed_noise(&f).map(|c| c.component),
            Some(LaunchComponent::Azimuth)
        );
        assert!(
            beyond_assumed_noise(&floor(false, [calm, calm, (1.08, 0.003), calm, calm])).is_none()
        );
        assert!(
            beyond_assumed_noise(&floor(true, [calm, calm, (1.08, 0.02), calm, calm])).is_none()
        );
        assert!(beyond_assumed_noise(&floor(true, [calm; 5])).is_none());
        // Structure found: the structure verdict speaks instead.
        assert!(
            beyond_assumed_noise(&floor(true, [calm, calm, (1.3, 1e-6), calm, calm])).is_none()
        );
    }
}
