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

    /// Index in [`Output::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Output::Launch(c) => c.index(),
            Output::SmashFactor => 5,
        }
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

/// A side of the face centre a speed-loss slope is taken toward.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// `+z`, along the horizontal line.
    Toe,
    /// `−z`, along the horizontal line.
    Heel,
    /// `+y`, along the vertical line.
    Crown,
    /// `−y`, along the vertical line.
    Sole,
}

impl Side {
    /// All sides in file order.
    pub const ALL: [Side; 4] = [Side::Toe, Side::Heel, Side::Crown, Side::Sole];

    /// The name in metric names.
    pub const fn name(self) -> &'static str {
        match self {
            Side::Toe => "toe",
            Side::Heel => "heel",
            Side::Crown => "crown",
            Side::Sole => "sole",
        }
    }
}

/// One scalar metric of a design (see the table in the module docs). Adding a metric is one
/// variant here plus its arms in [`Metric::name`], [`Metric::unit`], [`Metric::all`] and
/// [`super::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Metric {
    /// `cof_<output>`: the output for a strike at the centre of face.
    Centre(Output),
    /// `speed_loss_<side>_mph_per_mm`: the ball-speed slope away from the centre.
    SpeedLoss(Side),
    /// `gear_sidespin_rpm_per_mm`: sidespin slope along the horizontal line.
    GearSidespin,
    /// `gear_backspin_rpm_per_mm`: backspin slope along the vertical line.
    GearBackspin,
    /// `mean_<output>` over the distribution.
    Mean(Output),
    /// `std_<output>` over the distribution.
    Std(Output),
}

impl Metric {
    /// All metrics in file order; [`Metric::Mean`] and [`Metric::Std`] only with a distribution.
    pub fn all(with_distribution: bool) -> Vec<Metric> {
        let mut v: Vec<Metric> = Output::ALL.map(Metric::Centre).to_vec();
        v.extend(Side::ALL.map(Metric::SpeedLoss));
        v.extend([Metric::GearSidespin, Metric::GearBackspin]);
        if with_distribution {
            v.extend(Output::ALL.map(Metric::Mean));
            v.extend(Output::ALL.map(Metric::Std));
        }
        v
    }

    /// Name (with unit), as in files and in `[optimise] objective`.
    pub fn name(self) -> String {
        match self {
            Metric::Centre(o) => format!("cof_{}", o.column()),
            Metric::SpeedLoss(s) => format!("speed_loss_{}_mph_per_mm", s.name()),
            Metric::GearSidespin => "gear_sidespin_rpm_per_mm".into(),
            Metric::GearBackspin => "gear_backspin_rpm_per_mm".into(),
            Metric::Mean(o) => format!("mean_{}", o.column()),
            Metric::Std(o) => format!("std_{}", o.column()),
        }
    }

    /// Unit, for tables (`mph`, `rpm/mm`, `1`).
    pub const fn unit(self) -> &'static str {
        match self {
            Metric::Centre(o) | Metric::Mean(o) | Metric::Std(o) => o.unit(),
            Metric::SpeedLoss(_) => "mph/mm",
            Metric::GearSidespin | Metric::GearBackspin => "rpm/mm",
        }
    }

    /// Whether the metric needs a `[distribution]`.
    pub const fn needs_distribution(self) -> bool {
        matches!(self, Metric::Mean(_) | Metric::Std(_))
    }

    /// The metric of a name (any metric, with or without a distribution).
    pub fn from_name(name: &str) -> Option<Metric> {
        Metric::all(true).into_iter().find(|m| m.name() == name)
    }
}

/// Metric names, in file order; `mean_*` and `std_*` only with a distribution.
pub fn metric_names(with_distribution: bool) -> Vec<String> {
    Metric::all(with_distribution)
        .into_iter()
        .map(Metric::name)
        .collect()
}

/// Unit of a metric name, for tables (`mph`, `rpm/mm`, `1`; `1` for an unknown name).
pub fn metric_unit(name: &str) -> String {
    Metric::from_name(name).map_or("1", Metric::unit).into()
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
        assert_eq!(metric_unit("cof_launch_angle_deg"), "deg");
    }

    #[test]
    fn names_are_unique_and_read_back() {
        let all = Metric::all(true);
        assert_eq!(all.len(), 6 + 4 + 2 + 6 + 6);
        for m in &all {
            assert_eq!(Metric::from_name(&m.name()), Some(*m));
            assert!(m.name().ends_with(&m.unit().replace('/', "_per_")) || m.unit() == "1");
        }
        let without = Metric::all(false);
        assert!(without.iter().all(|m| !m.needs_distribution()));
        assert_eq!(&all[..without.len()], &without[..]);
    }
}
