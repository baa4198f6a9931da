//! Direct steady-state solve of the friction drive (docs/fem-drive.md §12, the
//! Papers C/D concept for the string): the time-invariant state at fixed σ is sought
//! directly — nodal unknowns z, transport rate c, driven speed ω₂ and one friction
//! traction per friction point — as the root of the steady equations (DS1)–(DS4) by a
//! semismooth Newton method with an active set (stick/slip per point), under a
//! continuation in the load and the transport inertia, on a mesh fitted to the four
//! contact boundaries and the two stick→slip transitions.

use std::f64::consts::PI;
use std::sync::Arc;

use drive::contour::{Contour, Pulley, Region};
use nalgebra::SVector;
use num_dual::{gradient, hessian};
use drive::view::SolutionView;
use rayon::prelude::*;

use crate::assembly::Assembler;
use crate::error::{FemError, NewtonFailure};
use crate::formulation::Kernel;
use crate::kinematics::{ElementContext, Scalar, TermParams, NDOF};
use crate::linear::BorderedLu;
use crate::mesh::Mesh;
use crate::quadrature::Rule;
use crate::solution::FemSolution;

use super::contact::reachable_pulley;

/// One friction point of the steady problem (docs/fem-drive.md §12): a node within
/// reach of a pulley. Its stretch and gap are the trapezoidal means over the two element
/// edges that meet there (equal except at a region transition, where the slopes are
/// separate); one traction per node, so the node's S-equation carries one unknown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPoint {
    /// σ of the node, m.
    pub sigma: f64,
    /// The pulley the point can touch.
    pub pulley: Pulley,
    /// Trapezoidal weight (h_left + h_right)/2, m.
    pub weight: f64,
    /// The node.
    pub node: usize,
    /// Element ending at the node (its edge ξ = +1) and its weight h/2.
    pub left: (usize, f64),
    /// Element starting at the node (its edge ξ = −1) and its weight h/2.
    pub right: (usize, f64),
    /// The whole node, or one half of a node split at a fitted stick→slip transition.
    pub part: Part,
}

/// Which share of a node a friction point carries (docs/fem-drive.md §12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Both edges, weight (h_l + h_r)/2, v upwind (the element ending at the node).
    Whole,
    /// The upstream half of a transition node: weight h_l/2, v of the element ending
    /// there (the stick side).
    Left,
    /// The downstream half: weight h_r/2, v of the element starting there (the slip
    /// side) — so the traction jump at the transition sits exactly at the node.
    Right,
}

impl FrictionPoint {
    /// The element whose stretch λ̄ gives the point's velocity (DS0).
    pub fn velocity_element(&self) -> usize {
        if self.part == Part::Right {
            self.right.0
        } else {
            self.left.0
        }
    }

    /// σ where the point's velocity is sampled: the midpoint of its element.
    pub fn velocity_sigma(&self) -> f64 {
        if self.part == Part::Right {
            self.sigma + self.right.1
        } else {
            self.sigma - self.left.1
        }
    }
}

/// The state of a friction point in a converged steady solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointResult {
    /// The point.
    pub point: FrictionPoint,
    /// τ_⊥, force per contour length of the belt on the drum along +σ, N/m.
    pub traction: f64,
    /// Normal traction P⟨−γ⟩, N/m.
    pub normal: f64,
    /// Relative velocity v = cλ − Rω_k of belt and drum surface, m/s.
    pub velocity: f64,
    /// Slip (|τ + κv| ≥ b with b > 0).
    pub slip: bool,
}

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
}

/// The steady problem on one mesh: X = (z, c, ω₂, τ₁ … τ_m).
pub struct SteadyProblem<'a> {
    /// Assembler of the string (strain, gravity, normal penalty in its params).
    pub asm: &'a Assembler,
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

/// The friction points of a mesh (docs/fem-drive.md §12): one per node within reach of
/// a pulley, two (the halves [`Part::Left`], [`Part::Right`]) at a node within 10⁻⁶ of
/// its element lengths of one of the stick→slip transitions `splits` (σ).
pub fn friction_points(asm: &Assembler, splits: &[f64]) -> Vec<FrictionPoint> {
    let mesh = asm.mesh();
    let contour = mesh.contour();
    let lc = contour.length();
    let n = mesh.len();
    let mut out = Vec::new();
    for k in 0..n {
        let left = (k + n - 1) % n;
        let (el_l, el_r) = (mesh.elements()[left], mesh.elements()[k]);
        let sigma = mesh.node_sigmas()[k];
        let reach = |region: Region| reachable_pulley(contour, region, sigma);
        let pulley = reach(el_r.region).or_else(|| reach(el_l.region));
        let Some(pulley) = pulley else { continue };
        let whole = FrictionPoint { sigma, pulley, weight: 0.5 * (el_l.h + el_r.h), node: k, left: (left, 0.5 * el_l.h), right: (k, 0.5 * el_r.h), part: Part::Whole };
        if splits.iter().any(|&t| wrapped_diff(t, sigma, lc).abs() <= 1e-6 * (el_l.h + el_r.h)) {
            out.push(FrictionPoint { weight: 0.5 * el_l.h, part: Part::Left, ..whole });
            out.push(FrictionPoint { weight: 0.5 * el_r.h, part: Part::Right, ..whole });
        } else {
            out.push(whole);
        }
    }
    out
}

