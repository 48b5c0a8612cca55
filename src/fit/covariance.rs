//! Parameter covariance, correlation and identifiability from the Jacobian at a solution.
//!
//! With `J` the Jacobian of the whitened residuals at the solution (no damping) and
//! `s² = χ²/(N − p)` the reduced χ²:
//!
//! ```text
//! Cov(θ) = (JᵀJ)⁻¹ · s²          stderr_j = √Cov_jj          ρ_jk = Cov_jk / (stderr_j·stderr_k)
//! ```
//!
//! Scaling by `s²` makes the standard errors honest when the noise scales are off or the
//! model misses something (then `s² > 1` and the errors grow).
//!
//! Identifiability: a parameter is *insensitive* when moving it across its whole physical range
//! changes the (linearised) whitened residuals by less than [`INSENSITIVE_NORM`]
//! (`‖J_j‖·(upper_j − lower_j)`); parameters are *collinear* when the smallest eigenvalue of
//! the column-normalised `JᵀJ` (the correlation matrix of the columns) is below
//! [`COLLINEAR_EIGENVALUE`], i.e. some combination of them changes nothing.

use nalgebra::DMatrix;

/// `‖J_j‖·range_j` below this: the parameter does not change the residuals.
pub const INSENSITIVE_NORM: f64 = 1e-3;

/// Smallest eigenvalue of the column-normalised `JᵀJ` below this: collinear columns
/// (correlation of two columns beyond `1 − 1e-6`).
pub const COLLINEAR_EIGENVALUE: f64 = 1e-6;

/// Can the data determine the parameters?
#[derive(Debug, Clone, PartialEq)]
pub struct Identifiability {
    /// Parameters whose Jacobian column is (numerically) zero.
    pub insensitive: Vec<usize>,
    /// Smallest eigenvalue of the column-normalised `JᵀJ` over the sensitive parameters.
    pub min_eigenvalue: f64,
    /// Parameters taking part (|eigenvector entry| > 0.3) in the degenerate direction, when the
    /// smallest eigenvalue is below [`COLLINEAR_EIGENVALUE`].
    pub collinear: Vec<usize>,
}

impl Identifiability {
    /// Every parameter determined by the data?
    pub fn ok(&self) -> bool {
        self.insensitive.is_empty() && self.collinear.is_empty()
    }

