//! Branch-free maths that the compiler can vectorise: `atan2`.
//!
//! `std`'s `f64::atan2` calls libm, which no compiler vectorises, and the face-map kernel needs
//! two of them per impact. [`atan2`] is written with selects only (no branches, no calls), so a
//! loop over it compiles to packed SIMD code, and it uses only `+ − × ÷` and bit
//! operations, all correctly rounded in IEEE 754: the scalar and the vector code give the
//! same bits on every x86-64 machine.
//!
//! Method (Cephes `atan.c`, S. L. Moshier): reduce the first-octant ratio `t = |y|/|x|` to
//! `|x_r| ≤ 0.66` with
//!
//! ```text
//! t ≤ 0.66:               x_r = |y|/|x|,               atan t = x_r + R(x_r)
//! 0.66 < t ≤ tan(3π/8):   x_r = (|y| − |x|)/(|y| + |x|), atan t = π/4 + x_r + R(x_r)
//! t > tan(3π/8):          x_r = −|x|/|y|,              atan t = π/2 + x_r + R(x_r)
//! ```
//!
//! (formed directly from `|x|`, `|y|`, which is one division and more accurate than going
//! through `t`), with the degree 4/5 rational `R(x) = x·z·P(z)/Q(z)`, `z = x²`, of Cephes
//! (relative error ≤ 1.8e-16 on the reduced range). The quadrant is restored by folding
//! `π − ·` into a double-double constant, then the sign of `y` is copied. The tests check the
//! error against `f64::atan2` over millions of points (a few ulp at most).
//!
//! Special values: `atan2(±0, +0) = ±0`, `atan2(±0, −0) = ±π`, NaN in → NaN out. Infinite
//! arguments are not supported (the kernel never produces them for valid impacts).

use crate::lanes::{Lanes, V};

/// `tan(3π/8)`.
const T3P8: f64 = 2.414_213_562_373_095;

/// π/4 and π/2 and their double-double tails (`hi + lo` = the constant to ~1e-32).
const PIO4_HI: f64 = std::f64::consts::FRAC_PI_4;
const PIO4_LO: f64 = 3.061_616_997_868_383e-17;
const PIO2_HI: f64 = std::f64::consts::FRAC_PI_2;
const PIO2_LO: f64 = 6.123_233_995_736_766e-17;
const PI3O4_HI: f64 = 2.356_194_490_192_345;
const PI3O4_LO: f64 = 9.184_850_993_605_148e-17;
const PI_HI: f64 = std::f64::consts::PI;
const PI_LO: f64 = 1.224_646_799_147_353_2e-16;

/// Cephes `atan.c` numerator coefficients, highest power first.
const P: [f64; 5] = [
    -8.750_608_600_031_904e-1,
    -1.615_753_718_733_365e1,
    -7.500_855_792_314_705e1,
    -1.228_866_684_490_136_2e2,
    -6.485_021_904_942_025e1,
];
/// Cephes `atan.c` denominator coefficients (monic; leading 1 omitted), highest power first.
const Q: [f64; 5] = [
    2.485_846_490_142_306_3e1,
    1.650_270_098_316_988_5e2,
    4.328_810_604_912_903e2,
    4.853_903_996_359_137e2,
    1.945_506_571_482_614e2,
];

/// Four-quadrant arctangent of `y/x`, rad, in `[−π, π]`, without branches.
///
/// Agrees with `f64::atan2` to a few ulp for finite arguments (see the module docs). This is
/// lane 0 of [`atan2_v`]: the same operations, so the same bits.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    atan2_v::<V>(V::splat(y), V::splat(x)).0[0]
}

/// [`atan2`] on any lane type (the same operations on every lane, so the same bits).
#[inline(always)]
pub fn atan2_v<L: Lanes>(y: L, x: L) -> L {
    let ax = x.abs();
    let ay = y.abs();
    let x_neg = x.sign_bit();
    let big = ay.gt(ax * T3P8);
    let small = ay.le(ax * 0.66) & !big;
    let mid = !(big | small);
    // Reduced argument x_r = num/den and the constant hi + lo that the octant contributes,
    // with π − · already folded in for x < 0.
    let num = L::select(big, -ax, L::select(small, ay, ay - ax));
    let den = L::select(big, ay, L::select(small, ax, ay + ax));
    // atan2(±0, ±0): 0/0 would be NaN; the answer is the constant alone.
    let den = L::select(den.eq(L::splat(0.0)), L::splat(1.0), den);
    let hi = L::select(
        big,
        L::splat(PIO2_HI),
        L::select(mid, pick(x_neg, PI3O4_HI, PIO4_HI), pick(x_neg, PI_HI, 0.0)),
    );
    let lo = L::select(
        big,
        L::splat(PIO2_LO),
        L::select(mid, pick(x_neg, PI3O4_LO, PIO4_LO), pick(x_neg, PI_LO, 0.0)),
    );
    let xr = num / den;
    let z = xr * xr;
    let p = (((z * P[0] + P[1]) * z + P[2]) * z + P[3]) * z + P[4];
    let q = ((((z + Q[0]) * z + Q[1]) * z + Q[2]) * z + Q[3]) * z + Q[4];
    // atan(x_r) = x_r + x_r·z·P/Q; for x < 0 the angle is the constant minus it.
    let r = xr * (z * p / q) + xr;
    let r = L::select(x_neg, -r, r);
    let angle = hi + (r + lo);
    // Copy the sign of y (also gives ±0 and ±π for y = ±0).
    angle.copysign(y)
}

