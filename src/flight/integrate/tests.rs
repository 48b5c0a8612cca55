//! Tests of the batched integrator (`super`).

use super::*;
use crate::flight::aero::{Fmm2022Re, NathanLyu};
use crate::flight::G_M_S2;
use crate::flight::{Atmosphere, FlightLaunch};

fn drive() -> FlightLaunch {
    FlightLaunch::from_file_units(167.0, 10.9, 0.0, 2686.0, 0.0)
}

#[test]
fn vacuum_flight_matches_closed_form() {
    // No air: the range of a projectile v²·sin 2θ / g, apex v²sin²θ/(2g).
    let mut cfg = FlightConfig::default();
    cfg.air.density_kg_m3 = 0.0;
    let l = FlightLaunch::from_file_units(100.0, 30.0, 0.0, 3000.0, 0.0);
    let f = fly_one(&cfg, &l).unwrap();
    let v = l.ball_speed_m_s;
    let range = v * v * (2.0 * l.launch_angle_rad).sin() / G_M_S2;
    let apex = (v * l.launch_angle_rad.sin()).powi(2) / (2.0 * G_M_S2);
    assert!((f.carry_m - range).abs() < 1e-9, "{} {}", f.carry_m, range);
    assert!((f.apex_m - apex).abs() < 1e-9);
    assert!((f.land_angle_rad - l.launch_angle_rad).abs() < 1e-9);
    let tof = 2.0 * v * l.launch_angle_rad.sin() / G_M_S2;
    assert!((f.flight_time_s - tof).abs() < 1e-9);
}

#[test]
fn flights_shorter_than_one_step_land_after_their_apex() {
    // A 5 mph pitch lasts 0.08 s, a quarter of the default step: the step's crossing at
    // θ = 0 is the launch, not the landing. In vacuum the closed form; in air a fine step
    // (to 1 mm, a tenth of the step tolerance of the flight's 0.01 yd).
    let mut vacuum = FlightConfig::default();
    vacuum.air.density_kg_m3 = 0.0;
    for (mph, deg) in [(5.0, 10.0), (2.0, 60.0), (1.0, 5.0)] {
        let l = FlightLaunch::from_file_units(mph, deg, 0.0, 1000.0, 0.0);
        let f = fly_one(&vacuum, &l).unwrap();
        let (v, th) = (l.ball_speed_m_s, l.launch_angle_rad);
        let range = v * v * (2.0 * th).sin() / G_M_S2;
        assert!(
            (f.carry_m - range).abs() < 1e-9 * (1.0 + range),
            "{mph} mph: {f:?}"
        );
        assert!((f.land_angle_rad - th).abs() < 1e-9, "{mph} mph: {f:?}");
        let tof = 2.0 * v * th.sin() / G_M_S2;
        assert!((f.flight_time_s - tof).abs() < 1e-9, "{mph} mph: {f:?}");
    }
    let air = FlightConfig::default();
    let fine = FlightConfig {
        dt_s: Some(0.001),
        ..FlightConfig::default()
    };
    let l = FlightLaunch::from_file_units(5.0, 10.0, 0.0, 1000.0, 0.0);
    let (f, g) = (fly_one(&air, &l).unwrap(), fly_one(&fine, &l).unwrap());
    let (dc, da) = (f.carry_m - g.carry_m, f.land_angle_rad - g.land_angle_rad);
    let close = dc.abs() < 1e-3 && da.abs() < 1e-3;
    assert!(f.carry_m > 0.15 && close, "{f:?} {g:?}");
}

/// The results, in input order, are each launch's own whatever the batch: 37 launches (one
/// task, in input order) and 300 in a scrambled order of hang time with a bad launch among them
/// (flown in hang order, [`in_hang_order`], and put back), by `fly` and by `fly_with`.
#[test]
fn batching_and_threads_do_not_change_results() {
    let cfg = FlightConfig::default();
    let ls: Vec<FlightLaunch> = (0..37)
        .map(|k| {
            FlightLaunch::from_file_units(
                100.0 + k as f64,
                8.0 + 0.3 * k as f64,
                -3.0 + 0.2 * k as f64,
                2000.0 + 150.0 * k as f64,
                -800.0 + 40.0 * k as f64,
            )
        })
        .collect();
    let all = fly(&cfg, &ls);
    for (k, l) in ls.iter().enumerate() {
        assert_eq!(all[k], fly_one(&cfg, l), "launch {k}");
    }
    let mut many: Vec<FlightLaunch> = (0..300)
        .map(|k| {
            let (a, b) = ((k * 37) % 101, (k * 53) % 97);
            FlightLaunch::from_file_units(
                60.0 + a as f64,
                2.0 + 0.4 * b as f64,
                -3.0 + 0.02 * k as f64,
                1500.0 + 30.0 * b as f64,
                -600.0 + 4.0 * k as f64,
            )
        })
        .collect();
    many[150].launch_angle_rad = f64::NAN;
    let flown = fly(&cfg, &many);
    let with = cfg.aero.visit(FlyWith {
        cfg: &cfg,
        launches: &many,
    });
    assert!(flown[150].is_err());
    for (k, l) in many.iter().enumerate() {
        // Debug text: the shortest digits that give back the same bits, and NaN equal to NaN.
        let own = format!("{:?}", fly_one(&cfg, l));
        assert_eq!(format!("{:?}", flown[k]), own, "launch {k}");
        assert_eq!(format!("{:?}", with[k]), own, "launch {k}");
    }
    let mut serial = vec![Ok(fly_one(&cfg, &ls[0]).unwrap()); ls.len()];
    fly_serial(&cfg, &ls, &mut serial);
    assert_eq!(all, serial);
}

