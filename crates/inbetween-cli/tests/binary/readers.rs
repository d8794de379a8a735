//! The readers on hostile input (issue 11): inputs read with a size limit, messages that quote at
//! most 60 characters of the user's text, and reading linear in the number of tracks.

use crate::support::bin;
use inbetween::Fps;
use inbetween_io::document::shorten;
use inbetween_io::{
    DEFAULT_MAX_INPUT_BYTES, Format, ReadOptions, parse_bytes, read_limited, read_path_limited,
};
use std::io::Read;
use std::path::Path;
use std::time::{Duration, Instant};

const KEY: &str = "0.7071067811865476,0,0.7071067811865476,0";

#[test]
fn reading_stops_one_byte_past_the_limit() {
    // An endless reader: without the limit this never returns.
    let mut zeros = std::io::repeat(b'0');
    let err = read_limited(&mut zeros, 1000, "<stdin>").unwrap_err();
    assert_eq!(
        err.message(),
        "<stdin>: input larger than 1000 bytes (input size limit)"
    );
    // It read exactly limit + 1 bytes from the reader.
    let mut counted = Counting(std::io::repeat(b'0'), 0);
    read_limited(&mut counted, 1000, "<stdin>").unwrap_err();
    assert_eq!(counted.1, 1001);

    // At the limit is fine; one byte more is not.
    let mut exact = &[b'x'; 1000][..];
    assert_eq!(
        read_limited(&mut exact, 1000, "<stdin>").unwrap().len(),
        1000
    );
    let mut over = &[b'x'; 1001][..];
    assert!(read_limited(&mut over, 1000, "<stdin>").is_err());
    assert_eq!(DEFAULT_MAX_INPUT_BYTES, 1 << 30);
}

struct Counting<R>(R, u64);

impl<R: Read> Read for Counting<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.0.read(buf)?;
        self.1 += n as u64;
        Ok(n)
    }
}

#[test]
fn files_and_devices_are_read_up_to_the_limit() {
    let opts = ReadOptions::default();
    let err = |r: Result<_, inbetween::Error>| match r.map(|_| ()) {
        Err(inbetween::Error::Input(e)) => e.message(),
        other => panic!("expected an input error, found {other:?}"),
    };
    // A device without a size: read up to limit + 1 bytes, then refused.
    if Path::new("/dev/zero").exists() {
        assert_eq!(
            err(read_path_limited(
                Path::new("/dev/zero"),
                None,
                &opts,
                1 << 20
            )),
            "/dev/zero: input larger than 1048576 bytes (input size limit)"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("k.csv");
    let text = format!("time,w,x,y,z\n0,1,0,0,0\n1,{KEY}\n");
    std::fs::write(&path, &text).unwrap();
    let n = text.len() as u64;
    let (doc, format) = read_path_limited(&path, None, &opts, n).unwrap();
    assert_eq!((doc.tracks[0].keys.len(), format), (2, Format::Csv));
    assert_eq!(
        err(read_path_limited(&path, None, &opts, n - 1)),
        format!(
            "{}: input larger than {} bytes (input size limit)",
            path.display(),
            n - 1
        )
    );
}

#[test]
fn a_file_beyond_the_default_limit_is_refused_unread() {
    // A sparse file of 1 GiB + 1 byte: refused from its size, at once, without reading it.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.csv");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(DEFAULT_MAX_INPUT_BYTES + 1).unwrap();
    drop(f);
    let start = Instant::now();
    let out = bin()
        .args(["convert", path.to_str().unwrap()])
        .timeout(Duration::from_secs(60))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: {}: input larger than 1073741824 bytes (--max-input-bytes)\n",
            path.display()
        )
    );
    assert!(
        start.elapsed() < Duration::from_secs(30),
        "{:?}",
        start.elapsed()
    );
}

