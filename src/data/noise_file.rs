//! Instrument-noise file (TOML): the noise the diagnosis's noise floor assumes.
//!
//! ```toml
//! [noise]
//! instrument = "camera"        # optional base class: camera (default) or radar
//!
//! [noise.delivery]             # 1σ of the measured delivery, file units; any subset
//! club_speed_mph = 0.4
//! impact_y_mm = 2.0
//!
//! [noise.launch]               # 1σ of the launch monitor, file units; any subset
//! backspin_rpm = 100.0
//! ```
//!
//! Keys left out take the base class's value. The `[noise.delivery]` and `[noise.launch]` tables
//! have the keys and meaning of a synth configuration's, so a world's noise can be copied over.
//! Unknown keys are errors naming the file, line and key.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use super::{read_text, DataError, TomlDoc};
use crate::diagnose::noise_floor::{InstrumentClass, InstrumentNoise};
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    noise: RawNoise,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNoise {
    instrument: Option<Spanned<String>>,
    delivery: Option<BTreeMap<String, Spanned<f64>>>,
    launch: Option<BTreeMap<String, Spanned<f64>>>,
}

/// Read an instrument-noise file.
pub fn read_noise_file(path: &Path) -> Result<InstrumentNoise, DataError> {
    parse_noise_file(path, &read_text(path)?)
}

/// Parse an instrument-noise file's text (`path` names it in errors).
pub fn parse_noise_file(path: &Path, text: &str) -> Result<InstrumentNoise, DataError> {
    let doc = TomlDoc::new(path, text);
    let raw: RawFile = doc.parse(
        "a noise file has a [noise] table (optional instrument = \"camera\"|\"radar\") with \
         [noise.delivery] and [noise.launch] standard deviations in file units",
    )?;
    let mut noise = match &raw.noise.instrument {
        None => InstrumentClass::Camera.noise(),
        Some(s) => {
            let classes: Vec<(&str, InstrumentClass)> =
                InstrumentClass::ALL.map(|c| (c.name(), c)).to_vec();
            let what = "instrument class";
            doc.one_of(s.span(), "noise.instrument", what, s.get_ref(), &classes)?
                .noise()
        }
    };
    noise.name = format!("{} (base {})", path.display(), noise.name);
    let sd = |v: &Spanned<f64>, key: &str| {
        doc.within(
            v.span(),
            key,
            *v.get_ref(),
            (0.0, 1e4),
            "(standard deviation)",
        )
    };
    let vars: Vec<(&str, DeliveryVar)> = DeliveryVar::ALL.map(|d| (d.column(), d)).to_vec();
    for (key, v) in raw.noise.delivery.iter().flatten() {
        let full = format!("noise.delivery.{key}");
        let var = doc.one_of(v.span(), &full, "delivery variable", key, &vars)?;
        noise.delivery_sd[var.index()] = sd(v, &full)?;
    }
    let components: Vec<(&str, LaunchComponent)> =
        LaunchComponent::ALL.map(|c| (c.column(), c)).to_vec();
    for (key, v) in raw.noise.launch.iter().flatten() {
        let full = format!("noise.launch.{key}");
        let c = doc.one_of(v.span(), &full, "launch component", key, &components)?;
        noise.launch_sd[c.index()] = sd(v, &full)?;
    }
    Ok(noise)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(t: &str) -> Result<InstrumentNoise, DataError> {
        parse_noise_file(Path::new("noise.toml"), t)
    }

    #[test]
    fn keys_override_the_base_class() {
        let n = parse(
            "[noise]\ninstrument = \"radar\"\n[noise.delivery]\nimpact_y_mm = 2.0\n\
             [noise.launch]\nbackspin_rpm = 90.0\n",
        )
        .unwrap();
        let radar = InstrumentClass::Radar.noise();
        assert_eq!(n.delivery_sd[DeliveryVar::ImpactY.index()], 2.0);
        assert_eq!(
            n.delivery_sd[DeliveryVar::ImpactZ.index()],
            radar.delivery_sd[10]
        );
        assert_eq!(n.launch_sd[3], 90.0);
        assert_eq!(n.launch_sd[0], radar.launch_sd[0]);
    }

    #[test]
    fn errors_name_the_key_and_line() {
        for (text, key, line) in [
            ("[noise]\ninstrument = \"sonar\"\n", "noise.instrument", 2),
            ("[noise.delivery]\nspeed = 1.0\n", "noise.delivery.speed", 2),
            (
                "[noise.launch]\n\nbackspin_rpm = -3.0\n",
                "noise.launch.backspin_rpm",
                3,
            ),
        ] {
            let e = parse(text).unwrap_err().to_string();
            assert!(e.contains(key), "{e}");
            assert!(e.contains(&format!("noise.toml:{line}")), "{e}");
        }
        assert!(parse("[noise]\nfoo = 1\n").is_err());
    }
}
