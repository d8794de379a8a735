//! The curve options and rates from their Python spellings: the command line's names
//! (`"bezier"`, `"rest"`, `"as-given"`), and rates as numbers, strings or fractions.

use crate::input_error;
use inbetween::{CurveOptions, EndConditions, Ends, Fps, PathMode, Scheme};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt, PyString};

/// The curve options of a scheme, end rule and path by name, on minaccel's grid `grid_rate`,
/// with the default tangent rule ([`with_tangent`] sets another).
pub fn curve(scheme: &str, ends: &str, path: &str, grid_rate: Fps) -> PyResult<CurveOptions> {
    Ok(CurveOptions {
        scheme: self::scheme(scheme)?,
        path: self::path(path)?,
        ends: EndConditions::from(self::ends(ends)?),
        grid_rate,
        ..CurveOptions::default()
    })
}

/// `opts` with the tangent rule named `name` (spline, nam-kim), or the scheme's own.
pub fn with_tangent(opts: CurveOptions, name: Option<&str>) -> PyResult<CurveOptions> {
    let tangent = match name {
        Some(name) => Some(name.parse().map_err(|e: inbetween::InputError| {
            input_error(format!("tangent: {}", crate::message(&e)))
        })?),
        None => None,
    };
    Ok(CurveOptions { tangent, ..opts })
}

/// A scheme by name: hermite, squad, bezier, slerp, nlerp, minaccel.
pub fn scheme(name: &str) -> PyResult<Scheme> {
    name.parse()
        .map_err(|e: inbetween::InputError| input_error(format!("scheme: {}", crate::message(&e))))
}

/// An end rule by name: chord, rest, cyclic.
pub fn ends(name: &str) -> PyResult<Ends> {
    match name {
        "chord" => Ok(Ends::Chord),
        "rest" => Ok(Ends::Rest),
        "cyclic" => Ok(Ends::Cyclic),
        _ => Err(input_error(format!(
            "ends: expected chord, rest or cyclic, found {name:?}"
        ))),
    }
}

/// A path rule by name: shortest, as-given (Euler-angle turns need the angles, which arrays of
/// quaternions do not carry).
pub fn path(name: &str) -> PyResult<PathMode> {
    match name {
        "shortest" => Ok(PathMode::Shortest),
        "as-given" | "as_given" => Ok(PathMode::AsGiven),
        _ => Err(input_error(format!(
            "path: expected shortest or as-given, found {name:?}"
        ))),
    }
}

/// The frame rates are expressed in: `"world"` (the default, as the library gives them) or
/// `"body"` (each rate turned into the rotated body's own axes, R(q)ᵀ ω); `true` for body.
pub fn body_frame(name: Option<&str>) -> PyResult<bool> {
    match name {
        None | Some("world") => Ok(false),
        Some("body") => Ok(true),
        Some(other) => Err(input_error(format!(
            "frame: expected \"world\" or \"body\", found {}",
            crate::shown(other)
        ))),
    }
}

/// An integer argument (a Python or numpy integer, not a bool or a float): `Some` within `lo..=hi`,
/// `None` for any other integer, however large (the caller names its range); a `TypeError` for
/// anything else.
pub fn integer(what: &str, x: &Bound<'_, PyAny>, (lo, hi): (i64, i64)) -> PyResult<Option<i64>> {
    if x.is_instance_of::<pyo3::types::PyBool>() {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{what}: expected an integer, found a bool"
        )));
    }
    let index = x.call_method0("__index__").map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{what}: expected an integer, found {}",
            x.get_type()
                .name()
                .map_or_else(|_| "an object".into(), |n| n.to_string())
        ))
    })?;
    Ok(index
        .extract::<i64>()
        .ok()
        .filter(|v| (lo..=hi).contains(v)))
}

/// A frame rate: an int, a string the command line accepts (`"24"`, `"29.97"`, `"30000/1001"`),
/// a `fractions.Fraction` (anything with integer `numerator` and `denominator`), or a float
/// taken as the decimal it prints as (`59.9999885559082` is 599999885559082/10¹³ frames per
/// second, exactly; the NTSC decimals 23.976, 29.97, 59.94 mean their /1001 ratios, as on the
/// command line).
pub fn rate(what: &str, x: &Bound<'_, PyAny>) -> PyResult<Fps> {
    let located = |e: inbetween::InputError| input_error(format!("{what}: {}", crate::message(&e)));
    if x.is_instance_of::<pyo3::types::PyBool>() {
        return Err(input_error(format!(
            "{what}: expected a frame rate, found a bool"
        )));
    }
    if let Ok(s) = x.cast::<PyString>() {
        return Fps::parse(&s.to_cow()?).map_err(located);
    }
    if x.is_instance_of::<PyInt>() {
        let n: i128 = x.extract()?;
        let n = u64::try_from(n).map_err(|_| {
            input_error(format!("{what}: expected a positive frame rate, found {n}"))
        })?;
        return Fps::new(n, 1).map_err(located);
    }
    if x.is_instance_of::<PyFloat>() {
        return decimal_rate(x.extract()?).map_err(located);
    }
    if let (Ok(n), Ok(d)) = (x.getattr("numerator"), x.getattr("denominator"))
        && let (Ok(n), Ok(d)) = (n.extract::<u64>(), d.extract::<u64>())
    {
        return Fps::new(n, d).map_err(located);
    }
    Err(input_error(format!(
        "{what}: expected a frame rate (a number, a string such as \"30000/1001\", or a \
         Fraction), found {}",
        x.get_type().name()?
    )))
}

/// The rate `x` denotes as the shortest decimal that reads back to it: [`Fps::from_f64`] where
/// that decimal has at most 9 decimals (the command line's rule, NTSC included), else the
/// decimal itself as a ratio over a power of ten.
fn decimal_rate(x: f64) -> inbetween::error::InputResult<Fps> {
    if let Ok(fps) = Fps::from_f64(x) {
        return Ok(fps);
    }
    let text = format!("{x}");
    let exact = text.split_once('.').and_then(|(int, frac)| {
        let den = 10u64.checked_pow(u32::try_from(frac.len()).ok()?)?;
        let num = format!("{int}{frac}").parse::<u64>().ok()?;
        Some((num, den))
    });
    match exact {
        Some((num, den)) if x > 0.0 => Fps::new(num, den),
        _ => Fps::from_f64(x),
    }
}
