//! Exact rational frame rates and the frame grid: which frames a span has, which piece of a
//! curve each frame belongs to, and when a frame is a key.
//!
//! A rate is `num/den` frames per second in lowest terms. The NTSC decimals `23.976`, `29.97`,
//! `59.94` (and `47.952`, `119.88`) mean the exact `N·1000/1001` ratios; any other decimal is
//! taken exactly as written (`12.5` = 25/2). Frame `k` is at time `k·den/num`, computed from the
//! integer index (one rounding), never by accumulating `t += dt`.
//!
//! The frame-clock rule (docs/spec.md §3), in one place (`Fps::pieces`): a track's frames are
//! those with `t_1 − 1e-9 ≤ k/fps ≤ t_n + 1e-9`. Piece `s` (between breaks `t_s` and `t_{s+1}`:
//! keys, or minaccel's grid points) takes the frames with `t_s − 1e-9 ≤ k/fps < t_{s+1} − 1e-9`,
//! except one nearer `t_s` (breaks less than 2e-9 s apart); the last piece runs to
//! `t_n + 1e-9`. A frame within 1e-9 s of its piece's start, or of the last break, *is* that
//! break (it snaps).
//!
//! ```
//! use inbetween::Fps;
//!
//! let fps: Fps = "29.97".parse()?;
//! assert_eq!((fps.num(), fps.den()), (30000, 1001));
//! assert_eq!(fps.time_of(30000), 1001.0);
//! // Keys at 0 and 0.25 s at 30 fps: frames 0..=7; 0.1 s is frame 3, 0.11 s no frame.
//! let fps = Fps::new(30, 1)?;
//! assert_eq!(fps.frames_between(0.0, 0.25), (0, 7));
//! assert_eq!((fps.frame_at(0.1), fps.frame_at(0.11)), (Some(3), None));
//! # Ok::<(), inbetween::InputError>(())
//! ```

use crate::error::InputResult;
use crate::error::input_err;
use std::fmt;

/// Largest accepted rate, frames per second.
pub(crate) const MAX_FPS: f64 = 1e7;

/// Tolerance in seconds for a frame to count as inside a track or on a key (docs/spec.md §3).
pub(crate) const TIME_TOL: f64 = 1e-9;

