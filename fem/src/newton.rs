//! Newton's method with a line search on the assembled energy (docs/fem-string.md §8).
//!
//! At iterate z: K Δ = −G (sparse LU). Trial z + αΔ, α = 1, ½, ¼, … ≥ α_min: accepted if
//! admissible (finite energy, ∂σS > 0) and either Armijo's energy decrease
//! Π(z + αΔ) ≤ Π(z) + 10⁻⁴ α GᵀΔ holds (when GᵀΔ < 0) or the scaled residual does not
//! grow. **Converged** when a full step is taken with ‖Δ‖ ≤ tolerance, where
//! ‖Δ‖ = max_i |Δ_i|/d_i (d_i = H for values, 1 for slopes); the scaled residual
//! ‖G‖ = max_i |G_i|/(F_ref c_i) (c_i = 1 for values, the node spacing for slopes) is
//! reported.

use numerics::newton::{Damping, Evaluation, NewtonError, NewtonOptions, NewtonProblem, Progress, TrialKind, TrialStep, Verdict};

use crate::assembly::{Assembler, ElementKernel};
use crate::dofs::DofKind;
use crate::kinematics::TermParams;
use crate::linear::SparseLu;

/// Armijo constant of the energy test.
const ARMIJO: f64 = 1e-4;
/// Smallest line-search factor α_min = 2⁻²⁰.
pub(crate) const MIN_ALPHA: f64 = 9.5367431640625e-7;

/// Norm weights of the unknowns (docs/fem-string.md §8).
#[derive(Debug, Clone)]
pub struct Scales {
    /// d_i: H for values, 1 for slopes.
    update: Vec<f64>,
    /// F_ref · c_i.
    residual: Vec<f64>,
    /// Energy scale F_ref · H, J.
    pub energy: f64,
}

impl Scales {
    /// Weights for the unknowns of `asm` with length scale `length` (H, m) and force
    /// scale `force` (F_ref, N).
    pub fn new<const N: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, length: f64, force: f64) -> Scales {
        let kinds = asm.dofs().kinds();
        let spacing = asm.dofs().spacing();
        Scales {
            update: kinds.iter().map(|k| if *k == DofKind::Value { length } else { 1.0 }).collect(),
            residual: kinds
                .iter()
                .zip(spacing)
                .map(|(k, h)| if *k == DofKind::Value { force } else { force * h })
                .collect(),
            energy: force * length,
        }
    }

    /// ‖Δ‖ = max |Δ_i|/d_i.
    pub fn update_norm(&self, d: &[f64]) -> f64 {
        d.iter().zip(&self.update).fold(0.0, |m, (v, w)| m.max(v.abs() / w))
    }

    /// ‖G‖ = max |G_i|/(F_ref c_i).
    pub fn residual_norm(&self, g: &[f64]) -> f64 {
        g.iter().zip(&self.residual).fold(0.0, |m, (v, w)| m.max(v.abs() / w))
    }
}

/// Work and final norms of one Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct NewtonReport {
    /// Iterations (= tangent assemblies and factorisations).
    pub iterations: usize,
    /// Last scaled update ‖Δ‖.
    pub update_norm: f64,
    /// Scaled residual ‖G‖ at the converged state.
    pub residual_norm: f64,
    /// Π at the converged state, J.
    pub energy: f64,
    /// Smallest line-search factor used.
    pub min_alpha: f64,
    /// Regularised (Levenberg–Marquardt) factorisations beyond the plain Newton ones.
    pub regularised: usize,
}

/// Why a Newton solve failed.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonFailure {
    /// Iteration limit or line search exhausted.
    Diverged {
        /// Iterations done.
        iterations: usize,
        /// Last ‖Δ‖.
        update: f64,
        /// Last ‖G‖.
        residual: f64,
        /// The line search found no acceptable step.
        line_search_failed: bool,
    },
    /// The tangent could not be factorised.
    Singular {
        /// Iteration.
        iteration: usize,
        /// faer's message.
        detail: String,
    },
    /// The starting point is not admissible (∂σS ≤ 0 or non-finite).
    Inadmissible,
}

