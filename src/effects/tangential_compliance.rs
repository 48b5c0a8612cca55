//! `tangential_compliance`: the tangential law of a compliant, gripping contact — a restitution
//! of the approach that depends on the regime, and one of the gear-effect drive.
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
//! u_t' = −e_t·u1t − e_g·Δ_g          e_t = et0 + k_tan·|u1t|/u1n,   e_g = eg
//! K P  = u1 + e·u1n·n + e_t·u1t − e_g·(K·n)_t·P_n0,      P_n0 = (1 + e)·u1n/(n·K·n)
//! ```
//!
//! ## The gear-effect drive (`eg`)
//!
//! Off the centre, the contact point does not only arrive with a tangential velocity `u1t`: the
//! normal impulse itself drives it sideways while it is delivered, through the coupling terms
//! of the collision matrix `K` (the gear effect; Stronge, *Impact Mechanics*, 2000, ch. 5, for
//! the collision matrix of eccentric impact and how the normal and tangential impulses couple).
//! Without any tangential force it would leave with `u1t + Δ_g`, `Δ_g = −(K·n)_t·P_n`. While the
//! contact grips, write `ξ` for the tangential stretch of the contact spring (`ξ̇ = u_t`),
//! `k_t(t)` for its stiffness and `k_tt` for the tangential block of `K` (taken as isotropic):
//! from `u(t) = u1 − K·P(t)` and `Ṗ_t = k_t·ξ`,
//!
//! ```text
//! ξ̈ + k_tt·k_t(t)·ξ = −(K·n)_t·F_n(t),       ξ(0) = 0,   ξ̇(0) = u1t
//! ```
//!
//! a tangential oscillator started by the approach and driven by the normal force. Being linear
//! while it grips, its velocity at separation is a free response `−e_t·u1t` plus a forced
//! response `−e_g·Δ_g`, with *different* factors. For a constant frequency `ω_t` and a normal
//! pulse symmetric about half the contact time `T`: `e_t = −cos(ω_t·T)` and
//! `e_g = −⟨cos(ω_t·τ)⟩_F`, the impulse-weighted mean over the pulse. For a half-sine pulse
//! (`T = π/ω_n`) and `r = ω_t/ω_n`, `r² = κ·k_tt/k_nn` (Maw, Barber & Fawcett's ratio, `≈ κ·χ`):
//!
//! ```text
//! e_t = −cos(π·r),       e_g = (1 + cos(π·r)) / (2·(r² − 1)) = (1 − e_t) / (2·(r² − 1))
//! ```
//!
//! `e_g = 0` is the rigid grip (the paper), `e_g > 0` a spring that reverses part of the
//! gear-driven slip before release. The form is negative only for `r < 1` (a tangential spring
//! slower than the normal one), which no ball reaches: `χ = 1 + m·R²/I ≥ 2.5` for any ball whose
//! mass is spread symmetrically about its centre (`I ≤ ⅔·m·R²`, the thin shell) and
//! `κ = 2(1−ν)/(2−ν) ≥ ⅔`, so `r² = κ·χ ≥ 5/3`. Its physical bounds are therefore `0 … 1`: a
//! negative value could only stand in for something else (a stiffer head weakens the gear
//! effect alike). For a driver and a golf
//! ball (`r ≈ 1.4–1.6`) the linear estimate is `e_t ≈ −0.3…0.3` but `e_g ≈ 0.36–0.42`: applying
//! `e_t` to the gear-driven motion too (`u_t' = −e_t·(u1t + Δ_g)`) gets its size wrong, and its
//! sign wherever `e_t < 0` (it fits the simulator worse than no `e_g` at all), and a
//! law without `e_g` leaves the gear effect's spin as the rigid grip has it, which a fit then
//! repairs with an implausibly deep centre of mass (`com_offset` dx −12 to −21 mm in the
//! compliant worlds). The Hertz pulse (the spring stiffens as `δ^½`) and micro-slip change the
//! numbers, so `e_g` is fitted; one constant is enough over a driver's range of incidence. The
//! normal impulse in `Δ_g` is the frictionless one, `P_n0`, so the law stays one linear solve
//! (the difference is second order in the coupling). `tests/contact_world.rs`
//! (`gear_restitution_fits_the_mindlin_spring_off_centre`) checks the form against the
//! time-integrated contact of `crate::synth::contact` with the Mindlin spring as its only extra
//! ingredient.
//!
//! The gross-slip branch is the `friction` effect's Coulomb limit, which the tangential law
//! applies on top when it is set (`|P_t| ≤ μ·P_n`); at driver lofts the no-slip impulse needs
//! only μ ≈ 0.06, so it is rarely reached and is not a parameter here (it would be
//! unidentifiable).

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "tangential_compliance";

/// One-line description.
pub const DESCRIPTION: &str = "compliant tangential grip (Maw-Barber-Fawcett): rebound e_t = et0 + k_tan*|u1t|/u1n \
     of the approach, eg of the gear-effect drive";

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
    spec(
        "eg",
        "1",
        0.0,
        0.0,
        1.0,
        (0.0, 0.5),
        "gear restitution: rebound of the tangential velocity the normal impulse drives (0 = no slip)",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]). Several add.
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.tangential_restitution += v[0];
    p.tangential_restitution_slope += v[1];
    p.gear_restitution += v[2];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::LaunchAngle, Pattern::Trend("dynamic_loft_deg"), "the tangential rebound changing with obliquity"),
    row(LaunchComponent::Backspin, Pattern::Trend("dynamic_loft_deg"), "spin depending on the contact regime"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a tangential rebound or friction outside ball-on-face values: behaves like a spin lever or a loft bias rather than shear compliance",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "spin over a wide range of dynamic loft, from gripping to sliding impacts";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("its rebound changes with the obliquity every shot has");
