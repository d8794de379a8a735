//! How far apart two motions are (`inbetween diff`, and the check of `reduce
//! --position-tolerance`; docs/spec.md §5b): per track the geodesic angle between the two
//! rotations at each compared time, and the distance between translations; with a skeleton,
//! the world-space displacement of every point a viewer sees ([`crate::skeleton`]).

use crate::rotation::quat::rotation_angle_between;
use crate::skeleton::Skeleton;
use glam::{DAffine3, DQuat, DVec3};

/// The largest value of a series, where it is, and the mean.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Extent {
    /// The largest value (0 for no values; a NaN counts as infinite).
    pub max: f64,
    /// The index of the first value that is the largest.
    pub at: usize,
    /// The mean of the values.
    pub mean: f64,
    /// How many values.
    pub count: usize,
}

impl Extent {
    /// The extent of `values`.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Extent {
        let mut e = Extent::default();
        let mut sum = 0.0;
        for (i, v) in values.into_iter().enumerate() {
            let v = if v.is_nan() { f64::INFINITY } else { v };
            if v > e.max || i == 0 {
                (e.max, e.at) = (v, i);
            }
            sum += v;
            e.count += 1;
        }
        if e.count > 0 {
            e.mean = sum / e.count as f64;
        }
        e
    }
}

/// One track of motion A against motion B at the same times.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackDiff {
    /// The rotation angle between the two, rad.
    pub angle: Extent,
    /// The distance between the two translations, where both have them.
    pub translation: Option<Extent>,
}

/// A track's difference: A's rotations `a` (and translations `a_pos`) against `b(k)`, B's
/// rotation (and translation) at the same `k`-th time.
pub fn track_diff(
    a: &[DQuat],
    a_pos: Option<&[DVec3]>,
    b: impl Fn(usize) -> (DQuat, Option<DVec3>),
) -> TrackDiff {
    let bs: Vec<(DQuat, Option<DVec3>)> = (0..a.len()).map(b).collect();
    let angle = Extent::of(
        a.iter()
            .zip(&bs)
            .map(|(&qa, &(qb, _))| rotation_angle_between(qa, qb)),
    );
    let translation = match (a_pos, bs.first().and_then(|b| b.1)) {
        (Some(p), Some(_)) => {
            Some(Extent::of(p.iter().zip(&bs).map(|(&pa, &(_, pb))| {
                pb.map_or(f64::INFINITY, |pb| (pa - pb).length())
            })))
        }
        _ => None,
    };
    TrackDiff { angle, translation }
}

/// Every joint's world-space displacement over the frames of two poses of one skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldDiff {
    /// Per track: the largest displacement of the points it moves (its joint's, and those of
    /// the joints below it that no other track animates) over the frames, with the frame; the
    /// mean is of its joint's origin. `None` for a track no joint takes.
    pub tracks: Vec<Option<Extent>>,
    /// Per frame, the largest displacement of any point measured (infinite for a NaN): the
    /// curve whose largest value is the largest of `tracks` (`inbetween view` draws it).
    pub frames: Vec<f64>,
}

/// A pose source: the rotation and translation of track `t` at frame `f`, as `(f, t) → pose`.
pub(crate) type Poses<'a> = dyn Fn(usize, usize) -> (DQuat, Option<DVec3>) + Sync + 'a;

