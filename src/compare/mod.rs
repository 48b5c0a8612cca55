//! Model against measurements: where and how the model fails.
//!
//! Pure: shots with measured launch + the model's predicted launch → [`CompareReport`]. Errors are
//! **model − measured** in file units (mph, deg, rpm), as in the paper's tables. The report holds
//!
//! - the paper's Table 2 layout: mean and STD of the error per component, per group and for all
//!   shots, with the t-test of each mean against zero;
//! - the errors binned over the face (impact location), so a user sees where on the face it fails;
//! - the errors binned by club speed and by dynamic loft (quantile bins);
//! - the Pearson correlation of each error component with each delivery variable;
//! - a ranked list of [`Finding`]s, each with hints from a small table of effect
//!   [`SIGNATURES`]: which library effects produce such a pattern.
//!
//! Undefined statistics are `None`, never NaN.

pub mod signatures;

use serde::Serialize;

use crate::limits::OptionError;
use crate::model::{DeliveryVar, Shot, N_DELIVERY};
use crate::physics::{Launch, LaunchComponent};
use crate::stats::{pearson, student_t_two_sided_p, Summary};

pub use signatures::{hints_for, Hint, Pattern, Signature, SIGNATURES};

/// Settings of a comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompareOptions {
    /// Significance level of the flags (two-sided), default 0.01.
    pub alpha: f64,
    /// Side of a face bin, mm (default 5).
    pub face_bin_mm: f64,
    /// Bins with fewer shots than this are left empty (default 5).
    pub min_bin_count: usize,
    /// Number of quantile bins for the speed and loft tables (default 5).
    pub quantile_bins: usize,
    /// |r| from which a significant correlation is called strong and reported (default 0.2).
    pub strong_r: f64,
}

/// Face bin sides [`CompareOptions`] accepts, mm: impact locations are measured to about a
/// millimetre, and a bin larger than the face holds every shot.
pub const FACE_BIN_MM: std::ops::RangeInclusive<f64> = 0.5..=100.0;

impl CompareOptions {
    /// Significance level, in (0, 1).
    pub fn with_alpha(mut self, alpha: f64) -> Result<Self, OptionError> {
        self.alpha = alpha;
        self.check_alpha().map(|()| self)
    }

    /// Side of a face bin, mm, in [`FACE_BIN_MM`].
    pub fn with_face_bin_mm(mut self, face_bin_mm: f64) -> Result<Self, OptionError> {
        self.face_bin_mm = face_bin_mm;
        self.check_face_bin().map(|()| self)
    }

    /// Smallest shot count of a reported face bin, ≥ 1.
    pub fn with_min_bin_count(mut self, min_bin_count: usize) -> Result<Self, OptionError> {
        self.min_bin_count = min_bin_count;
        self.check_counts().map(|()| self)
    }

    /// Number of quantile bins, ≥ 1.
    pub fn with_quantile_bins(mut self, quantile_bins: usize) -> Result<Self, OptionError> {
        self.quantile_bins = quantile_bins;
        self.check_counts().map(|()| self)
    }

    /// |r| from which a correlation is strong, in [0, 1].
    pub fn with_strong_r(mut self, strong_r: f64) -> Result<Self, OptionError> {
        self.strong_r = strong_r;
        self.check_strong_r().map(|()| self)
    }

    /// Every option in its allowed range (the fields are public, so [`compare`] checks again).
    pub fn validate(&self) -> Result<(), OptionError> {
        self.check_alpha()?;
        self.check_face_bin()?;
        self.check_counts()?;
        self.check_strong_r()
    }

    fn check_alpha(&self) -> Result<(), OptionError> {
        let a = self.alpha;
        OptionError::check(a > 0.0 && a < 1.0, "alpha", a, "in (0, 1)")
    }

    fn check_face_bin(&self) -> Result<(), OptionError> {
        let b = self.face_bin_mm;
        OptionError::check(
            FACE_BIN_MM.contains(&b),
            "face_bin_mm",
            b,
            "from 0.5 to 100 mm",
        )
    }

    fn check_counts(&self) -> Result<(), OptionError> {
        OptionError::check(
            self.min_bin_count >= 1,
            "min_bin_count",
            self.min_bin_count,
            "at least 1",
        )?;
        OptionError::check(
            self.quantile_bins >= 1,
            "quantile_bins",
            self.quantile_bins,
            "at least 1",
        )
    }

