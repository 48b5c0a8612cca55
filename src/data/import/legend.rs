//! Sign legends in a header's brackets: Foresight's FSX Play and FSX Live exports write a
//! column's unit and which way its sign points together, `Push/Pull (deg L-/R+)`,
//! `Club Path (deg out-in-/in-out+)`, `Face Impact Horizontal (mm toe-/heel+)`. The unit is read
//! as any bracketed unit is ([`super::cell::split_header`]); the legend fixes the sign of a
//! column with a direction (it wins over the mapping's `direction`, and a legend that names
//! other sides refuses the file) and the side of a positive heel–toe impact offset (so no
//! `--impact-offset-positive` is needed, and one that says otherwise refuses the file).

use super::OffsetSide;

impl OffsetSide {
    /// `toe` or `heel`.
    pub fn word(self) -> &'static str {
        match self {
            Self::Toe => "toe",
            Self::Heel => "heel",
        }
    }
}

/// A header's sign legend: the words of the negative and of the positive side, lower case.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Legend {
    pub negative: String,
    pub positive: String,
}

/// The side family a word belongs to and whether it is that family's positive side in the
/// shots file (right, in-to-out and open are + for a right-handed golfer, up is +).
fn side(word: &str) -> Option<(&'static str, bool)> {
    Some(match word {
        "r" | "right" => ("lateral", true),
        "l" | "left" => ("lateral", false),
        "in-out" | "in-to-out" => ("lateral", true),
        "out-in" | "out-to-in" => ("lateral", false),
        "open" => ("lateral", true),
        "closed" => ("lateral", false),
        "u" | "up" | "high" => ("vertical", true),
        "d" | "down" | "low" => ("vertical", false),
        "toe" => ("offset", true),
        "heel" => ("offset", false),
        _ => return None,
    })
}

impl Legend {
    /// `L-/R+`, `closed-/open+`, `toe down-/toe up+`: two sides joined by `/`, the first
    /// ending in `-`, the second in `+` (either order).
    pub fn parse(text: &str) -> Option<Self> {
        let (a, b) = text.trim().split_once('/')?;
        let words = |s: &str, end: char| {
            s.trim()
                .strip_suffix(end)
                .map(|w| w.trim().to_lowercase())
                .filter(|w| !w.is_empty())
        };
        match (words(a, '-'), words(b, '+')) {
            (Some(negative), Some(positive)) => Some(Self { negative, positive }),
            _ => match (words(a, '+'), words(b, '-')) {
                (Some(positive), Some(negative)) => Some(Self { negative, positive }),
                _ => None,
            },
        }
    }

    /// The legend as written in the header, `neg-/pos+`.
    pub fn text(&self) -> String {
        format!("{}-/{}+", self.negative, self.positive)
    }

    /// Both sides in one family: the family and whether the legend's positive side is that
    /// family's positive side.
    fn family(&self) -> Option<(&'static str, bool)> {
        let (fp, pos) = side(&self.positive)?;
        let (fn_, neg) = side(&self.negative)?;
        (fp == fn_ && pos != neg).then_some((fp, pos))
    }

    /// The factor a column with `direction` (`R+`, `L+`, `U+`, `D+`, `I-O+`, `O-I+`) takes for
    /// its signed numbers to follow this legend: 1 when the legend's positive side is the
    /// direction's, −1 when it is the other; `None` when the legend names sides of another
    /// kind.
    pub fn sign_for(&self, direction: &str) -> Option<i8> {
        let (family, legend_pos) = self.family()?;
        let (want, dir_pos) = match direction
            .trim_end_matches('+')
            .to_ascii_uppercase()
            .as_str()
        {
            "R" | "I-O" => ("lateral", true),
            "L" | "O-I" => ("lateral", false),
            "U" => ("vertical", true),
            "D" => ("vertical", false),
            _ => return None,
        };
        (family == want).then_some(if legend_pos == dir_pos { 1 } else { -1 })
    }

    /// The side a positive heel–toe offset points to, when the legend names toe and heel.
    pub fn offset_side(&self) -> Option<OffsetSide> {
        match self.family()? {
            ("offset", true) => Some(OffsetSide::Toe),
            ("offset", false) => Some(OffsetSide::Heel),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legends_read_their_sides() {
        let l = |s| Legend::parse(s).unwrap();
        assert_eq!(l("L-/R+").sign_for("R+"), Some(1));
        assert_eq!(l("R-/L+").sign_for("R+"), Some(-1));
        assert_eq!(l("R+/L-").sign_for("R+"), Some(1));
        assert_eq!(l("out-in-/in-out+").sign_for("R+"), Some(1));
        assert_eq!(l("closed-/open+").sign_for("R+"), Some(1));
        assert_eq!(l("open-/closed+").sign_for("R+"), Some(-1));
        assert_eq!(l("low-/high+").sign_for("U+"), Some(1));
        assert_eq!(l("low-/high+").sign_for("R+"), None);
        assert_eq!(l("toe-/heel+").offset_side(), Some(OffsetSide::Heel));
        assert_eq!(l("heel-/toe+").offset_side(), Some(OffsetSide::Toe));
        assert_eq!(l("toe down-/toe up+").offset_side(), None);
        assert_eq!(l("toe down-/toe up+").sign_for("R+"), None);
        assert_eq!(l("L-/L+").sign_for("R+"), None);
        assert!(Legend::parse("deg").is_none());
        assert!(Legend::parse("L/R").is_none());
    }
}
