//! `plot`: an SVG chart of a track's angular motion, schemes side by side, made with plotters'
//! SVG backend (no system fonts or libraries needed).
//!
//! - `speed` (default): `|ω(t)|` in `--angles` units per second, one line per scheme; a jump of
//!   angular velocity at a key shows as a vertical step (both one-sided values are drawn).
//! - `components`: `ω_x, ω_y, ω_z`, one line each per scheme (solid, dashed, dotted).
//! - `energy`: Barr's energy accumulated over the grid `analyze` takes it on
//!   ([`inbetween::metrics::energy_rate`]), `Σ_{t_p ≤ t} w_p |q_p'' ∖ q_p|²`.
//!
//! Keys are marked by a dot on the time axis, and by grey vertical lines while those stay
//! readable: when the keys are on average at least [`KEY_LINE_SPACING`] pixels apart on the
//! time axis (dense keys drew a grey curtain over the curves). Colours are the
//! Okabe–Ito palette (readable with colour-blindness), one per scheme.

use glam::DVec3;
use inbetween::clock::Fps;
use inbetween::curve::minaccel::energy;
use inbetween::curve::piecewise::Side;
use inbetween::curve::{Curve, CurveOptions, Scheme};
use inbetween::error::Error;
use inbetween::rotation::AngleUnit;
use inbetween::track::Track;
use plotters::prelude::*;

/// What to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum What {
    /// `|ω|` over time.
    Speed,
    /// `ωx`, `ωy`, `ωz` over time.
    Components,
    /// Accumulated energy over time.
    Energy,
}

/// Samples per key segment for the smooth schemes.
const SAMPLES: usize = 120;

/// The least mean spacing of the keys on the time axis, in pixels of the 1440-pixel-wide
/// chart, for their vertical lines to be drawn.
pub const KEY_LINE_SPACING: f64 = 8.0;

/// The colour of a scheme.
pub fn colour(s: Scheme) -> RGBColor {
    match s {
        Scheme::Hermite => RGBColor(0x00, 0x72, 0xB2),
        Scheme::Squad => RGBColor(0xE6, 0x9F, 0x00),
        Scheme::Bezier => RGBColor(0x00, 0x9E, 0x73),
        Scheme::Slerp => RGBColor(0x99, 0x99, 0x99),
        Scheme::Nlerp => RGBColor(0xCC, 0x79, 0xA7),
        Scheme::MinAccel => RGBColor(0xD5, 0x5E, 0x00),
    }
}

/// `(t, ω)` samples of a curve: each key segment sampled from its start (right side) to its end
/// (left side), so jumps at keys are kept; minaccel at its grid points. A one-key track (a
/// constant) is at rest over the second around its key that the chart shows.
fn velocity_samples(curve: &Curve) -> Vec<(f64, DVec3)> {
    let mut out = Vec::new();
    let key_times = curve.key_times();
    if let [t] = key_times[..] {
        return vec![(t - 0.5, DVec3::ZERO), (t + 0.5, DVec3::ZERO)];
    }
    match curve.scheme() {
        Scheme::Hermite | Scheme::Squad | Scheme::Bezier | Scheme::Slerp | Scheme::Nlerp => {
            for i in 0..key_times.len() - 1 {
                let (t0, t1) = (key_times[i], key_times[i + 1]);
                for j in 0..=SAMPLES {
                    let t = t0 + (t1 - t0) * j as f64 / SAMPLES as f64;
                    let side = if j == SAMPLES {
                        Side::Left
                    } else {
                        Side::Right
                    };
                    out.push((t, curve.omega(t, side)));
                }
            }
        }
        Scheme::MinAccel => {
            let times = curve.breaks();
            for &t in times {
                let is_key = key_times.binary_search_by(|k| k.total_cmp(&t)).is_ok();
                if is_key && t != times[0] {
                    out.push((t, curve.omega(t, Side::Left)));
                }
                if !is_key || t != times[times.len() - 1] {
                    out.push((t, curve.omega(t, Side::Right)));
                }
            }
        }
    }
    out
}

/// One line to draw: points, label, colour, dash pattern (0 solid, 1 dashed, 2 dotted).
struct Line {
    points: Vec<(f64, f64)>,
    label: String,
    colour: RGBColor,
    dash: u8,
}

