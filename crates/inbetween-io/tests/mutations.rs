//! A bounded mutation test of the FBX and USD readers (docs/reliability.md, *Untrusted
//! folders*): every fixture of `fixtures/fbx` and `fixtures/usd` (text, usdc and usdz; a usdc
//! also cut at every length) mutated a few hundred ways
//! with a fixed seed — bytes flipped, the file cut short, ranges repeated or deleted, numbers
//! and lengths made huge, deep nesting spliced in — and read. Each read must return a document
//! or an input error: no panic (caught and named with its mutation), no abort, and each within
//! a few seconds, allocating at most [`memory_bound`] at a time on its thread. Deterministic,
//! so a failure reproduces; CI runs it in seconds.

use inbetween_io::{Format, ReadOptions, parse_bytes};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The system allocator, counting the bytes each thread holds and the most it held.
struct Counting;

thread_local! {
    static HELD: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = HELD.try_with(|h| {
            h.set(h.get() + layout.size());
            let _ = PEAK.try_with(|p| p.set(p.get().max(h.get())));
        });
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        let _ = HELD.try_with(|h| h.set(h.get().saturating_sub(layout.size())));
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most a read of `len` bytes may hold at once: what the binary USD reader's budget allows
/// (64 times the file and 64 MiB) and as much again for the document and its copies.
fn memory_bound(len: usize) -> usize {
    2 * (64 * len + (64 << 20))
}

/// xorshift64*: a fixed, dependency-free sequence.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One mutation of `bytes` (its description, the bytes).
fn mutate(bytes: &[u8], rng: &mut Rng, text: bool) -> (String, Vec<u8>) {
    let mut b = bytes.to_vec();
    let n = b.len();
    let at = rng.below(n);
    match rng.below(8) {
        0 => {
            let k = 1 + rng.below(8);
            for _ in 0..k {
                let i = rng.below(n);
                b[i] ^= 1 << rng.below(8);
            }
            (format!("{k} bits flipped"), b)
        }
        1 => {
            b.truncate(at);
            (format!("cut at {at}"), b)
        }
        2 => {
            let len = 1 + rng.below(64);
            let end = (at + len).min(n);
            let piece = b[at..end].to_vec();
            let times = 1 + rng.below(50);
            for _ in 0..times {
                b.splice(at..at, piece.iter().copied());
            }
            (format!("{len} bytes at {at} repeated {times} times"), b)
        }
        3 => {
            let end = (at + 1 + rng.below(256)).min(n);
            b.drain(at..end);
            (format!("bytes {at}..{end} deleted"), b)
        }
        4 if !text => {
            // A little-endian u32 or u64 made huge: array lengths, offsets, counts.
            let wide = rng.below(2) == 1;
            let width = if wide { 8 } else { 4 };
            if at + width <= n {
                let v: u64 = [u64::MAX, 1 << 31, 1 << 40, 0x7fff_ffff][rng.below(4)];
                b[at..at + width].copy_from_slice(&v.to_le_bytes()[..width]);
            }
            (format!("{width} bytes at {at} made huge"), b)
        }
        4 => {
            // A number made huge, tiny or not a number.
            let with = [
                "1e308",
                "-1e308",
                "1e-320",
                "nan",
                "inf",
                "99999999999999999999",
            ];
            let w = with[rng.below(with.len())];
            let digit = b[at..].iter().position(u8::is_ascii_digit).map(|d| at + d);
            if let Some(d) = digit {
                b.splice(d..d + 1, w.bytes());
            }
            (format!("a number at {at} made {w}"), b)
        }
        5 if text => {
            let depth = 100 + rng.below(5000);
            let open = ["(", "[", "def \"a\" {\n"][rng.below(3)];
            let nest = open.repeat(depth);
            b.splice(at..at, nest.bytes());
            (format!("{depth} levels of {open:?} at {at}"), b)
        }
        5 => {
            // A byte range copied over another (FBX node records pointing anywhere).
            let from = rng.below(n);
            let len = (1 + rng.below(32)).min(n - from).min(n - at);
            let piece = b[from..from + len].to_vec();
            b[at..at + len].copy_from_slice(&piece);
            (format!("{len} bytes from {from} copied to {at}"), b)
        }
        6 => {
            let junk: Vec<u8> = (0..1 + rng.below(32)).map(|_| rng.next() as u8).collect();
            let len = junk.len();
            b.splice(at..at, junk);
            (format!("{len} random bytes inserted at {at}"), b)
        }
        _ => {
            // Two mutations.
            let (a, once) = mutate(bytes, rng, text);
            let (c, twice) = mutate(&once, rng, text);
            (format!("{a}, then {c}"), twice)
        }
    }
}

fn fixtures(dir: &str, ext: &str) -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(dir);
    let mut found = Vec::new();
    for sub in [root.clone(), root.join("real")] {
        let Ok(entries) = std::fs::read_dir(&sub) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.extension().is_some_and(|e| e == ext) {
                found.push(p);
            }
        }
    }
    found.sort();
    assert!(!found.is_empty(), "no {ext} fixtures in {}", root.display());
    found
}

