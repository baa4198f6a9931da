//! `cosserat-pulley` (Paper C): a shear-deformable (Cosserat) belt in steady motion over
//! one rotating pulley with a stick then a slip zone, the open four-segment BVP of
//! docs/cosserat-pulley.md (spec §2.4), mode `tensions`: c, N_in, N_out given, the pulley
//! speed ω = cλ_B/R and the stick → slip angle φ_B computed.
//!
//! The belt theory is the section law [`law::ScaledCosseratPulley`] on the open
//! [`Topology::one_pulley`]; its span equations, contact-boundary rows and the force
//! (C2) are `cosserat_hanging`'s with the transport term χ = ρc². [`solve`] builds the
//! string creep solution with bending layers as the start (spec §2.4), runs the belt
//! machinery's homotopy (log a from a₀, = a unless the scene's bending layer is too thin
//! for the start, [`START_LAYER`]) and final solve by collocation or shooting, then the
//! moment balance (C-2) and the admissibility checks of spec §2.4
//! ([`CosseratPulleySolution::check_admissible`]).

pub mod law;
mod view;

use std::f64::consts::{FRAC_PI_2, PI};
use std::time::Instant;

use serde::Serialize;

use drive::summary::{PulleySummary, Summary};
use drive::scene::End;
use drive::OpenContour;

use crate::belt::balance::Balance;
use crate::belt::run::{self, StageError};
use crate::belt::solution::wrap_angle;
use crate::belt::topology::Scaling;
use crate::belt::{check_positive, ArcKind, BeltError, BeltOptions, BeltPoint, BeltProblem, Scales, SectionLaw, SegmentKind, Topology};
use crate::sigma_map::SigmaMap;
use crate::solution::{Solution, Stats};
pub use law::{Closing, ScaledCosseratPulley};
use law::LAMBDA_B;

/// Relative tolerance of the moment balance (C-2) against F_ref·R (as the other belt
/// balances, `belt::balance`).
pub const MOMENT_TOLERANCE: f64 = 1e-4;

/// The smallest bending layer √(a₀/T̃) of the homotopy start, relative to R: a scene
/// with a thinner layer starts at a₀ with this layer and continues in log a.
pub const START_LAYER: f64 = 0.05;

/// Which two of the four global quantities {N_in, N_out, ω, φ_B} a one-pulley scene
/// prescribes besides c (spec §2.3; the scene's `drive.tension_in`, `tension_out`,
/// `pulley_speed`, `stick_slip_angle`). A mode other than `Tensions` adds one unknown, the
/// free end's effective force, and one condition, its prescription.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Mode {
    /// N_in and N_out given (the data's `tension_in`, `tension_out`): ω and φ_B computed.
    Tensions,
    /// The stick → slip angle φ_B (rad) and the tension of the end `given`: ω and the
    /// other tension computed. φ_B fixes the slip arc, not its sense: `driving` chooses
    /// the pulley driving the belt (N_in > N_out) or braking it (N_in < N_out).
    Transition {
        /// φ_B, rad.
        stick_slip_angle: f64,
        /// The end whose tension is given.
        given: End,
        /// The pulley drives the belt (σ = +1) or brakes it (σ = −1).
        driving: bool,
    },
    /// ω (rad/s, clockwise positive) and N_out given: the stick stretch λ_B = ωR/c is
    /// known, N_in and φ_B computed. (With N_in given instead, ω carries no information
    /// about N_out: the stick zone sits on the inflow side and λ_B = λ(N_in) up to terms
    /// exponentially small in the stick arc over the edge layer — refused by the scene
    /// dispatch, `bvp::scene::cosserat_pulley_data`.)
    PulleySpeed {
        /// ω, rad/s.
        pulley_speed: f64,
    },
}

/// The pulley speed ω given with N_in does not determine N_out (see [`Mode::PulleySpeed`]).
pub const PULLEY_SPEED_WITH_TENSION_IN: &str = "ω fixes the stick stretch λ_B = ωR/c, and the stick zone sits on the inflow side, so λ_B ≈ λ(N_in): ω and N_in together leave N_out undetermined (up to exponentially small terms); prescribe `pulley_speed` with `tension_out`";

/// Physical data of a one-pulley scene (SI units). In a mode other than
/// [`Mode::Tensions`] the free end's tension holds the string estimate of the start
/// ([`CosseratPulley::with_mode`]) until the solve replaces it by the solved value.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CosseratPulley {
    /// Pulley radius R to the belt centreline (m).
    pub radius: f64,
    /// Distance D of the end sections x = −D from the pulley centre (m).
    pub end_distance: f64,
    /// Transport rate c (m/s).
    pub transport_rate: f64,
    /// Axial force at the inflow end N_in (N).
    pub tension_in: f64,
    /// Axial force at the outflow end N_out (N).
    pub tension_out: f64,
    /// b₁ (N).
    pub axial_stiffness: f64,
    /// a (N·m²).
    pub bending_stiffness: f64,
    /// b₂ (N).
    pub shear_stiffness: f64,
    /// ρ (kg/m).
    pub mass_per_length: f64,
    /// Coulomb coefficient μ.
    pub friction: f64,
    /// Persistent transport inertia on (χ = ρc²) or off (χ = 0).
    pub inertia: bool,
    /// The prescription mode.
    pub mode: Mode,
}

