//! Unit conversions between file units and the SI units used everywhere inside the engine.
//!
//! Internal quantities are SI (m, kg, s, rad). File columns and TOML keys carry their unit in
//! their name (`_mm`, `_g`, `_mph`, `_deg`, `_rpm`, `_gcm2`); these constants convert them.

/// Metres per millimetre.
pub const M_PER_MM: f64 = 1e-3;
/// Kilograms per gram.
pub const KG_PER_G: f64 = 1e-3;
/// kg·m² per g·cm².
pub const KGM2_PER_GCM2: f64 = 1e-7;
/// m/s per mile per hour (exact by definition of the international mile).
pub const M_S_PER_MPH: f64 = 0.44704;
/// rad/s per revolution per minute.
pub const RAD_S_PER_RPM: f64 = 2.0 * std::f64::consts::PI / 60.0;
/// Radians per degree.
pub const RAD_PER_DEG: f64 = std::f64::consts::PI / 180.0;

/// Millimetres to metres.
#[inline]
pub fn mm(v_mm: f64) -> f64 {
    v_mm * M_PER_MM
}
/// Degrees to radians.
#[inline]
pub fn deg(v_deg: f64) -> f64 {
    v_deg * RAD_PER_DEG
}
/// Miles per hour to metres per second.
#[inline]
pub fn mph(v_mph: f64) -> f64 {
    v_mph * M_S_PER_MPH
}
/// Revolutions per minute to radians per second.
#[inline]
pub fn rpm(v_rpm: f64) -> f64 {
    v_rpm * RAD_S_PER_RPM
}
/// Grams to kilograms.
#[inline]
pub fn g(v_g: f64) -> f64 {
    v_g * KG_PER_G
}
/// g·cm² to kg·m².
#[inline]
pub fn gcm2(v_gcm2: f64) -> f64 {
    v_gcm2 * KGM2_PER_GCM2
}

/// A number as a message shows it: the shortest decimal form that reads back to the same value
/// when that is short (`-5`, `0.0025`, `305`), scientific notation otherwise (`-1e300`, `2.5e-9`),
/// so that a huge or tiny input value is not echoed with hundreds of digits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-5..1e15).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}
