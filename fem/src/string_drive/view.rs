//! The common view of a drive state (docs/fem-drive.md §8): geometry, axial force and
//! material coordinate of the string solution ([`FemSolution`]), the contact state
//! Stick/Slip, the normal traction and the friction traction from the integration-point
//! states.

use drive::contour::Pulley;
use drive::summary::Summary;
use drive::view::{ContactState, SolutionView};

use crate::formulation::layout::LayoutElement;
use crate::formulation::Kernel;
use crate::kinematics::NDOF;
use crate::solution::FemSolution;

use super::contact::PointState;

/// One contact point as the common view reads it: what the transient
/// ([`PointState`]) and the direct steady solve both produce — no transient-only fields
/// (upstream references, multipliers, slip bound), so the steady solve fills none with
/// placeholders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewPoint {
    /// ξ in the element.
    pub xi: f64,
    /// σ of the point, m.
    pub sigma: f64,
    /// The pulley the point can touch (`None`: a span point out of reach).
    pub pulley: Option<Pulley>,
    /// Weight of the normal term, m (0 for a friction-only point).
    pub weight: f64,
    /// Weight of the friction term, m (0 for a point without friction).
    pub friction_weight: f64,
    /// Normal traction τ_γ, N/m.
    pub normal: f64,
    /// Tangential traction τ_⊥ (the belt's on the drum), N/m.
    pub tangential: f64,
    /// Sliding.
    pub slip: bool,
}

impl From<&PointState> for ViewPoint {
    fn from(p: &PointState) -> ViewPoint {
        ViewPoint { xi: p.xi, sigma: p.sigma, pulley: p.pulley, weight: p.weight, friction_weight: p.friction_weight, normal: p.normal, tangential: p.tangential, slip: p.slip }
    }
}

