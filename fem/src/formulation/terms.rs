//! Energy terms as units, one per effect (issue 11, "One MEL element core";
//! docs/fem-string.md §4, docs/fem-rod.md K7, docs/fem-drive.md D8).
//!
//! A term is an [`EnergyTerm`]: its integration rule and its energy per unit contour
//! length σ over the point values (S, ∂σS, ν, ∂σν, ∂²σν) of [`PointFields`], generic over
//! the number type so that forward-mode AD differentiates it exactly. A term owns its
//! parameters; which terms an element carries is decided once from the effects
//! ([`TermParams`], built from [`crate::FemProblem`]'s `EffectSet` and section data) by
//! [`StandardTerms::new`]. The integrators (the f64 energy, the per-point gradient and
//! Hessian paths of `formulation`) walk a term list through a [`TermVisitor`], so a new
//! effect is a new unit, not a new branch in every integrator.
//!
//! An effect is a [`PointDensity`]; a formulation gives it a rule ([`Integrated`]),
//! which makes it an [`EnergyTerm`].
//!
//! | unit | effect | density, J/m |
//! |---|---|---|
//! | [`Strain`] | membrane strain (F8) | W(λ) ∂σS |
//! | [`Gravity`] | gravity potential (F9) | ρg y ∂σS |
//! | [`PenaltyContact`] | normal penalty contact (F10) | ½ P ⟨−γ⟩² |
//! | [`Bending`] | Kirchhoff bending (K7) | ½ EI θ_σ² / ∂σS |
//! | [`TransportInertia`] | −T of the steady drive (D8), belt speed c an unknown (integrates itself) | −ρc² \|∂σr\|² / (2 ∂σS) |
//!
//! A term may carry state from one converged step to the next ([`HistoryTerm`], held
//! per integration point by [`TermHistory`]): the hook the shell's elastic interlayer
//! needs for its advected deformation (spec eqs. 40, 41). A load with a return mapping
//! — Coulomb friction, the augmented-Lagrangian contact — is a [`MappedTerm`]: its
//! energy also depends on global unknowns of the step and on a per-point state frozen
//! during a solve and committed from the mapping after it
//! (`string_drive::contact::{AugmentedContact, CoulombFriction}`).

use std::fmt::Debug;

use num_dual::{Dual2_64, Dual64};

use super::{ElementContext, PointFields, Rule, Scalar, TermParams, TermRules, NDOF};

/// One energy term of an element — one effect — over point values.
pub trait EnergyTerm<D: Scalar> {
    /// The term's integration rule on ξ ∈ [−1, 1].
    fn rule(&self) -> Rule;

    /// Energy per unit contour length σ at the `point`-th point of [`Self::rule`], J/m,
    /// from the point values `p`.
    fn density(&self, el: &ElementContext, p: &PointFields<D>, point: usize) -> D;

    /// The term's share of the element energy at that point, J, for the rule weight `wt`
    /// and the element Jacobian `jac` = dσ/dξ: `density × (wt · jac)`. A term whose
    /// density carries a constant factor may fold the weight into it.
    #[inline]
    fn point_energy(&self, el: &ElementContext, p: &PointFields<D>, point: usize, wt: f64, jac: f64) -> D {
        self.density(el, p, point) * (wt * jac)
    }
}

/// Something that walks a term list (an integrator): called once per term, statically
/// dispatched.
pub trait TermVisitor<D: Scalar> {
    /// Integrate (or otherwise use) one term.
    fn visit<T: EnergyTerm<D>>(&mut self, term: &T);
}

/// The energy density of one effect at a point, J per unit contour length σ, over the
/// point values — what a term is before a formulation gives it an integration rule
/// ([`Integrated`]).
pub trait PointDensity<D: Scalar> {
    /// Energy per unit σ at the point with values `p`, J/m.
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D;
}

/// An effect's density with the integration rule a formulation gives it: an
/// [`EnergyTerm`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integrated<T> {
    /// Integration rule.
    pub rule: Rule,
    /// The effect.
    pub effect: T,
}

impl<D: Scalar, T: PointDensity<D>> EnergyTerm<D> for Integrated<T> {
    fn rule(&self) -> Rule {
        self.rule
    }

    #[inline]
    fn density(&self, el: &ElementContext, p: &PointFields<D>, _point: usize) -> D {
        self.effect.density(el, p)
    }
}

/// Membrane strain energy U (F8): W(λ) ∂σS with the formulation's strain energy density
/// W(λ) per unstretched length (J/m) as a function of the stretch λ = |∂σr|/∂σS (F4).
#[derive(Debug, Clone, Copy)]
pub struct Strain<W>(pub W);