/// The world displacement between `a` and `b` posed on `skeleton` at `frames` frames, every
/// point of [`Skeleton::points`] measured (with the three points at `shell` around each joint
/// when given). `a` and `b` give the pose of track `t` at frame `f` as `(rotation, translation)`.
pub fn world_diff(
    skeleton: &Skeleton,
    frames: usize,
    a: &(dyn Fn(usize, usize) -> (DQuat, Option<DVec3>) + Sync),
    b: &(dyn Fn(usize, usize) -> (DQuat, Option<DVec3>) + Sync),
    shell: Option<f64>,
) -> WorldDiff {
    let owner = skeleton.owners();
    let point_owner: Vec<Option<usize>> = skeleton
        .point_joints(shell.is_some())
        .iter()
        .map(|&j| owner[j])
        .collect();
    let track_joints = skeleton.track_joints();
    let tracks = skeleton.track_count();
    let scan = scan(skeleton, frames, a, b, shell, None);
    let mut best = vec![(0.0f64, 0usize); tracks];
    for (&(d, f), o) in scan.points.iter().zip(&point_owner) {
        if let Some(t) = *o
            && (d > best[t].0 || (d == best[t].0 && f < best[t].1))
        {
            best[t] = (d, f);
        }
    }
    WorldDiff {
        tracks: (0..tracks)
            .map(|t| {
                track_joints[t].map(|j| Extent {
                    max: best[t].0,
                    at: best[t].1,
                    mean: if frames > 0 {
                        scan.origin_sums[j] / frames as f64
                    } else {
                        0.0
                    },
                    count: frames,
                })
            })
            .collect(),
        frames: scan.frames,
    }
}

/// A point's displacement past its limit at one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Miss {
    pub(crate) frame: usize,
    pub(crate) point: usize,
    /// The displacement (length units; infinite for a NaN).
    pub(crate) displacement: f64,
}

/// Per point of [`Skeleton::points`] (in its order, with the shell's points when `shell` is
/// given), its largest world displacement between `a` and `b` over `frames` frames and the first
/// frame where it occurs (a NaN counts as infinite); and every point and frame where the
/// displacement exceeds the point's entry of `limits`, in frame order.
pub(crate) fn point_misses(
    skeleton: &Skeleton,
    frames: usize,
    a: &Poses<'_>,
    b: &Poses<'_>,
    shell: Option<f64>,
    limits: &[f64],
) -> (Vec<(f64, usize)>, Vec<Miss>) {
    let scan = scan(skeleton, frames, a, b, shell, Some(limits));
    (scan.points, scan.misses)
}

/// What one pass over the frames measures.
struct Scan {
    /// Per point, the largest displacement and its first frame.
    points: Vec<(f64, usize)>,
    /// Per joint, the sum over the frames of its origin's displacement.
    origin_sums: Vec<f64>,
    /// Per frame, the largest displacement of any point.
    frames: Vec<f64>,
    /// The points past their limits, when limits are given.
    misses: Vec<Miss>,
}

/// The frames posed and compared, in chunks on the cores; the chunks merged in frame order.
fn scan(
    skeleton: &Skeleton,
    frames: usize,
    a: &Poses<'_>,
    b: &Poses<'_>,
    shell: Option<f64>,
    limits: Option<&[f64]>,
) -> Scan {
    let n_points = skeleton.point_joints(shell.is_some()).len();
    let n_joints = skeleton.joints().len();
    let chunk = frames
        .div_ceil(crate::parallel::MAX_THREADS.max(1) * 4)
        .max(1);
    let starts: Vec<usize> = (0..frames).step_by(chunk).collect();
    let parts = crate::parallel::map(&starts, |&s| {
        let mut best = vec![(0.0f64, s); n_points];
        let mut origin_sums = vec![0.0; n_joints];
        let mut largest = Vec::with_capacity(chunk);
        let mut misses = Vec::new();
        let (mut wa, mut wb) = (Vec::new(), Vec::new());
        let (mut pa, mut pb) = (Vec::new(), Vec::new());
        for f in s..(s + chunk).min(frames) {
            skeleton.world(|t| a(f, t), &mut wa);
            skeleton.world(|t| b(f, t), &mut wb);
            points(skeleton, &wa, shell, &mut pa);
            points(skeleton, &wb, shell, &mut pb);
            let mut frame_max = 0.0f64;
            for (point, ((x, y), best)) in pa.iter().zip(&pb).zip(&mut best).enumerate() {
                let d = nan_max((*x - *y).length());
                frame_max = frame_max.max(d);
                if d > best.0 {
                    *best = (d, f);
                }
                if limits.is_some_and(|l| d > l[point]) {
                    misses.push(Miss {
                        frame: f,
                        point,
                        displacement: d,
                    });
                }
            }
            largest.push(frame_max);
            for ((x, y), sum) in wa.iter().zip(&wb).zip(&mut origin_sums) {
                *sum += nan_max((x.translation - y.translation).length());
            }
        }
        Scan {
            points: best,
            origin_sums,
            frames: largest,
            misses,
        }
    });
    let mut out = Scan {
        points: vec![(0.0, 0); n_points],
        origin_sums: vec![0.0; n_joints],
        frames: Vec::with_capacity(frames),
        misses: Vec::new(),
    };
    for part in parts {
        for (o, p) in out.points.iter_mut().zip(&part.points) {
            if p.0 > o.0 {
                *o = *p;
            }
        }
        for (o, p) in out.origin_sums.iter_mut().zip(&part.origin_sums) {
            *o += p;
        }
        out.frames.extend(part.frames);
        out.misses.extend(part.misses);
    }
    out
}

