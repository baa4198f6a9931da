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
use super::{BeltPoint, StringHangingSolution};
use crate::sigma_map::SigmaMap;

/// Wrap an angle to (−π, π].
pub(crate) fn wrap_angle(a: f64) -> f64 {
    let mut w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w -= 2.0 * PI;
    }
    w
}

impl StringHangingSolution {
    /// The σ map of this solution (docs: [`crate::sigma_map`]).
    pub(super) fn build_sigma_map(&self) -> SigmaMap {
        let contour = Contour::new(self.data.radius, self.data.centre_distance).expect("validated geometry");
        SigmaMap::new(contour, &super::problem::SIDES, &self.solution, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        })
    }

    /// The belt point at contour coordinate σ, with its segment.
    fn at_sigma(&self, sigma: f64) -> (usize, BeltPoint) {
        let (k, xi) = self.sigma_map.locate(sigma, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        });
        (k, self.point(k, xi))
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
        self.sigma_map.contour()
    }

    fn position(&self, sigma: f64) -> [f64; 2] {
        let (_, pt) = self.at_sigma(sigma);
        [pt.x, pt.y]
    }

    fn axial_force(&self, sigma: f64) -> f64 {
        self.at_sigma(sigma).1.tension
    }

    fn bending_moment(&self, _sigma: f64) -> Option<f64> {
        None
    }

    fn transverse_force(&self, _sigma: f64) -> Option<f64> {
        None
    }

    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        // Per unit contour length on the arc: p / λ · (R_belt / R) with R_belt = R.
        let (_, pt) = self.at_sigma(sigma);
        Some(pt.pressure.map_or(0.0, |p| p / (1.0 + pt.tension / self.data.axial_stiffness)))
    }

    fn contact_state(&self, sigma: f64) -> ContactState {
        match self.at_sigma(sigma).0 {
            DRIVEN_ARC | DRIVER_ARC => ContactState::Contact,
            _ => ContactState::Free,
        }
    }

    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.at_sigma(sigma).1.material
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
