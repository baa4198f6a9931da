//! The Cosserat belt in steady motion as a section law of the open one-pulley topology
//! (docs/cosserat-pulley.md), in scaled variables: lengths by R, forces by F_ref =
//! max(N_in, N_out), moments and the torque by F_ref·R, the bending stiffness a by
//! F_ref·R².
//!
//! Spans run in the material coordinate s with the Cosserat span of `cosserat_hanging`
//! ((CP1), spec (C1) with the transport term χ = ρc²); arcs run in the polar angle φ:
//! stick (θ, M, s, τ) with λ the law's own parameter λ_B, slip (θ, M, s, τ, λ) with λ′
//! from the Coulomb law (C4). The contact boundaries are the Cosserat ones (no edge
//! forces, [`contact_rows`]); the two open ends carry the end conditions of spec §2.3.

use std::f64::consts::{FRAC_PI_2, PI};

use crate::belt::law::{BeltPoint, ContactEdges, Rows, Scales, SectionLaw};
use crate::belt::solution::BeltSolution;
use crate::belt::topology::{ArcKind, Pulley, SegmentKind, Topology};
use crate::belt::BeltError;
use crate::cosserat_hanging::law::{contact_rows, span_rhs, ArcForce, Edge, ScaledCosseratHanging};
use crate::problem::Scalar;

use super::CosseratPulley;

/// Span state components (the Cosserat span of `cosserat_hanging`).
pub(crate) const SPAN: [&str; 7] = ["x", "y", "theta", "M", "F_x", "F_y", "s"];
/// Arc state components: θ, M, s, τ; λ (slip only).
const THETA: usize = 0;
const MOMENT: usize = 1;
const MATERIAL: usize = 2;
const TORQUE: usize = 3;
const LAMBDA: usize = 4;
/// Parameter index of the stick stretch λ_B (after the topology's five).
pub(crate) const LAMBDA_B: usize = 5;
/// Parameter index of the free end's effective force (modes other than `tensions`).
const END_FORCE: usize = 6;
/// Parameter index of the stick → slip angle φ_B (the topology's `phi_t`).
const PHI_B: usize = 3;

/// The condition that closes a mode other than `tensions` (spec §2.3), in place of the
/// free end's force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Closing {
    /// Mode `tensions`: both end forces given, nothing to add.
    None,
    /// Mode `transition`: φ_B = the given angle (rad).
    StickSlipAngle(f64),
    /// Mode `pulley_speed`: λ_B = ωR/c.
    StickStretch(f64),
}

/// The scaled one-pulley problem. Its homotopy path η interpolates the bending
/// stiffness in log, a(η) = a₀^(1−η) a^η, from the start a₀ (= a unless a continuation
/// is needed).
#[derive(Debug, Clone)]
pub struct ScaledCosseratPulley {
    /// b₁/F_ref.
    pub axial: f64,
    /// b₂/F_ref.
    pub shear: f64,
    /// χ/F_ref = ρc²/F_ref (0 without the inertia effect).
    pub chi: f64,
    /// a₀ and a over F_ref R².
    pub bending_start: f64,
    /// a/(F_ref R²).
    pub bending: f64,
    /// D/R.
    pub end_distance: f64,
    /// F̃·e₁ at the inflow end, F̃·e₁ at the outflow end (spec §2.3), over F_ref.
    pub end_forces: [f64; 2],
    /// Coulomb coefficient μ.
    pub mu: f64,
    /// Slip sign σ: +1 when the pulley drives the belt (N_in > N_out: the belt is slower
    /// than the surface in the slip zone), −1 when it brakes.
    pub slip_sign: f64,
    /// The end (0 inflow, 1 outflow) whose effective force is the unknown parameter
    /// `end_force` instead of `end_forces[e]` (its start value); `None` in mode `tensions`.
    pub free_end: Option<usize>,
    /// The condition that replaces the free end's force.
    pub closing: Closing,
}

/// One arc point in d/ds: slopes and the contact loads of (C3).
pub(crate) struct ArcSlopes<D> {
    /// θ′, M′, λ′, τ′.
    pub d: [D; 4],
    /// p and f_t (scaled, per unstretched length).
    pub pressure: D,
    pub friction: D,
    /// F̃ = T t + S n.
    pub force: ArcForce<D>,
    /// Stretch λ and shear angle γ.
    pub lambda: D,
    pub gamma: D,
}

impl ScaledCosseratPulley {
    /// a(η) (scaled).
    pub fn bending_at<D: Scalar>(&self, eta: D) -> D {
        (D::from(self.bending_start.ln()) * (D::from(1.0) - eta) + eta * self.bending.ln()).exp()
    }

    /// (C2) F̃ = T t + S n at (λ, γ).
    fn force<D: Scalar>(&self, lambda: D, gamma: D) -> ArcForce<D> {
        ArcForce::new(self.axial, self.shear, self.chi, lambda, gamma)
    }

