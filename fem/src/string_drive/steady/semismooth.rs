//! The solve loop of the direct steady solve: semismooth Newton with an active set and a backtracking line search on the scaled merit, with its variable weights and row scales.

use numerics::newton::{Damping, Evaluation, NewtonError, NewtonOptions, NewtonProblem, Progress, TrialStep, Verdict};

use super::*;

/// Norm weights of X (docs/fem-drive.md §12): z as the step system (H for values, 1 for
/// slopes), R ω₁ for c, ω₁ for ω₂, 10³ F_ref/R for the tractions (they follow z; the
/// round-off of the stiff normal penalty, ≈ 10⁻⁸ N in the ν-rows, would otherwise keep
/// their update above 10⁻¹⁰ of F_ref/R).
pub(super) fn variable_weights<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, h: f64, r: f64, omega1: f64, f_ref: f64, m: usize) -> Vec<f64> {
    let mut w = super::super::system::weights(asm, h, r, 1.0);
    w.truncate(asm.len());
    w.push(r * omega1);
    w.push(omega1);
    w.extend(std::iter::repeat_n(1e3 * f_ref / r, m));
    w
}

/// Row scales of the merit ½‖F‖²: 1/F_ref for force rows, 1/(F_ref h_node) for the
/// slope rows (whose residuals are moments, N·m).
pub(super) fn row_scales<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, f_ref: f64, m: usize) -> Vec<f64> {
    let dofs = asm.dofs();
    let mut s: Vec<f64> = dofs
        .kinds()
        .iter()
        .zip(dofs.spacing())
        .map(|(k, sp)| if *k == crate::dofs::DofKind::Value { 1.0 / f_ref } else { 1.0 / (f_ref * sp) })
        .collect();
    s.extend(std::iter::repeat_n(1.0 / f_ref, 2 + m));
    s
}

pub(super) fn merit(r: &[f64], s: &[f64]) -> f64 {
    0.5 * r.iter().zip(s).map(|(a, b)| (a * b) * (a * b)).sum::<f64>()
}

/// The smallest damping factor α of the backtracking.
const MIN_DAMPING: f64 = 1.0 / 1024.0;

/// The largest α of a penalty kink on the full step for which the step is linearised
/// again at its trial ([`Semismooth`]'s `relinearise`): every point that enters contact
/// along the step does so within its first eighth, so the trial's contact set is the
/// step's from there on, and halving would spend three trials or more to reach the
/// first kink (against one Jacobian pass, one factorisation and one residual for the
/// trial's Newton step).
const RELINEARISE_KINK: f64 = 1.0 / 8.0;

/// Whether the step from pressures `before` (the unclipped penalty pressures λ − Pγ of
/// [`SteadyProblem::penalty_pressures`] at the iterate) to `after` (at the full-step
/// trial) brings at least one point into contact and every such point early: its kink,
/// where the pressure interpolated linearly in α crosses 0, at α ≤ `limit`.
fn enters_early(before: &[Option<f64>], after: &[Option<f64>], limit: f64) -> bool {
    let mut kinks = before.iter().zip(after).filter_map(|(b, a)| match (*b, *a) {
        (Some(b), Some(a)) if b <= 0.0 && a > 0.0 => Some(-b / (a - b)),
        _ => None,
    });
    kinks.next().is_some_and(|first| first <= limit && kinks.all(|k| k <= limit))
}

/// A problem with its pattern.
pub(super) struct Patterned<'p, 'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    problem: &'p SteadyProblem<'a, N, P, E, K>,
    rows: Vec<usize>,
    cols: Vec<usize>,
}

impl<'p, 'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> Patterned<'p, 'a, N, P, E, K> {
    pub(super) fn new(problem: &'p SteadyProblem<'a, N, P, E, K>) -> Self {
        let (rows, cols) = problem.pattern();
        Patterned { problem, rows, cols }
    }
}

impl<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> std::ops::Deref for Patterned<'_, 'a, N, P, E, K> {
    type Target = SteadyProblem<'a, N, P, E, K>;
    fn deref(&self) -> &SteadyProblem<'a, N, P, E, K> {
        self.problem
    }
}

/// Work of one semismooth Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SteadyNewton {
    /// Iterations.
    pub iterations: usize,
    /// Last scaled update.
    pub update_norm: f64,
}

