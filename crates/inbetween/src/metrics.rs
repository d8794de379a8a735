//! `analyze`: smoothness figures of a track's curve, per scheme, for choosing a scheme and for
//! gating regressions.
//!
//! | field | meaning | unit |
//! |---|---|---|
//! | `duration` | `t_n − t_1` | s |
//! | `angle` | total angle travelled, `∫|ω| dt` (Simpson, ≥ 8 samples per frame interval) | angle |
//! | `max_speed`, `mean_speed` | largest `|ω|` over the samples; `angle / duration` | angle/s |
//! | `max_accel` | largest `|α|` over the samples | angle/s² |
//! | `c1_jump` | largest `|ω(t_k⁺) − ω(t_k⁻)|` over interior keys (C¹ defect) | angle/s |
//! | `c2_jump` | largest `|α(t_k⁺) − α(t_k⁻)|` over interior keys (C² defect) | angle/s² |
//! | `energy` | Barr's discrete `E = Σ w_p |q_p'' ∖ q_p|²` on the grid of [`energy_rate`] | (S³ units)²/s³ |
//!
//! ω and α are world-frame angular velocity and acceleration ([`crate::Curve`]); "angle" is
//! `--angles` (degrees by default).
//!
//! The energy is taken on a grid finer than the frames where the keys are dense
//! ([`energy_rate`]: at least `ENERGY_SAMPLES_PER_KEY` samples per key interval on average,
//! at most `MAX_ENERGY_MULTIPLE` times the frame rate): on the frames alone, keys at every
//! frame (motion capture) are every sample, and every scheme through them had the same energy.

use crate::clock::Fps;
use crate::curve::Scheme;
use crate::curve::minaccel::{Report, energy};
use crate::curve::piecewise::Side;
use crate::curve::{Curve, CurveOptions};
use crate::error::InputResult;
use crate::rotation::AngleUnit;
use crate::track::Track;
use glam::DQuat;

/// The figures of one track and scheme (angles in radians).
#[derive(Debug, Clone, PartialEq)]
pub struct Metrics {
    /// The track's name.
    pub track: Option<String>,
    /// The scheme measured.
    pub scheme: Scheme,
    /// `t_n − t_1`, s.
    pub duration: f64,
    /// Total angle travelled `∫|ω| dt`, rad.
    pub angle: f64,
    /// Largest `|ω|`, rad/s.
    pub max_speed: f64,
    /// `angle / duration`, rad/s.
    pub mean_speed: f64,
    /// Largest `|α|`, rad/s².
    pub max_accel: f64,
    /// Largest jump of `ω` at an interior key, rad/s.
    pub c1_jump: f64,
    /// Largest jump of `α` at an interior key, rad/s².
    pub c2_jump: f64,
    /// Barr's discrete energy over the frames.
    pub energy: f64,
    /// minaccel's solver report.
    pub solver: Option<Report>,
}

/// Samples per frame interval for the integrals and maxima.
const SAMPLES_PER_FRAME: f64 = 8.0;

/// The fewest samples per key interval, on average, that the energy is taken on.
pub(crate) const ENERGY_SAMPLES_PER_KEY: u64 = 8;

/// The largest multiple of the frame rate the energy is taken at.
pub(crate) const MAX_ENERGY_MULTIPLE: u64 = 8;

/// The rate whose grid the energy of a curve through `key_times` is taken on: `m·fps`, with
/// `m` the smallest whole number for which the keys' mean interval `(t_n − t_1)/(n − 1)` holds
/// at least `ENERGY_SAMPLES_PER_KEY` grid intervals, at most `MAX_ENERGY_MULTIPLE` (and
/// never past the highest rate, `MAX_FPS`). Keys 8 or more frames apart on
/// average give `fps` itself; keys at every frame give `8·fps`, so that the grid sees the
/// curve between keys.
///
/// ```
/// use inbetween::Fps;
/// use inbetween::metrics::energy_rate;
/// let fps = Fps::new(30, 1).unwrap();
/// let every_frame: Vec<f64> = (0..31).map(|k| k as f64 / 30.0).collect();
/// assert_eq!(energy_rate(&every_frame, fps), Fps::new(240, 1).unwrap());
/// assert_eq!(energy_rate(&[0.0, 0.1, 0.2, 0.3], fps), Fps::new(90, 1).unwrap()); // 3 frames apart
/// assert_eq!(energy_rate(&[0.0, 0.5, 1.0], fps), fps); // 15 frames apart
/// ```
pub fn energy_rate(key_times: &[f64], fps: Fps) -> Fps {
    let n = key_times.len();
    if n < 2 {
        return fps;
    }
    let mean = (key_times[n - 1] - key_times[0]) / (n - 1) as f64;
    let frames = mean * fps.as_f64();
    let m = if frames >= ENERGY_SAMPLES_PER_KEY as f64 {
        1
    } else {
        // frames > 0: the keys are increasing.
        ((ENERGY_SAMPLES_PER_KEY as f64 / frames).ceil() as u64).clamp(1, MAX_ENERGY_MULTIPLE)
    };
    (1..=m)
        .rev()
        .find_map(|m| {
            fps.num()
                .checked_mul(m)
                .and_then(|num| Fps::new(num, fps.den()).ok())
        })
        .unwrap_or(fps)
}

