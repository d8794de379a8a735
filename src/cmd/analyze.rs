//! `inbetween analyze`: the smoothness figures of every track under the chosen schemes.

use crate::analyze::{FIELDS, Metrics, analyze, text_table};
use crate::cli::{AnalyzeArgs, ReportFormat};
use crate::io::num::{NumFormat, NumWriter};
use crate::io::output::Output;
use crate::rotation::AngleUnit;
use std::io::{Read, Write};

pub fn run(
    args: &AnalyzeArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<()> {
    let (doc, _, tracks, opts) = super::read_curves(&args.input, &args.curve, stdin, warn)?;
    let unit = args.input.angles;
    let mut rows = Vec::new();
    for track in &tracks {
        for &s in &args.scheme.0 {
            let m = analyze(track, s.into(), &opts).map_err(|e| match &track.name {
                Some(n) => e.at(format!("{}: track \"{n}\"", doc.source)),
                None => e.at(&doc.source),
            })?;
            if let Some(r) = m.solver
                && !r.converged
            {
                warn(&format!(
                    "track {}: minaccel did not converge in {} iterations; its figures are of the \
                     best curve found",
                    track.name.as_deref().unwrap_or("-"),
                    r.iterations
                ));
            }
            rows.push(m);
        }
    }
    let bytes = match args.output_format {
        ReportFormat::Text => text_table(&rows, unit).into_bytes(),
        ReportFormat::Csv => csv_report(&rows, unit),
        ReportFormat::Json => json_report(&rows, unit),
    };
    let mut out = Output::open(args.output.as_deref())?;
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
