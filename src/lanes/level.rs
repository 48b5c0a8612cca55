//! Which lane type this machine runs ([`simd_level`]), detected at run time.

/// A code path of the batched evaluations, from the most portable to the widest. Every path
/// gives the same bits (see [`super`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SimdLevel {
    /// Portable code: [`super::V`] (baseline x86-64 SSE2, or any other architecture).
    Portable,
    /// AVX2 (x86-64), detected at run time: 4 lanes of `__m256d`.
    Avx2,
    /// AVX-512F (x86-64), detected at run time: 8 lanes of `__m512d`.
    Avx512,
}

impl SimdLevel {
    /// Every level, narrowest first.
    pub const ALL: [SimdLevel; 3] = [SimdLevel::Portable, SimdLevel::Avx2, SimdLevel::Avx512];

    /// `self` if this machine runs it, else the widest level below it that it does run (to run
    /// a chosen path where possible: tests compare every level's bits).
    pub fn or_supported(self) -> SimdLevel {
        self.min(simd_level())
    }
}

/// The widest code path this machine runs (detected once by `std`, then a cached load).
pub fn simd_level() -> SimdLevel {
    #[cfg(target_arch = "x86_64")]
    {
        // `is_x86_feature_detected` also checks that the operating system saves the registers.
        if std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx2") {
            return SimdLevel::Avx512;
        }
        if std::is_x86_feature_detected!("avx2") {
            return SimdLevel::Avx2;
        }
    }
    SimdLevel::Portable
}
