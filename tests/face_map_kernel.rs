//! The face-map kernel against the generic reference path, `ImpactModel::solve` + `launch()`:
//! same validity on every point, same launch outputs to 1e-12 relative (1e-9 absolute near
//! zero), over random models with random effects, random deliveries and random grids; and
//! bit-identical results whatever the chunking, point order, thread count or code path.

use nalgebra::Vector3;
use proptest::prelude::*;
use smash::physics::{ImpactModel, ModelParams};
use smash::sweep::{face_map, FaceMapKernel, LaunchGrid, SimdLevel};
use smash::{Delivery, LaunchComponent};

fn paper_params() -> ModelParams {
    ModelParams::paper_driver()
}

/// Random models: the paper's driver with a random subset of effects at random strengths,
/// and random face radii.
fn model_strategy() -> impl Strategy<Value = ImpactModel> {
    let on = |p: f64| prop::bool::weighted(p);
    (
        (
            on(0.5),
            -0.03f64..0.06,
            on(0.5),
            -2.0e-3f64..2.0e-3,
            -2.0e-3f64..2.0e-3,
        ),
        (on(0.5), -0.4f64..0.4, on(0.4), 0.05f64..0.8),
        (on(0.5), -0.01f64..0.02, on(0.5), 0.0f64..300.0),
        (on(0.5), -4.0f64..4.0, -4.0f64..4.0),
        (on(0.5), prop::array::uniform3(-6e-3f64..6e-3), 0.6f64..1.5),
        (
            0.15f64..0.6,
            0.15f64..0.6,
            0.6f64..1.0,
            on(0.5),
            0.0f64..1.0,
        ),
    )
        .prop_map(
            |(
                (am, dm, bo, dy, dz),
                (tr, et, fr, mu),
                (cs, k, cr, c),
                (bias, loft, face),
                (co, com, scale),
                (bulge, roll, cor, cp, q),
            )| {
                let mut p = paper_params();
                if cp {
                    p.cor_power_q = q;
                }
                if am {
                    p.club_mass_kg += dm;
                }
                if bo {
                    p.ball_offset_y_m = dy;
                    p.ball_offset_z_m = dz;
                }
                if tr {
                    p.tangential_restitution = et;
                }
                if fr {
                    p.friction_mu = Some(mu);
                }
                if cs {
                    p.cor_speed_k_s_per_m = k;
                }
                if cr {
                    p.cor_radial_c_per_m2 = c;
                }
                if bias {
                    p.loft_bias_rad = loft.to_radians();
                    p.face_bias_rad = face.to_radians();
                }
                if co {
                    p.club_com_m += Vector3::from(com);
                }
                p.club_inertia_kgm2 *= scale;
                p.bulge_m = bulge;
                p.roll_m = roll;
                p.cor = cor;
                ImpactModel::new(p).expect("valid random model")
            },
        )
}

/// Random deliveries; some slow and spinning fast, so that the club does not approach the ball
/// over part of the face.
fn delivery_strategy() -> impl Strategy<Value = Delivery> {
    (
        prop_oneof![3 => 25.0f64..60.0, 1 => 0.2f64..3.0],
        prop::array::uniform3(-8.0f64..8.0),
        5.0f64..35.0,
        -4.0f64..4.0,
        prop_oneof![3 => prop::array::uniform3(-40.0f64..40.0), 1 => prop::array::uniform3(-150.0f64..150.0)],
    )
        .prop_map(|(speed, [attack, path, face], loft, lie, omega)| Delivery {
            club_speed_m_s: speed,
            attack_angle_rad: attack.to_radians(),
            club_path_rad: path.to_radians(),
            dynamic_loft_rad: loft.to_radians(),
            face_angle_rad: face.to_radians(),
            lie_tilt_rad: lie.to_radians(),
            club_omega_rad_s: Vector3::from(omega),
            impact_y_m: 0.0,
            impact_z_m: 0.0,
            shaft_mass_g: None,
        })
}

