//! `cor_level`: the face's own COR, fitted (`cor → cor + dcor`).
//!
//! The nominal COR of a club file is fixed; without this effect a face that is livelier or
//! deader than its file says can only be absorbed by other effects (a negative added mass, say).
//! The composed COR must stay in (0, 1] (checked when the model is built).

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_level";

/// One-line description.
pub const DESCRIPTION: &str = "the face's COR itself: cor -> cor + dcor";

/// Parameters, in file order. Plausible range: a conforming driver's COR is at most 0.830 plus
/// the test tolerance 0.008 (USGA/R&A Equipment Rules, Appendix II 5a, and the pendulum test
/// protocol); drivers measure mostly 0.78–0.83, so a fitted change beyond −0.05…+0.02 from a
/// nominal near the limit is another effect in disguise.
pub const PARAMS: &[ParamSpec] = &[spec(
    "dcor",
    "1",
    0.0,
    -0.5,
    0.17,
    (-0.05, 0.02),
    "change of the face's normal COR at the reference speed and the face centre",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.cor += v[0];
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Bias, "the face's own COR"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a face COR outside what conforming drivers show: behaves like an effective mass change (shaft taking part) or energy lost in a compliant contact",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "a COR test of the face (pendulum CT or ball-cannon rebound) or head speed just after impact";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a COR change moves ball speed at every delivery");