/// The gap γ at a point of an element and its gradient in the element's q; `None`
/// where no pulley can be reached (F10).
fn point_gap(el: &ElementContext, q: &[f64; NDOF], xi: f64) -> Option<(f64, [f64; NDOF])> {
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
fn element_stretch(el: &ElementContext, q: &[f64; NDOF]) -> (f64, [f64; NDOF]) {
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

/// −T of (D8) for one element with c an unknown: −∫ ρc²|∂σr|²/(2∂σS) dσ (strain rule).
fn inertia_energy<D: Scalar>(el: &ElementContext, q: &[D; NDOF], c: D, rho: f64, rule: Rule) -> D {
    let jac = el.jacobian();
    let mut total = c * 0.0;
    for &(xi, wt) in rule.points() {
        let p = el.fields(q, xi);
        let t = el.tangent_length(&p);
        total -= t * t / p.ds * c * c * (0.5 * rho * wt * jac);
    }
    total
}

/// Entries of one friction point: rows and columns in the point's variable list
/// (q of the left element, q of the right element, c, ω₂, τ, and for the slip half of a
/// split node the τ of its stick half) — see [`SteadyProblem::variables`].
const NPV: usize = 2 * NDOF + 4;

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
const NEV: usize = NDOF + 4;

/// Residual entries and Jacobian block of an element's friction load.
type ElementLoad = ([f64; NEV], [[f64; NEV]; NEV]);

/// Quadrature of the friction load (DS1)–(DS3): 4-point Gauss–Legendre (τ linear × λ ×
/// a cubic shape function).
const FRICTION_RULE: Rule = Rule::Gauss(4);

impl SteadyProblem<'_> {
    /// Number of unknowns nz + 2 + m.
    pub fn len(&self) -> usize {
        self.asm.len() + 2 + self.points.len()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Index of c, ω₂ and of τ_i.
    fn ic(&self) -> usize {
        self.asm.len()
    }
    fn iw(&self) -> usize {
        self.asm.len() + 1
    }
    fn it(&self, i: usize) -> usize {
        self.asm.len() + 2 + i
    }

    /// The global indices of point i's variables (q of the left and right elements,
    /// c, ω₂, τ_i). The node's own unknowns appear twice (once per element); the pattern
    /// sums duplicates.
    fn variables(&self, i: usize) -> [Option<usize>; NPV] {
        let pt = &self.points[i];
        let il = self.asm.dofs().element(pt.left.0);
        let ir = self.asm.dofs().element(pt.right.0);
        let partner = (pt.part == Part::Right && i > 0 && self.points[i - 1].part == Part::Left).then(|| self.it(i - 1));
        std::array::from_fn(|k| match k {
            k if k < NDOF => il[k],
            k if k < 2 * NDOF => ir[k - NDOF],
            k if k == 2 * NDOF => Some(self.ic()),
            k if k == 2 * NDOF + 1 => Some(self.iw()),
            k if k == 2 * NDOF + 2 => Some(self.it(i)),
            _ => partner,
        })
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
    fn element_variables(&self, e: usize, owners: [Option<usize>; 2]) -> [Option<usize>; NEV] {
        let idx = self.asm.dofs().element(e);
        std::array::from_fn(|k| match k {
            k if k < NDOF => idx[k],
            k if k == NDOF => Some(self.ic()),
            k if k == NDOF + 1 => Some(self.iw()),
            k if k == NDOF + 2 => owners[0].map(|i| self.it(i)),
            _ => owners[1].map(|i| self.it(i)),
        })
    }

    /// (DS1)–(DS3) of one element, the consistent (Galerkin) friction load with τ
    /// linear between its edge values: −∫ τ λ ∂S/∂q dσ on the S-rows (values and
    /// slopes), +∫ τ λ dσ on the c-row, −∫ τ dσ on the ω₂-row of a driven element;
    /// with its Jacobian in (q, c, ω₂, τ_a, τ_b).
    fn element_friction(&self, e: usize, z: &[f64], tau: [f64; 2], driven: bool) -> ElementLoad {
        let el = self.asm.context(e, &self.params);
        let q = self.asm.dofs().gather(e, z, self.length);
        let qv = SVector::<f64, NDOF>::from_fn(|i, _| q[i]);
        let jac = el.jacobian();
        let h = el.geometry.h;
        let (ic, iw, ia) = (NDOF, NDOF + 1, NDOF + 2);
        let mut r = [0.0; NEV];
        let mut j = [[0.0; NEV]; NEV];
        for &(xi, wg) in FRICTION_RULE.points() {
            let (lam, dl) = gradient(
                |v| {
                    let qq: [_; NDOF] = std::array::from_fn(|i| v[i]);
                    el.stretch(&el.fields(&qq, xi))
                },
                &qv,
            );
            let shape = [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)];
            let t = shape[0] * tau[0] + shape[1] * tau[1];
            let w = wg * jac;
            let (vw, _) = crate::hermite::weights(xi, h);
            // S = Σ vw_k (s_a, s'_a, s_b, s'_b): local indices 0, 1, 4, 5
            for (k, &loc) in [0usize, 1, 4, 5].iter().enumerate() {
                r[loc] -= w * t * lam * vw[k];
                for m in 0..NDOF {
                    j[loc][m] -= w * t * dl[m] * vw[k];
                }
                for a in 0..2 {
                    j[loc][ia + a] -= w * shape[a] * lam * vw[k];
                }
            }
            r[ic] += w * t * lam;
            for m in 0..NDOF {
                j[ic][m] += w * t * dl[m];
            }
            for a in 0..2 {
                j[ic][ia + a] += w * shape[a] * lam;
            }
            if driven {
                r[iw] -= w * t;
                for a in 0..2 {
                    j[iw][ia + a] -= w * shape[a];
                }
            }
        }
        (r, j)
    }

    /// Slip dissipation D = ∫ τ v dσ, v = cλ − Rω_k, with the quadrature and the
    /// linear τ of the friction load — so P_in = P_out + D holds by (DS2) to round-off.
    pub fn dissipation(&self, x: &[f64]) -> f64 {
        let z = &x[..self.asm.len()];
        let (c, w2) = (x[self.ic()], x[self.iw()]);
        let mut d = 0.0;
        for (e, o) in self.edge_owners().into_iter().enumerate() {
            let Some(first) = o[0].or(o[1]) else { continue };
            let omega = if self.points[first].pulley == Pulley::Driven { w2 } else { self.sp.omega1 };
            let tau = [o[0].map_or(0.0, |i| x[self.it(i)]), o[1].map_or(0.0, |i| x[self.it(i)])];
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
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
        // transport inertia (D8) with c an unknown: rows q, columns (q, c)
        if let Some(rho) = sp.inertia {
            let per: Vec<(f64, [f64; NDOF + 1], [[f64; NDOF + 1]; NDOF + 1])> = (0..self.asm.mesh().len())
                .into_par_iter()
                .map(|e| {
                    let el = self.asm.context(e, &self.params);
                    let q = self.asm.dofs().gather(e, z, self.length);
                    let v = SVector::<f64, { NDOF + 1 }>::from_fn(|i, _| if i < NDOF { q[i] } else { c });
                    let (en, g, h) = hessian(
                        |v| {
                            let qq: [_; NDOF] = std::array::from_fn(|i| v[i]);
                            inertia_energy(&el, &qq, v[NDOF], rho, self.strain_rule)
                        },
                        &v,
                    );
                    (en, std::array::from_fn(|i| g[i]), std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)])))
                })
                .collect();
            for (e, (_, g, h)) in per.iter().enumerate() {
                let idx = self.asm.dofs().element(e);
                for (i, gi) in idx.iter().enumerate() {
                    let Some(gi) = gi else { continue };
                    residual[*gi] += g[i];
                    if with_jacobian {
                        for (j, gj) in idx.iter().enumerate() {
                            if gj.is_some() {
                                values.push(h[i][j]);
                            }
                        }
                        values.push(h[i][NDOF]);
                    }
                }
            }
        }
        // friction points (DS1)–(DS4)
        let mut per: Vec<([f64; NPV], [[f64; NPV]; NPV], PointResult)> = (0..self.points.len())
            .into_par_iter()
            .map(|i| self.point_terms(i, z, c, w2, x[self.it(i)], false))
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
                per[k] = self.point_terms(k, z, c, w2, x[self.it(k)], true);
            }
        }
        // both halves of a split node sticking would be two multipliers on one node
        // (proportional columns): the slip half then carries the stick half's traction,
        // w_R (τ_R − τ_L) = 0 — the whole node's behaviour (§12)
        for i in 1..per.len() {
            if self.points[i].part == Part::Right && self.points[i - 1].part == Part::Left && !per[i].2.slip && !per[i - 1].2.slip {
                let w = self.points[i].weight;
                let it = 2 * NDOF + 2;
                per[i].0[it] = w * (x[self.it(i)] - x[self.it(i - 1)]);
                per[i].1[it] = [0.0; NPV];
                per[i].1[it][it] = w;
                per[i].1[it][NPV - 1] = -w;
            }
        }
        let mut results = Vec::with_capacity(self.points.len());
        for (i, (r, j, res)) in per.into_iter().enumerate() {
            let v = self.variables(i);
            for (a, ga) in v.iter().enumerate() {
                let Some(ga) = ga else { continue };
                residual[*ga] += r[a];
                if with_jacobian {
                    for (b, gb) in v.iter().enumerate() {
                        if gb.is_some() {
                            values.push(j[a][b]);
                        }
                    }
                }
            }
            results.push(res);
        }
        // (DS1)–(DS3): the consistent friction load of every element with friction points
        let owners = self.edge_owners();
        let loads: Vec<Option<ElementLoad>> = owners
            .par_iter()
            .enumerate()
            .map(|(e, o)| {
                let first = o[0].or(o[1])?;
                let tau = [o[0].map_or(0.0, |i| x[self.it(i)]), o[1].map_or(0.0, |i| x[self.it(i)])];
                Some(self.element_friction(e, z, tau, self.points[first].pulley == Pulley::Driven))
            })
            .collect();
        for (e, load) in loads.into_iter().enumerate() {
            let Some((r, j)) = load else { continue };
            let v = self.element_variables(e, owners[e]);
            for (a, ga) in v.iter().enumerate() {
                let Some(ga) = ga else { continue };
                residual[*ga] += r[a];
                if with_jacobian {
                    for (b, gb) in v.iter().enumerate() {
                        if gb.is_some() {
                            values.push(j[a][b]);
                        }
                    }
                }
            }
        }
        // the driven pulley's torque balance (DS3) divided by R: + (M₂ + d₂ω₂)/R
        residual[self.iw()] += (sp.torque + sp.damping * w2) / sp.radius;
        if with_jacobian {
            values.push(0.0);
            values.push(sp.damping / sp.radius);
        }
        let finite = residual.iter().all(|v| v.is_finite()) && values.iter().all(|v| v.is_finite());
        finite.then_some(Evaluated { residual, values, results })
    }

    /// The residual entries and Jacobian block of friction point i in its variables
    /// (q_left, q_right, c, ω₂, τ_i): (DS1) −wτλ̄ on the S-row of the node, (DS2)
    /// +wτλ̄, (DS3) −wτ (driven), (DS4) w(τ − clip(τ + κv, −b, b)) with v = cλ̄ − Rω_k,
    /// b = μP⟨−γ̄⟩ (λ̄, γ̄: trapezoidal means of the two edges).
    fn point_terms(&self, i: usize, z: &[f64], c: f64, w2: f64, tau: f64, force_stick: bool) -> ([f64; NPV], [[f64; NPV]; NPV], PointResult) {
        let pt = self.points[i];
        let sp = &self.sp;
        let w = pt.weight;
        // λ̄ of the point's velocity element (DS0), γ̄ the trapezoidal mean of the
        // node's two edges, with gradients in (q_left, q_right)
        let (lam, dlam) = {
            let e = pt.velocity_element();
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let (l, dl) = element_stretch(&el, &q);
            let mut d = [0.0; 2 * NDOF];
            let off = if pt.part == Part::Right { NDOF } else { 0 };
            d[off..off + NDOF].copy_from_slice(&dl);
            (l, d)
        };
        let mut gap: Option<(f64, [f64; 2 * NDOF])> = Some((0.0, [0.0; 2 * NDOF]));
        let node_weight = pt.left.1 + pt.right.1;
        for (side, (e, we), xi) in [(0, pt.left, 1.0), (1, pt.right, -1.0)] {
            let el = self.asm.context(e, &self.params);
            let q = self.asm.dofs().gather(e, z, self.length);
            let g = point_gap(&el, &q, xi);
            let f = we / node_weight;
            gap = match (gap, g) {
                (Some((acc, mut dacc)), Some((gv, dg))) => {
                    for k in 0..NDOF {
                        dacc[side * NDOF + k] += f * dg[k];
                    }
                    Some((acc + f * gv, dacc))
                }
                _ => None,
            };
        }
        let (ic, iw, it) = (2 * NDOF, 2 * NDOF + 1, 2 * NDOF + 2);
        let mut r = [0.0; NPV];
        let mut j = [[0.0; NPV]; NPV];
        // (DS1)–(DS3) are the elements' consistent friction loads (`element_friction`)
        let driven = pt.pulley == Pulley::Driven;
        // (DS4)
        let omega = if driven { w2 } else { sp.omega1 };
        let v = c * lam - sp.radius * omega;
        let (normal, dnormal) = match gap {
            Some((g, dg)) if g < 0.0 => (-sp.penalty * g, dg.map(|d| -sp.penalty * d)),
            _ => (0.0, [0.0; 2 * NDOF]),
        };
        let b = sp.mu * normal;
        let y = tau + sp.kappa * v;
        let slip = y.abs() >= b && !force_stick;
        if slip {
            let s = if b > 0.0 { y.signum() } else { 0.0 };
            r[it] = w * (tau - b * s);
            j[it][it] = w;
            for k in 0..2 * NDOF {
                j[it][k] = -w * s * sp.mu * dnormal[k];
            }
        } else {
            r[it] = -w * sp.kappa * v;
            for k in 0..2 * NDOF {
                j[it][k] = -w * sp.kappa * c * dlam[k];
            }
            j[it][ic] = -w * sp.kappa * lam;
            if driven {
                j[it][iw] = w * sp.kappa * sp.radius;
            }
        }
        (r, j, PointResult { point: pt, traction: tau, normal, velocity: v, slip: slip && b > 0.0 })
    }
}

