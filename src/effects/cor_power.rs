//! `cor_power`: the ball's COR falling as a power of the normal approach speed,
//! `e = cor·(u1n / 48.77 m/s)^(−q)`.
//!
//! The usual empirical form of a golf ball's COR against impact speed (a power law fitted to
//! rebound tests over a speed range; the linear `cor_speed` is its tangent at 48.77 m/s, with
//! `k = q·cor/48.77 m/s`). The law itself is [`crate::physics::laws::Restitution`], which the
//! scalar solve and the face-map kernel share; this effect sets its exponent.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_power";

/// One-line description.
pub const DESCRIPTION: &str = "COR falls as a power of normal approach speed: cor*(u1n/48.77)^-q";

/// Parameters, in file order. Physical: the COR does not rise with speed (`q >= 0`), and
/// `q <= 1` keeps the rebound speed `e·u1n` from falling as the impact gets faster.
/// Plausible: `q` up to 0.3 is a COR drop of at most ~0.005 per m/s at 48.77 m/s, the plausible
/// range of `cor_speed` (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[spec(
    "q",
    "1",
    0.0,
    0.0,
    1.0,
    (0.0, 0.3),
    "exponent of the COR's power law in normal approach speed (0 = off)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]). Several apply as one product:
/// exponents add.
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.cor_power_q += v[0];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Trend("club_speed_mph"), "COR falling with impact speed"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a COR falling with speed faster than balls do: behaves like a COR level or energy lost in a compliant contact",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "shots over a wider range of club speed";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ClubSpeed],
    "its COR falls as a power of approach speed, so the club speed must vary",
);