impl<D: Scalar, W: Fn(D) -> D> PointDensity<D> for Strain<W> {
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D {
        (self.0)(el.stretch(p)) * p.ds
    }
}

/// Gravity potential W (F9): ρg y ∂σS, with ρg in N per unstretched metre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity(pub f64);

impl<D: Scalar> PointDensity<D> for Gravity {
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D {
        el.height(p) * p.ds * self.0
    }
}

/// Penalty normal contact V_γ (F10): ½ P ⟨−γ⟩² with the penalty factor P in N/m² and the
/// gap γ of [`ElementContext::gap`] (zero where no pulley can be reached).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PenaltyContact(pub f64);

impl<D: Scalar> PointDensity<D> for PenaltyContact {
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D {
        match el.gap(p) {
            Some(gap) if gap.re() < 0.0 => gap * gap * (0.5 * self.0),
            _ => D::zero(),
        }
    }
}

/// The augmented-Lagrangian normal traction of Table 1 (§6.1, docs/fem-drive.md (D6)):
/// ⟨λ − Pγ⟩₊ for the multiplier λ (N/m), the penalty P (N/m²) and the gap γ (m, > 0
/// separated); 0 where no gap is defined. With λ = 0 the penalty's P⟨−γ⟩. It is also the
/// first-order (Uzawa) update of the multiplier, λ ← ⟨λ − Pγ⟩₊.
#[inline]
pub fn augmented_traction(lambda: f64, penalty: f64, gap: Option<f64>) -> f64 {
    gap.map_or(0.0, |g| (lambda - penalty * g).max(0.0))
}

/// Normal-contact multipliers λ_γ (N per unit contour length) of the augmented
/// Lagrangian as a field over the contour coordinate σ (docs/fem-cosserat.md §12.5):
/// piecewise linear through the values at the contact rule's points of the mesh they were
/// updated on, so they survive a refit of the mesh (the refitted mesh's points read the
/// field where they are). Open ([`Self::from_samples`], the one-pulley layout, whose σ
/// runs from 0 to the end section): 0 outside the samples. Periodic
/// ([`Self::periodic`], a closed loop of contour length L_c): σ is read modulo L_c and
/// the field runs on from the last sample to the first one + L_c.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactMultipliers {
    /// (σ, λ), strictly increasing in σ.
    samples: Vec<(f64, f64)>,
    /// L_c of a closed loop; `None`: open.
    period: Option<f64>,
}

impl ContactMultipliers {
    /// The open field through `samples` (σ, λ): sorted by σ, values at equal σ (an
    /// element edge that is a point of two elements) averaged.
    ///
    /// # Panics
    /// Never; a non-finite sample is the caller's error and is dropped.
    pub fn from_samples(mut samples: Vec<(f64, f64)>) -> ContactMultipliers {
        samples.retain(|s| s.0.is_finite() && s.1.is_finite());
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out: Vec<(f64, f64, usize)> = Vec::with_capacity(samples.len());
        for (sigma, lambda) in samples {
            match out.last_mut() {
                Some(last) if last.0 == sigma => {
                    last.1 += lambda;
                    last.2 += 1;
                }
                _ => out.push((sigma, lambda, 1)),
            }
        }
        ContactMultipliers { samples: out.into_iter().map(|(s, l, n)| (s, l / n as f64)).collect(), period: None }
    }

    /// The periodic field of a closed loop of contour length `period` (m, > 0) through
    /// `samples` (σ, λ), σ taken modulo `period` (a non-positive or non-finite period
    /// gives the open field).
    pub fn periodic(samples: Vec<(f64, f64)>, period: f64) -> ContactMultipliers {
        if !(period > 0.0 && period.is_finite()) {
            return ContactMultipliers::from_samples(samples);
        }
        let wrapped = samples.into_iter().map(|(s, l)| (s.rem_euclid(period), l)).collect();
        ContactMultipliers { period: Some(period), ..ContactMultipliers::from_samples(wrapped) }
    }

