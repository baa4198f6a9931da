//! The eight-segment BVP of `docs/string-drive.md`, in scaled variables.
//!
//! Lengths are scaled by the centre distance H, forces by F_ref, speeds by
//! V = √(F_ref/ρ) (so ρc²/F_ref = c̃²), angular speeds by V/H, torques by F_ref·H.
//! Segment order, states, parameters and conditions are the tables of the note: the
//! two-pulley topology with Coulomb friction (stick then slip on each pulley); span state
//! (x, y, F̃_x, F̃_y, s) in s, (D3); arc state (T̃, s, m) in φ, (D6), (D7).

use std::f64::consts::PI;

use crate::belt::balance;
use crate::belt::law::{BeltPoint, Rows, Scales, SectionLaw};
use crate::belt::solution::{BeltSolution, TightLoop};
use crate::belt::topology::{ArcKind, PowerFlow, Pulley, SegmentKind, Topology};
use crate::belt::BeltError;
use crate::problem::Scalar;
use crate::string_hanging::law::{norm, string_contact_end, string_contact_start};

use super::StringDrive;

/// The scaled problem with the four-phase homotopy in η of the note:
/// η ∈ [0, ¼] torque and damping 0 → full; [¼, ½] gravity 0 → g; [½, ¾] length L₀ → L;
/// [¾, 1] driver speed 0 → ω₁.
#[derive(Debug, Clone)]
pub struct ScaledStringDrive {
    /// R / H.
    pub radius: f64,
    /// EA / F_ref.
    pub axial_stiffness: f64,
    /// ρ g H / F_ref at full gravity.
    pub weight: f64,
    /// Persistent transport inertia on (ρc² terms) or off.
    pub inertia: bool,
    /// μ.
    pub friction: f64,
    /// ω₁ H / V.
    pub driver_speed: f64,
    /// M₂ / (F_ref H).
    pub torque: f64,
    /// d₂ V / (F_ref H²).
    pub damping: f64,
    /// L₀ / H (η ≤ ½).
    pub length_start: f64,
    /// L / H.
    pub length: f64,
    /// Which pulley puts power into the belt (the slip signs), from the scene's net load
    /// M₂ + d₂ω₁ and running direction.
    pub flow: PowerFlow,
    /// d₂ω₁/(F_ref H) when the net load M₂ + d₂ω₁ and M₂ alone would drive the belt the
    /// opposite ways, else 0: the path then holds the load at the scene's net value while
    /// the driver is at rest, (M₂ + d₂(ω₁ − ω₁(η)) + d₂ω₂)·f(η), so the power flow — the
    /// slip signs of the topology — never changes along the path.
    pub preload: f64,
}

fn ramp(eta: f64, from: f64) -> f64 {
    (4.0 * eta - from).clamp(0.0, 1.0)
}

impl ScaledStringDrive {
    /// Fraction of the torque and damping at η (phase 1, η ∈ [0, ¼]).
    pub fn torque_factor<D: Scalar>(&self, eta: D) -> D {
        if eta.re() < 0.25 { eta * 4.0 } else { D::from(1.0) }
    }
    /// Weight per unstretched length at η (phase 2, η ∈ [¼, ½]).
    pub fn weight_at<D: Scalar>(&self, eta: D) -> D {
        let e = eta.re();
        if e <= 0.25 {
            D::from(0.0)
        } else if e < 0.5 {
            (eta * 4.0 - 1.0) * self.weight
        } else {
            D::from(self.weight)
        }
    }
    /// Unstretched length at η (phase 3, η ∈ [½, ¾]).
    pub fn length_at<D: Scalar>(&self, eta: D) -> D {
        let e = eta.re();
        if e <= 0.5 {
            D::from(self.length_start)
        } else if e < 0.75 {
            (eta * 4.0 - 2.0) * (self.length - self.length_start) + self.length_start
        } else {
            D::from(self.length)
        }
    }
    /// Driver speed at η (phase 4, η ∈ [¾, 1]).
    pub fn speed_at<D: Scalar>(&self, eta: D) -> D {
        if eta.re() <= 0.75 { D::from(0.0) } else { (eta * 4.0 - 3.0) * self.driver_speed }
    }
    /// The phase fractions (torque, gravity, length, speed) at η (f64).
    pub fn phases(eta: f64) -> [f64; 4] {
        [ramp(eta, 0.0), ramp(eta, 1.0), ramp(eta, 2.0), ramp(eta, 3.0)]
    }

    /// Stretch λ of (D2) at effective tension `t` and transport rate `c` (scaled).
    pub fn stretch<D: Scalar>(&self, t: D, c: D) -> D {
        if self.inertia { (t + self.axial_stiffness) / (-(c * c) + self.axial_stiffness) } else { t / self.axial_stiffness + 1.0 }
    }

