//! Carry distances in metres read as yards (or yards read as metres), caught by physics: each
//! shot's measured carry against the carry the project's own flight model (`smash flight`'s
//! default, [`FlightConfig::default`]: FMM 2022 aerodynamics, sea-level ISA air at 15 °C, 50 %
//! humidity) gives its measured launch (no source outside the project: the model is the
//! relation, and its error on real sessions is what the bands below are set against). A carry
//! in metres read as yards is 0.9144 times what it should be, one in yards read as metres
//! 1/0.9144 = 1.094 times.
//!
//! The median ratio of measured to modelled carry of the correctly-united real files at hand
//! (`tests/data/real/`, `cli/tests/fixtures/import/trackman_normalized.csv`; the corpus
//! fixtures hold fewer than [`MIN_SHOTS`] full shots) is 0.996–1.034, except a FlightScope
//! Mevo+ 8-iron session at 1.092: the monitor's own carries run 9 % past the model. So:
//!
//! - metres read as yards (the carry column read in yd, median in [`METRES_AS_YARDS`],
//!   0.88–0.95) is a band no real file reaches, 4.6 % below the lowest: a note names the
//!   column, the ratio and the fix when the yards were assumed; when the file states yards
//!   (a real Garmin R50 session of wedges stating `[Yards]` reads 0.949) it says what it saw
//!   and recommends nothing;
//! - yards read as metres (read in m, median in [`YARDS_AS_METRES`], 1.06–1.13) is where that
//!   Mevo+ file sits, so it is not evidence: the note says what it saw and recommends nothing.
//!
//! Neither is a refusal. A median far below both bands ([`FAR_SHORT`]) is looked at again
//! with the ball speed read in km/h (an app set to km/h whose file states no unit, or states
//! mph over km/h values), with the carry as read and, when read in yards, in metres: when
//! exactly one of those readings lands in [`UNIT_READING_BAND`], every launch speed of the file
//! is wrong as read, and the file is refused naming that reading; when none does (limited-flight
//! range balls, a headwind, a mapping's error the units cannot explain), a note says what was
//! seen and the carries are kept. The Rapsodo MLM2PRO exports of github.com/dagla123456/GolfAI
//! (1,929 shots in 23 sessions, km/h and metres in a file stating no unit) read 0.41–0.53 as mph
//! and yards, 1.01–1.03 as km/h and metres and 0.92–0.94 as km/h and yards.
use crate::flight::{FlightConfig, FlightLaunch};

/// Fewest shots the median is taken over: a handful of mishits must not decide, and the
/// sessions whose carries were furthest from the model's (issue 44: a 19-shot Uneekor session
/// at 10.7 %, a one-shot OpenFlight log at 13 %) were short ones.
pub(super) const MIN_SHOTS: usize = 20;

/// Most shots flown for the check (spread evenly over the file): enough for a median whose
/// sampling error (about 1.25 σ/√n, with σ ≈ 5 % per shot) is a few tenths of a percent, and
/// cheap on a 10,000-shot export.
const MAX_SHOTS: usize = 400;

/// Shots slower than this are not used: chips and half swings, whose carries the monitors and
/// the model both get least right (issue 44 counted shots over 40 mph).
const MIN_BALL_SPEED_MPH: f64 = 40.0;

/// The band of the median ratio (measured / modelled carry) taken as "metres read as yards":
/// around 0.9144, below every correctly-united real file (lowest 0.996) by 4.6 %.
pub(super) const METRES_AS_YARDS: (f64, f64) = (0.88, 0.95);

/// The band of "yards read as metres", around 1/0.9144 = 1.094: a real Mevo+ session in
/// yards reads 1.092, so a ratio here is reported without a recommendation.
pub(super) const YARDS_AS_METRES: (f64, f64) = (1.06, 1.13);

/// Below this median ratio the carries are looked at in other units ([`check`]): 30 %
/// below the lowest correctly-united real file (0.996) and 23 % below metres read as yards
/// (0.914), while km/h read as mph gives 0.41–0.61 (the sessions above; the same sessions'
/// carries in yards).
pub(super) const FAR_SHORT: f64 = 0.7;

/// Fewest shots the check at [`FAR_SHORT`] is taken over: a ratio that far off is no handful
/// of mishits' doing (a note on metres needs [`MIN_SHOTS`]).
pub(super) const FAR_SHORT_MIN_SHOTS: usize = 5;

/// Where another reading of the units must land to be named as the file's: the correctly-united
/// real files' medians, 0.996–1.034, widened by 5 % below and 2.5 % above, so that it holds
/// neither metres read as yards (0.914) nor yards read as metres (1.094; a Mevo+ session reads
/// 1.092 correctly united, which is why a reading there cannot be told from a monitor whose
/// carries run long).
pub(super) const UNIT_READING_BAND: (f64, f64) = (0.95, 1.06);

