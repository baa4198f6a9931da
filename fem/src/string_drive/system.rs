//! The global system of one time step (D3): the string's energy from the shared
//! [`Assembler`] (strain, gravity), the extra element terms of [`super::contact`] in
//! (q, a, φ), and the load potential (D4); a Newton solver on it (as
//! docs/fem-string.md §8: Armijo line search on Π, Levenberg–Marquardt fallback, faer
//! sparse LU of the banded block with the symbolic factorisation reused and the 2 × 2
//! Schur complement of (a, φ): `linear::BorderedLu`).

use rayon::prelude::*;

use crate::assembly::Assembler;
use crate::dofs::DofKind;
use crate::error::NewtonFailure;
use crate::kinematics::{TermParams, NDOF};
use crate::linear::BorderedLu;
use crate::quadrature::Rule;

use super::contact::{self, PointState, StepParams, NEXT};

const ARMIJO: f64 = 1e-4;
const MIN_ALPHA: f64 = 9.5367431640625e-7;

/// Energy, gradient and Hessian of an element's extra terms in (q, a, φ).
type ExtraDerivatives = (f64, [f64; NEXT], [[f64; NEXT]; NEXT]);

/// Load of the driven pulley (D4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Load {
    /// M₂, N·m.
    pub torque: f64,
    /// d₂, N·m·s.
    pub damping: f64,
    /// Δt, s.
    pub time_step: f64,
}

impl Load {
    /// V_load(φ) = M₂ φ + d₂ φ²/(2Δt).
    fn energy(&self, phi: f64) -> f64 {
        self.torque * phi + 0.5 * self.damping / self.time_step * phi * phi
    }
}

/// One time step's discrete problem: x = (z, a, φ).
pub struct StepSystem<'a> {
    /// The string's assembler (penalty `None`: contact is an extra term here).
    pub asm: &'a Assembler,
    /// Strain and gravity parameters.
    pub params: TermParams,
    /// Belt length L, m.
    pub length: f64,
    /// Contact points per element.
    pub points: &'a [Vec<PointState>],
    /// Contact and inertia parameters.
    pub step: StepParams,
    /// The load.
    pub load: Load,
    /// The strain rule (for the inertia term).
    pub strain_rule: Rule,
}

/// Pattern of the step system: the assembler's 8×8 blocks, one 10×10 block per element
/// for the extra terms, and the (φ, φ) entry of the load.
pub struct Pattern {
    /// Row of each triplet.
    pub rows: Vec<usize>,
    /// Column of each triplet.
    pub cols: Vec<usize>,
    /// Position of one (i, i) triplet per unknown.
    pub diagonal: Vec<usize>,
}

impl Pattern {
    /// The pattern for `asm` (+ a, φ).
    pub fn new(asm: &Assembler) -> Pattern {
        let nz = asm.len();
        let (r0, c0) = asm.pattern();
        let mut rows = r0.to_vec();
        let mut cols = c0.to_vec();
        for e in 0..asm.mesh().len() {
            let idx = extended(asm, e);
            for gi in idx.iter().flatten() {
                for gj in idx.iter().flatten() {
                    rows.push(*gi);
                    cols.push(*gj);
                }
            }
        }
        rows.push(nz + 1);
        cols.push(nz + 1);
        let mut diagonal = vec![usize::MAX; nz + 2];
        for (k, (&r, &c)) in rows.iter().zip(&cols).enumerate() {
            if r == c && diagonal[r] == usize::MAX {
                diagonal[r] = k;
            }
        }
        Pattern { rows, cols, diagonal }
    }
}

/// Global indices of element e's 10 extra-term variables.
fn extended(asm: &Assembler, e: usize) -> [Option<usize>; NEXT] {
    let idx = asm.dofs().element(e);
    let nz = asm.len();
    std::array::from_fn(|i| if i < NDOF { idx[i] } else { Some(nz + i - NDOF) })
}

