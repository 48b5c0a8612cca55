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
//!
//! **Offered or world-only.** A definition read from an effects file or a club file is
//! [`Offer::Candidate`]: `diagnose` ranks it beside the library's effects and `compare` hints at
//! it ([`offered`]). One read from a `synth` world's file is [`Offer::WorldOnly`]: physics the
//! world hides, nameable by that world's `[[hidden]]` tables but never offered to a model
//! search, so that a diagnosis run after a synth in the same process (the Python package, the
//! tests) does not get the hidden truth among its candidates, as a separate `smash diagnose`
//! never does. The same definition read later from an effects or club file becomes offered.

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

/// Whether a registered definition is offered to model searches (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Offer {
    /// From an effects file or a club file: a default candidate of `diagnose`, a hint of
    /// `compare`.
    Candidate,
    /// From a synth world's file (its config or base club): the world's hidden physics, not
    /// offered by this reading (registered like [`Offer::Reread`]: one an effects or club file
    /// offered stays offered).
    WorldOnly,
    /// A club's own text read back (a written club checked, a club variant made): a definition
    /// registered before keeps whether it is offered; one new to the registry is not offered.
    Reread,
}

/// A registered definition and whether it is offered ([`Offer`]).
struct Entry {
    effect: &'static UserEffect,
    offered: bool,
}

static REGISTRY: RwLock<Vec<Entry>> = RwLock::new(Vec::new());

/// The registered user-defined effect called `name`.
pub fn lookup(name: &str) -> Option<&'static UserEffect> {
    REGISTRY
        .read()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .map(|e| e.effect)
        .find(|u| u.name == name)
}

/// Every registered user-defined effect, in registration order (offered or not: every one
/// can be named).
pub fn registered() -> Vec<&'static UserEffect> {
    REGISTRY
        .read()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .map(|e| e.effect)
        .collect()
}

/// The registered user-defined effects offered to model searches ([`Offer::Candidate`]), in
/// registration order: `diagnose`'s default candidates and `compare`'s hints.
pub fn offered() -> Vec<&'static UserEffect> {
    REGISTRY
        .read()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .filter(|e| e.offered)
        .map(|e| e.effect)
        .collect()
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

/// Register `def` as `offer` says: a new name is added; a name already registered with the
/// same definition returns that one (offered from now on if `offer` is
/// [`Offer::Candidate`], else as it was); a name of the library or registered with another
/// definition is an error.
pub fn register(def: UserEffect, offer: Offer) -> Result<&'static UserEffect, RegisterError> {
    if EffectKind::from_name(def.name).is_some() {
        return Err(RegisterError::LibraryName { name: def.name });
    }
    let offered = offer == Offer::Candidate;
    let mut reg = REGISTRY.write().unwrap_or_else(|e| e.into_inner());
    if let Some(old) = reg.iter_mut().find(|e| e.effect.name == def.name) {
        if *old.effect == def {
            old.offered |= offered;
            return Ok(old.effect);
        }
        return Err(RegisterError::DefinedDifferently {
            name: def.name,
            source_file: old.effect.source.clone(),
        });
    }
    let leaked: &'static UserEffect = Box::leak(Box::new(def));
    reg.push(Entry {
        effect: leaked,
        offered,
    });
    Ok(leaked)
}
