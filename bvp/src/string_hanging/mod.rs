//! `string-hanging`: an extensible string loop hanging under gravity on two non-rotating
//! frictionless pulleys, as the six-segment BVP derived in `docs/string-hanging.md`.
//!
//! [`solve`] reaches the scene from the tight, weightless closed form by the homotopy of
//! the note, then solves at the requested tolerance with the requested method
//! ([`crate::belt::run`]), checks the closure balance ([`crate::belt::balance`]) and the
//! contact conditions (p ≥ 0 on the arcs, no span inside a pulley) and returns a
//! [`StringHangingSolution`], which implements the common [`SolutionView`].

pub mod problem;
pub mod view;

use std::f64::consts::PI;
use std::time::Instant;

use serde::Serialize;

use crate::belt::run::{self, StageError};
use crate::belt::{balance, BeltError, BeltOptions};
use crate::solution::{Solution, Stats};
pub use problem::ScaledStringHanging;
use problem::*;

/// Physical data of the scene (SI units).
#[derive(Debug, Clone, Copy, Serialize)]
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
}

/// Scales of the nondimensionalisation (docs/string-hanging.md, "Scaling").
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Scales {
    /// Length scale H (m).
    pub length: f64,
    /// Force scale F_ref (N).
    pub force: f64,
}

/// A solved `string-hanging` scene.
#[derive(Debug, Clone)]
pub struct StringHangingSolution {
    /// The physical data.
    pub data: StringHanging,
    /// The scaled problem (η = 1 is the scene).
    pub problem: ScaledStringHanging,
    /// The BVP solution in scaled variables at η = 1.
    pub solution: Solution,
    /// Scales.
    pub scales: Scales,
    /// Options of the run (method and tolerance of the final solve among them).
    pub options: BeltOptions,
    /// Work of the whole computation (homotopy + final solve); `wall_seconds` is the
    /// total wall time.
    pub stats: Stats,
    /// Homotopy steps taken.
    pub homotopy_steps: usize,
    sigma_map: crate::sigma_map::SigmaMap,
}

/// Validate the physical data.
fn validate(d: &StringHanging) -> Result<(), BeltError> {
    crate::belt::check_positive(&[
        ("pulley_radius", d.radius),
        ("centre_distance", d.centre_distance),
        ("length", d.length),
        ("axial_stiffness", d.axial_stiffness),
        ("mass_per_length", d.mass_per_length),
    ])?;
    if !d.gravity.is_finite() || d.gravity < 0.0 {
        return Err(BeltError::InvalidInput { name: "gravity", value: d.gravity, reason: "must be finite and ≥ 0" });
    }
    crate::belt::check_pulleys_apart(d.radius, d.centre_distance)?;
    if d.gravity == 0.0 && d.tight_tension() <= 0.0 {
        return Err(BeltError::WeightlessSlack { length: d.length, geometric_length: d.geometric_length() });
    }
    Ok(())
}

/// The scaled problem and its scales (docs/string-hanging.md, "Scaling" and "Homotopy").
pub fn scaled_problem(d: &StringHanging) -> (ScaledStringHanging, Scales) {
    let h = d.centre_distance;
    let weight_total = d.mass_per_length * d.gravity * d.length;
    let target = d.tight_tension();
    // The larger of the weight and the stretched-on tension, so that scaled forces are
    // O(1) for slack and for stretched-on belts alike.
    let force = weight_total.max(target);
    // Starting tension of the weightless tight loop.
    let t0 = if d.gravity > 0.0 { weight_total.max(target) } else { target };
    let length_start = d.geometric_length() / (1.0 + t0 / d.axial_stiffness);
    let problem = ScaledStringHanging {
        radius: d.radius / h,
        axial_stiffness: d.axial_stiffness / force,
        weight: d.mass_per_length * d.gravity * h / force,
        length_start: length_start / h,
        length: d.length / h,
    };
    (problem, Scales { length: h, force })
}

