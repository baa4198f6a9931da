//! Sparse LU of the global tangent and the bordered LU of the drive's Newton systems,
//! shared with `bvp` in the `numerics` crate (the unit tests live there). Failures are
//! reported as messages here until fem's solvers take [`numerics::LinearError`].

/// A sparse LU with cached symbolic factorisation (`set_pattern` once, `factorize` per
/// iteration). Duplicate triplets are summed.
pub type SparseLu = numerics::SparseLu<String>;

/// A sparse system [A B; C D] with two global unknowns as its border, solved by A's LU
/// and the 2 × 2 Schur complement (the drive's two solvers use it with (c, ω₂) and
/// (a, φ) as the border).
pub type BorderedLu = numerics::BorderedLu<String>;
