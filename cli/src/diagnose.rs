//! `smash diagnose`: which effects does the data ask for? Forward selection with grouped
//! cross-validation (see [`smash::diagnose`]).
//!
//! Size: the command's arguments, its JSON and its text report read the same `Diagnosis` and
//! must stay in step (every field in both forms); the text report is split by section.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use indicatif::ProgressBar;
use serde_json::json;

use smash::data::club_file::{club_toml_checked, read_club};
use smash::data::noise_file::read_noise_file;
use smash::data::output_plan::OutputPlan;
use smash::data::shots::ShotTable;
use smash::diagnose::honest;
use smash::diagnose::noise_floor::{noise_floor, InstrumentClass, NoiseFloor, SpreadBand};
use smash::diagnose::{
    diagnose, DiagnoseOptions, DiagnoseProgress, Diagnosis, DEFAULT_IMPACT_NOISE_CANDIDATES_MM,
};
use smash::fit::{parse_effect_list, FitError, ParamEstimate};
use smash::physics::LaunchComponent;
use smash::ClubSpec;

use super::progress::job_bar;

pub mod text;

/// Arguments of `smash diagnose`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    smash diagnose --club configs/clubs/paper_driver.toml --shots shots.csv\n  \
    smash diagnose --club club.toml --shots shots.csv --json --out-club diagnosed.toml")]
pub struct DiagnoseArgs {
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Club file (TOML); its own [[effect]] tables stay fixed.
    #[arg(long, value_name = "CLUB.toml")]
    pub club: PathBuf,

    /// Shots file (CSV) with measured launch columns (and a golfer column for grouped folds).
    #[arg(long, value_name = "SHOTS.csv")]
    pub shots: PathBuf,

    /// Format of --shots (a launch-monitor export is converted on the fly).
    #[command(flatten)]
    pub shots_format: super::ShotsFormatArgs,

    /// Write a self-contained HTML report (gains per candidate and step, errors before and after,
    /// estimates with their plausible ranges).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,

    /// Write the club with the selected effects, only after success.
    #[arg(long, value_name = "OUT.toml")]
    pub out_club: Option<PathBuf>,

    /// Print one JSON object on stdout (progress and prose go to stderr).
    #[arg(long)]
    pub json: bool,

    /// `--wide`: the full candidate and noise-floor tables.
    #[command(flatten)]
    pub wide: crate::text::WideArgs,

    /// Cross-validation folds (grouped by golfer).
    #[arg(
        long,
        default_value_t = 5,
        value_name = "K",
        help_heading = "Selection",
        allow_negative_numbers = true
    )]
    pub folds: usize,

    /// Most effects to select.
    #[arg(
        long,
        default_value_t = 10,
        value_name = "N",
        help_heading = "Selection",
        allow_negative_numbers = true
    )]
    pub max_steps: usize,

    /// Candidates (default: every library effect, plus added_mass@group and
    /// hosel_mass@group), same syntax as calibrate --effects.
    #[arg(long, value_name = "LIST", help_heading = "Selection")]
    pub candidates: Option<String>,

    /// Every default candidate except these (e.g. face_curvature,added_mass@group): what
    /// diagnose concludes when the library lacks them.
    #[arg(
        long,
        value_name = "LIST",
        help_heading = "Selection",
        conflicts_with = "candidates"
    )]
    pub without: Option<String>,

    /// Iteration limit of each fit.
    #[arg(
        long,
        default_value_t = 100,
        value_name = "N",
        help_heading = "Selection",
        allow_negative_numbers = true
    )]
    pub max_iters: u64,

    /// Measurement noise of the inputs. Without --impact-noise-mm, impact-location noise of
    /// 1, 1.5, 2 and 3 mm is offered as a candidate beside the effects.
    #[command(flatten)]
    pub measurement: super::MeasurementArgs,

    /// What to do when the shots do not match the club.
    #[command(flatten)]
    pub club_check: super::ClubCheckArgs,

    /// Take the measured impact locations as exact (offer no impact-noise candidate).
    #[arg(
        long,
        conflicts_with = "impact_noise_mm",
        help_heading = "Measurement noise"
    )]
    pub exact_impact_locations: bool,

    /// Instrument class whose documented noise sets the noise floor (camera: camera launch
    /// monitor with marker-based delivery capture; radar: Doppler launch monitor).
    /// Given (or with --noise), selection also stops once the errors are at the noise floor;
    /// without either, the floor is reported for the camera class and only the penalty stops.
    #[arg(
        long,
        value_name = "CLASS",
        value_parser = super::likelihood::parse_instrument,
        help_heading = "Noise floor"
    )]
    pub instrument: Option<InstrumentClass>,

    /// Instrument noise file ([noise] table: instrument, [noise.delivery], [noise.launch]);
    /// overrides --instrument.
    #[arg(long, value_name = "NOISE.toml", help_heading = "Noise floor")]
    pub noise: Option<PathBuf>,
}

