//! `smash`: golf clubhead–ball impact engine.
//!
//! The flow, one room per folder or file:
//!
//! - [`physics`]: the pure momentum-based impact model (face torus, frames, 3×3 impulse solve,
//!   launch conditions). No I/O.
//! - [`effects`]: the named library of physics beyond the nominal model, each with parameters,
//!   units and bounds.
//! - [`club`]: a club as users describe it (nominal + effects) → a validated model per group.
//! - [`data`]: club TOML, shots CSV, predictions CSV; the one place that writes files.
//! - [`predict`]: shots → model → predictions.
//! - [`sweep`]: design-study sweeps: the vectorised face-map kernel over impact grids.
//! - [`cli`]: the `smash` command line, a thin layer over the library.

// `!(x > 0.0)` is used on purpose: it rejects NaN along with the non-positive values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod cli;
pub mod club;
pub mod data;
pub mod effects;
pub mod physics;
pub mod predict;
pub mod sweep;
pub mod units;

pub use club::ClubSpec;
pub use effects::{Effect, EffectKind};
pub use physics::{Delivery, ImpactModel, ImpactOutcome, Launch, LaunchComponent, ModelParams};
