//! The batched flight integrator: classic fourth-order Runge–Kutta with a fixed step over
//! `2·N` trajectories at once (two lane vectors of [`Lanes::N`]: AVX-512, AVX2 or portable lanes,
//! the widest this machine runs, [`crate::lanes::simd_level`]), rayon across batches.
//!
//! State per trajectory: position and velocity in G and the spin rate. The spin axis is
//! constant (the decay moment is antiparallel to the spin), so spin is one number. Each step
//! every lane checks whether it passed its apex (root of the derivative of a cubic Hermite
//! interpolant over the step: positions and velocities at both ends, error `O(h⁴)` like the
//! step itself) and whether it may have touched the ground (it ends the step below the ground,
//! or passes a trough). Such a step is re-integrated in [`REFINE`] substeps and the contact is
//! the first root of a substep's interpolant at the ground (`y = −tee height`; safeguarded
//! Newton), so the landing does not depend on the step. Such lanes leave their batch and their
//! contact searches are done a vector at a time, whatever batch and step they come from
//! ([`defer`]). The step `dt` is fixed by a tolerance test against a 64× finer step (see
//! `tests/flight.rs`); an independent adaptive Dormand–Prince integrator checks the whole.
//!
//! Every lane runs the same sequence of operations whatever its batch, position, thread or
//! instruction set (no fused multiply–add, no libm calls in the vector code; `ln` of the
//! wind profile is per lane), so results do not depend on batching or thread count.

// Fixed-length index loops over several lane arrays are the clearest form here.
#![allow(clippy::needless_range_loop)]

use rayon::prelude::*;

use super::aero::{CoefficientModel, ModelVisitor};
use super::{Flight, FlightConfig, FlightError, FlightLaunch, SpinDecay};
use crate::lanes::{simd_level, LaneMask, Lanes, SimdLevel, MAX_LANES, V};
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x8};

/// Launches one rayon task takes.
const PER_TASK: usize = 64;

/// Fly every launch; results in input order. Invalid launches give their error, the others are
/// integrated in batches of `2·N` in parallel.
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
    in_hang_order(launches, out, |l, o| {
        l.par_chunks(PER_TASK)
            .zip(o.par_chunks_mut(PER_TASK))
            .for_each(|(l, o)| fly_serial(cfg, l, o))
    });
}

/// [`fly_serial`] with the launches flown in hang order ([`in_hang_order`]), results in input
/// order: the same results, with less time spent on lanes that have landed while their batch
/// flies on, when the launches come in no particular order (a piece of a launch file).
pub fn fly_serial_in_hang_order(
    cfg: &FlightConfig,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    in_hang_order(launches, out, |l, o| fly_serial(cfg, l, o))
}

/// `fly` applied to the launches sorted by their vertical launch speed (ties in input order), its
/// results put back in input order into `out`.
///
/// A batch flies until its last lane lands (or leaves for its contact search, [`defer`]):
/// launches that stay in the air about as long as each other, batched together, leave in the
/// same few steps. On 200,000 random drives (150–180 mph, 8–14°) `smash flight` took 0.55–0.58 s
/// of CPU for 0.63–0.69 s in input order (3 runs each on a loaded machine, 28 Nov 2026, when
/// each group's contacts were searched in their step), with the same bytes out. Each lane's
/// result is the same bits in any batch (the module docs), so only the order of work changes.
fn in_hang_order(
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
    fly: impl FnOnce(&[FlightLaunch], &mut [Result<Flight, FlightError>]),
) {
    if launches.len() <= PER_TASK {
        return fly(launches, out);
    }
    let key: Vec<f64> = launches
        .iter()
        .map(|l| l.ball_speed_m_s * l.launch_angle_rad.sin())
        .collect();
    let mut order: Vec<usize> = (0..launches.len()).collect();
    order.sort_by(|&a, &b| key[a].total_cmp(&key[b]).then(a.cmp(&b)));
    let sorted: Vec<FlightLaunch> = order.iter().map(|&i| launches[i]).collect();
    let mut flown = out.to_vec();
    fly(&sorted, &mut flown);
    for (r, &i) in flown.into_iter().zip(&order) {
        out[i] = r;
    }
}

/// [`fly_into`] on the calling thread only.
pub fn fly_serial(
    cfg: &FlightConfig,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    cfg.aero.visit(FlyOn {
        level: simd_level(),
        cfg,
        launches,
        out,
    })
}

