//! Paper D's own scheme for the steady two-pulley drive (spec §3.4–§3.5; docs/cosserat-drive.md,
//! "FE, second way"): a **fixed topology** — on each pulley the stick rows v = 0 up to a
//! prescribed stick→slip point B and the slip rows τ = sμp after it (s the slip
//! direction), on a mesh with a (split) node at each B — instead of the semismooth
//! solve's Coulomb complementarity. The fixed system is square for any (B₁, B₂), but a
//! wrong B leaves a stick zone that Coulomb's law would not hold: its stick tractions
//! exceed μp where the stick constraint absorbs a tension jump (a concentrated traction).
//! The matching measure of pulley k is that excess, signed,
//!
//! ```text
//!   E_k = Σ_{stick points i of k} w_i (τ_i − clip(τ_i, −μp_i, μp_i))   (N),
//! ```
//!
//! zero exactly when every stick point obeys Coulomb's bound (the slip points obey it by
//! their row): the fixed topology then is a state of Coulomb's law, a solution of the
//! original problem. On the FE the excess sits at the stick→slip node itself (measured;
//! the spec expected it at the stick-zone entry), and E_k vanishes on a *band* of B_k
//! about one local element wide, not at a point — so a root finder that stops at the
//! first zero (Brent) would return any point of it. The scheme locates each band by a
//! scalar search per pulley in the travel coordinate ([`Band`]: steps, regula falsi,
//! then bisection of both edges), both pulleys advanced by each solve, and takes the
//! band centres — for the Cosserat element. On the string (nodal normal) the points are
//! instead the roots of a smooth matching function, the front speed G_k = s_k·v(B_k⁺)
//! (`PaperD::fronts`, [`Root`]), and the slip rows' bound is the drum's reaction from
//! the belt's radial equilibrium (`SteadyProblem::equilibrium_normal`): docs/fem-drive.md
//! §12, "Fourth round".

use std::cell::RefCell;

use numerics::Sig;

use super::*;

pub use drive::scene::SteadyScheme;

/// The scheme a steady loop runs (`fem.steady_scheme` resolved): `auto` by the belt's
/// friction normal — Paper D's on the string (nodal normal) when the mesh may be fitted,
/// else the semismooth fit; a named scheme as it is.
pub(crate) fn resolved(scheme: SteadyScheme, normal: FrictionNormal, fitting: bool) -> SteadyScheme {
    match scheme {
        SteadyScheme::Auto if normal == FrictionNormal::Nodal && fitting => SteadyScheme::PaperD,
        SteadyScheme::Auto => SteadyScheme::Semismooth,
        named => named,
    }
}

/// The growth of the default normal penalty with the mesh under Paper D's scheme on the
/// string (the Cosserat rod's bands keep κ: not measured there):
/// max(1, (n/128)²) for n elements (P = κ (n/128)² EA/R², from 128 elements on). The
/// penetration δ = p/P shortens the belt's path round both drums by 2πδ, a uniform
/// relative tension error 2πR/(κL) wherever the span tension is set by the stretch
/// (3.6e-6 at κ = 10⁵ on the low-tension drive, R = 0.08 m, L = 1.41 m), while the
/// mesh error falls like h²: with a fixed κ the penalty's error is the larger one from
/// ≈ 512 elements and the tensions stop converging there (docs/fem-drive.md §12, "Ninth
/// round"). κ ∝ n² keeps it a fixed fraction of the mesh error. Applied to the
/// fixed-topology solves only (`steady::solve_layout`), whose prescribed contact set
/// takes the stiffer penalty: the static start, the load continuation and the
/// semismooth fit keep κ (with it, the fit's low-tension driven slip arc at 512 elements
/// got worse, 4.5e-4 → 3.5e-3).
pub(crate) fn penalty_mesh_scale(elements: usize) -> f64 {
    (elements as f64 / 128.0).powi(2).max(1.0)
}

/// Work and outcome of Paper D's scheme (in the run's `options.drive.report.paper_d`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct PaperDReport {
    /// Outer iterations: evaluations of the matching measures, i.e. fixed-topology
    /// (auxiliary) solves at a new pair (B₁, B₂).
    pub outer_iterations: usize,
    /// Newton solves of the fixed topology in all (refits to the contact boundaries
    /// at a pair included).
    pub auxiliary_solves: usize,
    /// The matching measures E₁, E₂ (driver, driven) at the result, N.
    pub matching_residual: [f64; 2],
    /// The prescribed stick→slip points at the result, σ on the contour, m.
    pub transition_sigma: [f64; 2],
    /// Width of the band of prescribed points whose fixed topology is Coulomb-admissible
    /// (E = 0) per pulley, m: the result is its centre (the Cosserat element). On the
    /// string, whose points are the roots of the front speeds, the width of each root's
    /// last bracket (0 when the secant ended before bracketing it).
    pub band_width: [f64; 2],
    /// The front speeds G₁, G₂ at the result (driver, driven; `PaperD::fronts`: the slip
    /// run's relative velocity extrapolated to its prescribed start), m/s.
    pub front_speed: [f64; 2],
    /// Wall time of the scheme (after the load continuation), s.
    pub seconds: f64,
}

/// Most fixed-topology solves at a new pair of points (outer iterations).
const MAX_OUTER: usize = 32;

/// Polishing steps of the front roots after their searches end (`front_roots`).
const POLISH: usize = 8;

/// Most refits to the contact boundaries at one pair of points.
const BOUNDARY_PASSES: usize = 3;

/// One solved fixed-topology state at the prescribed points `at` (σ, m).
struct Aux<const N: usize, K: LayoutElement<N> + ?Sized> {
    at: [f64; 2],
    state: State<N, K>,
    defects: [f64; 2],
    fronts: [f64; 2],
}

/// The scheme's fixed parts and its solved states.
pub(super) struct PaperD<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    data: SteadyFitData<'a, K>,
    elements: usize,
    arc_weight: f64,
    /// Slip direction s of each pulley's slip rows (driver, driven).
    slip_sign: [f64; 2],
    mu: f64,
    solved: RefCell<Vec<Aux<N, K>>>,
    report: RefCell<PaperDReport>,
    newton_iterations: RefCell<usize>,
    _sizes: std::marker::PhantomData<([f64; P], [f64; E])>,
}

