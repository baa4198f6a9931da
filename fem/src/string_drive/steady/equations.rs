//! The steady equations (DS1)–(DS4) on one mesh: unknown layout, sparsity pattern, residual and generalised Jacobian (assembly of the element kernels and the friction points).

use super::*;

/// Parameters of the steady equations that do not change within a Newton solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyParams {
    /// μ.
    pub mu: f64,
    /// Normal penalty P, N/m² (the normal traction is P⟨−γ⟩).
    pub penalty: f64,
    /// κ of the active-set decision τ + κv, N·s/m² (any κ > 0 gives the same roots).
    pub kappa: f64,
    /// R, m.
    pub radius: f64,
    /// ω₁, rad/s.
    pub omega1: f64,
    /// Load torque M₂ (already scaled by the continuation parameter), N·m.
    pub torque: f64,
    /// Damping d₂ (scaled), N·m·s.
    pub damping: f64,
    /// ρ (scaled) of the transport inertia, kg/m; `None` without inertia.
    pub inertia: Option<f64>,
    /// What closes the system: the loop's (DS2)/(DS3) or the open layout's ends.
    pub ends: Ends,
}

/// The rows of the slots c and ω₂ and the end loads (docs/fem-cosserat.md §12.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ends {
    /// The closed loop: the c-row is the global material balance (DS2) ∫τλ dσ = 0, the
    /// ω₂-row the driven pulley's torque balance (DS3).
    Loop,
    /// The open one-pulley layout in mode `tensions` (the pulley is the loop's driven
    /// one, ω its speed in the ω₂ slot): the c-row c − c₀ = 0 (c given), the ω-row the
    /// global material balance (C21) ∫τλ dσ − (𝓗_out − 𝓗_in) = 0, and 𝓗_out on the
    /// ξ-row of the outflow node (C18); 𝓗_in would sit on the ξ-row of the gauge node,
    /// which (C21) replaces.
    Open {
        /// c₀, m/s.
        transport_rate: f64,
        /// 𝓗(N_in) of (C18), N (unused in mode `pulley_speed`).
        flux_in: f64,
        /// 𝓗(N_out) of (C18), N.
        flux_out: f64,
        /// Mode `pulley_speed` (docs/fem-cosserat.md §12.7): ω given, rad/s — the stick
        /// rows read it, and the ω-slot holds 𝓗_in instead (N), the unknown (C21)
        /// determines. `None`: mode `tensions`, ω the unknown in its slot.
        pulley_speed: Option<f64>,
    },
}

impl SteadyParams {
    /// ω of a friction point's pulley (the driven one's: the unknown `w2` of the ω₂ slot
    /// unless the open ends give it) and whether it is that unknown.
    pub fn point_speed(&self, driven: bool, w2: f64) -> (f64, bool) {
        match (driven, self.ends) {
            (false, _) => (self.omega1, false),
            (true, Ends::Open { pulley_speed: Some(w), .. }) => (w, false),
            (true, _) => (w2, true),
        }
    }
}

/// The steady problem on one mesh: X = (z, c, ω₂, τ₁ … τ_m), for an element of any
/// 1-D layout with N unknowns (the string's 8 by default, the Cosserat rod's 12); P and
/// E are the sizes of a friction point's and an element load's variable lists,
/// 2N + 4 and N + 4 ([`point_size`], [`element_size`]; checked in [`Self::len`]).
pub struct SteadyProblem<'a, const N: usize = NDOF, const P: usize = NPV, const E: usize = NEV, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    /// Assembler of the element (its energy: strain, gravity, normal penalty in its
    /// params; for the Cosserat rod also shear and bending).
    pub asm: &'a Assembler<N, K>,
    /// Term parameters with the normal penalty.
    pub params: TermParams,
    /// Belt length L, m.
    pub length: f64,
    /// The friction points.
    pub points: &'a [FrictionPoint],
    /// Parameters.
    pub sp: SteadyParams,
    /// Strain rule of the formulation (for the inertia term).
    pub strain_rule: Rule,
}

/// Entries of one friction point: rows and columns in the point's variable list
/// (q of the left element, q of the right element, c, ω₂, τ, and for the slip half of a
/// split node the τ of its stick half) — see [`SteadyProblem::variables`].
pub(super) const NPV: usize = point_size(NDOF);

/// Size of a friction point's variable list for an element of N unknowns: 2N + 4.
pub const fn point_size(n: usize) -> usize {
    2 * n + 4
}

/// Size of an element load's variable list for an element of N unknowns: N + 4.
pub const fn element_size(n: usize) -> usize {
    n + 4
}

// the copies of a problem share its references (a derived Clone would ask K: Clone)
impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> Clone for SteadyProblem<'_, N, P, E, K> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> Copy for SteadyProblem<'_, N, P, E, K> {}