impl StepSystem<'_> {
    /// Number of unknowns (4N + 7 + 2).
    pub fn len(&self) -> usize {
        self.asm.len() + 2
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        false
    }

    fn split<'x>(&self, x: &'x [f64]) -> (&'x [f64], f64, f64) {
        let nz = self.asm.len();
        (&x[..nz], x[nz], x[nz + 1])
    }

    /// Π(x), J; `None` if inadmissible or not finite.
    pub fn energy(&self, x: &[f64]) -> Option<f64> {
        let (z, a, phi) = self.split(x);
        let base = self.asm.energy(z, &self.params, self.length)?;
        let extra: f64 = (0..self.asm.mesh().len())
            .into_par_iter()
            .map(|e| {
                let pts = &self.points[e];
                if !contact::active(pts, &self.step) {
                    return 0.0;
                }
                let el = self.asm.context(e, &self.params);
                let q = self.asm.dofs().gather(e, z, self.length);
                contact::element_energy(&el, &q, a, phi, pts, &self.step, self.strain_rule)
            })
            .sum();
        let total = base + extra + self.load.energy(phi);
        total.is_finite().then_some(total)
    }

    /// Π and G; `None` if inadmissible or not finite.
    pub fn gradient(&self, x: &[f64]) -> Option<(f64, Vec<f64>)> {
        let (z, a, phi) = self.split(x);
        let (base, gz) = self.asm.gradient(z, &self.params, self.length)?;
        let mut g = gz;
        g.extend([0.0, 0.0]);
        let per: Vec<(usize, f64, [f64; NEXT])> = (0..self.asm.mesh().len())
            .into_par_iter()
            .filter(|&e| contact::active(&self.points[e], &self.step))
            .map(|e| {
                let el = self.asm.context(e, &self.params);
                let q = self.asm.dofs().gather(e, z, self.length);
                let (en, ge) = contact::element_gradient(&el, &q, a, phi, &self.points[e], &self.step, self.strain_rule);
                (e, en, ge)
            })
            .collect();
        let mut energy = base + self.load.energy(phi);
        for (e, en, ge) in per {
            energy += en;
            for (i, gi) in extended(self.asm, e).iter().enumerate() {
                if let Some(gi) = gi {
                    g[*gi] += ge[i];
                }
            }
        }
        let nz = self.asm.len();
        g[nz + 1] += self.load.torque + self.load.damping / self.load.time_step * phi;
        (energy.is_finite() && g.iter().all(|v| v.is_finite())).then_some((energy, g))
    }

    /// Π, G and the Hessian values in the order of [`Pattern::new`].
    pub fn assemble(&self, x: &[f64]) -> Option<(f64, Vec<f64>, Vec<f64>)> {
        let (z, a, phi) = self.split(x);
        let base = self.asm.assemble(z, &self.params, self.length)?;
        let mut g = base.gradient;
        g.extend([0.0, 0.0]);
        let mut values = base.values;
        let per: Vec<Option<ExtraDerivatives>> = (0..self.asm.mesh().len())
            .into_par_iter()
            .map(|e| {
                if !contact::active(&self.points[e], &self.step) {
                    return None;
                }
                let el = self.asm.context(e, &self.params);
                let q = self.asm.dofs().gather(e, z, self.length);
                Some(contact::element_derivatives(&el, &q, a, phi, &self.points[e], &self.step, self.strain_rule))
            })
            .collect();
        let mut energy = base.energy + self.load.energy(phi);
        for (e, d) in per.iter().enumerate() {
            let idx = extended(self.asm, e);
            match d {
                Some((en, ge, he)) => {
                    energy += en;
                    for (i, gi) in idx.iter().enumerate() {
                        let Some(gi) = gi else { continue };
                        g[*gi] += ge[i];
                        for (j, gj) in idx.iter().enumerate() {
                            if gj.is_some() {
                                values.push(he[i][j]);
                            }
                        }
                    }
                }
                None => {
                    let n = idx.iter().flatten().count();
                    values.extend(std::iter::repeat_n(0.0, n * n));
                }
            }
        }
        let nz = self.asm.len();
        g[nz + 1] += self.load.torque + self.load.damping / self.load.time_step * phi;
        values.push(self.load.damping / self.load.time_step);
        let finite = energy.is_finite() && g.iter().all(|v| v.is_finite()) && values.iter().all(|v| v.is_finite());
        finite.then_some((energy, g, values))
    }
}

/// Norm weights of the step unknowns: d_i = H for S̃, ν and a, H/R for φ, 1 for slopes
/// (docs/fem-drive.md §3); `steady` gives the steady-state weights of §7 (∂σS by
/// F_ref/EA) instead.
pub fn weights(asm: &Assembler, centre_distance: f64, radius: f64, slope_s: f64) -> Vec<f64> {
    let dofs = asm.dofs();
    let mut w: Vec<f64> = dofs.kinds().iter().map(|k| if *k == DofKind::Value { centre_distance } else { 1.0 }).collect();
    for k in 0..asm.mesh().len() {
        let nd = dofs.node(k);
        w[nd.slopes_in.0] = slope_s;
        w[nd.slopes_out.0] = slope_s;
    }
    w.push(centre_distance);
    w.push(centre_distance / radius);
    w
}

