//! Interpolating curves on S³, one module per scheme behind the small `Segment` trait.
//!
//! A segment joins keys `s` and `s+1` over the local parameter `u = (t − t_s)/Δ_s ∈ [0, 1]`. It
//! can be evaluated directly at any `u` (`Segment::eval`, for tests and off-grid samples) and
//! can generate its in-betweens at equally spaced `u` (`Segment::frames`), where the fixed great
//! arcs of the segment advance by forward differences (`rotation::arc`) and only the blends are evaluated
//! per frame.
//!
//! Every blend is the geodesic of S³ between its two points, never hemisphere-flipped, so the
//! curve is continuous in S³ (docs/spec.md §4.3); `antipode_gap` finds where a blend's two points come
//! close to antipodal and the geodesic between them stops being well defined.
//!
//! [`Curve`] ([`piecewise`]) is a whole track's curve under any scheme, minaccel included, as a
//! function of time; [`CurveOptions`] are what shapes it.

pub(crate) mod banded;
pub(crate) mod bezier;
pub(crate) mod blend4;
pub(crate) mod hermite;
pub mod minaccel;
pub(crate) mod nlerp;
pub mod piecewise;
pub(crate) mod slerp;
pub(crate) mod squad;

pub use piecewise::Curve;

use crate::clock::Fps;
use crate::tangent::{EndConditions, Knots, PathMode, TangentRule};
use crate::track::Tcb;
use glam::{DQuat, DVec3};
use std::fmt;

/// A scheme's segment (see the module documentation).
pub(crate) trait Segment: Sized {
    /// In-betweens at equally spaced `u`; an endless iterator (take what is needed).
    type Frames: Iterator<Item = DQuat>;

    /// The segment from key `s` to key `s + 1`.
    fn new(keys: &Knots, s: usize, blend: Blend) -> Self;

    /// Direct evaluation at `u`.
    fn eval(&self, u: f64) -> DQuat;

    /// The points at `u₀, u₀ + δ, u₀ + 2δ, …` by forward differences.
    fn frames(&self, u0: f64, du: f64) -> Self::Frames;

    /// A frame up to its last blends, for a scheme whose frames end in blends done four at a
    /// time as lanes (`blend4.rs`); [`std::convert::Infallible`] for the others.
    type Pending: Copy;

    /// The first `n` (1 ≤ `n` ≤ 3) frames of [`Segment::frames`]`(u0, du)` up to their last
    /// blends (the slots from `n` on repeat the first), so that the frames of several short
    /// segments share one block of lanes — a segment holding fewer than four frames, as in a
    /// resample to a lower rate, would fill a block of its own for one frame.
    /// [`Segment::finish4`] completes them to the bits `frames` gives: a lane's blends never
    /// depend on the other lanes. `None` for a scheme without lanes.
    fn gather(&self, _u0: f64, _du: f64, _n: usize) -> Option<[Self::Pending; 3]> {
        None
    }

    /// The frames of four pending lanes ([`Segment::gather`]).
    fn finish4(lanes: &[Self::Pending; 4]) -> [DQuat; 4];

    /// Whether the frames of `keys`' short segments (fewer than four frames) are evaluated
    /// directly, four segments at a time as lanes ([`Segment::direct4`]), instead of gathered:
    /// a segment with one frame is then never built on its own.
    fn direct(_keys: &Knots) -> bool {
        false
    }

    /// Segment `s[i]` at `u[i]` for the four lanes, and each lane's segment's
    /// [`Segment::blend_bound`]: the segments built and evaluated as lanes where the scheme has
    /// them (bezier), here one by one. A scheme that evaluates directly
    /// ([`Segment::direct`]) has no [`Segment::limitation`]: only a lane's blend bound tells
    /// whether its segment is checked further.
    fn direct4(keys: &Knots, blend: Blend, s: [usize; 4], u: [f64; 4]) -> ([DQuat; 4], [f64; 4]) {
        let segs = s.map(|s| Self::new(keys, s, blend));
        (
            std::array::from_fn(|i| segs[i].eval(u[i])),
            segs.map(|s| s.blend_bound()),
        )
    }

