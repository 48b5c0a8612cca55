//! Design studies: face maps over design variants, summaries, sensitivities and optimisation.
//!
//! The flow, one file per step:
//!
//! - [`spec`]: the study file → a resolved [`Study`] (strict parsing, defaults in one place).
//! - [`design`]: design variables (CoM offsets, inertia scalings, principal-moment changes,
//!   discretionary-mass moves) and how they change the clubhead.
//! - [`distribution`]: swings and Gaussian impact/swing scatter (quadrature or fixed-seed samples).
//! - [`metrics`]: outputs and the scalar metrics of a design (centre values, speed retention,
//!   gear effect, distribution mean and spread).
//! - [`sweep`]: variants × grid as a flat work list, computed in parallel with the face-map
//!   kernel (`crate::sweep::kernel`), split into shards.
//! - [`sensitivity`]: central differences at the base design, maps and a ranked table.
//! - [`optimise`]: an argmin cost function over bounded design variables (Nelder–Mead).
//! - [`output`]: the output files as bytes; [`shard`]: shard files and their merge.
//!
//! Nothing here writes files or prints: the CLI does.

pub mod design;
pub mod distribution;
pub mod metrics;
pub mod optimise;
pub mod output;
pub mod sensitivity;
pub mod shard;
pub mod spec;
pub mod sweep;

pub use spec::{parse_study, read_study, resolved_toml, Study};
pub use sweep::{Prepared, VariantResult};

use crate::data::DataError;

/// Most grid points (variants × rows × columns) one run sweeps. Until the study outputs stream
/// to disk, every point's results and its CSV and SVG text are held in memory before writing:
/// a 1000 × 1000 grid peaked at 356 MB resident (`/usr/bin/time -v smash run`, 263 MB of
/// files), about 360 B per point, so 20 million points stay near 7 GB, well inside this
/// machine's 24 GB shared with other work (50 million were accepted before and aborted at
/// 15 GB). Raise this once the outputs stream to disk.
pub const MAX_SWEEP_POINTS: u128 = 20_000_000;

/// Why a study cannot be run or merged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// A file problem (study, club or shard file).
    #[error(transparent)]
    Data(#[from] DataError),
    /// The sweep is larger than one run can hold.
    #[error(
        "the study sweeps {points} grid points ({variants} variant(s) × {ny}×{nz} grid); one run holds at \
         most {MAX_SWEEP_POINTS}: use a coarser [grid] or fewer [design] values"
    )]
    TooLarge {
        /// Variants × rows × columns.
        points: u128,
        /// Variants.
        variants: usize,
        /// Rows.
        ny: usize,
        /// Columns.
        nz: usize,
    },
    /// A design variant of the sweep is not physical.
    #[error("design variant {id} ({values}) is not physical: {problem}")]
    Variant {
        /// Variant id (0-based, as in the outputs).
        id: usize,
        /// The variant's values.
        values: String,
        /// What is wrong.
        problem: String,
    },
    /// A design (sensitivity step, optimiser point) is not physical.
    #[error("design ({values}) is not physical: {problem}")]
    Design {
        /// The design's values.
        values: String,
        /// What is wrong.
        problem: String,
    },
    /// The study's swing does not reach the ball at the face centre.
    #[error("[delivery]: {problem}")]
    Swing {
        /// What is wrong.
        problem: String,
    },
    /// A summary metric of a variant came out infinite or undefined.
    #[error(
        "design variant {id} ({values}): {metric} is {value}, not a number: an impact of the \
         summary probe lines or the [distribution] is off the face or does not reach the ball; \
         narrow [summary] half_width_mm or the [distribution]"
    )]
    NotFinite {
        /// Variant id.
        id: usize,
        /// The variant's values.
        values: String,
        /// The metric's name.
        metric: String,
        /// Its value (`inf`, `NaN`).
        value: f64,
    },
    /// The optimiser failed.
    #[error("optimiser: {0}")]
    Optimise(String),
    /// Shards do not fit together.
    #[error("merge: {0}")]
    Merge(String),
}

/// Everything after the sweep: sensitivities, optimisation and the output files.
pub fn finish(
    p: &Prepared,
    results: &[VariantResult],
) -> Result<(output::Files, Option<optimise::OptimiseResult>), StudyError> {
    metrics::check_finite(p, results)?;
    let sens = sensitivity::sensitivities(p)?;
    let opt = optimise::optimise(p)?;
    Ok((output::study_files(p, results, &sens, opt.as_ref()), opt))
}
