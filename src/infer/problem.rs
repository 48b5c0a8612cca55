//! The head fit's least-squares problem: the launch residuals of [`FitProblem`], whitened by a
//! full 5 × 5 noise covariance (the launch components' errors are correlated: a noisy loft
//! moves launch angle and backspin together), followed by one prior row a parameter.
//!
//! Rows, for shot `i` with errors `e_i = ŷ_i(θ) − y_i` (file units) and noise covariance
//! `Σ = D R D` (`D` the per-component scales, `R` the correlation, `R = L Lᵀ`):
//!
//! ```text
//! data:   L⁻¹ D⁻¹ e_i                       (5 rows a shot; Σ r² = Σ e_iᵀ Σ⁻¹ e_i)
//! prior:  (θ_j − θ0_j) / σ_j                (one row a parameter)
//! ```
//!
//! so that `‖r‖²` is `−2 ln` of the posterior up to a constant, with the start head `θ0` a
//! Gaussian prior of widths `σ` ([`super::head`]).

use argmin::core::{Error as ArgminError, Jacobian, Operator};
use nalgebra::{DMatrix, DVector, Matrix5, Vector5};

use crate::fit::{FitProblem, Weighting};
use crate::stats;

/// A noise covariance of the five launch components, file units.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseCov {
    /// Per-component 1σ (file units: mph, deg, deg, rpm, rpm).
    pub sd: [f64; 5],
    /// Correlation matrix.
    pub corr: Matrix5<f64>,
}

impl NoiseCov {
    /// The covariance `D R D`.
    pub fn matrix(&self) -> Matrix5<f64> {
        let d = Matrix5::from_diagonal(&Vector5::from(self.sd));
        d * self.corr * d
    }

    /// From a covariance matrix (a correlation that is not positive definite is replaced by
    /// the identity: the components are then whitened one by one).
    pub fn from_matrix(m: &Matrix5<f64>) -> Self {
        let sd: [f64; 5] = std::array::from_fn(|c| m[(c, c)].max(f64::MIN_POSITIVE).sqrt());
        let corr = Matrix5::from_fn(|a, b| m[(a, b)] / (sd[a] * sd[b]));
        Self::checked(sd, corr)
    }

    fn checked(sd: [f64; 5], corr: Matrix5<f64>) -> Self {
        let ok = corr.iter().all(|v| v.is_finite()) && corr.cholesky().is_some();
        Self {
            sd,
            corr: if ok { corr } else { Matrix5::identity() },
        }
    }

    /// From model − measured errors: robust per-component scales (1.4826·MAD about the median,
    /// as calibrate's) and the correlation of the standardised errors clipped at ±3 (so that a
    /// few wild shots do not set it).
    pub fn from_errors(errors: &[[f64; 5]]) -> Self {
        let sd = crate::fit::noise_scales(errors);
        let med: [f64; 5] = std::array::from_fn(|c| {
            let col: Vec<f64> = errors.iter().map(|e| e[c]).collect();
            stats::median(&col)
        });
        let z: Vec<[f64; 5]> = errors
            .iter()
            .map(|e| std::array::from_fn(|c| ((e[c] - med[c]) / sd[c]).clamp(-3.0, 3.0)))
            .collect();
        let mean: [f64; 5] =
            std::array::from_fn(|c| z.iter().map(|r| r[c]).sum::<f64>() / z.len().max(1) as f64);
        let mut cov = Matrix5::zeros();
        for r in &z {
            let v = Vector5::from_fn(|c, _| r[c] - mean[c]);
            cov += v * v.transpose();
        }
        let d: [f64; 5] = std::array::from_fn(|c| cov[(c, c)].max(f64::MIN_POSITIVE).sqrt());
        let corr = Matrix5::from_fn(|a, b| {
            if a == b {
                1.0
            } else {
                cov[(a, b)] / (d[a] * d[b])
            }
        });
        Self::checked(sd, corr)
    }

    /// `L⁻¹ D⁻¹`: errors (file units) to whitened rows.
    pub fn whitening(&self) -> Matrix5<f64> {
        self.whitener() * Matrix5::from_diagonal(&Vector5::from(self.sd.map(|s| 1.0 / s)))
    }

    /// `L⁻¹`, the whitening of standardised errors.
    pub fn whitener(&self) -> Matrix5<f64> {
        let l = self.corr.cholesky().expect("checked positive definite").l();
        l.try_inverse().expect("a Cholesky factor is invertible")
    }
}

/// The head fit's problem (see the module docs).
#[derive(Debug, Clone)]
pub struct HeadProblem<'a> {
    inner: FitProblem<'a>,
    whiten: Matrix5<f64>,
    centre: DVector<f64>,
    prior_sd: DVector<f64>,
    /// The solver's upper bounds, full vector (the layout's unless narrowed).
    upper: DVector<f64>,
}

