//! Frames as a NumPy `.npz` archive: named arrays in a zip of stored `.npy` entries
//! ([`super::zip`]), `np.load(path)["rotations"]`, no pickles.
//!
//! ```text
//! times.npy            (T,)       <f8   frame times, s
//! frames.npy           (T,)       <i8   frame numbers
//! names.npy            (J,)       <U{n} track names ("" for an unnamed track)
//! rotations.npy        (T, J, W)  <f8   the rotation values in the CSV columns' order
//! velocities.npy       (T, J, 3)  <f8   world-frame angular velocity (with velocities)
//! translations.npy     (T, J, 3)  <f8   positions, zeros for a track without (when any has them)
//! has_translation.npy  (J,)       |b1   which tracks have positions (beside translations.npy)
//! parents.npy          (J,)       <i8   each track's nearest ancestor that is a track, −1 for
//!                                       none (an input with a skeleton: BVH, FBX, glTF, USD)
//! offsets.npy          (J, 3)     <f8   each track's joint's rest translation (with parents.npy)
//! fps.npy              ()         <U    the output rate as the tool spells it: "30", "30000/1001"
//! rotation.npy         ()         <U    the representation: "quat", "euler:ZYX", …
//! angles.npy           ()         <U    the unit of every angle written: "deg" or "rad"
//! ```
//!
//! Every track has the same frames (`T` of them, the same numbers): the arrays are frame-major
//! (`[t, j]`), so they are held in memory until the last track (8·(W + 6) bytes a frame and
//! track at most) and written at [`FrameSink::finish`]. [`npz_size`] says beforehand how large
//! the archive will be; a zip without ZIP64 holds at most [`zip::MAX_BYTES`].

use super::npy::array_header;
use super::zip::{self, ZipWriter};
use super::{Bad, Style, internal_error, rotation_fault, velocity_fault};
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use inbetween::rotation::MAX_WIDTH;
use std::io::{self, Write};

/// What an archive holds besides the rotations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NpzShape {
    /// `T`, the frames of every track.
    pub frames: u64,
    /// `J`, the tracks.
    pub tracks: usize,
    /// Write `velocities.npy`.
    pub velocity: bool,
    /// Write `translations.npy` and `has_translation.npy` (some track has positions).
    pub positions: bool,
    /// Write `parents.npy` and `offsets.npy` ([`NpzWriter::with_tree`]).
    pub tree: bool,
}

/// The tracks' tree: each track's nearest ancestor that is a track and its joint's rest
/// translation (a BVH `OFFSET`, a glTF node's `translation`).
#[derive(Debug, Clone, PartialEq)]
pub struct Tree {
    /// Per track, the index of its parent track, −1 for none.
    pub parents: Vec<i64>,
    /// Per track, its joint's rest translation.
    pub offsets: Vec<[f64; 3]>,
}

impl Tree {
    /// The tree of `tracks` tracks on `skeleton`, when the skeleton animates exactly those
    /// tracks, each through a joint.
    pub fn of(skeleton: &inbetween::skeleton::Skeleton, tracks: usize) -> Option<Tree> {
        if skeleton.track_count() != tracks {
            return None;
        }
        let joints: Option<Vec<usize>> = skeleton.track_joints().into_iter().collect();
        let offsets = joints?
            .iter()
            .map(|&j| skeleton.joints()[j].translation.to_array())
            .collect();
        let parents = skeleton
            .track_parents()
            .iter()
            .map(|p| p.map_or(-1, |t| t as i64))
            .collect();
        Some(Tree { parents, offsets })
    }
}

/// The most bytes `names.npy` may take: NumPy's fixed-width unicode gives every track the
/// longest name's width (4 bytes a character), so one long name among many tracks would make
/// gigabytes of padding.
pub const MAX_NAMES_BYTES: u64 = 64 << 20;

/// The bytes of `names.npy` for `tracks` names, the longest `name_chars` characters.
pub fn names_size(tracks: usize, name_chars: usize) -> u64 {
    (4 * name_chars.max(1) as u64).saturating_mul(tracks as u64)
}

