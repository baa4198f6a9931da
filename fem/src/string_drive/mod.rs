//! The friction drive (`string-drive`, Paper B) by MEL finite elements: the string of
//! [`crate::static_homotopy`] transported in σ through a quasistatic transient — a
//! sequence of energy minima with prescribed driver rotation increments ω₁Δt (§7.1) —
//! with the driven pulley's rotation as an unknown under its load, Coulomb friction by
//! the augmented Lagrangian return mapping of Table 1 (§6.1) or its penalty
//! regularisation, and persistent transport inertia on request — analysis `transient`
//! ([`solve`]) runs it to the steady state. Analysis `steady` is solved directly
//! ([`steady::solve`]: the stationary equations with the transport rate and the driven
//! speed as unknowns, semismooth Newton on the stick/slip complementarity, load
//! continuation and contact fitting; docs/fem-drive.md §12). Equations, signs and
//! measured numbers: docs/fem-drive.md.
//!
//! Layers: [`contact`] (per-point state, D2, D6, D7, D8, exact derivatives),
//! [`system`] (the step's global system and its Newton solver), [`steady`] (the direct
//! steady solve), this module (the common start from the typed
//! [`crate::FemProblem`], time loop with the AL outer loop, steady-state criterion,
//! outputs), [`view`] (the common view with stick/slip states).

use std::f64::consts::PI;
use std::sync::Arc;
use std::time::Instant;

use drive::contour::{Contour, Direction, Pulley, Region};
use drive::result::History;
use drive::scene::{Analysis, Scene};
use drive::summary::PulleySummary;
use drive::view::SolutionView;

use crate::assembly::Assembler;
use crate::error::FemError;
use crate::formulation::layout::LayoutElement;
use crate::formulation::Kernel;
use crate::kinematics::{TermParams, NDOF};
use crate::linear::BorderedLu;
use crate::mesh::Mesh;
use crate::options::{FemOptions, SolverSettings};
use crate::problem::{ContactLaw, FemProblem};
use crate::solution::FemSolution;
use crate::static_homotopy::HomotopyReport;
use crate::{FemRun, FemStats};

pub mod contact;
pub mod steady;
pub mod system;
pub mod view;

use contact::{PointState, StepParams, NEXT};
use system::{Load, Pattern, StepSystem};
pub use view::{DriveSolution, ViewPoint};

/// Friction treatment (docs/fem-drive.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionMethod {
    /// Augmented Lagrangian of Table 1 (multipliers λ_γ, λ_⊥ updated per step).
    AugmentedLagrangian,
    /// Penalty regularisation (λ_γ = λ_⊥ = 0; only the slip bound is iterated).
    Penalty,
}

/// Settings of the drive transient. `Default` gives the documented values; the scene's
/// `fem.time_step`, `fem.max_steps`, `fem.steady_tolerance` override them
/// ([`DriveSettings::from_scene`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DriveSettings {
    /// Δt, s (> 0); `None` = the driver surface moves by one arc element per step.
    pub time_step: Option<f64>,
    /// Largest number of time steps. Default 4000; ≥ 1.
    pub max_steps: usize,
    /// Steady when the change rate r_n (§7) ≤ this for 3 consecutive steps. Default
    /// 1e-6 per radian of driver rotation; (0, 1).
    pub steady_tolerance: f64,
    /// `steady`: stop at the steady state (error if not reached); `transient`: also
    /// stop there, but report the last state if `max_steps` is reached first.
    pub stop_at_steady: bool,
    /// Friction treatment. Default augmented Lagrangian.
    pub friction: FrictionMethod,
    /// AL outer loop converged when the largest multiplier change is ≤ this × F_ref/R.
    /// Default 1e-7 (the floor is set by Newton's update tolerance times P_γ); (0, 1e-2].
    pub al_tolerance: f64,
    /// Outer (AL) iterations per step. Default 30; ≥ 1.
    pub max_al_iterations: usize,
    /// κ_⊥ of the tangential penalty P_⊥ = κ_⊥ EA/R² (N/m²). Default 300; > 0. Much
    /// softer than P_γ on purpose: the slip bound b = μτ_γ and P_⊥ set the width b/P_⊥
    /// of the stick band of (D7); a band far below the per-step slip makes the
    /// stick/slip state of the points flip from one Newton iteration to the next. The
    /// augmented Lagrangian removes the penalty error of P_⊥ (§5).
    pub tangential_penalty_factor: f64,
    /// Newton iteration limit per solve. Default 40; ≥ 5.
    pub max_newton_iterations: usize,
    /// Largest number of contact-fitting passes of the direct steady solve — refit
    /// attempts, a rejected (retried) one included; `FitRules::max_passes` of
    /// [`crate::fitting`] (docs/fem-drive.md §12; the moves per pass are limited to
    /// 0.3 h, so it needs more passes than the static fit's [`SolverSettings::max_fits`]).
    /// Default 30; ≥ 1. The only control of those passes (the static fit's `max_fits`
    /// does not apply).
    pub max_fits: usize,
    /// How the direct steady solve finds the stick and slip zones after its load
    /// continuation (the scene's `fem.steady_scheme`): the semismooth fit
    /// (docs/fem-drive.md §12), Paper D's fixed topology (spec §3.5), or by the belt
    /// (default: Paper D's on the string with the semismooth fit as fallback, the
    /// semismooth fit on the Cosserat rod; [`steady::SteadyScheme`]). Not read by the
    /// transient.
    pub steady_scheme: steady::SteadyScheme,
    /// The normal contact of the direct steady solve of a one-pulley scene (the scene's
    /// `fem.contact`, docs/fem-cosserat.md §12.5): the penalty (default) or the
    /// augmented Lagrangian, whose outer loop takes `al_tolerance` and
    /// `max_al_iterations`. Not read by the transient or the loop.
    pub normal_contact: steady::NormalContact,
    /// The augmented Lagrangian of `normal_contact` has converged when the largest
    /// multiplier change is ≤ this × F_ref/R (its iteration limit is
    /// `max_al_iterations`). Default 1e-3; (0, 1e-2]. Looser than the transient's
    /// `al_tolerance`: each update is followed by the fit, whose refits read the field on
    /// moved meshes, and the change then stalls at 0.06–0.13 N/m = (4–9)·10⁻⁴ F_ref/R on
    /// `cosserat-pulley` (measured) — a gap of ≤ 1.5·10⁻¹² m at P = 1e11 N/m², which moves
    /// a contact edge (γ ≈ p₀x²/(2b₂) beside it) by ≤ 5·10⁻⁸ m (docs/fem-cosserat.md §12.5).
    pub contact_tolerance: f64,
}