    /// Axial force T from the effective tension (D2) (scaled).
    pub fn axial_force<D: Scalar>(&self, t: D, c: D) -> D {
        if self.inertia {
            let rc2 = c * c;
            (t + rc2) * self.axial_stiffness / (-rc2 + self.axial_stiffness)
        } else {
            t
        }
    }

    /// The tight, weightless loop at rest with length L₀ (the exact η = 0 solution).
    pub fn tight_tension(&self) -> f64 {
        self.axial_stiffness * ((2.0 + 2.0 * PI * self.radius) / self.length_start - 1.0)
    }
}

impl SectionLaw for ScaledStringDrive {
    type Data = StringDrive;
    type Start = ();

    fn friction(d: &StringDrive) -> Option<f64> {
        Some(d.friction)
    }

    const SPAN_STATES: &'static [&'static str] = &["x", "y", "Fe_x", "Fe_y", "s"];
    const ARC_STATES: &'static [&'static str] = &["Te", "s", "m"];

    /// The moving string reads the belt speed c (its stretch N/EA + 1 depends on ρc²).
    fn rhs_reads(&self, topology: &Topology) -> Vec<usize> {
        vec![topology.motion().expect("a drive topology has its motion").transport]
    }

    fn span_rhs<D: Scalar>(&self, topology: &Topology, l: D, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        // (D3) times the span length ℓ.
        let w = self.weight_at(eta);
        let c = transport(topology, p);
        let t = norm(y[2], y[3]);
        let stretch = self.stretch(t, c);
        f[0] = l * stretch * y[2] / t;
        f[1] = l * stretch * y[3] / t;
        f[2] = D::from(0.0);
        f[3] = if self.weight != 0.0 { l * w } else { D::from(0.0) };
        f[4] = l;
    }

    fn arc_rhs<D: Scalar>(&self, topology: &Topology, kind: ArcKind, pulley: Pulley, phi: D, dphi: D, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        // (D6), (D7) times Δφ.
        let w = self.weight_at(eta);
        let c = transport(topology, p);
        let t = y[0];
        let stretch = self.stretch(t, c);
        let r = self.radius;
        let ds = -(stretch.recip()) * r;
        // Gravity terms only when the scene has gravity (weight ≠ 0).
        let gravity = self.weight != 0.0;
        let dt = if kind == ArcKind::Slip {
            let mut pressure = t * stretch / r;
            if gravity {
                pressure += w * phi.sin();
            }
            let mut dt = pressure * (pulley.slip_sign(topology.direction(), self.flow) * self.friction);
            if gravity {
                dt += w * phi.cos();
            }
            dt * r / stretch
        } else {
            D::from(0.0)
        };
        f[0] = dphi * dt;
        f[1] = dphi * ds;
        f[2] = if gravity { dphi * (dt + w * phi.cos() * ds) * r } else { dphi * dt * r };
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], jump: Option<D>, _: &[D], _: D, rows: &mut Rows<D>) {
        // Tangential entry into the stick zone; the accumulated torque starts at 0.
        string_contact_start(self.radius, pulley, phi, e, arc, jump, rows);
        rows.push(arc[2]);
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], s: &[D], closes_loop: bool, _: &[D], _: D, rows: &mut Rows<D>) {
        string_contact_end(self.radius, pulley, phi, arc_end, s, closes_loop, rows);
    }

    fn loop_conditions<D: Scalar>(&self, topology: &Topology, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, rows: &mut Rows<D>) {
        let motion = topology.motion().expect("a drive topology has its motion");
        let (c, omega2) = (p[motion.transport], p[motion.driven_speed]);
        let rad = self.radius;
        let stick = |pulley| topology.arc(pulley, ArcKind::Stick).expect("a drive topology has stick arcs");
        // Total unstretched length.
        rows.push(yb[topology.len() - 1][1] - self.length_at(eta));
        // (D5): kinematics of the two stick zones.
        rows.push(c * self.stretch(ya[stick(Pulley::Driver)][0], c) - self.speed_at(eta) * rad);
        rows.push(omega2 * rad - c * self.stretch(ya[stick(Pulley::Driven)][0], c));
        // (D8): torque balance of the driven pulley.
        let m_end = yb[topology.last_arc(Pulley::Driven)][2];
        let mut load = omega2 * self.damping + self.torque;
        if self.preload != 0.0 {
            load += (-(self.speed_at(eta) / self.driver_speed) + 1.0) * self.preload;
        }
        rows.push(m_end - load * self.torque_factor(eta));
    }

    fn point(&self, d: &StringDrive, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], p: &[f64]) -> BeltPoint {
        let (lh, fr) = (sc.length, sc.force);
        let c = transport(topology, p);
        let moving = |x: f64, yy: f64, theta: f64, te: f64, material: f64| BeltPoint {
            effective_tension: Some(te * fr),
            ..BeltPoint::new(x, yy, theta, self.axial_force(te, c) * fr, self.stretch(te, c), material)
        };
        let seg = topology.segment(k);
        match (seg.pulley(), phi) {
            (Some(pulley), Some(phi)) => {
                let te = y[0];
                let x = pulley.centre_x() * lh + d.radius * phi.cos();
                let mut pt = moving(x, d.radius * phi.sin(), phi - std::f64::consts::FRAC_PI_2, te, y[1] * lh);
                let w = d.mass_per_length * d.gravity;
                let pressure = te * fr * pt.stretch / d.radius + w * phi.sin();
                let slip = seg.kind == SegmentKind::Arc(ArcKind::Slip);
                pt.pressure = Some(pressure);
                pt.friction = Some(if slip { pulley.slip_sign(topology.direction(), self.flow) * d.friction * pressure } else { -w * phi.cos() });
                pt.angle = Some(phi);
                pt.torque = Some(y[2] * fr * lh);
                pt
            }
            _ => moving(y[0] * lh, y[1] * lh, y[3].atan2(y[2]), y[2].hypot(y[3]), y[4] * lh),
        }
    }

    fn power_flow(&self) -> PowerFlow {
        self.flow
    }

    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        let (input, output, dissipation) = sol.power_balance();
        balance::check_power(input - output - dissipation, sol.power_scale())
    }

    fn admissible_window(&self) -> (f64, f64) {
        // Contact angles within 90° of their tight values; stick and slip arcs ≥ 0
        // (stick before slip) up to 1e-9 rad.
        (std::f64::consts::FRAC_PI_2, 1e-9)
    }

    fn arc_force_name(&self) -> &'static str {
        "effective tension"
    }

    fn positive_force(_: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        pt.effective_tension.map(|t| ("effective tension", t))
    }
}

