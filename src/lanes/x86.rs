//! The explicit x86-64 lane types: [`F64x4`] over `__m256d` (AVX2) and [`F64x8`] over
//! `__m512d` (AVX-512F), each with its mask type, written with `core::arch` intrinsics so that
//! the compiler neither splits a vector into halves nor chooses other instructions than these.
//!
//! # Safety
//!
//! The operations are safe functions that execute AVX (or AVX-512F) instructions. That is sound
//! because of one invariant of this crate: **a value of [`F64x4`] or [`M4`] exists only on a
//! machine with AVX2, and a value of [`F64x8`] or [`M8`] only on one with AVX-512F.** The types
//! are private to the crate, and they are named only by the dispatching functions (the
//! `*_avx2` and `*_avx512` functions of the fits and of the flight integrator), each an
//! `unsafe fn` with `#[target_feature]` called only where the level is at most
//! [`super::simd_level`]'s (`SimdLevel::or_supported`): every generic lane function
//! instantiated with one of these types runs inside such a call. The operations are `#[inline(always)]`, so they are
//! compiled into those functions with their instruction set.
//!
//! Only correctly rounded `+ − × ÷ √`, ordered quiet comparisons, blends and bit operations are
//! used (no `fmadd`), so both types give the bits of the portable [`super::V`].

use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use super::{LaneMask, Lanes, Real};

/// 4 lanes of `f64` in an AVX register (see the module docs for when one may exist).
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F64x4(__m256d);

/// Lane mask of [`F64x4`]: each lane all ones (true) or all zeros (false), as `vcmppd` makes.
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct M4(__m256d);

/// 8 lanes of `f64` in an AVX-512 register (see the module docs for when one may exist).
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F64x8(__m512d);

/// Lane mask of [`F64x8`]: bit `i` is lane `i` (an AVX-512 mask register).
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct M8(__mmask8);

/// `unsafe { $e }` for the intrinsics of a lane type's operation.
macro_rules! simd {
    ($e:expr) => {
        // SAFETY: values of the lane types exist only on machines with their instruction set
        // (the invariant of the module docs), and the intrinsics only read their arguments
        // (loads and stores are from and to local arrays of the vector's size).
        unsafe { $e }
    };
}

/// The arithmetic operators of a lane type, with `f64` on the right splatted.
macro_rules! arith {
    ($t:ident, $tr:ident, $f:ident, $op:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t {
                $t(simd!($op(self.0, o.0)))
            }
        }
        impl $tr<f64> for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: f64) -> $t {
                self.$f(<$t as Real>::splat(o))
            }
        }
    };
}

arith!(F64x4, Add, add, _mm256_add_pd);
arith!(F64x4, Sub, sub, _mm256_sub_pd);
arith!(F64x4, Mul, mul, _mm256_mul_pd);
arith!(F64x4, Div, div, _mm256_div_pd);
arith!(F64x8, Add, add, _mm512_add_pd);
arith!(F64x8, Sub, sub, _mm512_sub_pd);
arith!(F64x8, Mul, mul, _mm512_mul_pd);
arith!(F64x8, Div, div, _mm512_div_pd);

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        F64x4(simd!(_mm256_xor_pd(self.0, _mm256_set1_pd(-0.0))))
    }
}

impl Neg for F64x8 {
    type Output = F64x8;
    #[inline(always)]
    fn neg(self) -> F64x8 {
        let sign = simd!(_mm512_set1_epi64(i64::MIN));
        F64x8(simd!(_mm512_castsi512_pd(_mm512_xor_si512(
            _mm512_castpd_si512(self.0),
            sign
        ))))
    }
}

impl BitAnd for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitand(self, o: M4) -> M4 {
        M4(simd!(_mm256_and_pd(self.0, o.0)))
    }
}

impl BitOr for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitor(self, o: M4) -> M4 {
        M4(simd!(_mm256_or_pd(self.0, o.0)))
    }
}

impl Not for M4 {
    type Output = M4;
    #[inline(always)]
    fn not(self) -> M4 {
        let ones = simd!(_mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
        M4(simd!(_mm256_xor_pd(self.0, ones)))
    }
}

impl LaneMask for M4 {
    #[inline(always)]
    fn any(self) -> bool {
        simd!(_mm256_movemask_pd(self.0)) != 0
    }
    #[inline(always)]
    fn all(self) -> bool {
        simd!(_mm256_movemask_pd(self.0)) == 0b1111
    }
    #[inline(always)]
    fn get(self, i: usize) -> bool {
        (simd!(_mm256_movemask_pd(self.0)) >> i) & 1 != 0
    }
    #[inline(always)]
    fn select_mask(self, a: M4, b: M4) -> M4 {
        M4(simd!(_mm256_blendv_pd(b.0, a.0, self.0)))
    }
}

impl BitAnd for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitand(self, o: M8) -> M8 {
        M8(self.0 & o.0)
    }
}

impl BitOr for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitor(self, o: M8) -> M8 {
        M8(self.0 | o.0)
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        M8(!self.0)
    }
}

impl LaneMask for M8 {
    #[inline(always)]
    fn any(self) -> bool {
        self.0 != 0
    }
    #[inline(always)]
    fn all(self) -> bool {
        self.0 == 0xff
    }
    #[inline(always)]
    fn get(self, i: usize) -> bool {
        (self.0 >> i) & 1 != 0
    }
    #[inline(always)]
    fn select_mask(self, a: M8, b: M8) -> M8 {
        M8((self.0 & a.0) | (!self.0 & b.0))
    }
}

