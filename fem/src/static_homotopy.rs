//! The static analysis with homotopy: the string (`string-hanging`) or, with EI, the
//! Kirchhoff rod (`rod-hanging`) on two frictionless pulleys by MEL finite elements
//! (module `string_hanging` until issue 11; it solves both belts, and starts the
//! drives): the problem data, the tight starting state (F11), the two-phase
//! homotopy with step control under a capped penalty, the penalty continuation to the
//! final P, and the contact fitting (docs/fem-string.md §5, §9).

use std::f64::consts::PI;
use std::sync::Arc;

use drive::contour::Contour;

use crate::assembly::{Assembler, ElementKernel};
use numerics::continuation::{self, ContinuationError, Growth, Homotopy, Step, StepControl, StepLimit, StepOptions};
use crate::error::FemError;
use crate::fitting::{self, Beyond, FitReport, FitRules, Fallback, Fitted, Measure, MoveLimit, Secant};
use crate::formulation::layout::LayoutElement;
use crate::formulation::{ContactMultipliers, Kernel};
use crate::kinematics::{TermParams, NDOF};
use crate::linear::SparseLu;
use crate::mesh::{Grading, Mesh};
use crate::newton::{self, NewtonFailure, NewtonSettings, Scales};
use crate::options::SolverSettings;
use numerics::Sig;
use crate::problem::{BeltSection, Geometry};
use crate::solution::FemSolution;
use crate::string_drive::steady::{multiplier_update, AugmentedFailure, AugmentedReport};

/// The static fit's tie tolerance of its meshes' element distribution, elements
/// ([`Mesh::regraded`]): the upper span's two end pieces are mirror images, and without
/// it the extra element flips between them with the nm moves of the fitting, the
/// recovered boundaries jumping by 3.4e-9 m with it (`string-hanging` at 256 elements,
/// docs/fem-string.md §5). Remainders within 1e-3 elements (≈ 5 µm of length at 256)
/// are tied; at the fixed point the two pieces differ by 3e-9 m (6e-7 elements).
pub const STATIC_FIT_TIE: f64 = 1e-3;

/// Decay length of the Cosserat mesh grading, in shear layers √(a/b₂) (docs/fem-cosserat.md §9).
pub const GRADING_WIDTH: f64 = 2.0;
/// Peak refinement of the Cosserat mesh grading: elements at a contact edge are about
/// 1 + this times shorter than far from it (docs/fem-cosserat.md §9).
pub const GRADING_RATIO: f64 = 8.0;

/// The grading of a Cosserat rod's fitted meshes towards its contact edges over its
/// shear layer ℓ = √(a/b₂) (docs/fem-cosserat.md §9): density
/// 1 + [`GRADING_RATIO`]·exp(−d/([`GRADING_WIDTH`]·ℓ)) at the distance d from an edge.
/// `None` (uniform pieces) without a (a string) or without b₂ (a Kirchhoff rod). The
/// static fit and the one-pulley drive's fit grade so; the two-pulley steady drive's fit
/// grades more strongly (`string_drive::steady`, fem-cosserat.md §11.1).
pub fn shear_layer_grading(bending_stiffness: Option<f64>, shear_stiffness: Option<f64>) -> Option<Grading> {
    layer_grading(bending_stiffness, shear_stiffness, GRADING_WIDTH, GRADING_RATIO)
}

/// A grading towards the breakpoints over `width` shear layers ℓ = √(a/b₂) with the peak
/// refinement `ratio` ([`Grading`]); `None` without a or without b₂.
pub fn layer_grading(bending_stiffness: Option<f64>, shear_stiffness: Option<f64>, width: f64, ratio: f64) -> Option<Grading> {
    let layer = (bending_stiffness? / shear_stiffness?).sqrt();
    Some(Grading { width: width * layer, ratio })
}

/// The static frictionless problem of a string or Kirchhoff rod on two pulleys: the
/// typed data of [`crate::FemProblem`] it needs (SI) with the penalty resolved.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StringHanging {
    /// R and H.
    pub geometry: Geometry,
    /// L, EA, ρ and EI (`None`: a string; `Some`: a Kirchhoff rod, docs/fem-rod.md).
    pub belt: BeltSection,
    /// g, m/s² (`None`: no gravity term at all).
    pub gravity: Option<f64>,
    /// P, N/m² (`None`: no contact term).
    pub penalty: Option<f64>,
}

/// The element `K` rebuilt with augmented-Lagrangian multipliers
/// ([`LayoutElement::with_contact_multipliers`] for a `dyn` element); `None`: it has
/// penalty contact only.
pub type WithMultipliers<K> = dyn Fn(&K, Arc<ContactMultipliers>) -> Option<Arc<K>>;