/// The size in bytes of the archive [`NpzWriter`] writes for `shape` with `width` rotation
/// values per frame and the longest track name `name_chars` characters long, or a little more
/// (each `.npy` header counted as 128 bytes; saturating).
pub fn npz_size(width: usize, shape: NpzShape, name_chars: usize) -> u64 {
    let cells = shape.frames.saturating_mul(shape.tracks as u64);
    let vectors = cells.saturating_mul(24);
    let mut entries = vec![
        ("times.npy", 8 * shape.frames),
        ("frames.npy", 8 * shape.frames),
        ("names.npy", names_size(shape.tracks, name_chars)),
        ("rotations.npy", cells.saturating_mul(8 * width as u64)),
        ("fps.npy", 4 * 24),
        ("rotation.npy", 4 * 16),
        ("angles.npy", 4 * 3),
    ];
    if shape.velocity {
        entries.push(("velocities.npy", vectors));
    }
    if shape.positions {
        entries.push(("translations.npy", vectors));
        entries.push(("has_translation.npy", shape.tracks as u64));
    }
    if shape.tree {
        entries.push(("parents.npy", 8 * shape.tracks as u64));
        entries.push(("offsets.npy", 24 * shape.tracks as u64));
    }
    let sized: Vec<(usize, u64)> = entries
        .iter()
        .map(|&(name, bytes)| (name.len(), bytes.saturating_add(128)))
        .collect();
    zip::archive_size(&sized)
}

/// Collects frames into frame-major arrays and writes them as `.npz` at the end.
pub struct NpzWriter<W: Write> {
    w: Option<W>,
    style: Style,
    fps: Fps,
    shape: NpzShape,
    names: Vec<String>,
    frames: Vec<i64>,
    times: Vec<f64>,
    /// `(T, J, W)`, `(T, J, 3)`, `(T, J, 3)` as little-endian bytes.
    rotations: Vec<u8>,
    velocities: Vec<u8>,
    translations: Vec<u8>,
    has_translation: Vec<bool>,
    tree: Option<Tree>,
    /// The current track's index and its frames so far.
    track: usize,
    frame: u64,
    vals: [f64; MAX_WIDTH],
    unwrap: Option<inbetween::rotation::unwrap::EulerUnwrap>,
}

impl<W: Write> NpzWriter<W> {
    /// A writer of `shape.tracks` tracks of `shape.frames` frames each at `fps` (checked as they
    /// come): memory for all of them is taken now ([`npz_size`] tells how much).
    pub fn new(w: W, style: Style, fps: Fps, shape: NpzShape) -> Self {
        let cells = (shape.frames as usize).saturating_mul(shape.tracks);
        let width = style.repr.width();
        let zeros = |n: usize, on: bool| if on { vec![0u8; n] } else { Vec::new() };
        NpzWriter {
            w: Some(w),
            style,
            fps,
            shape,
            names: Vec::with_capacity(shape.tracks),
            frames: Vec::with_capacity(shape.frames as usize),
            times: Vec::with_capacity(shape.frames as usize),
            rotations: vec![0u8; cells.saturating_mul(8 * width)],
            velocities: zeros(cells.saturating_mul(24), shape.velocity),
            translations: zeros(cells.saturating_mul(24), shape.positions),
            has_translation: Vec::with_capacity(shape.tracks),
            tree: None,
            track: 0,
            frame: 0,
            vals: [0.0; MAX_WIDTH],
            unwrap: None,
        }
    }

    /// Also writes the tracks' tree (`shape.tree` must be set, and `tree` must be of
    /// `shape.tracks` tracks).
    pub fn with_tree(mut self, tree: Tree) -> Self {
        debug_assert!(self.shape.tree && tree.parents.len() == self.shape.tracks);
        self.tree = Some(tree);
        self
    }

    /// The writer, after [`FrameSink::finish`].
    pub fn into_inner(self) -> io::Result<W> {
        self.w
            .ok_or_else(|| io::Error::other("internal error: npz writer used after finish"))
    }

    /// The error for frame `k` of track `j`, which must not be written (a bug upstream).
    #[cold]
    fn refuse(&self, j: usize, k: i64, bad: Bad) -> io::Error {
        let name = Some(self.names[j].as_str()).filter(|n| !n.is_empty());
        internal_error(&format!("frame {k}"), name, j, bad)
    }

