//! Ball flight: validation against TrackMan's PGA Tour averages, the step-size tolerance test
//! and an independent cross-check by an adaptive Dormand–Prince 5(4) integrator written here
//! from the equations of motion (not sharing code with `smash::flight::integrate`).

use smash::flight::aero::{CoefficientModel, Fmm2022Re, Fmm2022ReFamily, Fmm2022Tour};
use smash::flight::integrate::fly_with;
use smash::flight::trackman::{TourAverage, LPGA_TOUR_2023, PGA_TOUR, PGA_TOUR_2023};
use smash::flight::{fly, fly_one, AeroModel, Atmosphere, FlightConfig, FlightLaunch, SpinDecay};
use smash::lanes::V;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Carry errors (%), land-angle errors (°) and (model, TrackMan) apex heights (yd) of `aero` in
/// the default atmosphere against a TrackMan table.
fn trackman_errors(aero: AeroModel, rows: &[TourAverage]) -> (Vec<f64>, Vec<f64>, Vec<(f64, f64)>) {
    // Default atmosphere: ISA sea level 15 °C, 1013.25 hPa, 50 % relative humidity, still air.
    let cfg = FlightConfig {
        aero,
        ..FlightConfig::default()
    };
    let launches: Vec<FlightLaunch> = rows.iter().map(|r| r.launch()).collect();
    let flights = fly(&cfg, &launches);
    let (mut carry, mut land, mut apex) = (Vec::new(), Vec::new(), Vec::new());
    println!(
        "{}: club  carry  TM   err%   apex  TM  land  TM",
        cfg.aero.name()
    );
    for (r, f) in rows.iter().zip(&flights) {
        let f = f.as_ref().unwrap();
        let e = 100.0 * (f.carry_yd() / r.carry_yd - 1.0);
        println!(
            "{:8} {:6.1} {:4} {:+5.2} {:5.1} {:3} {:5.1} {:3}",
            r.club,
            f.carry_yd(),
            r.carry_yd,
            e,
            f.apex_yd(),
            r.max_height_yd,
            f.land_angle_deg(),
            r.land_angle_deg
        );
        carry.push(e.abs());
        land.push((f.land_angle_deg() - r.land_angle_deg).abs());
        apex.push((f.apex_yd(), r.max_height_yd));
    }
    (carry, land, apex)
}

fn worst(v: &[f64]) -> f64 {
    v.iter().cloned().fold(0.0, f64::max)
}

/// Asserts a table's median and worst |carry error| (%) and its worst land-angle error (°).
fn assert_errors_within(
    carry: &[f64],
    land: &[f64],
    median_pct: f64,
    carry_pct: f64,
    land_deg: f64,
) {
    let med = median(carry.to_vec());
    assert!(med <= median_pct, "median carry error {med:.2} %");
    assert!(
        worst(carry) <= carry_pct,
        "worst carry error {:.2} %",
        worst(carry)
    );
    assert!(
        worst(land) <= land_deg,
        "worst land-angle error {:.2}°",
        worst(land)
    );
}

/// Issue 11's targets for `fmm2022-tour` (the default before `fmm2022`, calibrated on the three
/// TrackMan tables, this one among them: disclosed, with its leave-one-table-out errors, in
/// docs/flight-models.md) in the default atmosphere (ISA sea level, 15 °C, 1013.25 hPa, 50 %
/// relative humidity, still air): median |carry error| ≤ 2 %, worst ≤ 4 %, every land angle
/// within 5°. Measured: 1.58 %, 2.73 % (driver, 3-wood, 7-iron), 2.77° (4-iron).
#[test]
fn trackman_pga_tour_meets_the_issue_targets() {
    let (carry, land, _) = trackman_errors(AeroModel::Fmm2022Tour, &PGA_TOUR);
    assert_errors_within(&carry, &land, 2.0, 4.0, 5.0);
}

/// `fmm2022-tour`'s apex heights on the PGA Tour table: measured within 3.64 yd (all but the
/// driver high); the bound is the measured value rounded up, a regression guard.
#[test]
fn trackman_pga_tour_fmm2022_tour_apex_regression() {
    let (_, _, apex) = trackman_errors(AeroModel::Fmm2022Tour, &PGA_TOUR);
    for (model, tm) in apex {
        assert!((model - tm).abs() < 3.7, "apex {model} vs {tm}");
    }
}

