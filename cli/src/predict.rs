//! `smash predict`: launch conditions for a shots file or for one delivery.

use std::path::PathBuf;

use anyhow::{bail, Context};
use clap::Args;

use smash::data::club_file::read_club;
use smash::data::predictions::predictions_csv;
use smash::data::shots::DEFAULT_GROUP;
use smash::data::write_atomic;
use smash::limits;
use smash::model::{delivery_from_file_units, DeliveryVar};
use smash::report::predict::OneShotReport;
use smash::report::render::Render;
use smash::{ClubSpec, ImpactOutcome};

/// Arguments of `smash predict`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  smash predict --club configs/clubs/paper_driver.toml --shots shots.csv --out pred.csv\n  \
                  smash predict --club configs/clubs/paper_driver.toml --speed 100 --loft 12 --impact-z 10"
)]
pub struct PredictArgs {
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Club file (TOML): clubhead, ball and optional [[effect]] tables.
    #[arg(long, value_name = "CLUB.toml")]
    pub club: PathBuf,

    /// Shots file (CSV). Writes predictions to --out.
    #[arg(
        long,
        value_name = "SHOTS.csv",
        requires = "out",
        conflicts_with = "club_speed_mph"
    )]
    pub shots: Option<PathBuf>,

    /// Format of --shots (a launch-monitor export is converted on the fly).
    #[command(flatten)]
    pub shots_format: super::ShotsFormatArgs,

    /// Predictions file to write (CSV: input columns, pred_*, and err_* where measured).
    #[arg(long, value_name = "PRED.csv")]
    pub out: Option<PathBuf>,

    /// One-shot form: clubhead CoM speed, mph.
    #[arg(
        long = "speed-mph",
        visible_alias = "speed",
        value_name = "MPH",
        help_heading = "One delivery",
        allow_negative_numbers = true
    )]
    pub club_speed_mph: Option<f64>,
    /// Dynamic loft at impact, deg.
    #[arg(
        long = "loft-deg",
        visible_alias = "loft",
        value_name = "DEG",
        help_heading = "One delivery",
        allow_negative_numbers = true
    )]
    pub dynamic_loft_deg: Option<f64>,
    /// Attack angle, deg (+ up).
    #[arg(
        long = "attack-deg",
        visible_alias = "attack",
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub attack_angle_deg: f64,
    /// Club path, deg (+ right of target, in-to-out for a right-hander).
    #[arg(
        long = "path-deg",
        visible_alias = "path",
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub club_path_deg: f64,
    /// Face angle, deg (+ open).
    #[arg(
        long = "face-deg",
        visible_alias = "face",
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub face_angle_deg: f64,
    /// Lie tilt, deg (+ toe up).
    #[arg(
        long = "lie-deg",
        visible_alias = "lie",
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub lie_tilt_deg: f64,
    /// Impact location up the face from the centre, mm.
    #[arg(
        long = "impact-y-mm",
        visible_alias = "impact-y",
        default_value_t = 0.0,
        value_name = "MM",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub impact_y_mm: f64,
    /// Impact location toward the toe from the centre, mm.
    #[arg(
        long = "impact-z-mm",
        visible_alias = "impact-z",
        default_value_t = 0.0,
        value_name = "MM",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub impact_z_mm: f64,
    /// Clubhead angular velocity about ground x, rad/s.
    #[arg(
        long = "omega-x-rad-s",
        default_value_t = 0.0,
        value_name = "RAD/S",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub omega_x_rad_s: f64,
    /// Clubhead angular velocity about ground y (up), rad/s.
    #[arg(
        long = "omega-y-rad-s",
        default_value_t = 0.0,
        value_name = "RAD/S",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub omega_y_rad_s: f64,
    /// Clubhead angular velocity about ground z, rad/s.
    #[arg(
        long = "omega-z-rad-s",
        default_value_t = 0.0,
        value_name = "RAD/S",
        allow_negative_numbers = true,
        help_heading = "One delivery"
    )]
    pub omega_z_rad_s: f64,
    /// Group whose effects apply (one-shot form).
    #[arg(long, default_value = DEFAULT_GROUP, help_heading = "One delivery")]
    pub group: String,

    /// Also fly each predicted launch: pred_carry_yd, pred_offline_yd, pred_apex_yd,
    /// pred_flight_time_s, pred_land_angle_deg (and err_* where the shots file has measured
    /// carry_yd, … columns).
    #[arg(long)]
    pub flight: bool,
    /// Flight options (with --flight).
    #[command(flatten)]
    pub flight_options: crate::flight::FlightOptions,
}

