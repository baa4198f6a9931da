//! Time stepping over a surface mesh (issue 11 item 3; docs/fem-time-stepping.md): steps
//! t_n → t_{n+1} = t_n + Δt, each the minimisation of an incremental energy by Newton
//! ([`numerics::newton`], backtracking with Armijo's test on that energy), with the
//! kernel's history per integration point advected along σ before the step and advanced
//! after it ([`SurfaceHistory`]), and optional inertia on the nodal unknowns.
//!
//! One step, with z the global unknowns, Π(z; t, h) the kernel's energy at time t over
//! the history h, c the kernel's belt speed:
//! 1. h̃ = h_n advected by c(t_n + Δt/2) Δt (semi-Lagrangian, cubic along σ);
//! 2. z_{n+1} = argmin Π(z; t_{n+1}, h̃) + ½ κ (z − ẑ)ᵀ M (z − ẑ) — quasistatic without
//!    the second term; with inertia (mass matrix M from a kernel, [`Inertia`]):
//!    - backward Euler: κ = 1/Δt², ẑ = z_n + Δt v_n; then v_{n+1} = (z_{n+1} − z_n)/Δt;
//!      first order, amplification |A| = 1/√(1 + ω²Δt²) for a mode of frequency ω;
//!    - Newmark, average acceleration (β = ¼, γ = ½): κ = 4/Δt²,
//!      ẑ = z_n + Δt v_n + ¼Δt² a_n; then a_{n+1} = κ(z_{n+1} − ẑ),
//!      v_{n+1} = v_n + ½Δt(a_n + a_{n+1}); second order, |A| = 1, phase
//!      2 atan(ωΔt/2) per step instead of ωΔt;
//! 3. h_{n+1} = advance(z_{n+1}, h̃) at every history point.
//!
//! A failed step is a [`TimeSteppingError`] naming the step, its times and the cause;
//! the state stays at t_n (a caller may retry with a smaller Δt).

use drive::result::{Frame, SurfaceFields, TimeSeries};
use drive::ResultError;
use numerics::linear::SparseLu;
use numerics::newton::{self, Damping, NewtonError, NewtonOptions, NewtonProblem, NewtonStats, TrialStep, Verdict, SUFFICIENT_DECREASE};
use thiserror::Error;

use crate::element::Field;
use crate::surface::assembly::{Evaluation, PointDerivative, SurfaceAssembler, SurfaceKernel};
use crate::surface::history::SurfaceHistory;
use crate::surface::SurfaceError;

/// Why the time stepping failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TimeSteppingError {
    /// The initial unknowns or velocities: wrong length, not finite, or inadmissible.
    #[error("initial {what}: {reason}")]
    InitialState { what: &'static str, reason: String },
    /// A step that is not finite and positive.
    #[error("step {step} at t = {time:.6e} s: Δt = {dt:e} is not finite and > 0")]
    InvalidStep { step: usize, time: f64, dt: f64 },
    /// Newton did not converge in a step.
    #[error("step {step} (t = {time:.6e} s → {end:.6e} s): {cause}")]
    Newton { step: usize, time: f64, end: f64, cause: NewtonError<SurfaceError> },
    /// The mesh, numbering, history or a factorisation.
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    /// A recorded channel or frame is not a valid result.
    #[error("output after step {step}: {cause}")]
    Output { step: usize, cause: ResultError },
}

/// The time integration of the inertia term.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// Backward Euler (first order, dissipative).
    BackwardEuler,
    /// Newmark's average acceleration (trapezoidal; second order, no amplitude error).
    Newmark,
}

/// Inertia on the nodal unknowns: a scheme and a mass matrix in the stiffness
/// kernel's Hessian pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct Inertia {
    scheme: Scheme,
    mass: Vec<f64>,
}

