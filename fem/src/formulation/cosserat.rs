//! The planar Cosserat (shear-deformable) rod as a MEL finite element (issue 13; spec
//! `cosserat-and-shell.md` §1.10; docs/fem-cosserat.md, equations (C0)–(C3) there).
//!
//! Fields {s, ν, ψ} on Hermite cubics ([`COSSERAT`], 12 unknowns per element), with ψ the
//! section rotation relative to the contour tangent: the director angle is
//! θ = ϑ_g(σ) + ψ (C0), so ψ is periodic round the loop. Strains (C2):
//! Γ₁ = (A cos ψ + B sin ψ)/∂σs − 1, Γ₂ = (B cos ψ − A sin ψ)/∂σs, κ = (∂σψ − α)/∂σs with
//! ∂σr = A t_g + B n_g = (1 + αν) t_g + ∂σν n_g. Energy terms as units: the new
//! [`StrainEnergy`] (stretch and shear) and [`SectionBending`] (densities of the rotation ψ, docs §3),
//! and the string's [`Gravity`] and [`PenaltyContact`] unchanged (they act on the
//! centreline only). At a Cartesian/polar transition the polar element's slopes follow
//! from the shared Cartesian ones by the augmented map (C3) — the rod's (K9) for ∂σs, ∂σν
//! and ∂σψ̃ = f ∂σψ + 1/R for the rotation — or the slopes are separate
//! ([`Transitions`]).
//!
//! The element implements [`ElementKernel<12>`] directly; energy, gradient and Hessian are
//! exact by forward AD, per integration point over the five point values
//! u = (∂σs, ν, ∂σν, ψ, ∂σψ) with the linear Hermite map and the chain rule through (C3).

use nalgebra::{Const, SVector, U1};
use num_dual::{Dual2SVec64, DualSVec64};

use super::terms::{AugmentedPenalty, ContactMultipliers, Gravity, PenaltyContact, PointDensity};
use super::layout::{FrictionNormal, LayoutElement};
use super::{ElementContext, ElementDerivatives, PointFields, Rule, Scalar, TermParams, TermRules, Theory, NDOF};
use crate::assembly::{ElementKernel, ADMISSIBILITY_POINTS};
use crate::problem::BeltSection;
use std::sync::Arc;
use crate::element::{ElementLayout, COSSERAT, STRING};

/// Unknowns per Cosserat element: per node (s, ∂σs, ν, ∂σν, ψ, ∂σψ).
pub const NC: usize = COSSERAT.dofs();

/// Field numbers in [`COSSERAT`].
const FIELD_S: usize = 0;
const FIELD_NU: usize = 1;
const FIELD_PSI: usize = 2;

/// Point values a term density may depend on: u = (∂σs, ν, ∂σν, ψ, ∂σψ) (the value s
/// never enters an energy).
const POINT_VALUES: usize = 5;

/// The integration rule of each energy term (docs/fem-cosserat.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CosseratRules {
    /// Stretch energy U₁ (Simpson against membrane locking, eq. 45, Fig. 7).
    pub stretch: Rule,
    /// Shear energy U₂ (text silent: Gauss 3, Simpson or reduced Gauss 2).
    pub shear: Rule,
    /// Bending energy U_κ.
    pub bending: Rule,
    /// Gravity potential W (F9).
    pub gravity: Rule,
    /// Penalty contact V_γ (F10).
    pub contact: Rule,
}

impl CosseratRules {
    /// The recommended rules (Simpson stretch; bending, gravity and contact by Gauss 3,
    /// as `rod-simpson`) with the shear rule `shear`.
    pub const fn with_shear(shear: Rule) -> CosseratRules {
        CosseratRules { stretch: Rule::Simpson, shear, bending: Rule::Gauss(3), gravity: Rule::Gauss(3), contact: Rule::Gauss(3) }
    }

    /// Every rule, to sample admissibility at all of them.
    fn all(&self) -> [Rule; 5] {
        [self.stretch, self.shear, self.bending, self.gravity, self.contact]
    }
}

/// How the slopes meet at a Cartesian/polar transition (docs/fem-cosserat.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transitions {
    /// One shared slope triple (the Cartesian side's) and the augmented map (C3) on the
    /// polar side: Γ₁, Γ₂ and κ continuous (spec §1.10 (ii), the default).
    Augmented,
    /// Two independent slope triples, C⁰ in σ (spec §1.10 (i), for comparison).
    Separate,
}

/// The Cosserat rod element. The axial stiffness b₁ (`axial_stiffness`), the bending
/// stiffness a (`bending_stiffness`; no bending term if `None`), the weight ρg and the
/// penalty factor P come from the [`TermParams`] of each evaluation — as for every
/// element on the assembler, whose callers (the homotopy in the weight) pass them per
/// call; the shear stiffness b₂, the rules and the transition treatment are the
/// element's own. The registered elements (`cosserat-gauss`, `cosserat-reduced`) carry
/// no b₂ (`None`): the static analysis binds the scene's `belt.shear_stiffness` to them
/// ([`LayoutElement::for_belt`]) before it assembles; an unbound element assembles a NaN
/// shear energy, which the solver reports as non-finite.
#[derive(Debug, Clone, PartialEq)]
pub struct CosseratElement {
    /// Shear stiffness b₂, N (> 0); `None` for a registered element, bound to the
    /// scene's b₂ by [`LayoutElement::for_belt`].
    pub shear_stiffness: Option<f64>,
    /// Rule per term.
    pub rules: CosseratRules,
    /// Slopes at the transitions.
    pub transitions: Transitions,
    /// The augmented-Lagrangian multipliers of the normal contact as a field over σ
    /// ([`AugmentedPenalty`]; docs/fem-cosserat.md §12.5); `None`: the plain penalty.
    pub contact_multipliers: Option<Arc<ContactMultipliers>>,
}

/// The fields of a Cosserat element at one point.
#[derive(Debug, Clone, Copy)]
pub struct CosseratPoint<D> {
    /// σ of the point, m.
    pub sigma: f64,
    /// Material coordinate s, m.
    pub s: D,
    /// ∂σs.
    pub ds: D,
    /// Deflection ν, m.
    pub nu: D,
    /// ∂σν.
    pub dnu: D,
    /// Rotation relative to the contour tangent ψ = θ − ϑ_g, rad (C0).
    pub psi: D,
    /// ∂σψ, 1/m.
    pub dpsi: D,
}

impl<D: Scalar> CosseratPoint<D> {
    /// The centreline's point values for the string's units (gravity, contact), which
    /// read σ, ∂σs and ν only; ∂²σν is not a Cosserat point value and set to zero.
    pub fn centreline(&self) -> PointFields<D> {
        PointFields { sigma: self.sigma, s: self.s, ds: self.ds, nu: self.nu, dnu: self.dnu, d2nu: D::zero() }
    }