    fn check_strong_r(&self) -> Result<(), OptionError> {
        let r = self.strong_r;
        OptionError::check((0.0..=1.0).contains(&r), "strong_r", r, "in [0, 1]")
    }
}

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            alpha: 0.01,
            face_bin_mm: 5.0,
            min_bin_count: 5,
            quantile_bins: 5,
            strong_r: 0.2,
        }
    }
}

/// A delivery variable the errors are related to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variable {
    /// A delivery variable of the shots file.
    Delivery(DeliveryVar),
    /// `impact_r_mm`: the distance of the impact from the face centre.
    ImpactRadius,
}

impl Variable {
    /// Column-style name (`club_speed_mph`, …; `impact_r_mm` is the distance from the centre).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Delivery(v) => v.column(),
            Self::ImpactRadius => "impact_r_mm",
        }
    }

    /// Unit.
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Delivery(v) => v.unit(),
            Self::ImpactRadius => "mm",
        }
    }

    /// The value of a shot, file units.
    pub fn get(self, s: &Shot) -> f64 {
        match self {
            Self::Delivery(v) => v.file_value(&s.delivery),
            Self::ImpactRadius => s.delivery.impact_y_m.hypot(s.delivery.impact_z_m) * 1e3,
        }
    }
}

/// The delivery variables correlated with the errors: every [`DeliveryVar`], then the impact
/// radius.
pub const VARIABLES: [Variable; N_DELIVERY + 1] = {
    let mut v = [Variable::ImpactRadius; N_DELIVERY + 1];
    let mut i = 0;
    while i < N_DELIVERY {
        v[i] = Variable::Delivery(DeliveryVar::ALL[i]);
        i += 1;
    }
    v
};

/// Mean and spread of one error component.
#[derive(Debug, Clone, Serialize)]
pub struct ComponentError {
    /// Launch column (`ball_speed_mph`, …).
    pub component: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Summary with the t-test of mean = 0.
    #[serde(flatten)]
    pub summary: Summary,
    /// Mean significantly different from zero at `alpha`.
    pub significant: bool,
}

/// The Table 2 block of one group (or `all`).
#[derive(Debug, Clone, Serialize)]
pub struct GroupBias {
    /// Group name, or `all`.
    pub group: String,
    /// Number of shots.
    pub n: usize,
    /// One entry per launch component, in file order.
    pub components: Vec<ComponentError>,
}

/// One face bin of the errors.
#[derive(Debug, Clone, Serialize)]
pub struct FaceBin {
    /// Bin centre up the face, mm.
    pub y_mm: f64,
    /// Bin centre toward the toe, mm.
    pub z_mm: f64,
    /// Shots in the bin.
    pub count: usize,
    /// Mean error per component (`None` when `count < min_bin_count`).
    pub mean: Vec<Option<f64>>,
    /// STD of the error per component (`None` when `count < min_bin_count`).
    pub std: Vec<Option<f64>>,
}

/// Errors binned over the face on a square grid.
#[derive(Debug, Clone, Serialize)]
pub struct FaceResiduals {
    /// Bin side, mm.
    pub bin_mm: f64,
    /// Fewest shots for a bin to get a mean.
    pub min_count: usize,
    /// Row centres (y), ascending.
    pub ys_mm: Vec<f64>,
    /// Column centres (z), ascending.
    pub zs_mm: Vec<f64>,
    /// Every grid cell, row-major (row `i` is `ys_mm[i]`), empty cells included.
    pub bins: Vec<FaceBin>,
}

impl FaceResiduals {
    /// Row-major grid of the mean error of component `c` (NaN where empty), for heatmaps.
    pub fn grid(&self, c: LaunchComponent) -> Vec<f64> {
        self.bins
            .iter()
            .map(|b| b.mean[c.index()].unwrap_or(f64::NAN))
            .collect()
    }
}

/// One quantile bin of a delivery variable.
#[derive(Debug, Clone, Serialize)]
pub struct BinnedRow {
    /// Lowest value in the bin.
    pub lo: f64,
    /// Highest value in the bin.
    pub hi: f64,
    /// Shots.
    pub count: usize,
    /// Mean error per component.
    pub mean: Vec<Option<f64>>,
}

/// Errors binned by one delivery variable.
#[derive(Debug, Clone, Serialize)]
pub struct BinnedTable {
    /// Variable name.
    pub variable: &'static str,
    /// Rows, ascending.
    pub rows: Vec<BinnedRow>,
}

