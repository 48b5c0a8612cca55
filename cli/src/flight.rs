//! `smash flight`: fly launch conditions to landing; options shared with `smash predict
//! --flight`.

use smash::limits::fmt_value;
use std::path::PathBuf;

use clap::Args;

mod calibrate;
mod diagnose;
mod measured;

use smash::data::flight_conditions::{
    columns_used, file_headers, fly_with_conditions, UserConditions,
};
use smash::data::flight_files::{flight_csv, flight_error_at, read_atmosphere, LaunchSource};
use smash::data::flight_stream::{fly_csv_file, split_results, Flown, CHUNK_BYTES};
use smash::data::flight_summary::summarise_file;
use smash::data::launch_read::LaunchRead;
use smash::data::DataError;
use smash::flight::{AeroModel, Atmosphere, FlightConfig, Ground, SpinDecay};
use smash::report::flight::FlightReport;

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
    /// The first option given on the command line (aero and spin decay: other than their
    /// defaults), as its flag, or `None`: `predict` refuses flight options without `--flight`
    /// rather than ignore them.
    pub fn first_given(&self) -> Option<&'static str> {
        let given = [
            (self.aero != smash::flight::aero::MODEL_NAMES[0], "--aero"),
            (self.spin_decay != "moment", "--spin-decay"),
            (self.atmosphere.is_some(), "--atmosphere"),
            (self.temperature_c.is_some(), "--temperature-c"),
            (self.pressure_hpa.is_some(), "--pressure-hpa"),
            (self.elevation_m.is_some(), "--elevation-m"),
            (self.humidity_pct.is_some(), "--humidity-pct"),
            (self.wind_speed_m_s.is_some(), "--wind-speed-m-s"),
            (self.wind_direction_deg.is_some(), "--wind-direction-deg"),
            (self.wind_height_m.is_some(), "--wind-height-m"),
            (self.roughness_m.is_some(), "--roughness-m"),
            (self.total, "--total"),
            (self.dt_s.is_some(), "--dt-s"),
            (self.max_time_s.is_some(), "--max-time-s"),
        ];
        given.iter().find(|(g, _)| *g).map(|(_, flag)| *flag)
    }

    /// Which conditions the user set: an `--atmosphere` file sets them all.
    pub fn user_conditions(&self) -> UserConditions {
        let file = self.atmosphere.is_some();
        UserConditions {
            temperature: file || self.temperature_c.is_some(),
            pressure: file || self.pressure_hpa.is_some() || self.elevation_m.is_some(),
            humidity: file || self.humidity_pct.is_some(),
        }
    }

    /// The flight configuration these options describe.
    pub fn config(&self) -> anyhow::Result<FlightConfig> {
        let atm = self.atmosphere()?;
        self.config_in(&atm)
    }

    /// The atmosphere the options describe (file, then flags over it).
    pub fn atmosphere(&self) -> anyhow::Result<Atmosphere> {
        let mut atm = match &self.atmosphere {
            Some(p) => read_atmosphere(p)?,
            None => Atmosphere::default(),
        };
        if let Some(v) = self.temperature_c {
            atm.temperature_c = v;
        }
        if let Some(v) = self.pressure_hpa {
            atm.pressure_hpa = Some(v);
            atm.elevation_m = None;
        }
        if let Some(v) = self.elevation_m {
            atm.elevation_m = Some(v);
            if self.pressure_hpa.is_none() {
                atm.pressure_hpa = None;
            }
        }
        if let Some(v) = self.humidity_pct {
            atm.humidity_pct = v;
        }
        if let Some(v) = self.wind_speed_m_s {
            atm.wind_speed_m_s = v;
        }
        if let Some(v) = self.wind_direction_deg {
            atm.wind_direction_deg = v;
        }
        if let Some(v) = self.wind_height_m {
            atm.wind_height_m = v;
        }
        if let Some(v) = self.roughness_m {
            atm.roughness_m = v;
        }
        Ok(atm)
    }

    /// The flight configuration of these options in the atmosphere `atm`.
    fn config_in(&self, atm: &Atmosphere) -> anyhow::Result<FlightConfig> {
        let air = atm
            .air()
            .map_err(|e| anyhow::anyhow!("--{}: {e}", e.key.replace('_', "-")))?;
        let aero = AeroModel::from_name(&self.aero).map_err(|e| anyhow::anyhow!("--aero: {e}"))?;
        let spin_decay = match self.spin_decay.as_str() {
            "moment" => SpinDecay::Moment,
            "none" => SpinDecay::None,
            s => match s.strip_prefix("exp:").map(str::parse::<f64>) {
                Some(Ok(tau)) if tau.is_finite() => {
                    check_spin_decay_tau(tau, self.dt_s)?;
                    SpinDecay::Exponential {
                        time_constant_s: tau,
                    }
                }
                _ => anyhow::bail!(
                    "--spin-decay '{}': allowed are moment, none, exp:TAU with TAU in seconds",
                    smash::data::escape(s)
                ),
            },
        };
        let ground = if self.total {
            let g = Ground {
                restitution: self
                    .ground_restitution
                    .unwrap_or(smash::flight::ground::DEFAULT_RESTITUTION),
                roll_decel_m_s2: self
                    .roll_decel_m_s2
                    .unwrap_or(smash::flight::ground::DEFAULT_ROLL_DECEL_M_S2),
            };
            g.check().map_err(|e| anyhow::anyhow!("--total: {e}"))?;
            Some(g)
        } else {
            None
        };
        if let Some(dt_s) = self.dt_s {
            if !(MIN_DT_S..=0.5).contains(&dt_s) {
                anyhow::bail!(
                    "--dt-s {}: must be within [{MIN_DT_S}, 0.5] s (a smaller step only adds \
                     rounding: a 10 s flight would take over 10^5 steps)",
                    fmt_value(dt_s)
                );
            }
        }
        let dt_s = self.dt_s;
        let max_time_s = self.max_time_s.unwrap_or(smash::flight::DEFAULT_MAX_TIME_S);
        if !(max_time_s > 0.0 && max_time_s <= 120.0) {
            anyhow::bail!(
                "--max-time-s {}: must be within (0, 120] s",
                fmt_value(max_time_s)
            );
        }
        let tee_mm = self.tee_mm.unwrap_or(0.0);
        let max_tee_mm = smash::flight::MAX_TEE_HEIGHT_M * 1e3;
        if !(0.0..=max_tee_mm).contains(&tee_mm) {
            anyhow::bail!(
                "--tee-mm {}: must be within [0, {}] mm (0: the ball on the ground; a tee may \
                 be at most 4 in long)",
                fmt_value(tee_mm),
                fmt_value(max_tee_mm)
            );
        }
        Ok(FlightConfig {
            aero,
            air,
            spin_decay,
            dt_s,
            max_time_s,
            ground,
            tee_height_m: tee_mm * 1e-3,
            ..FlightConfig::default()
        })
    }
}