impl<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> PaperD<'a, N, P, E, K> {
    pub(super) fn new(start: State<N, K>, data: SteadyFitData<'a, K>, elements: usize, arc_weight: f64, mu: f64, load: f64) -> Self {
        // the driver drives when the load resists (M₂ + d₂ω₂ of the sign of ω₁): its belt is
        // slower than its surface in the slip zone, v < 0 clockwise (τ and v share their sign)
        let s = -load.signum();
        let defects = [f64::NAN; 2];
        PaperD {
            data,
            elements,
            arc_weight,
            slip_sign: [s, -s],
            mu,
            solved: RefCell::new(vec![Aux { at: [f64::NAN; 2], state: start, defects, fronts: [f64::NAN; 2] }]),
            report: RefCell::new(PaperDReport::default()),
            newton_iterations: RefCell::new(0),
            _sizes: std::marker::PhantomData,
        }
    }

    fn contour(&self) -> Contour {
        *self.solved.borrow()[0].state.asm.mesh().contour()
    }

    /// The fixed topology's points on `asm` with the transitions `at`: the node at each
    /// is split, the points of a pulley upstream of its transition (in the travel) stick,
    /// downstream slip.
    /// The nodes at the contact boundaries `zones` (pulley, σ_start, σ_end) carry their
    /// contact side only ([`contact_side_halves`]; on the Cosserat rod since
    /// docs/fem-cosserat.md §11.1, as in the semismooth scheme's refits).
    fn points(&self, asm: &Assembler<N, K>, at: [f64; 2], zones: &[(Pulley, f64, f64)]) -> Vec<FrictionPoint> {
        let contour = *asm.mesh().contour();
        let sign = self.data.direction.sign();
        let mut points = friction_points(asm, &at, self.data.direction);
        let nodal = self.data.kernel.friction_normal() == FrictionNormal::Nodal;
        contact_side_halves(&mut points, zones, contour.length());
        for p in &mut points {
            // the string: the contact set is the topology's (`in_contact_zone`)
            if nodal && !in_contact_zone(p, zones, contour.length()) {
                p.fixed = Some(Fixed::Free);
                continue;
            }
            let k = usize::from(p.pulley == Pulley::Driven);
            let u = sign * (unwrapped(&contour, p.pulley, p.sigma) - unwrapped(&contour, p.pulley, at[k]));
            // a half of the split node: the upstream half sticks
            let stick = if u.abs() <= 1e-9 * contour.length() { sign * p.part.offset() < 0.0 || p.part == Part::Whole } else { u < 0.0 };
            p.fixed = Some(if stick { Fixed::Stick } else { Fixed::Slip(self.slip_sign[k]) });
        }
        points
    }

    /// E₁, E₂ of a solved state (module documentation).
    fn defects(&self, results: &[PointResult]) -> [f64; 2] {
        let mut e = [0.0; 2];
        for p in results.iter().filter(|p| p.normal > 0.0 && p.point.fixed == Some(Fixed::Stick)) {
            let b = self.mu * p.normal;
            e[usize::from(p.point.pulley == Pulley::Driven)] += p.point.weight * (p.traction - p.traction.clamp(-b, b));
        }
        e
    }

    /// The front speeds G₁, G₂ of a solved state at the transitions `at`: on each pulley
    /// ŝ·v(B⁺), the relative velocity of the slip run extrapolated to its prescribed start B
    /// by the quadratic through its first three distinct velocity samples (each
    /// element's v at its midpoint). A concentrated stick traction J at B makes the
    /// tension jump by J there, so v(B⁺) = cJ/EA: G is a smooth signed measure of J
    /// with a simple root at the transition of Coulomb's law (the clipped excess E is
    /// zero on a band about an element wide, module documentation).
    fn fronts(&self, results: &[PointResult], at: [f64; 2]) -> [f64; 2] {
        let contour = self.contour();
        let sign = self.data.direction.sign();
        [Pulley::Driver, Pulley::Driven].map(|pulley| {
            let k = usize::from(pulley == Pulley::Driven);
            let u = |sigma: f64| sign * unwrapped(&contour, pulley, sigma);
            let mut slip: Vec<&PointResult> = results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0 && matches!(p.point.fixed, Some(Fixed::Slip(_)))).collect();
            slip.sort_by(|a, b| (u(a.point.sigma), sign * a.point.part.offset()).partial_cmp(&(u(b.point.sigma), sign * b.point.part.offset())).unwrap_or(std::cmp::Ordering::Equal));
            let mut samples: Vec<(f64, f64)> = Vec::with_capacity(3);
            for p in slip {
                let x = u(p.point.velocity_sigma());
                if samples.last().is_none_or(|q| (x - q.0).abs() > 1e-12) {
                    samples.push((x, p.velocity));
                }
                if samples.len() == 3 {
                    break;
                }
            }
            let b = u(at[k]);
            let v = match samples[..] {
                [(x0, y0), (x1, y1), (x2, y2)] => {
                    let d1 = (y1 - y0) / (x1 - x0);
                    let d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
                    y0 + d1 * (b - x0) + d2 * (b - x0) * (b - x1)
                }
                [(x0, y0), (x1, y1)] => y0 + (y1 - y0) / (x1 - x0) * (b - x0),
                [(_, y0)] => y0,
                _ => f64::NAN,
            };
            // NaN without a slip sample: the root search stops there and `front_roots`
            // refuses it (a missing measure is not a root)
            if v.is_finite() { self.slip_sign[k] * v } else { f64::NAN }
        })
    }

    /// Solve the fixed topology at the transitions `at` from the solved state nearest to
    /// it: a mesh with a node at each contact boundary located on that state and at each
    /// transition, then refits to the boundaries located on the new state (at most
    /// `passes`, until they are within `tolerance` of their nodes).
    fn solve_at(&self, at: [f64; 2]) -> Result<([f64; 2], [f64; 2]), FemError> {
        let contour = self.contour();
        let d = &self.data;
        let lc = contour.length();
        let dist = |a: &[f64; 2]| if a[0].is_nan() { f64::INFINITY } else { crate::fitting::periodic_diff(a[0], at[0], lc).abs().max(crate::fitting::periodic_diff(a[1], at[1], lc).abs()) };
        let nearest = {
            let s = self.solved.borrow();
            let (i, _) = s.iter().enumerate().min_by(|a, b| dist(&a.1.at).total_cmp(&dist(&b.1.at))).expect("the start");
            i
        };
        self.report.borrow_mut().outer_iterations += 1;
        let (mut x_from, mut sol, mut results_from, mut nz_from) = {
            let s = self.solved.borrow();
            let st = &s[nearest].state;
            (st.x.clone(), solution(st, d), st.results.clone(), st.asm.len())
        };
        let arc_element = {
            let s = self.solved.borrow();
            PI * d.r / s[0].state.asm.mesh().elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1) as f64
        };
        let mut state = None;
        // the node-snapped contact zones of the last pass's mesh
        let mut zones_fitted: Vec<(Pulley, f64, f64)> = Vec::new();
        // the contact boundaries follow the transitions by a fraction of an element: at most
        // BOUNDARY_PASSES refits, until they are within 1 % of an arc element of their nodes
        for _pass in 0..BOUNDARY_PASSES {
            let boundaries = sol.contact_boundaries();
            if let Some(st) = &state {
                let st: &State<N, K> = st;
                let nodes = st.asm.mesh().node_sigmas();
                let off = boundaries.iter().map(|&g| nodes.iter().map(|&n| crate::fitting::periodic_diff(n, g, lc).abs()).fold(f64::INFINITY, f64::min)).fold(0.0f64, f64::max);
                if off <= 1e-2 * arc_element {
                    break;
                }
            }
            let mut breaks = boundaries.clone();
            breaks.extend(at);
            // the boundaries the mesh is fitted to (a Cosserat rod's: the gap crossings
            // corrected by the penalty layer; the string's: its zones)
            let zones = sol.contact_edges();
            // the string: a zone's part on a span's straight contour in elements of at most
            // half an arc element (`span_contact_breaks`)
            if self.data.kernel.friction_normal() == FrictionNormal::Nodal {
                breaks.extend(span_contact_breaks(&contour, &zones, 0.5 * arc_element));
            }
            let (mesh, _) = Mesh::graded(contour, self.elements, self.arc_weight, &breaks, d.grading)?;
            let zones = zones_on_nodes(&zones, &mesh);
            // a refit that would rebuild the same mesh — no node and no contact-zone end
            // more than 1 % of an arc element from the last pass's — solves the same fixed
            // topology again: the last pass's state stands. The boundary check above does
            // not see it where `Mesh::graded` dropped a boundary within 2 % of an element of
            // an arc's end (it then stays off its node) or where the located boundary moves
            // by less than a node's snap each pass: 27 solves for 9 pairs on the Exudyn
            // scene at 128 elements before (docs/fem-drive.md §12, "Tenth round")
            if let Some(st) = &state {
                let st: &State<N, K> = st;
                if same_mesh(st.asm.mesh(), &mesh, &zones_fitted, &zones, 1e-2 * arc_element) {
                    break;
                }
            }
            zones_fitted.clone_from(&zones);
            let asm = Assembler::with_kernel(mesh, d.kernel.clone());
            let points = self.points(&asm, at, &zones);
            let mut x = crate::static_homotopy::transfer(&sol, &asm);
            x.extend([x_from[nz_from], x_from[nz_from + 1]]);
            x.extend(points.iter().map(|p| interpolate_traction(&results_from, &contour, p)));
            let prob: SteadyProblem<N, P, E, K> = SteadyProblem { asm: &asm, params: d.params, length: d.length, points: &points, sp: (d.sp_at)(1.0), strain_rule: d.strain_rule };
            let w = variable_weights(&asm, d.h, d.r, d.omega1.abs(), d.f_ref, points.len());
            let scales = row_scales(&asm, d.f_ref, points.len());
            let n = newton_or_ladder(&prob, &mut x, &w, &scales, d.tolerance, d.max_iterations, &[1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0]).map_err(|e| FemError::PaperDFailed {
                outer: self.report.borrow().outer_iterations,
                residual: f64::NAN,
                reason: format!("the fixed-topology solve at the prescribed points σ_B = ({}, {}) m did not converge: {e}", Sig(at[0]), Sig(at[1])),
            })?;
            *self.newton_iterations.borrow_mut() += n.iterations;
            self.report.borrow_mut().auxiliary_solves += 1;
            numerics::phases::count(numerics::phases::Step::FittingPass, 1);
            let results = prob.evaluate(&x, false).map(|e| e.results).unwrap_or_default();
            let st = State { asm, x, results, rho: self.solved.borrow()[0].state.rho };
            sol = solution(&st, d);
            (x_from, results_from, nz_from) = (st.x.clone(), st.results.clone(), st.asm.len());
            state = Some(st);
        }
        let state = state.expect("one pass");
        let defects = self.defects(&state.results);
        let fronts = self.fronts(&state.results, at);
        self.solved.borrow_mut().push(Aux { at, state, defects, fronts });
        Ok((defects, fronts))
    }
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> PaperD<'_, N, P, E, K> {
    /// Run the scheme from the load continuation's state; the solved state, the report and
    /// the Newton iterations spent.
    ///
    /// # Errors
    /// [`FemError::PaperDFailed`].
    pub(super) fn run(self) -> Result<(State<N, K>, PaperDReport, usize), FemError> {
        let clock = std::time::Instant::now();
        let contour = self.contour();
        let start: [Option<f64>; 2] = {
            let s = self.solved.borrow();
            [Pulley::Driver, Pulley::Driven].map(|p| transition(&s[0].state.results, &contour, p))
        };
        let [Some(b1), Some(b2)] = start else {
            return Err(FemError::PaperDFailed { outer: 0, residual: f64::NAN, reason: format!("the load continuation's state has no stick→slip point on a pulley (driver {:?}, driven {:?}) to start from", start[0], start[1]) });
        };
        let sign = self.data.direction.sign();
        // u = ς·σ unwrapped: the coordinate running with the belt
        let u_of = |k: usize, sigma: f64| sign * unwrapped(&contour, [Pulley::Driver, Pulley::Driven][k], sigma);
        let arc_element = {
            let s = self.solved.borrow();
            let mesh = s[0].state.asm.mesh();
            PI * self.data.r / mesh.elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1) as f64
        };
        let start = [u_of(0, b1), u_of(1, b2)];
        // the string (nodal normal): the roots of the front speeds; the Cosserat element
        // (tributary normal): the centres of the bands of E = 0 (module documentation)
        let (at, widths) = match self.data.kernel.friction_normal() {
            FrictionNormal::Nodal => self.front_roots(start, arc_element)?,
            FrictionNormal::Tributary => self.band_centres(start, arc_element)?,
        };
        let e = {
            let s = self.solved.borrow();
            let last = s.last().expect("solved");
            if last.at == at {
                last.defects
            } else {
                drop(s);
                self.solve_at(at)?.0
            }
        };
        if e != [0.0; 2] {
            return Err(FemError::PaperDFailed {
                outer: self.report.borrow().outer_iterations,
                residual: e[0].abs().max(e[1].abs()),
                reason: format!("the located stick→slip points σ_B = ({}, {}) m leave a concentrated stick traction E = ({}, {}) N", Sig(at[0]), Sig(at[1]), Sig(e[0]), Sig(e[1])),
            });
        }
        if let Some(r) = lifted_prescribed(&self.solved.borrow().last().expect("solved").state.results) {
            return Err(FemError::PaperDFailed {
                outer: self.report.borrow().outer_iterations,
                residual: r.normal.abs(),
                reason: format!(
                    "the prescribed point at σ = {} m on the {} presses by the penalty but its drum reaction from the radial balance is {} N/m < 0 (the span's tension below ρc²λ there): its row would be dropped to τ = 0, so the fixed topology has no admissible state",
                    Sig(r.point.sigma),
                    r.point.pulley.name(),
                    Sig(r.normal)
                ),
            });
        }
        let best = self.solved.into_inner().pop().expect("solved");
        let mut report = self.report.into_inner();
        report.matching_residual = best.defects;
        report.transition_sigma = best.at;
        report.band_width = widths;
        report.front_speed = best.fronts;
        report.seconds = clock.elapsed().as_secs_f64();
        Ok((best.state, report, self.newton_iterations.into_inner()))
    }

    /// The outer iteration's failure after `MAX_OUTER` solves: `what` was not located,
    /// the last points `u` (along the travel) and measures `last` (in `unit`).
    fn outer_limit(&self, what: &str, u: [f64; 2], last: [f64; 2], unit: &str) -> FemError {
        let contour = self.contour();
        let sign = self.data.direction.sign();
        FemError::PaperDFailed {
            outer: self.report.borrow().outer_iterations,
            residual: last[0].abs().max(last[1].abs()),
            reason: format!(
                "{what} not located within {MAX_OUTER} fixed-topology solves (last σ_B = ({}, {}) m, measures ({}, {}) {unit})",
                Sig(contour.wrap(sign * u[0])),
                Sig(contour.wrap(sign * u[1])),
                Sig(last[0]),
                Sig(last[1])
            ),
        }
    }

    /// The roots of the front speeds G₁, G₂ (`fronts`) from `start` (u along the travel):
    /// secant steps of at most one arc element (the cap doubling with each cut in a row),
    /// then the secant safeguarded by the regula falsi once bracketed, to 10⁻⁶ of an arc
    /// element. The points (σ) and
    /// the final brackets (m).
    fn front_roots(&self, start: [f64; 2], arc_element: f64) -> Result<([f64; 2], [f64; 2]), FemError> {
        let contour = self.contour();
        let sign = self.data.direction.sign();
        let sigma_of = |u: f64| contour.wrap(sign * u);
        let tolerance = 1e-6 * arc_element;
        let mut roots = [Root::new(), Root::new()];
        let mut u = start;
        loop {
            if self.report.borrow().outer_iterations >= MAX_OUTER {
                return Err(self.outer_limit("the stick→slip points whose slip run starts at rest (front speeds G = 0) were", u, [roots[0].last, roots[1].last], "m/s"));
            }
            let (_, g) = self.solve_at([sigma_of(u[0]), sigma_of(u[1])])?;
            for k in 0..2 {
                roots[k].record(u[k], g[k]);
            }
            match (roots[0].next(tolerance, arc_element), roots[1].next(tolerance, arc_element)) {
                (None, None) => break,
                (a, b) => u = [a.unwrap_or(u[0]), b.unwrap_or(u[1])],
            }
        }
        // polish: a pulley whose search ended while the other still moved carries a G that
        // drifted with its partner's point (through the tension level), and its bracket
        // mixes G of different partner points, so its slope can be far too steep to see
        // the drift (measured at 1024 elements on the low-tension drive: the driver left
        // 7.9 µm off its root while the driven moved 17 steps). Judged by the slope across
        // its whole search, a point more than the step tolerance off takes that Newton
        // step, and its search restarts from the fresh pair (docs/fem-drive.md §12,
        // "Fifth round"); at most `POLISH` = 8 times (3 left `drive-slack`'s driven point 2e-7 m
        // off at 128 elements after the root search was tightened to 1e-6 of an arc
        // element, measured with the banded LU's round-off; 23 solves with 8).
        for _ in 0..POLISH {
            let off = roots.each_ref().map(|r| r.last.is_finite() && r.span_slope().is_finite() && r.last.abs() > r.span_slope().abs() * tolerance);
            if off == [false; 2] || self.report.borrow().outer_iterations >= MAX_OUTER {
                break;
            }
            let (before, g_before) = (u, roots.each_ref().map(|r| r.last));
            for k in (0..2).filter(|&k| off[k]) {
                u[k] -= roots[k].last / roots[k].span_slope();
            }
            let (_, g) = self.solve_at([sigma_of(u[0]), sigma_of(u[1])])?;
            for k in 0..2 {
                // a moved point's search restarts from the fresh pair; a point that stayed
                // keeps its search with the refreshed G
                if off[k] {
                    roots[k] = Root::new();
                    roots[k].record(before[k], g_before[k]);
                }
                roots[k].record(u[k], g[k]);
            }
        }
        // the search ends on its step; the point is a root only if G there is what that
        // step leaves of it: |G| ≤ |∂G/∂u| × 10 × the step tolerance (∂G/∂u from the
        // bracket, else the last secant); a missing or non-finite G is no root
        for (k, root) in roots.iter().enumerate() {
            let g = root.last;
            let slope = root.slope();
            if !(g == 0.0 || (g.is_finite() && slope.is_finite() && g.abs() <= slope.abs() * 10.0 * tolerance)) {
                let pulley = if k == 0 { "driver" } else { "driven" };
                return Err(FemError::PaperDFailed {
                    outer: self.report.borrow().outer_iterations,
                    residual: g.abs(),
                    reason: format!(
                        "the {pulley}'s stick→slip point σ_B = {} m is no root of its front speed: G = {} m/s (slope {} 1/s, step tolerance {} m){}",
                        Sig(sigma_of(u[k])),
                        Sig(g),
                        Sig(slope),
                        Sig(tolerance),
                        if g.is_finite() { "" } else { " — no slip point downstream of it to measure G" }
                    ),
                });
            }
        }
        Ok(([sigma_of(u[0]), sigma_of(u[1])], [roots[0].bracket(), roots[1].bracket()]))
    }

    /// The centres of the bands of E = 0 from `start` (u along the travel), both edges to
    /// 0.5 % of an arc element. The points (σ) and the bands' widths (m).
    fn band_centres(&self, start: [f64; 2], arc_element: f64) -> Result<([f64; 2], [f64; 2]), FemError> {
        let contour = self.contour();
        let sign = self.data.direction.sign();
        let sigma_of = |u: f64| contour.wrap(sign * u);
        let signed = |e: [f64; 2]| [self.slip_sign[0] * e[0], self.slip_sign[1] * e[1]];
        let mut bands = [Band::new(0.1 * arc_element), Band::new(0.1 * arc_element)];
        // the band edges to 0.5 % of an arc element (measured bands: ≈ 0.1 arc element)
        let tolerance = 5e-3 * arc_element;
        let mut u = start;
        loop {
            if self.report.borrow().outer_iterations >= MAX_OUTER {
                return Err(self.outer_limit("the band of stick→slip points without a concentrated stick traction was", u, [bands[0].last, bands[1].last], "N"));
            }
            let (e, _) = self.solve_at([sigma_of(u[0]), sigma_of(u[1])])?;
            let e = signed(e);
            for k in 0..2 {
                bands[k].record(u[k], e[k]);
            }
            match (bands[0].next(tolerance), bands[1].next(tolerance)) {
                (None, None) => break,
                (a, b) => u = [a.unwrap_or(u[0]), b.unwrap_or(u[1])],
            }
        }
        // the band centres, solved: Coulomb-admissible on both pulleys (E = 0)
        let centre = [bands[0].centre(), bands[1].centre()];
        let at = [sigma_of(centre[0]), sigma_of(centre[1])];
        self.solve_at(at)?;
        Ok((at, [bands[0].width(), bands[1].width()]))
    }
}

