//! Do the shots belong to the club file? A check made before anything is fitted.
//!
//! A comparison, a calibration or a diagnosis explains the shots' errors by properties of the
//! head in the club file. Shots hit with another club (a 7-iron session against a driver file) or
//! with several clubs (an export of a whole bag) have errors that come from the wrong head, and
//! every "finding" would be an artefact. Three pieces of evidence are compared with the club:
//!
//! - the club names in the shots' `group` column (an export's `Club` column: `Driver`, `7 Iron`,
//!   `7i`, `PW`, `5 Wood`, `4 Hybrid`, …): several different clubs, or one whose usual loft is
//!   far from the file's `loft_deg`;
//! - the delivered dynamic loft against the file's static loft;
//! - the club speed against the fastest speed a club of that loft is swung at.
//!
//! Group names that are not club names (shafts `A`, `B`, golfers) are left alone. Pure: no I/O.

use std::fmt;

use crate::model::Shot;
use crate::units::{M_S_PER_MPH, RAD_PER_DEG};

/// Most a driver-like club's delivered dynamic loft exceeds its static loft, deg (median of a
/// session). Derived: TrackMan's published PGA Tour averages (as reproduced, e.g., in the
/// 2009–2010 tables of club speed, attack angle and launch by club) launch the driver about
/// 11° with heads of 8.5–10.5°, i.e. a dynamic loft some 2–4° above the static loft (the launch
/// is about 0.85 of the dynamic loft for a driver); club golfers who add loft by flipping the
/// hands at impact reach two to three times that. 10° keeps every such session (a test set of
/// deliberately wide driver deliveries has its median 8.6° above its 9.8° head) and still
/// refuses a 7-iron (delivered near 20–25°) against a 9–11° driver.
pub const MAX_LOFT_ADDED_DEG: f64 = 10.0;

/// Most an iron's delivered dynamic loft falls below its static loft, deg (median of a
/// session). Derived: the same tour averages launch a 7-iron (static about 34°) near 16°, which
/// with a launch of about 0.8 of the dynamic loft for irons means some 20°: forward shaft lean
/// takes 12–14° off. 16° keeps that with a margin of a club's loft step (3–4°, the spacing of a
/// set) and still refuses a driver session (about 12°) against a 7-iron file (34°) or a wedge
/// session against a wood.
pub const MAX_LOFT_REMOVED_DEG: f64 = 16.0;

/// Largest distance between a named club's usual static loft and the file's `loft_deg`, deg.
/// Derived: neighbouring clubs of a set differ by 3–4° of loft and makers' "strong" and
/// "traditional" lofts of the same number differ by up to about 4°; 7° accepts a club named one
/// number off or with strong lofts and refuses a club two classes away (a 7-iron, ~34°, against
/// a driver, ~10°, or a pitching wedge, ~46°, against a 7-iron file is refused as well as a
/// hybrid against a wedge).
pub const MAX_NAMED_LOFT_GAP_DEG: f64 = 7.0;

/// Fastest club speed of a driver, mph: the fastest long-drive swings measured are near 150 mph
/// (the same bound as [`crate::limits::CLUB_SPEED_MPH`]'s note).
pub const FASTEST_DRIVER_SPEED_MPH: f64 = 150.0;

/// TrackMan's published PGA Tour average club speeds by club (mph), with the static loft of a
/// typical set (deg; makers vary by ±2°, so these are derived, not measured, lofts): the speed
/// falls as the club gets shorter and more lofted. Used as a shape, scaled to
/// [`FASTEST_DRIVER_SPEED_MPH`], to bound the speed a club of a given loft can be swung at.
const TOUR_SPEED_BY_LOFT: [(f64, f64); 8] = [
    (10.5, 112.0), // driver
    (15.0, 107.0), // 3-wood
    (18.0, 103.0), // 5-wood
    (21.0, 100.0), // hybrid
    (27.0, 94.0),  // 5-iron
    (34.0, 90.0),  // 7-iron
    (42.0, 85.0),  // 9-iron
    (46.0, 83.0),  // pitching wedge
];