/// `fmm2022-tour` on the 2023 PGA Tour table (in its calibration): measured 1.64 % median,
/// 3.42 % worst carry, 3.22° worst land angle; bounds the measured values rounded up.
#[test]
fn trackman_pga_tour_2023_regression() {
    let (carry, land, _) = trackman_errors(AeroModel::Fmm2022Tour, &PGA_TOUR_2023);
    assert_errors_within(&carry, &land, 1.7, 3.5, 3.3);
}

/// `fmm2022-tour` on the 2023 LPGA Tour table (in its calibration): measured 1.62 % median,
/// 3.70 % worst carry, 6.92° worst land angle (the 3-wood, see docs/flight-models.md); bounds the
/// measured values rounded up.
#[test]
fn trackman_lpga_tour_2023_regression() {
    let (carry, land, _) = trackman_errors(AeroModel::Fmm2022Tour, &LPGA_TOUR_2023);
    assert_errors_within(&carry, &land, 1.7, 3.8, 7.0);
}

/// `fmm2022-re` (the default before, fitted to the LPGA rows only) on the PGA Tour table:
/// measured 0.86 % median, 3.92 % worst carry, 5.07° worst land angle (the driver), apex within
/// 3.90 yd; bounds the measured values rounded up, a regression guard.
#[test]
fn trackman_pga_tour_fmm2022_re_regression() {
    let (carry, land, apex) = trackman_errors(AeroModel::Fmm2022Re, &PGA_TOUR);
    assert_errors_within(&carry, &land, 0.9, 4.0, 5.1);
    for (model, tm) in apex {
        assert!((model - tm).abs() < 4.0, "apex {model} vs {tm}");
    }
    let (carry, land, _) = trackman_errors(AeroModel::Fmm2022Re, &PGA_TOUR_2023);
    assert_errors_within(&carry, &land, 1.4, 4.8, 3.3);
}

/// `fmm2022` as published, the default (chosen on real shots: `tests/flight_real.rs`), misses
/// issue 11's targets on the tour table (measured 1.98 % median, 4.84 % worst carry, 7.2° worst
/// land angle, apex within 3 yd): a secondary check, never a fitting target, and a regression
/// guard on those values.
#[test]
fn trackman_pga_tour_fmm2022_as_published_regression() {
    assert_eq!(AeroModel::default(), AeroModel::Fmm2022);
    let (carry, land, apex) = trackman_errors(AeroModel::default(), &PGA_TOUR);
    assert_errors_within(&carry, &land, 2.0, 4.9, 7.3);
    for (model, tm) in apex {
        assert!((model - tm).abs() < 3.0, "apex {model} vs {tm}");
    }
}

/// The fits' objective on TrackMan tables: Σ over their rows of (carry error %)² + (land
/// error °/2)² + (apex error yd/2)².
fn objective(m: &Fmm2022ReFamily, tables: &[&[TourAverage]]) -> f64 {
    let cfg = FlightConfig::default();
    let rows: Vec<&TourAverage> = tables.iter().flat_map(|t| t.iter()).collect();
    let launches: Vec<FlightLaunch> = rows.iter().map(|r| r.launch()).collect();
    fly_with(&cfg, m, &launches)
        .iter()
        .zip(rows)
        .map(|(f, r)| {
            let f = f.as_ref().unwrap();
            let c = 100.0 * (f.carry_yd() / r.carry_yd - 1.0);
            let l = (f.land_angle_deg() - r.land_angle_deg) / 2.0;
            let a = (f.apex_yd() - r.max_height_yd) / 2.0;
            c * c + l * l + a * a
        })
        .sum()
}

