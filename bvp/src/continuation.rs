//! Continuation in the scalar parameter η: natural-parameter (homotopy) and
//! pseudo-arclength, with step control, mesh adaptation and fold location.
//!
//! Notation: F(z, η) = 0 are the collocation equations on a mesh
//! ([`crate::collocation`]), z ∈ R^n their unknowns, w = (z, η) ∈ R^{n+1}. Inner
//! product and norm on w (mesh-independent RMS of the state plus η):
//!
//! ```text
//!     ⟨a, b⟩_w = (1/n) Σ_{i<n} a_i b_i + a_η b_η,      ‖a‖_w = ⟨a, a⟩_w^{1/2}.
//! ```
//!
//! # Bordered systems (all sparse; no dense row)
//!
//! The *local-parametrisation* matrix with coordinate m ∈ {0, …, n} (m = n means η),
//!
//! ```text
//!     Â(m) = [ ∂F/∂z   ∂F/∂η ]
//!            [     e_mᵀ      ],
//! ```
//!
//! is nonsingular along a branch wherever the branch's tangent has a non-zero m-th
//! component — in particular at a fold if m is a state coordinate (Rheinboldt,
//! "Numerical Analysis of Parametrized Nonlinear Equations", 1986). It is factorised
//! with the sparse LU of [`crate::newton::SparseLu`]; the tangent is Â(m)⁻¹ e_{n+1},
//! normalised. The pseudo-arclength matrix, whose last row is the dense vector
//! (t_z/n, t_η), is solved by Sherman–Morrison from Â(m) (m = argmax |t_i|), so that
//! no dense row ever enters the sparse factorisation (a dense row would make faer's
//! column-elimination-tree bound dense).
//!
//! # Fold location
//!
//! A fold is detected when the η-component of the oriented tangent changes sign
//! between two accepted points a and b. It is then located on b's mesh: with m the
//! state coordinate that changes most from a to b and s = z_m, the function
//! g(s) = dη/dz_m (the η-component of Â(m)⁻¹ e_{n+1} at the solution of
//! F(z, η) = 0, z_m = s) changes sign on [s_a, s_b]; its root is found with argmin's
//! Brent method. η is stationary at the fold, so an error δs in s costs only O(δs²)
//! in η. If the residual there exceeds the tolerance the mesh is refined and the fold
//! located again.

use crate::collocation::discretisation::{validate_solution, Discretisation};
use crate::collocation::{adapt, check_node_cap, mesh, Adapted, CollocationOptions, Corrector, FixedEta};
use crate::error::BvpError;
use crate::newton::{self, NewtonReport, NewtonSystem, SparseLu};
use crate::problem::Problem;
use crate::solution::{Solution, Stats};
use numerics::continuation::{ContinuationError, Homotopy, Step, StepControl};
use std::time::Instant;

/// Options of [`natural`] and [`pseudo_arclength`]. Serialisable.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ContinuationOptions {
    /// First step: |Δη| for [`natural`], the arclength Δs in ‖·‖_w for
    /// [`pseudo_arclength`]. Default 0.1; valid in [min_step, max_step].
    pub initial_step: f64,
    /// Smallest step; a failure below it is [`BvpError::ContinuationStalled`].
    /// Default 1e-8; valid > 0.
    pub min_step: f64,
    /// Largest step. Default 0.5; valid ≥ min_step.
    pub max_step: f64,
    /// Step growth factor after a quick step. Default 1.5; valid (1, 10].
    pub growth: f64,
    /// A step is quick if all its Newton iterations (over all its mesh passes) are at
    /// most this. Default 4.
    pub fast_iterations: usize,
    /// Maximum number of accepted steps. [`natural`] fails with
    /// [`BvpError::ContinuationStalled`] when η_to is not reached by then;
    /// [`pseudo_arclength`] ends the branch ([`Termination::MaxSteps`]). Default 500;
    /// valid ≥ 1.
    pub max_steps: usize,
    /// Locate folds found by [`pseudo_arclength`]. Default `true`.
    pub locate_folds: bool,
    /// Brent tolerance on the fold coordinate s, relative to 1 + max(|s_a|, |s_b|).
    /// Default 1e-10; valid (0, 1e-2].
    pub fold_tolerance: f64,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        Self {
            initial_step: 0.1,
            min_step: 1e-8,
            max_step: 0.5,
            growth: 1.5,
            fast_iterations: 4,
            max_steps: 500,
            locate_folds: true,
            fold_tolerance: 1e-10,
        }
    }
}

