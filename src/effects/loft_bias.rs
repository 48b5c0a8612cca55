//! `loft_bias`: bias on delivered dynamic loft.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;
use crate::units::deg;

/// Name in files and on the command line.
pub const NAME: &str = "loft_bias";

/// One-line description.
pub const DESCRIPTION: &str = "bias on the measured dynamic loft";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "deg",
    "deg",
    0.0,
    -15.0,
    15.0,
    (-3.0, 3.0),
    "added to the delivered dynamic loft",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.loft_bias_rad += deg(v[0]);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::LaunchAngle, Pattern::Bias, "delivered loft measured with an offset"),
    row(LaunchComponent::LaunchAngle, Pattern::Trend("dynamic_loft_deg"), "loft reading"),
    row(LaunchComponent::Backspin, Pattern::Bias, "spin loft read with an offset"),
    row(LaunchComponent::Backspin, Pattern::Trend("dynamic_loft_deg"), "spin loft: loft reading"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a delivery bias larger than a calibrated monitor has: behaves like the head rotating during a finite contact (dynamic loft changing while in contact)",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "an independent dynamic-loft measurement (high-speed video of the face)";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("an offset of the delivered loft moves launch and spin of every shot");