/// An impact-location noise in mm as printed: to 1e-6 mm, so that 1.8 mm shows as 1.8 after
/// the metre round trip.
pub(crate) fn location_mm(m: f64) -> f64 {
    (m * 1e9).round() / 1e6
}

struct Bar(ProgressBar);

impl DiagnoseProgress for Bar {
    fn step(&self, step: usize, jobs: usize) {
        self.0.set_length(jobs as u64);
        self.0.set_position(0);
        self.0.set_message(format!("fits of step {step}"));
    }
    fn job_done(&self) {
        self.0.inc(1);
    }
}

/// Run `smash diagnose`.
pub fn run(args: DiagnoseArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    let mut inputs = vec![("--club", args.club.as_path()), ("--shots", &args.shots)];
    if let Some(noise) = &args.noise {
        inputs.push(("--noise", noise));
    }
    let plan = OutputPlan::new(&inputs)
        .file("--out-club", args.out_club.as_deref())
        .file("--report", args.report.as_deref());
    plan.check()?;
    let club = read_club(&args.club)?;
    let mut table = args.shots_format.read(&args.shots)?;
    plan.check()?; // again: a `--format` mapping file is an input known once read
    let conventions = super::to_model_convention(&club, &mut table, args.json, true)?;
    super::warn_groups_without_effects(&args.club, &club, &table.shots);
    let bar = Bar(job_bar(1, "fits"));
    let result = compute(&args, &club, &table, Some(&bar));
    bar.0.finish_and_clear();
    let (d, floor) = result?;
    for w in &d.warnings {
        eprintln!("warning: {}", smash::data::escape(w));
    }
    let mut staging = plan.stage();
    if let Some(out) = &args.out_club {
        let comment = format!(
            "Club with the effects selected by smash diagnose on {} ({} shots): {}",
            args.shots.display(),
            d.n_shots,
            if d.selected.is_empty() {
                "none".to_owned()
            } else {
                d.selected.join(", ")
            }
        );
        staging.file(out, club_toml_checked(&d.club, &comment, out)?.as_bytes())?;
    }
    if let Some(path) = &args.report {
        let title = format!("{} on {}", club.name, args.shots.display());
        let html = smash::report::html::diagnose_page(&to_json(&d, &floor), &title)
            .map_err(anyhow::Error::msg)?;
        staging.file(path, html.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("club with selected effects -> {}", out.display());
    }
    if let Some(path) = &args.report {
        eprintln!("report -> {}", path.display());
    }
    if args.json {
        crate::stdout::println(serde_json::to_string_pretty(&to_json(&d, &floor))?)?;
    } else {
        let layout = text::Layout::of(&args);
        let text = text::text_report(&d, &floor, &layout);
        crate::stdout::print(format!("{conventions}{text}"))?;
    }
    Ok(())
}

/// The diagnosis of `table` with `club` under `args`' options (its `--club` and `--shots` only
/// name them in messages) and its noise floor; `progress` sees the fits. What `run` reports.
pub fn compute(
    args: &DiagnoseArgs,
    club: &ClubSpec,
    table: &ShotTable,
    progress: Option<&dyn DiagnoseProgress>,
) -> anyhow::Result<(Diagnosis, NoiseFloor)> {
    let mismatch = args
        .club_check
        .check(&args.club, club, &args.shots, &table.shots)?;
    let known_noise = match (&args.noise, args.instrument) {
        (Some(p), _) => Some(read_noise_file(p)?),
        (None, Some(c)) => Some(c.noise()),
        (None, None) => None,
    };
    let assumed = known_noise.is_none();
    let instrument = known_noise
        .clone()
        .unwrap_or_else(|| InstrumentClass::Camera.noise());
    if !table.has_measurements() {
        return Err(FitError::NoMeasurements).context(args.shots.display().to_string());
    }
    if args.folds < 2 {
        anyhow::bail!("--folds must be at least 2, got {}", args.folds);
    }
    let candidates = match (&args.candidates, &args.without) {
        (Some(list), _) => Some(parse_effect_list(list)?),
        (None, Some(list)) => Some(
            smash::diagnose::default_candidates_without(&table.shots, &parse_effect_list(list)?)
                .context("--without")?,
        ),
        (None, None) => None,
    };
    let opts = DiagnoseOptions {
        folds: args.folds,
        max_steps: args.max_steps,
        max_iters: args.max_iters,
        candidates,
        impact_noise: args.measurement.impact_noise_mm,
        impact_noise_candidates_mm: if args.exact_impact_locations {
            Vec::new()
        } else {
            DEFAULT_IMPACT_NOISE_CANDIDATES_MM.to_vec()
        },
        noise_floor: known_noise,
        // Without golfers, whole sessions (dates), time blocks or clubs form the folds.
        fold_keys: smash::data::sessions::fold_keys(table, args.folds)?,
        ..DiagnoseOptions::default()
    };
    let mut d = diagnose(club, &table.shots, &opts, progress)
        .with_context(|| args.shots.display().to_string())?;
    d.club_mismatch = mismatch;
    let mut floor = noise_floor(&d, &table.shots, &instrument)?;
    floor.assumed = assumed;
    d.shared_signals = smash::diagnose::shared::shared_signals(&d, &table.shots, &floor)?;
    Ok((d, floor))
}

fn estimates_json(ps: &[ParamEstimate]) -> Vec<serde_json::Value> {
    estimates_json_with(ps, |_| None)
}

/// Estimates as JSON, each with its plausibility and (when `status` says) its status.
fn estimates_json_with(
    ps: &[ParamEstimate],
    status: impl Fn(&ParamEstimate) -> Option<&'static str>,
) -> Vec<serde_json::Value> {
    ps.iter()
        .map(|p| {
            let mut v = json!({
                "effect": p.effect, "param": p.param, "group": p.group,
                "value": p.value, "stderr": p.stderr, "unit": p.unit,
            });
            if let (Some(o), serde_json::Value::Object(h)) =
                (v.as_object_mut(), honest::plausibility_json(p))
            {
                o.extend(h);
                if let Some(st) = status(p) {
                    o.insert("status".into(), st.into());
                }
            }
            v
        })
        .collect()
}

/// `finding`, `stand_in`, `absent` (on its no-effect bound), `unchanged` (not significantly
/// different from its no-effect value), `provisional` (its value differs
/// across strata of the shots) or `ambiguous` (a plausible value with a plausible rival, or
/// aliased with another effect).
fn status(d: &Diagnosis, p: &ParamEstimate) -> &'static str {
    if d.club_mismatch.is_some() {
        "wrong_club"
    } else if honest::is_plausible(p) == Some(false) {
        "stand_in"
    } else if honest::is_absent(p) {
        "absent"
    } else if honest::is_unchanged(p, d.estimates.len()) {
        "unchanged"
    } else if d.is_finding(p) {
        "finding"
    } else if d.provisional(p).is_some() {
        "provisional"
    } else {
        "ambiguous"
    }
}