impl ContinuationOptions {
    /// Check the documented ranges.
    pub fn validate(&self) -> Result<(), BvpError> {
        let bad = |m: String| Err(BvpError::InvalidInput(m));
        if !(self.min_step > 0.0 && self.min_step.is_finite()) {
            return bad(format!("continuation min_step {} must be > 0", self.min_step));
        }
        if !(self.max_step >= self.min_step && self.max_step.is_finite()) {
            return bad(format!("continuation max_step {} < min_step {}", self.max_step, self.min_step));
        }
        if !(self.initial_step >= self.min_step && self.initial_step <= self.max_step) {
            return bad(format!(
                "continuation initial_step {} outside [min_step, max_step] = [{}, {}]",
                self.initial_step, self.min_step, self.max_step
            ));
        }
        if !(self.growth > 1.0 && self.growth <= 10.0) {
            return bad(format!("continuation growth {} outside (1, 10]", self.growth));
        }
        if self.max_steps == 0 {
            return bad("continuation max_steps must be ≥ 1".into());
        }
        if !(self.fold_tolerance > 0.0 && self.fold_tolerance <= 1e-2) {
            return bad(format!("fold_tolerance {} outside (0, 1e-2]", self.fold_tolerance));
        }
        Ok(())
    }
}

/// One accepted point of a branch.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BranchPoint {
    /// The solution (its `stats` are the work of this step only).
    pub solution: Solution,
    /// η of the point.
    pub eta: f64,
    /// The step that led here (0 for the first point): |Δη| or Δs.
    pub step: f64,
    /// dη/ds, the η-component of the unit tangent (pseudo-arclength only).
    pub tangent_eta: Option<f64>,
}

/// A located fold (limit point) of the branch.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Fold {
    /// η at the fold.
    pub eta: f64,
    /// The solution at the fold (on the mesh used to locate it).
    pub solution: Solution,
    /// The fold lies between `points[after_point]` and `points[after_point + 1]`.
    pub after_point: usize,
    /// The state coordinate s = z_m used to locate it, in words.
    pub coordinate: String,
    /// Its value at the fold.
    pub coordinate_value: f64,
    /// Evaluations of g(s) = dη/ds (each one bordered Newton solve).
    pub evaluations: usize,
}

/// Why a branch ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Termination {
    /// [`natural`] reached η_to.
    Reached,
    /// [`pseudo_arclength`] left the η interval (the last point lies just outside).
    LeftInterval,
    /// [`pseudo_arclength`] took `max_steps` steps.
    MaxSteps,
}

/// A computed branch.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Branch {
    /// Accepted points in order.
    pub points: Vec<BranchPoint>,
    /// Located folds (pseudo-arclength with `locate_folds`).
    pub folds: Vec<Fold>,
    /// Why the branch ended.
    pub termination: Termination,
    /// Totals over the branch, failed attempts and fold location included
    /// (`unknowns`, `mesh_nodes` of the last point; `max_residual` over the points).
    pub stats: Stats,
}

impl Branch {
    /// The last solution (for [`natural`]: the one at η_to).
    pub fn last(&self) -> Option<&Solution> {
        self.points.last().map(|p| &p.solution)
    }

    /// (η, functional(solution)) for every point, e.g. for a branch diagram.
    pub fn values(&self, functional: impl Fn(&Solution) -> f64) -> Vec<(f64, f64)> {
        self.points.iter().map(|p| (p.eta, functional(&p.solution))).collect()
    }
}

/// The root of a scalar function on [a, b] (f(a) f(b) ≤ 0) by Brent's method
/// ([`numerics::roots::brent`]), to absolute tolerance `tol` in the argument. Errors of
/// `f` are passed through; the search's own failures are [`BvpError::NonFinite`] or
/// [`BvpError::InvalidInput`] with the numbers.
pub(crate) fn brent_root(f: impl FnMut(f64) -> Result<f64, BvpError>, a: f64, b: f64, tol: f64) -> Result<f64, BvpError> {
    use numerics::roots::RootError;
    numerics::roots::brent(f, a, b, tol).map_err(|e| match e {
        RootError::Evaluation(e) => e,
        e @ RootError::NonFinite { .. } => BvpError::NonFinite { what: format!("root function: {e}") },
        e => BvpError::InvalidInput(format!("Brent root: {e}")),
    })
}

/// ⟨a, b⟩_w on (z, η) vectors.
fn wdot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() - 1;
    a[..n].iter().zip(&b[..n]).map(|(x, y)| x * y).sum::<f64>() / n as f64 + a[n] * b[n]
}

fn wnorm(a: &[f64]) -> f64 {
    wdot(a, a).sqrt()
}

fn argmax_abs(v: &[f64]) -> usize {
    v.iter().enumerate().fold((0, -1.0), |(im, vm), (i, &x)| if x.abs() > vm { (i, x.abs()) } else { (im, vm) }).0
}

/// The extra equation of a bordered system.
enum Constraint {
    /// w_m − s = 0.
    Fix { s: f64 },
    /// ⟨t, w − base⟩_w − ds = 0 (solved by Sherman–Morrison from Â(m)); `u` caches
    /// Â(m)⁻¹ e_{n+1} for the current factorisation.
    Arclength { base: Vec<f64>, tangent: Vec<f64>, ds: f64, u: Vec<f64> },
}

