//! The geometrically linearised, pre-tensioned Kirchhoff rod pressed by a rigid stamp
//! (§6.3, Fig. 5a of the reference): its closed form and a Hermite beam FE with penalty
//! contact, to check how a penalty FE represents the concentrated edge forces of an
//! unshearable rod in contact. Derivation, conventions and measured numbers:
//! `docs/rod-stamp.md` (equations (T1)–(T8) cited below).
//!
//! This module is standalone: it shares only the Hermite shape functions, the quadrature
//! rules and the sparse LU with the MEL elements.

use thiserror::Error;

use crate::hermite;
use crate::linear::SparseLu;
use crate::quadrature::Rule;

/// The data of the stamp problem (SI units), docs/rod-stamp.md "Problem".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stamp {
    /// Half span ℓ between the pinned supports, m (> 0).
    pub half_span: f64,
    /// Bending stiffness EI, N·m² (> 0).
    pub bending_stiffness: f64,
    /// Axial pre-tension F, N (> 0).
    pub axial_force: f64,
    /// Radius ρ of the stamp face, m (> 0); linearised to a parabola (T1).
    pub stamp_radius: f64,
    /// Indentation δ: height of the stamp apex above the supports, m.
    pub indentation: f64,
}

impl Stamp {
    /// The parameters of Fig. 5a of the reference (§6.3; docs/rod-stamp.md): ℓ = 1 m,
    /// EI = 1 N·m², F = 100 N, ρ = 1 m, δ = 0.2 m.
    pub const FIG_5A: Stamp = Stamp {
        half_span: 1.0,
        bending_stiffness: 1.0,
        axial_force: 100.0,
        stamp_radius: 1.0,
        indentation: 0.2,
    };
}

/// Why the stamp problem has no (contact-zone) solution.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StampError {
    /// A parameter is non-finite or out of range.
    #[error("invalid stamp input: {name} = {value} ({reason})")]
    InvalidInput {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// δ outside (δ₀, ℓ²/2ρ) of (T6): point contact or a stamp reaching the supports.
    #[error(
        "no contact zone: indentation δ = {indentation} m must lie between the point-contact onset δ₀ = {onset} m and the full-contact value ℓ²/(2ρ) = {full} m (docs/rod-stamp.md, T6)"
    )]
    NoContactZone {
        indentation: f64,
        onset: f64,
        full: f64,
    },
    /// Cosserat rod (docs/rod-stamp.md, C-10): b₂ ≤ F makes β² = (b₂ − F)/EI ≤ 0 — the
    /// pre-tension reaches the shear stiffness (shear-critical), no edge layer exists.
    #[error(
        "shear-critical Cosserat rod: shear stiffness b₂ = {shear_stiffness} N must exceed the axial force F = {axial_force} N (β² = (b₂ − F)/EI > 0, docs/rod-stamp.md C2)"
    )]
    ShearCritical {
        shear_stiffness: f64,
        axial_force: f64,
    },
    /// Cosserat rod: δ ≤ 0, the stamp apex does not rise above the supports (any δ > 0
    /// gives a contact zone: the shearable rod has no point-contact regime).
    #[error(
        "no contact: indentation δ = {indentation} m ≤ 0, the stamp does not reach the straight rod (docs/rod-stamp.md C9)"
    )]
    NoContact { indentation: f64 },
    /// Cosserat rod: δ ≥ ℓ²/(2ρ), the stamp face reaches the supports.
    #[error(
        "stamp wider than the span: indentation δ = {indentation} m ≥ ℓ²/(2ρ) = {full} m, the stamp face reaches the supports (docs/rod-stamp.md C9)"
    )]
    StampWiderThanSpan { indentation: f64, full: f64 },
    /// Cosserat rod: the free rod dips below the stamp face (gap < 0 outside the zone).
    #[error("the free rod penetrates the stamp: gap {gap} m at x = {x} m (docs/rod-stamp.md C10)")]
    Penetration { x: f64, gap: f64 },
    /// The scalar root of (T5) or the FE Newton iteration failed.
    #[error("stamp solver: {0}")]
    Solver(String),
}