/// Whether the mesh `new` with its node-snapped contact zones `zones_new` is the mesh `old`
/// with `zones_old` to within `tolerance` (m): the same node count, the same zones (pulley)
/// and no node and no zone end more than `tolerance` apart (periodic in σ).
fn same_mesh(old: &Mesh, new: &Mesh, zones_old: &[(Pulley, f64, f64)], zones_new: &[(Pulley, f64, f64)], tolerance: f64) -> bool {
    let lc = new.contour().length();
    let near = |a: f64, b: f64| crate::fitting::periodic_diff(a, b, lc).abs() <= tolerance;
    let (a, b) = (old.node_sigmas(), new.node_sigmas());
    a.len() == b.len()
        && a.iter().zip(b).all(|(&x, &y)| near(x, y))
        && zones_old.len() == zones_new.len()
        && zones_old.iter().zip(zones_new).all(|(z, w)| z.0 == w.0 && near(z.1, w.1) && near(z.2, w.2))
}

/// A point whose row the fixed topology prescribes while its normal traction is negative:
/// the radial-balance reaction of the string (`equilibrium_normal`) is below zero where the
/// penalty still says the node presses, and the prescribed row is then dropped for τ = 0
/// (equations.rs) — a state Paper D's scheme must not return. Out of contact the normal
/// is 0, not negative, and τ = 0 is right there.
fn lifted_prescribed(results: &[PointResult]) -> Option<&PointResult> {
    results.iter().find(|r| r.point.fixed.is_some() && r.normal < 0.0)
}

