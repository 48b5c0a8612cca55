//! Identifiability: the Fisher information of the data rows, its eigen-decomposition in units
//! of the prior widths, the weak directions in words, which parameters the data determine, the
//! prior's share of each estimate.
//!
//! With `J` the whitened data rows' Jacobian, `F = JᵀJ` is the Fisher information of the shots
//! (the prior left out), and `D = diag(σ_prior)`. In prior-width units `F_u = D F D`: an
//! eigenvalue `λ` of `F_u` says the data alone pin the combination along its eigenvector to
//! `1/√λ` prior widths. A direction is **weak** when `1/√λ` exceeds the determined fraction `f`.
//!
//! A parameter is **determined** when its data-only standard error `√(F⁻¹)_jj` (marginal: the
//! other parameters free) is below `f` of its prior width. With `f = 1/3` the data then hold at
//! least 90 % of the information on it (`1/(1 + f²)`), so the estimate is the data's: the start
//! head pulls it by at most `f/√(1 + f²) ≈ 0.32` of its standard error per prior width that the
//! truth lies from the start.
//!
//! The prior's share of an estimate is `1 − Var_post/Var_data` (marginal variances: the
//! posterior's `(F + P)⁻¹` against the data's `F⁻¹`, `P = D⁻²`): 0 when the data alone set it,
//! 1 when they say nothing about it.

use nalgebra::{DMatrix, SymmetricEigen};
use serde::Serialize;

use super::head::HEAD_PARAMS;

/// Relative eigenvalue below which a direction counts as unseen (rounding of `F`).
const UNSEEN: f64 = 1e-12;

/// Smallest weight of a parameter named in a direction's words.
const LEADING: f64 = 0.3;

/// One eigen-direction of the Fisher information in prior-width units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Direction {
    /// Eigenvalue of `D F D`.
    pub eigenvalue: f64,
    /// Data-only standard error along the direction, prior widths (`None`: not seen at all).
    pub data_se_prior_widths: Option<f64>,
    /// The eigenvector's components, per parameter (club-file key), largest first, those of
    /// weight ≥ 0.3 only.
    pub leading: Vec<(String, f64)>,
    /// Weaker than the determined fraction?
    pub weak: bool,
    /// In words.
    pub text: String,
}

/// What the shots determine at one head.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Identifiability {
    /// Every direction, weakest first.
    pub directions: Vec<Direction>,
    /// Per parameter: the data-only standard error in the fitted parameter's unit (`None`:
    /// not determined at all).
    #[serde(skip)]
    pub data_se: Vec<Option<f64>>,
    /// Per parameter: determined?
    #[serde(skip)]
    pub determined: Vec<bool>,
    /// Keys of the determined parameters.
    pub determined_params: Vec<String>,
    /// Keys of the others.
    pub undetermined_params: Vec<String>,
}

/// `Fu = D F D` with `D = diag(sd)`.
fn scaled(fisher: &DMatrix<f64>, sd: &[f64]) -> DMatrix<f64> {
    DMatrix::from_fn(fisher.nrows(), fisher.ncols(), |a, b| {
        fisher[(a, b)] * sd[a] * sd[b]
    })
}

/// Marginal data-only variances `(F⁻¹)_jj` in the fitted units (∞ where the data see nothing
/// of the parameter), by the eigen-decomposition of `D F D`.
pub fn data_variances(fisher: &DMatrix<f64>, sd: &[f64]) -> Vec<f64> {
    let e = SymmetricEigen::new(scaled(fisher, sd));
    let top = e.eigenvalues.iter().cloned().fold(0.0, f64::max);
    (0..sd.len())
        .map(|j| {
            let mut v = 0.0;
            for (k, &l) in e.eigenvalues.iter().enumerate() {
                let w = e.eigenvectors[(j, k)].powi(2);
                if w < 1e-24 {
                    continue;
                }
                if l <= UNSEEN * top || l <= 0.0 {
                    return f64::INFINITY;
                }
                v += w / l;
            }
            v * sd[j] * sd[j]
        })
        .collect()
}

