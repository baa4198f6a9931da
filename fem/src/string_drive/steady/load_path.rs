//! The load continuation of the direct steady solve (docs/fem-drive.md §12): η scales the
//! driven load M₂, d₂ and the transport inertia ρ. η = 0 first (the static start carried
//! into the steady unknowns), then η → 1 by [`numerics::continuation::natural`], the step
//! doubled after a solve of at most 6 Newton iterations and halved after a failure.

use super::*;
use numerics::continuation::{self, ContinuationError, Growth, Homotopy, Step, StepControl, StepLimit, StepOptions};

/// Smallest step of the load continuation.
const MIN_STEP: f64 = 1e-4;

/// Newton iterations up to which a converged step doubles the next one.
const FAST_SOLVE: usize = 6;

/// The steady problem along η, and its last converged state.
pub(super) struct LoadPath<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    /// The steady equations at η (everything but the η-scaled parameters).
    pub problem: SteadyProblem<'a, N, P, E, K>,
    /// The η-scaled parameters.
    pub at: &'a dyn Fn(f64) -> SteadyParams,
    /// Variable weights and row scales of the semismooth Newton.
    pub w: &'a [f64],
    pub scales: &'a [f64],
    /// Newton tolerance and iteration limit.
    pub tolerance: f64,
    pub max_iterations: usize,
    pub kernel: &'a Arc<K>,
    /// ρ of the belt, kg/m, if the transport inertia is on (the critical speed is checked
    /// on every converged state).
    pub inertia: Option<f64>,
    /// Last converged unknowns X and their point results.
    pub x: Vec<f64>,
    pub results: Vec<PointResult>,
    pub report: &'a mut SteadyReport,
}

