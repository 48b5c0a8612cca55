//! `compression_lever`: the ball's compression shortens the lever of the tangential force.
//!
//! The momentum model turns the tangential impulse `P_t` into spin through the ball's radius:
//! angular impulse `R·P_t` (lever `r_b = −R·n`). A real ball is flattened against the face while
//! it takes that impulse. For a sphere pressed on a much stiffer flat by `δ`, the contact plane
//! lies at `R − δ` from the ball's centre (Hertz geometry: Johnson, *Contact Mechanics*, 1985,
//! ch. 4: the approach of a sphere on a flat is `δ = a²/R`), so a tangential force `F_t(t)` acts on the
//! lever `R − δ(t)` and the ball's angular impulse is
//!
//! ```text
//! L = ∫ (R − δ) F_t dt = (R − δ̄)·P_t,          δ̄ = ∫ δ F_t dt / ∫ F_t dt
//! ```
//!
//! with `δ̄` the compression weighted by the tangential force's history. The separation
//! kinematics keep the full radius (at release `δ = 0`, the contact point is `R` from the
//! centre). In the impulse–momentum equations both parts enter through the ball's term of the
//! collision matrix, `R·(R − δ̄)/I_b·(1 − n nᵀ)`, and through the spin `(R − δ̄)·P_t/I_b`: exactly
//! those of a ball with the radius `R` and the moment of inertia `I_b·R/(R − δ̄)`. So the effect
//! divides the ball's moment of inertia by `λ = 1 − δ̄/R` and the laws stay as they are
//! ([`crate::physics::laws::CollisionMatrix`] and the spin `L/I_b` read it). Scaling the lever
//! in *both* places (`r_b = −(R − δ̄)·n`, collision term `(R − δ̄)²/I_b`) would also shorten the
//! separation kinematics' lever, which a ball that has recovered its shape at release does not
//! have.
//!
//! **Why it matters.** With a rigid grip (`e_t = 0`) the contact point leaves rolling and the
//! lever only redistributes the impulse; with a compliant tangential grip (the spring gives
//! shear energy back, `tangential_compliance`) the tangential rebound is set by the spring and
//! the spin per unit tangential impulse is what the lever makes it. The incoming tangential
//! velocity depends on attack angle and club path (and on loft and face angle), so a ball that
//! spins 20 % less per unit tangential impulse than the model thinks leaves residuals in launch
//! angle and azimuth that trend with attack angle and club path, which no other library form
//! removes (`docs/compliant-worlds.md`).
//!
//! **Size.** For Hertz contact the force-weighted mean of `δ` over the impact is
//! `(5/18)·u1n·τ ≈ 0.82·δ_max` (with `τ = 2.94·δ_max/u1n`; Johnson §11.1). A golf ball on a
//! driver face at 45–50 m/s normal speed is compressed to `δ_max` ≈ 6–7 mm (the Hertz
//! stiffness that gives the observed ≈ 0.45 ms contact), so `δ̄` ≈ 4.5–5.5 mm: `λ` ≈ 0.75–0.8.
//! The tangential force's history is not the normal force's (under a gripping Mindlin spring
//! it peaks near maximum compression and reverses before release; Maw, Barber & Fawcett, Wear
//! 38, 1976), so `δ̄` is fitted, not computed. The compliant-contact world of
//! `crate::synth::contact` fits 4.6 mm against its 6.3 mm mean peak compression
//! (`tests/contact_world.rs`, `compression_lever_fits_the_compliant_contact`).
//!
//! One constant is a first-order form: `δ_max` grows as `u1n^0.8`, ±10 % over a driver's speed
//! range; against the simulator a speed-scaled `δ̄` fitted no better than a constant one.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "compression_lever";

/// One-line description.
pub const DESCRIPTION: &str = "ball compressed by delta_mm under the tangential force: spin lever R - delta, \
     i.e. ball inertia I_b*R/(R - delta)";

/// Parameters, in file order. Physical: a compression is not negative and stays below the
/// radius (15 mm is 70 % of a golf ball's). Plausible: the force-weighted mean compression of a
/// golf ball at driver speeds, 0.82 of a 6–7 mm peak (module docs), with margin: 0–7 mm
/// (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[spec(
    "delta_mm",
    "mm",
    0.0,
    0.0,
    15.0,
    (0.0, 7.0),
    "ball compression weighted by the tangential force: the spin lever is radius - delta",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]). Several compose as successive
/// shortenings (the factors `R/(R − δ)` multiply).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    let r = p.ball_radius_m;
    p.ball_inertia_kgm2 *= r / (r - v[0] * 1e-3);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::Backspin, Pattern::Bias, "a shorter spin lever of the compressed ball"),
    row(LaunchComponent::Backspin, Pattern::Trend("club_speed_mph"), "the ball compressing more at speed"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a spin lever shortened beyond what a compressed ball gives: behaves like a loft bias or a tangential rebound outside ball-on-face values",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "spin against launch over a range of attack angle (the tangential approach) and club speed (the compression)";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a shorter lever changes the spin of every shot with a tangential approach");