/// Random grid axes: mostly on the face, sometimes reaching past the torus (|y| > roll, or
/// |z| > ρ), lengths not multiples of the chunk size.
fn axes_strategy() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (
        prop::collection::vec(prop_oneof![4 => -0.03f64..0.03, 1 => -0.7f64..0.7], 1..12),
        prop::collection::vec(prop_oneof![4 => -0.05f64..0.05, 1 => -1.5f64..1.5], 1..23),
    )
}

fn close(got: f64, want: f64) -> bool {
    let d = (got - want).abs();
    d <= 1e-12 * want.abs() || d <= 1e-9
}

/// Whether the friction decision of `model` at `d` is within rounding of its threshold
/// (|P_t| = mu·P_n for the no-slip impulse), where the kernel and the generic path may
/// legitimately take different branches.
fn near_slip_threshold(model: &ImpactModel, d: &Delivery) -> bool {
    let Some(mu) = model.params().friction_mu else {
        return false;
    };
    let mut p = model.params().clone();
    p.friction_mu = None;
    let Ok(o) = ImpactModel::new(p).unwrap().solve(d) else {
        return false;
    };
    let pn = o.impulse_n_s.dot(&o.normal);
    let pt = (o.impulse_n_s - pn * o.normal).norm();
    (pt - mu * pn).abs() <= 1e-9 * o.impulse_n_s.norm()
}

/// Compare a kernel result at `(y, z)` (index `i` of `grid`) with the generic path.
fn check_point(
    model: &ImpactModel,
    d0: &Delivery,
    y: f64,
    z: f64,
    grid: &LaunchGrid,
    i: usize,
) -> Result<(), TestCaseError> {
    let mut d = *d0;
    d.impact_y_m = y;
    d.impact_z_m = z;
    match model.solve(&d) {
        Ok(o) => {
            prop_assert!(grid.valid[i], "valid point ({y}, {z}) flagged invalid");
            if near_slip_threshold(model, &d) {
                return Ok(());
            }
            let l = o.launch();
            for c in LaunchComponent::ALL {
                let (got, want) = (grid.component(c)[i], l.get_si(c));
                prop_assert!(
                    close(got, want),
                    "{c:?} at ({y}, {z}): kernel {got:e}, generic {want:e}, diff {:e}",
                    got - want
                );
            }
        }
        Err(e) => {
            prop_assert!(
                !grid.valid[i],
                "invalid point ({y}, {z}) flagged valid: {e}"
            );
            for c in LaunchComponent::ALL {
                prop_assert!(grid.component(c)[i].is_nan());
            }
        }
    }
    Ok(())
}

