//! `string-drive`: the steady friction drive of an extensible string on two pulleys, as
//! the eight-segment BVP derived in `docs/string-drive.md` (free spans, a stick zone and
//! a slip zone on each pulley; Paper B, §8.2 of the reference; Coulomb law of §6.1).
//!
//! [`solve`] checks the data (named errors for the cases with no steady solution, exact
//! without gravity by [`crate::analytical::belt_creep`]), reaches the scene from the tight
//! loop at rest by the three-phase homotopy of the note (torque, then gravity and
//! length, then speed), solves at the requested tolerance with the requested method and
//! checks the topology and the contact law. [`StringDriveSolution`] implements the
//! common [`drive::view::SolutionView`] (module `view`).

pub mod problem;
pub mod view;

use std::cell::RefCell;
use std::f64::consts::PI;
use std::time::Instant;

use serde::Serialize;

use crate::analytical::belt_creep::{CreepData, CreepError, CreepSolution};
use crate::belt::run::{self, StageError};
use crate::belt::{balance, BeltError, BeltOptions};
use crate::error::BvpError;
use crate::solution::{Solution, Stats};
pub use problem::ScaledStringDrive;
use problem::*;

/// Physical data of a steady drive scene (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StringDrive {
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
    /// Gravity g ≥ 0 (m/s²); 0 = no gravity effect.
    pub gravity: f64,
    /// Persistent transport inertia (ρc² terms).
    pub inertia: bool,
    /// Coulomb coefficient μ > 0.
    pub friction: f64,
    /// Driver speed ω₁ ≥ 0 (rad/s, clockwise).
    pub driver_speed: f64,
    /// Resisting torque M₂ ≥ 0 (N·m).
    pub driven_torque: f64,
    /// Viscous damping d₂ ≥ 0 of the driven pulley (N·m·s).
    pub driven_damping: f64,
}

impl StringDrive {
    /// L_geom = 2H + 2πR.
    pub fn geometric_length(&self) -> f64 {
        2.0 * self.centre_distance + 2.0 * PI * self.radius
    }

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
}

/// Scales of the nondimensionalisation (docs/string-drive.md, "Scaling").
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Scales {
    /// Length H (m).
    pub length: f64,
    /// Force F_ref (N).
    pub force: f64,
    /// Speed V = √(F_ref/ρ) (m/s).
    pub speed: f64,
}

/// A solved steady drive.
#[derive(Debug, Clone)]
pub struct StringDriveSolution {
    /// The physical data.
    pub data: StringDrive,
    /// The scaled problem.
    pub problem: ScaledStringDrive,
    /// The BVP solution (scaled) at η = 1.
    pub solution: Solution,
    /// Scales.
    pub scales: Scales,
    /// Options of the run (method and tolerance of the final solve among them).
    pub options: BeltOptions,
    /// Work of the whole run (homotopy + final solve).
    pub stats: Stats,
    /// Accepted homotopy steps.
    pub homotopy_steps: usize,
    sigma_map: crate::sigma_map::SigmaMap,
}

fn validate(d: &StringDrive) -> Result<(), BeltError> {
    crate::belt::check_positive(&[
        ("pulley_radius", d.radius),
        ("centre_distance", d.centre_distance),
        ("length", d.length),
        ("axial_stiffness", d.axial_stiffness),
        ("mass_per_length", d.mass_per_length),
    ])?;
    let non_negative = [
        ("gravity", d.gravity),
        ("driver_speed", d.driver_speed),
        ("driven_torque", d.driven_torque),
        ("driven_damping", d.driven_damping),
    ];
    for (name, value) in non_negative {
        if !(value.is_finite() && value >= 0.0) {
            let reason = match name {
                "driver_speed" => "must be finite and ≥ 0 (a drive running backwards is the mirror image: mirror the scene)",
                "driven_torque" => "must be finite and ≥ 0 (a driven pulley that drives swaps the roles of the pulleys)",
                _ => "must be finite and ≥ 0",
            };
            return Err(BeltError::InvalidInput { name, value, reason });
        }
    }
    if !(d.friction.is_finite() && d.friction > 0.0) {
        return Err(BeltError::InvalidInput {
            name: "coulomb",
            value: d.friction,
            reason: "a steady friction drive needs μ > 0 (without friction the belt speed is undetermined)",
        });
    }
    crate::belt::check_pulleys_apart(d.radius, d.centre_distance)?;
    let wave_speed = (d.axial_stiffness / d.mass_per_length).sqrt();
    if d.inertia && d.driver_speed * d.radius >= wave_speed {
        return Err(BeltError::WaveSpeedReached { belt_speed: d.driver_speed * d.radius, wave_speed });
    }
    Ok(())
}