/// The steady equations as a [`NewtonProblem`] for the semismooth Newton: the
/// generalised Jacobian of the active set of the Jacobian pass (which yields F as
/// well), trials judged by their residual (the active set may change along the step).
struct Semismooth<'s, 'p, 'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    problem: &'s Patterned<'p, 'a, N, P, E, K>,
    lu: BorderedLu,
    w: &'s [f64],
    scales: &'s [f64],
    /// The Jacobian pass at the iterate: ∂F/∂X, F and the point results.
    values: Vec<f64>,
    residual: Vec<f64>,
    results: Vec<PointResult>,
    /// The point results of the last trial evaluated (`None`: inadmissible).
    trial_results: Option<Vec<PointResult>>,
    /// The last step was a best trial, not an accepted one.
    took_best: bool,
    /// The last step was whole and below the tolerance.
    small_before: bool,
    /// Steps in a row at the round-off floor.
    floor_count: usize,
    /// The active set (slip per point) of the iterate before, for the round-off floor.
    previous_set: Option<Vec<bool>>,
    /// The Jacobian pass at the iterate (values, F, point results) while the problem is
    /// linearised at a full-step trial ([`NewtonProblem::relinearise`]).
    saved: Option<(Vec<f64>, Vec<f64>, Vec<PointResult>)>,
}