/// A positive rational frame rate, exact (`30000/1001`, not 29.97002997…).
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
    /// The rate used when neither the command line nor the document gives one: 30 fps.
    pub const DEFAULT: Fps = Fps { num: 30, den: 1 };

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

    /// Parses `24`, `29.97`, `30000/1001`, `12.5`, `1e7`, `2.5e1`.
    ///
    /// A decimal may have an exponent (`e`/`E`, optionally signed); it must denote an exact
    /// decimal of at most 9 decimals once trailing zeros are dropped: `1.2e-1` is 3/25,
    /// `1.5e-10` is refused. The NTSC decimals mean their /1001 ratios in every spelling
    /// (`29.97`, `29.970`, `2.997e1`); a ratio `N/D` is always exact. A value outside 1e-6 to
    /// 1e7 frames per second, in any spelling, is refused with the range message, which quotes
    /// the value as written.
    pub fn parse(s: &str) -> InputResult<Fps> {
        let s = s.trim();
        let bad = || {
            input_err!(
                "expected a positive frame rate such as 24, 29.97 or 30000/1001, found \"{s}\""
            )
        };
        let zero = || input_err!("expected a positive frame rate, found {s}");
        let range = || {
            input_err!(
                "expected a frame rate between 1e-6 and {MAX_FPS:e} frames per second, found {s}"
            )
        };
        if let Some((n, d)) = s.split_once('/') {
            let n: u64 = n.trim().parse().map_err(|_| bad())?;
            let d: u64 = d.trim().parse().map_err(|_| bad())?;
            if n == 0 || d == 0 {
                return Err(zero());
            }
            return Fps::new(n, d).map_err(|_| range());
        }
        // digits[.digits][e[+|-]digits], at least one digit before the exponent.
        let (mantissa, exponent) = match s.find(['e', 'E']) {
            Some(i) => (&s[..i], Some(&s[i + 1..])),
            None => (s, None),
        };
        let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        let digits_ok = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
        if int.is_empty() && frac.is_empty() || !digits_ok(int) || !digits_ok(frac) {
            return Err(bad());
        }
        let exponent: i64 = match exponent {
            None => 0,
            Some(e) => {
                let unsigned = e.strip_prefix(['+', '-']).unwrap_or(e);
                if unsigned.is_empty() || !digits_ok(unsigned) {
                    return Err(bad());
                }
                // Beyond ±10⁶ only the sign matters (the value is far out of range).
                let magnitude: i64 = unsigned
                    .trim_start_matches('0')
                    .parse::<i64>()
                    .map_or(1_000_000, |m| m.min(1_000_000));
                if e.starts_with('-') {
                    -magnitude
                } else {
                    magnitude
                }
            }
        };
        // value = significant · 10^power, significant without leading or trailing zeros.
        let all = format!("{int}{frac}");
        let significant = all.trim_start_matches('0').trim_end_matches('0');
        if significant.is_empty() {
            return Err(zero());
        }
        let trailing = all.trim_end_matches('0').len();
        let power = exponent - frac.len() as i64 + (all.len() - trailing) as i64;
        // 10^order ≤ value < 10^(order+1): out of 1e-6..1e7 whatever the digits.
        let order = significant.len() as i64 - 1 + power;
        if !(-6..=7).contains(&order) {
            return Err(range());
        }
        // At most 9 decimals (at most 17 significant digits here), so num/den fit a u64.
        if power < -9 {
            return Err(bad());
        }
        let sig: u64 = significant.parse().map_err(|_| bad())?;
        let (num, den) = if power >= 0 {
            (sig * 10u64.pow(power as u32), 1)
        } else {
            (sig, 10u64.pow((-power) as u32))
        };
        let fps = Fps::new(num, den).map_err(|_| range())?;
        // The NTSC decimals, however spelled (29.97, 29.970, 2.997e1), are the /1001 ratios.
        const NTSC: [(u64, u64, u64); 5] = [
            (2997, 125, 24000), // 23.976
            (2997, 100, 30000), // 29.97
            (5994, 125, 48000), // 47.952
            (2997, 50, 60000),  // 59.94
            (2997, 25, 120000), // 119.88
        ];
        match NTSC.iter().find(|&&(n, d, _)| (n, d) == (fps.num, fps.den)) {
            Some(&(_, _, ntsc)) => Fps::new(ntsc, 1001),
            None => Ok(fps),
        }
    }

    /// A rate from a JSON number (integers and the decimals [`Fps::parse`] accepts).
    pub fn from_f64(x: f64) -> InputResult<Fps> {
        if !x.is_finite() || x <= 0.0 {
            return Err(input_err!(
                "expected a positive frame rate, found {}",
                crate::error::num(x)
            ));
        }
        if !(1e-6..=MAX_FPS).contains(&x) {
            return Err(input_err!(
                "expected a frame rate between 1e-6 and {MAX_FPS:e} frames per second, found {}",
                crate::error::num(x)
            ));
        }
        // Rust's `{}` is the shortest decimal that reads back to `x`, without exponent.
        Fps::parse(&format!("{x}"))
    }

    /// Numerator of the rate in lowest terms.
    pub fn num(&self) -> u64 {
        self.num
    }

    /// Denominator of the rate in lowest terms.
    pub fn den(&self) -> u64 {
        self.den
    }

    /// The rate as a float (frames per second).
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

    /// Number of frames of the span `[t0, t1]` (see [`Fps::frames_between`]).
    pub fn frame_count(&self, t0: f64, t1: f64) -> u64 {
        let (a, b) = self.frames_between(t0, t1);
        (b - a + 1).max(0) as u64
    }

    /// The frames of each piece between consecutive `breaks` (strictly increasing, at least two,
    /// [`Fps::in_range`]), by the frame-clock rule of the module documentation. Only pieces with
    /// frames are listed, in order; together they are every frame of the span exactly once.
    pub(crate) fn pieces(self, breaks: &[f64]) -> Pieces<'_> {
        let n = breaks.len();
        let (first, last) = self.frames_between(breaks[0], breaks[n - 1]);
        Pieces {
            fps: self,
            breaks,
            s: 0,
            k: first,
            last,
        }
    }
}

/// How close, in frame periods, a key must be to a frame it misses for a warning (§3).
pub(crate) const NEAR_MISS: f64 = 1e-3;

impl Fps {
    /// The frame nearest time `t`.
    pub fn nearest_frame(&self, t: f64) -> i64 {
        let k = (t * self.as_f64()).round() as i64;
        // The rounding of t·fps can be off by one near a half: compare the neighbours' times.
        (k - 1..=k + 1)
            .min_by(|&a, &b| {
                (self.time_of(a) - t)
                    .abs()
                    .total_cmp(&(self.time_of(b) - t).abs())
            })
            .unwrap_or(k)
    }

    /// The frame whose time is `t` (within 1e-9 s, docs/spec.md §3), or `None` when `t` is
    /// between frames.
    pub fn frame_at(&self, t: f64) -> Option<i64> {
        let k = self.nearest_frame(t);
        ((self.time_of(k) - t).abs() <= TIME_TOL).then_some(k)
    }

    /// `t` moved onto the grid when it is within `eps` frame periods of a frame, else `t`.
    pub fn snap(&self, t: f64, eps: f64) -> f64 {
        let k = self.nearest_frame(t);
        let tk = self.time_of(k);
        if (tk - t).abs() <= eps / self.as_f64() {
            tk
        } else {
            t
        }
    }

