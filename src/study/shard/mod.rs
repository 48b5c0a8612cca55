//! Shards: a part of a study's work list written to disk, and their merge.
//!
//! A shard folder holds `study.toml` (the resolved study, identical for every shard and for the
//! unsharded run), `shard.toml` (`shard`, `shards`, `first_item`, `end_item`), `rows.csv` (the
//! shard's grid rows: `variant,row,col,valid` and the five launch components in SI units) and
//! `metrics.csv` (`variant,metric,value`). `shard.toml` also records the SHA-256 of the resolved
//! study and of the club file; merge refuses shards that disagree, or that disagree with the
//! files as they are now, and checks every field it reads back. Values are written in their shortest round-trip
//! decimal form, so reading them back gives the same bits; invalid values are empty cells.

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::data::DataError;

use super::metrics::metric_names;
use super::output::{cell, Files};
use super::spec::resolved_toml;
use super::sweep::{ItemResult, Prepared};
use super::StudyError;

mod fields;
mod merge;
mod scratch;

pub use merge::merge_shards;
pub use scratch::DiskGrids;

const ROWS_HEADER: &str =
    "variant,row,col,valid,ball_speed_m_s,launch_angle_rad,azimuth_rad,backspin_rad_s,sidespin_rad_s";

/// A `--shard` value that is not `k/N` with `0 ≤ k < N` (the value as given).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "--shard '{0}': expected k/N with 0 ≤ k < N, e.g. 0/4 (k is 0-based, as $SLURM_ARRAY_TASK_ID)"
)]
pub struct ShardSpecError(pub String);

/// Parse `k/N` (0-based `k < N`).
pub fn parse_shard_spec(s: &str) -> Result<(usize, usize), ShardSpecError> {
    let err = || ShardSpecError(s.to_owned());
    let (a, b) = s.split_once('/').ok_or_else(err)?;
    let k: usize = a.trim().parse().map_err(|_| err())?;
    let n: usize = b.trim().parse().map_err(|_| err())?;
    if n == 0 || k >= n {
        return Err(err());
    }
    Ok((k, n))
}

/// SHA-256 of `bytes`, as 64 lowercase hex digits (what `sha256sum` prints).
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}

/// SHA-256 of the study's club file as it is now.
fn club_sha256(p: &Prepared) -> Result<String, StudyError> {
    let path = &p.study.club_path;
    crate::data::safe_write::note_input(path);
    let bytes = std::fs::read(path)
        .map_err(|e| DataError::file(path, format!("cannot read the study's club file: {e}")))?;
    Ok(sha256_hex(&bytes))
}

/// Files of shard `k` of `n` holding `items`. `shard.toml` records the SHA-256 of the resolved
/// study (`study.toml` as written) and of the club file, so that `smash merge` can prove the
/// shards belong together.
pub fn shard_files(
    p: &Prepared,
    k: usize,
    n: usize,
    items: &[ItemResult],
) -> Result<Files, StudyError> {
    let range = p.shard_range(k, n);
    let study = resolved_toml(&p.study);
    let mut meta = String::new();
    let _ = writeln!(
        meta,
        "# Shard of a study; merge all shards with `smash merge`."
    );
    let _ = writeln!(
        meta,
        "shard = {k}\nshards = {n}\nfirst_item = {}\nend_item = {}",
        range.start, range.end
    );
    let _ = writeln!(
        meta,
        "# SHA-256 of study.toml and of the club file it names (compare with `sha256sum`)."
    );
    let _ = writeln!(
        meta,
        "study_sha256 = \"{}\"\nclub_sha256 = \"{}\"",
        sha256_hex(study.as_bytes()),
        club_sha256(p)?
    );
    let mut rows = format!("{ROWS_HEADER}\n");
    let mut metrics = String::from("variant,metric,value\n");
    let names = metric_names(p.study.distribution.is_some());
    for it in items {
        match it {
            ItemResult::Row { variant, row, grid } => {
                for j in 0..grid.len() {
                    let _ = writeln!(
                        rows,
                        "{variant},{row},{j},{},{},{},{},{},{}",
                        u8::from(grid.valid[j]),
                        cell(grid.ball_speed_m_s[j]),
                        cell(grid.launch_angle_rad[j]),
                        cell(grid.azimuth_rad[j]),
                        cell(grid.backspin_rad_s[j]),
                        cell(grid.sidespin_rad_s[j]),
                    );
                }
            }
            ItemResult::Metrics { variant, values } => {
                for (name, v) in names.iter().zip(values) {
                    let _ = writeln!(metrics, "{variant},{name},{}", cell(*v));
                }
            }
        }
    }
    Ok(vec![
        ("study.toml".into(), study.into_bytes()),
        ("shard.toml".into(), meta.into_bytes()),
        ("rows.csv".into(), rows.into_bytes()),
        ("metrics.csv".into(), metrics.into_bytes()),
    ])
}

/// Which recorded hash two shards disagree on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hashed {
    /// The resolved study (`study.toml`).
    Study,
    /// The club file.
    Club,
}

impl std::fmt::Display for Hashed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Hashed::Study => "studies",
            Hashed::Club => "club files",
        })
    }
}