/// Newton settings.
#[derive(Debug, Clone, Copy)]
pub struct NewtonSettings {
    /// Tolerance on ‖Δ‖.
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

/// The levels of backtracking on an energy Π shared by the static problem and the
/// transient step (`string_drive::system`): level 0 the plain tangent K; then
/// Levenberg–Marquardt shifts μ = 10⁻⁶, 10⁻⁵, … ≤ 10² ([`shifted`]); then the last
/// resort, which goes back to the plain step of level 0 (its factorisation was
/// overwritten, and backtracking solves only for −G) and accepts a trial whose residual
/// norm does not grow. Trials of the other levels are searched along descent directions
/// only and accepted by Armijo's rule on Π with a round-off allowance.
pub(crate) struct EnergyLevels {
    /// Armijo's round-off allowance (10⁻¹³ F_ref H).
    allowance: f64,
    /// μ of the current level (0: the plain tangent).
    pub(crate) mu: f64,
    /// The current level is the last resort.
    pub(crate) last_resort: bool,
    /// The last plain Newton step solved.
    plain_step: Vec<f64>,
}

/// What [`EnergyLevels::next`] moved to.
pub(crate) enum NextLevel {
    /// The shift `mu`: refactorise.
    Shift,
    /// The last resort (nothing to factorise).
    LastResort,
    /// No level is left.
    Exhausted,
}

impl EnergyLevels {
    /// n unknowns, Armijo's round-off allowance.
    pub(crate) fn new(n: usize, allowance: f64) -> Self {
        EnergyLevels { allowance, mu: 0.0, last_resort: false, plain_step: vec![0.0; n] }
    }

    /// A new iterate: level 0.
    pub(crate) fn restart(&mut self) {
        self.mu = 0.0;
        self.last_resort = false;
    }

    /// At the last resort, `b` becomes the plain step (`true`); otherwise `false`: the
    /// caller solves.
    pub(crate) fn reuse_plain_step(&self, b: &mut [f64]) -> bool {
        if self.last_resort {
            b.copy_from_slice(&self.plain_step);
        }
        self.last_resort
    }

    /// After a solve of level 0: keep its step.
    pub(crate) fn solved(&mut self, step: &[f64]) {
        if self.mu == 0.0 {
            self.plain_step.copy_from_slice(step);
        }
    }

    /// [`NewtonProblem::line_search`]: the last resort, or a descent direction.
    pub(crate) fn line_search(&self, slope: f64) -> bool {
        self.last_resort || slope < 0.0
    }

    /// [`NewtonProblem::accept_step`]: at the last resort the trial's merit is its
    /// residual norm, accepted up to `residual_bound` (the iterate's); otherwise Armijo.
    pub(crate) fn verdict(&self, t: &TrialStep<'_>, residual_bound: f64) -> Verdict {
        let accept = if self.last_resort {
            t.trial_merit <= residual_bound
        } else {
            t.trial_merit <= t.merit + ARMIJO * t.damping * t.slope + self.allowance
        };
        if accept {
            Verdict::Accept
        } else {
            Verdict::Reject
        }
    }

    /// Go to the next level.
    pub(crate) fn next(&mut self) -> NextLevel {
        if self.last_resort {
            return NextLevel::Exhausted;
        }
        self.mu = if self.mu == 0.0 { 1e-6 } else { 10.0 * self.mu };
        if self.mu <= 1e2 {
            NextLevel::Shift
        } else {
            self.last_resort = true;
            NextLevel::LastResort
        }
    }
}

/// D = diag K of the matrix `values` with pattern (`rows`, `cols`), duplicates summed,
/// into `d`.
pub(crate) fn diagonal_sums(values: &[f64], rows: &[usize], cols: &[usize], d: &mut [f64]) {
    d.fill(0.0);
    for (k, &v) in values.iter().enumerate() {
        if rows[k] == cols[k] {
            d[rows[k]] += v;
        }
    }
}

/// K + μ max(|D_i|, `floor`) on the diagonal entries `diagonal` (one position per
/// unknown).
pub(crate) fn shifted(values: &[f64], diagonal: &[usize], d: &[f64], mu: f64, floor: f64) -> Vec<f64> {
    let mut shifted = values.to_vec();
    for (i, &pos) in diagonal.iter().enumerate() {
        shifted[pos] += mu * d[i].abs().max(floor).max(1e-300);
    }
    shifted
}

/// The static Newton problem on [`numerics::newton`]: G = ∂Π/∂z with its tangent from
/// one assembly pass, trials judged by the energy alone, the levels of
/// [`EnergyLevels`] (the last resort on the scaled residual ‖G‖).
struct StaticNewton<'a, const N: usize, K: ElementKernel<N> + ?Sized> {
    asm: &'a Assembler<N, K>,
    lu: &'a mut SparseLu,
    params: &'a TermParams,
    length: f64,
    scales: &'a Scales,
    levels: EnergyLevels,
    /// Π, K and D = diag K of the last assembly, and its ‖G‖.
    energy: f64,
    values: Vec<f64>,
    d: Vec<f64>,
    rnorm: f64,
    /// ‖Δ‖ of the last plain step.
    last_update: f64,
    /// Failed levels (= regularised factorisations, plus one for the last resort).
    regularised: usize,
    /// Π and ‖G‖ at the converging full step (the returned solution).
    converged: Option<(f64, f64)>,
}