    /// λ(σ), N/m: linear between the samples; open: 0 outside them; periodic: σ modulo
    /// L_c, linear from the last sample to the first one + L_c.
    pub fn at(&self, sigma: f64) -> f64 {
        let (Some(&first), Some(&last)) = (self.samples.first(), self.samples.last()) else { return 0.0 };
        let sigma = self.period.map_or(sigma, |l| sigma.rem_euclid(l));
        let k = self.samples.partition_point(|s| s.0 <= sigma);
        if k == 0 || k == self.samples.len() {
            if let Some(l) = self.period {
                // the wrap-around segment, last → first + L_c
                let (s0, s1) = (last.0, first.0 + l);
                let x = if sigma >= last.0 { sigma } else { sigma + l };
                return if s1 > s0 { last.1 + (first.1 - last.1) * (x - s0) / (s1 - s0) } else { last.1 };
            }
            return if k == self.samples.len() && last.0 == sigma { last.1 } else { 0.0 };
        }
        let ((s0, l0), (s1, l1)) = (self.samples[k - 1], self.samples[k]);
        l0 + (l1 - l0) * (sigma - s0) / (s1 - s0)
    }

    /// The samples (σ, λ).
    pub fn samples(&self) -> &[(f64, f64)] {
        &self.samples
    }

    /// The largest |λ₁(σ) − λ₂(σ)| over both fields' samples, N/m.
    pub fn max_change(&self, other: &ContactMultipliers) -> f64 {
        self.samples.iter().chain(&other.samples).map(|&(s, _)| (self.at(s) - other.at(s)).abs()).fold(0.0, f64::max)
    }
}

/// Augmented-Lagrangian normal contact (Table 1, column 1; docs/fem-drive.md (D6)) with
/// the multipliers as a field over σ: ⟨λ(σ) − Pγ⟩₊² / (2P) per unit σ, whose derivative in
/// the gap is −⟨λ − Pγ⟩₊ — the penalty V_γ of [`PenaltyContact`] for λ ≡ 0 (the same
/// energy, ½P⟨−γ⟩²). Equivalently the penalty on the gap shifted by λ/P.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AugmentedPenalty<'a> {
    /// P, N/m².
    pub penalty: f64,
    /// λ(σ).
    pub multipliers: &'a ContactMultipliers,
}

impl<D: Scalar> PointDensity<D> for AugmentedPenalty<'_> {
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D {
        match el.gap(p) {
            Some(gap) => {
                let t = gap * (-self.penalty) + self.multipliers.at(p.sigma);
                if t.re() > 0.0 {
                    t * t * (0.5 / self.penalty)
                } else {
                    D::zero()
                }
            }
            None => D::zero(),
        }
    }
}

/// Kirchhoff bending energy U_b (docs/fem-rod.md K7): ½ EI θ_σ² / ∂σS with EI in N·m²
/// and the angle rate θ_σ of [`ElementContext::angle_rate`] (needs ∂²σν).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bending(pub f64);

impl<D: Scalar> PointDensity<D> for Bending {
    fn density(&self, el: &ElementContext, p: &PointFields<D>) -> D {
        let k = el.angle_rate(p);
        k * k / p.ds * (0.5 * self.0)
    }
}

/// A point density's value, gradient and Hessian over the point values
/// u = (∂σS, ν, ∂σν, ∂²σν) (in this order), summed over the terms at one point with each
/// term's weight: what the Kirchhoff rod's element derivatives are projected from
/// (docs/fem-rod.md §4). Each unit fills in its own share ([`Strain::add_jet`],
/// [`Gravity::add_jet`], [`PenaltyContact::add_jet`], [`Bending::add_jet`]) by the chain
/// rule through the one or two intermediate values its density is a function of, with
/// AD only where a function is the formulation's (W(λ)) or the contour's (the gap, the
/// height) — one variable at a time. Equal to `Dual2SVec64<4>` AD of the density to
/// round-off (tested in `formulation`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointJet {
    /// Energy, J (the weights included).
    pub value: f64,
    /// ∂/∂u.
    pub gradient: [f64; 4],
    /// ∂²/∂u², symmetric.
    pub hessian: [[f64; 4]; 4],
}

impl PointJet {
    /// Adds `s` × (f, ∂f/∂uᵢ, ∂²f/∂uᵢ∂uⱼ) of a density f of (∂σS, x, y) where x, y are
    /// the point values number `ix`, `iy` (the Hessian's off-diagonal entries
    /// mirrored): the shared last step of the units' chain rules.
    #[inline]
    #[allow(clippy::too_many_arguments)] // the 6 derivatives of f(∂σS, x, y), named as in the formulas
    fn add_ds_xy(&mut self, s: f64, f: f64, [f_s, f_x, f_y]: [f64; 3], [f_ss, f_sx, f_sy]: [f64; 3], [f_xx, f_xy, f_yy]: [f64; 3], (ix, iy): (usize, usize)) {
        self.value += s * f;
        self.gradient[0] += s * f_s;
        self.gradient[ix] += s * f_x;
        self.gradient[iy] += s * f_y;
        let h = &mut self.hessian;
        h[0][0] += s * f_ss;
        h[0][ix] += s * f_sx;
        h[ix][0] += s * f_sx;
        h[0][iy] += s * f_sy;
        h[iy][0] += s * f_sy;
        h[ix][ix] += s * f_xx;
        h[ix][iy] += s * f_xy;
        h[iy][ix] += s * f_xy;
        h[iy][iy] += s * f_yy;
    }
}

