//! `string-drive`: the steady friction drive of an extensible string on two pulleys, as
//! the eight-segment BVP derived in `docs/string-drive.md` (free spans, a stick zone and
//! a slip zone on each pulley; Paper B, §8.2 of the reference; Coulomb law of §6.1).
//!
//! [`solve`] checks the data (named errors for the cases with no steady solution, exact
//! without gravity by [`crate::analytical::belt_creep`]), reaches the scene from the tight
//! loop at rest by the three-phase homotopy of the note (torque, then gravity and
//! length, then speed), solves at the requested tolerance with the requested method and
//! checks the topology and the contact law. [`StringDriveSolution`] implements the
//! common [`drive::view::SolutionView`]. The drive is the string's section law in steady
//! motion ([`law`]) on the two-pulley topology with Coulomb friction.

pub mod law;

use std::f64::consts::PI;
use std::time::Instant;

use numerics::Sig;
use serde::Serialize;

use crate::analytical::belt_creep::{CreepData, CreepError, CreepSolution};
use crate::belt::balance;
use crate::belt::run::StageError;
use crate::belt::solution::{self, tight_guess, Run};
use crate::belt::topology::{ContactModel, Direction, PowerFlow, Topology};
use crate::belt::{BeltError, BeltOptions, BeltProblem, BeltSolution, Scales};
use crate::error::BvpError;
use crate::solution::Solution;
use crate::string_hanging::StringHanging;
pub use law::ScaledStringDrive;

/// Physical data of a steady drive scene (SI units): the loop of the string at rest
/// (pulleys, belt, gravity; its fields read through `Deref`) and the drive's motion and
/// loads.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StringDrive {
    /// The pulleys, the belt and gravity, as for the string at rest.
    pub belt: StringHanging,
    /// Persistent transport inertia (ρc² terms).
    pub inertia: bool,
    /// Coulomb coefficient μ > 0.
    pub friction: f64,
    /// Driver speed ω₁ (rad/s, clockwise positive; negative: the belt runs
    /// counter-clockwise).
    pub driver_speed: f64,
    /// Load torque M₂ (N·m, clockwise torque the belt must exert on the driven pulley:
    /// positive resists a clockwise drive; with the sign of −ω₁ the load drives).
    pub driven_torque: f64,
    /// Viscous damping d₂ ≥ 0 of the driven pulley (N·m·s).
    pub driven_damping: f64,
}

impl std::ops::Deref for StringDrive {
    type Target = StringHanging;

    fn deref(&self) -> &StringHanging {
        &self.belt
    }
}

impl StringDrive {
    /// The gravity-free data of belt-creep theory.
    pub fn creep_data(&self) -> CreepData {
        CreepData {
            radius: self.radius,
            centre_distance: self.centre_distance,
            length: self.length,
            axial_stiffness: self.axial_stiffness,
            mass_per_length: self.mass_per_length,
            inertia: self.inertia,
            friction: self.friction,
            driver_speed: self.driver_speed,
            driven_torque: self.driven_torque,
            driven_damping: self.driven_damping,
        }
    }

    /// The gravity-free closed form of this drive (exact when g = 0).
    pub fn creep(&self) -> Result<CreepSolution, CreepError> {
        self.creep_data().solve()
    }

    /// The net driven load at the driver's speed, M₂ + d₂ω₁ (N·m): its sign relative to
    /// the running direction decides the power flow (docs/string-drive.md, "Both
    /// rotation senses and both power flows").
    pub fn net_load(&self) -> f64 {
        self.driven_torque + self.driven_damping * self.driver_speed
    }

    /// The running direction of the belt (the driver's sense of rotation).
    pub fn direction(&self) -> Direction {
        Direction::of_speed(self.driver_speed)
    }

    /// Which pulley puts power into the belt.
    pub fn power_flow(&self) -> PowerFlow {
        PowerFlow::of_load(self.net_load(), self.direction())
    }
}

