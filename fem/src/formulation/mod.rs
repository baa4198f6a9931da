//! Element formulations: the plug-in point of the crate (DESIGN.md "A new element
//! formulation plugs in by implementing one trait").
//!
//! A formulation implements [`Formulation`]: a name, a strain measure with its energy
//! density, and the integration rule of each energy term — or, if it needs more
//! freedom, its whole element energy. Everything else (assembly, Newton, homotopy, the
//! solution view, the harness) works through the object-safe [`Kernel`] that every
//! [`Formulation`] gets by a blanket implementation: values in f64, gradients and
//! Hessians by forward-mode AD (`num_dual::Dual2SVec64<8>`), exact.
//!
//! # Adding a formulation
//! From any crate (no fork of `fem`): a unit struct with `impl Formulation for MyElement`
//! written against the re-exports of this module ([`ElementContext`], [`TermParams`],
//! [`TermRules`], [`Rule`], [`Scalar`], [`Theory`], [`NDOF`], [`standard_terms`],
//! [`biot_density`]), then one call [`register`]`(MyElement)` at start-up. From then on
//! [`crate::solve_scene`] and the verification harness find it by name like a built-in
//! one. The workspace's `examples/custom_formulation.rs` does this end to end.
//!
//! ```
//! use fem::formulation::{self, biot_density, Formulation, Rule, Scalar, TermRules};
//!
//! /// A string with the strain energy integrated by the 2-point Gauss rule.
//! struct StringGauss2;
//!
//! impl Formulation for StringGauss2 {
//!     fn name(&self) -> &'static str { "string-gauss2-doc" }
//!     fn description(&self) -> &'static str { "string, Biot strain, 2-point Gauss membrane rule" }
//!     fn strain_measure(&self) -> &'static str { "Biot" }
//!     fn rules(&self) -> TermRules {
//!         TermRules { strain: Rule::Gauss(2), gravity: Rule::Gauss(3), contact: Rule::Gauss(3), bending: Rule::Gauss(3) }
//!     }
//!     fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
//!         biot_density(stretch, axial_stiffness)
//!     }
//! }
//!
//! formulation::register(StringGauss2).unwrap();
//! assert!(fem::available_formulations().contains(&"string-gauss2-doc"));
//! // a second registration of the name is refused, the first stays
//! assert!(matches!(formulation::register(StringGauss2), Err(formulation::RegistryError::Duplicate { .. })));
//! ```
//!
//! A formulation shipped with the crate instead gets a file in `fem/src/formulation/`
//! and one line in the built-in list (`built_in` below). The AD-vs-finite-difference
//! test and the consistency checks in this module's tests run over every built-in
//! formulation, so a new one is checked without writing a test.
//!
//! # Elements of another layout (the Cosserat rod's {s, ν, θ})
//! [`Formulation`] and [`Kernel`] are the string layout's face ({s, ν}, [`NDOF`] = 8
//! unknowns, [`PointFields`]); the registry itself holds [`RegisteredElement`]s, one
//! variant per 1-D layout of [`crate::element`]:
//! - [`RegisteredElement::String`]: a [`Formulation`] behind `Arc<dyn Kernel>` (strings
//!   and Kirchhoff rods; [`register`], [`register_kernel`]);
//! - [`RegisteredElement::Cosserat`]: an element on [`crate::element::COSSERAT`]
//!   (12 unknowns) that implements [`crate::assembly::ElementKernel`]`<12>` (energy,
//!   gradient, Hessian, admissibility, transition slopes) and
//!   [`layout::LayoutElement`]`<12>` (name, theory, rules, term labels, the axial force
//!   at a point, the effective unknowns, the start of θ), added with
//!   [`register_element`].
//!
//! [`find_element`] and [`elements`] see every entry (the CLI, [`crate::solve_scene`] and
//! the harness resolve names through them); [`find`] and [`registry`] return the string
//! layout's kernels only. [`crate::solve_problem`] matches the entry's layout and runs
//! the static analysis ([`crate::static_homotopy`]) and the solution view
//! ([`crate::FemSolution`]) monomorphised for it — both are generic over
//! `<const N, K: LayoutElement<N>>`, so the string path is compiled exactly as before.
//! The drive analyses (`string_drive`) take the string layout only and answer another
//! layout with [`crate::FemError::Unsupported`]. `fem/tests/layout_element.rs` registers
//! a 12-unknown test element by name and solves `rod-hanging` with it.

use std::sync::{Arc, LazyLock, PoisonError, RwLock, RwLockReadGuard};

use nalgebra::{Const, SVector, U1};
use num_dual::{gradient, hessian, Dual2SVec64, Dual2_64, Dual64, DualSVec64};

use crate::kinematics::{NU_DOFS, S_DOFS};

// The surface an element formulation is written against, in one place, so that a crate
// outside `fem` can `use fem::formulation::*`-style import what `impl Formulation` needs:
// the element context and its point fields, the term parameters, the unknowns per
// element, the scalar trait the energy is generic over (AD duals and f64), the
// integration rules, and the belt theory.
pub use crate::kinematics::{ElementContext, PointFields, TermParams, NDOF};
pub use crate::quadrature::{QuadratureError, Rule};
pub use numerics::Scalar;

mod built_in;
pub mod cosserat;
pub mod layout;
pub mod terms;

pub use built_in::{BuiltIn, ROD_GAUSS, ROD_SIMPSON, STRING_GAUSS, STRING_SIMPSON};
pub use layout::{RegisteredElement, NDOF_COSSERAT};
pub use drive::scene::Theory;
pub use terms::{augmented_traction, AugmentedPenalty, ContactMultipliers, Bending, EnergyTerm, Gravity, HistoryTerm, Integrated, PenaltyContact, PointDensity, PointJet, StandardTerms, Strain, TermHistory, TermVisitor, TransportInertia};
use terms::EnergySum;

/// The integration rule of each energy term (§7.3; docs/fem-string.md §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct TermRules {
    /// Strain energy U (F8).
    pub strain: Rule,
    /// Gravity potential W (F9).
    pub gravity: Rule,
    /// Penalty contact potential V_γ (F10).
    pub contact: Rule,
    /// Bending energy U_b (docs/fem-rod.md K7); used only where EI is given (rods).
    pub bending: Rule,
}

