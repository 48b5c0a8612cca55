//! Study files (TOML): what to sweep, summarise, differentiate and optimise.
//!
//! The format is documented in `configs/README.md` ("Design studies"). Parsing is strict:
//! unknown keys, wrong types and unphysical values are errors naming the file, line, key and
//! what is allowed (through the one validator, [`crate::data::TomlDoc`]). One file per section
//! of the study file; this one holds the resolved [`Study`], the loading step (the only I/O:
//! the study and its club file) and the whole-study limits. [`resolved_toml`] writes the
//! resolved study back (by serde, from the same raw structs the parser reads) as a study file
//! that parses to the same [`Study`], so a run can be repeated from the `study.toml` written
//! beside its outputs.

mod axis;
mod delivery;
mod design;
mod distribution;
mod header;
mod optimise;
mod sensitivity;
mod summary;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use toml::Spanned;

pub use axis::Axis;
pub use design::{DesignSpace, Grid};
pub use optimise::{Goal, OptimiseSpec};
pub use summary::Probe;

use super::design::DesignVar;
use super::distribution::{Distribution, SwingSpec};
use super::metrics::Output;
use crate::club::ClubSpec;
use crate::data::club_file::read_club;
use crate::data::{read_text, DataError, TomlDoc};
use crate::limits::{self, count_product};

/// A resolved study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Name (also the default output folder `results/<name>`).
    pub name: String,
    /// Base club file, absolute.
    pub club_path: PathBuf,
    /// The base club.
    pub club: ClubSpec,
    /// Group whose effects apply.
    pub group: String,
    /// Outputs to map.
    pub outputs: Vec<Output>,
    /// Output folder (relative to the working directory unless absolute).
    pub output_dir: PathBuf,
    /// The fixed swing used for the maps and summaries.
    pub swing: SwingSpec,
    /// Distribution of swings and impact locations, for `mean_*` and `std_*` metrics.
    pub distribution: Option<Distribution>,
    /// The face grid.
    pub grid: Grid,
    /// Design variants.
    pub design: DesignSpace,
    /// Sensitivities: variables and central-difference steps.
    pub sensitivity: Option<Vec<(DesignVar, f64)>>,
    /// Probe lines of the summaries.
    pub probe: Probe,
    /// Optimisation.
    pub optimise: Option<OptimiseSpec>,
    /// The study in yards (`[yards]`, see [`super::yards_spec`]).
    pub yards: Option<super::yards_spec::YardsSpec>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    study: header::RawHeader,
    delivery: delivery::RawDelivery,
    distribution: Option<Spanned<distribution::RawDistribution>>,
    grid: design::RawGrid,
    design: Option<design::RawDesign>,
    sensitivity: Option<Spanned<sensitivity::RawSensitivity>>,
    summary: Option<summary::RawSummary>,
    optimise: Option<Spanned<optimise::RawOptimise>>,
    /// Parsed on its own by [`super::yards_spec`].
    yards: Option<toml::Value>,
}

const LAYOUT: &str = "a study file has [study], [delivery], [grid] and optional [distribution], \
                      [design], [sensitivity], [summary], [optimise], [yards]; see \
                      configs/README.md";

/// Defaults, in one place.
pub mod defaults {
    /// Group.
    pub const GROUP: &str = "all";
    /// Quadrature nodes per dimension.
    pub const NODES: usize = 5;
    /// Samples.
    pub const SAMPLES: usize = 256;
    /// Random seed.
    pub const SEED: u64 = 1;
    /// Probe half-width, mm.
    pub const HALF_WIDTH_MM: f64 = 20.0;
    /// Probe step, mm.
    pub const STEP_MM: f64 = 2.0;
    /// Optimiser iterations.
    pub const MAX_ITERS: u64 = 200;
    /// Optimiser tolerance (objective units).
    pub const TOLERANCE: f64 = 1e-6;
    /// Largest number of impacts per quadrature distribution.
    pub const MAX_QUADRATURE_POINTS: usize = crate::limits::MAX_QUADRATURE_POINTS;
}

/// Read and resolve a study file. The club path is relative to the study file.
pub fn read_study(path: &Path) -> Result<Study, DataError> {
    let text = read_text(path)?;
    parse_study(path, &text)
}

/// Parse and resolve study text (`path` locates the club and names the file in messages). The
/// club file is the one thing read here; everything after [`load_club`] is pure.
pub fn parse_study(path: &Path, text: &str) -> Result<Study, DataError> {
    let doc = TomlDoc::new(path, text);
    let raw: RawStudy = doc.parse(LAYOUT)?;
    let h = header::parse_header(&doc, &raw.study)?;
    let (club_path, club) = load_club(&doc, &raw.study)?;
    club.check_group(&h.group).map_err(|m| {
        let span = raw.study.group.as_ref().map_or(0..0, |g| g.span());
        doc.err(span, "study.group", m)
    })?;
    let study = Study {
        name: h.name,
        club_path,
        club,
        group: h.group,
        outputs: h.outputs,
        output_dir: h.output_dir,
        swing: delivery::parse_delivery(&doc, &raw.delivery)?,
        distribution: None,
        grid: design::parse_grid(&doc, &raw.grid)?,
        design: DesignSpace {
            axes: Vec::new(),
            discretionary_mass: None,
        },
        sensitivity: None,
        probe: Probe {
            half_width_mm: defaults::HALF_WIDTH_MM,
            step_mm: defaults::STEP_MM,
        },
        optimise: None,
        yards: None,
    };
    resolve(&doc, &raw, study)
}

