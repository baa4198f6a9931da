//! Collocation with residual control and adaptive mesh (Gauss–Legendre, orders 4, 6, 8).
//!
//! `run` reads as the algorithm ([`solve`]):
//! 1. sample the guess's dense output on its own mesh (node and stage values),
//! 2. solve the collocation equations (implicit Runge–Kutta form with node and stage
//!    values as unknowns, all segments and the parameters in one sparse system) by the
//!    damped Newton method of [`crate::newton`], each Newton matrix condensed to the
//!    mesh-node values ([`condensed`]) and factorised by a structured LU of that
//!    almost-block-diagonal system (faer's sparse LU for many segments),
//! 3. estimate the residual on every interval ([`CollocationOptions::tolerance`]),
//! 4. insert nodes where it exceeds the tolerance, remove nodes where it is far below
//!    (rules below), carry the solution over with its dense output, and repeat.
//!
//! Mesh rules, with residual order q ([`Scheme::residual_order`], ρ ∝ h^q):
//! - an interval with ρ_i > tol gets one new node (midpoint) if ρ_i ≤ 2^q tol, else two
//!   (thirds);
//! - when every interval passes, two neighbouring intervals (widths h_1, h_2,
//!   H = h_1 + h_2) are merged if the predicted residual of the merged interval,
//!   max(ρ_1 (H/h_1)^q, ρ_2 (H/h_2)^q), is ≤ tol / 2^q — a safety margin of 2^q below the
//!   insertion threshold. If the coarser mesh nevertheless fails, the last accepted
//!   mesh and solution are returned, so insertion and removal cannot alternate.
//!
//! Compare scipy's `solve_bvp` (Kierzenka & Shampine, "A BVP solver based on residual
//! control and the MATLAB PSE", ACM TOMS 27, 2001), which uses the 4th-order
//! Lobatto IIIA scheme with the same residual measure.

mod abd;
pub(crate) mod condensed;
pub(crate) mod discretisation;
pub(crate) mod mesh;
pub mod scheme;

pub use scheme::Scheme;

use crate::error::{check_fraction, BvpError};
use crate::newton::{self, NewtonOptions, NewtonReport, NewtonSystem};
use crate::problem::{JacobianMode, Problem};
use crate::solution::{Solution, Stats};
use numerics::phases::{self, timed, Phase};
use condensed::CondensedLu;
use discretisation::{validate_solution, Discretisation};
use std::time::Instant;

/// Options of [`solve`]. Serialisable so that a run can be reproduced.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct CollocationOptions {
    /// Collocation scheme. Default [`Scheme::Gauss8`], chosen by cost: the residual
    /// tolerance asks for a mesh on which the residual, O(h^s), is small, so the scheme
    /// with the most stages needs the fewest nodes, and the work per node and Newton
    /// iteration is about the same for all three (`docs/bvp-engine.md`, "Speed":
    /// elastica at tol 1e-8 with 213 nodes against gauss6's 985, Bratu 63 against 305).
    pub scheme: Scheme,
    /// Residual tolerance tol. Valid range [1e-13, 0.1]; default 1e-6.
    ///
    /// A solution is accepted when, on every interval [x_i, x_i + h_i] of every segment,
    ///
    /// ```text
    ///     ρ_i = ( (1/h_i) ∫ Σ_a [ (u_a'(x) − f_a(x, u(x))) / (1 + |f_a(x, u(x))|) ]² dx )^{1/2} < tol,
    /// ```
    ///
    /// u the collocation polynomial (the dense output), the integral evaluated by the
    /// 5-point Lobatto rule (exact for degree 7), a the ODE component (the RMS over the
    /// interval of the Euclidean norm of the componentwise relative residual, as in
    /// scipy's `solve_bvp`), **and** the boundary residual max_i |g_i| < tol. The
    /// Newton iteration on each mesh must meet its own test first (see
    /// `newton_tolerance_factor`).
    ///
    /// ρ = O(h^q), q = [`Scheme::residual_order`]; the node values are more accurate,
    /// O(h^{2s}) ([`Scheme::order`]).
    pub tolerance: f64,
    /// Cap on the total number of mesh nodes over all segments; exceeding it returns
    /// [`BvpError::MeshCapReached`]. Default 100 000; valid ≥ 2 per segment and at
    /// least the number of nodes of the guess.
    pub max_nodes: usize,
    /// Newton iterations per mesh. Default 30; valid 1..=10 000.
    pub max_newton_iterations: usize,
    /// The Newton iteration on a mesh converges when the scaled correction
    /// max_i |Δz_i| / (1 + |z_i|) ≤ max(newton_tolerance_factor · tol, 1e-13)
    /// ([`crate::newton`]). Default 1e-2; valid (0, 1].
    pub newton_tolerance_factor: f64,
    /// Smallest Newton damping factor. Default 1e-4; valid (0, 1].
    pub min_damping: f64,
    /// Jacobians by automatic differentiation or finite differences. Default AD.
    pub jacobian: JacobianMode,
    /// Adapt the mesh. With `false` the equations are solved on the guess's mesh only
    /// and the residual is reported in [`Stats::max_residual`] without being enforced
    /// (for convergence studies on fixed meshes). Default `true`.
    pub adapt_mesh: bool,
    /// Remove nodes where the residual is far below the tolerance (module
    /// documentation). Default `true`.
    pub remove_nodes: bool,
    /// Maximum number of mesh adaptation passes (insertions plus removals) before
    /// [`BvpError::RefinementLimit`]. Default 50; valid ≥ 1.
    pub max_refinements: usize,
}