/// Newton system in w = (z, η) for F(z, η) = 0 plus one constraint.
struct Bordered<'s, 'a, P: Problem> {
    disc: &'s Discretisation<'a, P>,
    lu: &'s mut SparseLu,
    m: usize,
    constraint: Constraint,
    rows: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
    jeta: Vec<f64>,
}

impl<'s, 'a, P: Problem> Bordered<'s, 'a, P> {
    fn new(disc: &'s Discretisation<'a, P>, lu: &'s mut SparseLu, m: usize, constraint: Constraint) -> Self {
        Self { disc, lu, m, constraint, rows: vec![], cols: vec![], vals: vec![], jeta: vec![] }
    }

    /// Factorise Â(m) at w.
    fn factor_local(&mut self, w: &[f64]) -> Result<(), BvpError> {
        let n = self.disc.n;
        self.disc.jacobian(&w[..n], w[n], &mut self.rows, &mut self.cols, &mut self.vals, &mut self.jeta);
        for i in 0..n {
            self.rows.push(i);
            self.cols.push(n);
            self.vals.push(self.jeta[i]);
        }
        self.rows.push(n);
        self.cols.push(self.m);
        self.vals.push(1.0);
        self.lu.factorize(n + 1, &self.rows, &self.cols, &self.vals)
    }

    /// Â(m)⁻¹ e_{n+1} with the current factorisation (its m-th entry is 1).
    fn local_tangent(&self) -> Result<Vec<f64>, BvpError> {
        let n = self.disc.n;
        let mut x = vec![0.0; n + 1];
        x[n] = 1.0;
        self.lu.solve_in_place(&mut x)?;
        Ok(x)
    }
}

impl<P: Problem> NewtonSystem for Bordered<'_, '_, P> {
    fn size(&self) -> usize {
        self.disc.n + 1
    }
    fn residual(&mut self, w: &[f64], r: &mut [f64]) -> Result<(), BvpError> {
        let n = self.disc.n;
        self.disc.residual(&w[..n], w[n], &mut r[..n]);
        r[n] = match &self.constraint {
            Constraint::Fix { s } => w[self.m] - s,
            Constraint::Arclength { base, tangent, ds, .. } => {
                let d: Vec<f64> = w.iter().zip(base).map(|(a, b)| a - b).collect();
                wdot(tangent, &d) - ds
            }
        };
        Ok(())
    }
    fn factorize(&mut self, w: &[f64]) -> Result<(), BvpError> {
        self.factor_local(w)?;
        if matches!(self.constraint, Constraint::Arclength { .. }) {
            let x = self.local_tangent()?;
            if let Constraint::Arclength { u, .. } = &mut self.constraint {
                *u = x;
            }
        }
        Ok(())
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), BvpError> {
        self.lu.solve_in_place(b)?;
        if let Constraint::Arclength { tangent, u, .. } = &self.constraint {
            // M = Â(m) + e_{n+1} vᵀ, v = (t_z/n, t_η) − e_m.
            let m = self.m;
            let vy = wdot(tangent, b) - b[m];
            let denom = 1.0 + wdot(tangent, u) - u[m];
            if denom.is_nan() || denom.abs() <= 1e-14 {
                return Err(BvpError::SingularJacobian {
                    iteration: 0,
                    detail: format!("pseudo-arclength bordering: Sherman–Morrison denominator {denom:e}"),
                });
            }
            let f = vy / denom;
            for (bi, ui) in b.iter_mut().zip(u) {
                *bi -= f * ui;
            }
        }
        Ok(())
    }
}

fn pack(z: &[f64], eta: f64) -> Vec<f64> {
    let mut w = z.to_vec();
    w.push(eta);
    w
}

/// Unit tangent (‖t‖_w = 1) at a solution from Â(m), with the sign of the raw solve.
fn tangent<P: Problem>(disc: &Discretisation<'_, P>, z: &[f64], eta: f64, m: usize) -> Result<Vec<f64>, BvpError> {
    let mut lu = SparseLu::new();
    let mut sys = Bordered::new(disc, &mut lu, m, Constraint::Fix { s: 0.0 });
    sys.factor_local(&pack(z, eta))?;
    let mut x = sys.local_tangent()?;
    let norm = wnorm(&x);
    if !(norm.is_finite() && norm > 0.0) {
        return Err(BvpError::SingularJacobian { iteration: 0, detail: "tangent computation".into() });
    }
    x.iter_mut().for_each(|v| *v /= norm);
    Ok(x)
}

/// Pseudo-arclength corrector: F(z, η) = 0, ⟨t, w − base⟩_w = ds.
struct PalCorrector {
    base: Vec<f64>,
    tangent: Vec<f64>,
    ds: f64,
    lu: SparseLu,
    newton: newton::NewtonOptions,
}