impl<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> LoadPath<'a, N, P, E, K> {
    /// The path of `problem` along η (parameters `at`) from the unknowns `x` converged at
    /// η = 0, with the semismooth Newton's weights `w`, row `scales`, `tolerance` and
    /// `max_iterations`; `inertia` as [`LoadPath::inertia`]; its work counted in `report`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        problem: SteadyProblem<'a, N, P, E, K>,
        at: &'a dyn Fn(f64) -> SteadyParams,
        (w, scales): (&'a [f64], &'a [f64]),
        (tolerance, max_iterations): (f64, usize),
        kernel: &'a Arc<K>,
        inertia: Option<f64>,
        x: Vec<f64>,
        report: &'a mut SteadyReport,
    ) -> Self {
        LoadPath { problem, at, w, scales, tolerance, max_iterations, kernel, inertia, x, results: Vec::new(), report }
    }
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> Homotopy for LoadPath<'_, N, P, E, K> {
    type Failure = NewtonFailure;
    type Error = FemError;

    fn advance(&mut self, _eta: f64, target: f64) -> Result<Step<NewtonFailure>, FemError> {
        let prob = SteadyProblem { sp: (self.at)(target), ..self.problem };
        let mut xt = self.x.clone();
        match newton(&prob, &mut xt, self.w, self.scales, self.tolerance, self.max_iterations) {
            Ok(n) => {
                self.report.newton_iterations += n.iterations;
                self.report.continuation_steps += 1;
                self.x = xt;
                self.results = prob.evaluate(&self.x, false).map(|e| e.results).unwrap_or_default();
                if let Some(rho) = self.inertia {
                    let asm = prob.asm;
                    let sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &self.x[..asm.len()], prob.params, prob.length, self.kernel.clone());
                    let c = self.x[asm.len()];
                    check_critical(&sol, target * rho * c * c)?;
                }
                Ok(Step::Accepted { iterations: n.iterations })
            }
            Err(reason) => {
                self.report.newton_iterations += self.max_iterations;
                self.report.rejected += 1;
                Ok(Step::Rejected(reason))
            }
        }
    }
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> LoadPath<'_, N, P, E, K> {
    /// Solve at η = 0, then continue to η = 1.
    ///
    /// # Errors
    /// [`FemError::FrictionCapacityExceeded`] (stalled within 5 % of what a pulley's
    /// contact can carry), [`FemError::HomotopyStalled`], [`FemError::SpeedAtOrAboveCritical`].
    pub(super) fn run(&mut self) -> Result<(), FemError> {
        if let Step::Rejected(reason) = self.advance(0.0, 0.0)? {
            return Err(self.stalled(0.0, 0.5, 0.0, &reason));
        }
        // the step doubles after a fast solve, halves after a failure; it never needs
        // to exceed the whole path (1)
        let mut control = StepControl::new(StepOptions {
            initial: 1.0,
            min: MIN_STEP,
            max: 1.0,
            shrink: 0.5,
            limit: StepLimit::Attempts(usize::MAX),
            growth: Growth::Quick { fast: FAST_SOLVE, factor: 2.0 },
            snap: 0.0,
        })
        .map_err(|e| FemError::InvalidOption { field: "load continuation steps", value: MIN_STEP.to_string(), reason: e.to_string() })?;
        match continuation::natural(self, 0.0, 1.0, &mut control, &[]) {
            Ok(_) => Ok(()),
            Err(ContinuationError::Aborted(e)) => Err(e),
            Err(ContinuationError::Stalled { eta, step, target, cause, .. }) => {
                let reason = cause.map_or_else(String::new, |r| r.to_string());
                Err(self.stalled(eta.0, step.0, target.0, &reason))
            }
            Err(ContinuationError::StepLimit { eta, step, cause, .. }) => {
                let reason = cause.map_or_else(String::new, |r| r.to_string());
                Err(self.stalled(eta.0, step.0, eta.0, &reason))
            }
        }
    }

    /// The continuation stalls where a pulley's load reaches what its contact can
    /// carry, R Σ w μ P⟨−γ⟩ of the last converged state (full slip): within 5 % of it,
    /// the named error with the whole load; else [`FemError::HomotopyStalled`].
    fn stalled(&self, eta: f64, step: f64, target: f64, reason: &dyn std::fmt::Display) -> FemError {
        let sp = (self.at)(1.0);
        // R Σ w μ P⟨−γ⟩ over a pulley's loaded points of the last converged state; `None`
        // without any
        let capacity_of = |pulley: Pulley| {
            let pts: Vec<&PointResult> = self.results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
            (!pts.is_empty()).then(|| sp.radius * pts.iter().map(|p| p.point.weight * sp.mu * p.normal).sum::<f64>())
        };
        // the open one-pulley layout in mode `tensions`: the load is the end fluxes'
        // difference, carried by the friction (C21: ∫τλ dσ = 𝓗_out − 𝓗_in, λ ≈ 1), so the
        // torque R|𝓗_out − 𝓗_in| the step aimed at against R Σ w μ P⟨−γ⟩ (measured: N_in =
        // 1000 N, N_out = 10 N, μ = 0.3 stalled at η = 0.627, N_out(η) ≈ 379 N, where the
        // BVP's capacity search ends at 390 N); the error names the whole load's torque
        // (the layout's pulley is the loop's driven one)
        if let (Ends::Open { flux_in, flux_out, pulley_speed: None, .. }, Ends::Open { flux_out: step_out, .. }, Some(capacity)) = (sp.ends, (self.at)(target).ends, capacity_of(Pulley::Driven)) {
            if sp.radius * (step_out - flux_in).abs() >= 0.95 * capacity {
                return FemError::FrictionCapacityExceeded { pulley: "single".to_string(), torque: sp.radius * (flux_out - flux_in).abs(), capacity, time: None };
            }
        }
        let demand = sp.torque + sp.damping * self.x[self.problem.asm.len() + 1];
        for pulley in [Pulley::Driven, Pulley::Driver] {
            let Some(capacity) = capacity_of(pulley) else { continue };
            if target * demand >= 0.95 * capacity {
                return FemError::FrictionCapacityExceeded { pulley: pulley.name().to_string(), torque: demand, capacity, time: None };
            }
        }
        FemError::HomotopyStalled { eta, step, min_step: MIN_STEP, steps: self.report.continuation_steps, last_failure: reason.to_string() }
    }
}
