//! `inbetween`: keyframe in-betweening for 3D orientations.
//!
//! A [`Track`] holds keyframe times and unit quaternions, validated once. A [`Curve`] is built
//! from a track and [`CurveOptions`] under any [`Scheme`] — Nam & Kim's Hermite by blending two
//! great arcs, squad, spherical Bézier, slerp, or Barr et al.'s minimal-tangential-acceleration
//! spline — and sampled at any time: rotation, world-frame angular velocity and angular
//! acceleration. [`bake()`] streams a curve's frames on an exact frame grid ([`Fps`]) into a
//! [`FrameSink`], by forward differences, as `inbetween interp` writes them.
//!
//! ```
//! use inbetween::rotation::quat::rotation_angle_between as angle;
//! use inbetween::{Curve, CurveOptions, Scheme, Track};
//! use glam::{DQuat, EulerRot};
//!
//! let keys = [(0.0, 0.0), (0.4, 90.0), (1.0, 120.0), (1.5, 300.0)];
//! let track = Track::new(
//!     keys.iter().map(|k| k.0).collect(),
//!     keys.iter()
//!         .map(|k| DQuat::from_euler(EulerRot::ZYX, f64::to_radians(k.1), 0.3, 0.0))
//!         .collect(),
//! )?;
//! for scheme in [Scheme::Hermite, Scheme::MinAccel] {
//!     let curve = Curve::new(&track, &CurveOptions { scheme, ..CurveOptions::default() })?;
//!     // Off the frame grid: any time in the span.
//!     for t in [0.0123, 0.5, 1.41421] {
//!         let q = curve.rotation(t);
//!         let w = curve.angular_velocity(t); // rad/s, world frame
//!         assert!((q.length() - 1.0).abs() < 1e-12 && w.is_finite());
//!     }
//!     // The curve passes through the keys.
//!     assert!(angle(curve.rotation(0.4), track.rotations()[1]) < 1e-12);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Layout: [`track`] (validated keys), [`tangent`] (path rule, tangents, end conditions),
//! [`curve`] (one module per scheme, and [`Curve`]), [`clock`] (exact rates and the frame-clock
//! rule), [`mod@bake`] (the frame loop), [`rotation`] (representations, Euler conventions, `log`/
//! `exp`), [`metrics`] (smoothness figures); with the `io` feature `io` (CSV, JSON and npy in
//! and out), with `chart` `chart` (SVG). The command line (`cli`, on by default) is the
//! binary's own and not part of this API.

#![warn(missing_docs, unreachable_pub)]

pub mod bake;
pub mod clock;
pub mod curve;
pub mod diff;
pub mod error;
pub mod metrics;
pub mod parallel;
mod position;
pub mod reduce;
pub mod rotation;
pub mod skeleton;
pub mod tangent;
pub mod track;

pub use bake::{BakeOptions, FrameSink, bake, bake_over};
pub use clock::Fps;
pub use curve::{Blend, Curve, CurveOptions, Scheme};
pub use error::{Error, InputError};
pub use rotation::{AngleUnit, EulerSeq, Repr};
pub use tangent::{EndConditions, Ends, PathMode, TangentRule};
pub use track::{Tcb, Track, TrackError};
