#![allow(dead_code)] // each bench uses part of the shared workload
//! Shared workload of the benches: 10³ segments × 10³ in-betweens (1001 keys one second apart at
//! 1000 fps), keys turning about changing axes.

use glam::{DQuat, DVec3};
use inbetween::{Fps, Track};

pub const SEGMENTS: usize = 1_000;
pub const INBETWEENS: usize = 1_000;

pub fn track(segments: usize) -> Track {
    let quats: Vec<DQuat> = (0..=segments)
        .map(|i| {
            let a = i as f64;
            let axis = DVec3::new((0.31 * a).sin(), (0.7 * a).cos(), 0.5).normalize();
            DQuat::from_axis_angle(axis, 0.3 + 0.5 * (0.13 * a).sin())
                * DQuat::from_rotation_z(0.2 * a)
        })
        .collect();
    Track::new((0..=segments).map(|i| i as f64).collect(), quats).expect("a valid track")
}

pub fn fps() -> Fps {
    Fps::new(INBETWEENS as u64, 1).unwrap()
}