/// Norm weights of X (docs/fem-drive.md §12): z as the step system (H for values, 1 for
/// slopes), R ω₁ for c, ω₁ for ω₂, 10³ F_ref/R for the tractions (they follow z; the
/// round-off of the stiff normal penalty, ≈ 10⁻⁸ N in the ν-rows, would otherwise keep
/// their update above 10⁻¹⁰ of F_ref/R).
fn variable_weights(asm: &Assembler, h: f64, r: f64, omega1: f64, f_ref: f64, m: usize) -> Vec<f64> {
    let mut w = super::system::weights(asm, h, r, 1.0);
    w.truncate(asm.len());
    w.push(r * omega1);
    w.push(omega1);
    w.extend(std::iter::repeat_n(1e3 * f_ref / r, m));
    w
}

/// Row scales of the merit ½‖F‖²: 1/F_ref for force rows, 1/(F_ref h_node) for the
/// slope rows (whose residuals are moments, N·m).
fn row_scales(asm: &Assembler, f_ref: f64, m: usize) -> Vec<f64> {
    let dofs = asm.dofs();
    let mut s: Vec<f64> = dofs
        .kinds()
        .iter()
        .zip(dofs.spacing())
        .map(|(k, sp)| if *k == crate::dofs::DofKind::Value { 1.0 / f_ref } else { 1.0 / (f_ref * sp) })
        .collect();
    s.extend(std::iter::repeat_n(1.0 / f_ref, 2 + m));
    s
}

fn merit(r: &[f64], s: &[f64]) -> f64 {
    0.5 * r.iter().zip(s).map(|(a, b)| (a * b) * (a * b)).sum::<f64>()
}

/// A problem with its pattern.
struct Patterned<'p, 'a> {
    problem: &'p SteadyProblem<'a>,
    rows: Vec<usize>,
    cols: Vec<usize>,
}

impl<'p, 'a> Patterned<'p, 'a> {
    fn new(problem: &'p SteadyProblem<'a>) -> Self {
        let (rows, cols) = problem.pattern();
        Patterned { problem, rows, cols }
    }
}

impl<'a> std::ops::Deref for Patterned<'_, 'a> {
    type Target = SteadyProblem<'a>;
    fn deref(&self) -> &SteadyProblem<'a> {
        self.problem
    }
}

/// Work of one semismooth Newton solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SteadyNewton {
    /// Iterations.
    pub iterations: usize,
    /// Last scaled update.
    pub update_norm: f64,
}

