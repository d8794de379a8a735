//! [`Curve`]: a track's curve under any scheme as a function of time, with its world-frame
//! angular velocity and acceleration: what a program samples, and what `interp --velocity`,
//! `analyze` and `plot` measure.
//!
//! The curve is piecewise: a segment between keys for hermite, squad, bezier and slerp; a grid
//! interval (slerp between grid points) for minaccel. Derivatives are one-sided at the pieces'
//! ends: each is taken from one piece's own formula (continued a little past its end), so a jump
//! at a key shows as the difference of the two sides.
//!
//! - `ω = 2·(dQ/dt)·Q⁻¹` (vector part), world frame, rad/s. For a segment scheme `dQ/du` is the
//!   fourth-order central difference of the exact segment formula with `h = 1e-3` in `u`
//!   (truncation ~h⁴·Q⁽⁵⁾/30, rounding ~ε/h: about 1e-12 relative for ordinary motion); for
//!   minaccel's slerp pieces it is exact, `2·log(q_{j+1} q_j⁻¹)/h_j`.
//! - `α = dω/dt` by the same difference of `ω` within the piece (about 1e-9 relative).
//! - At a time that is a piece boundary, [`Side::Right`] takes the piece that starts there
//!   (except at the last point, which has only a left piece).

use crate::clock::TIME_TOL;
use crate::curve::bezier::Bezier;
use crate::curve::hermite::Hermite;
use crate::curve::minaccel::{self, Report};
use crate::curve::nlerp::Nlerp;
use crate::curve::slerp::Slerp;
use crate::curve::squad::Squad;
use crate::curve::{Blend, CurveOptions, Scheme, Segment};
use crate::error::{InputError, InputResult};
use crate::rotation::quat::{geodesic, log};
use crate::tangent::{Ends, Knots, PathMode};
use crate::track::Track;
use glam::{DQuat, DVec3};
use std::sync::OnceLock;

mod batch;

/// Which piece to use at a piece boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The piece that ends there.
    Left,
    /// The piece that starts there (at the last point: the last piece).
    Right,
}

/// Largest accepted end velocity, rad/s: beyond it the tangents' products overflow (and a frame
/// period cannot resolve the motion anyway).
pub const MAX_SPEED: f64 = 1e15;

/// How far apart (rad) the first and last key of a cyclic track may be.
pub(crate) const CYCLIC_TOL: f64 = 1e-6;

/// Step in `u` of the finite differences.
const H: f64 = 1e-3;

/// A track's curve: every scheme, minaccel included, evaluable at any time in its span.
///
/// Built once from a [`Track`] and [`CurveOptions`] (the tangents, or minaccel's solve, happen
/// here), then sampled at any time: [`Curve::rotation`], [`Curve::angular_velocity`] (world
/// frame, rad/s) and [`Curve::angular_acceleration`] (rad/s²). Times outside the keys' span are
/// clamped to it. A time within 1e-9 s of a key (or of one of minaccel's grid points) is that
/// key, as in the frame clock, so that a sample at a frame time is the frame `interp` writes. At
/// a key the derivatives are those of the piece that starts there (at the last key, of the last
/// piece).
///
/// For hermite, squad, bezier and slerp the rotation is the scheme's closed form; minaccel's
/// curve is the solved grid, joined by great arcs (its grid rate is [`CurveOptions::grid_rate`]).
///
/// ```
/// use inbetween::rotation::quat::rotation_angle_between as angle;
/// use inbetween::{Curve, CurveOptions, Scheme, Track};
/// use glam::{DQuat, DVec3};
///
/// let track = Track::new(
///     vec![0.0, 1.0, 2.0],
///     vec![DQuat::IDENTITY, DQuat::from_rotation_z(1.0), DQuat::from_rotation_z(2.0)],
/// )?;
/// let curve = Curve::new(&track, &CurveOptions { scheme: Scheme::Slerp, ..Default::default() })?;
/// // Half-way through the first second: half a radian about z, at 1 rad/s.
/// let q = curve.rotation(0.5);
/// assert!(angle(q, DQuat::from_rotation_z(0.5)) < 1e-12);
/// assert!((curve.angular_velocity(0.5) - DVec3::Z).length() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Curve {
    name: Option<String>,
    positions: Option<crate::position::Positions>,
    euler_start: Option<(crate::EulerSeq, [f64; 3])>,
    scheme: Scheme,
    pieces: Pieces,
    report: Option<Report>,
}

