//! One damped Newton method for F(z) = 0, z ∈ Rⁿ, with typed failures and work
//! statistics, generic over a [`NewtonProblem`] (residual, Jacobian factorisation and
//! solve, optional hooks) — the nonlinear layer above [`crate::linear`].
//!
//! # Tolerance (exact definition)
//! The iteration has converged when a **full Newton correction** Δz_k = −J(z_k)⁻¹F(z_k)
//! satisfies ‖Δz_k‖ ≤ `tolerance`, with the norm of [`NewtonProblem::norm`] — by
//! default the scaled maximum norm
//!
//! ```text
//!     ‖v‖_z = max_i |v_i| / (1 + |z_i|)      (weights frozen at the current iterate z_k)
//! ```
//!
//! i.e. each unknown's change relative to its own size, absolute below 1. The corrected
//! point z_k + Δz_k is returned; its error is O(‖Δz_k‖²) (quadratic convergence). The
//! residual F itself is never compared with the tolerance; a problem whose unknowns have
//! other natural scales (lengths in H, slopes, forces) overrides `norm` with its weights.
//!
//! # Damping ([`Damping`], chosen by [`NewtonProblem::damping`])
//! **Natural monotonicity** (Deuflhard, "Newton Methods for Nonlinear Problems",
//! Springer 2004, §3.3, the error-oriented NLEQ-ERR scheme, simplified), at iterate z_k:
//! 1. Δz_k = −J(z_k)⁻¹ F(z_k) (one factorisation); converged if ‖Δz_k‖ ≤ tol (above).
//! 2. A damping factor λ ∈ [λ_min, 1] is accepted if, with the simplified correction
//!    Δ̄ = −J(z_k)⁻¹ F(z_k + λΔz_k) (same LU, one residual and one solve),
//!    Θ = ‖Δ̄‖ / ‖Δz_k‖ ≤ 1 − λ/4. On rejection λ ← max(min(λ/2, μ), λ/10) with
//!    Deuflhard's prediction μ = ½ ‖Δz_k‖ λ² / ‖Δ̄ − (1 − λ)Δz_k‖, until λ < λ_min
//!    ([`NewtonError::DampingExhausted`]). A trial with a non-finite residual, or one
//!    that [`NewtonProblem::admissible`] rejects, is rejected like a failed test.
//! 3. If λ = 1 was accepted and ‖Δ̄‖ ≤ tol, Δ̄ is applied as well and
//!    z_k + Δz_k + Δ̄ is returned (Δ̄ is the next Newton correction up to O(‖Δz_k‖²):
//!    this saves one Jacobian near the solution).
//! 4. The next iteration starts with λ = min(1, 2λ_k).
//!
//! **Round-off floor.** F(z) is evaluated in floating point, so near the root the
//! computed residual is its rounding error δ and the computed correction is J⁻¹δ,
//! however close z is: the correction cannot fall below that floor, and there the
//! monotonicity test compares two round-off corrections (Θ ≈ 1) and rejects. A tolerance
//! below the floor would end in [`NewtonError::DampingExhausted`] at a point that is as
//! converged as it can be. So when a correction above the tolerance first fails the
//! test in an iteration, the problem is asked for the floor at z_k
//! ([`NewtonProblem::correction_floor`], an estimate of ‖J⁻¹δ‖ from the residual's
//! terms); if ‖Δz_k‖ ≤ floor, z_k + Δz_k is returned as converged (its last correction
//! in [`NewtonStats::last_correction`] is then above the tolerance, below the floor).
//! A problem without a floor (the default) is judged by the tolerance alone.
//!
//! The converged iterate's residual is evaluated once more, to check that it is finite
//! ([`NonFiniteWhat::ConvergedResidual`]), unless the problem checks that itself
//! ([`NewtonProblem::converged_residual`]).
//!
//! **Backtracking** on a merit function m ([`NewtonProblem::merit`], by default
//! ½‖F‖₂²), at iterate z_k:
//! 1. Δz_k as above. If ‖Δz_k‖ ≤ tol the full step is taken without a merit test when
//!    the trial is admissible (finite residual, [`NewtonProblem::admissible`]): the
//!    merit is at round-off there.
//! 2. Otherwise α = 1, ½, ¼, … ≥ λ_min (after a rejected admissible trial the α of
//!    [`NewtonProblem::next_damping`], e.g. [`skip_halvings`]); a trial is judged by
//!    [`NewtonProblem::accept_step`] (by default Armijo's m(z + αΔz) ≤ (1 − c α) m(z),
//!    c = [`SUFFICIENT_DECREASE`]), which may also abandon the search at once (e.g. Δz
//!    is not a descent direction of an energy). A rejected full step of the plain
//!    Newton step may first be linearised again at its trial
//!    ([`NewtonProblem::relinearise`]): the trial's own Newton step, z + Δz + Δz', is
//!    taken if `accept_step` accepts it against m(z) (α = 1), else the search goes on.
//! 3. If no α is accepted — or [`NewtonProblem::line_search`] declines the step (e.g.
//!    not a descent direction), or the step is not finite (a numerically singular
//!    Jacobian) — [`NewtonProblem::regularise`] is asked for level 1, 2, …
//!    (e.g. Levenberg–Marquardt J + μ D): on `true` the problem has refactorised, the
//!    step is solved again and searched again. When the levels are exhausted the best
//!    admissible trial by merit is taken if `take_best` is set, else the solve fails
//!    ([`NewtonError::LineSearchFailed`], or [`NewtonError::SingularStep`] if the last
//!    step was not finite).
//! 4. After every accepted step [`NewtonProblem::converged`] decides (default: a full
//!    step with ‖Δz_k‖ ≤ tol) — a semismooth Newton adds "and the active set did not
//!    change", or a round-off floor.

//! # Shared passes ([`Evaluation`], chosen by [`NewtonProblem::evaluation`])
//! Both off by default (the scheme above, evaluation for evaluation). A problem whose
//! Jacobian pass also yields F (an assembly of energy, gradient and Hessian) sets
//! `residual_with_factorization`: F(z_k) is then taken from
//! [`NewtonProblem::factorize_with_residual`] at every iteration and F(z₀) is not
//! evaluated apart. A problem whose merit is cheaper than its residual (an energy
//! against its gradient) sets `merit_only`: backtracking judges every trial by
//! [`NewtonProblem::trial_merit`] and evaluates F only at the accepted trial — with
//! both set, never outside the factorisations (a converged iterate is returned without
//! its residual). The iterates are the same as without the hooks when the passes give
//! the same numbers.
//!
//! # How fem's three Newton loops are mapped onto this
//! All three use backtracking with [`Evaluation::residual_with_factorization`]: their
//! Jacobian pass (the assembly of Π, G and K, or the steady equations with their
//! Jacobian) yields the residual, and the step is taken from that pass's residual.
//! - `fem/src/newton.rs` (static string/rod, `StaticNewton`): `Backtracking { take_best:
//!   false }`, α ≥ 2⁻²⁰, [`Evaluation::merit_only`] with `merit` = Π (trials by the
//!   energy pass alone; the converging full step by the gradient pass, whose ‖G‖ and Π
//!   are reported); `norm` = max |Δ_i|/d_i (d_i = H for values, 1 for slopes);
//!   `line_search` only along descent directions (GᵀΔ < 0); `accept_step` = Armijo on Π
//!   with the 10⁻¹³ F_ref H allowance; `regularise` refactorises K + μ diag|K|,
//!   μ = 10⁻⁶, …, 10², then one last level (the last resort) that reuses the plain step
//!   of level 0 and accepts where the scaled residual ‖G‖ does not grow (these levels
//!   are `fem::newton::EnergyLevels`, shared with the transient step); `converged` only
//!   at the converging full step.
//! - `fem/src/string_drive/system.rs` (the transient step, `StepProblem`): as the
//!   static one on [`crate::linear::BorderedLu`] (values stored by the factorisation,
//!   factorised in `solve`), D floored at 10⁻⁸ max|D|; a singular tangent (a fully
//!   sliding pulley) makes a non-finite step, which fails its level like an indefinite
//!   one (an error at μ = 10²); the converging full step is judged by Π, the last resort
//!   by max |G|.
//! - `fem/src/string_drive/steady/semismooth.rs` (the steady semismooth Newton,
//!   `Semismooth`): `Backtracking { take_best: true }` (the active set may change along
//!   the step), α ≥ 2⁻¹⁰ with `next_damping` = [`skip_halvings`] (α/4 where a
//!   quadratic model of the merit rejects α/2 and α/4), trials judged by their
//!   residual (no `merit_only`: the active
//!   set of the trial is needed); `relinearise` at a rejected full step whose trial
//!   brings penalty points into contact within the first eighth of the step and keeps
//!   every slip flag; `merit` = ½ Σ (F_i/s_i)²; `accept_step` = Armijo with
//!   c = 10⁻⁴, or any admissible trial of a correction below the tolerance; `solve`
//!   retries a singular generalised Jacobian with diagonal shifts 10⁻¹², …, 10⁻⁴ of |D|;
//!   `converged` = a whole small step that kept the active set (or two in a row), or the
//!   round-off floor (three steps within 10³ tol on the same set that reduce the merit by
//!   less than 10 %). The caller checks Coulomb's bound of the points taken as stick on
//!   the accepted trial's results.
//!
//! With the same passes the migrated loops give bit-identical iterates, iteration
//! counts and failure numbers; an error at the iteration limit re-evaluates the last
//! iterate (as the loops did, which evaluated it before the limit check).
//!
//! [`crate::linear::BorderedLu`] factorises inside its `solve`; a problem on it stores
//! the Jacobian values in `factorize` and calls `BorderedLu::solve` in `solve`. Backtracking
//! does one solve per factorisation, so this costs nothing extra (natural monotonicity
//! would refactorise for each simplified correction).
//!
//! Failures are values ([`NewtonError`]): every variant carries the iteration and the
//! last scaled correction and residual.

use thiserror::Error;

use crate::linear::{LinearError, TripletLu};
use crate::phases::{self, timed, Phase};

/// Armijo's constant c of the default backtracking test m(z + αΔz) ≤ (1 − cα) m(z).
pub const SUFFICIENT_DECREASE: f64 = 1e-4;

/// Options of [`solve`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NewtonOptions {
    /// Convergence threshold on the norm of a full Newton correction (module
    /// documentation: by default max_i |Δz_i| / (1 + |z_i|)). Default 1e-10; valid
    /// range (0, 1).
    pub tolerance: f64,
    /// Maximum number of Newton iterations (Jacobian factorisations without
    /// regularisation). Default 30; valid ≥ 1.
    pub max_iterations: usize,
    /// Smallest damping factor λ_min (α_min of backtracking) before giving up.
    /// Default 1e-4; valid (0, 1].
    pub min_damping: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self { tolerance: 1e-10, max_iterations: 30, min_damping: 1e-4 }
    }
}

/// A [`NewtonOptions`] field outside its documented range.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("Newton {field} = {value} outside {range}")]
pub struct InvalidOptions {
    /// Field name.
    pub field: &'static str,
    /// The value given.
    pub value: f64,
    /// The valid range.
    pub range: &'static str,
}

