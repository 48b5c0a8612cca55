//! The batched flight integrator: classic fourth-order Runge–Kutta with a fixed step over
//! `2·W` trajectories at once (two groups of [`W`]) (lanes of `f64`, AVX2 when the machine has it), rayon across
//! batches.
//!
//! State per trajectory: position and velocity in G and the spin rate. The spin axis is
//! constant (the decay moment is antiparallel to the spin), so spin is one number. Each step
//! every lane checks, with a cubic Hermite interpolant over the step (positions and
//! velocities at both ends, error `O(h⁴)` like the step itself), whether the ball came down
//! through `y = 0` (root by safeguarded Newton) or passed its apex (root of the interpolant's
//! derivative). The step `dt` is fixed by a tolerance test against a 64× finer step (see
//! `tests/flight.rs`); an independent adaptive Dormand–Prince integrator checks the whole.
//!
//! Every lane runs the same sequence of operations whatever its batch, position, thread or
//! instruction set (no fused multiply–add, no libm calls in the vector code; `ln` of the
//! wind profile is per lane), so results do not depend on batching or thread count.

// Fixed-length index loops over several lane arrays are the clearest form here.
#![allow(clippy::needless_range_loop)]

use rayon::prelude::*;

use super::aero::{CoefficientModel, Fmm2022, Fmm2022Re, Fmm2022Tour, NathanLyu};
use super::hermite::Hermite;
use super::{AeroModel, Flight, FlightConfig, FlightError, FlightLaunch, SpinDecay, G_M_S2};
use crate::lanes::{V, W};
use crate::sweep::kernel::{simd_level, SimdLevel};

/// Launches one rayon task takes.
const PER_TASK: usize = 64;

/// Fly every launch; results in input order. Invalid launches give their error, the others are
/// integrated in batches of `2·W` in parallel.
pub fn fly(cfg: &FlightConfig, launches: &[FlightLaunch]) -> Vec<Result<Flight, FlightError>> {
    let mut out = vec![
        Err(FlightError::NeverLands {
            time_limit_s: cfg.max_time_s,
        });
        launches.len()
    ];
    fly_into(cfg, launches, &mut out);
    out
}

/// One launch.
pub fn fly_one(cfg: &FlightConfig, launch: &FlightLaunch) -> Result<Flight, FlightError> {
    fly(cfg, std::slice::from_ref(launch)).remove(0)
}

/// [`fly`] into a caller's slice (same length as `launches`).
pub fn fly_into(
    cfg: &FlightConfig,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    assert_eq!(launches.len(), out.len(), "one result per launch");
    launches
        .par_chunks(PER_TASK)
        .zip(out.par_chunks_mut(PER_TASK))
        .for_each(|(l, o)| fly_serial(cfg, l, o));
}

/// [`fly_into`] on the calling thread only.
pub fn fly_serial(
    cfg: &FlightConfig,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    let wind = cfg.air.has_wind();
    match &cfg.aero {
        AeroModel::Fmm2022Tour => dispatch(cfg, &Fmm2022Tour, wind, launches, out),
        AeroModel::Fmm2022Re => dispatch(cfg, &Fmm2022Re, wind, launches, out),
        AeroModel::Fmm2022 => dispatch(cfg, &Fmm2022, wind, launches, out),
        AeroModel::NathanLyu => dispatch(cfg, &NathanLyu, wind, launches, out),
        AeroModel::Table(t) => dispatch(cfg, t.as_ref(), wind, launches, out),
    }
}

/// [`fly`] with any coefficient model (`cfg.aero` is ignored), e.g. a model being fitted.
pub fn fly_with<C: CoefficientModel>(
    cfg: &FlightConfig,
    model: &C,
    launches: &[FlightLaunch],
) -> Vec<Result<Flight, FlightError>> {
    let mut out = vec![
        Err(FlightError::NeverLands {
            time_limit_s: cfg.max_time_s,
        });
        launches.len()
    ];
    let wind = cfg.air.has_wind();
    launches
        .par_chunks(PER_TASK)
        .zip(out.par_chunks_mut(PER_TASK))
        .for_each(|(l, o)| dispatch(cfg, model, wind, l, o));
    out
}