/// The root search of one pulley's front speed G(u) in u (m, along the travel).
#[derive(Debug, Clone)]
struct Root {
    /// (u, G) of every solve, in order.
    history: Vec<(f64, f64)>,
    /// The nearest points with G < 0 and G > 0.
    below: Option<(f64, f64)>,
    above: Option<(f64, f64)>,
    last: f64,
    /// Unbracketed secant steps in a row cut to the step cap; each doubles the cap.
    clipped: i32,
}

impl Root {
    fn new() -> Self {
        Root { history: Vec::new(), below: None, above: None, last: f64::NAN, clipped: 0 }
    }

    fn record(&mut self, u: f64, g: f64) {
        self.last = g;
        // a point that did not move this solve keeps its place in the history with the
        // new G: the other pulley's move changes it, and the next step must see that
        match self.history.last_mut() {
            Some(h) if h.0 == u => h.1 = g,
            _ => self.history.push((u, g)),
        }
        if !g.is_finite() {
            return;
        }
        let closer = |b: Option<(f64, f64)>| b.is_none_or(|b: (f64, f64)| g.abs() < b.1.abs());
        if g < 0.0 && closer(self.below) {
            self.below = Some((u, g));
        } else if g > 0.0 && closer(self.above) {
            self.above = Some((u, g));
        }
    }

