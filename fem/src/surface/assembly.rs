//! Assembly over a [`SurfaceMesh`]: a [`SurfaceKernel`] gives energy densities per unit
//! reference area at integration points as functions of P point values (chosen
//! derivatives f, ∂σf, ∂ζf, ∂²σf, ∂σ∂ζf, ∂²ζf of the fields it uses,
//! [`PointVariable`]); [`SurfaceAssembler`] integrates them over the Bogner–Fox–Schmit
//! elements with each term's Gauss rule per direction and sums energy, gradient and
//! Hessian over the periodic mesh.
//!
//! Derivatives are exact: forward-mode AD (num-dual) of the density over the point
//! values its term reads ([`SurfaceKernel::term_variables`]: a dual number of as many
//! directions, zero derivatives by the others), then the chain rule through the BFS weights, which are linear in the element
//! unknowns q — ∂E/∂q = Σ_points w J Bᵀ ∂W/∂v, ∂²E/∂q² = Σ_points w J Bᵀ ∂²W/∂v² B with
//! B = ∂v/∂q the weight rows of [`BfsRectangle::derivative_weights`] — the per-point
//! path of the 1-D formulations (`formulation`, `PointHessian`). A map that is
//! nonlinear in q (the shell's augmented transition map, spec §4.4, docs/fem-shell.md
//! (S12)) is given by the kernel as products c q_i q_j added to point values
//! ([`QuadraticTerm`], [`SurfaceKernel::quadratic_terms`]); the assembler then uses the
//! Jacobian J_m = B + ∂(Σ c q_i q_j)/∂q in place of B and adds the curvature term
//! Σ_p (∂W/∂v_p) ∇²v_p, as `pointwise_derivatives_rod` does in 1-D.
//! Elements are evaluated in parallel (rayon) and summed in element order, so results
//! do not depend on the thread count. The Hessian's triplet pattern is fixed by the
//! numbering; duplicates are summed by the sparse LU.

use num_dual::{gradient, hessian, Dual2SVec64, DualSVec64};
use nalgebra::SVector;
use rayon::prelude::*;

use crate::assembly::Assembled;
use crate::element::{BfsRectangle, ElementLayout, Field, SurfaceElement};
use crate::quadrature::Rule;
use crate::Scalar;

pub use super::dofs::PointDerivative;
use super::dofs::{EdgeConstraint, NodeConstraint, SurfaceDofMap, PER_FIELD};
use super::history::SurfaceHistory;
use super::mesh::SurfaceMesh;
use super::SurfaceError;

/// One value a kernel's density reads at a point: a derivative of a field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PointVariable {
    /// The field.
    pub field: Field,
    /// Which derivative.
    pub derivative: PointDerivative,
}

/// One energy term of a kernel: its Gauss (or Simpson, trapezoidal) rule in σ and in ζ,
/// and the number of history values it keeps per integration point (0: none).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceTerm {
    /// Rule in σ (ξ) and in ζ (η).
    pub rule: [Rule; 2],
    /// History values per integration point.
    pub history: usize,
}

/// Two components of a term's state for a zone that cuts the elements
/// ([`SurfaceKernel::cut_history`]), both set by the core after every advance: the
/// `indicator` at every point ([`SurfaceKernel::zone`], > 0 in the zone: the
/// interlayer's gap), and the `share`. Between neighbouring distinct points of a row, one
/// inside and one outside, the core finds the zone's edge as the root of the indicator
/// of the finite element solution itself, evaluated along the row between the two
/// points (Brent); each point inside gets as its share the zone's part of its cell
/// ([`Rule::cell`]: the σ-interval its weight stands for) plus the zone's part of the
/// cell of a neighbour outside it (whose own value is not the zone's integrand: u = 0
/// out of contact), over its cell's length — so it may exceed 1 — and each point outside
/// 0. The shares times the cells' lengths add up to the zone's length, continuous as an
/// edge moves, where whole points count the zone to within a cell (first order in h); a
/// single share still jumps where an edge crosses a point (the length changes hands
/// between neighbours: an O(h²) change of the integral). With `entry`, the core also
/// sets at each point inside its distance along the row from the zone's upstream edge
/// (the edge the transport carries the material in through; the distance may wrap
/// around the loop), 0 outside, and the row's length where the whole row is inside:
/// how far the material at the point has travelled inside the zone, which a kernel
/// needs to tell material that has been inside for a whole step from material that
/// entered during it (the interlayer's contact of a point's foot, docs/fem-shell.md
/// §7 (b)): a distance from the committed edge, continuous as the edge moves, where an
/// interpolated indicator switches where it crosses a level. With a non-empty `record`,
/// the core also sets at each point inside the kernel's [`SurfaceKernel::edge_record`]
/// evaluated at that upstream edge (0 outside and where the whole row is inside): what
/// the material that entered during the step met at the edge (the interlayer: the
/// belt's position and material coordinate there, docs/fem-shell.md §7 (g)).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CutHistory {
    /// The indicator at the point (> 0 in the zone).
    pub indicator: usize,
    /// The share the core sets.
    pub share: usize,
    /// The distance from the zone's upstream edge the core sets, if any.
    pub entry: Option<usize>,
    /// The components the core sets to the kernel's record at the upstream edge (empty:
    /// none).
    pub record: std::ops::Range<usize>,
}

/// Where and when a density is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// σ, m.
    pub sigma: f64,
    /// ζ, m.
    pub zeta: f64,
    /// Element number.
    pub element: usize,
    /// Time at the end of the step being solved, s (prescribed loads and data).
    pub time: f64,
    /// The step Δt, s (rates of viscous terms; 0 in a static evaluation).
    pub dt: f64,
}

/// One product c · q_i · q_j (or, without j, a term c · q_i) added to a point value
/// (derivative `derivative` of `field`) of an element: the part of a kernel's point map
/// beyond the BFS interpolant, at most quadratic in the element unknowns. `i`, `j` name
/// a nodal unknown as (field, 4 · node + nodal derivative), node in BFS order, nodal
/// derivative in [`PointDerivative::NODAL`] order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticTerm {
    /// The field whose point value gets the product.
    pub field: Field,
    /// Which of its six derivative rows.
    pub derivative: PointDerivative,
    /// First factor's unknown.
    pub i: (Field, usize),
    /// Second factor's unknown; None for a term linear in q_i.
    pub j: Option<(Field, usize)>,
    /// c.
    pub coefficient: f64,
}

