//! A skeleton: joints in a hierarchy with their rest transforms, some of them animated by
//! tracks, and the points a viewer sees — each joint's origin, its bone ends (BVH `End Site`s)
//! and, optionally, three points around it (ACL's *virtual vertices*) — composed from the root
//! into world space (docs/spec.md §5a, *World space*).
//!
//! A joint's world transform is its parent's world transform times its local transform
//! `T(t)·R(q)·S(s)`: `t` the track's translation at that frame where the track has
//! translations (BVH position channels, glTF translation channels), else the rest translation
//! (BVH `OFFSET`, glTF node `translation`); `q` the track's rotation, else the rest rotation
//! (identity in BVH); `s` the rest scale (1 in BVH). BVH position channels therefore replace
//! the `OFFSET` of their joint, as bvhio and Blender's importer read them.
//!
//! ```
//! use inbetween::skeleton::{Joint, Skeleton};
//! use glam::{DQuat, DVec3};
//!
//! // A root turned by a track, and a bone of length 2 along x ending in an end point.
//! let skeleton = Skeleton::new(vec![
//!     Joint::new("root", None, DVec3::ZERO).with_track(0),
//!     Joint::new("bone", Some(0), DVec3::X).with_ends(vec![DVec3::new(2.0, 0.0, 0.0)]),
//! ])?;
//! let mut points = Vec::new();
//! let quarter = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
//! skeleton.points(|_| (quarter, None), None, &mut points);
//! // root origin, bone origin, bone end: (0,0,0), (0,1,0), (0,3,0)
//! assert!((points[2] - DVec3::new(0.0, 3.0, 0.0)).length() < 1e-15);
//! # Ok::<(), inbetween::InputError>(())
//! ```

use crate::error::{InputError, input_err};
use glam::{DAffine3, DQuat, DVec3};

/// One joint of a [`Skeleton`].
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// The joint's name (a BVH joint's track name, a glTF node's).
    pub name: String,
    /// The parent's index in [`Skeleton::joints`], always before the joint; `None` for a root.
    pub parent: Option<usize>,
    /// The rest translation in the parent's frame (BVH `OFFSET`).
    pub translation: DVec3,
    /// The rest rotation (identity for BVH).
    pub rotation: DQuat,
    /// The rest scale (one for BVH).
    pub scale: DVec3,
    /// The track that animates the joint, by its index among the tracks.
    pub track: Option<usize>,
    /// Further points in the joint's own frame: bone ends (a BVH `End Site`).
    pub ends: Vec<DVec3>,
}

impl Joint {
    /// A joint at `translation` from its parent, unrotated, unscaled, not animated.
    pub fn new(name: impl Into<String>, parent: Option<usize>, translation: DVec3) -> Joint {
        Joint {
            name: name.into(),
            parent,
            translation,
            rotation: DQuat::IDENTITY,
            scale: DVec3::ONE,
            track: None,
            ends: Vec::new(),
        }
    }

    /// The joint animated by track `track`.
    pub fn with_track(mut self, track: usize) -> Joint {
        self.track = Some(track);
        self
    }

    /// The joint with end points `ends` in its frame.
    pub fn with_ends(mut self, ends: Vec<DVec3>) -> Joint {
        self.ends = ends;
        self
    }
}

/// Joints in a hierarchy, parents first (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Skeleton {
    joints: Vec<Joint>,
    tracks: usize,
}

