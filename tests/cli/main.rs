//! One integration target: conventions against scipy tables, the binary's golden files, error
//! messages, and property tests.

mod analyze;
mod conventions;
mod errors;
mod golden;
mod hard_cases;
mod minaccel;
mod plot;
mod properties;
mod reliability;
mod roundtrip;
mod support;
