//! The Cosserat rod as a section law of the frictionless two-pulley loop
//! (docs/cosserat-hanging.md), in scaled variables: lengths by H, forces by F_ref (the
//! string's force scale), moments by F_ref·H, the bending stiffness a by F_ref·H².
//!
//! Spans run in the material coordinate s (the span parameter is the unstretched span
//! length), arcs in the polar angle φ. θ is unwrapped so that it is continuous round the
//! loop (upper spans θ ≈ 0, lower spans θ ≈ −π, the driver arc ending near −2π); the
//! loop closes with θ(start of segment 0) = θ(end of the driver arc) + 2π. Unlike the
//! Kirchhoff rod, θ is a state on the arcs (the section may shear against the pulley
//! tangent, γ = φ − π/2 − θ), and r, θ, M and the force F are continuous at every
//! contact boundary: there are no concentrated edge forces (CH4).

use std::f64::consts::{FRAC_PI_2, PI};

use crate::belt::balance;
use crate::belt::law::{BeltPoint, ContactEdges, Rows, Scales, SectionLaw};
use crate::belt::solution::BeltSolution;
use crate::belt::topology::{ArcKind, Pulley, SegmentKind, Topology};
use crate::belt::BeltError;
use crate::problem::Scalar;
use crate::rod_hanging::law::{section_energy, ScaledRodHanging, ROD_WINDOW};
use crate::string_hanging::law::on_pulley;
use crate::string_hanging::StringHangingSolution;

use super::CosseratHanging;

/// Arc state components.
const LAMBDA: usize = 0;
const THETA: usize = 1;
const MOMENT: usize = 2;
const MATERIAL: usize = 3;

/// The scaled Cosserat problem: the Kirchhoff rod's scaled data and homotopy in η (the
/// bending stiffness interpolated in log, a(η) = a₀^(1−η) a^η, from the string-like
/// start a₀) with the scene's shear stiffness.
#[derive(Debug, Clone)]
pub struct ScaledCosseratHanging {
    /// R/H, b₁ = EA, ρgH, L/H, a₀ and a, scaled as the Kirchhoff rod's.
    pub rod: ScaledRodHanging,
    /// b₂ / F_ref (shear stiffness).
    pub shear_stiffness: f64,
}

/// The force of a section on a pulley, F = T t + S n, and its partial derivatives in the
/// stretch λ and the shear angle γ ((CH2), spec (C2) with χ = 0).
#[derive(Debug, Clone, Copy)]
pub struct ArcForce<D> {
    /// Tangential component T = F·t.
    pub t: D,
    /// Normal component S = F·n.
    pub s: D,
    /// ∂T/∂λ.
    pub t_l: D,
    /// ∂T/∂γ.
    pub t_g: D,
    /// ∂S/∂λ.
    pub s_l: D,
    /// ∂S/∂γ.
    pub s_g: D,
}

impl<D: Scalar> ArcForce<D> {
    /// F̃ = T t + S n at stretch λ and shear angle γ for stiffnesses b₁, b₂ and the
    /// transport term χ = ρc² (spec (C2); χ = 0 at rest, (CH2)).
    pub fn new(b1: f64, b2: f64, chi: f64, lambda: D, gamma: D) -> Self {
        let (s, c) = (gamma.sin(), gamma.cos());
        let t_l = c * c * (b1 - chi) + s * s * (b2 - chi);
        let s_l = s * c * (b2 - b1);
        ArcForce {
            t: lambda * t_l - c * b1,
            s: lambda * s_l + s * b1,
            t_l,
            t_g: lambda * s * c * (2.0 * (b2 - b1)) + s * b1,
            s_l,
            s_g: lambda * (c * c - s * s) * (b2 - b1) + c * b1,
        }
    }
}

