//! The noise floor: how much scatter of model − measured the instruments alone explain.
//!
//! If the model were right, the errors would still scatter, for two reasons: the launch monitor's
//! own noise on the measured launch (SD `σ_c` per component), and the noise on the measured
//! delivery (SD `s_j` per delivery variable), which the model turns into launch error through its
//! own sensitivities. Linearised around each shot's measured delivery, the expected variance of
//! shot `i`'s error in component `c` is
//!
//! ```text
//! v_ic = σ_c² + Σ_j (∂L_c/∂x_j)² · s_j,eff²
//! ```
//!
//! with `∂L_c/∂x_j` the model's own Jacobian (central differences of the final club's launch in
//! file units). For the impact location, when the model averages over where the ball was most
//! likely struck (regression calibration with noise `σ_m`, given with `--impact-noise-mm` or
//! selected by diagnose, see [`crate::measurement`]), `σ_m` is taken as the true noise: the
//! model's location error is `t − μ_post = k·(t − μ) − (1 − k)·ε` with
//! `k = σ_m²/(σ_T² + σ_m²)` and `σ_T² = var(measured) − σ_m²` (the true spread), whose variance
//! `k²·σ_T² + (1 − k)²·σ_m²` simplifies to the posterior variance `(1 − k)·σ_m²`. Without a
//! location model the instrument's own location SD `s` enters raw (`s_eff = s`).
//!
//! The test: under the model, `S_c = Σ_i (r_ic − r̄_c)² / v_ic` is χ² with `n − 1` degrees of
//! freedom. The report gives the ratio `√(S_c/(n − 1))` (1 when what remains is noise), the
//! expected and observed SD, and the upper-tail p-value (Wilson–Hilferty normal approximation
//! of χ²); beside it, the mean error is tested against its expected standard error
//! (`z = Σ r_i / √Σ v_i`, two-sided), since a bias barely moves the spread. A component where
//! either p-value is below `STRUCTURE_ALPHA / 10` ([`STRUCTURE_ALPHA`] = 1 % shared by the ten
//! tests) carries **unexplained structure**; its standardised errors are then correlated with
//! every delivery variable to say what the structure trends with, and searched for structure
//! no straight line follows (a face map of impact location and club-speed bins, with
//! quadratics: [`shape`]); the shape is named when its test beats every straight line.
//!
//! The verdict is only as good as the instrument noise given: too small a noise invents
//! structure, too large a noise hides it. Defaults per instrument class are in
//! [`InstrumentClass`] and `docs/noise-floor.md`.

use rayon::prelude::*;

use crate::club::ClubSpec;
use crate::fit::{FitData, FitError, FitProblem, GivenScales, ParamLayout, Weighting};
use crate::model::Shot;
use crate::model::{default_launch_noise, delivery_from_file_units, DeliveryVar, N_DELIVERY};
use crate::physics::{Delivery, LaunchComponent};
use crate::stats::{self, tdist::student_t_cdf};

use super::Diagnosis;

pub mod shape;
use self::shape::{ShapeSearch, TERMS_TRIED};

/// Family-wise significance of "structure remains", shared by the five components.
pub const STRUCTURE_ALPHA: f64 = 0.01;

/// Family-wise significance of the trend a component's errors are said to follow, shared by
/// the delivery variables tried.
pub const TREND_ALPHA: f64 = 0.01;

/// A class of instruments with documented default noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InstrumentClass {
    /// A camera-based launch monitor (photometric ball and club data) with marker-based
    /// delivery capture: `smash synth`'s defaults.
    Camera,
    /// A Doppler-radar launch monitor: ball data good, spin axis and club data (face, loft,
    /// impact location) noisier.
    Radar,
}

impl InstrumentClass {
    /// Every class.
    pub const ALL: [InstrumentClass; 2] = [Self::Camera, Self::Radar];

