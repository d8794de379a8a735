//! Forward-difference drift against direct evaluation, as quoted in docs/schemes.md:
//! `cargo run --release --example drift`.
//!
//! For one great arc of 2 rad on S³ it prints the largest 4D distance between the recurrence and
//! `C(u)` evaluated directly, for our formulation (`s = 4 sin²(h/2)`, first difference without
//! subtraction) and the paper's (`s = 2(1 − cos h)`, `d₀ = C(δ) − C(0)`), at 10² … 10⁶ steps.

use glam::DQuat;
use inbetween::rotation::arc::Arc;

fn main() {
    let a = DQuat::from_rotation_x(0.2);
    let b = DQuat::from_axis_angle(glam::DVec3::new(0.0, 0.6, 0.8), 4.0);
    let arc = Arc::between(a, b);
    println!("steps      ours        paper");
    for n in [100usize, 1_000, 10_000, 100_000, 1_000_000] {
        let du = 1.0 / n as f64;
        let ours = arc
            .steps(0.0, du)
            .take(n + 1)
            .enumerate()
            .map(|(j, q)| (q - arc.eval(j as f64 * du)).length())
            .fold(0.0, f64::max);
        let h = arc.span() * du;
        let s = 2.0 * (1.0 - h.cos());
        let (mut q, mut d) = (arc.eval(0.0), arc.eval(du) - arc.eval(0.0));
        let mut paper: f64 = 0.0;
        for j in 0..=n {
            paper = paper.max((q - arc.eval(j as f64 * du)).length());
            q += d;
            d -= q * s;
        }
        println!("{n:<9}  {ours:.2e}    {paper:.2e}");
    }
}
