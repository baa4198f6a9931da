//! `numerics`: the numerical building blocks shared by beltcheck's two independent
//! solvers, `bvp` and `fem`. Both depend on this crate and never on each other: they
//! share code, not answers.
//!
//! # Layers (each builds only on those above it)
//! - [`scalar`]: the number type of functions differentiated by forward-mode AD
//!   ([`Scalar`]: `f64` and num-dual's duals);
//! - [`linear`]: sparse direct solves — [`linear::SparseLu`] (symbolic factorisation once
//!   per pattern, numeric per iteration), [`linear::TripletLu`] (the same from triplets,
//!   pattern cached by comparison) and [`linear::BorderedLu`] (a sparse block with two
//!   dense border unknowns by its 2 × 2 Schur complement), failures as
//!   [`linear::LinearError`]; [`SparseLu::banded`] factorises a band with a small dense
//!   border (global unknowns, a closed loop's wrap-around) by [`banded::BorderedBand`]
//!   — an LU with partial pivoting within the band and the border's Schur complement,
//!   linear in n — and falls back to faer's LU for any other pattern;
//! - [`quadrature`]: integration rules on [−1, 1] (Gauss–Legendre 1…5 points, Simpson,
//!   trapezoidal) — fem's element rules and bvp's collocation nodes;
//! - [`fmt`]: numbers in messages with significant digits ([`Sig`]);
//! - [`newton`]: one damped Newton for F(z) = 0 over a [`newton::NewtonProblem`]
//!   (residual, Jacobian factorisation and solve, optional norm / merit / admissibility /
//!   step-acceptance / regularisation / convergence hooks), with natural-monotonicity or
//!   backtracking damping, work statistics and typed failures. Its tolerance is on the
//!   full Newton correction in the scaled maximum norm max_i |Δz_i| / (1 + |z_i|)
//!   (weights at the current iterate; a problem may supply its own norm) — see the
//!   module for the exact algorithm and for how fem's three Newton loops map onto it.
//! - [`continuation`]: continuation in a scalar parameter η — step control
//!   ([`continuation::StepControl`], the growth rules of bvp's and fem's homotopies as
//!   [`continuation::Growth`]), natural-parameter continuation over a
//!   [`continuation::Homotopy`], pseudo-arclength continuation over a
//!   [`continuation::Branch`] with fold detection, and fold location by Brent's method.
//!   The caller keeps its predictor, corrector and mesh transfer; what moves here is the
//!   part every continuation repeats.
//! - [`drift`]: the drift of a signal that settles by a damped oscillation (a line under
//!   e^{−λt}(B cos Ωt + C sin Ωt), by variable projection with argmin's Nelder–Mead) —
//!   the shell's run-off after its lateral transient.
//! - [`phases`]: where a solve's time goes — seconds per phase (assembly, symbolic and
//!   numeric LU, solves, residuals, integration, mesh adaptation, fitting) and work
//!   counts, marked by every solver and collected by the caller around a whole solve.
//!
//! Errors are typed enums carrying the numbers; the linear solvers are generic over the
//! caller's error type `E: From<LinearError>` so that each crate keeps its own error enum.

pub mod banded;
pub mod continuation;
pub mod drift;
pub mod fmt;
pub mod linear;
pub mod newton;
pub mod phases;
pub mod quadrature;
pub mod roots;
pub mod scalar;
#[cfg(test)]
mod test_support;

pub use fmt::Sig;
pub use linear::{BorderedLu, LinearError, SparseLu, TripletLu};
pub use newton::{NewtonError, NewtonOptions, NewtonProblem, NewtonStats};
pub use quadrature::Rule;
pub use scalar::Scalar;