/// A 2-D element kernel: energy densities per unit reference area (dσ dζ) over P point
/// values, term by term; the terms' history (if any) and the belt speed that advects it.
/// The shell (issue 15) is one: P = its fields' derivatives, terms membrane (Simpson ×
/// Gauss 3), bending, gravity, interlayer (trapezoidal × Gauss 2, history u).
pub trait SurfaceKernel<const P: usize>: Send + Sync {
    /// The element layout (2-D; the fields the variables read must be in it).
    fn layout(&self) -> ElementLayout;
    /// The point values the densities read, in the order of the density's argument.
    fn variables(&self) -> [PointVariable; P];
    /// The terms (index = the `term` argument below).
    fn terms(&self) -> Vec<SurfaceTerm>;
    /// Energy per unit reference area of `term` at `at`, J/m², from the point values `v`
    /// and the term's history state at the point (the advected state of the last
    /// converged step; empty for a term without history).
    fn density<D: Scalar>(&self, term: usize, at: &SurfacePoint, v: &[D; P], state: &[f64]) -> D;
    /// The point values `term`'s density depends on: indices into its argument,
    /// ascending, no repeats. The assembler differentiates each term over these only — a
    /// dual number of that many directions instead of P, the cost of a second-order dual
    /// growing as its directions squared — and takes the derivatives by the others as
    /// zero, so a term must not read a value it does not list. Default: all P.
    fn term_variables(&self, term: usize) -> Vec<usize> {
        let _ = term;
        (0..P).collect()
    }
    /// W, ∂W/∂v and ∂²W/∂v² of `term` at a point by the kernel's own means (e.g. a chain
    /// rule through intermediate quantities), into `dw` and `ddw` at least for the
    /// term's variables ([`Self::term_variables`]); None: the assembler differentiates
    /// [`Self::density`] by forward AD, which a kernel's own Hessian must match to
    /// round-off. Default: None.
    #[allow(clippy::too_many_arguments)]
    fn point_hessian(&self, term: usize, at: &SurfacePoint, v: &[f64; P], state: &[f64], dw: &mut [f64; P], ddw: &mut [[f64; P]; P]) -> Option<f64> {
        let _ = (term, at, v, state, dw, ddw);
        None
    }
    /// Whether point values are admissible (e.g. ∂σS > 0). Default: always.
    fn admissible(&self, at: &SurfacePoint, v: &[f64; P]) -> bool {
        let _ = (at, v);
        true
    }
    /// The history state of `term` at a point before the first step. Default: zeros.
    fn initial(&self, term: usize, at: &SurfacePoint, state: &mut [f64]) {
        let _ = (term, at);
        state.fill(0.0);
    }
    /// The state of `term` after a converged step from the converged point values `v` and
    /// the advected state before the step, `previous`. Default: unchanged (pure transport).
    fn advance(&self, term: usize, at: &SurfacePoint, v: &[f64; P], previous: &[f64], next: &mut [f64]) {
        let _ = (term, at, v);
        next.copy_from_slice(previous);
    }
    /// The products added to the BFS point values of element `element` (rectangle `rect`)
    /// at the reference point (ξ, η), pushed onto `out`: a point map quadratic in the
    /// element unknowns (docs/fem-shell.md (S12)). Default: none (the plain BFS map).
    fn quadratic_terms(&self, element: usize, rect: &BfsRectangle, xi: f64, eta: f64, out: &mut Vec<QuadraticTerm>) {
        let _ = (element, rect, xi, eta, out);
    }
    /// The belt speed c(t) that transports the history along σ, m/s. Default 0.
    fn belt_speed(&self, time: f64) -> f64 {
        let _ = time;
        0.0
    }
    /// The components of `term`'s state that the advection keeps between the values of
    /// the two points bracketing the foot (a transported quantity carried from step to
    /// step by its own recursion, e.g. the interlayer's u; [`crate::surface::history`]).
    /// Default: none (plain cubic interpolation of every component).
    fn bounded_history(&self, term: usize) -> std::ops::Range<usize> {
        let _ = term;
        0..0
    }
    /// The component of `term`'s state that marks where its bounded components
    /// ([`Self::bounded_history`]) are a field: ≥ ½ where they are (the interlayer's
    /// contact flag), < ½ where they were released (u set to 0 out of contact — a jump,
    /// not the continuation of the field). A foot whose cubic stencil contains a
    /// released point interpolates the bounded components linearly between its two
    /// bracketing points ([`crate::surface::history`]). Default: none (every point
    /// counts).
    fn history_support(&self, term: usize) -> Option<usize> {
        let _ = term;
        None
    }
    /// Components of `term`'s state that are not advected: each point keeps its own
    /// value of the last commit (e.g. whether the point itself was in contact).
    fn fixed_history(&self, term: usize) -> std::ops::Range<usize> {
        let _ = term;
        0..0
    }
    /// The kept components ([`Self::fixed_history`]) of `term`'s state for an integrand
    /// cut inside the elements by a committed zone (the interlayer's contact), as
    /// [`CutHistory`]: the core sets each point's indicator ([`Self::zone`]) and share of
    /// the zone after every advance ([`crate::surface::history`]). Default: none.
    fn cut_history(&self, term: usize) -> Option<CutHistory> {
        let _ = term;
        None
    }
    /// The indicator of [`Self::cut_history`]'s zone (> 0 inside) at any point of an
    /// element from the point values `v` of the converged configuration: the core
    /// evaluates it at the term's points and between them, to find the zone's edges.
    /// Default: 0 (never called without a cut).
    fn zone(&self, term: usize, at: &SurfacePoint, v: &[f64; P]) -> f64 {
        let _ = (term, at, v);
        0.0
    }
    /// The values the core keeps at every point inside [`Self::cut_history`]'s zone from
    /// the zone's upstream edge ([`CutHistory::record`]), evaluated there from the point
    /// values `v` of the converged configuration into `out`. Default: nothing (never
    /// called without a record).
    fn edge_record(&self, term: usize, at: &SurfacePoint, v: &[f64; P], out: &mut [f64]) {
        let _ = (term, at, v, out);
    }
}