impl Inertia {
    /// The mass matrix M is the Hessian of the mass kernel's energy (a quadratic form,
    /// e.g. ½ρ|v|² over the point values): assembled once at zero, at t = 0.
    ///
    /// # Errors
    /// [`SurfaceError::MassMismatch`] if the two kernels are not numbered alike (same
    /// mesh, fields and constraints), [`SurfaceError::Inadmissible`] if the mass is not
    /// finite.
    pub fn new<K: SurfaceKernel<P>, M: SurfaceKernel<Q>, const P: usize, const Q: usize>(
        scheme: Scheme,
        stiffness: &SurfaceAssembler<K, P>,
        mass: &SurfaceAssembler<M, Q>,
    ) -> Result<Inertia, SurfaceError> {
        if stiffness.mesh() != mass.mesh() || stiffness.dofs() != mass.dofs() {
            return Err(SurfaceError::MassMismatch { detail: format!("{} vs {} unknowns on meshes equal: {}", stiffness.len(), mass.len(), stiffness.mesh() == mass.mesh()) });
        }
        let ev = Evaluation { time: 0.0, dt: 0.0, history: None };
        let m = mass.assemble(&vec![0.0; mass.len()], &ev).ok_or(SurfaceError::Inadmissible { what: "mass matrix" })?;
        Ok(Inertia { scheme, mass: m.values })
    }
}

/// y = M x for matrix values in the pattern (rows, cols).
fn multiply(rows: &[usize], cols: &[usize], values: &[f64], x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    for ((&r, &c), &v) in rows.iter().zip(cols).zip(values) {
        y[r] += v * x[c];
    }
    y
}

/// Velocities and accelerations of the nodal unknowns.
#[derive(Debug, Clone)]
struct Motion {
    inertia: Inertia,
    velocity: Vec<f64>,
    acceleration: Vec<f64>,
}

impl Motion {
    /// κ and ẑ of the step (module documentation).
    fn predictor(&self, z: &[f64], dt: f64) -> (f64, Vec<f64>) {
        match self.inertia.scheme {
            Scheme::BackwardEuler => (1.0 / (dt * dt), z.iter().zip(&self.velocity).map(|(x, v)| x + dt * v).collect()),
            Scheme::Newmark => (
                4.0 / (dt * dt),
                z.iter().zip(&self.velocity).zip(&self.acceleration).map(|((x, v), a)| x + dt * v + 0.25 * dt * dt * a).collect(),
            ),
        }
    }

    /// Velocities and accelerations after the step to `z` from `previous`.
    fn update(&mut self, previous: &[f64], z: &[f64], dt: f64, kappa: f64, predicted: &[f64]) {
        for i in 0..z.len() {
            match self.inertia.scheme {
                Scheme::BackwardEuler => {
                    let v = (z[i] - previous[i]) / dt;
                    self.acceleration[i] = (v - self.velocity[i]) / dt;
                    self.velocity[i] = v;
                }
                Scheme::Newmark => {
                    let a = kappa * (z[i] - predicted[i]);
                    self.velocity[i] += 0.5 * dt * (self.acceleration[i] + a);
                    self.acceleration[i] = a;
                }
            }
        }
    }
}

/// One step's incremental energy as a Newton problem (residual = its gradient).
struct StepProblem<'a, K, const P: usize> {
    asm: &'a SurfaceAssembler<K, P>,
    ev: Evaluation<'a>,
    lu: &'a mut SparseLu<SurfaceError>,
    /// κ, M values, ẑ.
    inertia: Option<(f64, &'a [f64], Vec<f64>)>,
    /// The energy at the last residual's point.
    cache: Option<(Vec<f64>, f64)>,
}