/// Why a call of [`Semismooth`] failed.
enum SemismoothError {
    /// The Jacobian pass at an accepted iterate failed.
    Inadmissible,
    /// The generalised Jacobian is singular even shifted; the LU's first message.
    Singular(String),
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> NewtonProblem for Semismooth<'_, '_, '_, N, P, E, K> {
    type Error = SemismoothError;
    fn size(&self) -> usize {
        self.problem.len()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<(), SemismoothError> {
        match self.problem.evaluate(x, false) {
            Some(et) => {
                r.copy_from_slice(&et.residual);
                self.trial_results = Some(et.results);
            }
            None => {
                r.fill(f64::NAN);
                self.trial_results = None;
            }
        }
        Ok(())
    }
    fn factorize(&mut self, _x: &[f64]) -> Result<(), SemismoothError> {
        unreachable!("Semismooth factorises with its residual")
    }
    fn factorize_with_residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<(), SemismoothError> {
        // the bordered LU factorises inside its solve
        let ev = self.problem.evaluate(x, true).ok_or(SemismoothError::Inadmissible)?;
        r.copy_from_slice(&ev.residual);
        (self.values, self.residual, self.results) = (ev.values, ev.residual, ev.results);
        Ok(())
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), SemismoothError> {
        let Err(e) = self.lu.solve(&self.values, &[], b) else { return Ok(()) };
        // a singular generalised Jacobian (an active set without a unique solution) is
        // regularised on its diagonal, Levenberg–Marquardt style, 1e-12 → 1e-4 of D
        let mut d = vec![0.0; b.len()];
        crate::newton::diagonal_sums(&self.values, &self.problem.rows, &self.problem.cols, &mut d);
        let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for f in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4] {
            let shift: Vec<f64> = d.iter().map(|v| f * v.abs().max(1e-6 * dmax).max(1e-300)).collect();
            b.iter_mut().zip(&self.residual).for_each(|(s, r)| *s = -r);
            if self.lu.solve(&self.values, &shift, b).is_ok() {
                return Ok(());
            }
        }
        Err(SemismoothError::Singular(e))
    }
    fn damping(&self) -> Damping {
        // the best trial is taken if none decreases the merit enough
        Damping::Backtracking { take_best: true }
    }
    fn evaluation(&self) -> Evaluation {
        Evaluation { residual_with_factorization: true, merit_only: false }
    }
    /// Halving without the trials that a quadratic model of the merit rejects
    /// ([`numerics::newton::skip_halvings`], the slope at α = 0 that of Newton's step on
    /// ½‖SF‖², −2m, and `accept_step`'s Armijo decrease 10⁻⁴ m). Where the residual has
    /// a kink a little ahead on the step (traced on the Exudyn drive's first solves on a
    /// new mesh: one node's row grows linearly in α from α ≈ 1/400 on, the Jacobian at
    /// the iterate not seeing it; the full step once past it converges at once), the
    /// merit is 100–350× its start at α = 1 and halving spent 10–11 trials to reach
    /// α ≈ 1/512 (docs/performance.md, seventh round).
    fn next_damping(&mut self, t: &TrialStep<'_>, previous: Option<(f64, f64)>) -> f64 {
        numerics::newton::skip_halvings(t.merit, -2.0 * t.merit, 1e-4 * t.merit, t.damping, t.trial_merit, previous, MIN_DAMPING)
    }
    /// A rejected full step whose trial brings points of the element penalty into
    /// contact, each early on the step — its kink, found by interpolating the point's
    /// unclipped pressure λ − Pγ linearly between the iterate and the trial, at α ≤
    /// [`RELINEARISE_KINK`] — while every friction point keeps its slip flag, is
    /// linearised at the trial, with the trial's contact set: the Jacobian at the
    /// iterate does not see the penalty stiffness that the step runs into, and the merit
    /// beyond the kink grows with the squared overshoot. Traced on the Exudyn drive's
    /// first solves on a mesh: the nodes at one pulley's tangent points 10⁻⁷ m off the
    /// drum at the iterate and 2·10⁻⁴ m into it at α = 1 (the kink at α ≈ 1/400), the
    /// merit 330–350× its start; halving spent 6–10 trials per iteration for two or three
    /// iterations to creep up to the kink, while the trial's own Newton step brings the
    /// merit to 10⁻⁶–10⁻⁷ of the iterate's (docs/performance.md, eighth round). Not when
    /// a slip flag changes too: the trial's slip set is then a guess that halving
    /// corrects (the fronts move an element or so per iteration; on `cosserat-drive` at
    /// 256 and 512 elements every such relinearised step was rejected, 5 and 15
    /// Jacobians wasted), nor when a point enters further on the step (the Cosserat
    /// rod's penalty points, kinks at α ≈ 0.2–0.8 next to early ones: on
    /// `cosserat-pulley` at 64 elements 11–22 such relinearised steps rejected).
    fn relinearise(&mut self, t: &TrialStep<'_>) -> bool {
        let Some(trial) = self.trial_results.as_ref() else { return false };
        if trial.iter().zip(&self.results).any(|(a, b)| a.slip != b.slip) {
            return false;
        }
        let early = enters_early(&self.problem.penalty_pressures(t.z), &self.problem.penalty_pressures(t.trial), RELINEARISE_KINK);
        if early {
            self.saved = Some((std::mem::take(&mut self.values), std::mem::take(&mut self.residual), std::mem::take(&mut self.results)));
        }
        early
    }
    fn restore_factorization(&mut self, _x: &[f64]) -> Result<(), SemismoothError> {
        if let Some((values, residual, results)) = self.saved.take() {
            (self.values, self.residual, self.results) = (values, residual, results);
        }
        Ok(())
    }
    fn norm(&self, v: &[f64], _x: &[f64]) -> f64 {
        super::super::system::scaled_norm(v, self.w)
    }
    fn merit(&mut self, _x: &[f64], r: &[f64]) -> f64 {
        merit(r, self.scales)
    }
    /// Armijo on ½‖F‖²; a step below the tolerance is taken at its first admissible
    /// trial (the merit is at round-off).
    fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
        if t.correction <= t.tolerance || t.trial_merit <= (1.0 - 1e-4 * t.damping) * t.merit {
            Verdict::Accept
        } else {
            Verdict::Reject
        }
    }
    fn converged(&mut self, p: &Progress<'_>) -> bool {
        self.took_best = p.best_trial;
        let small = p.correction <= p.tolerance;
        let same_set = !p.best_trial
            && self.trial_results.as_ref().is_some_and(|t| t.iter().zip(&self.results).all(|(a, b)| a.slip == b.slip));
        // the round-off floor: steps within 10³ of the tolerance that no longer reduce
        // the merit by 10 % for 3 iterations on the same active set (fine meshes of a
        // stiff normal penalty). A best trial (no trial decreased the merit enough, the
        // line search at its floor) keeps the set if the iterate's is the previous
        // iterate's: on strongly graded meshes the whole step stalls at 1–2× the
        // tolerance there (docs/fem-cosserat.md §11.1)
        let set: Vec<bool> = self.results.iter().map(|r| r.slip).collect();
        let kept = if p.best_trial { self.previous_set.as_ref() == Some(&set) } else { same_set };
        self.previous_set = Some(set);
        self.floor_count = if p.correction <= 1e3 * p.tolerance && kept && p.merit_after > 0.9 * p.merit_before { self.floor_count + 1 } else { 0 };
        // converged: a whole step below the tolerance that kept the active set, or two
        // in a row (a point exactly at its slip bound may flip at round-off)
        if (p.damping == 1.0 && small && (same_set || self.small_before)) || self.floor_count >= 3 {
            return true;
        }
        self.small_before = p.damping == 1.0 && small;
        false
    }
}

