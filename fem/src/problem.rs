//! The typed FE problem: everything the solvers need from a scene, read once at one
//! boundary ([`FemProblem::from_scene`]) — geometry, the belt's section data, the effects
//! as typed flags and parameters, the driven load and the analysis. Solvers and analyses
//! receive a [`FemProblem`], never the raw [`drive::scene::Scene`]; the numerical options
//! stay in [`crate::FemOptions`], [`crate::SolverSettings`] and
//! [`crate::string_drive::DriveSettings`].

use drive::scene::{Analysis, Contact, Scene, Theory};

use crate::error::FemError;
use crate::options::{FemOptions, SolverSettings};
use crate::static_homotopy::StringHanging;

/// The Cosserat rod's default penalty is at least this times b₂²/a (N/m²): its penalty
/// layer √(b₂/P) is then ≤ √(a/b₂)/10. Below b₂ = √(κ EA a/R²)/10 (4.0e3 N on
/// `cosserat-hanging`) κ EA/R² is the larger and nothing changes. Measured on
/// `cosserat-hanging` at 512 elements against the BVP's contact arc, with P = κ EA/R²
/// (3.1e11) → this floor: b₂ = 2e4 N 0.29° → 0.009°, b₂ = 1e5 N 0.47° → 0.001° (the
/// error of κ EA/R² alone did not fall with the mesh: 113.0247° at 512, 1024 and 2048
/// elements against 112.5565°); a factor 10 left 0.025° at 1e5.
pub const SHEAR_PENALTY_FACTOR: f64 = 100.0;

/// Pulley geometry: two equal pulleys, centres on the x axis.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Geometry {
    /// Pulley radius R, m.
    pub radius: f64,
    /// Centre distance H, m.
    pub centre_distance: f64,
}

/// Section data of the belt.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BeltSection {
    /// Belt theory (the formulation must discretise it).
    pub theory: Theory,
    /// Unstretched length L, m.
    pub length: f64,
    /// EA, N.
    pub axial_stiffness: f64,
    /// ρ, kg/m.
    pub mass_per_length: f64,
    /// EI, N·m²; `Some` only for a Kirchhoff or Cosserat rod (a string's EI is ignored).
    pub bending_stiffness: Option<f64>,
    /// Shear stiffness b₂, N; `Some` only for a Cosserat rod (`belt.shear_stiffness`,
    /// read by the Cosserat elements, docs/fem-cosserat.md).
    pub shear_stiffness: Option<f64>,
}

/// The contact law between belt and pulleys.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactLaw {
    /// Normal penalty contact only.
    Frictionless,
    /// Coulomb friction with coefficient μ.
    Coulomb {
        /// μ ≥ 0.
        mu: f64,
    },
    /// Elastic interlayer of the shell (P, P_⊥ in N/m³); no MEL model yet.
    ElasticLayer {
        /// P.
        normal: f64,
        /// P_⊥.
        tangential: f64,
    },
}

/// The effects the scene calls for, as typed flags and parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EffectSet {
    /// g, m/s² (`None` = no gravity term at all).
    pub gravity: Option<f64>,
    /// Persistent transport inertia (ρc² terms).
    pub inertia: bool,
    /// Contact law.
    pub contact: ContactLaw,
}

/// The drive's motion and load.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DriveLoad {
    /// ω₁, rad/s (clockwise positive).
    pub driver_speed: f64,
    /// M₂, N·m.
    pub driven_torque: f64,
    /// d₂, N·m·s.
    pub driven_damping: f64,
}

/// The typed FE problem of a scene.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FemProblem {
    /// Pulleys.
    pub geometry: Geometry,
    /// Belt section.
    pub belt: BeltSection,
    /// Effects.
    pub effects: EffectSet,
    /// Driver motion and driven load.
    pub drive: DriveLoad,
    /// Analysis kind.
    pub analysis: Analysis,
    /// The open ends of a one-pulley scene (docs/fem-cosserat.md §12); `None` for the
    /// loop. The geometry's centre distance is then
    /// D: the open contour is the loop's of H = D without its second arc.
    pub open: Option<crate::string_drive::steady::OpenEnds>,
}

