//! `reduce --position-tolerance LEN`: keys within a world-space bound of every joint, End Site
//! and `--shell` point (the library's [`inbetween::reduce::reduce_world`]; docs/spec.md §5a).

use super::report::unit;
use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::{Curves, glob};
use inbetween::reduce::{ReduceOptions, Reduced, TrackFrames, WorldReduced, WorldTolerance};
use inbetween::skeleton::Skeleton;
use inbetween::{Error, InputError};

/// The options `--position-tolerance` cannot be given with, and why; an error naming the first
/// given.
pub(super) fn check_options(args: &ReduceArgs, gltf_output: bool) -> Result<(), Error> {
    let Some(len) = args.position_tolerance else {
        return Ok(());
    };
    let refused = if args.distance.is_some() {
        Some((
            "--distance",
            "it measures each joint's error at a distance in its own frame; the position \
             tolerance measures every point in world space",
        ))
    } else if args.output.precision.is_some() {
        Some((
            "--precision",
            "the world bound is verified on the keys at full precision (the default output)",
        ))
    } else if gltf_output && args.translation_tolerance.is_some() {
        Some((
            "--translation-tolerance",
            "for glTF output the translation channels are kept as they are, and the world \
             bound is met by the rotations",
        ))
    } else {
        None
    };
    match refused {
        Some((flag, why)) => Err(InputError::new(format!(
            "--position-tolerance {len} cannot be given with {flag}: {why}"
        ))
        .into()),
        None => Ok(()),
    }
}

/// Each joint's limit: `--position-tolerance`, or the last `--joint-tolerance` whose globs
/// match its name.
pub(super) fn limits(args: &ReduceArgs, skeleton: &Skeleton) -> Result<Vec<f64>, Error> {
    let len = args.position_tolerance.unwrap_or(f64::INFINITY);
    let mut limits = vec![len; skeleton.joints().len()];
    for spec in &args.joint_tolerance {
        let bad = |why: &str| {
            InputError::new(format!(
                "--joint-tolerance \"{}\": {why}",
                inbetween::error::shorten(spec)
            ))
        };
        let Some((globs, value)) = spec.rsplit_once('=') else {
            return Err(bad("expected GLOBS=LEN, e.g. 'LeftFoot,RightFoot=0.2'").into());
        };
        let value = match value.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && x > 0.0 => x,
            _ => return Err(bad("expected a positive length after '='").into()),
        };
        for g in globs.split(',').map(str::trim) {
            let mut matched = false;
            for (limit, joint) in limits.iter_mut().zip(skeleton.joints()) {
                if glob(g, &joint.name) {
                    *limit = value;
                    matched = true;
                }
            }
            if !matched {
                let names: Vec<String> = skeleton
                    .joints()
                    .iter()
                    .take(20)
                    .map(|j| format!("\"{}\"", inbetween::error::shorten(&j.name)))
                    .collect();
                let more = if skeleton.joints().len() > 20 {
                    ", …"
                } else {
                    ""
                };
                return Err(bad(&format!(
                    "\"{}\" matches no joint; the joints are {}{more}",
                    inbetween::error::shorten(g),
                    names.join(", ")
                ))
                .into());
            }
        }
    }
    Ok(limits)
}

/// The tracks of `input` reduced under the world bound: `frames` are the tracks' frames (with
/// their translations, which pose the skeleton), reduced with `opts` (the local bound);
/// translations are reduced under their budgets when `translations`, else kept; `margin` is the
/// rotation error the keys may gain as written (rad).
pub(super) fn reduce(
    args: &ReduceArgs,
    input: &Curves,
    frames: &[TrackFrames<'_>],
    opts: &ReduceOptions,
    (translations, margin): (bool, f64),
    told: &mut dyn Events,
) -> Result<Vec<Reduced>, Error> {
    let source = &input.doc.source;
    let Some(skeleton) = input.doc.hierarchy.as_deref() else {
        return Err(InputError::new(format!(
            "{source}: --position-tolerance needs a skeleton to pose (a BVH clip, or a glTF \
             animation of one node tree); this input has none"
        ))
        .into());
    };
    let world = WorldTolerance {
        limits: limits(args, skeleton)?,
        shell: args.shell,
        translations,
        shared_keys: args.shared_keys,
        margin,
    };
    let done =
        inbetween::reduce::reduce_world(skeleton, frames, opts, &world).map_err(|e| match e {
            Error::Input(e) => Error::Input(e.at(source)),
            other => other,
        })?;
    if args.verbose {
        report(args, input, skeleton, &world, &done, told);
    }
    Ok(done.tracks)
}

/// `-v`: per track its keys, its largest local angle, its budget and the largest world
/// displacement of its points (its joint's, and those of joints below it that no track
/// animates); then the whole clip's largest displacement and where.
fn report(
    args: &ReduceArgs,
    input: &Curves,
    skeleton: &Skeleton,
    world: &WorldTolerance,
    done: &WorldReduced,
    told: &mut dyn Events,
) {
    let owner = skeleton.owners();
    let point_joints = skeleton.point_joints(world.shell.is_some());
    let mut worst = vec![(0.0f64, 0usize); done.tracks.len()];
    for (&(d, f), &j) in done.points.iter().zip(&point_joints) {
        if let Some(t) = owner[j]
            && d > worst[t].0
        {
            worst[t] = (d, f);
        }
    }
    let angles = args.input.angles;
    for (t, (track, r)) in input.tracks.iter().zip(&done.tracks).enumerate() {
        let budget = &done.budgets[t];
        let translation = r.max_position_error.map_or(String::new(), |p| {
            format!(", max translation error {p:.3e}")
        });
        told.report(&format!(
            "inbetween: reduce: track {}: {} frames, {} keys ({:.1} %), max angle {:.3e} \
             (budget {:.3e}) {}{translation}, world displacement {:.3e} at frame {}",
            inbetween::error::shorten(track.name().unwrap_or("-")),
            track.len(),
            r.keys.len(),
            100.0 * r.keys.len() as f64 / track.len().max(1) as f64,
            unit(args, r.max_error),
            angles.from_rad(budget.angle),
            angles.as_str(),
            worst[t].0,
            worst[t].1
        ));
    }
    if let Some((p, &(d, f))) = done
        .points
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.0.total_cmp(&b.1.0))
    {
        told.report(&format!(
            "inbetween: reduce: world: largest displacement {d:.6e} at joint {} frame {f} \
             (limit {}), {} round{}",
            inbetween::error::shorten(&skeleton.joints()[point_joints[p]].name),
            world.limits[point_joints[p]],
            done.rounds,
            if done.rounds == 1 { "" } else { "s" }
        ));
    }
}