/// Work of a homotopy run.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct HomotopyReport {
    /// Accepted homotopy steps (the start point included).
    pub steps: usize,
    /// Rejected (retried) steps.
    pub rejected: usize,
    /// Newton iterations summed over all attempts.
    pub newton_iterations: usize,
    /// Newton report of the final point.
    pub last: newton::NewtonReport,
    /// Starting unstretched length L₀, m.
    pub start_length: f64,
    /// Starting tension T₀ (F11), N.
    pub start_tension: f64,
    /// Penalty-continuation solves after the homotopy (raising P ×10 per solve).
    pub penalty_steps: usize,
    /// The contact fitting (converged: the boundaries moved less than the tolerance).
    #[serde(flatten)]
    pub fit: FitReport,
    /// Smallest axial force at the integration points and nodes, N (negative: the
    /// discrete string is locally compressed — under-resolution near a contact edge).
    pub min_axial_force: f64,
    /// σ of that smallest axial force, m.
    pub min_axial_force_sigma: f64,
}

/// The tight weightless loop of length `l0` with penalty `p` (F11): tension T₀ and
/// penetration δ. Without a penalty δ = 0 and T₀ = EA(L_geom/L₀ − 1).
pub fn tight_loop(contour: &Contour, l0: f64, axial_stiffness: f64, penalty: Option<f64>) -> (f64, f64) {
    let (r, lg) = (contour.radius(), contour.length());
    let ea = axial_stiffness;
    match penalty {
        Some(p) => {
            let t = ea * (lg / l0 - 1.0) / (1.0 + 2.0 * PI * ea / (r * p * l0));
            (t, t / (r * p))
        }
        None => (ea * (lg / l0 - 1.0), 0.0),
    }
}

/// The discrete problem at the tight start of the homotopy (F11), with the term
/// parameters and belt length of a homotopy parameter η — one Newton solve of the path,
/// for benchmarks and work-counter tests ([`StringHanging::start_problem`]).
pub struct StartProblem<const N: usize = NDOF, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    /// Mesh, numbering and formulation.
    pub assembler: Assembler<N, K>,
    /// Global unknowns: the tight loop at L₀ (F11).
    pub z: Vec<f64>,
    /// Term parameters at η (penalty capped at the homotopy value).
    pub params: TermParams,
    /// Belt length at η, m.
    pub length: f64,
    /// Norm weights (§8).
    pub scales: Scales,
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> StartProblem<N, K> {
    /// Newton from `z` at the problem's parameters (the LU with its symbolic
    /// factorisation is built here), `z` overwritten with the solution.
    ///
    /// # Errors
    /// [`FemError::NewtonDiverged`], [`FemError::SingularTangent`], [`FemError::NonFinite`].
    pub fn newton(&mut self, settings: &SolverSettings) -> Result<newton::NewtonReport, FemError> {
        let mut lu = SparseLu::banded();
        let (rows, cols) = self.assembler.pattern();
        lu.set_pattern(self.assembler.len(), rows, cols)
            .map_err(|detail| FemError::SingularTangent { eta: 0.0, iteration: 0, detail })?;
        let ns = NewtonSettings { tolerance: settings.update_tolerance, max_iterations: 100 };
        newton::solve(&self.assembler, &mut lu, &mut self.z, &self.params, self.length, &self.scales, &ns)
            .map_err(|f| to_error(f, f64::NAN, settings.update_tolerance))
    }
}

impl StringHanging {
    /// The tight start (F11) on `mesh` with the parameters of η (see [`StartProblem`]).
    ///
    /// # Errors
    /// [`FemError::IllPosed`] for a weightless slack loop; an invalid `settings`.
    pub fn start_problem<const N: usize, K: LayoutElement<N> + ?Sized>(&self, mesh: Mesh, kernel: Arc<K>, settings: &SolverSettings, eta: f64) -> Result<StartProblem<N, K>, FemError> {
        settings.validate()?;
        let contour = *mesh.contour();
        let (l0, t_start) = self.start(&contour)?;
        let f_ref = t_start.max(self.weight() * self.belt.length);
        let cap = settings.homotopy_penalty_factor * self.belt.axial_stiffness / (contour.radius() * contour.radius());
        let soft = StringHanging { penalty: self.penalty.map(|p| p.min(cap)), ..*self };
        let (t0, delta) = tight_loop(&contour, l0, self.belt.axial_stiffness, soft.penalty);
        let assembler = Assembler::with_kernel(mesh, kernel);
        let scales = Scales::new(&assembler, contour.centre_distance(), f_ref);
        let z = tight_state(&assembler, l0, t0, delta, self.belt.axial_stiffness);
        let (params, length) = soft.at(eta.clamp(0.0, 1.0), l0);
        Ok(StartProblem { assembler, z, params, length, scales })
    }

    /// The contour of the problem.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for invalid geometry (a validated scene never has it).
    pub fn contour(&self) -> Result<Contour, FemError> {
        Contour::new(self.geometry.radius, self.geometry.centre_distance).map_err(|e| FemError::Unsupported(e.to_string()))
    }

    /// The grading of the fitted meshes: [`shear_layer_grading`] of the belt.
    fn grading(&self) -> Option<Grading> {
        shear_layer_grading(self.belt.bending_stiffness, self.belt.shear_stiffness)
    }

    /// ρ g, N/m (0 without gravity).
    fn weight(&self) -> f64 {
        self.gravity.map_or(0.0, |g| self.belt.mass_per_length * g)
    }

