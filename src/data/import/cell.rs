//! One cell of an export, in the one grammar every preset and mapping file shares: a number
//! (with thousands separators, a decimal comma in a decimal-comma file), optionally with a side
//! letter or word before or after it (`5.4 L`, `L5.4`, `2.4° R`, `U 3`, `4.1 I-O`) when the
//! column takes directions, and optionally the column's own unit (`152 mph`, `11.7°`), in any
//! order, case and spacing.

use super::legend::Legend;
use super::units::Unit;

pub(super) use crate::data::shots::list_lines;

/// A row of the export: its 1-based file line and its cells.
pub(super) type Row = (usize, Vec<String>);

/// The directions a column's cells may carry, as `direction = "…"` names them: the words that
/// mean positive and the words that mean negative (compared ignoring case).
pub(super) fn direction_words(
    direction: &str,
) -> Option<(&'static [&'static str], &'static [&'static str])> {
    const R: &[&str] = &["R", "RIGHT", "RT"];
    const L: &[&str] = &["L", "LEFT", "LT"];
    const U: &[&str] = &["U", "UP"];
    const D: &[&str] = &["D", "DOWN", "DN"];
    const IO: &[&str] = &["I-O", "IN-OUT", "IN-TO-OUT", "I/O", "IO"];
    const OI: &[&str] = &["O-I", "OUT-IN", "OUT-TO-IN", "O/I", "OI"];
    const B: &[&str] = &["B", "BACK", "BACKSPIN"];
    const T: &[&str] = &["T", "TOP", "TOPSPIN"];
    Some(match direction {
        "R+" => (R, L),
        "L+" => (L, R),
        "U+" => (U, D),
        "D+" => (D, U),
        "I-O+" => (IO, OI),
        "O-I+" => (OI, IO),
        // Square Golf writes a topped ball's spin `T708`: topspin, negative backspin.
        "B+" => (B, T),
        _ => return None,
    })
}

/// The `direction` values a mapping may give.
pub(super) const DIRECTIONS: [&str; 7] = ["R+", "L+", "U+", "D+", "I-O+", "O-I+", "B+"];

/// Parse a number as an export writes it: `1,234.5` (thousands commas) or, in a file that
/// writes decimal commas, `1.234,5` / `3.083` (thousands dots) and `3,5`. `None`: not a number.
pub(super) fn parse_number(text: &str, decimal_comma: bool) -> Option<f64> {
    let t = text.trim();
    let (thousands, decimal) = if decimal_comma {
        ('.', ',')
    } else {
        (',', '.')
    };
    let body = t.strip_prefix(['-', '+']).unwrap_or(t);
    let int_part = body.split(decimal).next().unwrap_or("");
    let grouped = int_part.contains(thousands) && {
        let groups: Vec<&str> = int_part.split(thousands).collect();
        (1..=3).contains(&groups[0].len())
            && !groups[0].starts_with('0')
            && groups.iter().all(|g| g.bytes().all(|b| b.is_ascii_digit()))
            && groups[1..].iter().all(|g| g.len() == 3)
    };
    let mut s = if grouped {
        t.replace(thousands, "")
    } else {
        t.to_owned()
    };
    if decimal_comma {
        s = s.replace(',', ".");
    }
    if s.contains(',') {
        return None;
    }
    crate::data::number::parse_f64(&s)
}

