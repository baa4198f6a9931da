//! The BVP engine's damped Newton: [`numerics::newton`] with its default damping,
//! Deuflhard's natural monotonicity test (error-oriented NLEQ-ERR, simplified), and its
//! default tolerance norm ‖Δz‖ = max_i |Δz_i| / (1 + |z_i|) (weights frozen at the
//! current iterate; the algorithm and the tolerance are defined exactly there).
//!
//! A system is supplied through [`NewtonSystem`]: a residual, a Jacobian factorisation
//! at a point and a solve with that factorisation. Sparse Jacobians are factorised with
//! [`SparseLu`], which computes the symbolic LU once per sparsity pattern (once per
//! mesh) and only refactorises numerically in each iteration (DEPENDENCIES.md: symbolic
//! 83 ms vs numeric 31 ms at n = 100 000).
//!
//! Failures are values: [`BvpError::NewtonDiverged`] (iteration limit, or λ below
//! λ_min; its `residual` field is the last scaled Newton correction ‖Δz‖, the quantity
//! compared with the tolerance), [`BvpError::SingularJacobian`] and
//! [`BvpError::NonFinite`] (the mapping from [`numerics::newton::NewtonError`] is in
//! `error.rs`).

use crate::error::BvpError;
use numerics::newton::NewtonProblem;

pub use numerics::newton::{scaled_norm, NewtonOptions};

/// Work done by one Newton solve (iterations = Jacobian factorisations, residual
/// evaluations, solves, last scaled correction, smallest damping factor).
pub type NewtonReport = numerics::newton::NewtonStats;

/// Sparse LU of a square matrix given as (row, col, value) triplets, with the symbolic
/// factorisation cached for as long as the pattern does not change (duplicates summed);
/// shared with `fem` in the `numerics` crate, failures as [`BvpError`].
pub type SparseLu = numerics::TripletLu<BvpError>;

/// A square nonlinear system F(z) = 0 with a factorisable Jacobian.
pub trait NewtonSystem {
    /// Number of unknowns n (= number of equations).
    fn size(&self) -> usize;
    /// Residual F(z) into `r` (length n). Non-finite entries are allowed here; the
    /// Newton loop checks them.
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), BvpError>;
    /// Evaluate and factorise the Jacobian ∂F/∂z at `z`; later [`Self::solve`] calls
    /// use this factorisation.
    fn factorize(&mut self, z: &[f64]) -> Result<(), BvpError>;
    /// Overwrite `b` with J⁻¹ b for the last factorised Jacobian.
    fn solve(&mut self, b: &mut [f64]) -> Result<(), BvpError>;
    /// The round-off floor of the Newton correction at `z` (the Jacobian factorised
    /// there), in the scaled norm: [`numerics::newton::NewtonProblem::correction_floor`].
    /// Default: none.
    fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, BvpError> {
        let _ = z;
        Ok(None)
    }
    /// Whether the residual at the converged iterate is evaluated to check it is finite
    /// ([`numerics::newton::NewtonProblem::converged_residual`]). Default: `true`.
    fn converged_residual(&self) -> bool {
        true
    }
}

/// A [`NewtonSystem`] as the shared Newton's problem (default damping, norm and hooks).
struct Shared<'s, S>(&'s mut S);

impl<S: NewtonSystem> NewtonProblem for Shared<'_, S> {
    type Error = BvpError;
    fn size(&self) -> usize {
        self.0.size()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), BvpError> {
        self.0.residual(z, r)
    }
    fn factorize(&mut self, z: &[f64]) -> Result<(), BvpError> {
        self.0.factorize(z)
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), BvpError> {
        self.0.solve(b)
    }
    fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, BvpError> {
        self.0.correction_floor(z)
    }
    fn converged_residual(&self) -> bool {
        self.0.converged_residual()
    }
}

/// Solve F(z) = 0 by the damped Newton method of the module documentation, starting
/// from and overwriting `z` (length n). On error `z` holds the last accepted iterate.
///
/// # Errors
/// [`BvpError::NewtonDiverged`], [`BvpError::SingularJacobian`], [`BvpError::NonFinite`],
/// [`BvpError::InvalidInput`] (options, dimensions), or the system's own error.
pub fn solve<S: NewtonSystem>(system: &mut S, z: &mut [f64], opts: &NewtonOptions) -> Result<NewtonReport, BvpError> {
    Ok(numerics::newton::solve(&mut Shared(system), z, opts)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// F(z) = (z0² + z1² − 4, z0 − z1) with root (√2, √2); a dense Jacobian as triplets.
    struct Circle {
        lu: SparseLu,
    }

    impl NewtonSystem for Circle {
        fn size(&self) -> usize {
            2
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), BvpError> {
            r[0] = z[0] * z[0] + z[1] * z[1] - 4.0;
            r[1] = z[0] - z[1];
            Ok(())
        }
        fn factorize(&mut self, z: &[f64]) -> Result<(), BvpError> {
            self.lu.factorize(2, &[0, 0, 1, 1], &[0, 1, 0, 1], &[2.0 * z[0], 2.0 * z[1], 1.0, -1.0])
        }
        fn solve(&mut self, b: &mut [f64]) -> Result<(), BvpError> {
            self.lu.solve_in_place(b)
        }
    }

    #[test]
    fn converges_quadratically_and_reuses_symbolic() {
        let mut sys = Circle { lu: SparseLu::new() };
        let mut z = vec![10.0, 0.3];
        let rep = solve(&mut sys, &mut z, &NewtonOptions { tolerance: 1e-13, ..Default::default() }).unwrap();
        assert!((z[0] - 2f64.sqrt()).abs() < 1e-12 && (z[1] - 2f64.sqrt()).abs() < 1e-12);
        assert!(rep.iterations <= 10, "{rep:?}");
        assert_eq!(sys.lu.symbolic_factorisations(), 1);
        assert_eq!(sys.lu.numeric_factorisations(), rep.iterations);
    }

    #[test]
    fn failures_map_to_bvp_errors() {
        // z = (0, 0): Jacobian [[0, 0], [1, −1]] is singular, at iteration 1.
        let mut sys = Circle { lu: SparseLu::new() };
        let err = solve(&mut sys, &mut [0.0, 0.0], &NewtonOptions::default()).unwrap_err();
        assert!(matches!(err, BvpError::SingularJacobian { iteration: 1, .. }), "{err}");
        // two iterations from far away are not enough
        let opts = NewtonOptions { max_iterations: 2, ..Default::default() };
        let err = solve(&mut sys, &mut [10.0, 0.3], &opts).unwrap_err();
        assert!(matches!(err, BvpError::NewtonDiverged { iterations: 2, residual, .. } if residual > 1e-3), "{err}");
        let err = solve(&mut sys, &mut [1.0], &NewtonOptions::default()).unwrap_err();
        assert!(matches!(err, BvpError::InvalidInput(_)), "{err}");
    }
}