/// The posterior covariance `(F + D⁻²)⁻¹` (fitted units).
pub fn posterior_cov(fisher: &DMatrix<f64>, sd: &[f64]) -> DMatrix<f64> {
    let mut h = fisher.clone();
    for (j, s) in sd.iter().enumerate() {
        h[(j, j)] += 1.0 / (s * s);
    }
    // Symmetric positive definite by the prior: Cholesky, or a pseudo-inverse on failure.
    match h.clone().cholesky() {
        Some(c) => c.inverse(),
        None => h
            .pseudo_inverse(1e-14)
            .unwrap_or_else(|_| DMatrix::zeros(sd.len(), sd.len())),
    }
}

/// The estimate's covariance when the shots' noise is not what the weights assume (the
/// sandwich): `H⁻¹ (M + P) H⁻¹` with `H = F + P`, `P = D⁻²` and `M` the covariance of the data
/// rows' score, `Σ_i J_iᵀ r_i r_iᵀ J_i` over the shots' blocks of rows (or its expectation).
/// With `M = F` (every shot as noisy as the weights say) it is the posterior `H⁻¹`.
pub fn sandwich_cov(fisher: &DMatrix<f64>, meat: &DMatrix<f64>, sd: &[f64]) -> DMatrix<f64> {
    let h_inv = posterior_cov(fisher, sd);
    let mut m = meat.clone();
    for (j, s) in sd.iter().enumerate() {
        m[(j, j)] += 1.0 / (s * s);
    }
    &h_inv * m * &h_inv
}

/// `Σ_i J_iᵀ A_i J_i` over the blocks of five rows (one a shot) of the data Jacobian `jac`.
pub fn block_meat(jac: &DMatrix<f64>, a: impl Fn(usize) -> nalgebra::Matrix5<f64>) -> DMatrix<f64> {
    let p = jac.ncols();
    let mut m = DMatrix::zeros(p, p);
    for i in 0..jac.nrows() / 5 {
        let ji = jac.rows(5 * i, 5);
        m += ji.transpose() * a(i) * ji;
    }
    m
}

fn direction_text(leading: &[(String, f64)], words: &[&str], se: Option<f64>) -> String {
    let se_text = se.map_or("the shots do not see it at all".to_owned(), |s| {
        format!("data SE along it {s:.2} prior widths")
    });
    match leading {
        [] => format!("a mixture of every parameter is barely seen ({se_text})"),
        [(_, _)] => format!("{} is barely seen by these shots ({se_text})", words[0]),
        [(_, a), (_, b), rest @ ..] => {
            let alike = if a * b < 0.0 {
                "the same way"
            } else {
                "in opposite ways"
            };
            let with = if rest.is_empty() {
                String::new()
            } else {
                format!(" (with {})", words[2..].join(", "))
            };
            format!(
                "{} and {}{with} move the launch {alike}: changing them together in the ratio \
                 {:.2} : {:.2} of their prior widths leaves the launch unchanged to within the \
                 noise ({se_text}); only their combination is determined",
                words[0], words[1], a, b
            )
        }
    }
}