/// Residual, Jacobian values (pattern order) and the point results of one evaluation.
pub struct Evaluated {
    /// F(X).
    pub residual: Vec<f64>,
    /// ∂F/∂X in the order of [`SteadyProblem::pattern`].
    pub values: Vec<f64>,
    /// Per friction point: (traction, normal, velocity, slip).
    pub results: Vec<PointResult>,
}

/// Variables of an element's friction load: q (8), c, ω₂, τ_a, τ_b.
pub(super) const NEV: usize = element_size(NDOF);

/// Residual entries and, for a Jacobian pass, the Jacobian block of an element's
/// friction load (of a friction point: [`PointTerms`]).
pub(super) type ElementLoad<const E: usize> = ([f64; E], Option<Box<[[f64; E]; E]>>);

/// Residual entries, the Jacobian block (a Jacobian pass only) and the results of a
/// friction point.
pub(super) type PointTerms<const P: usize> = ([f64; P], Option<Box<[[f64; P]; P]>>, PointResult);

/// Quadrature of the friction load (DS1)–(DS3): 4-point Gauss–Legendre (τ linear × λ ×
/// a cubic shape function).
pub(super) const FRICTION_RULE: Rule = Rule::Gauss(4);

impl<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized> SteadyProblem<'_, N, P, E, K> {
    /// The variable-list sizes fit N.
    const SIZES: () = assert!(P == point_size(N) && E == element_size(N), "SteadyProblem<N, P, E>: P = 2N + 4, E = N + 4");

    /// Number of unknowns nz + 2 + m.
    pub fn len(&self) -> usize {
        let () = Self::SIZES;
        self.asm.len() + 2 + self.points.len()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Index of c, ω₂ and of τ_i.
    pub(super) fn ic(&self) -> usize {
        self.asm.len()
    }
    pub(super) fn iw(&self) -> usize {
        self.asm.len() + 1
    }
    pub(super) fn it(&self, i: usize) -> usize {
        self.asm.len() + 2 + i
    }

    /// The global indices of point i's variables (q of the left and right elements,
    /// c, ω₂, τ_i). The node's own unknowns appear twice (once per element); the pattern
    /// sums duplicates.
    pub(super) fn variables(&self, i: usize) -> [Option<usize>; P] {
        let pt = &self.points[i];
        let il = self.asm.dofs().element(pt.left.0);
        let ir = self.asm.dofs().element(pt.right.0);
        let partner = self.stick_partner(i).or_else(|| self.entry_neighbour(i)).map(|j| self.it(j));
        std::array::from_fn(|k| match k {
            k if k < N => il[k],
            k if k < 2 * N => ir[k - N],
            k if k == 2 * N => Some(self.ic()),
            k if k == 2 * N + 1 => Some(self.iw()),
            k if k == 2 * N + 2 => Some(self.it(i)),
            _ => partner,
        })
    }

    /// The stick half of a split node whose slip half is point i (docs/fem-drive.md
    /// §12): the slip half is the one downstream in the belt's travel — [`Part::Right`]
    /// clockwise, [`Part::Left`] counter-clockwise; `None` for any other point.
    pub(super) fn stick_partner(&self, i: usize) -> Option<usize> {
        let pt = &self.points[i];
        match (pt.part, pt.direction) {
            _ if pt.boundary => None,
            (Part::Right, Direction::Clockwise) => (i > 0 && self.points[i - 1].part == Part::Left && !self.points[i - 1].boundary).then(|| i - 1),
            (Part::Left, Direction::CounterClockwise) => (i + 1 < self.points.len() && self.points[i + 1].part == Part::Right && !self.points[i + 1].boundary).then_some(i + 1),
            _ => None,
        }
    }

    /// The point whose traction a prescribed stick entry half i carries (Paper D's
    /// contact-side halves, [`FrictionPoint::is_entry`]): the point at the next node on its
    /// contact side, downstream in the travel (docs/fem-drive.md §12, "Fifth round");
    /// `None` for any other point, and for Paper D's string (its entry halves have their
    /// own row).
    pub(super) fn entry_neighbour(&self, i: usize) -> Option<usize> {
        let pt = &self.points[i];
        // a stick entry half: Paper D's prescribed one, or the semismooth scheme's while
        // its (DS4) sticks (the tie is applied then, `evaluate`)
        if !pt.is_entry() || matches!(pt.fixed, Some(Fixed::Slip(_))) {
            return None;
        }
        // Paper D's string: the entry half's own row, the stick zone's traction at the
        // run-on point (`point_terms`, docs/fem-drive.md §12, "Sixth round")
        if pt.fixed.is_some() && self.asm.kernel().friction_normal() == FrictionNormal::Nodal {
            return None;
        }
        let (m, n) = (self.points.len(), self.asm.mesh().node_count());
        let (j, node) = if pt.part == Part::Right { ((i + 1) % m, (pt.node + 1) % n) } else { ((i + m - 1) % m, (pt.node + n - 1) % n) };
        let q = &self.points[j];
        (q.node == node && q.pulley == pt.pulley).then_some(j)
    }

    /// Per element, the friction points whose tractions hold at its edges ξ = −1, +1
    /// (a whole node's point at both adjacent edges, a half at its own side's).
    pub fn edge_owners(&self) -> Vec<[Option<usize>; 2]> {
        let mut out = vec![[None, None]; self.asm.mesh().len()];
        for (i, p) in self.points.iter().enumerate() {
            if p.part != Part::Right {
                out[p.left.0][1] = Some(i);
            }
            if p.part != Part::Left {
                out[p.right.0][0] = Some(i);
            }
        }
        out
    }

    /// Global indices of element e's friction-load variables (q, c, ω₂, τ_a, τ_b).
    pub(super) fn element_variables(&self, e: usize, owners: [Option<usize>; 2]) -> [Option<usize>; E] {
        let idx = self.asm.dofs().element(e);
        std::array::from_fn(|k| match k {
            k if k < N => idx[k],
            k if k == N => Some(self.ic()),
            k if k == N + 1 => Some(self.iw()),
            k if k == N + 2 => owners[0].map(|i| self.it(i)),
            _ => owners[1].map(|i| self.it(i)),
        })
    }

    /// (DS1)–(DS3) of one element, the consistent (Galerkin) friction load with τ
    /// linear between its edge values: −∫ τ λ ∂S/∂q dσ on the S-rows (values and
    /// slopes), +∫ τ λ dσ on the c-row, −∫ τ dσ on the ω₂-row of a driven element
    /// (open ends, §12.3 of docs/fem-cosserat.md: +∫ τ λ dσ on the ω-row, nothing else);
    /// with, if `jacobian`, its Jacobian in (q, c, ω₂, τ_a, τ_b) (else the values alone,
    /// by plain f64 evaluation).
    pub(super) fn element_friction(&self, e: usize, z: &[f64], tau: [f64; 2], driven: bool, jacobian: bool) -> ElementLoad<E> {
        let el = self.asm.context(e, &self.params);
        let layout = self.asm.kernel().layout();
        let q = self.asm.dofs().gather(e, z, self.length);
        let jac = el.jacobian();
        let h = el.geometry.h;
        let (ic, iw, ia) = (N, N + 1, N + 2);
        let mut r = [0.0; E];
        let mut block = jacobian.then(|| Box::new([[0.0; E]; E]));
        for &(xi, wg) in FRICTION_RULE.points() {
            let (lam, dl) = point_stretch(layout, &el, &q, xi, jacobian);
            let shape = [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)];
            let t = shape[0] * tau[0] + shape[1] * tau[1];
            let w = wg * jac;
            match material_derivatives(layout, &el, &q, xi, jacobian) {
                (_, None) => {
                    let (vw, _) = crate::hermite::weights(xi, h);
                    // S = Σ vw_k (s_a, s'_a, s_b, s'_b): the s unknowns of the layout
                    for (k, &loc) in layout.hermite_indices(0).iter().enumerate() {
                        r[loc] -= w * t * lam * vw[k];
                        if let Some(j) = block.as_deref_mut() {
                            for m in 0..N {
                                j[loc][m] -= w * t * dl[m] * vw[k];
                            }
                            for a in 0..2 {
                                j[loc][ia + a] -= w * shape[a] * lam * vw[k];
                            }
                        }
                    }
                }
                // S through the augmented map: ∂S/∂q on every row, with ∂²S/∂q²
                (ds, Some(d2s)) => {
                    for loc in 0..N {
                        r[loc] -= w * t * lam * ds[loc];
                        if let Some(j) = block.as_deref_mut() {
                            for m in 0..N {
                                j[loc][m] -= w * t * (dl[m] * ds[loc] + lam * d2s[loc][m]);
                            }
                            for a in 0..2 {
                                j[loc][ia + a] -= w * shape[a] * lam * ds[loc];
                            }
                        }
                    }
                }
            }
            // the material balance (DS2)/(C21): the c-row on a loop, the ω-row open
            let ib = if self.sp.ends == Ends::Loop { ic } else { iw };
            r[ib] += w * t * lam;
            let on_loop = driven && self.sp.ends == Ends::Loop;
            if on_loop {
                r[iw] -= w * t;
            }
            if let Some(j) = block.as_deref_mut() {
                for m in 0..N {
                    j[ib][m] += w * t * dl[m];
                }
                for a in 0..2 {
                    j[ib][ia + a] += w * shape[a] * lam;
                    if on_loop {
                        j[iw][ia + a] -= w * shape[a];
                    }
                }
            }
        }
        (r, block)
    }

    /// Slip dissipation D = ∫ τ v dσ, v = cλ − Rω_k, with the quadrature and the
    /// linear τ of the friction load — so P_in = P_out + D holds by (DS2) to round-off.
    pub fn dissipation(&self, x: &[f64]) -> f64 {
        self.dissipation_on(x, None)
    }

    /// The part of [`Self::dissipation`] on one pulley's friction load (all of it with
    /// `None`).
    pub fn dissipation_on(&self, x: &[f64], pulley: Option<Pulley>) -> f64 {
        let z = &x[..self.asm.len()];
        let (c, w2) = (x[self.ic()], x[self.iw()]);
        let mut d = 0.0;
        for (e, o) in self.edge_owners().into_iter().enumerate() {
            let Some(first) = o[0].or(o[1]) else { continue };
            if pulley.is_some_and(|p| self.points[first].pulley != p) {
                continue;
            }
            let (omega, _) = self.sp.point_speed(self.points[first].pulley == Pulley::Driven, w2);
            let tau = [o[0].map_or(0.0, |i| x[self.it(i)]), o[1].map_or(0.0, |i| x[self.it(i)])];
            let el = self.asm.context(e, &self.params);
            let q = centreline(self.asm.kernel().layout(), &el, &self.asm.dofs().gather(e, z, self.length));
            for &(xi, wg) in FRICTION_RULE.points() {
                let t = 0.5 * (1.0 - xi) * tau[0] + 0.5 * (1.0 + xi) * tau[1];
                d += wg * el.jacobian() * t * (c * el.stretch(&el.fields(&q, xi)) - self.sp.radius * omega);
            }
        }
        d
    }

    /// The pattern: the assembler's blocks, per element (q × (q, c)) if inertia, per
    /// friction point its block, per element with friction its friction-load block, and
    /// the diagonal of c, ω₂.
    pub fn pattern(&self) -> (Vec<usize>, Vec<usize>) {
        let (r0, c0) = self.asm.pattern();
        let mut rows = r0.to_vec();
        let mut cols = c0.to_vec();
        if self.sp.inertia.is_some() {
            for e in 0..self.asm.mesh().len() {
                let idx = self.asm.dofs().element(e);
                for gi in idx.iter().flatten() {
                    for gj in idx.iter().flatten().copied().chain([self.ic()]) {
                        rows.push(*gi);
                        cols.push(gj);
                    }
                }
            }
        }
        for i in 0..self.points.len() {
            let v = self.variables(i);
            for gi in v.iter().flatten() {
                for gj in v.iter().flatten() {
                    rows.push(*gi);
                    cols.push(*gj);
                }
            }
        }
        for (e, owners) in self.edge_owners().into_iter().enumerate() {
            if owners == [None, None] {
                continue;
            }
            let v = self.element_variables(e, owners);
            for gi in v.iter().flatten() {
                for gj in v.iter().flatten() {
                    rows.push(*gi);
                    cols.push(*gj);
                }
            }
        }
        for k in [self.ic(), self.iw()] {
            rows.push(k);
            cols.push(k);
        }
        (rows, cols)
    }

    /// The element penalty's normal traction before its clipping, λ − Pγ (P the
    /// penalty, γ the gap, λ the contact multiplier of an augmented layout, else 0), at X:
    /// for each element and each point of its contact rule, in that order; the penalty
    /// presses where it is > 0 (its kink at 0). `None` at a point out of every pulley's
    /// reach. Empty without a penalty.
    pub(super) fn penalty_pressures(&self, x: &[f64]) -> Vec<Option<f64>> {
        let Some(penalty) = self.params.penalty else { return Vec::new() };
        let kernel = self.asm.kernel();
        let layout = kernel.layout();
        let rule = kernel.rules().contact;
        let z = &x[..self.asm.len()];
        let mut out = Vec::with_capacity(self.asm.mesh().len() * rule.points().len());
        for e in 0..self.asm.mesh().len() {
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            for &(xi, _) in rule.points() {
                out.push(point_gap(layout, &el, &q, xi, false).map(|(g, _)| {
                    // ⟨λ − P·0⟩₊ = λ (λ ≥ 0)
                    let lambda = kernel.contact_traction(penalty, el.sigma(xi), Some(0.0));
                    lambda - penalty * g
                }));
            }
        }
        out
    }

    /// F(X) and its generalised Jacobian (the active set of the current X); `None` if
    /// z is inadmissible or a value is not finite.
    pub fn evaluate(&self, x: &[f64], with_jacobian: bool) -> Option<Evaluated> {
        let nz = self.asm.len();
        let z = &x[..nz];
        let (c, w2) = (x[self.ic()], x[self.iw()]);
        let sp = &self.sp;
        let (mut residual, mut values) = if with_jacobian {
            let a = self.asm.assemble(z, &self.params, self.length)?;
            (a.gradient, a.values)
        } else {
            let (_, g) = self.asm.gradient(z, &self.params, self.length)?;
            (g, Vec::new())
        };
        residual.resize(self.len(), 0.0);
        let owners = self.edge_owners();
        if with_jacobian {
            // the blocks below, at most: no regrowth of the value list (measured: its
            // reallocations were 1.3 % of a solve)
            let loaded = owners.iter().filter(|o| **o != [None, None]).count();
            let inertia = if sp.inertia.is_some() { self.asm.mesh().len() * N * (N + 1) } else { 0 };
            values.reserve(inertia + self.points.len() * P * P + loaded * E * E + 2);
        }
        // transport inertia (D8) with c an unknown: rows q, columns (q, c)
        if let Some(rho) = sp.inertia {
            let layout = self.asm.kernel().layout();
            if with_jacobian {
                let per: Vec<InertiaBlock<N>> = (0..self.asm.mesh().len())
                    .into_par_iter()
                    .map(|e| inertia_derivatives(layout, &self.asm.context(e, &self.params), &self.asm.dofs().gather(e, z, self.length), c, rho, self.strain_rule))
                    .collect();
                for (e, (g, gc, h)) in per.iter().enumerate() {
                    // the c column after each row's q columns
                    scatter(self.asm.dofs().element(e), g, &|i, j| if j == N { gc[i] } else { h[i][j] }, Some(N), &mut residual, Some(&mut values));
                }
            } else {
                let per: Vec<[f64; N]> = (0..self.asm.mesh().len())
                    .into_par_iter()
                    .map(|e| inertia_gradient(layout, &self.asm.context(e, &self.params), &self.asm.dofs().gather(e, z, self.length), c, rho, self.strain_rule))
                    .collect();
                for (e, g) in per.iter().enumerate() {
                    scatter(self.asm.dofs().element(e), g, &|_, _| 0.0, None, &mut residual, None);
                }
            }
        }
        // friction points (DS1)–(DS4)
        let mut per: Vec<PointTerms<P>> = (0..self.points.len())
            .into_par_iter()
            .map(|i| self.point_terms(i, x, false, with_jacobian))
            .collect();
        // a pulley whose contact points all slide leaves c or ω₂ without an equation
        // (no steady creep state has that: each contact zone sticks at entry); within
        // an iterate, the point nearest to sticking, min (|τ + κv| − b)/b, is taken as
        // stick (§12) — at a converged state it must then satisfy |τ| ≤ b itself
        for pulley in [Pulley::Driver, Pulley::Driven] {
            let contact = |k: &usize| self.points[*k].pulley == pulley && per[*k].2.normal > 0.0;
            let idx: Vec<usize> = (0..per.len()).filter(|k| contact(k)).collect();
            if idx.is_empty() || idx.iter().any(|&k| !per[k].2.slip) {
                continue;
            }
            let margin = |k: usize| {
                let res = &per[k].2;
                ((res.traction + sp.kappa * res.velocity).abs() - sp.mu * res.normal) / (sp.mu * res.normal)
            };
            if let Some(&k) = idx.iter().min_by(|a, b| margin(**a).total_cmp(&margin(**b))) {
                per[k] = self.point_terms(k, x, true, with_jacobian);
            }
        }
        // ties w (τ_i − τ_j) = 0 on the point's row, τ_j in its partner slot:
        // - both halves of a split node sticking would be two multipliers on one node
        //   (proportional columns): the slip half then carries the stick half's traction —
        //   the whole node's behaviour (§12);
        // - a stick entry half of the Cosserat rod's contact-side halves: its upwind
        //   element is free, so it has no kinematic row (v = 0 would pin that free
        //   element's mean stretch to the stick zone's, a concentrated traction at the
        //   run-on point, measured); it carries its downstream neighbour's traction, and
        //   the stick rows of the contact elements hold the zone (docs/fem-cosserat.md
        //   §11.1; Paper D's string has the entry row of `point_terms` instead)
        for i in 0..per.len() {
            let tie = match (self.stick_partner(i), self.entry_neighbour(i)) {
                (Some(j), _) if !per[i].2.slip && !per[j].2.slip => Some(j),
                (None, Some(j)) if !per[i].2.slip && per[i].2.normal > 0.0 => Some(j),
                _ => None,
            };
            if let Some(j) = tie {
                let w = self.points[i].weight;
                let it = 2 * N + 2;
                per[i].0[it] = w * (x[self.it(i)] - x[self.it(j)]);
                if let Some(jac) = per[i].1.as_deref_mut() {
                    jac[it] = [0.0; P];
                    jac[it][it] = w;
                    jac[it][P - 1] = -w;
                }
            }
        }
        let mut results = Vec::with_capacity(self.points.len());
        for (i, (r, j, res)) in per.into_iter().enumerate() {
            scatter(&self.variables(i), &r, &|a, b| j.as_ref().map_or(0.0, |j| j[a][b]), None, &mut residual, with_jacobian.then_some(&mut values));
            results.push(res);
        }
        // (DS1)–(DS3): the consistent friction load of every element with friction points
        let loads: Vec<Option<ElementLoad<E>>> = owners
            .par_iter()
            .enumerate()
            .map(|(e, o)| {
                let first = o[0].or(o[1])?;
                let tau = [o[0].map_or(0.0, |i| x[self.it(i)]), o[1].map_or(0.0, |i| x[self.it(i)])];
                Some(self.element_friction(e, z, tau, self.points[first].pulley == Pulley::Driven, with_jacobian))
            })
            .collect();
        for (e, load) in loads.into_iter().enumerate() {
            let Some((r, j)) = load else { continue };
            scatter(&self.element_variables(e, owners[e]), &r, &|a, b| j.as_ref().map_or(0.0, |j| j[a][b]), None, &mut residual, with_jacobian.then_some(&mut values));
        }
        match sp.ends {
            // the driven pulley's torque balance (DS3) divided by R: + (M₂ + d₂ω₂)/R
            Ends::Loop => {
                residual[self.iw()] += (sp.torque + sp.damping * w2) / sp.radius;
                if with_jacobian {
                    values.push(0.0);
                    values.push(sp.damping / sp.radius);
                }
            }
            // c given; (C21) less the end fluxes; 𝓗_out on the outflow node's ξ-row (C18)
            // (mode `pulley_speed`: 𝓗_in the unknown of the ω-slot)
            Ends::Open { transport_rate, flux_in, flux_out, pulley_speed } => {
                residual[self.ic()] = c - transport_rate;
                residual[self.iw()] -= flux_out - if pulley_speed.is_some() { w2 } else { flux_in };
                if let Some(s_end) = self.asm.dofs().node_unknowns(self.asm.mesh().node_count() - 1).values[0] {
                    residual[s_end] += flux_out;
                }
                if with_jacobian {
                    // the c-row's only entry (the friction blocks leave it zero when open)
                    values.push(1.0);
                    values.push(if pulley_speed.is_some() { 1.0 } else { 0.0 });
                }
            }
        }
        let finite = residual.iter().all(|v| v.is_finite()) && values.iter().all(|v| v.is_finite());
        finite.then_some(Evaluated { residual, values, results })
    }

    /// The normal traction P⟨−γ̄⟩ of a friction point and its gradient in (q_left,
    /// q_right): γ̄ the trapezoidal mean of the gaps at the node's two element edges (the
    /// loop's for an element with [`FrictionNormal::Nodal`], docs/fem-drive.md §12).
    /// The gradient only if `grad` (else zero), here and in the other normal rules.
    fn nodal_normal(&self, pt: FrictionPoint, z: &[f64], grad: bool) -> (f64, [f64; P]) {
        let layout = self.asm.kernel().layout();
        let mut gap: Option<(f64, [f64; P])> = Some((0.0, [0.0; P]));
        let node_weight = pt.left.1 + pt.right.1;
        for (side, (e, we), xi) in [(0, pt.left, 1.0), (1, pt.right, -1.0)] {
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let g = point_gap(layout, &el, &q, xi, grad);
            let f = we / node_weight;
            gap = match (gap, g) {
                (Some((acc, mut dacc)), Some((gv, dg))) => {
                    for k in 0..N {
                        dacc[side * N + k] += f * dg[k];
                    }
                    Some((acc + f * gv, dacc))
                }
                _ => None,
            };
        }
        match gap {
            Some((g, dg)) if g < 0.0 => (-self.sp.penalty * g, dg.map(|d| -self.sp.penalty * d)),
            _ => (0.0, [0.0; P]),
        }
    }

    /// The normal traction of a Paper D point of the string loop (a [`Fixed`] row on an
    /// element with [`FrictionNormal::Nodal`]) from the belt's radial equilibrium on the
    /// drum, as the BVP's: p = (N − ρc²λ)/R + (ρg/λ) ŷ·e_r with N = EA(λ − 1), λ the
    /// half-weighted mean of the two edges' stretch at the node and e_r the drum's outward
    /// normal at the node's contour point, per contour length (the drum's arc per σ:
    /// 1 on the pulley's arc region, |g − c|/R ≈ 1/cos θ on a span's straight contour θ
    /// past the tangent point); a contact boundary's half ([`FrictionPoint::boundary`])
    /// takes its own side alone, and a point the topology puts out of contact
    /// ([`Fixed::Free`]) none — the contact set is the prescribed zones', never the sign of
    /// an iterate's gap (docs/fem-drive.md §12, "Sixth round"). With its gradient in (q_left, q_right) and its
    /// derivative in c. The stiff penalty's nodal gap is no measure of the pressure where
    /// the contact runs into a span's Cartesian part (the cubic meets the drum only at the
    /// contact rule's points): there the nodal bound μP⟨−γ̄⟩ shifts the slip zone's
    /// tension by O(μp) × a share of an element, measured 2.3e-3 N at 1024 elements on
    /// the low-tension drive (docs/fem-drive.md §12).
    fn equilibrium_normal(&self, pt: FrictionPoint, z: &[f64], c: f64, grad: bool) -> (f64, [f64; P], f64) {
        let layout = self.asm.kernel().layout();
        // out of contact by the topology (`in_contact_zone`): no reaction
        if pt.fixed == Some(Fixed::Free) {
            return (0.0, [0.0; P], 0.0);
        }
        let (mut lam, mut dlam) = (0.0, [0.0; P]);
        // a contact-side half: its own side only (docs/fem-drive.md §12, "Fifth round")
        for (side, (e, _), xi) in [(0, pt.left, 1.0), (1, pt.right, -1.0)] {
            let Some(f) = pt.side_share(side) else { continue };
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let (l, dl) = point_stretch(layout, &el, &q, xi, grad);
            lam += f * l;
            for k in 0..N {
                dlam[side * N + k] += f * dl[k];
            }
        }
        let contour = *self.asm.mesh().contour();
        let r = self.sp.radius;
        let centre = contour.pulley_centre(pt.pulley);
        let x = contour.position(pt.sigma, 0.0);
        let (ex, ey) = (x[0] - centre[0], x[1] - centre[1]);
        let dist = (ex * ex + ey * ey).sqrt();
        let ey = ey / dist;
        // per contour length: the drum's arc per σ, 1 on the pulley's arc, 1/cos θ ≈ |g − c|/R
        // (to O(θ⁴)) where the contact runs into a span's straight contour at θ past it
        let per_contour = dist.max(r) / r;
        let rho = self.sp.inertia.unwrap_or(0.0);
        let weight = self.params.weight.unwrap_or(0.0);
        let ea = self.params.axial_stiffness;
        let p = (ea * (lam - 1.0) - rho * c * c * lam) / r + weight * ey / lam;
        let dp_dlam = (ea - rho * c * c) / r - weight * ey / (lam * lam);
        (per_contour * p, dlam.map(|d| per_contour * dp_dlam * d), -per_contour * 2.0 * rho * c * lam / r)
    }

    /// The normal traction of a friction point of the open layout, and of the loop for an
    /// element with [`FrictionNormal::Tributary`] (docs/fem-cosserat.md §11.1, §12.3): the mean contact pressure ⟨λ − Pγ⟩₊ (the penalty's P⟨−γ⟩ without multipliers, §12.5) of the two elements at the node over the
    /// contact rule's points, weighted by the elements' halves at the node — the pressure
    /// the penalty term actually applies. (The nodal gap is no measure of it for the
    /// Cosserat element at the default penalty: the penalty, sampled at the rule's points
    /// only, leaves the cubic ν above the pulley at the nodes by ~10 times the
    /// penetration, measured.)
    pub(super) fn tributary_normal(&self, pt: FrictionPoint, z: &[f64], grad: bool) -> (f64, [f64; P]) {
        let layout = self.asm.kernel().layout();
        let rule = self.asm.kernel().rules().contact;
        let (mut p, mut dp) = (0.0, [0.0; P]);
        // a contact-side half (docs/fem-cosserat.md §11.1): its contact element's mean alone
        for (side, e) in [(0, pt.left.0), (1, pt.right.0)] {
            let Some(f) = pt.side_share(side) else { continue };
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            for &(xi, wg) in rule.points() {
                let Some((g, dg)) = point_gap(layout, &el, &q, xi, grad) else { continue };
                let t = self.asm.kernel().contact_traction(self.sp.penalty, el.sigma(xi), Some(g));
                if t > 0.0 {
                    // the element mean: Σ w_g ⟨λ_g − Pγ_g⟩₊ / 2
                    p += f * 0.5 * wg * t;
                    for k in 0..N {
                        dp[side * N + k] -= f * 0.5 * wg * self.sp.penalty * dg[k];
                    }
                }
            }
        }
        (p, dp)
    }

    /// The residual entries and Jacobian block of friction point i in its variables
    /// (q_left, q_right, c, ω₂, τ_i): (DS1) −wτλ̄ on the S-row of the node, (DS2)
    /// +wτλ̄, (DS3) −wτ (driven), (DS4) w(τ − clip(τ + κv, −b, b)) with v = cλ̄ − Rω_k,
    /// b = μp with p the normal load of the element's [`FrictionNormal`] rule (λ̄: the upwind element's mean).
    /// The Jacobian block only if `jacobian` (else the values by plain f64 evaluation).
    pub(super) fn point_terms(&self, i: usize, x: &[f64], force_stick: bool, jacobian: bool) -> PointTerms<P> {
        let (z, c, w2, tau) = (&x[..self.asm.len()], x[self.ic()], x[self.iw()], x[self.it(i)]);
        let pt = self.points[i];
        let sp = &self.sp;
        let w = pt.weight;
        let layout = self.asm.kernel().layout();
        // λ̄ of the point's velocity element (DS0), γ̄ the trapezoidal mean of the
        // node's two edges, with gradients in (q_left, q_right)
        let (lam, dlam) = {
            let e = pt.velocity_element();
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let (l, dl) = element_stretch(layout, &el, &q, jacobian);
            // (q_left, q_right) in the first 2N entries
            let mut d = [0.0; P];
            let off = if pt.velocity_from_right() { N } else { 0 };
            d[off..off + N].copy_from_slice(&dl);
            (l, d)
        };
        // the element's rule on the loop; the open layout's is the tributary pressure
        let mut eq_dc = 0.0;
        let (normal, dnormal) = match (sp.ends, self.asm.kernel().friction_normal()) {
            // Paper D's fixed topology on the string: the drum's reaction from the belt's
            // radial equilibrium (docs/fem-drive.md §12, fourth round)
            (Ends::Loop, FrictionNormal::Nodal) if pt.fixed.is_some() => {
                let (p, dp, dpc) = self.equilibrium_normal(pt, z, c, jacobian);
                eq_dc = dpc;
                (p, dp)
            }
            (Ends::Loop, FrictionNormal::Nodal) => self.nodal_normal(pt, z, jacobian),
            (Ends::Loop, FrictionNormal::Tributary) | (Ends::Open { .. }, _) => self.tributary_normal(pt, z, jacobian),
        };
        let (ic, iw, it) = (2 * N, 2 * N + 1, 2 * N + 2);
        let mut r = [0.0; P];
        let mut block = jacobian.then(|| Box::new([[0.0; P]; P]));
        // (DS1)–(DS3) are the elements' consistent friction loads (`element_friction`)
        let driven = pt.pulley == Pulley::Driven;
        // (DS4)
        let (omega, omega_unknown) = sp.point_speed(driven, w2);
        let v = c * lam - sp.radius * omega;
        let b = sp.mu * normal;
        let y = tau + sp.kappa * v;
        // Paper D's fixed topology prescribes the row of a point in contact (spec §3.5)
        let fixed = pt.fixed.filter(|_| b > 0.0);
        let slip = match fixed {
            Some(Fixed::Stick) => false,
            Some(Fixed::Slip(_) | Fixed::Free) => true,
            None => y.abs() >= b && !force_stick,
        };
        if slip {
            let s = match fixed {
                Some(Fixed::Slip(s)) => s,
                Some(Fixed::Free) => 0.0,
                _ if b > 0.0 => y.signum(),
                _ => 0.0,
            };
            r[it] = w * (tau - b * s);
            if let Some(j) = block.as_deref_mut() {
                j[it][it] = w;
                for k in 0..2 * N {
                    j[it][k] = -w * s * sp.mu * dnormal[k];
                }
                j[it][ic] = -w * s * sp.mu * eq_dc;
            }
        } else if pt.is_entry() && fixed == Some(Fixed::Stick) && self.asm.kernel().friction_normal() == FrictionNormal::Nodal {
            // a stick entry half of Paper D's contact-side halves: its own element's
            // kinematic row is its downstream neighbour's, so its row is the stick zone's
            // traction at the run-on point, the weight along the belt −(ρg/λ)∂σy on its
            // contact side (docs/fem-drive.md §12, "Sixth round")
            let (side, xi) = if pt.part == Part::Right { (1, -1.0) } else { (0, 1.0) };
            let e = if side == 1 { pt.right.0 } else { pt.left.0 };
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let (t_eq, dt) = tangential_weight(layout, &el, &q, xi, self.params.weight.unwrap_or(0.0), jacobian);
            r[it] = w * (tau - t_eq);
            if let Some(j) = block.as_deref_mut() {
                j[it][it] = w;
                for k in 0..N {
                    j[it][side * N + k] = -w * dt[k];
                }
            }
        } else {
            r[it] = -w * sp.kappa * v;
            if let Some(j) = block.as_deref_mut() {
                for k in 0..2 * N {
                    j[it][k] = -w * sp.kappa * c * dlam[k];
                }
                j[it][ic] = -w * sp.kappa * lam;
                if omega_unknown {
                    j[it][iw] = w * sp.kappa * sp.radius;
                }
            }
        }
        (r, block, PointResult { point: pt, traction: tau, normal, velocity: v, slip: slip && b > 0.0 })
    }
}

/// Add a local residual `r` into `residual` at the global indices `idx` (None: a fixed
/// unknown, skipped) and, if `values` is given, the local Jacobian block `jac(a, b)` in
/// pattern order: per present row a, the present columns b, then the column `extra` of
/// that row if given (the c column of the inertia term).
fn scatter(idx: &[Option<usize>], r: &[f64], jac: &dyn Fn(usize, usize) -> f64, extra: Option<usize>, residual: &mut [f64], mut values: Option<&mut Vec<f64>>) {
    for (a, ga) in idx.iter().enumerate() {
        let Some(ga) = ga else { continue };
        residual[*ga] += r[a];
        if let Some(values) = values.as_deref_mut() {
            for (b, gb) in idx.iter().enumerate() {
                if gb.is_some() {
                    values.push(jac(a, b));
                }
            }
            if let Some(b) = extra {
                values.push(jac(a, b));
            }
        }
    }
}
