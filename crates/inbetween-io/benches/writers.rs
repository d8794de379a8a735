//! Frame writers: bytes per frame for CSV (shortest round-trip, `--precision 9`), JSON and npy,
//! and the whole library pipeline (hermite curve + CSV) on 10⁶ frames into a discarding writer.
//! `cargo bench --bench writers`

#[path = "../../inbetween/benches/support/mod.rs"]
mod support;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DQuat;
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween::{BakeOptions, Curve, CurveOptions, FrameSink, bake};
use inbetween_io::Format;
use inbetween_io::num::NumFormat;
use inbetween_io::write::{FrameWriter, NpyWriter, Style};
use std::hint::black_box;
use std::io;
use support::{fps, track};

const FRAMES: usize = 100_000;

fn style(num: NumFormat) -> Style {
    Style {
        repr: Repr::Quat,
        angles: AngleUnit::Deg,
        quat_order: QuatOrder::Wxyz,
        num,
        euler: Default::default(),
    }
}

fn frames() -> Vec<(i64, f64, DQuat)> {
    let fps = fps();
    (0..FRAMES as i64)
        .map(|k| {
            let t = fps.time_of(k);
            (
                k,
                t,
                DQuat::from_euler(glam::EulerRot::ZYX, t, 0.3 * t, -0.7 * t),
            )
        })
        .collect()
}

fn write_all(sink: &mut dyn FrameSink, frames: &[(i64, f64, DQuat)]) {
    sink.begin_track(None).unwrap();
    for &(k, t, q) in frames {
        sink.frame(k, t, q, None).unwrap();
    }
    sink.end_track().unwrap();
    sink.finish().unwrap();
}

fn bench(c: &mut Criterion) {
    let data = frames();
    let mut g = c.benchmark_group("writer");
    g.throughput(Throughput::Elements(FRAMES as u64));
    for (name, format, num) in [
        ("csv_shortest", Format::Csv, NumFormat::Shortest),
        ("csv_precision9", Format::Csv, NumFormat::Fixed(9)),
        ("json_shortest", Format::Json, NumFormat::Shortest),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut w = FrameWriter::new(io::sink(), format, style(num), fps(), false, false);
                write_all(&mut w, black_box(&data));
            })
        });
    }
    g.bench_function("npy", |b| {
        b.iter(|| {
            let mut w = NpyWriter::new(
                io::sink(),
                style(NumFormat::Shortest),
                FRAMES as u64,
                false,
                false,
            );
            write_all(&mut w, black_box(&data));
        })
    });
    g.finish();

    // End to end through the library: 10³ segments × 10³ in-betweens, hermite, CSV, discarded.
    let t = track(support::SEGMENTS);
    let mut g = c.benchmark_group("end_to_end");
    g.throughput(Throughput::Elements(
        (support::SEGMENTS * support::INBETWEENS + 1) as u64,
    ));
    g.sample_size(10);
    for (name, num) in [
        ("hermite_csv_shortest", NumFormat::Shortest),
        ("hermite_csv_precision9", NumFormat::Fixed(9)),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let curve = Curve::new(&t, &CurveOptions::default()).unwrap();
                let mut w =
                    FrameWriter::new(io::sink(), Format::Csv, style(num), fps(), false, false);
                bake(&curve, fps(), BakeOptions::default(), &mut w, &mut |_| {}).unwrap();
                w.finish().unwrap();
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