impl Default for CollocationOptions {
    fn default() -> Self {
        Self {
            scheme: Scheme::Gauss8,
            tolerance: 1e-6,
            max_nodes: 100_000,
            max_newton_iterations: 30,
            newton_tolerance_factor: 1e-2,
            min_damping: 1e-4,
            jacobian: JacobianMode::Ad,
            adapt_mesh: true,
            remove_nodes: true,
            max_refinements: 50,
        }
    }
}

impl CollocationOptions {
    /// Check the documented ranges.
    pub fn validate(&self) -> Result<(), BvpError> {
        let bad = |m: String| Err(BvpError::InvalidInput(m));
        if !(1e-13..=0.1).contains(&self.tolerance) {
            return bad(format!("collocation tolerance {} outside [1e-13, 0.1]", self.tolerance));
        }
        if self.max_nodes < 2 {
            return bad(format!("max_nodes {} < 2", self.max_nodes));
        }
        if !(1..=10_000).contains(&self.max_newton_iterations) {
            return bad(format!("max_newton_iterations {} outside 1..=10000", self.max_newton_iterations));
        }
        check_fraction("newton_tolerance_factor", self.newton_tolerance_factor)?;
        check_fraction("min_damping", self.min_damping)?;
        if self.max_refinements == 0 {
            return bad("max_refinements must be ≥ 1".into());
        }
        Ok(())
    }

    /// The Newton options used on each mesh.
    pub fn newton(&self) -> NewtonOptions {
        NewtonOptions {
            tolerance: (self.newton_tolerance_factor * self.tolerance).max(1e-13),
            max_iterations: self.max_newton_iterations,
            min_damping: self.min_damping,
        }
    }
}

/// Solve `problem` by collocation starting from `guess` (at η = `guess.eta`), on the
/// guess's own mesh at first.
///
/// The guess is sampled with its dense output (node and stage values; a
/// [`Solution::from_fn`] guess is piecewise linear). The returned [`Solution`] holds
/// node values, the collocation polynomials as dense output and the work counters; it
/// meets the tolerance defined at [`CollocationOptions::tolerance`] (unless
/// `adapt_mesh` is off).
///
/// Errors: [`BvpError::InvalidInput`] (options, guess shape), Newton failures on a mesh
/// ([`BvpError::NewtonDiverged`], [`BvpError::SingularJacobian`],
/// [`BvpError::NonFinite`]), [`BvpError::MeshCapReached`],
/// [`BvpError::RefinementLimit`].
pub fn solve<P: Problem>(problem: &P, guess: &Solution, opts: &CollocationOptions) -> Result<Solution, BvpError> {
    validate_solution(problem, guess, "guess")?;
    let meshes: Vec<Vec<f64>> = guess.segments.iter().map(|s| s.mesh.clone()).collect();
    solve_on_meshes(problem, guess, meshes, opts)
}

/// As [`solve`], but starting on the given initial meshes (one per segment, each from 0
/// to 1, strictly increasing, ≥ 2 nodes): the guess is interpolated onto them with its
/// dense output.
pub fn solve_on_meshes<P: Problem>(
    problem: &P,
    guess: &Solution,
    meshes: Vec<Vec<f64>>,
    opts: &CollocationOptions,
) -> Result<Solution, BvpError> {
    let start = Instant::now();
    opts.validate()?;
    validate_solution(problem, guess, "guess")?;
    check_node_cap(&meshes, opts)?;
    let disc = Discretisation::new(problem, opts.scheme, opts.jacobian, meshes)?;
    let z = disc.sample(guess)?;
    let mut stats = Stats::default();
    let mut corrector = FixedEta::new(opts);
    let done = adapt(disc, z, guess.eta, &mut corrector, opts, &mut stats)?;
    Ok(done.into_solution(stats, start, 0))
}

pub(crate) fn check_node_cap(meshes: &[Vec<f64>], opts: &CollocationOptions) -> Result<(), BvpError> {
    let nodes: usize = meshes.iter().map(Vec::len).sum();
    if nodes > opts.max_nodes {
        return Err(BvpError::InvalidInput(format!(
            "the initial mesh has {nodes} nodes, more than max_nodes = {}",
            opts.max_nodes
        )));
    }
    Ok(())
}