impl CosseratPulley {
    /// χ = ρc² with the inertia effect, else 0 (N).
    pub fn chi(&self) -> f64 {
        if self.inertia { self.mass_per_length * self.transport_rate * self.transport_rate } else { 0.0 }
    }

    /// F̃·e₁ = T̃ = N − χ(1 + N/b₁) of an end section with axial force N and Q = 0 (spec §2.3).
    pub fn effective(&self, tension: f64) -> f64 {
        tension - self.chi() * (1.0 + tension / self.axial_stiffness)
    }

    /// The stretch of a straight section with T̃: T̃ = b₁(λ − 1) − χλ.
    pub fn stretch(&self, effective: f64) -> f64 {
        (effective + self.axial_stiffness) / (self.axial_stiffness - self.chi())
    }

    /// Slip sign σ: +1 when N_in ≥ N_out (the pulley drives the belt), −1 when it brakes.
    pub fn slip_sign(&self) -> f64 {
        if self.tension_in >= self.tension_out { 1.0 } else { -1.0 }
    }

    /// The string creep (a → 0) slip arc ln(T̃_high/T̃_low)/μ (rad), spec C-9.
    pub fn string_slip_arc(&self) -> f64 {
        (self.effective(self.tension_in) / self.effective(self.tension_out)).ln().abs() / self.friction
    }

    /// The shear layer ℓ_s = √(a/(b₂ − χ)) (m) of the edge pressure peaks (spec §1.8).
    pub fn shear_layer(&self) -> f64 {
        (self.bending_stiffness / (self.shear_stiffness - self.chi())).sqrt()
    }

    /// N of an end section with T̃ (Q = 0): the inverse of [`CosseratPulley::effective`].
    pub fn tension_of(&self, effective: f64) -> f64 {
        (effective + self.chi()) / (1.0 - self.chi() / self.axial_stiffness)
    }

    /// The end whose tension the solve computes: 0 inflow, 1 outflow; `None` in mode
    /// `tensions`.
    pub fn free_end(&self) -> Option<usize> {
        match self.mode {
            Mode::Tensions => None,
            Mode::Transition { given: End::In, .. } => Some(1),
            Mode::Transition { given: End::Out, .. } | Mode::PulleySpeed { .. } => Some(0),
        }
    }

    /// The data in `mode`, the free end's tension set to the string estimate of the start
    /// (spec §2.4): mode `pulley_speed` the stick section's T̃ at λ_B = ωR/c; mode
    /// `transition` the capstan T̃_high = T̃_low e^{μ(φ_B − φ_C)} over the slip arc from φ_B
    /// to the string contact end φ_C = −π/2 + √(a/T̃_out)/R. The given tension is read
    /// from its field.
    ///
    /// # Errors
    /// [`BeltError::InvalidInput`] when the prescription has no positive effective
    /// tension or no slip arc (φ_B below the contact end).
    pub fn with_mode(self, mode: Mode) -> Result<CosseratPulley, BeltError> {
        let mut d = CosseratPulley { mode, ..self };
        let contact_end = |t_out: f64| -FRAC_PI_2 + (d.bending_stiffness / t_out).sqrt() / d.radius;
        match mode {
            Mode::Tensions => {}
            Mode::PulleySpeed { pulley_speed } => {
                check_positive(&[("pulley_speed", pulley_speed), ("transport_rate", d.transport_rate)])?;
                let stretch = pulley_speed * d.radius / d.transport_rate;
                let effective = (d.axial_stiffness - d.chi()) * stretch - d.axial_stiffness;
                if effective.is_nan() || effective <= 0.0 {
                    return Err(BeltError::InvalidInput { name: "pulley_speed", value: pulley_speed, reason: "the stick stretch ωR/c leaves no positive effective tension at the inflow end" });
                }
                d.tension_in = d.tension_of(effective);
            }
            Mode::Transition { stick_slip_angle, given, driving } => {
                let sm = if driving { d.friction } else { -d.friction };
                let known = d.effective(match given {
                    End::In => d.tension_in,
                    End::Out => d.tension_out,
                });
                if !(known > 0.0 && sm.is_finite()) {
                    return Err(BeltError::InvalidInput { name: "tension", value: known, reason: "the given end has no positive effective tension" });
                }
                // T̃_in = T̃_out e^{σμ(φ_B − φ_C)}; with T̃_in given, φ_C depends on T̃_out: a
                // fixed point (a contraction: ∂φ_C/∂T̃_out ≪ 1/(μT̃))
                let mut t_out = known;
                for _ in 0..30 {
                    let arc = stick_slip_angle - contact_end(t_out);
                    if arc.is_nan() || arc < 0.0 {
                        return Err(BeltError::InvalidInput { name: "stick_slip_angle", value: stick_slip_angle, reason: "the stick → slip angle lies below the contact end φ_C ≈ −π/2 + √(a/T̃_out)/R: no slip arc" });
                    }
                    if given == End::Out {
                        d.tension_in = d.tension_of(known * (sm * arc).exp());
                        break;
                    }
                    t_out = known * (-sm * arc).exp();
                }
                if given == End::In {
                    d.tension_out = d.tension_of(t_out);
                }
            }
        }
        Ok(d)
    }
}

