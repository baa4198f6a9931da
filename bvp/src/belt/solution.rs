//! One solution type and one view for every belt problem: a solved [`BeltProblem`] with
//! its data, scales and work counters ([`BeltSolution`]), the stages that make it
//! ([`solve`]: homotopy with the acceptance test, final solve, balance and contact
//! checks), its point output along the loop, and the common [`SolutionView`] (σ lookup
//! through [`crate::sigma_map`], the summary from the topology and the law's points).

use std::cell::RefCell;
use std::f64::consts::PI;
use std::time::Instant;

use drive::contour::{Contour, Path};
use drive::summary::{PulleySummary, Summary};
use drive::view::SolutionView;

use crate::sigma_map::SigmaMap;
use crate::solution::{SegmentSolution, Solution, Stats};

use super::law::{BeltPoint, ContactEdges, Pulleys, Scales, SectionLaw};
use super::problem::BeltProblem;
use super::run::{self, StageError};
use super::topology::{ArcKind, Pulley, Scaling, SegmentKind, Topology};
use super::{BeltError, BeltOptions};

/// ∫ g ds over an arc segment whose dense output `point`(ξ) runs over `mesh` (ξ ∈ [0, 1])
/// and sweeps the angle `dphi` (rad) on a pulley of radius `radius`: ds = R dφ/λ with φ
/// linear in ξ; Gauss–Legendre with 5 points ([`numerics::Rule`]) on each mesh interval.
pub fn arc_integral(mesh: &[f64], dphi: f64, radius: f64, point: impl Fn(f64) -> BeltPoint, g: impl Fn(&BeltPoint) -> f64) -> f64 {
    let rule = numerics::Rule::Gauss(5);
    mesh.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            rule.points()
                .iter()
                .map(|&(x, wt)| {
                    let pt = point(0.5 * (a + b) + 0.5 * (b - a) * x);
                    g(&pt) * radius / pt.stretch * dphi * 0.5 * (b - a) * wt
                })
                .sum::<f64>()
        })
        .sum()
}

/// The largest value of g(k, ξ) over the segments k of `segments` (each with its mesh
/// in ξ ∈ [0, 1]): the best of the mesh nodes and 8 points per mesh interval, refined by
/// golden section between the best sample's neighbours, so that an interior extremum of
/// a smooth g is found to ~1e-10 of the interval rather than to the sampling's O(h²).
/// NaN if g is NaN everywhere.
pub fn sampled_extremum(segments: &[(usize, &[f64])], g: impl Fn(usize, f64) -> f64) -> f64 {
    const SUB: usize = 8;
    let mut best = (f64::NEG_INFINITY, 0, 0.0, 0.0);
    for &(k, mesh) in segments {
        let mut xis: Vec<f64> = Vec::with_capacity(SUB * mesh.len());
        for w in mesh.windows(2) {
            xis.extend((0..SUB).map(|j| w[0] + (w[1] - w[0]) * j as f64 / SUB as f64));
        }
        xis.extend(mesh.last());
        for (i, &xi) in xis.iter().enumerate() {
            let v = g(k, xi);
            if v > best.0 {
                best = (v, k, xis[i.saturating_sub(1)], xis[(i + 1).min(xis.len() - 1)]);
            }
        }
    }
    let (mut value, k, mut a, mut b) = best;
    if !value.is_finite() {
        return if value == f64::NEG_INFINITY { f64::NAN } else { value };
    }
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut gc, mut gd) = (g(k, c), g(k, d));
    for _ in 0..48 {
        if gc > gd {
            b = d;
            (d, gd) = (c, gc);
            c = b - r * (b - a);
            gc = g(k, c);
        } else {
            a = c;
            (c, gc) = (d, gd);
            d = a + r * (b - a);
            gd = g(k, d);
        }
    }
    for v in [gc, gd] {
        if v.is_finite() && v > value {
            value = v;
        }
    }
    value
}

/// Wrap an angle to (−π, π].
pub fn wrap_angle(a: f64) -> f64 {
    let mut w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w -= 2.0 * PI;
    }
    w
}

/// A solved belt problem.
#[derive(Debug, Clone)]
pub struct BeltSolution<L: SectionLaw> {
    /// The physical data.
    pub data: L::Data,
    /// The scaled problem (topology and law; η = 1 is the scene).
    pub problem: BeltProblem<L>,
    /// The BVP solution in scaled variables at η = 1.
    pub solution: Solution,
    /// Scales.
    pub scales: Scales,
    /// The pulleys and the belt's weight (SI units).
    pub pulleys: Pulleys,
    /// Options of the run (method and tolerance of the final solve among them).
    pub options: BeltOptions,
    /// Work of the run (homotopy + final solve); `wall_seconds` is its wall time.
    pub stats: Stats,
    /// Accepted homotopy points (start included).
    pub homotopy_steps: usize,
    /// What the homotopy started from, kept with the solution (the Kirchhoff rod: the
    /// string solution of the same data).
    pub start: L::Start,
    sigma_map: SigmaMap,
}

