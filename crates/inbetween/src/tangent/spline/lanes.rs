//! The `spline` tangent of four consecutive interior keys at once, as SIMD lanes.
//!
//! Most keys of a dense track have the plain window of [`Windows::tangent`]: seven keys, none
//! cut by an end or a loop's seam, no chords summing past the half-turn rule, no spin. For four
//! such keys in a row the window's not-a-knot solve ([`super::slope`] with seven
//! points, the key in the middle) and the limit to Nam & Kim's tangent run here with one key
//! per lane (`wide::f64x4`), operation for operation as the scalar code does them — additions,
//! products, quotients and square roots are exact IEEE operations in either form — so each lane
//! is the scalar tangent's bits (tested). Any other key is done by [`Windows::tangent`].

use super::{REACH, TIE, Windows};
use crate::tangent::columns::{V4, load};
use glam::DVec3;
use std::f64::consts::PI;
use wide::f64x4;

impl Windows<'_> {
    /// Whether key `i` has the plain window (module documentation): the same tests, in the same
    /// arithmetic, by which [`Windows::tangent`] would leave that path (`plain4`'s reference).
    #[cfg(test)]
    fn plain(&self, i: usize) -> bool {
        let n = self.quats.len();
        if !self.has_far() || i < REACH || i + REACH >= n {
            return false;
        }
        let l = &self.lengths;
        if l[i - 1] + l[i] >= PI - TIE {
            return false;
        }
        let within = |a: usize, b: usize, c: usize| {
            // Lengths are finite: `<=` is the scalar path's `!(len > π − TIE)`.
            let two = 0.0 + l[a] + l[b];
            two <= PI - TIE && two + l[c] <= PI - TIE
        };
        within(i - 1, i - 2, i - 3) && within(i, i + 1, i + 2)
    }

    /// Whether keys `i‥i+3` all have the plain window: the tests of `plain` (the scalar reference,
    /// kept for the tests), one key per lane, in the same arithmetic (the same answer, tested).
    fn plain4(&self, i: usize) -> bool {
        let n = self.quats.len();
        if !self.has_far() || i < REACH || i + 3 + REACH >= n {
            return false;
        }
        // Lengths of segments i − 3 + k, lane l at key i + l (all within the track: i + 6 < n).
        let lengths = &self.lengths[i - 3..i + 6];
        let l: [f64x4; 2 * REACH] = std::array::from_fn(|k| load(lengths, k));
        let bound = f64x4::splat(PI - TIE);
        // The scalar test leaves when `l[i−1] + l[i] >= π − TIE`.
        if (l[2] + l[3]).simd_ge(bound).any() {
            return false;
        }
        let zero = f64x4::ZERO;
        let (back, ahead) = (zero + l[2] + l[1], zero + l[3] + l[4]);
        (back.simd_le(bound)
            & (back + l[0]).simd_le(bound)
            & ahead.simd_le(bound)
            & (ahead + l[5]).simd_le(bound))
        .all()
    }

    /// The `spline` tangents of keys `from‥from + out.len()` into `out`: four at a time where
    /// the four have the plain window, else one by [`Windows::tangent`] (its bits either way).
    pub(in crate::tangent) fn fill(&self, from: usize, out: &mut [DVec3]) {
        let mut k = 0;
        while k < out.len() {
            let i = from + k;
            if let Some(four) = (k + 4 <= out.len()).then(|| self.tangent4(i)).flatten() {
                out[k..k + 4].copy_from_slice(&four.lanes());
                k += 4;
            } else {
                out[k] = self.tangent(i);
                k += 1;
            }
        }
    }

    /// The tangents of keys `i‥i+3` (lane `l` key `i + l`) when all four have the plain window,
    /// else `None`.
    pub(super) fn tangent4(&self, i: usize) -> Option<V4> {
        if !self.plain4(i) {
            return None;
        }
        // Every load below is of keys or segments `i − 3‥i + 6`, which the plain windows of
        // keys `i‥i+3` hold.
        // Each column cut once to the part read (one bounds test, not one per load).
        let far2 = self.far[0].window(i - 2, 6);
        let far3 = self.far[1].window(i - 3, 7);
        let chords = self.chord_columns.window(i - 1, 5);
        let y = [
            far3.lanes(0).neg(),
            far2.lanes(0).neg(),
            chords.lanes(0).neg(),
            V4::ZERO,
            chords.lanes(1),
            far2.lanes(2),
            far3.lanes(3),
        ];
        // h[p] = t[i − 3 + p + 1] − t[i − 3 + p], lane l at key i + l.
        let times = &self.times[i - 3..i + 7];
        let t: [f64x4; 2 * REACH + 1] = std::array::from_fn(|p| load(times, p));
        let h: [f64x4; 2 * REACH] = std::array::from_fn(|p| t[p + 1] - t[p]);
        let w = slope7(&h, &y);
        // The limit, as `Windows::tangent` takes it: the span is (t[i] − t[i−1]) + (t[i+1] − t[i]).
        let span = h[2] + h[3];
        let nk = far2.lanes(1).div(span);
        let c = w.sub(nk);
        let room = f64x4::splat(0.5) * nk.length();
        let off = c.length();
        let limited = nk.add(c.mul(room / off));
        Some(w.or_where(off.simd_gt(room), limited))
    }
}

/// The tangents of a track's keys asked for in increasing order: four at a time where the four
/// keys have the plain window, else one by [`Windows::tangent`].
pub(in crate::tangent) struct InOrder<'w, 'a> {
    windows: &'w Windows<'a>,
    /// Keys `from‥from + len` are in `block`.
    from: usize,
    len: usize,
    block: [DVec3; 4],
}