/// A string-layout element formulation (implement this to add one; see the module
/// docs; an element of another layout implements [`layout::LayoutElement`]).
pub trait Formulation: Send + Sync + 'static {
    /// Registry name, e.g. `string-gauss` (lowercase, `-` separated).
    fn name(&self) -> &'static str;

    /// One line for listings and reports.
    fn description(&self) -> &'static str;

    /// Name of the strain measure, e.g. `Biot`.
    fn strain_measure(&self) -> &'static str;

    /// The belt theory the formulation discretises (default: the string). A rod
    /// formulation ([`Theory::Kirchhoff`]) shares one slope pair at each transition and
    /// gets the augmented map (docs/fem-rod.md §3); the crate answers `Unsupported` when
    /// a scene's theory differs from the formulation's.
    fn theory(&self) -> Theory {
        Theory::String
    }

    /// The integration rule of each term.
    fn rules(&self) -> TermRules;

    /// Strain energy per unstretched length W(λ), J/m, as a function of the stretch λ
    /// and the axial stiffness EA. The axial force is N = dW/dλ (computed by AD).
    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D;

    /// The element energy (J) for local unknowns `q` (docs/fem-string.md F7–F10): by
    /// default the sum of the active terms of [`standard_terms`] with [`Self::rules`].
    /// Override only for a formulation that is not "strain density + rules".
    fn element_energy<D: Scalar>(&self, el: &ElementContext, q: &[D; NDOF]) -> D
    where
        Self: Sized,
    {
        let rules = self.rules();
        standard_terms(el, &el.effective(q), &rules, |lambda| {
            self.strain_energy_density(lambda, el.params.axial_stiffness)
        })
    }

    /// True (default) if [`Self::element_energy`] is the standard sum of point densities
    /// ([`standard_terms`]): the kernel then differentiates each point density with
    /// respect to the three point values (∂σS, ν, ∂σν) and applies the linear Hermite
    /// map exactly (about 10× cheaper than AD over all 8 unknowns, and the same
    /// numbers); a Kirchhoff rod's element (bending and the augmented map) takes each
    /// term's derivatives at a point by its own chain rule ([`PointJet`]), with AD only
    /// in λ for [`Self::strain_energy_density`]. A formulation that overrides
    /// `element_energy` must return false; its derivatives then come from AD over the
    /// whole element energy.
    fn pointwise(&self) -> bool {
        true
    }
}

/// The element energy Σ of the active terms (docs/fem-string.md §4): the units of
/// [`StandardTerms`] that `el.params` switches on — U (F8) with the density `w(λ)`
/// integrated per unstretched length (× ∂σS), W (F9) if `el.params.weight` is set, V_γ
/// (F10) if `el.params.penalty` is set, the bending energy (docs/fem-rod.md K7) if
/// `el.params.bending_stiffness` is set — each with its rule from `rules`. `q` are the
/// effective unknowns (after the augmented map).
pub fn standard_terms<D: Scalar>(
    el: &ElementContext,
    q: &[D; NDOF],
    rules: &TermRules,
    w: impl Fn(D) -> D,
) -> D {
    let mut sum = EnergySum::new(el, q);
    StandardTerms::new(&el.params, rules, w).visit(&mut sum);
    sum.total
}

/// Energy and gradient of a standard element summed over its terms and their points
/// with the density differentiated per point by `DualSVec64<V>` (first order) with
/// respect to the V point values, as [`PointHessian`] without the second derivatives:
/// the residual-only pass of a Newton line search.
struct PointGradient<'a, const V: usize> {
    el: &'a ElementContext,
    q: &'a [f64; NDOF],
    energy: f64,
    grad: [f64; NDOF],
}

/// The per-point loop both dual visitors share: at each point of the term's rule the
/// fields as duals in the V point values (∂σS, ν, ∂σν the variables 0, 1, 2; ∂²σν the
/// variable 3 when `curvature`, else a constant; σ and S constants), the density there,
/// and `add(ξ, w·J, density)`.
#[inline]
fn for_each_dual_point<D: Scalar, T: EnergyTerm<D>>(el: &ElementContext, q: &[f64; NDOF], term: &T, curvature: bool, var: impl Fn(f64, usize) -> D, mut add: impl FnMut(f64, f64, D)) {
    let jac = el.jacobian();
    for (k, &(xi, wt)) in term.rule().points().iter().enumerate() {
        let p = el.fields(q, xi);
        let d2nu = if curvature { var(p.d2nu, 3) } else { D::from(p.d2nu) };
        let pd = PointFields { sigma: p.sigma, s: D::from(p.s), ds: var(p.ds, 0), nu: var(p.nu, 1), dnu: var(p.dnu, 2), d2nu };
        add(xi, wt * jac, term.density(el, &pd, k));
    }
}

/// The two first-order visitors, V = 3 (∂²σν a constant) and V = 4 (a variable).
macro_rules! point_gradient {
    ($v:literal, curvature: $curvature:literal) => {
        impl TermVisitor<DualSVec64<$v>> for PointGradient<'_, $v> {
            #[inline]
            fn visit<T: EnergyTerm<DualSVec64<$v>>>(&mut self, term: &T) {
                let var = |v: f64, i: usize| DualSVec64::<$v>::from_re(v).derivative(i);
                for_each_dual_point(self.el, self.q, term, $curvature, var, |xi, scale, f| {
                    self.energy += scale * f.re;
                    let g = f.eps.unwrap_generic(Const::<$v>, U1);
                    let g: [f64; $v] = std::array::from_fn(|a| g[a]);
                    add_point_gradient(&point_map::<$v>(xi, self.el.geometry.h), &g, scale, &mut self.grad);
                });
            }
        }
    };
}

point_gradient!(3, curvature: false);
point_gradient!(4, curvature: true);

fn pointwise_gradient(el: &ElementContext, q: &[f64; NDOF], rules: &TermRules, w: impl Fn(DualSVec64<3>) -> DualSVec64<3>) -> (f64, [f64; NDOF]) {
    let mut v = PointGradient::<3> { el, q, energy: 0.0, grad: [0.0; NDOF] };
    StandardTerms::new(&el.params, rules, w).visit(&mut v);
    (v.energy, v.grad)
}

/// [`pointwise_derivatives_rod`] without the Hessian: g̃ per point by `DualSVec64<4>`
/// in the effective unknowns, then g = J_mᵀ g̃ — the same arithmetic as the gradient of
/// the Hessian path.
fn pointwise_gradient_rod(el: &ElementContext, q: &[f64; NDOF], rules: &TermRules, w: impl Fn(DualSVec64<4>) -> DualSVec64<4>) -> (f64, [f64; NDOF]) {
    let qe = el.effective(q);
    let mut v = PointGradient::<4> { el, q: &qe, energy: 0.0, grad: [0.0; NDOF] };
    StandardTerms::new(&el.params, rules, w).visit(&mut v);
    (v.energy, map_transpose_times(&map_jacobian(el, q), &v.grad))
}

/// The linear map B (V × 8) from an element's unknowns to the point values
/// u = (∂σS, ν, ∂σν[, ∂²σν]) at ξ: row 0 the ∂σS weights on the s unknowns, rows 1, 2
/// (and 3 for V = 4) the ν, ∂σν (, ∂²σν) weights on the ν unknowns.
#[inline]
fn point_map<const V: usize>(xi: f64, h: f64) -> [[f64; NDOF]; V] {
    let (wv, wd) = crate::hermite::weights(xi, h);
    let mut b = [[0.0; NDOF]; V];
    for (k, &i) in S_DOFS.iter().enumerate() {
        b[0][i] = wd[k];
    }
    for (k, &i) in NU_DOFS.iter().enumerate() {
        b[1][i] = wv[k];
        b[2][i] = wd[k];
    }
    if let Some(row) = b.get_mut(3) {
        let w2 = crate::hermite::second_weights(xi, h);
        for (k, &i) in NU_DOFS.iter().enumerate() {
            row[i] = w2[k];
        }
    }
    b
}