    /// Name on the command line and in files.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Camera => "camera",
            Self::Radar => "radar",
        }
    }

    /// Look a class up by name.
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == s)
    }

    /// The class's default noise (1σ, file units). Reasons: `docs/noise-floor.md`.
    pub fn noise(self) -> InstrumentNoise {
        match self {
            Self::Camera => InstrumentNoise {
                name: self.name().to_owned(),
                launch_sd: LaunchComponent::ALL.map(default_launch_noise),
                delivery_sd: DeliveryVar::ALL.map(DeliveryVar::default_noise),
            },
            Self::Radar => InstrumentNoise {
                name: self.name().to_owned(),
                launch_sd: [0.7, 0.4, 0.6, 150.0, 250.0],
                delivery_sd: DeliveryVar::ALL.map(|v| match v {
                    DeliveryVar::ClubSpeed => 0.8,
                    DeliveryVar::AttackAngle | DeliveryVar::ClubPath => 0.6,
                    DeliveryVar::DynamicLoft | DeliveryVar::FaceAngle => 0.8,
                    DeliveryVar::LieTilt => 1.0,
                    DeliveryVar::OmegaX | DeliveryVar::OmegaY | DeliveryVar::OmegaZ => 1.0,
                    DeliveryVar::ImpactY | DeliveryVar::ImpactZ => 3.0,
                }),
            },
        }
    }
}

/// Instrument noise, 1σ in file units.
#[derive(Debug, Clone, PartialEq)]
pub struct InstrumentNoise {
    /// Where the values come from (a class name, or a file).
    pub name: String,
    /// Launch monitor, per launch component.
    pub launch_sd: [f64; 5],
    /// Delivery measurement, per [`DeliveryVar`] (impact location included).
    pub delivery_sd: [f64; N_DELIVERY],
}

/// The noise-floor verdict for one launch component.
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentFloor {
    /// Component.
    pub component: LaunchComponent,
    /// Mean error, file units.
    pub mean: f64,
    /// Mean error in units of the expected SD.
    pub mean_in_sd: f64,
    /// SD of the errors if the model were right (root mean expected variance), file units.
    pub expected_sd: f64,
    /// Observed SD of the errors, file units.
    pub observed_sd: f64,
    /// `√(S/(n − 1))`: 1 when what remains is noise.
    pub ratio: f64,
    /// Upper-tail p-value of `S` under χ²(n − 1).
    pub p_value: f64,
    /// Two-sided p-value of the mean error under the expected variances
    /// (`z = Σ r_i / √Σ v_i`).
    pub mean_p_value: f64,
    /// Is there unexplained structure (either p-value below `STRUCTURE_ALPHA / 10`)?
    pub structure: bool,
    /// The delivery variable the standardised errors correlate with most, with `r`, when that
    /// correlation is significant ([`TREND_ALPHA`] shared by the variables).
    pub trend: Option<(DeliveryVar, f64)>,
    /// Structure no straight line follows: the face map and club-speed bins of what remains,
    /// their tests, and the term named when one beats every straight line
    /// ([`shape::ShapeSearch::found`]). Reporting only: nothing downstream reads it.
    pub shape: ShapeSearch,
}

impl ComponentFloor {
    /// One line of text: "what remains is noise" or where structure remains.
    pub fn verdict(&self) -> String {
        let name = self.component.column();
        if self.structure && self.p_value >= STRUCTURE_ALPHA / 10.0 {
            format!(
                "unexplained bias remains in {name} (mean {:+.2} expected SD, p = {:.1e})",
                self.mean_in_sd, self.mean_p_value
            )
        } else if self.structure {
            let trend = match (self.shape.words(self.component), self.trend) {
                (Some(words), _) => format!("; follows {}: {words}", self.shape_subject()),
                (None, Some((v, r))) => format!("; trends with {}, r = {r:.2}", v.column()),
                (None, None) => String::new(),
            };
            format!(
                "unexplained structure remains in {name} ({:.2}× the expected spread{trend})",
                self.ratio
            )
        } else if let Some(words) = self.quiet_shape() {
            format!(
                "{name}: the spread is as the noise explains ({:.2}× the expected spread), but it \
                 follows {}: {words}",
                self.ratio,
                self.shape_subject()
            )
        } else {
            format!(
                "{name}: what remains is noise ({:.2}× the expected spread)",
                self.ratio
            )
        }
    }

    /// What the shape found follows, in words.
    fn shape_subject(&self) -> &'static str {
        match self.shape.found {
            Some(t) if t.term.is_face() => "impact location (face map)",
            _ => "club speed (not a straight line)",
        }
    }

    /// The shape of a component without structure, in words, when its test is significant
    /// over the five components too (`TREND_ALPHA / (5 · TERMS_TRIED)`): the spread test can
    /// miss a shape the given noise overstates.
    pub fn quiet_shape(&self) -> Option<String> {
        let t = self.shape.found?;
        let level = TREND_ALPHA / (5 * TERMS_TRIED) as f64;
        (!self.structure && t.p_value < level)
            .then(|| self.shape.words(self.component))
            .flatten()
    }
}

