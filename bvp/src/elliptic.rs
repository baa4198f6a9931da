//! Complete elliptic integrals, Jacobi elliptic functions and the incomplete integral of
//! the second kind, for the closed-form elastica in [`crate::analytical`].
//!
//! Conventions: every function takes the **modulus** k ∈ [0, 1] (the parameter is
//! m = k²), as in Abramowitz & Stegun ch. 16–17 and DLMF ch. 19, 22:
//!
//! ```text
//!     K(k) = ∫_0^{π/2} dφ / √(1 − k² sin²φ),      E(k) = ∫_0^{π/2} √(1 − k² sin²φ) dφ,
//!     u = ∫_0^{am u} dφ / √(1 − k² sin²φ),        sn u = sin am u,  cn u = cos am u,
//!     dn u = √(1 − k² sn² u),                     ε(u) = ∫_0^u dn² t dt = E(am u, k).
//! ```
//!
//! Methods:
//! - K and E by the arithmetic–geometric mean (A&S 17.6.1–17.6.4),
//! - sn, cn, dn, am by the descending Landen / AGM scheme (A&S 16.4, DLMF 22.20(ii)),
//! - incomplete E(φ, k) and F(φ, k) by Carlson's symmetric integrals R_F, R_D with the
//!   duplication algorithm (Carlson, Numer. Algorithms 10, 1995; DLMF 19.25.5, 19.25.9,
//!   19.36(i)).
//!
//! Inputs outside the domain (k ∉ [0, 1], non-finite arguments) give `NaN`, as
//! `f64::sqrt` does; nothing here panics. All results are accurate to a few ulp × the
//! condition of the function (tests check ≤ 1e-14 relative against reference values).

use std::f64::consts::PI;

/// Largest number of AGM / Landen steps. Convergence is quadratic: from c_0 ≤ 1 the
/// step count to reach 2^-53 is ≤ 6 for k ≤ 1 − 1e-15, so 64 is never reached.
const MAX_AGM_STEPS: usize = 64;

/// The AGM sequences a_n, b_n, c_n of A&S 17.6.1 started from a_0 = 1, b_0 = k' = √(1 − k²),
/// c_0 = k, up to the first n with |c_n| ≤ ε · a_n. Returns `(a, c)` as vectors (length
/// N + 1). For k < 1 only.
fn agm_sequence(k: f64) -> (Vec<f64>, Vec<f64>) {
    let kp = ((1.0 - k) * (1.0 + k)).sqrt();
    let mut a = vec![1.0];
    let mut c = vec![k];
    let (mut an, mut bn) = (1.0_f64, kp);
    for _ in 0..MAX_AGM_STEPS {
        if c.last()
            .is_some_and(|&cn: &f64| cn.abs() <= f64::EPSILON * an)
        {
            break;
        }
        let a1 = 0.5 * (an + bn);
        let b1 = (an * bn).sqrt();
        let c1 = 0.5 * (an - bn);
        an = a1;
        bn = b1;
        a.push(an);
        c.push(c1);
    }
    (a, c)
}

/// True when `k` is a valid modulus.
fn valid_modulus(k: f64) -> bool {
    (0.0..=1.0).contains(&k)
}

/// Complete elliptic integral of the first kind K(k) (A&S 17.6.1: K = π / (2 AGM(1, k'))).
///
/// K(0) = π/2; K(1) = +∞; `NaN` for k ∉ [0, 1].
pub fn complete_k(k: f64) -> f64 {
    complete_ke(k).0
}

/// Complete elliptic integral of the second kind E(k) (A&S 17.6.3–17.6.4).
///
/// E(0) = π/2; E(1) = 1; `NaN` for k ∉ [0, 1].
pub fn complete_e(k: f64) -> f64 {
    complete_ke(k).1
}

/// Both complete integrals `(K(k), E(k))` from one AGM sequence:
///
/// ```text
///     K = π / (2 a_N),     E = K · (1 − Σ_{n=0}^{N} 2^{n−1} c_n²).
/// ```
pub fn complete_ke(k: f64) -> (f64, f64) {
    if !valid_modulus(k) {
        return (f64::NAN, f64::NAN);
    }
    if k == 1.0 {
        return (f64::INFINITY, 1.0);
    }
    let (a, c) = agm_sequence(k);
    let kk = PI / (2.0 * a[a.len() - 1]);
    let mut sum = 0.0;
    let mut w = 0.5;
    for cn in &c {
        sum += w * cn * cn;
        w *= 2.0;
    }
    (kk, kk * (1.0 - sum))
}