/// Fastest median club speed a session with a club of `loft_deg` can have, mph: the tour
/// speeds' shape (interpolated in loft, flat beyond the table) scaled so the driver's is
/// [`FASTEST_DRIVER_SPEED_MPH`].
pub fn fastest_speed_mph(loft_deg: f64) -> f64 {
    let t = &TOUR_SPEED_BY_LOFT;
    let tour = if loft_deg <= t[0].0 {
        t[0].1
    } else if loft_deg >= t[t.len() - 1].0 {
        t[t.len() - 1].1
    } else {
        let i = t.iter().position(|(l, _)| *l >= loft_deg).expect("inside");
        let ((l0, v0), (l1, v1)) = (t[i - 1], t[i]);
        v0 + (v1 - v0) * (loft_deg - l0) / (l1 - l0)
    };
    FASTEST_DRIVER_SPEED_MPH * tour / t[0].1
}

/// A club as named in an export's `Club` column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ClubKind {
    /// Driver (`Driver`, `Dr`, `1W`).
    Driver,
    /// Fairway wood of a number (`3 Wood`, `5W`).
    Wood(u8),
    /// Hybrid of a number (`4 Hybrid`, `4H`).
    Hybrid(u8),
    /// Iron of a number (`7 Iron`, `7i`).
    Iron(u8),
    /// Pitching wedge.
    PitchingWedge,
    /// Gap (approach) wedge.
    GapWedge,
    /// Sand wedge.
    SandWedge,
    /// Lob wedge.
    LobWedge,
}

impl ClubKind {
    /// Read a club name (case, spaces, `-` and `_` ignored); `None` when it names no club.
    pub fn parse(name: &str) -> Option<Self> {
        let s: String = name
            .chars()
            .filter(|c| !c.is_whitespace() && *c != '-' && *c != '_')
            .flat_map(char::to_lowercase)
            .collect();
        let named = match s.as_str() {
            "driver" | "dr" | "drv" | "1w" | "1wood" | "wood1" => Some(Self::Driver),
            "pw" | "pitchingwedge" | "pitching" => Some(Self::PitchingWedge),
            "gw" | "aw" | "gapwedge" | "approachwedge" | "uw" => Some(Self::GapWedge),
            "sw" | "sandwedge" => Some(Self::SandWedge),
            "lw" | "lobwedge" => Some(Self::LobWedge),
            _ => None,
        };
        if named.is_some() {
            return named;
        }
        // `7iron`, `iron7`, `7i`, `5wood`, `5w`, `fw5`, `4hybrid`, `4h`, `hy4`, `4hy`.
        let digits: String = s.chars().filter(char::is_ascii_digit).collect();
        let letters: String = s.chars().filter(|c| !c.is_ascii_digit()).collect();
        let n: u8 = digits.parse().ok().filter(|n| (1..=11).contains(n))?;
        match letters.as_str() {
            "i" | "iron" => Some(Self::Iron(n)),
            "w" | "wood" | "fw" | "fairway" | "fairwaywood" if n == 1 => Some(Self::Driver),
            "w" | "wood" | "fw" | "fairway" | "fairwaywood" => Some(Self::Wood(n)),
            "h" | "hy" | "hyb" | "hybrid" | "rescue" | "u" | "ut" | "utility" => {
                Some(Self::Hybrid(n))
            }
            _ => None,
        }
    }

    /// Usual static loft, deg. Derived from a typical modern set (makers differ by a few
    /// degrees): driver 10.5°; woods from 15° (3-wood) by 1.5° a number; hybrids from 19° (3H)
    /// by 3° a number; irons from 34° (7-iron) by 4° a number; wedges 46° (PW), 50° (gap),
    /// 56° (sand), 60° (lob).
    pub fn usual_loft_deg(self) -> f64 {
        match self {
            Self::Driver => 10.5,
            Self::Wood(n) => 15.0 + 1.5 * (f64::from(n) - 3.0),
            Self::Hybrid(n) => 19.0 + 3.0 * (f64::from(n) - 3.0),
            Self::Iron(n) => 34.0 + 4.0 * (f64::from(n) - 7.0),
            Self::PitchingWedge => 46.0,
            Self::GapWedge => 50.0,
            Self::SandWedge => 56.0,
            Self::LobWedge => 60.0,
        }
    }
}