/// The point fields with ν as the one dual variable of `D` (the others constants): for
/// the units whose contour functions (the gap, the height) are differentiated in ν alone.
#[inline]
fn nu_variable<D: Scalar>(p: &PointFields<f64>, nu: D) -> PointFields<D> {
    PointFields { sigma: p.sigma, s: D::from(p.s), ds: D::from(p.ds), nu, dnu: D::from(p.dnu), d2nu: D::from(p.d2nu) }
}

impl<W: Fn(Dual2_64) -> Dual2_64> Strain<W> {
    /// Adds `s` × the jet of W(λ) ∂σS ([`PointJet`]): with t = |∂σr| = √(a² + b²),
    /// a = 1 + αν, b = ∂σν, λ = t/∂σS and W, W′, W″ at λ (AD in λ alone),
    /// f_S = W − λW′, f_t = W′, f_SS = λ²W″/∂σS, f_St = −λW″/∂σS, f_tt = W″/∂σS; then
    /// through t: t_ν = αa/t, t_b = b/t, t_νν = α²b²/t³, t_νb = −αab/t³, t_bb = a²/t³.
    #[inline]
    pub fn add_jet(&self, el: &ElementContext, p: &PointFields<f64>, s: f64, jet: &mut PointJet) {
        let alpha = el.alpha();
        let (a, b, ds) = (1.0 + alpha * p.nu, p.dnu, p.ds);
        let t = (a * a + b * b).sqrt();
        let lambda = t / ds;
        let w = (self.0)(Dual2_64::from_re(lambda).derivative());
        let (w0, w1, w2) = (w.re, w.v1, w.v2);
        let (f_t, f_tt) = (w1, w2 / ds);
        let (t_n, t_b) = (alpha * a / t, b / t);
        let t3 = t * t * t;
        let (t_nn, t_nb, t_bb) = (alpha * alpha * b * b / t3, -alpha * a * b / t3, a * a / t3);
        let f_st = -lambda * f_tt;
        jet.add_ds_xy(
            s,
            w0 * ds,
            [w0 - lambda * w1, f_t * t_n, f_t * t_b],
            [lambda * lambda * f_tt, f_st * t_n, f_st * t_b],
            [f_tt * t_n * t_n + f_t * t_nn, f_tt * t_n * t_b + f_t * t_nb, f_tt * t_b * t_b + f_t * t_bb],
            (1, 2),
        );
    }
}

impl Gravity {
    /// Adds `s` × the jet of ρg y ∂σS ([`PointJet`]): y = g_y + ν n_{g,y} is linear in ν
    /// (y and n_{g,y} by one `Dual64` in ν through [`ElementContext::height`]).
    #[inline]
    pub fn add_jet(&self, el: &ElementContext, p: &PointFields<f64>, s: f64, jet: &mut PointJet) {
        let y = el.height(&nu_variable(p, Dual64::from_re(p.nu).derivative()));
        let (y, n_y) = (y.re * self.0, y.eps * self.0);
        jet.value += s * y * p.ds;
        jet.gradient[0] += s * y;
        jet.gradient[1] += s * n_y * p.ds;
        jet.hessian[0][1] += s * n_y;
        jet.hessian[1][0] += s * n_y;
    }
}

impl PenaltyContact {
    /// Adds `s` × the jet of ½P⟨−γ⟩² ([`PointJet`]): a function of ν alone, differentiated
    /// by one `Dual2_64` in ν through the unit's own density (and so the gap of
    /// [`ElementContext::gap`]).
    #[inline]
    pub fn add_jet(&self, el: &ElementContext, p: &PointFields<f64>, s: f64, jet: &mut PointJet) {
        let f: Dual2_64 = self.density(el, &nu_variable(p, Dual2_64::from_re(p.nu).derivative()));
        jet.value += s * f.re;
        jet.gradient[1] += s * f.v1;
        jet.hessian[1][1] += s * f.v2;
    }
}