/// Values of the Jacobi elliptic functions at one argument.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    /// sn(u, k) = sin am(u).
    pub sn: f64,
    /// cn(u, k) = cos am(u).
    pub cn: f64,
    /// dn(u, k) = √(1 − k² sn²), always > 0 for k < 1.
    pub dn: f64,
    /// The amplitude am(u, k), continuous and increasing in u (am(u + 2K) = am(u) + π).
    pub am: f64,
}

/// sn, cn, dn and am at `u` for modulus `k` by the descending Landen (AGM) scheme,
/// A&S 16.4.3:
///
/// ```text
///     φ_N = 2^N a_N u,   φ_{n−1} = ½ (φ_n + arcsin((c_n / a_n) sin φ_n)),   n = N … 1,
///     am = φ_0,  sn = sin φ_0,  cn = cos φ_0,  dn = √(cn² + k'² sn²).
/// ```
///
/// (dn = √(1 − k² sn²) written as a sum of non-negative terms: no cancellation near
/// sn = ±1. A&S's dn = cos φ_0 / cos(φ_1 − φ_0) is 0/0 at odd multiples of K.)
///
/// k = 0 gives (sin u, cos u, 1, u); k = 1 gives (tanh u, sech u, sech u, gd u).
/// All fields are `NaN` for k ∉ [0, 1] or non-finite u.
pub fn jacobi(u: f64, k: f64) -> Jacobi {
    let nan = Jacobi {
        sn: f64::NAN,
        cn: f64::NAN,
        dn: f64::NAN,
        am: f64::NAN,
    };
    if !valid_modulus(k) || !u.is_finite() {
        return nan;
    }
    if k == 0.0 {
        return Jacobi {
            sn: u.sin(),
            cn: u.cos(),
            dn: 1.0,
            am: u,
        };
    }
    if k == 1.0 {
        let sech = 1.0 / u.cosh();
        return Jacobi {
            sn: u.tanh(),
            cn: sech,
            dn: sech,
            am: u.sinh().atan(),
        };
    }
    let (a, c) = agm_sequence(k);
    let n = a.len() - 1;
    let mut phi = (2.0_f64).powi(n as i32) * a[n] * u;
    for i in (1..=n).rev() {
        let s = (c[i] / a[i] * phi.sin()).clamp(-1.0, 1.0);
        phi = 0.5 * (phi + s.asin());
    }
    let (sn, cn) = phi.sin_cos();
    let kp2 = (1.0 - k) * (1.0 + k);
    let dn = (cn * cn + kp2 * sn * sn).sqrt();
    Jacobi {
        sn,
        cn,
        dn,
        am: phi,
    }
}

/// Carlson's symmetric integral of the first kind
/// R_F(x, y, z) = ½ ∫_0^∞ dt / √((t+x)(t+y)(t+z)) for x, y, z ≥ 0 with at most one zero
/// (duplication algorithm, Carlson 1995 eq. (2.2)–(2.4); DLMF 19.36.1). `NaN` outside the
/// domain.
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    let domain = x >= 0.0 && y >= 0.0 && z >= 0.0 && x + y > 0.0 && y + z > 0.0 && x + z > 0.0;
    if !domain || !(x + y + z).is_finite() {
        return f64::NAN;
    }
    let (mut x, mut y, mut z) = (x, y, z);
    let mut a = (x + y + z) / 3.0;
    // Stop when 4^-m Q < |A_m| with Q = (3r)^{-1/6} max|A_0 − v|, r = ε: the truncation
    // error of the series below is then ≈ ε.
    let mut q =
        (3.0 * f64::EPSILON).powf(-1.0 / 6.0) * (a - x).abs().max((a - y).abs()).max((a - z).abs());
    for _ in 0..200 {
        if q < a.abs() {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lam = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lam);
        y = 0.25 * (y + lam);
        z = 0.25 * (z + lam);
        a = 0.25 * (a + lam);
        q *= 0.25;
    }
    // X = (A_0 − x_0)/(4^m A_m) = (A_m − x_m)/A_m, likewise Y; Z = −X − Y.
    let dx = (a - x) / a;
    let dy = (a - y) / a;
    let dz = -(dx + dy);
    let e2 = dx * dy - dz * dz;
    let e3 = dx * dy * dz;
    (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / a.sqrt()
}

