//! World space (`reduce --position-tolerance`, docs/spec.md §4.8 and §5a): keys whose motion,
//! posed on a skeleton and composed from the root, keeps every point a viewer sees — each joint's
//! origin, its end points and, with a shell, three points around it — within a length of the
//! original at every frame.
//!
//! ## The bound
//! Change one joint's local rotation by an angle θ (its translation by τ) and every point below
//! it moves by at most `σ·(2·u·sin(θ/2) + τ)`: `u` the point's distance from the joint in the
//! joint's own (unscaled) frame, `σ` the largest stretch of the joint's parent's world transform
//! (the product of its ancestors' largest rest scales; 1 without scales). Changing the joints of
//! a chain one after the other, the displacements add (the triangle inequality): a point moves
//! by at most the sum of those terms over the animated joints at and above it. With `U` a track's
//! *reach*, the largest `u` of any point below it at any frame, a per-track budget `e` with
//! `σ·(2·U·sin(θ/2) + τ) = e` bounds that track's share at every point below it.
//!
//! ## Budgets, rounds and the guarantee
//! The *rigorous* split gives each track a share of every chain it is on such that the shares
//! on any chain add up to at most its point's limit `L(p)`, whatever the curves do within their
//! tolerances. It is loose — errors of different joints rarely line up — so reduce starts from
//! each chain's limit times `k(p)^START` (`k` the number of animated joints on the chain: as if
//! their errors added up to `k^START` of one). Both are split in proportion to weights
//! ([`Setup::weights`]) from the root down ([`Setup::fill`]: what an ancestor does not take,
//! its share set by a tighter chain elsewhere, goes to the tracks below it; no share past the
//! least limit of the points below its track).
//! A track with translations to reduce gives them the part of its share that the weights'
//! probe chooses. Reduce then reduces every track under its budget, poses the kept keys' curves
//! at every frame and measures every point. Where points miss, keys are added where they miss
//! ([`insert`]: the track that moves a missing point most at that frame takes it as a key) and
//! the points are measured again, until every point is within. Shared keys (one key set for
//! all tracks) tighten budgets instead: where a point misses its limit by a ratio `r`, every
//! budget on its chain is scaled by `0.95/r`, never below the rigorous split, and those tracks
//! are reduced again; once every point is within, the budgets grow once by their chains'
//! slack, and where that misses the round within stands. Keys added in vain for
//! [`insert::MAX_INSERTIONS`] rounds fall back to tightening. At the rigorous split no point
//! can miss, so the rounds end; the result returned is the measured round within with the
//! fewest keys. Guaranteed: every point within its limit at every frame (measured, not just
//! bound).
//! Not optimal: the budgets are a heuristic split, the track that takes a key where a point
//! misses is chosen by a rule of thumb, and the keys of each track are those of the per-track
//! method (greedy or optimal) under its budget, completed where points missed.

use super::*;
use crate::diff::point_misses;
use crate::error::input_err;
use crate::skeleton::Skeleton;
use glam::DAffine3;

mod insert;

/// The budgets start from each chain's limit split as if its tracks' errors added up to
/// `k^START` of one (`k` tracks on the chain): ½ would be errors adding like independent random
/// ones. 0.9 starts beyond the limits on many chains; the points that miss take keys where they
/// miss ([`insert`]), which keeps fewer keys than a start within the limits (measured on the
/// eight tuning clips only: docs/reduce.md, "World space").
pub(crate) const START: f64 = 0.9;

/// The start for shared keys, which tighten budgets instead of adding keys (one key set for
/// every track: a key added to one is added to all).
pub(crate) const SHARED_START: f64 = 0.7;

/// The probe of the weights splits each chain's limit equally, as if its tracks' errors added up
/// to `k^PROBE_START` of one: looser than the start, so that the probe is quick (only the tracks'
/// relative needs matter).
pub(crate) const PROBE_START: f64 = 0.4;

/// A loosening reduces again only the tracks whose budget it grows by more than this factor.
pub(crate) const MIN_GROWTH: f64 = 1.05;

/// The share of a track's budget given to its translation, when it has translations to reduce,
/// in the weights' probe (the split then takes the probe's measure of each track's).
pub(crate) const TRANSLATION_SHARE: f64 = 0.25;

/// Each round scales the budgets on a chain that missed by this much more than the miss.
pub(crate) const TIGHTENING: f64 = 0.95;

/// How many times the budgets of shared keys grow by their slack once every point is within
/// its limit.
pub(crate) const LOOSENINGS: usize = 1;

/// The most joints along the points' chains to the root (the points times their depth) a
/// world-space reduce composes: 2²⁴, a skeleton of 4 000 joints in one chain (real ones hold
/// a few thousand); a chain of 100 000 joints (5·10⁹) is refused before its chains are built.
pub(super) const MAX_CHAIN_WORK: u64 = 1 << 24;

/// A budget grows by its chains' slack (limit over displacement) to this power...
pub(crate) const LOOSENING: f64 = 0.8;