    /// The strains (Γ₁, Γ₂, κ) of (C2) on element `el`.
    #[inline]
    pub fn strains(&self, el: &ElementContext) -> [D; 3] {
        let alpha = el.alpha();
        let a = self.nu * alpha + 1.0;
        let b = self.dnu;
        let (sn, cs) = self.psi.sin_cos();
        [(a * cs + b * sn) / self.ds - 1.0, (b * cs - a * sn) / self.ds, (self.dpsi - alpha) / self.ds]
    }
}

/// An energy term of the Cosserat element: its density per unit σ at a point, J/m.
pub trait CosseratDensity<D: Scalar> {
    /// Energy per unit σ at the point `p` of element `el`, J/m.
    fn density(&self, el: &ElementContext, p: &CosseratPoint<D>) -> D;
}

/// The energy of one strain of (C2) with its stiffness b: ½ b Γ² ∂σs (eq. 13) — the
/// stretch energy U₁ (Γ₁, b₁ in N, [`StrainEnergy::stretch`]) and the shear energy U₂
/// (Γ₂, b₂ in N, [`StrainEnergy::shear`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainEnergy {
    /// Index of the strain in [`CosseratPoint::strains`]: 0 = Γ₁, 1 = Γ₂.
    pub component: usize,
    /// Its stiffness b, N.
    pub stiffness: f64,
}

impl StrainEnergy {
    /// Stretch energy U₁ = ½ b₁ Γ₁² ∂σs, b₁ in N.
    pub const fn stretch(b1: f64) -> StrainEnergy {
        StrainEnergy { component: 0, stiffness: b1 }
    }

    /// Shear energy U₂ = ½ b₂ Γ₂² ∂σs, b₂ in N.
    pub const fn shear(b2: f64) -> StrainEnergy {
        StrainEnergy { component: 1, stiffness: b2 }
    }
}

impl<D: Scalar> CosseratDensity<D> for StrainEnergy {
    fn density(&self, el: &ElementContext, p: &CosseratPoint<D>) -> D {
        let g = p.strains(el)[self.component];
        g * g * p.ds * (0.5 * self.stiffness)
    }
}

/// Bending energy of the section rotation U_κ: ½ a κ² ∂σs = ½ a (∂σψ − α)²/∂σs (eq. 13,
/// (C2)), a in N·m².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionBending(pub f64);

impl<D: Scalar> CosseratDensity<D> for SectionBending {
    fn density(&self, el: &ElementContext, p: &CosseratPoint<D>) -> D {
        let k = p.dpsi - el.alpha();
        k * k / p.ds * (0.5 * self.0)
    }
}

/// A string unit acting on the centreline (gravity, penalty contact), used unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OnCentreline<T>(pub T);

impl<D: Scalar, T: PointDensity<D>> CosseratDensity<D> for OnCentreline<T> {
    fn density(&self, el: &ElementContext, p: &CosseratPoint<D>) -> D {
        self.0.density(el, &p.centreline())
    }
}

/// Something that walks the element's active terms (an integrator).
pub trait CosseratVisitor<D: Scalar> {
    /// Integrate one term with its rule.
    fn visit<T: CosseratDensity<D>>(&mut self, rule: Rule, term: &T);
}

/// The element's unknowns q in [`COSSERAT`] order → its {s, ν} part in [`STRING`] order
/// (for the string layout's helpers: the augmented map (K9) and
/// `terms::TransportInertia`, whose densities do not involve the rotation).
pub fn string_part<D: Scalar>(q: &[D; NC]) -> [D; NDOF] {
    let mut out = [D::zero(); NDOF];
    for f in [FIELD_S, FIELD_NU] {
        for (i, j) in STRING.hermite_indices(f).into_iter().zip(COSSERAT.hermite_indices(f)) {
            out[i] = q[j];
        }
    }
    out
}

impl CosseratElement {
    /// The element with shear stiffness `shear_stiffness` (N), the rules `rules` and the
    /// augmented transitions.
    pub fn new(shear_stiffness: f64, rules: CosseratRules) -> CosseratElement {
        CosseratElement { shear_stiffness: Some(shear_stiffness), rules, transitions: Transitions::Augmented, contact_multipliers: None }
    }

    /// The registered element of shear rule `shear`: no b₂ of its own, the scene's is
    /// bound by [`LayoutElement::for_belt`].
    pub const fn from_scene(shear: Rule) -> CosseratElement {
        CosseratElement { shear_stiffness: None, rules: CosseratRules::with_shear(shear), transitions: Transitions::Augmented, contact_multipliers: None }
    }

    /// Visit the active terms in assembly order: stretch, shear, bending (if
    /// `params.bending_stiffness`), gravity (if `params.weight`), contact (if
    /// `params.penalty`).
    pub fn visit<D: Scalar, V: CosseratVisitor<D>>(&self, params: &TermParams, v: &mut V) {
        let r = &self.rules;
        v.visit(r.stretch, &StrainEnergy::stretch(params.axial_stiffness));
        v.visit(r.shear, &StrainEnergy::shear(self.shear_stiffness.unwrap_or(f64::NAN)));
        if let Some(a) = params.bending_stiffness {
            v.visit(r.bending, &SectionBending(a));
        }
        if let Some(w) = params.weight {
            v.visit(r.gravity, &OnCentreline(Gravity(w)));
        }
        match (params.penalty, &self.contact_multipliers) {
            (Some(penalty), Some(m)) => v.visit(r.contact, &OnCentreline(AugmentedPenalty { penalty, multipliers: m })),
            (Some(p), None) => v.visit(r.contact, &OnCentreline(PenaltyContact(p))),
            (None, _) => {}
        }
    }

    /// The effective unknowns q̃ (C3): at a flagged node of a polar element (ν that
    /// node's deflection, f = 1 + αν) ∂σs and ∂σν by the rod's map (K9,
    /// [`ElementContext::effective`]) and ∂σψ̃ = f ∂σψ + α; elsewhere q̃ = q.
    pub fn effective_unknowns<D: Scalar>(el: &ElementContext, q: &[D; NC]) -> [D; NC] {
        if !el.augmented.iter().any(|&a| a) {
            return *q;
        }
        let mapped = el.effective(&string_part(q));
        let mut out = *q;
        for f in [FIELD_S, FIELD_NU] {
            for (i, j) in STRING.hermite_indices(f).into_iter().zip(COSSERAT.hermite_indices(f)) {
                out[j] = mapped[i];
            }
        }
        let alpha = el.alpha();
        for (node, &flag) in el.augmented.iter().enumerate() {
            if flag {
                let f = q[COSSERAT.index(node, FIELD_NU, 0)] * alpha + 1.0;
                let i = COSSERAT.index(node, FIELD_PSI, 1);
                out[i] = q[i] * f + alpha;
            }
        }
        out
    }