/// The machine-readable report.
pub fn to_json(d: &Diagnosis, floor: &NoiseFloor) -> serde_json::Value {
    let comp_map = |v: &[f64; 5]| -> serde_json::Value {
        LaunchComponent::ALL
            .iter()
            .map(|c| (c.column().to_owned(), json!(v[c.index()])))
            .collect::<serde_json::Map<_, _>>()
            .into()
    };
    let steps: Vec<serde_json::Value> = d
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| {
            json!({
                "step": i + 1,
                "base": s.base,
                "noise_scales": comp_map(&s.noise_scales),
                "base_cv_chi2": s.base_cv_chi2,
                "selected": s.selected,
                "swap": s.swap.as_ref().map(|w| json!({
                    "out": w.out,
                    "in": w.inn,
                    "cv_chi2_before": w.cv_before,
                    "cv_chi2_after": w.cv_after,
                    "text": w.text(),
                })),
                "at_noise_floor": s.at_noise_floor,
                "alias": s.alias.as_ref().map(|a| a.to_json()),
                "rivals": s.rivals.iter().map(honest::Rival::to_json).collect::<Vec<_>>(),
                "candidates": s.candidates.iter().map(|c| json!({
                    "effect": c.label,
                    "n_params": c.n_params,
                    "cv_chi2": c.cv_chi2,
                    "gain": c.gain,
                    "score": if c.spread_gain.is_some() { "spread_likelihood" } else { "cv_chi2" },
                    "penalty": c.penalty,
                    "margin": c.margin(),
                    "eligible": c.eligible(),
                    "converged": c.converged,
                    "unidentified": c.unidentified,
                    "failure": c.failure,
                    "rms_reduction": comp_map(&c.rms_reduction),
                    "params": estimates_json(&c.params),
                })).collect::<Vec<_>>(),
                "after": s.after.to_json(),
                "fit": crate::likelihood::score_json(&s.fit),
            })
        })
        .collect();
    json!({
        "command": "diagnose",
        "selected": d.selected,
        "impact_noise_mm": d.impact_noise.map(|n| json!({
            "y": location_mm(n.sigma_y_m),
            "z": location_mm(n.sigma_z_m),
            "estimated": d.impact_noise_estimated,
        })),
        "delivery_noise": d.delivery_noise.filter(|n| n.is_active()).map(|n| json!({
            "sd": crate::delivery_noise::to_json(&n),
            "estimated": d.delivery_noise_estimated,
        })),
        "calibrate_flags": calibrate_flags(d),
        "estimates": estimates_json_with(&d.estimates, |p| Some(status(d, p))),
        "findings": d.estimates.iter().filter(|p| d.is_finding(p)).map(|p| p.label()).collect::<Vec<_>>(),
        "provisional": d.estimates.iter().filter_map(|p| d.provisional(p).map(|why| json!({
            "param": p.label(), "failed_check": why,
        }))).collect::<Vec<_>>(),
        "strata": d.strata.as_ref().map(crate::strata::to_json),
        "ambiguous": d.ambiguities.iter().map(honest::Ambiguity::to_json).collect::<Vec<_>>(),
        "stand_ins": d.estimates.iter().filter_map(|p| honest::stand_in(p).map(|w| json!({
            "param": p.label(), "value": p.value, "unit": p.unit,
            "plausible_range": honest::plausible_range_text(p), "behaves_like": w,
            "most_alike": d.alike(p).iter().map(|(l, r)| json!({"candidate": l, "r": r}))
                .collect::<Vec<_>>(),
        }))).collect::<Vec<_>>(),
        "aliases": d.aliases.iter().map(honest::Alias::to_json).collect::<Vec<_>>(),
        "likelihood": crate::likelihood::to_json("final", &d.final_fit, &d.nominal_fit),
        "noise_floor": floor.to_json(),
        "conclusion": conclusion(d, floor),
        "steps": steps,
        "folds": d.folds,
        "fold_by": d.fold_by.name(),
        "club_mismatch": d.club_mismatch,
        "n_shots": d.n_shots,
        "warnings": d.warnings,
        "before": d.before.to_json(),
        "after": d.after.to_json(),
    })
}

