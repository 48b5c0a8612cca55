//! One scale for comparing models: the Gaussian log-likelihood of the launch errors.
//!
//! The fits whiten their residuals with noise scales estimated from their own errors (what the
//! optimiser and the standard errors need), so the χ² of two fits are sums over different
//! scales and cannot be compared. Models are compared instead by the likelihood of the errors
//! `e_ic` (model − measured, shot `i`, launch component `c`, file units) under independent
//! Gaussian noise, with each component's scale either
//!
//! - **given** ([`GivenScales`]: per shot and component a variance `v_ic` fixed before any fit,
//!   from the instruments' noise): `−2 ln L = Σ_ic [e_ic²/v_ic + ln(2π·v_ic)]`, the χ² with those
//!   scales plus a constant that is the same for every model of the same shots; or
//! - **profiled** (estimated in the fit by maximum likelihood, `σ̂_c² = RSS_c/n_c` with
//!   `RSS_c = Σ_i e_ic²`): `−2 ln L = Σ_c n_c·(ln(2π·σ̂_c²) + 1)`.
//!
//! Either way the value depends only on the errors of the model being scored (and the given
//! variances), never on the scales another fit estimated, so the nominal model scores the same
//! in every run on the same shots, and a candidate that fits better scores lower.
//! `AIC = −2 ln L + 2k` and `BIC = −2 ln L + k·ln N`, `N` the number of residuals (shots × 5)
//! and `k` the fitted parameters, plus the five scales when they are profiled (for every model
//! alike, the nominal one included).

/// Smallest profiled variance, file units² (guards a model that fits noiseless data exactly:
/// `ln 0` would be −∞).
const MIN_VARIANCE: f64 = 1e-24;

/// Noise variances fixed before any fit: per shot and launch component, file units².
#[derive(Debug, Clone, PartialEq)]
pub struct GivenScales {
    /// Where they come from (an instrument class's name or a noise file's), for reports.
    pub name: String,
    /// Per shot, in launch component order, the expected variance of the error.
    pub variances: Vec<[f64; 5]>,
}

impl GivenScales {
    /// The root-mean variance of each component: the scale reports print.
    pub fn scales(&self) -> [f64; 5] {
        let n = self.variances.len().max(1) as f64;
        std::array::from_fn(|c| (self.variances.iter().map(|v| v[c]).sum::<f64>() / n).sqrt())
    }
}

/// How the scales of a [`Likelihood`] were set.
#[derive(Debug, Clone, PartialEq)]
pub enum ScaleSource {
    /// Estimated in each fit (maximum likelihood, `σ̂_c² = RSS_c/n_c`); `k` counts them.
    Profiled,
    /// Given before any fit; the name of where they come from.
    Given(String),
}

impl ScaleSource {
    /// `profiled` or `given`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Profiled => "profiled",
            Self::Given(_) => "given",
        }
    }

    /// The given scales' source (`None` when profiled).
    pub fn name(&self) -> Option<&str> {
        match self {
            Self::Profiled => None,
            Self::Given(n) => Some(n),
        }
    }
}

/// The likelihood score of one model's errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Likelihood {
    /// How the scales were set.
    pub source: ScaleSource,
    /// Noise scale of each launch component, file units: the profiled `σ̂_c`, or the given
    /// variances' root mean.
    pub scales: [f64; 5],
    /// `−2 ln L`.
    pub minus_2_ln_l: f64,
    /// Residuals `N` (shots × 5).
    pub n_residuals: usize,
    /// Parameters counted: the fitted ones, plus 5 when the scales are profiled.
    pub k: usize,
}

impl Likelihood {
    /// Score `errors` (model − measured, one array a shot, file units) of a model with
    /// `n_params` fitted parameters: with `given` variances (one array a shot, the same shots)
    /// or, without, profiled scales.
    ///
    /// # Panics
    /// When `given` holds another number of shots than `errors`.
    pub fn of(errors: &[[f64; 5]], n_params: usize, given: Option<&GivenScales>) -> Self {
        let n_residuals = errors.len() * 5;
        match given {
            Some(g) => {
                assert_eq!(g.variances.len(), errors.len(), "one variance row a shot");
                let two_pi = std::f64::consts::TAU;
                let minus_2_ln_l = errors
                    .iter()
                    .zip(&g.variances)
                    .flat_map(|(e, v)| (0..5).map(move |c| (e[c], v[c])))
                    .map(|(e, v)| e * e / v + (two_pi * v).ln())
                    .sum();
                Self {
                    source: ScaleSource::Given(g.name.clone()),
                    scales: g.scales(),
                    minus_2_ln_l,
                    n_residuals,
                    k: n_params,
                }
            }
            None => {
                let n = errors.len() as f64;
                let var: [f64; 5] = std::array::from_fn(|c| {
                    (errors.iter().map(|e| e[c] * e[c]).sum::<f64>() / n).max(MIN_VARIANCE)
                });
                let minus_2_ln_l = var
                    .iter()
                    .map(|v| n * ((std::f64::consts::TAU * v).ln() + 1.0))
                    .sum();
                Self {
                    source: ScaleSource::Profiled,
                    scales: var.map(f64::sqrt),
                    minus_2_ln_l,
                    n_residuals,
                    k: n_params + 5,
                }
            }
        }
    }

