//! The flight models on the real shots the repository may ship (`tests/data/README.md`, "Ball
//! flight"): two Rapsodo MLM2PRO sessions whose carry is Rapsodo's own flight model flown from
//! the measured launch (`flight_modelled = 1`), so this compares two models, not a model and
//! tracked flights.
//!
//! The split was fixed before any model was flown on them: `rapsodo_mlm2pro_7i.csv` (59
//! 7-iron shots) is the fit/choose session, `rapsodo_mlm2pro_mixed.csv` (6 7-iron and 9
//! 5-iron shots) is held out and only reported. The calibration (`drag,lift`, chosen on the
//! fit session: the spin-decay scale is not determined there, ±1.9) is fitted on the fit
//! session and flown on the held-out one.
//!
//! Limits per club class on the held-out shots are the figures measured when they were set
//! (README, "Real shots") with a margin; they MAY ONLY TIGHTEN. Both sessions are irons, so
//! the iron class is the only one with shots; the driver, wood/hybrid and wedge classes have
//! none to check.

use std::path::Path;

use smash::data::import::{import, load_mapping, ImportOptions};
use smash::flight::calibrate::{calibrate, MeasuredFlight, Scaled, Term};
use smash::flight::integrate::fly_with;
use smash::flight::{AeroModel, CoefficientModel, FlightConfig, FlightLaunch, M_PER_YD};

/// One shot: its club (`group`) and its measured flight.
struct Shot {
    club: String,
    flight: MeasuredFlight,
}

/// The shots of a real Rapsodo export, imported as `smash import --format rapsodo` does.
fn session(name: &str) -> Vec<Shot> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/real")
        .join(name);
    let bytes = std::fs::read(&path).unwrap();
    let mapping = load_mapping("rapsodo").unwrap();
    let imported = import(&path, &bytes, &mapping, &ImportOptions::default()).unwrap();
    let mut reader = csv::Reader::from_reader(imported.csv.as_slice());
    let headers: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let col = |n: &str| headers.iter().position(|h| h == n).unwrap();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            let x = |n: &str| r[col(n)].parse::<f64>().unwrap();
            assert_eq!(&r[col("flight_modelled")], "1");
            Shot {
                club: r[col("group")].to_string(),
                flight: MeasuredFlight {
                    launch: FlightLaunch::from_file_units(
                        x("ball_speed_mph"),
                        x("launch_angle_deg"),
                        x("azimuth_deg"),
                        x("backspin_rpm"),
                        x("sidespin_rpm"),
                    ),
                    carry_m: Some(x("carry_yd") * M_PER_YD),
                    apex_m: Some(x("apex_yd") * M_PER_YD),
                    land_angle_rad: Some(x("land_angle_deg").to_radians()),
                },
            }
        })
        .collect()
}

/// The club class of a Rapsodo club cell (`7i`, `5i`: irons); these sessions hold no other.
fn class(club: &str) -> &'static str {
    match club {
        "Dr" | "DR" | "1W" => "driver",
        c if c.ends_with('i') => "iron",
        c if c.ends_with('W') || c.ends_with('H') => "wood/hybrid",
        _ => "wedge",
    }
}

/// Median and P90 of |carry error| %, bias %, RMSE yd.
#[derive(Debug, Clone, Copy)]
struct Figures {
    n: usize,
    median_pct: f64,
    p90_pct: f64,
    bias_pct: f64,
    rmse_yd: f64,
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    let pos = q * (sorted.len() - 1) as f64;
    let (lo, f) = (pos.floor() as usize, pos - pos.floor());
    let hi = (lo + 1).min(sorted.len() - 1);
    sorted[lo] + f * (sorted[hi] - sorted[lo])
}

/// The carry figures of `model` on `shots` of class `cls`, default atmosphere and step.
fn figures<C: CoefficientModel>(model: &C, shots: &[Shot], cls: &str) -> Option<Figures> {
    let shots: Vec<&Shot> = shots.iter().filter(|s| class(&s.club) == cls).collect();
    if shots.is_empty() {
        return None;
    }
    let launches: Vec<FlightLaunch> = shots.iter().map(|s| s.flight.launch).collect();
    let flights = fly_with(&FlightConfig::default(), model, &launches);
    let (mut pct, mut sq) = (Vec::new(), 0.0);
    for (s, f) in shots.iter().zip(flights) {
        let measured = s.flight.carry_m.unwrap();
        let err = f.unwrap().carry_m - measured;
        pct.push(100.0 * err / measured);
        sq += (err / M_PER_YD).powi(2);
    }
    let bias_pct = pct.iter().sum::<f64>() / pct.len() as f64;
    let mut abs: Vec<f64> = pct.iter().map(|p| p.abs()).collect();
    abs.sort_by(f64::total_cmp);
    Some(Figures {
        n: abs.len(),
        median_pct: quantile(&abs, 0.5),
        p90_pct: quantile(&abs, 0.9),
        bias_pct,
        rmse_yd: (sq / abs.len() as f64).sqrt(),
    })
}

/// A model as it is (every scale 1).
fn plain(inner: &AeroModel) -> Scaled<'_> {
    Scaled {
        inner,
        drag: 1.0,
        lift: 1.0,
        moment: 1.0,
    }
}

