//! The section law of the extensible string at rest (docs/string-hanging.md), in scaled
//! variables: lengths by the centre distance H, forces by F_ref.
//!
//! Span state (x, y, F_x, F_y, s) in the unstretched arc length s, (S2); frictionless arc
//! state (T, s) in the polar angle φ, (S4). At a contact start the span meets the pulley
//! tangentially and the tension carries over (plus the closure jump f at the driver's
//! first contact); at a contact end the span force is T times the pulley tangent.

use crate::belt::balance;
use crate::belt::law::{BeltPoint, Rows, Scales, SectionLaw};
use crate::belt::solution::{BeltSolution, TightLoop};
use crate::belt::topology::{ArcKind, Pulley, SegmentKind, Topology};
use crate::belt::BeltError;
use crate::problem::Scalar;

use super::StringHanging;

/// The scaled string with the two-phase homotopy in η of the note: for η ∈ [0, ½] the
/// weight is switched on at the tight length, w(η) = 2η w, L(η) = L₀; for η ∈ [½, 1] the
/// belt is lengthened under its full weight, L(η) = L₀ + (2η − 1)(L − L₀).
#[derive(Debug, Clone)]
pub struct ScaledStringHanging {
    /// R / H.
    pub radius: f64,
    /// EA / F_ref.
    pub axial_stiffness: f64,
    /// ρ g H / F_ref at full gravity (η ≥ ½).
    pub weight: f64,
    /// L₀ / H: unstretched length for η ≤ ½.
    pub length_start: f64,
    /// L / H: the scene's unstretched length (η = 1).
    pub length: f64,
}

impl ScaledStringHanging {
    /// Weight per unstretched length at homotopy parameter η.
    pub fn weight_at<D: Scalar>(&self, eta: D) -> D {
        if eta.re() < 0.5 { eta * (2.0 * self.weight) } else { D::from(self.weight) }
    }

    /// Unstretched loop length at homotopy parameter η.
    pub fn length_at<D: Scalar>(&self, eta: D) -> D {
        if eta.re() <= 0.5 {
            D::from(self.length_start)
        } else {
            (eta * 2.0 - 1.0) * (self.length - self.length_start) + self.length_start
        }
    }
}

/// |F| of a span force.
pub(crate) fn norm<D: Scalar>(fx: D, fy: D) -> D {
    (fx * fx + fy * fy).sqrt()
}

/// Point on `pulley` (scaled radius `rad`) at polar angle φ.
pub(crate) fn on_pulley<D: Scalar>(rad: f64, pulley: Pulley, phi: D) -> (D, D) {
    (phi.cos() * rad + pulley.centre_x(), phi.sin() * rad)
}

/// A string span (x, y, F_x, F_y, s) meets `pulley` at φ: on the circle, tangential,
/// tension carried over to arc state 0 (minus the closure jump), s continuous.
#[allow(clippy::too_many_arguments)]
pub(crate) fn string_contact_start<D: Scalar>(rad: f64, pulley: Pulley, phi: D, e: &[D], arc: &[D], jump: Option<D>, rows: &mut Rows<D>) {
    let (px, py) = on_pulley(rad, pulley, phi);
    rows.push(e[0] - px);
    rows.push(e[1] - py);
    rows.push(e[2] * phi.cos() + e[3] * phi.sin());
    let carried = arc[0] - norm(e[2], e[3]);
    rows.push(match jump {
        Some(f) => carried - f,
        None => carried,
    });
    rows.push(arc[1] - e[4]);
}

/// A string span starts where the belt leaves `pulley` at φ: on the circle, span force
/// = arc state 0 times the clockwise tangent, s continuous (0 where the loop closes).
pub(crate) fn string_contact_end<D: Scalar>(rad: f64, pulley: Pulley, phi: D, arc_end: &[D], s: &[D], closes_loop: bool, rows: &mut Rows<D>) {
    let (px, py) = on_pulley(rad, pulley, phi);
    let (tx, ty) = (phi.sin(), -phi.cos());
    let t = arc_end[0];
    rows.push(s[0] - px);
    rows.push(s[1] - py);
    rows.push(s[2] - t * tx);
    rows.push(s[3] - t * ty);
    rows.push(if closes_loop { s[4] } else { s[4] - arc_end[1] });
}

impl SectionLaw for ScaledStringHanging {
    type Data = StringHanging;
    type Start = ();