    /// The fields at ξ from the (effective) unknowns q̃ (eq. 43).
    #[inline]
    pub fn point<D: Scalar>(el: &ElementContext, q: &[D; NC], xi: f64) -> CosseratPoint<D> {
        let [s, ds, _] = el.field(COSSERAT, q, FIELD_S, xi);
        let [nu, dnu, _] = el.field(COSSERAT, q, FIELD_NU, xi);
        let [psi, dpsi, _] = el.field(COSSERAT, q, FIELD_PSI, xi);
        CosseratPoint { sigma: el.sigma(xi), s, ds, nu, dnu, psi, dpsi }
    }

    /// The element energy, J, for the unknowns q (before the map), generic so that AD
    /// differentiates it (and the map) exactly.
    pub fn element_energy<D: Scalar>(&self, el: &ElementContext, q: &[D; NC]) -> D {
        let qe = Self::effective_unknowns(el, q);
        let mut sum = Sum { el, q: &qe, total: D::zero() };
        self.visit(&el.params, &mut sum);
        sum.total
    }

    /// Energy, gradient and Hessian by AD over all 12 unknowns (`Dual2SVec64<12>`): the
    /// reference the per-point path is tested against.
    pub fn derivatives_full(&self, el: &ElementContext, q: &[f64; NC]) -> ElementDerivatives<NC> {
        let (e, g, h) = num_dual::hessian(|v| self.element_energy(el, &std::array::from_fn(|i| v[i])), &SVector::<f64, NC>::from_column_slice(q));
        ElementDerivatives { energy: e, gradient: std::array::from_fn(|i| g[i]), hessian: std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])) }
    }

    /// Energy, gradient and Hessian: per point by `Dual2SVec64<5>` over u (linear in q̃),
    /// then the chain rule through the map (C3) — exact, equal to [`Self::derivatives_full`].
    pub fn derivatives_pointwise(&self, el: &ElementContext, q: &[f64; NC]) -> ElementDerivatives<NC> {
        let qe = Self::effective_unknowns(el, q);
        let mut v = PointHessian { el, q: &qe, out: ElementDerivatives { energy: 0.0, gradient: [0.0; NC], hessian: [[0.0; NC]; NC] } };
        self.visit(&el.params, &mut v);
        chain_through_map(el, q, v.out)
    }
}

/// The f64 or AD energy as a running sum over terms and points.
struct Sum<'a, D> {
    el: &'a ElementContext,
    q: &'a [D; NC],
    total: D,
}

impl<D: Scalar> CosseratVisitor<D> for Sum<'_, D> {
    fn visit<T: CosseratDensity<D>>(&mut self, rule: Rule, term: &T) {
        let jac = self.el.jacobian();
        for &(xi, wt) in rule.points() {
            let p = CosseratElement::point(self.el, self.q, xi);
            self.total += term.density(self.el, &p) * (wt * jac);
        }
    }
}

/// The point values of `p` as AD numbers by `var(value, variable)`: ∂σs, ν, ∂σν, ψ,
/// ∂σψ the variables 0–4, s a constant (`None`; no density reads it).
fn seeded<D: Scalar>(p: &CosseratPoint<f64>, var: impl Fn(f64, Option<usize>) -> D) -> CosseratPoint<D> {
    CosseratPoint { sigma: p.sigma, s: var(p.s, None), ds: var(p.ds, Some(0)), nu: var(p.nu, Some(1)), dnu: var(p.dnu, Some(2)), psi: var(p.psi, Some(3)), dpsi: var(p.dpsi, Some(4)) }
}

/// Per-point derivatives in the effective unknowns q̃.
struct PointHessian<'a> {
    el: &'a ElementContext,
    q: &'a [f64; NC],
    out: ElementDerivatives<NC>,
}

type D5 = Dual2SVec64<POINT_VALUES>;

impl CosseratVisitor<D5> for PointHessian<'_> {
    fn visit<T: CosseratDensity<D5>>(&mut self, rule: Rule, term: &T) {
        let el = self.el;
        let jac = el.jacobian();
        for &(xi, wt) in rule.points() {
            let p = CosseratElement::point(el, self.q, xi);
            let pd = seeded(&p, |v, i| i.map_or(D5::from_re(v), |i| D5::from_re(v).derivative(i)));
            let f = term.density(el, &pd);
            let scale = wt * jac;
            let g = f.v1.unwrap_generic(U1, Const::<POINT_VALUES>);
            let h = f.v2.unwrap_generic(Const::<POINT_VALUES>, Const::<POINT_VALUES>);
            self.out.energy += scale * f.re;
            crate::hermite::add_point_derivatives(&point_rows(xi, el.geometry.h), scale, |a| g[a], |a, b| h[(a, b)], &mut self.out.gradient, Some(&mut self.out.hessian));
        }
    }
}

/// The point values u_a = Σ_k w_a[k] q̃[idx_a[k]] = (∂σs, ν, ∂σν, ψ, ∂σψ) at ξ: per value
/// the unknowns idx_a and the weights w_a.
fn point_rows(xi: f64, h: f64) -> [([usize; 4], [f64; 4]); POINT_VALUES] {
    let (wv, wd) = crate::hermite::weights(xi, h);
    let [is, inu, ipsi] = [FIELD_S, FIELD_NU, FIELD_PSI].map(|f| COSSERAT.hermite_indices(f));
    [(is, wd), (inu, wv), (inu, wd), (ipsi, wv), (ipsi, wd)]
}

/// Per-point energy and gradient in the effective unknowns q̃ (first-order duals: the
/// residual evaluations of a line search need no Hessian).
struct PointGradient<'a> {
    el: &'a ElementContext,
    q: &'a [f64; NC],
    energy: f64,
    gradient: [f64; NC],
}

type G5 = DualSVec64<POINT_VALUES>;

impl CosseratVisitor<G5> for PointGradient<'_> {
    fn visit<T: CosseratDensity<G5>>(&mut self, rule: Rule, term: &T) {
        let el = self.el;
        let jac = el.jacobian();
        for &(xi, wt) in rule.points() {
            let p = CosseratElement::point(el, self.q, xi);
            let pd = seeded(&p, |v, i| i.map_or(G5::from_re(v), |i| G5::from_re(v).derivative(i)));
            let f = term.density(el, &pd);
            let scale = wt * jac;
            let g = f.eps.unwrap_generic(Const::<POINT_VALUES>, U1);
            self.energy += scale * f.re;
            crate::hermite::add_point_derivatives(&point_rows(xi, el.geometry.h), scale, |a| g[a], |_, _| 0.0, &mut self.gradient, None);
        }
    }
}