/// Semismooth Newton on F(X) = 0 from `x` (overwritten on success): the generalised
/// Jacobian of the current active set, a backtracking line search on the merit
/// ½‖F‖² (the best trial is taken if none decreases it enough — the active set may
/// change along the step), converged when the full step's scaled norm is ≤ `tolerance`
/// and the active set did not change.
///
/// # Errors
/// [`NewtonFailure`] with the iteration count and the last update norm.
pub fn newton(problem: &SteadyProblem, x: &mut [f64], w: &[f64], scales: &[f64], tolerance: f64, max_iterations: usize) -> Result<SteadyNewton, NewtonFailure> {
    let n = x.len();
    let problem = &Patterned::new(problem);
    let mut lu = BorderedLu::new(&problem.rows, &problem.cols, n, [problem.ic(), problem.iw()]).map_err(NewtonFailure::Pattern)?;
    let mut report = SteadyNewton::default();
    let mut last_update = f64::INFINITY;
    let mut trial = vec![0.0; n];
    let mut small_before = false;
    let mut floor_count = 0usize;
    loop {
        let Some(ev) = problem.evaluate(x, true) else {
            return Err(NewtonFailure::Inadmissible { iteration: report.iterations });
        };
        if report.iterations >= max_iterations {
            return Err(NewtonFailure::NotConverged { iterations: report.iterations, update: last_update, tolerance });
        }
        report.iterations += 1;
        let m0 = merit(&ev.residual, scales);
        // a singular generalised Jacobian (an active set without a unique solution) is
        // regularised on its diagonal, Levenberg–Marquardt style, 1e-12 → 1e-4 of D
        let mut step: Vec<f64> = ev.residual.iter().map(|r| -r).collect();
        let solved = lu.solve(&ev.values, &[], &mut step);
        if let Err(e) = solved {
            let mut d = vec![0.0; n];
            for (k, &v) in ev.values.iter().enumerate() {
                if problem.rows[k] == problem.cols[k] {
                    d[problem.rows[k]] += v;
                }
            }
            let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut ok = false;
            for f in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4] {
                let shift: Vec<f64> = d.iter().map(|v| f * v.abs().max(1e-6 * dmax).max(1e-300)).collect();
                step.iter_mut().zip(&ev.residual).for_each(|(s, r)| *s = -r);
                if lu.solve(&ev.values, &shift, &mut step).is_ok() {
                    ok = true;
                    break;
                }
            }
            if !ok {
                return Err(NewtonFailure::Singular { matrix: "Jacobian", iteration: report.iterations, detail: e });
            }
        }
        let unorm = super::system::scaled_norm(&step, w);
        last_update = unorm;
        // a step below the tolerance is taken whole (the merit is at round-off)
        let small = unorm <= tolerance;
        let mut best: Option<(f64, f64)> = None;
        let mut alpha = 1.0;
        let mut accepted = None;
        while alpha >= 1.0 / 1024.0 {
            for i in 0..n {
                trial[i] = x[i] + alpha * step[i];
            }
            if let Some(et) = problem.evaluate(&trial, false) {
                let mt = merit(&et.residual, scales);
                if small || mt <= (1.0 - 1e-4 * alpha) * m0 {
                    accepted = Some((alpha, et, mt));
                    break;
                }
                if best.is_none_or(|(_, m)| mt < m) {
                    best = Some((alpha, mt));
                }
            }
            alpha *= 0.5;
        }
        // the accepted trial's evaluation and merit are those of the new x
        let (alpha, same_set, merit_after, after) = match accepted {
            Some((a, et, mt)) => (a, et.results.iter().zip(&ev.results).all(|(p, q)| p.slip == q.slip), mt, Some(et)),
            None => match best {
                Some((a, mt)) => (a, false, mt, None),
                None => return Err(NewtonFailure::LineSearch { what: "no admissible step", iteration: report.iterations, update: unorm }),
            },
        };
        for i in 0..n {
            x[i] += alpha * step[i];
        }
        // the round-off floor: steps within 10³ of the tolerance that no longer reduce
        // the merit by 10 % for 3 iterations on the same active set (fine meshes of a
        // stiff normal penalty)
        floor_count = if unorm <= 1e3 * tolerance && same_set && merit_after > 0.9 * m0 { floor_count + 1 } else { 0 };
        // converged: a whole step below the tolerance that kept the active set, or two
        // in a row (a point exactly at its slip bound may flip at round-off)
        if (alpha == 1.0 && small && (same_set || small_before)) || floor_count >= 3 {
            // a point taken as stick only to give its pulley an equation (see
            // `evaluate`) must obey Coulomb's bound by itself at the solution
            if let Some(p) = after.and_then(|e| e.results.into_iter().find(|p| !p.slip && p.traction.abs() > problem.sp.mu * p.normal * (1.0 + 1e-8) + 1e-12)) {
                return Err(NewtonFailure::NoCoulombState { traction: p.traction.abs(), bound: problem.sp.mu * p.normal, sigma: p.point.sigma });
            }
            report.update_norm = unorm;
            return Ok(report);
        }
        small_before = alpha == 1.0 && small;
    }
}

/// Work of a direct steady solve (in the run's `options.drive`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SteadyReport {
    /// Accepted continuation steps in η (load and inertia scaled by η), η = 0 included.
    pub continuation_steps: usize,
    /// Rejected continuation steps.
    pub rejected: usize,
    /// Newton iterations over all solves.
    pub newton_iterations: usize,
    /// Fitting passes (each a Newton solve on a refitted mesh).
    pub fits: usize,
    /// Fitting passes whose Newton solve failed and were retried with a smaller move.
    pub rejected_fits: usize,
    /// True if the fitting converged (every boundary within the tolerance of a node).
    pub fit_converged: bool,
    /// Largest distance of a recovered boundary or transition from its node after the
    /// last pass, m.
    pub fit_last_move: Option<f64>,
    /// Why a fitting pass failed (the solution is then the last converged one).
    pub fit_failure: Option<String>,
    /// Friction points (one per node within reach of a pulley; two at a split node).
    pub friction_points: usize,
    /// Wall time of the static start (homotopy of fem-string.md §9), s.
    pub static_seconds: f64,
    /// Wall time of the load continuation, s.
    pub continuation_seconds: f64,
    /// Wall time of the fitting passes, s.
    pub fitting_seconds: f64,
}

/// A converged steady state on one mesh.
struct State {
    /// ρ of the transport inertia (kg/m), if any.
    rho: Option<f64>,
    asm: Assembler,
    x: Vec<f64>,
    results: Vec<PointResult>,
}

/// Unwrapped σ of a pulley's zone (the driver's straddles σ = 0).
fn unwrapped(contour: &Contour, pulley: Pulley, sigma: f64) -> f64 {
    super::unwrap(contour, pulley, sigma)
}

