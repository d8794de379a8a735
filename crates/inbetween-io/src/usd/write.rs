//! `.usda` output: a skeleton's motion as a UsdSkel `Skeleton` and its `SkelAnimation`
//! (docs/formats.md, *USD*).
//!
//! ```text
//! #usda 1.0
//! ( defaultPrim = "Clip"  metersPerUnit  upAxis = "Y"
//!   timeCodesPerSecond = framesPerSecond = <rate>  startTimeCode  endTimeCode )
//! def SkelRoot "Clip" {
//!   def Skeleton "Skeleton" (prepend apiSchemas = ["SkelBindingAPI"]) {
//!     uniform token[] joints          every joint, parents first, as paths "Hips/Spine"
//!     uniform matrix4d[] restTransforms, bindTransforms   local and composed rest poses
//!     rel skel:animationSource = </Clip/Skeleton/Animation>
//!     def SkelAnimation "Animation" {
//!       uniform token[] joints
//!       quatf[] rotations.timeSamples     (w, x, y, z), each joint at each sample
//!       float3[] translations.timeSamples
//!       half3[] scales.timeSamples        all three with the same sample times
//! } } }
//! ```
//!
//! A time code is a frame number at the clip's rate (`timeCodesPerSecond` its exact value as a
//! double: 30000/1001 is `29.97002997002997`). A joint that no track animates holds its rest
//! rotation and translation at every sample. Joint names become USD identifiers
//! (`usd_name`). Values are written as USD stores them — float32 rotations and translations,
//! half scales — each as the shortest decimal that reads back as that float.

use glam::{DQuat, DVec3};
use inbetween::clock::Fps;
use inbetween::skeleton::Skeleton;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::io::{self, Write};

/// A joint name as a USD identifier: every character other than an ASCII letter, digit or `_`
/// becomes `_`, a leading digit (or an empty name) gets a `_` before it. `Bone.001` is
/// `Bone_001`, `mixamorig:Hips` is `mixamorig_Hips`.
pub(crate) fn usd_name(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}

/// The joints' USD paths: each joint's name as a USD identifier ([`usd_name`]; of a name that
/// is already a joint path, `Hips/Spine` as read from USD, its last part) under its parent's
/// path, so that a USD input's joints keep their paths. Where two joints would share a path,
/// the later gets `_<its index>` (and `_2`, `_3`, … after that while the path is taken): no
/// two joints are ever written with one path.
pub(crate) fn joint_paths(skeleton: &Skeleton) -> Vec<String> {
    let mut paths: Vec<String> = Vec::with_capacity(skeleton.joints().len());
    let mut seen = HashSet::new();
    for (i, j) in skeleton.joints().iter().enumerate() {
        let leaf = j.name.rsplit('/').next().unwrap_or(&j.name);
        let prefix = j
            .parent
            .map(|p| format!("{}/", paths[p]))
            .unwrap_or_default();
        let base = usd_name(leaf);
        let mut path = format!("{prefix}{base}");
        let mut k = 1;
        while seen.contains(&path) {
            path = if k == 1 {
                format!("{prefix}{base}_{i}")
            } else {
                format!("{prefix}{base}_{i}_{k}")
            };
            k += 1;
        }
        seen.insert(path.clone());
        paths.push(path);
    }
    paths
}

/// One track's samples: a rotation at each time code and, for a track with translations, a
/// position.
#[derive(Debug, Clone, Default)]
pub(crate) struct TrackSamples {
    /// Rotation at each sample.
    pub rotations: Vec<DQuat>,
    /// Position at each sample, when the track has translations.
    pub positions: Option<Vec<DVec3>>,
}

/// How the stage is set up: its length unit and up axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    /// `metersPerUnit`.
    pub meters_per_unit: f64,
    /// `upAxis = "Z"`, else `"Y"`.
    pub z_up: bool,
}

