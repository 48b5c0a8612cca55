//! `smash infer-club`: the head's effective properties from the shots, with honest
//! uncertainty. The library owns the work ([`smash::infer`]); here the arguments are parsed,
//! the files read and the outputs printed or written.

use smash::report::render::Render;
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use smash::data::club_file::{club_toml_checked, read_club};
use smash::data::noise_file::read_noise_file;
use smash::data::output_plan::OutputPlan;
use smash::diagnose::noise_floor::InstrumentClass;
use smash::infer::{self, Report, Settings};

/// Arguments of `smash infer-club`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    smash infer-club --shots session.csv --start configs/clubs/paper_driver.toml \\\n      \
    --out-club head.toml\n  \
    smash infer-club --shots session.csv --start configs/clubs/paper_driver.toml --plan \\\n      \
    --plan-shots 1200 --target-se com_mm[0]=1,cor=0.003")]
pub struct InferClubArgs {
    /// Shots file (CSV) with delivery, impact location and measured launch, or a
    /// launch-monitor export with --format.
    #[arg(long, value_name = "SHOTS.csv")]
    pub shots: PathBuf,

    /// Format of --shots (a launch-monitor export is converted on the fly).
    #[command(flatten)]
    pub shots_format: crate::ShotsFormatArgs,

    /// The start club: the prior's centre (each head parameter a Gaussian of the width in
    /// docs/plausible-ranges.md), and everything not inferred (masses, ball, other effects).
    #[arg(long, value_name = "CLUB.toml")]
    pub start: PathBuf,

    /// Write the inferred club (each value's SE and provenance in comments), only after
    /// success.
    #[arg(long, value_name = "OUT.toml")]
    pub out_club: Option<PathBuf>,

    /// Print the report as one JSON object on stdout (docs/json.md).
    #[arg(long)]
    pub json: bool,

    /// Write a self-contained HTML report: the estimates, what the shots determine, and the
    /// uncertainty ellipses of the correlated pairs.
    #[arg(long, value_name = "FILE.html", conflicts_with = "plan")]
    pub report: Option<PathBuf>,

    /// Plan instead of fitting: the standard error each parameter would have, and the shots
    /// needed to determine it, for the session's swings and impact spread at the start head.
    #[arg(long)]
    pub plan: bool,

    /// --plan: the number of shots to plan for (default: the session's).
    #[arg(long, value_name = "N", requires = "plan")]
    pub plan_shots: Option<usize>,

    /// --plan: spread the impact locations about their mean to these SDs, mm (up, toe).
    #[arg(long, value_name = "SY,SZ", requires = "plan", value_parser = parse_pair, allow_hyphen_values = true)]
    pub impact_spread_mm: Option<(f64, f64)>,

    /// --plan: wanted standard errors, `key=SE` comma-separated in the club file's units
    /// (e.g. com_mm[0]=1,cor=0.003).
    #[arg(long, value_name = "LIST", requires = "plan")]
    pub target_se: Option<String>,

    /// Instrument class whose noise the measurement model and the plan assume (default
    /// camera).
    #[arg(long, value_name = "CLASS", value_parser = super::likelihood::parse_instrument)]
    pub instrument: Option<InstrumentClass>,

    /// Instrument noise file ([noise] table, as diagnose's; overrides --instrument).
    #[arg(long, value_name = "NOISE.toml")]
    pub noise: Option<PathBuf>,

    /// Settings file (TOML, the keys of smash::infer::Settings; flags override it).
    #[arg(long, value_name = "SETTINGS.toml")]
    pub settings: Option<PathBuf>,

    /// Skip the profile-likelihood intervals (faster).
    #[arg(long)]
    pub no_profile: bool,
}

fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    let bad = || format!("'{s}': expected two numbers SY,SZ in mm, each > 0 (e.g. 8,10)");
    let (a, b) = s.split_once(',').ok_or_else(bad)?;
    let (a, b): (f64, f64) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0 {
        Ok((a, b))
    } else {
        Err(bad())
    }
}

fn parse_targets(s: &str) -> anyhow::Result<Vec<(String, f64)>> {
    s.split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| {
            let (k, v) = t.split_once('=').with_context(|| {
                format!("--target-se '{t}': expected key=SE (e.g. com_mm[0]=1)")
            })?;
            let v: f64 = v
                .trim()
                .parse()
                .with_context(|| format!("--target-se '{t}': the SE is not a number"))?;
            Ok((k.trim().to_owned(), v))
        })
        .collect()
}

