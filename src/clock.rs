//! Exact rational frame rates and the frame grid.
//!
//! A rate is `num/den` frames per second in lowest terms. The NTSC decimals `23.976`, `29.97`,
//! `59.94` (and `47.952`, `119.88`) mean the exact `N·1000/1001` ratios; any other decimal is
//! taken exactly as written (`12.5` = 25/2). Frame `k` is at time `k·den/num`, computed from the
//! integer index (one rounding), never by accumulating `t += dt`.

use crate::error::InputResult;
use crate::input_err;
use std::fmt;

/// Largest accepted rate, frames per second.
pub const MAX_FPS: f64 = 1e7;

/// Tolerance in seconds for a frame to count as inside a track or on a key (SPEC §3).
pub const TIME_TOL: f64 = 1e-9;

/// A positive rational frame rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fps {
    num: u64,
    den: u64,
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

impl Fps {
    /// `num/den` frames per second; both positive.
    pub fn new(num: u64, den: u64) -> InputResult<Fps> {
        if num == 0 || den == 0 {
            return Err(if den == 1 {
                input_err!("expected a positive frame rate, found {num}")
            } else {
                input_err!("expected a positive frame rate, found {num}/{den}")
            });
        }
        let g = gcd(num, den);
        let fps = Fps {
            num: num / g,
            den: den / g,
        };
        if fps.as_f64() > MAX_FPS || fps.as_f64() < 1e-6 {
            return Err(input_err!(
                "expected a frame rate between 1e-6 and {MAX_FPS:e} frames per second, found {fps}"
            ));
        }
        Ok(fps)
    }

    /// Parses `24`, `29.97`, `30000/1001`, `12.5`.
    pub fn parse(s: &str) -> InputResult<Fps> {
        let s = s.trim();
        let bad = || {
            input_err!(
                "expected a positive frame rate such as 24, 29.97 or 30000/1001, found \"{s}\""
            )
        };
        if let Some((n, d)) = s.split_once('/') {
            let n: u64 = n.trim().parse().map_err(|_| bad())?;
            let d: u64 = d.trim().parse().map_err(|_| bad())?;
            return Fps::new(n, d).map_err(|e| e.at(format!("\"{s}\"")));
        }
        match s {
            "23.976" => return Fps::new(24000, 1001),
            "29.97" => return Fps::new(30000, 1001),
            "47.952" => return Fps::new(48000, 1001),
            "59.94" => return Fps::new(60000, 1001),
            "119.88" => return Fps::new(120000, 1001),
            _ => {}
        }
        let (int, frac) = s.split_once('.').unwrap_or((s, ""));
        let digits_ok = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
        if int.is_empty() && frac.is_empty() || !digits_ok(int) || !digits_ok(frac) {
            return Err(bad());
        }
        if frac.len() > 9 || int.len() > 12 {
            return Err(bad());
        }
        let den = 10u64.pow(frac.len() as u32);
        let num: u64 = format!("{int}{frac}").parse().map_err(|_| bad())?;
        Fps::new(num, den)
    }

    /// A rate from a JSON number (integers and the decimals [`Fps::parse`] accepts).
    pub fn from_f64(x: f64) -> InputResult<Fps> {
        if !x.is_finite() || x <= 0.0 {
            return Err(input_err!("expected a positive frame rate, found {x}"));
        }
        Fps::parse(&format!("{x}"))
    }

    pub fn num(&self) -> u64 {
        self.num
    }

    pub fn den(&self) -> u64 {
        self.den
    }

