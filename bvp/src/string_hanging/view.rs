//! The common solution view of a `string-hanging` BVP solution: quantities at a contour
//! coordinate σ, and the summary.
//!
//! The BVP is parametrised by segment and ξ, not by σ. The belt point "at σ" is the one on
//! the contour normal at σ (the MEL description, eq. 27): σ(k, ξ) = σ of the inverse
//! contour map of the belt point, which increases monotonically along the loop. A table
//! of σ at dense samples brackets a query, and bisection on the dense output refines it.

use std::f64::consts::PI;

use drive::contour::Contour;
use drive::summary::{PulleySummary, Summary};
use drive::view::{ContactState, SolutionView};

use super::problem::{DRIVER_ARC, DRIVEN_ARC, LOWER_RIGHT, UPPER_LEFT};
use super::{BeltPoint, Scales, StringHanging, StringHangingSolution};
use crate::solution::Solution;

/// σ at dense samples along the loop, unwrapped to increase monotonically.
#[derive(Debug, Clone)]
pub(super) struct SigmaTable {
    contour: Contour,
    /// (segment, ξ, σ unwrapped).
    entries: Vec<(usize, f64, f64)>,
}

/// Wrap an angle to (−π, π].
fn wrap_angle(a: f64) -> f64 {
    let mut w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w -= 2.0 * PI;
    }
    w
}

impl SigmaTable {
    pub(super) fn new(data: &StringHanging, _problem: &super::ScaledStringHanging, scales: &Scales, solution: &Solution) -> Self {
        let contour = Contour::new(data.radius, data.centre_distance).expect("validated geometry");
        // A temporary solution object is not available yet; evaluate points directly.
        let total = contour.length();
        let mut entries = Vec::new();
        let mut last = f64::NEG_INFINITY;
        let mut offset = 0.0;
        for (k, seg) in solution.segments.iter().enumerate() {
            let mut xis: Vec<f64> = Vec::new();
            for w in seg.mesh.windows(2) {
                for j in 0..8 {
                    xis.push(w[0] + (w[1] - w[0]) * j as f64 / 8.0);
                }
            }
            xis.push(1.0);
            for xi in xis {
                let pt = point_of(data, scales, solution, k, xi);
                let (s, _) = contour.sigma_nu([pt.x, pt.y]);
                let mut su = s + offset;
                if last.is_finite() && su < last - 0.5 * total {
                    offset += total;
                    su += total;
                }
                last = su;
                entries.push((k, xi, su));
            }
        }
        Self { contour, entries }
    }

    /// Segment and ξ of the belt point at contour coordinate `sigma`.
    fn locate(&self, sol: &StringHangingSolution, sigma: f64) -> (usize, f64) {
        let total = self.contour.length();
        let first = self.entries[0].2;
        let s = first + (sigma - first).rem_euclid(total);
        let i = self.entries.partition_point(|e| e.2 <= s).clamp(1, self.entries.len() - 1);
        let (k0, x0, s0) = self.entries[i - 1];
        let (k1, x1, _) = self.entries[i];
        if k0 != k1 {
            // The bracket joins two segments at a shared point.
            return (k0, x0);
        }
        let sigma_at = |xi: f64| {
            let pt = sol.point(k0, xi);
            let (v, _) = self.contour.sigma_nu([pt.x, pt.y]);
            // Unwrap to the neighbourhood of the table entry.
            v + ((s0 - v) / total).round() * total
        };
        let (mut a, mut b) = (x0, x1);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if sigma_at(m) <= s {
                a = m;
            } else {
                b = m;
            }
            if b - a < 1e-15 {
                break;
            }
        }
        (k0, 0.5 * (a + b))
    }

    fn point(&self, sol: &StringHangingSolution, sigma: f64) -> (usize, BeltPoint) {
        let (k, xi) = self.locate(sol, sigma);
        (k, sol.point(k, xi))
    }
}

/// `StringHangingSolution::point` before the solution object exists.
fn point_of(data: &StringHanging, scales: &Scales, solution: &Solution, k: usize, xi: f64) -> BeltPoint {
    let seg = &solution.segments[k];
    let y = if xi >= 1.0 { seg.end().to_vec() } else { seg.eval(xi) };
    if super::problem::is_span(k) {
        BeltPoint { x: y[0] * scales.length, y: y[1] * scales.length, tension: 0.0, material: 0.0, pressure: None }
    } else {
        let p = &solution.params;
        let (pa, pb) = if k == DRIVEN_ARC {
            (p[super::problem::P_PHI2A], p[super::problem::P_PHI2B])
        } else {
            (p[super::problem::P_PHI1A], p[super::problem::P_PHI1B])
        };
        let phi = pa + xi * (pb - pa);
        let cx = if k == DRIVER_ARC { -0.5 } else { 0.5 } * data.centre_distance;
        BeltPoint { x: cx + data.radius * phi.cos(), y: data.radius * phi.sin(), tension: 0.0, material: 0.0, pressure: None }
    }
}

impl StringHangingSolution {
    fn pulley_summary(&self, driver: bool) -> PulleySummary {
        let (a, b) = self.contact_angles(driver);
        PulleySummary {
            contact_arc: Some(a - b),
            contact_start: Some(wrap_angle(a)),
            contact_end: Some(wrap_angle(b)),
            ..PulleySummary::default()
        }
    }
}

impl SolutionView for StringHangingSolution {
    fn contour(&self) -> &Contour {
        &self.sigma_table.contour
    }

    fn position(&self, sigma: f64) -> [f64; 2] {
        let (_, pt) = self.sigma_table.point(self, sigma);
        [pt.x, pt.y]
    }

    fn axial_force(&self, sigma: f64) -> f64 {
        self.sigma_table.point(self, sigma).1.tension
    }

    fn bending_moment(&self, _sigma: f64) -> Option<f64> {
        None
    }

    fn transverse_force(&self, _sigma: f64) -> Option<f64> {
        None
    }

    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        // Per unit contour length on the arc: p / λ · (R_belt / R) with R_belt = R.
        let (_, pt) = self.sigma_table.point(self, sigma);
        Some(pt.pressure.map_or(0.0, |p| p / (1.0 + pt.tension / self.data.axial_stiffness)))
    }

    fn contact_state(&self, sigma: f64) -> ContactState {
        match self.sigma_table.point(self, sigma).0 {
            DRIVEN_ARC | DRIVER_ARC => ContactState::Contact,
            _ => ContactState::Free,
        }
    }

    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.sigma_table.point(self, sigma).1.material
    }

    fn summary(&self) -> Summary {
        let upper = self.point(UPPER_LEFT, 1.0);
        let lower = self.point(LOWER_RIGHT, 1.0);
        Summary {
            y_upper_mid: Some(upper.y),
            y_lower_mid: Some(lower.y),
            tension_upper_mid: Some(upper.tension),
            tension_lower_mid: Some(lower.tension),
            driver: Some(self.pulley_summary(true)),
            driven: Some(self.pulley_summary(false)),
            ..Summary::default()
        }
    }
}
