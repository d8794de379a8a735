//! Requests by keyword, as Python's `process_file` gives them: each option set by its long name
//! (`fps`, `translation-tolerance` or `translation_tolerance`) from its text, parsed by the same
//! functions as the command line's, and the defaults of the command line ([`Default`]; its tests
//! check both against clap's definitions).

use crate::args::{
    BlendArg, ConvertArgs, CurveArgs, EndsArg, EulerArg, InputArgs, InterpArgs, MethodArg,
    OutputArgs, PathArg, ReduceArgs, SchemeArg, SpanArg, TangentArg, parse_angles, parse_columns,
    parse_delimiter, parse_format, parse_fps, parse_non_negative, parse_output_format,
    parse_positive, parse_precision, parse_quat_order, parse_repr, parse_snap, parse_time_unit,
    parse_times, parse_unit_interval, parse_vec3,
};
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};

/// Options set by name. `set` returns `Ok(false)` for a name the request does not have, and the
/// parser's message for a value it refuses; a flag (`velocity`) takes `true` or `false`.
pub trait Keywords {
    /// The long names, as the command line spells them (without `--`).
    fn names() -> Vec<&'static str>;
    /// Sets the option `name` to the value `text`.
    fn set(&mut self, name: &str, text: &str) -> Result<bool, String>;
}

/// A flag's value: `true` or `false`.
fn flag(text: &str) -> Result<bool, String> {
    match text {
        "true" | "True" => Ok(true),
        "false" | "False" => Ok(false),
        _ => Err(format!(
            "expected true or false, found \"{}\"",
            crate::shown::printable(text)
        )),
    }
}

/// A whole number of at most 64 bits.
fn whole(text: &str) -> Result<u64, String> {
    text.parse().map_err(|_| {
        format!(
            "expected a whole number, found \"{}\"",
            crate::shown::printable(text)
        )
    })
}

impl Default for InputArgs {
    fn default() -> Self {
        InputArgs {
            input: None,
            from: None,
            angles: AngleUnit::Deg,
            input_angles: None,
            key_fps: None,
            delimiter: None,
            columns: None,
            time_unit: None,
            times: None,
            quat_order: QuatOrder::Wxyz,
            input_format: None,
            animation: None,
            max_input_bytes: inbetween_io::DEFAULT_MAX_INPUT_BYTES,
            tracks: None,
        }
    }
}

impl Keywords for InputArgs {
    fn names() -> Vec<&'static str> {
        vec![
            "from",
            "angles",
            "input-angles",
            "key-fps",
            "delimiter",
            "columns",
            "time-unit",
            "times",
            "quat-order",
            "input-format",
            "animation",
            "max-input-bytes",
            "tracks",
        ]
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "from" => self.from = Some(parse_repr(text)?),
            "angles" => self.angles = parse_angles(text)?,
            "input-angles" => self.input_angles = Some(parse_angles(text)?),
            "key-fps" => self.key_fps = Some(parse_fps(text)?),
            "delimiter" => self.delimiter = Some(parse_delimiter(text)?),
            "columns" => self.columns = Some(parse_columns(text)?),
            "time-unit" => self.time_unit = Some(parse_time_unit(text)?),
            "times" => self.times = Some(parse_times(text)?),
            "quat-order" => self.quat_order = parse_quat_order(text)?,
            "input-format" => self.input_format = Some(parse_format(text)?),
            "animation" => self.animation = Some(text.to_string()),
            "max-input-bytes" => self.max_input_bytes = whole(text)?,
            "tracks" => self.tracks = Some(text.to_string()),
            _ => return Ok(false),
        }
        Ok(true)
    }
}

impl Default for OutputArgs {
    fn default() -> Self {
        OutputArgs {
            to: Repr::Quat,
            output_format: None,
            output: None,
            euler: EulerArg::Continuous,
            precision: None,
        }
    }
}

