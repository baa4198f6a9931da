//! The one-pulley solution through the common [`SolutionView`]: σ on the open contour of
//! the scene (`drive::OpenContour`, from the inflow end x = −D along the upper side,
//! clockwise round the pulley, to the outflow end), the belt point on the contour normal
//! at σ found by [`SigmaMap`] over the four segments.

use drive::contour::Path;
use drive::summary::Summary;
use drive::view::{ContactState, SolutionView};

use crate::belt::{ArcKind, BeltPoint, SegmentKind};
use crate::sigma_map::SigmaMap;

use super::CosseratPulleySolution;

impl CosseratPulleySolution {
    /// The σ table of the solution on its open contour (built once by the solve).
    pub(super) fn build_sigma_map(&self) -> SigmaMap {
        SigmaMap::new(self.sigma_map.path(), &self.problem.topology.sides(), &self.solution, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        })
    }

    /// Segment and the belt point on the contour normal at σ (clamped to the ends).
    pub fn at_sigma(&self, sigma: f64) -> (usize, BeltPoint) {
        let (k, xi) = self.sigma_map.locate(sigma, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        });
        (k, self.point(k, xi))
    }
}

impl SolutionView for CosseratPulleySolution {
    fn path(&self) -> Path {
        self.sigma_map.path()
    }

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

    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        // per unit contour length on the arc: p/λ (dσ = R dφ = λ ds)
        let (_, pt) = self.at_sigma(sigma);
        Some(pt.pressure.map_or(0.0, |p| p / pt.stretch))
    }

    fn friction_traction(&self, sigma: f64) -> Option<f64> {
        let (_, pt) = self.at_sigma(sigma);
        Some(pt.friction.map_or(0.0, |f| f / pt.stretch))
    }

    fn contact_state(&self, sigma: f64) -> ContactState {
        match self.problem.topology.segment(self.at_sigma(sigma).0).kind {
            SegmentKind::Span => ContactState::Free,
            SegmentKind::Arc(ArcKind::Frictionless) => ContactState::Contact,
            SegmentKind::Arc(ArcKind::Stick) => ContactState::Stick,
            SegmentKind::Arc(ArcKind::Slip) => ContactState::Slip,
        }
    }

    fn rotation(&self, sigma: f64) -> Option<f64> {
        self.at_sigma(sigma).1.theta
    }

    fn shear_strain(&self, sigma: f64) -> Option<f64> {
        Some(self.at_sigma(sigma).1.shear? / self.data.shear_stiffness)
    }

    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.at_sigma(sigma).1.material
    }

    fn summary(&self) -> Summary {
        CosseratPulleySolution::summary(self)
    }
}