impl NewtonOptions {
    /// Check the documented ranges.
    ///
    /// # Errors
    /// [`InvalidOptions`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), InvalidOptions> {
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(InvalidOptions { field: "tolerance", value: self.tolerance, range: "(0, 1)" });
        }
        if self.max_iterations == 0 {
            return Err(InvalidOptions { field: "max_iterations", value: 0.0, range: "≥ 1" });
        }
        if !(self.min_damping > 0.0 && self.min_damping <= 1.0) {
            return Err(InvalidOptions { field: "min_damping", value: self.min_damping, range: "(0, 1]" });
        }
        Ok(())
    }
}

/// The damping strategy (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// Deuflhard's natural monotonicity test on the simplified correction.
    NaturalMonotonicity,
    /// Backtracking α = 1, ½, … on the merit; `take_best`: when no α is accepted and no
    /// regularisation is left, take the admissible trial of least merit instead of
    /// failing.
    Backtracking {
        /// Take the best trial when the line search fails.
        take_best: bool,
    },
}

/// Work done by one Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct NewtonStats {
    /// Newton iterations (= unregularised Jacobian evaluations and factorisations).
    pub iterations: usize,
    /// Residual evaluations F(z) by [`NewtonProblem::residual`] (a residual evaluated
    /// with the Jacobian, [`Evaluation::residual_with_factorization`], is not counted).
    pub residual_evaluations: usize,
    /// Trials judged by [`NewtonProblem::trial_merit`] alone ([`Evaluation::merit_only`]).
    pub merit_evaluations: usize,
    /// Factorisations, regularised ones included.
    pub factorisations: usize,
    /// Linear solves with a factorised Jacobian.
    pub solves: usize,
    /// Regularised refactorisations ([`NewtonProblem::regularise`] returning `true`).
    pub regularisations: usize,
    /// Factorisations at a rejected full-step trial ([`NewtonProblem::relinearise`]),
    /// counted in `iterations` and `factorisations` too.
    pub relinearisations: usize,
    /// Of them, those whose step was taken.
    pub relinearisations_taken: usize,
    /// Last scaled Newton correction ‖Δz‖ (the quantity compared with the tolerance).
    pub last_correction: f64,
    /// Smallest damping factor used.
    pub min_damping_used: f64,
}

/// Which call of the problem failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// [`NewtonProblem::residual`].
    Residual,
    /// [`NewtonProblem::factorize`] or [`NewtonProblem::regularise`].
    Factorize,
    /// [`NewtonProblem::solve`].
    Solve,
}

/// What turned out non-finite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NonFiniteWhat {
    /// The initial iterate.
    InitialIterate,
    /// The residual at the initial iterate.
    InitialResidual,
    /// The residual at the converged iterate.
    ConvergedResidual,
    /// The residual at an accepted iterate whose trial was judged by its merit alone, or
    /// the residual a factorisation evaluated ([`Evaluation`]).
    IterateResidual,
}

impl std::fmt::Display for NonFiniteWhat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NonFiniteWhat::InitialIterate => "Newton initial iterate",
            NonFiniteWhat::InitialResidual => "residual at the initial iterate",
            NonFiniteWhat::ConvergedResidual => "residual at the converged iterate",
            NonFiniteWhat::IterateResidual => "residual at an accepted iterate",
        })
    }
}

/// Why a Newton solve failed. `correction` is the last scaled Newton correction ‖Δz‖
/// (the quantity compared with the tolerance), `residual` the max-norm ‖F‖_∞ at the
/// last accepted iterate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NewtonError<E> {
    /// Options outside their ranges.
    #[error(transparent)]
    InvalidOptions(#[from] InvalidOptions),
    /// The initial iterate does not have n entries.
    #[error("Newton: initial iterate has {got} entries, system has {expected}")]
    DimensionMismatch { expected: usize, got: usize },
    /// A non-finite iterate or residual where no damping can help.
    #[error("non-finite value in {what} (iteration {iteration})")]
    NonFinite { iteration: usize, what: NonFiniteWhat },
    /// The iteration limit was reached.
    #[error("Newton iteration did not converge: correction {correction:.3e} after {iterations} iterations (tolerance {tolerance:.1e}, residual {residual:.3e})")]
    MaxIterations { iterations: usize, correction: f64, residual: f64, tolerance: f64 },
    /// Natural monotonicity: the damping factor fell below its minimum.
    #[error("Newton damping {damping:.3e} below its minimum at iteration {iteration}: correction {correction:.3e} (tolerance {tolerance:.1e}, residual {residual:.3e})")]
    DampingExhausted { iteration: usize, damping: f64, correction: f64, residual: f64, tolerance: f64 },
    /// Backtracking: no acceptable step, regularisation exhausted, `take_best` unset or
    /// no admissible trial at all.
    #[error("no acceptable Newton step at iteration {iteration}: correction {correction:.3e} (tolerance {tolerance:.1e}), merit {merit:.3e}, residual {residual:.3e}")]
    LineSearchFailed { iteration: usize, correction: f64, merit: f64, residual: f64, tolerance: f64 },
    /// The Newton correction is not finite (a numerically singular Jacobian).
    #[error("non-finite Newton correction at iteration {iteration} (numerically singular Jacobian, residual {residual:.3e})")]
    SingularStep { iteration: usize, residual: f64 },
    /// A call of the problem failed.
    #[error("Newton iteration {iteration}, {stage:?}: {error}")]
    Problem { iteration: usize, stage: Stage, error: E },
}

/// One backtracking trial, as [`NewtonProblem::accept_step`] sees it.
#[derive(Debug, Clone, Copy)]
pub struct TrialStep<'a> {
    /// Iteration (1-based).
    pub iteration: usize,
    /// Regularisation level of the step (0: the plain Newton step).
    pub level: usize,
    /// Damping factor α.
    pub damping: f64,
    /// Current iterate z.
    pub z: &'a [f64],
    /// Step Δz (undamped).
    pub step: &'a [f64],
    /// Trial z + αΔz.
    pub trial: &'a [f64],
    /// F(z).
    pub residual: &'a [f64],
    /// F(z + αΔz) (finite); `None` when the trial was judged by its merit alone
    /// ([`Evaluation::merit_only`]).
    pub trial_residual: Option<&'a [f64]>,
    /// m(z).
    pub merit: f64,
    /// m(z + αΔz).
    pub trial_merit: f64,
    /// F(z)ᵀΔz: when F is the gradient of an energy Π, the slope dΠ(z + αΔz)/dα at
    /// α = 0 (negative for a descent direction).
    pub slope: f64,
    /// Norm of the unregularised Newton correction of this iteration.
    pub correction: f64,
    /// The tolerance.
    pub tolerance: f64,
}

/// What a backtracking test decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Take this trial.
    Accept,
    /// Try a smaller α.
    Reject,
    /// Stop this line search (go to the next regularisation level).
    Abandon,
}

/// An accepted step, as [`NewtonProblem::converged`] sees it.
#[derive(Debug, Clone, Copy)]
pub struct Progress<'a> {
    /// Iteration (1-based).
    pub iteration: usize,
    /// Damping factor taken.
    pub damping: f64,
    /// Norm of the unregularised Newton correction of this iteration.
    pub correction: f64,
    /// The tolerance.
    pub tolerance: f64,
    /// Merit before the step.
    pub merit_before: f64,
    /// Merit after the step.
    pub merit_after: f64,
    /// The new iterate.
    pub z: &'a [f64],
    /// Its residual; `None` when it was not evaluated (its trial was judged by its merit
    /// alone and the next factorisation evaluates it, [`Evaluation`]).
    pub residual: Option<&'a [f64]>,    /// The step is the best trial taken after a failed line search (`take_best`), not
    /// an accepted one.
    pub best_trial: bool,
}

/// Which evaluations the problem's passes share, chosen by
/// [`NewtonProblem::evaluation`]. Both are off by default, which is the scheme of the
/// module documentation; with both off [`solve`] never calls
/// [`NewtonProblem::factorize_with_residual`] or [`NewtonProblem::trial_merit`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Evaluation {
    /// "The factorisation evaluated the residual too": the Jacobian pass of the problem
    /// yields F(z) as well (e.g. an assembly of energy, gradient and Hessian at once).
    /// Newton then factorises by [`NewtonProblem::factorize_with_residual`] and takes
    /// F(z_k) from it for the step, the merit m(z_k) and the failure reports, replacing
    /// the residual it held (that of the accepted trial); F(z₀) is not evaluated
    /// separately before the first iteration.
    pub residual_with_factorization: bool,
    /// "Judge a trial by its merit alone" (backtracking only; natural monotonicity
    /// ignores it): every trial z + αΔz, the full step below the tolerance included, is
    /// judged by [`NewtonProblem::trial_merit`] (admissibility and merit in one call,
    /// no residual; [`TrialStep::trial_residual`] is `None`). The residual is then
    /// evaluated only at the accepted trial, by [`NewtonProblem::residual`] — or, with
    /// `residual_with_factorization`, not at all: the next factorisation yields it, and
    /// a converged iterate is returned without it ([`Progress::residual`] is `None`).
    pub merit_only: bool,
}

/// Which trial [`NewtonProblem::trial_merit`] judges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrialKind {
    /// The full step of a correction below the tolerance: taken without a merit test
    /// if admissible, and by the default [`NewtonProblem::converged`] the returned
    /// solution (a problem that reports the solution's residual may evaluate it here).
    Converging,
    /// A trial of the line search, judged by [`NewtonProblem::accept_step`].
    Search,
}

