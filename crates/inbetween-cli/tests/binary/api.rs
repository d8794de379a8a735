//! The library's crate-root API against the binary: at frame times a [`Curve`] gives the
//! rotations and angular velocities `interp` writes, and [`bake`] streams the same frames. (The
//! library's own API tests are in crates/inbetween/tests/library.)

use crate::support::{
    Collect, api_keys as keys, api_options as options, api_track as track, assert_rot_close,
    assert_vec_close, bin, stdout_of,
};
use glam::{DQuat, DVec3};
use inbetween::{BakeOptions, Curve, Fps, Scheme, bake};

/// `interp` on the same keys: `(time, rotation, angular velocity in rad/s)` per frame.
fn interp(scheme: Scheme, fps: &str) -> Vec<(f64, DQuat, DVec3)> {
    let (times, quats) = keys();
    let mut csv = String::from("time,w,x,y,z\n");
    for (t, q) in times.iter().zip(&quats) {
        // `{:?}` is Rust's shortest round-trip form: the binary reads the same f64.
        csv += &format!("{t:?},{:?},{:?},{:?},{:?}\n", q.w, q.x, q.y, q.z);
    }
    let text = stdout_of(
        bin()
            .args(["interp", "-", "--velocity", "--angles", "rad"])
            .args(["--scheme", &scheme.to_string(), "--fps", fps])
            .args(["--start-velocity", "0,0.5,-1"])
            .write_stdin(csv),
    );
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("frame,time,w,x,y,z,wx,wy,wz"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            let q = DQuat::from_xyzw(v[3], v[4], v[5], v[2]);
            (v[1], q, DVec3::new(v[6], v[7], v[8]))
        })
        .collect()
}

#[test]
fn curves_at_frame_times_are_what_interp_writes() {
    let track = track();
    for fps in ["30", "29.97"] {
        let rate: Fps = fps.parse().unwrap();
        for scheme in Scheme::ALL {
            let curve = Curve::new(&track, &options(scheme, rate)).unwrap();
            let frames = interp(scheme, fps);
            assert_eq!(
                frames.len() as u64,
                rate.frame_count(0.0, 2.0),
                "{scheme} {fps}"
            );
            for (t, q, w) in frames {
                let what = format!("{scheme} at {fps} fps, t = {t}");
                assert_rot_close(curve.rotation(t), q, 1e-12, &what);
                assert_vec_close(curve.angular_velocity(t), w, 1e-9, &what);
            }
        }
    }
}

#[test]
fn bake_streams_the_frames_interp_writes() {
    let track = track();
    let fps: Fps = "29.97".parse().unwrap();
    for scheme in Scheme::ALL {
        let curve = Curve::new(&track, &options(scheme, fps)).unwrap();
        let mut sink = Collect::default();
        let opts = BakeOptions {
            velocity: true,
            parallel: false,
        };
        bake(&curve, fps, opts, &mut sink, &mut |w| panic!("{w}")).unwrap();
        let want = interp(scheme, "29.97");
        assert_eq!(sink.frames.len(), want.len());
        for ((k, t, q, w), (tw, qw, ww)) in sink.frames.iter().zip(&want) {
            assert_eq!((t, fps.time_of(*k)), (tw, *t), "{scheme} frame {k}");
            // The binary normalises the keys it reads: the same curve up to the last bits.
            let what = format!("{scheme} frame {k}");
            assert_rot_close(*q, *qw, 1e-14, &what);
            assert_vec_close(w.unwrap(), *ww, 1e-12, &what);
        }
    }
}