/// km/h in a mph.
const KMH_PER_MPH: f64 = 1.609_344;

/// Yards in a metre (1 yd = 0.9144 m exactly).
const YD_PER_M: f64 = 1.0 / 0.9144;

/// One shot's launch and measured carry, shots-file units.
#[derive(Debug, Clone, Copy)]
pub(super) struct CarryShot {
    pub ball_mph: f64,
    pub launch_deg: f64,
    pub backspin_rpm: f64,
    pub carry_yd: f64,
}

impl CarryShot {
    /// A shot the check can use: a full swing's launch and a carry.
    pub(super) fn usable(&self) -> bool {
        self.ball_mph >= MIN_BALL_SPEED_MPH
            && (1.0..=60.0).contains(&self.launch_deg)
            && self.carry_yd > 10.0
            && self.backspin_rpm.abs() <= 15_000.0
    }
}

/// The median of measured over modelled carry of `shots` (usable ones, at most
/// [`MAX_SHOTS`] spread evenly) and how many it is over; `None` below `min_shots`.
fn median_ratio(shots: &[CarryShot], min_shots: usize) -> Option<(f64, usize)> {
    let usable: Vec<&CarryShot> = shots.iter().filter(|s| s.usable()).collect();
    if usable.len() < min_shots {
        return None;
    }
    let step = usable.len().div_ceil(MAX_SHOTS);
    let picked: Vec<&CarryShot> = usable.into_iter().step_by(step).collect();
    let launches: Vec<FlightLaunch> = picked
        .iter()
        .map(|s| FlightLaunch::from_file_units(s.ball_mph, s.launch_deg, 0.0, s.backspin_rpm, 0.0))
        .collect();
    let cfg = FlightConfig::default();
    let mut ratios: Vec<f64> = crate::flight::fly(&cfg, &launches)
        .into_iter()
        .zip(&picked)
        .filter_map(|(f, s)| {
            let model = f.ok()?.carry_yd();
            (model > 10.0).then(|| s.carry_yd / model)
        })
        .filter(|r| r.is_finite())
        .collect();
    if ratios.len() < min_shots {
        return None;
    }
    ratios.sort_by(f64::total_cmp);
    Some((ratios[ratios.len() / 2], ratios.len()))
}

/// How the carry and ball-speed columns were read: header, units, and whether each unit was
/// assumed (a preset's default, the file stating none) or stated (units row, header, mapping).
pub(super) struct AsRead<'a> {
    pub header: &'a str,
    pub carry_unit: &'a str,
    pub carry_assumed: bool,
    pub speed_unit: &'a str,
    pub speed_assumed: bool,
}

/// What [`check`] makes of the carries' units.
#[derive(Debug, PartialEq)]
pub(super) enum CarryUnits {
    /// Far short, and one reading of the units explains it: the file is refused, naming it.
    Refuse(String),
    /// Far short with no reading explaining it (the carries kept as read), or in one of the
    /// bands of metres read as yards or yards read as metres ([`note`]): a note.
    Note(String),
}

/// The carries' units checked against the flight model, the median ratio computed once
/// (module docs): below [`FAR_SHORT`] over at least [`FAR_SHORT_MIN_SHOTS`] shots, read again
/// with the ball speed in km/h ([`far_short`]); else, over at least [`MIN_SHOTS`], the note
/// of a ratio in one of the two bands ([`note`]); `None` otherwise.
pub(super) fn check(shots: &[CarryShot], read: &AsRead) -> Option<CarryUnits> {
    let (ratio, n) = median_ratio(shots, FAR_SHORT_MIN_SHOTS)?;
    if ratio < FAR_SHORT {
        return Some(far_short(shots, read, ratio, n));
    }
    // `n` counts the ratios, at most the usable shots: at least MIN_SHOTS of both, as the
    // band notes need.
    let note = note(read.header, read.carry_unit, ratio, n, read.carry_assumed);
    note.filter(|_| n >= MIN_SHOTS).map(CarryUnits::Note)
}