/// A square nonlinear system F(z) = 0 with a factorisable Jacobian, and the hooks of
/// the damped Newton (all optional).
pub trait NewtonProblem {
    /// The caller's error type (passed through as [`NewtonError::Problem`]).
    type Error;
    /// Number of unknowns n (= number of equations).
    fn size(&self) -> usize;
    /// Residual F(z) into `r` (length n). Non-finite entries are allowed; the Newton
    /// loop treats them as an inadmissible trial.
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), Self::Error>;
    /// Evaluate and factorise the Jacobian ∂F/∂z at `z`; later [`Self::solve`] calls use
    /// this factorisation.
    fn factorize(&mut self, z: &[f64]) -> Result<(), Self::Error>;
    /// Overwrite `b` with J⁻¹ b for the last factorised Jacobian.
    fn solve(&mut self, b: &mut [f64]) -> Result<(), Self::Error>;

    /// The damping strategy. Default: natural monotonicity.
    fn damping(&self) -> Damping {
        Damping::NaturalMonotonicity
    }
    /// The norm of a correction `v` at iterate `z` that is compared with the tolerance.
    /// Default: [`scaled_norm`].
    fn norm(&self, v: &[f64], z: &[f64]) -> f64 {
        scaled_norm(v, z)
    }
    /// The merit of backtracking at `z` with residual `r`. Default ½ Σ r_i².
    fn merit(&mut self, z: &[f64], r: &[f64]) -> f64 {
        let _ = z;
        0.5 * r.iter().map(|v| v * v).sum::<f64>()
    }
    /// Whether a trial point with a finite residual may be taken at all (e.g. ∂σS > 0).
    /// Default: every finite one.
    fn admissible(&mut self, trial: &[f64], r: &[f64]) -> bool {
        let _ = (trial, r);
        true
    }
    /// The backtracking test. Default: Armijo on the merit,
    /// m(z + αΔz) ≤ (1 − [`SUFFICIENT_DECREASE`] α) m(z).
    fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
        if t.trial_merit <= (1.0 - SUFFICIENT_DECREASE * t.damping) * t.merit {
            Verdict::Accept
        } else {
            Verdict::Reject
        }
    }
    /// Backtracking: refactorise a regularised Jacobian at `z` for `level` = 1, 2, …
    /// after a failed line search; `false` when no level is left. Default: none.
    fn regularise(&mut self, z: &[f64], level: usize) -> Result<bool, Self::Error> {
        let _ = (z, level);
        Ok(false)
    }
    /// Natural monotonicity: the round-off floor of the Newton correction at `z`, the
    /// Jacobian factorised there — the size, in [`Self::norm`], of J⁻¹δ for the rounding
    /// errors δ of the residual's evaluation at `z` (module documentation, "Round-off
    /// floor"). Asked only when a correction above the tolerance fails the
    /// monotonicity test. Default: `None` (no floor known: the tolerance alone decides).
    fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, Self::Error> {
        let _ = z;
        Ok(None)
    }
    /// Natural monotonicity: whether the residual at the converged iterate is evaluated
    /// before it is returned, to check that it is finite
    /// ([`NonFiniteWhat::ConvergedResidual`]; the residual itself is not returned). A
    /// problem that evaluates its equations at the returned point anyway answers `false`
    /// and saves that pass — bvp's collocation, whose residual estimate evaluates f at
    /// every stage there and fails on a non-finite value. Default: `true`.
    fn converged_residual(&self) -> bool {
        true
    }
    /// Backtracking: whether the iteration has converged after an accepted step.
    /// Default: a full step (α = 1) whose correction met the tolerance.
    fn converged(&mut self, p: &Progress<'_>) -> bool {
        p.damping == 1.0 && p.correction <= p.tolerance
    }
    /// Backtracking: whether to search along the step of regularisation `level` whose
    /// slope is F(z)ᵀΔz at all; `false` goes on to the next level without evaluating a
    /// trial (an energy minimiser searches along descent directions only, slope < 0).
    /// The full step of a correction below the tolerance is tried first regardless.
    /// Default: always.
    fn line_search(&mut self, level: usize, slope: f64) -> bool {
        let _ = (level, slope);
        true
    }
    /// Backtracking: the next α after the trial `t` (α = `t.damping`, judged admissible)
    /// was rejected; `previous` is (α, merit) of the admissible trial judged before it in
    /// the same search, if any. A value below `min_damping` ends the search. Default:
    /// α/2 (an inadmissible trial is always followed by α/2). [`skip_halvings`] skips a
    /// halving that a quadratic model of the merit rejects.
    fn next_damping(&mut self, t: &TrialStep<'_>, previous: Option<(f64, f64)>) -> f64 {
        let _ = previous;
        0.5 * t.damping
    }
    /// Backtracking: whether to linearise again at the rejected full-step trial `t`
    /// (α = 1 of the plain step, admissible) before halving — for a piecewise smooth F
    /// whose active set at the trial differs from the iterate's (e.g. a contact point
    /// entering its penalty a little ahead on the step, which the Jacobian at the
    /// iterate does not see). On `true` Newton factorises at the trial (the problem may
    /// keep its factorisation at the iterate for [`Self::restore_factorization`]) and
    /// judges the trial's own full Newton step, z + Δz + Δz', by [`Self::accept_step`]
    /// against m(z) with α = 1 and the correction ‖Δz'‖: taken if accepted, else the
    /// iterate's factorisation is restored and the line search goes on along Δz as if
    /// nothing had been tried. Default: `false`.
    fn relinearise(&mut self, t: &TrialStep<'_>) -> bool {
        let _ = t;
        false
    }
    /// After a [`Self::relinearise`] whose step was not taken (or whose factorisation
    /// or solve failed): make the factorisation at the iterate `z` the current one
    /// again. Default: [`Self::factorize`] at `z`.
    fn restore_factorization(&mut self, z: &[f64]) -> Result<(), Self::Error> {
        self.factorize(z)
    }
    /// Which evaluations share a pass ([`Evaluation`]). Default: none.
    fn evaluation(&self) -> Evaluation {
        Evaluation::default()
    }
    /// With [`Evaluation::residual_with_factorization`], used instead of
    /// [`Self::factorize`]: evaluate and factorise the Jacobian at `z` and write F(z)
    /// into `r` from the same pass. Default: `factorize` and `residual`, one after the
    /// other.
    fn factorize_with_residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), Self::Error> {
        self.factorize(z)?;
        self.residual(z, r)
    }
    /// With [`Evaluation::merit_only`], how backtracking judges a trial: `Some(m)` with
    /// its merit m (what [`Self::merit`] gives there) if the trial is admissible,
    /// `None` (or a non-finite m) if not. An error is reported at [`Stage::Residual`].
    /// Default: [`Self::residual`], [`Self::admissible`] and [`Self::merit`].
    fn trial_merit(&mut self, trial: &[f64], kind: TrialKind) -> Result<Option<f64>, Self::Error> {
        let _ = kind;
        let mut r = vec![0.0; self.size()];
        self.residual(trial, &mut r)?;
        if all_finite(&r) && self.admissible(trial, &r) {
            Ok(Some(self.merit(trial, &r)))
        } else {
            Ok(None)
        }
    }
}

/// The margin of [`skip_halvings`] on the model's largest accepted step, and on its
/// prediction of the previous trial: a merit with a kink ahead (its growth from the kink
/// on, not from α = 0) is less convex near α = 0 than the quadratic from α = 0 through
/// the trial, so the model's accepted steps are too few.
const SKIP_MARGIN: f64 = 2.0;

/// The next damping factor of a halving line search, α/4 instead of α/2 where a
/// quadratic model of the merit rejects α/2 and α/4 with a margin. The model q(s) = φ(0)
/// + φ'(0) s + C s² of φ(s) = m(z + sΔz) takes C from the rejected trial φ(`alpha`) =
/// `trial_merit`, with φ(0) = `merit` and φ'(0) = `slope` (< 0); the test accepts φ(s) ≤
/// φ(0) − `decrease`·s, under the model for s ≤ s* = (−φ'(0) − `decrease`)/C. The result
/// is α/4 if α/4 ≥ 2s* and α/4 ≥ `min_damping`, and if the model is borne out by the
/// `previous` trial (α₀, φ(α₀)) of the search: the merit fell from it, and q(α₀) ≥ φ(α₀)/2
/// (a merit that grows faster than quadratically, e.g. 10⁸× at α = 1 and 40× at ¼
/// beyond a stiff penalty's kink, is less convex near 0 than the model); else α/2 — so
/// the trials are those of plain halving less some the model rejects.
///
/// For Newton's step on the merit ½‖F‖² the slope is −2φ(0) (FᵀJΔz = −‖F‖²). Where a
/// kink of F lies a little ahead on the step (e.g. a contact point entering at a small
/// α), the merit beyond it grows like the squared overshoot (at α = 1 to 100–350 times
/// its start on the Exudyn drive) and every other halving down to the kink is skipped.
/// Replayed on the traced line searches of the catalogue's steady FE runs
/// (`string-drive-exudyn` at 64 … 512 elements, `string-drive`, `cosserat-drive`,
/// `cosserat-pulley`), each ends where plain halving ends (docs/performance.md, seventh
/// round).
///
/// Tried and not kept: the minimiser of the quadratic/cubic interpolation safeguarded
/// to [α/10, α/2] (Nocedal & Wright §3.5): on the Exudyn drive's load continuation,
/// whose merit at α = 1 is only 1.3–3× its start (active-set changes, not a quadratic
/// bump), it took α ≈ 0.1–0.25 where halving accepted ½, and 37 iterations instead of 11;
/// skips without the check against the previous trial (from α = 1 on, or up to α/8)
/// changed the outcome of some searches (docs/performance.md, seventh round).
pub fn skip_halvings(merit: f64, slope: f64, decrease: f64, alpha: f64, trial_merit: f64, previous: Option<(f64, f64)>, min_damping: f64) -> f64 {
    let c = (trial_merit - merit - slope * alpha) / (alpha * alpha);
    let accepted = (-slope - decrease) / c;
    let half = 0.5 * alpha;
    let borne_out = previous.is_some_and(|(a0, m0)| m0 > trial_merit && m0 <= SKIP_MARGIN * (merit + slope * a0 + c * a0 * a0));
    if c > 0.0 && accepted.is_finite() && borne_out && 0.5 * half >= SKIP_MARGIN * accepted && 0.5 * half >= min_damping {
        0.5 * half
    } else {
        half
    }
}

/// ‖v‖_z = max_i |v_i| / (1 + |z_i|).
pub fn scaled_norm(v: &[f64], z: &[f64]) -> f64 {
    v.iter().zip(z).fold(0.0_f64, |m, (&vi, &zi)| m.max(vi.abs() / (1.0 + zi.abs())))
}

/// Whether every entry is finite — one pass without an early exit, which vectorises
/// (the early-exit `all` compared one entry per branch: ~1.5 % of a gauss8 elastica
/// solve, run 11 of `docs/performance.md`'s issue-17 section).
fn all_finite(v: &[f64]) -> bool {
    v.iter().fold(true, |ok, x| ok & x.is_finite())
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// (α, merit, trial, its residual if evaluated) of the best admissible trial of a
/// backtracking search.
type BestTrial = (f64, f64, Vec<f64>, Option<Vec<f64>>);

/// A step linearised at a trial and taken ([`NewtonProblem::relinearise`]): the new
/// iterate, its residual if evaluated, its merit and the trial's correction ‖Δz'‖.
type Relinearised = (Vec<f64>, Option<Vec<f64>>, f64, f64);

/// The state shared by both damping strategies.
struct Run<'p, P: NewtonProblem> {
    problem: &'p mut P,
    opts: NewtonOptions,
    stats: NewtonStats,
    /// ‖F‖_∞ at the last accepted iterate (with
    /// [`Evaluation::residual_with_factorization`]: at the last factorised one).
    residual: f64,
    evaluation: Evaluation,
}

