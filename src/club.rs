//! A club as users describe it: nominal clubhead and ball, plus the effects that calibrate it.
//!
//! [`ClubSpec`] is what a club file holds. [`ClubSpec::model_for_group`] composes the nominal
//! parameters with the effects that apply to one group of shots and validates the result into
//! an [`ImpactModel`], ready for the inner loop.

use std::collections::BTreeMap;

use crate::effects::Effect;
use crate::physics::{ImpactModel, ModelParams, ParamError};

/// A group a club's effects do not make physical, or do not name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GroupError {
    /// The clubhead CoM of a group with its effects is not behind the face
    /// ([`ClubSpec::check_com_behind_face`]).
    #[error("with the effects of group '{}': {source}", group.escape_debug())]
    ComNotBehindFace {
        /// The group (`all`: the effects that name no group).
        group: String,
        /// Where the CoM is and where it must be.
        source: crate::limits::LimitError,
    },
    /// A group no effect names ([`ClubSpec::check_group`]).
    #[error("group '{}' is not a group of this club's effects; {}", group.escape_debug(), groups_allowed(groups))]
    Unknown {
        /// The group asked for.
        group: String,
        /// The groups the club's effects name.
        groups: Vec<String>,
    },
}

/// What a `--group` may name, for [`GroupError::Unknown`].
fn groups_allowed(groups: &[String]) -> String {
    if groups.is_empty() {
        "it has no group effects, so only 'all' (the default) applies".to_owned()
    } else {
        format!(
            "its groups are {}, or 'all' (the effects that name no group)",
            groups
                .iter()
                .map(|g| format!("'{}'", g.escape_debug()))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// Clubhead, ball and effects, SI units inside.
#[derive(Debug, Clone, PartialEq)]
pub struct ClubSpec {
    /// Human name of the club.
    pub name: String,
    /// Static loft, rad (informational: the delivered dynamic loft drives the model).
    pub static_loft_rad: Option<f64>,
    /// Nominal physical parameters (no effect applied).
    pub nominal: ModelParams,
    /// Effects, in file order.
    pub effects: Vec<Effect>,
}

impl ClubSpec {
    /// Build a club and check that its nominal parameters and every group's composition are
    /// physical.
    pub fn new(
        name: String,
        static_loft_rad: Option<f64>,
        nominal: ModelParams,
        effects: Vec<Effect>,
    ) -> Result<Self, ParamError> {
        let spec = Self {
            name,
            static_loft_rad,
            nominal,
            effects,
        };
        ImpactModel::new(spec.nominal.clone())?;
        for group in spec.effect_groups() {
            spec.model_for_group(&group).map_err(|mut e| {
                e.problem = format!("{} (with the effects of group '{group}')", e.problem);
                e
            })?;
        }
        // Shots of a group no effect names get the global effects only.
        spec.model_for_group("\u{0}no-group")?;
        Ok(spec)
    }

    /// The same club with other effects (validated).
    pub fn with_effects(&self, effects: Vec<Effect>) -> Result<Self, ParamError> {
        Self::new(
            self.name.clone(),
            self.static_loft_rad,
            self.nominal.clone(),
            effects,
        )
    }

    /// `Ok` when the clubhead's centre of mass is behind the face for every group with its
    /// effects applied (`com_offset`, `hosel_mass`, … may move it): otherwise the group and
    /// the position ([`crate::limits::check_club_com_x_mm`]).
    pub fn check_com_behind_face(&self) -> Result<(), GroupError> {
        let mut groups = self.effect_groups();
        groups.push("all".to_owned());
        for g in groups {
            let x_mm = self.params_for_group(&g).club_com_m.x * 1e3;
            crate::limits::check_club_com_x_mm(x_mm).map_err(|source| {
                GroupError::ComNotBehindFace {
                    group: g.clone(),
                    source,
                }
            })?;
        }
        Ok(())
    }

    /// Groups named by any effect.
    pub fn effect_groups(&self) -> Vec<String> {
        let mut groups: Vec<String> = self
            .effects
            .iter()
            .filter_map(|e| e.group().map(str::to_owned))
            .collect();
        groups.sort();
        groups.dedup();
        groups
    }

    /// `Ok` when `group` (a `--group` flag or a study's `group`) names a group of this club's
    /// effects, or is `all` (the default: the effects that name no group); otherwise a message
    /// listing the groups the club has. A group no effect names would silently get the global
    /// effects only, which is never what a user who typed it meant.
    pub fn check_group(&self, group: &str) -> Result<(), GroupError> {
        let groups = self.effect_groups();
        if group == "all" || groups.iter().any(|g| g == group) {
            return Ok(());
        }
        Err(GroupError::Unknown {
            group: group.to_owned(),
            groups,
        })
    }

    /// Model parameters for shots of `group`: nominal plus every effect that applies.
    pub fn params_for_group(&self, group: &str) -> ModelParams {
        let mut p = self.nominal.clone();
        for e in self.effects.iter().filter(|e| e.applies_to(group)) {
            e.apply(&mut p);
        }
        p
    }

    /// Validated impact model for shots of `group`.
    pub fn model_for_group(&self, group: &str) -> Result<ImpactModel, ParamError> {
        ImpactModel::new(self.params_for_group(group))
    }

    /// One model per distinct group.
    pub fn models_for_groups<'a, I>(
        &self,
        groups: I,
    ) -> Result<BTreeMap<String, ImpactModel>, ParamError>
    where
        I: IntoIterator<Item = &'a str>,
    {
        let mut out = BTreeMap::new();
        for g in groups {
            if !out.contains_key(g) {
                out.insert(g.to_owned(), self.model_for_group(g)?);
            }
        }
        Ok(out)
    }
}
