//! The augmented-Lagrangian normal contact of the direct steady solve of the open
//! one-pulley layout (Table 1, column 1, §6.1; docs/fem-cosserat.md §12.5): an outer
//! (Uzawa) loop around the steady solve on the fitted mesh, the multipliers λ_γ a field
//! over σ ([`ContactMultipliers`]) updated at the contact rule's points,
//! λ ← ⟨λ − Pγ⟩₊, and held by the element (so the refits of the fitting read them on
//! their own meshes).

use super::*;
use crate::formulation::ContactMultipliers;

/// The outer loop's work (in the run's `options.drive.report.contact`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct AugmentedReport {
    /// Multiplier updates (each followed by a Newton solve and the fit, except the last).
    pub iterations: usize,
    /// The largest multiplier change of the last update, N/m.
    pub multiplier_change: f64,
    /// The tolerance on it, `al_tolerance` × F_ref/R, N/m.
    pub tolerance: f64,
    /// The largest |γ| at a loaded point of the contact rule at the end, m.
    pub max_gap: f64,
    /// Converged; false: the result is the penalty solve's (a stated warning).
    pub converged: bool,
}

/// The Uzawa update at the contact rule's points of the state `x` on `asm`: the new
/// multipliers ⟨λ(σ_j) − Pγ_j⟩₊ with λ the element's field (0 for the plain penalty:
/// the first update is the penalty pressure), and the largest |γ_j| at a point that
/// carries pressure. `period`: the contour length L_c of a closed loop (the field is
/// periodic in σ, [`ContactMultipliers::periodic`]); `None`: the open layout.
pub(crate) fn multiplier_update<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, x: &[f64], params: &TermParams, penalty: f64, period: Option<f64>) -> (ContactMultipliers, f64) {
    let kernel = asm.kernel();
    let (layout, rule) = (kernel.layout(), kernel.rules().contact);
    let mut samples = Vec::new();
    let mut max_gap: f64 = 0.0;
    for e in 0..asm.mesh().len() {
        let el = asm.context(e, params);
        let q = asm.dofs().gather(e, x, 0.0);
        for &(xi, _) in rule.points() {
            let Some((gap, _)) = point_gap(layout, &el, &q, xi, false) else { continue };
            let sigma = el.sigma(xi);
            let lambda = kernel.contact_traction(penalty, sigma, Some(gap));
            if lambda > 0.0 {
                max_gap = max_gap.max(gap.abs());
            }
            samples.push((sigma, lambda));
        }
    }
    let field = match period {
        Some(l) => ContactMultipliers::periodic(samples, l),
        None => ContactMultipliers::from_samples(samples),
    };
    (field, max_gap)
}

/// Why the outer loop stopped without a result.
#[derive(Debug, Clone, PartialEq)]
pub enum AugmentedFailure {
    /// The element has penalty contact only.
    Unsupported,
    /// A solve with the updated multipliers failed.
    Solve(String),
    /// `max_al_iterations` updates without the multiplier change below the tolerance.
    NotConverged { change: f64, tolerance: f64, iterations: usize },
}

impl std::fmt::Display for AugmentedFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AugmentedFailure::Unsupported => write!(f, "the element has penalty contact only"),
            AugmentedFailure::Solve(e) => write!(f, "a solve with the updated multipliers failed ({e})"),
            AugmentedFailure::NotConverged { change, tolerance, iterations } => {
                write!(f, "the multiplier change {} N/m is above the tolerance {} N/m after {iterations} updates", numerics::Sig(*change), numerics::Sig(*tolerance))
            }
        }
    }
}

/// The converged state's Newton solve on its own mesh with the kernel `kernel` (new
/// multipliers), from its unknowns.
pub(super) fn resolve<const N: usize, const P: usize, const E: usize>(state: &State<N, dyn LayoutElement<N>>, kernel: Arc<dyn LayoutElement<N>>, d: &SteadyFitData<'_, dyn LayoutElement<N>>, report: &mut SteadyReport) -> Result<State<N, dyn LayoutElement<N>>, NewtonFailure> {
    let asm = Assembler::with_kernel(state.asm.mesh().clone(), kernel);
    let points: Vec<FrictionPoint> = state.results.iter().map(|p| p.point).collect();
    let prob: SteadyProblem<N, P, E, dyn LayoutElement<N>> = SteadyProblem { asm: &asm, params: d.params, length: d.length, points: &points, sp: (d.sp_at)(1.0), strain_rule: d.strain_rule };
    let mut w = variable_weights(&asm, d.h, d.r, d.omega1.abs(), d.f_ref, points.len());
    if let Some(slot) = d.slot_weight {
        w[asm.len() + 1] = slot;
    }
    let scales = row_scales(&asm, d.f_ref, points.len());
    let mut x = state.x.clone();
    let n = newton(&prob, &mut x, &w, &scales, d.tolerance, d.max_iterations)?;
    report.newton_iterations += n.iterations;
    let results = prob.evaluate(&x, false).map(|e| e.results).unwrap_or_default();
    Ok(State { asm, x, results, rho: state.rho })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formulation::augmented_traction;

    /// The update is Table 1's: λ ← ⟨λ − Pγ⟩₊ (penetration γ < 0 raises it, a gap
    /// lowers it to zero), and the field interpolates linearly, 0 outside its samples.
    #[test]
    fn uzawa_update_and_field() {
        let p = 1e11;
        assert_eq!(augmented_traction(0.0, p, Some(-1e-9)), 100.0);
        assert_eq!(augmented_traction(100.0, p, Some(0.0)), 100.0);
        assert!((augmented_traction(100.0, p, Some(2e-10)) - 80.0).abs() < 1e-9);
        assert_eq!(augmented_traction(100.0, p, Some(2e-9)), 0.0);
        assert_eq!(augmented_traction(100.0, p, None), 0.0);
        let m = ContactMultipliers::from_samples(vec![(0.3, 30.0), (0.1, 10.0), (0.2, 10.0), (0.2, 30.0)]);
        assert_eq!(m.samples(), &[(0.1, 10.0), (0.2, 20.0), (0.3, 30.0)]);
        assert!((m.at(0.15) - 15.0).abs() < 1e-12);
        assert_eq!(m.at(0.3), 30.0);
        assert_eq!(m.at(0.05), 0.0);
        assert_eq!(m.at(0.35), 0.0);
        let z = ContactMultipliers::default();
        assert_eq!(m.max_change(&z), 30.0);
        assert_eq!(z.at(1.0), 0.0);
        // a closed loop's field (L_c = 1) is periodic: σ modulo L_c, and it runs on from
        // the last sample (0.95) to the first + L_c (1.05) across σ = 0
        let c = ContactMultipliers::periodic(vec![(0.95, 10.0), (1.05, 30.0), (0.5, 0.0)], 1.0);
        assert_eq!(c.samples(), &[(1.05f64.rem_euclid(1.0), 30.0), (0.5, 0.0), (0.95, 10.0)]);
        for (sigma, want) in [(0.0, 20.0), (1.0, 20.0), (-0.02, 16.0), (0.98, 16.0), (2.05, 30.0), (0.75, 10.0 * 0.25 / 0.45)] {
            assert!((c.at(sigma) - want).abs() < 1e-9, "λ({sigma}) = {} ≠ {want}", c.at(sigma));
        }
        assert_eq!(ContactMultipliers::from_samples(vec![(0.95, 10.0), (0.05, 30.0)]).at(1.0), 0.0);
    }
}
