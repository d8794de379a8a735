//! `import inbetween`: the Python binding of the `inbetween` crate (docs/python.md). The
//! extension module `inbetween._inbetween` holds the compiled functions and classes; the Python
//! package `inbetween` (python/inbetween) turns its arguments into float64 arrays (scipy
//! `Rotation` objects included) and gives the documented signatures.
//!
//! - [`curve`]: `Curve`, one curve per joint through keys (K, 4) or (K, J, 4).
//! - [`resample`]: `resample` and `frame_times`, dense frames onto another exact rate.
//! - [`reduce`]: `reduce`, the fewest keys within a tolerance, verified on every frame.
//! - [`read`]: `read`, any file the command line reads, as tracks of arrays.
//! - [`write`]: `write`, tracks of arrays as CSV, JSON, npy, npz, BVH on a skeleton, or glTF
//!   written into the asset they were read from ([`gltf`]).
//! - [`batch`]: `process_file`, one command of the command line on one file (for Dask, joblib,
//!   Ray).
//! - [`arrays`]: numpy arrays in and out, shapes checked with messages naming the argument.
//! - [`options`]: schemes, end rules, paths and rates from their Python spellings.

use pyo3::prelude::*;

mod arrays;
mod batch;
mod curve;
mod frames;
mod gltf;
mod options;
mod read;
mod reduce;
mod resample;
mod rot6d;
mod write;

pyo3::create_exception!(
    _inbetween,
    InputError,
    pyo3::exceptions::PyValueError,
    "Input that inbetween refuses: a shape, a value or a rate, with the library's message."
);

/// The library's message with each setting it names as this package's keyword (`rotation`,
/// `key_fps`, …), never a command-line flag.
pub(crate) fn message(e: &inbetween::InputError) -> String {
    use inbetween::error::Setting;
    e.parts().render(|s| match s {
        Setting::Scheme => "scheme",
        Setting::FrameRate => "fps_out",
        Setting::KeyRate => "key_fps",
        Setting::Rotation => "rotation",
        Setting::InputAngles => "angles",
        Setting::SharedKeys => "shared_keys",
        Setting::Animation => "animation",
        Setting::Skeleton => "skeleton",
        Setting::MaxInputBytes => "max_bytes",
    })
}

/// A user's text in a message: control characters escaped, at most 100 characters quoted.
pub(crate) fn shown(text: &str) -> String {
    let escaped: String = text.chars().flat_map(char::escape_debug).collect();
    format!("\"{}\"", inbetween::error::shorten(&escaped))
}

/// An [`InputError`] with `message`.
pub(crate) fn input_error(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}

/// A library error as Python raises it: the user's input an [`InputError`], I/O an `OSError`, a
/// failed internal check a `RuntimeError`.
pub(crate) fn error(e: inbetween::Error) -> PyErr {
    match e {
        inbetween::Error::Input(e) => input_error(message(&e)),
        inbetween::Error::Io(e) => e.into(),
        inbetween::Error::Internal(m) => pyo3::exceptions::PyRuntimeError::new_err(m),
    }
}

#[pymodule]
fn _inbetween(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    // The package's version: the crate's, which pyproject.toml repeats.
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<curve::Curve>()?;
    m.add_function(wrap_pyfunction!(resample::resample, m)?)?;
    m.add_function(wrap_pyfunction!(resample::frame_times, m)?)?;
    m.add_function(wrap_pyfunction!(rot6d::rot6d, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::reduce, m)?)?;
    m.add_function(wrap_pyfunction!(read::read, m)?)?;
    m.add_function(wrap_pyfunction!(write::write, m)?)?;
    m.add_function(wrap_pyfunction!(batch::process_file, m)?)?;
    Ok(())
}