impl Bending {
    /// Adds `s` × the jet of ½EI θ_σ²/∂σS ([`PointJet`]) by the chain rule through
    /// θ_σ = N/D (K3) with N = a e − αa² − 2αb², D = a² + b², a = 1 + αν, b = ∂σν,
    /// e = ∂²σν: θ_x = (N_x − θD_x)/D, θ_xy = (N_xy − θ_x D_y − θ_y D_x − θD_xy)/D over
    /// (a, b, e), ∂/∂ν = α ∂/∂a; then with c = EI, f_θ = cθ/∂σS, f_θθ = c/∂σS,
    /// f_S = −cθ²/(2∂σS²), f_Sθ = −cθ/∂σS², f_SS = cθ²/∂σS³.
    #[inline]
    pub fn add_jet(&self, el: &ElementContext, p: &PointFields<f64>, s: f64, jet: &mut PointJet) {
        let alpha = el.alpha();
        let (a, b, e, ds) = (1.0 + alpha * p.nu, p.dnu, p.d2nu, p.ds);
        let d = a * a + b * b;
        let k = (a * e - alpha * a * a - 2.0 * alpha * b * b) / d;
        // first derivatives over (a, b, e); N_aa = −2α, N_bb = −4α, N_ae = 1, D_aa = D_bb = 2
        let (n_a, n_b, n_e) = (e - 2.0 * alpha * a, -4.0 * alpha * b, a);
        let (d_a, d_b) = (2.0 * a, 2.0 * b);
        let k_a = (n_a - k * d_a) / d;
        let k_b = (n_b - k * d_b) / d;
        let k_e = n_e / d;
        let k_aa = (-2.0 * alpha - 2.0 * k_a * d_a - 2.0 * k) / d;
        let k_ab = (-k_a * d_b - k_b * d_a) / d;
        let k_ae = (1.0 - k_e * d_a) / d;
        let k_bb = (-4.0 * alpha - 2.0 * k_b * d_b - 2.0 * k) / d;
        let k_be = (-k_e * d_b) / d;
        // over u = (∂σS, ν, ∂σν, ∂²σν): a = 1 + αν
        let g = [alpha * k_a, k_b, k_e];
        let hk = [[alpha * alpha * k_aa, alpha * k_ab, alpha * k_ae], [alpha * k_ab, k_bb, k_be], [alpha * k_ae, k_be, 0.0]];
        let c = self.0;
        let (f_k, f_kk) = (c * k / ds, c / ds);
        let f_sk = -f_k / ds;
        jet.value += s * 0.5 * c * k * k / ds;
        jet.gradient[0] += s * (-0.5 * f_k * k / ds);
        jet.hessian[0][0] += s * (f_k * k / (ds * ds));
        for x in 0..3 {
            jet.gradient[x + 1] += s * f_k * g[x];
            jet.hessian[0][x + 1] += s * f_sk * g[x];
            jet.hessian[x + 1][0] += s * f_sk * g[x];
            for y in 0..3 {
                jet.hessian[x + 1][y + 1] += s * (f_kk * g[x] * g[y] + f_k * hk[x][y]);
            }
        }
    }
}

/// Transport inertia of the direct steady state, −T of (D8): −ρc² |∂σr|² / (2 ∂σS) per
/// unit σ with the belt speed c (docs/fem-drive.md §12). c is an unknown of the steady
/// problem beside the element's, not a point value, so this unit integrates itself
/// ([`Self::element_energy`]) instead of being an [`EnergyTerm`] over point values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransportInertia {
    /// Integration rule (the formulation's strain rule).
    pub rule: Rule,
    /// ρ, kg/m.
    pub rho: f64,
}

impl TransportInertia {
    /// −T of one element, J, for its unknowns `q` and the belt speed `c` (generic, so
    /// that AD differentiates it in both): −Σ_points ρc²|∂σr|²/(2∂σS) · w · dσ/dξ.
    #[inline]
    pub fn element_energy<D: Scalar>(&self, el: &ElementContext, q: &[D; NDOF], c: D) -> D {
        let jac = el.jacobian();
        let mut total = c * 0.0;
        for &(xi, wt) in self.rule.points() {
            total += self.point_energy(el, &el.fields(q, xi), c, wt * jac);
        }
        total
    }

    /// −T at one point, J, for the rule weight times the Jacobian `scale`:
    /// −ρc²|∂σr|²/(2∂σS) · `scale` (generic in the point values, so that AD
    /// differentiates it per point).
    #[inline]
    pub fn point_energy<D: Scalar>(&self, el: &ElementContext, p: &PointFields<D>, c: D, scale: f64) -> D {
        let t = el.tangent_length(p);
        -(t * t / p.ds * c * c * (0.5 * self.rho * scale))
    }
}

