//! Synthetic experiments: a configured world of golfers, shafts and hidden physics → shots with
//! measured launch, for testing the comparison, diagnosis and calibration against a known truth.
//!
//! Pure: [`generate`] maps a configuration and a base club to shots; reading the configuration
//! ([`config`]) and writing files happen at the edge.
//!
//! ## The world
//!
//! Each golfer `g` has a tendency per delivery variable, `μ_g = mean + between·z_g`, drawn once
//! and shared across groups (the same golfer hits every shaft); each swing is
//! `x = μ_g + within·z_s`. Swings whose impact falls outside the face limits, whose delivery
//! cannot be solved (not approaching the ball) or whose world COR leaves (0, 1] are **redrawn**
//! from the shot's own random stream and counted in [`SynthRun::redrawn`]; more than
//! `max_redraws_per_shot` redraws for one shot is an error.
//!
//! The true launch is computed with the base club plus the hidden library effects and the
//! world-only physics ([`WorldPhysics`]), from the clean delivery. The world-only forms are not in
//! the effect library, so no calibrated club can reproduce them exactly (a power-law COR, once
//! world-only here, is the library effect `cor_power`: hide it with `[[hidden]]`):
//!
//! ```text
//! face_flex     e −= cy·y² + cz·z²                 (y, z in mm; cy ≠ cz: anisotropic)
//! offset_speed  dy, dz += k·(u1n − 48.77 m/s)      (ball flattening grows with speed)
//! loft_gain     δ_true = δ·(1 + gain)
//! contact       the impact integrated in time with a compliant contact (see [`contact`]):
//!               Hertz + Hunt–Crossley normal force, Mindlin tangential spring with a Coulomb
//!               limit, the contact point travelling over the torus face, the head turning,
//!               and optionally a shaft-tip mass on a spring–damper at the hosel
//! ```
//!
//! `u1n` does not depend on the COR or the ball offset, so each shot is solved once to get `u1n`
//! and once more with its own model. The shots file then carries the delivery as measured
//! (clean + motion-capture noise) and the launch as measured (true + launch-monitor noise).
//!
//! ## Reproducibility
//!
//! ChaCha8 streams from the seed: stream 0 draws the golfers' tendencies, stream `k + 1` draws
//! everything of shot `k` (swing scatter, redraws, noise). Results are bit-for-bit identical for
//! the same configuration and seed, on any machine and thread count.

pub mod config;
pub mod contact;
pub mod files;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use crate::club::ClubSpec;
use crate::model::{PerComponent, Shot};
use crate::physics::impact::COR_SPEED_REFERENCE_M_S;
use crate::physics::{Delivery, ImpactError, ImpactModel, Launch, LaunchComponent, ParamError};
use crate::units::{deg, mm, mph, rpm};

pub use contact::{ContactOutcome, ContactParams, ContactWorld, ShaftTip};

pub use crate::model::delivery::{delivery_from_file_units, DeliveryVar, N_DELIVERY};
pub use config::{
    config_toml, parse_config, read_config, GroupSpec, Spread, SynthConfig, WorldPhysics,
};

/// One synthetic shot, file units throughout (mph, deg, rad/s, mm, rpm).
#[derive(Debug, Clone, PartialEq)]
pub struct SynthShot {
    /// Unique id, `<group>-<golfer>-<swing>`.
    pub id: String,
    /// Group (shaft).
    pub group: String,
    /// Golfer, `G01`, `G02`, …
    pub golfer: String,
    /// Shaft mass of the group, g.
    pub shaft_mass_g: f64,
    /// Delivery as swung, in [`DeliveryVar::ALL`] order.
    pub clean_delivery: [f64; N_DELIVERY],
    /// Delivery as measured (clean + measurement noise): what the shots file holds.
    pub delivery: [f64; N_DELIVERY],
    /// True launch, file units.
    pub true_launch: PerComponent<f64>,
    /// Launch as measured (true + launch-monitor noise): what the shots file holds.
    pub launch: PerComponent<f64>,
    /// Normal COR the world used for this shot.
    pub cor_effective: f64,
    /// Normal approach speed `u1n` of this shot in the world, m/s.
    pub normal_approach_speed_m_s: f64,
}

impl SynthShot {
    /// The measured delivery in SI units, converted exactly as `read_shots` converts the file.
    pub fn measured_delivery(&self) -> Delivery {
        Delivery {
            shaft_mass_g: Some(self.shaft_mass_g),
            ..delivery_from_file_units(&self.delivery)
        }
    }

