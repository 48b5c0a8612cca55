//! `cor_radial`: cOR falling with squared distance from the face centre.

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_radial";

/// One-line description.
pub const DESCRIPTION: &str = "COR falls with squared distance from the face centre";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "c_per_mm2",
    "1/mm²",
    0.0,
    0.0,
    2e-3,
    (0.0, 3e-4),
    "COR drop per mm² of squared distance from the face centre (COR peaks at the centre: c >= 0)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.cor_radial_c_per_m2 += v[0] * 1e6;
}
