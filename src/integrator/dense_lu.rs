//! A dense LU factorization with partial pivoting (faer) on buffers sized once: no heap
//! allocation per factorization or solve.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Mat, MatMut, Par};

/// Workspace for `A x = b` with `A` n x n.
pub struct DenseLu {
    n: usize,
    /// The matrix to factor; overwritten by its factors.
    pub matrix: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
}

impl DenseLu {
    pub fn new(n: usize) -> DenseLu {
        let req = StackReq::any_of(&[
            factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default()),
            solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq),
        ]);
        DenseLu {
            n,
            matrix: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            scratch: MemBuffer::new(req),
        }
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    /// Write the saddle-point matrix `[c M, J^T; J, 0]` (`M` n x n, `J` m x n) into `matrix`,
    /// ready for [`Self::factor`]; `n + m` must be this workspace's size.
    pub fn set_saddle_point(&mut self, mass: &Mat<f64>, mass_factor: f64, jac: &Mat<f64>) {
        let (n, m) = (mass.nrows(), jac.nrows());
        debug_assert_eq!(n + m, self.n);
        let a = &mut self.matrix;
        for i in 0..n {
            for j in 0..n {
                a[(i, j)] = mass_factor * mass[(i, j)];
            }
        }
        for k in 0..m {
            for j in 0..n {
                a[(n + k, j)] = jac[(k, j)];
                a[(j, n + k)] = jac[(k, j)];
            }
            for l in 0..m {
                a[(n + k, n + l)] = 0.0;
            }
        }
    }

    /// Factor `matrix` in place. Returns false if a pivot is zero or not finite.
    pub fn factor(&mut self) -> bool {
        let stack = MemStack::new(&mut self.scratch);
        factor::lu_in_place(
            self.matrix.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            stack,
            Default::default(),
        );
        let mut max_pivot: f64 = 0.0;
        let mut min_pivot = f64::INFINITY;
        for i in 0..self.n {
            let p = self.matrix[(i, i)].abs();
            if !p.is_finite() {
                return false;
            }
            max_pivot = max_pivot.max(p);
            min_pivot = min_pivot.min(p);
        }
        self.n == 0 || min_pivot > 1e-14 * max_pivot
    }

    /// Solve in place with the last factorization.
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let n = self.n;
        let stack = MemStack::new(&mut self.scratch);
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, n);
        let rhs = MatMut::from_column_major_slice_mut(rhs, n, 1);
        solve::solve_in_place(
            self.matrix.as_ref(),
            self.matrix.as_ref(),
            perm,
            rhs,
            Par::Seq,
            stack,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_pivoting_system() {
        let mut lu = DenseLu::new(3);
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        for i in 0..3 {
            for j in 0..3 {
                lu.matrix[(i, j)] = a[i][j];
            }
        }
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[i][j] * x[j]).sum())
            .collect();
        assert!(lu.factor());
        lu.solve(&mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn reports_singular() {
        let mut lu = DenseLu::new(2);
        lu.matrix[(0, 0)] = 1.0;
        lu.matrix[(0, 1)] = 2.0;
        lu.matrix[(1, 0)] = 2.0;
        lu.matrix[(1, 1)] = 4.0;
        assert!(!lu.factor());
    }
}
