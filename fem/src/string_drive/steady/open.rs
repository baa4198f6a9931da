//! The direct steady solve of the open one-pulley layout (Paper C; docs/fem-cosserat.md
//! §12): the loop's steady equations on an open mesh ([`Mesh::open`], the loop's contour
//! of H = D without its second arc), with [`Ends::Open`] closing them — c given, ω the
//! unknown of the global material balance (C21), the end fluxes 𝓗 of (C18) — and a
//! continuation in the outflow tension from N_out = N_in (pure stick, no friction load)
//! to the scene's N_out. Mode `pulley_speed` swaps the ω-slot's unknown for 𝓗_in (§12.7);
//! mode `stick_slip_angle` finds the free tension by Brent's method on the FE's φ_B (§12.7).

use numerics::Sig;
use std::f64::consts::FRAC_PI_2;

use drive::contour::OpenContour;
use drive::scene::End;
use drive::summary::{PulleySummary, Summary};
use drive::contour::Path;
use drive::view::ContactState;

use super::*;

/// The open ends of a one-pulley scene as the FE reads them: of `tension_in`,
/// `tension_out`, `pulley_speed`, `stick_slip_angle` the scene gives two (validated by
/// the scene; [`OpenEnds::mode`] refuses the combinations the FE does not solve).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct OpenEnds {
    /// D, m: the end sections are at x = −D.
    pub end_distance: f64,
    /// c, m/s.
    pub transport_rate: f64,
    /// N_in, N, if given.
    pub tension_in: Option<f64>,
    /// N_out, N, if given.
    pub tension_out: Option<f64>,
    /// ω, rad/s (clockwise positive), if given.
    pub pulley_speed: Option<f64>,
    /// φ_B, rad (polar angle of the stick → slip point), if given.
    pub stick_slip_angle: Option<f64>,
    /// With φ_B given: the belt drives the pulley (N_in < N_out), else the pulley drives
    /// the belt (φ_B fixes the slip arc, not its sense).
    pub belt_drives_pulley: bool,
}

/// What a one-pulley scene prescribes besides c (spec §2.3), as the FE solves it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OpenMode {
    /// N_in, N_out given.
    Tensions { tension_in: f64, tension_out: f64 },
    /// ω and N_out given (ω with N_in leaves N_out undetermined, as the BVP says).
    PulleySpeed { pulley_speed: f64, tension_out: f64 },
    /// φ_B and the tension of `given`; `driving`: the pulley drives the belt (N_in >
    /// N_out), else the belt drives the pulley.
    Transition { stick_slip_angle: f64, given: End, tension: f64, driving: bool },
}

/// ω with N_in leaves N_out undetermined (the BVP's `PULLEY_SPEED_WITH_TENSION_IN`).
const PULLEY_SPEED_WITH_TENSION_IN: &str = "ω fixes the stick stretch λ_B = ωR/c of the stick zone, which sits on the inflow side: λ_B ≈ λ(N_in), so ω and N_in together leave N_out undetermined (up to exponentially small terms); prescribe `pulley_speed` with `tension_out`";

impl OpenEnds {
    /// The prescription mode.
    ///
    /// # Errors
    /// [`FemError::Prescription`] for `pulley_speed` with `tension_in` (ill-posed), and
    /// for a pair the scene validation refuses (not two of the four, no tension).
    pub fn mode(&self) -> Result<OpenMode, FemError> {
        match (self.tension_in, self.tension_out, self.pulley_speed, self.stick_slip_angle) {
            (Some(tension_in), Some(tension_out), None, None) => Ok(OpenMode::Tensions { tension_in, tension_out }),
            (None, Some(tension_out), Some(pulley_speed), None) => Ok(OpenMode::PulleySpeed { pulley_speed, tension_out }),
            (Some(_), None, Some(pulley_speed), None) => Err(FemError::Prescription { name: "pulley_speed", value: pulley_speed, reason: PULLEY_SPEED_WITH_TENSION_IN.into() }),
            (Some(tension), None, None, Some(stick_slip_angle)) => Ok(OpenMode::Transition { stick_slip_angle, given: End::In, tension, driving: !self.belt_drives_pulley }),
            (None, Some(tension), None, Some(stick_slip_angle)) => Ok(OpenMode::Transition { stick_slip_angle, given: End::Out, tension, driving: !self.belt_drives_pulley }),
            _ => Err(FemError::Prescription { name: "drive", value: f64::NAN, reason: "a one-pulley scene gives exactly two of tension_in, tension_out, pulley_speed, stick_slip_angle, at least one a tension".into() }),
        }
    }
}

/// 𝓗 of (C18) on a straight end section with axial force N (Q = M = 0): N(1 + Γ₁/2) −
/// ½χλ², Γ₁ = N/b₁, λ = 1 + Γ₁, χ = ρc² (N).
pub fn end_flux(tension: f64, axial_stiffness: f64, chi: f64) -> f64 {
    let g1 = tension / axial_stiffness;
    tension * (1.0 + 0.5 * g1) - 0.5 * chi * (1.0 + g1) * (1.0 + g1)
}

/// N of an end section with flux 𝓗 of (C18): the root of 𝓗(N) = h near `guess` (Newton;
/// ∂𝓗/∂N = 1 + Γ₁ − χλ/b₁ > 0 below the critical speed).
fn end_tension(flux: f64, axial_stiffness: f64, chi: f64, guess: f64) -> f64 {
    let mut n = guess;
    for _ in 0..20 {
        let lam = 1.0 + n / axial_stiffness;
        let step = (end_flux(n, axial_stiffness, chi) - flux) / (lam - chi * lam / axial_stiffness);
        n -= step;
        if step.abs() <= 1e-15 * n.abs() {
            break;
        }
    }
    n
}

