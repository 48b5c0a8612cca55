//! Synthetic-experiment configuration (TOML): strict parse, defaults in one place, and the
//! resolved configuration written back as TOML (the truth file).
//!
//! Every section and key is optional; what is left out takes the paper's design and the
//! defaults of [`DeliveryVar`] and [`LaunchComponent`] noise (documented in
//! `configs/synth/README.md`). Unknown keys are errors; every error names the file, line and key.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

use crate::data::club_file::parse_effect_table;
use crate::data::{parse_toml, read_text, toml_key_error, DataError};
use crate::effects::Effect;
use crate::limits::{self, count_product};
use crate::model::{default_launch_noise, DeliveryVar, PerComponent, N_DELIVERY};
use crate::physics::LaunchComponent;

use super::contact::{ContactParams, ShaftTip};

// The synthetic golfer's default scatter of each delivery variable belongs to synth, not to
// the shared definition of the variables (crate::model).
impl DeliveryVar {
    /// Default spread: population mean, golfer-to-golfer SD, swing-to-swing SD (file units).
    ///
    /// Driver values for skilled amateurs (reasoning and sources in `configs/synth/README.md`).
    pub const fn default_spread(self) -> Spread {
        let (mean, between, within) = match self {
            Self::ClubSpeed => (105.0, 8.0, 2.0),
            Self::AttackAngle => (0.0, 3.0, 1.5),
            Self::ClubPath => (0.0, 3.0, 1.5),
            Self::DynamicLoft => (12.0, 2.0, 1.0),
            Self::FaceAngle => (0.0, 2.5, 1.5),
            Self::LieTilt => (0.0, 2.0, 1.0),
            Self::OmegaX => (0.0, 2.0, 1.0),
            Self::OmegaY => (0.0, 3.0, 1.5),
            Self::OmegaZ => (0.0, 2.0, 1.0),
            Self::ImpactY => (0.0, 3.0, 7.0),
            Self::ImpactZ => (0.0, 4.0, 8.0),
        };
        Spread {
            mean,
            between,
            within,
        }
    }
}

/// How one delivery variable scatters: `value = mean + between·z_golfer + within·z_swing`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spread {
    /// Population mean, file unit.
    pub mean: f64,
    /// Standard deviation of golfers' own means about the population mean (≥ 0).
    pub between: f64,
    /// Standard deviation of one golfer's swings about their own mean (≥ 0).
    pub within: f64,
}

/// One group of shots (a shaft, in the paper's design).
#[derive(Debug, Clone, PartialEq)]
pub struct GroupSpec {
    /// Group name written in the `group` column.
    pub name: String,
    /// Shaft mass, g (> 0), written in the `shaft_mass_g` column.
    pub shaft_mass_g: f64,
}

/// World-only physics: forms the effect library does not have, so a model can only approximate
/// them. Each is off when `None`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorldPhysics {
    /// Anisotropic face flex: `e = cor − cy·y² − cz·z²` (y, z in mm), each in [0, 2e-3] 1/mm².
    pub face_flex_per_mm2: Option<(f64, f64)>,
    /// Speed-dependent ball offset (ball flattening): `dy, dz += k·(u1n − 48.77 m/s)`,
    /// mm per m/s, each in [−0.5, 0.5].
    pub offset_speed_mm_per_m_s: Option<(f64, f64)>,
    /// Loft gain: the true dynamic loft is `δ·(1 + gain)`, `gain` in [−0.5, 0.5].
    pub loft_gain: Option<f64>,
    /// Time-integrated compliant contact ([`super::contact`]) in place of the momentum model.
    pub contact: Option<ContactParams>,
}

impl WorldPhysics {
    /// Is any world-only physics switched on?
    pub fn is_active(&self) -> bool {
        self.face_flex_per_mm2.is_some()
            || self.offset_speed_mm_per_m_s.is_some()
            || self.loft_gain.is_some()
            || self.contact.is_some()
    }
}