impl<K: SurfaceKernel<P>, const P: usize> StepProblem<'_, K, P> {
    /// ½κ(z − ẑ)ᵀM(z − ẑ) and κM(z − ẑ).
    fn inertial(&self, z: &[f64]) -> Option<(f64, Vec<f64>)> {
        let (kappa, mass, predicted) = self.inertia.as_ref()?;
        let d: Vec<f64> = z.iter().zip(predicted).map(|(a, b)| a - b).collect();
        let (rows, cols) = self.asm.pattern();
        let md = multiply(rows, cols, mass, &d);
        let energy = 0.5 * kappa * d.iter().zip(&md).map(|(a, b)| a * b).sum::<f64>();
        Some((energy, md.into_iter().map(|v| kappa * v).collect()))
    }

    fn energy(&self, z: &[f64]) -> f64 {
        let inertial = self.inertial(z).map_or(0.0, |(e, _)| e);
        self.asm.energy(z, &self.ev).map_or(f64::INFINITY, |e| e + inertial)
    }
}

impl<K: SurfaceKernel<P>, const P: usize> NewtonProblem for StepProblem<'_, K, P> {
    type Error = SurfaceError;

    fn size(&self) -> usize {
        self.asm.len()
    }

    /// ∇Π(z) + κM(z − ẑ); NaN where z is inadmissible (Newton rejects such a trial).
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), SurfaceError> {
        match self.asm.gradient(z, &self.ev) {
            Some((mut energy, g)) => {
                r.copy_from_slice(&g);
                if let Some((e, gi)) = self.inertial(z) {
                    energy += e;
                    r.iter_mut().zip(gi).for_each(|(a, b)| *a += b);
                }
                self.cache = Some((z.to_vec(), energy));
            }
            None => {
                r.fill(f64::NAN);
                self.cache = None;
            }
        }
        Ok(())
    }

    fn factorize(&mut self, z: &[f64]) -> Result<(), SurfaceError> {
        let mut a = self.asm.assemble(z, &self.ev).ok_or(SurfaceError::Inadmissible { what: "Hessian at an accepted iterate" })?;
        if let Some((kappa, mass, _)) = &self.inertia {
            a.values.iter_mut().zip(mass.iter()).for_each(|(k, m)| *k += kappa * m);
        }
        self.lu.factorize(&a.values)
    }

    fn solve(&mut self, b: &mut [f64]) -> Result<(), SurfaceError> {
        self.lu.solve_in_place(b)
    }

    fn damping(&self) -> Damping {
        Damping::Backtracking { take_best: false }
    }

    /// The incremental energy (from the residual pass at the same point when there is one).
    fn merit(&mut self, z: &[f64], _r: &[f64]) -> f64 {
        match &self.cache {
            Some((at, e)) if at.as_slice() == z => *e,
            _ => self.energy(z),
        }
    }

    /// Armijo on the energy: m(z + αΔz) ≤ m(z) + c α ∇mᵀΔz, with a round-off allowance
    /// of 10⁻¹² |m(z)|; a step that is not a descent direction is abandoned.
    fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
        if t.slope >= 0.0 {
            return Verdict::Abandon;
        }
        if t.trial_merit <= t.merit + SUFFICIENT_DECREASE * t.damping * t.slope + 1e-12 * t.merit.abs() {
            Verdict::Accept
        } else {
            Verdict::Reject
        }
    }
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    /// Step number (1-based).
    pub step: usize,
    /// t_{n+1}, s.
    pub time: f64,
    /// The incremental energy at the converged state, J.
    pub energy: f64,
    /// Newton's work.
    pub newton: NewtonStats,
}