/// Converges the discrete equations on one mesh (fixed η, or with η unknown under a
/// continuation constraint), and carries its own data over when the mesh changes.
pub(crate) trait Corrector<P: Problem> {
    /// Newton on `disc` from (`z`, `eta`), overwriting them with the converged point.
    fn correct(
        &mut self,
        disc: &Discretisation<'_, P>,
        z: &mut Vec<f64>,
        eta: &mut f64,
    ) -> Result<NewtonReport, BvpError>;
    /// The mesh changes from `old` (converged point `old_z`, `old_eta`) to `new`; by
    /// default the corrector carries no data of its own over.
    fn transfer(
        &mut self,
        _old: &Discretisation<'_, P>,
        _old_z: &[f64],
        _old_eta: f64,
        _new: &Discretisation<'_, P>,
    ) -> Result<(), BvpError> {
        Ok(())
    }
}

/// The plain solve: Newton on F(z; η) = 0 with η fixed, each Newton matrix condensed
/// to the mesh nodes ([`condensed`]); the factorisation object (with its symbolic LU)
/// lives as long as the corrector, across meshes and continuation steps.
pub(crate) struct FixedEta {
    lu: CondensedLu,
    newton: NewtonOptions,
}

impl FixedEta {
    pub fn new(opts: &CollocationOptions) -> Self {
        Self { lu: CondensedLu::new(), newton: opts.newton() }
    }
}

struct FixedEtaSystem<'s, 'a, P: Problem> {
    disc: &'s Discretisation<'a, P>,
    eta: f64,
    lu: &'s mut CondensedLu,
}

impl<P: Problem> NewtonSystem for FixedEtaSystem<'_, '_, P> {
    fn size(&self) -> usize {
        self.disc.n
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), BvpError> {
        self.disc.residual(z, self.eta, r);
        Ok(())
    }
    fn factorize(&mut self, z: &[f64]) -> Result<(), BvpError> {
        self.lu.factorize(self.disc, z, self.eta)
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), BvpError> {
        self.lu.solve(self.disc, b)
    }
    /// ‖J⁻¹δ‖ for a sample δ of the residual's rounding errors ([`rounding_sample`]):
    /// an upper estimate of the floor — at the 1e-11 solve of `string-hanging-steel`,
    /// where the corrections stall at 1.3–2.9e-13 (`docs/bvp-engine.md`, "Round-off
    /// floor"), it gives 4e-12 to 2e-11, so stalled corrections are recognised and a
    /// correction far above round-off is not.
    fn correction_floor(&mut self, z: &[f64]) -> Result<Option<f64>, BvpError> {
        let mut delta = vec![0.0; self.disc.n];
        self.disc.residual_terms(z, self.eta, &mut delta);
        rounding_sample(&mut delta);
        self.lu.solve(self.disc, &mut delta)?;
        let floor = newton::scaled_norm(&delta, z);
        Ok(Some(floor))
    }
    /// No residual pass at the converged iterate: every caller of
    /// [`Corrector::correct`] estimates the residual there next
    /// ([`Discretisation::residual_norms`]), which evaluates f at every stage again and
    /// fails on a non-finite value (one residual pass per mesh, ~3 % of a gauss8
    /// elastica solve).
    fn converged_residual(&self) -> bool {
        false
    }
}

/// Turn the term magnitudes T_i of the residual's rows
/// ([`Discretisation::residual_terms`]) into a sample of its rounding error,
/// δ_i = ±u T_i (u = 2⁻⁵³, the signs a fixed pseudo-random sequence, so that the floor
/// and the iterates are reproducible).
fn rounding_sample(t: &mut [f64]) {
    let u = f64::EPSILON / 2.0;
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    for v in t.iter_mut() {
        // 64-bit LCG (Knuth's MMIX constants); the top bit gives the sign.
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let sign = if state >> 63 == 0 { 1.0 } else { -1.0 };
        *v *= sign * u;
    }
}

impl<P: Problem> Corrector<P> for FixedEta {
    fn correct(
        &mut self,
        disc: &Discretisation<'_, P>,
        z: &mut Vec<f64>,
        eta: &mut f64,
    ) -> Result<NewtonReport, BvpError> {
        let mut system = FixedEtaSystem { disc, eta: *eta, lu: &mut self.lu };
        newton::solve(&mut system, z, &self.newton)
    }
}

/// A converged point on an adapted mesh.
pub(crate) struct Adapted<'a, P: Problem> {
    pub disc: Discretisation<'a, P>,
    pub z: Vec<f64>,
    pub eta: f64,
    /// max(max_i ρ_i, boundary residual).
    pub max_residual: f64,
    /// The dense output at `z` ([`Discretisation::residual_norms_and_solution`], default
    /// stats).
    pub output: Solution,
}

impl<P: Problem> Adapted<'_, P> {
    /// The solution with its statistics completed (unknowns, nodes, residual, time
    /// since `start`, right-hand-side evaluations counted since the shared counter read
    /// `rhs_baseline`).
    pub fn solution(&self, stats: Stats, start: Instant, rhs_baseline: usize) -> Solution {
        self.complete(self.output.clone(), stats, start, rhs_baseline)
    }

    /// [`Self::solution`], consuming the point.
    pub fn into_solution(self, stats: Stats, start: Instant, rhs_baseline: usize) -> Solution {
        let Adapted { disc, max_residual, output, .. } = self;
        complete(&disc, max_residual, output, stats, start, rhs_baseline)
    }

    fn complete(&self, sol: Solution, stats: Stats, start: Instant, rhs_baseline: usize) -> Solution {
        complete(&self.disc, self.max_residual, sol, stats, start, rhs_baseline)
    }
}