    /// L₀ and the force scale F_ref (docs/fem-string.md §9).
    ///
    /// # Errors
    /// [`FemError::IllPosed`] for a weightless loop with L ≥ L_geom.
    pub fn start(&self, contour: &Contour) -> Result<(f64, f64), FemError> {
        let lg = contour.length();
        let ea = self.belt.axial_stiffness;
        let w = self.weight() * self.belt.length;
        let t_target = if self.belt.length < lg { ea * (lg / self.belt.length - 1.0) } else { 0.0 };
        let t0 = w.max(t_target);
        if t0.is_nan() || t0 <= 0.0 {
            return Err(FemError::IllPosed { length: self.belt.length, geometric_length: lg });
        }
        // L₀ = L when the belt is stretched on at least as much as T₀ requires
        let l0 = (lg / (1.0 + t0 / ea)).min(self.belt.length);
        Ok((l0, t0))
    }

    /// Term parameters and belt length at homotopy parameter η.
    fn at(&self, eta: f64, l0: f64) -> (TermParams, f64) {
        let g_scale = (2.0 * eta).min(1.0);
        let l = l0 + (2.0 * eta - 1.0).max(0.0) * (self.belt.length - l0);
        let params = TermParams {
            axial_stiffness: self.belt.axial_stiffness,
            weight: self.gravity.map(|g| g_scale * g * self.belt.mass_per_length),
            penalty: self.penalty,
            bending_stiffness: self.belt.bending_stiffness,
        };
        (params, l)
    }

    /// Solve on `mesh` with `kernel` by the homotopy of §9, then fit the mesh to the
    /// contact boundaries (§5) if `settings.contact_fitting`. Generic over the element
    /// (its layout, N unknowns): a registered formulation (`Arc<dyn Kernel>`, N = 8) or an
    /// element of another layout (the Cosserat layout's {s, ν, θ}, N = 12), monomorphised
    /// for each; fields after s and ν start from [`LayoutElement::start_field`].
    ///
    /// # Errors
    /// [`FemError::IllPosed`], [`FemError::HomotopyStalled`], [`FemError::NewtonDiverged`],
    /// [`FemError::SingularTangent`], [`FemError::NonFinite`].
    pub fn solve<const N: usize, K: LayoutElement<N> + ?Sized>(
        &self,
        mesh: Mesh,
        kernel: Arc<K>,
        settings: &SolverSettings,
    ) -> Result<(FemSolution<N, K>, HomotopyReport, usize), FemError> {
        self.solve_with_tie(mesh, kernel, settings, STATIC_FIT_TIE)
    }

    /// [`Self::solve`] with the fitted meshes' tie tolerance `tie` (elements,
    /// [`Mesh::regraded`]): a drive's start keeps 0, the distribution by the largest
    /// remainder however small the difference (docs/fem-string.md §5).
    ///
    /// # Errors
    /// As [`Self::solve`].
    #[allow(clippy::too_many_arguments)]
    pub fn solve_with_tie<const N: usize, K: LayoutElement<N> + ?Sized>(
        &self,
        mesh: Mesh,
        kernel: Arc<K>,
        settings: &SolverSettings,
        tie: f64,
    ) -> Result<(FemSolution<N, K>, HomotopyReport, usize), FemError> {
        settings.validate()?;
        let contour = *mesh.contour();
        let (l0, t_start) = self.start(&contour)?;
        let f_ref = t_start.max(self.weight() * self.belt.length);
        let newton_settings = NewtonSettings { tolerance: settings.update_tolerance, max_iterations: settings.max_step_iterations };
        // the homotopy runs with the penalty capped at κ_h EA/R² (Newton is cheaper with a
        // softer contact); the penalty is then raised ×10 per solve to its final value
        let cap = settings.homotopy_penalty_factor * self.belt.axial_stiffness / (contour.radius() * contour.radius());
        let soft = StringHanging { penalty: self.penalty.map(|p| p.min(cap)), ..*self };
        let (t0, delta) = tight_loop(&contour, l0, self.belt.axial_stiffness, soft.penalty);
        let mut report = HomotopyReport { start_length: l0, start_tension: t0, ..Default::default() };

        let asm = Assembler::with_kernel(mesh, kernel.clone());
        let scales = Scales::new(&asm, contour.centre_distance(), f_ref);
        let mut lu = SparseLu::banded();
        let (rows, cols) = asm.pattern();
        lu.set_pattern(asm.len(), rows, cols)
            .map_err(|detail| FemError::SingularTangent { eta: 0.0, iteration: 0, detail })?;
        let z0 = tight_state(&asm, l0, t0, delta, self.belt.axial_stiffness);
        let z = soft.homotopy(&asm, &mut lu, z0, l0, &scales, &newton_settings, settings, &mut report)?;
        let (params, length) = self.at(1.0, l0);
        let soft_params = TermParams { penalty: soft.penalty, ..params };
        let unknowns = asm.len();
        let mut sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &z, soft_params, length, kernel.clone());
        let fit_newton = NewtonSettings { tolerance: settings.update_tolerance, max_iterations: 40 };
        let fitting = settings.contact_fitting && self.penalty.is_some();

