//! Scheme kernels: in-betweens per second, f64, no formatting — 10³ segments × 10³ in-betweens
//! each, per-segment set-up included. `cargo bench --bench kernels`

mod support;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DQuat;
use inbetween::curve::bezier::Bezier;
use inbetween::curve::hermite::Hermite;
use inbetween::curve::slerp::Slerp;
use inbetween::curve::squad::Squad;
use inbetween::curve::{Blend, Segment};
use inbetween::tangent::{EndConditions, Knots, PathMode};
use std::hint::black_box;
use support::{INBETWEENS, SEGMENTS, track};

/// Generates every in-between of every segment and folds them (so nothing is optimised away).
fn run<S: Segment>(keys: &Knots) -> DQuat {
    let du = 1.0 / INBETWEENS as f64;
    let mut acc = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    for s in 0..keys.segments() {
        let seg = S::new(keys, s, Blend::Cubic);
        for q in seg.frames(0.0, du).take(INBETWEENS) {
            acc += q;
        }
    }
    acc
}

fn bench(c: &mut Criterion) {
    let keys = Knots::new(
        &track(SEGMENTS),
        PathMode::Shortest,
        EndConditions::default(),
    );
    let mut g = c.benchmark_group("kernel");
    g.throughput(Throughput::Elements((SEGMENTS * INBETWEENS) as u64));
    g.sample_size(20);
    g.bench_function("slerp", |b| {
        b.iter(|| black_box(run::<Slerp>(black_box(&keys))))
    });
    g.bench_function("hermite", |b| {
        b.iter(|| black_box(run::<Hermite>(black_box(&keys))))
    });
    g.bench_function("squad", |b| {
        b.iter(|| black_box(run::<Squad>(black_box(&keys))))
    });
    g.bench_function("bezier", |b| {
        b.iter(|| black_box(run::<Bezier>(black_box(&keys))))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
