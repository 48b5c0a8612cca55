//! `friction`: coulomb friction limit on the tangential impulse.

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "friction";

/// One-line description.
pub const DESCRIPTION: &str = "Coulomb limit mu on the tangential impulse (gross slip)";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "mu",
    "1",
    0.4,
    1e-3,
    2.0,
    (0.1, 0.6),
    "Coulomb friction coefficient face-ball",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.friction_mu = Some(p.friction_mu.map_or(v[0], |mu| mu.min(v[0])));
}
