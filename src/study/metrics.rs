//! Outputs of a study and the scalar metrics that summarise a design.
//!
//! Metrics, all in file units (names carry the unit):
//!
//! | metric | definition |
//! |---|---|
//! | `cof_<output>` | the output for a strike at the centre of face |
//! | `speed_loss_toe_mph_per_mm` | −(least-squares slope of ball speed vs z) over `z ∈ [0, L]` at `y = 0` |
//! | `speed_loss_heel_mph_per_mm` | the same over `z ∈ [−L, 0]`, per mm toward the heel |
//! | `speed_loss_crown_mph_per_mm` | the same vs y over `y ∈ [0, L]` at `z = 0` |
//! | `speed_loss_sole_mph_per_mm` | the same over `y ∈ [−L, 0]`, per mm toward the sole |
//! | `gear_sidespin_rpm_per_mm` | slope of sidespin vs z over `z ∈ [−L, L]` at `y = 0` (horizontal gear effect; negative = toe hits hook) |
//! | `gear_backspin_rpm_per_mm` | slope of backspin vs y over `y ∈ [−L, L]` at `z = 0` (vertical gear effect) |
//! | `mean_<output>`, `std_<output>` | weighted mean and standard deviation over the `[distribution]` |
//!
//! `L` is the summary half-width (`[summary] half_width_mm`), probed every `step_mm`. Positive
//! speed loss means the ball is slower off centre. A metric that needs an impact that cannot be
//! computed (off the face) is NaN in memory and an empty cell in files. They are computed by
//! [`super::evaluate`].

use crate::physics::LaunchComponent;
use crate::sweep::kernel::LaunchGrid;

/// One mapped output: a launch component or the smash factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Output {
    /// A launch component.
    Launch(LaunchComponent),
    /// Ball speed over clubhead speed.
    SmashFactor,
}

impl Output {
    /// All outputs in file order.
    pub const ALL: [Output; 6] = [
        Output::Launch(LaunchComponent::BallSpeed),
        Output::Launch(LaunchComponent::LaunchAngle),
        Output::Launch(LaunchComponent::Azimuth),
        Output::Launch(LaunchComponent::Backspin),
        Output::Launch(LaunchComponent::Sidespin),
        Output::SmashFactor,
    ];

    /// Column name (with unit).
    pub const fn column(self) -> &'static str {
        match self {
            Output::Launch(c) => c.column(),
            Output::SmashFactor => "smash_factor",
        }
    }

    /// Unit (`1` for the smash factor).
    pub const fn unit(self) -> &'static str {
        match self {
            Output::Launch(c) => c.unit(),
            Output::SmashFactor => "1",
        }
    }

    /// Human label.
    pub const fn label(self) -> &'static str {
        match self {
            Output::Launch(c) => c.label(),
            Output::SmashFactor => "Smash factor",
        }
    }

    /// Whether the values change sign across the face (diverging colour scale).
    pub const fn signed(self) -> bool {
        matches!(
            self,
            Output::Launch(LaunchComponent::Azimuth | LaunchComponent::Sidespin)
        )
    }

    /// From a column name.
    pub fn from_column(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|o| o.column() == s)
    }

    /// All column names, comma-separated.
    pub fn all_columns() -> String {
        Self::ALL.map(|o| o.column()).join(", ")
    }

    /// The value at point `i` of `grid` in file units (NaN when invalid).
    pub fn file_value(self, grid: &LaunchGrid, i: usize, club_speed_m_s: f64) -> f64 {
        if !grid.valid[i] {
            return f64::NAN;
        }
        match self {
            Output::Launch(c) => grid.component(c)[i] * c.file_units_per_si(),
            Output::SmashFactor => grid.ball_speed_m_s[i] / club_speed_m_s,
        }
    }
}

/// Metric names, in file order; `mean_*` and `std_*` only with a distribution.
pub fn metric_names(with_distribution: bool) -> Vec<String> {
    let mut v: Vec<String> = Output::ALL
        .iter()
        .map(|o| format!("cof_{}", o.column()))
        .collect();
    for side in ["toe", "heel", "crown", "sole"] {
        v.push(format!("speed_loss_{side}_mph_per_mm"));
    }
    v.push("gear_sidespin_rpm_per_mm".into());
    v.push("gear_backspin_rpm_per_mm".into());
    if with_distribution {
        for o in Output::ALL {
            v.push(format!("mean_{}", o.column()));
        }
        for o in Output::ALL {
            v.push(format!("std_{}", o.column()));
        }
    }
    v
}

/// Unit of a metric, for tables (`mph`, `rpm/mm`, `1`).
pub fn metric_unit(name: &str) -> String {
    if let Some(rest) = name.strip_suffix("_per_mm") {
        let u = rest.rsplit('_').next().unwrap_or("");
        return format!("{u}/mm");
    }
    let col = name
        .strip_prefix("cof_")
        .or_else(|| name.strip_prefix("mean_"))
        .or_else(|| name.strip_prefix("std_"))
        .unwrap_or(name);
    Output::from_column(col).map_or("1".into(), |o| o.unit().into())
}

/// Least-squares slope of `v` against `x`; NaN if any value is NaN.
pub fn ls_slope(x: &[f64], v: &[f64]) -> f64 {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let mv = v.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let sxv: f64 = x.iter().zip(v).map(|(a, b)| (a - mx) * (b - mv)).sum();
    sxv / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_line_is_exact() {
        let x = [-2.0, 0.0, 1.0, 5.0];
        let v: Vec<f64> = x.iter().map(|x| 3.0 - 0.5 * x).collect();
        assert!((ls_slope(&x, &v) + 0.5).abs() < 1e-14);
    }

    #[test]
    fn metric_units_follow_names() {
        assert_eq!(metric_unit("cof_ball_speed_mph"), "mph");
        assert_eq!(metric_unit("std_sidespin_rpm"), "rpm");
        assert_eq!(metric_unit("gear_sidespin_rpm_per_mm"), "rpm/mm");
        assert_eq!(metric_unit("speed_loss_toe_mph_per_mm"), "mph/mm");
        assert_eq!(metric_unit("mean_smash_factor"), "1");
    }
}