/// The first 12 hex digits of a SHA-256, as messages show it.
fn short(h: &str) -> &str {
    h.get(..12).unwrap_or(h)
}

/// Why shards do not fit together: which file (and line), and what mismatched.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MergeError {
    /// No shard folder was given.
    #[error("no shard folders given")]
    NoShards,
    /// Two shards record different hashes of the study or the club.
    #[error(
        "{} and {} were computed with different {what} (SHA-256 {}… and {}… in their \
         shard.toml); run all shards again with the same study and club",
        first.display(), other.display(), short(first_sha), short(other_sha)
    )]
    Differ {
        /// The first shard folder.
        first: PathBuf,
        /// The shard folder that differs from it.
        other: PathBuf,
        /// Which hash.
        what: Hashed,
        /// The first shard's hash.
        first_sha: String,
        /// The other's.
        other_sha: String,
    },
    /// A shard's `study.toml` is not the study its `shard.toml` records.
    #[error(
        "{}: study.toml is not the study its shard.toml records (edited after the run?); run \
         the shard again",
        dir.display()
    )]
    StudyEdited {
        /// The shard folder.
        dir: PathBuf,
    },
    /// The club file changed since the shards were computed.
    #[error(
        "the club file {} changed since the shards were computed (SHA-256 now {}…, in the \
         shards {}…); run the shards again",
        club.display(), short(now), short(recorded)
    )]
    ClubChanged {
        /// The club file.
        club: PathBuf,
        /// Its hash now.
        now: String,
        /// The hash the shards record.
        recorded: String,
    },
    /// A shard of a different split.
    #[error("{}: shard of {shards}, {} is of {expected}", file.display(), first.display())]
    ShardCount {
        /// Its `shard.toml`.
        file: PathBuf,
        /// Its `shards`.
        shards: usize,
        /// The first shard folder.
        first: PathBuf,
        /// The first shard's `shards`.
        expected: usize,
    },
    /// The same shard twice.
    #[error("shard {shard} is given twice ({})", dir.display())]
    Duplicate {
        /// Shard index.
        shard: usize,
        /// The second folder holding it.
        dir: PathBuf,
    },
    /// A shard's work items are not those of its index.
    #[error(
        "{}: work items {first_item}..{end_item} are not those of shard {shard} of {shards} \
         ({}..{})",
        file.display(), expected.0, expected.1
    )]
    WrongItems {
        /// Its `shard.toml`.
        file: PathBuf,
        /// Recorded first item.
        first_item: usize,
        /// Recorded end item.
        end_item: usize,
        /// Shard index.
        shard: usize,
        /// Shards.
        shards: usize,
        /// The items of that shard.
        expected: (u128, u128),
    },
    /// A grid row with too few points.
    #[error(
        "{}:{line}: variant {variant} row {row} has {points} of {nz} points",
        file.display()
    )]
    ShortRow {
        /// The `rows.csv`.
        file: PathBuf,
        /// Line of the row's last point.
        line: u64,
        /// Variant id.
        variant: usize,
        /// Grid row.
        row: usize,
        /// Points given.
        points: usize,
        /// Grid columns.
        nz: usize,
    },
    /// A work item given twice (in this or an earlier shard).
    #[error("{}:{line}: work item {item} appears twice", file.display())]
    ItemTwice {
        /// The file holding the second copy.
        file: PathBuf,
        /// Its line.
        line: u64,
        /// Work item index.
        item: usize,
    },
    /// A variant with too few metrics.
    #[error("{}: variant {variant} has {got} of {expected} metrics", file.display())]
    MetricCount {
        /// The `metrics.csv`.
        file: PathBuf,
        /// Variant id.
        variant: usize,
        /// Metrics given.
        got: usize,
        /// The study's metrics.
        expected: usize,
    },
    /// Shards not given (the first ten).
    #[error(
        "shards {}{} of {shards} are missing",
        missing.iter().map(usize::to_string).collect::<Vec<_>>().join(", "),
        if *more { ", …" } else { "" }
    )]
    MissingShards {
        /// Missing shard indices (at most ten).
        missing: Vec<usize>,
        /// Whether more are missing.
        more: bool,
        /// Shards of the study.
        shards: usize,
    },
    /// A work item no shard holds.
    #[error("work item {item} (variant {variant}) is missing: are all shards given?")]
    MissingItem {
        /// Work item index.
        item: usize,
        /// Its variant.
        variant: usize,
    },
    /// The study is larger than a merge takes.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::CapError),
}

/// A sharded study may have at most [`super::MAX_MERGE_POINTS`] grid points.
pub fn check_mergeable(p: &Prepared) -> Result<(), StudyError> {
    crate::limits::count_product(
        "grid points of a sharded study",
        &[
            ("design variants", p.variants.len()),
            ("grid rows", p.ys_mm.len()),
            ("grid columns", p.zs_mm.len()),
        ],
        super::MAX_MERGE_POINTS as usize,
        "a merge's time and disk grow with the study; use a coarser [grid] or fewer [design] \
         values",
    )
    .map(|_| ())
    .map_err(|e| StudyError::Merge(MergeError::TooLarge(e)))
}
