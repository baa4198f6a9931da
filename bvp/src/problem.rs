//! The multi-segment boundary value problem in standard form.
//!
//! A problem is a chain of segments k = 0..m, each with its own ODE system
//!
//! ```text
//!     y_k'(x) = f_k(x, y_k, p, η),    x ∈ [0, 1],   y_k ∈ R^{n_k},
//! ```
//!
//! on the *normalised* interval [0, 1]. Unknown physical segment lengths (span
//! lengths, contact arc angles) are entries of the parameter vector p ∈ R^{n_p} that
//! scale the right-hand side (Ascher & Russell, "Reformulation of boundary value
//! problems into standard form", SIAM Review 23, 1981). Integral constraints are
//! reformulated as extra ODE components z' = h with two boundary conditions.
//!
//! Boundary, interface and integral conditions are one residual vector
//!
//! ```text
//!     g(y_0(0), y_0(1), …, y_{m-1}(0), y_{m-1}(1), p, η) = 0,   g ∈ R^{Σ n_k + n_p},
//! ```
//!
//! so the problem is square: Σ n_k unknown initial states and n_p parameters.
//!
//! η is a scalar *continuation parameter* (a homotopy parameter, a load factor, the
//! Bratu λ). It is fixed during an ordinary solve and becomes an unknown under
//! pseudo-arclength continuation.
//!
//! Both functions are generic over the scalar type so that Jacobians are computed by
//! forward-mode automatic differentiation ([`num_dual`]); `f64` gives plain values.

/// Scalar types the problem functions are evaluated with: `f64` and the dual numbers
/// of `num_dual` (first derivatives); one definition for `bvp` and `fem`.
pub use numerics::Scalar;

/// A square multi-segment BVP (see the module documentation for the form).
pub trait Problem: Sync {
    /// Number of segments m ≥ 1.
    fn n_segments(&self) -> usize;
    /// ODE dimension n_k of segment `k`.
    fn dim(&self, k: usize) -> usize;
    /// Number of unknown parameters n_p (segment lengths, loads, …).
    fn n_params(&self) -> usize;
    /// Right-hand side f_k(x, y, p, η) of segment `k` written into `f` (length n_k).
    fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]);
    /// The parameters f_k can depend on, as indices into p in ascending order; `None`
    /// (the default) means every parameter. Derivatives of f_k with respect to the other
    /// parameters are then exactly zero and are not evaluated ([`crate::jacobian`]): a
    /// belt segment reads its own span length or arc angles and few others, so this
    /// halves the cost of its Jacobian. A problem that declares a set must not read any
    /// parameter outside it (tested for every belt law by comparing with `None`).
    fn rhs_params(&self, _k: usize) -> Option<&[usize]> {
        None
    }
    /// Boundary/interface/integral residual g written into `r` (length Σ n_k + n_p).
    /// `ya[k]` = y_k(0), `yb[k]` = y_k(1).
    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]);
    /// Component names of segment `k` (for messages and output); defaults to y0, y1, ….
    fn component_names(&self, k: usize) -> Vec<String> {
        (0..self.dim(k)).map(|i| format!("y{i}")).collect()
    }
    /// Parameter names (for messages and output); defaults to p0, p1, ….
    fn param_names(&self) -> Vec<String> {
        (0..self.n_params()).map(|i| format!("p{i}")).collect()
    }
    /// Total number of boundary conditions Σ n_k + n_p.
    fn n_bc(&self) -> usize {
        (0..self.n_segments()).map(|k| self.dim(k)).sum::<usize>() + self.n_params()
    }
}

/// How Jacobians of `rhs` and `bc` are formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JacobianMode {
    /// Forward-mode automatic differentiation with `num_dual::Dual64` (exact).
    #[default]
    Ad,
    /// Central finite differences with step h_j = ε^{1/3} · max(1, |u_j|), ε = 2^-52.
    FiniteDifference,
}
