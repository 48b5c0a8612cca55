//! `cor_speed`: cOR falling linearly with normal approach speed.

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_speed";

/// One-line description.
pub const DESCRIPTION: &str = "COR falls linearly with normal approach speed";

/// Parameters, in file order.
pub const PARAMS: &[ParamSpec] = &[spec(
    "k_per_m_s",
    "s/m",
    0.0,
    0.0,
    0.02, (0.0, 0.005),
    "COR drop per m/s of normal approach speed above 48.77 m/s (a ball's COR falls with speed: k >= 0)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.cor_speed_k_s_per_m += v[0];
}