    /// ∂G/∂u (1/s): across the bracket once the root is bracketed, else the secant of the
    /// last two points; NaN with fewer than two. A bracket of zero width (a point that
    /// stayed put while its G changed sign with the partner's move: both ends at one u)
    /// has no slope: the secant then (before, an infinite slope failed the root check of a
    /// point at G = −5e-13 m/s, measured at 2048 elements).
    fn slope(&self) -> f64 {
        match (self.below, self.above, &self.history[..]) {
            (Some(b), Some(a), _) if a.0 != b.0 => (a.1 - b.1) / (a.0 - b.0),
            (_, _, [.., (u0, g0), (u1, g1)]) => (g1 - g0) / (u1 - u0),
            _ => f64::NAN,
        }
    }

    /// ∂G/∂u (1/s) across the whole search: between its first and its last point (NaN
    /// with fewer than two) — each G of its own partner point, so a drift of G with the
    /// partner weighs against the whole distance searched, not against one short step.
    fn span_slope(&self) -> f64 {
        match &self.history[..] {
            [(u0, g0), .., (u1, g1)] => (g1 - g0) / (u1 - u0),
            _ => f64::NAN,
        }
    }

    /// Width of the bracket of the root (m), or 0 when it is not bracketed.
    fn bracket(&self) -> f64 {
        match (self.below, self.above) {
            (Some(b), Some(a)) => (a.0 - b.0).abs(),
            _ => 0.0,
        }
    }