/// Solve the one-pulley scene `problem` (its [`crate::problem::FemProblem::open`]) with
/// the element `kernel` of layout N (docs/fem-cosserat.md §12).
///
/// # Errors
/// [`FemError::Unsupported`] (not a one-pulley scene, gravity, no Coulomb contact),
/// [`FemError::Prescription`] (ω with N_in; ω or φ_B without a steady state),
/// [`FemError::InvalidOption`] (D ≤ 2R, element count),
/// [`FemError::SpeedAtOrAboveCritical`] (T̃ ≤ 0 at a given end or b₁, b₂ ≤ ρc²),
/// [`FemError::HomotopyStalled`], [`FemError::NonFinite`].
pub fn solve_open<const N: usize, const P: usize, const E: usize>(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::super::DriveSettings, kernel: Arc<dyn LayoutElement<N>>) -> Result<crate::FemRun, FemError> {
    let clock = std::time::Instant::now();
    let ends = problem.open.ok_or_else(|| FemError::Unsupported("the open FE solves one-pulley scenes only".into()))?;
    let mode = ends.mode()?;
    let crate::problem::ContactLaw::Coulomb { mu } = problem.effects.contact else {
        return Err(FemError::Unsupported("the one-pulley FE needs Coulomb contact".into()));
    };
    if problem.effects.gravity.is_some() {
        return Err(FemError::Unsupported("the one-pulley FE has no gravity: the end fluxes (C18) of docs/fem-cosserat.md §12 are derived without it".into()));
    }
    let b = &problem.belt;
    let r = problem.geometry.radius;
    let d = ends.end_distance;
    let c0 = ends.transport_rate;
    let contour = Contour::new(r, d).map_err(|e| FemError::InvalidOption { field: "drive.end_distance", value: d.to_string(), reason: format!("the open FE takes the loop's contour of H = D and needs D > 2R ({e})") })?;
    let rho = problem.effects.inertia.then_some(b.mass_per_length);
    let chi = rho.map_or(0.0, |rho| rho * c0 * c0);
    let b1 = b.axial_stiffness;
    // the given tensions, and the string estimate of a free one (docs/cosserat-pulley.md,
    // modes): mode `pulley_speed` the stick section's T̃ at λ_B = ωR/c; mode `transition`
    // the capstan over φ_B − φ_C, φ_C = −π/2 + √(a/T̃_out)/R
    let effective = |n: f64| n - chi * (1.0 + n / b1);
    let tension_of = |t: f64| (t + chi) / (1.0 - chi / b1);
    let (given, estimate): (Vec<(&str, f64)>, [f64; 2]) = match mode {
        OpenMode::Tensions { tension_in, tension_out } => (vec![("inflow", tension_in), ("outflow", tension_out)], [tension_in, tension_out]),
        OpenMode::PulleySpeed { pulley_speed, tension_out } => {
            let t_in = (b1 - chi) * pulley_speed * r / c0 - b1;
            if t_in.is_nan() || t_in <= 0.0 || pulley_speed <= 0.0 {
                return Err(FemError::Prescription { name: "pulley_speed", value: pulley_speed, reason: format!("the stick stretch ωR/c leaves the effective tension T̃_in = {t_in:.6e} N ≤ 0 at the inflow end") });
            }
            (vec![("outflow", tension_out)], [tension_of(t_in), tension_out])
        }
        OpenMode::Transition { stick_slip_angle, given, tension, driving } => {
            let a = b.bending_stiffness.unwrap_or(0.0);
            let t = effective(tension);
            let phi_c = |t_out: f64| -FRAC_PI_2 + (a / t_out).sqrt() / r;
            // the capstan over the slip arc: N_in > N_out when the pulley drives
            let mu_s = if driving { mu } else { -mu };
            let free = match given {
                End::Out => tension_of(t * (mu_s * (stick_slip_angle - phi_c(t))).exp()),
                End::In => tension_of(t * (-mu_s * (stick_slip_angle - phi_c(t))).exp()),
            };
            if !(stick_slip_angle > phi_c(t) && free.is_finite()) {
                return Err(FemError::Prescription { name: "stick_slip_angle", value: stick_slip_angle, reason: format!("below the contact end φ_C ≈ −π/2 + √(a/T̃)/R = {:.6}: no slip arc", phi_c(t)) });
            }
            let pair = if given == End::In { [tension, free] } else { [free, tension] };
            (vec![(if given == End::In { "inflow" } else { "outflow" }, tension)], pair)
        }
    };
    // the effective tension T̃ = N − χλ at the given ends, and b₁, b₂ above χ (spec §1.2)
    for (span, n) in given {
        let lam = 1.0 + n / b1;
        let b2 = kernel.shear_stiffness().unwrap_or(f64::INFINITY);
        if n - chi * lam <= 0.0 || b1 <= chi || b2 <= chi {
            return Err(FemError::SpeedAtOrAboveCritical { span: span.into(), tension: n, inertia_force: chi * lam, time: None });
        }
    }
    let mesh = Mesh::open(contour, opts.elements, settings.arc_weight)?;
    let penalty = problem.penalty(opts, settings);
    let params = TermParams { axial_stiffness: b1, weight: None, penalty: Some(penalty), bending_stiffness: b.bending_stiffness };
    let asm = Assembler::with_kernel(mesh, kernel.clone());
    let omega0 = c0 * (1.0 + estimate[0] / b1) / r;
    let arc_elements = asm.mesh().elements().iter().filter(|e| e.region == Region::DrivenArc).count().max(1);
    // κ = P_⊥ Δt₀ as the loop's (any κ > 0 has the same roots)
    let kappa = drive_settings.tangential_penalty_factor * b1 / (r * r) * (PI * r / arc_elements as f64) / (r * omega0.abs());
    let points = friction_points(&asm, &[], Direction::Clockwise);
    let f_ref = estimate[0].max(estimate[1]);
    let w = variable_weights(&asm, d, r, omega0.abs(), f_ref, points.len());
    let scales = row_scales(&asm, f_ref, points.len());
    let base = SteadyParams { mu, penalty, kappa, radius: r, omega1: omega0, torque: 0.0, damping: 0.0, inertia: rho, ends: Ends::Loop };
    // the fit (§12.5): a node at the contact start A, the stick→slip point B and the
    // contact end C, the mesh graded towards them over the shear layer √(a/(b₂ − ρc²))
    let fit = settings.contact_fitting.then(|| OpenFit { settings, drive_settings, grading: crate::static_homotopy::shear_layer_grading(params.bending_stiffness, kernel.shear_stiffness().map(|b2| b2 - chi)), element: PI * r / arc_elements as f64 });
    let setup = OpenSetup::<N, P, E, dyn LayoutElement<N>> { asm: &asm, points: &points, params, base, w: &w, scales: &scales, tolerance: settings.update_tolerance, max_iterations: drive_settings.max_newton_iterations, kernel: &kernel, transport_rate: c0, axial_stiffness: b1, chi, rho, end_distance: d, f_ref, _sizes: std::marker::PhantomData };
    let mut report = SteadyReport { friction_points: points.len(), ..Default::default() };
    let flux = |n: f64| end_flux(n, b1, chi);
    let (mut state, sp) = match mode {
        OpenMode::Tensions { tension_in, tension_out } => {
            let (from, to) = (setup.ends(flux(tension_in), flux(tension_in), None), setup.ends(flux(tension_in), flux(tension_out), None));
            // nested: the continuation on a coarse mesh, carried up by doublings
            // (nested.rs); on this mesh if a rung fails
            let sp_to = setup.sp(to);
            let sp_at = move |_: f64| sp_to;
            let base = setup.fit_data(&sp_at, None, None);
            let data = nested::NestedData { base: &base, arc_weight: settings.arc_weight, inertia: None, start_rates: [c0, omega0] };
            let levels = nested::coarse_levels_from(opts.elements, nested::MIN_COARSE_OPEN);
            let (x, results) = match setup.nested(&levels, contour, tension_in, (from, to), &data, &mut report) {
                Some(solved) => solved,
                None => {
                    report.nested_meshes.clear();
                    let stick = setup.stick(tension_in, &mut report)?;
                    setup.path(stick, from, to, &w, &mut report)?
                }
            };
            (State { rho, asm: setup.assembler(), x, results }, sp_to)
        }
        OpenMode::PulleySpeed { pulley_speed, tension_out } => {
            // the pure-stick state of N_in = N_out has ω_stick in its ω-slot; from it, the
            // ω-slot holds 𝓗_in (start 𝓗_out) and ω moves from ω_stick to the given
            let mut stick = setup.stick(tension_out, &mut report)?;
            let nz = asm.len();
            let omega_stick = stick[nz + 1];
            let h_out = flux(tension_out);
            stick[nz + 1] = h_out;
            let mut w_speed = w.clone();
            w_speed[nz + 1] = f_ref;
            let to = setup.ends(f64::NAN, h_out, Some(pulley_speed));
            let (x, results) = setup.path(stick, setup.ends(f64::NAN, h_out, Some(omega_stick)), to, &w_speed, &mut report).map_err(|e| FemError::Prescription { name: "pulley_speed", value: pulley_speed, reason: format!("no steady state found between the pure-stick speed {omega_stick:.9} rad/s and the given ({e}); beyond the friction capacity there is none") })?;
            (State { rho, asm: setup.assembler(), x, results }, setup.sp(to))
        }
        // fitted per evaluation of its root find (§12.7), so no fit after it
        OpenMode::Transition { stick_slip_angle, given, tension, driving } => setup.transition(stick_slip_angle, given, tension, driving, estimate[if given == End::In { 1 } else { 0 }], fit.as_ref(), &mut report)?,
    };
    report.continuation_seconds = clock.elapsed().as_secs_f64();
    // the loop's fitting (§12.5)
    if let Some(fit) = fit.as_ref().filter(|_| !matches!(mode, OpenMode::Transition { .. })) {
        let sp_at = move |_: f64| sp;
        state = setup.fit(state, &sp_at, matches!(mode, OpenMode::PulleySpeed { .. }).then_some(f_ref), fit, &mut report)?;
    }
    report.fitting_seconds = clock.elapsed().as_secs_f64() - report.continuation_seconds;
    // the augmented Lagrangian around the converged penalty state (§12.5); the penalty
    // result, with a stated warning, where it fails
    if drive_settings.normal_contact == NormalContact::AugmentedLagrangian {
        let slot_weight = matches!(mode, OpenMode::PulleySpeed { .. }).then_some(f_ref);
        let penalty_state = (state.asm.mesh().clone(), state.x.clone(), state.results.clone());
        let mut al = AugmentedReport::default();
        match setup.augmented(state, sp, slot_weight, fit.as_ref(), drive_settings, &mut al, &mut report) {
            Ok(s) => state = s,
            Err(failure) => {
                report.warnings.push(format!("the augmented Lagrangian of the normal contact did not converge ({failure}): the result is the penalty solve's (P = {} N/m²)", numerics::Sig(penalty)));
                let (mesh, x, results) = penalty_state;
                state = State { rho, asm: Assembler::with_kernel(mesh, kernel.clone()), x, results };
            }
        }
        report.contact = Some(al);
    }
    let (nz, x) = (state.asm.len(), &state.x);
    let (h_in, omega) = match sp.ends {
        Ends::Open { pulley_speed: Some(w), .. } => (x[nz + 1], w),
        Ends::Open { flux_in, .. } => (flux_in, x[nz + 1]),
        Ends::Loop => unreachable!("open ends"),
    };
    let Ends::Open { flux_out: h_out, .. } = sp.ends else { unreachable!("open ends") };
    let tensions = [end_tension(h_in, b1, chi, estimate[0]), end_tension(h_out, b1, chi, estimate[1])];
    open_finish::<N, P, E, dyn LayoutElement<N>>(problem, opts, settings, drive_settings, &state.asm.kernel().clone(), &state, OpenRun { ends, tensions, fluxes: [h_in, h_out], omega, params, sp, penalty, kappa, mu, report, clock })
}