impl<'w, 'a> InOrder<'w, 'a> {
    pub(in crate::tangent) fn new(windows: &'w Windows<'a>) -> Self {
        InOrder {
            windows,
            from: 0,
            len: 0,
            block: [DVec3::ZERO; 4],
        }
    }

    /// The `spline` tangent of key `i` (the bits of [`Windows::tangent`]).
    pub(in crate::tangent) fn get(&mut self, i: usize) -> DVec3 {
        if (self.from..self.from + self.len).contains(&i) {
            return self.block[i - self.from];
        }
        match self.windows.tangent4(i) {
            Some(block) => {
                let block = block.lanes();
                (self.from, self.len, self.block) = (i, 4, block);
                block[0]
            }
            None => {
                self.len = 0;
                self.windows.tangent(i)
            }
        }
    }
}

/// [`super::slope`] for seven points and the middle one, in lanes, with its operations
/// in its order.
#[inline(always)]
fn slope7(h: &[f64x4; 6], y: &[V4; 7]) -> V4 {
    let one = f64x4::ONE;
    let d: [V4; 6] = std::array::from_fn(|k| y[k + 1].sub(y[k]).mul(one / h[k]));
    let three = f64x4::splat(3.0);
    let two = f64x4::splat(2.0);
    let mut b = [V4::ZERO; 7];
    for k in 1..6 {
        b[k] = d[k - 1].mul(h[k]).add(d[k].mul(h[k - 1])).mul(three);
    }
    let (h0, h1) = (h[0], h[1]);
    b[0] = d[0]
        .mul((h0 + two * (h0 + h1)) * h1)
        .add(d[1].mul(h0 * h0))
        .div(h0 + h1);
    let (ha, hb) = (h[4], h[5]);
    b[6] = d[4]
        .mul(hb * hb)
        .add(d[5].mul((two * (ha + hb) + hb) * ha))
        .div(ha + hb);
    let zero = f64x4::ZERO;
    let rows: [(f64x4, f64x4, f64x4, V4); 5] = [
        (zero, h0 + h1, h0, b[1].sub(b[0])),
        (h[2], two * (h[1] + h[2]), h[1], b[2]),
        (h[3], two * (h[2] + h[3]), h[2], b[3]),
        (h[4], two * (h[3] + h[4]), h[3], b[4]),
        (hb, ha + hb, zero, b[5].sub(b[6])),
    ];
    let (mut cp, mut dp) = ([zero; 5], [V4::ZERO; 5]);
    for (r, &(sub, diag, sup, rhs)) in rows.iter().enumerate() {
        let (c_prev, d_prev) = if r == 0 {
            (zero, V4::ZERO)
        } else {
            (cp[r - 1], dp[r - 1])
        };
        let inv = one / (diag - sub * c_prev);
        cp[r] = sup * inv;
        dp[r] = rhs.sub(d_prev.mul(sub)).mul(inv);
    }
    let mut s = dp[4];
    for r in [3, 2] {
        s = dp[r].sub(s.mul(cp[r]));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::quat::exp;
    use glam::DQuat;

    fn bits(v: DVec3) -> [u64; 3] {
        v.to_array().map(f64::to_bits)
    }

    /// Every lane is the scalar tangent's bits, on uneven keys of a smooth motion, beside a hold
    /// (where the limit acts) and near spins (where the plain window ends).
    #[test]
    fn lanes_are_the_scalar_tangents_bits() {
        let n = 64;
        let mut times = vec![0.0];
        for k in 1..n {
            let h = 0.01 + 0.004 * ((k * 7) % 5) as f64;
            times.push(times[k - 1] + h);
        }
        let quats: Vec<DQuat> = (0..n)
            .map(|k| {
                let x = times[k];
                let v = match k {
                    20..=24 => DVec3::new(0.3, 0.1, 0.2), // a hold
                    40..=42 => DVec3::new(0.0, 0.0, 0.8 * (k - 40) as f64), // fast steps
                    _ => DVec3::new(0.6 * (2.0 * x).sin(), 0.4 * (5.0 * x).cos(), x),
                };
                exp(v)
            })
            .collect();
        let chords: Vec<DVec3> = quats
            .windows(2)
            .map(|q| crate::rotation::quat::log(q[1] * q[0].conjugate()))
            .collect();
        let keys = crate::tangent::logs::Keys::of(&quats);
        let w = Windows::new(&times, &quats, &keys, &chords, false);
        let (mut lanes, mut limited) = (0, 0);
        for i in 1..n - 4 {
            if let Some(four) = w.tangent4(i) {
                lanes += 1;
                for (l, &got) in four.lanes().iter().enumerate() {
                    assert_eq!(bits(got), bits(w.tangent(i + l)), "key {}", i + l);
                }
            }
            assert_eq!(w.plain4(i), (0..4).all(|l| w.plain(i + l)), "key {i}");
            if w.plain(i) {
                // The limit acted: the tangent is at half Nam & Kim's length from it.
                let nk =
                    w.far[0].get(i - 1) / ((times[i] - times[i - 1]) + (times[i + 1] - times[i]));
                let off = (w.tangent(i) - nk).length();
                if nk.length() > 0.0 && (off - 0.5 * nk.length()).abs() <= 1e-12 * nk.length() {
                    limited += 1;
                }
            }
        }
        println!("{lanes} blocks in lanes, the limit at {limited} keys");
        assert!(lanes > 30, "{lanes} blocks in lanes");
        assert!(limited > 0, "no key where the limit acts");
    }
}