/// ...the slack counted up to this.
pub(crate) const MAX_LOOSENING: f64 = 4.0;

/// The most frames of a track the probe of the weights reduces.
pub(crate) const PROBE_FRAMES: usize = 1000;

/// Rounds after which every budget still above the rigorous split is set to it.
pub(crate) const MAX_ROUNDS: usize = 24;

/// The smallest rotation tolerance a budget may come to (rad): what reduce can verify.
pub(crate) const MIN_ANGLE: f64 = 1e-9;

/// What `reduce --position-tolerance` guarantees.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldTolerance {
    /// Per joint of the skeleton, the largest world displacement of its points (length units).
    pub limits: Vec<f64>,
    /// Measure the three points at this distance along each joint's axes too (ACL's virtual
    /// vertices).
    pub shell: Option<f64>,
    /// Reduce the tracks' translations under their budgets; else they are kept exactly (the
    /// tracks' positions then only pose the skeleton).
    pub translations: bool,
    /// One set of key times for all tracks (`reduce_shared_each`).
    pub shared_keys: bool,
    /// The rotation error (rad) each track's keys may gain where they are written (float32 in
    /// glTF): every point's limit is tightened by what that error can move it.
    pub margin: f64,
}

/// A track's budget: the rotation tolerance (rad) and translation tolerance it was reduced with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Largest local rotation error, rad.
    pub angle: f64,
    /// Largest translation error (length units), for a track whose translations are reduced.
    pub translation: Option<f64>,
}

/// Tracks reduced in world space.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldReduced {
    /// Each track's keys and local errors, as [`reduce_frames`] gives them.
    pub tracks: Vec<Reduced>,
    /// Each track's budget.
    pub budgets: Vec<Budget>,
    /// Per point of [`Skeleton::points`] (with the shell's when measured), its largest world
    /// displacement and the first frame where it occurs.
    pub points: Vec<(f64, usize)>,
    /// How many times the tracks were reduced (1: the starting budgets held).
    pub rounds: usize,
}

