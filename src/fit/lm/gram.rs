//! `JᵀJ` of a Jacobian, dense or mostly of zeros, with the same bits as nalgebra's `tr_mul`.

use nalgebra::DMatrix;

/// `JᵀJ`, the upper triangle by column dot products and mirrored: the same bits as
/// `j.tr_mul(&j)` (nalgebra forms each entry as the dot of two columns, and a dot product's
/// terms and their order are the same either way round) in a little over half the work.
pub(crate) fn gram(j: &DMatrix<f64>) -> DMatrix<f64> {
    let p = j.ncols();
    let zeros = j.iter().filter(|v| **v == 0.0).count();
    if 2 * zeros > j.len() && j.iter().all(|v| v.is_finite()) {
        return sparse_gram(j);
    }
    let mut a = DMatrix::zeros(p, p);
    for c in 0..p {
        for k in c..p {
            let v = j.column(c).dot(&j.column(k));
            a[(c, k)] = v;
            a[(k, c)] = v;
        }
    }
    a
}

/// [`gram`] of a Jacobian mostly of zeros (the flight diagnosis's drag per ball type: a column
/// a ball type, non-zero on that ball's shots only), from the non-zero entries, with the same
/// bits. nalgebra's dot adds the product of row `i` to accumulator `i mod 8` over the whole
/// blocks of eight rows, combines the accumulators as `((0 + (a0 + a4)) + (a1 + a5)) + …` and
/// adds the remaining rows in order. A product of 0 leaves an accumulator as it was (none is
/// ever −0: each starts at +0, and `x + (−x)` is +0), so the products of the rows where both
/// columns are non-zero, added to the same accumulators in the same order, give the same sum.
/// Only for finite entries (0 · ∞ is NaN).
fn sparse_gram(j: &DMatrix<f64>) -> DMatrix<f64> {
    let (m, p) = j.shape();
    let whole = m - m % 8;
    let nonzero: Vec<Vec<(usize, f64)>> = (0..p)
        .map(|c| {
            let col = j.column(c);
            (0..m)
                .filter(|&r| col[r] != 0.0)
                .map(|r| (r, col[r]))
                .collect()
        })
        .collect();
    let mut a = DMatrix::zeros(p, p);
    let mut tail = Vec::new();
    for c in 0..p {
        for k in c..p {
            let (x, y) = (&nonzero[c], &nonzero[k]);
            let mut acc = [0.0f64; 8];
            tail.clear();
            let (mut u, mut w) = (0, 0);
            while u < x.len() && w < y.len() {
                match x[u].0.cmp(&y[w].0) {
                    std::cmp::Ordering::Less => u += 1,
                    std::cmp::Ordering::Greater => w += 1,
                    std::cmp::Ordering::Equal => {
                        let (r, t) = (x[u].0, x[u].1 * y[w].1);
                        if r < whole {
                            acc[r % 8] += t;
                        } else {
                            tail.push(t);
                        }
                        u += 1;
                        w += 1;
                    }
                }
            }
            let mut v = 0.0;
            v += acc[0] + acc[4];
            v += acc[1] + acc[5];
            v += acc[2] + acc[6];
            v += acc[3] + acc[7];
            for t in &tail {
                v += t;
            }
            a[(c, k)] = v;
            a[(k, c)] = v;
        }
    }
    a
}
