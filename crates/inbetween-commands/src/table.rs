//! Reports as a terminal shows them: aligned text tables of six-significant-digit numbers
//! (`analyze`'s figures, `diff`'s rows).

use inbetween::metrics::Metrics;
use inbetween::rotation::AngleUnit;
use std::fmt::Write as _;

/// An aligned table for a terminal, with units in the header.
pub fn text_table(rows: &[Metrics], unit: AngleUnit) -> String {
    let u = unit.as_str();
    let header = [
        "track".to_string(),
        "scheme".to_string(),
        "duration s".to_string(),
        format!("angle {u}"),
        format!("max speed {u}/s"),
        format!("mean speed {u}/s"),
        format!("max accel {u}/s²"),
        format!("C¹ jump {u}/s"),
        format!("C² jump {u}/s²"),
        "energy E".to_string(),
    ];
    let mut cells: Vec<Vec<String>> = vec![header.to_vec()];
    for r in rows {
        let mut row = vec![
            r.track.clone().unwrap_or_else(|| "-".into()),
            r.scheme.name().to_string(),
        ];
        row.extend(r.values(unit).iter().map(|x| format_sig(*x)));
        cells.push(row);
    }
    aligned(&cells, 2)
}

/// `cells` (a header row first) as an aligned text table: the first `left` columns padded on
/// the right, the others (numbers) on the left, two spaces apart, one line per row.
pub fn aligned(cells: &[Vec<String>], left: usize) -> String {
    let columns = cells.first().map_or(0, Vec::len);
    let widths: Vec<usize> = (0..columns)
        .map(|c| {
            cells
                .iter()
                .map(|r| r.get(c).map_or(0, |s| s.chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    for row in cells {
        for (c, cell) in row.iter().enumerate() {
            let pad = widths[c].saturating_sub(cell.chars().count());
            if c < left {
                let _ = write!(out, "{cell}{}", " ".repeat(pad));
            } else {
                let _ = write!(out, "{}{cell}", " ".repeat(pad));
            }
            out.push_str(if c + 1 < row.len() { "  " } else { "\n" });
        }
    }
    out
}

/// Six significant digits, without exponent for ordinary magnitudes.
pub fn format_sig(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let mag = x.abs().log10().floor() as i32;
    if !(-4..9).contains(&mag) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sig_format() {
        assert_eq!(format_sig(123.456789), "123.457");
        assert_eq!(format_sig(0.001234567), "0.00123457");
        assert_eq!(format_sig(1.5e-9), "1.50000e-9");
        assert_eq!(format_sig(0.0), "0");
    }

    #[test]
    fn tables_align_names_left_and_numbers_right() {
        let cells = vec![
            vec!["track".to_string(), "max".to_string()],
            vec!["hip".to_string(), "1.5".to_string()],
        ];
        assert_eq!(aligned(&cells, 1), "track  max\nhip    1.5\n");
    }
}
