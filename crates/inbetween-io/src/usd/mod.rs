//! USD: a skeleton's motion written as `.usda` text ([`mod@write`], [`frames`], [`keys`]), a UsdSkel
//! `Skeleton` with its `SkelAnimation`, and read back ([`read`]) from text (`text`) or binary
//! (`binary`: usdc by openusd, usdz; `bounds` checks a crate's claims first).

mod binary;
mod bounds;
pub mod frames;
pub mod keys;
mod lex;
pub mod read;
pub(crate) mod text;
pub mod write;

/// Whether undeclared, unnamed bytes (standard input) are binary USD: a usdc crate's magic
/// `PXR-USDC`, or a zip whose first entry (by its local header) is a USD layer, as a usdz
/// package's root layer is (an `.npz` holds `.npy` entries).
pub fn is_binary_usd(bytes: &[u8]) -> bool {
    if binary::is_crate(bytes) {
        return true;
    }
    if !binary::is_zip(bytes) || bytes.len() < 30 {
        return false;
    }
    let n = usize::from(u16::from_le_bytes([bytes[26], bytes[27]]));
    bytes.get(30..30 + n).is_some_and(|name| {
        let name = String::from_utf8_lossy(name).to_ascii_lowercase();
        [".usdc", ".usda", ".usd"].iter().any(|e| name.ends_with(e))
    })
}
