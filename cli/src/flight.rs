//! `smash flight`: fly launch conditions to landing; options shared with `smash predict
//! --flight`.

use smash::app::flight::FlightSettings;
use std::path::PathBuf;

use clap::Args;

mod calibrate;
mod diagnose;
mod measured;

use smash::app::flight::conditions::{
    columns_used, file_headers, fly_with_conditions, UserConditions,
};
use smash::app::flight::stream::{fly_csv_file, split_results, Flown, CHUNK_BYTES};
use smash::data::flight_files::{flight_csv, flight_error_at, LaunchSource};
use smash::data::flight_summary::summarise_file;
use smash::data::launch_read::LaunchRead;
use smash::data::DataError;
use smash::flight::{Atmosphere, FlightConfig};
use smash::report::flight::FlightReport;
use smash::report::render::Render;

/// Flight options (model, atmosphere, ground, integration).
#[derive(Debug, Clone, Args)]
pub struct FlightOptions {
    /// Aerodynamic coefficient model: fmm2022 (default: Ferguson, McNally & McPhee 2022 as
    /// published, the best of these on the fit part of the shipped real shots),
    /// fmm2022-tour (the same held above the still-air drag, with a drag rise and lift loss
    /// across the drag crisis, calibrated on TrackMan's PGA, PGA 2023 and LPGA 2023 averages),
    /// fmm2022-re (the same quadratics with a low-Reynolds drag rise fitted to the LPGA
    /// averages), nathan-lyu (Reynolds-dependent drag crisis), or table:PATH (CSV with
    /// spin_factor, cd, cl and optionally cm, reynolds).
    #[arg(
        long,
        default_value = smash::flight::aero::MODEL_NAMES[0],
        value_name = "NAME",
        help_heading = "Flight"
    )]
    pub aero: String,
    /// Spin decay: moment (aerodynamic moment from the model's C_M; default), none, or
    /// exp:TAU (exponential with time constant TAU seconds, at least 1 s and 10 steps).
    #[arg(
        long,
        default_value = "moment",
        value_name = "MODE",
        help_heading = "Flight"
    )]
    pub spin_decay: String,
    /// TOML file with an [atmosphere] table (keys as the flags below, without dashes and with
    /// underscores); flags given on the command line override it.
    #[arg(
        long,
        value_name = "FILE.toml",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub atmosphere: Option<PathBuf>,
    /// Air temperature, °C (default 15).
    #[arg(
        long,
        value_name = "C",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub temperature_c: Option<f64>,
    /// Station pressure, hPa (default: ISA at --elevation-m, or 1013.25).
    #[arg(
        long,
        value_name = "HPA",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub pressure_hpa: Option<f64>,
    /// Elevation above sea level, m (ISA pressure there).
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub elevation_m: Option<f64>,
    /// Relative humidity, % (default 50).
    #[arg(
        long,
        value_name = "PCT",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub humidity_pct: Option<f64>,
    /// Wind speed at --wind-height-m, m/s (default 0).
    #[arg(
        long,
        value_name = "M/S",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub wind_speed_m_s: Option<f64>,
    /// Direction the wind blows toward, degrees from the target line toward the right
    /// (0 tailwind, 90 left to right, 180 headwind).
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub wind_direction_deg: Option<f64>,
    /// Height of the wind speed, m (default 10, the WMO anemometer height).
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub wind_height_m: Option<f64>,
    /// Roughness length of the ground for the log wind profile, m (default 0.03).
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help_heading = "Atmosphere"
    )]
    pub roughness_m: Option<f64>,
    /// Add total_yd with the simple bounce-and-roll model.
    #[arg(long, help_heading = "Ground")]
    pub total: bool,
    /// Turf coefficient of restitution for --total (default 0.20).
    #[arg(
        long,
        value_name = "E",
        requires = "total",
        allow_negative_numbers = true,
        help_heading = "Ground"
    )]
    pub ground_restitution: Option<f64>,
    /// Effective run-out deceleration for --total, m/s² (default 12, see src/flight/ground.rs).
    #[arg(
        long,
        value_name = "M/S2",
        requires = "total",
        allow_negative_numbers = true,
        help_heading = "Ground"
    )]
    pub roll_decel_m_s2: Option<f64>,
    /// Integration time step, s (default 0.35 in still air, 0.1 in wind; chosen by a tolerance
    /// test).
    #[arg(
        long,
        value_name = "S",
        allow_negative_numbers = true,
        help_heading = "Flight"
    )]
    pub dt_s: Option<f64>,
    /// Height of a teed ball above the ground, mm: the gap under the ball (default 0, the ball
    /// on the ground). The ball lands when it first touches the ground, so from the ground a
    /// launch below horizontal lands at once; from a tee it may dip and fly on.
    #[arg(
        long,
        value_name = "MM",
        allow_negative_numbers = true,
        help_heading = "Flight"
    )]
    pub tee_mm: Option<f64>,
    /// Longest flight before it is an error, s (default 30).
    #[arg(
        long,
        value_name = "S",
        allow_negative_numbers = true,
        help_heading = "Flight"
    )]
    pub max_time_s: Option<f64>,
}

