//! Units a launch monitor writes, and their conversion to the shots file's units.
//!
//! Factors are to SI: 1 mph = 0.44704 m/s and 1 yd = 0.9144 m (international yard and mile,
//! exact by definition), 1 ft = 0.3048 m, 1 in = 0.0254 m, 1 km/h = 1/3.6 m/s. Conditions a
//! monitor states: temperature to °C (°F: (F − 32) × 5/9), pressure to Pa (1 psi =
//! 6894.757293168 Pa, from 1 lbf = 4.4482216152605 N and 1 in = 0.0254 m; 1 inHg = 3386.389 Pa,
//! NIST SP 811 appendix B.8; 1 hPa = 1 mbar = 100 Pa), relative humidity in percent.

use crate::units::M_S_PER_MPH;

/// What a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// m/s and friends.
    Speed,
    /// m and friends.
    Length,
    /// Degrees.
    Angle,
    /// Revolutions per minute.
    Spin,
    /// Seconds.
    Time,
    /// Air temperature, °C.
    Temperature,
    /// Air pressure, Pa.
    Pressure,
    /// A percentage (relative humidity).
    Percent,
}

impl Quantity {
    /// Units accepted for this quantity, as written in messages.
    pub fn allowed(self) -> &'static str {
        match self {
            Quantity::Speed => "mph, km/h, m/s",
            Quantity::Length => "m, yd, ft, mm, cm, in",
            Quantity::Angle => "deg",
            Quantity::Spin => "rpm",
            Quantity::Time => "s",
            Quantity::Temperature => "°C, °F",
            Quantity::Pressure => "Pa, hPa, kPa, mbar, psi, inHg",
            Quantity::Percent => "%",
        }
    }
}

/// A unit: what it measures and its size in SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// Canonical spelling (`mph`, `km/h`, `m/s`, `m`, `yd`, `ft`, `mm`, `cm`, `in`, `deg`, `rpm`, `s`).
    pub name: &'static str,
    /// What it measures.
    pub quantity: Quantity,
    /// Size in SI units (m/s, m, deg, rpm, s, °C, Pa, %).
    pub si: f64,
    /// Zero of the unit in SI units (°F: −160/9 °C); 0 for every unit but temperatures.
    pub offset: f64,
}

const UNITS: [Unit; 21] = [
    Unit {
        name: "mph",
        quantity: Quantity::Speed,
        si: M_S_PER_MPH,
        offset: 0.0,
    },
    Unit {
        name: "km/h",
        quantity: Quantity::Speed,
        si: 1.0 / 3.6,
        offset: 0.0,
    },
    Unit {
        name: "m/s",
        quantity: Quantity::Speed,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "m",
        quantity: Quantity::Length,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "yd",
        quantity: Quantity::Length,
        si: 0.9144,
        offset: 0.0,
    },
    Unit {
        name: "ft",
        quantity: Quantity::Length,
        si: 0.3048,
        offset: 0.0,
    },
    Unit {
        name: "mm",
        quantity: Quantity::Length,
        si: 1e-3,
        offset: 0.0,
    },
    Unit {
        name: "cm",
        quantity: Quantity::Length,
        si: 1e-2,
        offset: 0.0,
    },
    Unit {
        name: "in",
        quantity: Quantity::Length,
        si: 0.0254,
        offset: 0.0,
    },
    Unit {
        name: "deg",
        quantity: Quantity::Angle,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "rpm",
        quantity: Quantity::Spin,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "s",
        quantity: Quantity::Time,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "°C",
        quantity: Quantity::Temperature,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "°F",
        quantity: Quantity::Temperature,
        si: 5.0 / 9.0,
        offset: -160.0 / 9.0,
    },
    Unit {
        name: "Pa",
        quantity: Quantity::Pressure,
        si: 1.0,
        offset: 0.0,
    },
    Unit {
        name: "hPa",
        quantity: Quantity::Pressure,
        si: 100.0,
        offset: 0.0,
    },
    Unit {
        name: "kPa",
        quantity: Quantity::Pressure,
        si: 1000.0,
        offset: 0.0,
    },
    Unit {
        name: "mbar",
        quantity: Quantity::Pressure,
        si: 100.0,
        offset: 0.0,
    },
    Unit {
        name: "psi",
        quantity: Quantity::Pressure,
        si: 6894.757293168,
        offset: 0.0,
    },
    Unit {
        name: "inHg",
        quantity: Quantity::Pressure,
        si: 3386.389,
        offset: 0.0,
    },
    Unit {
        name: "%",
        quantity: Quantity::Percent,
        si: 1.0,
        offset: 0.0,
    },
];

