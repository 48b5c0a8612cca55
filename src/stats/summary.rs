//! Sample summaries and the one-sample t-test of a mean.

use serde::Serialize;

use super::tdist::student_t_two_sided_p;

/// Arithmetic mean; NaN for an empty slice.
pub fn mean(xs: &[f64]) -> f64 {
    xs.iter().sum::<f64>() / xs.len() as f64
}

/// Sample standard deviation (divisor `n − 1`); NaN for fewer than two values.
pub fn std_dev(xs: &[f64]) -> f64 {
    let n = xs.len();
    if n < 2 {
        return f64::NAN;
    }
    let m = mean(xs);
    (xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1) as f64).sqrt()
}

/// Mean, spread and the one-sample t-test of `mean = 0` for one sample.
///
/// `t = mean / (std/√n)` with `n − 1` degrees of freedom. Fields that are undefined for the
/// sample (std for `n < 2`; `t` and `p` when the std is zero or undefined) are `None`, so no NaN
/// reaches a report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Summary {
    /// Sample size.
    pub n: usize,
    /// Mean (`None` for an empty sample).
    pub mean: Option<f64>,
    /// Sample standard deviation.
    pub std: Option<f64>,
    /// Standard error of the mean, `std/√n`.
    pub sem: Option<f64>,
    /// t statistic of the mean against zero.
    pub t: Option<f64>,
    /// Two-sided p-value of that t.
    pub p: Option<f64>,
}

/// Spreads at or below this (absolute, in file units: mph, deg, rpm, mm) are rounding, not data.
pub const ROUNDING_FLOOR: f64 = 1e-9;

/// Is a sample with standard deviation `sd` and largest magnitude `max_abs` effectively
/// constant (its spread only floating-point rounding)?
pub fn effectively_constant(sd: f64, max_abs: f64) -> bool {
    !(sd > ROUNDING_FLOOR && sd > 1e-12 * max_abs)
}

impl Summary {
    /// Summarise a sample.
    pub fn of(xs: &[f64]) -> Self {
        let n = xs.len();
        let finite = |v: f64| v.is_finite().then_some(v);
        let m = if n > 0 { finite(mean(xs)) } else { None };
        let s = if n > 1 { finite(std_dev(xs)) } else { None };
        let sem = s.map(|s| s / (n as f64).sqrt());
        let max_abs = xs.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let (t, p) = match (m, s, sem) {
            (Some(m), Some(sd), Some(se)) if !effectively_constant(sd, max_abs) => {
                let t = m / se;
                (Some(t), Some(student_t_two_sided_p(t, (n - 1) as f64)))
            }
            _ => (None, None),
        };
        Self {
            n,
            mean: m,
            std: s,
            sem,
            t,
            p,
        }
    }

    /// Is the mean different from zero at level `alpha` (two-sided)?
    pub fn significant(&self, alpha: f64) -> bool {
        self.p.is_some_and(|p| p < alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn summary_of_known_sample() {
        let xs = [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0];
        let s = Summary::of(&xs);
        assert_eq!(s.n, 8);
        assert_relative_eq!(s.mean.unwrap(), 5.0);
        // Sum of squares 32, n − 1 = 7.
        assert_relative_eq!(s.std.unwrap(), (32.0f64 / 7.0).sqrt(), epsilon = 1e-14);
        let t = 5.0 / ((32.0f64 / 7.0).sqrt() / 8f64.sqrt());
        assert_relative_eq!(s.t.unwrap(), t, epsilon = 1e-12);
        assert!(s.p.unwrap() < 1e-3 && s.significant(0.01));
    }

    #[test]
    fn degenerate_samples_have_no_nan() {
        let e = Summary::of(&[]);
        assert_eq!((e.mean, e.std, e.t, e.p), (None, None, None, None));
        let one = Summary::of(&[3.0]);
        assert_eq!((one.mean, one.std, one.t), (Some(3.0), None, None));
        let flat = Summary::of(&[1.0, 1.0, 1.0]);
        assert_eq!((flat.std, flat.t, flat.p), (Some(0.0), None, None));
        assert!(!flat.significant(0.01));
    }
}