impl Default for DriveSettings {
    fn default() -> Self {
        DriveSettings {
            time_step: None,
            max_steps: 4000,
            steady_tolerance: 1e-6,
            stop_at_steady: true,
            friction: FrictionMethod::AugmentedLagrangian,
            al_tolerance: 1e-7,
            max_al_iterations: 30,
            tangential_penalty_factor: 300.0,
            max_newton_iterations: 40,
            max_fits: 30,
            steady_scheme: steady::SteadyScheme::Auto,
            normal_contact: steady::NormalContact::Penalty,
            contact_tolerance: 1e-3,
        }
    }
}

impl DriveSettings {
    /// Defaults with the scene's `fem` block applied.
    pub fn from_scene(scene: &Scene) -> DriveSettings {
        let f = scene.fem_settings();
        let d = DriveSettings::default();
        DriveSettings {
            time_step: f.time_step,
            max_steps: f.max_steps.unwrap_or(d.max_steps),
            steady_tolerance: f.steady_tolerance.unwrap_or(d.steady_tolerance),
            steady_scheme: f.steady_scheme.unwrap_or_default(),
            normal_contact: f.contact.unwrap_or_default(),
            ..d
        }
    }

    /// Checks the documented ranges.
    ///
    /// # Errors
    /// [`FemError::InvalidOption`] naming the field.
    pub fn validate(&self) -> Result<(), FemError> {
        let bad = |field: &'static str, value: String, reason: &str| Err(FemError::InvalidOption { field, value, reason: reason.into() });
        if let Some(dt) = self.time_step {
            if !(dt.is_finite() && dt > 0.0) {
                return bad("time_step", dt.to_string(), "must be positive and finite (s)");
            }
        }
        if self.max_steps == 0 {
            return bad("max_steps", "0".into(), "must be ≥ 1");
        }
        if !(self.steady_tolerance > 0.0 && self.steady_tolerance < 1.0) {
            return bad("steady_tolerance", self.steady_tolerance.to_string(), "must lie in (0, 1)");
        }
        if !(self.al_tolerance > 0.0 && self.al_tolerance <= 1e-2) {
            return bad("al_tolerance", self.al_tolerance.to_string(), "must lie in (0, 1e-2]");
        }
        if !(self.contact_tolerance > 0.0 && self.contact_tolerance <= 1e-2) {
            return bad("contact_tolerance", self.contact_tolerance.to_string(), "must lie in (0, 1e-2]");
        }
        if self.max_al_iterations == 0 {
            return bad("max_al_iterations", "0".into(), "must be ≥ 1");
        }
        if !(self.tangential_penalty_factor.is_finite() && self.tangential_penalty_factor > 0.0) {
            return bad("tangential_penalty_factor", self.tangential_penalty_factor.to_string(), "must be positive and finite");
        }
        if self.max_fits == 0 {
            return bad("max_fits", "0".into(), "must be ≥ 1");
        }
        if self.max_newton_iterations < 5 {
            return bad("max_newton_iterations", self.max_newton_iterations.to_string(), "must be ≥ 5");
        }
        Ok(())
    }
}

/// True if the scene is a friction drive of a string (analysis steady or transient,
/// Coulomb contact) — the scenes [`solve`] handles.
pub fn applies(scene: &Scene) -> bool {
    FemProblem::from_scene(scene).is_string_drive()
}

/// Per-step record (the history plus solver work).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
struct StepRecord {
    al_iterations: usize,
    newton_iterations: usize,
    al_converged: bool,
}

/// Outputs of the pulleys from the point states (docs/fem-drive.md §8).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct PulleyOut {
    torque: f64,
    /// σ of the stick→slip transition (unwrapped like the zone), if both exist.
    slip_start: Option<f64>,
    all_slip: bool,
    no_slip: bool,
    /// A leading run of slip points followed by stick: (points, Σ w (−τ_⊥) over it, N).
    entry_slip: Option<(usize, f64)>,
}