/// Reads every mutation of every fixture; returns how many were read and how many refused.
fn run(files: &[PathBuf], format: Format, per_file: usize, seed: u64) -> (usize, usize) {
    let mut rng = Rng(seed);
    let (mut read, mut refused) = (0, 0);
    for file in files {
        let text = format == Format::Usd && file.extension().is_some_and(|e| e == "usda");
        let bytes = std::fs::read(file).unwrap();
        for k in 0..per_file {
            let (what, mutated) = mutate(&bytes, &mut rng, text);
            let (len, t) = (mutated.len(), Instant::now());
            HELD.with(|h| PEAK.with(|p| p.set(h.get())));
            let before = HELD.with(Cell::get);
            let result = std::panic::catch_unwind(|| {
                parse_bytes(
                    mutated,
                    "m",
                    Some(file),
                    Some(format),
                    &ReadOptions::default(),
                )
                .map(|_| ())
            });
            let took = t.elapsed();
            let peak = PEAK.with(Cell::get) - before;
            assert!(
                peak <= memory_bound(len),
                "{} mutation {k} ({what}): {peak} bytes held at once",
                file.display()
            );
            match result {
                Ok(Ok(())) => read += 1,
                Ok(Err(inbetween::Error::Input(e))) => {
                    assert!(
                        e.message().len() < 2000,
                        "{}: {what}: message of {} bytes",
                        file.display(),
                        e.message().len()
                    );
                    refused += 1
                }
                Ok(Err(e)) => panic!(
                    "{} mutation {k} ({what}): not an input error: {e}",
                    file.display()
                ),
                Err(_) => panic!(
                    "{} mutation {k} ({what}): the reader panicked",
                    file.display()
                ),
            }
            assert!(
                took < Duration::from_secs(5),
                "{} mutation {k} ({what}): {took:?}",
                file.display()
            );
        }
    }
    (read, refused)
}

#[test]
fn mutated_usd_layers_are_read_or_refused() {
    let files = fixtures("usd", "usda");
    let (read, refused) = run(&files, Format::Usd, 1500, 0x5eed_0001);
    eprintln!("usd: {} files, {read} read, {refused} refused", files.len());
    // The mutations reach both outcomes (a test that only ever refused would prove little).
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}

#[test]
fn mutated_binary_usd_is_read_or_refused() {
    let mut files = fixtures("usd", "usdc");
    files.extend(fixtures("usd", "usdz"));
    let (read, refused) = run(&files, Format::Usd, 400, 0x5eed_0003);
    eprintln!(
        "usdc/usdz: {} files, {read} read, {refused} refused",
        files.len()
    );
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}

/// A usdc crate cut at every length (its table of contents is at the end): each an input
/// error, none a panic, each quick and small.
#[test]
fn every_truncation_of_a_usdc_is_refused() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/usd/skel_ntsc.usdc");
    let bytes = std::fs::read(&file).unwrap();
    for n in 0..bytes.len() {
        let t = Instant::now();
        HELD.with(|h| PEAK.with(|p| p.set(h.get())));
        let before = HELD.with(Cell::get);
        let result = std::panic::catch_unwind(|| {
            parse_bytes(
                bytes[..n].to_vec(),
                "cut.usdc",
                None,
                Some(Format::Usd),
                &ReadOptions::default(),
            )
            .map(|_| ())
        });
        match result {
            Ok(Err(inbetween::Error::Input(e))) => {
                assert!(e.message().starts_with("cut.usdc"), "{}", e.message())
            }
            Ok(other) => panic!("cut at {n}: {other:?}"),
            Err(_) => panic!("cut at {n}: the reader panicked"),
        }
        assert!(t.elapsed() < Duration::from_secs(2), "cut at {n}");
        let peak = PEAK.with(Cell::get) - before;
        assert!(peak <= memory_bound(n), "cut at {n}: {peak} bytes");
    }
}

#[test]
fn mutated_fbx_scenes_are_read_or_refused() {
    let files = fixtures("fbx", "fbx");
    let (read, refused) = run(&files, Format::Fbx, 500, 0x5eed_0002);
    eprintln!("fbx: {} files, {read} read, {refused} refused", files.len());
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}