    /// The arc of `kind` in d/ds at φ (R = 1 scaled): λ = λ_B in stick, the state in slip;
    /// (C3) for p and f_t, (C4) for λ′ in slip, M′ = −λS, θ′ = M/a, τ′ = −R f_t.
    pub(crate) fn arc_slopes<D: Scalar>(&self, kind: ArcKind, a: D, phi: D, y: &[D], lambda_b: D) -> ArcSlopes<D> {
        let lambda = if kind == ArcKind::Slip { y[LAMBDA] } else { lambda_b };
        let gamma = phi - FRAC_PI_2 - y[THETA];
        let f = self.force(lambda, gamma);
        let dphi = -lambda;
        let dtheta = y[MOMENT] / a;
        let dgamma = dphi - dtheta;
        let dlambda = if kind == ArcKind::Slip {
            let sm = self.slip_sign * self.mu;
            ((f.t_g - f.s_g * sm) * dgamma - (f.s + f.t * sm) * dphi) / (f.s_l * sm - f.t_l)
        } else {
            D::from(0.0)
        };
        let dt = f.t_l * dlambda + f.t_g * dgamma;
        let ds = f.s_l * dlambda + f.s_g * dgamma;
        let pressure = -ds - f.t * dphi;
        let friction = f.s * dphi - dt;
        ArcSlopes { d: [dtheta, -(lambda * f.s), dlambda, -friction], pressure, friction, force: f, lambda, gamma }
    }
}

fn arc_kind(kind: SegmentKind) -> ArcKind {
    match kind {
        SegmentKind::Arc(k) => k,
        SegmentKind::Span => unreachable!("an arc segment"),
    }
}

impl SectionLaw for ScaledCosseratPulley {
    type Data = CosseratPulley;
    type Start = ();

