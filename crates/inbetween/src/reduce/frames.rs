//! One track's frames and the segment test on them (the per-track oracle): the curve a segment
//! `a..b` has in the whole curve, probed at the frame that missed last, and whether every frame
//! inside meets the tolerances.

use super::*;

/// The error measure of reduce between rotations `a` and `b` (exported as
/// [`rotation_error`](super::rotation_error)): the geodesic angle (rad), or with
/// `opts.distance` D the displacement `2·D·sin(θ/2)` of a point D from the joint.
pub fn error(opts: &ReduceOptions, a: DQuat, b: DQuat) -> f64 {
    let theta = rotation_angle_between(a, b);
    match opts.distance {
        Some(d) => 2.0 * d * (0.5 * theta).sin(),
        None => theta,
    }
}

/// The frames of one track.
pub(super) struct Frames<'a> {
    pub(super) times: &'a [f64],
    pub(super) quats: &'a [DQuat],
    pub(super) positions: Option<&'a [DVec3]>,
    /// The frames' Euler angles, for `--path euler`.
    pub(super) euler: Option<(crate::EulerSeq, &'a [DVec3])>,
    /// Each frame's velocity estimates, when keys carry velocities.
    pub(super) estimates: Option<Vec<[DVec3; ESTIMATES]>>,
    /// The estimate each frame carries when it is a key (an index into its estimates; the
    /// centred one until a method chooses another).
    pub(super) choice: Vec<std::cell::Cell<u8>>,
    /// How many estimates the methods choose from: [`ESTIMATES`] where keys carry velocities
    /// and the scheme uses them, else 1.
    pub(super) choices: usize,
    pub(super) threshold: Threshold,
    /// The frame that last missed in [`Frames::feasible`].
    pub(super) hint: std::cell::Cell<usize>,
    /// The key before the segments being tested, which their first key's tangent depends on
    /// when tangents are estimated ([`Frames::segment_curve`]); set by the methods.
    pub(super) before: std::cell::Cell<Option<usize>>,
    /// The frames' spacing (s) when they are evenly spaced ([`even_spacing`]): then segments
    /// are evaluated at the frames as `interp` generates in-betweens.
    pub(super) spacing: Option<f64>,
    /// The times the keys will be written at, per frame, when they differ from the frames'
    /// ([`TrackFrames::key_times`]).
    pub(super) key_times: Option<&'a [f64]>,
    /// Knots reused by [`Frames::probe`], where segment tests may be probed
    /// ([`Frames::with_probe`]).
    pub(super) probe: Option<std::cell::RefCell<Knots>>,
    /// Per frame, the last frame of the run of frames held exactly from it (the same rotation
    /// to the bit, and position and Euler angles where they are tested), where there is a
    /// probe ([`Frames::held`]).
    pub(super) held_until: Vec<usize>,
}

/// The spacing of evenly spaced frame times: every time within 1e-9 of a frame of the spacing
/// from the first (a rate's frame clock, a file's fixed frame time), else `None`.
pub(super) fn even_spacing(times: &[f64]) -> Option<f64> {
    let n = times.len();
    if n < 3 {
        return None;
    }
    let dt = (times[n - 1] - times[0]) / (n - 1) as f64;
    let even = times
        .iter()
        .enumerate()
        .all(|(k, &t)| (t - (times[0] + k as f64 * dt)).abs() <= 1e-9 * dt);
    (dt > 0.0 && even).then_some(dt)
}

