//! Newton's method with a line search on the assembled energy (docs/fem-string.md §8).
//!
//! At iterate z: K Δ = −G (sparse LU). Trial z + αΔ, α = 1, ½, ¼, … ≥ α_min: accepted if
//! admissible (finite energy, ∂σS > 0) and either Armijo's energy decrease
//! Π(z + αΔ) ≤ Π(z) + 10⁻⁴ α GᵀΔ holds (when GᵀΔ < 0) or the scaled residual does not
//! grow. **Converged** when a full step is taken with ‖Δ‖ ≤ tolerance, where
//! ‖Δ‖ = max_i |Δ_i|/d_i (d_i = H for values, 1 for slopes); the scaled residual
//! ‖G‖ = max_i |G_i|/(F_ref c_i) (c_i = 1 for values, the node spacing for slopes) is
//! reported.

use crate::assembly::Assembler;
use crate::dofs::DofKind;
use crate::kinematics::TermParams;
use crate::linear::SparseLu;

/// Armijo constant of the energy test.
const ARMIJO: f64 = 1e-4;
/// Smallest line-search factor α_min = 2⁻²⁰.
const MIN_ALPHA: f64 = 9.5367431640625e-7;

/// Norm weights of the unknowns (docs/fem-string.md §8).
#[derive(Debug, Clone)]
pub struct Scales {
    /// d_i: H for values, 1 for slopes.
    update: Vec<f64>,
    /// F_ref · c_i.
    residual: Vec<f64>,
    /// Energy scale F_ref · H, J.
    pub energy: f64,
}

impl Scales {
    /// Weights for the unknowns of `asm` with length scale `length` (H, m) and force
    /// scale `force` (F_ref, N).
    pub fn new(asm: &Assembler, length: f64, force: f64) -> Scales {
        let kinds = asm.dofs().kinds();
        let spacing = asm.dofs().spacing();
        Scales {
            update: kinds.iter().map(|k| if *k == DofKind::Value { length } else { 1.0 }).collect(),
            residual: kinds
                .iter()
                .zip(spacing)
                .map(|(k, h)| if *k == DofKind::Value { force } else { force * h })
                .collect(),
            energy: force * length,
        }
    }

    /// ‖Δ‖ = max |Δ_i|/d_i.
    pub fn update_norm(&self, d: &[f64]) -> f64 {
        d.iter().zip(&self.update).fold(0.0, |m, (v, w)| m.max(v.abs() / w))
    }

    /// ‖G‖ = max |G_i|/(F_ref c_i).
    pub fn residual_norm(&self, g: &[f64]) -> f64 {
        g.iter().zip(&self.residual).fold(0.0, |m, (v, w)| m.max(v.abs() / w))
    }
}

/// Work and final norms of one Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct NewtonReport {
    /// Iterations (= tangent assemblies and factorisations).
    pub iterations: usize,
    /// Last scaled update ‖Δ‖.
    pub update_norm: f64,
    /// Scaled residual ‖G‖ at the converged state.
    pub residual_norm: f64,
    /// Π at the converged state, J.
    pub energy: f64,
    /// Smallest line-search factor used.
    pub min_alpha: f64,
    /// Regularised (Levenberg–Marquardt) factorisations beyond the plain Newton ones.
    pub regularised: usize,
}

/// Why a Newton solve failed.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonFailure {
    /// Iteration limit or line search exhausted.
    Diverged {
        /// Iterations done.
        iterations: usize,
        /// Last ‖Δ‖.
        update: f64,
        /// Last ‖G‖.
        residual: f64,
        /// The line search found no acceptable step.
        line_search_failed: bool,
    },
    /// The tangent could not be factorised.
    Singular {
        /// Iteration.
        iteration: usize,
        /// faer's message.
        detail: String,
    },
    /// The starting point is not admissible (∂σS ≤ 0 or non-finite).
    Inadmissible,
}