/// The flights of `launches` into `out` on this thread, on the lanes of `level`, under the
/// configuration's own coefficient model (what [`fly_serial`] runs at the machine's level and
/// the tests at each level).
struct FlyOn<'a, 'o> {
    level: SimdLevel,
    cfg: &'a FlightConfig,
    launches: &'a [FlightLaunch],
    out: &'o mut [Result<Flight, FlightError>],
}

impl ModelVisitor for FlyOn<'_, '_> {
    type Output = ();
    fn visit<C: CoefficientModel>(self, model: &C) {
        let wind = self.cfg.air.has_wind();
        dispatch_on(self.level, self.cfg, model, wind, self.launches, self.out)
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
    in_hang_order(launches, &mut out, |l, o| {
        l.par_chunks(PER_TASK)
            .zip(o.par_chunks_mut(PER_TASK))
            .for_each(|(l, o)| dispatch(cfg, model, wind, l, o))
    });
    out
}

fn dispatch<C: CoefficientModel>(
    cfg: &FlightConfig,
    model: &C,
    wind: bool,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    dispatch_on(simd_level(), cfg, model, wind, launches, out)
}

/// [`dispatch`] on the lanes of `level` (the widest level at most `level` this machine runs):
/// every level gives the same bits.
fn dispatch_on<C: CoefficientModel>(
    level: SimdLevel,
    cfg: &FlightConfig,
    model: &C,
    wind: bool,
    launches: &[FlightLaunch],
    out: &mut [Result<Flight, FlightError>],
) {
    let k = Consts::new(cfg, model.reynolds_at_reference_air(), wind);
    let (k, args) = (&k, (cfg, model, launches, out));
    match level.or_supported() {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `or_supported` keeps a level only where `simd_level()` reports it, which it
        // does only when the CPU (and operating system) have AVX-512F.
        SimdLevel::Avx512 => unsafe { batches_avx512::<C>(k, args) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above, AVX2.
        SimdLevel::Avx2 => unsafe { batches_avx2::<C>(k, args) },
        _ => batches_portable::<C>(k, args),
    }
}

/// [`batches`] on the portable lanes [`V`] (no instruction set assumed), a function of its own:
/// inlined into `dispatch_on`, every lane operation's little loop would sit in one function with
/// the rest of the dispatch, and LLVM's loop passes (loop rotation above all) take time
/// quadratic in a function's size — the test profile's build of the library spent most of its
/// 40 CPU-minutes there.
#[inline(never)]
fn batches_portable<C: CoefficientModel>(k: &Consts, args: Args<'_, C>) {
    batches::<V, C>(k, args)
}

/// What [`batches`] integrates: the configuration, the coefficient model, the launches and
/// their results.
type Args<'a, C> = (
    &'a FlightConfig,
    &'a C,
    &'a [FlightLaunch],
    &'a mut [Result<Flight, FlightError>],
);

/// [`batches`] on [`F64x8`], compiled for AVX-512F.
///
/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn batches_avx512<C: CoefficientModel>(k: &Consts, args: Args<'_, C>) {
    batches::<F64x8, C>(k, args)
}

/// [`batches`] on [`F64x4`], compiled for AVX2.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn batches_avx2<C: CoefficientModel>(k: &Consts, args: Args<'_, C>) {
    batches::<F64x4, C>(k, args)
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
    /// Height of the ground in G, m: the ball centre at contact, `−tee height` (the centre is
    /// at `y = 0` at address, one radius above a ball-on-the-ground's contact point).
    ground_y: f64,
    /// Height of the ball centre above the ground at address, m (for the wind profile).
    centre_above_ground: f64,
    dt: f64,
    max_time: f64,
    /// Whether the air moves: the wind profile is then evaluated lane by lane at each stage.
    /// (A flag, not a type parameter: one copy of the integrator serves both, at the cost of
    /// a branch every stage that always goes the same way.)
    wind: bool,
}

impl Consts {
    /// `reference_re`: the Reynolds number in the reference air
    /// ([`CoefficientModel::reynolds_at_reference_air`]).
    fn new(cfg: &FlightConfig, reference_re: bool, wind: bool) -> Self {
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
            re_per_speed: if reference_re {
                let air = super::aero::reference_air();
                air.density_kg_m3 * 2.0 * b.radius_m / air.viscosity_pa_s
            } else {
                rho * 2.0 * b.radius_m / cfg.air.viscosity_pa_s
            },
            radius: b.radius_m,
            ground_y: -cfg.tee_height_m,
            centre_above_ground: b.radius_m + cfg.tee_height_m,
            dt: cfg.dt(),
            max_time: cfg.max_time_s,
            wind,
        }
    }
}

