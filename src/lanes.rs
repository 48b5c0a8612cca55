//! The number types the model is evaluated on, and the lane vectors the batched code runs on.
//!
//! [`Real`] is what the physics is written against once: `f64` (one shot) or a vector of lanes.
//! [`Lanes`] adds what batched code needs of a vector (its width, gathering and scattering
//! lanes, comparisons, `|x|`, sign bits). Three vector types implement it:
//!
//! | type | lanes | where it runs |
//! |---|---:|---|
//! | [`V`] (`[f64; 4]`, every operation a fixed-length loop) | 4 | anywhere (the portable path) |
//! | `F64x4` (`__m256d`, `x86` module) | 4 | x86-64 with AVX2, chosen at run time |
//! | `F64x8` (`__m512d`, `x86` module) | 8 | x86-64 with AVX-512F, chosen at run time |
//!
//! [`simd_level`] says which this machine runs. Code that evaluates lanes is written once,
//! generic over [`Lanes`], and instantiated per level inside a `#[target_feature]` function
//! entered only after [`simd_level`] reported that level (see [`SimdLevel`]).
//!
//! **Same bits on every path.** Only IEEE-754 correctly rounded operations (`+ − × ÷ √`),
//! ordered quiet comparisons, blends and bit operations are used, never a fused multiply–add
//! (the explicit types call the separate multiply and add instructions; Rust never contracts
//! them), so a lane's result is the same on the portable, AVX2 and AVX-512 paths and the same as
//! the scalar `f64` evaluation of the same code. `powf` and the libm functions of user-defined
//! effects run lane by lane on the scalar function.

use std::fmt::Debug;
use std::ops::{BitAnd, BitOr, IndexMut, Not};

mod level;
mod portable;
mod real;
#[cfg(target_arch = "x86_64")]
mod x86;

pub use level::{simd_level, SimdLevel};
pub use portable::{M, V, W};
pub use real::Real;
#[cfg(target_arch = "x86_64")]
pub(crate) use x86::{F64x4, F64x8};

/// `[f(0), f(1)]`, always inlined into the caller. Lane code builds its small arrays with this
/// and [`each3`] rather than `std::array::from_fn` or `<[T; N]>::map`, which the compiler may keep
/// out of line: the explicit vector types' operations there would not be compiled with the
/// caller's instruction set (`target_feature`), but called one by one.
#[inline(always)]
pub fn each2<T>(mut f: impl FnMut(usize) -> T) -> [T; 2] {
    [f(0), f(1)]
}

/// `[f(0), f(1), f(2)]`, always inlined into the caller (see [`each2`]).
#[inline(always)]
pub fn each3<T>(mut f: impl FnMut(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

/// The most lanes any vector type has (stack buffers of lane indices are this long).
pub const MAX_LANES: usize = 8;

/// Per-lane truth values of a [`Real`] (`bool` for `f64`).
pub trait LaneMask:
    Copy + Debug + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self>
{
    /// Whether any lane is true.
    fn any(self) -> bool;
    /// Whether every lane is true.
    fn all(self) -> bool;
    /// Lane `i`.
    fn get(self, i: usize) -> bool;
    /// Lane-wise `if self { a } else { b }`.
    fn select_mask(self, a: Self, b: Self) -> Self;
}

impl LaneMask for bool {
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
    #[inline(always)]
    fn all(self) -> bool {
        self
    }
    #[inline(always)]
    fn get(self, _i: usize) -> bool {
        self
    }
    #[inline(always)]
    fn select_mask(self, a: Self, b: Self) -> Self {
        if self {
            a
        } else {
            b
        }
    }
}

/// A vector of [`Lanes::N`] doubles: [`Real`] plus what batched code needs. Constants combine
/// with a vector on its right only (`x * 2.0`, `L::splat(1.0) / x`): multiplication and
/// addition commute exactly in IEEE 754, so this is the same bits as the constant on the left.
pub trait Lanes: Real + Debug + Send + Sync + 'static {
    /// Number of lanes.
    const N: usize;
    /// `[f64; N]`.
    type Array: Copy + Debug + AsRef<[f64]> + AsMut<[f64]> + IndexMut<usize, Output = f64>;
    /// Lane `i` is `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// The first [`Lanes::N`] entries of `s`.
    ///
    /// # Panics
    /// If `s` is shorter.
    fn load(s: &[f64]) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> Self::Array;
    /// Lane `i`.
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.to_array()[i]
    }
    /// Lane-wise `|x|`.
    fn abs(self) -> Self;
    /// `|self|` with the sign bit of `sign`.
    fn copysign(self, sign: Self) -> Self;
    /// Lanes whose sign bit is set (including −0 and negative NaNs).
    fn sign_bit(self) -> Self::Mask;
    /// Lane-wise `self < o` (false for NaN).
    fn lt(self, o: Self) -> Self::Mask;
    /// Lane-wise `self <= o` (false for NaN).
    fn le(self, o: Self) -> Self::Mask;
    /// Lane-wise `self == o` (false for NaN).
    fn eq(self, o: Self) -> Self::Mask;
    /// Lanes that are finite (neither infinite nor NaN).
    #[inline(always)]
    fn finite(self) -> Self::Mask {
        self.abs().lt(Self::splat(f64::INFINITY))
    }
}

/// Prefetch hint for every cache line of `items` (no effect off x86-64).
#[inline(always)]
pub(crate) fn prefetch<T>(items: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        const LINE: usize = 64;
        let start = items.as_ptr().cast::<i8>();
        let bytes = std::mem::size_of_val(items);
        let mut off = 0;
        while off < bytes {
            // SAFETY: a prefetch never faults; the address is inside `items`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.add(off)) };
            off += LINE;
        }
        if bytes > 0 {
            // The last line, when `items` does not start on a line boundary.
            // SAFETY: as above, the last byte of `items`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.add(bytes - 1)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = items;
}
