//! Shared helpers for the integration tests.

use glam::DQuat;
use std::path::{Path, PathBuf};

/// The repository's `fixtures/` directory.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")
}

/// Angle between two rotations in radians (q and −q are the same rotation).
pub fn rot_angle(a: DQuat, b: DQuat) -> f64 {
    inbetween::rotation::quat::rotation_angle_between(a, b)
}

/// Reads a CSV file with a header into rows of strings keyed by column name.
pub fn read_table(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut rdr = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let headers = rdr.headers().unwrap().clone();
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            headers
                .iter()
                .zip(r.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}
