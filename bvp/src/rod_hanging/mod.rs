//! `rod-hanging`: an extensible, unshearable (Kirchhoff) rod loop hanging under gravity on
//! two non-rotating frictionless pulleys, as the six-segment BVP derived in
//! `docs/rod-hanging.md` (41 unknowns).
//!
//! [`solve`] first solves the string of the same data ([`crate::string_hanging::solve`]),
//! builds the rod guess from it at a bending stiffness EI₀ whose boundary layer
//! √(EI₀/T) is 5 % of H, continues in log EI to the scene's EI — downwards for thin
//! layers, upwards for stiff rods; EI(η) = EI₀^(1−η) EI^η covers both —
//! (`continuation::natural_checked`), then solves at the requested tolerance by
//! collocation or shooting ([`Method`]).

pub mod problem;
pub mod view;

use std::f64::consts::{FRAC_PI_2, PI};
use std::time::Instant;

use serde::Serialize;

use crate::belt::run::{self, StageError};
use crate::belt::{balance, BeltError, BeltOptions, BvpMethod};
use crate::collocation::Scheme;
use crate::solution::{Solution, Stats};
use crate::string_hanging::{self, StringHanging};
pub use crate::string_hanging::Scales;
pub use problem::ScaledRodHanging;
use problem::*;

/// Physical data of the scene (SI units).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RodHanging {
    /// Pulley radius R to the rod centreline (m).
    pub radius: f64,
    /// Centre distance H (m).
    pub centre_distance: f64,
    /// Unstretched loop length L (m).
    pub length: f64,
    /// Axial stiffness EA (N).
    pub axial_stiffness: f64,
    /// Bending stiffness EI (N·m²).
    pub bending_stiffness: f64,
    /// Mass per unstretched length ρ (kg/m).
    pub mass_per_length: f64,
    /// Gravitational acceleration g (m/s²).
    pub gravity: f64,
}

impl RodHanging {
    /// The string with the same data (EI dropped).
    pub fn string(&self) -> StringHanging {
        StringHanging {
            radius: self.radius,
            centre_distance: self.centre_distance,
            length: self.length,
            axial_stiffness: self.axial_stiffness,
            mass_per_length: self.mass_per_length,
            gravity: self.gravity,
        }
    }
}

/// One point of the rod in physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodPoint {
    /// Position (m).
    pub x: f64,
    /// Position (m).
    pub y: f64,
    /// Tangent angle θ (rad, unwrapped as in [`problem`]).
    pub theta: f64,
    /// Bending moment M (N·m).
    pub moment: f64,
    /// Axial force N = Q·t (N).
    pub tension: f64,
    /// Transverse force V = Q·n (N).
    pub shear: f64,
    /// Material coordinate s (m).
    pub material: f64,
    /// Contact force per unstretched length p (N/m) of (R5) on an arc; `None` on a span.
    pub pressure: Option<f64>,
}

/// Concentrated contact reactions (R6) at the four contact boundaries (N).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EdgeForces {
    /// Driven pulley, first contact (end of segment 1, φ₂ₐ): `edge_force_start`.
    pub driven_start: f64,
    /// Driven pulley, last contact (start of segment 3, φ₂_b): `edge_force_end`.
    pub driven_end: f64,
    /// Driver pulley, first contact (end of segment 4, φ₁ₐ).
    pub driver_start: f64,
    /// Driver pulley, last contact (start of segment 0, φ₁_b).
    pub driver_end: f64,
}

/// A solved `rod-hanging` scene.
#[derive(Debug, Clone)]
pub struct RodHangingSolution {
    /// The physical data.
    pub data: RodHanging,
    /// The scaled problem (η = 1 is the scene).
    pub problem: ScaledRodHanging,
    /// The BVP solution in scaled variables at η = 1.
    pub solution: Solution,
    /// Scales (moments scale by force·length).
    pub scales: Scales,
    /// Options of the run (method and tolerance of the final solve among them).
    pub options: BeltOptions,
    /// Work of the rod computation (homotopy + final solve; string solve excluded).
    pub stats: Stats,
    /// Homotopy points (including the start).
    pub homotopy_steps: usize,
    /// The string solution of the same data used as the start.
    pub string: string_hanging::StringHangingSolution,
    /// EI₀ (N·m²) of the homotopy start.
    pub bending_start: f64,
}