    /// The next point, `None` once the last step was below `tolerance` or G = 0. Before
    /// the root is bracketed a secant step is cut to `max_step`, doubled for each cut in a
    /// row (a start many elements off — 31 mm, 22 arc elements, measured at 1024 on the
    /// counter-clockwise low-tension drive — is then crossed in a few solves, not one
    /// solve per element); the cap never takes a step beyond the secant's own. Once
    /// bracketed, the secant is taken where it lies strictly inside the bracket and either
    /// in its inner 80 % or converging — its step at most half the last one, or the last
    /// solve at least halved |G| — else the regula falsi of the bracket's ends, kept a tenth
    /// off them.
    fn next(&mut self, tolerance: f64, max_step: f64) -> Option<f64> {
        let &(u1, g1) = self.history.last().expect("a point is recorded before the next");
        if g1 == 0.0 || !g1.is_finite() {
            return None;
        }
        let previous = match self.history[..] {
            [.., p, _] => Some(p),
            _ => None,
        };
        let secant = previous.filter(|p| p.1 != g1).map(|(u0, g0)| u1 - g1 * (u1 - u0) / (g1 - g0));
        let next = match (self.below, self.above) {
            (Some(b), Some(a)) => {
                let (lo, hi) = (b.0.min(a.0), b.0.max(a.0));
                let falsi = b.0 - b.1 * (a.0 - b.0) / (a.1 - b.1);
                let inner = |x: f64| x > lo + 0.1 * (hi - lo) && x < hi - 0.1 * (hi - lo);
                // near the root the secant lands next to the newest point, often an end of
                // the bracket: the inner 80 % alone refused it, and the regula falsi a tenth
                // of the bracket away threw the search off the root it had all but reached
                // (one or two solves more per search on the Exudyn scene, docs/fem-drive.md
                // §12, "Tenth round"). Never outside or on an end: those G are known.
                let converging = |x: f64| previous.is_some_and(|(u0, g0)| (x - u1).abs() <= 0.5 * (u1 - u0).abs() || g1.abs() <= 0.5 * g0.abs());
                match secant.filter(|&x| x > lo && x < hi && (inner(x) || converging(x))) {
                    Some(x) => x,
                    None => falsi.clamp(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo)),
                }
            }
            _ => match secant {
                Some(x) => {
                    let cap = max_step * 2f64.powi(self.clipped.min(10));
                    self.clipped = if (x - u1).abs() > cap { self.clipped + 1 } else { 0 };
                    u1 + (x - u1).clamp(-cap, cap)
                }
                None => u1 + 0.1 * max_step,
            },
        };
        ((next - u1).abs() > tolerance).then_some(next)
    }
}

/// The search of one pulley's band of admissible prescribed points in u (m, along the
/// travel): ŝE < 0 upstream of it, 0 in it, > 0 downstream (ŝ the slip direction).
#[derive(Debug, Clone, Copy)]
struct Band {
    /// Largest u with ŝE < 0, smallest and largest with ŝE = 0, smallest with ŝE > 0.
    below: Option<f64>,
    inside: Option<(f64, f64)>,
    above: Option<f64>,
    /// ŝE at the smallest u above and the largest below (for the regula falsi before a
    /// point inside is found).
    e_below: f64,
    e_above: f64,
    /// The unbracketed step, doubled after each use, m.
    step: f64,
    last: f64,
}

impl Band {
    fn new(step: f64) -> Self {
        Band { below: None, inside: None, above: None, e_below: 0.0, e_above: 0.0, step, last: f64::NAN }
    }

    fn record(&mut self, u: f64, e: f64) {
        self.last = e;
        if e < 0.0 {
            if self.below.is_none_or(|b| u > b) {
                (self.below, self.e_below) = (Some(u), e);
            }
        } else if e > 0.0 {
            if self.above.is_none_or(|a| u < a) {
                (self.above, self.e_above) = (Some(u), e);
            }
        } else {
            self.inside = Some(self.inside.map_or((u, u), |(lo, hi)| (lo.min(u), hi.max(u))));
        }
    }

    /// The next point to solve at, `None` once both edges are within `tolerance`.
    fn next(&mut self, tolerance: f64) -> Option<f64> {
        let mut stepped = |from: f64, dir: f64| {
            let x = from + dir * self.step;
            self.step *= 2.0;
            x
        };
        match (self.below, self.inside, self.above) {
            // before the band is found: the regula falsi in the bracket (kept a tenth off
            // its ends), else a step towards it
            (Some(b), None, Some(a)) => {
                let x = b - self.e_below * (a - b) / (self.e_above - self.e_below);
                Some(x.clamp(b + 0.1 * (a - b), a - 0.1 * (a - b)))
            }
            (Some(b), None, None) => Some(stepped(b, 1.0)),
            (None, None, Some(a)) => Some(stepped(a, -1.0)),
            (None, None, None) => unreachable!("a point is recorded before the next"),
            // in the band: bisect the wider open edge, stepping out first where unbracketed
            (below, Some((lo, hi)), above) => {
                let gap_lo = below.map_or(f64::INFINITY, |b| lo - b);
                let gap_hi = above.map_or(f64::INFINITY, |a| a - hi);
                if gap_lo <= tolerance && gap_hi <= tolerance {
                    return None;
                }
                Some(if gap_lo >= gap_hi {
                    below.map_or_else(|| stepped(lo, -1.0), |b| 0.5 * (b + lo))
                } else {
                    above.map_or_else(|| stepped(hi, 1.0), |a| 0.5 * (hi + a))
                })
            }
        }
    }

