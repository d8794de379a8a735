//! `Frame Time` ↔ an exact rate.
//!
//! Writers round the frame time (`0.0333333`, `.0083333`, `0.0416667`), so `1 / frame time` is
//! never the rate the motion was sampled at. `rate_from_frame_time` recovers it: the nearest
//! of `STANDARD_RATES` when `1 / frame time` is within `RATE_TOLERANCE` (relative) of it,
//! else the decimal exactly as written (`0.0125` is 80 fps, `0.011` is 1000/11 fps).
//! `frame_time_text` writes a rate back: the exact decimal when `1 / rate` has one of at most
//! `MAX_EXACT_DECIMALS` decimals (`0.01`, `0.008`, `0.04`), else 9 significant digits
//! (`0.0333333333`), which read back to the same rate.
//!
//! (Its example is a unit test: `module_example`.)

use inbetween::clock::Fps;
use inbetween::error::{InputResult, shorten};

/// The rates a rounded frame time snaps to, as `(num, den)`: the integer rates of film, video,
/// games and motion capture, and the NTSC `N·1000/1001` ratios of 24, 30, 48, 60, 120 and 240.
pub(crate) const STANDARD_RATES: [(u64, u64); 18] = [
    (12, 1),
    (15, 1),
    (24, 1),
    (25, 1),
    (30, 1),
    (48, 1),
    (50, 1),
    (60, 1),
    (90, 1),
    (100, 1),
    (120, 1),
    (240, 1),
    (24000, 1001),
    (30000, 1001),
    (48000, 1001),
    (60000, 1001),
    (120000, 1001),
    (240000, 1001),
];

/// How close `1 / frame time` must be to a standard rate, relative, to be taken as it: 1e-4
/// (a frame time rounded to 6 significant digits is within 1e-6; neighbouring standard rates,
/// 30 and 30000/1001, are 1e-3 apart).
pub(crate) const RATE_TOLERANCE: f64 = 1e-4;

/// The most decimals of a frame time [`frame_time_text`] writes exactly (`0.0125`); a rate
/// whose frame time needs more (or does not terminate) gets 9 significant digits.
pub(crate) const MAX_EXACT_DECIMALS: u32 = 12;

/// The standard rate within [`RATE_TOLERANCE`] (relative) of `approx` frames per second, if
/// any: the rule for a rate a writer rounded (a BVH `Frame Time`, a USD `timeCodesPerSecond`
/// such as Blender's 30.000030398399637 for a scene at 30/0.999999).
pub(crate) fn nearest_standard(approx: f64) -> Option<Fps> {
    let (n, d, rel) = STANDARD_RATES
        .iter()
        .map(|&(n, d)| {
            let r = n as f64 / d as f64;
            (n, d, (approx - r).abs() / r)
        })
        .min_by(|a, b| a.2.total_cmp(&b.2))?;
    (rel <= RATE_TOLERANCE).then(|| Fps::new(n, d).expect("a standard rate"))
}

