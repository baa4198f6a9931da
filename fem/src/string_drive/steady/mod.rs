//! Direct steady-state solve of the friction drive (docs/fem-drive.md §12, the
//! Papers C/D concept for the string): the time-invariant state at fixed σ is sought
//! directly — nodal unknowns z, transport rate c, driven speed ω₂ and one friction
//! traction per friction point — as the root of the steady equations (DS1)–(DS4) by a
//! semismooth Newton method with an active set (stick/slip per point), under a
//! continuation in the load and the transport inertia, on a mesh fitted to the four
//! contact boundaries and the two stick→slip transitions.

use std::f64::consts::PI;
use std::sync::Arc;

use drive::contour::{Contour, Direction, Pulley, Region};
use nalgebra::SVector;
use num_dual::{gradient, hessian};
use drive::view::SolutionView;
use rayon::prelude::*;

use crate::assembly::Assembler;
use crate::error::{FemError, NewtonFailure};
use crate::fitting::{Beyond, FitEnd, FitReport, FitRules, Fallback, Measure, MoveLimit, Secant, Stall};
use crate::formulation::layout::{FrictionNormal, LayoutElement};
use crate::formulation::Kernel;
use crate::kinematics::{ElementContext, Scalar, TermParams, NDOF};
use crate::linear::BorderedLu;
use crate::mesh::Mesh;
use crate::quadrature::Rule;
use crate::solution::FemSolution;

use super::contact::reachable_pulley;

mod augmented;
mod equations;
mod fitting;
mod kernels;
mod load_path;
mod nested;
mod open;
mod output;
pub(crate) mod paper_d;
mod semismooth;
mod topology;

pub use augmented::{AugmentedFailure, AugmentedReport};
pub(crate) use augmented::multiplier_update;
pub use drive::scene::NormalContact;
use augmented::*;
pub use equations::*;
pub use fitting::*;
pub use open::{end_flux, solve_open, OpenEnds, OpenMode};
use kernels::*;
use load_path::LoadPath;
use output::*;
pub use paper_d::{PaperDReport, SteadyScheme};
use paper_d::PaperD;
pub use semismooth::*;
pub use topology::*;

/// Work of a direct steady solve (in the run's `options.drive`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SteadyReport {
    /// Accepted continuation steps in η (load and inertia scaled by η), η = 0 included.
    pub continuation_steps: usize,
    /// Rejected continuation steps.
    pub rejected: usize,
    /// Element counts of the coarse meshes of the nested start (coarsest first, the
    /// load continuation on the first): empty when the continuation ran on the solve's
    /// own mesh (fewer than 128 elements, or a rung of the ladder failed).
    pub nested_meshes: Vec<usize>,
    /// Newton iterations over all solves.
    pub newton_iterations: usize,
    /// The contact fitting (converged: every boundary and transition within the
    /// tolerance of a node; the last move: their largest distance from their nodes).
    #[serde(flatten)]
    pub fit: FitReport,
    /// Fitting passes whose Newton solve failed and were retried with a smaller move.
    pub rejected_fits: usize,
    /// Friction points (one per node within reach of a pulley; two at a split node).
    pub friction_points: usize,
    /// Wall time of the static start (homotopy of fem-string.md §9), s.
    pub static_seconds: f64,
    /// Wall time of the load continuation, s.
    pub continuation_seconds: f64,
    /// Wall time of the fitting passes, s.
    pub fitting_seconds: f64,
    /// Paper D's scheme, when the scene asks for it (`fem.steady_scheme` = `paper-d`):
    /// its outer iterations and final matching residual.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper_d: Option<PaperDReport>,
    /// The scheme that found the stick and slip zones (`paper-d` or `semismooth`; the
    /// scene's `fem.steady_scheme` resolved, `paper_d::resolved`, and `semismooth`
    /// after Paper D's failure under `auto`).
    pub scheme: SteadyScheme,
    /// Why Paper D's scheme, chosen by `auto`, failed before the semismooth fit took over.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper_d_failure: Option<String>,
    /// The augmented-Lagrangian outer loop of the normal contact (`fem.contact` =
    /// `augmented-lagrangian`, docs/fem-cosserat.md §12.5).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact: Option<AugmentedReport>,
    /// Stated warnings of the solve (the run's notes; [`slip_resolution_warnings`]).
    #[serde(skip)]
    pub warnings: Vec<String>,
}

/// A converged steady state on one mesh.
struct State<const N: usize, K: LayoutElement<N> + ?Sized> {
    /// ρ of the transport inertia (kg/m), if any.
    rho: Option<f64>,
    asm: Assembler<N, K>,
    x: Vec<f64>,
    results: Vec<PointResult>,
}

// by hand: the kernel is shared, so no `K: Clone` bound as `derive` would add
impl<const N: usize, K: LayoutElement<N> + ?Sized> Clone for State<N, K> {
    fn clone(&self) -> Self {
        State { rho: self.rho, asm: self.asm.clone(), x: self.x.clone(), results: self.results.clone() }
    }
}

/// Peak refinement of the two-pulley steady drive's grading towards its contact edges
/// and stick→slip transitions (docs/fem-cosserat.md §11.1; the static fit's is
/// [`crate::static_homotopy::GRADING_RATIO`]).
pub const DRIVE_GRADING_RATIO: f64 = 64.0;
/// Decay length of that grading, in shear layers √(a/b₂).
pub const DRIVE_GRADING_WIDTH: f64 = 1.0;
/// The arcs' weight in the distribution of the elements of a graded steady drive
/// ([`Mesh::new`]; a larger `fem` arc weight is kept).
pub const DRIVE_ARC_WEIGHT: f64 = 2.0;

/// The grading of the two-pulley steady drive's fitted meshes (docs/fem-cosserat.md
/// §11.1): [`DRIVE_GRADING_RATIO`] over [`DRIVE_GRADING_WIDTH`] shear layers, `None` for a
/// belt without a shear layer (a string).
fn drive_grading(bending_stiffness: Option<f64>, shear_stiffness: Option<f64>) -> Option<crate::mesh::Grading> {
    crate::static_homotopy::layer_grading(bending_stiffness, shear_stiffness, DRIVE_GRADING_WIDTH, DRIVE_GRADING_RATIO)
}