/// The fixed parts of the open steady problem on one mesh, and its solves.
struct OpenSetup<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    asm: &'a Assembler<N, K>,
    points: &'a [FrictionPoint],
    params: TermParams,
    /// Everything but the ends.
    base: SteadyParams,
    w: &'a [f64],
    scales: &'a [f64],
    tolerance: f64,
    max_iterations: usize,
    kernel: &'a Arc<K>,
    transport_rate: f64,
    axial_stiffness: f64,
    chi: f64,
    /// ρ of the transport inertia (kg/m), if any.
    rho: Option<f64>,
    /// D (m) and F_ref (N) of the variable weights and row scales.
    end_distance: f64,
    f_ref: f64,
    _sizes: std::marker::PhantomData<([f64; P], [f64; E])>,
}

impl<const N: usize, const P: usize, const E: usize> OpenSetup<'_, N, P, E, dyn LayoutElement<N>> {
    /// The augmented-Lagrangian outer loop (docs/fem-cosserat.md §12.5) from the
    /// converged penalty `state` at `sp`: the Uzawa update λ ← ⟨λ − Pγ⟩₊ at the contact
    /// rule's points (the first from λ = 0: the penalty pressure), the element rebuilt
    /// with the multipliers as a field over σ, a Newton solve on the mesh and, with `fit`,
    /// the fit to A, B, C (its refits read the field on their meshes); converged when the
    /// largest multiplier change is ≤ `contact_tolerance` × F_ref/R. The failure
    /// otherwise (the caller keeps the penalty state).
    #[allow(clippy::too_many_arguments)]
    fn augmented(&self, mut state: State<N, dyn LayoutElement<N>>, sp: SteadyParams, slot_weight: Option<f64>, fit: Option<&OpenFit<'_>>, drive_settings: &super::super::DriveSettings, al: &mut AugmentedReport, report: &mut SteadyReport) -> Result<State<N, dyn LayoutElement<N>>, AugmentedFailure> {
        let penalty = self.base.penalty;
        al.tolerance = drive_settings.contact_tolerance * self.f_ref / self.base.radius;
        let sp_at = move |_: f64| sp;
        for k in 0..=drive_settings.max_al_iterations {
            let current = state.asm.kernel().contact_multipliers().cloned().unwrap_or_default();
            let (next, max_gap) = multiplier_update(&state.asm, &state.x, &self.params, penalty, None);
            al.iterations = k;
            al.multiplier_change = next.max_change(&current);
            al.max_gap = max_gap;
            if k > 0 && al.multiplier_change <= al.tolerance {
                al.converged = true;
                return Ok(state);
            }
            if k == drive_settings.max_al_iterations {
                break;
            }
            let Some(kernel) = state.asm.kernel().with_contact_multipliers(Some(Arc::new(next))) else {
                return Err(AugmentedFailure::Unsupported);
            };
            let data = SteadyFitData { kernel: &kernel, ..self.fit_data(&sp_at, slot_weight, fit.and_then(|f| f.grading)) };
            state = match resolve::<N, P, E>(&state, kernel.clone(), &data, report) {
                Ok(s) => s,
                Err(e) => return Err(AugmentedFailure::Solve(e.to_string())),
            };
            if let Some(fit) = fit {
                let grading = fit.grading;
                let data = SteadyFitData { kernel: &kernel, ..self.fit_data(&sp_at, slot_weight, grading) };
                state = match super::fit_steady::<N, P, E, dyn LayoutElement<N>>(state, data, fit.settings, fit.drive_settings, fit.element, report) {
                    Ok(s) => s,
                    Err(e) => return Err(AugmentedFailure::Solve(e.to_string())),
                };
            }
        }
        Err(AugmentedFailure::NotConverged { change: al.multiplier_change, tolerance: al.tolerance, iterations: al.iterations })
    }
}