#[test]
fn a_huge_field_is_quoted_cut() {
    // 10 MB in one CSV field: the message quotes 60 characters of it, not 10 MB.
    let big = "9".repeat(10_000_000) + "x";
    let text = format!("time,w,x,y,z\n0,1,0,0,0\n1,{big},0,0,0\n");
    let out = bin()
        .args(["convert", "-", "--input-format", "csv"])
        .write_stdin(text)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: <stdin>:3: column \"w\": expected a number, found \"{}…\"\n",
            "9".repeat(60)
        )
    );
    // The same in JSON, in a string where a number belongs.
    let text = format!(r#"{{"keys": [{{"time": 0, "quat": ["{big}", 0, 0, 0]}}]}}"#);
    let out = bin()
        .args(["convert", "-", "--input-format", "json"])
        .write_stdin(text)
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: <stdin>: keys[0]: \"quat[0]\": invalid type: string \"{}…\", expected f64\n",
            "9".repeat(60)
        )
    );
}

#[test]
fn shorten_counts_characters_and_keeps_them_whole() {
    assert_eq!(shorten(&"a".repeat(60)), "a".repeat(60));
    assert_eq!(shorten(&"a".repeat(61)), format!("{}…", "a".repeat(60)));
    // Four-byte characters: 60 of them, never a split one.
    assert_eq!(shorten(&"🦀".repeat(61)), format!("{}…", "🦀".repeat(60)));
    assert_eq!(shorten(&"🦀".repeat(60)), "🦀".repeat(60));
    assert_eq!(shorten(""), "");
}

/// `n` tracks of two keys, rows interleaved (each track's first key, then each second key).
fn many_tracks_csv(n: usize) -> String {
    let mut s = String::from("track,time,w,x,y,z\n");
    for i in 0..n {
        s.push_str(&format!("t{i},0,1,0,0,0\n"));
    }
    for i in 0..n {
        s.push_str(&format!("t{i},1,{KEY}\n"));
    }
    s
}

fn many_tracks_json(n: usize) -> String {
    let tracks: Vec<String> = (0..n)
        .map(|i| {
            format!(
                r#"{{"name": "t{i}", "keys": [{{"time": 0, "quat": [1, 0, 0, 0]}}, {{"time": 1, "quat": [{KEY}]}}]}}"#
            )
        })
        .collect();
    format!("{{\"tracks\": [\n{}\n]}}\n", tracks.join(",\n"))
}

/// 10⁵ tracks through the whole process, in a debug build: seconds when reading is linear in
/// the number of tracks (about 6 s measured), many minutes when it is quadratic (the scan of
/// every earlier track per row or per track). The budget is generous against a loaded machine.
#[test]
fn a_hundred_thousand_tracks_take_seconds() {
    const N: usize = 100_000;
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in [
        ("k.csv", many_tracks_csv(N)),
        ("k.json", many_tracks_json(N)),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let start = Instant::now();
        let out = bin()
            .args(["interp", path.to_str().unwrap(), "--fps", "2", "-o"])
            .arg(dir.path().join("out"))
            .timeout(Duration::from_secs(120))
            .output()
            .unwrap();
        let took = start.elapsed();
        assert!(
            out.status.success(),
            "{name}: {:?} after {took:?}: {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(took < Duration::from_secs(90), "{name}: {took:?}");
        // Three frames per track (0, 0.5 and 1 s), plus the header.
        if name.ends_with(".csv") {
            let written = std::fs::read_to_string(dir.path().join("out")).unwrap();
            assert_eq!(written.lines().count(), 3 * N + 1);
        }
    }
}

/// The library path the bench measures: tracks in input order, names kept, each found once.
#[test]
fn tracks_keep_first_appearance_order() {
    let (doc, _) = parse_bytes(
        many_tracks_csv(1000).into_bytes(),
        "k.csv",
        None,
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    let tracks = doc.tracks(Fps::DEFAULT).unwrap();
    assert_eq!(tracks.len(), 1000);
    for (i, t) in tracks.iter().enumerate() {
        assert_eq!(t.name(), Some(format!("t{i}").as_str()));
    }
    assert_eq!(doc.tracks[999].loc(1).to_string(), "2001");
}
