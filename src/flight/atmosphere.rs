//! The air the ball flies through: density and viscosity from temperature, pressure (or
//! elevation) and humidity, and wind with a logarithmic boundary-layer profile.
//!
//! Formulas, each with its source:
//! - density of moist air: the CIPM-2007 equation (A. Picard, R. S. Davis, M. Gläser and
//!   K. Fujii, "Revised formula for the density of moist air (CIPM-2007)", *Metrologia* 45
//!   (2008) 149–155), with its saturation vapour pressure, enhancement factor and
//!   compressibility factor; CO₂ mole fraction fixed at 0.0004;
//! - pressure from elevation: the International Standard Atmosphere troposphere (ISO 2533:1975;
//!   sea level 101 325 Pa and 288.15 K, lapse rate 6.5 K/km);
//! - dynamic viscosity: Sutherland's law with the constants of F. M. White, *Viscous Fluid
//!   Flow* (3rd ed., 2006, Table 1-2): μ₀ = 1.716e-5 Pa·s at T₀ = 273.15 K, S = 110.4 K.
//!   Humidity changes the viscosity of air by under 1 % at golf conditions and is ignored.
//! - wind: the neutral-stability logarithmic profile `u(h) = u_ref·ln(h/z₀)/ln(h_ref/z₀)`
//!   (e.g. J. R. Garratt, *The Atmospheric Boundary Layer*, 1992, §3.2), zero below `z₀`.

use crate::limits::fmt_value;

/// Universal gas constant used by CIPM-2007, J/(mol·K).
pub const R_GAS_J_MOL_K: f64 = 8.314_472;
/// Molar mass of dry air at CO₂ mole fraction 0.0004 (CIPM-2007), kg/mol.
pub const M_DRY_AIR_KG_MOL: f64 = 28.965_46e-3;
/// Molar mass of water (CIPM-2007), kg/mol.
pub const M_WATER_KG_MOL: f64 = 18.015_28e-3;
/// 0 °C in kelvin.
pub const ZERO_C_K: f64 = 273.15;
/// ISA sea-level pressure, Pa (ISO 2533).
pub const ISA_P0_PA: f64 = 101_325.0;
/// ISA sea-level temperature, K (ISO 2533).
pub const ISA_T0_K: f64 = 288.15;
/// ISA tropospheric lapse rate, K/m (ISO 2533).
pub const ISA_LAPSE_K_M: f64 = 0.0065;
/// Standard gravity, m/s² (CGPM 1901; ISO 80000-3).
pub const G_STANDARD_M_S2: f64 = 9.806_65;
/// Sutherland reference viscosity, Pa·s (White 2006, Table 1-2).
pub const SUTHERLAND_MU0_PA_S: f64 = 1.716e-5;
/// Sutherland reference temperature, K (White 2006).
pub const SUTHERLAND_T0_K: f64 = 273.15;
/// Sutherland constant of air, K (White 2006).
pub const SUTHERLAND_S_K: f64 = 110.4;
/// Default aerodynamic roughness length of a mown fairway, m (open flat grassland, Davenport
/// class "open", as tabulated by J. Wieringa, *Boundary-Layer Meteorology* 63 (1993) 323–363).
pub const DEFAULT_ROUGHNESS_M: f64 = 0.03;
/// Default wind reference height, m: the WMO standard anemometer height (WMO-No. 8, 2018).
pub const DEFAULT_WIND_HEIGHT_M: f64 = 10.0;

/// Allowed ranges (what a golf course on Earth can see; outside them the formulas above are not
/// validated): temperature, °C.
pub const TEMPERATURE_RANGE_C: (f64, f64) = (-30.0, 50.0);
/// Station pressure, hPa (Dead Sea shore to about 4000 m).
pub const PRESSURE_RANGE_HPA: (f64, f64) = (600.0, 1100.0);
/// Elevation, m.
pub const ELEVATION_RANGE_M: (f64, f64) = (-430.0, 4500.0);
/// Relative humidity, %.
pub const HUMIDITY_RANGE_PCT: (f64, f64) = (0.0, 100.0);
/// Wind speed at the reference height, m/s (a gale is about 20 m/s).
pub const WIND_RANGE_M_S: (f64, f64) = (0.0, 30.0);

