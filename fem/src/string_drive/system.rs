//! The global system of one time step (D3): the belt's energy from the shared
//! [`Assembler`] (strain, gravity, and whatever else the element carries), the extra
//! element terms of [`super::contact`] in (q, a, φ) on the element's centreline, and the
//! load potential (D4); a Newton solver on it (as
//! docs/fem-string.md §8: Armijo line search on Π, Levenberg–Marquardt fallback, faer
//! sparse LU of the banded block with the symbolic factorisation reused and the 2 × 2
//! Schur complement of (a, φ): `linear::BorderedLu`). Generic over the element: N
//! unknowns of any 1-D layout and its kernel K ([`LayoutElement`]), with X = N + 2
//! ([`super::contact::extended_size`]); the defaults are the string's formulations.

use numerics::newton::{Damping, Evaluation, NewtonError, NewtonOptions, NewtonProblem, Progress, TrialKind, TrialStep, Verdict};
use rayon::prelude::*;

use crate::assembly::{Assembler, ElementKernel};
use crate::dofs::DofKind;
use crate::error::NewtonFailure;
use crate::formulation::layout::LayoutElement;
use crate::formulation::Kernel;
use crate::kinematics::{TermParams, NDOF};
use crate::linear::BorderedLu;
use crate::newton::{diagonal_sums, shifted, EnergyLevels, NextLevel, MIN_ALPHA};
use crate::quadrature::Rule;

use super::contact::{self, PointState, StepParams, NEXT};

/// Energy, gradient and Hessian of an element's extra terms in (q, a, φ).
type ExtraDerivatives<const X: usize> = (f64, [f64; X], [[f64; X]; X]);

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

/// One time step's discrete problem: x = (z, a, φ), for an element with N unknowns
/// (X = N + 2).
pub struct StepSystem<'a, const N: usize = NDOF, const X: usize = NEXT, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    /// The belt's assembler (penalty `None`: contact is an extra term here).
    pub asm: &'a Assembler<N, K>,
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