impl Skeleton {
    /// The skeleton of `joints`. Errors: a parent that does not come before its child, a track
    /// animating two joints, a value that is not finite.
    pub fn new(joints: Vec<Joint>) -> Result<Skeleton, InputError> {
        // Tracks seen, by a hash set: linear in the joints.
        let mut seen = std::collections::HashSet::new();
        let mut tracks = 0;
        for (i, j) in joints.iter().enumerate() {
            if j.parent.is_some_and(|p| p >= i) {
                return Err(input_err!(
                    "joint {i} ({:?}): its parent comes after it",
                    crate::error::shorten(&j.name)
                ));
            }
            let finite = j.translation.is_finite()
                && j.rotation.is_finite()
                && j.scale.is_finite()
                && j.ends.iter().all(|e| e.is_finite());
            if !finite {
                return Err(input_err!(
                    "joint {i} ({:?}): a value is not finite",
                    crate::error::shorten(&j.name)
                ));
            }
            if let Some(t) = j.track {
                if !seen.insert(t) {
                    return Err(input_err!(
                        "joint {i} ({:?}): track {t} already animates another joint",
                        crate::error::shorten(&j.name)
                    ));
                }
                tracks = tracks.max(t + 1);
            }
        }
        Ok(Skeleton { joints, tracks })
    }

    /// The skeleton with end points added where an animated joint's rotation would move no
    /// point: a joint with no end point of its own and no descendant away from its origin (a
    /// leaf bone exported without its end, a glTF joint without children). Such a joint gets
    /// the three points at a bone length `d` along its own x, y and z axes — `d` its own rest
    /// offset from its parent (its bone's length), else the median length of the skeleton's
    /// non-zero offsets — so that any rotation of it moves one of them by at least
    /// `2·d·√⅔·sin(θ/2)`. Returns the skeleton, each joint given points with its `d` (in the
    /// length units of its parent's frame), and the joints that could not be given any (a
    /// skeleton whose offsets are all zero).
    pub fn with_default_ends(&self) -> (Skeleton, Vec<(usize, f64)>, Vec<usize>) {
        // Whether a point of the joint's subtree lies away from its origin, children first.
        let mut moves: Vec<bool> = self
            .joints
            .iter()
            .map(|j| j.ends.iter().any(|&e| e != DVec3::ZERO))
            .collect();
        for (i, j) in self.joints.iter().enumerate().rev() {
            if let Some(p) = j.parent {
                moves[p] |= moves[i] || j.translation != DVec3::ZERO;
            }
        }
        let mut offsets: Vec<f64> = self
            .joints
            .iter()
            .map(|j| j.translation.length())
            .filter(|&l| l > 0.0)
            .collect();
        offsets.sort_by(f64::total_cmp);
        let median = offsets.get(offsets.len() / 2).copied();
        let mut out = self.clone();
        let (mut given, mut unbounded) = (Vec::new(), Vec::new());
        for (i, j) in out.joints.iter_mut().enumerate() {
            if j.track.is_none() || moves[i] {
                continue;
            }
            let own = j.translation.length();
            let Some(d) = Some(own).filter(|&l| l > 0.0).or(median) else {
                unbounded.push(i);
                continue;
            };
            // In the joint's own frame, whose rest scale stretches it.
            let local = d / j.scale.abs().max_element().max(f64::MIN_POSITIVE);
            j.ends
                .extend([DVec3::X, DVec3::Y, DVec3::Z].map(|axis| axis * local));
            given.push((i, d));
        }
        (out, given, unbounded)
    }

    /// The skeleton with a shell of radius `d` in world units: every joint gets the three end
    /// points `d/σ` along its own x, y and z axes, `σ` the product of the largest rest scale
    /// factors of the joint and its ancestors — `d` from the joint in world space where those
    /// scales are uniform (an armature scaled to 0.0254 has its shell in the scene's units, not
    /// in its bones'), at most `d` otherwise.
    pub fn with_shell(&self, d: f64) -> Skeleton {
        let mut out = self.clone();
        let mut sigma: Vec<f64> = Vec::with_capacity(self.joints.len());
        for j in &mut out.joints {
            let own = j.scale.abs().max_element();
            let s = j.parent.map_or(own, |p| sigma[p] * own);
            sigma.push(s);
            let local = d / s.max(f64::MIN_POSITIVE);
            j.ends
                .extend([DVec3::X, DVec3::Y, DVec3::Z].map(|axis| axis * local));
        }
        out
    }

