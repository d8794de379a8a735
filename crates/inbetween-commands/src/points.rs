//! The points a world-space measure sees, one rule for `reduce --position-tolerance` and `diff`
//! (docs/spec.md §4.7): every joint's origin and end points; without `--shell`, end points at a
//! bone length for a joint whose rotation would move none; with `--shell D`, three points `D`
//! from every joint in world units; `--shell 0`, neither.

use inbetween::skeleton::Skeleton;

/// `skeleton` with the points `--shell` asks for as end points: the skeleton, the joints given
/// default ends with their bone lengths, and the joints left with no point to bound them.
pub fn measured(
    skeleton: &Skeleton,
    shell: Option<f64>,
) -> (Skeleton, Vec<(usize, f64)>, Vec<usize>) {
    match shell {
        None => skeleton.with_default_ends(),
        Some(d) if d > 0.0 => (skeleton.with_shell(d), Vec::new(), Vec::new()),
        Some(_) => (skeleton.clone(), Vec::new(), Vec::new()),
    }
}