/// Independent lane groups integrated together, so that the out-of-order core overlaps one
/// group's long dependency chain (square roots, divisions) with the other's. (`rk4` is written
/// out for two.)
const G: usize = 2;

/// Most launches a batch takes (`G` vectors of the widest lane type).
const MAX_B: usize = G * MAX_LANES;

#[inline(always)]
fn batches<L: Lanes, C: CoefficientModel>(k: &Consts, args: Args<'_, C>) {
    let (cfg, model, launches, out) = args;
    let b = G * L::N;
    let mut idx = [0usize; MAX_B];
    let mut next = 0;
    // Contact searches put off (`defer`), and where the launches flown again start.
    let mut queue = defer::Queue::new();
    let mut redo = 0;
    loop {
        // The next `b` valid launches (fewer at the end); invalid ones get their error.
        let mut n = 0;
        while n < b && next < launches.len() {
            match launches[next].check() {
                Err(e) => out[next] = Err(e),
                Ok(()) => {
                    idx[n] = next;
                    n += 1;
                }
            }
            next += 1;
        }
        let put_off = n > 0 && defer::deferring();
        if n == 0 {
            // Every launch has flown: the searches still waiting, then the launches whose
            // put-off search found no landing, each contact now searched in its step.
            queue.search::<L, C>(cfg, k, model, out);
            while n < b && redo < queue.redo.len() {
                idx[n] = queue.redo[redo];
                n += 1;
                redo += 1;
            }
        }
        if n == 0 {
            break;
        }
        for j in n..b {
            idx[j] = idx[n - 1];
        }
        // One call site: `batch` is inlined once per instruction set and coefficient model.
        let run = (launches, &idx[..b], n);
        batch::<L, C>(cfg, k, model, run, out, (put_off, &mut queue));
    }
}

/// The start of the trajectories of the launches `idx` (one a lane; lane `L` is lane
/// `L % N` of group `L / N`): the states and the unit spin axes.
#[inline(always)]
fn start<L: Lanes>(launches: &[FlightLaunch], idx: &[usize]) -> ([St<L>; G], [[L; 3]; G]) {
    let (mut v, mut w, mut ax) = ([[0.0; MAX_B]; 3], [0.0; MAX_B], [[0.0; MAX_B]; 3]);
    for (lane, &i) in idx.iter().enumerate() {
        let l = &launches[i];
        let (sl, cl) = l.launch_angle_rad.sin_cos();
        let (sa, ca) = l.azimuth_rad.sin_cos();
        let sp = l.ball_speed_m_s;
        v[0][lane] = sp * cl * ca;
        v[1][lane] = sp * sl;
        v[2][lane] = sp * cl * sa;
        // ω = (0, −sidespin, backspin) in G.
        let (wy, wz) = (-l.sidespin_rad_s, l.backspin_rad_s);
        let wm = wy.hypot(wz);
        w[lane] = wm;
        if wm > 0.0 {
            ax[1][lane] = wy / wm;
            ax[2][lane] = wz / wm;
        } else {
            ax[2][lane] = 1.0;
        }
    }
    // Written out, no closure around the loads (see `crate::lanes::each2`).
    let zero = L::splat(0.0);
    let mut st = [St {
        p: [zero; 3],
        v: [zero; 3],
        w: zero,
    }; G];
    let mut axes = [[zero; 3]; G];
    for g in 0..G {
        let at = g * L::N;
        for j in 0..3 {
            st[g].v[j] = L::load(&v[j][at..]);
            axes[g][j] = L::load(&ax[j][at..]);
        }
        st[g].w = L::load(&w[at..]);
    }
    (st, axes)
}

/// A state's lanes as arrays (to follow one lane through an event).
struct Lanewise<L: Lanes> {
    p: [L::Array; 3],
    v: [L::Array; 3],
    w: L::Array,
}

impl<L: Lanes> St<L> {
    #[inline(always)]
    fn lanewise(&self) -> Lanewise<L> {
        let (p, v) = (&self.p, &self.v);
        Lanewise {
            p: [p[0].to_array(), p[1].to_array(), p[2].to_array()],
            v: [v[0].to_array(), v[1].to_array(), v[2].to_array()],
            w: self.w.to_array(),
        }
    }
}

