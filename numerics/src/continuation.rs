//! Continuation in a scalar parameter η: step control, natural-parameter continuation
//! (homotopy), pseudo-arclength continuation with fold detection, and fold location.
//!
//! The model-dependent parts — the predictor, the corrector (a Newton solve), what a
//! "state" is, mesh transfer — stay with the caller behind two small traits:
//! [`Homotopy`] (natural parameter) and [`Branch`] (pseudo-arclength). What is shared is
//! the part every continuation repeats: how long the next step is, when to give up,
//! when the path turned round a fold, and where exactly it turned.
//!
//! # Step control ([`StepControl`])
//! A step from η to a target is *accepted* when the caller's corrector converges (and
//! its own acceptance test passes), otherwise *rejected*. After an accepted step of
//! length `done` taking `k` Newton iterations the next step is set by the [`Growth`]
//! rule:
//! - [`Growth::Quick`]: step ← min(factor·step, max) if k ≤ fast, else unchanged;
//! - [`Growth::Bands`]: step ← clamp(f·done, min, max) with f = fast / middle / slow
//!   factor for k ≤ fast, ≤ slow, > slow;
//! - [`Growth::Always`]: step ← min(factor·step, max).
//!
//! A rejected step is multiplied by `shrink`; below `min` the continuation has
//! stalled ([`ContinuationError::Stalled`], with the last failure as its cause). The
//! target is η + step towards `to`, snapped to `to` when within a relative `snap` of the
//! step, and never beyond a breakpoint (a kink of the path, e.g. where one homotopy
//! phase hands over to the next), which is hit exactly.
//!
//! # Folds
//! Along a branch w(s) = (z(s), η(s)) with unit tangent t = dw/ds, a fold (turning
//! point) is where dη/ds = t_η changes sign. [`pseudo_arclength`] records every pair of
//! consecutive accepted points whose oriented tangents have η-components of opposite
//! sign ([`FoldBracket`]); [`locate_fold`] then finds the root of a caller-supplied
//! continuous function g (typically t_η as a function of a state coordinate that is
//! monotone through the fold) on the bracket with Brent's method (argmin). η is
//! stationary at the fold, so an error δ in the coordinate costs only O(δ²) in η.

use thiserror::Error;

use crate::fmt::Sig;

/// How many steps a continuation may take before it gives up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepLimit {
    /// At most this many accepted steps.
    Accepted(usize),
    /// At most this many attempts, accepted or rejected.
    Attempts(usize),
}

/// How the step grows after an accepted step (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Growth {
    /// step ← min(factor·step, max) if the step took at most `fast` Newton iterations.
    Quick { fast: usize, factor: f64 },
    /// step ← clamp(f·done, min, max), f by the iteration band: ≤ `fast`, ≤ `slow`, more.
    Bands { fast: usize, slow: usize, factors: [f64; 3] },
    /// step ← min(factor·step, max) after every accepted step.
    Always { factor: f64 },
}

/// Options of a [`StepControl`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepOptions {
    /// First step, in [min, max].
    pub initial: f64,
    /// Smallest step; a rejection below it stalls the continuation. > 0.
    pub min: f64,
    /// Largest step, ≥ min.
    pub max: f64,
    /// Factor of a rejected step, in (0, 1).
    pub shrink: f64,
    /// The step limit.
    pub limit: StepLimit,
    /// Growth after an accepted step.
    pub growth: Growth,
    /// The target snaps to the end when the remaining distance is at most
    /// step·(1 + snap); ≥ 0 (0: only when the step reaches past the end).
    pub snap: f64,
}

/// A [`StepOptions`] outside its documented ranges.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("continuation step options: {0}")]
pub struct InvalidStepOptions(pub String);

