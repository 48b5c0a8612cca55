//! The one validator of TOML configuration files (club, effects, noise, study and synth files).
//!
//! Every reader deserializes its file into raw structs of [`toml::Spanned`] values with
//! [`TomlDoc::parse`], then checks each value with the methods here. Each refusal is one line
//! naming the file, the line and column of the value, the dotted key, what was wrong and what is
//! allowed (the physical range with its unit, the integer bounds, or the allowed names, with the
//! nearest allowed name when a name looks mistyped):
//!
//! ```text
//! study.toml:7: column 18: key delivery.club_speed_mph: club speed 900 is outside the physical range [1, 250] mph
//! ```

use std::ops::Range;
use std::path::Path;

use toml::Spanned;

use super::{line_col, DataError, Num};
use crate::limits::PhysicalRange;

mod shape;
pub use shape::{exact, exact_opt, FixedShape, ShapeError};

/// A TOML file's text and path: the context of every message about it.
#[derive(Debug, Clone, Copy)]
pub struct TomlDoc<'a> {
    /// The file (named in messages; not read here).
    pub path: &'a Path,
    /// Its text (spans index into it).
    pub text: &'a str,
}

impl<'a> TomlDoc<'a> {
    /// The document `text` of the file `path`.
    pub fn new(path: &'a Path, text: &'a str) -> Self {
        Self { path, text }
    }

    /// Deserialize the whole file into `T` (strict keys and types come from `T`'s serde
    /// attributes). A syntax or schema error names the line, column and key; an unknown key
    /// gets the nearest allowed one; `layout` (what such a file holds) is appended.
    pub fn parse<T: serde::de::DeserializeOwned>(&self, layout: &str) -> Result<T, DataError> {
        parse_toml(self.path, self.text, layout)
    }

    /// An error about `key`, whose value starts at `span.start`.
    pub fn err(&self, span: Range<usize>, key: &str, msg: impl std::fmt::Display) -> DataError {
        toml_key_error(self.path, self.text, span.start, key, msg)
    }

    /// An error about `key` as a whole (a limit on several values together): no line.
    pub fn whole(&self, key: &str, msg: impl std::fmt::Display) -> DataError {
        DataError::at(self.path, None, Some(format!("key {key}")), msg)
    }

    /// A value in its physical range (see [`crate::limits`]).
    pub fn ranged(
        &self,
        v: &Spanned<f64>,
        key: &str,
        range: PhysicalRange,
    ) -> Result<f64, DataError> {
        range
            .check(*v.get_ref())
            .map_err(|m| self.err(v.span(), key, m))
    }

    /// An optional value in its physical range, `default` when absent.
    pub fn opt_ranged(
        &self,
        v: &Option<Spanned<f64>>,
        key: &str,
        range: PhysicalRange,
        default: f64,
    ) -> Result<f64, DataError> {
        v.as_ref()
            .map_or(Ok(default), |v| self.ranged(v, key, range))
    }

    /// Every element of a fixed-length list in one physical range.
    pub fn each_ranged<const N: usize>(
        &self,
        v: &Spanned<[f64; N]>,
        key: &str,
        range: PhysicalRange,
    ) -> Result<[f64; N], DataError> {
        for x in v.get_ref() {
            range.check(*x).map_err(|m| self.err(v.span(), key, m))?;
        }
        Ok(*v.get_ref())
    }

    /// A finite `x` in `[lo, hi]` (in `unit`, which may be empty or a description).
    pub fn within(
        &self,
        span: Range<usize>,
        key: &str,
        x: f64,
        (lo, hi): (f64, f64),
        unit: &str,
    ) -> Result<f64, DataError> {
        if x.is_finite() && x >= lo && x <= hi {
            return Ok(x);
        }
        let unit = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        Err(self.err(
            span,
            key,
            format!(
                "must be a finite number in [{}, {}]{unit}, got {}",
                Num(lo),
                Num(hi),
                Num(x)
            ),
        ))
    }