/// Solve a friction-drive scene (see [`super::applies`]) for its steady state directly
/// (docs/fem-drive.md §12).
///
/// # Errors
/// As [`super::solve`] without the transient's step errors: [`FemError::Unsupported`]
/// (ω₁ ≤ 0), [`FemError::InvalidOption`], the static start's errors,
/// [`FemError::FrictionCapacityExceeded`], [`FemError::SpeedAtOrAboveCritical`],
/// [`FemError::HomotopyStalled`] (the load continuation failed otherwise),
/// [`FemError::SteadyFitFailed`], [`FemError::NonFinite`].
pub fn solve(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::DriveSettings, kernel: Arc<dyn Kernel>) -> Result<crate::FemRun, FemError> {
    solve_layout::<NDOF, NPV, NEV, dyn Kernel>(problem, opts, settings, drive_settings, kernel)
}

/// [`solve`] for an element of any 1-D layout with N unknowns (P = 2N + 4, E = N + 4:
/// [`point_size`], [`element_size`]): the string's formulations (N = 8, [`solve`]) and
/// the Cosserat rod's elements (N = 12, docs/fem-cosserat.md §10). The friction and
/// contact rows act on the element's centreline {s, ν}; further fields (the Cosserat
/// rotation ψ) enter through the element's energy only.
///
/// # Errors
/// As [`solve`].
pub fn solve_layout<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized + 'static>(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::DriveSettings, kernel: Arc<K>) -> Result<crate::FemRun, FemError> {
    let clock = std::time::Instant::now();
    // a rod with a shear layer: its fitted meshes graded towards the contact edges and
    // transitions, twice the arcs' share of the elements (docs/fem-cosserat.md §11.1)
    let grading = drive_grading(problem.belt.bending_stiffness, kernel.shear_stiffness());
    let arc_weight = if grading.is_some() { settings.arc_weight.max(DRIVE_ARC_WEIGHT) } else { settings.arc_weight };
    let super::DriveStart { mu, omega1, start, report: homotopy, penalty, t_static, f_ref } = super::drive_start(problem, opts, settings, drive_settings, kernel.clone(), arc_weight)?;
    let static_seconds = clock.elapsed().as_secs_f64();
    let b = &problem.belt;
    let r = problem.geometry.radius;
    let contour = *start.mesh().contour();
    let h = contour.centre_distance();
    let (load_torque, damping) = (problem.drive.driven_torque, problem.drive.driven_damping);
    let weight = problem.weight();
    // the belt's bending stiffness as the static start has it (the Cosserat rod's a;
    // none for the string)
    let params = TermParams { axial_stiffness: b.axial_stiffness, weight, penalty: Some(penalty), bending_stiffness: start.params().bending_stiffness };
    let length = b.length;
    let strain_rule = kernel.rules().strain;
    let inertia = problem.effects.inertia;
    let asm = Assembler::with_kernel(start.mesh().clone(), kernel.clone());
    let arc_elements = asm.mesh().elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1);
    // κ = P_⊥ Δt₀: the transient's tangential penalty times its default step (§5, §7)
    let kappa = drive_settings.tangential_penalty_factor * b.axial_stiffness / (r * r) * (PI * r / arc_elements as f64) / (r * omega1.abs());
    // the belt runs against σ for a driver turning counter-clockwise: the upwind element
    // of each friction point and the order stick → slip along σ follow it
    let direction = Direction::of_speed(omega1);
    let sp_at = |eta: f64| SteadyParams {
        mu,
        penalty,
        kappa,
        radius: r,
        omega1,
        torque: eta * load_torque,
        damping: eta * damping,
        inertia: inertia.then_some(eta * b.mass_per_length),
        ends: Ends::Loop,
    };
    let lambda0 = 1.0 + t_static / b.axial_stiffness;
    // critical speed, checked on the start state with c = Rω₁/λ₀ (docs/fem-drive.md §6)
    if inertia {
        let c0 = r * omega1 / lambda0;
        check_critical(&start, b.mass_per_length * c0 * c0)?;
    }
    let points = friction_points(&asm, &[], direction);
    let mut x = crate::static_homotopy::transfer(&start, &asm);
    x.extend([r * omega1 / lambda0, omega1]);
    x.extend(std::iter::repeat_n(0.0, points.len()));
    let mut report = SteadyReport { friction_points: points.len(), static_seconds, ..Default::default() };
    let tol = settings.update_tolerance;
    let max_it = drive_settings.max_newton_iterations;

    // continuation in η: load M₂, d₂ and inertia ρ scaled by η (§12)
    let w = variable_weights(&asm, h, r, omega1.abs(), f_ref, points.len());
    let scales = row_scales(&asm, f_ref, points.len());
    // nested: the continuation on a coarse mesh, carried up to this one (nested.rs);
    // on this mesh from the static start if a rung fails
    let rho = inertia.then_some(b.mass_per_length);
    // (not for a rod with a graded shear layer: its rungs need 12–23 iterations each on
    // cosserat-drive, no fewer fine-mesh iterations than the continuation on the fine
    // mesh itself, measured)
    let levels = if grading.is_none() { nested::coarse_levels(opts.elements) } else { Vec::new() };
    let fit_data = SteadyFitData { params, length, kernel: &kernel, sp_at: &sp_at, strain_rule, h, r, omega1, f_ref, slot_weight: None, direction, tolerance: tol, max_iterations: max_it, grading };
    let nested_data = nested::NestedData { base: &fit_data, arc_weight, inertia: rho, start_rates: [x[asm.len()], x[asm.len() + 1]] };
    let nested = nested::nested_start::<N, P, E, K>(&start, &asm, &points, &levels, &nested_data, &mut report)?;
    let (x, last_results) = match nested {
        Some(solved) => solved,
        None => {
            report.nested_meshes.clear();
            let steady = SteadyProblem::<N, P, E, K> { asm: &asm, params, length, points: &points, sp: sp_at(0.0), strain_rule };
            let mut path = LoadPath::new(steady, &sp_at, (&w, &scales), (tol, max_it), &kernel, rho, x, &mut report);
            path.run()?;
            (path.x, path.results)
        }
    };
    let mut state = State { asm, x, results: last_results, rho: inertia.then_some(b.mass_per_length) };
    report.continuation_seconds = clock.elapsed().as_secs_f64() - static_seconds;

    // fitting: a node at every contact boundary and stick→slip transition (§12)
    let element = PI * r / arc_elements as f64;
    let scheme = paper_d::resolved(drive_settings.steady_scheme, kernel.friction_normal(), settings.contact_fitting);
    report.scheme = scheme;
    let (mut final_params, mut final_penalty) = (params, penalty);
    if scheme == SteadyScheme::PaperD {
        // Paper D's fixed topology instead of the fitting (spec §3.5, `paper_d`); chosen
        // by the belt, its failure falls back to the semismooth fit from the same state
        let fallback = (drive_settings.steady_scheme == SteadyScheme::Auto).then(|| state.clone());
        // on the string the default penalty grows with the mesh for the fixed topology's
        // solves only (`paper_d::penalty_mesh_scale`): the static start and the load
        // continuation keep κ (with the grown penalty throughout, the Exudyn scene at 512
        // elements took 351 Newton iterations and 2.5 s against 88 and 0.41 s, measured)
        let grown = if opts.penalty.is_none() && kernel.friction_normal() == FrictionNormal::Nodal { paper_d::penalty_mesh_scale(opts.elements) * penalty } else { penalty };
        let grown_params = TermParams { penalty: Some(grown), ..params };
        let grown_sp_at = |eta: f64| SteadyParams { penalty: grown, ..sp_at(eta) };
        let grown_data = SteadyFitData { params: grown_params, sp_at: &grown_sp_at, ..fit_data };
        // timed as the fitting it replaces (its fixed-topology solves in their own phases),
        // each of them a fitting pass (`PaperD::solve_at`)
        let run = numerics::phases::timed(numerics::phases::Phase::Fitting, || PaperD::<N, P, E, K>::new(state, grown_data, opts.elements, arc_weight, mu, load_torque + damping * omega1).run());
        match (run, fallback) {
            (Ok((solved, pd, iterations)), _) => {
                (final_params, final_penalty) = (grown_params, grown);
                state = solved;
                report.newton_iterations += iterations;
                report.paper_d = Some(pd);
            }
            (Err(e @ FemError::PaperDFailed { .. }), Some(start)) => {
                report.warnings.push(format!("Paper D's fixed-topology scheme, the string drive's default, failed ({e}); the result is the semismooth fit's, whose stick→slip fronts converge at order ≈ 0.5 only (docs/fem-drive.md §12)"));
                report.scheme = SteadyScheme::Semismooth;
                report.paper_d_failure = Some(e.to_string());
                state = fit_steady::<N, P, E, K>(start, fit_data, settings, drive_settings, element, &mut report)?;
            }
            (Err(e), _) => return Err(e),
        }
    } else if settings.contact_fitting {
        state = fit_steady::<N, P, E, K>(state, fit_data, settings, drive_settings, element, &mut report)?;
    }
    report.fitting_seconds = clock.elapsed().as_secs_f64() - static_seconds - report.continuation_seconds;
    finish::<N, P, E, K>(problem, opts, settings, drive_settings, kernel, state, final_params, final_penalty, kappa, mu, homotopy, report, clock)
}

