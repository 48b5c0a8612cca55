//! Honest reading of fitted values: plausibility, stand-ins and aliases.
//!
//! A fit always finds *some* value for a parameter. When the data contain physics the library
//! lacks, the fit bends whatever knobs it has to mimic it, and the values it lands on can be
//! far from anything a real club shows (a negative shaft mass, a centre of mass moved 5 mm).
//! This module turns such values into what they are:
//!
//! - **plausibility**: every parameter has a plausible range ([`crate::effects::ParamSpec`]
//!   `plausible`, sources in `docs/plausible-ranges.md`). A value outside it is a **stand-in**:
//!   the effect reproduces some other physics, and [`stand_in`] says which it behaves like. A
//!   stand-in is never reported as a finding.
//! - **aliases**: two parameters whose estimates correlate beyond
//!   [`crate::fit::calibrate::STRONG_CORRELATION`] cannot be told apart by the data; [`aliases`]
//!   names them and the measurement that would separate them.

use nalgebra::DMatrix;

use crate::effects::{EffectKind, ParamSpec};
use crate::fit::calibrate::STRONG_CORRELATION;
use crate::fit::ParamEstimate;

/// The library specification of an estimate's parameter (`None` for an effect or key the
/// library does not know).
pub fn spec_of(p: &ParamEstimate) -> Option<&'static ParamSpec> {
    crate::effects::EffectId::from_name(p.effect)?
        .params()
        .iter()
        .find(|s| s.key == p.param)
}

/// Is the value inside its plausible range? `None` when the parameter has no known range.
pub fn is_plausible(p: &ParamEstimate) -> Option<bool> {
    let (lo, hi) = spec_of(p)?.plausible;
    Some(p.value >= lo && p.value <= hi)
}

/// Does the fit leave this parameter *absent*: stopped on a physical bound that is also its
/// neutral (no-effect) value, as `cor_radial.c_per_mm2 = 0` (COR does not fall off the centre
/// at all)? Such a value says the effect is not there at the optimum, so it is not a finding;
/// `docs/diagnose-selection.md`, "Absent at a bound".
pub fn is_absent(p: &ParamEstimate) -> bool {
    p.at_bound
        && spec_of(p).is_some_and(|s| {
            let on_neutral = (p.value - s.default).abs() <= 1e-9 * (s.upper - s.lower);
            on_neutral && (s.default == s.lower || s.default == s.upper)
        })
}

/// Family-wise error rate of reading a parameter as changed from its no-effect value: the
/// conventional 5 %, shared (Bonferroni) over every parameter of the final model.
pub const UNCHANGED_ALPHA: f64 = 0.05;

/// Is this parameter of a selected effect indistinguishable from its no-effect value? Its
/// two-sided p-value against that value, `|value − neutral|/SE` read as a normal deviate, is at
/// least [`UNCHANGED_ALPHA`] / `n_params` (the parameters the final model estimates: a claim is
/// made of each, so the rate is shared among them). Then the data show no change from the club
/// file in it (a face curvature whose roll is 5 ± 5 mm from the file's, say), and it is not a
/// finding even when the effect's other parameters are. `friction.mu` has no finite no-effect
/// value (its default is a typical value), so it is never read this way.
/// `docs/diagnose-selection.md`, "Absent at a bound".
pub fn is_unchanged(p: &ParamEstimate, n_params: usize) -> bool {
    if EffectKind::from_name(p.effect) == Some(EffectKind::Friction) {
        return false;
    }
    match (spec_of(p), p.stderr) {
        (Some(s), Some(se)) if se > 0.0 => {
            let z = (p.value - s.default).abs() / se;
            // A normal deviate: Student's t with effectively infinite degrees of freedom.
            let p_value = crate::stats::tdist::student_t_two_sided_p(z, 1e9);
            p_value >= UNCHANGED_ALPHA / n_params.max(1) as f64
        }
        _ => false,
    }
}

/// Is an implausible value within two standard errors of its plausible range? Then the fit
/// does not tell it from a plausible value (`added_mass@C.dm_g = −1.41 ± 1.58 g` against
/// `[0, 20]`), and reading it as a stand-in for other physics claims more than the data show.
/// `false` for a plausible value, one without a range or without a finite standard error.
pub fn implausible_within_noise(p: &ParamEstimate) -> bool {
    let (Some(false), Some(spec), Some(se)) = (is_plausible(p), spec_of(p), p.stderr) else {
        return false;
    };
    let (lo, hi) = spec.plausible;
    let gap = if p.value < lo {
        lo - p.value
    } else {
        p.value - hi
    };
    se.is_finite() && gap <= 2.0 * se
}

