//! Measurement error in the delivered inputs: regression calibration of noisy impact locations
//! ([`ImpactNoise`]) and of the other delivery variables ([`DeliveryNoise`]).
//!
//! A launch monitor or motion-capture system measures where the ball met the face with some
//! scatter, `m = t + ε`, `ε ~ N(0, diag(σ_y², σ_z²))`. Speed and spin are curved functions of the
//! location (speed falls roughly with the square of the distance from the sweet spot), so a
//! model evaluated at the *measured* location is biased: it predicts too little speed on
//! average, and its error grows with the measured distance from the centre. Left alone, a fit
//! blames that on physics (an inertia or COR-falloff effect that is not there).
//!
//! The correction here is regression calibration. The true locations of a set of shots are
//! taken as normal, `t ~ N(μ, Σ_t)`, with `μ` the mean measured location and
//! `Σ_t = Cov(m) − Σ_ε` (the measured spread minus the noise). Given a measurement, the true
//! location is then normal with
//!
//! ```text
//! Σ_post = (Σ_t⁻¹ + Σ_ε⁻¹)⁻¹        μ_post = Σ_post (Σ_t⁻¹ μ + Σ_ε⁻¹ m)
//! ```
//!
//! and the model's expected launch is the average over that posterior, taken by a 3 × 3
//! Gauss–Hermite rule (exact for polynomials up to degree 5 in each coordinate; the launch is
//! smooth and nearly quadratic over a few millimetres). Only the measured *locations* enter the
//! prior, never the measured launch, so the correction leaks nothing from outcomes into a
//! cross-validation fold.

use nalgebra::{Matrix2, Vector2, Vector3};

use crate::physics::delivery_vars::{DeliveryVar, N_DELIVERY};
use crate::physics::{Delivery, ImpactError, ImpactModel, ImpactOutcome, Launch, LaunchComponent};

/// 1σ measurement noise of the impact location, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactNoise {
    /// Vertical (up the face), m.
    pub sigma_y_m: f64,
    /// Heel–toe, m.
    pub sigma_z_m: f64,
}

/// Why a noise model cannot be applied to a set of shots.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasurementError {
    /// A σ is negative or not finite.
    #[error(
        "impact noise must be finite and >= 0 mm, got σ_y = {sigma_y_mm} mm, σ_z = {sigma_z_mm} mm"
    )]
    BadSigma {
        /// σ_y, mm.
        sigma_y_mm: f64,
        /// σ_z, mm.
        sigma_z_mm: f64,
    },
    /// The noise is as large as the measured spread: nothing is left for the true spread.
    #[error(
        "impact noise σ_{axis} = {sigma_mm} mm is not smaller than the spread of the measured \
         impact locations ({spread_mm:.2} mm): the true locations would have no spread; \
         check the noise or the data"
    )]
    NoiseExceedsSpread {
        /// `y` or `z`.
        axis: char,
        /// σ given, mm.
        sigma_mm: f64,
        /// Standard deviation of the measured locations, mm.
        spread_mm: f64,
    },
    /// The measured locations barely spread on an axis: no prior can be formed.
    #[error(
        "the measured impact locations do not spread along {axis} (true spread below 1 µm after \
         removing the noise); the impact-noise correction needs shots spread over the face"
    )]
    Degenerate {
        /// `y` or `z`.
        axis: char,
    },
    /// Fewer than three shots: no spread to estimate.
    #[error("at least 3 shots are needed to correct for impact-location noise")]
    TooFewShots,
}

/// One quadrature node: a plausible true location and its weight (weights of a shot sum to 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocationNode {
    /// Vertical location, m.
    pub y_m: f64,
    /// Heel–toe location, m.
    pub z_m: f64,
    /// Weight.
    pub weight: f64,
}

/// Nodes per shot of the 3 × 3 Gauss–Hermite rule.
pub const NODES_PER_SHOT: usize = 9;

/// Gauss–Hermite (probabilists') 3-point rule for N(0, 1): nodes 0, ±√3, weights 2/3, 1/6, 1/6.
const GH3: [(f64, f64); 3] = [
    (-1.732_050_807_568_877_2, 1.0 / 6.0),
    (0.0, 2.0 / 3.0),
    (1.732_050_807_568_877_2, 1.0 / 6.0),
];