/// The pieces of a curve.
#[derive(Debug, Clone)]
enum Pieces {
    /// One segment per pair of keys, built on the first sample and kept (baking builds its own,
    /// one at a time, so `interp` never holds them all).
    Segments {
        keys: Knots,
        blend: Blend,
        segs: OnceLock<Segs>,
    },
    /// minaccel's solution: slerp between grid points.
    Grid {
        times: Vec<f64>,
        points: Vec<DQuat>,
        keys: Knots,
    },
}

/// The segments of a segment scheme, built once so that sampling does not rebuild them.
#[derive(Debug, Clone)]
enum Segs {
    Slerp(Vec<Slerp>),
    Nlerp(Vec<Nlerp>),
    Hermite(Vec<Hermite>),
    Squad(Vec<Squad>),
    Bezier(Vec<Bezier>),
}

impl Segs {
    fn new(keys: &Knots, scheme: Scheme, blend: Blend) -> Segs {
        fn all<S: Segment>(keys: &Knots, blend: Blend) -> Vec<S> {
            (0..keys.segments())
                .map(|s| S::new(keys, s, blend))
                .collect()
        }
        match scheme {
            Scheme::Slerp => Segs::Slerp(all(keys, blend)),
            Scheme::Nlerp => Segs::Nlerp(all(keys, blend)),
            Scheme::Hermite => Segs::Hermite(all(keys, blend)),
            Scheme::Squad => Segs::Squad(all(keys, blend)),
            // minaccel is a grid curve and never builds segments.
            Scheme::Bezier | Scheme::MinAccel => Segs::Bezier(all(keys, blend)),
        }
    }

    #[inline]
    fn eval(&self, i: usize, u: f64) -> DQuat {
        match self {
            Segs::Slerp(v) => v[i].eval(u),
            Segs::Nlerp(v) => v[i].eval(u),
            Segs::Hermite(v) => v[i].eval(u),
            Segs::Squad(v) => v[i].eval(u),
            Segs::Bezier(v) => v[i].eval(u),
        }
    }
}

/// `ω = 2·Q'·Q⁻¹` from a derivative `dq` at `q`.
#[inline]
fn omega_of(q: DQuat, dq: DQuat) -> DVec3 {
    let p = dq * q.conjugate();
    DVec3::new(p.x, p.y, p.z) * 2.0
}

/// Fourth-order central difference of `f` at `x` with step `h`.
#[inline]
fn d4<T, F>(f: F, x: f64, h: f64) -> T
where
    F: Fn(f64) -> T,
    T: std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    (f(x - 2.0 * h) - f(x + 2.0 * h) + (f(x + h) - f(x - h)) * 8.0) * (1.0 / (12.0 * h))
}

/// The step in `u` of the differences in segment `s`: [`H`], or less where the segment turns more
/// than 10 rad (from its end tangents), so that the step turns at most 0.01 rad and the
/// truncation error (~(step·turn)⁴) stays below 1e-9 relative however fast the spin.
pub(crate) fn step_in(keys: &Knots, s: usize) -> f64 {
    let turn = 2.0
        * (keys.w[s].length().max(keys.w_in[s + 1].length()) * keys.delta(s))
            .max(keys.chords.as_ref().map_or(0.0, |c| c[s].length()));
    H.min(0.01 / turn)
}

/// Angular velocity (rad/s) of a segment at parameter `u`, for a segment `delta` seconds long:
/// its closed form ([`Segment::velocity`]) where it has one, else the fourth-order difference of
/// its exact formula with step `h` in `u` ([`step_in`]).
pub(crate) fn segment_omega<S: Segment>(seg: &S, u: f64, delta: f64, h: f64) -> DVec3 {
    if let Some(w) = seg.velocity(u) {
        return w / delta;
    }
    let dq = d4(|x| seg.eval(x), u, h) * (1.0 / delta);
    omega_of(seg.eval(u), dq)
}

/// Angular velocity (rad/s) of the slerp from `a` to `b` over `h` seconds.
pub(crate) fn chord_omega(a: DQuat, b: DQuat, h: f64) -> DVec3 {
    log(b * a.conjugate()) * (2.0 / h)
}

/// The position curve of a curve under `opts` through translations `p` at key `times`: linear
/// for slerp and nlerp, else cubic, with the end rule of `opts`.
fn positions(times: &[f64], p: &[DVec3], opts: &CurveOptions) -> crate::position::Positions {
    crate::position::Positions::new(times, p, opts.scheme.is_keys_only(), opts.ends.ends)
}