/// Validate the data (spec §2.2): every input finite and > 0, b₁, b₂ > χ, T̃ > 0 at both
/// ends. (The string creep slip arc beyond the wrap is not a refusal: the rod's edge
/// pressure peaks carry friction the string has not, [`solve`].)
pub fn validate(d: &CosseratPulley, opts: &BeltOptions) -> Result<(), BeltError> {
    opts.check_tolerance()?;
    let geometry = [("pulley_radius", d.radius), ("end_distance", d.end_distance), ("transport_rate", d.transport_rate)];
    let loads = [("tension_in", d.tension_in), ("tension_out", d.tension_out), ("coulomb", d.friction)];
    let section = [("axial_stiffness", d.axial_stiffness), ("bending_stiffness", d.bending_stiffness), ("shear_stiffness", d.shear_stiffness), ("mass_per_length", d.mass_per_length)];
    check_positive(&[&geometry[..], &loads, &section].concat())?;
    let chi = d.chi();
    for (stiffness, value) in [("axial stiffness b₁", d.axial_stiffness), ("shear stiffness b₂", d.shear_stiffness)] {
        if chi >= value {
            let critical_rate = (value / d.mass_per_length).sqrt();
            return Err(BeltError::SpeedAtOrAboveCritical { stiffness, value, chi, transport_rate: d.transport_rate, critical_rate });
        }
    }
    for (end, tension) in [("inflow", d.tension_in), ("outflow", d.tension_out)] {
        let effective = d.effective(tension);
        if effective <= 0.0 {
            return Err(BeltError::EffectiveTensionNotPositive { end, tension, effective, chi });
        }
    }
    Ok(())
}

/// The string's estimate of the contact arc, π − (√(a/T̃_in) + √(a/T̃_out))/R (rad): the
/// wrap less the two bending layers.
fn string_contact_arc(d: &CosseratPulley) -> f64 {
    let (t_in, t_out) = (d.effective(d.tension_in), d.effective(d.tension_out));
    PI - ((d.bending_stiffness / t_in).sqrt() + (d.bending_stiffness / t_out).sqrt()) / d.radius
}

