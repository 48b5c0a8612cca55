//! The delivery conventions a mapping records per column (`at`, `how`) and the three shots
//! columns they become (`face_at`, `velocity_at`, `face_angle_from`; [`crate::model::convention`]).
//!
//! Dynamic loft and face angle are one orientation and share one point; club speed, attack
//! angle and path are one velocity and share one point. Only the face angle may be derived
//! from the launch (the model can stand in for it: [`crate::model::convention`]).

use super::{ColumnSpec, Mapping};
use crate::model::convention::{
    name_of, names, parse_name, DeliveryConvention, FaceAngleSource, FacePoint, VelocityPoint,
    FACE_ANGLE_FROM_COLUMN, FACE_AT_COLUMN, VELOCITY_AT_COLUMN,
};

/// Targets that are the face's orientation.
const ORIENTATION: [&str; 2] = ["dynamic_loft_deg", "face_angle_deg"];
/// Targets that are the head's velocity.
const VELOCITY: [&str; 3] = ["club_speed_mph", "attack_angle_deg", "club_path_deg"];
/// Values of `how`.
const HOW: [(FaceAngleSource, &str); 2] = FaceAngleSource::ALL;

/// A mapping's `at` or `how` that its target does not allow ([`check_column`],
/// [`check_mapping`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MappingError {
    /// `at` on a target that is not a delivery angle or velocity.
    #[error(
        "target '{target}': `at` is for the delivery's angles and velocity ({}, {})",
        ORIENTATION.join(", "),
        VELOCITY.join(", ")
    )]
    AtNotForTarget {
        /// The column's target.
        target: String,
    },
    /// An `at` the target does not know.
    #[error("target '{target}': at = '{at}' is not known (allowed: {allowed})")]
    AtUnknown {
        /// The column's target.
        target: String,
        /// The `at` given.
        at: String,
        /// The points allowed.
        allowed: String,
    },
    /// A `how` that is not known.
    #[error("target '{target}': how = '{how}' is not known (allowed: {})", names(&HOW))]
    HowUnknown {
        /// The column's target.
        target: String,
        /// The `how` given.
        how: String,
    },
    /// `derived_from_launch` on another target than the face angle.
    #[error(
        "target '{target}': only face_angle_deg may be derived_from_launch (smash can stand in \
         for a face angle, not for other derived values: leave such a column unmapped)"
    )]
    DerivedNotFace {
        /// The column's target.
        target: String,
    },
    /// `how` on a column that is not a delivery column.
    #[error("target '{target}': `how` is for delivery columns")]
    HowNotDelivery {
        /// The column's target.
        target: String,
    },
    /// Two columns of one orientation or velocity stating different points.
    #[error(
        "targets '{a}' (at = {at_a}) and '{b}' (at = {at_b}) must state the same point: they \
         are one {kind}"
    )]
    PointsDiffer {
        /// One target.
        a: String,
        /// Its point, or `(not stated)`.
        at_a: String,
        /// The other target.
        b: String,
        /// Its point, or `(not stated)`.
        at_b: String,
        /// `orientation` or `velocity`.
        kind: &'static str,
    },
}

/// One column's `at` and `how`: allowed for its target.
pub(super) fn check_column(c: &ColumnSpec) -> Result<(), MappingError> {
    let t = c.target.as_str();
    let target = || t.to_owned();
    if let Some(at) = &c.at {
        let known = if ORIENTATION.contains(&t) {
            parse_name(&FacePoint::ALL, at)
                .is_some()
                .then_some(())
                .ok_or(names(&FacePoint::ALL))
        } else if VELOCITY.contains(&t) {
            parse_name(&VelocityPoint::ALL, at)
                .is_some()
                .then_some(())
                .ok_or(names(&VelocityPoint::ALL))
        } else {
            return Err(MappingError::AtNotForTarget { target: target() });
        };
        known.map_err(|allowed| MappingError::AtUnknown {
            target: target(),
            at: at.clone(),
            allowed,
        })?;
    }
    if let Some(how) = &c.how {
        let v = parse_name(&HOW, how).ok_or_else(|| MappingError::HowUnknown {
            target: target(),
            how: how.clone(),
        })?;
        if v == FaceAngleSource::Launch && t != "face_angle_deg" {
            return Err(MappingError::DerivedNotFace { target: target() });
        }
        if !ORIENTATION.contains(&t) && !VELOCITY.contains(&t) && !t.starts_with("impact_") {
            return Err(MappingError::HowNotDelivery { target: target() });
        }
    }
    Ok(())
}

/// The columns of one orientation or velocity state one point.
pub(super) fn check_mapping(m: &Mapping) -> Result<(), MappingError> {
    for group in [&ORIENTATION[..], &VELOCITY[..]] {
        let stated: Vec<(&str, Option<&str>)> = m
            .column
            .iter()
            .filter(|c| group.contains(&c.target.as_str()))
            .map(|c| (c.target.as_str(), c.at.as_deref()))
            .collect();
        if let Some(((a, pa), (b, pb))) = stated
            .iter()
            .zip(stated.iter().skip(1))
            .find(|((_, x), (_, y))| x != y)
        {
            let show = |p: &Option<&str>| p.unwrap_or("(not stated)").to_owned();
            return Err(MappingError::PointsDiffer {
                a: (*a).to_owned(),
                at_a: show(pa),
                b: (*b).to_owned(),
                at_b: show(pb),
                kind: if group.len() == 2 {
                    "orientation"
                } else {
                    "velocity"
                },
            });
        }
    }
    Ok(())
}

/// The convention the mapping states for the columns it maps (`mapped` tells which targets the
/// export has).
pub(super) fn of_mapping(m: &Mapping, mapped: &dyn Fn(&str) -> bool) -> DeliveryConvention {
    let at = |group: &[&str]| {
        m.column
            .iter()
            .filter(|c| group.contains(&c.target.as_str()) && mapped(&c.target))
            .find_map(|c| c.at.clone())
    };
    let face_from = m
        .column
        .iter()
        .find(|c| c.target == "face_angle_deg" && mapped(&c.target))
        .and_then(|c| c.how.as_deref())
        .and_then(|h| parse_name(&HOW, h))
        .unwrap_or_default();
    DeliveryConvention {
        face_at: at(&ORIENTATION)
            .and_then(|a| parse_name(&FacePoint::ALL, &a))
            .unwrap_or_default(),
        velocity_at: at(&VELOCITY)
            .and_then(|a| parse_name(&VelocityPoint::ALL, &a))
            .unwrap_or_default(),
        face_angle_from: face_from,
    }
}

/// The shots columns a convention is written as, with their values.
pub(super) fn cells(c: DeliveryConvention) -> [(&'static str, &'static str); 3] {
    [
        (FACE_AT_COLUMN, name_of(&FacePoint::ALL, c.face_at)),
        (
            VELOCITY_AT_COLUMN,
            name_of(&VelocityPoint::ALL, c.velocity_at),
        ),
        (
            FACE_ANGLE_FROM_COLUMN,
            name_of(&FaceAngleSource::ALL, c.face_angle_from),
        ),
    ]
}
