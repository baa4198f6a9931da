//! Mesh fitting of the direct steady solve on the shared driver [`crate::fitting`]: the
//! breakpoints (contact boundaries and the stick→slip transitions located from the point
//! results), σ unwrapping, and the refit — traction transfer to the new mesh and a
//! semismooth Newton solve with a penalty ladder on failure.

use super::*;
use crate::fitting::Fitted;

/// Unwrapped σ of a pulley's zone (the driver's straddles σ = 0).
pub(super) fn unwrapped(contour: &Contour, pulley: Pulley, sigma: f64) -> f64 {
    super::super::unwrap(contour, pulley, sigma)
}

/// The stick→slip transition of a pulley (docs/fem-drive.md §12): the zero of the
/// relative velocity v of the trailing slip run — each point's v is the stretch of its
/// element, placed at the element's midpoint — extrapolated by the quadratic through the
/// 2nd–4th distinct samples (the line through the first two on a short run), clamped
/// between the stick point before the last one and the second slip sample; `None` if the
/// pulley has no stick point or no slip point. All in the coordinate u = ±σ (unwrapped)
/// that runs with the belt, so that the stick run comes first in either direction.
pub fn transition(results: &[PointResult], contour: &Contour, pulley: Pulley) -> Option<f64> {
    let mut pts: Vec<&PointResult> = results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
    let sign = pts.first()?.point.direction.sign();
    // the halves of a split node in the order of travel too
    let key = |p: &PointResult| (sign * unwrapped(contour, pulley, p.point.sigma), sign * p.point.part.offset());
    pts.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap_or(std::cmp::Ordering::Equal));
    let last_stick = pts.iter().rposition(|p| !p.slip)?;
    if last_stick + 1 >= pts.len() {
        return None;
    }
    let s = |p: &PointResult| sign * unwrapped(contour, pulley, p.point.sigma);
    let mid = |p: &PointResult| sign * unwrapped(contour, pulley, p.point.velocity_sigma());
    let a = pts[last_stick];
    // the distinct velocity samples of the slip run (the slip half of a split node and
    // the next node share their element), up to four
    let mut samples: Vec<&PointResult> = Vec::with_capacity(4);
    for p in &pts[last_stick + 1..] {
        if samples.last().is_none_or(|q| (mid(p) - mid(q)).abs() > 1e-12) {
            samples.push(p);
        }
        if samples.len() == 4 {
            break;
        }
    }
    let b = samples[0];
    let mut sigma = 0.5 * (s(a) + s(b));
    // the zero may lie up to one element upstream of the last stick point or up to the
    // second slip sample downstream
    let lo = if last_stick > 0 { s(pts[last_stick - 1]) } else { s(a) };
    let hi = samples.get(1).map_or(s(b), |c| s(c));
    let linear = |p: &PointResult, q: &PointResult| {
        let (mp, mq) = (mid(p), mid(q));
        (mq > mp && (q.velocity - p.velocity).abs() > 0.0).then(|| mp - p.velocity * (mq - mp) / (q.velocity - p.velocity))
    };
    // the quadratic through the 2nd–4th samples (the first slip element carries the
    // stick zone's alternating layer, §12), else the line through the first two
    let root = match samples[..] {
        [_, p, q, r] => {
            let (x0, x1, x2) = (mid(p), mid(q), mid(r));
            let (y0, y1, y2) = (p.velocity, q.velocity, r.velocity);
            // v = y0 + d1 (x − x0) + d2 (x − x0)(x − x1)
            let d1 = (y1 - y0) / (x1 - x0);
            let d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
            // in t = x − x0: d2 t² + (d1 − d2 (x1 − x0)) t + y0 = 0, the root nearest the line's
            let (qa, qb, qc) = (d2, d1 - d2 * (x1 - x0), y0);
            let guess = linear(p, q);
            let disc = qb * qb - 4.0 * qa * qc;
            if qa.abs() > 0.0 && disc >= 0.0 {
                let sq = disc.sqrt();
                let t1 = (-qb + sq) / (2.0 * qa);
                let t2 = (-qb - sq) / (2.0 * qa);
                let g = guess.map_or(x0, |g| g - x0);
                Some(x0 + if (t1 - g).abs() < (t2 - g).abs() { t1 } else { t2 })
            } else {
                guess
            }
        }
        [p, q, ..] => linear(p, q),
        _ => None,
    };
    if let Some(root) = root.filter(|r| r.is_finite()) {
        sigma = root.clamp(lo, hi);
    }
    Some(contour.wrap(sign * sigma))
}

