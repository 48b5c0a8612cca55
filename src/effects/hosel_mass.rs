//! `hosel_mass`: the shaft tip's effective mass as a point mass at the hosel.
//!
//! The paper's added mass puts the shaft's share at the head's centre of mass (`added_mass`:
//! only `m_c` changes). The shaft actually joins the head at the hosel, heelward, above and
//! behind the face centre, so a mass `dm` there also moves the combined centre of mass toward the
//! hosel and adds inertia by the parallel-axis theorem. With the head's mass `m`, centre of mass
//! `c` and the hosel point `h` (club file `hosel_mm`, face frame F; default
//! [`crate::physics::impact::DRIVER_HOSEL_MM`]), `d = h − c` and the reduced mass
//! `μ = m·dm/(m + dm)`:
//!
//! ```text
//! m' = m + dm        c' = c + (dm/(m + dm))·d        I' = I + μ·(|d|²·1 − d dᵀ)
//! ```
//!
//! (`I'` is the inertia of head plus point mass about the new centre `c'`: the two parallel-axis
//! terms `m·|c − c'|²…` and `dm·|h − c'|²…` sum to `μ·|d|²…`.)

use nalgebra::Matrix3;

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "hosel_mass";

/// One-line description.
pub const DESCRIPTION: &str =
    "shaft tip mass as a point mass at the hosel: mass, CoM and inertia change together";

/// Parameters, in file order. Physical: a point mass is not negative. Plausible: the same
/// range as `added_mass` (the paper's fitted shaft effect is a few grams).
pub const PARAMS: &[ParamSpec] = &[spec(
    "dm_g",
    "g",
    0.0,
    0.0,
    200.0,
    (0.0, 10.0),
    "point mass at the club's hosel_mm (face frame)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    let dm = v[0] * 1e-3;
    let m = p.club_mass_kg;
    let total = m + dm;
    let d = p.hosel_m - p.club_com_m;
    let reduced = m * dm / total;
    p.club_inertia_kgm2 +=
        (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * reduced;
    p.club_com_m += d * (dm / total);
    p.club_mass_kg = total;
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::BallSpeed, Pattern::Bias, "effective clubhead mass: the shaft tip at the hosel"),
    row(LaunchComponent::BallSpeed, Pattern::GroupBias, "shaft tip mass at the hosel, per shaft"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "more shaft mass at the hosel than a shaft tip has: behaves like a higher face COR or a centre of mass and inertia different from the file's",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "heel and toe strikes (the hosel mass changes the gear effect) with shafts of different tip mass";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("a mass change moves ball speed at every delivery");
