//! `inbetween diff A B`: how far motion B is from motion A, per track and, with a skeleton, in
//! world space (the library's [`inbetween::diff`]; docs/spec.md §5b).

use super::settings::{Curves, read_curves};
use crate::args::{DiffArgs, InputArgs, ReportFormat};
use crate::events::Events;
use crate::played::{self, TrackCurve};
use crate::table::{aligned, format_sig};
use glam::{DQuat, DVec3};
use inbetween::diff::{Extent, TrackDiff, WorldDiff, track_diff, world_diff};
use inbetween::rotation::AngleUnit;
use inbetween::skeleton::Skeleton;
use inbetween::{Error, InputError, Track};
use inbetween_io::Format;
use inbetween_io::gltf::document::{Mode, Sampler};
use inbetween_io::num::{NumFormat, NumWriter};
use std::collections::HashMap;
use std::io::{Read, Write};

/// Times closer than this are the same frame (`--common-frames`).
const SAME_TIME: f64 = 1e-9;

/// One track's row: its name, A's compared times, and the differences.
struct Row {
    name: String,
    times: Vec<f64>,
    diff: TrackDiff,
    world: Option<Extent>,
}

/// Both motions read, B played at A's compared times, and what `diff` measures there: one
/// computation for `diff`'s report and `view`'s page.
pub(crate) struct Compared {
    /// Motion A as read.
    pub(crate) a: Curves,
    /// Motion B as read.
    pub(crate) b: Curves,
    /// Per track of A, its name in A's order.
    pub(crate) names: Vec<String>,
    /// Per track of A, the indices of its keys compared.
    pub(crate) compared: Vec<Vec<usize>>,
    /// Per track of A, B's rotation and translation at each compared key.
    pub(crate) b_poses: Vec<Vec<(DQuat, Option<DVec3>)>>,
    /// The world displacement, when A has a skeleton and every track is compared at the same
    /// frames.
    pub(crate) world: Option<WorldDiff>,
    rows: Vec<Row>,
}