/// A converged drive state behind the common view, for an element of any 1-D layout
/// (the string's by default).
pub struct DriveSolution<const N: usize = NDOF, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    base: FemSolution<N, K>,
    /// Contact-capable points of the normal term, sorted by σ.
    points: Vec<ViewPoint>,
    /// Friction points (element edges), sorted by σ.
    friction: Vec<ViewPoint>,
    /// Per element, τ_⊥ at its edges ξ = −1, +1 (0 at an edge without a pulley).
    edge_tractions: Vec<[f64; 2]>,
    summary: Summary,
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> Clone for DriveSolution<N, K> {
    fn clone(&self) -> Self {
        DriveSolution { base: self.base.clone(), points: self.points.clone(), friction: self.friction.clone(), edge_tractions: self.edge_tractions.clone(), summary: self.summary.clone() }
    }
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> DriveSolution<N, K> {
    /// The view of `base` with the point states `points` (per element) and the drive
    /// summary.
    pub fn new(base: FemSolution<N, K>, per_element: &[Vec<ViewPoint>], summary: Summary) -> Self {
        let edge_tractions = per_element
            .iter()
            .map(|pts| {
                let at = |xi: f64| pts.iter().find(|p| p.xi == xi && p.friction_weight > 0.0 && p.pulley.is_some()).map_or(0.0, |p| p.tangential);
                [at(-1.0), at(1.0)]
            })
            .collect();
        let mut points = per_element.concat();
        points.retain(|p| p.pulley.is_some());
        points.sort_by(|a, b| a.sigma.total_cmp(&b.sigma));
        let friction = points.iter().filter(|p| p.friction_weight > 0.0).copied().collect();
        points.retain(|p| p.weight > 0.0);
        DriveSolution { base, points, friction, edge_tractions, summary }
    }

    /// The belt's solution (string or rod).
    pub fn string(&self) -> &FemSolution<N, K> {
        &self.base
    }

    /// The normal-contact integration points (σ-sorted) with their last state.
    pub fn points(&self) -> &[ViewPoint] {
        &self.points
    }

    /// The friction points (element edges, σ-sorted) with their stick/slip state.
    pub fn friction_points(&self) -> &[ViewPoint] {
        &self.friction
    }

    /// The two points of `set` enclosing σ (by σ, periodic) and the interpolation weight
    /// of the second; `None` without points.
    fn neighbours<'a>(&self, set: &'a [ViewPoint], sigma: f64) -> Option<(&'a ViewPoint, &'a ViewPoint, f64)> {
        if set.is_empty() {
            return None;
        }
        let l = self.base.mesh().contour().length();
        let w = self.base.mesh().contour().wrap(sigma);
        let k = set.partition_point(|p| p.sigma <= w);
        let n = set.len();
        let a = &set[(k + n - 1) % n];
        let b = &set[k % n];
        let span = (b.sigma - a.sigma).rem_euclid(l);
        let t = if span > 0.0 { ((w - a.sigma).rem_euclid(l) / span).clamp(0.0, 1.0) } else { 0.0 };
        Some((a, b, t))
    }
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> SolutionView for DriveSolution<N, K> {
    fn path(&self) -> drive::contour::Path {
        self.base.path()
    }

    fn position(&self, sigma: f64) -> [f64; 2] {
        self.base.position(sigma)
    }

    fn axial_force(&self, sigma: f64) -> f64 {
        self.base.axial_force(sigma)
    }

    /// The rod's bending moment ([`FemSolution`]'s; `None` for the string).
    fn bending_moment(&self, sigma: f64) -> Option<f64> {
        self.base.bending_moment(sigma)
    }

    /// The rod's transverse force ([`FemSolution`]'s; `None` for the string).
    fn transverse_force(&self, sigma: f64) -> Option<f64> {
        self.base.transverse_force(sigma)
    }

    /// The rod's section rotation θ ([`FemSolution`]'s; `None` for the string).
    fn rotation(&self, sigma: f64) -> Option<f64> {
        self.base.rotation(sigma)
    }

    /// The element's shear strain Γ₂ ([`FemSolution`]'s; `None` for the string).
    fn shear_strain(&self, sigma: f64) -> Option<f64> {
        self.base.shear_strain(sigma)
    }

    /// τ_γ interpolated linearly between the neighbouring contact points; 0 outside
    /// the contact zones.
    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        if self.base.contact_state(sigma) == ContactState::Free {
            return Some(0.0);
        }
        Some(self.neighbours(&self.points, sigma).map_or(0.0, |(a, b, t)| ((1.0 - t) * a.normal + t * b.normal).max(0.0)))
    }

    /// The pulley's traction on the belt, −τ_⊥ (τ_⊥ is the belt's on the drum, §5 of
    /// docs/fem-drive.md), per unit contour length along +σ: linear within each element
    /// between its two edge points (the interpolant whose integral is the trapezoidal
    /// friction rule, so −R∫τ dσ over an arc is the summary torque exactly); 0 in the
    /// elements without friction points (the spans beyond reach of a pulley). Not clipped
    /// to the recovered contact zone: the element holding a contact end carries the
    /// traction of its inner edge point, as the torque does.
    fn friction_traction(&self, sigma: f64) -> Option<f64> {
        let (e, xi) = self.base.mesh().locate(self.base.mesh().contour().wrap(sigma));
        if !xi.is_finite() {
            return None; // non-finite σ: no point of the belt
        }
        let [left, right] = self.edge_tractions.get(e).copied().unwrap_or([0.0, 0.0]);
        Some(-0.5 * ((1.0 - xi) * left + (1.0 + xi) * right))
    }

    /// Free outside the recovered contact zones; inside, Slip or Stick as the nearer
    /// neighbouring friction point.
    fn contact_state(&self, sigma: f64) -> ContactState {
        if self.base.contact_state(sigma) == ContactState::Free {
            return ContactState::Free;
        }
        match self.neighbours(&self.friction, sigma) {
            Some((a, b, t)) => {
                let p = if t < 0.5 { a } else { b };
                if p.slip {
                    ContactState::Slip
                } else {
                    ContactState::Stick
                }
            }
            None => ContactState::Contact,
        }
    }

    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.base.material_coordinate(sigma)
    }

    fn deflection(&self, sigma: f64) -> f64 {
        self.base.deflection(sigma)
    }

    fn summary(&self) -> Summary {
        self.summary.clone()
    }
}