/// Correlation of one error component with one delivery variable.
#[derive(Debug, Clone, Serialize)]
pub struct CorrelationEntry {
    /// Launch column.
    pub component: &'static str,
    /// Delivery variable.
    pub variable: &'static str,
    /// Pairs.
    pub n: usize,
    /// Pearson r.
    pub r: f64,
    /// t statistic.
    pub t: f64,
    /// Two-sided p-value.
    pub p: f64,
    /// p < alpha.
    pub significant: bool,
    /// Significant and |r| ≥ `strong_r`.
    pub strong: bool,
}

/// One ranked observation about where the model fails.
#[derive(Debug, Clone, Serialize)]
pub struct Finding {
    /// Launch column.
    pub component: &'static str,
    /// What kind of pattern.
    pub pattern: Pattern,
    /// Strength used for ranking: |t| of the test behind the finding.
    pub strength: f64,
    /// One sentence.
    pub text: String,
    /// Library effects that produce such a pattern (from [`SIGNATURES`]).
    pub hints: Vec<String>,
}

/// Everything a comparison found.
#[derive(Debug, Clone, Serialize)]
pub struct CompareReport {
    /// Shots compared.
    pub n_shots: usize,
    /// Significance level used for flags.
    pub alpha: f64,
    /// Table 2 layout: one block per group, then `all`.
    pub table2: Vec<GroupBias>,
    /// Errors over the face.
    pub face: FaceResiduals,
    /// Errors by club speed and by dynamic loft.
    pub binned: Vec<BinnedTable>,
    /// Every component × variable correlation.
    pub correlations: Vec<CorrelationEntry>,
    /// Number of tests behind the flags (biases per group and all, correlations) and the number
    /// of false flags expected by chance if the model were right.
    pub tests: usize,
    /// `tests × alpha`.
    pub expected_false_flags: f64,
    /// Flags raised in all those tests.
    pub flags: usize,
    /// Ranked findings, strongest first.
    pub findings: Vec<Finding>,
}

/// Why a comparison cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompareError {
    /// Shots without measured launch.
    #[error(
        "shot '{shot_id}' has no measured launch; compare needs the columns {}",
        launch_columns()
    )]
    NoMeasurement {
        /// Shot id.
        shot_id: String,
    },
    /// Counts differ.
    #[error("{shots} shots but {predictions} predictions")]
    Length {
        /// Shots.
        shots: usize,
        /// Predictions.
        predictions: usize,
    },
    /// Nothing to compare.
    #[error("no shots to compare")]
    Empty,
    /// Too many face bins.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::CapError),
    /// An option out of range.
    #[error(transparent)]
    Option(#[from] OptionError),
}

fn launch_columns() -> String {
    LaunchComponent::ALL.map(|c| c.column()).join(", ")
}

fn errors_of(shots: &[Shot], predicted: &[Launch]) -> Result<Vec<[f64; 5]>, CompareError> {
    if shots.len() != predicted.len() {
        return Err(CompareError::Length {
            shots: shots.len(),
            predictions: predicted.len(),
        });
    }
    if shots.is_empty() {
        return Err(CompareError::Empty);
    }
    shots
        .iter()
        .zip(predicted)
        .map(|(s, p)| {
            let m = s
                .measured
                .as_ref()
                .ok_or_else(|| CompareError::NoMeasurement {
                    shot_id: s.id.clone(),
                })?;
            Ok(LaunchComponent::ALL.map(|c| p.get_file(c) - m.get_file(c)))
        })
        .collect()
}

fn group_errors(group: &str, errs: &[&[f64; 5]], alpha: f64) -> GroupBias {
    GroupBias {
        group: group.to_owned(),
        n: errs.len(),
        components: LaunchComponent::ALL
            .iter()
            .map(|&c| {
                let xs: Vec<f64> = errs.iter().map(|e| e[c.index()]).collect();
                let summary = Summary::of(&xs);
                ComponentError {
                    component: c.column(),
                    unit: c.unit(),
                    significant: summary.significant(alpha),
                    summary,
                }
            })
            .collect(),
    }
}

