//! Nested start of the direct steady solve (docs/fem-drive.md §12, "Nested
//! iteration"): the load continuation in η runs on a coarse mesh, and its state at
//! η = 1 is carried up a ladder of meshes, each twice as fine as the one before, to the
//! solve's own mesh, with one semismooth Newton solve at η = 1 per rung.
//!
//! Why: on one mesh the semismooth Newton moves each slip front by about one element
//! per iteration (the damped steps flip one or two points per pulley; traced on the
//! Exudyn drive: 0 → 96 slip points in 38 iterations at 256 elements), so the load
//! continuation's iterations grow like N. From the converged state of a mesh half as
//! fine, every front lies within an element or two of its fine-mesh position, and the
//! fine solve needs a bounded number of iterations.

use super::*;

/// Fewest elements of the coarsest mesh of the ladder: the Exudyn drive's continuation
/// converges there in 31 iterations, and coarser meshes resolve the slip arcs of the
/// slack drives too poorly (drive-slack at 32: a driver slip arc of 36° against 9.3°,
/// docs/fem-drive.md §12) to give a start close to the fine solution.
pub(super) const MIN_COARSE: usize = 64;

/// The element counts of the coarse meshes for a solve on `elements`: `elements`/2,
/// /4, … while at least [`MIN_COARSE`], coarsest first; empty below 2 [`MIN_COARSE`].
pub(super) fn coarse_levels(elements: usize) -> Vec<usize> {
    coarse_levels_from(elements, MIN_COARSE)
}

/// Fewest elements of the coarsest mesh of the open one-pulley layout's ladder
/// (docs/fem-cosserat.md §12.5): 128, on which the continuation of `cosserat-pulley`
/// converges in 31 iterations with the shear layer graded (its mesh-convergence study
/// starts there); the fine solves of the rungs above take 3–8 iterations (measured).
pub(super) const MIN_COARSE_OPEN: usize = 128;

/// The element counts `elements`/2, /4, … while at least `min`, coarsest first; empty
/// below 2 `min`.
pub(super) fn coarse_levels_from(elements: usize, min: usize) -> Vec<usize> {
    let mut levels = Vec::new();
    let mut n = elements;
    while n / 2 >= min {
        n /= 2;
        levels.push(n);
    }
    levels.reverse();
    levels
}

/// A converged state at η = 1: the unknowns X and their point results.
type Converged = (Vec<f64>, Vec<PointResult>);

/// What the nested start needs besides the meshes: the refits' data (the same
/// equations, weights and Newton settings) and the start.
pub(super) struct NestedData<'d, 'a, K: ?Sized> {
    pub base: &'d SteadyFitData<'a, K>,
    /// The arc weight of the coarse meshes' element distribution.
    pub arc_weight: f64,
    /// ρ of the transport inertia, if on.
    pub inertia: Option<f64>,
    /// c and ω₂ of the start state (c = Rω₁/λ₀, ω₂ = ω₁).
    pub start_rates: [f64; 2],
}

/// The unknowns X of `asm` (friction `points`) from the converged state `x` (`results`)
/// of the assembler `from`: z by the transfer of the static homotopy (the old
/// solution's fields at the new nodes), c and ω₂ copied, each traction interpolated
/// linearly in σ between the old points of its pulley.
fn prolong<const N: usize, K: LayoutElement<N> + ?Sized>(from: &Assembler<N, K>, x: &[f64], results: &[PointResult], asm: &Assembler<N, K>, points: &[FrictionPoint], d: &NestedData<'_, '_, K>) -> Vec<f64> {
    let nz = from.len();
    let sol = FemSolution::new(from.mesh().clone(), from.dofs(), &x[..nz], d.base.params, d.base.length, d.base.kernel.clone());
    let contour = *asm.mesh().contour();
    let mut out = crate::static_homotopy::transfer(&sol, asm);
    out.extend([x[nz], x[nz + 1]]);
    out.extend(points.iter().map(|p| interpolate_traction(results, &contour, p)));
    out
}

