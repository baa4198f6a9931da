//! Global assembly: element energies, gradients and Hessians summed over the closed
//! loop (docs/fem-string.md §8). Element evaluations run in parallel (rayon); the
//! triplet pattern of the Hessian is fixed by the mesh, so the symbolic LU is reused.

use std::sync::Arc;

use drive::contour::Contour;
use drive::scene::Theory;
use rayon::prelude::*;

use crate::dofs::DofMap;
use crate::element::{ElementLayout, STRING};
use crate::formulation::{ElementDerivatives, Kernel};
use crate::kinematics::{ElementContext, TermParams, NDOF};
use crate::mesh::Mesh;

/// Points per element at which ∂σS > 0 is required (besides the strain rule's points).
pub(crate) const ADMISSIBILITY_POINTS: [f64; 5] = [-1.0, -0.5, 0.0, 0.5, 1.0];

/// What assembly needs from an element with N local unknowns in the 1-D Hermite layout
/// [`Self::layout`] (N = `layout().dofs()`): its energy with gradient and Hessian, when
/// a local state is admissible, and how the slopes meet at region transitions. Every
/// registered formulation (`dyn Kernel`, the string layout, N = 8) is one; an element
/// with another field set (the Cosserat rod's {s, ν, θ}, N = 12) implements it directly.
pub trait ElementKernel<const N: usize>: Send + Sync {
    /// The field layout.
    fn layout(&self) -> ElementLayout;
    /// True: two slope sets at each region transition (one per adjacent element); false:
    /// one shared set, the polar side's by the augmented map (docs/fem-rod.md §3).
    fn separate_transition_slopes(&self) -> bool;
    /// True if the local unknowns q are an admissible state (∂σS > 0 where sampled).
    fn admissible(&self, el: &ElementContext, q: &[f64; N]) -> bool;
    /// Element energy, J.
    fn energy(&self, el: &ElementContext, q: &[f64; N]) -> f64;
    /// Energy and gradient.
    fn gradient(&self, el: &ElementContext, q: &[f64; N]) -> (f64, [f64; N]);
    /// Energy, gradient and Hessian.
    fn derivatives(&self, el: &ElementContext, q: &[f64; N]) -> ElementDerivatives<N>;
}

impl ElementKernel<NDOF> for dyn Kernel {
    fn layout(&self) -> ElementLayout {
        STRING
    }

    /// A rod shares one (Cartesian) slope pair at each transition (docs/fem-rod.md §3).
    fn separate_transition_slopes(&self) -> bool {
        self.theory() == Theory::String
    }

    /// ∂σS > 0 at the admissibility points and the strain rule's points.
    fn admissible(&self, el: &ElementContext, q: &[f64; NDOF]) -> bool {
        let q = el.effective(q);
        ADMISSIBILITY_POINTS.iter().chain(self.rules().strain.points().iter().map(|p| &p.0)).all(|&xi| el.fields(&q, xi).ds > 0.0)
    }

    fn energy(&self, el: &ElementContext, q: &[f64; NDOF]) -> f64 {
        Kernel::energy(self, el, q)
    }

    fn gradient(&self, el: &ElementContext, q: &[f64; NDOF]) -> (f64, [f64; NDOF]) {
        Kernel::gradient(self, el, q)
    }

    fn derivatives(&self, el: &ElementContext, q: &[f64; NDOF]) -> ElementDerivatives {
        Kernel::derivatives(self, el, q)
    }
}

/// The discrete problem: mesh, numbering, element kernel; the parameters that the
/// homotopy changes (weight, belt length) are arguments of every evaluation. Generic over
/// the element's unknown count N and kernel K; the default is the registered
/// formulations' string layout (N = 8, `dyn Kernel`).
pub struct Assembler<const N: usize = NDOF, K: ElementKernel<N> + ?Sized = dyn Kernel> {
    mesh: Mesh,
    dofs: DofMap<N>,
    kernel: Arc<K>,
    rows: Vec<usize>,
    cols: Vec<usize>,
    diagonal: Vec<usize>,
    /// Per element: augmented map at start / end node (docs/fem-rod.md §3).
    augmented: Vec<[bool; 2]>,
}

// by hand: the kernel is shared (`Arc`), so no `K: Clone` bound as `derive` would add
impl<const N: usize, K: ElementKernel<N> + ?Sized> Clone for Assembler<N, K> {
    fn clone(&self) -> Self {
        Assembler { mesh: self.mesh.clone(), dofs: self.dofs.clone(), kernel: Arc::clone(&self.kernel), rows: self.rows.clone(), cols: self.cols.clone(), diagonal: self.diagonal.clone(), augmented: self.augmented.clone() }
    }
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
        Assembler::with_kernel(mesh, kernel)
    }
}