impl<P: NewtonProblem> Run<'_, P> {
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        self.stats.residual_evaluations += 1;
        let iteration = self.stats.iterations;
        let problem = &mut *self.problem;
        timed(Phase::Residuals, || problem.residual(z, r)).map_err(|error| NewtonError::Problem { iteration, stage: Stage::Residual, error })
    }

    /// Factorise at `z`; with [`Evaluation::residual_with_factorization`] `r` becomes
    /// F(z) from the same pass.
    fn factorize(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        let iteration = self.stats.iterations + 1;
        let failed = |error| NewtonError::Problem { iteration, stage: Stage::Factorize, error };
        let problem = &mut *self.problem;
        if self.evaluation.residual_with_factorization {
            timed(Phase::Assembly, || problem.factorize_with_residual(z, r)).map_err(failed)?;
            if !all_finite(r) {
                let what = if iteration == 1 { NonFiniteWhat::InitialResidual } else { NonFiniteWhat::IterateResidual };
                return Err(NewtonError::NonFinite { iteration, what });
            }
            self.residual = max_abs(r);
        } else {
            timed(Phase::Assembly, || problem.factorize(z)).map_err(failed)?;
        }
        self.stats.iterations += 1;
        phases::count(phases::Step::NewtonIteration, 1);
        self.stats.factorisations += 1;
        Ok(())
    }

    /// Judge `trial`: `Some(merit)` if it is admissible — by its residual (into
    /// `r_trial`) or, with [`Evaluation::merit_only`], by its merit alone.
    fn judge(&mut self, trial: &[f64], r_trial: &mut [f64], kind: TrialKind) -> Result<Option<f64>, NewtonError<P::Error>> {
        if self.evaluation.merit_only {
            self.stats.merit_evaluations += 1;
            let iteration = self.stats.iterations;
            let problem = &mut *self.problem;
            let merit = timed(Phase::Residuals, || problem.trial_merit(trial, kind))
                .map_err(|error| NewtonError::Problem { iteration, stage: Stage::Residual, error })?;
            return Ok(merit.filter(|m| m.is_finite()));
        }
        self.residual(trial, r_trial)?;
        if all_finite(r_trial) && self.problem.admissible(trial, r_trial) {
            Ok(Some(self.problem.merit(trial, r_trial)))
        } else {
            Ok(None)
        }
    }

    /// [`NewtonProblem::relinearise`]'s attempt: factorise at the rejected full-step
    /// `trial` of the iterate `z` (residual `r`, merit `merit`; `r_trial` the trial's
    /// residual if evaluated), take the trial's Newton step Δz' and judge z + Δz + Δz'
    /// against m(z). `Some((point, its residual if evaluated, its merit, ‖Δz'‖))` if
    /// accepted; `None` after restoring the factorisation at `z`.
    #[allow(clippy::too_many_arguments)]
    fn relinearised(&mut self, z: &[f64], r: &[f64], trial: &[f64], r_trial: &[f64], merit: f64, slope: f64, iteration: usize) -> Result<Option<Relinearised>, NewtonError<P::Error>> {
        let n = z.len();
        let merit_only = self.evaluation.merit_only;
        self.stats.relinearisations += 1;
        let residual = self.residual;
        let mut r_lin = r_trial.to_vec();
        let mut attempt = || -> Result<Option<Relinearised>, NewtonError<P::Error>> {
            // without the residual from the factorisation and trials judged by merit
            // alone, F(trial) is not known yet
            if merit_only && !self.evaluation.residual_with_factorization {
                self.residual(trial, &mut r_lin)?;
            }
            self.factorize(trial, &mut r_lin)?;
            let mut step = vec![0.0; n];
            self.newton_step(&r_lin, &mut step)?;
            if !all_finite(&step) {
                return Ok(None);
            }
            let correction = self.problem.norm(&step, trial);
            let point: Vec<f64> = trial.iter().zip(&step).map(|(a, b)| a + b).collect();
            let mut r_point = vec![0.0; n];
            let Some(m) = self.judge(&point, &mut r_point, TrialKind::Search)? else { return Ok(None) };
            let whole: Vec<f64> = point.iter().zip(z).map(|(a, b)| a - b).collect();
            let t = TrialStep {
                iteration,
                level: 0,
                damping: 1.0,
                z,
                step: &whole,
                trial: &point,
                residual: r,
                trial_residual: (!merit_only).then_some(&r_point[..]),
                merit,
                trial_merit: m,
                slope,
                correction,
                tolerance: self.opts.tolerance,
            };
            Ok((self.problem.accept_step(&t) == Verdict::Accept).then(|| (point, (!merit_only).then_some(r_point), m, correction)))
        };
        // a failure at the trial (its factorisation or step) only ends the attempt
        if let Ok(Some(taken)) = attempt() {
            self.stats.relinearisations_taken += 1;
            return Ok(Some(taken));
        }
        let problem = &mut *self.problem;
        timed(Phase::Assembly, || problem.restore_factorization(z)).map_err(|error| NewtonError::Problem { iteration, stage: Stage::Factorize, error })?;
        self.residual = residual;
        Ok(None)
    }

    /// `out` = −J⁻¹ `r`.
    fn newton_step(&mut self, r: &[f64], out: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        for (d, &ri) in out.iter_mut().zip(r) {
            *d = -ri;
        }
        self.solve(out)
    }

    fn solve(&mut self, b: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        let iteration = self.stats.iterations;
        let problem = &mut *self.problem;
        timed(Phase::LinearSolves, || problem.solve(b)).map_err(|error| NewtonError::Problem { iteration, stage: Stage::Solve, error })?;
        self.stats.solves += 1;
        Ok(())
    }

    /// [`NewtonProblem::correction_floor`] at `z` (a failure is reported at
    /// [`Stage::Solve`]: the floor is a solve with the current factorisation).
    fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, NewtonError<P::Error>> {
        let iteration = self.stats.iterations;
        let problem = &mut *self.problem;
        let floor = timed(Phase::LinearSolves, || problem.correction_floor(z)).map_err(|error| NewtonError::Problem { iteration, stage: Stage::Solve, error })?;
        if floor.is_some() {
            self.stats.solves += 1;
        }
        Ok(floor)
    }

    fn max_iterations(&self, correction: f64) -> NewtonError<P::Error> {
        NewtonError::MaxIterations {
            iterations: self.stats.iterations,
            correction,
            residual: self.residual,
            tolerance: self.opts.tolerance,
        }
    }

    fn natural_monotonicity(&mut self, z: &mut [f64], r: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        let n = z.len();
        let tol = self.opts.tolerance;
        let mut dz = vec![0.0; n];
        let mut dbar = vec![0.0; n];
        let mut trial = vec![0.0; n];
        let mut lambda: f64 = 1.0;
        let mut last_norm = f64::INFINITY;
        loop {
            if self.stats.iterations >= self.opts.max_iterations {
                return Err(self.max_iterations(last_norm));
            }
            self.factorize(z, r)?;
            self.newton_step(r, &mut dz)?;
            if !all_finite(&dz) {
                return Err(NewtonError::SingularStep { iteration: self.stats.iterations, residual: self.residual });
            }
            let norm = self.problem.norm(&dz, z);
            last_norm = norm;
            self.stats.last_correction = norm;
            if norm <= tol {
                for (t, (&zi, &d)) in trial.iter_mut().zip(z.iter().zip(&dz)) {
                    *t = zi + d;
                }
                return self.finish(z, &trial, r);
            }
            let mut floor_asked = false;
            loop {
                for (t, (&zi, &d)) in trial.iter_mut().zip(z.iter().zip(&dz)) {
                    *t = zi + lambda * d;
                }
                self.residual(&trial, r)?;
                let mut accepted = false;
                let mut mu = lambda / 2.0;
                if all_finite(r) && self.problem.admissible(&trial, r) {
                    self.newton_step(r, &mut dbar)?;
                    if all_finite(&dbar) {
                        let nbar = self.problem.norm(&dbar, z);
                        let theta = nbar / norm;
                        if theta <= 1.0 - lambda / 4.0 {
                            accepted = true;
                            if lambda == 1.0 && nbar <= tol {
                                for (t, &b) in trial.iter_mut().zip(&dbar) {
                                    *t += b;
                                }
                                self.stats.last_correction = nbar;
                                return self.finish(z, &trial, r);
                            }
                        } else {
                            let diff: Vec<f64> = dbar.iter().zip(&dz).map(|(&b, &d)| b - (1.0 - lambda) * d).collect();
                            let dn = self.problem.norm(&diff, z);
                            if dn > 0.0 {
                                mu = 0.5 * norm * lambda * lambda / dn;
                            }
                        }
                    }
                }
                if accepted {
                    break;
                }
                if !floor_asked {
                    floor_asked = true;
                    if self.correction_floor(z)?.is_some_and(|floor| norm <= floor) {
                        for (t, (&zi, &d)) in trial.iter_mut().zip(z.iter().zip(&dz)) {
                            *t = zi + d;
                        }
                        return self.finish(z, &trial, r);
                    }
                }
                lambda = (mu.min(lambda / 2.0)).max(lambda / 10.0);
                self.stats.min_damping_used = self.stats.min_damping_used.min(lambda);
                if lambda < self.opts.min_damping {
                    return Err(NewtonError::DampingExhausted {
                        iteration: self.stats.iterations,
                        damping: lambda,
                        correction: norm,
                        residual: self.residual,
                        tolerance: tol,
                    });
                }
            }
            z.copy_from_slice(&trial);
            // `r` holds F(trial) = F(z_{k+1}).
            self.residual = max_abs(r);
            lambda = if lambda == 1.0 { 1.0 } else { (2.0 * lambda).min(1.0) };
        }
    }

    /// Evaluate the residual at the converged `trial` (unless the problem declines,
    /// [`NewtonProblem::converged_residual`]) and take it.
    fn finish(&mut self, z: &mut [f64], trial: &[f64], r: &mut [f64]) -> Result<(), NewtonError<P::Error>> {
        if !self.problem.converged_residual() {
            z.copy_from_slice(trial);
            return Ok(());
        }
        self.residual(trial, r)?;
        if !all_finite(r) {
            return Err(NewtonError::NonFinite {
                iteration: self.stats.iterations,
                what: NonFiniteWhat::ConvergedResidual,
            });
        }
        z.copy_from_slice(trial);
        Ok(())
    }

    fn backtracking(&mut self, z: &mut [f64], r: &mut [f64], take_best: bool) -> Result<(), NewtonError<P::Error>> {
        let n = z.len();
        let tol = self.opts.tolerance;
        let merit_only = self.evaluation.merit_only;
        let mut step = vec![0.0; n];
        let mut trial = vec![0.0; n];
        let mut r_trial = vec![0.0; n];
        let mut last_norm = f64::INFINITY;
        loop {
            if self.stats.iterations >= self.opts.max_iterations {
                return Err(self.max_iterations(last_norm));
            }
            self.factorize(z, r)?;
            let merit = self.problem.merit(z, r);
            let mut level = 0;
            let mut best: Option<BestTrial> = None;
            // (α, merit) of the accepted trial; whether `r_trial` holds its residual
            let mut best_trial = false;
            let (alpha, merit_after, evaluated) = 'levels: loop {
                self.newton_step(r, &mut step)?;
                // a non-finite step (numerically singular Jacobian) fails its level
                let finite = all_finite(&step);
                if finite {
                    let slope: f64 = step.iter().zip(r.iter()).map(|(s, g)| s * g).sum();
                    if level == 0 {
                        last_norm = self.problem.norm(&step, z);
                        self.stats.last_correction = last_norm;
                        if last_norm <= tol {
                            for i in 0..n {
                                trial[i] = z[i] + step[i];
                            }
                            if let Some(m) = self.judge(&trial, &mut r_trial, TrialKind::Converging)? {
                                break 'levels (1.0, m, !merit_only);
                            }
                        }
                    }
                    if self.problem.line_search(level, slope) {
                        let mut alpha = 1.0;
                        // (α, merit) of the last admissible trial of this search
                        let mut previous: Option<(f64, f64)> = None;
                        while alpha >= self.opts.min_damping {
                            for i in 0..n {
                                trial[i] = z[i] + alpha * step[i];
                            }
                            if let Some(trial_merit) = self.judge(&trial, &mut r_trial, TrialKind::Search)? {
                                let t = TrialStep {
                                    iteration: self.stats.iterations,
                                    level,
                                    damping: alpha,
                                    z,
                                    step: &step,
                                    trial: &trial,
                                    residual: r,
                                    trial_residual: (!merit_only).then_some(&r_trial[..]),
                                    merit,
                                    trial_merit,
                                    slope,
                                    correction: last_norm,
                                    tolerance: tol,
                                };
                                match self.problem.accept_step(&t) {
                                    Verdict::Accept => break 'levels (alpha, trial_merit, !merit_only),
                                    Verdict::Abandon => break,
                                    Verdict::Reject => {}
                                }
                                let next = self.problem.next_damping(&t, previous);
                                if alpha == 1.0 && level == 0 && self.problem.relinearise(&t) {
                                    let iteration = self.stats.iterations;
                                    if let Some((point, r_point, m, correction)) = self.relinearised(z, r, &trial, &r_trial, merit, slope, iteration)? {
                                        trial = point;
                                        if let Some(rp) = r_point {
                                            r_trial = rp;
                                        }
                                        last_norm = correction;
                                        self.stats.last_correction = correction;
                                        break 'levels (1.0, m, !merit_only);
                                    }
                                }
                                if take_best && best.as_ref().is_none_or(|b| trial_merit < b.1) {
                                    best = Some((alpha, trial_merit, trial.clone(), (!merit_only).then(|| r_trial.clone())));
                                }
                                previous = Some((alpha, trial_merit));
                                alpha = next;
                                continue;
                            }
                            alpha *= 0.5;
                        }
                    }
                }
                level += 1;
                let iteration = self.stats.iterations;
                let problem = &mut *self.problem;
                let regularised = timed(Phase::Assembly, || problem.regularise(z, level))
                    .map_err(|error| NewtonError::Problem { iteration, stage: Stage::Factorize, error })?;
                if regularised {
                    self.stats.regularisations += 1;
                    self.stats.factorisations += 1;
                    continue;
                }
                match best.take() {
                    Some((a, m, t, rt)) => {
                        best_trial = true;
                        trial = t;
                        let evaluated = rt.is_some();
                        if let Some(rt) = rt {
                            r_trial = rt;
                        }
                        break 'levels (a, m, evaluated);
                    }
                    None if !finite => return Err(NewtonError::SingularStep { iteration, residual: self.residual }),
                    None => {
                        return Err(NewtonError::LineSearchFailed {
                            iteration,
                            correction: last_norm,
                            merit,
                            residual: self.residual,
                            tolerance: tol,
                        })
                    }
                }
            };
            self.stats.min_damping_used = self.stats.min_damping_used.min(alpha);
            z.copy_from_slice(&trial);
            let known = if evaluated {
                r.copy_from_slice(&r_trial);
                true
            } else if !self.evaluation.residual_with_factorization {
                self.residual(z, r)?;
                if !all_finite(r) {
                    return Err(NewtonError::NonFinite { iteration: self.stats.iterations, what: NonFiniteWhat::IterateResidual });
                }
                true
            } else {
                false
            };
            if known {
                self.residual = max_abs(r);
            }
            let progress = Progress {
                iteration: self.stats.iterations,
                damping: alpha,
                correction: last_norm,
                tolerance: tol,
                merit_before: merit,
                merit_after,
                z,
                residual: known.then_some(&r[..]),
                best_trial,
            };
            if self.problem.converged(&progress) {
                return Ok(());
            }
        }
    }
}