/// The evaluation state: time, step and the (advected) history the densities read.
#[derive(Debug, Clone, Copy)]
pub struct Evaluation<'a> {
    /// Time, s.
    pub time: f64,
    /// Step, s.
    pub dt: f64,
    /// History states (required if a term keeps history).
    pub history: Option<&'a SurfaceHistory>,
}

/// One integration point of a term on an element: its indices in the term's rule, its
/// place, the BFS weight rows and the quadrature weight × area Jacobian.
pub(crate) struct QuadraturePoint {
    pub(crate) a: usize,
    pub(crate) b: usize,
    /// Reference coordinates (ξ, η).
    pub(crate) xi: f64,
    pub(crate) eta: f64,
    pub(crate) at: SurfacePoint,
    pub(crate) weights: [[f64; PER_FIELD]; 6],
    pub(crate) scale: f64,
}

/// Element energy, local gradient and local Hessian (row-major).
type ElementHessian = (f64, Vec<f64>, Vec<f64>);

/// The products the kernel adds to the point values at one point, as
/// [`SurfaceAssembler::quadratic`] gives them.
type Products = Vec<(usize, usize, Option<usize>, f64)>;

/// A field given with its nodal derivatives: (σ, ζ) ↦ [f, ∂σf, ∂ζf, ∂σ∂ζf].
pub type NodalFunction<'a> = &'a dyn Fn(f64, f64) -> [f64; 4];

/// The discrete surface problem: mesh, numbering, kernel.
pub struct SurfaceAssembler<K, const P: usize> {
    mesh: SurfaceMesh,
    dofs: SurfaceDofMap,
    kernel: K,
    terms: Vec<SurfaceTerm>,
    /// Per point variable: (field slot, weight row).
    slots: [(usize, usize); P],
    /// Per term: the variables it is differentiated over ([`SurfaceKernel::term_variables`]
    /// padded to a dual dimension, [`padded`]).
    variables: Vec<Vec<usize>>,
    /// Per element: None for a plain BFS element, else per term and integration point
    /// (in the order of [`Self::points`]) the kernel's products ([`Self::quadratic`]) —
    /// they depend on the geometry only, so they are formed once.
    products: Vec<Option<Vec<Vec<Products>>>>,
    rows: Vec<usize>,
    cols: Vec<usize>,
}

impl<K: SurfaceKernel<P>, const P: usize> SurfaceAssembler<K, P> {
    /// The kernel on `mesh`, numbering the fields its variables read, with the edge
    /// constraints `fixed`.
    ///
    /// # Errors
    /// [`SurfaceError::BadKernel`] (layout not 2-D, a field it lacks, an invalid rule).
    pub fn new(mesh: SurfaceMesh, kernel: K, fixed: &[EdgeConstraint]) -> Result<Self, SurfaceError> {
        SurfaceAssembler::with_nodes(mesh, kernel, fixed, &[])
    }

    /// [`Self::new`] with the single-node constraints `nodes` besides the edge
    /// constraints `fixed` ([`SurfaceDofMap::with_nodes`]).
    ///
    /// # Errors
    /// As [`Self::new`]; a node constraint off the mesh.
    pub fn with_nodes(mesh: SurfaceMesh, kernel: K, fixed: &[EdgeConstraint], nodes: &[NodeConstraint]) -> Result<Self, SurfaceError> {
        let layout = kernel.layout();
        let variables = kernel.variables();
        let fields: Vec<Field> = variables.iter().map(|v| v.field).collect();
        let dofs = SurfaceDofMap::with_nodes(&mesh, layout, &fields, fixed, nodes)?;
        let terms = kernel.terms();
        if let Some(rule) = terms.iter().flat_map(|t| t.rule).find(|r| r.validate().is_err()) {
            return Err(SurfaceError::BadKernel { layout: format!("{:?}", layout.fields), reason: format!("rule {}", rule.name()) });
        }
        let slots = std::array::from_fn(|p| (dofs.slot(variables[p].field).expect("numbered above"), variables[p].derivative as usize));
        let mut listed = Vec::with_capacity(terms.len());
        for t in 0..terms.len() {
            let vars = kernel.term_variables(t);
            if vars.is_empty() || vars.windows(2).any(|w| w[0] >= w[1]) || vars.iter().any(|&p| p >= P) {
                return Err(SurfaceError::BadKernel { layout: format!("{:?}", layout.fields), reason: format!("variables of term {t}: {vars:?} (ascending indices below {P})") });
            }
            listed.push(padded::<P>(&vars));
        }
        let variables = listed;
        let (mut rows, mut cols) = (Vec::new(), Vec::new());
        for e in 0..mesh.len() {
            let active: Vec<usize> = dofs.element(e).iter().flatten().copied().collect();
            for &r in &active {
                rows.extend(std::iter::repeat_n(r, active.len()));
                cols.extend_from_slice(&active);
            }
        }
        let mut asm = SurfaceAssembler { mesh, dofs, kernel, terms, slots, variables, products: Vec::new(), rows, cols };
        asm.products = (0..asm.mesh.len())
            .map(|e| {
                let per: Vec<Vec<Products>> = (0..asm.terms.len()).map(|t| asm.points(e, t, 0.0, 0.0).map(|point| asm.quadratic(e, point.xi, point.eta)).collect()).collect();
                per.iter().flatten().any(|p| !p.is_empty()).then_some(per)
            })
            .collect();
        Ok(asm)
    }

    /// The mesh.
    pub fn mesh(&self) -> &SurfaceMesh {
        &self.mesh
    }

    /// The numbering.
    pub fn dofs(&self) -> &SurfaceDofMap {
        &self.dofs
    }

    /// The kernel.
    pub fn kernel(&self) -> &K {
        &self.kernel
    }

    /// The kernel's terms.
    pub fn terms(&self) -> &[SurfaceTerm] {
        &self.terms
    }

    /// Number of global unknowns (of [`SurfaceDofMap`]).
    pub fn unknowns(&self) -> usize {
        self.dofs.len()
    }

