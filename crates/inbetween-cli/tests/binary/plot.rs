//! `plot` (issue 5): the SVG parses as XML, holds one series per scheme, and marks the keys.

use assert_cmd::Command;
use inbetween::Scheme;

fn plot(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("chart.svg");
    let run = Command::cargo_bin("inbetween")
        .unwrap()
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .arg("plot")
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read_to_string(out).unwrap()
}

/// Each scheme's colour, as docs/spec.md gives them (Okabe–Ito).
fn hex(s: Scheme) -> String {
    match s {
        Scheme::Hermite => "#0072B2",
        Scheme::Squad => "#E69F00",
        Scheme::Bezier => "#009E73",
        Scheme::Slerp => "#999999",
        Scheme::Nlerp => "#CC79A7",
        Scheme::MinAccel => "#D55E00",
    }
    .to_string()
}

/// Polylines in a colour with more than `min_points` points (the legend glyphs have two).
fn long_lines(doc: &roxmltree::Document, stroke: &str, min_points: usize) -> usize {
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(stroke))
        .filter(|n| {
            n.attribute("points")
                .unwrap_or("")
                .split_whitespace()
                .count()
                > min_points
        })
        .count()
}

#[test]
fn speed_chart_has_a_series_per_scheme_and_key_markers() {
    let text = plot(&["fixtures/interp/uniform.json"]);
    let doc = roxmltree::Document::parse(&text).expect("valid XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    for s in Scheme::ALL {
        assert_eq!(long_lines(&doc, &hex(s), 20), 1, "{s:?}");
    }
    // Five keys, plus the legend's dot.
    let dots = doc
        .descendants()
        .filter(|n| n.has_tag_name("circle") && n.attribute("fill") == Some("#B0B0B0"))
        .count();
    assert_eq!(dots, 5 + 1);
    let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
    let all = texts.join(" ");
    for label in [
        "time (s)",
        "angular speed (deg/s)",
        "hermite",
        "minaccel",
        "keys",
    ] {
        assert!(all.contains(label), "{label}");
    }
}

/// `n` keys over one second, turning about z at a varying speed, as CSV in `dir`.
fn keys_csv(dir: &std::path::Path, n: usize) -> std::path::PathBuf {
    let mut text = String::from("time,w,x,y,z\n");
    for i in 0..n {
        let t = i as f64 / (n - 1) as f64;
        let half = t * t;
        text += &format!("{t},{},0,0,{}\n", half.cos(), half.sin());
    }
    let path = dir.join(format!("keys{n}.csv"));
    std::fs::write(&path, text).unwrap();
    path
}

/// Key lines are drawn while the keys are at least 8 px apart on average on the time axis
/// (about 1280 px wide: up to some 160 key intervals); denser keys, which drew a grey curtain,
/// keep only their dots on the axis.
#[test]
fn key_lines_only_while_readable() {
    let dir = tempfile::tempdir().unwrap();
    for (n, lines) in [(5, 5), (100, 100), (150, 150), (175, 0), (400, 0)] {
        let keys = keys_csv(dir.path(), n);
        let text = plot(&[keys.to_str().unwrap(), "--scheme", "bezier"]);
        let doc = roxmltree::Document::parse(&text).unwrap();
        let count = |tag: &str, attr: &str| {
            doc.descendants()
                .filter(|e| e.has_tag_name(tag) && e.attribute(attr) == Some("#B0B0B0"))
                .count()
        };
        assert_eq!(count("polyline", "stroke"), lines, "{n} keys");
        // Every key keeps its dot (and the legend has one).
        assert_eq!(count("circle", "fill"), n + 1, "{n} keys");
    }
}

#[test]
fn chosen_schemes_only_and_components() {
    let text = plot(&[
        "fixtures/interp/multitrack.json",
        "--track",
        "head",
        "--scheme",
        "slerp,hermite",
        "--what",
        "components",
        "--angles",
        "rad",
    ]);
    let doc = roxmltree::Document::parse(&text).unwrap();
    // Solid ωx is one polyline per scheme; dashed and dotted lines are many short segments.
    assert_eq!(long_lines(&doc, &hex(Scheme::Hermite), 20), 1);
    assert_eq!(long_lines(&doc, &hex(Scheme::Slerp), 20), 1);
    assert_eq!(long_lines(&doc, &hex(Scheme::Squad), 1), 0);
    let all: String = doc.descendants().filter_map(|n| n.text()).collect();
    assert!(all.contains("rad/s") && all.contains("track head"));
}

#[test]
fn unknown_track_is_an_input_error() {
    let run = Command::cargo_bin("inbetween")
        .unwrap()
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .args([
            "plot",
            "fixtures/interp/multitrack.json",
            "--track",
            "tail",
            "-o",
            "/dev/null",
        ])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&run.stderr),
        "inbetween: error: fixtures/interp/multitrack.json: --track: expected one of hip, head, found \"tail\"\n"
    );
}