/// The club file `study.club` names (canonical path, parsed club).
fn load_club(doc: &TomlDoc<'_>, h: &header::RawHeader) -> Result<(PathBuf, ClubSpec), DataError> {
    let club_file = header::club_file(doc.path, h);
    let club_path = std::fs::canonicalize(&club_file).map_err(|e| {
        doc.err(
            h.club.span(),
            "study.club",
            format!(
                "cannot open club file {}: {e} (paths are relative to the study file)",
                club_file.display()
            ),
        )
    })?;
    let club = read_club(&club_path)?;
    Ok((club_path, club))
}

/// The sections that depend on others (the club, the distribution, the design), in file order.
fn resolve(doc: &TomlDoc<'_>, raw: &RawStudy, mut s: Study) -> Result<Study, DataError> {
    s.distribution = raw
        .distribution
        .as_ref()
        .map(|d| distribution::parse_distribution(doc, d))
        .transpose()?;
    s.design = design::parse_design(doc, raw.design.as_ref(), &s.club)?;
    let (n_variants, n_points) = sweep_size(doc, &s.grid, &s.design)?;
    s.sensitivity = raw
        .sensitivity
        .as_ref()
        .map(|r| sensitivity::parse_sensitivity(doc, r, &s.design))
        .transpose()?;
    s.probe = summary::parse_summary(doc, raw.summary.as_ref(), &s.club, &s.club_path)?;
    check_impacts(doc, &s, n_variants, n_points)?;
    let has_distribution = s.distribution.is_some();
    let mass = s.design.discretionary_mass.as_ref();
    s.optimise = raw
        .optimise
        .as_ref()
        .map(|o| optimise::parse_optimise(doc, o.get_ref(), has_distribution, mass))
        .transpose()?;
    s.yards = super::yards_spec::parse_yards(doc.path, doc.text, &s.club, has_distribution)?;
    Ok(s)
}

/// Design variants and grid points (variants × rows × columns), each within its cap.
fn sweep_size(
    doc: &TomlDoc<'_>,
    grid: &Grid,
    design: &DesignSpace,
) -> Result<(usize, usize), DataError> {
    let axis_counts: Vec<(&str, usize)> = design
        .axes
        .iter()
        .map(|(v, a)| (v.key(), a.len()))
        .collect();
    let n_variants = count_product(
        "design variants",
        &axis_counts,
        limits::MAX_DESIGN_VARIANTS,
        "use fewer [design] values",
    )
    .map_err(|e| doc.whole("design", e.to_string()))?;
    let n_points = count_product(
        "grid points",
        &[
            ("design variants", n_variants),
            ("grid.y_mm values", grid.y_mm.len()),
            ("grid.z_mm values", grid.z_mm.len()),
        ],
        super::MAX_SWEEP_POINTS as usize,
        "a run's time and disk grow with it; use a coarser [grid] or fewer [design] values",
    )
    .map_err(|e| doc.whole("grid", e.to_string()))?;
    Ok((n_variants, n_points))
}

/// All impacts of the study (grid, probe lines and distribution points of every variant)
/// within [`limits::MAX_STUDY_IMPACTS`].
fn check_impacts(
    doc: &TomlDoc<'_>,
    s: &Study,
    n_variants: usize,
    n_points: usize,
) -> Result<(), DataError> {
    let per_variant = limits::count_sum(
        "impacts per design variant",
        &[
            ("grid points", n_points / n_variants.max(1)),
            ("summary probes", 4 * s.probe.points()),
            (
                "distribution points",
                s.distribution.as_ref().map_or(0, |d| d.point_count()),
            ),
        ],
        limits::MAX_STUDY_IMPACTS,
        "",
    )
    .map_err(|e| doc.whole("grid", e.to_string()))?;
    count_product(
        "impact evaluations",
        &[
            ("design variants", n_variants),
            ("impacts per variant", per_variant),
        ],
        limits::MAX_STUDY_IMPACTS,
        "use fewer [design] values, a coarser [grid] or fewer distribution points",
    )
    .map_err(|e| doc.whole("design", e.to_string()))?;
    Ok(())
}

/// The resolved study as a study file: every default written out. Parses back to the same study.
pub fn resolved_toml(s: &Study) -> String {
    let text = |x: &str| Spanned::new(0..0, x.to_owned());
    let raw = RawStudy {
        study: header::RawHeader {
            name: text(&s.name),
            club: text(&s.club_path.to_string_lossy()),
            group: Some(text(&s.group)),
            outputs: Some(s.outputs.iter().map(|o| text(o.column())).collect()),
            output_dir: Some(s.output_dir.to_string_lossy().into_owned()),
        },
        delivery: delivery::raw_delivery(&s.swing),
        distribution: s
            .distribution
            .as_ref()
            .map(|d| Spanned::new(0..0, distribution::raw_distribution(d))),
        grid: design::raw_grid(&s.grid),
        design: design::raw_design(&s.design),
        sensitivity: s
            .sensitivity
            .as_ref()
            .map(|v| Spanned::new(0..0, sensitivity::raw_sensitivity(v))),
        summary: Some(summary::raw_summary(&s.probe)),
        optimise: s
            .optimise
            .as_ref()
            .map(|o| Spanned::new(0..0, optimise::raw_optimise(o))),
        yards: s.yards.as_ref().map(super::yards_spec::yards_value),
    };
    let body = toml::to_string(&raw).expect("a resolved study is plain TOML data");
    format!(
        "# Resolved study: every default filled in. `smash run` on this file repeats the run.\n\
         {body}"
    )
}
