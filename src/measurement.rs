//! Measurement error in the delivered inputs: regression calibration of noisy impact locations.
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

    #[test]
    fn noise_larger_than_the_spread_is_an_error() {
        let noise = ImpactNoise::from_mm(50.0, 1.0).unwrap();
        let e = noise.posterior_nodes(&grid()).unwrap_err().to_string();
        assert!(e.contains("σ_y = 50 mm"), "{e}");
        assert!(ImpactNoise::from_mm(-1.0, 0.0).is_err());
        assert!(ImpactNoise::from_mm(f64::NAN, 0.0).is_err());
    }
}