/// Carries whose median ratio `ratio` over `n` shots is below [`FAR_SHORT`], read again with
/// the ball speed in km/h (module docs).
fn far_short(shots: &[CarryShot], read: &AsRead, ratio: f64, n: usize) -> CarryUnits {
    let AsRead {
        header,
        carry_unit,
        speed_unit,
        ..
    } = *read;
    let seen = format!(
        "column '{header}' (read in {carry_unit}, the ball speed in {speed_unit}): the median of \
         {n} carries is {ratio:.3} times the carry smash's flight model gives their launches, \
         where correctly-united real files give 0.996-1.092"
    );
    // km/h written where mph is read, the carry as read or (read in yards) in metres.
    let mut readings: Vec<(String, &str, f64, f64)> = Vec::new();
    if speed_unit == "mph" {
        let as_read = format!("km/h and {carry_unit}");
        readings.push((as_read, carry_unit, KMH_PER_MPH, 1.0));
        if carry_unit == "yd" {
            readings.push(("km/h and m".to_owned(), "m", KMH_PER_MPH, YD_PER_M));
        }
    }
    let scored: Vec<(String, &str, f64)> = readings
        .into_iter()
        .filter_map(|(label, carry, speed_factor, carry_factor)| {
            let again: Vec<CarryShot> = shots
                .iter()
                .map(|s| CarryShot {
                    ball_mph: s.ball_mph / speed_factor,
                    carry_yd: s.carry_yd * carry_factor,
                    ..*s
                })
                .collect();
            let (r, _) = median_ratio(&again, FAR_SHORT_MIN_SHOTS)?;
            Some((label, carry, r))
        })
        .collect();
    let listed: String = scored
        .iter()
        .map(|(label, _, r)| format!("; read as {label}, {r:.3}"))
        .collect();
    let (lo, hi) = UNIT_READING_BAND;
    let fits: Vec<&(String, &str, f64)> = scored
        .iter()
        .filter(|(_, _, r)| (lo..=hi).contains(r))
        .collect();
    let [(label, carry, _)] = fits.as_slice() else {
        return CarryUnits::Note(format!(
            "{seen}{listed}: no reading of the units brings them to {lo}-{hi}, so they are kept \
             as read; check the export (limited-flight range balls, a strong headwind and a \
             mapping's wrong column all give short carries)"
        ));
    };
    let fix = if read.speed_assumed && (read.carry_assumed || *carry == carry_unit) {
        format!(
            "the file does not state its units and the preset's were assumed: state the file's \
             with unit = \"km/h\" for the speeds{} in a mapping file (--format NAME.toml, a copy \
             of the preset in configs/import/) and import again",
            if *carry == carry_unit {
                String::new()
            } else {
                format!(" and unit = \"{carry}\" for the distances")
            }
        )
    } else {
        format!(
            "the file states {speed_unit} and {carry_unit}, which its values contradict: correct \
             the units in its units row or header and import again"
        )
    };
    CarryUnits::Refuse(format!("{seen}{listed}: the values are in {label}; {fix}"))
}

