//! The common solution view of a `string-drive` BVP solution (σ lookup as in
//! `string_hanging::view`), with the stick and slip zones as contact states.

use drive::contour::Contour;
use drive::summary::{PulleySummary, Summary};
use drive::view::{ContactState, SolutionView};

use super::problem::*;
use super::{BeltPoint, StringDriveSolution};
use crate::sigma_map::SigmaMap;
use crate::string_hanging::view::wrap_angle;

impl StringDriveSolution {
    pub(super) fn build_sigma_map(&self) -> SigmaMap {
        let contour = Contour::new(self.data.radius, self.data.centre_distance).expect("validated geometry");
        SigmaMap::new(contour, &super::problem::SIDES, &self.solution, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        })
    }

    /// The belt point at contour coordinate σ, with its segment.
    pub fn at_sigma(&self, sigma: f64) -> (usize, BeltPoint) {
        let (k, xi) = self.sigma_map.locate(sigma, |k, xi| {
            let p = self.point(k, xi);
            [p.x, p.y]
        });
        (k, self.point(k, xi))
    }

    fn pulley_summary(&self, driver: bool) -> PulleySummary {
        let (a, t, b) = self.contact_angles(driver);
        PulleySummary {
            contact_arc: Some(a - b),
            contact_start: Some(wrap_angle(a)),
            contact_end: Some(wrap_angle(b)),
            stick_arc: Some(a - t),
            slip_arc: Some(t - b),
            torque: Some(self.torque(driver)),
            ..PulleySummary::default()
        }
    }
}

impl SolutionView for StringDriveSolution {
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
        // Per unit contour length: p / λ on the arc (belt centreline on the contour).
        let (_, pt) = self.at_sigma(sigma);
        Some(pt.pressure.map_or(0.0, |p| p / pt.stretch))
    }

    fn friction_traction(&self, sigma: f64) -> Option<f64> {
        // τ per unstretched length, + in the direction of travel = +σ (ω₁ ≥ 0, validated);
        // per unit contour length τ/λ, as the pressure.
        let (_, pt) = self.at_sigma(sigma);
        Some(pt.friction.map_or(0.0, |f| f / pt.stretch))
    }

    fn contact_state(&self, sigma: f64) -> ContactState {
        match self.at_sigma(sigma).0 {
            DRIVEN_STICK | DRIVER_STICK => ContactState::Stick,
            DRIVEN_SLIP | DRIVER_SLIP => ContactState::Slip,
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
            tension_tight: Some(self.point(DRIVER_STICK, 0.0).tension),
            tension_slack: Some(self.point(DRIVEN_STICK, 0.0).tension),
            driven_speed: Some(self.driven_speed()),
            transport_rate: Some(self.transport_rate()),
            driver: Some(self.pulley_summary(true)),
            driven: Some(self.pulley_summary(false)),
            ..Summary::default()
        }
    }
}
