//! What each output format can carry (docs/spec.md §3): one table, so that the command line and
//! Python refuse the same things for the same reasons. A front end asks [`of`] and words the
//! refusal with its own option's name: the reasons here name no option.

use inbetween_io::{Format, OutputFormat};

/// What an output format needs from the input before it can be written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Needs {
    /// Nothing beyond tracks.
    Tracks,
    /// A skeleton to write the motion on: BVH (a BVH input's, or a template's), USD (the
    /// input's hierarchy).
    Skeleton,
    /// The glTF asset the tracks were read from, which the output is written into.
    Asset,
    /// The rate the frames are at (npy, npz: frames, not keys).
    Rate,
}

/// What an output format can carry. Each `no_…` field is `None` where the format carries it,
/// else the reason it does not (a clause such as "BVH has no place for angular velocities").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Capability {
    /// What it needs.
    pub needs: Needs,
    /// Angular velocities beside the rotations.
    pub no_velocities: Option<&'static str>,
    /// Each track over its own span of frames (else one span for all).
    pub no_track_spans: Option<&'static str>,
    /// A selection of the tracks (else every joint of the skeleton is written).
    pub no_track_selection: Option<&'static str>,
    /// Numbers to a chosen number of digits (else float32).
    pub no_precision: Option<&'static str>,
}

/// The table.
pub fn of(format: OutputFormat) -> Capability {
    let all = Capability {
        needs: Needs::Tracks,
        no_velocities: None,
        no_track_spans: None,
        no_track_selection: None,
        no_precision: None,
    };
    match format {
        OutputFormat::Doc(Format::Csv | Format::Json) => all,
        OutputFormat::Npy | OutputFormat::Npz => Capability {
            needs: Needs::Rate,
            ..all
        },
        OutputFormat::Bvh => Capability {
            needs: Needs::Skeleton,
            no_velocities: Some("BVH has no place for angular velocities"),
            no_track_spans: Some("a BVH file has one frame range for every joint"),
            no_track_selection: Some("a BVH file is written with every joint of its skeleton"),
            ..all
        },
        OutputFormat::Gltf(_) => Capability {
            needs: Needs::Asset,
            no_velocities: Some("glTF has no place for angular velocities"),
            no_track_spans: Some("glTF output writes each animation over its own span"),
            ..all
        },
        OutputFormat::Usda | OutputFormat::Doc(Format::Usd) => Capability {
            needs: Needs::Skeleton,
            no_velocities: Some("USD has no place for angular velocities"),
            no_track_spans: Some("USD samples every joint at the same times"),
            no_track_selection: Some(
                "a USD skeleton is written with every joint, posed by its track",
            ),
            no_precision: Some("USD stores its values as float32"),
        },
        OutputFormat::Fbx => Capability {
            needs: Needs::Skeleton,
            no_velocities: Some("FBX has no place for angular velocities"),
            no_track_selection: Some(
                "an FBX skeleton is written with every joint, posed by its track",
            ),
            no_precision: Some("FBX stores its keys as float32"),
            ..all
        },
        // Not documents these variants write (each has its own output variant): nothing to
        // carry.
        OutputFormat::Doc(Format::Bvh | Format::Gltf | Format::Fbx | Format::Amass) => all,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_documents_carry_everything_and_skeletal_formats_refuse_by_reason() {
        for f in [Format::Csv, Format::Json] {
            assert_eq!(of(OutputFormat::Doc(f)).needs, Needs::Tracks);
            assert!(of(OutputFormat::Doc(f)).no_velocities.is_none());
        }
        assert_eq!(of(OutputFormat::Npz).needs, Needs::Rate);
        assert_eq!(of(OutputFormat::Bvh).needs, Needs::Skeleton);
        assert_eq!(of(OutputFormat::Usda).needs, Needs::Skeleton);
        let glb = of(OutputFormat::Gltf(inbetween_io::gltf::ContainerFormat::Glb));
        assert_eq!(glb.needs, Needs::Asset);
        assert!(glb.no_track_selection.is_none() && glb.no_velocities.is_some());
        for f in [OutputFormat::Bvh, OutputFormat::Usda] {
            let c = of(f);
            assert!(c.no_velocities.is_some() && c.no_track_spans.is_some());
            assert!(c.no_track_selection.is_some());
        }
        // FBX: a skeleton, every joint, float32 keys; each joint's curves have their own keys.
        let fbx = of(OutputFormat::Fbx);
        assert_eq!(fbx.needs, Needs::Skeleton);
        assert!(fbx.no_velocities.is_some() && fbx.no_track_selection.is_some());
        assert!(fbx.no_precision.is_some() && fbx.no_track_spans.is_none());
    }
}