    const SPAN_STATES: &'static [&'static str] = &["x", "y", "F_x", "F_y", "s"];
    const ARC_STATES: &'static [&'static str] = &["T", "s"];

    /// The static string reads no parameter besides its own span length or arc angles.
    fn rhs_reads(&self, _: &Topology) -> Vec<usize> {
        Vec::new()
    }

    fn span_rhs<D: Scalar>(&self, _: &Topology, l: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (S2) times the span length ℓ.
        let w = self.weight_at(eta);
        let t = norm(y[2], y[3]);
        let stretch = t / self.axial_stiffness + 1.0;
        f[0] = l * stretch * y[2] / t;
        f[1] = l * stretch * y[3] / t;
        f[2] = D::from(0.0);
        f[3] = l * w;
        f[4] = l;
    }

    fn arc_rhs<D: Scalar>(&self, _: &Topology, _: ArcKind, _: Pulley, phi: D, dphi: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (S4) times Δφ = φ_b − φ_a.
        let w = self.weight_at(eta);
        let stretch = y[0] / self.axial_stiffness + 1.0;
        f[0] = dphi * w * self.radius * phi.cos() / stretch;
        f[1] = -dphi * self.radius / stretch;
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], jump: Option<D>, _: &[D], _: D, rows: &mut Rows<D>) {
        string_contact_start(self.radius, pulley, phi, e, arc, jump, rows);
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], s: &[D], closes_loop: bool, _: &[D], _: D, rows: &mut Rows<D>) {
        string_contact_end(self.radius, pulley, phi, arc_end, s, closes_loop, rows);
    }

    fn loop_conditions<D: Scalar>(&self, topology: &Topology, _: &[&[D]], yb: &[&[D]], _: &[D], eta: D, rows: &mut Rows<D>) {
        // Total unstretched length.
        rows.push(yb[topology.len() - 1][1] - self.length_at(eta));
    }

    fn point(&self, d: &StringHanging, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], _: &[f64]) -> BeltPoint {
        let (lh, fr) = (sc.length, sc.force);
        let at_rest = |x: f64, yy: f64, theta: f64, tension: f64, material: f64| {
            BeltPoint::new(x, yy, theta, tension, 1.0 + tension / d.axial_stiffness, material)
        };
        match (topology.segment(k).pulley(), phi) {
            (Some(pulley), Some(phi)) => {
                let cx = pulley.centre_x() * lh;
                let tension = y[0] * fr;
                let mut pt = at_rest(cx + d.radius * phi.cos(), d.radius * phi.sin(), phi - std::f64::consts::FRAC_PI_2, tension, y[1] * lh);
                pt.pressure = Some(tension * pt.stretch / d.radius + d.mass_per_length * d.gravity * phi.sin());
                pt.angle = Some(phi);
                pt
            }
            _ => at_rest(y[0] * lh, y[1] * lh, y[3].atan2(y[2]), y[2].hypot(y[3]) * fr, y[4] * lh),
        }
    }

    fn first_integral(d: &StringHanging, pt: &BeltPoint) -> Option<f64> {
        // E = T + T²/(2EA) − ρ g y (S6).
        Some(pt.tension + pt.tension * pt.tension / (2.0 * d.axial_stiffness) - d.mass_per_length * d.gravity * pt.y)
    }

    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        balance::check_loop_closure(sol, sol.data.length)
    }

    fn admissible_window(&self) -> (f64, f64) {
        // Each contact angle within a quarter turn of its tight-contour value, so each
        // contact arc lies in (0, 2π) and no span winds an extra turn round a pulley.
        (std::f64::consts::FRAC_PI_2, 0.0)
    }

    fn arc_force_name(&self) -> &'static str {
        "tension"
    }

    fn positive_force(_: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        Some(("tension", pt.tension))
    }
}

impl TightLoop for ScaledStringHanging {
    fn tight_state(&self, kind: SegmentKind, position: [f64; 2], force: [f64; 2], tension: f64, material: f64) -> Vec<f64> {
        match kind {
            SegmentKind::Span => vec![position[0], position[1], force[0], force[1], material],
            SegmentKind::Arc(_) => vec![tension, material],
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

    fn problem() -> BeltProblem<ScaledStringHanging> {
        let law = ScaledStringHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length_start: 3.0, length: 3.2 };
        BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), law)
    }

    /// AD Jacobians of (S2), (S4) and the 33 conditions agree with central differences
    /// at an arbitrary state; 1e-6 relative is the accuracy of h ~ ε^{1/3} differences.
    #[test]
    fn ad_jacobians_match_finite_differences() {
        let pb = problem();
        assert_eq!(pb.n_bc(), 33);
        let p = [0.4, 0.6, 0.5, 0.45, 1.7, -1.4, -1.8, -4.6, 0.01];
        for eta in [0.3, 0.8] {
            let worst = ad_fd_mismatch_sampled(&pb, &p, eta);
            assert!(worst <= 1e-6, "η = {eta}: AD vs central differences: {worst:e}");
        }
    }
}
