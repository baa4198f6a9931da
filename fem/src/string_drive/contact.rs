//! Coulomb contact of the moving string: per-integration-point state, the term units
//! of the normal contact (D6, [`AugmentedContact`]) and Coulomb friction (D7,
//! [`CoulombFriction`]) — each a [`MappedTerm`]: an energy at the trial state and the
//! augmented-Lagrangian return mapping of Table 1 (§6.1), committed after a converged
//! solve ([`commit`]) — and the element energy of the drive's extra terms with the
//! transport inertia (D8), with exact derivatives by AD (docs/fem-drive.md §2, §5, §6).
//!
//! The extra terms of an element depend on its N unknowns q — of any 1-D layout: the
//! terms read the element's centreline {s, ν} ([`ElementContext::centreline`], through
//! the augmented map where the element has one) — and on the two global step unknowns
//! a (material advance at σ = 0, D1) and φ (driven rotation increment, §4): N + 2
//! variables ([`extended_size`]; 10 for the string), differentiated together by
//! `Dual2SVec64<N + 2>`.

use drive::contour::{Contour, Pulley, Region};
use nalgebra::SVector;
use num_dual::{gradient, hessian};

use crate::element::ElementLayout;
use crate::formulation::terms::MappedTerm;
use crate::kinematics::{ElementContext, PointFields, Scalar, NDOF};
use crate::quadrature::Rule;

/// Variables of the extra element terms of an element with N unknowns: q (N), a, φ.
pub const fn extended_size(n: usize) -> usize {
    n + 2
}

/// Variables of the extra element terms of a string element: q (8), a, φ.
pub const NEXT: usize = extended_size(NDOF);

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

/// The augmented-Lagrangian normal contact (D6) as a term unit: per point the
/// multiplier λ_γ and the weight w_γ of its [`PointState`]; energy
/// w_γ ⟨λ_γ − P_γ γ⟩²/(2P_γ) on the gap's domain, return mapping τ_γ = ⟨λ_γ − P_γ γ⟩
/// (Table 1; with λ_γ kept 0, the plain penalty).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AugmentedContact {
    /// P_γ, N/m².
    pub penalty: f64,
}

impl MappedTerm<2> for AugmentedContact {
    type State = PointState;
    /// τ_γ, N/m.
    type Mapped = f64;

    #[inline]
    fn point_energy<D: Scalar>(&self, el: &ElementContext, p: &PointFields<D>, _globals: &[D; 2], pt: &PointState) -> Option<D> {
        if pt.weight > 0.0 {
            if let Some(gap) = el.gap(p) {
                let t = gap * (-self.penalty) + pt.lambda_n;
                if t.re() > 0.0 {
                    return Some(t * t * (0.5 / self.penalty * pt.weight));
                }
            }
        }
        None
    }

    fn map(&self, el: &ElementContext, p: &PointFields<f64>, _globals: &[f64; 2], pt: &PointState) -> f64 {
        match pt.pulley {
            Some(_) => crate::formulation::augmented_traction(pt.lambda_n, self.penalty, el.gap(p)),
            None => 0.0,
        }
    }
}

/// Coulomb friction (D7) as a term unit: per point the multiplier λ_⊥, the slip bound
/// b = μ τ̂_γ frozen during a solve, the upstream references of the slip displacement
/// u (D2) and the weight w_⊥ of its [`PointState`]; energy w_⊥ F_b(λ_⊥ + P_⊥ u), whose
/// derivative in u is the return mapping τ_⊥ = clip(λ_⊥ + P_⊥ u, −b, b) (Table 1). The
/// globals are the step's (a, φ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoulombFriction {
    /// P_⊥, N/m².
    pub tangential_penalty: f64,
    /// Drum surface advance of the driver over the step, R ω₁ Δt, m.
    pub driver_advance: f64,
    /// R, m.
    pub radius: f64,
}

/// The friction return mapping at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slip {
    /// u (D2), m.
    pub displacement: f64,
    /// τ* = λ_⊥ + P_⊥ u, N/m.
    pub trial: f64,
    /// τ_⊥ = clip(τ*, −b, b), N/m.
    pub tangential: f64,
    /// Φ ≥ 0 (sliding) with the frozen bound.
    pub slip: bool,
}

