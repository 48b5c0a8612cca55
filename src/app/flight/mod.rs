//! `flight`: fly launch conditions to landing. The settings of the flight (aerodynamic model,
//! atmosphere, ground, integration) are shared with `predict --flight`. The launch file is
//! flown as a stream ([`stream`]: read, flown and written in chunks, bounded memory) or, when
//! the file states the conditions of each shot, in each shot's own air ([`conditions`]).

pub mod conditions;
pub mod stream;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::data::flight_files::{read_atmosphere, LaunchSource};
use crate::data::launch_read::LaunchRead;
use crate::flight::{AeroModel, Atmosphere, FlightConfig, Ground, SpinDecay};
use crate::limits::fmt_value;
use conditions::UserConditions;

/// The flight's settings: model, atmosphere, ground, integration. Unset values take the
/// defaults their fields name (an atmosphere file sets them all, and a value given here
/// overrides it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FlightSettings {
    /// Aerodynamic coefficient model (`fmm2022`, `fmm2022-tour`, `fmm2022-re`, `nathan-lyu`
    /// or `table:PATH`).
    pub aero: String,
    /// Spin decay: `moment`, `none` or `exp:TAU` (s).
    pub spin_decay: String,
    /// TOML file with an `[atmosphere]` table.
    pub atmosphere: Option<PathBuf>,
    /// Air temperature, °C (default 15).
    pub temperature_c: Option<f64>,
    /// Station pressure, hPa (default: ISA at `elevation_m`, or 1013.25).
    pub pressure_hpa: Option<f64>,
    /// Elevation above sea level, m.
    pub elevation_m: Option<f64>,
    /// Relative humidity, % (default 50).
    pub humidity_pct: Option<f64>,
    /// Wind speed at `wind_height_m`, m/s (default 0).
    pub wind_speed_m_s: Option<f64>,
    /// Direction the wind blows toward, degrees from the target line toward the right.
    pub wind_direction_deg: Option<f64>,
    /// Height of the wind speed, m (default 10).
    pub wind_height_m: Option<f64>,
    /// Roughness length of the ground for the log wind profile, m (default 0.03).
    pub roughness_m: Option<f64>,
    /// Add the total distance with the simple bounce-and-roll model.
    pub total: bool,
    /// Turf coefficient of restitution with `total` (default 0.20).
    pub ground_restitution: Option<f64>,
    /// Effective run-out deceleration with `total`, m/s² (default 12).
    pub roll_decel_m_s2: Option<f64>,
    /// Integration time step, s (default 0.35 in still air, 0.1 in wind).
    pub dt_s: Option<f64>,
    /// Height of a teed ball above the ground, mm (default 0).
    pub tee_mm: Option<f64>,
    /// Longest flight before it is an error, s (default 30).
    pub max_time_s: Option<f64>,
}

impl Default for FlightSettings {
    fn default() -> Self {
        Self {
            aero: crate::flight::aero::MODEL_NAMES[0].to_owned(),
            spin_decay: "moment".to_owned(),
            atmosphere: None,
            temperature_c: None,
            pressure_hpa: None,
            elevation_m: None,
            humidity_pct: None,
            wind_speed_m_s: None,
            wind_direction_deg: None,
            wind_height_m: None,
            roughness_m: None,
            total: false,
            ground_restitution: None,
            roll_decel_m_s2: None,
            dt_s: None,
            tee_mm: None,
            max_time_s: None,
        }
    }
}

/// Settings of `flight` on a launch table: the flight's and which columns to fly.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FlyTableSettings {
    /// The flight.
    #[serde(flatten)]
    pub flight: FlightSettings,
    /// Which launch columns to fly (default: measured if present).
    pub launch: Option<LaunchSource>,
    /// Refuse the whole table at the first row that cannot be used.
    pub strict: bool,
}

