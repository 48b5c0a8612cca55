//! `friction`: coulomb friction limit on the tangential impulse.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "friction";

/// One-line description.
pub const DESCRIPTION: &str = "Coulomb limit mu on the tangential impulse (gross slip)";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "mu",
    "1",
    0.4,
    1e-3,
    2.0,
    (0.1, 0.6),
    "Coulomb friction coefficient face-ball",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.friction_mu = Some(p.friction_mu.map_or(v[0], |mu| mu.min(v[0])));
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::LaunchAngle, Pattern::Trend("dynamic_loft_deg"), "how far the ball follows the face normal"),
    row(LaunchComponent::Azimuth, Pattern::Trend("face_angle_deg"), "how far the ball follows the face vs the path"),
    row(LaunchComponent::Azimuth, Pattern::Trend("club_path_deg"), "how far the ball follows the path"),
    row(LaunchComponent::Backspin, Pattern::Trend("dynamic_loft_deg"), "spin loft: slip at high loft"),
    row(LaunchComponent::Backspin, Pattern::Trend("club_speed_mph"), "spin growing with speed: slip"),
    row(LaunchComponent::Sidespin, Pattern::Trend("face_angle_deg"), "face-to-path spin axis"),
    row(LaunchComponent::Sidespin, Pattern::Trend("club_path_deg"), "face-to-path spin axis"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a slip limit outside ball-on-face values: behaves like tangential compliance",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "spin over a wider range of dynamic loft (the tangential regime changes with obliquity)";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a slip limit caps the tangential impulse of oblique shots, whatever else varies");