        // contact fitting with the soft penalty (docs/fem-string.md §5)
        if fitting {
            sol = fit(sol, &soft_params, length, &kernel, &mut lu, &scales, &fit_newton, settings, settings.grading.or(self.grading()), tie, &mut report);
        }
        // penalty continuation to the final P on the (fitted) mesh, then refit
        if let (Some(target), Some(mut current)) = (self.penalty, soft.penalty) {
            if current < target {
                let asm = Assembler::with_kernel(sol.mesh().clone(), kernel.clone());
                let mut z = transfer(&sol, &asm);
                while current < target {
                    current = (10.0 * current).min(target);
                    let p = TermParams { penalty: Some(current), ..params };
                    let r = newton::solve(&asm, &mut lu, &mut z, &p, length, &scales, &fit_newton)
                        .map_err(|f| to_error(f, 1.0, settings.update_tolerance))?;
                    report.newton_iterations += r.iterations;
                    report.penalty_steps += 1;
                    report.last = r;
                }
                sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &z, params, length, kernel.clone());
                if fitting {
                    sol = fit(sol, &params, length, &kernel, &mut lu, &scales, &fit_newton, settings, settings.grading.or(self.grading()), tie, &mut report);
                }
            }
        }

        let (sigma, tension) = sol.min_axial_force();
        if !tension.is_finite() {
            return Err(FemError::NonFinite { what: format!("axial force at σ = {sigma}") });
        }
        report.min_axial_force = tension;
        report.min_axial_force_sigma = sigma;
        let _ = f_ref;
        Ok((sol, report, unknowns))
    }

    /// The augmented-Lagrangian normal contact on the static loop (Table 1, column 1;
    /// docs/fem-cosserat.md §12.5) around the converged penalty solution `sol` of
    /// [`Self::solve`]: the Uzawa update λ ← ⟨λ − Pγ⟩₊ at the contact rule's points (the
    /// first from λ = 0: the penalty pressure), the multipliers a field periodic in σ
    /// over the closed contour ([`ContactMultipliers::periodic`]) held by the element that
    /// `rebuild` makes from the solution's, a Newton solve on the mesh and, with
    /// `settings.contact_fitting`, the fit to the contact boundaries (its refits read the
    /// field on their meshes); converged when the largest multiplier change is
    /// ≤ `contact_tolerance` × F_ref/R. The work is added to `report`.
    ///
    /// # Errors
    /// The failure (the caller keeps the penalty solution) with the outer loop's work:
    /// no penalty, an element without multipliers (`rebuild` gives `None`), a failed
    /// solve, or `max_iterations` updates above the tolerance.
    pub fn augment<const N: usize, K: LayoutElement<N> + ?Sized>(
        &self,
        mut sol: FemSolution<N, K>,
        rebuild: &WithMultipliers<K>,
        settings: &SolverSettings,
        (contact_tolerance, max_iterations): (f64, usize),
        report: &mut HomotopyReport,
    ) -> Result<(FemSolution<N, K>, AugmentedReport), (AugmentedFailure, AugmentedReport)> {
        let contour = *sol.mesh().contour();
        let mut al = AugmentedReport::default();
        let Some(penalty) = self.penalty else { return Err((AugmentedFailure::Unsupported, al)) };
        let f_ref = match self.start(&contour) {
            Ok((_, t_start)) => t_start.max(self.weight() * self.belt.length),
            Err(e) => return Err((AugmentedFailure::Solve(e.to_string()), al)),
        };
        al.tolerance = contact_tolerance * f_ref / contour.radius();
        let (params, length) = (*sol.params(), sol.length());
        let newton_settings = NewtonSettings { tolerance: settings.update_tolerance, max_iterations: 40 };
        let mut asm = Assembler::with_kernel(sol.mesh().clone(), sol.kernel().clone());
        let scales = Scales::new(&asm, contour.centre_distance(), f_ref);
        let mut lu = SparseLu::new();
        let (rows, cols) = asm.pattern();
        if let Err(detail) = lu.set_pattern(asm.len(), rows, cols) {
            return Err((AugmentedFailure::Solve(detail), al));
        }
        for k in 0..=max_iterations {
            let mut z = transfer(&sol, &asm);
            let current = sol.kernel().contact_multipliers().cloned().unwrap_or_default();
            let (next, max_gap) = multiplier_update(&asm, &z, &params, penalty, Some(contour.length()));
            al.iterations = k;
            al.multiplier_change = next.max_change(&current);
            al.max_gap = max_gap;
            if k > 0 && al.multiplier_change <= al.tolerance {
                al.converged = true;
                return Ok((sol, al));
            }
            if k == max_iterations {
                break;
            }
            let Some(kernel) = rebuild(sol.kernel(), Arc::new(next)) else { return Err((AugmentedFailure::Unsupported, al)) };
            asm = Assembler::with_kernel(sol.mesh().clone(), kernel.clone());
            match newton::solve(&asm, &mut lu, &mut z, &params, length, &scales, &newton_settings) {
                Ok(r) => {
                    report.newton_iterations += r.iterations;
                    report.last = r;
                }
                Err(f) => return Err((AugmentedFailure::Solve(to_error(f, 1.0, settings.update_tolerance).to_string()), al)),
            }
            sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &z, params, length, kernel.clone());
            if settings.contact_fitting {
                sol = fit(sol, &params, length, &kernel, &mut lu, &scales, &newton_settings, settings, settings.grading.or(self.grading()), STATIC_FIT_TIE, report);
                asm = Assembler::with_kernel(sol.mesh().clone(), kernel);
            }
        }
        Err((AugmentedFailure::NotConverged { change: al.multiplier_change, tolerance: al.tolerance, iterations: al.iterations }, al))
    }

    /// Natural-parameter continuation η: 0 → 1 from the converged start `z` (§9).
    #[allow(clippy::too_many_arguments)]
    fn homotopy<const N: usize, K: ElementKernel<N> + ?Sized>(
        &self,
        asm: &Assembler<N, K>,
        lu: &mut SparseLu,
        mut z: Vec<f64>,
        l0: f64,
        scales: &Scales,
        newton_settings: &NewtonSettings,
        settings: &SolverSettings,
        report: &mut HomotopyReport,
    ) -> Result<Vec<f64>, FemError> {
        // η = 0: the tight weightless loop (F11), corrected by Newton
        // (for a rod the start is not exact: the arcs' moment −EIλ/R meets straight spans,
        // and Newton builds the four transition boundary layers, docs/fem-rod.md §5 —
        // hence the larger iteration limit of this first solve)
        let (p0, len0) = self.at(0.0, l0);
        let start_settings = NewtonSettings { max_iterations: newton_settings.max_iterations.max(100), ..*newton_settings };
        let r = newton::solve(asm, lu, &mut z, &p0, len0, scales, &start_settings)
            .map_err(|f| to_error(f, 0.0, settings.update_tolerance))?;
        report.newton_iterations += r.iterations;
        report.steps = 1;
        report.last = r;

        if self.gravity.is_none() && self.belt.length == l0 {
            return Ok(z);
        }
        // step control on the Newton iterations of the accepted step
        // fast: ≤ 40 % of the iteration limit (8 of 20), slow: > 60 % (12); the next step
        // 2, 1.25 or 0.6 times the step done; a rejected step × ¼
        let fast = (2 * settings.max_step_iterations) / 5;
        let slow = (3 * settings.max_step_iterations) / 5;
        let mut control = StepControl::new(StepOptions {
            initial: settings.initial_step,
            min: settings.min_step,
            max: settings.max_step,
            shrink: 0.25,
            limit: StepLimit::Attempts(settings.max_steps),
            growth: Growth::Bands { fast, slow, factors: [2.0, 1.25, 0.6] },
            snap: 0.0,
        })
        .map_err(|e| FemError::InvalidOption { field: "initial_step/min_step/max_step/max_steps", value: settings.initial_step.to_string(), reason: e.to_string() })?;
        let mut path = StaticPath { data: self, asm, lu, l0, scales, newton_settings, tolerance: settings.update_tolerance, z, prev: None, report };
        // the path is smooth within each phase [0, ½] (gravity on), [½, 1] (length to
        // L), kinked at ½: a breakpoint, hit exactly
        let stalled = match continuation::natural(&mut path, 0.0, 1.0, &mut control, &[0.5]) {
            Ok(_) => return Ok(path.z),
            Err(ContinuationError::Aborted(never)) => match never {},
            Err(ContinuationError::Stalled { eta, step, cause, .. }) => FemError::HomotopyStalled {
                eta: eta.0,
                step: step.0,
                min_step: settings.min_step,
                steps: path.report.steps,
                last_failure: cause.unwrap_or_default(),
            },
            Err(ContinuationError::StepLimit { eta, step, cause, .. }) => FemError::HomotopyStalled {
                eta: eta.0,
                step: step.0,
                min_step: settings.min_step,
                steps: path.report.steps,
                last_failure: format!("step limit {} reached; {}", settings.max_steps, cause.unwrap_or_default()),
            },
        };
        Err(self.stalled(stalled, l0, asm.mesh().len()))
    }

    /// A stalled homotopy in the scene's terms: the phase it was in (weight on for
    /// η ≤ ½, the loop lengthened from the tight L₀ to L above), the numbers that make the
    /// scene hard — its slack L/L_geom, and the pulley radius against the element length
    /// of a uniform mesh of `elements` — and what to try.
    fn stalled(&self, cause: FemError, l0: f64, elements: usize) -> FemError {
        let eta = match &cause {
            FemError::HomotopyStalled { eta, .. } => *eta,
            _ => return cause,
        };
        let (r, h) = (self.geometry.radius, self.geometry.centre_distance);
        let lg = 2.0 * h + 2.0 * PI * r;
        let at = if eta < 0.5 {
            format!("the FE homotopy stalled switching on the weight ({} % of ρg, at the tight length L₀ = {} m)", Sig(200.0 * eta), Sig(l0))
        } else {
            format!("the FE homotopy stalled lengthening the loop from the tight L₀ = {} m to L = {} m ({} % of the way)", Sig(l0), Sig(self.belt.length), Sig(200.0 * (eta - 0.5)))
        };
        let size = lg / elements as f64;
        // the weight's strain ρgL/EA: below ~1e-10 the weight is lost in the round-off
        // of the tension and no mesh helps (EA = 1e17 N on `rod-hanging`: 8e-17)
        let weight_strain = self.gravity.unwrap_or(0.0) * self.belt.mass_per_length * self.belt.length / self.belt.axial_stiffness;
        if weight_strain > 0.0 && weight_strain < 1e-10 {
            let hard = format!(
                "the weight's strain ρgL/EA = {} (EA = {} N) is below what double precision resolves against the belt's tension; a smaller axial stiffness is what to try (the weight strains the belt by far less than the tolerance already at EA ≈ 1e12 N)",
                Sig(weight_strain),
                Sig(self.belt.axial_stiffness)
            );
            return FemError::StaticHomotopyStalled { at, hard, cause: Box::new(cause) };
        }
        let hard = format!(
            "the scene's slack L/L_geom = {} and pulley radius R = {} m against an element length of ≈ {} m ({} elements per half pulley) make it hard; try a finer mesh (--elements {}) — a pulley resolved by few elements under a slack belt is the usual cause",
            Sig(self.belt.length / lg),
            Sig(r),
            Sig(size),
            Sig(PI * r / size),
            (2 * elements).min(crate::mesh::MAX_ELEMENTS)
        );
        FemError::StaticHomotopyStalled { at, hard, cause: Box::new(cause) }
    }
}