/// The stick→slip transition of a pulley (docs/fem-drive.md §12): the zero of the
/// relative velocity v of the trailing slip run — each point's v is the stretch of its
/// element, placed at the element's midpoint — extrapolated by the quadratic through the
/// 2nd–4th distinct samples (the line through the first two on a short run), clamped
/// between the stick point before the last one and the second slip sample; `None` if the
/// pulley has no stick point or no slip point.
pub fn transition(results: &[PointResult], contour: &Contour, pulley: Pulley) -> Option<f64> {
    let mut pts: Vec<&PointResult> = results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
    pts.sort_by(|a, b| unwrapped(contour, pulley, a.point.sigma).total_cmp(&unwrapped(contour, pulley, b.point.sigma)));
    let last_stick = pts.iter().rposition(|p| !p.slip)?;
    if last_stick + 1 >= pts.len() {
        return None;
    }
    let s = |p: &PointResult| unwrapped(contour, pulley, p.point.sigma);
    let mid = |p: &PointResult| unwrapped(contour, pulley, p.point.velocity_sigma());
    let a = pts[last_stick];
    // the distinct velocity samples of the slip run (the slip half of a split node and
    // the next node share their element), up to four
    let mut samples: Vec<&PointResult> = Vec::with_capacity(4);
    for p in &pts[last_stick + 1..] {
        if samples.last().is_none_or(|q| (mid(p) - mid(q)).abs() > 1e-12) {
            samples.push(p);
        }
        if samples.len() == 4 {
            break;
        }
    }
    let b = samples[0];
    let mut sigma = 0.5 * (s(a) + s(b));
    // the zero may lie up to one element upstream of the last stick point or up to the
    // second slip sample downstream
    let lo = if last_stick > 0 { s(pts[last_stick - 1]) } else { s(a) };
    let hi = samples.get(1).map_or(s(b), |c| s(c));
    let linear = |p: &PointResult, q: &PointResult| {
        let (mp, mq) = (mid(p), mid(q));
        (mq > mp && (q.velocity - p.velocity).abs() > 0.0).then(|| mp - p.velocity * (mq - mp) / (q.velocity - p.velocity))
    };
    // the quadratic through the 2nd–4th samples (the first slip element carries the
    // stick zone's alternating layer, §12), else the line through the first two
    let root = match samples[..] {
        [_, p, q, r] => {
            let (x0, x1, x2) = (mid(p), mid(q), mid(r));
            let (y0, y1, y2) = (p.velocity, q.velocity, r.velocity);
            // v = y0 + d1 (x − x0) + d2 (x − x0)(x − x1)
            let d1 = (y1 - y0) / (x1 - x0);
            let d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
            // in t = x − x0: d2 t² + (d1 − d2 (x1 − x0)) t + y0 = 0, the root nearest the line's
            let (qa, qb, qc) = (d2, d1 - d2 * (x1 - x0), y0);
            let guess = linear(p, q);
            let disc = qb * qb - 4.0 * qa * qc;
            if qa.abs() > 0.0 && disc >= 0.0 {
                let sq = disc.sqrt();
                let t1 = (-qb + sq) / (2.0 * qa);
                let t2 = (-qb - sq) / (2.0 * qa);
                let g = guess.map_or(x0, |g| g - x0);
                Some(x0 + if (t1 - g).abs() < (t2 - g).abs() { t1 } else { t2 })
            } else {
                guess
            }
        }
        [p, q, ..] => linear(p, q),
        _ => None,
    };
    if let Some(root) = root.filter(|r| r.is_finite()) {
        sigma = root.clamp(lo, hi);
    }
    Some(contour.wrap(sigma))
}

/// Signed periodic difference a − b on a contour of length l, in (−l/2, l/2].
fn wrapped_diff(a: f64, b: f64, l: f64) -> f64 {
    let d = (a - b).rem_euclid(l);
    if d > 0.5 * l {
        d - l
    } else {
        d
    }
}

