//! Coulomb contact of the moving string: per-integration-point state, the augmented
//! Lagrangian return mapping of Table 1 (§6.1) and the element energy of the drive's
//! extra terms — normal contact (D6), friction (D7), transport inertia (D8) — with
//! exact derivatives by AD (docs/fem-drive.md §2, §5, §6).
//!
//! The extra terms of an element depend on its 8 string unknowns q and on the two
//! global step unknowns a (material advance at σ = 0, D1) and φ (driven rotation
//! increment, §4): 10 variables, differentiated together by `Dual2SVec64<10>`.

use drive::contour::{Contour, Pulley, Region};
use nalgebra::SVector;
use num_dual::{gradient, hessian};

use crate::kinematics::{ElementContext, PointFields, Scalar, NDOF};
use crate::quadrature::Rule;

/// Variables of the extra element terms: q (8), a, φ.
pub const NEXT: usize = NDOF + 2;

/// Per-step parameters of the contact and inertia terms.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StepParams {
    /// Normal penalty P_γ, N/m².
    pub penalty: f64,
    /// Tangential penalty P_⊥, N/m².
    pub tangential_penalty: f64,
    /// Drum surface advance of the driver over the step, R ω₁ Δt, m.
    pub driver_advance: f64,
    /// R, m.
    pub radius: f64,
    /// ρc² (N) of the transport inertia (D8), if the scene asks for inertia.
    pub inertia: Option<f64>,
}

/// State of one integration point of the contact rule (docs/fem-drive.md §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// ξ in the element.
    pub xi: f64,
    /// Weight of the normal term (D6): contact-rule weight × Jacobian, m (0 for a
    /// point of the friction rule only).
    pub weight: f64,
    /// Weight of the friction term (D7): trapezoidal weight × Jacobian at ξ = ±1, else
    /// 0, m (the mixed rule of §7.3: friction on the element edges).
    pub friction_weight: f64,
    /// σ of the point, m.
    pub sigma: f64,
    /// The pulley the point can touch (`None`: a span point out of reach).
    pub pulley: Option<Pulley>,
    /// d_ref: contour travel of the particle at σ over the previous step (the upstream
    /// reference point is σ − d_ref), m (D2).
    pub travel_ref: f64,
    /// S̃_n(σ − d_ref), m.
    pub s_ref: f64,
    /// ∂σS̃_n(σ − d_ref).
    pub slope_ref: f64,
    /// |∂σr|_n(σ): physical length per contour length at the point (1 + αν on an arc).
    pub metric: f64,
    /// Normal multiplier λ_γ, N/m.
    pub lambda_n: f64,
    /// Tangential multiplier λ_⊥, N/m.
    pub lambda_t: f64,
    /// Slip bound b = μ τ̂_γ frozen during a Newton solve, N/m.
    pub bound: f64,
    /// Sliding (Φ ≥ 0) at the last evaluation.
    pub slip: bool,
    /// Normal traction τ_γ of the last evaluation, N/m.
    pub normal: f64,
    /// Tangential traction τ_⊥ of the last evaluation, N/m.
    pub tangential: f64,
    /// Tangential relative displacement u of the last evaluation (D2), m.
    pub displacement: f64,
}

/// The points of the mixed rule of §7.3 on ξ ∈ [−1, 1]: (ξ, weight of the normal term,
/// weight of the friction term) — the contact rule's points for the normal term, the
/// element edges ξ = ±1 (trapezoidal weight 1) for friction; an edge that is a point of
/// the contact rule carries both.
pub fn mixed_rule(contact_rule: Rule) -> Vec<(f64, f64, f64)> {
    let mut rule: Vec<(f64, f64, f64)> = contact_rule.points().iter().map(|&(xi, w)| (xi, w, 0.0)).collect();
    for edge in [-1.0, 1.0] {
        match rule.iter_mut().find(|p| p.0 == edge) {
            Some(p) => p.2 = 1.0,
            None => rule.push((edge, 0.0, 1.0)),
        }
    }
    rule
}

/// The pulley a point at σ in `region` can touch: the arc's pulley, or the pulley whose
/// centre is within R in x of a span point (the domain of the gap, fem-string.md F10).
pub fn reachable_pulley(contour: &Contour, region: Region, sigma: f64) -> Option<Pulley> {
    if let Some(p) = region.pulley() {
        return Some(p);
    }
    let x = contour.g(sigma)[0];
    let half = 0.5 * contour.centre_distance();
    let r = contour.radius();
    if (x - half).abs() < r {
        Some(Pulley::Driven)
    } else if (x + half).abs() < r {
        Some(Pulley::Driver)
    } else {
        None
    }
}