    /// The clean delivery in SI units.
    pub fn true_delivery(&self) -> Delivery {
        Delivery {
            shaft_mass_g: Some(self.shaft_mass_g),
            ..delivery_from_file_units(&self.clean_delivery)
        }
    }

    /// The shot as the engine sees it after reading the shots file.
    pub fn to_shot(&self) -> Shot {
        let l = &self.launch;
        Shot {
            id: self.id.clone(),
            group: self.group.clone(),
            golfer: Some(self.golfer.clone()),
            delivery: self.measured_delivery(),
            measured: Some(Launch {
                ball_speed_m_s: mph(l[0]),
                launch_angle_rad: deg(l[1]),
                azimuth_rad: deg(l[2]),
                backspin_rad_s: rpm(l[3]),
                sidespin_rad_s: rpm(l[4]),
            }),
        }
    }
}

/// A generated experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthRun {
    /// Shots in file order: group, then golfer, then swing.
    pub shots: Vec<SynthShot>,
    /// Swings redrawn because they were off the face or could not be solved.
    pub redrawn: usize,
}

/// Why an experiment cannot be generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SynthError {
    /// The base club with the hidden effects is not physical for a group.
    #[error("the base club with the hidden effects is not physical for group '{group}': {source}")]
    World {
        /// Group.
        group: String,
        /// Problem.
        source: ParamError,
    },
    /// A shot could not be drawn within the redraw limit.
    #[error(
        "shot '{shot_id}': no playable swing in {attempts} draws (last problem: {last}); the \
         delivery spreads or face limits make most swings unplayable"
    )]
    Unplayable {
        /// Shot id.
        shot_id: String,
        /// Draws tried.
        attempts: usize,
        /// Last reason a draw was rejected.
        last: String,
    },
}