/// One integration point's share of an element's gradient and Hessian (docs/fem-string.md
/// §7): with the point's density derivatives g = ∂_u f, H = ∂²_u f and u = B q,
/// grad += s Bᵀ g and hess += s Bᵀ H B for the weight s = w · dσ/dξ.
#[inline]
#[allow(clippy::needless_range_loop)] // the V × 8 products read clearer with indices
fn add_point<const V: usize>(b: &[[f64; NDOF]; V], g: &[f64; V], h: &[[f64; V]; V], scale: f64, grad: &mut [f64; NDOF], hess: &mut [[f64; NDOF]; NDOF]) {
    add_point_gradient(b, g, scale, grad);
    // Bᵀ H, then (Bᵀ H) B
    let mut bth = [[0.0; V]; NDOF];
    for i in 0..NDOF {
        for a in 0..V {
            let bi = b[a][i];
            if bi != 0.0 {
                for c in 0..V {
                    bth[i][c] += bi * h[a][c];
                }
            }
        }
    }
    for (row, bt) in hess.iter_mut().zip(&bth) {
        for (j, hv) in row.iter_mut().enumerate() {
            let mut s = bt[0] * b[0][j];
            for a in 1..V {
                s += bt[a] * b[a][j];
            }
            *hv += scale * s;
        }
    }
}

/// The gradient share of [`add_point`]: grad += s Bᵀ g.
#[inline]
#[allow(clippy::needless_range_loop)] // the V × 8 product reads clearer with indices
fn add_point_gradient<const V: usize>(b: &[[f64; NDOF]; V], g: &[f64; V], scale: f64, grad: &mut [f64; NDOF]) {
    for i in 0..NDOF {
        for a in 0..V {
            let bi = b[a][i];
            if bi != 0.0 {
                grad[i] += scale * bi * g[a];
            }
        }
    }
}

/// Energy, gradient and Hessian of a standard element summed over its terms and their
/// points with the density differentiated per point by `Dual2SVec64<V>` with respect to
/// the V point values (V = 3: ∂σS, ν, ∂σν; V = 4: and ∂²σν), see [`add_point`].
struct PointHessian<'a, const V: usize> {
    el: &'a ElementContext,
    q: &'a [f64; NDOF],
    out: ElementDerivatives,
}

/// The two per-point visitors differ only in the dual type and whether ∂²σν is a
/// variable (V = 4) or a constant (V = 3).
macro_rules! point_hessian {
    ($v:literal, curvature: $curvature:literal) => {
        impl TermVisitor<Dual2SVec64<$v>> for PointHessian<'_, $v> {
            #[inline]
            fn visit<T: EnergyTerm<Dual2SVec64<$v>>>(&mut self, term: &T) {
                let var = |v: f64, i: usize| Dual2SVec64::<$v>::from_re(v).derivative(i);
                for_each_dual_point(self.el, self.q, term, $curvature, var, |xi, scale, f| {
                    let g = f.v1.unwrap_generic(U1, Const::<$v>);
                    let h = f.v2.unwrap_generic(Const::<$v>, Const::<$v>);
                    self.out.energy += scale * f.re;
                    let g: [f64; $v] = std::array::from_fn(|a| g[a]);
                    let h: [[f64; $v]; $v] = std::array::from_fn(|a| std::array::from_fn(|c| h[(a, c)]));
                    add_point(&point_map::<$v>(xi, self.el.geometry.h), &g, &h, scale, &mut self.out.gradient, &mut self.out.hessian);
                });
            }
        }
    };
}

point_hessian!(3, curvature: false);
#[cfg(test)]
point_hessian!(4, curvature: true);

/// Energy, gradient and Hessian of a standard element (docs/fem-string.md §7): at each
/// integration point the density is differentiated by `Dual2SVec64<3>` with respect to
/// u = (∂σS, ν, ∂σν), which depend linearly on q through the Hermite weights B
/// (u = B q, B 3 × 8); then g += w Bᵀ ∂_u f and K += w Bᵀ ∂²_u f B. Exact (the chain
/// rule through a linear map), and equal to AD over all 8 unknowns.
fn pointwise_derivatives(el: &ElementContext, q: &[f64; NDOF], rules: &TermRules, w: impl Fn(Dual2SVec64<3>) -> Dual2SVec64<3>) -> ElementDerivatives {
    let mut v = PointHessian::<3> { el, q, out: ElementDerivatives { energy: 0.0, gradient: [0.0; NDOF], hessian: [[0.0; NDOF]; NDOF] } };
    StandardTerms::new(&el.params, rules, w).visit(&mut v);
    v.out
}

/// True if the 3-variable per-point path applies: no bending term (it needs ∂²σν) and
/// no augmented map (nonlinear in q); otherwise the 4-variable path with the chain rule
/// through the map ([`pointwise_derivatives_rod`]) is used.
fn plain(el: &ElementContext) -> bool {
    el.params.bending_stiffness.is_none() && !el.augmented.iter().any(|&a| a)
}