/// Computes the figures of `curve`, sampled at least 8 times per frame interval of `fps`; the
/// energy is that of its points on the grid of [`energy_rate`] (build a minaccel curve with
/// that grid rate, as [`measure_each`] does, for its energy to be that of its grid).
pub(crate) fn measure(curve: &Curve, fps: Fps) -> Metrics {
    let rate = fps;
    let b = curve.breaks().to_vec();
    let fps = rate.as_f64();
    let (mut angle, mut max_speed, mut max_accel) = (0.0, 0.0f64, 0.0f64);
    for i in 0..b.len() - 1 {
        let (t0, t1) = (b[i], b[i + 1]);
        // Simpson over the piece, an even number of intervals.
        let m = (((t1 - t0) * fps * SAMPLES_PER_FRAME).ceil() as usize)
            .max(2)
            .div_ceil(2)
            * 2;
        let h = (t1 - t0) / m as f64;
        let mut integral = 0.0;
        for j in 0..=m {
            let t = t0 + j as f64 * h;
            let side = if j == m { Side::Left } else { Side::Right };
            let speed = curve.omega(t, side).length();
            let weight = if j == 0 || j == m {
                1.0
            } else if j % 2 == 1 {
                4.0
            } else {
                2.0
            };
            integral += weight * speed;
            max_speed = max_speed.max(speed);
            max_accel = max_accel.max(curve.alpha(t, side).length());
        }
        angle += integral * h / 3.0;
    }
    let keys = curve.key_times().to_vec();
    let (mut c1, mut c2) = (0.0f64, 0.0f64);
    for &tk in keys.iter().skip(1).take(keys.len().saturating_sub(2)) {
        c1 = c1.max((curve.omega(tk, Side::Right) - curve.omega(tk, Side::Left)).length());
        c2 = c2.max((curve.alpha(tk, Side::Right) - curve.alpha(tk, Side::Left)).length());
    }
    let fine = energy_rate(&keys, rate);
    let (first, last) = fine.frames_between(keys[0], keys[keys.len() - 1]);
    let (times, pts): (Vec<f64>, Vec<DQuat>) = (first..=last)
        .map(|k| {
            let t = fine.time_of(k);
            (t, curve.eval(t))
        })
        .unzip();
    let duration = keys[keys.len() - 1] - keys[0];
    Metrics {
        track: curve.name().map(str::to_string),
        scheme: curve.scheme(),
        duration,
        angle,
        max_speed,
        // A one-key track (a constant) has no duration and no speed.
        mean_speed: if duration > 0.0 {
            angle / duration
        } else {
            0.0
        },
        max_accel,
        c1_jump: c1,
        c2_jump: c2,
        energy: if times.len() >= 3 {
            energy(&times, &pts)
        } else {
            0.0
        },
        solver: curve.solver_report().copied(),
    }
}

/// The figures of every track's curve under each of `schemes` (track by track, each track's
/// schemes in order), measured as `measure` measures them (minaccel solved on the grid of
/// [`energy_rate`], whatever the options' grid rate), the tracks shared out among the
/// machine's cores (at most `MAX_THREADS` (8) threads); a curve that cannot be built is its error in that
/// place. The same whatever the number of threads.
pub fn measure_each(
    tracks: &[Track],
    schemes: &[CurveOptions],
    fps: Fps,
) -> Vec<InputResult<Metrics>> {
    crate::parallel::map(tracks, |track| {
        schemes
            .iter()
            .map(|opts| {
                let opts = CurveOptions {
                    grid_rate: energy_rate(track.times(), fps),
                    ..*opts
                };
                Curve::new(track, &opts).map(|c| measure(&c, fps))
            })
            .collect::<Vec<_>>()
    })
    .into_iter()
    .flatten()
    .collect()
}

/// Column names of the csv and json output, in order.
pub const FIELDS: [&str; 10] = [
    "track",
    "scheme",
    "duration",
    "angle",
    "max_speed",
    "mean_speed",
    "max_accel",
    "c1_jump",
    "c2_jump",
    "energy",
];