/// Solve a friction-drive scene (see [`applies`]).
///
/// # Errors
/// [`FemError::Unsupported`] (ω₁ = 0), [`FemError::InvalidOption`], the static start's
/// errors, [`FemError::FrictionCapacityExceeded`], [`FemError::DriveStepFailed`],
/// [`FemError::SteadyStateNotReached`], [`FemError::NonFinite`].
pub fn solve(problem: &FemProblem, opts: &FemOptions, settings: &SolverSettings, drive_settings: &DriveSettings, kernel: Arc<dyn Kernel>) -> Result<FemRun, FemError> {
    solve_layout::<NDOF, NEXT, dyn Kernel>(problem, opts, settings, drive_settings, kernel)
}

/// [`solve`] for an element of any 1-D layout with N unknowns (X = N + 2:
/// [`contact::extended_size`]): the string's formulations (N = 8, [`solve`]) or an
/// element of another field set (the Cosserat rod's {s, ν, θ}, N = 12). The analysis
/// reads the element only through [`LayoutElement`]: its energy by the [`Assembler`],
/// its axial force, rules and term labels; the contact, friction and transport-inertia
/// terms, the point states, the upstream references and the outputs act on the
/// element's centreline {s, ν} ([`crate::kinematics::ElementContext::centreline`]).
///
/// # Errors
/// As [`solve`].
pub fn solve_layout<const N: usize, const X: usize, K: LayoutElement<N> + ?Sized + 'static>(problem: &FemProblem, opts: &FemOptions, settings: &SolverSettings, drive_settings: &DriveSettings, kernel: Arc<K>) -> Result<FemRun, FemError> {
    let clock = Instant::now();
    let DriveStart { mu, omega1, start, report, penalty, t_static, f_ref } = drive_start(problem, opts, settings, drive_settings, kernel.clone(), settings.arc_weight)?;
    // the belt runs along σ (ω₁ > 0) or against it (ω₁ < 0; docs/fem-drive.md §13): the
    // signed quantities (drum advance Rω₁Δt, the upstream reference σ − d_ref, a, φ)
    // carry the sense themselves; the step, the rate (D9) and the capacity take |ω₁|,
    // the stick/slip order on a pulley and the arcs follow the travel
    let direction = Direction::of_speed(omega1);
    let speed = omega1.abs();
    let b = &problem.belt;
    let r = problem.geometry.radius;
    let contour = *start.mesh().contour();
    let mut newton_total = report.newton_iterations;
    let h = contour.centre_distance();
    let load_torque = problem.drive.driven_torque;
    let damping = problem.drive.driven_damping;

    let asm = Assembler::with_kernel(start.mesh().clone(), kernel.clone());
    let layout = kernel.layout();
    let mut z = crate::static_homotopy::transfer(&start, &asm);
    // the belt's bending stiffness as the static start has it (none for the string)
    let params = TermParams { axial_stiffness: b.axial_stiffness, weight: problem.weight(), penalty: None, bending_stiffness: start.params().bending_stiffness };
    let length = b.length;
    let strain_rule = kernel.rules().strain;
    let contact_rule = kernel.rules().contact;

    // 2. time step, point states
    let arc_elements = asm.mesh().elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1);
    let dt = drive_settings.time_step.unwrap_or(PI * r / arc_elements as f64 / (r * speed));
    let dt_first = dt;
    // P_⊥ = κ_⊥ EA/R², capped at P_γ (a tangential penalty above the normal one makes
    // the tangent singular at soft normal penalties)
    let p_t = (drive_settings.tangential_penalty_factor * b.axial_stiffness / (r * r)).min(penalty);
    let al = drive_settings.friction == FrictionMethod::AugmentedLagrangian;
    let mut points: Vec<Vec<PointState>> = (0..asm.mesh().len())
        .map(|e| {
            let el = asm.context(e, &params);
            let q = el.centreline(layout, &asm.dofs().gather(e, &z, length));
            // the contact rule's points for the normal term and the element edges
            // ξ = ±1 (trapezoidal weights) for friction: the mixed rule of §7.3
            contact::mixed_rule(contact_rule)
                .into_iter()
                .map(|(xi, w, wf)| {
                    let sigma = el.sigma(xi);
                    let pulley = contact::reachable_pulley(&contour, el.geometry.region, sigma);
                    let p = el.fields(&q, xi);
                    let tau = match (pulley, el.gap(&p)) {
                        (Some(_), Some(g)) => (-penalty * g).max(0.0),
                        _ => 0.0,
                    };
                    PointState {
                        xi,
                        weight: w * el.jacobian(),
                        friction_weight: wf * el.jacobian(),
                        sigma,
                        pulley,
                        travel_ref: r * omega1 * dt_first,
                        s_ref: p.s,
                        slope_ref: p.ds,
                        metric: el.tangent_length(&p),
                        lambda_n: if al { tau } else { 0.0 },
                        lambda_t: 0.0,
                        bound: mu * tau,
                        slip: false,
                        normal: tau,
                        tangential: 0.0,
                        displacement: 0.0,
                    }
                })
                .collect()
        })
        .collect();

    set_references(&mut points, &asm, &z, &params, length, &contour);
    let pattern = Pattern::new::<N, X, K>(&asm);
    let mut lu = BorderedLu::new(&pattern.rows, &pattern.cols, asm.len() + 2, [asm.len(), asm.len() + 1])
        .map_err(|detail| FemError::SingularTangent { eta: 1.0, iteration: 0, detail })?;
    let w_newton = system::weights(&asm, h, r, 1.0);
    let w_steady = system::weights(&asm, h, r, f_ref / b.axial_stiffness);

    // starting guesses: belt speed = driver surface speed at the mean stretch
    let lambda0 = 1.0 + t_static / b.axial_stiffness;
    let mut a_prev = r * omega1 * dt / lambda0;
    let mut phi_prev = omega1 * dt;
    let mut c_prev = a_prev / dt;
    let mut omega2_prev = omega1;
    let mut history = History::default();
    let mut records: Vec<StepRecord> = Vec::new();
    let mut quiet = 0usize;
    let mut last_rate = f64::INFINITY;
    let mut steady = false;
    let mut time = 0.0;
    let mut x: Vec<f64> = z.iter().copied().chain([a_prev, phi_prev]).collect();
    let mut outs = [PulleyOut::default(); 2];
    let mut z_old = z.clone();

    for step in 1..=drive_settings.max_steps {
        time = step as f64 * dt;
        let step_params = StepParams {
            penalty,
            tangential_penalty: p_t,
            driver_advance: r * omega1 * dt,
            radius: r,
            inertia: problem.effects.inertia.then_some(b.mass_per_length * c_prev * c_prev),
        };
        // critical speed (docs/fem-drive.md §6): the effective tension N − ρc²λ of both
        // spans (at their midpoints, with c of the last step) must stay positive
        if let Some(rc2) = step_params.inertia {
            for (span, sigma) in [("upper", 0.5 * h), ("lower", 1.5 * h + PI * r)] {
                let (n, stretch, _) = state_at(&asm, &z, &params, length, sigma);
                if n - rc2 * stretch <= 0.0 {
                    return Err(FemError::SpeedAtOrAboveCritical { span: span.into(), tension: n, inertia_force: rc2 * stretch, time: Some(time) });
                }
            }
        }
        let load = Load { torque: load_torque, damping, time_step: dt };
        // predictor: the material keeps its motion of the last step (secant in time),
        // x = 2 z_n − z_{n−1}; in a steady state this is z_n itself
        let nz = z.len();
        for i in 0..nz {
            x[i] = 2.0 * z[i] - z_old[i];
        }
        if asm.energy(&x[..nz], &params, length).is_none() {
            x[..nz].copy_from_slice(&z);
        }
        x[nz] = a_prev;
        x[nz + 1] = phi_prev;
        let mut rec = StepRecord::default();
        for _ in 0..drive_settings.max_al_iterations {
            // capacity with the frozen bounds (docs/fem-drive.md §5)
            // (either sense: the load drives when M₂ + d₂ω₂ opposes ω₁)
            let demand = load_torque + damping * omega2_prev;
            for pulley in [Pulley::Driven, Pulley::Driver] {
                let cap = r * points.iter().flatten().filter(|p| p.pulley == Some(pulley)).map(|p| p.friction_weight * p.bound).sum::<f64>();
                if demand.abs() > cap {
                    return Err(FemError::FrictionCapacityExceeded { pulley: pulley.name().to_string(), torque: demand, capacity: cap, time: Some(time) });
                }
            }
            let sys = StepSystem::<N, X, K> { asm: &asm, params, length, points: &points, step: step_params, load, strain_rule };
            let mut res = system::newton(&sys, &pattern, &mut lu, &mut x, &w_newton, settings.update_tolerance, drive_settings.max_newton_iterations, f_ref * h);
            if res.is_err() {
                // retry once from the last state itself (no secant predictor)
                x[..nz].copy_from_slice(&z);
                x[nz] = a_prev;
                x[nz + 1] = phi_prev;
                res = system::newton(&sys, &pattern, &mut lu, &mut x, &w_newton, settings.update_tolerance, drive_settings.max_newton_iterations, f_ref * h);
            }
            let nres = match res {
                Ok(n) => n,
                Err(reason) => {
                    // a pulley in full slip cannot hold the load: report it as such
                    for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
                        if outs[k].all_slip {
                            let cap = r * points.iter().flatten().filter(|p| p.pulley == Some(pulley)).map(|p| p.friction_weight * p.bound).sum::<f64>();
                            return Err(FemError::FrictionCapacityExceeded { pulley: pulley.name().to_string(), torque: demand, capacity: cap, time: Some(time) });
                        }
                    }
                    return Err(FemError::DriveStepFailed { step, time, reason });
                }
            };
            rec.newton_iterations += nres.iterations;
            rec.al_iterations += 1;
            // Table 1: evaluate and update every point
            let (a, phi) = (x[nz], x[nz + 1]);
            let mut change: f64 = 0.0;
            let mut switches = 0usize;
            let terms = contact::DriveTerms::new(&step_params);
            for (e, pts) in points.iter_mut().enumerate() {
                let el = asm.context(e, &params);
                let q = el.centreline(layout, &asm.dofs().gather(e, &x[..nz], length));
                for pt in pts.iter_mut() {
                    if pt.pulley.is_none() {
                        continue;
                    }
                    let ev = terms.evaluate(&el, &q, a, phi, pt);
                    let (c, switched) = contact::commit(pt, &ev, mu, al);
                    change = change.max(c);
                    switches += usize::from(switched);
                }
            }
            if change <= drive_settings.al_tolerance * f_ref / r && switches == 0 {
                rec.al_converged = true;
                break;
            }
        }
        newton_total += rec.newton_iterations;
        let (a, phi) = (x[nz], x[nz + 1]);
        let omega2 = phi / dt;
        let c = a / dt;
        // steady-state rate (§7)
        let dz: Vec<f64> = x[..nz].iter().zip(&z).map(|(n, o)| n - o).collect();
        let rate = (system::scaled_norm(&dz, &w_steady[..nz]).max((omega2 - omega2_prev).abs() / speed).max((c - c_prev).abs() / c.abs().max(1e-300))) / (speed * dt);
        z_old.copy_from_slice(&z);
        z.copy_from_slice(&x[..nz]);
        // the new state becomes the previous one of the points (S̃_n)
        for (e, pts) in points.iter_mut().enumerate() {
            let el = asm.context(e, &params);
            let q = el.centreline(layout, &asm.dofs().gather(e, &z, length));
            for pt in pts.iter_mut() {
                // the travel of this step becomes the reference of the next (D2)
                if pt.pulley.is_some() && pt.bound > 0.0 {
                    pt.travel_ref = (pt.displacement + drum_advance(pt, r * omega1 * dt, phi * r)) / pt.metric;
                }
                pt.metric = el.tangent_length(&el.fields(&q, pt.xi));
            }
        }
        set_references(&mut points, &asm, &z, &params, length, &contour);
        outs = [pulley_out(&points, Pulley::Driver, r, &contour, direction), pulley_out(&points, Pulley::Driven, r, &contour, direction)];
        record(&mut history, time, omega2, c, &asm, &z, &params, length, &contour, &points, &outs, rate, direction);
        records.push(rec);
        a_prev = a;
        phi_prev = phi;
        c_prev = c;
        omega2_prev = omega2;
        last_rate = rate;
        quiet = if rate <= drive_settings.steady_tolerance && rec.al_converged { quiet + 1 } else { 0 };
        if quiet >= 3 {
            steady = true;
            if drive_settings.stop_at_steady {
                break;
            }
        }
    }
    if !steady && matches!(problem.analysis, Analysis::Steady) {
        return Err(FemError::SteadyStateNotReached { steps: history.len(), time, rate: last_rate, tolerance: drive_settings.steady_tolerance });
    }
    // a steady state must stick at entry (docs/fem-drive.md §11): a leading slip run
    // whose friction force exceeds 20 % of the force the pulley transmits, (M₂ + d₂ω₂)/R,
    // shifts the stick-zone tension by more than 20 % of the tension difference that sets
    // the slip arcs — an error; smaller ones are reported in options.drive
    let transmitted = (load_torque + damping * phi_prev / dt).abs() / r;
    let entry_slip_force = outs.iter().filter_map(|o| o.entry_slip).fold(0.0f64, |m, (_, f)| m.max(f.abs()));
    if steady {
        for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
            if let Some((n, force)) = outs[k].entry_slip {
                if force.abs() > 0.2 * transmitted + 1e-9 * f_ref {
                    return Err(FemError::EntrySlip { pulley: pulley.name().to_string(), entry_slip_points: n, entry_force: force, transmitted, time });
                }
            }
        }
    }

    // 3. outputs of the last state
    let sol_params = TermParams { penalty: Some(penalty), ..params };
    let base = FemSolution::new(asm.mesh().clone(), asm.dofs(), &z, sol_params, length, kernel.clone());
    let omega2 = phi_prev / dt;
    let c = a_prev / dt;
    let mut summary = base.summary();
    let (tu, tl) = (summary.tension_upper_mid.unwrap_or(0.0), summary.tension_lower_mid.unwrap_or(0.0));
    summary.tension_tight = Some(stick_zone_force(&base, Pulley::Driver, outs[0].slip_start, direction).unwrap_or(tu.max(tl)));
    summary.tension_slack = Some(stick_zone_force(&base, Pulley::Driven, outs[1].slip_start, direction).unwrap_or(tu.min(tl)));
    summary.driven_speed = Some(omega2);
    summary.transport_rate = Some(c);
    for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
        let block = if k == 0 { &mut summary.driver } else { &mut summary.driven };
        let ps = block.get_or_insert_with(PulleySummary::default);
        let (arc, slip) = arcs(&base, &points, pulley, &contour, &outs[k], direction);
        ps.contact_arc = ps.contact_arc.or(Some(arc));
        ps.slip_arc = Some(slip);
        ps.stick_arc = Some((ps.contact_arc.unwrap_or(arc) - slip).max(0.0));
        ps.torque = Some(outs[k].torque);
    }
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let dissipation: f64 = points.iter().flatten().map(|p| p.friction_weight * p.tangential * p.displacement).sum::<f64>() / dt;
    let power_in = -outs[0].torque * omega1;
    let power_out = (load_torque + damping * omega2) * omega2;
    let max_penetration = base.max_penetration();
    let stick_slip_max = points.iter().flatten().filter(|p| p.bound > 0.0 && !p.slip).fold(0.0f64, |m, p| m.max(p.displacement.abs()));
    let view_points: Vec<Vec<ViewPoint>> = points.iter().map(|pts| pts.iter().map(ViewPoint::from).collect()).collect();
    let view = DriveSolution::new(base, &view_points, summary.clone());
    let mut terms = kernel.term_labels(&params);
    terms.push(format!(
        "Coulomb contact, {} (μ = {mu}, P_γ = {penalty:.6e} N/m², P_⊥ = {p_t:.6e} N/m², {contact_rule})",
        match drive_settings.friction {
            FrictionMethod::AugmentedLagrangian => "augmented Lagrangian (Table 1)",
            FrictionMethod::Penalty => "penalty regularisation",
        }
    ));
    terms.push(format!("driven load M₂ = {load_torque} N·m, d₂ = {damping} N·m·s"));
    if problem.effects.inertia {
        terms.push(format!("transport inertia (ρ = {} kg/m)", b.mass_per_length));
    }
    let options = opts.record(Some(penalty), settings, serde_json::json!({
        "drive": {
            "settings": drive_settings,
            "time_step": dt,
            "steps": history.len(),
            "steady": steady,
            "final_change_rate": last_rate,
            "al_iterations": records.iter().map(|r| r.al_iterations).sum::<usize>(),
            "al_unconverged_steps": records.iter().filter(|r| !r.al_converged).count(),
            "power_in": power_in,
            "power_out": power_out,
            "dissipation": dissipation,
            "max_penetration": max_penetration,
            "stick_slip_max": stick_slip_max,
            "entry_slip_force": entry_slip_force,
            "tangential_penalty": p_t,
        },
        "homotopy": report,
    }));
    let stats = FemStats {
        wall_seconds: clock.elapsed().as_secs_f64(),
        newton_iterations: newton_total,
        unknowns: asm.len() + 2,
        elements: opts.elements,
        homotopy_steps: report.steps,
    };
    Ok(FemRun { view: Box::new(view), summary, stats, options, terms, history: Some(history), notes: Vec::new(), unfitted: None })
}

