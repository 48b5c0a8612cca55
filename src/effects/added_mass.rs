//! `added_mass`: added clubhead mass (the paper's shaft effect).

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
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

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Bias, "effective clubhead mass: the shaft taking part"),
    row(LaunchComponent::BallSpeed, Pattern::GroupBias, "shaft mass taking part in the impact"),
    row(LaunchComponent::Backspin, Pattern::GroupBias, "shaft-dependent spin"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn {
    below: "less ball speed and a different spin split than the head's mass gives: behaves like a lower face COR or energy lost in a compliant contact, not like mass leaving the head",
    above: "more ball speed than the head gives: behaves like a higher face COR or a heavier hosel (shaft tip) than the head alone",
};

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "head speed just after impact (momentum balance) or shafts of different tip mass";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a mass change moves ball speed at every delivery: shots that differ in any way identify it");
