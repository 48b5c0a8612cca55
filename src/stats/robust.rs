//! Robust location and scale: median, root mean square, normal-consistent MAD.

/// Scale factor making the median absolute deviation a consistent estimator of the standard
/// deviation of a normal distribution: `σ ≈ 1.4826 · MAD`.
pub const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// Root mean square; `NaN` for an empty slice.
pub fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Median (selects in a copy: the same order statistics as sorting, in linear time); `NaN` for
/// an empty slice.
pub fn median(x: &[f64]) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    let mut v = x.to_vec();
    let n = v.len();
    let (below, &mut upper, _) = v.select_nth_unstable_by(n / 2, f64::total_cmp);
    if n % 2 == 1 {
        upper
    } else {
        let lower = below
            .iter()
            .copied()
            .max_by(f64::total_cmp)
            .expect("n is even and > 0");
        0.5 * (lower + upper)
    }
}

/// Robust scale: `1.4826 · median(|x − median(x)|)`, the normal-consistent MAD. Insensitive to
/// a shift of all values (a bias) and to a minority of outliers.
pub fn robust_scale(x: &[f64]) -> f64 {
    let m = median(x);
    let dev: Vec<f64> = x.iter().map(|v| (v - m).abs()).collect();
    MAD_TO_SIGMA * median(&dev)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{mean, std_dev};
    use approx::assert_relative_eq;

    #[test]
    fn location_and_scale() {
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_relative_eq!(mean(&x), 2.5);
        assert_relative_eq!(std_dev(&x), (5.0f64 / 3.0).sqrt());
        assert_relative_eq!(median(&x), 2.5);
        assert_relative_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        // The middle pair of an even count, whatever the order.
        assert_eq!(median(&[9.0, -1.0, 4.0, 2.0, 7.0, 3.0]), 3.5);
        assert_eq!(median(&[5.0, 5.0]), 5.0);
        assert_relative_eq!(rms(&[3.0, 4.0]), (12.5f64).sqrt());
        // A shift does not change the robust scale; an outlier barely does.
        let y = [10.0, 11.0, 12.0, 13.0, 14.0];
        assert_relative_eq!(robust_scale(&y), MAD_TO_SIGMA * 1.0);
        let z = [10.0, 11.0, 12.0, 13.0, 1e6];
        assert_relative_eq!(robust_scale(&z), MAD_TO_SIGMA * 1.0);
    }

    #[test]
    fn robust_scale_of_normal_sample_matches_sigma() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, Normal};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let d = Normal::new(5.0, 2.0).unwrap();
        let x: Vec<f64> = (0..20_000).map(|_| d.sample(&mut rng)).collect();
        assert!((robust_scale(&x) - 2.0).abs() < 0.05);
        assert!((std_dev(&x) - 2.0).abs() < 0.05);
    }
}
