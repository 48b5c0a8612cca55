//! `ball_offset`: shifted ball centre of mass relative to the contact point (the paper's ball deformation).

use super::{spec, ParamSpec};
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
