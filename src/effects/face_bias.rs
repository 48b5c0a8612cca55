//! `face_bias`: bias on delivered face angle.

use super::{spec, ParamSpec};
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