/// Concentrated contact reactions at the four contact boundaries (N): the jump of the
/// transverse force Q where a span meets an arc (the Kirchhoff rod's (R6)).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EdgeForces {
    /// Driven pulley, first contact.
    pub driven_start: f64,
    /// Driven pulley, last contact.
    pub driven_end: f64,
    /// Driver pulley, first contact.
    pub driver_start: f64,
    /// Driver pulley, last contact.
    pub driver_end: f64,
}

/// The acceptance test of every homotopy point: the topology's check with the law's
/// window, the arc force (arc state 0) > 0, and on a frictionless loop a closure jump
/// far below it (docs/string-hanging.md, "Homotopy").
pub fn on_branch<L: SectionLaw>(problem: &BeltProblem<L>, s: &Solution, force_scale: f64) -> Result<(), String> {
    let topo = &problem.topology;
    let (window, slack) = problem.law.admissible_window();
    topo.check(&s.params, window, slack)?;
    let name = problem.law.arc_force_name();
    let f_min = (0..topo.len())
        .filter(|&k| !topo.is_span(k))
        .flat_map(|k| s.segments[k].nodes.iter().map(|y| problem.law.arc_force(y)))
        .fold(f64::INFINITY, f64::min);
    match topo.closure_jump() {
        Some(j) => {
            let defect = s.params[j].abs();
            if f_min > 0.0 && defect <= 1e-3 * f_min {
                Ok(())
            } else {
                Err(format!(
                    "left the physical branch: smallest arc {name} {:.3e} N, closure defect {:.3e} N",
                    f_min * force_scale,
                    defect * force_scale
                ))
            }
        }
        None if f_min > 0.0 => Ok(()),
        None => Err(format!("{name} {:.3e} N ≤ 0 on an arc", f_min * force_scale)),
    }
}

/// What a belt run starts from: the data, the scaled problem on its topology, the scales,
/// the pulleys, the homotopy start and what the solution keeps of it.
pub struct Run<'a, L: SectionLaw> {
    /// The physical data.
    pub data: L::Data,
    /// The scaled problem.
    pub problem: BeltProblem<L>,
    /// The scales.
    pub scales: Scales,
    /// The pulleys and the belt's weight.
    pub pulleys: Pulleys,
    /// The homotopy start (a solution at η = 0).
    pub guess: &'a Solution,
    /// Kept with the solution.
    pub start: L::Start,
}

/// Solve a belt problem: homotopy η: 0 → 1 from the guess with [`on_branch`] as the
/// acceptance test (or, when the law [`SectionLaw::starts_at_scene`], one path-tolerance
/// solve from the guess at η = 1), the final solve, then the law's balance check and the contact
/// checks ([`BeltSolution::check_contact`]). `failure` names a failed stage; it gets the
/// last rejection of the acceptance test.
pub fn solve<L: SectionLaw>(
    run: Run<'_, L>,
    opts: &BeltOptions,
    clock: Instant,
    failure: impl FnOnce(StageError, Option<&str>) -> BeltError,
) -> Result<BeltSolution<L>, BeltError> {
    let Run { data, problem, scales, pulleys, guess, start } = run;
    let last_rejection: RefCell<Option<String>> = RefCell::new(None);
    let accept = |s: &Solution| -> Result<(), String> {
        let verdict = on_branch(&problem, s, scales.force);
        if let Err(r) = &verdict {
            *last_rejection.borrow_mut() = Some(r.clone());
        }
        verdict
    };
    let stages = if problem.law.starts_at_scene() {
        run::direct_and_final_solve(&problem, &Solution { eta: 1.0, ..guess.clone() }, opts, clock)
    } else {
        run::homotopy_and_final_solve(&problem, guess, opts, accept, clock)
    };
    let solved = match stages {
        Ok(s) => s,
        Err(e) => return Err(failure(e, last_rejection.borrow().as_deref())),
    };
    finish(data, problem, scales, pulleys, start, solved, opts)
}