/// Pattern of the step system: the assembler's N×N blocks, one X×X block (X = N + 2)
/// per element for the extra terms, and the (φ, φ) entry of the load.
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
    pub fn new<const N: usize, const X: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>) -> Pattern {
        let nz = asm.len();
        let (r0, c0) = asm.pattern();
        let mut rows = r0.to_vec();
        let mut cols = c0.to_vec();
        for e in 0..asm.mesh().len() {
            let idx = extended::<N, X, K>(asm, e);
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

/// Global indices of element e's X = N + 2 extra-term variables.
fn extended<const N: usize, const X: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, e: usize) -> [Option<usize>; X] {
    let idx = asm.dofs().element(e);
    let nz = asm.len();
    std::array::from_fn(|i| if i < N { idx[i] } else { Some(nz + i - N) })
}

impl<const N: usize, const X: usize, K: LayoutElement<N> + ?Sized> StepSystem<'_, N, X, K> {
    /// Number of unknowns (4N + 7 + 2).
    pub fn len(&self) -> usize {
        self.asm.len() + 2
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The element's field layout.
    fn layout(&self) -> crate::element::ElementLayout {
        self.asm.kernel().layout()
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
                contact::element_energy(self.layout(), &el, &q, a, phi, pts, &self.step, self.strain_rule)
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
        let per: Vec<(usize, f64, [f64; X])> = (0..self.asm.mesh().len())
            .into_par_iter()
            .filter(|&e| contact::active(&self.points[e], &self.step))
            .map(|e| {
                let el = self.asm.context(e, &self.params);
                let q = self.asm.dofs().gather(e, z, self.length);
                let (en, ge) = contact::element_gradient(self.layout(), &el, &q, a, phi, &self.points[e], &self.step, self.strain_rule);
                (e, en, ge)
            })
            .collect();
        let mut energy = base + self.load.energy(phi);
        for (e, en, ge) in per {
            energy += en;
            for (i, gi) in extended::<N, X, K>(self.asm, e).iter().enumerate() {
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
        let per: Vec<Option<ExtraDerivatives<X>>> = (0..self.asm.mesh().len())
            .into_par_iter()
            .map(|e| {
                if !contact::active(&self.points[e], &self.step) {
                    return None;
                }
                let el = self.asm.context(e, &self.params);
                let q = self.asm.dofs().gather(e, z, self.length);
                Some(contact::element_derivatives(self.layout(), &el, &q, a, phi, &self.points[e], &self.step, self.strain_rule))
            })
            .collect();
        let mut energy = base.energy + self.load.energy(phi);
        for (e, d) in per.iter().enumerate() {
            let idx = extended::<N, X, K>(self.asm, e);
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
pub fn weights<const N: usize, K: crate::assembly::ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, centre_distance: f64, radius: f64, slope_s: f64) -> Vec<f64> {
    let dofs = asm.dofs();
    let mut w: Vec<f64> = dofs.kinds().iter().map(|k| if *k == DofKind::Value { centre_distance } else { 1.0 }).collect();
    for k in 0..asm.mesh().len() {
        let nd = dofs.node_unknowns(k);
        w[nd.slopes_in[0]] = slope_s;
        w[nd.slopes_out[0]] = slope_s;
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

/// The step system as a [`NewtonProblem`]: G = ∂Π/∂x with its tangent from one
/// assembly pass, trials judged by Π alone, the levels of [`EnergyLevels`] (D floored
/// at 10⁻⁸ max|D|: a direction without stiffness — φ or a when every friction point of
/// a pulley slides, d₂ = 0 — is regularised too; the last resort on max |G|),
/// factorised by the bordered LU inside its solve. A singular tangent (a pulley whose
/// points all slide) fails its level like an indefinite one (its step is not finite);
/// at the last μ it is an error. The plain step of the last resort is the last one
/// solved: of an earlier iteration if this one's plain tangent was singular.
struct StepProblem<'s, 'a, const N: usize, const X: usize, K: LayoutElement<N> + ?Sized> {
    sys: &'s StepSystem<'a, N, X, K>,
    pattern: &'s Pattern,
    lu: &'s mut BorderedLu,
    w: &'s [f64],
    levels: EnergyLevels,
    /// Π, the Hessian values and D = diag K of the last assembly; max |G| there.
    energy: f64,
    values: Vec<f64>,
    d: Vec<f64>,
    g0: f64,
    /// The values of the current shifted level.
    shifted: Vec<f64>,
    /// The LU's message if the last solve failed.
    singular: Option<String>,
    converged: bool,
}

/// Why a call of [`StepProblem`] failed.
enum StepError {
    /// The assembly at an accepted iterate failed (∂σS ≤ 0 or non-finite).
    Inadmissible,
    /// The tangent shifted by the last μ is singular; the LU's message.
    Singular(String),
}

/// max |v_i|.
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

impl<const N: usize, const X: usize, K: LayoutElement<N> + ?Sized> NewtonProblem for StepProblem<'_, '_, N, X, K> {
    type Error = StepError;
    fn size(&self) -> usize {
        self.sys.len()
    }
    fn evaluation(&self) -> Evaluation {
        Evaluation { residual_with_factorization: true, merit_only: true }
    }
    fn damping(&self) -> Damping {
        Damping::Backtracking { take_best: false }
    }
    /// G(x), NaN where inadmissible (not called with both evaluation hooks: G comes
    /// with the assembly, trials are judged by `trial_merit`).
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<(), StepError> {
        let g = self.sys.gradient(x).map(|(_, g)| g);
        r.copy_from_slice(g.as_deref().unwrap_or(&vec![f64::NAN; r.len()]));
        Ok(())
    }
    fn factorize(&mut self, x: &[f64]) -> Result<(), StepError> {
        let mut r = vec![0.0; self.size()];
        self.factorize_with_residual(x, &mut r)
    }
    fn factorize_with_residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<(), StepError> {
        // the bordered LU factorises inside its solve
        let (energy, grad, values) = self.sys.assemble(x).ok_or(StepError::Inadmissible)?;
        diagonal_sums(&values, &self.pattern.rows, &self.pattern.cols, &mut self.d);
        self.g0 = max_abs(&grad);
        r.copy_from_slice(&grad);
        self.energy = energy;
        self.values = values;
        self.levels.restart();
        Ok(())
    }
    fn solve(&mut self, b: &mut [f64]) -> Result<(), StepError> {
        if self.levels.reuse_plain_step(b) {
            return Ok(());
        }
        let values = if self.levels.mu == 0.0 { &self.values } else { &self.shifted };
        match self.lu.solve(values, &[], b) {
            Ok(()) => {
                self.singular = None;
                self.levels.solved(b);
            }
            Err(e) => {
                self.singular = Some(e);
                b.fill(f64::NAN);
            }
        }
        Ok(())
    }
    fn norm(&self, v: &[f64], _x: &[f64]) -> f64 {
        scaled_norm(v, self.w)
    }
    fn merit(&mut self, _x: &[f64], _r: &[f64]) -> f64 {
        self.energy
    }
    fn trial_merit(&mut self, trial: &[f64], kind: TrialKind) -> Result<Option<f64>, StepError> {
        if kind == TrialKind::Converging {
            let energy = self.sys.energy(trial);
            self.converged = energy.is_some();
            return Ok(energy);
        }
        if self.levels.last_resort {
            return Ok(self.sys.gradient(trial).map(|(_, g)| max_abs(&g)));
        }
        Ok(self.sys.energy(trial))
    }
    fn line_search(&mut self, _level: usize, slope: f64) -> bool {
        self.levels.line_search(slope)
    }
    fn accept_step(&mut self, t: &TrialStep<'_>) -> Verdict {
        self.levels.verdict(t, self.g0)
    }
    /// Only the converging full step ends the iteration.
    fn converged(&mut self, _p: &Progress<'_>) -> bool {
        self.converged
    }
    fn regularise(&mut self, _x: &[f64], _level: usize) -> Result<bool, StepError> {
        if let Some(e) = self.singular.take() {
            if self.levels.mu >= 1e2 {
                return Err(StepError::Singular(e));
            }
        }
        match self.levels.next() {
            NextLevel::Exhausted => return Ok(false),
            NextLevel::Shift => {
                let floor = 1e-8 * max_abs(&self.d);
                self.shifted = shifted(&self.values, &self.pattern.diagonal, &self.d, self.levels.mu, floor);
            }
            NextLevel::LastResort => {}
        }
        Ok(true)
    }
}

/// Newton on the step system from `x` (overwritten): [`numerics::newton::solve`] with
/// backtracking (Armijo on Π, Levenberg–Marquardt levels, a last resort on the
/// gradient; [`StepProblem`]). `lu` holds `pattern` with (a, φ) as its border (their
/// rows are dense: the bordered solve keeps the cost linear).
///
/// # Errors
/// [`NewtonFailure`] with the iteration count and the last update norm.
#[allow(clippy::too_many_arguments)]
pub fn newton<const N: usize, const X: usize, K: LayoutElement<N> + ?Sized>(sys: &StepSystem<N, X, K>, pattern: &Pattern, lu: &mut BorderedLu, x: &mut [f64], w: &[f64], tolerance: f64, max_iterations: usize, energy_scale: f64) -> Result<StepNewton, NewtonFailure> {
    let n = x.len();
    let mut problem = StepProblem {
        sys,
        pattern,
        lu,
        w,
        levels: EnergyLevels::new(n, 1e-13 * energy_scale),
        energy: 0.0,
        values: Vec::new(),
        d: vec![0.0; n],
        g0: 0.0,
        shifted: Vec::new(),
        singular: None,
        converged: false,
    };
    let opts = NewtonOptions { tolerance, max_iterations, min_damping: MIN_ALPHA };
    match numerics::newton::solve(&mut problem, x, &opts) {
        Ok(stats) => Ok(StepNewton { iterations: stats.iterations, update_norm: stats.last_correction }),
        Err(e) => Err(match e {
            // the state of the last iterate is checked before the iteration limit
            NewtonError::MaxIterations { iterations, .. } if sys.assemble(x).is_none() => NewtonFailure::Inadmissible { iteration: iterations },
            NewtonError::MaxIterations { iterations, correction, .. } => NewtonFailure::NotConverged { iterations, update: correction, tolerance },
            NewtonError::LineSearchFailed { iteration, correction, .. } => {
                NewtonFailure::LineSearch { what: "line search failed", iteration, update: correction }
            }
            NewtonError::NonFinite { iteration, .. } | NewtonError::Problem { iteration, error: StepError::Inadmissible, .. } => {
                NewtonFailure::Inadmissible { iteration: iteration.saturating_sub(1) }
            }
            NewtonError::Problem { iteration, error: StepError::Singular(detail), .. } => NewtonFailure::Singular { matrix: "tangent", iteration, detail },
            NewtonError::SingularStep { iteration, .. } => {
                NewtonFailure::Singular { matrix: "tangent", iteration, detail: "non-finite Newton step".into() }
            }
            NewtonError::InvalidOptions(_) | NewtonError::DimensionMismatch { .. } | NewtonError::DampingExhausted { .. } => {
                NewtonFailure::NotConverged { iterations: 0, update: f64::INFINITY, tolerance }
            }
        }),
    }
}

#[cfg(test)]
mod tests {
    //! The step system generic over the element: with the Cosserat element (N = 12,
    //! {s, ν, ψ}, one shared slope triple at each transition and the augmented map (C3)
    //! on the polar side) the assembled gradient and Hessian of Π — the element's own
    //! energy, the contact, friction and transport-inertia terms on its centreline
    //! through the map, and the load — match central differences of Π and of the
    //! gradient over every unknown (z, a, φ), to 1e-6 of the largest entry (measured
    //! 1.3e-7 for the gradient and 3.0e-7 for the Hessian: round-off ε|Π|/d of the
    //! differences).
    use std::sync::Arc;

    use drive::contour::Contour;

    use super::*;
    use crate::formulation::cosserat::{CosseratElement, CosseratRules};
    use crate::mesh::Mesh;
    use crate::test_rng::Rng;

    const NC: usize = crate::formulation::layout::NDOF_COSSERAT;

    #[test]
    fn cosserat_step_system_matches_finite_differences() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let mesh = Mesh::new(contour, 24, 1.0).unwrap();
        let kernel = Arc::new(CosseratElement::new(5.0e3, CosseratRules::with_shear(Rule::Gauss(3))));
        let asm = Assembler::<NC, CosseratElement>::with_kernel(mesh, kernel);
        let length = 0.98 * contour.length();
        let params = TermParams { axial_stiffness: 2.0e4, weight: Some(1.2), penalty: None, bending_stiffness: Some(0.02) };
        assert!((0..asm.mesh().len()).any(|e| asm.context(e, &params).augmented.contains(&true)), "the map (C3) is exercised");
        let mut rng = Rng(0x005e_ed0f_7a5e_1234);
        // a state near the contour: s = σ L/L_c, ν pressed 10 µm into the drums (less
        // some noise), a small ψ; slopes around their smooth values
        let dofs = asm.dofs();
        let mut z = vec![0.0; asm.len()];
        for (k, &sigma) in asm.mesh().node_sigmas().iter().enumerate().take(asm.mesh().len()) {
            let nd = dofs.node_unknowns(k);
            let on_arc = asm.mesh().elements()[k].region.is_polar();
            let values = [sigma * length / contour.length(), if on_arc { -1.0e-5 } else { -2.0e-3 } + 1e-6 * rng.next(), 1e-3 * (rng.next() - 0.5)];
            let slopes = [length / contour.length() * (1.0 + 1e-3 * rng.next()), 1e-4 * (rng.next() - 0.5), 1e-2 * (rng.next() - 0.5)];
            for f in 0..3 {
                if let Some(i) = nd.values[f] {
                    z[i] = values[f];
                }
                z[nd.slopes_in[f]] = slopes[f];
                z[nd.slopes_out[f]] = slopes[f];
            }
        }
        // contact points of the mixed rule with references and multipliers around the
        // state; every other element slips (a small bound), the rest stick
        let layout = asm.kernel().layout();
        let points: Vec<Vec<PointState>> = (0..asm.mesh().len())
            .map(|e| {
                let el = asm.context(e, &params);
                let q = el.centreline(layout, &dofs.gather(e, &z, length));
                contact::mixed_rule(Rule::Simpson)
                    .into_iter()
                    .map(|rule_point| {
                        let pulley = contact::reachable_pulley(&contour, el.geometry.region, el.sigma(rule_point.0));
                        contact::tests::random_point(&el, &q, rule_point, pulley, &mut rng, e % 2 == 0)
                    })
                    .collect()
            })
            .collect();
        let step = StepParams { penalty: 3.0e6, tangential_penalty: 2.0e6, driver_advance: 1.0e-3, radius: 0.08, inertia: Some(40.0) };
        let load = Load { torque: 2.0, damping: 0.01, time_step: 1e-3 };
        let sys = StepSystem::<NC, { NC + 2 }, CosseratElement> { asm: &asm, params, length, points: &points, step, load, strain_rule: Rule::Simpson };
        let pattern = Pattern::new::<NC, { NC + 2 }, CosseratElement>(&asm);
        let mut x = z.clone();
        x.extend([1.0e-3, 0.0125]);
        let n = x.len();
        let (energy, g, values) = sys.assemble(&x).expect("admissible");
        let (e2, g2) = sys.gradient(&x).unwrap();
        assert_eq!((energy.to_bits(), g.len()), (e2.to_bits(), n));
        assert!(g.iter().zip(&g2).all(|(a, b)| (a - b).abs() <= 1e-12 * a.abs().max(1.0)), "gradient of assemble and of gradient");
        let mut dense = vec![0.0; n * n];
        for (k, v) in values.iter().enumerate() {
            dense[pattern.rows[k] * n + pattern.cols[k]] += v;
        }
        let gmax = g.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        let hmax = dense.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        let mut worst: [f64; 2] = [0.0; 2];
        for j in 0..n {
            // steps 1e-8 of the unknown's scale, at least 1e-10 (m or 1): the terms are
            // piecewise smooth (⟨·⟩ of D6, stick/slip of D7), as in contact::tests;
            // smaller steps on the 10 µm deflections let round-off (ε|Π|/d) reach 1e-6
            // of the largest entry; truncation and round-off stay below it
            let d = 1e-8 * x[j].abs().max(1e-2);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += d;
            xm[j] -= d;
            let fd = (sys.energy(&xp).unwrap() - sys.energy(&xm).unwrap()) / (2.0 * d);
            worst[0] = worst[0].max((fd - g[j]).abs() / gmax);
            assert!((fd - g[j]).abs() <= 1e-6 * gmax, "G[{j}]: assembled {} FD {fd}", g[j]);
            let (gp, gm) = (sys.gradient(&xp).unwrap().1, sys.gradient(&xm).unwrap().1);
            for i in 0..n {
                let fd = (gp[i] - gm[i]) / (2.0 * d);
                worst[1] = worst[1].max((fd - dense[i * n + j]).abs() / hmax);
                assert!((fd - dense[i * n + j]).abs() <= 1e-6 * hmax, "K[{i}][{j}]: assembled {} FD {fd}", dense[i * n + j]);
            }
        }
        // the friction, contact and load rows of (a, φ) are exercised
        assert!(g[n - 2].abs() > 0.0 && g[n - 1].abs() > 0.0 && dense[(n - 2) * n + n - 1] != 0.0);
        println!("{n} unknowns: gradient error {:e}, Hessian error {:e} of their largest entries", worst[0], worst[1]);
    }
}