/// The identifiability of the head parameters from the data rows' Fisher information `fisher`
/// (fitted units) with prior widths `sd` (fitted units) and determined fraction `f`.
pub fn identifiability(fisher: &DMatrix<f64>, sd: &[f64], f: f64) -> Identifiability {
    let e = SymmetricEigen::new(scaled(fisher, sd));
    let top = e.eigenvalues.iter().cloned().fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..sd.len()).collect();
    order.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
    let directions = order
        .iter()
        .map(|&k| {
            let l = e.eigenvalues[k];
            let se = (l > UNSEEN * top && l > 0.0).then(|| 1.0 / l.sqrt());
            let mut comp: Vec<(usize, f64)> = (0..sd.len())
                .map(|j| (j, e.eigenvectors[(j, k)]))
                .filter(|(_, w)| w.abs() >= LEADING)
                .collect();
            comp.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
            comp.truncate(3);
            let leading: Vec<(String, f64)> = comp
                .iter()
                .map(|&(j, w)| (HEAD_PARAMS[j].key.to_owned(), w))
                .collect();
            let words: Vec<&str> = comp.iter().map(|&(j, _)| HEAD_PARAMS[j].words).collect();
            let weak = se.is_none_or(|s| s > f);
            Direction {
                eigenvalue: l,
                data_se_prior_widths: se,
                text: direction_text(&leading, &words, se),
                leading,
                weak,
            }
        })
        .collect();
    let var = data_variances(fisher, sd);
    let data_se: Vec<Option<f64>> = var
        .iter()
        .map(|v| v.is_finite().then(|| v.sqrt()))
        .collect();
    let determined: Vec<bool> = data_se
        .iter()
        .zip(sd)
        .map(|(se, s)| se.is_some_and(|se| se < f * s))
        .collect();
    let keys = |want: bool| {
        determined
            .iter()
            .enumerate()
            .filter(|(_, &d)| d == want)
            .map(|(j, _)| HEAD_PARAMS[j].key.to_owned())
            .collect()
    };
    Identifiability {
        directions,
        determined_params: keys(true),
        undetermined_params: keys(false),
        data_se,
        determined,
    }
}

/// The prior's share of each estimate, `1 − Var_post/Var_data` (1 where the data see nothing).
pub fn prior_shares(post: &DMatrix<f64>, data_var: &[f64]) -> Vec<f64> {
    data_var
        .iter()
        .enumerate()
        .map(|(j, &v)| {
            if v.is_finite() && v > 0.0 {
                (1.0 - post[(j, j)] / v).clamp(0.0, 1.0)
            } else {
                1.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Information on parameters 0 and 1 only through their sum (and a little on 0 alone).
    fn aliased() -> (DMatrix<f64>, Vec<f64>) {
        let n = HEAD_PARAMS.len();
        let sd: Vec<f64> = HEAD_PARAMS.iter().map(|h| h.prior_sd).collect();
        // Rows in prior-width units: u0 + u1 measured to 0.01, u2 to 0.1, the rest unseen.
        let mut j = DMatrix::zeros(2, n);
        j[(0, 0)] = 100.0 / sd[0];
        j[(0, 1)] = 100.0 / sd[1];
        j[(1, 2)] = 10.0 / sd[2];
        (j.transpose() * j, sd)
    }

    #[test]
    fn an_aliased_pair_is_named_and_neither_is_determined() {
        let (f, sd) = aliased();
        let id = identifiability(&f, &sd, 1.0 / 3.0);
        assert_eq!(id.determined_params, vec![HEAD_PARAMS[2].key.to_owned()]);
        let pair = id
            .directions
            .iter()
            .find(|d| d.leading.len() == 2 && d.leading[0].0.starts_with("com_mm"))
            .expect("the CoM depth-height direction");
        assert!(
            pair.weak && pair.text.contains("the same way"),
            "{}",
            pair.text
        );
        assert!(pair.text.contains("only their combination is determined"));
        // Data-only SE of parameter 2: 0.1 prior widths.
        let v = data_variances(&f, &sd);
        assert!((v[2].sqrt() / sd[2] - 0.1).abs() < 1e-9, "{}", v[2]);
        assert!(v[0].is_infinite() && v[1].is_infinite());
    }

    #[test]
    fn prior_share_is_the_variance_ratio() {
        let (f, sd) = aliased();
        let post = posterior_cov(&f, &sd);
        let shares = prior_shares(&post, &data_variances(&f, &sd));
        // Parameter 2: data variance 0.01 σ², posterior 1/(100 + 1) σ² → share 1/101.
        assert!((shares[2] - 1.0 / 101.0).abs() < 1e-9, "{}", shares[2]);
        assert_eq!(shares[0], 1.0);
        assert_eq!(shares[5], 1.0);
    }
}
