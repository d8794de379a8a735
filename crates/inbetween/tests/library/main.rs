//! The library API's tests: conventions against scipy tables, the crate-root API as an engine
//! uses it, minaccel against its dense reference, and property tests of the curves. (The
//! crate-root API against the binary's output is in crates/inbetween-cli/tests/binary/api.rs;
//! minaccel's energy on the interp fixtures, which reads them, in
//! crates/inbetween-io/tests/minaccel_fixtures.rs.)

mod support;

mod api;
mod conventions;
mod minaccel;
mod properties;
mod reduce;
mod spins;
mod tangents;
mod unwrap;