/// `sol` (the dense output of a converged point on `disc`) with the statistics of
/// [`Adapted::solution`].
fn complete<P: Problem>(disc: &Discretisation<'_, P>, max_residual: f64, mut sol: Solution, mut stats: Stats, start: Instant, rhs_baseline: usize) -> Solution {
    stats.unknowns = disc.n;
    stats.mesh_nodes = disc.n_nodes();
    stats.max_residual = max_residual;
    stats.rhs_evaluations = disc.rhs_evals.get() - rhs_baseline;
    stats.wall_seconds = start.elapsed().as_secs_f64();
    sol.stats = stats;
    sol
}

/// Carry a converged point over to `meshes` with its dense output `output`
/// ([`Discretisation::residual_norms_and_solution`]).
pub(crate) fn remesh<'a, P: Problem>(
    disc: &Discretisation<'a, P>,
    output: &Solution,
    meshes: Vec<Vec<f64>>,
) -> Result<(Discretisation<'a, P>, Vec<f64>), BvpError> {
    let new = disc.with_meshes(meshes)?;
    let z_new = new.sample(output)?;
    Ok((new, z_new))
}

/// Refinement passes in a row that may leave the best residual above half its value
/// before them (a floor, [`BvpError::ResidualFloor`]). A refinement that resolves the
/// solution reduces the residual by 2^q per halved interval (q ≥ 4 for every scheme), so
/// eight passes without a factor 2 are no pre-asymptotic phase: on `cosserat-pulley`
/// with b₂ = 1e6 N at tol 1e-8 (gauss6) the residual wandered between 1.0e-8 and 2.5e-8
/// over 43 passes while the mesh grew from 1100 to 1215 nodes in the stiff segment,
/// until the pass limit; with the damping halvings it solves (3079 nodes).
pub const FLOOR_PASSES: usize = 8;

/// Halvings of the chattering segments before a residual floor is an error.
pub const DAMPING_PASSES: usize = 2;

/// One mesh adaptation pass of [`adapt`]: the point carried over to `meshes`
/// ([`remesh`]) and the corrector's data with it, timed and counted as mesh adaptation.
fn adapted_mesh<'a, P: Problem, C: Corrector<P>>(
    disc: &Discretisation<'a, P>,
    z: &[f64],
    eta: f64,
    output: &Solution,
    meshes: Vec<Vec<f64>>,
    corrector: &mut C,
) -> Result<(Discretisation<'a, P>, Vec<f64>), BvpError> {
    timed(Phase::MeshAdaptation, || {
        let (new_disc, new_z) = remesh(disc, output, meshes)?;
        corrector.transfer(disc, z, eta, &new_disc)?;
        phases::count(phases::Step::MeshRefinement, 1);
        Ok((new_disc, new_z))
    })
}

