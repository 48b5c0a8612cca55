//! `smash calibrate`: fit named effects to measured launch conditions.

use std::path::PathBuf;
use std::sync::Arc;

use clap::{Args, ValueEnum};

use smash::app::calibrate::CalibrateSettings;
use smash::app::inputs::{prepare_table, NamedClub, Prepared};
use smash::data::club_file::club_toml_checked;
use smash::fit::Method;
use smash::report::render::{CalibrateContext, Render};

use super::progress::IterationLine;

/// Fitting procedure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Whitened Levenberg-Marquardt on all five launch components (noise scales estimated
    /// from the data, re-estimated after a first fit).
    Lm,
    /// The paper's procedure: cost of its Eq. 11, alternating W = inf (velocity) and W = 0
    /// (spin) stages, each parameter in the stage where it is more sensitive.
    Paper,
}

/// Arguments of `smash calibrate`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    smash calibrate --club configs/clubs/paper_driver.toml --shots shots.csv \\\n      \
    --effects added_mass@group,ball_offset --out-club calibrated.toml\n  \
    smash calibrate --club club.toml --shots shots.csv --effects added_mass@A --method paper --json")]
pub struct CalibrateArgs {
    /// Club, shots, measurement noise, report formats.
    #[command(flatten)]
    pub inputs: crate::measured::MeasuredArgs,

    /// Effects to fit, comma-separated: `name` (global), `name@group` (one per group of the
    /// shots), `name@A` (group A only).
    #[arg(long, value_name = "LIST")]
    pub effects: String,

    /// Fitting procedure.
    #[arg(long, value_enum, default_value = "lm")]
    pub method: MethodArg,

    /// Write the calibrated club (club TOML with [[effect]] tables), only after success.
    #[arg(long, value_name = "OUT.toml")]
    pub out_club: Option<PathBuf>,

    /// Iteration limit of each solver run.
    #[arg(
        long,
        default_value_t = 100,
        value_name = "N",
        help_heading = "Solver",
        allow_negative_numbers = true,
        value_parser = crate::parse_iterations
    )]
    pub max_iters: u64,

    /// 1σ noise of the measured delivery variables other than the impact location: the model
    /// is then evaluated at each shot's expected true delivery given all the shots' measured
    /// ones and golfers (regression calibration). An instrument class (camera, radar) or a
    /// multiple of one (2xcamera), and/or column=SD entries in the shots file's units (e.g.
    /// club_speed_mph=0.8,dynamic_loft_deg=1); variables not named are exact. `smash diagnose`
    /// prints the value it selected.
    #[arg(
        long,
        value_name = "SPEC",
        value_parser = super::delivery_noise::parse,
        allow_hyphen_values = true,
        help_heading = "Measurement noise"
    )]
    pub delivery_noise: Option<smash::measurement::DeliveryNoise>,

    /// Instrument class whose noise, carried through the nominal model, gives the scales every
    /// model is scored by (-2 ln L, AIC, BIC); without it or --noise they are profiled.
    #[arg(long, value_name = "CLASS", value_parser = super::likelihood::parse_instrument,
        help_heading = "Model comparison")]
    pub instrument: Option<smash::diagnose::noise_floor::InstrumentClass>,

    /// Instrument noise file ([noise] table, as diagnose's) giving the scales (overrides it).
    #[arg(long, value_name = "NOISE.toml", help_heading = "Model comparison")]
    pub noise: Option<PathBuf>,
}

impl CalibrateArgs {
    /// The settings these arguments give.
    pub fn settings(&self) -> CalibrateSettings {
        CalibrateSettings {
            shots: self.inputs.shots_format.settings(),
            impact_noise_mm: self.inputs.measurement.impact_noise_mm,
            effects: self.effects.clone(),
            method: match self.method {
                MethodArg::Lm => Method::Lm,
                MethodArg::Paper => Method::Paper,
            },
            max_iters: self.max_iters,
            delivery_noise: self.delivery_noise,
            instrument: self.instrument,
            noise: self.noise.clone(),
            ignore_club_mismatch: self.inputs.club_check.ignore_club_mismatch,
        }
    }
}

/// Run `smash calibrate`.
pub fn run(args: CalibrateArgs) -> anyhow::Result<()> {
    let settings = args.settings();
    let crate::measured::Loaded { plan, club, table } = args
        .inputs
        .load_for_fit(args.noise.as_deref(), args.out_club.as_deref())?;
    let named = NamedClub {
        spec: &club,
        path: &args.inputs.club,
    };
    let Prepared { table, .. } =
        prepare_table(named, table, (true, true), &mut smash::app::StderrNotes)?;
    let mismatch =
        args.inputs
            .club_check
            .check(&args.inputs.club, &club, &args.inputs.shots, &table.shots)?;
    let line = Arc::new(IterationLine::new());
    let report = smash::app::calibrate::run_prepared(
        &settings,
        &club,
        &args.inputs.shots,
        &table,
        mismatch,
        Some(line.clone()),
    );
    line.finish();
    let report = report?;
    let cal = &report.calibration;
    let mut staging = plan.stage();
    if let Some(out) = &args.out_club {
        let comment = format!(
            "Calibrated by smash calibrate --effects {} --method {} on {} ({} shots).\n\
             chi2 = {:.3}, reduced chi2 = {:.4}; {}{}",
            args.effects,
            cal.method.name(),
            args.inputs.shots.display(),
            table.shots.len(),
            cal.chi2,
            cal.reduced_chi2,
            cal.termination,
            super::mismatch_comment(report.club_mismatch.as_deref())
        );
        staging.file(out, club_toml_checked(&cal.club, &comment, out)?.as_bytes())?;
    }
    let page = match &args.inputs.report {
        Some(_) => {
            let title = format!(
                "{} calibrated on {} ({} shots)",
                club.name,
                args.inputs.shots.display(),
                table.shots.len()
            );
            Some(smash::app::calibrate::page(
                &report,
                &table,
                &settings,
                (&args.inputs.shots, title),
            )?)
        }
        None => None,
    };
    let cx = CalibrateContext {
        wide: args.inputs.wide.wide,
        page,
    };
    if let (Some(path), Some(html)) = (&args.inputs.report, report.html(&cx)) {
        staging.file(path, html?.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("calibrated club -> {}", out.display());
    }
    if let Some(path) = &args.inputs.report {
        eprintln!("report -> {}", path.display());
    }
    match report.json().filter(|_| args.inputs.json) {
        Some(json) => crate::stdout::println(json)?,
        None => crate::stdout::print(report.text(&cx))?,
    }
    Ok(())
}
