//! Element kernels of the direct steady solve for an element of any 1-D layout
//! ([`crate::element::ElementLayout`]): the centreline {s, ν} of its unknowns, the gap and
//! stretch of an element at a point, the material coordinate's derivatives for the
//! friction load, and the transport-inertia energy (AD over the element's unknowns).

use super::*;
use crate::element::ElementLayout;
use crate::formulation::terms::TransportInertia;
use crate::formulation::PointFields;

/// The centreline {s, ν} of an element of `layout` ([`ElementContext::centreline`]).
#[inline]
pub(super) fn centreline<D: Scalar, const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[D; N]) -> [D; NDOF] {
    el.centreline(layout, q)
}

/// The gap γ at a point of an element and its gradient in the element's q; `None`
/// where no pulley can be reached (F10).
pub(super) fn point_gap<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64) -> Option<(f64, [f64; N])> {
    el.gap(&el.fields(&centreline(layout, el, q), xi))?;
    let (g, gg) = gradient(
        |v| {
            let qq: [_; N] = std::array::from_fn(|i| v[i]);
            el.gap(&el.fields(&centreline(layout, el, &qq), xi)).unwrap_or(v[0] * 0.0)
        },
        &SVector::<f64, N>::from_fn(|i, _| q[i]),
    );
    Some((g, std::array::from_fn(|i| gg[i])))
}

/// The upwind stretch of an element (docs/fem-drive.md §12): physical length over
/// material length, λ̄_e = ∫_e |∂σr| dσ / (S_b − S_a) (5-point Gauss–Legendre), with its
/// gradient in q. The steady limit of the transient's windowed slip (D2) for a window of
/// one element.
pub(super) fn element_stretch<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N]) -> (f64, [f64; N]) {
    let qv = SVector::<f64, N>::from_fn(|i, _| q[i]);
    let jac = el.jacobian();
    let (lam, g) = gradient(
        |v| {
            let qq: [_; N] = std::array::from_fn(|i| v[i]);
            let qc = centreline(layout, el, &qq);
            let mut len = v[0] * 0.0;
            for &(xi, w) in Rule::Gauss(5).points() {
                let p = el.fields(&qc, xi);
                len += el.tangent_length(&p) * (w * jac);
            }
            len / (qc[4] - qc[0])
        },
        &qv,
    );
    (lam, std::array::from_fn(|i| g[i]))
}

/// The stretch λ at ξ of an element with its gradient in q.
pub(super) fn point_stretch<const N: usize>(layout: ElementLayout, el: &ElementContext, qv: &SVector<f64, N>, xi: f64) -> (f64, SVector<f64, N>) {
    gradient(
        |v| {
            let qq: [_; N] = std::array::from_fn(|i| v[i]);
            el.stretch(&el.fields(&centreline(layout, el, &qq), xi))
        },
        qv,
    )
}

/// ∂S/∂q at ξ, and ∂²S/∂q² where the augmented map makes S nonlinear in q (`None`:
/// S is linear in q, ∂S/∂q the Hermite value weights of the s unknowns).
pub(super) fn material_derivatives<const N: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], xi: f64) -> ([f64; N], Option<[[f64; N]; N]>) {
    if !el.augmented.iter().any(|&a| a) {
        let (vw, _) = crate::hermite::weights(xi, el.geometry.h);
        let mut d = [0.0; N];
        for (k, i) in layout.hermite_indices(0).into_iter().enumerate() {
            d[i] = vw[k];
        }
        return (d, None);
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
    // without the augmented map the point values u = (∂σS, ν, ∂σν) are linear in q:
    // per point the 3 × 3 derivatives of −T in u by `Dual2SVec64<3>`, then
    // ∂/∂q = Σ (∂/∂u) w and ∂²/∂q² = Σ wᵀ (∂²/∂u²) w — exact, and a small fraction of
    // the cost of the Hessian by AD over all N unknowns (measured, docs/performance.md)
    type D3 = num_dual::Dual2SVec64<3>;
    let term = TransportInertia { rule, rho };
    let jac = el.jacobian();
    let qc = centreline(layout, el, q);
    let (is, inu) = (layout.hermite_indices(0), layout.hermite_indices(1));
    let mut gq = [0.0; N];
    let mut h = [[0.0; N]; N];
    for &(xi, wt) in rule.points() {
        let p = el.fields(&qc, xi);
        let var = |v: f64, i: usize| D3::from_re(v).derivative(i);
        let pd = PointFields { sigma: p.sigma, s: D3::from_re(p.s), ds: var(p.ds, 0), nu: var(p.nu, 1), dnu: var(p.dnu, 2), d2nu: D3::from_re(p.d2nu) };
        let f = term.point_energy(el, &pd, D3::from_re(c), wt * jac);
        let g = f.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
        let hu = f.v2.unwrap_generic(nalgebra::Const::<3>, nalgebra::Const::<3>);
        let (wv, wd) = crate::hermite::weights(xi, el.geometry.h);
        let rows = [(is, wd), (inu, wv), (inu, wd)];
        crate::hermite::add_point_derivatives(&rows, 1.0, |a| g[a], |a, b| hu[(a, b)], &mut gq, Some(&mut h));
    }
    let gc = if c != 0.0 { gq.map(|v| 2.0 * v / c) } else { [0.0; N] };
    (gq, gc, h)
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
