//! Settings shared by the commands that build curves (interp, analyze, plot).

use crate::analyze::CurveOptions;
use crate::cli::{BlendArg, CurveArgs, EndsArg, PathArg, SchemeArg};
use crate::clock::Fps;
use crate::curve::{Blend, Scheme};
use crate::keys::{Document, TimedTrack};
use crate::rotation::AngleUnit;
use crate::tangent::{EndConditions, Ends, PathMode};
use glam::DVec3;

impl From<SchemeArg> for Scheme {
    fn from(s: SchemeArg) -> Scheme {
        match s {
            SchemeArg::Hermite => Scheme::Hermite,
            SchemeArg::Squad => Scheme::Squad,
            SchemeArg::Bezier => Scheme::Bezier,
            SchemeArg::Slerp => Scheme::Slerp,
            SchemeArg::Minaccel => Scheme::MinAccel,
        }
    }
}

/// The output rate (`--fps`, else the document's, else 30), the validated tracks (a document's
/// `frame` values at its own `fps`), and the curve options.
pub fn curve_setup(
    args: &CurveArgs,
    doc: &Document,
    unit: AngleUnit,
) -> Result<(Vec<TimedTrack>, CurveOptions), crate::InputError> {
    let default_fps = Fps::new(30, 1).expect("30 is valid");
    let frame_fps = doc.fps.or(args.fps).unwrap_or(default_fps);
    let fps = args.fps.or(doc.fps).unwrap_or(default_fps);
    let tracks = doc.timed_tracks(frame_fps)?;
    for t in &tracks {
        for &time in [t.times[0], t.times[t.times.len() - 1]].iter() {
            if !fps.in_range(time) {
                return Err(crate::input_err!(
                    "{}: time {} s is beyond the frame numbers --fps {fps} supports (2^53)",
                    doc.source,
                    crate::error::num(time)
                ));
            }
        }
    }
    let omega = |v: Option<[f64; 3]>| v.map(|a| DVec3::from_array(a.map(|x| unit.to_rad(x))));
    let opts = CurveOptions {
        fps,
        blend: match args.blend {
            BlendArg::Cubic => Blend::Cubic,
            BlendArg::Quadratic => Blend::Quadratic,
        },
        path: match args.path {
            PathArg::Shortest => PathMode::Shortest,
            PathArg::AsGiven => PathMode::AsGiven,
        },
        ends: EndConditions {
            ends: match args.ends {
                EndsArg::Chord => Ends::Chord,
                EndsArg::Rest => Ends::Rest,
            },
            start: omega(args.start_velocity),
            end: omega(args.end_velocity),
        },
    };
    Ok((tracks, opts))
}
