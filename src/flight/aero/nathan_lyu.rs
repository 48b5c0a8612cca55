//! `nathan-lyu`: the Reynolds-dependent drag-crisis law of Nathan's trajectory calculator and
//! libgolf, after the still-air measurements of Lyu et al. (2018); see the parent module's
//! documentation for the sources.

use super::{CoefficientModel, Coefficients, SMITS_SMITH_CM_PER_S};
use crate::lanes::Lanes;

/// The Reynolds-dependent drag-crisis law (Nathan's calculator / libgolf, after Lyu et al.
/// 2018; see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NathanLyu;

impl NathanLyu {
    /// Sub-critical drag coefficient (below [`Self::RE_LOW`]).
    pub const CD_LOW: f64 = 0.500;
    /// Super-critical drag coefficient (above [`Self::RE_HIGH`]).
    pub const CD_HIGH: f64 = 0.212;
    /// Reynolds number where the drag crisis starts.
    pub const RE_LOW: f64 = 0.5e5;
    /// Reynolds number where it ends.
    pub const RE_HIGH: f64 = 1.0e5;
    /// Added drag per unit spin factor.
    pub const CD_PER_S: f64 = 0.15;
    /// Lift: `C_L = a·S + b·S²` up to [`Self::S_LIFT_MAX`].
    pub const CL: [f64; 2] = [1.99, -3.25];
    /// Spin factor above which lift is constant.
    pub const S_LIFT_MAX: f64 = 0.3;
    /// Lift above [`Self::S_LIFT_MAX`].
    pub const CL_MAX: f64 = 0.305;
}

impl CoefficientModel for NathanLyu {
    fn reynolds_at_reference_air(&self) -> bool {
        true
    }

    #[inline]
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let t = ((re - Self::RE_LOW) / (Self::RE_HIGH - Self::RE_LOW)).clamp(0.0, 1.0);
        let cd = Self::CD_LOW + t * (Self::CD_HIGH - Self::CD_LOW) + Self::CD_PER_S * s;
        let cl = if s < Self::S_LIFT_MAX {
            s * (Self::CL[0] + s * Self::CL[1])
        } else {
            Self::CL_MAX
        };
        Coefficients {
            cd,
            cl,
            cm: SMITS_SMITH_CM_PER_S * s,
        }
    }

    #[inline(always)]
    fn coefficients_v<L: Lanes>(&self, s: L, re: L) -> (L, L, L) {
        let t = (re - Self::RE_LOW) * (1.0 / (Self::RE_HIGH - Self::RE_LOW));
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let t = L::select(t.lt(zero), zero, t);
        let t = L::select(t.gt(one), one, t);
        let cd = t * (Self::CD_HIGH - Self::CD_LOW) + Self::CD_LOW + s * Self::CD_PER_S;
        let cl = L::select(
            s.lt(L::splat(Self::S_LIFT_MAX)),
            s * (s * Self::CL[1] + Self::CL[0]),
            L::splat(Self::CL_MAX),
        );
        (cd, cl, s * SMITS_SMITH_CM_PER_S)
    }
}
