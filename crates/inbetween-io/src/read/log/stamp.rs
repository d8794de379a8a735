//! Time stamps of timestamped logs: a unit (seconds to nanoseconds) and whether key times count
//! from the first stamp. Stamps are read into whole nanoseconds (`i128`), so that the
//! difference of two 19-digit nanosecond stamps (1.4e18 ns, beyond f64's 2^53) is exact before
//! it becomes seconds.

use inbetween::error::{InputResult, shorten};

/// The unit of a log's time column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeUnit {
    /// Seconds (`s`), decimals allowed (TUM: `1305031102.175304`).
    Seconds,
    /// Milliseconds (`ms`), decimals allowed.
    Millis,
    /// Microseconds (`us`), whole numbers only.
    Micros,
    /// Nanoseconds (`ns`), whole numbers only (EuRoC, `rostopic echo -p`).
    Nanos,
}

impl TimeUnit {
    /// `s`, `ms`, `us` (or `µs`) or `ns`.
    pub fn parse(s: &str) -> InputResult<TimeUnit> {
        match s {
            "s" => Ok(TimeUnit::Seconds),
            "ms" => Ok(TimeUnit::Millis),
            "us" | "µs" => Ok(TimeUnit::Micros),
            "ns" => Ok(TimeUnit::Nanos),
            _ => Err(input_err!(
                "expected a time unit s, ms, us or ns, found \"{}\"",
                shorten(s)
            )),
        }
    }

    /// The number of decimal digits between this unit and a nanosecond (9 for seconds).
    fn digits(self) -> u32 {
        match self {
            TimeUnit::Seconds => 9,
            TimeUnit::Millis => 6,
            TimeUnit::Micros => 3,
            TimeUnit::Nanos => 0,
        }
    }

    /// Whether stamps in this unit must be whole numbers.
    fn whole(self) -> bool {
        matches!(self, TimeUnit::Micros | TimeUnit::Nanos)
    }

    /// The unit's name as written in messages: `seconds`, …, `nanoseconds`.
    fn name(self) -> &'static str {
        match self {
            TimeUnit::Seconds => "seconds",
            TimeUnit::Millis => "milliseconds",
            TimeUnit::Micros => "microseconds",
            TimeUnit::Nanos => "nanoseconds",
        }
    }
}

impl std::fmt::Display for TimeUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TimeUnit::Seconds => "s",
            TimeUnit::Millis => "ms",
            TimeUnit::Micros => "us",
            TimeUnit::Nanos => "ns",
        })
    }
}

/// Whether a log's key times are its stamps as written or counted from its first stamp.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TimeOrigin {
    /// The first stamp is t = 0 s; the others are their exact difference from it.
    #[default]
    Relative,
    /// The stamps themselves, in seconds (a 1.4e18 ns stamp keeps about 0.24 µs in f64).
    Absolute,
}

impl TimeOrigin {
    /// `relative` or `absolute`.
    pub fn parse(s: &str) -> InputResult<TimeOrigin> {
        match s {
            "relative" => Ok(TimeOrigin::Relative),
            "absolute" => Ok(TimeOrigin::Absolute),
            _ => Err(input_err!(
                "expected relative or absolute, found \"{}\"",
                shorten(s)
            )),
        }
    }
}

impl std::fmt::Display for TimeOrigin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TimeOrigin::Relative => "relative",
            TimeOrigin::Absolute => "absolute",
        })
    }
}

/// The largest magnitude of a stamp, in nanoseconds (about 3e12 years): the sums and products
/// below stay far inside `i128`, and seconds far inside f64's range.
const MAX_NANOS: i128 = 10i128.pow(29);