impl<P: Problem> Corrector<P> for PalCorrector {
    fn correct(
        &mut self,
        disc: &Discretisation<'_, P>,
        z: &mut Vec<f64>,
        eta: &mut f64,
    ) -> Result<NewtonReport, BvpError> {
        let n = disc.n;
        let m = argmax_abs(&self.tangent);
        let constraint =
            Constraint::Arclength { base: self.base.clone(), tangent: self.tangent.clone(), ds: self.ds, u: vec![] };
        let mut sys = Bordered::new(disc, &mut self.lu, m, constraint);
        let mut w = pack(z, *eta);
        let report = newton::solve(&mut sys, &mut w, &self.newton)?;
        *eta = w[n];
        w.truncate(n);
        *z = w;
        Ok(report)
    }

    /// Base point by the dense output; tangent by differencing the dense-output map
    /// along it (step 1e-7 (1 + ‖base‖_∞)), renormalised on the new mesh.
    fn transfer(
        &mut self,
        old: &Discretisation<'_, P>,
        _old_z: &[f64],
        _old_eta: f64,
        new: &Discretisation<'_, P>,
    ) -> Result<(), BvpError> {
        let n = old.n;
        let eta0 = self.base[n];
        let base_sol = old.to_solution(&self.base[..n], eta0, Stats::default());
        let zb = new.sample(&base_sol)?;
        let eps = 1e-7 * (1.0 + self.base.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
        let shifted: Vec<f64> = self.base[..n].iter().zip(&self.tangent).map(|(b, t)| b + eps * t).collect();
        let shifted_sol = old.to_solution(&shifted, eta0 + eps * self.tangent[n], Stats::default());
        let zs = new.sample(&shifted_sol)?;
        let mut t: Vec<f64> = zs.iter().zip(&zb).map(|(a, b)| (a - b) / eps).collect();
        t.push(self.tangent[n]);
        let norm = wnorm(&t);
        if !(norm.is_finite() && norm > 0.0) {
            return Err(BvpError::NonFinite { what: "transferred tangent".into() });
        }
        t.iter_mut().for_each(|v| *v /= norm);
        self.base = pack(&zb, eta0);
        self.tangent = t;
        self.lu = SparseLu::new();
        Ok(())
    }
}

/// The corrector run of one continuation step (natural or pseudo-arclength): the
/// adapted point and what its statistics need ([`Adapted::solution`]).
struct StepSolve<'p, P: Problem> {
    adapted: Adapted<'p, P>,
    stats: Stats,
    start: Instant,
    rhs_baseline: usize,
}

/// Adaptive solve of a step from the predictor (`z0`, `eta0`) on a copy of the mesh of
/// the accepted point `cur`, with `corrector`; its Newton work is added to `total`
/// whether it converges or not. `Ok(Err(cause))`: a failure a smaller step may mend
/// ([`retryable`]); `Err`: one it may not.
fn step_solve<'p, P: Problem, C: Corrector<P>>(
    cur: &Adapted<'p, P>,
    z0: Vec<f64>,
    eta0: f64,
    corrector: &mut C,
    opts: &CollocationOptions,
    total: &mut Stats,
) -> Result<Result<StepSolve<'p, P>, String>, BvpError> {
    let disc = cur.disc.with_meshes(cur.disc.meshes.clone())?;
    let rhs_baseline = cur.disc.rhs_evals.get();
    let start = Instant::now();
    let mut stats = Stats::default();
    match adapt(disc, z0, eta0, corrector, opts, &mut stats) {
        Ok(adapted) => {
            total.add_iterations(&stats);
            Ok(Ok(StepSolve { adapted, stats, start, rhs_baseline }))
        }
        Err(e) if retryable(&e) => {
            total.add_iterations(&stats);
            Ok(Err(e.to_string()))
        }
        Err(e) => Err(e),
    }
}

/// Whether a failed step should be retried with a smaller step.
fn retryable(e: &BvpError) -> bool {
    matches!(e, BvpError::NewtonDiverged { .. } | BvpError::SingularJacobian { .. } | BvpError::NonFinite { .. })
}

/// The first point: a plain adaptive solve of `guess` at `eta`.
fn first_point<'a, P: Problem>(
    problem: &'a P,
    guess: &Solution,
    eta: f64,
    opts: &CollocationOptions,
    total: &mut Stats,
) -> Result<(Adapted<'a, P>, Solution), BvpError> {
    validate_solution(problem, guess, "guess")?;
    let meshes: Vec<Vec<f64>> = guess.segments.iter().map(|s| s.mesh.clone()).collect();
    check_node_cap(&meshes, opts)?;
    let disc = Discretisation::new(problem, opts.scheme, opts.jacobian, meshes)?;
    let z = disc.sample(guess)?;
    let t0 = Instant::now();
    let mut st = Stats::default();
    let a = adapt(disc, z, eta, &mut FixedEta::new(opts), opts, &mut st)?;
    total.add_iterations(&st);
    let sol = a.solution(st, t0, 0);
    Ok((a, sol))
}

