//! `resample` and `frame_times`: dense frames at one exact rate onto another, as `interp`
//! writes them (every input frame a key, the output frames those of the exact output grid
//! inside the clip's span, baked by the library's [`inbetween::bake`]).

use crate::arrays::{self, quat_row};
use crate::curve::curve_error;
use crate::{input_error, options};
use glam::{DQuat, DVec3};
use inbetween::{BakeOptions, Fps, FrameSink};
use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// The times of the frames `resample` writes for `n` input frames at `fps_in` onto `fps_out`:
/// `k/fps_out` for every `k` from 0 to `⌊(n − 1)/fps_in · fps_out⌋` (within 1e-9 s, the frame
/// clock's rule), exact rationals rounded once.
#[pyfunction]
pub fn frame_times<'py>(
    py: Python<'py>,
    n: Bound<'py, PyAny>,
    fps_in: Bound<'py, PyAny>,
    fps_out: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let Some(n) = crate::options::integer("n", &n, (i64::MIN, i64::MAX))? else {
        return Err(input_error(format!(
            "n: expected at least one frame and at most 2^63 - 1, found {}",
            n.str()?
        )));
    };
    if n < 1 {
        return Err(input_error(format!(
            "n: expected at least one frame, found {n}"
        )));
    }
    // At most i64::MAX: a usize on every platform a wheel is built for.
    let n = usize::try_from(n).unwrap_or(usize::MAX);
    let (fps_in, fps_out) = (
        options::rate("fps_in", &fps_in)?,
        options::rate("fps_out", &fps_out)?,
    );
    let (a, b) = grid(n, fps_in, fps_out)?;
    fits(b - a + 1, 1)?;
    let times: Vec<f64> = (a..=b).map(|k| fps_out.time_of(k)).collect();
    Ok(numpy::PyArray1::from_vec(py, times))
}

/// The most numbers a result of `resample` or `frame_times` may hold: 2²⁸ (2 GiB of float64),
/// so that a grid too large for memory is a `ValueError` before anything is allocated, never
/// an allocation failure that aborts the interpreter.
pub const MAX_VALUES: i64 = 1 << 28;

/// An error unless `frames` frames of `per_frame` numbers each fit in [`MAX_VALUES`].
fn fits(frames: i64, per_frame: i64) -> PyResult<()> {
    let values = frames.saturating_mul(per_frame);
    if frames < 0 || values > MAX_VALUES {
        return Err(input_error(format!(
            "the result would hold {frames} frames of {per_frame} numbers, more than the \
             {MAX_VALUES} numbers (2 GiB of float64) a result may hold: resample a shorter \
             span, fewer joints or a lower rate"
        )));
    }
    Ok(())
}

/// The output frames `(first, last)` for `n` input frames.
fn grid(n: usize, fps_in: Fps, fps_out: Fps) -> PyResult<(i64, i64)> {
    if n == 0 {
        return Err(input_error("n: expected at least one frame, found 0"));
    }
    let last = i64::try_from(n - 1).unwrap_or(i64::MAX);
    let end = fps_in.time_of(last);
    if !fps_out.in_range(end) || !fps_in.in_range(end) {
        return Err(input_error(format!(
            "{n} frames at {fps_in} fps span {end} s, beyond what the frame clock supports"
        )));
    }
    Ok(fps_out.frames_between(0.0, end))
}

/// Where a joint's baked frames go: straight into the (M, J, C) output arrays, row `(m, j)`
/// of each, in the caller's quaternion order.
struct Rows<'a> {
    rotations: &'a Out,
    velocities: Option<&'a Out>,
    /// The positions, for a track with translations.
    positions: Option<&'a Out>,
    joint: usize,
    joints: usize,
    frames: usize,
    /// The next frame's row.
    m: usize,
    scalar_first: bool,
    /// Angular velocities in the body's axes (`frame="body"`), else the world's.
    body: bool,
}

/// A float64 output array's data, written by the workers at rows no two of them share (each
/// joint's rows by the one worker that bakes it).
struct Out {
    data: *mut f64,
    len: usize,
}

// SAFETY: the array is new and not yet handed to Python; each worker writes only the rows of
// the joint it bakes, and `Out::write` checks the bounds.
unsafe impl Send for Out {}
unsafe impl Sync for Out {}