    /// The joints, parents first.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// One more than the largest track index of the joints.
    pub fn track_count(&self) -> usize {
        self.tracks
    }

    /// The joint each track animates (`None` for a track no joint takes).
    pub fn track_joints(&self) -> Vec<Option<usize>> {
        let mut out = vec![None; self.tracks];
        for (i, j) in self.joints.iter().enumerate() {
            if let Some(t) = j.track {
                out[t] = Some(i);
            }
        }
        out
    }

    /// Each track's nearest ancestor joint that is animated, as a track index (`None`: none).
    pub fn track_parents(&self) -> Vec<Option<usize>> {
        let mut out = vec![None; self.tracks];
        for j in &self.joints {
            if let Some(t) = j.track {
                out[t] = self
                    .animated_ancestor(j.parent)
                    .and_then(|a| self.joints[a].track);
            }
        }
        out
    }

    /// The nearest animated joint at or above `joint`.
    fn animated_ancestor(&self, mut joint: Option<usize>) -> Option<usize> {
        while let Some(j) = joint {
            if self.joints[j].track.is_some() {
                return Some(j);
            }
            joint = self.joints[j].parent;
        }
        None
    }

    /// The skeleton with its tracks renumbered: track `t` becomes `map[t]`, and a joint whose
    /// track maps to `None` (or past `map`) is no longer animated (a track selection).
    pub fn retracked(&self, map: &[Option<usize>]) -> Skeleton {
        let mut joints = self.joints.clone();
        for j in &mut joints {
            j.track = j.track.and_then(|t| map.get(t).copied().flatten());
        }
        let tracks = joints
            .iter()
            .filter_map(|j| j.track)
            .max()
            .map_or(0, |m| m + 1);
        Skeleton { joints, tracks }
    }

    /// The world transform of every joint for one pose: `pose(track)` gives that track's
    /// rotation and, where it has one, its translation. `out` is overwritten.
    pub fn world(&self, pose: impl Fn(usize) -> (DQuat, Option<DVec3>), out: &mut Vec<DAffine3>) {
        out.clear();
        for j in &self.joints {
            let (q, t) = j.track.map_or((j.rotation, None), &pose);
            let local =
                DAffine3::from_scale_rotation_translation(j.scale, q, t.unwrap_or(j.translation));
            let world = j.parent.map_or(local, |p| out[p] * local);
            out.push(world);
        }
    }

    /// The points of one pose in world space ([`Skeleton::world`]), joint by joint: its origin,
    /// its end points, and with `shell = Some(d)` the three points at `d` along its own x, y
    /// and z axes. `out` is overwritten; [`Skeleton::point_joints`] says whose each point is.
    pub fn points(
        &self,
        pose: impl Fn(usize) -> (DQuat, Option<DVec3>),
        shell: Option<f64>,
        out: &mut Vec<DVec3>,
    ) {
        let mut world = Vec::with_capacity(self.joints.len());
        self.world(pose, &mut world);
        self.points_of(&world, shell, out);
    }

    /// [`Skeleton::points`] of world transforms already composed.
    pub fn points_of(&self, world: &[DAffine3], shell: Option<f64>, out: &mut Vec<DVec3>) {
        out.clear();
        for (j, w) in self.joints.iter().zip(world) {
            out.push(w.translation);
            out.extend(j.ends.iter().map(|&e| w.transform_point3(e)));
            if let Some(d) = shell {
                out.extend([DVec3::X, DVec3::Y, DVec3::Z].map(|axis| w.transform_point3(axis * d)));
            }
        }
    }

    /// The joint of each point [`Skeleton::points`] gives, in its order.
    pub fn point_joints(&self, shell: bool) -> Vec<usize> {
        let mut out = Vec::new();
        for (i, j) in self.joints.iter().enumerate() {
            let n = 1 + j.ends.len() + if shell { 3 } else { 0 };
            out.extend(std::iter::repeat_n(i, n));
        }
        out
    }

