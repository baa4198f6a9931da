//! `cosserat-drive` (Paper D): the shear-deformable (Cosserat) belt on two pulleys in
//! steady motion with gravity, transport inertia and a stick then a slip zone on each
//! pulley, the BVP of docs/cosserat-drive.md (spec §3.3).
//!
//! The belt theory is the section law [`law::ScaledCosseratDrive`] on the string drive's
//! topology with Coulomb friction; its spans, contact boundaries and arcs are the static
//! loop's and the one-pulley belt's equations with the transport term and the weight.
//! [`solve`] solves the `string-drive` BVP of the same scene (its homotopy in load,
//! gravity, length and speed), builds the Cosserat guess from it and continues in log a
//! from a₀ to the scene's a (no path when a₀ = a: the scene's bending layer is at least
//! the start layer), then solves by collocation or shooting and checks the balances and
//! the admissibility of the stick/slip topology.
//!
//! [`DriveMode::StickSlipAngle`] swaps the datum M₂ for the driver's stick → slip angle
//! φ_B1 (spec §3.4, check D-9): M₂ becomes an unknown of the same BVP, solved by
//! [`solve_from`] from a standard solution (no homotopy of its own).

pub mod law;

use std::f64::consts::FRAC_PI_2;
use std::time::Instant;

use numerics::Sig;
use serde::Serialize;

use drive::scene::{Analysis, Contact, Layout, Scene, Theory};

use crate::belt::run::StageError;
use crate::belt::solution::{self, Run};
use crate::belt::topology::{ArcKind, Pulley, Scaling, SegmentKind};
use crate::belt::{check_positive, BeltError, BeltOptions, BeltProblem, BeltSolution, BvpMethod, SectionLaw};
use crate::collocation::Scheme;
use crate::error::BvpError;
use crate::rod_hanging::{self, ScaledRodHanging};
use crate::scene::{string_drive_data, SceneSolveError};
use crate::solution::Solution;
use crate::string_drive::{self, StringDrive, StringDriveSolution};
pub use law::ScaledCosseratDrive;

/// What a Cosserat drive prescribes besides ω₁, L and d₂ (spec §3.3–§3.4): the load
/// torque M₂, or the driver's stick → slip angle with M₂ released. Either keeps the BVP
/// square (docs/cosserat-drive.md, "Prescribed stick→slip angle").
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub enum DriveMode {
    /// M₂ given (`drive.driven_torque`): the catalogue drive of spec §3.3.
    #[default]
    LoadTorque,
    /// The driver's stick → slip angle φ_B1 given, M₂ an unknown (spec §3.4 (i), Paper C's
    /// swap of a kinetic datum for a transition point). `driver` is the polar angle (rad)
    /// of the point between the driver's stick and slip arcs, unwrapped as the driver's
    /// contact angles (docs/cosserat-drive.md, "Conventions"): its arc runs from
    /// φ₁ₐ ≈ −π/2 down to φ₁_b ≈ −3π/2, so φ_B1 ≈ −4.33 rad on the catalogue scene (the
    /// summary's wrapped `contact_start` − `stick_arc` + 2π·k). `drive.driven_torque`
    /// then sets only the power flow (its sign) and the standard solve [`solve`] starts
    /// from; the solution's `data` carries the solved M₂.
    StickSlipAngle {
        /// φ_B1, rad.
        driver: f64,
    },
}

/// Physical data of a Cosserat drive scene (SI units): the string drive's (pulleys, belt
/// with b₁ = EA, gravity, inertia, μ, ω₁, M₂, d₂), the Cosserat constants and what is
/// prescribed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CosseratDrive {
    /// The drive with the belt as an extensible string (a = 0).
    pub drive: StringDrive,
    /// Bending stiffness a (N·m²).
    pub bending_stiffness: f64,
    /// Shear stiffness b₂ (N).
    pub shear_stiffness: f64,
    /// M₂ given (scenes) or φ_B1 given with M₂ released.
    pub mode: DriveMode,
}

/// A solved Cosserat drive; its `start` is the string drive solution of the same scene.
pub type CosseratDriveSolution = BeltSolution<ScaledCosseratDrive>;

