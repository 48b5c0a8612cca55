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
//!   column, the ratio and the fix;
//! - yards read as metres (read in m, median in [`YARDS_AS_METRES`], 1.06–1.13) is where that
//!   Mevo+ file sits, so it is not evidence: the note says what it saw and recommends nothing.
//!
//! Neither is a refusal. A median far below both bands is ([`FAR_SHORT`]): every launch speed
//! of the file is then wrong, not only its distances. Speeds in km/h and distances in metres
//! read as mph and yards (an app set to metric units, its file stating none: the Rapsodo
//! MLM2PRO exports of github.com/dagla123456/GolfAI, 1,929 shots in 23 sessions, read
//! 0.41–0.53, and 1.01–1.03 read in km/h and metres) give about 0.45; the refusal says what
//! the same carries give read that way.

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

/// Below this median ratio the carries are refused as read ([`far_short`]): half-way in
/// logarithm between metres read as yards (0.914, [`METRES_AS_YARDS`] from 0.88) and km/h and
/// metres read as mph and yards (about 0.45), 30 % below the lowest correctly-united real file
/// (0.996).
pub(super) const FAR_SHORT: f64 = 0.7;

/// Fewest shots the refusal at [`FAR_SHORT`] is taken over: a ratio that far off is no
/// handful of mishits' doing (a note needs [`MIN_SHOTS`]).
pub(super) const FAR_SHORT_MIN_SHOTS: usize = 5;

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
/// [`MAX_SHOTS`] spread evenly) and how many it is over; `None` below [`MIN_SHOTS`].
pub(super) fn median_ratio(shots: &[CarryShot]) -> Option<(f64, usize)> {
    median_ratio_of(shots, MIN_SHOTS)
}

/// [`median_ratio`] over at least `min_shots`.
fn median_ratio_of(shots: &[CarryShot], min_shots: usize) -> Option<(f64, usize)> {
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

/// The refusal of a file whose carries (column `header`, read in `carry_unit`, with the ball
/// speed read in `speed_unit`) have a median ratio below [`FAR_SHORT`] over at least
/// [`FAR_SHORT_MIN_SHOTS`] shots; with the median the same shots give read as km/h and metres
/// when they were read as mph and yards.
pub(super) fn far_short(
    shots: &[CarryShot],
    header: &str,
    carry_unit: &str,
    speed_unit: &str,
) -> Option<String> {
    let (ratio, n) = median_ratio_of(shots, FAR_SHORT_MIN_SHOTS)?;
    if ratio >= FAR_SHORT {
        return None;
    }
    let mut why = format!(
        "column '{header}' (read in {carry_unit}, the ball speed in {speed_unit}): the median of \
         {n} carries is {ratio:.3} times the carry smash's flight model gives their launches, \
         where correctly-united real files give 0.996-1.092 and no golf shot's units give below \
         {FAR_SHORT}: the ball speed is read in too large a unit or the carry in too small a one"
    );
    if carry_unit == "yd" && speed_unit == "mph" {
        let metric: Vec<CarryShot> = shots
            .iter()
            .map(|s| CarryShot {
                ball_mph: s.ball_mph / KMH_PER_MPH,
                carry_yd: s.carry_yd * YD_PER_M,
                ..*s
            })
            .collect();
        if let Some((m, k)) = median_ratio_of(&metric, FAR_SHORT_MIN_SHOTS) {
            why.push_str(&format!(
                "; read as km/h and metres the same file gives {m:.3} (over {k} shots){}",
                if (0.9..=1.15).contains(&m) {
                    ": it is in metric units (an app set to km/h and metres), which it does \
                     not state; state them with unit = \"km/h\" for the speeds and unit = \"m\" \
                     for the distances in a mapping file (--format NAME.toml, a copy of the \
                     preset in configs/import/) and import again"
                } else {
                    ""
                }
            ));
        }
    }
    Some(why)
}

/// The note for a file whose carries (column `header`, read in `unit`) have the median ratio
/// `ratio` over `n` shots, when it is in one of the two bands.
pub(super) fn note(header: &str, unit: &str, ratio: f64, n: usize) -> Option<String> {
    let within = |(lo, hi): (f64, f64)| (lo..=hi).contains(&ratio);
    let seen = format!(
        "column '{header}' (read in {unit}): the median of {n} carries is {ratio:.3} times the \
         carry smash's flight model gives their launches"
    );
    if within(METRES_AS_YARDS) && unit == "yd" {
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
        let firm = note("Carry", "yd", 0.92, 50).unwrap();
        assert!(firm.starts_with("column 'Carry' (read in yd): the median of 50 carries is 0.920"));
        assert!(firm.contains("the carries are in metres") && firm.contains("unit = \"m\""));
        // Read in metres, metres-like carries are right; read in yards, a Mevo+-like 1.09 too.
        assert_eq!(note("Carry", "m", 0.92, 50), None);
        assert_eq!(note("Carry", "yd", 1.09, 50), None);
        assert_eq!(note("Carry", "yd", 0.996, 50), None);
        let soft = note("Carry", "m", 1.094, 50).unwrap();
        assert!(soft.contains("does not settle it"), "{soft}");
        assert_eq!(note("Carry", "m", 1.2, 50), None);
    }

    #[test]
    fn the_model_gives_a_ratio_near_one_for_its_own_carries_and_too_few_shots_give_none() {
        let launches: Vec<(f64, f64, f64)> = (0..30)
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
        let shots: Vec<CarryShot> = launches
            .iter()
            .zip(flown)
            .map(|(&(b, l, s), f)| CarryShot {
                ball_mph: b,
                launch_deg: l,
                backspin_rpm: s,
                carry_yd: f.unwrap().carry_yd() * 0.9144,
            })
            .collect();
        let (r, n) = median_ratio(&shots).unwrap();
        assert_eq!(n, 30);
        assert!((r - 0.9144).abs() < 1e-9, "{r}");
        assert_eq!(median_ratio(&shots[..MIN_SHOTS - 1]), None);
    }
}