impl FlightOptions {
    /// The settings these options give.
    pub fn settings(&self) -> FlightSettings {
        FlightSettings {
            aero: self.aero.clone(),
            spin_decay: self.spin_decay.clone(),
            atmosphere: self.atmosphere.clone(),
            temperature_c: self.temperature_c,
            pressure_hpa: self.pressure_hpa,
            elevation_m: self.elevation_m,
            humidity_pct: self.humidity_pct,
            wind_speed_m_s: self.wind_speed_m_s,
            wind_direction_deg: self.wind_direction_deg,
            wind_height_m: self.wind_height_m,
            roughness_m: self.roughness_m,
            total: self.total,
            ground_restitution: self.ground_restitution,
            roll_decel_m_s2: self.roll_decel_m_s2,
            dt_s: self.dt_s,
            tee_mm: self.tee_mm,
            max_time_s: self.max_time_s,
        }
    }

    /// The first option given on the command line ([`FlightSettings::first_given`]).
    pub fn first_given(&self) -> Option<&'static str> {
        self.settings().first_given()
    }

    /// Which conditions the user set: an `--atmosphere` file sets them all.
    pub fn user_conditions(&self) -> UserConditions {
        self.settings().user_conditions()
    }

    /// The flight configuration these options describe.
    pub fn config(&self) -> anyhow::Result<FlightConfig> {
        self.settings().config()
    }

    /// The atmosphere the options describe (file, then flags over it).
    pub fn atmosphere(&self) -> anyhow::Result<Atmosphere> {
        self.settings().atmosphere()
    }
}

/// Arguments of `smash flight`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  smash flight --shots launch.csv --out flight.csv\n  \
                  smash flight --shots pred.csv --launch predicted --elevation-m 1600 --temperature-c 28 --out f.csv"
)]
pub struct FlightArgs {
    /// Launch file (CSV): ball_speed_mph, launch_angle_deg, backspin_rpm and optionally
    /// azimuth_deg, sidespin_rpm (or the same with pred_, as `smash predict` writes them).
    #[arg(long, value_name = "LAUNCH.csv")]
    pub shots: PathBuf,
    /// Output file (CSV: input columns, pred_carry_yd, pred_offline_yd, pred_apex_yd,
    /// pred_flight_time_s, pred_land_angle_deg [, pred_total_yd], err_* where measured).
    #[arg(long, value_name = "F.csv")]
    pub out: PathBuf,
    /// Which launch columns to fly: measured (ball_speed_mph, …) or predicted
    /// (pred_ball_speed_mph, …). Default: measured if present.
    #[arg(long, value_name = "WHICH", value_parser = ["measured", "predicted"])]
    pub launch: Option<String>,
    /// Print the comparison with the measured flight columns (carry_yd, offline_yd, apex_yd,
    /// land_angle_deg) as one JSON object on stdout instead of the text table on stderr.
    #[arg(long)]
    pub json: bool,
    /// Write a self-contained HTML report of the comparison with the measured flights (charts
    /// per club).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
    /// Calibrate the flight to the measured carry, apex and land angle: fit scalings of the
    /// listed terms (drag, lift, spin_decay; comma-separated) with their standard errors,
    /// then fly and compare with the calibrated model.
    #[arg(long, value_name = "TERMS", conflicts_with = "diagnose")]
    pub calibrate: Option<String>,
    /// With --calibrate: fit the scalings separately per ball (the `ball_type` column) or per
    /// session (a `session`, `date`, `datetime`, `date_time` or `timestamp` column), each with
    /// its standard errors, and fly each part's shots with its own scalings.
    #[arg(long, value_name = "ball|session", requires = "calibrate", value_parser = ["ball", "session"])]
    pub calibrate_by: Option<String>,
    /// Diagnose the flight model against the measured carry, apex and land angle: which term
    /// is off (drag level, lift slope, drag crisis, spin decay, drag per ball_type), ranked by
    /// cross-validated gain (folds by session when the file has a session or date column, else
    /// by shot); the selected terms are then flown and compared.
    #[arg(long)]
    pub diagnose: bool,
    /// Refuse the whole file at the first row that cannot be used. By default such a row (a
    /// cell that is not a number, a value outside its physical range, a launch that cannot be
    /// flown) is left out and counted, one note per reason.
    #[arg(long)]
    pub strict: bool,
    /// Flight options.
    #[command(flatten)]
    pub flight: FlightOptions,
}