/// Carlson's symmetric integral of the second kind
/// R_D(x, y, z) = (3/2) ∫_0^∞ dt / ((t+z) √((t+x)(t+y)(t+z))) for x, y ≥ 0 (at most one
/// zero), z > 0 (Carlson 1995 eq. (2.28)–(2.30); DLMF 19.36.2). `NaN` outside the domain.
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    let domain = x >= 0.0 && y >= 0.0 && z > 0.0 && x + y > 0.0;
    if !domain || !(x + y + z).is_finite() {
        return f64::NAN;
    }
    let (mut x, mut y, mut z) = (x, y, z);
    let mut a = (x + y + 3.0 * z) / 5.0;
    let mut q =
        (f64::EPSILON / 4.0).powf(-1.0 / 6.0) * (a - x).abs().max((a - y).abs()).max((a - z).abs());
    let mut sum = 0.0;
    let mut pow4 = 1.0; // 4^-m
    for _ in 0..200 {
        if q < a.abs() {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lam = sx * sy + sy * sz + sz * sx;
        sum += pow4 / (sz * (z + lam));
        x = 0.25 * (x + lam);
        y = 0.25 * (y + lam);
        z = 0.25 * (z + lam);
        a = 0.25 * (a + lam);
        q *= 0.25;
        pow4 *= 0.25;
    }
    let dx = (a - x) / a;
    let dy = (a - y) / a;
    let dz = -(dx + dy) / 3.0;
    let xy = dx * dy;
    let z2 = dz * dz;
    let e2 = xy - 6.0 * z2;
    let e3 = (3.0 * xy - 8.0 * z2) * dz;
    let e4 = 3.0 * (xy - z2) * z2;
    let e5 = xy * z2 * dz;
    let series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
        - 3.0 * e4 / 22.0
        - 9.0 * e2 * e3 / 52.0
        + 3.0 * e5 / 26.0;
    pow4 * series / (a * a.sqrt()) + 3.0 * sum
}

/// The reduction φ = φ_r + nπ, φ_r ∈ [−π/2, π/2]; returns (φ_r, n).
fn reduce_amplitude(phi: f64) -> (f64, f64) {
    let n = (phi / PI).round();
    (phi - n * PI, n)
}

/// An incomplete integral I(φ, k) = ∫_0^φ g(sin²θ) dθ of any real amplitude by the
/// reduction φ = φ_r + nπ ([`reduce_amplitude`]): I(φ) = I(φ_r) + 2n I(π/2), with
/// `reduced(s, c)` = I(φ_r) from s = sin φ_r ≠ 0, c = cos φ_r (I = 0 at s = 0) and
/// `complete(k)` = I(π/2) (evaluated only for n ≠ 0). `NaN` for k ∉ [0, 1] or a
/// non-finite φ.
fn by_reduction(phi: f64, k: f64, complete: fn(f64) -> f64, reduced: impl Fn(f64, f64) -> f64) -> f64 {
    if !valid_modulus(k) || !phi.is_finite() {
        return f64::NAN;
    }
    let (pr, n) = reduce_amplitude(phi);
    let (s, c) = pr.sin_cos();
    let ir = if s == 0.0 { 0.0 } else { reduced(s, c) };
    if n == 0.0 {
        ir
    } else {
        ir + 2.0 * n * complete(k)
    }
}

/// Incomplete elliptic integral of the first kind F(φ, k) = ∫_0^φ dθ / √(1 − k² sin²θ)
/// for any real φ (F(φ + nπ) = F(φ) + 2nK), DLMF 19.25.5:
/// F(φ_r, k) = sin φ_r · R_F(cos²φ_r, 1 − k² sin²φ_r, 1). `NaN` for k ∉ [0, 1] and for
/// k = 1, |φ| ≥ π/2.
pub fn incomplete_f(phi: f64, k: f64) -> f64 {
    by_reduction(phi, k, complete_k, |s, c| s * carlson_rf(c * c, 1.0 - k * k * s * s, 1.0))
}

