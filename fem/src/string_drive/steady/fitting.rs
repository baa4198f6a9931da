//! Mesh fitting of the direct steady solve: the stick→slip transitions located from the point results, σ unwrapping, and the traction transfer to a new mesh.

use super::*;

/// Unwrapped σ of a pulley's zone (the driver's straddles σ = 0).
pub(super) fn unwrapped(contour: &Contour, pulley: Pulley, sigma: f64) -> f64 {
    super::super::unwrap(contour, pulley, sigma)
}

/// The stick→slip transition of a pulley (docs/fem-drive.md §12): the zero of the
/// relative velocity v of the trailing slip run — each point's v is the stretch of its
/// element, placed at the element's midpoint — extrapolated by the quadratic through the
/// 2nd–4th distinct samples (the line through the first two on a short run), clamped
/// between the stick point before the last one and the second slip sample; `None` if the
/// pulley has no stick point or no slip point. All in the coordinate u = ±σ (unwrapped)
/// that runs with the belt, so that the stick run comes first in either direction.
pub fn transition(results: &[PointResult], contour: &Contour, pulley: Pulley) -> Option<f64> {
    let mut pts: Vec<&PointResult> = results.iter().filter(|p| p.point.pulley == pulley && p.normal > 0.0).collect();
    let sign = pts.first()?.point.direction.sign();
    // the halves of a split node in the order of travel too
    let key = |p: &PointResult| (sign * unwrapped(contour, pulley, p.point.sigma), sign * p.point.part.offset());
    pts.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap_or(std::cmp::Ordering::Equal));
    let last_stick = pts.iter().rposition(|p| !p.slip)?;
    if last_stick + 1 >= pts.len() {
        return None;
    }
    let s = |p: &PointResult| sign * unwrapped(contour, pulley, p.point.sigma);
    let mid = |p: &PointResult| sign * unwrapped(contour, pulley, p.point.velocity_sigma());
    let a = pts[last_stick];
    // the distinct velocity samples of the slip run (the slip half of a split node and
    // the next node share their element), up to four
    let mut samples: Vec<&PointResult> = Vec::with_capacity(4);
    for p in &pts[last_stick + 1..] {
        if samples.last().is_none_or(|q| (mid(p) - mid(q)).abs() > 1e-12) {
            samples.push(p);
        }
        if samples.len() == 4 {
            break;
        }
    }
    let b = samples[0];
    let mut sigma = 0.5 * (s(a) + s(b));
    // the zero may lie up to one element upstream of the last stick point or up to the
    // second slip sample downstream
    let lo = if last_stick > 0 { s(pts[last_stick - 1]) } else { s(a) };
    let hi = samples.get(1).map_or(s(b), |c| s(c));
    let linear = |p: &PointResult, q: &PointResult| {
        let (mp, mq) = (mid(p), mid(q));
        (mq > mp && (q.velocity - p.velocity).abs() > 0.0).then(|| mp - p.velocity * (mq - mp) / (q.velocity - p.velocity))
    };
    // the quadratic through the 2nd–4th samples (the first slip element carries the
    // stick zone's alternating layer, §12), else the line through the first two
    let root = match samples[..] {
        [_, p, q, r] => {
            let (x0, x1, x2) = (mid(p), mid(q), mid(r));
            let (y0, y1, y2) = (p.velocity, q.velocity, r.velocity);
            // v = y0 + d1 (x − x0) + d2 (x − x0)(x − x1)
            let d1 = (y1 - y0) / (x1 - x0);
            let d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
            // in t = x − x0: d2 t² + (d1 − d2 (x1 − x0)) t + y0 = 0, the root nearest the line's
            let (qa, qb, qc) = (d2, d1 - d2 * (x1 - x0), y0);
            let guess = linear(p, q);
            let disc = qb * qb - 4.0 * qa * qc;
            if qa.abs() > 0.0 && disc >= 0.0 {
                let sq = disc.sqrt();
                let t1 = (-qb + sq) / (2.0 * qa);
                let t2 = (-qb - sq) / (2.0 * qa);
                let g = guess.map_or(x0, |g| g - x0);
                Some(x0 + if (t1 - g).abs() < (t2 - g).abs() { t1 } else { t2 })
            } else {
                guess
            }
        }
        [p, q, ..] => linear(p, q),
        _ => None,
    };
    if let Some(root) = root.filter(|r| r.is_finite()) {
        sigma = root.clamp(lo, hi);
    }
    Some(contour.wrap(sign * sigma))
}

/// Signed periodic difference a − b on a contour of length l, in (−l/2, l/2].
pub(super) fn wrapped_diff(a: f64, b: f64, l: f64) -> f64 {
    let d = (a - b).rem_euclid(l);
    if d > 0.5 * l {
        d - l
    } else {
        d
    }
}

/// τ at a new friction point from the old solution: linear in σ between the two old
/// points of the same pulley that enclose it (the nearer one at a zone end).
pub(super) fn interpolate_traction(old: &[PointResult], contour: &Contour, p: &FrictionPoint) -> f64 {
    let s = unwrapped(contour, p.pulley, p.sigma);
    let mut pts: Vec<(f64, f64)> = old.iter().filter(|o| o.point.pulley == p.pulley).map(|o| (unwrapped(contour, p.pulley, o.point.sigma), o.traction)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    if pts.is_empty() {
        return 0.0;
    }
    let k = pts.partition_point(|q| q.0 <= s);
    if k == 0 {
        return pts[0].1;
    }
    if k == pts.len() {
        return pts[k - 1].1;
    }
    let (a, b) = (pts[k - 1], pts[k]);
    if b.0 > a.0 {
        a.1 + (b.1 - a.1) * (s - a.0) / (b.0 - a.0)
    } else {
        a.1
    }
}
