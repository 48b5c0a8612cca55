//! The rival-family check's columns and their held-out least squares: launch errors and signals
//! whitened into `5n`-vectors, the impact-location and per-component level columns, and the
//! cross-validated fit of a target on a set of columns ([`cv_sse`]).

use nalgebra::{DMatrix, DVector};

use crate::model::{DeliveryVar, Shot};

use super::super::noise_floor::delivery_to_file_units;

/// Whitened 5n-vectors: row `5i + c` is shot `i`, component `c`.
pub(super) type Column = DVector<f64>;

pub(super) fn whiten(rows: &[[f64; 5]], sigma: &[f64; 5]) -> Column {
    DVector::from_iterator(
        rows.len() * 5,
        rows.iter()
            .flat_map(|r| (0..5).map(move |c| r[c] / sigma[c])),
    )
}

/// The location columns: per component, `y, z, y², z², y·z` (cm) on that component's rows.
pub(super) fn location_columns(shots: &[Shot]) -> Vec<Column> {
    let yz: Vec<(f64, f64)> = shots
        .iter()
        .map(|s| {
            let d = delivery_to_file_units(&s.delivery);
            (
                d[DeliveryVar::ImpactY.index()] / 10.0,
                d[DeliveryVar::ImpactZ.index()] / 10.0,
            )
        })
        .collect();
    let terms: [fn(f64, f64) -> f64; 5] =
        [|y, _| y, |_, z| z, |y, _| y * y, |_, z| z * z, |y, z| y * z];
    let mut out = Vec::with_capacity(25);
    for c in 0..5 {
        for term in terms {
            let mut col = DVector::zeros(shots.len() * 5);
            for (i, &(y, z)) in yz.iter().enumerate() {
                col[5 * i + c] = term(y, z);
            }
            out.push(col);
        }
    }
    out
}

/// Least squares of `t` on `cols`, held out fold by fold: the summed squared held-out residual
/// (`Σ t²` without columns), and the coefficients fitted on all rows.
pub(super) fn cv_sse(cols: &[&Column], t: &Column, fold_of: &[usize]) -> (f64, DVector<f64>) {
    let p = cols.len();
    if p == 0 {
        return (t.norm_squared(), DVector::zeros(0));
    }
    let rows = t.len();
    let n_folds = fold_of.iter().max().map_or(1, |m| m + 1);
    // Unit-norm columns, so one small ridge suits every column.
    let norms: Vec<f64> = cols
        .iter()
        .map(|c| c.norm().max(f64::MIN_POSITIVE))
        .collect();
    // Row-major, a row's entries together. Most location and level columns are zero on four
    // rows of five, and a zero entry adds nothing to a row's outer product: each row adds the
    // products of its non-zero entries only (every sum still taken over the rows in order).
    let norms = &norms;
    let x: Vec<f64> = (0..rows)
        .flat_map(|r| (0..p).map(move |j| cols[j][r] / norms[j]))
        .collect();
    let mut a_f = vec![DMatrix::<f64>::zeros(p, p); n_folds];
    let mut b_f = vec![DVector::<f64>::zeros(p); n_folds];
    let mut nz: Vec<(usize, f64)> = Vec::with_capacity(p);
    for r in 0..rows {
        let f = fold_of[r / 5];
        nz.clear();
        nz.extend(
            x[r * p..(r + 1) * p]
                .iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(j, v)| (j, *v)),
        );
        let (a, b) = (&mut a_f[f], &mut b_f[f]);
        for &(k, xk) in &nz {
            for &(j, xj) in &nz {
                a[(j, k)] += xj * xk;
            }
            b[k] += xk * t[r];
        }
    }
    let a: DMatrix<f64> = a_f.iter().fold(DMatrix::zeros(p, p), |s, m| s + m);
    let b: DVector<f64> = b_f.iter().fold(DVector::zeros(p), |s, v| s + v);
    let solve = |a: DMatrix<f64>, b: DVector<f64>| -> DVector<f64> {
        let ridge = 1e-9 * a.trace().max(f64::MIN_POSITIVE) / p as f64;
        let a = a + DMatrix::identity(p, p) * ridge;
        match a.clone().cholesky() {
            Some(ch) => ch.solve(&b),
            None => a
                .svd(true, true)
                .solve(&b, 1e-12)
                .unwrap_or_else(|_| DVector::zeros(p)),
        }
    };
    let betas: Vec<DVector<f64>> = (0..n_folds)
        .map(|f| solve(&a - &a_f[f], &b - &b_f[f]))
        .collect();
    let sse = (0..rows)
        .map(|r| {
            let beta = &betas[fold_of[r / 5]];
            let fitted: f64 = x[r * p..(r + 1) * p]
                .iter()
                .zip(beta.iter())
                .map(|(v, b)| v * b)
                .sum();
            (t[r] - fitted).powi(2)
        })
        .sum();
    let all = solve(a, b);
    let coef = DVector::from_iterator(p, (0..p).map(|j| all[j] / norms[j]));
    (sse, coef)
}

/// A constant per launch component (one column each).
pub(super) fn level_columns(n_shots: usize) -> Vec<Column> {
    (0..5)
        .map(|c| DVector::from_fn(n_shots * 5, |r, _| f64::from(u8::from(r % 5 == c))))
        .collect()
}

/// Share of the variation of `s` about its per-component means that `cols` (location and
/// level columns) explain, in sample: how much of what the signal changes from shot to shot is
/// a function of where the ball was struck.
pub(super) fn varies_with_location(s: &Column, cols: &[&Column]) -> f64 {
    let no_folds = vec![0; s.len() / 5];
    let (_, coef) = cv_sse(cols, s, &no_folds);
    let fitted = cols
        .iter()
        .zip(coef.iter())
        .fold(DVector::zeros(s.len()), |acc, (c, &k)| acc + *c * k);
    let mut means = [0.0; 5];
    for (r, v) in s.iter().enumerate() {
        means[r % 5] += v / (s.len() / 5) as f64;
    }
    let about_means: f64 = s
        .iter()
        .enumerate()
        .map(|(r, v)| (v - means[r % 5]).powi(2))
        .sum();
    1.0 - (s - fitted).norm_squared() / about_means.max(f64::MIN_POSITIVE)
}

/// Share of a signal's sum of squares in one launch component from which the component counts
/// as one the signal moves.
pub(super) const MOVED_SHARE: f64 = 0.1;

/// The launch components `signals` move: each carrying at least [`MOVED_SHARE`] of some
/// signal's sum of squares.
pub(super) fn moved_components(signals: &[&Column]) -> [bool; 5] {
    let mut moved = [false; 5];
    for s in signals {
        let total = s.norm_squared().max(f64::MIN_POSITIVE);
        for (c, m) in moved.iter_mut().enumerate() {
            let own: f64 = s.iter().skip(c).step_by(5).map(|v| v * v).sum();
            *m |= own / total >= MOVED_SHARE;
        }
    }
    moved
}