/// Scaled max norm max |v_i|/w_i.
pub fn scaled_norm(v: &[f64], w: &[f64]) -> f64 {
    v.iter().zip(w).fold(0.0, |m, (a, b)| m.max(a.abs() / b))
}

/// Work of one Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct StepNewton {
    /// Iterations.
    pub iterations: usize,
    /// Last scaled update.
    pub update_norm: f64,
}

/// Newton on the step system from `x` (overwritten). `lu` holds `pattern` with (a, φ)
/// as its border (their rows are dense: the bordered solve keeps the cost linear).
///
/// # Errors
/// [`NewtonFailure`] with the iteration count and the last update norm.
#[allow(clippy::too_many_arguments)]
pub fn newton(sys: &StepSystem, pattern: &Pattern, lu: &mut BorderedLu, x: &mut [f64], w: &[f64], tolerance: f64, max_iterations: usize, energy_scale: f64) -> Result<StepNewton, NewtonFailure> {
    let n = x.len();
    let mut step = vec![0.0; n];
    let mut newton_step = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut report = StepNewton::default();
    let mut last_update = f64::INFINITY;
    let allowance = 1e-13 * energy_scale;
    loop {
        let Some((energy, grad, values)) = sys.assemble(x) else {
            return Err(NewtonFailure::Inadmissible { iteration: report.iterations });
        };
        if report.iterations >= max_iterations {
            return Err(NewtonFailure::NotConverged { iterations: report.iterations, update: last_update, tolerance });
        }
        report.iterations += 1;
        let mut d = vec![0.0; n];
        for (k, &v) in values.iter().enumerate() {
            if pattern.rows[k] == pattern.cols[k] {
                d[pattern.rows[k]] += v;
            }
        }
        // D = diag |K|, floored at 1e-8 of its largest entry: a direction without
        // stiffness (φ or a when every friction point of a pulley slides, d₂ = 0) is
        // regularised too
        let floor = 1e-8 * d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut mu = 0.0;
        let mut accepted = false;
        while mu <= 1e2 {
            let mut vals = values.clone();
            if mu > 0.0 {
                for (i, &pos) in pattern.diagonal.iter().enumerate() {
                    vals[pos] += mu * d[i].abs().max(floor).max(1e-300);
                }
            }
            // a singular tangent (e.g. a pulley whose points all slide, d₂ = 0) is
            // regularised like an indefinite one
            for (s, g) in step.iter_mut().zip(&grad) {
                *s = -g;
            }
            let solved = lu.solve(&vals, &[], &mut step);
            if let Err(e) = solved {
                if mu >= 1e2 {
                    return Err(NewtonFailure::Singular { matrix: "tangent", iteration: report.iterations, detail: e });
                }
                mu = if mu == 0.0 { 1e-6 } else { 10.0 * mu };
                continue;
            }
            let unorm = scaled_norm(&step, w);
            let slope: f64 = step.iter().zip(&grad).map(|(s, g)| s * g).sum();
            if mu == 0.0 {
                last_update = unorm;
                newton_step.copy_from_slice(&step);
                if unorm <= tolerance {
                    for i in 0..n {
                        trial[i] = x[i] + step[i];
                    }
                    if sys.energy(&trial).is_some() {
                        x.copy_from_slice(&trial);
                        report.update_norm = unorm;
                        return Ok(report);
                    }
                }
            }
            if slope < 0.0 {
                let mut alpha = 1.0;
                while alpha >= MIN_ALPHA {
                    for i in 0..n {
                        trial[i] = x[i] + alpha * step[i];
                    }
                    if let Some(e) = sys.energy(&trial) {
                        if e <= energy + ARMIJO * alpha * slope + allowance {
                            accepted = true;
                            break;
                        }
                    }
                    alpha *= 0.5;
                }
                if accepted {
                    break;
                }
            }
            mu = if mu == 0.0 { 1e-6 } else { 10.0 * mu };
        }
        if !accepted {
            // last resort: the Newton step where the gradient does not grow
            let g0 = grad.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut alpha = 1.0;
            while alpha >= MIN_ALPHA {
                for i in 0..n {
                    trial[i] = x[i] + alpha * newton_step[i];
                }
                if let Some((_, g)) = sys.gradient(&trial) {
                    if g.iter().fold(0.0f64, |m, v| m.max(v.abs())) <= g0 {
                        accepted = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if !accepted {
                return Err(NewtonFailure::LineSearch { what: "line search failed", iteration: report.iterations, update: last_update });
            }
        }
        x.copy_from_slice(&trial);
    }
}