/// Reduces `tracks`, the tracks of `skeleton` (track `t` animating the joint whose `track` is
/// `t`; all with the same frame times), so that every point stays within its joint's limit in
/// world space (see the module documentation). `opts.tolerance` is each track's largest local
/// rotation error too (`PI` for none), `opts.translation_tolerance` its largest translation
/// error (`None` for none); `opts.distance` must be `None`.
pub fn reduce_world(
    skeleton: &Skeleton,
    tracks: &[TrackFrames<'_>],
    opts: &ReduceOptions,
    world: &WorldTolerance,
) -> Result<WorldReduced, Error> {
    let mut setup = Setup::new(skeleton, tracks, opts, world)?;
    let (weights, translation_share) = setup.weights()?;
    setup.translation_share = translation_share;
    let rigorous = setup.budgets(&weights, |_| 1.0);
    let frames = tracks.first().map_or(0, |t| t.times.len());
    let original = |f: usize, t: usize| (tracks[t].rotations[f], tracks[t].positions.map(|p| p[f]));
    let mut reduced: Vec<Option<Reduced>> = vec![None; tracks.len()];
    let mut poses: Vec<Vec<(DQuat, Option<DVec3>)>> = vec![Vec::new(); tracks.len()];
    let mut redo: Vec<bool> = vec![true; tracks.len()];
    // The result with the fewest keys so far that met every limit, and its key count.
    let mut best: Option<(usize, WorldReduced)> = None;
    let mut loosenings = 0;
    let mut measure_only = false;
    let mut insertions = 0;
    // A point is within when its displacement is at most this (its limit less round-off).
    let strict: Vec<f64> = setup.limits.iter().map(|l| l * (1.0 - 1e-9)).collect();
    // Keys are added where points miss, except to shared keys (one key set for all tracks),
    // whose budgets tighten and then grow by their slack.
    let (start, loosen, max_insertions) = if world.shared_keys {
        (SHARED_START, LOOSENINGS, 0)
    } else {
        (START, 0, insert::MAX_INSERTIONS)
    };
    let mut budgets = setup.budgets(&weights, |k| k.powf(start));
    for round in 1.. {
        if !measure_only {
            setup.reduce(&budgets, &redo, &mut reduced, &mut poses)?;
        }
        measure_only = false;
        let posed = |f: usize, t: usize| poses[t][f];
        let (points, misses) =
            point_misses(skeleton, frames, &original, &posed, world.shell, &strict);
        // World positions too large to compose (offsets, translations or the shell near the
        // largest float) measure nothing: an input error, never keys written on a NaN.
        if let Some((p, &(_, f))) = points.iter().enumerate().find(|(_, (d, _))| !d.is_finite()) {
            return Err(input_err!(
                "joint \"{}\": its world position at frame {f} is not a finite number: the \
                 skeleton's offsets, translations or shell are too large to compose in float64",
                crate::error::shorten(&skeleton.joints()[setup.point_joints[p]].name)
            )
            .into());
        }
        // Per track, the least ratio of limit to displacement over the points below it.
        let mut slack = vec![f64::INFINITY; tracks.len()];
        for (p, &(d, _)) in points.iter().enumerate() {
            let ratio = strict[p] / d;
            for &t in &setup.chains[p] {
                slack[t] = slack[t].min(ratio);
            }
        }
        let within = slack.iter().all(|&s| s >= 1.0);
        if !within && insertions < max_insertions {
            let added = setup.insertions(skeleton, &misses, &reduced, &poses);
            if added.iter().any(|a| !a.is_empty()) {
                insertions += 1;
                setup.add_keys(&budgets, &added, &mut reduced, &mut poses)?;
                measure_only = true;
                continue;
            }
        }
        if within {
            let keys = reduced.iter().flatten().map(|r| r.keys.len()).sum();
            if best.as_ref().is_none_or(|b| keys < b.0) {
                let result = WorldReduced {
                    tracks: reduced.iter().flatten().cloned().collect(),
                    budgets: (0..tracks.len())
                        .map(|t| setup.budget_of(t, budgets[t]))
                        .collect(),
                    points: points.clone(),
                    rounds: round,
                };
                best = Some((keys, result));
            }
            if loosenings == loosen || round >= MAX_ROUNDS {
                let (_, mut result) = best.expect("a result within the limits");
                result.rounds = round;
                return Ok(result);
            }
            loosenings += 1;
        } else if loosenings > 0 {
            // The loosening (of shared keys) missed: the round within stands.
            let (_, mut result) = best.expect("a result within the limits");
            result.rounds = round;
            return Ok(result);
        } else if round >= MAX_ROUNDS
            && let Some((_, mut result)) = best.take()
        {
            result.rounds = round;
            return Ok(result);
        }
        // Within: every budget grows by part of its chains' slack; else those on chains that
        // missed shrink by more than the miss, never below the rigorous split.
        let mut changed = false;
        for t in 0..tracks.len() {
            let floor = rigorous[t].0;
            let e = if within {
                // Never past the least limit of the points below it: alone, it could use all of it.
                let growth = slack[t]
                    .min(MAX_LOOSENING)
                    .powf(LOOSENING)
                    .min(setup.cap(t) / budgets[t].0);
                if growth > MIN_GROWTH {
                    budgets[t].0 * growth
                } else {
                    budgets[t].0
                }
            } else if round >= MAX_ROUNDS {
                floor
            } else if slack[t] < 1.0 {
                (budgets[t].0 * TIGHTENING * slack[t]).max(floor)
            } else {
                budgets[t].0
            };
            redo[t] = e != budgets[t].0;
            changed |= redo[t];
            budgets[t].0 = e;
        }
        if !changed {
            if let Some((_, mut result)) = best.take() {
                result.rounds = round;
                return Ok(result);
            }
            let (p, &(d, f)) = points
                .iter()
                .enumerate()
                .max_by(|a, b| (a.1.0 / setup.limits[a.0]).total_cmp(&(b.1.0 / setup.limits[b.0])))
                .expect("a point missed");
            return Err(Error::Internal(format!(
                "internal error: reduce in world space: a point of joint \"{}\" moves by \
                 {d:e} at frame {f} at the rigorous budgets, more than its limit {:e}",
                skeleton.joints()[setup.point_joints[p]].name,
                setup.limits[p]
            )));
        }
        if world.shared_keys {
            redo.fill(true);
        }
    }
    unreachable!("the rounds end at the rigorous budgets")
}

/// A track's share of its chains' limits (length units), and its translation cap.
type Share = (f64, Option<f64>);

/// A track's rotation and translation at one frame.
type Pose = (DQuat, Option<DVec3>);

/// What the rounds share: the skeleton's geometry and each point's limit and chain.
struct Setup<'a> {
    tracks: &'a [TrackFrames<'a>],
    opts: &'a ReduceOptions,
    world: &'a WorldTolerance,
    /// Per point, its limit.
    limits: Vec<f64>,
    /// Per point, its joint.
    point_joints: Vec<usize>,
    /// Per point, the tracks at and above its joint.
    chains: Vec<Vec<usize>>,
    /// Per track, its parent chain's largest stretch σ.
    stretch: Vec<f64>,
    /// Per track, its reach U.
    reach: Vec<f64>,
    /// Per track with translations to reduce, the part of its share given to them.
    translation_share: Vec<f64>,
    /// The tracks, each after every track above it.
    order: Vec<usize>,
    /// Per track, the points at and below its joint.
    below: Vec<Vec<usize>>,
    /// Per track, its joint's name (for messages).
    names: Vec<String>,
}