/// Split a cell into the number's text and the words around it (before and after).
fn split_number(s: &str) -> Option<(&str, &str, &str)> {
    let b = s.as_bytes();
    let start = (0..b.len()).find(|&i| {
        let digit = |j: usize| b.get(j).is_some_and(u8::is_ascii_digit);
        digit(i)
            || (b[i] == b'.' && digit(i + 1))
            || (matches!(b[i], b'-' | b'+')
                && (digit(i + 1) || (b.get(i + 1) == Some(&b'.') && digit(i + 2)))
                // `I-O` and `O-I` are words, not a sign.
                && !(i > 0 && b[i - 1].is_ascii_alphabetic()))
    })?;
    let mut end = start;
    while end < b.len() {
        let c = b[end];
        let ok = c.is_ascii_digit()
            || c == b'.'
            || c == b','
            || ((c == b'-' || c == b'+') && (end == start || matches!(b[end - 1], b'e' | b'E')))
            || ((c == b'e' || c == b'E')
                && end > start
                && b.get(end + 1)
                    .is_some_and(|n| n.is_ascii_digit() || *n == b'-' || *n == b'+'));
        if !ok {
            break;
        }
        end += 1;
    }
    // A trailing separator belongs to no number (`5,` in a list).
    while end > start && matches!(b[end - 1], b',' | b'.') && !b[start..end - 1].is_empty() {
        if b[start..end - 1].iter().any(u8::is_ascii_digit) {
            end -= 1;
        } else {
            break;
        }
    }
    Some((&s[..start], &s[start..end], &s[end..]))
}

/// Why a cell is not a value of its column ([`parse_cell`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CellError {
    /// No number, or words that are neither the column's unit nor a direction.
    #[error("{} is not a number", crate::data::quote_cell(raw))]
    NotANumber {
        /// The cell as read.
        raw: String,
    },
    /// A direction word in a column that takes none.
    #[error("'{raw}': this column does not take L/R, U/D or I-O/O-I directions ('{word}')")]
    NoDirections {
        /// The cell as read.
        raw: String,
        /// The direction word.
        word: String,
    },
    /// A direction word of another kind than the column's, or a second one.
    #[error("'{raw}': '{word}' is not a direction of this column (it takes {} or {})", takes[0], takes[1])]
    NotADirection {
        /// The cell as read.
        raw: String,
        /// The word.
        word: String,
        /// The column's two directions.
        takes: [&'static str; 2],
    },
    /// A unit other than the column's.
    #[error("mixed units: '{raw}' is in {cell_unit} but the column is in {column_unit}")]
    MixedUnits {
        /// The cell as read.
        raw: String,
        /// The cell's unit.
        cell_unit: &'static str,
        /// The column's unit.
        column_unit: &'static str,
    },
    /// A sign and a direction together.
    #[error("'{raw}': both a sign and a direction ('{word}'); write one")]
    SignAndDirection {
        /// The cell as read.
        raw: String,
        /// The direction word.
        word: String,
    },
}

