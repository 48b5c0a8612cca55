//! `tangential_restitution`: tangential restitution `e_t`.

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "tangential_restitution";

/// One-line description.
pub const DESCRIPTION: &str = "tangential rebound e_t instead of no slip";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "et",
    "1",
    0.0,
    -1.0,
    1.0,
    (-0.3, 0.3),
    "tangential restitution (0 = no slip, the paper's model)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.tangential_restitution += v[0];
}