/// The scaled problem and its scales (docs/string-drive.md, "Scaling and homotopy").
pub fn scaled_problem(d: &StringDrive) -> (ScaledStringDrive, Scales) {
    let h = d.centre_distance;
    let weight_total = d.mass_per_length * d.gravity * d.length;
    let target = d.axial_stiffness * (d.geometric_length() / d.length - 1.0);
    let torque = d.driven_torque + d.driven_damping * d.driver_speed;
    let force = weight_total.max(target).max(torque / d.radius);
    let speed = (force / d.mass_per_length).sqrt();
    let capacity_tension = 2.0 * torque / (d.radius * (1.0 - (-d.friction * PI).exp()));
    let t0 = weight_total.max(target).max(capacity_tension);
    let length_start = if t0 == target { d.length } else { d.geometric_length() / (1.0 + t0 / d.axial_stiffness) };
    let problem = ScaledStringDrive {
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
    };
    (problem, Scales { length: h, force, speed })
}

/// The exact solution at η = 0: the tight weightless loop at rest with length L₀ —
/// straight spans, half-turn arcs all in stick, zero slip arcs, uniform tension.
pub fn tight_guess(p: &ScaledStringDrive, nodes: usize) -> Solution {
    let ea = p.axial_stiffness;
    let t0 = p.tight_tension();
    let stretch = 1.0 + t0 / ea;
    let l = 0.5 / stretch;
    let arc = PI * p.radius / stretch;
    let r = p.radius;
    let mut params = vec![0.0; N_PARAMS];
    for &i in &P_LEN {
        params[i] = l;
    }
    params[P_PHI2A] = PI / 2.0;
    params[P_PHI2T] = -PI / 2.0;
    params[P_PHI2B] = -PI / 2.0;
    params[P_PHI1A] = -PI / 2.0;
    params[P_PHI1T] = -1.5 * PI;
    params[P_PHI1B] = -1.5 * PI;
    Solution::from_fn(8, nodes, params, 0.0, |k, x| match k {
        UPPER_LEFT => vec![-0.5 + 0.5 * x, r, t0, 0.0, l * x],
        UPPER_RIGHT => vec![0.5 * x, r, t0, 0.0, l * (1.0 + x)],
        DRIVEN_STICK => vec![t0, 2.0 * l + arc * x, 0.0],
        DRIVEN_SLIP => vec![t0, 2.0 * l + arc, 0.0],
        LOWER_RIGHT => vec![0.5 - 0.5 * x, -r, -t0, 0.0, 2.0 * l + arc + l * x],
        LOWER_LEFT => vec![-0.5 * x, -r, -t0, 0.0, 3.0 * l + arc + l * x],
        DRIVER_STICK => vec![t0, 4.0 * l + arc * (1.0 + x), 0.0],
        _ => vec![t0, 4.0 * l + 2.0 * arc, 0.0],
    })
}

/// The segment topology (docs/string-drive.md, "Checks"): contact angles within 90° of
/// their tight values, stick and slip arcs ≥ 0 (stick before slip), spans of positive
/// length, transport rate ≥ 0. `slack` is the tolerance on the arcs (rad).
// The negated comparisons are deliberate: a NaN parameter must fail these checks.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn topology_check(p: &[f64], slack: f64) -> Result<(), String> {
    use std::f64::consts::FRAC_PI_2;
    let ranges = [
        ("first contact on the driven pulley", P_PHI2A, FRAC_PI_2),
        ("last contact on the driven pulley", P_PHI2B, -FRAC_PI_2),
        ("first contact on the driver", P_PHI1A, -FRAC_PI_2),
        ("last contact on the driver", P_PHI1B, -3.0 * FRAC_PI_2),
    ];
    for (what, i, tight) in ranges {
        if !((p[i] - tight).abs() < FRAC_PI_2) {
            return Err(format!(
                "{what} at {:.2}° is more than 90° from its tight-contour value {:.0}°",
                p[i].to_degrees(),
                tight.to_degrees()
            ));
        }
    }
    for (pulley, a, t, b) in [("driven", P_PHI2A, P_PHI2T, P_PHI2B), ("driver", P_PHI1A, P_PHI1T, P_PHI1B)] {
        if !(p[a] - p[t] >= -slack) {
            return Err(format!("the stick arc on the {pulley} pulley would be negative ({:.4e} rad): the slip zone covers the whole contact arc", p[a] - p[t]));
        }
        if !(p[t] - p[b] >= -slack) {
            return Err(format!("the slip arc on the {pulley} pulley would be negative ({:.4e} rad): the slip direction reverses", p[t] - p[b]));
        }
    }
    for &i in &P_LEN {
        if !(p[i] > 0.0) {
            return Err(format!("a span half has non-positive length {:.3e}", p[i]));
        }
    }
    if !(p[P_C] >= -1e-12) {
        return Err(format!("negative transport rate {:.3e}", p[P_C]));
    }
    Ok(())
}