fn finish_stats<P: Problem>(total: &mut Stats, last: &Adapted<'_, P>, points: &[BranchPoint], start: Instant) {
    total.unknowns = last.disc.n;
    total.mesh_nodes = last.disc.n_nodes();
    total.rhs_evaluations = last.disc.rhs_evals.get();
    total.max_residual = points.iter().fold(0.0_f64, |m, p| m.max(p.solution.stats.max_residual));
    total.wall_seconds = start.elapsed().as_secs_f64();
}

/// Natural-parameter continuation (homotopy) from η_from to η_to.
///
/// Solves at η_from from `guess` (its own `eta` is ignored), then steps η towards
/// η_to: predictor = secant extrapolation through the last two points (the previous
/// solution sampled on the current mesh; the current solution for the first step),
/// corrector = the adaptive collocation solve at the new η. A step whose Newton
/// iterations stay ≤ `fast_iterations` grows the next by `growth` (up to `max_step`); a
/// failed step (Newton divergence, singular Jacobian, non-finite values) is halved and
/// retried. The last point of the returned branch is at exactly η_to.
///
/// Errors: [`BvpError::ContinuationStalled`] (step below `min_step`, with the last
/// failure as cause, or `max_steps` reached; typically at a fold, where natural
/// continuation cannot pass), the errors of [`crate::collocation::solve`].
pub fn natural<P: Problem>(
    problem: &P,
    guess: &Solution,
    eta_from: f64,
    eta_to: f64,
    copts: &ContinuationOptions,
    opts: &CollocationOptions,
) -> Result<Branch, BvpError> {
    natural_checked(problem, guess, eta_from, eta_to, copts, opts, |_| Ok(()))
}

/// [`natural`] with a problem-specific acceptance test: a converged step whose solution
/// `accept` rejects (returning the reason) is treated like a failed step — halved and
/// retried — so that the path cannot jump to a spurious solution of the discrete
/// equations (e.g. one with a negative tension). The reason of the last rejection is the
/// cause of [`BvpError::ContinuationStalled`] if the step falls below `min_step`.
pub fn natural_checked<P: Problem>(
    problem: &P,
    guess: &Solution,
    eta_from: f64,
    eta_to: f64,
    copts: &ContinuationOptions,
    opts: &CollocationOptions,
    accept: impl Fn(&Solution) -> Result<(), String>,
) -> Result<Branch, BvpError> {
    let start = Instant::now();
    copts.validate()?;
    opts.validate()?;
    if !(eta_from.is_finite() && eta_to.is_finite()) {
        return Err(BvpError::InvalidInput(format!("eta range [{eta_from}, {eta_to}] not finite")));
    }
    let mut total = Stats::default();
    let (cur, sol) = first_point(problem, guess, eta_from, opts, &mut total)?;
    let points = vec![BranchPoint { solution: sol, eta: eta_from, step: 0.0, tangent_eta: None }];
    let mut control = step_control(copts, numerics::continuation::StepLimit::Accepted(copts.max_steps))?;
    let mut path = NaturalPath { opts, accept: &accept, cur, points, total, corrector: FixedEta::new(opts) };
    let stalled = |eta: f64, step: f64, cause: String| BvpError::ContinuationStalled { eta, step, min_step: copts.min_step, cause };
    match numerics::continuation::natural(&mut path, eta_from, eta_to, &mut control, &[]) {
        Ok(_) => {}
        Err(ContinuationError::Aborted(e)) => return Err(e),
        Err(ContinuationError::Stalled { eta, step, cause, .. }) => return Err(stalled(eta.0, step.0, cause.unwrap_or_default())),
        Err(ContinuationError::StepLimit { eta, step, .. }) => {
            return Err(stalled(eta.0, step.0, format!("max_steps = {} reached before eta = {eta_to}", copts.max_steps)))
        }
    }
    let NaturalPath { cur, points, mut total, .. } = path;
    finish_stats(&mut total, &cur, &points, start);
    Ok(Branch { points, folds: vec![], termination: Termination::Reached, stats: total })
}

/// The step control of [`ContinuationOptions`]: the step grows by `growth` after a step
/// of at most `fast_iterations` Newton iterations (up to `max_step`), halves after a
/// failure; the end η is taken when within 1e-12 of a step.
fn step_control(copts: &ContinuationOptions, limit: numerics::continuation::StepLimit) -> Result<StepControl, BvpError> {
    use numerics::continuation::{Growth, StepOptions};
    StepControl::new(StepOptions {
        initial: copts.initial_step,
        min: copts.min_step,
        max: copts.max_step,
        shrink: 0.5,
        limit,
        growth: Growth::Quick { fast: copts.fast_iterations, factor: copts.growth },
        snap: 1e-12,
    })
    .map_err(|e| BvpError::InvalidInput(e.to_string()))
}

