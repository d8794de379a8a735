//! One module per subcommand: validated settings from the parsed arguments, then the library.

pub mod analyze;
pub mod batch;
pub mod convert;
pub mod diff;
pub mod interp;
pub mod plot;
pub mod reduce;
pub mod settings;
pub mod skeleton;
