//! Where the balls of a distribution land: the weighted landing points, their mean and 2 × 2
//! covariance, and the dispersion ellipse at a confidence level (bivariate normal: the ellipse
//! `dᵀΣ⁻¹d ≤ χ²₂(p)`, `χ²₂(p) = −2·ln(1 − p)`, semi-axes `√(χ²₂(p)·λᵢ)` along the
//! eigenvectors of `Σ`, area `π·χ²₂(p)·√det Σ`). [`super::yards::yard_metrics`] reports the
//! area; a picture draws the points and the ellipse from this.
//!
//! Pure: no I/O.

/// One landing point of a distribution, yd, with its weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LandingPoint {
    /// Carry: the landing's signed coordinate along the target line, yd.
    pub carry_yd: f64,
    /// Offline: across the target line, yd (+ right).
    pub offline_yd: f64,
    /// Its weight in the distribution (the weights sum to 1 over a pattern).
    pub weight: f64,
}

/// The landing pattern of a distribution: its points and their weighted moments.
#[derive(Debug, Clone, PartialEq)]
pub struct Landing {
    /// Every landing point, weights normalised to sum to 1.
    pub points: Vec<LandingPoint>,
    /// Weighted mean carry, yd.
    pub mean_carry_yd: f64,
    /// Weighted mean offline, yd.
    pub mean_offline_yd: f64,
    /// Weighted (population) covariance `[[carry, carry·offline], [carry·offline, offline]]`,
    /// yd².
    pub cov_yd2: [[f64; 2]; 2],
}

/// The dispersion ellipse of a pattern at a confidence level, yd.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Centre: mean carry, yd.
    pub centre_carry_yd: f64,
    /// Centre: mean offline, yd.
    pub centre_offline_yd: f64,
    /// Semi-major axis, yd (≥ the minor; 0 for a pattern with no spread).
    pub semi_major_yd: f64,
    /// Semi-minor axis, yd (≥ 0).
    pub semi_minor_yd: f64,
    /// Angle of the major axis from the carry direction toward the offline (+ right)
    /// direction, degrees, in (−90, 90].
    pub major_from_carry_deg: f64,
    /// Confidence level, in (0, 1).
    pub confidence: f64,
}

impl Ellipse {
    /// Its area, yd².
    pub fn area_yd2(&self) -> f64 {
        std::f64::consts::PI * self.semi_major_yd * self.semi_minor_yd
    }
}

/// `χ²₂(p)`: the squared Mahalanobis radius of the bivariate-normal ellipse holding `p`.
pub fn chi2_2(confidence: f64) -> f64 {
    -2.0 * (1.0 - confidence).ln()
}

impl Landing {
    /// The pattern of weighted points `(carry yd, offline yd, weight)`; `None` when there is
    /// no point, the total weight is not positive or a value is not finite.
    pub fn of(points: impl IntoIterator<Item = (f64, f64, f64)>) -> Option<Self> {
        let raw: Vec<(f64, f64, f64)> = points.into_iter().collect();
        let sw: f64 = raw.iter().map(|p| p.2).sum();
        let finite = raw
            .iter()
            .all(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite() && p.2 >= 0.0);
        if raw.is_empty() || !finite || !(sw > 0.0 && sw.is_finite()) {
            return None;
        }
        // Raw weights in the sums, divided by their total at the end: the arithmetic the yard
        // metrics have always used, so their figures do not move in the last place.
        let (mut sx, mut sz) = (0.0, 0.0);
        for &(x, z, w) in &raw {
            sx += w * x;
            sz += w * z;
        }
        let (mx, mz) = (sx / sw, sz / sw);
        let (mut vxx, mut vzz, mut vxz) = (0.0, 0.0, 0.0);
        for &(x, z, w) in &raw {
            vxx += w * (x - mx) * (x - mx);
            vzz += w * (z - mz) * (z - mz);
            vxz += w * (x - mx) * (z - mz);
        }
        let (vxx, vzz, vxz) = (vxx / sw, vzz / sw, vxz / sw);
        let points = raw
            .iter()
            .map(|&(x, z, w)| LandingPoint {
                carry_yd: x,
                offline_yd: z,
                weight: w / sw,
            })
            .collect();
        Some(Landing {
            points,
            mean_carry_yd: mx,
            mean_offline_yd: mz,
            cov_yd2: [[vxx, vxz], [vxz, vzz]],
        })
    }

    /// Standard deviation of carry, yd.
    pub fn std_carry_yd(&self) -> f64 {
        self.cov_yd2[0][0].max(0.0).sqrt()
    }

