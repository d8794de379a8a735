//! The command line (clap derive): the commands, each a request of the commands crate
//! ([`inbetween_commands::args`], whose doc comments are the options' help text and whose
//! parsers make a bad value a usage error naming the flag, exit 2), and the guards every line
//! of standard error passes.

use clap::{Parser, Subcommand};
use inbetween_commands::args::{
    AnalyzeArgs, ConvertArgs, DiffArgs, InterpArgs, PlotArgs, ReduceArgs, ViewArgs,
};

/// Keyframe in-betweener for 3D orientations: reads keyframes (quaternions, Euler angles,
/// matrices, axis-angle, rotation vectors) from CSV, JSON, BVH motion capture, glTF 2.0
/// (.gltf, .glb), FBX or USD (.usda) and writes every in-between frame as CSV, JSON, npy, npz,
/// BVH, glTF, USD or FBX.
#[derive(Debug, Parser)]
#[command(name = "inbetween", version, max_term_width = 100)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Smoothness report per track and scheme: speed, acceleration, jumps at keys, energy.
    ///
    /// Examples:
    ///   inbetween analyze keys.json
    ///   inbetween analyze keys.csv --scheme hermite,minaccel --output-format csv
    ///   inbetween analyze keys.json --scheme squad --fps 60 --angles rad --output-format json
    #[command(verbatim_doc_comment)]
    Analyze(AnalyzeArgs),

    /// Compare two motions with the same tracks: per track the largest and mean angle between
    /// them, and with a skeleton the largest world-space displacement of each joint.
    ///
    /// Examples:
    ///   inbetween diff clip.bvh small.json
    ///   inbetween diff golden.csv out.csv --max-angle 0.001
    ///   inbetween diff clip.bvh back.bvh --shell 3 --max-position 0.5 --output-format json
    #[command(verbatim_doc_comment)]
    Diff(DiffArgs),

    /// SVG chart of angular speed (or velocity components, or accumulated energy) over time,
    /// schemes side by side, keys marked.
    ///
    /// Examples:
    ///   inbetween plot keys.json -o speed.svg
    ///   inbetween plot keys.csv --scheme slerp,hermite,minaccel --what components -o w.svg
    ///   inbetween plot rig.json --track hip --what energy -o energy.svg
    #[command(verbatim_doc_comment)]
    Plot(PlotArgs),

    /// Interpolate keyframes: write every frame between the first and last key.
    ///
    /// Examples:
    ///   inbetween interp keys.json --fps 30
    ///   cat keys.csv | inbetween interp - --fps 24 --to euler:ZYX
    ///   inbetween interp keys.csv --fps 29.97 --scheme squad --ends rest -o frames.csv
    ///   inbetween interp keys.json --start-velocity 0,0,90 --path as-given --precision 9
    #[command(verbatim_doc_comment)]
    Interp(InterpArgs),

    /// Change representation and/or format of keyframes, without interpolating.
    ///
    /// Examples:
    ///   inbetween convert keys.csv --to euler:ZYX
    ///   cat keys.json | inbetween convert --to matrix --output-format csv
    ///   inbetween convert keys.csv --from euler:zxz --angles rad --to quat -o keys.json
    #[command(verbatim_doc_comment)]
    Convert(ConvertArgs),

    /// The fewest keys that interp turns back into the motion: every input frame within the
    /// tolerance, checked before writing.
    ///
    /// Examples:
    ///   inbetween reduce clip.csv --tolerance 0.5 -o keys.json
    ///   inbetween reduce clip.bvh --tolerance 1 --translation-tolerance 0.1 --shared-keys -o keys.json
    ///   inbetween reduce frames.csv --tolerance 0.2 --distance 50 --scheme slerp
    ///   inbetween reduce anim.glb --tolerance 0.5 --scheme slerp -o small.glb
    #[command(verbatim_doc_comment)]
    Reduce(ReduceArgs),

    /// One self-contained HTML page that plays A (and B beside it, as diff plays it) as stick
    /// figures, with the world displacement per frame under them and B's keyed frames marked.
    ///
    /// Examples:
    ///   inbetween view clip.bvh -o clip.html
    ///   inbetween view clip.bvh small.json --tolerance 0.5 -o check.html
    ///   inbetween view clip.bvh small.glb --overlay --title "walk, reduced" -o walk.html
    #[command(verbatim_doc_comment)]
    View(ViewArgs),
}

impl Command {
    /// One meaning per spelling: `-o -` is standard output exactly as no `-o` is (so that
    /// defaults which depend on "is there an output file" treat both alike).
    pub fn normalise(&mut self) {
        let output = match self {
            Command::Convert(a) => &mut a.output.output,
            Command::Interp(a) => &mut a.output.output,
            Command::Reduce(a) => &mut a.output.output,
            Command::Analyze(a) => &mut a.output,
            Command::Diff(a) => &mut a.output,
            Command::Plot(_) | Command::View(_) => return,
        };
        if output.as_deref().is_some_and(|p| p.as_os_str() == "-") {
            *output = None;
        }
    }
}

