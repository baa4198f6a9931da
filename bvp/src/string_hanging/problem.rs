//! The six-segment BVP of `docs/string-hanging.md`, in scaled variables.
//!
//! Lengths are scaled by the centre distance H, forces by `force_scale`. Segment order,
//! states, parameters and conditions are exactly the tables of the note.

use crate::problem::{Problem, Scalar};

/// Segment indices (direction of σ).
pub const UPPER_LEFT: usize = 0;
/// Upper span from x = 0 to the driven pulley.
pub const UPPER_RIGHT: usize = 1;
/// Contact arc on the driven (right) pulley.
pub const DRIVEN_ARC: usize = 2;
/// Lower span from the driven pulley to x = 0.
pub const LOWER_RIGHT: usize = 3;
/// Lower span from x = 0 to the driver pulley.
pub const LOWER_LEFT: usize = 4;
/// Contact arc on the driver (left) pulley.
pub const DRIVER_ARC: usize = 5;

/// True for the four free-span segments.
pub fn is_span(k: usize) -> bool {
    !matches!(k, DRIVEN_ARC | DRIVER_ARC)
}

/// The side of the loop of each segment, in segment order (for the σ map).
pub const SIDES: [crate::sigma_map::Side; 6] = {
    use crate::sigma_map::Side::{Arc, LowerSpan, UpperSpan};
    [UpperSpan, UpperSpan, Arc, LowerSpan, LowerSpan, Arc]
};
/// Span state layout: (x, y, F_x, F_y, s).
pub const SPAN_DIM: usize = 5;
/// Arc state layout: (T, s).
pub const ARC_DIM: usize = 2;

/// Parameter indices: span lengths ℓ₀, ℓ₁, ℓ₃, ℓ₄ (scaled, unstretched).
pub const P_LEN: [usize; 4] = [0, 1, 2, 3];
/// φ₂ₐ: first contact on the driven pulley.
pub const P_PHI2A: usize = 4;
/// φ₂_b: last contact on the driven pulley.
pub const P_PHI2B: usize = 5;
/// φ₁ₐ: first contact on the driver pulley.
pub const P_PHI1A: usize = 6;
/// φ₁_b: last contact on the driver pulley.
pub const P_PHI1B: usize = 7;
/// f: closure defect (tension jump at the driver's first contact; exactly 0).
pub const P_DEFECT: usize = 8;
/// Number of parameters.
pub const N_PARAMS: usize = 9;

/// Index into the parameter vector of the span length of span segment `k`.
pub fn span_len_index(k: usize) -> usize {
    match k {
        UPPER_LEFT => P_LEN[0],
        UPPER_RIGHT => P_LEN[1],
        LOWER_RIGHT => P_LEN[2],
        LOWER_LEFT => P_LEN[3],
        _ => unreachable!("segment {k} is not a span"),
    }
}

/// The scaled problem with the two-phase homotopy in η of the note: for η ∈ [0, ½] the
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

    /// Pulley centre x-coordinate (scaled): driver −½, driven +½.
    pub fn centre_x(driver: bool) -> f64 {
        if driver { -0.5 } else { 0.5 }
    }
}

fn tension<D: Scalar>(fx: D, fy: D) -> D {
    (fx * fx + fy * fy).sqrt()
}

