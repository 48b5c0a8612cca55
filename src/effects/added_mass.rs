//! `added_mass`: added clubhead mass (the paper's shaft effect).

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "added_mass";

/// One-line description.
pub const DESCRIPTION: &str = "m_c -> m_c + dm (shaft mass taking part in the impact)";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "dm_g",
    "g",
    0.0,
    -100.0,
    200.0,
    (0.0, 10.0),
    "mass added to the clubhead",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.club_mass_kg += v[0] * 1e-3;
}
