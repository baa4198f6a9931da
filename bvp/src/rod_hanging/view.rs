//! The common solution view of a `rod-hanging` BVP solution: quantities at a contour
//! coordinate σ (through [`crate::sigma_map`]) and the summary, including the bending
//! moments at mid-span and the concentrated edge forces (R6) of docs/rod-hanging.md.

use drive::contour::Contour;
use drive::summary::{PulleySummary, Summary};
use drive::view::{ContactState, SolutionView};

use super::problem::{DRIVER_ARC, DRIVEN_ARC};
use super::{RodHangingSolution, RodPoint};
use crate::sigma_map::SigmaMap;
use crate::string_hanging::view::wrap_angle;

/// A solved rod behind the common view.
#[derive(Debug, Clone)]
pub struct RodView {
    /// The solution.
    pub solution: RodHangingSolution,
    map: SigmaMap,
}

impl RodView {
    /// Build the σ map of `solution`.
    pub fn new(solution: RodHangingSolution) -> Self {
        let d = &solution.data;
        let contour = Contour::new(d.radius, d.centre_distance).expect("validated geometry");
        let map = SigmaMap::new(contour, &crate::string_hanging::problem::SIDES, &solution.solution, |k, xi| {
            let p = solution.point(k, xi);
            [p.x, p.y]
        });
        Self { solution, map }
    }

    fn at_sigma(&self, sigma: f64) -> (usize, RodPoint) {
        let s = &self.solution;
        let (k, xi) = self.map.locate(sigma, |k, xi| {
            let p = s.point(k, xi);
            [p.x, p.y]
        });
        (k, s.point(k, xi))
    }

    fn pulley(&self, driver: bool) -> PulleySummary {
        let (a, b) = self.solution.contact_angles(driver);
        let e = self.solution.edge_forces();
        let (start, end) = if driver { (e.driver_start, e.driver_end) } else { (e.driven_start, e.driven_end) };
        PulleySummary {
            contact_arc: Some(a - b),
            contact_start: Some(wrap_angle(a)),
            contact_end: Some(wrap_angle(b)),
            edge_force_start: Some(start),
            edge_force_end: Some(end),
            ..PulleySummary::default()
        }
    }
}

impl SolutionView for RodView {
    fn contour(&self) -> &Contour {
        self.map.contour()
    }

    fn position(&self, sigma: f64) -> [f64; 2] {
        let (_, p) = self.at_sigma(sigma);
        [p.x, p.y]
    }

    fn axial_force(&self, sigma: f64) -> f64 {
        self.at_sigma(sigma).1.tension
    }

    fn bending_moment(&self, sigma: f64) -> Option<f64> {
        Some(self.at_sigma(sigma).1.moment)
    }

    fn transverse_force(&self, sigma: f64) -> Option<f64> {
        Some(self.at_sigma(sigma).1.shear)
    }

    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        // Distributed part (R5), per unit deformed length: p / λ; the edge forces are
        // concentrated and reported in the summary.
        let (_, p) = self.at_sigma(sigma);
        Some(p.pressure.map_or(0.0, |q| q / (1.0 + p.tension / self.solution.data.axial_stiffness)))
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
        let (upper, lower) = self.solution.mid_span();
        Summary {
            y_upper_mid: Some(upper.y),
            y_lower_mid: Some(lower.y),
            tension_upper_mid: Some(upper.tension),
            tension_lower_mid: Some(lower.tension),
            moment_upper_mid: Some(upper.moment),
            moment_lower_mid: Some(lower.moment),
            driver: Some(self.pulley(true)),
            driven: Some(self.pulley(false)),
            ..Summary::default()
        }
    }
}