/// Solve F(z) = 0 by the damped Newton method of the module documentation, starting
/// from and overwriting `z` (length n). On error `z` holds the last accepted iterate.
///
/// # Errors
/// [`NewtonError`]: invalid options or dimensions, a non-finite start, the iteration
/// limit, exhausted damping or line search, a singular step, or the problem's own error.
pub fn solve<P: NewtonProblem>(
    problem: &mut P,
    z: &mut [f64],
    opts: &NewtonOptions,
) -> Result<NewtonStats, NewtonError<P::Error>> {
    opts.validate()?;
    let n = problem.size();
    if z.len() != n {
        return Err(NewtonError::DimensionMismatch { expected: n, got: z.len() });
    }
    if !all_finite(z) {
        return Err(NewtonError::NonFinite { iteration: 0, what: NonFiniteWhat::InitialIterate });
    }
    let damping = problem.damping();
    let evaluation = problem.evaluation();
    let mut run = Run {
        problem,
        opts: *opts,
        stats: NewtonStats { min_damping_used: 1.0, ..Default::default() },
        residual: f64::INFINITY,
        evaluation,
    };
    let mut r = vec![0.0; n];
    // with the residual from the factorisation, F(z₀) comes with the first one
    if !evaluation.residual_with_factorization {
        run.residual(z, &mut r)?;
        if !all_finite(&r) {
            return Err(NewtonError::NonFinite { iteration: 0, what: NonFiniteWhat::InitialResidual });
        }
        run.residual = max_abs(&r);
    }
    match damping {
        Damping::NaturalMonotonicity => run.natural_monotonicity(z, &mut r)?,
        Damping::Backtracking { take_best } => run.backtracking(z, &mut r, take_best)?,
    }
    Ok(run.stats)
}

/// (row, col, value) triplets of a sparse matrix; duplicates are summed.
#[derive(Debug, Clone, Default)]
pub struct Triplets {
    /// Row indices.
    pub rows: Vec<usize>,
    /// Column indices.
    pub cols: Vec<usize>,
    /// Values.
    pub vals: Vec<f64>,
}

impl Triplets {
    /// Empty the lists (keeping their capacity).
    pub fn clear(&mut self) {
        self.rows.clear();
        self.cols.clear();
        self.vals.clear();
    }

    /// Append the entry `v` at (`r`, `c`).
    pub fn push(&mut self, r: usize, c: usize, v: f64) {
        self.rows.push(r);
        self.cols.push(c);
        self.vals.push(v);
    }
}

/// A system given by its residual and its Jacobian as a sparse matrix; [`Sparse`] makes
/// it a [`NewtonProblem`] factorised by a [`TripletLu`] (with its damping and norm; a
/// problem that needs the other hooks implements [`NewtonProblem`] itself).
pub trait SparseSystem {
    /// The caller's error type; sparse LU failures convert into it.
    type Error: From<LinearError>;
    /// Number of unknowns n.
    fn size(&self) -> usize;
    /// Residual F(z) into `r`.
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), Self::Error>;
    /// The Jacobian ∂F/∂z at `z` into `jac` (cleared by the caller).
    fn jacobian(&mut self, z: &[f64], jac: &mut Triplets) -> Result<(), Self::Error>;
    /// The damping strategy ([`NewtonProblem::damping`]). Default: natural monotonicity.
    fn damping(&self) -> Damping {
        Damping::NaturalMonotonicity
    }
    /// The tolerance norm ([`NewtonProblem::norm`]). Default: [`scaled_norm`].
    fn norm(&self, v: &[f64], z: &[f64]) -> f64 {
        scaled_norm(v, z)
    }
}

/// A [`SparseSystem`] with its LU (kept across solves: the symbolic factorisation is
/// redone only when the Jacobian's pattern changes).
#[derive(Debug)]
pub struct Sparse<S: SparseSystem> {
    /// The system.
    pub system: S,
    /// Its LU.
    pub lu: TripletLu<S::Error>,
    jac: Triplets,
}

impl<S: SparseSystem> Sparse<S> {
    /// `system` with an empty LU.
    pub fn new(system: S) -> Self {
        Self { system, lu: TripletLu::new(), jac: Triplets::default() }
    }
}

impl<S: SparseSystem> NewtonProblem for Sparse<S> {
    type Error = S::Error;
    fn size(&self) -> usize {
        self.system.size()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), S::Error> {
        self.system.residual(z, r)
    }
    fn factorize(&mut self, z: &[f64]) -> Result<(), S::Error> {
        self.jac.clear();
        self.system.jacobian(z, &mut self.jac)?;
        self.lu.factorize(self.system.size(), &self.jac.rows, &self.jac.cols, &self.jac.vals)
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), S::Error> {
        self.lu.solve_in_place(b)
    }
    fn damping(&self) -> Damping {
        self.system.damping()
    }
    fn norm(&self, v: &[f64], z: &[f64]) -> f64 {
        self.system.norm(v, z)
    }
}

#[cfg(test)]
mod tests {
    /// The skip on a quadratic merit 1 − 2s + Cs² (Armijo's decrease 10⁻⁴, s* = (2 −
    /// 10⁻⁴)/C the largest accepted step): α/4 where α/4 ≥ 2s* and the previous trial
    /// bears the model out, never below the minimum damping, else plain halving.
    #[test]
    fn skip_halvings_skips_what_the_model_rejects_with_a_margin() {
        let q = |c: f64, a: f64| 1.0 - 2.0 * a + c * a * a;
        // the previous trial at 2α on the same quadratic
        let skip = |c: f64, alpha: f64, min: f64| super::skip_halvings(1.0, -2.0, 1e-4, alpha, q(c, alpha), Some((2.0 * alpha, q(c, 2.0 * alpha))), min);
        // C = 9 (s* = 0.222) from α = ½: ⅛ < 2s*, ¼ is tried; C = 351 (s* = 5.7e-3): ⅛
        assert_eq!(skip(9.0, 0.5, 1e-3), 0.25);
        assert_eq!(skip(351.0, 0.5, 1e-3), 0.125);
        // from α = 1/128 with C = 1e6: 1/512, but not below the minimum damping
        assert_eq!(skip(1e6, 1.0 / 128.0, 1.0 / 1024.0), 1.0 / 512.0);
        assert_eq!(skip(1e6, 1.0 / 128.0, 3e-3), 1.0 / 256.0);
        // s* with its margin exactly at α/4 (C = 16(2 − 10⁻⁴)/α): α/4
        assert_eq!(skip(16.0 * (2.0 - 1e-4) / 0.5, 0.5, 1e-6), 0.125);
        // no previous trial (α = 1): halving
        assert_eq!(super::skip_halvings(1.0, -2.0, 1e-4, 1.0, q(351.0, 1.0), None, 1e-6), 0.5);
        // the merit did not fall from the previous trial, or grew from it faster than
        // the model (10⁸ at α = 1, 40 at ¼: q(1) = 634): halving
        assert_eq!(super::skip_halvings(1.0, -2.0, 1e-4, 0.5, q(351.0, 0.5), Some((1.0, q(351.0, 0.5))), 1e-6), 0.25);
        assert_eq!(super::skip_halvings(1.0, -2.0, 1e-4, 0.25, 40.0, Some((1.0, 1e8)), 1e-6), 0.125);
        // … within the margin of 2 it skips: 40 at ¼, 1200 at 1
        assert_eq!(super::skip_halvings(1.0, -2.0, 1e-4, 0.25, 40.0, Some((1.0, 1200.0)), 1e-6), 0.0625);
        // flat or concave model, no slope: halving
        assert_eq!(super::skip_halvings(1.0, -2.0, 1e-4, 0.5, -0.5, Some((1.0, 3.0)), 1e-6), 0.25);
        assert_eq!(super::skip_halvings(0.0, 0.0, 0.0, 0.25, 0.0, Some((0.5, 1.0)), 1e-6), 0.125);
    }

