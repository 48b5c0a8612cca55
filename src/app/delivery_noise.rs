//! The delivery-noise setting (`--delivery-noise SPEC`): the noise of the measured delivery
//! variables other than the impact location, for regression calibration
//! ([`crate::measurement::DeliveryNoise`]).
//!
//! A spec is a comma-separated list. Its first entry may name an instrument class whose
//! documented delivery noise (`docs/noise-floor.md`) every variable takes, or a multiple of one
//! (`camera`, `2xcamera`: the levels `smash diagnose` offers as `delivery_noise(2x camera)`);
//! `column=SD` entries then set one variable's 1σ in the shots file's unit (`club_speed_mph=0.8`,
//! the keys of a noise file's `[noise.delivery]` table). Variables left out are taken as exact.
//! The impact location's noise is `--impact-noise-mm`. [`spec`] writes a noise back as a list of
//! `column=SD` entries, so the flags `smash diagnose` prints reproduce its selection.

use crate::diagnose::noise_floor::InstrumentClass;
use crate::measurement::DeliveryNoise;
use crate::model::{DeliveryVar, N_DELIVERY};

/// Largest 1σ accepted, file units (as in a noise file).
const MAX_SD: f64 = 1e4;

/// Largest multiple of an instrument class accepted.
const MAX_MULTIPLE: f64 = 100.0;

use crate::report::delivery_noise::settable;

/// A `--delivery-noise` spec refused: what was wrong and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct SpecError(pub String);

fn columns() -> String {
    DeliveryVar::ALL
        .into_iter()
        .filter(|&v| settable(v))
        .map(|v| v.column())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `CLASS` or `KxCLASS` as the class's delivery noise times `K`; `None` when `item` is not of
/// that form (it may then be a `column=SD` entry).
fn class_multiple(item: &str) -> Option<Result<[f64; N_DELIVERY], SpecError>> {
    let class = InstrumentClass::ALL
        .into_iter()
        .find(|c| item.ends_with(c.name()))?;
    let prefix = &item[..item.len() - class.name().len()];
    let k = if prefix.is_empty() {
        1.0
    } else {
        let Some(num) = prefix.strip_suffix('x') else {
            return Some(Err(SpecError(format!(
                "'{item}': a class multiple is written like 2xcamera"
            ))));
        };
        match num.trim().parse::<f64>() {
            Ok(k) if k.is_finite() && (0.0..=MAX_MULTIPLE).contains(&k) => k,
            _ => {
                return Some(Err(SpecError(format!(
                    "'{item}': the multiple must be a number within [0, {MAX_MULTIPLE}]"
                ))))
            }
        }
    };
    let sd = class.noise().delivery_sd.map(|s| s * k);
    Some(Ok(std::array::from_fn(|i| {
        if settable(DeliveryVar::ALL[i]) {
            sd[i]
        } else {
            0.0
        }
    })))
}

/// Parse a `--delivery-noise` spec (see the module docs).
pub fn parse(s: &str) -> Result<DeliveryNoise, SpecError> {
    let mut sd = [0.0; N_DELIVERY];
    let mut set = [false; N_DELIVERY];
    let items: Vec<&str> = s.split(',').map(str::trim).collect();
    for (k, item) in items.iter().enumerate() {
        if let Some(class) = class_multiple(item) {
            if k > 0 {
                return Err(SpecError(format!(
                    "'{item}': an instrument class must come first, before column=SD entries"
                )));
            }
            sd = class?;
            continue;
        }
        let Some((key, value)) = item.split_once('=') else {
            return Err(SpecError(format!(
                "'{item}' is neither an instrument class ({}, or a multiple such as 2xcamera) \
                 nor a column=SD entry",
                InstrumentClass::ALL.map(|c| c.name()).join(", ")
            )));
        };
        let key = key.trim();
        let var = DeliveryVar::from_column(key).ok_or_else(|| {
            SpecError(format!(
                "'{key}' is not a delivery column; allowed: {}",
                columns()
            ))
        })?;
        if !settable(var) {
            return Err(SpecError(format!(
                "'{key}': the impact location's noise is given with --impact-noise-mm"
            )));
        }
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| SpecError(format!("{key}: '{}' is not a number", value.trim())))?;
        if !(v.is_finite() && (0.0..=MAX_SD).contains(&v)) {
            return Err(SpecError(format!(
                "{key} = {}: a standard deviation must be within [0, {MAX_SD}] {}",
                crate::limits::fmt_value(v),
                var.unit()
            )));
        }
        if std::mem::replace(&mut set[var.index()], true) {
            return Err(SpecError(format!(
                "'{key}' is given twice; give each column once"
            )));
        }
        sd[var.index()] = v;
    }
    Ok(DeliveryNoise::new(sd))
}

pub use crate::report::delivery_noise::spec;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_multiples_and_columns() {
        let camera = InstrumentClass::Camera.noise().delivery_sd;
        let speed = DeliveryVar::ClubSpeed.index();
        let loft = DeliveryVar::DynamicLoft.index();
        let y = DeliveryVar::ImpactY.index();
        let n = parse("camera").unwrap();
        assert_eq!(n.sd[speed], camera[speed]);
        assert_eq!(n.sd[y], 0.0, "the location is --impact-noise-mm's");
        let n = parse("2xcamera, dynamic_loft_deg=1.25").unwrap();
        assert_eq!(n.sd[speed], 2.0 * camera[speed]);
        assert_eq!(n.sd[loft], 1.25);
        let n = parse("club_speed_mph=0.8").unwrap();
        assert_eq!(n.sd[speed], 0.8);
        assert_eq!(n.sd[loft], 0.0);
        assert!(!parse("club_speed_mph=0").unwrap().is_active());
    }

    #[test]
    fn a_spec_reads_back_to_the_same_noise() {
        let mut sd = InstrumentClass::Camera.noise().delivery_sd.map(|s| s * 1.5);
        sd[DeliveryVar::ImpactY.index()] = 0.0;
        sd[DeliveryVar::ImpactZ.index()] = 0.0;
        sd[DeliveryVar::FaceAngle.index()] = 0.0;
        let noise = DeliveryNoise::new(sd);
        let text = spec(&noise).unwrap();
        assert!(
            !text.contains("face_angle_deg") && !text.contains("impact"),
            "{text}"
        );
        let back = parse(&text).unwrap();
        for (a, b) in back.sd.iter().zip(&noise.sd) {
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{a} vs {b}");
        }
        assert_eq!(spec(&DeliveryNoise::new([0.0; N_DELIVERY])), None);
    }

    #[test]
    fn bad_specs_say_what_is_allowed() {
        for (bad, says) in [
            ("sonar", "neither an instrument class"),
            ("club_speed=1", "allowed: club_speed_mph"),
            ("impact_y_mm=2", "--impact-noise-mm"),
            ("club_speed_mph=-1", "within [0, 10000] mph"),
            ("club_speed_mph=NaN", "within [0, 10000]"),
            ("club_speed_mph=fast", "not a number"),
            ("club_speed_mph=1,camera", "must come first"),
            ("-2xcamera", "within [0, 100]"),
            ("2camera", "written like 2xcamera"),
        ] {
            let e = parse(bad).unwrap_err().to_string();
            assert!(e.contains(says), "{bad}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }
}