/// Newton settings.
#[derive(Debug, Clone, Copy)]
pub struct NewtonSettings {
    /// Tolerance on ‖Δ‖.
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

/// Solve G(z) = 0 from `z` (overwritten with the solution; on failure with the last
/// accepted iterate). `lu` must hold the pattern of `asm`.
///
/// Each iteration tries the Newton step K Δ = −G first; if it is not a descent
/// direction of Π or its line search fails (K indefinite, e.g. a compressed string,
/// or a contact set that changes within the step), it is regularised,
/// (K + μ D) Δ = −G with D = diag |K| and μ = 10⁻⁶, 10⁻⁵, … ≤ 10², which turns Δ
/// towards steepest descent in the metric D (Levenberg–Marquardt). A step is accepted
/// by Armijo's rule on Π with a round-off allowance of 10⁻¹³ F_ref H; as a last resort
/// the plain Newton step is accepted where the scaled residual does not grow.
pub fn solve(
    asm: &Assembler,
    lu: &mut SparseLu,
    z: &mut [f64],
    params: &TermParams,
    length: f64,
    scales: &Scales,
    settings: &NewtonSettings,
) -> Result<NewtonReport, NewtonFailure> {
    let n = z.len();
    let mut report = NewtonReport { min_alpha: 1.0, ..Default::default() };
    let mut step = vec![0.0; n];
    let mut newton_step = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut last_update = f64::INFINITY;
    let mut last_residual = f64::INFINITY;
    let diag = asm.diagonal_positions();
    let allowance = 1e-13 * scales.energy;
    loop {
        let Some(a) = asm.assemble(z, params, length) else {
            return if report.iterations == 0 {
                Err(NewtonFailure::Inadmissible)
            } else {
                Err(NewtonFailure::Diverged {
                    iterations: report.iterations,
                    update: last_update,
                    residual: last_residual,
                    line_search_failed: false,
                })
            };
        };
        let rnorm = scales.residual_norm(&a.gradient);
        last_residual = rnorm;
        if report.iterations >= settings.max_iterations {
            return Err(NewtonFailure::Diverged {
                iterations: report.iterations,
                update: last_update,
                residual: rnorm,
                line_search_failed: false,
            });
        }
        report.iterations += 1;
        // D = diag |K| (duplicates summed)
        let mut d = vec![0.0; n];
        for (k, &v) in a.values.iter().enumerate() {
            let (r, c) = (asm.pattern().0[k], asm.pattern().1[k]);
            if r == c {
                d[r] += v;
            }
        }
        let mut mu = 0.0;
        let mut accepted = false;
        while mu <= 1e2 {
            let mut values = a.values.clone();
            if mu > 0.0 {
                for (i, &pos) in diag.iter().enumerate() {
                    values[pos] += mu * d[i].abs().max(1e-300);
                }
            }
            lu.factorize(&values)
                .map_err(|detail| NewtonFailure::Singular { iteration: report.iterations, detail })?;
            for (s, g) in step.iter_mut().zip(&a.gradient) {
                *s = -g;
            }
            lu.solve_in_place(&mut step)
                .map_err(|detail| NewtonFailure::Singular { iteration: report.iterations, detail })?;
            let unorm = scales.update_norm(&step);
            let slope: f64 = step.iter().zip(&a.gradient).map(|(s, g)| s * g).sum();
            if mu == 0.0 {
                last_update = unorm;
                newton_step.copy_from_slice(&step);
                // converged: take the full step (it must be admissible)
                if unorm <= settings.tolerance {
                    for i in 0..n {
                        trial[i] = z[i] + step[i];
                    }
                    if let Some((energy, g)) = asm.gradient(&trial, params, length) {
                        z.copy_from_slice(&trial);
                        report.update_norm = unorm;
                        report.residual_norm = scales.residual_norm(&g);
                        report.energy = energy;
                        return Ok(report);
                    }
                }
            }
            if slope < 0.0 {
                // Armijo line search on Π
                let mut alpha = 1.0;
                while alpha >= MIN_ALPHA {
                    for i in 0..n {
                        trial[i] = z[i] + alpha * step[i];
                    }
                    if let Some(energy) = asm.energy(&trial, params, length) {
                        if energy <= a.energy + ARMIJO * alpha * slope + allowance {
                            accepted = true;
                            break;
                        }
                    }
                    alpha *= 0.5;
                }
                if accepted {
                    report.min_alpha = report.min_alpha.min(alpha);
                    break;
                }
            }
            mu = if mu == 0.0 { 1e-6 } else { 10.0 * mu };
            report.regularised += 1;
        }
        if !accepted {
            // last resort: the Newton step where the scaled residual does not grow
            let mut alpha = 1.0;
            while alpha >= MIN_ALPHA {
                for i in 0..n {
                    trial[i] = z[i] + alpha * newton_step[i];
                }
                if let Some((_, g)) = asm.gradient(&trial, params, length) {
                    if scales.residual_norm(&g) <= rnorm {
                        accepted = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if !accepted {
                return Err(NewtonFailure::Diverged {
                    iterations: report.iterations,
                    update: last_update,
                    residual: rnorm,
                    line_search_failed: true,
                });
            }
            report.min_alpha = report.min_alpha.min(alpha);
        }
        z.copy_from_slice(&trial);
    }
}