/// Semismooth Newton on F(X) = 0 from `x` (overwritten on success):
/// [`numerics::newton::solve`] with the generalised Jacobian of the current active set,
/// a backtracking line search on the merit ½‖F‖² (the best trial is taken if none
/// decreases it enough — the active set may change along the step), converged when
/// the full step's scaled norm is ≤ `tolerance` and the active set did not change (or
/// two such steps in a row, or the round-off floor).
///
/// # Errors
/// [`NewtonFailure`] with the iteration count and the last update norm.
pub fn newton<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(problem: &SteadyProblem<N, P, E, K>, x: &mut [f64], w: &[f64], scales: &[f64], tolerance: f64, max_iterations: usize) -> Result<SteadyNewton, NewtonFailure> {
    let n = x.len();
    let problem = &Patterned::new(problem);
    let lu = cached_lu(&problem.rows, &problem.cols, n, [problem.ic(), problem.iw()])?;
    let mut semismooth = Semismooth {
        problem,
        lu,
        w,
        scales,
        values: Vec::new(),
        residual: Vec::new(),
        results: Vec::new(),
        trial_results: None,
        took_best: false,
        small_before: false,
        floor_count: 0,
        previous_set: None,
        saved: None,
    };
    let opts = NewtonOptions { tolerance, max_iterations, min_damping: MIN_DAMPING };
    let solved = numerics::newton::solve(&mut semismooth, x, &opts);
    LU_CACHE.with(|c| *c.borrow_mut() = Some((problem.rows.clone(), problem.cols.clone(), [problem.ic(), problem.iw()], semismooth.lu)));
    let stats = solved.map_err(|e| match e {
        // the state of the last iterate is checked before the iteration limit
        NewtonError::MaxIterations { iterations, .. } if problem.evaluate(x, true).is_none() => NewtonFailure::Inadmissible { iteration: iterations },
        NewtonError::MaxIterations { iterations, correction, .. } => NewtonFailure::NotConverged { iterations, update: correction, tolerance },
        NewtonError::LineSearchFailed { iteration, correction, .. } => NewtonFailure::LineSearch { what: "no admissible step", iteration, update: correction },
        NewtonError::NonFinite { iteration, .. } | NewtonError::Problem { iteration, error: SemismoothError::Inadmissible, .. } => {
            NewtonFailure::Inadmissible { iteration: iteration.saturating_sub(1) }
        }
        NewtonError::Problem { iteration, error: SemismoothError::Singular(detail), .. } => NewtonFailure::Singular { matrix: "Jacobian", iteration, detail },
        NewtonError::SingularStep { iteration, .. } => NewtonFailure::Singular { matrix: "Jacobian", iteration, detail: "non-finite Newton step".into() },
        NewtonError::InvalidOptions(_) | NewtonError::DimensionMismatch { .. } | NewtonError::DampingExhausted { .. } => {
            NewtonFailure::NotConverged { iterations: 0, update: f64::INFINITY, tolerance }
        }
    })?;
    // a point taken as stick only to give its pulley an equation (see `evaluate`) must
    // obey Coulomb's bound by itself at the solution (the accepted trial's results); a
    // point of Paper D's fixed topology sticks whatever its traction (its excess is the
    // scheme's matching measure, `paper_d`)
    let after = if semismooth.took_best { None } else { semismooth.trial_results };
    if let Some(p) = after.and_then(|r| r.into_iter().find(|p| !p.slip && p.point.fixed.is_none() && p.traction.abs() > problem.sp.mu * p.normal * (1.0 + 1e-8) + 1e-12)) {
        return Err(NewtonFailure::NoCoulombState { traction: p.traction.abs(), bound: problem.sp.mu * p.normal, sigma: p.point.sigma });
    }
    Ok(SteadyNewton { iterations: stats.iterations, update_norm: stats.last_correction })
}

/// A bordered LU with its pattern (rows, cols, border), kept for the next solve.
type CachedLu = (Vec<usize>, Vec<usize>, [usize; 2], BorderedLu);

thread_local! {
    /// The bordered LU of this thread's last [`newton`] solve: the steps of a load
    /// continuation, the rungs of a penalty ladder and the solves of Paper D's scheme
    /// repeat one sparsity pattern, whose symbolic factorisation (as costly as 1–2
    /// numeric ones, measured) is then done once.
    static LU_CACHE: std::cell::RefCell<Option<CachedLu>> = const { std::cell::RefCell::new(None) };
}