/// A solved state of mode `stick_slip_angle`'s root find: the free tension N_f, X and the
/// point results on the setup's mesh (the continuation's), and the state fitted from it
/// (with the fit on).
type Solved<const N: usize, K> = (f64, Vec<f64>, Vec<PointResult>, Option<State<N, K>>);

/// What the fit to A, B, C (§12.5) needs besides the state: the settings, the grading
/// over the shear layer and the arc element of the uniform mesh.
struct OpenFit<'s> {
    settings: &'s crate::options::SolverSettings,
    drive_settings: &'s super::super::DriveSettings,
    grading: Option<crate::mesh::Grading>,
    element: f64,
}

/// Ends `a` + η(`b` − `a`) (fluxes and the given ω; `a`, `b` of one mode).
fn blend(a: Ends, b: Ends, eta: f64) -> Ends {
    match (a, b) {
        (Ends::Open { transport_rate, flux_in: ia, flux_out: oa, pulley_speed: wa }, Ends::Open { flux_in: ib, flux_out: ob, pulley_speed: wb, .. }) => Ends::Open {
            transport_rate,
            flux_in: ia + eta * (ib - ia),
            flux_out: oa + eta * (ob - oa),
            pulley_speed: wa.zip(wb).map(|(wa, wb)| wa + eta * (wb - wa)),
        },
        _ => b,
    }
}

impl<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized + 'static> OpenSetup<'a, N, P, E, K> {
    fn ends(&self, flux_in: f64, flux_out: f64, pulley_speed: Option<f64>) -> Ends {
        Ends::Open { transport_rate: self.transport_rate, flux_in, flux_out, pulley_speed }
    }

    fn sp(&self, ends: Ends) -> SteadyParams {
        SteadyParams { ends, ..self.base }
    }

    /// An assembler of this setup's mesh.
    fn assembler(&self) -> Assembler<N, K> {
        Assembler::with_kernel(self.asm.mesh().clone(), self.kernel.clone())
    }

    /// The fitting's data at the parameters `sp_at` (ω-slot weight `slot_weight`, grading
    /// `grading`).
    fn fit_data<'f>(&'f self, sp_at: &'f dyn Fn(f64) -> SteadyParams, slot_weight: Option<f64>, grading: Option<crate::mesh::Grading>) -> SteadyFitData<'f, K> {
        SteadyFitData {
            params: self.params,
            length: 0.0,
            kernel: self.kernel,
            sp_at,
            strain_rule: self.kernel.rules().strain,
            h: self.end_distance,
            r: self.base.radius,
            omega1: self.base.omega1,
            f_ref: self.f_ref,
            slot_weight,
            direction: Direction::Clockwise,
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            grading,
        }
    }

    /// The loop's fitting (`fit_steady`, §12.5) of the converged `state` at `sp_at`.
    fn fit(&self, state: State<N, K>, sp_at: &dyn Fn(f64) -> SteadyParams, slot_weight: Option<f64>, fit: &OpenFit<'_>, report: &mut SteadyReport) -> Result<State<N, K>, FemError> {
        super::fit_steady::<N, P, E, K>(state, self.fit_data(sp_at, slot_weight, fit.grading), fit.settings, fit.drive_settings, fit.element, report)
    }