impl fmt::Display for ClubKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Driver => write!(f, "driver"),
            Self::Wood(n) => write!(f, "{n}-wood"),
            Self::Hybrid(n) => write!(f, "{n}-hybrid"),
            Self::Iron(n) => write!(f, "{n}-iron"),
            Self::PitchingWedge => write!(f, "pitching wedge"),
            Self::GapWedge => write!(f, "gap wedge"),
            Self::SandWedge => write!(f, "sand wedge"),
            Self::LobWedge => write!(f, "lob wedge"),
        }
    }
}

/// One way the shots do not belong to the club file.
#[derive(Debug, Clone, PartialEq)]
pub enum Mismatch {
    /// The `group` column names several clubs (their names as written, one per club).
    MixedClubs {
        /// Group names, one per distinct club.
        names: Vec<String>,
    },
    /// The `group` column names one club whose usual loft is far from the file's.
    NamedClub {
        /// The name as written.
        name: String,
        /// The club it names.
        kind: ClubKind,
        /// The club file's static loft, deg.
        club_loft_deg: f64,
    },
    /// The delivered dynamic loft is outside what the file's static loft allows.
    Loft {
        /// Median dynamic loft of the shots, deg.
        median_deg: f64,
        /// The club file's static loft, deg.
        club_loft_deg: f64,
    },
    /// The club speed is faster than a club of the file's loft is swung.
    Speed {
        /// Median club speed of the shots, mph.
        median_mph: f64,
        /// Fastest median for the file's loft, mph ([`fastest_speed_mph`]).
        fastest_mph: f64,
        /// The club file's static loft, deg.
        club_loft_deg: f64,
    },
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::MixedClubs { names } => write!(
                f,
                "the shots' group column names {} different clubs ({}), but a club file has one \
                 head and one loft: split the export by club, one file per club, each with its \
                 own club file",
                names.len(),
                names
                    .iter()
                    .map(|n| format!("'{}'", n.escape_debug()))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Self::NamedClub {
                name,
                kind,
                club_loft_deg,
            } => write!(
                f,
                "the shots are of '{}' (a {kind}, usual loft about {:.0}°) but the club file's \
                 loft is {club_loft_deg:.1}° (more than {MAX_NAMED_LOFT_GAP_DEG:.0}° apart)",
                name.escape_debug(),
                kind.usual_loft_deg()
            ),
            Self::Loft {
                median_deg,
                club_loft_deg,
            } => write!(
                f,
                "the shots' median dynamic loft is {median_deg:.1}° but the club file's loft is \
                 {club_loft_deg:.1}° (a club is delivered at most {MAX_LOFT_ADDED_DEG:.0}° above \
                 or {MAX_LOFT_REMOVED_DEG:.0}° below its loft)"
            ),
            Self::Speed {
                median_mph,
                fastest_mph,
                club_loft_deg,
            } => write!(
                f,
                "the shots' median club speed is {median_mph:.1} mph, faster than a club of \
                 {club_loft_deg:.1}° loft is swung (at most about {fastest_mph:.0} mph)"
            ),
        }
    }
}

/// The outcome of [`check`]: every mismatch found (none: the shots fit the club).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ClubCheck {
    /// Mismatches, the club names first.
    pub mismatches: Vec<Mismatch>,
}

impl ClubCheck {
    /// Do the shots fit the club?
    pub fn is_match(&self) -> bool {
        self.mismatches.is_empty()
    }

