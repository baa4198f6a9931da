//! The six-segment BVP of `docs/rod-hanging.md`, in scaled variables.
//!
//! Lengths are scaled by the centre distance H, forces by `F_ref` (the string's force
//! scale), moments by F_ref·H, so the bending stiffness is EI/(F_ref H²). Segment order,
//! parameters and conditions are the table (41 unknowns) of the note; the segment and
//! parameter indices are those of the frictionless two-pulley [`Topology`].
//!
//! One convention is fixed here that the note leaves implicit: θ is unwrapped so that it
//! is continuous along the free spans (upper spans θ ≈ 0, lower spans θ ≈ −π). With
//! φ₁_b ∈ (−2π, −π) the condition "θ = φ₁_b − π/2" at the start of segment 0 is taken
//! modulo 2π, as θ = φ₁_b − π/2 + 2π; the other three contact conditions are as written.

use std::f64::consts::{FRAC_PI_2, PI};

use crate::belt::balance;
use crate::belt::law::{BeltPoint, Rows, Scales, SectionLaw};
use crate::belt::solution::BeltSolution;
use crate::belt::topology::{ArcKind, Pulley, SegmentKind, Topology};
use crate::belt::BeltError;
use crate::problem::Scalar;
use crate::string_hanging::law::on_pulley;
use crate::string_hanging::StringHangingSolution;

use super::RodHanging;

/// The scaled rod problem with the homotopy in η of the note: the bending stiffness is
/// interpolated in log, EI(η) = EI₀^(1−η) EI^η; everything else is the scene's.
#[derive(Debug, Clone)]
pub struct ScaledRodHanging {
    /// R / H.
    pub radius: f64,
    /// EA / F_ref.
    pub axial_stiffness: f64,
    /// ρ g H / F_ref.
    pub weight: f64,
    /// L / H.
    pub length: f64,
    /// EI₀ / (F_ref H²): bending stiffness at η = 0.
    pub bending_start: f64,
    /// EI / (F_ref H²): the scene's bending stiffness (η = 1).
    pub bending: f64,
}

impl ScaledRodHanging {
    /// Scaled bending stiffness at homotopy parameter η.
    pub fn bending_at<D: Scalar>(&self, eta: D) -> D {
        let (a, b) = (self.bending_start.ln(), self.bending.ln());
        (eta * (b - a) + a).exp()
    }

    /// The factor 1 + EI/(EA R²) of (R4).
    pub fn arc_factor<D: Scalar>(&self, ei: D) -> D {
        ei / (self.axial_stiffness * self.radius * self.radius) + 1.0
    }

    /// Scaled dN/ds on an arc at angle φ (R4).
    pub fn arc_dn<D: Scalar>(&self, ei: D, phi: D) -> D {
        -(phi.cos() * self.weight) / self.arc_factor(ei)
    }

    /// Scaled transverse force V on an arc (R3) at angle φ with axial force N.
    pub fn arc_v<D: Scalar>(&self, ei: D, phi: D, n: D) -> D {
        let lambda = n / self.axial_stiffness + 1.0;
        ei * self.arc_dn(ei, phi) / (lambda * (self.radius * self.axial_stiffness))
    }

    /// Scaled contact pressure p on an arc (R5), with V′ from (R3), (R4) differentiated.
    pub fn arc_pressure(&self, ei: f64, phi: f64, n: f64) -> f64 {
        let (r, ea, w) = (self.radius, self.axial_stiffness, self.weight);
        let lambda = 1.0 + n / ea;
        let c = self.arc_factor(ei);
        let dn = self.arc_dn(ei, phi);
        let dv = ei / (r * ea) * (-w * phi.sin() / (c * r) - dn * dn / (ea * lambda * lambda));
        lambda * n / r + w * phi.sin() - dv
    }
}

/// N = Q·t and V = Q·n of a span state.
pub fn span_nv<D: Scalar>(y: &[D]) -> (D, D) {
    let (c, s) = (y[2].cos(), y[2].sin());
    (y[4] * c + y[5] * s, y[5] * c - y[4] * s)
}

impl ScaledRodHanging {
    /// M = −EI λ(N) / R on the pulley.
    fn arc_moment<D: Scalar>(&self, ei: D, n: D) -> D {
        -ei * (n / self.axial_stiffness + 1.0) / self.radius
    }
}

/// M²/(2EI) + N + N²/(2EA): the bending and axial part of the rods' first integral
/// ((R7); the Cosserat rod's (CH5) adds Q²/(2b₂)), in N.
pub(crate) fn section_energy(moment: f64, axial_force: f64, bending_stiffness: f64, axial_stiffness: f64) -> f64 {
    moment * moment / (2.0 * bending_stiffness) + axial_force + axial_force * axial_force / (2.0 * axial_stiffness)
}

/// The rods' acceptance window (Kirchhoff and Cosserat). The string's window (a quarter
/// turn) is too narrow for a rod: a stiff rod on a slack loop leaves the pulleys earlier,
/// and its lower span can depart above the pulley's horizontal diameter (φ₂_b > 0,
/// heading downwards); whether such a state is physical is decided by the contact checks
/// (edge forces or pressures, p ≥ 0, no span through a pulley), not by this window.
/// Wraps must be positive.
pub(crate) const ROD_WINDOW: (f64, f64) = (PI, 0.0);

impl SectionLaw for ScaledRodHanging {
    type Data = RodHanging;
    type Start = StringHangingSolution;

