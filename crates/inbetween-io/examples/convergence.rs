//! Convergence order of every scheme on a smooth synthetic motion, as quoted in docs/schemes.md:
//! `cargo run --release --example convergence`.
//!
//! The motion is `q(t) = Rz(a(t))·Ry(b(t))·Rx(c(t))` with smooth angles over 4 s. Keys are taken
//! every `h` seconds (h = 0.4 … 0.025, halving), each scheme (chord ends, shortest path) is
//! sampled 64 times per segment, and the error is the rotation angle to `q(t)`. Three measures:
//! the largest error anywhere, the largest over the middle half of the span (away from the ends,
//! whose chord or free end conditions are of lower order and reach a few segments in), and the
//! mean. minaccel is solved on a
//! fixed grid of 25 600 points per second. The order between two
//! spacings is `log2(error(h) / error(h/2))`. hermite and bezier are measured with both tangent
//! rules (`spline`, the default, and `nam-kim`); a second table takes uneven keys (every odd key
//! 0.3·h late) for the schemes with tangents.

use glam::DQuat;
use inbetween::rotation::quat::rotation_angle_between;
use inbetween::{Curve, CurveOptions, Fps, Scheme, TangentRule, Track};

const T: f64 = 4.0;
const SAMPLES: usize = 64;

fn motion(t: f64) -> DQuat {
    let a = 0.9 * (1.3 * t).sin() + 0.4 * t;
    let b = 0.6 * (0.7 * t + 0.3).cos();
    let c = 0.5 * (2.1 * t + 0.4).sin() - 0.2 * t;
    DQuat::from_rotation_z(a) * DQuat::from_rotation_y(b) * DQuat::from_rotation_x(c)
}

/// (max, middle-half max, mean) error in radians with keys every `h` seconds (`uneven`: every
/// odd key 0.3·h late).
fn errors(scheme: Scheme, tangent: TangentRule, uneven: bool, h: f64) -> (f64, f64, f64) {
    let n = (T / h).round() as usize;
    let late = |k: usize| {
        if uneven && k % 2 == 1 && k < n {
            0.3 * h
        } else {
            0.0
        }
    };
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * h + late(k)).collect();
    let track = Track::new(times.clone(), times.iter().map(|&t| motion(t)).collect())
        .expect("a valid track");
    // minaccel's grid: 25 600 points per second whatever h, so that its own discretisation
    // (great arcs between grid points, error ~ spacing²) stays below the errors measured.
    let grid = Fps::new(25_600, 1).expect("a rate");
    let opts = CurveOptions {
        scheme,
        grid_rate: grid,
        tangent: Some(tangent),
        ..CurveOptions::default()
    };
    let curve = Curve::new(&track, &opts).expect("a curve");
    let (mut max, mut interior, mut sum, mut count) = (0.0f64, 0.0f64, 0.0, 0);
    for w in times.windows(2) {
        for j in 0..SAMPLES {
            let t = w[0] + (w[1] - w[0]) * (j as f64 + 0.5) / SAMPLES as f64;
            let e = rotation_angle_between(curve.rotation(t), motion(t));
            max = max.max(e);
            if (T / 4.0..=3.0 * T / 4.0).contains(&t) {
                interior = interior.max(e);
            }
            sum += e;
            count += 1;
        }
    }
    (max, interior, sum / count as f64)
}

fn main() {
    let mut rows: Vec<(Scheme, TangentRule)> = Vec::new();
    for scheme in Scheme::ALL {
        rows.push((scheme, TangentRule::Spline));
        if matches!(scheme, Scheme::Hermite | Scheme::Bezier) {
            rows.push((scheme, TangentRule::NamKim));
        }
    }
    table(&rows, false);
    println!();
    let uneven: Vec<(Scheme, TangentRule)> = rows
        .iter()
        .copied()
        .filter(|(s, _)| matches!(s, Scheme::Hermite | Scheme::Bezier | Scheme::Squad))
        .collect();
    table(&uneven, true);
}

fn table(rows: &[(Scheme, TangentRule)], uneven: bool) {
    let spacings = [0.4, 0.2, 0.1, 0.05, 0.025];
    let keys = if uneven { ", odd keys 0.3h late" } else { "" };
    println!("error (rad) and order log2(e(h)/e(h/2)); keys every h s over {T} s{keys}");
    println!(
        "{:<17} {:>6} {:>11} {:>5} {:>11} {:>5} {:>11} {:>5}",
        "scheme", "h", "max", "ord", "middle", "ord", "mean", "ord"
    );
    for &(scheme, tangent) in rows {
        let name = match (scheme, tangent) {
            (Scheme::Hermite | Scheme::Bezier, TangentRule::NamKim) => format!("{scheme} nam-kim"),
            (Scheme::Hermite | Scheme::Bezier, _) => format!("{scheme} spline"),
            _ => scheme.to_string(),
        };
        let mut prev: Option<(f64, f64, f64)> = None;
        for &h in &spacings {
            let e = errors(scheme, tangent, uneven, h);
            let ord = |a: f64, b: f64| format!("{:.2}", (a / b).log2());
            let (o1, o2, o3) = match prev {
                Some(p) => (ord(p.0, e.0), ord(p.1, e.1), ord(p.2, e.2)),
                None => ("".into(), "".into(), "".into()),
            };
            println!(
                "{:<17} {:>6} {:>11.3e} {:>5} {:>11.3e} {:>5} {:>11.3e} {:>5}",
                name, h, e.0, o1, e.1, o2, e.2, o3
            );
            prev = Some(e);
        }
    }
}