impl<'a> Frames<'a> {
    /// One track's frames for `opts`: its velocities estimated when keys carry them.
    pub(super) fn new(track: &TrackFrames<'a>, opts: &ReduceOptions) -> Frames<'a> {
        let (times, quats) = (track.times, track.rotations);
        Frames {
            times,
            quats,
            positions: track.positions,
            euler: track.euler,
            estimates: opts.velocities.then(|| {
                // The frames as the curve connects them: `--path as-given` as given, else each
                // in the hemisphere of the one before (`--path euler`'s chords between
                // neighbouring frames are those steps, unless the angles jump by half a turn).
                let mut q = quats.to_vec();
                if opts.curve.path != PathMode::AsGiven {
                    apply_path(&mut q, PathMode::Shortest);
                }
                velocity_estimates(times, &q)
            }),
            choice: vec![std::cell::Cell::new(0); quats.len()],
            choices: if opts.velocities && !opts.curve.scheme.is_keys_only() {
                ESTIMATES
            } else {
                1
            },
            threshold: Threshold::new(opts),
            hint: std::cell::Cell::new(0),
            before: std::cell::Cell::new(None),
            // Keys at other times than their frames' are evaluated directly at the frame times.
            spacing: even_spacing(times).filter(|_| track.key_times.is_none()),
            key_times: track.key_times,
            probe: None,
            held_until: Vec::new(),
        }
        .with_probe(opts)
    }

    /// Whether segment `a..b` surely meets the tolerances because it holds one pose: its frames
    /// are held exactly ([`Frames::held_until`]) and its keys' velocities are zero, so its curve
    /// is that pose to round-off (a few ulps, against tolerances of at least [`HELD_TOLERANCE`]).
    /// On held joints every segment test passes, each evaluating every frame; this decides them
    /// without a curve.
    pub(super) fn held(&self, a: usize, b: usize, opts: &ReduceOptions) -> bool {
        self.held_until.get(a).is_some_and(|&last| last >= b)
            && self.pair_velocities(a, b, opts) == [Some(DVec3::ZERO); 2]
    }

    /// The velocities keys `a` and `b` carry in segment `a..b`'s curve when keys carry them, as
    /// [`Frames::segment_curve`] gives them: the ends' given velocities at the first and last
    /// frame, else each key's own.
    fn pair_velocities(&self, a: usize, b: usize, opts: &ReduceOptions) -> [Option<DVec3>; 2] {
        let (n, ends) = (self.quats.len(), opts.curve.ends);
        [
            ends.start.filter(|_| a == 0).or(self.velocity(a)),
            ends.end.filter(|_| b == n - 1).or(self.velocity(b)),
        ]
    }

    /// Segment tests are probed ([`Frames::probe`]) where the probe's knots are the
    /// segment curve's and building that curve cannot fail: keys carry velocities, all within
    /// the curve's speed limit (the ends' too), the scheme is a segment scheme, TCB is valid,
    /// the keys sit at their frames' times, and the frames are a valid track, with their Euler
    /// angles for `--path euler` (so every subset of them is).
    pub(super) fn with_probe(mut self, opts: &ReduceOptions) -> Frames<'a> {
        let fine = |v: &DVec3| {
            v.is_finite() && crate::rotation::magnitude::length(v.to_array()) <= MAX_SPEED
        };
        let c = &opts.curve;
        let probes = self
            .estimates
            .as_ref()
            .is_some_and(|e| e.iter().flatten().all(fine))
            && [c.ends.start, c.ends.end].iter().flatten().all(fine)
            && c.scheme != Scheme::MinAccel
            && c.tcb.is_valid()
            && self.key_times.is_none()
            && self
                .positions
                .is_none_or(|p| p.iter().all(|x| x.is_finite()))
            && Track::new(self.times.to_vec(), self.quats.to_vec()).is_ok_and(|t| {
                match (c.path, self.euler) {
                    (PathMode::Euler, Some((seq, e))) => {
                        t.with_euler_angles(seq, e.to_vec()).is_ok()
                    }
                    (PathMode::Euler, None) => false,
                    _ => true,
                }
            });
        if !probes {
            return self;
        }
        let (t, q) = (
            [self.times[0], self.times[1]],
            [self.quats[0], self.quats[1]],
        );
        let knots = Knots::pair(t, q, c.path, [DVec3::ZERO; 2], None);
        self.probe = Some(std::cell::RefCell::new(knots));
        let positions = self.positions.filter(|_| self.reduces_positions(opts));
        let ample = |tol: f64, size: f64| tol >= HELD_TOLERANCE * size.max(1.0);
        let tolerant = ample(self.threshold.angle, 1.0)
            && positions.is_none_or(|p| {
                let size = p.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max);
                opts.translation_tolerance
                    .is_some_and(|tol| ample(tol, size))
            });
        if tolerant {
            let euler = self.euler.filter(|_| c.path == PathMode::Euler);
            let same = |i: usize, j: usize| {
                let bits = |q: DQuat| q.to_array().map(f64::to_bits);
                bits(self.quats[i]) == bits(self.quats[j])
                    && positions.is_none_or(|p| p[i] == p[j])
                    && euler.is_none_or(|(_, e)| e[i] == e[j])
            };
            let n = self.quats.len();
            self.held_until = vec![n - 1; n];
            for i in (0..n - 1).rev() {
                if same(i, i + 1) {
                    self.held_until[i] = self.held_until[i + 1];
                } else {
                    self.held_until[i] = i;
                }
            }
        }
        self
    }

    /// The knots of segment `a..b`'s curve as [`Frames::segment_curve`] would shape them, in
    /// the reused probe knots, where there is a probe ([`Frames::with_probe`]): the two keys with
    /// their velocities (the ends' velocities only at the first and last frame).
    pub(super) fn probe(
        &self,
        a: usize,
        b: usize,
        opts: &ReduceOptions,
    ) -> Option<RefMut<'_, Knots>> {
        let probe = self.probe.as_ref()?;
        let [Some(start), Some(end)] = self.pair_velocities(a, b, opts) else {
            return None;
        };
        let mut knots = probe.borrow_mut();
        let (t, q) = (
            [self.times[a], self.times[b]],
            [self.quats[a], self.quats[b]],
        );
        let euler = self.euler.map(|(seq, e)| (seq, [e[a], e[b]]));
        knots.set_pair(t, q, opts.curve.path, [start, end], euler);
        Some(knots)
    }

    /// The curve of segment `a..b` on the probe's `knots` ([`Frames::probe`]): the curve
    /// [`Frames::segment_curve`] builds, without its track.
    pub(super) fn probe_curve(
        &self,
        knots: &Knots,
        a: usize,
        b: usize,
        opts: &ReduceOptions,
    ) -> Curve {
        // The segment's own ends are chords (its end velocities are in the knots).
        let ends = EndConditions {
            ends: Ends::Chord,
            ..opts.curve.ends
        };
        let segment = CurveOptions { ends, ..opts.curve };
        let positions = self.positions.map(|p| [p[a], p[b]]);
        let euler = self.euler.filter(|_| opts.curve.path == PathMode::Euler);
        let euler_start = euler.map(|(seq, e)| (seq, e[a].to_array()));
        Curve::of_knots(
            knots.clone(),
            &segment,
            positions.as_ref().map(|p| &p[..]),
            euler_start,
        )
    }

    /// Whether the track's positions are reduced (it has them, and a tolerance for them).
    pub(super) fn reduces_positions(&self, opts: &ReduceOptions) -> bool {
        self.positions.is_some() && opts.translation_tolerance.is_some()
    }

    /// The velocity frame `i` carries as a key (its chosen estimate), when keys carry them.
    pub(super) fn velocity(&self, i: usize) -> Option<DVec3> {
        self.estimates
            .as_ref()
            .map(|e| e[i][usize::from(self.choice[i].get())])
    }

    /// Frame `i` carries estimate `c` when it is a key.
    pub(super) fn choose(&self, i: usize, c: usize) {
        self.choice[i].set(c as u8);
    }

    /// The velocities the frames `keys` carry, when keys carry them.
    pub(super) fn key_velocities(&self, keys: &[usize]) -> Option<Vec<DVec3>> {
        self.estimates
            .as_ref()
            .map(|_| keys.iter().filter_map(|&i| self.velocity(i)).collect())
    }

    /// The curve through the frames `keys` (with their velocities when asked), as `interp`
    /// builds it.
    pub(super) fn curve(&self, keys: &[usize], opts: &CurveOptions) -> InputResult<Curve> {
        Curve::new(&self.track(keys, opts)?, opts)
    }

    /// [`Frames::curve`], unless minaccel's grid would need more than `grid_limit` points
    /// ([`Curve::new_within`]).
    pub(super) fn curve_within(
        &self,
        keys: &[usize],
        opts: &CurveOptions,
        grid_limit: usize,
    ) -> InputResult<Option<Curve>> {
        Curve::new_within(&self.track(keys, opts)?, opts, grid_limit)
    }

    /// The frames `keys` as a track's keys: their times (as written), rotations, and, as the
    /// frames have them, velocities, translations and (for `--path euler`) Euler angles.
    pub(super) fn track(&self, keys: &[usize], opts: &CurveOptions) -> InputResult<Track> {
        let key_times = self.key_times.unwrap_or(self.times);
        let t: Vec<f64> = keys.iter().map(|&i| key_times[i]).collect();
        let q: Vec<DQuat> = keys.iter().map(|&i| self.quats[i]).collect();
        let mut track = Track::new(t, q)?;
        if self.estimates.is_some() {
            track = track.with_key_velocities(keys.iter().map(|&i| self.velocity(i)).collect())?;
        }
        if let Some(p) = self.positions {
            track = track.with_translations(keys.iter().map(|&i| p[i]).collect())?;
        }
        if let Some((seq, e)) = self.euler.filter(|_| opts.path == PathMode::Euler) {
            track = track.with_euler_angles(seq, keys.iter().map(|&i| e[i]).collect())?;
        }
        Ok(track)
    }

    /// The curve [`Frames::feasible`] tests segment `a..b` on, as the whole curve will have it:
    /// the keys `a` and `b`, and where the keys' tangents are estimated from their neighbours (no
    /// velocities) the key before `a` ([`Frames::before`]) and a stand-in for the key after `b`
    /// (as far past `b` as `a` is before it); the start's end condition only on the first frame,
    /// the end's only on the last (rest as a zero velocity there), and a loop's seam as a chord
    /// end (verification, on the whole curve, settles the seam).
    ///
    /// `None` for a minaccel segment whose grid would need more than one refinement of its
    /// frames ([`SEGMENT_GRID_FACTOR`]): its start curve turns more than a quarter turn between
    /// two frames, and the segment is taken as not feasible, unsolved.
    pub(super) fn segment_curve(
        &self,
        a: usize,
        b: usize,
        opts: &ReduceOptions,
    ) -> InputResult<Option<Curve>> {
        let n = self.quats.len();
        let neighbours = self.estimates.is_none();
        let mut keys = Vec::with_capacity(4);
        keys.extend(self.before.get().filter(|&p| neighbours && p < a));
        keys.extend([a, b]);
        keys.extend((neighbours && b < n - 1).then(|| (2 * b - a).min(n - 1)));
        let ends = opts.curve.ends;
        // Rest is the velocity of an end without one: with velocities, the key's own.
        let rest = neighbours && ends.ends == Ends::Rest;
        let given =
            |at: bool, v: Option<DVec3>| at.then(|| v.or(rest.then_some(DVec3::ZERO))).flatten();
        let curve = CurveOptions {
            ends: EndConditions {
                ends: Ends::Chord,
                start: given(keys[0] == 0, ends.start),
                end: given(keys[keys.len() - 1] == n - 1, ends.end),
            },
            ..opts.curve
        };
        let key_times = self.key_times.unwrap_or(self.times);
        let span = key_times[keys[keys.len() - 1]] - key_times[keys[0]];
        let steps = (span * opts.curve.grid_rate.as_f64()).ceil();
        let limit = (SEGMENT_GRID_FACTOR as f64 * steps).min(usize::MAX as f64) as usize;
        self.curve_within(&keys, &curve, limit.saturating_add(SEGMENT_GRID_SLACK))
    }

    /// The worst frame strictly between keys `a` and `b` of `curve` and whether every frame
    /// there meets the tolerances; their rotation errors are added to `errors`.
    pub(super) fn check(
        &self,
        curve: &Curve,
        (piece, a, b): (usize, usize, usize),
        opts: &ReduceOptions,
        errors: &mut Errors,
    ) -> (bool, usize) {
        let mut worst = (0.0f64, a);
        let mut ok = true;
        // A hair inside the tolerance, so that keys written and read back (velocities in
        // degrees per second round to the last bit) still meet it.
        let tol = opts.tolerance * (1.0 - 1e-9);
        let points = self.generated(curve, (piece, a, b));
        for k in a + 1..b {
            let q = points
                .as_ref()
                .map_or_else(|| curve.rotation(self.times[k]), |p| p[k - a - 1]);
            let e = error(opts, q, self.quats[k]);
            errors.add(e);
            let mut bad = e > tol;
            let mut score = e / opts.tolerance;
            if let (Some(p), Some(tol)) = (self.positions, opts.translation_tolerance) {
                let d = (curve.position(self.times[k]).unwrap_or(DVec3::ZERO) - p[k]).length();
                errors.position = Some(errors.position.unwrap_or(0.0).max(d));
                bad |= d > tol;
                score = score.max(d / tol);
            }
            ok &= !bad;
            if score > worst.0 {
                worst = (score, k);
            }
        }
        if b > a + 1
            && let Some(u) = near_antipode(curve, piece)
        {
            // The frame nearest the blend's near-antipode becomes a key.
            let k = a + (u * (b - a) as f64).round() as usize;
            return (false, k.clamp(a + 1, b - 1));
        }
        (ok, worst.1)
    }

    /// The frames strictly inside segment `piece` of `curve` (from frame `a` to frame `b`) as
    /// `interp` generates them at the frames' rate ([`Curve::segment_points`]: forward
    /// differences from the segment's first frame after its key, the first at
    /// `u₀ = (t_{a+1} − t_a)/Δ`, then steps of the spacing over `Δ`), when the frames are
    /// evenly spaced and the scheme is a segment scheme; else `None` (evaluated directly).
    pub(super) fn generated(
        &self,
        curve: &Curve,
        (piece, a, b): (usize, usize, usize),
    ) -> Option<Vec<DQuat>> {
        let dt = self.spacing?;
        if b <= a + 1 {
            return None;
        }
        let delta = self.times[b] - self.times[a];
        let u0 = (self.times[a + 1] - self.times[a]) / delta;
        let mut points = Vec::with_capacity(b - a - 1);
        curve.segment_points(piece, (u0, dt / delta), b - a - 1, |q| {
            points.push(q);
            true
        })?;
        Some(points)
    }

    /// Whether the segment `a..b` alone meets the tolerances. Stops at the first frame that
    /// misses, trying first the frame that missed last time (`hint`: neighbouring segments
    /// usually miss at the same frame), and decides most frames from the cosine of the half
    /// angle ([`Threshold`]). Evenly spaced frames are generated as `interp` generates
    /// in-betweens ([`Curve::segment_points`]), which agrees with [`Curve::rotation`], and so
    /// with [`Frames::check`], to round-off: a frame within round-off of the tolerance may be
    /// judged differently, which verification settles.
    pub(super) fn feasible(&self, a: usize, b: usize, opts: &ReduceOptions) -> InputResult<bool> {
        if b == a + 1 || self.held(a, b, opts) {
            return Ok(true);
        }
        let hint = self.hint.get();
        let at_hint = hint > a && hint < b;
        // Whether the rotation at the hint was probed (and met the tolerance).
        let mut probed = false;
        let curve = match self.probe(a, b, opts) {
            // Most tests miss at the frame that missed last: that frame is evaluated on the
            // probe's one segment (the curve's value to the last bit) before any curve is built.
            Some(knots) => {
                let c = &opts.curve;
                let miss = |k: usize| {
                    let q = segment_rotation(&knots, c.scheme, c.blend, self.times[k]);
                    !self.threshold.within(opts, q, self.quats[k])
                };
                if at_hint && miss(hint) {
                    return Ok(false);
                }
                probed = at_hint;
                self.probe_curve(&knots, a, b, opts)
            }
            None => match self.segment_curve(a, b, opts)? {
                Some(curve) => curve,
                None => return Ok(false),
            },
        };
        // The segment's index in that curve: after the key before `a`, if it has one.
        let start = self.key_times.map_or(self.times[a], |t| t[a]);
        let piece = curve.key_times().partition_point(|&t| t < start);
        let placed = |k: usize| match (self.positions, opts.translation_tolerance) {
            (Some(p), Some(tol)) => {
                let d = (curve.position(self.times[k]).unwrap_or(DVec3::ZERO) - p[k]).length();
                d <= tol
            }
            _ => true,
        };
        let within =
            |k: usize, q: DQuat| self.threshold.within(opts, q, self.quats[k]) && placed(k);
        // A probed rotation is the curve's to the bit: only the position is left to test.
        if at_hint
            && !(if probed {
                placed(hint)
            } else {
                within(hint, curve.rotation(self.times[hint]))
            })
        {
            return Ok(false);
        }
        // The frames first: most segments tested miss a frame, and the antipode's search
        // (hundreds of blend evaluations) is then not needed.
        let missed = match self.spacing {
            Some(dt) => {
                let delta = self.times[b] - self.times[a];
                let mut k = a + 1;
                curve
                    .segment_points(piece, (dt / delta, dt / delta), b - a - 1, |q| {
                        let ok = k == hint || within(k, q);
                        k += 1;
                        ok
                    })
                    .map(|all| (!all).then(|| k - 1))
            }
            None => None,
        };
        let missed = missed.unwrap_or_else(|| {
            (a + 1..b).find(|&k| k != hint && !within(k, curve.rotation(self.times[k])))
        });
        if let Some(k) = missed {
            self.hint.set(k);
            return Ok(false);
        }
        Ok(near_antipode(&curve, piece).is_none())
    }

    /// [`Frames::feasible`] with frame `b` carrying estimate `c`.
    pub(super) fn feasible_with(
        &self,
        a: usize,
        b: usize,
        c: usize,
        opts: &ReduceOptions,
    ) -> InputResult<bool> {
        self.choose(b, c);
        self.feasible(a, b, opts)
    }

    /// Every frame that is not one of `keys` back to the centred estimate, so that keys added by
    /// verification carry it.
    pub(super) fn keep_choices(&self, keys: &[usize]) {
        let mut k = keys.iter().peekable();
        for (i, c) in self.choice.iter().enumerate() {
            if k.peek() == Some(&&i) {
                k.next();
            } else {
                c.set(0);
            }
        }
    }
}

