//! Numbers in output files: the shortest decimal that reads back to the same `f64`, laid out as
//! Rust's `Display` lays it out (plain digits, never an exponent, no trailing `.0`), so files are
//! byte-identical to `format!("{v}")` while the digits come from `zmij` (a Schubfach-family
//! shortest round-trip algorithm, several times faster than `Display` and about twice as fast
//! as `ryu` on the 17-digit values a face map is made of).
//!
//! The two can differ only where the value lies exactly halfway between two shortest decimals
//! (the fast algorithms round half to even, `Display` half up): when the exact decimal expansion
//! of the double has one digit more than the shortest form. Those rare values (and magnitudes
//! of 2⁵³ and more) are detected exactly and written by `Display`.

/// Append `v` (finite) to `out` exactly as `format!("{v}")` would write it.
#[inline]
pub fn push_f64(out: &mut Vec<u8>, v: f64) {
    debug_assert!(v.is_finite(), "non-finite value written to a file");
    let mut buf = zmij::Buffer::new();
    let s = buf.format_finite(v).as_bytes();
    if may_differ_from_display(v, s) {
        use std::io::Write as _;
        let _ = write!(out, "{v}");
        return;
    }
    // zmij writes plain digits from 1e-5 up to 1e16 (and `0.0`): no exponent to look for.
    let plain = v == 0.0 || (1e-5..1e16).contains(&v.abs());
    if plain {
        out.extend_from_slice(s.strip_suffix(b".0").unwrap_or(s));
    } else if let Some(e) = s.iter().position(|&b| b == b'e' || b == b'E') {
        push_plain(out, &s[..e], &s[e + 1..]);
    } else if let Some(stripped) = s.strip_suffix(b".0") {
        out.extend_from_slice(stripped);
    } else {
        out.extend_from_slice(s);
    }
}

/// Could the fast digits `s` of `v` differ from `Display`'s? Only at a tie: the exact value
/// of `v` has exactly one significant digit more than `s`.
#[inline]
fn may_differ_from_display(v: f64, s: &[u8]) -> bool {
    let bits = v.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (mut m, mut e) = if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    };
    if m == 0 {
        return false;
    }
    let tz = m.trailing_zeros();
    m >>= tz;
    e += i64::from(tz);
    if e >= 0 {
        // An integer: exact (so never a tie) below 2^53; larger ones are left to Display.
        return v.abs() >= (1u64 << 53) as f64;
    }
    // v = m / 2^f = m·5^f / 10^f: the exact decimal has digits(m·5^f) significant digits,
    // at least 0.69·f, so with more than 25 fractional bits it is longer than any tie (18).
    let f = (-e) as u32;
    if f > 25 {
        return false;
    }
    let exact = u128::from(m) * 5u128.pow(f);
    let exact_digits = exact.ilog10() as usize + 1;
    let mantissa = s
        .iter()
        .position(|&b| b == b'e' || b == b'E')
        .map_or(s, |i| &s[..i]);
    let digits: Vec<u8> = mantissa
        .iter()
        .copied()
        .filter(u8::is_ascii_digit)
        .collect();
    let first = digits
        .iter()
        .position(|&d| d != b'0')
        .unwrap_or(digits.len());
    let last = digits
        .iter()
        .rposition(|&d| d != b'0')
        .map_or(first, |i| i + 1);
    exact_digits == last.saturating_sub(first) + 1
}

/// Append `v` to `out`; a non-finite value becomes nothing (an empty CSV cell), and −0 is
/// written `0` (a sign on nothing reads as a tiny negative value).
#[inline]
pub fn push_cell(out: &mut Vec<u8>, v: f64) {
    if v.is_finite() {
        push_f64(out, if v == 0.0 { 0.0 } else { v });
    }
}

/// `mantissa` (`[-]d[.ddd]`) times ten to `exp` (`[+-]n`), written without an exponent.
#[cold]
fn push_plain(out: &mut Vec<u8>, mantissa: &[u8], exp: &[u8]) {
    let (neg, m) = match mantissa.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, mantissa),
    };
    let int_len = m.iter().position(|&b| b == b'.').unwrap_or(m.len()) as i64;
    let mut digits: Vec<u8> = m.iter().copied().filter(u8::is_ascii_digit).collect();
    while digits.len() > 1 && digits.last() == Some(&b'0') {
        digits.pop();
    }
    let e: i64 = std::str::from_utf8(exp)
        .ok()
        .and_then(|t| t.parse().ok())
        .expect("zmij writes a decimal exponent");
    let point = int_len + e;
    if neg {
        out.push(b'-');
    }
    let n = digits.len() as i64;
    if point <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', (-point) as usize));
        out.extend_from_slice(&digits);
    } else if point >= n {
        out.extend_from_slice(&digits);
        out.extend(std::iter::repeat_n(b'0', (point - n) as usize));
    } else {
        out.extend_from_slice(&digits[..point as usize]);
        out.push(b'.');
        out.extend_from_slice(&digits[point as usize..]);
    }
}

/// `s.parse::<f64>().ok()`, faster on the plain decimals of data files.
///
/// A cell of the form `[+-]digits[.digits]` with at most 19 digits, a digit string `m` of at
/// most 2^53 and at most 22 digits after the point is `m / 10^k` with `m` and `10^k` both exact
/// `f64`s, so one IEEE division gives the correctly rounded value, which is what std's parser
/// returns (Clinger's fast path, the first thing std's parser tries too; std's generality cost
/// more than the division on cells of a few digits). Anything else (exponents, `inf`, long or
/// malformed cells) is std's to parse or refuse, so the same cells are accepted.
#[inline]
pub fn parse_f64(s: &str) -> Option<f64> {
    match plain_decimal(s.as_bytes()) {
        Some(v) => Some(v),
        None => s.parse().ok(),
    }
}