impl Unit {
    /// Parse a unit as vendors write it: `mph`, `[mph]`, `(km/h)`, `kph`, `yds`, `°`, `deg`, …
    /// Case and surrounding brackets are ignored. `None` for anything else.
    pub fn parse(text: &str) -> Option<Unit> {
        let t = text
            .trim()
            .trim_start_matches(['[', '('])
            .trim_end_matches([']', ')'])
            .trim()
            .to_ascii_lowercase();
        let canonical = match t.as_str() {
            "mph" | "mi/h" => "mph",
            // `km/t`, `opm`, `sek`: the Norwegian spellings of a Garmin Golf app export.
            "km/h" | "kmh" | "kph" | "kmph" | "km/t" => "km/h",
            "m/s" | "mps" => "m/s",
            "m" | "meter" | "meters" | "metre" | "metres" => "m",
            "yd" | "yds" | "yard" | "yards" => "yd",
            "ft" | "feet" | "foot" => "ft",
            "mm" => "mm",
            "cm" => "cm",
            "in" | "inch" | "inches" | "\"" => "in",
            // `(*)`: FlightScope's web export writes its degree sign as an asterisk.
            "deg" | "°" | "degree" | "degrees" | "º" | "*" => "deg",
            "rpm" | "r/min" | "opm" => "rpm",
            "s" | "sec" | "secs" | "seconds" | "sek" => "s",
            "°c" | "c" | "degc" | "deg c" | "celsius" | "℃" => "°C",
            "°f" | "f" | "degf" | "deg f" | "fahrenheit" | "℉" => "°F",
            "pa" => "Pa",
            "hpa" => "hPa",
            "kpa" => "kPa",
            "mbar" | "mb" => "mbar",
            "psi" => "psi",
            "inhg" | "in hg" => "inHg",
            "%" | "pct" | "percent" => "%",
            _ => return None,
        };
        UNITS.iter().copied().find(|u| u.name == canonical)
    }

    /// `value` in this unit expressed in `to` (same quantity). Identical units return `value`
    /// unchanged, bit for bit.
    pub fn convert(self, value: f64, to: Unit) -> f64 {
        debug_assert_eq!(self.quantity, to.quantity);
        if self.name == to.name {
            value
        } else if self.offset == 0.0 && to.offset == 0.0 {
            value * (self.si / to.si)
        } else {
            (value * self.si + self.offset - to.offset) / to.si
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_vendor_spellings() {
        for (text, name) in [
            ("[mph]", "mph"),
            ("(km/h)", "km/h"),
            ("KPH", "km/h"),
            ("[yds]", "yd"),
            ("°", "deg"),
            ("[deg]", "deg"),
            ("in", "in"),
            ("[rpm]", "rpm"),
        ] {
            assert_eq!(Unit::parse(text).map(|u| u.name), Some(name), "{text}");
        }
        assert!(Unit::parse("furlong").is_none());
        assert!(Unit::parse("").is_none());
    }

    #[test]
    fn conversions_match_definitions() {
        let u = |s| Unit::parse(s).unwrap();
        assert!((u("km/h").convert(160.9344, u("mph")) - 100.0).abs() < 1e-12);
        assert!((u("m/s").convert(44.704, u("mph")) - 100.0).abs() < 1e-12);
        assert!((u("m").convert(0.9144, u("yd")) - 1.0).abs() < 1e-15);
        assert!((u("ft").convert(3.0, u("yd")) - 1.0).abs() < 1e-15);
        assert!((u("in").convert(1.0, u("mm")) - 25.4).abs() < 1e-12);
        assert_eq!(u("mph").convert(0.1, u("mph")), 0.1);
        assert!((u("°F").convert(77.0, u("°C")) - 25.0).abs() < 1e-12);
        assert!((u("[deg F]").convert(32.0, u("°C"))).abs() < 1e-12);
        assert!((u("psi").convert(14.695_948_8, u("Pa")) - 101_325.0).abs() < 0.01);
        assert!((u("kPa").convert(101.325, u("Pa")) - 101_325.0).abs() < 1e-9);
    }
}
