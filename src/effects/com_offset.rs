//! `com_offset`: offset of the clubhead centre of mass.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;
use crate::units::mm;

/// Name in files and on the command line.
pub const NAME: &str = "com_offset";

/// One-line description.
pub const DESCRIPTION: &str = "clubhead centre of mass offset, in F";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "dx_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along x_F (face normal)",
    ),
    spec(
        "dy_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along y_F (up)",
    ),
    spec(
        "dz_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along z_F (toe)",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.club_com_m.x += mm(v[0]);
    p.club_com_m.y += mm(v[1]);
    p.club_com_m.z += mm(v[2]);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Trend("impact_y_mm"), "effective mass varying up the face"),
    row(LaunchComponent::BallSpeed, Pattern::Trend("impact_z_mm"), "heel-toe energy loss: CoM position"),
    row(LaunchComponent::LaunchAngle, Pattern::Trend("impact_y_mm"), "vertical gear effect"),
    row(LaunchComponent::Azimuth, Pattern::Trend("impact_z_mm"), "horizontal gear effect"),
    row(LaunchComponent::Backspin, Pattern::Trend("impact_y_mm"), "vertical gear effect: CoM height and depth"),
    row(LaunchComponent::Sidespin, Pattern::Trend("impact_z_mm"), "horizontal gear effect: CoM"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a centre of mass moved beyond CAD tolerance: behaves like gear effect changed by a finite contact (the contact point travels, the head rotates) or tangential compliance",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "a measured centre of mass (balance) and shots spread over the face";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("the CoM sets the lever arm of every impact, centre strikes included");