/// A solved steady drive.
pub type StringDriveSolution = BeltSolution<ScaledStringDrive>;

fn validate(d: &StringDrive) -> Result<(), BeltError> {
    d.belt.check_loop()?;
    // both senses of rotation and both power flows are solved (docs/string-drive.md,
    // "Both rotation senses and both power flows")
    for (name, value) in [("driver_speed", d.driver_speed), ("driven_torque", d.driven_torque)] {
        if !value.is_finite() {
            return Err(BeltError::InvalidInput { name, value, reason: "must be finite" });
        }
    }
    if !(d.driven_damping.is_finite() && d.driven_damping >= 0.0) {
        return Err(BeltError::InvalidInput { name: "driven_damping", value: d.driven_damping, reason: "must be finite and ≥ 0" });
    }
    if !(d.friction.is_finite() && d.friction > 0.0) {
        return Err(BeltError::InvalidInput {
            name: "coulomb",
            value: d.friction,
            reason: "a steady friction drive needs μ > 0 (without friction the belt speed is undetermined)",
        });
    }
    let wave_speed = (d.axial_stiffness / d.mass_per_length).sqrt();
    if d.inertia && d.driver_speed.abs() * d.radius >= wave_speed {
        return Err(BeltError::WaveSpeedReached { belt_speed: d.driver_speed.abs() * d.radius, wave_speed });
    }
    Ok(())
}

/// The scaled problem and its scales (docs/string-drive.md, "Scaling and homotopy").
pub fn scaled_problem(d: &StringDrive) -> (BeltProblem<ScaledStringDrive>, Scales) {
    let scales = scales(d);
    (scaled_problem_in(d, scales), scales)
}

/// The scales of a drive: H, F_ref = max(ρgL, EA(L_geom/L − 1), |M₂ + d₂ω₁|/R),
/// V = √(F_ref/ρ).
fn scales(d: &StringDrive) -> Scales {
    let weight_total = d.mass_per_length * d.gravity * d.length;
    let target = d.axial_stiffness * (d.geometric_length() / d.length - 1.0);
    let force = weight_total.max(target).max(d.net_load().abs() / d.radius);
    Scales { length: d.centre_distance, force, speed: (force / d.mass_per_length).sqrt() }
}

/// The scales of a warm start of drive `d` from a solution in scales `previous`: its
/// force scale F_ref (so the previous scaled forces, moments and transport rate are a
/// guess of the same size), the length scale H and V = √(F_ref/ρ) of `d` (the scaled
/// law places the pulleys at x = ∓1/2 and writes χ/F_ref = c̃²).
pub fn warm_scales(d: &StringDrive, previous: Scales) -> Scales {
    Scales { length: d.centre_distance, force: previous.force, speed: (previous.force / d.mass_per_length).sqrt() }
}

/// The scaled problem of a drive in given scales (those of [`scaled_problem`], or a
/// nearby scene's for a warm start, [`solve_from`]).
pub fn scaled_problem_in(d: &StringDrive, scales: Scales) -> BeltProblem<ScaledStringDrive> {
    let Scales { length: h, force, speed } = scales;
    let weight_total = d.mass_per_length * d.gravity * d.length;
    let target = d.axial_stiffness * (d.geometric_length() / d.length - 1.0);
    let torque = d.net_load().abs();
    let capacity_tension = 2.0 * torque / (d.radius * (1.0 - (-d.friction * PI).exp()));
    let t0 = weight_total.max(target).max(capacity_tension);
    let length_start = if t0 == target { d.length } else { d.geometric_length() / (1.0 + t0 / d.axial_stiffness) };
    let law = ScaledStringDrive {
        radius: d.radius / h,
        axial_stiffness: d.axial_stiffness / force,
        weight: d.mass_per_length * d.gravity * h / force,
        inertia: d.inertia,
        friction: d.friction,
        driver_speed: d.driver_speed * h / speed,
        torque: d.driven_torque / (force * h),
        damping: d.driven_damping * speed / (force * h * h),
        length_start: length_start / h,
        length: d.length / h,
        flow: d.power_flow(),
        preload: 0.0,
    };
    // M₂ alone would drive the belt the other way round than the net load: hold the
    // net load while the driver is at rest (law docs)
    let law = if d.driven_torque * d.net_load() < 0.0 { ScaledStringDrive { preload: law.damping * law.driver_speed, ..law } } else { law };
    let topology = Topology::two_pulley_running(ContactModel::Coulomb, d.direction());
    BeltProblem::new(topology, law)
}