impl Out {
    fn of(a: &Bound<'_, PyArrayDyn<f64>>) -> Out {
        Out {
            // A new C-contiguous array of `len()` elements, alive while it is written.
            data: a.data(),
            len: a.len(),
        }
    }

    /// Row `at` of `C` numbers.
    #[inline]
    fn write<const C: usize>(&self, at: usize, row: [f64; C]) {
        assert!((at + 1) * C <= self.len, "a row beyond the output array");
        // SAFETY: in bounds (checked above); no other thread writes this row (see `Out`).
        unsafe { std::ptr::write(self.data.add(at * C).cast::<[f64; C]>(), row) }
    }
}

impl Rows<'_> {
    /// The row of the frame to come, or an error past the grid's last frame.
    #[inline]
    fn at(&self) -> std::io::Result<usize> {
        match self.m < self.frames {
            true => Ok(self.m * self.joints + self.joint),
            false => Err(std::io::Error::other("a frame beyond the output grid")),
        }
    }
}

impl FrameSink for Rows<'_> {
    #[inline]
    fn frame(&mut self, _k: i64, _t: f64, q: DQuat, omega: Option<DVec3>) -> std::io::Result<()> {
        let at = self.at()?;
        self.rotations.write(at, quat_row(q, self.scalar_first));
        if let (Some(out), Some(w)) = (self.velocities, omega) {
            let w = if self.body {
                crate::curve::body_rate(q, w)
            } else {
                w
            };
            out.write(at, w.to_array());
        }
        self.m += 1;
        Ok(())
    }

    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> std::io::Result<()> {
        if let Some(out) = self.positions {
            out.write(self.at()?, position.to_array());
        }
        self.frame(k, time, q, omega)
    }
}

/// Why a joint was not baked.
enum Refused {
    /// Its keys (the track).
    Track(inbetween::TrackError),
    /// Its curve.
    Curve(inbetween::InputError),
    /// The bake (the sink's error).
    Bake(std::io::Error),
}