/// Mode `tensions` beyond the string's capstan ([`solve`]): the larger tension given,
/// the other free, φ_B searched from the middle of the string contact arc toward the
/// contact start (the slip arc growing, the free tension moving away from the given) until
/// the free tension passes the scene's; Brent's method on that bracket; then the
/// `tensions` solve from the root's solution (its parameters less the free end's force).
fn beyond_the_capstan(data: &CosseratPulley, opts: &BeltOptions, clock: Instant) -> Result<CosseratPulleySolution, BeltError> {
    let driving = data.tension_in >= data.tension_out;
    let (given, target, free_name) = if driving { (End::In, data.tension_out, "outflow") } else { (End::Out, data.tension_in, "inflow") };
    // continued from a solution at a nearby φ_B (near the contact start the string creep
    // start is too far off: braking N_in = 7, N_out = 15 N failed from it 0.13 rad before
    // the contact start), else from the creep start
    let at = |phi: f64, from: Option<&Solution>| -> Result<CosseratPulleySolution, BeltError> {
        let d = data.with_mode(Mode::Transition { stick_slip_angle: phi, given, driving })?;
        match from.map(|f| solve_from(&d, opts, Some(f), clock)) {
            Some(Ok(s)) => Ok(s),
            _ => solve_from(&d, opts, None, clock),
        }
    };
    let free = |s: &CosseratPulleySolution| if driving { s.data.tension_out } else { s.data.tension_in };
    // g > 0: the free tension (the smaller) still above the scene's, nearer the given
    // one — too little slip
    let g = |s: &CosseratPulleySolution| (free(s) - target) / target;
    let contact = string_contact_arc(data);
    let phi_c = -FRAC_PI_2 + (data.bending_stiffness / data.effective(data.tension_out)).sqrt() / data.radius;
    let mut lo = phi_c + 0.5 * contact;
    let mut s_lo = at(lo, None)?;
    let mut work = s_lo.stats.clone();
    let mut hi = None;
    // the free tension met with less than half the string contact arc of slip (large μ:
    // the edge peaks carry most of it): the bracket lies below, toward the contact end
    if g(&s_lo) <= 0.0 {
        let mut upper = (lo, s_lo);
        let mut found = None;
        for _ in 0..20 {
            let phi = phi_c + 0.5 * (upper.0 - phi_c);
            let s = at(phi, Some(&upper.1.solution))?;
            work.add_iterations(&s.stats);
            if g(&s) > 0.0 {
                found = Some((phi, s));
                break;
            }
            upper = (phi, s);
        }
        let Some(lower) = found else {
            return Err(BeltError::Inadmissible(format!("mode `tensions` beyond the string's capstan: no stick → slip angle above the contact end φ_C ≈ {phi_c:.6} rad leaves the {free_name} tension above {target} N")));
        };
        (lo, s_lo) = lower;
        hi = Some(upper);
    }
    // toward the contact start of the last solution, each step half the stick arc left
    // (a quarter of the step after a failed solve, down to 1e-3 of the stick arc); the
    // capacity is met when the stick arc is gone (1e-9 of the contact arc)
    let mut frac = 0.5;
    let mut last_failure = None;
    for _ in 0..80 {
        if hi.is_some() {
            break;
        }
        let [a, b, _] = s_lo.contact_angles();
        let stick = a - b;
        if stick <= 1e-9 * contact {
            return Err(BeltError::CapstanLimitExceeded {
                end: free_name,
                target,
                reached: free(&s_lo),
                stick_arc: stick,
                string_slip_arc: data.string_slip_arc(),
                contact_arc: contact,
                mu: data.friction,
            });
        }
        let phi = lo + frac * stick;
        match at(phi, Some(&s_lo.solution)) {
            Ok(s) => {
                work.add_iterations(&s.stats);
                if g(&s) <= 0.0 {
                    hi = Some((phi, s));
                } else {
                    (lo, s_lo, frac) = (phi, s, (2.0 * frac).min(0.5));
                }
            }
            Err(cause) => {
                last_failure = Some((phi, cause));
                frac /= 4.0;
                if frac < 1e-3 {
                    break;
                }
            }
        }
    }
    let Some((hi, s_hi)) = hi else {
        let [a, b, _] = s_lo.contact_angles();
        let (phi, cause) = last_failure.unwrap_or((lo, BeltError::Inadmissible("80 steps".into())));
        return Err(BeltError::CapstanSearchFailed { end: free_name, target, reached: free(&s_lo), stick_arc: a - b, phi, cause: Box::new(cause) });
    };
    let mut best = s_hi;
    let root = numerics::roots::brent(
        |phi: f64| -> Result<f64, BeltError> {
            let s = at(phi, Some(&best.solution))?;
            work.add_iterations(&s.stats);
            let v = g(&s);
            if v.abs() < g(&best).abs() {
                best = s;
            }
            Ok(v)
        },
        lo,
        hi,
        1e-10,
    );
    if let Err(e) = root {
        return Err(BeltError::Inadmissible(format!("mode `tensions` beyond the string's capstan: the search of φ_B for the {free_name} tension {target} N failed ({e})")));
    }
    let mut start = best.solution.clone();
    start.params.truncate(LAMBDA_B + 1);
    let mut sol = solve_from(data, opts, Some(&start), clock)?;
    work.add_iterations(&sol.stats);
    sol.stats.newton_iterations = work.newton_iterations;
    sol.stats.jacobian_evaluations = work.jacobian_evaluations;
    sol.stats.refinements = work.refinements;
    Ok(sol)
}

/// Stick and slip arcs below this (rad) are round-off, not zones: the pure-stick
/// solution (N_in = N_out) has a slip arc of ~1e-16 and no stick → slip point.
const SLIP_ARC_FLOOR: f64 = 1e-12;

/// A solved one-pulley scene: data, the scaled problem on the open topology, the BVP
/// solution at η = 1, scales and the work of the run.
#[derive(Debug, Clone)]
pub struct CosseratPulleySolution {
    /// The physical data.
    pub data: CosseratPulley,
    /// The scaled problem.
    pub problem: BeltProblem<ScaledCosseratPulley>,
    /// The BVP solution (scaled).
    pub solution: Solution,
    /// Scales: length R, force F_ref = max(N_in, N_out), speed √(F_ref/ρ).
    pub scales: Scales,
    /// Options of the run.
    pub options: BeltOptions,
    /// Work of homotopy and final solve.
    pub stats: Stats,
    /// Accepted homotopy points (start included).
    pub homotopy_steps: usize,
    /// σ on the open contour at dense samples (the common view's lookup).
    sigma_map: SigmaMap,
}

