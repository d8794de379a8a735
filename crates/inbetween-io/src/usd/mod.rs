//! USD: a skeleton's motion written as `.usda` text ([`mod@write`], [`frames`], [`keys`]), a UsdSkel
//! `Skeleton` with its `SkelAnimation`, and read back ([`read`], on the text syntax of `text`).

pub mod frames;
pub mod keys;
mod lex;
pub mod read;
pub(crate) mod text;
pub mod write;