/// Runs `diff`; `Ok(Some(message))` when a `--max-angle`/`--max-position` limit is exceeded
/// (the report is written all the same).
pub fn run(
    args: &DiffArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<Option<String>, Error> {
    let format = super::analyze::report_format(args.output_format, args.output.as_deref())?;
    let c = compare(args, stdin, warn)?;
    let rows = &c.rows;
    let unit = args.input.angles;
    let bytes = match (args.per_frame, format) {
        (true, _) => per_frame(&c, format)?,
        (false, ReportFormat::Text) => text(rows, unit).into_bytes(),
        (false, ReportFormat::Csv) => csv(rows, unit),
        (false, ReportFormat::Json) => json(rows, unit),
    };
    let reads = [&c.a.reads[..], &c.b.reads[..]].concat();
    let mut out = crate::output::open_output(args.output.as_deref(), &reads)?;
    out.write_all(&bytes)?;
    out.commit()?;
    Ok(exceeded(rows, args, unit))
}

/// Reads A and B and measures B against A at A's times, as `diff` does (its output options
/// unused): every error `diff` reports on its inputs.
pub(crate) fn compare(
    args: &DiffArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<Compared, Error> {
    // Each side's keys as its format plays them, unless --scheme says how (played::scheme).
    let scheme = |f, recorded| played::scheme(args.scheme, f, recorded);
    let a_stdin = args
        .input
        .input
        .as_deref()
        .is_none_or(|p| p.as_os_str() == "-");
    if a_stdin && args.other.as_os_str() == "-" {
        return Err(InputError::new("diff: A and B cannot both be standard input").into());
    }
    // --animation chooses in each side that is a glTF asset or FBX scene; a side whose name says
    // it is another format (the keys a reduce of one animation wrote) is read as it is. With
    // neither side such, A is read with it and says so.
    let mut a_input = args.input.clone();
    let mut b_input = args.input.clone();
    b_input.input = Some(args.other.clone());
    if args.input.animation.is_some() {
        let other_format = |i: &InputArgs| {
            i.input_format.is_none()
                && i.input
                    .as_deref()
                    .and_then(Format::from_path)
                    .is_some_and(|f| !matches!(f, Format::Gltf | Format::Fbx))
        };
        let (a_other, b_other) = (other_format(&a_input), other_format(&b_input));
        if b_other && !a_other {
            b_input.animation = None;
        } else if a_other && !b_other {
            a_input.animation = None;
        }
    }
    let a = read_curves(&a_input, &args.curve, &scheme, stdin, warn)?;
    let b = read_curves(&b_input, &args.curve, &scheme, stdin, warn)?;
    let names = |tracks: &[Track]| -> Vec<String> {
        tracks
            .iter()
            .enumerate()
            .map(|(i, t)| t.name().map_or_else(|| format!("track{i}"), str::to_string))
            .collect()
    };
    let (a_names, b_names) = (names(&a.tracks), names(&b.tracks));
    let b_of: HashMap<&str, usize> = b_names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.as_str(), i))
        .collect();
    let missing = |names: &[String], other: &[String], source: &str, other_source: &str| {
        let have: std::collections::HashSet<&str> = other.iter().map(String::as_str).collect();
        names.iter().find(|n| !have.contains(n.as_str())).map(|n| {
            InputError::new(format!(
                "diff: track \"{}\" of {source} is not a track of {other_source}; compare the \
                 same tracks (--tracks selects some)",
                inbetween::error::shorten(n)
            ))
        })
    };
    let (sa, sb) = (&a.doc.source, &b.doc.source);
    if let Some(e) = missing(&a_names, &b_names, sa, sb).or(missing(&b_names, &a_names, sb, sa)) {
        return Err(e.into());
    }
    // B as interp plays it: without --scheme, a glTF B's STEP and CUBICSPLINE channels are
    // their samplers; with --scheme, every track is the curve of its keys under that scheme.
    let b_sources = match args.scheme {
        None => played::sources(&b, Mode::Frames),
        Some(_) => vec![None; b.tracks.len()],
    };
    let b_sampled = played::sampled_frames(&b, &b_sources);
    let indices: Vec<usize> = (0..b.tracks.len()).collect();
    let curves: Vec<Result<TrackCurve, Error>> =
        inbetween::parallel::map(&indices, |&i| played::curve(&b, i, &b_sources, &b_sampled));
    let curves = curves
        .into_iter()
        .collect::<Result<Vec<TrackCurve>, Error>>()?;
    // A glTF B's translation channels are played as a player plays them, at A's times: its
    // tracks hold them only sampled at its rotation keys.
    let b_samplers: Vec<Option<Sampler>> = b
        .tracks
        .iter()
        .map(|t| {
            let g = b.gltf.as_ref()?;
            let source = g.source_of(t.name()?, Mode::Frames)?;
            Some(g.sampler(source.index, b.fps))
        })
        .collect();
    // Per track of A: the compared key indices and B's rotation and translation there.
    let mut compared: Vec<Vec<usize>> = Vec::with_capacity(a.tracks.len());
    let mut b_poses = Vec::with_capacity(a.tracks.len());
    let mut rows = Vec::with_capacity(a.tracks.len());
    for (ta, name) in a.tracks.iter().zip(&a_names) {
        let j = b_of[name.as_str()];
        let (tb, cb) = (&b.tracks[j], &curves[j]);
        let (keys, poses) = at_a_times(ta, tb, cb, b_samplers[j].as_ref(), args.common_frames);
        if keys.is_empty() {
            return Err(InputError::new(format!(
                "diff: track \"{}\": no key time of {sa} is a key time of {sb} (within 1e-9 \
                 s); without --common-frames B is interpolated at A's times",
                inbetween::error::shorten(name)
            ))
            .into());
        }
        let rot: Vec<_> = keys.iter().map(|&k| ta.rotations()[k]).collect();
        let pos: Option<Vec<_>> = ta
            .translations()
            .map(|p| keys.iter().map(|&k| p[k]).collect());
        let diff = track_diff(&rot, pos.as_deref(), |k| poses[k]);
        rows.push(Row {
            name: name.clone(),
            times: keys.iter().map(|&k| ta.times()[k]).collect(),
            diff,
            world: None,
        });
        compared.push(keys);
        b_poses.push(poses);
    }
    let world = world(
        &a,
        b.doc.hierarchy.as_deref(),
        &compared,
        &b_poses,
        args,
        warn,
    )?;
    if let Some(world) = &world {
        for (row, w) in rows.iter_mut().zip(&world.tracks) {
            row.world = *w;
        }
    }
    // Positions too large to compose (offsets, translations or --shell near the largest
    // float) make no number to report: an input error, never `inf` in the report.
    for row in &rows {
        let ext = |e: &Extent| [e.max, e.mean];
        let measured = [
            Some(&row.diff.angle),
            row.diff.translation.as_ref(),
            row.world.as_ref(),
        ];
        let what = ["angle", "translation difference", "world displacement"];
        if let Some((_, w)) = measured
            .iter()
            .zip(what)
            .find(|(e, _)| e.is_some_and(|e| ext(e).iter().any(|x| !x.is_finite())))
        {
            return Err(InputError::new(format!(
                "diff: track \"{}\": its {w} is not a finite number: the skeleton's offsets, \
                 translations or --shell are too large to compose in float64",
                inbetween::error::shorten(&row.name)
            ))
            .into());
        }
    }
    Ok(Compared {
        a,
        b,
        names: a_names,
        compared,
        b_poses,
        world,
        rows,
    })
}

