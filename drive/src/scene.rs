//! The scene: drive geometry, belt, effects, analysis and solver settings, exactly
//! the JSON format of DESIGN.md ("Scene format"), validated.
//!
//! Units are SI throughout. Reading a scene ([`Scene::from_json_str`],
//! [`Scene::from_path`]) runs three stages, each failing with a [`SceneError`] that
//! names the field path:
//! 1. JSON syntax;
//! 2. the schema walk: unknown keys at every level (with the nearest valid name
//!    suggested), missing required fields, wrong JSON types, unknown enumeration
//!    values; `null` for an optional field means "absent";
//! 3. [`Scene::validate`]: finiteness, signs and ranges, geometry, and the
//!    compatibility of theory, effects and analysis (rules below).
//!
//! # Compatibility rules (checked by [`Scene::validate`])
//! - theory `string`: `bending_stiffness` and `shear_stiffness` absent (or `null`);
//! - theory `kirchhoff`: `bending_stiffness` required (> 0), `shear_stiffness` absent;
//! - theory `cosserat`: both required (> 0);
//! - theory `shell` (Kirchhoff–Love, unshearable): `bending_stiffness` required,
//!   `shear_stiffness` absent;
//! - contact `elastic_layer`: theory `shell` only;
//! - analysis `static`: no motion, so `driver_speed`, `driven_torque` and
//!   `driven_damping` must be 0, `inertia` must not be `true`, and Coulomb friction is
//!   rejected — the friction forces of a belt at rest are statically indeterminate,
//!   so friction needs analysis `steady` or `transient`;
//! - analysis `steady`: the belt is driven through the contact, so contact must be
//!   `coulomb` (or `elastic_layer` for a shell); frictionless contact leaves the belt
//!   speed undetermined;
//! - analysis `transient`: solved by finite elements only, so no `bvp` block.
//!
//! Geometry: R > 0, H > 2R (the pulleys must not overlap), belt length L > 0. A belt
//! shorter than the contour (L < 2H + 2πR, stretched on) is valid: it is a hard case,
//! not an error; so is a very slack belt.

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::contour::Contour;
use crate::error::SceneError;
use crate::result::FIELD_NORM_NAMES;
use crate::suggest::nearest;
use crate::summary::SCALAR_NAMES;

/// A complete scene (one JSON file of the catalogue).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Identifier, used for report file names: non-empty, only ASCII letters,
    /// digits, `-`, `_`, `.`. Required.
    pub name: String,
    /// Free text for reports. Optional, default empty.
    #[serde(default)]
    pub description: String,
    /// Pulleys and loads. Required.
    pub drive: DriveGeometry,
    /// The belt's structural theory and stiffnesses. Required.
    pub belt: Belt,
    /// The effects to simulate (absent = not simulated). Required.
    pub effects: Effects,
    /// Static, steady motion, or transient. Required.
    pub analysis: Analysis,
    /// BVP solver settings. Optional; absent = [`BvpSettings::default`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bvp: Option<BvpSettings>,
    /// Finite element settings. Optional; absent = [`FemSettings::default`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fem: Option<FemSettings>,
    /// CI gate tolerances. Optional; absent = [`GateSettings::default`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gate: Option<GateSettings>,
    /// Published results of another code for this scene, shown beside ours in the
    /// report (never gated). Optional; absent = no peer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peer: Option<Peer>,
}

/// Published results of another code for the same physical drive (`peer` block): the
/// report tabulates them beside the BVP reference with the relative difference. They are
/// documentation, not a reference: models differ (friction law, bending, transient), so
/// the gate never uses them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Peer {
    /// Who computed them and how (code, model, discretisation, instant). Required,
    /// non-empty.
    pub source: String,
    /// Where they are published (URL or citation). Optional.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub reference: String,
    /// Summary scalar name ([`crate::summary::SCALAR_NAMES`]) → published value, in this
    /// project's units and signs. Required, non-empty, finite values.
    pub values: BTreeMap<String, f64>,
    /// Why the results should differ. Optional.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
}

