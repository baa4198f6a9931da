//! The common solution view: the one interface through which the verification
//! harness reads a BVP solution and an FE solution (DESIGN.md "The common solution
//! view"), so that neither method can borrow the other's answer.
//!
//! Every field is a function of the contour coordinate σ along the solution's [`Path`]:
//! the closed two-pulley loop (σ any real, wrapped periodically with [`Contour::wrap`]) or
//! the open contour of a one-pulley scene (σ ∈ [0, 2D + πR] from the inflow end). "At σ"
//! means *the belt point on the contour normal at σ*: r(σ) = g(σ) + ν(σ) n_g(σ) (eq. 27),
//! whatever material point happens to be there. Units SI.

use serde::{Deserialize, Serialize};

use crate::contour::{Contour, Path};
use crate::result::Fields;
use crate::summary::Summary;

/// Contact state of the belt point at σ.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ContactState {
    /// Not touching a pulley (free span).
    Free,
    /// In frictionless contact (or contact without a stick/slip distinction, e.g. the
    /// elastic interlayer).
    Contact,
    /// In Coulomb contact, sticking.
    Stick,
    /// In Coulomb contact, sliding.
    Slip,
}

/// A solved belt, sampled at contour coordinates σ.
///
/// Methods returning `Option` give `None` for a quantity the model does not have
/// (e.g. the bending moment of a string) — never a made-up zero.
pub trait SolutionView {
    /// The contour the solution is parametrised on: the two-pulley loop or the open
    /// one-pulley contour.
    fn path(&self) -> Path;

    /// The two-pulley loop the solution lies on; `None` on the open contour of a
    /// one-pulley scene.
    fn contour(&self) -> Option<Contour> {
        self.path().as_loop().copied()
    }

    /// r(σ) = g(σ) + ν(σ) n_g(σ), m (eq. 27).
    fn position(&self, sigma: f64) -> [f64; 2];

    /// Axial force N(σ) (the tension, not the effective tension), N.
    fn axial_force(&self, sigma: f64) -> f64;

    /// Bending moment M(σ), N·m; `None` for a string.
    fn bending_moment(&self, sigma: f64) -> Option<f64>;

    /// Transverse (shear) force Q(σ), N; `None` for a string.
    fn transverse_force(&self, sigma: f64) -> Option<f64>;

    /// Normal contact pressure p(σ) ≥ 0: contact force per unit length of the
    /// contour, N/m; `Some(0.0)` on the free spans; `None` if the method has no
    /// distributed pressure (e.g. concentrated edge forces only).
    fn contact_pressure(&self, sigma: f64) -> Option<f64>;

    /// Tangential contact traction exerted by the pulley on the belt, N per metre of
    /// contour, positive in the direction of increasing σ; `Some(0.0)` on the free spans;
    /// `None` for a model without friction (the default).
    fn friction_traction(&self, _sigma: f64) -> Option<f64> {
        None
    }

    /// Contact state at σ.
    fn contact_state(&self, sigma: f64) -> ContactState;

    /// Cross-section rotation θ(σ), rad: the angle of the director e₁ from +x,
    /// counter-clockwise, continuous along the belt; `None` for a model without a section
    /// rotation of its own (the default; a string).
    fn rotation(&self, _sigma: f64) -> Option<f64> {
        None
    }

    /// Shear strain Γ₂(σ) = Q/b₂ (dimensionless) of a shear-deformable rod; `None` for an
    /// unshearable model (the default).
    fn shear_strain(&self, _sigma: f64) -> Option<f64> {
        None
    }

    /// Material coordinate s(σ), m: the unstretched arc length, from the material
    /// origin of the method, of the particle at σ (at the instant of the snapshot
    /// for moving belts); increases with σ by the belt length L per loop.
    fn material_coordinate(&self, sigma: f64) -> f64;

    /// Transverse deflection ν(σ), m (positive away from the pulleys). Default: the
    /// inverse map of [`Contour::sigma_nu`] applied to [`SolutionView::position`].
    fn deflection(&self, sigma: f64) -> f64 {
        self.path().sigma_nu(self.position(sigma)).1
    }

    /// Named scalars of the solution.
    fn summary(&self) -> Summary;
}

/// Samples a view at `n` equally spaced points σ_i = i·L/n, i = 0..n, L the length of
/// its [`Path`].
///
/// `moment` is present only if the view returns a moment at every sample (absent
/// for a string). `n = 0` gives empty fields.
pub fn sample_fields<V: SolutionView + ?Sized>(view: &V, n: usize) -> Fields {
    let l = view.path().length();
    let sigma: Vec<f64> = (0..n).map(|i| l * i as f64 / n as f64).collect();
    fields_at(view, sigma)
}