fn validate(d: &RodHanging, opts: &BeltOptions) -> Result<(), BeltError> {
    if !(d.bending_stiffness.is_finite() && d.bending_stiffness > 0.0) {
        return Err(BeltError::InvalidInput {
            name: "bending_stiffness",
            value: d.bending_stiffness,
            reason: "must be finite and > 0 (EI = 0 is the string)",
        });
    }
    opts.check_tolerance()?;
    if !(opts.start_layer > 0.0 && opts.start_layer.is_finite()) {
        return Err(BeltError::InvalidInput { name: "start_layer", value: opts.start_layer, reason: "must be finite and > 0" });
    }
    Ok(())
}


/// Unwrap an angle into (centre − π, centre + π].
fn unwrap(a: f64, centre: f64) -> f64 {
    let mut a = a;
    while a > centre + PI {
        a -= 2.0 * PI;
    }
    while a <= centre - PI {
        a += 2.0 * PI;
    }
    a
}

/// The rod guess at EI₀ from the string solution (scaled): θ from the span force
/// direction, Q = F, M = 0 on the spans except the boundary layers at the pulleys, where
/// M = −EI₀λ/R · exp(−d/ℓ_b), ℓ_b = √(EI₀/T); N = T and s on the arcs; the string's
/// parameters.
pub fn rod_guess(string: &Solution, rod: &ScaledRodHanging, nodes: usize) -> Solution {
    let ei0 = rod.bending_start;
    let params = string.params.clone();
    Solution::from_fn(6, nodes, params.clone(), 0.0, |k, xi| {
        let y = string.eval(k, xi);
        if !is_span(k) {
            return y;
        }
        let (fx, fy) = (y[2], y[3]);
        let t = fx.hypot(fy);
        let centre = if matches!(k, UPPER_LEFT | UPPER_RIGHT) { 0.0 } else { -PI };
        let theta = unwrap(fy.atan2(fx), centre);
        let layer = (ei0 / t).sqrt();
        let l = params[span_len_index(k)];
        let d = if matches!(k, UPPER_LEFT | LOWER_RIGHT) { l * xi } else { l * (1.0 - xi) };
        let m = -ei0 * (1.0 + t / rod.axial_stiffness) / rod.radius * (-d / layer).exp();
        vec![y[0], y[1], theta, m, fx, fy, y[4]]
    })
}

/// The segment topology of the string note: every contact angle less than a half turn
/// from its tight-contour value, positive wraps on both pulleys and positive span
/// lengths. The string's window (a quarter turn) is too narrow for the rod: a stiff rod
/// on a slack loop leaves the pulleys earlier, and its lower span can depart above the
/// pulley's horizontal diameter (φ₂_b > 0, heading downwards); whether such a state is
/// physical is decided by the contact checks (edge forces, p ≥ 0, no span through a
/// pulley), not by this window.
// The negated comparisons are deliberate: a NaN parameter must fail these checks.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn topology_check(p: &[f64]) -> Result<(), String> {
    let ranges = [
        ("first contact on the driven pulley", P_PHI2A, FRAC_PI_2),
        ("last contact on the driven pulley", P_PHI2B, -FRAC_PI_2),
        ("first contact on the driver pulley", P_PHI1A, -FRAC_PI_2),
        ("last contact on the driver pulley", P_PHI1B, -3.0 * FRAC_PI_2),
    ];
    for (what, i, tight) in ranges {
        if !((p[i] - tight).abs() < PI) {
            return Err(format!(
                "{what} at {:.2}° is more than 180° from its tight-contour value {:.0}°",
                p[i].to_degrees(),
                tight.to_degrees()
            ));
        }
    }
    for (what, a, b) in [("driven", P_PHI2A, P_PHI2B), ("driver", P_PHI1A, P_PHI1B)] {
        if !(p[a] > p[b]) {
            return Err(format!("non-positive wrap {:.3}° on the {what} pulley", (p[a] - p[b]).to_degrees()));
        }
    }
    for &i in &P_LEN {
        if !(p[i] > 0.0) {
            return Err(format!("a span half has non-positive length {:.3e}", p[i]));
        }
    }
    Ok(())
}

