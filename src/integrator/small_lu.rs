//! LU with partial pivoting for the small dense systems of the partitioned integrator
//! (4 x 4 constraint blocks, n x n reduced mass matrices with n of a few modes), on a buffer
//! sized once: plain loops, no per-call setup (Golub and Van Loan, *Matrix Computations*,
//! 4th ed., algorithm 3.4.1). A general library's LU costs several times more at these sizes.

/// An `n x n` matrix (row-major) factored in place as `P A = L U`.
#[derive(Clone, Debug)]
pub struct SmallLu {
    n: usize,
    /// Row-major entries; after [`SmallLu::factor`], `L` (unit diagonal, below) and `U`.
    pub a: Vec<f64>,
    perm: Vec<usize>,
}

impl SmallLu {
    pub fn new(n: usize) -> SmallLu {
        SmallLu {
            n,
            a: vec![0.0; n * n],
            perm: (0..n).collect(),
        }
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    /// Entry `(i, j)` to fill before [`SmallLu::factor`].
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, x: f64) {
        self.a[i * self.n + j] = x;
    }

    /// Factor in place. Returns false if a pivot is zero, tiny against the largest (1e-14) or
    /// not finite.
    pub fn factor(&mut self) -> bool {
        let n = self.n;
        let a = &mut self.a;
        let mut max_pivot: f64 = 0.0;
        let mut min_pivot = f64::INFINITY;
        for k in 0..n {
            self.perm[k] = k;
        }
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].abs();
            for i in k + 1..n {
                let x = a[i * n + k].abs();
                if x > best {
                    best = x;
                    p = i;
                }
            }
            if !best.is_finite() || best == 0.0 {
                return false;
            }
            if p != k {
                for j in 0..n {
                    a.swap(k * n + j, p * n + j);
                }
                self.perm.swap(k, p);
            }
            max_pivot = max_pivot.max(best);
            min_pivot = min_pivot.min(best);
            let pivot = a[k * n + k];
            for i in k + 1..n {
                let l = a[i * n + k] / pivot;
                a[i * n + k] = l;
                if l != 0.0 {
                    for j in k + 1..n {
                        a[i * n + j] -= l * a[k * n + j];
                    }
                }
            }
        }
        n == 0 || min_pivot > 1e-14 * max_pivot
    }

    /// Solve `A x = b` in place (`b` becomes `x`), with `work` of length n.
    pub fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        let n = self.n;
        let a = &self.a;
        for i in 0..n {
            work[i] = b[self.perm[i]];
        }
        for i in 0..n {
            let mut s = work[i];
            for j in 0..i {
                s -= a[i * n + j] * work[j];
            }
            work[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = work[i];
            for j in i + 1..n {
                s -= a[i * n + j] * work[j];
            }
            work[i] = s / a[i * n + i];
        }
        b[..n].copy_from_slice(&work[..n]);
    }

    /// Solve `A^T x = b` in place, with `work` of length n.
    pub fn solve_transpose(&self, b: &mut [f64], work: &mut [f64]) {
        // A^T = U^T L^T P: U^T y = b, L^T z = y, x = P^T z.
        let n = self.n;
        let a = &self.a;
        work[..n].copy_from_slice(&b[..n]);
        for i in 0..n {
            let mut s = work[i];
            for j in 0..i {
                s -= a[j * n + i] * work[j];
            }
            work[i] = s / a[i * n + i];
        }
        for i in (0..n).rev() {
            let mut s = work[i];
            for j in i + 1..n {
                s -= a[j * n + i] * work[j];
            }
            work[i] = s;
        }
        for i in 0..n {
            b[self.perm[i]] = work[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn system() -> ([[f64; 4]; 4], [f64; 4]) {
        (
            [
                [0.0, 2.0, 1.0, -1.0],
                [1.0, 1.0, 0.0, 3.0],
                [3.0, 0.0, 1.0, 0.5],
                [-2.0, 4.0, 1.5, 1.0],
            ],
            [1.0, -2.0, 0.5, 3.0],
        )
    }

    #[test]
    fn solves_and_solves_transposed() {
        let (a, x) = system();
        let mut lu = SmallLu::new(4);
        for i in 0..4 {
            for j in 0..4 {
                lu.set(i, j, a[i][j]);
            }
        }
        assert!(lu.factor());
        let mut work = [0.0; 4];
        let mut b: Vec<f64> = (0..4)
            .map(|i| (0..4).map(|j| a[i][j] * x[j]).sum())
            .collect();
        lu.solve(&mut b, &mut work);
        let mut bt: Vec<f64> = (0..4)
            .map(|i| (0..4).map(|j| a[j][i] * x[j]).sum())
            .collect();
        lu.solve_transpose(&mut bt, &mut work);
        for i in 0..4 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
            assert!((bt[i] - x[i]).abs() < 1e-14, "{bt:?}");
        }
    }

    #[test]
    fn reports_singular() {
        let mut lu = SmallLu::new(2);
        lu.a.copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!lu.factor());
    }
}
