//! Scheme kernels: in-betweens per second, f64, no formatting — 10³ segments × 10³ in-betweens
//! each, through the public path a front end takes ([`bake`] of a [`Curve`] into a sink that only
//! folds the frames), the curve's set-up included. `cargo bench --bench kernels`

mod support;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{DQuat, DVec3};
use inbetween::{BakeOptions, Curve, CurveOptions, FrameSink, Scheme, Track, bake};
use std::hint::black_box;
use support::{INBETWEENS, SEGMENTS, fps, track};

/// Folds every frame (so nothing is optimised away).
struct Fold(DQuat);

impl FrameSink for Fold {
    fn frame(&mut self, _k: i64, _t: f64, q: DQuat, _w: Option<DVec3>) -> std::io::Result<()> {
        self.0 += q;
        Ok(())
    }
}

/// Builds the scheme's curve through `track` and generates every in-between of every segment.
fn run(track: &Track, scheme: Scheme) -> DQuat {
    let opts = CurveOptions {
        scheme,
        ..CurveOptions::default()
    };
    let curve = Curve::new(track, &opts).expect("a valid curve");
    let mut sink = Fold(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0));
    bake(
        &curve,
        fps(),
        BakeOptions::default(),
        &mut sink,
        &mut |_| {},
    )
    .expect("no I/O");
    sink.0
}

fn bench(c: &mut Criterion) {
    let track = track(SEGMENTS);
    let mut g = c.benchmark_group("kernel");
    g.throughput(Throughput::Elements((SEGMENTS * INBETWEENS) as u64));
    g.sample_size(20);
    for scheme in [
        Scheme::Slerp,
        Scheme::Nlerp,
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
    ] {
        g.bench_function(scheme.to_string(), |b| {
            b.iter(|| black_box(run(black_box(&track), scheme)))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