/// Powers of ten that are exact `f64`s.
const EXACT_POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The value of `[+-]digits[.digits]` when [`parse_f64`]'s exact division applies, else
/// `None`.
#[inline]
fn plain_decimal(b: &[u8]) -> Option<f64> {
    let (neg, b) = match b.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, b),
    };
    if b.is_empty() || b.len() > 20 {
        return None;
    }
    let (mut m, mut digits, mut point) = (0u64, 0usize, None);
    for (i, &c) in b.iter().enumerate() {
        let d = c.wrapping_sub(b'0');
        if d < 10 {
            // Wraps only past 19 digits, which are refused below.
            m = m.wrapping_mul(10).wrapping_add(u64::from(d));
            digits += 1;
        } else if c == b'.' && point.is_none() {
            point = Some(i);
        } else {
            return None;
        }
    }
    let frac = point.map_or(0, |p| b.len() - p - 1);
    if digits == 0 || digits > 19 || m > 1 << 53 {
        return None;
    }
    let v = m as f64 / EXACT_POW10[frac];
    Some(if neg { -v } else { v })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same_as_display(v: f64) {
        let mut out = Vec::new();
        push_f64(&mut out, v);
        assert_eq!(
            String::from_utf8(out).unwrap(),
            format!("{v}"),
            "bits {:#x}",
            v.to_bits()
        );
    }

    #[test]
    fn matches_display_on_edge_values() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1.5,
            100.0,
            1e15,
            1e16,
            1e17,
            1.2345e21,
            1e-5,
            1e-6,
            1e-7,
            -2.5e-9,
            123_456_789.125,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -f64::MAX,
            0.30000000000000004,
        ] {
            same_as_display(v);
        }
    }

    #[test]
    fn matches_display_on_random_bit_patterns() {
        // A fixed xorshift sequence over all exponents, and values on a typical output scale.
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if v.is_finite() {
                same_as_display(v);
                same_as_display((x >> 11) as f64 / (1u64 << 53) as f64 * 300.0 - 150.0);
            }
        }
    }

    #[test]
    fn matches_display_on_values_with_few_fractional_bits() {
        // Values with few fractional bits, where shortest-digit ties exist (1 + 2^-17 is one).
        same_as_display(1.0 + 2f64.powi(-17));
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let int = (x >> 14) as f64; // up to 2^50
            let frac = (x & 7) as f64 / 8.0;
            same_as_display(int + frac);
            same_as_display(-(int / 4.0 + frac));
            same_as_display(int * 16.0 + frac);
            let k = (x % 40) as i32;
            same_as_display(((x >> 20) as f64) * 2f64.powi(-k - 10));
        }
    }

    #[test]
    fn non_finite_cells_are_empty() {
        let mut out = Vec::new();
        push_cell(&mut out, f64::NAN);
        push_cell(&mut out, f64::INFINITY);
        assert!(out.is_empty());
    }

    /// `parse_f64` is `str::parse` on every cell: plain decimals of every length around the
    /// fast path's limits (2^53, 19 digits, 22 decimals), signs, zeros, points at either end,
    /// and what std refuses or reads another way.
    #[test]
    fn parse_f64_is_std_parse() {
        let same = |s: &str| {
            let (fast, std) = (parse_f64(s), s.parse::<f64>().ok());
            assert_eq!(fast.map(f64::to_bits), std.map(f64::to_bits), "{s:?}");
        };
        for s in [
            "",
            "+",
            "-",
            ".",
            "+.",
            "-.",
            "0",
            "-0",
            "+0",
            "-0.0",
            "0.",
            ".0",
            "-.5",
            "+.5",
            "5.",
            "1..2",
            "1.2.3",
            "--1",
            "+-1",
            "1-",
            " 1",
            "1 ",
            "1e5",
            "1E-5",
            "1e",
            "e1",
            "inf",
            "-inf",
            "Infinity",
            "NaN",
            "nan",
            "0x10",
            "1_0",
            "١",
            "9007199254740992",
            "9007199254740993",
            "9007199254740991",
            "900719925474099.3",
            "9007199254740993.0",
            "1234567890123456789",
            "12345678901234567890",
            "99999999999999999999",
            "0.0000000000000000000001",
            "0.00000000000000000000001",
            "1.0000000000000000000",
            "00000000000000000001",
            "0000000000000000001.5",
            "159.71",
            "-600",
            "2087",
            "8.91",
        ] {
            same(s);
        }
        let mut x: u64 = 0x853c_49e6_748f_ea9b;
        for _ in 0..300_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let digits = (x % 21) as usize + 1;
            let mantissa = (x >> 8) % 10u64.pow(digits.min(19) as u32);
            let mut t = format!("{mantissa:0digits$}");
            let point = ((x >> 40) % (digits as u64 + 2)) as usize;
            if point <= t.len() {
                t.insert(point, '.');
            }
            match (x >> 50) % 3 {
                0 => same(&t),
                1 => same(&format!("-{t}")),
                _ => same(&format!("+{t}")),
            }
            same(&format!("{}", f64::from_bits(x)));
            same(&format!(
                "{:.3}",
                (x >> 11) as f64 / (1u64 << 53) as f64 * 600.0 - 300.0
            ));
        }
    }
}