/// Writes `skeleton`'s motion as `.usda` (see the module documentation): `codes` the sample
/// time codes (frame numbers at `fps`, increasing), `tracks[t]` the samples of track `t` (a
/// value per code), `stage` the length unit and up axis. Errors (`InvalidInput`, internal): a
/// track count or sample count that does not match, a value that is not finite.
pub(crate) fn write_usda<W: Write>(
    mut out: W,
    skeleton: &Skeleton,
    fps: Fps,
    codes: &[f64],
    tracks: &[TrackSamples],
    stage: Stage,
) -> io::Result<()> {
    let internal =
        |m: String| io::Error::new(io::ErrorKind::InvalidInput, format!("internal error: {m}"));
    if tracks.len() != skeleton.track_count() {
        return Err(internal(format!(
            "{} tracks for a skeleton of {}",
            tracks.len(),
            skeleton.track_count()
        )));
    }
    if let Some(t) = tracks.iter().position(|t| {
        t.rotations.len() != codes.len()
            || t.positions.as_ref().is_some_and(|p| p.len() != codes.len())
    }) {
        return Err(internal(format!(
            "track {t} has another number of samples than {}",
            codes.len()
        )));
    }
    if codes.is_empty() || codes.windows(2).any(|w| w[0] >= w[1] || w[1].is_nan()) {
        return Err(internal("USD samples need increasing time codes".into()));
    }
    let joints = skeleton.joints();
    let paths = joint_paths(skeleton);
    let rate = fps.num() as f64 / fps.den() as f64;
    let mut s = String::new();
    let _ = writeln!(s, "#usda 1.0\n(");
    let _ = writeln!(s, "    defaultPrim = \"Clip\"");
    let _ = writeln!(s, "    endTimeCode = {}", num(codes[codes.len() - 1]));
    let _ = writeln!(s, "    framesPerSecond = {}", num(rate));
    // 12 significant digits: 2.54 cm computed as 2.54 × 0.01 is 0.025400000000000002.
    let unit: f64 = format!("{:.11e}", stage.meters_per_unit)
        .parse()
        .unwrap_or(stage.meters_per_unit);
    let _ = writeln!(s, "    metersPerUnit = {}", num(unit));
    let _ = writeln!(s, "    startTimeCode = {}", num(codes[0]));
    let _ = writeln!(s, "    timeCodesPerSecond = {}", num(rate));
    let up = if stage.z_up { "Z" } else { "Y" };
    let _ = writeln!(s, "    upAxis = \"{up}\"\n)\n");
    let _ = writeln!(s, "def SkelRoot \"Clip\"\n{{");
    let _ = writeln!(
        s,
        "    def Skeleton \"Skeleton\" (\n        prepend apiSchemas = [\"SkelBindingAPI\"]\n    )\n    {{"
    );
    let tokens: Vec<String> = paths.iter().map(|p| format!("\"{p}\"")).collect();
    let tokens = tokens.join(", ");
    let _ = writeln!(s, "        uniform token[] joints = [{tokens}]");
    // Rest poses: local, then composed from the root.
    let mut world: Vec<glam::DMat4> = Vec::with_capacity(joints.len());
    let mut rest = Vec::with_capacity(joints.len());
    for j in joints {
        let local =
            glam::DMat4::from_scale_rotation_translation(j.scale, j.rotation, j.translation);
        let w = j.parent.map_or(local, |p| world[p] * local);
        rest.push(matrix(&local));
        world.push(w);
    }
    let bind: Vec<String> = world.iter().map(matrix).collect();
    let _ = writeln!(
        s,
        "        uniform matrix4d[] bindTransforms = [{}]",
        bind.join(", ")
    );
    let _ = writeln!(
        s,
        "        uniform matrix4d[] restTransforms = [{}]",
        rest.join(", ")
    );
    let _ = writeln!(
        s,
        "        rel skel:animationSource = </Clip/Skeleton/Animation>\n"
    );
    let _ = writeln!(s, "        def SkelAnimation \"Animation\"\n        {{");
    let _ = writeln!(s, "            uniform token[] joints = [{tokens}]");
    out.write_all(s.as_bytes())?;
    s.clear();

    let pose = |j: usize, i: usize| -> (DQuat, DVec3) {
        let joint = &joints[j];
        match joint.track {
            Some(t) => {
                let q = tracks[t].rotations[i];
                let p = tracks[t]
                    .positions
                    .as_ref()
                    .map_or(joint.translation, |p| p[i]);
                (q, p)
            }
            None => (joint.rotation, joint.translation),
        }
    };
    let rotations = |i: usize, j: usize| -> io::Result<String> {
        let q = pose(j, i).0;
        if !q.is_finite() {
            return Err(internal(format!(
                "joint \"{}\" has a rotation that is not finite",
                joints[j].name
            )));
        }
        let q = if q.w < 0.0 { -q } else { q };
        Ok(format!(
            "({}, {}, {}, {})",
            f32s(q.w),
            f32s(q.x),
            f32s(q.y),
            f32s(q.z)
        ))
    };
    let scales = |_: usize, j: usize| -> io::Result<String> {
        let v = joints[j].scale;
        Ok(format!("({}, {}, {})", f32s(v.x), f32s(v.y), f32s(v.z)))
    };
    let translations = |i: usize, j: usize| -> io::Result<String> {
        let p = pose(j, i).1;
        if !p.is_finite() {
            return Err(internal(format!(
                "joint \"{}\" has a translation that is not finite",
                joints[j].name
            )));
        }
        Ok(format!("({}, {}, {})", f32s(p.x), f32s(p.y), f32s(p.z)))
    };
    samples(
        &mut out,
        "quatf[] rotations",
        codes,
        joints.len(),
        rotations,
    )?;
    samples(&mut out, "half3[] scales", codes, joints.len(), scales)?;
    samples(
        &mut out,
        "float3[] translations",
        codes,
        joints.len(),
        translations,
    )?;
    let _ = writeln!(s, "        }}\n    }}\n}}");
    out.write_all(s.as_bytes())?;
    out.flush()
}