const CLASSES: [&str; 4] = ["driver", "wood/hybrid", "iron", "wedge"];

/// Held-out carry limits per class for the default model and for the calibrated one:
/// (class, median %, P90 %, |bias| %, RMSE yd). Set on 26 Nov 2026 from the figures then
/// measured (default: 5.18, 8.31, −5.78, 8.87; calibrated: 0.73, 4.69, −1.69, 3.70) with a
/// margin; they MAY ONLY TIGHTEN.
type Limit = (&'static str, f64, f64, f64, f64);
const DEFAULT_LIMITS: [Limit; 1] = [("iron", 5.5, 9.0, 6.5, 9.5)];
const CALIBRATED_LIMITS: [Limit; 1] = [("iron", 1.5, 5.5, 2.5, 4.5)];

fn check(what: &str, f: &Figures, limit: Limit) {
    let (cls, median, p90, bias, rmse) = limit;
    assert!(
        f.median_pct <= median && f.p90_pct <= p90 && f.bias_pct.abs() <= bias && f.rmse_yd <= rmse,
        "{what}, {cls}: {f:?} beyond the limits (median {median} %, P90 {p90} %, |bias| \
         {bias} %, RMSE {rmse} yd)"
    );
}

/// Every model's held-out figures are printed (the README quotes them); the default and the
/// calibrated model keep their limits, and the calibration fitted on the fit session lowers
/// the held-out error of the default below the default's own.
#[test]
fn held_out_real_carry_per_club_class() {
    let fit = session("rapsodo_mlm2pro_7i.csv");
    let held = session("rapsodo_mlm2pro_mixed.csv");
    assert_eq!((fit.len(), held.len()), (59, 15));
    for name in smash::flight::aero::MODEL_NAMES {
        let model = AeroModel::from_name(name).unwrap();
        for cls in CLASSES {
            for (part, shots) in [("fit", &fit), ("held-out", &held)] {
                if let Some(f) = figures(&plain(&model), shots, cls) {
                    println!("{name:<13} {part:<8} {cls:<11} {f:?}");
                }
            }
        }
    }
    let cfg = FlightConfig::default();
    let fit_shots: Vec<MeasuredFlight> = fit.iter().map(|s| s.flight).collect();
    let cal = calibrate(&cfg, &fit_shots, &[Term::Drag, Term::Lift]).unwrap();
    println!("calibrated on the fit session: {cal:?}");
    let calibrated = cal.model(&cfg.aero);
    for cls in CLASSES {
        let (Some(d), Some(c)) = (
            figures(&plain(&cfg.aero), &held, cls),
            figures(&calibrated, &held, cls),
        ) else {
            assert!(figures(&plain(&cfg.aero), &held, cls).is_none(), "{cls}");
            continue;
        };
        println!("held-out {cls}: default {d:?}\n               calibrated {c:?}");
        assert!(
            d.n > 0 && c.rmse_yd < d.rmse_yd && c.median_pct < d.median_pct,
            "{cls}"
        );
        let limit = |l: &[Limit]| *l.iter().find(|x| x.0 == cls).unwrap();
        check("default", &d, limit(&DEFAULT_LIMITS));
        check("calibrated", &c, limit(&CALIBRATED_LIMITS));
    }
}

/// The terms `smash flight --diagnose` selects on the fit session, flown on the held-out one:
/// reported (README), and no worse than the default there.
#[test]
fn terms_diagnosed_on_the_fit_session_on_held_out_shots() {
    use smash::flight::diagnose::{diagnose, DiagnoseInput};
    let fit = session("rapsodo_mlm2pro_7i.csv");
    let held = session("rapsodo_mlm2pro_mixed.csv");
    let cfg = FlightConfig::default();
    let shots: Vec<MeasuredFlight> = fit.iter().map(|s| s.flight).collect();
    let d = diagnose(
        &cfg,
        DiagnoseInput {
            shots: &shots,
            balls: None,
            sessions: None,
            folds: 5,
        },
    )
    .unwrap();
    println!("{}", d.text());
    let launches: Vec<FlightLaunch> = held.iter().map(|s| s.flight.launch).collect();
    let (mut sq_d, mut sq_0) = (0.0, 0.0);
    let plain_flights = fly_with(&cfg, &plain(&cfg.aero), &launches);
    for ((s, f), f0) in held.iter().zip(d.fly(&cfg, &launches)).zip(plain_flights) {
        let m = s.flight.carry_m.unwrap();
        sq_d += ((f.unwrap().carry_m - m) / M_PER_YD).powi(2);
        sq_0 += ((f0.unwrap().carry_m - m) / M_PER_YD).powi(2);
    }
    let n = held.len() as f64;
    let (rmse_d, rmse_0) = ((sq_d / n).sqrt(), (sq_0 / n).sqrt());
    println!("held-out carry RMSE: diagnosed terms {rmse_d:.2} yd, default {rmse_0:.2} yd");
    assert!(
        !d.selected.is_empty() && rmse_d < rmse_0,
        "{:?}",
        d.selected
    );
}