/// Run `smash flight`.
pub fn run(args: FlightArgs) -> anyhow::Result<()> {
    let mut inputs = vec![("--shots", args.shots.as_path())];
    if let Some(a) = &args.flight.atmosphere {
        inputs.push(("--atmosphere", a.as_path()));
    }
    let mut outputs = vec![("--out", args.out.as_path(), false)];
    if let Some(r) = &args.report {
        outputs.push(("--report", r.as_path(), false));
    }
    smash::data::safe_write::refuse_inputs(&outputs, &inputs)?;
    let cfg = args.flight.config()?;
    let source = args.launch.as_deref().map(|s| match s {
        "predicted" => LaunchSource::Predicted,
        _ => LaunchSource::Measured,
    });
    let read = LaunchRead {
        source,
        with_total: cfg.ground.is_some(),
        strict: args.strict,
    };
    let user = args.flight.user_conditions();
    let headers = file_headers(&args.shots)?;
    let from_file = columns_used(&headers, user);
    let t0 = std::time::Instant::now();
    let fitting = match (&args.calibrate, args.diagnose) {
        (Some(_), _) => Some("--calibrate"),
        (None, true) => Some("--diagnose"),
        _ => None,
    };
    let mut diagnosis = None;
    let mut fit_notes = Vec::new();
    let mut calibration = Vec::new();
    let (flown, conditions) = if let Some(flag) = fitting {
        if !from_file.is_empty() {
            anyhow::bail!(
                "{flag} flies every shot in one atmosphere, but {} states conditions per \
                 shot ({}): set them with --elevation-m, --temperature-c and --humidity-pct",
                args.shots.display(),
                from_file.iter().map(|c| c.1).collect::<Vec<_>>().join(", ")
            );
        }
        let (flown, d, notes, parts) = fit_and_fly(&args, &cfg, read)?;
        (diagnosis, fit_notes, calibration) = (d, notes, parts);
        (flown, None)
    } else if from_file.is_empty() {
        let flown = fly_csv_file(&args.shots, &args.out, &cfg, read, CHUNK_BYTES)?;
        (flown, None)
    } else {
        let base = args.flight.atmosphere()?;
        let (flown, used) = fly_with_conditions(&args.shots, &args.out, &cfg, &base, user, read)?;
        (flown, Some(used))
    };
    let secs = t0.elapsed().as_secs_f64();
    let warnings = flown.notes();
    for note in &warnings {
        crate::text::print_note("shots", &smash::data::escape(note));
    }
    let air = match &conditions {
        None => format!("air {:.4} kg/m³", cfg.air.density_kg_m3),
        Some(c) => format!(
            "air per shot from the file's {} ({} distinct){}",
            c.columns.join(", "),
            c.atmospheres,
            user.overridden_text()
        ),
    };
    eprintln!(
        "{}  in {secs:.3} s (reading, flying and writing)",
        crate::text::wrap_long(&format!(
            "flew {} shot(s) with {} ({air}, ball {}) -> {}\n",
            flown.shots,
            cfg.aero.name(),
            cfg.start_text(),
            args.out.display()
        ))
    );
    let Some(summary) = summarise_file(&args.out)? else {
        if args.json || args.report.is_some() {
            anyhow::bail!(
                "{}: no measured flight column (carry_yd, offline_yd, apex_yd or \
                 land_angle_deg) to compare with for --json or --report",
                args.shots.display()
            );
        }
        return Ok(());
    };
    let flown = format!(
        "{} shots flown with {} ({air})",
        flown.shots,
        cfg.aero.name()
    );
    let modelled = summary.modelled_notes();
    let mut report = FlightReport::new(flown, summary, diagnosis);
    report.calibration = calibration;
    report.warnings = warnings;
    // Printed before the fit's results; in the report too.
    report.warnings.extend(fit_notes);
    for note in modelled {
        if !args.json {
            crate::text::print_note("flight", &note);
        }
        report.warnings.push(note);
    }
    match report.json().filter(|_| args.json) {
        Some(json) => crate::stdout::println(json)?,
        None => eprint!("\n{}", Render::text(&report, &())),
    }
    if let (Some(path), Some(html)) = (&args.report, report.html(&())) {
        let html = html.map_err(|e| anyhow::anyhow!("--report: {e}"))?;
        smash::data::write_atomic(path, html.as_bytes())?;
        eprintln!("report -> {}", path.display());
    }
    Ok(())
}