/// The adaptive loop: correct, estimate, insert or remove nodes, repeat.
///
/// Removal is tried only on a mesh that meets the tolerance; if the coarser mesh fails
/// (Newton failure or residual above tolerance) the last accepted mesh and solution
/// are returned, so insertion and removal cannot alternate. `stats` receives Newton
/// iterations, Jacobian evaluations and refinement passes.
pub(crate) fn adapt<'a, P: Problem, C: Corrector<P>>(
    mut disc: Discretisation<'a, P>,
    mut z: Vec<f64>,
    mut eta: f64,
    corrector: &mut C,
    opts: &CollocationOptions,
    stats: &mut Stats,
) -> Result<Adapted<'a, P>, BvpError> {
    let q = opts.scheme.residual_order();
    let tol = opts.tolerance;
    let mut accepted: Option<Adapted<'a, P>> = None;
    let mut passes = 0;
    // Best residual of the refinement passes, and the best before the last FLOOR_PASSES.
    let mut history: Vec<f64> = Vec::new();
    let mut damping = 0;
    loop {
        let report = match corrector.correct(&disc, &mut z, &mut eta) {
            Ok(r) => r,
            Err(e) => {
                if let BvpError::NewtonDiverged { iterations, .. } = e {
                    stats.newton_iterations += iterations;
                    stats.jacobian_evaluations += iterations;
                }
                return accepted.ok_or(e);
            }
        };
        stats.newton_iterations += report.iterations;
        stats.jacobian_evaluations += report.iterations;
        let (rho, bc, output) = match timed(Phase::Residuals, || disc.residual_norms_and_solution(&z, eta)) {
            Ok(v) => v,
            Err(e) => return accepted.ok_or(e),
        };
        let max_rho = rho.iter().flatten().fold(0.0_f64, |m, &r| m.max(r));
        let max_residual = max_rho.max(bc);
        if !opts.adapt_mesh {
            return Ok(Adapted { disc, z, eta, max_residual, output });
        }
        if max_rho < tol {
            if bc >= tol {
                return accepted.ok_or(BvpError::NewtonDiverged {
                    iterations: report.iterations,
                    residual: bc,
                    tolerance: tol,
                });
            }
            if opts.remove_nodes && passes < opts.max_refinements {
                let coarse: Vec<Option<Vec<f64>>> = timed(Phase::MeshAdaptation, || {
                    disc.meshes.iter().zip(&rho).map(|(m, r)| mesh::coarsen(m, r, tol, q)).collect()
                });
                if coarse.iter().any(Option::is_some) {
                    let meshes =
                        coarse.into_iter().zip(&disc.meshes).map(|(c, m)| c.unwrap_or_else(|| m.clone())).collect();
                    let (new_disc, new_z) = adapted_mesh(&disc, &z, eta, &output, meshes, corrector)?;
                    accepted = Some(Adapted { disc, z, eta, max_residual, output });
                    disc = new_disc;
                    z = new_z;
                    passes += 1;
                    stats.refinements += 1;
                    continue;
                }
            }
            return Ok(Adapted { disc, z, eta, max_residual, output });
        }
        if let Some(a) = accepted {
            return Ok(a);
        }
        let meshes: Vec<Vec<f64>> =
            timed(Phase::MeshAdaptation, || disc.meshes.iter().zip(&rho).map(|(m, r)| mesh::refine(m, r, tol, q)).collect());
        let nodes: usize = meshes.iter().map(Vec::len).sum();
        if nodes > opts.max_nodes {
            return Err(BvpError::MeshCapReached { max_nodes: opts.max_nodes, residual: max_rho, tolerance: tol });
        }
        if passes >= opts.max_refinements {
            return Err(BvpError::RefinementLimit { passes, residual: max_rho, tolerance: tol });
        }
        history.push(max_rho);
        let mut meshes = meshes;
        if let Some(e) = residual_floor(&history, tol, disc.meshes.iter().map(Vec::len).sum()) {
            // The residual chatters near tol: on a stiff segment whose fast mode is far
            // from resolved (h·|μ| ≫ 1) the Gauss collocation carries its error from
            // interval to interval undamped (|R(−∞)| = 1: A- but not L-stable), so a
            // node inserted anywhere moves the residual of intervals elsewhere. Halving
            // every interval of the offending segments damps it (|R(hμ)| drops fast as
            // h|μ| falls); after DAMPING_PASSES such halvings the floor is an error.
            if damping >= DAMPING_PASSES {
                return Err(e);
            }
            damping += 1;
            history.clear();
            meshes = disc.meshes.iter().zip(&rho).map(|(m, r)| if r.iter().any(|&x| x > tol) { mesh::halve(m) } else { m.clone() }).collect();
            if meshes.iter().map(Vec::len).sum::<usize>() > opts.max_nodes {
                return Err(BvpError::MeshCapReached { max_nodes: opts.max_nodes, residual: max_rho, tolerance: tol });
            }
        }
        let (new_disc, new_z) = adapted_mesh(&disc, &z, eta, &output, meshes, corrector)?;
        disc = new_disc;
        z = new_z;
        passes += 1;
        stats.refinements += 1;
    }
}