/// The noise floor of a diagnosis.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseFloor {
    /// Instrument noise assumed.
    pub instrument: InstrumentNoise,
    /// Per launch component, in [`LaunchComponent::ALL`] order.
    pub components: Vec<ComponentFloor>,
    /// Shots the spreads were measured on.
    pub n_shots: usize,
    /// Was the instrument noise assumed (a default class) rather than given by the user?
    /// Set by the caller, who knows; `false` from [`noise_floor_of`].
    pub assumed: bool,
}

/// Where an observed-to-expected spread ratio lies (see [`NoiseFloor::spread_band`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpreadBand {
    /// Well below 1: the errors scatter less than the noise assumed, which is too large; the
    /// test cannot see structure of that size.
    WellBelow,
    /// Within the band: as the noise assumed explains.
    Near,
    /// Well above 1: structure remains, or the noise is larger than assumed.
    WellAbove,
}

impl SpreadBand {
    /// `well_below`, `near` or `well_above`.
    pub fn name(self) -> &'static str {
        match self {
            Self::WellBelow => "well_below",
            Self::Near => "near",
            Self::WellAbove => "well_above",
        }
    }
}

impl NoiseFloor {
    /// Half-width of the band around 1 inside which a spread ratio counts as near 1: the larger
    /// of 0.1 and three standard errors of the ratio under the noise (`√(S/ν)` with
    /// `S ~ χ²(ν)`, `ν = n − 1`, has standard error `1/√(2ν)` for large `ν`).
    pub fn band_half_width(&self) -> f64 {
        let nu = (self.n_shots.max(2) - 1) as f64;
        (3.0 / (2.0 * nu).sqrt()).max(0.1)
    }

    /// Where component `c`'s ratio lies relative to 1 (see [`Self::band_half_width`]).
    pub fn spread_band(&self, c: &ComponentFloor) -> SpreadBand {
        let h = self.band_half_width();
        if c.ratio < 1.0 - h {
            SpreadBand::WellBelow
        } else if c.ratio > 1.0 + h {
            SpreadBand::WellAbove
        } else {
            SpreadBand::Near
        }
    }

    /// Does structure remain in any component?
    pub fn structure_remains(&self) -> bool {
        self.components.iter().any(|c| c.structure)
    }
}

/// A delivery in file units, [`DeliveryVar::ALL`] order (inverse of
/// [`delivery_from_file_units`]).
pub fn delivery_to_file_units(d: &Delivery) -> [f64; N_DELIVERY] {
    [
        d.club_speed_m_s / crate::units::M_S_PER_MPH,
        d.attack_angle_rad.to_degrees(),
        d.club_path_rad.to_degrees(),
        d.dynamic_loft_rad.to_degrees(),
        d.face_angle_rad.to_degrees(),
        d.lie_tilt_rad.to_degrees(),
        d.club_omega_rad_s.x,
        d.club_omega_rad_s.y,
        d.club_omega_rad_s.z,
        d.impact_y_m * 1e3,
        d.impact_z_m * 1e3,
    ]
}

/// Upper-tail probability of χ²(ν) at `s` (Wilson–Hilferty).
pub fn chi2_upper_tail(s: f64, nu: f64) -> f64 {
    let a = 2.0 / (9.0 * nu);
    let z = ((s / nu).cbrt() - (1.0 - a)) / a.sqrt();
    1.0 - student_t_cdf(z, 1e9)
}

/// Variance of the measured impact location on each axis (`impact_y_mm`, `impact_z_mm`) over
/// the shots, mm².
pub(super) fn measured_location_variance(shots: &[Shot]) -> [f64; 2] {
    [DeliveryVar::ImpactY, DeliveryVar::ImpactZ].map(|var| {
        let x: Vec<f64> = shots
            .iter()
            .map(|s| delivery_to_file_units(&s.delivery)[var.index()])
            .collect();
        stats::std_dev(&x).powi(2)
    })
}

/// Variance (mm²) of the location error that remains in a model that averages over noisy
/// impact locations with noise `sigma_mm`, when that is the true noise: the posterior variance
/// `(1 − k)·σ²`, `k = σ²/var(measured)` (see the module docs). Without such a model the raw
/// noise `σ²` would remain; with `σ = 0`, nothing.
pub(super) fn corrected_location_variance(sigma_mm: f64, var_measured_mm2: f64) -> f64 {
    let s2 = sigma_mm * sigma_mm;
    let k = (s2 / var_measured_mm2.max(f64::MIN_POSITIVE)).min(1.0);
    (1.0 - k) * s2
}