/// The smallest tolerance (rad, and relative to the largest coordinate for positions) at which
/// held frames are taken as met without evaluating them ([`Frames::held`]): far above the
/// round-off of a curve through keys that are one pose.
pub(super) const HELD_TOLERANCE: f64 = 1e-9;

/// How near an antipode (`‖a + b‖` of a blend's two points, [`crate::curve::antipode_gap`])
/// the blends of a segment with frames inside may come. Where they come nearer, the geodesic
/// between them is barely defined: a perturbation `ε` of its points (round-off: direct
/// evaluation against `interp`'s forward differences, a velocity written to the last digit)
/// moves it by about `π·ε/gap`, and at the antipode itself by anything up to half a turn. A
/// segment nearer than this is never feasible, and verification splits it (docs/spec.md §4.7).
pub(crate) const ANTIPODE_MARGIN: f64 = 1e-3;

/// Where the blends of segment `piece` of `curve` come within [`ANTIPODE_MARGIN`] of an
/// antipode: the `u` where they come nearest.
pub(super) fn near_antipode(curve: &Curve, piece: usize) -> Option<f64> {
    curve
        .segment_antipode_gap(piece)
        .filter(|&(gap, _)| gap < ANTIPODE_MARGIN)
        .map(|(_, u)| u)
}

