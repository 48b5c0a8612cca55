//! Landing and apex of the lanes of one group in one step of the batched integrator
//! (`super`): where a step's (or substep's) cubic Hermite interpolant first comes down to the
//! ground, and the highest point before it.

use super::super::aero::CoefficientModel;
use super::super::hermite::{roots_between, Crossing, Hermite};
use super::step::{rk4_one, St};
use super::{Consts, Lanewise, REFINE};
use crate::flight::{Flight, FlightConfig};
use crate::lanes::{Lanes, MAX_LANES};

#[cfg(test)]
thread_local! {
    /// Steps of a lane group re-integrated for a contact on this thread (a count the tests
    /// bound).
    pub(super) static REFINED: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    /// Contact-refinement substeps computed on this thread.
    pub(super) static SUBSTEPS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The lanes of one group whose events a step searches: `contact[i]`, a lane that may touch
/// the ground in the step (searched on the step re-integrated in [`REFINE`] substeps);
/// `apex[i]`, a lane that only passes its apex (searched on the step itself).
pub(super) struct Search {
    pub(super) contact: [bool; MAX_LANES],
    pub(super) apex: [bool; MAX_LANES],
}

/// The events of one lane group in the step from `s` to `ns` at time `t`: per searched lane
/// (`search`) its landing, if it lands in the step, and its apex `top[i]` (on entry the apex
/// before the step) raised to the highest point before the landing, or over the whole step.
/// The apex lanes are searched on the step itself, the contact lanes by [`contacts`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn events<L: Lanes, C: CoefficientModel>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    (axis, s, ns): (&[L; 3], &St<L>, &St<L>),
    search: &Search,
    top: &mut [f64; MAX_LANES],
    t: f64,
) -> [Option<Flight>; MAX_LANES] {
    let ax = [axis[0].to_array(), axis[1].to_array(), axis[2].to_array()];
    let mut landed = [None; MAX_LANES];
    let (from, to) = (s.lanewise(), ns.lanewise());
    let mut any_contact = false;
    for i in 0..L::N {
        if search.contact[i] {
            any_contact = true;
        } else if search.apex[i] {
            let axis_i = [ax[0][i], ax[1][i], ax[2][i]];
            landed[i] = land_in(cfg, k, (&from, &to), k.dt, i, &axis_i, &mut top[i], t);
        }
    }
    if any_contact {
        let found = contacts::<L, C>(
            cfg,
            k,
            model,
            (axis, s),
            &search.contact,
            top,
            &[t; MAX_LANES],
        );
        for i in 0..L::N {
            if search.contact[i] {
                landed[i] = found[i];
            }
        }
    }
    landed
}

/// The landings of the lanes `contact` of the group at `s` (lane `i` at time `t[i]`), searched
/// on the step re-integrated in [`REFINE`] substeps from `s`, each substep's interpolant in
/// turn; and their apexes `top[i]` (on entry the apex before the step) raised to the highest
/// point before the landing, or over the whole step. The lanes may come from different
/// batches and steps: every lane's operations are its own, so its bits are the same.
///
/// The substeps are computed only as far as they are needed: once every contact lane has
/// landed, the later substeps would change nothing (each lane's search stops at its landing),
/// so they are not computed.
#[inline(always)]
pub(super) fn contacts<L: Lanes, C: CoefficientModel>(
    cfg: &FlightConfig,
    k: &Consts,
    model: &C,
    (axis, s): (&[L; 3], &St<L>),
    contact: &[bool; MAX_LANES],
    top: &mut [f64; MAX_LANES],
    t: &[f64; MAX_LANES],
) -> [Option<Flight>; MAX_LANES] {
    #[cfg(test)]
    REFINED.with(|n| n.set(n.get() + 1));
    let ax = [axis[0].to_array(), axis[1].to_array(), axis[2].to_array()];
    let mut pending = 0usize;
    for i in 0..L::N {
        pending += usize::from(contact[i]);
    }
    let fine = Consts {
        dt: k.dt / REFINE as f64,
        ..*k
    };
    // The landings found, each finished (its crossing searched) once all are found: the
    // searches then overlap, lane by lane ([`roots_between`]).
    let mut found: [Option<Landing>; MAX_LANES] = [None; MAX_LANES];
    let (mut cur, mut from) = (*s, s.lanewise());
    for j in 0..REFINE {
        if pending == 0 {
            break;
        }
        cur = rk4_one::<L, C>(&fine, cfg, model, axis, &cur);
        #[cfg(test)]
        SUBSTEPS.with(|n| n.set(n.get() + 1));
        let to = cur.lanewise();
        for i in 0..L::N {
            if !contact[i] || found[i].is_some() {
                continue;
            }
            let ends = Ends::of(&from, &to, i);
            let hy = ends.height(fine.dt);
            match hy.crossing(k.ground_y) {
                None => ends.clears(&hy, &mut top[i]),
                Some(crossing) => {
                    let t0 = t[i] + j as f64 * fine.dt;
                    found[i] = Some(Landing {
                        ends,
                        h: fine.dt,
                        t: t0,
                        crossing,
                    });
                    pending -= 1;
                }
            }
        }
        from = to;
    }
    land_all::<L>(cfg, k, &found, &ax, top)
}