impl Stamp {
    pub(crate) fn validate(&self) -> Result<(), StampError> {
        for (name, value) in [
            ("half_span", self.half_span),
            ("bending_stiffness", self.bending_stiffness),
            ("axial_force", self.axial_force),
            ("stamp_radius", self.stamp_radius),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(StampError::InvalidInput {
                    name,
                    value,
                    reason: "must be finite and > 0",
                });
            }
        }
        if !self.indentation.is_finite() {
            return Err(StampError::InvalidInput {
                name: "indentation",
                value: self.indentation,
                reason: "must be finite",
            });
        }
        Ok(())
    }

    /// k = √(F/EI), 1/m.
    pub fn k(&self) -> f64 {
        (self.axial_force / self.bending_stiffness).sqrt()
    }

    /// The stamp face w_s(x) (T1), m.
    pub fn face(&self, x: f64) -> f64 {
        self.indentation - x * x / (2.0 * self.stamp_radius)
    }

    /// The contact-zone range (δ₀, ℓ²/2ρ) of the indentation (T6), m.
    pub fn indentation_range(&self) -> (f64, f64) {
        let (l, k, r) = (self.half_span, self.k(), self.stamp_radius);
        (
            l / ((k * l).tanh() * r * k) - 1.0 / (r * k * k),
            l * l / (2.0 * r),
        )
    }
}

/// The closed-form solution (T3)–(T7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedForm {
    /// The data.
    pub stamp: Stamp,
    /// Contact half width a, m.
    pub half_width: f64,
    /// Constant pressure F/ρ inside the zone (T3), N/m.
    pub pressure: f64,
    /// Concentrated force P at each edge (T7), N.
    pub edge_force: f64,
    /// Downward force of each support, = P + F a/ρ (balance), N.
    pub support_reaction: f64,
    b: f64,
    c: f64,
}

impl ClosedForm {
    /// The deflection w(x), m, for |x| ≤ ℓ.
    pub fn deflection(&self, x: f64) -> f64 {
        let x = x.abs();
        if x <= self.half_width {
            self.stamp.face(x)
        } else {
            let xi = x - self.stamp.half_span;
            self.b * xi + self.c * (self.stamp.k() * xi).sinh()
        }
    }

    /// Total upward force of the stamp, 2aF/ρ + 2P, N.
    pub fn stamp_force(&self) -> f64 {
        2.0 * self.half_width * self.pressure + 2.0 * self.edge_force
    }
}

/// (B, C, f(a)) of (T4)–(T5).
fn edge_conditions(s: &Stamp, a: f64) -> (f64, f64, f64) {
    let (k, r) = (s.k(), s.stamp_radius);
    let d = a - s.half_span;
    let c = -1.0 / (r * k * k * (k * d).sinh());
    let b = -a / r + 1.0 / ((k * d).tanh() * r * k);
    let f = b * d - 1.0 / (r * k * k) - s.indentation + a * a / (2.0 * r);
    (b, c, f)
}

/// The closed form of docs/rod-stamp.md: the half width a from (T5) by Brent's method,
/// then (T3), (T4), (T7).
///
/// # Errors
/// [`StampError::InvalidInput`], [`StampError::NoContactZone`] (δ outside (T6)),
/// [`StampError::Solver`] if the root is not found.
pub fn closed_form(stamp: &Stamp) -> Result<ClosedForm, StampError> {
    stamp.validate()?;
    let (onset, full) = stamp.indentation_range();
    if !(stamp.indentation > onset && stamp.indentation < full) {
        return Err(StampError::NoContactZone {
            indentation: stamp.indentation,
            onset,
            full,
        });
    }
    let l = stamp.half_span;
    // f(0) = δ₀ − δ < 0 and f(ℓ⁻) → ℓ²/2ρ − δ > 0; stay off ℓ where coth k(a − ℓ) blows up.
    let (lo, hi) = (0.0, l * (1.0 - 1e-12));
    let residual = |a: f64| Ok::<f64, std::convert::Infallible>(edge_conditions(stamp, a).2);
    let a = numerics::roots::brent(residual, lo, hi, 1e-15 * l)
        .map_err(|e| StampError::Solver(format!("Brent on (T5): {e}")))?;
    let (b, c, _) = edge_conditions(stamp, a);
    let k = stamp.k();
    let pressure = stamp.axial_force / stamp.stamp_radius;
    let edge_force = stamp.bending_stiffness * k / (stamp.stamp_radius * (k * (l - a)).tanh());
    Ok(ClosedForm {
        stamp: *stamp,
        half_width: a,
        pressure,
        edge_force,
        support_reaction: edge_force + pressure * a,
        b,
        c,
    })
}

