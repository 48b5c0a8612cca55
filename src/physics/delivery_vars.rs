//! The delivery variables: the eleven numbers a shots file gives for how the club met the ball,
//! in shots-file column order and file units (mph, deg, rad/s, mm), with their physical ranges
//! and the typical noise of the instruments that measure them (and of the launch monitor).
//!
//! Shared by the synthetic experiments (which generate them), the noise-floor diagnosis and the
//! noise file (which assume their noise), and by user-defined effects (whose expressions read
//! them by column name), so it sits in `physics`, below all of them; [`crate::model`]
//! re-exports it as `model::delivery`.

use nalgebra::Vector3;

use super::{Delivery, LaunchComponent};
use crate::limits::{self, PhysicalRange};
use crate::units::{deg, mm, mph, M_S_PER_MPH};

/// The delivery variables, in shots-file column order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeliveryVar {
    /// Clubhead CoM speed, mph.
    ClubSpeed,
    /// Attack angle, deg.
    AttackAngle,
    /// Club path, deg.
    ClubPath,
    /// Dynamic loft, deg.
    DynamicLoft,
    /// Face angle, deg.
    FaceAngle,
    /// Lie tilt, deg.
    LieTilt,
    /// Clubhead angular velocity about ground x, rad/s.
    OmegaX,
    /// About ground y (up), rad/s.
    OmegaY,
    /// About ground z, rad/s.
    OmegaZ,
    /// Impact location up the face, mm.
    ImpactY,
    /// Impact location toward the toe, mm.
    ImpactZ,
}

/// Number of delivery variables.
pub const N_DELIVERY: usize = 11;

impl DeliveryVar {
    /// All variables in column order.
    pub const ALL: [DeliveryVar; N_DELIVERY] = [
        Self::ClubSpeed,
        Self::AttackAngle,
        Self::ClubPath,
        Self::DynamicLoft,
        Self::FaceAngle,
        Self::LieTilt,
        Self::OmegaX,
        Self::OmegaY,
        Self::OmegaZ,
        Self::ImpactY,
        Self::ImpactZ,
    ];