fn face_residuals(
    shots: &[Shot],
    errs: &[[f64; 5]],
    o: &CompareOptions,
) -> Result<FaceResiduals, CompareError> {
    let b = o.face_bin_mm;
    let idx = |v_m: f64| (v_m * 1e3 / b).floor() as i64;
    let iy: Vec<i64> = shots.iter().map(|s| idx(s.delivery.impact_y_m)).collect();
    let iz: Vec<i64> = shots.iter().map(|s| idx(s.delivery.impact_z_m)).collect();
    let range = |v: &[i64]| (*v.iter().min().unwrap(), *v.iter().max().unwrap());
    let ((y0, y1), (z0, z1)) = (range(&iy), range(&iz));
    let span = |lo: i64, hi: i64| {
        usize::try_from(hi.saturating_sub(lo)).map_or(usize::MAX, |d| d.saturating_add(1))
    };
    crate::limits::count_product(
        "face bins",
        &[("rows", span(y0, y1)), ("columns", span(z0, z1))],
        crate::limits::MAX_FACE_BINS,
        "use a larger --bin-mm",
    )?;
    let ys_mm: Vec<f64> = (y0..=y1).map(|i| (i as f64 + 0.5) * b).collect();
    let zs_mm: Vec<f64> = (z0..=z1).map(|i| (i as f64 + 0.5) * b).collect();
    let mut cells: Vec<Vec<usize>> = vec![Vec::new(); ys_mm.len() * zs_mm.len()];
    for (k, (y, z)) in iy.iter().zip(&iz).enumerate() {
        cells[(y - y0) as usize * zs_mm.len() + (z - z0) as usize].push(k);
    }
    let bins = cells
        .iter()
        .enumerate()
        .map(|(cell, members)| {
            let enough = members.len() >= o.min_bin_count;
            let per: Vec<Summary> = LaunchComponent::ALL
                .iter()
                .map(|c| {
                    let xs: Vec<f64> = members.iter().map(|&k| errs[k][c.index()]).collect();
                    Summary::of(&xs)
                })
                .collect();
            FaceBin {
                y_mm: ys_mm[cell / zs_mm.len()],
                z_mm: zs_mm[cell % zs_mm.len()],
                count: members.len(),
                mean: per.iter().map(|s| s.mean.filter(|_| enough)).collect(),
                std: per.iter().map(|s| s.std.filter(|_| enough)).collect(),
            }
        })
        .collect();
    Ok(FaceResiduals {
        bin_mm: b,
        min_count: o.min_bin_count,
        ys_mm,
        zs_mm,
        bins,
    })
}

fn binned(v: &Variable, shots: &[Shot], errs: &[[f64; 5]], nbins: usize) -> BinnedTable {
    let mut order: Vec<usize> = (0..shots.len()).collect();
    let x: Vec<f64> = shots.iter().map(|s| v.get(s)).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    let nbins = nbins.clamp(1, shots.len());
    let rows = (0..nbins)
        .map(|i| {
            let part = &order[i * order.len() / nbins..(i + 1) * order.len() / nbins];
            BinnedRow {
                lo: x[part[0]],
                hi: x[*part.last().expect("non-empty bin")],
                count: part.len(),
                mean: LaunchComponent::ALL
                    .iter()
                    .map(|c| {
                        let xs: Vec<f64> = part.iter().map(|&k| errs[k][c.index()]).collect();
                        Summary::of(&xs).mean
                    })
                    .collect(),
            }
        })
        .collect();
    BinnedTable {
        variable: v.name(),
        rows,
    }
}

/// Welch's t between two samples' means; `None` when undefined.
fn welch_t(a: &[f64], b: &[f64]) -> Option<(f64, f64)> {
    let (sa, sb) = (Summary::of(a), Summary::of(b));
    let (ma, mb, ea, eb) = (sa.mean?, sb.mean?, sa.sem?, sb.sem?);
    let se2 = ea * ea + eb * eb;
    if !(se2 > 0.0) {
        return None;
    }
    let t = (ma - mb) / se2.sqrt();
    let df = se2 * se2 / (ea.powi(4) / (a.len() - 1) as f64 + eb.powi(4) / (b.len() - 1) as f64);
    Some((t, student_t_two_sided_p(t, df)))
}

fn direction(variable: &str, r: f64) -> String {
    let up = r > 0.0;
    match variable {
        "impact_y_mm" => if up {
            "rises toward the crown"
        } else {
            "rises toward the sole"
        }
        .into(),
        "impact_z_mm" => if up {
            "rises toward the toe"
        } else {
            "rises toward the heel"
        }
        .into(),
        "impact_r_mm" => if up {
            "rises off-centre"
        } else {
            "falls off-centre"
        }
        .into(),
        v => format!("{} with {v}", if up { "rises" } else { "falls" }),
    }
}

fn fmt_p(p: f64) -> String {
    if p < 1e-16 {
        "p < 1e-16".into()
    } else {
        format!("p = {p:.1e}")
    }
}