/// What `--calibrate` or `--diagnose` made: the flights written, the diagnosis
/// (`--diagnose`), the notes on what was fitted to and the scalings (`--calibrate`).
type Fitted = (
    Flown,
    Option<smash::flight::diagnose::FlightDiagnosis>,
    Vec<String>,
    Vec<smash::report::flight::CalibratedPart>,
);

/// `--calibrate` or `--diagnose`: the fit and the flights written ([`Fitted`]).
fn fit_and_fly(args: &FlightArgs, cfg: &FlightConfig, read: LaunchRead) -> anyhow::Result<Fitted> {
    Ok(match &args.calibrate {
        Some(terms) => {
            let (flown, notes, parts) = calibrate::calibrate_and_fly(args, cfg, read, terms)?;
            (flown, None, notes, parts)
        }
        None => {
            let (flown, d, notes) = diagnose::diagnose_and_fly(args, cfg, read)?;
            (flown, Some(d), notes, Vec::new())
        }
    })
}

/// The flights of every launch of `table` (`results`, in its order) written to `--out` with
/// the table's own columns; a launch that did not land is left out and counted (under
/// `--strict`, the first is refused in one line naming file, line and column).
fn write_flown(
    args: &FlightArgs,
    cfg: &FlightConfig,
    mut table: smash::data::flight_files::LaunchTable,
    results: Vec<Result<smash::flight::Flight, smash::flight::FlightError>>,
) -> anyhow::Result<Flown> {
    let (flights, errs) = split_results(&args.shots, &table.lines, table.source.prefix(), results);
    table.leave_out(&args.shots, errs, args.strict)?;
    let bytes = flight_csv(
        &table.headers,
        &table.records,
        &flights,
        cfg.ground.is_some(),
    );
    smash::data::write_atomic(&args.out, &bytes)?;
    Ok(Flown {
        shots: flights.len(),
        source: table.source,
        left_out: table.left_out,
    })
}

/// Results to flights, or the first failure as one line naming file, line and column.
pub fn collect(
    path: &std::path::Path,
    lines: &[usize],
    prefix: &str,
    results: Vec<Result<smash::flight::Flight, smash::flight::FlightError>>,
) -> Result<Vec<smash::flight::Flight>, DataError> {
    results
        .into_iter()
        .zip(lines)
        .map(|(r, &line)| r.map_err(|e| flight_error_at(path, line, prefix, &e)))
        .collect()
}
