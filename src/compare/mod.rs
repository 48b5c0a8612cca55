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
//!   [`signatures`]: which library effects produce such a pattern, and, given their measured
//!   signatures ([`UserHints`]), which user-defined effects can cancel it.
//!
//! Undefined statistics are `None`, never NaN.

mod findings;
pub mod signatures;
mod tables;
pub mod user_hints;

use serde::Serialize;

use crate::limits::OptionError;
use crate::model::{DeliveryVar, Shot, N_DELIVERY};
use crate::physics::{Launch, LaunchComponent};
use crate::stats::Summary;

pub use signatures::{hints_for, signatures, Hint, Pattern, Signature};
pub use user_hints::{UserHints, UserSignature};

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
    /// Library effects that produce such a pattern (from [`signatures`]).
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
    /// Why the shots do not match the club, when a caller compared them anyway (then there
    /// are no findings: errors of another club's shots say nothing about this head). In the
    /// JSON only when there is a mismatch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub club_mismatch: Option<String>,
    /// What the run warned about: rows of the shots file left out, one note per reason (set
    /// by the caller that read the file).
    pub warnings: Vec<String>,
}

impl CompareReport {
    /// The report of shots that do not match the club (`why`): no findings.
    pub fn mismatched(mut self, why: String) -> Self {
        self.findings.clear();
        self.club_mismatch = Some(why);
        self
    }
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

/// Compare measured launch with the model's predictions, shot by shot, with the library's
/// effect hints.
pub fn compare(
    shots: &[Shot],
    predicted: &[Launch],
    o: &CompareOptions,
) -> Result<CompareReport, CompareError> {
    compare_with_hints(shots, predicted, o, &UserHints::default())
}

/// [`compare`], with hints at the user-defined effects whose signatures `user` holds (measured
/// on these shots by [`UserHints::measure`]).
pub fn compare_with_hints(
    shots: &[Shot],
    predicted: &[Launch],
    o: &CompareOptions,
    user: &UserHints,
) -> Result<CompareReport, CompareError> {
    o.validate()?;
    let errs = tables::errors_of(shots, predicted)?;
    let group_of: Vec<&str> = shots.iter().map(|s| s.group.as_str()).collect();
    let mut groups = group_of.clone();
    groups.sort();
    groups.dedup();
    let mut table2: Vec<GroupBias> = groups
        .iter()
        .map(|g| {
            let e: Vec<&[f64; 5]> = errs
                .iter()
                .zip(&group_of)
                .filter(|(_, sg)| *sg == g)
                .map(|(e, _)| e)
                .collect();
            tables::group_errors(g, &e, o.alpha)
        })
        .collect();
    table2.push(tables::group_errors(
        "all",
        &errs.iter().collect::<Vec<_>>(),
        o.alpha,
    ));
    let correlations = tables::correlations(shots, &errs, o);
    let findings = findings::Evidence {
        errs: &errs,
        group_of: &group_of,
        groups: &groups,
        table2: &table2,
        correlations: &correlations,
        o,
        user,
    }
    .findings();

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
        face: tables::face_residuals(shots, &errs, o)?,
        binned: ["club_speed_mph", "dynamic_loft_deg"]
            .iter()
            .map(|n| {
                let v = VARIABLES.iter().find(|v| v.name() == *n).expect("variable");
                tables::binned(v, shots, &errs, o.quantile_bins)
            })
            .collect(),
        table2,
        correlations,
        tests,
        expected_false_flags: tests as f64 * o.alpha,
        flags,
        findings,
        club_mismatch: None,
        warnings: Vec::new(),
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

/// Three significant figures (scientific notation from a million up and below 0.001, where three
/// decimals would print a value that is not zero as zero: a COR falloff of 2.5e-4 per mm² is
/// `2.50e-4`, not `0.000`).
pub fn sig3(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e6).contains(&a) {
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