/// Compare measured launch with the model's predictions, shot by shot.
pub fn compare(
    shots: &[Shot],
    predicted: &[Launch],
    o: &CompareOptions,
) -> Result<CompareReport, CompareError> {
    o.validate()?;
    let errs = errors_of(shots, predicted)?;
    let mut groups: Vec<&str> = shots.iter().map(|s| s.group.as_str()).collect();
    groups.sort();
    groups.dedup();
    let members =
        |g: &str| -> Vec<usize> { (0..shots.len()).filter(|&k| shots[k].group == g).collect() };
    let mut table2: Vec<GroupBias> = groups
        .iter()
        .map(|g| {
            let e: Vec<&[f64; 5]> = members(g).iter().map(|&k| &errs[k]).collect();
            group_errors(g, &e, o.alpha)
        })
        .collect();
    table2.push(group_errors(
        "all",
        &errs.iter().collect::<Vec<_>>(),
        o.alpha,
    ));

    let mut correlations = Vec::new();
    for c in LaunchComponent::ALL {
        let y: Vec<f64> = errs.iter().map(|e| e[c.index()]).collect();
        for v in &VARIABLES {
            let x: Vec<f64> = shots.iter().map(|s| v.get(s)).collect();
            if let Some(k) = pearson(&x, &y) {
                let significant = k.p < o.alpha;
                correlations.push(CorrelationEntry {
                    component: c.column(),
                    variable: v.name(),
                    n: k.n,
                    r: k.r,
                    t: k.t,
                    p: k.p,
                    significant,
                    strong: significant && k.r.abs() >= o.strong_r,
                });
            }
        }
    }

    // Findings.
    let all = table2.last().expect("all block");
    let mut findings = Vec::new();
    for c in LaunchComponent::ALL {
        let ce = &all.components[c.index()];
        let mut trends: Vec<&CorrelationEntry> = correlations
            .iter()
            .filter(|k| k.component == c.column() && k.strong)
            .collect();
        trends.sort_by(|a, b| b.t.abs().total_cmp(&a.t.abs()));
        if ce.significant {
            let (m, t, p) = (
                ce.summary.mean.unwrap_or(0.0),
                ce.summary.t.unwrap_or(0.0),
                ce.summary.p.unwrap_or(1.0),
            );
            let mut text = format!(
                "{} is {} {} too {} (t = {}, {})",
                c.label(),
                sig3(m.abs()),
                c.unit(),
                if m > 0.0 { "high" } else { "low" },
                fmt_t(t),
                fmt_p(p)
            );
            if let Some(k) = trends.first() {
                text.push_str(&format!(
                    ", {} (r = {:.2} with {})",
                    direction(k.variable, k.r),
                    k.r,
                    k.variable
                ));
            }
            findings.push(Finding {
                component: c.column(),
                pattern: Pattern::Bias,
                strength: t.abs(),
                text,
                hints: hints_for(c, &Pattern::Bias),
            });
        }
        for k in &trends {
            let pattern = Pattern::Trend(k.variable);
            findings.push(Finding {
                component: c.column(),
                pattern,
                strength: k.t.abs(),
                text: format!(
                    "{} error {} (r = {:.2}, t = {}, {})",
                    c.label(),
                    direction(k.variable, k.r),
                    k.r,
                    fmt_t(k.t),
                    fmt_p(k.p)
                ),
                hints: hints_for(c, &pattern),
            });
        }
        // Group differences: largest vs smallest group mean, Bonferroni over the pairs.
        if groups.len() > 1 {
            let block = |g: &str| table2.iter().find(|b| b.group == g).expect("group block");
            let mean_of = |g: &str| block(g).components[c.index()].summary.mean.unwrap_or(0.0);
            let lo = groups
                .iter()
                .copied()
                .min_by(|a, b| mean_of(a).total_cmp(&mean_of(b)));
            let hi = groups
                .iter()
                .copied()
                .max_by(|a, b| mean_of(a).total_cmp(&mean_of(b)));
            if let (Some(lo), Some(hi)) = (lo, hi) {
                let xs = |g: &str| -> Vec<f64> {
                    members(g).iter().map(|&k| errs[k][c.index()]).collect()
                };
                let pairs = groups.len() * (groups.len() - 1) / 2;
                if let Some((t, p)) = welch_t(&xs(hi), &xs(lo)) {
                    if p * (pairs as f64) < o.alpha {
                        let list: Vec<String> = groups
                            .iter()
                            .map(|g| format!("{g} {}", sig3(mean_of(g))))
                            .collect();
                        findings.push(Finding {
                            component: c.column(),
                            pattern: Pattern::GroupBias,
                            strength: t.abs(),
                            text: format!(
                                "{} error differs between groups: {} {} (Welch t = {} for {hi} vs {lo}, {})",
                                c.label(),
                                list.join(", "),
                                c.unit(),
                                fmt_t(t),
                                fmt_p(p)
                            ),
                            hints: hints_for(c, &Pattern::GroupBias),
                        });
                    }
                }
            }
        }
    }
    findings.sort_by(|a, b| b.strength.total_cmp(&a.strength));

    let bias_tests = table2.len() * LaunchComponent::ALL.len();
    let tests = bias_tests + correlations.len();
    let flags = table2
        .iter()
        .flat_map(|b| &b.components)
        .filter(|c| c.significant)
        .count()
        + correlations.iter().filter(|k| k.significant).count();
    Ok(CompareReport {
        n_shots: shots.len(),
        alpha: o.alpha,
        face: face_residuals(shots, &errs, o)?,
        binned: ["club_speed_mph", "dynamic_loft_deg"]
            .iter()
            .map(|n| {
                let v = VARIABLES.iter().find(|v| v.name() == *n).expect("variable");
                binned(v, shots, &errs, o.quantile_bins)
            })
            .collect(),
        table2,
        correlations,
        tests,
        expected_false_flags: tests as f64 * o.alpha,
        flags,
        findings,
    })
}

