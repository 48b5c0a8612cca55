//! `shaft_fraction`: added clubhead mass in proportion to each shot's shaft mass.
//!
//! The paper's second adjustment adds mass to the head for the shaft's part in the impact, and
//! its Figure 3 shows the added mass rising with the mass of the shaft (Table 4: 2.54, 0.88 and
//! 1.18 g for shafts of 74.5, 60.3 and 70.9 g). `added_mass@group` fits one mass per shaft;
//! this effect fits the relation itself, one fraction for every shaft:
//!
//! ```text
//! m_c → m_c + f·m_shaft
//! ```
//!
//! with `m_shaft` the shot's `shaft_mass_g` column (the paper's mean driver shaft,
//! [`crate::physics::user_terms::DEFAULT_SHAFT_MASS_G`], when the shots file has none). The
//! mass differs from shot to shot, so it is applied per shot through the same pre-solve term a
//! user-defined `club_mass_g` expression uses ([`crate::physics::user_terms`]): the law is
//! written once. Two of them on one shot add. Its lane form is that term's: the fits evaluate
//! it on lane vectors of shots, each lane with its own shaft mass
//! ([`crate::physics::ImpactModel::shot_consts_of`]), never one shot at a time
//! (`tests/lane_path.rs` counts the lanes' refusals).

use std::sync::OnceLock;

use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use super::{spec, ParamSpec};
use crate::physics::expr::Program;
use crate::physics::user_terms::{
    AppliedTerm, Quantity, UserTermDef, MAX_USER_PARAMS, VAR_NOMINAL, VAR_PARAM0,
    VAR_SHAFT_MASS,
};
use crate::physics::{LaunchComponent, ModelParams};

/// Name in files and on the command line.
pub const NAME: &str = "shaft_fraction";

/// One-line description.
pub const DESCRIPTION: &str =
    "m_c -> m_c + f*shaft_mass (added mass in proportion to each shot's shaft mass)";

/// Parameters, in file order. Physical: no part of a shaft leaves the head, and at most the
/// whole shaft takes part. Plausible: the paper's three shafts give 0.015–0.034; 0.15 (about
/// 10 g of a 70 g shaft) is `added_mass`'s plausible limit (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[spec(
    "f",
    "1",
    0.0,
    0.0,
    1.0,
    (0.0, 0.15),
    "fraction of the shaft's mass added to the clubhead",
)];

/// The pre-solve term `club_mass_g = club_mass_g + f·shaft_mass_g`, compiled once.
fn term() -> &'static UserTermDef {
    static TERM: OnceLock<UserTermDef> = OnceLock::new();
    TERM.get_or_init(|| {
        let text = "club_mass_g + f * shaft_mass_g";
        let resolve = |name: &str| match name {
            "club_mass_g" => Ok(VAR_NOMINAL),
            "f" => Ok(VAR_PARAM0),
            "shaft_mass_g" => Ok(VAR_SHAFT_MASS),
            other => Err(crate::physics::expr::UnknownName(other.to_owned())),
        };
        UserTermDef {
            effect: NAME,
            quantity: Quantity::ClubMassG,
            program: Program::compile(text, &resolve).expect("a fixed, valid expression"),
            text,
        }
    })
}

/// Apply with parameter values `v` (units of [`PARAMS`]).
pub fn apply(v: &[f64], p: &mut ModelParams) {
    let mut params = [0.0; MAX_USER_PARAMS];
    params[0] = v[0];
    p.user.push(AppliedTerm {
        def: term(),
        params,
    });
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(
        LaunchComponent::BallSpeed,
        Pattern::Bias,
        "effective clubhead mass: part of the shaft taking part",
    ),
    row(
        LaunchComponent::BallSpeed,
        Pattern::GroupBias,
        "more mass taking part behind a heavier shaft",
    ),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "more of the shaft taking part than a half-millisecond impact allows: behaves like a higher \
     face COR or a heavier head than the file's",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str =
    "shafts of different mass on the same head (the added mass must follow the shaft mass), or \
     head speed just after impact";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing(
    "a mass change moves ball speed at every delivery; with one shaft mass it is added_mass, and \
     only shafts of different mass tell the two apart",
);