/// Atmosphere as the user states it (file units in the names). Either pressure or elevation.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Atmosphere {
    /// Air temperature, °C.
    #[serde(default = "default_temperature")]
    pub temperature_c: f64,
    /// Station (not sea-level-corrected) pressure, hPa. Mutually exclusive with elevation.
    #[serde(default)]
    pub pressure_hpa: Option<f64>,
    /// Elevation above sea level, m: the pressure is then the ISA pressure there.
    #[serde(default)]
    pub elevation_m: Option<f64>,
    /// Relative humidity, %.
    #[serde(default = "default_humidity")]
    pub humidity_pct: f64,
    /// Wind speed at `wind_height_m`, m/s.
    #[serde(default)]
    pub wind_speed_m_s: f64,
    /// Direction the wind blows toward, degrees in the horizontal plane of G from the target
    /// line (`x`) toward the right (`z`): 0 = tailwind, 90 = blowing left to right, 180 =
    /// headwind.
    #[serde(default)]
    pub wind_direction_deg: f64,
    /// Height at which the wind speed is given, m.
    #[serde(default = "default_wind_height")]
    pub wind_height_m: f64,
    /// Aerodynamic roughness length of the ground, m.
    #[serde(default = "default_roughness")]
    pub roughness_m: f64,
}

fn default_temperature() -> f64 {
    DEFAULT_TEMPERATURE_C
}
fn default_humidity() -> f64 {
    DEFAULT_HUMIDITY_PCT
}
fn default_wind_height() -> f64 {
    DEFAULT_WIND_HEIGHT_M
}
fn default_roughness() -> f64 {
    DEFAULT_ROUGHNESS_M
}

/// Default temperature, °C: the ISA sea-level value.
pub const DEFAULT_TEMPERATURE_C: f64 = 15.0;
/// Default relative humidity, %.
pub const DEFAULT_HUMIDITY_PCT: f64 = 50.0;

impl Default for Atmosphere {
    /// ISA sea level (15 °C, 1013.25 hPa), 50 % relative humidity, still air.
    fn default() -> Self {
        Self {
            temperature_c: DEFAULT_TEMPERATURE_C,
            pressure_hpa: None,
            elevation_m: None,
            humidity_pct: DEFAULT_HUMIDITY_PCT,
            wind_speed_m_s: 0.0,
            wind_direction_deg: 0.0,
            wind_height_m: DEFAULT_WIND_HEIGHT_M,
            roughness_m: DEFAULT_ROUGHNESS_M,
        }
    }
}

/// Air properties derived from an [`Atmosphere`], SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Air {
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Dynamic viscosity, Pa·s.
    pub viscosity_pa_s: f64,
    /// Wind at the reference height, G frame (x, z) components, m/s.
    pub wind_ref_m_s: [f64; 2],
    /// Reference height of the wind, m.
    pub wind_height_m: f64,
    /// Roughness length, m.
    pub roughness_m: f64,
}

impl Air {
    /// Whether there is any wind.
    pub fn has_wind(&self) -> bool {
        self.wind_ref_m_s != [0.0, 0.0]
    }

    /// Wind (x, z components, m/s) at height `h_m` above the ground: the log profile, zero at
    /// and below the roughness length.
    #[inline]
    pub fn wind_at(&self, h_m: f64) -> [f64; 2] {
        if !(h_m > self.roughness_m) {
            return [0.0, 0.0];
        }
        let f = (h_m / self.roughness_m).ln() / (self.wind_height_m / self.roughness_m).ln();
        [self.wind_ref_m_s[0] * f, self.wind_ref_m_s[1] * f]
    }
}

/// Why an atmosphere is not usable: one key, its value, what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("atmosphere {key} = {}: {allowed}", fmt_value(*value))]
pub struct AtmosphereError {
    /// The key (file name of the quantity).
    pub key: &'static str,
    /// The value given.
    pub value: f64,
    /// What is allowed.
    pub allowed: String,
}

fn check(key: &'static str, value: f64, range: (f64, f64)) -> Result<(), AtmosphereError> {
    if !(value >= range.0 && value <= range.1) {
        return Err(AtmosphereError {
            key,
            value,
            allowed: format!(
                "must be within [{}, {}]",
                fmt_value(range.0),
                fmt_value(range.1)
            ),
        });
    }
    Ok(())
}