    /// F(x) = x − 1 + K⟨x − a⟩ (K = 10⁴, a = 0.003) from x = 0: the Jacobian there does
    /// not see the kink a little ahead on the step, whose merit at α = 1 is 10⁸ times the
    /// start's — the situation of a contact point entering along the semismooth steady
    /// step. Halving tries 1, ½, …, 1/256 before 1/512 is accepted; the skip tries 1, ½,
    /// then every other α of halving's grid while the model holds, and reaches the same
    /// root with fewer residuals.
    #[test]
    fn skipped_halvings_reach_the_root_with_fewer_trials() {
        struct Kink {
            skip: bool,
            slope: f64,
            trials: Vec<f64>,
            iterates: Vec<f64>,
        }
        const K: f64 = 1e4;
        const A: f64 = 0.003;
        impl super::NewtonProblem for Kink {
            type Error = super::LinearError;
            fn size(&self) -> usize {
                1
            }
            fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), super::LinearError> {
                r[0] = z[0] - 1.0 + K * (z[0] - A).max(0.0);
                Ok(())
            }
            fn factorize(&mut self, z: &[f64]) -> Result<(), super::LinearError> {
                self.iterates.push(z[0]);
                self.slope = if z[0] > A { 1.0 + K } else { 1.0 };
                Ok(())
            }
            fn solve(&mut self, b: &mut [f64]) -> Result<(), super::LinearError> {
                b[0] /= self.slope;
                Ok(())
            }
            fn damping(&self) -> super::Damping {
                super::Damping::Backtracking { take_best: true }
            }
            fn next_damping(&mut self, t: &super::TrialStep<'_>, previous: Option<(f64, f64)>) -> f64 {
                self.trials.push(t.damping);
                if self.skip {
                    super::skip_halvings(t.merit, -2.0 * t.merit, super::SUFFICIENT_DECREASE * t.merit, t.damping, t.trial_merit, previous, 1.0 / 1024.0)
                } else {
                    0.5 * t.damping
                }
            }
        }
        let opts = super::NewtonOptions { tolerance: 1e-12, max_iterations: 30, min_damping: 1.0 / 1024.0 };
        let root = (1.0 + K * A) / (1.0 + K);
        let mut runs = vec![];
        for skip in [false, true] {
            let mut p = Kink { skip, slope: 0.0, trials: vec![], iterates: vec![] };
            let mut z = [0.0];
            let stats = super::solve(&mut p, &mut z, &opts).unwrap();
            assert!((z[0] - root).abs() < 1e-14, "{z:?}");
            runs.push((stats, p.trials, p.iterates, z[0]));
        }
        let (halving, skipped) = (&runs[0], &runs[1]);
        // halving's first search rejects 1 … 1/256; the skip tries every other α of
        // halving's grid (powers of two) and ends at the same root with fewer residuals
        assert_eq!(&halving.1[..9], &[1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125, 0.015625, 0.0078125, 0.00390625]);
        assert_eq!(&skipped.1[..2], &[1.0, 0.5]);
        assert!(skipped.1.iter().all(|a| a.log2().fract() == 0.0), "{:?}", skipped.1);
        assert!(skipped.0.residual_evaluations + 8 <= halving.0.residual_evaluations, "{:?} against {:?}", skipped.0, halving.0);
    }

    /// F(x) = x − 1 + K⟨x − a⟩ as above, with [`NewtonProblem::relinearise`] asked
    /// where the rejected full step crosses the kink. Linearised at the trial, the
    /// trial's Newton step lands on the root: one relinearisation, taken, and the root
    /// with at most four residuals where halving spends 35. With a wrong Jacobian at the
    /// trial (slope 1 there: its step overshoots far to the left, rejected) the
    /// factorisation at the iterate is restored each time and the search goes on along
    /// the iterate's step exactly as halving's: the same α, the same iterates, one
    /// residual and one factorisation more per attempt.
    #[test]
    fn relinearising_at_a_trial_past_the_kink() {
        struct Kink {
            relinearise: bool,
            wrong_at_trial: bool,
            at_trial: bool,
            slope: f64,
            trials: Vec<f64>,
            iterates: Vec<f64>,
            /// The factorisations at a trial.
            at_trials: Vec<f64>,
            restored: Vec<f64>,
        }
        const K: f64 = 1e4;
        const A: f64 = 0.003;
        impl super::NewtonProblem for Kink {
            type Error = super::LinearError;
            fn size(&self) -> usize {
                1
            }
            fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), super::LinearError> {
                r[0] = z[0] - 1.0 + K * (z[0] - A).max(0.0);
                Ok(())
            }
            fn factorize(&mut self, z: &[f64]) -> Result<(), super::LinearError> {
                if self.at_trial {
                    self.at_trials.push(z[0]);
                } else {
                    self.iterates.push(z[0]);
                }
                self.slope = if z[0] > A && !(self.at_trial && self.wrong_at_trial) { 1.0 + K } else { 1.0 };
                self.at_trial = false;
                Ok(())
            }
            fn solve(&mut self, b: &mut [f64]) -> Result<(), super::LinearError> {
                b[0] /= self.slope;
                Ok(())
            }
            fn damping(&self) -> super::Damping {
                super::Damping::Backtracking { take_best: true }
            }
            fn next_damping(&mut self, t: &super::TrialStep<'_>, _previous: Option<(f64, f64)>) -> f64 {
                self.trials.push(t.damping);
                0.5 * t.damping
            }
            fn relinearise(&mut self, t: &super::TrialStep<'_>) -> bool {
                self.at_trial = self.relinearise && t.z[0] <= A && t.trial[0] > A;
                self.at_trial
            }
            fn restore_factorization(&mut self, z: &[f64]) -> Result<(), super::LinearError> {
                self.restored.push(z[0]);
                self.slope = if z[0] > A { 1.0 + K } else { 1.0 };
                Ok(())
            }
        }
        let opts = super::NewtonOptions { tolerance: 1e-12, max_iterations: 30, min_damping: 1.0 / 1024.0 };
        let root = (1.0 + K * A) / (1.0 + K);
        let run = |relinearise: bool, wrong_at_trial: bool| {
            let mut p = Kink { relinearise, wrong_at_trial, at_trial: false, slope: 0.0, trials: vec![], iterates: vec![], at_trials: vec![], restored: vec![] };
            let mut z = [0.0];
            let stats = super::solve(&mut p, &mut z, &opts).unwrap();
            assert!((z[0] - root).abs() < 1e-14, "{z:?}");
            (stats, p)
        };
        let (plain, plain_p) = run(false, false);
        let (taken, taken_p) = run(true, false);
        assert_eq!((taken.relinearisations, taken.relinearisations_taken), (1, 1));
        assert_eq!(plain.relinearisations, 0);
        // the iterate 0, then the trial 1 (factorised there), then the root
        assert_eq!(taken_p.at_trials, vec![1.0]);
        assert_eq!(taken_p.iterates[0], 0.0);
        assert!((taken_p.iterates[1] - root).abs() < 1e-14, "{:?}", taken_p.iterates);
        assert!(taken_p.restored.is_empty());
        assert!(taken.residual_evaluations <= 4 && taken.residual_evaluations + 30 <= plain.residual_evaluations, "{taken:?} against {plain:?}");
        // the relinearised steps are not taken (each full step from the left of the
        // kink tries one): back to the iterate's search each time, which goes on as
        // halving's
        let (rejected, rejected_p) = run(true, true);
        let k = rejected.relinearisations;
        assert!(k >= 1 && rejected.relinearisations_taken == 0, "{rejected:?}");
        assert_eq!(rejected_p.at_trials.len(), k);
        assert_eq!(rejected_p.restored.len(), k);
        assert!(rejected_p.restored.iter().all(|z| rejected_p.iterates.contains(z) && *z <= A), "{:?}", rejected_p.restored);
        assert_eq!(rejected_p.trials, plain_p.trials);
        assert_eq!(rejected_p.iterates, plain_p.iterates);
        assert_eq!(rejected.residual_evaluations, plain.residual_evaluations + k);
        assert_eq!(rejected.iterations, plain.iterations + k);
    }

    use super::*;

    /// F(z) = ((z + 10⁴) − 10⁴) − 0.3: the root 0.3, J = 1, but z + 10⁴ is rounded to
    /// the grid of ulp(10⁴) = 2⁻³⁹ ≈ 1.8e-12, on which 0.3 lies 0.4 of a step from a
    /// point, so the computed |F| never falls below ≈ 7e-13: the correction's round-off
    /// floor. `floor` says whether [`NewtonProblem::correction_floor`] reports it,
    /// u (|z| + 2·10⁴ + 0.3) / (1 + |z|) (the rounding of the two sums, in the scaled
    /// norm).
    struct Snapped {
        floor: bool,
    }

    impl NewtonProblem for Snapped {
        type Error = LinearError;
        fn size(&self) -> usize {
            1
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            r[0] = ((z[0] + 1e4) - 1e4) - 0.3;
            Ok(())
        }
        fn factorize(&mut self, _: &[f64]) -> Result<(), LinearError> {
            Ok(())
        }
        fn solve(&mut self, _: &mut [f64]) -> Result<(), LinearError> {
            Ok(())
        }
        fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, LinearError> {
            let u = f64::EPSILON / 2.0;
            Ok(self.floor.then(|| u * (z[0].abs() + 2e4 + 0.3) / (1.0 + z[0].abs())))
        }
    }

    /// A tolerance (1e-15) below the round-off floor (≈ 5e-13 scaled): without the floor
    /// natural monotonicity stalls there and fails with the damping exhausted; with it the
    /// stalled correction is recognised and the iterate is the root to within the floor
    /// (|z − 0.3| ≤ 2 ulp(10⁴) ≈ 3.6e-12), after the one full step from z = 1 and one
    /// stalled iteration.
    #[test]
    fn natural_monotonicity_stops_at_the_round_off_floor() {
        let opts = NewtonOptions { tolerance: 1e-15, ..Default::default() };
        let mut z = [1.0];
        let err = solve(&mut Snapped { floor: false }, &mut z, &opts).unwrap_err();
        assert!(matches!(err, NewtonError::DampingExhausted { correction, .. } if correction > 1e-13 && correction < 2e-12), "{err}");
        let mut z = [1.0];
        let stats = solve(&mut Snapped { floor: true }, &mut z, &opts).unwrap();
        assert!((z[0] - 0.3).abs() <= 2.0 * 2f64.powi(-39), "z = {}", z[0]);
        assert_eq!(stats.iterations, 2, "{stats:?}");
        assert!(stats.last_correction > opts.tolerance && stats.last_correction < 2e-12, "{stats:?}");
    }

    /// F(z) = z² − 2 with the residual calls counted; `check` is its
    /// [`NewtonProblem::converged_residual`].
    struct Root2 {
        check: bool,
        residual_calls: usize,
        j: f64,
    }

    impl NewtonProblem for Root2 {
        type Error = LinearError;
        fn size(&self) -> usize {
            1
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            self.residual_calls += 1;
            r[0] = z[0] * z[0] - 2.0;
            Ok(())
        }
        fn factorize(&mut self, z: &[f64]) -> Result<(), LinearError> {
            self.j = 2.0 * z[0];
            Ok(())
        }
        fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
            b[0] /= self.j;
            Ok(())
        }
        fn converged_residual(&self) -> bool {
            self.check
        }
    }

    /// Natural monotonicity without the converged iterate's residual: the same iterate
    /// and counters to the bit, one residual pass fewer (from z = 10: damped first steps,
    /// then the simplified correction below the tolerance taken, and from z = √2 − 1.4e-5:
    /// a first full correction below a loose tolerance).
    #[test]
    fn natural_monotonicity_can_skip_the_converged_residual() {
        for (start, tolerance) in [(10.0, 1e-12), (std::f64::consts::SQRT_2 - 1.4e-5, 1e-3)] {
            let opts = NewtonOptions { tolerance, ..Default::default() };
            let run = |check| {
                let mut p = Root2 { check, residual_calls: 0, j: 0.0 };
                let mut z = [start];
                let stats = solve(&mut p, &mut z, &opts).unwrap();
                (z, stats, p.residual_calls)
            };
            let (z0, s0, calls0) = run(true);
            let (z1, s1, calls1) = run(false);
            assert!((z0[0] - 2f64.sqrt()).abs() < 1e-3, "{z0:?}");
            assert_eq!(z1[0].to_bits(), z0[0].to_bits());
            assert_eq!((s1.iterations, s1.solves, s1.last_correction.to_bits()), (s0.iterations, s0.solves, s0.last_correction.to_bits()));
            assert_eq!(calls1 + 1, calls0);
            assert_eq!((s0.residual_evaluations, s1.residual_evaluations), (calls0, calls1));
        }
    }

    /// F(x, y, w) = (x² + y² + w² − 3, x − y, y − w³): the root (1, 1, 1) is regular
    /// (det J = −2(3w² + 1 + … ) ≠ 0 there); given as residual + sparse Jacobian.
    struct Sphere {
        damping: Damping,
    }

    impl SparseSystem for Sphere {
        type Error = LinearError;
        fn size(&self) -> usize {
            3
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            r[0] = z[0] * z[0] + z[1] * z[1] + z[2] * z[2] - 3.0;
            r[1] = z[0] - z[1];
            r[2] = z[1] - z[2] * z[2] * z[2];
            Ok(())
        }
        fn jacobian(&mut self, z: &[f64], jac: &mut Triplets) -> Result<(), LinearError> {
            for (c, &zc) in z.iter().enumerate() {
                jac.push(0, c, 2.0 * zc);
            }
            jac.push(1, 0, 1.0);
            jac.push(1, 1, -1.0);
            jac.push(2, 1, 1.0);
            jac.push(2, 2, -3.0 * z[2] * z[2]);
            Ok(())
        }
        fn damping(&self) -> Damping {
            self.damping
        }
    }

    fn sphere(damping: Damping) -> Sparse<Sphere> {
        Sparse::new(Sphere { damping })
    }

    /// From (1.3, 0.8, 1.2) (30 % off) Newton converges quadratically: the correction
    /// goes 3e-1 → 1e-1 → 1e-2 → 1e-4 → 1e-8 → 1e-16, so a tolerance of 1e-12 is met in
    /// at most 6 iterations; both damping strategies take full steps this close.
    #[test]
    fn converges_quadratically_from_a_nearby_start() {
        for damping in [Damping::NaturalMonotonicity, Damping::Backtracking { take_best: false }] {
            let mut p = sphere(damping);
            let mut z = vec![1.3, 0.8, 1.2];
            let opts = NewtonOptions { tolerance: 1e-12, ..Default::default() };
            let stats = solve(&mut p, &mut z, &opts).unwrap();
            for zi in &z {
                assert!((zi - 1.0).abs() < 1e-14, "{damping:?}: {z:?}");
            }
            assert!(stats.iterations <= 6, "{damping:?}: {stats:?}");
            assert_eq!(stats.factorisations, stats.iterations);
            assert_eq!(p.lu.numeric_factorisations(), stats.iterations);
            assert_eq!(p.lu.symbolic_factorisations(), 1);
            assert!(stats.last_correction <= 1e-12 && stats.min_damping_used == 1.0, "{stats:?}");
        }
    }

    /// A far start with w small (J₂₂ = −3w² nearly zero, so the first full step
    /// overshoots by 10²) needs damping and still converges; the work counters are
    /// consistent (every iteration one factorisation and at least one solve and
    /// residual). From (−2, 0.5, 0.05) the iterates stall near a local minimum of ‖F‖
    /// (x ≈ −2, ‖F‖_∞ ≈ 2.5): both strategies fail there with their typed error.
    #[test]
    fn damps_from_a_far_start() {
        for damping in [Damping::NaturalMonotonicity, Damping::Backtracking { take_best: false }] {
            let mut p = sphere(damping);
            let mut z = vec![5.0, 5.0, 0.1];
            let stats = solve(&mut p, &mut z, &NewtonOptions::default()).unwrap();
            let r = [z[0] * z[0] + z[1] * z[1] + z[2] * z[2] - 3.0, z[0] - z[1], z[1] - z[2].powi(3)];
            assert!(r.iter().all(|v| v.abs() < 1e-9), "{damping:?}: {z:?}");
            assert!(stats.min_damping_used < 1.0, "{damping:?}: {stats:?}");
            assert!(stats.solves >= stats.iterations && stats.residual_evaluations > stats.iterations);
            let err = solve(&mut sphere(damping), &mut [-2.0, 0.5, 0.05], &NewtonOptions::default()).unwrap_err();
            match (damping, err) {
                (Damping::NaturalMonotonicity, NewtonError::DampingExhausted { damping, correction, residual, .. }) => {
                    assert!(damping < 1e-4 && correction > 1.0 && residual > 2.0);
                }
                (Damping::Backtracking { .. }, NewtonError::LineSearchFailed { correction, merit, residual, .. }) => {
                    assert!(correction > 1.0 && merit > 2.0 && residual > 2.0);
                }
                (_, other) => panic!("{damping:?}: unexpected {other}"),
            }
        }
    }

    /// A scalar equation f(x) = 0 given by x ↦ (f(x), f′(x)).
    struct Scalar1<F: FnMut(f64) -> (f64, f64)> {
        f: F,
        slope: f64,
        damping: Damping,
    }

    impl<F: FnMut(f64) -> (f64, f64)> NewtonProblem for Scalar1<F> {
        type Error = LinearError;
        fn size(&self) -> usize {
            1
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            r[0] = (self.f)(z[0]).0;
            Ok(())
        }
        fn factorize(&mut self, z: &[f64]) -> Result<(), LinearError> {
            self.slope = (self.f)(z[0]).1;
            if self.slope == 0.0 {
                return Err(LinearError::Singular { detail: "zero derivative".into() });
            }
            Ok(())
        }
        fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
            b[0] /= self.slope;
            Ok(())
        }
        fn damping(&self) -> Damping {
            self.damping
        }
    }

    /// F(x) = x² + 1 has no real root: natural monotonicity cannot find a λ with a
    /// decreasing simplified correction and gives up with its numbers; backtracking
    /// finds no merit decrease in some iteration (the merit ½(x² + 1)² has its minimum
    /// 0.5 at x = 0, where J is singular).
    #[test]
    fn failures_are_typed_with_their_numbers() {
        let no_root = |damping| Scalar1 { f: |x: f64| (x * x + 1.0, 2.0 * x), slope: 0.0, damping };
        let opts = NewtonOptions::default();
        let err = solve(&mut no_root(Damping::NaturalMonotonicity), &mut [1.7], &opts).unwrap_err();
        match err {
            NewtonError::DampingExhausted { iteration, damping, correction, residual, tolerance } => {
                assert!(iteration >= 1 && damping < opts.min_damping && tolerance == opts.tolerance);
                // |Δx| = (x² + 1)/|2x| ≥ 1 for every x: the correction never gets small
                assert!(correction > 0.1 && residual >= 1.0, "{err}");
            }
            NewtonError::MaxIterations { correction, residual, .. } => assert!(correction > 0.1 && residual >= 1.0),
            other => panic!("unexpected {other}"),
        }
        let err = solve(&mut no_root(Damping::Backtracking { take_best: false }), &mut [1.7], &opts).unwrap_err();
        assert!(
            matches!(err, NewtonError::LineSearchFailed { merit, .. } if merit >= 0.5)
                || matches!(err, NewtonError::MaxIterations { residual, .. } if residual >= 1.0)
                || matches!(err, NewtonError::Problem { stage: Stage::Factorize, .. }),
            "{err}"
        );
        // the iteration limit: x³ − 8 from x = 100 needs ~15 iterations, 3 are allowed
        let mut cubic = Scalar1 { f: |x: f64| (x * x * x - 8.0, 3.0 * x * x), slope: 0.0, damping: Damping::NaturalMonotonicity };
        let err = solve(&mut cubic, &mut [100.0], &NewtonOptions { max_iterations: 3, ..opts }).unwrap_err();
        assert!(matches!(err, NewtonError::MaxIterations { iterations: 3, correction, .. } if correction > 1e-3), "{err}");
        // a singular Jacobian at the start is the problem's own error, at iteration 1
        let err = solve(&mut no_root(Damping::NaturalMonotonicity), &mut [0.0], &opts).unwrap_err();
        assert!(matches!(err, NewtonError::Problem { iteration: 1, stage: Stage::Factorize, error: LinearError::Singular { .. } }), "{err}");
        // inputs
        assert!(matches!(solve(&mut cubic, &mut [1.0, 2.0], &opts), Err(NewtonError::DimensionMismatch { expected: 1, got: 2 })));
        assert!(matches!(
            solve(&mut cubic, &mut [f64::NAN], &opts),
            Err(NewtonError::NonFinite { what: NonFiniteWhat::InitialIterate, .. })
        ));
        let bad = NewtonOptions { tolerance: 2.0, ..opts };
        assert!(matches!(solve(&mut cubic, &mut [1.0], &bad), Err(NewtonError::InvalidOptions(InvalidOptions { field: "tolerance", .. }))));
    }

    /// The hooks: an admissibility bound (x > 0) keeps backtracking on the positive
    /// root of x² − 4 from x = 0.1, where the plain first step would jump to x ≈ 20;
    /// `converged` may ask for more than the default (two small steps in a row).
    #[test]
    fn hooks_shape_the_iteration() {
        struct Positive {
            slope: f64,
            small_steps: usize,
        }
        impl NewtonProblem for Positive {
            type Error = LinearError;
            fn size(&self) -> usize {
                1
            }
            fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
                r[0] = z[0] * z[0] - 4.0;
                Ok(())
            }
            fn factorize(&mut self, z: &[f64]) -> Result<(), LinearError> {
                self.slope = 2.0 * z[0];
                Ok(())
            }
            fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
                b[0] /= self.slope;
                Ok(())
            }
            fn damping(&self) -> Damping {
                Damping::Backtracking { take_best: false }
            }
            fn admissible(&mut self, trial: &[f64], _r: &[f64]) -> bool {
                trial[0] > 0.0
            }
            fn converged(&mut self, p: &Progress<'_>) -> bool {
                self.small_steps = if p.damping == 1.0 && p.correction <= p.tolerance { self.small_steps + 1 } else { 0 };
                self.small_steps >= 2
            }
        }
        let mut p = Positive { slope: 0.0, small_steps: 0 };
        let mut z = [0.1];
        let stats = solve(&mut p, &mut z, &NewtonOptions::default()).unwrap();
        assert!((z[0] - 2.0).abs() < 1e-14, "{z:?}");
        assert_eq!(p.small_steps, 2);
        // x² − 4 = 0 from 0.1: ~10 iterations (damped, then quadratic), one more for the
        // second small step
        assert!(stats.iterations <= 14, "{stats:?}");
    }

    /// Π(z) = Σ (cosh z_i − b_i z_i), minimised by Newton on F = ∇Π = sinh z − b with
    /// Armijo on Π; every pass counts its calls. The assembly pass `factorize_with_residual`
    /// returns Π, F and J = diag cosh z at once.
    struct Catenary {
        b: Vec<f64>,
        evaluation: Evaluation,
        jac: Vec<f64>,
        energy_at_z: f64,
        residual_calls: usize,
        energy_calls: usize,
        assemblies: usize,
    }

    impl Catenary {
        fn new(evaluation: Evaluation) -> Self {
            Catenary { b: vec![6.0, -2.0, 0.5], evaluation, jac: vec![], energy_at_z: 0.0, residual_calls: 0, energy_calls: 0, assemblies: 0 }
        }
        fn energy(&self, z: &[f64]) -> f64 {
            z.iter().zip(&self.b).map(|(x, b)| x.cosh() - b * x).sum()
        }
    }

    impl NewtonProblem for Catenary {
        type Error = LinearError;
        fn size(&self) -> usize {
            self.b.len()
        }
        fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            self.residual_calls += 1;
            for ((ri, x), b) in r.iter_mut().zip(z).zip(&self.b) {
                *ri = x.sinh() - b;
            }
            Ok(())
        }
        fn factorize(&mut self, z: &[f64]) -> Result<(), LinearError> {
            self.jac = z.iter().map(|x| x.cosh()).collect();
            self.energy_at_z = self.energy(z);
            Ok(())
        }
        fn factorize_with_residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
            self.assemblies += 1;
            self.factorize(z)?;
            for ((ri, x), b) in r.iter_mut().zip(z).zip(&self.b) {
                *ri = x.sinh() - b;
            }
            Ok(())
        }
        fn solve(&mut self, v: &mut [f64]) -> Result<(), LinearError> {
            for (vi, j) in v.iter_mut().zip(&self.jac) {
                *vi /= j;
            }
            Ok(())
        }
        fn damping(&self) -> Damping {
            Damping::Backtracking { take_best: false }
        }
        fn evaluation(&self) -> Evaluation {
            self.evaluation
        }
        fn merit(&mut self, z: &[f64], _r: &[f64]) -> f64 {
            // Π at the factorised point is known from the assembly pass
            if z.iter().zip(&self.jac).all(|(x, j)| x.cosh() == *j) {
                self.energy_at_z
            } else {
                self.energy_calls += 1;
                self.energy(z)
            }
        }
        fn trial_merit(&mut self, trial: &[f64], _kind: TrialKind) -> Result<Option<f64>, LinearError> {
            self.energy_calls += 1;
            Ok(Some(self.energy(trial)))
        }
        fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
            if t.trial_merit <= t.merit + SUFFICIENT_DECREASE * t.damping * t.slope {
                Verdict::Accept
            } else {
                Verdict::Reject
            }
        }
    }

    /// The two evaluation hooks change which passes run, not the iterates: from z = 0
    /// (b = (6, −2, ½): the first full step to z₁ = 6 overshoots asinh 6 ≈ 2.5 and
    /// raises Π from 0 to ≈ 162, so it is damped) every variant
    /// takes the same steps bit for bit. Without hooks every trial costs a residual
    /// (plus the initial one); with the factorisation's residual the initial one goes;
    /// with merit-only trials each trial costs an energy and only accepted ones a
    /// residual; with both, no residual is evaluated apart from the assemblies.
    #[test]
    fn evaluation_hooks_share_passes_and_keep_the_iterates() {
        let run = |evaluation| {
            let mut p = Catenary::new(evaluation);
            let mut z = vec![0.0, 0.0, 0.0];
            let stats = solve(&mut p, &mut z, &NewtonOptions::default()).unwrap();
            (z, stats, p)
        };
        let (z0, s0, p0) = run(Evaluation::default());
        for (zi, b) in z0.iter().zip([6.0_f64, -2.0, 0.5]) {
            assert!((zi - b.asinh()).abs() < 1e-14, "{z0:?}");
        }
        assert!(s0.min_damping_used < 1.0 && s0.iterations >= 4, "{s0:?}");
        // trials: one residual each, plus F(z₀)
        let trials = s0.residual_evaluations - 1;
        assert_eq!(p0.residual_calls, s0.residual_evaluations);
        assert!(trials > s0.iterations, "damped: more trials than iterations, {s0:?}");
        assert_eq!((p0.assemblies, s0.merit_evaluations), (0, 0));

        let (z1, s1, p1) = run(Evaluation { residual_with_factorization: true, merit_only: false });
        assert_eq!(z1, z0);
        assert_eq!((s1.iterations, s1.factorisations), (s0.iterations, s0.factorisations));
        assert_eq!(p1.residual_calls, trials, "the initial residual comes with the first assembly");
        assert_eq!(p1.assemblies, s1.iterations);

        let (z2, s2, p2) = run(Evaluation { residual_with_factorization: false, merit_only: true });
        assert_eq!(z2, z0);
        assert_eq!(s2.iterations, s0.iterations);
        assert_eq!(s2.merit_evaluations, trials);
        // F(z₀) and one per accepted trial (= per iteration)
        assert_eq!(p2.residual_calls, 1 + s2.iterations);
        assert_eq!(s2.residual_evaluations, p2.residual_calls);

        let (z3, s3, p3) = run(Evaluation { residual_with_factorization: true, merit_only: true });
        assert_eq!(z3, z0);
        assert_eq!(s3.iterations, s0.iterations);
        assert_eq!((p3.residual_calls, s3.residual_evaluations), (0, 0));
        assert_eq!(p3.energy_calls, trials);
        assert_eq!(p3.assemblies, s3.iterations);
    }

    /// Π(x) = x⁴/4 − x (F = x³ − 1, J = 3x²) from x = 0, where J = 0: the step is not
    /// finite, which fails level 0 and goes to the regularisation J + 1 (level 1) instead
    /// of stopping. From x = −1 the Newton step of Π (J = 3 > 0, F = −2) is a descent
    /// direction; from x = 0.3 with the concave Π(x) = −cos x + x²/20 (F = sin x + x/10,
    /// J = cos x + 1/10 < 0 beyond x ≈ 1.67) `line_search` skips the ascending plain
    /// step, which saves exactly its α = 1 trial compared with abandoning it there.
    #[test]
    fn singular_and_ascending_steps_go_to_regularisation() {
        struct Energy {
            f: fn(f64) -> (f64, f64, f64),
            jac: f64,
            level: usize,
            skip_ascent: bool,
        }
        impl NewtonProblem for Energy {
            type Error = LinearError;
            fn factorize(&mut self, z: &[f64]) -> Result<(), LinearError> {
                (_, _, self.jac) = (self.f)(z[0]);
                self.level = 0;
                Ok(())
            }
            fn size(&self) -> usize {
                1
            }
            fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), LinearError> {
                let (_, gradient, _) = (self.f)(z[0]);
                r[0] = gradient;
                Ok(())
            }
            fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
                b[0] /= if self.level == 0 { self.jac } else { self.jac.abs() + 1.0 };
                Ok(())
            }
            fn damping(&self) -> Damping {
                Damping::Backtracking { take_best: false }
            }
            fn evaluation(&self) -> Evaluation {
                Evaluation { residual_with_factorization: false, merit_only: true }
            }
            fn merit(&mut self, z: &[f64], _r: &[f64]) -> f64 {
                (self.f)(z[0]).0
            }
            fn trial_merit(&mut self, trial: &[f64], _kind: TrialKind) -> Result<Option<f64>, LinearError> {
                Ok(Some((self.f)(trial[0]).0))
            }
            fn line_search(&mut self, _level: usize, slope: f64) -> bool {
                !self.skip_ascent || slope < 0.0
            }
            fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
                if t.slope >= 0.0 {
                    Verdict::Abandon
                } else if t.trial_merit <= t.merit + SUFFICIENT_DECREASE * t.damping * t.slope {
                    Verdict::Accept
                } else {
                    Verdict::Reject
                }
            }
            fn regularise(&mut self, _z: &[f64], level: usize) -> Result<bool, LinearError> {
                self.level = level;
                Ok(level == 1)
            }
        }
        let quartic = |x: f64| (0.25 * x.powi(4) - x, x.powi(3) - 1.0, 3.0 * x * x);
        let mut p = Energy { f: quartic, jac: 0.0, level: 0, skip_ascent: true };
        let mut z = [0.0];
        let stats = solve(&mut p, &mut z, &NewtonOptions::default()).unwrap();
        assert!((z[0] - 1.0).abs() < 1e-12, "{z:?}");
        assert!(stats.regularisations >= 1, "{stats:?}");

        let concave = |x: f64| (-x.cos() + x * x / 20.0, x.sin() + x / 10.0, x.cos() + 0.1);
        let mut counts = vec![];
        for skip_ascent in [false, true] {
            let mut p = Energy { f: concave, jac: 0.0, level: 0, skip_ascent };
            let mut z = [2.5];
            let stats = solve(&mut p, &mut z, &NewtonOptions::default()).unwrap();
            // the minimum of −cos x + x²/20 is x = 0
            assert!(z[0].abs() < 1e-12, "{z:?}");
            assert!(stats.regularisations >= 1, "{stats:?}");
            counts.push((stats.merit_evaluations, stats.regularisations, z[0]));
        }
        // same path, one trial less per ascending plain step
        assert_eq!(counts[0].1, counts[1].1);
        assert_eq!(counts[0].2, counts[1].2);
        assert_eq!(counts[0].0, counts[1].0 + counts[1].1);
    }
}
