//! The direct steady solve of the open one-pulley layout (Paper C; docs/fem-cosserat.md
//! §12): the loop's steady equations on an open mesh ([`Mesh::open`], the loop's contour
//! of H = D without its second arc), with [`Ends::Open`] closing them — c given, ω the
//! unknown of the global material balance (C21), the end fluxes 𝓗 of (C18) — and a
//! continuation in the outflow tension from N_out = N_in (pure stick, no friction load)
//! to the scene's N_out. Mode `tensions` only.

use drive::contour::OpenContour;
use drive::summary::{PulleySummary, Summary};
use drive::contour::Path;
use drive::view::ContactState;

use super::*;

/// The open ends of a one-pulley scene as the FE reads them (mode `tensions`).
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
}

/// 𝓗 of (C18) on a straight end section with axial force N (Q = M = 0): N(1 + Γ₁/2) −
/// ½χλ², Γ₁ = N/b₁, λ = 1 + Γ₁, χ = ρc² (N).
pub fn end_flux(tension: f64, axial_stiffness: f64, chi: f64) -> f64 {
    let g1 = tension / axial_stiffness;
    tension * (1.0 + 0.5 * g1) - 0.5 * chi * (1.0 + g1) * (1.0 + g1)
}

/// Solve the one-pulley scene `problem` (its [`crate::problem::FemProblem::open`]) with
/// the element `kernel` of layout N (docs/fem-cosserat.md §12).
///
/// # Errors
/// [`FemError::Unsupported`] (not a one-pulley scene in mode `tensions`, gravity, no
/// Coulomb contact), [`FemError::InvalidOption`] (D ≤ 2R, element count),
/// [`FemError::SpeedAtOrAboveCritical`] (T̃ ≤ 0 at an end or b₁, b₂ ≤ ρc²),
/// [`FemError::HomotopyStalled`], [`FemError::NonFinite`].
pub fn solve_open<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized + 'static>(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::super::DriveSettings, kernel: Arc<K>) -> Result<crate::FemRun, FemError> {
    let clock = std::time::Instant::now();
    let ends = problem.open.ok_or_else(|| FemError::Unsupported("the open FE solves one-pulley scenes only".into()))?;
    let (Some(tension_in), Some(tension_out)) = (ends.tension_in, ends.tension_out) else {
        return Err(FemError::Unsupported("the one-pulley FE solves mode `tensions` (tension_in and tension_out given) only; modes `pulley_speed` and `transition` are not built (docs/fem-cosserat.md §12.3)".into()));
    };
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
    // the effective tension T̃ = N − χλ at both ends, and b₁, b₂ above χ (spec §1.2)
    for (span, n) in [("inflow", tension_in), ("outflow", tension_out)] {
        let lam = 1.0 + n / b.axial_stiffness;
        let b2 = kernel.shear_stiffness().unwrap_or(f64::INFINITY);
        if n - chi * lam <= 0.0 || b.axial_stiffness <= chi || b2 <= chi {
            return Err(FemError::SpeedAtOrAboveCritical { span: span.into(), tension: n, inertia_force: chi * lam, time: None });
        }
    }
    let mesh = Mesh::open(contour, opts.elements, settings.arc_weight)?;
    let penalty = problem.penalty(opts, settings);
    let params = TermParams { axial_stiffness: b.axial_stiffness, weight: None, penalty: Some(penalty), bending_stiffness: b.bending_stiffness };
    let asm = Assembler::with_kernel(mesh, kernel.clone());
    let lambda_in = 1.0 + tension_in / b.axial_stiffness;
    let omega0 = c0 * lambda_in / r;
    let arc_elements = asm.mesh().elements().iter().filter(|e| e.region == Region::DrivenArc).count().max(1);
    // κ = P_⊥ Δt₀ as the loop's (any κ > 0 has the same roots)
    let kappa = drive_settings.tangential_penalty_factor * b.axial_stiffness / (r * r) * (PI * r / arc_elements as f64) / (r * omega0.abs());
    let (h_in, h_out) = (end_flux(tension_in, b.axial_stiffness, chi), end_flux(tension_out, b.axial_stiffness, chi));
    let sp_at = |eta: f64| SteadyParams {
        mu,
        penalty,
        kappa,
        radius: r,
        omega1: omega0,
        torque: 0.0,
        damping: 0.0,
        inertia: rho,
        // η carries the outflow flux from the inflow's (pure stick) to the scene's
        ends: Ends::Open { transport_rate: c0, flux_in: h_in, flux_out: h_in + eta * (h_out - h_in) },
    };
    let points = friction_points(&asm, &[], Direction::Clockwise);
    let mut x = straight_start(&asm, lambda_in, tension_in / (r * penalty));
    x.extend([c0, omega0]);
    x.extend(std::iter::repeat_n(0.0, points.len()));
    let f_ref = tension_in.max(tension_out);
    let w = variable_weights(&asm, d, r, omega0.abs(), f_ref, points.len());
    let scales = row_scales(&asm, f_ref, points.len());
    let mut report = SteadyReport { friction_points: points.len(), ..Default::default() };
    // η = 0 (N_out = N_in, pure stick) from the tight start: far from equilibrium in
    // the stiff normal penalty where the belt lifts off the arc's ends over the bending
    // layer: a penalty ladder P/10⁴ → P
    let start = SteadyProblem::<N, P, E, K> { asm: &asm, params, length: 0.0, points: &points, sp: sp_at(0.0), strain_rule: kernel.rules().strain };
    let tol = settings.update_tolerance;
    let max_it = drive_settings.max_newton_iterations;
    let n0 = penalty_ladder(&start, &mut x, &w, &scales, tol, max_it, &[1e-4, 1e-3, 1e-2, 1e-1, 1.0]).map_err(|e| FemError::HomotopyStalled { eta: 0.0, step: 0.0, min_step: 0.0, steps: 0, last_failure: format!("the pure-stick start (N_out = N_in): {e}") })?;
    report.newton_iterations += n0.iterations;
    // the critical speed is checked on the ends above (the loop's check reads its
    // mid-spans): no inertia check on the path
    let mut path = LoadPath::new(start, &sp_at, (&w, &scales), (tol, max_it), &kernel, None, x, &mut report);
    path.run()?;
    let (x, results) = (path.x, path.results);
    report.continuation_seconds = clock.elapsed().as_secs_f64();
    let state = State { rho, asm, x, results };
    open_finish::<N, P, E, K>(problem, opts, settings, drive_settings, &kernel, &state, OpenRun { ends, tensions: [tension_in, tension_out], params, sp: sp_at(1.0), penalty, kappa, mu, report, clock })
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
    /// N_in, N_out, N.
    tensions: [f64; 2],
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
    let (c, omega) = (state.x[nz], state.x[nz + 1]);
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
    let slip = if any_slip { transition(&state.results, &contour, pulley).map_or(arc, |s| (angle(s) - end).rem_euclid(2.0 * PI).min(arc)) } else { 0.0 };
    let end_sigma = mesh.end_sigma();
    let summary = Summary {
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
            ..PulleySummary::default()
        }),
        ..Summary::default()
    };
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let points: Vec<FrictionPoint> = state.results.iter().map(|p| p.point).collect();
    let prob = SteadyProblem::<N, P, E, K> { asm, params: run.params, length: 0.0, points: &points, sp: run.sp, strain_rule: kernel.rules().strain };
    // power (§12.4): −torque·ω = c(𝓗_in − 𝓗_out) + D to round-off by (C21)
    let dissipation = prob.dissipation(&state.x);
    let Ends::Open { flux_in, flux_out, .. } = run.sp.ends else { unreachable!("open ends") };
    let power_in = -torque * omega;
    let power_ends = c * (flux_in - flux_out);
    let per_element = view_points(state, run.params, 0.0, kernel);
    let view = OpenView { inner: super::super::DriveSolution::new(base, &per_element, summary.clone()), open: OpenContour::new(r, run.ends.end_distance).map_err(|e| FemError::Unsupported(e.to_string()))?, shift: 0.5 * run.ends.end_distance, summary: summary.clone() };
    let mut terms = kernel.term_labels(&TermParams { penalty: None, ..run.params });
    terms.push(format!("Coulomb contact, direct steady state of the open one-pulley layout (semismooth Newton, μ = {}, P_γ = {:.6e} N/m², friction on the nodes)", run.mu, run.penalty));
    terms.push(format!("open ends: c = {c} m/s, N_in = {}, N_out = {} N (end fluxes (C18))", run.tensions[0], run.tensions[1]));
    if problem.effects.inertia {
        terms.push(format!("transport inertia (ρ = {} kg/m)", problem.belt.mass_per_length));
    }
    let mut report = run.report;
    report.fitting_seconds = 0.0;
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
    Ok(crate::FemRun { view: Box::new(view), summary, stats, options, terms, history: None, notes: Vec::new() })
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
