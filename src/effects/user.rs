//! User-defined effects: `[[define_effect]]` tables read at run time, no recompiling
//! (`docs/user-effects.md`).
//!
//! A definition names parameters (key, unit, default, physical bounds, plausible range) and sets
//! one or more model quantities ([`Quantity`]), each to an expression compiled once
//! ([`crate::physics::expr`]). Applying the effect with parameter values
//! ([`UserEffect::apply`]) adds its compiled terms to [`ModelParams::user`]; the model evaluates
//! them per shot ([`crate::physics::user_terms`]). Files are read by
//! [`crate::data::effect_defs`].
//!
//! Definitions live in a process-wide registry ([`register`]), so that an effect list or a club
//! file can name them like library effects. A name may not clash with the library; defining
//! the same name twice is allowed only with the same definition (a calibrated club file that
//! carries the definition read beside the definitions file it came from).

use std::sync::RwLock;

use super::{EffectKind, ParamSpec, MAX_EFFECT_PARAMS};
use crate::physics::user_terms::{AppliedTerm, MAX_USER_PARAMS};
pub use crate::physics::user_terms::{Quantity, UserTermDef};
use crate::physics::ModelParams;

const _: () = assert!(MAX_USER_PARAMS == MAX_EFFECT_PARAMS);

/// A user-defined effect (leaked once when registered: definitions live for the process).
#[derive(Debug)]
pub struct UserEffect {
    /// Name in files and on the command line.
    pub name: &'static str,
    /// One-line description.
    pub doc: &'static str,
    /// Parameters, in file order.
    pub params: &'static [ParamSpec],
    /// The quantities it sets, in file order.
    pub terms: Vec<&'static UserTermDef>,
    /// The definition as a `[[define_effect]]` table (written back to calibrated club files).
    pub toml: String,
    /// Where it was defined (file), for messages.
    pub source: String,
}

impl PartialEq for UserEffect {
    fn eq(&self, o: &Self) -> bool {
        self.name == o.name && self.toml == o.toml
    }
}

/// Equality is by name and definition text, an equivalence.
impl Eq for UserEffect {}

impl UserEffect {
    /// Apply with parameter values `v` (units of [`UserEffect::params`]): add its terms to the
    /// model's user terms.
    pub fn apply(&self, v: &[f64], p: &mut ModelParams) {
        let mut params = [0.0; MAX_USER_PARAMS];
        params[..v.len()].copy_from_slice(v);
        for def in &self.terms {
            p.user.push(AppliedTerm { def, params });
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Registry

static REGISTRY: RwLock<Vec<&'static UserEffect>> = RwLock::new(Vec::new());

/// The registered user-defined effect called `name`.
pub fn lookup(name: &str) -> Option<&'static UserEffect> {
    REGISTRY
        .read()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .copied()
        .find(|u| u.name == name)
}

/// Every registered user-defined effect, in registration order.
pub fn registered() -> Vec<&'static UserEffect> {
    REGISTRY.read().unwrap_or_else(|e| e.into_inner()).clone()
}

/// Why a user-defined effect cannot be registered ([`register`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RegisterError {
    /// The name of a library effect.
    #[error(
        "'{name}' is the name of a library effect; a user-defined effect needs its own name (the \
         library has: {})",
        EffectKind::all_names()
    )]
    LibraryName {
        /// The name.
        name: &'static str,
    },
    /// A name registered before with another definition.
    #[error(
        "'{name}' is already defined differently (in {source_file}); user-defined effects need \
         distinct names"
    )]
    DefinedDifferently {
        /// The name.
        name: &'static str,
        /// Where the first definition came from.
        source_file: String,
    },
}

/// Register `def`: a new name is added; a name already registered with the same definition
/// returns that one; a name of the library or registered with another definition is an error.
pub fn register(def: UserEffect) -> Result<&'static UserEffect, RegisterError> {
    if EffectKind::from_name(def.name).is_some() {
        return Err(RegisterError::LibraryName { name: def.name });
    }
    let mut reg = REGISTRY.write().unwrap_or_else(|e| e.into_inner());
    if let Some(old) = reg.iter().find(|u| u.name == def.name) {
        if **old == def {
            return Ok(old);
        }
        return Err(RegisterError::DefinedDifferently {
            name: def.name,
            source_file: old.source.clone(),
        });
    }
    let leaked: &'static UserEffect = Box::leak(Box::new(def));
    reg.push(leaked);
    Ok(leaked)
}
