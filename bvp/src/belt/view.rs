//! The σ-sampled part of the common [`drive::view::SolutionView`], shared by every belt
//! BVP solution: the belt point on the contour normal at σ and its segment give the
//! position, the section forces, the contact tractions per unit contour length and the
//! contact state. (A blanket impl of the drive crate's trait is not possible here, so
//! the methods are written once in [`sampled_view_methods`] and expanded into each impl.)

use drive::view::ContactState;

use super::law::BeltPoint;
use super::topology::{ArcKind, SegmentKind};

/// The contact state of a segment of `kind`: free on a span, else the arc's kind.
pub fn contact_state(kind: SegmentKind) -> ContactState {
    match kind {
        SegmentKind::Span => ContactState::Free,
        SegmentKind::Arc(ArcKind::Frictionless) => ContactState::Contact,
        SegmentKind::Arc(ArcKind::Stick) => ContactState::Stick,
        SegmentKind::Arc(ArcKind::Slip) => ContactState::Slip,
    }
}

/// A traction per unstretched length `value` (pressure p or friction f_t, N/m; `None` off
/// the arcs) of the belt point `point` per unit contour length: v/λ, since the belt
/// centreline lies on the contour of the arc (dσ = R dφ = λ ds); 0 off the arcs.
pub fn per_contour_length(value: Option<f64>, point: &BeltPoint) -> f64 {
    value.map_or(0.0, |v| v / point.stretch)
}

/// The σ-sampled methods of `SolutionView` (position, axial and transverse force,
/// bending moment, section rotation, shear strain, contact pressure, friction traction, contact state,
/// material coordinate), expanded inside `impl SolutionView for T` of a belt solution `T` with
/// `fn at_sigma(&self, σ) -> (usize, BeltPoint)` (segment and point at σ) and
/// `fn topology(&self) -> &Topology`. The friction traction is `None` for a topology
/// without stick or slip arcs, + in the direction of travel = +σ.
macro_rules! sampled_view_methods {
    () => {
        fn position(&self, sigma: f64) -> [f64; 2] {
            let (_, pt) = self.at_sigma(sigma);
            [pt.x, pt.y]
        }

        fn axial_force(&self, sigma: f64) -> f64 {
            self.at_sigma(sigma).1.tension
        }

        fn bending_moment(&self, sigma: f64) -> Option<f64> {
            self.at_sigma(sigma).1.moment
        }

        fn transverse_force(&self, sigma: f64) -> Option<f64> {
            self.at_sigma(sigma).1.shear
        }

        fn shear_strain(&self, sigma: f64) -> Option<f64> {
            self.at_sigma(sigma).1.shear_strain
        }

        /// The section rotation θ of a rod (the director angle of a Cosserat rod, the
        /// tangent angle of a Kirchhoff rod), unwrapped to lie within π of the contour's
        /// tangent angle ([`drive::contour::Path::unwrap_near_tangent`]); `None` for a
        /// string (no moment, no section rotation of its own).
        fn rotation(&self, sigma: f64) -> Option<f64> {
            let (_, pt) = self.at_sigma(sigma);
            pt.moment?;
            Some(self.path().unwrap_near_tangent(sigma, pt.theta?))
        }

        fn contact_pressure(&self, sigma: f64) -> Option<f64> {
            // the Kirchhoff rod's edge forces are concentrated and reported in the summary
            let (_, pt) = self.at_sigma(sigma);
            Some($crate::belt::view::per_contour_length(pt.pressure, &pt))
        }

        fn friction_traction(&self, sigma: f64) -> Option<f64> {
            if !self.topology().has_friction() {
                return None;
            }
            let (_, pt) = self.at_sigma(sigma);
            Some($crate::belt::view::per_contour_length(pt.friction, &pt))
        }

        fn contact_state(&self, sigma: f64) -> drive::view::ContactState {
            $crate::belt::view::contact_state(self.topology().segment(self.at_sigma(sigma).0).kind)
        }

        fn material_coordinate(&self, sigma: f64) -> f64 {
            self.at_sigma(sigma).1.material
        }
    };
}
pub(crate) use sampled_view_methods;