    fn shape_error(&self, what: String) -> io::Error {
        io::Error::other(format!(
            "internal error: npz writer: {what} (announced {} tracks of {} frames)",
            self.shape.tracks, self.shape.frames
        ))
    }

    /// One frame of the current track, `position` when it has one.
    fn put(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: Option<DVec3>,
    ) -> io::Result<()> {
        let (j, t) = (self.track.wrapping_sub(1), self.frame);
        if j >= self.shape.tracks || t >= self.shape.frames {
            return Err(self.shape_error(format!("frame {t} of track {j}")));
        }
        // The first track sets the frames; every other track has the same.
        if j == 0 {
            self.frames.push(k);
            self.times.push(time);
        } else if self.frames[t as usize] != k {
            return Err(self.shape_error(format!(
                "track {j} has frame {k} where track 0 has frame {}",
                self.frames[t as usize]
            )));
        }
        let repr = self.style.repr;
        let euler = self.unwrap.as_mut().map(|u| u.next(q));
        self.style.fill(q, euler, &mut self.vals);
        let unit = self.style.angles;
        let w = omega.map(|o| o.to_array().map(|x| unit.from_rad(x)));
        let width = repr.width();
        let values = &self.vals[..width];
        let bad_position = position.and_then(|p| p.to_array().into_iter().find(|x| !x.is_finite()));
        let fault = if !time.is_finite() {
            Some(Bad::NonFinite("time", time))
        } else if let Some(x) = bad_position {
            Some(Bad::NonFinite("translation", x))
        } else if let Some(bad) = rotation_fault(repr, q, values) {
            Some(bad)
        } else if self.shape.velocity && !w.is_some_and(|w| w.iter().all(|x| x.is_finite())) {
            Some(velocity_fault(w))
        } else {
            None
        };
        if let Some(bad) = fault {
            return Err(self.refuse(j, k, bad));
        }
        let cell = t as usize * self.shape.tracks + j;
        put_f64s(&mut self.rotations, cell * width, values);
        if let Some(w) = w.filter(|_| self.shape.velocity) {
            put_f64s(&mut self.velocities, cell * 3, &w);
        }
        if let Some(p) = position.filter(|_| self.shape.positions) {
            put_f64s(&mut self.translations, cell * 3, &p.to_array());
            self.has_translation[j] = true;
        }
        self.frame += 1;
        Ok(())
    }
}

/// Writes `values` as little-endian f64 into `buf` from value index `at`.
fn put_f64s(buf: &mut [u8], at: usize, values: &[f64]) {
    for (i, x) in values.iter().enumerate() {
        buf[8 * (at + i)..8 * (at + i + 1)].copy_from_slice(&x.to_le_bytes());
    }
}

/// A fixed-width unicode array's dtype and bytes (`<U{n}`: UCS4 little-endian, each string
/// padded with NULs to the longest, at least one character).
fn unicode(strings: &[&str]) -> (String, Vec<u8>) {
    let n = strings
        .iter()
        .map(|s| s.chars().count())
        .max()
        .unwrap_or(0)
        .max(1);
    let mut bytes = Vec::with_capacity(4 * n * strings.len());
    for s in strings {
        let mut len = 0;
        for c in s.chars() {
            bytes.extend_from_slice(&u32::from(c).to_le_bytes());
            len += 1;
        }
        bytes.resize(bytes.len() + 4 * (n - len), 0);
    }
    (format!("<U{n}"), bytes)
}

