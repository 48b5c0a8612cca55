//! Structure in what remains that no straight line follows: a component's standardised errors
//! `z_i = (r_i − r̄)/√v_i` binned over the face (impact location, a face map) and over club
//! speed, and low-order polynomials fitted to them.
//!
//! Each term is an F test, not a χ² test on the bin means: the bin (or polynomial) mean square
//! is divided by the residual mean square of `z` itself, so the test asks whether the errors
//! depend on where the ball was struck, whatever their overall scale. A χ² test
//! `Σ n_b·z̄_b² ~ χ²(B − 1)` (one degree less, the overall mean being removed) assumes
//! `var(z) = 1`, which is what the spread test already rejects whenever a component carries
//! unexplained structure: it would then name the face map for any excess scatter.
//!
//! - face-map bins: the shots binned by quantiles of `impact_y_mm` (rows, up the face) and
//!   `impact_z_mm` (columns, toward the toe), `k × k` cells with `k` the most (2 to 4) that
//!   leaves [`MIN_BIN_SHOTS`] shots per cell on average; one-way analysis of variance of `z`
//!   over the non-empty cells, `F(B − 1, n − B)`;
//! - face quadratic: `z` fitted by least squares on `y, z, y², z², yz` (the radial `y² + z²`
//!   lies in their span), `F(5, n − 6)`;
//! - club-speed bins (up to 6 quantile bins, [`MIN_BIN_SHOTS`]·2 shots each) and club-speed
//!   quadratic (`x, x²`, `F(2, n − 3)`).

use nalgebra::{DMatrix, DVector};

use crate::model::{DeliveryVar, N_DELIVERY};
use crate::physics::LaunchComponent;
use crate::stats::tdist::incomplete_beta;

/// Shots a face-map cell holds on average, at least (fewer shots: a coarser map).
pub const MIN_BIN_SHOTS: usize = 25;

/// A non-linear term tried.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeTerm {
    /// Face-map bins of impact location.
    FaceBins,
    /// Quadratic in impact location.
    FaceQuadratic,
    /// Club-speed bins.
    SpeedBins,
    /// Quadratic in club speed.
    SpeedQuadratic,
}

impl ShapeTerm {
    /// Every term, in the order tried.
    pub const ALL: [ShapeTerm; 4] = [
        Self::FaceBins,
        Self::FaceQuadratic,
        Self::SpeedBins,
        Self::SpeedQuadratic,
    ];

    /// Name in the JSON.
    pub const fn name(self) -> &'static str {
        match self {
            Self::FaceBins => "face_map_bins",
            Self::FaceQuadratic => "face_quadratic",
            Self::SpeedBins => "club_speed_bins",
            Self::SpeedQuadratic => "club_speed_quadratic",
        }
    }

    /// Does the term read impact location?
    pub const fn is_face(self) -> bool {
        matches!(self, Self::FaceBins | Self::FaceQuadratic)
    }
}

/// Terms a component's pointer chooses among: the linear correlation with every delivery
/// variable and the non-linear terms; the Bonferroni divisor of [`super::TREND_ALPHA`].
pub const TERMS_TRIED: usize = N_DELIVERY + ShapeTerm::ALL.len();

/// The level each of the [`TERMS_TRIED`] terms is tested at (1 % family-wise).
pub const ALPHA_EACH: f64 = super::TREND_ALPHA / TERMS_TRIED as f64;

/// The F test of one term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TermTest {
    /// Term.
    pub term: ShapeTerm,
    /// F statistic.
    pub f: f64,
    /// Degrees of freedom of the term and of the residual.
    pub df: (usize, usize),
    /// Upper-tail p-value of `F`.
    pub p_value: f64,
}

/// One bin: its shots, their mean error (file units) and mean standardised error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bin {
    /// Shots in the bin.
    pub count: usize,
    /// Mean error (model − measured), the component's file unit; NaN when empty.
    pub mean_error: f64,
    /// Mean of `z` (centred standardised errors); NaN when empty.
    pub z_mean: f64,
}