/// Where a Cosserat span meets an arc ([`contact_rows`]).
#[derive(Debug, Clone, Copy)]
pub enum Edge<D> {
    /// First contact; the closure jump (if any) is added to the tangential force.
    Start { jump: Option<D> },
    /// Last contact; `closes_loop` where θ gains 2π and s restarts.
    End { closes_loop: bool },
}

/// (CH4) / spec §1.6: the seven conditions at a contact boundary of a Cosserat span
/// `span` = (x, y, θ, M, F̃ₓ, F̃ᵧ, s) and an arc end with (θ, M, s) = `arc` and force
/// `f` (T, S of (C2)): on the circle of `pulley` at φ, θ, M, F̃ and s continuous — no
/// concentrated edge force.
#[allow(clippy::too_many_arguments)]
pub fn contact_rows<D: Scalar>(radius: f64, pulley: Pulley, phi: D, span: &[D], arc: [D; 3], f: &ArcForce<D>, edge: Edge<D>, rows: &mut Rows<D>) {
    let (px, py) = on_pulley(radius, pulley, phi);
    let (tx, ty, nx, ny) = (phi.sin(), -phi.cos(), phi.cos(), phi.sin());
    let [theta, moment, material] = arc;
    rows.push(span[0] - px);
    rows.push(span[1] - py);
    match edge {
        Edge::Start { jump } => {
            rows.push(theta - span[2]);
            rows.push(moment - span[3]);
            let carried = f.t - (span[4] * tx + span[5] * ty);
            rows.push(match jump {
                Some(j) => carried - j,
                None => carried,
            });
            rows.push(f.s - (span[4] * nx + span[5] * ny));
            rows.push(material - span[6]);
        }
        Edge::End { closes_loop } => {
            rows.push(if closes_loop { span[2] - (theta + 2.0 * PI) } else { span[2] - theta });
            rows.push(span[3] - moment);
            rows.push(span[4] * tx + span[5] * ty - f.t);
            rows.push(span[4] * nx + span[5] * ny - f.s);
            rows.push(if closes_loop { span[6] } else { span[6] - material });
        }
    }
}

/// (CH1) / spec (C1) in s, times the span length ℓ: state (x, y, θ, M, F̃ₓ, F̃ᵧ, s),
/// Γ₁ = (F̃·e₁ + χ)/(b₁ − χ), Γ₂ = F̃·e₂/(b₂ − χ) (χ = 0 at rest), weight ρg per length.
#[allow(clippy::too_many_arguments)]
pub fn span_rhs<D: Scalar>(b1: f64, b2: f64, chi: f64, weight: f64, a: D, l: D, y: &[D], f: &mut [D]) {
    moving_span_rhs(b1, b2, D::from(chi), D::from(weight), a, l, y, f);
}

/// [`span_rhs`] with χ and the weight as scalars of the solve: the drive's χ = ρc² reads
/// the unknown transport rate c (docs/cosserat-drive.md, (CD1)).
#[allow(clippy::too_many_arguments)]
pub fn moving_span_rhs<D: Scalar>(b1: f64, b2: f64, chi: D, weight: D, a: D, l: D, y: &[D], f: &mut [D]) {
    let (n, q) = ScaledCosseratHanging::span_nq(y);
    let (g1, g2) = ((n + chi) / (-chi + b1), q / (-chi + b2));
    let (c, s) = (y[2].cos(), y[2].sin());
    let dx = (g1 + 1.0) * c - g2 * s;
    let dy = (g1 + 1.0) * s + g2 * c;
    f[0] = l * dx;
    f[1] = l * dy;
    f[2] = l * y[3] / a;
    f[3] = -(l * (dx * y[5] - dy * y[4]));
    f[4] = D::from(0.0);
    f[5] = l * weight;
    f[6] = l;
}

impl ScaledCosseratHanging {
    /// (CH2) F = T t + S n on an arc at stretch λ and shear angle γ.
    pub fn arc_force<D: Scalar>(&self, lambda: D, gamma: D) -> ArcForce<D> {
        ArcForce::new(self.rod.axial_stiffness, self.shear_stiffness, 0.0, lambda, gamma)
    }