/// The scaled law of the data at the homotopy start a₀ (spec §2.4).
fn scaled(d: &CosseratPulley) -> (ScaledCosseratPulley, Scales) {
    let fr = d.tension_in.max(d.tension_out);
    let r = d.radius;
    let scales = Scales { length: r, force: fr, speed: (fr / d.mass_per_length).sqrt() };
    let bending = d.bending_stiffness / (fr * r * r);
    let t_min = d.effective(d.tension_in).min(d.effective(d.tension_out)) / fr;
    // the layer √(a/T̃) of the start at least START_LAYER·R
    let bending_start = bending.max(START_LAYER * START_LAYER * t_min);
    let law = ScaledCosseratPulley {
        axial: d.axial_stiffness / fr,
        shear: d.shear_stiffness / fr,
        chi: d.chi() / fr,
        bending_start,
        bending,
        end_distance: d.end_distance / r,
        end_forces: [d.effective(d.tension_in) / fr, d.effective(d.tension_out) / fr],
        mu: d.friction,
        slip_sign: d.slip_sign(),
        free_end: d.free_end(),
        closing: match d.mode {
            Mode::Tensions => Closing::None,
            Mode::Transition { stick_slip_angle, .. } => Closing::StickSlipAngle(stick_slip_angle),
            Mode::PulleySpeed { pulley_speed } => Closing::StickStretch(pulley_speed * d.radius / d.transport_rate),
        },
    };
    (law, scales)
}

/// The start (scaled, η = 0, bending stiffness a₀): the string creep solution (stick at
/// T̃_in, slip with T̃ = T̃_in e^{σμ(φ − φ_B)}, φ_B from the capstan) with zero shear on the
/// arcs, θ = φ − π/2, M = −a₀λ/R, exponential bending layers of length ℓ = √(a₀/T̃) in
/// the spans and contact angles π/2 − ℓ_in/R, −π/2 + ℓ_out/R (spec §2.4).
pub fn creep_guess(d: &CosseratPulley, law: &ScaledCosseratPulley, nodes: usize) -> Solution {
    let fr = d.tension_in.max(d.tension_out);
    let a = law.bending_start;
    let [t_in, t_out] = law.end_forces;
    let lam = |t: f64| d.stretch(t * fr);
    let (l_in, l_out) = ((a / t_in).sqrt(), (a / t_out).sqrt());
    let (phi_a, phi_c) = (FRAC_PI_2 - l_in, -FRAC_PI_2 + l_out);
    let phi_b = (phi_c + d.string_slip_arc()).min(phi_a);
    let sm = law.slip_sign * law.mu;
    let dd = law.end_distance;
    let (xa, xc) = (phi_a.cos(), phi_c.cos());
    let (lam_b, lam_out) = (lam(t_in), lam(t_out));
    let (l0, l3) = ((xa + dd) / lam_b, (xc + dd) / lam_out);
    let t_slip = |phi: f64| t_in * (sm * (phi - phi_b)).exp();
    let s_b = l0 + (phi_a - phi_b) / lam_b;
    // s on the slip arc by the trapezoidal rule over 64 steps of 1/λ
    let s_slip = |phi: f64| {
        let n = 64;
        let h = (phi_b - phi) / n as f64;
        (0..n).map(|i| 0.5 * h * (1.0 / lam(t_slip(phi_b - i as f64 * h)) + 1.0 / lam(t_slip(phi_b - (i + 1) as f64 * h)))).sum::<f64>()
    };
    let s_c = s_b + s_slip(phi_c);
    let mut params = vec![l0, l3, phi_a, phi_b, phi_c, lam_b];
    params.extend(law.free_end.map(|e| law.end_forces[e]));
    Solution::from_fn(4, nodes, params, 0.0, |k, xi| match k {
        0 => {
            let x = -dd + (xa + dd) * xi;
            let e = ((x - xa) / l_in).exp();
            let theta_a = -l_in;
            vec![x, phi_a.sin() + theta_a * l_in * (e - 1.0), theta_a * e, a * theta_a / l_in * e, t_in, 0.0, l0 * xi]
        }
        1 => {
            let phi = phi_a + (phi_b - phi_a) * xi;
            vec![phi - FRAC_PI_2, -a * lam_b, l0 + (phi_a - phi) / lam_b, 0.0]
        }
        2 => {
            let phi = phi_b + (phi_c - phi_b) * xi;
            let t = t_slip(phi);
            vec![phi - FRAC_PI_2, -a * lam(t), s_b + s_slip(phi), t - t_in, lam(t)]
        }
        _ => {
            let x = xc - (xc + dd) * xi;
            let e = (-(xc - x) / l_out).exp();
            let theta = -PI + l_out * e;
            vec![x, phi_c.sin() - l_out * l_out * (1.0 - e), theta, -a * e, t_out * theta.cos(), t_out * theta.sin(), s_c + l3 * xi]
        }
    })
}