/// Incomplete elliptic integral of the second kind E(φ, k) = ∫_0^φ √(1 − k² sin²θ) dθ for
/// any real φ (E(φ + nπ) = E(φ) + 2nE(k)), DLMF 19.25.9:
///
/// ```text
///     E(φ_r, k) = s R_F(c², 1 − k²s², 1) − (k²/3) s³ R_D(c², 1 − k²s², 1),
///     s = sin φ_r, c = cos φ_r.
/// ```
///
/// `NaN` for k ∉ [0, 1].
pub fn incomplete_e(phi: f64, k: f64) -> f64 {
    by_reduction(phi, k, complete_e, |s, c| {
        let (x, y) = (c * c, 1.0 - k * k * s * s);
        // At k = 1, φ_r = ±π/2 both x and y vanish; E(±π/2, 1) = ±1 (R_D term finite).
        if x + y == 0.0 {
            s
        } else {
            s * carlson_rf(x, y, 1.0) - k * k / 3.0 * s * s * s * carlson_rd(x, y, 1.0)
        }
    })
}

/// Jacobi's epsilon function ε(u, k) = ∫_0^u dn²(t, k) dt = E(am u, k) (DLMF 22.16.14).
pub fn jacobi_epsilon(u: f64, k: f64) -> f64 {
    incomplete_e(jacobi(u, k).am, k)
}