    /// The band's centre: midway between its located edges.
    fn centre(&self) -> f64 {
        let (lo, hi) = self.inside.expect("located");
        let lo_edge = self.below.map_or(lo, |b| 0.5 * (b + lo));
        let hi_edge = self.above.map_or(hi, |a| 0.5 * (hi + a));
        0.5 * (lo_edge + hi_edge)
    }

    /// The band's width between its located edges, m.
    fn width(&self) -> f64 {
        let (lo, hi) = self.inside.expect("located");
        self.above.map_or(hi, |a| 0.5 * (hi + a)) - self.below.map_or(lo, |b| 0.5 * (b + lo))
    }
}

#[cfg(test)]
mod tests {
    use super::{lifted_prescribed, Band, Root};
    use super::super::topology::{Fixed, FrictionPoint, Part, PointResult};
    use drive::contour::{Direction, Pulley};

    /// Only a prescribed point with a negative normal is refused: a free point with a
    /// negative normal (the semismooth rows never see one: the penalty is ≥ 0) and a
    /// prescribed point out of contact (normal 0) are not.
    #[test]
    fn a_prescribed_point_with_a_negative_reaction_is_found() {
        let point = FrictionPoint { sigma: 0.3, pulley: Pulley::Driver, weight: 0.01, node: 7, left: (6, 0.005), right: (7, 0.005), part: Part::Whole, direction: Direction::Clockwise, fixed: None, boundary: false };
        let result = |fixed: Option<Fixed>, normal: f64| PointResult { point: FrictionPoint { fixed, ..point }, traction: 0.0, normal, velocity: 0.0, slip: false };
        let ok = [result(Some(Fixed::Stick), 12.0), result(Some(Fixed::Slip(1.0)), 0.0), result(None, -3.0)];
        assert_eq!(lifted_prescribed(&ok), None);
        let bad = [result(Some(Fixed::Stick), 12.0), result(Some(Fixed::Slip(-1.0)), -0.5)];
        assert_eq!(lifted_prescribed(&bad).map(|r| r.normal), Some(-0.5));
    }

    /// Two coupled front speeds, as the joint fixed-topology solve gives them: each
    /// pulley's G depends weakly on the other's point (through the tension level). The
    /// searches run as `front_roots` runs them (both recorded after every joint solve, a
    /// pulley whose step ended stays put, its G refreshed) and end at the joint root with
    /// |G| within the check `front_roots` applies. With strong coupling the per-pulley
    /// searches can stop off the root: then that check must refuse the point (it is what
    /// turns such an end into `PaperDFailed` rather than a result).
    #[test]
    fn coupled_front_roots_end_at_the_root_or_fail_the_root_check() {
        let (r1, r2) = (0.0213, 0.0371);
        let (tolerance, max_step) = (1e-7, 1e-3);
        let search = |c12: f64, c21: f64| {
            let g = |u: [f64; 2]| [3.0 * (u[0] - r1) + c12 * (u[1] - r2), 1.5 * (u[1] - r2) + c21 * (u[0] - r1)];
            let mut roots = [Root::new(), Root::new()];
            let mut u = [0.0205, 0.0390];
            for _ in 0..60 {
                let gu = g(u);
                for k in 0..2 {
                    roots[k].record(u[k], gu[k]);
                }
                match (roots[0].next(tolerance, max_step), roots[1].next(tolerance, max_step)) {
                    (None, None) => break,
                    (a, b) => u = [a.unwrap_or(u[0]), b.unwrap_or(u[1])],
                }
            }
            let passes = roots.iter().all(|r| r.last == 0.0 || r.last.abs() <= r.slope().abs() * 10.0 * tolerance);
            (u, passes)
        };
        let (u, passes) = search(0.1, -0.05);
        assert!(passes, "weak coupling: the root check fails at {u:?}");
        assert!((u[0] - r1).abs() < 1e-6 && (u[1] - r2).abs() < 1e-6, "weak coupling: ended at {u:?}, roots ({r1}, {r2})");
        let (u, passes) = search(2.0, -0.8);
        let off = (u[0] - r1).abs().max((u[1] - r2).abs());
        assert!(passes == (off < 1e-5), "strong coupling: ended {off:.1e} m off the root, root check {passes}");
        // a point whose G changes sign while it stays put (the partner moved): a bracket of
        // zero width, whose slope is the secant's, finite
        let mut still = Root::new();
        still.record(0.0200, -3.0e-4);
        still.record(0.0210, 2.0e-6);
        still.record(0.0210, -1.0e-9);
        assert_eq!(still.bracket(), 0.0);
        assert!((still.slope() - (-1.0e-9 + 3.0e-4) / 1.0e-3).abs() < 1e-12, "slope {}", still.slope());
        // a missing measure is no root: NaN stops the search without a slope to pass
        let mut lone = Root::new();
        lone.record(0.01, f64::NAN);
        assert_eq!(lone.next(tolerance, max_step), None);
        assert!(!lone.last.is_finite() && lone.slope().is_nan());
    }