/// τ at a new friction point from the old solution: linear in σ between the two old
/// points of the same pulley that enclose it (the nearer one at a zone end).
pub(super) fn interpolate_traction(old: &[PointResult], contour: &Contour, p: &FrictionPoint) -> f64 {
    let s = unwrapped(contour, p.pulley, p.sigma);
    let mut pts: Vec<(f64, f64)> = old.iter().filter(|o| o.point.pulley == p.pulley).map(|o| (unwrapped(contour, p.pulley, o.point.sigma), o.traction)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    if pts.is_empty() {
        return 0.0;
    }
    let k = pts.partition_point(|q| q.0 <= s);
    if k == 0 {
        return pts[0].1;
    }
    if k == pts.len() {
        return pts[k - 1].1;
    }
    let (a, b) = (pts[k - 1], pts[k]);
    if b.0 > a.0 {
        a.1 + (b.1 - a.1) * (s - a.0) / (b.0 - a.0)
    } else {
        a.1
    }
}

/// What a steady refit needs besides the state.
pub(super) struct SteadyFitData<'a, K: ?Sized> {
    pub params: TermParams,
    pub length: f64,
    pub kernel: &'a Arc<K>,
    /// The η-scaled parameters (the refits solve at η = 1).
    pub sp_at: &'a dyn Fn(f64) -> SteadyParams,
    pub strain_rule: Rule,
    /// H, R, ω₁ and F_ref of the variable weights and row scales.
    pub h: f64,
    pub r: f64,
    pub omega1: f64,
    pub f_ref: f64,
    /// The variable weight of the ω-slot when it holds another unknown: 𝓗_in (N) in the
    /// open layout's mode `pulley_speed` (docs/fem-cosserat.md §12.7); `None`: ω's, ω₁.
    pub slot_weight: Option<f64>,
    /// The belt's running direction (the upwind element of each friction point).
    pub direction: Direction,
    /// Newton tolerance and iteration limit.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// The grading of the refitted meshes towards the breakpoints (a Cosserat rod's
    /// shear layer, docs/fem-cosserat.md §11; `None`: uniform pieces).
    pub grading: Option<crate::mesh::Grading>,
}

// by hand: references and numbers only, so no `K: Copy` bound as `derive` would add
impl<K: ?Sized> Clone for SteadyFitData<'_, K> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K: ?Sized> Copy for SteadyFitData<'_, K> {}

/// The steady state as a [`Fitted`]: the breakpoints are the contact boundaries and the
/// stick→slip transitions (docs/fem-drive.md §12); a refit splits the node at each
/// fitted transition into its stick and slip halves.
pub(super) struct SteadyFit<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> {
    state: State<N, K>,
    /// The accepted state's solution (boundaries, transfer).
    sol: FemSolution<N, K>,
    /// The pulleys of the located contact zones, in the order of their boundaries
    /// (σ_start, σ_end each) at the head of the located breakpoints; the rest are
    /// transitions.
    zones: Vec<Pulley>,
    data: SteadyFitData<'a, K>,
    report: &'a mut SteadyReport,
}

impl<'a, const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> SteadyFit<'a, N, P, E, K> {
    pub(super) fn new(state: State<N, K>, data: SteadyFitData<'a, K>, report: &'a mut SteadyReport) -> Self {
        let sol = solution(&state, &data);
        SteadyFit { state, sol, zones: Vec::new(), data, report }
    }

    pub(super) fn into_state(self) -> State<N, K> {
        self.state
    }
}