/// Which physics an implausible value behaves like (`None` when the value is plausible or the
/// parameter unknown). The reading is the effect's own (`STAND_IN` in its file): what else moves
/// the same launch components the same way.
pub fn stand_in(p: &ParamEstimate) -> Option<&'static str> {
    if is_plausible(p)? {
        return None;
    }
    let (lo, _) = spec_of(p)?.plausible;
    let s = EffectKind::from_name(p.effect)?.stand_in();
    Some(if p.value < lo { s.below } else { s.above })
}

/// What measurement pins a parameter of this effect down independently (`SEPARATE_BY` in the
/// effect's file).
pub fn separating_measurement(effect: &str) -> &'static str {
    EffectKind::from_name(effect).map_or(
        "an independent measurement of this parameter",
        EffectKind::separate_by,
    )
}

/// Two parameters the data cannot tell apart.
#[derive(Debug, Clone, PartialEq)]
pub struct Alias {
    /// First parameter, `effect[@group].param`.
    pub a: String,
    /// Second parameter.
    pub b: String,
    /// Correlation of their estimates.
    pub r: f64,
    /// What would separate them.
    pub separate_by: String,
}

impl Alias {
    /// Are the two parameters of different effects (not two parameters of one effect, nor one
    /// effect's values in two groups)?
    pub fn across_effects(&self) -> bool {
        effect_of_label(&self.a) != effect_of_label(&self.b)
    }

    /// One line of text.
    pub fn text(&self) -> String {
        format!(
            "{} and {} (r = {:+.2}): the data cannot tell them apart; to separate them: {}",
            self.a, self.b, self.r, self.separate_by
        )
    }
}

/// The effect name of an estimate's label, `effect[@group].param`.
pub fn effect_of_label(label: &str) -> &str {
    let name = label.split('.').next().unwrap_or(label);
    name.split('@').next().unwrap_or(name)
}

/// Pairs of `params` whose estimates correlate beyond [`STRONG_CORRELATION`] in `correlation`
/// (indexed like `params`). Pairs within one multi-parameter effect are aliases too.
pub fn aliases(params: &[ParamEstimate], correlation: Option<&DMatrix<f64>>) -> Vec<Alias> {
    let Some(c) = correlation else {
        return Vec::new();
    };
    let n = params.len().min(c.nrows()).min(c.ncols());
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let r = c[(i, j)];
            if r.abs() > STRONG_CORRELATION {
                let (ea, eb) = (params[i].effect, params[j].effect);
                let separate_by = if ea == eb {
                    separating_measurement(ea).to_owned()
                } else {
                    format!(
                        "for {ea}: {}; for {eb}: {}",
                        separating_measurement(ea),
                        separating_measurement(eb)
                    )
                };
                out.push(Alias {
                    a: params[i].label(),
                    b: params[j].label(),
                    r,
                    separate_by,
                });
            }
        }
    }
    out
}

/// What a candidate's fit changed in the predictions: its errors minus the base model's,
/// each component divided by its noise scale, flattened (shot-major).
pub fn explained_signal(base: &[[f64; 5]], after: &[[f64; 5]], sigma: &[f64; 5]) -> Vec<f64> {
    base.iter()
        .zip(after)
        .flat_map(|(b, a)| (0..5).map(move |c| (a[c] - b[c]) / sigma[c]))
        .collect()
}

/// Correlation (uncentred: both changes are measured from the same base) of two candidates'
/// explained signals: near 1 when they change the predictions alike.
pub fn signal_correlation(a: &[f64], b: &[f64]) -> f64 {
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += x * y;
        aa += x * x;
        bb += y * y;
    }
    if aa > 0.0 && bb > 0.0 {
        ab / (aa * bb).sqrt()
    } else {
        0.0
    }
}

/// Two candidates of one step that explained the same signal: the best by evidence
/// (`instead_of`) had an implausible value, the other (`selected`) a plausible one.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplainedAlias {
    /// The plausible candidate selected.
    pub selected: String,
    /// The candidate with more evidence and an implausible value.
    pub instead_of: String,
    /// Correlation of the changes they make to the predictions.
    pub r: f64,
}

