//! `inbetween analyze`: the smoothness figures of every track under the chosen schemes.

use super::settings::read_curves;
use crate::args::{AnalyzeArgs, ReportFormat};
use crate::events::Events;
use crate::table::text_table;
use inbetween::metrics::{FIELDS, Metrics, measure_each};
use inbetween::rotation::AngleUnit;
use inbetween::{CurveOptions, Error, Scheme};
use inbetween_io::num::{NumFormat, NumWriter};
use std::io::{Read, Write};

/// Runs `analyze`: the figures of every track under every chosen scheme.
pub fn run(args: &AnalyzeArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    let input = read_curves(
        &args.input,
        &args.curve,
        &|_, _| Scheme::default(),
        stdin,
        warn,
    )?;
    let unit = args.input.angles;
    let schemes: Vec<CurveOptions> = args
        .scheme
        .0
        .iter()
        .map(|&s| CurveOptions {
            scheme: s.into(),
            ..input.opts
        })
        .collect();
    let measured = measure_each(&input.tracks, &schemes, input.fps);
    let mut rows = Vec::with_capacity(measured.len());
    for (m, track) in measured.into_iter().zip(
        input
            .tracks
            .iter()
            .flat_map(|t| std::iter::repeat_n(t, schemes.len())),
    ) {
        let m = m.map_err(|e| e.at(&input.doc.source))?;
        m.check_finite(unit)?;
        if let Some(r) = m.solver
            && !r.converged
        {
            warn.warning(&format!(
                "track {}: minaccel did not converge in {} iterations; its figures are of the \
                 best curve found",
                track.name().unwrap_or("-"),
                r.iterations
            ));
        }
        rows.push(m);
    }
    let format = report_format(args.output_format, args.output.as_deref());
    let bytes = match format {
        ReportFormat::Text => text_table(&rows, unit).into_bytes(),
        ReportFormat::Csv => csv_report(&rows, unit),
        ReportFormat::Json => json_report(&rows, unit),
    };
    let mut out = crate::output::open_output(args.output.as_deref(), &input.reads)?;
    out.write_all(&bytes)?;
    out.commit()?;
    Ok(())
}

fn csv_report(rows: &[Metrics], unit: AngleUnit) -> Vec<u8> {
    let mut nums = NumWriter::new(NumFormat::Shortest);
    let mut out = FIELDS.join(",").into_bytes();
    out.push(b'\n');
    for r in rows {
        let name = r.track.as_deref().unwrap_or("");
        let quoted = if name.contains([',', '"', '\n']) {
            format!("\"{}\"", name.replace('"', "\"\""))
        } else {
            name.to_string()
        };
        out.extend_from_slice(format!("{quoted},{}", r.scheme.name()).as_bytes());
        for v in r.values(unit) {
            out.push(b',');
            nums.float(&mut out, v);
        }
        out.push(b'\n');
    }
    out
}

fn json_report(rows: &[Metrics], unit: AngleUnit) -> Vec<u8> {
    let items: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| {
            let mut m = serde_json::Map::new();
            m.insert("track".into(), r.track.clone().into());
            m.insert("scheme".into(), r.scheme.name().into());
            for (k, v) in FIELDS[2..].iter().zip(r.values(unit)) {
                m.insert((*k).into(), v.into());
            }
            if let Some(s) = r.solver {
                m.insert("solver_iterations".into(), s.iterations.into());
                m.insert("solver_converged".into(), s.converged.into());
            }
            serde_json::Value::Object(m)
        })
        .collect();
    let doc = serde_json::json!({"angles": unit.as_str(), "rows": items});
    let mut out = serde_json::to_vec_pretty(&doc).unwrap_or_default();
    out.push(b'\n');
    out
}

/// A report's format: `--output-format`, else by the extension of `-o` (`.csv`, `.json`), else
/// text (`analyze`, `diff`).
pub(super) fn report_format(
    given: Option<ReportFormat>,
    output: Option<&std::path::Path>,
) -> ReportFormat {
    let by_extension = || {
        let ext = output?.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "csv" => Some(ReportFormat::Csv),
            "json" => Some(ReportFormat::Json),
            _ => None,
        }
    };
    given.or_else(by_extension).unwrap_or(ReportFormat::Text)
}
