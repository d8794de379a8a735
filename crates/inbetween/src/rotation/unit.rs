//! The unit of angles read and written: degrees or radians.

use crate::error::{InputResult, input_err};

/// Unit of every angle read or written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AngleUnit {
    /// Degrees.
    #[default]
    Deg,
    /// Radians.
    Rad,
}

impl AngleUnit {
    /// `deg` or `rad`.
    pub fn parse(s: &str) -> InputResult<AngleUnit> {
        match s {
            "deg" => Ok(AngleUnit::Deg),
            "rad" => Ok(AngleUnit::Rad),
            _ => Err(input_err!("expected \"deg\" or \"rad\", found \"{s}\"")),
        }
    }

    /// `deg` or `rad`.
    pub fn as_str(self) -> &'static str {
        match self {
            AngleUnit::Deg => "deg",
            AngleUnit::Rad => "rad",
        }
    }

    /// An angle in this unit, in radians.
    pub fn to_rad(self, a: f64) -> f64 {
        match self {
            AngleUnit::Deg => a.to_radians(),
            AngleUnit::Rad => a,
        }
    }

    /// An angle in radians, in this unit.
    pub fn from_rad(self, a: f64) -> f64 {
        match self {
            AngleUnit::Deg => a.to_degrees(),
            AngleUnit::Rad => a,
        }
    }
}