/// Integrate the launches `idx` (the first `n` are real, the rest padding copies). Lane `L` is
/// lane `L % N` of group `L / N`. With `put_off`, a lane that may touch the ground in a step
/// leaves the batch and waits in `queue` for its contact search ([`defer`]); else the contact
/// is searched in the step.
#[inline(always)]
fn batch<L: Lanes, C: CoefficientModel>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    (launches, idx, n): (&[FlightLaunch], &[usize], usize),
    out: &mut [Result<Flight, FlightError>],
    (put_off, queue): (bool, &mut defer::Queue),
) {
    let (mut s, axis) = start::<L>(launches, idx);
    let zero = L::splat(0.0);
    let ground = L::splat(k.ground_y);
    let h = k.dt;
    let mut apex = [zero; G];
    let mut done = [[false; MAX_LANES]; G];
    let mut left = G * L::N;
    let mut t = 0.0;
    let mut steps = 0u64;
    while left > 0 && t < k.max_time {
        let ns = rk4::<L, C>(k, cfg, model, &axis, &s);
        for g in 0..G {
            // The apex before this step (a lane that lands in it keeps only the part of the
            // step before its landing) and after it.
            let before = apex[g];
            apex[g] = L::select(ns[g].p[1].gt(apex[g]), ns[g].p[1], apex[g]);
            // Lanes that end the step below the ground or pass a trough (the trajectory may
            // dip below the ground within the step: a contact to search for), or pass the apex
            // (done lanes included: they are left out below).
            let (s, ns) = (&s[g], &ns[g]);
            let contact = ns.p[1].lt(ground) | (s.v[1].lt(zero) & !ns.v[1].lt(zero));
            let event = contact | (s.v[1].gt(zero) & !ns.v[1].gt(zero));
            if !event.any() {
                continue;
            }
            let mut top = [0.0; MAX_LANES];
            top[..L::N].copy_from_slice(apex[g].to_array().as_ref());
            let before = before.to_array();
            let mut search = land::Search {
                contact: [false; MAX_LANES],
                apex: [false; MAX_LANES],
            };
            let from = s.lanewise();
            let ax = [
                axis[g][0].to_array(),
                axis[g][1].to_array(),
                axis[g][2].to_array(),
            ];
            for i in 0..L::N {
                if done[g][i] || !event.get(i) {
                    continue;
                }
                top[i] = before[i];
                if !contact.get(i) {
                    search.apex[i] = true;
                } else if !put_off {
                    search.contact[i] = true;
                } else {
                    // The lane leaves the batch; its contact is searched with others'.
                    done[g][i] = true;
                    left -= 1;
                    let lane = g * L::N + i;
                    let axis_i = [ax[0][i], ax[1][i], ax[2][i]];
                    if lane < n && queue.push::<L>(&from, axis_i, i, t, before[i], idx[lane]) {
                        queue.search::<L, C>(cfg, k, model, out);
                    }
                }
            }
            // Plain code, no closure: a closure does not inherit the target feature of this
            // function, so lane operations inlined into one become out-of-line calls
            // (`.ci/no_outlined_intrinsics.py` checks the binary).
            let landed =
                land::events::<L, C>(cfg, k, model, (&axis[g], s, ns), &search, &mut top, t);
            for i in 0..L::N {
                let Some(f) = landed[i] else {
                    continue;
                };
                let lane = g * L::N + i;
                if lane < n {
                    out[idx[lane]] = Ok(f);
                }
                done[g][i] = true;
                left -= 1;
            }
            apex[g] = L::load(&top);
        }
        s = ns;
        steps += 1;
        t = steps as f64 * h;
    }
    for lane in 0..n {
        if !done[lane / L::N][lane % L::N] {
            out[idx[lane]] = Err(FlightError::NeverLands {
                time_limit_s: k.max_time,
            });
        }
    }
}

/// Substeps a step is re-integrated in where a lane may touch the ground: the contact is then
/// found on an interpolant 8⁴ = 4096 times more accurate, so a ball that grazes the ground or
/// lands at a shallow angle (where a small height error moves the contact far) lands at the
/// same place at any step (`tests/flight_step.rs`).
const REFINE: usize = 8;

mod defer;
mod land;
mod step;

use step::{rk4, St};

#[cfg(test)]
mod tests;