    /// An upper bound of the S³ angle between the two points of any blend of the segment; below
    /// π their geodesic is well defined everywhere. Zero for a scheme without blends.
    fn blend_bound(&self) -> f64;

    /// The smallest `‖a + b‖` over the segment's blends at `u` (0 means antipodal).
    fn blend_gap(&self, u: f64) -> f64;

    /// A limitation of the scheme that this segment runs into, to be reported on stderr.
    fn limitation(&self) -> Option<crate::error::Message> {
        None
    }

    /// The world-frame angular velocity per unit `u` at `u` where the scheme has it in closed
    /// form (`None`: it is taken by differences of `Segment::eval`).
    fn velocity(&self, _u: f64) -> Option<DVec3> {
        None
    }
}

/// Interpolation scheme (`--scheme`). Names are the command line's: `hermite`, `squad`,
/// `bezier`, `slerp`, `nlerp`, `minaccel`.
///
/// ```
/// use inbetween::Scheme;
///
/// let s: Scheme = "minaccel".parse()?;
/// assert_eq!(s, Scheme::MinAccel);
/// assert_eq!(s.to_string(), "minaccel");
/// assert_eq!(Scheme::ALL.len(), 6);
/// assert!("catmull".parse::<Scheme>().is_err());
/// # Ok::<(), inbetween::InputError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Scheme {
    /// Nam & Kim's Hermite by blending two great arcs (`curve/hermite.rs`); C¹.
    Hermite,
    /// Shoemake's squad (`curve/squad.rs`); C¹.
    Squad,
    /// Spherical cubic Bézier by de Casteljau's construction (`curve/bezier.rs`); C¹. The default:
    /// fourth order in the key spacing with the spline tangent (hermite is second), local, and the
    /// spherical counterpart of the cubic Hermite of the same tangents (docs/schemes.md).
    #[default]
    Bezier,
    /// Piecewise great arcs (`curve/slerp.rs`); C⁰.
    Slerp,
    /// The normalised lerp of consecutive keys (`curve/nlerp.rs`): how Blender plays `LINEAR`
    /// quaternion F-curves and ozz-animation its keys; C⁰.
    Nlerp,
    /// Barr et al.'s minimal tangential acceleration on a grid ([`minaccel`]); not per segment.
    MinAccel,
}

impl Scheme {
    /// Every scheme, in the order of the command line's help.
    pub const ALL: [Scheme; 6] = [
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
        Scheme::Slerp,
        Scheme::Nlerp,
        Scheme::MinAccel,
    ];

    /// The scheme's name on the command line and in output.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Hermite => "hermite",
            Scheme::Squad => "squad",
            Scheme::Bezier => "bezier",
            Scheme::Slerp => "slerp",
            Scheme::Nlerp => "nlerp",
            Scheme::MinAccel => "minaccel",
        }
    }

    /// The tangent rule the scheme takes unless told otherwise: Nam & Kim's for `hermite`,
    /// whose construction (and error, second order) is theirs, the fourth-order `spline` for
    /// the others (docs/schemes.md).
    pub fn tangent(self) -> TangentRule {
        match self {
            Scheme::Hermite => TangentRule::NamKim,
            _ => TangentRule::Spline,
        }
    }

    /// slerp and nlerp: each segment is its two keys' alone, without tangents (positions are
    /// linear between keys, reduce has no velocities to choose).
    pub(crate) fn is_keys_only(self) -> bool {
        matches!(self, Scheme::Slerp | Scheme::Nlerp)
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl std::str::FromStr for Scheme {
    type Err = crate::InputError;

    fn from_str(s: &str) -> Result<Scheme, crate::InputError> {
        Scheme::ALL
            .into_iter()
            .find(|x| x.name() == s)
            .ok_or_else(|| {
                crate::error::input_err!(
                    "expected a scheme from hermite, squad, bezier, slerp, nlerp, minaccel, found \"{s}\""
                )
            })
    }
}

/// What shapes a track's curve besides its keys.
///
/// ```
/// use inbetween::{CurveOptions, Ends, Fps, Scheme};
///
/// let opts = CurveOptions {
///     scheme: Scheme::Squad,
///     ends: Ends::Rest.into(),
///     ..CurveOptions::default()
/// };
/// assert_eq!(opts.grid_rate, Fps::DEFAULT);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveOptions {
    /// The interpolation scheme.
    pub scheme: Scheme,
    /// Hermite's blending function (hermite only).
    pub blend: Blend,
    /// How quaternion signs of consecutive keys are treated.
    pub path: PathMode,
    /// End tangents: the rule, and given end velocities (which override the track's own).
    pub ends: EndConditions,
    /// minaccel's grid rate: the grid has at least this many points per second (interp uses
    /// its output rate, so that every frame is a grid point or between two).
    pub grid_rate: Fps,
    /// Kochanek–Bartels tension, continuity and bias of the keys without their own
    /// ([`crate::Track::with_key_tcb`]); zero gives the ordinary tangents. minaccel refuses
    /// non-zero values.
    pub tcb: Tcb,
    /// The tangent of an interior key without its own velocity or TCB values; `None`: the
    /// scheme's own ([`Scheme::tangent`]).
    pub tangent: Option<TangentRule>,
}

