//! Barr's discrete energy E of every scheme on the minaccel grid of a keyframe file's tracks,
//! as quoted in docs/schemes.md: `cargo run --release --example energies -- KEYS [FPS]`.

use inbetween::clock::Fps;
use inbetween::curve::minaccel::Problem;
use inbetween::curve::{Blend, Scheme};
use inbetween::interp::eval_at;
use inbetween::io::{ReadOptions, read_path};
use inbetween::tangent::{EndConditions, Keys, PathMode};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(args.get(1).ok_or("usage: KEYS [FPS]")?);
    let fps: f64 = args.get(2).map_or(Ok(30.0), |s| s.parse())?;
    let (doc, _) = read_path(path, None, &ReadOptions::default())?;
    for track in doc.timed_tracks(doc.fps.unwrap_or(Fps::new(30, 1)?))? {
        let keys = Keys::new(&track, PathMode::Shortest, EndConditions::default());
        let problem = Problem::new(&keys, fps)?;
        let grid = problem.grid_times().to_vec();
        println!("track {:?}: {} grid points", track.name, grid.len());
        for scheme in [
            Scheme::Slerp,
            Scheme::Squad,
            Scheme::Bezier,
            Scheme::Hermite,
        ] {
            let pts: Vec<_> = grid
                .iter()
                .map(|&t| eval_at(&keys, scheme, Blend::Cubic, t).expect("per-segment scheme"))
                .collect();
            println!("  {:<9} E = {:.6}", scheme.name(), problem.energy_of(&pts));
        }
        let sol = problem.solve();
        println!(
            "  {:<9} E = {:.6}  ({} Newton iterations)",
            "minaccel", sol.report.energy, sol.report.iterations
        );
    }
    Ok(())
}
