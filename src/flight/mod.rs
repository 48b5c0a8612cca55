//! Ball flight: from launch (ball speed, angles, spin) to the first landing, then optionally
//! a simple bounce and roll.
//!
//! A spinning ball under gravity, aerodynamic drag against the air-relative velocity, Magnus
//! lift along `ω × v_rel`, and spin decay, in the G frame of CONVENTIONS (origin at the ball
//! centre at address, `x` toward the target, `y` up, `z` right). The ball starts on the ground
//! or on a tee ([`FlightConfig::tee_height_m`], the gap under the ball; 0 by default) and lands
//! when it first touches the ground, its centre at `y = −tee height`: one radius above the
//! ground, like at address. Contact is found on the step's interpolant, so a ball launched
//! downward or grazing the ground lands (or not) whatever the time step.
//!
//! - [`aero`]: coefficient models (`C_D`, `C_L`, `C_M` from spin factor and Reynolds number),
//!   the trait and the built-in and table models;
//! - [`atmosphere`]: air density and viscosity from temperature, pressure or elevation and
//!   humidity; wind with a log profile;
//! - [`integrate`]: the batched fixed-step integrator (lanes of `f64`, rayon across batches);
//! - [`ground`]: bounce and roll after the first landing;
//! - [`trackman`]: TrackMan's tour averages, the calibration and validation data.
//!
//! Pure physics: no I/O.

pub mod aero;
pub mod atmosphere;
pub mod calibrate;
pub mod diagnose;
pub mod ground;
mod hermite;
pub mod integrate;
pub mod trackman;
pub mod workload;

pub use aero::{AeroModel, CoefficientModel, Coefficients};
pub use atmosphere::{Air, Atmosphere, AtmosphereError};
pub use ground::Ground;
pub use integrate::{fly, fly_one};

use crate::units;

/// Metres per yard (exact, international yard of 1959).
pub const M_PER_YD: f64 = 0.9144;
/// Standard gravity, m/s² (CGPM 1901).
pub const G_M_S2: f64 = 9.806_65;

/// The ball as it flies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball {
    /// Mass, kg.
    pub mass_kg: f64,
    /// Radius, m.
    pub radius_m: f64,
    /// Moment of inertia about a diameter, kg·m².
    pub inertia_kg_m2: f64,
}

impl Default for Ball {
    /// The Rules of Golf ball at its limits (Equipment Rules, Part 4: mass at most 45.93 g,
    /// diameter at least 42.67 mm), moment of inertia of a uniform sphere `2/5·m·R²`
    /// (8.36e-6 kg·m², within the 8.0–8.6e-6 kg·m² measured on tour balls).
    fn default() -> Self {
        let (m, r) = (0.045_93, 0.042_67 / 2.0);
        Self {
            mass_kg: m,
            radius_m: r,
            inertia_kg_m2: 0.4 * m * r * r,
        }
    }
}

/// How the spin decays in flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpinDecay {
    /// An aerodynamic moment `½ρ|v|²·A·2R·C_M` against the spin, `C_M` from the coefficient
    /// model (the default; Smits & Smith 1994 form).
    Moment,
    /// Exponential decay with this time constant, s.
    Exponential {
        /// Time constant, s.
        time_constant_s: f64,
    },
    /// No decay.
    None,
}

/// Default fixed time step in still air, s: the largest of 0.2, 0.25, … 0.5 s that passes the
/// tolerance test in `tests/flight.rs` (carry, offline and apex within 0.02 yd of a step 64
/// times finer and within 2 cm of an adaptive Dormand–Prince reference, land angle within
/// 0.02°, driver to wedge plus extreme launches) with a margin of two or more under
/// `fmm2022-tour`, the hardest built-in model for the step: measured 0.0087 yd and 0.0086° at
/// 0.35 s (0.0138 yd at 0.4 s, over half the bound; under `fmm2022-re` 0.0070 yd and 0.0017°;
/// under the default `fmm2022` 0.0012 yd and 0.0007°). 2 cm is a
/// fifth of the 0.1 yd to which launch monitors report carry, so a
/// smaller step buys nothing a user can see.
pub const DEFAULT_DT_S: f64 = 0.35;
/// Default fixed time step in wind, s: the log profile's steep gradient near the ground needs
/// smaller steps (same test, 0.05 yd).
pub const DEFAULT_DT_WIND_S: f64 = 0.1;
/// Default longest flight, s (a 90° pop-up at 250 mph stays up under 15 s).
pub const DEFAULT_MAX_TIME_S: f64 = 30.0;

