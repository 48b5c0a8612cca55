//! The conditions a normalised export states in words (TrackMan's `Condition` column: "Data
//! are normalized to no wind conditions at 0 ft altitude, 77 ℉ with a Premium ball"): the
//! altitude, the air temperature, the ball, and that the flight figures are the vendor's model
//! of the shot in those conditions, not what was tracked.

use super::units::Unit;

/// What a condition statement says.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Condition {
    /// Altitude, m.
    pub altitude_m: Option<f64>,
    /// Air temperature, °C.
    pub temperature_c: Option<f64>,
    /// The ball (`Premium`).
    pub ball: Option<String>,
    /// The data are normalised: carry, side, apex and landing are the vendor's flight model.
    pub normalized: bool,
}

impl Condition {
    /// Read a statement; `None` for an empty cell.
    pub(super) fn parse(text: &str) -> Option<Self> {
        let t = text.trim();
        if t.is_empty() {
            return None;
        }
        let words: Vec<&str> = t
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty())
            .collect();
        let mut c = Condition {
            normalized: t.to_ascii_lowercase().contains("normali"),
            ..Condition::default()
        };
        for (i, w) in words.iter().enumerate() {
            let next = words.get(i + 1).copied().unwrap_or("");
            let after = words.get(i + 2).copied().unwrap_or("");
            let Ok(v) = w.parse::<f64>() else {
                // A number with its unit in one word: `77℉`, `25°C`.
                if let Some((v, unit)) = split_number(w) {
                    c.temperature(v, unit);
                }
                continue;
            };
            if after.eq_ignore_ascii_case("altitude") {
                if let Some(u) = Unit::parse(next).filter(|u| u.name == "ft" || u.name == "m") {
                    c.altitude_m = Some(u.convert(v, Unit::parse("m").expect("m")));
                }
            } else {
                c.temperature(v, next);
            }
        }
        if let Some(i) = words.iter().position(|w| w.eq_ignore_ascii_case("ball")) {
            let start = words[..i]
                .iter()
                .rposition(|w| matches!(w.to_ascii_lowercase().as_str(), "a" | "an" | "with"))
                .map_or(i, |s| s + 1);
            if start < i {
                c.ball = Some(words[start..i].join(" "));
            }
        }
        Some(c)
    }

    /// Take `v unit` as the temperature when `unit` is one.
    fn temperature(&mut self, v: f64, unit: &str) {
        if let Some(u) = Unit::parse(unit).filter(|u| u.name == "°F" || u.name == "°C") {
            self.temperature_c = Some(u.convert(v, Unit::parse("°C").expect("°C")));
        }
    }
}

/// `77℉` → (77, "℉").
fn split_number(word: &str) -> Option<(f64, &str)> {
    let end = word
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter(|&e| e > 0)?;
    Some((word[..end].parse().ok()?, &word[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trackman_statement() {
        let c = Condition::parse(
            "Data are normalized to no wind conditions at 0 ft altitude, 77 ℉ with a Premium ball",
        )
        .unwrap();
        assert!(c.normalized);
        assert_eq!(c.altitude_m, Some(0.0));
        assert!((c.temperature_c.unwrap() - 25.0).abs() < 1e-12);
        assert_eq!(c.ball.as_deref(), Some("Premium"));
        let c = Condition::parse("normalized at 1609 m altitude, 20°C with a Range ball").unwrap();
        assert_eq!(c.altitude_m, Some(1609.0));
        assert_eq!(c.temperature_c, Some(20.0));
        assert_eq!(c.ball.as_deref(), Some("Range"));
        let c = Condition::parse("5000 ft altitude").unwrap();
        assert!(!c.normalized);
        assert!((c.altitude_m.unwrap() - 1524.0).abs() < 1e-9);
        assert!(Condition::parse("  ").is_none());
    }
}
