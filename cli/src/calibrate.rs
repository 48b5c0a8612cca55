//! `smash calibrate`: fit named effects to measured launch conditions.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::{Args, ValueEnum};
use serde_json::json;

use smash::data::club_file::{club_toml_checked, read_club};
use smash::data::output_plan::OutputPlan;
use smash::data::shots::ShotTable;
use smash::diagnose::honest;
use smash::fit::{
    calibrate_scored, parse_effect_list, CalibrateOptions, Calibration, FitError, Method, Progress,
};
use smash::physics::LaunchComponent;
use smash::stats::t_statistic;
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
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Club file (TOML); its own [[effect]] tables stay fixed.
    #[arg(long, value_name = "CLUB.toml")]
    pub club: PathBuf,

    /// Shots file (CSV) with measured launch columns.
    #[arg(long, value_name = "SHOTS.csv")]
    pub shots: PathBuf,

    /// Format of --shots (a launch-monitor export is converted on the fly).
    #[command(flatten)]
    pub shots_format: super::ShotsFormatArgs,

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

    /// Write a self-contained HTML report (errors before and after, estimates with their
    /// plausible ranges, the calibrated model's trends and face maps).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,

    /// Print one JSON object on stdout (progress and prose go to stderr).
    #[arg(long)]
    pub json: bool,

    /// `--wide`: the errors before and after side by side however wide.
    #[command(flatten)]
    pub wide: crate::text::WideArgs,

    /// Iteration limit of each solver run.
    #[arg(
        long,
        default_value_t = 100,
        value_name = "N",
        help_heading = "Solver",
        allow_negative_numbers = true
    )]
    pub max_iters: u64,

    /// Measurement noise of the inputs.
    #[command(flatten)]
    pub measurement: super::MeasurementArgs,

    /// What to do when the shots do not match the club.
    #[command(flatten)]
    pub club_check: super::ClubCheckArgs,

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
    args.effect_defs.load()?;
    let mut inputs = vec![("--club", args.club.as_path()), ("--shots", &args.shots)];
    inputs.extend(args.noise.as_deref().map(|n| ("--noise", n)));
    let plan = OutputPlan::new(&inputs)
        .file("--out-club", args.out_club.as_deref())
        .file("--report", args.report.as_deref());
    plan.check()?;
    let club = read_club(&args.club)?;
    let mut table = args.shots_format.read(&args.shots)?;
    plan.check()?; // again: a `--format` mapping file is an input known once read
    super::to_model_convention(&club, &mut table, true, true)?;
    super::warn_groups_without_effects(&args.club, &club, &table.shots);
    let mismatch = args
        .club_check
        .check(&args.club, &club, &args.shots, &table.shots)?;
    let line = Arc::new(IterationLine::new());
    let cal = compute(&args, &club, &table, Some(line.clone()));
    line.finish();
    let cal = cal?;
    let mut staging = plan.stage();
    if let Some(out) = &args.out_club {
        let comment = format!(
            "Calibrated by smash calibrate --effects {} --method {} on {} ({} shots).\n\
             chi2 = {:.3}, reduced chi2 = {:.4}; {}",
            args.effects,
            cal.method.name(),
            args.shots.display(),
            table.shots.len(),
            cal.chi2,
            cal.reduced_chi2,
            cal.termination
        );
        staging.file(out, club_toml_checked(&cal.club, &comment, out)?.as_bytes())?;
    }
    if let Some(path) = &args.report {
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
            args.measurement.impact_noise_mm,
        )
        .with_context(|| args.shots.display().to_string())?;
        let after = smash::compare::compare(
            &table.shots,
            &launches,
            &smash::compare::CompareOptions::default(),
        )?;
        let residuals = smash::report::html::ShotResiduals::new(&table.shots, &launches);
        let title = format!(
            "{} calibrated on {} ({} shots)",
            club.name,
            args.shots.display(),
            table.shots.len()
        );
        let html = smash::report::html::calibrate_page(&cal, &after, &residuals, &title)
            .map_err(anyhow::Error::msg)?;
        staging.file(path, html.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("calibrated club -> {}", out.display());
    }
    if let Some(path) = &args.report {
        eprintln!("report -> {}", path.display());
    }
    if args.json {
        let mut json = to_json(&cal);
        json["club_mismatch"] = serde_json::json!(mismatch);
        crate::stdout::println(serde_json::to_string_pretty(&json)?)?;
    } else {
        let mut text = crate::calibrate_text::text_report(&cal, table.shots.len(), args.wide.wide);
        if let Some(why) = &mismatch {
            let head = format!(
                "NO FINDINGS: the shots do not match the club ({why}); the fitted values describe \
                 another club's shots, not this head\n"
            );
            text = crate::text::wrap_long(&head) + &text;
        }
        crate::stdout::print(text)?;
    }
    Ok(())
}