impl<'a> Setup<'a> {
    fn new(
        skeleton: &Skeleton,
        tracks: &'a [TrackFrames<'a>],
        opts: &'a ReduceOptions,
        world: &'a WorldTolerance,
    ) -> Result<Setup<'a>, Error> {
        let joints = skeleton.joints();
        if opts.distance.is_some() {
            return Err(input_err!(
                "the position tolerance measures world positions; a distance measure does not \
                 apply"
            )
            .into());
        }
        if world.limits.len() != joints.len() {
            return Err(Error::Internal(format!(
                "internal error: {} joint limits for {} joints",
                world.limits.len(),
                joints.len()
            )));
        }
        let track_joints = skeleton.track_joints();
        if let Some(t) =
            (0..tracks.len()).find(|&t| track_joints.get(t).is_none_or(Option::is_none))
        {
            return Err(input_err!(
                "track {t} animates no joint of the skeleton: a position tolerance needs every \
                 track on it"
            )
            .into());
        }
        if let Some(t) = tracks.iter().position(|t| t.times != tracks[0].times) {
            return Err(input_err!(
                "track {t} has other frame times than track 0: a position tolerance poses the \
                 skeleton at each frame, so the tracks need one grid"
            )
            .into());
        }
        let point_joints = skeleton.point_joints(world.shell.is_some());
        // Each point is measured along its chain to the root: the work and the chains' memory
        // grow with the points times their depth, bounded before anything is built.
        let mut depth = vec![0u64; joints.len()];
        for (i, j) in joints.iter().enumerate() {
            depth[i] = j.parent.map_or(1, |p| depth[p] + 1);
        }
        let work: u64 = point_joints.iter().map(|&j| depth[j]).sum();
        if work > MAX_CHAIN_WORK {
            return Err(input_err!(
                "the skeleton's {} points lie up to {} joints deep: {work} joints along their \
                 chains to the root, more than the {MAX_CHAIN_WORK} a position tolerance \
                 composes; reduce per joint (a rotation tolerance) instead",
                point_joints.len(),
                depth.iter().max().copied().unwrap_or(0)
            )
            .into());
        }
        let chains: Vec<Vec<usize>> = point_joints
            .iter()
            .map(|&j| {
                let chain = skeleton.animated_chain(j);
                chain.iter().filter_map(|&a| joints[a].track).collect()
            })
            .collect();
        let limits: Vec<f64> = point_joints.iter().map(|&j| world.limits[j]).collect();
        // Chains run from the point's joint up: a track's depth is how many tracks are above it.
        let mut depth_of = vec![0usize; tracks.len()];
        let mut below = vec![Vec::new(); tracks.len()];
        for (p, chain) in chains.iter().enumerate() {
            for (i, &t) in chain.iter().enumerate() {
                depth_of[t] = chain.len() - 1 - i;
                below[t].push(p);
            }
        }
        let mut order: Vec<usize> = (0..tracks.len()).collect();
        order.sort_by_key(|&t| depth_of[t]);
        let mut stretch = vec![1.0; tracks.len()];
        for (t, j) in track_joints.iter().take(tracks.len()).enumerate() {
            let mut at = j.and_then(|j| joints[j].parent);
            while let Some(a) = at {
                stretch[t] *= joints[a].scale.abs().max_element();
                at = joints[a].parent;
            }
        }
        let reach = reaches(skeleton, tracks, world.shell, &chains);
        // What the written keys' rounding can move each point by.
        let wobble = |t: usize| 2.0 * stretch[t] * reach[t] * (0.5 * world.margin).sin();
        let mut tight = Vec::with_capacity(limits.len());
        for (p, (&limit, chain)) in limits.iter().zip(&chains).enumerate() {
            let l = limit - chain.iter().map(|&t| wobble(t)).sum::<f64>();
            if l <= 0.0 {
                return Err(input_err!(
                    "the position tolerance {limit} of joint \"{}\" is smaller than what its \
                     keys' float32 rounding can move its points ({:.3e}); give a larger one",
                    joints[point_joints[p]].name,
                    limit - l
                )
                .into());
            }
            tight.push(l);
        }
        let limits = tight;
        Ok(Setup {
            tracks,
            opts,
            world,
            limits,
            point_joints,
            chains,
            stretch,
            reach,
            translation_share: vec![TRANSLATION_SHARE; tracks.len()],
            order,
            below,
            names: (track_joints.iter().take(tracks.len()))
                .map(|j| j.map_or_else(String::new, |j| joints[j].name.clone()))
                .collect(),
        })
    }

    /// Each track's share for `weights`: every point's allowance `L(p)·slack(k)` (`k` the
    /// number of tracks on the point's chain) split among its chain from the root down
    /// ([`Setup::fill`]). With `slack` 1 the shares on any chain add up to at most its limit
    /// (the rigorous split).
    fn budgets(&self, weights: &[f64], slack: impl Fn(f64) -> f64) -> Vec<Share> {
        let allowance: Vec<f64> = (self.chains.iter().zip(&self.limits))
            .map(|(chain, &limit)| limit * slack(chain.len() as f64))
            .collect();
        self.fill(&allowance, weights)
            .into_iter()
            .map(|e| (e, self.opts.translation_tolerance))
            .collect()
    }

    /// The least limit of the points below track `t` (infinite for none).
    fn cap(&self, t: usize) -> f64 {
        self.below[t]
            .iter()
            .map(|&p| self.limits[p])
            .fold(f64::INFINITY, f64::min)
    }

    /// Splits each point's `allowance` among the tracks on its chain in proportion to
    /// `weights`, from the root down: each track takes the least, over the points below it, of
    /// its weight's part of what its ancestors left of the point's allowance, and never more
    /// than the least limit of those points. The shares on any chain add up to at most its
    /// allowance; what an ancestor leaves (its share set by another chain) goes to the tracks
    /// below it.
    fn fill(&self, allowance: &[f64], weights: &[f64]) -> Vec<f64> {
        let mut left = allowance.to_vec();
        let mut rest: Vec<f64> = self
            .chains
            .iter()
            .map(|c| c.iter().map(|&t| weights[t]).sum())
            .collect();
        let mut share = vec![f64::INFINITY; self.tracks.len()];
        for &t in &self.order {
            let w = weights[t];
            // A limit that is not a number (a reach too large to compose: the rounds then refuse
            // the input, naming the point) constrains nothing here.
            let e = self.below[t]
                .iter()
                .filter(|&&p| !left[p].is_nan())
                .map(|&p| (left[p].max(0.0) * w / rest[p]).min(left[p].max(0.0)))
                .fold(self.cap(t), f64::min);
            share[t] = e;
            for &p in &self.below[t] {
                left[p] -= e;
                rest[p] -= w;
            }
        }
        share
    }

    /// Each track's weight in the split, and the part of its share its translations take:
    /// what keys it needs for its share, from a probe. A track keeping `k` keys at angle `θ` is
    /// taken to keep about `c·θ^(−½)` (`c = k·√θ`) at others, and its share `e` of a chain to
    /// buy `θ ≈ e/(σU)`; the fewest keys on one chain under `Σ e ≤ L` then give each track a
    /// share in proportion to `c^(2/3)·(σU)^(1/3)` (Lagrange). Translations are a term of their
    /// own (`c = k·√τ` from their keys at `τ`, lever `σ`), added to the track's weight, their
    /// part of its share that term's (between 5 % and 95 %). The probe: every track reduced on
    /// its own under the equal split, `L(p)·k^PROBE_START/k`, its rotations and translations
    /// apart, on at most [`PROBE_FRAMES`] of its frames (evenly taken, the last among them: only
    /// the tracks' relative needs matter).
    fn weights(&self) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let equal = vec![1.0; self.tracks.len()];
        let shares = self.budgets(&equal, |k| k.powf(PROBE_START));
        let opts = self.options(&shares)?;
        let all: Vec<usize> = (0..self.tracks.len()).collect();
        // Built once: one track's probe must not rebuild every track's frames (quadratic in
        // the tracks: a 100 000-joint star took 100 s, 20 s with this; found by a helper).
        let frames = self.frames();
        let probe = crate::parallel::map(&all, |&t| {
            let thinned = Thinned::of(&frames[t]);
            let f = thinned.frames();
            let Some(tau) = opts[t]
                .translation_tolerance
                .filter(|_| f.positions.is_some())
            else {
                return reduce_frames(&f, &opts[t]).map(|r| (r.keys.len(), None));
            };
            let rotation = TrackFrames {
                positions: None,
                ..f
            };
            let translation = ReduceOptions {
                tolerance: std::f64::consts::PI,
                ..opts[t]
            };
            let r = reduce_frames(&rotation, &opts[t])?;
            let p = reduce_frames(&f, &translation)?;
            Ok((r.keys.len(), Some((p.keys.len(), tau))))
        });
        let mut weights = Vec::with_capacity(all.len());
        let mut translation_share = Vec::with_capacity(all.len());
        for (t, r) in probe.into_iter().enumerate() {
            let (keys, translation) = r?;
            let c = keys as f64 * opts[t].tolerance.min(std::f64::consts::PI).sqrt();
            let u = self.stretch[t] * self.reach[t];
            // A track that moves no point still takes part, with a small weight.
            let w = (c.powf(2.0 / 3.0) * u.powf(1.0 / 3.0)).max(1e-12);
            match translation {
                Some((keys, tau)) => {
                    let c = keys as f64 * tau.sqrt();
                    let wt = c.powf(2.0 / 3.0) * self.stretch[t].powf(1.0 / 3.0);
                    weights.push(w + wt);
                    translation_share.push((wt / (w + wt)).clamp(0.05, 0.95));
                }
                _ => {
                    weights.push(w);
                    translation_share.push(TRANSLATION_SHARE);
                }
            }
        }
        Ok((weights, translation_share))
    }

    /// The rotation and translation tolerances of track `t` for its share `e`.
    fn budget_of(&self, t: usize, (e, cap): Share) -> Budget {
        let sigma = self.stretch[t];
        let translation =
            (self.world.translations && self.tracks[t].positions.is_some()).then(|| {
                let tau = self.translation_share[t] * e / sigma;
                cap.map_or(tau, |c| c.min(tau))
            });
        let rotation = e - sigma * translation.unwrap_or(0.0);
        let span = 2.0 * sigma * self.reach[t];
        let angle = if span <= rotation || span == 0.0 {
            std::f64::consts::PI
        } else {
            2.0 * (rotation / span).asin()
        };
        Budget {
            angle: angle.min(self.opts.tolerance),
            translation,
        }
    }

    /// Reduces the tracks marked in `redo` under their budgets (all of them together for shared
    /// keys), and poses their kept keys' curves at every frame.
    fn reduce(
        &self,
        shares: &[Share],
        redo: &[bool],
        reduced: &mut [Option<Reduced>],
        poses: &mut [Vec<(DQuat, Option<DVec3>)>],
    ) -> Result<(), Error> {
        let opts = self.options(shares)?;
        let frames = self.frames();
        let todo: Vec<usize> = (0..self.tracks.len())
            .filter(|&t| redo[t] || self.world.shared_keys)
            .collect();
        let done: Vec<Reduced> = if self.world.shared_keys {
            reduce_shared_each(&frames, &opts)?
        } else {
            crate::parallel::map(&todo, |&t| reduce_frames(&frames[t], &opts[t]))
                .into_iter()
                .collect::<Result<_, _>>()?
        };
        let posed =
            crate::parallel::map(&todo.iter().zip(&done).collect::<Vec<_>>(), |&(&t, r)| {
                self.pose(t, &frames[t], r)
            });
        for ((&t, r), p) in todo.iter().zip(done).zip(posed) {
            poses[t] = p?;
            reduced[t] = Some(r);
        }
        Ok(())
    }

    /// Each track's options for its share.
    fn options(&self, shares: &[Share]) -> Result<Vec<ReduceOptions>, Error> {
        let mut opts = Vec::with_capacity(self.tracks.len());
        for (t, &share) in shares.iter().enumerate() {
            let b = self.budget_of(t, share);
            if b.angle < MIN_ANGLE {
                return Err(input_err!(
                    "the position tolerance leaves track {t} (joint \"{}\") a rotation \
                     tolerance of {:.3e} rad (its points reach {:.6e} from its joint), below what \
                     reduce can verify ({MIN_ANGLE:e} rad); give a larger position tolerance",
                    crate::error::shorten(&self.names[t]),
                    b.angle,
                    self.reach[t]
                )
                .into());
            }
            opts.push(ReduceOptions {
                tolerance: b.angle,
                translation_tolerance: b.translation,
                ..*self.opts
            });
        }
        Ok(opts)
    }

    /// The tracks' frames as reduced: with their translations when those are reduced.
    fn frames(&self) -> Vec<TrackFrames<'a>> {
        self.tracks
            .iter()
            .map(|t| TrackFrames {
                positions: t.positions.filter(|_| self.world.translations),
                ..*t
            })
            .collect()
    }

    /// Track `t`'s kept keys posed at every frame: the curve `interp` builds through them, and
    /// the frames' own translations where translations are kept.
    fn pose(
        &self,
        t: usize,
        frames: &TrackFrames,
        r: &Reduced,
    ) -> Result<Vec<(DQuat, Option<DVec3>)>, Error> {
        let curve = Curve::new(&kept_track(frames, r, &self.opts.curve)?, &self.opts.curve)?;
        let original = self.tracks[t].positions;
        Ok(frames
            .times
            .iter()
            .enumerate()
            .map(|(f, &time)| {
                let position = match (frames.positions, original) {
                    (Some(_), _) => curve.position(time),
                    (None, Some(p)) => Some(p[f]),
                    (None, None) => None,
                };
                (curve.rotation(time), position)
            })
            .collect())
    }
}

