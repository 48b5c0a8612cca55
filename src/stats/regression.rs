//! Straight-line least squares and t statistics of estimates.

use super::correlation::pearson;
use super::summary::mean;

/// t statistic of an estimate: `value / stderr` (`NaN` when the standard error is not positive).
pub fn t_statistic(value: f64, stderr: f64) -> f64 {
    if stderr > 0.0 {
        value / stderr
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
        r: pearson(x, y).map_or(f64::NAN, |c| c.r),
        n: x.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::pearson;
    use approx::assert_relative_eq;

    #[test]
    fn regression_recovers_a_line() {
        let x = [74.5, 60.3, 70.9];
        let y: Vec<f64> = x.iter().map(|v| 0.1 * v - 5.0).collect();
        let f = linear_regression(&x, &y).unwrap();
        assert_relative_eq!(f.slope, 0.1, epsilon = 1e-12);
        assert_relative_eq!(f.intercept, -5.0, epsilon = 1e-10);
        assert_relative_eq!(f.r, 1.0, epsilon = 1e-12);
        assert!(linear_regression(&[1.0, 1.0], &[2.0, 3.0]).is_none());
        assert_relative_eq!(pearson(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]).unwrap().r, -1.0);
        assert_relative_eq!(t_statistic(2.0, 0.5), 4.0);
    }
}