/// Tangential relative displacement over the step (D2): the particle at σ at t_{n+1},
/// s = S̃_{n+1}(σ) − a in the gauge of step n, sat at σ' = S̃_n⁻¹(s) at t_n; with the
/// inverse linearised about the upstream reference point σ − d_ref,
/// σ − σ' = d_ref − (S̃_{n+1}(σ) − a − S̃_n(σ − d_ref)) / ∂σS̃_n(σ − d_ref), and
/// u = |∂σr|_n (σ − σ') − R Δθ_k, R Δθ₁ = `driver_advance`, Δθ₂ = φ. Linear in
/// (S̃_{n+1}(σ), a, φ): the friction force acts on the material only, upwind.
#[inline]
pub fn slip_displacement<D: Scalar>(_el: &ElementContext, p: &PointFields<D>, a: D, phi: D, pt: &PointState, sp: &StepParams) -> D {
    let travel = ((p.s - a - pt.s_ref) * (-1.0 / pt.slope_ref) + pt.travel_ref) * pt.metric;
    match pt.pulley {
        Some(Pulley::Driver) => travel - sp.driver_advance,
        Some(Pulley::Driven) => travel - phi * sp.radius,
        None => travel * 0.0,
    }
}

/// F_b(τ) of (D7): τ²/(2P) for |τ| ≤ b, (b|τ| − b²/2)/P beyond; F_b' = clip(τ, −b, b)/P.
#[inline]
fn friction_envelope<D: Scalar>(tau: D, bound: f64, stiffness: f64) -> D {
    if tau.re().abs() <= bound {
        tau * tau * (0.5 / stiffness)
    } else {
        (tau * tau.re().signum() * bound - 0.5 * bound * bound) * (1.0 / stiffness)
    }
}

/// The contact terms at one point, weighted (J): w_γ ψ_γ (D6) on the gap's domain,
/// w_⊥ ψ_⊥ (D7) where the point carries a slip bound.
#[inline]
pub fn point_energy<D: Scalar>(el: &ElementContext, p: &PointFields<D>, a: D, phi: D, pt: &PointState, sp: &StepParams) -> D {
    let mut f = p.nu * 0.0;
    if pt.pulley.is_none() {
        return f;
    }
    if pt.weight > 0.0 {
        if let Some(gap) = el.gap(p) {
            let t = gap * (-sp.penalty) + pt.lambda_n;
            if t.re() > 0.0 {
                f += t * t * (0.5 / sp.penalty * pt.weight);
            }
        }
    }
    if pt.bound > 0.0 && pt.friction_weight > 0.0 {
        let u = slip_displacement(el, p, a, phi, pt, sp);
        let tau = u * sp.tangential_penalty + pt.lambda_t;
        f += friction_envelope(tau, pt.bound, sp.tangential_penalty) * pt.friction_weight;
    }
    f
}

/// True if the element has a term to evaluate (a contact-capable point or inertia).
pub fn active(points: &[PointState], sp: &StepParams) -> bool {
    sp.inertia.is_some() || points.iter().any(|p| p.pulley.is_some())
}

/// The extra energy of one element, J: Σ over its contact points of w ψ (D6, D7), minus
/// the transport kinetic energy (D8) integrated with the strain rule `strain_rule`.
pub fn element_energy<D: Scalar>(
    el: &ElementContext,
    q: &[D; NDOF],
    a: D,
    phi: D,
    points: &[PointState],
    sp: &StepParams,
    strain_rule: Rule,
) -> D {
    let mut total = a * 0.0;
    for pt in points {
        if pt.pulley.is_none() {
            continue;
        }
        let p = el.fields(q, pt.xi);
        total += point_energy(el, &p, a, phi, pt, sp);
    }
    if let Some(rc2) = sp.inertia {
        let jac = el.jacobian();
        for &(xi, wt) in strain_rule.points() {
            let p = el.fields(q, xi);
            let t = el.tangent_length(&p);
            total -= t * t / p.ds * (0.5 * rc2 * wt * jac);
        }
    }
    total
}

fn pack(q: &[f64; NDOF], a: f64, phi: f64) -> SVector<f64, NEXT> {
    SVector::<f64, NEXT>::from_fn(|i, _| if i < NDOF { q[i] } else if i == NDOF { a } else { phi })
}

