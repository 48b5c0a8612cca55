//! Face-map values as CSV text: rounded to [`MAP_DIGITS`] significant digits.
//!
//! A face map's values are model outputs (ball speed, angles, spins, smash factor) whose
//! shortest round-trip form has 16–17 digits, far beyond anything the model or a measurement
//! resolves. Written to ten significant digits they change by at most 5·10⁻¹⁰ relative (the
//! tolerance the engine's results keep is 10⁻⁹), and a 9 × 801² study writes about a third
//! fewer bytes, which is what its run time is mostly made of (the kernel's page-cache copy).
//! Exact doubles are one flag away: `--format parquet` stores the long table's values bit for
//! bit, and shard files keep every digit so that a merge equals the unsharded run byte for byte.
//!
//! The text is the value correctly rounded to ten significant digits (as `format!("{v:.9e}")`
//! rounds it), laid out as `Display` lays out a number: plain digits, never an exponent, no
//! trailing zeros or point.

/// Significant digits of a face-map value in CSV files.
pub const MAP_DIGITS: u32 = 10;

/// `10^k` for `k` in `0..=22`, each exact in an `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Smallest ten-digit integer.
const LOW: f64 = 1e9;
/// Smallest eleven-digit integer.
const HIGH: f64 = 1e10;

/// `00` to `99`.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Append `v` rounded to [`MAP_DIGITS`] significant digits; a non-finite value becomes nothing
/// (an empty cell).
#[inline]
pub fn push_map_cell(out: &mut Vec<u8>, v: f64) {
    if !v.is_finite() {
        return;
    }
    let a = v.abs();
    match digits_fast(a) {
        Some((m, e)) => {
            // At most a sign, `0.`, twelve zeros and ten digits.
            let mut buf = [b'0'; 32];
            let len = layout(&mut buf, v.is_sign_negative(), m, e);
            // A fixed-size copy, then cut to length: no variable-length `memcpy` call.
            let start = out.len();
            out.extend_from_slice(&buf);
            out.truncate(start + len);
        }
        None => push_exact(out, v),
    }
}

/// `a · 10^(9 − e)` for `9 − e` in `0..=22` (one exact power of ten, one rounding).
#[inline]
fn scaled(a: f64, e: i32) -> Option<f64> {
    POW10.get(usize::try_from(9 - e).ok()?).map(|p| a * p)
}

/// The ten digits `m ∈ [10⁹, 10¹⁰)` and decimal exponent `e ∈ [−13, 9]` of `a`
/// (`a ≈ m · 10^(e − 9)`), correctly rounded; `None` where one multiplication cannot prove it:
/// zero, magnitudes outside about `10⁻¹³..10¹⁰`, and values within a few millionths of a unit
/// of the tenth digit from a tie.
#[inline]
fn digits_fast(a: f64) -> Option<(u64, i32)> {
    let biased = ((a.to_bits() >> 52) & 0x7ff) as i32;
    if biased == 0 {
        return None;
    }
    // floor(e2 · log10 2), within one of the decimal exponent; corrected below.
    let mut e = ((biased - 1023) * 78913) >> 18;
    let mut s = scaled(a, e)?;
    while s >= HIGH {
        e += 1;
        s = scaled(a, e)?;
    }
    while s < LOW {
        e -= 1;
        s = scaled(a, e)?;
    }
    // `s` is within half an ulp (≤ 1e-6 at this size) of the exact product: a fraction this
    // close to one half might round either way, so it takes the exact path.
    let int = s as u64;
    let frac = s - int as f64;
    if (frac - 0.5).abs() < 4e-6 {
        return None;
    }
    let m = int + u64::from(frac > 0.5);
    if m >= 10_000_000_000 {
        return Some((1_000_000_000, e + 1));
    }
    Some((m, e))
}

/// `m` (ten digits) as ASCII.
#[inline]
fn ten_digits(m: u64) -> [u8; 10] {
    let hi = (m / 100_000_000) as usize;
    let lo = (m % 100_000_000) as u32;
    let (a, b) = ((lo / 10_000) as usize, (lo % 10_000) as usize);
    let mut d = [0u8; 10];
    for (k, x) in [hi, a / 100, a % 100, b / 100, b % 100]
        .into_iter()
        .enumerate()
    {
        d[2 * k] = PAIRS[2 * x];
        d[2 * k + 1] = PAIRS[2 * x + 1];
    }
    d
}

/// `±m · 10^(e − 9)` (`m` of ten digits, `e ∈ [−13, 9]`) in plain notation without trailing
/// zeros into `buf` (all `b'0'`); returns its length.
#[inline]
fn layout(buf: &mut [u8; 32], negative: bool, m: u64, e: i32) -> usize {
    let d = ten_digits(m);
    let mut n = 10;
    while n > 1 && d[n - 1] == b'0' {
        n -= 1;
    }
    let p = usize::from(negative);
    if negative {
        buf[0] = b'-';
    }
    if e >= 0 {
        let int = e as usize + 1;
        buf[p..p + 10].copy_from_slice(&d);
        if n <= int {
            return p + int;
        }
        buf[p + int] = b'.';
        buf[p + int + 1..p + n + 1].copy_from_slice(&d[int..n]);
        p + n + 1
    } else {
        // `0.`, then −e − 1 zeros (already in `buf`), then the digits.
        buf[p + 1] = b'.';
        let at = p + 1 + (-e) as usize;
        buf[at..at + 10].copy_from_slice(&d);
        at + n
    }
}