impl StepOptions {
    /// Check the documented ranges.
    pub fn validate(&self) -> Result<(), InvalidStepOptions> {
        let bad = |m: String| Err(InvalidStepOptions(m));
        if !(self.min > 0.0 && self.min.is_finite()) {
            return bad(format!("min step {} must be > 0 and finite", Sig(self.min)));
        }
        if !(self.max >= self.min && self.max.is_finite()) {
            return bad(format!("max step {} must be ≥ min step {}", Sig(self.max), Sig(self.min)));
        }
        if !(self.initial >= self.min && self.initial <= self.max) {
            return bad(format!(
                "initial step {} outside [min, max] = [{}, {}]",
                Sig(self.initial),
                Sig(self.min),
                Sig(self.max)
            ));
        }
        if !(self.shrink > 0.0 && self.shrink < 1.0) {
            return bad(format!("shrink factor {} outside (0, 1)", Sig(self.shrink)));
        }
        if !(self.snap >= 0.0 && self.snap.is_finite()) {
            return bad(format!("snap {} must be ≥ 0", Sig(self.snap)));
        }
        match self.limit {
            StepLimit::Accepted(0) | StepLimit::Attempts(0) => return bad("step limit must be ≥ 1".into()),
            _ => {}
        }
        let growth_ok = match self.growth {
            Growth::Quick { factor, .. } | Growth::Always { factor } => factor >= 1.0 && factor.is_finite(),
            Growth::Bands { fast, slow, factors } => fast <= slow && factors.iter().all(|f| *f > 0.0 && f.is_finite()),
        };
        if !growth_ok {
            return bad(format!("growth rule {:?} invalid (factors ≥ 1, bands ordered)", self.growth));
        }
        Ok(())
    }
}

/// The continuation could not go on: the step fell below its minimum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stalled {
    /// The step after the last rejection.
    pub step: f64,
    /// The minimum step.
    pub min_step: f64,
}

impl Stalled {
    /// The error of a continuation that stalled at the accepted `eta` trying `target`
    /// after `accepted` steps, `failure` being the last rejected solve.
    fn at<F, E>(self, eta: f64, target: f64, accepted: usize, failure: F) -> ContinuationError<F, E> {
        ContinuationError::Stalled {
            eta: Sig(eta),
            step: Sig(self.step),
            min_step: Sig(self.min_step),
            target: Sig(target),
            accepted,
            cause: Some(failure),
        }
    }
}

/// Step length control of one continuation (module documentation).
#[derive(Debug, Clone)]
pub struct StepControl {
    opts: StepOptions,
    step: f64,
    accepted: usize,
    rejected: usize,
}

impl StepControl {
    /// A controller at the initial step.
    pub fn new(opts: StepOptions) -> Result<Self, InvalidStepOptions> {
        opts.validate()?;
        Ok(Self { opts, step: opts.initial, accepted: 0, rejected: 0 })
    }

    /// The current step.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// The options.
    pub fn options(&self) -> &StepOptions {
        &self.opts
    }

    /// Accepted steps so far.
    pub fn accepted(&self) -> usize {
        self.accepted
    }

    /// Rejected steps so far.
    pub fn rejected(&self) -> usize {
        self.rejected
    }

    /// Whether the step limit allows another attempt.
    pub fn may_try(&self) -> bool {
        match self.opts.limit {
            StepLimit::Accepted(n) => self.accepted < n,
            StepLimit::Attempts(n) => self.accepted + self.rejected < n,
        }
    }

    /// The next target from `eta` towards `to`: η ± step, snapped to `to` (module
    /// documentation) and never past a breakpoint strictly between η and `to`.
    pub fn target(&self, eta: f64, to: f64, breakpoints: &[f64]) -> f64 {
        let remaining = (to - eta).abs();
        let dir = if to >= eta { 1.0 } else { -1.0 };
        let stepped = eta + dir * self.step;
        let reaches = remaining <= self.step * (1.0 + self.opts.snap) || (stepped - to) * dir >= 0.0;
        let mut target = if reaches { to } else { stepped };
        for &b in breakpoints {
            if (b - eta) * dir > 0.0 && (target - b) * dir > 0.0 {
                target = b;
            }
        }
        target
    }