/// Run `smash predict`: the shots-file form (`--shots`, `--out`) or the one-shot form.
pub fn run(args: PredictArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    if let (false, Some(flag)) = (args.flight, args.flight_options.first_given()) {
        bail!("{flag} is a flight option: give --flight to fly the launches, or leave it out");
    }
    let club = read_club(&args.club)?;
    match &args.shots {
        Some(shots_path) => predict_file(&args, &club, shots_path),
        None => predict_one(&args, &club),
    }
}

/// Predict every shot of `shots_path` and write the predictions CSV (with flight columns under
/// `--flight`) to `--out`; refuses a shot whose impact has no finite launch.
fn predict_file(
    args: &PredictArgs,
    club: &ClubSpec,
    shots_path: &std::path::Path,
) -> anyhow::Result<()> {
    let out = args.out.as_ref().expect("clap: --shots requires --out");
    smash::data::safe_write::refuse_inputs(
        &[("--out", out, false)],
        &[("--shots", shots_path), ("--club", &args.club)],
    )?;
    let table = args.shots_format.read(shots_path)?;
    // A mapping file (`--format NAME.toml`) is an input too, known once read: refuse an output
    // that would replace it before anything is said about the shots.
    smash::data::safe_write::check_output(out, false)?;
    let named = smash::app::inputs::NamedClub {
        spec: club,
        path: &args.club,
    };
    let table = smash::app::inputs::prepare_table(
        named,
        table,
        (true, false),
        &mut smash::app::StderrNotes,
    )?
    .table;
    let outcomes = predict_checked(&args.club, club, shots_path, &table)?;
    let mut bytes = predictions_csv(&table, &outcomes);
    if args.flight {
        bytes = add_flight(args, shots_path, &bytes, (&outcomes, &table.lines))?;
    }
    write_atomic(out, &bytes)?;
    eprintln!(
        "predicted {} shot(s) with {} -> {}",
        outcomes.len(),
        club.name,
        out.display()
    );
    Ok(())
}

/// Every shot of `table` predicted with `club` (`club_path` and `shots_path` name them in
/// messages); refuses a shot whose impact has no finite launch.
pub fn predict_checked(
    club_path: &std::path::Path,
    club: &ClubSpec,
    shots_path: &std::path::Path,
    table: &smash::data::shots::ShotTable,
) -> anyhow::Result<Vec<ImpactOutcome>> {
    smash::app::predict::predict_checked(
        smash::app::inputs::NamedClub {
            spec: club,
            path: club_path,
        },
        shots_path,
        table,
    )
}

/// The one-shot form: check the delivery given by flags, solve its impact and print the launch
/// (and its flight under `--flight`).
fn predict_one(args: &PredictArgs, club: &ClubSpec) -> anyhow::Result<()> {
    let (Some(speed), Some(loft)) = (args.club_speed_mph, args.dynamic_loft_deg) else {
        bail!("give either --shots SHOTS.csv --out PRED.csv, or a delivery with at least --speed MPH and --loft DEG");
    };
    if args.out.is_some() {
        bail!("--out goes with --shots; the one-shot form prints its table");
    }
    let values = DeliveryVar::ALL.map(|v| match v {
        DeliveryVar::ClubSpeed => speed,
        DeliveryVar::AttackAngle => args.attack_angle_deg,
        DeliveryVar::ClubPath => args.club_path_deg,
        DeliveryVar::DynamicLoft => loft,
        DeliveryVar::FaceAngle => args.face_angle_deg,
        DeliveryVar::LieTilt => args.lie_tilt_deg,
        DeliveryVar::OmegaX => args.omega_x_rad_s,
        DeliveryVar::OmegaY => args.omega_y_rad_s,
        DeliveryVar::OmegaZ => args.omega_z_rad_s,
        DeliveryVar::ImpactY => args.impact_y_mm,
        DeliveryVar::ImpactZ => args.impact_z_mm,
    });
    for v in DeliveryVar::ALL {
        v.range()
            .check(values[v.index()])
            .map_err(|m| anyhow::anyhow!("{}: {m}", flag(v)))?;
    }
    let delivery = delivery_from_file_units(&values);
    club.check_group(&args.group)
        .map_err(|m| anyhow::anyhow!("--group: {}: {m}", args.club.display()))?;
    let model = club
        .model_for_group(&args.group)
        .with_context(|| format!("{}: group '{}'", args.club.display(), args.group))?;
    let outcome = model.solve(&delivery)?;
    if !(outcome.launch().is_finite() && outcome.smash_factor().is_finite()) {
        bail!(
            "the impact of this delivery ({} mph) with {} has no finite launch; check the \
             delivery and the club",
            limits::fmt_value(speed),
            args.club.display()
        );
    }
    let flight = if args.flight {
        let cfg = args.flight_options.config()?;
        let f = smash::flight::fly_one(
            &cfg,
            &smash::flight::FlightLaunch::from_launch(&outcome.launch()),
        )
        .map_err(|e| anyhow::anyhow!("flight: {e}"))?;
        Some((f, cfg.start_text()))
    } else {
        None
    };
    let report = OneShotReport {
        club: club.name.clone(),
        group: args.group.clone(),
        delivery: values,
        outcome,
        flight,
    };
    let text = report.text(&());
    crate::stdout::print(text)?;
    Ok(())
}

