//! What the asset targets share: a sink that checks every frame, and the pipeline from a read
//! document to baked frames (slerp, at the document's rate or 30 fps), bounded in frames so that
//! each run stays short (a harness limit, not the tool's).

use glam::{DQuat, DVec3};
use inbetween_io::document::Document;
use inbetween::{BakeOptions, Curve, CurveOptions, FrameSink, Fps, Scheme, bake};
use std::io;

/// Every frame finite, unit, its time finite; positions finite.
pub struct Check;

impl FrameSink for Check {
    fn frame(&mut self, _k: i64, t: f64, q: DQuat, w: Option<DVec3>) -> io::Result<()> {
        assert!(t.is_finite(), "time {t}");
        assert!(q.is_finite(), "frame {q}");
        assert!((q.length() - 1.0).abs() < 1e-6, "|q| = {}", q.length());
        if let Some(w) = w {
            assert!(w.is_finite(), "velocity {w}");
        }
        Ok(())
    }
    fn frame_at(
        &mut self,
        k: i64,
        t: f64,
        q: DQuat,
        w: Option<DVec3>,
        p: DVec3,
    ) -> io::Result<()> {
        assert!(p.is_finite(), "position {p}");
        self.frame(k, t, q, w)
    }
}

/// The document's tracks baked with `scheme` at `fps`, when they validate and span at most
/// `cap` frames in all; a failure to validate must be an input error (it is a `Result`).
pub fn bake_document(doc: &Document, fps: Fps, scheme: Scheme, cap: f64) {
    let Ok(tracks) = doc.tracks(fps) else {
        return;
    };
    let mut total = 0.0;
    for t in &tracks {
        let (a, b) = t.span();
        assert!(a.is_finite() && b.is_finite(), "span {a} {b}");
        if !fps.in_range(a) || !fps.in_range(b) {
            return;
        }
        total += (b - a) * fps.as_f64() + 1.0;
    }
    if total > cap {
        return;
    }
    let opts = CurveOptions {
        scheme,
        grid_rate: fps,
        ..CurveOptions::default()
    };
    for t in &tracks {
        let Ok(curve) = Curve::new(t, &opts) else {
            return;
        };
        bake(&curve, fps, BakeOptions::default(), &mut Check, &mut |_| {}).expect("no I/O error");
    }
}