impl Keywords for OutputArgs {
    fn names() -> Vec<&'static str> {
        vec!["to", "output-format", "euler", "precision"]
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "to" => self.to = parse_repr(text)?,
            "output-format" => self.output_format = Some(parse_output_format(text)?),
            "euler" => self.euler = EulerArg::parse(text)?,
            "precision" => self.precision = Some(parse_precision(text)?),
            _ => return Ok(false),
        }
        Ok(true)
    }
}

impl Default for CurveArgs {
    fn default() -> Self {
        CurveArgs {
            fps: None,
            blend: BlendArg::Cubic,
            ends: EndsArg::Chord,
            tangent: None,
            tension: 0.0,
            continuity: 0.0,
            bias: 0.0,
            start_velocity: None,
            end_velocity: None,
            path: PathArg::Shortest,
            snap_keys: None,
        }
    }
}

impl Keywords for CurveArgs {
    fn names() -> Vec<&'static str> {
        vec![
            "fps",
            "blend",
            "ends",
            "tangent",
            "tension",
            "continuity",
            "bias",
            "start-velocity",
            "end-velocity",
            "path",
            "snap-keys",
        ]
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "fps" => self.fps = Some(parse_fps(text)?),
            "blend" => self.blend = BlendArg::parse(text)?,
            "ends" => self.ends = EndsArg::parse(text)?,
            "tangent" => self.tangent = Some(TangentArg::parse(text)?),
            "tension" => self.tension = parse_unit_interval(text)?,
            "continuity" => self.continuity = parse_unit_interval(text)?,
            "bias" => self.bias = parse_unit_interval(text)?,
            "start-velocity" => self.start_velocity = Some(parse_vec3(text)?),
            "end-velocity" => self.end_velocity = Some(parse_vec3(text)?),
            "path" => self.path = PathArg::parse(text)?,
            "snap-keys" => self.snap_keys = Some(parse_snap(text)?),
            _ => return Ok(false),
        }
        Ok(true)
    }
}

impl Keywords for ConvertArgs {
    fn names() -> Vec<&'static str> {
        let mut names = InputArgs::names();
        names.extend(OutputArgs::names());
        names.extend(["fps", "skeleton"]);
        names
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "fps" => self.fps = Some(parse_fps(text)?),
            "skeleton" => self.skeleton = Some(text.into()),
            _ => return Ok(self.input.set(name, text)? || self.output.set(name, text)?),
        }
        Ok(true)
    }
}

/// The default of `interp --max-frames`.
pub const MAX_FRAMES: u64 = 1_000_000_000;

impl Default for InterpArgs {
    fn default() -> Self {
        InterpArgs {
            input: InputArgs::default(),
            output: OutputArgs::default(),
            batch: Default::default(),
            scheme: None,
            curve: CurveArgs::default(),
            velocity: false,
            skeleton: None,
            verbose: false,
            span: SpanArg::Clip,
            max_frames: MAX_FRAMES,
        }
    }
}

impl Keywords for InterpArgs {
    fn names() -> Vec<&'static str> {
        let mut names = InputArgs::names();
        names.extend(OutputArgs::names());
        names.extend(CurveArgs::names());
        names.extend([
            "scheme",
            "velocity",
            "skeleton",
            "verbose",
            "span",
            "max-frames",
        ]);
        names
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "scheme" => self.scheme = Some(SchemeArg::parse(text)?),
            "velocity" => self.velocity = flag(text)?,
            "skeleton" => self.skeleton = Some(text.into()),
            "verbose" => self.verbose = flag(text)?,
            "span" => self.span = SpanArg::parse(text)?,
            "max-frames" => self.max_frames = whole(text)?,
            _ => {
                return Ok(self.input.set(name, text)?
                    || self.output.set(name, text)?
                    || self.curve.set(name, text)?);
            }
        }
        Ok(true)
    }
}

