//! The eight-segment BVP of `docs/string-drive.md`, in scaled variables.
//!
//! Lengths are scaled by the centre distance H, forces by F_ref, speeds by
//! V = √(F_ref/ρ) (so ρc²/F_ref = c̃²), angular speeds by V/H, torques by F_ref·H.
//! Segment order, states, parameters and conditions are the tables of the note.

use std::f64::consts::PI;

use crate::problem::{Problem, Scalar};

/// Upper (slack) span from the driver to x = 0.
pub const UPPER_LEFT: usize = 0;
/// Upper span from x = 0 to the driven pulley.
pub const UPPER_RIGHT: usize = 1;
/// Stick zone on the driven pulley (entered slack).
pub const DRIVEN_STICK: usize = 2;
/// Slip zone on the driven pulley.
pub const DRIVEN_SLIP: usize = 3;
/// Lower (tight) span from the driven pulley to x = 0.
pub const LOWER_RIGHT: usize = 4;
/// Lower span from x = 0 to the driver.
pub const LOWER_LEFT: usize = 5;
/// Stick zone on the driver (entered tight).
pub const DRIVER_STICK: usize = 6;
/// Slip zone on the driver.
pub const DRIVER_SLIP: usize = 7;

/// True for the four free-span segments.
pub fn is_span(k: usize) -> bool {
    matches!(k, UPPER_LEFT | UPPER_RIGHT | LOWER_RIGHT | LOWER_LEFT)
}

/// True for the driver's arc segments.
pub fn on_driver(k: usize) -> bool {
    matches!(k, DRIVER_STICK | DRIVER_SLIP)
}

/// True for the slip segments.
pub fn is_slip(k: usize) -> bool {
    matches!(k, DRIVEN_SLIP | DRIVER_SLIP)
}

/// The side of the loop of each segment, in segment order (for the σ map).
pub const SIDES: [crate::sigma_map::Side; 8] = {
    use crate::sigma_map::Side::{Arc, LowerSpan, UpperSpan};
    [UpperSpan, UpperSpan, Arc, Arc, LowerSpan, LowerSpan, Arc, Arc]
};
/// Span state (x, y, F̃_x, F̃_y, s); arc state (T̃, s, m).
pub const SPAN_DIM: usize = 5;
/// Arc state dimension.
pub const ARC_DIM: usize = 3;

/// Span lengths ℓ₀, ℓ₁, ℓ₄, ℓ₅ (scaled, unstretched) of segments 0, 1, 4, 5.
pub const P_LEN: [usize; 4] = [0, 1, 2, 3];
/// First contact on the driven pulley.
pub const P_PHI2A: usize = 4;
/// Stick → slip on the driven pulley.
pub const P_PHI2T: usize = 5;
/// Last contact on the driven pulley.
pub const P_PHI2B: usize = 6;
/// First contact on the driver.
pub const P_PHI1A: usize = 7;
/// Stick → slip on the driver.
pub const P_PHI1T: usize = 8;
/// Last contact on the driver.
pub const P_PHI1B: usize = 9;
/// Transport rate c̃.
pub const P_C: usize = 10;
/// Driven speed ω̃₂.
pub const P_OMEGA2: usize = 11;
/// Number of parameters.
pub const N_PARAMS: usize = 12;

/// Parameter index of the span length of span segment `k`.
pub fn span_len_index(k: usize) -> usize {
    match k {
        UPPER_LEFT => P_LEN[0],
        UPPER_RIGHT => P_LEN[1],
        LOWER_RIGHT => P_LEN[2],
        LOWER_LEFT => P_LEN[3],
        _ => unreachable!("segment {k} is not a span"),
    }
}