/// Solve a belt problem from a converged solution of a nearby scene (a *warm start*, the
/// step of a natural-parameter continuation in a scene field, `beltcheck sweep`): the
/// guess `run.guess` must be a solution at η = 1 of a problem with the same topology,
/// power flow and scales (the caller builds `run.problem` with the previous solution's
/// scales). No homotopy: the final solve at `opts` from the guess on its mesh, then the
/// acceptance test of every homotopy point ([`on_branch`]: a warm solve that converged
/// onto another branch, e.g. one that lost a stick arc, is refused with the reason), the
/// law's balance check and the contact checks, as [`solve`].
///
/// # Errors
/// [`BeltError::Solver`] (stage "warm start …") when the final solve fails;
/// [`BeltError::ContactViolated`] when the solution left the physical branch; the
/// balance and contact errors of [`solve`].
pub fn solve_from<L: SectionLaw>(run: Run<'_, L>, opts: &BeltOptions, clock: Instant) -> Result<BeltSolution<L>, BeltError> {
    let Run { data, problem, scales, pulleys, guess, start } = run;
    let guess = Solution { eta: 1.0, ..guess.clone() };
    let solution = run::final_solve(&problem, &guess, opts)
        .map_err(|cause| BeltError::Solver { stage: "warm start from the previous point of the continuation", cause })?;
    on_branch(&problem, &solution, scales.force).map_err(BeltError::ContactViolated)?;
    let mut stats = Stats::default();
    stats.close_with(&solution.stats, clock);
    let solved = run::Solved { solution, stats, homotopy_steps: 0 };
    finish(data, problem, scales, pulleys, start, solved, opts)
}

/// The secant predictor of a continuation step: `newer` + r (`newer` − `older`) on
/// `newer`'s meshes. The difference of the states is taken at `newer`'s nodes (`older`
/// by its dense output there) and interpolated linearly inside each interval, added to
/// `newer`'s dense output; the parameters are extrapolated alike. `None` when the two
/// do not have the same segments, dimensions and parameters, or r is not finite.
pub fn secant_guess(newer: &Solution, older: &Solution, ratio: f64) -> Option<Solution> {
    let shaped = newer.segments.len() == older.segments.len()
        && newer.params.len() == older.params.len()
        && newer.segments.iter().zip(&older.segments).all(|(a, b)| a.dim() == b.dim());
    if !(shaped && ratio.is_finite()) {
        return None;
    }
    let segments = newer
        .segments
        .iter()
        .zip(&older.segments)
        .map(|(seg, old)| {
            // the step of every component at every node, r (y_newer − y_older)
            let steps: Vec<Vec<f64>> = seg
                .mesh
                .iter()
                .zip(&seg.nodes)
                .map(|(&x, y)| y.iter().zip(old.eval(x)).map(|(a, b)| ratio * (a - b)).collect())
                .collect();
            let nodes = seg.nodes.iter().zip(&steps).map(|(y, d)| y.iter().zip(d).map(|(a, b)| a + b).collect()).collect();
            let poly = seg
                .poly
                .iter()
                .enumerate()
                .map(|(i, comps)| {
                    comps
                        .iter()
                        .enumerate()
                        .map(|(j, c)| {
                            let mut c = c.clone();
                            c.resize(c.len().max(2), 0.0);
                            c[0] += steps[i][j];
                            c[1] += steps[i + 1][j] - steps[i][j];
                            c
                        })
                        .collect()
                })
                .collect();
            SegmentSolution { mesh: seg.mesh.clone(), nodes, poly }
        })
        .collect();
    let params = newer.params.iter().zip(&older.params).map(|(a, b)| a + ratio * (a - b)).collect();
    Some(Solution { segments, params, eta: newer.eta, stats: Stats::default() })
}

/// The solution of a solved run with its σ map, after the law's balance check and the
/// contact checks.
fn finish<L: SectionLaw>(
    data: L::Data,
    problem: BeltProblem<L>,
    scales: Scales,
    pulleys: Pulleys,
    start: L::Start,
    solved: run::Solved,
    opts: &BeltOptions,
) -> Result<BeltSolution<L>, BeltError> {
    let contour = Contour::new(pulleys.radius, pulleys.centre_distance).expect("validated geometry");
    let mut sol = BeltSolution {
        data,
        problem,
        solution: solved.solution,
        scales,
        pulleys,
        options: opts.clone(),
        stats: solved.stats,
        homotopy_steps: solved.homotopy_steps,
        start,
        sigma_map: SigmaMap::empty(contour),
    };
    sol.sigma_map = SigmaMap::new(contour, &sol.problem.topology.sides(), &sol.solution, |k, xi| {
        let p = sol.point(k, xi);
        [p.x, p.y]
    });
    L::check_balance(&sol)?;
    sol.check_contact()?;
    Ok(sol)
}

impl<L: SectionLaw> BeltSolution<L> {
    /// This solution with its BVP solution replaced by the secant predictor towards a
    /// point r steps beyond it ([`secant_guess`] from `older`): a warm start of a
    /// continuation with a first-order predictor. `None` unless both have the same
    /// scales and topology (then the scaled states are comparable) and the predictor
    /// exists.
    pub fn predicted(&self, older: &Self, ratio: f64) -> Option<Self>
    where
        L: Clone,
        L::Data: Clone,
        L::Start: Clone,
    {
        if self.scales != older.scales || self.problem.topology != older.problem.topology {
            return None;
        }
        let solution = secant_guess(&self.solution, &older.solution, ratio)?;
        Some(Self { solution, ..self.clone() })
    }