    /// A finite number (in `unit`).
    pub fn finite(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, DataError> {
        let x = *v.get_ref();
        if x.is_finite() {
            return Ok(x);
        }
        Err(self.err(
            v.span(),
            key,
            format!("must be a finite number ({unit}), got {}", Num(x)),
        ))
    }

    /// A finite number > 0 (in `unit`).
    pub fn positive(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, DataError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            return Ok(x);
        }
        Err(self.err(
            v.span(),
            key,
            format!("must be a finite number > 0 ({unit}), got {}", Num(x)),
        ))
    }

    /// An integer from `lo` to `hi`.
    pub fn count(
        &self,
        v: &Spanned<i64>,
        key: &str,
        (lo, hi): (i64, i64),
    ) -> Result<usize, DataError> {
        let x = *v.get_ref();
        if (lo..=hi).contains(&x) && x >= 0 {
            return Ok(x as usize);
        }
        Err(self.err(
            v.span(),
            key,
            format!("must be an integer from {lo} to {hi}, got {x}"),
        ))
    }

    /// A finite number from a loosely typed value (integer or float), located at `span`.
    pub fn number(&self, v: &toml::Value, span: Range<usize>, key: &str) -> Result<f64, DataError> {
        let x = match v {
            toml::Value::Float(f) => *f,
            toml::Value::Integer(i) => *i as f64,
            other => {
                return Err(self.err(
                    span,
                    key,
                    format!("must be a number, got {}", other.type_str()),
                ))
            }
        };
        if x.is_finite() {
            return Ok(x);
        }
        Err(self.err(span, key, format!("must be finite, got {}", Num(x))))
    }

    /// The entry of `allowed` named `given`, or an error: "unknown `what` 'given' (did you
    /// mean 'x'?); allowed: …".
    pub fn one_of<T: Copy>(
        &self,
        span: Range<usize>,
        key: &str,
        what: &str,
        given: &str,
        allowed: &[(&str, T)],
    ) -> Result<T, DataError> {
        if let Some((_, v)) = allowed.iter().find(|(n, _)| *n == given) {
            return Ok(*v);
        }
        let names: Vec<&str> = allowed.iter().map(|(n, _)| *n).collect();
        Err(self.unknown(span, key, what, given, &names))
    }

    /// The error for a name that is not one of `allowed` (see [`Self::one_of`]).
    pub fn unknown(
        &self,
        span: Range<usize>,
        key: &str,
        what: &str,
        given: &str,
        allowed: &[&str],
    ) -> DataError {
        self.err(span, key, unknown_message(what, given, allowed))
    }
}

/// "unknown `what` 'given' (did you mean 'x'?); allowed: a, b, …".
pub fn unknown_message(what: &str, given: &str, allowed: &[&str]) -> String {
    let hint = did_you_mean(given, allowed.iter().copied())
        .map_or_else(String::new, |m| format!(" (did you mean '{m}'?)"));
    format!(
        "unknown {what} '{}'{hint}; allowed: {}",
        super::escape(given),
        allowed.join(", ")
    )
}

pub use crate::suggest::did_you_mean;

/// Deserialize TOML `text` (strict types and keys come from `T`'s serde attributes). A syntax or
/// schema error names the file, line, column and (when the line has one) the key; an unknown
/// key gets the nearest allowed one; `layout` (what such a file holds) is appended so the message
/// says what is allowed.
pub fn parse_toml<T: serde::de::DeserializeOwned>(
    path: &Path,
    text: &str,
    layout: &str,
) -> Result<T, DataError> {
    toml::from_str(text).map_err(|e| {
        let message = e.message().trim();
        let hint = unknown_field_hint(message);
        let (line, place) = match e.span() {
            Some(span) => {
                let (line, col) = line_col(text, span.start);
                let place = match key_at(text, span.start) {
                    Some(key) => format!("column {col}: key {key}"),
                    None => format!("column {col}"),
                };
                (Some(line), Some(place))
            }
            None => (None, None),
        };
        let message = short_floats(message);
        DataError::at(path, line, place, format!("{message}{hint} ({layout})"))
    })
}

/// `message` with the floats serde quotes (`floating point \`1000…000.0\``, every digit of 1e308
/// written out) in their shortest form.
fn short_floats(message: &str) -> String {
    const TAG: &str = "floating point `";
    let Some(at) = message.find(TAG) else {
        return message.to_owned();
    };
    let start = at + TAG.len();
    let Some(len) = message[start..].find('`') else {
        return message.to_owned();
    };
    match message[start..start + len].parse::<f64>() {
        Ok(v) => format!(
            "{}{}{}",
            &message[..start],
            crate::limits::fmt_value(v),
            &message[start + len..]
        ),
        Err(_) => message.to_owned(),
    }
}