/// The bordered LU of the pattern (`rows`, `cols`) of size `n` with `border`: the cached
/// one if its pattern is this one, else a new one (its symbolic factorisation done).
fn cached_lu(rows: &[usize], cols: &[usize], n: usize, border: [usize; 2]) -> Result<BorderedLu, NewtonFailure> {
    let cached = LU_CACHE.with(|c| c.borrow_mut().take());
    match cached {
        Some((r, c, b, lu)) if b == border && lu.dim() == n && r == rows && c == cols => Ok(lu),
        _ => BorderedLu::banded(rows, cols, n, border).map_err(NewtonFailure::Pattern),
    }
}

/// [`newton`] on `problem` from `x`; if it fails, [`penalty_ladder`] from the same `x`
/// (a refit whose kink moved between elements is far from equilibrium in the stiff
/// normal penalty).
///
/// # Errors
/// The ladder's first failing solve's [`NewtonFailure`].
pub fn newton_or_ladder<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(problem: &SteadyProblem<N, P, E, K>, x: &mut [f64], w: &[f64], scales: &[f64], tolerance: f64, max_iterations: usize, ladder: &[f64]) -> Result<SteadyNewton, NewtonFailure> {
    let x0 = x.to_vec();
    let solved = newton(problem, x, w, scales, tolerance, max_iterations);
    if solved.is_ok() {
        return solved;
    }
    x.copy_from_slice(&x0);
    penalty_ladder(problem, x, w, scales, tolerance, max_iterations, ladder)
}

/// [`newton`] at the normal penalty P·f for each f of `ladder` in turn (the last 1), each
/// from the previous one's solution; iterations summed.
///
/// # Errors
/// The first failing solve's [`NewtonFailure`].
pub fn penalty_ladder<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(problem: &SteadyProblem<N, P, E, K>, x: &mut [f64], w: &[f64], scales: &[f64], tolerance: f64, max_iterations: usize, ladder: &[f64]) -> Result<SteadyNewton, NewtonFailure> {
    let mut iterations = 0;
    let mut last = SteadyNewton::default();
    let penalty = problem.sp.penalty;
    for f in ladder {
        let soft = TermParams { penalty: Some(f * penalty), ..problem.params };
        let sp = SteadyParams { penalty: f * penalty, ..problem.sp };
        let p = SteadyProblem { params: soft, sp, ..*problem };
        let n = newton(&p, x, w, scales, tolerance, max_iterations)?;
        iterations += n.iterations;
        last = SteadyNewton { iterations, ..n };
    }
    Ok(last)
}

#[cfg(test)]
mod tests {
    use super::enters_early;

    /// Kinks by linear interpolation of the pressure: −1 → 399 crosses at α = 1/400,
    /// −1 → 1 at ½; a point that stays out, stays in, leaves or is out of reach is no
    /// kink; one late kink next to an early one spoils the set.
    #[test]
    fn early_entries_by_the_interpolated_kink() {
        let limit = 1.0 / 8.0;
        assert!(enters_early(&[Some(-1.0), Some(-5.0), Some(3.0)], &[Some(399.0), Some(-1.0), Some(4.0)], limit));
        assert!(!enters_early(&[Some(-1.0)], &[Some(1.0)], limit));
        // exactly at the limit: −1 → 7 crosses at ⅛
        assert!(enters_early(&[Some(-1.0)], &[Some(7.0)], limit));
        assert!(!enters_early(&[Some(-1.0)], &[Some(6.9)], limit));
        // no point enters: staying out, staying in, leaving, out of reach
        assert!(!enters_early(&[Some(-1.0), Some(2.0), Some(2.0), None, Some(-1.0)], &[Some(-0.5), Some(3.0), Some(-2.0), Some(5.0), None], limit));
        assert!(!enters_early(&[], &[], limit));
        // an early and a late one (the Cosserat rod's kinks at 0.5 next to 0.03)
        assert!(!enters_early(&[Some(-0.03), Some(-1.0)], &[Some(0.97), Some(1.0)], limit));
        // a point touching at the iterate (pressure 0) and pressed at the trial: α = 0
        assert!(enters_early(&[Some(0.0)], &[Some(1.0)], limit));
    }
}
