//! `string-hanging`: an extensible string loop hanging under gravity on two non-rotating
//! frictionless pulleys, as the six-segment BVP derived in `docs/string-hanging.md`.
//!
//! [`solve`] reaches the scene from the tight, weightless closed form by the homotopy of
//! the note, then solves at the requested tolerance with the requested method
//! ([`crate::belt::run`]), checks the closure balance ([`crate::belt::balance`]) and the
//! contact conditions (p ≥ 0 on the arcs, no span inside a pulley) and returns a
//! [`StringHangingSolution`], which implements the common view. The string is a section
//! law ([`law`]) on the frictionless two-pulley topology.

pub mod law;

use std::f64::consts::PI;
use std::time::Instant;

use numerics::Sig;
use serde::Serialize;

use crate::belt::run::StageError;
use crate::error::BvpError;
use crate::belt::solution::{self, tight_guess, Run};
use crate::belt::topology::{ContactModel, Topology};
use crate::belt::law::Pulleys;
use crate::belt::{BeltError, BeltOptions, BeltProblem, BeltSolution, Scales};
pub use law::ScaledStringHanging;

/// Physical data of the scene (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StringHanging {
    /// Pulley radius R to the belt centreline (m).
    pub radius: f64,
    /// Centre distance H (m).
    pub centre_distance: f64,
    /// Unstretched loop length L (m).
    pub length: f64,
    /// Axial stiffness EA (N).
    pub axial_stiffness: f64,
    /// Mass per unstretched length ρ (kg/m).
    pub mass_per_length: f64,
    /// Gravitational acceleration g ≥ 0 (m/s²); 0 = no gravity effect.
    pub gravity: f64,
}

impl StringHanging {
    /// Geometric contour length L_geom = 2H + 2πR.
    pub fn geometric_length(&self) -> f64 {
        2.0 * self.centre_distance + 2.0 * PI * self.radius
    }

    /// Tension of the weightless tight loop with this length, EA (L_geom/L − 1); ≤ 0 for
    /// a belt at least as long as the contour.
    pub fn tight_tension(&self) -> f64 {
        self.axial_stiffness * (self.geometric_length() / self.length - 1.0)
    }

    /// The pulleys and the belt's weight ρg.
    pub fn pulleys(&self) -> Pulleys {
        Pulleys { radius: self.radius, centre_distance: self.centre_distance, weight: self.mass_per_length * self.gravity }
    }
}

/// A solved `string-hanging` scene.
pub type StringHangingSolution = BeltSolution<ScaledStringHanging>;

impl StringHanging {
    /// The checks every loop on two pulleys needs: R, H, L, EA, ρ finite and > 0,
    /// g finite and ≥ 0, pulleys apart (H > 2R).
    pub fn check_loop(&self) -> Result<(), BeltError> {
        crate::belt::check_positive(&[
            ("pulley_radius", self.radius),
            ("centre_distance", self.centre_distance),
            ("length", self.length),
            ("axial_stiffness", self.axial_stiffness),
            ("mass_per_length", self.mass_per_length),
        ])?;
        if !self.gravity.is_finite() || self.gravity < 0.0 {
            return Err(BeltError::InvalidInput { name: "gravity", value: self.gravity, reason: "must be finite and ≥ 0" });
        }
        crate::belt::check_pulleys_apart(self.radius, self.centre_distance)
    }
}

/// Validate the physical data.
fn validate(d: &StringHanging) -> Result<(), BeltError> {
    d.check_loop()?;
    if d.gravity == 0.0 && d.tight_tension() <= 0.0 {
        return Err(BeltError::WeightlessSlack { length: d.length, geometric_length: d.geometric_length() });
    }
    Ok(())
}

/// The scaled problem and its scales (docs/string-hanging.md, "Scaling" and "Homotopy").
pub fn scaled_problem(d: &StringHanging) -> (BeltProblem<ScaledStringHanging>, Scales) {
    let h = d.centre_distance;
    let weight_total = d.mass_per_length * d.gravity * d.length;
    let target = d.tight_tension();
    // The larger of the weight and the stretched-on tension, so that scaled forces are
    // O(1) for slack and for stretched-on belts alike.
    let force = weight_total.max(target);
    // Starting tension of the weightless tight loop.
    let t0 = if d.gravity > 0.0 { weight_total.max(target) } else { target };
    let length_start = d.geometric_length() / (1.0 + t0 / d.axial_stiffness);
    let law = ScaledStringHanging {
        radius: d.radius / h,
        axial_stiffness: d.axial_stiffness / force,
        weight: d.mass_per_length * d.gravity * h / force,
        length_start: length_start / h,
        length: d.length / h,
    };
    let scales = Scales { length: h, force, speed: (force / d.mass_per_length).sqrt() };
    (BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), law), scales)
}

