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
        if let Some(clip) = input.gltf.as_deref()
            && clip.animations().len() > 1
        {
            let all = clip.animations();
            let mut labels: Vec<String> = all
                .iter()
                .take(20)
                .map(|a| match a.name() {
                    Some(name) => format!("{} \"{}\"", a.index(), inbetween::error::shorten(name)),
                    None => a.index().to_string(),
                })
                .collect();
            if all.len() > 20 {
                labels.push(format!("and {} more", all.len() - 20));
            }
            return Err(InputError::new(format!(
                "{source}: --position-tolerance poses one animation at a time, and this asset \
                 has {}: choose one with --animation NAME|INDEX ({})",
                all.len(),
                labels.join(", ")
            ))
            .into());
        }
        return Err(InputError::new(format!(
            "{source}: --position-tolerance needs a skeleton to pose (a BVH clip, or a glTF \
             animation of one node tree); this input has none"
        ))
        .into());
    };
    // Every bone bounded: without --shell, a joint whose rotation moves no point gets end
    // points at a bone length (`--shell 0`: none, and nothing added).
    // --shell D: three points D from every joint in world units, as end points.
    let (bounded, given, unbounded) = crate::points::measured(skeleton, args.shell);
    let skeleton = &bounded;
    if !unbounded.is_empty() {
        told.warning(&format!(
            "{source}: --position-tolerance does not bound the rotation of {}: it moves no \
             point and the skeleton has no bone length to give it end points (--shell D does)",
            joint_list(skeleton, &unbounded)
        ));
    }
    let world = WorldTolerance {
        limits: limits(args, skeleton)?,
        shell: None,
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
        told.report(&format!(
            "inbetween: reduce: world: skeleton of {} joints, extent {} at the first frame \
             (length units){}",
            skeleton.joints().len(),
            extent(skeleton, frames),
            if given.is_empty() {
                String::new()
            } else {
                let joints: Vec<usize> = given.iter().map(|g| g.0).collect();
                format!(
                    "; end points at a bone length on {} joint{} that moved no point: {}",
                    given.len(),
                    if given.len() == 1 { "" } else { "s" },
                    joint_list(skeleton, &joints)
                )
            }
        ));
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

/// At most 20 joints' names, quoted, and how many more.
fn joint_list(skeleton: &Skeleton, joints: &[usize]) -> String {
    let mut names: Vec<String> = joints
        .iter()
        .take(20)
        .map(|&j| {
            format!(
                "\"{}\"",
                inbetween::error::shorten(&skeleton.joints()[j].name)
            )
        })
        .collect();
    if joints.len() > 20 {
        names.push(format!("and {} more", joints.len() - 20));
    }
    names.join(", ")
}

/// The size of the first frame's points: `X × Y × Z` of their bounding box.
fn extent(skeleton: &Skeleton, frames: &[TrackFrames<'_>]) -> String {
    let first = |t: usize| {
        let f = &frames[t];
        (f.rotations[0], f.positions.map(|p| p[0]))
    };
    let (mut world, mut points) = (Vec::new(), Vec::new());
    skeleton.world(first, &mut world);
    skeleton.points_of(&world, None, &mut points);
    let (lo, hi) = points.iter().fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let size = (hi - lo).max(glam::DVec3::ZERO);
    format!("{:.4} × {:.4} × {:.4}", size.x, size.y, size.z)
}