/// Options of the FE model (docs/rod-stamp.md "The FE model").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StampFeOptions {
    /// Number of elements on [−ℓ, ℓ], even and ≥ 2.
    pub elements: usize,
    /// Penalty factor P_γ, N/m² (> 0).
    pub penalty: f64,
    /// Gauss points per element for the contact term (1…5).
    pub quadrature_points: u8,
    /// Iteration cap of the semismooth Newton iteration.
    pub max_iterations: usize,
}

impl Default for StampFeOptions {
    fn default() -> Self {
        Self {
            elements: 64,
            penalty: 1e8,
            quadrature_points: 4,
            max_iterations: 200,
        }
    }
}

/// The FE solution.
#[derive(Debug, Clone, PartialEq)]
pub struct StampFe {
    /// The data.
    pub stamp: Stamp,
    /// The options used.
    pub options: StampFeOptions,
    /// Node coordinates x_i, m.
    pub nodes: Vec<f64>,
    /// Nodal deflections w_i, m.
    pub deflection: Vec<f64>,
    /// Nodal slopes w′_i.
    pub slope: Vec<f64>,
    /// Downward reactions at the left and right support, N.
    pub support_reactions: [f64; 2],
    /// ∫ p_h dx, N.
    pub stamp_force: f64,
    /// Semismooth Newton iterations, all penalty stages.
    pub iterations: usize,
}

impl StampFe {
    fn element_length(&self) -> f64 {
        2.0 * self.stamp.half_span / self.options.elements as f64
    }

    /// (w, w′) of element e at ξ ∈ [−1, 1].
    fn fields(&self, e: usize, xi: f64) -> (f64, f64) {
        let h = self.element_length();
        let (v, d) = hermite::weights(xi, h);
        let q = [
            self.deflection[e],
            self.slope[e],
            self.deflection[e + 1],
            self.slope[e + 1],
        ];
        (dot(&v, &q), dot(&d, &q))
    }

    /// The penalty pressure p_h = P_γ ⟨−g⟩₊ at each contact integration point, as
    /// (x, weight·h/2, p).
    pub fn pressure_points(&self) -> Vec<(f64, f64, f64)> {
        let h = self.element_length();
        let rule = Rule::Gauss(self.options.quadrature_points);
        let mut out = Vec::with_capacity(self.options.elements * rule.points().len());
        for e in 0..self.options.elements {
            for &(xi, wq) in rule.points() {
                let x = self.nodes[e] + 0.5 * (1.0 + xi) * h;
                let g = self.fields(e, xi).0 - self.stamp.face(x);
                out.push((x, 0.5 * h * wq, self.options.penalty * (-g).max(0.0)));
            }
        }
        out
    }

    /// Largest |x| of an integration point in contact, m (0 without contact).
    pub fn half_width(&self) -> f64 {
        self.pressure_points()
            .iter()
            .filter(|p| p.2 > 0.0)
            .map(|p| p.0.abs())
            .fold(0.0, f64::max)
    }

    /// The edge force of docs/rod-stamp.md: ∫_{|x| > x_c} p_h dx / 2 − (F/ρ)(a − x_c), the
    /// penalty force beyond the cut x_c minus the distributed part inside the exact zone
    /// (mean of both edges), for the edge position `a` and the window Δ = `window`. The
    /// cut x_c is the node nearest to a − Δ, so that whole elements are integrated (a cut
    /// inside an element would add an O(h F/ρ) quadrature error), N.
    pub fn edge_force(&self, a: f64, window: f64) -> f64 {
        let h = self.element_length();
        let cut = ((a - window + self.stamp.half_span) / h).round() * h - self.stamp.half_span;
        let near: f64 = self
            .pressure_points()
            .iter()
            .filter(|p| p.0.abs() > cut)
            .map(|p| p.1 * p.2)
            .sum();
        0.5 * near - self.stamp.axial_force / self.stamp.stamp_radius * (a - cut)
    }
}

fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solve the FE model (T8) by the semismooth Newton iteration.
///
/// Unknowns: (w_i, w′_i) for every node, w₀ = w_n = 0 removed. The energy is
/// piecewise quadratic and C¹, so Newton converges once the active set of the penalty
/// integration points stops changing; it stops when the gradient is at round-off (see
/// the code for the exact norm), at each stage of a continuation in P_γ
/// (from (4EI/P_γ)^¼ = ℓ/10 up by factors of 10). Steps are
/// chosen by an exact line search on Π (a root of the monotone directional derivative),
/// which prevents the active-set cycling of the plain
/// semismooth iteration on fine meshes.
///
/// # Errors
/// [`StampError::InvalidInput`] for bad data or options; [`StampError::Solver`] if the
/// LU fails or the active set keeps changing for `max_iterations`.
pub fn solve_fe(stamp: &Stamp, opts: &StampFeOptions) -> Result<StampFe, StampError> {
    stamp.validate()?;
    let n = opts.elements;
    if n < 2 || !n.is_multiple_of(2) {
        return Err(StampError::InvalidInput {
            name: "elements",
            value: n as f64,
            reason: "must be even and ≥ 2",
        });
    }
    if !(opts.penalty.is_finite() && opts.penalty > 0.0) {
        return Err(StampError::InvalidInput {
            name: "penalty",
            value: opts.penalty,
            reason: "must be finite and > 0",
        });
    }
    let rule = Rule::Gauss(opts.quadrature_points);
    if rule.validate().is_err() {
        return Err(StampError::InvalidInput {
            name: "quadrature_points",
            value: f64::from(opts.quadrature_points),
            reason: "must be 1…5",
        });
    }
    let h = 2.0 * stamp.half_span / n as f64;
    // Element stiffness of EI/2 w″² + F/2 w′² (exact by Gauss 3: degree ≤ 4).
    let mut ke = [[0.0; 4]; 4];
    for &(xi, wq) in Rule::Gauss(3).points() {
        let d2 = hermite::second_weights(xi, h);
        let d1 = hermite::weights(xi, h).1;
        for a in 0..4 {
            for b in 0..4 {
                ke[a][b] += 0.5
                    * h
                    * wq
                    * (stamp.bending_stiffness * d2[a] * d2[b] + stamp.axial_force * d1[a] * d1[b]);
            }
        }
    }
    let contact_points: Vec<ContactPoint> = rule
        .points()
        .iter()
        .map(|&(xi, wq)| ContactPoint {
            xi,
            weight: wq,
            shape: hermite::weights(xi, h).0,
        })
        .collect();
    let beam = PenaltyBeam {
        stamp,
        elements: n,
        stiffness: ke,
        contact_points,
        penalty: opts.penalty,
        max_iterations: opts.max_iterations,
    };
    let m = beam.minimise()?;
    let mut fe = StampFe {
        stamp: *stamp,
        options: *opts,
        deflection: (0..=n).map(|i| m.z[2 * i]).collect(),
        slope: (0..=n).map(|i| m.z[2 * i + 1]).collect(),
        nodes: m.nodes,
        support_reactions: m.support_reactions,
        stamp_force: 0.0,
        iterations: m.iterations,
    };
    fe.stamp_force = fe.pressure_points().iter().map(|p| p.1 * p.2).sum();
    Ok(fe)
}

/// One contact integration point of an element: ξ ∈ [−1, 1], its weight on [−1, 1] and
/// the weights of the four element unknowns in the deflection w(ξ).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactPoint {
    pub xi: f64,
    pub weight: f64,
    pub shape: [f64; 4],
}