impl ImpactNoise {
    /// Noise from σ in mm (each finite and ≥ 0).
    pub fn from_mm(sigma_y_mm: f64, sigma_z_mm: f64) -> Result<Self, MeasurementError> {
        let ok = |s: f64| s.is_finite() && s >= 0.0;
        if !(ok(sigma_y_mm) && ok(sigma_z_mm)) {
            return Err(MeasurementError::BadSigma {
                sigma_y_mm,
                sigma_z_mm,
            });
        }
        Ok(Self {
            sigma_y_m: sigma_y_mm * 1e-3,
            sigma_z_m: sigma_z_mm * 1e-3,
        })
    }

    /// Posterior quadrature nodes of the true impact location of every delivery.
    pub fn nodes_for<'a>(
        &self,
        deliveries: impl IntoIterator<Item = &'a Delivery>,
    ) -> Result<Vec<[LocationNode; NODES_PER_SHOT]>, MeasurementError> {
        let locs: Vec<(f64, f64)> = deliveries
            .into_iter()
            .map(|d| (d.impact_y_m, d.impact_z_m))
            .collect();
        self.posterior_nodes(&locs)
    }

    /// Posterior quadrature nodes of the true location for every measured `(y_m, z_m)`.
    pub fn posterior_nodes(
        &self,
        measured: &[(f64, f64)],
    ) -> Result<Vec<[LocationNode; NODES_PER_SHOT]>, MeasurementError> {
        let n = measured.len();
        if n < 3 {
            return Err(MeasurementError::TooFewShots);
        }
        let mean = measured
            .iter()
            .fold(Vector2::zeros(), |a, &(y, z)| a + Vector2::new(y, z))
            / n as f64;
        let mut cov = Matrix2::zeros();
        for &(y, z) in measured {
            let d = Vector2::new(y, z) - mean;
            cov += d * d.transpose();
        }
        cov /= (n - 1) as f64;
        let noise = Matrix2::new(self.sigma_y_m.powi(2), 0.0, 0.0, self.sigma_z_m.powi(2));
        for (axis, k, s) in [('y', 0, self.sigma_y_m), ('z', 1, self.sigma_z_m)] {
            if s * s >= cov[(k, k)] {
                return Err(MeasurementError::NoiseExceedsSpread {
                    axis,
                    sigma_mm: s * 1e3,
                    spread_mm: cov[(k, k)].sqrt() * 1e3,
                });
            }
        }
        let true_cov = cov - noise;
        for (axis, k) in [('y', 0), ('z', 1)] {
            if !(true_cov[(k, k)] >= 1e-12) {
                return Err(MeasurementError::Degenerate { axis });
            }
        }
        // A true covariance that is not positive definite (strongly correlated measured y and
        // z with large noise) is repaired by dropping the correlation.
        let true_cov = if true_cov.determinant() > 0.0 {
            true_cov
        } else {
            Matrix2::new(true_cov[(0, 0)], 0.0, 0.0, true_cov[(1, 1)])
        };
        let prior_prec = true_cov
            .try_inverse()
            .ok_or(MeasurementError::Degenerate { axis: 'y' })?;
        // Zero noise on an axis: the measurement is the truth on that axis (infinite precision);
        // handled by a tiny floor that leaves the posterior there at the measurement.
        let floor = 1e-24;
        let noise_prec = Matrix2::new(
            1.0 / self.sigma_y_m.powi(2).max(floor),
            0.0,
            0.0,
            1.0 / self.sigma_z_m.powi(2).max(floor),
        );
        let post_cov = (prior_prec + noise_prec)
            .try_inverse()
            .expect("positive definite");
        let chol = post_cov.cholesky().expect("positive definite").l();
        let prior_term = prior_prec * mean;
        Ok(measured
            .iter()
            .map(|&(y, z)| {
                let mu = post_cov * (prior_term + noise_prec * Vector2::new(y, z));
                let mut nodes = [LocationNode {
                    y_m: 0.0,
                    z_m: 0.0,
                    weight: 0.0,
                }; NODES_PER_SHOT];
                for (i, &(a, wa)) in GH3.iter().enumerate() {
                    for (j, &(b, wb)) in GH3.iter().enumerate() {
                        let t = mu + chol * Vector2::new(a, b);
                        nodes[3 * i + j] = LocationNode {
                            y_m: t.x,
                            z_m: t.y,
                            weight: wa * wb,
                        };
                    }
                }
                nodes
            })
            .collect())
    }
}