/// The exact solution at η = 0: the tight weightless loop at rest with length L₀ —
/// straight spans, half-turn arcs all in stick, zero slip arcs, uniform tension.
pub fn tight_start(problem: &BeltProblem<ScaledStringDrive>, nodes: usize) -> Solution {
    let p = &problem.law;
    let t0 = p.tight_tension();
    tight_guess(problem, t0, 1.0 + t0 / p.axial_stiffness, p.radius, nodes)
}

/// Solve a `string-drive` scene from its data alone.
pub fn solve(data: &StringDrive, opts: &BeltOptions) -> Result<StringDriveSolution, BeltError> {
    let clock = Instant::now();
    check(data, opts)?;
    let (problem, scales) = scaled_problem(data);
    let guess = tight_start(&problem, 5);
    let run = Run { data: *data, problem, scales, pulleys: data.pulleys(), guess: &guess, start: () };
    solution::solve(run, opts, clock, |e, last_rejection| match e {
        StageError::Homotopy(cause) => homotopy_failure(data, cause, last_rejection),
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })
}

/// The data and the options valid, and no exact no-solution case of belt-creep theory
/// (without gravity), before any iteration.
fn check(data: &StringDrive, opts: &BeltOptions) -> Result<(), BeltError> {
    validate(data)?;
    opts.check_tolerance()?;
    if data.gravity == 0.0 {
        data.creep()?;
    }
    Ok(())
}

/// Solve a drive from the solution `previous` of a nearby drive (a warm start:
/// [`solution::solve_from`] in `previous`'s scales). `None` when `previous` cannot start
/// it: another running direction or power flow (another topology or slip signs).
pub fn solve_from(data: &StringDrive, opts: &BeltOptions, previous: &StringDriveSolution) -> Option<Result<StringDriveSolution, BeltError>> {
    let clock = Instant::now();
    let scales = warm_scales(data, previous.scales);
    let problem = scaled_problem_in(data, scales);
    if problem.topology != previous.problem.topology || problem.law.flow != previous.problem.law.flow {
        return None;
    }
    if let Err(e) = check(data, opts) {
        return Some(Err(e));
    }
    let run = Run { data: *data, problem, scales, pulleys: data.pulleys(), guess: &previous.solution, start: () };
    Some(solution::solve_from(run, opts, clock))
}