    /// The topology.
    pub fn topology(&self) -> &Topology {
        &self.problem.topology
    }

    /// The belt at segment `k`, normalised coordinate ξ ∈ [0, 1] (dense output; exact
    /// node values at ξ = 0, 1).
    pub fn point(&self, k: usize, xi: f64) -> BeltPoint {
        let y = self.solution.segments[k].state_at(xi);
        let p = &self.solution.params;
        let phi = match self.topology().segment(k).scaling {
            Scaling::Arc { start, end, .. } => {
                let (pa, pb) = (p[start], p[end]);
                Some(pa + xi.clamp(0.0, 1.0) * (pb - pa))
            }
            Scaling::Span { .. } => None,
        };
        self.problem.law.point(&self.data, &self.scales, self.topology(), k, phi, &y, p)
    }

    /// Points sampled along the whole loop: every mesh node and `per_interval` − 1 dense
    /// points inside each mesh interval, in the direction of σ, with their segment and ξ.
    pub fn samples(&self, per_interval: usize) -> Vec<(usize, f64, BeltPoint)> {
        self.solution.sample_points(per_interval).into_iter().map(|(k, xi)| (k, xi, self.point(k, xi))).collect()
    }

    /// The belt at mid-span (x = 0, a mesh node): (upper, lower).
    pub fn mid_span(&self) -> (BeltPoint, BeltPoint) {
        let (upper, lower) = self.topology().mid_spans();
        (self.point(upper, 1.0), self.point(lower, 1.0))
    }

    /// Contact angles of `pulley`: (first contact, [stick → slip,] last contact), rad,
    /// unwrapped, decreasing.
    pub fn contact_angles(&self, pulley: Pulley) -> Vec<f64> {
        self.topology().contact_angles(pulley, &self.solution.params)
    }

    /// The closure jump f (N) of a frictionless loop: the tension jump the discrete
    /// solution needs at the driver's first contact; 0 for the exact solution.
    pub fn closure_defect(&self) -> Option<f64> {
        self.topology().closure_jump().map(|j| self.solution.params[j] * self.scales.force)
    }

    /// The law's first integral at a point (N), where it has one.
    pub fn invariant(&self, point: &BeltPoint) -> Option<f64> {
        L::first_integral(&self.data, point)
    }

    /// The drift of the law's first integral round the loop, (max − min)/N_max over
    /// `per_interval` dense samples per mesh interval, and N_max (N): imposed nowhere, it
    /// measures the discretisation error. `None` where the law has no first integral.
    pub fn invariant_drift(&self, per_interval: usize) -> Option<(f64, f64)> {
        let pts = self.samples(per_interval);
        let (mut lo, mut hi, mut nmax) = (f64::INFINITY, f64::NEG_INFINITY, 0.0_f64);
        for (_, _, p) in &pts {
            let e = self.invariant(p)?;
            (lo, hi, nmax) = (lo.min(e), hi.max(e), nmax.max(p.tension));
        }
        Some(((hi - lo) / nmax, nmax))
    }

    /// Concentrated edge forces (jumps of Q at the contact boundaries), where the law
    /// outputs Q.
    pub fn edge_forces(&self) -> Option<EdgeForces> {
        if L::CONTACT_EDGES != ContactEdges::Forces {
            return None;
        }
        let topo = self.topology();
        let v = |k: usize, xi: f64| self.point(k, xi).shear;
        let jumps = |pulley: Pulley| -> Option<(f64, f64)> {
            let (before, after) = topo.spans_around(pulley);
            let (first, last) = (topo.first_arc(pulley), topo.last_arc(pulley));
            Some((v(before, 1.0)? - v(first, 0.0)?, v(last, 1.0)? - v(after, 0.0)?))
        };
        let (driven_start, driven_end) = jumps(Pulley::Driven)?;
        let (driver_start, driver_end) = jumps(Pulley::Driver)?;
        Some(EdgeForces { driven_start, driven_end, driver_start, driver_end })
    }

    /// Transport rate c (m/s) of a drive.
    pub fn transport_rate(&self) -> Option<f64> {
        self.topology().motion().map(|m| self.solution.params[m.transport] * self.scales.speed)
    }

    /// Driven pulley speed ω₂ (rad/s) of a drive.
    pub fn driven_speed(&self) -> Option<f64> {
        self.topology().motion().map(|m| self.solution.params[m.driven_speed] * self.scales.speed / self.scales.length)
    }

    /// Torque of the belt on `pulley` (N·m, clockwise positive) where the law integrates
    /// it: its value at the last contact.
    pub fn torque(&self, pulley: Pulley) -> Option<f64> {
        self.point(self.topology().last_arc(pulley), 1.0).torque
    }