/// A stamp as written, in whole nanoseconds; the message (without location) when it is not a
/// number of `unit`. A plain decimal (`-12.5`, `1403636579758555392`) is read exactly, digits
/// beyond a nanosecond rounded half away from zero; seconds and milliseconds in exponent form
/// (`1.3e9`) go through f64. Microseconds and nanoseconds must be whole numbers.
pub(crate) fn parse(raw: &str, unit: TimeUnit) -> Result<i128, String> {
    let whole_expected = || {
        format!(
            "expected a whole number of {}, found \"{}\"",
            unit.name(),
            shorten(raw)
        )
    };
    let (negative, digits) = match raw.as_bytes().first() {
        Some(b'-') => (true, &raw[1..]),
        Some(b'+') => (false, &raw[1..]),
        _ => (false, raw),
    };
    let (int, frac) = digits.split_once('.').unwrap_or((digits, ""));
    let plain = !(int.is_empty() && frac.is_empty())
        && int.bytes().all(|b| b.is_ascii_digit())
        && frac.bytes().all(|b| b.is_ascii_digit());
    if !plain {
        if unit.whole() {
            return Err(whole_expected());
        }
        return match raw.parse::<f64>() {
            Ok(x) if x.is_finite() => {
                let ns = x * 10f64.powi(unit.digits() as i32);
                if ns.abs() > MAX_NANOS as f64 {
                    Err(out_of_range(raw))
                } else {
                    Ok(ns.round() as i128)
                }
            }
            _ => Err(format!(
                "expected a time stamp in {}, found \"{}\"",
                unit.name(),
                shorten(raw)
            )),
        };
    }
    let int = int.trim_start_matches('0');
    if int.len() > 30 {
        return Err(out_of_range(raw));
    }
    let scale = 10i128.pow(unit.digits());
    let mut ns = if int.is_empty() {
        0
    } else {
        int.parse::<i128>().map_err(|_| out_of_range(raw))? * scale
    };
    let kept = frac.len().min(unit.digits() as usize);
    let (head, tail) = frac.split_at(kept);
    if unit.whole() && frac.bytes().any(|b| b != b'0') {
        return Err(whole_expected());
    }
    if !head.is_empty() {
        let padding = 10i128.pow(unit.digits() - kept as u32);
        ns += head.parse::<i128>().map_err(|_| out_of_range(raw))? * padding;
    }
    if tail.as_bytes().first().is_some_and(|&b| b >= b'5') {
        ns += 1;
    }
    if ns > MAX_NANOS {
        return Err(out_of_range(raw));
    }
    Ok(if negative { -ns } else { ns })
}

fn out_of_range(raw: &str) -> String {
    format!(
        "expected a time stamp within ±1e29 ns, found \"{}\"",
        shorten(raw)
    )
}

/// A stamp in seconds: its difference from `first` (exact in nanoseconds, rounded once to
/// f64) for relative times, else the stamp itself (beyond 2^53 ns, whole seconds and the
/// fraction added in f64: one rounding more).
pub(crate) fn seconds(ns: i128, first: i128, origin: TimeOrigin) -> f64 {
    const NS: i128 = 1_000_000_000;
    match origin {
        TimeOrigin::Relative => (ns - first) as f64 / 1e9,
        // Exact in f64 below 2^53 ns, so one rounding in the division.
        TimeOrigin::Absolute if ns.abs() < 1 << 53 => ns as f64 / 1e9,
        TimeOrigin::Absolute => ns.div_euclid(NS) as f64 + ns.rem_euclid(NS) as f64 / 1e9,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamps_are_read_exactly_in_nanoseconds() {
        let ns = TimeUnit::Nanos;
        assert_eq!(
            parse("1403636579758555392", ns),
            Ok(1_403_636_579_758_555_392)
        );
        assert_eq!(parse("18446744073709551615", ns), Ok(u64::MAX as i128));
        assert_eq!(parse("-5", ns), Ok(-5));
        assert_eq!(parse("7.000", ns), Ok(7));
        assert_eq!(
            parse("1403636579758555.5", TimeUnit::Micros).unwrap_err(),
            "expected a whole number of microseconds, found \"1403636579758555.5\""
        );
        assert_eq!(
            parse("1e9", ns).unwrap_err(),
            "expected a whole number of nanoseconds, found \"1e9\""
        );
        assert_eq!(
            parse("1305031102.175304", TimeUnit::Seconds),
            Ok(1_305_031_102_175_304_000)
        );
        assert_eq!(parse(".5", TimeUnit::Seconds), Ok(500_000_000));
        assert_eq!(parse("0.0000000015", TimeUnit::Seconds), Ok(2));
        assert_eq!(parse("1.5", TimeUnit::Millis), Ok(1_500_000));
        assert_eq!(parse("1.5e3", TimeUnit::Seconds), Ok(1_500_000_000_000));
        assert!(parse("abc", TimeUnit::Seconds).is_err());
        assert!(parse("", TimeUnit::Seconds).is_err());
        assert!(parse(".", TimeUnit::Seconds).is_err());
        assert!(parse("nan", TimeUnit::Seconds).is_err());
        assert!(parse(&"9".repeat(40), ns).is_err());
        // Two stamps 1 ns apart, 1.4e18 ns from the epoch: f64 alone cannot tell them apart.
        let (a, b) = (1_403_636_579_758_555_392i128, 1_403_636_579_758_555_393i128);
        assert_eq!(a as f64, b as f64);
        assert_eq!(seconds(b, a, TimeOrigin::Relative), 1e-9);
        assert_eq!(seconds(a, a, TimeOrigin::Absolute), 1_403_636_579.758_555_4);
        assert_eq!(seconds(-1, 0, TimeOrigin::Absolute), -1e-9);
    }
}