/// Everything a flight needs besides the launch.
#[derive(Debug, Clone, PartialEq)]
pub struct FlightConfig {
    /// Coefficient model.
    pub aero: AeroModel,
    /// Air (density, viscosity, wind).
    pub air: Air,
    /// Ball.
    pub ball: Ball,
    /// Spin decay.
    pub spin_decay: SpinDecay,
    /// Fixed time step, s (`None`: [`DEFAULT_DT_S`], or [`DEFAULT_DT_WIND_S`] in wind).
    pub dt_s: Option<f64>,
    /// Longest flight before it is an error, s.
    pub max_time_s: f64,
    /// Bounce and roll after landing (`None`: carry only).
    pub ground: Option<Ground>,
    /// Gap between the ball's lowest point and the ground at launch, m: 0 for a ball on the
    /// ground (the default), the tee height for a teed ball, at most [`MAX_TEE_HEIGHT_M`].
    /// The ball lands when it first touches the ground, so a launch below horizontal lands at
    /// once from the ground and after a dip below its address height from a tee.
    pub tee_height_m: f64,
}

/// Highest tee accepted, m: a tee may be at most 4 in (101.6 mm) long (Rules of Golf,
/// Equipment Rules, Part 3: tees), so no ball sits higher above the ground.
pub const MAX_TEE_HEIGHT_M: f64 = 0.1016;

impl Default for FlightConfig {
    /// `fmm2022`, the default [`Atmosphere`], the Rules ball, moment spin decay, default steps,
    /// no ground model, the ball on the ground.
    fn default() -> Self {
        Self {
            aero: AeroModel::default(),
            air: Atmosphere::default()
                .air()
                .expect("the default atmosphere is valid"),
            ball: Ball::default(),
            spin_decay: SpinDecay::Moment,
            dt_s: None,
            max_time_s: DEFAULT_MAX_TIME_S,
            ground: None,
            tee_height_m: 0.0,
        }
    }
}

impl FlightConfig {
    /// The time step used, s.
    pub fn dt(&self) -> f64 {
        self.dt_s.unwrap_or(if self.air.has_wind() {
            DEFAULT_DT_WIND_S
        } else {
            DEFAULT_DT_S
        })
    }

    /// Where the ball starts, for reports: "on the ground" or "teed N mm".
    pub fn start_text(&self) -> String {
        if self.tee_height_m > 0.0 {
            // To 0.1 mm, as given (101.6 mm, not 102).
            let mm = (self.tee_height_m * 1e4).round() / 10.0;
            format!("teed {mm} mm")
        } else {
            "on the ground".to_string()
        }
    }
}

/// Launch conditions, SI, as CONVENTIONS defines them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightLaunch {
    /// Ball speed, m/s.
    pub ball_speed_m_s: f64,
    /// Launch angle, rad (+ up).
    pub launch_angle_rad: f64,
    /// Azimuth, rad (+ right of target).
    pub azimuth_rad: f64,
    /// Backspin `ω_z`, rad/s (+ backspin).
    pub backspin_rad_s: f64,
    /// Sidespin `−ω_y`, rad/s (+ curves right).
    pub sidespin_rad_s: f64,
}