/// The model's expected launch (SI), ball velocity and spin (G) for delivery `d`: at the measured
/// location when `nodes` is `None`, else the weighted average over the location nodes.
#[inline]
pub fn expected_outcome(
    model: &ImpactModel,
    d: &Delivery,
    nodes: Option<&[LocationNode; NODES_PER_SHOT]>,
) -> Result<(Launch, Vector3<f64>, Vector3<f64>), ImpactError> {
    match nodes {
        None => expected_over(None, |_| model.solve(d)),
        Some(nodes) => expected_over(Some(nodes), |k| {
            model.solve(&Delivery {
                impact_y_m: nodes[k].y_m,
                impact_z_m: nodes[k].z_m,
                ..*d
            })
        }),
    }
}

/// The averaging of [`expected_outcome`] over any way of solving the impact: `solve(k)` is the
/// impact at node `k` (or at the measured location, `k = 0`, when `nodes` is `None`). The fits
/// call it with impacts solved from precomputed frames; both give the same bits.
#[inline]
pub fn expected_over(
    nodes: Option<&[LocationNode; NODES_PER_SHOT]>,
    mut solve: impl FnMut(usize) -> Result<ImpactOutcome, ImpactError>,
) -> Result<(Launch, Vector3<f64>, Vector3<f64>), ImpactError> {
    let Some(nodes) = nodes else {
        let o = solve(0)?;
        return Ok((o.launch(), o.ball_velocity_m_s, o.ball_spin_rad_s));
    };
    let mut acc = [0.0; 5];
    let (mut v, mut w) = (Vector3::zeros(), Vector3::zeros());
    for (k, node) in nodes.iter().enumerate() {
        let o = solve(k)?;
        let l = o.launch();
        for (a, c) in acc.iter_mut().zip(LaunchComponent::ALL) {
            *a += node.weight * l.get_si(c);
        }
        v += node.weight * o.ball_velocity_m_s;
        w += node.weight * o.ball_spin_rad_s;
    }
    let launch = Launch {
        ball_speed_m_s: acc[0],
        launch_angle_rad: acc[1],
        azimuth_rad: acc[2],
        backspin_rad_s: acc[3],
        sidespin_rad_s: acc[4],
    };
    Ok((launch, v, w))
}

/// 1σ measurement noise of the delivery variables other than the impact location (file units,
/// [`DeliveryVar::ALL`] order; the impact-location entries are ignored here: the location is
/// averaged over by [`ImpactNoise`]).
///
/// A slope fitted against a noisy regressor is attenuated, and a model evaluated at the
/// *measured* club speed or loft predicts the full slope where the data, seen through the noise,
/// show a flatter one: the errors trend with the measured delivery by `f′·k·(m − μ)`, `k` the
/// share of the measured spread that is noise. Over a few hundred shots that trend is lost in
/// the launch noise; over thousands an effect that bends the slopes (`cor_power`,
/// `inertia_scale`, a compression lever) fits it and clears the `ln n` penalty. Regression
/// calibration evaluates the model at `E[x_true | measured]` instead.
///
/// The prior of the true values is one-way random effects by golfer (a golfer's swings scatter
/// about that golfer's tendency): `x = μ + b_g + w`, `b_g ~ N(0, τ²)`, `w ~ N(0, ω²)`, measured
/// `m = x + e`, `e ~ N(0, σ²)`. For a golfer with `n` shots and mean measurement `m̄`, with
/// `a = ω² + σ²`, the Gaussian conditional mean is
///
/// ```text
/// E[x_i | m] = μ + (ω²/a)·(m_i − μ) + n·τ²·σ² / (a·(a + n·τ²)) · (m̄ − μ)
/// ```
///
/// (from `Cov(x_i, m) = τ²·1 + ω²·e_i` and `Cov(m) = τ²·11ᵀ + a·I`): a shot shrinks toward its
/// golfer's tendency, itself shrunk toward the grand mean. `μ`, `τ²` and `ω² + σ²` are the
/// one-way ANOVA moment estimates of the measured values (`τ² ≥ 0`, `ω² ≥ 0`); without golfers
/// every shot is its own golfer's only swing and `τ² = 0`, the pooled calibration. Only measured
/// deliveries enter, never outcomes, so nothing leaks into a cross-validation fold. The model is
/// evaluated at the conditional mean (first order: the launch is nearly linear in these
/// variables over the posterior spread, `σ·√(ω²/a)`, less than a degree or a mile an hour).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeliveryNoise {
    /// 1σ per variable, file units (mph, deg, rad/s); impact location ignored.
    pub sd: [f64; N_DELIVERY],
}