/// Natural continuation on collocation meshes as a [`Homotopy`]: the accepted point
/// (`cur`, its adapted mesh), the branch so far and the work counters.
struct NaturalPath<'a, 'p, P: Problem, A> {
    opts: &'a CollocationOptions,
    accept: &'a A,
    cur: Adapted<'p, P>,
    points: Vec<BranchPoint>,
    total: Stats,
    /// One corrector for all steps: its symbolic factorisation serves every step on the
    /// same mesh.
    corrector: FixedEta,
}

impl<'p, P: Problem, A: Fn(&Solution) -> Result<(), String>> Homotopy for NaturalPath<'_, 'p, P, A> {
    /// The cause of a rejected step, in words.
    type Failure = String;
    type Error = BvpError;

    /// Predictor: secant extrapolation through the last two points (the previous
    /// solution sampled on the current mesh; the current solution for the first step);
    /// corrector: the adaptive collocation solve at the new η, then the acceptance test.
    fn advance(&mut self, eta: f64, target: f64) -> Result<Step<String>, BvpError> {
        let cur = &self.cur;
        let mut z0 = cur.z.clone();
        if self.points.len() >= 2 {
            let prev = &self.points[self.points.len() - 2].solution;
            let zp = cur.disc.sample(prev)?;
            let ratio = (target - cur.eta) / (cur.eta - prev.eta);
            for (zi, (&zc, &zq)) in z0.iter_mut().zip(cur.z.iter().zip(&zp)) {
                *zi = zc + ratio * (zc - zq);
            }
        }
        let StepSolve { adapted: a, stats: st, start: t0, rhs_baseline: baseline } =
            match step_solve(cur, z0, target, &mut self.corrector, self.opts, &mut self.total)? {
                Ok(step) => step,
                Err(reason) => return Ok(Step::Rejected(reason)),
            };
        let iterations = st.newton_iterations;
        let sol = a.solution(st, t0, baseline);
        if let Err(reason) = (self.accept)(&sol) {
            return Ok(Step::Rejected(format!("step to eta = {target:.6e} rejected: {reason}")));
        }
        self.points.push(BranchPoint { solution: sol, eta: target, step: (target - eta).abs(), tangent_eta: None });
        self.cur = a;
        Ok(Step::Accepted { iterations })
    }
}

/// Pseudo-arclength continuation from the solution near `guess` (at `guess.eta`),
/// leaving in the direction where η increases if `direction` > 0 (decreases if < 0),
/// until η leaves [`eta_min`, `eta_max`] or `max_steps` steps are taken.
///
/// Step: predictor w + Δs t; corrector = Newton on F(z, η) = 0,
/// ⟨t, w − w_prev⟩_w = Δs (module documentation) on the current mesh, followed by mesh
/// adaptation (the base point and tangent are carried to a new mesh with the dense
/// output and the corrector re-run there). The new tangent is oriented along the
/// secant from the previous point. Step control as in [`natural`], in Δs. Folds are
/// detected by a sign change of dη/ds and, with `locate_folds`, located by
/// [`Fold`]'s procedure (module documentation).
///
/// Errors: [`BvpError::ContinuationStalled`] (step below `min_step`),
/// [`BvpError::FoldLocationFailed`], the errors of [`crate::collocation::solve`].
pub fn pseudo_arclength<P: Problem>(
    problem: &P,
    guess: &Solution,
    direction: f64,
    eta_min: f64,
    eta_max: f64,
    copts: &ContinuationOptions,
    opts: &CollocationOptions,
) -> Result<Branch, BvpError> {
    let start = Instant::now();
    copts.validate()?;
    opts.validate()?;
    if !(direction != 0.0 && direction.is_finite()) {
        return Err(BvpError::InvalidInput(format!("direction {direction} must be non-zero")));
    }
    if !(eta_min < eta_max && eta_min <= guess.eta && guess.eta <= eta_max) {
        return Err(BvpError::InvalidInput(format!(
            "need eta_min < eta_max with the guess's eta = {} inside [{eta_min}, {eta_max}]",
            guess.eta
        )));
    }
    let mut total = Stats::default();
    let (cur, sol) = first_point(problem, guess, guess.eta, opts, &mut total)?;
    let n0 = cur.disc.n;
    let mut t = tangent(&cur.disc, &cur.z, cur.eta, n0)?;
    if t[n0] * direction < 0.0 {
        t.iter_mut().for_each(|v| *v = -*v);
    }
    let points = vec![BranchPoint { solution: sol, eta: cur.eta, step: 0.0, tangent_eta: Some(t[n0]) }];
    let mut control = step_control(copts, numerics::continuation::StepLimit::Accepted(copts.max_steps))?;
    let mut path = ArclengthPath { copts, opts, cur, t, points, folds: Vec::new(), total };
    let report = match numerics::continuation::pseudo_arclength(&mut path, eta_min, eta_max, &mut control, |_, _| true) {
        Ok(report) => report,
        Err(ContinuationError::Aborted(e)) => return Err(e),
        Err(ContinuationError::Stalled { eta, step, cause, .. }) => {
            return Err(BvpError::ContinuationStalled { eta: eta.0, step: step.0, min_step: copts.min_step, cause: cause.unwrap_or_default() })
        }
        // (numerics' pseudo_arclength ends a branch at its step limit with `Ok`)
        Err(ContinuationError::StepLimit { eta, step, .. }) => {
            return Err(BvpError::ContinuationStalled { eta: eta.0, step: step.0, min_step: copts.min_step, cause: "step limit".into() })
        }
    };
    let termination = match report.end {
        numerics::continuation::BranchEnd::LeftWindow => Termination::LeftInterval,
        numerics::continuation::BranchEnd::StepLimit => Termination::MaxSteps,
    };
    let ArclengthPath { cur, points, folds, mut total, .. } = path;
    finish_stats(&mut total, &cur, &points, start);
    Ok(Branch { points, folds, termination, stats: total })
}