/// The contact fitting of a converged steady state (docs/fem-drive.md §12 "Fitting"; the
/// open one-pulley layout's, docs/fem-cosserat.md §12.5) on the shared driver
/// [`crate::fitting::fit`]: a node at every contact boundary and stick→slip transition,
/// the mesh graded towards them by `data.grading`. `element` is the mean arc element πR/n
/// (m) the stall and failure thresholds are measured in. Recorded in `report`.
///
/// # Errors
/// [`FemError::SteadyFitFailed`] when a located point stays more than 5 % of `element`
/// from its node.
fn fit_steady<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(state: State<N, K>, data: SteadyFitData<K>, settings: &crate::options::SolverSettings, drive_settings: &super::DriveSettings, element: f64, report: &mut SteadyReport) -> Result<State<N, K>, FemError> {
    let lc = state.asm.mesh().contour().length();
    let rules = FitRules {
        tolerance: settings.fit_tolerance * lc,
        max_passes: drive_settings.max_fits,
        // the distance of each breakpoint from its nearest node
        measure: Measure::NearestNode,
        // a secant per breakpoint on F(x) = g(x) − x (as fem-string.md §5; the plain
        // iteration x ← g(x) oscillates for the drive's transitions); a secant step
        // beyond twice the plain one is not trusted
        secant: Secant { bound: 2.0, beyond: Beyond::Plain, degenerate: 1e-12 * lc, fallback: Fallback::Located },
        // at most 0.3 of the local element length per pass (÷4 after a failed pass,
        // down to 0.02): a refit is then a small perturbation of the transferred
        // state (a kink moved across an element leaves the stiff normal penalty far
        // from equilibrium)
        limit: MoveLimit::Element { max: 0.3, grow: 2.0, shrink: 0.25, min: 0.02 },
        // stalled below 5 % of an element: no 10 % gain over the best pass in 4
        // passes (a point the mesh cannot take, e.g. within 2 % of an element of a
        // region transition, where `Mesh::fitted` keeps the transition node)
        stall: Some(Stall { gain: 0.9, patience: 4, below: 0.05 * element }),
        keep_best: false,
        // the largest remainder decides (the steady fits are not symmetric)
        tie: 0.0,
        // a stick→slip transition whose located position jumps across its node (the
        // node sticks on one side and slips on the other, §12 "A transition that
        // jumps"): bisected to 1 % of an element, once the stall's patience is spent
        bracket: Some(0.01 * element),
    };
    let mut fit = SteadyFit::<N, P, E, K>::new(state, data, report);
    let out = crate::fitting::fit(&mut fit, &rules);
    let state = fit.into_state();
    report.fit.record(&out);
    report.rejected_fits = out.rejected;
    // within the 5 % the error below allows, but not fitted: the arcs of the result
    // carry the offset (stated, never a clean result)
    if let (FitEnd::PassLimit, Some(m)) = (&out.end, out.last_move.filter(|m| *m > rules.tolerance)) {
        report.warnings.push(format!(
            "the mesh fitting stopped at its pass limit ({} passes, `fem.max_fits`) with a contact boundary or stick→slip transition {} m ({:.1} % of an arc element) from its node: the arcs carry that offset",
            out.passes + out.rejected,
            numerics::Sig(m),
            100.0 * m / element
        ));
    }
    if let FitEnd::Bracketed { width, jump } = out.end {
        report.warnings.push(format!(
            "the stick→slip transition could not be fitted to a node on this mesh: its located position jumps by {} m ({:.1} % of an arc element) as the node crosses it (the node sticks on one side, slips on the other); the node was bisected onto the jump to {} m, and the stick and slip arcs carry up to {} m — a finer mesh resolves it (docs/fem-drive.md §12)",
            numerics::Sig(jump),
            100.0 * jump / element,
            numerics::Sig(width),
            numerics::Sig(jump)
        ));
    }
    // an unresolved fit leaves the stick/slip arcs wrong by a fraction of an element or
    // more: a named error above 5 % of an arc element (§12; the unresolved cases
    // measured sit at 10–50 %, the stalled but resolved ones at ≤ 1 %)
    if let Some(m) = report.fit.fit_last_move.filter(|m| !report.fit.fit_converged && *m > 0.05 * element) {
        let reason = report.fit.fit_failure.clone().unwrap_or_else(|| "the passes did not converge".into());
        return Err(FemError::SteadyFitFailed { passes: report.fit.fits + report.rejected_fits, last_move: m, element, reason });
    }
    Ok(state)
}