    /// Standard deviation of offline, yd.
    pub fn std_offline_yd(&self) -> f64 {
        self.cov_yd2[1][1].max(0.0).sqrt()
    }

    /// Area of the ellipse at `confidence`, yd²: `π·χ²₂(p)·√det Σ`.
    pub fn ellipse_area_yd2(&self, confidence: f64) -> f64 {
        let [[vxx, vxz], [_, vzz]] = self.cov_yd2;
        let det = (vxx * vzz - vxz * vxz).max(0.0);
        std::f64::consts::PI * chi2_2(confidence) * det.sqrt()
    }

    /// The dispersion ellipse at `confidence` (in (0, 1)), from the covariance's eigenvalues
    /// and eigenvectors.
    pub fn ellipse(&self, confidence: f64) -> Ellipse {
        let [[vxx, vxz], [_, vzz]] = self.cov_yd2;
        let half_sum = 0.5 * (vxx + vzz);
        let root = (0.25 * (vxx - vzz) * (vxx - vzz) + vxz * vxz).sqrt();
        let (l1, l2) = ((half_sum + root).max(0.0), (half_sum - root).max(0.0));
        let k2 = chi2_2(confidence);
        let angle = if root > 0.0 {
            0.5 * (2.0 * vxz).atan2(vxx - vzz)
        } else {
            0.0
        };
        Ellipse {
            centre_carry_yd: self.mean_carry_yd,
            centre_offline_yd: self.mean_offline_yd,
            semi_major_yd: (k2 * l1).sqrt(),
            semi_minor_yd: (k2 * l2).sqrt(),
            major_from_carry_deg: angle.to_degrees(),
            confidence,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ellipse_of_the_covariance_has_the_area_of_the_metrics() {
        // A tilted cloud: carry and offline correlated (long shots go right).
        let pts = [
            (250.0, 5.0, 1.0),
            (240.0, -3.0, 2.0),
            (260.0, 9.0, 1.0),
            (245.0, 4.0, 3.0),
            (255.0, -1.0, 1.5),
        ];
        let l = Landing::of(pts).unwrap();
        let e = l.ellipse(0.95);
        assert!((e.area_yd2() - l.ellipse_area_yd2(0.95)).abs() < 1e-9 * e.area_yd2());
        assert!(e.semi_major_yd >= e.semi_minor_yd && e.semi_minor_yd > 0.0);
        // Long shots go right: the major axis leans from carry toward + offline.
        assert!(e.major_from_carry_deg > 0.0 && e.major_from_carry_deg < 90.0);
        // The major axis is an eigenvector of Σ with eigenvalue a²/χ²₂.
        let (s, c) = e.major_from_carry_deg.to_radians().sin_cos();
        let [[a, b], [_, d]] = l.cov_yd2;
        let lam = e.semi_major_yd.powi(2) / chi2_2(0.95);
        assert!((a * c + b * s - lam * c).abs() < 1e-9 && (b * c + d * s - lam * s).abs() < 1e-9);
        // Weights are normalised; the centre is the weighted mean.
        let sw: f64 = l.points.iter().map(|p| p.weight).sum();
        assert!((sw - 1.0).abs() < 1e-15);
        let mean: f64 = pts.iter().map(|p| p.0 * p.2).sum::<f64>() / 8.5;
        assert!((e.centre_carry_yd - mean).abs() < 1e-12);
    }

    #[test]
    fn an_axis_aligned_cloud_and_degenerate_patterns() {
        // Σ = diag(9, 4): semi-axes 3k and 2k along carry and offline.
        let l = Landing {
            points: vec![],
            mean_carry_yd: 200.0,
            mean_offline_yd: 0.0,
            cov_yd2: [[9.0, 0.0], [0.0, 4.0]],
        };
        let e = l.ellipse(0.95);
        let k = chi2_2(0.95).sqrt();
        assert!((e.semi_major_yd - 3.0 * k).abs() < 1e-12);
        assert!((e.semi_minor_yd - 2.0 * k).abs() < 1e-12);
        assert_eq!(e.major_from_carry_deg, 0.0);
        // One point: no spread, a zero ellipse; bad input is refused, not propagated.
        let one = Landing::of([(230.0, 1.0, 1.0)]).unwrap();
        let e1 = one.ellipse(0.95);
        assert_eq!(
            (e1.semi_major_yd, e1.semi_minor_yd, e1.area_yd2()),
            (0.0, 0.0, 0.0)
        );
        assert!(Landing::of([]).is_none());
        assert!(Landing::of([(f64::NAN, 0.0, 1.0)]).is_none());
        assert!(Landing::of([(1.0, 0.0, 0.0)]).is_none());
    }
}