impl Default for CurveOptions {
    /// bezier, cubic blend (for hermite), shortest path, chord ends, 30 fps grid, zero TCB,
    /// each scheme's own tangent rule.
    fn default() -> CurveOptions {
        CurveOptions {
            scheme: Scheme::Bezier,
            blend: Blend::Cubic,
            path: PathMode::Shortest,
            ends: EndConditions::default(),
            grid_rate: Fps::DEFAULT,
            tcb: Tcb::ZERO,
            tangent: None,
        }
    }
}

/// Hermite blending function `f(u)` (`--blend`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Blend {
    /// `3u² − 2u³`.
    #[default]
    Cubic,
    /// `2u²` for `u < ½`, `1 − 2(1 − u)²` after.
    Quadratic,
}

impl Blend {
    /// `f(u)`, with `f(0) = 0`, `f(1) = 1`, `f'(0) = f'(1) = 0`.
    #[inline]
    pub fn f(self, u: f64) -> f64 {
        match self {
            Blend::Cubic => u * u * (3.0 - 2.0 * u),
            Blend::Quadratic => {
                if u < 0.5 {
                    2.0 * u * u
                } else {
                    let v = 1.0 - u;
                    1.0 - 2.0 * v * v
                }
            }
        }
    }
}

/// Where the blends of `seg` come closest to antipodal: the smallest `‖a + b‖` over `u ∈ [0, 1]`
/// and the `u` where it is, or `None` when [`Segment::blend_bound`] shows they cannot come within
/// 1e-6 rad of it. Samples 255 points strictly inside the segment, then refines the smallest by
/// golden-section search within `[1e-6, 1 − 1e-6]`: at `u = 0` and `u = 1` every blend has weight
/// 0 or 1 and is its first or second point whatever the geodesic, so no jump can happen there
/// (a spin whose arcs are antipodal exactly at a key, such as `--path euler` spins, is not
/// reported).
pub(crate) fn antipode_gap<S: Segment>(seg: &S) -> Option<(f64, f64)> {
    if seg.blend_bound() < std::f64::consts::PI - 1e-6 {
        return None;
    }
    const N: usize = 256;
    let (mut best_i, mut best) = (0, f64::INFINITY);
    for i in 1..N {
        let g = seg.blend_gap(i as f64 / N as f64);
        if g < best {
            (best_i, best) = (i, g);
        }
    }
    const END: f64 = 1e-6;
    let (mut lo, mut hi) = (
        ((best_i - 1) as f64 / N as f64).max(END),
        ((best_i + 1) as f64 / N as f64).min(1.0 - END),
    );
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let a = hi - r * (hi - lo);
        let b = lo + r * (hi - lo);
        if seg.blend_gap(a) < seg.blend_gap(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let u = 0.5 * (lo + hi);
    let g = seg.blend_gap(u);
    Some(if g < best {
        (g, u)
    } else {
        (best, best_i as f64 / N as f64)
    })
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Shared checks for every scheme's unit tests.

    use super::*;
    use crate::tangent::{EndConditions, PathMode};
    use crate::track::Track;
    use glam::DVec3;

    pub(crate) fn keys(times: &[f64], quats: &[DQuat], ends: EndConditions) -> Knots {
        let track = Track::new(times.to_vec(), quats.to_vec()).expect("a valid track");
        Knots::new(&track, PathMode::Shortest, ends)
    }

    pub(crate) fn sample_track() -> Track {
        let q = [
            DQuat::IDENTITY,
            DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 1.1),
            DQuat::from_euler(glam::EulerRot::ZYX, 0.9, -0.4, 1.3),
            DQuat::from_rotation_x(2.6),
        ];
        Track::new(vec![0.0, 0.5, 1.25, 2.0], q.to_vec()).expect("a valid track")
    }

    pub(crate) fn sample_keys() -> Knots {
        Knots::new(
            &sample_track(),
            PathMode::Shortest,
            EndConditions::default(),
        )
    }

    /// Frames gathered across segments into shared blocks of lanes are the bits `frames` gives,
    /// whatever shares their block (a hold's degenerate blends included).
    pub(crate) fn check_gathered<const K: usize, S>(k: &Knots, blend: Blend)
    where
        S: Segment<Pending = blend4::Pending<K>>,
    {
        for s in 0..k.segments() {
            let seg = S::new(k, s, blend);
            for (u0, du, n) in [(0.3, 0.7, 1), (0.1, 0.4, 2), (0.05, 0.3, 3), (0.9, 0.05, 2)] {
                let want: Vec<DQuat> = seg.frames(u0, du).take(n).collect();
                let lanes = seg.gather(u0, du, n).expect("the scheme has lanes");
                for m in 0..n {
                    // Lane m of a block whose other lanes are a hold: every point the same.
                    let hold = blend4::Pending {
                        points: [lanes[m].points[0]; K],
                        f: 0.5,
                    };
                    let mut block = [hold; 4];
                    block[(m + s) % 4] = lanes[m];
                    let got = S::finish4(&block)[(m + s) % 4];
                    assert_eq!(
                        got.to_array().map(f64::to_bits),
                        want[m].to_array().map(f64::to_bits),
                        "segment {s}, frame {m} of {n}"
                    );
                }
            }
        }
    }

    /// Keys hit, forward differences agree with direct evaluation, unit norm.
    pub(crate) fn check_segment<S: Segment>(k: &Knots, blend: Blend) {
        for s in 0..k.segments() {
            let seg = S::new(k, s, blend);
            assert!(
                (seg.eval(0.0) - k.quats[s]).length() < 1e-14,
                "segment {s} start"
            );
            assert!(
                (seg.eval(1.0) - k.quats[s + 1]).length() < 1e-14,
                "segment {s} end"
            );
            let n = 997;
            let du = 1.0 / n as f64;
            let u0 = 0.25 * du;
            for (j, q) in seg.frames(u0, du).take(n).enumerate() {
                let direct = seg.eval(u0 + j as f64 * du);
                assert!((q - direct).length() < 1e-13, "segment {s} frame {j}");
                assert!((q.length() - 1.0).abs() < 1e-13);
            }
        }
    }

    /// `dQ/du` at `u` by central differences (one-sided at the ends).
    pub(crate) fn deriv<S: Segment>(seg: &S, u: f64) -> DQuat {
        let h = 1e-6;
        if u <= 0.0 {
            (seg.eval(u + h) * 4.0 - seg.eval(u + 2.0 * h) - seg.eval(u) * 3.0) / (2.0 * h)
        } else if u >= 1.0 {
            (seg.eval(u) * 3.0 - seg.eval(u - h) * 4.0 + seg.eval(u - 2.0 * h)) / (2.0 * h)
        } else {
            (seg.eval(u + h) - seg.eval(u - h)) / (2.0 * h)
        }
    }
}
