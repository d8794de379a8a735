//! `inbetween analyze`: the smoothness figures of every track under the chosen schemes.

use super::settings::read_curves;
use crate::args::{AnalyzeArgs, ReportFormat};
use crate::events::Events;
use crate::table::text_table;
use inbetween::metrics::{FIELDS, Metrics, measure_each};
use inbetween::rotation::AngleUnit;
use inbetween::{CurveOptions, Error, InputError, Scheme};
use inbetween_io::num::{NumFormat, NumWriter};
use std::io::{Read, Write};

/// Runs `analyze`: the figures of every track under every chosen scheme.
pub fn run(args: &AnalyzeArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    let format = report_format(args.output_format, args.output.as_deref())?;
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
/// text (`analyze`, `diff`). Without `--output-format`, an `-o` named for a format of motion the
/// tool reads or writes (`.fbx`, `.bvh`, `.usda`, `.glb`, `.npz`, `.html`, …, any case) is an
/// input error: the report's text would go into a file whose name says another format.
pub(super) fn report_format(
    given: Option<ReportFormat>,
    output: Option<&std::path::Path>,
) -> Result<ReportFormat, InputError> {
    if let Some(format) = given {
        return Ok(format);
    }
    let ext = output
        .and_then(|p| p.extension())
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "csv" => Ok(ReportFormat::Csv),
        "json" => Ok(ReportFormat::Json),
        "bvh" | "fbx" | "gltf" | "glb" | "usd" | "usda" | "usdc" | "usdz" | "npy" | "npz"
        | "html" | "htm" | "svg" => Err(InputError::new(format!(
            "{}: a report is text, csv or json, not the .{ext} this name says: name it .txt, \
             .csv or .json, or say what to write under this name with --output-format",
            output.map(|p| p.display().to_string()).unwrap_or_default()
        ))),
        _ => Ok(ReportFormat::Text),
    }
}