/// Fly every launch of `input` (a launch file or CSV text from memory): the flight file's bytes.
pub fn fly_input(
    settings: &FlyTableSettings,
    input: &super::inputs::ShotsInput,
) -> anyhow::Result<Vec<u8>> {
    use super::inputs::ShotsInput;
    match input {
        ShotsInput::File(p) => {
            crate::data::safe_write::note_input(p);
            let text = crate::data::read_text(p)?;
            fly_table(settings, p, text.as_bytes())
        }
        ShotsInput::Csv { label, bytes } => fly_table(settings, label, bytes),
    }
}

/// Fly every launch of the CSV text `bytes` (named `label` in messages): the flight file's
/// bytes (the input columns, the flight's and the errors where measured).
pub fn fly_table(
    settings: &FlyTableSettings,
    label: &Path,
    bytes: &[u8],
) -> anyhow::Result<Vec<u8>> {
    let f = &settings.flight;
    if (f.ground_restitution.is_some() || f.roll_decel_m_s2.is_some()) && !f.total {
        anyhow::bail!(
            "ground_restitution and roll_decel_m_s2 are settings of the total distance: set total \
             too"
        );
    }
    let cfg = settings.flight.config()?;
    let (csv, _) = stream::fly_csv_bytes(
        label,
        bytes,
        &cfg,
        LaunchRead {
            source: settings.launch,
            strict: settings.strict,
            ..Default::default()
        },
    )?;
    Ok(csv)
}

impl FlightSettings {
    /// The first option given on the command line (aero and spin decay: other than their
    /// defaults), as its flag, or `None`: `predict` refuses flight options without `--flight`
    /// rather than ignore them.
    pub fn first_given(&self) -> Option<&'static str> {
        let given = [
            (self.aero != crate::flight::aero::MODEL_NAMES[0], "--aero"),
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
                    crate::data::escape(s)
                ),
            },
        };
        let ground = if self.total {
            let g = Ground {
                restitution: self
                    .ground_restitution
                    .unwrap_or(crate::flight::ground::DEFAULT_RESTITUTION),
                roll_decel_m_s2: self
                    .roll_decel_m_s2
                    .unwrap_or(crate::flight::ground::DEFAULT_ROLL_DECEL_M_S2),
            };
            g.check().map_err(|e| anyhow::anyhow!("--total: {e}"))?;
            Some(g)
        } else {
            None
        };
        if let Some(dt_s) = self.dt_s {
            // Each side of the range has its own reason.
            let why = if dt_s.is_nan() {
                Some("not a number")
            } else if dt_s > MAX_DT_S {
                Some(
                    "a longer step loses accuracy: at 0.4 s the hardest flight model's carry is \
                     already off by over half the 0.02 yd the step is held to",
                )
            } else if dt_s < MIN_DT_S {
                Some(
                    "a smaller step only adds rounding: a 10 s flight would take over 10^5 \
                     steps",
                )
            } else {
                None
            };
            if let Some(why) = why {
                anyhow::bail!(
                    "--dt-s {}: must be within [{MIN_DT_S}, {MAX_DT_S}] s ({why})",
                    fmt_value(dt_s)
                );
            }
        }
        let dt_s = self.dt_s;
        let max_time_s = self.max_time_s.unwrap_or(crate::flight::DEFAULT_MAX_TIME_S);
        if !(max_time_s > 0.0 && max_time_s <= 120.0) {
            anyhow::bail!(
                "--max-time-s {}: must be within (0, 120] s",
                fmt_value(max_time_s)
            );
        }
        let tee_mm = self.tee_mm.unwrap_or(0.0);
        let max_tee_mm = crate::flight::MAX_TEE_HEIGHT_M * 1e3;
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

/// Largest `--dt-s`, s: the step tolerance test in `tests/flight.rs` holds the default 0.35 s
/// step of the hardest model to 0.0087 yd and found 0.4 s already over half the bound
/// ([`crate::flight::DEFAULT_DT_S`]); 0.5 s is the coarsest step a user may ask for, and a
/// step of seconds would jump over the landing of a whole flight.
const MAX_DT_S: f64 = 0.5;

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
    let dt = dt_s.unwrap_or(crate::flight::DEFAULT_DT_S);
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