    /// (rows, cols) of the Hessian triplets, fixed by the numbering.
    pub fn pattern(&self) -> (&[usize], &[usize]) {
        (&self.rows, &self.cols)
    }

    /// The numbered unknowns of σ-node `i` (every ζ-node, field and nodal derivative),
    /// ascending. The numbering runs node by node with σ outermost, so the Hessian is a
    /// band of half-width ≈ (the unknowns of a σ-node and of two ζ-nodes) except where
    /// the closed loop's last σ-element couples the last σ-node with σ-node 0: with
    /// σ-node 0's unknowns as the border the rest is that band
    /// ([`numerics::banded::BandStructure::with_border`]; docs/fem-shell.md §14).
    pub fn sigma_node_unknowns(&self, i: usize) -> Vec<usize> {
        let nf = self.dofs.fields().len();
        let mut out: Vec<usize> = (0..=self.mesh.zeta_elements())
            .flat_map(|j| {
                let node = self.mesh.node(i, j);
                (0..nf).flat_map(move |slot| PointDerivative::NODAL.into_iter().map(move |d| (node, slot, d)))
            })
            .filter_map(|(node, slot, d)| self.dofs.node_unknown(node, slot, d))
            .collect();
        out.sort_unstable();
        out
    }

    /// The σ-interval (m) that point `point` of `term`'s rule on element e stands for
    /// ([`Rule::cell`]; the history's cut cells, [`CutHistory`]) — outside
    /// [`Self::points`], which the element loops call every iteration.
    pub(crate) fn cell(&self, e: usize, term: usize, point: &QuadraturePoint) -> [f64; 2] {
        let el: BfsRectangle = self.mesh.element(e);
        self.terms[term].rule[0].cell(point.a).map(|x| el.point(x, point.eta)[0])
    }

