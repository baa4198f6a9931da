//! Element kernels of the direct steady solve: the gap and stretch of an element at a point, the transport-inertia energy (AD over point values).

use super::*;
use crate::formulation::terms::TransportInertia;

/// The gap γ at a point of an element and its gradient in the element's q; `None`
/// where no pulley can be reached (F10).
pub(super) fn point_gap(el: &ElementContext, q: &[f64; NDOF], xi: f64) -> Option<(f64, [f64; NDOF])> {
    el.gap(&el.fields(q, xi))?;
    let (g, gg) = gradient(
        |v| {
            let qq: [_; NDOF] = std::array::from_fn(|i| v[i]);
            el.gap(&el.fields(&qq, xi)).unwrap_or(v[0] * 0.0)
        },
        &SVector::<f64, NDOF>::from_fn(|i, _| q[i]),
    );
    Some((g, std::array::from_fn(|i| gg[i])))
}

/// The upwind stretch of an element (docs/fem-drive.md §12): physical length over
/// material length, λ̄_e = ∫_e |∂σr| dσ / (S_b − S_a) (5-point Gauss–Legendre), with its
/// gradient in q. The steady limit of the transient's windowed slip (D2) for a window of
/// one element.
pub(super) fn element_stretch(el: &ElementContext, q: &[f64; NDOF]) -> (f64, [f64; NDOF]) {
    let qv = SVector::<f64, NDOF>::from_fn(|i, _| q[i]);
    let jac = el.jacobian();
    let (lam, g) = gradient(
        |v| {
            let qq: [_; NDOF] = std::array::from_fn(|i| v[i]);
            let mut len = v[0] * 0.0;
            for &(xi, w) in Rule::Gauss(5).points() {
                let p = el.fields(&qq, xi);
                len += el.tangent_length(&p) * (w * jac);
            }
            len / (qq[4] - qq[0])
        },
        &qv,
    );
    (lam, std::array::from_fn(|i| g[i]))
}

/// −T of (D8) for one element with c an unknown: the [`TransportInertia`] term unit
/// with the strain rule, −∫ ρc²|∂σr|²/(2∂σS) dσ.
pub(super) fn inertia_energy<D: Scalar>(el: &ElementContext, q: &[D; NDOF], c: D, rho: f64, rule: Rule) -> D {
    TransportInertia { rule, rho }.element_energy(el, q, c)
}
