//! Same-run A/B of the frame writer, sequential vs two threads, on 10⁶ hermite frames to a
//! discarding writer: `cargo run --release --example writer_ab`.

use glam::{DQuat, DVec3};
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween::{BakeOptions, Curve, CurveOptions, Fps, FrameSink, Track, bake};
use inbetween_io::Format;
use inbetween_io::num::NumFormat;
use inbetween_io::write::{FrameWriter, Style};
use std::time::Instant;

fn main() {
    let n = 1000;
    let track = Track::new(
        (0..=n).map(f64::from).collect(),
        (0..=n)
            .map(|i| {
                let a = f64::from(i);
                DQuat::from_axis_angle(DVec3::new(a.sin(), 0.5, 1.0).normalize(), 0.3 * a)
            })
            .collect(),
    )
    .expect("a valid track");
    let fps = Fps::new(1000, 1).unwrap();
    let curve = Curve::new(&track, &CurveOptions::default()).expect("a hermite curve");
    let opts = BakeOptions {
        velocity: false,
        parallel: true,
    };
    for num in [NumFormat::Shortest, NumFormat::Fixed(9)] {
        let style = Style {
            repr: Repr::Quat,
            angles: AngleUnit::Deg,
            quat_order: QuatOrder::Wxyz,
            num,
            euler: Default::default(),
        };
        let mut times = [Vec::new(), Vec::new()];
        for _ in 0..7 {
            for (i, parallel) in [false, true].into_iter().enumerate() {
                let w = FrameWriter::new(std::io::sink(), Format::Csv, style, fps, false, false);
                let mut w = if parallel { w } else { w.sequential() };
                let t0 = Instant::now();
                bake(&curve, fps, opts, &mut w, &mut |_| {}).unwrap();
                w.finish().unwrap();
                times[i].push(t0.elapsed().as_secs_f64());
            }
        }
        for t in &mut times {
            t.sort_by(f64::total_cmp);
        }
        println!(
            "{num:?}: sequential {:.1} ms, two threads {:.1} ms (medians of 7)",
            times[0][3] * 1e3,
            times[1][3] * 1e3
        );
    }
}