/// The `--per-frame` report: per compared frame of A, its index among them, its time and the
/// largest world displacement of any point there ([`WorldDiff::frames`]).
fn per_frame(c: &Compared, format: ReportFormat) -> Result<Vec<u8>, Error> {
    let Some(world) = &c.world else {
        return Err(InputError::new(format!(
            "diff: --per-frame reports world displacements, which {} does not give: it needs a \
             skeleton and every track compared at the same frames",
            c.a.doc.source
        ))
        .into());
    };
    let times: Vec<f64> = c.compared[0]
        .iter()
        .map(|&k| c.a.tracks[0].times()[k])
        .collect();
    let mut nums = NumWriter::new(NumFormat::Shortest);
    Ok(match format {
        ReportFormat::Csv => {
            let mut out = b"frame,time,max_world\n".to_vec();
            for (f, (t, d)) in times.iter().zip(&world.frames).enumerate() {
                out.extend_from_slice(format!("{f},").as_bytes());
                nums.float(&mut out, *t);
                out.push(b',');
                nums.float(&mut out, *d);
                out.push(b'\n');
            }
            out
        }
        ReportFormat::Json => {
            let rows: Vec<_> = times
                .iter()
                .zip(&world.frames)
                .enumerate()
                .map(|(f, (t, d))| serde_json::json!({"frame": f, "time": t, "max_world": d}))
                .collect();
            let mut out = serde_json::to_vec_pretty(&serde_json::json!({ "frames": rows }))
                .unwrap_or_default();
            out.push(b'\n');
            out
        }
        ReportFormat::Text => {
            let mut cells = vec![vec![
                "frame".to_string(),
                "time s".into(),
                "max world".into(),
            ]];
            for (f, (t, d)) in times.iter().zip(&world.frames).enumerate() {
                cells.push(vec![f.to_string(), format_sig(*t), format_sig(*d)]);
            }
            aligned(&cells, 1).into_bytes()
        }
    })
}

/// The key indices of `a` compared and B's rotation and translation at each: every key of A,
/// B's curve there (its translation from `sampler`, a glTF B's channels, where given); with
/// `common`, the keys of A with a key of B at the same time, B's key.
#[allow(clippy::type_complexity)]
fn at_a_times(
    a: &Track,
    b: &Track,
    curve: &TrackCurve,
    sampler: Option<&Sampler>,
    common: bool,
) -> (Vec<usize>, Vec<(glam::DQuat, Option<glam::DVec3>)>) {
    let mut keys = Vec::new();
    let mut poses = Vec::new();
    for (k, &t) in a.times().iter().enumerate() {
        if !common {
            keys.push(k);
            let position = sampler
                .and_then(|s| s.at(t).1)
                .or_else(|| curve.position(t));
            poses.push((curve.rotation(t), position));
            continue;
        }
        let bt = b.times();
        let i = bt.partition_point(|&x| x < t - SAME_TIME);
        if i < bt.len() && (bt[i] - t).abs() <= SAME_TIME {
            keys.push(k);
            poses.push((b.rotations()[i], b.translations().map(|p| p[i])));
        }
    }
    (keys, poses)
}