/// Solve a `string-drive` scene from its data alone.
pub fn solve(data: &StringDrive, opts: &BeltOptions) -> Result<StringDriveSolution, BeltError> {
    let clock = Instant::now();
    validate(data)?;
    opts.check_tolerance()?;
    if data.gravity == 0.0 {
        // Exact no-solution cases of belt-creep theory, before any iteration.
        data.creep()?;
    }
    let (problem, scales) = scaled_problem(data);
    let start = tight_guess(&problem, 5);
    let last_rejection: RefCell<Option<String>> = RefCell::new(None);
    let physical = |s: &Solution| -> Result<(), String> {
        let verdict = physical_check(s, scales.force);
        if let Err(r) = &verdict {
            *last_rejection.borrow_mut() = Some(r.clone());
        }
        verdict
    };
    let solved = run::homotopy_and_final_solve(&problem, &start, opts, physical, clock).map_err(|e| match e {
        StageError::Homotopy(cause) => homotopy_failure(data, cause, last_rejection.borrow().as_deref()),
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })?;
    let mut sol = StringDriveSolution {
        data: *data,
        problem,
        solution: solved.solution,
        scales,
        options: opts.clone(),
        stats: solved.stats,
        homotopy_steps: solved.homotopy_steps,
        sigma_map: crate::sigma_map::SigmaMap::empty(
            drive::contour::Contour::new(data.radius, data.centre_distance).expect("validated geometry"),
        ),
    };
    sol.sigma_map = sol.build_sigma_map();
    let (input, output, dissipation) = sol.power_balance();
    balance::check_power(input - output - dissipation, sol.power_scale())?;
    sol.check_contact()?;
    Ok(sol)
}

/// The named error of a homotopy that stalled: the friction capacity or a reversed slip
/// when the last rejected point says so (its stick or slip arc vanished), else the
/// solver's failure.
fn homotopy_failure(data: &StringDrive, cause: BvpError, last_rejection: Option<&str>) -> BeltError {
    if let BvpError::ContinuationStalled { eta, .. } = &cause {
        let path = ScaledStringDrive::phases(*eta);
        let torque = data.driven_torque + data.driven_damping * data.driver_speed;
        if let Some(reason) = last_rejection.filter(|r| r.contains("slip arc")) {
            let weight_torque = 2.0 * data.mass_per_length * data.gravity * data.radius * data.radius;
            return BeltError::SlipReversed { torque, weight_torque, path, reason: reason.to_string() };
        }
        if let Some(reason) = last_rejection.filter(|r| r.contains("stick arc")) {
            return BeltError::FrictionCapacityExceeded { torque, path, reason: reason.to_string() };
        }
    }
    BeltError::Solver { stage: "homotopy from the tight loop at rest", cause }
}

/// The acceptance test of every homotopy point: topology and T̃ > 0 on the arcs.
fn physical_check(s: &Solution, force: f64) -> Result<(), String> {
    topology_check(&s.params, 1e-9)?;
    let t_min = [DRIVEN_STICK, DRIVEN_SLIP, DRIVER_STICK, DRIVER_SLIP]
        .iter()
        .flat_map(|&k| s.segments[k].nodes.iter().map(|y| y[0]))
        .fold(f64::INFINITY, f64::min);
    if t_min > 0.0 {
        Ok(())
    } else {
        Err(format!("effective tension {:.3e} N ≤ 0 on an arc", t_min * force))
    }
}

/// One point of the belt in physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltPoint {
    /// Position (m).
    pub x: f64,
    /// Position (m).
    pub y: f64,
    /// Axial force T (N).
    pub tension: f64,
    /// Effective tension T̃ = T − ρc²λ (N; = T without inertia).
    pub effective_tension: f64,
    /// Stretch λ.
    pub stretch: f64,
    /// Material coordinate s (m), 0 where the belt leaves the driver.
    pub material: f64,
    /// Contact force per unstretched length p (N/m) of (D4) on an arc; `None` on a span.
    pub pressure: Option<f64>,
    /// Friction force on the belt per unstretched length τ (N/m, + in the direction of
    /// travel); `None` on a span.
    pub friction: Option<f64>,
    /// Polar angle on the pulley (rad, unwrapped); `None` on a span.
    pub angle: Option<f64>,
    /// Accumulated torque m of (D7) on the pulley (N·m); `None` on a span.
    pub torque: Option<f64>,
}

