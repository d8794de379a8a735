//! Magnitudes of input values without overflow or underflow, angles without lost turns, and
//! numbers beyond f64's range for messages (docs/spec.md §2, *Input validation*).
//!
//! ```text
//! ‖v‖ = s · ‖v / s‖,  s = max |v_i|        (squares of 1e200 overflow, of 1e-200 underflow)
//! deg:  a mod 360 exactly, then to radians  (1e200° ≡ 128°: f64 `%` is exact)
//! rad:  |a| ≤ 1e15, else an input error     (beyond, the decimal the user wrote and the f64
//!                                            read differ by a sizeable fraction of a turn)
//! ```
//!
//! Components whose largest magnitude lies in `[1e-100, 1e100]` are squared as they are, so
//! ordinary inputs give the same bits as a plain `length()`.

use crate::error::num;
use std::ops::RangeInclusive;

/// Largest magnitude of an angle in radians, and largest length of a rotation vector in its
/// own unit (`rad` or `deg`). The ulp of 1e15 is 0.125, so a radian value there still carries
/// its fraction of a turn to about 1%; at 2⁵³ ≈ 9e15 the ulp is a third of a turn.
pub const MAX_ANGLE: f64 = 1e15;

/// Largest magnitudes whose squares are summed without scaling.
const PLAIN: RangeInclusive<f64> = 1e-100..=1e100;

/// `v` as `s · w` with `w` safe to square: `s = 1` and `w = v` when the largest magnitude is in
/// `[1e-100, 1e100]` (or all are zero), else `s` is the largest magnitude and `w = v / s`.
///
/// ```
/// use inbetween::rotation::magnitude::split;
///
/// assert_eq!(split([3.0, 4.0]), (1.0, [3.0, 4.0]));
/// let (s, w) = split([3e200, -4e200]);
/// assert_eq!(s, 4e200);
/// assert!((w[0] - 0.75).abs() < 1e-16 && w[1] == -1.0);
/// ```
pub fn split<const N: usize>(v: [f64; N]) -> (f64, [f64; N]) {
    let s = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if s == 0.0 || PLAIN.contains(&s) {
        (1.0, v)
    } else {
        (s, v.map(|x| x / s))
    }
}

