//! A finding must hold in every part of the shots: stability across independent strata.
//!
//! A parameter that reads real physics has one value however the shots are cut; a stand-in
//! (a parameter absorbing physics the model lacks) drifts, because what it compensates for
//! differs between strata — an inertia error standing in for a face-curvature error reads
//! differently in heel and in toe strikes. So the final model is refitted on each stratum of
//! each family, the shots cut
//!
//! - by club speed into terciles (slow, middle, fast),
//! - by impact height into the lower and upper half of the strikes (at the median),
//! - by heel-toe impact into the heel-side and toe-side half (at the median),
//! - by group (when there are several; not for a per-group parameter),
//! - by session (the date column's sessions, when there are several),
//!
//! each fit started from the all-shots values with the all-shots noise scales, a stratum with
//! fewer than [`MIN_STRATUM_SHOTS`] shots (or ten a parameter) left out. All the shots are
//! refitted the same way as a reference row (the reported values come from a fit whose noise
//! scales were estimated one round earlier; for a stand-in that can move the value). For each parameter and
//! family, the strata values `v_s ± se_s` are tested for one common value: with `v̄` the
//! inverse-variance weighted mean, `χ² = Σ_s (v_s − v̄)²/se_s²` is χ² with `S − 1` degrees of
//! freedom under the hypothesis. A check fails when its upper-tail p-value is below
//! [`STRATA_ALPHA`] divided by the number of checks made (Bonferroni over parameters and
//! families); a value that would be a finding is then *provisional*, with the failed check named
//! ("inertia_scale.s: 1.05 in heel-side strikes, 1.19 in toe-side strikes").

use nalgebra::DVector;
use rayon::prelude::*;

use super::noise_floor::chi2_upper_tail;
use crate::fit::{covariance, fit_quietly, FitData, ParamEstimate, ParamLayout, Weighting};
use crate::stats::KeyKind;

/// Family-wise significance of "the strata disagree", shared by every check of a diagnosis.
pub const STRATA_ALPHA: f64 = 0.01;

/// Fewest shots a stratum needs to be fitted.
pub const MIN_STRATUM_SHOTS: usize = 30;

/// One stratum's fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Stratum {
    /// What it holds ("slow (club speed < 98.2 mph)").
    pub label: String,
    /// Shots in it.
    pub n: usize,
    /// Per parameter of the model (layout order): value and standard error, `None` when the
    /// fit failed or the parameter is not identifiable there.
    pub values: Vec<Option<(f64, f64)>>,
}

/// One parameter's test in one family.
#[derive(Debug, Clone, PartialEq)]
pub struct Consistency {
    /// `Σ (v_s − v̄)²/se_s²`.
    pub chi2: f64,
    /// Strata compared minus one.
    pub dof: usize,
    /// Upper-tail p-value of `chi2`.
    pub p_value: f64,
    /// Is `p_value` at or above the per-check threshold?
    pub stable: bool,
}

impl Consistency {
    /// `= 2.1e-6`, or `< 1e-15` below what the tail approximation resolves.
    pub fn p_text(&self) -> String {
        if self.p_value < 1e-15 {
            "< 1e-15".to_owned()
        } else {
            format!("= {:.1e}", self.p_value)
        }
    }
}

/// One way of cutting the shots.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// Its name ("club speed terciles").
    pub name: String,
    /// Its strata (those with enough shots).
    pub strata: Vec<Stratum>,
    /// Per parameter (layout order): the test, `None` when fewer than two strata have a value
    /// (or the cut does not apply to the parameter).
    pub checks: Vec<Option<Consistency>>,
}

/// The strata check of a diagnosis's final model.
#[derive(Debug, Clone, PartialEq)]
pub struct StrataCheck {
    /// Parameter labels (`effect.param`, `effect@group.param`), layout order.
    pub params: Vec<String>,
    /// The families.
    pub families: Vec<Family>,
    /// The threshold each check's p-value is held to: [`STRATA_ALPHA`] / checks made.
    pub alpha_each: f64,
}

impl StrataCheck {
    /// The first failed check of parameter `label`, as text ("inertia_scale.s: 1.05 ± 0.02 in
    /// heel-side strikes, 1.19 ± 0.03 in toe-side strikes (p = 2.1e-6)"); `None` when it passed
    /// every check made.
    pub fn failed(&self, label: &str) -> Option<String> {
        let j = self.params.iter().position(|p| p == label)?;
        self.families.iter().find_map(|f| {
            let c = f.checks[j].as_ref().filter(|c| !c.stable)?;
            let values: Vec<String> = f
                .strata
                .iter()
                .filter_map(|s| {
                    s.values[j].map(|(v, se)| format!("{} ± {} in {}", num(v), num(se), s.label))
                })
                .collect();
            Some(format!(
                "{label} differs across {}: {} (p {})",
                f.name,
                values.join(", "),
                c.p_text()
            ))
        })
    }
}

