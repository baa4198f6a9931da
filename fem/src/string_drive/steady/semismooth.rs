//! The solve loop of the direct steady solve: semismooth Newton with an active set and a backtracking line search on the scaled merit, with its variable weights and row scales.

use super::*;

/// Norm weights of X (docs/fem-drive.md §12): z as the step system (H for values, 1 for
/// slopes), R ω₁ for c, ω₁ for ω₂, 10³ F_ref/R for the tractions (they follow z; the
/// round-off of the stiff normal penalty, ≈ 10⁻⁸ N in the ν-rows, would otherwise keep
/// their update above 10⁻¹⁰ of F_ref/R).
pub(super) fn variable_weights(asm: &Assembler, h: f64, r: f64, omega1: f64, f_ref: f64, m: usize) -> Vec<f64> {
    let mut w = super::super::system::weights(asm, h, r, 1.0);
    w.truncate(asm.len());
    w.push(r * omega1);
    w.push(omega1);
    w.extend(std::iter::repeat_n(1e3 * f_ref / r, m));
    w
}

/// Row scales of the merit ½‖F‖²: 1/F_ref for force rows, 1/(F_ref h_node) for the
/// slope rows (whose residuals are moments, N·m).
pub(super) fn row_scales(asm: &Assembler, f_ref: f64, m: usize) -> Vec<f64> {
    let dofs = asm.dofs();
    let mut s: Vec<f64> = dofs
        .kinds()
        .iter()
        .zip(dofs.spacing())
        .map(|(k, sp)| if *k == crate::dofs::DofKind::Value { 1.0 / f_ref } else { 1.0 / (f_ref * sp) })
        .collect();
    s.extend(std::iter::repeat_n(1.0 / f_ref, 2 + m));
    s
}

pub(super) fn merit(r: &[f64], s: &[f64]) -> f64 {
    0.5 * r.iter().zip(s).map(|(a, b)| (a * b) * (a * b)).sum::<f64>()
}

/// A problem with its pattern.
pub(super) struct Patterned<'p, 'a> {
    problem: &'p SteadyProblem<'a>,
    rows: Vec<usize>,
    cols: Vec<usize>,
}

impl<'p, 'a> Patterned<'p, 'a> {
    pub(super) fn new(problem: &'p SteadyProblem<'a>) -> Self {
        let (rows, cols) = problem.pattern();
        Patterned { problem, rows, cols }
    }
}

impl<'a> std::ops::Deref for Patterned<'_, 'a> {
    type Target = SteadyProblem<'a>;
    fn deref(&self) -> &SteadyProblem<'a> {
        self.problem
    }
}

/// Work of one semismooth Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SteadyNewton {
    /// Iterations.
    pub iterations: usize,
    /// Last scaled update.
    pub update_norm: f64,
}