impl ExplainedAlias {
    /// One line of text.
    pub fn text(&self) -> String {
        format!(
            "{} and {} explain the same signal (r = {:.2}); {} is selected because its value is \
             plausible and {}'s is not",
            self.selected, self.instead_of, self.r, self.selected, self.instead_of
        )
    }
}

/// An unselected candidate that explains nearly the same signal as a selected effect (see
/// [`crate::diagnose::select::RIVAL_MARGIN`]): the data hardly prefer one to the other. At a
/// step, measured by the cross-validated margins; in the final report, by swapping it in for
/// the selected effect in the final model.
#[derive(Debug, Clone, PartialEq)]
pub struct Rival {
    /// The candidate (`name` or `name@group`).
    pub label: String,
    /// Its values fitted at that step.
    pub params: Vec<ParamEstimate>,
    /// How much less well it explains the data than the selected effect (a difference of
    /// `χ² + k·ln n` or of cross-validated margins; ≤ the rival margin, may be negative).
    pub margin_gap: f64,
    /// Correlation of the changes the two fits make to the predictions.
    pub r: f64,
    /// Are all its values inside their plausible ranges?
    pub plausible: bool,
}

impl Rival {
    /// A rival with its values `params`, its margin gap and correlation; plausible when every
    /// value with a plausible range lies inside it.
    pub(crate) fn new(label: String, params: Vec<ParamEstimate>, margin_gap: f64, r: f64) -> Self {
        Self {
            label,
            plausible: params.iter().all(|p| is_plausible(p).unwrap_or(true)),
            params,
            margin_gap,
            r,
        }
    }
}

fn value_text(p: &ParamEstimate) -> String {
    let v = if p.value != 0.0 && p.value.abs() < 1e-3 {
        format!("{:+.3e}", p.value)
    } else {
        format!("{:+.4}", p.value)
    };
    if p.unit.is_empty() {
        format!("{} = {v}", p.label())
    } else {
        format!("{} = {v} {}", p.label(), p.unit)
    }
}

fn values_text(ps: &[ParamEstimate]) -> String {
    ps.iter().map(value_text).collect::<Vec<_>>().join(", ")
}

/// A selected effect with the rivals of the step that selected it.
#[derive(Debug, Clone, PartialEq)]
pub struct Ambiguity {
    /// The selected effect (`name` or `name@group`).
    pub selected: String,
    /// Its final values.
    pub estimates: Vec<ParamEstimate>,
    /// The unselected candidates that explained nearly the same signal, best first.
    pub rivals: Vec<Rival>,
}

impl Ambiguity {
    /// The selected values are plausible and so are some rival's: two plausible readings the
    /// data cannot tell apart, so neither is a finding.
    pub fn is_ambiguous(&self) -> bool {
        self.selected_is_plausible() && self.rivals.iter().any(|r| r.plausible)
    }

    /// Are all the selected effect's values inside their plausible ranges?
    fn selected_is_plausible(&self) -> bool {
        self.estimates
            .iter()
            .all(|p| is_plausible(p).unwrap_or(true))
    }

    /// One line of text.
    pub fn text(&self) -> String {
        let alternatives: Vec<String> = self
            .rivals
            .iter()
            .map(|r| {
                let fit = if r.margin_gap >= 0.0 {
                    format!("fits worse by {:.1}", r.margin_gap)
                } else {
                    format!("fits better by {:.1}", -r.margin_gap)
                };
                format!(
                    "{} ({}; r = {:.2}, {fit}{})",
                    r.label,
                    values_text(&r.params),
                    r.r,
                    if r.plausible { "" } else { ", implausible" }
                )
            })
            .collect();
        let effect_of = |label: &str| label.split('@').next().unwrap_or(label).to_owned();
        let mut separate: Vec<String> = std::iter::once(&self.selected)
            .chain(self.rivals.iter().map(|r| &r.label))
            .map(|l| {
                let e = effect_of(l);
                format!("for {e}: {}", separating_measurement(&e))
            })
            .collect();
        separate.dedup();
        let verdict = if self.is_ambiguous() {
            "ambiguous, not a finding: the data cannot tell these apart"
        } else if !self.selected_is_plausible() && self.rivals.iter().any(|r| r.plausible) {
            "the data hardly prefer one; the selected value is implausible (a stand-in) and a \
             plausible alternative explains the same signal: look to the alternative's physics"
        } else {
            "the data hardly prefer one; the alternatives' values are implausible"
        };
        format!(
            "{} ({}) or {}: {verdict}; to separate them: {}",
            self.selected,
            values_text(&self.estimates),
            alternatives.join(" or "),
            separate.join("; ")
        )
    }
}