impl<const N: usize, K: ElementKernel<N> + ?Sized> Assembler<N, K> {
    /// The problem on `mesh` with the element kernel `kernel` (its layout fixes the
    /// numbering).
    pub fn with_kernel(mesh: Mesh, kernel: Arc<K>) -> Assembler<N, K> {
        let separate = kernel.separate_transition_slopes();
        let dofs = DofMap::with_layout(&mesh, kernel.layout(), separate);
        let augmented = crate::dofs::augmented_flags(&mesh, separate);
        let mut rows = Vec::with_capacity(mesh.len() * N * N);
        let mut cols = Vec::with_capacity(mesh.len() * N * N);
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
    pub fn dofs(&self) -> &DofMap<N> {
        &self.dofs
    }

    /// The formulation.
    pub fn kernel(&self) -> &Arc<K> {
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

    /// True if every unknown is finite and every element's state is admissible
    /// ([`ElementKernel::admissible`]: ∂σS > 0 at the admissibility points and the strain
    /// rule's points for a formulation).
    pub fn admissible(&self, z: &[f64], params: &TermParams, length: f64) -> bool {
        if !z.iter().all(|v| v.is_finite()) {
            return false;
        }
        (0..self.mesh.len()).into_par_iter().all(|e| self.kernel.admissible(&self.context(e, params), &self.dofs.gather(e, z, length)))
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
        let per: Vec<(f64, [f64; N])> = (0..self.mesh.len())
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
            if idx.iter().all(Option::is_some) {
                // every unknown free: the element's block is its whole Hessian, row-major
                for (gi, gv) in idx.iter().flatten().zip(&d.gradient) {
                    g[*gi] += gv;
                }
                values.extend_from_slice(d.hessian.as_flattened());
                continue;
            }
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
    pub fn element_derivatives(&self, z: &[f64], params: &TermParams, length: f64) -> Vec<ElementDerivatives<N>> {
        (0..self.mesh.len())
            .into_par_iter()
            .map(|e| self.kernel.derivatives(&self.context(e, params), &self.dofs.gather(e, z, length)))
            .collect()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    //! The assembler over another layout: a three-field {s, ν, θ} element (the
    //! [`crate::element::COSSERAT`] layout, 12 unknowns) assembled on the closed loop, its
    //! assembled gradient and Jacobian (the Hessian, from the triplets) against central
    //! finite differences of the assembled energy and gradient.
    use super::*;
    use crate::element::COSSERAT;
    use crate::formulation::{biot_density, PointFields, Rule, Scalar};
    use nalgebra::SVector;

    const NC: usize = COSSERAT.dofs();

    /// A test element with the Cosserat field set (not the Cosserat rod of the spec): Biot
    /// membrane energy of (s, ν), a rotation stiffness ½ EI (∂σθ)²/∂σS and a shear-like
    /// coupling ½ GA (θ − ∂σν)² ∂σS, by 3-point Gauss; derivatives by AD over all 12
    /// unknowns.
    struct ThreeField {
        ea: f64,
        ei: f64,
        ga: f64,
    }

    impl ThreeField {
        fn element_energy<D: Scalar>(&self, el: &ElementContext, q: &[D; NC]) -> D {
            let mut total = D::zero();
            for &(xi, wt) in Rule::Gauss(3).points() {
                let [s, ds, _] = el.field(COSSERAT, q, 0, xi);
                let [nu, dnu, d2nu] = el.field(COSSERAT, q, 1, xi);
                let [theta, dtheta, _] = el.field(COSSERAT, q, 2, xi);
                let p = PointFields { sigma: el.sigma(xi), s, ds, nu, dnu, d2nu };
                let shear = theta - dnu;
                let w = biot_density(el.stretch(&p), self.ea) * ds + dtheta * dtheta / ds * (0.5 * self.ei) + shear * shear * ds * (0.5 * self.ga);
                total += w * (wt * el.jacobian());
            }
            total
        }
    }

    impl ElementKernel<NC> for ThreeField {
        fn layout(&self) -> ElementLayout {
            COSSERAT
        }
        fn separate_transition_slopes(&self) -> bool {
            true
        }
        fn admissible(&self, el: &ElementContext, q: &[f64; NC]) -> bool {
            ADMISSIBILITY_POINTS.iter().all(|&xi| el.field(COSSERAT, q, 0, xi)[1] > 0.0)
        }
        fn energy(&self, el: &ElementContext, q: &[f64; NC]) -> f64 {
            self.element_energy(el, q)
        }
        fn gradient(&self, el: &ElementContext, q: &[f64; NC]) -> (f64, [f64; NC]) {
            let d = self.derivatives(el, q);
            (d.energy, d.gradient)
        }
        fn derivatives(&self, el: &ElementContext, q: &[f64; NC]) -> ElementDerivatives<NC> {
            let (e, g, h) = num_dual::hessian(|v| self.element_energy(el, &std::array::from_fn(|i| v[i])), &SVector::<f64, NC>::from_column_slice(q));
            ElementDerivatives { energy: e, gradient: std::array::from_fn(|i| g[i]), hessian: std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])) }
        }
    }

    /// Central differences with step 1e-6 on unknowns of size O(0.01–1): truncation
    /// h²|E'''|/6 ≲ 1e-12·1e4 and round-off ε|E|/h ≲ 1e-10·|E| stay below 1e-6 of the
    /// gradient and Hessian scales (EA = 1e4 N dominates) — tolerance 1e-6 relative to
    /// the largest entry.
    #[test]
    fn three_field_layout_assembles_with_a_consistent_jacobian() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let mesh = Mesh::new(contour, 10, 1.0).unwrap();
        let asm = Assembler::<NC, ThreeField>::with_kernel(mesh, Arc::new(ThreeField { ea: 1.0e4, ei: 2.0e-3, ga: 50.0 }));
        assert_eq!(asm.dofs().layout(), COSSERAT);
        assert_eq!(asm.len(), 6 * 10 - 1 + 12);
        // elements 0 and 9 touch node 0, whose s is fixed: 11 unknowns each
        assert_eq!(asm.pattern().0.len(), 8 * NC * NC + 2 * (NC - 1) * (NC - 1));
        // a stretched state with deflection and rotation waves of either sign
        let length = 1.03 * contour.length();
        let z = wave_state(&asm, length / contour.length());
        let params = TermParams { axial_stiffness: 1.0e4, weight: None, penalty: None, bending_stiffness: None };
        let jac = assert_consistent_jacobian(&asm, &z, &params, length);
        // θ couples into the assembled system: its unknowns have nonzero diagonal entries
        let theta_value = asm.dofs().node_unknowns(3).values[2].unwrap();
        assert!(jac[theta_value][theta_value] > 0.0);
    }