fn dispatch<C: CoefficientModel>(
    cfg: &FlightConfig,
    model: &C,
    wind: bool,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    let k = Consts::new(cfg);
    #[cfg(target_arch = "x86_64")]
    if simd_level() == SimdLevel::Avx2 {
        // SAFETY: AVX2 and FMA were detected at run time.
        unsafe {
            if wind {
                batches_avx2::<C, true>(cfg, &k, model, launches, out)
            } else {
                batches_avx2::<C, false>(cfg, &k, model, launches, out)
            }
        }
        return;
    }
    let _ = simd_level;
    if wind {
        batches::<C, true>(cfg, &k, model, launches, out)
    } else {
        batches::<C, false>(cfg, &k, model, launches, out)
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn batches_avx2<C: CoefficientModel, const WIND: bool>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    batches::<C, WIND>(cfg, k, model, launches, out)
}

/// Constants of the equations of motion for one configuration.
#[derive(Clone, Copy)]
struct Consts {
    /// `ρA/(2m)`, 1/m: drag or lift acceleration per `C·|v|²`.
    k_force: f64,
    /// `ρA·R/I`, 1/m²·… : spin deceleration per `C_M·|v|²` (moment `½ρ|v|²·A·2R·C_M`).
    k_moment: f64,
    /// `1/τ` of exponential decay, 1/s (0 unless that mode).
    inv_tau: f64,
    /// Whether the moment law applies.
    moment: bool,
    /// `ρ·2R/μ`, s/m: Reynolds number per speed.
    re_per_speed: f64,
    radius: f64,
    dt: f64,
    max_time: f64,
}

impl Consts {
    fn new(cfg: &FlightConfig) -> Self {
        let b = &cfg.ball;
        let rho = cfg.air.density_kg_m3;
        let area = std::f64::consts::PI * b.radius_m * b.radius_m;
        let (inv_tau, moment) = match cfg.spin_decay {
            SpinDecay::Moment => (0.0, true),
            SpinDecay::Exponential { time_constant_s } => (1.0 / time_constant_s, false),
            SpinDecay::None => (0.0, false),
        };
        Self {
            k_force: rho * area / (2.0 * b.mass_kg),
            k_moment: rho * area * b.radius_m / b.inertia_kg_m2,
            inv_tau,
            moment,
            re_per_speed: rho * 2.0 * b.radius_m / cfg.air.viscosity_pa_s,
            radius: b.radius_m,
            dt: cfg.dt(),
            max_time: cfg.max_time_s,
        }
    }
}

/// State of [`W`] trajectories.
#[derive(Clone, Copy)]
struct St {
    p: [V; 3],
    v: [V; 3],
    w: V,
}

/// Time derivative of velocity and spin.
#[derive(Clone, Copy)]
struct Rate {
    a: [V; 3],
    dw: V,
}

#[inline(always)]
fn rate<C: CoefficientModel, const WIND: bool>(
    k: &Consts,
    cfg: &FlightConfig,
    model: &C,
    axis: &[V; 3],
    s: &St,
) -> Rate {
    let mut vr = s.v;
    if WIND {
        let (mut wx, mut wz) = ([0.0; W], [0.0; W]);
        for i in 0..W {
            let w = cfg.air.wind_at(s.p[1].0[i] + k.radius);
            wx[i] = w[0];
            wz[i] = w[1];
        }
        vr[0] = vr[0] - V(wx);
        vr[2] = vr[2] - V(wz);
    }
    let v2 = vr[0] * vr[0] + vr[1] * vr[1] + vr[2] * vr[2];
    let vm = v2.sqrt();
    let tiny = V::splat(1e-300);
    let inv_v = 1.0 / vm.lt(tiny).select(tiny, vm);
    let sf = k.radius * s.w * inv_v;
    let re = k.re_per_speed * vm;
    let (cd, cl, cm) = model.coefficients_v(sf, re);
    // Lift direction: axis × v_rel, normalised.
    let c = [
        axis[1] * vr[2] - axis[2] * vr[1],
        axis[2] * vr[0] - axis[0] * vr[2],
        axis[0] * vr[1] - axis[1] * vr[0],
    ];
    let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let cn = c2.sqrt();
    let zero = V::splat(0.0);
    let inv_c = cn
        .gt(zero)
        .select(1.0 / cn.gt(zero).select(cn, V::splat(1.0)), zero);
    let drag = k.k_force * cd * vm;
    let lift = k.k_force * cl * v2 * inv_c;
    let a = [
        lift * c[0] - drag * vr[0],
        lift * c[1] - drag * vr[1] - G_M_S2,
        lift * c[2] - drag * vr[2],
    ];
    let dw = if k.moment {
        -(k.k_moment * cm * v2)
    } else {
        -(k.inv_tau * s.w)
    };
    Rate { a, dw }
}

#[inline(always)]
fn axpy(s: &St, h: f64, v: &[V; 3], r: &Rate) -> St {
    St {
        p: [s.p[0] + h * v[0], s.p[1] + h * v[1], s.p[2] + h * v[2]],
        v: [
            s.v[0] + h * r.a[0],
            s.v[1] + h * r.a[1],
            s.v[2] + h * r.a[2],
        ],
        w: s.w + h * r.dw,
    }
}

/// Independent lane groups integrated together, so that the out-of-order core overlaps one
/// group's long dependency chain (square roots, divisions) with the other's.
const G: usize = 2;

/// Launches per batch.
const B: usize = G * W;

#[inline(always)]
fn rk4<C: CoefficientModel, const WIND: bool>(
    k: &Consts,
    cfg: &FlightConfig,
    model: &C,
    axis: &[[V; 3]; G],
    s: &[St; G],
) -> [St; G] {
    let h = k.dt;
    let r1: [Rate; G] = std::array::from_fn(|g| rate::<C, WIND>(k, cfg, model, &axis[g], &s[g]));
    let s2: [St; G] = std::array::from_fn(|g| axpy(&s[g], 0.5 * h, &s[g].v, &r1[g]));
    let r2: [Rate; G] = std::array::from_fn(|g| rate::<C, WIND>(k, cfg, model, &axis[g], &s2[g]));
    let s3: [St; G] = std::array::from_fn(|g| axpy(&s[g], 0.5 * h, &s2[g].v, &r2[g]));
    let r3: [Rate; G] = std::array::from_fn(|g| rate::<C, WIND>(k, cfg, model, &axis[g], &s3[g]));
    let s4: [St; G] = std::array::from_fn(|g| axpy(&s[g], h, &s3[g].v, &r3[g]));
    let r4: [Rate; G] = std::array::from_fn(|g| rate::<C, WIND>(k, cfg, model, &axis[g], &s4[g]));
    let h6 = h / 6.0;
    let comb = |a: V, b: V, c: V, d: V| a + 2.0 * (b + c) + d;
    std::array::from_fn(|g| {
        let mut n = s[g];
        for j in 0..3 {
            n.p[j] = s[g].p[j] + h6 * comb(s[g].v[j], s2[g].v[j], s3[g].v[j], s4[g].v[j]);
            n.v[j] = s[g].v[j] + h6 * comb(r1[g].a[j], r2[g].a[j], r3[g].a[j], r4[g].a[j]);
        }
        n.w = s[g].w + h6 * comb(r1[g].dw, r2[g].dw, r3[g].dw, r4[g].dw);
        n
    })
}

#[inline(always)]
fn batches<C: CoefficientModel, const WIND: bool>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    let mut idx = [0usize; B];
    let mut n = 0;
    for (i, l) in launches.iter().enumerate() {
        match l.check() {
            Err(e) => out[i] = Err(e),
            Ok(()) => {
                idx[n] = i;
                n += 1;
                if n == B {
                    batch::<C, WIND>(cfg, k, model, launches, &idx, B, out);
                    n = 0;
                }
            }
        }
    }
    if n > 0 {
        for j in n..B {
            idx[j] = idx[n - 1];
        }
        batch::<C, WIND>(cfg, k, model, launches, &idx, n, out);
    }
}