impl StringDriveSolution {
    /// Transport rate c (m/s).
    pub fn transport_rate(&self) -> f64 {
        self.solution.params[P_C] * self.scales.speed
    }

    /// Driven speed ω₂ (rad/s).
    pub fn driven_speed(&self) -> f64 {
        self.solution.params[P_OMEGA2] * self.scales.speed / self.scales.length
    }

    /// (φ_a, φ_t, φ_b) of a pulley, rad, unwrapped, φ_a ≥ φ_t ≥ φ_b.
    pub fn contact_angles(&self, driver: bool) -> (f64, f64, f64) {
        let p = &self.solution.params;
        if driver { (p[P_PHI1A], p[P_PHI1T], p[P_PHI1B]) } else { (p[P_PHI2A], p[P_PHI2T], p[P_PHI2B]) }
    }

    /// Torque of the belt on a pulley (N·m, clockwise positive): m at the last contact.
    pub fn torque(&self, driver: bool) -> f64 {
        let k = if driver { DRIVER_SLIP } else { DRIVEN_SLIP };
        self.solution.segments[k].end()[2] * self.scales.force * self.scales.length
    }

    /// The belt at segment `k`, ξ ∈ [0, 1] (dense output; node values at the ends).
    pub fn point(&self, k: usize, xi: f64) -> BeltPoint {
        let y = self.solution.segments[k].state_at(xi);
        let (lh, fr) = (self.scales.length, self.scales.force);
        let c = self.solution.params[P_C];
        let pb = &self.problem;
        if is_span(k) {
            let te = y[2].hypot(y[3]);
            BeltPoint {
                x: y[0] * lh,
                y: y[1] * lh,
                tension: pb.axial_force(te, c) * fr,
                effective_tension: te * fr,
                stretch: pb.stretch(te, c),
                material: y[4] * lh,
                pressure: None,
                friction: None,
                angle: None,
                torque: None,
            }
        } else {
            let (ia, ib) = arc_params(k);
            let (pa, pbb) = (self.solution.params[ia], self.solution.params[ib]);
            let phi = pa + xi.clamp(0.0, 1.0) * (pbb - pa);
            let driver = on_driver(k);
            let te = y[0];
            let stretch = pb.stretch(te, c);
            let d = &self.data;
            let w = d.mass_per_length * d.gravity;
            let pressure = te * fr * stretch / d.radius + w * phi.sin();
            let friction = if is_slip(k) { ScaledStringDrive::slip_sign(k) * d.friction * pressure } else { -w * phi.cos() };
            BeltPoint {
                x: ScaledStringDrive::centre_x(driver) * lh + d.radius * phi.cos(),
                y: d.radius * phi.sin(),
                tension: pb.axial_force(te, c) * fr,
                effective_tension: te * fr,
                stretch,
                material: y[1] * lh,
                pressure: Some(pressure),
                friction: Some(friction),
                angle: Some(phi),
                torque: Some(y[2] * fr * lh),
            }
        }
    }

    /// Points along the loop: every mesh node and `per_interval` − 1 dense points inside
    /// each mesh interval, with their segment and ξ.
    pub fn samples(&self, per_interval: usize) -> Vec<(usize, f64, BeltPoint)> {
        self.solution.sample_points(per_interval).into_iter().map(|(k, xi)| (k, xi, self.point(k, xi))).collect()
    }

    /// The power scale P_ref of the balance check (W, [`crate::belt::balance`]): the
    /// scene's resisting power (M₂ + d₂ω₁) ω₁, or F_ref ω₁R for a drive without load.
    pub fn power_scale(&self) -> f64 {
        let d = &self.data;
        let resisting = (d.driven_torque + d.driven_damping * d.driver_speed) * d.driver_speed;
        if resisting > 0.0 { resisting } else { self.scales.force * d.driver_speed * d.radius }
    }