/// Why a call of [`StaticNewton`] failed.
enum StaticError {
    /// The assembly at an accepted iterate failed (∂σS ≤ 0 or non-finite).
    Inadmissible,
    /// faer's message.
    Singular(String),
}

impl<const N: usize, K: ElementKernel<N> + ?Sized> StaticNewton<'_, N, K> {
    fn factorize_level(&mut self) -> Result<(), StaticError> {
        let mu = self.levels.mu;
        if mu == 0.0 {
            return self.lu.factorize(&self.values).map_err(StaticError::Singular);
        }
        let values = shifted(&self.values, self.asm.diagonal_positions(), &self.d, mu, 0.0);
        self.lu.factorize(&values).map_err(StaticError::Singular)
    }
}

impl<const N: usize, K: ElementKernel<N> + ?Sized> NewtonProblem for StaticNewton<'_, N, K> {
    type Error = StaticError;
    fn size(&self) -> usize {
        self.asm.len()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), StaticError> {
        // not called with both evaluation hooks (the gradient comes with the assembly,
        // trials are judged by `trial_merit`)
        match self.asm.gradient(z, self.params, self.length) {
            Some((_, g)) => r.copy_from_slice(&g),
            None => r.fill(f64::NAN),
        }
        Ok(())
    }
    fn factorize(&mut self, z: &[f64]) -> Result<(), StaticError> {
        let mut r = vec![0.0; self.size()];
        self.factorize_with_residual(z, &mut r)
    }
    fn factorize_with_residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), StaticError> {
        let a = self.asm.assemble(z, self.params, self.length).ok_or(StaticError::Inadmissible)?;
        self.rnorm = self.scales.residual_norm(&a.gradient);
        let (rows, cols) = self.asm.pattern();
        diagonal_sums(&a.values, rows, cols, &mut self.d);
        r.copy_from_slice(&a.gradient);
        self.energy = a.energy;
        self.values = a.values;
        self.levels.restart();
        self.factorize_level()
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), StaticError> {
        if self.levels.reuse_plain_step(b) {
            return Ok(());
        }
        self.lu.solve_in_place(b).map_err(StaticError::Singular)?;
        if self.levels.mu == 0.0 {
            self.last_update = self.scales.update_norm(b);
        }
        self.levels.solved(b);
        Ok(())
    }
    fn damping(&self) -> Damping {
        Damping::Backtracking { take_best: false }
    }
    fn evaluation(&self) -> Evaluation {
        Evaluation { residual_with_factorization: true, merit_only: true }
    }
    fn norm(&self, v: &[f64], _z: &[f64]) -> f64 {
        self.scales.update_norm(v)
    }
    fn merit(&mut self, _z: &[f64], _r: &[f64]) -> f64 {
        self.energy
    }
    fn trial_merit(&mut self, trial: &[f64], kind: TrialKind) -> Result<Option<f64>, StaticError> {
        let (asm, p, l) = (self.asm, self.params, self.length);
        Ok(match kind {
            // the converged state's residual norm and energy are reported
            TrialKind::Converging => asm.gradient(trial, p, l).map(|(energy, g)| {
                self.converged = Some((energy, self.scales.residual_norm(&g)));
                energy
            }),
            // the last resort's merit is the scaled residual
            TrialKind::Search if self.levels.last_resort => asm.gradient(trial, p, l).map(|(_, g)| self.scales.residual_norm(&g)),
            TrialKind::Search => asm.energy(trial, p, l),
        })
    }
    fn line_search(&mut self, _level: usize, slope: f64) -> bool {
        self.levels.line_search(slope)
    }
    /// Only the converging full step ends the iteration (an accepted full step that
    /// is not it continues).
    fn converged(&mut self, _p: &Progress<'_>) -> bool {
        self.converged.is_some()
    }
    fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
        self.levels.verdict(t, self.rnorm)
    }
    fn regularise(&mut self, _z: &[f64], _level: usize) -> Result<bool, StaticError> {
        match self.levels.next() {
            NextLevel::Exhausted => return Ok(false),
            NextLevel::Shift => self.factorize_level()?,
            NextLevel::LastResort => {}
        }
        self.regularised += 1;
        Ok(true)
    }
}

