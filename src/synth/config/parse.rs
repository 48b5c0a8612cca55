//! The synth-config parser: raw structs (also what the writer serializes) and their checks.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::{GroupSpec, Spread, SynthConfig};
use crate::data::club_file::parse_effect_table;
use crate::data::{read_text, DataError, TomlDoc};
use crate::limits::{self, count_product};
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::synth::contact::{ContactParams, ShaftTip};

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawConfig {
    pub club: Option<String>,
    pub seed: Option<Spanned<i64>>,
    pub design: Option<RawDesign>,
    pub delivery: Option<BTreeMap<String, Spanned<Spread>>>,
    pub face: Option<RawFace>,
    pub noise: Option<RawNoise>,
    /// User-defined effects the `[[hidden]]` tables may name (a truth file carries those it
    /// hides, so it regenerates its shots without `--effect-defs`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub define_effect: Vec<Spanned<crate::data::effect_defs::RawDefinition>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden: Vec<Spanned<toml::Table>>,
    pub world: Option<RawWorld>,
    /// Written by `smash synth` into truth files; ignored on input.
    #[serde(skip_serializing)]
    #[allow(dead_code)]
    pub truth: Option<toml::Table>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDesign {
    pub golfers: Option<Spanned<i64>>,
    pub swings_per_golfer: Option<Spanned<i64>>,
    pub max_redraws_per_shot: Option<Spanned<i64>>,
    pub groups: Option<Spanned<Vec<RawGroup>>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGroup {
    pub name: String,
    pub shaft_mass_g: f64,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFace {
    pub max_abs_y_mm: Option<Spanned<f64>>,
    pub max_abs_z_mm: Option<Spanned<f64>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNoise {
    pub delivery: Option<BTreeMap<String, Spanned<f64>>>,
    pub launch: Option<BTreeMap<String, Spanned<f64>>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWorld {
    pub cor_power: Option<Spanned<RawCorPower>>,
    pub face_flex: Option<Spanned<RawFaceFlex>>,
    pub offset_speed: Option<Spanned<RawOffsetSpeed>>,
    pub loft_gain: Option<Spanned<RawLoftGain>>,
    pub contact: Option<Spanned<RawContact>>,
}

#[derive(Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContact {
    pub hertz_k_n_per_m1_5: Option<f64>,
    pub cor_ref: Option<f64>,
    pub mu: Option<f64>,
    pub tangential_stiffness_ratio: Option<f64>,
    pub tangential_damping_ratio: Option<f64>,
    pub steps_per_contact: Option<i64>,
    pub shaft_tip: Option<RawShaftTip>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShaftTip {
    pub mass_g: Option<f64>,
    pub frequency_hz: Option<f64>,
    pub damping_ratio: Option<f64>,
    pub hosel_mm: Option<[f64; 3]>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCorPower {
    pub p: f64,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFaceFlex {
    pub cy_per_mm2: f64,
    pub cz_per_mm2: f64,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOffsetSpeed {
    pub dy_mm_per_m_s: f64,
    pub dz_mm_per_m_s: f64,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoftGain {
    pub gain: f64,
}

/// Largest count of golfers, swings or redraws: no experiment, real or synthetic, is larger.
const MAX_COUNT: i64 = 1_000_000;

/// Largest noise standard deviation, file units.
const MAX_NOISE_SD: f64 = 1e4;

const LAYOUT: &str = "a synth config has top-level club, seed and tables [design], [delivery], \
                      [face], [noise.delivery], [noise.launch], [[define_effect]], [[hidden]], \
                      [world]; see \
                      configs/synth/README.md";

/// Read and validate a synth configuration. The `club` path is resolved relative to the
/// configuration file's folder.
pub fn read_config(path: &Path) -> Result<SynthConfig, DataError> {
    let text = read_text(path)?;
    parse_config(path, &text)
}

/// Parse and validate configuration text (`path` locates the club file and names errors).
pub fn parse_config(path: &Path, text: &str) -> Result<SynthConfig, DataError> {
    let doc = TomlDoc::new(path, text);
    let raw: RawConfig = doc.parse(LAYOUT)?;
    let mut cfg = SynthConfig::default();
    let base = path.parent().unwrap_or(Path::new(""));
    cfg.club = base.join(raw.club.as_deref().unwrap_or("../clubs/paper_driver.toml"));
    if let Some(s) = &raw.seed {
        cfg.seed = doc.count(s, "seed", (0, i64::MAX))? as u64;
    }
    if let Some(d) = &raw.design {
        parse_design(&doc, d, &mut cfg)?;
    }
    for (key, spread) in raw.delivery.iter().flatten() {
        let (var, s) = parse_spread(&doc, key, spread)?;
        cfg.delivery[var.index()] = s;
    }
    if let Some(f) = &raw.face {
        let side =
            |v: &Spanned<f64>, key| doc.within(v.span(), key, *v.get_ref(), (1.0, 100.0), "mm");
        if let Some(v) = &f.max_abs_y_mm {
            cfg.max_abs_impact_y_mm = side(v, "face.max_abs_y_mm")?;
        }
        if let Some(v) = &f.max_abs_z_mm {
            cfg.max_abs_impact_z_mm = side(v, "face.max_abs_z_mm")?;
        }
    }
    if let Some(n) = &raw.noise {
        parse_noise(&doc, n, &mut cfg)?;
    }
    // User-defined effects first, so that [[hidden]] tables can name them: the world's hidden
    // physics, never offered to a diagnosis that runs after in the same process.
    crate::data::effect_defs::register_definitions(
        path,
        text,
        &raw.define_effect,
        crate::effects::user::Offer::WorldOnly,
    )?;
    for (i, t) in raw.hidden.iter().enumerate() {
        cfg.hidden
            .push(parse_effect_table(path, text, "hidden", i, t)?);
    }
    if let Some(w) = &raw.world {
        parse_world(&doc, w, &mut cfg)?;
    }
    Ok(cfg)
}

fn parse_design(doc: &TomlDoc<'_>, d: &RawDesign, cfg: &mut SynthConfig) -> Result<(), DataError> {
    if let Some(v) = &d.golfers {
        cfg.golfers = doc.count(v, "design.golfers", (1, MAX_COUNT))?;
    }
    if let Some(v) = &d.swings_per_golfer {
        cfg.swings_per_golfer = doc.count(v, "design.swings_per_golfer", (1, MAX_COUNT))?;
    }
    if let Some(v) = &d.max_redraws_per_shot {
        cfg.max_redraws_per_shot = doc.count(v, "design.max_redraws_per_shot", (0, MAX_COUNT))?;
    }
    if let Some(g) = &d.groups {
        cfg.groups = parse_groups(doc, g)?;
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
        doc.err(span, "design", e.to_string())
    })?;
    Ok(())
}

fn parse_groups(
    doc: &TomlDoc<'_>,
    g: &Spanned<Vec<RawGroup>>,
) -> Result<Vec<GroupSpec>, DataError> {
    let key = "design.groups";
    if g.get_ref().is_empty() {
        return Err(doc.err(g.span(), key, "needs at least one group"));
    }
    let mut groups: Vec<GroupSpec> = Vec::new();
    for (i, rg) in g.get_ref().iter().enumerate() {
        let k = format!("{key}[{i}]");
        if rg.name.is_empty() || rg.name.contains([',', '"', '\n']) {
            return Err(doc.err(
                g.span(),
                &format!("{k}.name"),
                "must be a non-empty name without commas, quotes or line breaks",
            ));
        }
        if groups.iter().any(|x| x.name == rg.name) {
            return Err(doc.err(
                g.span(),
                &format!("{k}.name"),
                format!("group '{}' is listed twice", rg.name),
            ));
        }
        let m = limits::SHAFT_MASS_G
            .check(rg.shaft_mass_g)
            .map_err(|m| doc.err(g.span(), &format!("{k}.shaft_mass_g"), m))?;
        groups.push(GroupSpec {
            name: rg.name.clone(),
            shaft_mass_g: m,
        });
    }
    Ok(groups)
}

fn delivery_var(
    doc: &TomlDoc<'_>,
    span: std::ops::Range<usize>,
    full: &str,
    key: &str,
) -> Result<DeliveryVar, DataError> {
    let allowed: Vec<(&str, DeliveryVar)> = DeliveryVar::ALL.map(|v| (v.column(), v)).to_vec();
    doc.one_of(span, full, "delivery variable", key, &allowed)
}

fn parse_spread(
    doc: &TomlDoc<'_>,
    key: &str,
    spread: &Spanned<Spread>,
) -> Result<(DeliveryVar, Spread), DataError> {
    let full = format!("delivery.{key}");
    let sp = spread.span();
    let var = delivery_var(doc, sp.clone(), &full, key)?;
    let s = *spread.get_ref();
    let range = var.range();
    range
        .check(s.mean)
        .map_err(|m| doc.err(sp.clone(), &format!("{full}.mean"), m))?;
    // A spread wider than the whole physical range draws nothing but redraws.
    let width = (0.0, range.max - range.min);
    doc.within(
        sp.clone(),
        &format!("{full}.between"),
        s.between,
        width,
        range.unit,
    )?;
    doc.within(sp, &format!("{full}.within"), s.within, width, range.unit)?;
    Ok((var, s))
}

fn parse_noise(doc: &TomlDoc<'_>, n: &RawNoise, cfg: &mut SynthConfig) -> Result<(), DataError> {
    let sd = |v: &Spanned<f64>, key: &str| {
        doc.within(
            v.span(),
            key,
            *v.get_ref(),
            (0.0, MAX_NOISE_SD),
            "(standard deviation)",
        )
    };
    for (key, v) in n.delivery.iter().flatten() {
        let full = format!("noise.delivery.{key}");
        let var = delivery_var(doc, v.span(), &full, key)?;
        cfg.delivery_noise[var.index()] = sd(v, &full)?;
    }
    let components: Vec<(&str, LaunchComponent)> =
        LaunchComponent::ALL.map(|c| (c.column(), c)).to_vec();
    for (key, v) in n.launch.iter().flatten() {
        let full = format!("noise.launch.{key}");
        let c = doc.one_of(v.span(), &full, "launch component", key, &components)?;
        cfg.launch_noise[c] = sd(v, &full)?;
    }
    Ok(())
}

fn parse_world(doc: &TomlDoc<'_>, w: &RawWorld, cfg: &mut SynthConfig) -> Result<(), DataError> {
    if let Some(v) = &w.cor_power {
        // The power-law COR is the library effect `cor_power` now (one definition of it).
        return Err(doc.err(
            v.span(),
            "world.cor_power",
            format!(
                "the power-law COR is the library effect `cor_power`: write [[hidden]] name = \
                 \"cor_power\", q = {:?} instead",
                v.get_ref().p
            ),
        ));
    }
    if let Some(v) = &w.face_flex {
        let (r, sp) = (v.get_ref(), v.span());
        let flex = |x, key| doc.within(sp.clone(), key, x, (0.0, 2e-3), "1/mm²");
        let cy = flex(r.cy_per_mm2, "world.face_flex.cy_per_mm2")?;
        let cz = flex(r.cz_per_mm2, "world.face_flex.cz_per_mm2")?;
        cfg.world.face_flex_per_mm2 = Some((cy, cz));
    }
    if let Some(v) = &w.offset_speed {
        let (r, sp) = (v.get_ref(), v.span());
        let k = |x, key| doc.within(sp.clone(), key, x, (-0.5, 0.5), "mm/(m/s)");
        let ky = k(r.dy_mm_per_m_s, "world.offset_speed.dy_mm_per_m_s")?;
        let kz = k(r.dz_mm_per_m_s, "world.offset_speed.dz_mm_per_m_s")?;
        cfg.world.offset_speed_mm_per_m_s = Some((ky, kz));
    }
    if let Some(v) = &w.loft_gain {
        let gain = v.get_ref().gain;
        cfg.world.loft_gain =
            Some(doc.within(v.span(), "world.loft_gain.gain", gain, (-0.5, 0.5), "")?);
    }
    if let Some(v) = &w.contact {
        cfg.world.contact = Some(parse_contact(doc, v)?);
        if w.cor_power.is_some() || w.face_flex.is_some() || w.offset_speed.is_some() {
            return Err(doc.err(
                v.span(),
                "world.contact",
                "makes its own restitution and ball deformation: it cannot be combined with \
                 world.cor_power, world.face_flex or world.offset_speed (loft_gain is allowed)",
            ));
        }
    }
    Ok(())
}

fn parse_contact(doc: &TomlDoc<'_>, v: &Spanned<RawContact>) -> Result<ContactParams, DataError> {
    let r = v.get_ref();
    let within = |x, key: &str, bounds, unit| {
        doc.within(v.span(), &format!("world.contact.{key}"), x, bounds, unit)
    };
    let mut c = ContactParams::default();
    if let Some(x) = r.hertz_k_n_per_m1_5 {
        c.hertz_k_n_per_m1_5 = within(x, "hertz_k_n_per_m1_5", (1e5, 1e18), "N/m^1.5")?;
    }
    if let Some(x) = r.cor_ref {
        c.cor_ref = Some(within(x, "cor_ref", (0.05, 1.0), "")?);
    }
    if let Some(x) = r.mu {
        c.mu = within(x, "mu", (1e-3, 1e3), "")?;
    }
    if let Some(x) = r.tangential_stiffness_ratio {
        c.tangential_stiffness_ratio = within(x, "tangential_stiffness_ratio", (1e-4, 1e4), "")?;
    }
    if let Some(x) = r.tangential_damping_ratio {
        c.tangential_damping_ratio = within(x, "tangential_damping_ratio", (0.0, 10.0), "")?;
    }
    if let Some(x) = r.steps_per_contact {
        let n = Spanned::new(v.span(), x);
        c.steps_per_contact =
            doc.count(&n, "world.contact.steps_per_contact", (20, 100_000))? as u32;
    }
    if let Some(t) = &r.shaft_tip {
        let mut tip = ShaftTip::default();
        if let Some(x) = t.mass_g {
            tip.mass_g = within(x, "shaft_tip.mass_g", (0.01, 500.0), "g")?;
        }
        if let Some(x) = t.frequency_hz {
            tip.frequency_hz = within(x, "shaft_tip.frequency_hz", (10.0, 1e6), "Hz")?;
        }
        if let Some(x) = t.damping_ratio {
            tip.damping_ratio = within(x, "shaft_tip.damping_ratio", (0.0, 10.0), "")?;
        }
        if let Some(h) = t.hosel_mm {
            for x in h {
                within(x, "shaft_tip.hosel_mm", (-200.0, 200.0), "mm")?;
            }
            tip.hosel_mm = Some(h);
        }
        c.shaft_tip = Some(tip);
    }
    Ok(c)
}
