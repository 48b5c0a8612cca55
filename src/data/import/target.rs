//! What a mapped column feeds: the shots columns an import may write, with their units.

use super::units::{Quantity, Unit};
use crate::data::shots::measured_range;
use crate::limits::{self, PhysicalRange};
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;

/// The measured-launch columns written only when the whole launch is measured.
pub(super) const LAUNCH: [&str; 3] = ["ball_speed_mph", "launch_angle_deg", "azimuth_deg"];

/// What a mapped column feeds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Target {
    /// A numeric shots column with its unit.
    Num(&'static str, &'static str),
    /// Heel–toe offset, sign stated by the user.
    ImpactOffset,
    /// Total spin, rpm.
    SpinRate,
    /// Spin axis tilt, deg (+ tilts right: the ball curves right).
    SpinAxis,
    /// Smash factor (ball speed / club speed): checked against the two speeds, not written.
    SmashFactor,
    /// Length of the radar's track, yd (TrackMan's `Last data Point - Length`): a track that
    /// ends well short of the carry means the carry is the vendor's flight model.
    TrackedLength,
    /// Text columns.
    ShotId,
    Group,
    Golfer,
    Status,
    /// The ball model the monitor names (`Premium`, `Range`), written as `ball_type`.
    BallType,
    /// When the shot was hit (a date, a time of day or both, as the export writes them),
    /// written as `datetime`: what cross-validation folds are grouped by when the shots name no
    /// golfer (sessions by date, time blocks within one; `crate::data::sessions`).
    Datetime,
    /// A statement of the conditions the data are normalised to (TrackMan's `Condition`):
    /// read into `altitude_m`, `air_temperature_c`, `ball_type` and `flight_modelled`.
    Condition,
    /// 0/1 flags: the cell values of the column's `estimated` list set them.
    SpinEstimated,
    ClubEstimated,
}

/// Flight columns an import may carry through, with their units, in output order.
const FLIGHT_NUMERIC: [(&str, &str); 7] = [
    ("carry_yd", "yd"),
    ("apex_yd", "yd"),
    ("total_yd", "yd"),
    ("offline_yd", "yd"),
    ("land_angle_deg", "deg"),
    ("flight_time_s", "s"),
    ("dynamic_lie_deg", "deg"),
];

/// The conditions a monitor states, with their units: the atmosphere a shot flew in (or was
/// normalised to).
pub(super) const CONDITIONS: [(&str, &str); 4] = [
    ("altitude_m", "m"),
    ("air_temperature_c", "°C"),
    ("air_pressure_pa", "Pa"),
    ("relative_humidity_pct", "%"),
];

/// Numeric shots columns an import may write, with their units, in output order: the delivery
/// variables (launch monitors do not measure the clubhead's angular velocity), the launch
/// components, the flight columns, then the conditions.
pub(super) fn numeric() -> Vec<(&'static str, &'static str)> {
    DeliveryVar::ALL
        .into_iter()
        .filter(|v| {
            !matches!(
                v,
                DeliveryVar::OmegaX | DeliveryVar::OmegaY | DeliveryVar::OmegaZ
            )
        })
        .map(|v| (v.column(), v.unit()))
        .chain(LaunchComponent::ALL.map(|c| (c.column(), c.unit())))
        .chain(FLIGHT_NUMERIC)
        .chain(CONDITIONS)
        .collect()
}

/// The special targets, by name.
const SPECIAL: [(&str, Target); 14] = [
    ("impact_offset_mm", Target::ImpactOffset),
    ("spin_rate_rpm", Target::SpinRate),
    ("spin_axis_deg", Target::SpinAxis),
    ("smash_factor", Target::SmashFactor),
    ("tracked_length_yd", Target::TrackedLength),
    ("shot_id", Target::ShotId),
    ("group", Target::Group),
    ("golfer", Target::Golfer),
    ("status", Target::Status),
    ("ball_type", Target::BallType),
    ("datetime", Target::Datetime),
    ("condition", Target::Condition),
    ("spin_estimated", Target::SpinEstimated),
    ("club_estimated", Target::ClubEstimated),
];

impl Target {
    pub(super) fn parse(s: &str) -> Option<Target> {
        if let Some((_, t)) = SPECIAL.iter().find(|(n, _)| *n == s) {
            return Some(*t);
        }
        let (c, u) = numeric().into_iter().find(|(c, _)| *c == s)?;
        Some(Target::Num(c, u))
    }

    pub(super) fn names() -> Vec<&'static str> {
        let mut v: Vec<&str> = numeric().into_iter().map(|(c, _)| c).collect();
        v.extend(SPECIAL.iter().map(|(n, _)| *n));
        v
    }

    /// The unit values are converted to.
    pub(super) fn unit(self) -> Option<Unit> {
        let name = match self {
            Target::Num(_, u) => u,
            Target::ImpactOffset => "mm",
            Target::SpinRate => "rpm",
            Target::SpinAxis => "deg",
            Target::TrackedLength => "yd",
            _ => return None,
        };
        Unit::parse(name)
    }

    /// The physical range of the values it feeds (shots-file units), when it has one: the
    /// delivery's and the launch's, the impact offset's, the spin rate's and axis's (the
    /// flight columns are checked when the shots are read).
    pub(super) fn range(self) -> Option<PhysicalRange> {
        match self {
            Target::Num(c, _) if condition_range(c).is_some() => condition_range(c),
            Target::Num(c, _) => {
                DeliveryVar::from_column(c)
                    .map(DeliveryVar::range)
                    .or_else(|| {
                        LaunchComponent::ALL
                            .into_iter()
                            .find(|l| l.column() == c)
                            .map(measured_range)
                    })
            }
            Target::ImpactOffset => Some(limits::IMPACT_LOCATION_MM),
            Target::SpinRate => Some(limits::SPIN_RATE_RPM),
            Target::SpinAxis => Some(limits::SPIN_AXIS_DEG),
            _ => None,
        }
    }

    pub(super) fn quantity(self) -> Option<Quantity> {
        self.unit().map(|u| u.quantity)
    }
}

/// The range of a stated condition: altitude from the Dead Sea shore (−430 m) to 5,000 m (no
/// golf course lies higher: the highest, in the Andes and Himalaya, are near 4,000 m); air
/// from −30 °C to 60 °C (past the hottest air temperature recorded, 56.7 °C); pressure from
/// 50 kPa (about 5,500 m in the standard atmosphere) to 110 kPa (above the highest sea-level
/// pressure recorded, 108.4 kPa); relative humidity 0–100 %.
fn condition_range(column: &str) -> Option<PhysicalRange> {
    let (quantity, unit, min, max) = match column {
        "altitude_m" => ("altitude", "m", -430.0, 5000.0),
        "air_temperature_c" => ("air temperature", "°C", -30.0, 60.0),
        "air_pressure_pa" => ("air pressure", "Pa", 50_000.0, 110_000.0),
        "relative_humidity_pct" => ("relative humidity", "%", 0.0, 100.0),
        _ => return None,
    };
    Some(PhysicalRange {
        quantity,
        unit,
        min,
        max,
        min_inclusive: true,
    })
}