/// A resolved synthetic-experiment configuration, file units.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthConfig {
    /// Base club file (resolved relative to the config file).
    pub club: PathBuf,
    /// Random seed.
    pub seed: u64,
    /// Number of golfers (≥ 1).
    pub golfers: usize,
    /// Swings each golfer makes with each group's club (≥ 1).
    pub swings_per_golfer: usize,
    /// Groups (shafts), at least one, names unique.
    pub groups: Vec<GroupSpec>,
    /// Delivery scatter per variable, in [`DeliveryVar::ALL`] order.
    pub delivery: [Spread; N_DELIVERY],
    /// Largest |impact y| on the face, mm: swings beyond are redrawn.
    pub max_abs_impact_y_mm: f64,
    /// Largest |impact z| on the face, mm: swings beyond are redrawn.
    pub max_abs_impact_z_mm: f64,
    /// Redraws allowed per shot before giving up (an error: the configuration is unplayable).
    pub max_redraws_per_shot: usize,
    /// Measurement noise SD on the delivery, per variable, file units.
    pub delivery_noise: [f64; N_DELIVERY],
    /// Launch-monitor noise SD, per launch component, file units.
    pub launch_noise: PerComponent<f64>,
    /// Hidden library effects (global or per group).
    pub hidden: Vec<Effect>,
    /// Hidden world-only physics.
    pub world: WorldPhysics,
}

impl Default for SynthConfig {
    /// The paper's design: shafts A, B, C of 74.5, 60.3 and 70.9 g; 20 golfers; 10 swings each.
    fn default() -> Self {
        Self {
            club: PathBuf::from("../clubs/paper_driver.toml"),
            seed: 1,
            golfers: 20,
            swings_per_golfer: 10,
            groups: [("A", 74.5), ("B", 60.3), ("C", 70.9)]
                .map(|(n, m)| GroupSpec {
                    name: n.into(),
                    shaft_mass_g: m,
                })
                .to_vec(),
            delivery: DeliveryVar::ALL.map(DeliveryVar::default_spread),
            max_abs_impact_y_mm: 25.0,
            max_abs_impact_z_mm: 40.0,
            max_redraws_per_shot: 1000,
            delivery_noise: DeliveryVar::ALL.map(DeliveryVar::default_noise),
            launch_noise: PerComponent::from_fn(default_launch_noise),
            hidden: Vec::new(),
            world: WorldPhysics::default(),
        }
    }
}

impl SynthConfig {
    /// Number of shots the design produces.
    pub fn n_shots(&self) -> usize {
        self.groups.len() * self.golfers * self.swings_per_golfer
    }