    /// A start many step caps from the root (the counter-clockwise low-tension drive at
    /// 1024 elements: 22 arc elements): the cap doubles with each cut step in a row, so a
    /// near-linear G (its slope falling by a third over the way, as measured there) is
    /// crossed in ≤ 20 solves (measured 11 and 18) — one cap per solve takes 26–31 here, and
    /// took 23 at 1024 elements, which exhausted the outer budget —
    /// and no step goes beyond the secant's own (from a start past the root the search
    /// still ends at it).
    #[test]
    fn a_distant_start_is_crossed_in_a_few_solves() {
        let (root, max_step, tolerance) = (-1.2357, 1.37e-3, 1.37e-9);
        let g = |u: f64| 1.6e-3 * (u - root) * (1.0 + 10.0 * (u - root));
        for start in [-1.2050, -1.2700, root + 0.3 * max_step] {
            let mut r = Root::new();
            let mut u = start;
            let mut solves = 0;
            loop {
                solves += 1;
                assert!(solves <= 20, "from {start}: {solves} solves, at {u}");
                r.record(u, g(u));
                match r.next(tolerance, max_step) {
                    Some(next) => u = next,
                    None => break,
                }
            }
            assert!((u - root).abs() < 10.0 * tolerance, "from {start}: ended at {u}, {} off", u - root);
            assert!(r.last.abs() <= r.slope().abs() * 10.0 * tolerance, "from {start}: the root check, G = {}", r.last);
        }
    }

    /// A root near an end of its bracket, as the front searches meet it (the Exudyn scene at
    /// 128 elements: the bracket 1.08 mm wide, the root 4.4 µm past its lower end): the
    /// secant's step lands next to that end, outside the bracket's inner 80 %, and is taken
    /// because it converges — the regula falsi clamped a tenth off the end threw the search
    /// 0.1 mm past the root (|G| 22× the last) and cost solves more. A secant outside the
    /// bracket or on its end is never taken: the safeguard keeps the step strictly inside.
    #[test]
    fn a_bracketed_secant_is_not_thrown_off_its_end() {
        let (root, max_step, tolerance) = (1.003486379, 2.45e-3, 2.45e-9);
        // G of the front's shape: slope ≈ 0.48 1/s, mildly curved
        let g = |u: f64| 0.48 * (u - root) * (1.0 + 10.0 * (u - root));
        let mut r = Root::new();
        let (u_above, u_near) = (root + 1.07e-3, root - 4.4e-6);
        r.record(u_above, g(u_above));
        r.record(u_near, g(u_near));
        let (lo, hi) = (u_near, u_above);
        let next = r.next(tolerance, max_step).expect("not converged yet");
        assert!(next > lo && next < hi, "the step left the bracket [{lo}, {hi}]: {next}");
        assert!(next < lo + 0.1 * (hi - lo), "the converging secant was thrown off the bracket's end: {next}, {:.2e} of the bracket from it", (next - lo) / (hi - lo));
        assert!((next - root).abs() < 0.1 * (u_near - root).abs(), "the secant step does not converge: {:.2e} m off, was {:.2e}", next - root, u_near - root);
        // on to the root: within three more solves, every step inside the bracket
        let mut u = next;
        let mut solves = 0;
        loop {
            solves += 1;
            assert!(solves <= 3, "{solves} solves, at {u} ({:.2e} off)", u - root);
            r.record(u, g(u));
            let (lo, hi) = (r.below.expect("bracketed").0, r.above.expect("bracketed").0);
            match r.next(tolerance, max_step) {
                Some(x) => {
                    assert!(x > lo.min(hi) && x < lo.max(hi), "step {x} outside the bracket ({lo}, {hi})");
                    u = x;
                }
                None => break,
            }
        }
        assert!((u - root).abs() < 10.0 * tolerance, "ended {:.2e} m off the root", u - root);
        assert!(r.last.abs() <= r.slope().abs() * 10.0 * tolerance, "the root check: G = {}", r.last);
        // a secant beyond the bracket (the last two points on one side, G nearly flat
        // between them): the regula falsi of the ends instead, a tenth off them
        let mut far = Root::new();
        far.record(0.0, -1.0);
        far.record(1.0, 1.0);
        far.record(0.5, 0.3);
        far.record(0.6, 0.31);
        let (lo, hi) = (0.0, 0.5);
        let x = far.next(tolerance, max_step).expect("a step");
        assert!(x >= lo + 0.1 * (hi - lo) - 1e-15 && x <= hi - 0.1 * (hi - lo) + 1e-15, "a secant off the bracket was taken: {x}");
        // a secant exactly on an end, though converging (|G| halved), is no step either:
        // that end's G is known; the regula falsi instead
        let mut on_end = Root::new();
        on_end.record(0.0, -1.0);
        on_end.record(1.0, 1.0);
        on_end.record(0.5, 0.5);
        on_end.record(0.25, 0.25);
        // the bracket [0, 0.25]; the secant of (0.5, 0.5), (0.25, 0.25) is u = 0, its lower end
        let x = on_end.next(tolerance, max_step).expect("a step");
        assert!((0.025..=0.225).contains(&x), "the step sits on or near an end of [0, 0.25]: {x}");
        assert!((x - 0.2).abs() < 1e-12, "not the regula falsi of the ends: {x}");
    }

    /// The band search on a measure of the FE's shape (negative and growing up to the
    /// band, zero on it, positive after): from either side and from inside, it ends
    /// with both edges bracketed to the tolerance, and its centre is the band's to half
    /// of it; the work (solves) is counted.
    #[test]
    fn band_search_finds_the_centre_of_a_zero_band() {
        let (lo, hi) = (0.0123, 0.0137);
        let measure = |u: f64| if u < lo { 40.0 * (u - lo) } else if u > hi { 25.0 * (u - hi) } else { 0.0 };
        let tolerance = 5e-5;
        for start in [0.005, 0.0125, 0.02] {
            let mut band = Band::new(1e-3);
            let mut u = start;
            let mut solves = 0;
            loop {
                band.record(u, measure(u));
                solves += 1;
                match band.next(tolerance) {
                    Some(next) => u = next,
                    None => break,
                }
                assert!(solves < 32, "from {start}: not located in 32 solves");
            }
            let centre = band.centre();
            assert!((centre - 0.5 * (lo + hi)).abs() <= 0.5 * tolerance, "from {start}: centre {centre}");
            assert!((band.width() - (hi - lo)).abs() <= tolerance, "from {start}: width {}", band.width());
            assert_eq!(measure(centre), 0.0);
            // work counter: 19 solves from 7 mm below the band (steps of 1, 2, 4 mm, the
            // regula falsi, then both edges bisected from ≈ 1 mm to 50 µm)
            assert!(solves <= 20, "from {start}: {solves} solves");
        }
    }
}
