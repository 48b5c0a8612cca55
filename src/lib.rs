//! `smash`: golf clubhead–ball impact engine.
//!
//! The flow, one room per folder, in the order data moves through them:
//!
//! - [`lanes`]: a tiny portable SIMD type (fixed-width `f64` lanes) that the batch code (physics
//!   laws, face-map kernel, flight integrator) is written in.
//! - [`physics`]: the pure momentum-based impact model (face torus, frames, 3×3 impulse solve,
//!   launch conditions). No I/O.
//! - [`effects`]: the named library of physics beyond the nominal model, each with parameters,
//!   units and bounds.
//! - [`club`]: a club as users describe it (nominal + effects) → a validated model per group.
//! - [`club_match`]: do the shots belong to the club file (names, delivered loft, speed)?
//! - [`model`]: the domain types every room above the physics shares: a shot and the delivery
//!   variables (column, unit, range, typical instrument noise). No I/O.
//! - [`data`]: club TOML, shots CSV, predictions CSV, noise files, launch-monitor import; the one
//!   place that writes files.
//! - [`synth`]: synthetic experiments with hidden effects and world-only physics (and the bytes
//!   of their files).
//! - [`predict`]: shots → model → predictions.
//! - [`compare`]: model against measurements: Table 2, significance, face maps, findings.
//! - [`stats`]: pure statistics (summaries, t tests, correlation, robust scale, regression,
//!   Table-2 error statistics, grouped folds).
//! - [`fit`]: residual problem, bounded Levenberg–Marquardt through argmin, covariance,
//!   calibration reports.
//! - [`diagnose`]: which effect is missing: grouped cross-validation and forward selection.
//! - [`flight`]: ball flight from launch to landing (aerodynamics, atmosphere, batched
//!   integrator, bounce and roll) and its validation data.
//! - [`sweep`]: the face-map kernel: many impacts of one model and swing, fast.
//! - [`study`]: design studies: maps over design variants, summaries, sensitivities, optimiser,
//!   shards.
//! - [`report`]: output rendering (SVG heatmaps, CSV matrices, text tables).
//!
//! The `smash` command line is a separate package of the workspace (`cli/`), a thin layer over
//! this library; the library itself has no command-line dependencies.

// `!(x > 0.0)` is used on purpose: it rejects NaN along with the non-positive values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod club;
pub mod club_match;
pub mod compare;
pub mod conventions;
pub mod data;
pub mod diagnose;
pub mod effects;
pub mod fit;
pub mod flight;
pub mod inputs;
pub mod lanes;
pub mod limits;
pub mod line_index;
pub mod measurement;
pub mod model;
pub mod physics;
pub mod predict;
pub mod report;
pub mod stats;
pub mod study;
pub mod suggest;
pub mod sweep;
pub mod synth;
pub mod units;

pub use club::ClubSpec;
pub use effects::{Effect, EffectKind};
pub use physics::{Delivery, ImpactModel, ImpactOutcome, Launch, LaunchComponent, ModelParams};
