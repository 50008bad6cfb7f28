//! The symmetric-definite generalized eigenproblem `K a = lambda M a`.
//!
//! Method: Cholesky `M = L L^T` (faer), `C = L^-1 K L^-T`, the self-adjoint eigensolver of
//! faer on `C = Y Lambda Y^T`, then `a = L^-T Y`. The modes come out mass-normalized
//! (`a^T M a = I`) and sorted by increasing eigenvalue (Golub and Van Loan, *Matrix
//! Computations*, 4th ed., section 8.7.2).

use faer::{Mat, Side};

use crate::error::ModelError;

/// Eigenvalues (ascending) and mass-normalized eigenvectors (columns).
pub struct GeneralizedEigen {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
}

/// Solve `K a = lambda M a` for symmetric `K` and symmetric positive definite `M`.
pub fn generalized_symmetric_eigen(
    k: &Mat<f64>,
    m: &Mat<f64>,
) -> Result<GeneralizedEigen, ModelError> {
    let n = k.nrows();
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: Vec::new(),
            vectors: Mat::zeros(0, 0),
        });
    }
    let llt = m.llt(Side::Lower).map_err(|e| ModelError::Numerical {
        message: format!("the reduced mass matrix is not positive definite ({e:?})"),
    })?;
    let l = llt.L();
    // X = L^-1 K, then C = L^-1 X^T = L^-1 K L^-T.
    let mut x = k.clone();
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(c.as_mut());
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let evd = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| ModelError::Numerical {
            message: format!("the eigensolver did not converge ({e:?})"),
        })?;
    let values: Vec<f64> = (0..n).map(|i| evd.S()[i]).collect();
    let mut vectors = evd.U().to_owned();
    l.transpose()
        .solve_upper_triangular_in_place(vectors.as_mut());
    Ok(GeneralizedEigen { values, vectors })
}

/// The same problem through the Cholesky factor of `K` (symmetric positive definite):
/// `M a = mu K a`, `lambda = 1 / mu`, the vectors rescaled to `a^T M a = 1`, the eigenvalues
/// ascending. Used when `M` is so ill-conditioned that the `M`-based form loses the lowest
/// eigenvalues to round-off (a stubby shear-deformable rod on a fine mesh: the IIE mass
/// degenerates as `Phi = 12 E I / (G A_s l^2)` grows): here the absolute error is about
/// `eps mu_max`, i.e. a relative error of `eps` for the lowest `lambda`. Fails if `K` is not
/// positive definite or an eigenvalue `mu` is not positive.
pub fn generalized_symmetric_eigen_by_stiffness(
    k: &Mat<f64>,
    m: &Mat<f64>,
) -> Result<GeneralizedEigen, ModelError> {
    let inverse = generalized_symmetric_eigen(m, k).map_err(|_| ModelError::Numerical {
        message: "the reduced stiffness matrix is not positive definite".into(),
    })?;
    let n = k.nrows();
    if let Some(&mu) = inverse
        .values
        .iter()
        .find(|&&mu| mu.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
    {
        return Err(ModelError::Numerical {
            message: format!("the reduced mass matrix is not positive definite (eigenvalue {mu:e} of M relative to K)"),
        });
    }
    // mu ascending = lambda descending: reverse.
    let values: Vec<f64> = (0..n).rev().map(|i| 1.0 / inverse.values[i]).collect();
    let vectors = Mat::from_fn(n, n, |r, j| {
        let i = n - 1 - j;
        inverse.vectors[(r, i)] / inverse.values[i].sqrt()
    });
    Ok(GeneralizedEigen { values, vectors })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_by_two_against_closed_form() {
        // K = diag(2, 8), M = diag(1, 2): lambdas 2 and 4.
        let k = Mat::from_fn(2, 2, |i, j| if i == j { [2.0, 8.0][i] } else { 0.0 });
        let m = Mat::from_fn(2, 2, |i, j| if i == j { [1.0, 2.0][i] } else { 0.0 });
        let e = generalized_symmetric_eigen(&k, &m).unwrap();
        assert!((e.values[0] - 2.0).abs() < 1e-14 && (e.values[1] - 4.0).abs() < 1e-14);
        let mm = e.vectors.transpose() * &m * &e.vectors;
        assert!((mm[(0, 0)] - 1.0).abs() < 1e-14 && (mm[(1, 1)] - 1.0).abs() < 1e-14);
        let s = generalized_symmetric_eigen_by_stiffness(&k, &m).unwrap();
        assert!((s.values[0] - 2.0).abs() < 1e-14 && (s.values[1] - 4.0).abs() < 1e-14);
        let mm = s.vectors.transpose() * &m * &s.vectors;
        assert!((mm[(0, 0)] - 1.0).abs() < 1e-14 && (mm[(1, 1)] - 1.0).abs() < 1e-14);
        assert!(mm[(0, 1)].abs() < 1e-14);
    }
}