impl Default for ReduceArgs {
    fn default() -> Self {
        ReduceArgs {
            input: InputArgs::default(),
            output: OutputArgs::default(),
            batch: Default::default(),
            tolerance: None,
            position_tolerance: None,
            shell: None,
            joint_tolerance: Vec::new(),
            scheme: None,
            curve: CurveArgs::default(),
            method: MethodArg::Greedy,
            distance: None,
            translation_tolerance: None,
            scale_tolerance: None,
            shared_keys: false,
            no_velocities: false,
            verbose: false,
        }
    }
}

impl Keywords for ReduceArgs {
    fn names() -> Vec<&'static str> {
        let mut names = InputArgs::names();
        names.extend(OutputArgs::names());
        names.extend(CurveArgs::names());
        names.extend([
            "tolerance",
            "position-tolerance",
            "shell",
            "joint-tolerance",
            "scheme",
            "method",
            "distance",
            "translation-tolerance",
            "scale-tolerance",
            "shared-keys",
            "no-velocities",
            "verbose",
        ]);
        names
    }

    fn set(&mut self, name: &str, text: &str) -> Result<bool, String> {
        match name {
            "tolerance" => self.tolerance = Some(parse_positive(text)?),
            "position-tolerance" => self.position_tolerance = Some(parse_positive(text)?),
            "shell" => self.shell = Some(parse_non_negative(text)?),
            // Repeatable: each value another rule.
            "joint-tolerance" => self.joint_tolerance.push(text.to_string()),
            "scheme" => self.scheme = Some(SchemeArg::parse(text)?),
            "method" => self.method = MethodArg::parse(text)?,
            "distance" => self.distance = Some(parse_positive(text)?),
            "translation-tolerance" => self.translation_tolerance = Some(parse_positive(text)?),
            "scale-tolerance" => self.scale_tolerance = Some(parse_positive(text)?),
            "shared-keys" => self.shared_keys = flag(text)?,
            "no-velocities" => self.no_velocities = flag(text)?,
            "verbose" => self.verbose = flag(text)?,
            _ => {
                return Ok(self.input.set(name, text)?
                    || self.output.set(name, text)?
                    || self.curve.set(name, text)?);
            }
        }
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inbetween::Fps;

    #[test]
    fn options_are_set_by_their_long_names_and_parsed_as_the_command_line_parses_them() {
        let mut r = ReduceArgs::default();
        for (name, text) in [
            ("tolerance", "0.5"),
            ("fps", "29.97"),
            ("to", "euler:ZYX"),
            ("method", "optimal"),
            ("joint-tolerance", "Left*=0.2"),
            ("joint-tolerance", "Hips=0.1"),
            ("shared-keys", "true"),
        ] {
            assert_eq!(r.set(name, text), Ok(true), "{name}");
        }
        assert_eq!(r.tolerance, Some(0.5));
        assert_eq!(r.curve.fps, Some(Fps::parse("30000/1001").unwrap()));
        assert_eq!(r.method, MethodArg::Optimal);
        assert_eq!(r.joint_tolerance, ["Left*=0.2", "Hips=0.1"]);
        assert!(r.shared_keys);
        assert_eq!(
            r.set("velocity", "true"),
            Ok(false),
            "interp's, not reduce's"
        );
        let e = r.set("tolerance", "-1").unwrap_err();
        assert_eq!(e, "expected a positive number, found \"-1\"");
        let e = r.set("method", "best").unwrap_err();
        assert_eq!(e, "expected one of greedy, optimal, found \"best\"");
        assert!(r.set("shared-keys", "yes").is_err());
    }

    #[test]
    fn every_name_listed_is_one_the_setter_knows() {
        fn check<K: Keywords + Default>() {
            for name in K::names() {
                let mut k = K::default();
                // Every option refuses an empty value or takes it: either way it is known.
                assert!(
                    !matches!(k.set(name, ""), Ok(false)),
                    "{name} is listed but not set"
                );
            }
        }
        check::<ConvertArgs>();
        check::<InterpArgs>();
        check::<ReduceArgs>();
    }
}