fn bits(g: &LaunchGrid) -> Vec<u64> {
    LaunchComponent::ALL
        .iter()
        .flat_map(|&c| g.component(c).iter().map(|v| v.to_bits()))
        .chain(g.valid.iter().map(|&v| v as u64))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Face maps agree with the generic solve point by point, validity exactly.
    #[test]
    fn face_map_matches_generic_solve(
        model in model_strategy(),
        d in delivery_strategy(),
        (ys, zs) in axes_strategy(),
    ) {
        let grid = face_map(&model, &d, &ys, &zs);
        prop_assert_eq!(grid.len(), ys.len() * zs.len());
        for (i, &y) in ys.iter().enumerate() {
            for (j, &z) in zs.iter().enumerate() {
                check_point(&model, &d, y, z, &grid, i * zs.len() + j)?;
            }
        }
    }

    /// Arbitrary point sets agree with the generic solve too.
    #[test]
    fn points_match_generic_solve(
        model in model_strategy(),
        d in delivery_strategy(),
        pts in prop::collection::vec((prop_oneof![4 => -0.03f64..0.03, 1 => -0.7f64..0.7],
                                      prop_oneof![4 => -0.05f64..0.05, 1 => -1.5f64..1.5]), 1..40),
    ) {
        let (ys, zs): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
        let mut grid = LaunchGrid::with_len(ys.len());
        FaceMapKernel::new(&model, &d).eval_points(&ys, &zs, grid.all_out());
        for i in 0..ys.len() {
            check_point(&model, &d, ys[i], zs[i], &grid, i)?;
        }
    }

    /// A point's bits do not depend on its position in a row, the chunking, the thread
    /// count or the code path (AVX2 or portable).
    #[test]
    fn results_are_bit_identical_however_computed(
        model in model_strategy(),
        d in delivery_strategy(),
        (ys, zs) in axes_strategy(),
        shift in 0usize..9,
    ) {
        let k = FaceMapKernel::new(&model, &d);
        let n = ys.len() * zs.len();
        let mut serial = LaunchGrid::with_len(n);
        k.eval_grid(&ys, &zs, &mut serial);
        let reference = bits(&serial);
        prop_assert_eq!(&bits(&face_map(&model, &d, &ys, &zs)), &reference);
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut par = LaunchGrid::with_len(n);
            pool.install(|| k.par_eval_grid(&ys, &zs, &mut par));
            prop_assert_eq!(&bits(&par), &reference);
        }
        // Portable path, row by row.
        let mut portable = LaunchGrid::with_len(n);
        for (i, &y) in ys.iter().enumerate() {
            k.eval_row_on(SimdLevel::Portable, y, &zs, portable.row_out(i * zs.len(), zs.len()));
        }
        prop_assert_eq!(&bits(&portable), &reference);
        // The same points as a flat point list, rotated by `shift` so they sit in other lanes
        // and chunks, on both paths.
        let (mut py, mut pz): (Vec<f64>, Vec<f64>) = ys
            .iter()
            .flat_map(|&y| zs.iter().map(move |&z| (y, z)))
            .unzip();
        let s = shift % n;
        py.rotate_left(s);
        pz.rotate_left(s);
        for level in [SimdLevel::Avx2, SimdLevel::Portable] {
            let mut pts = LaunchGrid::with_len(n);
            k.eval_points_on(level, &py, &pz, pts.all_out());
            let mut unrotated = LaunchGrid::with_len(n);
            for i in 0..n {
                let j = (i + n - s) % n;
                for c in LaunchComponent::ALL {
                    let v = pts.component(c)[j];
                    match c {
                        LaunchComponent::BallSpeed => unrotated.ball_speed_m_s[i] = v,
                        LaunchComponent::LaunchAngle => unrotated.launch_angle_rad[i] = v,
                        LaunchComponent::Azimuth => unrotated.azimuth_rad[i] = v,
                        LaunchComponent::Backspin => unrotated.backspin_rad_s[i] = v,
                        LaunchComponent::Sidespin => unrotated.sidespin_rad_s[i] = v,
                    }
                }
                unrotated.valid[i] = pts.valid[j];
            }
            prop_assert_eq!(&bits(&unrotated), &reference);
        }
    }
}

/// A dense face map of the paper's driver: max relative deviation from the generic solve,
/// printed for the record (run with `--nocapture`).
#[test]
fn paper_driver_dense_map_deviation() {
    let model = ImpactModel::new(paper_params()).unwrap();
    let d = Delivery {
        club_speed_m_s: 47.0,
        attack_angle_rad: (-1.0f64).to_radians(),
        club_path_rad: 1.5f64.to_radians(),
        dynamic_loft_rad: 12.5f64.to_radians(),
        face_angle_rad: 0.5f64.to_radians(),
        lie_tilt_rad: 0.5f64.to_radians(),
        club_omega_rad_s: Vector3::new(-2.0, 5.0, -10.0),
        impact_y_m: 0.0,
        impact_z_m: 0.0,
        shaft_mass_g: None,
    };
    let n = 201;
    let lin = |h: f64| -> Vec<f64> {
        (0..n)
            .map(|i| -h + 2.0 * h * i as f64 / (n - 1) as f64)
            .collect()
    };
    let (ys, zs) = (lin(0.025), lin(0.040));
    let grid = face_map(&model, &d, &ys, &zs);
    let mut worst = [0.0f64; 5];
    for (i, &y) in ys.iter().enumerate() {
        for (j, &z) in zs.iter().enumerate() {
            let mut dd = d;
            dd.impact_y_m = y;
            dd.impact_z_m = z;
            let l = model.solve(&dd).unwrap().launch();
            for c in LaunchComponent::ALL {
                let (got, want) = (grid.component(c)[i * n + j], l.get_si(c));
                assert!(close(got, want), "{c:?} at ({y}, {z}): {got} vs {want}");
                if want.abs() > 1e-3 {
                    worst[c.index()] = worst[c.index()].max(((got - want) / want).abs());
                }
            }
        }
    }
    eprintln!("max relative deviation kernel vs generic (speed, launch, azimuth, backspin, sidespin; |value| > 1e-3): {worst:?}");
}

