//! Reading is linear in the number of tracks: documents of 10⁴ and 10⁵ two-key tracks (CSV with
//! interleaved rows, JSON `tracks`) parsed by `inbetween_io::parse_bytes` and validated by
//! `Document::tracks`. Time per track should not grow from 10⁴ to 10⁵.
//! `cargo bench --bench tracks`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use inbetween::Fps;
use inbetween_io::{Format, ReadOptions, parse_bytes};
use std::hint::black_box;

/// `n` tracks of two keys, rows interleaved: every track's first key, then every second key.
fn csv(n: usize) -> Vec<u8> {
    let mut s = String::from("track,time,w,x,y,z\n");
    for i in 0..n {
        s.push_str(&format!("t{i},0,1,0,0,0\n"));
    }
    for i in 0..n {
        s.push_str(&format!(
            "t{i},1,0.7071067811865476,0,0.7071067811865476,0\n"
        ));
    }
    s.into_bytes()
}

/// The same `n` tracks as a JSON document.
fn json(n: usize) -> Vec<u8> {
    let tracks: Vec<String> = (0..n)
        .map(|i| {
            format!(
                "{{\"name\": \"t{i}\", \"keys\": [{{\"time\": 0, \"quat\": [1, 0, 0, 0]}}, \
                 {{\"time\": 1, \"quat\": [0.7071067811865476, 0, 0.7071067811865476, 0]}}]}}"
            )
        })
        .collect();
    format!("{{\"tracks\": [\n{}\n]}}\n", tracks.join(",\n")).into_bytes()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("read_tracks");
    g.sample_size(10);
    for n in [10_000, 100_000] {
        for (name, format, bytes) in [
            ("csv", Format::Csv, csv(n)),
            ("json", Format::Json, json(n)),
        ] {
            g.throughput(Throughput::Elements(n as u64));
            g.bench_with_input(BenchmarkId::new(name, n), &bytes, |b, bytes| {
                b.iter(|| {
                    let (doc, _) = parse_bytes(
                        bytes.clone(),
                        "bench",
                        None,
                        Some(format),
                        &ReadOptions::default(),
                    )
                    .unwrap();
                    let tracks = doc.tracks(Fps::DEFAULT).unwrap();
                    assert_eq!(tracks.len(), n);
                    black_box(tracks)
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