impl Peer {
    /// Checks (paths `peer.*`): non-empty source and values, every name a summary scalar
    /// (nearest suggested), every value finite.
    ///
    /// # Errors
    /// The first violation.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.source.trim().is_empty() {
            return Err(SceneError::Invalid { path: "peer.source".into(), reason: "must not be empty".into() });
        }
        if self.values.is_empty() {
            return Err(SceneError::Invalid { path: "peer.values".into(), reason: "must name at least one summary quantity".into() });
        }
        for (name, &v) in &self.values {
            let path = format!("peer.values.{name}");
            if !SCALAR_NAMES.iter().any(|k| k == name) {
                return Err(SceneError::UnknownField {
                    path,
                    suggestion: nearest(name, SCALAR_NAMES.iter().copied()),
                    allowed: SCALAR_NAMES.iter().map(|k| k.to_string()).collect(),
                });
            }
            check_finite(&path, v)?;
        }
        Ok(())
    }
}

/// Pulley geometry and the loads of the drive (`drive` block).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveGeometry {
    /// R, m, > 0: radius of both pulleys *to the belt centreline*. Required.
    pub pulley_radius: f64,
    /// H, m, > 2R: distance of the pulley centres (−H/2, 0) and (+H/2, 0). Required.
    pub centre_distance: f64,
    /// ω₁, rad/s, finite, clockwise positive (the upper span moves in +x); must be 0
    /// in a static analysis. Required.
    pub driver_speed: f64,
    /// M₂, N·m, finite: torque resisting the motion of the driven pulley; must be 0
    /// in a static analysis. Required.
    pub driven_torque: f64,
    /// d₂, N·m·s, ≥ 0: viscous resistance of the driven pulley, resisting torque
    /// d₂·ω₂ in addition to M₂; must be 0 in a static analysis. Optional, default 0.
    #[serde(default)]
    pub driven_damping: f64,
}

/// Structural theory of the belt (`belt.theory`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Theory {
    /// Extensible string: axial stiffness only (`"string"`).
    String,
    /// Kirchhoff rod: extensible, unshearable (`"kirchhoff"`); needs EI.
    Kirchhoff,
    /// Cosserat rod: extensible, shear-deformable (`"cosserat"`); needs EI and GA.
    Cosserat,
    /// Kirchhoff–Love shell (`"shell"`, Paper E); needs EI.
    Shell,
}

impl Theory {
    /// The JSON spelling.
    pub fn name(self) -> &'static str {
        match self {
            Theory::String => "string",
            Theory::Kirchhoff => "kirchhoff",
            Theory::Cosserat => "cosserat",
            Theory::Shell => "shell",
        }
    }
}

impl fmt::Display for Theory {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The belt (`belt` block). Stiffnesses are of the whole cross-section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Belt {
    /// Structural theory. Required.
    pub theory: Theory,
    /// L, m, > 0: unstretched length of the closed belt. Required. May be shorter
    /// than the contour 2H + 2πR (stretched on).
    pub length: f64,
    /// EA, N, > 0: axial stiffness, N = EA·(λ − 1). Required.
    pub axial_stiffness: f64,
    /// EI, N·m², > 0: bending stiffness, M = EI·κ. Required for `kirchhoff`,
    /// `cosserat`, `shell`; absent or `null` for `string`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    /// GA, N, > 0: shear stiffness, Q = GA·γ. Required for `cosserat`; absent or
    /// `null` otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_stiffness: Option<f64>,
    /// ρ, kg/m, > 0: mass per unit unstretched length. Required.
    pub mass_per_length: f64,
}

/// Contact model between belt and pulleys (`effects.contact`).
///
/// JSON: `"frictionless"`, `{"coulomb": μ}`, or
/// `{"elastic_layer": {"normal_stiffness": P, "tangential_stiffness": P_t}}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Contact {
    /// Normal contact only: no tangential unknowns, no stick/slip segments.
    Frictionless,
    /// Coulomb dry friction with coefficient μ ≥ 0 (dimensionless); needs analysis
    /// `steady` or `transient`.
    Coulomb(f64),
    /// Elastic interlayer of the drums (§6.2, eqs. 40–41); theory `shell` only.
    ElasticLayer(ElasticLayer),
}

/// Stiffness coefficients of the elastic interlayer, eq. (40) of the reference:
/// V_γ = ½∬ P γ² J dσ dζ, V_⊥ = ½∬ P_⊥ u·u J dσ dζ.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticLayer {
    /// P, N/m³ (pressure per penetration), > 0. Required.
    pub normal_stiffness: f64,
    /// P_⊥, N/m³ (shear traction per tangential displacement), > 0. Required.
    pub tangential_stiffness: f64,
}