impl Problem for ScaledStringHanging {
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
        let w = self.weight_at(eta);
        if is_span(k) {
            // (S2) times the span length ℓ.
            let l = p[span_len_index(k)];
            let t = tension(y[2], y[3]);
            let stretch = t / self.axial_stiffness + 1.0;
            f[0] = l * stretch * y[2] / t;
            f[1] = l * stretch * y[3] / t;
            f[2] = D::from(0.0);
            f[3] = l * w;
            f[4] = l;
        } else {
            // (S4) times Δφ = φ_b − φ_a.
            let (pa, pb) = if k == DRIVEN_ARC { (P_PHI2A, P_PHI2B) } else { (P_PHI1A, P_PHI1B) };
            let dphi = p[pb] - p[pa];
            let phi = p[pa] + dphi * x;
            let stretch = y[0] / self.axial_stiffness + 1.0;
            f[0] = dphi * w * self.radius * phi.cos() / stretch;
            f[1] = -dphi * self.radius / stretch;
        }
    }

    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
        let rad = self.radius;
        let mut i = 0;
        let mut push = |v: D| {
            r[i] = v;
            i += 1;
        };
        // Point on a pulley and the clockwise tangent there.
        let on = |driver: bool, phi: D| -> (D, D) {
            (phi.cos() * rad + Self::centre_x(driver), phi.sin() * rad)
        };
        let tangent = |phi: D| -> (D, D) { (phi.sin(), -phi.cos()) };

        // Start of 0: leaves the driver at φ₁_b.
        let phi = p[P_PHI1B];
        let (px, py) = on(true, phi);
        let (tx, ty) = tangent(phi);
        let s0 = ya[UPPER_LEFT];
        let t5 = yb[DRIVER_ARC][0];
        push(s0[0] - px);
        push(s0[1] - py);
        push(s0[2] - t5 * tx);
        push(s0[3] - t5 * ty);
        push(s0[4]);
        // 0 → 1 at x = 0.
        push(yb[UPPER_LEFT][0]);
        for c in 0..SPAN_DIM {
            push(ya[UPPER_RIGHT][c] - yb[UPPER_LEFT][c]);
        }
        // End of 1: meets the driven pulley at φ₂ₐ.
        let phi = p[P_PHI2A];
        let (px, py) = on(false, phi);
        let e1 = yb[UPPER_RIGHT];
        push(e1[0] - px);
        push(e1[1] - py);
        push(e1[2] * phi.cos() + e1[3] * phi.sin());
        push(ya[DRIVEN_ARC][0] - tension(e1[2], e1[3]));
        push(ya[DRIVEN_ARC][1] - e1[4]);
        // Start of 3: leaves the driven pulley at φ₂_b.
        let phi = p[P_PHI2B];
        let (px, py) = on(false, phi);
        let (tx, ty) = tangent(phi);
        let s3 = ya[LOWER_RIGHT];
        let t2 = yb[DRIVEN_ARC][0];
        push(s3[0] - px);
        push(s3[1] - py);
        push(s3[2] - t2 * tx);
        push(s3[3] - t2 * ty);
        push(s3[4] - yb[DRIVEN_ARC][1]);
        // 3 → 4 at x = 0.
        push(yb[LOWER_RIGHT][0]);
        for c in 0..SPAN_DIM {
            push(ya[LOWER_LEFT][c] - yb[LOWER_RIGHT][c]);
        }
        // End of 4: meets the driver at φ₁ₐ, with the closure defect f.
        let phi = p[P_PHI1A];
        let (px, py) = on(true, phi);
        let e4 = yb[LOWER_LEFT];
        push(e4[0] - px);
        push(e4[1] - py);
        push(e4[2] * phi.cos() + e4[3] * phi.sin());
        push(ya[DRIVER_ARC][0] - tension(e4[2], e4[3]) - p[P_DEFECT]);
        push(ya[DRIVER_ARC][1] - e4[4]);
        // End of 5: total unstretched length.
        push(yb[DRIVER_ARC][1] - self.length_at(eta));
        debug_assert_eq!(i, 33);
    }

    fn component_names(&self, k: usize) -> Vec<String> {
        let names: &[&str] = if is_span(k) { &["x", "y", "F_x", "F_y", "s"] } else { &["T", "s"] };
        names.iter().map(|s| s.to_string()).collect()
    }

    fn param_names(&self) -> Vec<String> {
        ["l0", "l1", "l3", "l4", "phi2a", "phi2b", "phi1a", "phi1b", "defect"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jacobian::ad_fd_mismatch;

    fn problem() -> ScaledStringHanging {
        ScaledStringHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length_start: 3.0, length: 3.2 }
    }

    /// AD Jacobians of (S2), (S4) and the conditions agree with central differences
    /// at an arbitrary state; 1e-6 relative is the accuracy of h ~ ε^{1/3} differences.
    #[test]
    fn ad_jacobians_match_finite_differences() {
        let pb = problem();
        let p = [0.4, 0.6, 0.5, 0.45, 1.7, -1.4, -1.8, -4.6, 0.01];
        let ys: Vec<Vec<f64>> = (0..6).map(|k| (0..pb.dim(k)).map(|i| 0.3 + 0.17 * i as f64 - 0.05 * k as f64).collect()).collect();
        let ends: Vec<Vec<f64>> = (0..12).map(|j| (0..pb.dim(j / 2)).map(|i| 0.2 + 0.1 * (i + j) as f64).collect()).collect();
        let ya: Vec<&[f64]> = (0..6).map(|k| ends[2 * k].as_slice()).collect();
        let yb: Vec<&[f64]> = (0..6).map(|k| ends[2 * k + 1].as_slice()).collect();
        let worst = ad_fd_mismatch(&pb, 0.37, &ys, &ya, &yb, &p, 0.8);
        assert!(worst <= 1e-6, "AD vs central differences: {worst:e}");
    }
}