/// `t` clamped to the breaks' span, and within [`TIME_TOL`] of a break that break (the nearer).
fn snap(b: &[f64], t: f64) -> f64 {
    let t = t.clamp(b[0], b[b.len() - 1]);
    let i = b.partition_point(|&x| x < t);
    let near = |j: usize| b.get(j).filter(|&&x| (x - t).abs() <= TIME_TOL);
    match (i.checked_sub(1).and_then(near), near(i)) {
        (Some(&a), Some(&c)) => {
            if t - a < c - t {
                a
            } else {
                c
            }
        }
        (Some(&x), None) | (None, Some(&x)) => x,
        (None, None) => t,
    }
}

/// The piece of the breaks `b` (two or more) containing `t` on `side`, and `t`'s parameter `u`
/// in it.
fn piece(b: &[f64], t: f64, side: Side) -> (usize, f64) {
    let n = b.len();
    let i = match side {
        Side::Right => b.partition_point(|&x| x <= t).saturating_sub(1),
        Side::Left => b.partition_point(|&x| x < t).saturating_sub(1),
    }
    .min(n - 2);
    (i, (t - b[i]) / (b[i + 1] - b[i]))
}

/// The rotation at `t` of the curve of `keys` (two or more) under a segment scheme (minaccel
/// reads as bezier, as [`Segs::new`] builds it): [`Curve::rotation`]'s value, to the last bit,
/// building only the one segment `t` falls in (reduce's probe of a segment, which would
/// otherwise build a whole curve to evaluate one frame).
pub(crate) fn segment_rotation(keys: &Knots, scheme: Scheme, blend: Blend, t: f64) -> DQuat {
    fn at<S: Segment>(keys: &Knots, blend: Blend, (i, u): (usize, f64)) -> DQuat {
        S::new(keys, i, blend).eval(u)
    }
    let b = &keys.times;
    let t = snap(b, t);
    if let Ok(g) = b.binary_search_by(|x| x.total_cmp(&t)) {
        return keys.quats[g];
    }
    let p = piece(b, t, Side::Right);
    match scheme {
        Scheme::Slerp => at::<Slerp>(keys, blend, p),
        Scheme::Nlerp => at::<Nlerp>(keys, blend, p),
        Scheme::Hermite => at::<Hermite>(keys, blend, p),
        Scheme::Squad => at::<Squad>(keys, blend, p),
        Scheme::Bezier | Scheme::MinAccel => at::<Bezier>(keys, blend, p),
    }
}

impl Curve {
    /// Builds the curve of `track` under `opts`: tangents for the segment schemes, the solve on
    /// its grid for minaccel (which fails only for a grid larger than
    /// `MAX_GRID_POINTS`; the message names the track).
    pub fn new(track: &Track, opts: &CurveOptions) -> InputResult<Curve> {
        let built = Curve::build(track, opts, |_| Ok::<(), std::convert::Infallible>(()))?;
        Ok(built.unwrap_or_else(|never| match never {}))
    }

    /// [`Curve::new`], unless the scheme is minaccel and its grid would have more than
    /// `grid_limit` points ([`minaccel::Prepared::fits`]): then `None`, before solving.
    pub(crate) fn new_within(
        track: &Track,
        opts: &CurveOptions,
        grid_limit: usize,
    ) -> InputResult<Option<Curve>> {
        let built = Curve::build(track, opts, |p| {
            if p.fits(grid_limit) { Ok(()) } else { Err(()) }
        })?;
        Ok(built.ok())
    }

