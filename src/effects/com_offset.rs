//! `com_offset`: offset of the clubhead centre of mass.

use super::{spec, ParamSpec};
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