/// Euclidean length of `v` without overflow or underflow (infinite only when the length
/// itself exceeds `f64::MAX`).
///
/// ```
/// use inbetween::rotation::magnitude::length;
///
/// // The squares of these overflow and underflow; the lengths are right to the last bits.
/// assert!((length([3e200, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
/// assert!((length([3e-200, 4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
/// ```
pub fn length<const N: usize>(v: [f64; N]) -> f64 {
    let (s, w) = split(v);
    s * w.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// An angle in `deg` reduced exactly to `(−360, 360)` and converted to radians; an angle in
/// `rad` returned as it is when its magnitude is at most [`MAX_ANGLE`], else `None`.
pub(crate) fn angle_to_rad(a: f64, unit: super::unit::AngleUnit) -> Option<f64> {
    match unit {
        // `%` of finite f64 values is exact (the remainder is representable).
        super::unit::AngleUnit::Deg => Some((a % 360.0).to_radians()),
        super::unit::AngleUnit::Rad => (a.abs() <= MAX_ANGLE).then_some(a),
    }
}

/// The product of finite `factors`, for a message: [`num`] (or `{:.p$e}` with `precision`)
/// when the product is a normal f64 (or a factor is zero), else the same notation computed from the factors'
/// decimal mantissas and exponents, so that a value beyond f64's range still shows its digits
/// (`product_num(&[2.0, 1e308], None)` is `2e308`, not `inf`).
pub(crate) fn product_num(factors: &[f64], precision: Option<usize>) -> String {
    let p: f64 = factors.iter().product();
    let fmt = |x: f64| match precision {
        Some(d) => format!("{x:.d$e}"),
        None => format!("{x:e}"),
    };
    let exact_zero = factors.contains(&0.0);
    if p.is_finite() && (exact_zero || p.abs() >= f64::MIN_POSITIVE) {
        return match precision {
            Some(_) => fmt(p),
            None => num(p),
        };
    }
    // m · 10^e, with m kept in [1, 10).
    let (mut m, mut e) = (1.0f64, 0i64);
    for &x in factors {
        let (mx, ex) = decimal(x);
        m *= mx;
        e += ex;
        let (mm, em) = decimal(m);
        m = mm;
        e += em;
    }
    let digits = fmt(m);
    let (mant, exp) = decimal_parts(&digits);
    format!("{mant}e{}", exp + e)
}

/// `x = m · 10^e` with `1 ≤ |m| < 10` (m = 0 for zero), from Rust's `{:e}` digits.
fn decimal(x: f64) -> (f64, i64) {
    let s = format!("{x:e}");
    let (m, e) = decimal_parts(&s);
    (m.parse().unwrap_or(0.0), e)
}

/// The mantissa text and exponent of a `{:e}` rendering.
fn decimal_parts(s: &str) -> (&str, i64) {
    match s.split_once('e') {
        Some((m, e)) => (m, e.parse().unwrap_or(0)),
        None => (s, 0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::AngleUnit;

    #[test]
    fn ordinary_lengths_are_plain_sums() {
        let v = [0.1, -0.7, 0.3, 0.2];
        let plain: f64 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert_eq!(length(v), plain);
        assert_eq!(split(v), (1.0, v));
        assert_eq!(length([0.0; 3]), 0.0);
    }

    #[test]
    fn huge_and_tiny_lengths_do_not_overflow() {
        // 3-4-5 at every scale: exact closed form.
        for scale in [1e300, 1e200, 1e-200, 1e-300, 1e-310] {
            let l = length([3.0 * scale, 4.0 * scale, 0.0]);
            assert!((l / (5.0 * scale) - 1.0).abs() < 1e-15, "{scale:e}: {l:e}");
        }
        // The plain sum of squares fails at these scales (the reason for this module).
        assert!((3e200f64 * 3e200 + 4e200 * 4e200).sqrt().is_infinite());
        assert_eq!((3e-200f64 * 3e-200 + 4e-200 * 4e-200).sqrt(), 0.0);
        // Only a length beyond f64 itself is infinite.
        assert!(length([f64::MAX, f64::MAX]).is_infinite());
    }

    #[test]
    fn degrees_are_reduced_exactly() {
        // int(1e200) mod 360 = 128 and int(1e300) mod 360 = 0 (Python's exact integers).
        let r = angle_to_rad(1e200, AngleUnit::Deg).unwrap();
        assert_eq!(r, 128f64.to_radians());
        assert_eq!(angle_to_rad(1e300, AngleUnit::Deg), Some(0.0));
        assert_eq!(
            angle_to_rad(-1e200, AngleUnit::Deg),
            Some((-128f64).to_radians())
        );
        // Ordinary angles are untouched.
        for a in [-90.0, 0.25, 359.5, -359.5] {
            assert_eq!(angle_to_rad(a, AngleUnit::Deg), Some(f64::to_radians(a)));
        }
    }

    #[test]
    fn radians_beyond_the_limit_are_refused() {
        assert_eq!(angle_to_rad(1e15, AngleUnit::Rad), Some(1e15));
        assert_eq!(angle_to_rad(-1e15, AngleUnit::Rad), Some(-1e15));
        assert_eq!(angle_to_rad(1.0000000000000002e15, AngleUnit::Rad), None);
        assert_eq!(angle_to_rad(-1e300, AngleUnit::Rad), None);
    }

    #[test]
    fn products_beyond_f64_keep_their_digits() {
        assert_eq!(product_num(&[1.01, 1.0], None), "1.01");
        assert_eq!(product_num(&[1.0, 1e200], None), "1e200");
        assert_eq!(product_num(&[2.0, 1e308], None), "2e308");
        assert_eq!(product_num(&[-1.5, 1e200, 1e200], None), "-1.5e400");
        assert_eq!(product_num(&[1.5, 1e-200, 1e-200], None), "1.5e-400");
        assert_eq!(product_num(&[3.0, 1e200, 1e200], Some(3)), "3.000e400");
        assert_eq!(product_num(&[9.9996, 1e300, 1e300], Some(3)), "1.000e601");
        assert_eq!(product_num(&[0.1418, 1.0], Some(3)), "1.418e-1");
        assert_eq!(product_num(&[0.0, 1e300], None), "0");
        // A subnormal product loses digits: it too goes the decimal way.
        assert_eq!(product_num(&[1.25, 1e-310], None), "1.25e-310");
        // An underflow to zero is not zero.
        assert_eq!(product_num(&[-1.0, 1e-200, 1e-200], None), "-1e-400");
    }
}
