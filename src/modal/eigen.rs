//! The symmetric-definite generalized eigenproblem `K a = lambda M a`.
//!
//! Method: Cholesky `M = L L^T` (faer), `C = L^-1 K L^-T`, `C = Y Lambda Y^T` by Householder
//! tridiagonalization and the implicit symmetric QR iteration (faer), then `a = L^-T Y`. The
//! modes come out mass-normalized (`a^T M a = I`) and sorted by increasing eigenvalue (Golub
//! and Van Loan, *Matrix Computations*, 4th ed., sections 8.3 and 8.7.2). The eigenvalues carry
//! an absolute error of about `eps |C| = eps lambda_max`.
//!
//! The QR iteration runs at every size: faer 0.24's default switches to divide and conquer on
//! the tridiagonal form from order 128, and on the rod's matrices (graded: the spectrum of a
//! mesh of `N` elements spans about `N^4`) that path loses the lowest eigenvalues. Measured on
//! the uniform benchmark rod (tests/every_element_count.rs): with divide and conquer the first
//! simply supported frequency is off by up to 7 % from 86 elements (0 Hz at 127), the free-free
//! rod keeps no three zero eigenvalues from 42 elements and the cantilever turns indefinite;
//! with the QR iteration every count up to [`crate::beam::mesh::MAX_ELEMENTS`] is within the
//! discretization error of the closed forms.

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
    let (values, mut vectors) = self_adjoint_qr(&c)?;
    l.transpose()
        .solve_upper_triangular_in_place(vectors.as_mut());
    Ok(GeneralizedEigen { values, vectors })
}

/// As [`generalized_symmetric_eigen`], for the rods with interior coordinates (the
/// hierarchical shear-deformable element): Jacobi-scaled (`D K D`, `D M D` with
/// `D = diag(M)^-1/2`, which leaves the eigenvalues as they are and brings the mass matrix of
/// nodal rotations, displacements and interior coordinates to unit diagonal), Cholesky, and
/// nalgebra's symmetric QR eigensolver on `C = L^-1 K L^-T` (Golub and Van Loan, section
/// 8.3). Measured (tests/rod_exact_frequencies.rs, the stubby rod at 32 and 64 elements): the
/// QR iteration on that `C` agrees with the stiffness-based form
/// ([`generalized_symmetric_eigen_by_stiffness`]) to 1e-12, where faer 0.24's default
/// (divide and conquer from order 128) loses the lowest eigenvalue (about 1e-5 relative at 32
/// elements, NaN at 64).
pub fn generalized_symmetric_eigen_scaled(
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
    let not_pd = || ModelError::Numerical {
        message: "the reduced mass matrix is not positive definite".into(),
    };
    let d: Vec<f64> = (0..n)
        .map(|i| {
            let mii = m[(i, i)];
            if mii > 0.0 {
                Ok(1.0 / mii.sqrt())
            } else {
                Err(not_pd())
            }
        })
        .collect::<Result<_, _>>()?;
    let ms = nalgebra::DMatrix::from_fn(n, n, |i, j| m[(i, j)] * d[i] * d[j]);
    let ks = nalgebra::DMatrix::from_fn(n, n, |i, j| k[(i, j)] * d[i] * d[j]);
    let chol = ms.cholesky().ok_or_else(not_pd)?;
    let l = chol.l();
    let x = l.solve_lower_triangular(&ks).ok_or_else(not_pd)?;
    let c = l
        .solve_lower_triangular(&x.transpose())
        .ok_or_else(not_pd)?;
    let c = (&c + c.transpose()) * 0.5;
    let evd = nalgebra::SymmetricEigen::try_new(c, f64::EPSILON, 0).ok_or_else(|| {
        ModelError::Numerical {
            message: "the eigensolver did not converge".into(),
        }
    })?;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| evd.eigenvalues[a].total_cmp(&evd.eigenvalues[b]));
    let values: Vec<f64> = order.iter().map(|&i| evd.eigenvalues[i]).collect();
    // a = D L^-T y.
    let y = nalgebra::DMatrix::from_fn(n, n, |r, j| evd.eigenvectors[(r, order[j])]);
    let z = l
        .transpose()
        .solve_upper_triangular(&y)
        .ok_or_else(not_pd)?;
    let vectors = Mat::from_fn(n, n, |r, j| d[r] * z[(r, j)]);
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
    by_stiffness(k, m, generalized_symmetric_eigen)
}

/// [`generalized_symmetric_eigen_by_stiffness`] through [`generalized_symmetric_eigen_scaled`]
/// (scaled by the diagonal of `K`): for a rod with interior coordinates whose spectrum spans
/// too many decades for the mass-based form (the shear-deformable element with a nearly rigid
/// shear modulus: its interior shear modes sit some 1e13 above the first bending mode).
pub fn generalized_symmetric_eigen_by_stiffness_scaled(
    k: &Mat<f64>,
    m: &Mat<f64>,
) -> Result<GeneralizedEigen, ModelError> {
    by_stiffness(k, m, generalized_symmetric_eigen_scaled)
}

fn by_stiffness(
    k: &Mat<f64>,
    m: &Mat<f64>,
    solve: fn(&Mat<f64>, &Mat<f64>) -> Result<GeneralizedEigen, ModelError>,
) -> Result<GeneralizedEigen, ModelError> {
    let inverse = solve(m, k).map_err(|_| ModelError::Numerical {
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

/// The eigendecomposition `c = U diag(s) U^T` of a symmetric `c` (its lower triangle), the
/// eigenvalues ascending: faer's Householder tridiagonalization and implicit symmetric QR
/// iteration (Golub and Van Loan, sections 8.3.1 and 8.3.3) at every order (the recursion
/// threshold of its divide and conquer set beyond any order; below 128 this is what faer's
/// default does too).
fn self_adjoint_qr(c: &Mat<f64>) -> Result<(Vec<f64>, Mat<f64>), ModelError> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{self, ComputeEigenvectors, SelfAdjointEvdParams};
    let n = c.nrows();
    let params = SelfAdjointEvdParams {
        recursion_threshold: usize::MAX,
        ..faer::Auto::<f64>::auto()
    };
    let mut u = Mat::<f64>::zeros(n, n);
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let par = faer::Par::Seq;
    let mut buffer = MemBuffer::new(evd::self_adjoint_evd_scratch::<f64>(
        n,
        ComputeEigenvectors::Yes,
        par,
        params.into(),
    ));
    evd::self_adjoint_evd(
        c.as_ref(),
        s.as_mut(),
        Some(u.as_mut()),
        par,
        MemStack::new(&mut buffer),
        params.into(),
    )
    .map_err(|e| ModelError::Numerical {
        message: format!("the eigensolver did not converge ({e:?})"),
    })?;
    Ok(((0..n).map(|i| s[i]).collect(), u))
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
