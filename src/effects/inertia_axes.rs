//! `inertia_axes`: the clubhead's moments of inertia about the vertical and the heel–toe axes
//! of the face frame, each scaled on its own.
//!
//! `inertia_scale` scales the whole tensor, so a fit can only say the head is stiffer or
//! softer against turning in every direction at once. A real head differs from a typical one
//! axis by axis: its moment about the vertical axis `y_F` (the "MOI" of the rules, set by how
//! far toe and heel weight sit from the CoM) governs the horizontal gear effect and the speed
//! lost heel and toe; its moment about the heel–toe axis `z_F` governs the vertical gear effect
//! of high and low strikes.
//!
//! The three moments are not independent: with the head's second moments of mass
//! `M_xx = ∫x² dm`, `M_yy = ∫y² dm`, `M_zz = ∫z² dm` (about the CoM, F axes),
//! `I_xx = M_yy + M_zz`, `I_yy = M_xx + M_zz`, `I_zz = M_xx + M_yy`. Scaling two diagonal
//! entries alone soon gives a tensor no mass distribution has (the paper driver's `I_yy` can
//! rise only 22 % before it exceeds `I_xx + I_zz`). So the effect moves mass, not entries:
//!
//! ```text
//! M_xx → s_z·M_xx,  M_yy → s_z·M_yy      (the spreads front–back and up–down: I_zz → s_z·I_zz)
//! M_zz → s_y·I_yy − s_z·M_xx             (the heel–toe spread that makes I_yy → s_y·I_yy)
//! I_xx → M_yy' + M_zz'                    (follows; the products of inertia are kept)
//! ```
//!
//! with the `M` of the diagonal entries as they are when the effect applies. Neutral at
//! `(1, 1)`; two of them on one shot compose (each scales the moments it names), and they
//! commute with `inertia_scale` (every step is linear and homogeneous in the tensor); at
//! `s_y = s_z = s` it is `inertia_scale` with `s`. The heel–toe spread is floored at a fifth of
//! the head's own (`s_y/s_z` far below the plausible range for a driver; `I_yy` is then above
//! `s_y·I_yy`), so that every point of the physical box leaves a tensor a head can have. Its lane form is the collision matrix's: the effect only changes
//! [`ModelParams::club_inertia_kgm2`], which the scalar solve and the lanes read alike
//! (`docs/adding-an-effect.md`).

use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use super::{spec, ParamSpec};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Smallest heel-toe second moment of mass the effect leaves, as a fraction of the head's own.
const HEEL_TOE_FLOOR: f64 = 0.2;

/// Name in files and on the command line.
pub const NAME: &str = "inertia_axes";

/// One-line description.
pub const DESCRIPTION: &str =
    "clubhead moments about the vertical (y_F) and heel-toe (z_F) axes scaled by moving mass (I_xx follows)";

/// Parameters, in file order. Physical: 0.5–2 about the vertical axis; 0.6–2 about the heel–toe
/// axis, whose factor also scales the crown–sole spread, which the paper driver's product of
/// inertia `I_xy` needs above about half its own for the tensor to stay one a head can have.
/// Plausible: ±25 % (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "sy",
        "1",
        1.0,
        0.5,
        2.0,
        (0.75, 1.25),
        "factor on the moment of inertia about the vertical axis y_F (I_yy)",
    ),
    spec(
        "sz",
        "1",
        1.0,
        0.6,
        2.0,
        (0.75, 1.25),
        "factor on the moment of inertia about the heel-toe axis z_F (I_zz)",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    let (sy, sz) = (v[0], v[1]);
    let i = &mut p.club_inertia_kgm2;
    let (ixx, iyy, izz) = (i[(0, 0)], i[(1, 1)], i[(2, 2)]);
    let m_xx = 0.5 * (iyy + izz - ixx);
    let m_yy = 0.5 * (ixx + izz - iyy);
    // Floored at a fifth of the head's own heel-toe spread: beyond it (s_y/s_z far below the
    // plausible range) the tensor would stop being one a mass distribution can have, and every
    // point of the box [lower, upper] must stay evaluable for a fit.
    let m_zz = (sy * iyy - sz * m_xx).max(HEEL_TOE_FLOOR * 0.5 * (ixx + iyy - izz));
    i[(0, 0)] = sz * m_yy + m_zz;
    i[(1, 1)] = sy * iyy;
    i[(2, 2)] = sz * izz;
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(
        LaunchComponent::Sidespin,
        Pattern::Trend("impact_z_mm"),
        "horizontal gear effect: moment about the vertical axis",
    ),
    row(
        LaunchComponent::BallSpeed,
        Pattern::Trend("impact_z_mm"),
        "heel-toe energy loss: moment about the vertical axis",
    ),
    row(
        LaunchComponent::Backspin,
        Pattern::Trend("impact_y_mm"),
        "vertical gear effect: moment about the heel-toe axis",
    ),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a head that turns more or less about one axis than a head's mass distribution allows: \
     behaves like a CoM deeper or shallower than the file's, a finite contact time or \
     tangential compliance",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str =
    "the head's moments measured on an MOI instrument, and strikes spread heel to toe and high to low";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ImpactY, DeliveryVar::ImpactZ],
    "a moment about one axis only acts when the impact line misses the CoM along the other, so \
     the impact location must vary",
);
