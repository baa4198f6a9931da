//! The geometrically linearised, pre-tensioned **Cosserat** (shear-deformable) rod
//! pressed by a rigid stamp (§6.3, Fig. 5b of the reference; check C-10 of
//! `shared/spec/cosserat-and-shell.md`): its closed form and a Timoshenko beam FE with
//! penalty contact. The Kirchhoff version is [`crate::stamp`]; this one shares its data
//! ([`Stamp`]), its errors ([`StampError`]) and its penalty Newton solver. Derivation,
//! conventions and measured numbers: `docs/rod-stamp.md`, section "The Cosserat rod"
//! (equations (C1)–(C13) cited below).
//!
//! Unlike the Kirchhoff rod, the contact pressure is finite: F/ρ plus an exponential edge
//! layer of length ℓ_s = 1/β = √(EI/(b₂ − F)) with the peak p(a) ≈ √(F b₂)/ρ at the zone
//! edges; there are no concentrated edge forces.

use crate::quadrature::Rule;
use crate::stamp::{ContactPoint, PenaltyBeam, Stamp, StampError};

/// The data of the Cosserat stamp problem: the Kirchhoff data and the shear stiffness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosseratStamp {
    /// ℓ, EI, F, ρ, δ as for the Kirchhoff rod.
    pub stamp: Stamp,
    /// Shear stiffness b₂, N (> F: (C2)).
    pub shear_stiffness: f64,
}

impl CosseratStamp {
    /// The data of check C-10: Fig. 5a's (ℓ = 1 m, EI = 1 N·m², F = 100 N, ρ = 1 m,
    /// δ = 0.2 m) with the shear stiffness `b2`.
    pub fn fig_5b(b2: f64) -> Self {
        Self {
            stamp: Stamp::FIG_5A,
            shear_stiffness: b2,
        }
    }

    fn validate(&self) -> Result<(), StampError> {
        self.stamp.validate()?;
        let b2 = self.shear_stiffness;
        if !(b2.is_finite() && b2 > 0.0) {
            return Err(StampError::InvalidInput {
                name: "shear_stiffness",
                value: b2,
                reason: "must be finite and > 0",
            });
        }
        if b2 <= self.stamp.axial_force {
            return Err(StampError::ShearCritical {
                shear_stiffness: b2,
                axial_force: self.stamp.axial_force,
            });
        }
        Ok(())
    }

    /// β = √((b₂ − F)/EI), 1/m: the edge-layer decay rate inside the zone (C2).
    pub fn beta(&self) -> f64 {
        ((self.shear_stiffness - self.stamp.axial_force) / self.stamp.bending_stiffness).sqrt()
    }

    /// k_f = √(F(b₂ − F)/(EI b₂)), 1/m: the free-zone decay rate (C2).
    pub fn k_free(&self) -> f64 {
        let (f, b2) = (self.stamp.axial_force, self.shear_stiffness);
        (f * (b2 - f) / (self.stamp.bending_stiffness * b2)).sqrt()
    }
}

/// cosh(u)/cosh(v) for |u| ≤ |v| without overflow (exponentially scaled).
fn cosh_ratio(u: f64, v: f64) -> f64 {
    let (u, v) = (u.abs(), v.abs());
    (u - v).exp() * (1.0 + (-2.0 * u).exp()) / (1.0 + (-2.0 * v).exp())
}

/// sinh(u)/cosh(v) for |u| ≤ |v| without overflow (exponentially scaled).
fn sinh_cosh_ratio(u: f64, v: f64) -> f64 {
    let (au, av) = (u.abs(), v.abs());
    u.signum() * (au - av).exp() * (1.0 - (-2.0 * au).exp()) / (1.0 + (-2.0 * av).exp())
}

/// The quantities of (C6)–(C8) at a trial half width a.
#[derive(Debug, Clone, Copy)]
struct Edge {
    /// G = A cosh βa (C6), rad/m.
    g: f64,
    /// tanh βa.
    t: f64,
    /// Excess E = (b₂ − F) G tanh βa (C8), N.
    excess: f64,
    /// Support reaction R = F a/ρ + E (C8), N.
    reaction: f64,
    /// Residual f(a) of (C7), m.
    residual: f64,
}