    /// The track owning each joint's points: its own, else its nearest animated ancestor's
    /// (`None` above every animated joint).
    pub fn owners(&self) -> Vec<Option<usize>> {
        let mut out: Vec<Option<usize>> = Vec::with_capacity(self.joints.len());
        for j in &self.joints {
            let owner = j.track.or_else(|| j.parent.and_then(|p| out[p]));
            out.push(owner);
        }
        out
    }

    /// Whether `ancestor` is `joint` or above it.
    pub fn is_at_or_above(&self, ancestor: usize, joint: usize) -> bool {
        let mut at = Some(joint);
        while let Some(j) = at {
            if j == ancestor {
                return true;
            }
            at = self.joints[j].parent;
        }
        false
    }

    /// The animated joints at or above `joint`, nearest first.
    pub fn animated_chain(&self, joint: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut at = self.animated_ancestor(Some(joint));
        while let Some(j) = at {
            out.push(j);
            at = self.animated_ancestor(self.joints[j].parent);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn arm() -> Skeleton {
        Skeleton::new(vec![
            Joint::new("root", None, DVec3::new(1.0, 0.0, 0.0)).with_track(1),
            Joint::new("mid", Some(0), DVec3::new(0.0, 0.0, 0.0)),
            Joint::new("elbow", Some(1), DVec3::new(2.0, 0.0, 0.0))
                .with_track(0)
                .with_ends(vec![DVec3::new(3.0, 0.0, 0.0)]),
        ])
        .unwrap()
    }

    /// Closed form: root at (5,0,0) turned 90° about z, elbow turned 90° about z: the elbow
    /// sits at (5,2,0), its end 3 further along −x: (2,2,0).
    #[test]
    fn composes_from_the_root() {
        let s = arm();
        let quarter = DQuat::from_rotation_z(FRAC_PI_2);
        let mut p = Vec::new();
        s.points(
            |t| (quarter, (t == 1).then_some(DVec3::new(5.0, 0.0, 0.0))),
            Some(0.5),
            &mut p,
        );
        let want = [
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.0, 0.5, 0.0),
            DVec3::new(4.5, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.5),
        ];
        for (got, want) in p[..4].iter().zip(want) {
            assert!((*got - want).length() < 1e-15, "{got} {want}");
        }
        let elbow = &p[8..];
        assert!((elbow[0] - DVec3::new(5.0, 2.0, 0.0)).length() < 1e-14);
        assert!((elbow[1] - DVec3::new(2.0, 2.0, 0.0)).length() < 1e-14);
        assert_eq!(
            s.point_joints(true),
            [0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 2]
        );
        assert_eq!(s.track_parents(), [Some(1), None]);
        assert_eq!(s.animated_chain(2), [2, 0]);
        assert_eq!(s.track_joints(), [Some(2), Some(0)]);
        let only_root = s.retracked(&[None, Some(0)]);
        assert_eq!(only_root.track_joints(), [Some(0)]);
        assert_eq!(only_root.animated_chain(2), [0]);
    }

    #[test]
    fn refuses_what_is_not_a_hierarchy() {
        let late = Skeleton::new(vec![Joint::new("a", Some(0), DVec3::ZERO)]);
        assert!(late.unwrap_err().to_string().contains("parent comes after"));
        let twice = Skeleton::new(vec![
            Joint::new("a", None, DVec3::ZERO).with_track(0),
            Joint::new("b", Some(0), DVec3::ZERO).with_track(0),
        ]);
        assert!(twice.unwrap_err().to_string().contains("already animates"));
        let nan = Skeleton::new(vec![Joint::new("a", None, DVec3::NAN)]);
        assert!(nan.unwrap_err().to_string().contains("not finite"));
    }

    #[test]
    fn joints_that_move_no_point_get_default_ends_at_a_bone_length() {
        // root -> arm (offset 2 along x) -> hand (offset 1, a leaf without an end);
        // a second leaf "tip" with its own end site is left alone.
        let skeleton = Skeleton::new(vec![
            Joint::new("root", None, DVec3::ZERO).with_track(0),
            Joint::new("arm", Some(0), DVec3::new(2.0, 0.0, 0.0)).with_track(1),
            Joint::new("hand", Some(1), DVec3::new(1.0, 0.0, 0.0)).with_track(2),
            Joint::new("tip", Some(1), DVec3::new(0.0, 3.0, 0.0))
                .with_track(3)
                .with_ends(vec![DVec3::Y]),
            Joint::new("still", Some(0), DVec3::ZERO),
        ])
        .unwrap();
        let (bounded, given, unbounded) = skeleton.with_default_ends();
        assert_eq!(given, [(2, 1.0)]);
        assert!(unbounded.is_empty());
        assert_eq!(
            bounded.joints()[2].ends,
            [DVec3::X, DVec3::Y, DVec3::Z],
            "the hand's bone length along each axis"
        );
        assert_eq!(bounded.joints()[3].ends, [DVec3::Y]);
        // Any rotation of the hand now moves a point: a quarter turn about x moves the y and z
        // points by √2.
        let quarter = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
        let (mut rest, mut turned) = (Vec::new(), Vec::new());
        bounded.points(|_| (DQuat::IDENTITY, None), None, &mut rest);
        bounded.points(
            |t| (if t == 2 { quarter } else { DQuat::IDENTITY }, None),
            None,
            &mut turned,
        );
        let moved = rest
            .iter()
            .zip(&turned)
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        assert!((moved - 2f64.sqrt()).abs() < 1e-12, "{moved}");
        // A root alone at the origin with no offsets anywhere: nothing to derive a length from.
        let lone =
            Skeleton::new(vec![Joint::new("only", None, DVec3::ZERO).with_track(0)]).unwrap();
        let (_, given, unbounded) = lone.with_default_ends();
        assert!(given.is_empty());
        assert_eq!(unbounded, [0]);
        // A leaf at zero offset takes the median offset.
        let zero = Skeleton::new(vec![
            Joint::new("root", None, DVec3::ZERO).with_track(0),
            Joint::new("a", Some(0), DVec3::new(0.0, 4.0, 0.0)),
            Joint::new("b", Some(1), DVec3::ZERO).with_track(1),
        ])
        .unwrap();
        assert_eq!(zero.with_default_ends().1, [(2, 4.0)]);
    }

    #[test]
    fn a_shell_is_in_world_units_under_a_scaled_armature() {
        // An armature scaled by 0.5 (a unit conversion), a bone below it at local offset 4.
        let mut armature = Joint::new("armature", None, DVec3::ZERO).with_track(0);
        armature.scale = DVec3::splat(0.5);
        let skeleton = Skeleton::new(vec![
            armature,
            Joint::new("bone", Some(0), DVec3::new(4.0, 0.0, 0.0)).with_track(1),
        ])
        .unwrap();
        let shelled = skeleton.with_shell(0.1);
        let mut points = Vec::new();
        shelled.points(|_| (DQuat::IDENTITY, None), None, &mut points);
        // bone: origin at 2 (world), its shell points 0.1 from it in world space.
        let origin = points[4];
        assert!((origin - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-15);
        for p in &points[5..8] {
            assert!(((*p - origin).length() - 0.1).abs() < 1e-15, "{p}");
        }
        // The armature's own shell too: 0.1 in world space, 0.2 in its frame.
        assert!(((points[1] - points[0]).length() - 0.1).abs() < 1e-15);
        assert_eq!(shelled.joints()[0].ends[0], DVec3::new(0.2, 0.0, 0.0));
    }
}