/// Energy, gradient and Hessian of the extra terms of an element in (q, a, φ), exact
/// (forward-mode AD over all 10 variables).
pub fn element_derivatives(el: &ElementContext, q: &[f64; NDOF], a: f64, phi: f64, points: &[PointState], sp: &StepParams, strain_rule: Rule) -> (f64, [f64; NEXT], [[f64; NEXT]; NEXT]) {
    let (e, g, h) = hessian(|v| element_energy(el, &std::array::from_fn(|i| v[i]), v[NDOF], v[NDOF + 1], points, sp, strain_rule), &pack(q, a, phi));
    (e, std::array::from_fn(|i| g[i]), std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])))
}

/// Energy and gradient of the extra terms (AD, first order).
pub fn element_gradient(el: &ElementContext, q: &[f64; NDOF], a: f64, phi: f64, points: &[PointState], sp: &StepParams, strain_rule: Rule) -> (f64, [f64; NEXT]) {
    let (e, g) = gradient(|v| element_energy(el, &std::array::from_fn(|i| v[i]), v[NDOF], v[NDOF + 1], points, sp, strain_rule), &pack(q, a, phi));
    (e, std::array::from_fn(|i| g[i]))
}

/// Evaluation of one point at a converged Newton state and its Table 1 update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// τ_γ = ⟨λ_γ − P_γ γ⟩, N/m.
    pub normal: f64,
    /// u (D2), m.
    pub displacement: f64,
    /// τ_⊥ = clip(τ*, −b, b) with the frozen bound, N/m.
    pub tangential: f64,
    /// Φ ≥ 0 (sliding) with the frozen bound.
    pub slip: bool,
    /// τ* = λ_⊥ + P_⊥ u, N/m.
    pub trial: f64,
}

/// Table 1, detection and evaluation at a point (f64), with the frozen multipliers and
/// bound of `pt`.
pub fn evaluate(el: &ElementContext, q: &[f64; NDOF], a: f64, phi: f64, pt: &PointState, sp: &StepParams) -> Evaluation {
    let p = el.fields(q, pt.xi);
    let normal = match (pt.pulley, el.gap(&p)) {
        (Some(_), Some(gap)) => (pt.lambda_n - sp.penalty * gap).max(0.0),
        _ => 0.0,
    };
    if pt.pulley.is_none() || pt.bound <= 0.0 || pt.friction_weight <= 0.0 {
        return Evaluation { normal, displacement: 0.0, tangential: 0.0, slip: false, trial: 0.0 };
    }
    let u = slip_displacement(el, &p, a, phi, pt, sp);
    let trial = pt.lambda_t + sp.tangential_penalty * u;
    let slip = trial.abs() >= pt.bound;
    let tangential = if slip { pt.bound * trial.signum() } else { trial };
    Evaluation { normal, displacement: u, tangential, slip, trial }
}

#[cfg(test)]
mod tests {
    //! The extra terms' AD gradient and Hessian against central finite differences
    //! (docs/fem-drive.md §5, §6), at random states of every region with penetrated
    //! contact, both stick and slip points, and inertia.
    use super::*;
    use crate::kinematics::TermParams;
    use crate::mesh::ElementGeometry;

    use crate::test_rng::Rng;

