//! The Cosserat belt in steady motion as a section law of the two-pulley loop with
//! Coulomb friction (docs/cosserat-drive.md), in the string drive's scaled variables:
//! lengths by H, forces by F_ref, speeds by V = √(F_ref/ρ) (so χ/F_ref = c̃²), torques
//! and moments by F_ref·H, the bending stiffness a by F_ref·H².
//!
//! Spans: the Cosserat span of the static loop with χ = ρc² and the weight ((CD1),
//! `cosserat_hanging::law::moving_span_rhs`). Arcs: the one-pulley arc ((CP3),
//! `cosserat_pulley`'s `arc_slopes` at χ = 0 and no weight, in lengths of R) plus the
//! transport and weight terms of (CD3). Contact boundaries: `contact_rows` of the static
//! loop with the effective force (CD2). The stick stretches λ₁, λ₂ are the law's own
//! parameters after the topology's twelve; with the driver's stick → slip angle
//! prescribed ([`DriveMode::StickSlipAngle`]) the load torque M₂ follows them as an
//! unknown, closed by φ_B1 = the given angle (spec §3.4).

use std::f64::consts::FRAC_PI_2;

use crate::belt::law::{BeltPoint, ContactEdges, Rows, Scales, SectionLaw};
use crate::belt::solution::BeltSolution;
use crate::belt::topology::{ArcKind, Pulley, SegmentKind, Topology};
use crate::belt::{balance, BeltError};
use crate::cosserat_hanging::law::{contact_rows, moving_span_rhs, ArcForce, Edge, ScaledCosseratHanging};
use crate::cosserat_pulley::law::{ArcSlopes, Closing};
use crate::cosserat_pulley::ScaledCosseratPulley;
use crate::problem::Scalar;
use crate::string_drive::{ScaledStringDrive, StringDriveSolution};
use crate::string_hanging::law::on_pulley;

use super::{CosseratDrive, DriveMode};

/// Arc state components (the one-pulley belt's): θ, M, s, τ; λ (slip only).
const THETA: usize = 0;
const MOMENT: usize = 1;
const MATERIAL: usize = 2;
const TORQUE: usize = 3;
const LAMBDA: usize = 4;
/// Parameter indices on the Coulomb loop (`Topology::two_pulley_running`): transport rate
/// c, driven speed ω₂, then the law's stick stretches λ₁ (driver), λ₂ (driven).
pub const TRANSPORT: usize = 10;
pub const DRIVEN_SPEED: usize = 11;
pub const LAMBDA_DRIVER: usize = 12;
pub const LAMBDA_DRIVEN: usize = 13;
/// Parameter index of the load torque M₂/(F_ref H) when it is released
/// ([`DriveMode::StickSlipAngle`]).
pub const LOAD_TORQUE: usize = 14;

/// The scaled Cosserat drive: the string drive's scaled scene (at η = 1 of its own path:
/// R/H, b₁, weight, μ, ω₁, M₂, d₂, L, power flow) and the Cosserat constants, with the
/// homotopy a(η) = a₀^(1−η) a^η at the scene's b₂.
#[derive(Debug, Clone)]
pub struct ScaledCosseratDrive {
    /// The string drive of the same scene, scaled (its `*_at(η)` path is not used).
    pub string: ScaledStringDrive,
    /// b₂ / F_ref.
    pub shear: f64,
    /// a₀ / (F_ref H²), the homotopy start.
    pub bending_start: f64,
    /// a / (F_ref H²).
    pub bending: f64,
    /// What closes the driven torque balance: M₂ given (the string law's `torque`), or
    /// the driver's stick → slip angle given with M₂ the parameter [`LOAD_TORQUE`].
    pub mode: DriveMode,
}

impl ScaledCosseratDrive {
    /// The one-pulley belt of this drive's section with slip sign `slip_sign` (its arc
    /// equations and its log-a path), at χ = 0: the drive adds the transport and the
    /// weight itself.
    fn one_pulley(&self, slip_sign: f64) -> ScaledCosseratPulley {
        ScaledCosseratPulley {
            axial: self.string.axial_stiffness,
            shear: self.shear,
            chi: 0.0,
            bending_start: self.bending_start,
            bending: self.bending,
            end_distance: f64::NAN,
            end_forces: [f64::NAN; 2],
            mu: self.string.friction,
            slip_sign,
            free_end: None,
            closing: Closing::None,
        }
    }

    /// a(η) = a₀^(1−η) a^η (scaled), the one-pulley belt's path.
    pub fn bending_at<D: Scalar>(&self, eta: D) -> D {
        self.one_pulley(1.0).bending_at(eta)
    }