/// Bins of the shots over one or two delivery variables, by quantiles.
#[derive(Debug, Clone, PartialEq)]
pub struct BinMap {
    /// Edges of the rows (`impact_y_mm` for a face map, club speed for speed bins), ascending.
    pub row_edges: Vec<f64>,
    /// Edges of the columns (`impact_z_mm`); `[]` for one variable.
    pub col_edges: Vec<f64>,
    /// Row-major, first row lowest.
    pub bins: Vec<Bin>,
}

impl BinMap {
    /// Columns (1 for one variable).
    pub fn n_cols(&self) -> usize {
        self.col_edges.len().saturating_sub(1).max(1)
    }
}

/// The search of one component.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShapeSearch {
    /// Face map of what remains (rows up the face, columns toward the toe), when there are
    /// enough shots.
    pub face_map: Option<BinMap>,
    /// Club-speed bins (rows), when there are enough shots.
    pub speed_bins: Option<BinMap>,
    /// Every term's test.
    pub tests: Vec<TermTest>,
    /// The term the pointer names: the smallest p-value of all [`TERMS_TRIED`], when that is a
    /// non-linear term and below `TREND_ALPHA / TERMS_TRIED`.
    pub found: Option<TermTest>,
}

/// Quantile edges of `x` in `k` bins (fewer when values tie).
fn quantile_edges(x: &[f64], k: usize) -> Vec<f64> {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    let mut e = vec![s[0]];
    for j in 1..k {
        let q = s[j * n / k];
        if q > e[e.len() - 1] {
            e.push(q);
        }
    }
    e.push(s[n - 1].max(e[e.len() - 1]));
    e
}

/// The bin of `x` among `edges` (`[e0, e1)`, …, `[e_{k−1}, e_k]`).
fn bin_of(edges: &[f64], x: f64) -> usize {
    edges[1..edges.len() - 1].partition_point(|&e| e <= x)
}

/// Bins per axis of a face map of `n` shots (0: too few shots).
fn face_bins_per_axis(n: usize) -> usize {
    (2..=4)
        .rev()
        .find(|k| n >= k * k * MIN_BIN_SHOTS)
        .unwrap_or(0)
}

/// The map of `r` and `z` over bins `cell[i]` of `n_bins`.
fn bin_means(cell: &[usize], n_bins: usize, r: &[f64], z: &[f64]) -> Vec<Bin> {
    let mut acc = vec![(0usize, 0.0, 0.0); n_bins];
    for ((&c, ri), zi) in cell.iter().zip(r).zip(z) {
        acc[c].0 += 1;
        acc[c].1 += ri;
        acc[c].2 += zi;
    }
    acc.into_iter()
        .map(|(n, sr, sz)| Bin {
            count: n,
            mean_error: if n > 0 { sr / n as f64 } else { f64::NAN },
            z_mean: if n > 0 { sz / n as f64 } else { f64::NAN },
        })
        .collect()
}

/// Upper-tail probability of `F(d1, d2)` at `f`.
pub fn f_upper_tail(f: f64, d1: usize, d2: usize) -> f64 {
    let (a, b) = (d1 as f64, d2 as f64);
    incomplete_beta(b / 2.0, a / 2.0, b / (b + a * f.max(0.0)))
}

/// One-way analysis of variance of `z` over the non-empty bins of `bins`.
fn anova(term: ShapeTerm, cell: &[usize], bins: &[Bin], z: &[f64]) -> Option<TermTest> {
    let n = z.len();
    let grand = z.iter().sum::<f64>() / n as f64;
    let used = bins.iter().filter(|b| b.count > 0).count();
    let between: f64 = bins
        .iter()
        .filter(|b| b.count > 0)
        .map(|b| b.count as f64 * (b.z_mean - grand).powi(2))
        .sum();
    let within: f64 = cell
        .iter()
        .zip(z)
        .map(|(&c, zi)| (zi - bins[c].z_mean).powi(2))
        .sum();
    test_of(
        term,
        between,
        within,
        used.checked_sub(1)?,
        n.checked_sub(used)?,
    )
}

