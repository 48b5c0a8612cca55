//! `tangential_compliance`: a tangential restitution that depends on the contact regime.
//!
//! A ball gripping the face stores energy in tangential shear and gives part of it back before
//! it leaves: the contact point's tangential velocity reverses, and the spin overshoots the
//! rolling value of the paper's no-slip condition (Maw, Barber & Fawcett, Wear 38, 1976, and
//! J. Lubr. Technol. 103, 1981; Cross, Am. J. Phys. 70, 2002, measured the reversal of the
//! friction force). Maw, Barber and Fawcett show that the tangential restitution is a function of
//! the normalised incidence `ψ = κ·(u1t/u1n)/μ`, the ratio of the contact point's
//! tangential to normal approach speed scaled by the stiffness ratio `κ = 2(1−ν)/(2−ν)` and the
//! friction coefficient. For a solid sphere gripping throughout, a linear shear spring gives
//! `e_t = −cos(π·√(κ·χ))` with `χ = 1 + m·R²/I` (3.5 for a uniform ball): about −0.1 to −0.5 for
//! ν = 0.5…0.35, i.e. the contact point's tangential velocity does *not* reverse but the spin
//! falls short of rolling; as `ψ` grows, micro-slip at the edge of the contact lets the spring
//! release earlier and `e_t` rises toward and past 0, until gross slip sets in (the Coulomb
//! line, where `e_t` falls again). Over a driver's range of incidence (lofts 8–16°, `ψ` ≈
//! 0.2–0.8) the compliant-contact world of `crate::synth::contact` follows roughly a straight
//! line in `tan θ = |u1t|/u1n`, the first-order form of the grip/micro-slip branch of the MBF
//! curve used here:
//!
//! ```text
//! K P = u1 + e·u1n·n + e_t·(u1 − u1n·n),      e_t = et0 + k_tan·|u1t|/u1n
//! ```
//!
//! The gross-slip branch is the `friction` effect's Coulomb limit, which the tangential law
//! applies on top when it is set (`|P_t| ≤ μ·P_n`); at driver lofts the no-slip impulse needs
//! only μ ≈ 0.06, so it is rarely reached and is not a parameter here (it would be
//! unidentifiable).

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "tangential_compliance";

/// One-line description.
pub const DESCRIPTION: &str =
    "regime-dependent tangential rebound (Maw-Barber-Fawcett): e_t = et0 + k_tan*|u1t|/u1n";

/// Parameters, in file order. Ranges and sources: `docs/plausible-ranges.md`.
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "et0",
        "1",
        0.0,
        -1.0,
        1.0,
        (-0.6, 0.6),
        "tangential restitution at normal incidence (0 = the paper's no slip)",
    ),
    spec(
        "k_tan",
        "1",
        0.0,
        -5.0,
        5.0,
        (0.0, 3.0),
        "rise of e_t per unit tangent of the incidence |u1t|/u1n (micro-slip)",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]). Several add.
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.tangential_restitution += v[0];
    p.tangential_restitution_slope += v[1];
}