/// The plausible range of an estimate as text (`[lo, hi] unit`), or an empty string.
pub fn plausible_range_text(p: &ParamEstimate) -> String {
    spec_of(p).map_or_else(String::new, |s| {
        format!("[{}, {}] {}", s.plausible.0, s.plausible.1, s.unit)
    })
}

/// The text mark after an estimate: empty when plausible, `⚠ implausible` otherwise.
pub fn mark(p: &ParamEstimate) -> &'static str {
    match is_plausible(p) {
        Some(false) => " [implausible: stand-in]",
        _ => "",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn est(effect: &'static str, param: &'static str, value: f64) -> ParamEstimate {
        ParamEstimate {
            effect,
            group: None,
            param,
            unit: "",
            value,
            stderr: Some(0.1),
            at_bound: false,
        }
    }

    /// `cor_radial.c_per_mm2 = 0` on its lower bound (3000-shot `compliant_driver`): no COR
    /// fall-off at all, absent rather than found; a small positive value off the bound is a
    /// reading, and so is a value on a bound that is not the no-effect one.
    #[test]
    fn a_value_on_its_no_effect_bound_is_absent() {
        let mut zero = est("cor_radial", "c_per_mm2", 0.0);
        assert!(!is_absent(&zero), "not flagged on a bound by the fit");
        zero.at_bound = true;
        assert!(is_absent(&zero));
        assert!(!is_absent(&est("cor_radial", "c_per_mm2", 2e-5)));
        let spec = spec_of(&est("inertia_scale", "s", 1.0)).unwrap();
        let mut low = est("inertia_scale", "s", spec.lower);
        low.at_bound = true;
        assert!(
            !is_absent(&low),
            "s at its lower bound is not s = 1 (no effect)"
        );
    }

    #[test]
    fn a_negative_shaft_mass_is_a_stand_in_and_a_small_positive_one_is_not() {
        let neg = est("added_mass", "dm_g", -5.2);
        assert_eq!(is_plausible(&neg), Some(false));
        assert!(stand_in(&neg).unwrap().contains("lower face COR"));
        let pos = est("added_mass", "dm_g", 2.3);
        assert_eq!(is_plausible(&pos), Some(true));
        assert_eq!(stand_in(&pos), None);
        assert_eq!(mark(&pos), "");
        assert!(!mark(&neg).is_empty());
    }

    /// −1.41 ± 1.58 g is not told from 0 g (the plausible range starts there); −5.2 ± 1.0 g
    /// is, and a value without a standard error is judged by its value alone.
    #[test]
    fn an_implausible_value_within_two_se_of_its_range_is_noise() {
        let mut near = est("added_mass", "dm_g", -1.41);
        near.stderr = Some(1.58);
        assert!(implausible_within_noise(&near));
        let mut far = est("added_mass", "dm_g", -5.2);
        far.stderr = Some(1.0);
        assert!(!implausible_within_noise(&far));
        far.stderr = None;
        assert!(!implausible_within_noise(&far));
        let mut inside = est("added_mass", "dm_g", 2.3);
        inside.stderr = Some(10.0);
        assert!(!implausible_within_noise(&inside));
    }

    #[test]
    fn every_library_parameter_has_a_plausible_range_inside_its_bounds() {
        for k in EffectKind::ALL {
            for s in k.params() {
                let (lo, hi) = s.plausible;
                assert!(s.lower <= lo && lo < hi && hi <= s.upper, "{}.{}", k, s.key);
                // The neutral value is plausible (friction's is a typical value).
                assert!(lo <= s.default && s.default <= hi, "{}.{}", k, s.key);
            }
        }
    }

    #[test]
    fn aliases_are_the_pairs_beyond_the_threshold() {
        let ps = [
            est("added_mass", "dm_g", -5.0),
            est("com_offset", "dx_mm", 5.0),
            est("cor_speed", "k_per_m_s", 0.002),
        ];
        let c = DMatrix::from_row_slice(3, 3, &[1.0, -0.95, 0.2, -0.95, 1.0, 0.5, 0.2, 0.5, 1.0]);
        let a = aliases(&ps, Some(&c));
        assert_eq!(a.len(), 1);
        assert_eq!(
            (a[0].a.as_str(), a[0].b.as_str()),
            ("added_mass.dm_g", "com_offset.dx_mm")
        );
        assert!(a[0].separate_by.contains("head speed just after impact"));
        assert!(a[0].separate_by.contains("centre of mass"));
        assert!(aliases(&ps, None).is_empty());
    }

    fn rival(label: &str, effect: &'static str, param: &'static str, value: f64) -> Rival {
        let params = vec![est(effect, param, value)];
        Rival {
            label: label.into(),
            plausible: params.iter().all(|p| is_plausible(p).unwrap_or(true)),
            params,
            margin_gap: 2.0,
            r: 0.97,
        }
    }

    #[test]
    fn a_plausible_selection_with_a_plausible_rival_is_ambiguous_not_a_finding() {
        let mut a = Ambiguity {
            selected: "added_mass".into(),
            estimates: vec![est("added_mass", "dm_g", 8.7)],
            rivals: vec![rival("cor_level", "cor_level", "dcor", 0.02)],
        };
        assert!(a.is_ambiguous());
        let t = a.text();
        assert!(t.contains("added_mass") && t.contains("cor_level"), "{t}");
        assert!(t.contains("cannot tell these apart"), "{t}");
        assert!(a.is_ambiguous());
        // An implausible rival leaves the selection a finding.
        a.rivals = vec![rival("cor_level", "cor_level", "dcor", 0.3)];
        assert!(!a.is_ambiguous());
        assert!(
            a.text().contains("alternatives' values are implausible"),
            "{}",
            a.text()
        );
        // An implausible selection is a stand-in, not an ambiguity, and the text points to the
        // plausible rival's physics instead of calling the alternatives implausible.
        a.estimates = vec![est("added_mass", "dm_g", -5.0)];
        a.rivals = vec![rival("cor_level", "cor_level", "dcor", 0.02)];
        assert!(!a.is_ambiguous());
        let t = a.text();
        assert!(t.contains("selected value is implausible"), "{t}");
        assert!(!t.contains("alternatives' values are implausible"), "{t}");
    }

    #[test]
    fn an_alias_across_effects_is_told_from_one_within_an_effect() {
        let params = [
            est("ball_offset", "dy_mm", 0.8),
            est("ball_offset", "dz_mm", 0.0),
            est("loft_bias", "deg", 1.9),
        ];
        let c = DMatrix::from_row_slice(3, 3, &[1.0, 0.95, 0.98, 0.95, 1.0, 0.1, 0.98, 0.1, 1.0]);
        let a = aliases(&params, Some(&c));
        assert_eq!(a.len(), 2);
        // dy and dz of one effect: the effect is still read; dy and the loft bias: which effect
        // carries the signal is the question.
        assert!(!a[0].across_effects() && a[1].across_effects());
        assert_eq!(effect_of_label("added_mass@A.dm_g"), "added_mass");
        assert_eq!(effect_of_label("loft_bias.deg"), "loft_bias");
    }
}