/// A usage message with every run of more than [`MAX_QUOTED_CHARS`] characters that are not
/// white space or quotes cut to that many and `…` (clap echoes a bad value whole, and the tip
/// for an unknown flag echoes it twice).
///
/// [`MAX_QUOTED_CHARS`]: inbetween::error::MAX_QUOTED_CHARS
pub fn bounded(msg: &str) -> String {
    let limit = inbetween::error::MAX_QUOTED_CHARS;
    let mut out = String::with_capacity(msg.len().min(4096));
    let mut run = 0usize;
    let mut cut = false;
    for c in msg.chars() {
        if c.is_whitespace() || c == '\'' || c == '"' {
            run = 0;
            cut = false;
            out.push(c);
        } else {
            run += 1;
            if run <= limit {
                out.push(c);
            } else if !cut {
                out.push('…');
                cut = true;
            }
        }
    }
    out
}

pub use inbetween_commands::shown::line;

#[cfg(test)]
mod tests {
    use super::{Cli, Command, bounded};
    use clap::{CommandFactory, Parser, ValueEnum};
    use inbetween_commands::args::{
        BlendArg, ConvertArgs, EndsArg, EulerArg, InterpArgs, MethodArg, PathArg, ReduceArgs,
        ReportFormat, SchemeArg, SpanArg, WhatArg,
    };

    /// The long options of `command` that one input takes (not a batch's, not `-o`).
    fn longs(command: &str) -> Vec<String> {
        let batch = ["out-dir", "jobs", "manifest", "refresh", "follow", "output"];
        let mut names: Vec<String> = Cli::command()
            .find_subcommand(command)
            .unwrap()
            .get_arguments()
            .filter_map(|a| a.get_long().map(str::to_string))
            .filter(|l| !batch.contains(&l.as_str()))
            .collect();
        names.sort();
        names
    }

    /// Python's keywords are the command line's options: the same names, the same defaults
    /// (a request by keyword with none given equals the command line's with none given).
    #[test]
    fn requests_by_keyword_are_the_command_lines() {
        for command in ["interp", "convert", "reduce"] {
            let mut names = inbetween_commands::batch::option_names(command).unwrap();
            names.sort();
            assert_eq!(names, longs(command), "{command}");
        }
        let parse = |args: &[&str]| Cli::try_parse_from(args).unwrap().command;
        let Command::Interp(i) = parse(&["inbetween", "interp"]) else {
            panic!()
        };
        assert_eq!(i, InterpArgs::default());
        let Command::Convert(c) = parse(&["inbetween", "convert"]) else {
            panic!()
        };
        assert_eq!(c, ConvertArgs::default());
        let Command::Reduce(r) = parse(&["inbetween", "reduce", "--tolerance", "1"]) else {
            panic!()
        };
        let by_keyword = ReduceArgs {
            tolerance: Some(1.0),
            ..ReduceArgs::default()
        };
        assert_eq!(r, by_keyword);
    }

    /// Each closed set of values has the names clap derives for it, in the same order.
    #[test]
    fn named_values_are_clap_s() {
        fn same<T: ValueEnum + PartialEq + std::fmt::Debug>(names: &[(&str, T)]) {
            let clap: Vec<String> = T::value_variants()
                .iter()
                .map(|v| v.to_possible_value().unwrap().get_name().to_string())
                .collect();
            let ours: Vec<&str> = names.iter().map(|n| n.0).collect();
            assert_eq!(clap, ours);
            for (v, n) in T::value_variants().iter().zip(names) {
                assert_eq!(v, &n.1);
            }
        }
        same(MethodArg::NAMES);
        same(EulerArg::NAMES);
        same(SpanArg::NAMES);
        same(WhatArg::NAMES);
        same(ReportFormat::NAMES);
        same(SchemeArg::NAMES);
        same(BlendArg::NAMES);
        same(EndsArg::NAMES);
        same(PathArg::NAMES);
    }

    /// Every setting's flag is a flag of some command, so no message names a flag that does
    /// not exist.
    #[test]
    fn every_setting_is_a_flag_of_the_command_line() {
        use inbetween::error::Setting;
        use inbetween_commands::flags::flag;
        let cli = Cli::command();
        let flags: Vec<String> = cli
            .get_subcommands()
            .flat_map(|c| c.get_arguments())
            .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
            .collect();
        for s in Setting::ALL {
            assert!(flags.iter().any(|f| f == flag(s)), "{s:?}: {}", flag(s));
        }
    }

    #[test]
    fn long_runs_are_cut_and_quotes_kept() {
        let long = "7".repeat(100_000);
        let msg = format!("error: invalid value '{long}' for '--fps <RATE>': found {long}\n");
        let b = bounded(&msg);
        let cut = format!("{}…", "7".repeat(60));
        assert_eq!(
            b,
            format!("error: invalid value '{cut}' for '--fps <RATE>': found {cut}\n")
        );
    }

    #[test]
    fn short_messages_are_unchanged() {
        let msg = "error: unexpected argument '--frob' found\n\n  tip: try '--fps'\n";
        assert_eq!(bounded(msg), msg);
    }
}