    /// The same configuration with all measurement noise set to zero.
    pub fn without_noise(mut self) -> Self {
        self.delivery_noise = [0.0; N_DELIVERY];
        self.launch_noise = PerComponent::default();
        self
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    club: Option<String>,
    seed: Option<Spanned<i64>>,
    design: Option<RawDesign>,
    delivery: Option<BTreeMap<String, Spanned<Spread>>>,
    face: Option<RawFace>,
    noise: Option<RawNoise>,
    #[serde(default)]
    hidden: Vec<Spanned<toml::Table>>,
    world: Option<RawWorld>,
    /// Written by `smash synth` into truth files; ignored on input.
    #[allow(dead_code)]
    truth: Option<toml::Table>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDesign {
    golfers: Option<Spanned<i64>>,
    swings_per_golfer: Option<Spanned<i64>>,
    max_redraws_per_shot: Option<Spanned<i64>>,
    groups: Option<Spanned<Vec<RawGroup>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGroup {
    name: String,
    shaft_mass_g: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFace {
    max_abs_y_mm: Option<Spanned<f64>>,
    max_abs_z_mm: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNoise {
    delivery: Option<BTreeMap<String, Spanned<f64>>>,
    launch: Option<BTreeMap<String, Spanned<f64>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWorld {
    cor_power: Option<Spanned<RawCorPower>>,
    face_flex: Option<Spanned<RawFaceFlex>>,
    offset_speed: Option<Spanned<RawOffsetSpeed>>,
    loft_gain: Option<Spanned<RawLoftGain>>,
    contact: Option<Spanned<RawContact>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    hertz_k_n_per_m1_5: Option<f64>,
    cor_ref: Option<f64>,
    mu: Option<f64>,
    tangential_stiffness_ratio: Option<f64>,
    tangential_damping_ratio: Option<f64>,
    steps_per_contact: Option<i64>,
    shaft_tip: Option<RawShaftTip>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShaftTip {
    mass_g: Option<f64>,
    frequency_hz: Option<f64>,
    damping_ratio: Option<f64>,
    hosel_mm: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCorPower {
    p: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFaceFlex {
    cy_per_mm2: f64,
    cz_per_mm2: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOffsetSpeed {
    dy_mm_per_m_s: f64,
    dz_mm_per_m_s: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoftGain {
    gain: f64,
}

struct Ctx<'a> {
    path: &'a Path,
    text: &'a str,
}

impl Ctx<'_> {
    fn err(&self, span: std::ops::Range<usize>, key: &str, msg: impl Into<String>) -> DataError {
        toml_key_error(self.path, self.text, span.start, key, msg)
    }

    /// An integer from `min` to 1,000,000 (no experiment, real or synthetic, is larger).
    fn count(&self, v: &Spanned<i64>, key: &str, min: i64) -> Result<usize, DataError> {
        let x = *v.get_ref();
        if x >= min && x <= 1_000_000 {
            Ok(x as usize)
        } else {
            Err(self.err(
                v.span(),
                key,
                format!("must be an integer from {min} to 1000000, got {x}"),
            ))
        }
    }

    fn in_range(
        &self,
        span: std::ops::Range<usize>,
        key: &str,
        x: f64,
        lo: f64,
        hi: f64,
        unit: &str,
    ) -> Result<f64, DataError> {
        if x.is_finite() && x >= lo && x <= hi {
            Ok(x)
        } else {
            Err(self.err(
                span,
                key,
                format!(
                    "must be a finite number in [{lo}, {hi}] {unit}, got {}",
                    crate::data::Num(x)
                ),
            ))
        }
    }
}

/// Read and validate a synth configuration. The `club` path is resolved relative to the
/// configuration file's folder.
pub fn read_config(path: &Path) -> Result<SynthConfig, DataError> {
    let text = read_text(path)?;
    parse_config(path, &text)
}

/// Parse and validate configuration text (`path` locates the club file and names errors).
pub fn parse_config(path: &Path, text: &str) -> Result<SynthConfig, DataError> {
    let ctx = Ctx { path, text };
    let raw: RawConfig = parse_toml(path, text, "a synth config has top-level club, seed and tables [design], [delivery], [face], [noise.delivery], [noise.launch], [[hidden]], [world]; see configs/synth/README.md")?;
    let mut cfg = SynthConfig::default();
    let base = path.parent().unwrap_or(Path::new(""));
    cfg.club = base.join(raw.club.as_deref().unwrap_or("../clubs/paper_driver.toml"));
    if let Some(s) = &raw.seed {
        if *s.get_ref() < 0 {
            return Err(ctx.err(s.span(), "seed", "must be an integer ≥ 0"));
        }
        cfg.seed = *s.get_ref() as u64;
    }
    if let Some(d) = &raw.design {
        if let Some(v) = &d.golfers {
            cfg.golfers = ctx.count(v, "design.golfers", 1)?;
        }
        if let Some(v) = &d.swings_per_golfer {
            cfg.swings_per_golfer = ctx.count(v, "design.swings_per_golfer", 1)?;
        }
        if let Some(v) = &d.max_redraws_per_shot {
            cfg.max_redraws_per_shot = ctx.count(v, "design.max_redraws_per_shot", 0)?;
        }
        if let Some(g) = &d.groups {
            let key = "design.groups";
            if g.get_ref().is_empty() {
                return Err(ctx.err(g.span(), key, "needs at least one group"));
            }
            let mut groups = Vec::new();
            for (i, rg) in g.get_ref().iter().enumerate() {
                let k = format!("{key}[{i}]");
                if rg.name.is_empty() || rg.name.contains([',', '"', '\n']) {
                    return Err(ctx.err(
                        g.span(),
                        &format!("{k}.name"),
                        "must be a non-empty name without commas, quotes or line breaks",
                    ));
                }
                if groups.iter().any(|x: &GroupSpec| x.name == rg.name) {
                    return Err(ctx.err(
                        g.span(),
                        &format!("{k}.name"),
                        format!("group '{}' is listed twice", rg.name),
                    ));
                }
                let m = limits::SHAFT_MASS_G
                    .check(rg.shaft_mass_g)
                    .map_err(|m| ctx.err(g.span(), &format!("{k}.shaft_mass_g"), m))?;
                groups.push(GroupSpec {
                    name: rg.name.clone(),
                    shaft_mass_g: m,
                });
            }
            cfg.groups = groups;
        }
        count_product(
            "shots",
            &[
                ("groups", cfg.groups.len()),
                ("design.golfers", cfg.golfers),
                ("design.swings_per_golfer", cfg.swings_per_golfer),
            ],
            limits::MAX_SYNTH_SHOTS,
            "every shot is held in memory before the file is written; use fewer golfers or swings",
        )
        .map_err(|e| {
            let span = d
                .golfers
                .as_ref()
                .or(d.swings_per_golfer.as_ref())
                .map_or(0..0, |v| v.span());
            ctx.err(span, "design", e.to_string())
        })?;
    }
    if let Some(map) = &raw.delivery {
        for (key, spread) in map {
            let full = format!("delivery.{key}");
            let var = DeliveryVar::ALL
                .into_iter()
                .find(|v| v.column() == key)
                .ok_or_else(|| {
                    ctx.err(
                        spread.span(),
                        &full,
                        format!("unknown delivery variable; allowed: {}", delivery_keys()),
                    )
                })?;
            let s = *spread.get_ref();
            let sp = spread.span();
            let range = var.range();
            range
                .check(s.mean)
                .map_err(|m| ctx.err(sp.clone(), &format!("{full}.mean"), m))?;
            // A spread wider than the whole physical range draws nothing but redraws.
            let width = range.max - range.min;
            ctx.in_range(
                sp.clone(),
                &format!("{full}.between"),
                s.between,
                0.0,
                width,
                range.unit,
            )?;
            ctx.in_range(
                sp.clone(),
                &format!("{full}.within"),
                s.within,
                0.0,
                width,
                range.unit,
            )?;
            cfg.delivery[var.index()] = s;
        }
    }
    if let Some(f) = &raw.face {
        if let Some(v) = &f.max_abs_y_mm {
            cfg.max_abs_impact_y_mm = ctx.in_range(
                v.span(),
                "face.max_abs_y_mm",
                *v.get_ref(),
                1.0,
                100.0,
                "mm",
            )?;
        }
        if let Some(v) = &f.max_abs_z_mm {
            cfg.max_abs_impact_z_mm = ctx.in_range(
                v.span(),
                "face.max_abs_z_mm",
                *v.get_ref(),
                1.0,
                100.0,
                "mm",
            )?;
        }
    }
    if let Some(n) = &raw.noise {
        for (key, v) in n.delivery.iter().flatten() {
            let full = format!("noise.delivery.{key}");
            let var = DeliveryVar::ALL
                .into_iter()
                .find(|d| d.column() == key)
                .ok_or_else(|| {
                    ctx.err(
                        v.span(),
                        &full,
                        format!("unknown delivery variable; allowed: {}", delivery_keys()),
                    )
                })?;
            cfg.delivery_noise[var.index()] = ctx.in_range(
                v.span(),
                &full,
                *v.get_ref(),
                0.0,
                1e4,
                "(standard deviation)",
            )?;
        }
        for (key, v) in n.launch.iter().flatten() {
            let full = format!("noise.launch.{key}");
            let c = LaunchComponent::ALL
                .into_iter()
                .find(|c| c.column() == key)
                .ok_or_else(|| {
                    let keys: Vec<&str> = LaunchComponent::ALL.iter().map(|c| c.column()).collect();
                    ctx.err(
                        v.span(),
                        &full,
                        format!("unknown launch component; allowed: {}", keys.join(", ")),
                    )
                })?;
            cfg.launch_noise[c] = ctx.in_range(
                v.span(),
                &full,
                *v.get_ref(),
                0.0,
                1e4,
                "(standard deviation)",
            )?;
        }
    }
    for (i, t) in raw.hidden.iter().enumerate() {
        cfg.hidden
            .push(parse_effect_table(path, text, "hidden", i, t)?);
    }
    if let Some(w) = &raw.world {
        if let Some(v) = &w.cor_power {
            // The power-law COR is the library effect `cor_power` now (one definition of it).
            return Err(ctx.err(
                v.span(),
                "world.cor_power",
                format!(
                    "the power-law COR is the library effect `cor_power`: write \
                     [[hidden]] name = \"cor_power\", q = {:?} instead",
                    v.get_ref().p
                ),
            ));
        }
        if let Some(v) = &w.face_flex {
            let r = v.get_ref();
            let cy = ctx.in_range(
                v.span(),
                "world.face_flex.cy_per_mm2",
                r.cy_per_mm2,
                0.0,
                2e-3,
                "1/mm²",
            )?;
            let cz = ctx.in_range(
                v.span(),
                "world.face_flex.cz_per_mm2",
                r.cz_per_mm2,
                0.0,
                2e-3,
                "1/mm²",
            )?;
            cfg.world.face_flex_per_mm2 = Some((cy, cz));
        }
        if let Some(v) = &w.offset_speed {
            let r = v.get_ref();
            let ky = ctx.in_range(
                v.span(),
                "world.offset_speed.dy_mm_per_m_s",
                r.dy_mm_per_m_s,
                -0.5,
                0.5,
                "mm/(m/s)",
            )?;
            let kz = ctx.in_range(
                v.span(),
                "world.offset_speed.dz_mm_per_m_s",
                r.dz_mm_per_m_s,
                -0.5,
                0.5,
                "mm/(m/s)",
            )?;
            cfg.world.offset_speed_mm_per_m_s = Some((ky, kz));
        }
        if let Some(v) = &w.loft_gain {
            cfg.world.loft_gain = Some(ctx.in_range(
                v.span(),
                "world.loft_gain.gain",
                v.get_ref().gain,
                -0.5,
                0.5,
                "",
            )?);
        }
        if let Some(v) = &w.contact {
            cfg.world.contact = Some(parse_contact(&ctx, v)?);
            if w.cor_power.is_some() || w.face_flex.is_some() || w.offset_speed.is_some() {
                return Err(ctx.err(
                    v.span(),
                    "world.contact",
                    "makes its own restitution and ball deformation: it cannot be combined with \
                     world.cor_power, world.face_flex or world.offset_speed (loft_gain is allowed)",
                ));
            }
        }
    }
    Ok(cfg)
}

fn parse_contact(ctx: &Ctx, v: &Spanned<RawContact>) -> Result<ContactParams, DataError> {
    let r = v.get_ref();
    let sp = || v.span();
    let mut c = ContactParams::default();
    if let Some(x) = r.hertz_k_n_per_m1_5 {
        c.hertz_k_n_per_m1_5 = ctx.in_range(
            sp(),
            "world.contact.hertz_k_n_per_m1_5",
            x,
            1e5,
            1e18,
            "N/m^1.5",
        )?;
    }
    if let Some(x) = r.cor_ref {
        c.cor_ref = Some(ctx.in_range(sp(), "world.contact.cor_ref", x, 0.05, 1.0, "")?);
    }
    if let Some(x) = r.mu {
        c.mu = ctx.in_range(sp(), "world.contact.mu", x, 1e-3, 1e3, "")?;
    }
    if let Some(x) = r.tangential_stiffness_ratio {
        c.tangential_stiffness_ratio = ctx.in_range(
            sp(),
            "world.contact.tangential_stiffness_ratio",
            x,
            1e-4,
            1e4,
            "",
        )?;
    }
    if let Some(x) = r.tangential_damping_ratio {
        c.tangential_damping_ratio = ctx.in_range(
            sp(),
            "world.contact.tangential_damping_ratio",
            x,
            0.0,
            10.0,
            "",
        )?;
    }
    if let Some(x) = r.steps_per_contact {
        if !(20..=100_000).contains(&x) {
            return Err(ctx.err(
                sp(),
                "world.contact.steps_per_contact",
                format!("must be an integer from 20 to 100000, got {x}"),
            ));
        }
        c.steps_per_contact = x as u32;
    }
    if let Some(t) = &r.shaft_tip {
        let mut tip = ShaftTip::default();
        if let Some(x) = t.mass_g {
            tip.mass_g =
                ctx.in_range(sp(), "world.contact.shaft_tip.mass_g", x, 0.01, 500.0, "g")?;
        }
        if let Some(x) = t.frequency_hz {
            tip.frequency_hz = ctx.in_range(
                sp(),
                "world.contact.shaft_tip.frequency_hz",
                x,
                10.0,
                1e6,
                "Hz",
            )?;
        }
        if let Some(x) = t.damping_ratio {
            tip.damping_ratio = ctx.in_range(
                sp(),
                "world.contact.shaft_tip.damping_ratio",
                x,
                0.0,
                10.0,
                "",
            )?;
        }
        if let Some(h) = t.hosel_mm {
            for x in h {
                ctx.in_range(
                    sp(),
                    "world.contact.shaft_tip.hosel_mm",
                    x,
                    -200.0,
                    200.0,
                    "mm",
                )?;
            }
            tip.hosel_mm = Some(h);
        }
        c.shaft_tip = Some(tip);
    }
    Ok(c)
}

fn delivery_keys() -> String {
    DeliveryVar::ALL.map(|v| v.column()).join(", ")
}

/// The resolved configuration as synth-config TOML: every key explicit, the club path as
/// resolved. Parsing it back gives the same configuration (with the club path taken as given).
pub fn config_toml(cfg: &SynthConfig) -> String {
    let mut s = String::new();
    let q = |v: &str| toml::Value::String(v.to_owned()).to_string();
    let _ = writeln!(s, "club = {}", q(&cfg.club.to_string_lossy()));
    let _ = writeln!(s, "seed = {}", cfg.seed);
    let _ = writeln!(s, "\n[design]");
    let _ = writeln!(s, "golfers = {}", cfg.golfers);
    let _ = writeln!(s, "swings_per_golfer = {}", cfg.swings_per_golfer);
    let _ = writeln!(s, "max_redraws_per_shot = {}", cfg.max_redraws_per_shot);
    let groups: Vec<String> = cfg
        .groups
        .iter()
        .map(|g| {
            format!(
                "{{ name = {}, shaft_mass_g = {:?} }}",
                q(&g.name),
                g.shaft_mass_g
            )
        })
        .collect();
    let _ = writeln!(s, "groups = [{}]", groups.join(", "));
    let _ = writeln!(
        s,
        "\n[delivery]  # mean, golfer-to-golfer SD, swing-to-swing SD"
    );
    for v in DeliveryVar::ALL {
        let d = cfg.delivery[v.index()];
        let _ = writeln!(
            s,
            "{} = {{ mean = {:?}, between = {:?}, within = {:?} }}",
            v.column(),
            d.mean,
            d.between,
            d.within
        );
    }
    let _ = writeln!(s, "\n[face]");
    let _ = writeln!(s, "max_abs_y_mm = {:?}", cfg.max_abs_impact_y_mm);
    let _ = writeln!(s, "max_abs_z_mm = {:?}", cfg.max_abs_impact_z_mm);
    let _ = writeln!(s, "\n[noise.delivery]  # measurement SD");
    for v in DeliveryVar::ALL {
        let _ = writeln!(s, "{} = {:?}", v.column(), cfg.delivery_noise[v.index()]);
    }
    let _ = writeln!(s, "\n[noise.launch]  # launch-monitor SD");
    for c in LaunchComponent::ALL {
        let _ = writeln!(s, "{} = {:?}", c.column(), cfg.launch_noise[c]);
    }
    let w = &cfg.world;
    if w.is_active() {
        let _ = writeln!(s, "\n[world]");
        if let Some((cy, cz)) = w.face_flex_per_mm2 {
            let _ = writeln!(
                s,
                "face_flex = {{ cy_per_mm2 = {cy:?}, cz_per_mm2 = {cz:?} }}"
            );
        }
        if let Some((ky, kz)) = w.offset_speed_mm_per_m_s {
            let _ = writeln!(
                s,
                "offset_speed = {{ dy_mm_per_m_s = {ky:?}, dz_mm_per_m_s = {kz:?} }}"
            );
        }
        if let Some(g) = w.loft_gain {
            let _ = writeln!(s, "loft_gain = {{ gain = {g:?} }}");
        }
        if let Some(c) = &w.contact {
            let mut parts = vec![
                format!("hertz_k_n_per_m1_5 = {:?}", c.hertz_k_n_per_m1_5),
                format!("mu = {:?}", c.mu),
                format!(
                    "tangential_stiffness_ratio = {:?}",
                    c.tangential_stiffness_ratio
                ),
                format!(
                    "tangential_damping_ratio = {:?}",
                    c.tangential_damping_ratio
                ),
                format!("steps_per_contact = {}", c.steps_per_contact),
            ];
            if let Some(e) = c.cor_ref {
                parts.insert(1, format!("cor_ref = {e:?}"));
            }
            if let Some(t) = &c.shaft_tip {
                let hosel = t.hosel_mm.map_or_else(String::new, |h| {
                    format!(", hosel_mm = [{:?}, {:?}, {:?}]", h[0], h[1], h[2])
                });
                parts.push(format!(
                    "shaft_tip = {{ mass_g = {:?}, frequency_hz = {:?}, damping_ratio = {:?}{hosel} }}",
                    t.mass_g, t.frequency_hz, t.damping_ratio,
                ));
            }
            let _ = writeln!(s, "contact = {{ {} }}", parts.join(", "));
        }
    }
    for e in &cfg.hidden {
        let _ = writeln!(s, "\n[[hidden]]");
        let _ = writeln!(s, "name = \"{}\"", e.kind().name());
        for (spec, v) in e.kind().params().iter().zip(e.values()) {
            let _ = writeln!(s, "{} = {:?}", spec.key, v);
        }
        if let Some(g) = e.group() {
            let _ = writeln!(s, "group = {}", q(g));
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SynthConfig, DataError> {
        parse_config(Path::new("configs/synth/x.toml"), text)
    }

    #[test]
    fn empty_config_is_the_paper_design() {
        let c = parse("").unwrap();
        assert_eq!(c.n_shots(), 600);
        assert_eq!(c.groups.len(), 3);
        assert_eq!(c.groups[1].shaft_mass_g, 60.3);
        assert_eq!(
            c.club,
            Path::new("configs/synth/../clubs/paper_driver.toml")
        );
    }

    #[test]
    fn resolved_config_round_trips() {
        let text = r#"
seed = 7
[design]
golfers = 3
groups = [{ name = "X", shaft_mass_g = 65.0 }]
[delivery]
club_speed_mph = { mean = 95.0, between = 5.0, within = 1.0 }
[noise.launch]
backspin_rpm = 80.0
[world]
face_flex = { cy_per_mm2 = 2e-5, cz_per_mm2 = 8e-5 }
offset_speed = { dy_mm_per_m_s = 0.01, dz_mm_per_m_s = 0.0 }
loft_gain = { gain = 0.05 }
[[hidden]]
name = "added_mass"
dm_g = 2.0
group = "X"
"#;
        let c = parse(text).unwrap();
        assert_eq!(c.delivery[0].mean, 95.0);
        assert_eq!(c.launch_noise[3], 80.0);
        let back = parse_config(Path::new("t.toml"), &config_toml(&c)).unwrap();
        let mut expect = c.clone();
        expect.club = PathBuf::from(c.club.to_string_lossy().as_ref());
        assert_eq!(back, expect);
    }

    #[test]
    fn contact_world_round_trips_and_refuses_other_restitution_forms() {
        let text = "[world]\nloft_gain = { gain = 0.02 }\ncontact = { mu = 0.3, cor_ref = 0.8, \
                    shaft_tip = { mass_g = 3.0, hosel_mm = [-10.0, 12.0, -40.0] } }\n";
        let c = parse(text).unwrap();
        let k = c.world.contact.unwrap();
        assert_eq!(k.mu, 0.3);
        assert_eq!(k.cor_ref, Some(0.8));
        let tip = k.shaft_tip.unwrap();
        assert_eq!((tip.mass_g, tip.hosel_mm.unwrap()[2]), (3.0, -40.0));
        assert_eq!(
            tip.frequency_hz,
            super::super::contact::DEFAULT_TIP_FREQUENCY_HZ
        );
        let back = parse_config(Path::new("t.toml"), &config_toml(&c)).unwrap();
        assert_eq!(back.world, c.world);
        let e =
            parse("[world]\nface_flex = { cy_per_mm2 = 1e-5, cz_per_mm2 = 1e-5 }\ncontact = {}\n")
                .unwrap_err();
        assert!(e.to_string().contains("world.contact"), "{e}");
        let e = parse("[world]\ncontact = { mu = -1.0 }\n").unwrap_err();
        assert!(e.to_string().contains("world.contact.mu"), "{e}");
        let e = parse("[world]\ncontact = { muu = 1.0 }\n").unwrap_err();
        assert!(e.to_string().contains("muu"), "{e}");
    }

    #[test]
    fn errors_name_key_and_line() {
        let cases = [
            ("seed = 1\nbogus = 3\n", "bogus", 2),
            (
                "\n[delivery]\nclub_sped_mph = { mean = 1.0, between = 0.0, within = 0.0 }\n",
                "delivery.club_sped_mph",
                3,
            ),
            (
                "[delivery]\nclub_speed_mph = { mean = 100.0, between = -1.0, within = 0.0 }\n",
                "delivery.club_speed_mph.between",
                2,
            ),
            (
                "[delivery]\nclub_speed_mph = { mean = 100.0, between = 1.0 }\n",
                "within",
                2,
            ),
            ("[design]\ngolfers = 0\n", "design.golfers", 2),
            (
                "[noise.launch]\nbackspin_rpm = -5.0\n",
                "noise.launch.backspin_rpm",
                2,
            ),
            ("[world]\ncor_power = { p = 0.1 }\n", "world.cor_power", 2),
            (
                "[world]\nface_flex = { cy_per_mm2 = 1e-5 }\n",
                "cz_per_mm2",
                2,
            ),
            ("\n\n[[hidden]]\nname = \"added_mass\"\ndm = 2.0\n", "dm", 3),
            (
                "[[hidden]]\nname = \"added_mass\"\ndm_g = 2000.0\n",
                "dm_g",
                1,
            ),
        ];
        for (text, key, line) in cases {
            let e = parse(text).unwrap_err();
            let msg = e.to_string();
            assert!(msg.contains(key), "{msg} should name {key}");
            assert_eq!(e.line, Some(line), "{msg}");
        }
    }
}