    /// The frames a span `[t0, t1]` just misses: the frame before `t0` and the frame after `t1`
    /// when they are within `NEAR_MISS` frame periods of the key (and so not written, being more
    /// than 1e-9 s outside). Keys computed from a rounded frame time (`0.0333333` s) land there.
    pub fn near_misses(&self, t0: f64, t1: f64) -> (Option<i64>, Option<i64>) {
        let (first, last) = self.frames_between(t0, t1);
        let near = |k: i64, t: f64| (self.time_of(k) - t).abs() <= NEAR_MISS / self.as_f64();
        (
            Some(first - 1).filter(|&k| near(k, t0)),
            Some(last + 1).filter(|&k| near(k, t1)),
        )
    }
}

/// The frames `from..to` of piece `piece` (between breaks `piece` and `piece + 1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PieceFrames {
    /// The piece's index.
    pub(crate) piece: usize,
    /// Its first frame.
    pub(crate) from: i64,
    /// One past its last frame.
    pub(crate) to: i64,
    /// Frame `from` is within 1e-9 s of the piece's start: it is the break itself.
    pub(crate) snap_start: bool,
    /// Frame `to − 1` is within 1e-9 s of the last break (last piece only, and not the frame
    /// that already snapped to the start): it is the last break itself.
    pub(crate) snap_end: bool,
}

/// Iterator of [`PieceFrames`], from `Fps::pieces`.
#[derive(Debug, Clone)]
pub(crate) struct Pieces<'a> {
    fps: Fps,
    breaks: &'a [f64],
    s: usize,
    k: i64,
    last: i64,
}

impl Iterator for Pieces<'_> {
    type Item = PieceFrames;

    fn next(&mut self) -> Option<PieceFrames> {
        let (fps, times) = (self.fps, self.breaks);
        let n = times.len();
        while self.s + 1 < n {
            let s = self.s;
            self.s += 1;
            let (t0, t1) = (times[s], times[s + 1]);
            let end = if s == n - 2 {
                self.last + 1
            } else {
                // Frames from 1e-9 s before the next break belong to it, except one that is
                // nearer this break (breaks less than 2e-9 s apart).
                let mut e = fps.first_frame_from(t1).min(self.last + 1);
                while e <= self.last
                    && fps.time_of(e) < t1
                    && fps.time_of(e) - t0 < t1 - fps.time_of(e)
                {
                    e += 1;
                }
                e
            };
            if self.k < end {
                let from = self.k;
                self.k = end;
                let snap_start = (fps.time_of(from) - t0).abs() <= TIME_TOL;
                let snap_end = s == n - 2
                    && from + i64::from(snap_start) < end
                    && (fps.time_of(end - 1) - t1).abs() <= TIME_TOL;
                return Some(PieceFrames {
                    piece: s,
                    from,
                    to: end,
                    snap_start,
                    snap_end,
                });
            }
        }
        None
    }
}

impl std::str::FromStr for Fps {
    type Err = crate::InputError;

