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

/// The portable extension module, `inbetween._inbetween` (baseline x86-64: SSE2).
#[cfg(not(feature = "avx2"))]
#[pymodule]
fn _inbetween(m: &Bound<'_, PyModule>) -> PyResult<()> {
    register(m)
}

/// The same module compiled for AVX2 without FMA, `inbetween._inbetween_avx2`
/// (tools/wheel/build.sh; the package imports it where [`cpu_has_avx2`] says the CPU runs it).
/// No operation is fused or reordered by the wider lanes, so its results are the portable
/// module's bits (tested: crates/inbetween-py/tests/test_simd.py).
#[cfg(feature = "avx2")]
#[pymodule]
fn _inbetween_avx2(m: &Bound<'_, PyModule>) -> PyResult<()> {
    register(m)
}

fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
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
    m.add_function(wrap_pyfunction!(cpu_has_avx2, m)?)?;
    Ok(())
}

/// Whether this CPU runs `_inbetween_avx2`: every feature that module is compiled with
/// (tools/wheel/build.sh `AVX2_FEATURES`), as the operating system reports them.
#[pyfunction]
fn cpu_has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("avx")
            && std::arch::is_x86_feature_detected!("sse4.2")
            && std::arch::is_x86_feature_detected!("sse4.1")
            && std::arch::is_x86_feature_detected!("ssse3")
            && std::arch::is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}
