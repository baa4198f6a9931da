//! Scalar roots: Brent's method (argmin's `BrentRoot`) on a bracket, for functions whose
//! evaluation can fail (a Newton solve inside, typically).
//!
//! Every scalar root search of the workspace goes through [`brent`]: the fold location
//! of the continuation ([`crate::continuation::locate_fold`]), the closed forms of the
//! `bvp` crate (Bratu's θ, the elastica's parameters), the one-pulley FE's prescribed
//! stick→slip angle. A failed evaluation ends the search and is returned as it was
//! raised, so the caller's error (with its numbers) reaches the user unchanged; a
//! non-finite value is an error of its own, never a root.

use argmin::core::{CostFunction, Executor, State, TerminationReason};
use argmin::solver::brent::BrentRoot;
use thiserror::Error;

use crate::fmt::Sig;

/// Why [`brent`] found no root.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RootError<E> {
    /// g has the same sign at both ends of the bracket (or a non-finite value there).
    #[error("g({a}) = {ga} and g({b}) = {gb} do not bracket a root")]
    NotBracketed { a: Sig, b: Sig, ga: Sig, gb: Sig },
    /// An evaluation of g failed.
    #[error("{0}")]
    Evaluation(E),
    /// g was not finite inside the bracket.
    #[error("g({x}) = {value} inside the bracket [{a}, {b}]")]
    NonFinite { a: Sig, b: Sig, x: Sig, value: Sig },
    /// Brent's method did not converge.
    #[error("Brent's method did not converge on [{a}, {b}] ({reason})")]
    NotConverged { a: Sig, b: Sig, reason: String },
}

/// The root x* of g between `a` and `b` (either order; g(a)·g(b) ≤ 0), to within the
/// absolute tolerance `tol` in x, by Brent's method, at most 200 iterations. An end
/// where g is exactly zero is returned without further evaluations.
///
/// # Errors
/// [`RootError`]: no bracket, a failed or non-finite evaluation, no convergence.
pub fn brent<E>(mut g: impl FnMut(f64) -> Result<f64, E>, a: f64, b: f64, tol: f64) -> Result<f64, RootError<E>> {
    let ga = g(a).map_err(RootError::Evaluation)?;
    if ga == 0.0 {
        return Ok(a);
    }
    let gb = g(b).map_err(RootError::Evaluation)?;
    if gb == 0.0 {
        return Ok(b);
    }
    if !(ga.is_finite() && gb.is_finite()) || ga * gb > 0.0 {
        return Err(RootError::NotBracketed { a: Sig(a), b: Sig(b), ga: Sig(ga), gb: Sig(gb) });
    }
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    let failure = std::cell::RefCell::new(None);
    let cost = Scalar { g: std::cell::RefCell::new(g), failure: &failure, bracket: (lo, hi) };
    let res = Executor::new(cost, BrentRoot::new(lo, hi, tol)).configure(|s| s.param(0.5 * (lo + hi)).max_iters(200)).run();
    if let Some(e) = failure.borrow_mut().take() {
        return Err(e);
    }
    let not_converged = |reason: String| RootError::NotConverged { a: Sig(lo), b: Sig(hi), reason };
    let res = res.map_err(|e| not_converged(e.to_string()))?;
    let state = res.state();
    match state.get_termination_reason() {
        Some(TerminationReason::SolverConverged) => {}
        other => return Err(not_converged(format!("{other:?}"))),
    }
    state.get_best_param().copied().ok_or_else(|| not_converged("no estimate".into()))
}

/// g as argmin's cost function; a failed or non-finite evaluation is remembered (the
/// first one) and ends Brent's iteration.
struct Scalar<'a, G, E> {
    g: std::cell::RefCell<G>,
    failure: &'a std::cell::RefCell<Option<RootError<E>>>,
    bracket: (f64, f64),
}

impl<G: FnMut(f64) -> Result<f64, E>, E> CostFunction for Scalar<'_, G, E> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &f64) -> Result<f64, argmin::core::Error> {
        let failed = match (self.g.borrow_mut())(*x) {
            Ok(v) if v.is_finite() => return Ok(v),
            Ok(v) => RootError::NonFinite { a: Sig(self.bracket.0), b: Sig(self.bracket.1), x: Sig(*x), value: Sig(v) },
            Err(e) => RootError::Evaluation(e),
        };
        self.failure.borrow_mut().get_or_insert(failed);
        Err(argmin::core::Error::msg("evaluation failed"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq)]
    struct Failed(f64);

    /// x³ = 1/8 on either order of the bracket, to the tolerance asked; an exact zero at
    /// an end is returned as is.
    #[test]
    fn finds_a_cubic_root_from_either_end() {
        for (a, b) in [(0.0, 1.0), (1.0, 0.0)] {
            let x = brent(|x: f64| Ok::<f64, Failed>(x.powi(3) - 0.125), a, b, 1e-13).unwrap();
            assert!((x - 0.5).abs() < 1e-12, "{x}");
        }
        assert_eq!(brent(|x: f64| Ok::<f64, Failed>(x - 2.0), 2.0, 5.0, 1e-12).unwrap(), 2.0);
    }

    /// No bracket, a failing evaluation inside and a non-finite value inside are three
    /// different errors; the caller's own error comes back unchanged.
    #[test]
    fn failures_are_named() {
        let e = brent(|x: f64| Ok::<f64, Failed>(x * x + 1.0), -1.0, 1.0, 1e-10).unwrap_err();
        assert!(matches!(e, RootError::NotBracketed { .. }), "{e:?}");
        // every evaluation strictly inside the bracket fails (or is NaN); the ends do not
        let inside = |x: f64| x > 0.0 && x < 0.5;
        let e = brent(|x: f64| if inside(x) { Err(Failed(x)) } else { Ok(x - 0.45) }, 0.0, 0.5, 1e-10).unwrap_err();
        assert!(matches!(e, RootError::Evaluation(Failed(x)) if inside(x)), "{e:?}");
        let e = brent(|x: f64| Ok::<f64, Failed>(if inside(x) { f64::NAN } else { x - 0.45 }), 0.0, 0.5, 1e-10).unwrap_err();
        assert!(matches!(e, RootError::NonFinite { .. }), "{e:?}");
    }
}