    /// Record an accepted step of length `done` that took `iterations` Newton
    /// iterations, and set the next step by the growth rule.
    pub fn accept(&mut self, done: f64, iterations: usize) {
        self.accepted += 1;
        crate::phases::count(crate::phases::Step::ContinuationStep, 1);
        let o = &self.opts;
        self.step = match o.growth {
            Growth::Quick { fast, factor } => {
                if iterations <= fast {
                    (self.step * factor).min(o.max)
                } else {
                    self.step
                }
            }
            Growth::Bands { fast, slow, factors } => {
                let f = if iterations <= fast {
                    factors[0]
                } else if iterations <= slow {
                    factors[1]
                } else {
                    factors[2]
                };
                (f * done.abs()).clamp(o.min, o.max)
            }
            Growth::Always { factor } => (self.step * factor).min(o.max),
        };
    }

    /// Record a rejected step: shrink; [`Stalled`] when the step falls below the minimum.
    pub fn reject(&mut self) -> Result<(), Stalled> {
        self.rejected += 1;
        self.step *= self.opts.shrink;
        if self.step < self.opts.min {
            Err(Stalled { step: self.step, min_step: self.opts.min })
        } else {
            Ok(())
        }
    }
}

/// The outcome of one solve of a continuation that did not end it.
#[derive(Debug, Clone, PartialEq)]
pub enum Step<F> {
    /// Converged (and accepted by the caller's own tests): the caller keeps the new
    /// state; `iterations` are the Newton iterations the solve took.
    Accepted { iterations: usize },
    /// Not converged or not acceptable: the caller keeps the old state; a shorter step
    /// may succeed.
    Rejected(F),
}

/// Why a continuation ended without reaching its end. `F` is the caller's failure of
/// one solve (a rejected step), `E` its error that ends the continuation at once.
#[derive(Debug, Clone, PartialEq)]
pub enum ContinuationError<F, E> {
    /// The step fell below its minimum; `cause` is the last rejected solve.
    Stalled { eta: Sig, step: Sig, min_step: Sig, target: Sig, accepted: usize, cause: Option<F> },
    /// The step limit was reached before the end; `cause` is the last rejected solve.
    StepLimit { eta: Sig, step: Sig, accepted: usize, rejected: usize, cause: Option<F> },
    /// The caller ended the continuation.
    Aborted(E),
}

impl<F: std::fmt::Display, E: std::fmt::Display> std::fmt::Display for ContinuationError<F, E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ContinuationError::Stalled { eta, step, min_step, target, accepted, cause } => write!(
                f,
                "continuation stalled at η = {eta} (step {step} < minimum {min_step}, last target {target}) after {accepted} accepted steps{}",
                cause_suffix(cause)
            ),
            ContinuationError::StepLimit { eta, step, accepted, rejected, cause } => write!(
                f,
                "continuation step limit reached at η = {eta} ({accepted} accepted, {rejected} rejected, step {step}){}",
                cause_suffix(cause)
            ),
            ContinuationError::Aborted(e) => write!(f, "{e}"),
        }
    }
}

impl<F, E> std::error::Error for ContinuationError<F, E>
where
    F: std::fmt::Display + std::fmt::Debug,
    E: std::fmt::Display + std::fmt::Debug,
{
}

fn cause_suffix<F: std::fmt::Display>(cause: &Option<F>) -> String {
    match cause {
        Some(c) => format!("; last failure: {c}"),
        None => String::new(),
    }
}

/// A path in η solved point by point by natural-parameter continuation.
pub trait Homotopy {
    /// Why one solve failed (a rejected step).
    type Failure;
    /// An error that ends the whole continuation at once (e.g. a physical limit found
    /// on an accepted state).
    type Error;
    /// Move the accepted state from `from` to `to` (predictor and corrector). On
    /// [`Step::Accepted`] the state is at `to`; on [`Step::Rejected`] it must still be
    /// the one at `from`.
    ///
    /// # Errors
    /// An error that ends the continuation.
    fn advance(&mut self, from: f64, to: f64) -> Result<Step<Self::Failure>, Self::Error>;
}

/// What a continuation did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathReport {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Newton iterations of the accepted steps.
    pub iterations: usize,
}