/// One attribute's `timeSamples`: at each code, `value(sample, joint)` of every joint.
fn samples<W: Write>(
    out: &mut W,
    attribute: &str,
    codes: &[f64],
    joints: usize,
    value: impl Fn(usize, usize) -> io::Result<String>,
) -> io::Result<()> {
    let mut s = format!("            {attribute}.timeSamples = {{\n");
    for (i, &c) in codes.iter().enumerate() {
        let _ = write!(s, "                {}: [", num(c));
        for j in 0..joints {
            if j > 0 {
                s.push_str(", ");
            }
            s.push_str(&value(i, j)?);
        }
        s.push_str("],\n");
        if s.len() > 1 << 16 {
            out.write_all(s.as_bytes())?;
            s.clear();
        }
    }
    s.push_str("            }\n");
    out.write_all(s.as_bytes())
}

/// A double as the shortest decimal that reads back as it (`-0` as `0`).
fn num(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x}") }
}

/// A value rounded to float32, as the shortest decimal that reads back as that float.
fn f32s(x: f64) -> String {
    let f = x as f32;
    if f == 0.0 { "0".into() } else { format!("{f}") }
}

/// A 4×4 matrix as usda writes it: rows, the translation in the last (row vectors).
fn matrix(m: &glam::DMat4) -> String {
    let c = m.to_cols_array_2d();
    // glam's columns are USD's rows (USD multiplies row vectors on the left).
    let rows: Vec<String> = c
        .iter()
        .map(|r| {
            format!(
                "({}, {}, {}, {})",
                num(r[0]),
                num(r[1]),
                num(r[2]),
                num(r[3])
            )
        })
        .collect();
    format!("({})", rows.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use inbetween::skeleton::Joint;

    #[test]
    fn names_become_identifiers() {
        assert_eq!(usd_name("Bone.001"), "Bone_001");
        assert_eq!(usd_name("mixamorig:Hips"), "mixamorig_Hips");
        assert_eq!(usd_name("3ds"), "_3ds");
        assert_eq!(usd_name(""), "_");
        assert_eq!(usd_name("Bip01 L Thigh"), "Bip01_L_Thigh");
    }

    #[test]
    fn colliding_names_get_their_index() {
        let s = Skeleton::new(vec![
            Joint::new("a", None, DVec3::ZERO).with_track(0),
            Joint::new("b.1", Some(0), DVec3::X),
            Joint::new("b_1", Some(0), DVec3::Y),
        ])
        .unwrap();
        assert_eq!(joint_paths(&s), ["a", "a/b_1", "a/b_1_2"]);
        // The suffix itself taken: the next one.
        let s = Skeleton::new(vec![
            Joint::new("a", None, DVec3::ZERO).with_track(0),
            Joint::new("b_1_2", Some(0), DVec3::X),
            Joint::new("b.1", Some(0), DVec3::Y),
            Joint::new("b_1", Some(0), DVec3::Z),
        ])
        .unwrap();
        let paths = joint_paths(&s);
        assert_eq!(paths, ["a", "a/b_1_2", "a/b_1", "a/b_1_3"]);
        let unique: HashSet<&String> = paths.iter().collect();
        assert_eq!(unique.len(), paths.len());
        // Names that are USD joint paths keep them.
        let s = Skeleton::new(vec![
            Joint::new("Hips", None, DVec3::ZERO).with_track(0),
            Joint::new("Hips/arm", Some(0), DVec3::X),
            Joint::new("Hips/arm/hand", Some(1), DVec3::X),
            Joint::new("Hips/leg", Some(0), DVec3::Y),
            Joint::new("Hips/leg/hand", Some(3), DVec3::Y),
        ])
        .unwrap();
        assert_eq!(
            joint_paths(&s),
            [
                "Hips",
                "Hips/arm",
                "Hips/arm/hand",
                "Hips/leg",
                "Hips/leg/hand"
            ]
        );
    }

    #[test]
    fn writes_samples_of_every_joint() {
        let s = Skeleton::new(vec![
            Joint::new("Hips", None, DVec3::new(0.0, 90.0, 0.0)).with_track(0),
            Joint::new("Spine", Some(0), DVec3::new(0.0, 10.0, 0.0)),
        ])
        .unwrap();
        let q = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let track = TrackSamples {
            rotations: vec![DQuat::IDENTITY, -q],
            positions: Some(vec![DVec3::new(0.0, 90.0, 0.0), DVec3::new(1.0, 90.0, 0.0)]),
        };
        let mut out = Vec::new();
        write_usda(
            &mut out,
            &s,
            Fps::new(30000, 1001).unwrap(),
            &[0.0, 1.0],
            &[track],
            Stage {
                meters_per_unit: 0.025400000000000002,
                z_up: true,
            },
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.contains("timeCodesPerSecond = 29.97002997002997\n"),
            "{text}"
        );
        assert!(text.contains("metersPerUnit = 0.0254\n") && text.contains("upAxis = \"Z\"\n"));
        assert!(text.contains("uniform token[] joints = [\"Hips\", \"Hips/Spine\"]"));
        // −q is written with w ≥ 0; the unanimated joint holds its rest pose.
        assert!(
            text.contains("1: [(0.70710677, 0, 0, 0.70710677), (1, 0, 0, 0)],"),
            "{text}"
        );
        assert!(text.contains("1: [(1, 90, 0), (0, 10, 0)],"));
        assert!(text.contains("((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 100, 0, 1))"));
        let mut out = Vec::new();
        let short = TrackSamples {
            rotations: vec![DQuat::IDENTITY],
            positions: None,
        };
        let e = write_usda(
            &mut out,
            &s,
            Fps::new(30, 1).unwrap(),
            &[0.0, 1.0],
            &[short],
            Stage {
                meters_per_unit: 1.0,
                z_up: false,
            },
        );
        assert!(e.unwrap_err().to_string().contains("internal error"));
    }
}