/// Energy, gradient and Hessian of a standard element with the bending term and/or the
/// augmented map (docs/fem-rod.md §3, §4): the effective unknowns q̃ = m(q) (K9); at each
/// distinct integration point of the active terms' rules the terms' densities, value,
/// gradient and Hessian over u = (∂σS, ν, ∂σν, ∂²σν) = B q̃ (B: 4 × 8 Hermite weights),
/// each unit by its own chain rule ([`PointJet`]: AD only in λ for W(λ) and in ν for
/// the contour's functions), are summed with their rule weights into one jet; each jet
/// is projected once, g̃ += Bᵀ g and K̃ += Bᵀ H B by the blocks of B (∂σS reads the s
/// unknowns, ν, ∂σν, ∂²σν the ν unknowns: [`add_jet`]); then the chain rule through the
/// map, exactly: g = J_mᵀ g̃, K = J_mᵀ K̃ J_m + Σᵢ g̃ᵢ ∇²mᵢ ([`through_map`], only
/// where a node is flagged). The map changes only the slopes of a flagged
/// node (offset o = 0 or 4): m_{o+1} = q_{o+1} f, m_{o+3} = q_{o+3} f with
/// f = 1 + α q_{o+2}, so J_m differs from the identity in the rows o+1, o+3 and each
/// ∇²mᵢ has the two entries α at (o+1|o+3, o+2). Equal to AD over the whole element and
/// to the per-point `Dual2SVec64<4>` AD it replaces (tested), at about a fifth of the
/// latter's instructions (docs/performance.md, "The static rod's assembly").
fn pointwise_derivatives_rod(el: &ElementContext, q: &[f64; NDOF], rules: &TermRules, w: impl Fn(Dual2_64) -> Dual2_64) -> ElementDerivatives {
    let qe = el.effective(q);
    let terms = StandardTerms::new(&el.params, rules, w);
    let active = [Some(terms.strain.rule), terms.gravity.map(|t| t.rule), terms.contact.map(|t| t.rule), terms.bending.map(|t| t.rule)];
    // the distinct points of the active terms' rules (ξ compared exactly: Simpson's and
    // Gauss's midpoints coincide; at most 4 terms × 5 points, Gauss(5) the largest rule)
    let mut xis = [0.0; 20];
    let mut len = 0;
    for &(xi, _) in active.iter().flatten().flat_map(|r| r.points()) {
        if !xis[..len].contains(&xi) {
            xis[len] = xi;
            len += 1;
        }
    }
    let jac = el.jacobian();
    // the weight × dσ/dξ of `rule` at ξ, if ξ is one of its points
    let scale = |rule: Rule, xi: f64| rule.points().iter().find(|p| p.0 == xi).map(|p| p.1 * jac);
    let mut out = ElementDerivatives { energy: 0.0, gradient: [0.0; NDOF], hessian: [[0.0; NDOF]; NDOF] };
    for &xi in &xis[..len] {
        let p = el.fields(&qe, xi);
        let mut jet = PointJet::default();
        if let Some(s) = scale(terms.strain.rule, xi) {
            terms.strain.effect.add_jet(el, &p, s, &mut jet);
        }
        if let Some((t, s)) = terms.gravity.and_then(|t| Some((t, scale(t.rule, xi)?))) {
            t.effect.add_jet(el, &p, s, &mut jet);
        }
        if let Some((t, s)) = terms.contact.and_then(|t| Some((t, scale(t.rule, xi)?))) {
            t.effect.add_jet(el, &p, s, &mut jet);
        }
        if let Some((t, s)) = terms.bending.and_then(|t| Some((t, scale(t.rule, xi)?))) {
            t.effect.add_jet(el, &p, s, &mut jet);
        }
        out.energy += jet.value;
        add_jet(xi, el.geometry.h, &jet, &mut out.gradient, &mut out.hessian);
    }
    if el.augmented.iter().any(|&a| a) {
        out = through_map(el, q, out);
    }
    out
}

/// One point's jet ([`PointJet`], weights included) into an element's gradient and
/// Hessian in the effective unknowns (docs/fem-string.md §7): with u = B q̃ — ∂σS = w_dᵀ
/// q̃_s, (ν, ∂σν, ∂²σν) = (w_v, w_d, w₂)ᵀ q̃_ν — g̃ += Bᵀ g and K̃ += Bᵀ H B by blocks:
/// K̃_ss += H₀₀ w_d w_dᵀ, K̃_sν += w_d mᵀ with m = Σ_b H₀b c_b, K̃_νν += Cᵀ H_νν C
/// (C: the 3 × 4 weights c of ν, ∂σν, ∂²σν).
#[inline]
#[allow(clippy::needless_range_loop)] // the 4 × 4 blocks read clearer with indices
fn add_jet(xi: f64, h: f64, jet: &PointJet, grad: &mut [f64; NDOF], hess: &mut [[f64; NDOF]; NDOF]) {
    let (wv, wd) = crate::hermite::weights(xi, h);
    let w2 = crate::hermite::second_weights(xi, h);
    let (g, hh) = (&jet.gradient, &jet.hessian);
    // per ν unknown l: its weights c_l = (w_v, w_d, w₂) and H_νν c_l, H_0ν · c_l
    let c: [[f64; 3]; 4] = std::array::from_fn(|l| [wv[l], wd[l], w2[l]]);
    let mut hc = [[0.0; 3]; 4];
    let mut m = [0.0; 4];
    for l in 0..4 {
        for a in 0..3 {
            hc[l][a] = hh[a + 1][1] * c[l][0] + hh[a + 1][2] * c[l][1] + hh[a + 1][3] * c[l][2];
        }
        m[l] = hh[0][1] * c[l][0] + hh[0][2] * c[l][1] + hh[0][3] * c[l][2];
    }
    for k in 0..4 {
        let (si, ni) = (S_DOFS[k], NU_DOFS[k]);
        grad[si] += g[0] * wd[k];
        grad[ni] += g[1] * c[k][0] + g[2] * c[k][1] + g[3] * c[k][2];
        let h00 = hh[0][0] * wd[k];
        for l in 0..4 {
            let (sj, nj) = (S_DOFS[l], NU_DOFS[l]);
            hess[si][sj] += h00 * wd[l];
            let sn = wd[k] * m[l];
            hess[si][nj] += sn;
            hess[nj][si] += sn;
            hess[ni][nj] += c[k][0] * hc[l][0] + c[k][1] * hc[l][1] + c[k][2] * hc[l][2];
        }
    }
}

/// The chain rule through the augmented map (K9) of an element with a flagged node
/// ([`pointwise_derivatives_rod`]): from the derivatives `d` in the effective unknowns
/// to those in q, g = J_mᵀ g̃, K = J_mᵀ K̃ J_m + Σᵢ g̃ᵢ ∇²mᵢ.
#[allow(clippy::needless_range_loop)] // dense 8 × 8 matrix products read clearer with indices
fn through_map(el: &ElementContext, q: &[f64; NDOF], d: ElementDerivatives) -> ElementDerivatives {
    let ElementDerivatives { energy, gradient: ge, hessian: he } = d;
    let alpha = el.alpha();
    let jm = map_jacobian(el, q);
    let mut out = ElementDerivatives { energy, gradient: map_transpose_times(&jm, &ge), hessian: [[0.0; NDOF]; NDOF] };
    // Jᵀ K̃ J
    let mut kj = [[0.0; NDOF]; NDOF];
    for a in 0..NDOF {
        for j in 0..NDOF {
            kj[a][j] = (0..NDOF).map(|b| he[a][b] * jm[b][j]).sum();
        }
    }
    for i in 0..NDOF {
        for j in 0..NDOF {
            out.hessian[i][j] = (0..NDOF).map(|a| jm[a][i] * kj[a][j]).sum();
        }
    }
    // Σᵢ g̃ᵢ ∇²mᵢ: α g̃ₖ at (k, ν of the node) for the node's slopes k, symmetric
    for (flag, end) in el.augmented.iter().zip([0usize, 2]) {
        if *flag {
            for k in [S_DOFS[end + 1], NU_DOFS[end + 1]] {
                let v = ge[k] * alpha;
                out.hessian[k][NU_DOFS[end]] += v;
                out.hessian[NU_DOFS[end]][k] += v;
            }
        }
    }
    out
}