impl Atmosphere {
    /// Station pressure, Pa: the stated one, the ISA pressure at the stated elevation, or ISA
    /// sea level.
    pub fn pressure_pa(&self) -> f64 {
        match (self.pressure_hpa, self.elevation_m) {
            (Some(p), _) => p * 100.0,
            (None, Some(h)) => isa_pressure_pa(h),
            (None, None) => ISA_P0_PA,
        }
    }

    /// Check every value and derive the air.
    pub fn air(&self) -> Result<Air, AtmosphereError> {
        check("temperature_c", self.temperature_c, TEMPERATURE_RANGE_C)?;
        check("humidity_pct", self.humidity_pct, HUMIDITY_RANGE_PCT)?;
        if let (Some(_), Some(h)) = (self.pressure_hpa, self.elevation_m) {
            return Err(AtmosphereError {
                key: "elevation_m",
                value: h,
                allowed: "give either pressure_hpa or elevation_m, not both".into(),
            });
        }
        if let Some(p) = self.pressure_hpa {
            check("pressure_hpa", p, PRESSURE_RANGE_HPA)?;
        }
        if let Some(h) = self.elevation_m {
            check("elevation_m", h, ELEVATION_RANGE_M)?;
        }
        check("wind_speed_m_s", self.wind_speed_m_s, WIND_RANGE_M_S)?;
        check(
            "wind_direction_deg",
            self.wind_direction_deg,
            (-360.0, 360.0),
        )?;
        check("roughness_m", self.roughness_m, (1e-4, 1.0))?;
        if !(self.wind_height_m > self.roughness_m && self.wind_height_m <= 100.0) {
            return Err(AtmosphereError {
                key: "wind_height_m",
                value: self.wind_height_m,
                allowed: format!(
                    "must be above the roughness length ({} m) and at most 100 m",
                    fmt_value(self.roughness_m)
                ),
            });
        }
        let t_k = self.temperature_c + ZERO_C_K;
        let p = self.pressure_pa();
        let dir = self.wind_direction_deg.to_radians();
        Ok(Air {
            density_kg_m3: moist_air_density_kg_m3(p, t_k, self.humidity_pct / 100.0),
            viscosity_pa_s: sutherland_viscosity_pa_s(t_k),
            wind_ref_m_s: [
                self.wind_speed_m_s * dir.cos(),
                self.wind_speed_m_s * dir.sin(),
            ],
            wind_height_m: self.wind_height_m,
            roughness_m: self.roughness_m,
        })
    }
}

/// ISA pressure at geopotential elevation `h_m` (troposphere), Pa.
pub fn isa_pressure_pa(h_m: f64) -> f64 {
    // Exponent g·M/(R·L) with the ISA constants (R = 287.052 87 J/(kg·K) for dry air).
    let exponent = G_STANDARD_M_S2 / (287.052_87 * ISA_LAPSE_K_M);
    ISA_P0_PA * (1.0 - ISA_LAPSE_K_M * h_m / ISA_T0_K).powf(exponent)
}

/// Saturation vapour pressure over water (CIPM-2007, after Davis 1992), Pa, at `t_k` kelvin.
pub fn saturation_vapour_pressure_pa(t_k: f64) -> f64 {
    const A: f64 = 1.237_884_7e-5; // K⁻²
    const B: f64 = -1.912_131_6e-2; // K⁻¹
    const C: f64 = 33.937_110_47;
    const D: f64 = -6.343_164_5e3; // K
    (A * t_k * t_k + B * t_k + C + D / t_k).exp()
}

/// Density of moist air (CIPM-2007), kg/m³, at pressure `p_pa`, temperature `t_k` and relative
/// humidity `rh` (0–1).
pub fn moist_air_density_kg_m3(p_pa: f64, t_k: f64, rh: f64) -> f64 {
    let t_c = t_k - ZERO_C_K;
    // Enhancement factor f = α + β·p + γ·t².
    let f = 1.000_62 + 3.14e-8 * p_pa + 5.6e-7 * t_c * t_c;
    let x_v = rh * f * saturation_vapour_pressure_pa(t_k) / p_pa;
    // Compressibility factor.
    let (a0, a1, a2) = (1.581_23e-6, -2.9331e-8, 1.1043e-10);
    let (b0, b1) = (5.707e-6, -2.051e-8);
    let (c0, c1) = (1.9898e-4, -2.376e-6);
    let (d, e) = (1.83e-11, -0.765e-8);
    let z = 1.0
        - p_pa / t_k
            * (a0
                + a1 * t_c
                + a2 * t_c * t_c
                + (b0 + b1 * t_c) * x_v
                + (c0 + c1 * t_c) * x_v * x_v)
        + (p_pa * p_pa) / (t_k * t_k) * (d + e * x_v * x_v);
    p_pa * M_DRY_AIR_KG_MOL / (z * R_GAS_J_MOL_K * t_k)
        * (1.0 - x_v * (1.0 - M_WATER_KG_MOL / M_DRY_AIR_KG_MOL))
}