fn test_of(
    term: ShapeTerm,
    explained: f64,
    residual: f64,
    d1: usize,
    d2: usize,
) -> Option<TermTest> {
    if d1 == 0 || d2 == 0 || residual <= 0.0 || !explained.is_finite() {
        return None;
    }
    let f = (explained / d1 as f64) / (residual / d2 as f64);
    Some(TermTest {
        term,
        f,
        df: (d1, d2),
        p_value: f_upper_tail(f, d1, d2),
    })
}

/// `x` centred and scaled to unit SD (`None` when constant).
fn standardised(x: &[f64]) -> Option<Vec<f64>> {
    let m = crate::stats::mean(x);
    let sd = crate::stats::std_dev(x);
    (sd > 0.0 && sd.is_finite()).then(|| x.iter().map(|v| (v - m) / sd).collect())
}

/// Least-squares fit of `z` on an intercept and `cols`: the F test of the columns.
fn polynomial(term: ShapeTerm, cols: &[Vec<f64>], z: &[f64]) -> Option<TermTest> {
    let (n, p) = (z.len(), cols.len());
    let x = DMatrix::from_fn(n, p + 1, |i, j| if j == 0 { 1.0 } else { cols[j - 1][i] });
    let y = DVector::from_column_slice(z);
    let beta = x.clone().svd(true, true).solve(&y, 1e-10).ok()?;
    let rss = (&y - &x * beta).norm_squared();
    let mean = y.mean();
    let tss: f64 = z.iter().map(|v| (v - mean).powi(2)).sum();
    test_of(term, (tss - rss).max(0.0), rss, p, n.checked_sub(p + 1)?)
}

/// The non-linear terms of `z` (with `r` the errors, file units) over the shots' deliveries
/// (file units), and the term named against the best linear p-value `linear_p` (the smallest
/// two-sided p of the correlations with each delivery variable).
pub(super) fn search(
    deliveries: &[[f64; N_DELIVERY]],
    r: &[f64],
    z: &[f64],
    linear_p: f64,
) -> ShapeSearch {
    let n = z.len();
    let col = |v: DeliveryVar| deliveries.iter().map(|d| d[v.index()]).collect::<Vec<_>>();
    let (y, zz, speed) = (
        col(DeliveryVar::ImpactY),
        col(DeliveryVar::ImpactZ),
        col(DeliveryVar::ClubSpeed),
    );
    let mut out = ShapeSearch::default();
    let k = face_bins_per_axis(n);
    if k >= 2 {
        let (ye, ze) = (quantile_edges(&y, k), quantile_edges(&zz, k));
        let nc = ze.len() - 1;
        let cell: Vec<usize> = y
            .iter()
            .zip(&zz)
            .map(|(a, b)| bin_of(&ye, *a) * nc + bin_of(&ze, *b))
            .collect();
        let bins = bin_means(&cell, (ye.len() - 1) * nc, r, z);
        out.tests
            .extend(anova(ShapeTerm::FaceBins, &cell, &bins, z));
        out.face_map = Some(BinMap {
            row_edges: ye,
            col_edges: ze,
            bins,
        });
    }
    if let (Some(u), Some(w)) = (standardised(&y), standardised(&zz)) {
        let sq = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).collect();
        let cols = vec![sq(&u, &u), sq(&w, &w), sq(&u, &w), u, w];
        out.tests
            .extend(polynomial(ShapeTerm::FaceQuadratic, &cols, z));
    }
    let ks = (n / (2 * MIN_BIN_SHOTS)).min(6);
    if ks >= 2 {
        let e = quantile_edges(&speed, ks);
        let cell: Vec<usize> = speed.iter().map(|x| bin_of(&e, *x)).collect();
        let bins = bin_means(&cell, e.len() - 1, r, z);
        out.tests
            .extend(anova(ShapeTerm::SpeedBins, &cell, &bins, z));
        out.speed_bins = Some(BinMap {
            row_edges: e,
            col_edges: Vec::new(),
            bins,
        });
    }
    if let Some(s) = standardised(&speed) {
        let s2 = s.iter().map(|v| v * v).collect();
        out.tests
            .extend(polynomial(ShapeTerm::SpeedQuadratic, &[s, s2], z));
    }
    out.found = out
        .tests
        .iter()
        .copied()
        .filter(|t| t.p_value < ALPHA_EACH && t.p_value < linear_p)
        .min_by(|a, b| a.p_value.total_cmp(&b.p_value));
    out
}