/// A track's frames thinned to at most [`PROBE_FRAMES`], for the probe.
struct Thinned {
    times: Vec<f64>,
    rotations: Vec<DQuat>,
    positions: Option<Vec<DVec3>>,
    euler: Option<(crate::EulerSeq, Vec<DVec3>)>,
    key_times: Option<Vec<f64>>,
}

impl Thinned {
    fn of(t: &TrackFrames<'_>) -> Thinned {
        let n = t.times.len();
        let stride = n.div_ceil(PROBE_FRAMES).max(1);
        let mut at: Vec<usize> = (0..n).step_by(stride).collect();
        if n > 0 && at.last() != Some(&(n - 1)) {
            at.push(n - 1);
        }
        let pick = |v: &[DVec3]| at.iter().map(|&i| v[i]).collect::<Vec<_>>();
        Thinned {
            times: at.iter().map(|&i| t.times[i]).collect(),
            rotations: at.iter().map(|&i| t.rotations[i]).collect(),
            positions: t.positions.map(pick),
            euler: t.euler.map(|(seq, e)| (seq, pick(e))),
            key_times: t.key_times.map(|k| at.iter().map(|&i| k[i]).collect()),
        }
    }

    fn frames(&self) -> TrackFrames<'_> {
        TrackFrames {
            times: &self.times,
            rotations: &self.rotations,
            positions: self.positions.as_deref(),
            euler: self.euler.as_ref().map(|(seq, e)| (*seq, &e[..])),
            key_times: self.key_times.as_deref(),
        }
    }
}

