//! Element kernels of the direct steady solve for an element of any 1-D layout
//! ([`crate::element::ElementLayout`]): the centreline {s, ν} of its unknowns, the gap and
//! stretch of an element at a point, the material coordinate's derivatives for the
//! friction load, and the transport-inertia energy (AD over the element's unknowns).

use super::*;
use crate::element::ElementLayout;
use crate::formulation::terms::TransportInertia;
use crate::formulation::PointFields;
use num_dual::DualSVec64;

/// The centreline {s, ν} of an element of `layout` ([`ElementContext::centreline`]).
#[inline]
pub(super) fn centreline<D: Scalar, const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[D; N]) -> [D; NDOF] {
    el.centreline(layout, q)
}

/// f(q) and, if `grad`, ∂f/∂q by first-order AD over the element's N unknowns; without
/// it f alone in plain f64 (the residual-only pass of the line search) and a zero
/// gradient. `value` and `dual` are the one generic function at the two number types.
#[inline]
pub(super) fn value_and_gradient<const N: usize>(q: &[f64; N], grad: bool, value: impl Fn(&[f64; N]) -> f64, dual: impl Fn(&[DualSVec64<N>; N]) -> DualSVec64<N>) -> (f64, [f64; N]) {
    if !grad {
        return (value(q), [0.0; N]);
    }
    let (f, g) = gradient(|v| dual(&std::array::from_fn(|i| v[i])), &SVector::<f64, N>::from_fn(|i, _| q[i]));
    (f, std::array::from_fn(|i| g[i]))
}

/// The gap γ at a point of an element and, if `grad`, its gradient in the element's q
/// (else zero); `None` where no pulley can be reached (F10).
pub(super) fn point_gap<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64, grad: bool) -> Option<(f64, [f64; N])> {
    let g = el.gap(&el.fields(&centreline(layout, el, q), xi))?;
    if !grad {
        return Some((g, [0.0; N]));
    }
    Some(value_and_gradient(q, true, |_| g, |qq| el.gap(&el.fields(&centreline(layout, el, qq), xi)).unwrap_or(qq[0] * 0.0)))
}

/// The upwind stretch of an element (docs/fem-drive.md §12): physical length over
/// material length, λ̄_e = ∫_e |∂σr| dσ / (S_b − S_a) (5-point Gauss–Legendre).
fn element_stretch_of<D: Scalar, const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[D; N]) -> D {
    let jac = el.jacobian();
    let qc = centreline(layout, el, q);
    let mut len = q[0] * 0.0;
    for &(xi, w) in Rule::Gauss(5).points() {
        let p = el.fields(&qc, xi);
        len += el.tangent_length(&p) * (w * jac);
    }
    len / (qc[4] - qc[0])
}

/// [`element_stretch_of`] with, if `grad`, its gradient in q (else zero). The steady
/// limit of the transient's windowed slip (D2) for a window of one element.
pub(super) fn element_stretch<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], grad: bool) -> (f64, [f64; N]) {
    value_and_gradient(q, grad, |qq| element_stretch_of(layout, el, qq), |qq| element_stretch_of(layout, el, qq))
}

/// The stretch λ at ξ of an element with, if `grad`, its gradient in q (else zero).
pub(super) fn point_stretch<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64, grad: bool) -> (f64, [f64; N]) {
    value_and_gradient(q, grad, |qq| el.stretch(&el.fields(&centreline(layout, el, qq), xi)), |qq| el.stretch(&el.fields(&centreline(layout, el, qq), xi)))
}

/// The weight's component along +σ per contour length at ξ of an element,
/// −(ρg/λ) ∂σy (N/m; `weight` = ρg per unstretched metre, ∂σy = (1 + αν) t_g,y + ∂σν n_g,y
/// the height's derivative of eq. (27)): the traction a stick zone carries where the belt
/// keeps its stretch (docs/fem-drive.md §12, "Sixth round").
fn tangential_weight_of<D: Scalar, const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[D; N], xi: f64, weight: f64) -> D {
    let p = el.fields(&centreline(layout, el, q), xi);
    let (t, n) = (el.contour.t_g(p.sigma), el.contour.n_g(p.sigma));
    let dy = (p.nu * el.alpha() + 1.0) * t[1] + p.dnu * n[1];
    dy * (-weight) / el.stretch(&p)
}

/// [`tangential_weight_of`] with, if `grad`, its gradient in q (else zero).
pub(super) fn tangential_weight<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64, weight: f64, grad: bool) -> (f64, [f64; N]) {
    value_and_gradient(q, grad, |qq| tangential_weight_of(layout, el, qq, xi, weight), |qq| tangential_weight_of(layout, el, qq, xi, weight))
}

/// ∂S/∂q at ξ, and where the augmented map makes S nonlinear in q `Some(∂²S/∂q²)` —
/// computed only if `second`, else zero (the residual needs ∂S/∂q alone); `None`: S is
/// linear in q, ∂S/∂q the Hermite value weights of the s unknowns.
pub(super) fn material_derivatives<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64, second: bool) -> ([f64; N], Option<[[f64; N]; N]>) {
    if !el.augmented.iter().any(|&a| a) {
        let (vw, _) = crate::hermite::weights(xi, el.geometry.h);
        let mut d = [0.0; N];
        for (k, i) in layout.hermite_indices(0).into_iter().enumerate() {
            d[i] = vw[k];
        }
        return (d, None);
    }
    if !second {
        let (_, g) = value_and_gradient(q, true, |qq| el.fields(&centreline(layout, el, qq), xi).s, |qq| el.fields(&centreline(layout, el, qq), xi).s);
        return (g, Some([[0.0; N]; N]));
    }
    let (_, g, h) = hessian(
        |v| {
            let qq: [_; N] = std::array::from_fn(|i| v[i]);
            el.fields(&centreline(layout, el, &qq), xi).s
        },
        &SVector::<f64, N>::from_fn(|i, _| q[i]),
    );
    (std::array::from_fn(|i| g[i]), Some(std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)]))))
}

