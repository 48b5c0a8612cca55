//! `fmm2022-tour`, the default coefficient model: Ferguson, McNally & McPhee's (2022)
//! quadratics with the spin part of the drag held above the still-air drag of modern balls, a
//! drag rise and a lift loss across the measured drag-crisis window, the five constants
//! calibrated on all three TrackMan tour tables this project has (disclosed: the PGA Tour
//! table it is validated on is one of them; docs/flight-models.md).

use super::{crisis_rise_v, CoefficientModel, Coefficients, DragFloor, Fmm2022, Fmm2022ReFamily};
use crate::lanes::Lanes;

/// [`Fmm2022`] held above the still-air drag floor, with a drag rise and a lift loss across
/// the drag-crisis window (the `fmm2022-tour` model, the default):
///
/// `C_D = smax(C_D,fmm(S) + DS·S, 0.212 + 0.15·S) + DR·r(Re)`,
/// `C_L = C_L,fmm(S)·(1 − LL·r(Re))`, `C_M = 0.01·S` (`fmm2022`'s),
///
/// `S` held at 0.75 beyond `fmm2022`'s fitted range and the lift tapered to 0 at `S` = 0 as in
/// [`Fmm2022`]; `smax` the smooth maximum of [`DragFloor::smooth_max`]; `r = 3t² − 2t³` of
/// `t = clamp((RE_HIGH − Re)/(RE_HIGH − RE_LOW), 0, 1)`, 1 below `RE_LOW` and 0 above
/// `RE_HIGH`.
///
/// Why this family (fixed before it was fitted): the floor `0.212 + 0.15·S` is the still-air
/// super-critical drag of modern balls (Lyu et al. 2018, as Nathan's calculator takes it;
/// [`DragFloor`]), which `fmm2022`'s drag less a slope would otherwise undercut at a drive's
/// launch; the rise is confined to where still-air and wind-tunnel measurements put the drag
/// crisis (`Re` ≤ 10⁵: Lyu et al. 2018; Bearman & Harvey, Aeronautical Quarterly 27 (1976)
/// 112–122), and the boundary layer's transition there costs Magnus lift too.
///
/// Constants: a least-squares fit on a grid (`DR` 0–0.40 by 0.01, `DS` −0.40–0.40 by 0.05,
/// `LL` 0–1 by 0.05, `RE_LOW` 2–8·10⁴ and `RE_HIGH` 8·10⁴–10⁵ by 10⁴, at least 2·10⁴ apart;
/// 263,466 candidates, the optimum inside the grid but for `RE_HIGH`, at the family's bound)
/// to the 35 rows of TrackMan's PGA Tour, 2023 PGA Tour and 2023 LPGA Tour averages
/// ([`crate::flight::trackman`]) in the default atmosphere, minimising Σ (carry error %)² +
/// (land-angle error °/2)² + (apex error yd/2)². Leave-one-table-out errors are in
/// docs/flight-models.md.
/// `examples/trackman_refit.rs --joint` repeats the fit and its validation; `tests/flight.rs`
/// checks these constants are a minimum of that objective.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fmm2022Tour;

impl Fmm2022Tour {
    /// `DR`: drag added below [`Self::RE_LOW`] (fitted, see the type documentation).
    pub const CD_LOW_RE: f64 = 0.04;
    /// `DS`: change of `fmm2022`'s drag slope per unit spin factor, before the floor (fitted).
    pub const CD_PER_S: f64 = -0.15;
    /// `LL`: fraction of the lift lost below [`Self::RE_LOW`] (fitted).
    pub const LIFT_LOSS: f64 = 0.60;
    /// Reynolds number below which the whole rise and lift loss apply (fitted).
    pub const RE_LOW: f64 = 7.0e4;
    /// Reynolds number above which there is neither (fitted; the family's upper bound, the end
    /// of the measured crisis).
    pub const RE_HIGH: f64 = 1.0e5;

    /// The fitted member of the family searched by `examples/trackman_refit.rs --joint`.
    pub const FAMILY: Fmm2022ReFamily = Fmm2022ReFamily {
        cd_low_re: Self::CD_LOW_RE,
        cd_per_s: Self::CD_PER_S,
        re_low: Self::RE_LOW,
        re_high: Self::RE_HIGH,
        lift_loss: Self::LIFT_LOSS,
        drag_floor: true,
    };
}

