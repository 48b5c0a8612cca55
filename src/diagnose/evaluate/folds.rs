//! Cross-validation folds: the training and held-out subsets of the data, and a training
//! fold's rows of an evaluation on all shots.

use nalgebra::{DMatrix, DVector};

use super::AllShots;
use crate::fit::FitData;

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