    /// The curve of `track` under `opts`, unless `gate` refuses minaccel's prepared grid.
    fn build<E>(
        track: &Track,
        opts: &CurveOptions,
        gate: impl FnOnce(&minaccel::Prepared) -> Result<(), E>,
    ) -> InputResult<Result<Curve, E>> {
        let given = [
            ("start", opts.ends.start.or(track.start_velocity())),
            ("end", opts.ends.end.or(track.end_velocity())),
        ];
        for (end, v) in given {
            if let Some(v) = v.filter(|v| !v.is_finite()) {
                return Err(InputError::new(format!(
                    "{end} velocity: expected three finite numbers, found {v}"
                )));
            }
            let speed = v.map(|v| crate::rotation::magnitude::length(v.to_array()));
            if let Some(speed) = speed.filter(|&s| s > MAX_SPEED) {
                return Err(InputError::new(format!(
                    "{end} velocity: expected at most {MAX_SPEED:e} rad/s, found {} rad/s",
                    crate::error::num(speed)
                )));
            }
        }
        let name = track.name().map(str::to_string);
        let named = |e: InputError| match &name {
            Some(n) => e.at(format!("track \"{}\"", crate::error::shorten(n))),
            None => e,
        };
        if let Some(v) = track.key_velocities() {
            for (i, w) in v.iter().enumerate() {
                let speed = w.map_or(0.0, |w| crate::rotation::magnitude::length(w.to_array()));
                if speed > MAX_SPEED {
                    return Err(named(InputError::new(format!(
                        "key {i}: angular velocity: expected at most {MAX_SPEED:e} rad/s, found {} \
                         rad/s",
                        crate::error::num(speed)
                    ))));
                }
            }
        }
        if opts.path == PathMode::Euler && opts.scheme == Scheme::Nlerp {
            return Err(InputError::new(
                "path euler: nlerp blends the keys' four components and cannot keep a turn of a \
                 whole rotation or more between two keys; use another scheme",
            ));
        }
        if opts.path == PathMode::Euler && track.len() > 1 && track.euler_angles().is_none() {
            return Err(named(InputError::new(
                "path euler: the track's keys carry no Euler angles (Track::with_euler_angles)",
            )));
        }
        if !opts.tcb.is_valid() {
            let t = opts.tcb;
            return Err(InputError::new(format!(
                "tension, continuity and bias: expected values between -1 and 1, found {}, {}, {}",
                t.tension, t.continuity, t.bias
            )));
        }
        let shaped = !opts.tcb.is_zero()
            || track
                .key_tcb()
                .is_some_and(|v| v.iter().flatten().any(|t| !t.is_zero()));
        if opts.scheme == Scheme::MinAccel && shaped {
            return Err(named(InputError::new(
                "minaccel has no tangents to shape: tension, continuity and bias must be 0 (use \
                 hermite, bezier or squad)",
            )));
        }
        if opts.ends.ends == Ends::Cyclic && track.len() > 1 {
            let (first, last) = (track.rotations()[0], track.rotations()[track.len() - 1]);
            let apart = crate::rotation::quat::rotation_angle_between(first, last);
            if apart > CYCLIC_TOL {
                return Err(named(InputError::new(format!(
                    "ends cyclic: the last key is {}° from the first key's rotation (a loop needs \
                     them equal within {CYCLIC_TOL:e} rad)",
                    crate::error::num(apart.to_degrees())
                ))));
            }
            let given = opts.ends.start.is_some()
                || opts.ends.end.is_some()
                || track.start_velocity().is_some()
                || track.end_velocity().is_some();
            if given {
                return Err(named(InputError::new(
                    "ends cyclic: a loop has no ends, so start and end velocities do not apply",
                )));
            }
        }
        let keys = Knots::shaped(
            track,
            opts.path,
            opts.ends,
            opts.tcb,
            opts.tangent.unwrap_or(opts.scheme.tangent()),
        );
        let (pieces, report) = match opts.scheme {
            // One key: a constant, whatever the scheme.
            _ if track.len() == 1 => (
                Pieces::Segments {
                    segs: OnceLock::new(),
                    keys,
                    blend: opts.blend,
                },
                None,
            ),
            Scheme::MinAccel => {
                let prepared = minaccel::Prepared::new(&keys, opts.grid_rate.as_f64()).map_err(
                    |e| match &name {
                        Some(n) => e.at(format!("track \"{}\"", crate::error::shorten(n))),
                        None => e,
                    },
                )?;
                if let Err(refused) = gate(&prepared) {
                    return Ok(Err(refused));
                }
                let sol = prepared.solve();
                let pieces = Pieces::Grid {
                    times: sol.times,
                    points: sol.points,
                    keys,
                };
                (pieces, Some(sol.report))
            }
            _ => (
                Pieces::Segments {
                    segs: OnceLock::new(),
                    keys,
                    blend: opts.blend,
                },
                None,
            ),
        };
        Ok(Ok(Curve {
            positions: track
                .translations()
                .map(|p| positions(track.times(), p, opts)),
            name,
            euler_start: track
                .euler_angles()
                .map(|(seq, angles)| (seq, angles[0].to_array())),
            scheme: opts.scheme,
            pieces,
            report,
        }))
    }