impl CosseratDrive {
    /// The data of a two-pulley Cosserat scene in steady motion with Coulomb friction.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneSolveError> {
        let fits = scene.drive.layout == Layout::TwoPulley && scene.belt.theory == Theory::Cosserat && scene.analysis == Analysis::Steady;
        let (true, &Contact::Coulomb(mu)) = (fits, &scene.effects.contact) else {
            return Err(SceneSolveError::Unsupported(format!(
                "layout {}, theory {}, analysis {}, contact {:?}: the Cosserat drive is the two-pulley Cosserat belt in steady motion with Coulomb friction",
                scene.drive.layout, scene.belt.theory, scene.analysis, scene.effects.contact
            )));
        };
        Ok(Self {
            drive: string_drive_data(scene, mu),
            bending_stiffness: scene.belt.bending_stiffness.unwrap_or(f64::NAN),
            shear_stiffness: scene.belt.shear_stiffness.unwrap_or(f64::NAN),
            mode: DriveMode::LoadTorque,
        })
    }

    /// The transport term χ = ρc² at transport rate `c` with the inertia effect, else 0 (N).
    pub fn chi(&self, c: f64) -> f64 {
        if self.drive.inertia { self.drive.mass_per_length * c * c } else { 0.0 }
    }

    /// The shear layer √(a/(b₂ − χ)) (m) at transport rate `c`.
    pub fn shear_layer(&self, c: f64) -> f64 {
        (self.bending_stiffness / (self.shear_stiffness - self.chi(c))).sqrt()
    }
}

/// Validate the Cosserat constants and the speed: a, b₂ finite and > 0, the transport
/// term at the belt speed |ω₁|R (λ → 1) below b₂ and b₁ (`SpeedAtOrAboveCritical`).
pub fn validate(d: &CosseratDrive, opts: &BeltOptions) -> Result<(), BeltError> {
    opts.check_tolerance()?;
    check_positive(&[("bending_stiffness", d.bending_stiffness), ("shear_stiffness", d.shear_stiffness)])?;
    let rate = d.drive.driver_speed.abs() * d.drive.radius;
    critical(d, rate)
}

/// `SpeedAtOrAboveCritical` when χ = ρc² at `rate` (m/s) reaches b₂ or b₁.
fn critical(d: &CosseratDrive, rate: f64) -> Result<(), BeltError> {
    let chi = d.chi(rate);
    for (stiffness, value) in [("shear stiffness b₂", d.shear_stiffness), ("axial stiffness b₁", d.drive.axial_stiffness)] {
        if chi >= value {
            let critical_rate = (value / d.drive.mass_per_length).sqrt();
            return Err(BeltError::SpeedAtOrAboveCritical { stiffness, value, chi, transport_rate: rate, critical_rate });
        }
    }
    Ok(())
}

/// The string drive of the same scene, the homotopy start: by collocation (gauss6,
/// 1e-8) with the run's mesh cap and homotopy tolerance. Its own named errors (friction
/// capacity, reversed slip, wave speed) are the scene's.
pub fn string_start(d: &CosseratDrive, opts: &BeltOptions) -> Result<StringDriveSolution, BeltError> {
    let sopts = BeltOptions { method: BvpMethod::Collocation, scheme: Scheme::Gauss6, tolerance: 1e-8, ..opts.clone() };
    string_drive::solve(&d.drive, &sopts)
}

/// The scaled law: the string drive's scaled scene and a₀ = max(a, a_layer), a_layer
/// from the bending layer √(a_layer/T̃) = `start_layer`·H at the string's upper mid-span
/// effective tension: a scene whose layer is at least the start layer starts at its own
/// a (no path in a, as the one-pulley belt's `cosserat_pulley`), a thinner one
/// continues from the start layer down to its a.
fn scaled_law(d: &CosseratDrive, string: &StringDriveSolution, opts: &BeltOptions) -> ScaledCosseratDrive {
    let (h, fr) = (string.scales.length, string.scales.force);
    let (upper_mid, _) = string.topology().mid_spans();
    let mid = string.solution.segments[upper_mid].end();
    let t_mid = mid[2].hypot(mid[3]);
    let bending = d.bending_stiffness / (fr * h * h);
    ScaledCosseratDrive {
        string: string.problem.law.clone(),
        shear: d.shear_stiffness / fr,
        bending_start: bending.max(opts.start_layer * opts.start_layer * t_mid),
        bending,
        mode: DriveMode::LoadTorque,
    }
}