/// Smallest `--dt-s`, s: the default steps (0.35 s, 0.1 s in wind) already keep the carry
/// within 0.01 yd of a converged flight, so 1e-4 s is 1000 times finer than any need, and a
/// step of 1e-9 s would make a 7 s flight take 7·10^9 steps (it ran for ever).
const MIN_DT_S: f64 = 1e-4;

/// Smallest exponential spin-decay time constant, s. Measured golf-ball spin decays slowly:
/// time constants of roughly 20–30 s (Smits & Smith 1994, "A new aerodynamic model of a golf
/// ball in flight", Science and Golf II), so 1 s is far below any real ball.
const MIN_SPIN_DECAY_TAU_S: f64 = 1.0;

/// How many integration steps the spin-decay time constant must span: an explicit integrator
/// resolves `exp(-t/τ)` only when the step is a small fraction of τ (at 0.35 s and τ = 0.1 s
/// the flight went silently unstable).
const STEPS_PER_SPIN_DECAY_TAU: f64 = 10.0;

/// Refuse an exponential spin-decay time constant that is unphysical or not resolved by the
/// step (`dt_s`: the `--dt-s` given, else the largest default step).
fn check_spin_decay_tau(tau: f64, dt_s: Option<f64>) -> anyhow::Result<()> {
    let dt = dt_s.unwrap_or(smash::flight::DEFAULT_DT_S);
    let least = MIN_SPIN_DECAY_TAU_S.max(STEPS_PER_SPIN_DECAY_TAU * dt);
    if !(least..=1e4).contains(&tau) {
        anyhow::bail!(
            "--spin-decay exp:{}: TAU must be within [{}, 10000] s (at least \
             {MIN_SPIN_DECAY_TAU_S} s and {STEPS_PER_SPIN_DECAY_TAU} time steps of {} s; \
             measured golf-ball spin-decay constants are about 20–30 s)",
            fmt_value(tau),
            fmt_value(least),
            fmt_value(dt)
        );
    }
    Ok(())
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
    let (flown, conditions) = if let Some(flag) = fitting {
        if !from_file.is_empty() {
            anyhow::bail!(
                "{flag} flies every shot in one atmosphere, but {} states conditions per \
                 shot ({}): set them with --elevation-m, --temperature-c and --humidity-pct",
                args.shots.display(),
                from_file.iter().map(|c| c.1).collect::<Vec<_>>().join(", ")
            );
        }
        match &args.calibrate {
            Some(terms) => (
                calibrate::calibrate_and_fly(&args, &cfg, read, terms)?,
                None,
            ),
            None => {
                let (flown, d) = diagnose::diagnose_and_fly(&args, &cfg, read)?;
                diagnosis = Some(d);
                (flown, None)
            }
        }
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
    let mut report = FlightReport::new(flown, summary, diagnosis);
    report.warnings = warnings;
    if args.json {
        crate::stdout::println(serde_json::to_string_pretty(&report)?)?;
    } else {
        eprint!("\n{}", report.text());
    }
    if let Some(path) = &args.report {
        let html = smash::report::html::flight_page(&report)
            .map_err(|e| anyhow::anyhow!("--report: {e}"))?;
        smash::data::write_atomic(path, html.as_bytes())?;
        eprintln!("report -> {}", path.display());
    }
    Ok(())
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
