//! Helpers shared by the test targets: paths, the binary, approximate equality, and a sink that
//! collects baked frames.
#![allow(dead_code)] // each target uses a different part

use glam::{DQuat, DVec3};
use inbetween::{
    BakeOptions, Blend, Curve, CurveOptions, EndConditions, Fps, FrameSink, PathMode, Scheme,
    Track, bake,
};
use std::io;
use std::path::{Path, PathBuf};

/// The repository's `fixtures/` directory.
pub fn fixtures() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("fixtures")
}

/// The `inbetween` binary, run from the repository root.
pub fn bin() -> assert_cmd::Command {
    let mut c = assert_cmd::Command::cargo_bin("inbetween").expect("the binary is built");
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    c
}

/// The Python of the reference checkers (`target/ci-venv`, which `.ci/run` builds from
/// `fixtures/requirements.txt`), or `None` with a note that the check `what` is skipped. Where
/// INBETWEEN_REQUIRE_PYTHON_CHECKS is set (CI) a missing venv is a failure instead.
#[track_caller]
pub fn checker_python(what: &str) -> Option<PathBuf> {
    let python =
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("target/ci-venv/bin/python");
    if python.exists() {
        return Some(python);
    }
    assert!(
        std::env::var_os("INBETWEEN_REQUIRE_PYTHON_CHECKS").is_none(),
        "target/ci-venv is missing ({what})"
    );
    eprintln!("note: {what} skipped (no target/ci-venv)");
    None
}

/// Runs `python script args…` from the repository root and parses its standard output as
/// JSON, asserting it succeeded.
#[track_caller]
pub fn python_json(python: &Path, script: &str, args: &[&std::ffi::OsStr]) -> serde_json::Value {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let o = std::process::Command::new(python)
        .arg(root.join(script))
        .args(args)
        .current_dir(root)
        .output()
        .expect("python runs");
    assert!(
        o.status.success(),
        "{script}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON from the checker")
}

/// Runs `cmd`, asserts it succeeded (printing its stderr if not), and returns its stdout.
#[track_caller]
pub fn stdout_of(cmd: &mut assert_cmd::Command) -> String {
    let out = cmd.output().expect("the binary runs");
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// A BVH text's rows after the `Frame Time` line, as numbers.
pub fn bvh_rows(text: &str) -> Vec<Vec<f64>> {
    let body = text.split_once("Frame Time:").unwrap().1;
    body.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split_ascii_whitespace()
                .map(|x| x.parse().unwrap())
                .collect()
        })
        .collect()
}

/// Runs `cmd`, asserts it exited with `code` (printing its stderr if not), and returns its
/// stderr.
#[track_caller]
pub fn stderr_of(cmd: &mut assert_cmd::Command, code: i32) -> String {
    let out = cmd.output().expect("the binary runs");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "{err}");
    err
}

/// The maths crate's test helpers (angles between rotations, closeness, CSV tables), shared
/// with its library tests rather than copied.
#[allow(dead_code, unreachable_pub)]
#[path = "../../../inbetween/tests/library/support.rs"]
mod library;
#[allow(unused_imports)]
pub use library::{
    api_keys, api_options, api_track, assert_rot_close, assert_vec_close, read_table, rot_angle,
};

/// One baked frame: number, time, rotation, angular velocity (when asked for).
pub type Frame = (i64, f64, DQuat, Option<DVec3>);

/// Frames collected in memory.
#[derive(Default)]
pub struct Collect {
    /// The frames, in order.
    pub frames: Vec<Frame>,
}

impl FrameSink for Collect {
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        self.frames.push((k, time, q, omega));
        Ok(())
    }
}

/// A valid track (panics otherwise).
pub fn track(times: Vec<f64>, quats: Vec<DQuat>) -> Track {
    Track::new(times, quats).expect("a valid track")
}

/// Everything `interp` needs besides the track, as one struct for tests.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    pub fps: Fps,
    pub scheme: Scheme,
    pub blend: Blend,
    pub path: PathMode,
    pub ends: EndConditions,
    pub velocity: bool,
    pub parallel: bool,
}

impl Settings {
    /// The curve options (minaccel's grid at the output rate, as `interp`).
    pub fn curve(&self) -> CurveOptions {
        CurveOptions {
            scheme: self.scheme,
            blend: self.blend,
            path: self.path,
            ends: self.ends,
            grid_rate: self.fps,
            tcb: Default::default(),
            tangent: None,
        }
    }
}

/// Settings with the cubic blend, the shortest path and two-thread generation allowed.
pub fn settings(scheme: Scheme, fps: &str, ends: EndConditions) -> Settings {
    Settings {
        fps: Fps::parse(fps).unwrap(),
        scheme,
        blend: Blend::Cubic,
        path: PathMode::Shortest,
        ends,
        velocity: false,
        parallel: true,
    }
}

/// The curve of `t` under `scheme` with the given ends (cubic blend, shortest path, 30 fps grid).
pub fn curve(t: &Track, scheme: Scheme, path: PathMode, ends: EndConditions) -> Curve {
    let opts = CurveOptions {
        scheme,
        path,
        ends,
        ..CurveOptions::default()
    };
    Curve::new(t, &opts).expect("a curve")
}

/// Bakes one track as `interp` does: its frames `(k, t, q)` and the warnings.
pub fn interpolate(t: &Track, s: &Settings) -> (Vec<(i64, f64, DQuat)>, Vec<String>) {
    let (frames, warnings) = bake_frames(t, s);
    (
        frames.into_iter().map(|(k, t, q, _)| (k, t, q)).collect(),
        warnings,
    )
}

/// Bakes one track as `interp` does, with velocities when `s.velocity`.
pub fn bake_frames(t: &Track, s: &Settings) -> (Vec<Frame>, Vec<String>) {
    let curve = Curve::new(t, &s.curve()).expect("a curve");
    let mut sink = Collect::default();
    let mut warnings = Vec::new();
    let opts = BakeOptions {
        velocity: s.velocity,
        parallel: s.parallel,
    };
    bake(
        &curve,
        s.fps,
        opts,
        &mut sink,
        &mut |w: &inbetween::error::Message| warnings.push(w.to_string()),
    )
    .unwrap();
    (sink.frames, warnings)
}