impl DeliveryNoise {
    /// Noise from per-variable σ (file units); an entry that is not finite and > 0 is exact.
    pub fn new(sd: [f64; N_DELIVERY]) -> Self {
        Self { sd }
    }

    /// Is any variable (other than the impact location) noisy?
    pub fn is_active(&self) -> bool {
        DeliveryVar::ALL.iter().any(|&v| {
            !matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ) && self.sd[v.index()] > 0.0
        })
    }

    /// The deliveries at the conditional mean of their true values, given every shot's measured
    /// delivery and its golfer (`None` for all: pooled). `golfer_of` has one entry per delivery.
    pub fn calibrate<G: AsRef<str>>(
        &self,
        deliveries: &[Delivery],
        golfer_of: &[Option<G>],
    ) -> Vec<Delivery> {
        let mut out = deliveries.to_vec();
        let n = deliveries.len();
        if n < 3 {
            return out;
        }
        let groups = golfer_groups(golfer_of);
        for v in DeliveryVar::ALL {
            let s2 = self.sd[v.index()].powi(2);
            if matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ)
                || !(s2.is_finite() && s2 > 0.0)
            {
                continue;
            }
            let m: Vec<f64> = deliveries.iter().map(|d| v.file_value(d)).collect();
            let c = RandomEffects::estimate(&m, &groups);
            let omega2 = (c.a - s2).max(0.0);
            let a = c.a.max(s2);
            for g in &groups {
                let k = g.len() as f64;
                let mbar = g.iter().map(|&i| m[i]).sum::<f64>() / k;
                let pull = k * c.tau2 * s2 / (a * (a + k * c.tau2));
                for &i in g {
                    let x = c.mu + omega2 / a * (m[i] - c.mu) + pull * (mbar - c.mu);
                    v.set_file_value(&mut out[i], x);
                }
            }
        }
        out
    }
}

/// Shot indices by golfer (every shot alone when any golfer is unknown).
fn golfer_groups<G: AsRef<str>>(golfer_of: &[Option<G>]) -> Vec<Vec<usize>> {
    if golfer_of.iter().any(Option::is_none) {
        return (0..golfer_of.len()).map(|i| vec![i]).collect();
    }
    let mut by: std::collections::BTreeMap<&str, Vec<usize>> = Default::default();
    for (i, g) in golfer_of.iter().enumerate() {
        by.entry(g.as_ref().map_or("", AsRef::as_ref))
            .or_default()
            .push(i);
    }
    by.into_values().collect()
}

/// One-way random-effects moments of measured values: grand mean, between-golfer variance `τ²`
/// and within-golfer variance `a = ω² + σ²`.
struct RandomEffects {
    mu: f64,
    tau2: f64,
    a: f64,
}

