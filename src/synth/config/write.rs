//! The resolved synth configuration written back as TOML, by serde from the parser's raw
//! structs (so the writer cannot drift from what the parser accepts).

use toml::Spanned;

use super::parse::{
    RawConfig, RawContact, RawDesign, RawFace, RawFaceFlex, RawGroup, RawLoftGain, RawNoise,
    RawOffsetSpeed, RawShaftTip, RawWorld,
};
use super::{SynthConfig, WorldPhysics};
use crate::data::club_file::effect_table;
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;

fn sp<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

/// The resolved configuration as synth-config TOML: every key explicit, the club path as
/// resolved. Parsing it back gives the same configuration (with the club path taken as given).
pub fn config_toml(cfg: &SynthConfig) -> String {
    let groups = cfg
        .groups
        .iter()
        .map(|g| RawGroup {
            name: g.name.clone(),
            shaft_mass_g: g.shaft_mass_g,
        })
        .collect();
    let raw = RawConfig {
        club: Some(cfg.club.to_string_lossy().into_owned()),
        seed: Some(sp(cfg.seed as i64)),
        design: Some(RawDesign {
            golfers: Some(sp(cfg.golfers as i64)),
            swings_per_golfer: Some(sp(cfg.swings_per_golfer as i64)),
            max_redraws_per_shot: Some(sp(cfg.max_redraws_per_shot as i64)),
            groups: Some(sp(groups)),
        }),
        delivery: Some(
            DeliveryVar::ALL
                .iter()
                .map(|v| (v.column().to_owned(), sp(cfg.delivery[v.index()])))
                .collect(),
        ),
        face: Some(RawFace {
            max_abs_y_mm: Some(sp(cfg.max_abs_impact_y_mm)),
            max_abs_z_mm: Some(sp(cfg.max_abs_impact_z_mm)),
        }),
        noise: Some(RawNoise {
            delivery: Some(
                DeliveryVar::ALL
                    .iter()
                    .map(|v| (v.column().to_owned(), sp(cfg.delivery_noise[v.index()])))
                    .collect(),
            ),
            launch: Some(
                LaunchComponent::ALL
                    .iter()
                    .map(|c| (c.column().to_owned(), sp(cfg.launch_noise[*c])))
                    .collect(),
            ),
        }),
        define_effect: hidden_definitions(cfg),
        hidden: cfg.hidden.iter().map(|e| sp(effect_table(e))).collect(),
        world: cfg.world.is_active().then(|| raw_world(&cfg.world)),
        truth: None,
    };
    toml::to_string(&raw).expect("a resolved synth configuration is plain TOML data")
}

/// The definitions of the user-defined effects the configuration hides, each once.
fn hidden_definitions(cfg: &SynthConfig) -> Vec<Spanned<crate::data::effect_defs::RawDefinition>> {
    let mut defined: Vec<&str> = Vec::new();
    let mut out = Vec::new();
    for u in cfg.hidden.iter().filter_map(|e| e.kind().user()) {
        if !defined.contains(&u.name) {
            defined.push(u.name);
            out.push(sp(crate::data::effect_defs::raw_definition_of(u)));
        }
    }
    out
}

fn raw_world(w: &WorldPhysics) -> RawWorld {
    RawWorld {
        cor_power: None,
        face_flex: w.face_flex_per_mm2.map(|(cy, cz)| {
            sp(RawFaceFlex {
                cy_per_mm2: cy,
                cz_per_mm2: cz,
            })
        }),
        offset_speed: w.offset_speed_mm_per_m_s.map(|(ky, kz)| {
            sp(RawOffsetSpeed {
                dy_mm_per_m_s: ky,
                dz_mm_per_m_s: kz,
            })
        }),
        loft_gain: w.loft_gain.map(|gain| sp(RawLoftGain { gain })),
        contact: w.contact.as_ref().map(|c| {
            sp(RawContact {
                hertz_k_n_per_m1_5: Some(c.hertz_k_n_per_m1_5),
                cor_ref: c.cor_ref,
                mu: Some(c.mu),
                tangential_stiffness_ratio: Some(c.tangential_stiffness_ratio),
                tangential_damping_ratio: Some(c.tangential_damping_ratio),
                steps_per_contact: Some(i64::from(c.steps_per_contact)),
                shaft_tip: c.shaft_tip.as_ref().map(|t| RawShaftTip {
                    mass_g: Some(t.mass_g),
                    frequency_hz: Some(t.frequency_hz),
                    damping_ratio: Some(t.damping_ratio),
                    hosel_mm: t.hosel_mm,
                }),
            })
        }),
    }
}