    /// The assembled energy, gradient and Jacobian (the Hessian, from the triplets) of
    /// `asm` at z against central differences of the assembled energy and gradient
    /// (step 1e-6, tolerance 1e-6 relative to the largest entry; the callers justify it
    /// for their element), and `gradient` against `assemble` to round-off. Returns the
    /// dense Jacobian.
    pub(crate) fn assert_consistent_jacobian<const N: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, z: &[f64], params: &TermParams, length: f64) -> Vec<Vec<f64>> {
        let a = asm.assemble(z, params, length).expect("admissible");
        let (e0, g0) = asm.gradient(z, params, length).unwrap();
        assert!((a.energy - e0).abs() <= 1e-12 * e0.abs());
        // the Jacobian of the residual G = ∂Π/∂z: sum the triplets
        let nz = asm.len();
        let mut jac = vec![vec![0.0; nz]; nz];
        let (rows, cols) = asm.pattern();
        for ((&r, &c), &v) in rows.iter().zip(cols).zip(&a.values) {
            jac[r][c] += v;
        }
        let gscale = a.gradient.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let jscale = jac.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let h = 1e-6;
        for i in 0..nz {
            let (mut zp, mut zm) = (z.to_vec(), z.to_vec());
            zp[i] += h;
            zm[i] -= h;
            let (ep, gp) = asm.gradient(&zp, params, length).unwrap();
            let (em, gm) = asm.gradient(&zm, params, length).unwrap();
            let fd = (ep - em) / (2.0 * h);
            assert!((fd - a.gradient[i]).abs() <= 1e-6 * gscale, "G[{i}]: {} vs FD {fd}", a.gradient[i]);
            assert!((g0[i] - a.gradient[i]).abs() <= 1e-12 * gscale);
            for j in 0..nz {
                let fdj = (gp[j] - gm[j]) / (2.0 * h);
                assert!((fdj - jac[j][i]).abs() <= 1e-6 * jscale, "J[{j}][{i}]: {} vs FD {fdj}", jac[j][i]);
            }
        }
        jac
    }

    /// A state of a three-field ({s, ν, θ}) assembler: uniform stretch `stretch` with
    /// deflection and rotation waves of either sign; the slopes of the element starting
    /// at a node are 1 % larger than those of the one ending there (the same unknown
    /// where the slopes are shared, which then takes the larger value).
    pub(crate) fn wave_state<const N: usize, K: ElementKernel<N> + ?Sized>(asm: &Assembler<N, K>, stretch: f64) -> Vec<f64> {
        let mut z = vec![0.0; asm.len()];
        for (k, &sigma) in asm.mesh().node_sigmas().iter().take(asm.mesh().len()).enumerate() {
            let n = asm.dofs().node_unknowns(k);
            let phase = 7.0 * sigma;
            let values = [sigma * stretch, 0.002 * phase.sin(), 0.05 * phase.cos()];
            let slopes = [stretch + 0.01 * phase.cos(), 0.014 * phase.cos(), -0.35 * phase.sin()];
            for f in 0..3 {
                if let Some(i) = n.values[f] {
                    z[i] = values[f];
                }
                z[n.slopes_in[f]] = slopes[f];
                z[n.slopes_out[f]] = slopes[f] * 1.01;
            }
        }
        z
    }
}