    /// χ/F_ref = c̃² with the inertia effect, else 0.
    pub fn chi<D: Scalar>(&self, p: &[D]) -> D {
        if self.string.inertia { p[TRANSPORT] * p[TRANSPORT] } else { D::from(0.0) }
    }

    /// The load torque M₂/(F_ref H): the scene's, or the parameter [`LOAD_TORQUE`] when
    /// the mode releases it.
    pub fn load_torque<D: Scalar>(&self, p: &[D]) -> D {
        match self.mode {
            DriveMode::LoadTorque => D::from(self.string.torque),
            DriveMode::StickSlipAngle { .. } => p[LOAD_TORQUE],
        }
    }

    /// Stick stretch λ_i of `pulley`.
    pub fn stick_stretch<D: Copy>(pulley: Pulley, p: &[D]) -> D {
        match pulley {
            Pulley::Driver => p[LAMBDA_DRIVER],
            _ => p[LAMBDA_DRIVEN],
        }
    }

    /// (CD2) F̃ = T̃ t + S n at (λ, γ): the static force of (CH2) with T̃ = T⁰ − χλ,
    /// T̃_λ = T⁰_λ − χ.
    pub fn force<D: Scalar>(&self, lambda: D, gamma: D, chi: D) -> ArcForce<D> {
        let f = ArcForce::new(self.string.axial_stiffness, self.shear, 0.0, lambda, gamma);
        ArcForce { t: f.t - chi * lambda, t_l: f.t_l - chi, ..f }
    }

    /// The arc of `kind` on `pulley` at φ in d/ds (CD3): the one-pulley arc at χ = 0 and
    /// no weight in lengths of R, converted to lengths of H, plus the transport and
    /// weight terms.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn arc<D: Scalar>(&self, topology: &Topology, kind: ArcKind, pulley: Pulley, phi: D, y: &[D], p: &[D], eta: D) -> ArcSlopes<D> {
        let (r, w) = (self.string.radius, self.string.weight);
        let one_pulley = self.one_pulley(pulley.slip_sign(topology.direction(), self.string.flow));
        let sm = one_pulley.slip_sign * one_pulley.mu;
        let zero = D::from(0.0);
        let slip = kind == ArcKind::Slip;
        // state in lengths of R: M/R = M_H / r
        let y_r = [y[THETA], y[MOMENT] / r, zero, zero, if slip { y[LAMBDA] } else { zero }];
        let a = one_pulley.bending_at(eta);
        let sl = one_pulley.arc_slopes(kind, a / (r * r), phi, &y_r, Self::stick_stretch(pulley, p));
        let (lambda, f0) = (sl.lambda, sl.force);
        // d/ds_H = (1/r) d/ds_R; p, f_t per length of H = (per length of R)/r
        let (dtheta, dmoment, dlambda0) = (sl.d[0] / r, sl.d[1], sl.d[2] / r);
        let chi = self.chi(p);
        let dphi = -(lambda / r);
        let (sin, cos) = (phi.sin(), phi.cos());
        let dlambda = if slip {
            let d0 = f0.s_l * sm - f0.t_l;
            (dlambda0 * d0 + chi * lambda * dphi * sm + (cos + sin * sm) * w) / (d0 + chi)
        } else {
            zero
        };
        let change = dlambda - dlambda0;
        let pressure = sl.pressure / r - f0.s_l * change + chi * lambda * dphi + sin * w;
        let friction = sl.friction / r - f0.t_l * change + chi * dlambda - cos * w;
        ArcSlopes {
            d: [dtheta, dmoment, dlambda, -(friction * r)],
            pressure,
            friction,
            force: self.force(lambda, sl.gamma, chi),
            lambda,
            gamma: sl.gamma,
        }
    }

    /// The effective force at a contact boundary of an arc with state `arc`: at λ_i on a
    /// stick arc, at the state λ on a slip arc.
    fn edge_force<D: Scalar>(&self, pulley: Pulley, phi: D, arc: &[D], p: &[D]) -> ArcForce<D> {
        let lambda = if arc.len() > LAMBDA { arc[LAMBDA] } else { Self::stick_stretch(pulley, p) };
        self.force(lambda, phi - FRAC_PI_2 - arc[THETA], self.chi(p))
    }

    /// Physical point from the effective force components F̃·e₁ = T̃, F̃·e₂ (scaled) and
    /// the position, θ, M, s (scaled) of a section (CD0).
    #[allow(clippy::too_many_arguments)]
    fn section(&self, sc: &Scales, chi: f64, position: [f64; 2], theta: f64, moment: f64, te: f64, qe: f64, material: f64) -> BeltPoint {
        let (lh, fr, b1, b2) = (sc.length, sc.force, self.string.axial_stiffness, self.shear);
        let g1 = (te + chi) / (b1 - chi);
        let g2 = qe / (b2 - chi);
        let mut pt = BeltPoint::new(position[0] * lh, position[1] * lh, theta, b1 * g1 * fr, (1.0 + g1).hypot(g2), material * lh);
        pt.shear = Some(b2 * g2 * fr);
        pt.shear_strain = Some(g2);
        pt.moment = Some(moment * fr * lh);
        pt.effective_tension = Some(te * fr);
        pt
    }
}