/// Solve a friction-drive scene (see [`super::applies`]) for its steady state directly
/// (docs/fem-drive.md §12).
///
/// # Errors
/// As [`super::solve`] without the transient's step errors: [`FemError::Unsupported`]
/// (ω₁ ≤ 0), [`FemError::InvalidOption`], the static start's errors,
/// [`FemError::FrictionCapacityExceeded`], [`FemError::SpeedAtOrAboveCritical`],
/// [`FemError::HomotopyStalled`] (the load continuation failed otherwise),
/// [`FemError::SteadyFitFailed`], [`FemError::NonFinite`].
pub fn solve(problem: &crate::problem::FemProblem, opts: &crate::options::FemOptions, settings: &crate::options::SolverSettings, drive_settings: &super::DriveSettings, kernel: Arc<dyn Kernel>) -> Result<crate::FemRun, FemError> {
    let clock = std::time::Instant::now();
    let super::DriveStart { mu, omega1, start, report: homotopy, penalty, t_static, f_ref } = super::drive_start(problem, opts, settings, drive_settings, kernel.clone())?;
    let static_seconds = clock.elapsed().as_secs_f64();
    let b = &problem.belt;
    let r = problem.geometry.radius;
    let contour = *start.mesh().contour();
    let h = contour.centre_distance();
    let (load_torque, damping) = (problem.drive.driven_torque, problem.drive.driven_damping);
    let weight = problem.weight();
    let params = TermParams { axial_stiffness: b.axial_stiffness, weight, penalty: Some(penalty), bending_stiffness: None };
    let length = b.length;
    let strain_rule = kernel.rules().strain;
    let inertia = problem.effects.inertia;
    let asm = Assembler::new(start.mesh().clone(), kernel.clone());
    let arc_elements = asm.mesh().elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1);
    // κ = P_⊥ Δt₀: the transient's tangential penalty times its default step (§5, §7)
    let kappa = drive_settings.tangential_penalty_factor * b.axial_stiffness / (r * r) * (PI * r / arc_elements as f64) / (r * omega1);
    let sp_at = |eta: f64| SteadyParams {
        mu,
        penalty,
        kappa,
        radius: r,
        omega1,
        torque: eta * load_torque,
        damping: eta * damping,
        inertia: inertia.then_some(eta * b.mass_per_length),
    };
    let lambda0 = 1.0 + t_static / b.axial_stiffness;
    // critical speed, checked on the start state with c = Rω₁/λ₀ (docs/fem-drive.md §6)
    if inertia {
        let c0 = r * omega1 / lambda0;
        check_critical(&start, b.mass_per_length * c0 * c0)?;
    }
    let points = friction_points(&asm, &[]);
    let mut x = crate::string_hanging::transfer(&start, &asm);
    x.extend([r * omega1 / lambda0, omega1]);
    x.extend(std::iter::repeat_n(0.0, points.len()));
    let mut report = SteadyReport { friction_points: points.len(), static_seconds, ..Default::default() };
    let tol = settings.update_tolerance;
    let max_it = drive_settings.max_newton_iterations;

    // continuation in η: load M₂, d₂ and inertia ρ scaled by η (§12)
    let w = variable_weights(&asm, h, r, omega1, f_ref, points.len());
    let scales = row_scales(&asm, f_ref, points.len());
    let mut eta: f64 = 0.0;
    let mut step: f64 = 1.0;
    let min_step = 1e-4;
    let mut last_results: Vec<PointResult> = Vec::new();
    let mut first = true;
    loop {
        let target = if first { 0.0 } else { (eta + step).min(1.0) };
        let prob = SteadyProblem { asm: &asm, params, length, points: &points, sp: sp_at(target), strain_rule };
        let mut xt = x.clone();
        match newton(&prob, &mut xt, &w, &scales, tol, max_it) {
            Ok(n) => {
                report.newton_iterations += n.iterations;
                report.continuation_steps += 1;
                x = xt;
                eta = target;
                last_results = prob.evaluate(&x, false).map(|e| e.results).unwrap_or_default();
                if inertia {
                    let sol = FemSolution::new(asm.mesh().clone(), asm.dofs(), &x[..asm.len()], params, length, kernel.clone());
                    let c = x[asm.len()];
                    check_critical(&sol, eta * b.mass_per_length * c * c)?;
                }
                if !first && n.iterations <= 6 {
                    step *= 2.0;
                }
                first = false;
                if eta >= 1.0 {
                    break;
                }
            }
            Err(reason) => {
                report.newton_iterations += max_it;
                report.rejected += 1;
                step *= 0.5;
                if first || step < min_step {
                    // the continuation stalls where a pulley's load reaches what its
                    // contact can carry, R Σ w μ P⟨−γ⟩ of the last converged state (full
                    // slip): within 5 % of it, the named error with the whole load
                    let demand = load_torque + damping * x[asm.len() + 1];
                    for pulley in [Pulley::Driven, Pulley::Driver] {
                        let pts: Vec<&PointResult> = last_results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
                        let capacity = r * pts.iter().map(|p| p.point.weight * mu * p.normal).sum::<f64>();
                        if !pts.is_empty() && target * demand >= 0.95 * capacity {
                            return Err(FemError::FrictionCapacityExceeded { pulley: pulley.name().to_string(), torque: demand, capacity, time: None });
                        }
                    }
                    return Err(FemError::HomotopyStalled { eta, step, min_step, steps: report.continuation_steps, last_failure: reason.to_string() });
                }
            }
        }
    }
    let mut state = State { asm, x, results: last_results, rho: inertia.then_some(b.mass_per_length) };
    report.continuation_seconds = clock.elapsed().as_secs_f64() - static_seconds;

    // fitting: a node at every contact boundary and stick→slip transition (§12)
    let element = PI * r / arc_elements as f64;
    if settings.contact_fitting {
        let tol_fit = settings.fit_tolerance * contour.length();
        let lc = contour.length();
        // the breakpoints the current mesh was fitted to, and (x, F = g(x) − x) of the
        // pass before: a secant per breakpoint on F(x) = 0 (as fem-string.md §5; the
        // plain iteration x ← g(x) oscillates for the drive's transitions)
        let mut fitted_to: Option<Vec<f64>> = None;
        let mut move_limit: f64 = 0.3;
        let (mut best_move, mut best_pass, mut passes) = (f64::INFINITY, 0usize, 0usize);
        let mut previous: Option<(Vec<f64>, Vec<f64>)> = None;
        for _ in 0..drive_settings.max_fits {
            let sol = FemSolution::new(state.asm.mesh().clone(), state.asm.dofs(), &state.x[..state.asm.len()], params, length, kernel.clone())
                .with_transport_inertia(rho_c2(&state));
            let mut breaks = sol.contact_boundaries();
            let boundaries = breaks.len();
            breaks.extend([Pulley::Driver, Pulley::Driven].iter().filter_map(|&p| transition(&state.results, &contour, p)));
            let nodes = state.asm.mesh().node_sigmas();
            let moved = breaks.iter().map(|&s| nodes.iter().map(|&n| wrapped_diff(n, s, lc).abs()).fold(f64::INFINITY, f64::min)).fold(0.0f64, f64::max);
            report.fit_last_move = Some(moved);
            if moved <= tol_fit {
                report.fit_converged = true;
                break;
            }
            // stalled below 5 % of an element: no 10 % gain over the best pass in 4
            // passes (a point the mesh cannot take, e.g. within 2 % of an element of a
            // region transition, where `Mesh::fitted` keeps the transition node)
            if moved < 0.9 * best_move {
                best_move = moved;
                best_pass = passes;
            } else if passes >= best_pass + 4 && moved < 0.05 * element {
                break;
            }
            passes += 1;
            let residual: Option<Vec<f64>> = fitted_to.as_ref().filter(|x| x.len() == breaks.len()).map(|x| breaks.iter().zip(x).map(|(g, x)| wrapped_diff(*g, *x, lc)).collect());
            let next: Vec<f64> = match (&fitted_to, &residual, &previous) {
                (Some(x), Some(f), Some((xp, fp))) if xp.len() == x.len() => (0..x.len())
                    .map(|i| {
                        let dx = wrapped_diff(x[i], xp[i], lc);
                        let df = f[i] - fp[i];
                        if df.abs() > 1e-12 * lc && dx != 0.0 {
                            let step = -f[i] * dx / df;
                            // a secant step beyond twice the plain one is not trusted
                            contour.wrap(x[i] + if step.abs() <= 2.0 * f[i].abs() { step } else { f[i] })
                        } else {
                            breaks[i]
                        }
                    })
                    .collect(),
                _ => breaks.clone(),
            };
            // at most 0.3 of the local element length per pass (÷4 after a failed pass,
            // down to 0.02): a refit is then a small perturbation of the transferred
            // state (a kink moved across an element leaves the stiff normal penalty far
            // from equilibrium)
            let nodes_now = state.asm.mesh().node_sigmas().to_vec();
            let next: Vec<f64> = next
                .iter()
                .zip(&breaks)
                .map(|(&target, &g)| {
                    let near = nodes_now.iter().copied().min_by(|a, b| wrapped_diff(*a, g, lc).abs().total_cmp(&wrapped_diff(*b, g, lc).abs())).unwrap_or(g);
                    let (e, _) = state.asm.mesh().locate(g);
                    let limit = move_limit * state.asm.mesh().elements()[e].h;
                    let d = wrapped_diff(target, near, lc);
                    if d.abs() > limit {
                        contour.wrap(near + limit * d.signum())
                    } else {
                        target
                    }
                })
                .collect();
            previous = match (fitted_to.take(), residual) {
                (Some(x), Some(f)) => Some((x, f)),
                _ => None,
            };
            let breaks = next;
            let Ok((mesh, _)) = Mesh::fitted(contour, opts.elements, settings.arc_weight, &breaks) else {
                report.fit_failure = Some("the fitted mesh could not be built".into());
                break;
            };
            let asm = Assembler::new(mesh, kernel.clone());
            // the node at each fitted transition is split into its stick and slip halves
            let points = friction_points(&asm, &breaks[boundaries..]);
            let mut x = crate::string_hanging::transfer(&sol, &asm);
            let nz_old = state.asm.len();
            x.extend([state.x[nz_old], state.x[nz_old + 1]]);
            x.extend(points.iter().map(|p| interpolate_traction(&state.results, &contour, p)));
            let prob = SteadyProblem { asm: &asm, params, length, points: &points, sp: sp_at(1.0), strain_rule };
            let w = variable_weights(&asm, h, r, omega1, f_ref, points.len());
            let scales = row_scales(&asm, f_ref, points.len());
            // the transferred state is far from equilibrium in the stiff normal penalty
            // where a kink moved between elements: on failure, a penalty ladder
            // P/10⁵ → P from the transferred state
            let x0 = x.clone();
            let mut solved = newton(&prob, &mut x, &w, &scales, tol, max_it);
            if solved.is_err() {
                x.copy_from_slice(&x0);
                let mut iterations = 0;
                for f in [1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0] {
                    let soft = TermParams { penalty: Some(f * penalty), ..params };
                    let sp = SteadyParams { penalty: f * penalty, ..sp_at(1.0) };
                    let p = SteadyProblem { asm: &asm, params: soft, length, points: &points, sp, strain_rule };
                    solved = newton(&p, &mut x, &w, &scales, tol, max_it).map(|n| {
                        iterations += n.iterations;
                        SteadyNewton { iterations, ..n }
                    });
                    if solved.is_err() {
                        break;
                    }
                }
            }
            match solved {
                Ok(n) => {
                    report.newton_iterations += n.iterations;
                    report.fits += 1;
                    let results = prob.evaluate(&x, false).map(|e| e.results).unwrap_or_default();
                    state = State { asm, x, results, rho: state.rho };
                    fitted_to = Some(breaks);
                    move_limit = (2.0 * move_limit).min(0.3);
                }
                Err(reason) => {
                    if move_limit > 0.02 {
                        move_limit *= 0.25;
                        report.rejected_fits += 1;
                        continue;
                    }
                    report.fit_failure = Some(reason.to_string());
                    break;
                }
            }
        }
    }
    report.fitting_seconds = clock.elapsed().as_secs_f64() - static_seconds - report.continuation_seconds;
    // an unresolved fit leaves the stick/slip arcs wrong by a fraction of an element or
    // more: a named error above 5 % of an arc element (§12; the unresolved cases
    // measured sit at 10–50 %, the stalled but resolved ones at ≤ 1 %)
    if let Some(m) = report.fit_last_move.filter(|m| settings.contact_fitting && !report.fit_converged && *m > 0.05 * element) {
        let reason = report.fit_failure.clone().unwrap_or_else(|| "the passes did not converge".into());
        return Err(FemError::SteadyFitFailed { passes: report.fits + report.rejected_fits, last_move: m, element, reason });
    }
    finish(problem, opts, settings, drive_settings, kernel, state, params, penalty, kappa, mu, homotopy, report, clock)
}