/// What both drive solvers start from (docs/fem-drive.md §3): the checked inputs μ, ω₁,
/// the static frictionless solution of the scene's string with its gravity and length
/// (homotopy of fem-string.md §9, fitted to its contact boundaries, at the final penalty
/// P), and the force scale F_ref = max(T_static, M₂/R, ρgL) of the norms.
struct DriveStart<const N: usize = NDOF, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    mu: f64,
    omega1: f64,
    start: FemSolution<N, K>,
    report: HomotopyReport,
    penalty: f64,
    /// The larger |mid-span axial force| of the static start, N.
    t_static: f64,
    f_ref: f64,
}

/// The common start of [`solve`] and [`steady::solve`], on a mesh of `opts.elements`
/// with the arcs weighted by `arc_weight` ([`Mesh::new`]).
///
/// # Errors
/// [`FemError::InvalidOption`] (drive settings), [`FemError::Unsupported`] (no Coulomb
/// contact, ω₁ = 0), the static start's errors.
fn drive_start<const N: usize, K: LayoutElement<N> + ?Sized>(problem: &FemProblem, opts: &FemOptions, settings: &SolverSettings, drive_settings: &DriveSettings, kernel: Arc<K>, arc_weight: f64) -> Result<DriveStart<N, K>, FemError> {
    drive_settings.validate()?;
    let ContactLaw::Coulomb { mu } = problem.effects.contact else {
        return Err(FemError::Unsupported("the FE drive needs Coulomb contact".into()));
    };
    let omega1 = problem.drive.driver_speed;
    if !omega1.is_finite() || omega1 == 0.0 {
        return Err(FemError::Unsupported(format!(
            "driver_speed ω₁ = {omega1} rad/s: the FE drive needs a turning driver (ω₁ ≠ 0; its steady-state norms scale with ω₁R)"
        )));
    }
    let b = &problem.belt;
    let r = problem.geometry.radius;
    let penalty = problem.penalty(opts, settings);
    let data = problem.hanging(penalty);
    let contour = data.contour()?;
    let mesh = Mesh::new(contour, opts.elements, arc_weight)?;
    // the start keeps the untied element distribution (tie 0): Paper D's fitted mesh
    // ties its span end pieces within 2e-6 elements, so its result depends on the start's
    // boundaries by nm (docs/fem-string.md §5)
    let (start, report, _) = data.solve_with_tie(mesh, kernel, settings, 0.0)?;
    let s0 = start.summary();
    let t_static = s0.tension_upper_mid.unwrap_or(0.0).abs().max(s0.tension_lower_mid.unwrap_or(0.0).abs());
    let weight = problem.weight().unwrap_or(0.0);
    let f_ref = t_static.max(problem.drive.driven_torque.abs() / r).max(weight * b.length).max(1e-300);
    Ok(DriveStart { mu, omega1, start, report, penalty, t_static, f_ref })
}