/// Solve G(z) = 0 from `z` (overwritten with the solution; on failure with the last
/// accepted iterate). `lu` must hold the pattern of `asm`.
///
/// Each iteration tries the Newton step K Δ = −G first; if it is not a descent
/// direction of Π or its line search fails (K indefinite, e.g. a compressed string,
/// or a contact set that changes within the step), it is regularised,
/// (K + μ D) Δ = −G with D = diag |K| and μ = 10⁻⁶, 10⁻⁵, … ≤ 10², which turns Δ
/// towards steepest descent in the metric D (Levenberg–Marquardt). A step is accepted
/// by Armijo's rule on Π with a round-off allowance of 10⁻¹³ F_ref H; as a last resort
/// the plain Newton step is accepted where the scaled residual does not grow. The
/// iteration is [`numerics::newton::solve`] (backtracking, the gradient taken from the
/// tangent's assembly, trials judged by Π alone).
pub fn solve<const N: usize, K: ElementKernel<N> + ?Sized>(
    asm: &Assembler<N, K>,
    lu: &mut SparseLu,
    z: &mut [f64],
    params: &TermParams,
    length: f64,
    scales: &Scales,
    settings: &NewtonSettings,
) -> Result<NewtonReport, NewtonFailure> {
    let n = z.len();
    let mut problem = StaticNewton {
        asm,
        lu,
        params,
        length,
        scales,
        levels: EnergyLevels::new(n, 1e-13 * scales.energy),
        energy: 0.0,
        values: Vec::new(),
        d: vec![0.0; n],
        rnorm: f64::INFINITY,
        last_update: f64::INFINITY,
        regularised: 0,
        converged: None,
    };
    let opts = NewtonOptions { tolerance: settings.tolerance, max_iterations: settings.max_iterations, min_damping: MIN_ALPHA };
    let diverged = |iterations, update, residual, line_search_failed| NewtonFailure::Diverged { iterations, update, residual, line_search_failed };
    match numerics::newton::solve(&mut problem, z, &opts) {
        Ok(stats) => {
            let (energy, residual_norm) = problem.converged.unwrap_or((f64::NAN, f64::NAN));
            Ok(NewtonReport {
                iterations: stats.iterations,
                update_norm: stats.last_correction,
                residual_norm,
                energy,
                min_alpha: stats.min_damping_used,
                regularised: problem.regularised,
            })
        }
        Err(e) => Err(match e {
            NewtonError::MaxIterations { iterations, correction, .. } => {
                // ‖G‖ at the last iterate, from its assembly (the last one's if it fails)
                let residual = asm.assemble(z, params, length).map_or(problem.rnorm, |a| scales.residual_norm(&a.gradient));
                diverged(iterations, correction, residual, false)
            }
            NewtonError::LineSearchFailed { iteration, correction, .. } => diverged(iteration, correction, problem.rnorm, true),
            NewtonError::NonFinite { iteration, .. } | NewtonError::Problem { iteration, error: StaticError::Inadmissible, .. } => {
                if iteration <= 1 {
                    NewtonFailure::Inadmissible
                } else {
                    diverged(iteration - 1, problem.last_update, problem.rnorm, false)
                }
            }
            NewtonError::Problem { iteration, error: StaticError::Singular(detail), .. } => NewtonFailure::Singular { iteration, detail },
            NewtonError::SingularStep { iteration, .. } => NewtonFailure::Singular { iteration, detail: "non-finite Newton step".into() },
            NewtonError::InvalidOptions(_) | NewtonError::DimensionMismatch { .. } | NewtonError::DampingExhausted { .. } => {
                diverged(0, f64::INFINITY, f64::INFINITY, false)
            }
        }),
    }
}