fn edge(c: &CosseratStamp, a: f64) -> Edge {
    let s = &c.stamp;
    let (f, b2, r) = (s.axial_force, c.shear_stiffness, s.stamp_radius);
    let (beta, k) = (c.beta(), c.k_free());
    let len = s.half_span - a;
    let t = (beta * a).tanh();
    let tt = (k * len).tanh();
    let g = 1.0 / (r * (beta + t * (b2 * k / f) * tt));
    let excess = (b2 - f) * g * t;
    let reaction = f * a / r + excess;
    let residual = reaction * len / f - excess * tt / (f * k) - s.indentation + a * a / (2.0 * r);
    Edge {
        g,
        t,
        excess,
        reaction,
        residual,
    }
}

/// The closed-form solution (C3)–(C8) of the Cosserat rod on the stamp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosseratClosedForm {
    /// The data.
    pub data: CosseratStamp,
    /// Contact half width a_c, m.
    pub half_width: f64,
    /// Pressure at the centre p(0), N/m.
    pub pressure_centre: f64,
    /// Pressure at the zone edges p(a_c), N/m (its maximum).
    pub pressure_edge: f64,
    /// Excess ∫₀^{a_c} (p − F/ρ) dx, N: what the edge layer adds to the constant part.
    pub excess: f64,
    /// Downward force of each support, = ∫₀^{a_c} p dx = −V (C8), N.
    pub support_reaction: f64,
    /// G = A cosh βa_c (C6).
    g: f64,
    /// tanh βa_c.
    t: f64,
}

impl CosseratClosedForm {
    /// The five numbers of a row of spec C-10's table, in its column order: a_c, p(0),
    /// p(a_c), the excess, the support reaction.
    pub fn table_row(&self) -> [f64; 5] {
        [self.half_width, self.pressure_centre, self.pressure_edge, self.excess, self.support_reaction]
    }

    fn beta(&self) -> f64 {
        self.data.beta()
    }

    /// Transverse force in the free zone, V = −R (C4), N.
    fn v(&self) -> f64 {
        -self.support_reaction
    }

    /// C cosh k(x − ℓ) of (C4) for x in the free zone (x ≥ a_c), scaled.
    fn c_cosh(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let k = self.data.k_free();
        self.g * self.t * self.data.shear_stiffness / s.axial_force
            * cosh_ratio(k * (x - s.half_span), k * (self.half_width - s.half_span))
    }

    /// C sinh k(x − ℓ) of (C4) for x in the free zone, scaled.
    fn c_sinh(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let k = self.data.k_free();
        self.g * self.t * self.data.shear_stiffness / s.axial_force
            * sinh_cosh_ratio(k * (x - s.half_span), k * (self.half_width - s.half_span))
    }

    /// A sinh βx = G sinh βx / cosh βa_c for |x| ≤ a_c (scaled).
    fn a_sinh(&self, x: f64) -> f64 {
        self.g * sinh_cosh_ratio(self.beta() * x, self.beta() * self.half_width)
    }

    /// A cosh βx = G cosh βx / cosh βa_c for |x| ≤ a_c (scaled).
    fn a_cosh(&self, x: f64) -> f64 {
        self.g * cosh_ratio(self.beta() * x, self.beta() * self.half_width)
    }

    /// The deflection w(x), m, |x| ≤ ℓ: the stamp face in the zone, (C4) outside.
    pub fn deflection(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let x = x.abs();
        if x <= self.half_width {
            s.face(x)
        } else {
            let (f, b2) = (s.axial_force, self.data.shear_stiffness);
            self.v() * (x - s.half_span) / f + (1.0 - f / b2) * self.c_sinh(x) / self.data.k_free()
        }
    }

    /// The slope w′(x) (C3), (C4).
    pub fn slope(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let (sign, x) = (x.signum(), x.abs());
        sign * if x <= self.half_width {
            -x / s.stamp_radius
        } else {
            let (f, b2) = (s.axial_force, self.data.shear_stiffness);
            self.rotation(x) * (1.0 - f / b2) + self.v() / b2
        }
    }

    /// The section rotation ψ(x), rad (C3), (C4); odd in x.
    pub fn rotation(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let (sign, x) = (x.signum(), x.abs());
        sign * if x <= self.half_width {
            -x / s.stamp_radius + self.a_sinh(x)
        } else {
            self.v() / s.axial_force + self.c_cosh(x)
        }
    }

    /// The bending moment M = EI ψ′(x), N·m; even in x.
    pub fn moment(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let x = x.abs();
        s.bending_stiffness
            * if x <= self.half_width {
                -1.0 / s.stamp_radius + self.beta() * self.a_cosh(x)
            } else {
                self.data.k_free() * self.c_sinh(x)
            }
    }

