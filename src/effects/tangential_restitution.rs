//! `tangential_restitution`: tangential restitution `e_t`.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "tangential_restitution";

/// One-line description.
pub const DESCRIPTION: &str = "tangential rebound e_t instead of no slip";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "et",
    "1",
    0.0,
    -1.0,
    1.0,
    (-0.3, 0.3),
    "tangential restitution (0 = no slip, the paper's model)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.tangential_restitution += v[0];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::LaunchAngle, Pattern::Trend("dynamic_loft_deg"), "how far the ball follows the face normal"),
    row(LaunchComponent::Azimuth, Pattern::Trend("face_angle_deg"), "how far the ball follows the face vs the path"),
    row(LaunchComponent::Azimuth, Pattern::Trend("club_path_deg"), "how far the ball follows the path"),
    row(LaunchComponent::Backspin, Pattern::Trend("dynamic_loft_deg"), "spin loft: grip"),
    row(LaunchComponent::Sidespin, Pattern::Trend("face_angle_deg"), "face-to-path spin axis"),
    row(LaunchComponent::Sidespin, Pattern::Trend("club_path_deg"), "face-to-path spin axis"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "more or less spin than a rebound of that size allows: behaves like regime-dependent tangential compliance or a loft bias",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "spin over a wider range of dynamic loft (the tangential regime changes with obliquity)";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("every oblique impact has a tangential approach it scales, so any delivery shows it");