/// The transport rate c̃ of the parameter vector.
fn transport<D: Copy>(topology: &Topology, p: &[D]) -> D {
    p[topology.motion().expect("a drive topology has its motion").transport]
}

impl TightLoop for ScaledStringDrive {
    fn tight_state(&self, kind: SegmentKind, position: [f64; 2], force: [f64; 2], tension: f64, material: f64) -> Vec<f64> {
        match kind {
            SegmentKind::Span => vec![position[0], position[1], force[0], force[1], material],
            SegmentKind::Arc(_) => vec![tension, material, 0.0],
        }
    }
}

#[cfg(test)]
impl ScaledStringDrive {
    /// A scaled drive with O(1) generic data for unit tests (R/H = 0.18, EA/F = 50,
    /// μ = 0.6, L/H = 3.2 from L₀/H = 3), with `inertia` and scaled weight `weight`.
    pub(crate) fn fixture(inertia: bool, weight: f64) -> Self {
        Self {
            radius: 0.18,
            axial_stiffness: 50.0,
            weight,
            inertia,
            friction: 0.6,
            driver_speed: 0.9,
            torque: 0.2,
            damping: 0.05,
            length_start: 3.0,
            length: 3.2,
            flow: PowerFlow::FromDriver,
            preload: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::belt::problem::BeltProblem;
    use crate::belt::topology::ContactModel;
    use crate::jacobian::ad_fd_mismatch_sampled;
    use crate::problem::Problem;

    /// AD Jacobians of (D3), (D6), (D7) and the 44 conditions agree with central
    /// differences at an arbitrary state, in each homotopy phase, with and without
    /// inertia and gravity, clockwise and counter-clockwise with the power from the
    /// driven pulley and a preload; 1e-6 relative is the accuracy of h ~ ε^{1/3} differences.
    #[test]
    fn ad_jacobians_match_finite_differences() {
        use crate::belt::topology::Direction;
        let ccw = |law: ScaledStringDrive| ScaledStringDrive { driver_speed: -law.driver_speed, flow: PowerFlow::FromDriven, preload: 0.03, ..law };
        for (inertia, weight, direction) in [
            (false, 0.7, Direction::Clockwise),
            (true, 0.7, Direction::Clockwise),
            (true, 0.0, Direction::Clockwise),
            (true, 0.7, Direction::CounterClockwise),
        ] {
            let law = ScaledStringDrive::fixture(inertia, weight);
            let law = if direction == Direction::Clockwise { law } else { ccw(law) };
            let pb = BeltProblem::new(Topology::two_pulley_running(ContactModel::Coulomb, direction), law);
            assert_eq!(pb.n_bc(), 44);
            let p = [0.4, 0.6, 0.5, 0.45, 1.7, 0.3, -1.4, -1.8, -3.9, -4.6, 0.3 * direction.sign(), 0.8];
            for eta in [0.2, 0.4, 0.6, 0.9] {
                let worst = ad_fd_mismatch_sampled(&pb, &p, eta);
                assert!(worst <= 1e-6, "inertia {inertia}, eta {eta}: AD vs central differences {worst:e}");
            }
        }
    }
}