/// (start, end) angle parameter indices of arc segment `k`.
pub fn arc_params(k: usize) -> (usize, usize) {
    match k {
        DRIVEN_STICK => (P_PHI2A, P_PHI2T),
        DRIVEN_SLIP => (P_PHI2T, P_PHI2B),
        DRIVER_STICK => (P_PHI1A, P_PHI1T),
        DRIVER_SLIP => (P_PHI1T, P_PHI1B),
        _ => unreachable!("segment {k} is not an arc"),
    }
}

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

    /// Pulley centre x (scaled): driver −½, driven +½.
    pub fn centre_x(driver: bool) -> f64 {
        if driver { -0.5 } else { 0.5 }
    }

    /// Slip sign κ of (D6): +1 on the driver, −1 on the driven pulley.
    pub fn slip_sign(k: usize) -> f64 {
        if on_driver(k) { 1.0 } else { -1.0 }
    }

    /// The tight, weightless loop at rest with length L₀ (the exact η = 0 solution).
    pub fn tight_tension(&self) -> f64 {
        self.axial_stiffness * ((2.0 + 2.0 * PI * self.radius) / self.length_start - 1.0)
    }
}

fn norm<D: Scalar>(fx: D, fy: D) -> D {
    (fx * fx + fy * fy).sqrt()
}

impl Problem for ScaledStringDrive {
    fn n_segments(&self) -> usize {
        8
    }

    fn dim(&self, k: usize) -> usize {
        if is_span(k) { SPAN_DIM } else { ARC_DIM }
    }

    fn n_params(&self) -> usize {
        N_PARAMS
    }

    fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        let w = self.weight_at(eta);
        let c = p[P_C];
        if is_span(k) {
            // (D3) times the span length ℓ.
            let l = p[span_len_index(k)];
            let t = norm(y[2], y[3]);
            let stretch = self.stretch(t, c);
            f[0] = l * stretch * y[2] / t;
            f[1] = l * stretch * y[3] / t;
            f[2] = D::from(0.0);
            f[3] = if self.weight != 0.0 { l * w } else { D::from(0.0) };
            f[4] = l;
        } else {
            // (D6), (D7) times Δφ.
            let (pa, pb) = arc_params(k);
            let dphi = p[pb] - p[pa];
            let phi = p[pa] + dphi * x;
            let t = y[0];
            let stretch = self.stretch(t, c);
            let r = self.radius;
            let ds = -(stretch.recip()) * r;
            // Gravity terms only when the scene has gravity (weight ≠ 0).
            let gravity = self.weight != 0.0;
            let dt = if is_slip(k) {
                let mut pressure = t * stretch / r;
                if gravity {
                    pressure += w * phi.sin();
                }
                let mut dt = pressure * (Self::slip_sign(k) * self.friction);
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
    }

    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
        let rad = self.radius;
        let mut i = 0;
        let mut push = |v: D| {
            r[i] = v;
            i += 1;
        };
        let on = |driver: bool, phi: D| -> (D, D) { (phi.cos() * rad + Self::centre_x(driver), phi.sin() * rad) };
        let tangent = |phi: D| -> (D, D) { (phi.sin(), -phi.cos()) };
        let c = p[P_C];

        // Start of 0: leaves the driver at φ₁_b with the effective tension of the slip end.
        let phi = p[P_PHI1B];
        let (px, py) = on(true, phi);
        let (tx, ty) = tangent(phi);
        let s0 = ya[UPPER_LEFT];
        let t7 = yb[DRIVER_SLIP][0];
        push(s0[0] - px);
        push(s0[1] - py);
        push(s0[2] - t7 * tx);
        push(s0[3] - t7 * ty);
        push(s0[4]);
        // 0 → 1 at x = 0.
        push(yb[UPPER_LEFT][0]);
        for j in 0..SPAN_DIM {
            push(ya[UPPER_RIGHT][j] - yb[UPPER_LEFT][j]);
        }
        // End of 1: meets the driven pulley at φ₂ₐ, tangentially.
        let phi = p[P_PHI2A];
        let (px, py) = on(false, phi);
        let e1 = yb[UPPER_RIGHT];
        push(e1[0] - px);
        push(e1[1] - py);
        push(e1[2] * phi.cos() + e1[3] * phi.sin());
        push(ya[DRIVEN_STICK][0] - norm(e1[2], e1[3]));
        push(ya[DRIVEN_STICK][1] - e1[4]);
        push(ya[DRIVEN_STICK][2]);
        // Driven stick → slip.
        for j in 0..ARC_DIM {
            push(ya[DRIVEN_SLIP][j] - yb[DRIVEN_STICK][j]);
        }
        // Start of 4: leaves the driven pulley at φ₂_b.
        let phi = p[P_PHI2B];
        let (px, py) = on(false, phi);
        let (tx, ty) = tangent(phi);
        let s4 = ya[LOWER_RIGHT];
        let t3 = yb[DRIVEN_SLIP][0];
        push(s4[0] - px);
        push(s4[1] - py);
        push(s4[2] - t3 * tx);
        push(s4[3] - t3 * ty);
        push(s4[4] - yb[DRIVEN_SLIP][1]);
        // 4 → 5 at x = 0.
        push(yb[LOWER_RIGHT][0]);
        for j in 0..SPAN_DIM {
            push(ya[LOWER_LEFT][j] - yb[LOWER_RIGHT][j]);
        }
        // End of 5: meets the driver at φ₁ₐ.
        let phi = p[P_PHI1A];
        let (px, py) = on(true, phi);
        let e5 = yb[LOWER_LEFT];
        push(e5[0] - px);
        push(e5[1] - py);
        push(e5[2] * phi.cos() + e5[3] * phi.sin());
        push(ya[DRIVER_STICK][0] - norm(e5[2], e5[3]));
        push(ya[DRIVER_STICK][1] - e5[4]);
        push(ya[DRIVER_STICK][2]);
        // Driver stick → slip.
        for j in 0..ARC_DIM {
            push(ya[DRIVER_SLIP][j] - yb[DRIVER_STICK][j]);
        }
        // Total unstretched length.
        push(yb[DRIVER_SLIP][1] - self.length_at(eta));
        // (D5): kinematics of the two stick zones.
        push(c * self.stretch(ya[DRIVER_STICK][0], c) - self.speed_at(eta) * rad);
        push(p[P_OMEGA2] * rad - c * self.stretch(ya[DRIVEN_STICK][0], c));
        // (D8): torque balance of the driven pulley.
        push(yb[DRIVEN_SLIP][2] - (p[P_OMEGA2] * self.damping + self.torque) * self.torque_factor(eta));
        debug_assert_eq!(i, 44);
    }