/// The terms of a string or Kirchhoff-rod element as the effects call for them, with
/// the formulation's rules: strain always; gravity if `params.weight`, penalty contact if
/// `params.penalty`, bending if `params.bending_stiffness` is set. Visited in this order
/// (the assembly order of the energy).
#[derive(Debug, Clone, Copy)]
pub struct StandardTerms<W> {
    /// U (F8).
    pub strain: Integrated<Strain<W>>,
    /// W (F9).
    pub gravity: Option<Integrated<Gravity>>,
    /// V_γ (F10).
    pub contact: Option<Integrated<PenaltyContact>>,
    /// U_b (K7).
    pub bending: Option<Integrated<Bending>>,
}

impl<W> StandardTerms<W> {
    /// The terms `params` switches on, each with its rule from `rules`; `law` is the
    /// strain energy density W(λ).
    pub fn new(params: &TermParams, rules: &TermRules, law: W) -> StandardTerms<W> {
        StandardTerms {
            strain: Integrated { rule: rules.strain, effect: Strain(law) },
            gravity: params.weight.map(|w| Integrated { rule: rules.gravity, effect: Gravity(w) }),
            contact: params.penalty.map(|p| Integrated { rule: rules.contact, effect: PenaltyContact(p) }),
            bending: params.bending_stiffness.map(|ei| Integrated { rule: rules.bending, effect: Bending(ei) }),
        }
    }

    /// Visit every active term, in assembly order.
    #[inline]
    pub fn visit<D: Scalar, V: TermVisitor<D>>(&self, visitor: &mut V)
    where
        W: Fn(D) -> D,
    {
        visitor.visit(&self.strain);
        if let Some(t) = &self.gravity {
            visitor.visit(t);
        }
        if let Some(t) = &self.contact {
            visitor.visit(t);
        }
        if let Some(t) = &self.bending {
            visitor.visit(t);
        }
    }
}

/// The element energy as a running sum over terms and their points (the f64 energy
/// and the whole-element AD path): Σ_terms Σ_points point_energy, in visiting order.
pub struct EnergySum<'a, D> {
    el: &'a ElementContext,
    q: &'a [D; NDOF],
    jac: f64,
    /// The sum so far, J.
    pub total: D,
}

impl<'a, D: Scalar> EnergySum<'a, D> {
    /// An empty sum for element `el` with (effective) unknowns `q`.
    pub fn new(el: &'a ElementContext, q: &'a [D; NDOF]) -> Self {
        EnergySum { el, q, jac: el.jacobian(), total: D::zero() }
    }
}

impl<D: Scalar> TermVisitor<D> for EnergySum<'_, D> {
    #[inline]
    fn visit<T: EnergyTerm<D>>(&mut self, term: &T) {
        for (k, &(xi, wt)) in term.rule().points().iter().enumerate() {
            let p = self.el.fields(self.q, xi);
            self.total += term.point_energy(self.el, &p, k, wt, self.jac);
        }
    }
}

/// A term with state carried from one converged step to the next, per integration
/// point — e.g. the shell's elastic interlayer, whose energy (spec eq. 40) depends on the
/// interlayer deformation advected from the previous step (eq. 41). The term itself is
/// a stateless rule; the states live in a [`TermHistory`].
pub trait HistoryTerm {
    /// The state at one integration point.
    type State: Clone + Debug;

    /// The integration rule (one state per point of it).
    fn rule(&self) -> Rule;

    /// The state before the first step at point ξ of element `el`.
    fn initial(&self, el: &ElementContext, xi: f64) -> Self::State;

    /// Energy per unit σ at a point given the state of the last converged step, J/m.
    fn density<D: Scalar>(&self, el: &ElementContext, p: &PointFields<D>, state: &Self::State) -> D;

    /// The state after a converged step, from the converged point values and the state
    /// before the step.
    fn advance(&self, el: &ElementContext, p: &PointFields<f64>, previous: &Self::State) -> Self::State;
}

/// A history term over a mesh: per element, one state per integration point. During a
/// step the states are read only ([`TermHistory::element`] is an [`EnergyTerm`] like any
/// other); [`TermHistory::commit`] advances them once the step has converged.
#[derive(Debug, Clone)]
pub struct TermHistory<T: HistoryTerm> {
    term: T,
    states: Vec<Vec<T::State>>,
}