/// The next `k`-th double after `x` (toward +∞), for positive or negative finite `x`.
fn nudge(x: f64, k: i64) -> f64 {
    let b = x.to_bits() as i64;
    if x >= 0.0 {
        f64::from_bits((b + k) as u64)
    } else {
        f64::from_bits((b - k) as u64)
    }
}

/// Validity agrees exactly even at the rim of the approach region: bisect, to the last bit,
/// the heel–toe location where the generic solve switches between "approaching" and "not
/// approaching" (u1·n = 0), then compare the kernel on the doubles around it.
#[test]
fn validity_agrees_at_the_approach_boundary_to_the_last_bit() {
    let mut checked = 0;
    // (speed, ω_y, lie, loft, rows): spinning slow clubs, where u1·n changes fast along the
    // row, and a club moving almost along a steep face (loft 85°, no spin), where u1·n is
    // nearly flat in z near the rim so the sign is decided by the last bits.
    let cases = [
        (
            1.0,
            60.0,
            0.0f64,
            10.0f64,
            vec![-0.02, -0.01, -0.004, 0.0, 0.006, 0.013, 0.021],
        ),
        (2.0, -90.0, 2.0, 10.0, vec![-0.01, 0.0, 0.013]),
        (0.5, 25.0, -3.0, 10.0, vec![-0.01, 0.0, 0.013]),
        (40.0, 0.0, 0.0, 85.0, vec![0.0262, 0.0264, 0.0266]),
        (40.0, 0.0, 1.0, 84.0, vec![0.0290, 0.0295]),
    ];
    for (speed, omega_y, lie, loft, rows) in cases {
        for friction in [None, Some(0.3)] {
            let mut p = paper_params();
            p.friction_mu = friction;
            p.ball_offset_y_m = 0.3e-3;
            let model = ImpactModel::new(p).unwrap();
            let d = Delivery {
                club_speed_m_s: speed,
                attack_angle_rad: 0.0,
                club_path_rad: 0.0,
                dynamic_loft_rad: loft.to_radians(),
                face_angle_rad: 0.0,
                lie_tilt_rad: lie.to_radians(),
                club_omega_rad_s: Vector3::new(0.0, omega_y, 0.0),
                impact_y_m: 0.0,
                impact_z_m: 0.0,
                shaft_mass_g: None,
            };
            let ok = |y: f64, z: f64| {
                let mut dd = d;
                dd.impact_y_m = y;
                dd.impact_z_m = z;
                model.solve(&dd).is_ok()
            };
            let kernel = FaceMapKernel::new(&model, &d);
            for &y in &rows {
                let (mut lo, mut hi) = if loft > 45.0 { (0.0, 0.2) } else { (-0.2, 0.2) };
                if ok(y, lo) == ok(y, hi) {
                    continue;
                }
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid == lo || mid == hi {
                        break;
                    }
                    if ok(y, mid) == ok(y, lo) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let zs: Vec<f64> = (-400..=400).map(|k| nudge(lo, k)).collect();
                let mut row = LaunchGrid::with_len(zs.len());
                kernel.eval_row(y, &zs, row.all_out());
                for (j, &z) in zs.iter().enumerate() {
                    assert_eq!(row.valid[j], ok(y, z), "validity at ({y}, {z:e})");
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 200, "only {checked} boundary points found");
}