    const SPAN_STATES: &'static [&'static str] = &["x", "y", "theta", "M", "Q_x", "Q_y", "s"];
    const ARC_STATES: &'static [&'static str] = &["N", "s"];

    /// No path in EI when the scene's bending layer is at least the start layer.
    fn starts_at_scene(&self) -> bool {
        self.bending_start == self.bending
    }

    /// The static rod reads no parameter besides its own span length or arc angles.
    fn rhs_reads(&self, _: &Topology) -> Vec<usize> {
        Vec::new()
    }

    fn span_rhs<D: Scalar>(&self, _: &Topology, l: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (R2) times the span length ℓ.
        let ei = self.bending_at(eta);
        let (n, v) = span_nv(y);
        let lambda = n / self.axial_stiffness + 1.0;
        f[0] = l * lambda * y[2].cos();
        f[1] = l * lambda * y[2].sin();
        f[2] = l * y[3] / ei;
        f[3] = -l * lambda * v;
        f[4] = D::from(0.0);
        f[5] = l * self.weight;
        f[6] = l;
    }

    fn arc_rhs<D: Scalar>(&self, _: &Topology, _: ArcKind, _: Pulley, phi: D, dphi: D, y: &[D], _: &[D], eta: D, f: &mut [D]) {
        // (R4) with φ as variable, ds/dφ = −R/λ, times Δφ = φ_b − φ_a.
        let ei = self.bending_at(eta);
        let lambda = y[0] / self.axial_stiffness + 1.0;
        let ds = -dphi * self.radius / lambda;
        f[0] = ds * self.arc_dn(ei, phi);
        f[1] = ds;
    }

    fn contact_start<D: Scalar>(&self, _: ArcKind, pulley: Pulley, phi: D, e: &[D], arc: &[D], jump: Option<D>, _: &[D], eta: D, rows: &mut Rows<D>) {
        // On the circle, tangential, M = −EIλ/R, N carried over (minus the closure jump).
        let ei = self.bending_at(eta);
        let (px, py) = on_pulley(self.radius, pulley, phi);
        let n = span_nv(e).0;
        rows.push(e[0] - px);
        rows.push(e[1] - py);
        rows.push(e[2] - (phi - FRAC_PI_2));
        rows.push(e[3] - self.arc_moment(ei, n));
        let carried = arc[0] - n;
        rows.push(match jump {
            Some(f) => carried - f,
            None => carried,
        });
        rows.push(arc[1] - e[6]);
    }

    fn contact_end<D: Scalar>(&self, pulley: Pulley, phi: D, arc_end: &[D], s: &[D], closes_loop: bool, _: &[D], eta: D, rows: &mut Rows<D>) {
        // Leaves the pulley at φ: on the circle, tangential (θ unwrapped by +2π where the
        // loop closes, see module doc), M = −EIλ/R, N continuous, s continuous.
        let ei = self.bending_at(eta);
        let (px, py) = on_pulley(self.radius, pulley, phi);
        let n = arc_end[0];
        rows.push(s[0] - px);
        rows.push(s[1] - py);
        rows.push(if closes_loop { s[2] - (phi + (2.0 * PI - FRAC_PI_2)) } else { s[2] - (phi - FRAC_PI_2) });
        rows.push(s[3] - self.arc_moment(ei, n));
        rows.push(span_nv(s).0 - n);
        rows.push(if closes_loop { s[6] } else { s[6] - arc_end[1] });
    }

    fn loop_conditions<D: Scalar>(&self, topology: &Topology, _: &[&[D]], yb: &[&[D]], _: &[D], _: D, rows: &mut Rows<D>) {
        // Total unstretched length.
        rows.push(yb[topology.len() - 1][1] - self.length);
    }

    fn point(&self, d: &RodHanging, sc: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], _: &[f64]) -> BeltPoint {
        let (lh, fr) = (sc.length, sc.force);
        let rod = |x: f64, yy: f64, theta: f64, moment: f64, tension: f64, shear: f64, material: f64| BeltPoint {
            shear: Some(shear),
            moment: Some(moment),
            ..BeltPoint::new(x, yy, theta, tension, 1.0 + tension / d.axial_stiffness, material)
        };
        match (topology.segment(k).pulley(), phi) {
            (Some(pulley), Some(phi)) => {
                let ei = self.bending;
                let n = y[0];
                let lambda = 1.0 + n / self.axial_stiffness;
                let mut pt = rod(
                    (pulley.centre_x() + self.radius * phi.cos()) * lh,
                    self.radius * phi.sin() * lh,
                    phi - FRAC_PI_2,
                    -ei * lambda / self.radius * fr * lh,
                    n * fr,
                    self.arc_v(ei, phi, n) * fr,
                    y[1] * lh,
                );
                pt.pressure = Some(self.arc_pressure(ei, phi, n) * fr / lh);
                pt.angle = Some(phi);
                pt
            }
            _ => {
                let (n, v) = span_nv(y);
                rod(y[0] * lh, y[1] * lh, y[2], y[3] * fr * lh, n * fr, v * fr, y[6] * lh)
            }
        }
    }

    fn first_integral(d: &RodHanging, pt: &BeltPoint) -> Option<f64> {
        // (R7) E = M²/(2EI) + N + N²/(2EA) − ρ g y.
        Some(section_energy(pt.moment?, pt.tension, d.bending_stiffness, d.axial_stiffness) - d.mass_per_length * d.gravity * pt.y)
    }

    fn check_balance(sol: &BeltSolution<Self>) -> Result<(), BeltError> {
        balance::check_loop_closure(sol, sol.data.length)
    }

    fn admissible_window(&self) -> (f64, f64) {
        ROD_WINDOW
    }

    fn arc_force_name(&self) -> &'static str {
        "axial force"
    }

    fn positive_force(kind: SegmentKind, pt: &BeltPoint) -> Option<(&'static str, f64)> {
        (kind != SegmentKind::Span).then_some(("axial force", pt.tension))
    }
}

// The AD-vs-finite-difference check of this problem is bvp/tests/rod_hanging.rs (a).