    /// The same score with `extra` more parameters counted (a noise level chosen from the data).
    pub fn with_extra_params(mut self, extra: usize) -> Self {
        self.k += extra;
        self
    }

    /// `−2 ln L + 2k`.
    pub fn aic(&self) -> f64 {
        self.minus_2_ln_l + 2.0 * self.k as f64
    }

    /// `−2 ln L + k·ln N`.
    pub fn bic(&self) -> f64 {
        self.minus_2_ln_l + self.k as f64 * (self.n_residuals as f64).ln()
    }

    /// Is every number finite?
    pub fn is_finite(&self) -> bool {
        self.minus_2_ln_l.is_finite() && self.scales.iter().all(|s| s.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn errors() -> Vec<[f64; 5]> {
        (0..40)
            .map(|i| {
                let x = i as f64;
                [
                    (x * 0.37).sin(),
                    0.5 * (x * 1.3).cos(),
                    0.2 * x.sin(),
                    300.0 * (x * 0.7).cos(),
                    150.0 * (x * 0.11).sin(),
                ]
            })
            .collect()
    }

    /// Profiled: the maximum over the scales of the Gaussian likelihood, so any other fixed
    /// scale scores worse, and at the profiled scales the given formula agrees.
    #[test]
    fn profiled_is_the_given_formula_at_its_own_scales_and_beats_any_other() {
        let e = errors();
        let p = Likelihood::of(&e, 2, None);
        assert_eq!(p.k, 7);
        assert_eq!(p.n_residuals, 200);
        let at = |f: f64| GivenScales {
            name: "test".into(),
            variances: vec![p.scales.map(|s| (f * s).powi(2)); e.len()],
        };
        let same = Likelihood::of(&e, 2, Some(&at(1.0)));
        assert!((same.minus_2_ln_l - p.minus_2_ln_l).abs() < 1e-9 * p.minus_2_ln_l.abs());
        assert_eq!(same.k, 2);
        for f in [0.8, 0.95, 1.05, 1.3] {
            assert!(Likelihood::of(&e, 2, Some(&at(f))).minus_2_ln_l > p.minus_2_ln_l);
        }
        assert_eq!(p.aic(), p.minus_2_ln_l + 14.0);
        assert_eq!(p.bic(), p.minus_2_ln_l + 7.0 * 200f64.ln());
    }

    /// Given: χ² with the variances plus the constant Σ ln(2π v), by hand.
    #[test]
    fn given_is_chi2_plus_the_constant() {
        let e = vec![[1.0, 0.0, 2.0, 0.0, 0.0], [0.0, -1.0, 0.0, 3.0, 0.0]];
        let v = vec![[1.0, 4.0, 4.0, 9.0, 1.0], [1.0, 4.0, 4.0, 9.0, 1.0]];
        let g = GivenScales {
            name: "t".into(),
            variances: v.clone(),
        };
        let l = Likelihood::of(&e, 0, Some(&g));
        let chi2 = 1.0 + 1.0 + 0.25 + 1.0;
        let c: f64 = v
            .iter()
            .flatten()
            .map(|x| (std::f64::consts::TAU * x).ln())
            .sum();
        assert!((l.minus_2_ln_l - (chi2 + c)).abs() < 1e-12);
        assert_eq!(l.source.kind(), "given");
        assert_eq!(l.scales[1], 2.0);
    }

    /// Smaller errors score lower on either scale, and a perfect fit stays finite.
    #[test]
    fn better_fits_score_lower_and_a_perfect_fit_is_finite() {
        let e = errors();
        let half: Vec<[f64; 5]> = e.iter().map(|r| r.map(|x| 0.5 * x)).collect();
        assert!(
            Likelihood::of(&half, 0, None).minus_2_ln_l < Likelihood::of(&e, 0, None).minus_2_ln_l
        );
        assert!(Likelihood::of(&[[0.0; 5]; 3], 0, None).is_finite());
    }
}