/// Pseudo-arclength continuation on collocation meshes as a [`numerics::continuation::Branch`]:
/// the accepted point (`cur`, its adapted mesh) with its oriented unit tangent `t`, the
/// branch so far, the located folds and the work counters.
struct ArclengthPath<'a, 'p, P: Problem> {
    copts: &'a ContinuationOptions,
    opts: &'a CollocationOptions,
    cur: Adapted<'p, P>,
    t: Vec<f64>,
    points: Vec<BranchPoint>,
    folds: Vec<Fold>,
    total: Stats,
}

impl<P: Problem> numerics::continuation::Branch for ArclengthPath<'_, '_, P> {
    /// The cause of a rejected step, in words.
    type Failure = String;
    type Error = BvpError;

    fn eta(&self) -> f64 {
        self.cur.eta
    }

    fn tangent_eta(&self) -> f64 {
        self.t[self.cur.disc.n]
    }

    /// Predictor w + Δs t; corrector: Newton on F = 0 with the arclength condition,
    /// then mesh adaptation; the new tangent is oriented along the secant from the
    /// previous point, and a fold between the two (sign change of dη/ds) is located at
    /// once on the new mesh when `locate_folds` is set.
    fn advance(&mut self, ds: f64) -> Result<Step<String>, BvpError> {
        let (cur, t) = (&self.cur, &self.t);
        let n = cur.disc.n;
        let z0: Vec<f64> = cur.z.iter().zip(t).map(|(z, ti)| z + ds * ti).collect();
        let eta0 = cur.eta + ds * t[n];
        let mut corrector =
            PalCorrector { base: pack(&cur.z, cur.eta), tangent: t.clone(), ds, lu: SparseLu::new(), newton: self.opts.newton() };
        let StepSolve { adapted: a, stats: st, start: t0, rhs_baseline: baseline } =
            match step_solve(cur, z0, eta0, &mut corrector, self.opts, &mut self.total)? {
                Ok(step) => step,
                Err(reason) => return Ok(Step::Rejected(reason)),
            };
        let iterations = st.newton_iterations;
        let prev = &self.points[self.points.len() - 1].solution;
        let zp = a.disc.sample(prev)?;
        let mut secant: Vec<f64> = a.z.iter().zip(&zp).map(|(x, y)| x - y).collect();
        secant.push(a.eta - prev.eta);
        let m = argmax_abs(&secant);
        let mut t_new = tangent(&a.disc, &a.z, a.eta, m)?;
        if wdot(&t_new, &secant) < 0.0 {
            t_new.iter_mut().for_each(|v| *v = -*v);
        }
        let n_new = a.disc.n;
        let sol = a.solution(st, t0, baseline);
        let fold_here = t[n] * t_new[n_new] < 0.0;
        self.points.push(BranchPoint { solution: sol, eta: a.eta, step: ds, tangent_eta: Some(t_new[n_new]) });
        if fold_here && self.copts.locate_folds {
            let i = self.points.len() - 2;
            let fold = locate_fold(&self.points[i].solution, &a, i, self.copts, self.opts, &mut self.total)?;
            self.folds.push(fold);
        }
        self.cur = a;
        self.t = t_new;
        Ok(Step::Accepted { iterations })
    }
}

/// Describe unknown `m` of `disc` in words.
fn describe<P: Problem>(disc: &Discretisation<'_, P>, m: usize) -> String {
    let s = disc.tab.s;
    for k in 0..disc.n_segments() {
        if m < disc.offsets[k + 1] {
            let n = disc.dims[k];
            let local = m - disc.offsets[k];
            let (i, rest) = (local / ((s + 1) * n), local % ((s + 1) * n));
            let (slot, a) = (rest / n, rest % n);
            let name = disc.problem.component_names(k).get(a).cloned().unwrap_or_else(|| format!("y{a}"));
            return if slot == 0 {
                format!("{name} of segment {k} at x = {:.6}", disc.meshes[k][i])
            } else {
                format!("{name} of segment {k}, stage {} of interval {i}", slot - 1)
            };
        }
    }
    let q = m - disc.offsets[disc.n_segments()];
    disc.problem.param_names().get(q).cloned().unwrap_or_else(|| format!("p{q}"))
}