/// The exact solution at η = 0: the weightless tight loop (straight spans, half-turn
/// arcs, uniform tension), sampled on `nodes` nodes per segment.
pub fn tight_guess(p: &ScaledStringHanging, nodes: usize) -> Solution {
    let ea = p.axial_stiffness;
    let geometric = 2.0 + 2.0 * PI * p.radius;
    let stretch = geometric / p.length_start;
    let t0 = ea * (stretch - 1.0);
    let l = 0.5 / stretch;
    let arc = PI * p.radius / stretch;
    let r = p.radius;
    let mut params = vec![0.0; N_PARAMS];
    for &i in &P_LEN {
        params[i] = l;
    }
    params[P_PHI2A] = PI / 2.0;
    params[P_PHI2B] = -PI / 2.0;
    params[P_PHI1A] = -PI / 2.0;
    params[P_PHI1B] = -1.5 * PI;
    Solution::from_fn(6, nodes, params, 0.0, |k, x| match k {
        UPPER_LEFT => vec![-0.5 + 0.5 * x, r, t0, 0.0, l * x],
        UPPER_RIGHT => vec![0.5 * x, r, t0, 0.0, l * (1.0 + x)],
        DRIVEN_ARC => vec![t0, 2.0 * l + arc * x],
        LOWER_RIGHT => vec![0.5 - 0.5 * x, -r, -t0, 0.0, 2.0 * l + arc + l * x],
        LOWER_LEFT => vec![-0.5 * x, -r, -t0, 0.0, 3.0 * l + arc + l * x],
        _ => vec![t0, 4.0 * l + arc * (1.0 + x)],
    })
}