/// Solve a `rod-hanging` scene from its data alone.
pub fn solve(data: &RodHanging, opts: &BeltOptions) -> Result<RodHangingSolution, BeltError> {
    let clock = Instant::now();
    validate(data, opts)?;
    // The start: the string of the same data by collocation (gauss6, 1e-8), with the
    // run's mesh cap, Jacobian mode and homotopy tolerance.
    let sopts = BeltOptions {
        method: BvpMethod::Collocation,
        scheme: Scheme::default(),
        tolerance: 1e-8,
        shooting_intervals: BeltOptions::default().shooting_intervals,
        ..opts.clone()
    };
    let string = string_hanging::solve(&data.string(), &sopts).map_err(|e| BeltError::StringStart(Box::new(e)))?;
    let scales = string.scales;
    let (h, fr) = (scales.length, scales.force);
    let sp = &string.problem;
    // String mid-span tension (upper span, x = 0), scaled.
    let mid = string.solution.segments[UPPER_LEFT].end();
    let t_mid = mid[2].hypot(mid[3]);
    let bending_start_scaled = opts.start_layer * opts.start_layer * t_mid;
    let problem = ScaledRodHanging {
        radius: sp.radius,
        axial_stiffness: sp.axial_stiffness,
        weight: sp.weight,
        length: sp.length,
        bending_start: bending_start_scaled,
        bending: data.bending_stiffness / (fr * h * h),
    };
    let guess = rod_guess(&string.solution, &problem, 81);
    let physical = |s: &Solution| -> Result<(), String> {
        topology_check(&s.params)?;
        let n_min = [DRIVEN_ARC, DRIVER_ARC]
            .iter()
            .flat_map(|&k| s.segments[k].nodes.iter().map(|y| y[0]))
            .fold(f64::INFINITY, f64::min);
        let defect = s.params[P_DEFECT].abs();
        if n_min > 0.0 && defect <= 1e-3 * n_min {
            Ok(())
        } else {
            Err(format!(
                "left the physical branch: smallest arc axial force {:.3e} N, closure defect {:.3e} N",
                n_min * fr,
                defect * fr
            ))
        }
    };
    let solved = run::homotopy_and_final_solve(&problem, &guess, opts, physical, clock).map_err(|e| match e {
        StageError::Homotopy(cause) => BeltError::Solver { stage: "homotopy in log EI from the string", cause },
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })?;
    let sol = RodHangingSolution {
        data: *data,
        problem,
        solution: solved.solution,
        scales,
        options: opts.clone(),
        stats: solved.stats,
        homotopy_steps: solved.homotopy_steps,
        string,
        bending_start: bending_start_scaled * fr * h * h,
    };
    let weight = data.mass_per_length * data.gravity * data.length;
    balance::check_closure(sol.closure_defect(), weight, fr)?;
    sol.check_contact()?;
    Ok(sol)
}

impl RodHangingSolution {
    fn phi_range(&self, k: usize) -> (f64, f64) {
        let p = &self.solution.params;
        if k == DRIVEN_ARC { (p[P_PHI2A], p[P_PHI2B]) } else { (p[P_PHI1A], p[P_PHI1B]) }
    }

    fn ei_scaled(&self) -> f64 {
        self.problem.bending
    }

    /// The rod at segment `k`, normalised coordinate ξ ∈ [0, 1] (exact node values at the
    /// ends).
    pub fn point(&self, k: usize, xi: f64) -> RodPoint {
        let y = self.solution.segments[k].state_at(xi);
        let (lh, fr) = (self.scales.length, self.scales.force);
        let pb = &self.problem;
        if is_span(k) {
            let (n, v) = span_nv(&y);
            RodPoint {
                x: y[0] * lh,
                y: y[1] * lh,
                theta: y[2],
                moment: y[3] * fr * lh,
                tension: n * fr,
                shear: v * fr,
                material: y[6] * lh,
                pressure: None,
            }
        } else {
            let (pa, pb_) = self.phi_range(k);
            let phi = pa + xi.clamp(0.0, 1.0) * (pb_ - pa);
            let cx = ScaledRodHanging::centre_x(k == DRIVER_ARC);
            let ei = self.ei_scaled();
            let n = y[0];
            let lambda = 1.0 + n / pb.axial_stiffness;
            RodPoint {
                x: (cx + pb.radius * phi.cos()) * lh,
                y: pb.radius * phi.sin() * lh,
                theta: phi - FRAC_PI_2,
                moment: -ei * lambda / pb.radius * fr * lh,
                tension: n * fr,
                shear: pb.arc_v(ei, phi, n) * fr,
                material: y[1] * lh,
                pressure: Some(pb.arc_pressure(ei, phi, n) * fr / lh),
            }
        }
    }