    /// The frictionless arc in d/ds ((CH3)): (λ′, θ′, M′, γ′) and the force at polar
    /// angle φ, bending stiffness `a`, state (λ, θ, M).
    fn arc_slopes<D: Scalar>(&self, a: D, phi: D, y: &[D]) -> ([D; 4], ArcForce<D>) {
        let lambda = y[LAMBDA];
        let gamma = phi - FRAC_PI_2 - y[THETA];
        let f = self.arc_force(lambda, gamma);
        let dphi = -(lambda / self.rod.radius);
        let dtheta = y[MOMENT] / a;
        let dgamma = dphi - dtheta;
        // f_t = −w cos φ − T′ + S φ′ = 0, T′ = T_λ λ′ + T_γ γ′.
        let dlambda = (f.s * dphi - phi.cos() * self.rod.weight - f.t_g * dgamma) / f.t_l;
        let dmoment = -(lambda * f.s);
        ([dlambda, dtheta, dmoment, dgamma], f)
    }

    /// (CH3) Contact pressure p = w sin φ − S′ − T φ′ on an arc (scaled), at bending
    /// stiffness `a`.
    pub fn arc_pressure(&self, a: f64, phi: f64, y: &[f64]) -> f64 {
        let ([dlambda, _, _, dgamma], f) = self.arc_slopes(a, phi, y);
        let ds = f.s_l * dlambda + f.s_g * dgamma;
        self.rod.weight * phi.sin() - ds + f.t * y[LAMBDA] / self.rod.radius
    }

    /// (CH1) Axial and shear force N = F·e₁, Q = F·e₂ of a span state (with transport,
    /// the effective force's components F̃·e₁, F̃·e₂).
    pub fn span_nq<D: Scalar>(y: &[D]) -> (D, D) {
        let (c, s) = (y[2].cos(), y[2].sin());
        (y[4] * c + y[5] * s, y[5] * c - y[4] * s)
    }
}

impl SectionLaw for ScaledCosseratHanging {
    type Data = CosseratHanging;
    type Start = StringHangingSolution;