/// [`pointwise_derivatives_rod`] with each point's density differentiated by
/// `Dual2SVec64<4>` AD over all four point values instead of the units' chain rules —
/// the path the rod's derivatives took before (kept as the tests' oracle): the effective
/// unknowns q̃ = m(q) (K9); at each
/// integration point the density is differentiated by `Dual2SVec64<4>` with respect to
/// u = (∂σS, ν, ∂σν, ∂²σν) = B q̃ (B: 4 × 8 Hermite weights), summed to g̃ = ∂E/∂q̃ and
/// K̃ = ∂²E/∂q̃²; then the chain rule through the map, exactly:
/// g = J_mᵀ g̃, K = J_mᵀ K̃ J_m + Σᵢ g̃ᵢ ∇²mᵢ. The map changes only the slopes of a flagged
/// node (offset o = 0 or 4): m_{o+1} = q_{o+1} f, m_{o+3} = q_{o+3} f with
/// f = 1 + α q_{o+2}, so J_m differs from the identity in the rows o+1, o+3 and each
/// ∇²mᵢ has the two entries α at (o+1|o+3, o+2). Equal to AD over the whole element
/// (tested), about an order of magnitude cheaper.
#[cfg(test)]
fn pointwise_derivatives_rod_ad(el: &ElementContext, q: &[f64; NDOF], rules: &TermRules, w: impl Fn(Dual2SVec64<4>) -> Dual2SVec64<4>) -> ElementDerivatives {
    let qe = el.effective(q);
    let mut v = PointHessian::<4> { el, q: &qe, out: ElementDerivatives { energy: 0.0, gradient: [0.0; NDOF], hessian: [[0.0; NDOF]; NDOF] } };
    StandardTerms::new(&el.params, rules, w).visit(&mut v);
    // the chain rule through the augmented map (K9), shared with the fast path (the
    // identity without a flagged node); both are held to AD over the whole element
    through_map(el, q, v.out)
}

/// J_m = ∂m/∂q of the augmented map (K9) ([`pointwise_derivatives_rod`]): the identity
/// but for the rows o+1, o+3 of a flagged node, (1 + α q_{o+2}) on the diagonal and
/// α q_k in the column o+2.
fn map_jacobian(el: &ElementContext, q: &[f64; NDOF]) -> [[f64; NDOF]; NDOF] {
    let alpha = el.alpha();
    let mut jm = [[0.0; NDOF]; NDOF];
    for (i, row) in jm.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for (flag, end) in el.augmented.iter().zip([0usize, 2]) {
        if *flag {
            let nu = NU_DOFS[end];
            let fac = 1.0 + alpha * q[nu];
            for k in [S_DOFS[end + 1], NU_DOFS[end + 1]] {
                jm[k][k] = fac;
                jm[k][nu] = alpha * q[k];
            }
        }
    }
    jm
}

/// J_mᵀ g̃: the gradient in q from the one in the effective unknowns.
fn map_transpose_times(jm: &[[f64; NDOF]; NDOF], ge: &[f64; NDOF]) -> [f64; NDOF] {
    std::array::from_fn(|j| (0..NDOF).map(|k| jm[k][j] * ge[k]).sum())
}

/// The labels of the centreline terms every formulation shares, in assembly order:
/// gravity (if `params.weight`) and penalty contact (if `params.penalty`), with their
/// integration rules.
pub(crate) fn centreline_term_labels(params: &TermParams, gravity: Rule, contact: Rule) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(w) = params.weight {
        out.push(format!("gravity potential ({}, ρg = {:.6e} N/m)", gravity, w));
    }
    if let Some(p) = params.penalty {
        out.push(format!("penalty normal contact ({}, P = {:.6e} N/m²)", contact, p));
    }
    out
}

/// The Biot strain energy density ½ EA (λ − 1)², J/m (eq. 17; N = EA(λ − 1), (S1)).
pub fn biot_density<D: Scalar>(stretch: D, axial_stiffness: f64) -> D {
    let e = stretch - 1.0;
    e * e * (0.5 * axial_stiffness)
}

/// Result of an element evaluation with derivatives, for N local unknowns (8: the
/// string layout of every formulation).
#[derive(Debug, Clone, Copy)]
pub struct ElementDerivatives<const N: usize = NDOF> {
    /// Energy, J.
    pub energy: f64,
    /// ∂E/∂q.
    pub gradient: [f64; N],
    /// ∂²E/∂q², row-major.
    pub hessian: [[f64; N]; N],
}

/// The object-safe face of a [`Formulation`], used by assembly, solvers and the view.
/// Implemented for every [`Formulation`]; do not implement it directly.
pub trait Kernel: Send + Sync {
    /// See [`Formulation::name`].
    fn name(&self) -> &'static str;
    /// See [`Formulation::description`].
    fn description(&self) -> &'static str;
    /// See [`Formulation::strain_measure`].
    fn strain_measure(&self) -> &'static str;
    /// See [`Formulation::rules`].
    fn rules(&self) -> TermRules;
    /// See [`Formulation::theory`].
    fn theory(&self) -> Theory;
    /// Element energy in f64, J.
    fn energy(&self, el: &ElementContext, q: &[f64; NDOF]) -> f64;
    /// Energy and gradient (forward-mode AD, `DualSVec64<8>`).
    fn gradient(&self, el: &ElementContext, q: &[f64; NDOF]) -> (f64, [f64; NDOF]);
    /// Energy, gradient and Hessian (per point for a pointwise formulation — by AD in
    /// the point values for a string, by the terms' chain rules for a rod —, else by AD
    /// over the whole element).
    fn derivatives(&self, el: &ElementContext, q: &[f64; NDOF]) -> ElementDerivatives;
    /// Energy, gradient and Hessian by AD over the whole element energy
    /// (`Dual2SVec64<8>`): the reference the fast path is tested against.
    fn derivatives_full(&self, el: &ElementContext, q: &[f64; NDOF]) -> ElementDerivatives;
    /// Axial force N = dW/dλ, N (by a dual number from the energy density).
    fn axial_force(&self, stretch: f64, axial_stiffness: f64) -> f64;
    /// Labels of the terms assembled for `params`, e.g.
    /// `strain energy (Biot, gauss3)`.
    fn term_labels(&self, params: &TermParams) -> Vec<String>;
}

