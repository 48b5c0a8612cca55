//! The portable lane type: [`W`] doubles processed lane-wise.
//!
//! Every operation is written out for each of the four lanes of a `[f64; W]` (or `[u64; W]`
//! mask), marked `#[inline(always)]`, which LLVM's SLP vectoriser turns into packed
//! instructions where it can (pairs of SSE2 instructions on baseline x86-64). No loops: a loop
//! per operation gave LLVM's loop passes tens of thousands of four-trip loops to rotate and
//! unroll in each kernel, most of the library's build time. Only IEEE-754 correctly rounded
//! operations (`+ − × ÷ √`) and bit operations are used, and never fused multiply–add, so it
//! gives the same bits as the explicit SIMD types (`super::x86`).

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use super::{LaneMask, Lanes};

/// Lanes of the portable vector [`V`] (one AVX2 register of doubles).
pub const W: usize = 4;

const SIGN: u64 = 1 << 63;

/// `W` doubles.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(transparent)]
pub struct V(pub [f64; W]);

/// `W` lane masks: all ones (true) or all zeros (false), like the result of `vcmppd`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(transparent)]
pub struct M(pub [u64; W]);

/// `[e(0), e(1), e(2), e(3)]`: an expression of the lane index written out for each lane.
macro_rules! each {
    (|$i:ident| $e:expr) => {
        [
            {
                let $i = 0;
                $e
            },
            {
                let $i = 1;
                $e
            },
            {
                let $i = 2;
                $e
            },
            {
                let $i = 3;
                $e
            },
        ]
    };
}

// `each!` writes out four lanes.
const _: () = assert!(W == 4);

macro_rules! lanewise {
    ($a:expr, $b:expr, |$x:ident, $y:ident| $e:expr) => {{
        let (a, b) = ($a, $b);
        each!(|i| {
            let ($x, $y) = (a[i], b[i]);
            $e
        })
    }};
}

impl V {
    /// All lanes `v`.
    #[inline(always)]
    pub fn splat(v: f64) -> Self {
        Self([v; W])
    }

    /// Load from the first `W` entries of `s`.
    #[inline(always)]
    pub fn load(s: &[f64; W]) -> Self {
        Self(*s)
    }

    /// Lane-wise square root (correctly rounded).
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        let a = self.0;
        Self(each!(|i| a[i].sqrt()))
    }

    /// Lane-wise `self^e` (libm `pow` per lane: the same bits as the scalar `f64::powf`).
    #[inline(always)]
    pub fn powf(self, e: f64) -> Self {
        let a = self.0;
        Self(each!(|i| a[i].powf(e)))
    }

    /// Raw bits.
    #[inline(always)]
    pub fn to_bits(self) -> [u64; W] {
        let a = self.0;
        each!(|i| a[i].to_bits())
    }

    /// From raw bits.
    #[inline(always)]
    pub fn from_bits(b: [u64; W]) -> Self {
        Self(each!(|i| f64::from_bits(b[i])))
    }

    /// Lane-wise `|x|`.
    #[inline(always)]
    pub fn abs(self) -> Self {
        Self::from_bits(lanewise!(self.to_bits(), [0u64; W], |a, _b| a & !SIGN))
    }

    /// `|self|` with the sign bit of `sign`.
    #[inline(always)]
    pub fn copysign(self, sign: Self) -> Self {
        Self::from_bits(lanewise!(self.to_bits(), sign.to_bits(), |a, b| (a
            & !SIGN)
            | (b & SIGN)))
    }

    /// Lanes whose sign bit is set (including −0 and negative NaNs).
    #[inline(always)]
    pub fn sign_bit(self) -> M {
        M(lanewise!(
            self.to_bits(),
            [0u64; W],
            |a, _b| if a & SIGN != 0 { !0 } else { 0 }
        ))
    }

    /// Lane-wise `self < o`.
    #[inline(always)]
    pub fn lt(self, o: Self) -> M {
        M(cmp(self, o, |a, b| a < b))
    }

    /// Lane-wise `self <= o`.
    #[inline(always)]
    pub fn le(self, o: Self) -> M {
        M(cmp(self, o, |a, b| a <= b))
    }

    /// Lane-wise `self > o`.
    #[inline(always)]
    pub fn gt(self, o: Self) -> M {
        M(cmp(self, o, |a, b| a > b))
    }

    /// Lane-wise `self == o`.
    #[inline(always)]
    pub fn eq(self, o: Self) -> M {
        M(cmp(self, o, |a, b| a == b))
    }
}