/// The moment balance about the pulley centre (spec §1.7, C-2): the torque τ(C) =
/// −R∫f_t ds equals −[M + k·(r × F̃)]_in^out; checked to [`MOMENT_TOLERANCE`]·F_ref·R.
/// `point(k, ξ)` is the solution's point output.
pub fn check_moment_balance(d: &CosseratPulley, point: impl Fn(usize, f64) -> BeltPoint) -> Result<(), BeltError> {
    let value = moment_imbalance(d, point);
    let scale = d.tension_in.max(d.tension_out) * d.radius;
    Balance { name: "moment imbalance about the pulley centre", value, unit: "N·m", scale, scale_name: "moment scale F_ref·R", tolerance: MOMENT_TOLERANCE }
        .check()
}

/// τ(C) + [M + k·(r × F̃)]_in^out (N·m), 0 for the exact solution (C-2).
pub fn moment_imbalance(d: &CosseratPulley, point: impl Fn(usize, f64) -> BeltPoint) -> f64 {
    let (inflow, outflow, last_contact) = (point(0, 0.0), point(3, 1.0), point(2, 1.0));
    let moment_of = |p: &BeltPoint| {
        let f = effective_force(d, p);
        p.moment.unwrap_or(0.0) + p.x * f[1] - p.y * f[0]
    };
    last_contact.torque.unwrap_or(f64::NAN) + moment_of(&outflow) - moment_of(&inflow)
}

/// The effective force F̃ (N) of a point: F̃·e₁ = T̃, F̃·e₂ = Q (b₂ − χ)/b₂ (spec §1.2).
pub fn effective_force(d: &CosseratPulley, p: &BeltPoint) -> [f64; 2] {
    let theta = p.theta.unwrap_or(f64::NAN);
    let (te, qe) = (p.effective_tension.unwrap_or(f64::NAN), p.shear.unwrap_or(f64::NAN) * (d.shear_stiffness - d.chi()) / d.shear_stiffness);
    let (c, s) = (theta.cos(), theta.sin());
    [te * c - qe * s, te * s + qe * c]
}

/// Solve a one-pulley scene in mode `tensions` from its data alone (module docs).
///
/// Mode `tensions` with a tension ratio beyond the string's capstan over the wrap
/// (ln(T̃_high/T̃_low)/μ ≥ the string contact arc) has no string start; the rod may still
/// carry it (μ times its edge pressure peaks adds friction, docs/cosserat-pulley.md). Such
/// a scene is solved through mode `transition` (the larger tension given, φ_B searched
/// toward the contact start until the other tension is met) and then in mode `tensions`
/// from that solution; where φ_B reaches the contact start first,
/// [`BeltError::CapstanLimitExceeded`] names the tension the friction can hold.
pub fn solve(data: &CosseratPulley, opts: &BeltOptions) -> Result<CosseratPulleySolution, BeltError> {
    let clock = Instant::now();
    validate(data, opts)?;
    let across_layer = |e| crate::belt::error::across_layer(e, opts, data.shear_layer(), PI * data.radius);
    if data.mode == Mode::Tensions && data.string_slip_arc() >= string_contact_arc(data) {
        return beyond_the_capstan(data, opts, clock).map_err(across_layer);
    }
    solve_from(data, opts, None, clock).map_err(across_layer)
}

/// [`solve`] after validation, from `start` (a solution at η = 1 of the same topology
/// and parameters) or else the string creep start with its homotopy.
fn solve_from(data: &CosseratPulley, opts: &BeltOptions, start: Option<&Solution>, clock: Instant) -> Result<CosseratPulleySolution, BeltError> {
    let contour = OpenContour::new(data.radius, data.end_distance)
        .map_err(|_| BeltError::InvalidInput { name: "end_distance", value: data.end_distance, reason: "R and D must be finite and > 0" })?;
    let (law, scales) = scaled(data);
    let guess = creep_guess(data, &law, 41);
    let problem = BeltProblem::new(Topology::one_pulley(), law);
    let (window, slack) = problem.law.admissible_window();
    let accept = |s: &Solution| problem.topology.check(&s.params, window, slack);
    // the start at the scene's a needs no homotopy: straight to the path and final solves
    let stages = if let Some(start) = start {
        run::direct_and_final_solve(&problem, start, opts, clock)
    } else if problem.law.bending_start == problem.law.bending {
        run::direct_and_final_solve(&problem, &Solution { eta: 1.0, ..guess }, opts, clock)
    } else {
        run::homotopy_and_final_solve(&problem, &guess, opts, accept, clock)
    };
    let hard = || format!("bending layer √(a/T̃_out) = {:.3e} R, shear layer √(a/(b₂ − ρc²)) = {:.3e} R", (data.bending_stiffness / data.effective(data.tension_out)).sqrt() / data.radius, data.shear_layer() / data.radius);
    // without a path in a the first solve is the start itself: no homotopy to have stalled
    let direct = start.is_some() || problem.law.bending_start == problem.law.bending;
    let solved = stages.map_err(|e| match e {
        StageError::Homotopy(cause) if direct => BeltError::StartFailed {
            stage: if start.is_some() { "the solve from the previous solution" } else { "the solve at the scene's a from the string's creep state (no continuation in a needed)" },
            hard: hard(),
            cause,
        },
        StageError::Homotopy(cause) => BeltError::HomotopyStalled {
            stage: "homotopy in log a",
            // a failure before the first continuation step is the corrector at the start
            eta: match &cause {
                crate::error::BvpError::ContinuationStalled { eta, .. } => *eta,
                _ => 0.0,
            },
            at: format!("bending stiffness from a₀ = {:.3e} N·m² to a = {:.3e} N·m²", problem.law.bending_start * scales.force * scales.length * scales.length, data.bending_stiffness),
            hard: hard(),
            cause,
        },
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })?;
    let mut sol = CosseratPulleySolution {
        data: *data,
        problem,
        solution: solved.solution,
        scales,
        options: opts.clone(),
        stats: solved.stats,
        homotopy_steps: solved.homotopy_steps,
        sigma_map: SigmaMap::empty(contour),
    };
    check_moment_balance(&sol.data, |k, xi| sol.point(k, xi))?;
    sol.check_admissible()?;
    // the free end's tension: its start estimate replaced by the solved value
    match sol.data.free_end() {
        Some(0) => sol.data.tension_in = sol.point(0, 0.0).tension,
        Some(_) => sol.data.tension_out = sol.point(3, 1.0).tension,
        None => {}
    }
    sol.sigma_map = sol.build_sigma_map();
    Ok(sol)
}