    pub fn as_f64(&self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// Time of frame `k` in seconds: `k·den/num` with a single rounding while `|k·den| < 2⁵³`.
    #[inline]
    pub fn time_of(&self, k: i64) -> f64 {
        match k.checked_mul(self.den as i64) {
            Some(kd) => kd as f64 / self.num as f64,
            None => k as f64 * self.den as f64 / self.num as f64,
        }
    }

    /// Seconds from a (possibly fractional) frame number.
    pub fn frame_to_time(&self, frame: f64) -> f64 {
        frame * self.den as f64 / self.num as f64
    }

    /// Largest frame number the grid supports: frame times stay exact below 2⁵³.
    pub const MAX_FRAME: i64 = 1 << 53;

    /// Whether time `t` (seconds) is within the frame numbers the grid supports.
    pub fn in_range(&self, t: f64) -> bool {
        (t * self.as_f64()).abs() < (Self::MAX_FRAME - 2) as f64
    }

    /// The smallest `k` with `k/fps ≥ t − 1e-9`. `t` must be [`Fps::in_range`].
    pub fn first_frame_from(&self, t: f64) -> i64 {
        let mut k = ((t - TIME_TOL) * self.as_f64()).ceil() as i64;
        while self.time_of(k - 1) >= t - TIME_TOL {
            k -= 1;
        }
        while self.time_of(k) < t - TIME_TOL {
            k += 1;
        }
        k
    }

    /// The largest `k` with `k/fps ≤ t + 1e-9`. `t` must be [`Fps::in_range`].
    pub fn last_frame_until(&self, t: f64) -> i64 {
        let mut k = ((t + TIME_TOL) * self.as_f64()).floor() as i64;
        while self.time_of(k + 1) <= t + TIME_TOL {
            k += 1;
        }
        while self.time_of(k) > t + TIME_TOL {
            k -= 1;
        }
        k
    }

    /// The frames `k` with `t0 − 1e-9 ≤ k/fps ≤ t1 + 1e-9`, as an inclusive range (empty when
    /// `first > last`).
    pub fn frames_between(&self, t0: f64, t1: f64) -> (i64, i64) {
        (self.first_frame_from(t0), self.last_frame_until(t1))
    }
}

impl fmt::Display for Fps {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ntsc_rates_are_exact_ratios() {
        assert_eq!(Fps::parse("29.97").unwrap(), Fps::new(30000, 1001).unwrap());
        assert_eq!(
            Fps::parse("23.976").unwrap(),
            Fps::new(24000, 1001).unwrap()
        );
        assert_eq!(Fps::parse("59.94").unwrap(), Fps::new(60000, 1001).unwrap());
        assert_eq!(Fps::parse("30000/1001").unwrap().to_string(), "30000/1001");
        assert_eq!(Fps::parse("60/2").unwrap().to_string(), "30");
        assert_eq!(Fps::parse("12.5").unwrap(), Fps::new(25, 2).unwrap());
        assert_eq!(
            Fps::from_f64(29.97).unwrap(),
            Fps::new(30000, 1001).unwrap()
        );
        assert_eq!(Fps::from_f64(24.0).unwrap(), Fps::new(24, 1).unwrap());
    }

    #[test]
    fn bad_rates() {
        for s in [
            "0",
            "-24",
            "abc",
            "",
            "1/0",
            "0/5",
            "1e3",
            ".",
            "1e400",
            "99999999999",
        ] {
            assert!(Fps::parse(s).is_err(), "{s}");
        }
    }

    #[test]
    fn frame_times_from_the_index() {
        let fps = Fps::parse("29.97").unwrap();
        assert_eq!(fps.time_of(30000), 1001.0);
        assert_eq!(fps.time_of(1), 1001.0 / 30000.0);
    }

    #[test]
    fn frames_between_with_tolerance() {
        let fps = Fps::parse("30").unwrap();
        assert_eq!(fps.frames_between(0.0, 1.0), (0, 30));
        assert_eq!(fps.frames_between(0.1, 0.2), (3, 6));
        assert_eq!(fps.frames_between(0.1 + 5e-10, 0.2 - 5e-10), (3, 6));
        assert_eq!(fps.frames_between(0.101, 0.132), (4, 3));
        assert_eq!(fps.frames_between(-1.0, -0.5), (-30, -15));
    }
}