/// `fmm2022-re`'s constants are the LPGA fit: the family at them is the built-in model (its
/// lane form, a separate implementation, agrees), and one grid step either way in any
/// parameter does not lower the objective.
#[test]
fn fmm2022_re_constants_minimise_the_lpga_objective() {
    let best = Fmm2022ReFamily::FITTED;
    for (s, re) in [(0.1, 3e4), (0.3, 8e4), (0.5, 1.2e5), (0.9, 3e5)] {
        let (a, b) = (best.coefficients(s, re), Fmm2022Re.coefficients(s, re));
        assert!((a.cd - b.cd).abs() < 1e-15 && a.cl == b.cl && a.cm == b.cm);
        let (cd, cl, cm) = Fmm2022Re.coefficients_v(V::splat(s), V::splat(re));
        assert!((a.cd - cd.0[0]).abs() < 1e-15 && a.cl == cl.0[0] && a.cm == cm.0[0]);
    }
    let lpga = |m: &Fmm2022ReFamily| objective(m, &[&LPGA_TOUR_2023]);
    let f0 = lpga(&best);
    type Step = fn(&mut Fmm2022ReFamily, f64);
    let steps: [(Step, f64); 5] = [
        (|m, d| m.cd_low_re += d, 0.01),
        (|m, d| m.cd_per_s += d, 0.05),
        (|m, d| m.re_low += d, 1e4),
        (|m, d| m.re_high += d, 1e4),
        (|m, d| m.lift_loss += d.abs(), 0.05),
    ];
    for (k, (step, d)) in steps.iter().enumerate() {
        for sign in [-1.0, 1.0] {
            let mut m = best;
            step(&mut m, sign * d);
            let f = lpga(&m);
            assert!(f >= f0, "parameter {k} {sign:+}: {f} < {f0}");
        }
    }
}

/// Whether a member of the joint fit's family is on its grid's range (`examples/trackman_refit.rs
/// --joint`): `DR` 0–0.40, `DS` ±0.40, `LL` 0–1, `RE_LOW` ≥ 2·10⁴, `RE_HIGH` ≤ 10⁵ (the end of
/// the measured drag crisis), the window at least 2·10⁴ wide.
fn in_joint_family(m: &Fmm2022ReFamily) -> bool {
    let e = 1e-9;
    (-e..=0.40 + e).contains(&m.cd_low_re)
        && (-0.40 - e..=0.40 + e).contains(&m.cd_per_s)
        && (-e..=1.0 + e).contains(&m.lift_loss)
        && m.re_low >= 2e4 - 1.0
        && m.re_high <= 1e5 + 1.0
        && m.re_high - m.re_low >= 2e4 - 1.0
}

/// `fmm2022-tour`'s constants are the joint fit on all three TrackMan tables: the family at
/// them is the built-in model (scalar and lane forms), and no grid point in its neighbourhood
/// (every combination of one step down, none or one step up in each of the five constants,
/// inside the family) has a lower objective. The whole grid is searched by
/// `cargo run --release --example trackman_refit -- --joint` (the optimum: 220.40).
#[test]
fn fmm2022_tour_constants_minimise_the_joint_objective() {
    let best = Fmm2022Tour::FAMILY;
    for (s, re) in [
        (0.08, 2.2e5),
        (0.1, 3e4),
        (0.3, 8e4),
        (0.5, 9.5e4),
        (0.9, 3e5),
    ] {
        let (a, b) = (best.coefficients(s, re), Fmm2022Tour.coefficients(s, re));
        assert!(a == b, "{a:?} {b:?}");
        let (cd, cl, cm) = Fmm2022Tour.coefficients_v(V::splat(s), V::splat(re));
        assert!((a.cd - cd.0[0]).abs() < 1e-15 && (a.cl - cl.0[0]).abs() < 1e-15);
        assert!(a.cm == cm.0[0]);
    }
    let tables: [&[TourAverage]; 3] = [&PGA_TOUR, &PGA_TOUR_2023, &LPGA_TOUR_2023];
    let f0 = objective(&best, &tables);
    println!("joint objective at the shipped constants: {f0:.2}");
    let steps = [0.01, 0.05, 0.05, 1e4, 1e4];
    let mut seen = 0;
    for code in 0..243 {
        let mut d = [0.0; 5];
        let mut c = code;
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = ((c % 3) as f64 - 1.0) * steps[k];
            c /= 3;
        }
        let m = Fmm2022ReFamily {
            cd_low_re: best.cd_low_re + d[0],
            cd_per_s: best.cd_per_s + d[1],
            lift_loss: best.lift_loss + d[2],
            re_low: best.re_low + d[3],
            re_high: best.re_high + d[4],
            drag_floor: true,
        };
        if d == [0.0; 5] || !in_joint_family(&m) {
            continue;
        }
        seen += 1;
        let f = objective(&m, &tables);
        assert!(f >= f0, "step {d:?}: {f} < {f0}");
    }
    // 3^5 − 1 neighbours less those past RE_HIGH = 1e5: 2·3^4 − 1 = 161, and of these the
    // ones narrower than 2e4 (RE_LOW up, RE_HIGH down: 3^3 = 27) are outside too.
    assert_eq!(seen, 161 - 27);
}

