//! Friction-point topology of the direct steady solve (docs/fem-drive.md §12): the friction points of a mesh, their halves at a stick→slip transition, and the point results.

use super::*;

/// One friction point of the steady problem (docs/fem-drive.md §12): a node within
/// reach of a pulley. Its stretch and gap are the trapezoidal means over the two element
/// edges that meet there (equal except at a region transition, where the slopes are
/// separate); one traction per node, so the node's S-equation carries one unknown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPoint {
    /// σ of the node, m.
    pub sigma: f64,
    /// The pulley the point can touch.
    pub pulley: Pulley,
    /// Trapezoidal weight (h_left + h_right)/2, m.
    pub weight: f64,
    /// The node.
    pub node: usize,
    /// Element ending at the node (its edge ξ = +1) and its weight h/2.
    pub left: (usize, f64),
    /// Element starting at the node (its edge ξ = −1) and its weight h/2.
    pub right: (usize, f64),
    /// The whole node, or one half of a node split at a fitted stick→slip transition.
    pub part: Part,
    /// The running direction of the belt: the upwind element of a whole node is the one
    /// ending at it clockwise, the one starting at it counter-clockwise.
    pub direction: Direction,
    /// Paper D's fixed topology (spec §3.5, [`super::paper_d`]): the point's row while it
    /// is in contact, prescribed instead of decided by Coulomb's law; `None` (the direct
    /// semismooth solve): decided per iterate by (DS4).
    pub fixed: Option<Fixed>,
    /// Contact-side halves (docs/fem-drive.md §12, "Fifth round": Paper D's fixed topology
    /// on the string; docs/fem-cosserat.md §11.1: the Cosserat drive's fitted meshes): the
    /// node is a contact boundary and the point is its contact side only — a half
    /// ([`Part::Left`] or [`Part::Right`], the side in contact) whose traction loads that
    /// element alone, so no friction acts on the free element beyond the boundary. A
    /// stick entry half ([`FrictionPoint::is_entry`]) has no kinematic row (its upwind
    /// element is free): it carries the traction of its downstream neighbour.
    pub boundary: bool,
}

/// A friction point's prescribed row in Paper D's fixed topology (spec §3.5): while the
/// point is in contact (p > 0) either the stick row v = 0 whatever |τ|, or the slip row
/// τ = s μ p with the slip direction s given; out of contact τ = 0 as always.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fixed {
    /// v = 0.
    Stick,
    /// τ = s μ p, s = ±1.
    Slip(f64),
    /// Out of contact by the topology (the string's Paper D points outside the prescribed
    /// contact zones, [`in_contact_zone`]): τ = 0, whatever the gap of the iterate.
    Free,
}

/// Which share of a node a friction point carries (docs/fem-drive.md §12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Both edges, weight (h_l + h_r)/2, v upwind (the element ending at the node
    /// clockwise, the one starting there counter-clockwise).
    Whole,
    /// The half of a transition node before it along σ: weight h_l/2, v of the element
    /// ending there (the stick side clockwise, the slip side counter-clockwise).
    Left,
    /// The half after it along σ: weight h_r/2, v of the element starting there — so
    /// the traction jump at the transition sits exactly at the node.
    Right,
}

impl Part {
    /// The half's side of its node along σ: −1 [`Part::Left`], 0 whole, +1 [`Part::Right`].
    pub fn offset(self) -> f64 {
        match self {
            Part::Left => -1.0,
            Part::Whole => 0.0,
            Part::Right => 1.0,
        }
    }
}

impl FrictionPoint {
    /// True when the point's velocity is sampled in the element starting at the node.
    pub fn velocity_from_right(&self) -> bool {
        match self.part {
            Part::Right => true,
            Part::Left => false,
            Part::Whole => self.direction == Direction::CounterClockwise,
        }
    }

    /// The element whose stretch λ̄ gives the point's velocity (DS0).
    pub fn velocity_element(&self) -> usize {
        if self.velocity_from_right() {
            self.right.0
        } else {
            self.left.0
        }
    }

    /// A contact boundary's half whose contact side lies downstream in the travel: where
    /// the belt runs onto the pulley ([`Part::Right`] clockwise, [`Part::Left`]
    /// counter-clockwise).
    pub fn is_entry(&self) -> bool {
        self.boundary && (self.part == Part::Right) == (self.direction == Direction::Clockwise)
    }

    /// The share of side `side` (0: the element ending at the node, 1: the one starting
    /// there) in the point's means over its node's edges (its normal load): that side's
    /// h/2 over the point's sides' — both sides for a whole node or a split half, the own
    /// side alone for a contact-side half ([`FrictionPoint::boundary`]); `None` for a
    /// contact-side half's free side.
    pub fn side_share(&self, side: usize) -> Option<f64> {
        let own = !self.boundary || (side == 1) == (self.part == Part::Right);
        let sides = match (self.boundary, self.part) {
            (true, Part::Right) => self.right.1,
            (true, _) => self.left.1,
            (false, _) => self.left.1 + self.right.1,
        };
        own.then(|| (if side == 0 { self.left.1 } else { self.right.1 }) / sides)
    }