/// The best physical candidate the final model leaves out whose held-out gain beats its
/// parameters' penalty `k·ln n` but not the selection's (`k·ln n + 2·ln m`): what the data
/// nearly show, with the candidates they cannot tell it from (`search/unresolved.rs`).
#[derive(Debug, Clone, PartialEq)]
pub struct Unresolved {
    /// The candidate (`name` or `name@group`).
    pub label: String,
    /// Its values fitted beside the final model.
    pub params: Vec<ParamEstimate>,
    /// Held-out gain in χ².
    pub gain: f64,
    /// Its full penalty, `k·ln n + 2·ln m`.
    pub penalty: f64,
    /// Other near misses whose fit changed the predictions like its own (`r > 0.9`).
    pub alike: Vec<(String, f64)>,
    /// How many times the shots would have to grow for a gain growing with them to beat the
    /// penalty.
    pub growth: f64,
}

impl Unresolved {
    /// One line of text.
    pub fn text(&self) -> String {
        let alike = if self.alike.is_empty() {
            String::new()
        } else {
            let names: Vec<String> = self
                .alike
                .iter()
                .map(|(l, r)| format!("{l} (r = {r:.2})"))
                .collect();
            format!(
                "; the data cannot tell it from {}, which change the predictions alike",
                names.join(", ")
            )
        };
        format!(
            "not resolved: {} ({}) gains {:.1} held out against a penalty of {:.1}{alike}; about \
             {:.1}× the shots would decide",
            self.label,
            values_text(&self.params),
            self.gain,
            self.penalty,
            self.growth
        )
    }
}
