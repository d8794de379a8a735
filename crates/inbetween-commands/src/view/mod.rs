//! `inbetween view A [B] -o page.html`: one self-contained HTML page that plays motion A (and B
//! beside it, as `diff` plays it) as stick figures, with the world displacement per frame that
//! `diff` measures drawn under them (docs/spec.md §1 *Options of `view`*; the page's contents
//! in docs/formats.md *The view page*).

mod page;

use crate::args::{DiffArgs, PageFormat, ViewArgs};
use crate::diff::compare;
use crate::events::Events;
use crate::played;
use crate::settings::{Curves, read_curves};
use glam::{DQuat, DVec3};
use inbetween::skeleton::Skeleton;
use inbetween::{Error, InputError};
use page::{Figure, Page};
use std::io::{Read, Write};
use std::path::Path;

pub use page::MAX_POSITION_BYTES;

/// Key times of B closer than this to a frame's time mark that frame (as `diff`'s
/// `--common-frames`).
const SAME_TIME: f64 = 1e-9;

/// Runs `view`: reads A (and B), poses both on A's skeleton at A's frames, and writes the page.
pub fn run(args: &ViewArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    let output = (args.output.as_os_str() != "-").then_some(args.output.as_path());
    if let Some(path) = output {
        check_name(path, args.output_format)?;
    }
    let page = match &args.other {
        Some(other) => pair(args, other, stdin, warn)?,
        None => single(args, stdin, warn)?,
    };
    let html = page.html();
    let mut out = crate::output::open_output(output, &page.reads)?;
    out.write_all(html.as_bytes())?;
    out.commit()?;
    Ok(())
}

/// An `-o` name `view` writes: `.html` or `.htm` (any case), unless the format is given.
fn check_name(path: &Path, format: Option<PageFormat>) -> Result<(), InputError> {
    let html = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"));
    if html || format == Some(PageFormat::Html) {
        return Ok(());
    }
    Err(InputError::new(format!(
        "-o {}: view writes an HTML page: name it .html, or say what to write under this name \
         with --output-format html",
        crate::shown::shown(path)
    )))
}