impl SectionLaw for ScaledCosseratDrive {
    type Data = CosseratDrive;
    type Start = StringDriveSolution;

    const SPAN_STATES: &'static [&'static str] = ScaledCosseratPulley::SPAN_STATES;
    const ARC_STATES: &'static [&'static str] = ScaledCosseratPulley::ARC_STATES;
    const CONTACT_EDGES: ContactEdges = ContactEdges::Pressures;

    fn friction(d: &CosseratDrive) -> Option<f64> {
        Some(d.drive.friction)
    }

    fn power_flow(&self) -> crate::belt::topology::PowerFlow {
        self.string.flow
    }

    /// The one-pulley belt's layout: λ is a state in slip only.
    fn state_names(&self, kind: SegmentKind) -> &'static [&'static str] {
        self.one_pulley(1.0).state_names(kind)
    }

    /// λ₁, λ₂; M₂ after them when the mode releases it.
    fn extra_params(&self) -> &'static [&'static str] {
        match self.mode {
            DriveMode::LoadTorque => &["lambda1", "lambda2"],
            DriveMode::StickSlipAngle { .. } => &["lambda1", "lambda2", "load_torque"],
        }
    }

    /// Spans and arcs read c (χ = ρc²); the stick arcs λ₁, λ₂.
    fn rhs_reads(&self, _: &Topology) -> Vec<usize> {
        vec![TRANSPORT, LAMBDA_DRIVER, LAMBDA_DRIVEN]
    }

    fn span_rhs<D: Scalar>(&self, _: &Topology, l: D, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        // (CD1) times the span length ℓ.
        let s = &self.string;
        moving_span_rhs(s.axial_stiffness, self.shear, self.chi(p), D::from(s.weight), self.bending_at(eta), l, y, f);
    }

    fn arc_rhs<D: Scalar>(&self, topology: &Topology, kind: ArcKind, pulley: Pulley, phi: D, dphi: D, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        // (CD3) with φ as variable, ds/dφ = −R/λ, times Δφ.
        let arc = self.arc(topology, kind, pulley, phi, y, p, eta);
        let ds = -(dphi * self.string.radius / arc.lambda);
        // d/ds of (θ, M, s, τ, λ) in the state order; a stick arc has no λ
        let [dtheta, dmoment, dlambda, dtorque] = arc.d;
        for (fj, slope) in f.iter_mut().zip([dtheta, dmoment, D::from(1.0), dtorque, dlambda]) {
            *fj = ds * slope;
        }
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], _: Option<D>, p: &[D], _: D, rows: &mut Rows<D>) {
        // (CD4) at the first contact; τ = 0.
        let f = self.edge_force(pulley, phi, arc, p);
        contact_rows(self.string.radius, pulley, phi, e, [arc[THETA], arc[MOMENT], arc[MATERIAL]], &f, Edge::Start { jump: None }, rows);
        rows.push(arc[TORQUE]);
    }

    fn arc_to_arc<D: Scalar>(&self, pulley: Pulley, from_end: &[D], to_start: &[D], p: &[D], rows: &mut Rows<D>) {
        // (CD5): θ, M, s, τ continuous; the slip side at λ_i (after a clockwise stick
        // arc, before a counter-clockwise one).
        for j in [THETA, MOMENT, MATERIAL, TORQUE] {
            rows.push(to_start[j] - from_end[j]);
        }
        let slip_side = if to_start.len() > LAMBDA { to_start[LAMBDA] } else { from_end[LAMBDA] };
        rows.push(slip_side - Self::stick_stretch(pulley, p));
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], span: &[D], closes_loop: bool, p: &[D], _: D, rows: &mut Rows<D>) {
        // (CD4) at the last contact; θ gains 2π and s restarts where the loop closes.
        let f = self.edge_force(pulley, phi, arc_end, p);
        let arc = [arc_end[THETA], arc_end[MOMENT], arc_end[MATERIAL]];
        contact_rows(self.string.radius, pulley, phi, span, arc, &f, Edge::End { closes_loop }, rows);
    }

    fn loop_conditions<D: Scalar>(&self, topology: &Topology, _: &[&[D]], yb: &[&[D]], p: &[D], _: D, rows: &mut Rows<D>) {
        // (CD6): length, the stick kinematics of both pulleys, the driven torque balance;
        // with M₂ released (one more unknown) the prescribed φ_B1 (one more row).
        let s = &self.string;
        let (c, omega2) = (p[TRANSPORT], p[DRIVEN_SPEED]);
        rows.push(yb[topology.len() - 1][MATERIAL] - s.length);
        rows.push(c * p[LAMBDA_DRIVER] - s.driver_speed * s.radius);
        rows.push(c * p[LAMBDA_DRIVEN] - omega2 * s.radius);
        rows.push(yb[topology.last_arc(Pulley::Driven)][TORQUE] - (omega2 * s.damping + self.load_torque(p)));
        if let DriveMode::StickSlipAngle { driver } = self.mode {
            let angle = topology.transition_angle(Pulley::Driver).expect("a drive has a stick → slip point on the driver");
            rows.push(p[angle] - driver);
        }
    }

    fn point(&self, _: &CosseratDrive, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], p: &[f64]) -> BeltPoint {
        let chi = self.chi(p);
        let seg = topology.segment(k);
        match (seg.pulley(), phi, seg.kind) {
            (Some(pulley), Some(phi), SegmentKind::Arc(kind)) => {
                let arc = self.arc(topology, kind, pulley, phi, y, p, 1.0);
                let (sg, cg) = (arc.gamma.sin(), arc.gamma.cos());
                // e₁ = cos γ t − sin γ n, e₂ = sin γ t + cos γ n
                let (f, fr, lh) = (arc.force, sc.force, sc.length);
                let (te, qe) = (f.t * cg - f.s * sg, f.t * sg + f.s * cg);
                let (px, py) = on_pulley(self.string.radius, pulley, phi);
                BeltPoint {
                    pressure: Some(arc.pressure * fr / lh),
                    friction: Some(arc.friction * fr / lh),
                    angle: Some(phi),
                    torque: Some(y[TORQUE] * fr * lh),
                    ..self.section(sc, chi, [px, py], y[THETA], y[MOMENT], te, qe, y[MATERIAL])
                }
            }
            _ => {
                let (te, qe) = ScaledCosseratHanging::span_nq(y);
                self.section(sc, chi, [y[0], y[1]], y[2], y[3], te, qe, y[6])
            }
        }
    }

    /// The power balance (D-3) at the solved M₂ (the scene's, or the released one).
    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        let drive = sol.solved_drive();
        let (input, output, dissipation) = balance::drive_power(sol, &drive);
        balance::check_power(input - output - dissipation, balance::drive_power_scale(&drive, sol.scales.force))
    }

    fn admissible_window(&self) -> (f64, f64) {
        // contact angles within 90° of their tight values; stick and slip arcs ≥ 0
        (FRAC_PI_2, 1e-9)
    }

    /// a₀ = a when the scene's bending layer is at least the start layer
    /// (`cosserat_drive::scaled_law`): no path in a.
    fn starts_at_scene(&self) -> bool {
        self.bending_start == self.bending
    }

    fn arc_force_name(&self) -> &'static str {
        "slip-zone stretch force b₁(λ − 1)"
    }

    /// The homotopy's positive arc force: b₁(λ − 1) of a slip arc node (the stick arcs
    /// carry λ_i as a parameter, not a state; their T̃ is checked after the solve).
    fn arc_force(&self, arc_state: &[f64]) -> f64 {
        arc_state.get(LAMBDA).map_or(f64::INFINITY, |l| self.string.axial_stiffness * (l - 1.0))
    }

    /// b₁(λ − 1): the slip direction follows the stretch (λ ≤ λ_i where the pulley drags
    /// the belt, the belt slower than the surface; λ ≥ λ_i where it brakes); N = b₁(λ cos γ
    /// − 1) also varies with the shear angle in the edge layers.
    fn slip_force(&self, d: &CosseratDrive, pt: &BeltPoint) -> f64 {
        d.drive.axial_stiffness * (pt.stretch - 1.0)
    }

    fn positive_force(_: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        pt.effective_tension.map(|t| ("effective tension", t))
    }
}
