//! `smash calibrate`: fit named effects to measured launch conditions.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::{Args, ValueEnum};

use smash::data::club_file::club_toml_checked;
use smash::data::shots::ShotTable;
use smash::fit::{
    calibrate_scored, parse_effect_list, CalibrateOptions, FitError, Method, Progress,
};
use smash::report::calibrate::CalibrateReport;
use smash::ClubSpec;

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
        allow_negative_numbers = true
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

/// Run `smash calibrate`.
pub fn run(args: CalibrateArgs) -> anyhow::Result<()> {
    let crate::measured::Loaded {
        plan,
        club,
        mut table,
    } = args
        .inputs
        .load_for_fit(args.noise.as_deref(), args.out_club.as_deref())?;
    super::to_model_convention(&club, &mut table, true, true)?;
    super::warn_groups_without_effects(&args.inputs.club, &club, &table.shots);
    let mismatch =
        args.inputs
            .club_check
            .check(&args.inputs.club, &club, &args.inputs.shots, &table.shots)?;
    let line = Arc::new(IterationLine::new());
    let report = compute(&args, &club, &table, mismatch, Some(line.clone()));
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
    if let Some(path) = &args.inputs.report {
        // The calibrated model under the fit's measurement model: at the expected true
        // deliveries, averaged over the likely impact locations.
        let mut expected = table.shots.clone();
        if let Some(noise) = cal.delivery_noise {
            let deliveries: Vec<_> = expected.iter().map(|s| s.delivery).collect();
            let golfers: Vec<_> = expected.iter().map(|s| s.golfer.clone()).collect();
            for (s, d) in expected
                .iter_mut()
                .zip(noise.calibrate(&deliveries, &golfers))
            {
                s.delivery = d;
            }
        }
        let launches = smash::predict::expected_launches(
            &cal.club,
            &expected,
            args.inputs.measurement.impact_noise_mm,
        )
        .with_context(|| args.inputs.shots.display().to_string())?;
        let after = smash::compare::compare(
            &table.shots,
            &launches,
            &smash::compare::CompareOptions::default(),
        )?;
        let residuals = smash::report::html::ShotResiduals::new(&table.shots, &launches);
        let title = format!(
            "{} calibrated on {} ({} shots)",
            club.name,
            args.inputs.shots.display(),
            table.shots.len()
        );
        let html = smash::report::html::calibrate_page(&report, &after, &residuals, &title)
            .map_err(anyhow::Error::msg)?;
        staging.file(path, html.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("calibrated club -> {}", out.display());
    }
    if let Some(path) = &args.inputs.report {
        eprintln!("report -> {}", path.display());
    }
    if args.inputs.json {
        crate::stdout::println(serde_json::to_string_pretty(&report)?)?;
    } else {
        crate::stdout::print(smash::report::calibrate::text::render(
            &report,
            args.inputs.wide.wide,
        ))?;
    }
    Ok(())
}

/// The report of the calibration of `table` with `club` under `args`' options (its `--club`
/// and `--shots` only name them in messages), refused when any reported number is not finite;
/// `club_mismatch`: why the shots are another club's, when the caller's club check let them
/// through. `progress` sees the solver's iterations. What `run` reports.
pub fn compute(
    args: &CalibrateArgs,
    club: &ClubSpec,
    table: &ShotTable,
    club_mismatch: Option<String>,
    progress: Option<Arc<dyn Progress>>,
) -> anyhow::Result<CalibrateReport> {
    if !table.has_measurements() {
        return Err(FitError::NoMeasurements).context(args.inputs.shots.display().to_string());
    }
    let requests = parse_effect_list(&args.effects)?;
    let opts = CalibrateOptions {
        method: match args.method {
            MethodArg::Lm => Method::Lm,
            MethodArg::Paper => Method::Paper,
        },
        max_iters: args.max_iters,
        parallel: true,
        impact_noise: args.inputs.measurement.impact_noise_mm,
        delivery_noise: args.delivery_noise,
    };
    let given = super::likelihood::given_scales(
        (args.noise.as_deref(), args.instrument),
        club,
        &table.shots,
        args.inputs.measurement.impact_noise_mm,
    )
    .with_context(|| args.inputs.shots.display().to_string())?;
    let cal = calibrate_scored(
        club,
        &table.shots,
        &requests,
        &opts,
        given.as_ref(),
        progress,
    )
    .with_context(|| args.inputs.shots.display().to_string())?;
    // Nothing infinite or undefined is reported or written into a club file.
    let mut numbers: Vec<(String, f64)> = vec![
        ("chi2".into(), cal.chi2),
        ("nominal chi2".into(), cal.chi2_before),
        ("reduced chi2".into(), cal.reduced_chi2),
        ("-2 ln L".into(), cal.likelihood.minus_2_ln_l),
        (
            "nominal -2 ln L".into(),
            cal.likelihood_nominal.minus_2_ln_l,
        ),
    ];
    numbers.extend(cal.params.iter().map(|p| (p.label(), p.value)));
    if let Some((name, v)) = numbers.iter().find(|(_, v)| !v.is_finite()) {
        anyhow::bail!(
            "{}: the fit's {name} is {v}, not a number; the measurements do not fit this model \
             (check the shots' measured launch values)",
            args.inputs.shots.display()
        );
    }
    Ok(CalibrateReport {
        calibration: cal,
        n_shots: table.shots.len(),
        club_mismatch,
        warnings: table.left_out_notes(),
    })
}