impl FlightLaunch {
    /// From file units (mph, degrees, rpm).
    pub fn from_file_units(
        ball_speed_mph: f64,
        launch_angle_deg: f64,
        azimuth_deg: f64,
        backspin_rpm: f64,
        sidespin_rpm: f64,
    ) -> Self {
        Self {
            ball_speed_m_s: units::mph(ball_speed_mph),
            launch_angle_rad: units::deg(launch_angle_deg),
            azimuth_rad: units::deg(azimuth_deg),
            backspin_rad_s: units::rpm(backspin_rpm),
            sidespin_rad_s: units::rpm(sidespin_rpm),
        }
    }

    /// From a launch of the impact model.
    pub fn from_launch(l: &crate::physics::Launch) -> Self {
        Self {
            ball_speed_m_s: l.ball_speed_m_s,
            launch_angle_rad: l.launch_angle_rad,
            azimuth_rad: l.azimuth_rad,
            backspin_rad_s: l.backspin_rad_s,
            sidespin_rad_s: l.sidespin_rad_s,
        }
    }

    /// Check the launch is physical; the error names the quantity in file units.
    pub fn check(&self) -> Result<(), FlightError> {
        let bad = |field: &'static str, value: f64, allowed: &'static str| {
            Err(FlightError::InvalidLaunch {
                field,
                value,
                allowed,
            })
        };
        // File units back from SI: drop the last-digit noise of the round trip (120° must not
        // read 119.99999999999999 in a message) by rounding to 12 significant digits, which
        // keeps a tiny value as given (1e-300 mph is not 0). That rounding moves a value by
        // less than 1e-11 of itself, so a value inside its range by more than 1e-9 of the
        // limit is accepted without it (formatting five numbers per launch to 12 digits was
        // a tenth of `smash flight`'s time); any other value is rounded and checked as before,
        // so the same launches are accepted and every message is unchanged.
        let tidy = |x: f64| {
            if x.is_finite() && x != 0.0 {
                format!("{x:.11e}").parse().unwrap_or(x)
            } else {
                x
            }
        };
        let clearly_within = |x: f64, limit: f64| x.abs() <= limit * (1.0 - 1e-9);
        let mph = self.ball_speed_m_s / units::M_S_PER_MPH;
        if !(mph >= MIN_BALL_SPEED_MPH * (1.0 + 1e-9) && clearly_within(mph, MAX_BALL_SPEED_MPH)) {
            let mph = tidy(mph);
            if !(MIN_BALL_SPEED_MPH..=MAX_BALL_SPEED_MPH).contains(&mph) {
                return bad("ball_speed_mph", mph, BALL_SPEED_ALLOWED);
            }
        }
        let angles = [
            ("launch_angle_deg", self.launch_angle_rad),
            ("azimuth_deg", self.azimuth_rad),
        ];
        for (field, rad) in angles {
            let deg = rad.to_degrees();
            if !clearly_within(deg, 90.0) && !(tidy(deg).abs() <= 90.0) {
                return bad(field, tidy(deg), "must be within [-90, 90] degrees");
            }
        }
        let spins = [
            ("backspin_rpm", self.backspin_rad_s),
            ("sidespin_rpm", self.sidespin_rad_s),
        ];
        for (field, rad_s) in spins {
            let rpm = rad_s / units::RAD_S_PER_RPM;
            if !clearly_within(rpm, MAX_SPIN_RPM) && !(tidy(rpm).abs() <= MAX_SPIN_RPM) {
                return bad(
                    field,
                    tidy(rpm),
                    "must be within ±20000 rpm (about twice a wedge's spin)",
                );
            }
        }
        Ok(())
    }
}

/// Highest ball speed accepted, mph.
pub const MAX_BALL_SPEED_MPH: f64 = 250.0;
/// Lowest ball speed accepted, mph. Slower than this the ball rises less than a hundredth of
/// its own radius (v²/2g = 0.01 mm at 1 mph) and is on the ground again within a step's rounding:
/// 1e-300 mph once "flew" to a land angle of −12°. The impact model's own floor is the same
/// (`limits::CLUB_SPEED_MPH`).
pub const MIN_BALL_SPEED_MPH: f64 = 1.0;
/// What a ball speed must be, as the refusal says it.
const BALL_SPEED_ALLOWED: &str =
    "must be at least 1 mph (slower, the ball does not fly) and at most 250 mph (beyond the long-drive record)";