    /// σ where the point's velocity is sampled: the midpoint of its element.
    pub fn velocity_sigma(&self) -> f64 {
        if self.velocity_from_right() {
            self.sigma + self.right.1
        } else {
            self.sigma - self.left.1
        }
    }
}

/// The state of a friction point in a converged steady solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointResult {
    /// The point.
    pub point: FrictionPoint,
    /// τ_⊥, force per contour length of the belt on the drum along +σ, N/m.
    pub traction: f64,
    /// Normal traction P⟨−γ⟩, N/m.
    pub normal: f64,
    /// Relative velocity v = cλ − Rω_k of belt and drum surface, m/s.
    pub velocity: f64,
    /// Slip (|τ + κv| ≥ b with b > 0).
    pub slip: bool,
}

/// The friction points of a mesh (docs/fem-drive.md §12) for a belt running in
/// `direction`: one per node within reach of a pulley, two (the halves [`Part::Left`],
/// [`Part::Right`]) at a node within 10⁻⁶ of its element lengths of one of the
/// stick→slip transitions `splits` (σ).
pub fn friction_points<const N: usize, K: LayoutElement<N> + ?Sized>(asm: &Assembler<N, K>, splits: &[f64], direction: Direction) -> Vec<FrictionPoint> {
    let mesh = asm.mesh();
    let contour = mesh.contour();
    let lc = contour.length();
    let n = mesh.len();
    let mut out = Vec::new();
    // an open mesh (docs/fem-cosserat.md §12.1): its interior nodes, and only its one
    // pulley (the loop's second pulley, at the open ends, does not exist)
    let nodes = if mesh.is_open() { 1..n } else { 0..n };
    for k in nodes {
        let left = (k + n - 1) % n;
        let (el_l, el_r) = (mesh.elements()[left], mesh.elements()[k]);
        let sigma = mesh.node_sigmas()[k];
        let reach = |region: Region| reachable_pulley(contour, region, sigma);
        let pulley = reach(el_r.region).or_else(|| reach(el_l.region));
        let Some(pulley) = pulley.filter(|p| !(mesh.is_open() && *p == Pulley::Driver)) else { continue };
        let whole = FrictionPoint { sigma, pulley, weight: 0.5 * (el_l.h + el_r.h), node: k, left: (left, 0.5 * el_l.h), right: (k, 0.5 * el_r.h), part: Part::Whole, direction, fixed: None, boundary: false };
        if splits.iter().any(|&t| crate::fitting::periodic_diff(t, sigma, lc).abs() <= 1e-6 * (el_l.h + el_r.h)) {
            out.push(FrictionPoint { weight: 0.5 * el_l.h, part: Part::Left, ..whole });
            out.push(FrictionPoint { weight: 0.5 * el_r.h, part: Part::Right, ..whole });
        } else {
            out.push(whole);
        }
    }
    out
}

/// σ of a pulley's prescribed stick→slip point in Paper D's fixed topology (the node split
/// into a fixed stick and a fixed slip half); `None` without a fixed topology.
pub fn fixed_transition(results: &[PointResult], pulley: Pulley) -> Option<f64> {
    results.iter().find(|p| p.point.pulley == pulley && p.point.fixed.is_some() && p.point.part != Part::Whole && !p.point.boundary).map(|p| p.point.sigma)
}

/// The contact-side halves (docs/fem-drive.md §12, "Fifth round": Paper D's on the string;
/// docs/fem-cosserat.md §11.1: both schemes on the Cosserat drive): the point at a node within 10⁻⁶ of its element lengths of a contact zone's start
/// (`zones`: per pulley σ_start, σ_end along σ) becomes the half on the zone's side
/// ([`Part::Right`]), at its end [`Part::Left`], with that side's weight only and
/// [`FrictionPoint::boundary`] set. A node that is also a stick→slip split is left as it is.
pub fn contact_side_halves(points: &mut [FrictionPoint], zones: &[(Pulley, f64, f64)], lc: f64) {
    for p in points.iter_mut().filter(|p| p.part == Part::Whole) {
        let (sigma, tolerance, pulley) = (p.sigma, 1e-6 * 2.0 * (p.left.1 + p.right.1), p.pulley);
        let near = |s: f64| crate::fitting::periodic_diff(s, sigma, lc).abs() <= tolerance;
        for &(_, start, end) in zones.iter().filter(|z| z.0 == pulley) {
            if near(start) {
                *p = FrictionPoint { weight: p.right.1, part: Part::Right, boundary: true, ..*p };
            } else if near(end) {
                *p = FrictionPoint { weight: p.left.1, part: Part::Left, boundary: true, ..*p };
            }
        }
    }
}