    /// The vertical (transverse) force F_y = Fψ + b₂γ_s, γ_s = w′ − ψ (C1), N; odd in x.
    pub fn shear_force(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let (sign, x) = (x.signum(), x.abs());
        sign * if x <= self.half_width {
            -s.axial_force * x / s.stamp_radius
                - (self.data.shear_stiffness - s.axial_force) * self.a_sinh(x)
        } else {
            self.v()
        }
    }

    /// The contact pressure p(x) = F/ρ + (b₂ − F) A β cosh βx in the zone (C3), 0
    /// outside, N/m.
    pub fn pressure(&self, x: f64) -> f64 {
        let s = &self.data.stamp;
        let x = x.abs();
        if x <= self.half_width {
            s.axial_force / s.stamp_radius
                + (self.data.shear_stiffness - s.axial_force) * self.beta() * self.a_cosh(x)
        } else {
            0.0
        }
    }

    /// Total upward force of the stamp ∫p dx = 2(F a_c/ρ + E), N.
    pub fn stamp_force(&self) -> f64 {
        2.0 * self.support_reaction
    }
}

/// The closed form of docs/rod-stamp.md (C-10): the half width a_c from the scalar
/// equation (C7) by Brent's method on the bracket (0, ℓ) of (C9), then (C8); the gap in
/// the free zone is checked on 400 points (C10).
///
/// # Errors
/// [`StampError::InvalidInput`] (non-positive data), [`StampError::ShearCritical`]
/// (b₂ ≤ F), [`StampError::NoContact`] (δ ≤ 0), [`StampError::StampWiderThanSpan`]
/// (δ ≥ ℓ²/2ρ), [`StampError::Penetration`] (gap < 0 in the free zone),
/// [`StampError::Solver`] if the root is not found.
pub fn closed_form(data: &CosseratStamp) -> Result<CosseratClosedForm, StampError> {
    data.validate()?;
    let s = &data.stamp;
    if s.indentation <= 0.0 {
        return Err(StampError::NoContact {
            indentation: s.indentation,
        });
    }
    let full = s.half_span * s.half_span / (2.0 * s.stamp_radius);
    if s.indentation >= full {
        return Err(StampError::StampWiderThanSpan {
            indentation: s.indentation,
            full,
        });
    }
    // f(0) = −δ < 0, f(ℓ) = ℓ²/2ρ − δ > 0 (C9)
    let residual = |a: f64| Ok::<f64, std::convert::Infallible>(edge(data, a).residual);
    let a = numerics::roots::brent(residual, 0.0, s.half_span, 1e-15 * s.half_span)
        .map_err(|e| StampError::Solver(format!("Brent on (C7): {e}")))?;
    let e = edge(data, a);
    let (f, b2, r) = (s.axial_force, data.shear_stiffness, s.stamp_radius);
    let beta = data.beta();
    let cf = CosseratClosedForm {
        data: *data,
        half_width: a,
        pressure_centre: f / r + (b2 - f) * beta * e.g * cosh_ratio(0.0, beta * a),
        pressure_edge: f / r + (b2 - f) * beta * e.g,
        excess: e.excess,
        support_reaction: e.reaction,
        g: e.g,
        t: e.t,
    };
    // (C10): gap ≥ 0 in the free zone (guaranteed by A > 0, checked)
    let scale = s.indentation.abs().max(full);
    for i in 1..=400 {
        let x = a + (s.half_span - a) * f64::from(i) / 400.0;
        let gap = cf.deflection(x) - s.face(x);
        // NaN counts as a failure
        if gap.is_nan() || gap < -1e-13 * scale {
            return Err(StampError::Penetration { x, gap });
        }
    }
    Ok(cf)
}

/// Options of the Timoshenko FE (docs/rod-stamp.md "The Cosserat FE").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosseratFeOptions {
    /// Number of elements on [−ℓ, ℓ], even and ≥ 4.
    pub elements: usize,
    /// Penalty factor P_γ, N/m²; `None`: the default of [`default_penalty`].
    pub penalty: Option<f64>,
    /// Integration rule of the shear energy: `Gauss(1)` (reduced, locking-free, the
    /// default) or `Gauss(2)` (exact for the linear element, which locks: kept to show it).
    pub shear_rule: Rule,
    /// Iteration cap of the semismooth Newton iteration (per penalty stage).
    pub max_iterations: usize,
}

impl Default for CosseratFeOptions {
    fn default() -> Self {
        Self {
            elements: 256,
            penalty: None,
            shear_rule: Rule::Gauss(1),
            max_iterations: 200,
        }
    }
}

