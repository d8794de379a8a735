//! Helpers of the library's tests: the fixtures' path, approximate equality, the scipy tables, a
//! sink that collects baked frames, and baking a track as `interp` does. (The binary's tests
//! have their own, in crates/inbetween-cli/tests/support.)

use glam::{DQuat, DVec3, EulerRot};
use inbetween::{
    BakeOptions, Curve, CurveOptions, EndConditions, Ends, Fps, FrameSink, PathMode, Scheme, Track,
    bake,
};
use std::io;
use std::path::{Path, PathBuf};

/// The repository's `fixtures/` directory.
pub fn fixtures() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("fixtures")
}

/// Angle between two rotations in radians (q and −q are the same rotation).
/// The pure quaternion `(0, v)` times `q`: `q̇ = (0, ω)·q / 2` for a world-frame rate `ω`.
pub fn pure_mul(v: DVec3, q: DQuat) -> DQuat {
    DQuat::from_xyzw(v.x, v.y, v.z, 0.0) * q
}

pub fn rot_angle(a: DQuat, b: DQuat) -> f64 {
    inbetween::rotation::quat::rotation_angle_between(a, b)
}

/// Asserts that two rotations are within `tol` radians, printing both and the angle.
#[track_caller]
pub fn assert_rot_close(a: DQuat, b: DQuat, tol: f64, what: &str) {
    let d = rot_angle(a, b);
    assert!(
        d <= tol,
        "{what}: {a} vs {b}: {d:e} rad apart (tolerance {tol:e})"
    );
}

/// Asserts `|a − b| ≤ rel·max(|a|, |b|, 1)`, printing both and the difference.
#[track_caller]
pub fn assert_vec_close(a: DVec3, b: DVec3, rel: f64, what: &str) {
    let d = (a - b).length();
    let scale = a.length().max(b.length()).max(1.0);
    assert!(
        d <= rel * scale,
        "{what}: {a} vs {b}: |difference| {d:e} (tolerance {:e})",
        rel * scale
    );
}

/// Reads a CSV file with a header into rows of strings keyed by column name.
pub fn read_table(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut rdr = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let headers = rdr.headers().unwrap().clone();
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            headers
                .iter()
                .zip(r.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

/// Frames collected in memory: number, time, rotation, angular velocity (when asked for).
#[derive(Default)]
pub struct Collect {
    /// The frames, in order.
    pub frames: Vec<(i64, f64, DQuat, Option<DVec3>)>,
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

/// What [`interpolate`] needs besides the track (the cubic blend).
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    pub fps: Fps,
    pub scheme: Scheme,
    pub path: PathMode,
    pub ends: EndConditions,
}

/// Settings with the shortest path.
pub fn settings(scheme: Scheme, fps: &str, ends: EndConditions) -> Settings {
    Settings {
        fps: Fps::parse(fps).unwrap(),
        scheme,
        path: PathMode::Shortest,
        ends,
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

/// Bakes one track as `interp` does (minaccel's grid at the output rate, two-thread generation
/// allowed, no velocities): its frames `(k, t, q)` and the warnings.
pub fn interpolate(t: &Track, s: &Settings) -> (Vec<(i64, f64, DQuat)>, Vec<String>) {
    let opts = CurveOptions {
        scheme: s.scheme,
        path: s.path,
        ends: s.ends,
        grid_rate: s.fps,
        ..CurveOptions::default()
    };
    let curve = Curve::new(t, &opts).expect("a curve");
    let mut sink = Collect::default();
    let mut warnings = Vec::new();
    let opts = BakeOptions {
        velocity: false,
        parallel: true,
    };
    bake(
        &curve,
        s.fps,
        opts,
        &mut sink,
        &mut |w: &inbetween::error::Message| warnings.push(w.to_string()),
    )
    .unwrap();
    let frames = sink
        .frames
        .into_iter()
        .map(|(k, t, q, _)| (k, t, q))
        .collect();
    (frames, warnings)
}

/// The API tests' keys (the library's and the binary's api.rs): five keys, unevenly spaced,
/// turning about every axis (one step over 90°).
pub fn api_keys() -> (Vec<f64>, Vec<DQuat>) {
    let times = vec![0.0, 0.37, 0.9, 1.55, 2.0];
    let quats = [
        (0.0, 0.0, 0.0),
        (0.9, -0.3, 0.2),
        (1.4, 0.5, -0.6),
        (2.9, 0.1, 0.4),
        (3.3, -0.2, 1.1),
    ]
    .iter()
    .map(|&(a, b, c)| DQuat::from_euler(EulerRot::ZYX, a, b, c))
    .collect();
    (times, quats)
}

pub fn api_track() -> Track {
    let (t, q) = api_keys();
    Track::new(t, q).unwrap()
}

pub fn api_options(scheme: Scheme, fps: Fps) -> CurveOptions {
    CurveOptions {
        scheme,
        ends: EndConditions {
            ends: Ends::Chord,
            start: Some(DVec3::new(0.0, 0.5, -1.0)),
            end: None,
        },
        grid_rate: fps,
        ..CurveOptions::default()
    }
}