    /// The curve [`Curve::new`] builds under a segment scheme from the track that `keys` were
    /// shaped from, given those knots (reduce's probe knots, [`Knots::set_pair`]) and the
    /// track's translations and first Euler angles: no track, and none of its checks (the caller
    /// has made them).
    pub(crate) fn of_knots(
        keys: Knots,
        opts: &CurveOptions,
        translations: Option<&[DVec3]>,
        euler_start: Option<(crate::EulerSeq, [f64; 3])>,
    ) -> Curve {
        Curve {
            name: None,
            positions: translations.map(|p| positions(&keys.times, p, opts)),
            euler_start,
            scheme: opts.scheme,
            pieces: Pieces::Segments {
                keys,
                blend: opts.blend,
                segs: OnceLock::new(),
            },
            report: None,
        }
    }

    /// The track's name.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The first key's Euler angles (radians, as written) when the track's keys were given as
    /// Euler angles ([`Track::with_euler_angles`]): where continuous Euler output starts.
    pub fn euler_start(&self) -> Option<(crate::EulerSeq, [f64; 3])> {
        self.euler_start
    }

    /// The position at `t` (clamped to the span) when the track has translations: the
    /// Euclidean counterpart of the scheme (docs/spec.md §4.6) — linear between keys under
    /// slerp, else the cubic Hermite curve with the scheme's tangent rule and end conditions;
    /// finite for any finite keys.
    pub fn position(&self, t: f64) -> Option<glam::DVec3> {
        self.positions.as_ref().map(|p| p.at(t))
    }

