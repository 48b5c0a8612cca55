//! Synthetic-experiment configuration (TOML): strict parse, defaults in one place, and the
//! resolved configuration written back as TOML (the truth file).
//!
//! Every section and key is optional; what is left out takes the paper's design and the
//! defaults of [`DeliveryVar`] and [`LaunchComponent`] noise (documented in
//! `configs/synth/README.md`). Unknown keys are errors; every error names the file, line and key
//! (through the one validator, [`crate::data::TomlDoc`]). The parser is in `parse.rs`, the
//! writer (serde, from the same raw structs) in `write.rs`.

mod parse;
mod write;

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use crate::effects::Effect;
use crate::model::{default_launch_noise, DeliveryVar, PerComponent, N_DELIVERY};

use super::contact::ContactParams;

pub use parse::{parse_config, read_config};
pub use write::config_toml;

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
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::DataError;
    use std::path::Path;

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