/// The default penalty (C13): P_γ = 10⁶ (b₂ − F)²/EI, so that the penalty layer
/// √((b₂ − F)/P_γ) is 10⁻³ of the shear layer ℓ_s, but at most 10⁻⁴ (F/ρ)/(ε_mach δ),
/// where the round-off of the penalty pressure P_γ ε_mach δ reaches 10⁻⁴ F/ρ.
pub fn default_penalty(data: &CosseratStamp) -> f64 {
    let s = &data.stamp;
    let eb = data.shear_stiffness - s.axial_force;
    let resolved = 1e6 * eb * eb / s.bending_stiffness;
    let roundoff = 1e-4 * (s.axial_force / s.stamp_radius)
        / (f64::EPSILON * s.indentation.abs().max(1e-3 * s.half_span));
    resolved.min(roundoff)
}

/// The Timoshenko FE solution.
#[derive(Debug, Clone, PartialEq)]
pub struct CosseratStampFe {
    /// The data.
    pub data: CosseratStamp,
    /// The options used.
    pub options: CosseratFeOptions,
    /// The penalty factor used, N/m².
    pub penalty: f64,
    /// Node coordinates x_i, m.
    pub nodes: Vec<f64>,
    /// Nodal deflections w_i, m.
    pub deflection: Vec<f64>,
    /// Nodal section rotations ψ_i.
    pub rotation: Vec<f64>,
    /// Downward reactions at the left and right support, N.
    pub support_reactions: [f64; 2],
    /// ∫ p_h dx (trapezoidal), N.
    pub stamp_force: f64,
    /// Semismooth Newton iterations, all penalty stages.
    pub iterations: usize,
}

/// The edge estimate (C13) at one zone edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeEdge {
    /// |x| of the edge, m.
    pub position: f64,
    /// The pressure extrapolated to it, N/m.
    pub pressure: f64,
}

impl CosseratStampFe {
    fn element_length(&self) -> f64 {
        2.0 * self.data.stamp.half_span / self.options.elements as f64
    }

    /// The nodal penalty pressures p_i = P_γ ⟨−g_i⟩₊, N/m (the trapezoidal contact rule:
    /// node i carries the force h p_i, h/2 p_i at the supports).
    pub fn nodal_pressure(&self) -> Vec<f64> {
        self.nodes
            .iter()
            .zip(&self.deflection)
            .map(|(&x, &w)| self.penalty * (self.data.stamp.face(x) - w).max(0.0))
            .collect()
    }

    /// The pressure at the centre node x = 0, N/m.
    pub fn pressure_centre(&self) -> f64 {
        self.nodal_pressure()[self.options.elements / 2]
    }

    /// Largest |x| of a node in contact, m: the crude edge, good to one element (the only
    /// one available when h > ℓ_s).
    pub fn contact_half_width(&self) -> f64 {
        self.nodal_pressure()
            .iter()
            .zip(&self.nodes)
            .filter(|(p, _)| **p > 0.0)
            .map(|(_, x)| x.abs())
            .fold(0.0, f64::max)
    }

    /// The edge of (C13) on one side (`right` = true: x > 0): the last node L in contact
    /// carries h p_L; with the pressure extrapolated to x_L from the two nodes inside it
    /// (the exponential edge layer of (C3) over the constant F/ρ: q_i = p_i − F/ρ,
    /// q̂_L = q_{L−1}²/q_{L−2}), its contact covers h p_L / p̂_L of its tributary length,
    /// so the edge is x_L − h/2 + h p_L/p̂_L; the edge pressure is the same extrapolation
    /// to that point. `None` if fewer than three nodes are in contact on that side.
    pub fn edge(&self, right: bool) -> Option<FeEdge> {
        let p = self.nodal_pressure();
        let n = self.options.elements;
        let h = self.element_length();
        let base = self.data.stamp.axial_force / self.data.stamp.stamp_radius;
        // node indices walking from the centre outwards on the chosen side
        let idx = |j: usize| if right { n / 2 + j } else { n / 2 - j };
        let last = (0..=n / 2).take_while(|&j| p[idx(j)] > 0.0).last()?;
        if last < 2 {
            return None;
        }
        let (pl, q1, q2) = (
            p[idx(last)],
            p[idx(last - 1)] - base,
            p[idx(last - 2)] - base,
        );
        // growth factor per element towards the edge; a flat or noisy profile: constant
        let ratio = if q1 > 0.0 && q2 > 0.0 && q1 > q2 {
            q1 / q2
        } else {
            1.0
        };
        let p_hat = base + q1 * ratio;
        let x_last = self.nodes[idx(last)].abs();
        let position = x_last - 0.5 * h + h * pl / p_hat;
        let pressure = base + q1 * ratio.powf((position - self.nodes[idx(last - 1)].abs()) / h);
        Some(FeEdge { position, pressure })
    }