/// Natural-parameter continuation of `path` from η = `from` (where its state is
/// already solved) to exactly η = `to`, through every breakpoint in between (hit
/// exactly).
///
/// # Errors
/// [`ContinuationError::Stalled`] / [`ContinuationError::StepLimit`] with the last
/// accepted η, the step and the last rejected solve; [`ContinuationError::Aborted`]
/// with the caller's error.
pub fn natural<H: Homotopy>(
    path: &mut H,
    from: f64,
    to: f64,
    control: &mut StepControl,
    breakpoints: &[f64],
) -> Result<PathReport, ContinuationError<H::Failure, H::Error>> {
    let mut report = PathReport::default();
    let mut eta = from;
    let mut cause = None;
    while eta != to {
        if !control.may_try() {
            return Err(ContinuationError::StepLimit {
                eta: Sig(eta),
                step: Sig(control.step()),
                accepted: control.accepted(),
                rejected: control.rejected(),
                cause,
            });
        }
        let target = control.target(eta, to, breakpoints);
        match path.advance(eta, target).map_err(ContinuationError::Aborted)? {
            Step::Accepted { iterations } => {
                control.accept(target - eta, iterations);
                report.accepted += 1;
                report.iterations += iterations;
                eta = target;
            }
            Step::Rejected(failure) => {
                report.rejected += 1;
                if let Err(s) = control.reject() {
                    return Err(s.at(eta, target, control.accepted(), failure));
                }
                cause = Some(failure);
            }
        }
    }
    Ok(report)
}

/// A solution branch w = (z, η) traced by pseudo-arclength continuation.
pub trait Branch {
    /// Why one solve failed (a rejected step).
    type Failure;
    /// An error that ends the branch at once.
    type Error;
    /// η of the accepted point.
    fn eta(&self) -> f64;
    /// dη/ds of the accepted point's unit tangent, oriented along the direction of
    /// travel (the caller orients each new tangent along the secant from the previous
    /// point).
    fn tangent_eta(&self) -> f64;
    /// Predictor w + Δs·t and corrector (F = 0 with the arclength condition
    /// ⟨t, w − w₀⟩ = Δs). On [`Step::Accepted`] the accepted point and its oriented
    /// tangent are the new ones; on [`Step::Rejected`] the state is unchanged.
    ///
    /// # Errors
    /// An error that ends the branch.
    fn advance(&mut self, ds: f64) -> Result<Step<Self::Failure>, Self::Error>;
}

/// Two consecutive accepted points between which dη/ds changed sign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldBracket {
    /// Index of the point before the fold (0 = the start point).
    pub before: usize,
    /// η at the point before and after.
    pub eta: [f64; 2],
    /// dη/ds at the point before and after.
    pub tangent_eta: [f64; 2],
}

/// Why a branch ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BranchEnd {
    /// η left the window [η_min, η_max] (the last point is the first outside).
    LeftWindow,
    /// The step limit was reached.
    StepLimit,
}

/// What a pseudo-arclength continuation did.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchReport {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Newton iterations of the accepted steps.
    pub iterations: usize,
    /// Every fold passed, in order.
    pub folds: Vec<FoldBracket>,
    /// Why it ended.
    pub end: BranchEnd,
}

/// Pseudo-arclength continuation of `branch` from its accepted point until η leaves
/// [`eta_min`, `eta_max`] or the step limit; `on_point` sees every accepted point (with
/// its index, the start point being 0) and may stop the branch by returning `false`
/// (reported as [`BranchEnd::LeftWindow`]). Folds are detected as in the module
/// documentation.
pub fn pseudo_arclength<B: Branch>(
    branch: &mut B,
    eta_min: f64,
    eta_max: f64,
    control: &mut StepControl,
    mut on_point: impl FnMut(usize, &B) -> bool,
) -> Result<BranchReport, ContinuationError<B::Failure, B::Error>> {
    let mut report =
        BranchReport { accepted: 0, rejected: 0, iterations: 0, folds: vec![], end: BranchEnd::StepLimit };
    if !on_point(0, branch) {
        report.end = BranchEnd::LeftWindow;
        return Ok(report);
    }
    loop {
        if !control.may_try() {
            report.end = BranchEnd::StepLimit;
            return Ok(report);
        }
        let (eta0, t0) = (branch.eta(), branch.tangent_eta());
        let ds = control.step();
        match branch.advance(ds).map_err(ContinuationError::Aborted)? {
            Step::Accepted { iterations } => {
                control.accept(ds, iterations);
                report.accepted += 1;
                report.iterations += iterations;
                let (eta1, t1) = (branch.eta(), branch.tangent_eta());
                if t0 * t1 < 0.0 {
                    report.folds.push(FoldBracket {
                        before: report.accepted - 1,
                        eta: [eta0, eta1],
                        tangent_eta: [t0, t1],
                    });
                }
                let inside = eta1 >= eta_min && eta1 <= eta_max;
                if !on_point(report.accepted, branch) || !inside {
                    report.end = BranchEnd::LeftWindow;
                    return Ok(report);
                }
            }
            Step::Rejected(failure) => {
                report.rejected += 1;
                if let Err(s) = control.reject() {
                    return Err(s.at(eta0, eta0, control.accepted(), failure));
                }
            }
        }
    }
}