/// A value in 4 significant figures, scientific when small.
fn num(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else {
        format!("{x:.4}")
    }
}

/// A way of cutting the shots: its name, and per stratum its label and shot indices.
pub(super) type Cut = (String, Vec<(String, Vec<usize>)>);

/// The cuts of `data`, as the module docs list them; `session_keys` the shots' session keys
/// when known.
pub(super) fn families(data: &FitData, session_keys: Option<&crate::stats::FoldKeys>) -> Vec<Cut> {
    let n = data.len();
    // The reference: every shot, fitted the strata's way (their start and noise scales); one
    // stratum, so no test.
    let mut out = vec![(
        "all shots".to_owned(),
        vec![("all shots, refitted alike".to_owned(), (0..n).collect())],
    )];
    let by = |x: &[f64]| -> Vec<usize> {
        let mut idx: Vec<usize> = (0..n).collect();
        idx.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
        idx
    };
    let speed_mph: Vec<f64> = data
        .deliveries
        .iter()
        .map(|d| d.club_speed_m_s / crate::units::M_S_PER_MPH)
        .collect();
    let order = by(&speed_mph);
    let cut = |k: usize| speed_mph[order[(k * n / 3).min(n - 1)]];
    out.push((
        "club speed terciles".to_owned(),
        vec![
            (
                format!("slow (< {:.1} mph)", cut(1)),
                order[..n / 3].to_vec(),
            ),
            ("middle".to_owned(), order[n / 3..2 * n / 3].to_vec()),
            (
                format!("fast (≥ {:.1} mph)", cut(2)),
                order[2 * n / 3..].to_vec(),
            ),
        ],
    ));
    for (name, lo, hi, mm) in [
        (
            "impact height",
            "low",
            "high",
            data.deliveries
                .iter()
                .map(|d| d.impact_y_m * 1e3)
                .collect::<Vec<_>>(),
        ),
        (
            "heel-toe impact",
            "heel-side",
            "toe-side",
            data.deliveries
                .iter()
                .map(|d| d.impact_z_m * 1e3)
                .collect::<Vec<_>>(),
        ),
    ] {
        let order = by(&mm);
        let median = mm[order[n / 2]];
        out.push((
            format!("{name} halves"),
            vec![
                (
                    format!("{lo} strikes (< {median:.1} mm)"),
                    order[..n / 2].to_vec(),
                ),
                (format!("{hi} strikes"), order[n / 2..].to_vec()),
            ],
        ));
    }
    if data.groups.len() > 1 {
        let strata = (0..data.groups.len())
            .map(|g| {
                let idx = (0..n).filter(|&i| data.group_of[i] == g).collect();
                (format!("group {}", data.groups[g]), idx)
            })
            .collect();
        out.push(("groups".to_owned(), strata));
    }
    if let Some(k) = session_keys.filter(|k| k.kind == KeyKind::Session && k.keys.len() == n) {
        let mut names: Vec<&String> = k.keys.iter().collect();
        names.sort_unstable();
        names.dedup();
        if names.len() > 1 {
            let strata = names
                .iter()
                .map(|s| {
                    let idx = (0..n).filter(|&i| &&k.keys[i] == s).collect();
                    (format!("session {s}"), idx)
                })
                .collect();
            out.push(("sessions".to_owned(), strata));
        }
    }
    out
}