/// The effects a scene calls for (`effects` block); absent = not simulated.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Effects {
    /// g, m/s², ≥ 0, acting in −y. Optional; absent = no gravity term at all (a
    /// present 0 keeps the term with g = 0, the degenerate-sag hard case).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<f64>,
    /// `true`: persistent transport inertia of steady motion (ρc² terms). Optional;
    /// absent or `false` = none; `true` is rejected in a static analysis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<bool>,
    /// Contact model. Required.
    pub contact: Contact,
}

/// Kind of analysis (`analysis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Analysis {
    /// Equilibrium at rest (`"static"`).
    Static,
    /// Steady motion: stationary shape, constant transport rate (`"steady"`).
    Steady,
    /// Time stepping, quasistatic or dynamic (`"transient"`); FE only.
    Transient,
}

impl Analysis {
    /// The JSON spelling.
    pub fn name(self) -> &'static str {
        match self {
            Analysis::Static => "static",
            Analysis::Steady => "steady",
            Analysis::Transient => "transient",
        }
    }
}

impl fmt::Display for Analysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// BVP solution method (`bvp.method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum BvpMethod {
    /// Collocation with residual control and mesh adaptation (`"bvp-collocation"`).
    #[default]
    #[serde(rename = "bvp-collocation")]
    Collocation,
    /// Multiple shooting on an adaptive ODE integrator (`"bvp-shooting"`).
    #[serde(rename = "bvp-shooting")]
    Shooting,
}

impl BvpMethod {
    /// The JSON spelling, also the `method` of a result.
    pub fn name(self) -> &'static str {
        match self {
            BvpMethod::Collocation => "bvp-collocation",
            BvpMethod::Shooting => "bvp-shooting",
        }
    }
}

/// Settings of the BVP reference (`bvp` block). Every field optional.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BvpSettings {
    /// Method. Default `"bvp-collocation"`.
    #[serde(default)]
    pub method: BvpMethod,
    /// Relative tolerance of the solution, 0 < tol < 1; its exact norm is defined by
    /// the `bvp` crate (collocation: residual of the collocation equations relative
    /// to 1 + |f|, as scipy's `solve_bvp` `tol`; shooting: the integrator's local
    /// relative tolerance). Default 1e-8.
    #[serde(default = "BvpSettings::default_tolerance")]
    pub tolerance: f64,
    /// Collocation scheme, e.g. `"gauss6"`; the name is validated by the `bvp`
    /// crate; unused by shooting. Non-empty. Default `"gauss6"`.
    #[serde(default = "BvpSettings::default_scheme")]
    pub scheme: String,
    /// Maximum mesh nodes of collocation before it gives up, ≥ 4. Default 20000.
    #[serde(default = "BvpSettings::default_max_nodes")]
    pub max_nodes: usize,
    /// Intervals of multiple shooting per segment, ≥ 1. Default 8.
    #[serde(default = "BvpSettings::default_shooting_intervals")]
    pub shooting_intervals: usize,
}

impl BvpSettings {
    fn default_tolerance() -> f64 {
        1e-8
    }
    fn default_scheme() -> String {
        "gauss6".to_string()
    }
    fn default_max_nodes() -> usize {
        20_000
    }
    fn default_shooting_intervals() -> usize {
        8
    }
}

impl Default for BvpSettings {
    fn default() -> Self {
        BvpSettings {
            method: BvpMethod::default(),
            tolerance: Self::default_tolerance(),
            scheme: Self::default_scheme(),
            max_nodes: Self::default_max_nodes(),
            shooting_intervals: Self::default_shooting_intervals(),
        }
    }
}

/// Settings of the finite element runs (`fem` block). Every field optional.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FemSettings {
    /// Number of elements round the loop for a single run, ≥ 4 (element boundaries
    /// coincide with the four region transitions). Default 256.
    #[serde(default = "FemSettings::default_elements")]
    pub elements: usize,
    /// Element counts of a convergence study, each ≥ 4, strictly increasing.
    /// Default empty = [`FemSettings::meshes`] derives elements/4, elements/2,
    /// elements.
    #[serde(default)]
    pub mesh_sequence: Vec<usize>,
    /// Names of the element formulations to run (validated by the `fem` crate);
    /// non-empty names, no repeats. Default empty = every built-in formulation that
    /// fits the theory.
    #[serde(default)]
    pub formulations: Vec<String>,
    /// Contact penalty factor P_γ (§6.1, Table 1), N/m² for rods (force per length
    /// per penetration), > 0. Default absent = the `fem` crate scales it from the
    /// belt stiffness.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
    /// Time step Δt of the quasistatic transient (analyses `steady`, `transient`), s,
    /// positive and finite. Default absent = the `fem` crate chooses it (the driver
    /// surface moves by one arc element per step; docs/fem-drive.md §7).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_step: Option<f64>,
    /// Largest number of time steps of the transient, ≥ 1. Default absent = the `fem`
    /// crate's default (4000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<usize>,
    /// Steady-state threshold: largest scaled change of the primary unknowns per radian
    /// of driver rotation (docs/fem-drive.md §7), 0 < tol < 1. Default absent = 1e-6.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady_tolerance: Option<f64>,
}