/// [`fly_with`] under the configuration's own model.
struct FlyWith<'a> {
    cfg: &'a FlightConfig,
    launches: &'a [FlightLaunch],
}

impl ModelVisitor for FlyWith<'_> {
    type Output = Vec<Result<Flight, FlightError>>;
    fn visit<C: CoefficientModel>(self, model: &C) -> Self::Output {
        fly_with(self.cfg, model, self.launches)
    }
}

/// Every lane type this machine runs (portable, AVX2, AVX-512) flies the same bits, with
/// and without wind (and the ground roll), under every built-in model.
#[test]
fn every_lane_type_flies_the_same_bits() {
    let ls: Vec<FlightLaunch> = (0..53)
        .map(|k| {
            let k = k as f64;
            FlightLaunch::from_file_units(
                40.0 + 2.7 * k,
                4.0 + 0.9 * k,
                -6.0 + 0.25 * k,
                300.0 + 160.0 * k,
                -1500.0 + 55.0 * k,
            )
        })
        .collect();
    let windy = FlightConfig {
        air: Atmosphere {
            wind_speed_m_s: 7.0,
            wind_direction_deg: 70.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap(),
        ground: Some(Default::default()),
        ..FlightConfig::default()
    };
    for cfg in [FlightConfig::default(), windy] {
        for level in SimdLevel::ALL {
            let (a, b) = (
                bits(level, &cfg, &Fmm2022Re, &ls),
                bits(SimdLevel::Portable, &cfg, &Fmm2022Re, &ls),
            );
            assert_eq!(a, b, "{level:?}");
            let (a, b) = (
                bits(level, &cfg, &NathanLyu, &ls),
                bits(SimdLevel::Portable, &cfg, &NathanLyu, &ls),
            );
            assert_eq!(a, b, "{level:?}");
        }
    }
}

/// The bits of the flights of `ls` on the lanes of `level`.
fn bits<C: CoefficientModel>(
    level: SimdLevel,
    cfg: &FlightConfig,
    model: &C,
    ls: &[FlightLaunch],
) -> Vec<u64> {
    let mut out = vec![Err(FlightError::NeverLands { time_limit_s: 0.0 }); ls.len()];
    dispatch_on(level, cfg, model, cfg.air.has_wind(), ls, &mut out);
    out.iter()
        .flat_map(|f| {
            let f = f.as_ref().expect("lands");
            [
                f.carry_m,
                f.offline_m,
                f.apex_m,
                f.land_angle_rad,
                f.flight_time_s,
            ]
            .into_iter()
            .chain(f.total_m)
            .map(f64::to_bits)
        })
        .collect()
}

/// The flights of `ls` under `cfg` on the lanes of `level`, on this thread, with the contact
/// searches put off or not ([`defer`]), and the contact refinement's counts: steps
/// re-integrated, substeps computed.
fn fly_counting(
    level: SimdLevel,
    cfg: &FlightConfig,
    ls: &[FlightLaunch],
    put_off: bool,
) -> (Vec<Result<Flight, FlightError>>, u64, u64) {
    land::REFINED.with(|n| n.set(0));
    land::SUBSTEPS.with(|n| n.set(0));
    defer::DEFER.with(|d| d.set(put_off));
    let mut out = vec![Err(FlightError::NeverLands { time_limit_s: 0.0 }); ls.len()];
    cfg.aero.visit(FlyOn {
        level,
        cfg,
        launches: ls,
        out: &mut out,
    });
    defer::DEFER.with(|d| d.set(true));
    let refined = land::REFINED.with(|n| n.get());
    (out, refined, land::SUBSTEPS.with(|n| n.get()))
}

/// Contact searches put off and done a vector at a time give the same bits as searched in
/// their steps, on 2,000 drives in no particular order, and take about one refinement for
/// every `N` drives instead of about three for every group of `N` (each stopping once its
/// lanes have landed).
#[test]
fn contact_searches_put_off_are_the_same_bits_in_fewer_refinements() {
    let cfg = FlightConfig::default();
    let ls = crate::flight::workload::drives(2000);
    for level in SimdLevel::ALL {
        let (now, refined_now, substeps_now) = fly_counting(level, &cfg, &ls, false);
        let (later, refined, substeps) = fly_counting(level, &cfg, &ls, true);
        assert_eq!(format!("{later:?}"), format!("{now:?}"), "{level:?}");
        let lanes = match level.or_supported() {
            SimdLevel::Avx512 => 8,
            _ => 4,
        };
        let vectors = (ls.len() as u64).div_ceil(lanes);
        assert!(refined <= vectors + 1, "{level:?}: {refined} refinements");
        assert!(
            refined_now > 2 * vectors,
            "{level:?}: {refined_now} refinements"
        );
        assert!(
            substeps < refined * REFINE as u64,
            "{level:?}: {substeps} substeps"
        );
        assert!(
            2 * substeps < substeps_now,
            "{level:?}: {substeps} {substeps_now} substeps"
        );
    }
}

/// Launches whose contact search finds no landing (a ball that dips from a tee and flies on,
/// a trough that does not reach the ground) are flown again with each contact searched in its
/// step: the same bits as never putting a search off, with wind, ground roll and every model.
#[test]
fn dips_that_fly_on_are_the_same_bits_when_put_off() {
    let mut ls: Vec<FlightLaunch> = (0..40)
        .map(|k| {
            let k = k as f64;
            FlightLaunch::from_file_units(60.0 + 3.0 * k, -1.5 + 0.1 * k, 0.0, 4000.0, 0.0)
        })
        .collect();
    ls.extend(crate::flight::workload::drives(50));
    ls[7].ball_speed_m_s = f64::NAN;
    defer::REDONE.with(|n| n.set(0));
    for aero in crate::flight::aero::MODEL_NAMES {
        let cfg = FlightConfig {
            aero: crate::flight::AeroModel::from_name(aero).unwrap(),
            tee_height_m: 0.04,
            ground: Some(Default::default()),
            ..FlightConfig::default()
        };
        let windy = FlightConfig {
            air: Atmosphere {
                wind_speed_m_s: 6.0,
                wind_direction_deg: 200.0,
                ..Atmosphere::default()
            }
            .air()
            .unwrap(),
            ..cfg.clone()
        };
        for cfg in [cfg, windy] {
            for level in SimdLevel::ALL {
                let (now, ..) = fly_counting(level, &cfg, &ls, false);
                let (later, refined, _) = fly_counting(level, &cfg, &ls, true);
                assert_eq!(format!("{later:?}"), format!("{now:?}"), "{aero} {level:?}");
                assert!(refined > 0);
            }
        }
    }
    // Some searches found no landing, and those launches were flown again.
    assert!(defer::REDONE.with(|n| n.get()) > 0);
}

#[test]
fn slice_spin_curves_right_and_wind_pushes() {
    let cfg = FlightConfig::default();
    let mut l = drive();
    l.sidespin_rad_s = crate::units::rpm(800.0);
    let f = fly_one(&cfg, &l).unwrap();
    assert!(f.offline_m > 5.0, "{}", f.offline_m);
    let straight = fly_one(&cfg, &drive()).unwrap();
    assert!(straight.offline_m.abs() < 1e-9);
    let tail = FlightConfig {
        air: Atmosphere {
            wind_speed_m_s: 5.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap(),
        ..FlightConfig::default()
    };
    let head = FlightConfig {
        air: Atmosphere {
            wind_speed_m_s: 5.0,
            wind_direction_deg: 180.0,
            ..Atmosphere::default()
        }
        .air()
        .unwrap(),
        ..FlightConfig::default()
    };
    let ft = fly_one(&tail, &drive()).unwrap();
    let fh = fly_one(&head, &drive()).unwrap();
    assert!(ft.carry_m > straight.carry_m + 3.0 && fh.carry_m < straight.carry_m - 3.0);
}

#[test]
fn bad_launches_and_time_limit() {
    let cfg = FlightConfig::default();
    let mut l = drive();
    l.ball_speed_m_s = -1.0;
    assert!(matches!(
        fly_one(&cfg, &l),
        Err(FlightError::InvalidLaunch {
            field: "ball_speed_mph",
            ..
        })
    ));
    let mut l = drive();
    l.launch_angle_rad = 1.7;
    assert!(matches!(
        fly_one(&cfg, &l),
        Err(FlightError::InvalidLaunch {
            field: "launch_angle_deg",
            ..
        })
    ));
    let mut l = drive();
    l.backspin_rad_s = crate::units::rpm(50_000.0);
    assert!(fly_one(&cfg, &l).is_err());
    let short = FlightConfig {
        max_time_s: 2.0,
        ..FlightConfig::default()
    };
    assert_eq!(
        fly_one(&short, &drive()),
        Err(FlightError::NeverLands { time_limit_s: 2.0 })
    );
}