impl FemProblem {
    /// The one place the FE code reads a scene's physical data.
    pub fn from_scene(scene: &Scene) -> FemProblem {
        let b = &scene.belt;
        let dr = &scene.drive;
        let open = match (dr.layout, dr.end_distance, dr.transport_rate, dr.tension_in, dr.tension_out) {
            (drive::scene::Layout::OnePulley, Some(end_distance), Some(transport_rate), tension_in, tension_out) => Some(crate::string_drive::steady::OpenEnds { end_distance, transport_rate, tension_in, tension_out, pulley_speed: dr.pulley_speed, stick_slip_angle: dr.stick_slip_angle, belt_drives_pulley: dr.belt_drives_pulley == Some(true) }),
            _ => None,
        };
        FemProblem {
            geometry: Geometry { radius: scene.drive.pulley_radius, centre_distance: open.map_or(scene.drive.centre_distance, |o| o.end_distance) },
            belt: BeltSection {
                theory: b.theory,
                length: b.length,
                axial_stiffness: b.axial_stiffness,
                mass_per_length: b.mass_per_length,
                bending_stiffness: match b.theory {
                    Theory::Kirchhoff | Theory::Cosserat => b.bending_stiffness,
                    _ => None,
                },
                shear_stiffness: match b.theory {
                    Theory::Cosserat => b.shear_stiffness,
                    _ => None,
                },
            },
            effects: EffectSet {
                gravity: scene.effects.gravity,
                inertia: scene.effects.inertia == Some(true),
                contact: match &scene.effects.contact {
                    Contact::Frictionless => ContactLaw::Frictionless,
                    Contact::Coulomb(mu) => ContactLaw::Coulomb { mu: *mu },
                    Contact::ElasticLayer(l) => ContactLaw::ElasticLayer { normal: l.normal_stiffness, tangential: l.tangential_stiffness },
                },
            },
            drive: DriveLoad {
                driver_speed: scene.drive.driver_speed,
                driven_torque: scene.drive.driven_torque,
                driven_damping: scene.drive.driven_damping,
            },
            analysis: scene.analysis,
            open,
        }
    }

    /// Weight per length ρg, N/m (`None` without gravity).
    pub fn weight(&self) -> Option<f64> {
        self.effects.gravity.map(|g| g * self.belt.mass_per_length)
    }

    /// The normal penalty P: `opts.penalty`, or κ EA/R² (docs/fem-string.md §9) — for a
    /// Cosserat rod at least [`SHEAR_PENALTY_FACTOR`]·b₂²/a, so that the penalty layer
    /// √(b₂/P) at a contact edge stays a tenth of the shear layer √(a/b₂) that carries the
    /// edge pressure peak (docs/fem-cosserat.md §9.6).
    pub fn penalty(&self, opts: &FemOptions, settings: &SolverSettings) -> f64 {
        let r = self.geometry.radius;
        let axial = settings.penalty_factor * self.belt.axial_stiffness / (r * r);
        let shear = match (self.belt.shear_stiffness, self.belt.bending_stiffness) {
            (Some(b2), Some(a)) => SHEAR_PENALTY_FACTOR * b2 * b2 / a,
            _ => 0.0,
        };
        opts.penalty.unwrap_or(axial.max(shear))
    }

    /// True for a friction drive of a string (analysis steady or transient, Coulomb
    /// contact) — the problems [`crate::string_drive`] solves.
    pub fn is_string_drive(&self) -> bool {
        matches!(self.belt.theory, Theory::String)
            && matches!(self.analysis, Analysis::Steady | Analysis::Transient)
            && matches!(self.effects.contact, ContactLaw::Coulomb { .. })
    }

