//! The still-air drag floor: the super-critical drag of modern golf balls measured in still
//! air, as a law in spin factor, and the smooth maximum that holds a fitted drag above it.
//!
//! The model `fmm2022-tour` ([`super::Fmm2022Tour`]) holds its spin drag above it; in
//! the family both it and `fmm2022-re` come from it is [`super::Fmm2022ReFamily::drag_floor`]
//! (`cargo run --release --example trackman_refit -- --joint`; docs/flight-models.md).

use super::NathanLyu;
use crate::lanes::Lanes;

/// The still-air super-critical drag of modern golf balls, `C_D = 0.212 + 0.15·S`: the
/// high-Reynolds branch of A. M. Nathan's trajectory calculator (and libgolf), built on the
/// still-air measurements of B. Lyu, J. Kensrud et al., "Aerodynamics of golf balls in still
/// air", Proceedings 2 (2018) 238 (ISEA 2018) — the constants of [`NathanLyu::CD_HIGH`] and
/// [`NathanLyu::CD_PER_S`]. Bearman & Harvey's spinning ball (Aeronautical Quarterly 27 (1976)
/// 112–122) is above it (0.247 at 88 m/s and 2000 rpm, `S` 0.05): a drag below this law is
/// below every still-air or wind-tunnel measurement this project found.
///
/// Used as a floor: `max(C_D, floor)` is taken smoothly ([`DragFloor::smooth_max`]) so that
/// the force keeps a continuous slope and fixed-step RK4 its accuracy.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DragFloor;

impl DragFloor {
    /// The floor's value at `S` = 0 (dimensionless).
    pub const CD: f64 = NathanLyu::CD_HIGH;
    /// The floor's rise per unit spin factor (dimensionless).
    pub const CD_PER_S: f64 = NathanLyu::CD_PER_S;
    /// Half-width `k` of the smooth maximum, in drag coefficient: the result is the plain
    /// maximum where the two laws differ by `k` or more, and exceeds it by at most `k/4`
    /// (0.0025, about 1 % of a drive's `C_D`) where they cross. This project's choice.
    pub const BLEND: f64 = 0.01;

    /// The floor at spin factor `s`.
    #[inline]
    pub fn cd(s: f64) -> f64 {
        Self::CD + Self::CD_PER_S * s
    }

    /// `max(a, b)` with the corner rounded by a parabola over `|a − b| < k`
    /// ([`Self::BLEND`]): `h = clamp(½ + (a − b)/(2k), 0, 1)`, `b + (a − b)·h + k·h·(1 − h)`;
    /// value and slope continuous.
    #[inline]
    pub fn smooth_max(a: f64, b: f64) -> f64 {
        let k = Self::BLEND;
        let h = (0.5 + 0.5 * (a - b) / k).clamp(0.0, 1.0);
        b + (a - b) * h + k * h * (1.0 - h)
    }

    /// [`Self::smooth_max`] on lanes (any [`Lanes`] type; the same operations, so the same
    /// bits: `+` and `×` commute exactly, so a lane operand may stand on either side).
    #[inline(always)]
    pub fn smooth_max_v<L: Lanes>(a: L, b: L) -> L {
        let k = Self::BLEND;
        let h = (a - b) * 0.5 / k + 0.5;
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let h = L::select(h.lt(zero), zero, h);
        let h = L::select(h.gt(one), one, h);
        b + (a - b) * h + h * k * (one - h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flight::aero::{CoefficientModel, Fmm2022ReFamily};

    #[test]
    fn smooth_max_is_the_maximum_away_from_the_corner() {
        let k = DragFloor::BLEND;
        for (a, b) in [
            (0.3, 0.2),
            (0.2, 0.3),
            (0.25, 0.25 - 1.5 * k),
            (0.25 - 1.5 * k, 0.25),
        ] {
            assert_eq!(DragFloor::smooth_max(a, b), a.max(b), "{a} {b}");
        }
        // At the crossing, k/4 above; never below the maximum, never more than k/4 above.
        assert!((DragFloor::smooth_max(0.22, 0.22) - 0.22 - 0.25 * k).abs() < 1e-15);
        for i in 0..=400 {
            let a = 0.2 + 1e-4 * i as f64;
            let m = DragFloor::smooth_max(a, 0.22);
            assert!(
                m >= a.max(0.22) && m <= a.max(0.22) + 0.25 * k + 1e-15,
                "{a}"
            );
        }
        // Continuous slope at both ends of the blend (a corner would jump by 1).
        let h = 1e-7;
        let slope = |x: f64| {
            (DragFloor::smooth_max(x + h, 0.22) - DragFloor::smooth_max(x - h, 0.22)) / (2.0 * h)
        };
        for e in [0.22 - k, 0.22 + k] {
            assert!(
                (slope(e - 2.0 * h) - slope(e + 2.0 * h)).abs() < 1e-4,
                "{e}"
            );
        }
    }

    #[test]
    fn floor_is_the_still_air_law() {
        assert!((DragFloor::cd(0.0) - 0.212).abs() < 1e-15);
        assert!((DragFloor::cd(0.2) - 0.242).abs() < 1e-15);
    }

    #[test]
    fn the_family_holds_its_spin_drag_above_the_floor_then_adds_the_rise() {
        // The floored LPGA fit (docs/flight-models.md, "Earlier attempts"): rise 0.11 below
        // Re 8e4, gone at 1e5.
        let floored = Fmm2022ReFamily {
            cd_low_re: 0.11,
            cd_per_s: -0.15,
            re_low: 8e4,
            re_high: 1e5,
            lift_loss: 0.25,
            drag_floor: true,
        };
        let plain = Fmm2022ReFamily {
            drag_floor: false,
            ..floored
        };
        for s in [0.0, 0.05, 0.08, 0.2, 0.4, 0.7] {
            for (re, rise) in [(2e5, 0.0), (9e4, 0.055), (5e4, 0.11)] {
                let (f, p) = (floored.coefficients(s, re), plain.coefficients(s, re));
                assert!(f.cd >= DragFloor::cd(s) + rise - 1e-12, "{s} {re}");
                assert!(f.cd >= p.cd - 1e-12 && f.cl == p.cl && f.cm == p.cm);
                // Where the spin part is clear of the floor the floor changes nothing.
                if p.cd - rise > DragFloor::cd(s) + DragFloor::BLEND {
                    assert!((f.cd - p.cd).abs() < 1e-12, "{s} {re}");
                }
            }
        }
        // A drive's launch (S 0.08, Re 2.2e5): fmm2022 less 0.15·S is 0.187, floored to 0.224.
        let c = floored.coefficients(0.08, 2.2e5);
        assert!((c.cd - 0.224).abs() < 1e-12, "{}", c.cd);
    }
}