/// The model's launch (file units) of each shot and its derivatives with respect to each
/// delivery variable (file units per file unit): central differences over `±steps[j]`
/// (one-sided when one side cannot be solved; a zero column when `steps[j]` is 0 or neither
/// side can be solved).
pub(crate) fn delivery_jacobians(
    club: &ClubSpec,
    shots: &[Shot],
    steps: &[f64; N_DELIVERY],
) -> Result<Vec<[[f64; 5]; N_DELIVERY]>, FitError> {
    // Each group's model (or why it cannot be made) first; then the shots side by side, the
    // first failing shot in file order reported, as a pass in order would.
    let mut models = std::collections::BTreeMap::new();
    for s in shots {
        if !models.contains_key(s.group.as_str()) {
            let m = club.model_for_group(&s.group);
            models.insert(s.group.as_str(), m);
        }
    }
    let per_shot: Vec<Result<_, FitError>> = shots
        .par_iter()
        .map(|s| {
            let model = models[s.group.as_str()]
                .as_ref()
                .map_err(|e| FitError::GroupModel {
                    group: s.group.clone(),
                    source: e.clone(),
                })?;
            let x0 = delivery_to_file_units(&s.delivery);
            let launch_at = |x: &[f64; N_DELIVERY]| {
                // The file-unit vector has no shaft mass: carry the shot's own.
                let d = Delivery {
                    shaft_mass_g: s.delivery.shaft_mass_g,
                    ..delivery_from_file_units(x)
                };
                model.solve(&d).ok().map(|o| o.launch().to_file_units())
            };
            let f0 = launch_at(&x0).ok_or_else(|| FitError::Unsolvable {
                shot_id: s.id.clone(),
            })?;
            Ok(std::array::from_fn(|j| {
                let h = steps[j];
                if h <= 0.0 {
                    return [0.0; 5];
                }
                let mut xp = x0;
                xp[j] += h;
                let mut xm = x0;
                xm[j] -= h;
                match (launch_at(&xp), launch_at(&xm)) {
                    (Some(p), Some(m)) => std::array::from_fn(|c| (p[c] - m[c]) / (2.0 * h)),
                    (Some(p), None) => std::array::from_fn(|c| (p[c] - f0[c]) / h),
                    (None, Some(m)) => std::array::from_fn(|c| (f0[c] - m[c]) / h),
                    (None, None) => [0.0; 5],
                }
            }))
        })
        .collect();
    per_shot.into_iter().collect()
}

/// The instruments' noise `inst` as the given scales of a likelihood
/// ([`crate::fit::likelihood`]): each shot's expected error variance per component (see the
/// module docs) with the model `club` (the nominal model, so that every model of the same shots
/// is scored on the same variances) and the location correction `location_model`.
pub fn given_scales(
    club: &ClubSpec,
    shots: &[Shot],
    inst: &InstrumentNoise,
    location_model: Option<crate::measurement::ImpactNoise>,
) -> Result<GivenScales, FitError> {
    let variances = expected_variances(club, shots, inst, location_model)?
        .into_iter()
        .map(|v| v.map(|x| x.max(f64::MIN_POSITIVE)))
        .collect();
    Ok(GivenScales {
        name: inst.name.clone(),
        variances,
    })
}

/// Expected variance of each shot's error per component (see the module docs).
pub fn expected_variances(
    club: &ClubSpec,
    shots: &[Shot],
    inst: &InstrumentNoise,
    location_model: Option<crate::measurement::ImpactNoise>,
) -> Result<Vec<[f64; 5]>, FitError> {
    // Effective SD of the location axes: a location model's noise is taken as the true noise,
    // and only its posterior variance remains; without one, the instrument's raw noise.
    let mut sd_eff = inst.delivery_sd;
    if let Some(m) = location_model {
        let var_meas = measured_location_variance(shots);
        for (a, (var, sigma_m)) in [
            (DeliveryVar::ImpactY, m.sigma_y_m),
            (DeliveryVar::ImpactZ, m.sigma_z_m),
        ]
        .into_iter()
        .enumerate()
        {
            sd_eff[var.index()] = corrected_location_variance(sigma_m * 1e3, var_meas[a]).sqrt();
        }
    }
    // Central differences over ±sd/2.
    let jac = delivery_jacobians(club, shots, &sd_eff.map(|sd| 0.5 * sd))?;
    Ok(jac
        .iter()
        .map(|jac| {
            std::array::from_fn(|c| {
                inst.launch_sd[c].powi(2)
                    + (0..N_DELIVERY)
                        .map(|j| (jac[j][c] * sd_eff[j]).powi(2))
                        .sum::<f64>()
            })
        })
        .collect())
}

