//! A simple bounce-and-roll model after the first landing (for `total_yd`).
//!
//! 1. First impact with the turf: the normal speed is reversed and scaled by the turf's
//!    coefficient of restitution `e`; tangentially the ball leaves rolling, which conserves the
//!    angular momentum about the contact point (the "rolling at the end of impact" limit of
//!    R. Cross, "Bounce of a spinning ball near normal incidence", *Am. J. Phys.* 73 (2005)
//!    914–920): `v_t' = (5/7)·v_t − (2/7)·R·ω_back` for a uniform sphere; a ball whose backspin
//!    would send it backwards stops instead (`v_t' ≥ 0`).
//! 2. Further hops: each lands rolling, so `v_t'` is kept and the normal speed shrinks by `e`
//!    per hop; the hop lengths `2·v_t'·v_n/g` sum to `2·v_t'·e·v_n/(g·(1 − e))`.
//! 3. Run out at constant deceleration `a` to rest: `v_t'²/(2a)`.
//!
//! The two parameters are effective values, not turf measurements: the defaults (e = 0.2,
//! a = 12 m/s²) are chosen so that the PGA Tour average drive (TrackMan table, flown by the
//! default model) runs out 25 yd, the difference between the Tour's average driving distance
//! (299.9 yd in 2023, PGA Tour statistics as quoted by Golf Monthly, 5 Dec 2023) and its average
//! carry (275 yd). The rolling limit of step 1 keeps more horizontal speed than a ball plowing
//! into real turf, so `a` absorbs those losses too and is far above a pure rolling resistance
//! (about 0.5 m/s² on a green). Greens, wet or firm fairways need other values; spin-back and
//! slope are not modelled.

use super::G_M_S2;
use crate::limits::fmt_value;

/// Default turf coefficient of restitution (dimensionless), see the module documentation.
pub const DEFAULT_RESTITUTION: f64 = 0.20;
/// Default rolling deceleration, m/s², see the module documentation.
pub const DEFAULT_ROLL_DECEL_M_S2: f64 = 12.0;

/// Slowest run-out deceleration accepted, m/s² (see [`Ground::check`]).
pub const MIN_ROLL_DECEL_M_S2: f64 = 0.1;

/// Turf parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// Normal coefficient of restitution of the turf, in [0, 1).
    pub restitution: f64,
    /// Effective run-out deceleration, m/s² (> 0).
    pub roll_decel_m_s2: f64,
}

impl Default for Ground {
    fn default() -> Self {
        Self {
            restitution: DEFAULT_RESTITUTION,
            roll_decel_m_s2: DEFAULT_ROLL_DECEL_M_S2,
        }
    }
}

/// A ground parameter outside its range (the value given).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum GroundError {
    /// The turf's coefficient of restitution is not within [0, 1).
    #[error("ground restitution = {}: must be within [0, 1)", fmt_value(*.0))]
    Restitution(f64),
    /// The run-out deceleration is not within [0.1, 50] m/s².
    #[error(
        "ground roll_decel_m_s2 = {}: must be within [0.1, 50] m/s² (the fastest greens roll \
         out at about 0.4)",
        fmt_value(*roll_decel_m_s2)
    )]
    RollDecel {
        /// The deceleration given, m/s².
        roll_decel_m_s2: f64,
    },
}

impl Ground {
    /// Check the parameters.
    pub fn check(&self) -> Result<(), GroundError> {
        if !(self.restitution >= 0.0 && self.restitution < 1.0) {
            return Err(GroundError::Restitution(self.restitution));
        }
        // The lower end: the USGA Stimpmeter releases a ball at about 1.83 m/s, and on the
        // fastest greens (Stimp 14 ft, 4.27 m) it rolls out at v²/2d ≈ 0.39 m/s²; no turf is a
        // quarter as slow. Below that the run-out grows without bound (1e-300 m/s² once gave a
        // 304-digit total).
        if !(MIN_ROLL_DECEL_M_S2..=50.0).contains(&self.roll_decel_m_s2) {
            return Err(GroundError::RollDecel {
                roll_decel_m_s2: self.roll_decel_m_s2,
            });
        }
        Ok(())
    }

    /// Distance from the first landing to rest along the direction of travel, m, from the
    /// horizontal and (downward) vertical landing speeds, m/s, the backspin about the axis
    /// across the direction of travel, rad/s, and the ball radius, m.
    pub fn run_m(&self, v_t: f64, v_n_down: f64, backspin_rad_s: f64, radius_m: f64) -> f64 {
        let vt = ((5.0 * v_t - 2.0 * radius_m * backspin_rad_s) / 7.0).max(0.0);
        let e = self.restitution;
        let hops = 2.0 * vt * e * v_n_down.max(0.0) / (G_M_S2 * (1.0 - e));
        hops + vt * vt / (2.0 * self.roll_decel_m_s2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_limits() {
        let g = Ground::default();
        // No spin, no bounce: a rolling ball at 5/7 of the landing speed.
        let dead = Ground {
            restitution: 0.0,
            ..g
        };
        let vt: f64 = 5.0 / 7.0 * 14.0;
        assert!(
            (dead.run_m(14.0, 10.0, 0.0, 0.02) - vt * vt / (2.0 * g.roll_decel_m_s2)).abs() < 1e-12
        );
        // Enough backspin stops it dead.
        assert_eq!(g.run_m(10.0, 10.0, 5000.0, 0.02), 0.0);
        assert!(g.check().is_ok());
        let e = Ground {
            restitution: 1.0,
            ..g
        }
        .check()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "ground restitution = 1: must be within [0, 1)"
        );
        let e = Ground {
            roll_decel_m_s2: 0.01,
            ..g
        }
        .check()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "ground roll_decel_m_s2 = 0.01: must be within [0.1, 50] m/s² (the fastest greens \
             roll out at about 0.4)"
        );
    }
}