fn settings(args: &InferClubArgs) -> anyhow::Result<Settings> {
    let mut s = match &args.settings {
        Some(p) => infer::read_settings(p)?,
        None => Settings::default(),
    };
    let noise = match (&args.noise, args.instrument) {
        (Some(p), _) => Some(read_noise_file(p)?),
        (None, Some(c)) => Some(c.noise()),
        (None, None) => None,
    };
    if let Some(n) = noise {
        s.launch_noise_sd = n.launch_sd;
        s.delivery_noise_sd = n.delivery_sd;
    }
    if args.no_profile {
        s.profile_grid_se.clear();
    }
    if let Err(e) = s.check() {
        anyhow::bail!(
            "{}: {e}",
            args.settings
                .as_deref()
                .map_or("settings".to_owned(), |p| p.display().to_string())
        );
    }
    Ok(s)
}

/// The comment block of the written club: provenance and every value's SE.
fn club_comment(args: &InferClubArgs, r: &Report) -> String {
    let mut c = format!(
        "Inferred by smash infer-club from {} ({} shots), start (prior centre) {}.\n\
         Values: posterior mode +- SE (prior included); 'determined' = {}.\n",
        args.shots.display(),
        r.n_shots,
        args.start.display(),
        r.determined_rule
    );
    for p in &r.params {
        c.push_str(&format!(
            "{} = {} +- {} {} (start {}; prior share {:.0} %; {})\n",
            p.name,
            infer::report::fmt_num(p.value),
            infer::report::fmt_num(p.stderr),
            p.unit,
            infer::report::fmt_num(p.start),
            100.0 * p.prior_share,
            if p.determined {
                "determined by the shots"
            } else {
                "NOT determined by the shots: mostly the start club's value"
            }
        ));
    }
    c
}

/// Run `smash infer-club`.
pub fn run(args: InferClubArgs) -> anyhow::Result<()> {
    let mut inputs = vec![("--start", args.start.as_path()), ("--shots", &args.shots)];
    if let Some(n) = &args.noise {
        inputs.push(("--noise", n));
    }
    if let Some(s) = &args.settings {
        inputs.push(("--settings", s));
    }
    let plan = OutputPlan::new(&inputs)
        .file("--out-club", args.out_club.as_deref())
        .file("--report", args.report.as_deref());
    plan.check()?;
    let settings = settings(&args)?;
    let club = read_club(&args.start)?;
    let mut table = args.shots_format.read(&args.shots)?;
    plan.check()?;
    smash::app::inputs::to_model_convention(
        &club,
        &mut table,
        (true, true),
        &mut smash::app::StderrNotes,
    )?;
    if !table.has_measurements() {
        return Err(smash::fit::FitError::NoMeasurements).context(args.shots.display().to_string());
    }
    if args.plan {
        let targets = args
            .target_se
            .as_deref()
            .map(parse_targets)
            .transpose()?
            .unwrap_or_default();
        let r = infer::run_plan(
            &settings,
            &club,
            &table.shots,
            args.plan_shots,
            args.impact_spread_mm.map(|(a, b)| [a, b]),
            &targets,
        )
        .with_context(|| args.shots.display().to_string())?;
        match r.json().filter(|_| args.json) {
            Some(json) => crate::stdout::println(json)?,
            None => crate::stdout::print(r.text(&()))?,
        }
        return Ok(());
    }
    let r = infer::run(&settings, &club, &table.shots)
        .with_context(|| args.shots.display().to_string())?;
    let mut staging = plan.stage();
    if let Some(out) = &args.out_club {
        staging.file(
            out,
            club_toml_checked(&r.club, &club_comment(&args, &r), out)?.as_bytes(),
        )?;
    }
    let title = format!("{} inferred from {}", club.name, args.shots.display());
    if let (Some(path), Some(html)) = (&args.report, r.html(&title)) {
        staging.file(path, html?.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("inferred club -> {}", out.display());
    }
    if let Some(path) = &args.report {
        eprintln!("report -> {}", path.display());
    }
    match r.json().filter(|_| args.json) {
        Some(json) => crate::stdout::println(json)?,
        None => crate::stdout::print(r.text(&title))?,
    }
    Ok(())
}