/// `tension_tight` / `tension_slack` (docs/fem-drive.md §8): the axial force of the
/// driver's / driven pulley's stick zone — creep theory's T_t, T_s, as the BVP reports
/// them (docs/string-drive.md) — midway between the contact entry and the stick→slip
/// transition `transition` (σ; the whole zone without one); `None` without a recovered
/// zone or with the transition outside it.
fn stick_zone_force<const N: usize, K: LayoutElement<N> + ?Sized>(base: &FemSolution<N, K>, pulley: Pulley, transition: Option<f64>, direction: Direction) -> Option<f64> {
    stick_zone_middle(base, pulley, transition, direction).map(|sigma| base.axial_force(sigma))
}

/// σ (wrapped) of the middle of the stick zone of [`stick_zone_force`], where it and
/// `stretch_stick` are read; `None` as there.
fn stick_zone_middle<const N: usize, K: LayoutElement<N> + ?Sized>(base: &FemSolution<N, K>, pulley: Pulley, transition: Option<f64>, direction: Direction) -> Option<f64> {
    let contour = base.mesh().contour();
    let zone = base.zone(pulley)?;
    let span = zone.sigma_end - zone.sigma_start;
    if direction == Direction::CounterClockwise {
        // the belt runs on at the zone's end along σ: stick from the transition to there
        let stick = transition.map_or(span, |t| (zone.sigma_end - t).rem_euclid(contour.length()));
        return (stick > 0.0 && stick <= span).then(|| contour.wrap(zone.sigma_end - 0.5 * stick));
    }
    let stick = transition.map_or(span, |t| (t - zone.sigma_start).rem_euclid(contour.length()));
    (stick > 0.0 && stick <= span).then(|| contour.wrap(zone.sigma_start + 0.5 * stick))
}