/// The solution of a steady state (with its transport inertia ρc²).
pub(super) fn solution<const N: usize, K: LayoutElement<N> + ?Sized>(state: &State<N, K>, d: &SteadyFitData<K>) -> FemSolution<N, K> {
    FemSolution::new(state.asm.mesh().clone(), state.asm.dofs(), &state.x[..state.asm.len()], d.params, d.length, d.kernel.clone()).with_transport_inertia(rho_c2(state))
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> Fitted for SteadyFit<'_, N, P, E, K> {
    type Failure = NewtonFailure;
    type Snapshot = (Mesh, Vec<f64>, Vec<PointResult>);

    fn mesh(&self) -> &Mesh {
        self.state.asm.mesh()
    }

    fn locate(&mut self) -> Vec<f64> {
        let contour = *self.state.asm.mesh().contour();
        let edges = self.sol.contact_edges();
        self.zones = edges.iter().map(|z| z.0).collect();
        let mut breaks: Vec<f64> = edges.iter().flat_map(|z| [z.1, z.2]).collect();
        breaks.extend([Pulley::Driver, Pulley::Driven].iter().filter_map(|&p| transition(&self.state.results, &contour, p)));
        breaks
    }

    fn refit(&mut self, mesh: Mesh, breaks: &[f64]) -> Result<(), NewtonFailure> {
        let d = &self.data;
        let contour = *mesh.contour();
        let asm = Assembler::with_kernel(mesh, d.kernel.clone());
        // the node at each fitted transition is split into its stick and slip halves
        let nb = 2 * self.zones.len();
        let mut points = friction_points(&asm, &breaks[nb..], d.direction);
        // the Cosserat loop (tributary normal load): the node at each fitted contact
        // boundary carries its contact side only (docs/fem-cosserat.md §11.1); the
        // string's semismooth points keep the whole boundary nodes (fem-drive.md §12)
        if d.kernel.friction_normal() == FrictionNormal::Tributary && (d.sp_at)(1.0).ends == Ends::Loop {
            let zones: Vec<(Pulley, f64, f64)> = self.zones.iter().enumerate().map(|(k, &p)| (p, breaks[2 * k], breaks[2 * k + 1])).collect();
            contact_side_halves(&mut points, &zones, contour.length());
        }
        let mut x = crate::static_homotopy::transfer(&self.sol, &asm);
        let nz_old = self.state.asm.len();
        x.extend([self.state.x[nz_old], self.state.x[nz_old + 1]]);
        x.extend(points.iter().map(|p| interpolate_traction(&self.state.results, &contour, p)));
        let prob: SteadyProblem<N, P, E, K> = SteadyProblem { asm: &asm, params: d.params, length: d.length, points: &points, sp: (d.sp_at)(1.0), strain_rule: d.strain_rule };
        let mut w = variable_weights(&asm, d.h, d.r, d.omega1.abs(), d.f_ref, points.len());
        if let Some(slot) = d.slot_weight {
            w[asm.len() + 1] = slot;
        }
        let scales = row_scales(&asm, d.f_ref, points.len());
        // the transferred state is far from equilibrium in the stiff normal penalty
        // where a kink moved between elements: on failure, a penalty ladder
        // P/10⁵ → P from the transferred state
        let n = newton_or_ladder(&prob, &mut x, &w, &scales, d.tolerance, d.max_iterations, &[1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0])?;
        self.report.newton_iterations += n.iterations;
        let results = prob.evaluate(&x, false).map(|e| e.results).unwrap_or_default();
        self.state = State { asm, x, results, rho: self.state.rho };
        self.sol = solution(&self.state, &self.data);
        Ok(())
    }

    fn snapshot(&self) -> Self::Snapshot {
        (self.state.asm.mesh().clone(), self.state.x.clone(), self.state.results.clone())
    }

    fn restore(&mut self, (mesh, x, results): Self::Snapshot) {
        self.state = State { asm: Assembler::with_kernel(mesh, self.data.kernel.clone()), x, results, rho: self.state.rho };
        self.sol = solution(&self.state, &self.data);
    }

    fn grading(&self) -> Option<crate::mesh::Grading> {
        self.data.grading
    }
}
