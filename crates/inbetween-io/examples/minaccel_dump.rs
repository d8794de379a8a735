//! Prints the minaccel solution of a keyframe file's first track as JSON (grid times and points
//! `[w, x, y, z]`), for checking against an independent optimiser:
//! `cargo run --release --example minaccel_dump -- KEYS FPS [rest]`.

use inbetween::curve::minaccel::solve;
use inbetween::tangent::Knots;
use inbetween::{EndConditions, Ends, Fps, PathMode};
use inbetween_io::{ReadOptions, read_path};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(args.get(1).ok_or("usage: KEYS FPS [rest]")?);
    let fps: f64 = args.get(2).ok_or("usage: KEYS FPS [rest]")?.parse()?;
    let (doc, _) = read_path(path, None, &ReadOptions::default())?;
    let tracks = doc.tracks(doc.fps.unwrap_or(Fps::DEFAULT))?;
    let ends = EndConditions {
        ends: if args.get(3).map(String::as_str) == Some("rest") {
            Ends::Rest
        } else {
            Ends::Chord
        },
        ..Default::default()
    };
    let keys = Knots::new(&tracks[0], PathMode::Shortest, ends);
    let sol = solve(&keys, fps)?;
    let pts: Vec<[f64; 4]> = sol.points.iter().map(|q| [q.w, q.x, q.y, q.z]).collect();
    println!(
        "{}",
        serde_json::json!({"times": sol.times, "points": pts, "energy": sol.report.energy,
                           "iterations": sol.report.iterations, "converged": sol.report.converged})
    );
    Ok(())
}