/// The flights of the landings `found` (lane `i`'s spin axis `ax[·][i]`, apex `top[i]`), their
/// crossings searched together.
#[inline(always)]
fn land_all<L: Lanes>(
    cfg: &FlightConfig,
    k: &Consts,
    found: &[Option<Landing>; MAX_LANES],
    ax: &[L::Array; 3],
    top: &mut [f64; MAX_LANES],
) -> [Option<Flight>; MAX_LANES] {
    let mut hm = [[0.0; MAX_LANES]; 4];
    let (mut lo, mut hi, mut th) = ([0.0; MAX_LANES], [0.0; MAX_LANES], [0.0; MAX_LANES]);
    let mut active = [0.0; MAX_LANES];
    let mut any = false;
    for i in 0..L::N {
        let Some(l) = &found[i] else {
            continue;
        };
        let c = l.ends.height(l.h).coefficients();
        for j in 0..4 {
            hm[j][i] = c[j];
        }
        th[i] = l.crossing.start();
        if let Crossing::Between { lo: a, hi: b, .. } = l.crossing {
            (lo[i], hi[i], active[i], any) = (a, b, 1.0, true);
        }
    }
    if any {
        let hm = [
            L::load(&hm[0]),
            L::load(&hm[1]),
            L::load(&hm[2]),
            L::load(&hm[3]),
        ];
        let bracket = (L::load(&lo), L::load(&hi));
        let active = L::load(&active).gt(L::splat(0.5));
        let roots = roots_between::<L>(hm, k.ground_y, bracket, L::load(&th), active).to_array();
        th[..L::N].copy_from_slice(roots.as_ref());
    }
    let mut landed = [None; MAX_LANES];
    for i in 0..L::N {
        if let Some(l) = &found[i] {
            let axis = [ax[0][i], ax[1][i], ax[2][i]];
            landed[i] = Some(finish(cfg, k, l, &axis, &mut top[i], th[i]));
        }
    }
    landed
}

/// One lane's ends of a (sub)step: positions, velocities and spin at its start and end.
#[derive(Clone, Copy)]
struct Ends {
    p: [[f64; 3]; 2],
    v: [[f64; 3]; 2],
    w: [f64; 2],
}

impl Ends {
    /// Lane `i`'s ends of the (sub)step from `s` to `ns`.
    #[inline(always)]
    fn of<L: Lanes>(s: &Lanewise<L>, ns: &Lanewise<L>, i: usize) -> Self {
        Ends {
            p: [
                [s.p[0][i], s.p[1][i], s.p[2][i]],
                [ns.p[0][i], ns.p[1][i], ns.p[2][i]],
            ],
            v: [
                [s.v[0][i], s.v[1][i], s.v[2][i]],
                [ns.v[0][i], ns.v[1][i], ns.v[2][i]],
            ],
            w: [s.w[i], ns.w[i]],
        }
    }
    /// Coordinate `j`'s interpolant over the (sub)step of length `h`.
    #[inline(always)]
    fn interpolant(&self, j: usize, h: f64) -> Hermite {
        Hermite::new(self.p[0][j], self.p[1][j], self.v[0][j], self.v[1][j], h)
    }
    /// The height's interpolant.
    #[inline(always)]
    fn height(&self, h: f64) -> Hermite {
        self.interpolant(1, h)
    }
    /// The apex `apex` (on entry the apex before the (sub)step) raised over a (sub)step that
    /// does not come down to the ground (height interpolant `hy`).
    #[inline(always)]
    fn clears(&self, hy: &Hermite, apex: &mut f64) {
        *apex = apex.max(self.p[1][1]);
        if self.v[0][1] > 0.0 && self.v[1][1] <= 0.0 {
            *apex = apex.max(hy.max());
        }
    }
}

/// A landing found in a (sub)step of length `h` from time `t`, its crossing not yet searched.
#[derive(Clone, Copy)]
struct Landing {
    ends: Ends,
    h: f64,
    t: f64,
    crossing: Crossing,
}

/// Lane `i`'s landing in the (sub)step of length `h` from `s` to `ns` starting at time `t`, if
/// the step's interpolant comes down to the ground (`y = −tee height`) in it, and its apex
/// `apex` (on entry the apex before the step) raised to the highest point before the landing,
/// or over the whole step.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn land_in<L: Lanes>(
    cfg: &FlightConfig,
    k: &Consts,
    (s, ns): (&Lanewise<L>, &Lanewise<L>),
    h: f64,
    i: usize,
    axis: &[f64; 3],
    apex: &mut f64,
    t: f64,
) -> Option<Flight> {
    let ends = Ends::of(s, ns, i);
    let hy = ends.height(h);
    let Some(crossing) = hy.crossing(k.ground_y) else {
        ends.clears(&hy, apex);
        return None;
    };
    let th = hy.root(k.ground_y, crossing);
    let l = Landing {
        ends,
        h,
        t,
        crossing,
    };
    Some(finish(cfg, k, &l, axis, apex, th))
}

/// The flight of landing `l` at `th` (the crossing, in the (sub)step's θ), its apex `apex` (on
/// entry the apex before the (sub)step) raised to the highest point before the landing.
#[inline(always)]
fn finish(
    cfg: &FlightConfig,
    k: &Consts,
    l: &Landing,
    axis: &[f64; 3],
    apex: &mut f64,
    th: f64,
) -> Flight {
    let (e, h) = (&l.ends, l.h);
    let hy = e.height(h);
    *apex = apex.max(hy.max_until(th));
    let interp = |j: usize| {
        let hj = e.interpolant(j, h);
        (hj.at(th), hj.slope(th) / h)
    };
    let (x, vx) = interp(0);
    let (z, vz) = interp(2);
    let vy = hy.slope(th) / h;
    let w = e.w[0] + th * (e.w[1] - e.w[0]);
    let horiz = vx.hypot(vz);
    let mut f = Flight {
        carry_m: x,
        offline_m: z,
        apex_m: apex.max(0.0),
        flight_time_s: l.t + th * h,
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
        let back = w * (axis[0] * -uz + axis[2] * ux);
        let roll = gr.run_m(horiz, -vy, back, k.radius);
        f.total_m = Some(x + roll * ux);
    }
    f
}