    #[test]
    fn ad_matches_finite_differences() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let sp = StepParams { penalty: 3.0e6, tangential_penalty: 2.0e6, driver_advance: 1.0e-3, radius: 0.08, inertia: Some(40.0) };
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut worst: f64 = 0.0;
        for (region, sa, h) in [
            (Region::UpperSpan, 0.40, 0.03),
            (Region::DrivenArc, 0.50, 0.02),
            (Region::LowerSpan, 1.10, 0.04),
            (Region::DriverArc, 1.20, 0.03),
            (Region::UpperSpan, 0.0, 0.03),
        ] {
            let el = ElementContext {
                geometry: ElementGeometry { sigma_a: sa, h, region },
                contour,
                params: TermParams { axial_stiffness: 2.0e4, weight: None, penalty: None, bending_stiffness: None },
                augmented: [false; 2],
            };
            for trial in 0..30 {
                let q = [
                    sa + 0.001 * rng.next(),
                    0.99 + 0.01 * rng.next(),
                    -2e-4 + 3e-4 * rng.next(),
                    -1e-3 + 2e-3 * rng.next(),
                    sa + h + 0.001 * rng.next(),
                    0.99 + 0.01 * rng.next(),
                    -2e-4 + 3e-4 * rng.next(),
                    -1e-3 + 2e-3 * rng.next(),
                ];
                let (a, phi) = (1.0e-3 + 1e-4 * rng.next(), 0.0125 + 1e-3 * rng.next());
                let points: Vec<PointState> = Rule::Simpson
                    .points()
                    .iter()
                    .map(|&(xi, w)| {
                        let sigma = el.sigma(xi);
                        let p = el.fields(&q, xi);
                        // half the points with a bound that makes them slip, half stick
                        PointState {
                            xi,
                            weight: w * el.jacobian(),
                            friction_weight: if xi.abs() == 1.0 { el.jacobian() } else { 0.0 },
                            sigma,
                            pulley: reachable_pulley(&contour, region, sigma),
                            travel_ref: 1.0e-3 * (1.0 + 0.1 * rng.next()),
                            s_ref: p.s - 1.0e-3 * (1.0 + 0.1 * rng.next()),
                            slope_ref: p.ds * (1.0 + 1e-3 * rng.next()),
                            metric: el.tangent_length(&p),
                            lambda_n: 50.0 * rng.next(),
                            lambda_t: 20.0 * (rng.next() - 0.5),
                            bound: if trial % 2 == 0 { 1e-3 } else { 1e6 },
                            slip: false,
                            normal: 0.0,
                            tangential: 0.0,
                            displacement: 0.0,
                        }
                    })
                    .collect();
                let (_, g, hm) = element_derivatives(&el, &q, a, phi, &points, &sp, Rule::Simpson);
                let x0 = pack(&q, a, phi);
                let f = |x: &SVector<f64, NEXT>| {
                    let qq: [f64; NDOF] = std::array::from_fn(|i| x[i]);
                    element_energy(&el, &qq, x[NDOF], x[NDOF + 1], &points, &sp, Rule::Simpson)
                };
                let gmax = g.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
                let hmax = hm.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
                for i in 0..NEXT {
                    // steps 1e-8 of the variable's scale: the terms are piecewise smooth
                    // (⟨·⟩ of D6, stick/slip of D7), and a step of 1e-7 crossed a kink
                    // in one random state; truncation O(d²) and round-off O(ε f/d) stay
                    // below 1e-6 of the largest entry
                    let d = 1e-8 * x0[i].abs().max(1e-3);
                    let mut xp = x0;
                    let mut xm = x0;
                    xp[i] += d;
                    xm[i] -= d;
                    let fd = (f(&xp) - f(&xm)) / (2.0 * d);
                    worst = worst.max((fd - g[i]).abs() / gmax);
                    assert!((fd - g[i]).abs() <= 1e-5 * gmax, "{region:?} grad {i}: AD {} FD {fd}", g[i]);
                    let qp: [f64; NDOF] = std::array::from_fn(|k| xp[k]);
                    let qm: [f64; NDOF] = std::array::from_fn(|k| xm[k]);
                    let (_, gp) = element_gradient(&el, &qp, xp[NDOF], xp[NDOF + 1], &points, &sp, Rule::Simpson);
                    let (_, gm) = element_gradient(&el, &qm, xm[NDOF], xm[NDOF + 1], &points, &sp, Rule::Simpson);
                    for j in 0..NEXT {
                        let fd = (gp[j] - gm[j]) / (2.0 * d);
                        assert!((fd - hm[j][i]).abs() <= 1e-5 * hmax, "{region:?} hess ({j},{i}): AD {} FD {fd}", hm[j][i]);
                    }
                }
            }
        }
        assert!(worst < 1e-5);
    }

    /// (D7) is the potential of the return mapping: its derivative in u is τ_⊥ of
    /// [`evaluate`], stick and slip.
    #[test]
    fn friction_potential_derivative_is_the_return_mapping() {
        for (lt, b, u) in [(3.0, 10.0, 1e-6), (3.0, 10.0, 1e-4), (-3.0, 10.0, -1e-4), (0.0, 2.0, 0.0)] {
            let k = 1.0e5;
            let tau = lt + k * u;
            let d = 1e-9;
            let fd = (friction_envelope(lt + k * (u + d), b, k) - friction_envelope(lt + k * (u - d), b, k)) / (2.0 * d);
            let expect = tau.clamp(-b, b);
            assert!((fd - expect).abs() < 1e-5 * b, "u {u}: {fd} vs {expect}");
        }
    }
}