/// Integrate the launches `idx` (the first `n` are real, the rest padding copies). Lane `L` is
/// lane `L % W` of group `L / W`.
#[inline(always)]
fn batch<C: CoefficientModel, const WIND: bool>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    launches: &[FlightLaunch],
    idx: &[usize; B],
    n: usize,
    out: &mut [Result<Flight, FlightError>],
) {
    let zero = V::splat(0.0);
    let mut s = [St {
        p: [zero; 3],
        v: [zero; 3],
        w: zero,
    }; G];
    let mut axis = [[zero; 3]; G];
    for lane in 0..B {
        let (g, i) = (lane / W, lane % W);
        let l = &launches[idx[lane]];
        let (sl, cl) = l.launch_angle_rad.sin_cos();
        let (sa, ca) = l.azimuth_rad.sin_cos();
        let sp = l.ball_speed_m_s;
        s[g].v[0].0[i] = sp * cl * ca;
        s[g].v[1].0[i] = sp * sl;
        s[g].v[2].0[i] = sp * cl * sa;
        // ω = (0, −sidespin, backspin) in G.
        let (wy, wz) = (-l.sidespin_rad_s, l.backspin_rad_s);
        let w = wy.hypot(wz);
        s[g].w.0[i] = w;
        if w > 0.0 {
            axis[g][1].0[i] = wy / w;
            axis[g][2].0[i] = wz / w;
        } else {
            axis[g][2].0[i] = 1.0;
        }
    }
    let h = k.dt;
    let mut apex = [zero; G];
    let mut done = [[false; W]; G];
    let mut left = B;
    let mut t = 0.0;
    let mut steps = 0u64;
    while left > 0 && t < k.max_time {
        let ns = rk4::<C, WIND>(k, cfg, model, &axis, &s);
        for g in 0..G {
            let (s, ns) = (&s[g], &ns[g]);
            apex[g] = ns.p[1].gt(apex[g]).select(ns.p[1], apex[g]);
            // Lanes that cross the ground or pass the apex this step (done lanes included:
            // the scalar code below skips them).
            let event = ns.p[1].lt(zero) | (s.v[1].gt(zero) & !ns.v[1].gt(zero));
            if !event.any() {
                continue;
            }
            for i in 0..W {
                if done[g][i] || !event.get(i) {
                    continue;
                }
                let (y0, y1) = (s.p[1].0[i], ns.p[1].0[i]);
                let (vy0, vy1) = (s.v[1].0[i], ns.v[1].0[i]);
                let hy = Hermite::new(y0, y1, vy0, vy1, h);
                if vy0 > 0.0 && vy1 <= 0.0 {
                    apex[g].0[i] = apex[g].0[i].max(hy.max());
                }
                if y1 >= 0.0 {
                    continue;
                }
                let th = hy.root();
                let interp = |j: usize| {
                    let hj = Hermite::new(s.p[j].0[i], ns.p[j].0[i], s.v[j].0[i], ns.v[j].0[i], h);
                    (hj.at(th), hj.slope(th) / h)
                };
                let (x, vx) = interp(0);
                let (z, vz) = interp(2);
                let vy = hy.slope(th) / h;
                let w = s.w.0[i] + th * (ns.w.0[i] - s.w.0[i]);
                let horiz = vx.hypot(vz);
                let mut f = Flight {
                    carry_m: x,
                    offline_m: z,
                    apex_m: apex[g].0[i].max(0.0),
                    flight_time_s: t + th * h,
                    land_angle_rad: (-vy).atan2(horiz),
                    land_speed_m_s: (horiz * horiz + vy * vy).sqrt(),
                    land_spin_rad_s: w,
                    total_m: None,
                };
                if let Some(gr) = &cfg.ground {
                    // Backspin component about the horizontal axis across the direction of
                    // travel: ω·(ĥ × ŷ) with ĥ the unit horizontal velocity, ĥ × ŷ = (−uz, 0, ux).
                    let (ux, uz) = if horiz > 0.0 {
                        (vx / horiz, vz / horiz)
                    } else {
                        (1.0, 0.0)
                    };
                    let back = w * (axis[g][0].0[i] * -uz + axis[g][2].0[i] * ux);
                    let roll = gr.run_m(horiz, -vy, back, k.radius);
                    f.total_m = Some(x + roll * ux);
                }
                let lane = g * W + i;
                if lane < n {
                    out[idx[lane]] = Ok(f);
                }
                done[g][i] = true;
                left -= 1;
            }
        }
        s = ns;
        steps += 1;
        t = steps as f64 * h;
    }
    for lane in 0..n {
        if !done[lane / W][lane % W] {
            out[idx[lane]] = Err(FlightError::NeverLands {
                time_limit_s: k.max_time,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
        for (mph, deg) in [(5.0, 10.0), (2.0, 60.0), (0.5, 5.0)] {
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
        let mut serial = vec![Ok(fly_one(&cfg, &ls[0]).unwrap()); ls.len()];
        fly_serial(&cfg, &ls, &mut serial);
        assert_eq!(all, serial);
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
}