/// The two-phase homotopy of §9 as a [`Homotopy`]: the path is smooth within each phase
/// [0, ½] (gravity on), [½, 1] (length to L), kinked at ½, which a step hits exactly.
struct StaticPath<'a, const N: usize, K: ElementKernel<N> + ?Sized> {
    data: &'a StringHanging,
    asm: &'a Assembler<N, K>,
    lu: &'a mut SparseLu,
    l0: f64,
    scales: &'a Scales,
    newton_settings: &'a NewtonSettings,
    tolerance: f64,
    /// Last accepted state.
    z: Vec<f64>,
    /// The accepted point before it, for the secant predictor.
    prev: Option<(f64, Vec<f64>)>,
    report: &'a mut HomotopyReport,
}

/// The phase of a step from a to b: 0 or 1 within a phase, 2 across the kink.
fn phase(a: f64, b: f64) -> u8 {
    if b <= 0.5 {
        0
    } else if a >= 0.5 {
        1
    } else {
        2
    }
}

impl<const N: usize, K: ElementKernel<N> + ?Sized> Homotopy for StaticPath<'_, N, K> {
    /// The failure as the error it would be, in words.
    type Failure = String;
    type Error = std::convert::Infallible;

    fn advance(&mut self, eta: f64, target: f64) -> Result<Step<String>, Self::Error> {
        let (asm, z) = (self.asm, &self.z);
        let (params, length) = self.data.at(target, self.l0);
        let (_, length_now) = self.data.at(eta, self.l0);
        let mut trial = z.clone();
        match &self.prev {
            // secant predictor within a phase; unknowns of nodes in contact are kept
            // (extrapolating them would push them into the pulley, against the penalty)
            Some((eta_p, z_p)) if phase(*eta_p, eta) == phase(eta, target) && phase(eta, target) < 2 => {
                let f = (target - eta) / (eta - eta_p);
                for i in 0..trial.len() {
                    trial[i] += f * (z[i] - z_p[i]);
                }
                keep_contact_nodes(asm, z, &mut trial, &params, length_now);
            }
            _ => scale_material(asm, &mut trial, length / length_now),
        }
        let outcome = newton::solve(asm, self.lu, &mut trial, &params, length, self.scales, self.newton_settings);
        let outcome = match outcome {
            Err(NewtonFailure::Inadmissible) => {
                // the predictor overshot into ∂σS ≤ 0: retry from the last point itself
                trial = z.clone();
                scale_material(asm, &mut trial, length / length_now);
                newton::solve(asm, self.lu, &mut trial, &params, length, self.scales, self.newton_settings)
            }
            o => o,
        };
        Ok(match outcome {
            Ok(r) => {
                self.report.newton_iterations += r.iterations;
                self.report.steps += 1;
                self.report.last = r;
                self.prev = Some((eta, std::mem::replace(&mut self.z, trial)));
                Step::Accepted { iterations: r.iterations }
            }
            Err(f) => {
                if let NewtonFailure::Diverged { iterations, .. } = &f {
                    self.report.newton_iterations += iterations;
                }
                self.report.rejected += 1;
                Step::Rejected(to_error(f, target, self.tolerance).to_string())
            }
        })
    }
}