/// The calibration of `table` with `club` under `args`' options (its `--club` and `--shots`
/// only name them in messages), refused when any reported number is not finite; `progress`
/// sees the solver's iterations. What `run` reports.
pub fn compute(
    args: &CalibrateArgs,
    club: &ClubSpec,
    table: &ShotTable,
    progress: Option<Arc<dyn Progress>>,
) -> anyhow::Result<Calibration> {
    if !table.has_measurements() {
        return Err(FitError::NoMeasurements).context(args.shots.display().to_string());
    }
    let requests = parse_effect_list(&args.effects)?;
    let opts = CalibrateOptions {
        method: match args.method {
            MethodArg::Lm => Method::Lm,
            MethodArg::Paper => Method::Paper,
        },
        max_iters: args.max_iters,
        parallel: true,
        impact_noise: args.measurement.impact_noise_mm,
        delivery_noise: args.delivery_noise,
    };
    let given = super::likelihood::given_scales(
        (args.noise.as_deref(), args.instrument),
        club,
        &table.shots,
        args.measurement.impact_noise_mm,
    )
    .with_context(|| args.shots.display().to_string())?;
    let cal = calibrate_scored(
        club,
        &table.shots,
        &requests,
        &opts,
        given.as_ref(),
        progress,
    )
    .with_context(|| args.shots.display().to_string())?;
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
            args.shots.display()
        );
    }
    Ok(cal)
}

fn opt(v: Option<f64>) -> serde_json::Value {
    v.filter(|x| x.is_finite())
        .map_or(serde_json::Value::Null, |x| json!(x))
}

/// The machine-readable report.
pub fn to_json(cal: &Calibration) -> serde_json::Value {
    let labels: Vec<String> = cal.params.iter().map(|p| p.label()).collect();
    let params: Vec<serde_json::Value> = cal
        .params
        .iter()
        .map(|p| {
            json!({
                "effect": p.effect,
                "param": p.param,
                "group": p.group,
                "value": p.value,
                "stderr": opt(p.stderr),
                "unit": p.unit,
                "t": opt(p.stderr.map(|s| t_statistic(p.value, s))),
                "at_bound": p.at_bound,
                "plausible": honest::is_plausible(p),
                "plausible_range": honest::spec_of(p).map(|s| [s.plausible.0, s.plausible.1]),
                "stand_in": honest::stand_in(p),
            })
        })
        .collect();
    let correlation = cal.correlation.as_ref().map(|c| {
        let rows: Vec<Vec<f64>> = (0..c.nrows())
            .map(|i| (0..c.ncols()).map(|j| c[(i, j)]).collect())
            .collect();
        json!({"labels": labels, "matrix": rows})
    });
    let flagged: Vec<serde_json::Value> = cal
        .strongly_correlated
        .iter()
        .map(|p| json!({"a": labels[p.a], "b": labels[p.b], "r": p.r}))
        .collect();
    let unidentified: Vec<&String> = cal
        .identifiability
        .unidentified()
        .into_iter()
        .map(|j| &labels[j])
        .collect();
    let noise: serde_json::Map<String, serde_json::Value> = LaunchComponent::ALL
        .iter()
        .map(|c| (c.column().to_owned(), json!(cal.noise_scales[c.index()])))
        .collect();
    let shaft = cal.shaft_relation.as_ref().map(|s| {
        json!({
            "points": s.points.iter().map(|(g, m, dm, se)| json!({
                "group": g, "shaft_mass_g": m, "dm_g": dm, "stderr": opt(*se)
            })).collect::<Vec<_>>(),
            "slope_g_per_g": s.line.slope,
            "intercept_g": s.line.intercept,
            "r": s.line.r,
        })
    });
    let stages: Vec<serde_json::Value> = cal
        .paper_stages
        .iter()
        .map(|a| {
            json!({
                "param": labels[a.param],
                "stage": match a.stage { smash::fit::Stage::Linear => "W=inf", smash::fit::Stage::Angular => "W=0" },
                "linear_sensitivity": a.linear_sensitivity,
                "angular_sensitivity": a.angular_sensitivity,
            })
        })
        .collect();
    json!({
        "command": "calibrate",
        "method": cal.method.name(),
        "params": params,
        "correlation": correlation,
        "strongly_correlated": flagged,
        "aliases": honest::aliases(&cal.params, cal.correlation.as_ref()).iter().map(honest::Alias::to_json).collect::<Vec<_>>(),
        "unidentifiable": unidentified,
        "chi2": cal.chi2,
        "chi2_nominal": cal.chi2_before,
        "n_residuals": cal.n_residuals,
        "dof": cal.dof,
        "reduced_chi2": cal.reduced_chi2,
        "aic": cal.aic,
        "bic": cal.bic,
        "evaluations": cal.evaluations,
        "iterations": cal.iterations,
        "termination": cal.termination,
        "noise_scales": noise,
        "before": cal.before.to_json(),
        "after": cal.after.to_json(),
        "shaft_relation": shaft,
        "paper_stages": stages,
        "measurement_model": measurement_json(cal),
        "likelihood": super::likelihood::to_json("calibrated", &cal.likelihood, &cal.likelihood_nominal),
    })
}

/// The impact-location (mm, to 1e-6) and delivery noise the fit assumed (`null`: as measured).
fn measurement_json(cal: &Calibration) -> serde_json::Value {
    let mm = |m: f64| (m * 1e9).round() / 1e6;
    json!({
        "impact_noise_mm": cal.impact_noise.map(|n| json!({
            "y": mm(n.sigma_y_m),
            "z": mm(n.sigma_z_m),
        })),
        "delivery_noise": cal.delivery_noise.as_ref().map(super::delivery_noise::to_json),
    })
}