/// R Δθ_k of the pulley of a point: `driver` for the driver, `driven` for the driven one.
fn drum_advance(pt: &PointState, driver: f64, driven: f64) -> f64 {
    match pt.pulley {
        Some(Pulley::Driver) => driver,
        Some(Pulley::Driven) => driven,
        None => 0.0,
    }
}

/// The upstream references of (D2) from the state z_n: S̃_n and ∂σS̃_n at σ − d_ref
/// (unwrapped across σ = 0 with the closure S(σ + L_c) = S(σ) + L, F5).
fn set_references<const N: usize, K: LayoutElement<N> + ?Sized>(points: &mut [Vec<PointState>], asm: &Assembler<N, K>, z: &[f64], params: &TermParams, length: f64, contour: &Contour) {
    let lc = contour.length();
    for pt in points.iter_mut().flatten() {
        if pt.pulley.is_none() {
            continue;
        }
        let at = pt.sigma - pt.travel_ref;
        let loops = (at / lc).floor();
        let (e, xi) = asm.mesh().locate(at - loops * lc);
        let el = asm.context(e, params);
        let q = el.centreline(asm.kernel().layout(), &asm.dofs().gather(e, z, length));
        let f = el.fields(&q, xi);
        pt.s_ref = f.s + loops * length;
        pt.slope_ref = f.ds;
    }
}

