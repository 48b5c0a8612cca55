//! [`Real`]: the number type the laws and user-defined expressions are evaluated on, `f64` (one
//! shot) or a vector of lanes, with the same operations on both; its `f64` and [`V`] forms.

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::{LaneMask, M, V, W};

/// A number the laws are evaluated on: `f64` (one shot) or a vector of lanes ([`V`], and the
/// explicit SIMD types of [`super::Lanes`]).
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// Per-lane truth value (`bool` for `f64`).
    type Mask: LaneMask;
    /// Every lane `v`.
    fn splat(v: f64) -> Self;
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    /// `self^e` (libm `pow`, lane by lane).
    fn powf(self, e: f64) -> Self;
    /// `self > o`, lane by lane.
    fn gt(self, o: Self) -> Self::Mask;
    /// All lanes false.
    fn no() -> Self::Mask;
    /// `if m { a } else { b }`, lane by lane.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `f` applied lane by lane (the libm functions of user-defined effects).
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
    /// `f` applied to the lanes of `self` and `o` pairwise.
    fn zip_map(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        f64::powf(self, e)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> bool {
        self > o
    }
    #[inline(always)]
    fn no() -> bool {
        false
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip_map(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        f(self, o)
    }
}

impl Real for V {
    type Mask = M;
    #[inline(always)]
    fn splat(v: f64) -> Self {
        V::splat(v)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        V::sqrt(self)
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        V::powf(self, e)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M {
        V::gt(self, o)
    }
    #[inline(always)]
    fn no() -> M {
        M([0; W])
    }
    #[inline(always)]
    fn select(m: M, a: Self, b: Self) -> Self {
        m.select(a, b)
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut r = self.0;
        for v in &mut r {
            *v = f(*v);
        }
        V(r)
    }
    #[inline(always)]
    fn zip_map(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut r = self.0;
        for (v, w) in r.iter_mut().zip(o.0) {
            *v = f(*v, w);
        }
        V(r)
    }
}