/// A t statistic for prose: one decimal, or scientific notation when huge.
pub fn fmt_t(t: f64) -> String {
    if t.abs() >= 1e6 {
        format!("{t:.2e}")
    } else {
        format!("{t:.1}")
    }
}

/// Three significant figures (scientific notation from a million up).
pub fn sig3(v: f64) -> String {
    let a = v.abs();
    if a >= 1e6 {
        format!("{v:.2e}")
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::delivery_from_file_units;

    fn shots(n: usize) -> (Vec<Shot>, Vec<Launch>) {
        let launch = Launch {
            ball_speed_m_s: 65.0,
            launch_angle_rad: 0.2,
            azimuth_rad: 0.0,
            backspin_rad_s: 280.0,
            sidespin_rad_s: 0.0,
        };
        let shots = (0..n)
            .map(|i| {
                let mut v = DeliveryVar::ALL.map(|v| v.range().min.max(0.0));
                v[DeliveryVar::ClubSpeed.index()] = 95.0 + i as f64;
                v[DeliveryVar::DynamicLoft.index()] = 12.0;
                v[DeliveryVar::ImpactZ.index()] = i as f64 - 5.0;
                Shot {
                    id: format!("s{i}"),
                    group: "all".into(),
                    golfer: None,
                    delivery: delivery_from_file_units(&v),
                    measured: Some(launch),
                }
            })
            .collect();
        let predicted = (0..n)
            .map(|i| Launch {
                ball_speed_m_s: 65.0 + 0.1 * i as f64,
                ..launch
            })
            .collect();
        (shots, predicted)
    }

    #[test]
    fn a_bad_bin_size_is_an_error_not_an_allocation() {
        let (s, p) = shots(12);
        for bin in [0.0, -1.0, f64::NAN, 1e-300, f64::INFINITY] {
            let o = CompareOptions {
                face_bin_mm: bin,
                ..CompareOptions::default()
            };
            match compare(&s, &p, &o) {
                Err(CompareError::Option(e)) => assert_eq!(e.option, "face_bin_mm"),
                other => panic!("bin {bin}: {:?}", other.map(|r| r.table2.len())),
            }
            assert!(CompareOptions::default().with_face_bin_mm(bin).is_err());
        }
        assert!(compare(&s, &p, &CompareOptions::default()).is_ok());
    }

    #[test]
    fn builders_check_each_option() {
        let o = CompareOptions::default();
        assert!(o.with_alpha(0.0).is_err());
        assert!(o.with_alpha(1.0).is_err());
        assert!(o.with_alpha(f64::NAN).is_err());
        assert_eq!(o.with_alpha(0.05).unwrap().alpha, 0.05);
        assert!(o.with_min_bin_count(0).is_err());
        assert!(o.with_quantile_bins(0).is_err());
        assert!(o.with_strong_r(1.5).is_err());
        let b = o.with_face_bin_mm(3.0).unwrap();
        assert_eq!(b.face_bin_mm, 3.0);
        assert!(b.validate().is_ok());
    }
}