/// Parse one cell: a number, optionally with a direction word before or after it (when the
/// column takes directions: `direction` is one of [`DIRECTIONS`]) and the column's own unit,
/// in any order. Returns the value in the column's unit.
pub(super) fn parse_cell(
    raw: &str,
    unit: Unit,
    direction: Option<&str>,
    decimal_comma: bool,
) -> Result<f64, CellError> {
    let s = raw.trim();
    let not_a_number = || CellError::NotANumber {
        raw: raw.to_owned(),
    };
    let (before, number, after) = split_number(s).ok_or_else(not_a_number)?;
    let v = parse_number(number, decimal_comma).ok_or_else(not_a_number)?;
    let mut words: Vec<String> = before
        .split_whitespace()
        .chain(after.split_whitespace())
        .map(str::to_owned)
        .collect();
    // `2.4°L`, `11.7°R`: a unit glued to a letter.
    let is_side = |w: &str| {
        let upper = w.to_ascii_uppercase();
        ["R+", "U+", "I-O+", "B+"]
            .iter()
            .filter_map(|d| direction_words(d))
            .any(|(p, n)| p.contains(&upper.as_str()) || n.contains(&upper.as_str()))
    };
    if words.len() == 1
        && words[0].len() > 1
        && Unit::parse(&words[0]).is_none()
        && !is_side(&words[0])
    {
        let w = words[0].clone();
        for (i, _) in w.char_indices().skip(1) {
            let (a, b) = w.split_at(i);
            if Unit::parse(a).is_some() && b.chars().all(|c| c.is_ascii_alphabetic()) {
                words = vec![a.to_owned(), b.to_owned()];
                break;
            }
            if Unit::parse(b).is_some() && a.chars().all(|c| c.is_ascii_alphabetic()) {
                words = vec![a.to_owned(), b.to_owned()];
                break;
            }
        }
    }
    let mut letter: Option<bool> = None;
    let mut side_word: Option<String> = None;
    for w in words {
        let upper = w.to_ascii_uppercase();
        // Every family of words, so that a misplaced one is named, not read as a unit.
        if is_side(&w) {
            let Some(words) = direction.and_then(direction_words) else {
                return Err(CellError::NoDirections {
                    raw: raw.to_owned(),
                    word: w,
                });
            };
            let is_pos = words.0.contains(&upper.as_str());
            let is_neg = words.1.contains(&upper.as_str());
            if !(is_pos || is_neg) || letter.is_some() {
                return Err(CellError::NotADirection {
                    raw: raw.to_owned(),
                    word: w,
                    takes: [words.0[0], words.1[0]],
                });
            }
            letter = Some(is_pos);
            side_word = Some(w);
            continue;
        }
        match Unit::parse(&w) {
            Some(u) if u.name == unit.name => {}
            Some(u) => {
                return Err(CellError::MixedUnits {
                    raw: raw.to_owned(),
                    cell_unit: u.name,
                    column_unit: unit.name,
                })
            }
            None => return Err(not_a_number()),
        }
    }
    match letter {
        None => Ok(v),
        Some(_) if number.starts_with(['-', '+']) => Err(CellError::SignAndDirection {
            raw: raw.to_owned(),
            word: side_word.unwrap_or_default(),
        }),
        Some(true) => Ok(v),
        Some(false) => Ok(-v),
    }
}

/// Column names compared without case, spacing or a trailing unit in brackets.
fn normalise(name: &str) -> String {
    name.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase()
}

/// Split `Ball Speed (mph)` / `Carry[yd]` into the name and the bracketed unit. A unit followed
/// by a sign legend, `Push/Pull (deg L-/R+)`, gives the unit ([`header_legend`] gives the legend).
pub(super) fn split_header(h: &str) -> (String, Option<String>) {
    match bracketed(h) {
        Some((name, unit, _)) => (normalise(name), Some(unit.to_owned())),
        None => (normalise(h.trim()), None),
    }
}

/// The sign legend after the unit in a header's brackets (`L-/R+` of `Push/Pull (deg L-/R+)`).
pub(super) fn header_legend(h: &str) -> Option<Legend> {
    bracketed(h).and_then(|(_, _, legend)| legend)
}