/// Launches over the range the tool is used for: the TrackMan table plus curved, pushed,
/// high, low and very fast shots.
fn launch_set() -> Vec<FlightLaunch> {
    let mut v: Vec<FlightLaunch> = PGA_TOUR.iter().map(|r| r.launch()).collect();
    for (speed, la, az, back, side) in [
        (170.0, 12.0, 2.0, 2500.0, 900.0),
        (150.0, 8.0, -4.0, 3200.0, -1200.0),
        (95.0, 32.0, 0.0, 10_500.0, 300.0),
        (185.0, 5.0, 0.0, 1500.0, 0.0),
        (240.0, 14.0, 1.0, 2200.0, -400.0),
        (60.0, 45.0, 0.0, 6000.0, 0.0),
        (130.0, -3.0, 0.0, 4000.0, 0.0),
        (150.0, -0.3, 0.0, 3000.0, 0.0),
        (160.0, -1.1, 0.0, 2600.0, 0.0),
    ] {
        v.push(FlightLaunch::from_file_units(speed, la, az, back, side));
    }
    v
}

#[test]
fn step_size_passes_the_tolerance_test() {
    // The default step against a 64× finer one, for every built-in model: carry, offline and
    // apex within 0.02 yd (0.05 yd in wind), land angle within 0.02°, flight time within 2 ms.
    // Measured under the default `fmm2022`: 0.0012 yd, 0.0007° in still air at 0.35 s; 0.044 yd
    // (offline), 0.004° in the 8 m/s wind at 0.1 s (`fmm2022-tour`, the hardest of the three
    // `fmm2022` models: 0.0087 yd, 0.0086°; 0.0485 yd, 0.011°).
    for aero in [
        AeroModel::Fmm2022,
        AeroModel::Fmm2022Tour,
        AeroModel::Fmm2022Re,
    ] {
        step_tolerance(aero, [0.02 / 2.0, 0.05, 0.02, 2e-3]);
    }
    // `nathan-lyu`'s drag has corners (a linear ramp between `Re` 5·10⁴ and 10⁵, a kink in
    // `C_L` at `S` = 0.3), which cost RK4 its order: measured 0.077 yd carry, 0.006° and 2.7 ms
    // in still air. It is held to 0.1 yd (the resolution to which launch monitors report
    // carry, without the margin) and 5 ms, and docs/flight-models.md says so.
    step_tolerance(AeroModel::NathanLyu, [0.1, 0.1, 0.02, 5e-3]);
}