/// The contact zones `zones` (pulley, σ_start, σ_end) with each boundary moved to the
/// nearest node of `mesh`: the node [`contact_side_halves`] makes the boundary's half.
/// A boundary the mesh was given as a breakpoint is a node already and stays; one that
/// [`Mesh::graded`] dropped (within 2 % of an element of a region end or of another
/// breakpoint) sits next to the node that took its place. Left unmoved, no point would
/// be its half and the node beside it would be whole — on its free side a free point
/// (τ = 0) whose hat halves the friction of the last contact element (measured on
/// `string-drive-exudyn` by Paper D at 64–128 elements: the driven exit 0.19 mm before
/// the arc's end node, the slip zone's friction short by ≈ 8 N, its stick arc 10 % off;
/// docs/fem-drive.md §12, "Seventh round").
pub fn zones_on_nodes(zones: &[(Pulley, f64, f64)], mesh: &Mesh) -> Vec<(Pulley, f64, f64)> {
    let lc = mesh.contour().length();
    let nearest = |s: f64| mesh.node_sigmas().iter().copied().min_by(|&a, &b| crate::fitting::periodic_diff(a, s, lc).abs().total_cmp(&crate::fitting::periodic_diff(b, s, lc).abs())).unwrap_or(s);
    zones.iter().map(|&(pulley, start, end)| (pulley, nearest(start), nearest(end))).collect()
}

/// Whether a Paper D point of the string lies in its pulley's prescribed contact zone
/// (`zones`: per pulley σ_start, σ_end along σ, as [`contact_side_halves`] takes them): a
/// contact boundary's half ([`FrictionPoint::boundary`]), or a node strictly inside the
/// zone (beyond 10⁻⁶ of its element lengths of either end). The fixed topology's contact
/// set (docs/fem-drive.md §12, "Sixth round"): the sign of the gap of an iterate is no
/// measure of it — the stiff penalty's penetration (≈ 10⁻¹⁰ m) is far below the gap error
/// of a state transferred to a new mesh (≈ 10⁻⁸ m), so on the first solve at a new mesh
/// whole stretches of a contact zone read as free (measured on the counter-clockwise
/// low-tension drive: the driver's whole slip zone).
pub fn in_contact_zone(p: &FrictionPoint, zones: &[(Pulley, f64, f64)], lc: f64) -> bool {
    let tolerance = 1e-6 * 2.0 * (p.left.1 + p.right.1);
    p.boundary
        || zones.iter().filter(|z| z.0 == p.pulley).any(|&(_, start, end)| {
            let u = (p.sigma - start).rem_euclid(lc);
            u > tolerance && u < (end - start).rem_euclid(lc) - tolerance
        })
}

/// Breakpoints that divide the part of each contact zone (`zones`: pulley, σ_start, σ_end)
/// lying on a span's straight contour — between a boundary and its pulley's arc — into
/// elements no longer than `h_max` (m), equally spaced. There the deflection ν carries the
/// drum's curvature (ν ≈ u²/2R past the tangent point), which the cubic follows only at
/// the contact rule's points; a piece left as one element of its own length, which does
/// not shrink with the mesh, set the stick zone's tension level (docs/fem-drive.md §12,
/// "Sixth round").
pub fn span_contact_breaks(contour: &Contour, zones: &[(Pulley, f64, f64)], h_max: f64) -> Vec<f64> {
    let lc = contour.length();
    let mut out = Vec::new();
    for &(pulley, start, end) in zones {
        let arc = if pulley == Pulley::Driver { Region::DriverArc } else { Region::DrivenArc };
        let (a0, a1) = contour.region_bounds(arc);
        let span = (end - start).rem_euclid(lc);
        // the piece before the arc (start → a0) and after it (a1 → end), along +σ
        for (from, length) in [(start, (a0 - start).rem_euclid(lc)), (a1, (end - a1).rem_euclid(lc))] {
            if length <= 0.0 || length >= span {
                continue;
            }
            let n = (length / h_max).ceil().max(1.0) as usize;
            out.extend((1..n).map(|j| contour.wrap(from + length * j as f64 / n as f64)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A zone boundary the mesh took as a breakpoint stays; one `Mesh::graded` dropped
    /// (within 2 % of an element of a region end) moves to the node that took its place,
    /// so the boundary is a node and [`contact_side_halves`] makes that node its half.
    #[test]
    fn zone_boundaries_move_to_the_nodes_that_took_them() {
        let contour = Contour::new(0.1, 0.1 * PI).unwrap();
        let (a0, a1) = contour.region_bounds(Region::DrivenArc);
        let h = (a1 - a0) / Mesh::new(contour, 128, 1.0).unwrap().elements().iter().filter(|e| e.region == Region::DrivenArc).count() as f64;
        // the exit 1 % of an element before the arc's end (dropped), the entry 0.3 of an
        // element before its start, on the span (kept)
        let (start, end) = (a0 - 0.3 * h, a1 - 0.01 * h);
        let (mesh, used) = Mesh::graded(contour, 128, 1.0, &[start, end], None).unwrap();
        assert_eq!(used.len(), 1, "the exit is dropped, the entry kept: {used:?}");
        let zones = zones_on_nodes(&[(Pulley::Driven, start, end)], &mesh);
        assert_eq!(zones[0].1, start, "a node already");
        assert_eq!(zones[0].2, a1, "the arc's end node");
        let lc = contour.length();
        let on_node = |s: f64| mesh.node_sigmas().iter().any(|&n| crate::fitting::periodic_diff(n, s, lc).abs() < 1e-15);
        assert!(on_node(zones[0].1) && on_node(zones[0].2));
    }
}