/// A alone: every frame of its tracks, one figure.
fn single(args: &ViewArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<Page, Error> {
    let scheme = |f, recorded| played::scheme(args.scheme, f, recorded);
    let a = read_curves(&args.input, &args.curve, &scheme, stdin, warn)?;
    let skeleton = skeleton_of(&a)?;
    let first = a.tracks[0].times();
    if let Some(t) = a.tracks.iter().find(|t| t.times() != first) {
        return Err(InputError::new(format!(
            "{}: track \"{}\" has other key times than the first track: view draws tracks that \
             share their frames (interp the input first)",
            a.doc.source,
            inbetween::error::shorten(t.name().unwrap_or("?"))
        ))
        .into());
    }
    let frames: Vec<usize> = (0..first.len()).collect();
    let points = skeleton.point_joints(false).len();
    page::check_size(&a.doc.source, frames.len(), points, 1)?;
    let figure = figure(&a.doc.source, &skeleton, &frames, &|f, t| {
        pose(&a, frames[f], t)
    })?;
    let times = first.to_vec();
    Page::new(args, &a, &skeleton, times, vec![figure], None)
}

/// A and B: B played at A's frames as `diff` plays it ([`compare`]), the displacement curve
/// `diff` measures.
fn pair(
    args: &ViewArgs,
    other: &Path,
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<Page, Error> {
    let diff_args = DiffArgs {
        input: args.input.clone(),
        other: other.to_path_buf(),
        scheme: args.scheme,
        curve: args.curve.clone(),
        common_frames: args.common_frames,
        shell: args.shell,
        per_frame: false,
        max_angle: None,
        max_position: None,
        output_format: None,
        output: None,
    };
    let c = compare(&diff_args, stdin, warn)?;
    let skeleton = skeleton_of(&c.a)?;
    let Some(world) = &c.world else {
        return Err(InputError::new(format!(
            "{}: view needs every track of A compared at the same frames, to pose the skeleton \
             (interp the input first)",
            c.a.doc.source
        ))
        .into());
    };
    let frames = &c.compared[0];
    let points = skeleton.point_joints(false).len();
    page::check_size(&c.a.doc.source, frames.len(), points, 2)?;
    let a_figure = figure(&c.a.doc.source, &skeleton, frames, &|f, t| {
        pose(&c.a, frames[f], t)
    })?;
    let b_figure = figure(&c.b.doc.source, &skeleton, frames, &|f, t| c.b_poses[t][f])?;
    let times: Vec<f64> = frames.iter().map(|&k| c.a.tracks[0].times()[k]).collect();
    let mut key_times: Vec<f64> =
        c.b.tracks
            .iter()
            .flat_map(|t| t.times().iter().copied())
            .collect();
    key_times.sort_by(f64::total_cmp);
    let keyed: Vec<usize> = (0..times.len())
        .filter(|&f| {
            let i = key_times.partition_point(|&x| x < times[f] - SAME_TIME);
            i < key_times.len() && (key_times[i] - times[f]).abs() <= SAME_TIME
        })
        .collect();
    let keys = c.b.tracks.iter().map(|t| t.len()).sum();
    let largest =
        world.frames.iter().enumerate().fold(
            (0.0f64, 0usize),
            |m, (f, &d)| if d > m.0 { (d, f) } else { m },
        );
    let worst_track = world
        .tracks
        .iter()
        .enumerate()
        .filter_map(|(t, e)| e.map(|e| (t, e.max)))
        .fold(None, |m: Option<(usize, f64)>, (t, d)| match m {
            Some((_, best)) if best >= d => m,
            _ => Some((t, d)),
        })
        .map(|(t, _)| c.names[t].clone());
    // B's own skeleton, where it has one that is not A's: both figures are A's all the same
    // (as diff measures them, with its warning), which the page says.
    let b_skeleton_differs =
        c.b.doc
            .hierarchy
            .as_deref()
            .is_some_and(|s| s.joints() != skeleton.joints());
    let compared = page::Compared {
        errors: world.frames.clone(),
        b_skeleton_differs,
        keyed,
        keys,
        largest: (largest.0, times.get(largest.1).copied().unwrap_or(0.0)),
        worst_track,
    };
    let mut page = Page::new(
        args,
        &c.a,
        &skeleton,
        times,
        vec![a_figure, b_figure],
        Some(compared),
    )?;
    page.reads.extend(c.b.reads.iter().cloned());
    Ok(page)
}

/// A's skeleton, which every figure is posed on.
fn skeleton_of(a: &Curves) -> Result<Skeleton, Error> {
    let Some(s) = a.doc.hierarchy.as_deref() else {
        // Why there is none: a glTF's tracks from several animations (each poses the nodes
        // apart) or nodes that are not a forest (docs/spec.md §4.8); else keys, which have none.
        let why = match a.gltf.as_deref().map(|g| g.animations().len()) {
            Some(n) if n > 1 => format!(
                "its tracks come from {n} animations, each posing the nodes apart: choose one \
                 with --animation NAME or INDEX"
            ),
            Some(_) => "its nodes do not form a forest".to_string(),
            None => "keys have none: draw them as B beside the clip they came from".to_string(),
        };
        return Err(InputError::new(format!(
            "{}: view draws a skeleton, and this input gives none to compose its joints on \
             ({why})",
            a.doc.source
        ))
        .into());
    };
    if s.track_count() != a.tracks.len() {
        return Err(InputError::new(format!(
            "{}: view poses the skeleton by its tracks, and this input has {} tracks for a \
             skeleton that animates {}",
            a.doc.source,
            a.tracks.len(),
            s.track_count()
        ))
        .into());
    }
    Ok(s.clone())
}

/// Track `t` of `a` at key `k`: its rotation and translation.
fn pose(a: &Curves, k: usize, t: usize) -> (DQuat, Option<DVec3>) {
    let tr = &a.tracks[t];
    (tr.rotations()[k], tr.translations().map(|p| p[k]))
}

/// The points of `skeleton` ([`Skeleton::points`]: each joint's origin and end points) posed at
/// each of `frames.len()` frames by `pose(frame, track)`, as float32; a position that is not
/// finite in float32 is an input error naming the joint and frame.
fn figure(
    source: &str,
    skeleton: &Skeleton,
    frames: &[usize],
    pose: &(dyn Fn(usize, usize) -> (DQuat, Option<DVec3>) + Sync),
) -> Result<Figure, Error> {
    let owners = skeleton.point_joints(false);
    let mut positions = Vec::with_capacity(frames.len() * owners.len() * 3);
    let mut points = Vec::with_capacity(owners.len());
    for f in 0..frames.len() {
        skeleton.points(|t| pose(f, t), None, &mut points);
        for (p, j) in points.iter().zip(&owners) {
            let xyz = [p.x as f32, p.y as f32, p.z as f32];
            if xyz.iter().any(|x| !x.is_finite()) {
                // Shortest digits, in exponent form when large (`1e39`, not 40 digits).
                return Err(InputError::new(format!(
                    "{source}: joint \"{}\": its world position at frame {f} is not a finite \
                     float32 number ({:?}, {:?}, {:?})",
                    inbetween::error::shorten(&skeleton.joints()[*j].name),
                    p.x,
                    p.y,
                    p.z
                ))
                .into());
            }
            positions.extend(xyz);
        }
    }
    Ok(Figure {
        source: source.to_string(),
        positions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_page_is_named_html_unless_the_format_is_said() {
        for ok in ["page.html", "PAGE.HTM", "dir.v/p.Html"] {
            assert!(check_name(Path::new(ok), None).is_ok(), "{ok}");
        }
        for bad in ["page.txt", "page", "page.html.bak", ".html"] {
            let e = check_name(Path::new(bad), None).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("-o {bad}: view writes an HTML page")),
                "{e}"
            );
            assert!(check_name(Path::new(bad), Some(PageFormat::Html)).is_ok());
        }
    }
}
