//! `face_bias`: bias on delivered face angle.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;
use crate::units::deg;

/// Name in files and on the command line.
pub const NAME: &str = "face_bias";

/// One-line description.
pub const DESCRIPTION: &str = "bias on the measured face angle";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "deg",
    "deg",
    0.0,
    -15.0,
    15.0,
    (-3.0, 3.0),
    "added to the delivered face angle",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.face_bias_rad += deg(v[0]);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::Azimuth, Pattern::Bias, "delivered face angle measured with an offset"),
    row(LaunchComponent::Azimuth, Pattern::Trend("face_angle_deg"), "how far the ball follows the face vs the path"),
    row(LaunchComponent::Sidespin, Pattern::Bias, "face reading"),
    row(LaunchComponent::Sidespin, Pattern::Trend("face_angle_deg"), "face-to-path spin axis"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a delivery bias larger than a calibrated monitor has: behaves like the head rotating during a finite contact (face angle changing while in contact)",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "an independent face-angle measurement (high-speed video of the face)";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("an offset of the delivered face angle moves azimuth and side spin of every shot");