/// The load continuation on the coarsest mesh of `levels` (from the static start
/// `start`), then one Newton solve at η = 1 on each finer mesh of `levels` and last on
/// `fine` (its friction points `fine_points`), each from the state of the mesh before
/// it. `Ok(None)`: a step of the ladder failed (the caller continues on `fine` itself);
/// the work done is counted in `report` either way.
///
/// # Errors
/// [`FemError::SpeedAtOrAboveCritical`] on a converged state of the ladder.
pub(super) fn nested_start<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(
    start: &FemSolution<N, K>,
    fine: &Assembler<N, K>,
    fine_points: &[FrictionPoint],
    levels: &[usize],
    d: &NestedData<'_, '_, K>,
    report: &mut SteadyReport,
) -> Result<Option<Converged>, FemError> {
    let contour = *fine.mesh().contour();
    let Some((&coarsest, finer)) = levels.split_first() else { return Ok(None) };
    // every mesh of the ladder fitted to the static start's contact boundaries, as the
    // fine one is: a coarse state on a uniform mesh carried to the fitted fine mesh
    // starts 10³× further from equilibrium (merit 4e-2 against 3e-5 per rung, measured
    // at 512 elements) and needs 31 iterations instead of 3–4 (a coarse mesh on which
    // `Mesh::graded` ignores a boundary, one within 2 % of an element of a region
    // transition, is uniform there: its rung takes 6–17)
    let breaks = start.contact_boundaries();
    let coarse = |n: usize| Mesh::graded(contour, n, d.arc_weight, &breaks, d.base.grading).ok().map(|(m, _)| m);
    let Some(mesh) = coarse(coarsest) else { return Ok(None) };
    let asm = Assembler::with_kernel(mesh, d.base.kernel.clone());
    let points = friction_points(&asm, &[], d.base.direction);
    let mut x = crate::static_homotopy::transfer(start, &asm);
    x.extend(d.start_rates);
    x.extend(std::iter::repeat_n(0.0, points.len()));
    let w = variable_weights(&asm, d.base.h, d.base.r, d.base.omega1.abs(), d.base.f_ref, points.len());
    let scales = row_scales(&asm, d.base.f_ref, points.len());
    let steady = SteadyProblem::<N, P, E, K> { asm: &asm, params: d.base.params, length: d.base.length, points: &points, sp: (d.base.sp_at)(0.0), strain_rule: d.base.strain_rule };
    let mut path = LoadPath::new(steady, d.base.sp_at, (&w, &scales), (d.base.tolerance, d.base.max_iterations), d.base.kernel, d.inertia, x, report);
    match path.run() {
        Ok(()) => {}
        Err(e @ FemError::SpeedAtOrAboveCritical { .. }) => return Err(e),
        Err(_) => return Ok(None),
    }
    let (mut x, mut results) = (path.x, path.results);
    let mut prev = asm;
    report.nested_meshes.push(coarsest);
    // the finer coarse meshes, then the fine one
    for &n in finer {
        let Some(mesh) = coarse(n) else { return Ok(None) };
        let asm = Assembler::with_kernel(mesh, d.base.kernel.clone());
        let points = friction_points(&asm, &[], d.base.direction);
        let Some(next) = rung::<N, P, E, K>(&prev, &x, &results, &asm, &points, d, report)? else { return Ok(None) };
        (x, results, prev) = (next.0, next.1, asm);
        report.nested_meshes.push(n);
    }
    rung::<N, P, E, K>(&prev, &x, &results, fine, fine_points, d, report)
}

/// One rung of the ladder: the state of `from` carried to `asm` and solved there at
/// η = 1; `None` if the Newton solve fails.
pub(super) fn rung<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized>(
    from: &Assembler<N, K>,
    x: &[f64],
    results: &[PointResult],
    asm: &Assembler<N, K>,
    points: &[FrictionPoint],
    d: &NestedData<'_, '_, K>,
    report: &mut SteadyReport,
) -> Result<Option<Converged>, FemError> {
    let mut xn = prolong(from, x, results, asm, points, d);
    let sp = (d.base.sp_at)(1.0);
    let prob = SteadyProblem::<N, P, E, K> { asm, params: d.base.params, length: d.base.length, points, sp, strain_rule: d.base.strain_rule };
    let w = variable_weights(asm, d.base.h, d.base.r, d.base.omega1.abs(), d.base.f_ref, points.len());
    let scales = row_scales(asm, d.base.f_ref, points.len());
    match newton(&prob, &mut xn, &w, &scales, d.base.tolerance, d.base.max_iterations) {
        Ok(n) => {
            report.newton_iterations += n.iterations;
            if let Some(rho) = d.inertia {
                let sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &xn[..asm.len()], d.base.params, d.base.length, d.base.kernel.clone());
                let c = xn[asm.len()];
                check_critical(&sol, rho * c * c)?;
            }
            let results = prob.evaluate(&xn, false).map(|e| e.results).unwrap_or_default();
            Ok(Some((xn, results)))
        }
        Err(_) => {
            report.newton_iterations += d.base.max_iterations;
            Ok(None)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ladder halves down to at least 64 elements, coarsest first, and is empty
    /// where no mesh of ≥ 64 elements is half as fine.
    #[test]
    fn coarse_levels_halve_down_to_the_minimum() {
        assert!(coarse_levels(64).is_empty());
        assert!(coarse_levels(127).is_empty());
        assert_eq!(coarse_levels(128), vec![64]);
        assert_eq!(coarse_levels(512), vec![64, 128, 256]);
        assert_eq!(coarse_levels(300), vec![75, 150]);
        assert!(coarse_levels_from(255, MIN_COARSE_OPEN).is_empty());
        assert_eq!(coarse_levels_from(512, MIN_COARSE_OPEN), vec![128, 256]);
    }
}