/// Draws the chart of `track` for `schemes` (each with the rest of `opts`) and returns the SVG
/// text; energy is accumulated on the grid of `energy_rate` at `fps`. Fails when minaccel cannot
/// solve (an input error) or plotters cannot draw.
pub fn svg(
    track: &Track,
    schemes: &[Scheme],
    what: What,
    opts: &CurveOptions,
    fps: Fps,
    unit: AngleUnit,
) -> Result<String, Error> {
    let u = unit.as_str();
    let mut lines = Vec::new();
    // The energy's grid, analyze's; minaccel is solved on it, as analyze solves it.
    let fine = inbetween::metrics::energy_rate(track.times(), fps);
    for &s in schemes {
        let grid_rate = if what == What::Energy {
            fine
        } else {
            opts.grid_rate
        };
        let curve = Curve::new(
            track,
            &CurveOptions {
                scheme: s,
                grid_rate,
                ..*opts
            },
        )?;
        let c = colour(s);
        match what {
            What::Speed => lines.push(Line {
                points: velocity_samples(&curve)
                    .iter()
                    .map(|(t, w)| (*t, unit.from_rad(w.length())))
                    .collect(),
                label: s.name().to_string(),
                colour: c,
                dash: 0,
            }),
            What::Components => {
                let samples = velocity_samples(&curve);
                for (axis, name) in ["ωx", "ωy", "ωz"].iter().enumerate() {
                    lines.push(Line {
                        points: samples
                            .iter()
                            .map(|(t, w)| (*t, unit.from_rad(w[axis])))
                            .collect(),
                        label: format!("{} {name}", s.name()),
                        colour: c,
                        dash: axis as u8,
                    });
                }
            }
            What::Energy => {
                let (t0, t1) = track.span();
                let (first, last) = fine.frames_between(t0, t1);
                let times: Vec<f64> = (first..=last).map(|k| fine.time_of(k)).collect();
                let pts: Vec<_> = times.iter().map(|&t| curve.eval(t)).collect();
                let mut acc = 0.0;
                // A track may span no frame at all (keys closer than a frame period).
                let mut points: Vec<(f64, f64)> =
                    times.first().map(|&t| (t, 0.0)).into_iter().collect();
                for p in 1..times.len().saturating_sub(1) {
                    acc += energy(&times[p - 1..p + 2], &pts[p - 1..p + 2]);
                    points.push((times[p], acc));
                }
                lines.push(Line {
                    points,
                    label: s.name().to_string(),
                    colour: c,
                    dash: 0,
                });
            }
        }
    }
    let (title, y_desc) = match what {
        What::Speed => ("Angular speed", format!("angular speed ({u}/s)")),
        What::Components => (
            "Angular velocity (world frame)",
            format!("angular velocity ({u}/s)"),
        ),
        What::Energy => (
            "Accumulated energy E (Barr et al.)",
            "E, accumulated".to_string(),
        ),
    };
    let name = track
        .name()
        .map_or(String::new(), |n| format!(" — track {n}"));
    let (t0, t1) = match track.span() {
        // A one-key track: a second around its key.
        (a, b) if a == b => (a - 0.5, b + 0.5),
        span => span,
    };
    let ys = lines.iter().flat_map(|l| l.points.iter().map(|p| p.1));
    let (mut y0, mut y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
        (a.min(y), b.max(y))
    });
    if !(y0.is_finite() && y1.is_finite()) {
        // Nothing to draw (no sample): the range of a curve at rest.
        (y0, y1) = (0.0, 0.0);
    }
    if what != What::Components {
        y0 = y0.min(0.0);
    }
    if y1.partial_cmp(&y0) != Some(std::cmp::Ordering::Greater) {
        y1 = y0 + 1.0;
    }
    // Headroom above the data for the legend (upper right).
    let span = y1 - y0;
    let (y0, y1) = (
        if y0 < 0.0 { y0 - 0.06 * span } else { y0 },
        y1 + 0.42 * span,
    );

    let mut text = String::new();
    {
        // plotters' SVG backend works in whole pixels: a large canvas keeps lines smooth (the
        // SVG scales to any size).
        let root = SVGBackend::with_string(&mut text, (1440, 810)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| {
            Error::Io(std::io::Error::other(format!("cannot draw the chart: {e}")))
        };
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("{title}{name}"), ("sans-serif", 34))
            .margin(24)
            .x_label_area_size(66)
            .y_label_area_size(108)
            .build_cartesian_2d(t0..t1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc(y_desc)
            .light_line_style(RGBColor(0xEE, 0xEE, 0xEE))
            .bold_line_style(RGBColor(0xDD, 0xDD, 0xDD))
            .label_style(("sans-serif", 21))
            .axis_desc_style(("sans-serif", 24))
            .draw()
            .map_err(|e| err(&e))?;
        let grey = RGBColor(0xB0, 0xB0, 0xB0);
        let keys = track.times();
        let px = |t: f64| f64::from(chart.backend_coord(&(t, y0)).0);
        let spacing = match keys {
            [first, .., last] => (px(*last) - px(*first)) / (keys.len() - 1) as f64,
            _ => f64::INFINITY,
        };
        for &tk in keys.iter().filter(|_| spacing >= KEY_LINE_SPACING) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(tk, y0), (tk, y1)],
                    grey.stroke_width(2),
                )))
                .map_err(|e| err(&e))?;
        }
        chart
            .draw_series(
                track
                    .times()
                    .iter()
                    .map(|&tk| Circle::new((tk, y0), 6, grey.filled())),
            )
            .map_err(|e| err(&e))?
            .label("keys")
            .legend(move |(x, y)| Circle::new((x + 15, y), 6, grey.filled()));
        for line in lines {
            let c = line.colour;
            let style = c.stroke_width(3);
            let dash = line.dash;
            let series = match dash {
                0 => chart.draw_series(LineSeries::new(line.points, style)),
                d => chart.draw_series(DashedLineSeries::new(
                    line.points,
                    if d == 1 { 12 } else { 3 },
                    6,
                    style,
                )),
            }
            .map_err(|e| err(&e))?;
            // The legend glyph carries the line's dash pattern: solid, dashed or dotted.
            series.label(line.label).legend(move |(x, y)| {
                let parts: [(i32, i32); 4] = match dash {
                    0 => [(0, 30); 4],
                    1 => [(0, 12), (18, 30), (18, 30), (18, 30)],
                    _ => [(0, 3), (9, 12), (18, 21), (27, 30)],
                };
                let seg =
                    |(a, b): (i32, i32)| PathElement::new(vec![(a, 0), (b, 0)], c.stroke_width(3));
                EmptyElement::at((x, y))
                    + seg(parts[0])
                    + seg(parts[1])
                    + seg(parts[2])
                    + seg(parts[3])
            });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(0xCC, 0xCC, 0xCC))
            .label_font(("sans-serif", 21))
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(text)
}