/// A history term bound to one element's states: an [`EnergyTerm`].
pub struct ElementHistory<'a, T: HistoryTerm> {
    term: &'a T,
    states: &'a [T::State],
}

impl<D: Scalar, T: HistoryTerm> EnergyTerm<D> for ElementHistory<'_, T> {
    fn rule(&self) -> Rule {
        self.term.rule()
    }

    #[inline]
    fn density(&self, el: &ElementContext, p: &PointFields<D>, point: usize) -> D {
        self.term.density(el, p, &self.states[point])
    }
}

impl<T: HistoryTerm> TermHistory<T> {
    /// The initial states of `term` on the elements `contexts`.
    pub fn new(term: T, contexts: &[ElementContext]) -> Self {
        let states = contexts.iter().map(|el| term.rule().points().iter().map(|&(xi, _)| term.initial(el, xi)).collect()).collect();
        TermHistory { term, states }
    }

    /// The term.
    pub fn term(&self) -> &T {
        &self.term
    }

    /// The states of element `e`, one per point of the rule.
    pub fn states(&self, e: usize) -> &[T::State] {
        &self.states[e]
    }

    /// Element `e`'s share of the term, to be visited with the element's other terms.
    pub fn element(&self, e: usize) -> ElementHistory<'_, T> {
        ElementHistory { term: &self.term, states: &self.states[e] }
    }

    /// Advance every state after a converged step: `converged(e)` gives element e's
    /// (effective) unknowns at the converged state.
    pub fn commit(&mut self, contexts: &[ElementContext], converged: impl Fn(usize) -> [f64; NDOF]) {
        let term = &self.term;
        for (e, (el, states)) in contexts.iter().zip(&mut self.states).enumerate() {
            let q = converged(e);
            for (state, &(xi, _)) in states.iter_mut().zip(term.rule().points()) {
                *state = term.advance(el, &el.fields(&q, xi), state);
            }
        }
    }
}

/// A term that is a load with a return mapping rather than a potential of the element
/// unknowns alone — Coulomb friction, the augmented-Lagrangian contact
/// (docs/fem-drive.md §5, §6): its energy at a point depends on the point values, on `G`
/// global unknowns of the step (the drive's material advance a and driven rotation φ,
/// §4) and on a per-point state frozen during a solve (multipliers, slip bound, upstream
/// references). It is evaluated at the trial state; after a converged solve its return
/// mapping evaluates each point, from which the state is committed (as
/// [`HistoryTerm::advance`] does for a history term). A model picks these units by the
/// scene's effects (the string drive: `string_drive::contact::DriveTerms`).
pub trait MappedTerm<const G: usize> {
    /// The per-point state (its weights included).
    type State;
    /// The return mapping's result at a point.
    type Mapped;

    /// The term's weighted energy at a point, J (the point's weight is part of the
    /// state); `None` where the term is inactive at the point.
    fn point_energy<D: Scalar>(&self, el: &ElementContext, p: &PointFields<D>, globals: &[D; G], state: &Self::State) -> Option<D>;

    /// The return mapping at the converged point values.
    fn map(&self, el: &ElementContext, p: &PointFields<f64>, globals: &[f64; G], state: &Self::State) -> Self::Mapped;
}

#[cfg(test)]
mod tests {
    //! The history hook with a small test term: a spring of stiffness k per unit σ that
    //! ties ν to its value at the last converged step, ½ k (ν − ν_prev)² (a backward-Euler
    //! viscous layer; the interlayer of eq. 40 has the same structure with an advected
    //! state).
    use super::*;
    use crate::mesh::ElementGeometry;
    use drive::contour::{Contour, Region};
    use nalgebra::SVector;
    use num_dual::gradient;

    /// The tether of stiffness k (N/m²).
    struct Tether(f64);

    impl HistoryTerm for Tether {
        type State = f64;
        fn rule(&self) -> Rule {
            Rule::Gauss(3)
        }
        fn initial(&self, _el: &ElementContext, _xi: f64) -> f64 {
            0.0
        }
        fn density<D: Scalar>(&self, _el: &ElementContext, p: &PointFields<D>, state: &f64) -> D {
            let d = p.nu - *state;
            d * d * (0.5 * self.0)
        }
        fn advance(&self, _el: &ElementContext, p: &PointFields<f64>, _previous: &f64) -> f64 {
            p.nu
        }
    }