/// An error about the TOML key `key` whose value sits at byte `offset` of `text`.
pub fn toml_key_error(
    path: &Path,
    text: &str,
    offset: usize,
    key: &str,
    message: impl std::fmt::Display,
) -> DataError {
    let (line, col) = line_col(text, offset);
    DataError::at(
        path,
        Some(line),
        Some(format!("column {col}: key {key}")),
        message,
    )
}

/// For serde's "unknown field `x`, expected one of `a`, `b`", the nearest allowed field.
fn unknown_field_hint(message: &str) -> String {
    let Some(rest) = message.strip_prefix("unknown field `") else {
        return String::new();
    };
    let Some((given, expected)) = rest.split_once('`') else {
        return String::new();
    };
    let candidates = expected.split('`').skip(1).step_by(2);
    did_you_mean(given, candidates).map_or_else(String::new, |m| format!(" (did you mean `{m}`?)"))
}

/// The dotted key written on the line holding byte `offset`: the table header above it and the
/// key before the line's `=` (or the header itself, on a header line). `None` when the line is
/// neither (a value continued over several lines).
pub(crate) fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = text[start..].lines().next().unwrap_or("").trim();
    let header_of = |l: &str| -> Option<String> {
        let l = l.trim();
        let inner = l.strip_prefix('[')?;
        let inner = inner.strip_prefix('[').unwrap_or(inner);
        let end = inner.find(']')?;
        Some(inner[..end].trim().to_owned())
    };
    if line.starts_with('[') {
        return header_of(line);
    }
    let (left, _) = line.split_once('=')?;
    let key = left.trim().trim_matches('"');
    let is_key = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if !is_key {
        return None;
    }
    let header = text[..start]
        .lines()
        .rev()
        .find(|l| l.trim_start().starts_with('['))
        .and_then(header_of);
    Some(match header {
        Some(h) => format!("{h}.{key}"),
        None => key.to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::CLUB_SPEED_MPH;
    use serde::Deserialize;

    const PATH: &str = "cfg.toml";

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Raw {
        delivery: RawDelivery,
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct RawDelivery {
        club_speed_mph: Spanned<f64>,
        nodes: Option<Spanned<i64>>,
        method: Option<Spanned<String>>,
    }

    fn doc(text: &str) -> TomlDoc<'_> {
        TomlDoc::new(Path::new(PATH), text)
    }

    const TEXT: &str = "# a comment\n[delivery]\nclub_speed_mph =   900.0\nnodes = 0\n\
                        method = \"quadrture\"\n";

    #[test]
    fn range_refusal_names_position_key_value_range_and_unit() {
        let d = doc(TEXT);
        let raw: Raw = d.parse("layout").unwrap();
        let e = d
            .ranged(
                &raw.delivery.club_speed_mph,
                "delivery.club_speed_mph",
                CLUB_SPEED_MPH,
            )
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "cfg.toml:3: column 20: key delivery.club_speed_mph: club speed 900 is outside the \
             physical range [1, 250] mph"
        );
        let ok = "[delivery]\nclub_speed_mph = 100\n";
        let raw: Raw = doc(ok).parse("layout").unwrap();
        let v = doc(ok).ranged(&raw.delivery.club_speed_mph, "k", CLUB_SPEED_MPH);
        assert_eq!(v, Ok(100.0));
    }

    #[test]
    fn within_states_bounds_and_unit_and_refuses_non_finite() {
        let d = doc(TEXT);
        let e = d.within(0..0, "k", -1.0, (0.0, 2e-3), "1/mm²").unwrap_err();
        assert!(
            e.message
                .contains("must be a finite number in [0, 0.002] 1/mm², got -1"),
            "{e}"
        );
        assert!(d.within(0..0, "k", f64::NAN, (0.0, 1.0), "").is_err());
        assert!(d
            .within(0..0, "k", f64::INFINITY, (0.0, f64::MAX), "")
            .is_err());
        assert_eq!(d.within(0..0, "k", 1.0, (0.0, 1.0), ""), Ok(1.0));
        assert!(d.positive(&Spanned::new(0..0, 0.0), "k", "mm").is_err());
        assert!(d.finite(&Spanned::new(0..0, f64::NAN), "k", "mm").is_err());
    }

    #[test]
    fn count_refusal_points_at_the_value() {
        let d = doc(TEXT);
        let raw: Raw = d.parse("layout").unwrap();
        let e = d
            .count(
                raw.delivery.nodes.as_ref().unwrap(),
                "delivery.nodes",
                (1, 20),
            )
            .unwrap_err();
        assert_eq!(e.line, Some(4));
        assert_eq!(
            e.to_string(),
            "cfg.toml:4: column 9: key delivery.nodes: must be an integer from 1 to 20, got 0"
        );
        let ok = Spanned::new(0..0, 20);
        assert_eq!(d.count(&ok, "k", (1, 20)), Ok(20));
    }

    #[test]
    fn allowed_set_suggests_the_nearest_name() {
        let d = doc(TEXT);
        let raw: Raw = d.parse("layout").unwrap();
        let m = raw.delivery.method.unwrap();
        let allowed = [("quadrature", 1), ("samples", 2)];
        let e = d
            .one_of(m.span(), "delivery.method", "method", m.get_ref(), &allowed)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "cfg.toml:5: column 10: key delivery.method: unknown method 'quadrture' (did you \
             mean 'quadrature'?); allowed: quadrature, samples"
        );
        assert_eq!(d.one_of(0..0, "k", "m", "samples", &allowed), Ok(2));
        // Nothing near: no suggestion, still the allowed set.
        let e = d.one_of(0..0, "k", "method", "xyz", &allowed).unwrap_err();
        assert!(
            e.message
                .ends_with("unknown method 'xyz'; allowed: quadrature, samples"),
            "{e}"
        );
    }

    #[test]
    fn unknown_key_names_line_column_key_and_the_nearest_field() {
        let text = "[delivery]\nclub_speed_mph = 100.0\nnodez = 3\n";
        let e = doc(text).parse::<Raw>("the layout").unwrap_err();
        let s = e.to_string();
        assert!(
            s.starts_with("cfg.toml:3: column 1: key delivery.nodez: "),
            "{s}"
        );
        assert!(s.contains("unknown field `nodez`"), "{s}");
        assert!(s.contains("(did you mean `nodes`?)"), "{s}");
        assert!(s.ends_with("(the layout)"), "{s}");
    }

    #[test]
    fn wrong_type_names_line_column_and_key() {
        let text = "[delivery]\n\nclub_speed_mph = \"fast\"\n";
        let e = doc(text).parse::<Raw>("layout").unwrap_err();
        let s = e.to_string();
        assert!(
            s.starts_with("cfg.toml:3: column 18: key delivery.club_speed_mph: "),
            "{s}"
        );
        assert!(
            s.contains("invalid type: string \"fast\", expected f64"),
            "{s}"
        );
        let e = doc("[delivery]\nnodes = 2\n")
            .parse::<Raw>("layout")
            .unwrap_err();
        assert!(
            e.to_string().contains("missing field `club_speed_mph`"),
            "{e}"
        );
    }

    #[test]
    fn number_accepts_integers_and_refuses_other_types() {
        let d = doc(TEXT);
        assert_eq!(d.number(&toml::Value::Integer(3), 0..0, "k"), Ok(3.0));
        let e = d
            .number(&toml::Value::String("x".into()), 12..12, "grid.y_mm")
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "cfg.toml:2: column 1: key grid.y_mm: must be a number, got string"
        );
    }

    #[test]
    fn key_at_reads_headers_and_keys() {
        let t = "a = 1\n[x.y]\nb = 2\n[[h]]\n\"c\" = 3\n";
        assert_eq!(key_at(t, 0).as_deref(), Some("a"));
        assert_eq!(key_at(t, 6).as_deref(), Some("x.y"));
        assert_eq!(key_at(t, 14).as_deref(), Some("x.y.b"));
        assert_eq!(key_at(t, t.len() - 2).as_deref(), Some("h.c"));
    }
}