/// [`push_map_cell`] by the standard library's exact formatting (zero and rare values).
#[cold]
fn push_exact(out: &mut Vec<u8>, v: f64) {
    if v.is_sign_negative() {
        out.push(b'-');
    }
    let a = v.abs();
    if a == 0.0 {
        out.push(b'0');
        return;
    }
    let s = format!("{a:.9e}");
    let (mant, exp) = s.split_once('e').expect("`{:e}` writes an exponent");
    let digits: Vec<u8> = mant.bytes().filter(u8::is_ascii_digit).collect();
    let e: i64 = exp.parse().expect("`{:e}` writes an integer exponent");
    let n = digits.iter().rposition(|&d| d != b'0').map_or(1, |i| i + 1);
    let digits = &digits[..n];
    if e >= 0 {
        let int = e as usize + 1;
        if n <= int {
            out.extend_from_slice(digits);
            out.resize(out.len() + int - n, b'0');
        } else {
            out.extend_from_slice(&digits[..int]);
            out.push(b'.');
            out.extend_from_slice(&digits[int..]);
        }
    } else {
        out.extend_from_slice(b"0.");
        out.resize(out.len() + (-e - 1) as usize, b'0');
        out.extend_from_slice(digits);
    }
}

/// A matrix line `y,v,v,…\n`: the row's coordinate `y` in full, its values as map cells.
pub fn push_matrix_row(out: &mut Vec<u8>, y: f64, values: &[f64]) {
    crate::data::number::push_f64(out, y);
    for v in values {
        out.push(b',');
        push_map_cell(out, *v);
    }
    out.push(b'\n');
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The independent reference: the standard library rounds to ten significant digits
    /// (exactly), and a decimal of ten digits reads back to a double whose `Display` is those
    /// digits.
    fn reference(v: f64) -> String {
        if !v.is_finite() {
            return String::new();
        }
        let r: f64 = format!("{v:.9e}").parse().unwrap();
        format!("{r}")
    }

    fn fast(v: f64) -> String {
        let mut out = Vec::new();
        push_map_cell(&mut out, v);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn equals_the_standard_library_rounding_over_every_magnitude() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut fast_path = 0;
        for _ in 0..400_000 {
            // Random bits: every exponent and sign, including subnormals.
            let v = f64::from_bits(rng.random::<u64>());
            if !v.is_finite() {
                continue;
            }
            assert_eq!(fast(v), reference(v), "{v:e}");
        }
        for _ in 0..400_000 {
            // Face-map magnitudes: 1e-6 .. 1e5, both signs.
            let v = 10f64.powf(rng.random_range(-6.0..5.0)) * if rng.random() { 1.0 } else { -1.0 };
            assert_eq!(fast(v), reference(v), "{v:e}");
            fast_path += usize::from(digits_fast(v.abs()).is_some());
        }
        assert!(fast_path > 390_000, "the fast path is taken ({fast_path})");
    }

    #[test]
    fn ties_powers_of_ten_and_carries_round_as_the_standard_library() {
        let cases = [
            0.0,
            -0.0,
            1.0,
            10.0,
            1e9,
            1e10,
            1e22,
            1e23,
            1e-5,
            1e-7,
            0.1,
            0.3,
            1.5,
            148.5,
            // Exactly representable ties of the eleventh digit (half to even, exactly).
            1.00000000005,
            2.5000000001,
            1_234_567_890.5,
            1_234_567_891.5,
            8_589_934_592.5,
            // Rounding up to the next power of ten.
            9_999_999_999.6,
            0.999_999_999_96,
            99.999_999_999_9,
            -9.999_999_999_5,
            1e300,
            f64::MIN_POSITIVE,
            5e-324,
            2700.0,
            12.345_678_901_234_567,
        ];
        for v in cases {
            for v in [v, -v, v.next_up(), v.next_down()] {
                if v.abs() < 1e-300 {
                    // Ten digits of the smallest subnormals do not read back to themselves, so
                    // `reference` does not apply: the same decimal as the standard library's.
                    let want: f64 = format!("{v:.9e}").parse().unwrap();
                    assert_eq!(fast(v).parse::<f64>().unwrap().to_bits(), want.to_bits());
                } else if v.is_finite() {
                    assert_eq!(fast(v), reference(v), "{v:e}");
                }
            }
        }
        assert_eq!(fast(f64::NAN), "");
        assert_eq!(fast(f64::INFINITY), "");
        assert_eq!(fast(148.531_274_812_345_67), "148.5312748");
        assert_eq!(fast(-0.000_012_345_678_901_2), "-0.0000123456789");
    }

    #[test]
    fn a_cell_is_within_half_a_unit_of_the_tenth_digit() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..100_000 {
            let v: f64 = 10f64.powf(rng.random_range(-8.0..8.0));
            let back: f64 = fast(v).parse().unwrap();
            assert!(((back - v) / v).abs() <= 5.000_001e-10, "{v:e} -> {back:e}");
        }
    }
}