/// Semismooth Newton on F(X) = 0 from `x` (overwritten on success): the generalised
/// Jacobian of the current active set, a backtracking line search on the merit
/// ½‖F‖² (the best trial is taken if none decreases it enough — the active set may
/// change along the step), converged when the full step's scaled norm is ≤ `tolerance`
/// and the active set did not change.
///
/// # Errors
/// [`NewtonFailure`] with the iteration count and the last update norm.
pub fn newton(problem: &SteadyProblem, x: &mut [f64], w: &[f64], scales: &[f64], tolerance: f64, max_iterations: usize) -> Result<SteadyNewton, NewtonFailure> {
    let n = x.len();
    let problem = &Patterned::new(problem);
    let mut lu = BorderedLu::new(&problem.rows, &problem.cols, n, [problem.ic(), problem.iw()]).map_err(NewtonFailure::Pattern)?;
    let mut report = SteadyNewton::default();
    let mut last_update = f64::INFINITY;
    let mut trial = vec![0.0; n];
    let mut small_before = false;
    let mut floor_count = 0usize;
    loop {
        let Some(ev) = problem.evaluate(x, true) else {
            return Err(NewtonFailure::Inadmissible { iteration: report.iterations });
        };
        if report.iterations >= max_iterations {
            return Err(NewtonFailure::NotConverged { iterations: report.iterations, update: last_update, tolerance });
        }
        report.iterations += 1;
        let m0 = merit(&ev.residual, scales);
        // a singular generalised Jacobian (an active set without a unique solution) is
        // regularised on its diagonal, Levenberg–Marquardt style, 1e-12 → 1e-4 of D
        let mut step: Vec<f64> = ev.residual.iter().map(|r| -r).collect();
        let solved = lu.solve(&ev.values, &[], &mut step);
        if let Err(e) = solved {
            let mut d = vec![0.0; n];
            for (k, &v) in ev.values.iter().enumerate() {
                if problem.rows[k] == problem.cols[k] {
                    d[problem.rows[k]] += v;
                }
            }
            let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut ok = false;
            for f in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4] {
                let shift: Vec<f64> = d.iter().map(|v| f * v.abs().max(1e-6 * dmax).max(1e-300)).collect();
                step.iter_mut().zip(&ev.residual).for_each(|(s, r)| *s = -r);
                if lu.solve(&ev.values, &shift, &mut step).is_ok() {
                    ok = true;
                    break;
                }
            }
            if !ok {
                return Err(NewtonFailure::Singular { matrix: "Jacobian", iteration: report.iterations, detail: e });
            }
        }
        let unorm = super::super::system::scaled_norm(&step, w);
        last_update = unorm;
        // a step below the tolerance is taken whole (the merit is at round-off)
        let small = unorm <= tolerance;
        let mut best: Option<(f64, f64)> = None;
        let mut alpha = 1.0;
        let mut accepted = None;
        while alpha >= 1.0 / 1024.0 {
            for i in 0..n {
                trial[i] = x[i] + alpha * step[i];
            }
            if let Some(et) = problem.evaluate(&trial, false) {
                let mt = merit(&et.residual, scales);
                if small || mt <= (1.0 - 1e-4 * alpha) * m0 {
                    accepted = Some((alpha, et, mt));
                    break;
                }
                if best.is_none_or(|(_, m)| mt < m) {
                    best = Some((alpha, mt));
                }
            }
            alpha *= 0.5;
        }
        // the accepted trial's evaluation and merit are those of the new x
        let (alpha, same_set, merit_after, after) = match accepted {
            Some((a, et, mt)) => (a, et.results.iter().zip(&ev.results).all(|(p, q)| p.slip == q.slip), mt, Some(et)),
            None => match best {
                Some((a, mt)) => (a, false, mt, None),
                None => return Err(NewtonFailure::LineSearch { what: "no admissible step", iteration: report.iterations, update: unorm }),
            },
        };
        for i in 0..n {
            x[i] += alpha * step[i];
        }
        // the round-off floor: steps within 10³ of the tolerance that no longer reduce
        // the merit by 10 % for 3 iterations on the same active set (fine meshes of a
        // stiff normal penalty)
        floor_count = if unorm <= 1e3 * tolerance && same_set && merit_after > 0.9 * m0 { floor_count + 1 } else { 0 };
        // converged: a whole step below the tolerance that kept the active set, or two
        // in a row (a point exactly at its slip bound may flip at round-off)
        if (alpha == 1.0 && small && (same_set || small_before)) || floor_count >= 3 {
            // a point taken as stick only to give its pulley an equation (see
            // `evaluate`) must obey Coulomb's bound by itself at the solution
            if let Some(p) = after.and_then(|e| e.results.into_iter().find(|p| !p.slip && p.traction.abs() > problem.sp.mu * p.normal * (1.0 + 1e-8) + 1e-12)) {
                return Err(NewtonFailure::NoCoulombState { traction: p.traction.abs(), bound: problem.sp.mu * p.normal, sigma: p.point.sigma });
            }
            report.update_norm = unorm;
            return Ok(report);
        }
        small_before = alpha == 1.0 && small;
    }
}
