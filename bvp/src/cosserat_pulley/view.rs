//! The one-pulley solution through the common [`SolutionView`]: σ on the open contour of
//! the scene (`drive::OpenContour`, from the inflow end x = −D along the upper side,
//! clockwise round the pulley, to the outflow end), the belt point on the contour normal
//! at σ found by [`SigmaMap`] over the four segments.

use drive::contour::Path;
use drive::summary::Summary;
use drive::view::SolutionView;

use crate::belt::{BeltPoint, Topology};
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

    /// The open one-pulley topology.
    pub fn topology(&self) -> &Topology {
        &self.problem.topology
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

    crate::belt::view::sampled_view_methods!();

    fn summary(&self) -> Summary {
        CosseratPulleySolution::summary(self)
    }
}