/// The world-space displacement per track, when A has a skeleton and every track of A is
/// compared at the same times; `None` otherwise (an error with `--max-position` if nothing else
/// measures positions).
fn world(
    a: &super::settings::Curves,
    b_skeleton: Option<&Skeleton>,
    compared: &[Vec<usize>],
    b_poses: &[Vec<(glam::DQuat, Option<glam::DVec3>)>],
    args: &DiffArgs,
    warn: &mut dyn Events,
) -> Result<Option<WorldDiff>, Error> {
    let Some(skeleton) = a.doc.hierarchy.as_deref() else {
        return Ok(None);
    };
    let first = &a.tracks[0];
    let same_frames = a
        .tracks
        .iter()
        .zip(compared)
        .all(|(t, k)| t.times() == first.times() && k.as_slice() == compared[0].as_slice());
    if skeleton.track_count() != a.tracks.len() || !same_frames {
        if args.shell.is_some() || args.max_position.is_some() {
            warn.warning(&format!(
                "{}: world positions are not measured: they need every track compared at the \
                 same frames",
                a.doc.source
            ));
        }
        return Ok(None);
    }
    if b_skeleton.is_some_and(|s| s.joints() != skeleton.joints()) {
        warn.warning("diff: B's skeleton differs from A's; world positions are measured on A's");
    }
    let frames = &compared[0];
    let pose_a = |f: usize, t: usize| {
        let k = frames[f];
        let tr = &a.tracks[t];
        (tr.rotations()[k], tr.translations().map(|p| p[k]))
    };
    let pose_b = |f: usize, t: usize| b_poses[t][f];
    // The points reduce bounds: default ends, or the shell in world units (crate::points).
    let (measured, _, _) = crate::points::measured(skeleton, args.shell);
    Ok(Some(world_diff(
        &measured,
        frames.len(),
        &pose_a,
        &pose_b,
        None,
    )))
}

/// The largest of one measure over the tracks: (value, track, time).
fn largest(rows: &[Row], pick: impl Fn(&Row) -> Option<Extent>) -> Option<(f64, &Row, f64)> {
    let mut best: Option<(f64, &Row, f64)> = None;
    for r in rows {
        if let Some(e) = pick(r)
            && best.is_none_or(|(m, _, _)| e.max > m)
        {
            best = Some((e.max, r, r.times[e.at]));
        }
    }
    best
}

/// The message for a limit exceeded, if one is.
fn exceeded(rows: &[Row], args: &DiffArgs, unit: AngleUnit) -> Option<String> {
    let u = unit.as_str();
    if let (Some(limit), Some((m, r, t))) = (args.max_angle, largest(rows, |r| Some(r.diff.angle)))
        && unit.from_rad(m) > limit
    {
        return Some(format!(
            "diff: the largest angle, {} {u} (track \"{}\", {t} s), exceeds --max-angle {limit}",
            format_sig(unit.from_rad(m)),
            inbetween::error::shorten(&r.name)
        ));
    }
    let limit = args.max_position?;
    for (what, pick) in [
        (
            "world displacement",
            &(|r: &Row| r.world) as &dyn Fn(&Row) -> Option<Extent>,
        ),
        ("translation difference", &|r: &Row| r.diff.translation),
    ] {
        if let Some((m, r, t)) = largest(rows, pick)
            && m > limit
        {
            return Some(format!(
                "diff: the largest {what}, {} (track \"{}\", {t} s), exceeds --max-position \
                 {limit}",
                format_sig(m),
                inbetween::error::shorten(&r.name)
            ));
        }
    }
    None
}

/// The columns of a row (angles in `unit`); `None` for a measure the row does not have.
fn values(r: &Row, unit: AngleUnit) -> [Option<f64>; 8] {
    let at = |e: Option<Extent>| e.map(|e| r.times[e.at]);
    let a = r.diff.angle;
    let t = r.diff.translation;
    [
        Some(unit.from_rad(a.max)),
        Some(r.times[a.at]),
        Some(unit.from_rad(a.mean)),
        t.map(|e| e.max),
        at(t),
        r.world.map(|e| e.max),
        at(r.world),
        r.world.map(|e| e.mean),
    ]
}

const FIELDS: [&str; 8] = [
    "max_angle",
    "max_angle_time",
    "mean_angle",
    "max_translation",
    "max_translation_time",
    "max_world",
    "max_world_time",
    "mean_world",
];

