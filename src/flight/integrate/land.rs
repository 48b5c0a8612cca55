//! Landing and apex of one lane in one step of the batched integrator (`super`): where the
//! step's cubic Hermite interpolant first comes down to the ground, and the highest point
//! before it.

use super::super::hermite::Hermite;
use super::{Consts, Lanewise};
use crate::flight::{Flight, FlightConfig};
use crate::lanes::Lanes;

/// Lane `i`'s event in a step from time `t`, given as the lane states `states` at the ends of
/// its substeps of length `h` (the step itself, or its re-integration in substeps): its
/// landing if an interpolant comes down to the ground (`y = −tee height`) in a substep, the
/// first such, and its apex `apex` (on entry the apex before the step) raised to the highest
/// point before the landing, or over the whole step.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn land<L: Lanes>(
    cfg: &FlightConfig,
    k: &Consts,
    states: &[Lanewise<L>],
    h: f64,
    i: usize,
    axis: &[f64; 3],
    apex: &mut f64,
    t: f64,
) -> Option<Flight> {
    for (j, pair) in states.windows(2).enumerate() {
        let t0 = t + j as f64 * h;
        if let Some(f) = land_in(cfg, k, (&pair[0], &pair[1]), h, i, axis, apex, t0) {
            return Some(f);
        }
    }
    None
}

/// [`land`] on one substep from `s` to `ns` starting at time `t`.
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
    let (y0, y1) = (s.p[1][i], ns.p[1][i]);
    let (vy0, vy1) = (s.v[1][i], ns.v[1][i]);
    let hy = Hermite::new(y0, y1, vy0, vy1, h);
    let Some(th) = hy.first_down_to(k.ground_y) else {
        *apex = apex.max(y1);
        if vy0 > 0.0 && vy1 <= 0.0 {
            *apex = apex.max(hy.max());
        }
        return None;
    };
    *apex = apex.max(hy.max_until(th));
    let interp = |j: usize| {
        let hj = Hermite::new(s.p[j][i], ns.p[j][i], s.v[j][i], ns.v[j][i], h);
        (hj.at(th), hj.slope(th) / h)
    };
    let (x, vx) = interp(0);
    let (z, vz) = interp(2);
    let vy = hy.slope(th) / h;
    let w = s.w[i] + th * (ns.w[i] - s.w[i]);
    let horiz = vx.hypot(vz);
    let mut f = Flight {
        carry_m: x,
        offline_m: z,
        apex_m: apex.max(0.0),
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
        let back = w * (axis[0] * -uz + axis[2] * ux);
        let roll = gr.run_m(horiz, -vy, back, k.radius);
        f.total_m = Some(x + roll * ux);
    }
    Some(f)
}
