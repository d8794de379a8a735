//! AMASS motion files: NumPy `.npz` archives of SMPL-H or SMPL-X parameters (docs/formats.md,
//! *AMASS*).
//!
//! `poses` (frames × 156, SMPL-H's 52 joints, or frames × 165, SMPL-X's 55) holds each joint's
//! rotation relative to its parent as a rotation vector (radians); `trans` (frames × 3) the
//! pelvis' translation; the rate is `mocap_framerate` (AMASS's SMPL-H files) or
//! `mocap_frame_rate` (its SMPL-X release), a number read by the rule of `--fps` (`59.94` is
//! 60000/1001). Everything else (`betas`, `gender`, `dmpls`, the split `root_orient`,
//! `pose_body`, … of SMPL-X files) is kept to be written back ([`Amass::resample`]).
//!
//! [`read`] checks the archive (`zip`) and each array ([`npy`]) against the file before
//! allocating from it; [`Amass::document`] makes one track per joint (named as smplx names them,
//! [`joints`]), the pelvis' carrying `trans`. The joints' rest offsets depend on the body's shape
//! (`betas`) and on the model files, which are not redistributed: the document has no hierarchy,
//! so world-space measures refuse it as they refuse keys without a skeleton.

pub mod joints;
pub mod npy;
mod write;
pub(crate) mod zip;

pub use joints::Model;
pub use npy::{Array, Kind};
pub use write::Resampled;

use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use glam::DVec3;
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult, Setting};
use inbetween::message;
use inbetween::rotation::{AngleUnit, Repr};
use std::path::Path;

/// The two spellings of the rate key: AMASS's SMPL-H files, then its SMPL-X release.
pub(crate) const RATE_KEYS: [&str; 2] = ["mocap_framerate", "mocap_frame_rate"];

/// An AMASS motion file as read.
#[derive(Debug, Clone)]
pub struct Amass {
    source: String,
    arrays: Vec<(String, Array)>,
    model: Model,
    frames: usize,
    poses: Vec<f64>,
    trans: Option<Vec<f64>>,
    fps: Fps,
    rate_key: Option<String>,
}

/// Whether the input is an `.npz` archive: the format as given, else `path`'s extension
/// (`.npz`), else the bytes are a zip archive (`PK\3\4`, or `PK\5\6` for an empty one) of a
/// path with no extension the formats know.
pub(crate) fn is_npz(bytes: &[u8], path: Option<&Path>, format: Option<crate::Format>) -> bool {
    if let Some(f) = format {
        return f == crate::Format::Amass;
    }
    if let Some(f) = path.and_then(crate::Format::from_path) {
        return f == crate::Format::Amass;
    }
    bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06")
}

/// Reads an AMASS `.npz` archive (stored or deflated); `source` names it in messages, and
/// `key_rate` stands in for a missing rate key (a rate key contradicting it is an error, by
/// [`crate::settle`]).
pub fn read(bytes: &[u8], source: &str, key_rate: Option<Fps>) -> InputResult<Amass> {
    let entries = zip::entries(bytes, source)?;
    let mut arrays = Vec::with_capacity(entries.len());
    for e in &entries {
        let Some(key) = e.name.strip_suffix(".npy") else {
            return Err(input_err!(
                "{source}: entry \"{}\" is not a NumPy array (.npy); an .npz holds only arrays",
                inbetween::error::shorten(&e.name)
            ));
        };
        let what = format!("{source}: key \"{key}\"");
        let array = npy::parse(e.data(source)?.into_owned(), &what)?;
        arrays.push((key.to_string(), array));
    }
    let find = |k: &str| arrays.iter().find(|(n, _)| n == k).map(|(_, a)| a);
    let Some(poses) = find("poses") else {
        let keys: Vec<String> = arrays.iter().map(|(k, _)| format!("\"{k}\"")).collect();
        return Err(input_err!(
            "{source}: no key \"poses\": an AMASS motion file holds poses (frames × 156 for \
             SMPL-H, frames × 165 for SMPL-X); its keys are {}",
            if keys.is_empty() {
                "none".to_string()
            } else {
                keys.join(", ")
            }
        ));
    };
    let model = match poses.shape[..] {
        [_, w] if poses.kind == Kind::Float => Model::of_width(w),
        _ => None,
    };
    let (Some(model), Some(values)) = (model, poses.floats()) else {
        return Err(input_err!(
            "{source}: key \"poses\": expected float rotation vectors of shape (frames, 156) \
             (SMPL-H) or (frames, 165) (SMPL-X), found {} of shape {}",
            poses.descr,
            npy::shape_text(&poses.shape)
        ));
    };
    let frames = poses.shape[0] as usize;
    if frames == 0 {
        return Err(input_err!(
            "{source}: key \"poses\": expected at least one frame, found none"
        ));
    }
    let width = 3 * model.joint_count();
    if let Some(i) = values.iter().position(|x| !x.is_finite()) {
        return Err(input_err!(
            "{source}: key \"poses\": frame {} column {}: expected a finite number, found {}",
            i / width,
            i % width,
            values[i]
        ));
    }
    // AMASS's other per-frame arrays: a row count other than poses' is a broken file, not an
    // array to copy as it is.
    for key in [
        "dmpls",
        "root_orient",
        "pose_body",
        "pose_hand",
        "pose_jaw",
        "pose_eye",
    ] {
        if let Some(a) = find(key).filter(|a| a.shape.first() != Some(&(frames as u64))) {
            return Err(input_err!(
                "{source}: key \"{key}\": expected one row per frame of poses ({frames}), \
                 found shape {}",
                npy::shape_text(&a.shape)
            ));
        }
    }
    let trans = match find("trans") {
        None => None,
        Some(t) => {
            let floats = t.floats().filter(|_| t.kind == Kind::Float);
            let Some(v) = floats.filter(|_| t.shape[..] == [frames as u64, 3]) else {
                return Err(input_err!(
                    "{source}: key \"trans\": expected floats of shape ({frames}, 3), one \
                     translation per frame of poses, found {} of shape {}",
                    t.descr,
                    npy::shape_text(&t.shape)
                ));
            };
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(input_err!(
                    "{source}: key \"trans\": frame {}: expected a finite number, found {}",
                    i / 3,
                    v[i]
                ));
            }
            Some(v)
        }
    };
    let (fps, rate_key) = rate(&arrays, source, key_rate)?;
    Ok(Amass {
        source: source.to_string(),
        arrays,
        model,
        frames,
        poses: values,
        trans,
        fps,
        rate_key,
    })
}