/// Solve a `string-hanging` scene from its data alone (homotopy of the note, then the
/// final solve with `opts.method` at `opts.tolerance`, then the contact checks).
pub fn solve(data: &StringHanging, opts: &BeltOptions) -> Result<StringHangingSolution, BeltError> {
    let clock = Instant::now();
    validate(data)?;
    opts.check_tolerance()?;
    let (problem, scales) = scaled_problem(data);
    let start = tight_guess(&problem, 5);
    // Every accepted homotopy point must stay on the physical branch: positive tension on
    // both arcs and a closure defect far below it (docs/string-hanging.md, "Homotopy").
    let physical = |s: &Solution| -> Result<(), String> {
        topology_check(&s.params)?;
        let t_min = [DRIVEN_ARC, DRIVER_ARC]
            .iter()
            .flat_map(|&k| s.segments[k].nodes.iter().map(|y| y[0]))
            .fold(f64::INFINITY, f64::min);
        let defect = s.params[P_DEFECT].abs();
        if t_min > 0.0 && defect <= 1e-3 * t_min {
            Ok(())
        } else {
            Err(format!(
                "left the physical branch: smallest arc tension {:.3e} N, closure defect {:.3e} N",
                t_min * scales.force,
                defect * scales.force
            ))
        }
    };
    let solved = run::homotopy_and_final_solve(&problem, &start, opts, physical, clock).map_err(|e| match e {
        StageError::Homotopy(cause) => BeltError::Solver { stage: "homotopy from the tight weightless loop", cause },
        StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
    })?;
    let mut sol = StringHangingSolution {
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
    let weight = data.mass_per_length * data.gravity * data.length;
    balance::check_closure(sol.closure_defect(), weight, scales.force)?;
    sol.check_contact()?;
    Ok(sol)
}

/// The segment topology of the note: each contact angle within a quarter turn of its
/// tight-contour value (φ₂ₐ ∈ (0, π), φ₂_b ∈ (−π, 0), φ₁ₐ ∈ (−π, 0), φ₁_b ∈ (−2π, −π)), so
/// each contact arc lies in (0, 2π) and no span winds an extra turn round a pulley, and
/// every span has positive length. The discrete equations have other, unphysical,
/// solutions (a belt wound once more round a pulley, at an enormous tension): this test
/// keeps the homotopy and the final solve off them.
// The negated comparisons are deliberate: a NaN parameter must fail these checks.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn topology_check(p: &[f64]) -> Result<(), String> {
    use std::f64::consts::FRAC_PI_2;
    let ranges = [
        ("first contact on the driven pulley", P_PHI2A, FRAC_PI_2),
        ("last contact on the driven pulley", P_PHI2B, -FRAC_PI_2),
        ("first contact on the driver pulley", P_PHI1A, -FRAC_PI_2),
        ("last contact on the driver pulley", P_PHI1B, -3.0 * FRAC_PI_2),
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
    for &i in &P_LEN {
        if !(p[i] > 0.0) {
            return Err(format!("a span half has non-positive length {:.3e}", p[i]));
        }
    }
    Ok(())
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
    /// Material coordinate s (m), 0 where the belt leaves the driver.
    pub material: f64,
    /// Contact force per unstretched length p (N/m) of (S5) on an arc; `None` on a span.
    pub pressure: Option<f64>,
}

impl StringHangingSolution {
    fn phi_range(&self, k: usize) -> (f64, f64) {
        let p = &self.solution.params;
        if k == DRIVEN_ARC { (p[P_PHI2A], p[P_PHI2B]) } else { (p[P_PHI1A], p[P_PHI1B]) }
    }

    /// The belt at segment `k`, normalised coordinate ξ ∈ [0, 1] (dense output; exact
    /// node values at ξ = 0, 1).
    pub fn point(&self, k: usize, xi: f64) -> BeltPoint {
        let y = self.solution.segments[k].state_at(xi);
        let (lh, fr) = (self.scales.length, self.scales.force);
        if is_span(k) {
            BeltPoint {
                x: y[0] * lh,
                y: y[1] * lh,
                tension: y[2].hypot(y[3]) * fr,
                material: y[4] * lh,
                pressure: None,
            }
        } else {
            let (pa, pb) = self.phi_range(k);
            let phi = pa + xi.clamp(0.0, 1.0) * (pb - pa);
            let cx = ScaledStringHanging::centre_x(k == DRIVER_ARC) * lh;
            let tension = y[0] * fr;
            let stretch = 1.0 + tension / self.data.axial_stiffness;
            let pressure = tension * stretch / self.data.radius + self.data.mass_per_length * self.data.gravity * phi.sin();
            BeltPoint {
                x: cx + self.data.radius * phi.cos(),
                y: self.data.radius * phi.sin(),
                tension,
                material: y[1] * lh,
                pressure: Some(pressure),
            }
        }
    }

    /// Contact arc data of a pulley: (φ_a, φ_b) in radians, unwrapped, φ_a > φ_b.
    pub fn contact_angles(&self, driver: bool) -> (f64, f64) {
        self.phi_range(if driver { DRIVER_ARC } else { DRIVEN_ARC })
    }

    /// The closure defect f (N): the tension jump the discrete solution needs at the
    /// driver's first contact; 0 for the exact solution.
    pub fn closure_defect(&self) -> f64 {
        self.solution.params[P_DEFECT] * self.scales.force
    }

    /// The frictionless invariant E = T + T²/(2EA) − ρ g y (S6) at a point (N).
    pub fn invariant(&self, pt: &BeltPoint) -> f64 {
        let d = &self.data;
        pt.tension + pt.tension * pt.tension / (2.0 * d.axial_stiffness) - d.mass_per_length * d.gravity * pt.y
    }

    /// Points sampled along the whole loop: every mesh node and `per_interval` − 1 dense
    /// points inside each mesh interval, in the direction of σ, with their segment and ξ.
    pub fn samples(&self, per_interval: usize) -> Vec<(usize, f64, BeltPoint)> {
        self.solution.sample_points(per_interval).into_iter().map(|(k, xi)| (k, xi, self.point(k, xi))).collect()
    }

    /// Check the conditions the segment topology assumes (docs/string-hanging.md,
    /// "Checks"): p ≥ 0 on the arcs, T > 0, no span point inside a pulley.
    pub fn check_contact(&self) -> Result<(), BeltError> {
        topology_check(&self.solution.params).map_err(BeltError::ContactViolated)?;
        let d = &self.data;
        let pressure_floor = -1e-9 * (d.mass_per_length * d.gravity + self.scales.force / d.radius);
        let inside = d.radius * (1.0 - 1e-6);
        for (k, xi, pt) in self.samples(4) {
            let finite = pt.x.is_finite() && pt.y.is_finite() && pt.tension.is_finite() && pt.material.is_finite();
            if !finite {
                return Err(BeltError::ContactViolated(format!("non-finite solution in segment {k} at ξ = {xi:.4}")));
            }
            if pt.tension <= 0.0 {
                return Err(BeltError::ContactViolated(format!(
                    "tension {:.4e} N ≤ 0 at ({:.5}, {:.5}) m",
                    pt.tension, pt.x, pt.y
                )));
            }
            if let Some(p) = pt.pressure {
                if p < pressure_floor {
                    return Err(BeltError::ContactViolated(format!(
                        "contact force {p:.4e} N/m < 0 on the {} pulley at ({:.5}, {:.5}) m: the belt would lift off inside the arc",
                        if k == DRIVER_ARC { "driver" } else { "driven" },
                        pt.x,
                        pt.y
                    )));
                }
            } else {
                for (name, cx) in [("driver", -0.5 * d.centre_distance), ("driven", 0.5 * d.centre_distance)] {
                    let dist = (pt.x - cx).hypot(pt.y);
                    if dist < inside {
                        return Err(BeltError::ContactViolated(format!(
                            "free span passes through the {name} pulley: distance {dist:.6} m from its centre < R = {:.6} m at ({:.5}, {:.5}) m",
                            d.radius, pt.x, pt.y
                        )));
                    }
                }
            }
        }
        Ok(())
    }
}