    /// The indices of parameters that cannot be determined.
    pub fn unidentified(&self) -> Vec<usize> {
        let mut v = self.insensitive.clone();
        v.extend(&self.collinear);
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// Covariance and friends of the parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Covariance {
    /// `(JᵀJ)⁻¹·s²`, when `JᵀJ` is invertible and the parameters identifiable.
    pub matrix: Option<DMatrix<f64>>,
    /// Standard error of each parameter (`None` when not identifiable).
    pub stderr: Vec<Option<f64>>,
    /// Correlation matrix of the estimates (`None` when not identifiable).
    pub correlation: Option<DMatrix<f64>>,
    /// Identifiability diagnostics.
    pub identifiability: Identifiability,
}

/// Identifiability of the columns of `jac` (whitened residuals × parameters) for parameters with
/// physical ranges `ranges`.
pub fn identifiability(jac: &DMatrix<f64>, ranges: &[f64]) -> Identifiability {
    let p = jac.ncols();
    let norms: Vec<f64> = (0..p).map(|j| jac.column(j).norm()).collect();
    let insensitive: Vec<usize> = (0..p)
        .filter(|&j| !(norms[j] * ranges[j] >= INSENSITIVE_NORM))
        .collect();
    let sensitive: Vec<usize> = (0..p).filter(|j| !insensitive.contains(j)).collect();
    let mut min_eigenvalue = 1.0;
    let mut collinear = Vec::new();
    if sensitive.len() >= 2 {
        let k = sensitive.len();
        let mut c = DMatrix::zeros(k, k);
        for (a, &ja) in sensitive.iter().enumerate() {
            for (b, &jb) in sensitive.iter().enumerate() {
                c[(a, b)] = jac.column(ja).dot(&jac.column(jb)) / (norms[ja] * norms[jb]);
            }
        }
        let eig = c.symmetric_eigen();
        let (imin, &lmin) = eig
            .eigenvalues
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("k ≥ 2");
        min_eigenvalue = lmin;
        if lmin < COLLINEAR_EIGENVALUE {
            let v = eig.eigenvectors.column(imin);
            collinear = sensitive
                .iter()
                .enumerate()
                .filter(|(a, _)| v[*a].abs() > 0.3)
                .map(|(_, &j)| j)
                .collect();
        }
    }
    Identifiability {
        insensitive,
        min_eigenvalue,
        collinear,
    }
}

/// Covariance of the estimates from the Jacobian `jac` of whitened residuals at the solution,
/// the reduced χ² `reduced_chi2` and the parameters' physical `ranges`.
pub fn covariance(jac: &DMatrix<f64>, reduced_chi2: f64, ranges: &[f64]) -> Covariance {
    let p = jac.ncols();
    let identifiability = identifiability(jac, ranges);
    let inverse = if identifiability.ok() {
        jac.tr_mul(jac).try_inverse()
    } else {
        None
    };
    match inverse {
        Some(inv) => {
            let cov = inv * reduced_chi2;
            let se: Vec<f64> = (0..p).map(|j| cov[(j, j)].max(0.0).sqrt()).collect();
            let corr = DMatrix::from_fn(p, p, |a, b| {
                if a == b {
                    1.0
                } else {
                    cov[(a, b)] / (se[a] * se[b])
                }
            });
            Covariance {
                matrix: Some(cov),
                stderr: se.into_iter().map(Some).collect(),
                correlation: Some(corr),
                identifiability,
            }
        }
        None => {
            // Standard errors of the identifiable parameters, conditional on the others held
            // at their values; none for the unidentified ones.
            let bad = identifiability.unidentified();
            let good: Vec<usize> = (0..p).filter(|j| !bad.contains(j)).collect();
            let mut stderr = vec![None; p];
            if !good.is_empty() && good.len() < p {
                let sub = jac.select_columns(&good);
                if let Some(inv) = sub.tr_mul(&sub).try_inverse() {
                    for (a, &j) in good.iter().enumerate() {
                        stderr[j] = Some((inv[(a, a)] * reduced_chi2).max(0.0).sqrt());
                    }
                }
            }
            Covariance {
                matrix: None,
                stderr,
                correlation: None,
                identifiability,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn an_unidentified_parameter_does_not_hide_the_others_errors() {
        let x = [0.0, 1.0, 2.0, 3.0];
        // Second column: the residuals do not depend on it at all.
        let j = DMatrix::from_fn(4, 2, |i, k| if k == 0 { x[i] } else { 0.0 });
        let c = covariance(&j, 1.0, &[10.0, 10.0]);
        assert!(!c.identifiability.ok());
        assert_eq!(c.stderr[1], None);
        let want = 1.0 / x.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert_relative_eq!(c.stderr[0].unwrap(), want, max_relative = 1e-12);
    }

    #[test]
    fn straight_line_covariance_matches_textbook() {
        // r_i = (a + b·x_i − y_i)/σ with σ = 1: Cov = (XᵀX)⁻¹ when s² = 1.
        let x = [0.0, 1.0, 2.0, 3.0];
        let j = DMatrix::from_fn(4, 2, |i, k| if k == 0 { 1.0 } else { x[i] });
        let c = covariance(&j, 1.0, &[10.0, 10.0]);
        // XᵀX = [[4, 6], [6, 14]], det 20 → inverse [[0.7, −0.3], [−0.3, 0.2]].
        assert_relative_eq!(c.stderr[0].unwrap(), 0.7f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(c.stderr[1].unwrap(), 0.2f64.sqrt(), epsilon = 1e-12);
        let r = c.correlation.unwrap()[(0, 1)];
        assert_relative_eq!(r, -0.3 / (0.7f64 * 0.2).sqrt(), epsilon = 1e-12);
        let c2 = covariance(&j, 4.0, &[10.0, 10.0]);
        assert_relative_eq!(c2.stderr[0].unwrap(), 2.0 * 0.7f64.sqrt(), epsilon = 1e-12);
    }

    #[test]
    fn flags_collinear_and_insensitive_columns() {
        let j = DMatrix::from_fn(5, 3, |i, k| match k {
            0 => i as f64,
            1 => 2.0 * i as f64,
            _ => 0.0,
        });
        let c = covariance(&j, 1.0, &[1.0, 1.0, 1.0]);
        assert!(!c.identifiability.ok());
        assert_eq!(c.identifiability.insensitive, vec![2]);
        assert_eq!(c.identifiability.collinear, vec![0, 1]);
        assert!(c.stderr.iter().all(Option::is_none));
    }
}