/// The rate: the rate key's value (either spelling; both must agree) read as `--fps` reads a
/// number ([`Fps::from_f64`]: 120.0 is 120, 59.94 is 60000/1001), settled with `key_rate`.
fn rate(
    arrays: &[(String, Array)],
    source: &str,
    key_rate: Option<Fps>,
) -> InputResult<(Fps, Option<String>)> {
    let mut found: Option<(Fps, &str, String)> = None;
    for (key, a) in arrays
        .iter()
        .filter(|(k, _)| RATE_KEYS.contains(&k.as_str()))
    {
        let value = a.floats().filter(|v| v.len() == 1 && a.shape.len() <= 1);
        let Some(x) = value.map(|v| v[0]) else {
            return Err(input_err!(
                "{source}: key \"{key}\": expected one number (the frames per second), found {} \
                 of shape {}",
                a.descr,
                npy::shape_text(&a.shape)
            ));
        };
        let fps = Fps::from_f64(x).map_err(|e| e.at(format!("{source}: key \"{key}\"")))?;
        if let Some((other, k, _)) = &found
            && *other != fps
        {
            return Err(input_err!(
                "{source}: keys \"{k}\" ({other} fps) and \"{key}\" ({fps} fps) disagree"
            ));
        }
        found.get_or_insert((fps, key, inbetween::error::num(x)));
    }
    let declared = found.as_ref().map(|(f, _, w)| (*f, w.as_str()));
    let key = found.as_ref().map_or("mocap_framerate", |(_, k, _)| k);
    match crate::settle(source, key, declared, Setting::KeyRate, key_rate)? {
        Some(fps) => Ok((fps, found.map(|(_, k, _)| k.to_string()))),
        None => Err(InputError::new(message![
            format!(
                "{source}: no key \"mocap_framerate\" or \"mocap_frame_rate\": the rate of its \
                 frames is unknown; give it ("
            ),
            Setting::KeyRate,
            ")"
        ])),
    }
}

impl Amass {
    /// The file's name in messages.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The body model, by the width of `poses`.
    pub fn model(&self) -> Model {
        self.model
    }

    /// The number of frames (rows of `poses`).
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The rate of the frames.
    pub fn fps(&self) -> Fps {
        self.fps
    }

    /// The rate key as the file spells it (`None` when the rate was given instead).
    pub fn rate_key(&self) -> Option<&str> {
        self.rate_key.as_deref()
    }

    /// The arrays in archive order, by key.
    pub fn arrays(&self) -> &[(String, Array)] {
        &self.arrays
    }

    /// Frame `i`'s rotation vector of `joint` (radians).
    pub fn rotvec(&self, i: usize, joint: usize) -> [f64; 3] {
        let at = i * 3 * self.model.joint_count() + 3 * joint;
        [self.poses[at], self.poses[at + 1], self.poses[at + 2]]
    }

    /// The document: one track per joint in `poses` order, named by [`Model::names`], one key
    /// per frame at [`Amass::fps`]; the pelvis' track carries `trans` as its translations.
    pub fn document(&self) -> InputResult<Document> {
        let names = self.model.names();
        let mut tracks = Vec::with_capacity(names.len());
        for (j, name) in names.into_iter().enumerate() {
            let mut keys = Vec::with_capacity(self.frames);
            for i in 0..self.frames {
                let (rot, _) = Repr::RotVec
                    .to_quat(&self.rotvec(i, j), AngleUnit::Rad)
                    .map_err(|e| {
                        e.at(format!(
                            "{}: key \"poses\": frame {i} joint {j} ({name})",
                            self.source
                        ))
                    })?;
                keys.push(Key {
                    when: KeyTime::Frame(i as f64),
                    rot,
                });
            }
            let translations = match (&self.trans, j) {
                (Some(t), 0) => t
                    .chunks_exact(3)
                    .map(|p| Some(DVec3::new(p[0], p[1], p[2])))
                    .collect(),
                _ => Vec::new(),
            };
            tracks.push(DocTrack {
                name: Some(name),
                translations,
                ..DocTrack::new(keys, KeyOrigin::Frames)
            });
        }
        Ok(Document {
            fps: Some(self.fps),
            rotation: Some(Repr::RotVec),
            tracks,
            named_tracks: true,
            // AMASS's translations are metres, its world Z up.
            unit_meters: Some(1.0),
            z_up: Some(true),
            ..Document::new(self.source.clone())
        })
    }
}

#[cfg(test)]
mod tests;