impl RandomEffects {
    fn estimate(m: &[f64], groups: &[Vec<usize>]) -> Self {
        let n = m.len() as f64;
        let g = groups.len() as f64;
        let mu = m.iter().sum::<f64>() / n;
        let means: Vec<f64> = groups
            .iter()
            .map(|gr| gr.iter().map(|&i| m[i]).sum::<f64>() / gr.len() as f64)
            .collect();
        if g >= n {
            // Every shot its own group: no within-golfer replication, pooled variance.
            let var = m.iter().map(|x| (x - mu).powi(2)).sum::<f64>() / (n - 1.0);
            return Self {
                mu,
                tau2: 0.0,
                a: var,
            };
        }
        let mut ss_within = 0.0;
        let mut ss_between = 0.0;
        let mut sum_k2 = 0.0;
        for (gr, &mean) in groups.iter().zip(&means) {
            let k = gr.len() as f64;
            ss_within += gr.iter().map(|&i| (m[i] - mean).powi(2)).sum::<f64>();
            ss_between += k * (mean - mu).powi(2);
            sum_k2 += k * k;
        }
        let a = ss_within / (n - g);
        if g < 2.0 {
            return Self { mu, tau2: 0.0, a };
        }
        let ms_between = ss_between / (g - 1.0);
        let n0 = (n - sum_k2 / n) / (g - 1.0);
        Self {
            mu,
            tau2: ((ms_between - a) / n0).max(0.0),
            a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Vec<(f64, f64)> {
        (0..400)
            .map(|i| {
                (
                    ((i % 20) as f64 - 9.5) * 1e-3,
                    ((i / 20) as f64 - 9.5) * 1.5e-3,
                )
            })
            .collect()
    }

    #[test]
    fn quadrature_integrates_the_posterior_moments() {
        let noise = ImpactNoise::from_mm(2.0, 3.0).unwrap();
        let m = grid();
        let nodes = noise.posterior_nodes(&m).unwrap();
        for ns in &nodes {
            let w: f64 = ns.iter().map(|n| n.weight).sum();
            assert!((w - 1.0).abs() < 1e-15);
        }
        // Shrinkage toward the mean: the posterior mean of an outer shot lies inside it.
        let (i_out, _) = m
            .iter()
            .enumerate()
            .max_by(|a, b| a.1 .0.abs().total_cmp(&b.1 .0.abs()))
            .unwrap();
        let post_y: f64 = nodes[i_out].iter().map(|n| n.weight * n.y_m).sum();
        let mean_y = m.iter().map(|p| p.0).sum::<f64>() / m.len() as f64;
        assert!((post_y - mean_y).abs() < (m[i_out].0 - mean_y).abs());
        // Posterior variance on y: 1/(1/σt² + 1/σε²), σt² = var(m) − σε².
        let var_m = m.iter().map(|p| (p.0 - mean_y).powi(2)).sum::<f64>() / (m.len() - 1) as f64;
        let st2 = var_m - 4e-6;
        let want = 1.0 / (1.0 / st2 + 1.0 / 4e-6);
        let got: f64 = nodes[0]
            .iter()
            .map(|n| n.weight * n.y_m * n.y_m)
            .sum::<f64>()
            - nodes[0]
                .iter()
                .map(|n| n.weight * n.y_m)
                .sum::<f64>()
                .powi(2);
        assert!(
            (got - want).abs() < 1e-9 * want.max(1e-12) + 1e-15,
            "{got} vs {want}"
        );
    }

    #[test]
    fn zero_noise_leaves_locations_as_measured() {
        let noise = ImpactNoise::from_mm(0.0, 0.0).unwrap();
        let m = grid();
        for (ns, &(y, z)) in noise.posterior_nodes(&m).unwrap().iter().zip(&m) {
            for n in ns {
                assert!((n.y_m - y).abs() < 1e-9 && (n.z_m - z).abs() < 1e-9);
            }
        }
    }

    /// Measured club speeds of `golfers` golfers with `swings` each (deterministic scatter).
    fn speeds(golfers: usize, swings: usize) -> (Vec<Delivery>, Vec<Option<String>>) {
        let mut ds = Vec::new();
        let mut who = Vec::new();
        for g in 0..golfers {
            for s in 0..swings {
                let mph = 95.0
                    + 6.0 * ((g * 7 % 11) as f64 - 5.0) / 5.0
                    + 1.5 * ((s * 5 + g) % 7) as f64 / 3.0;
                let mut d =
                    crate::physics::delivery_vars::delivery_from_file_units(&[0.0; N_DELIVERY]);
                DeliveryVar::ClubSpeed.set_file_value(&mut d, mph);
                ds.push(d);
                who.push(Some(format!("G{g}")));
            }
        }
        (ds, who)
    }

    fn club_speed_noise(sd: f64) -> DeliveryNoise {
        let mut s = [0.0; N_DELIVERY];
        s[DeliveryVar::ClubSpeed.index()] = sd;
        DeliveryNoise::new(s)
    }

    #[test]
    fn delivery_calibration_is_the_gaussian_conditional_mean() {
        // Independent check of the closed form: E[x | m] = μ + Cov(x, m)·Cov(m)⁻¹·(m − μ) by a
        // dense solve for one golfer's shots, with the same moment estimates.
        let (ds, who) = speeds(12, 6);
        let sd = 0.9;
        let got = club_speed_noise(sd).calibrate(&ds, &who);
        let m: Vec<f64> = ds
            .iter()
            .map(|d| DeliveryVar::ClubSpeed.file_value(d))
            .collect();
        let groups = golfer_groups(&who);
        let c = RandomEffects::estimate(&m, &groups);
        assert!(c.tau2 > 0.0 && c.a > sd * sd);
        let omega2 = c.a - sd * sd;
        for g in &groups {
            let k = g.len();
            let cov_m =
                nalgebra::DMatrix::from_fn(k, k, |i, j| c.tau2 + if i == j { c.a } else { 0.0 });
            let dev = nalgebra::DVector::from_fn(k, |i, _| m[g[i]] - c.mu);
            let sol = cov_m.lu().solve(&dev).unwrap();
            for (i, &shot) in g.iter().enumerate() {
                let cov_xm = nalgebra::DVector::from_fn(k, |j, _| {
                    c.tau2 + if i == j { omega2 } else { 0.0 }
                });
                let want = c.mu + cov_xm.dot(&sol);
                let have = DeliveryVar::ClubSpeed.file_value(&got[shot]);
                assert!((have - want).abs() < 1e-9, "{have} vs {want}");
            }
        }
    }

    #[test]
    fn delivery_calibration_without_golfers_is_the_pooled_attenuation() {
        let (ds, _) = speeds(12, 6);
        let none: Vec<Option<String>> = vec![None; ds.len()];
        let sd = 0.9;
        let got = club_speed_noise(sd).calibrate(&ds, &none);
        let m: Vec<f64> = ds
            .iter()
            .map(|d| DeliveryVar::ClubSpeed.file_value(d))
            .collect();
        let n = m.len() as f64;
        let mu = m.iter().sum::<f64>() / n;
        let var = m.iter().map(|x| (x - mu).powi(2)).sum::<f64>() / (n - 1.0);
        let keep = 1.0 - sd * sd / var;
        for (d, x) in got.iter().zip(&m) {
            let want = mu + keep * (x - mu);
            assert!((DeliveryVar::ClubSpeed.file_value(d) - want).abs() < 1e-9);
        }
        // Other variables, and no noise at all, leave the deliveries as measured.
        assert_eq!(club_speed_noise(0.0).calibrate(&ds, &none), ds);
        assert!(!club_speed_noise(0.0).is_active());
        let mut loc = [0.0; N_DELIVERY];
        loc[DeliveryVar::ImpactY.index()] = 2.0;
        assert!(!DeliveryNoise::new(loc).is_active());
        assert_eq!(DeliveryNoise::new(loc).calibrate(&ds, &none), ds);
    }

    #[test]
    fn noise_larger_than_the_spread_is_an_error() {
        let noise = ImpactNoise::from_mm(50.0, 1.0).unwrap();
        let e = noise.posterior_nodes(&grid()).unwrap_err().to_string();
        assert!(e.contains("σ_y = 50 mm"), "{e}");
        assert!(ImpactNoise::from_mm(-1.0, 0.0).is_err());
        assert!(ImpactNoise::from_mm(f64::NAN, 0.0).is_err());
    }
}
