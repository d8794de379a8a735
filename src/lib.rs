//! `inbetween`: keyframe in-betweening for 3D orientations.
//!
//! The library does the work; the binary (`src/main.rs`) parses arguments, calls
//! [`cmd`], and maps errors to exit codes. Layout:
//!
//! - [`rotation`]: representations and conversions (quaternions, scipy-style Euler sequences on
//!   glam's `EulerRot`, matrices, axis-angle, rotation vectors), and quaternion `log`/`exp`.
//! - [`keys`]: keyframe documents and validated tracks.
//! - [`clock`]: exact rational frame rates and the frame grid.
//! - [`io`]: CSV and JSON readers and writers, atomic output.
//! - [`cli`], [`cmd`]: the command line.

pub mod analyze;
pub mod cli;
pub mod clock;
pub mod cmd;
pub mod error;
pub mod io;
pub mod keys;
pub mod motion;
pub mod plot;
pub mod rotation;

pub use error::InputError;
pub mod curve;
pub mod interp;
pub mod tangent;