    /// Power balance (W): (input M_in ω₁, output (M₂ + d₂ω₂) ω₂, slip dissipation
    /// D = Σ ∫_slip τ (ωR − cλ) ds), the dissipation by 5-point Gauss–Legendre quadrature
    /// on each mesh interval of the dense output (docs/string-drive.md, "Torques, power").
    pub fn power_balance(&self) -> (f64, f64, f64) {
        let d = &self.data;
        let input = -self.torque(true) * d.driver_speed;
        let omega2 = self.driven_speed();
        let output = (d.driven_torque + d.driven_damping * omega2) * omega2;
        let c = self.transport_rate();
        const GX: [f64; 5] = [-0.906_179_845_938_664, -0.538_469_310_105_683, 0.0, 0.538_469_310_105_683, 0.906_179_845_938_664];
        const GW: [f64; 5] = [0.236_926_885_056_189, 0.478_628_670_499_366, 0.568_888_888_888_889, 0.478_628_670_499_366, 0.236_926_885_056_189];
        let mut dissipation = 0.0;
        for k in [DRIVEN_SLIP, DRIVER_SLIP] {
            let omega = if on_driver(k) { d.driver_speed } else { omega2 };
            let (ia, ib) = arc_params(k);
            let dphi = (self.solution.params[ib] - self.solution.params[ia]).abs();
            for w in self.solution.segments[k].mesh.windows(2) {
                let (a, b) = (w[0], w[1]);
                for (gx, gw) in GX.iter().zip(GW) {
                    let xi = 0.5 * (a + b) + 0.5 * (b - a) * gx;
                    let pt = self.point(k, xi);
                    let ds = d.radius / pt.stretch * dphi * 0.5 * (b - a) * gw;
                    dissipation += pt.friction.unwrap_or(0.0) * (omega * d.radius - c * pt.stretch) * ds;
                }
            }
        }
        (input, output, dissipation)
    }

    /// Check the conditions the segment topology assumes (docs/string-drive.md,
    /// "Checks"): topology, T̃ > 0, p ≥ 0, no span inside a pulley, slip direction, and
    /// the stick-zone friction bound.
    pub fn check_contact(&self) -> Result<(), BeltError> {
        let v = |s: String| BeltError::ContactViolated(s);
        topology_check(&self.solution.params, 1e-9).map_err(v)?;
        let d = &self.data;
        let w = d.mass_per_length * d.gravity;
        let force_floor = 1e-9 * (w + self.scales.force / d.radius);
        let inside = d.radius * (1.0 - 1e-6);
        let t_stick = |k: usize| self.point(k, 0.0).tension;
        let (t_tight, t_slack) = (t_stick(DRIVER_STICK), t_stick(DRIVEN_STICK));
        for (k, xi, pt) in self.samples(4) {
            let finite = [pt.x, pt.y, pt.tension, pt.effective_tension, pt.material].iter().all(|v| v.is_finite());
            if !finite {
                return Err(v(format!("non-finite solution in segment {k} at ξ = {xi:.4}")));
            }
            if pt.effective_tension <= 0.0 {
                return Err(v(format!("effective tension {:.4e} N ≤ 0 at ({:.5}, {:.5}) m", pt.effective_tension, pt.x, pt.y)));
            }
            let pulley = if on_driver(k) { "driver" } else { "driven" };
            match (pt.pressure, pt.friction) {
                (Some(p), Some(tau)) => {
                    if p < -force_floor {
                        return Err(v(format!("contact force {p:.4e} N/m < 0 on the {pulley} pulley at ({:.5}, {:.5}) m", pt.x, pt.y)));
                    }
                    if !is_slip(k) && tau.abs() > d.friction * p + force_floor {
                        return Err(v(format!(
                            "the stick zone on the {pulley} pulley needs friction {:.4e} N/m > μp = {:.4e} N/m at ({:.5}, {:.5}) m",
                            tau.abs(),
                            d.friction * p,
                            pt.x,
                            pt.y
                        )));
                    }
                    let tol = 1e-9 * self.scales.force;
                    if k == DRIVER_SLIP && pt.tension > t_tight + tol {
                        return Err(v(format!("slip direction: tension {:.6e} N above the stick tension {t_tight:.6e} N in the driver's slip zone", pt.tension)));
                    }
                    if k == DRIVEN_SLIP && pt.tension < t_slack - tol {
                        return Err(v(format!("slip direction: tension {:.6e} N below the stick tension {t_slack:.6e} N in the driven slip zone", pt.tension)));
                    }
                }
                _ => {
                    for (name, cx) in [("driver", -0.5 * d.centre_distance), ("driven", 0.5 * d.centre_distance)] {
                        let dist = (pt.x - cx).hypot(pt.y);
                        if dist < inside {
                            return Err(v(format!(
                                "free span passes through the {name} pulley: distance {dist:.6} m < R = {:.6} m at ({:.5}, {:.5}) m",
                                d.radius, pt.x, pt.y
                            )));
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