    fn component_names(&self, k: usize) -> Vec<String> {
        let names: &[&str] = if is_span(k) { &["x", "y", "Fe_x", "Fe_y", "s"] } else { &["Te", "s", "m"] };
        names.iter().map(|s| s.to_string()).collect()
    }

    fn param_names(&self) -> Vec<String> {
        ["l0", "l1", "l4", "l5", "phi2a", "phi2t", "phi2b", "phi1a", "phi1t", "phi1b", "c", "omega2"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jacobian::ad_fd_mismatch;

    /// AD Jacobians of (D3), (D6), (D7) and the 44 conditions agree with central
    /// differences at an arbitrary state, in each homotopy phase, with and without
    /// inertia and gravity; 1e-6 relative is the accuracy of h ~ ε^{1/3} differences.
    #[test]
    fn ad_jacobians_match_finite_differences() {
        for (inertia, weight) in [(false, 0.7), (true, 0.7), (true, 0.0)] {
            let pb = ScaledStringDrive {
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
            };
            let p = [0.4, 0.6, 0.5, 0.45, 1.7, 0.3, -1.4, -1.8, -3.9, -4.6, 0.3, 0.8];
            let ys: Vec<Vec<f64>> =
                (0..8).map(|k| (0..pb.dim(k)).map(|i| 0.3 + 0.17 * i as f64 - 0.03 * k as f64).collect()).collect();
            let ends: Vec<Vec<f64>> = (0..16).map(|j| (0..pb.dim(j / 2)).map(|i| 0.2 + 0.1 * (i + j) as f64).collect()).collect();
            let ya: Vec<&[f64]> = (0..8).map(|k| ends[2 * k].as_slice()).collect();
            let yb: Vec<&[f64]> = (0..8).map(|k| ends[2 * k + 1].as_slice()).collect();
            for eta in [0.2, 0.4, 0.6, 0.9] {
                let worst = ad_fd_mismatch(&pb, 0.37, &ys, &ya, &yb, &p, eta);
                assert!(worst <= 1e-6, "inertia {inertia}, eta {eta}: AD vs central differences {worst:e}");
            }
        }
    }
}