    fn problem(&self, ends: Ends) -> SteadyProblem<'a, N, P, E, K> {
        SteadyProblem { asm: self.asm, params: self.params, length: 0.0, points: self.points, sp: self.sp(ends), strain_rule: self.kernel.rules().strain }
    }

    /// The pure-stick state N_out = N_in = `tension` (no friction load), mode `tensions`:
    /// from the tight start, far from equilibrium in the stiff normal penalty where the
    /// belt lifts off the arc's ends over the bending layer — a penalty ladder P/10⁴ → P.
    fn stick(&self, tension: f64, report: &mut SteadyReport) -> Result<Vec<f64>, FemError> {
        let lambda = 1.0 + tension / self.axial_stiffness;
        let h = end_flux(tension, self.axial_stiffness, self.chi);
        let mut x = straight_start(self.asm, lambda, tension / (self.base.radius * self.base.penalty));
        x.extend([self.transport_rate, self.transport_rate * lambda / self.base.radius]);
        x.extend(std::iter::repeat_n(0.0, self.points.len()));
        let start = self.problem(self.ends(h, h, None));
        let n0 = penalty_ladder(&start, &mut x, self.w, self.scales, self.tolerance, self.max_iterations, &[1e-4, 1e-3, 1e-2, 1e-1, 1.0])
            .map_err(|e| FemError::StartFailed { start: format!("pure stick at N_in = N_out = {} N", Sig(tension)), cause: e.to_string(), hard: self.layers(tension) })?;
        report.newton_iterations += n0.iterations;
        Ok(x)
    }

    /// The scene's layers at the tension `tension` (N) against R, in words: the bending
    /// layer √(a/T̃) and, for a shear-deformable belt, the shear layer √(a/(b₂ − ρc²)) —
    /// what makes a start hard (a shear layer of many R: b₂ close to ρc²).
    fn layers(&self, tension: f64) -> String {
        let r = self.base.radius;
        let a = self.params.bending_stiffness.unwrap_or(0.0);
        let effective = tension - self.chi * (1.0 + tension / self.axial_stiffness);
        let mut text = format!("bending layer √(a/T̃) = {} R (T̃ = {} N)", Sig((a / effective).sqrt() / r), Sig(effective));
        if let Some(b2) = self.kernel.shear_stiffness() {
            text += &format!(
                ", shear layer √(a/(b₂ − ρc²)) = {} R (b₂ − ρc² = {} N: the closer b₂ is to ρc², the softer the belt in shear)",
                Sig((a / (b2 - self.chi)).sqrt() / r),
                Sig(b2 - self.chi)
            );
        }
        text
    }

    /// The loop's load continuation from the state `x` converged at `from` to `to`
    /// (variable weights `w`). The critical speed is checked on the given ends (the loop's
    /// check reads its mid-spans): no inertia check on the path.
    fn path(&self, x: Vec<f64>, from: Ends, to: Ends, w: &[f64], report: &mut SteadyReport) -> Result<(Vec<f64>, Vec<PointResult>), FemError> {
        let at = |eta: f64| self.sp(blend(from, to, eta));
        let mut path = LoadPath::new(self.problem(from), &at, (w, self.scales), (self.tolerance, self.max_iterations), self.kernel, None, x, report);
        path.run()?;
        Ok((path.x, path.results))
    }

    /// Mode `tensions` by the nested start (nested.rs): the pure stick state and the
    /// continuation from `ends.0` to `ends.1` on the open mesh of the first of `levels`,
    /// then one Newton solve at `ends.1` on each finer one and last on this setup's
    /// mesh, each from the state of the mesh before it. `None` if a step fails (the
    /// caller then continues on this mesh itself; the work done is counted in `report`).
    fn nested(&self, levels: &[usize], contour: Contour, tension_in: f64, ends: (Ends, Ends), data: &nested::NestedData<'_, '_, K>, report: &mut SteadyReport) -> Option<(Vec<f64>, Vec<PointResult>)> {
        let (&coarsest, finer) = levels.split_first()?;
        let base = data.base;
        let open_asm = |n: usize| Mesh::open(contour, n, data.arc_weight).ok().map(|mesh| Assembler::with_kernel(mesh, self.kernel.clone()));
        let asm = open_asm(coarsest)?;
        let points = friction_points(&asm, &[], Direction::Clockwise);
        let w = variable_weights(&asm, base.h, base.r, base.omega1.abs(), base.f_ref, points.len());
        let scales = row_scales(&asm, base.f_ref, points.len());
        let coarse = OpenSetup { asm: &asm, points: &points, w: &w, scales: &scales, ..*self };
        let stick = coarse.stick(tension_in, report).ok()?;
        let (mut x, mut results) = coarse.path(stick, ends.0, ends.1, &w, report).ok()?;
        report.nested_meshes.push(coarsest);
        let mut prev = asm;
        for &n in finer {
            let asm = open_asm(n)?;
            let points = friction_points(&asm, &[], Direction::Clockwise);
            (x, results) = nested::rung::<N, P, E, K>(&prev, &x, &results, &asm, &points, data, report).ok()??;
            prev = asm;
            report.nested_meshes.push(n);
        }
        nested::rung::<N, P, E, K>(&prev, &x, &results, self.asm, self.points, data, report).ok()?
    }

    /// φ_B of a converged state: the polar angle of the located zero of v on the slip
    /// run (as the summary's), the contact end φ_C when nothing slips (slip arc 0).
    fn stick_slip_angle_of(&self, asm: &Assembler<N, K>, x: &[f64], results: &[PointResult]) -> Option<f64> {
        let contour = *asm.mesh().contour();
        let sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &x[..asm.len()], self.params, 0.0, self.kernel.clone());
        let angle = |sigma: f64| contour.polar_angle(Pulley::Driven, sol.position(sigma));
        match results.iter().any(|p| p.slip) {
            true => transition(results, &contour, Pulley::Driven).map(angle),
            false => results.iter().rfind(|p| p.normal > 0.0).map(|p| angle(p.point.sigma)),
        }
    }

    /// Mode `stick_slip_angle` (docs/fem-cosserat.md §12.7): the free tension N_f with
    /// φ_B(N_f) = `phi` (`driving`: the pulley drives the belt, N_in > N_out; else the
    /// belt drives the pulley), the tension of `given` fixed. Each
    /// evaluation is a mode-`tensions` solve continued from the nearest one done; string
    /// steps (∂φ_B/∂N_f ≈ ±1/(μT̃_f), the capstan's) until φ_B − φ brackets a root, then
    /// Brent's method on the bracket to 10⁻¹⁰ relative in N_f. Each evaluation continues on
    /// this setup's mesh; with `fit`, a copy of its state is then fitted to A, B, C and φ_B
    /// is the fitted solve's (smooth in N_f, §12.7). (Continuing on the nearest state's
    /// fitted mesh, whose split node sits at the old B, gave a different fitted state: 64
    /// elements, N_out given, a wrong bracket at N_in = 14.948 N with φ_B 0.012 rad off.)
    #[allow(clippy::too_many_arguments)] // the mode's four data, the start and the fit
    fn transition(&self, phi: f64, given: End, tension: f64, driving: bool, estimate: f64, fit: Option<&OpenFit<'_>>, report: &mut SteadyReport) -> Result<(State<N, K>, SteadyParams), FemError> {
        let (b1, chi) = (self.axial_stiffness, self.chi);
        let h_given = end_flux(tension, b1, chi);
        let ends_of = |free: f64| match given {
            End::In => self.ends(h_given, end_flux(free, b1, chi), None),
            End::Out => self.ends(end_flux(free, b1, chi), h_given, None),
        };
        let stick = self.stick(tension, report)?;
        // solved states by N_f; a new one continues from the nearest
        let solved: std::cell::RefCell<Vec<Solved<N, K>>> = std::cell::RefCell::new(vec![(tension, stick, Vec::new(), None)]);
        let report = std::cell::RefCell::new(report);
        // each evaluation's fit warnings, by its free tension: only the state returned
        // states its own (the search's other evaluations are not the result)
        let notes: std::cell::RefCell<Vec<(f64, Vec<String>)>> = std::cell::RefCell::new(Vec::new());
        let solve = |free: f64| -> Result<f64, FemError> {
            let (from, x) = {
                let s = solved.borrow();
                let (n, x, ..) = s.iter().min_by(|a, b| (a.0 - free).abs().total_cmp(&(b.0 - free).abs())).expect("the stick state");
                (*n, x.clone())
            };
            let (x, results) = self.path(x, ends_of(from), ends_of(free), self.w, &mut report.borrow_mut())?;
            let state = State { rho: self.rho, asm: self.assembler(), x, results };
            let (x, results, fitted) = match fit {
                Some(fit) => {
                    let sp = self.sp(ends_of(free));
                    let (x, results) = (state.x.clone(), state.results.clone());
                    let before = report.borrow().warnings.len();
                    let fitted = self.fit(state, &move |_: f64| sp, None, fit, &mut report.borrow_mut())?;
                    let said = report.borrow_mut().warnings.split_off(before);
                    notes.borrow_mut().push((free, said));
                    (x, results, Some(fitted))
                }
                None => (state.x, state.results, None),
            };
            let on = fitted.as_ref();
            let angle = on.map_or_else(|| self.stick_slip_angle_of(self.asm, &x, &results), |s| self.stick_slip_angle_of(&s.asm, &s.x, &s.results)).ok_or_else(|| FemError::Prescription { name: "stick_slip_angle", value: phi, reason: format!("no contact zone at the free tension {free:.9} N") })?;
            solved.borrow_mut().push((free, x, results, fitted));
            Ok(angle - phi)
        };
        // driving: N_in > N_out, φ_B grows with N_in and falls with N_out; the belt
        // driving the pulley (N_in < N_out): the other way round
        let sense = if (given == End::Out) == driving { 1.0 } else { -1.0 };
        let slope = |n: f64| sense / (self.base.mu * (n - chi * (1.0 + n / b1)));
        let (mut n0, mut g0) = (estimate, solve(estimate)?);
        let mut bracket = None;
        // at the root to the FE's round-off in φ_B (Newton's update tolerance 1e-10 leaves
        // ~1e-11 rad; measured 4e-12 on a state continued to itself)
        let at_root = |g: f64| g.abs() <= 1e-10;
        if at_root(g0) {
            bracket = Some((n0, n0));
        }
        for _ in 0..8 {
            if bracket.is_some() {
                break;
            }
            // the string step overshot by 20 % (so that it brackets the root where the
            // capstan slope is that accurate), kept on the sense's side of the given tension
            let mut n1 = n0 - 1.2 * g0 / slope(n0);
            if (n1 - tension) * sense <= 0.0 {
                n1 = tension + 0.5 * (n0 - tension);
            }
            let g1 = solve(n1)?;
            if at_root(g1) {
                bracket = Some((n1, n1));
            } else if g0 * g1 < 0.0 {
                bracket = Some((n0, n1));
            }
            (n0, g0) = (n1, g1);
        }
        let Some((lo, hi)) = bracket else {
            return Err(FemError::Prescription { name: "stick_slip_angle", value: phi, reason: format!("no free tension brackets φ_B = φ within 8 string steps (last N = {n0:.9} N, φ_B − φ = {g0:.3e} rad)") });
        };
        let root = if lo == hi { lo } else {
            let g = &solve;
            numerics::continuation::locate_fold(g, lo, hi, 1e-10).map_err(|e| match e {
                numerics::continuation::FoldError::Evaluation(e) => e,
                other => FemError::Prescription { name: "stick_slip_angle", value: phi, reason: other.to_string() },
            })?
        };
        // the state at the root (solved, or continued to it)
        let known = solved.borrow().iter().position(|s| s.0 == root);
        let i = match known {
            Some(i) => i,
            None => {
                solve(root)?;
                solved.borrow().len() - 1
            }
        };
        let said = notes.into_inner().into_iter().rev().find(|n| n.0 == root).map(|n| n.1).unwrap_or_default();
        report.borrow_mut().warnings.extend(said);
        let (_, x, results, fitted) = solved.into_inner().swap_remove(i);
        let state = fitted.unwrap_or_else(|| State { rho: self.rho, asm: self.assembler(), x, results });
        Ok((state, self.sp(ends_of(root))))
    }
}