/// Largest spin component accepted, rpm.
pub const MAX_SPIN_RPM: f64 = 20_000.0;

/// Where and how the ball lands, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// Carry, m: the signed distance of the first landing along the target line (G `x`), so a
    /// ball blown back behind the golfer has a negative carry; [`Self::offline_m`] is the
    /// other component. Launch monitors report carry along the target line with "carry side"
    /// across it, not the straight-line distance to the landing.
    pub carry_m: f64,
    /// Lateral position at landing, m (+ right of target, G `z`).
    pub offline_m: f64,
    /// Greatest height of the ball centre above its address height, m.
    pub apex_m: f64,
    /// Time from launch to landing, s.
    pub flight_time_s: f64,
    /// Angle of descent below horizontal at landing, rad (positive).
    pub land_angle_rad: f64,
    /// Ball speed at landing (ground frame), m/s.
    pub land_speed_m_s: f64,
    /// Spin rate at landing, rad/s.
    pub land_spin_rad_s: f64,
    /// Where the ball stops along the target line (signed, like [`Self::carry_m`]), m, when a
    /// [`Ground`] model is given.
    pub total_m: Option<f64>,
}

impl Flight {
    /// Carry in yards.
    pub fn carry_yd(&self) -> f64 {
        self.carry_m / M_PER_YD
    }
    /// Offline in yards.
    pub fn offline_yd(&self) -> f64 {
        self.offline_m / M_PER_YD
    }
    /// Apex in yards.
    pub fn apex_yd(&self) -> f64 {
        self.apex_m / M_PER_YD
    }
    /// Land angle in degrees.
    pub fn land_angle_deg(&self) -> f64 {
        self.land_angle_rad.to_degrees()
    }
    /// Total in yards.
    pub fn total_yd(&self) -> Option<f64> {
        self.total_m.map(|t| t / M_PER_YD)
    }
}

/// Why a flight has no result.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FlightError {
    /// A launch value out of its physical range.
    #[error("{field} = {}: {allowed}", crate::limits::fmt_value(*value))]
    InvalidLaunch {
        /// Column name (file units).
        field: &'static str,
        /// The value, file units.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The ball did not come down within the time limit.
    #[error("{}", never_lands(*time_limit_s))]
    NeverLands {
        /// The limit, s.
        time_limit_s: f64,
    },
}

/// What [`FlightError::NeverLands`] says. Below the default limit the flight was cut off by the
/// limit the user gave (`--max-time-s`), which is no fault of the launch: the message says so
/// and how to fly it ([`cut_by_given_limit`] tells such a message apart). At the default or
/// above, longer than any golf flight (a 90° pop-up at 250 mph lands within 15 s), the launch
/// or the wind is what to look at.
fn never_lands(time_limit_s: f64) -> String {
    let t = crate::limits::fmt_value(time_limit_s);
    if time_limit_s < DEFAULT_MAX_TIME_S {
        format!("{CUT_BY_GIVEN_LIMIT} {t} s: raise --max-time-s to fly it")
    } else {
        format!(
            "the ball has not landed within {t} s (--max-time-s; no golf flight lasts that \
             long): check the launch and the wind"
        )
    }
}

/// The start of the message of a flight cut off by a `--max-time-s` below the default.
const CUT_BY_GIVEN_LIMIT: &str = "the ball has not landed within the --max-time-s given,";