    fn contexts() -> Vec<ElementContext> {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let params = TermParams { axial_stiffness: 1.0, weight: None, penalty: None, bending_stiffness: None };
        [(0.10, 0.04), (0.14, 0.05)]
            .into_iter()
            .map(|(sigma_a, h)| ElementContext { geometry: ElementGeometry { sigma_a, h, region: Region::UpperSpan }, contour, params, augmented: [false; 2] })
            .collect()
    }

    /// Element energy of the history term alone.
    fn energy<D: Scalar>(hist: &TermHistory<Tether>, e: usize, el: &ElementContext, q: &[D; NDOF]) -> D {
        let mut sum = EnergySum::new(el, q);
        sum.visit(&hist.element(e));
        sum.total
    }

    /// Uniform ν = a on an element of length h: ½ k (a − a_prev)² h, exact with Gauss 3
    /// (a quadratic in the unknowns, constant in ξ) — to round-off (a few dozen rounded
    /// operations on O(1) numbers: 1e-13 relative).
    #[test]
    fn history_term_sees_the_last_converged_step_only() {
        let els = contexts();
        let mut hist = TermHistory::new(Tether(250.0), &els);
        assert_eq!(hist.states(1).len(), 3);
        let uniform = |el: &ElementContext, a: f64, slope: f64| -> [f64; NDOF] {
            let (sa, sb) = (el.geometry.sigma_a, el.geometry.sigma_a + el.geometry.h);
            [sa, 1.0, a + slope * sa, slope, sb, 1.0, a + slope * sb, slope]
        };
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs().max(1e-300);
        for (e, el) in els.iter().enumerate() {
            let h = el.geometry.h;
            assert!(close(energy(&hist, e, el, &uniform(el, 0.002, 0.0)), 0.5 * 250.0 * 0.002f64.powi(2) * h));
        }
        // step 1 converges at ν = 0.002 + 0.1 σ (linear): the states take those values
        let step1: Vec<_> = els.iter().map(|el| uniform(el, 0.002, 0.1)).collect();
        hist.commit(&els, |e| step1[e]);
        for (e, el) in els.iter().enumerate() {
            for (s, &(xi, _)) in hist.states(e).iter().zip(Rule::Gauss(3).points()) {
                assert!(close(*s, 0.002 + 0.1 * el.sigma(xi)));
            }
            // zero at the converged state, ½k(Δ)²h for a uniform shift Δ from it
            assert!(energy(&hist, e, el, &step1[e]).abs() <= 1e-30);
            let shifted = uniform(el, 0.002 + 0.003, 0.1);
            assert!(close(energy(&hist, e, el, &shifted), 0.5 * 250.0 * 0.003f64.powi(2) * el.geometry.h));
        }
        // the states advance from the converged values, not from trial states seen before
        let _ = energy(&hist, 0, &els[0], &uniform(&els[0], 1.0, 0.0));
        assert!(close(hist.states(0)[1], 0.002 + 0.1 * els[0].sigma(0.0)));
    }

    /// The history term differentiates by AD like any term: gradient against central
    /// differences (step 1e-6 on O(1e-3) unknowns of a quadratic energy: truncation
    /// vanishes, round-off ≈ ε E/h ≈ 1e-12 of the gradient scale; tolerance 1e-8).
    #[test]
    fn history_term_gradient_matches_finite_differences() {
        let els = contexts();
        let mut hist = TermHistory::new(Tether(40.0), &els);
        let el = els[1];
        let q0 = [0.14, 1.0, 0.001, 0.02, 0.19, 1.01, 0.0015, -0.01];
        hist.commit(&els, |_| q0);
        let q = [0.14, 1.0, 0.0013, 0.05, 0.19, 1.01, 0.0011, 0.03];
        let (_, g) = gradient(
            |v| {
                let a: [_; NDOF] = std::array::from_fn(|i| v[i]);
                energy(&hist, 1, &el, &a)
            },
            &SVector::<f64, NDOF>::from_column_slice(&q),
        );
        let scale = g.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        let mut moved = 0;
        for i in 0..NDOF {
            let (mut qp, mut qm) = (q, q);
            qp[i] += 1e-6;
            qm[i] -= 1e-6;
            let fd = (energy(&hist, 1, &el, &qp) - energy(&hist, 1, &el, &qm)) / 2e-6;
            assert!((fd - g[i]).abs() <= 1e-8 * scale, "grad[{i}]: AD {} FD {fd}", g[i]);
            moved += usize::from(g[i].abs() > 1e-6 * scale);
        }
        // only the ν unknowns carry the term
        assert_eq!(moved, 4);
    }
}