/// z of the tight start: the contour at uniform stretch λ, s = σ/λ, ψ = 0, ν = 0 on the
/// spans and −δ on the arc (the penalty's penetration under the hoop pressure, so that the
/// start is in contact and the stick rows carry ω).
fn straight_start<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, lambda: f64, delta: f64) -> Vec<f64> {
    let mut z = vec![0.0; asm.len()];
    let mesh = asm.mesh();
    let (a, b) = mesh.contour().region_bounds(Region::DrivenArc);
    for k in 0..mesh.node_count() {
        let nd = asm.dofs().node_unknowns(k);
        let sigma = mesh.node_sigmas()[k];
        if let Some(s) = nd.values[0] {
            z[s] = sigma / lambda;
        }
        if let Some(nu) = nd.values[1].filter(|_| (a..=b).contains(&sigma)) {
            z[nu] = -delta;
        }
        z[nd.slopes_in[0]] = 1.0 / lambda;
        z[nd.slopes_out[0]] = 1.0 / lambda;
    }
    z
}

/// What [`open_finish`] needs besides the state.
struct OpenRun {
    ends: OpenEnds,
    /// N_in, N_out, N (given or solved: 𝓗 of (C18) inverted).
    tensions: [f64; 2],
    /// 𝓗_in, 𝓗_out of the solved state, N.
    fluxes: [f64; 2],
    /// ω, rad/s (solved or given).
    omega: f64,
    params: TermParams,
    sp: SteadyParams,
    penalty: f64,
    kappa: f64,
    mu: f64,
    report: SteadyReport,
    clock: std::time::Instant,
}

