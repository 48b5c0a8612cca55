//! `inertia_scale`: scaling of the clubhead inertia tensor.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "inertia_scale";

/// One-line description.
pub const DESCRIPTION: &str = "clubhead inertia tensor scaled";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "s",
    "1",
    1.0,
    0.1,
    10.0,
    (0.85, 1.15),
    "factor on the clubhead inertia tensor",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.club_inertia_kgm2 *= v[0];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Trend("impact_z_mm"), "heel-toe energy loss: inertia"),
    row(LaunchComponent::Azimuth, Pattern::Trend("impact_z_mm"), "horizontal gear effect"),
    row(LaunchComponent::Backspin, Pattern::Trend("impact_y_mm"), "vertical gear effect: inertia"),
    row(LaunchComponent::Sidespin, Pattern::Trend("impact_z_mm"), "horizontal gear effect: inertia"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a head that turns more or less off-centre than its inertia allows: behaves like a finite contact time, a shaft constraint at the hosel, tangential compliance or a face whose curvature differs from the file's",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "a measured moment of inertia (pendulum or MOI instrument) and off-centre shots";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("the head turns about its CoM on every impact whose line misses it, and the CoM is never exactly behind the face centre");
