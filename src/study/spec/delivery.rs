//! The `[delivery]` table: the fixed swing of the maps and summaries.

use serde::{Deserialize, Serialize};
use toml::Spanned;

use crate::data::{DataError, TomlDoc};
use crate::model::DeliveryVar;
use crate::study::distribution::SwingSpec;

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDelivery {
    pub club_speed_mph: Spanned<f64>,
    pub dynamic_loft_deg: Spanned<f64>,
    pub attack_angle_deg: Option<Spanned<f64>>,
    pub club_path_deg: Option<Spanned<f64>>,
    pub face_angle_deg: Option<Spanned<f64>>,
    pub lie_tilt_deg: Option<Spanned<f64>>,
    #[serde(default, deserialize_with = "crate::data::toml_check::exact_opt")]
    pub club_omega_rad_s: Option<Spanned<[f64; 3]>>,
}

pub(super) fn parse_delivery(doc: &TomlDoc<'_>, d: &RawDelivery) -> Result<SwingSpec, DataError> {
    let angle = DeliveryVar::AttackAngle.range();
    let opt = |v: &Option<Spanned<f64>>, key: &str| doc.opt_ranged(v, key, angle, 0.0);
    Ok(SwingSpec {
        club_speed_mph: doc.ranged(
            &d.club_speed_mph,
            "delivery.club_speed_mph",
            DeliveryVar::ClubSpeed.range(),
        )?,
        dynamic_loft_deg: doc.ranged(
            &d.dynamic_loft_deg,
            "delivery.dynamic_loft_deg",
            DeliveryVar::DynamicLoft.range(),
        )?,
        attack_angle_deg: opt(&d.attack_angle_deg, "delivery.attack_angle_deg")?,
        club_path_deg: opt(&d.club_path_deg, "delivery.club_path_deg")?,
        face_angle_deg: opt(&d.face_angle_deg, "delivery.face_angle_deg")?,
        lie_tilt_deg: opt(&d.lie_tilt_deg, "delivery.lie_tilt_deg")?,
        club_omega_rad_s: match &d.club_omega_rad_s {
            None => [0.0; 3],
            Some(w) => {
                doc.each_ranged(w, "delivery.club_omega_rad_s", DeliveryVar::OmegaX.range())?
            }
        },
    })
}

/// The swing as a `[delivery]` table, every default written out.
pub(super) fn raw_delivery(w: &SwingSpec) -> RawDelivery {
    let s = |x: f64| Some(Spanned::new(0..0, x));
    RawDelivery {
        club_speed_mph: Spanned::new(0..0, w.club_speed_mph),
        dynamic_loft_deg: Spanned::new(0..0, w.dynamic_loft_deg),
        attack_angle_deg: s(w.attack_angle_deg),
        club_path_deg: s(w.club_path_deg),
        face_angle_deg: s(w.face_angle_deg),
        lie_tilt_deg: s(w.lie_tilt_deg),
        club_omega_rad_s: Some(Spanned::new(0..0, w.club_omega_rad_s)),
    }
}