/// What the diagnosis concludes about the structure left in the errors, and, when the
/// instrument noise was assumed, what the verdict rests on ([`assumed_note`]).
pub fn conclusion(d: &Diagnosis, floor: &NoiseFloor) -> String {
    format!("{}{}", verdict(d, floor), assumed_note(floor))
}

/// Without `--noise` or `--instrument`: the verdict rests on the assumed class's noise; the
/// observed-to-expected spread ratio per component, and what a ratio well below or well above
/// 1 means (empty when the noise was given).
fn assumed_note(floor: &NoiseFloor) -> String {
    if !floor.assumed {
        return String::new();
    }
    let ratios: Vec<String> = floor
        .components
        .iter()
        .map(|c| format!("{} {:.2}", c.component.column(), c.ratio))
        .collect();
    let band = |b: SpreadBand| -> Vec<&str> {
        floor
            .components
            .iter()
            .filter(|c| floor.spread_band(c) == b)
            .map(|c| c.component.column())
            .collect()
    };
    let h = floor.band_half_width();
    let mut s = format!(
        ". This verdict rests on the ASSUMED {} instrument noise (no --noise or --instrument \
         given); observed/expected spread: {}",
        floor.instrument.name,
        ratios.join(", ")
    );
    let below = band(SpreadBand::WellBelow);
    if !below.is_empty() {
        s.push_str(&format!(
            "; well below 1 (under {:.2}) in {}: the assumed noise is too large for these \
             errors, so the test cannot see structure there",
            1.0 - h,
            below.join(", ")
        ));
    }
    let above = band(SpreadBand::WellAbove);
    if !above.is_empty() {
        s.push_str(&format!(
            "; well above 1 (over {:.2}) in {}: structure remains there, or the instruments \
             are noisier than assumed",
            1.0 + h,
            above.join(", ")
        ));
    }
    if below.is_empty() && above.is_empty() {
        s.push_str(&format!("; each within {h:.2} of 1"));
    }
    s.push_str("; give the instruments' noise with --noise to test it");
    s
}