/// Nodes per segment of the Cosserat guess: 20 intervals, two per start layer on the
/// longest segment (a half span ≈ H/2 against a layer of 5 % of H); the first
/// collocation solve refines where the layers need it.
const GUESS_NODES: usize = 21;

/// The Cosserat guess at a₀ from the string drive solution (scaled; spec §3.3 [P]): on
/// the spans the Kirchhoff rod's guess ([`rod_hanging::rod_guess`]: θ from the force
/// direction, M in exponential layers), on the arcs zero shear θ = φ − π/2, M = −a₀λ/R,
/// λ from (D2), τ = the string's torque m; λ_i from the string's stick-zone tensions.
pub fn cosserat_guess(string: &StringDriveSolution, problem: &BeltProblem<ScaledCosseratDrive>, nodes: usize) -> Solution {
    let law = &problem.law;
    let sl = &law.string;
    let rod = ScaledRodHanging {
        radius: sl.radius,
        axial_stiffness: sl.axial_stiffness,
        weight: sl.weight,
        length: sl.length,
        bending_start: law.bending_start,
        bending: law.bending,
    };
    let topo = &problem.topology;
    let spans = rod_hanging::rod_guess(&string.solution, &BeltProblem::new(topo.clone(), rod), nodes);
    let sp = &string.solution.params;
    let c = sp[law::TRANSPORT];
    let stick_stretch = |pulley| {
        let k = topo.arc(pulley, ArcKind::Stick).expect("a drive has stick arcs");
        sl.stretch(string.solution.segments[k].nodes[0][0], c)
    };
    let mut params = sp.clone();
    params.extend([stick_stretch(Pulley::Driver), stick_stretch(Pulley::Driven)]);
    Solution::from_fn(topo.len(), nodes, params, 0.0, |k, xi| {
        let Scaling::Arc { start, end, .. } = topo.segment(k).scaling else { return spans.eval(k, xi) };
        let [te, s, m] = string.solution.eval(k, xi)[..] else { unreachable!("the string drive's arc state is (T̃, s, m)") };
        let phi = sp[start] + xi * (sp[end] - sp[start]);
        let lambda = sl.stretch(te, c);
        let mut y = vec![phi - FRAC_PI_2, -law.bending_start * lambda / sl.radius, s, m];
        if topo.segment(k).kind == SegmentKind::Arc(ArcKind::Slip) {
            y.push(lambda);
        }
        y
    })
}

/// Solve a Cosserat drive from its data alone (module docs). With the driver's stick →
/// slip angle prescribed ([`DriveMode::StickSlipAngle`]): the standard drive at the
/// data's M₂, then [`solve_from`] it with φ_B1 given and M₂ released; the work of both
/// is counted.
pub fn solve(data: &CosseratDrive, opts: &BeltOptions) -> Result<CosseratDriveSolution, BeltError> {
    if let DriveMode::StickSlipAngle { .. } = data.mode {
        let standard = solve(&CosseratDrive { mode: DriveMode::LoadTorque, ..*data }, opts)?;
        let mut sol = solve_from(data, opts, &standard).expect("the standard drive of the same data has its topology and power flow")?;
        sol.stats.add_work(&standard.stats);
        sol.stats.wall_seconds += standard.stats.wall_seconds;
        sol.homotopy_steps = standard.homotopy_steps;
        return Ok(sol);
    }
    let clock = Instant::now();
    validate(data, opts)?;
    let string = string_start(data, opts)?;
    let law = scaled_law(data, &string, opts);
    let problem = BeltProblem::new(string.topology().clone(), law);
    let guess = cosserat_guess(&string, &problem, GUESS_NODES);
    let (scales, pulleys) = (string.scales, string.pulleys);
    let a0 = problem.law.bending_start * scales.force * scales.length * scales.length;
    let run = Run { data: *data, problem, scales, pulleys, guess: &guess, start: string };
    let direct = run.problem.law.starts_at_scene();
    let sol = solution::solve(run, opts, clock, |e, last_rejection| match e {
        StageError::Homotopy(cause) if direct => BeltError::Solver { stage: "the first solve at the scene's a from the string drive", cause },
        StageError::Homotopy(cause) => homotopy_failure(data, a0, cause, last_rejection),
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })?;
    sol.check_admissible()?;
    Ok(sol)
}