/// The total row: the largest of each measure (and when), means over every compared time.
fn total(rows: &[Row], unit: AngleUnit) -> (usize, [Option<f64>; 8], Option<String>) {
    let count: usize = rows.iter().map(|r| r.diff.angle.count).sum();
    let mean = |pick: &dyn Fn(&Row) -> Option<Extent>| -> Option<f64> {
        let (mut sum, mut n) = (0.0, 0usize);
        for e in rows.iter().filter_map(pick) {
            sum += e.mean * e.count as f64;
            n += e.count;
        }
        (n > 0).then(|| sum / n as f64)
    };
    let angle = largest(rows, |r| Some(r.diff.angle));
    let tr = largest(rows, |r| r.diff.translation);
    let wo = largest(rows, |r| r.world);
    let v = [
        angle.map(|(m, _, _)| unit.from_rad(m)),
        angle.map(|(_, _, t)| t),
        mean(&|r| Some(r.diff.angle)).map(|m| unit.from_rad(m)),
        tr.map(|(m, _, _)| m),
        tr.map(|(_, _, t)| t),
        wo.map(|(m, _, _)| m),
        wo.map(|(_, _, t)| t),
        mean(&|r| r.world),
    ];
    (count, v, angle.map(|(_, r, _)| r.name.clone()))
}

fn text(rows: &[Row], unit: AngleUnit) -> String {
    let u = unit.as_str();
    let header = [
        "track".to_string(),
        "frames".into(),
        format!("max angle {u}"),
        "at s".into(),
        format!("mean angle {u}"),
        "max translation".into(),
        "at s".into(),
        "max world".into(),
        "at s".into(),
        "mean world".into(),
    ];
    let cell = |v: Option<f64>| v.map_or_else(|| "-".to_string(), format_sig);
    let mut cells = vec![header.to_vec()];
    for r in rows {
        let mut row = vec![r.name.clone(), r.diff.angle.count.to_string()];
        row.extend(values(r, unit).map(cell));
        cells.push(row);
    }
    let (count, v, _) = total(rows, unit);
    let mut row = vec!["total".to_string(), count.to_string()];
    row.extend(v.map(cell));
    cells.push(row);
    aligned(&cells, 1)
}

fn csv(rows: &[Row], unit: AngleUnit) -> Vec<u8> {
    let mut nums = NumWriter::new(NumFormat::Shortest);
    let mut out = format!("kind,track,frames,{}\n", FIELDS.join(",")).into_bytes();
    let mut line = |out: &mut Vec<u8>, kind: &str, name: &str, n: usize, v: [Option<f64>; 8]| {
        let quoted = if name.contains([',', '"', '\n', '\r']) {
            format!("\"{}\"", name.replace('"', "\"\""))
        } else {
            name.to_string()
        };
        out.extend_from_slice(format!("{kind},{quoted},{n}").as_bytes());
        for x in v {
            out.push(b',');
            if let Some(x) = x {
                nums.float(out, x);
            }
        }
        out.push(b'\n');
    };
    for r in rows {
        line(
            &mut out,
            "track",
            &r.name,
            r.diff.angle.count,
            values(r, unit),
        );
    }
    let (count, v, worst) = total(rows, unit);
    line(&mut out, "total", worst.as_deref().unwrap_or(""), count, v);
    out
}

fn json(rows: &[Row], unit: AngleUnit) -> Vec<u8> {
    let object = |name: Option<&str>, n: usize, v: [Option<f64>; 8]| {
        let mut m = serde_json::Map::new();
        if let Some(name) = name {
            m.insert("track".into(), name.into());
        }
        m.insert("frames".into(), n.into());
        for (k, x) in FIELDS.iter().zip(v) {
            m.insert((*k).into(), x.map_or(serde_json::Value::Null, Into::into));
        }
        serde_json::Value::Object(m)
    };
    let tracks: Vec<_> = rows
        .iter()
        .map(|r| object(Some(&r.name), r.diff.angle.count, values(r, unit)))
        .collect();
    let (count, v, worst) = total(rows, unit);
    let mut total = object(None, count, v);
    if let (serde_json::Value::Object(m), Some(w)) = (&mut total, worst) {
        m.insert("max_angle_track".into(), w.into());
    }
    let doc = serde_json::json!({"angles": unit.as_str(), "tracks": tracks, "total": total});
    let mut out = serde_json::to_vec_pretty(&doc).unwrap_or_default();
    out.push(b'\n');
    out
}