    /// Check the conditions the segment topology assumes (docs/string-hanging.md,
    /// docs/rod-hanging.md, docs/string-drive.md, "Checks"): the topology, every value
    /// finite, the law's positive force, p ≥ 0 on the arcs, the stick-zone friction bound
    /// |f_t| ≤ μp and the slip direction with friction, no span point inside a pulley,
    /// edge forces ≥ 0 where the law has them.
    pub fn check_contact(&self) -> Result<(), BeltError> {
        let v = BeltError::ContactViolated;
        let topo = self.topology();
        let (window, slack) = self.problem.law.admissible_window();
        topo.check(&self.solution.params, window, slack).map_err(v)?;
        let Pulleys { radius, centre_distance, weight } = self.pulleys;
        let fr = self.scales.force;
        let pressure_floor = -1e-9 * (weight + fr / radius);
        let inside = radius * (1.0 - 1e-6);
        let mu = L::friction(&self.data);
        let law = &self.problem.law;
        let stick_tension = |pulley| topo.arc(pulley, ArcKind::Stick).map(|k| law.slip_force(&self.data, &self.point(k, 0.0)));
        // the pulley that puts power in drags the belt along its travel: the tension falls
        // from the stick zone through the slip zone; on the other it rises
        let flow = self.problem.law.power_flow();
        let puts_power_in = |pulley: Pulley| pulley.slip_sign(topo.direction(), flow) * topo.direction().sign() > 0.0;
        for (k, xi, pt) in self.samples(4) {
            let optional = [pt.theta, pt.effective_tension, pt.shear, pt.moment, pt.pressure, pt.friction];
            let finite = [pt.x, pt.y, pt.tension, pt.material].iter().chain(optional.iter().flatten()).all(|v| v.is_finite());
            if !finite {
                return Err(v(format!("non-finite solution in segment {k} at ξ = {xi:.4}")));
            }
            let kind = topo.segment(k).kind;
            if let Some((name, value)) = L::positive_force(kind, &pt) {
                if value <= 0.0 {
                    return Err(v(format!("{name} {value:.4e} N ≤ 0 at ({:.5}, {:.5}) m", pt.x, pt.y)));
                }
            }
            let Some(pulley) = topo.segment(k).pulley() else {
                for pulley in [Pulley::Driver, Pulley::Driven] {
                    let dist = (pt.x - pulley.centre_x() * centre_distance).hypot(pt.y);
                    if dist < inside {
                        return Err(v(format!(
                            "free span passes through the {} pulley: distance {dist:.6} m from its centre < R = {radius:.6} m at ({:.5}, {:.5}) m",
                            pulley.name(),
                            pt.x,
                            pt.y
                        )));
                    }
                }
                continue;
            };
            let name = pulley.name();
            let p = pt.pressure.unwrap_or(f64::NAN);
            if p < pressure_floor {
                return Err(v(format!(
                    "contact force {p:.4e} N/m < 0 on the {name} pulley at ({:.5}, {:.5}) m: the belt would lift off inside the arc",
                    pt.x, pt.y
                )));
            }
            let (Some(mu), Some(tau)) = (mu, pt.friction) else { continue };
            if kind == SegmentKind::Arc(ArcKind::Stick) && tau.abs() > mu * p - pressure_floor {
                return Err(v(format!(
                    "the stick zone on the {name} pulley needs friction {:.4e} N/m > μp = {:.4e} N/m at ({:.5}, {:.5}) m",
                    tau.abs(),
                    mu * p,
                    pt.x,
                    pt.y
                )));
            }
            let tol = 1e-9 * fr;
            if kind == SegmentKind::Arc(ArcKind::Slip) {
                let tension = law.slip_force(&self.data, &pt);
                match (puts_power_in(pulley), stick_tension(pulley)) {
                    (true, Some(t)) if tension > t + tol => {
                        return Err(v(format!(
                            "slip direction: tension {tension:.6e} N above the stick tension {t:.6e} N in the {name} pulley's slip zone (it puts power in)"
                        )));
                    }
                    (false, Some(t)) if tension < t - tol => {
                        return Err(v(format!(
                            "slip direction: tension {tension:.6e} N below the stick tension {t:.6e} N in the {name} pulley's slip zone (it takes power out)"
                        )));
                    }
                    _ => {}
                }
            }
        }
        if let Some(e) = self.edge_forces() {
            let floor = -1e-7 * fr;
            for (what, f) in [
                ("driven first contact", e.driven_start),
                ("driven last contact", e.driven_end),
                ("driver first contact", e.driver_start),
                ("driver last contact", e.driver_end),
            ] {
                if f < floor {
                    return Err(v(format!("edge force {f:.4e} N < 0 at the {what}: the pulley would pull")));
                }
            }
        }
        Ok(())
    }