impl Real for F64x4 {
    type Mask = M4;
    #[inline(always)]
    fn splat(v: f64) -> Self {
        F64x4(simd!(_mm256_set1_pd(v)))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F64x4(simd!(_mm256_sqrt_pd(self.0)))
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        self.map(|x| x.powf(e))
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M4 {
        M4(simd!(_mm256_cmp_pd::<_CMP_GT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn no() -> M4 {
        M4(simd!(_mm256_setzero_pd()))
    }
    #[inline(always)]
    fn select(m: M4, a: Self, b: Self) -> Self {
        F64x4(simd!(_mm256_blendv_pd(b.0, a.0, m.0)))
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut a = self.to_array();
        for v in &mut a {
            *v = f(*v);
        }
        Self::load(&a)
    }
    #[inline(always)]
    fn zip_map(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let (mut a, b) = (self.to_array(), o.to_array());
        for (v, w) in a.iter_mut().zip(b) {
            *v = f(*v, w);
        }
        Self::load(&a)
    }
}

impl Lanes for F64x4 {
    const N: usize = 4;
    type Array = [f64; 4];
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        Self::load(&[f(0), f(1), f(2), f(3)])
    }
    #[inline(always)]
    fn load(s: &[f64]) -> Self {
        let s: &[f64; 4] = s[..4].try_into().expect("4 lanes");
        F64x4(simd!(_mm256_loadu_pd(s.as_ptr())))
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        let mut a = [0.0; 4];
        simd!(_mm256_storeu_pd(a.as_mut_ptr(), self.0));
        a
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F64x4(simd!(_mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0)))
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        let s = simd!(_mm256_set1_pd(-0.0));
        let mag = simd!(_mm256_andnot_pd(s, self.0));
        F64x4(simd!(_mm256_or_pd(mag, _mm256_and_pd(s, sign.0))))
    }
    #[inline(always)]
    fn sign_bit(self) -> M4 {
        // A lane is negative as a signed integer exactly when its sign bit is set.
        let bits = simd!(_mm256_castpd_si256(self.0));
        let neg = simd!(_mm256_cmpgt_epi64(_mm256_setzero_si256(), bits));
        M4(simd!(_mm256_castsi256_pd(neg)))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M4 {
        M4(simd!(_mm256_cmp_pd::<_CMP_LT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn le(self, o: Self) -> M4 {
        M4(simd!(_mm256_cmp_pd::<_CMP_LE_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M4 {
        M4(simd!(_mm256_cmp_pd::<_CMP_EQ_OQ>(self.0, o.0)))
    }
}

impl Real for F64x8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(v: f64) -> Self {
        F64x8(simd!(_mm512_set1_pd(v)))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F64x8(simd!(_mm512_sqrt_pd(self.0)))
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        self.map(|x| x.powf(e))
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M8 {
        M8(simd!(_mm512_cmp_pd_mask::<_CMP_GT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn no() -> M8 {
        M8(0)
    }
    #[inline(always)]
    fn select(m: M8, a: Self, b: Self) -> Self {
        // `mask_blend(k, x, y)` takes `y` where `k` is set.
        F64x8(simd!(_mm512_mask_blend_pd(m.0, b.0, a.0)))
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut a = self.to_array();
        for v in &mut a {
            *v = f(*v);
        }
        Self::load(&a)
    }
    #[inline(always)]
    fn zip_map(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let (mut a, b) = (self.to_array(), o.to_array());
        for (v, w) in a.iter_mut().zip(b) {
            *v = f(*v, w);
        }
        Self::load(&a)
    }
}

impl F64x8 {
    /// The lanes' bits as integers.
    #[inline(always)]
    fn bits(self) -> __m512i {
        simd!(_mm512_castpd_si512(self.0))
    }

    /// From bits.
    #[inline(always)]
    fn from_bits(b: __m512i) -> Self {
        F64x8(simd!(_mm512_castsi512_pd(b)))
    }
}

impl Lanes for F64x8 {
    const N: usize = 8;
    type Array = [f64; 8];
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        Self::load(&[f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)])
    }
    #[inline(always)]
    fn load(s: &[f64]) -> Self {
        let s: &[f64; 8] = s[..8].try_into().expect("8 lanes");
        F64x8(simd!(_mm512_loadu_pd(s.as_ptr())))
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 8] {
        let mut a = [0.0; 8];
        simd!(_mm512_storeu_pd(a.as_mut_ptr(), self.0));
        a
    }
    #[inline(always)]
    fn abs(self) -> Self {
        let mag = simd!(_mm512_set1_epi64(i64::MAX));
        Self::from_bits(simd!(_mm512_and_si512(self.bits(), mag)))
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        let (mag, s) = simd!((_mm512_set1_epi64(i64::MAX), _mm512_set1_epi64(i64::MIN)));
        let a = simd!(_mm512_and_si512(self.bits(), mag));
        let b = simd!(_mm512_and_si512(sign.bits(), s));
        Self::from_bits(simd!(_mm512_or_si512(a, b)))
    }
    #[inline(always)]
    fn sign_bit(self) -> M8 {
        let s = simd!(_mm512_set1_epi64(i64::MIN));
        M8(simd!(_mm512_test_epi64_mask(self.bits(), s)))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M8 {
        M8(simd!(_mm512_cmp_pd_mask::<_CMP_LT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn le(self, o: Self) -> M8 {
        M8(simd!(_mm512_cmp_pd_mask::<_CMP_LE_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M8 {
        M8(simd!(_mm512_cmp_pd_mask::<_CMP_EQ_OQ>(self.0, o.0)))
    }
}
