//! What a mapped column feeds: the shots columns an import may write, with their units.

use super::units::{Quantity, Unit};
use crate::data::shots::measured_range;
use crate::limits::{self, PhysicalRange};
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;

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
    /// Text columns.
    ShotId,
    Group,
    Golfer,
    Status,
}

/// Flight columns an import may carry through, with their units, in output order.
const FLIGHT_NUMERIC: [(&str, &str); 6] = [
    ("carry_yd", "yd"),
    ("apex_yd", "yd"),
    ("total_yd", "yd"),
    ("offline_yd", "yd"),
    ("land_angle_deg", "deg"),
    ("dynamic_lie_deg", "deg"),
];

/// Numeric shots columns an import may write, with their units, in output order: the delivery
/// variables (launch monitors do not measure the clubhead's angular velocity), the launch
/// components, then the flight columns.
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
        .collect()
}

/// Columns an empty cell may not leave empty even when the column itself may be absent.
pub(super) fn is_core(target: &str) -> bool {
    !matches!(
        target,
        "carry_yd" | "apex_yd" | "total_yd" | "offline_yd" | "land_angle_deg" | "dynamic_lie_deg"
    )
}

impl Target {
    pub(super) fn parse(s: &str) -> Option<Target> {
        Some(match s {
            "impact_offset_mm" => Target::ImpactOffset,
            "spin_rate_rpm" => Target::SpinRate,
            "spin_axis_deg" => Target::SpinAxis,
            "shot_id" => Target::ShotId,
            "group" => Target::Group,
            "golfer" => Target::Golfer,
            "status" => Target::Status,
            _ => {
                let (c, u) = numeric().into_iter().find(|(c, _)| *c == s)?;
                Target::Num(c, u)
            }
        })
    }

    pub(super) fn names() -> Vec<&'static str> {
        let mut v: Vec<&str> = numeric().into_iter().map(|(c, _)| c).collect();
        v.extend([
            "impact_offset_mm",
            "spin_rate_rpm",
            "spin_axis_deg",
            "shot_id",
            "group",
            "golfer",
            "status",
        ]);
        v
    }

    /// The unit values are converted to.
    pub(super) fn unit(self) -> Option<Unit> {
        let name = match self {
            Target::Num(_, u) => u,
            Target::ImpactOffset => "mm",
            Target::SpinRate => "rpm",
            Target::SpinAxis => "deg",
            _ => return None,
        };
        Unit::parse(name)
    }

    /// The physical range of the values it feeds (shots-file units), when it has one: the
    /// delivery's and the launch's, the impact offset's, the spin rate's and axis's (the
    /// flight columns are checked when the shots are read).
    pub(super) fn range(self) -> Option<PhysicalRange> {
        match self {
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