/// Solve a Cosserat drive from the solution `previous` of a nearby drive (a warm start,
/// [`solution::solve_from`]): the scene's a directly (no path in a) in `previous`'s
/// scales, on its topology. The solution keeps `previous`'s string drive as its `start`
/// (the string solution the continuation began from, not one of this scene). `None` when
/// `previous` cannot start it: another running direction or power flow.
///
/// Either mode from a solution of either mode: with the driver's stick → slip angle
/// prescribed ([`DriveMode::StickSlipAngle`]) M₂ starts at `previous`'s (solved or given)
/// load torque and the solution's `data` carries the solved one.
///
/// # Errors
/// Those of [`solution::solve_from`]; [`BeltError::TransitionOutsideContact`] when the
/// prescribed φ_B1 does not lie strictly inside `previous`'s driver contact arc,
/// [`BeltError::InvalidInput`] when it is not finite.
pub fn solve_from(data: &CosseratDrive, opts: &BeltOptions, previous: &CosseratDriveSolution) -> Option<Result<CosseratDriveSolution, BeltError>> {
    let clock = Instant::now();
    let scales = string_drive::warm_scales(&data.drive, previous.scales);
    let string = string_drive::scaled_problem_in(&data.drive, scales);
    if string.topology != previous.problem.topology || string.law.flow != previous.problem.law.string.flow {
        return None;
    }
    let bending = data.bending_stiffness / (scales.force * scales.length * scales.length);
    let law = ScaledCosseratDrive { string: string.law, shear: data.shear_stiffness / scales.force, bending_start: bending, bending, mode: data.mode };
    // the guess's parameters: the topology's and λ₁, λ₂, then M₂ where it is an unknown
    let mut params = previous.solution.params[..law::LOAD_TORQUE].to_vec();
    if let DriveMode::StickSlipAngle { .. } = data.mode {
        params.push(previous.load_torque() / (scales.force * scales.length));
    }
    let guess = Solution { params, ..previous.solution.clone() };
    let solved = validate(data, opts).and_then(|()| transition_inside_contact(data, previous)).and_then(|()| {
        let run = Run {
            data: *data,
            problem: BeltProblem::new(string.topology, law),
            scales,
            pulleys: data.drive.pulleys(),
            guess: &guess,
            start: previous.start.clone(),
        };
        solution::solve_from(run, opts, clock)
    });
    Some(solved.and_then(|mut sol| {
        sol.check_admissible()?;
        sol.data.drive.driven_torque = sol.load_torque();
        Ok(sol)
    }))
}

/// A prescribed φ_B1 finite and strictly inside the driver's contact arc of `previous`
/// (the solve's start), else the named error; nothing to check in mode `LoadTorque`.
fn transition_inside_contact(data: &CosseratDrive, previous: &CosseratDriveSolution) -> Result<(), BeltError> {
    let DriveMode::StickSlipAngle { driver } = data.mode else { return Ok(()) };
    if !driver.is_finite() {
        return Err(BeltError::InvalidInput { name: "stick_slip_angle", value: driver, reason: "must be finite" });
    }
    let angles = previous.contact_angles(Pulley::Driver);
    let (first, last) = (angles[0], angles[angles.len() - 1]);
    if driver < first.max(last) && driver > first.min(last) {
        return Ok(());
    }
    Err(BeltError::TransitionOutsideContact { pulley: Pulley::Driver.name(), angle: driver, first_contact: first, last_contact: last })
}

