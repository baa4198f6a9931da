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
//!   [`linear::LinearError`];
//! - [`quadrature`]: integration rules on [−1, 1] (Gauss–Legendre 1…5 points, Simpson,
//!   trapezoidal) — fem's element rules and bvp's collocation nodes.
//!
//! Errors are typed enums carrying the numbers; the linear solvers are generic over the
//! caller's error type `E: From<LinearError>` so that each crate keeps its own error enum.

pub mod linear;
pub mod quadrature;
pub mod scalar;

pub use linear::{BorderedLu, LinearError, SparseLu, TripletLu};
pub use quadrature::Rule;
pub use scalar::Scalar;