/// Where row `i` of `rows` lies up the face, and column `j` of `cols` from heel to toe.
fn face_words(i: usize, j: usize, rows: usize, cols: usize) -> String {
    let row = match rows {
        2 => ["low", "high"].get(i),
        3 => ["bottom", "middle", "top"].get(i),
        _ => ["bottom", "lower middle", "upper middle", "top"].get(i),
    };
    let col = match cols {
        2 => ["heel", "toe"].get(j),
        3 => ["heel", "centre", "toe"].get(j),
        _ => ["heel", "centre-heel", "centre-toe", "toe"].get(j),
    };
    format!(
        "the {} row, {} column",
        row.unwrap_or(&"?"),
        col.unwrap_or(&"?")
    )
}

/// An error of component `c`, signed, without its unit: rpm to the unit and the rest to 0.01.
pub fn error_value(v: f64, c: LaunchComponent) -> String {
    match c {
        LaunchComponent::Backspin | LaunchComponent::Sidespin => format!("{v:+.0}"),
        _ => format!("{v:+.2}"),
    }
}

/// [`error_value`] with the component's unit.
pub fn error_text(v: f64, c: LaunchComponent) -> String {
    format!("{} {}", error_value(v, c), c.unit())
}

impl ShapeSearch {
    /// The shape the pointer found, in words: the largest and smallest bin means (bins of at
    /// least half [`MIN_BIN_SHOTS`] shots) in the component's unit, and where they are.
    pub fn words(&self, c: LaunchComponent) -> Option<String> {
        let found = self.found?;
        let map = if found.term.is_face() {
            self.face_map.as_ref()?
        } else {
            self.speed_bins.as_ref()?
        };
        let nc = map.n_cols();
        let nr = map.row_edges.len() - 1;
        let full = |k: &usize| map.bins[*k].count >= MIN_BIN_SHOTS / 2;
        let key = |k: &usize| map.bins[*k].mean_error;
        let ks: Vec<usize> = (0..map.bins.len()).filter(full).collect();
        let hi = *ks.iter().max_by(|a, b| key(a).total_cmp(&key(b)))?;
        let lo = *ks.iter().min_by(|a, b| key(a).total_cmp(&key(b)))?;
        let at = |k: usize| {
            let (i, j) = (k / nc, k % nc);
            let (r0, r1) = (map.row_edges[i], map.row_edges[i + 1]);
            if found.term.is_face() {
                let (c0, c1) = (map.col_edges[j], map.col_edges[j + 1]);
                format!(
                    "in {} (y {r0:.1} to {r1:.1} mm, z {c0:.1} to {c1:.1} mm)",
                    face_words(i, j, nr, nc)
                )
            } else {
                format!("at club speed {r0:.1} to {r1:.1} mph")
            }
        };
        let what = if found.term.is_face() {
            "face map below"
        } else {
            "club-speed bins in the JSON"
        };
        Some(format!(
            "{} error is {} {} and {} {} ({what})",
            c.column(),
            error_text(key(&hi), c),
            at(hi),
            error_text(key(&lo), c),
            at(lo)
        ))
    }
}

#[cfg(test)]
#[path = "shape_tests.rs"]
mod tests;