    /// Whether the track has translations.
    pub fn has_positions(&self) -> bool {
        self.positions.is_some()
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// First and last key time, s.
    pub fn span(&self) -> (f64, f64) {
        let t = self.key_times();
        (t[0], t[t.len() - 1])
    }

    /// minaccel's solver report (`None` for the other schemes).
    pub fn solver_report(&self) -> Option<&Report> {
        self.report.as_ref()
    }

    /// The knots: keys after the path rule, with their tangents.
    pub fn knots(&self) -> &Knots {
        match &self.pieces {
            Pieces::Segments { keys, .. } | Pieces::Grid { keys, .. } => keys,
        }
    }

    /// The blending function of the segment schemes.
    pub(crate) fn blend(&self) -> Blend {
        match self.pieces {
            Pieces::Segments { blend, .. } => blend,
            Pieces::Grid { .. } => Blend::Cubic,
        }
    }

    /// The piece boundaries: key times, or minaccel's grid times.
    pub fn breaks(&self) -> &[f64] {
        match &self.pieces {
            Pieces::Segments { keys, .. } => &keys.times,
            Pieces::Grid { times, .. } => times,
        }
    }

    /// minaccel's grid points (empty for the other schemes).
    pub fn grid_points(&self) -> &[DQuat] {
        match &self.pieces {
            Pieces::Segments { .. } => &[],
            Pieces::Grid { points, .. } => points,
        }
    }

    /// The key times.
    pub fn key_times(&self) -> &[f64] {
        &self.knots().times
    }

    /// `t` clamped to the span and, within 1e-9 s of a break, moved onto it.
    fn snap(&self, t: f64) -> f64 {
        snap(self.breaks(), t)
    }

    /// The rotation at time `t` (s), a unit quaternion. Before the first key it is the first
    /// key, after the last the last (held); within 1e-9 s of a key it is that key — after the
    /// path rule, so possibly the negation of the quaternion given (the same rotation).
    pub fn rotation(&self, t: f64) -> DQuat {
        let t = self.snap(t);
        match self.breaks().binary_search_by(|x| x.total_cmp(&t)) {
            // On a break: the key (or grid point) itself, as the frame clock writes it.
            Ok(g) => match &self.pieces {
                Pieces::Segments { keys, .. } => keys.quats[g],
                Pieces::Grid { points, .. } => points[g],
            },
            Err(_) => self.eval(t),
        }
    }

    /// World-frame angular velocity at `t`, rad/s: at a key, that of the segment starting there
    /// (the last segment's at the last key); zero outside the span, where the pose is held.
    pub fn angular_velocity(&self, t: f64) -> DVec3 {
        if self.outside(t) {
            return DVec3::ZERO;
        }
        self.omega(self.snap(t), Side::Right)
    }

    /// World-frame angular acceleration at `t`, rad/s², on the same terms as
    /// [`Curve::angular_velocity`].
    pub fn angular_acceleration(&self, t: f64) -> DVec3 {
        if self.outside(t) {
            return DVec3::ZERO;
        }
        self.alpha(self.snap(t), Side::Right)
    }

    /// More than 1e-9 s outside the keys' span.
    fn outside(&self, t: f64) -> bool {
        let (t0, t1) = self.span();
        t < t0 - TIME_TOL || t > t1 + TIME_TOL
    }

    /// The piece containing `t` on `side`, and `t`'s parameter `u` in it.
    fn piece(&self, t: f64, side: Side) -> (usize, f64) {
        piece(self.breaks(), t, side)
    }

    /// Evaluates piece `i` at parameter `u` (continued past [0, 1] by its own formula).
    fn eval_piece(&self, i: usize, u: f64) -> DQuat {
        match &self.pieces {
            Pieces::Segments { segs, keys, blend } => segs
                .get_or_init(|| Segs::new(keys, self.scheme, *blend))
                .eval(i, u),
            Pieces::Grid { points, .. } => geodesic(points[i], points[i + 1], u),
        }
    }

    /// The points of segment `i` at `u₀, u₀ + δ, …` (`count` of them), generated as `interp`
    /// generates in-betweens ([`Segment::frames`]: forward differences, blends four at a time),
    /// each handed to `visit` until it returns false. `Some(true)` when every point was
    /// accepted, `Some(false)` at the first refused, `None` for minaccel's grid curve, whose
    /// pieces are not the keys' segments. The points agree with [`Curve::rotation`] at the
    /// same times to the forward differences' round-off (`docs/schemes.md`).
    pub(crate) fn segment_points(
        &self,
        i: usize,
        (u0, du): (f64, f64),
        count: usize,
        visit: impl FnMut(DQuat) -> bool,
    ) -> Option<bool> {
        fn all<S: Segment>(
            seg: &S,
            (u0, du): (f64, f64),
            count: usize,
            visit: impl FnMut(DQuat) -> bool,
        ) -> bool {
            seg.frames(u0, du).take(count).all(visit)
        }
        let Pieces::Segments { segs, keys, blend } = &self.pieces else {
            return None;
        };
        let segs = segs.get_or_init(|| Segs::new(keys, self.scheme, *blend));
        let u = (u0, du);
        Some(match segs {
            Segs::Slerp(v) => all(&v[i], u, count, visit),
            Segs::Nlerp(v) => all(&v[i], u, count, visit),
            Segs::Hermite(v) => all(&v[i], u, count, visit),
            Segs::Squad(v) => all(&v[i], u, count, visit),
            Segs::Bezier(v) => all(&v[i], u, count, visit),
        })
    }

    /// Where the blends of segment `i` come closest to antipodal ([`crate::curve::antipode_gap`]:
    /// the smallest `‖a + b‖` and its `u`), `None` where they cannot come near it, and for
    /// minaccel's grid curve, which has no blends. What `interp` checks before it generates the
    /// segment's frames.
    pub(crate) fn segment_antipode_gap(&self, i: usize) -> Option<(f64, f64)> {
        let Pieces::Segments { segs, keys, blend } = &self.pieces else {
            return None;
        };
        let segs = segs.get_or_init(|| Segs::new(keys, self.scheme, *blend));
        match segs {
            Segs::Slerp(v) => crate::curve::antipode_gap(v.get(i)?),
            Segs::Nlerp(v) => crate::curve::antipode_gap(v.get(i)?),
            Segs::Hermite(v) => crate::curve::antipode_gap(v.get(i)?),
            Segs::Squad(v) => crate::curve::antipode_gap(v.get(i)?),
            Segs::Bezier(v) => crate::curve::antipode_gap(v.get(i)?),
        }
    }

    /// A one-key track: the key's rotation at every time, at rest.
    pub fn is_constant(&self) -> bool {
        self.breaks().len() == 1
    }

    /// The curve at time `t` (the right piece at a boundary), without snapping.
    pub fn eval(&self, t: f64) -> DQuat {
        if self.is_constant() {
            return self.knots().quats[0];
        }
        let (i, u) = self.piece(t, Side::Right);
        self.eval_piece(i, u)
    }

    /// Angular velocity in piece `i` at parameter `u`, rad/s.
    fn omega_piece(&self, i: usize, u: f64) -> DVec3 {
        let b = self.breaks();
        let delta = b[i + 1] - b[i];
        match &self.pieces {
            Pieces::Grid { points, .. } => chord_omega(points[i], points[i + 1], delta),
            Pieces::Segments { .. } => {
                if let Some(seg) = self.nlerp_piece(i) {
                    return seg.omega(u) / delta;
                }
                let h = step_in(self.knots(), i);
                let dq = d4(|x| self.eval_piece(i, x), u, h) * (1.0 / delta);
                omega_of(self.eval_piece(i, u), dq)
            }
        }
    }

    /// Segment `i` of an nlerp curve, whose derivatives are in closed form.
    fn nlerp_piece(&self, i: usize) -> Option<Nlerp> {
        let Pieces::Segments { segs, keys, blend } = &self.pieces else {
            return None;
        };
        match segs.get_or_init(|| Segs::new(keys, self.scheme, *blend)) {
            Segs::Nlerp(v) => Some(v[i]),
            _ => None,
        }
    }

    /// World-frame angular velocity at `t`, rad/s.
    ///
    /// For minaccel's grid curve: inside a piece, the piece's own (exact) velocity; at a grid
    /// point, the velocity of the smooth curve the grid discretises — the mean of the two
    /// neighbouring pieces (second order), or, at a key or an end, the one-sided second-order
    /// extrapolation `1.5·ω_near − 0.5·ω_next` from `side`, so that a jump at a key measures the
    /// curve and not its discretisation.
    pub fn omega(&self, t: f64, side: Side) -> DVec3 {
        if self.is_constant() {
            return DVec3::ZERO;
        }
        let (i, u) = self.piece(t, side);
        let Pieces::Grid { times, .. } = &self.pieces else {
            return self.omega_piece(i, u);
        };
        let Some((g, one_sided)) = self.grid_point(t) else {
            return self.omega_piece(i, u);
        };
        let n = times.len() - 1; // pieces
        let c = |j: usize| self.omega_piece(j, 0.5);
        match (one_sided, side) {
            (false, _) => (c(g - 1) + c(g)) * 0.5,
            (true, Side::Right) if g < n => {
                if g + 1 < n {
                    c(g) * 1.5 - c(g + 1) * 0.5
                } else {
                    c(g)
                }
            }
            (true, _) if g >= 1 => {
                if g >= 2 {
                    c(g - 1) * 1.5 - c(g - 2) * 0.5
                } else {
                    c(g - 1)
                }
            }
            _ => c(g.min(n - 1)),
        }
    }

    /// For a grid curve and a time on one of its points: the point's index, and whether only
    /// one-sided estimates make sense there (a key or an end).
    fn grid_point(&self, t: f64) -> Option<(usize, bool)> {
        let Pieces::Grid { times, keys, .. } = &self.pieces else {
            return None;
        };
        let key_times = &keys.times;
        let g = times.partition_point(|&x| x < t);
        if g >= times.len() || times[g] != t {
            return None;
        }
        let edge = g == 0
            || g == times.len() - 1
            || key_times.binary_search_by(|k| k.total_cmp(&t)).is_ok();
        Some((g, edge))
    }

    /// World-frame angular acceleration at `t`, rad/s². For minaccel's grid curve, the
    /// difference of neighbouring pieces' velocities over the distance of their midpoints:
    /// centred inside, one-sided (on `side`) at a key or an end.
    pub(crate) fn alpha(&self, t: f64, side: Side) -> DVec3 {
        if self.is_constant() {
            return DVec3::ZERO;
        }
        let (i, u) = self.piece(t, side);
        match &self.pieces {
            Pieces::Grid { times, .. } => {
                let n = times.len() - 1;
                if n < 2 {
                    return DVec3::ZERO;
                }
                let mid = |j: usize| 0.5 * (times[j] + times[j + 1]);
                let slope = |a: usize, b: usize| {
                    (self.omega_piece(b, 0.5) - self.omega_piece(a, 0.5)) / (mid(b) - mid(a))
                };
                match self.grid_point(t) {
                    Some((g, true)) => match side {
                        Side::Right if g + 1 < n => slope(g, g + 1),
                        Side::Left if g >= 2 => slope(g - 2, g - 1),
                        _ => slope(i.min(n - 2), i.min(n - 2) + 1),
                    },
                    Some((g, false)) => slope(g - 1, g),
                    None => slope(i.saturating_sub(1).min(n - 2), (i + 1).min(n - 1).max(1)),
                }
            }
            Pieces::Segments { .. } => {
                let b = self.breaks();
                if let Some(seg) = self.nlerp_piece(i) {
                    return seg.alpha(u) / ((b[i + 1] - b[i]) * (b[i + 1] - b[i]));
                }
                let h = step_in(self.knots(), i);
                d4(|x| self.omega_piece(i, x), u, h) * (1.0 / (b[i + 1] - b[i]))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::{sample_keys, sample_track};

    /// The schemes whose pieces are the keys' segments.
    const SEGMENT_SCHEMES: [Scheme; 5] = [
        Scheme::Slerp,
        Scheme::Nlerp,
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
    ];

    fn curve(scheme: Scheme) -> Curve {
        let opts = CurveOptions {
            scheme,
            ..CurveOptions::default()
        };
        Curve::new(&sample_track(), &opts).unwrap()
    }

    #[test]
    fn segment_rotation_is_the_curves_rotation_to_the_bit() {
        for scheme in SEGMENT_SCHEMES {
            let c = curve(scheme);
            let (t0, t1) = c.span();
            for j in 0..=200 {
                // Keys, times within the snap tolerance of them, and between.
                let t = t0 + (t1 - t0) * j as f64 / 200.0 + [0.0, 1e-10, -3e-10][j % 3];
                let got = segment_rotation(c.knots(), scheme, c.blend(), t);
                let bits = |q: DQuat| q.to_array().map(f64::to_bits);
                assert_eq!(bits(got), bits(c.rotation(t)), "{scheme} at {t}");
            }
        }
    }

    #[test]
    fn segment_points_are_the_rotations_at_their_times() {
        let k = sample_keys();
        for scheme in SEGMENT_SCHEMES {
            let c = curve(scheme);
            for s in 0..k.segments() {
                let (u0, du) = (0.03, 0.0937);
                let mut got = Vec::new();
                let all = c.segment_points(s, (u0, du), 10, |q| {
                    got.push(q);
                    true
                });
                assert_eq!((all, got.len()), (Some(true), 10), "{scheme}");
                for (j, q) in got.iter().enumerate() {
                    let t = k.times[s] + (u0 + j as f64 * du) * k.delta(s);
                    let d = (*q - c.rotation(t)).length();
                    assert!(d < 1e-13, "{scheme} segment {s} point {j}: {d:e}");
                }
                // A refusal stops the points there.
                let mut seen = 0;
                let all = c.segment_points(s, (u0, du), 10, |_| {
                    seen += 1;
                    seen < 6
                });
                assert_eq!((all, seen), (Some(false), 6), "{scheme}");
            }
        }
        assert_eq!(
            curve(Scheme::MinAccel).segment_points(0, (0.1, 0.1), 3, |_| true),
            None
        );
    }

    #[test]
    fn slerp_velocity_is_the_chord() {
        let k = sample_keys();
        let c = curve(Scheme::Slerp);
        let w = log(k.quats[2] * k.quats[1].conjugate()) * (2.0 / k.delta(1));
        for t in [0.5, 0.7, 1.0, 1.2] {
            assert!((c.omega(t, Side::Right) - w).length() < 1e-10 * w.length());
        }
        // At key 1 the left side is the previous chord.
        let w0 = log(k.quats[1] * k.quats[0].conjugate()) * (2.0 / k.delta(0));
        assert!((c.omega(0.5, Side::Left) - w0).length() < 1e-10 * w0.length());
        assert!(c.alpha(0.7, Side::Right).length() < 1e-6);
    }

    #[test]
    fn hermite_velocity_at_keys_is_the_tangent() {
        let k = crate::tangent::Knots::shaped(
            &sample_track(),
            PathMode::Shortest,
            Default::default(),
            crate::Tcb::ZERO,
            Scheme::Hermite.tangent(),
        );
        let c = curve(Scheme::Hermite);
        for i in 0..k.times.len() {
            let want = k.w[i] * 2.0;
            for side in [Side::Left, Side::Right] {
                let got = c.omega(k.times[i], side);
                assert!(
                    (got - want).length() < 1e-9 * want.length().max(1.0),
                    "{i} {side:?}"
                );
            }
        }
    }
}

#[cfg(test)]
mod snapping {
    use super::*;
    use crate::curve::test_support::{sample_keys, sample_track};

    #[test]
    fn times_near_a_key_are_the_key_and_outside_the_span_are_clamped() {
        let k = sample_keys();
        for scheme in Scheme::ALL {
            let opts = CurveOptions {
                scheme,
                ..CurveOptions::default()
            };
            let c = Curve::new(&sample_track(), &opts).unwrap();
            assert_eq!(c.rotation(k.times[1] + 5e-10), k.quats[1], "{scheme}");
            assert_eq!(c.rotation(k.times[2] - 5e-10), k.quats[2], "{scheme}");
            assert_eq!(c.rotation(-1.0), k.quats[0], "{scheme}");
            assert_eq!(c.rotation(99.0), k.quats[3], "{scheme}");
            assert_eq!(c.span(), (0.0, 2.0));
            assert_eq!(
                c.angular_velocity(k.times[1] + 5e-10),
                c.angular_velocity(k.times[1])
            );
        }
    }
}