    /// The belt point at contour coordinate σ, with its segment.
    pub fn at_sigma(&self, sigma: f64) -> (usize, BeltPoint) {
        let (k, xi) = self.sigma_map.locate(sigma, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        });
        (k, self.point(k, xi))
    }

    /// The largest value of `f` over the segments `ks` (its smallest: pass −f), by
    /// [`sampled_extremum`] on their meshes.
    pub fn arc_extremum(&self, ks: &[usize], f: impl Fn(&BeltPoint) -> f64) -> f64 {
        let meshes: Vec<(usize, &[f64])> = ks.iter().map(|&k| (k, self.solution.segments[k].mesh.as_slice())).collect();
        sampled_extremum(&meshes, |k, xi| f(&self.point(k, xi)))
    }

    /// Slip dissipation D = ∫_slip f_t (ωR − cλ) ds on `pulley` turning at `omega`
    /// (rad/s) (W), by 5-point Gauss–Legendre quadrature on each mesh interval of the
    /// slip arc's dense output (spec §1 (D)); `None` without a slip arc or transport.
    pub fn slip_dissipation(&self, pulley: Pulley, omega: f64) -> Option<f64> {
        let topo = self.topology();
        let k = topo.arc(pulley, ArcKind::Slip)?;
        let c = self.transport_rate()?;
        let r = self.pulleys.radius;
        let Scaling::Arc { start: ia, end: ib, .. } = topo.segment(k).scaling else { return None };
        let dphi = (self.solution.params[ib] - self.solution.params[ia]).abs();
        Some(arc_integral(&self.solution.segments[k].mesh, dphi, r, |xi| self.point(k, xi), |pt| pt.friction.unwrap_or(0.0) * (omega * r - c * pt.stretch)))
    }

    fn pulley_summary(&self, pulley: Pulley, edges: Option<EdgeForces>) -> PulleySummary {
        let angles = self.contact_angles(pulley);
        let (a, b) = (angles[0], angles[angles.len() - 1]);
        // (first, second) arc along σ: stick then slip clockwise, slip then stick
        // counter-clockwise (the stick arc is where the belt runs on)
        let stick_slip = (angles.len() == 3).then(|| {
            let (first, second) = (a - angles[1], angles[1] - b);
            let stick_first = self.topology().arc(pulley, ArcKind::Stick) == Some(self.topology().first_arc(pulley));
            if stick_first { (first, second) } else { (second, first) }
        });
        let (edge_start, edge_end) = match (pulley, edges) {
            (Pulley::Driver, Some(e)) => (Some(e.driver_start), Some(e.driver_end)),
            (Pulley::Driven, Some(e)) => (Some(e.driven_start), Some(e.driven_end)),
            (Pulley::Single, _) | (_, None) => (None, None),
        };
        let edge_pressure = |k: usize, xi: f64| match L::CONTACT_EDGES {
            ContactEdges::Pressures => self.point(k, xi).pressure,
            ContactEdges::Forces => None,
        };
        let topo = self.topology();
        let arcs = topo.arcs_on(pulley);
        // spec §2.6/§3.7's Cosserat additions: over the contact zone, its edges included
        let cosserat = L::CONTACT_EDGES == ContactEdges::Pressures;
        let pressure_min = cosserat.then(|| -self.arc_extremum(&arcs, |p| -p.pressure.unwrap_or(f64::NAN))).filter(|v| v.is_finite());
        let shear_strain_max = cosserat.then(|| self.arc_extremum(&arcs, |p| p.shear_strain.map_or(f64::NAN, f64::abs))).filter(|v| v.is_finite());
        let moment = |k: usize, xi: f64| if cosserat { self.point(k, xi).moment } else { None };
        // steady friction: the stick zone's stretch (constant there), the stick → slip
        // angle and the slip zone's dissipation at the stick kinematics ω = cλ_B/R (D-4)
        let stretch_stick = topo.arc(pulley, ArcKind::Stick).map(|k| self.point(k, 0.5).stretch);
        let dissipation = match (stretch_stick, self.transport_rate()) {
            (Some(lambda), Some(c)) => self.slip_dissipation(pulley, c * lambda / self.pulleys.radius),
            _ => None,
        };
        PulleySummary {
            edge_pressure_start: edge_pressure(topo.first_arc(pulley), 0.0),
            edge_pressure_end: edge_pressure(topo.last_arc(pulley), 1.0),
            pressure_min,
            stick_slip_angle: (angles.len() == 3).then(|| wrap_angle(angles[1])),
            shear_strain_max,
            moment_start: moment(topo.first_arc(pulley), 0.0),
            moment_end: moment(topo.last_arc(pulley), 1.0),
            stretch_stick,
            dissipation,
            contact_arc: Some(a - b),
            contact_start: Some(wrap_angle(a)),
            contact_end: Some(wrap_angle(b)),
            stick_arc: stick_slip.map(|s| s.0),
            slip_arc: stick_slip.map(|s| s.1),
            torque: self.torque(pulley),
            edge_force_start: edge_start,
            edge_force_end: edge_end,
        }
    }
}