/// Derivatives in q from those in q̃ = m(q) (C3): g = Jᵀ g̃, K = Jᵀ K̃ J + Σ_i g̃_i ∂²m_i.
/// At a flagged node each slope i (∂σs, ∂σν, ∂σψ) is m_i = q_i (1 + α ν_node) (+ α for
/// ψ), so J_ii = f, J_i,ν = α q_i and ∂²m_i/∂q_i∂ν = α.
fn chain_through_map(el: &ElementContext, q: &[f64; NC], d: ElementDerivatives<NC>) -> ElementDerivatives<NC> {
    if !el.augmented.iter().any(|&a| a) {
        return d;
    }
    let alpha = el.alpha();
    let mut jm = [[0.0; NC]; NC];
    for (i, row) in jm.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let mut second = Vec::with_capacity(6);
    for (node, &flag) in el.augmented.iter().enumerate() {
        if flag {
            let nu = COSSERAT.index(node, FIELD_NU, 0);
            for field in [FIELD_S, FIELD_NU, FIELD_PSI] {
                let i = COSSERAT.index(node, field, 1);
                jm[i][i] = 1.0 + alpha * q[nu];
                jm[i][nu] = alpha * q[i];
                second.push((i, nu, alpha * d.gradient[i]));
            }
        }
    }
    let mut out = ElementDerivatives { energy: d.energy, gradient: [0.0; NC], hessian: [[0.0; NC]; NC] };
    for (j, gj) in out.gradient.iter_mut().enumerate() {
        *gj = (0..NC).map(|k| jm[k][j] * d.gradient[k]).sum();
    }
    let mut kj = [[0.0; NC]; NC];
    for (a, row) in kj.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..NC).map(|b| d.hessian[a][b] * jm[b][j]).sum();
        }
    }
    for (i, row) in out.hessian.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..NC).map(|a| jm[a][i] * kj[a][j]).sum();
        }
    }
    for (i, j, v) in second {
        out.hessian[i][j] += v;
        out.hessian[j][i] += v;
    }
    out
}

impl ElementKernel<NC> for CosseratElement {
    fn layout(&self) -> ElementLayout {
        COSSERAT
    }

    fn separate_transition_slopes(&self) -> bool {
        self.transitions == Transitions::Separate
    }

    /// ∂σs > 0 (after the map) at the admissibility points and every term's points.
    fn admissible(&self, el: &ElementContext, q: &[f64; NC]) -> bool {
        let qe = Self::effective_unknowns(el, q);
        let rules = self.rules.all();
        let points = rules.iter().flat_map(|r| r.points().iter().map(|p| p.0));
        ADMISSIBILITY_POINTS.into_iter().chain(points).all(|xi| el.field(COSSERAT, &qe, FIELD_S, xi)[1] > 0.0)
    }

    fn energy(&self, el: &ElementContext, q: &[f64; NC]) -> f64 {
        self.element_energy(el, q)
    }

    /// Per point by first-order duals over u, then g = Jᵀ g̃ through the map (C3): the
    /// line searches of the steady solves evaluate 1–5 residuals per Hessian (measured,
    /// docs/performance.md), and the per-point Hessian costs ≈ 3 gradients.
    fn gradient(&self, el: &ElementContext, q: &[f64; NC]) -> (f64, [f64; NC]) {
        let qe = Self::effective_unknowns(el, q);
        let mut v = PointGradient { el, q: &qe, energy: 0.0, gradient: [0.0; NC] };
        self.visit(&el.params, &mut v);
        let d = chain_through_map(el, q, ElementDerivatives { energy: v.energy, gradient: v.gradient, hessian: [[0.0; NC]; NC] });
        (d.energy, d.gradient)
    }

    fn derivatives(&self, el: &ElementContext, q: &[f64; NC]) -> ElementDerivatives<NC> {
        self.derivatives_pointwise(el, q)
    }
}

