//! Sampling a `Curve` at arbitrary times, as a game engine does: `rotation` and
//! `angular_velocity` at 10⁵ times off every key, on 10³ segments; and `rotations` of the same
//! times sorted, against `rotation` one by one. `cargo bench --bench sample`

mod support;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{DQuat, DVec3};
use inbetween::{Curve, CurveOptions, Scheme};
use std::hint::black_box;
use support::{SEGMENTS, track};

const SAMPLES: usize = 100_000;

fn bench(c: &mut Criterion) {
    let track = track(SEGMENTS);
    // Off the keys and off any frame grid: an irrational step through the span.
    let times: Vec<f64> = (0..SAMPLES)
        .map(|i| (i as f64 * 0.618_033_988_749_895 * SEGMENTS as f64 / SAMPLES as f64) % 1000.0)
        .collect();
    let mut g = c.benchmark_group("sample");
    g.throughput(Throughput::Elements(SAMPLES as u64));
    g.sample_size(10);
    for scheme in [
        Scheme::Slerp,
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
    ] {
        let opts = CurveOptions {
            scheme,
            ..CurveOptions::default()
        };
        let curve = Curve::new(&track, &opts).unwrap();
        g.bench_function(format!("{scheme}_rotation"), |b| {
            b.iter(|| {
                let mut acc = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
                for &t in &times {
                    acc += curve.rotation(black_box(t));
                }
                black_box(acc)
            })
        });
        // Sorted times: one by one, and all at once (`Curve::rotations`, four at a time).
        let mut sorted = times.clone();
        sorted.sort_by(f64::total_cmp);
        g.bench_function(format!("{scheme}_rotation_sorted"), |b| {
            b.iter(|| {
                let mut acc = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
                for &t in &sorted {
                    acc += curve.rotation(black_box(t));
                }
                black_box(acc)
            })
        });
        let mut out = vec![DQuat::IDENTITY; SAMPLES];
        g.bench_function(format!("{scheme}_rotations_sorted"), |b| {
            b.iter(|| {
                curve.rotations(black_box(&sorted), &mut out);
                black_box(out[SAMPLES / 2])
            })
        });
        g.bench_function(format!("{scheme}_angular_velocity"), |b| {
            b.iter(|| {
                let mut acc = DVec3::ZERO;
                for &t in &times {
                    acc += curve.angular_velocity(black_box(t));
                }
                black_box(acc)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
