//! Keys added where points miss (docs/spec.md §4.7): the world-space counterpart of
//! verification. Where a point is displaced past its limit at a frame, the track on its chain
//! whose error there moves it most takes that frame as a key — per segment of that track's keys,
//! the frame where its points miss by the largest ratio to their limits — and its keys are
//! verified again under its budget. The other segments' curves do not change (with velocities a
//! segment depends on its two keys only), so the misses are repaired where they are, not by
//! tightening the track everywhere.

use super::*;
use crate::diff::Miss;

/// The most rounds of added keys before the budgets of the chains that still miss are tightened
/// instead.
pub(crate) const MAX_INSERTIONS: usize = 32;

impl Setup<'_> {
    /// Per track, the frames that become keys for `misses` (in frame order), given each
    /// track's keys (`reduced`) and their curves posed at every frame (`poses`).
    ///
    /// A miss of point `p` at frame `f` is laid on the track `t` of `p`'s chain that moves it
    /// most there: `2·sin(θ/2)·d + σ·δ`, with `θ` and `δ` the track's rotation and translation
    /// errors at `f` and `d` the point's distance from the track's joint at `f` as captured. A
    /// track whose error at `f` is zero (a key) takes none.
    pub(super) fn insertions(
        &self,
        skeleton: &Skeleton,
        misses: &[Miss],
        reduced: &[Option<Reduced>],
        poses: &[Vec<Pose>],
    ) -> Vec<Vec<usize>> {
        let track_joints = skeleton.track_joints();
        // Per track, per segment of its keys that a miss is laid on: the worst ratio and frame.
        let mut worst: Vec<Vec<(usize, f64, usize)>> = vec![Vec::new(); self.tracks.len()];
        let (mut world, mut points) = (Vec::<DAffine3>::new(), Vec::new());
        let mut at = usize::MAX;
        for m in misses {
            let f = m.frame;
            if f != at {
                let pose = |t: usize| {
                    let track = &self.tracks[t];
                    (track.rotations[f], track.positions.map(|p| p[f]))
                };
                skeleton.world(pose, &mut world);
                skeleton.points_of(&world, self.world.shell, &mut points);
                at = f;
            }
            let point = points[m.point];
            let mut blame: Option<(usize, f64)> = None;
            for &t in &self.chains[m.point] {
                let (q, position) = poses[t][f];
                // sin(θ/2) of the turn between the curve and the frame: its vector part's length.
                let half = (q.conjugate() * self.tracks[t].rotations[f]).xyz().length();
                let delta = match (position, self.tracks[t].positions) {
                    (Some(a), Some(b)) => (a - b[f]).length(),
                    _ => 0.0,
                };
                let joint = track_joints[t].expect("a track on a chain has a joint");
                let d = (point - world[joint].translation).length();
                let moved = 2.0 * half * d + self.stretch[t] * delta;
                if moved > 0.0 && blame.is_none_or(|(_, b)| moved > b) {
                    blame = Some((t, moved));
                }
            }
            let Some((t, _)) = blame else { continue };
            let Some(keys) = reduced[t].as_ref().map(|r| &r.keys) else {
                continue;
            };
            let segment = keys.partition_point(|&k| k <= f);
            if keys.get(segment.wrapping_sub(1)) == Some(&f) {
                continue;
            }
            let ratio = m.displacement / self.limits[m.point];
            // The misses come in frame order, so a track's segments do too.
            match worst[t].last_mut() {
                Some(w) if w.0 == segment => {
                    if ratio > w.1 {
                        *w = (segment, ratio, f);
                    }
                }
                _ => worst[t].push((segment, ratio, f)),
            }
        }
        worst
            .into_iter()
            .map(|w| w.into_iter().map(|(_, _, f)| f).collect())
            .collect()
    }

    /// Adds the frames `added` to each track's keys, verified under its budget in `shares`
    /// ([`with_keys`]), and poses the tracks that changed.
    pub(super) fn add_keys(
        &self,
        shares: &[Share],
        added: &[Vec<usize>],
        reduced: &mut [Option<Reduced>],
        poses: &mut [Vec<Pose>],
    ) -> Result<(), Error> {
        let opts = self.options(shares)?;
        let frames = self.frames();
        let todo: Vec<usize> = (0..self.tracks.len())
            .filter(|&t| !added[t].is_empty() && reduced[t].is_some())
            .collect();
        let done = crate::parallel::map(&todo, |&t| {
            let r = reduced[t].as_ref().expect("a track reduced");
            let r = with_keys(&frames[t], r, &added[t], &opts[t])?;
            let p = self.pose(t, &frames[t], &r)?;
            Ok::<_, Error>((r, p))
        });
        for (&t, d) in todo.iter().zip(done) {
            let (r, p) = d?;
            reduced[t] = Some(r);
            poses[t] = p;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{arm, frames, no_local_bound, world};
    use super::*;

    /// The arm: a root at the origin and a bone 1 along x with an end point 2 further, so the
    /// end point is 3 from the root's joint and 2 from the bone's. Both tracks hold the identity; their
    /// curves are turned about z at some frames, so a turn `θ` of the root moves the end point
    /// by `2·3·sin(θ/2)` and of the bone by `2·2·sin(θ/2)` (closed form).
    #[test]
    fn a_miss_is_laid_on_the_track_that_moves_the_point_most_at_its_worst_frame() {
        let (skeleton, ..) = arm();
        let times: Vec<f64> = (0..21).map(f64::from).collect();
        let still = vec![DQuat::IDENTITY; times.len()];
        let tracks = [frames(&times, &still), frames(&times, &still)];
        let opts = no_local_bound();
        let world = world(vec![1.0, 1.0], false);
        let setup = Setup::new(&skeleton, &tracks, &opts, &world).unwrap();
        let end = 2; // the points: root origin, bone origin, bone end
        assert_eq!(setup.point_joints, [0, 1, 1]);
        // Errors (root, bone) in rad at some frames: at 4 the bone moves the end 0.04, the root
        // 0.03; at 5 the bone too, by less; at 14 the root moves it 0.06, the bone 0.02; at 10
        // both are keys.
        let errors = [(4, 0.01, 0.02), (5, 0.005, 0.015), (14, 0.02, 0.01)];
        let mut poses: Vec<Vec<Pose>> = vec![vec![(DQuat::IDENTITY, None); times.len()]; 2];
        for &(f, root, bone) in &errors {
            poses[0][f].0 = DQuat::from_rotation_z(root);
            poses[1][f].0 = DQuat::from_rotation_z(bone);
        }
        let keys = |keys: Vec<usize>| {
            Some(Reduced {
                keys,
                velocities: None,
                max_error: 0.0,
                mean_error: 0.0,
                max_position_error: None,
            })
        };
        let reduced = [keys(vec![0, 10, 20]), keys(vec![0, 10, 20])];
        let miss = |frame: usize, displacement: f64| Miss {
            frame,
            point: end,
            displacement,
        };
        // Frame 5 misses by more than 4, but the bone moves the end point less there than at 4:
        // the ratio decides among one segment's misses, the movement which track takes it.
        let misses = [miss(4, 1.5), miss(5, 1.8), miss(10, 2.0), miss(14, 1.2)];
        let added = setup.insertions(&skeleton, &misses, &reduced, &poses);
        assert_eq!(added, [vec![14], vec![5]]);
        // Without the bone's error at 5 it goes to the root (0.03 > 0); at the keys, nowhere.
        poses[1][5].0 = DQuat::IDENTITY;
        let added = setup.insertions(&skeleton, &misses, &reduced, &poses);
        assert_eq!(added, [vec![5, 14], vec![4]]);
    }
}