/// σ unwrapped for a pulley's contact zone: the driver's zone straddles σ = 0 (it ends
/// on the upper span), so its σ < H/2 are moved up by L_c.
fn unwrap(contour: &Contour, pulley: Pulley, sigma: f64) -> f64 {
    if pulley == Pulley::Driver && sigma < 0.5 * contour.centre_distance() {
        sigma + contour.length()
    } else {
        sigma
    }
}

/// Torque and stick→slip transition of a pulley from its points (docs/fem-drive.md §8,
/// §13): the points in the order of the belt's travel — along σ clockwise, against it
/// counter-clockwise — so the belt runs onto the pulley at the first one.
fn pulley_out(points: &[Vec<PointState>], pulley: Pulley, radius: f64, contour: &Contour, direction: Direction) -> PulleyOut {
    let mut pts: Vec<&PointState> = points.iter().flatten().filter(|p| p.pulley == Some(pulley)).collect();
    let torque = radius * pts.iter().map(|p| p.friction_weight * p.tangential).sum::<f64>();
    pts.retain(|p| p.friction_weight > 0.0);
    pts.retain(|p| p.normal > 0.0);
    pts.sort_by(|a, b| unwrap(contour, pulley, a.sigma).total_cmp(&unwrap(contour, pulley, b.sigma)));
    if direction == Direction::CounterClockwise {
        pts.reverse();
    }
    let all_slip = !pts.is_empty() && pts.iter().all(|p| p.slip);
    let no_slip = pts.iter().all(|p| !p.slip);
    // the trailing run of slip points in the travel (slip zone before exit)
    let last_stick = pts.iter().rposition(|p| !p.slip);
    let slip_start = match last_stick {
        Some(i) if i + 1 < pts.len() => Some(0.5 * (unwrap(contour, pulley, pts[i].sigma) + unwrap(contour, pulley, pts[i + 1].sigma))),
        _ => None,
    };
    // the leading run of slip points, if stick follows (not a belt-creep pattern)
    let first_stick = pts.iter().position(|p| !p.slip);
    let entry_slip = match first_stick {
        Some(i) if i > 0 => Some((i, -pts[..i].iter().map(|p| p.friction_weight * p.tangential).sum::<f64>())),
        _ => None,
    };
    PulleyOut { torque, slip_start, all_slip, no_slip, entry_slip }
}