/// The exact solution at η = 0: the weightless tight loop (straight spans, half-turn
/// arcs, uniform tension), sampled on `nodes` nodes per segment.
pub fn tight_start(problem: &BeltProblem<ScaledStringHanging>, nodes: usize) -> crate::solution::Solution {
    let p = &problem.law;
    let stretch = (2.0 + 2.0 * PI * p.radius) / p.length_start;
    tight_guess(problem, p.axial_stiffness * (stretch - 1.0), stretch, p.radius, nodes)
}

/// Solve a `string-hanging` scene from its data alone (homotopy of the note, then the
/// final solve with `opts.method` at `opts.tolerance`, then the balance and contact
/// checks).
pub fn solve(data: &StringHanging, opts: &BeltOptions) -> Result<StringHangingSolution, BeltError> {
    let clock = Instant::now();
    validate(data)?;
    opts.check_tolerance()?;
    let (problem, scales) = scaled_problem(data);
    let guess = tight_start(&problem, 5);
    let run = Run { data: *data, problem, scales, pulleys: data.pulleys(), guess: &guess, start: () };
    let length_start = run.problem.law.length_start * scales.length;
    solution::solve(run, opts, clock, |e, _| match e {
        StageError::Homotopy(cause) => homotopy_failure(data, length_start, cause),
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })
}

/// A stalled homotopy named by the scene quantity it was switching on: the weight
/// (η ≤ ½, at the tight length L₀) or the length L₀ → L (η > ½, full weight).
fn homotopy_failure(d: &StringHanging, length_start: f64, cause: BvpError) -> BeltError {
    const STAGE: &str = "the homotopy from the tight weightless loop";
    let BvpError::ContinuationStalled { eta, .. } = cause else {
        return BeltError::Solver { stage: STAGE, cause };
    };
    let weight = d.mass_per_length * d.gravity;
    let (at, hard) = if eta < 0.5 {
        (
            format!("switching on the weight: {} % of ρg = {} N/m at the tight length L₀ = {} m", Sig(200.0 * eta), Sig(weight), Sig(length_start)),
            format!("the weight against the axial stiffness, ρgL/EA = {}, makes it hard", Sig(weight * d.length / d.axial_stiffness)),
        )
    } else {
        let l = length_start + (2.0 * eta - 1.0) * (d.length - length_start);
        (
            format!("lengthening the belt under its weight: L = {} m on the way from L₀ = {} m to the scene's {} m", Sig(l), Sig(length_start), Sig(d.length)),
            format!("the slack L/L_geom = {} of the scene (L_geom = 2H + 2πR = {} m) makes it hard", Sig(d.length / d.geometric_length()), Sig(d.geometric_length())),
        )
    };
    BeltError::HomotopyStalled { stage: STAGE, eta, at, hard, cause }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stall is named by the phase of the two-phase homotopy: the weight (η ≤ ½, its
    /// fraction 2η) or the length (η > ½, L₀ + (2η − 1)(L − L₀)), with the scene's
    /// dimensionless number; other failures stay solver errors.
    #[test]
    fn stalls_name_the_phase_and_its_number() {
        let d = StringHanging { radius: 0.08, centre_distance: 0.45, length: 1.5, axial_stiffness: 2.0e4, mass_per_length: 0.12, gravity: 9.81 };
        let stall = |eta: f64| BvpError::ContinuationStalled { eta, step: 1e-9, min_step: 1e-8, cause: "diverged".into() };
        let e = homotopy_failure(&d, 1.4, stall(0.25)).to_string();
        assert!(e.contains("switching on the weight: 50 % of ρg = 1.1772 N/m at the tight length L₀ = 1.4 m"), "{e}");
        assert!(e.contains("ρgL/EA = 8.829e-5"), "{e}");
        let e = homotopy_failure(&d, 1.4, stall(0.75)).to_string();
        assert!(e.contains("L = 1.45 m on the way from L₀ = 1.4 m to the scene's 1.5 m"), "{e}");
        let slack = format!("L/L_geom = {}", Sig(1.5 / d.geometric_length()));
        assert!(e.contains(&slack), "{e}");
        assert!(e.ends_with("(continuation stalled at eta = 7.500000000e-1: step 1.000e-9 below minimum 1.0e-8 (diverged))"), "{e}");
        let other = homotopy_failure(&d, 1.4, BvpError::NonFinite { what: "x".into() });
        assert!(matches!(other, BeltError::Solver { .. }), "{other}");
    }
}