impl<'a> HeadProblem<'a> {
    /// The problem `inner` (any weighting; it is replaced) whitened by `noise`, with the prior
    /// `N(centre, diag(prior_sd²))` on the full parameter vector.
    pub fn new(
        inner: FitProblem<'a>,
        noise: &NoiseCov,
        centre: DVector<f64>,
        prior_sd: DVector<f64>,
    ) -> Self {
        let upper = inner.layout().upper();
        Self {
            inner: inner.with_weighting(Weighting::launch(&noise.sd)),
            whiten: noise.whitener(),
            centre,
            prior_sd,
            upper,
        }
    }

    /// The solver's upper bounds `upper` (full vector; [`super::head::upper_bounds`]), where
    /// they are tighter than the layout's.
    pub fn with_upper(mut self, upper: &DVector<f64>) -> Self {
        self.upper = self.upper.zip_map(upper, f64::min);
        self
    }

    /// The solver's upper bound of parameter `j` (full-vector index).
    pub fn upper_of(&self, j: usize) -> f64 {
        self.upper[j]
    }

    /// The solver's upper bounds of the active parameters.
    pub fn active_upper(&self) -> DVector<f64> {
        let active = self.inner.active();
        DVector::from_iterator(active.len(), active.iter().map(|&j| self.upper[j]))
    }

    /// The residual problem inside.
    pub fn inner(&self) -> &FitProblem<'a> {
        &self.inner
    }

    /// Free only `active` (indices of the full vector); the others stay at `fixed`.
    pub fn with_active(mut self, active: Vec<usize>, fixed: DVector<f64>) -> Self {
        self.inner = self.inner.with_active(active, fixed);
        self
    }

    /// Data rows (whitened) of full `theta`.
    pub fn data_residuals(&self, theta: &[f64]) -> Result<DVector<f64>, crate::fit::EvalError> {
        let mut r = self.inner.residuals(theta)?;
        self.whiten_rows(r.as_mut_slice());
        Ok(r)
    }

    /// Data rows of the Jacobian in the active parameters at full `theta`.
    pub fn data_jacobian(
        &self,
        theta: &DVector<f64>,
    ) -> Result<DMatrix<f64>, crate::fit::EvalError> {
        let mut j = self.inner.jacobian_full(theta)?;
        let rows = j.nrows();
        for c in 0..j.ncols() {
            let col = &mut j.as_mut_slice()[c * rows..(c + 1) * rows];
            self.whiten_rows(col);
        }
        Ok(j)
    }

    /// Apply `L⁻¹` to each shot's block of five rows of a column.
    fn whiten_rows(&self, col: &mut [f64]) {
        for block in col.chunks_exact_mut(5) {
            let v = self.whiten * Vector5::from_column_slice(block);
            block.copy_from_slice(v.as_slice());
        }
    }

    /// `Σ ((θ_j − θ0_j)/σ_j)²` over the parameters not active (the fixed part of the prior).
    pub fn fixed_prior_chi2(&self, theta: &DVector<f64>) -> f64 {
        (0..theta.len())
            .filter(|j| !self.inner.active().contains(j))
            .map(|j| ((theta[j] - self.centre[j]) / self.prior_sd[j]).powi(2))
            .sum()
    }

    /// `Σ ((θ_j − θ0_j)/σ_j)²` over every parameter.
    pub fn prior_chi2(&self, theta: &DVector<f64>) -> f64 {
        (0..theta.len())
            .map(|j| ((theta[j] - self.centre[j]) / self.prior_sd[j]).powi(2))
            .sum()
    }
}

impl Operator for HeadProblem<'_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;

    fn apply(&self, active_values: &Self::Param) -> Result<Self::Output, ArgminError> {
        let theta = self.inner.full_theta(active_values.as_slice());
        let data = self.data_residuals(theta.as_slice())?;
        let active = self.inner.active();
        let mut r = DVector::zeros(data.len() + active.len());
        r.rows_mut(0, data.len()).copy_from(&data);
        for (k, &j) in active.iter().enumerate() {
            r[data.len() + k] = (theta[j] - self.centre[j]) / self.prior_sd[j];
        }
        Ok(r)
    }
}

impl Jacobian for HeadProblem<'_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;

    fn jacobian(&self, active_values: &Self::Param) -> Result<Self::Jacobian, ArgminError> {
        let theta = self.inner.full_theta(active_values.as_slice());
        let data = self.data_jacobian(&theta)?;
        let active = self.inner.active();
        let (n, p) = (data.nrows(), active.len());
        let mut jac = DMatrix::zeros(n + p, p);
        jac.rows_mut(0, n).copy_from(&data);
        for (k, &j) in active.iter().enumerate() {
            jac[(n + k, k)] = 1.0 / self.prior_sd[j];
        }
        Ok(jac)
    }
}