impl Metrics {
    /// The last line of defence before a report is written: every figure, in `unit`, is finite
    /// (a NaN or infinite figure is a bug, never printed). The error is of kind `InvalidData`:
    /// `internal error: non-finite figure in the analysis of track "hip", scheme hermite
    /// ("energy" = NaN)`.
    pub fn check_finite(&self, unit: AngleUnit) -> std::io::Result<()> {
        let values = self.values(unit);
        match values.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(i) => {
                let track = match &self.track {
                    Some(name) => format!("track \"{name}\""),
                    None => "an unnamed track".to_string(),
                };
                Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!(
                        "internal error: non-finite figure in the analysis of {track}, scheme {} \
                         (\"{}\" = {})",
                        self.scheme.name(),
                        FIELDS[i + 2],
                        values[i]
                    ),
                ))
            }
        }
    }

    /// The numeric fields in `unit` (after `track` and `scheme`).
    pub fn values(&self, unit: AngleUnit) -> [f64; 8] {
        let a = |x: f64| unit.from_rad(x);
        [
            self.duration,
            a(self.angle),
            a(self.max_speed),
            a(self.mean_speed),
            a(self.max_accel),
            a(self.c1_jump),
            a(self.c2_jump),
            self.energy,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figures(energy: f64, max_speed: f64) -> Metrics {
        Metrics {
            track: Some("hip".into()),
            scheme: Scheme::Squad,
            duration: 1.0,
            angle: 0.5,
            max_speed,
            mean_speed: 0.5,
            max_accel: 2.0,
            c1_jump: 0.0,
            c2_jump: 0.0,
            energy,
            solver: None,
        }
    }

    #[test]
    fn a_non_finite_figure_is_an_internal_error() {
        assert!(figures(1.0, 3.0).check_finite(AngleUnit::Deg).is_ok());
        let err = figures(f64::NAN, 3.0)
            .check_finite(AngleUnit::Deg)
            .unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidData);
        assert_eq!(
            err.to_string(),
            "internal error: non-finite figure in the analysis of track \"hip\", scheme squad \
             (\"energy\" = NaN)"
        );
        // Finite in radians, infinite in degrees.
        let mut m = figures(1.0, 1e307);
        assert!(m.check_finite(AngleUnit::Rad).is_ok());
        m.track = None;
        assert_eq!(
            m.check_finite(AngleUnit::Deg).unwrap_err().to_string(),
            "internal error: non-finite figure in the analysis of an unnamed track, scheme squad \
             (\"max_speed\" = inf)"
        );
    }

    /// Keys at every frame of 30 fps on `θ(t) = a·t²` about z: on the 240 fps grid of
    /// [`energy_rate`], slerp's energy is its corners at the keys alone, in closed form (each
    /// key `h·(sin δ₊ − sin δ₋)²/h⁴`, `δ±` the quaternion angle of one grid step on either
    /// side: the tangential part of the three-point `q''` on a great circle), and bezier's,
    /// a C¹ curve, is near the continuum `∫(θ''/2)² dt = a²` per second. On the frames alone
    /// (the rule before) every sample was a key and both were the same.
    #[test]
    fn on_dense_keys_the_energy_tells_slerp_from_bezier() {
        let (a, fps) = (2.0, Fps::new(30, 1).unwrap());
        let times: Vec<f64> = (0..=30).map(|k| fps.time_of(k)).collect();
        let theta = |t: f64| a * t * t;
        let quats = times
            .iter()
            .map(|&t| DQuat::from_rotation_z(theta(t)))
            .collect();
        let track = Track::new(times.clone(), quats).unwrap();
        assert_eq!(energy_rate(&times, fps), Fps::new(240, 1).unwrap());
        let figure = |scheme| {
            let opts = CurveOptions {
                scheme,
                ..CurveOptions::default()
            };
            let m = measure_each(std::slice::from_ref(&track), &[opts], fps);
            m[0].as_ref().unwrap().energy
        };
        let h = 1.0 / 240.0;
        let want: f64 = (1..30)
            .map(|i| {
                let step = |j: usize| (theta(times[j + 1]) - theta(times[j])) / 2.0 / 8.0;
                let (before, after) = (step(i - 1), step(i));
                h * ((after.sin() - before.sin()) / (h * h)).powi(2)
            })
            .sum();
        let slerp = figure(Scheme::Slerp);
        assert!(
            (slerp - want).abs() <= 1e-9 * want,
            "slerp {slerp} vs closed form {want}"
        );
        let bezier = figure(Scheme::Bezier);
        assert!(
            (bezier - a * a).abs() < 0.1 * a * a,
            "bezier {bezier} vs {}",
            a * a
        );
        assert!(slerp > 5.0 * bezier, "slerp {slerp}, bezier {bezier}");
        // The frames alone (every sample a key: one figure for every scheme) hid slerp's
        // corners: its figure there was bezier's.
        let on_keys = energy(&times, track.rotations());
        assert!(
            slerp > 5.0 * on_keys,
            "slerp {slerp}, on the keys {on_keys}"
        );
        assert!((on_keys - bezier).abs() < 0.1 * a * a, "{on_keys} {bezier}");
    }
}
