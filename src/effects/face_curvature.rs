//! `face_curvature`: the face's bulge and roll radii differ from the club file's.
//!
//! The face is a torus (`docs/conventions.md`, face geometry): its bulge radius curves it heel
//! to toe, its roll radius crown to sole. Real drivers spread over about 7–17 inches of each
//! (178–432 mm), and a club file often carries a generic 12 inches (305 mm, the paper's driver)
//! because the real radii are not published. Off the centre the face normal then points
//! elsewhere than the model's: a toe strike starts farther right the smaller the bulge radius,
//! a high strike higher the smaller the roll radius. At the centre the normal is the same for
//! any radii, so only shots spread over the face show the effect.
//!
//! `R_bulge → R_bulge + Δb`, `R_roll → R_roll + Δr`; two of them on one shot add.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "face_curvature";

/// One-line description.
pub const DESCRIPTION: &str =
    "the face's bulge and roll radii differ from the club file's (off-centre launch direction)";

/// Parameters, in file order. Physical: a radius stays above 50 mm for the paper's 305 mm face
/// (a tighter face would not be a driver's; a club whose file radius minus the change is not
/// positive is refused by the model's validation). Plausible: the spread of real drivers'
/// radii (about 178–432 mm) around a generic 305 mm file value (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "d_bulge_mm",
        "mm",
        0.0,
        -255.0,
        2000.0,
        (-130.0, 130.0),
        "change of the bulge (heel-toe) radius from the club file's",
    ),
    spec(
        "d_roll_mm",
        "mm",
        0.0,
        -255.0,
        2000.0,
        (-130.0, 130.0),
        "change of the roll (crown-sole) radius from the club file's",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.bulge_m += v[0] * 1e-3;
    p.roll_m += v[1] * 1e-3;
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(
        LaunchComponent::Azimuth,
        Pattern::Trend("impact_z_mm"),
        "bulge: the face normal turns heel to toe",
    ),
    row(
        LaunchComponent::LaunchAngle,
        Pattern::Trend("impact_y_mm"),
        "roll: the face normal turns crown to sole",
    ),
    row(
        LaunchComponent::Sidespin,
        Pattern::Trend("impact_z_mm"),
        "bulge: the spin axis tilts with the face normal",
    ),
    row(
        LaunchComponent::Backspin,
        Pattern::Trend("impact_y_mm"),
        "roll: spin loft changes up the face",
    ),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn {
    below: "a face curved more tightly than drivers are: behaves like gear effect stronger than \
            the file's CoM and inertia give, or a face twisted toward the toe",
    above: "a face flatter than drivers are: behaves like gear effect weaker than the file's CoM \
            and inertia give, or a loft or face angle that changes across the face",
};

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str =
    "the face's bulge and roll radii measured with a radius gauge, and strikes spread heel to toe \
     and high to low";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ImpactY, DeliveryVar::ImpactZ],
    "the radii only turn the face normal away from the centre, so the impact location must vary",
);