impl<F: Formulation> Kernel for F {
    fn name(&self) -> &'static str {
        Formulation::name(self)
    }

    fn description(&self) -> &'static str {
        Formulation::description(self)
    }

    fn strain_measure(&self) -> &'static str {
        Formulation::strain_measure(self)
    }

    fn rules(&self) -> TermRules {
        Formulation::rules(self)
    }

    fn theory(&self) -> Theory {
        Formulation::theory(self)
    }

    fn energy(&self, el: &ElementContext, q: &[f64; NDOF]) -> f64 {
        self.element_energy(el, q)
    }

    fn gradient(&self, el: &ElementContext, q: &[f64; NDOF]) -> (f64, [f64; NDOF]) {
        if self.pointwise() {
            let ea = el.params.axial_stiffness;
            if plain(el) {
                return pointwise_gradient(el, q, &Formulation::rules(self), |l| self.strain_energy_density(l, ea));
            }
            return pointwise_gradient_rod(el, q, &Formulation::rules(self), |l| self.strain_energy_density(l, ea));
        }
        let x = SVector::<f64, NDOF>::from_column_slice(q);
        let (e, g) = gradient(
            |v| {
                let a: [_; NDOF] = std::array::from_fn(|i| v[i]);
                self.element_energy(el, &a)
            },
            &x,
        );
        (e, std::array::from_fn(|i| g[i]))
    }

    fn derivatives(&self, el: &ElementContext, q: &[f64; NDOF]) -> ElementDerivatives {
        if self.pointwise() {
            let ea = el.params.axial_stiffness;
            if plain(el) {
                return pointwise_derivatives(el, q, &Formulation::rules(self), |l| self.strain_energy_density(l, ea));
            }
            return pointwise_derivatives_rod(el, q, &Formulation::rules(self), |l| self.strain_energy_density(l, ea));
        }
        self.derivatives_full(el, q)
    }

    fn derivatives_full(&self, el: &ElementContext, q: &[f64; NDOF]) -> ElementDerivatives {
        let x = SVector::<f64, NDOF>::from_column_slice(q);
        let (e, g, h) = hessian(
            |v| {
                let a: [_; NDOF] = std::array::from_fn(|i| v[i]);
                self.element_energy(el, &a)
            },
            &x,
        );
        ElementDerivatives {
            energy: e,
            gradient: std::array::from_fn(|i| g[i]),
            hessian: std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])),
        }
    }

    fn axial_force(&self, stretch: f64, axial_stiffness: f64) -> f64 {
        let l = Dual64::from_re(stretch).derivative();
        self.strain_energy_density(l, axial_stiffness).eps
    }

    fn term_labels(&self, params: &TermParams) -> Vec<String> {
        let r = Formulation::rules(self);
        let mut out = vec![format!(
            "strain energy ({}, {}, EA = {:.6e} N)",
            Formulation::strain_measure(self),
            r.strain,
            params.axial_stiffness
        )];
        out.extend(centreline_term_labels(params, r.gravity, r.contact));
        if let Some(ei) = params.bending_stiffness {
            out.push(format!("bending energy ({}, EI = {:.6e} N·m², C¹ augmented transitions)", r.bending, ei));
        }
        out
    }
}

/// The formulations shipped with the crate, default first. **Add a built-in formulation
/// here** (one line); an outside crate calls [`register`] instead.
fn built_in() -> Vec<RegisteredElement> {
    let kernels: [Arc<dyn Kernel>; 4] = [Arc::new(STRING_SIMPSON), Arc::new(STRING_GAUSS), Arc::new(ROD_SIMPSON), Arc::new(ROD_GAUSS)];
    // the Cosserat rod: Gauss 3 on the shear energy (the default of theory cosserat) and
    // the reduced Gauss 2 rule (shear locking, docs/fem-cosserat.md); b₂ from the scene
    let cosserat = [Rule::Gauss(3), Rule::Gauss(2)].map(|r| RegisteredElement::Cosserat(Arc::new(cosserat::CosseratElement::from_scene(r))));
    kernels.into_iter().map(RegisteredElement::String).chain(cosserat).collect()
}

/// The process-wide registry: the built-in formulations, then the registered elements in
/// registration order. Entries are only ever added, so a name once found stays valid.
static REGISTRY: LazyLock<RwLock<Vec<RegisteredElement>>> = LazyLock::new(|| RwLock::new(built_in()));

/// The registry for reading. No code panics while holding the lock, but a poisoned lock
/// still holds a consistent list (entries are pushed whole), so it is read anyway.
fn entries() -> RwLockReadGuard<'static, Vec<RegisteredElement>> {
    REGISTRY.read().unwrap_or_else(PoisonError::into_inner)
}

/// Every registered element of every layout: the built-in formulations (default first),
/// then those added by [`register`] and [`register_element`], in registration order. A
/// snapshot: later registrations do not change it.
pub fn elements() -> Vec<RegisteredElement> {
    entries().clone()
}

/// The registered element called `name`, whatever its layout.
pub fn find_element(name: &str) -> Option<RegisteredElement> {
    entries().iter().find(|k| k.name() == name).cloned()
}

/// The registered formulations of the string layout ({s, ν}: strings and Kirchhoff rods,
/// the entries [`RegisteredElement::String`] of [`elements`]), in registry order.
pub fn registry() -> Vec<Arc<dyn Kernel>> {
    entries().iter().filter_map(|k| k.string_kernel().cloned()).collect()
}

/// The registered formulation of the string layout called `name` (`None` also for an
/// element of another layout of that name: see [`find_element`]).
pub fn find(name: &str) -> Option<Arc<dyn Kernel>> {
    find_element(name).and_then(|k| k.string_kernel().cloned())
}

/// Why [`register`] refused a formulation.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RegistryError {
    /// The name is empty.
    #[error("a formulation needs a name (description: `{description}`)")]
    EmptyName {
        /// The formulation's description, to tell which one it was.
        description: &'static str,
    },
    /// The name is not lowercase ASCII letters, digits and `-` (the names are typed on
    /// the command line and in scene files, `fem.formulations`).
    #[error("formulation name `{name}`: use lowercase ASCII letters, digits and `-` only (offending character {offending:?})")]
    InvalidName {
        /// The name given.
        name: &'static str,
        /// The first character that is not allowed.
        offending: char,
    },
    /// A formulation of that name is already registered (built-in or outside).
    #[error("a formulation named `{name}` is already registered (registered: {registered:?})")]
    Duplicate {
        /// The name given.
        name: &'static str,
        /// The registered names at the time.
        registered: Vec<&'static str>,
    },
    /// One of the formulation's integration rules does not exist (e.g. `Gauss(9)`).
    #[error("formulation `{name}`: {term} rule: {source}")]
    InvalidRule {
        /// The formulation's name.
        name: &'static str,
        /// The term whose rule is invalid (`strain`, `gravity`, `contact`, `bending`).
        term: &'static str,
        /// The rule's own error.
        source: crate::quadrature::QuadratureError,
    },
}