/// τ at a new friction point from the old solution: linear in σ between the two old
/// points of the same pulley that enclose it (the nearer one at a zone end).
fn interpolate_traction(old: &[PointResult], contour: &Contour, p: &FrictionPoint) -> f64 {
    let s = unwrapped(contour, p.pulley, p.sigma);
    let mut pts: Vec<(f64, f64)> = old.iter().filter(|o| o.point.pulley == p.pulley).map(|o| (unwrapped(contour, p.pulley, o.point.sigma), o.traction)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    if pts.is_empty() {
        return 0.0;
    }
    let k = pts.partition_point(|q| q.0 <= s);
    if k == 0 {
        return pts[0].1;
    }
    if k == pts.len() {
        return pts[k - 1].1;
    }
    let (a, b) = (pts[k - 1], pts[k]);
    if b.0 > a.0 {
        a.1 + (b.1 - a.1) * (s - a.0) / (b.0 - a.0)
    } else {
        a.1
    }
}

/// ρc² of a state (0 without inertia).
fn rho_c2(state: &State) -> f64 {
    let c = state.x[state.asm.len()];
    state.rho.map_or(0.0, |rho| rho * c * c)
}

/// SpeedAtOrAboveCritical if N − ρc²λ ≤ 0 at a span midpoint of `sol` (ρc² given).
fn check_critical(sol: &FemSolution, rc2: f64) -> Result<(), FemError> {
    let c = sol.mesh().contour();
    let (h, r) = (c.centre_distance(), c.radius());
    for (span, sigma) in [("upper", 0.5 * h), ("lower", 1.5 * h + PI * r)] {
        let n = sol.recovered_axial_force(sigma);
        let stretch = sol.stretch(sigma);
        if n - rc2 * stretch <= 0.0 {
            return Err(FemError::SpeedAtOrAboveCritical { span: span.into(), tension: n, inertia_force: rc2 * stretch, time: None });
        }
    }
    Ok(())
}

/// Outputs of a converged steady state (docs/fem-drive.md §8, §12).
#[allow(clippy::too_many_arguments)]
fn finish(
    problem: &crate::problem::FemProblem,
    opts: &crate::options::FemOptions,
    settings: &crate::options::SolverSettings,
    drive_settings: &super::DriveSettings,
    kernel: Arc<dyn Kernel>,
    state: State,
    params: TermParams,
    penalty: f64,
    kappa: f64,
    mu: f64,
    homotopy: crate::string_hanging::HomotopyReport,
    report: SteadyReport,
    clock: std::time::Instant,
) -> Result<crate::FemRun, FemError> {
    let asm = &state.asm;
    let nz = asm.len();
    let mesh = asm.mesh();
    let contour = *mesh.contour();
    let r = contour.radius();
    let length = problem.belt.length;
    let (c, omega2) = (state.x[nz], state.x[nz + 1]);
    let omega1 = problem.drive.driver_speed;
    let (load_torque, damping) = (problem.drive.driven_torque, problem.drive.driven_damping);
    let base = FemSolution::new(mesh.clone(), asm.dofs(), &state.x[..nz], params, length, kernel.clone()).with_transport_inertia(rho_c2(&state));
    let mut summary = base.summary();
    // T_tight, T_slack: the axial forces of the driver's and the driven pulley's stick
    // zones (creep theory's, as the BVP's, docs/string-drive.md) — constant there (λ̄
    // pinned), taken midway between the contact entry and the transition; the larger /
    // smaller mid-span force where a pulley has no stick zone or no recovered zone
    let (tu, tl) = (summary.tension_upper_mid.unwrap_or(0.0), summary.tension_lower_mid.unwrap_or(0.0));
    let stick_force = |pulley: Pulley| super::stick_zone_force(&base, pulley, transition(&state.results, &contour, pulley));
    summary.tension_tight = Some(stick_force(Pulley::Driver).unwrap_or(tu.max(tl)));
    summary.tension_slack = Some(stick_force(Pulley::Driven).unwrap_or(tu.min(tl)));
    summary.driven_speed = Some(omega2);
    summary.transport_rate = Some(c);
    let mut torques = [0.0; 2];
    let mut entry_slip_force: f64 = 0.0;
    for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
        let mut pts: Vec<&PointResult> = state.results.iter().filter(|p| p.point.pulley == pulley).collect();
        torques[k] = r * pts.iter().map(|p| p.point.weight * p.traction).sum::<f64>();
        pts.retain(|p| p.normal > 0.0);
        pts.sort_by(|a, b| unwrapped(&contour, pulley, a.point.sigma).total_cmp(&unwrapped(&contour, pulley, b.point.sigma)));
        if let Some(i) = pts.iter().position(|p| !p.slip) {
            entry_slip_force = entry_slip_force.max(pts[..i].iter().map(|p| p.point.weight * p.traction).sum::<f64>().abs());
        }
        let angle = |sigma: f64| contour.polar_angle(pulley, base.position(contour.wrap(sigma)));
        let zone = base.zone(pulley);
        let (arc, end_angle) = match (zone, pts.first(), pts.last()) {
            (Some(z), _, _) => ((z.angle_start - z.angle_end).rem_euclid(2.0 * PI), z.angle_end),
            (None, Some(a), Some(b)) => ((angle(a.point.sigma) - angle(b.point.sigma)).rem_euclid(2.0 * PI), angle(b.point.sigma)),
            _ => (0.0, 0.0),
        };
        let slip = if pts.is_empty() || pts.iter().all(|p| !p.slip) {
            0.0
        } else if pts.iter().all(|p| p.slip) {
            arc
        } else {
            transition(&state.results, &contour, pulley).map_or(0.0, |s| (angle(s) - end_angle).rem_euclid(2.0 * PI).min(arc))
        };
        let block = if k == 0 { &mut summary.driver } else { &mut summary.driven };
        let ps = block.get_or_insert_with(drive::summary::PulleySummary::default);
        ps.contact_arc = ps.contact_arc.or(Some(arc));
        ps.slip_arc = Some(slip);
        ps.stick_arc = Some((ps.contact_arc.unwrap_or(arc) - slip).max(0.0));
        ps.torque = Some(torques[k]);
    }
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let points: Vec<FrictionPoint> = state.results.iter().map(|p| p.point).collect();
    let sp = SteadyParams { mu, penalty, kappa, radius: r, omega1, torque: load_torque, damping, inertia: None };
    let dissipation = SteadyProblem { asm, params, length, points: &points, sp, strain_rule: kernel.rules().strain }.dissipation(&state.x);
    let power_in = -torques[0] * omega1;
    let power_out = (load_torque + damping * omega2) * omega2;
    let max_penetration = base.max_penetration();
    let per_element = view_points(&state, params, length, &kernel);
    let view = super::DriveSolution::new(base, &per_element, summary.clone());
    let mut terms = kernel.term_labels(&TermParams { penalty: None, ..params });
    terms.push(format!("Coulomb contact, direct steady state (semismooth Newton, μ = {mu}, P_γ = {penalty:.6e} N/m², friction on the nodes)"));
    terms.push(format!("driven load M₂ = {load_torque} N·m, d₂ = {damping} N·m·s"));
    if problem.effects.inertia {
        terms.push(format!("transport inertia (ρ = {} kg/m)", problem.belt.mass_per_length));
    }
    let options = opts.record(Some(penalty), settings, serde_json::json!({
        "drive": {
            "solver": "steady",
            "settings": drive_settings,
            "kappa": kappa,
            "steady": true,
            "report": report,
            "power_in": power_in,
            "power_out": power_out,
            "dissipation": dissipation,
            "max_penetration": max_penetration,
            "entry_slip_force": entry_slip_force,
        },
        "homotopy": homotopy,
    }));
    let stats = crate::FemStats {
        wall_seconds: clock.elapsed().as_secs_f64(),
        newton_iterations: homotopy.newton_iterations + report.newton_iterations,
        unknowns: state.x.len(),
        elements: opts.elements,
        homotopy_steps: homotopy.steps + report.continuation_steps,
    };
    Ok(crate::FemRun { view: Box::new(view), summary, stats, options, terms, history: None })
}