/// The note for a file whose carries (column `header`, read in `unit`) have the median ratio
/// `ratio` over `n` shots, when it is in one of the two bands.
pub(super) fn note(
    header: &str,
    unit: &str,
    ratio: f64,
    n: usize,
    assumed: bool,
) -> Option<String> {
    let within = |(lo, hi): (f64, f64)| (lo..=hi).contains(&ratio);
    let seen = format!(
        "column '{header}' (read in {unit}): the median of {n} carries is {ratio:.3} times the \
         carry smash's flight model gives their launches"
    );
    if within(METRES_AS_YARDS) && unit == "yd" && !assumed {
        // The file states yards: taken at its word, since a session of wedges runs this short
        // of the model too (a real Garmin R50 wedge session stating `[Yards]`: 0.949).
        Some(format!(
            "{seen}, where metres read as yards give 0.914; the file states yards, and a session \
             of short clubs runs this short of the model too, so this does not settle it: if the \
             carries are in metres, state [m] in the export's units row or header"
        ))
    } else if within(METRES_AS_YARDS) && unit == "yd" {
        Some(format!(
            "{seen}, where metres read as yards give 0.914 and correctly-united real files \
             0.996-1.092: the carries are in metres; state it in the export's units row ([m]) or \
             with unit = \"m\" for carry_yd (and the other distances) in a mapping file \
             (--format NAME.toml, a copy of the preset in configs/import/), and import again"
        ))
    } else if within(YARDS_AS_METRES) && unit == "m" {
        Some(format!(
            "{seen}, where yards read as metres give 1.094; some monitors' own carries run that \
             far past the model too (a real Mevo+ session: 1.092), so this does not settle it: \
             if the carries are in yards, state it in the units row ([yd]) or with unit = \"yd\" \
             in a mapping file"
        ))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_metres_band_recommends_a_unit() {
        let firm = note("Carry", "yd", 0.92, 50, true).unwrap();
        assert!(firm.starts_with("column 'Carry' (read in yd): the median of 50 carries is 0.920"));
        assert!(firm.contains("the carries are in metres") && firm.contains("unit = \"m\""));
        // Read in metres, metres-like carries are right; read in yards, a Mevo+-like 1.09 too.
        assert_eq!(note("Carry", "m", 0.92, 50, true), None);
        assert_eq!(note("Carry", "yd", 1.09, 50, true), None);
        assert_eq!(note("Carry", "yd", 0.996, 50, true), None);
        let soft = note("Carry", "m", 1.094, 50, true).unwrap();
        assert!(soft.contains("does not settle it"), "{soft}");
        assert_eq!(note("Carry", "m", 1.2, 50, true), None);
    }

    #[test]
    fn the_model_gives_a_ratio_near_one_for_its_own_carries_and_too_few_shots_give_none() {
        let shots = written(30, 1.0, 0.9144);
        let (r, n) = median_ratio(&shots, MIN_SHOTS).unwrap();
        assert_eq!(n, 30);
        assert!((r - 0.9144).abs() < 1e-9, "{r}");
        assert_eq!(median_ratio(&shots[..MIN_SHOTS - 1], MIN_SHOTS), None);
    }

    /// `n` shots whose carries are the model's for their launches, then written with the ball
    /// speed times `speed` (1.609344: in km/h) and the carry times `carry`.
    fn written(n: usize, speed: f64, carry: f64) -> Vec<CarryShot> {
        let launches: Vec<(f64, f64, f64)> = (0..n)
            .map(|k| {
                (
                    100.0 + 3.0 * k as f64,
                    10.0 + 0.5 * k as f64,
                    6000.0 - 100.0 * k as f64,
                )
            })
            .collect();
        let flown = crate::flight::fly(
            &FlightConfig::default(),
            &launches
                .iter()
                .map(|&(b, l, s)| FlightLaunch::from_file_units(b, l, 0.0, s, 0.0))
                .collect::<Vec<_>>(),
        );
        launches
            .iter()
            .zip(flown)
            .map(|(&(b, l, s), f)| CarryShot {
                ball_mph: b * speed,
                launch_deg: l,
                backspin_rpm: s,
                carry_yd: f.unwrap().carry_yd() * carry,
            })
            .collect()
    }

    fn read(carry_assumed: bool, speed_assumed: bool) -> AsRead<'static> {
        AsRead {
            header: "Carry",
            carry_unit: "yd",
            carry_assumed,
            speed_unit: "mph",
            speed_assumed,
        }
    }

    #[test]
    fn far_short_carries_name_the_one_reading_that_explains_them() {
        // km/h and metres written, mph and yards assumed: refused, naming km/h and m.
        let metric = written(12, KMH_PER_MPH, 0.9144);
        let Some(CarryUnits::Refuse(why)) = check(&metric, &read(true, true)) else {
            panic!("metric file not refused");
        };
        assert!(
            why.contains("; read as km/h and m, 1.000")
                && why.contains("the values are in km/h and m")
                && why.contains("unit = \"km/h\" for the speeds and unit = \"m\""),
            "{why}"
        );
        // km/h and yards: refused naming km/h with the carry as read, and no metres.
        let kmh_yd = written(12, KMH_PER_MPH, 1.0);
        let Some(CarryUnits::Refuse(why)) = check(&kmh_yd, &read(true, true)) else {
            panic!("km/h file not refused");
        };
        assert!(
            why.contains("the values are in km/h and yd") && !why.contains("unit = \"m\""),
            "{why}"
        );
        // Units stated by the file: the fix is the file's units, not a mapping.
        let Some(CarryUnits::Refuse(why)) = check(&metric, &read(false, false)) else {
            panic!("stated metric file not refused");
        };
        assert!(why.contains("the file states mph and yd, which its values contradict"));
        // Short carries no unit explains (range balls): a note, kept.
        let short = written(12, 1.0, 0.66);
        assert!(matches!(
            check(&short, &read(true, true)),
            Some(CarryUnits::Note(_))
        ));
        // Too few shots, or a ratio above the bound: nothing.
        assert_eq!(
            check(&metric[..FAR_SHORT_MIN_SHOTS - 1], &read(true, true)),
            None
        );
        assert_eq!(check(&written(12, 1.0, 0.72), &read(true, true)), None);
    }

    /// Metres read as yards: the fix when the yards were assumed; what was seen, and no fix,
    /// when the file states them (a wedge session stating `[Yards]` reads 0.949).
    #[test]
    fn stated_yards_are_taken_at_their_word() {
        let metres = written(MIN_SHOTS, 1.0, 0.9144);
        assert!(matches!(
            check(&metres, &read(true, true)),
            Some(CarryUnits::Note(n)) if n.contains("the carries are in metres")
        ));
        let Some(CarryUnits::Note(n)) = check(&metres, &read(false, false)) else {
            panic!("no note on stated yards");
        };
        assert!(
            n.contains("the file states yards") && !n.contains("unit = \"m\""),
            "{n}"
        );
    }
}