    /// Shots-file column (and config key).
    pub const fn column(self) -> &'static str {
        match self {
            Self::ClubSpeed => "club_speed_mph",
            Self::AttackAngle => "attack_angle_deg",
            Self::ClubPath => "club_path_deg",
            Self::DynamicLoft => "dynamic_loft_deg",
            Self::FaceAngle => "face_angle_deg",
            Self::LieTilt => "lie_tilt_deg",
            Self::OmegaX => "club_omega_x_rad_s",
            Self::OmegaY => "club_omega_y_rad_s",
            Self::OmegaZ => "club_omega_z_rad_s",
            Self::ImpactY => "impact_y_mm",
            Self::ImpactZ => "impact_z_mm",
        }
    }

    /// Default measurement noise SD on the delivery (motion capture), file units.
    pub const fn default_noise(self) -> f64 {
        match self {
            Self::ClubSpeed => 0.4,
            Self::AttackAngle | Self::ClubPath | Self::FaceAngle => 0.3,
            Self::DynamicLoft => 0.5,
            Self::LieTilt => 0.5,
            Self::OmegaX | Self::OmegaY | Self::OmegaZ => 0.5,
            Self::ImpactY | Self::ImpactZ => 1.5,
        }
    }

    /// The physically meaningful values of the variable (see [`crate::limits`]).
    pub const fn range(self) -> PhysicalRange {
        match self {
            Self::ClubSpeed => limits::CLUB_SPEED_MPH,
            Self::DynamicLoft => limits::DYNAMIC_LOFT_DEG,
            Self::AttackAngle | Self::ClubPath | Self::FaceAngle | Self::LieTilt => {
                limits::DELIVERY_ANGLE_DEG
            }
            Self::OmegaX | Self::OmegaY | Self::OmegaZ => limits::CLUB_OMEGA_RAD_S,
            Self::ImpactY | Self::ImpactZ => limits::IMPACT_LOCATION_MM,
        }
    }

    /// Index in [`DeliveryVar::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// File unit (`mph`, `deg`, `rad/s`, `mm`).
    pub const fn unit(self) -> &'static str {
        match self {
            Self::ClubSpeed => "mph",
            Self::AttackAngle
            | Self::ClubPath
            | Self::DynamicLoft
            | Self::FaceAngle
            | Self::LieTilt => "deg",
            Self::OmegaX | Self::OmegaY | Self::OmegaZ => "rad/s",
            Self::ImpactY | Self::ImpactZ => "mm",
        }
    }

    /// Whether a shots file must have the column (the others default to 0).
    pub const fn required(self) -> bool {
        !matches!(
            self,
            Self::LieTilt | Self::OmegaX | Self::OmegaY | Self::OmegaZ
        )
    }

    /// The variable of a shots-file column.
    pub fn from_column(column: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|v| v.column() == column)
    }

    /// The variable's value in `d`, file units.
    pub fn file_value(self, d: &Delivery) -> f64 {
        match self {
            Self::ClubSpeed => d.club_speed_m_s / M_S_PER_MPH,
            Self::AttackAngle => d.attack_angle_rad.to_degrees(),
            Self::ClubPath => d.club_path_rad.to_degrees(),
            Self::DynamicLoft => d.dynamic_loft_rad.to_degrees(),
            Self::FaceAngle => d.face_angle_rad.to_degrees(),
            Self::LieTilt => d.lie_tilt_rad.to_degrees(),
            Self::OmegaX => d.club_omega_rad_s.x,
            Self::OmegaY => d.club_omega_rad_s.y,
            Self::OmegaZ => d.club_omega_rad_s.z,
            Self::ImpactY => d.impact_y_m * 1e3,
            Self::ImpactZ => d.impact_z_m * 1e3,
        }
    }

    /// Sets the variable in `d` from a file-unit value.
    pub fn set_file_value(self, d: &mut Delivery, v: f64) {
        match self {
            Self::ClubSpeed => d.club_speed_m_s = mph(v),
            Self::AttackAngle => d.attack_angle_rad = deg(v),
            Self::ClubPath => d.club_path_rad = deg(v),
            Self::DynamicLoft => d.dynamic_loft_rad = deg(v),
            Self::FaceAngle => d.face_angle_rad = deg(v),
            Self::LieTilt => d.lie_tilt_rad = deg(v),
            Self::OmegaX => d.club_omega_rad_s.x = v,
            Self::OmegaY => d.club_omega_rad_s.y = v,
            Self::OmegaZ => d.club_omega_rad_s.z = v,
            Self::ImpactY => d.impact_y_m = mm(v),
            Self::ImpactZ => d.impact_z_m = mm(v),
        }
    }
}

/// Default launch-monitor noise SD (a GCQuad-class camera unit), file units.
pub const fn default_launch_noise(c: LaunchComponent) -> f64 {
    match c {
        LaunchComponent::BallSpeed => 0.5,
        LaunchComponent::LaunchAngle => 0.3,
        LaunchComponent::Azimuth => 0.5,
        LaunchComponent::Backspin => 120.0,
        LaunchComponent::Sidespin => 150.0,
    }
}

/// Delivery in SI from file-unit values in [`DeliveryVar::ALL`] order.
pub fn delivery_from_file_units(v: &[f64; N_DELIVERY]) -> Delivery {
    let mut d = Delivery {
        club_speed_m_s: 0.0,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        dynamic_loft_rad: 0.0,
        face_angle_rad: 0.0,
        lie_tilt_rad: 0.0,
        club_omega_rad_s: Vector3::zeros(),
        impact_y_m: 0.0,
        impact_z_m: 0.0,
        shaft_mass_g: None,
    };
    for var in DeliveryVar::ALL {
        var.set_file_value(&mut d, v[var.index()]);
    }
    d
}

/// The file-unit values of `d` in [`DeliveryVar::ALL`] order.
pub fn delivery_to_file_units(d: &Delivery) -> [f64; N_DELIVERY] {
    DeliveryVar::ALL.map(|v| v.file_value(d))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_values_round_trip_through_a_delivery() {
        let v: [f64; N_DELIVERY] = std::array::from_fn(|i| 1.5 + i as f64);
        let back = delivery_to_file_units(&delivery_from_file_units(&v));
        for var in DeliveryVar::ALL {
            let (a, b) = (v[var.index()], back[var.index()]);
            assert!(
                (a - b).abs() < 1e-12 * a.abs(),
                "{}: {a} vs {b}",
                var.column()
            );
            assert_eq!(DeliveryVar::from_column(var.column()), Some(var));
            assert!(var.column().ends_with(&var.unit().replace('/', "_")));
        }
    }
}