/// The element on the registry's face ([`LayoutElement`]): what the static analysis and
/// the solution view need besides assembly. The axial force is N = b₁Γ₁ (eq. 14) at the
/// point; fields after s and ν (ψ) start at 0 (the director along the contour tangent,
/// the tight start state's ν = −δ is straight in the contour frame).
impl LayoutElement<NC> for CosseratElement {
    fn name(&self) -> &'static str {
        match self.rules.shear {
            Rule::Gauss(3) => "cosserat-gauss",
            Rule::Simpson => "cosserat-simpson",
            Rule::Gauss(2) => "cosserat-reduced",
            _ => "cosserat",
        }
    }

    fn description(&self) -> &'static str {
        "Cosserat rod (shear-deformable), fields {s, ν, ψ} on Hermite cubics (eq. 43) with the augmented map at the transitions, Simpson stretch, selectable shear rule, Gauss 3 bending, gravity and penalty contact (docs/fem-cosserat.md)"
    }

    fn theory(&self) -> Theory {
        Theory::Cosserat
    }

    fn rules(&self) -> TermRules {
        let r = &self.rules;
        TermRules { strain: r.stretch, gravity: r.gravity, contact: r.contact, bending: r.bending }
    }

    fn term_labels(&self, params: &TermParams) -> Vec<String> {
        let r = &self.rules;
        let mut out = vec![
            format!("stretch energy ({}, b₁ = {:.6e} N)", r.stretch, params.axial_stiffness),
            format!("shear energy ({}, b₂ = {:.6e} N)", r.shear, self.shear_stiffness.unwrap_or(f64::NAN)),
        ];
        if let Some(a) = params.bending_stiffness {
            out.push(format!("bending energy ({}, a = {:.6e} N·m², augmented transitions for ∂σs, ∂σν, ∂σψ)", r.bending, a));
        }
        out.extend(super::centreline_term_labels(params, r.gravity, r.contact));
        out
    }

    fn axial_force_at(&self, el: &ElementContext, q: &[f64; NC], xi: f64) -> f64 {
        el.params.axial_stiffness * Self::point(el, q, xi).strains(el)[0]
    }

    fn effective(&self, el: &ElementContext, q: &[f64; NC]) -> [f64; NC] {
        Self::effective_unknowns(el, q)
    }

    fn for_belt(&self, belt: &BeltSection) -> Option<Arc<dyn LayoutElement<NC>>> {
        let b2 = belt.shear_stiffness?;
        Some(Arc::new(CosseratElement { shear_stiffness: Some(b2), ..self.clone() }))
    }

    fn with_contact_multipliers(&self, multipliers: Option<Arc<ContactMultipliers>>) -> Option<Arc<dyn LayoutElement<NC>>> {
        Some(Arc::new(CosseratElement { contact_multipliers: multipliers, ..self.clone() }))
    }

    fn contact_multipliers(&self) -> Option<&ContactMultipliers> {
        self.contact_multipliers.as_deref()
    }

    fn shear_stiffness(&self) -> Option<f64> {
        self.shear_stiffness
    }

    /// Γ₂ of (C2) from the element's fields at ξ (continuous across elements: s, ν, ψ and
    /// their first derivatives are C¹ Hermite fields).
    fn shear_strain_at(&self, el: &ElementContext, q: &[f64; NC], xi: f64) -> Option<f64> {
        Some(Self::point(el, q, xi).strains(el)[1])
    }

    /// θ = ϑ_g(σ) + ψ (C0).
    fn rotation_at(&self, el: &ElementContext, q: &[f64; NC], xi: f64) -> Option<f64> {
        let p = Self::point(el, q, xi);
        Some(el.contour.tangent_angle(p.sigma) + p.psi)
    }

    /// The tributary penalty pressure: at the default penalty the element's cubic ν sits
    /// above the pulley at the nodes while the penalty presses it in between, at the
    /// contact rule's points (docs/fem-cosserat.md §11.1, §12.5).
    fn friction_normal(&self) -> FrictionNormal {
        FrictionNormal::Tributary
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::tests::{assert_consistent_jacobian, wave_state};
    use crate::assembly::Assembler;
    use crate::dofs::{augmented_flags, DofKind, DofMap};
    use crate::formulation::terms::{Bending, ContactMultipliers, Strain};
    use crate::formulation::{biot_density, find};
    use crate::mesh::{ElementGeometry, Mesh};
    use crate::test_rng::Rng;
    use drive::contour::{Contour, Region};
    use std::sync::Arc;

    const B1: f64 = 2.0e4;
    const B2: f64 = 1.0e3;
    const EI: f64 = 5.0e-3;

    fn contour() -> Contour {
        Contour::new(0.08, 0.45).unwrap()
    }

    fn params() -> TermParams {
        TermParams { axial_stiffness: B1, weight: Some(0.12 * 9.81), penalty: Some(3.0e6), bending_stiffness: Some(EI) }
    }

    fn context(region: Region, sigma_a: f64, h: f64, augmented: [bool; 2]) -> ElementContext {
        ElementContext { geometry: ElementGeometry { sigma_a, h, region }, contour: contour(), params: params(), augmented }
    }

    /// Elements of every region (the span ones reaching within R of a pulley, so the
    /// contact gap is active there) and polar elements with the map (C3) at the start,
    /// the end and both nodes.
    fn elements() -> Vec<ElementContext> {
        vec![
            context(Region::UpperSpan, 0.40, 0.03, [false; 2]),
            context(Region::DrivenArc, 0.50, 0.02, [false; 2]),
            context(Region::LowerSpan, 0.70, 0.04, [false; 2]),
            context(Region::LowerSpan, 1.10, 0.04, [false; 2]),
            context(Region::DriverArc, 1.20, 0.03, [false; 2]),
            context(Region::UpperSpan, 0.0, 0.03, [false; 2]),
            context(Region::DrivenArc, 0.45, 0.02, [true, false]),
            context(Region::DriverArc, 1.37, 0.03, [false, true]),
            context(Region::DriverArc, 1.25, 0.03, [true, true]),
        ]
    }

    /// Unknowns at node `node`: (s, ∂σs, ν, ∂σν, ψ, ∂σψ).
    fn set_node(q: &mut [f64; NC], node: usize, v: [f64; 6]) {
        for (k, x) in v.into_iter().enumerate() {
            q[COSSERAT.index(node, k / 2, k % 2)] = x;
        }
    }

    /// A random admissible state: ∂σs ≈ 1 ± 0.1, ν of either sign (some points penetrate),
    /// ∂σν ± 0.2, ψ ± 0.1 rad, ∂σψ ± 5 /m (curvatures up to about 1/(2.5 R)).
    fn random_q(el: &ElementContext, rng: &mut Rng) -> [f64; NC] {
        let sa = el.geometry.sigma_a;
        let mut q = [0.0; NC];
        for (node, sigma) in [(0, sa), (1, sa + el.geometry.h)] {
            let mut c = || rng.next() - 0.5;
            set_node(&mut q, node, [sigma * 0.98 + 0.01 * c(), 1.0 + 0.2 * c(), 0.004 * c(), 0.4 * c(), 0.2 * c(), 10.0 * c()]);
        }
        q
    }

    fn shear_rules() -> [CosseratRules; 3] {
        [Rule::Gauss(3), Rule::Simpson, Rule::Gauss(2)].map(CosseratRules::with_shear)
    }

    /// The augmented-Lagrangian contact (docs/fem-cosserat.md §12.5): with a zero field the
    /// element's energy is the penalty element's to round-off (the same ½P⟨−γ⟩²); with a
    /// field λ(σ) of 0–2·10⁴ N/m (the pressure at P = 3e6 for a gap of −7 mm) the gradient
    /// agrees with central differences of the energy (step and tolerance as
    /// [`derivatives_match_finite_differences`]) and the energy differs from the penalty's
    /// where a contact point carries λ — so the multipliers reach the assembled term.
    #[test]
    fn augmented_contact_energy_and_gradient() {
        let mut rng = Rng(0x0a1c_0a7c_2026_0013);
        let plain = CosseratElement::new(B2, CosseratRules::with_shear(Rule::Gauss(3)));
        let zero = CosseratElement { contact_multipliers: Some(Arc::new(ContactMultipliers::default())), ..plain.clone() };
        let field = ContactMultipliers::from_samples((0..=100).map(|k| (0.015 * k as f64, 1e4 * (1.0 + (7.0 * k as f64).sin()))).collect());
        let al = CosseratElement { contact_multipliers: Some(Arc::new(field)), ..plain.clone() };
        let mut differs = 0;
        for el in elements() {
            for _ in 0..10 {
                let q = random_q(&el, &mut rng);
                let e0 = plain.energy(&el, &q);
                assert!((zero.energy(&el, &q) - e0).abs() <= 1e-12 * e0.abs().max(1e-12));
                let d = al.derivatives(&el, &q);
                let scale = d.gradient.iter().fold(1.0f64, |m, g| m.max(g.abs()));
                let step = 1e-7;
                for i in 0..NC {
                    let (mut qp, mut qm) = (q, q);
                    qp[i] += step;
                    qm[i] -= step;
                    let fd = (al.energy(&el, &qp) - al.energy(&el, &qm)) / (2.0 * step);
                    assert!((fd - d.gradient[i]).abs() <= 1e-5 * scale, "{:?} grad[{i}]: AD {} FD {fd}", el.geometry.region, d.gradient[i]);
                }
                if (d.energy - e0).abs() > 1e-9 * e0.abs() {
                    differs += 1;
                }
            }
        }
        assert!(differs >= 10, "the multipliers changed the energy of only {differs} states");
    }

    /// Gradient and Hessian (the per-point path, which the kernel uses) against central
    /// differences of the f64 energy and of the gradient, for each shear rule on every
    /// element of [`elements`], 15 random states each. Step 1e-7 on unknowns of scale
    /// 0.01–1: truncation h²|E'''|/6 with |E'''| ≲ P·h_el ≈ 1e5 and round-off ε|E|/h stay
    /// below 1e-7 of the gradient scale — tolerance 1e-5 relative to max(1, |g|∞). The
    /// penalty term is only C¹ (its second derivative jumps at γ = 0): states whose
    /// stencil crosses γ = 0 are not counted for the Hessian, and at least 80 % must be
    /// checked.
    #[test]
    fn derivatives_match_finite_differences() {
        let mut rng = Rng(0x0c05_5e7a_2026_0013);
        for rules in shear_rules() {
            let k = CosseratElement::new(B2, rules);
            let (mut checked, mut total) = (0, 0);
            for el in elements() {
                for _ in 0..15 {
                    let q = random_q(&el, &mut rng);
                    assert!(k.admissible(&el, &q));
                    let d = k.derivatives(&el, &q);
                    let e0 = k.energy(&el, &q);
                    assert!((d.energy - e0).abs() <= 1e-12 * e0.abs().max(1e-12));
                    let scale = d.gradient.iter().fold(1.0f64, |m, g| m.max(g.abs()));
                    let hscale = d.hessian.iter().flatten().fold(1.0f64, |m, h| m.max(h.abs()));
                    let step = 1e-7;
                    let mut kink = false;
                    for i in 0..NC {
                        let (mut qp, mut qm) = (q, q);
                        qp[i] += step;
                        qm[i] -= step;
                        let fd = (k.energy(&el, &qp) - k.energy(&el, &qm)) / (2.0 * step);
                        assert!((fd - d.gradient[i]).abs() <= 1e-5 * scale, "{rules:?} {:?} {:?} grad[{i}]: AD {} FD {fd}", el.geometry.region, el.augmented, d.gradient[i]);
                        let (gp, gm) = (k.gradient(&el, &qp).1, k.gradient(&el, &qm).1);
                        for j in 0..NC {
                            kink |= ((gp[j] - gm[j]) / (2.0 * step) - d.hessian[j][i]).abs() > 1e-5 * hscale;
                        }
                    }
                    total += 1;
                    checked += usize::from(!kink);
                    for i in 0..NC {
                        for j in 0..NC {
                            assert!((d.hessian[i][j] - d.hessian[j][i]).abs() <= 1e-9 * hscale);
                        }
                    }
                }
            }
            assert!(5 * checked >= 4 * total, "{rules:?}: only {checked} of {total} Hessians checked");
        }
    }

    /// The per-point path equals AD over all 12 unknowns (both exact: round-off only,
    /// 1e-12 of the gradient and 1e-11 of the Hessian scale).
    #[test]
    fn pointwise_equals_full_ad() {
        let mut rng = Rng(99);
        for rules in shear_rules() {
            let k = CosseratElement::new(B2, rules);
            for el in elements() {
                for _ in 0..8 {
                    let q = random_q(&el, &mut rng);
                    let (a, b) = (k.derivatives_pointwise(&el, &q), k.derivatives_full(&el, &q));
                    // the gradient path (first-order duals per point, `gradient`) too
                    let (ge, g) = k.gradient(&el, &q);
                    assert!((a.energy - b.energy).abs() <= 1e-13 * b.energy.abs().max(1e-10));
                    assert!((ge - b.energy).abs() <= 1e-13 * b.energy.abs().max(1e-10));
                    let gs = b.gradient.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
                    let hs = b.hessian.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
                    for (i, (gi, bi)) in g.iter().zip(&b.gradient).enumerate() {
                        assert!((gi - bi).abs() <= 1e-12 * gs, "{:?} gradient path g[{i}]", el.augmented);
                    }
                    for i in 0..NC {
                        assert!((a.gradient[i] - b.gradient[i]).abs() <= 1e-12 * gs, "{:?} g[{i}]", el.augmented);
                        for j in 0..NC {
                            assert!((a.hessian[i][j] - b.hessian[i][j]).abs() <= 1e-11 * hs, "{:?} H[{i}][{j}]", el.augmented);
                        }
                    }
                }
            }
        }
    }

    /// Kirchhoff limit per point (docs/fem-cosserat.md §2): with the director along the
    /// tangent, ψ = atan2(∂σν, 1 + αν) and ∂σψ = θ_σ + α (θ_σ the rod's tangent angle
    /// rate K3), the shear energy vanishes and stretch + bending equal the rod's `Strain`
    /// (Biot) + `Bending` densities at random point values — to round-off (1e-13
    /// relative; the shear term to 1e-12 of the total, from Γ₂ ≈ 1e-17).
    #[test]
    fn kirchhoff_limit_pointwise() {
        let mut rng = Rng(4242);
        for el in elements() {
            for _ in 0..50 {
                let mut c = || rng.next() - 0.5;
                let p = PointFields { sigma: el.sigma(2.0 * c()), s: 0.3, ds: 1.0 + 0.4 * c(), nu: 0.01 * c(), dnu: 0.6 * c(), d2nu: 40.0 * c() };
                let rod = Strain(|l| biot_density(l, B1)).density(&el, &p) + Bending(EI).density(&el, &p);
                let psi = p.dnu.atan2(p.nu * el.alpha() + 1.0);
                let cp = CosseratPoint { sigma: p.sigma, s: p.s, ds: p.ds, nu: p.nu, dnu: p.dnu, psi, dpsi: el.angle_rate(&p) + el.alpha() };
                let shear = StrainEnergy::shear(B2).density(&el, &cp);
                let cos = StrainEnergy::stretch(B1).density(&el, &cp) + SectionBending(EI).density(&el, &cp);
                assert!((cos - rod).abs() <= 1e-13 * rod.abs(), "{cos} vs {rod}");
                assert!(shear.abs() <= 1e-12 * rod.abs(), "shear {shear}");
            }
        }
    }

    /// Kirchhoff limit per element: on states whose tangent angle is exactly a Hermite
    /// cubic — an arc at constant ν (ψ ≡ 0, with the map at either or both ends: the
    /// gathered ∂σψ = −α/f maps to 0), a span with linear ν (ψ ≡ atan ∂σν) — and random
    /// cubic s, the Cosserat element with the rod's rules has the energy of `rod-gauss` /
    /// `rod-simpson` (gravity and contact active, ν < 0 so the arc penetrates): equal to
    /// 1e-12 relative (the same sums in another order).
    #[test]
    fn kirchhoff_limit_matches_the_rod_elements() {
        let mut rng = Rng(7);
        let gauss = CosseratRules { stretch: Rule::Gauss(3), shear: Rule::Gauss(3), bending: Rule::Gauss(3), gravity: Rule::Gauss(3), contact: Rule::Gauss(3) };
        for (name, rules) in [("rod-gauss", gauss), ("rod-simpson", CosseratRules::with_shear(Rule::Gauss(2)))] {
            let rod = find(name).unwrap();
            let k = CosseratElement::new(B2, rules);
            for el in elements() {
                for _ in 0..5 {
                    let mut c = || rng.next() - 0.5;
                    let (sa, h) = (el.geometry.sigma_a, el.geometry.h);
                    let nu0 = -0.002 + 0.001 * c();
                    let slope = if el.geometry.region.is_polar() { 0.0 } else { 0.05 * c() };
                    let (nu_a, nu_b) = (nu0, nu0 + slope * h);
                    let psi = slope.atan();
                    let mut q = [0.0; NC];
                    for (node, sigma, nu) in [(0, sa, nu_a), (1, sa + h, nu_b)] {
                        // the gathered ∂σψ whose map (C3) gives ∂σψ̃ = 0 at a flagged node
                        let f = 1.0 + el.alpha() * nu;
                        let dpsi = if el.augmented[node] { -el.alpha() / f } else { 0.0 };
                        set_node(&mut q, node, [sigma + 0.01 * c(), 1.0 + 0.2 * c(), nu, slope, psi, dpsi]);
                    }
                    let (ec, er) = (k.energy(&el, &q), rod.energy(&el, &string_part(&q)));
                    assert!((ec - er).abs() <= 1e-12 * er.abs(), "{name} {:?} {:?}: {ec} vs {er}", el.geometry.region, el.augmented);
                }
            }
        }
    }

    /// A uniform shift of the material coordinate s changes neither the energy nor the
    /// gradient (s enters only through ∂σs): equal to round-off. ∂σs is a difference of
    /// s values of size ≈ 1 over h/2 ≈ 0.01, so shifting them changes it by ≈ 4ε·100
    /// ≈ 1e-13; with strains Γ₁ ≳ 0.01 in these states the energy moves by at most
    /// ≈ 2e-11 relative (measured ≤ 3e-13): tolerance 1e-11, the gradient 1e-10 of its scale.
    #[test]
    fn rigid_shift_of_s_changes_nothing() {
        let mut rng = Rng(31);
        let k = CosseratElement::new(B2, CosseratRules::with_shear(Rule::Gauss(3)));
        for el in elements() {
            let q = random_q(&el, &mut rng);
            let mut shifted = q;
            for node in 0..2 {
                shifted[COSSERAT.index(node, FIELD_S, 0)] += 0.37;
            }
            let (a, b) = (k.derivatives(&el, &q), k.derivatives(&el, &shifted));
            let gs = a.gradient.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            assert!((a.energy - b.energy).abs() <= 1e-11 * a.energy.abs(), "{} vs {}", a.energy, b.energy);
            for i in 0..NC {
                assert!((a.gradient[i] - b.gradient[i]).abs() <= 1e-10 * gs, "g[{i}]");
            }
        }
    }

    /// Closed forms on uniform states (constant integrands: every rule is exact, so the
    /// errors are round-off, 1e-12 relative):
    /// - a straight span element of contour length h, stretch λ (s = (σ − σ_a)/λ) and a
    ///   uniform rotation ψ₀: Γ₁ = λ cos ψ₀ − 1, Γ₂ = −λ sin ψ₀, E = ½(b₁Γ₁² + b₂Γ₂²) L with
    ///   L = h/λ; for ψ₀ = 0 the axial force from the gradient along d = ∂q/∂L (the
    ///   material force ∂E/∂L = W − Nλ, W = E/L) is N = b₁(λ − 1), and the moment of the
    ///   ψ-values' gradient is ∂E/∂ψ₀ = (−N λ sin ψ₀ − Q λ cos ψ₀) L;
    /// - an arc at constant ν with ψ = 0 and stretch λ = (1 + ν/R)/∂σs: ∂E/∂ν (all ν
    ///   values) = N h/R, the hoop relation p = N/R.
    #[test]
    fn closed_forms_of_uniform_states() {
        let k = CosseratElement::new(B2, CosseratRules::with_shear(Rule::Simpson));
        let mut el = context(Region::UpperSpan, 0.1, 0.05, [false; 2]);
        el.params.weight = None;
        let h = el.geometry.h;
        for lambda in [0.995, 1.0004, 1.03] {
            let l = h / lambda;
            for psi0 in [0.0, 0.02, -0.1] {
                let mut q = [0.0; NC];
                set_node(&mut q, 0, [0.2, 1.0 / lambda, 0.0, 0.0, psi0, 0.0]);
                set_node(&mut q, 1, [0.2 + l, 1.0 / lambda, 0.0, 0.0, psi0, 0.0]);
                let (g1, g2) = (lambda * psi0.cos() - 1.0, -lambda * psi0.sin());
                let (n, qs) = (B1 * g1, B2 * g2);
                let d = k.derivatives(&el, &q);
                // absolute strain round-off ≈ 50ε (∂σs = 1/λ inverted again): tolerance
                // 1e-14·(b₁|Γ₁| + b₂|Γ₂|)L beside 1e-12 relative
                let want = 0.5 * (B1 * g1 * g1 + B2 * g2 * g2) * l;
                let tol = 1e-12 * want + 1e-14 * (B1 * g1.abs() + B2 * g2.abs()) * l;
                assert!((d.energy - want).abs() <= tol, "λ {lambda} ψ {psi0}: {} vs {want}", d.energy);
                let dpsi: f64 = (0..2).map(|node| d.gradient[COSSERAT.index(node, FIELD_PSI, 0)]).sum();
                let want = (-n * lambda * psi0.sin() - qs * lambda * psi0.cos()) * l;
                assert!((dpsi - want).abs() <= 1e-12 * n.abs().max(1.0) * l, "∂E/∂ψ₀ {dpsi} vs {want}");
                if psi0 == 0.0 {
                    // d: s_b moves by 1, both slopes by 1/h
                    let de_dl = d.gradient[COSSERAT.index(1, FIELD_S, 0)] + (d.gradient[COSSERAT.index(0, FIELD_S, 1)] + d.gradient[COSSERAT.index(1, FIELD_S, 1)]) / h;
                    let axial = (d.energy / l - de_dl) / lambda;
                    assert!((axial - B1 * (lambda - 1.0)).abs() <= 1e-9 * B1 * (lambda - 1.0).abs().max(1e-3), "N {axial} vs {}", B1 * (lambda - 1.0));
                }
            }
        }
        // the arc: hoop relation
        let mut arc = context(Region::DrivenArc, 0.5, 0.02, [false; 2]);
        arc.params.weight = None;
        arc.params.penalty = None;
        let r = contour().radius();
        for (nu, ds) in [(0.001, 0.99), (0.003, 1.0), (-0.002, 1.01)] {
            let mut q = [0.0; NC];
            set_node(&mut q, 0, [0.5, ds, nu, 0.0, 0.0, 0.0]);
            set_node(&mut q, 1, [0.5 + ds * 0.02, ds, nu, 0.0, 0.0, 0.0]);
            let d = k.derivatives(&arc, &q);
            let n = B1 * ((1.0 + nu / r) / ds - 1.0);
            let dnu: f64 = (0..2).map(|node| d.gradient[COSSERAT.index(node, FIELD_NU, 0)]).sum();
            assert!((dnu - n * 0.02 / r).abs() <= 1e-12 * (B1 * 0.02 / r), "∂E/∂ν {dnu} vs N h/R {}", n * 0.02 / r);
        }
    }

    /// (C3): with one shared slope triple per transition and the map on the polar side,
    /// the strains Γ₁, Γ₂, κ of the two elements meeting at each of the four transitions
    /// agree for random nodal values (1e-12 relative: a few dozen operations on O(1–10)
    /// numbers). With separate slopes filled independently they do not — the check can
    /// fail.
    #[test]
    fn strains_are_continuous_across_transitions() {
        let mesh = Mesh::new(contour(), 20, 1.0).unwrap();
        let n = mesh.len();
        let mut rng = Rng(555);
        for separate in [false, true] {
            let map = DofMap::<NC>::with_layout(&mesh, COSSERAT, separate);
            let flags = augmented_flags(&mesh, separate);
            let mut broken = 0;
            for _ in 0..25 {
                let z: Vec<f64> = map.kinds().iter().map(|k| match k {
                    DofKind::Value => 0.02 * (rng.next() - 0.5),
                    DofKind::Slope => 1.0 + 0.8 * (rng.next() - 0.5),
                }).collect();
                for &node in &mesh.transition_nodes() {
                    let ctx = |e: usize| ElementContext { geometry: mesh.elements()[e], contour: contour(), params: params(), augmented: flags[e] };
                    let (cl, cr) = (ctx((node + n - 1) % n), ctx(node));
                    let ql = CosseratElement::effective_unknowns(&cl, &map.gather((node + n - 1) % n, &z, 1.3));
                    let qr = CosseratElement::effective_unknowns(&cr, &map.gather(node, &z, 1.3));
                    let sl = CosseratElement::point(&cl, &ql, 1.0).strains(&cl);
                    let sr = CosseratElement::point(&cr, &qr, -1.0).strains(&cr);
                    let ok = sl.iter().zip(&sr).all(|(a, b)| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0));
                    if separate {
                        broken += usize::from(!ok);
                    } else {
                        assert!(ok, "node {node}: {sl:?} vs {sr:?}");
                    }
                }
            }
            if separate {
                assert_eq!(broken, 100, "independent slopes should break the strains at every transition");
            }
        }
    }

    /// The element on the assembler: `Assembler::<12, CosseratElement>` with shared
    /// transition slopes, its assembled gradient and Jacobian against central
    /// differences of the assembled energy and gradient. Step 1e-6 on unknowns of size
    /// O(0.01–1): truncation h²|E'''|/6 ≲ 1e-12·1e4 and round-off ε|E|/h ≲ 1e-10·|E|
    /// stay below 1e-6 of the gradient and Jacobian scales — tolerance 1e-6 relative to
    /// the largest entry (no penalty term: it is only C¹).
    #[test]
    fn assembled_jacobian_is_consistent() {
        let c = contour();
        let mesh = Mesh::new(c, 10, 1.0).unwrap();
        let asm = Assembler::<NC, CosseratElement>::with_kernel(mesh, Arc::new(CosseratElement::new(B2, CosseratRules::with_shear(Rule::Gauss(2)))));
        // shared slopes: 6 per node, minus s₀
        assert_eq!(asm.len(), 6 * 10 - 1);
        let length = 1.02 * c.length();
        let z = wave_state(&asm, length / c.length());
        let p = TermParams { axial_stiffness: 1.0e4, weight: Some(1.2), penalty: None, bending_stiffness: Some(2.0e-3) };
        let jac = assert_consistent_jacobian(&asm, &z, &p, length);
        // the rotation couples in: its unknowns have positive diagonal entries
        let psi = asm.dofs().node_unknowns(3).values[FIELD_PSI].unwrap();
        assert!(jac[psi][psi] > 0.0);
    }

    /// `terms::TransportInertia` applies to the element's {s, ν} part unchanged
    /// (docs/fem-cosserat.md §3): on a straight span with ν = 0 (|∂σr| = 1) and uniform
    /// ∂σs, −T = −½ρc² h/∂σs whatever the rotation ψ, exact for every rule (constant
    /// integrand; 1e-13 relative).
    #[test]
    fn transport_inertia_on_the_string_part() {
        use crate::formulation::terms::TransportInertia;
        let el = context(Region::UpperSpan, 0.1, 0.05, [false; 2]);
        let mut q = [0.0; NC];
        set_node(&mut q, 0, [0.0, 0.98, 0.0, 0.0, 0.03, 0.0]);
        set_node(&mut q, 1, [0.049, 0.98, 0.0, 0.0, 0.03, 0.0]);
        let t = TransportInertia { rule: Rule::Simpson, rho: 0.12 }.element_energy(&el, &string_part(&q), 2.0);
        let want = -0.5 * 0.12 * 4.0 * 0.05 / 0.98;
        assert!((t - want).abs() <= 1e-13 * want.abs(), "{t} vs {want}");
    }
}