#[cfg(test)]
mod tests {
    //! Reference values: A&S Table 17.1 / DLMF 19 (K, E at k = 1/√2 and k = 1/2, checked
    //! against scipy.special 1.17 `ellipk`, `ellipe`, `ellipj`, `ellipeinc`), Carlson (1995)
    //! §3 test values for R_F and R_D. Tolerances are a few ulp × the size of the value
    //! (1e-14 relative): the algorithms are accurate to rounding level, so any larger
    //! error is a bug.
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    const TOL: f64 = 1e-14;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn complete_integrals_reference_values() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(complete_k(0.0), FRAC_PI_2, TOL));
        assert!(close(complete_e(0.0), FRAC_PI_2, TOL));
        assert!(
            close(complete_k(s), 1.854074677301372, TOL),
            "{}",
            complete_k(s)
        );
        assert!(
            close(complete_e(s), 1.350643881047675, TOL),
            "{}",
            complete_e(s)
        );
        assert!(close(complete_k(0.5), 1.685750354812596, TOL));
        assert!(close(complete_e(0.5), 1.4674622093394272, TOL));
        assert_eq!(complete_k(1.0), f64::INFINITY);
        assert_eq!(complete_e(1.0), 1.0);
        assert!(
            complete_k(1.5).is_nan() && complete_e(-0.1).is_nan() && complete_k(f64::NAN).is_nan()
        );
    }

    #[test]
    fn legendre_relation() {
        // E K' + E' K − K K' = π/2 (DLMF 19.7.1) for k' = √(1 − k²): a check that does not
        // rely on tabulated values.
        for &k in &[0.01, 0.3, 0.5, 0.8, 0.95, 0.999] {
            let kp = ((1.0_f64 - k) * (1.0 + k)).sqrt();
            let (kk, e) = complete_ke(k);
            let (kkp, ep) = complete_ke(kp);
            let lhs = e * kkp + ep * kk - kk * kkp;
            assert!(close(lhs, FRAC_PI_2, 1e-13), "k = {k}: {lhs}");
        }
    }

    #[test]
    fn jacobi_reference_values() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let j = jacobi(0.7, s);
        assert!(close(j.sn, 0.6243400909662173, TOL), "{j:?}");
        assert!(close(j.cn, 0.7811526424536344, TOL));
        assert!(close(j.dn, 0.8972734953213249, TOL));
        assert!(close(j.am, 0.6742864586034127, TOL));
        let j = jacobi(3.9, 0.99);
        assert!(close(j.sn, 0.9967694536684202, 1e-13), "{j:?}");
        assert!(close(j.cn, -0.08031597744881909, 1e-13));
        assert!(close(j.dn, 0.1619329743273787, 1e-13));
        assert!(close(j.am, 1.6511989043223851, 1e-13));
    }

    #[test]
    fn jacobi_quarter_period_and_identities() {
        for &k in &[0.0, 0.2, 0.5, std::f64::consts::FRAC_1_SQRT_2, 0.9, 0.999] {
            let kk = complete_k(k);
            let kp = ((1.0 - k) * (1.0 + k)).sqrt();
            let q = jacobi(kk, k);
            assert!(close(q.sn, 1.0, 1e-14), "k = {k}: sn(K) = {}", q.sn);
            assert!(q.cn.abs() < 1e-14, "k = {k}: cn(K) = {}", q.cn);
            assert!(close(q.dn, kp, 1e-13), "k = {k}: dn(K) = {}", q.dn);
            assert!(close(q.am, FRAC_PI_2, 1e-14));
            // Periodicity: sn(u + 4K) = sn u, am(u + 2K) = am u + π.
            for &u in &[-2.3, -0.4, 0.0, 0.9, 3.7] {
                let a = jacobi(u, k);
                let b = jacobi(u + 4.0 * kk, k);
                let c = jacobi(u + 2.0 * kk, k);
                assert!((a.sn - b.sn).abs() < 1e-13 && (a.cn - b.cn).abs() < 1e-13);
                assert!((c.am - a.am - PI).abs() < 1e-13);
                assert!((a.sn * a.sn + a.cn * a.cn - 1.0).abs() < 1e-15);
                assert!((a.dn * a.dn + k * k * a.sn * a.sn - 1.0).abs() < 1e-15);
            }
        }
        let t = jacobi(0.8, 1.0);
        assert!(close(t.sn, 0.8_f64.tanh(), TOL) && close(t.cn, 1.0 / 0.8_f64.cosh(), TOL));
        assert!(jacobi(1.0, 1.2).sn.is_nan() && jacobi(f64::INFINITY, 0.5).cn.is_nan());
    }

    #[test]
    fn jacobi_derivatives_by_central_differences() {
        // d sn/du = cn dn, d cn/du = −sn dn, d dn/du = −k² sn cn, d am/du = dn. Central
        // differences with h = 1e-5 have truncation error ~h² ≈ 1e-10 and rounding ~ε/h.
        let k = 0.83;
        let h = 1e-5;
        for &u in &[-1.1, 0.3, 2.2, 5.0] {
            let j = jacobi(u, k);
            let p = jacobi(u + h, k);
            let m = jacobi(u - h, k);
            let d = |f: fn(&Jacobi) -> f64| (f(&p) - f(&m)) / (2.0 * h);
            assert!((d(|j| j.sn) - j.cn * j.dn).abs() < 1e-9);
            assert!((d(|j| j.cn) + j.sn * j.dn).abs() < 1e-9);
            assert!((d(|j| j.dn) + k * k * j.sn * j.cn).abs() < 1e-9);
            assert!((d(|j| j.am) - j.dn).abs() < 1e-9);
        }
    }

    #[test]
    fn carlson_reference_values() {
        // Carlson (1995) §3: R_F(1, 2, 0) = 1.3110287771461, R_F(2, 3, 4) = 0.58408284167715,
        // R_D(0, 2, 1) = 1.7972103521034, R_D(2, 3, 4) = 0.16510527294261 (13 digits given).
        assert!(close(carlson_rf(1.0, 2.0, 0.0), 1.3110287771461, 1e-13));
        assert!(close(carlson_rf(2.0, 3.0, 4.0), 0.58408284167715, 1e-13));
        assert!(close(carlson_rd(0.0, 2.0, 1.0), 1.7972103521034, 1e-13));
        assert!(close(carlson_rd(2.0, 3.0, 4.0), 0.16510527294261, 1e-13));
        assert!(carlson_rf(-1.0, 1.0, 1.0).is_nan() && carlson_rd(1.0, 1.0, 0.0).is_nan());
    }

    #[test]
    fn incomplete_integrals() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(incomplete_e(1.1, s), 1.0063195443554824, TOL));
        for &k in &[0.0, 0.3, s, 0.97] {
            let (kk, e) = complete_ke(k);
            assert!(close(incomplete_e(FRAC_PI_2, k), e, 1e-14));
            assert!(close(incomplete_f(FRAC_PI_2, k), kk, 1e-14));
            assert!(close(
                incomplete_e(-FRAC_PI_2 + 3.0 * PI, k),
                5.0 * e,
                1e-14
            ));
            // F inverts am: F(am u, k) = u.
            for &u in &[-3.0, 0.25, 1.0, 4.5] {
                assert!((incomplete_f(jacobi(u, k).am, k) - u).abs() < 1e-13);
            }
            // ε(K) = E, ε(4K) = 4E.
            assert!(close(jacobi_epsilon(kk, k), e, 1e-14));
            assert!(close(jacobi_epsilon(4.0 * kk, k), 4.0 * e, 1e-13));
        }
        assert!(close(incomplete_e(FRAC_PI_2, 1.0), 1.0, TOL));
    }
}
