//! Launch conditions from the ball's velocity and spin in the ground frame.
//!
//! | quantity | definition |
//! |---|---|
//! | ball speed | `|v_b|` |
//! | launch angle | `atan2(v_y, hypot(v_x, v_z))` |
//! | azimuth | `atan2(v_z, v_x)`, + right of target |
//! | backspin | `ω_z` (+ is backspin) |
//! | sidespin | `−ω_y` (+ curves the ball right: slice spin for a right-hander) |

use nalgebra::Vector3;

use crate::units::{M_S_PER_MPH, RAD_PER_DEG, RAD_S_PER_RPM};

/// Launch conditions, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Launch {
    /// Ball speed, m/s.
    pub ball_speed_m_s: f64,
    /// Vertical launch angle, rad (+ up).
    pub launch_angle_rad: f64,
    /// Horizontal launch direction, rad (+ right of target).
    pub azimuth_rad: f64,
    /// Backspin, rad/s (+ back).
    pub backspin_rad_s: f64,
    /// Sidespin, rad/s (+ slice for a right-hander).
    pub sidespin_rad_s: f64,
}

/// The five launch components, in file order, with their file columns and units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LaunchComponent {
    /// Ball speed, file unit mph.
    BallSpeed,
    /// Launch angle, file unit deg.
    LaunchAngle,
    /// Azimuth, file unit deg.
    Azimuth,
    /// Backspin, file unit rpm.
    Backspin,
    /// Sidespin, file unit rpm.
    Sidespin,
}

impl LaunchComponent {
    /// All components in file order.
    pub const ALL: [LaunchComponent; 5] = [
        Self::BallSpeed,
        Self::LaunchAngle,
        Self::Azimuth,
        Self::Backspin,
        Self::Sidespin,
    ];

    /// Column name in shot and prediction files (`ball_speed_mph`, …).
    pub const fn column(self) -> &'static str {
        match self {
            Self::BallSpeed => "ball_speed_mph",
            Self::LaunchAngle => "launch_angle_deg",
            Self::Azimuth => "azimuth_deg",
            Self::Backspin => "backspin_rpm",
            Self::Sidespin => "sidespin_rpm",
        }
    }

    /// File unit (`mph`, `deg`, `rpm`).
    pub const fn unit(self) -> &'static str {
        match self {
            Self::BallSpeed => "mph",
            Self::LaunchAngle | Self::Azimuth => "deg",
            Self::Backspin | Self::Sidespin => "rpm",
        }
    }

    /// Human label.
    pub const fn label(self) -> &'static str {
        match self {
            Self::BallSpeed => "Ball speed",
            Self::LaunchAngle => "Launch angle",
            Self::Azimuth => "Azimuth",
            Self::Backspin => "Backspin",
            Self::Sidespin => "Sidespin",
        }
    }

    /// Multiply an SI value by this to get the file unit.
    pub const fn file_units_per_si(self) -> f64 {
        match self {
            Self::BallSpeed => 1.0 / M_S_PER_MPH,
            Self::LaunchAngle | Self::Azimuth => 1.0 / RAD_PER_DEG,
            Self::Backspin | Self::Sidespin => 1.0 / RAD_S_PER_RPM,
        }
    }

    /// Index in [`LaunchComponent::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }
}

impl Launch {
    /// Whether every component is a finite number (checked before anything is written).
    pub fn is_finite(&self) -> bool {
        LaunchComponent::ALL
            .iter()
            .all(|c| self.get_file(*c).is_finite())
    }

    /// Launch conditions from ball velocity (m/s) and spin (rad/s) in `G`.
    #[inline]
    pub fn from_ball_state(v: &Vector3<f64>, w: &Vector3<f64>) -> Self {
        Self {
            ball_speed_m_s: v.norm(),
            launch_angle_rad: v.y.atan2(v.x.hypot(v.z)),
            azimuth_rad: v.z.atan2(v.x),
            backspin_rad_s: w.z,
            sidespin_rad_s: -w.y,
        }
    }

    /// One component in SI units.
    #[inline]
    pub fn get_si(&self, c: LaunchComponent) -> f64 {
        match c {
            LaunchComponent::BallSpeed => self.ball_speed_m_s,
            LaunchComponent::LaunchAngle => self.launch_angle_rad,
            LaunchComponent::Azimuth => self.azimuth_rad,
            LaunchComponent::Backspin => self.backspin_rad_s,
            LaunchComponent::Sidespin => self.sidespin_rad_s,
        }
    }

    /// One component in its file unit (mph, deg or rpm).
    #[inline]
    pub fn get_file(&self, c: LaunchComponent) -> f64 {
        self.get_si(c) * c.file_units_per_si()
    }

    /// All five components in file units, in file order.
    #[inline]
    pub fn to_file_units(&self) -> [f64; 5] {
        LaunchComponent::ALL.map(|c| self.get_file(c))
    }
}
