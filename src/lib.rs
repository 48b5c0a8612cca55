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
//! - [`conventions`]: where and how a launch monitor defines the delivery, and its exact
//!   conversion to the model's convention with the club's own face geometry.
//! - [`measurement`]: measurement error in the delivered inputs (regression calibration of
//!   noisy impact locations and delivery variables).
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
//! - [`infer`]: `smash infer-club`: the head's effective properties estimated from the shots,
//!   with honest uncertainty.
//! - [`flight`]: ball flight from launch to landing (aerodynamics, atmosphere, batched
//!   integrator, bounce and roll) and its validation data.
//! - [`sweep`]: the face-map kernel: many impacts of one model and swing, fast.
//! - [`study`]: design studies: maps over design variants, summaries, sensitivities, optimiser,
//!   shards.
//! - [`report`]: output rendering (SVG heatmaps, CSV matrices, text tables).
//! - [`app`]: the commands as library calls: per command a settings type (serde) and a `run`
//!   from settings and inputs to the command's report, which the command line and the Python
//!   package only fill and render.
//!
//! Underneath every room, the floors any of them may use (they use none of the rooms):
//!
//! - [`units`]: conversions between the file units and the SI units used inside.
//! - [`limits`]: the physical range of every input quantity and the caps on one command's work.
//! - [`inputs`]: the files this process has read, so that no output is written over one.
//! - [`line_index`]: line numbers of byte offsets, whatever a file's line ends.
//! - [`suggest`]: "did you mean" for a name typed wrong.
//! - [`cancel`]: a cancellation token long work checks between its fits.
//! - [`wrap`]: word wrapping of long text lines at a report's width.
//!
//! The `smash` command line is a separate package of the workspace (`cli/`), a thin layer over
//! this library; the library itself has no command-line dependencies.
//!
//! # Example: from delivery to landing
//!
//! The paper's driver at 100 mph and 12° of dynamic loft, struck at the face centre, then the
//! ball flown in the default air. Deliveries and launches are in SI inside; the file units
//! (mph, degrees, rpm, mm) are the shots file's.
//!
//! ```
//! use std::path::Path;
//! use smash::data::club_file::read_club;
//! use smash::flight::{fly, FlightConfig, FlightLaunch};
//! use smash::model::{delivery_from_file_units, DeliveryVar, N_DELIVERY};
//!
//! let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
//! let club = read_club(&path)?;
//! let model = club.model_for_group("all")?;
//! let mut x = [0.0; N_DELIVERY]; // file units, in DeliveryVar::ALL order
//! x[DeliveryVar::ClubSpeed.index()] = 100.0; // mph
//! x[DeliveryVar::DynamicLoft.index()] = 12.0; // degrees
//! let launch = model.solve(&delivery_from_file_units(&x))?.launch();
//! let [ball_speed_mph, launch_deg, _, backspin_rpm, _] = launch.to_file_units();
//! // A driver's smash factor is about 1.4 to 1.5; loft launches the ball up with backspin.
//! assert!((135.0..=155.0).contains(&ball_speed_mph), "{ball_speed_mph} mph");
//! assert!(launch_deg > 5.0 && backspin_rpm > 1500.0, "{launch_deg}°, {backspin_rpm} rpm");
//!
//! let flight = fly(&FlightConfig::default(), &[FlightLaunch::from_launch(&launch)]).remove(0)?;
//! let carry_yd = flight.carry_m / 0.9144;
//! assert!((200.0..=280.0).contains(&carry_yd), "{carry_yd} yd");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// `!(x > 0.0)` is used on purpose: it rejects NaN along with the non-positive values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod app;
pub mod cancel;
pub mod club;
pub mod club_match;
pub mod compare;
pub mod conventions;
pub mod data;
pub mod diagnose;
pub mod effects;
pub mod fit;
pub mod flight;
pub mod infer;
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
pub mod wrap;

pub use club::ClubSpec;
pub use effects::{Effect, EffectKind};
pub use physics::{Delivery, ImpactModel, ImpactOutcome, Launch, LaunchComponent, ModelParams};