/// Each track's reach: the largest distance, in its joint's own unscaled frame, from its joint
/// to any point below it, over the frames as given.
fn reaches(
    skeleton: &Skeleton,
    tracks: &[TrackFrames<'_>],
    shell: Option<f64>,
    chains: &[Vec<usize>],
) -> Vec<f64> {
    let frames = tracks.first().map_or(0, |t| t.times.len());
    let joints = skeleton.joints();
    let track_joints = skeleton.track_joints();
    let chunk = frames
        .div_ceil(crate::parallel::MAX_THREADS.max(1) * 4)
        .max(1);
    let starts: Vec<usize> = (0..frames).step_by(chunk).collect();
    let parts = crate::parallel::map(&starts, |&s| {
        let (mut world, mut points) = (Vec::<DAffine3>::new(), Vec::new());
        let mut inverses: Vec<glam::DMat3> = Vec::with_capacity(tracks.len());
        let mut reach = vec![0.0f64; tracks.len()];
        for f in s..(s + chunk).min(frames) {
            let pose = |t: usize| (tracks[t].rotations[f], tracks[t].positions.map(|p| p[f]));
            skeleton.world(pose, &mut world);
            skeleton.points_of(&world, shell, &mut points);
            inverses.clear();
            inverses.extend(track_joints.iter().take(tracks.len()).map(|j| {
                let parent = j.and_then(|j| joints[j].parent);
                parent.map_or(glam::DMat3::IDENTITY, |a| world[a].matrix3.inverse())
            }));
            for (p, chain) in points.iter().zip(chains) {
                for &t in chain {
                    let j = track_joints[t].expect("a track on a chain has a joint");
                    let u = inverses[t] * (*p - world[j].translation);
                    reach[t] = reach[t].max(u.length());
                }
            }
        }
        reach
    });
    let mut reach = vec![0.0f64; tracks.len()];
    for part in parts {
        for (r, p) in reach.iter_mut().zip(part) {
            *r = r.max(p);
        }
    }
    reach
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;

    /// A root track turning about z, and a bone with an end point 2 from it, turned by a second
    /// track about x.
    pub(super) fn arm() -> (Skeleton, Vec<f64>, Vec<DQuat>, Vec<DQuat>) {
        let skeleton = Skeleton::new(vec![
            Joint::new("root", None, DVec3::ZERO).with_track(0),
            Joint::new("bone", Some(0), DVec3::new(1.0, 0.0, 0.0))
                .with_track(1)
                .with_ends(vec![DVec3::new(2.0, 0.0, 0.0)]),
        ])
        .unwrap();
        let times: Vec<f64> = (0..121).map(|i| f64::from(i) / 60.0).collect();
        let root = times
            .iter()
            .map(|&t| DQuat::from_rotation_z(0.8 * (2.1 * t).sin() + 0.3 * t * t))
            .collect();
        let bone = times
            .iter()
            .map(|&t| DQuat::from_rotation_x(1.1 * (3.3 * t).cos()) * DQuat::from_rotation_z(t))
            .collect();
        (skeleton, times, root, bone)
    }

    pub(super) fn frames<'a>(t: &'a [f64], q: &'a [DQuat]) -> TrackFrames<'a> {
        TrackFrames {
            times: t,
            rotations: q,
            positions: None,
            euler: None,
            key_times: None,
        }
    }

    pub(super) fn world(limits: Vec<f64>, shared_keys: bool) -> WorldTolerance {
        WorldTolerance {
            limits,
            shell: None,
            translations: true,
            shared_keys,
            margin: 0.0,
        }
    }

    pub(super) fn no_local_bound() -> ReduceOptions {
        ReduceOptions {
            tolerance: std::f64::consts::PI,
            ..ReduceOptions::default()
        }
    }

    /// Closed form: the end point is 2 from the bone's joint and 3 from the root at rest, so a
    /// bone error θ moves it by exactly 2·2·sin(θ/2): the bone's local error can be no more than
    /// 2·asin(L/4), whatever the split. And every point is within L, the root's tighter one too.
    #[test]
    fn the_split_passes_what_an_ancestor_leaves_to_the_joints_below_it() {
        // A root with two children: A's points have a tight limit, B's a loose one.
        let skeleton = Skeleton::new(vec![
            Joint::new("root", None, DVec3::ZERO).with_track(0),
            Joint::new("a", Some(0), DVec3::new(1.0, 0.0, 0.0))
                .with_track(1)
                .with_ends(vec![DVec3::new(2.0, 0.0, 0.0)]),
            Joint::new("b", Some(0), DVec3::new(0.0, 1.0, 0.0))
                .with_track(2)
                .with_ends(vec![DVec3::new(0.0, 3.0, 0.0)]),
        ])
        .unwrap();
        let times = [0.0, 1.0];
        let q = [DQuat::IDENTITY, DQuat::from_rotation_z(0.5)];
        let tracks = [frames(&times, &q), frames(&times, &q), frames(&times, &q)];
        let opts = no_local_bound();
        let world = world(vec![0.1, 0.01, 0.1], false);
        let setup = Setup::new(&skeleton, &tracks, &opts, &world).unwrap();
        let share = setup.fill(&setup.limits, &[1.0; 3]);
        // The root takes half of A's chain (0.005); A the rest of it; B what the root left of
        // its own chain (0.095), where a split of each chain on its own gave it 0.05.
        assert!((share[0] - 0.005).abs() < 1e-15, "{share:?}");
        assert!((share[1] - 0.005).abs() < 1e-15, "{share:?}");
        assert!((share[2] - 0.095).abs() < 1e-15, "{share:?}");
        for (chain, &limit) in setup.chains.iter().zip(&setup.limits) {
            let sum: f64 = chain.iter().map(|&t| share[t]).sum();
            assert!(sum <= limit * (1.0 + 1e-12), "{chain:?}: {sum} > {limit}");
        }
        // Never past the least limit below a track, whatever the allowance.
        let loose: Vec<f64> = setup.limits.iter().map(|l| l * 100.0).collect();
        let share = setup.fill(&loose, &[1.0; 3]);
        assert_eq!(share[1], 0.01, "{share:?}");
        assert!(share.iter().all(|&e| e <= 0.1), "{share:?}");
    }

    #[test]
    fn the_points_stay_within_their_limits_and_the_leaf_within_its_chord() {
        let (skeleton, t, root, bone) = arm();
        let tracks = [frames(&t, &root), frames(&t, &bone)];
        for shared in [false, true] {
            let limits = vec![0.01, 0.05];
            let r = reduce_world(
                &skeleton,
                &tracks,
                &no_local_bound(),
                &world(limits, shared),
            )
            .unwrap();
            // Points: root origin, bone origin, bone end.
            let [root_origin, bone_origin, end] = r.points[..] else {
                panic!("{:?}", r.points)
            };
            assert_eq!(root_origin.0, 0.0);
            assert!(bone_origin.0 <= 0.05 && end.0 <= 0.05, "{:?}", r.points);
            assert!(end.0 > 0.02, "the bound is used: {:?}", r.points);
            assert!(r.tracks[1].max_error <= 2.0 * (0.05f64 / 4.0).asin() + 1e-12);
            assert!(r.tracks.iter().all(|k| k.keys.len() < 60));
            if shared {
                assert_eq!(r.tracks[0].keys, r.tracks[1].keys);
            }
        }
    }

    /// A local bound holds beside the world one; a distance measure, a track that is not on the
    /// skeleton and a limit below the keys' rounding are refused.
    #[test]
    fn a_local_bound_holds_too_and_misuse_is_refused() {
        let (skeleton, t, root, bone) = arm();
        let tracks = [frames(&t, &root), frames(&t, &bone)];
        let local = ReduceOptions {
            tolerance: 0.2f64.to_radians(),
            ..ReduceOptions::default()
        };
        let r = reduce_world(&skeleton, &tracks, &local, &world(vec![1.0, 1.0], false)).unwrap();
        assert!(r.tracks.iter().all(|k| k.max_error <= local.tolerance));
        assert!(r.budgets.iter().all(|b| b.angle <= local.tolerance));
        let far = ReduceOptions {
            distance: Some(2.0),
            ..local
        };
        let e = reduce_world(&skeleton, &tracks, &far, &world(vec![1.0, 1.0], false));
        assert!(matches!(e, Err(Error::Input(_))), "{e:?}");
        let three = [tracks[0], tracks[1], tracks[1]];
        let e = reduce_world(&skeleton, &three, &local, &world(vec![1.0, 1.0], false));
        assert!(
            e.unwrap_err()
                .to_string()
                .contains("track 2 animates no joint")
        );
        let rounded = WorldTolerance {
            margin: 1e-3,
            ..world(vec![1e-3, 1e-3], false)
        };
        let e = reduce_world(&skeleton, &tracks, &local, &rounded).unwrap_err();
        assert!(e.to_string().contains("float32 rounding"), "{e}");
        // A limit that leaves a track less than reduce can verify names the track's joint.
        let tiny = world(vec![1e-12, 1e-12], false);
        let e = reduce_world(&skeleton, &tracks, &local, &tiny).unwrap_err();
        assert!(e.to_string().contains("track 0 (joint \"root\")"), "{e}");
    }
}