impl CosseratPulleySolution {
    /// The belt at segment `k` (0 inflow span, 1 stick, 2 slip, 3 outflow span), ξ ∈ [0, 1].
    pub fn point(&self, k: usize, xi: f64) -> BeltPoint {
        let y = self.solution.segments[k].state_at(xi);
        let p = &self.solution.params;
        let topo = &self.problem.topology;
        let phi = match topo.segment(k).scaling {
            Scaling::Arc { start, end, .. } => Some(p[start] + xi.clamp(0.0, 1.0) * (p[end] - p[start])),
            Scaling::Span { .. } => None,
        };
        self.problem.law.point(&self.data, &self.scales, topo, k, phi, &y, p)
    }

    /// Points at every mesh node and `per_interval` − 1 dense points per interval, with
    /// their segment and ξ, in the direction of travel.
    pub fn samples(&self, per_interval: usize) -> Vec<(usize, f64, BeltPoint)> {
        self.solution.sample_points(per_interval).into_iter().map(|(k, xi)| (k, xi, self.point(k, xi))).collect()
    }

    /// Contact angles (φ_A, φ_B, φ_C), rad.
    pub fn contact_angles(&self) -> [f64; 3] {
        let p = &self.solution.params;
        [p[2], p[3], p[4]]
    }

    /// Stick stretch λ_B.
    pub fn stick_stretch(&self) -> f64 {
        self.solution.params[LAMBDA_B]
    }

    /// Pulley speed ω = cλ_B/R (rad/s, clockwise positive), the stick kinematics (C-5).
    pub fn pulley_speed(&self) -> f64 {
        self.data.transport_rate * self.stick_stretch() / self.data.radius
    }

    /// Torque of the belt on the pulley, −R∫f_t ds (N·m, clockwise positive).
    pub fn torque(&self) -> f64 {
        self.point(2, 1.0).torque.unwrap_or(f64::NAN)
    }

    /// Slip dissipation D = ∫_slip f_t (ωR − cλ) ds ≥ 0 (W), by 5-point Gauss–Legendre
    /// quadrature on each mesh interval of the slip arc's dense output
    /// ([`crate::belt::solution::arc_integral`]), as the loop's [`crate::belt::solution::BeltSolution::slip_dissipation`].
    pub fn dissipation(&self) -> f64 {
        let (w, r, c) = (self.pulley_speed(), self.data.radius, self.data.transport_rate);
        let [_, b, cc] = self.contact_angles();
        crate::belt::solution::arc_integral(&self.solution.segments[2].mesh, (b - cc).abs(), r, |xi| self.point(2, xi), |p| p.friction.unwrap_or(0.0) * (w * r - c * p.stretch))
    }

    /// The largest value of `f` over the contact zone (the stick arc 1 and the slip arc
    /// 2, edges included) by [`crate::belt::solution::sampled_extremum`]; its smallest:
    /// pass −f.
    pub fn arc_extremum(&self, f: impl Fn(&BeltPoint) -> f64) -> f64 {
        let meshes: Vec<(usize, &[f64])> = [1, 2].into_iter().map(|k| (k, self.solution.segments[k].mesh.as_slice())).collect();
        crate::belt::solution::sampled_extremum(&meshes, |k, xi| f(&self.point(k, xi)))
    }