/// Frames `rotations` (T, 4) or (T, J, 4) at `fps_in` resampled onto `fps_out`: (M, 4) or
/// (M, J, 4), M = ⌊(T − 1)/fps_in · fps_out⌋ + 1 frames; with `velocity`, also the angular
/// velocities (M, 3) or (M, J, 3), rad/s, world frame (`frame="body"`: the body's axes); with
/// `translations` (T, 3) or (T, J, 3), also the positions at the new frames (M, 3) or (M, J, 3),
/// last in the tuple, as `interp` writes a track's translations.
#[pyfunction]
#[pyo3(signature = (
    rotations, fps_in, fps_out, *, scheme = "bezier", ends = "chord", path = "shortest",
    scalar_first = true, velocity = false, frame = None, translations = None, tangent = None
))]
#[allow(clippy::too_many_arguments)]
pub fn resample<'py>(
    py: Python<'py>,
    rotations: PyReadonlyArrayDyn<'py, f64>,
    fps_in: Bound<'py, PyAny>,
    fps_out: Bound<'py, PyAny>,
    scheme: &str,
    ends: &str,
    path: &str,
    scalar_first: bool,
    velocity: bool,
    frame: Option<&str>,
    translations: Option<PyReadonlyArrayDyn<'py, f64>>,
    tangent: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let body = options::body_frame(frame)?;
    let (fps_in, fps_out) = (
        options::rate("fps_in", &fps_in)?,
        options::rate("fps_out", &fps_out)?,
    );
    // The keys are read in place, one joint at a time, as each joint is baked: checked first
    // (the same errors and warning as `arrays::quats`, in the same order).
    let view = rotations.as_array();
    let layout = arrays::layout_of(&view, "rotations", 4)?;
    let data = arrays::standard(&view);
    let quats = arrays::Flat {
        data: &data,
        layout,
        width: 4,
    };
    arrays::check_quats(py, quats, "rotations", scalar_first)?;
    let p_view = translations.as_ref().map(|p| p.as_array());
    let p_data = p_view.as_ref().map(arrays::standard);
    let positions = match (&p_view, &p_data) {
        (Some(v), Some(d)) => {
            let p = arrays::Flat {
                data: d,
                layout,
                width: 3,
            };
            arrays::check_vectors(v, p, "translations", "rotations")?;
            Some(p)
        }
        _ => None,
    };
    let (first, last) = grid(layout.rows, fps_in, fps_out)?;
    let joints = layout.joints.unwrap_or(1);
    let width = 4 + if velocity { 3 } else { 0 } + if positions.is_some() { 3 } else { 0 };
    fits(last - first + 1, joints as i64 * width)?;
    // No joints, no frames: (0, 0, C), as the rows were counted from the first joint's.
    let frames = match joints {
        0 => 0,
        _ => usize::try_from(last - first + 1).unwrap_or(0),
    };
    let times: Vec<f64> = (0..layout.rows as i64).map(|k| fps_in.time_of(k)).collect();
    let opts = options::with_tangent(options::curve(scheme, ends, path, fps_out)?, tangent)?;
    // The output arrays, allocated once (zeros: pages the kernel maps as they are written).
    let shape = |c: usize| match layout.joints {
        None => vec![frames, c],
        Some(j) => vec![frames, j, c],
    };
    let new = |c: usize| PyArrayDyn::<f64>::zeros(py, IxDyn(&shape(c)), false);
    let out = new(4);
    let w = velocity.then(|| new(3));
    let p = positions.map(|_| new(3));
    let (out_q, out_w, out_p) = (
        Out::of(&out),
        w.as_ref().map(Out::of),
        p.as_ref().map(Out::of),
    );
    let bake = BakeOptions {
        velocity,
        parallel: false,
    };
    // Each joint on the cores without the GIL: its keys read, its track and curve built, its
    // frames baked into the arrays, then dropped (one joint's curve alive per core).
    let per_joint: Vec<usize> = (0..if frames == 0 { 0 } else { joints }).collect();
    let done = py.detach(|| {
        inbetween::parallel::map(&per_joint, |&j| {
            let keys = arrays::joint_quats(quats, j, scalar_first)
                .map_err(|e| Refused::Bake(std::io::Error::other(e)))?;
            let track = arrays::track(&times, keys);
            let track = match positions {
                Some(p) => track.and_then(|t| t.with_translations(arrays::joint_vectors(p, j))),
                None => track,
            };
            let track = track.map_err(Refused::Track)?;
            let curve = inbetween::Curve::new(&track, &opts).map_err(Refused::Curve)?;
            drop(track);
            let mut sink = Rows {
                rotations: &out_q,
                velocities: out_w.as_ref(),
                positions: out_p.as_ref(),
                joint: j,
                joints,
                frames,
                m: 0,
                scalar_first,
                body,
            };
            inbetween::bake(&curve, fps_out, bake, &mut sink, &mut |_| {})
                .map_err(Refused::Bake)?;
            match sink.m == frames {
                true => Ok(()),
                false => Err(Refused::Bake(std::io::Error::other(format!(
                    "{} frames baked for a grid of {frames}",
                    sink.m
                )))),
            }
        })
    });
    // Errors as when every track was built before any curve: the first joint whose keys are
    // refused, else the first whose curve is, else the first bake's.
    let located = |j: usize, what: &str| match layout.joints {
        Some(_) => format!("{what} (joint {j})"),
        None => what.to_string(),
    };
    let failed = |f: fn(&Refused) -> bool| {
        done.iter()
            .enumerate()
            .find(|(_, d)| d.as_ref().is_err_and(f))
    };
    if let Some((j, Err(Refused::Track(e)))) = failed(|r| matches!(r, Refused::Track(_))) {
        return Err(input_error(format!("{}: {e}", located(j, "rotations"))));
    }
    if let Some((j, Err(Refused::Curve(e)))) = failed(|r| matches!(r, Refused::Curve(_))) {
        return Err(curve_error(j, e, layout));
    }
    if let Some((_, Err(Refused::Bake(e)))) = failed(|r| matches!(r, Refused::Bake(_))) {
        return Err(pyo3::exceptions::PyRuntimeError::new_err(e.to_string()));
    }
    match (w, p) {
        (None, None) => Ok(out.into_any()),
        (None, Some(p)) => Ok((out, p).into_pyobject(py)?.into_any()),
        (Some(w), None) => Ok((out, w).into_pyobject(py)?.into_any()),
        (Some(w), Some(p)) => Ok((out, w, p).into_pyobject(py)?.into_any()),
    }
}