/// The rotation test of [`Frames::check`] (`error > tolerance·(1 − 1e-9)` misses) decided from
/// `|a·b|`, the cosine of half the angle between the rotations, which the error decreases with:
/// clearly above the threshold's cosine a frame meets the tolerance, clearly below it misses,
/// and within 1e-9 of it the error is computed as [`Frames::check`] computes it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Threshold {
    pub(super) cos_half: f64,
    /// The largest rotation angle error allowed (rad).
    pub(super) angle: f64,
}

/// Half-width of the band around [`Threshold::cos_half`] where the exact error decides.
pub(super) const BAND: f64 = 1e-9;

impl Threshold {
    pub(super) fn new(opts: &ReduceOptions) -> Threshold {
        let tol = opts.tolerance * (1.0 - 1e-9);
        // The half angle at which the error reaches `tol` (the error is `θ`, or `2D·sin(θ/2)`).
        let half = match opts.distance {
            Some(d) if tol >= 2.0 * d => std::f64::consts::FRAC_PI_2,
            Some(d) => (tol / (2.0 * d)).asin(),
            None => (0.5 * tol).min(std::f64::consts::FRAC_PI_2),
        };
        Threshold {
            cos_half: half.cos(),
            angle: 2.0 * half,
        }
    }

    /// Whether `a` is within the tolerance of `b` (the same answer as `error(a, b) <= tol`).
    #[inline]
    pub(super) fn within(&self, opts: &ReduceOptions, a: DQuat, b: DQuat) -> bool {
        let c = a.dot(b).abs();
        if c > self.cos_half + BAND {
            true
        } else if c < self.cos_half - BAND {
            false
        } else {
            error(opts, a, b) <= opts.tolerance * (1.0 - 1e-9)
        }
    }
}