    /// Same as [`Fps::parse`].
    fn from_str(s: &str) -> InputResult<Fps> {
        Fps::parse(s)
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

    /// Keys at 0, 0.1 and 0.25 s at 30 fps: frames 0..=7, split 0..3 and 3..8; frame 3 is the key.
    #[test]
    fn pieces_split_the_frames_at_the_keys() {
        let fps = Fps::new(30, 1).unwrap();
        let pieces: Vec<_> = fps.pieces(&[0.0, 0.1, 0.25]).collect();
        assert_eq!(
            (pieces[0].from, pieces[0].to, pieces[1].from, pieces[1].to),
            (0, 3, 3, 8)
        );
        assert!(pieces[1].snap_start && !pieces[1].snap_end);
    }

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
            "1e",
            "e3",
            "1e+",
            "1e3.5",
            "1e-3e1",
            ".",
            "1e400",
            "99999999999",
            "1.5e-10",
            "0x10",
            "+24",
        ] {
            assert!(Fps::parse(s).is_err(), "{s}");
        }
    }

    #[test]
    fn exponent_notation_is_the_exact_decimal() {
        // Each pair denotes the same decimal; the ratio is worked out by hand.
        for (s, num, den) in [
            ("1e7", 10_000_000, 1),
            ("1E7", 10_000_000, 1),
            ("1e+7", 10_000_000, 1),
            ("10000000", 10_000_000, 1),
            ("2.5e1", 25, 1),
            ("1.2e-1", 3, 25),
            ("0.12", 3, 25),
            ("120e-3", 3, 25),
            ("1e-6", 1, 1_000_000),
            ("0.000001", 1, 1_000_000),
            ("2.4e01", 24, 1),
            ("1.0000000000", 1, 1),
            ("1.234e-6", 617, 500_000_000),
        ] {
            assert_eq!(Fps::parse(s).unwrap(), Fps::new(num, den).unwrap(), "{s}");
        }
        // The NTSC decimals in any spelling.
        for s in ["29.97", "29.970", "2.997e1", "2997e-2"] {
            assert_eq!(
                Fps::parse(s).unwrap(),
                Fps::new(30000, 1001).unwrap(),
                "{s}"
            );
        }
        assert_eq!(Fps::parse("2997/100").unwrap().to_string(), "2997/100");
    }

    #[test]
    fn out_of_range_in_every_spelling_gives_the_range_message() {
        let range = |v: &str| {
            format!("expected a frame rate between 1e-6 and 1e7 frames per second, found {v}")
        };
        for s in [
            "1e8",
            "1.5e7",
            "10000001",
            "1e400",
            "99999999999",
            "1e-7",
            "0.0000001",
        ] {
            assert_eq!(Fps::parse(s).unwrap_err().message(), range(s), "{s}");
        }
        assert_eq!(
            Fps::parse("20000002/2").unwrap_err().message(),
            range("20000002/2")
        );
        // Zero in any spelling, quoted once (`--fps 0/0` used to quote it twice).
        for s in ["0", "0.0", "0e5", "0/0", "0/5", "1/0"] {
            assert_eq!(
                Fps::parse(s).unwrap_err().message(),
                format!("expected a positive frame rate, found {s}"),
                "{s}"
            );
        }
        assert_eq!(
            Fps::from_f64(1e-300).unwrap_err().message(),
            range("1e-300")
        );
        assert_eq!(Fps::from_f64(1e20).unwrap_err().message(), range("1e20"));
        assert_eq!(
            Fps::from_f64(1e7).unwrap(),
            Fps::new(10_000_000, 1).unwrap()
        );
        assert_eq!(Fps::from_f64(0.12).unwrap(), Fps::new(3, 25).unwrap());
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

    #[test]
    fn pieces_cover_every_frame_once_and_snap_to_breaks() {
        let fps = Fps::new(30, 1).unwrap();
        // Breaks on and off the grid; one 1e-10 s before frame 9.
        let breaks = [0.0, 0.1, 0.123, 0.3 - 1e-10, 0.5];
        let p: Vec<_> = fps.pieces(&breaks).collect();
        let mut k = 0;
        for q in &p {
            assert_eq!(q.from, k);
            k = q.to;
        }
        assert_eq!(k, 16);
        assert_eq!(
            p.iter()
                .map(|q| (q.piece, q.from, q.to))
                .collect::<Vec<_>>(),
            [(0, 0, 3), (1, 3, 4), (2, 4, 9), (3, 9, 16)]
        );
        assert!(p[0].snap_start && p[1].snap_start && !p[2].snap_start && p[3].snap_start);
        assert!(p[3].snap_end && !p[0].snap_end);
        // A track shorter than a frame: no frames.
        assert_eq!(fps.pieces(&[0.101, 0.132]).count(), 0);
    }

    #[test]
    fn near_misses_and_snapping() {
        let fps = Fps::new(30, 1).unwrap();
        // Motion capture's rounded frame time: 194 × 0.0333333 = 6.4666602 s, 6.5e-6 s (2e-4
        // frame periods) before frame 194.
        let t1 = 194.0 * 0.0333333;
        assert_eq!(fps.frames_between(0.0, t1), (0, 193));
        assert_eq!(fps.near_misses(0.0, t1), (None, Some(194)));
        assert_eq!(fps.near_misses(0.0, 6.4), (None, None));
        // A first key 1e-6 s after frame 3.
        assert_eq!(fps.near_misses(0.1 + 1e-6, 1.0), (Some(3), None));
        assert_eq!(fps.snap(t1, 1e-3), fps.time_of(194));
        assert_eq!(fps.snap(t1, 1e-4), t1);
        assert_eq!(fps.snap(0.5, 1e-3), 0.5);
        assert_eq!(fps.nearest_frame(-0.51 / 30.0), -1);
    }

    #[test]
    fn a_frame_between_close_breaks_goes_to_the_nearer() {
        let fps = Fps::new(10, 1).unwrap();
        // Frame 1 (0.1 s) is 0.6e-9 after break 1 and 0.4e-9 before break 2: nearer break 2.
        let p: Vec<_> = fps.pieces(&[0.0, 0.1 - 6e-10, 0.1 + 4e-10, 0.2]).collect();
        assert_eq!(
            p.iter()
                .map(|q| (q.piece, q.from, q.to))
                .collect::<Vec<_>>(),
            [(0, 0, 1), (2, 1, 3)]
        );
    }
}