/// A channel: a name (a lowercase identifier of [`TimeSeries`]) and its value after a step.
pub type Channels<'a, K, const P: usize> = &'a dyn Fn(&TimeStepping<K, P>) -> Vec<(&'static str, f64)>;

/// What [`TimeStepping::run`] records: channels after every step, and every
/// `frame_every` steps (0: never) a frame of fields on the grid σ × ζ, each a derivative
/// of a field under a name of [`drive::SURFACE_FIELD_NAMES`].
pub struct Recording<'a, K: SurfaceKernel<P>, const P: usize> {
    /// Channels per step (besides `newton_iterations`, always recorded).
    pub channels: Channels<'a, K, P>,
    /// Steps between frames; 0 for none.
    pub frame_every: usize,
    /// Grid σ of the frames, m.
    pub sigma: Vec<f64>,
    /// Grid ζ of the frames, m.
    pub zeta: Vec<f64>,
    /// (name, field, derivative) of each frame field.
    pub fields: Vec<(&'static str, Field, PointDerivative)>,
}

/// The time-stepping analysis of a surface kernel.
pub struct TimeStepping<K: SurfaceKernel<P>, const P: usize> {
    asm: SurfaceAssembler<K, P>,
    history: SurfaceHistory,
    lu: SparseLu<SurfaceError>,
    z: Vec<f64>,
    time: f64,
    step: usize,
    motion: Option<Motion>,
    newton: NewtonOptions,
}

impl<K: SurfaceKernel<P>, const P: usize> TimeStepping<K, P> {
    /// The analysis from the unknowns `z` at time `time` (quasistatic; see
    /// [`Self::with_inertia`]), the history at its initial states, Newton by `newton`.
    ///
    /// # Errors
    /// [`TimeSteppingError::InitialState`] (length, finiteness), [`TimeSteppingError::Surface`]
    /// (history points, the symbolic factorisation).
    pub fn new(asm: SurfaceAssembler<K, P>, z: Vec<f64>, time: f64, newton: NewtonOptions) -> Result<Self, TimeSteppingError> {
        if z.len() != asm.len() || !z.iter().all(|v| v.is_finite()) || !time.is_finite() {
            return Err(TimeSteppingError::InitialState { what: "unknowns", reason: format!("{} values (need {} finite) at t = {time}", z.len(), asm.len()) });
        }
        let history = SurfaceHistory::new(&asm, time)?;
        let mut lu = SparseLu::new();
        let (rows, cols) = asm.pattern();
        lu.set_pattern(asm.len(), rows, cols)?;
        Ok(TimeStepping { asm, history, lu, z, time, step: 0, motion: None, newton })
    }

    /// Switch inertia on with the initial velocities `velocity`; Newmark starts from the
    /// acceleration that balances the initial state, a₀ = −M⁻¹∇Π(z₀; t₀).
    ///
    /// # Errors
    /// [`TimeSteppingError::InitialState`] (length, finiteness, an inadmissible start),
    /// [`TimeSteppingError::Surface`] (a singular mass matrix).
    pub fn with_inertia(mut self, inertia: Inertia, velocity: Vec<f64>) -> Result<Self, TimeSteppingError> {
        if velocity.len() != self.z.len() || !velocity.iter().all(|v| v.is_finite()) {
            return Err(TimeSteppingError::InitialState { what: "velocities", reason: format!("{} values, need {} finite", velocity.len(), self.z.len()) });
        }
        let mut acceleration = vec![0.0; self.z.len()];
        if inertia.scheme == Scheme::Newmark {
            let ev = Evaluation { time: self.time, dt: 0.0, history: Some(&self.history) };
            let (_, g) = self.asm.gradient(&self.z, &ev).ok_or(TimeSteppingError::InitialState { what: "unknowns", reason: "inadmissible or not finite".into() })?;
            let (rows, cols) = self.asm.pattern();
            let mut mass = SparseLu::<SurfaceError>::new();
            mass.set_pattern(self.z.len(), rows, cols)?;
            mass.factorize(&inertia.mass)?;
            acceleration = g.iter().map(|v| -v).collect();
            mass.solve_in_place(&mut acceleration)?;
        }
        self.motion = Some(Motion { inertia, velocity, acceleration });
        Ok(self)
    }

    /// One step to t + Δt (module documentation); on failure the state is unchanged.
    ///
    /// # Errors
    /// [`TimeSteppingError::InvalidStep`], [`TimeSteppingError::Newton`].
    pub fn step(&mut self, dt: f64) -> Result<StepReport, TimeSteppingError> {
        let step = self.step + 1;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(TimeSteppingError::InvalidStep { step, time: self.time, dt });
        }
        let end = self.time + dt;
        let advected = self.history.advected(self.asm.kernel().belt_speed(self.time + 0.5 * dt) * dt);
        let ev = Evaluation { time: end, dt, history: Some(&advected) };
        let inertia = self.motion.as_ref().map(|m| {
            let (kappa, predicted) = m.predictor(&self.z, dt);
            (kappa, m.inertia.mass.as_slice(), predicted)
        });
        let mut z = self.z.clone();
        let mut problem = StepProblem { asm: &self.asm, ev, lu: &mut self.lu, inertia, cache: None };
        let newton = newton::solve(&mut problem, &mut z, &self.newton).map_err(|cause| TimeSteppingError::Newton { step, time: self.time, end, cause })?;
        let energy = problem.merit(&z, &[]);
        let kappa_predicted = problem.inertia.take().map(|(k, _, p)| (k, p));
        if let (Some(motion), Some((kappa, predicted))) = (self.motion.as_mut(), kappa_predicted) {
            motion.update(&self.z, &z, dt, kappa, &predicted);
        }
        self.history = advected.advance(&self.asm, &z, &ev);
        self.z = z;
        self.time = end;
        self.step = step;
        Ok(StepReport { step, time: end, energy, newton })
    }

    /// `steps` steps of Δt = `dt`, recording channels and frames.
    ///
    /// # Errors
    /// As [`Self::step`]; [`TimeSteppingError::Output`] for a channel or frame that is
    /// not a valid result (a name, a non-finite value).
    pub fn run(&mut self, steps: usize, dt: f64, recording: &Recording<K, P>) -> Result<TimeSeries, TimeSteppingError> {
        let mut series = TimeSeries::default();
        for _ in 0..steps {
            let report = self.step(dt)?;
            let mut values = (recording.channels)(self);
            values.push(("newton_iterations", report.newton.iterations as f64));
            series.push(report.time, &values);
            if recording.frame_every > 0 && report.step % recording.frame_every == 0 {
                let surface = self.surface_fields(&recording.sigma, &recording.zeta, &recording.fields);
                series.frames.push(Frame { time: report.time, fields: None, surface: Some(surface) });
            }
            series.check().map_err(|cause| TimeSteppingError::Output { step: report.step, cause })?;
        }
        Ok(series)
    }

    /// Fields on the grid σ × ζ: each (name, field, derivative) sampled from the current
    /// unknowns (a field the kernel does not use reads 0).
    pub fn surface_fields(&self, sigma: &[f64], zeta: &[f64], fields: &[(&'static str, Field, PointDerivative)]) -> SurfaceFields {
        let mut out = SurfaceFields { sigma: sigma.to_vec(), zeta: zeta.to_vec(), ..Default::default() };
        for &(name, field, derivative) in fields {
            let values = sigma
                .iter()
                .map(|&s| zeta.iter().map(|&z| self.asm.field_at(&self.z, field, s, z).map_or(0.0, |v| v[derivative as usize])).collect())
                .collect();
            out.values.insert(name.to_string(), values);
        }
        out
    }

    /// The assembler (mesh, numbering, kernel).
    pub fn assembler(&self) -> &SurfaceAssembler<K, P> {
        &self.asm
    }

    /// The current unknowns.
    pub fn unknowns(&self) -> &[f64] {
        &self.z
    }

    /// The current time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> usize {
        self.step
    }

    /// The committed history.
    pub fn history(&self) -> &SurfaceHistory {
        &self.history
    }

    /// Velocities of the unknowns (None when quasistatic).
    pub fn velocity(&self) -> Option<&[f64]> {
        self.motion.as_ref().map(|m| m.velocity.as_slice())
    }
}