/// Fly the predicted launches and append the flight columns to the predictions CSV (`lines`:
/// each outcome's line in the shots file). A predicted launch the flight model does not take
/// (over its speed range, never landing) keeps its prediction with empty flight cells, counted
/// in one note naming the first.
fn add_flight(
    args: &PredictArgs,
    shots_path: &std::path::Path,
    predictions: &[u8],
    (outcomes, lines): (&[smash::physics::ImpactOutcome], &[usize]),
) -> anyhow::Result<Vec<u8>> {
    use smash::data::flight_files::{flight_csv, parse_raw_csv, OutputLayout};
    use smash::data::flight_measured::check_measured;
    let cfg = args.flight_options.config()?;
    let launches: Vec<smash::flight::FlightLaunch> = outcomes
        .iter()
        .map(|o| smash::flight::FlightLaunch::from_launch(&o.launch()))
        .collect();
    let raw = parse_raw_csv(shots_path, predictions)?;
    let shots_raw = parse_raw_csv(
        shots_path,
        &smash::data::read_text(shots_path)?.into_bytes(),
    )?;
    let layout = OutputLayout::new(&shots_raw.headers, cfg.ground.is_some());
    check_measured(shots_path, &layout, &shots_raw.records, &shots_raw.lines)?;
    let mut unflown: Vec<usize> = Vec::new();
    let mut first = None;
    let flights: Vec<Option<smash::flight::Flight>> = smash::flight::fly(&cfg, &launches)
        .into_iter()
        .zip(lines)
        .map(|(r, &line)| {
            r.map_err(|e| {
                unflown.push(line);
                first.get_or_insert_with(|| format!("line {line}: {e}"));
            })
            .ok()
        })
        .collect();
    if let Some(first) = first {
        eprintln!(
            "{}",
            smash::report::text::wrap_long(&format!(
                "predict: {} of {} predicted launch(es) could not be flown, their flight columns \
                 left empty (line(s) {}; the first, {first})",
                unflown.len(),
                flights.len(),
                smash::data::shots::list_lines(&unflown)
            ))
        );
    }
    Ok(flight_csv(
        &raw.headers,
        &raw.records,
        &flights,
        cfg.ground.is_some(),
    ))
}

/// The command-line flag (its short alias) of a delivery variable in messages about the one-shot
/// form.
const fn flag(v: DeliveryVar) -> &'static str {
    match v {
        DeliveryVar::ClubSpeed => "--speed",
        DeliveryVar::AttackAngle => "--attack",
        DeliveryVar::ClubPath => "--path",
        DeliveryVar::DynamicLoft => "--loft",
        DeliveryVar::FaceAngle => "--face",
        DeliveryVar::LieTilt => "--lie",
        DeliveryVar::OmegaX => "--omega-x-rad-s",
        DeliveryVar::OmegaY => "--omega-y-rad-s",
        DeliveryVar::OmegaZ => "--omega-z-rad-s",
        DeliveryVar::ImpactY => "--impact-y",
        DeliveryVar::ImpactZ => "--impact-z",
    }
}
