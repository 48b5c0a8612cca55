//! Cross-validation folds: the training and held-out subsets of the data, a training fold's
//! rows of an evaluation on all shots, and the cross-validated χ² over the folds.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::AllShots;
use crate::club::ClubSpec;
use crate::diagnose::DiagnoseProgress;
use crate::fit::{run_lm_point_near, FitData, FitError, FitProblem, ParamLayout, Weighting};

/// Training and held-out subsets of the data, one pair per fold.
#[derive(Clone)]
pub(in crate::diagnose) struct Folds {
    pub(in crate::diagnose) train: Vec<FitData>,
    pub(in crate::diagnose) test: Vec<FitData>,
    /// Per fold, the indices (into the whole data) of its training shots, in order.
    pub(super) train_idx: Vec<Vec<usize>>,
}

pub(in crate::diagnose) fn make_folds(data: &FitData, fold_of: &[usize], n_folds: usize) -> Folds {
    let idx = |keep: &dyn Fn(usize) -> bool| -> Vec<usize> {
        (0..data.len()).filter(|&i| keep(fold_of[i])).collect()
    };
    let train_idx: Vec<Vec<usize>> = (0..n_folds).map(|f| idx(&|g| g != f)).collect();
    Folds {
        train: train_idx.iter().map(|i| data.subset(i)).collect(),
        test: (0..n_folds)
            .map(|f| data.subset(&idx(&|g| g == f)))
            .collect(),
        train_idx,
    }
}

fn chi2_at(
    club: &ClubSpec,
    layout: &ParamLayout,
    data: &FitData,
    w: Weighting,
    theta: &DVector<f64>,
) -> Result<f64, FitError> {
    let pr = FitProblem::new(club, layout.clone(), data, w);
    Ok(pr.residuals(theta.as_slice())?.norm_squared())
}

/// Cross-validated χ²: fit on each training fold from `start`, sum held-out χ². `at` is the
/// residuals and Jacobian on all shots (those the folds were made from) at `start`, when known:
/// each fold's fit then starts from its rows of them and keeps that Jacobian for its steps
/// ([`run_lm_point_near`]: `start`, the all-shots solution, is close to each fold's, so the
/// chord steps reach it without the `2p` shifted evaluations a step; the cross-validated χ²
/// agrees with the folds' own fits' to 1e-5 relative in the tests, 7e-7 measured, a few 0.01
/// of χ² on the paper world, where a candidate's penalty is about 12).
#[allow(clippy::too_many_arguments)]
pub(in crate::diagnose) fn cv_chi2(
    club: &ClubSpec,
    layout: &ParamLayout,
    folds: &Folds,
    w: Weighting,
    start: &DVector<f64>,
    at: Option<AllShots>,
    max_iters: u64,
    progress: Option<&dyn DiagnoseProgress>,
    cancel: Option<&crate::cancel::Cancel>,
) -> Result<f64, FitError> {
    let parts: Vec<Result<f64, FitError>> = (0..folds.train.len())
        .into_par_iter()
        .map(|f| {
            if crate::cancel::cancelled(cancel) {
                return Err(FitError::Cancelled);
            }
            let r = if layout.is_empty() {
                chi2_at(club, layout, &folds.test[f], w, start)
            } else {
                // Only the fold's solution is needed: no Jacobian at it.
                let pr = FitProblem::new(club, layout.clone(), &folds.train[f], w);
                let rows = at.map(|a| fold_rows(a, &folds.train_idx[f], w.rows_per_shot()));
                run_lm_point_near(pr, start, max_iters, rows)
                    .and_then(|run| chi2_at(club, layout, &folds.test[f], w, &run.theta))
            };
            if let Some(p) = progress {
                p.job_done();
            }
            r
        })
        .collect();
    parts.into_iter().sum()
}

/// The rows of the training shots `idx` of the all-shots residuals and Jacobian `at`
/// (`rows` residual rows a shot).
pub(super) fn fold_rows(
    (r, j): AllShots,
    idx: &[usize],
    rows: usize,
) -> (DVector<f64>, DMatrix<f64>) {
    // Each shot's rows are contiguous in a column: copied a shot at a time.
    let take = |col: &[f64], out: &mut [f64]| {
        for (o, &i) in out.chunks_exact_mut(rows).zip(idx) {
            o.copy_from_slice(&col[i * rows..(i + 1) * rows]);
        }
    };
    let n = idx.len() * rows;
    let mut fr = DVector::zeros(n);
    take(r.as_slice(), fr.as_mut_slice());
    let mut fj = DMatrix::zeros(n, j.ncols());
    for (c, out) in fj.as_mut_slice().chunks_exact_mut(n.max(1)).enumerate() {
        take(&j.as_slice()[c * j.nrows()..(c + 1) * j.nrows()], out);
    }
    (fr, fj)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fold's rows are the all-shots rows of its shots, in order (each shot's block of
    /// `rows` residuals in every column).
    #[test]
    fn fold_rows_are_the_shots_rows() {
        let (shots, rows, cols) = (7, 3, 2);
        let r = DVector::from_fn(shots * rows, |k, _| k as f64 + 0.5);
        let j = DMatrix::from_fn(shots * rows, cols, |k, c| (100 * c + k) as f64);
        let idx = [0, 2, 3, 6];
        let (fr, fj) = fold_rows((&r, &j), &idx, rows);
        assert_eq!(fr.len(), idx.len() * rows);
        assert_eq!(fj.shape(), (idx.len() * rows, cols));
        for (n, &i) in idx.iter().enumerate() {
            for q in 0..rows {
                assert_eq!(fr[n * rows + q], r[i * rows + q]);
                for c in 0..cols {
                    assert_eq!(fj[(n * rows + q, c)], j[(i * rows + q, c)]);
                }
            }
        }
        let (er, ej) = fold_rows((&r, &DMatrix::zeros(shots * rows, 0)), &[], rows);
        assert_eq!((er.len(), ej.shape()), (0, (0, 0)));
    }
}
