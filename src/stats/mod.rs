//! Pure numerics for fitting and reports: location and scale, robust scale, correlation,
//! straight-line regression, the Table-2 error statistics, and deterministic grouped k-fold
//! assignment. No I/O, no randomness that is not seeded by the inputs.

pub mod error_table;

pub use error_table::{launch_error_table, ErrorTable, GroupErrors, MeanStd};

/// Scale factor making the median absolute deviation a consistent estimator of the standard
/// deviation of a normal distribution: `σ ≈ 1.4826 · MAD`.
pub const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// Arithmetic mean; `NaN` for an empty slice.
pub fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Sample standard deviation (denominator `n − 1`); `0` for fewer than two values.
pub fn std_dev(x: &[f64]) -> f64 {
    if x.len() < 2 {
        return 0.0;
    }
    let m = mean(x);
    (x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
}

/// Root mean square; `NaN` for an empty slice.
pub fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Median (sorts a copy); `NaN` for an empty slice.
pub fn median(x: &[f64]) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Robust scale: `1.4826 · median(|x − median(x)|)`, the normal-consistent MAD. Insensitive to
/// a shift of all values (a bias) and to a minority of outliers.
pub fn robust_scale(x: &[f64]) -> f64 {
    let m = median(x);
    let dev: Vec<f64> = x.iter().map(|v| (v - m).abs()).collect();
    MAD_TO_SIGMA * median(&dev)
}

/// t statistic of an estimate: `value / stderr` (`NaN` when the standard error is not positive).
pub fn t_statistic(value: f64, stderr: f64) -> f64 {
    if stderr > 0.0 {
        value / stderr
    } else {
        f64::NAN
    }
}

/// Pearson correlation coefficient of paired samples; `NaN` when either has no spread.
pub fn pearson(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len(), "pearson: paired samples");
    let (mx, my) = (mean(x), mean(y));
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    if sxx > 0.0 && syy > 0.0 {
        sxy / (sxx * syy).sqrt()
    } else {
        f64::NAN
    }
}

/// Least-squares straight line `y = intercept + slope·x` and the correlation `r`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    /// Slope, units of y per unit of x.
    pub slope: f64,
    /// Intercept, units of y.
    pub intercept: f64,
    /// Pearson correlation of x and y.
    pub r: f64,
    /// Number of points.
    pub n: usize,
}

/// Ordinary least-squares line through paired points; `None` with fewer than two distinct x.
pub fn linear_regression(x: &[f64], y: &[f64]) -> Option<LineFit> {
    assert_eq!(x.len(), y.len(), "linear_regression: paired samples");
    let (mx, my) = (mean(x), mean(y));
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    if x.len() < 2 || !(sxx > 0.0) {
        return None;
    }
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let slope = sxy / sxx;
    Some(LineFit {
        slope,
        intercept: my - slope * mx,
        r: pearson(x, y),
        n: x.len(),
    })
}

/// Fold of each item for k-fold cross-validation where items sharing a key (a golfer) always
/// fall in the same fold. Distinct keys are sorted and dealt round-robin, so the assignment is
/// deterministic and the folds hold as equal a number of keys as possible.
///
/// Returns one fold index in `0..k` per item. `k` is capped at the number of distinct keys.
pub fn grouped_folds<S: AsRef<str>>(keys: &[S], k: usize) -> Vec<usize> {
    let mut distinct: Vec<&str> = keys.iter().map(AsRef::as_ref).collect();
    distinct.sort_unstable();
    distinct.dedup();
    let k = k.clamp(1, distinct.len().max(1));
    keys.iter()
        .map(|key| {
            let pos = distinct
                .binary_search(&key.as_ref())
                .expect("key is in the list");
            pos % k
        })
        .collect()
}

/// Shot-level fold assignment (no grouping): item `i` goes to fold `i mod k`.
pub fn item_folds(n: usize, k: usize) -> Vec<usize> {
    let k = k.clamp(1, n.max(1));
    (0..n).map(|i| i % k).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn location_and_scale() {
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_relative_eq!(mean(&x), 2.5);
        assert_relative_eq!(std_dev(&x), (5.0f64 / 3.0).sqrt());
        assert_relative_eq!(median(&x), 2.5);
        assert_relative_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
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

    #[test]
    fn regression_recovers_a_line() {
        let x = [74.5, 60.3, 70.9];
        let y: Vec<f64> = x.iter().map(|v| 0.1 * v - 5.0).collect();
        let f = linear_regression(&x, &y).unwrap();
        assert_relative_eq!(f.slope, 0.1, epsilon = 1e-12);
        assert_relative_eq!(f.intercept, -5.0, epsilon = 1e-10);
        assert_relative_eq!(f.r, 1.0, epsilon = 1e-12);
        assert!(linear_regression(&[1.0, 1.0], &[2.0, 3.0]).is_none());
        assert_relative_eq!(pearson(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]), -1.0);
        assert_relative_eq!(t_statistic(2.0, 0.5), 4.0);
    }

    #[test]
    fn grouped_folds_keep_keys_together() {
        let keys: Vec<String> = (0..60).map(|i| format!("g{:02}", i % 20)).collect();
        let folds = grouped_folds(&keys, 5);
        for (i, a) in keys.iter().enumerate() {
            for (j, b) in keys.iter().enumerate() {
                if a == b {
                    assert_eq!(folds[i], folds[j]);
                }
            }
        }
        let mut counts = [0; 5];
        for f in &folds {
            counts[*f] += 1;
        }
        assert_eq!(counts, [12; 5]);
        // Deterministic.
        assert_eq!(folds, grouped_folds(&keys, 5));
        // More folds than keys: capped.
        assert!(grouped_folds(&["a", "b"], 5).iter().all(|&f| f < 2));
        assert_eq!(item_folds(7, 3), vec![0, 1, 2, 0, 1, 2, 0]);
    }
}
