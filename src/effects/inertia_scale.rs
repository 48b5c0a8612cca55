//! `inertia_scale`: scaling of the clubhead inertia tensor.

use super::{spec, ParamSpec};
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
