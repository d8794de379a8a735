//! Lanes of 3-vectors for the tangents: [`V4`], four vectors as `wide::f64x4` lanes, and
//! [`Columns`], vectors in structure-of-arrays form from which four consecutive ones load as
//! lanes. Every operation is the IEEE operation glam's scalar code does, lane by lane.

use glam::DVec3;
use wide::f64x4;

/// Four 3-vectors as lanes.
#[derive(Clone, Copy)]
pub(super) struct V4 {
    pub(super) x: f64x4,
    pub(super) y: f64x4,
    pub(super) z: f64x4,
}

impl V4 {
    /// Zero in every lane.
    pub(super) const ZERO: V4 = V4 {
        x: f64x4::ZERO,
        y: f64x4::ZERO,
        z: f64x4::ZERO,
    };

    /// The lanes as vectors.
    pub(super) fn lanes(self) -> [DVec3; 4] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|l| DVec3::new(x[l], y[l], z[l]))
    }

    /// Lane-wise sum.
    pub(super) fn add(self, o: V4) -> V4 {
        V4 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    /// Lane-wise difference.
    pub(super) fn sub(self, o: V4) -> V4 {
        V4 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    /// Each lane's vector times its lane of `k`.
    pub(super) fn mul(self, k: f64x4) -> V4 {
        V4 {
            x: self.x * k,
            y: self.y * k,
            z: self.z * k,
        }
    }

    /// Each lane's vector over its lane of `k`.
    pub(super) fn div(self, k: f64x4) -> V4 {
        V4 {
            x: self.x / k,
            y: self.y / k,
            z: self.z / k,
        }
    }

    /// The vectors negated (a sign flip, as glam's `-v`).
    pub(super) fn neg(self) -> V4 {
        V4 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// glam's `length`: `√((x·x + y·y) + z·z)`.
    pub(super) fn length(self) -> f64x4 {
        (self.x * self.x + self.y * self.y + self.z * self.z).sqrt()
    }

    /// `if_true`'s lane where `mask` is set, else this one's.
    pub(super) fn or_where(self, mask: f64x4, if_true: V4) -> V4 {
        V4 {
            x: mask.select(if_true.x, self.x),
            y: mask.select(if_true.y, self.y),
            z: mask.select(if_true.z, self.z),
        }
    }
}

/// Vectors in structure-of-arrays form, so that four consecutive ones load as lanes.
#[derive(Debug, Clone, Default)]
pub(super) struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Columns {
    /// No vector yet, room for `n`.
    pub(super) fn with_capacity(n: usize) -> Columns {
        Columns {
            x: Vec::with_capacity(n),
            y: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
        }
    }

    /// Appends the four lanes of `v`.
    #[inline]
    pub(super) fn push4(&mut self, v: V4) {
        self.x.extend_from_slice(&v.x.to_array());
        self.y.extend_from_slice(&v.y.to_array());
        self.z.extend_from_slice(&v.z.to_array());
    }

    /// Sets vector `i` to zero.
    pub(super) fn set_zero(&mut self, i: usize) {
        (self.x[i], self.y[i], self.z[i]) = (0.0, 0.0, 0.0);
    }

    /// The columns of `v`.
    pub(super) fn of(v: &[DVec3]) -> Columns {
        Columns {
            x: v.iter().map(|v| v.x).collect(),
            y: v.iter().map(|v| v.y).collect(),
            z: v.iter().map(|v| v.z).collect(),
        }
    }

    /// Whether there is no vector.
    pub(super) fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Vector `i`.
    #[inline]
    pub(super) fn get(&self, i: usize) -> DVec3 {
        DVec3::new(self.x[i], self.y[i], self.z[i])
    }

    /// Vectors `from‥from+len`, as columns borrowed.
    #[inline]
    pub(super) fn window(&self, from: usize, len: usize) -> Window<'_> {
        let to = from + len;
        Window {
            x: &self.x[from..to],
            y: &self.y[from..to],
            z: &self.z[from..to],
        }
    }
}

/// Part of [`Columns`], borrowed.
#[derive(Clone, Copy)]
pub(super) struct Window<'c> {
    x: &'c [f64],
    y: &'c [f64],
    z: &'c [f64],
}

impl Window<'_> {
    /// Vectors `i‥i+3` of the window as lanes.
    #[inline]
    pub(super) fn lanes(self, i: usize) -> V4 {
        V4 {
            x: load(self.x, i),
            y: load(self.y, i),
            z: load(self.z, i),
        }
    }
}

/// `v[i‥i+3]` as lanes.
#[inline]
pub(super) fn load(v: &[f64], i: usize) -> f64x4 {
    let four: [f64; 4] = v[i..i + 4].try_into().expect("four values");
    f64x4::new(four)
}
