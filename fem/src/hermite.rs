//! Cubic Hermite shape functions, eq. (43) of the reference.
//!
//! On ξ ∈ [−1, 1]:
//! ψ₁ = ¼(ξ − 1)²(ξ + 2), ψ₂ = ¼(ξ − 1)²(ξ + 1), ψ₃ = ¼(ξ + 1)²(2 − ξ),
//! ψ₄ = ¼(ξ + 1)²(ξ − 1).
//! ψ₁, ψ₃ carry the nodal values at ξ = −1, +1; ψ₂, ψ₄ the nodal ξ-derivatives. With
//! σ-derivatives as nodal unknowns on an element of length h (σ = σ_a + (1 + ξ)h/2):
//!
//!   u(ξ) = ψ₁ u_a + (h/2) ψ₂ u'_a + ψ₃ u_b + (h/2) ψ₄ u'_b,   u' = ∂σu = (2/h) du/dξ.

/// ψ₁…ψ₄ at ξ.
#[inline]
pub fn psi(xi: f64) -> [f64; 4] {
    let (m, p) = (xi - 1.0, xi + 1.0);
    [
        0.25 * m * m * (xi + 2.0),
        0.25 * m * m * p,
        0.25 * p * p * (2.0 - xi),
        0.25 * p * p * m,
    ]
}

/// dψ₁/dξ … dψ₄/dξ at ξ.
#[inline]
pub fn dpsi(xi: f64) -> [f64; 4] {
    let (m, p) = (xi - 1.0, xi + 1.0);
    [
        0.75 * (xi * xi - 1.0),
        0.25 * m * (3.0 * xi + 1.0),
        -0.75 * (xi * xi - 1.0),
        0.25 * p * (3.0 * xi - 1.0),
    ]
}

/// Weights (value, σ-derivative) of the four nodal unknowns (u_a, u'_a, u_b, u'_b) of an
/// element of length `h` at ξ: u = Σ_k w_v,k q_k, ∂σu = Σ_k w_d,k q_k.
#[inline]
pub fn weights(xi: f64, h: f64) -> ([f64; 4], [f64; 4]) {
    let p = psi(xi);
    let d = dpsi(xi);
    let half = 0.5 * h;
    let inv = 2.0 / h;
    (
        [p[0], half * p[1], p[2], half * p[3]],
        [inv * d[0], d[1], inv * d[2], d[3]],
    )
}

/// d²ψ₁/dξ² … d²ψ₄/dξ² at ξ.
#[inline]
pub fn d2psi(xi: f64) -> [f64; 4] {
    [1.5 * xi, 1.5 * xi - 0.5, -1.5 * xi, 1.5 * xi + 0.5]
}

/// Weights of the four nodal unknowns for the second σ-derivative ∂²σu at ξ.
#[inline]
pub fn second_weights(xi: f64, h: f64) -> [f64; 4] {
    let d = d2psi(xi);
    let (a, b) = (4.0 / (h * h), 2.0 / h);
    [a * d[0], b * d[1], a * d[2], b * d[3]]
}

/// Adds one point's energy derivatives in its V point values u_a = Σ_k w_a[k] q[i_a[k]]
/// (`rows`: the unknowns i_a and weights w_a of each value, [`weights`]) to an element's:
/// ∂/∂q += `scale` Σ_a (∂/∂u_a) w_a and ∂²/∂q² += `scale` Σ_ab w_aᵀ (∂²/∂u_a∂u_b) w_b.
/// `hessian` is `None` for the gradient alone.
#[inline]
pub fn add_point_derivatives<const V: usize, const N: usize>(
    rows: &[([usize; 4], [f64; 4]); V],
    scale: f64,
    g: impl Fn(usize) -> f64,
    h: impl Fn(usize, usize) -> f64,
    gradient: &mut [f64; N],
    mut hessian: Option<&mut [[f64; N]; N]>,
) {
    for (a, (ia, wa)) in rows.iter().enumerate() {
        for k in 0..4 {
            let row = ia[k];
            let sa = scale * wa[k];
            gradient[row] += sa * g(a);
            if let Some(hess) = hessian.as_deref_mut() {
                for (b, (ib, wb)) in rows.iter().enumerate() {
                    let hab = sa * h(a, b);
                    for l in 0..4 {
                        hess[row][ib[l]] += hab * wb[l];
                    }
                }
            }
        }
    }
}