/// The verdict on the structure left in the errors.
fn verdict(d: &Diagnosis, floor: &NoiseFloor) -> String {
    let stand_ins: Vec<String> = d
        .estimates
        .iter()
        .filter(|p| honest::is_plausible(p) == Some(false))
        .map(|p| p.label())
        .collect();
    let mut stand_in_note = String::new();
    if !stand_ins.is_empty() {
        stand_in_note = format!(
            "; {} stand(s) in for physics the library lacks and is not a finding",
            stand_ins.join(", ")
        );
    }
    // Each kind of value that is not a finding, with why, when there is any.
    let mut not_findings = |why: &str, labels: Vec<String>, sep: &str| {
        if !labels.is_empty() {
            stand_in_note.push_str(&format!("; {why}: {}", labels.join(sep)));
        }
    };
    not_findings(
        "ambiguous, not findings (each has a plausible alternative the data cannot tell apart \
         from it)",
        d.ambiguities
            .iter()
            .filter(|a| a.is_ambiguous())
            .map(|a| a.selected.clone())
            .collect(),
        ", ",
    );
    not_findings(
        "aliased, not findings (the data cannot tell which effect carries the signal)",
        d.aliases
            .iter()
            .filter(|a| a.across_effects())
            .map(|a| format!("{} and {}", a.a, a.b))
            .collect(),
        "; ",
    );
    not_findings(
        "provisional, not findings (the value differs between parts of the shots beyond its \
         uncertainty, or its signal shares the trend of structure left)",
        d.estimates
            .iter()
            .filter(|p| d.provisional(p).is_some())
            .map(|p| p.label())
            .collect(),
        ", ",
    );
    if !floor.structure_remains() {
        return format!(
            "what remains is noise: the errors scatter as the instruments alone explain{stand_in_note}"
        );
    }
    let structured: Vec<&str> = floor
        .components
        .iter()
        .filter(|c| c.structure)
        .map(|c| c.component.column())
        .collect();
    // The last forward step (swap steps follow forward selection).
    let last = d.steps.iter().rfind(|s| s.swap.is_none());
    let stopped_by_limit = last.is_none_or(|s| s.selected.is_some());
    if stopped_by_limit {
        format!(
            "unexplained structure remains in {}, and the step limit was reached: raise \
             --max-steps to keep looking{stand_in_note}",
            structured.join(", ")
        )
    } else {
        let best = last
            .and_then(|s| s.candidates.first())
            .map_or(String::new(), |c| {
                format!(" (best: {}, margin {:.1})", c.label, c.margin())
            });
        format!(
            "unexplained structure remains in {}; no library candidate reduces it by more than \
             its penalty{best}: the data contain physics the library lacks (or the instrument \
             noise given is too small){stand_in_note}",
            structured.join(", ")
        )
    }
}

/// The `smash calibrate` flags that fit the diagnosis's final model (its effects and its
/// measurement model), each with its value.
pub(crate) fn calibrate_flag_pairs(d: &Diagnosis) -> Vec<(&'static str, String)> {
    let mut flags = Vec::new();
    if !d.selected.is_empty() {
        flags.push(("--effects", d.selected.join(",")));
    }
    if let Some(n) = d.impact_noise {
        flags.push((
            "--impact-noise-mm",
            format!("{},{}", location_mm(n.sigma_y_m), location_mm(n.sigma_z_m)),
        ));
    }
    if let Some(spec) = d
        .delivery_noise
        .as_ref()
        .and_then(crate::delivery_noise::spec)
    {
        flags.push(("--delivery-noise", spec));
    }
    flags
}

/// [`calibrate_flag_pairs`] as one string (JSON's `calibrate_flags`).
fn calibrate_flags(d: &Diagnosis) -> String {
    calibrate_flag_pairs(d)
        .into_iter()
        .map(|(f, v)| format!("{f} {v}"))
        .collect::<Vec<_>>()
        .join(" ")
}