    /// One line naming every mismatch (empty when they match).
    pub fn summary(&self) -> String {
        self.mismatches
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("; ")
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// Compare `shots` with a club of static loft `club_loft_deg` (`None`: the file states none,
/// and only the club names are compared with each other).
pub fn check(club_loft_deg: Option<f64>, shots: &[Shot]) -> ClubCheck {
    let mut mismatches = Vec::new();
    // Distinct clubs named by the groups (first name written for each).
    let mut named: Vec<(ClubKind, String)> = Vec::new();
    for s in shots {
        if let Some(k) = ClubKind::parse(&s.group) {
            if !named.iter().any(|(n, _)| *n == k) {
                named.push((k, s.group.clone()));
            }
        }
    }
    named.sort();
    if named.len() > 1 {
        mismatches.push(Mismatch::MixedClubs {
            names: named.iter().map(|(_, n)| n.clone()).collect(),
        });
    }
    let Some(loft) = club_loft_deg else {
        return ClubCheck { mismatches };
    };
    if let [(kind, name)] = named.as_slice() {
        if (kind.usual_loft_deg() - loft).abs() > MAX_NAMED_LOFT_GAP_DEG {
            mismatches.push(Mismatch::NamedClub {
                name: name.clone(),
                kind: *kind,
                club_loft_deg: loft,
            });
        }
    }
    let lofts = shots
        .iter()
        .map(|s| s.delivery.dynamic_loft_rad / RAD_PER_DEG)
        .collect();
    if let Some(m) = median(lofts) {
        if m > loft + MAX_LOFT_ADDED_DEG || m < loft - MAX_LOFT_REMOVED_DEG {
            mismatches.push(Mismatch::Loft {
                median_deg: m,
                club_loft_deg: loft,
            });
        }
    }
    let speeds = shots
        .iter()
        .map(|s| s.delivery.club_speed_m_s / M_S_PER_MPH)
        .collect();
    if let Some(m) = median(speeds) {
        let fastest = fastest_speed_mph(loft);
        if m > fastest {
            mismatches.push(Mismatch::Speed {
                median_mph: m,
                fastest_mph: fastest,
                club_loft_deg: loft,
            });
        }
    }
    ClubCheck { mismatches }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn club_names_of_exports_are_read() {
        for (s, k) in [
            ("Driver", ClubKind::Driver),
            ("1w", ClubKind::Driver),
            ("7 Iron", ClubKind::Iron(7)),
            ("7i", ClubKind::Iron(7)),
            ("Iron7", ClubKind::Iron(7)),
            ("PW", ClubKind::PitchingWedge),
            ("Pitching Wedge", ClubKind::PitchingWedge),
            ("5 Wood", ClubKind::Wood(5)),
            ("3W", ClubKind::Wood(3)),
            ("4 Hybrid", ClubKind::Hybrid(4)),
            ("4H", ClubKind::Hybrid(4)),
            ("SW", ClubKind::SandWedge),
        ] {
            assert_eq!(ClubKind::parse(s), Some(k), "{s}");
        }
        for s in ["A", "B", "C", "all", "shaft_x", "Premium", "12", "7"] {
            assert_eq!(ClubKind::parse(s), None, "{s}");
        }
    }

    #[test]
    fn usual_lofts_rise_through_the_bag() {
        let bag = [
            ClubKind::Driver,
            ClubKind::Wood(3),
            ClubKind::Wood(5),
            ClubKind::Hybrid(4),
            ClubKind::Iron(5),
            ClubKind::Iron(7),
            ClubKind::Iron(9),
            ClubKind::PitchingWedge,
            ClubKind::GapWedge,
            ClubKind::SandWedge,
            ClubKind::LobWedge,
        ];
        for w in bag.windows(2) {
            assert!(w[0].usual_loft_deg() < w[1].usual_loft_deg(), "{w:?}");
        }
    }

    #[test]
    fn fastest_speed_falls_with_loft() {
        assert_eq!(fastest_speed_mph(9.0), FASTEST_DRIVER_SPEED_MPH);
        let mut last = f64::INFINITY;
        for l in [10.5, 12.0, 20.0, 30.0, 40.0, 46.0, 60.0] {
            let v = fastest_speed_mph(l);
            assert!(v <= last && v > 100.0, "{l}: {v}");
            last = v;
        }
    }
}