/// Whether `message` is that of a flight cut off by the limit the user gave (below the
/// default): not a fault of the row it was read from.
pub fn cut_by_given_limit(message: &str) -> bool {
    message.contains(CUT_BY_GIVEN_LIMIT)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A launch out of range is named with its value in file units as given: a tiny value is
    /// not rounded to 0 (a ball speed of -2.5e-12 mph once read "= 0", and 1e-300 mph was
    /// refused as "= 0: must be > 0"), and 120° is not 119.99999999999999 after the SI round
    /// trip. A speed below the slowest flight (1e-300 mph) is refused, as given.
    #[test]
    fn bad_launch_values_print_as_given() {
        let msg = |l: FlightLaunch| l.check().unwrap_err().to_string();
        let launch = |mph, deg, rpm| FlightLaunch::from_file_units(mph, deg, 0.0, rpm, 0.0);
        let negative = msg(launch(-2.5e-12, 10.0, 2500.0));
        assert!(
            negative.starts_with("ball_speed_mph = -2.5e-12:"),
            "{negative}"
        );
        let huge = msg(launch(1e300, 10.0, 2500.0));
        assert!(huge.starts_with("ball_speed_mph = 1e300:"), "{huge}");
        let steep = msg(launch(150.0, 120.0, 2500.0));
        assert!(steep.starts_with("launch_angle_deg = 120:"), "{steep}");
        let spin = msg(launch(150.0, 10.0, 25_000.7));
        assert!(spin.starts_with("backspin_rpm = 25000.7:"), "{spin}");
        let tiny = msg(launch(1e-300, 10.0, 2500.0));
        assert!(
            tiny.starts_with("ball_speed_mph = 1e-300: must be at least 1 mph"),
            "{tiny}"
        );
        let slowest = launch(MIN_BALL_SPEED_MPH, 10.0, 2500.0);
        assert_eq!(slowest.check(), Ok(()));
        for ground in [None, Some(Ground::default())] {
            let cfg = FlightConfig {
                ground,
                ..FlightConfig::default()
            };
            // From the ground at 1 mph and 10°, the vacuum range v² sin 2θ / g is 7 mm: the
            // slowest launch accepted flies a few millimetres and lands, every number finite.
            let f = fly_one(&cfg, &slowest).unwrap();
            let v = crate::units::mph(MIN_BALL_SPEED_MPH);
            let vacuum_m = v * v * 20f64.to_radians().sin() / G_M_S2;
            assert!(
                f.carry_m >= 0.0 && f.carry_m <= vacuum_m * 1.001 && f.land_angle_rad.is_finite(),
                "{f:?}"
            );
        }
    }

    /// The check as it was before its fast path: every value rounded to 12 significant
    /// digits, then compared.
    fn check_by_rounding(l: &FlightLaunch) -> Result<(), FlightError> {
        let tidy = |x: f64| {
            if x.is_finite() && x != 0.0 {
                format!("{x:.11e}").parse().unwrap_or(x)
            } else {
                x
            }
        };
        let bad = |field, value, allowed| {
            Err(FlightError::InvalidLaunch {
                field,
                value,
                allowed,
            })
        };
        let mph = tidy(l.ball_speed_m_s / units::M_S_PER_MPH);
        if !(MIN_BALL_SPEED_MPH..=MAX_BALL_SPEED_MPH).contains(&mph) {
            return bad("ball_speed_mph", mph, BALL_SPEED_ALLOWED);
        }
        for (field, rad) in [
            ("launch_angle_deg", l.launch_angle_rad),
            ("azimuth_deg", l.azimuth_rad),
        ] {
            let deg = tidy(rad.to_degrees());
            if !(deg.abs() <= 90.0) {
                return bad(field, deg, "must be within [-90, 90] degrees");
            }
        }
        for (field, w) in [
            ("backspin_rpm", l.backspin_rad_s),
            ("sidespin_rpm", l.sidespin_rad_s),
        ] {
            let rpm = tidy(w / units::RAD_S_PER_RPM);
            if !(rpm.abs() <= MAX_SPIN_RPM) {
                return bad(
                    field,
                    rpm,
                    "must be within ±20000 rpm (about twice a wedge's spin)",
                );
            }
        }
        Ok(())
    }

    /// The check's fast path accepts and refuses exactly what rounding every value did, with
    /// the same messages: values at, just inside and just outside every limit and the fast
    /// path's own edges (ulp by ulp), zeros, tiny, huge and non-finite values.
    #[test]
    fn launch_check_equals_the_rounding_check() {
        let mut edges = vec![
            0.0,
            1e-300,
            1e-6,
            1e-6 * (1.0 - 1e-12),
            f64::MIN_POSITIVE,
            5e-324,
            1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        for limit in [MIN_BALL_SPEED_MPH, MAX_BALL_SPEED_MPH, 90.0, MAX_SPIN_RPM] {
            for centre in [limit, limit * (1.0 - 1e-9), limit * (1.0 - 5e-12)] {
                let mut up = centre;
                let mut down = centre;
                for _ in 0..40 {
                    edges.extend([up, down]);
                    up = f64::from_bits(up.to_bits() + 1);
                    down = f64::from_bits(down.to_bits() - 1);
                }
                for k in -30..=30 {
                    edges.push(centre * (1.0 + f64::from(k) * 1e-13));
                }
            }
        }
        let values: Vec<f64> = edges.iter().flat_map(|&v| [v, -v]).collect();
        let fine = FlightLaunch::from_file_units(150.0, 10.0, 1.0, 2500.0, 100.0);
        let mut n = 0;
        for &v in &values {
            // Each field in turn, in file units and converted from them.
            let as_given = [
                FlightLaunch {
                    ball_speed_m_s: v * units::M_S_PER_MPH,
                    ..fine
                },
                FlightLaunch {
                    launch_angle_rad: units::deg(v),
                    ..fine
                },
                FlightLaunch {
                    azimuth_rad: units::deg(v),
                    ..fine
                },
                FlightLaunch {
                    backspin_rad_s: units::rpm(v),
                    ..fine
                },
                FlightLaunch {
                    sidespin_rad_s: units::rpm(v),
                    ..fine
                },
                FlightLaunch::from_file_units(v, v, v, v, v),
            ];
            for l in as_given {
                let (fast, slow) = (l.check(), check_by_rounding(&l));
                // NaN values compare unequal: compare the messages too.
                assert_eq!(
                    format!("{fast:?}"),
                    format!("{slow:?}"),
                    "{v:e} ({:#x})",
                    v.to_bits()
                );
                n += usize::from(fast.is_ok());
            }
        }
        assert!(n > 100, "some launches pass: {n}");
    }

    #[test]
    fn carry_is_signed_along_the_target_line() {
        // In vacuum, launched 30° right of target: carry is the range times cos 30° (the
        // distance along the target line), offline the range times sin 30°.
        let mut vacuum = FlightConfig::default();
        vacuum.air.density_kg_m3 = 0.0;
        let l = FlightLaunch::from_file_units(100.0, 30.0, 30.0, 3000.0, 0.0);
        let f = fly_one(&vacuum, &l).unwrap();
        let v = l.ball_speed_m_s;
        let range = v * v * (2.0 * l.launch_angle_rad).sin() / G_M_S2;
        let (s, c) = l.azimuth_rad.sin_cos();
        assert!((f.carry_m - range * c).abs() < 1e-9, "{f:?} {range}");
        assert!((f.offline_m - range * s).abs() < 1e-9, "{f:?} {range}");
        // A pop-up into a gale is blown back behind the golfer: negative carry, and it rolls on
        // backwards.
        let gale = FlightConfig {
            air: Atmosphere {
                wind_speed_m_s: 30.0,
                wind_direction_deg: 180.0,
                ..Atmosphere::default()
            }
            .air()
            .unwrap(),
            ground: Some(Ground::default()),
            ..FlightConfig::default()
        };
        let pop = FlightLaunch::from_file_units(40.0, 80.0, 0.0, 1000.0, 0.0);
        let f = fly_one(&gale, &pop).unwrap();
        println!("{f:?}");
        assert!(f.carry_m < -1.0, "{f:?}");
        assert!(f.offline_m.abs() < 1e-9, "{f:?}");
        assert!(f.total_m.unwrap() <= f.carry_m, "{f:?}");
    }
}