/// Fold location failed: [`crate::roots::RootError`].
pub type FoldError<E> = crate::roots::RootError<E>;

/// The root s* ∈ [a, b] of g (a continuous function with g(a)·g(b) ≤ 0), to within
/// `tol`·(1 + max(|a|, |b|)), by [`crate::roots::brent`]. Used with g = the η-component
/// of the tangent as a function of a state coordinate monotone through the fold.
///
/// # Errors
/// [`FoldError`]: no bracket, a failed evaluation, no convergence.
pub fn locate_fold<E>(g: impl Fn(f64) -> Result<f64, E>, a: f64, b: f64, tol: f64) -> Result<f64, FoldError<E>> {
    crate::roots::brent(g, a, b, tol * (1.0 + a.abs().max(b.abs())))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(growth: Growth) -> StepOptions {
        StepOptions {
            initial: 0.1,
            min: 1e-6,
            max: 0.5,
            shrink: 0.5,
            limit: StepLimit::Accepted(500),
            growth,
            snap: 1e-12,
        }
    }

    #[test]
    fn options_are_validated() {
        let good = opts(Growth::Quick { fast: 4, factor: 1.5 });
        assert!(good.validate().is_ok());
        for bad in [
            StepOptions { min: 0.0, ..good },
            StepOptions { max: 1e-9, ..good },
            StepOptions { initial: 1.0, ..good },
            StepOptions { shrink: 1.0, ..good },
            StepOptions { snap: -1.0, ..good },
            StepOptions { limit: StepLimit::Attempts(0), ..good },
            StepOptions { growth: Growth::Always { factor: 0.5 }, ..good },
            StepOptions { growth: Growth::Bands { fast: 5, slow: 2, factors: [2.0, 1.0, 0.5] }, ..good },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }

    /// The three growth rules, the snap to the end and the breakpoints.
    #[test]
    fn step_rules() {
        let mut q = StepControl::new(opts(Growth::Quick { fast: 4, factor: 1.5 })).unwrap();
        q.accept(0.1, 5);
        assert_eq!(q.step(), 0.1);
        q.accept(0.1, 4);
        assert!((q.step() - 0.15).abs() < 1e-15);
        for _ in 0..10 {
            q.accept(0.1, 1);
        }
        assert_eq!(q.step(), 0.5);

        let mut b = StepControl::new(opts(Growth::Bands { fast: 8, slow: 12, factors: [2.0, 1.25, 0.6] })).unwrap();
        b.accept(0.05, 3);
        assert_eq!(b.step(), 0.1);
        b.accept(0.08, 10);
        assert_eq!(b.step(), 0.1);
        b.accept(0.1, 13);
        assert!((b.step() - 0.06).abs() < 1e-15);
        b.accept(1e-9, 13);
        assert_eq!(b.step(), 1e-6, "clamped to the minimum");

        let mut a = StepControl::new(opts(Growth::Always { factor: 2.0 })).unwrap();
        a.accept(0.1, 50);
        assert_eq!(a.step(), 0.2);
        assert!(a.reject().is_ok());
        assert_eq!(a.step(), 0.1);

        let c = StepControl::new(opts(Growth::Always { factor: 2.0 })).unwrap();
        assert_eq!(c.target(0.0, 1.0, &[]), 0.1);
        assert_eq!(c.target(0.95, 1.0, &[]), 1.0);
        assert_eq!(c.target(0.9, 1.0, &[]), 1.0, "remaining = step (within snap) lands on the end");
        assert_eq!(c.target(0.45, 1.0, &[0.5]), 0.5, "a breakpoint is hit exactly");
        assert_eq!(c.target(0.5, 1.0, &[0.5]), 0.6, "a breakpoint behind is ignored");
        assert_eq!(c.target(1.0, 0.0, &[0.5]), 0.9, "downwards");
        assert_eq!(c.target(0.55, 0.0, &[0.5]), 0.5);
    }

    #[test]
    fn rejection_below_minimum_stalls() {
        let mut c = StepControl::new(StepOptions { min: 0.03, ..opts(Growth::Always { factor: 2.0 }) }).unwrap();
        assert!(c.reject().is_ok()); // 0.05
        let s = c.reject().unwrap_err(); // 0.025 < 0.03
        assert_eq!(s, Stalled { step: 0.025, min_step: 0.03 });
        assert_eq!(c.rejected(), 2);
    }

    /// Scalar Newton on F(x, η) = x − η eˣ = 0 (the fold of the Bratu-like equation is
    /// at x = 1, η = 1/e): natural continuation from η = 0.
    struct Scalar1 {
        x: f64,
        max_iterations: usize,
    }

    #[derive(Debug, Clone, PartialEq)]
    struct Diverged(f64);

    impl std::fmt::Display for Diverged {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "Newton diverged at η = {}", self.0)
        }
    }

    impl Homotopy for Scalar1 {
        type Failure = Diverged;
        type Error = Diverged;
        fn advance(&mut self, _from: f64, to: f64) -> Result<Step<Diverged>, Diverged> {
            let mut x = self.x;
            for k in 1..=self.max_iterations {
                let f = x - to * x.exp();
                let df = 1.0 - to * x.exp();
                let dx = -f / df;
                if !dx.is_finite() {
                    return Ok(Step::Rejected(Diverged(to)));
                }
                x += dx;
                if dx.abs() < 1e-13 * (1.0 + x.abs()) {
                    // the lower branch only: x < 1 (beyond the fold Newton may land on
                    // the upper branch, which this path rejects)
                    if x >= 1.0 {
                        return Ok(Step::Rejected(Diverged(to)));
                    }
                    self.x = x;
                    return Ok(Step::Accepted { iterations: k });
                }
            }
            Ok(Step::Rejected(Diverged(to)))
        }
    }

    #[test]
    fn natural_reaches_the_end_exactly_and_stalls_at_a_fold() {
        let mut path = Scalar1 { x: 0.0, max_iterations: 30 };
        let mut c = StepControl::new(opts(Growth::Quick { fast: 4, factor: 1.5 })).unwrap();
        let r = natural(&mut path, 0.0, 0.3, &mut c, &[0.25]).unwrap();
        assert!(r.accepted >= 2 && r.iterations > 0);
        assert!((path.x - 0.3 * path.x.exp()).abs() < 1e-12, "on the path at η = 0.3 exactly");
        // beyond the fold η = 1/e there is no solution: the step shrinks until it stalls
        let mut c = StepControl::new(opts(Growth::Quick { fast: 4, factor: 1.5 })).unwrap();
        let e = natural(&mut path, 0.3, 0.5, &mut c, &[]).unwrap_err();
        match &e {
            ContinuationError::Stalled { eta, cause: Some(Diverged(_)), .. } => {
                assert!(eta.0 < 1.0 / std::f64::consts::E && eta.0 > 0.36, "stalled at η = {}", eta.0);
            }
            other => panic!("{other:?}"),
        }
        assert!(e.to_string().contains("last failure: Newton diverged"), "{e}");
        // a step limit is its own error
        let mut path = Scalar1 { x: 0.0, max_iterations: 30 };
        let mut c = StepControl::new(StepOptions { limit: StepLimit::Attempts(2), ..opts(Growth::Always { factor: 1.0 }) })
            .unwrap();
        assert!(matches!(natural(&mut path, 0.0, 0.3, &mut c, &[]), Err(ContinuationError::StepLimit { accepted: 2, .. })));
        // the caller's error ends the continuation at once, unchanged
        struct Abort;
        impl Homotopy for Abort {
            type Failure = ();
            type Error = &'static str;
            fn advance(&mut self, _: f64, to: f64) -> Result<Step<()>, &'static str> {
                if to > 0.15 {
                    Err("limit")
                } else {
                    Ok(Step::Accepted { iterations: 1 })
                }
            }
        }
        let mut c = StepControl::new(opts(Growth::Always { factor: 1.0 })).unwrap();
        assert_eq!(natural(&mut Abort, 0.0, 1.0, &mut c, &[]), Err(ContinuationError::Aborted("limit")));
    }

    /// A homotopy whose solves fail beyond a reach (a stand-in for Newton's radius of
    /// convergence), taking more iterations for longer steps: η reaches 1 exactly
    /// through the breakpoint ½, never stepping beyond the reach, with fem's static
    /// rule (2 / 1.25 / 0.6 × the step done by iteration band, ¼ on rejection).
    #[test]
    fn bands_reach_the_end_through_a_breakpoint_within_the_reach() {
        struct Reach {
            reach: f64,
            visited: Vec<f64>,
        }
        impl Homotopy for Reach {
            type Failure = f64;
            type Error = ();
            fn advance(&mut self, eta: f64, target: f64) -> Result<Step<f64>, ()> {
                if target - eta > self.reach {
                    return Ok(Step::Rejected(target));
                }
                self.visited.push(target);
                Ok(Step::Accepted { iterations: 2 + (20.0 * (target - eta) / self.reach) as usize })
            }
        }
        let mut c = StepControl::new(StepOptions {
            initial: 0.1,
            min: 1e-3,
            max: 0.5,
            shrink: 0.25,
            limit: StepLimit::Attempts(100),
            growth: Growth::Bands { fast: 8, slow: 12, factors: [2.0, 1.25, 0.6] },
            snap: 0.0,
        })
        .unwrap();
        let mut h = Reach { reach: 0.3, visited: vec![] };
        let r = natural(&mut h, 0.0, 1.0, &mut c, &[0.5]).unwrap();
        assert_eq!(*h.visited.last().unwrap(), 1.0);
        assert!(h.visited.contains(&0.5));
        assert!(h.visited.windows(2).all(|w| w[1] > w[0] && w[1] - w[0] <= 0.3 + 1e-15), "{:?}", h.visited);
        assert_eq!(r.accepted, h.visited.len());
        // 0.1 (8 iterations: next 2 × 0.1), 0.3 (15: 0.6 × 0.2), 0.42 (10: 1.25 × 0.12),
        // 0.5 (the breakpoint cuts 0.15 to 0.08; 7: 2 × 0.08), 0.66 (12: 1.25 × 0.16),
        // 0.86 (15: 0.6 × 0.2), 0.98, 1.0
        let expected = [0.1, 0.3, 0.42, 0.5, 0.66, 0.86, 0.98, 1.0];
        assert_eq!(h.visited.len(), expected.len(), "{:?}", h.visited);
        assert!(h.visited.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12), "{:?}", h.visited);
        assert_eq!(r.rejected, 0);
    }

    /// The unit circle x² + η² = 1 as a branch: folds at η = ±1 (x = 0). The corrector
    /// is Newton on (F, arclength) in R², the tangent t = (−η, x)·sign, oriented along
    /// the secant.
    struct Circle {
        w: [f64; 2], // (x, η)
        t: [f64; 2],
    }

    impl Branch for Circle {
        type Failure = Diverged;
        type Error = ();
        fn eta(&self) -> f64 {
            self.w[1]
        }
        fn tangent_eta(&self) -> f64 {
            self.t[1]
        }
        fn advance(&mut self, ds: f64) -> Result<Step<Diverged>, ()> {
            let w0 = self.w;
            let mut w = [w0[0] + ds * self.t[0], w0[1] + ds * self.t[1]];
            for k in 1..=20 {
                let f = [w[0] * w[0] + w[1] * w[1] - 1.0, self.t[0] * (w[0] - w0[0]) + self.t[1] * (w[1] - w0[1]) - ds];
                let j = [[2.0 * w[0], 2.0 * w[1]], self.t];
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                let d = [-(j[1][1] * f[0] - j[0][1] * f[1]) / det, -(-j[1][0] * f[0] + j[0][0] * f[1]) / det];
                w = [w[0] + d[0], w[1] + d[1]];
                if d[0].abs().max(d[1].abs()) < 1e-14 {
                    let mut t = [-w[1], w[0]];
                    if t[0] * (w[0] - w0[0]) + t[1] * (w[1] - w0[1]) < 0.0 {
                        t = [w[1], -w[0]];
                    }
                    self.w = w;
                    self.t = t;
                    return Ok(Step::Accepted { iterations: k });
                }
            }
            Ok(Step::Rejected(Diverged(w0[1])))
        }
    }

    #[test]
    fn pseudo_arclength_passes_and_locates_folds() {
        let mut c = Circle { w: [1.0, 0.0], t: [0.0, 1.0] };
        let mut ctl = StepControl::new(StepOptions {
            initial: 0.05,
            max: 0.2,
            limit: StepLimit::Accepted(200),
            ..opts(Growth::Quick { fast: 4, factor: 1.5 })
        })
        .unwrap();
        let mut points = vec![];
        // go round once: stop when the angle passes 2π (back near the start)
        let mut angle = 0.0_f64;
        let mut last = c.w;
        let r = pseudo_arclength(&mut c, -2.0, 2.0, &mut ctl, |i, b| {
            points.push((i, b.w));
            angle += (last[0] * b.w[1] - last[1] * b.w[0]).atan2(last[0] * b.w[0] + last[1] * b.w[1]);
            last = b.w;
            angle < 2.0 * std::f64::consts::PI
        })
        .unwrap();
        assert_eq!(r.end, BranchEnd::LeftWindow);
        assert_eq!(r.folds.len(), 2, "{:?}", r.folds);
        // every point on the circle
        for (_, w) in &points {
            assert!((w[0] * w[0] + w[1] * w[1] - 1.0).abs() < 1e-12);
        }
        // first fold at η = +1, second at η = −1: bracket the fold's η
        let f0 = r.folds[0];
        assert!(f0.tangent_eta[0] > 0.0 && f0.tangent_eta[1] < 0.0 && f0.eta[0] > 0.8 && f0.eta[1] > 0.8);
        let f1 = r.folds[1];
        assert!(f1.eta[0] < -0.8 && f1.eta[1] < -0.8);
        // locate the first fold in x (monotone through it): g(x) = dη/ds = x on the
        // upper half, root x = 0, η = 1 there to O(δ²)
        let xa = points[f0.before].1[0];
        let xb = points[f0.before + 1].1[0];
        let x = locate_fold(Ok::<f64, Diverged>, xa, xb, 1e-12).unwrap();
        assert!(x.abs() < 1e-11, "{x}");
        let eta = (1.0 - x * x).sqrt();
        assert!((eta - 1.0).abs() < 1e-20_f64.max(x * x));
    }

    #[test]
    fn fold_location_errors_are_named() {
        let e = locate_fold(|x: f64| Ok::<f64, Diverged>(x * x + 1.0), -1.0, 1.0, 1e-10).unwrap_err();
        assert!(matches!(e, FoldError::NotBracketed { .. }), "{e}");
        let e = locate_fold(|x: f64| if x > 0.2 { Err(Diverged(x)) } else { Ok(x) }, -1.0, 0.5, 1e-10).unwrap_err();
        assert!(matches!(e, FoldError::Evaluation(_)), "{e}");
        let r = locate_fold(|x: f64| Ok::<f64, Diverged>(x.powi(3) - 0.125), 0.0, 1.0, 1e-12).unwrap();
        assert!((r - 0.5).abs() < 1e-10, "{r}");
    }
}