impl<W: Write> FrameSink for NpzWriter<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        if self.track > 0 && self.frame != self.shape.frames {
            return Err(self.shape_error(format!(
                "track {} ended after {} frames",
                self.track - 1,
                self.frame
            )));
        }
        self.track += 1;
        self.frame = 0;
        self.names.push(name.unwrap_or("").to_string());
        self.has_translation.push(false);
        self.unwrap = self.style.unwrapper();
        Ok(())
    }

    fn euler_start(&mut self, seq: crate::EulerSeq, angles: [f64; 3]) {
        self.unwrap = self.style.unwrapper_from(seq, angles);
    }

    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        self.put(k, time, q, omega, None)
    }

    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        self.put(k, time, q, omega, Some(position))
    }

    fn finish(&mut self) -> io::Result<()> {
        let (t, j) = (self.shape.frames, self.shape.tracks as u64);
        if self.track as u64 != j || (j > 0 && self.frame != t) {
            return Err(self.shape_error(format!(
                "{} tracks written, the last with {} frames",
                self.track, self.frame
            )));
        }
        let w = self
            .w
            .take()
            .ok_or_else(|| self.shape_error("finished twice".into()))?;
        let mut z = ZipWriter::new(w);
        let mut entry = |name: &str, descr: &str, shape: &[u64], data: &[u8]| {
            z.entry(name, &[&array_header(descr, shape), data])
        };
        let le = |xs: &mut dyn Iterator<Item = [u8; 8]>| xs.flatten().collect::<Vec<u8>>();
        let times = le(&mut self.times.iter().map(|x| x.to_le_bytes()));
        let frames = le(&mut self.frames.iter().map(|k| k.to_le_bytes()));
        entry("times.npy", "<f8", &[t], &times)?;
        entry("frames.npy", "<i8", &[t], &frames)?;
        let names: Vec<&str> = self.names.iter().map(String::as_str).collect();
        let (descr, bytes) = unicode(&names);
        entry("names.npy", &descr, &[j], &bytes)?;
        let width = self.style.repr.width() as u64;
        entry("rotations.npy", "<f8", &[t, j, width], &self.rotations)?;
        if self.shape.velocity {
            entry("velocities.npy", "<f8", &[t, j, 3], &self.velocities)?;
        }
        if self.shape.positions {
            entry("translations.npy", "<f8", &[t, j, 3], &self.translations)?;
            let flags: Vec<u8> = self.has_translation.iter().map(|&b| u8::from(b)).collect();
            entry("has_translation.npy", "|b1", &[j], &flags)?;
        }
        if let Some(tree) = self
            .tree
            .as_ref()
            .filter(|t| t.parents.len() == self.shape.tracks)
        {
            let parents: Vec<u8> = tree.parents.iter().flat_map(|p| p.to_le_bytes()).collect();
            entry("parents.npy", "<i8", &[j], &parents)?;
            let offsets: Vec<u8> = tree
                .offsets
                .iter()
                .flatten()
                .flat_map(|x| x.to_le_bytes())
                .collect();
            entry("offsets.npy", "<f8", &[j, 3], &offsets)?;
        }
        let rotation = self.style.repr.to_string();
        for (name, text) in [
            ("fps.npy", self.fps.to_string()),
            ("rotation.npy", rotation),
            ("angles.npy", self.style.angles.as_str().to_string()),
        ] {
            let (descr, bytes) = unicode(&[&text]);
            entry(name, &descr, &[], &bytes)?;
        }
        self.w = Some(z.finish()?);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::NumFormat;
    use inbetween::rotation::{AngleUnit, QuatOrder, Repr};

    fn writer(tracks: usize, frames: u64, positions: bool) -> NpzWriter<Vec<u8>> {
        let style = Style {
            repr: Repr::Quat,
            angles: AngleUnit::Deg,
            quat_order: QuatOrder::Xyzw,
            num: NumFormat::Fixed(2),
            euler: Default::default(),
        };
        let shape = NpzShape {
            frames,
            tracks,
            velocity: true,
            positions,
            tree: false,
        };
        NpzWriter::new(Vec::new(), style, Fps::new(24, 1).unwrap(), shape)
    }

    fn f64_at(buf: &[u8], i: usize) -> f64 {
        f64::from_le_bytes(buf[8 * i..8 * i + 8].try_into().unwrap())
    }

    #[test]
    fn arrays_are_frame_major_and_quaternions_wxyz() {
        let mut w = writer(2, 3, true);
        for j in 0..2 {
            w.begin_track(Some(["a", "b"][j])).unwrap();
            for k in 0..3i64 {
                let q = DQuat::from_rotation_z(0.1 * (k + 10 * j as i64) as f64);
                let omega = Some(DVec3::new(k as f64, j as f64, 1.0));
                if j == 0 {
                    w.frame_at(k, k as f64 / 24.0, q, omega, DVec3::splat(k as f64))
                        .unwrap();
                } else {
                    w.frame(k, k as f64 / 24.0, q, omega).unwrap();
                }
            }
        }
        w.finish().unwrap();
        // Frame t of track j is cell t·J + j; w first whatever the JSON order; degrees.
        let q = DQuat::from_rotation_z(0.1 * 12.0);
        assert_eq!(f64_at(&w.rotations, 4 * 5), q.w);
        assert_eq!(f64_at(&w.rotations, 4 * 5 + 3), q.z);
        assert_eq!(f64_at(&w.velocities, 3 * 5), 2f64.to_degrees());
        assert_eq!(f64_at(&w.translations, 3 * 4), 2.0);
        // Track b has no positions: zeros, and has_translation says so.
        assert_eq!(f64_at(&w.translations, 3 * 5), 0.0);
        assert_eq!(w.has_translation, [true, false]);
        let bytes = w.into_inner().unwrap();
        assert!(bytes.starts_with(b"PK\x03\x04"));
        let size = npz_size(4, writer(2, 3, true).shape, 1);
        assert!(
            (bytes.len() as u64) <= size && size < bytes.len() as u64 + 2048,
            "{} {size}",
            bytes.len()
        );
    }

    #[test]
    fn tracks_on_other_frames_are_an_internal_error() {
        let mut w = writer(2, 2, false);
        w.begin_track(None).unwrap();
        for k in [0, 1] {
            w.frame(k, 0.0, DQuat::IDENTITY, Some(DVec3::ZERO)).unwrap();
        }
        w.begin_track(None).unwrap();
        let err = w.frame(5, 0.0, DQuat::IDENTITY, Some(DVec3::ZERO));
        assert_eq!(
            err.unwrap_err().to_string(),
            "internal error: npz writer: track 1 has frame 5 where track 0 has frame 0 \
             (announced 2 tracks of 2 frames)"
        );
        // A short track is found at the next track or at the end.
        let mut w = writer(1, 2, false);
        w.begin_track(None).unwrap();
        w.frame(0, 0.0, DQuat::IDENTITY, Some(DVec3::ZERO)).unwrap();
        assert!(w.finish().is_err());
    }

    #[test]
    fn non_finite_values_are_refused() {
        let cases = [
            (
                (f64::NAN, DQuat::IDENTITY, Some(DVec3::ZERO), None),
                "internal error: non-finite value in frame 0 of track \"hip\" (\"time\" = NaN)",
            ),
            (
                (
                    0.0,
                    DQuat::IDENTITY,
                    Some(DVec3::ZERO),
                    Some(DVec3::new(0.0, f64::INFINITY, 0.0)),
                ),
                "internal error: non-finite value in frame 0 of track \"hip\" (\"translation\" = inf)",
            ),
            (
                (
                    0.0,
                    DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0),
                    Some(DVec3::ZERO),
                    None,
                ),
                "internal error: zero or non-unit quaternion in frame 0 of track \"hip\" (norm 0)",
            ),
            (
                (0.0, DQuat::IDENTITY, None, None),
                "internal error: no angular velocity in frame 0 of track \"hip\"",
            ),
        ];
        for ((t, q, omega, p), want) in cases {
            let mut w = writer(1, 1, true);
            w.begin_track(Some("hip")).unwrap();
            let err = match p {
                Some(p) => w.frame_at(0, t, q, omega, p),
                None => w.frame(0, t, q, omega),
            };
            let err = err.unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::InvalidData);
            assert_eq!(err.to_string(), want);
        }
    }

    #[test]
    fn unicode_arrays_are_ucs4_padded_to_the_longest() {
        let (descr, bytes) = unicode(&["ab", "", "é"]);
        assert_eq!(descr, "<U2");
        let want: Vec<u8> = [0x61u32, 0x62, 0, 0, 0xE9, 0]
            .iter()
            .flat_map(|c| c.to_le_bytes())
            .collect();
        assert_eq!(bytes, want);
        assert_eq!(unicode(&[""]).0, "<U1");
    }
}
