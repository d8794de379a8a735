//! minaccel solve time: the paper's Figure 7 set-up (7 keys, 32 points per interval, 193 grid
//! points) and grids of about 10³, 10⁴, 10⁵ points over the same keys.
//! `cargo bench --bench minaccel`

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::{DQuat, DVec3};
use inbetween::curve::minaccel::solve;
use inbetween::tangent::Knots;
use inbetween::{EndConditions, PathMode, Track};
use std::hint::black_box;

/// Seven keys one second apart, turning about changing axes (Figure 7 has seven keys).
pub fn figure7_keys() -> Knots {
    let quats: Vec<DQuat> = (0..7)
        .map(|i| {
            let a = i as f64;
            let axis = DVec3::new(a.sin(), (0.7 * a).cos(), 0.5).normalize();
            DQuat::from_axis_angle(axis, 0.6 * a)
        })
        .collect();
    let track = Track::new((0..7).map(f64::from).collect(), quats).expect("a valid track");
    Knots::new(&track, PathMode::Shortest, EndConditions::default())
}

fn bench(c: &mut Criterion) {
    let keys = figure7_keys();
    let mut g = c.benchmark_group("minaccel");
    // 32 points per 1 s interval: 6·32 + 1 = 193 grid points.
    g.bench_function("figure7_193_points", |b| {
        b.iter(|| black_box(solve(black_box(&keys), 32.0).unwrap()))
    });
    for points in [1_000usize, 10_000, 100_000] {
        let fps = (points as f64 / 6.0).ceil();
        g.sample_size(if points >= 100_000 { 10 } else { 20 });
        g.bench_with_input(BenchmarkId::new("grid_points", points), &fps, |b, &fps| {
            b.iter(|| black_box(solve(black_box(&keys), fps).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