/// Contact fitting (docs/fem-string.md §5) on the shared driver [`fitting::fit`]: move
/// a node onto every recovered contact boundary of `sol` and re-solve, until the
/// boundaries move less than the tolerance or `max_fits` passes are done — a secant per
/// boundary on the positions fitted to, limited to 50 |F| and h_min/4. A pass whose
/// Newton solve fails ends the fitting (recorded in `report.fit`); a fitting
/// that does not converge returns the best fitted solution (smallest largest |F|: the
/// iteration stops above the tolerance; stated by the run, [`crate::fitting::Unfitted`]).
#[allow(clippy::too_many_arguments)]
fn fit<const N: usize, K: LayoutElement<N> + ?Sized>(
    sol: FemSolution<N, K>,
    params: &TermParams,
    length: f64,
    kernel: &Arc<K>,
    lu: &mut SparseLu,
    scales: &Scales,
    newton_settings: &NewtonSettings,
    settings: &SolverSettings,
    grading: Option<Grading>,
    tie: f64,
    report: &mut HomotopyReport,
) -> FemSolution<N, K> {
    let contour = *sol.mesh().contour();
    let elements = sol.mesh().len();
    let h_min = Mesh::new(contour, elements, settings.arc_weight).map_or(0.0, |m| m.elements().iter().fold(f64::INFINITY, |a, e| a.min(e.h)));
    let rules = FitRules {
        // fitted: every recovered boundary within fit_tolerance·L_c of its node
        tolerance: settings.fit_tolerance * contour.length(),
        max_passes: settings.max_fits,
        measure: Measure::FittedTo,
        secant: Secant { bound: 50.0, beyond: Beyond::Clamp, degenerate: 0.0, fallback: Fallback::Step },
        limit: MoveLimit::Step(0.25 * h_min),
        stall: None,
        keep_best: true,
        tie,
        // the static contact edges are continuous in x (no stick/slip states)
        bracket: None,
    };
    let mut problem = StaticFit { sol, params, length, kernel, lu, scales, newton_settings, tolerance: settings.update_tolerance, grading, report };
    let out = fitting::fit(&mut problem, &rules);
    let report = problem.report;
    report.fit.record(&out);
    problem.sol
}