/// Locate the fold between `a` (a solution) and the accepted point `b` (module
/// documentation), refining b's mesh if the fold solution misses the tolerance.
fn locate_fold<P: Problem>(
    a: &Solution,
    b: &Adapted<'_, P>,
    after_point: usize,
    copts: &ContinuationOptions,
    opts: &CollocationOptions,
    total: &mut Stats,
) -> Result<Fold, BvpError> {
    let t0 = Instant::now();
    let baseline = b.disc.rhs_evals.get();
    let fail = |detail: String| BvpError::FoldLocationFailed { eta_a: a.eta, eta_b: b.eta, detail };
    let b_sol = b.disc.to_solution(&b.z, b.eta, Stats::default());
    let mut disc = b.disc.with_meshes(b.disc.meshes.clone())?;
    let mut evaluations = 0;
    let mut newton_iterations = 0;
    for _ in 0..opts.max_refinements {
        let n = disc.n;
        let wa = pack(&disc.sample(a)?, a.eta);
        let wb = pack(&disc.sample(&b_sol)?, b.eta);
        let d: Vec<f64> = wb[..n].iter().zip(&wa[..n]).map(|(x, y)| x - y).collect();
        let m = argmax_abs(&d);
        let (sa, sb) = (wa[m], wb[m]);
        if sa == sb {
            return Err(fail("the two points coincide".into()));
        }
        let mut lu = SparseLu::new();
        let mut last: Option<Vec<f64>> = None;
        let newton_opts = opts.newton();
        // g(s) = dη/dz_m at the solution with z_m = s.
        let mut g = |s: f64| -> Result<f64, BvpError> {
            let r = (s - sa) / (sb - sa);
            let mut w: Vec<f64> = wa.iter().zip(&wb).map(|(x, y)| x + r * (y - x)).collect();
            let mut sys = Bordered::new(&disc, &mut lu, m, Constraint::Fix { s });
            let rep = newton::solve(&mut sys, &mut w, &newton_opts)?;
            newton_iterations += rep.iterations + 1;
            sys.factor_local(&w)?;
            let x = sys.local_tangent()?;
            evaluations += 1;
            last = Some(w);
            Ok(x[n])
        };
        let (ga, gb) = (g(sa)?, g(sb)?);
        if ga * gb > 0.0 {
            return Err(fail(format!("dη/ds has the same sign at both ends ({ga:e}, {gb:e})")));
        }
        let tol = copts.fold_tolerance * (1.0 + sa.abs().max(sb.abs()));
        let root = brent_root(&mut g, sa, sb, tol).map_err(|e| fail(e.to_string()))?;
        g(root)?;
        let w = last.take().ok_or_else(|| fail("no solution at the root".into()))?;
        let (rho, bc) = disc.residual_norms(&w[..n], w[n])?;
        let max_rho = rho.iter().flatten().fold(0.0_f64, |m, &r| m.max(r));
        if max_rho < opts.tolerance || !opts.adapt_mesh {
            let stats = Stats {
                newton_iterations,
                jacobian_evaluations: newton_iterations,
                rhs_evaluations: disc.rhs_evals.get() - baseline,
                unknowns: n + 1,
                mesh_nodes: disc.n_nodes(),
                max_residual: max_rho.max(bc),
                wall_seconds: t0.elapsed().as_secs_f64(),
                refinements: 0,
            };
            total.newton_iterations += newton_iterations;
            total.jacobian_evaluations += newton_iterations;
            return Ok(Fold {
                eta: w[n],
                solution: disc.to_solution(&w[..n], w[n], stats),
                after_point,
                coordinate: describe(&disc, m),
                coordinate_value: w[m],
                evaluations,
            });
        }
        let meshes: Vec<Vec<f64>> = disc
            .meshes
            .iter()
            .zip(&rho)
            .map(|(mm, r)| mesh::refine(mm, r, opts.tolerance, opts.scheme.residual_order()))
            .collect();
        let nodes: usize = meshes.iter().map(Vec::len).sum();
        if nodes > opts.max_nodes {
            return Err(BvpError::MeshCapReached {
                max_nodes: opts.max_nodes,
                residual: max_rho,
                tolerance: opts.tolerance,
            });
        }
        total.refinements += 1;
        numerics::phases::count(numerics::phases::Step::MeshRefinement, 1);
        disc = disc.with_meshes(meshes)?;
    }
    Err(fail(format!("no mesh met the tolerance in {} refinements", opts.max_refinements)))
}