impl CoulombFriction {
    /// Tangential relative displacement over the step (D2): the particle at σ at
    /// t_{n+1}, s = S̃_{n+1}(σ) − a in the gauge of step n, sat at σ' = S̃_n⁻¹(s) at t_n;
    /// with the inverse linearised about the upstream reference point σ − d_ref,
    /// σ − σ' = d_ref − (S̃_{n+1}(σ) − a − S̃_n(σ − d_ref)) / ∂σS̃_n(σ − d_ref), and
    /// u = |∂σr|_n (σ − σ') − R Δθ_k, R Δθ₁ = `driver_advance`, Δθ₂ = φ. Linear in
    /// (S̃_{n+1}(σ), a, φ): the friction force acts on the material only, upwind.
    #[inline]
    pub fn slip_displacement<D: Scalar>(&self, p: &PointFields<D>, &[a, phi]: &[D; 2], pt: &PointState) -> D {
        let travel = ((p.s - a - pt.s_ref) * (-1.0 / pt.slope_ref) + pt.travel_ref) * pt.metric;
        match pt.pulley {
            Some(Pulley::Driver) => travel - self.driver_advance,
            Some(Pulley::Driven) => travel - phi * self.radius,
            None => travel * 0.0,
        }
    }
}

impl MappedTerm<2> for CoulombFriction {
    type State = PointState;
    type Mapped = Slip;

    #[inline]
    fn point_energy<D: Scalar>(&self, _el: &ElementContext, p: &PointFields<D>, globals: &[D; 2], pt: &PointState) -> Option<D> {
        (pt.bound > 0.0 && pt.friction_weight > 0.0).then(|| {
            let u = self.slip_displacement(p, globals, pt);
            let tau = u * self.tangential_penalty + pt.lambda_t;
            friction_envelope(tau, pt.bound, self.tangential_penalty) * pt.friction_weight
        })
    }

    fn map(&self, _el: &ElementContext, p: &PointFields<f64>, globals: &[f64; 2], pt: &PointState) -> Slip {
        if pt.pulley.is_none() || pt.bound <= 0.0 || pt.friction_weight <= 0.0 {
            return Slip { displacement: 0.0, trial: 0.0, tangential: 0.0, slip: false };
        }
        let u = self.slip_displacement(p, globals, pt);
        let trial = pt.lambda_t + self.tangential_penalty * u;
        let slip = trial.abs() >= pt.bound;
        let tangential = if slip { pt.bound * trial.signum() } else { trial };
        Slip { displacement: u, trial, tangential, slip }
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

/// The drive's contact units of a step, picked from its parameters: the normal contact
/// at every point within reach of a pulley, friction where a point carries a slip bound
/// (μ τ̂_γ > 0) — the transport inertia (D8, ρc² if the scene asks for it) is
/// integrated beside them by [`element_energy`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveTerms {
    /// Normal contact (D6).
    pub contact: AugmentedContact,
    /// Friction (D7).
    pub friction: CoulombFriction,
}

impl DriveTerms {
    /// The units of a step.
    pub fn new(sp: &StepParams) -> DriveTerms {
        DriveTerms {
            contact: AugmentedContact { penalty: sp.penalty },
            friction: CoulombFriction { tangential_penalty: sp.tangential_penalty, driver_advance: sp.driver_advance, radius: sp.radius },
        }
    }

    /// The contact terms at one point, weighted (J): w_γ ψ_γ (D6) on the gap's domain,
    /// w_⊥ ψ_⊥ (D7) where the point carries a slip bound.
    #[inline]
    pub fn point_energy<D: Scalar>(&self, el: &ElementContext, p: &PointFields<D>, globals: &[D; 2], pt: &PointState) -> D {
        let mut f = p.nu * 0.0;
        if pt.pulley.is_none() {
            return f;
        }
        if let Some(e) = self.contact.point_energy(el, p, globals, pt) {
            f += e;
        }
        if let Some(e) = self.friction.point_energy(el, p, globals, pt) {
            f += e;
        }
        f
    }

