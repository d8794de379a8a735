//! Barr's discrete energy E of every scheme on the minaccel grid of a keyframe file's tracks,
//! as quoted in docs/schemes.md: `cargo run --release --example energies -- KEYS [FPS]`.

use inbetween::curve::minaccel::Problem;
use inbetween::tangent::Knots;
use inbetween::{Curve, CurveOptions, EndConditions, Fps, PathMode, Scheme};
use inbetween_io::{ReadOptions, read_path};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(args.get(1).ok_or("usage: KEYS [FPS]")?);
    let fps: f64 = args.get(2).map_or(Ok(30.0), |s| s.parse())?;
    let (doc, _) = read_path(path, None, &ReadOptions::default())?;
    for track in doc.tracks(doc.fps.unwrap_or(Fps::DEFAULT))? {
        let keys = Knots::new(&track, PathMode::Shortest, EndConditions::default());
        let problem = Problem::new(&keys, fps)?;
        let grid = problem.grid_times().to_vec();
        println!("track {:?}: {} grid points", track.name(), grid.len());
        for scheme in [
            Scheme::Slerp,
            Scheme::Squad,
            Scheme::Bezier,
            Scheme::Hermite,
        ] {
            let opts = CurveOptions {
                scheme,
                ..CurveOptions::default()
            };
            let curve = Curve::new(&track, &opts)?;
            let pts: Vec<_> = grid.iter().map(|&t| curve.rotation(t)).collect();
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
