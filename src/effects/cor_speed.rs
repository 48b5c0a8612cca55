//! `cor_speed`: cOR falling linearly with normal approach speed.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_speed";

/// One-line description.
pub const DESCRIPTION: &str = "COR falls linearly with normal approach speed";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "k_per_m_s",
    "s/m",
    0.0,
    0.0,
    0.02, (0.0, 0.005),
    "COR drop per m/s of normal approach speed above 48.77 m/s (a ball's COR falls with speed: k >= 0)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.cor_speed_k_s_per_m += v[0];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Trend("club_speed_mph"), "COR falling with impact speed"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a COR falling with speed faster than balls do: behaves like a COR level or a power-law COR and energy lost in a compliant contact",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "shots over a wider range of club speed";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ClubSpeed],
    "its COR slope is against approach speed, so the club speed must vary",
);