/// Samples a view at the given σ, in their order (`beltcheck reference --sigma`).
///
/// `moment` is present only if the view returns a moment at every σ (absent for a
/// string, and for no σ at all). On an open path (one-pulley scenes) and for a
/// shear-deformable rod (the Cosserat rod: a view with a shear strain) the fields of
/// issue 13 are written too — θ, Q, Γ₂, p, f_t and the contact state, each where the
/// view has it at every σ; the string's and the Kirchhoff rod's two-pulley results keep
/// their five fields (DESIGN's result format).
pub fn fields_at<V: SolutionView + ?Sized>(view: &V, sigma: Vec<f64>) -> Fields {
    let pos: Vec<[f64; 2]> = sigma.iter().map(|&s| view.position(s)).collect();
    let every = |f: &dyn Fn(f64) -> Option<f64>| -> Option<Vec<f64>> {
        if sigma.is_empty() {
            return None;
        }
        sigma.iter().map(|&s| f(s)).collect()
    };
    let extended = view.path().is_open() || sigma.first().is_some_and(|&s| view.shear_strain(s).is_some());
    let extra = |f: &dyn Fn(f64) -> Option<f64>| if extended { every(f) } else { None };
    Fields {
        x: pos.iter().map(|p| p[0]).collect(),
        y: pos.iter().map(|p| p[1]).collect(),
        tension: sigma.iter().map(|&s| view.axial_force(s)).collect(),
        moment: every(&|s| view.bending_moment(s)),
        rotation: extra(&|s| view.rotation(s)),
        transverse_force: extra(&|s| view.transverse_force(s)),
        shear_strain: extra(&|s| view.shear_strain(s)),
        pressure: extra(&|s| view.contact_pressure(s)),
        friction: extra(&|s| view.friction_traction(s)),
        state: (extended && !sigma.is_empty()).then(|| sigma.iter().map(|&s| view.contact_state(s)).collect()),
        sigma,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A belt lying on the contour with constant tension (the tight, gravity-free
    /// string): ν = 0, N = T, pressure T/R on the arcs.
    struct Tight {
        contour: Contour,
        tension: f64,
        rod: bool,
    }

    impl SolutionView for Tight {
        fn path(&self) -> Path {
            Path::Loop(self.contour)
        }
        fn position(&self, sigma: f64) -> [f64; 2] {
            self.contour.position(sigma, 0.0)
        }
        fn axial_force(&self, _: f64) -> f64 {
            self.tension
        }
        fn bending_moment(&self, _: f64) -> Option<f64> {
            self.rod.then_some(0.0)
        }
        fn transverse_force(&self, _: f64) -> Option<f64> {
            self.rod.then_some(0.0)
        }
        fn contact_pressure(&self, sigma: f64) -> Option<f64> {
            Some(self.tension * self.contour.alpha(sigma))
        }
        fn contact_state(&self, sigma: f64) -> ContactState {
            if self.contour.region(sigma).is_polar() {
                ContactState::Contact
            } else {
                ContactState::Free
            }
        }
        fn material_coordinate(&self, sigma: f64) -> f64 {
            sigma
        }
        fn summary(&self) -> Summary {
            Summary {
                tension_upper_mid: Some(self.tension),
                ..Default::default()
            }
        }
    }

    #[test]
    fn sampling() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let string = Tight {
            contour,
            tension: 10.0,
            rod: false,
        };
        let f = sample_fields(&string, 64);
        assert_eq!(f.len(), 64);
        assert!(f.moment.is_none());
        f.check().unwrap();
        assert_eq!(f.sigma[0], 0.0);
        assert!(f.sigma[63] < contour.length());
        assert!((f.x[0] + 0.225).abs() < 1e-15 && (f.y[0] - 0.08).abs() < 1e-15);
        assert!(string.deflection(1.0).abs() < 1e-14);

        let rod = Tight {
            contour,
            tension: 10.0,
            rod: true,
        };
        let dynamic: &dyn SolutionView = &rod;
        let f = sample_fields(dynamic, 8);
        assert_eq!(f.moment.as_ref().map(Vec::len), Some(8));

        let f = sample_fields(&rod, 0);
        assert!(f.is_empty() && f.moment.is_none());
    }
}