impl CoefficientModel for Fmm2022Tour {
    fn reynolds_at_reference_air(&self) -> bool {
        true
    }

    #[inline]
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        Self::FAMILY.coefficients(s, re)
    }

    #[inline(always)]
    fn coefficients_v<L: Lanes>(&self, s: L, re: L) -> (L, L, L) {
        let (cd, cl, cm) = Fmm2022.coefficients_v(s, re);
        let s = Fmm2022::held_spin_factor_v(s);
        // The scalar form's operations, a lane operand on the left where the scalar form has a
        // constant there (the same bits: `+` and `×` commute exactly).
        let r = crisis_rise_v(re, Self::RE_LOW, Self::RE_HIGH);
        let one = L::splat(1.0);
        let floor = s * DragFloor::CD_PER_S + DragFloor::CD;
        let cd = DragFloor::smooth_max_v(cd + s * Self::CD_PER_S, floor) + r * Self::CD_LOW_RE;
        (cd, cl * (one - r * Self::LIFT_LOSS), cm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::{V, W};

    #[test]
    fn lanes_form_equals_scalar_form() {
        for (s, re) in [
            (V([0.0, 0.005, 0.0199, 0.02]), V([3e4, 7e4, 1.2e5, 2e5])),
            (V([0.05, 0.08, 0.12, 0.2]), V([6.9e4, 7.5e4, 8.5e4, 9.9e4])),
            (V([0.0, 0.12, 0.31, 0.9]), V([3e4, 7e4, 1.2e5, 2e5])),
            (V([0.69, 0.72, 0.75, 0.79]), V([4e4, 8e4, 1e5, 1.6e5])),
        ] {
            let (cd, cl, cm) = Fmm2022Tour.coefficients_v(s, re);
            for i in 0..W {
                let c = Fmm2022Tour.coefficients(s.0[i], re.0[i]);
                assert!((c.cd - cd.0[i]).abs() < 1e-15, "{s:?} {re:?}");
                assert!((c.cl - cl.0[i]).abs() < 1e-15, "{s:?} {re:?}");
                assert!((c.cm - cm.0[i]).abs() < 1e-15, "{s:?} {re:?}");
            }
        }
    }

    #[test]
    fn floor_rise_and_lift_loss_where_documented() {
        for s in [0.0, 0.05, 0.08, 0.2, 0.4, 0.6] {
            let fmm = Fmm2022.coefficients(s, 2e5);
            let spin_part = fmm.cd - 0.15 * s;
            let floor = 0.212 + 0.15 * s;
            // Above the window: the floored spin drag, fmm2022's lift and moment.
            let hi = Fmm2022Tour.coefficients(s, 1.2e5);
            let smax = DragFloor::smooth_max(spin_part, floor);
            assert!((hi.cd - smax).abs() < 1e-15 && hi.cl == fmm.cl && hi.cm == fmm.cm);
            assert!(hi.cd >= floor && hi.cd >= spin_part, "{s}");
            // Below it: 0.04 more drag and 40 % of the lift; halfway, half of each.
            let lo = Fmm2022Tour.coefficients(s, 5e4);
            assert!((lo.cd - hi.cd - 0.04).abs() < 1e-15, "{s}");
            assert!((lo.cl - 0.4 * fmm.cl).abs() < 1e-15, "{s}");
            let mid = Fmm2022Tour.coefficients(s, 8.5e4);
            assert!((mid.cd - hi.cd - 0.02).abs() < 1e-15, "{s}");
            assert!((mid.cl - 0.7 * fmm.cl).abs() < 1e-15, "{s}");
        }
        // A drive's launch (S 0.08, Re 2.2e5): fmm2022 less 0.15·S is 0.187, floored to 0.224.
        assert!((Fmm2022Tour.coefficients(0.08, 2.2e5).cd - 0.224).abs() < 1e-12);
        // No spin, no lift, at every Reynolds number.
        for re in [2e4, 7e4, 1.2e5, 3e5] {
            let c = Fmm2022Tour.coefficients(0.0, re);
            assert!(c.cl == 0.0 && c.cd > 0.2, "{re}");
        }
    }
}
