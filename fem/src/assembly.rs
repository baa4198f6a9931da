//! Global assembly: element energies, gradients and Hessians summed over the closed
//! loop (docs/fem-string.md §8). Element evaluations run in parallel (rayon); the
//! triplet pattern of the Hessian is fixed by the mesh, so the symbolic LU is reused.

use std::sync::Arc;

use drive::contour::Contour;
use rayon::prelude::*;

use crate::dofs::DofMap;
use crate::formulation::{ElementDerivatives, Kernel};
use crate::kinematics::{ElementContext, TermParams, NDOF};
use crate::mesh::Mesh;

/// Points per element at which ∂σS > 0 is required (besides the strain rule's points).
const ADMISSIBILITY_POINTS: [f64; 5] = [-1.0, -0.5, 0.0, 0.5, 1.0];

/// The discrete problem: mesh, numbering, formulation; the parameters that the homotopy
/// changes (weight, belt length) are arguments of every evaluation.
pub struct Assembler {
    mesh: Mesh,
    dofs: DofMap,
    kernel: Arc<dyn Kernel>,
    rows: Vec<usize>,
    cols: Vec<usize>,
    diagonal: Vec<usize>,
    /// Per element: augmented map at start / end node (docs/fem-rod.md §3).
    augmented: Vec<[bool; 2]>,
}

/// Energy, gradient and Hessian values (in the order of [`Assembler::pattern`]).
#[derive(Debug, Clone)]
pub struct Assembled {
    /// Π, J.
    pub energy: f64,
    /// ∂Π/∂z.
    pub gradient: Vec<f64>,
    /// Hessian entries matching the pattern (duplicates to be summed).
    pub values: Vec<f64>,
}

impl Assembler {
    /// The problem on `mesh` with formulation `kernel`.
    pub fn new(mesh: Mesh, kernel: Arc<dyn Kernel>) -> Assembler {
        // a rod shares one (Cartesian) slope pair at each transition (docs/fem-rod.md §3)
        let separate = kernel.theory() == drive::scene::Theory::String;
        let dofs = DofMap::with_transition_slopes(&mesh, separate);
        let augmented = crate::dofs::augmented_flags(&mesh, separate);
        let mut rows = Vec::with_capacity(mesh.len() * NDOF * NDOF);
        let mut cols = Vec::with_capacity(mesh.len() * NDOF * NDOF);
        for e in 0..mesh.len() {
            let idx = dofs.element(e);
            for gi in idx.iter().flatten() {
                for gj in idx.iter().flatten() {
                    rows.push(*gi);
                    cols.push(*gj);
                }
            }
        }
        let mut diagonal = vec![usize::MAX; dofs.len()];
        for (k, (&r, &c)) in rows.iter().zip(&cols).enumerate() {
            if r == c && diagonal[r] == usize::MAX {
                diagonal[r] = k;
            }
        }
        Assembler { mesh, dofs, kernel, rows, cols, diagonal, augmented }
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The numbering.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The formulation.
    pub fn kernel(&self) -> &Arc<dyn Kernel> {
        &self.kernel
    }

    /// Number of global unknowns.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// (rows, cols) of the Hessian triplets, fixed for the mesh.
    pub fn pattern(&self) -> (&[usize], &[usize]) {
        (&self.rows, &self.cols)
    }

    /// For each unknown i, the position of one (i, i) entry in the pattern.
    pub fn diagonal_positions(&self) -> &[usize] {
        &self.diagonal
    }

    /// The context of element e with the term parameters `params`.
    pub fn context(&self, e: usize, params: &TermParams) -> ElementContext {
        ElementContext {
            geometry: self.mesh.elements()[e],
            contour: *self.contour(),
            params: *params,
            augmented: self.augmented[e],
        }
    }

    fn contour(&self) -> &Contour {
        self.mesh.contour()
    }

    /// True if ∂σS > 0 at the admissibility points and the strain rule's points of
    /// every element and every unknown is finite.
    pub fn admissible(&self, z: &[f64], params: &TermParams, length: f64) -> bool {
        if !z.iter().all(|v| v.is_finite()) {
            return false;
        }
        let rule = self.kernel.rules().strain;
        (0..self.mesh.len()).into_par_iter().all(|e| {
            let el = self.context(e, params);
            let q = el.effective(&self.dofs.gather(e, z, length));
            ADMISSIBILITY_POINTS
                .iter()
                .chain(rule.points().iter().map(|p| &p.0))
                .all(|&xi| el.fields(&q, xi).ds > 0.0)
        })
    }

    /// Π(z), J; `None` if z is not admissible or Π is not finite.
    pub fn energy(&self, z: &[f64], params: &TermParams, length: f64) -> Option<f64> {
        if !self.admissible(z, params, length) {
            return None;
        }
        let e: f64 = (0..self.mesh.len())
            .into_par_iter()
            .map(|e| self.kernel.energy(&self.context(e, params), &self.dofs.gather(e, z, length)))
            .sum();
        e.is_finite().then_some(e)
    }

    /// Π and G = ∂Π/∂z; `None` if z is not admissible or a value is not finite.
    pub fn gradient(&self, z: &[f64], params: &TermParams, length: f64) -> Option<(f64, Vec<f64>)> {
        if !self.admissible(z, params, length) {
            return None;
        }
        let per: Vec<(f64, [f64; NDOF])> = (0..self.mesh.len())
            .into_par_iter()
            .map(|e| self.kernel.gradient(&self.context(e, params), &self.dofs.gather(e, z, length)))
            .collect();
        let mut g = vec![0.0; self.len()];
        let mut energy = 0.0;
        for (e, (en, ge)) in per.iter().enumerate() {
            energy += en;
            for (i, gi) in self.dofs.element(e).iter().enumerate() {
                if let Some(gi) = gi {
                    g[*gi] += ge[i];
                }
            }
        }
        (energy.is_finite() && g.iter().all(|v| v.is_finite())).then_some((energy, g))
    }

    /// Π, G and the Hessian values in pattern order; `None` if z is not admissible or
    /// a value is not finite.
    pub fn assemble(&self, z: &[f64], params: &TermParams, length: f64) -> Option<Assembled> {
        if !self.admissible(z, params, length) {
            return None;
        }
        let per = self.element_derivatives(z, params, length);
        let mut g = vec![0.0; self.len()];
        let mut values = Vec::with_capacity(self.rows.len());
        let mut energy = 0.0;
        for (e, d) in per.iter().enumerate() {
            energy += d.energy;
            let idx = self.dofs.element(e);
            for (i, gi) in idx.iter().enumerate() {
                let Some(gi) = gi else { continue };
                g[*gi] += d.gradient[i];
                for (j, gj) in idx.iter().enumerate() {
                    if gj.is_some() {
                        values.push(d.hessian[i][j]);
                    }
                }
            }
        }
        let finite = energy.is_finite() && g.iter().all(|v| v.is_finite()) && values.iter().all(|v| v.is_finite());
        finite.then_some(Assembled { energy, gradient: g, values })
    }

    /// Every element's energy, gradient and Hessian (parallel; the benchmarked kernel).
    pub fn element_derivatives(&self, z: &[f64], params: &TermParams, length: f64) -> Vec<ElementDerivatives> {
        (0..self.mesh.len())
            .into_par_iter()
            .map(|e| self.kernel.derivatives(&self.context(e, params), &self.dofs.gather(e, z, length)))
            .collect()
    }
}