/// Summary, balances and the view of a converged open state (docs/fem-cosserat.md §12.4).
fn open_finish<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized + 'static>(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::super::DriveSettings, kernel: &Arc<K>, state: &State<N, K>, run: OpenRun) -> Result<crate::FemRun, FemError> {
    let asm = &state.asm;
    let nz = asm.len();
    let mesh = asm.mesh();
    let contour = *mesh.contour();
    let r = contour.radius();
    let (c, omega) = (state.x[nz], run.omega);
    let base = FemSolution::new(mesh.clone(), asm.dofs(), &state.x[..nz], run.params, 0.0, kernel.clone());
    let pulley = Pulley::Driven;
    let torque = r * state.results.iter().filter(|p| p.point.pulley == pulley).map(|p| p.point.weight * p.traction).sum::<f64>();
    let angle = |sigma: f64| contour.polar_angle(pulley, base.position(sigma));
    let zone = base.zone(pulley);
    let contact = state.results.iter().filter(|p| p.normal > 0.0);
    let (start, end) = match zone {
        Some(z) => (z.angle_start, z.angle_end),
        None => {
            let first = contact.clone().next().map_or(0.0, |p| angle(p.point.sigma));
            (first, contact.clone().next_back().map_or(0.0, |p| angle(p.point.sigma)))
        }
    };
    let arc = (start - end).rem_euclid(2.0 * PI);
    let any_slip = state.results.iter().any(|p| p.slip);
    let located = transition(&state.results, &contour, pulley);
    // the stick and slip runs of the contact points in the order of travel (+σ): Paper C's
    // topology is one stick run followed by one slip run (or either alone)
    let mut pts: Vec<&PointResult> = state.results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
    pts.sort_by(|a, b| (a.point.sigma, a.point.part.offset()).partial_cmp(&(b.point.sigma, b.point.part.offset())).unwrap_or(std::cmp::Ordering::Equal));
    let mut runs: Vec<(bool, f64, f64)> = Vec::new();
    for p in &pts {
        match runs.last_mut() {
            Some(run) if run.0 == p.slip => run.2 = p.point.sigma,
            _ => runs.push((p.slip, p.point.sigma, p.point.sigma)),
        }
    }
    let paper_c = runs.len() <= 1 || (runs.len() == 2 && !runs[0].0);
    let mut topology_note = None;
    let slip = if !any_slip {
        0.0
    } else if paper_c {
        located.map_or(arc, |s| (angle(s) - end).rem_euclid(2.0 * PI).min(arc))
    } else {
        // another topology (a slip run at the entry, several stick runs): the slip arc is
        // the total of the slip runs, each bounded midway between its outer points and the
        // neighbouring runs' (the trailing stick→slip point where it is located), the
        // first and last by the contact zone's edges
        let (s0, s1) = zone.map_or((runs[0].1, runs[runs.len() - 1].2), |z| (z.sigma_start, z.sigma_end));
        let n = runs.len();
        let bound = |i: usize| -> f64 {
            // the boundary between run i − 1 and run i (0 < i < n)
            if i == n - 1 && runs[i].0 {
                located.unwrap_or(0.5 * (runs[i - 1].2 + runs[i].1))
            } else {
                0.5 * (runs[i - 1].2 + runs[i].1)
            }
        };
        let extent = |i: usize| -> (f64, f64) { (if i == 0 { s0 } else { bound(i) }, if i + 1 == n { s1 } else { bound(i + 1) }) };
        let sweep = |(from, to): (f64, f64)| if to > from { (angle(from) - angle(to)).rem_euclid(2.0 * PI) } else { 0.0 };
        let described: Vec<String> = (0..n).map(|i| format!("{} {:.3}° → {:.3}°", if runs[i].0 { "slip" } else { "stick" }, angle(extent(i).0).to_degrees(), angle(extent(i).1).to_degrees())).collect();
        let total: f64 = (0..n).filter(|&i| runs[i].0).map(|i| sweep(extent(i))).sum();
        topology_note = Some(format!(
            "the contact zone is not Paper C's stick → slip but {} runs in the order of travel: {}; `pulley.slip_arc` is the total of the slip runs ({:.3}°) and `pulley.stick_arc` the rest, each run bounded midway between neighbouring friction points (± half an element). The BVP models one stick and one slip zone only: it is no reference for this scene",
            n,
            described.join(", "),
            total.min(arc).to_degrees()
        ));
        total.min(arc)
    };
    // spec §2.6: the stick → slip point of Paper C's topology, the stick zone's stretch
    // at its middle (entry → transition, the whole zone in pure stick)
    let transition_inside = paper_c && slip > 0.0 && slip < arc;
    let stick_middle = match (zone, located) {
        (Some(z), Some(t)) if transition_inside => Some(0.5 * (z.sigma_start + t)),
        (Some(z), _) if !any_slip => Some(0.5 * (z.sigma_start + z.sigma_end)),
        _ => None,
    };
    let cosserat = kernel.theory() == drive::scene::Theory::Cosserat;
    let end_sigma = mesh.end_sigma();
    let mut summary = Summary {
        transport_rate: Some(c),
        pulley_speed: Some(omega),
        tension_in: Some(base.recovered_axial_force(0.0)),
        tension_out: Some(base.recovered_axial_force(end_sigma)),
        y_in: Some(base.position(0.0)[1]),
        y_out: Some(base.position(end_sigma)[1]),
        pulley: Some(PulleySummary {
            contact_arc: Some(arc),
            contact_start: Some(start),
            contact_end: Some(end),
            stick_arc: Some(arc - slip),
            slip_arc: Some(slip),
            torque: Some(torque),
            edge_pressure_start: zone.and_then(|z| base.edge_pressure(pulley, z.sigma_start, 1.0)),
            edge_pressure_end: zone.and_then(|z| base.edge_pressure(pulley, z.sigma_end, -1.0)),
            stick_slip_angle: transition_inside.then(|| located.map(angle)).flatten(),
            stretch_stick: stick_middle.map(|s| base.stretch(s)),
            ..PulleySummary::default()
        }),
        ..Summary::default()
    };
    if let (true, Some(z), Some(ps)) = (cosserat, zone, summary.pulley.as_mut()) {
        base.cosserat_zone(z.sigma_start, z.sigma_end).fill(ps);
    }
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let points: Vec<FrictionPoint> = state.results.iter().map(|p| p.point).collect();
    let prob = SteadyProblem::<N, P, E, K> { asm, params: run.params, length: 0.0, points: &points, sp: run.sp, strain_rule: kernel.rules().strain };
    // power (§12.4): −torque·ω = c(𝓗_in − 𝓗_out) + D to round-off by (C21)
    let dissipation = prob.dissipation(&state.x);
    if let Some(ps) = summary.pulley.as_mut() {
        ps.dissipation = Some(dissipation).filter(|d| d.is_finite());
    }
    let [flux_in, flux_out] = run.fluxes;
    let power_in = -torque * omega;
    let power_ends = c * (flux_in - flux_out);
    let per_element = view_points(state, run.params, 0.0, kernel);
    let view = OpenView { inner: super::super::DriveSolution::new(base, &per_element, summary.clone()), open: OpenContour::new(r, run.ends.end_distance).map_err(|e| FemError::Unsupported(e.to_string()))?, shift: 0.5 * run.ends.end_distance, summary: summary.clone() };
    let mut terms = kernel.term_labels(&TermParams { penalty: None, ..run.params });
    terms.push(format!("Coulomb contact, direct steady state of the open one-pulley layout (semismooth Newton, μ = {}, P_γ = {:.6e} N/m², friction on the nodes)", run.mu, run.penalty));
    if kernel.contact_multipliers().is_some() {
        terms.push("normal contact by the augmented Lagrangian (Table 1; multipliers a field over σ, Uzawa updates, docs/fem-cosserat.md §12.5)".into());
    }
    terms.push(format!("open ends: c = {c} m/s, N_in = {}, N_out = {} N (end fluxes (C18))", run.tensions[0], run.tensions[1]));
    if problem.effects.inertia {
        terms.push(format!("transport inertia (ρ = {} kg/m)", problem.belt.mass_per_length));
    }
    let report = run.report;
    let options = opts.record(Some(run.penalty), settings, serde_json::json!({
        "drive": {
            "solver": "steady-open",
            "settings": drive_settings,
            "kappa": run.kappa,
            "steady": true,
            "report": report,
            "power_in": power_in,
            "power_ends": power_ends,
            "dissipation": dissipation,
            "max_penetration": view.inner_max_penetration(),
        },
    }));
    let stats = crate::FemStats { wall_seconds: run.clock.elapsed().as_secs_f64(), newton_iterations: report.newton_iterations, unknowns: state.x.len(), elements: opts.elements, homotopy_steps: report.continuation_steps };
    // the stated warnings (the augmented Lagrangian's fallback to the penalty, §12.5; an
    // edge pressure of a contact zone that could not be read is said, not left out silently)
    let mut notes = report.warnings;
    notes.extend(topology_note);
    // a slip zone shorter than a few arc elements is not resolved (the loop's rule); one
    // that no friction point catches at all, while the tensions differ, is said too: its
    // `slip_arc` 0 is the mesh's (N_in = 15, N_out = 14.999 N: the creep estimate is
    // 2.2e-4 rad against arc elements of ≈ 1e-2 rad at 128)
    let arc_count = mesh.elements().iter().filter(|e| e.region == Region::DrivenArc).count().max(1);
    let element = PI * r / arc_count as f64;
    notes.extend(super::output::slip_resolution_warning("pulley", slip * r, element, opts.elements, run.params.bending_stiffness));
    let [n_in, n_out] = [run.tensions[0], run.tensions[1]];
    let creep = (n_in / n_out).ln().abs() / run.mu;
    if slip == 0.0 && creep > 0.0 && creep.is_finite() {
        notes.push(format!(
            "unresolved slip zone on the pulley: no friction point slips although N_in = {n_in} N ≠ N_out = {n_out} N (torque {} N·m); the string's creep estimate of the slip arc, |ln(N_in/N_out)|/μ = {} rad, is {:.2} arc elements of {} rad, so `pulley.slip_arc` = 0 and `pulley.stick_arc` are the mesh's, not the belt's",
            Sig(torque),
            Sig(creep),
            creep * r / element,
            Sig(element / r)
        ));
    }
    if let (Some(_), Some(p)) = (zone, &summary.pulley) {
        for (edge, value) in [("start", p.edge_pressure_start), ("end", p.edge_pressure_end)] {
            if value.is_none() {
                notes.push(format!("the contact pressure at the zone's {edge} edge could not be read (fewer than three nodes inside the zone, or no positive pressure from the contact forces next to the edge): `pulley.edge_pressure_{edge}` is absent"));
            }
        }
    }
    Ok(crate::FemRun { view: Box::new(view), summary, stats, options, terms, history: None, notes, unfitted: None })
}