/// [`BvpError::ResidualFloor`] when the last [`FLOOR_PASSES`] refinement passes of
/// `history` (max scaled residual before each refinement) never fell below half the
/// best residual before them.
fn residual_floor(history: &[f64], tolerance: f64, nodes: usize) -> Option<BvpError> {
    let split = history.len().checked_sub(FLOOR_PASSES + 1)? + 1;
    let best_before = history[..split].iter().copied().fold(f64::INFINITY, f64::min);
    let best = history[split..].iter().copied().fold(f64::INFINITY, f64::min);
    (best >= 0.5 * best_before).then(|| BvpError::ResidualFloor {
        nodes,
        residual: history[history.len() - 1],
        best: best.min(best_before),
        tolerance,
        // The next power of ten above twice the worst residual of the window.
        attainable: 10f64.powf((2.0 * history[split..].iter().copied().fold(0.0, f64::max)).log10().ceil()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A residual that keeps shrinking (even slowly, by 2 in 8 passes) is no floor; one
    /// that wanders for FLOOR_PASSES passes without halving its best is, and the error
    /// suggests the next power of ten above twice the window's worst residual.
    #[test]
    fn residual_floor_needs_a_whole_window_without_halving() {
        let converging: Vec<f64> = (0..30).map(|i| 1e-2 * 0.5f64.powf(i as f64 / 7.0)).collect();
        for n in 1..=converging.len() {
            assert!(residual_floor(&converging[..n], 1e-12, 100).is_none(), "n = {n}");
        }
        // The trace of `cosserat-pulley` with b₂ = 1e6 N at tol 1e-8 (gauss6), shortened.
        let mut stalled = vec![1e-3, 1e-5, 2.1e-8, 2.09e-8, 2.5e-8, 1.9e-8, 1.6e-8, 1.47e-8, 1.8e-8, 1.8e-8];
        assert!(residual_floor(&stalled, 1e-8, 100).is_none(), "the window still holds the drop from 1e-5");
        stalled.push(1.5e-8);
        let Some(BvpError::ResidualFloor { best, attainable, residual, nodes, .. }) = residual_floor(&stalled, 1e-8, 1234) else {
            panic!("8 passes without halving 2.1e-8 are a floor")
        };
        assert_eq!((best, residual, nodes), (1.47e-8, 1.5e-8, 1234));
        assert!((attainable - 1e-7).abs() < 1e-22, "twice the worst 2.5e-8, rounded up: {attainable}");
        *stalled.last_mut().unwrap() = 1.0e-8;
        assert!(residual_floor(&stalled, 1e-9, 100).is_none(), "1.0e-8 halves the best 2.1e-8 before the window");
    }
    use crate::newton::SparseLu;
    use crate::problem::Scalar;

    /// Two segments with a parameter and η everywhere, nonlinear in all arguments:
    /// segment 0: y' = p0 (y1, −η sin y0 + y0 y1 x), segment 1: y' = p0 (cos y0 + η, y0²),
    /// with interface continuity, y_0(0) = (0.1, ·), and an integral-like condition on p.
    struct Test2;

    impl Problem for Test2 {
        fn n_segments(&self) -> usize {
            2
        }
        fn dim(&self, _k: usize) -> usize {
            2
        }
        fn n_params(&self) -> usize {
            1
        }
        fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
            if k == 0 {
                f[0] = p[0] * y[1];
                f[1] = p[0] * (-(eta * y[0].sin()) + y[0] * y[1] * x);
            } else {
                f[0] = p[0] * (y[0].cos() + eta);
                f[1] = p[0] * y[0] * y[0];
            }
        }
        fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
            r[0] = ya[0][0] - 0.1;
            r[1] = ya[1][0] - yb[0][0];
            r[2] = ya[1][1] - yb[0][1];
            r[3] = yb[1][0] * eta - 0.3;
            r[4] = p[0] * p[0] - 1.0 - ya[0][1] * yb[1][1];
        }
    }

    /// Deterministic pseudo-random numbers in [−1, 1) (64-bit LCG).
    fn lcg(state: &mut u64) -> f64 {
        *state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((*state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }

    /// The assembled Jacobian ∂F/∂z and ∂F/∂η against central differences of the
    /// residual at a random state, for every scheme and both Jacobian modes.
    /// Tolerance: central differences with step 1e-6 have truncation error
    /// O(h² |F'''|) ~ 1e-12 and round-off ~ ε/h ~ 1e-10 on entries of size O(1);
    /// 1e-7 relative to the largest entry leaves a margin of 10³ while a wrong entry
    /// (a missing h, a sign, a wrong column) is O(h_mesh) ≥ 1e-2.
    #[test]
    fn jacobian_matches_central_differences() {
        let mut state = 7u64;
        for scheme in Scheme::ALL {
            for mode in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
                let meshes = vec![vec![0.0, 0.3, 1.0], vec![0.0, 0.5, 0.6, 1.0]];
                let disc = Discretisation::new(&Test2, scheme, mode, meshes).unwrap();
                let n = disc.n;
                let z: Vec<f64> = (0..n).map(|_| lcg(&mut state)).collect();
                let eta = 0.7 + 0.2 * lcg(&mut state);
                let (mut rows, mut cols, mut vals, mut jeta) = (vec![], vec![], vec![], vec![]);
                disc.jacobian(&z, eta, &mut rows, &mut cols, &mut vals, &mut jeta);
                let mut dense = vec![0.0; n * (n + 1)];
                for ((&r, &c), &v) in rows.iter().zip(&cols).zip(&vals) {
                    dense[r * (n + 1) + c] += v;
                }
                for r in 0..n {
                    dense[r * (n + 1) + n] = jeta[r];
                }
                let step = 1e-6;
                let mut fd = vec![0.0; n * (n + 1)];
                let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
                for c in 0..=n {
                    let (mut zp, mut zm) = (z.clone(), z.clone());
                    let (mut ep, mut em) = (eta, eta);
                    if c < n {
                        zp[c] += step;
                        zm[c] -= step;
                    } else {
                        ep += step;
                        em -= step;
                    }
                    disc.residual(&zp, ep, &mut rp);
                    disc.residual(&zm, em, &mut rm);
                    for r in 0..n {
                        fd[r * (n + 1) + c] = (rp[r] - rm[r]) / (2.0 * step);
                    }
                }
                let scale = fd.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let err = dense.iter().zip(&fd).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(err < 1e-7 * scale, "{scheme} {mode:?}: max |J − J_fd| = {err:e} (scale {scale})");
            }
        }
    }

    /// The condensed factorisation solves the Newton system like the sparse LU of the
    /// full Jacobian, for every scheme, at a random state with a random right-hand side
    /// (two segments, a parameter, interface conditions), by the structured LU of the
    /// condensed system and by its sparse LU. All are backward stable solves of a
    /// system of order ~50 with condition ≲ 10⁴ here, so they agree to ~10⁻¹², 10⁻⁹
    /// relative to the largest entry; a wrong block, sign or pivot gives O(1). Meshes
    /// of one interval (no elimination step) and of several are both in it.
    #[test]
    fn condensed_solve_matches_full_lu() {
        let mut state = 11u64;
        for scheme in Scheme::ALL {
            for meshes in [vec![vec![0.0, 0.2, 0.5, 1.0], vec![0.0, 0.5, 0.6, 1.0]], vec![vec![0.0, 1.0], vec![0.0, 0.3, 1.0]]] {
                for (max_order, expected) in [(None, (0, 0, true)), (Some(0), (1, 0, false))] {
                    let what = format!("{scheme} {max_order:?}, structured or sparse as asked, not the fallback");
                    check_condensed_solve(&Test2, scheme, meshes.clone(), &mut state, max_order, expected, &what);
                }
            }
        }
    }

    /// At a random state, factorise and solve a random right-hand side with a
    /// [`CondensedLu`] (largest structured order `max_order`) and assert that the
    /// factorisations it used are `expected` and that its solution is the full
    /// uncondensed LU's to 1e-9 relative to the largest unknown (the two eliminations
    /// differ in round-off only, ~10⁻¹² here; a wrong block, sign or pivot gives O(1)).
    fn check_condensed_solve<P: Problem>(
        problem: &P,
        scheme: Scheme,
        meshes: Vec<Vec<f64>>,
        state: &mut u64,
        max_order: Option<usize>,
        expected: (usize, usize, bool),
        what: &str,
    ) {
        let disc = Discretisation::new(problem, scheme, JacobianMode::Ad, meshes).unwrap();
        let n = disc.n;
        let z: Vec<f64> = (0..n).map(|_| 0.5 * lcg(state)).collect();
        let eta = 0.8;
        let b: Vec<f64> = (0..n).map(|_| lcg(state)).collect();
        let (mut rows, mut cols, mut vals, mut jeta) = (vec![], vec![], vec![], vec![]);
        disc.jacobian(&z, eta, &mut rows, &mut cols, &mut vals, &mut jeta);
        let mut full = SparseLu::new();
        full.factorize(n, &rows, &cols, &vals).unwrap();
        let mut x_full = b.clone();
        full.solve_in_place(&mut x_full).unwrap();
        let scale = x_full.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut cond = CondensedLu::new();
        cond.max_block_order = max_order;
        cond.factorize(&disc, &z, eta).unwrap();
        let mut x = b;
        cond.solve(&disc, &mut x).unwrap();
        assert_eq!(cond.factorisations(), expected, "{what}");
        let err = x.iter().zip(&x_full).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-9 * scale, "{what}: max |x − x_full| = {err:e} (scale {scale})");
    }

    /// n components, n_p parameters, every component and parameter read, η too:
    /// f_a = sin(y_a) y_{a+1} + p_{a mod n_p} x y_a − η y_a² (cyclic a + 1) — a Jacobian
    /// with n + n_p + 1 columns, for the lane counts of [`crate::jacobian::RhsJacobian`].
    struct Wide(usize, usize);

    impl Problem for Wide {
        fn n_segments(&self) -> usize {
            1
        }
        fn dim(&self, _k: usize) -> usize {
            self.0
        }
        fn n_params(&self) -> usize {
            self.1
        }
        fn rhs<D: Scalar>(&self, _k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
            let n = self.0;
            for a in 0..n {
                let load = if self.1 > 0 { p[a % self.1] * x * y[a] } else { y[a] * x };
                f[a] = y[a].sin() * y[(a + 1) % n] + load - eta * y[a] * y[a];
            }
        }
        fn bc<D: Scalar>(&self, _ya: &[&[D]], _yb: &[&[D]], _p: &[D], _eta: D, _r: &mut [D]) {}
    }

    /// The reusable stage Jacobian of the condensation (columns side by side in vector
    /// dual numbers) gives the values of the allocating
    /// [`crate::jacobian::rhs_jacobian`] (one `Dual64` pass per column) to the bit, up to
    /// the sign of a zero — f from the first pass instead of a plain call — and without
    /// the η column leaves ∂f/∂η zero (Test2's segment 0 depends on η, so a skipped or
    /// stale column shows). Test2 (3 or 4 columns: 4 lanes) and [`Wide`] with 1 + 0 (1
    /// or 2 columns: 2 lanes), 4 + 2 (the elastica's 6 or 7: one pass of 8) and 7 + 3
    /// (10 or 11: two passes of 8, the second with f not rewritten) cover every lane
    /// count and the split into passes; a column in the wrong lane, entry or pass gives
    /// a different value.
    #[test]
    fn stage_jacobian_buffers_equal_the_allocating_version_to_the_bit() {
        use crate::jacobian::{rhs_jacobian, RhsJacobian};
        // ±0 as one value: a `Dual64` pass may add an exact zero term that the vector
        // duals leave out, which can only change the sign of a zero.
        let bits = |v: &[f64]| v.iter().map(|&x| if x == 0.0 { 0 } else { x.to_bits() }).collect::<Vec<_>>();
        fn check<P: Problem>(problem: &P, k: usize, state: &mut u64, jac: &mut RhsJacobian, bits: &dyn Fn(&[f64]) -> Vec<u64>) {
            let n = problem.dim(k);
            let y: Vec<f64> = (0..n).map(|_| lcg(state)).collect();
            let p: Vec<f64> = (0..problem.n_params()).map(|_| 1.0 + 0.3 * lcg(state)).collect();
            let (x, eta) = (0.37, 0.8);
            let (f, dfdy, dfdp, dfdeta) = rhs_jacobian(problem, JacobianMode::Ad, k, x, &y, &p, eta);
            assert!(dfdeta.iter().any(|&v| v != 0.0), "the test problems depend on η");
            assert!(dfdy.iter().chain(&dfdp).all(|v| v.is_finite()) && dfdy.iter().filter(|&&v| v != 0.0).count() >= n);
            for eta_column in [true, false] {
                jac.evaluate(problem, JacobianMode::Ad, k, x, &y, &p, eta, eta_column);
                let what = format!("n = {n}, n_p = {}, segment {k}, η column {eta_column}", p.len());
                assert_eq!(bits(&jac.f), bits(&f), "f, {what}");
                assert_eq!(bits(&jac.dfdy), bits(&dfdy), "∂f/∂y, {what}");
                assert_eq!(bits(&jac.dfdp), bits(&dfdp), "∂f/∂p, {what}");
                let expected = if eta_column { bits(&dfdeta) } else { bits(&vec![0.0; n]) };
                assert_eq!(bits(&jac.dfdeta), expected, "∂f/∂η, {what}");
            }
        }
        let mut state = 5u64;
        let mut jac = RhsJacobian::default();
        for k in 0..2 {
            check(&Test2, k, &mut state, &mut jac, &bits);
        }
        for (n, np) in [(1, 0), (4, 2), (7, 3), (4, 2), (1, 0)] {
            check(&Wide(n, np), 0, &mut state, &mut jac, &bits);
        }
    }

    /// Test2 with its boundary residuals multiplied by a factor: the same solution,
    /// boundary rows of another scale.
    struct ScaledBc(f64);

    impl Problem for ScaledBc {
        fn n_segments(&self) -> usize {
            Test2.n_segments()
        }
        fn dim(&self, k: usize) -> usize {
            Test2.dim(k)
        }
        fn n_params(&self) -> usize {
            Test2.n_params()
        }
        fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
            Test2.rhs(k, x, y, p, eta, f);
        }
        fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
            Test2.bc(ya, yb, p, eta, r);
            for v in r.iter_mut() {
                *v *= self.0;
            }
        }
    }

    /// The structured LU's fallback: boundary rows scaled by 1e-20 leave the last pivots
    /// of its final dense system (~1e-20) below 10⁻¹⁴ times its largest entry (O(1),
    /// the interval rows), so it reports a vanishing pivot and the condensed system goes
    /// to the sparse LU (one numeric factorisation, not the structured one) — whose
    /// solution must still be the full uncondensed LU's: the scaling changes no
    /// unknown, only the size of some equations. Same tolerance as
    /// `condensed_solve_matches_full_lu`; unscaled (factor 1), the structured LU is used.
    #[test]
    fn structured_lu_falls_back_to_the_sparse_lu_on_a_vanishing_pivot() {
        let mut state = 13u64;
        for (factor, expected) in [(1.0, (0, 0, true)), (1e-20, (1, 0, false))] {
            let meshes = vec![vec![0.0, 0.2, 0.5, 1.0], vec![0.0, 0.5, 0.6, 1.0]];
            let what = format!("boundary rows × {factor}: structured LU, or the sparse LU after a vanishing pivot");
            check_condensed_solve(&ScaledBc(factor), Scheme::Gauss8, meshes, &mut state, None, expected, &what);
        }
    }

    #[test]
    fn options_are_validated() {
        let guess = Solution::from_fn(2, 3, vec![1.0], 0.5, |_, _| vec![0.0, 0.0]);
        for opts in [
            CollocationOptions { tolerance: 0.0, ..Default::default() },
            CollocationOptions { tolerance: f64::NAN, ..Default::default() },
            CollocationOptions { max_nodes: 1, ..Default::default() },
            CollocationOptions { max_newton_iterations: 0, ..Default::default() },
            CollocationOptions { max_refinements: 0, ..Default::default() },
        ] {
            assert!(matches!(solve(&Test2, &guess, &opts), Err(BvpError::InvalidInput(_))));
        }
        let wrong = Solution::from_fn(1, 3, vec![1.0], 0.5, |_, _| vec![0.0, 0.0]);
        assert!(matches!(solve(&Test2, &wrong, &CollocationOptions::default()), Err(BvpError::InvalidInput(_))));
        let nan = Solution::from_fn(2, 3, vec![1.0], 0.5, |_, _| vec![f64::NAN, 0.0]);
        assert!(matches!(solve(&Test2, &nan, &CollocationOptions::default()), Err(BvpError::NonFinite { .. })));
    }
}