impl<L: SectionLaw> SolutionView for BeltSolution<L> {
    fn path(&self) -> Path {
        self.sigma_map.path()
    }

    super::view::sampled_view_methods!();

    fn summary(&self) -> Summary {
        let topo = self.topology();
        let (upper, lower) = self.mid_span();
        // N at the middle of the pulley's stick arc (ξ = ½: φ is linear in ξ on an arc),
        // spec §3.7 and the FE's definition (docs/fem-drive.md §8); for the string and the
        // Kirchhoff rod N is constant in a stick zone, for the Cosserat belt it varies in
        // the edge layers at its ends.
        let stick_middle = |pulley| topo.arc(pulley, ArcKind::Stick).map(|k| self.point(k, 0.5).tension);
        let edges = self.edge_forces();
        Summary {
            y_upper_mid: Some(upper.y),
            y_lower_mid: Some(lower.y),
            tension_upper_mid: Some(upper.tension),
            tension_lower_mid: Some(lower.tension),
            moment_upper_mid: upper.moment,
            moment_lower_mid: lower.moment,
            tension_tight: stick_middle(Pulley::Driver),
            tension_slack: stick_middle(Pulley::Driven),
            driven_speed: self.driven_speed(),
            transport_rate: self.transport_rate(),
            driver: Some(self.pulley_summary(Pulley::Driver, edges)),
            driven: Some(self.pulley_summary(Pulley::Driven, edges)),
            ..Summary::default()
        }
    }
}

/// A law whose start is the tight loop (straight spans, half-turn arcs, uniform tension).
pub trait TightLoop: SectionLaw {
    /// The state of a segment of `kind` at a point of the tight loop: position (x, y),
    /// span force (F_x, F_y), tension `tension`, material coordinate `material` (scaled).
    fn tight_state(&self, kind: SegmentKind, position: [f64; 2], force: [f64; 2], tension: f64, material: f64) -> Vec<f64>;
}