/// Why one draw of a swing is not played (the draw is made again; the last reason is reported
/// when none is playable).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Rejection {
    /// The impact lies outside the world's face limits.
    #[error("impact ({y_mm:.1}, {z_mm:.1}) mm is off the face limits")]
    OffFaceLimits {
        /// Vertical location, mm.
        y_mm: f64,
        /// Heel–toe location, mm.
        z_mm: f64,
    },
    /// A club speed that is not positive (the clean one, or the measured one).
    #[error("{}club speed ≤ 0", if *measured { "measured " } else { "" })]
    ClubSpeed {
        /// The measured speed (with its noise), not the clean one.
        measured: bool,
    },
    /// The momentum model cannot solve the delivery.
    #[error(transparent)]
    Impact(#[from] ImpactError),
    /// The world's physics make a head that is not physical for this shot.
    #[error("world model: {0}")]
    WorldModel(ParamError),
    /// The contact world's integration failed.
    #[error(transparent)]
    Contact(#[from] contact::ContactError),
    /// The measured delivery (with its noise) cannot be solved.
    #[error("measured delivery: {0}")]
    MeasuredDelivery(ImpactError),
    /// A value that would not read back from the shots file.
    #[error(transparent)]
    Limit(#[from] crate::limits::LimitError),
}

fn normals<const N: usize>(rng: &mut ChaCha8Rng) -> [f64; N] {
    std::array::from_fn(|_| rng.sample::<f64, _>(StandardNormal))
}

/// The world's impact for one clean delivery: hidden effects (in `model`) plus world physics.
/// Returns the true outcome's launch, the COR used and `u1n`.
pub fn world_impact(
    model: &ImpactModel,
    world: &WorldPhysics,
    clean: &Delivery,
) -> Result<(Launch, f64, f64), Rejection> {
    let mut d = *clean;
    if let Some(g) = world.loft_gain {
        d.dynamic_loft_rad *= 1.0 + g;
    }
    if let Some(c) = &world.contact {
        let cw = ContactWorld::new(model, *c)?;
        return contact_impact(&cw, &d);
    }
    let first = model.solve(&d)?;
    if !world.is_active() {
        return Ok((
            first.launch(),
            first.cor_effective,
            first.normal_approach_speed_m_s,
        ));
    }
    let u1n = first.normal_approach_speed_m_s;
    let mut p = model.params().clone();
    if let Some((cy, cz)) = world.face_flex_per_mm2 {
        let (y, z) = (d.impact_y_m * 1e3, d.impact_z_m * 1e3);
        p.cor -= cy * y * y + cz * z * z;
    }
    if let Some((ky, kz)) = world.offset_speed_mm_per_m_s {
        let dv = u1n - COR_SPEED_REFERENCE_M_S;
        p.ball_offset_y_m += mm(ky * dv);
        p.ball_offset_z_m += mm(kz * dv);
    }
    let shot_model = ImpactModel::new(p).map_err(Rejection::WorldModel)?;
    let out = shot_model.solve(&d)?;
    Ok((
        out.launch(),
        out.cor_effective,
        out.normal_approach_speed_m_s,
    ))
}

/// One shot of a contact world (the loft gain already applied to `d`): launch, COR achieved, `u1n`.
fn contact_impact(cw: &ContactWorld, d: &Delivery) -> Result<(Launch, f64, f64), Rejection> {
    let out = cw.impact(d)?;
    Ok((
        out.launch(),
        out.cor_measured,
        out.normal_approach_speed_m_s,
    ))
}

/// Generate the experiment of `cfg` with `base` as the nominal club (its own effects kept).
pub fn generate(cfg: &SynthConfig, base: &ClubSpec) -> Result<SynthRun, SynthError> {
    let models = group_models(cfg, base)?;
    let tendencies = golfer_tendencies(cfg);
    let width = cfg.golfers.to_string().len().max(2);
    let swing_width = cfg.swings_per_golfer.to_string().len().max(2);
    let mut shots = Vec::with_capacity(cfg.n_shots());
    let mut redrawn = 0;
    let mut k: u64 = 0;
    for (group, models) in cfg.groups.iter().zip(&models) {
        for (golfer, tendency) in tendencies.iter().enumerate() {
            for swing in 0..cfg.swings_per_golfer {
                k += 1;
                let golfer = format!("G{:0width$}", golfer + 1);
                let who = Swinger {
                    id: format!("{}-{}-{:0swing_width$}", group.name, golfer, swing + 1),
                    group,
                    golfer,
                    tendency,
                };
                let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
                rng.set_stream(k);
                let (shot, redraws) = play_shot(cfg, models, &who, &mut rng)?;
                redrawn += redraws;
                shots.push(shot);
            }
        }
    }
    Ok(SynthRun { shots, redrawn })
}

/// The models one group's shots are played with.
struct GroupModels {
    /// The world's: the base club with the hidden effects.
    world: ImpactModel,
    /// The base club's: the engine must be able to solve the measured delivery with it, or
    /// comparing would fail on a shot the world played (such draws are redrawn too).
    base: ImpactModel,
    /// The contact world, when configured (its damping calibrated once per group, not per shot).
    contact: Option<ContactWorld>,
}

/// The models of every group, in `cfg.groups` order.
fn group_models(cfg: &SynthConfig, base: &ClubSpec) -> Result<Vec<GroupModels>, SynthError> {
    let world_error = |group: &str| {
        let group = group.to_owned();
        move |source| SynthError::World { group, source }
    };
    let mut effects = base.effects.clone();
    effects.extend(cfg.hidden.iter().cloned());
    let world_club = base.with_effects(effects).map_err(world_error("all"))?;
    let world: Vec<ImpactModel> = cfg
        .groups
        .iter()
        .map(|g| {
            world_club
                .model_for_group(&g.name)
                .map_err(world_error(&g.name))
        })
        .collect::<Result<_, _>>()?;
    let base: Vec<ImpactModel> = cfg
        .groups
        .iter()
        .map(|g| base.model_for_group(&g.name).map_err(world_error(&g.name)))
        .collect::<Result<_, _>>()?;
    let contact: Vec<Option<ContactWorld>> = world
        .iter()
        .zip(&cfg.groups)
        .map(|(m, g)| {
            cfg.world
                .contact
                .map(|c| {
                    ContactWorld::new(m, c).map_err(|e| {
                        world_error(&g.name)(ParamError {
                            quantity: "world.contact",
                            problem: e.to_string(),
                        })
                    })
                })
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    Ok(world
        .into_iter()
        .zip(base)
        .zip(contact)
        .map(|((world, base), contact)| GroupModels {
            world,
            base,
            contact,
        })
        .collect())
}

/// Each golfer's tendency per delivery variable, `mean + between·z`, drawn from stream 0.
fn golfer_tendencies(cfg: &SynthConfig) -> Vec<[f64; N_DELIVERY]> {
    let mut golfer_rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    golfer_rng.set_stream(0);
    (0..cfg.golfers)
        .map(|_| {
            let z: [f64; N_DELIVERY] = normals(&mut golfer_rng);
            std::array::from_fn(|i| cfg.delivery[i].mean + cfg.delivery[i].between * z[i])
        })
        .collect()
}

/// Who swings a shot: its id, group, golfer and the golfer's tendency.
struct Swinger<'a> {
    id: String,
    group: &'a GroupSpec,
    golfer: String,
    tendency: &'a [f64; N_DELIVERY],
}

/// Draw swings from `rng` until one is playable; returns it and how many were redrawn.
/// More than `max_redraws_per_shot` redraws is an error naming the last problem.
fn play_shot(
    cfg: &SynthConfig,
    models: &GroupModels,
    who: &Swinger,
    rng: &mut ChaCha8Rng,
) -> Result<(SynthShot, usize), SynthError> {
    let mut attempts = 0;
    loop {
        attempts += 1;
        match draw_swing(cfg, models, who, rng) {
            Ok(shot) => return Ok((shot, attempts - 1)),
            Err(why) if attempts > cfg.max_redraws_per_shot => {
                return Err(SynthError::Unplayable {
                    shot_id: who.id.clone(),
                    attempts,
                    last: why.to_string(),
                })
            }
            Err(_) => {}
        }
    }
}

/// One draw of a swing: the clean delivery, its true launch in the world, and the measured
/// delivery and launch with their noise. Rejected (with the reason) when the impact is off the
/// face limits, the club speed is not positive, either model cannot solve it, or a value would
/// not read back from the shots file.
fn draw_swing(
    cfg: &SynthConfig,
    models: &GroupModels,
    who: &Swinger,
    rng: &mut ChaCha8Rng,
) -> Result<SynthShot, Rejection> {
    // Every draw takes all its random numbers first, so a rejection does not shift the stream.
    let z: [f64; N_DELIVERY] = normals(rng);
    let clean: [f64; N_DELIVERY] =
        std::array::from_fn(|i| who.tendency[i] + cfg.delivery[i].within * z[i]);
    let zd: [f64; N_DELIVERY] = normals(rng);
    let zl: [f64; 5] = normals(rng);
    let (impact_y, impact_z) = (
        clean[DeliveryVar::ImpactY.index()],
        clean[DeliveryVar::ImpactZ.index()],
    );
    if impact_y.abs() > cfg.max_abs_impact_y_mm || impact_z.abs() > cfg.max_abs_impact_z_mm {
        return Err(Rejection::OffFaceLimits {
            y_mm: impact_y,
            z_mm: impact_z,
        });
    }
    if !(clean[DeliveryVar::ClubSpeed.index()] > 0.0) {
        return Err(Rejection::ClubSpeed { measured: false });
    }
    let clean_si = Delivery {
        shaft_mass_g: Some(who.group.shaft_mass_g),
        ..delivery_from_file_units(&clean)
    };
    let (truth, cor, u1n) = match &models.contact {
        Some(cw) => {
            let mut d = clean_si;
            if let Some(g) = cfg.world.loft_gain {
                d.dynamic_loft_rad *= 1.0 + g;
            }
            contact_impact(cw, &d)?
        }
        None => world_impact(&models.world, &cfg.world, &clean_si)?,
    };
    let measured: [f64; N_DELIVERY] =
        std::array::from_fn(|i| clean[i] + cfg.delivery_noise[i] * zd[i]);
    if !(measured[DeliveryVar::ClubSpeed.index()] > 0.0) {
        return Err(Rejection::ClubSpeed { measured: true });
    }
    models
        .base
        .solve(&Delivery {
            shaft_mass_g: Some(who.group.shaft_mass_g),
            ..delivery_from_file_units(&measured)
        })
        .map_err(Rejection::MeasuredDelivery)?;
    let true_launch = PerComponent(truth.to_file_units());
    let launch = PerComponent::from_fn(|c| true_launch[c] + cfg.launch_noise[c] * zl[c.index()]);
    // What is written must read back: every value in its physical range.
    for (v, x) in DeliveryVar::ALL.iter().zip(measured) {
        v.range().check(x)?;
    }
    for (c, x) in launch.pairs() {
        crate::data::shots::measured_range(c).check(*x)?;
    }
    Ok(SynthShot {
        id: who.id.clone(),
        group: who.group.name.clone(),
        golfer: who.golfer.clone(),
        shaft_mass_g: who.group.shaft_mass_g,
        clean_delivery: clean,
        delivery: measured,
        true_launch,
        launch,
        cor_effective: cor,
        normal_approach_speed_m_s: u1n,
    })
}

/// Column order of synthetic shots files.
pub fn csv_header() -> Vec<&'static str> {
    let mut h = vec!["shot_id", "group", "golfer", "shaft_mass_g"];
    h.extend(DeliveryVar::ALL.map(|v| v.column()));
    h.extend(LaunchComponent::ALL.map(|c| c.column()));
    h
}
