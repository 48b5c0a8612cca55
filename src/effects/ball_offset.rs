//! `ball_offset`: shifted ball centre of mass relative to the contact point (the paper's ball deformation).

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;
use crate::units::mm;

/// Name in files and on the command line.
pub const NAME: &str = "ball_offset";

/// One-line description.
pub const DESCRIPTION: &str = "ball CoM shifted from the contact normal (ball deformation)";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "dy_mm",
        "mm",
        0.0,
        -10.0,
        10.0,
        (-2.0, 2.0),
        "contact point relative to ball CoM, along y_I",
    ),
    spec(
        "dz_mm",
        "mm",
        0.0,
        -10.0,
        10.0,
        (-2.0, 2.0),
        "contact point relative to ball CoM, along z_I",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.ball_offset_y_m += mm(v[0]);
    p.ball_offset_z_m += mm(v[1]);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::Backspin, Pattern::Bias, "ball deformation: CoM off the contact normal (dy)"),
    row(LaunchComponent::Backspin, Pattern::GroupBias, "shaft-dependent spin"),
    row(LaunchComponent::Backspin, Pattern::Trend("club_speed_mph"), "spin growing with speed: deformation"),
    row(LaunchComponent::Sidespin, Pattern::Bias, "ball deformation sideways (dz)"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a spin bias beyond any ball deformation: behaves like tangential compliance (spin depending on the contact regime) or a loft bias",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "spin over a wider range of dynamic loft";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a lever arm for the normal impulse: it shifts the spin of every shot");