/// The noise floor of `errors` (model − measured per shot, file units) of the model `club` on
/// `shots`, with instrument noise `inst` and the model's location correction `location_model`.
pub fn noise_floor_of(
    club: &ClubSpec,
    shots: &[Shot],
    errors: &[[f64; 5]],
    inst: &InstrumentNoise,
    location_model: Option<crate::measurement::ImpactNoise>,
) -> Result<NoiseFloor, FitError> {
    let v = expected_variances(club, shots, inst, location_model)?;
    let n = errors.len();
    let nu = (n.max(2) - 1) as f64;
    let deliveries: Vec<[f64; N_DELIVERY]> = shots
        .iter()
        .map(|s| delivery_to_file_units(&s.delivery))
        .collect();
    let components = LaunchComponent::ALL
        .iter()
        .map(|&comp| {
            let c = comp.index();
            let r: Vec<f64> = errors.iter().map(|e| e[c]).collect();
            let mean = stats::mean(&r);
            let s: f64 = r
                .iter()
                .zip(&v)
                .map(|(ri, vi)| (ri - mean).powi(2) / vi[c].max(f64::MIN_POSITIVE))
                .sum();
            let expected_sd = (v.iter().map(|vi| vi[c]).sum::<f64>() / n as f64).sqrt();
            let p_value = chi2_upper_tail(s, nu);
            let z_mean = r.iter().sum::<f64>() / v.iter().map(|vi| vi[c]).sum::<f64>().sqrt();
            let mean_p_value = 2.0 * (1.0 - student_t_cdf(z_mean.abs(), 1e9));
            let structure = p_value.min(mean_p_value) < STRUCTURE_ALPHA / 10.0;
            let z: Vec<f64> = r
                .iter()
                .zip(&v)
                .map(|(ri, vi)| (ri - mean) / vi[c].sqrt())
                .collect();
            // The variable named is the one the errors correlate with most, and only when that
            // correlation is itself significant (1 % shared by the variables tried): a weak r of
            // a shape no straight line follows names nothing.
            let best = DeliveryVar::ALL
                .iter()
                .filter_map(|&var| {
                    let x: Vec<f64> = deliveries.iter().map(|d| d[var.index()]).collect();
                    stats::pearson(&x, &z).map(|k| (var, k.r, k.p))
                })
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
            let trend = best
                .filter(|&(_, _, p)| p < TREND_ALPHA / N_DELIVERY as f64)
                .map(|(var, r, _)| (var, r));
            let shape = shape::search(&deliveries, &r, &z, best.map_or(1.0, |b| b.2));
            ComponentFloor {
                component: comp,
                mean,
                mean_in_sd: mean / expected_sd,
                expected_sd,
                observed_sd: stats::std_dev(&r),
                ratio: (s / nu).sqrt(),
                p_value,
                mean_p_value,
                structure,
                trend,
                shape,
            }
        })
        .collect();
    Ok(NoiseFloor {
        instrument: inst.clone(),
        components,
        n_shots: n,
        assumed: false,
    })
}

/// The noise floor of a diagnosis's final model on the shots it was made from.
pub fn noise_floor(
    d: &Diagnosis,
    shots: &[Shot],
    inst: &InstrumentNoise,
) -> Result<NoiseFloor, FitError> {
    let data = final_model_data(d, shots)?;
    let errors = launch_errors_of(&d.club, &data)?;
    noise_floor_of(&d.club, shots, &errors, inst, d.impact_noise)
}

/// The shots as the final model of `d` sees them (its delivery- and impact-noise treatment).
pub(super) fn final_model_data(d: &Diagnosis, shots: &[Shot]) -> Result<FitData, FitError> {
    FitData::from_shots(shots)?
        .with_delivery_noise(d.delivery_noise)
        .with_impact_noise(d.impact_noise)
}

/// Model − measured of `club` (its effects applied, nothing free) for every shot, file units.
pub(super) fn launch_errors_of(club: &ClubSpec, data: &FitData) -> Result<Vec<[f64; 5]>, FitError> {
    let (layout, unit) = (ParamLayout::new(Vec::new())?, Weighting::launch(&[1.0; 5]));
    Ok(FitProblem::new(club, layout, data, unit).launch_errors(&[])?)
}

#[cfg(test)]
mod tests;
