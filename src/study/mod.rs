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
//! - [`report`]: the run's report as one typed value, and its text, JSON and HTML renderers.
//! - [`yards`]: studies in yards (impact then ball flight): carry maps, robust carry and
//!   dispersion over a distribution, head constraints (mass, Rules MOI limit, CoM box) and a
//!   discretionary-mass optimiser for expected carry or dispersion; [`yards_variants`]: every
//!   design variant (and each optimiser's result) in yards against the base; [`landing`]: the
//!   landing points of a distribution, their covariance and dispersion ellipse.
//!
//! Nothing here writes files or prints: the CLI does.

pub mod design;
pub mod distribution;
pub mod evaluate;
pub mod landing;
pub mod metrics;
pub mod optimise;
pub mod output;
pub mod report;
pub mod sensitivity;
pub mod shard;
pub mod spec;
pub mod sweep;
pub mod whatif;
pub mod yards;
pub mod yards_run;
pub mod yards_spec;
pub mod yards_variants;

pub use spec::{parse_study, read_study, resolved_toml, Study};
pub use sweep::{Prepared, VariantResult};

use crate::data::DataError;

/// Most grid points (variants × rows × columns) one run sweeps. Outputs are streamed to disk a
/// band at a time, so memory does not grow with the sweep; the cap bounds the time and the disk
/// a run takes (about 70 bytes of CSV per point and output in the long table and matrices: a
/// 500 M-point run with three outputs writes about 100 GB).
pub const MAX_SWEEP_POINTS: u128 = 500_000_000;

/// Most grid points one shard run (`smash run --shard k/N`) computes: a shard is held in memory
/// and written as one `rows.csv` (about 150 bytes a point in all), so this keeps a shard run
/// under 1 GB. An unsharded run streams its outputs and is bounded only by [`MAX_SWEEP_POINTS`].
pub const MAX_SHARD_POINTS: u128 = 6_000_000;

/// Most grid points (variants × rows × columns) a sharded study may have in all: as many as an
/// unsharded run. `smash merge` streams too: it reads the shards' rows into a scratch file
/// beside the output folder (41 bytes a point) and writes the outputs from it a band at a time,
/// so its memory does not grow with the study (tested in `tests/study_memory.rs`); the cap bounds
/// its time and disk, as [`MAX_SWEEP_POINTS`] does a run's.
pub const MAX_MERGE_POINTS: u128 = MAX_SWEEP_POINTS;

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
    /// A shard holds more grid points than one run keeps in memory.
    #[error(
        "shard {k} of {n} holds {points} grid points; a shard holds at most {MAX_SHARD_POINTS} \
         (shards are kept in memory): use at least {min_shards} shards, or run unsharded \
         (streamed to disk)"
    )]
    ShardTooLarge {
        /// Shard index.
        k: usize,
        /// Shards.
        n: usize,
        /// Grid points in the shard.
        points: u128,
        /// Fewest shards that fit.
        min_shards: u128,
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
    #[error("design variant {id} ({values}): {metric} cannot be computed: {culprit}")]
    NotFinite {
        /// Variant id.
        id: usize,
        /// The variant's values.
        values: String,
        /// The metric's name.
        metric: String,
        /// Why, in the user's terms (the impact and the effect, swing or location that failed;
        /// see [`evaluate::culprit`]).
        culprit: String,
    },
    /// The optimiser failed.
    #[error("optimiser: {0}")]
    Optimise(String),
    /// Shards do not fit together (their files disagree).
    #[error("merge: {0}")]
    Merge(#[from] shard::MergeError),
    /// The work items of the shards do not make up the study.
    #[error("merge: {0}")]
    Items(#[from] ItemError),
    /// `[optimise] objective` names a metric the study does not compute.
    #[error("optimise.objective.{metric}: not a metric of this study; allowed: {allowed}")]
    UnknownMetric {
        /// The name given.
        metric: String,
        /// The study's metric names, comma-separated.
        allowed: String,
    },
}

/// Why the work items collected from shards do not make up the study.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ItemError {
    /// An item names a variant or row the study does not have.
    #[error(
        "variant {variant}{} is outside the study ({variants} variant(s) of {ny} grid rows)",
        row.map_or(String::new(), |r| format!(" row {r}"))
    )]
    Outside {
        /// Variant id.
        variant: usize,
        /// Grid row (`None` for the metrics item).
        row: Option<usize>,
        /// Variants of the study.
        variants: usize,
        /// Grid rows of the study.
        ny: usize,
    },
    /// An item index past the end of the study.
    #[error("work item {item} is outside the study")]
    PastEnd {
        /// Work item index.
        item: usize,
    },
    /// The same item twice.
    #[error("work item {item} appears twice")]
    Twice {
        /// Work item index.
        item: usize,
    },
    /// A row of the wrong length.
    #[error("variant {variant} row {row} has {points} points, the grid has {nz} columns")]
    RowLength {
        /// Variant id.
        variant: usize,
        /// Grid row.
        row: usize,
        /// Points in the row.
        points: usize,
        /// Grid columns.
        nz: usize,
    },
    /// An item no shard holds.
    #[error("work item {item} (variant {variant}) is missing: are all shards given?")]
    Missing {
        /// Work item index.
        item: usize,
        /// Its variant.
        variant: usize,
    },
}

/// Everything besides the face maps: sensitivities and optimisation (written with the maps by
/// [`output::write_study`]).
pub fn finish(
    p: &Prepared,
    metrics: &[Vec<f64>],
) -> Result<
    (
        Vec<sensitivity::Sensitivity>,
        Option<optimise::OptimiseResult>,
    ),
    StudyError,
> {
    check_finite(p, metrics)?;
    let sens = sensitivity::sensitivities(p)?;
    let opt = optimise::optimise(p)?;
    Ok((sens, opt))
}

/// Every summary metric of every variant is finite (nothing infinite or undefined may reach an
/// output); the first that is not is an error naming the variant and the metric.
pub fn check_finite(p: &Prepared, metrics: &[Vec<f64>]) -> Result<(), StudyError> {
    let names = metrics::metric_names(p.study.distribution.is_some());
    for (id, (d, m)) in p.variants.iter().zip(metrics).enumerate() {
        if let Some(j) = m.iter().position(|v| !v.is_finite()) {
            let culprit =
                evaluate::culprit(&p.models[id], &p.study, &p.groups).unwrap_or_else(|| {
                    "it overflows; narrow [summary] half_width_mm or the [distribution]".to_owned()
                });
            return Err(StudyError::NotFinite {
                id,
                values: d.describe(),
                metric: names.get(j).cloned().unwrap_or_default(),
                culprit,
            });
        }
    }
    Ok(())
}