    /// True for the steady friction drive of a Cosserat rod (analysis steady, Coulomb
    /// contact) — the problem [`crate::string_drive::steady`] solves with the Cosserat
    /// element (docs/fem-cosserat.md §7).
    pub fn is_cosserat_steady_drive(&self) -> bool {
        matches!(self.belt.theory, Theory::Cosserat) && matches!(self.analysis, Analysis::Steady) && matches!(self.effects.contact, ContactLaw::Coulomb { .. })
    }

    /// True for a one-pulley scene (open ends; docs/fem-cosserat.md §12).
    pub fn is_one_pulley(&self) -> bool {
        self.open.is_some()
    }

    /// True for the static string, Kirchhoff or Cosserat rod on frictionless pulleys.
    pub fn is_static_hanging(&self) -> bool {
        matches!(self.belt.theory, Theory::String | Theory::Kirchhoff | Theory::Cosserat)
            && matches!(self.analysis, Analysis::Static)
            && matches!(self.effects.contact, ContactLaw::Frictionless)
            && self.drive.driver_speed == 0.0
            && self.drive.driven_torque == 0.0
            && !self.effects.inertia
    }

    /// The static frictionless problem of this belt at penalty `penalty` (the string's
    /// or the rod's, by the belt theory) — the static analysis and the drives' start.
    pub fn hanging(&self, penalty: f64) -> StringHanging {
        StringHanging { geometry: self.geometry, belt: self.belt, gravity: self.effects.gravity, penalty: Some(penalty) }
    }

    /// The static problem with the penalty resolved.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] unless [`FemProblem::is_static_hanging`].
    pub fn static_data(&self, opts: &FemOptions, settings: &SolverSettings) -> Result<StringHanging, FemError> {
        if !self.is_static_hanging() {
            return Err(FemError::Unsupported(format!(
                "theory {}, analysis {}, contact {:?}: only the static string, Kirchhoff and Cosserat rod on frictionless pulleys (string-hanging, rod-hanging, cosserat-hanging) have an MEL model so far",
                self.belt.theory,
                self.analysis,
                self.effects.contact
            )));
        }
        Ok(self.hanging(self.penalty(opts, settings)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = r#"{"name": "t", "description": "",
        "drive": {"pulley_radius": 0.1, "centre_distance": 0.5, "driver_speed": 10.0, "driven_torque": 2.0, "driven_damping": 0.1},
        "belt": {"theory": "string", "length": 1.3, "axial_stiffness": 2.0e4, "mass_per_length": 0.2},
        "effects": {"gravity": 9.81, "inertia": true, "contact": {"coulomb": 0.4}},
        "analysis": "steady"}"#;

    #[test]
    fn reads_the_scene_into_typed_fields() {
        let scene = Scene::from_json_str(SCENE).unwrap();
        let p = FemProblem::from_scene(&scene);
        assert_eq!(p.geometry, Geometry { radius: 0.1, centre_distance: 0.5 });
        assert_eq!(p.belt.bending_stiffness, None);
        assert_eq!(p.belt.shear_stiffness, None);
        assert_eq!((p.belt.length, p.belt.axial_stiffness, p.belt.mass_per_length), (1.3, 2.0e4, 0.2));
        assert_eq!(p.effects.contact, ContactLaw::Coulomb { mu: 0.4 });
        assert!(p.effects.inertia);
        assert_eq!(p.drive, DriveLoad { driver_speed: 10.0, driven_torque: 2.0, driven_damping: 0.1 });
        assert_eq!(p.weight(), Some(9.81 * 0.2));
        assert!(p.is_string_drive());
        assert!(!p.is_static_hanging());
        let opts = FemOptions { elements: 64, formulation: crate::default_formulation().into(), penalty: None };
        assert_eq!(p.penalty(&opts, &SolverSettings::default()), SolverSettings::default().penalty_factor * 2.0e4 / (0.1 * 0.1));
        assert!(matches!(p.static_data(&opts, &SolverSettings::default()), Err(FemError::Unsupported(_))));
    }
}