/// Dynamic viscosity of air by Sutherland's law, Pa·s.
pub fn sutherland_viscosity_pa_s(t_k: f64) -> f64 {
    SUTHERLAND_MU0_PA_S * (t_k / SUTHERLAND_T0_K).powf(1.5) * (SUTHERLAND_T0_K + SUTHERLAND_S_K)
        / (t_k + SUTHERLAND_S_K)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cipm_dry_air_matches_published_values() {
        // Dry air, 20 °C, 101 325 Pa: 1.2041 kg/m³ (CIPM-2007 reference value; also the
        // ISA-derived tables). ISA sea level (15 °C, dry): 1.2250 kg/m³ (ISO 2533, which
        // neglects compressibility, so agreement to 1e-3 relative).
        let r20 = moist_air_density_kg_m3(101_325.0, 293.15, 0.0);
        assert!((r20 - 1.2041).abs() < 5e-4, "{r20}");
        let r15 = moist_air_density_kg_m3(101_325.0, 288.15, 0.0);
        assert!((r15 / 1.2250 - 1.0).abs() < 1e-3, "{r15}");
    }

    #[test]
    fn humid_air_is_lighter_and_saturation_pressure_is_right() {
        // Saturation vapour pressure at 20 °C is 2339 Pa (steam tables: 2.339 kPa).
        let ps = saturation_vapour_pressure_pa(293.15);
        assert!((ps - 2339.0).abs() < 3.0, "{ps}");
        let dry = moist_air_density_kg_m3(101_325.0, 303.15, 0.0);
        let wet = moist_air_density_kg_m3(101_325.0, 303.15, 1.0);
        // At 30 °C saturation lowers density by about 1.5 % (x_v ≈ 0.042, 1 − M_v/M_a ≈ 0.378).
        let drop = 1.0 - wet / dry;
        assert!(drop > 0.012 && drop < 0.018, "{drop}");
    }

    #[test]
    fn isa_pressure_and_viscosity() {
        // ISA at 1000 m: 89 875 Pa; at 2000 m: 79 495 Pa (ISO 2533 tables).
        assert!((isa_pressure_pa(1000.0) - 89_875.0).abs() < 10.0);
        assert!((isa_pressure_pa(2000.0) - 79_495.0).abs() < 10.0);
        // Air at 15 °C: 1.789e-5 Pa·s (ISA table value 1.7894e-5).
        let mu = sutherland_viscosity_pa_s(288.15);
        assert!((mu - 1.7894e-5).abs() < 2e-8, "{mu}");
    }

    #[test]
    fn log_profile() {
        let air = Atmosphere {
            wind_speed_m_s: 5.0,
            wind_direction_deg: 90.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap();
        let w10 = air.wind_at(10.0);
        assert!(w10[0].abs() < 1e-12 && (w10[1] - 5.0).abs() < 1e-12);
        let w1 = air.wind_at(1.0);
        let expect = 5.0 * (1.0f64 / 0.03).ln() / (10.0f64 / 0.03).ln();
        assert!((w1[1] - expect).abs() < 1e-12);
        assert_eq!(air.wind_at(0.01), [0.0, 0.0]);
    }

    #[test]
    fn out_of_range_names_the_key() {
        let e = Atmosphere {
            humidity_pct: 120.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap_err();
        assert_eq!(e.key, "humidity_pct");
        let e = Atmosphere {
            pressure_hpa: Some(1000.0),
            elevation_m: Some(100.0),
            ..Atmosphere::default()
        }
        .air()
        .unwrap_err();
        assert!(e.to_string().contains("not both"));
        let e = Atmosphere {
            temperature_c: f64::NAN,
            ..Atmosphere::default()
        }
        .air()
        .unwrap_err();
        assert_eq!(e.key, "temperature_c");
    }
}