    /// The integration points of `term` on element e at time `time`, step `dt`.
    pub(crate) fn points(&self, e: usize, term: usize, time: f64, dt: f64) -> impl Iterator<Item = QuadraturePoint> + '_ {
        let el: BfsRectangle = self.mesh.element(e);
        let [rs, rz] = self.terms[term].rule;
        let area = 0.25 * el.size[0] * el.size[1];
        rz.points().iter().enumerate().flat_map(move |(b, &(eta, wz))| {
            rs.points().iter().enumerate().map(move |(a, &(xi, ws))| {
                let [sigma, zeta] = el.point(xi, eta);
                QuadraturePoint { a, b, xi, eta, at: SurfacePoint { sigma, zeta, element: e, time, dt }, weights: el.derivative_weights(xi, eta), scale: ws * wz * area }
            })
        })
    }

    /// The products the kernel adds to element e's point values at (ξ, η), as
    /// (variable p, local i, local j, c) for the variables it reads (local index
    /// `16 · slot + k`; j None for a linear term); empty for a plain BFS element.
    pub(crate) fn quadratic(&self, e: usize, xi: f64, eta: f64) -> Vec<(usize, usize, Option<usize>, f64)> {
        let variables = self.kernel.variables();
        let mut out = Vec::new();
        for (t, i, j) in self.local_quadratic(e, xi, eta) {
            out.extend((0..P).filter(|&p| variables[p].field == t.field && variables[p].derivative == t.derivative).map(|p| (p, i, j, t.coefficient)));
        }
        out
    }

    /// The kernel's quadratic products at element e, (ξ, η) with their factors' local
    /// indices (products of unnumbered fields dropped).
    fn local_quadratic(&self, e: usize, xi: f64, eta: f64) -> Vec<(QuadraticTerm, usize, Option<usize>)> {
        let mut terms = Vec::new();
        self.kernel.quadratic_terms(e, &self.mesh.element(e), xi, eta, &mut terms);
        let local = |(field, k): (Field, usize)| self.dofs.slot(field).map(|s| s * PER_FIELD + k);
        terms
            .into_iter()
            .filter_map(|t| {
                let j = match t.j {
                    Some(j) => Some(local(j)?),
                    None => None,
                };
                Some((t, local(t.i)?, j))
            })
            .collect()
    }

    /// The P point values from the BFS weight rows, the element's local unknowns and the
    /// kernel's quadratic products ([`Self::quadratic`]) at the point.
    pub(crate) fn values(&self, weights: &[[f64; PER_FIELD]; 6], quadratic: &[(usize, usize, Option<usize>, f64)], q: &[f64]) -> [f64; P] {
        let mut v: [f64; P] = std::array::from_fn(|p| {
            let (slot, row) = self.slots[p];
            weights[row].iter().zip(&q[slot * PER_FIELD..(slot + 1) * PER_FIELD]).map(|(w, v)| w * v).sum()
        });
        for &(p, i, j, c) in quadratic {
            v[p] += c * q[i] * j.map_or(1.0, |j| q[j]);
        }
        v
    }

    /// The Jacobian rows ∂v_p/∂q (P × local length) at a point: the BFS rows plus the
    /// derivatives of the quadratic products.
    fn jacobian(&self, weights: &[[f64; PER_FIELD]; 6], quadratic: &[(usize, usize, Option<usize>, f64)], q: &[f64]) -> Vec<f64> {
        let n = q.len();
        let mut rows = vec![0.0; P * n];
        for (p, &(slot, row)) in self.slots.iter().enumerate() {
            rows[p * n + slot * PER_FIELD..p * n + (slot + 1) * PER_FIELD].copy_from_slice(&weights[row]);
        }
        for &(p, i, j, c) in quadratic {
            rows[p * n + i] += c * j.map_or(1.0, |j| q[j]);
            if let Some(j) = j {
                rows[p * n + j] += c * q[i];
            }
        }
        rows
    }

    /// W and ∂W/∂v (into `dw`; zero for the variables the term does not read) of term
    /// t at a point, by forward-mode AD over the term's variables.
    fn point_gradient(&self, t: usize, at: &SurfacePoint, v: &[f64; P], state: &[f64], dw: &mut [f64; P]) -> f64 {
        match self.variables[t].len() {
            4 => self.sub_gradient::<4>(t, at, v, state, dw),
            8 => self.sub_gradient::<8>(t, at, v, state, dw),
            13 => self.sub_gradient::<13>(t, at, v, state, dw),
            _ => self.sub_gradient::<P>(t, at, v, state, dw),
        }
    }

    /// [`Self::point_gradient`] with a dual number of N directions (N = the term's
    /// padded variable count).
    fn sub_gradient<const N: usize>(&self, t: usize, at: &SurfacePoint, v: &[f64; P], state: &[f64], dw: &mut [f64; P]) -> f64 {
        let vars = &self.variables[t];
        let x = SVector::<f64, N>::from_fn(|k, _| v[vars[k]]);
        let (w, g) = gradient(
            |x| {
                let mut all: [DualSVec64<N>; P] = std::array::from_fn(|p| DualSVec64::from_re(v[p]));
                vars.iter().enumerate().for_each(|(k, &p)| all[p] = x[k]);
                self.kernel.density(t, at, &all, state)
            },
            &x,
        );
        dw.fill(0.0);
        vars.iter().enumerate().for_each(|(k, &p)| dw[p] = g[k]);
        w
    }

    /// W, ∂W/∂v and ∂²W/∂v² (into `dw`, `ddw`; rows and columns of the variables the
    /// term does not read are left as they are — the caller reads the term's variables
    /// only, or zeroes them) of term t at a point: the kernel's own
    /// ([`SurfaceKernel::point_hessian`]) or forward-mode AD over the term's variables.
    fn point_hessian(&self, t: usize, at: &SurfacePoint, v: &[f64; P], state: &[f64], dw: &mut [f64; P], ddw: &mut [[f64; P]; P]) -> f64 {
        if let Some(w) = self.kernel.point_hessian(t, at, v, state, dw, ddw) {
            return w;
        }
        match self.variables[t].len() {
            4 => self.sub_hessian::<4>(t, at, v, state, dw, ddw),
            8 => self.sub_hessian::<8>(t, at, v, state, dw, ddw),
            13 => self.sub_hessian::<13>(t, at, v, state, dw, ddw),
            _ => self.sub_hessian::<P>(t, at, v, state, dw, ddw),
        }
    }

    /// [`Self::point_hessian`] with a second-order dual number of N directions.
    fn sub_hessian<const N: usize>(&self, t: usize, at: &SurfacePoint, v: &[f64; P], state: &[f64], dw: &mut [f64; P], ddw: &mut [[f64; P]; P]) -> f64 {
        let vars = &self.variables[t];
        let x = SVector::<f64, N>::from_fn(|k, _| v[vars[k]]);
        let (w, g, h) = hessian(
            |x| {
                let mut all: [Dual2SVec64<N>; P] = std::array::from_fn(|p| Dual2SVec64::from_re(v[p]));
                vars.iter().enumerate().for_each(|(k, &p)| all[p] = x[k]);
                self.kernel.density(t, at, &all, state)
            },
            &x,
        );
        for (k, &p) in vars.iter().enumerate() {
            dw[p] = g[k];
            for (l, &r) in vars.iter().enumerate() {
                ddw[p][r] = h[(k, l)];
            }
        }
        w
    }

    /// Every (term, point) of element e with its values and state: `visit` returns false
    /// to stop (an inadmissible point); false if stopped.
    /// The closure also gets the point's quadratic products ([`Self::quadratic`]).
    fn visit_points(&self, e: usize, q: &[f64], ev: &Evaluation, visit: impl FnMut(usize, &QuadraturePoint, &[f64; P], &[f64], &[(usize, usize, Option<usize>, f64)]) -> bool) -> bool {
        self.visit_term_points(e, q, ev, 0..self.terms.len(), visit)
    }

    /// [`Self::visit_points`] over the terms `terms` only.
    fn visit_term_points(&self, e: usize, q: &[f64], ev: &Evaluation, terms: std::ops::Range<usize>, mut visit: impl FnMut(usize, &QuadraturePoint, &[f64; P], &[f64], &[(usize, usize, Option<usize>, f64)]) -> bool) -> bool {
        for (t, term) in self.terms.iter().enumerate().take(terms.end).skip(terms.start) {
            for (k, point) in self.points(e, t, ev.time, ev.dt).enumerate() {
                let quadratic: &[_] = self.products[e].as_ref().map_or(&[], |per| &per[t][k]);
                let v = self.values(&point.weights, quadratic, q);
                if !self.kernel.admissible(&point.at, &v) {
                    return false;
                }
                let state = match (term.history, ev.history) {
                    (0, _) | (_, None) => &[][..],
                    (_, Some(h)) => h.state(t, e, point.a, point.b),
                };
                if !visit(t, &point, &v, state, quadratic) {
                    return false;
                }
            }
        }
        true
    }

    /// Element e's energy, J; `None` if a point is inadmissible.
    fn element_energy(&self, e: usize, z: &[f64], ev: &Evaluation) -> Option<f64> {
        let q = self.dofs.gather(e, z);
        let mut total = 0.0;
        self.visit_points(e, &q, ev, |t, point, v, state, _| {
            total += self.kernel.density(t, &point.at, v, state) * point.scale;
            true
        })
        .then_some(total)
    }

    /// Element e's energy and local gradient (order of [`SurfaceDofMap::element`]).
    fn element_gradient(&self, e: usize, z: &[f64], ev: &Evaluation) -> Option<(f64, Vec<f64>)> {
        let q = self.dofs.gather(e, z);
        let mut g = vec![0.0; q.len()];
        let mut total = 0.0;
        let mut dw = [0.0; P];
        self.visit_points(e, &q, ev, |t, point, v, state, quadratic| {
            let w = self.point_gradient(t, &point.at, v, state, &mut dw);
            total += w * point.scale;
            for &(p, i, j, c) in quadratic {
                let d = dw[p] * point.scale * c;
                g[i] += d * j.map_or(1.0, |j| q[j]);
                if let Some(j) = j {
                    g[j] += d * q[i];
                }
            }
            for &p in &self.variables[t] {
                let (slot, row) = self.slots[p];
                let d = dw[p] * point.scale;
                for (gk, wk) in g[slot * PER_FIELD..(slot + 1) * PER_FIELD].iter_mut().zip(&point.weights[row]) {
                    *gk += d * wk;
                }
            }
            true
        })
        .then_some((total, g))
    }

    /// Element e's energy, local gradient and local Hessian (row-major).
    fn element_hessian(&self, e: usize, z: &[f64], ev: &Evaluation) -> Option<ElementHessian> {
        let q = self.dofs.gather(e, z);
        let (n, nf) = (q.len(), self.dofs.fields().len());
        let mut g = vec![0.0; n];
        let mut h = vec![0.0; n * n];
        let mut total = 0.0;
        // per variable p and field slot s: Σ_{q of slot s} ∂²W/∂v_p∂v_q B_q (16 entries)
        let mut hb = vec![0.0; P * nf * PER_FIELD];
        let (mut dw, mut ddw) = ([0.0; P], [[0.0; P]; P]);
        self.visit_points(e, &q, ev, |t, point, v, state, quadratic| {
            let vars = &self.variables[t];
            let w = self.point_hessian(t, &point.at, v, state, &mut dw, &mut ddw);
            total += w * point.scale;
            if !quadratic.is_empty() {
                // the variables the term does not read: zero rows and columns
                if vars.len() < P {
                    let mut read = [false; P];
                    vars.iter().for_each(|&p| read[p] = true);
                    for p in (0..P).filter(|&p| !read[p]) {
                        dw[p] = 0.0;
                        ddw[p] = [0.0; P];
                        ddw.iter_mut().for_each(|row| row[p] = 0.0);
                    }
                }
                // the augmented map: dense J_m (P × n), H += Jᵀ W'' J + Σ_p W'_p ∇²v_p
                let jac = self.jacobian(&point.weights, quadratic, &q);
                let mut wj = vec![0.0; P * n];
                for p in 0..P {
                    let row = &jac[p * n..(p + 1) * n];
                    g.iter_mut().zip(row).for_each(|(gk, jk)| *gk += dw[p] * point.scale * jk);
                    for r in 0..P {
                        let c = ddw[r][p] * point.scale;
                        if c != 0.0 {
                            wj[r * n..(r + 1) * n].iter_mut().zip(row).for_each(|(o, jk)| *o += c * jk);
                        }
                    }
                }
                for r in 0..P {
                    for (i, &jri) in jac[r * n..(r + 1) * n].iter().enumerate().filter(|(_, v)| **v != 0.0) {
                        h[i * n..(i + 1) * n].iter_mut().zip(&wj[r * n..(r + 1) * n]).for_each(|(hij, b)| *hij += jri * b);
                    }
                }
                for &(p, i, j, c) in quadratic {
                    if let Some(j) = j {
                        let d = dw[p] * point.scale * c;
                        h[i * n + j] += d;
                        h[j * n + i] += d;
                    }
                }
                return true;
            }
            for &p in vars {
                hb[p * nf * PER_FIELD..(p + 1) * nf * PER_FIELD].fill(0.0);
                for &qv in vars {
                    let (slot, row) = self.slots[qv];
                    let c = ddw[p][qv] * point.scale;
                    let out = &mut hb[(p * nf + slot) * PER_FIELD..(p * nf + slot + 1) * PER_FIELD];
                    for (o, wk) in out.iter_mut().zip(&point.weights[row]) {
                        *o += c * wk;
                    }
                }
            }
            for &p in vars {
                let (slot, row) = self.slots[p];
                let d = dw[p] * point.scale;
                for (k, wk) in point.weights[row].iter().enumerate() {
                    let i = slot * PER_FIELD + k;
                    g[i] += d * wk;
                    if *wk == 0.0 {
                        continue;
                    }
                    for s in 0..nf {
                        let src = &hb[(p * nf + s) * PER_FIELD..(p * nf + s + 1) * PER_FIELD];
                        for (hij, b) in h[i * n + s * PER_FIELD..i * n + (s + 1) * PER_FIELD].iter_mut().zip(src) {
                            *hij += wk * b;
                        }
                    }
                }
            }
            true
        })
        .then_some((total, g, h))
    }

    /// ∬ f dσ dζ over the integration points of `term` (its rule): Σ over elements and
    /// points of the point's quadrature weight × area times f(point, values, state) —
    /// a resultant of a point-wise quantity of one term (the shell's lateral force per
    /// drum). `None` if a point is inadmissible or a sum is not finite.
    pub fn integrate<const N: usize>(&self, z: &[f64], ev: &Evaluation, term: usize, f: impl Fn(&SurfacePoint, &[f64; P], &[f64]) -> [f64; N] + Sync) -> Option<[f64; N]> {
        let per: Option<Vec<[f64; N]>> = (0..self.mesh.len())
            .into_par_iter()
            .map(|e| {
                let q = self.dofs.gather(e, z);
                let mut sum = [0.0; N];
                self.visit_term_points(e, &q, ev, term..term + 1, |_, point, v, state, _| {
                    sum.iter_mut().zip(f(&point.at, v, state)).for_each(|(s, x)| *s += x * point.scale);
                    true
                })
                .then_some(sum)
            })
            .collect();
        let total = per?.iter().fold([0.0; N], |mut t, s| {
            t.iter_mut().zip(s).for_each(|(a, b)| *a += b);
            t
        });
        total.iter().all(|x| x.is_finite()).then_some(total)
    }

    /// Π(z), J; `None` if a point is inadmissible or Π is not finite.
    pub fn energy(&self, z: &[f64], ev: &Evaluation) -> Option<f64> {
        let per: Option<Vec<f64>> = (0..self.mesh.len()).into_par_iter().map(|e| self.element_energy(e, z, ev)).collect();
        let total: f64 = per?.iter().sum();
        total.is_finite().then_some(total)
    }

    /// Π and ∂Π/∂z; `None` if a point is inadmissible or a value is not finite.
    pub fn gradient(&self, z: &[f64], ev: &Evaluation) -> Option<(f64, Vec<f64>)> {
        let per: Option<Vec<(f64, Vec<f64>)>> = (0..self.mesh.len()).into_par_iter().map(|e| self.element_gradient(e, z, ev)).collect();
        let mut g = vec![0.0; self.unknowns()];
        let mut total = 0.0;
        for (e, (en, ge)) in per?.iter().enumerate() {
            total += en;
            for (gi, v) in self.dofs.element(e).iter().zip(ge) {
                if let Some(gi) = gi {
                    g[*gi] += v;
                }
            }
        }
        (total.is_finite() && g.iter().all(|v| v.is_finite())).then_some((total, g))
    }

    /// Π, ∂Π/∂z and the Hessian values in the order of [`Self::pattern`]; `None` if a
    /// point is inadmissible or a value is not finite.
    pub fn assemble(&self, z: &[f64], ev: &Evaluation) -> Option<Assembled> {
        let per: Option<Vec<ElementHessian>> = (0..self.mesh.len()).into_par_iter().map(|e| self.element_hessian(e, z, ev)).collect();
        let mut g = vec![0.0; self.unknowns()];
        let mut values = Vec::with_capacity(self.rows.len());
        let mut energy = 0.0;
        for (e, (en, ge, he)) in per?.iter().enumerate() {
            energy += en;
            let idx = self.dofs.element(e);
            let active: Vec<usize> = (0..idx.len()).filter(|&i| idx[i].is_some()).collect();
            for &i in &active {
                g[idx[i].expect("active")] += ge[i];
                values.extend(active.iter().map(|&j| he[i * idx.len() + j]));
            }
        }
        let finite = energy.is_finite() && g.iter().all(|v| v.is_finite()) && values.iter().all(|v| v.is_finite());
        finite.then_some(Assembled { energy, gradient: g, values })
    }

    /// The six derivatives (f, ∂σ, ∂ζ, ∂²σ, ∂σ∂ζ, ∂²ζ) of `field` at (σ, ζ) from z, with
    /// the kernel's quadratic products (the augmented map); `None` if the field is not
    /// numbered.
    pub fn field_at(&self, z: &[f64], field: Field, sigma: f64, zeta: f64) -> Option<[f64; 6]> {
        let slot = self.dofs.slot(field)?;
        let (e, xi, eta) = self.mesh.locate(sigma, zeta);
        let q = self.dofs.gather(e, z);
        let w = self.mesh.element(e).derivative_weights(xi, eta);
        let local = &q[slot * PER_FIELD..(slot + 1) * PER_FIELD];
        let mut out: [f64; 6] = std::array::from_fn(|row| w[row].iter().zip(local).map(|(a, b)| a * b).sum());
        for (t, i, j) in self.local_quadratic(e, xi, eta).into_iter().filter(|(t, ..)| t.field == field) {
            out[t.derivative as usize] += t.coefficient * q[i] * j.map_or(1.0, |j| q[j]);
        }
        Some(out)
    }

    /// The nodal unknowns that interpolate a field given with its derivatives
    /// `f(σ, ζ) = [f, ∂σf, ∂ζf, ∂σ∂ζf]` (fields not listed and fixed unknowns left 0):
    /// the BFS interpolant, exact for bicubics.
    pub fn interpolate(&self, fields: &[(Field, NodalFunction)]) -> Vec<f64> {
        let mut z = vec![0.0; self.unknowns()];
        let (sigma, zeta) = (self.mesh.sigma_nodes(), self.mesh.zeta_nodes());
        for (i, &s) in sigma.iter().enumerate() {
            for (j, &zz) in zeta.iter().enumerate() {
                for (field, f) in fields {
                    let Some(slot) = self.dofs.slot(*field) else { continue };
                    let values = f(s, zz);
                    for (d, nodal) in PointDerivative::NODAL.into_iter().enumerate() {
                        if let Some(g) = self.dofs.node_unknown(self.mesh.node(i, j), slot, nodal) {
                            z[g] = values[d];
                        }
                    }
                }
            }
        }
        z
    }
}