/// ρc² of a state (0 without inertia).
fn rho_c2<const N: usize, K: LayoutElement<N> + ?Sized>(state: &State<N, K>) -> f64 {
    let c = state.x[state.asm.len()];
    state.rho.map_or(0.0, |rho| rho * c * c)
}

/// SpeedAtOrAboveCritical if N − ρc²λ ≤ 0 at a span midpoint of `sol` (ρc² given).
fn check_critical<const N: usize, K: LayoutElement<N> + ?Sized>(sol: &FemSolution<N, K>, rc2: f64) -> Result<(), FemError> {
    let c = sol.mesh().contour();
    let (h, r) = (c.centre_distance(), c.radius());
    for (span, sigma) in [("upper", 0.5 * h), ("lower", 1.5 * h + PI * r)] {
        let n = sol.recovered_axial_force(sigma);
        let stretch = sol.stretch(sigma);
        if n - rc2 * stretch <= 0.0 {
            return Err(FemError::SpeedAtOrAboveCritical { span: span.into(), tension: n, inertia_force: rc2 * stretch, time: None });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! The generalised Jacobian of (DS1)–(DS4) and of the inertia term against central
    //! differences of the residual F, at a converged drive state with gravity and
    //! inertia perturbed off equilibrium, for every column whose perturbation keeps the
    //! active set (stick/slip of every point and the sign of every gap) unchanged — for
    //! the string and for the Cosserat element (docs/fem-cosserat.md §10: its transport
    //! inertia (C11) and gravity (C12) through the augmented map (C3), the friction load
    //! (C14) with ∂²S/∂q² at the flagged nodes).
    use super::*;
    use crate::formulation::cosserat::{CosseratElement, CosseratRules, NC};

    const SCENE: &str = r#"{
      "name": "jacobian",
      "drive": {"pulley_radius": 0.08, "centre_distance": 0.45, "driver_speed": 10.0, "driven_torque": 2.0, "driven_damping": 0.01},
      "belt": {"theory": "string", "length": 1.3956749, "axial_stiffness": 20000.0, "mass_per_length": 0.12},
      "effects": {"gravity": 9.81, "inertia": true, "contact": {"coulomb": 0.3}},
      "analysis": "steady",
      "fem": {"elements": 24}
    }"#;

    /// `check` on the steady problem of `scene` with the element `kernel` and the bending
    /// stiffness `bending` of its term parameters, at a converged drive state with gravity
    /// and inertia perturbed off equilibrium (x).
    /// `fixed`: the points carry Paper D's fixed rows instead (alternately stick and slip,
    /// both slip senses; the string's slip bound is then the equilibrium normal);
    /// `halves`: every eighth point (every fourth without `fixed`) an entry half and every eighth (offset 5) an exit half
    /// of the contact-side halves (their own side's normal load — with `fixed` the
    /// equilibrium normal, a stick entry and a slip exit half; without, the semismooth
    /// rows, the entry halves' tractions below their bound so that their tie to the
    /// neighbour holds).
    #[allow(clippy::too_many_arguments)]
    fn with_state<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(scene: &drive::Scene, kernel: Arc<K>, bending: Option<f64>, ends: Ends, fixed: bool, halves: bool, check: impl FnOnce(&SteadyProblem<N, P, E, K>, &[f64])) {
        let opts = crate::options::FemOptions::from_scene(scene, crate::default_formulation());
        let settings = crate::options::SolverSettings::default();
        let super::super::DriveStart { start, penalty, .. } = super::super::drive_start(&crate::problem::FemProblem::from_scene(scene), &opts, &settings, &super::super::DriveSettings::default(), kernel.clone(), settings.arc_weight).unwrap();
        let asm = Assembler::with_kernel(start.mesh().clone(), kernel.clone());
        let mut points = friction_points(&asm, &[], Direction::Clockwise);
        for (i, p) in points.iter_mut().enumerate() {
            if fixed {
                p.fixed = Some(match i % 4 {
                    0 | 2 => Fixed::Stick,
                    1 => Fixed::Slip(1.0),
                    _ => Fixed::Slip(-1.0),
                });
            }
            match i % 8 {
                0 | 4 if halves && (i % 8 == 0 || !fixed) => *p = FrictionPoint { weight: p.right.1, part: Part::Right, boundary: true, ..*p },
                5 if halves => *p = FrictionPoint { weight: p.left.1, part: Part::Left, boundary: true, ..*p },
                _ => {}
            }
        }
        let b = &scene.belt;
        // a soft penalty keeps the FD of the normal term well conditioned
        let params = TermParams { axial_stiffness: b.axial_stiffness, weight: Some(9.81 * b.mass_per_length), penalty: Some(1e-3 * penalty), bending_stiffness: bending };
        let sp = SteadyParams { mu: 0.3, penalty: 1e-3 * penalty, kappa: 10.0, radius: 0.08, omega1: 10.0, torque: 2.0, damping: 0.01, inertia: Some(0.12), ends };
        let prob: SteadyProblem<N, P, E, K> = SteadyProblem { asm: &asm, params, length: b.length, points: &points, sp, strain_rule: kernel.rules().strain };
        if halves {
            // the Cosserat rod's stick entry halves are tied to their neighbour; Paper D's
            // string ones have their own row (the stick zone's traction at the run-on point)
            let own_row = |p: &FrictionPoint| p.is_entry() && p.fixed == Some(Fixed::Stick) && kernel.friction_normal() == FrictionNormal::Nodal;
            assert!((0..points.len()).any(|i| prob.entry_neighbour(i).is_some() || own_row(&points[i])), "a stick entry half's tie or row is exercised");
        }
        let mut x = crate::static_homotopy::transfer(&start, &asm);
        x.extend([0.79, 9.9]);
        // tractions of both signs, some above their bound (slip), some below (stick);
        // the semismooth scheme's entry halves below theirs (their tie active)
        x.extend((0..points.len()).map(|i| if i % 2 == 0 && !(halves && !fixed && i % 4 == 0) { 3000.0 } else { 10.0 } * ((i as f64) * 1.7).sin()));
        for (i, v) in x.iter_mut().enumerate().take(asm.len()) {
            *v += 1e-7 * ((i as f64) * 0.37).cos();
        }
        // pressed into the drums by 10 µm: a bound μP⟨−γ⟩ ≈ 900 N/m at the contact nodes;
        // a rotation ψ of 10⁻³ rad off the contour tangent where the layout has one
        for k in 0..asm.mesh().len() {
            let node = asm.dofs().node_unknowns(k);
            x[node.values[1].expect("ν at every node")] -= 1e-5;
            if let Some(psi) = node.values.get(2).copied().flatten().filter(|_| N > NDOF) {
                x[psi] += 1e-3 * ((k as f64) * 0.9).sin();
            }
        }
        check(&prob, &x);
    }

    /// The generalised Jacobian at [`with_state`]'s state against central differences of
    /// the residual.
    fn check_jacobian<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(scene: &drive::Scene, kernel: Arc<K>, bending: Option<f64>, ends: Ends, fixed: bool, halves: bool) {
        with_state::<N, P, E, K>(scene, kernel, bending, ends, fixed, halves, |prob, x| jacobian_against_differences(prob, x));
    }

    fn jacobian_against_differences<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(prob: &SteadyProblem<N, P, E, K>, x: &[f64]) {
        let asm = prob.asm;
        let points = prob.points;
        let x = x.to_vec();
        let n = x.len();
        let ev = prob.evaluate(&x, true).unwrap();
        let (rows, cols) = prob.pattern();
        let mut dense = vec![0.0; n * n];
        for (k, v) in ev.values.iter().enumerate() {
            dense[rows[k] * n + cols[k]] += v;
        }
        let signature = |e: &Evaluated| e.results.iter().map(|p| (p.slip, p.normal > 0.0)).collect::<Vec<_>>();
        let base = signature(&ev);
        let fmax = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut checked, mut worst) = (0, 0.0f64);
        // the step: 10⁻⁷ of the unknown or of its scale in the Newton update norm (the
        // variable weights: H for node values, 1 for slopes) — a fixed floor of 10⁻¹¹
        // drowns the near-zero ν, ψ and slope columns in round-off on graded meshes,
        // whose shortest elements (1.3 mm next to 124 mm) carry residuals of 3·10⁷
        let scale = variable_weights(asm, 0.45, 0.08, 10.0, 1.0, points.len());
        for j in 0..n {
            let d = 1e-7 * x[j].abs().max(if j < asm.len() { scale[j] } else { 1e-4 });
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += d;
            xm[j] -= d;
            let (ep, em) = (prob.evaluate(&xp, false).unwrap(), prob.evaluate(&xm, false).unwrap());
            if signature(&ep) != base || signature(&em) != base {
                continue;
            }
            checked += 1;
            for i in 0..n {
                let fd = (ep.residual[i] - em.residual[i]) / (2.0 * d);
                let err = (fd - dense[i * n + j]).abs();
                worst = worst.max(err / fmax);
                assert!(err <= 1e-6 * fmax + 1e-6 * fd.abs(), "J[{i}][{j}]: analytic {} FD {fd}", dense[i * n + j]);
            }
        }
        assert!(checked > n / 2, "only {checked} of {n} columns kept the active set");
        assert!(base.iter().any(|p| p.0) && base.iter().any(|p| !p.0 && p.1), "both stick and slip points are exercised");
        assert!(worst < 1e-6);
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let scene = drive::Scene::from_json_str(SCENE).unwrap();
        let opts = crate::options::FemOptions::from_scene(&scene, crate::default_formulation());
        let kernel = crate::formulation::find(&opts.formulation).unwrap();
        check_jacobian::<NDOF, NPV, NEV, dyn Kernel>(&scene, kernel.clone(), None, Ends::Loop, false, false);
        // Paper D's fixed rows with the equilibrium normal (its λ, c and e_r terms)
        check_jacobian::<NDOF, NPV, NEV, dyn Kernel>(&scene, kernel.clone(), None, Ends::Loop, true, false);
        // and with contact-side halves: an entry half's tie, a half's own-side normal
        check_jacobian::<NDOF, NPV, NEV, dyn Kernel>(&scene, kernel, None, Ends::Loop, true, true);
    }

    /// The residual-only pass (`evaluate(x, false)`: first-order or plain f64 terms, no
    /// Hessians or Jacobian blocks) equals the residual of the Jacobian pass to round-off,
    /// with the same point results, at [`with_state`]'s state (gravity, inertia, stick and
    /// slip points) for every element kind: the string, the string as Kirchhoff rod
    /// (bending, the augmented map's 4-value path), the string with Paper D's fixed rows
    /// (equilibrium normal), the Cosserat rod on the loop and with the open ends in both
    /// modes. Tolerance 1e-12 of the largest |F|: the two passes sum the same terms, the
    /// first derivatives by first- instead of second-order duals and the string's ν rows
    /// in another order (measured: 0.8e-16 … 3.6e-15 of the largest |F|).
    #[test]
    fn value_only_residual_equals_the_jacobian_pass() {
        fn same<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(prob: &SteadyProblem<N, P, E, K>, x: &[f64]) {
            let (full, value) = (prob.evaluate(x, true).unwrap(), prob.evaluate(x, false).unwrap());
            assert!(value.values.is_empty() && !full.values.is_empty(), "the residual pass builds no Jacobian");
            let fmax = full.residual.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(fmax > 0.0);
            for (i, (a, b)) in full.residual.iter().zip(&value.residual).enumerate() {
                assert!((a - b).abs() <= 1e-12 * fmax, "F[{i}]: Jacobian pass {a}, residual pass {b} (|F|max {fmax})");
            }
            assert_eq!(full.results.len(), value.results.len());
            for (a, b) in full.results.iter().zip(&value.results) {
                assert_eq!(a.slip, b.slip);
                for (u, v) in [(a.normal, b.normal), (a.velocity, b.velocity), (a.traction, b.traction)] {
                    assert!((u - v).abs() <= 1e-12 * u.abs().max(1.0), "point result {u} vs {v}");
                }
            }
            assert!(full.results.iter().any(|p| p.slip) && full.results.iter().any(|p| !p.slip && p.normal > 0.0), "stick and slip points");
        }
        let scene = drive::Scene::from_json_str(SCENE).unwrap();
        let opts = crate::options::FemOptions::from_scene(&scene, crate::default_formulation());
        let string = crate::formulation::find(&opts.formulation).unwrap();
        for (bending, fixed, halves) in [(None, false, false), (Some(1e-3), false, false), (None, true, false), (None, true, true)] {
            with_state::<NDOF, NPV, NEV, dyn Kernel>(&scene, string.clone(), bending, Ends::Loop, fixed, halves, same);
        }
        let json = SCENE.replace(r#""theory": "string""#, r#""theory": "cosserat", "bending_stiffness": 0.001, "shear_stiffness": 10000.0"#);
        let scene = drive::Scene::from_json_str(&json).unwrap();
        for ends in [Ends::Loop, Ends::Open { transport_rate: 0.79, flux_in: 300.0, flux_out: 250.0, pulley_speed: None }, Ends::Open { transport_rate: 0.79, flux_in: 300.0, flux_out: 250.0, pulley_speed: Some(9.95) }] {
            let kernel: Arc<dyn LayoutElement<NC>> = Arc::new(CosseratElement::new(1e4, CosseratRules::with_shear(Rule::Gauss(3))));
            with_state::<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>>(&scene, kernel, Some(1e-3), ends, false, false, same);
        }
        // the Cosserat loop's contact-side halves in the semismooth rows
        let kernel: Arc<dyn LayoutElement<NC>> = Arc::new(CosseratElement::new(1e4, CosseratRules::with_shear(Rule::Gauss(3))));
        with_state::<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>>(&scene, kernel, Some(1e-3), Ends::Loop, false, true, same);
    }

    /// The element penalty's unclipped pressures −Pγ (no multipliers on the string) at
    /// [`with_state`]'s state, pressed 10 µm into the drums: one per element and contact
    /// rule point, equal to −P times the gap of the solution at that σ, `None` out of
    /// reach; some points pressed, some free.
    #[test]
    fn penalty_pressures_are_minus_p_times_the_gap() {
        let scene = drive::Scene::from_json_str(SCENE).unwrap();
        let opts = crate::options::FemOptions::from_scene(&scene, crate::default_formulation());
        let string = crate::formulation::find(&opts.formulation).unwrap();
        with_state::<NDOF, NPV, NEV, dyn Kernel>(&scene, string, None, Ends::Loop, false, false, |prob, x| {
            let asm = prob.asm;
            let rule = asm.kernel().rules().contact;
            let penalty = prob.params.penalty.unwrap();
            let p = prob.penalty_pressures(x);
            assert_eq!(p.len(), asm.mesh().len() * rule.points().len());
            let sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &x[..asm.len()], prob.params, prob.length, asm.kernel().clone());
            let (mut pressed, mut free, mut out) = (0, 0, 0);
            for (k, pk) in p.iter().enumerate() {
                let (e, xi) = (k / rule.points().len(), rule.points()[k % rule.points().len()].0);
                let el = asm.context(e, &prob.params);
                // interior points only: a node's σ belongs to either element (same gap)
                let sigma = el.sigma(xi.clamp(-1.0 + 1e-12, 1.0 - 1e-12));
                match (pk, sol.gap(sigma)) {
                    (Some(v), Some(g)) => {
                        assert!((v + penalty * g).abs() <= 1e-6 * penalty * 1e-5, "element {e} ξ {xi}: {v} against −P·{g}");
                        if *v > 0.0 { pressed += 1 } else { free += 1 }
                    }
                    (None, None) => out += 1,
                    (a, b) => panic!("element {e} ξ {xi}: pressure {a:?}, gap {b:?}"),
                }
            }
            assert!(pressed > 0 && free > 0 && out > 0, "{pressed} pressed, {free} free, {out} out of reach");
        });
    }

    /// The Cosserat element (b₂ = 10⁴ N, a = 10⁻³ N·m², augmented transitions) on the same
    /// drive: the terms it adds to the steady equations — transport inertia and gravity
    /// on its centreline through the map (C3), the friction load's ∂²S/∂q² at the flagged
    /// nodes — against central differences.
    #[test]
    fn cosserat_jacobian_matches_finite_differences() {
        let json = SCENE.replace(r#""theory": "string""#, r#""theory": "cosserat", "bending_stiffness": 0.001, "shear_stiffness": 10000.0"#);
        let scene = drive::Scene::from_json_str(&json).unwrap();
        let kernel: Arc<dyn LayoutElement<NC>> = Arc::new(CosseratElement::new(1e4, CosseratRules::with_shear(Rule::Gauss(3))));
        let mesh = Mesh::new(crate::problem::FemProblem::from_scene(&scene).hanging(1.0).contour().unwrap(), 24, 1.0).unwrap();
        assert!(crate::dofs::augmented_flags(&mesh, kernel.separate_transition_slopes()).iter().flatten().any(|&a| a), "the map (C3) is exercised");
        check_jacobian::<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>>(&scene, kernel.clone(), Some(1e-3), Ends::Loop, false, false);
        // the semismooth rows with contact-side halves (docs/fem-cosserat.md §11.1): the
        // stick entry halves' ties, the halves' own-side tributary normal load
        with_state::<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>>(&scene, kernel, Some(1e-3), Ends::Loop, false, true, |prob, x| {
            let ev = prob.evaluate(x, false).unwrap();
            let tied = (0..prob.points.len()).filter(|&i| prob.entry_neighbour(i).is_some() && !ev.results[i].slip && ev.results[i].normal > 0.0).count();
            let exits = ev.results.iter().filter(|r| r.point.boundary && !r.point.is_entry() && r.normal > 0.0).count();
            assert!(tied >= 2 && exits >= 2, "{tied} tied stick entry halves, {exits} pressed exit halves");
            // a half's normal load is its own element's mean: not the whole node's
            let whole = |r: &PointResult| FrictionPoint { part: Part::Whole, boundary: false, weight: r.point.left.1 + r.point.right.1, ..r.point };
            let differs = ev.results.iter().filter(|r| r.point.boundary).any(|r| (prob.tributary_normal(whole(r), &x[..prob.asm.len()], false).0 - r.normal).abs() > 1e-6 * r.normal);
            assert!(differs, "the halves' normal load is their own side's");
            jacobian_against_differences(prob, x);
        });
    }

    /// The open layout's rows (docs/fem-cosserat.md §12.3, §12.7) on the same Cosserat
    /// state: c given, (C21) on the ω-row, 𝓗_out on the last node's ξ-row, the tributary
    /// normal load — in mode `tensions` (ω in its slot) and `pulley_speed` (ω given, the
    /// slot 𝓗_in) — against central differences. (The closed mesh only hosts the rows:
    /// the check is of the derivatives, not of a solution.)
    #[test]
    fn open_ends_jacobian_matches_finite_differences() {
        let json = SCENE.replace(r#""theory": "string""#, r#""theory": "cosserat", "bending_stiffness": 0.001, "shear_stiffness": 10000.0"#);
        let scene = drive::Scene::from_json_str(&json).unwrap();
        for pulley_speed in [None, Some(9.95)] {
            let kernel: Arc<dyn LayoutElement<NC>> = Arc::new(CosseratElement::new(1e4, CosseratRules::with_shear(Rule::Gauss(3))));
            let ends = Ends::Open { transport_rate: 0.79, flux_in: 300.0, flux_out: 250.0, pulley_speed };
            check_jacobian::<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>>(&scene, kernel, Some(1e-3), ends, false, false);
        }
    }

    /// The Cosserat element (b₂ = 10⁴ N, gauss3 shear) on the test drive's 24-element
    /// mesh in a wavy state (ψ ≠ 0, ν ≠ 0): (kernel, assembler, z).
    fn cosserat_wave_state() -> (Arc<dyn LayoutElement<NC>>, Assembler<NC, dyn LayoutElement<NC>>, Vec<f64>) {
        let json = SCENE.replace(r#""theory": "string""#, r#""theory": "cosserat", "bending_stiffness": 0.001, "shear_stiffness": 10000.0"#);
        let scene = drive::Scene::from_json_str(&json).unwrap();
        let kernel: Arc<dyn LayoutElement<NC>> = Arc::new(CosseratElement::new(1e4, CosseratRules::with_shear(Rule::Gauss(3))));
        let mesh = Mesh::new(crate::problem::FemProblem::from_scene(&scene).hanging(1.0).contour().unwrap(), 24, 1.0).unwrap();
        let asm = Assembler::with_kernel(mesh, kernel.clone());
        let z = crate::assembly::tests::wave_state(&asm, 0.99);
        (kernel, asm, z)
    }

    /// The per-point transport inertia (`inertia_derivatives` on an element without
    /// the augmented map) equals AD over all the element's unknowns
    /// (`inertia_derivatives_mapped`) to round-off — both exact — on every such element
    /// of a Cosserat mesh in a wavy state (ν, ψ ≠ 0): 1e-12 of the gradient and 1e-11 of
    /// the Hessian scale.
    #[test]
    fn pointwise_inertia_equals_full_ad() {
        let (kernel, asm, z) = cosserat_wave_state();
        let layout = kernel.layout();
        let params = TermParams { axial_stiffness: 2e4, weight: Some(1.1772), penalty: None, bending_stiffness: Some(1e-3) };
        let mut compared = 0;
        for e in 0..asm.mesh().len() {
            let el = asm.context(e, &params);
            if el.augmented.iter().any(|&a| a) {
                continue;
            }
            let q = asm.dofs().gather(e, &z, 1.3956749);
            for rule in [Rule::Simpson, Rule::Gauss(3)] {
                let (ga, gca, ha) = inertia_derivatives(layout, &el, &q, 0.8, 0.12, rule);
                let (gb, gcb, hb) = inertia_derivatives_mapped(layout, &el, &q, 0.8, 0.12, rule);
                let gs = gb.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
                let hs = hb.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
                for i in 0..NC {
                    assert!((ga[i] - gb[i]).abs() <= 1e-12 * gs && (gca[i] - gcb[i]).abs() <= 1e-12 * gs / 0.8, "element {e} g[{i}]: {} vs {}", ga[i], gb[i]);
                    for j in 0..NC {
                        assert!((ha[i][j] - hb[i][j]).abs() <= 1e-11 * hs, "element {e} H[{i}][{j}]: {} vs {}", ha[i][j], hb[i][j]);
                    }
                }
            }
            compared += 1;
        }
        assert!(compared >= 16, "{compared} elements compared");
    }

    /// The kernels the steady equations add for an element of the Cosserat layout,
    /// element by element against central differences on a wavy state (ψ ≠ 0, ν ≠ 0)
    /// and in every element whose nodes carry the augmented map (C3): the transport
    /// inertia −T (C11) in q and c (gradient, ∂²/∂q², ∂²/∂q∂c), the friction load (C14)
    /// with its Jacobian in (q, c, ω₂, τ_a, τ_b) — through the map S is quadratic in q —,
    /// and the gradients of the upwind stretch (DS0) and of the gap.
    #[test]
    fn cosserat_steady_kernels_match_central_differences() {
        let (kernel, asm, z) = cosserat_wave_state();
        let layout = kernel.layout();
        let points = friction_points(&asm, &[], Direction::Clockwise);
        let params = TermParams { axial_stiffness: 2e4, weight: Some(1.1772), penalty: None, bending_stiffness: Some(1e-3) };
        let sp = SteadyParams { mu: 0.3, penalty: 1e8, kappa: 10.0, radius: 0.08, omega1: 10.0, torque: 2.0, damping: 0.01, inertia: Some(0.12), ends: Ends::Loop };
        let prob: SteadyProblem<NC, { point_size(NC) }, { element_size(NC) }, dyn LayoutElement<NC>> = SteadyProblem { asm: &asm, params, length: 1.3956749, points: &points, sp, strain_rule: kernel.rules().strain };
        let owners = prob.edge_owners();
        let close = |a: f64, fd: f64, scale: f64, what: &str| assert!((a - fd).abs() <= 1e-6 * scale + 1e-7 * fd.abs(), "{what}: analytic {a}, central difference {fd}");
        let (mut mapped, mut loaded) = (0, 0);
        for (e, owner) in owners.iter().enumerate().take(asm.mesh().len()) {
            let el = asm.context(e, &params);
            if !el.augmented.iter().any(|&a| a) && e % 5 != 0 {
                continue;
            }
            mapped += usize::from(el.augmented.iter().any(|&a| a));
            let q = asm.dofs().gather(e, &z, prob.length);
            let bump = |i: usize, d: f64| {
                let mut p = q;
                p[i] += d;
                p
            };
            let step = |i: usize| 1e-6 * q[i].abs().max(1e-3);
            // −T (C11) and its derivatives
            let c = 0.8;
            let energy = |qq: &[f64; NC], cc: f64| crate::formulation::TransportInertia { rule: prob.strain_rule, rho: 0.12 }.element_energy(&el, &centreline(layout, &el, qq), cc);
            let (gq, gc, h) = inertia_derivatives(layout, &el, &q, c, 0.12, prob.strain_rule);
            let gscale = gq.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let hscale = h.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..NC {
                let d = step(i);
                close(gq[i], (energy(&bump(i, d), c) - energy(&bump(i, -d), c)) / (2.0 * d), gscale, "∂(−T)/∂q");
                let (gp, _, _) = inertia_derivatives(layout, &el, &bump(i, d), c, 0.12, prob.strain_rule);
                let (gm, _, _) = inertia_derivatives(layout, &el, &bump(i, -d), c, 0.12, prob.strain_rule);
                for j in 0..NC {
                    close(h[j][i], (gp[j] - gm[j]) / (2.0 * d), hscale, "∂²(−T)/∂q²");
                }
                let (gcp, _, _) = inertia_derivatives(layout, &el, &q, c + 1e-6, 0.12, prob.strain_rule);
                let (gcm, _, _) = inertia_derivatives(layout, &el, &q, c - 1e-6, 0.12, prob.strain_rule);
                close(gc[i], (gcp[i] - gcm[i]) / 2e-6, gscale, "∂²(−T)/∂q∂c");
            }
            // the upwind stretch and the gap at both edges
            let (_, dl) = element_stretch(layout, &el, &q, true);
            for i in 0..NC {
                let d = step(i);
                close(dl[i], (element_stretch(layout, &el, &bump(i, d), false).0 - element_stretch(layout, &el, &bump(i, -d), false).0) / (2.0 * d), 1.0 / el.geometry.h, "∂λ̄/∂q");
                for xi in [-1.0, 1.0] {
                    if let Some((_, dg)) = point_gap(layout, &el, &q, xi, true) {
                        let gap = |qq: &[f64; NC]| point_gap(layout, &el, qq, xi, false).unwrap().0;
                        close(dg[i], (gap(&bump(i, d)) - gap(&bump(i, -d))) / (2.0 * d), 1.0, "∂γ/∂q");
                    }
                }
            }
            // the friction load (C14) in the element's global unknowns, c, ω₂ and τ
            if *owner == [None, None] {
                continue;
            }
            loaded += usize::from(el.augmented.iter().any(|&a| a));
            let tau = [3000.0, -2000.0];
            let load = |zz: &[f64], t: [f64; 2]| prob.element_friction(e, zz, t, true, false).0;
            let jac = prob.element_friction(e, &z, tau, true, true).1.expect("a Jacobian pass");
            let jscale = jac.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            for (k, gi) in asm.dofs().element(e).iter().enumerate() {
                let Some(gi) = *gi else { continue };
                let d = 1e-6 * z[gi].abs().max(1e-3);
                let (mut zp, mut zm) = (z.clone(), z.clone());
                zp[gi] += d;
                zm[gi] -= d;
                let (rp, rm) = (load(&zp, tau), load(&zm, tau));
                for a in 0..NC + 2 {
                    close(jac[a][k], (rp[a] - rm[a]) / (2.0 * d), jscale, "∂(friction load)/∂q");
                }
            }
            for side in 0..2 {
                let (mut tp, mut tm) = (tau, tau);
                tp[side] += 1.0;
                tm[side] -= 1.0;
                let (rp, rm) = (load(&z, tp), load(&z, tm));
                for a in 0..NC + 2 {
                    close(jac[a][NC + 2 + side], (rp[a] - rm[a]) / 2.0, jscale, "∂(friction load)/∂τ");
                }
            }
        }
        assert!(mapped >= 4 && loaded >= 2, "the map (C3) is exercised: {mapped} mapped elements, {loaded} with friction");
    }
}