/// The static solution as a [`Fitted`]: a refit transfers it to the fitted mesh and
/// solves by Newton at the final homotopy parameters.
struct StaticFit<'a, const N: usize, K: LayoutElement<N> + ?Sized> {
    sol: FemSolution<N, K>,
    params: &'a TermParams,
    length: f64,
    kernel: &'a Arc<K>,
    lu: &'a mut SparseLu,
    scales: &'a Scales,
    newton_settings: &'a NewtonSettings,
    tolerance: f64,
    grading: Option<Grading>,
    report: &'a mut HomotopyReport,
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> Fitted for StaticFit<'_, N, K> {
    type Failure = FemError;
    type Snapshot = FemSolution<N, K>;

    fn mesh(&self) -> &Mesh {
        self.sol.mesh()
    }

    fn locate(&mut self) -> Vec<f64> {
        self.sol.contact_boundaries()
    }

    fn refit(&mut self, mesh: Mesh, _points: &[f64]) -> Result<(), FemError> {
        let asm = Assembler::with_kernel(mesh, self.kernel.clone());
        let mut z = transfer(&self.sol, &asm);
        // same topology, so the same sparsity pattern: the symbolic LU is reused
        match newton::solve(&asm, self.lu, &mut z, self.params, self.length, self.scales, self.newton_settings) {
            Ok(r) => {
                self.report.newton_iterations += r.iterations;
                self.report.last = r;
                self.sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &z, *self.params, self.length, self.kernel.clone());
                Ok(())
            }
            Err(f) => {
                if let NewtonFailure::Diverged { iterations, .. } = &f {
                    self.report.newton_iterations += iterations;
                }
                Err(to_error(f, 1.0, self.tolerance))
            }
        }
    }

    fn snapshot(&self) -> FemSolution<N, K> {
        self.sol.clone()
    }

    fn restore(&mut self, snapshot: FemSolution<N, K>) {
        self.sol = snapshot;
    }

    fn grading(&self) -> Option<Grading> {
        self.grading
    }
}

/// For every node in contact at `z` (gap < 0 with the element on either side), copy its
/// ν and ∂σν from `z` into `trial`.
fn keep_contact_nodes<const N: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, z: &[f64], trial: &mut [f64], params: &TermParams, length: f64) {
    let mesh = asm.mesh();
    let dofs = asm.dofs();
    let n = mesh.len();
    for k in 0..n {
        let el = asm.context(k, params);
        let q = dofs.gather(k, z, length);
        let p = el.layout_fields(dofs.layout(), &q, -1.0);
        if el.gap(&p).is_some_and(|g| g < 0.0) {
            let nd = dofs.node_unknowns(k);
            let nu = nd.values[1].expect("ν is an unknown at every node");
            for i in [nu, nd.slopes_in[1], nd.slopes_out[1]] {
                trial[i] = z[i];
            }
        }
    }
}