/// The slip arc of a pulley, rad (docs/fem-drive.md §8, §13): none without slip, the
/// contact arc `arc` in full slip, else from the stick→slip transition (σ, polar angle by
/// `angle`) to where the belt leaves the contact — its σ-end (polar angle `end`)
/// clockwise, its σ-start (`start`) counter-clockwise — at most `arc`.
fn slip_arc(out: &PulleyOut, arc: f64, [start, end]: [f64; 2], angle: impl Fn(f64) -> f64, direction: Direction) -> f64 {
    if out.no_slip {
        return 0.0;
    }
    if out.all_slip {
        return arc;
    }
    out.slip_start.map_or(0.0, |s| {
        let from = match direction {
            Direction::Clockwise => angle(s) - end,
            Direction::CounterClockwise => start - angle(s),
        };
        from.rem_euclid(2.0 * PI).min(arc)
    })
}

/// Contact arc (point-based fallback) and slip arc of a pulley, rad.
fn arcs<const N: usize, K: LayoutElement<N> + ?Sized>(base: &FemSolution<N, K>, points: &[Vec<PointState>], pulley: Pulley, contour: &Contour, out: &PulleyOut, direction: Direction) -> (f64, f64) {
    let mut pts: Vec<f64> = points.iter().flatten().filter(|p| p.pulley == Some(pulley) && p.normal > 0.0).map(|p| unwrap(contour, pulley, p.sigma)).collect();
    pts.sort_by(f64::total_cmp);
    let angle = |sigma: f64| contour.polar_angle(pulley, base.position(contour.wrap(sigma)));
    let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
        return (0.0, 0.0);
    };
    let end_angle = base.zone(pulley).filter(|z| z.recovered).map_or(angle(last), |z| z.angle_end);
    let start_angle = base.zone(pulley).filter(|z| z.recovered).map_or(angle(first), |z| z.angle_start);
    let arc = (start_angle - end_angle).rem_euclid(2.0 * PI);
    (arc, slip_arc(out, arc, [start_angle, end_angle], angle, direction))
}

/// Axial force (the element's, [`LayoutElement::axial_force_at`]), stretch of the
/// centreline and position of the state z at σ.
fn state_at<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, z: &[f64], params: &TermParams, length: f64, sigma: f64) -> (f64, f64, [f64; 2]) {
    let (e, xi) = asm.mesh().locate(asm.mesh().contour().wrap(sigma));
    let el = asm.context(e, params);
    let q = asm.dofs().gather(e, z, length);
    let p = el.fields(&el.centreline(asm.kernel().layout(), &q), xi);
    (asm.kernel().axial_force_at(&el, &q, xi), el.stretch(&p), el.position(&p))
}

/// Append one step to the history: raw axial force EA(λ − 1) at the span midpoints,
/// per pulley the torque and the stick/slip arcs from the point states (contact
/// boundaries at the first/last point carrying normal traction, O(h)).
#[allow(clippy::too_many_arguments)]
fn record<const N: usize, K: LayoutElement<N> + ?Sized>(history: &mut History, time: f64, omega2: f64, c: f64, asm: &Assembler<N, K>, z: &[f64], params: &TermParams, length: f64, contour: &Contour, points: &[Vec<PointState>], outs: &[PulleyOut; 2], rate: f64, direction: Direction) {
    let h = contour.centre_distance();
    let at = |sigma: f64| {
        let (n, _, position) = state_at(asm, z, params, length, sigma);
        (n, position)
    };
    history.time.push(time);
    history.driven_speed.push(omega2);
    history.transport_rate.push(c);
    history.tension_upper_mid.push(at(0.5 * h).0);
    history.tension_lower_mid.push(at(1.5 * h + PI * contour.radius()).0);
    for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
        let mut pts: Vec<f64> = points.iter().flatten().filter(|p| p.pulley == Some(pulley) && p.normal > 0.0).map(|p| unwrap(contour, pulley, p.sigma)).collect();
        pts.sort_by(f64::total_cmp);
        let angle = |sigma: f64| contour.polar_angle(pulley, at(sigma).1);
        let (contact, slip) = match (pts.first(), pts.last()) {
            (Some(&a), Some(&b)) => {
                let arc = (angle(a) - angle(b)).rem_euclid(2.0 * PI);
                (arc, slip_arc(&outs[k], arc, [angle(a), angle(b)], angle, direction))
            }
            _ => (0.0, 0.0),
        };
        let (stick_v, slip_v, torque_v) = if k == 0 {
            (&mut history.driver_stick_arc, &mut history.driver_slip_arc, &mut history.driver_torque)
        } else {
            (&mut history.driven_stick_arc, &mut history.driven_slip_arc, &mut history.driven_torque)
        };
        stick_v.push((contact - slip).max(0.0));
        slip_v.push(slip);
        torque_v.push(outs[k].torque);
    }
    history.change_rate.push(if rate.is_finite() { rate } else { f64::MAX });
}