/// Per element the point states the common view reads (docs/fem-drive.md §8): the
/// contact rule's points with their normal traction, the two edges with the traction
/// and state of their friction point.
fn view_points(state: &State, params: TermParams, length: f64, kernel: &Arc<dyn Kernel>) -> Vec<Vec<super::ViewPoint>> {
    let asm = &state.asm;
    let mesh = asm.mesh();
    let contour = mesh.contour();
    let n = mesh.len();
    let penalty = params.penalty.unwrap_or(0.0);
    let mut edge: Vec<[Option<PointResult>; 2]> = vec![[None, None]; n];
    for res in &state.results {
        // a node's point stands for both elements' edges, a half for its own side
        if res.point.part != Part::Right {
            edge[res.point.left.0][1] = Some(*res);
        }
        if res.point.part != Part::Left {
            edge[res.point.right.0][0] = Some(*res);
        }
    }
    let rule = kernel.rules().contact;
    (0..n)
        .map(|e| {
            let el = asm.context(e, &params);
            let q = asm.dofs().gather(e, &state.x[..asm.len()], length);
            super::contact::mixed_rule(rule)
                .into_iter()
                .map(|(xi, w, wf)| {
                    let sigma = el.sigma(xi);
                    let p = el.fields(&q, xi);
                    let pulley = reachable_pulley(contour, el.geometry.region, sigma);
                    let normal = match (pulley, el.gap(&p)) {
                        (Some(_), Some(g)) => (-penalty * g).max(0.0),
                        _ => 0.0,
                    };
                    let fr = if wf > 0.0 { edge[e][usize::from(xi > 0.0)] } else { None };
                    super::ViewPoint {
                        xi,
                        sigma,
                        pulley,
                        weight: w * el.jacobian(),
                        friction_weight: if fr.is_some() { el.jacobian() } else { 0.0 },
                        normal,
                        tangential: fr.map_or(0.0, |f| f.traction),
                        slip: fr.is_some_and(|f| f.slip),
                    }
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    //! The generalised Jacobian of (DS1)–(DS4) and of the inertia term against central
    //! differences of the residual F, at a converged drive state with gravity and
    //! inertia perturbed off equilibrium, for every column whose perturbation keeps the
    //! active set (stick/slip of every point and the sign of every gap) unchanged.
    use super::*;

    const SCENE: &str = r#"{
      "name": "jacobian",
      "drive": {"pulley_radius": 0.08, "centre_distance": 0.45, "driver_speed": 10.0, "driven_torque": 2.0, "driven_damping": 0.01},
      "belt": {"theory": "string", "length": 1.3956749, "axial_stiffness": 20000.0, "mass_per_length": 0.12},
      "effects": {"gravity": 9.81, "inertia": true, "contact": {"coulomb": 0.3}},
      "analysis": "steady",
      "fem": {"elements": 24}
    }"#;

    #[test]
    fn jacobian_matches_finite_differences() {
        let scene = drive::Scene::from_json_str(SCENE).unwrap();
        let opts = crate::options::FemOptions::from_scene(&scene, crate::default_formulation());
        let settings = crate::options::SolverSettings::default();
        let kernel = crate::formulation::find(&opts.formulation).unwrap();
        let super::super::DriveStart { start, penalty, .. } = super::super::drive_start(&crate::problem::FemProblem::from_scene(&scene), &opts, &settings, &super::super::DriveSettings::default(), kernel.clone()).unwrap();
        let asm = Assembler::new(start.mesh().clone(), kernel.clone());
        let points = friction_points(&asm, &[]);
        let b = &scene.belt;
        let params = TermParams { axial_stiffness: b.axial_stiffness, weight: Some(9.81 * b.mass_per_length), penalty: Some(penalty), bending_stiffness: None };
        // a soft penalty keeps the FD of the normal term well conditioned
        let params = TermParams { penalty: Some(1e-3 * penalty), ..params };
        let sp = SteadyParams { mu: 0.3, penalty: 1e-3 * penalty, kappa: 10.0, radius: 0.08, omega1: 10.0, torque: 2.0, damping: 0.01, inertia: Some(0.12) };
        let prob = SteadyProblem { asm: &asm, params, length: b.length, points: &points, sp, strain_rule: kernel.rules().strain };
        let mut x = crate::string_hanging::transfer(&start, &asm);
        x.extend([0.79, 9.9]);
        // tractions of both signs, some above their bound (slip), some below (stick)
        x.extend((0..points.len()).map(|i| if i % 2 == 0 { 3000.0 } else { 10.0 } * ((i as f64) * 1.7).sin()));
        for (i, v) in x.iter_mut().enumerate().take(asm.len()) {
            *v += 1e-7 * ((i as f64) * 0.37).cos();
        }
        // pressed into the drums by 10 µm: a bound μP⟨−γ⟩ ≈ 900 N/m at the contact nodes
        for k in 0..asm.mesh().len() {
            x[asm.dofs().node(k).nu] -= 1e-5;
        }
        let n = x.len();
        let ev = prob.evaluate(&x, true).unwrap();
        let (rows, cols) = prob.pattern();
        let mut dense = vec![0.0; n * n];
        for (k, v) in ev.values.iter().enumerate() {
            dense[rows[k] * n + cols[k]] += v;
        }
        let signature = |e: &Evaluated| e.results.iter().map(|p| (p.slip, p.normal > 0.0)).collect::<Vec<_>>();
        let base = signature(&ev);
        let fmax = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut checked, mut worst) = (0, 0.0f64);
        for j in 0..n {
            let d = 1e-7 * x[j].abs().max(1e-4);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += d;
            xm[j] -= d;
            let (ep, em) = (prob.evaluate(&xp, false).unwrap(), prob.evaluate(&xm, false).unwrap());
            if signature(&ep) != base || signature(&em) != base {
                continue;
            }
            checked += 1;
            for i in 0..n {
                let fd = (ep.residual[i] - em.residual[i]) / (2.0 * d);
                let err = (fd - dense[i * n + j]).abs();
                worst = worst.max(err / fmax);
                assert!(err <= 1e-6 * fmax + 1e-6 * fd.abs(), "J[{i}][{j}]: analytic {} FD {fd}", dense[i * n + j]);
            }
        }
        assert!(checked > n / 2, "only {checked} of {n} columns kept the active set");
        assert!(base.iter().any(|p| p.0) && base.iter().any(|p| !p.0 && p.1), "both stick and slip points are exercised");
        assert!(worst < 1e-6);
    }
}
