//! The page `view` writes: one HTML file with its style, its script and its data inline (no
//! request of any kind), the data a JSON object whose arrays are base64 of little-endian
//! float32 positions and float64 times and displacements (docs/formats.md *The view page*).

use crate::args::ViewArgs;
use crate::settings::Curves;
use base64::Engine;
use inbetween::skeleton::Skeleton;
use inbetween::{Error, InputError};
use serde_json::{Value, json};
use std::path::PathBuf;

/// The most bytes of float32 positions a page embeds (every figure, frame and point, 12 bytes
/// each, before base64): a page of at most about 45 MB. Beyond it, `view` refuses.
pub const MAX_POSITION_BYTES: usize = 32 << 20;

const TEMPLATE: &str = include_str!("page.html");
const STYLE: &str = include_str!("page.css");
const SCRIPT: &str = include_str!("page.js");

/// One figure: its source's name and its points' world positions, frame by frame, point by
/// point, x, y, z.
pub(super) struct Figure {
    pub(super) source: String,
    pub(super) positions: Vec<f32>,
}

/// What B against A adds to the page.
pub(super) struct Compared {
    /// The world displacement at each frame (`diff`'s measure).
    pub(super) errors: Vec<f64>,
    /// The frames at a key time of B.
    pub(super) keyed: Vec<usize>,
    /// B's keys, all tracks together.
    pub(super) keys: usize,
    /// The largest displacement and its time.
    pub(super) largest: (f64, f64),
    /// The track whose points move the most.
    pub(super) worst_track: Option<String>,
    /// B has a skeleton of its own that is not A's (B is drawn and measured on A's).
    pub(super) b_skeleton_differs: bool,
}

/// A page ready to be written: its data, and the files read (which `-o` may not replace).
pub(super) struct Page {
    data: Value,
    /// The files the command read.
    pub(super) reads: Vec<PathBuf>,
}

/// Refuses a page whose positions would pass [`MAX_POSITION_BYTES`]: `frames` frames of
/// `points` points for `figures` figures, 12 bytes each.
pub(super) fn check_size(
    source: &str,
    frames: usize,
    points: usize,
    figures: usize,
) -> Result<(), InputError> {
    let bytes = frames
        .saturating_mul(points)
        .saturating_mul(figures)
        .saturating_mul(12);
    if bytes <= MAX_POSITION_BYTES {
        return Ok(());
    }
    Err(InputError::new(format!(
        "{source}: the page would hold {frames} frames of {points} points for {figures} \
         figure(s), {bytes} bytes of positions, more than {MAX_POSITION_BYTES}; resample the \
         clip at a lower rate first (interp --fps)"
    )))
}

fn base64_f32(values: &[f32]) -> String {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn base64_f64(values: &[f64]) -> String {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// The file name of a source, for the title (its whole text when it has none).
fn file_name(source: &str) -> &str {
    source.rsplit(['/', '\\']).next().unwrap_or(source)
}

impl Page {
    /// The page of `figures` (A's first) posed on `skeleton` at `times`, with `compared` when
    /// there is a B.
    pub(super) fn new(
        args: &ViewArgs,
        a: &Curves,
        skeleton: &Skeleton,
        times: Vec<f64>,
        figures: Vec<Figure>,
        compared: Option<Compared>,
    ) -> Result<Page, Error> {
        let joints: Vec<Value> = skeleton
            .joints()
            .iter()
            .map(|j| json!({"name": j.name, "parent": j.parent}))
            .collect();
        // Each point's joint, and the point it is drawn from (-1 for a root's origin): an
        // origin from its parent joint's origin, an end point from its joint's origin.
        let owners = skeleton.point_joints(false);
        let mut origin_of = vec![0usize; skeleton.joints().len()];
        let mut from = Vec::with_capacity(owners.len());
        for (p, &j) in owners.iter().enumerate() {
            if p == 0 || owners[p - 1] != j {
                origin_of[j] = p;
                let parent = skeleton.joints()[j].parent;
                from.push(parent.map_or(-1, |q| origin_of[q] as i64));
            } else {
                from.push(origin_of[j] as i64);
            }
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for f in &figures {
            for p in f.positions.chunks_exact(3) {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        let up = usize::from(a.doc.z_up == Some(true)) + 1;
        let first = &figures[0].positions[..(owners.len() * 3).min(figures[0].positions.len())];
        let heights = first.chunks_exact(3).map(|p| p[up]);
        let height = heights.clone().fold(f32::NEG_INFINITY, f32::max)
            - heights.fold(f32::INFINITY, f32::min);
        let title = args.title.clone().unwrap_or_else(|| {
            let names: Vec<&str> = figures.iter().map(|f| file_name(&f.source)).collect();
            names.join(" and ")
        });
        let figs: Vec<Value> = figures
            .iter()
            .map(|f| json!({"source": f.source, "positions": base64_f32(&f.positions)}))
            .collect();
        let b = compared.map(|c| {
            json!({
                "errors": base64_f64(&c.errors),
                "keyed": c.keyed,
                "keys": c.keys,
                "largest": c.largest.0,
                "largest_time": c.largest.1,
                "worst_track": c.worst_track,
                "b_skeleton_differs": c.b_skeleton_differs,
            })
        });
        let data = json!({
            "format": "inbetween-view 1",
            "title": title,
            "frames": times.len(),
            "points": owners.len(),
            "times": base64_f64(&times),
            "joints": joints,
            "point_joint": owners,
            "point_from": from,
            "figures": figs,
            "compared": b,
            "tolerance": args.tolerance,
            "shell": args.shell,
            "up": if up == 2 { "z" } else { "y" },
            "unit_meters": a.doc.unit_meters,
            "box": {"min": lo, "max": hi},
            "height": height,
            "overlay": args.overlay,
        });
        Ok(Page {
            data,
            reads: a.reads.clone(),
        })
    }

    /// The page's text: the template with its style, script and data (JSON whose `<` are
    /// escaped, so no text of the input can close the script element).
    pub(super) fn html(&self) -> String {
        let data = self.data.to_string().replace('<', "\\u003c");
        // The data last: nothing of the input's text is searched for a marker.
        TEMPLATE
            .replacen("/*STYLE*/", STYLE, 1)
            .replacen("/*SCRIPT*/", SCRIPT, 1)
            .replacen("/*DATA*/", &data, 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_page_beyond_the_cap_is_refused_and_one_at_it_is_not() {
        // 12 bytes per point, frame and figure.
        let points_at_cap = MAX_POSITION_BYTES / 12;
        assert!(check_size("a.bvh", points_at_cap, 1, 1).is_ok());
        let e = check_size("a.bvh", points_at_cap / 2 + 1, 1, 2).unwrap_err();
        assert!(e.to_string().contains("more than 33554432"), "{e}");
        assert!(check_size("a.bvh", usize::MAX, usize::MAX, 2).is_err());
    }

    #[test]
    fn base64_holds_little_endian_floats() {
        let text = base64_f32(&[1.0, -2.5]);
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(text)
            .unwrap();
        assert_eq!(bytes, [0, 0, 128, 63, 0, 0, 32, 192]);
        assert_eq!(file_name("dir/sub\\clip.bvh"), "clip.bvh");
    }
}