    /// Edge forces (R6) at the four contact boundaries (N).
    pub fn edge_forces(&self) -> EdgeForces {
        let v = |k: usize, xi: f64| self.point(k, xi).shear;
        EdgeForces {
            driven_start: v(UPPER_RIGHT, 1.0) - v(DRIVEN_ARC, 0.0),
            driven_end: v(DRIVEN_ARC, 1.0) - v(LOWER_RIGHT, 0.0),
            driver_start: v(LOWER_LEFT, 1.0) - v(DRIVER_ARC, 0.0),
            driver_end: v(DRIVER_ARC, 1.0) - v(UPPER_LEFT, 0.0),
        }
    }

    /// The rod at mid-span (x = 0, a mesh node): (upper, lower).
    pub fn mid_span(&self) -> (RodPoint, RodPoint) {
        (self.point(UPPER_LEFT, 1.0), self.point(LOWER_RIGHT, 1.0))
    }

    /// Contact arc of a pulley: (φ_a, φ_b) in radians.
    pub fn contact_angles(&self, driver: bool) -> (f64, f64) {
        self.phi_range(if driver { DRIVER_ARC } else { DRIVEN_ARC })
    }

    /// The closure defect f (N).
    pub fn closure_defect(&self) -> f64 {
        self.solution.params[P_DEFECT] * self.scales.force
    }

    /// The invariant (R7) E = M²/(2EI) + N + N²/(2EA) − ρ g y at a point (N).
    pub fn invariant(&self, pt: &RodPoint) -> f64 {
        let d = &self.data;
        pt.moment * pt.moment / (2.0 * d.bending_stiffness) + pt.tension + pt.tension * pt.tension / (2.0 * d.axial_stiffness)
            - d.mass_per_length * d.gravity * pt.y
    }

    /// Points along the loop: every mesh node and `per_interval` − 1 dense points inside
    /// each mesh interval, with their segment and ξ.
    pub fn samples(&self, per_interval: usize) -> Vec<(usize, f64, RodPoint)> {
        self.solution.sample_points(per_interval).into_iter().map(|(k, xi)| (k, xi, self.point(k, xi))).collect()
    }

    /// Checks of docs/rod-hanging.md ("Homotopy"): topology, N > 0, p ≥ 0 inside the arcs,
    /// all four edge forces ≥ 0, no span point inside a pulley.
    pub fn check_contact(&self) -> Result<(), BeltError> {
        topology_check(&self.solution.params).map_err(BeltError::ContactViolated)?;
        let d = &self.data;
        let fr = self.scales.force;
        let pressure_floor = -1e-9 * (d.mass_per_length * d.gravity + fr / d.radius);
        let inside = d.radius * (1.0 - 1e-6);
        for (k, xi, pt) in self.samples(4) {
            if !(pt.x.is_finite() && pt.y.is_finite() && pt.tension.is_finite() && pt.moment.is_finite()) {
                return Err(BeltError::ContactViolated(format!("non-finite solution in segment {k} at ξ = {xi:.4}")));
            }
            if let Some(p) = pt.pressure {
                if pt.tension <= 0.0 {
                    return Err(BeltError::ContactViolated(format!("axial force {:.4e} N ≤ 0 on an arc", pt.tension)));
                }
                if p < pressure_floor {
                    return Err(BeltError::ContactViolated(format!(
                        "contact pressure {p:.4e} N/m < 0 at ({:.5}, {:.5}) m",
                        pt.x, pt.y
                    )));
                }
            } else {
                for (name, cx) in [("driver", -0.5 * d.centre_distance), ("driven", 0.5 * d.centre_distance)] {
                    let dist = (pt.x - cx).hypot(pt.y);
                    if dist < inside {
                        return Err(BeltError::ContactViolated(format!(
                            "free span passes through the {name} pulley: distance {dist:.6} m < R at ({:.5}, {:.5}) m",
                            pt.x, pt.y
                        )));
                    }
                }
            }
        }
        let e = self.edge_forces();
        let floor = -1e-7 * fr;
        for (what, v) in [
            ("driven first contact", e.driven_start),
            ("driven last contact", e.driven_end),
            ("driver first contact", e.driver_start),
            ("driver last contact", e.driver_end),
        ] {
            if v < floor {
                return Err(BeltError::ContactViolated(format!("edge force {v:.4e} N < 0 at the {what}: the pulley would pull")));
            }
        }
        Ok(())
    }
}