    /// The admissibility of the stick/slip topology (spec §2.4): φ_A > φ_B ≥ φ_C, p > 0
    /// on both arcs, |f_t| ≤ μp in stick, the slip direction (λ ≤ λ_B driving, ≥ λ_B
    /// braking) in slip, T̃ > 0, spans outside the pulley. Each failure names its numbers.
    pub fn check_admissible(&self) -> Result<(), BeltError> {
        let bad = BeltError::Inadmissible;
        let [a, b, c] = self.contact_angles();
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(a > b && b >= c - 1e-9) {
            return Err(bad(format!("contact angles out of order: φ_A = {a:.6}, φ_B = {b:.6}, φ_C = {c:.6} rad (need φ_A > φ_B ≥ φ_C)")));
        }
        let (mu, sign, lam_b) = (self.data.friction, self.data.slip_sign(), self.stick_stretch());
        let (r, fr) = (self.data.radius, self.scales.force);
        let floor = 1e-9 * fr / r;
        for (k, xi, pt) in self.samples(4) {
            let te = pt.effective_tension.unwrap_or(f64::NAN);
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(te > 0.0) {
                return Err(bad(format!("effective tension T̃ = {te:.4e} N ≤ 0 at ({:.5}, {:.5}) m", pt.x, pt.y)));
            }
            let kind = self.problem.topology.segment(k).kind;
            if kind == SegmentKind::Span {
                let dist = pt.x.hypot(pt.y);
                let edge = (k == 0 && xi == 1.0) || (k == 3 && xi == 0.0);
                if !edge && dist < r * (1.0 - 1e-9) {
                    return Err(bad(format!("free span inside the pulley: distance {dist:.6e} m < R = {r:.6e} m at ({:.5}, {:.5}) m", pt.x, pt.y)));
                }
                continue;
            }
            let (p, ft) = (pt.pressure.unwrap_or(f64::NAN), pt.friction.unwrap_or(f64::NAN));
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(p > 0.0) {
                return Err(bad(format!("contact pressure p = {p:.4e} N/m ≤ 0 at φ = {:.6} rad: the belt lifts off inside the arc", pt.angle.unwrap_or(f64::NAN))));
            }
            if kind == SegmentKind::Arc(ArcKind::Stick) && ft.abs() > mu * p + floor {
                return Err(bad(format!(
                    "stick zone needs |f_t| = {:.4e} N/m > μp = {:.4e} N/m at φ = {:.6} rad",
                    ft.abs(),
                    mu * p,
                    pt.angle.unwrap_or(f64::NAN)
                )));
            }
            if kind == SegmentKind::Arc(ArcKind::Slip) && sign * (pt.stretch - lam_b) > 1e-12 {
                return Err(bad(format!(
                    "slip direction reversed: λ = {:.12} against λ_B = {lam_b:.12} at φ = {:.6} rad (σ = {sign})",
                    pt.stretch,
                    pt.angle.unwrap_or(f64::NAN)
                )));
            }
        }
        Ok(())
    }

    /// The summary (issue 13, "Outputs", and spec §2.6's additions): the single pulley under `pulley.*`, the end
    /// quantities, ω and c; quantities the scene does not produce stay absent.
    pub fn summary(&self) -> Summary {
        let [a, b, c] = self.contact_angles();
        let (inflow, outflow) = (self.point(0, 0.0), self.point(3, 1.0));
        Summary {
            transport_rate: Some(self.data.transport_rate),
            pulley_speed: Some(self.pulley_speed()),
            tension_in: Some(inflow.tension),
            tension_out: Some(outflow.tension),
            y_in: Some(inflow.y),
            y_out: Some(outflow.y),
            pulley: Some(PulleySummary {
                contact_arc: Some(a - c),
                contact_start: Some(wrap_angle(a)),
                contact_end: Some(wrap_angle(c)),
                stick_arc: Some(a - b),
                slip_arc: Some(b - c),
                torque: Some(self.torque()),
                edge_pressure_start: self.point(1, 0.0).pressure,
                edge_pressure_end: self.point(2, 1.0).pressure,
                pressure_min: Some(-self.arc_extremum(|p| -p.pressure.unwrap_or(f64::NAN))).filter(|v| v.is_finite()),
                // a stick → slip point only between a stick and a slip zone (pure stick,
                // N_in = N_out: the slip arc is 0 to round-off and B is C, not a transition)
                stick_slip_angle: (a - b > SLIP_ARC_FLOOR && b - c > SLIP_ARC_FLOOR).then(|| wrap_angle(b)),
                shear_strain_max: Some(self.arc_extremum(|p| p.shear_strain.map_or(f64::NAN, f64::abs))).filter(|v| v.is_finite()),
                moment_start: self.point(1, 0.0).moment,
                moment_end: self.point(2, 1.0).moment,
                stretch_stick: Some(self.stick_stretch()),
                dissipation: Some(self.dissipation()),
                ..PulleySummary::default()
            }),
            ..Summary::default()
        }
    }

    /// The law's first integral E of (C5) at a point (N).
    pub fn invariant(&self, point: &BeltPoint) -> f64 {
        ScaledCosseratPulley::first_integral(&self.data, point).unwrap_or(f64::NAN)
    }
}
