//! `reduce` on one track: 1200 frames at 120 fps (10 s) of smooth motion with 0.05° of noise,
//! bezier with velocities at 0.5°, greedy and optimal (the six velocity estimates every reduced
//! track computes first are part of it). The end-to-end figure (a 60-joint, 60 s BVH clip) is in
//! docs/performance.md.
//! `cargo bench --bench reduce`

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::{DQuat, DVec3};
use inbetween::reduce::{Method, ReduceOptions, reduce};
use inbetween::{CurveOptions, Fps, Scheme};
use std::hint::black_box;

/// `n` frames at 120 fps: a smooth turn about changing axes with deterministic jitter.
fn frames(n: usize) -> (Vec<f64>, Vec<DQuat>) {
    let times: Vec<f64> = (0..n).map(|i| i as f64 / 120.0).collect();
    let quats = times
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let j = i as f64;
            let jitter = DVec3::new((12.9898 * j).sin(), (78.233 * j).sin(), (37.719 * j).sin())
                * 0.05f64.to_radians();
            DQuat::from_scaled_axis(jitter)
                * DQuat::from_euler(
                    glam::EulerRot::ZYX,
                    0.8 * (0.7 * t).sin() + 0.3 * t,
                    0.5 * (1.3 * t).cos(),
                    0.4 * (0.45 * t).sin(),
                )
        })
        .collect();
    (times, quats)
}

fn bench(c: &mut Criterion) {
    let (t, q) = frames(1200);
    let mut g = c.benchmark_group("reduce");
    g.sample_size(10);
    for method in [Method::Greedy, Method::Optimal] {
        let opts = ReduceOptions {
            curve: CurveOptions {
                scheme: Scheme::Bezier,
                grid_rate: Fps::new(120, 1).unwrap(),
                ..CurveOptions::default()
            },
            tolerance: 0.5f64.to_radians(),
            distance: None,
            translation_tolerance: None,
            velocities: true,
            method,
        };
        let name = format!("{method:?}").to_lowercase();
        g.bench_with_input(
            BenchmarkId::new("bezier_1200_frames", name),
            &opts,
            |b, o| b.iter(|| black_box(reduce(black_box(&t), black_box(&q), None, o).unwrap())),
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