    /// Table 1, detection and evaluation at a point (f64), with the frozen multipliers
    /// and bound of `pt`: both units' return mappings.
    pub fn evaluate(&self, el: &ElementContext, q: &[f64; NDOF], a: f64, phi: f64, pt: &PointState) -> Evaluation {
        let p = el.fields(q, pt.xi);
        let normal = self.contact.map(el, &p, &[a, phi], pt);
        let Slip { displacement, trial, tangential, slip } = self.friction.map(el, &p, &[a, phi], pt);
        Evaluation { normal, displacement, tangential, slip, trial }
    }
}

/// True if the element has a term to evaluate (a contact-capable point or inertia).
pub fn active(points: &[PointState], sp: &StepParams) -> bool {
    sp.inertia.is_some() || points.iter().any(|p| p.pulley.is_some())
}

/// The extra energy of one element of `layout` with unknowns q, J: Σ over its contact
/// points of w ψ (D6, D7), minus the transport kinetic energy (D8) integrated with the
/// strain rule `strain_rule` — all on the element's centreline {s, ν}.
#[allow(clippy::too_many_arguments)]
pub fn element_energy<D: Scalar, const N: usize>(
    layout: ElementLayout,
    el: &ElementContext,
    q: &[D; N],
    a: D,
    phi: D,
    points: &[PointState],
    sp: &StepParams,
    strain_rule: Rule,
) -> D {
    let q = &el.centreline(layout, q);
    let terms = DriveTerms::new(sp);
    let globals = [a, phi];
    let mut total = a * 0.0;
    for pt in points {
        if pt.pulley.is_none() {
            continue;
        }
        let p = el.fields(q, pt.xi);
        total += terms.point_energy(el, &p, &globals, pt);
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

/// (q, a, φ) of an element with N unknowns as one vector of X = N + 2.
fn pack<const N: usize, const X: usize>(q: &[f64; N], a: f64, phi: f64) -> SVector<f64, X> {
    debug_assert_eq!(X, extended_size(N));
    SVector::<f64, X>::from_fn(|i, _| if i < N { q[i] } else if i == N { a } else { phi })
}

/// Energy, gradient and Hessian of the extra terms of an element of `layout` in
/// (q, a, φ), exact (forward-mode AD over all X = N + 2 variables).
#[allow(clippy::too_many_arguments)]
pub fn element_derivatives<const N: usize, const X: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], a: f64, phi: f64, points: &[PointState], sp: &StepParams, strain_rule: Rule) -> (f64, [f64; X], [[f64; X]; X]) {
    let (e, g, h) = hessian(|v| element_energy(layout, el, &std::array::from_fn::<_, N, _>(|i| v[i]), v[N], v[N + 1], points, sp, strain_rule), &pack::<N, X>(q, a, phi));
    (e, std::array::from_fn(|i| g[i]), std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])))
}