/// Weights of (u, ∂σu, ∂²σu) at a generic ξ (a dual number in post-processing, to
/// differentiate a field along the element exactly): the same polynomials as
/// [`weights`] and [`second_weights`].
pub fn weights_generic<D: crate::kinematics::Scalar>(xi: D, h: f64) -> ([D; 4], [D; 4], [D; 4]) {
    let m = xi - 1.0;
    let p = xi + 1.0;
    let half = 0.5 * h;
    let inv = 2.0 / h;
    let inv2 = 4.0 / (h * h);
    let psi = [m * m * (xi + 2.0) * 0.25, m * m * p * 0.25, p * p * (-xi + 2.0) * 0.25, p * p * m * 0.25];
    let dpsi = [(xi * xi - 1.0) * 0.75, m * (xi * 3.0 + 1.0) * 0.25, (xi * xi - 1.0) * -0.75, p * (xi * 3.0 - 1.0) * 0.25];
    let d2 = [xi * 1.5, xi * 1.5 - 0.5, xi * -1.5, xi * 1.5 + 0.5];
    (
        [psi[0], psi[1] * half, psi[2], psi[3] * half],
        [dpsi[0] * inv, dpsi[1], dpsi[2] * inv, dpsi[3]],
        [d2[0] * inv2, d2[1] * inv, d2[2] * inv2, d2[3] * inv],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodal_properties() {
        let a = psi(-1.0);
        let b = psi(1.0);
        assert_eq!(a, [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(b, [0.0, 0.0, 1.0, 0.0]);
        let da = dpsi(-1.0);
        let db = dpsi(1.0);
        assert_eq!(da, [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(db, [0.0, 0.0, 0.0, 1.0]);
        // partition of unity of the value functions
        for k in 0..=20 {
            let xi = -1.0 + 0.1 * k as f64;
            let p = psi(xi);
            assert!((p[0] + p[2] - 1.0).abs() < 1e-15);
        }
    }

    /// dψ/dξ against central differences (h = 1e-6: truncation h²·|ψ'''|/6 ≤ 3e-13).
    #[test]
    fn derivatives_by_finite_differences() {
        let h = 1e-6;
        for k in 0..=40 {
            let xi = -0.99 + 0.0495 * k as f64;
            let (p, m) = (psi(xi + h), psi(xi - h));
            let d = dpsi(xi);
            for i in 0..4 {
                assert!(((p[i] - m[i]) / (2.0 * h) - d[i]).abs() < 1e-9);
            }
        }
    }

    /// Cubic reproduction: u = c₀ + c₁σ + c₂σ² + c₃σ³ on [σ_a, σ_b] is interpolated
    /// exactly (value and σ-derivative) from its nodal values and slopes.
    #[test]
    fn reproduces_cubics() {
        let (sa, h) = (0.3, 0.07);
        let u = |s: f64| 0.2 - 1.5 * s + 3.0 * s * s + 7.0 * s * s * s;
        let du = |s: f64| -1.5 + 6.0 * s + 21.0 * s * s;
        let q = [u(sa), du(sa), u(sa + h), du(sa + h)];
        for k in 0..=10 {
            let xi = -1.0 + 0.2 * k as f64;
            let s = sa + (1.0 + xi) * 0.5 * h;
            let (wv, wd) = weights(xi, h);
            let v: f64 = wv.iter().zip(&q).map(|(w, q)| w * q).sum();
            let d: f64 = wd.iter().zip(&q).map(|(w, q)| w * q).sum();
            assert!((v - u(s)).abs() < 1e-14 && (d - du(s)).abs() < 1e-12);
            let w2 = second_weights(xi, h);
            let d2: f64 = w2.iter().zip(&q).map(|(w, q)| w * q).sum();
            assert!((d2 - (6.0 + 42.0 * s)).abs() < 1e-9, "{d2}");
        }
    }
}