/// The step test for one model: its bounds on position in still air and in wind (yd), on the
/// land angle (°) and on the flight time (s).
fn step_tolerance(aero: AeroModel, bounds: [f64; 4]) {
    for wind in [0.0, 8.0] {
        let air = Atmosphere {
            wind_speed_m_s: wind,
            wind_direction_deg: 120.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap();
        let coarse = FlightConfig {
            aero: aero.clone(),
            air,
            ..FlightConfig::default()
        };
        let fine = FlightConfig {
            dt_s: Some(coarse.dt() / 64.0),
            ..coarse.clone()
        };
        let ls = launch_set();
        let (a, b) = (fly(&coarse, &ls), fly(&fine, &ls));
        let mut worst = [0.0f64; 5];
        for (a, b) in a.iter().zip(&b) {
            let (a, b) = (a.as_ref().unwrap(), b.as_ref().unwrap());
            let d = [
                (a.carry_yd() - b.carry_yd()).abs(),
                (a.offline_yd() - b.offline_yd()).abs(),
                (a.apex_yd() - b.apex_yd()).abs(),
                (a.land_angle_deg() - b.land_angle_deg()).abs(),
                (a.flight_time_s - b.flight_time_s).abs(),
            ];
            for (w, d) in worst.iter_mut().zip(d) {
                *w = w.max(d);
            }
        }
        println!(
            "{} wind {wind}: worst |coarse − fine| carry, offline, apex yd, land °, time s: \
             {worst:?}",
            aero.name()
        );
        // Still air: 0.02 yd and 0.02°. In wind the log profile's steep gradient near the
        // ground costs accuracy at launch and landing: 0.05 yd.
        // The default still-air step keeps a margin of two on the position bound.
        let tol = if wind == 0.0 { bounds[0] } else { bounds[1] };
        assert!(
            worst[0] < tol && worst[1] < tol && worst[2] < tol,
            "{}: {worst:?}",
            aero.name()
        );
        assert!(
            worst[3] < bounds[2] && worst[4] < bounds[3],
            "{}: {worst:?}",
            aero.name()
        );
    }
}

/// An independent integrator: adaptive Dormand–Prince 5(4) on the full 9-component state
/// (position, velocity, spin vector), written from the equations of motion with its own
/// coefficient, wind and event code.
mod reference {
    use super::*;

    pub struct Setup {
        pub rho: f64,
        pub mass: f64,
        pub radius: f64,
        pub inertia: f64,
        pub wind_ref: [f64; 2],
        /// Ball centre height at ground contact, m (`−tee height`).
        pub ground_y: f64,
        /// Density and viscosity the Reynolds number is taken in: the built-in models'
        /// reference air (ISA sea level), not the air flown through.
        pub re_rho: f64,
        /// Viscosity of that air, Pa·s.
        pub re_mu: f64,
        pub wind_h: f64,
        pub z0: f64,
    }

    type S9 = [f64; 9];

    fn deriv(c: &Setup, s: &S9) -> S9 {
        let area = std::f64::consts::PI * c.radius * c.radius;
        let h = s[1] + c.radius - c.ground_y;
        let (wx, wz) = if h > c.z0 {
            let f = (h / c.z0).ln() / (c.wind_h / c.z0).ln();
            (c.wind_ref[0] * f, c.wind_ref[1] * f)
        } else {
            (0.0, 0.0)
        };
        let vr = [s[3] - wx, s[4], s[5] - wz];
        let speed = (vr[0] * vr[0] + vr[1] * vr[1] + vr[2] * vr[2]).sqrt();
        let om = [s[6], s[7], s[8]];
        let spin = (om[0] * om[0] + om[1] * om[1] + om[2] * om[2]).sqrt();
        let sf = c.radius * spin / speed;
        let (cd, cl, cm) = coefficients(sf, c.re_rho * speed * 2.0 * c.radius / c.re_mu);
        let q = 0.5 * c.rho * speed * speed * area;
        let cross = [
            om[1] * vr[2] - om[2] * vr[1],
            om[2] * vr[0] - om[0] * vr[2],
            om[0] * vr[1] - om[1] * vr[0],
        ];
        let cn = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
        let mut d = [0.0; 9];
        for j in 0..3 {
            d[j] = s[3 + j];
            d[3 + j] = (q * cl * cross[j] / cn - q * cd * vr[j] / speed) / c.mass;
            d[6 + j] = -q * 2.0 * c.radius * cm * om[j] / spin / c.inertia;
        }
        d[4] -= 9.806_65;
        d
    }

    /// The default law written out from its published and fitted constants (Ferguson et al.
    /// 2022 quadratics, spin factor held at 0.75 from 0.80 on and blended in from 0.70 by a
    /// parabola tangent to both; lift tapered to 0 at S = 0 below 0.02; the drag less 0.15·S
    /// held above the still-air law 0.212 + 0.15·S by a maximum rounded within 0.01 of the
    /// crossing, plus 0.04 and times 0.4 for the lift below Re 7e4, fading as a smoothstep to
    /// nothing at 1e5): `(C_D, C_L, C_M)`.
    fn coefficients(sf: f64, re: f64) -> (f64, f64, f64) {
        // The parabola through (0.70, 0.70) with slope 1 and (0.80, 0.75) with slope 0.
        let s = if sf < 0.7 {
            sf
        } else if sf < 0.8 {
            0.75 - 5.0 * (0.8 - sf).powi(2)
        } else {
            0.75
        };
        let x = ((1e5 - re) / 3e4).clamp(0.0, 1.0);
        let crisis = x * x * (3.0 - 2.0 * x);
        // The rounded maximum: max(a, b) + (k − |a − b|)²/(4k) where |a − b| < k.
        let (spin_drag, still_air, k) =
            (0.1304 + 0.7787 * s - 0.8259 * s * s, 0.212 + 0.15 * s, 0.01);
        let gap = (spin_drag - still_air).abs();
        let rounding = if gap < k {
            (k - gap).powi(2) / (4.0 * k)
        } else {
            0.0
        };
        // No lift without spin: the fitted lift times a smoothstep in S/0.02 below S = 0.02.
        let u = (sf / 0.02).min(1.0);
        (
            spin_drag.max(still_air) + rounding + 0.04 * crisis,
            (0.0504 + 1.2031 * s - 1.1490 * s * s) * u * u * (3.0 - 2.0 * u) * (1.0 - 0.6 * crisis),
            0.01 * s,
        )
    }

    fn add(s: &S9, h: f64, ks: &[(f64, &S9)]) -> S9 {
        let mut r = *s;
        for (a, k) in ks {
            for j in 0..9 {
                r[j] += h * a * k[j];
            }
        }
        r
    }

    /// One Dormand–Prince step: (5th-order result, error estimate).
    fn dp_step(c: &Setup, s: &S9, h: f64) -> (S9, f64) {
        let k1 = deriv(c, s);
        let k2 = deriv(c, &add(s, h, &[(1.0 / 5.0, &k1)]));
        let k3 = deriv(c, &add(s, h, &[(3.0 / 40.0, &k1), (9.0 / 40.0, &k2)]));
        let k4 = deriv(
            c,
            &add(
                s,
                h,
                &[(44.0 / 45.0, &k1), (-56.0 / 15.0, &k2), (32.0 / 9.0, &k3)],
            ),
        );
        let k5 = deriv(
            c,
            &add(
                s,
                h,
                &[
                    (19372.0 / 6561.0, &k1),
                    (-25360.0 / 2187.0, &k2),
                    (64448.0 / 6561.0, &k3),
                    (-212.0 / 729.0, &k4),
                ],
            ),
        );
        let k6 = deriv(
            c,
            &add(
                s,
                h,
                &[
                    (9017.0 / 3168.0, &k1),
                    (-355.0 / 33.0, &k2),
                    (46732.0 / 5247.0, &k3),
                    (49.0 / 176.0, &k4),
                    (-5103.0 / 18656.0, &k5),
                ],
            ),
        );
        let y5 = add(
            s,
            h,
            &[
                (35.0 / 384.0, &k1),
                (500.0 / 1113.0, &k3),
                (125.0 / 192.0, &k4),
                (-2187.0 / 6784.0, &k5),
                (11.0 / 84.0, &k6),
            ],
        );
        let k7 = deriv(c, &y5);
        let y4 = add(
            s,
            h,
            &[
                (5179.0 / 57600.0, &k1),
                (7571.0 / 16695.0, &k3),
                (393.0 / 640.0, &k4),
                (-92097.0 / 339200.0, &k5),
                (187.0 / 2100.0, &k6),
                (1.0 / 40.0, &k7),
            ],
        );
        let mut err: f64 = 0.0;
        for j in 0..9 {
            let sc = 1e-12 + 1e-11 * y5[j].abs().max(s[j].abs());
            err = err.max((y5[j] - y4[j]).abs() / sc);
        }
        (y5, err)
    }

    /// (carry m, offline m, apex m, land angle rad, flight time s).
    pub fn fly(c: &Setup, l: &FlightLaunch) -> (f64, f64, f64, f64, f64) {
        let (v, la, az) = (l.ball_speed_m_s, l.launch_angle_rad, l.azimuth_rad);
        let mut s: S9 = [
            0.0,
            0.0,
            0.0,
            v * la.cos() * az.cos(),
            v * la.sin(),
            v * la.cos() * az.sin(),
            0.0,
            -l.sidespin_rad_s,
            l.backspin_rad_s,
        ];
        let (mut t, mut h, mut apex) = (0.0, 1e-3, 0.0f64);
        loop {
            let (n, err) = dp_step(c, &s, h);
            if err > 1.0 {
                h *= (0.9 * err.powf(-0.2)).max(0.1);
                continue;
            }
            if n[1] < c.ground_y {
                // Land: secant iterations on the step length to the ground.
                let (mut a, mut b) = (0.0, h);
                let (mut ya, mut yb) = (s[1] - c.ground_y, n[1] - c.ground_y);
                let mut end = n;
                let mut hl = h;
                for _ in 0..60 {
                    hl = b - yb * (b - a) / (yb - ya);
                    end = dp_step(c, &s, hl).0;
                    let e = end[1] - c.ground_y;
                    if e.abs() < 1e-11 || ya == 0.0 {
                        break;
                    }
                    if e > 0.0 {
                        a = hl;
                        ya = e;
                    } else {
                        b = hl;
                        yb = e;
                    }
                }
                let horiz = end[3].hypot(end[5]);
                // Carry: the landing's signed coordinate along the target line.
                return (
                    end[0],
                    end[2],
                    apex.max(end[1]),
                    (-end[4]).atan2(horiz),
                    t + hl,
                );
            }
            // Apex: where v_y changes sign, refine by secant on the step length.
            if s[4] > 0.0 && n[4] <= 0.0 {
                let (mut a, mut b) = (0.0, h);
                let (mut va, mut vb) = (s[4], n[4]);
                for _ in 0..60 {
                    let hm = b - vb * (b - a) / (vb - va);
                    let m = dp_step(c, &s, hm).0;
                    apex = apex.max(m[1]);
                    if m[4].abs() < 1e-12 {
                        break;
                    }
                    if m[4] > 0.0 {
                        a = hm;
                        va = m[4];
                    } else {
                        b = hm;
                        vb = m[4];
                    }
                }
            }
            apex = apex.max(n[1]);
            s = n;
            t += h;
            h *= (0.9 * err.max(1e-10).powf(-0.2)).min(5.0);
        }
    }
}

#[test]
fn agrees_with_an_independent_adaptive_integrator() {
    // On the ground and teed (40 mm): the downward launches land at once from the ground and
    // dip below their address height from the tee.
    let cases = [(0.0, 0.0, 0.0), (6.0, 200.0, 0.0), (0.0, 0.0, 0.04)];
    for (wind, dir, tee_m) in cases {
        let atm = Atmosphere {
            temperature_c: 27.0,
            elevation_m: Some(600.0),
            humidity_pct: 70.0,
            wind_speed_m_s: wind,
            wind_direction_deg: dir,
            ..Atmosphere::default()
        };
        let air = atm.air().unwrap();
        let reference = Atmosphere::default().air().unwrap();
        // The reference writes out `fmm2022-tour`'s law (the richest built-in one: floor,
        // Reynolds window, lift loss), so the batched integrator flies that model here.
        let cfg = FlightConfig {
            aero: AeroModel::Fmm2022Tour,
            air,
            spin_decay: SpinDecay::Moment,
            tee_height_m: tee_m,
            ..FlightConfig::default()
        };
        let setup = reference::Setup {
            rho: air.density_kg_m3,
            mass: cfg.ball.mass_kg,
            radius: cfg.ball.radius_m,
            inertia: cfg.ball.inertia_kg_m2,
            wind_ref: [wind * dir.to_radians().cos(), wind * dir.to_radians().sin()],
            wind_h: atm.wind_height_m,
            z0: atm.roughness_m,
            ground_y: -tee_m,
            re_rho: reference.density_kg_m3,
            re_mu: reference.viscosity_pa_s,
        };
        let mut worst = [0.0f64; 5];
        for l in launch_set() {
            let f = fly_one(&cfg, &l).unwrap();
            let r = reference::fly(&setup, &l);
            let d = [
                (f.carry_m - r.0).abs(),
                (f.offline_m - r.1).abs(),
                (f.apex_m - r.2).abs(),
                (f.land_angle_rad - r.3).abs().to_degrees(),
                (f.flight_time_s - r.4).abs(),
            ];
            for (w, d) in worst.iter_mut().zip(d) {
                *w = w.max(d);
            }
        }
        println!(
            "wind {wind}, tee {tee_m} m: worst |batched − DP45| carry, offline, apex m, land °, time s: {worst:?}"
        );
        // Integration tolerance: 2 cm in still air (5 cm in wind, see the step test), 0.02°,
        // 2 ms.
        let tol = if wind == 0.0 { 0.02 } else { 0.05 };
        assert!(
            worst[0] < tol && worst[1] < tol && worst[2] < tol,
            "{worst:?}"
        );
        assert!(worst[3] < 0.02 && worst[4] < 2e-3, "{worst:?}");
    }
}