    const SPAN_STATES: &'static [&'static str] = &SPAN;
    const ARC_STATES: &'static [&'static str] = &["theta", "M", "s", "tau"];
    const CONTACT_EDGES: ContactEdges = ContactEdges::Pressures;

    fn friction(data: &CosseratPulley) -> Option<f64> {
        Some(data.friction)
    }

    fn state_names(&self, kind: SegmentKind) -> &'static [&'static str] {
        match kind {
            SegmentKind::Span => Self::SPAN_STATES,
            SegmentKind::Arc(ArcKind::Slip) => &["theta", "M", "s", "tau", "lambda"],
            SegmentKind::Arc(_) => Self::ARC_STATES,
        }
    }

    fn extra_params(&self) -> &'static [&'static str] {
        match self.free_end {
            None => &["lambda_b"],
            Some(_) => &["lambda_b", "end_force"],
        }
    }

    /// The stick arc reads λ_B; nothing else besides each segment's own parameters.
    fn rhs_reads(&self, _: &Topology) -> Vec<usize> {
        vec![LAMBDA_B]
    }

    fn span_rhs<D: Scalar>(&self, _: &Topology, l: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (CP1) = (C1) in s times the span length, no gravity.
        span_rhs(self.axial, self.shear, self.chi, 0.0, self.bending_at(eta), l, y, f);
    }

    fn arc_rhs<D: Scalar>(&self, _: &Topology, kind: ArcKind, _: Pulley, phi: D, dphi: D, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        // (CP2)/(CP3) with φ as variable, ds/dφ = −R/λ, times Δφ.
        let a = self.bending_at(eta);
        let sl = self.arc_slopes(kind, a, phi, y, p[LAMBDA_B]);
        let ds = -(dphi / sl.lambda);
        let [dtheta, dmoment, dlambda, dtorque] = sl.d;
        f[THETA] = ds * dtheta;
        f[MOMENT] = ds * dmoment;
        f[MATERIAL] = ds;
        f[TORQUE] = ds * dtorque;
        if kind == ArcKind::Slip {
            f[LAMBDA] = ds * dlambda;
        }
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], _: Option<D>, p: &[D], _: D, rows: &mut Rows<D>) {
        // (CP4) at A: on the circle, θ, M, F̃ (at λ_B) and s continuous; τ = 0.
        let f = self.force(p[LAMBDA_B], phi - FRAC_PI_2 - arc[THETA]);
        contact_rows(1.0, pulley, phi, e, [arc[THETA], arc[MOMENT], arc[MATERIAL]], &f, Edge::Start { jump: None }, rows);
        rows.push(arc[TORQUE]);
    }

    fn arc_to_arc<D: Scalar>(&self, _: Pulley, from_end: &[D], to_start: &[D], p: &[D], rows: &mut Rows<D>) {
        // (CP5) at B: θ, M, s, τ continuous; the slip zone starts at λ = λ_B.
        for j in [THETA, MOMENT, MATERIAL, TORQUE] {
            rows.push(to_start[j] - from_end[j]);
        }
        rows.push(to_start[LAMBDA] - p[LAMBDA_B]);
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], span: &[D], _: bool, _: &[D], _: D, rows: &mut Rows<D>) {
        // (CP4) at C: on the circle, θ, M, F̃ (at the slip stretch) and s continuous.
        let f = self.force(arc_end[LAMBDA], phi - FRAC_PI_2 - arc_end[THETA]);
        let arc = [arc_end[THETA], arc_end[MOMENT], arc_end[MATERIAL]];
        contact_rows(1.0, pulley, phi, span, arc, &f, Edge::End { closes_loop: false }, rows);
    }

    fn open_ends<D: Scalar>(&self, inflow: &[D], outflow: &[D], p: &[D], _: D, rows: &mut Rows<D>) {
        // (CP6) inflow: x = −D, θ = 0, F̃ = (F̃_in, 0) (Q = 0), s = 0;
        // outflow: x = −D, θ = −π, M = 0, F̃·e₁ = F̃_out; the free end's force (modes
        // `transition`, `pulley_speed`) is the parameter `end_force`, closed by the mode's
        // prescription (spec §2.3).
        let force = |e: usize| if self.free_end == Some(e) { p[END_FORCE] } else { D::from(self.end_forces[e]) };
        let (f_in, f_out) = (force(0), force(1));
        rows.push(inflow[0] + self.end_distance);
        rows.push(inflow[2]);
        rows.push(inflow[4] - f_in);
        rows.push(inflow[5]);
        rows.push(inflow[6]);
        let (n, _) = ScaledCosseratHanging::span_nq(outflow);
        rows.push(outflow[0] + self.end_distance);
        rows.push(outflow[2] + PI);
        rows.push(outflow[3]);
        rows.push(n - f_out);
        match self.closing {
            Closing::None => {}
            Closing::StickSlipAngle(phi) => rows.push(p[PHI_B] - phi),
            Closing::StickStretch(stretch) => rows.push(p[LAMBDA_B] - stretch),
        }
    }

    fn loop_conditions<D: Scalar>(&self, _: &Topology, _: &[&[D]], _: &[&[D]], _: &[D], _: D, _: &mut Rows<D>) {
        // An open domain: every condition sits at an end or a junction.
    }

    fn point(&self, _: &CosseratPulley, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], p: &[f64]) -> BeltPoint {
        let (lr, fr) = (sc.length, sc.force);
        let (b1, b2, chi) = (self.axial, self.shear, self.chi);
        // N = b₁Γ₁, Q = b₂Γ₂ from the effective components F̃·e₁ = T̃, F̃·e₂ (§1.2)
        let section = |x: f64, yy: f64, theta: f64, moment: f64, te: f64, qe: f64, material: f64| {
            let (g1, g2) = ((te + chi) / (b1 - chi), qe / (b2 - chi));
            BeltPoint {
                shear: Some(b2 * g2 * fr),
                shear_strain: Some(g2),
                moment: Some(moment * fr * lr),
                effective_tension: Some(te * fr),
                ..BeltPoint::new(x * lr, yy * lr, theta, b1 * g1 * fr, (1.0 + g1).hypot(g2), material * lr)
            }
        };
        match phi {
            Some(phi) => {
                let kind = arc_kind(topology.segment(k).kind);
                let sl = self.arc_slopes(kind, self.bending, phi, y, p[LAMBDA_B]);
                let (sg, cg) = (sl.gamma.sin(), sl.gamma.cos());
                // e₁ = cos γ t − sin γ n, e₂ = sin γ t + cos γ n
                let (te, qe) = (sl.force.t * cg - sl.force.s * sg, sl.force.t * sg + sl.force.s * cg);
                let mut pt = section(phi.cos(), phi.sin(), y[THETA], y[MOMENT], te, qe, y[MATERIAL]);
                pt.pressure = Some(sl.pressure * fr / lr);
                pt.friction = Some(sl.friction * fr / lr);
                pt.angle = Some(phi);
                pt.torque = Some(y[TORQUE] * fr * lr);
                pt
            }
            None => {
                let (te, qe) = ScaledCosseratHanging::span_nq(y);
                section(y[0], y[1], y[2], y[3], te, qe, y[6])
            }
        }
    }

    fn first_integral(d: &CosseratPulley, pt: &BeltPoint) -> Option<f64> {
        // (C5) E = M²/(2a) + N + N²/(2b₁) + Q²/(2b₂) − ½χλ² (no gravity).
        let (m, q, n) = (pt.moment?, pt.shear?, pt.tension);
        Some(m * m / (2.0 * d.bending_stiffness) + n + n * n / (2.0 * d.axial_stiffness) + q * q / (2.0 * d.shear_stiffness) - 0.5 * d.chi() * pt.stretch * pt.stretch)
    }

    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        super::check_moment_balance(&sol.data, |k, xi| sol.point(k, xi))
    }

    fn admissible_window(&self) -> (f64, f64) {
        // first contact within 90° of π/2, last within 90° of −π/2; arcs may close to zero
        (FRAC_PI_2, 1e-9)
    }

    /// Not read: the one-pulley run does not use the loop's acceptance test
    /// (`belt::solution::on_branch`, whose arc force is arc state 0); its points are
    /// judged by `CosseratPulleySolution::check_admissible`, whose positive force is T̃.
    fn arc_force_name(&self) -> &'static str {
        "effective tension"
    }

    fn positive_force(kind: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        (kind != SegmentKind::Span).then_some(("effective tension", pt.effective_tension.unwrap_or(f64::NAN)))
    }
}