/// The loop-frame solution seen on the open contour (docs/fem-cosserat.md §12.1): x
/// shifted by −D/2, σ unchanged.
struct OpenView<const N: usize, K: LayoutElement<N> + ?Sized> {
    inner: super::super::DriveSolution<N, K>,
    open: OpenContour,
    shift: f64,
    summary: Summary,
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> OpenView<N, K> {
    fn inner_max_penetration(&self) -> f64 {
        self.inner.string().max_penetration()
    }
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> SolutionView for OpenView<N, K> {
    fn path(&self) -> Path {
        Path::Open(self.open)
    }
    fn position(&self, sigma: f64) -> [f64; 2] {
        let p = self.inner.position(sigma);
        [p[0] - self.shift, p[1]]
    }
    fn axial_force(&self, sigma: f64) -> f64 {
        self.inner.axial_force(sigma)
    }
    fn bending_moment(&self, sigma: f64) -> Option<f64> {
        self.inner.bending_moment(sigma)
    }
    fn transverse_force(&self, sigma: f64) -> Option<f64> {
        self.inner.transverse_force(sigma)
    }
    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        self.inner.contact_pressure(sigma)
    }
    fn friction_traction(&self, sigma: f64) -> Option<f64> {
        self.inner.friction_traction(sigma)
    }
    fn contact_state(&self, sigma: f64) -> ContactState {
        self.inner.contact_state(sigma)
    }
    fn rotation(&self, sigma: f64) -> Option<f64> {
        self.inner.rotation(sigma)
    }
    fn shear_strain(&self, sigma: f64) -> Option<f64> {
        self.inner.shear_strain(sigma)
    }
    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.inner.material_coordinate(sigma)
    }
    fn deflection(&self, sigma: f64) -> f64 {
        self.inner.deflection(sigma)
    }
    fn summary(&self) -> Summary {
        self.summary.clone()
    }
}