impl FemSettings {
    fn default_elements() -> usize {
        256
    }

    /// The element counts of a convergence study: `mesh_sequence` if given, else
    /// [elements/4, elements/2, elements] (halving h), dropping counts below 4.
    pub fn meshes(&self) -> Vec<usize> {
        if !self.mesh_sequence.is_empty() {
            return self.mesh_sequence.clone();
        }
        let mut m: Vec<usize> = [self.elements / 4, self.elements / 2, self.elements]
            .into_iter()
            .filter(|&n| n >= 4)
            .collect();
        m.dedup();
        m
    }
}

impl Default for FemSettings {
    fn default() -> Self {
        FemSettings {
            elements: Self::default_elements(),
            mesh_sequence: Vec::new(),
            formulations: Vec::new(),
            penalty: None,
            time_step: None,
            max_steps: None,
            steady_tolerance: None,
        }
    }
}

/// Settings of the CI gate (`gate` block). Every field optional.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GateSettings {
    /// Quantity name → admissible relative error |q − q_ref| / |q_ref| (> 0) against
    /// the tightest BVP reference. Names: the summary scalars
    /// ([`crate::summary::SCALAR_NAMES`], e.g. `y_upper_mid`, `driver.contact_arc`)
    /// and the field norms ([`crate::result::FIELD_NORM_NAMES`]). Default empty =
    /// nothing gated by value.
    #[serde(default)]
    pub tolerances: BTreeMap<String, f64>,
    /// Limits for the BVP methods (collocation and shooting at the gate's tolerance)
    /// where they should be held tighter than the FE: quantity name → admissible
    /// relative error, same names and ranges as `tolerances`. A quantity listed here
    /// replaces its `tolerances` limit for the BVP methods only; absent = the BVP methods
    /// are held to `tolerances`. Default empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub bvp_tolerances: BTreeMap<String, f64>,
    /// Minimum observed order of convergence p of the FE studies, > 0. Default
    /// absent = order not gated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_order: Option<f64>,
}

// ---------------------------------------------------------------------------
// Reading, writing, validating

/// Largest driver rotation per transient time step, rad (`fem.time_step` × |ω₁|):
/// π/4, so that a contact arc (≤ π) takes at least four steps to pass.
pub const MAX_STEP_ANGLE: f64 = std::f64::consts::FRAC_PI_4;

/// Largest FE element count (`fem.elements`, `fem.mesh_sequence`, the CLI's
/// `--elements`): the cost of a steady drive grows with the square of the elements, and
/// 16384 elements already take minutes.
pub const MAX_ELEMENTS: usize = 16_384;

/// Longest scene name, bytes (the name is a directory and file name of `report`; file
/// systems allow 255).
pub const MAX_NAME_LEN: usize = 100;

impl Scene {
    /// Parses and validates a scene from JSON text.
    ///
    /// # Errors
    /// The first problem found, naming its field path (see [`SceneError`]).
    pub fn from_json_str(text: &str) -> Result<Scene, SceneError> {
        let mut value = crate::schema::parse_strict(text)?;
        crate::schema::check_scene(&mut value)?;
        let scene: Scene = serde_json::from_value(value)
            // unreachable after the schema walk; kept as an error, not a panic
            .map_err(|e| SceneError::Invalid {
                path: "<scene>".into(),
                reason: e.to_string(),
            })?;
        scene.validate()?;
        Ok(scene)
    }

    /// Reads, parses and validates a scene file.
    ///
    /// # Errors
    /// [`SceneError::Io`] if the file cannot be read, else as
    /// [`Scene::from_json_str`].
    pub fn from_path(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Scene::from_json_str(&text)
    }