/// Energy and gradient of the extra terms (AD, first order).
#[allow(clippy::too_many_arguments)]
pub fn element_gradient<const N: usize, const X: usize>(layout: ElementLayout, el: &ElementContext, q: &[f64; N], a: f64, phi: f64, points: &[PointState], sp: &StepParams, strain_rule: Rule) -> (f64, [f64; X]) {
    let (e, g) = gradient(|v| element_energy(layout, el, &std::array::from_fn::<_, N, _>(|i| v[i]), v[N], v[N + 1], points, sp, strain_rule), &pack::<N, X>(q, a, phi));
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

/// Table 1's update of a point after a converged solve from its evaluation `ev`: the
/// multipliers λ_γ ← τ_γ (augmented Lagrangian; kept 0 for the penalty method) and
/// λ_⊥ ← τ_⊥ under the new bound (0 where the point carries no friction), the bound
/// b ← μ τ_γ, and the point's output (tractions, u, slip). Returns the largest change
/// of λ_γ, λ_⊥ and b (N/m) and whether the point switched between stick and slip.
pub fn commit(pt: &mut PointState, ev: &Evaluation, mu: f64, augmented: bool) -> (f64, bool) {
    let new_n = if augmented { ev.normal } else { 0.0 };
    let new_t = if !augmented || pt.bound <= 0.0 || pt.friction_weight <= 0.0 {
        0.0
    } else if ev.slip {
        mu * ev.normal * ev.trial.signum()
    } else {
        ev.trial
    };
    let new_b = mu * ev.normal;
    let change = (new_n - pt.lambda_n).abs().max((new_t - pt.lambda_t).abs()).max((new_b - pt.bound).abs());
    let switched = ev.slip != pt.slip && pt.bound > 0.0;
    pt.normal = ev.normal;
    pt.tangential = ev.tangential;
    pt.displacement = ev.displacement;
    pt.slip = ev.slip && pt.bound > 0.0;
    pt.lambda_n = new_n;
    pt.lambda_t = new_t;
    pt.bound = new_b;
    (change, switched)
}

#[cfg(test)]
pub(crate) mod tests {
    //! The extra terms' AD gradient and Hessian against central finite differences
    //! (docs/fem-drive.md §5, §6), at random states of every region with penetrated
    //! contact, both stick and slip points, and inertia.
    use super::*;
    use crate::element::STRING;
    use crate::kinematics::TermParams;
    use crate::mesh::ElementGeometry;

    use crate::test_rng::Rng;

    /// An element of `region` starting at σ = `sa`, of length `h`.
    fn context(contour: Contour, region: Region, sa: f64, h: f64) -> ElementContext {
        ElementContext {
            geometry: ElementGeometry { sigma_a: sa, h, region },
            contour,
            params: TermParams { axial_stiffness: 2.0e4, weight: None, penalty: None, bending_stiffness: None },
            augmented: [false; 2],
        }
    }

    /// A contact point at ξ of `el` (rule weights w, w_f) with references and multipliers
    /// drawn around the state `q`, and a slip bound that makes it slip (1e-3 N/m) or
    /// stick (1e6 N/m).
    pub(crate) fn random_point(el: &ElementContext, q: &[f64; NDOF], (xi, w, wf): (f64, f64, f64), pulley: Option<Pulley>, rng: &mut Rng, slipping: bool) -> PointState {
        let p = el.fields(q, xi);
        PointState {
            xi,
            weight: w * el.jacobian(),
            friction_weight: wf * el.jacobian(),
            sigma: el.sigma(xi),
            pulley,
            travel_ref: 1.0e-3 * (1.0 + 0.1 * rng.next()),
            s_ref: p.s - 1.0e-3 * (1.0 + 0.1 * rng.next()),
            slope_ref: p.ds * (1.0 + 1e-3 * rng.next()),
            metric: el.tangent_length(&p),
            lambda_n: 50.0 * rng.next(),
            lambda_t: 20.0 * (rng.next() - 0.5),
            bound: if slipping { 1e-3 } else { 1e6 },
            slip: false,
            normal: 0.0,
            tangential: 0.0,
            displacement: 0.0,
        }
    }

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
            let el = context(contour, region, sa, h);
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
                        // half the points with a bound that makes them slip, half stick
                        let wf = if xi.abs() == 1.0 { 1.0 } else { 0.0 };
                        random_point(&el, &q, (xi, w, wf), reachable_pulley(&contour, region, sigma), &mut rng, trial % 2 == 0)
                    })
                    .collect();
                let (_, g, hm) = element_derivatives::<NDOF, NEXT>(STRING, &el, &q, a, phi, &points, &sp, Rule::Simpson);
                let x0 = pack::<NDOF, NEXT>(&q, a, phi);
                let f = |x: &SVector<f64, NEXT>| {
                    let qq: [f64; NDOF] = std::array::from_fn(|i| x[i]);
                    element_energy(STRING, &el, &qq, x[NDOF], x[NDOF + 1], &points, &sp, Rule::Simpson)
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
                    let (_, gp) = element_gradient::<NDOF, NEXT>(STRING, &el, &qp, xp[NDOF], xp[NDOF + 1], &points, &sp, Rule::Simpson);
                    let (_, gm) = element_gradient::<NDOF, NEXT>(STRING, &el, &qm, xm[NDOF], xm[NDOF + 1], &points, &sp, Rule::Simpson);
                    for j in 0..NEXT {
                        let fd = (gp[j] - gm[j]) / (2.0 * d);
                        assert!((fd - hm[j][i]).abs() <= 1e-5 * hmax, "{region:?} hess ({j},{i}): AD {} FD {fd}", hm[j][i]);
                    }
                }
            }
        }
        assert!(worst < 1e-5);
    }

    /// Each unit's energy is the potential of its return mapping: at points of every
    /// region, ∂/∂a of the friction energy is w_⊥ τ_⊥ ∂u/∂a = w_⊥ τ_⊥ |∂σr|/∂σS̃_ref
    /// (stick and slip), and ∂/∂ν of the normal energy is −w_γ τ_γ ∂γ/∂ν (central
    /// differences, step 1e-9 of the variable: truncation and round-off ≤ 1e-6 of the
    /// traction); [`commit`] takes the mapped tractions into the multipliers.
    #[test]
    fn units_are_potentials_of_their_return_mappings() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let sp = StepParams { penalty: 3.0e6, tangential_penalty: 2.0e6, driver_advance: 1.0e-3, radius: 0.08, inertia: None };
        let terms = DriveTerms::new(&sp);
        let mut rng = Rng(0x0bad_cafe_1234_5678);
        let (mut stick, mut slip) = (0, 0);
        for (region, sa, h) in [(Region::DrivenArc, 0.50, 0.02), (Region::DriverArc, 1.20, 0.03)] {
            let el = context(contour, region, sa, h);
            for trial in 0..20 {
                let q = [sa, 1.0, -1e-4 * rng.next(), 0.0, sa + h, 1.0, -1e-4 * rng.next(), 0.0];
                let xi = 1.0;
                let p = el.fields(&q, xi);
                let pt = random_point(&el, &q, (xi, 1.0, 1.0), region.pulley(), &mut rng, trial % 2 == 0);
                let (a, phi) = (1.0e-3 * rng.next(), 0.0125);
                let ev = terms.evaluate(&el, &q, a, phi, &pt);
                // friction: d/da
                let d = 1e-9;
                let ef = |a: f64| terms.friction.point_energy(&el, &p, &[a, phi], &pt).unwrap();
                let fd = (ef(a + d) - ef(a - d)) / (2.0 * d);
                let expect = pt.friction_weight * ev.tangential * pt.metric / pt.slope_ref;
                assert!((fd - expect).abs() <= 1e-6 * pt.bound.min(ev.tangential.abs().max(1.0)) * pt.friction_weight, "friction: FD {fd}, mapped {expect}");
                if ev.slip {
                    slip += 1;
                } else {
                    stick += 1;
                }
                // normal: d/dν at the end node
                let shifted = |dn: f64| {
                    let mut qq = q;
                    qq[6] += dn;
                    el.fields(&qq, xi)
                };
                let en = |dn: f64| terms.contact.point_energy(&el, &shifted(dn), &[a, phi], &pt).unwrap_or(0.0);
                let gap = |dn: f64| el.gap(&shifted(dn)).unwrap();
                let fd = (en(d) - en(-d)) / (2.0 * d);
                let expect = -pt.weight * ev.normal * (gap(d) - gap(-d)) / (2.0 * d);
                assert!(ev.normal > 0.0, "the point is pressed into the drum");
                assert!((fd - expect).abs() <= 1e-6 * ev.normal * pt.weight, "normal: FD {fd}, mapped {expect}");
                // commit: the augmented multipliers take the mapped tractions
                let mut committed = pt;
                let (change, _) = commit(&mut committed, &ev, 0.4, true);
                assert_eq!((committed.lambda_n, committed.bound, committed.normal), (ev.normal, 0.4 * ev.normal, ev.normal));
                assert!(change >= (ev.normal - pt.lambda_n).abs());
            }
        }
        assert!(stick > 0 && slip > 0, "stick {stick}, slip {slip}");
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
