//! `view`'s page in headless Chromium (Debian's `chromium`, driven by its own command line):
//! it loads with nothing on the console, draws both figures (screenshots differ between two
//! frames, and with B hidden), and the displacement it decoded and shows equals `diff
//! --per-frame`. Skipped with a note where Chromium is missing, unless
//! INBETWEEN_REQUIRE_CHROMIUM is set (CI), which makes that a failure.

use crate::support::{bin, stdout_of};
use crate::view::{assert_self_contained, per_frame, reduced_pair};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The Chromium to run: `INBETWEEN_CHROMIUM`, else `/usr/bin/chromium`.
fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("INBETWEEN_CHROMIUM")
        .map_or_else(|| PathBuf::from("/usr/bin/chromium"), PathBuf::from);
    if path.is_file() {
        return Some(path);
    }
    assert!(
        std::env::var_os("INBETWEEN_REQUIRE_CHROMIUM").is_none(),
        "Chromium is required but {} is missing: apt-get install chromium",
        path.display()
    );
    eprintln!(
        "note: view's browser test skipped: needs chromium ({})",
        path.display()
    );
    None
}

/// Runs headless Chromium on `url` with `mode` (`--dump-dom`, `--screenshot=…`) in a fresh
/// profile, with the flags that keep it off the network, killed after 90 s; returns its stdout
/// and its console lines (Chromium logs each console message and uncaught error as
/// `…:CONSOLE:…`).
fn run(chromium: &Path, profile: &Path, url: &str, mode: &str) -> (String, Vec<String>) {
    let (out_path, err_path) = (profile.with_extension("out"), profile.with_extension("err"));
    let mut child = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--window-size=1000,760",
            "--force-device-scale-factor=1",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(mode)
        .arg(url)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .expect("chromium runs");
    let deadline = Instant::now() + Duration::from_secs(90);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            child.kill().ok();
            child.wait().ok();
            panic!("chromium did not finish within 90 s on {url}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
    assert!(status.success(), "chromium failed: {stderr}");
    let console = stderr
        .lines()
        .filter(|l| l.contains(":CONSOLE"))
        .map(str::to_string)
        .collect();
    (std::fs::read_to_string(&out_path).unwrap(), console)
}

#[test]
fn the_page_plays_in_headless_chromium() {
    let Some(chromium) = chromium() else { return };
    let dir = tempfile::tempdir().unwrap();
    let keys = reduced_pair(dir.path());
    let page = dir.path().join("page.html");
    stdout_of(
        bin()
            .args(["view", "fixtures/bvh/cmu_01_01.bvh"])
            .arg(&keys)
            .args(["--tolerance", "0.5", "-o"])
            .arg(&page),
    );
    assert_self_contained(&std::fs::read_to_string(&page).unwrap());
    let url = format!("file://{}", page.display());
    let profile = dir.path().join("profile");
    // The DOM once the script ran: ready, at the frame asked, its values the page decoded.
    let (dom, console) = run(
        &chromium,
        &profile,
        &format!("{url}#frame=20"),
        "--dump-dom",
    );
    assert!(console.is_empty(), "console: {console:?}");
    assert!(
        dom.contains("data-ready=\"1\""),
        "the script did not finish"
    );
    assert!(dom.contains("data-frame=\"20\""));
    // The frame shown is numbered from 0, as the fragment and `diff --per-frame` number it.
    assert!(
        dom.contains("<span id=\"readout\">frame 20 (0–60) · "),
        "the readout"
    );
    let open = "<pre id=\"values\" hidden=\"\">";
    let start = dom.find(open).expect("the values") + open.len();
    let end = start + dom[start..].find("</pre>").unwrap();
    let values: serde_json::Value = serde_json::from_str(&dom[start..end]).expect("JSON values");
    let shown: Vec<f64> = values["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let want: Vec<f64> = per_frame(dir.path(), "fixtures/bvh/cmu_01_01.bvh", &keys)
        .into_iter()
        .map(|(_, e)| e)
        .collect();
    assert_eq!(shown, want, "the page's curve against diff --per-frame");
    // Drawn: two frames differ, and hiding B changes the picture.
    let shot = |fragment: &str, name: &str| {
        let png = dir.path().join(name);
        let (_, console) = run(
            &chromium,
            &profile,
            &format!("{url}#{fragment}"),
            &format!("--screenshot={}", png.display()),
        );
        assert!(console.is_empty(), "console: {console:?}");
        let bytes = std::fs::read(&png).unwrap();
        assert!(bytes.starts_with(b"\x89PNG"), "{name} is a PNG");
        bytes
    };
    let early = shot("frame=5", "early.png");
    let late = shot("frame=45", "late.png");
    let hidden = shot("frame=45&b=hidden", "hidden.png");
    let overlay = shot("frame=45&overlay=1", "overlay.png");
    assert_ne!(early, late, "two frames draw the same picture");
    assert_ne!(late, hidden, "B hidden draws the same picture as B shown");
    assert_ne!(
        late, overlay,
        "B over A draws the same picture as B beside A"
    );
    assert_eq!(
        shot("frame=45", "again.png"),
        late,
        "the same frame twice differs"
    );
    // `az` and `el` turn the view chosen, whether they come before `view` or after it.
    let turned = shot("frame=45&view=side&az=30&el=10", "turned.png");
    assert_ne!(
        turned,
        shot("frame=45&view=side", "side.png"),
        "az, el unused"
    );
    assert_eq!(
        shot("frame=45&az=30&el=10&view=side", "turned_first.png"),
        turned,
        "view undid the az and el before it"
    );
    // A alone: one figure, no curve, the same silence.
    let single = dir.path().join("single.html");
    stdout_of(
        bin()
            .args(["view", "fixtures/bvh/cmu_01_01.bvh", "-o"])
            .arg(&single),
    );
    let url = format!("file://{}#frame=60", single.display());
    let (dom, console) = run(&chromium, &profile, &url, "--dump-dom");
    assert!(console.is_empty(), "console: {console:?}");
    assert!(dom.contains("data-ready=\"1\"") && dom.contains("data-frame=\"60\""));
    assert!(dom.contains("\"errors\":null"), "A alone has no curve");
}