/// A linear beam of `elements` equal elements on [−ℓ, ℓ] with two unknowns per node
/// (global dof 2i = w_i, 2i + 1 = a second nodal field: w′_i for the Hermite element,
/// ψ_i for the Timoshenko one), the deflection at both ends held at 0, a constant element
/// stiffness and the penalty contact term ∫ (P_γ/2) ⟨−g⟩₊² dx at the contact points:
/// the discrete energy (T8) / (C12) minimised by [`PenaltyBeam::minimise`].
pub(crate) struct PenaltyBeam<'a> {
    pub stamp: &'a Stamp,
    pub elements: usize,
    pub stiffness: [[f64; 4]; 4],
    pub contact_points: Vec<ContactPoint>,
    pub penalty: f64,
    pub max_iterations: usize,
}

/// The minimiser of a [`PenaltyBeam`].
pub(crate) struct Minimum {
    /// Node coordinates, m.
    pub nodes: Vec<f64>,
    /// All unknowns (dof 2i, 2i + 1 of node i), the constrained ones 0.
    pub z: Vec<f64>,
    /// Downward reactions at the left and right support, N.
    pub support_reactions: [f64; 2],
    /// Semismooth Newton iterations, all penalty stages.
    pub iterations: usize,
}

impl PenaltyBeam<'_> {
    /// Minimise the energy by the semismooth Newton iteration.
    ///
    /// Unknowns: the two nodal fields of every node, w₀ = w_n = 0 removed. The energy is
    /// piecewise quadratic and C¹, so Newton converges once the active set of the penalty
    /// integration points stops changing; it stops when the gradient is at round-off (see
    /// the code for the exact norm), at each stage of a continuation in P_γ
    /// (from (4EI/P_γ)^¼ = ℓ/10 up by factors of 10). Steps are
    /// chosen by an exact line search on Π (a root of the monotone directional derivative),
    /// which prevents the active-set cycling of the plain
    /// semismooth iteration on fine meshes.
    pub fn minimise(&self) -> Result<Minimum, StampError> {
        let stamp = self.stamp;
        let n = self.elements;
        let ke = self.stiffness;
        let contact_points = &self.contact_points;
        let h = 2.0 * stamp.half_span / n as f64;
        let nodes: Vec<f64> = (0..=n).map(|i| -stamp.half_span + i as f64 * h).collect();
        // Global dof 2i = w_i, 2i+1 = w′_i; free dofs exclude 0 (w₀) and 2n (w_n).
        let ndof = 2 * (n + 1);
        let map: Vec<Option<usize>> = {
            let mut next = 0;
            (0..ndof)
                .map(|g| {
                    if g == 0 || g == 2 * n {
                        None
                    } else {
                        next += 1;
                        Some(next - 1)
                    }
                })
                .collect()
        };
        let nfree = ndof - 2;
        let (mut rows, mut cols) = (Vec::new(), Vec::new());
        for e in 0..n {
            for a in 0..4 {
                for b in 0..4 {
                    if let (Some(i), Some(j)) = (map[2 * e + a], map[2 * e + b]) {
                        rows.push(i);
                        cols.push(j);
                    }
                }
            }
        }
        let mut lu = SparseLu::new();
        lu.set_pattern(nfree, &rows, &cols)
            .map_err(StampError::Solver)?;

        // φ′(t) of φ(t) = Π(z − t d): the directional derivative −∇Π(z − t d)·d (the
        // gradient is accurate where Π itself, a sum of cancelling O(EI/h³ |z|²) terms, is not).
        #[allow(clippy::needless_range_loop)]
        // e indexes the unknowns (2e + a) and the nodes together
        let slope_at = |z: &[f64], d: &[f64], t: f64, penalty: f64| -> f64 {
            let mut out = 0.0;
            for e in 0..n {
                let mut q = [0.0; 4];
                let mut de = [0.0; 4];
                for a in 0..4 {
                    let g = 2 * e + a;
                    de[a] = map[g].map_or(0.0, |i| d[i]);
                    q[a] = z[g] - t * de[a];
                }
                for a in 0..4 {
                    let mut ga: f64 = (0..4).map(|b| ke[a][b] * q[b]).sum();
                    for &ContactPoint {
                        xi,
                        weight: wq,
                        shape: v,
                    } in contact_points
                    {
                        let g = dot(&v, &q) - stamp.face(nodes[e] + 0.5 * (1.0 + xi) * h);
                        if g < 0.0 {
                            ga += 0.5 * h * wq * penalty * g * v[a];
                        }
                    }
                    out -= ga * de[a];
                }
            }
            out
        };
        // Penalty continuation: from the foundation modulus whose smearing length
        // (4 EI/P_γ)^¼ is ℓ/10 up to P_γ by factors of 10, each stage warm-started — from the
        // straight rod the stiff penalty problem needs many line-searched steps.
        let mut stages = vec![self.penalty];
        let p0 = 4.0 * stamp.bending_stiffness / (0.1 * stamp.half_span).powi(4);
        while stages[stages.len() - 1] / 10.0 > p0 {
            let next = stages[stages.len() - 1] / 10.0;
            stages.push(next);
        }
        stages.reverse();
        let mut z = vec![0.0; ndof];
        let force_scale = stamp.axial_force * stamp.half_span / stamp.stamp_radius;
        let mut iterations = 0;
        for (stage, &penalty) in stages.iter().enumerate() {
            let last_stage = stage + 1 == stages.len();
            let mut converged = false;
            for _ in 1..=self.max_iterations {
                // Residual (energy gradient) and tangent at z over all dofs.
                let mut grad = vec![0.0; ndof];
                let mut vals = Vec::with_capacity(rows.len());
                for e in 0..n {
                    let q = [z[2 * e], z[2 * e + 1], z[2 * e + 2], z[2 * e + 3]];
                    let mut k = ke;
                    let mut ge = [0.0; 4];
                    for a in 0..4 {
                        ge[a] = (0..4).map(|b| ke[a][b] * q[b]).sum();
                    }
                    for &ContactPoint {
                        xi,
                        weight: wq,
                        shape: v,
                    } in contact_points
                    {
                        let x = nodes[e] + 0.5 * (1.0 + xi) * h;
                        let g = dot(&v, &q) - stamp.face(x);
                        if g < 0.0 {
                            let c = 0.5 * h * wq * penalty;
                            for a in 0..4 {
                                ge[a] += c * g * v[a];
                                for b in 0..4 {
                                    k[a][b] += c * v[a] * v[b];
                                }
                            }
                        }
                    }
                    for a in 0..4 {
                        grad[2 * e + a] += ge[a];
                        for b in 0..4 {
                            if map[2 * e + a].is_some() && map[2 * e + b].is_some() {
                                vals.push(k[a][b]);
                            }
                        }
                    }
                }
                let mut r: Vec<f64> = (0..ndof)
                    .filter(|&g| map[g].is_some())
                    .map(|g| grad[g])
                    .collect();
                let res_norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                // Converged when the gradient of the C¹ energy is at round-off: below 1e-10 F ℓ/ρ,
                // or below 1e-14 of the largest tangent entry times the largest unknown (the
                // round-off floor of the residual, ~1e-16 EI/h³·|z| summed over a few terms).
                let kmax = vals.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let zmax = z.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                if res_norm <= (1e-10 * force_scale).max(1e-14 * kmax * zmax) {
                    converged = true;
                    if !last_stage {
                        break;
                    }
                    return Ok(Minimum {
                        nodes,
                        z,
                        // The support pushes up with ∂Π/∂w at the constrained dof; downward = −that.
                        support_reactions: [-grad[0], -grad[2 * n]],
                        iterations,
                    });
                }
                iterations += 1;
                lu.factorize(&vals).map_err(StampError::Solver)?;
                lu.solve_in_place(&mut r).map_err(StampError::Solver)?;
                // Exact line search on the convex φ(t) = Π(z − t r): the full Newton step if φ is
                // still descending at t = 1, else the root of the monotone φ′ on (0, 1) by the
                // Illinois method. Without it the plain semismooth iteration cycles between active
                // sets on fine meshes.
                let (mut t0, mut f0) = (0.0, slope_at(&z, &r, 0.0, penalty));
                let (mut t1, mut f1) = (1.0, slope_at(&z, &r, 1.0, penalty));
                let mut t = 1.0;
                if f1 > 0.0 && f0 < 0.0 {
                    let mut side = 0;
                    for _ in 0..60 {
                        t = (t0 * f1 - t1 * f0) / (f1 - f0);
                        let ft = slope_at(&z, &r, t, penalty);
                        if ft.abs() <= 1e-3 * f0.abs().max(f1.abs()) || (t1 - t0) < 1e-12 {
                            break;
                        }
                        if ft > 0.0 {
                            (t1, f1) = (t, ft);
                            if side == 1 {
                                f0 *= 0.5;
                            }
                            side = 1;
                        } else {
                            (t0, f0) = (t, ft);
                            if side == -1 {
                                f1 *= 0.5;
                            }
                            side = -1;
                        }
                    }
                }
                let mut trial = z.clone();
                for g in 0..ndof {
                    if let Some(i) = map[g] {
                        trial[g] = z[g] - t * r[i];
                    }
                }
                z.copy_from_slice(&trial);
            }
            if !converged {
                return Err(StampError::Solver(format!(
                "the active set of the penalty contact still changed after {} semismooth Newton iterations at P_γ = {penalty:e}",
                self.max_iterations
            )));
            }
        }
        unreachable!("the last penalty stage returns or errs")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data() -> Stamp {
        Stamp::FIG_5A
    }

    /// The closed form satisfies its own edge conditions and end conditions, and is C²
    /// at the edge (position, slope, moment continuous: §6.3).
    #[test]
    fn closed_form_conditions() {
        let s = data();
        let cf = closed_form(&s).unwrap();
        let a = cf.half_width;
        assert!(a > 0.0 && a < s.half_span);
        let w = |x: f64| cf.deflection(x);
        let eps = 1e-5;
        // continuity of w, w′, w″ across x = a by one-sided differences of each piece.
        let free = |x: f64| {
            let xi = x - s.half_span;
            cf.b * xi + cf.c * (s.k() * xi).sinh()
        };
        assert!((free(a) - s.face(a)).abs() < 1e-13);
        let d1 = |f: &dyn Fn(f64) -> f64, x: f64| (f(x + eps) - f(x - eps)) / (2.0 * eps);
        let d2 =
            |f: &dyn Fn(f64) -> f64, x: f64| (f(x + eps) - 2.0 * f(x) + f(x - eps)) / (eps * eps);
        assert!((d1(&free, a) - d1(&|x| s.face(x), a)).abs() < 1e-9);
        assert!((d2(&free, a) + 1.0 / s.stamp_radius).abs() < 1e-4);
        assert!(w(s.half_span).abs() < 1e-13 && d2(&free, s.half_span - 2.0 * eps).abs() < 1e-2);
        // gap ≥ 0 in the free zone
        for i in 0..=100 {
            let x = a + (s.half_span - a) * f64::from(i) / 100.0;
            assert!(w(x) - s.face(x) >= -1e-14, "penetration at x = {x}");
        }
        // (T7) from the jump of EI w‴: EI C k³ cosh k(a − ℓ).
        let k = s.k();
        let jump = s.bending_stiffness * cf.c * k.powi(3) * (k * (a - s.half_span)).cosh();
        assert!((jump - cf.edge_force).abs() < 1e-12 * cf.edge_force);
        // balance: support = half the stamp force
        assert!((2.0 * cf.support_reaction - cf.stamp_force()).abs() < 1e-12 * cf.stamp_force());
    }

    /// δ outside (δ₀, ℓ²/2ρ) is an error naming the bounds; bad data is an input error.
    #[test]
    fn errors() {
        let mut s = data();
        let (onset, full) = s.indentation_range();
        assert!((onset - 0.09).abs() < 1e-8 && (full - 0.5).abs() < 1e-15);
        s.indentation = 0.05;
        assert!(matches!(
            closed_form(&s),
            Err(StampError::NoContactZone { .. })
        ));
        s.indentation = 0.6;
        let e = closed_form(&s).unwrap_err().to_string();
        assert!(e.contains("0.6") && e.contains("0.5"), "{e}");
        s = data();
        s.axial_force = -1.0;
        assert!(matches!(
            closed_form(&s),
            Err(StampError::InvalidInput {
                name: "axial_force",
                ..
            })
        ));
        let opts = StampFeOptions {
            elements: 7,
            ..Default::default()
        };
        assert!(matches!(
            solve_fe(&data(), &opts),
            Err(StampError::InvalidInput {
                name: "elements",
                ..
            })
        ));
    }
}
