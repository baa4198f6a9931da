//! The belt point "at contour coordinate σ" for a multi-segment belt solution.
//!
//! A BVP solution is parametrised by segment k and ξ ∈ [0, 1], not by σ. The common
//! solution view (MEL description, eq. 27) asks for the belt point on the contour normal
//! at σ: the point whose inverse contour map (`Contour::sigma_nu`) gives σ. Along a
//! physical belt this σ increases monotonically round the loop, so a table of σ at dense
//! samples, unwrapped to increase, brackets any query, and bisection on the dense output
//! refines it to ~1e-15 in ξ.
//!
//! The inverse contour map alone cannot say on which straight a point between the pulley
//! centres (|x| ≤ H/2) lies: `Contour::sigma_nu` decides by the sign of y, so an upper
//! span that sags below the centre line (y < 0, slack belts on small pulleys) would be
//! read as the lower span and the σ table would fold back on itself (issue 12, item 1:
//! every upper-span field sample then sat at one point). The MEL description puts such
//! a point on the upper straight at ν = y − R < −R. So each segment carries its
//! [`Side`]: a span point between the centres takes σ of its own straight; a pulley
//! sector point (|x| > H/2) and an arc point are mapped by `sigma_nu` as before.
//!
//! On the open contour of a one-pulley scene ([`Path::Open`]) σ runs from the inflow end
//! to the outflow end and is not wrapped; `OpenContour::sigma_nu` decides by the side
//! of the pulley centre, which no span of an open belt without gravity crosses.

use drive::contour::{Contour, Path};

use crate::solution::Solution;

/// Which part of the loop a segment is: it decides which straight of the contour a
/// point between the pulley centres belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// A free span of the upper strand (σ runs left to right, x increasing).
    UpperSpan,
    /// A free span of the lower strand (σ runs right to left).
    LowerSpan,
    /// A contact arc on a pulley (always on the pulley circle: the sign of y decides).
    Arc,
}

/// σ of a belt point on a segment of side `side`: [`sigma_on`] on the loop (in
/// [0, L_c)), the open contour's inverse map on an open path.
fn sigma_on_path(path: &Path, side: Side, point: [f64; 2]) -> f64 {
    match path {
        Path::Loop(contour) => sigma_on(contour, side, point),
        Path::Open(open) => open.sigma_nu(point).0,
    }
}

/// σ (unwrapped into [0, L_c)) of a belt point on a segment of side `side`.
pub fn sigma_on(contour: &Contour, side: Side, point: [f64; 2]) -> f64 {
    let (h, r) = (contour.centre_distance(), contour.radius());
    let half = 0.5 * h;
    let x = point[0];
    if x.abs() <= half {
        match side {
            Side::UpperSpan => return contour.wrap(x + half),
            Side::LowerSpan => return contour.wrap(h + std::f64::consts::PI * r + half - x),
            Side::Arc => {}
        }
    }
    contour.sigma_nu(point).0
}

/// σ at dense samples along the loop: (segment, ξ, σ unwrapped), in loop order.
#[derive(Debug, Clone)]
pub struct SigmaMap {
    path: Path,
    sides: Vec<Side>,
    entries: Vec<(usize, f64, f64)>,
}

/// Samples per mesh interval in the table.
const PER_INTERVAL: usize = 8;

impl SigmaMap {
    /// The table for `solution` on `path` (a loop [`Contour`] or a [`Path`]), whose belt
    /// point at (k, ξ) is `point(k, ξ)` (m) and whose segment k lies on `sides[k]`.
    pub fn new(path: impl Into<Path>, sides: &[Side], solution: &Solution, point: impl Fn(usize, f64) -> [f64; 2]) -> Self {
        let path = path.into();
        assert_eq!(sides.len(), solution.segments.len(), "one side per segment");
        let total = path.length();
        let mut entries = Vec::new();
        let mut last = f64::NEG_INFINITY;
        let mut offset = 0.0;
        for (k, xi) in solution.sample_points(PER_INTERVAL) {
            let s = sigma_on_path(&path, sides[k], point(k, xi));
            let mut su = s + offset;
            if last.is_finite() && su < last - 0.5 * total {
                offset += total;
                su += total;
            }
            last = su;
            entries.push((k, xi, su));
        }
        Self { path, sides: sides.to_vec(), entries }
    }

    /// A map with no samples yet (for two-phase construction of a solution object whose
    /// `point` is needed to build the table); [`SigmaMap::locate`] answers (0, 0) until it
    /// is replaced by [`SigmaMap::new`].
    pub fn empty(path: impl Into<Path>) -> Self {
        Self { path: path.into(), sides: Vec::new(), entries: Vec::new() }
    }

    /// The path the table is on.
    pub fn path(&self) -> Path {
        self.path
    }

    /// Segment and ξ of the belt point at contour coordinate `sigma` (wrapped
    /// periodically on the loop; on an open path clamped to the ends of the belt);
    /// `point` as in [`SigmaMap::new`].
    pub fn locate(&self, sigma: f64, point: impl Fn(usize, f64) -> [f64; 2]) -> (usize, f64) {
        if self.entries.len() < 2 {
            return (0, 0.0);
        }
        let total = self.path.length();
        let first = self.entries[0].2;
        let s = match self.path {
            Path::Loop(_) => first + (sigma - first).rem_euclid(total),
            Path::Open(_) => sigma,
        };
        let i = self.entries.partition_point(|e| e.2 <= s).clamp(1, self.entries.len() - 1);
        let (k0, x0, s0) = self.entries[i - 1];
        let (k1, x1, _) = self.entries[i];
        if k0 != k1 {
            // The bracket joins two segments at a shared point.
            return (k0, x0);
        }
        let sigma_at = |xi: f64| {
            let v = sigma_on_path(&self.path, self.sides[k0], point(k0, xi));
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
}
