//! Banded symmetric positive-definite systems: Cholesky `A = L Lᵀ` in band storage, O(n·b²).
//!
//! Used by [`super::minaccel`], whose Gauss–Newton matrix is block-pentadiagonal with 3×3 blocks
//! (half-bandwidth 8). Written here rather than taken from a sparse crate: it is 60 lines, it
//! allocates once, and a general sparse factorisation would spend its time on symbolic analysis
//! of a structure we know.

/// A symmetric `n × n` matrix with half-bandwidth `b`, lower band stored row by row:
/// `data[i·(b+1) + (b − (i − j))] = A[i][j]` for `i − b ≤ j ≤ i`.
#[derive(Debug, Clone)]
pub(crate) struct Banded {
    n: usize,
    b: usize,
    data: Vec<f64>,
}

impl Banded {
    pub(crate) fn zeros(n: usize, b: usize) -> Self {
        Banded {
            n,
            b,
            data: vec![0.0; n * (b + 1)],
        }
    }

    /// Sets every entry to zero, keeping the allocation.
    pub(crate) fn clear(&mut self) {
        self.data.fill(0.0);
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        debug_assert!(j <= i && i - j <= self.b);
        i * (self.b + 1) + self.b - (i - j)
    }

    /// `A[i][j] += x` for `j ≤ i` (the lower triangle; the matrix is symmetric).
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, x: f64) {
        let k = self.at(i, j);
        self.data[k] += x;
    }

    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if j > i { (j, i) } else { (i, j) };
        if i - j > self.b {
            0.0
        } else {
            self.data[self.at(i, j)]
        }
    }

    /// Factorises in place into `L` (lower, same band). Returns false if the matrix is not
    /// positive definite (a pivot ≤ 0 or not finite).
    pub(crate) fn cholesky(&mut self) -> bool {
        let (n, b) = (self.n, self.b);
        for i in 0..n {
            let j0 = i.saturating_sub(b);
            for j in j0..=i {
                let k0 = j0.max(j.saturating_sub(b));
                let mut s = self.data[self.at(i, j)];
                for k in k0..j {
                    s -= self.data[self.at(i, k)] * self.data[self.at(j, k)];
                }
                if i == j {
                    if !(s > 0.0 && s.is_finite()) {
                        return false;
                    }
                    let k = self.at(i, i);
                    self.data[k] = s.sqrt();
                } else {
                    let k = self.at(i, j);
                    self.data[k] = s / self.data[self.at(j, j)];
                }
            }
        }
        true
    }

    /// Solves `L Lᵀ x = rhs` in place, after [`Banded::cholesky`].
    pub(crate) fn solve(&self, x: &mut [f64]) {
        let (n, b) = (self.n, self.b);
        for i in 0..n {
            let k0 = i.saturating_sub(b);
            let s: f64 = (k0..i)
                .zip(&x[k0..i])
                .map(|(k, xk)| self.data[self.at(i, k)] * xk)
                .sum();
            x[i] = (x[i] - s) / self.data[self.at(i, i)];
        }
        for i in (0..n).rev() {
            let k1 = (i + b + 1).min(n);
            let s: f64 = (i + 1..k1)
                .zip(&x[i + 1..k1])
                .map(|(k, xk)| self.data[self.at(k, i)] * xk)
                .sum();
            x[i] = (x[i] - s) / self.data[self.at(i, i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_banded_spd_system() {
        // A = tridiagonal-plus: 6 on the diagonal, −1 one off, 0.5 two off.
        let n = 40;
        let mut a = Banded::zeros(n, 2);
        for i in 0..n {
            a.add(i, i, 6.0);
            if i >= 1 {
                a.add(i, i - 1, -1.0);
            }
            if i >= 2 {
                a.add(i, i - 2, 0.5);
            }
        }
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let rhs: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a.get(i, j) * x_true[j]).sum())
            .collect();
        let mut x = rhs.clone();
        assert!(a.cholesky());
        a.solve(&mut x);
        for i in 0..n {
            assert!((x[i] - x_true[i]).abs() < 1e-14, "{i}");
        }
    }

    #[test]
    fn rejects_indefinite() {
        let mut a = Banded::zeros(2, 1);
        a.add(0, 0, 1.0);
        a.add(1, 0, 2.0);
        a.add(1, 1, 1.0);
        assert!(!a.cholesky());
    }
}
