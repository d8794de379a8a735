//! `--skeleton clip.bvh`: a BVH file whose hierarchy, channel orders and Frame Time keys are
//! written on (`convert` and `interp` to BVH or FBX), and how a document's tracks find its joints.

use inbetween::InputError;
use inbetween_io::OutputFormat;
use inbetween_io::clip::Clip;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// The `--skeleton` BVH file, read.
pub fn read(path: &Path) -> Result<Arc<Clip>, InputError> {
    let source = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| InputError::new(format!("{source}: cannot read: {e}")))?;
    Ok(Arc::new(inbetween_io::bvh::parse(&text, &source)?.0))
}

/// With `--skeleton`, the output must be BVH (its default there) or FBX (the same motion on
/// the same skeleton); another format is refused.
pub fn check_output(format: OutputFormat) -> Result<(), InputError> {
    if matches!(format, OutputFormat::Bvh | OutputFormat::Fbx) {
        return Ok(());
    }
    Err(InputError::new(
        "--skeleton: the output is neither BVH nor FBX; write it with -o out.bvh or -o out.fbx \
         (or --output-format bvh or fbx)",
    ))
}

/// The tracks in the order of `skeleton`'s joints with channels (what BVH frames are written in),
/// each found by its joint's track name (the first track of that name): every such joint needs a
/// track, with translations where it has position channels, and every track must be a joint's.
/// `tracks` are each track's name and whether it has translations; `source` names the keys,
/// `skeleton_source` the skeleton, in messages.
pub fn joint_order(
    skeleton: &Clip,
    tracks: &[(Option<&str>, bool)],
    source: &str,
    skeleton_source: &str,
) -> Result<Vec<usize>, InputError> {
    let mut by_name: HashMap<&str, usize> = HashMap::with_capacity(tracks.len());
    for (i, t) in tracks.iter().enumerate() {
        if let Some(n) = t.0 {
            by_name.entry(n).or_insert(i);
        }
    }
    let short = inbetween::error::shorten;
    let mut order = Vec::with_capacity(tracks.len());
    for j in skeleton.track_joints() {
        let joint = &skeleton.joints()[j];
        let name = joint.track_name();
        let Some(&i) = by_name.get(name) else {
            return Err(InputError::new(format!(
                "{source}: no track for joint \"{}\" of {skeleton_source}: output on a BVH \
                 skeleton needs a track per joint with channels, named as convert and reduce \
                 name them",
                short(name)
            )));
        };
        if joint.position().is_some() && !tracks[i].1 {
            return Err(InputError::new(format!(
                "{source}: track \"{}\" has no translations, which joint \"{}\" of \
                 {skeleton_source} has position channels for",
                short(name),
                short(name)
            )));
        }
        order.push(i);
    }
    if order.len() != tracks.len() {
        let extra = (0..tracks.len()).find(|i| !order.contains(i)).unwrap_or(0);
        let name = tracks[extra]
            .0
            .map_or("(unnamed)".into(), |n| short(n).into_owned());
        return Err(InputError::new(format!(
            "{source}: track \"{name}\" is not a joint of {skeleton_source} (output on a BVH \
             skeleton writes its joints only)"
        )));
    }
    Ok(order)
}

/// USD and FBX output's checks (§3, *USD output*, *FBX output*): the input's skeleton, and no
/// option the format has no place for (USD: `--span track`; both: `--velocity`, `--tracks`,
/// `--precision`).
pub fn usd_output(
    args: &crate::args::InterpArgs,
    doc: &inbetween_io::document::Document,
    format: OutputFormat,
) -> Result<std::sync::Arc<inbetween::skeleton::Skeleton>, inbetween::Error> {
    use inbetween::InputError;
    let Some(h) = doc.hierarchy.clone() else {
        let name = if format == OutputFormat::Fbx {
            "FBX"
        } else {
            "USD"
        };
        return Err(InputError::new(format!(
            "{}: {name} output is a skeleton's animation; this input has no skeleton (BVH, \
             glTF, FBX or USD input has one); write csv or json",
            doc.source
        ))
        .into());
    };
    super::settings::check_carries(args, format)?;
    Ok(h)
}
