//! Pearson correlation with its t-test of `r = 0`.
//!
//! `t = r·√((n − 2)/(1 − r²))` with `n − 2` degrees of freedom (exact for bivariate normal data).

use serde::Serialize;

use super::summary::effectively_constant;
use super::tdist::student_t_two_sided_p;

/// A correlation coefficient and its significance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Correlation {
    /// Number of pairs.
    pub n: usize,
    /// Pearson's r in [−1, 1].
    pub r: f64,
    /// t statistic of `r = 0`.
    pub t: f64,
    /// Two-sided p-value.
    pub p: f64,
}

/// Pearson correlation of `x` and `y` (same length). `None` when it is undefined: fewer than
/// three pairs, or either variable constant.
pub fn pearson(x: &[f64], y: &[f64]) -> Option<Correlation> {
    assert_eq!(
        x.len(),
        y.len(),
        "pearson: x and y must have the same length"
    );
    let n = x.len();
    if n < 3 {
        return None;
    }
    let mx = x.iter().sum::<f64>() / n as f64;
    let my = y.iter().sum::<f64>() / n as f64;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let (dx, dy) = (a - mx, b - my);
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let sd = |ss: f64| (ss / (n - 1) as f64).sqrt();
    if effectively_constant(sd(sxx), max_abs(x)) || effectively_constant(sd(syy), max_abs(y)) {
        return None;
    }
    let r = (sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0);
    let df = (n - 2) as f64;
    let one_minus = 1.0 - r * r;
    let (t, p) = if one_minus <= 0.0 {
        (f64::INFINITY.copysign(r), 0.0)
    } else {
        let t = r * (df / one_minus).sqrt();
        (t, student_t_two_sided_p(t, df))
    };
    let t = if t.is_finite() {
        t
    } else {
        1e300f64.copysign(r)
    };
    Some(Correlation { n, r, t, p })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn known_correlation() {
        // Anscombe's first quartet: r = 0.81642, p = 0.00217.
        let x = [10.0, 8.0, 13.0, 9.0, 11.0, 14.0, 6.0, 4.0, 12.0, 7.0, 5.0];
        let y = [
            8.04, 6.95, 7.58, 8.81, 8.33, 9.96, 7.24, 4.26, 10.84, 4.82, 5.68,
        ];
        let c = pearson(&x, &y).unwrap();
        assert_relative_eq!(c.r, 0.816_420_5, epsilon = 1e-6);
        assert_relative_eq!(c.p, 0.002_169_629, max_relative = 1e-4);
        let neg: Vec<f64> = y.iter().map(|v| -v).collect();
        assert_relative_eq!(pearson(&x, &neg).unwrap().r, -c.r, epsilon = 1e-12);
    }

    #[test]
    fn undefined_and_perfect_cases() {
        assert!(pearson(&[1.0, 2.0], &[1.0, 2.0]).is_none());
        assert!(pearson(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0]).is_none());
        let c = pearson(&[1.0, 2.0, 3.0, 4.0], &[2.0, 4.0, 6.0, 8.0]).unwrap();
        assert_eq!(c.r, 1.0);
        assert_eq!(c.p, 0.0);
        assert!(c.t.is_finite());
    }
}