/// The dual dimensions below P the assembler is compiled for (each one monomorphises
/// every kernel's density twice, first and second order): the shell's interlayer (4),
/// membrane (7) and bending (13) terms.
const DUAL_DIMENSIONS: [usize; 3] = [4, 8, 13];

/// A term's variables padded to the dual dimension it is differentiated with: to the
/// next of [`DUAL_DIMENSIONS`] by the first variables it does not list (their
/// derivatives come out as exact zeros), else all P.
fn padded<const P: usize>(listed: &[usize]) -> Vec<usize> {
    let size = DUAL_DIMENSIONS.into_iter().find(|&k| listed.len() <= k && k < P).unwrap_or(P);
    if size == P {
        return (0..P).collect();
    }
    let mut out = listed.to_vec();
    out.extend((0..P).filter(|p| !listed.contains(p)).take(size - listed.len()));
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    //! The assembler against central differences: a nonlinear two-field test kernel
    //! (not a shell) that reads every derivative row, with a history state, on a
    //! non-uniform periodic mesh with an edge constraint.
    use super::*;
    use crate::element::SHELL;
    use crate::surface::dofs::ZetaEdge;
    use crate::test_rng::Rng;

    const NU: [PointDerivative; 6] = [
        PointDerivative::Value,
        PointDerivative::DSigma,
        PointDerivative::DZeta,
        PointDerivative::DSigmaSigma,
        PointDerivative::DSigmaZeta,
        PointDerivative::DZetaZeta,
    ];

    /// W = ½(ν_σσ² + 2ν_σζ² + ν_ζζ²) + √(1 + ν_σ² + ν_ζ²) + 0.3 z_σ² ν + 0.1 z⁴ + 0.2 z_ζ ν_ζ
    /// + h (ν − 0.01)² (h the state of the second term, a history term).
    struct Nonlinear;

    impl SurfaceKernel<9> for Nonlinear {
        fn layout(&self) -> ElementLayout {
            SHELL
        }
        fn variables(&self) -> [PointVariable; 9] {
            let z = [PointDerivative::Value, PointDerivative::DSigma, PointDerivative::DZeta];
            std::array::from_fn(|p| if p < 6 { PointVariable { field: Field::Nu, derivative: NU[p] } } else { PointVariable { field: Field::Z, derivative: z[p - 6] } })
        }
        fn terms(&self) -> Vec<SurfaceTerm> {
            vec![SurfaceTerm { rule: [Rule::Gauss(3), Rule::Gauss(4)], history: 0 }, SurfaceTerm { rule: [Rule::Simpson, Rule::Gauss(2)], history: 1 }]
        }
        fn density<D: Scalar>(&self, term: usize, _at: &SurfacePoint, v: &[D; 9], state: &[f64]) -> D {
            if term == 1 {
                let d = v[0] - 0.01;
                return d * d * state[0];
            }
            let bend = (v[3] * v[3] + v[4] * v[4] * 2.0 + v[5] * v[5]) * 0.5;
            let stretch = (v[1] * v[1] + v[2] * v[2] + 1.0).sqrt();
            bend + stretch + v[7] * v[7] * v[0] * 0.3 + v[6].powi(4) * 0.1 + v[8] * v[2] * 0.2
        }
        fn initial(&self, _term: usize, at: &SurfacePoint, state: &mut [f64]) {
            state[0] = 2.0 + (7.0 * at.sigma).sin() * (1.0 + at.zeta);
        }
    }

    /// Central differences with step 1e-6 on unknowns of size ≲ 1: truncation
    /// h²|E'''| ~ 1e-12 and round-off ε|E|/h ~ 1e-10 relative to the entries' scale;
    /// tolerance 1e-6 of the largest entry. Gradient from the energy, Hessian (the
    /// Jacobian of the residual) from the gradient.
    #[test]
    fn gradient_and_hessian_match_central_differences() {
        let mesh = SurfaceMesh::new(1.3, vec![0.0, 0.2, 0.45, 0.6, 0.95], vec![-0.1, 0.02, 0.1]).unwrap();
        let fixed = [EdgeConstraint { edge: ZetaEdge::Lower, field: Field::Nu, nodal: PointDerivative::Value }];
        let asm = SurfaceAssembler::new(mesh, Nonlinear, &fixed).unwrap();
        let history = SurfaceHistory::new(&asm, 0.0).unwrap();
        let ev = Evaluation { time: 0.0, dt: 0.1, history: Some(&history) };
        let mut rng = Rng(5);
        let z: Vec<f64> = (0..asm.unknowns()).map(|_| 0.3 * (2.0 * rng.next() - 1.0)).collect();
        let a = asm.assemble(&z, &ev).unwrap();
        let (e, g) = asm.gradient(&z, &ev).unwrap();
        assert!((a.energy - e).abs() <= 1e-13 * e.abs() && (asm.energy(&z, &ev).unwrap() - e).abs() <= 1e-13 * e.abs());
        let n = asm.unknowns();
        let mut jac = vec![0.0; n * n];
        let (rows, cols) = asm.pattern();
        for ((&r, &c), &v) in rows.iter().zip(cols).zip(&a.values) {
            jac[r * n + c] += v;
        }
        let gscale = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let hscale = jac.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let step = 1e-6;
        for i in 0..n {
            let (mut zp, mut zm) = (z.clone(), z.clone());
            zp[i] += step;
            zm[i] -= step;
            let fd = (asm.energy(&zp, &ev).unwrap() - asm.energy(&zm, &ev).unwrap()) / (2.0 * step);
            assert!((fd - g[i]).abs() <= 1e-6 * gscale, "gradient[{i}]: {} vs FD {fd}", g[i]);
            assert!((g[i] - a.gradient[i]).abs() <= 1e-12 * gscale);
            let (gp, gm) = (asm.gradient(&zp, &ev).unwrap().1, asm.gradient(&zm, &ev).unwrap().1);
            for j in 0..n {
                let fd = (gp[j] - gm[j]) / (2.0 * step);
                assert!((fd - jac[j * n + i]).abs() <= 1e-6 * hscale, "hessian[{j}][{i}]: {} vs FD {fd}", jac[j * n + i]);
            }
        }
        // the history state enters: another state gives another energy
        let other = history.advected(0.3);
        assert!((asm.energy(&z, &Evaluation { history: Some(&other), ..ev }).unwrap() - e).abs() > 1e-6 * e.abs());
    }

    /// The interpolant of a bicubic (nodal data f, ∂σf, ∂ζf, ∂σ∂ζf) reproduces it and
    /// its second derivatives on every element that does not close the loop (the last
    /// σ-column joins σ = L to the data at σ = 0, where a non-periodic bicubic jumps);
    /// round-off of 16-term sums with weights up to 4/h² ≈ 10³: 1e-10.
    #[test]
    fn interpolation_reproduces_a_bicubic_away_from_the_closure() {
        let mesh = SurfaceMesh::new(1.3, vec![0.0, 0.2, 0.45, 0.6, 0.95], vec![-0.1, 0.02, 0.1]).unwrap();
        let asm = SurfaceAssembler::new(mesh, Nonlinear, &[]).unwrap();
        let p = |s: f64, z: f64| [1.0 + s * s * s - 2.0 * s * z * z + 3.0 * z * z * z * s * s, 3.0 * s * s - 2.0 * z * z + 6.0 * z * z * z * s, -4.0 * s * z + 9.0 * z * z * s * s, -4.0 * z + 18.0 * z * z * s];
        let q = |s: f64, z: f64| [z - s, -1.0, 1.0, 0.0];
        let z = asm.interpolate(&[(Field::Nu, &p), (Field::Z, &q)]);
        for (s, zeta) in [(0.1, -0.05), (0.5, 0.0), (0.9, 0.07)] {
            let nu = asm.field_at(&z, Field::Nu, s, zeta).unwrap();
            let [f, fs, fz, fsz] = p(s, zeta);
            let want = [f, fs, fz, 6.0 * s + 6.0 * zeta.powi(3), fsz, -4.0 * s + 18.0 * zeta * s * s];
            for (k, &w) in want.iter().enumerate() {
                assert!((nu[k] - w).abs() <= 1e-10, "({s}, {zeta}) derivative {k}: {} vs {w}", nu[k]);
            }
            let zf = asm.field_at(&z, Field::Z, s, zeta).unwrap();
            assert!((zf[0] - (zeta - s)).abs() <= 1e-12 && (zf[1] + 1.0).abs() <= 1e-12 && (zf[2] - 1.0).abs() <= 1e-12);
        }
        assert!(asm.field_at(&z, Field::S, 0.1, 0.0).is_none());
    }
}
