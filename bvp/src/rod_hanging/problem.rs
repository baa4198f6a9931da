//! The six-segment BVP of `docs/rod-hanging.md`, in scaled variables.
//!
//! Lengths are scaled by the centre distance H, forces by `F_ref` (the string's force
//! scale), moments by F_ref·H, so the bending stiffness is EI/(F_ref H²). Segment order,
//! parameters and conditions are the table (41 unknowns) of the note; the segment and
//! parameter indices are those of [`crate::string_hanging::problem`].
//!
//! One convention is fixed here that the note leaves implicit: θ is unwrapped so that it
//! is continuous along the free spans (upper spans θ ≈ 0, lower spans θ ≈ −π). With
//! φ₁_b ∈ (−2π, −π) the condition "θ = φ₁_b − π/2" at the start of segment 0 is taken
//! modulo 2π, as θ = φ₁_b − π/2 + 2π; the other three contact conditions are as written.

use std::f64::consts::{FRAC_PI_2, PI};

use crate::problem::{Problem, Scalar};
pub use crate::string_hanging::problem::{
    is_span, span_len_index, DRIVEN_ARC, DRIVER_ARC, LOWER_LEFT, LOWER_RIGHT, N_PARAMS, P_DEFECT, P_LEN, P_PHI1A,
    P_PHI1B, P_PHI2A, P_PHI2B, UPPER_LEFT, UPPER_RIGHT,
};

/// Span state layout: (x, y, θ, M, Q_x, Q_y, s).
pub const SPAN_DIM: usize = 7;
/// Arc state layout: (N, s).
pub const ARC_DIM: usize = 2;

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

    /// Pulley centre x-coordinate (scaled): driver −½, driven +½.
    pub fn centre_x(driver: bool) -> f64 {
        if driver { -0.5 } else { 0.5 }
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

impl Problem for ScaledRodHanging {
    fn n_segments(&self) -> usize {
        6
    }

    fn dim(&self, k: usize) -> usize {
        if is_span(k) { SPAN_DIM } else { ARC_DIM }
    }

    fn n_params(&self) -> usize {
        N_PARAMS
    }

    fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        let ei = self.bending_at(eta);
        if is_span(k) {
            // (R2) times the span length ℓ.
            let l = p[span_len_index(k)];
            let (n, v) = span_nv(y);
            let lambda = n / self.axial_stiffness + 1.0;
            f[0] = l * lambda * y[2].cos();
            f[1] = l * lambda * y[2].sin();
            f[2] = l * y[3] / ei;
            f[3] = -l * lambda * v;
            f[4] = D::from(0.0);
            f[5] = l * self.weight;
            f[6] = l;
        } else {
            // (R4) with φ as variable, ds/dφ = −R/λ, times Δφ = φ_b − φ_a.
            let (pa, pb) = if k == DRIVEN_ARC { (P_PHI2A, P_PHI2B) } else { (P_PHI1A, P_PHI1B) };
            let dphi = p[pb] - p[pa];
            let phi = p[pa] + dphi * x;
            let lambda = y[0] / self.axial_stiffness + 1.0;
            let ds = -dphi * self.radius / lambda;
            f[0] = ds * self.arc_dn(ei, phi);
            f[1] = ds;
        }
    }

    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
        let rad = self.radius;
        let ea = self.axial_stiffness;
        let ei = self.bending_at(eta);
        let mut i = 0;
        let mut push = |v: D| {
            r[i] = v;
            i += 1;
        };
        let on = |driver: bool, phi: D| -> (D, D) { (phi.cos() * rad + Self::centre_x(driver), phi.sin() * rad) };
        // M = −EI λ(N) / R on the pulley.
        let moment = |n: D| -> D { -ei * (n / ea + 1.0) / rad };

        // Start of 0: leaves the driver at φ₁_b (θ unwrapped by +2π, see module doc).
        let phi = p[P_PHI1B];
        let (px, py) = on(true, phi);
        let s0 = ya[UPPER_LEFT];
        let n5 = yb[DRIVER_ARC][0];
        push(s0[0] - px);
        push(s0[1] - py);
        push(s0[2] - (phi + (2.0 * PI - FRAC_PI_2)));
        push(s0[3] - moment(n5));
        push(span_nv(s0).0 - n5);
        push(s0[6]);
        // 0 → 1 at x = 0.
        push(yb[UPPER_LEFT][0]);
        for c in 0..SPAN_DIM {
            push(ya[UPPER_RIGHT][c] - yb[UPPER_LEFT][c]);
        }
        // End of 1: meets the driven pulley at φ₂ₐ.
        let phi = p[P_PHI2A];
        let (px, py) = on(false, phi);
        let e1 = yb[UPPER_RIGHT];
        let n1 = span_nv(e1).0;
        push(e1[0] - px);
        push(e1[1] - py);
        push(e1[2] - (phi - FRAC_PI_2));
        push(e1[3] - moment(n1));
        push(ya[DRIVEN_ARC][0] - n1);
        push(ya[DRIVEN_ARC][1] - e1[6]);
        // Start of 3: leaves the driven pulley at φ₂_b.
        let phi = p[P_PHI2B];
        let (px, py) = on(false, phi);
        let s3 = ya[LOWER_RIGHT];
        let n2 = yb[DRIVEN_ARC][0];
        push(s3[0] - px);
        push(s3[1] - py);
        push(s3[2] - (phi - FRAC_PI_2));
        push(s3[3] - moment(n2));
        push(span_nv(s3).0 - n2);
        push(s3[6] - yb[DRIVEN_ARC][1]);
        // 3 → 4 at x = 0.
        push(yb[LOWER_RIGHT][0]);
        for c in 0..SPAN_DIM {
            push(ya[LOWER_LEFT][c] - yb[LOWER_RIGHT][c]);
        }
        // End of 4: meets the driver at φ₁ₐ, with the closure defect f.
        let phi = p[P_PHI1A];
        let (px, py) = on(true, phi);
        let e4 = yb[LOWER_LEFT];
        let n4 = span_nv(e4).0;
        push(e4[0] - px);
        push(e4[1] - py);
        push(e4[2] - (phi - FRAC_PI_2));
        push(e4[3] - moment(n4));
        push(ya[DRIVER_ARC][0] - n4 - p[P_DEFECT]);
        push(ya[DRIVER_ARC][1] - e4[6]);
        // End of 5: total unstretched length.
        push(yb[DRIVER_ARC][1] - self.length);
        debug_assert_eq!(i, 41);
    }

    fn component_names(&self, k: usize) -> Vec<String> {
        let names: &[&str] = if is_span(k) { &["x", "y", "theta", "M", "Q_x", "Q_y", "s"] } else { &["N", "s"] };
        names.iter().map(|s| s.to_string()).collect()
    }

    fn param_names(&self) -> Vec<String> {
        ["l0", "l1", "l3", "l4", "phi2a", "phi2b", "phi1a", "phi1b", "defect"].iter().map(|s| s.to_string()).collect()
    }
}

// The AD-vs-finite-difference check of this problem is bvp/tests/rod_hanging.rs (a).
