//! `cor_spot`: the face's COR peaks away from its centre.
//!
//! A driver face is thinned unevenly, and its hot spot is often placed low or toward the toe,
//! where amateurs strike. With the peak at `a = (y₀, z₀)` and the falloff `c`,
//!
//! ```text
//! e = … − c·((y − y₀)² + (z − z₀)²)
//! ```
//!
//! which is `cor_radial` when `a = 0` (and adds to it exactly: the restitution law keeps the
//! sums `Σ c`, `Σ c·a` and `−Σ c·|a|²`, [`crate::physics::laws::Restitution`]). At the peak the
//! COR is the face's own `cor` (plus `cor_level`).

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "cor_spot";

/// One-line description.
pub const DESCRIPTION: &str =
    "COR peaks at (y0, z0) on the face and falls with squared distance from there";

/// `cor_radial`'s falloff parameter.
const FALLOFF: ParamSpec = super::cor_radial::PARAMS[0];

/// Parameters, in file order. Physical: the peak on a driver face (±30 mm high, ±40 mm heel to
/// toe); the falloff as `cor_radial`'s. Plausible: a peak within 10 mm of the centre (face
/// designs move the hot spot a few mm low and toeward) and `cor_radial`'s falloff range
/// (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[
    spec(
        "y0_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-10.0, 10.0),
        "height of the COR peak above the face centre",
    ),
    spec(
        "z0_mm",
        "mm",
        0.0,
        -40.0,
        40.0,
        (-10.0, 10.0),
        "heel-toe position of the COR peak (toward the toe: +z)",
    ),
    // The falloff is `cor_radial`'s, about another centre: the same bounds and plausible range.
    spec(
        "c_per_mm2",
        "1/mm²",
        0.0,
        FALLOFF.lower,
        FALLOFF.upper,
        FALLOFF.plausible,
        "COR drop per mm² of squared distance from the peak",
    ),
];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    let (y0_m, z0_m, c_per_m2) = (v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e6);
    p.cor_radial_c_per_m2 += c_per_m2;
    p.cor_radial_moment_per_m[0] += c_per_m2 * y0_m;
    p.cor_radial_moment_per_m[1] += c_per_m2 * z0_m;
    p.cor_radial_offset -= c_per_m2 * (y0_m * y0_m + z0_m * z0_m);
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(
        LaunchComponent::BallSpeed,
        Pattern::Trend("impact_y_mm"),
        "COR peaking above or below the centre",
    ),
    row(
        LaunchComponent::BallSpeed,
        Pattern::Trend("impact_z_mm"),
        "COR peaking toward the toe or heel",
    ),
    row(
        LaunchComponent::BallSpeed,
        Pattern::Trend("impact_r_mm"),
        "COR falling away from its peak",
    ),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a COR peak farther from the centre, or a falloff steeper, than faces have: behaves like \
     heel-toe energy loss of a CoM or inertia different from the file's, or anisotropic face flex",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str =
    "a COR (CT) map of the face at several points, or strikes spread around the suspected peak";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::AnyOf(
    &[DeliveryVar::ImpactY, DeliveryVar::ImpactZ],
    "its COR falls with distance from a peak on the face, so the impact location must vary",
);