fn points(skeleton: &Skeleton, world: &[DAffine3], shell: Option<f64>, out: &mut Vec<DVec3>) {
    skeleton.points_of(world, shell, out);
}

fn nan_max(d: f64) -> f64 {
    if d.is_nan() { f64::INFINITY } else { d }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;

    /// Closed form: a root turned by θ about z against the unturned pose moves a bone end at
    /// distance L by 2·L·sin(θ/2); the end's own joint is not animated, so the root owns it.
    #[test]
    fn a_turned_root_moves_the_end_by_the_chord() {
        let s = Skeleton::new(vec![
            Joint::new("root", None, DVec3::ZERO).with_track(0),
            Joint::new("bone", Some(0), DVec3::new(0.0, 0.0, 0.0))
                .with_ends(vec![DVec3::new(2.0, 0.0, 0.0)]),
        ])
        .unwrap();
        let theta = 0.3;
        let a = |f: usize, _t: usize| (DQuat::from_rotation_z(theta * f as f64), None);
        let b = |_f: usize, _t: usize| (DQuat::IDENTITY, None);
        let d = world_diff(&s, 3, &a, &b, None);
        let e = d.tracks[0].unwrap();
        let want = 2.0 * 2.0 * (theta * 2.0 / 2.0).sin();
        assert!((e.max - want).abs() < 1e-14, "{} {want}", e.max);
        assert_eq!(e.at, 2);
        // Per frame: the end's chord at each frame's angle, 0 at frame 0.
        for (f, &x) in d.frames.iter().enumerate() {
            let chord = 2.0 * 2.0 * (theta * f as f64 / 2.0).sin();
            assert!((x - chord).abs() < 1e-14, "frame {f}: {x} {chord}");
        }
        assert_eq!(d.frames.len(), 3);
        // The origin sits on the axis: it never moves.
        assert_eq!(e.mean, 0.0);
        // A shell at 0.5 around the root adds a point that moves by 2·0.5·sin(θ): less.
        let shelled = world_diff(&s, 3, &a, &b, Some(0.5)).tracks[0].unwrap();
        assert!((shelled.max - want).abs() < 1e-14);
    }

    #[test]
    fn track_diff_measures_angles_and_translations() {
        let a = [DQuat::IDENTITY, DQuat::from_rotation_x(0.25)];
        let p = [DVec3::ZERO, DVec3::X];
        let d = track_diff(&a, Some(&p), |_| (DQuat::IDENTITY, Some(DVec3::ZERO)));
        assert!((d.angle.max - 0.25).abs() < 1e-15);
        assert_eq!((d.angle.at, d.angle.count), (1, 2));
        assert!((d.angle.mean - 0.125).abs() < 1e-15);
        let t = d.translation.unwrap();
        assert_eq!((t.max, t.at, t.mean), (1.0, 1, 0.5));
        assert!(Extent::of([f64::NAN, 1.0]).max.is_infinite());
    }
}