/// Refit `layout` (at `theta`, the all-shots solution, whitened with `sigma`) of `club` on every
/// stratum of `cuts` and test each parameter's values for one common value (module docs).
pub(super) fn check(
    club: &crate::club::ClubSpec,
    data: &FitData,
    (layout, theta, sigma): (&ParamLayout, &DVector<f64>, [f64; 5]),
    estimates: &[ParamEstimate],
    cuts: Vec<Cut>,
    max_iters: u64,
) -> StrataCheck {
    let p = layout.len();
    let min_shots = MIN_STRATUM_SHOTS.max(10 * p);
    let (lower, upper) = (layout.lower(), layout.upper());
    let ranges: Vec<f64> = (0..p).map(|j| upper[j] - lower[j]).collect();
    let fit = |idx: &[usize]| -> Vec<Option<(f64, f64)>> {
        let sub = data.subset(idx);
        let w = Weighting::launch(&sigma);
        match fit_quietly(club, layout, &sub, w, theta, max_iters) {
            Ok(run) if run.converged => {
                let dof = (run.residuals.len().saturating_sub(p)).max(1);
                let cov = covariance(&run.jacobian, run.cost / dof as f64, &ranges);
                (0..p)
                    .map(|j| {
                        cov.stderr[j]
                            .filter(|s| *s > 0.0)
                            .map(|s| (run.theta[j], s))
                    })
                    .collect()
            }
            _ => vec![None; p],
        }
    };
    let mut families: Vec<Family> = cuts
        .into_par_iter()
        .map(|(name, strata)| {
            let strata: Vec<Stratum> = strata
                .into_par_iter()
                .filter(|(_, idx)| idx.len() >= min_shots)
                .map(|(label, idx)| Stratum {
                    label,
                    n: idx.len(),
                    values: fit(&idx),
                })
                .collect();
            Family {
                name,
                strata,
                checks: Vec::new(),
            }
        })
        .collect();
    // A per-group parameter has no value outside its group: not cut by group.
    let per_group: Vec<bool> = estimates.iter().map(|e| e.group.is_some()).collect();
    let tests: Vec<Vec<Option<(f64, usize)>>> = families
        .iter()
        .map(|f| {
            (0..p)
                .map(|j| {
                    (!(per_group[j] && f.name == "groups"))
                        .then(|| spread(f, j))
                        .flatten()
                })
                .collect()
        })
        .collect();
    let made = tests.iter().flatten().flatten().count().max(1);
    let alpha_each = STRATA_ALPHA / made as f64;
    for (f, t) in families.iter_mut().zip(tests) {
        f.checks = t
            .into_iter()
            .map(|c| {
                c.map(|(chi2, dof)| {
                    let p_value = chi2_upper_tail(chi2, dof as f64);
                    Consistency {
                        chi2,
                        dof,
                        p_value,
                        stable: p_value >= alpha_each,
                    }
                })
            })
            .collect();
    }
    StrataCheck {
        params: estimates.iter().map(ParamEstimate::label).collect(),
        families,
        alpha_each,
    }
}

/// `(Σ (v_s − v̄)²/se_s², S − 1)` of parameter `j` over the strata of `f` with a value; `None`
/// with fewer than two.
fn spread(f: &Family, j: usize) -> Option<(f64, usize)> {
    let vs: Vec<(f64, f64)> = f.strata.iter().filter_map(|s| s.values[j]).collect();
    if vs.len() < 2 {
        return None;
    }
    let w: f64 = vs.iter().map(|(_, se)| se.powi(-2)).sum();
    let mean = vs.iter().map(|(v, se)| v / (se * se)).sum::<f64>() / w;
    let chi2 = vs.iter().map(|(v, se)| ((v - mean) / se).powi(2)).sum();
    Some((chi2, vs.len() - 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn family(values: &[(f64, f64)]) -> Family {
        Family {
            name: "heel-toe impact halves".into(),
            strata: values
                .iter()
                .enumerate()
                .map(|(i, v)| Stratum {
                    label: format!("s{i}"),
                    n: 100,
                    values: vec![Some(*v)],
                })
                .collect(),
            checks: Vec::new(),
        }
    }

    /// The weighted spread by hand: values 1 ± 0.1 and 1.3 ± 0.1 have mean 1.15 and
    /// χ² = 2·1.5² = 4.5 on one degree of freedom; one stratum gives no test.
    #[test]
    fn spread_is_the_weighted_chi2_about_the_weighted_mean() {
        let (chi2, dof) = spread(&family(&[(1.0, 0.1), (1.3, 0.1)]), 0).unwrap();
        assert!((chi2 - 4.5).abs() < 1e-12, "{chi2}");
        assert_eq!(dof, 1);
        // Unequal errors: the precise value pulls the mean.
        let (chi2, _) = spread(&family(&[(1.0, 0.1), (2.0, 1.0)]), 0).unwrap();
        let mean = (1.0 / 0.01 + 2.0) / (100.0 + 1.0);
        let want = ((1.0 - mean) / 0.1f64).powi(2) + (2.0 - mean).powi(2);
        assert!((chi2 - want).abs() < 1e-12);
        assert!(spread(&family(&[(1.0, 0.1)]), 0).is_none());
    }

    /// A failed check names the parameter, the family and every stratum's value.
    #[test]
    fn a_failed_check_names_the_strata_values() {
        let mut f = family(&[(1.05, 0.02), (1.19, 0.03)]);
        f.checks = vec![Some(Consistency {
            chi2: 15.0,
            dof: 1,
            p_value: 1e-4,
            stable: false,
        })];
        let c = StrataCheck {
            params: vec!["inertia_scale.s".into()],
            families: vec![f],
            alpha_each: 0.001,
        };
        assert_eq!(
            c.failed("inertia_scale.s").unwrap(),
            "inertia_scale.s differs across heel-toe impact halves: 1.0500 ± 0.0200 in s0, \
             1.1900 ± 0.0300 in s1 (p = 1.0e-4)"
        );
        assert_eq!(c.failed("loft_bias.deg"), None);
    }
}