/// The exact rate of a `Frame Time` value as written (seconds per frame): a standard rate
/// when within [`RATE_TOLERANCE`], else `1 / frame time` with the frame time read as the
/// exact decimal written. Accepts what files write: `0.0333333`, `.0083333`, `8.3333e-3`, an
/// optional `+`. Errors (unlocated; the parser adds the line): not a number, not finite, zero
/// or negative, or a rate outside what [`Fps`] accepts.
pub(crate) fn rate_from_frame_time(text: &str) -> InputResult<Fps> {
    let t = text.trim();
    let x: f64 = t.parse().map_err(|_| {
        input_err!(
            "expected a frame time in seconds such as 0.0333333, found \"{}\"",
            shorten(t)
        )
    })?;
    if !x.is_finite() {
        return Err(input_err!(
            "expected a finite frame time, found \"{}\"",
            shorten(t)
        ));
    }
    if x <= 0.0 {
        return Err(input_err!(
            "expected a positive frame time, found {}",
            shorten(t)
        ));
    }
    if let Some(fps) = nearest_standard(1.0 / x) {
        return Ok(fps);
    }
    let (sig, pow10) = exact_decimal(t).ok_or_else(|| {
        input_err!(
            "expected a frame time in seconds such as 0.0333333, found \"{}\"",
            shorten(t)
        )
    })?;
    // rate = 1 / (sig · 10^pow10) = 10^-pow10 / sig.
    let range = || {
        input_err!(
            "expected a frame time between 1e-7 and 1e6 seconds, found {}",
            shorten(t)
        )
    };
    let (num, den) = if pow10 <= 0 {
        (10u128.checked_pow((-pow10) as u32).ok_or_else(range)?, sig)
    } else {
        (
            1,
            sig.checked_mul(10u128.checked_pow(pow10 as u32).ok_or_else(range)?)
                .ok_or_else(range)?,
        )
    };
    let g = gcd(num, den);
    let (num, den) = (num / g, den / g);
    match (u64::try_from(num), u64::try_from(den)) {
        (Ok(n), Ok(d)) => Fps::new(n, d).map_err(|_| range()),
        _ => Err(range()),
    }
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// The decimal `text` (already known to parse as a positive finite float) as `sig · 10^pow10`
/// with `sig` an integer of at most 19 significant digits: digits beyond the 19th are dropped
/// (a change below 1e-18 relative). `None` for spellings that are not plain decimals
/// (`inf` is excluded by the caller; hexadecimal is not a float in Rust).
fn exact_decimal(text: &str) -> Option<(u128, i64)> {
    let s = text.strip_prefix('+').unwrap_or(text);
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(i) => (&s[..i], s[i + 1..].parse::<i64>().ok()?),
        None => (s, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if !int.bytes().chain(frac.bytes()).all(|b| b.is_ascii_digit()) {
        return None;
    }
    let all = format!("{int}{frac}");
    let significant = all.trim_start_matches('0');
    let digits = significant.trim_end_matches('0');
    if digits.is_empty() {
        return None;
    }
    let trailing = significant.len() - digits.len();
    // value = digits · 10^(exponent − frac.len() + trailing); keep the first 19 digits.
    let kept = &digits[..digits.len().min(19)];
    let dropped = digits.len() - kept.len();
    let pow10 = exponent
        .checked_sub(frac.len() as i64)?
        .checked_add((trailing + dropped) as i64)?;
    Some((kept.parse().ok()?, pow10))
}

/// The `Frame Time` to write for `fps`: `1 / fps` as its exact decimal when that has at most
/// [`MAX_EXACT_DECIMALS`] decimals (`0.01`, `0.008`, `0.0125`, `2`), else rounded to 9
/// significant digits (`0.0333333333`, `0.00833333333`, `0.0333666667`) — enough for
/// [`rate_from_frame_time`] to recover any standard rate.
pub(crate) fn frame_time_text(fps: Fps) -> String {
    let (num, den) = (fps.num() as u128, fps.den() as u128);
    // den/num terminates iff num = 2^a·5^b; it then has max(a, b) decimals.
    let (mut rest, mut twos, mut fives) = (num, 0u32, 0u32);
    while rest % 2 == 0 {
        rest /= 2;
        twos += 1;
    }
    while rest % 5 == 0 {
        rest /= 5;
        fives += 1;
    }
    let decimals = twos.max(fives);
    if rest == 1 && decimals <= MAX_EXACT_DECIMALS {
        let scaled = den * 10u128.pow(decimals) / num;
        let int = scaled / 10u128.pow(decimals);
        let frac = scaled % 10u128.pow(decimals);
        return if decimals == 0 {
            int.to_string()
        } else {
            format!("{int}.{frac:0width$}", width = decimals as usize)
        };
    }
    // 9 significant digits, in plain notation for every frame time Fps allows (1e-7 to 1e6 s).
    let t = den as f64 / num as f64;
    let magnitude = t.log10().floor() as i32;
    let decimals = (8 - magnitude).max(0) as usize;
    let s = format!("{t:.decimals$}");
    // Rounding can carry into a new digit (9.999999999 → 10.00000000): one decimal too many,
    // harmless; trailing zeros of a rounded value are kept (they are significant digits).
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rate(text: &str) -> (u64, u64) {
        let f = rate_from_frame_time(text).unwrap();
        (f.num(), f.den())
    }

    #[test]
    fn rounded_frame_times_recover_standard_rates() {
        let table: [(&str, (u64, u64)); 14] = [
            ("0.0333333", (30, 1)),
            ("0.033333", (30, 1)),
            (".033333", (30, 1)),
            ("0.0416667", (24, 1)),
            ("0.008333", (120, 1)),
            (".0083333", (120, 1)),
            ("0.0166667", (60, 1)),
            ("0.04", (25, 1)),
            ("0.0333667", (30000, 1001)),
            ("0.0417083", (24000, 1001)),
            ("0.0166833", (60000, 1001)),
            ("0.0111111", (90, 1)),
            ("0.00416667", (240, 1)),
            ("8.33333e-3", (120, 1)),
        ];
        for (text, want) in table {
            assert_eq!(rate(text), want, "{text}");
        }
    }

    #[test]
    fn other_frame_times_are_the_decimal_as_written() {
        assert_eq!(rate("0.0125"), (80, 1));
        assert_eq!(rate("0.011"), (1000, 11));
        assert_eq!(rate("0.0142857"), (10_000_000, 142_857));
        assert_eq!(rate("2"), (1, 2));
        assert_eq!(rate("+0.5"), (2, 1));
        assert_eq!(rate("1.25e-2"), (80, 1));
        assert_eq!(rate("000.01250"), (80, 1));
        // 1e-4 relative is the edge: 30·(1 + 2e-4) is not 30.
        assert_eq!(rate("0.0333267"), (10_000_000, 333_267));
    }

    #[test]
    fn bad_frame_times_are_errors() {
        let err = |t: &str| rate_from_frame_time(t).unwrap_err().to_string();
        assert_eq!(
            err("abc"),
            "expected a frame time in seconds such as 0.0333333, found \"abc\""
        );
        assert_eq!(err("0"), "expected a positive frame time, found 0");
        assert_eq!(
            err("-0.0333333"),
            "expected a positive frame time, found -0.0333333"
        );
        assert_eq!(err("nan"), "expected a finite frame time, found \"nan\"");
        assert_eq!(err("inf"), "expected a finite frame time, found \"inf\"");
        assert_eq!(
            err("1e-9"),
            "expected a frame time between 1e-7 and 1e6 seconds, found 1e-9"
        );
        assert_eq!(
            err("1e300"),
            "expected a frame time between 1e-7 and 1e6 seconds, found 1e300"
        );
    }

    #[test]
    fn frame_time_text_is_exact_or_nine_digits() {
        let text = |n: u64, d: u64| frame_time_text(Fps::new(n, d).unwrap());
        assert_eq!(text(100, 1), "0.01");
        assert_eq!(text(125, 1), "0.008");
        assert_eq!(text(25, 1), "0.04");
        assert_eq!(text(80, 1), "0.0125");
        assert_eq!(text(1000, 11), "0.011");
        assert_eq!(text(1, 2), "2");
        assert_eq!(text(30, 1), "0.0333333333");
        assert_eq!(text(120, 1), "0.00833333333");
        assert_eq!(text(24, 1), "0.0416666667");
        assert_eq!(text(30000, 1001), "0.0333666667");
        assert_eq!(text(3, 1), "0.333333333");
        assert_eq!(text(1, 3), "3");
        assert_eq!(text(2, 3), "1.5");
        assert_eq!(text(3, 10), "3.33333333");
    }

    #[test]
    fn every_standard_rate_survives_writing_its_frame_time() {
        for (n, d) in STANDARD_RATES {
            let fps = Fps::new(n, d).unwrap();
            assert_eq!(rate_from_frame_time(&frame_time_text(fps)).unwrap(), fps);
            // And the 7-significant-digit rounding writers use.
            let six = format!("{:.6e}", d as f64 / n as f64);
            assert_eq!(rate_from_frame_time(&six).unwrap(), fps, "{six}");
        }
    }
}

#[cfg(test)]
mod examples {
    #[test]
    fn module_example() -> Result<(), inbetween::InputError> {
        use crate::bvh::rate::{frame_time_text, rate_from_frame_time};

        let fps = rate_from_frame_time("0.0333667")?;
        assert_eq!((fps.num(), fps.den()), (30000, 1001));
        assert_eq!(frame_time_text(fps), "0.0333666667");
        assert_eq!(rate_from_frame_time(&frame_time_text(fps))?, fps);
        let fps = rate_from_frame_time("0.011")?;
        assert_eq!((fps.num(), fps.den()), (1000, 11));
        assert_eq!(frame_time_text(fps), "0.011");
        Ok(())
    }
}