    /// Pretty JSON of the scene; [`Scene::from_json_str`] reads it back to an equal
    /// scene. Absent optional fields are omitted; settings blocks that are present
    /// are written with all their (default-filled) fields, for reproducibility.
    pub fn to_json_pretty(&self) -> String {
        // Serialising these plain structs cannot fail (string keys only).
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Checks values, geometry and the compatibility rules of the module docs.
    /// Called by the readers; call it after building or editing a scene in code.
    ///
    /// # Errors
    /// The first violation, naming its field path and the numbers.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_name()?;
        self.validate_drive()?;
        self.validate_belt()?;
        self.validate_effects()?;
        self.validate_analysis()?;
        if let Some(b) = &self.bvp {
            b.validate()?;
        }
        if let Some(f) = &self.fem {
            f.validate()?;
            self.validate_time_step(f)?;
        }
        if let Some(g) = &self.gate {
            g.validate()?;
        }
        if let Some(p) = &self.peer {
            p.validate()?;
        }
        Ok(())
    }

    fn validate_name(&self) -> Result<(), SceneError> {
        if self.name.is_empty() {
            return Err(SceneError::Invalid {
                path: "name".into(),
                reason: "must not be empty".into(),
            });
        }
        let shown = crate::error::clip(&self.name);
        if let Some(c) = self
            .name
            .chars()
            .find(|c| !(c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.')))
        {
            return Err(SceneError::Invalid {
                path: "name".into(),
                reason: format!(
                    "{shown:?} contains {c:?}: only ASCII letters, digits, `-`, `_` and `.` are allowed (the name is used for report file names)",
                ),
            });
        }
        if self.name.starts_with('.') {
            return Err(SceneError::Invalid {
                path: "name".into(),
                reason: format!(
                    "{shown:?} starts with `.`: the name is a report directory name, and `.`, `..` or a hidden name would write outside it or out of sight"
                ),
            });
        }
        if self.name.len() > MAX_NAME_LEN {
            return Err(SceneError::Invalid {
                path: "name".into(),
                reason: format!(
                    "{shown:?} has {} characters, at most {MAX_NAME_LEN} are allowed (the name is used for report file names)",
                    self.name.len()
                ),
            });
        }
        Ok(())
    }

    /// The driver turns at most [`MAX_STEP_ANGLE`] per transient time step.
    fn validate_time_step(&self, f: &FemSettings) -> Result<(), SceneError> {
        let Some(dt) = f.time_step else { return Ok(()) };
        let angle = self.drive.driver_speed.abs() * dt;
        if angle > MAX_STEP_ANGLE {
            return Err(SceneError::OutOfRange {
                path: "fem.time_step".into(),
                value: dt,
                range: format!(
                    "the driver turns |ω₁|·Δt = {} rad per step, at most {} rad (π/4) are allowed so that the friction fronts move by a fraction of an arc per step: Δt ≤ {} s",
                    crate::error::num(&angle),
                    crate::error::num(&MAX_STEP_ANGLE),
                    crate::error::num(&(MAX_STEP_ANGLE / self.drive.driver_speed.abs()))
                ),
            });
        }
        Ok(())
    }

    fn validate_drive(&self) -> Result<(), SceneError> {
        let d = &self.drive;
        Contour::new(d.pulley_radius, d.centre_distance)?;
        check_finite("drive.driver_speed", d.driver_speed)?;
        check_finite("drive.driven_torque", d.driven_torque)?;
        check_non_negative("drive.driven_damping", d.driven_damping)?;
        Ok(())
    }

    fn validate_belt(&self) -> Result<(), SceneError> {
        let b = &self.belt;
        check_positive("belt.length", b.length)?;
        check_positive("belt.axial_stiffness", b.axial_stiffness)?;
        check_positive("belt.mass_per_length", b.mass_per_length)?;
        let theory = b.theory;
        match (theory, b.bending_stiffness) {
            (Theory::String, Some(v)) => {
                return Err(SceneError::NotAllowed {
                    path: "belt.bending_stiffness".into(),
                    reason: format!(
                        "theory `string` has no bending stiffness (got {} N·m²); set it to null, or use theory `kirchhoff`",
                        crate::error::num(&v)
                    ),
                })
            }
            (Theory::String, None) => {}
            (_, None) => {
                return Err(SceneError::Required {
                    path: "belt.bending_stiffness".into(),
                    reason: format!("for theory `{theory}` (bending stiffness EI, N·m², > 0)"),
                })
            }
            (_, Some(v)) => check_positive("belt.bending_stiffness", v)?,
        }
        match (theory, b.shear_stiffness) {
            (Theory::Cosserat, None) => {
                return Err(SceneError::Required {
                    path: "belt.shear_stiffness".into(),
                    reason: "for theory `cosserat` (shear stiffness GA, N, > 0)".into(),
                })
            }
            (Theory::Cosserat, Some(v)) => check_positive("belt.shear_stiffness", v)?,
            (_, None) => {}
            (_, Some(v)) => {
                let why = match theory {
                    Theory::String => "theory `string` has no shear stiffness",
                    Theory::Shell => "the Kirchhoff–Love shell (theory `shell`) is unshearable",
                    _ => "the Kirchhoff rod (theory `kirchhoff`) is unshearable",
                };
                return Err(SceneError::NotAllowed {
                    path: "belt.shear_stiffness".into(),
                    reason: format!(
                        "{why} (got {} N); set it to null, or use theory `cosserat`",
                        crate::error::num(&v)
                    ),
                });
            }
        }
        Ok(())
    }

    fn validate_effects(&self) -> Result<(), SceneError> {
        let e = &self.effects;
        if let Some(g) = e.gravity {
            check_non_negative("effects.gravity", g)?;
        }
        match &e.contact {
            Contact::Frictionless => {}
            Contact::Coulomb(mu) => check_non_negative("effects.contact.coulomb", *mu)?,
            Contact::ElasticLayer(layer) => {
                check_positive(
                    "effects.contact.elastic_layer.normal_stiffness",
                    layer.normal_stiffness,
                )?;
                check_positive(
                    "effects.contact.elastic_layer.tangential_stiffness",
                    layer.tangential_stiffness,
                )?;
                if self.belt.theory != Theory::Shell {
                    return Err(SceneError::NotAllowed {
                        path: "effects.contact".into(),
                        reason: format!(
                            "the elastic interlayer contact model is for theory `shell` only (theory is `{}`); use \"frictionless\" or {{\"coulomb\": μ}}",
                            self.belt.theory
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    fn validate_analysis(&self) -> Result<(), SceneError> {
        let e = &self.effects;
        if self.analysis != Analysis::Static {
            // One rule for both methods (issue 12, "four quadrants"): the BVP refused these
            // and the FE either refused them with a misleading message (speed) or solved
            // them (torque). Neither sense is modelled by both yet, so both refuse here.
            let d = &self.drive;
            for (field, value, unit, what) in [
                ("drive.driver_speed", d.driver_speed, "rad/s", "a driver turning counter-clockwise (the upper span becomes the tight one; with gravity not the mirror image of the clockwise drive)"),
                ("drive.driven_torque", d.driven_torque, "N·m", "a load that drives (the slip zones swap pulleys)"),
            ] {
                if value < 0.0 {
                    return Err(SceneError::NotAllowed {
                        path: field.into(),
                        reason: format!(
                            "must be ≥ 0 (got {} {unit}): {what} is not modelled yet by either method; without gravity, mirror the scene",
                            crate::error::num(&value)
                        ),
                    });
                }
            }
        }
        match self.analysis {
            Analysis::Static => {
                if e.inertia == Some(true) {
                    return Err(SceneError::NotAllowed {
                        path: "effects.inertia".into(),
                        reason: "transport inertia needs analysis `steady` or `transient` (analysis is `static`)".into(),
                    });
                }
                if let Contact::Coulomb(mu) = e.contact {
                    return Err(SceneError::NotAllowed {
                        path: "effects.contact".into(),
                        reason: format!(
                            "friction needs analysis `steady` or `transient` (analysis is `static`, contact is {{\"coulomb\": {}}}): the friction forces of a belt at rest are statically indeterminate",
                            crate::error::num(&mu)
                        ),
                    });
                }
                let d = &self.drive;
                for (field, value, unit) in [
                    ("drive.driver_speed", d.driver_speed, "rad/s"),
                    ("drive.driven_torque", d.driven_torque, "N·m"),
                    ("drive.driven_damping", d.driven_damping, "N·m·s"),
                ] {
                    if value != 0.0 {
                        return Err(SceneError::NotAllowed {
                            path: field.into(),
                            reason: format!(
                                "a static analysis has no motion and transmits no torque, so it must be 0 (got {} {unit}); use analysis `steady`",
                                crate::error::num(&value)
                            ),
                        });
                    }
                }
            }
            Analysis::Steady | Analysis::Transient if e.contact == Contact::Coulomb(0.0) => {
                return Err(SceneError::NotAllowed {
                    path: "effects.contact.coulomb".into(),
                    reason: format!(
                        "a {} drive transmits its torque through friction and needs μ > 0 (got μ = 0): with μ = 0 no torque reaches the driven pulley and its speed is undetermined",
                        self.analysis
                    ),
                });
            }
            Analysis::Steady => {
                if e.contact == Contact::Frictionless {
                    return Err(SceneError::NotAllowed {
                        path: "effects.contact".into(),
                        reason: "frictionless contact in a steady analysis: steady motion is driven through friction, so use {\"coulomb\": μ} (or `elastic_layer` for a shell); without friction the belt speed is undetermined".into(),
                    });
                }
            }
            Analysis::Transient => {
                if self.bvp.is_some() {
                    return Err(SceneError::NotAllowed {
                        path: "bvp".into(),
                        reason: "a transient analysis is solved by finite elements only (the BVP solves `static` and `steady`); remove the `bvp` block".into(),
                    });
                }
            }
        }
        Ok(())
    }

    // -----------------------------------------------------------------------
    // Derived quantities

    /// The compound contour g(σ) of this scene's pulleys (assumes a validated scene;
    /// an invalid one gives meaningless numbers, never a panic).
    pub fn contour(&self) -> Contour {
        Contour::new_unchecked(self.drive.pulley_radius, self.drive.centre_distance)
    }

    /// L_geom = 2H + 2πR, m: length of the contour.
    pub fn geometric_length(&self) -> f64 {
        self.contour().length()
    }

    /// L / L_geom: > 1 slack, < 1 stretched on.
    pub fn slack_ratio(&self) -> f64 {
        self.belt.length / self.geometric_length()
    }

    /// The effects the scene calls for, as listed in reports, in a fixed order:
    /// `gravity` (if present, even g = 0), `transport inertia` (if `true`), and one
    /// of `frictionless contact`, `coulomb friction`, `elastic interlayer contact`.
    pub fn effect_names(&self) -> Vec<String> {
        let e = &self.effects;
        let mut names = Vec::new();
        if e.gravity.is_some() {
            names.push("gravity".to_string());
        }
        if e.inertia == Some(true) {
            names.push("transport inertia".to_string());
        }
        names.push(
            match e.contact {
                Contact::Frictionless => "frictionless contact",
                Contact::Coulomb(_) => "coulomb friction",
                Contact::ElasticLayer(_) => "elastic interlayer contact",
            }
            .to_string(),
        );
        names
    }

    /// The `bvp` block, or its defaults.
    pub fn bvp_settings(&self) -> BvpSettings {
        self.bvp.clone().unwrap_or_default()
    }

    /// The `fem` block, or its defaults.
    pub fn fem_settings(&self) -> FemSettings {
        self.fem.clone().unwrap_or_default()
    }

    /// The `gate` block, or its defaults.
    pub fn gate_settings(&self) -> GateSettings {
        self.gate.clone().unwrap_or_default()
    }
}

impl BvpSettings {
    /// Checks the ranges documented on the fields (paths `bvp.*`).
    ///
    /// # Errors
    /// The first field out of range.
    pub fn validate(&self) -> Result<(), SceneError> {
        check_positive("bvp.tolerance", self.tolerance)?;
        if self.tolerance >= 1.0 {
            return Err(SceneError::OutOfRange {
                path: "bvp.tolerance".into(),
                value: self.tolerance,
                range: "a relative tolerance, 0 < tolerance < 1".into(),
            });
        }
        if self.scheme.trim().is_empty() {
            return Err(SceneError::Invalid {
                path: "bvp.scheme".into(),
                reason: "must not be empty".into(),
            });
        }
        if self.max_nodes < 4 {
            return Err(SceneError::OutOfRange {
                path: "bvp.max_nodes".into(),
                value: self.max_nodes as f64,
                range: "at least 4".into(),
            });
        }
        if self.shooting_intervals < 1 {
            return Err(SceneError::OutOfRange {
                path: "bvp.shooting_intervals".into(),
                value: self.shooting_intervals as f64,
                range: "at least 1".into(),
            });
        }
        Ok(())
    }
}

impl FemSettings {
    /// Checks the ranges documented on the fields (paths `fem.*`).
    ///
    /// # Errors
    /// The first field out of range.
    pub fn validate(&self) -> Result<(), SceneError> {
        let four = "at least 4 elements (one per region of the contour) and at most 16384 (the cost grows with the square of the count)";
        if !(4..=MAX_ELEMENTS).contains(&self.elements) {
            return Err(SceneError::OutOfRange {
                path: "fem.elements".into(),
                value: self.elements as f64,
                range: four.into(),
            });
        }
        for (i, &n) in self.mesh_sequence.iter().enumerate() {
            let path = format!("fem.mesh_sequence[{i}]");
            if !(4..=MAX_ELEMENTS).contains(&n) {
                return Err(SceneError::OutOfRange {
                    path,
                    value: n as f64,
                    range: four.into(),
                });
            }
            if i > 0 && n <= self.mesh_sequence[i - 1] {
                return Err(SceneError::Invalid {
                    path,
                    reason: format!(
                        "the sequence must increase strictly, but {n} follows {}",
                        self.mesh_sequence[i - 1]
                    ),
                });
            }
        }
        for (i, name) in self.formulations.iter().enumerate() {
            let path = format!("fem.formulations[{i}]");
            if name.trim().is_empty() {
                return Err(SceneError::Invalid {
                    path,
                    reason: "a formulation name must not be empty".into(),
                });
            }
            if self.formulations[..i].contains(name) {
                return Err(SceneError::Invalid {
                    path,
                    reason: format!("formulation {name:?} is listed twice"),
                });
            }
        }
        if let Some(p) = self.penalty {
            check_positive("fem.penalty", p)?;
        }
        if let Some(dt) = self.time_step {
            check_positive("fem.time_step", dt)?;
        }
        if self.max_steps == Some(0) {
            return Err(SceneError::OutOfRange {
                path: "fem.max_steps".into(),
                value: 0.0,
                range: "at least 1 time step".into(),
            });
        }
        if let Some(t) = self.steady_tolerance {
            if !(t.is_finite() && t > 0.0 && t < 1.0) {
                return Err(SceneError::OutOfRange {
                    path: "fem.steady_tolerance".into(),
                    value: t,
                    range: "0 < tolerance < 1 (change per radian of driver rotation)".into(),
                });
            }
        }
        Ok(())
    }
}

impl GateSettings {
    /// Checks names and ranges (paths `gate.*`): every tolerance key must be a
    /// summary scalar or a field norm, with the nearest name suggested otherwise.
    ///
    /// # Errors
    /// The first unknown name or value out of range.
    pub fn validate(&self) -> Result<(), SceneError> {
        let all = self
            .tolerances
            .iter()
            .map(|(n, t)| ("tolerances", n, t))
            .chain(self.bvp_tolerances.iter().map(|(n, t)| ("bvp_tolerances", n, t)));
        for (block, name, &tol) in all {
            let path = format!("gate.{block}.{name}");
            let known = SCALAR_NAMES.iter().chain(FIELD_NORM_NAMES.iter());
            if !known.clone().any(|k| k == name) {
                return Err(SceneError::UnknownField {
                    path,
                    suggestion: nearest(name, known.clone().copied()),
                    allowed: known.map(|k| k.to_string()).collect(),
                });
            }
            check_positive(&path, tol)?;
        }
        if let Some(p) = self.min_order {
            check_positive("gate.min_order", p)?;
        }
        Ok(())
    }
}

/// `value` must be finite.
pub(crate) fn check_finite(path: &str, value: f64) -> Result<(), SceneError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SceneError::NotFinite {
            path: path.into(),
            value,
        })
    }
}

/// `value` must be finite and > 0.
pub(crate) fn check_positive(path: &str, value: f64) -> Result<(), SceneError> {
    check_finite(path, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(SceneError::NotPositive {
            path: path.into(),
            value,
        })
    }
}

/// `value` must be finite and ≥ 0.
pub(crate) fn check_non_negative(path: &str, value: f64) -> Result<(), SceneError> {
    check_finite(path, value)?;
    if value >= 0.0 {
        Ok(())
    } else {
        Err(SceneError::Negative {
            path: path.into(),
            value,
        })
    }
}
