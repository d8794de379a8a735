//! A BVH clip read for some of its joints only (`interp --tracks` on the lean path): every row is
//! read and checked as always, but only the chosen joints' motion values are kept, so memory
//! follows the tracks chosen, not the file.
//!
//! The clip keeps every joint, its hierarchy text and its track names (the same names as the
//! whole clip's); a joint not chosen loses its channels, so it is not a track
//! ([`Clip::track_joints`] lists the chosen ones, in file order) and its columns are gone: the
//! chosen joints' columns tile `0..channel_count()`. Such a clip is for sampling its tracks; its
//! rows are no longer the file's, so it is never written as BVH.

use super::{Clip, Joint};
use inbetween::error::InputResult;

/// Chooses joints: given the track names of the joints that are tracks (the whole clip's
/// [`Joint::track_name`]s of the joints with channels, in file order), one flag per name, or an
/// input error (which the read returns).
pub type Choose<'a> = &'a dyn Fn(&[String]) -> InputResult<Vec<bool>>;

/// Which columns of `joints` (the whole hierarchy, track names set or not) `choose` keeps, one
/// flag per column, and per joint whether it is kept.
pub(crate) fn columns(joints: &[Joint], choose: Choose) -> InputResult<(Vec<bool>, Vec<bool>)> {
    let given: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
    let ids: Vec<usize> = (0..joints.len()).collect();
    let names = crate::names::unique_names(&given, &ids);
    let tracks: Vec<usize> = (0..joints.len())
        .filter(|&j| !joints[j].channels.is_empty())
        .collect();
    let track_names: Vec<String> = tracks.iter().map(|&j| names[j].clone()).collect();
    let flags = choose(&track_names)?;
    let mut keep_joint = vec![false; joints.len()];
    for (&j, &k) in tracks.iter().zip(&flags) {
        keep_joint[j] = k;
    }
    let columns = joints
        .iter()
        .zip(&keep_joint)
        .flat_map(|(j, &k)| std::iter::repeat_n(k, j.channels.len()))
        .collect();
    Ok((columns, keep_joint))
}

/// Drops the channels of the joints not kept and renumbers the columns of the others; returns
/// the number of columns left.
pub(crate) fn narrow(joints: &mut [Joint], keep_joint: &[bool]) -> usize {
    let mut next = 0;
    for (j, &k) in joints.iter_mut().zip(keep_joint) {
        if !k {
            j.channels.clear();
        }
        j.first_column = next;
        next += j.channels.len();
    }
    next
}

/// `clip` (read whole) with only the joints `choose` keeps: its values compacted row by row.
pub(crate) fn of_clip(mut clip: Clip, choose: Choose) -> InputResult<Clip> {
    let (columns, keep_joint) = columns(&clip.joints, choose)?;
    let values = clip
        .rows()
        .flat_map(|row| {
            row.iter()
                .zip(&columns)
                .filter(|(_, k)| **k)
                .map(|(x, _)| *x)
        })
        .collect();
    clip.channels = narrow(&mut clip.joints, &keep_joint);
    clip.values = values;
    Ok(clip)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::read::tests::SMALL;
    use crate::bvh::{parse, parse_reader, parse_reader_chosen};

    /// A clip read for some joints has their tracks' values exactly as the whole clip has them,
    /// whether read in pieces or whole (`of_clip`).
    #[test]
    fn chosen_joints_keep_their_values_and_names() {
        let (whole, _) = parse(SMALL, "small.bvh").unwrap();
        let names: Vec<String> = whole
            .track_joints()
            .iter()
            .map(|&j| whole.joints()[j].track_name().to_string())
            .collect();
        let pick = |want: &'static [&'static str]| {
            move |names: &[String]| Ok(names.iter().map(|n| want.contains(&n.as_str())).collect())
        };
        let choose = pick(&["Chest", "Prop"]);
        let (piece, _) = parse_reader_chosen(SMALL.as_bytes(), "small.bvh", None, &choose).unwrap();
        let from_whole = of_clip(whole.clone(), &choose).unwrap();
        assert_eq!(piece, from_whole);
        let kept: Vec<&str> = piece
            .track_joints()
            .iter()
            .map(|&j| piece.joints()[j].track_name())
            .collect();
        assert_eq!(kept, ["Chest", "Prop"]);
        assert_eq!(piece.frame_count(), whole.frame_count());
        assert_eq!(piece.joints().len(), whole.joints().len());
        for name in kept {
            let (a, b) = (whole.joint(name).unwrap(), piece.joint(name).unwrap());
            for i in 0..whole.frame_count() {
                let want: Vec<f64> = whole.row(i)[a.columns()].to_vec();
                assert_eq!(&piece.row(i)[b.columns()], &want[..], "{name} row {i}");
            }
        }
        assert!(names.len() > 2);
        // Every joint chosen: the whole clip.
        let all = |names: &[String]| Ok(vec![true; names.len()]);
        let (every, _) = parse_reader_chosen(SMALL.as_bytes(), "small.bvh", None, &all).unwrap();
        assert_eq!(
            every,
            parse_reader(SMALL.as_bytes(), "small.bvh", None).unwrap().0
        );
    }

    /// The choice's error is the read's; a bad value in a joint not chosen is still an error.
    #[test]
    fn every_row_is_checked_and_the_choice_can_refuse() {
        let refuse = |_: &[String]| Err(inbetween::InputError::new("no such track"));
        let err = parse_reader_chosen(SMALL.as_bytes(), "small.bvh", None, &refuse);
        assert_eq!(err.unwrap_err().to_string(), "no such track");
        let (whole, _) = parse(SMALL, "small.bvh").unwrap();
        let first = whole.row(0)[0];
        let at = SMALL.find("Frame Time:").unwrap();
        let row_start = at + SMALL[at..].find('\n').unwrap() + 1;
        let cell_end = row_start + SMALL[row_start..].find([' ', '\t']).unwrap();
        assert_eq!(SMALL[row_start..cell_end].parse::<f64>().unwrap(), first);
        let bad = format!("{}nan{}", &SMALL[..row_start], &SMALL[cell_end..]);
        let only_prop = |names: &[String]| Ok(names.iter().map(|n| n == "Prop").collect());
        let err = parse_reader_chosen(bad.as_bytes(), "small.bvh", None, &only_prop);
        let want = parse_reader(bad.as_bytes(), "small.bvh", None).unwrap_err();
        assert_eq!(err.unwrap_err().to_string(), want.to_string());
    }
}