/// The tight loop as a solution at η = 0 on `nodes` nodes per segment: tension `tension`
/// and stretch `stretch` throughout (scaled), straight spans of unstretched length
/// 1/(2λ) each half, half-turn arcs of unstretched length πR/λ on pulleys of scaled
/// radius `radius` (with friction all stick: the slip arcs have zero length).
pub fn tight_guess<L: TightLoop>(problem: &BeltProblem<L>, tension: f64, stretch: f64, radius: f64, nodes: usize) -> Solution {
    let topo = &problem.topology;
    let l = 0.5 / stretch;
    let arc = PI * radius / stretch;
    let params = topo.tight_params(l);
    // Start of each segment's material coordinate and its unstretched length.
    let mut s0 = Vec::with_capacity(topo.len());
    let mut acc = 0.0;
    for seg in topo.segments() {
        let length = match seg.kind {
            SegmentKind::Span => l,
            SegmentKind::Arc(ArcKind::Slip) => 0.0,
            SegmentKind::Arc(_) => arc,
        };
        s0.push((acc, length));
        acc += length;
    }
    Solution::from_fn(topo.len(), nodes, params, 0.0, |k, x| {
        let seg = topo.segment(k);
        let (start, length) = s0[k];
        let material = start + length * x;
        match seg.pulley() {
            Some(_) => problem.law.tight_state(seg.kind, [0.0, 0.0], [0.0, 0.0], tension, material),
            None => {
                // Upper spans run left to right at y = R, lower spans right to left at −R;
                // the first half of each ends at x = 0.
                let upper = seg.side == crate::sigma_map::Side::UpperSpan;
                let first_half = topo.junction(k) == super::topology::Junction::MidSpan;
                let (x0, dir, y) = match (upper, first_half) {
                    (true, true) => (-0.5, 1.0, radius),
                    (true, false) => (0.0, 1.0, radius),
                    (false, true) => (0.5, -1.0, -radius),
                    (false, false) => (0.0, -1.0, -radius),
                };
                problem.law.tight_state(seg.kind, [x0 + dir * 0.5 * x, y], [dir * tension, 0.0], tension, material)
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::belt::topology::ContactModel;
    use crate::problem::Problem;
    use crate::string_drive::ScaledStringDrive;
    use crate::string_hanging::ScaledStringHanging;

    /// The largest |condition| and |y′ − f| (at ξ = ½ of every segment) of the tight
    /// loop of `problem` at η = 0.
    fn tight_defects<L: TightLoop>(problem: &BeltProblem<L>, tension: f64, stretch: f64, radius: f64) -> (f64, f64) {
        let g = tight_guess(problem, tension, stretch, radius, 5);
        let ya: Vec<&[f64]> = g.segments.iter().map(|s| s.start()).collect();
        let yb: Vec<&[f64]> = g.segments.iter().map(|s| s.end()).collect();
        let mut r = vec![0.0; problem.n_bc()];
        problem.bc(&ya, &yb, &g.params, 0.0, &mut r);
        let conditions = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut slope_gap = 0.0f64;
        for (k, seg) in g.segments.iter().enumerate() {
            let mut f = vec![0.0; problem.dim(k)];
            problem.rhs(k, 0.5, &seg.eval(0.5), &g.params, 0.0, &mut f);
            let slope = seg.eval_derivative(0.5);
            slope_gap = f.iter().zip(&slope).fold(slope_gap, |m, (a, b)| m.max((a - b).abs()));
        }
        (conditions, slope_gap)
    }

    /// The tight loop is the exact solution at η = 0 of the string (frictionless arcs)
    /// and of the drive at rest (stick arcs, slip arcs of zero length, no torque): every
    /// condition and the ODE residual of every segment vanish to round-off (1e-13 on
    /// O(1) scaled values).
    #[test]
    fn tight_loop_solves_the_start() {
        let string = ScaledStringHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length_start: 3.0, length: 3.2 };
        let stretch = (2.0 + 2.0 * PI * string.radius) / string.length_start;
        let tension = string.axial_stiffness * (stretch - 1.0);
        let pb = BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), string);
        let (conditions, slope) = tight_defects(&pb, tension, stretch, 0.18);
        assert!(conditions < 1e-13 && slope < 1e-13, "string: conditions {conditions:e}, y′ − f {slope:e}");

        let drive = ScaledStringDrive::fixture(true, 0.7);
        let tension = drive.tight_tension();
        let stretch = 1.0 + tension / drive.axial_stiffness;
        let pb = BeltProblem::new(Topology::two_pulley(ContactModel::Coulomb), drive);
        let (conditions, slope) = tight_defects(&pb, tension, stretch, 0.18);
        assert!(conditions < 1e-13 && slope < 1e-13, "drive: conditions {conditions:e}, y′ − f {slope:e}");
    }

    /// The secant predictor on two solutions on different meshes (the older's a
    /// superset of the newer's, so that both hold g at the newer's nodes), y(x; t) =
    /// g(x) + t·h(x) with h linear in x (so that the step is exact at the nodes and its
    /// linear interpolation exact inside): the predictor at t₁ + r(t₁ − t₀) is newer's dense
    /// output plus r(t₁ − t₀)·h to round-off at nodes and mid-intervals, the parameters
    /// extrapolated alike; other shapes or a non-finite ratio give `None`.
    #[test]
    fn secant_guess_extrapolates_along_the_line() {
        let g = |x: f64| [x * x * x, (3.0 * x).sin()];
        let h = |x: f64| [2.0 - x, 0.5 + 3.0 * x];
        let at = |mesh: &[f64], t: f64| {
            let nodes = mesh.iter().map(|&x| g(x).iter().zip(h(x)).map(|(a, b)| a + t * b).collect()).collect();
            Solution { segments: vec![SegmentSolution::piecewise_linear(mesh.to_vec(), nodes)], params: vec![1.0 + t, -2.0 * t], eta: 1.0, stats: Stats::default() }
        };
        let (t0, t1, r) = (0.3, 0.5, 1.5);
        let older = at(&[0.0, 0.05, 0.1, 0.25, 0.4, 0.6, 0.75, 0.9, 1.0], t0);
        let newer = at(&[0.0, 0.1, 0.25, 0.6, 0.9, 1.0], t1);
        let p = secant_guess(&newer, &older, r).expect("same shapes");
        let dt = r * (t1 - t0);
        let seg = &p.segments[0];
        assert_eq!(seg.mesh, newer.segments[0].mesh);
        for x in [0.0, 0.05, 0.1, 0.2, 0.25, 0.4, 0.6, 0.75, 0.9, 0.95, 1.0] {
            let want: Vec<f64> = newer.eval(0, x).iter().zip(h(x)).map(|(a, b)| a + dt * b).collect();
            for (a, b) in seg.eval(x).iter().zip(&want) {
                assert!((a - b).abs() < 1e-14, "dense output at {x}: {a} against {b}");
            }
        }
        for (y, &x) in seg.nodes.iter().zip(&seg.mesh) {
            for (a, b) in y.iter().zip(seg.eval(x)) {
                assert!((a - b).abs() < 1e-14, "node value at {x} against the dense output");
            }
        }
        let t2 = t1 + dt;
        for (a, b) in p.params.iter().zip([1.0 + t2, -2.0 * t2]) {
            assert!((a - b).abs() < 1e-14, "parameter {a} against {b}");
        }
        assert!(secant_guess(&newer, &older, f64::NAN).is_none());
        let fewer = Solution { params: vec![1.0], ..older.clone() };
        assert!(secant_guess(&newer, &fewer, r).is_none());
    }
}