/// A header's name, the unit in its trailing brackets and the sign legend after that unit.
fn bracketed(h: &str) -> Option<(&str, &str, Option<Legend>)> {
    let t = h.trim();
    for (open, close) in [('(', ')'), ('[', ']')] {
        let Some(i) = t.ends_with(close).then(|| t.rfind(open)).flatten() else {
            continue;
        };
        let inner = t[i + 1..t.len() - 1].trim();
        if Unit::parse(inner).is_some() {
            return Some((&t[..i], inner, None));
        }
        if let Some((unit, rest)) = inner.split_once(char::is_whitespace) {
            if let (Some(_), Some(legend)) = (Unit::parse(unit), Legend::parse(rest)) {
                return Some((&t[..i], unit, Some(legend)));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_split_units() {
        assert_eq!(
            split_header("Ball Speed (mph)"),
            ("ball speed".into(), Some("mph".into()))
        );
        assert_eq!(
            split_header("Carry[yd]"),
            ("carry".into(), Some("yd".into()))
        );
        assert_eq!(split_header("Dyn.  Loft"), ("dyn. loft".into(), None));
        assert_eq!(
            split_header("Push/Pull (deg L-/R+)"),
            ("push/pull".into(), Some("deg".into()))
        );
        assert_eq!(
            header_legend("Face Impact Horizontal (mm toe-/heel+)").map(|l| l.text()),
            Some("toe-/heel+".into())
        );
        assert_eq!(header_legend("Ball Speed (mph)"), None);
        assert_eq!(split_header("Club (name)"), ("club (name)".into(), None));
    }

    fn deg() -> Unit {
        Unit::parse("deg").unwrap()
    }

    fn p(raw: &str, d: Option<&str>) -> Result<f64, CellError> {
        parse_cell(raw, deg(), d, false)
    }

    #[test]
    fn directions_and_units_in_cells() {
        assert_eq!(p("5.4 L", Some("R+")), Ok(-5.4));
        assert_eq!(p("5.4R", Some("R+")), Ok(5.4));
        assert_eq!(p("L5.4", Some("R+")), Ok(-5.4));
        assert_eq!(p("R 5.4", Some("L+")), Ok(-5.4));
        assert_eq!(p("-2.5", Some("R+")), Ok(-2.5));
        assert_eq!(p("1e-3", None), Ok(1e-3));
        assert!(p("-5.4 L", Some("R+")).is_err());
        assert!(p("5.4 L", None).is_err());
        let mph = Unit::parse("mph").unwrap();
        assert_eq!(parse_cell("152.5 mph", mph, None, false), Ok(152.5));
        let f = Unit::parse("°F").unwrap();
        assert_eq!(parse_cell("77 °F", f, None, false), Ok(77.0));
        assert_eq!(parse_cell("77°F", f, None, false), Ok(77.0));
        let e = parse_cell("245 km/h", mph, None, false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("mixed units"), "{e}");
        assert!(parse_cell("fast", mph, None, false).is_err());
    }

    /// Units and side words in any order, case and spacing; the other families of words.
    #[test]
    fn one_grammar_for_every_cell() {
        for (raw, want) in [
            ("2.4° L", -2.4),
            ("2.4°L", -2.4),
            ("L 2.4°", -2.4),
            ("l2.4 deg", -2.4),
            ("2.4 Left", -2.4),
            ("right 2.4", 2.4),
            ("R 14.3°", 14.3),
            ("14.3 °R", 14.3),
        ] {
            assert_eq!(p(raw, Some("R+")), Ok(want), "{raw}");
        }
        assert_eq!(p("3.1 U", Some("U+")), Ok(3.1));
        assert_eq!(p("T708", Some("B+")), Ok(-708.0));
        assert_eq!(p("B 2650", Some("B+")), Ok(2650.0));
        assert!(p("T708", Some("R+")).is_err());
        assert_eq!(p("D 3.1", Some("U+")), Ok(-3.1));
        assert_eq!(p("4.2 I-O", Some("I-O+")), Ok(4.2));
        assert_eq!(p("4.2° O-I", Some("I-O+")), Ok(-4.2));
        assert_eq!(p("O-I 4.2", Some("I-O+")), Ok(-4.2));
        let e = p("3.1 U", Some("R+")).unwrap_err().to_string();
        assert!(e.contains("takes R or L"), "{e}");
        assert!(p("3 L R", Some("R+")).is_err());
        assert!(p("3 U", None)
            .unwrap_err()
            .to_string()
            .contains("does not take L/R"));
    }

    #[test]
    fn thousands_separators() {
        assert_eq!(parse_number("3,083", false), Some(3083.0));
        assert_eq!(parse_number("-1,234.5", false), Some(-1234.5));
        assert_eq!(parse_number("3.083", true), Some(3083.0));
        assert_eq!(parse_number("1.234,5", true), Some(1234.5));
        assert_eq!(parse_number("3,5", true), Some(3.5));
        assert_eq!(parse_number("0.5", true), Some(0.5));
        assert_eq!(parse_number("0.364", true), Some(0.364));
        assert_eq!(parse_number("3,5", false), None);
        assert_eq!(parse_number("12,34", false), None);
        let rpm = Unit::parse("rpm").unwrap();
        assert_eq!(parse_cell("3.083 rpm", rpm, None, true), Ok(3083.0));
    }
}