    /// The mean of both edges' estimates (C13).
    pub fn edges(&self) -> Option<FeEdge> {
        let (l, r) = (self.edge(false)?, self.edge(true)?);
        Some(FeEdge {
            position: 0.5 * (l.position + r.position),
            pressure: 0.5 * (l.pressure + r.pressure),
        })
    }
}

/// Solve the Timoshenko FE model (C12): linear w and ψ per element, the shear energy by
/// `shear_rule` (1-point reduced by default), bending and axial terms exactly, the
/// penalty contact at the nodes (trapezoidal rule), minimised by the semismooth Newton
/// iteration of the Kirchhoff FE ([`crate::stamp::solve_fe`]).
///
/// # Errors
/// [`StampError::InvalidInput`] for bad data or options, [`StampError::ShearCritical`],
/// [`StampError::Solver`] if the LU fails or the active set keeps changing.
pub fn solve_fe(
    data: &CosseratStamp,
    opts: &CosseratFeOptions,
) -> Result<CosseratStampFe, StampError> {
    data.validate()?;
    let n = opts.elements;
    if n < 4 || !n.is_multiple_of(2) {
        return Err(StampError::InvalidInput {
            name: "elements",
            value: n as f64,
            reason: "must be even and ≥ 4",
        });
    }
    let penalty = opts.penalty.unwrap_or_else(|| default_penalty(data));
    if !(penalty.is_finite() && penalty > 0.0) {
        return Err(StampError::InvalidInput {
            name: "penalty",
            value: penalty,
            reason: "must be finite and > 0",
        });
    }
    if opts.shear_rule.validate().is_err() {
        return Err(StampError::InvalidInput {
            name: "shear_rule",
            value: f64::NAN,
            reason: "not a valid rule",
        });
    }
    let s = &data.stamp;
    let h = 2.0 * s.half_span / n as f64;
    // q = (w₁, ψ₁, w₂, ψ₂): ψ′ = (ψ₂ − ψ₁)/h, w′ = (w₂ − w₁)/h, γ_s(ξ) = w′ − ψ(ξ)
    let bend = [0.0, -1.0 / h, 0.0, 1.0 / h];
    let axial = [-1.0 / h, 0.0, 1.0 / h, 0.0];
    let mut ke = [[0.0; 4]; 4];
    for a in 0..4 {
        for b in 0..4 {
            ke[a][b] =
                h * (s.bending_stiffness * bend[a] * bend[b] + s.axial_force * axial[a] * axial[b]);
        }
    }
    let eb = data.shear_stiffness - s.axial_force;
    for &(xi, wq) in opts.shear_rule.points() {
        let shear = [-1.0 / h, -0.5 * (1.0 - xi), 1.0 / h, -0.5 * (1.0 + xi)];
        for a in 0..4 {
            for b in 0..4 {
                ke[a][b] += 0.5 * h * wq * eb * shear[a] * shear[b];
            }
        }
    }
    let contact_points = Rule::Trapezoidal
        .points()
        .iter()
        .map(|&(xi, wq)| ContactPoint {
            xi,
            weight: wq,
            shape: [0.5 * (1.0 - xi), 0.0, 0.5 * (1.0 + xi), 0.0],
        })
        .collect();
    let beam = PenaltyBeam {
        stamp: s,
        elements: n,
        stiffness: ke,
        contact_points,
        penalty,
        max_iterations: opts.max_iterations,
    };
    let m = beam.minimise()?;
    let mut fe = CosseratStampFe {
        data: *data,
        options: *opts,
        penalty,
        deflection: (0..=n).map(|i| m.z[2 * i]).collect(),
        rotation: (0..=n).map(|i| m.z[2 * i + 1]).collect(),
        nodes: m.nodes,
        support_reactions: m.support_reactions,
        stamp_force: 0.0,
        iterations: m.iterations,
    };
    let p = fe.nodal_pressure();
    fe.stamp_force = p
        .iter()
        .enumerate()
        .map(|(i, &pi)| {
            if i == 0 || i == n {
                0.5 * h * pi
            } else {
                h * pi
            }
        })
        .sum();
    Ok(fe)
}