#[inline(always)]
fn cmp(a: V, b: V, f: impl Fn(f64, f64) -> bool) -> [u64; W] {
    let (a, b) = (a.0, b.0);
    each!(|i| if f(a[i], b[i]) { !0 } else { 0 })
}

impl M {
    /// Lane-wise `if self { a } else { b }`.
    #[inline(always)]
    pub fn select(self, a: V, b: V) -> V {
        let (a, b, m) = (a.to_bits(), b.to_bits(), self.0);
        V::from_bits(each!(|i| (a[i] & m[i]) | (b[i] & !m[i])))
    }

    /// Lane-wise `if self { a } else { b }` on masks.
    #[inline(always)]
    pub fn select_mask(self, a: M, b: M) -> M {
        (self & a) | (!self & b)
    }

    /// Whether any lane is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        let m = self.0;
        (m[0] | m[1] | m[2] | m[3]) != 0
    }

    /// Lane `i` as a `bool`.
    #[inline(always)]
    pub fn get(self, i: usize) -> bool {
        self.0[i] != 0
    }
}

impl BitAnd for M {
    type Output = M;
    #[inline(always)]
    fn bitand(self, o: M) -> M {
        M(lanewise!(self.0, o.0, |a, b| a & b))
    }
}

impl BitOr for M {
    type Output = M;
    #[inline(always)]
    fn bitor(self, o: M) -> M {
        M(lanewise!(self.0, o.0, |a, b| a | b))
    }
}

impl Not for M {
    type Output = M;
    #[inline(always)]
    fn not(self) -> M {
        M(lanewise!(self.0, self.0, |a, _b| !a))
    }
}

macro_rules! arith {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: V) -> V {
                V(lanewise!(self.0, o.0, |a, b| a $op b))
            }
        }
        impl $tr<f64> for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: f64) -> V {
                V(lanewise!(self.0, [o; W], |a, b| a $op b))
            }
        }
        impl $tr<V> for f64 {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: V) -> V {
                V(lanewise!([self; W], o.0, |a, b| a $op b))
            }
        }
    };
}

arith!(Add, add, +);
arith!(Sub, sub, -);
arith!(Mul, mul, *);
arith!(Div, div, /);

impl Neg for V {
    type Output = V;
    #[inline(always)]
    fn neg(self) -> V {
        V(lanewise!(self.0, self.0, |a, _b| -a))
    }
}

impl LaneMask for M {
    #[inline(always)]
    fn any(self) -> bool {
        M::any(self)
    }
    #[inline(always)]
    fn all(self) -> bool {
        let m = self.0;
        (m[0] & m[1] & m[2] & m[3]) != 0
    }
    #[inline(always)]
    fn get(self, i: usize) -> bool {
        M::get(self, i)
    }
    #[inline(always)]
    fn select_mask(self, a: M, b: M) -> M {
        M::select_mask(self, a, b)
    }
}

impl Lanes for V {
    const N: usize = W;
    type Array = [f64; W];
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        V([f(0), f(1), f(2), f(3)])
    }
    #[inline(always)]
    fn load(s: &[f64]) -> Self {
        V(s[..W].try_into().expect("W lanes"))
    }
    #[inline(always)]
    fn to_array(self) -> [f64; W] {
        self.0
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn abs(self) -> Self {
        V::abs(self)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        V::copysign(self, sign)
    }
    #[inline(always)]
    fn sign_bit(self) -> M {
        V::sign_bit(self)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M {
        V::lt(self, o)
    }
    #[inline(always)]
    fn le(self, o: Self) -> M {
        V::le(self, o)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M {
        V::eq(self, o)
    }
}
