//! One step of the batched integrator (`super`): the equations of motion of [`Lanes::N`]
//! trajectories (gravity, drag and lift from the coefficient model, the spin's decay) and the
//! classic fourth-order Runge–Kutta step over two lane groups at once, or over one (the
//! contact refinement's substeps), with the same operations lane by lane.

// Fixed-length index loops over several lane arrays are the clearest form here.
#![allow(clippy::needless_range_loop)]

use super::super::aero::CoefficientModel;
use super::super::{FlightConfig, G_M_S2};
use super::{Consts, G};
use crate::lanes::{Lanes, MAX_LANES};

/// State of [`Lanes::N`] trajectories.
#[derive(Clone, Copy)]
pub(super) struct St<L> {
    pub(super) p: [L; 3],
    pub(super) v: [L; 3],
    pub(super) w: L,
}

/// Time derivative of velocity and spin.
#[derive(Clone, Copy)]
struct Rate<L> {
    a: [L; 3],
    dw: L,
}

#[inline(always)]
fn rate<L: Lanes, C: CoefficientModel>(
    k: &Consts,
    cfg: &FlightConfig,
    model: &C,
    axis: &[L; 3],
    s: &St<L>,
) -> Rate<L> {
    let mut vr = s.v;
    if k.wind {
        let y = s.p[1].to_array();
        let (mut wx, mut wz) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
        for i in 0..L::N {
            let w = cfg.air.wind_at(y[i] + k.centre_above_ground);
            wx[i] = w[0];
            wz[i] = w[1];
        }
        vr[0] = vr[0] - L::load(&wx);
        vr[2] = vr[2] - L::load(&wz);
    }
    let v2 = vr[0] * vr[0] + vr[1] * vr[1] + vr[2] * vr[2];
    let vm = v2.sqrt();
    let tiny = L::splat(1e-300);
    let inv_v = L::splat(1.0) / L::select(vm.lt(tiny), tiny, vm);
    let sf = s.w * k.radius * inv_v;
    let re = vm * k.re_per_speed;
    let (cd, cl, cm) = model.coefficients_v(sf, re);
    // Lift direction: axis × v_rel, normalised.
    let c = [
        axis[1] * vr[2] - axis[2] * vr[1],
        axis[2] * vr[0] - axis[0] * vr[2],
        axis[0] * vr[1] - axis[1] * vr[0],
    ];
    let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let cn = c2.sqrt();
    let zero = L::splat(0.0);
    let positive = cn.gt(zero);
    let inv_c = L::select(
        positive,
        L::splat(1.0) / L::select(positive, cn, L::splat(1.0)),
        zero,
    );
    let drag = cd * k.k_force * vm;
    let lift = cl * k.k_force * v2 * inv_c;
    let a = [
        lift * c[0] - drag * vr[0],
        lift * c[1] - drag * vr[1] - G_M_S2,
        lift * c[2] - drag * vr[2],
    ];
    let dw = if k.moment {
        -(cm * k.k_moment * v2)
    } else {
        -(s.w * k.inv_tau)
    };
    Rate { a, dw }
}

#[inline(always)]
fn axpy<L: Lanes>(s: &St<L>, h: f64, v: &[L; 3], r: &Rate<L>) -> St<L> {
    St {
        p: [s.p[0] + v[0] * h, s.p[1] + v[1] * h, s.p[2] + v[2] * h],
        v: [
            s.v[0] + r.a[0] * h,
            s.v[1] + r.a[1] * h,
            s.v[2] + r.a[2] * h,
        ],
        w: s.w + r.dw * h,
    }
}

#[inline(always)]
pub(super) fn rk4<L: Lanes, C: CoefficientModel>(
    k: &Consts,
    cfg: &FlightConfig,
    model: &C,
    axis: &[[L; 3]; G],
    s: &[St<L>; G],
) -> [St<L>; G] {
    // Written out for the two groups (no closures around `rate`: see `crate::lanes::each2`).
    let h = k.dt;
    let (a0, a1) = (&axis[0], &axis[1]);
    let r1 = [
        rate::<L, C>(k, cfg, model, a0, &s[0]),
        rate::<L, C>(k, cfg, model, a1, &s[1]),
    ];
    let s2 = [
        axpy(&s[0], 0.5 * h, &s[0].v, &r1[0]),
        axpy(&s[1], 0.5 * h, &s[1].v, &r1[1]),
    ];
    let r2 = [
        rate::<L, C>(k, cfg, model, a0, &s2[0]),
        rate::<L, C>(k, cfg, model, a1, &s2[1]),
    ];
    let s3 = [
        axpy(&s[0], 0.5 * h, &s2[0].v, &r2[0]),
        axpy(&s[1], 0.5 * h, &s2[1].v, &r2[1]),
    ];
    let r3 = [
        rate::<L, C>(k, cfg, model, a0, &s3[0]),
        rate::<L, C>(k, cfg, model, a1, &s3[1]),
    ];
    let s4 = [
        axpy(&s[0], h, &s3[0].v, &r3[0]),
        axpy(&s[1], h, &s3[1].v, &r3[1]),
    ];
    let r4 = [
        rate::<L, C>(k, cfg, model, a0, &s4[0]),
        rate::<L, C>(k, cfg, model, a1, &s4[1]),
    ];
    let h6 = h / 6.0;
    [
        combine(
            h6,
            [&s[0], &s2[0], &s3[0], &s4[0]],
            [&r1[0], &r2[0], &r3[0], &r4[0]],
        ),
        combine(
            h6,
            [&s[1], &s2[1], &s3[1], &s4[1]],
            [&r1[1], &r2[1], &r3[1], &r4[1]],
        ),
    ]
}

/// [`rk4`] for one lane group: the same operations lane by lane, so the same bits (the
/// contact refinement re-integrates only the group that needs it).
#[inline(always)]
pub(super) fn rk4_one<L: Lanes, C: CoefficientModel>(
    k: &Consts,
    cfg: &FlightConfig,
    model: &C,
    axis: &[L; 3],
    s: &St<L>,
) -> St<L> {
    let h = k.dt;
    let r1 = rate::<L, C>(k, cfg, model, axis, s);
    let s2 = axpy(s, 0.5 * h, &s.v, &r1);
    let r2 = rate::<L, C>(k, cfg, model, axis, &s2);
    let s3 = axpy(s, 0.5 * h, &s2.v, &r2);
    let r3 = rate::<L, C>(k, cfg, model, axis, &s3);
    let s4 = axpy(s, h, &s3.v, &r3);
    let r4 = rate::<L, C>(k, cfg, model, axis, &s4);
    combine(h / 6.0, [s, &s2, &s3, &s4], [&r1, &r2, &r3, &r4])
}

/// The RK4 step from the stages' states `s` and rates `r`, `h6 = h/6`.
#[inline(always)]
fn combine<L: Lanes>(h6: f64, s: [&St<L>; 4], r: [&Rate<L>; 4]) -> St<L> {
    let mut n = *s[0];
    for j in 0..3 {
        n.p[j] = s[0].p[j] + comb(s[0].v[j], s[1].v[j], s[2].v[j], s[3].v[j]) * h6;
        n.v[j] = s[0].v[j] + comb(r[0].a[j], r[1].a[j], r[2].a[j], r[3].a[j]) * h6;
    }
    n.w = s[0].w + comb(r[0].dw, r[1].dw, r[2].dw, r[3].dw) * h6;
    n
}

/// RK4's weighted sum of the four stages' values (before the factor `h/6`).
#[inline(always)]
fn comb<L: Lanes>(a: L, b: L, c: L, d: L) -> L {
    a + (b + c) * 2.0 + d
}