/// The named error of a stalled homotopy in log a: the friction capacity or a reversed
/// slip when the last rejected point lost its stick or slip arc, else the bending
/// stiffness reached and the layers that make it hard.
fn homotopy_failure(d: &CosseratDrive, a0: f64, cause: BvpError, last_rejection: Option<&str>) -> BeltError {
    const STAGE: &str = "the homotopy in log a from the string drive";
    let torque = d.drive.net_load();
    // gravity, load, length and speed are complete: the string drive's path reached them
    let path = [1.0; 4];
    if let Some(reason) = last_rejection.filter(|r| r.contains("stick arc")) {
        return BeltError::FrictionCapacityExceeded { torque, path, reason: reason.to_string() };
    }
    if let Some(reason) = last_rejection.filter(|r| r.contains("slip arc")) {
        let weight_torque = 2.0 * d.drive.mass_per_length * d.drive.gravity * d.drive.radius * d.drive.radius;
        return BeltError::SlipReversed { torque, weight_torque, path, reason: reason.to_string() };
    }
    let BvpError::ContinuationStalled { eta, .. } = cause else {
        return BeltError::Solver { stage: STAGE, cause };
    };
    let a = d.bending_stiffness;
    let at = format!("bending stiffness a = {} N·m² on the way from a₀ = {} N·m² to the scene's {} N·m²", Sig(a0.powf(1.0 - eta) * a.powf(eta)), Sig(a0), Sig(a));
    let c = d.drive.driver_speed * d.drive.radius;
    let hard = format!("the shear layer √(a/(b₂ − ρc²)) = {} m against R = {} m makes it hard", Sig(d.shear_layer(c)), Sig(d.drive.radius));
    BeltError::HomotopyStalled { stage: STAGE, eta, at, hard, cause }
}

impl CosseratDriveSolution {
    /// Stick stretches (λ₁ driver, λ₂ driven).
    pub fn stick_stretches(&self) -> (f64, f64) {
        let p = &self.solution.params;
        (p[law::LAMBDA_DRIVER], p[law::LAMBDA_DRIVEN])
    }

    /// a₀ (N·m²) of the homotopy start.
    pub fn bending_start(&self) -> f64 {
        self.problem.law.bending_start * self.scales.force * self.scales.length * self.scales.length
    }

    /// Power balance (W): (input, output, slip dissipation), spec D-3, at the solved M₂.
    pub fn power_balance(&self) -> (f64, f64, f64) {
        crate::belt::balance::drive_power(self, &self.solved_drive())
    }

    /// The load torque M₂ (N·m): the data's, or the solved one where the mode releases it
    /// (the summary's driven `torque` is the torque it balances, M₂ + d₂ω₂).
    pub fn load_torque(&self) -> f64 {
        match self.problem.law.mode {
            DriveMode::LoadTorque => self.data.drive.driven_torque,
            DriveMode::StickSlipAngle { .. } => self.solution.params[law::LOAD_TORQUE] * self.scales.force * self.scales.length,
        }
    }

    /// The drive at the solved load torque: the data's with M₂ = [`Self::load_torque`].
    pub fn solved_drive(&self) -> StringDrive {
        StringDrive { driven_torque: self.load_torque(), ..self.data.drive }
    }

    /// The stick → slip angles (φ_B1 driver, φ_B2 driven), rad: polar angles, unwrapped as
    /// the contact angles (docs/cosserat-drive.md, "Conventions").
    pub fn stick_slip_angles(&self) -> (f64, f64) {
        let at = |pulley| self.solution.params[self.topology().transition_angle(pulley).expect("a drive has stick and slip arcs")];
        (at(Pulley::Driver), at(Pulley::Driven))
    }

    /// The admissibility check the loop's `check_contact` does not make (spec §3.3): b₁,
    /// b₂ > χ at the solved transport rate c. (The slip direction is checked there by the
    /// stretch, [`crate::belt::SectionLaw::slip_force`].)
    pub fn check_admissible(&self) -> Result<(), BeltError> {
        critical(&self.data, self.transport_rate().unwrap_or(f64::NAN).abs())
    }
}
