//! `cor_radial`: cOR falling with squared distance from the face centre.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
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

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Trend("impact_r_mm"), "COR falling off-centre"),
    row(LaunchComponent::BallSpeed, Pattern::Trend("impact_y_mm"), "COR varying up the face"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a COR falling off-centre faster than faces do: behaves like anisotropic face flex, a COR peak away from the centre or head rotation during a finite contact",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "shots spread wider over the face, centre to edge";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ImpactY, DeliveryVar::ImpactZ],
    "its COR falloff is with distance from the face centre, so the impact location must vary",
);
