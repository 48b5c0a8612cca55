//! A delivery noise as `smash diagnose` and `smash calibrate` print it: the spec that
//! `--delivery-noise` reads back, a phrase for the text reports and the JSON object.

use crate::measurement::DeliveryNoise;
use crate::model::DeliveryVar;

/// Is `v` a variable `--delivery-noise` sets (not the impact location, which is
/// `--impact-noise-mm`'s)?
pub fn settable(v: DeliveryVar) -> bool {
    !matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ)
}

/// A value as printed in a spec: to 12 significant digits (`0.6`, not `0.6000000000000001`,
/// for 1.5 × 0.4 mph).
fn tidy(v: f64) -> f64 {
    format!("{v:.11e}").parse().unwrap_or(v)
}

/// The spec of `noise`: its non-zero variables as `column=SD` entries (`None` when no variable
/// the option sets is noisy).
pub fn spec(noise: &DeliveryNoise) -> Option<String> {
    let items: Vec<String> = DeliveryVar::ALL
        .into_iter()
        .filter(|&v| settable(v) && noise.sd[v.index()] > 0.0)
        .map(|v| format!("{}={}", v.column(), tidy(noise.sd[v.index()])))
        .collect();
    (!items.is_empty()).then(|| items.join(","))
}

/// The noise as the "Measurement model:" lines say it: `club_speed_mph 0.4, …`.
pub fn describe(noise: &DeliveryNoise) -> String {
    DeliveryVar::ALL
        .into_iter()
        .filter(|&v| settable(v) && noise.sd[v.index()] > 0.0)
        .map(|v| format!("{} {} {}", v.column(), tidy(noise.sd[v.index()]), v.unit()))
        .collect::<Vec<_>>()
        .join(", ")
}