    const SPAN_STATES: &'static [&'static str] = &["x", "y", "theta", "M", "F_x", "F_y", "s"];
    const ARC_STATES: &'static [&'static str] = &["lambda", "theta", "M", "s"];
    const CONTACT_EDGES: ContactEdges = ContactEdges::Pressures;

    /// No path in a when the scene's bending layer is at least the start layer.
    fn starts_at_scene(&self) -> bool {
        self.rod.bending_start == self.rod.bending
    }

    /// The static Cosserat rod reads no parameter besides its own span length or arc
    /// angles.
    fn rhs_reads(&self, _: &Topology) -> Vec<usize> {
        Vec::new()
    }

    fn span_rhs<D: Scalar>(&self, _: &Topology, l: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (CH1) times the span length ℓ.
        let r = &self.rod;
        span_rhs(r.axial_stiffness, self.shear_stiffness, 0.0, r.weight, r.bending_at(eta), l, y, f);
    }

    fn arc_rhs<D: Scalar>(&self, _: &Topology, _: ArcKind, _: Pulley, phi: D, dphi: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (CH3) with φ as variable, ds/dφ = −R/λ, times Δφ = φ_b − φ_a.
        let a = self.rod.bending_at(eta);
        let ([dlambda, dtheta, dmoment, _], _) = self.arc_slopes(a, phi, y);
        let ds = -(dphi * self.rod.radius / y[LAMBDA]);
        f[LAMBDA] = ds * dlambda;
        f[THETA] = ds * dtheta;
        f[MOMENT] = ds * dmoment;
        f[MATERIAL] = ds;
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], jump: Option<D>, _: &[D], _: D, rows: &mut Rows<D>) {
        // (CH4): on the circle; θ, M, F = T t + S n and s continuous (the closure jump
        // is added to the tangential force at the driver's first contact).
        let f = self.arc_force(arc[LAMBDA], phi - FRAC_PI_2 - arc[THETA]);
        contact_rows(self.rod.radius, pulley, phi, e, [arc[THETA], arc[MOMENT], arc[MATERIAL]], &f, Edge::Start { jump }, rows);
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], s: &[D], closes_loop: bool, _: &[D], _: D, rows: &mut Rows<D>) {
        // (CH4) where the belt leaves the pulley; θ gains 2π and s restarts where the
        // loop closes.
        let f = self.arc_force(arc_end[LAMBDA], phi - FRAC_PI_2 - arc_end[THETA]);
        let arc = [arc_end[THETA], arc_end[MOMENT], arc_end[MATERIAL]];
        contact_rows(self.rod.radius, pulley, phi, s, arc, &f, Edge::End { closes_loop }, rows);
    }

    fn loop_conditions<D: Scalar>(&self, topology: &Topology, _: &[&[D]], yb: &[&[D]], _: &[D], _: D, rows: &mut Rows<D>) {
        // Total unstretched length.
        rows.push(yb[topology.len() - 1][MATERIAL] - self.rod.length);
    }

    fn point(&self, _: &CosseratHanging, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], _: &[f64]) -> BeltPoint {
        let (lh, fr) = (sc.length, sc.force);
        let rod = |x: f64, yy: f64, theta: f64, moment: f64, n: f64, q: f64, material: f64| {
            let (g1, g2) = (n / self.rod.axial_stiffness, q / self.shear_stiffness);
            BeltPoint {
                shear: Some(q * fr),
                shear_strain: Some(g2),
                moment: Some(moment * fr * lh),
                ..BeltPoint::new(x * lh, yy * lh, theta, n * fr, (1.0 + g1).hypot(g2), material * lh)
            }
        };
        match (topology.segment(k).pulley(), phi) {
            (Some(pulley), Some(phi)) => {
                let (lambda, theta) = (y[LAMBDA], y[THETA]);
                let gamma = phi - FRAC_PI_2 - theta;
                let n = self.rod.axial_stiffness * (lambda * gamma.cos() - 1.0);
                let q = self.shear_stiffness * lambda * gamma.sin();
                let (px, py) = on_pulley(self.rod.radius, pulley, phi);
                let mut pt = rod(px, py, theta, y[MOMENT], n, q, y[MATERIAL]);
                pt.pressure = Some(self.arc_pressure(self.rod.bending, phi, y) * fr / lh);
                pt.angle = Some(phi);
                pt
            }
            _ => {
                let (n, q) = Self::span_nq(y);
                rod(y[0], y[1], y[2], y[3], n, q, y[6])
            }
        }
    }

    fn first_integral(d: &CosseratHanging, pt: &BeltPoint) -> Option<f64> {
        // (CH5) E = M²/(2a) + N + N²/(2b₁) + Q²/(2b₂) − ρ g y.
        let q = pt.shear?;
        let r = &d.rod;
        let e = section_energy(pt.moment?, pt.tension, r.bending_stiffness, r.axial_stiffness) + q * q / (2.0 * d.shear_stiffness);
        Some(e - r.mass_per_length * r.gravity * pt.y)
    }

    fn arc_force_name(&self) -> &'static str {
        "axial force"
    }

    fn arc_force(&self, arc_state: &[f64]) -> f64 {
        // b₁(λ − 1): the axial force at zero shear angle, a scale for the acceptance test
        // (the point checks use N = b₁(λ cos γ − 1) itself).
        self.rod.axial_stiffness * (arc_state[LAMBDA] - 1.0)
    }

    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        balance::check_loop_closure(sol, sol.data.rod.length)
    }

    fn admissible_window(&self) -> (f64, f64) {
        ROD_WINDOW
    }

    fn positive_force(kind: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        (kind != SegmentKind::Span).then_some(("axial force", pt.tension))
    }
}