/// `a` where `m`, else `b`.
#[inline(always)]
fn pick<L: Lanes>(m: L::Mask, a: f64, b: f64) -> L {
    L::select(m, L::splat(a), L::splat(b))
}

/// `√(x² + y²)` on any lane type, correctly rounded operations only (so it vectorises).
/// Within 2 ulp of `f64::hypot` while `x²` and `y²` neither overflow nor underflow
/// (|x|, |y| between about 1e-150 and 1e150; ball velocities are far inside), which libm's
/// scaling guards against and this does not.
#[inline(always)]
pub fn hypot_v<L: Lanes>(x: L, y: L) -> L {
    (x * x + y * y).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Distance in units in the last place between two finite doubles of the same sign.
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        assert_eq!(a.is_sign_negative(), b.is_sign_negative(), "{a} vs {b}");
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn special_values() {
        for (y, x) in [
            (0.0, 0.0),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (1.0, -0.0),
            (1.0, 1.0),
            (-1.0, -1.0),
            (1.0, -1.0),
        ] {
            let (got, want) = (atan2(y, x), y.atan2(x));
            assert!(ulps(got, want) <= 1, "atan2({y}, {x}) = {got}, std {want}");
            assert_eq!(got.is_sign_negative(), want.is_sign_negative());
        }
        assert!(atan2(f64::NAN, 1.0).is_nan());
        assert!(atan2(1.0, f64::NAN).is_nan());
    }

    #[test]
    fn lane_hypot_is_within_two_ulp_of_std() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut worst = 0u64;
        for _ in 0..200_000 {
            let m: f64 = 10f64.powf(rng.random_range(-6.0..6.0));
            let x = V(std::array::from_fn(|_| m * rng.random_range(-1.0..1.0)));
            let y = V(std::array::from_fn(|_| m * rng.random_range(-1.0..1.0)));
            let h = hypot_v(x, y);
            for l in 0..crate::lanes::W {
                worst = worst.max(ulps(h.0[l], x.0[l].hypot(y.0[l])));
            }
        }
        assert!(worst <= 2, "max error {worst} ulp");
    }

    /// Max error over random directions and magnitudes, all four quadrants, and near the
    /// range-reduction boundaries.
    #[test]
    fn max_error_vs_std_is_a_few_ulp() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut worst = 0u64;
        let mut worst_rel = 0.0f64;
        let n = 2_000_000;
        for i in 0..n {
            let (y, x) = match i % 4 {
                0 => {
                    let t: f64 = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
                    let m: f64 = 10f64.powf(rng.random_range(-6.0..6.0));
                    (m * t.sin(), m * t.cos())
                }
                1 => (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)),
                2 => {
                    // Near |y|/|x| = 0.66 and tan(3π/8).
                    let t = if rng.random_bool(0.5) { 0.66 } else { T3P8 };
                    let t = t * (1.0 + rng.random_range(-1e-6..1e-6));
                    let sx = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                    let sy = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                    (sy * t, sx * 1.0)
                }
                _ => {
                    // Tiny angles (like azimuths and launch angles near zero).
                    let x: f64 = rng.random_range(1.0..100.0);
                    (x * rng.random_range(-1e-9..1e-9), x)
                }
            };
            let (got, want) = (atan2(y, x), y.atan2(x));
            worst = worst.max(ulps(got, want));
            worst_rel = worst_rel.max(((got - want) / want).abs());
        }
        eprintln!("atan2: max error {worst} ulp, max relative error {worst_rel:e}");
        assert!(worst <= 4, "max error {worst} ulp");
        assert!(worst_rel < 1e-15);
    }
}