/// Add a formulation to the process-wide registry, after the built-in ones: from then on
/// [`find`], [`registry`], [`crate::available_formulations`], [`crate::formulations_for`],
/// [`crate::solve_scene`] and the verification harness (`converge`, `report`, `gate`) see
/// it exactly like a built-in formulation. This is how a crate outside `fem` plugs in an
/// element formulation (see the crate docs and `examples/custom_formulation.rs` of the
/// workspace).
///
/// The registry is process-wide rather than a value passed to the harness because a
/// formulation is found by *name* everywhere — in scene files (`fem.formulations`), on
/// the command line, in reports and in `FemOptions` — and every one of those paths
/// already resolves names through this crate; one call at start-up then reaches all of
/// them without threading a registry argument through every study, gate and solve.
/// Registration only adds (there is no removal), so results of a name never change once
/// it is registered.
///
/// # Errors
/// [`RegistryError::EmptyName`], [`RegistryError::InvalidName`],
/// [`RegistryError::Duplicate`] (nothing is replaced: a built-in formulation cannot be
/// shadowed), [`RegistryError::InvalidRule`].
pub fn register<F: Formulation>(formulation: F) -> Result<(), RegistryError> {
    register_kernel(Arc::new(formulation))
}

/// [`register`] for a formulation already behind its object-safe face.
///
/// # Errors
/// As [`register`].
pub fn register_kernel(kernel: Arc<dyn Kernel>) -> Result<(), RegistryError> {
    register_element(RegisteredElement::String(kernel))
}