/// The global unknowns on `asm`'s mesh interpolated from a solution on another mesh of
/// the same contour and layout (one-sided slopes at region transitions), field by field
/// — the static homotopy's refits and the drives' start.
pub fn transfer<const N: usize, K: LayoutElement<N> + ?Sized>(sol: &FemSolution<N, K>, asm: &Assembler<N, K>) -> Vec<f64> {
    let mesh = asm.mesh();
    let dofs = asm.dofs();
    let fields = dofs.layout().fields.len();
    let mut z = vec![0.0; asm.len()];
    // every distinct node: the end node of an open mesh too
    for k in 0..mesh.node_count() {
        let sigma = mesh.node_sigmas()[k];
        let nd = dofs.node_unknowns(k);
        let shared_transition = nd.slopes_in == nd.slopes_out && mesh.is_transition(k);
        for f in 0..fields {
            let right = sol.one_sided_field(f, sigma, false);
            let left = sol.one_sided_field(f, sigma, true);
            if let Some(i) = nd.values[f] {
                z[i] = right[0];
            }
            z[nd.slopes_in[f]] = left[1];
            z[nd.slopes_out[f]] = right[1];
            if shared_transition && mesh.elements()[k].region.is_polar() {
                // one shared slope at a rod transition: the Cartesian side's, here the
                // element ending at the node (docs/fem-rod.md §3)
                z[nd.slopes_in[f]] = left[1];
            }
        }
    }
    z
}

/// Multiply every s value and ∂σs by `ratio` (the predictor when only L changes).
fn scale_material<const N: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, z: &mut [f64], ratio: f64) {
    if ratio == 1.0 || !ratio.is_finite() {
        return;
    }
    let dofs = asm.dofs();
    for k in 0..asm.mesh().node_count() {
        let nd = dofs.node_unknowns(k);
        if let Some(s) = nd.values[0] {
            z[s] *= ratio;
        }
        z[nd.slopes_in[0]] *= ratio;
        if nd.slopes_out[0] != nd.slopes_in[0] {
            z[nd.slopes_out[0]] *= ratio;
        }
    }
}

/// The global unknowns of the tight loop (F11): ν = −δ, ∂σS = (1 + αν)/λ₀ per region,
/// S integrated from S(0) = 0; the fields after s and ν from the element's
/// [`LayoutElement::start_field`].
fn tight_state<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, l0: f64, t0: f64, delta: f64, axial_stiffness: f64) -> Vec<f64> {
    let mesh = asm.mesh();
    let contour = mesh.contour();
    let lambda = 1.0 + t0 / axial_stiffness;
    let slope = |polar: bool| if polar { (1.0 - delta / contour.radius()) / lambda } else { 1.0 / lambda };
    let dofs = asm.dofs();
    let fields = dofs.layout().fields.len();
    let mut z = vec![0.0; asm.len()];
    let mut s = 0.0;
    let n = mesh.len();
    let els = mesh.elements();
    for k in 0..n {
        let nd = dofs.node_unknowns(k);
        if let Some(i) = nd.values[0] {
            z[i] = s;
        }
        z[nd.values[1].expect("ν is an unknown at every node")] = -delta;
        let (region_before, region_after) = (els[(k + n - 1) % n].region, els[k].region);
        let (before, after) = (region_before.is_polar(), region_after.is_polar());
        z[nd.slopes_in[0]] = slope(before);
        z[nd.slopes_in[1]] = 0.0;
        z[nd.slopes_out[0]] = slope(after);
        z[nd.slopes_out[1]] = 0.0;
        let shared = nd.slopes_in == nd.slopes_out;
        if shared {
            // one shared pair at a rod transition: the Cartesian side's primary slope;
            // the polar side's (1 − δ/R)/λ₀ follows from it by the map (docs/fem-rod.md K9)
            z[nd.slopes_out[0]] = slope(before && after);
        }
        let sigma = mesh.node_sigmas()[k];
        for f in 2..fields {
            let [value, slope_in] = asm.kernel().start_field(f, contour, sigma, region_before);
            let [_, slope_out] = asm.kernel().start_field(f, contour, sigma, region_after);
            z[nd.values[f].expect("fields after s are unknowns at every node")] = value;
            z[nd.slopes_in[f]] = slope_in;
            z[nd.slopes_out[f]] = if shared && after { slope_in } else { slope_out };
        }
        s += slope(after) * els[k].h;
    }
    // s now equals L₀ up to round-off (F11); the closure offset uses L₀ itself
    let _ = (s, l0);
    z
}

fn to_error(f: NewtonFailure, eta: f64, tolerance: f64) -> FemError {
    match f {
        NewtonFailure::Diverged { iterations, update, residual, line_search_failed } => {
            FemError::NewtonDiverged { eta, iterations, update, residual, tolerance, line_search_failed }
        }
        NewtonFailure::Singular { iteration, detail } => FemError::SingularTangent { eta, iteration, detail },
        NewtonFailure::Inadmissible => FemError::NonFinite {
            what: format!("starting state at η = {eta} (∂σS ≤ 0 or non-finite unknowns)"),
        },
    }
}