/// The named error of a homotopy that stalled: the friction capacity or a reversed slip
/// when the last rejected point says so (its stick or slip arc vanished), else the
/// solver's failure.
fn homotopy_failure(data: &StringDrive, cause: BvpError, last_rejection: Option<&str>) -> BeltError {
    const STAGE: &str = "the homotopy from the tight loop at rest";
    let BvpError::ContinuationStalled { eta, .. } = cause else {
        return BeltError::Solver { stage: STAGE, cause };
    };
    let path = ScaledStringDrive::phases(eta);
    let torque = data.net_load();
    if let Some(reason) = last_rejection.filter(|r| r.contains("slip arc")) {
        let weight_torque = 2.0 * data.mass_per_length * data.gravity * data.radius * data.radius;
        return BeltError::SlipReversed { torque, weight_torque, path, reason: reason.to_string() };
    }
    if let Some(reason) = last_rejection.filter(|r| r.contains("stick arc")) {
        return BeltError::FrictionCapacityExceeded { torque, path, reason: reason.to_string() };
    }
    // the phase in progress: the first quantity not yet at the scene's value
    let phase = path.iter().position(|&f| f < 1.0).unwrap_or(3);
    let pct = Sig(100.0 * path[phase]);
    let (w, ea, r) = (data.mass_per_length * data.gravity, data.axial_stiffness, data.radius);
    let (at, hard) = match phase {
        0 => (
            format!("switching on the load: {pct} % of M₂ + d₂ω₁ = {} N·m", Sig(torque)),
            format!("the load against the belt's pretension, (M₂ + d₂ω₁)/(R·EA) = {}, makes it hard", Sig(torque / (r * ea))),
        ),
        1 => (
            format!("switching on the weight: {pct} % of ρg = {} N/m", Sig(w)),
            format!("the weight against the axial stiffness, ρgL/EA = {}, makes it hard", Sig(w * data.length / ea)),
        ),
        2 => (
            format!("lengthening the belt: {pct} % of the way to the scene's L = {} m", Sig(data.length)),
            format!("the slack L/L_geom = {} of the scene makes it hard", Sig(data.length / data.geometric_length())),
        ),
        _ => (
            format!("speeding up: {pct} % of the scene's ω₁ = {} rad/s", Sig(data.driver_speed)),
            format!(
                "the belt speed against the wave speed, ρ(ω₁R)²/EA = {}, makes it hard",
                Sig(data.mass_per_length * (data.driver_speed * r).powi(2) / ea)
            ),
        ),
    };
    BeltError::HomotopyStalled { stage: STAGE, eta, at, hard, cause }
}

impl StringDriveSolution {
    /// The power scale P_ref of the balance check (W, [`crate::belt::balance`]): the
    /// scene's transmitted power |(M₂ + d₂ω₁) ω₁|, or F_ref |ω₁|R for a drive without
    /// load.
    pub fn power_scale(&self) -> f64 {
        balance::drive_power_scale(&self.data, self.scales.force)
    }

    /// Power balance (W): (input M_in ω₁, output (M₂ + d₂ω₂) ω₂, slip dissipation
    /// D = Σ ∫_slip τ (ωR − cλ) ds) ([`balance::drive_power`]; docs/string-drive.md,
    /// "Torques, power").
    pub fn power_balance(&self) -> (f64, f64, f64) {
        balance::drive_power(self, &self.data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stall the drive cannot classify (no stick or slip arc vanished) is named by the
    /// phase in progress — load, weight, length, speed — and that phase's number.
    #[test]
    fn stalls_name_the_phase_in_progress() {
        let belt = StringHanging { radius: 0.1, centre_distance: 0.5, length: 1.6, axial_stiffness: 1.0e4, mass_per_length: 0.5, gravity: 9.81 };
        let d = StringDrive { belt, inertia: true, friction: 0.4, driver_speed: 60.0, driven_torque: 10.0, driven_damping: 0.05 };
        let stall = |eta: f64| homotopy_failure(&d, BvpError::ContinuationStalled { eta, step: 1e-9, min_step: 1e-8, cause: "diverged".into() }, None).to_string();
        let e = stall(0.1);
        assert!(e.contains("switching on the load: 40 % of M₂ + d₂ω₁ = 13 N·m") && e.contains("(M₂ + d₂ω₁)/(R·EA) = 0.013"), "{e}");
        let e = stall(0.3);
        assert!(e.contains("switching on the weight: 20 % of ρg = 4.905 N/m") && e.contains("ρgL/EA = 7.848e-4"), "{e}");
        let e = stall(0.6);
        assert!(e.contains("lengthening the belt: 40 % of the way to the scene's L = 1.6 m"), "{e}");
        let e = stall(0.9);
        assert!(e.contains("speeding up: 60 % of the scene's ω₁ = 60 rad/s") && e.contains("ρ(ω₁R)²/EA = 0.0018"), "{e}");
    }
}