/// Register an element of any layout — e.g. an element on the Cosserat layout,
/// `register_element(RegisteredElement::Cosserat(Arc::new(MyRod)))` — with the checks and
/// the process-wide effect of [`register`]: from then on [`find_element`], [`elements`],
/// [`crate::available_formulations`], [`crate::formulations_for`] and
/// [`crate::solve_scene`] (the static analysis) find it by name.
///
/// # Errors
/// As [`register`].
pub fn register_element(element: RegisteredElement) -> Result<(), RegistryError> {
    let name = element.name();
    if name.is_empty() {
        return Err(RegistryError::EmptyName { description: element.description() });
    }
    if let Some(offending) = name.chars().find(|c| !(c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '-')) {
        return Err(RegistryError::InvalidName { name, offending });
    }
    let rules = element.rules();
    for (term, rule) in [("strain", rules.strain), ("gravity", rules.gravity), ("contact", rules.contact), ("bending", rules.bending)] {
        rule.validate().map_err(|source| RegistryError::InvalidRule { name, term, source })?;
    }
    let mut reg = REGISTRY.write().unwrap_or_else(PoisonError::into_inner);
    if reg.iter().any(|k| k.name() == name) {
        return Err(RegistryError::Duplicate { name, registered: reg.iter().map(|k| k.name()).collect() });
    }
    reg.push(element);
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Exact derivatives: AD gradient and Hessian against central finite differences of
    //! the f64 energy (gradient) and of the AD gradient (Hessian), for every registered
    //! formulation, at random states of each region with every term active and the
    //! contact term partly penetrated.
    use super::*;
    use crate::mesh::ElementGeometry;
    use drive::contour::{Contour, Region};

    use crate::test_rng::Rng;

    fn context(region: Region, sa: f64, h: f64) -> ElementContext {
        ElementContext {
            geometry: ElementGeometry { sigma_a: sa, h, region },
            contour: Contour::new(0.08, 0.45).unwrap(),
            params: TermParams { axial_stiffness: 2.0e4, weight: Some(0.12 * 9.81), penalty: Some(3.0e6), bending_stiffness: None },
            augmented: [false; 2],
        }
    }

    /// Elements in each region, the span ones reaching within R of a pulley centre. For a
    /// rod formulation (docs/fem-rod.md) the bending term is active (EI = 1e-3 N·m²) and
    /// the polar elements carry the augmented map (K9) at the start, the end and both
    /// nodes.
    fn elements_for(kernel: &dyn Kernel) -> Vec<ElementContext> {
        let mut els = vec![
            context(Region::UpperSpan, 0.40, 0.03),
            context(Region::DrivenArc, 0.50, 0.02),
            context(Region::LowerSpan, 0.70, 0.04),
            context(Region::LowerSpan, 1.10, 0.04),
            context(Region::DriverArc, 1.20, 0.03),
            context(Region::UpperSpan, 0.0, 0.03),
        ];
        if kernel.theory() == Theory::Kirchhoff {
            for el in &mut els {
                el.params.bending_stiffness = Some(1e-3);
            }
            els[1].augmented = [true, false];
            els[4].augmented = [false, true];
            let mut both = context(Region::DriverArc, 1.25, 0.03);
            both.params.bending_stiffness = Some(1e-3);
            both.augmented = [true, true];
            els.push(both);
        }
        els
    }


    /// A random admissible state: s' ≈ 1 ± 0.1, ν of either sign (so some points
    /// penetrate), slopes ±0.2.
    fn random_q(el: &ElementContext, rng: &mut Rng) -> [f64; NDOF] {
        let sa = el.geometry.sigma_a;
        let sb = sa + el.geometry.h;
        let mut c = || rng.next() - 0.5;
        [
            sa * 0.98 + 0.01 * c(),
            1.0 + 0.2 * c(),
            0.004 * c(),
            0.4 * c(),
            sb * 0.98 + 0.01 * c(),
            1.0 + 0.2 * c(),
            0.004 * c(),
            0.4 * c(),
        ]
    }

    /// Central differences with step 1e-7 (relative to the unknown's scale 1 or 0.1 m):
    /// truncation ≈ h²|E'''|/6 and round-off ≈ ε|E|/h; the element energies here are
    /// O(1e-2) J with third derivatives up to O(P·h_el) ≈ 1e5, so both are ≲ 1e-7 of
    /// the gradient scale — tolerance 1e-5 relative to max(1, |g|∞). The penalty term is
    /// only C¹ (its second derivative jumps where γ = 0); states whose FD stencil
    /// crosses γ = 0 are skipped for the Hessian (at most a few).
    #[test]
    fn ad_matches_finite_differences_for_every_formulation() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        for kernel in registry() {
            let mut hessian_checked = 0;
            for el in elements_for(kernel.as_ref()) {
                for _ in 0..20 {
                    let q = random_q(&el, &mut rng);
                    let d = kernel.derivatives(&el, &q);
                    let (e1, g1) = kernel.gradient(&el, &q);
                    let e0 = kernel.energy(&el, &q);
                    assert!((d.energy - e0).abs() <= 1e-12 * e0.abs().max(1e-12));
                    assert!((e1 - e0).abs() <= 1e-12 * e0.abs().max(1e-12));
                    let scale = d.gradient.iter().fold(1.0f64, |m, g| m.max(g.abs()));
                    let hstep = 1e-7;
                    let mut kink = false;
                    for i in 0..NDOF {
                        let (mut qp, mut qm) = (q, q);
                        qp[i] += hstep;
                        qm[i] -= hstep;
                        let fd = (kernel.energy(&el, &qp) - kernel.energy(&el, &qm)) / (2.0 * hstep);
                        assert!(
                            (fd - d.gradient[i]).abs() <= 1e-5 * scale,
                            "{} {:?} grad[{i}]: AD {} FD {fd}",
                            kernel.name(),
                            el.geometry.region,
                            d.gradient[i]
                        );
                        assert!((g1[i] - d.gradient[i]).abs() <= 1e-12 * scale);
                        // Hessian column i from the AD gradient
                        let gp = kernel.gradient(&el, &qp).1;
                        let gm = kernel.gradient(&el, &qm).1;
                        let hscale = d.hessian.iter().flatten().fold(1.0f64, |m, h| m.max(h.abs()));
                        for j in 0..NDOF {
                            let fdh = (gp[j] - gm[j]) / (2.0 * hstep);
                            if (fdh - d.hessian[j][i]).abs() > 1e-5 * hscale {
                                kink = true;
                            }
                        }
                    }
                    if !kink {
                        hessian_checked += 1;
                    }
                    // symmetric Hessian
                    for i in 0..NDOF {
                        for j in 0..NDOF {
                            assert!((d.hessian[i][j] - d.hessian[j][i]).abs() <= 1e-9 * d.hessian[i][i].abs().max(1.0));
                        }
                    }
                }
            }
            assert!(hessian_checked >= 100, "{}: only {hessian_checked} of 120 Hessians checked", kernel.name());
        }
    }

    /// The per-point path equals AD over the whole element (same numbers up to
    /// round-off: both are exact derivatives).
    #[test]
    fn pointwise_equals_full_ad() {
        let mut rng = Rng(77);
        for kernel in registry() {
            for el in elements_for(kernel.as_ref()) {
                for _ in 0..10 {
                    let q = random_q(&el, &mut rng);
                    let a = kernel.derivatives(&el, &q);
                    let b = kernel.derivatives_full(&el, &q);
                    assert!((a.energy - b.energy).abs() <= 1e-13 * b.energy.abs().max(1e-10));
                    let gs = b.gradient.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
                    let hs = b.hessian.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
                    for i in 0..NDOF {
                        assert!((a.gradient[i] - b.gradient[i]).abs() <= 1e-12 * gs, "{}", kernel.name());
                        for j in 0..NDOF {
                            assert!((a.hessian[i][j] - b.hessian[i][j]).abs() <= 1e-11 * hs, "{} H[{i}][{j}]", kernel.name());
                        }
                    }
                }
            }
        }
    }

    /// The Kirchhoff rod's chain-rule path (the units' [`PointJet`]s projected once per
    /// distinct point, the map's chain rule only at flagged nodes) against the per-point
    /// `Dual2SVec64<4>` AD it replaced, at 40 random states of each element of
    /// [`elements_for`] (every region, contact partly penetrated, the augmented map at
    /// either and both nodes), for both rod rules and a strain law with W‴ ≠ 0 besides
    /// Biot's: energy, gradient and Hessian to 1e-12 of the largest entry (both are exact
    /// derivatives; they differ only in the order of a few dozen roundings). The
    /// derivatives against central differences are
    /// [`ad_matches_finite_differences_for_every_formulation`], which runs the rods
    /// through this path.
    #[test]
    fn rod_chain_rule_equals_point_ad() {
        let mut rng = Rng(0x0dd_ba11);
        let cubic = |l: f64, ea: f64| -> f64 { let e = l - 1.0; ea * e * e * (0.5 + 0.3 * e) };
        for kernel in [ROD_SIMPSON, ROD_GAUSS] {
            let rules = kernel.rules;
            for el in elements_for(&kernel) {
                let ea = el.params.axial_stiffness;
                for trial in 0..40 {
                    let q = random_q(&el, &mut rng);
                    let (fast, oracle) = if trial % 2 == 0 {
                        (pointwise_derivatives_rod(&el, &q, &rules, |l| biot_density(l, ea)), pointwise_derivatives_rod_ad(&el, &q, &rules, |l| biot_density(l, ea)))
                    } else {
                        let w2 = |l: Dual2_64| { let e = l - 1.0; e * e * (e * 0.3 + 0.5) * ea };
                        let w4 = |l: Dual2SVec64<4>| { let e = l - 1.0; e * e * (e * 0.3 + 0.5) * ea };
                        assert!((w2(Dual2_64::from_re(1.1)).re - cubic(1.1, ea)).abs() < 1e-9);
                        (pointwise_derivatives_rod(&el, &q, &rules, w2), pointwise_derivatives_rod_ad(&el, &q, &rules, w4))
                    };
                    assert!((fast.energy - oracle.energy).abs() <= 1e-12 * oracle.energy.abs().max(1e-12), "{} energy {} vs {}", kernel.name, fast.energy, oracle.energy);
                    let gs = oracle.gradient.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
                    let hs = oracle.hessian.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
                    for i in 0..NDOF {
                        assert!((fast.gradient[i] - oracle.gradient[i]).abs() <= 1e-12 * gs, "{} {:?} g[{i}]: {} vs {}", kernel.name, el.augmented, fast.gradient[i], oracle.gradient[i]);
                        for j in 0..NDOF {
                            assert!((fast.hessian[i][j] - oracle.hessian[i][j]).abs() <= 1e-12 * hs, "{} {:?} H[{i}][{j}]: {} vs {}", kernel.name, el.augmented, fast.hessian[i][j], oracle.hessian[i][j]);
                        }
                    }
                }
            }
        }
    }

    /// N = dW/dλ: for Biot, EA(λ − 1) (S1).
    #[test]
    fn axial_force_is_the_biot_law() {
        for kernel in registry() {
            assert_eq!(kernel.strain_measure(), "Biot");
            for lambda in [0.99, 1.0, 1.0001, 1.2] {
                let n = kernel.axial_force(lambda, 2.0e4);
                assert!((n - 2.0e4 * (lambda - 1.0)).abs() < 1e-9, "{}", kernel.name());
            }
        }
    }

    #[test]
    fn registry_names_are_unique_and_findable() {
        let reg = registry();
        assert!(reg.len() >= 2);
        for (i, k) in reg.iter().enumerate() {
            assert!(find(k.name()).is_some());
            assert!(!k.description().is_empty());
            for other in &reg[i + 1..] {
                assert_ne!(k.name(), other.name());
            }
            for rule in [k.rules().strain, k.rules().gravity, k.rules().contact] {
                rule.validate().unwrap();
            }
        }
        assert!(find("no-such-element").is_none());
    }

    /// Labels list exactly the active terms.
    #[test]
    fn labels_follow_the_active_terms() {
        let k = find("string-gauss").unwrap();
        let p = TermParams { axial_stiffness: 1.0, weight: None, penalty: None, bending_stiffness: None };
        assert_eq!(k.term_labels(&p).len(), 1);
        let p = TermParams { axial_stiffness: 1.0, weight: Some(1.0), penalty: Some(1.0), bending_stiffness: None };
        let l = k.term_labels(&p);
        assert_eq!(l.len(), 3);
        assert!(l[0].starts_with("strain energy (Biot, gauss3"));
        let l = find("string-simpson").unwrap().term_labels(&p);
        assert!(l[0].starts_with("strain energy (Biot, simpson") && l[2].starts_with("penalty normal contact (simpson"));
    }
}
