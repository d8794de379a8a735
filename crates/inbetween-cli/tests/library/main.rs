//! The library API's tests: conventions against scipy tables, the crate-root API against the
//! binary, minaccel against its dense reference, and property tests of the curves.

#[path = "../support/mod.rs"]
mod support;

mod api;
mod conventions;
mod minaccel;
mod properties;
mod reduce;
mod spins;
mod tangents;
mod unwrap;