/// −T of (D8) for one element, the [`TransportInertia`] term unit with the strain rule
/// on the element's centreline, −∫ ρc²|∂σr|²/(2∂σS) dσ (docs/fem-cosserat.md (C10)),
/// with its derivatives: ∂/∂q, ∂²/∂q∂c and ∂²/∂q². −T is c² times its value at c = 1,
/// so ∂²(−T)/∂q∂c = 2 ∂(−T)/∂q / c.
pub(super) type InertiaBlock<const N: usize> = ([f64; N], [f64; N], [[f64; N]; N]);

pub(super) fn inertia_derivatives<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], c: f64, rho: f64, rule: Rule) -> InertiaBlock<N> {
    if el.augmented.iter().any(|&a| a) {
        return inertia_derivatives_mapped(layout, el, q, c, rho, rule);
    }
    let mut h = [[0.0; N]; N];
    let gq = inertia_pointwise(layout, el, q, c, rho, rule, Some(&mut h));
    let gc = if c != 0.0 { gq.map(|v| 2.0 * v / c) } else { [0.0; N] };
    (gq, gc, h)
}

/// ∂(−T)/∂q of [`inertia_derivatives`] alone, for the residual-only pass: per point by
/// first-order duals (or over all N unknowns with the augmented map), no Hessian.
pub(super) fn inertia_gradient<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], c: f64, rho: f64, rule: Rule) -> [f64; N] {
    if el.augmented.iter().any(|&a| a) {
        let energy = |qq: &[DualSVec64<N>; N]| TransportInertia { rule, rho }.element_energy(el, &centreline(layout, el, qq), qq[0] * 0.0 + c);
        return value_and_gradient(q, true, |_| 0.0, energy).1;
    }
    inertia_pointwise(layout, el, q, c, rho, rule, None)
}

/// ∂(−T)/∂q and, if `hessian` is given, ∂²(−T)/∂q² added to it, of an element without
/// the augmented map: its point values u = (∂σS, ν, ∂σν) are linear in q, so per point
/// the derivatives of −T in u by `Dual2SVec64<3>` (by `DualSVec64<3>` for the gradient
/// alone), then ∂/∂q = Σ (∂/∂u) w and ∂²/∂q² = Σ wᵀ (∂²/∂u²) w — exact, and a small
/// fraction of the cost of the Hessian by AD over all N unknowns (measured,
/// docs/performance.md).
fn inertia_pointwise<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], c: f64, rho: f64, rule: Rule, mut hessian: Option<&mut [[f64; N]; N]>) -> [f64; N] {
    type D2 = num_dual::Dual2SVec64<3>;
    type D1 = DualSVec64<3>;
    let term = TransportInertia { rule, rho };
    let jac = el.jacobian();
    let qc = centreline(layout, el, q);
    let (is, inu) = (layout.hermite_indices(0), layout.hermite_indices(1));
    let mut gq = [0.0; N];
    for &(xi, wt) in rule.points() {
        let p = el.fields(&qc, xi);
        let (wv, wd) = crate::hermite::weights(xi, el.geometry.h);
        let rows = [(is, wd), (inu, wv), (inu, wd)];
        match hessian.as_deref_mut() {
            Some(h) => {
                let var = |v: f64, i: usize| D2::from_re(v).derivative(i);
                let pd = PointFields { sigma: p.sigma, s: D2::from_re(p.s), ds: var(p.ds, 0), nu: var(p.nu, 1), dnu: var(p.dnu, 2), d2nu: D2::from_re(p.d2nu) };
                let f = term.point_energy(el, &pd, D2::from_re(c), wt * jac);
                let g = f.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
                let hu = f.v2.unwrap_generic(nalgebra::Const::<3>, nalgebra::Const::<3>);
                crate::hermite::add_point_derivatives(&rows, 1.0, |a| g[a], |a, b| hu[(a, b)], &mut gq, Some(h));
            }
            None => {
                let var = |v: f64, i: usize| D1::from_re(v).derivative(i);
                let pd = PointFields { sigma: p.sigma, s: D1::from_re(p.s), ds: var(p.ds, 0), nu: var(p.nu, 1), dnu: var(p.dnu, 2), d2nu: D1::from_re(p.d2nu) };
                let g = term.point_energy(el, &pd, D1::from_re(c), wt * jac).eps.unwrap_generic(nalgebra::Const::<3>, nalgebra::U1);
                crate::hermite::add_point_derivatives(&rows, 1.0, |a| g[a], |_, _| 0.0, &mut gq, None);
            }
        }
    }
    gq
}

/// [`inertia_derivatives`] of an element with the augmented map at a node (S and ν
/// nonlinear in q there): the Hessian by AD over all N unknowns.
pub(super) fn inertia_derivatives_mapped<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], c: f64, rho: f64, rule: Rule) -> InertiaBlock<N> {
    let (_, g, h) = hessian(
        |v| {
            let qq: [_; N] = std::array::from_fn(|i| v[i]);
            TransportInertia { rule, rho }.element_energy(el, &centreline(layout, el, &qq), v[0] * 0.0 + c)
        },
        &SVector::<f64, N>::from_fn(|i, _| q[i]),
    );
    let gq: [f64; N] = std::array::from_fn(|i| g[i]);
    let gc = if c != 0.0 { gq.map(|v| 2.0 * v / c) } else { [0.0; N] };
    (gq, gc, std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])))
}
