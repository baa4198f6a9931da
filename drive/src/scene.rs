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
//! # Layouts (`drive.layout`)
//! - `two-pulley` (default): the closed loop over two pulleys — `centre_distance`,
//!   `driver_speed`, `driven_torque` required, `driven_damping` optional, `belt.length`
//!   required;
//! - `one-pulley` (Paper C, spec §2.2): one pulley at the origin with open ends —
//!   `end_distance` D > 0 and `transport_rate` c > 0 required, exactly two of
//!   `tension_in`, `tension_out` (> 0), `pulley_speed`, `stick_slip_angle` (|φ_B| ≤ π),
//!   at least one a tension ([`SceneError::OnePulleyPrescription`]); `belt.length` and
//!   the two-pulley fields are not allowed; analysis `steady`; EA and (Cosserat) GA
//!   must exceed χ = ρc² ([`SceneError::SpeedAtOrAboveCritical`]).
//!
//! A field of the other layout, and a field of the other kind of belt (plate parameters
//! outside theory `shell`, a section inside it), is a [`SceneError::NotAllowed`] naming
//! it; a missing required one a [`SceneError::MissingField`].
//!
//! # Compatibility rules (checked by [`Scene::validate`])
//! - theory `string`: `bending_stiffness` and `shear_stiffness` absent (or `null`);
//! - theory `kirchhoff`: `bending_stiffness` required (> 0), `shear_stiffness` absent;
//! - theory `cosserat`: both required (> 0): a = EI, b₁ = EA, b₂ = GA of spec §1;
//! - theory `shell` (Kirchhoff–Love, unshearable): the plate `width` b, `thickness`
//!   h < b, `youngs_modulus` E, `poisson_ratio` −1 < ν < 0.5, `density` ρ_V required,
//!   `camber` optional (exactly one of `curvature`, `edge_length_difference`);
//!   `axial_stiffness`, `bending_stiffness`, `mass_per_length` not given but derived
//!   ([`Plate::section`]); `shear_stiffness` absent;
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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

/// How the belt runs (`drive.layout`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub enum Layout {
    /// The closed loop over two pulleys (`"two-pulley"`, the default): DESIGN.md's drive,
    /// σ ∈ [0, 2H + 2πR) ([`Contour`]).
    #[default]
    #[serde(rename = "two-pulley")]
    TwoPulley,
    /// One pulley centred at the origin with open ends (`"one-pulley"`, Paper C, spec
    /// §2.2): the belt enters at x = −D along the upper side moving in +x, wraps
    /// clockwise and leaves at x = −D along the lower side; σ ∈ [0, 2D + πR]
    /// ([`crate::contour::OpenContour`]).
    #[serde(rename = "one-pulley")]
    OnePulley,
}

impl Layout {
    /// The JSON spelling.
    pub fn name(self) -> &'static str {
        match self {
            Layout::TwoPulley => "two-pulley",
            Layout::OnePulley => "one-pulley",
        }
    }

    fn is_two_pulley(&self) -> bool {
        *self == Layout::TwoPulley
    }
}

impl fmt::Display for Layout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Pulley geometry and the loads of the drive (`drive` block).
///
/// Which fields a scene gives depends on [`DriveGeometry::layout`] (the schema walk names a
/// missing or misplaced one): `two-pulley` takes `centre_distance`, `driver_speed`,
/// `driven_torque` (required) and `driven_damping`; `one-pulley` takes `end_distance`,
/// `transport_rate` (required) and exactly two of `tension_in`, `tension_out`,
/// `pulley_speed`, `stick_slip_angle`, at least one a tension. The two-pulley numbers of a
/// one-pulley scene are 0 and are not written.
#[derive(Debug, Clone, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DriveGeometry {
    /// Closed loop over two pulleys or one pulley with open ends. Optional, default
    /// `two-pulley`.
    #[serde(default)]
    pub layout: Layout,
    /// R, m, > 0: radius of the pulleys *to the belt centreline*. Required.
    pub pulley_radius: f64,
    /// H, m, > 2R: distance of the pulley centres (−H/2, 0) and (+H/2, 0). Required for
    /// `two-pulley`; 0 (not allowed in the JSON) for `one-pulley`.
    #[serde(default)]
    pub centre_distance: f64,
    /// ω₁, rad/s, finite, clockwise positive (the upper span moves in +x); negative:
    /// the driver turns counter-clockwise, the belt runs onto the driver from the upper
    /// span, which is then the tight one when the driver drives (steady and transient
    /// analyses); must be 0 in a static analysis. Required for
    /// `two-pulley`; 0 for `one-pulley`.
    #[serde(default)]
    pub driver_speed: f64,
    /// M₂, N·m, finite: the load torque on the driven pulley, the clockwise torque the
    /// belt must exert on it (with d₂ω₂: M₂ + d₂ω₂). It resists the motion when it has
    /// the sign of ω₁ (positive for a clockwise drive); with the opposite sign and
    /// |M₂| > d₂|ω₁| the load drives and the driver brakes (power flows from the driven
    /// pulley; its slip zones swap sides of the power flow); must be 0 in a static
    /// analysis. Required for `two-pulley`; 0 for `one-pulley`.
    #[serde(default)]
    pub driven_torque: f64,
    /// d₂, N·m·s, ≥ 0: viscous resistance of the driven pulley, resisting torque
    /// d₂·ω₂ in addition to M₂; must be 0 in a static analysis. Optional, default 0;
    /// `two-pulley` only.
    #[serde(default)]
    pub driven_damping: f64,
    /// D, m, > 0 (`one-pulley`): distance of the two end sections x = −D from the pulley
    /// centre. Required for `one-pulley`.
    #[serde(default)]
    pub end_distance: Option<f64>,
    /// c, m/s, > 0 (`one-pulley`): prescribed transport rate (mass flux / ρ). Required for
    /// `one-pulley`.
    #[serde(default)]
    pub transport_rate: Option<f64>,
    /// N_in, N, > 0 (`one-pulley`): axial force at the inflow end (upper side).
    #[serde(default)]
    pub tension_in: Option<f64>,
    /// N_out, N, > 0 (`one-pulley`): axial force at the outflow end (lower side).
    #[serde(default)]
    pub tension_out: Option<f64>,
    /// ω, rad/s, finite, clockwise positive (`one-pulley`): prescribed pulley speed.
    #[serde(default)]
    pub pulley_speed: Option<f64>,
    /// φ_B, rad, in [−π, π] (`one-pulley`): polar angle of the stick-to-slip transition
    /// point, prescribed directly (Paper C).
    #[serde(default)]
    pub stick_slip_angle: Option<f64>,
    /// `one-pulley` with `stick_slip_angle` only: φ_B fixes the slip arc, not its sense.
    /// `true`: the belt drives the pulley (N_in < N_out, slip reversed); `false` (the
    /// default): the pulley drives the belt (N_in > N_out). With two tensions or ω given
    /// the sense follows from them, so the field is refused there.
    #[serde(default)]
    pub belt_drives_pulley: Option<bool>,
    /// ω₂, rad/s, finite (theory `shell` only, optional; default: `driver_speed`): the
    /// prescribed speed of the driven drum. In Paper E both drums turn at prescribed
    /// speeds (spec §4.15; Fig. 1 [T l.99]), so a shell scene has no load torque. It must
    /// turn in the sense of the driver (a belt cannot run over drums turning opposite
    /// ways) and is 0 in a static analysis.
    #[serde(default)]
    pub driven_speed: Option<f64>,
    /// The steering drum and the histories of its two tilt angles (theory `shell` only,
    /// optional; absent = aligned drums; spec §4.7, docs/fem-shell.md §8).
    #[serde(default)]
    pub steering: Option<Steering>,
}

/// Which drum of the two-pulley loop steers (`drive.steering.drum`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum SteeringDrum {
    /// The left drum, centre (−H/2, 0).
    Driver,
    /// The right drum, centre (+H/2, 0).
    Driven,
}

impl SteeringDrum {
    /// The JSON spelling.
    pub fn name(self) -> &'static str {
        match self {
            SteeringDrum::Driver => "driver",
            SteeringDrum::Driven => "driven",
        }
    }
}

/// Largest tilt angle of the steering drum, rad (π/4): the interlayer's contact rule
/// integrates across the width with two Gauss points, which holds for small
/// misalignments only ([T l.432]; docs/fem-shell.md §8).
pub const MAX_TILT: f64 = std::f64::consts::FRAC_PI_4;

/// The steering drum and its tilt (`drive.steering`, spec §4.7 and §4.15): the axis of
/// the steered drum is a(t) = Rot_x(β_x(t)) Rot_y(β_y(t)) e_z through its centre —
/// β_x (`tilt_x`) rotates it about the span direction x (tilt in the y–z plane), β_y
/// (`tilt_y`) in the plane of the two axes (the x–z plane, "swivel"). Each angle is a
/// piecewise-linear history `[[t, β], …]` (t in s from the start of the drums' rotation,
/// t ≥ 0, strictly increasing; β in rad, |β| < π/4), held at its first value before the
/// first point and at its last after the last; an absent or empty history is 0. The
/// solver ramps the angles from 0 to their values at t = 0 at rest, before the rotation
/// starts (docs/fem-shell.md §9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Steering {
    /// The steered drum. Required.
    pub drum: SteeringDrum,
    /// History of β_x, `[[t, β_x], …]` (s, rad). Optional, default none (0).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tilt_x: Vec<[f64; 2]>,
    /// History of β_y, `[[t, β_y], …]` (s, rad). Optional, default none (0).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tilt_y: Vec<[f64; 2]>,
}

impl Steering {
    /// The value of a history at time t (s from the start of the rotation):
    /// piecewise-linear, held constant outside; 0 for an empty history.
    pub fn angle_at(history: &[[f64; 2]], t: f64) -> f64 {
        let Some(first) = history.first() else { return 0.0 };
        if t <= first[0] {
            return first[1];
        }
        for w in history.windows(2) {
            let ([t0, b0], [t1, b1]) = (w[0], w[1]);
            if t <= t1 {
                return b0 + (b1 - b0) * (t - t0) / (t1 - t0);
            }
        }
        history[history.len() - 1][1]
    }

    /// Checks one history (path `drive.steering.<name>`): points finite, t ≥ 0 and
    /// strictly increasing, |β| < [`MAX_TILT`].
    fn validate_history(name: &str, history: &[[f64; 2]]) -> Result<(), SceneError> {
        for (i, &[t, beta]) in history.iter().enumerate() {
            let path = format!("drive.steering.{name}[{i}]");
            check_non_negative(&format!("{path}[0]"), t)?;
            check_finite(&format!("{path}[1]"), beta)?;
            if i > 0 && t <= history[i - 1][0] {
                return Err(SceneError::Invalid {
                    path,
                    reason: format!("the times of a tilt history must increase strictly, but t = {} s follows t = {} s", crate::error::num(&t), crate::error::num(&history[i - 1][0])),
                });
            }
            if beta.abs() >= MAX_TILT {
                return Err(SceneError::OutOfRange {
                    path: format!("{path}[1]"),
                    value: beta,
                    range: "|β| < π/4 rad (45°): a misalignment, not a turned drum (the contact rule across the width holds for small tilts only)".into(),
                });
            }
        }
        Ok(())
    }
}

/// The two prescribed quantities of a one-pulley scene (spec §2.3): exactly two of the
/// four, at least one a tension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OnePulleyLoad {
    /// N_in and N_out given; ω and φ_B are outputs (`prescribe: tensions`).
    Tensions {
        /// N_in, N.
        tension_in: f64,
        /// N_out, N.
        tension_out: f64,
    },
    /// φ_B and one tension given (Paper C's choice); ω and the other tension outputs.
    Transition {
        /// φ_B, rad.
        stick_slip_angle: f64,
        /// The end whose tension is given and its value, N.
        tension: (End, f64),
        /// The pulley drives the belt (N_in > N_out; `belt_drives_pulley` false or
        /// absent) or the belt drives it.
        driving: bool,
    },
    /// ω and one tension given ("the usual approach"); φ_B and the other tension outputs.
    PulleySpeed {
        /// ω, rad/s.
        pulley_speed: f64,
        /// The end whose tension is given and its value, N.
        tension: (End, f64),
    },
}

/// An open end of a one-pulley scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum End {
    /// The inflow end on the upper side.
    In,
    /// The outflow end on the lower side.
    Out,
}

impl DriveGeometry {
    /// Names and values of the one-pulley prescriptions given, in the order
    /// `tension_in`, `tension_out`, `pulley_speed`, `stick_slip_angle`.
    fn one_pulley_given(&self) -> Vec<(&'static str, f64)> {
        [
            ("tension_in", self.tension_in),
            ("tension_out", self.tension_out),
            ("pulley_speed", self.pulley_speed),
            ("stick_slip_angle", self.stick_slip_angle),
        ]
        .into_iter()
        .filter_map(|(n, v)| v.map(|v| (n, v)))
        .collect()
    }

    /// The prescribed pair of a one-pulley scene; `None` for a two-pulley scene or a pair
    /// that [`Scene::validate`] refuses.
    pub fn one_pulley_load(&self) -> Option<OnePulleyLoad> {
        if self.layout != Layout::OnePulley {
            return None;
        }
        let tension = match (self.tension_in, self.tension_out) {
            (Some(t), None) => Some((End::In, t)),
            (None, Some(t)) => Some((End::Out, t)),
            _ => None,
        };
        match (self.tension_in, self.tension_out, self.pulley_speed, self.stick_slip_angle) {
            (Some(tension_in), Some(tension_out), None, None) => Some(OnePulleyLoad::Tensions { tension_in, tension_out }),
            (_, _, None, Some(stick_slip_angle)) => tension.map(|tension| OnePulleyLoad::Transition { stick_slip_angle, tension, driving: self.belt_drives_pulley != Some(true) }),
            (_, _, Some(pulley_speed), None) => tension.map(|tension| OnePulleyLoad::PulleySpeed { pulley_speed, tension }),
            _ => None,
        }
    }
}

/// Writes the fields of the scene's layout only (a one-pulley scene has no
/// `centre_distance`, `driver_speed`, `driven_torque`, `driven_damping`), so that
/// [`Scene::from_json_str`] reads the written scene back.
impl Serialize for DriveGeometry {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(None)?;
        if !self.layout.is_two_pulley() {
            m.serialize_entry("layout", &self.layout)?;
        }
        m.serialize_entry("pulley_radius", &self.pulley_radius)?;
        match self.layout {
            Layout::TwoPulley => {
                m.serialize_entry("centre_distance", &self.centre_distance)?;
                m.serialize_entry("driver_speed", &self.driver_speed)?;
                m.serialize_entry("driven_torque", &self.driven_torque)?;
                m.serialize_entry("driven_damping", &self.driven_damping)?;
                if let Some(w) = self.driven_speed {
                    m.serialize_entry("driven_speed", &w)?;
                }
                if let Some(st) = &self.steering {
                    m.serialize_entry("steering", st)?;
                }
            }
            Layout::OnePulley => {
                for (name, v) in [("end_distance", self.end_distance), ("transport_rate", self.transport_rate)] {
                    if let Some(v) = v {
                        m.serialize_entry(name, &v)?;
                    }
                }
                for (name, v) in self.one_pulley_given() {
                    m.serialize_entry(name, &v)?;
                }
                if let Some(b) = self.belt_drives_pulley {
                    m.serialize_entry("belt_drives_pulley", &b)?;
                }
            }
        }
        m.end()
    }
}

/// Structural theory of the belt (`belt.theory`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
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
///
/// Theory `shell` gives the plate parameters (`width`, `thickness`, `youngs_modulus`,
/// `poisson_ratio`, `density`, optional `camber`) instead of `axial_stiffness`,
/// `bending_stiffness` and `mass_per_length`; the reader fills those three with the
/// planar-limit section of the plate ([`Plate::section`]) and does not write them back.
#[derive(Debug, Clone, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Belt {
    /// Structural theory. Required.
    pub theory: Theory,
    /// L, m, > 0: unstretched length of the closed belt. Required for layout
    /// `two-pulley`; not allowed (0 here) for `one-pulley`, whose belt has open ends.
    /// May be shorter than the contour 2H + 2πR (stretched on).
    #[serde(default)]
    pub length: f64,
    /// EA, N, > 0: axial stiffness, N = EA·(λ − 1). Required (`cosserat`: b₁); derived
    /// for `shell`.
    #[serde(default)]
    pub axial_stiffness: f64,
    /// EI, N·m², > 0: bending stiffness, M = EI·κ. Required for `kirchhoff`,
    /// `cosserat` (a); derived for `shell`; absent or `null` for `string`.
    #[serde(default)]
    pub bending_stiffness: Option<f64>,
    /// GA, N, > 0: shear stiffness, Q = GA·γ. Required for `cosserat` (b₂); absent or
    /// `null` otherwise.
    #[serde(default)]
    pub shear_stiffness: Option<f64>,
    /// ρ, kg/m, > 0: mass per unit unstretched length. Required; derived for `shell`.
    #[serde(default)]
    pub mass_per_length: f64,
    /// b, m, > 0: width of the shell (`shell` only, required).
    #[serde(default)]
    pub width: Option<f64>,
    /// h, m, > 0 and < b: thickness of the shell (`shell` only, required).
    #[serde(default)]
    pub thickness: Option<f64>,
    /// E, Pa, > 0: Young's modulus of the shell (`shell` only, required).
    #[serde(default)]
    pub youngs_modulus: Option<f64>,
    /// ν, −1 < ν < 0.5: Poisson's ratio of the shell (`shell` only, required).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// ρ_V, kg/m³, > 0: density of the shell material (`shell` only, required).
    #[serde(default)]
    pub density: Option<f64>,
    /// Camber imperfection of the shell (`shell` only, optional; absent = straight).
    #[serde(default)]
    pub camber: Option<Camber>,
}

/// Camber imperfection of a shell belt (`belt.camber`, spec §4.3): exactly one of the
/// two fields.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Camber {
    /// κ_c, 1/m, finite: in-plane curvature of the unstretched belt's centre line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature: Option<f64>,
    /// ΔL, m, finite: length difference of the two belt edges.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_length_difference: Option<f64>,
}

impl Camber {
    /// κ_c, 1/m, of a belt of width b and unstretched length L: `curvature` as given, or
    /// from `edge_length_difference` ΔL = κ_c b L (spec §4.3; ΔL is the length of the
    /// −ζ edge minus that of the +ζ edge, so ΔL > 0 ⇔ κ_c > 0, the +ζ edge shorter).
    pub fn curvature_for(&self, width: f64, length: f64) -> f64 {
        match (self.curvature, self.edge_length_difference) {
            (Some(k), _) => k,
            (None, Some(dl)) => dl / (width * length),
            (None, None) => 0.0,
        }
    }
}

/// The plate parameters of a shell belt (theory `shell`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Plate {
    /// b, m.
    pub width: f64,
    /// h, m.
    pub thickness: f64,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// ν.
    pub poisson_ratio: f64,
    /// ρ_V, kg/m³.
    pub density: f64,
}

/// The section of a belt seen as a rod in the plane: what the planar models use.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Section {
    /// EA, N.
    pub axial_stiffness: f64,
    /// EI, N·m².
    pub bending_stiffness: f64,
    /// ρ, kg/m.
    pub mass_per_length: f64,
}

impl Plate {
    /// The planar limit of the plate strip: EA = E b h, EI = E b h³ / (12 (1 − ν²)) (the
    /// plate's bending stiffness D times the width: a wide strip bends in cylindrical
    /// bending), ρ = ρ_V b h.
    pub fn section(&self) -> Section {
        let (b, h, e, nu) = (self.width, self.thickness, self.youngs_modulus, self.poisson_ratio);
        Section {
            axial_stiffness: e * b * h,
            bending_stiffness: e * b * h.powi(3) / (12.0 * (1.0 - nu * nu)),
            mass_per_length: self.density * b * h,
        }
    }
}

impl Belt {
    /// The five plate parameters by JSON name, as given.
    fn plate_fields(&self) -> [(&'static str, Option<f64>); 5] {
        [
            ("width", self.width),
            ("thickness", self.thickness),
            ("youngs_modulus", self.youngs_modulus),
            ("poisson_ratio", self.poisson_ratio),
            ("density", self.density),
        ]
    }

    /// The plate parameters of a shell belt (`None` unless all five are given).
    pub fn plate(&self) -> Option<Plate> {
        Some(Plate {
            width: self.width?,
            thickness: self.thickness?,
            youngs_modulus: self.youngs_modulus?,
            poisson_ratio: self.poisson_ratio?,
            density: self.density?,
        })
    }

    /// For theory `shell`: `axial_stiffness`, `bending_stiffness` and `mass_per_length`
    /// set to the plate's [`Plate::section`] (the reader calls this; call it after
    /// building a shell belt in code). Other theories are returned unchanged.
    pub fn with_derived_section(mut self) -> Belt {
        if self.theory == Theory::Shell {
            if let Some(s) = self.plate().map(|p| p.section()) {
                self.axial_stiffness = s.axial_stiffness;
                self.bending_stiffness = Some(s.bending_stiffness);
                self.mass_per_length = s.mass_per_length;
            }
        }
        self
    }
}

/// Writes what a scene file gives: no `length` for a one-pulley belt (0), no section for
/// a shell (derived from the plate), so that [`Scene::from_json_str`] reads it back.
impl Serialize for Belt {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("theory", &self.theory)?;
        if self.length != 0.0 {
            m.serialize_entry("length", &self.length)?;
        }
        let shell = self.theory == Theory::Shell;
        if !shell {
            m.serialize_entry("axial_stiffness", &self.axial_stiffness)?;
            if let Some(v) = self.bending_stiffness {
                m.serialize_entry("bending_stiffness", &v)?;
            }
        }
        if let Some(v) = self.shear_stiffness {
            m.serialize_entry("shear_stiffness", &v)?;
        }
        if !shell {
            m.serialize_entry("mass_per_length", &self.mass_per_length)?;
        }
        for (name, v) in self.plate_fields() {
            if let Some(v) = v {
                m.serialize_entry(name, &v)?;
            }
        }
        if let Some(c) = &self.camber {
            m.serialize_entry("camber", c)?;
        }
        m.end()
    }
}

/// Contact model between belt and pulleys (`effects.contact`).
///
/// JSON: `"frictionless"`, `{"coulomb": μ}`, or
/// `{"elastic_layer": {"normal_stiffness": P, "tangential_stiffness": P_t}}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
///
/// Given either as the two stiffnesses, or as the layer material (`thickness` d,
/// `youngs_modulus` E_l, `poisson_ratio` ν_l; spec §4.6), from which the reader derives
/// P = E_l(1 − ν_l)/((1 + ν_l)(1 − 2ν_l) d) (a thin layer bonded to the drum is laterally
/// confined) and P_⊥ = E_l/(2(1 + ν_l) d) ([`ElasticLayer::with_derived_stiffness`]); the
/// material form is written back as given.
#[derive(Debug, Clone, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ElasticLayer {
    /// P, N/m³ (pressure per penetration), > 0. Required unless the material is given.
    #[serde(default)]
    pub normal_stiffness: f64,
    /// P_⊥, N/m³ (shear traction per tangential displacement), > 0. Required unless the
    /// material is given.
    #[serde(default)]
    pub tangential_stiffness: f64,
    /// d, m, > 0: layer thickness (material form).
    #[serde(default)]
    pub thickness: Option<f64>,
    /// E_l, Pa, > 0: Young's modulus of the layer (material form).
    #[serde(default)]
    pub youngs_modulus: Option<f64>,
    /// ν_l, −1 < ν_l < 0.5: Poisson's ratio of the layer (material form).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
}

impl ElasticLayer {
    /// The layer material (d, E_l, ν_l) if all three are given.
    pub fn material(&self) -> Option<(f64, f64, f64)> {
        Some((self.thickness?, self.youngs_modulus?, self.poisson_ratio?))
    }

    /// Given the material: P and P_⊥ derived from it (type docs); else unchanged.
    pub fn with_derived_stiffness(mut self) -> ElasticLayer {
        if let Some((d, e, nu)) = self.material() {
            self.normal_stiffness = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * d);
            self.tangential_stiffness = e / (2.0 * (1.0 + nu) * d);
        }
        self
    }
}

/// Writes the form the scene gave: the material, or the two stiffnesses.
impl Serialize for ElasticLayer {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(None)?;
        match self.material() {
            Some((d, e, nu)) => {
                m.serialize_entry("thickness", &d)?;
                m.serialize_entry("youngs_modulus", &e)?;
                m.serialize_entry("poisson_ratio", &nu)?;
            }
            None => {
                m.serialize_entry("normal_stiffness", &self.normal_stiffness)?;
                m.serialize_entry("tangential_stiffness", &self.tangential_stiffness)?;
            }
        }
        m.end()
    }
}

/// The effects a scene calls for (`effects` block); absent = not simulated.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, schemars::JsonSchema)]
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// crate; unused by shooting. Non-empty. Default `"gauss8"` (the `bvp` crate's
    /// default, the cheapest at every accuracy measured).
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
        "gauss8".to_string()
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// belt stiffness (κ EA/R²), and in the fixed-topology solves of Paper D's steady
    /// scheme on a string also with the mesh (× max(1, (n/128)²) for n elements,
    /// docs/fem-drive.md §12).
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
    /// How the FE's direct steady solve of a two-pulley drive finds its stick and slip
    /// zones after the load continuation (analysis `steady`): `semismooth` — Coulomb
    /// complementarity per friction point and a mesh fitted to the located transitions
    /// (docs/fem-drive.md §12) — or `paper-d` — Paper D's fixed topology with prescribed
    /// stick→slip points iterated until no stick zone exceeds Coulomb's bound (spec
    /// §3.5, docs/cosserat-drive.md) — or `auto`: Paper D's on a string, the semismooth
    /// fit where that fails (a stated warning) and on a Cosserat rod. Default absent =
    /// `auto`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady_scheme: Option<SteadyScheme>,
    /// The FE's normal contact in the direct steady solve of a one-pulley Cosserat scene
    /// (docs/fem-cosserat.md §12.5): `penalty` — P⟨−γ⟩ — or `augmented-lagrangian` — the
    /// multipliers of Table 1 updated until the gap closes, the penalty result with a
    /// stated warning where that does not converge. Default absent = `penalty`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<NormalContact>,
    /// Shell only: elements n_σ round the loop (the σ-mesh is that of the equivalent rod
    /// of the planar start, with nodes on the four transitions and the rod's contact
    /// edges; docs/fem-shell.md §9.1), 8 … 4096. Default absent = 64.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements_sigma: Option<usize>,
    /// Shell only: elements n_ζ across the width, even (a node on the centre line), 2 …
    /// 64. Default absent: the fewest that resolve the belt's edge layer, chosen by the
    /// shell's solve (`fem::shell::scene::run_of`; [`Scene::shell_run`] alone, without the
    /// model, says 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements_zeta: Option<usize>,
    /// Shell only: time steps of the rotation (stage 2), ≥ 1; not with `duration`.
    /// Default absent = from `duration`, else one revolution of the belt L/(ωR).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
    /// Shell only: simulated time of the rotation (stage 2), s, > 0; the steps are
    /// ⌈duration/Δt⌉; not with `steps`. Default absent = see `steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Shell only: quasistatic steps of stage 1 at rest, in which the camber and the
    /// initial tilt are ramped from 0, ≥ 1. Default absent = 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp_steps: Option<usize>,
    /// Shell only: a frame of surface fields every this many steps of the rotation
    /// (besides the frames at the start and the end of the rotation, always written);
    /// 0 = those two only. Default absent = 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame_every: Option<usize>,
    /// Shell only: the σ-rule of the elastic interlayer's energy (× Gauss 2 across the
    /// width): `simpson` (element ends and middle) or `trapezoidal` (element ends only,
    /// the reference's rule [T l.420]), docs/fem-shell.md §6. Default absent = `simpson`:
    /// the trapezoidal rule leaves the belt unsupported between nodes, and a stiff belt's
    /// span tension shows it (a steel belt's static tension 60 % low at 32 elements, and
    /// drifting by 20 % in 24 steps at 64).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_rule: Option<ShellContactRule>,
    /// Shell only: the ζ-rule of the elastic interlayer's energy across the width:
    /// `gauss2` (the reference's [T l.420, 432]) to `gauss5`, docs/fem-shell.md §6.
    /// Default absent = `gauss2`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_rule_width: Option<ShellWidthRule>,
    /// Shell only: the ζ-nodes across the width: `graded` towards the belt's free edges,
    /// where the belt wrapped on a drum has an anticlastic edge layer of the length
    /// ℓ_e = min((D/P)^{1/4}, (4DR²/(Eh))^{1/4}) (3.5 mm for the shipped steel belt), or
    /// `uniform`;
    /// docs/fem-shell.md §9.5. Default absent = `graded` (for n_ζ = 2 both give the
    /// edges and the centre line).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zeta_mesh: Option<ShellZetaMesh>,
    /// Shell only: the grading of the σ-mesh towards the drums' contact edges, where the
    /// interlayer's contact starts and ends over the plate's foundation length
    /// ℓ_c = (D/P)^{1/4} (3.4 mm for the shipped steel belt): element density
    /// 1 + `ratio`·exp(−d/(`width`·ℓ_c)) at the distance d from an edge,
    /// docs/fem-shell.md §9.1 and §14 "Grading the σ-mesh harder". Default absent =
    /// ratio 8, width 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_grading: Option<ShellSigmaGrading>,
}

/// The grading of the shell's σ-mesh towards the contact edges (`fem.sigma_grading`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ShellSigmaGrading {
    /// Peak refinement, ≥ 0: the elements at a contact edge are about 1 + `ratio` times
    /// shorter than far from it (0: pieces of equal elements between the fitted contact
    /// edges and the transitions). Default 8.
    pub ratio: f64,
    /// Decay length of the refinement in foundation lengths ℓ_c, > 0. Default 2.
    pub width: f64,
}

impl ShellSigmaGrading {
    /// The largest `ratio` a scene may ask for: 1000 times shorter elements at the edges.
    pub const MAX_RATIO: f64 = 1000.0;
    /// The largest `width`, in ℓ_c: 1000 ℓ_c is 3.4 m for the steel belt, longer than
    /// its loop.
    pub const MAX_WIDTH: f64 = 1000.0;
}

impl Default for ShellSigmaGrading {
    fn default() -> Self {
        ShellSigmaGrading { ratio: 8.0, width: 2.0 }
    }
}

/// The shell's ζ-nodes across the width (`fem.zeta_mesh`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ShellZetaMesh {
    /// Graded towards both free edges over a few edge-layer lengths (peak refinement 9×).
    #[default]
    Graded,
    /// Equal elements across the width.
    Uniform,
}

/// The σ-rule of the shell's elastic interlayer (`fem.contact_rule`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ShellContactRule {
    /// ξ = −1, 0, 1 with weights ⅓, ⁴⁄₃, ⅓: the belt held at the element's middle too.
    #[default]
    Simpson,
    /// ξ = ±1 with weights 1: the contact at the nodes only (the reference's rule).
    Trapezoidal,
}

/// The ζ-rule of the shell's elastic interlayer across the width
/// (`fem.contact_rule_width`): Gauss–Legendre with 2 to 5 points per ζ-element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ShellWidthRule {
    /// 2 points: the reference's rule [T l.420, 432].
    #[default]
    Gauss2,
    /// 3 points.
    Gauss3,
    /// 4 points.
    Gauss4,
    /// 5 points.
    Gauss5,
}

impl ShellWidthRule {
    /// The points per ζ-element.
    pub const fn points(self) -> u8 {
        match self {
            ShellWidthRule::Gauss2 => 2,
            ShellWidthRule::Gauss3 => 3,
            ShellWidthRule::Gauss4 => 4,
            ShellWidthRule::Gauss5 => 5,
        }
    }

    /// The rule's name in prose ("Gauss 2").
    pub fn label(self) -> String {
        format!("Gauss {}", self.points())
    }
}

impl ShellContactRule {
    /// The rule's name in prose ("Simpson", "trapezoidal").
    pub const fn label(self) -> &'static str {
        match self {
            ShellContactRule::Simpson => "Simpson",
            ShellContactRule::Trapezoidal => "trapezoidal",
        }
    }
}

/// The shell's discretisation and run, resolved from the `fem` block with its defaults
/// ([`Scene::shell_run`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShellRun {
    /// n_σ.
    pub elements_sigma: usize,
    /// n_ζ.
    pub elements_zeta: usize,
    /// Δt, s.
    pub time_step: f64,
    /// Steps of the rotation.
    pub steps: usize,
    /// Steps of the ramp at rest.
    pub ramp_steps: usize,
    /// Frame interval (0: start and end only).
    pub frame_every: usize,
    /// The interlayer's σ-rule.
    pub contact_rule: ShellContactRule,
    /// The interlayer's ζ-rule.
    pub contact_rule_width: ShellWidthRule,
    /// The ζ-nodes across the width.
    pub zeta_mesh: ShellZetaMesh,
    /// The σ-mesh's grading towards the contact edges.
    pub sigma_grading: ShellSigmaGrading,
}

/// Default shell drum rotation per step ωΔt, rad (π/32): half an arc element of a
/// 64-element loop per step. At π/16 (the default until 5 Dec 2026) the steel belt's span
/// tensions carry a time-step error of up to 5 %, below 0.3 % at π/32
/// (docs/fem-shell.md §9.4).
pub const SHELL_STEP_ANGLE: f64 = std::f64::consts::PI / 32.0;

/// Largest number of rotation steps of a shell run (`fem.steps` or from `fem.duration`).
pub const MAX_SHELL_STEPS: usize = 100_000;

/// The FE's normal contact (`fem.contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum NormalContact {
    /// The penalty P⟨−γ⟩: a penetration T̃/(RP) and the penalty layer at the contact
    /// edges.
    #[default]
    Penalty,
    /// The augmented Lagrangian ⟨λ − Pγ⟩₊ with the first-order (Uzawa) update of the
    /// multipliers λ after each converged solve.
    AugmentedLagrangian,
}

/// The FE's scheme for the stick and slip zones of a steady two-pulley drive
/// (`fem.steady_scheme`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SteadyScheme {
    /// The scheme by the belt: Paper D's on the string's loop — its fronts converge at
    /// order ≈ 2 where the semismooth fit's stall at ≈ 0.5 (docs/fem-drive.md §12) —
    /// with the semismooth fit as the stated fallback when it fails; the semismooth fit on
    /// the Cosserat rod's loop.
    #[default]
    Auto,
    /// Coulomb complementarity per friction point (semismooth Newton), mesh fitted to
    /// the located contact boundaries and transitions.
    Semismooth,
    /// Paper D: fixed topology with prescribed stick→slip points and a scalar root find
    /// on the matching condition.
    PaperD,
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
            steady_scheme: None,
            contact: None,
            elements_sigma: None,
            elements_zeta: None,
            steps: None,
            duration: None,
            ramp_steps: None,
            frame_every: None,
            contact_rule: None,
            contact_rule_width: None,
            zeta_mesh: None,
            sigma_grading: None,
        }
    }
}

/// Settings of the CI gate (`gate` block). Every field optional.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// replaces its `tolerances` limit for the BVP methods only; a quantity listed here
    /// and not in `tolerances` is gated for the BVP methods alone (one the FE does not
    /// produce, e.g. the Cosserat edge pressures); absent = the BVP methods are held to
    /// `tolerances`. Default empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub bvp_tolerances: BTreeMap<String, f64>,
    /// Minimum observed order of convergence p of the FE studies, > 0. Default
    /// absent = order not gated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_order: Option<f64>,
    /// Tolerance of the gate's BVP reference (collocation gauss6) for this scene,
    /// 0 < tolerance < 1. Default absent = the gate's 1e-10
    /// (`verification::gate::GATE_REFERENCE_TOLERANCE`). A scene whose reference is
    /// costly at 1e-10 takes a looser one; its limits must then sit above the errors
    /// measured against the tighter reference.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_tolerance: Option<f64>,
    /// Tolerance of the gated BVP runs (collocation gauss4, shooting) for this scene,
    /// 0 < tolerance < 1, above `reference_tolerance` when both are given. Default
    /// absent = the gate's 1e-8; `beltcheck gate --tolerance` overrides it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bvp_tolerance: Option<f64>,
    /// Whether the gate runs the scene's FE studies. Default absent = true. `false` gates
    /// the BVP methods only, for a scene whose FE is solvable but too costly or not yet
    /// accurate enough to hold to the scene's limits in CI (`cosserat-drive`: its FE slip
    /// arcs are 19–35 % off at 512 elements, docs/fem-cosserat.md §11.1); the gate says so
    /// in its notes. `converge` and `report` still study the FE.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fem: Option<bool>,
    /// Shell scenes only: the levels n_σ × n_ζ of the gate's study, coarsest first, each
    /// with Δt scaled like the σ spacing, held against the Richardson extrapolation of the
    /// three finest (docs/verification.md "The shell's study"). Default absent = the
    /// scene's mesh, then 2× and 4× its n_σ at its n_ζ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub levels: Option<Vec<[usize; 2]>>,
    /// Shell scenes only: the rotation steps of the gate's runs at the scene's own
    /// Δt (the other levels take the same simulated time) — a CI-sized part of the
    /// scene's `fem.steps`. Default absent = the scene's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
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
        let mut scene: Scene = serde_json::from_value(value)
            // unreachable after the schema walk; kept as an error, not a panic
            .map_err(|e| SceneError::Invalid {
                path: "<scene>".into(),
                reason: e.to_string(),
            })?;
        scene.belt = scene.belt.with_derived_section();
        if let Contact::ElasticLayer(layer) = &mut scene.effects.contact {
            *layer = layer.clone().with_derived_stiffness();
        }
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
            self.validate_shell_fem(f)?;
            self.validate_time_step(f)?;
            self.validate_normal_contact(f)?;
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
    /// `fem.contact = "augmented-lagrangian"` is built for the Cosserat belt's direct
    /// steady solve of the one-pulley layout and its static analysis on two pulleys
    /// (docs/fem-cosserat.md §12.5); elsewhere it would be ignored, so it is refused by
    /// name.
    fn validate_normal_contact(&self, f: &FemSettings) -> Result<(), SceneError> {
        let built = self.belt.theory == Theory::Cosserat
            && ((self.drive.layout == Layout::OnePulley && self.analysis == Analysis::Steady) || (self.drive.layout != Layout::OnePulley && self.analysis == Analysis::Static));
        if f.contact == Some(NormalContact::AugmentedLagrangian) && !built {
            return Err(SceneError::NotAllowed {
                path: "fem.contact".into(),
                reason: format!(
                    "the augmented-Lagrangian normal contact is built for the Cosserat belt's steady one-pulley solve and its static analysis on two pulleys only (this scene: layout `{}`, theory `{}`, analysis `{}`); remove it or use `penalty`",
                    self.drive.layout.name(),
                    self.belt.theory.name(),
                    self.analysis.name()
                ),
            });
        }
        Ok(())
    }

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
        match d.layout {
            Layout::TwoPulley => {
                Contour::new(d.pulley_radius, d.centre_distance)?;
                check_finite("drive.driver_speed", d.driver_speed)?;
                check_finite("drive.driven_torque", d.driven_torque)?;
                check_non_negative("drive.driven_damping", d.driven_damping)?;
                self.validate_shell_drive()?;
            }
            Layout::OnePulley => self.validate_one_pulley()?,
        }
        Ok(())
    }

    /// The drive of a shell (spec §4.15): both drums at prescribed speeds, so no load
    /// torque or damping; ω₂ finite and in the sense of ω₁ (zero exactly when ω₁ is);
    /// the steering histories valid. Outside theory `shell` the schema walk refuses the
    /// fields; a scene built in code is refused here.
    fn validate_shell_drive(&self) -> Result<(), SceneError> {
        let d = &self.drive;
        if self.belt.theory != Theory::Shell {
            for (path, given) in [("drive.driven_speed", d.driven_speed.is_some()), ("drive.steering", d.steering.is_some())] {
                if given {
                    return Err(SceneError::NotAllowed { path: path.into(), reason: format!("it belongs to theory `shell` (both drums at prescribed speed, a steering drum); this scene's belt is theory `{}`", self.belt.theory) });
                }
            }
            return Ok(());
        }
        for (path, value, unit) in [("drive.driven_torque", d.driven_torque, "N·m"), ("drive.driven_damping", d.driven_damping, "N·m·s")] {
            if value != 0.0 {
                return Err(SceneError::NotAllowed {
                    path: path.into(),
                    reason: format!(
                        "a shell scene turns both drums at prescribed speeds (`driver_speed`, `driven_speed`; Paper E, spec §4.15), so there is no load on the driven drum: it must be 0 (got {} {unit})",
                        crate::error::num(&value)
                    ),
                });
            }
        }
        if let Some(w2) = d.driven_speed {
            check_finite("drive.driven_speed", w2)?;
            let w1 = d.driver_speed;
            if w1.signum() * w2.signum() < 0.0 || (w1 == 0.0) != (w2 == 0.0) {
                return Err(SceneError::Invalid {
                    path: "drive.driven_speed".into(),
                    reason: format!(
                        "ω₂ = {} rad/s and ω₁ = `drive.driver_speed` = {} rad/s: a belt cannot run over drums turning in opposite senses, or over one turning drum and one at rest; give both the same sign (both 0 at rest)",
                        crate::error::num(&w2),
                        crate::error::num(&w1)
                    ),
                });
            }
        }
        if let Some(st) = &d.steering {
            Steering::validate_history("tilt_x", &st.tilt_x)?;
            Steering::validate_history("tilt_y", &st.tilt_y)?;
        }
        Ok(())
    }

    /// The shell's run from the `fem` block with its defaults (docs on
    /// [`FemSettings`]): n_σ = 64, n_ζ = 2 (the shell's solve replaces an absent n_ζ by
    /// the fewest elements that resolve the belt's edge layer: `fem::shell::scene::run_of`),
    /// ωΔt = [`SHELL_STEP_ANGLE`] (Δt = π/(32ω₁);
    /// 1 s at rest), the rotation over `steps`, ⌈`duration`/Δt⌉ or one revolution of the
    /// belt L/(ω₁R), one ramp step, frames at the start and the end, the Simpson rule for
    /// the interlayer. Assumes a validated
    /// shell scene; `steps` is at least 1.
    pub fn shell_run(&self) -> ShellRun {
        let f = self.fem_settings();
        let omega = self.drive.driver_speed.abs();
        let time_step = f.time_step.unwrap_or(if omega > 0.0 { SHELL_STEP_ANGLE / omega } else { 1.0 });
        let revolution = if omega > 0.0 { self.belt.length / (omega * self.drive.pulley_radius) } else { time_step };
        let steps = match (f.steps, f.duration) {
            (Some(n), _) => n,
            (None, Some(d)) => (d / time_step - 1e-9).ceil().max(1.0) as usize,
            (None, None) => (revolution / time_step - 1e-9).ceil().max(1.0) as usize,
        };
        ShellRun {
            elements_sigma: f.elements_sigma.unwrap_or(64),
            elements_zeta: f.elements_zeta.unwrap_or(2),
            time_step,
            steps,
            ramp_steps: f.ramp_steps.unwrap_or(1),
            frame_every: f.frame_every.unwrap_or(0),
            contact_rule: f.contact_rule.unwrap_or_default(),
            contact_rule_width: f.contact_rule_width.unwrap_or_default(),
            zeta_mesh: f.zeta_mesh.unwrap_or_default(),
            sigma_grading: f.sigma_grading.unwrap_or_default(),
        }
    }

    /// The `fem` block of a shell: only the shell's settings (`elements_sigma`,
    /// `elements_zeta`, `time_step`, `steps` or `duration`, `ramp_steps`, `frame_every`,
    /// `contact_rule`, `contact_rule_width`, `zeta_mesh`, `sigma_grading`, the grading's
    /// ratio in [0, 1000] and width in (0, 1000]);
    /// the rod and string settings are refused by name rather than ignored; the rotation
    /// at most [`MAX_SHELL_STEPS`] steps.
    fn validate_shell_fem(&self, f: &FemSettings) -> Result<(), SceneError> {
        let shell = self.belt.theory == Theory::Shell;
        let shell_fields = [
            ("fem.elements_sigma", f.elements_sigma.is_some()),
            ("fem.elements_zeta", f.elements_zeta.is_some()),
            ("fem.steps", f.steps.is_some()),
            ("fem.duration", f.duration.is_some()),
            ("fem.ramp_steps", f.ramp_steps.is_some()),
            ("fem.frame_every", f.frame_every.is_some()),
            ("fem.contact_rule", f.contact_rule.is_some()),
            ("fem.contact_rule_width", f.contact_rule_width.is_some()),
            ("fem.zeta_mesh", f.zeta_mesh.is_some()),
            ("fem.sigma_grading", f.sigma_grading.is_some()),
        ];
        if !shell {
            if let Some((path, _)) = shell_fields.iter().find(|(_, given)| *given) {
                return Err(SceneError::NotAllowed { path: (*path).into(), reason: format!("a setting of the shell's FE; this scene's belt is theory `{}` (its FE mesh is `fem.elements`)", self.belt.theory) });
            }
            return Ok(());
        }
        let rod_fields = [
            ("fem.elements", f.elements != FemSettings::default_elements()),
            ("fem.mesh_sequence", !f.mesh_sequence.is_empty()),
            ("fem.formulations", !f.formulations.is_empty()),
            ("fem.penalty", f.penalty.is_some()),
            ("fem.max_steps", f.max_steps.is_some()),
            ("fem.steady_tolerance", f.steady_tolerance.is_some()),
            ("fem.steady_scheme", f.steady_scheme.is_some()),
            ("fem.contact", f.contact.is_some()),
        ];
        if let Some((path, _)) = rod_fields.iter().find(|(_, given)| *given) {
            return Err(SceneError::NotAllowed {
                path: (*path).into(),
                reason: "a setting of the rod and string FE, not read by the shell's: the shell takes `elements_sigma`, `elements_zeta`, `time_step`, `steps` or `duration`, `ramp_steps`, `frame_every`, `contact_rule`, `contact_rule_width`, `zeta_mesh`, `sigma_grading` (its contact is the scene's elastic interlayer)".into(),
            });
        }
        if let Some(g) = f.sigma_grading {
            // NaN fails both comparisons
            if !(g.ratio >= 0.0 && g.ratio <= ShellSigmaGrading::MAX_RATIO) {
                return Err(SceneError::OutOfRange { path: "fem.sigma_grading.ratio".into(), value: g.ratio, range: format!("from 0 to {} (the elements at a contact edge are 1 + ratio times shorter than far from it)", ShellSigmaGrading::MAX_RATIO) });
            }
            if !(g.width > 0.0 && g.width <= ShellSigmaGrading::MAX_WIDTH) {
                return Err(SceneError::OutOfRange { path: "fem.sigma_grading.width".into(), value: g.width, range: format!("above 0, at most {} (foundation lengths ℓ_c = (D/P)^{{1/4}})", ShellSigmaGrading::MAX_WIDTH) });
            }
        }
        let steps = self.shell_run().steps;
        if steps > MAX_SHELL_STEPS {
            let path = if f.steps.is_some() { "fem.steps" } else { "fem.duration" };
            return Err(SceneError::OutOfRange {
                path: path.into(),
                value: if f.steps.is_some() { steps as f64 } else { f.duration.unwrap_or(0.0) },
                range: format!("at most {MAX_SHELL_STEPS} time steps of the rotation (this gives {steps}); lengthen `fem.time_step` or shorten the run"),
            });
        }
        Ok(())
    }

    /// Spec §2.2–2.3: R, D, c > 0; the tensions > 0, ω finite, φ_B in [−π, π]; exactly
    /// two prescriptions, at least one a tension; EA (and GA of a Cosserat rod) above
    /// χ = ρc²; analysis `steady` (Paper C solves the steady motion).
    fn validate_one_pulley(&self) -> Result<(), SceneError> {
        let d = &self.drive;
        check_positive("drive.pulley_radius", d.pulley_radius)?;
        for (path, v) in [("drive.end_distance", d.end_distance), ("drive.transport_rate", d.transport_rate)] {
            // both required by the schema walk; a scene built in code may lack them
            let v = v.ok_or_else(|| SceneError::Required { path: path.into(), reason: "for layout `one-pulley`".into() })?;
            check_positive(path, v)?;
        }
        for (path, v) in [("drive.tension_in", d.tension_in), ("drive.tension_out", d.tension_out)] {
            if let Some(v) = v {
                check_positive(path, v)?;
            }
        }
        if let Some(w) = d.pulley_speed {
            check_finite("drive.pulley_speed", w)?;
        }
        if let Some(phi) = d.stick_slip_angle {
            check_finite("drive.stick_slip_angle", phi)?;
            // the string wraps the half from the top (π/2) to the bottom (−π/2) between its
            // horizontal spans, and a rod's contact lies inside the string's: a stick → slip
            // point elsewhere has no contact to lie in (both methods failed on φ_B = 2 rad,
            // the BVP's Newton and the FE's load path, under unrelated messages)
            if phi.abs() >= std::f64::consts::FRAC_PI_2 {
                return Err(SceneError::OutOfRange {
                    path: "drive.stick_slip_angle".into(),
                    value: phi,
                    range: "a polar angle about the pulley centre on the wrapped half, −π/2 < φ_B < π/2 rad (the belt touches the pulley at most from its top, φ = π/2, to its bottom, φ = −π/2: the string's contact arc between horizontal spans, which a rod's lies inside)".into(),
                });
            }
        }
        if d.one_pulley_load().is_none() {
            let given = d.one_pulley_given().into_iter().map(|(n, v)| (n.to_string(), v)).collect();
            return Err(SceneError::OnePulleyPrescription { given });
        }
        if d.belt_drives_pulley.is_some() && d.stick_slip_angle.is_none() {
            return Err(SceneError::NotAllowed {
                path: "drive.belt_drives_pulley".into(),
                reason: "it chooses the sense of a prescribed `stick_slip_angle` (φ_B fixes the slip arc, not its sense); with the two tensions or `pulley_speed` given the sense follows from them".into(),
            });
        }
        if let Some(g) = self.effects.gravity.filter(|&g| g != 0.0) {
            return Err(SceneError::NotAllowed {
                path: "effects.gravity".into(),
                reason: format!(
                    "layout `one-pulley` is Paper C's belt over one pulley without gravity (spec §2.2: its open ends carry no weight, and neither solver has the load on this layout); got {} m/s² — remove it or set it to 0",
                    crate::error::num(&g)
                ),
            });
        }
        if self.analysis != Analysis::Steady {
            return Err(SceneError::NotAllowed {
                path: "analysis".into(),
                reason: format!(
                    "layout `one-pulley` is the belt in steady motion over one pulley (Paper C), so the analysis must be `steady` (got `{}`)",
                    self.analysis
                ),
            });
        }
        let (rho, c) = (self.belt.mass_per_length, d.transport_rate.unwrap_or(0.0));
        let chi = rho * c * c;
        let stiffnesses = [("belt.axial_stiffness", Some(self.belt.axial_stiffness)), ("belt.shear_stiffness", self.belt.shear_stiffness)];
        for (path, k) in stiffnesses {
            if let Some(k) = k.filter(|&k| k <= chi) {
                return Err(SceneError::SpeedAtOrAboveCritical { path: path.into(), stiffness: k, mass_per_length: rho, transport_rate: c });
            }
        }
        // a tensioned shear rod softer in shear than its tension: the edge layers of the
        // linearised theory decay with β² = (b₂ − χ − T̃)/a (spec C-10's (b₂ − F)/a with the
        // moving belt's b₂ − χ and T̃), so at b₂ − χ ≤ T̃ they oscillate instead — measured:
        // both methods fail from their start there (docs/cosserat-pulley.md, hard cases)
        if let (Theory::Cosserat, Some(b2)) = (self.belt.theory, self.belt.shear_stiffness) {
            let chi = if self.effects.inertia == Some(true) { chi } else { 0.0 };
            let b1 = self.belt.axial_stiffness;
            for (end, n) in [("tension_in", d.tension_in), ("tension_out", d.tension_out)] {
                let Some(n) = n else { continue };
                let effective = n - chi * (1.0 + n / b1);
                if b2 - chi <= effective {
                    return Err(SceneError::NotAllowed {
                        path: "belt.shear_stiffness".into(),
                        reason: format!(
                            "b₂ − ρc² = {} N does not exceed the effective tension T̃ = {} N at `drive.{end}` = {} N: a tensioned rod that soft in shear has no decaying edge layers (β² = (b₂ − ρc² − T̃)/a ≤ 0 in the linearised theory, spec C-10), so neither method has a solution to offer; b₂ must exceed {} N",
                            crate::error::num(&(b2 - chi)),
                            crate::error::num(&effective),
                            crate::error::num(&n),
                            crate::error::num(&(effective + chi))
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    fn validate_belt(&self) -> Result<(), SceneError> {
        let b = &self.belt;
        if self.drive.layout == Layout::TwoPulley {
            check_positive("belt.length", b.length)?;
        }
        if b.theory == Theory::Shell {
            self.validate_plate()?;
        }
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

    /// The plate of a shell: every parameter given and positive, h < b (a shell is thin),
    /// −1 < ν < 0.5, camber with exactly one finite field.
    fn validate_plate(&self) -> Result<(), SceneError> {
        let b = &self.belt;
        for (name, v) in b.plate_fields() {
            let path = format!("belt.{name}");
            let v = v.ok_or_else(|| SceneError::Required { path: path.clone(), reason: "for theory `shell`".into() })?;
            if name == "poisson_ratio" {
                check_poisson_ratio(&path, v)?;
            } else {
                check_positive(&path, v)?;
            }
        }
        if let (Some(h), Some(w)) = (b.thickness, b.width) {
            if h >= w {
                return Err(SceneError::OutOfRange {
                    path: "belt.thickness".into(),
                    value: h,
                    range: format!("a shell is thin: h < b = `belt.width` = {} m", crate::error::num(&w)),
                });
            }
        }
        if let Some(c) = &b.camber {
            let path = match (c.curvature, c.edge_length_difference) {
                (Some(_), None) => "belt.camber.curvature",
                _ => "belt.camber.edge_length_difference",
            };
            match (c.curvature, c.edge_length_difference) {
                (Some(v), None) | (None, Some(v)) => check_finite(path, v)?,
                (k, d) => {
                    return Err(SceneError::Invalid {
                        path: "belt.camber".into(),
                        reason: format!(
                            "give exactly one of `curvature` (κ_c, 1/m) and `edge_length_difference` (ΔL, m); got {}",
                            if k.is_some() && d.is_some() { "both" } else { "neither" }
                        ),
                    })
                }
            }
            // the unstressed fibre at ζ has the length ℓ*(ζ) = 1 − κ_c ζ per unit length
            // (spec §4.3): an edge of zero or negative length is no belt
            if let (Some(w), Some(l)) = (b.width, Some(b.length).filter(|&l| l > 0.0)) {
                let kappa = c.curvature_for(w, l);
                if kappa.abs() * 0.5 * w >= 1.0 {
                    let given = c.curvature.or(c.edge_length_difference).unwrap_or(kappa);
                    return Err(SceneError::OutOfRange {
                        path: path.into(),
                        value: given,
                        range: format!(
                            "|κ_c| b/2 < 1: the unstressed fibre at ζ has the length (1 − κ_c ζ) per unit length, so an edge would have zero or negative length (κ_c = {} 1/m, b = {} m; ΔL = κ_c b L)",
                            crate::error::num(&kappa),
                            crate::error::num(&w)
                        ),
                    });
                }
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
                if let Some((d, e, nu)) = layer.material() {
                    check_positive("effects.contact.elastic_layer.thickness", d)?;
                    check_positive("effects.contact.elastic_layer.youngs_modulus", e)?;
                    check_poisson_ratio("effects.contact.elastic_layer.poisson_ratio", nu)?;
                }
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
        // Both rotation senses and both power flows are solved by both methods in steady
        // motion and by the FE transient (docs/string-drive.md, docs/fem-drive.md §13;
        // issue 12, "four quadrants").
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
                    ("drive.driven_speed", d.driven_speed.unwrap_or(0.0), "rad/s"),
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
                self.check_friction_capacity()?;
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

    /// A steady two-pulley friction drive whose load no belt tension of its order can
    /// carry: the friction of a wrap of at most a full turn carries at most
    /// R·T_t·(1 − e^{−2πμ}) (Euler–Eytelwein, T_s ≥ 0), so the load M = |M₂ + d₂ω₁|
    /// needs a tight-side tension T_need = M / (R(1 − e^{−2πμ})). The loop's tension is of
    /// the order T_belt = max(EA(L_geom/L − 1), 0) + ρgL + (EA(ρgH)²/24)^{1/3} + ρc²
    /// (the stretch, the weight, the tension of a span hanging at zero slack, the transport
    /// term with c = |ω₁|R), and T_t + T_s stays near twice it. Refused only when
    /// T_need > 100 × 2T_belt — a margin wide enough that no solvable scene is refused —
    /// with the numbers; the solvers find the nearer cases on their homotopy paths
    /// (`FrictionCapacityExceeded`). Before, μ = 1e-13 started the BVP from a loop at
    /// 8e14 N and failed with "Newton iteration did not converge", the FE with "homotopy
    /// stalled at η = 0" (issue 12, smaller items).
    fn check_friction_capacity(&self) -> Result<(), SceneError> {
        let (&Contact::Coulomb(mu), Layout::TwoPulley) = (&self.effects.contact, self.drive.layout) else {
            return Ok(());
        };
        let (d, b) = (&self.drive, &self.belt);
        let load = (d.driven_torque + d.driven_damping * d.driver_speed).abs();
        if load == 0.0 || mu.is_nan() || mu <= 0.0 {
            return Ok(());
        }
        let g = self.effects.gravity.unwrap_or(0.0).abs();
        let (ea, rho) = (b.axial_stiffness, b.mass_per_length);
        let stretch = (ea * (self.geometric_length() / b.length - 1.0)).max(0.0);
        let weight = rho * g * b.length;
        let hanging = (ea * (rho * g * d.centre_distance).powi(2) / 24.0).cbrt();
        let transport = if self.effects.inertia == Some(true) { rho * (d.driver_speed * d.pulley_radius).powi(2) } else { 0.0 };
        let belt = stretch + weight + hanging + transport;
        let need = load / (d.pulley_radius * -(-2.0 * std::f64::consts::PI * mu).exp_m1());
        if need > 100.0 * 2.0 * belt {
            return Err(SceneError::NotAllowed {
                path: "effects.contact.coulomb".into(),
                reason: format!(
                    "no steady solution: the load |M₂ + d₂ω₁| = {load:.4e} N·m needs a tight-side tension of at least {need:.4e} N to be carried by friction μ = {} over even a full turn of wrap (M/(R(1 − e^{{−2πμ}}))), but the belt's tension is of the order of {belt:.4e} N (stretch {stretch:.4e} N, weight {weight:.4e} N, hanging span {hanging:.4e} N, transport ρc² {transport:.4e} N): raise μ or the pretension, or lower the load",
                    crate::error::num(&mu),
                ),
            });
        }
        Ok(())
    }

    // -----------------------------------------------------------------------
    // Derived quantities

    /// The compound contour g(σ) of this scene's two pulleys (assumes a validated
    /// two-pulley scene; an invalid or one-pulley one gives meaningless numbers, never a
    /// panic — see [`Scene::open_contour`]).
    pub fn contour(&self) -> Contour {
        Contour::new_unchecked(self.drive.pulley_radius, self.drive.centre_distance)
    }

    /// The open contour of a one-pulley scene (`None` for the two-pulley loop, whose
    /// contour is [`Scene::contour`]; assumes a validated scene).
    pub fn open_contour(&self) -> Option<crate::contour::OpenContour> {
        match self.drive.layout {
            Layout::OnePulley => crate::contour::OpenContour::new(self.drive.pulley_radius, self.drive.end_distance?).ok(),
            Layout::TwoPulley => None,
        }
    }

    /// The reference line of this scene's layout: the two-pulley loop ([`Scene::contour`])
    /// or the open one-pulley contour ([`Scene::open_contour`]); assumes a validated scene.
    pub fn path(&self) -> crate::contour::Path {
        match self.open_contour() {
            Some(open) => crate::contour::Path::Open(open),
            None => crate::contour::Path::Loop(self.contour()),
        }
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
        check_relative_tolerance("bvp.tolerance", self.tolerance)?;
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
        if let Some(n) = self.elements_sigma {
            if !(8..=4096).contains(&n) {
                return Err(SceneError::OutOfRange { path: "fem.elements_sigma".into(), value: n as f64, range: "8 … 4096 elements round the loop (at least two per region of the contour)".into() });
            }
        }
        if let Some(n) = self.elements_zeta {
            if !(2..=64).contains(&n) || !n.is_multiple_of(2) {
                return Err(SceneError::OutOfRange {
                    path: "fem.elements_zeta".into(),
                    value: n as f64,
                    range: "an even number 2 … 64 of elements across the width (a node on the centre line ζ = 0 holds the zero modes of the static start, docs/fem-shell.md §9.1)".into(),
                });
            }
        }
        if self.steps == Some(0) {
            return Err(SceneError::OutOfRange { path: "fem.steps".into(), value: 0.0, range: "at least 1 time step".into() });
        }
        if let Some(d) = self.duration {
            check_positive("fem.duration", d)?;
            if self.steps.is_some() {
                return Err(SceneError::NotAllowed { path: "fem.duration".into(), reason: "give the rotation's length as `steps` or as `duration`, not both".into() });
            }
        }
        if self.ramp_steps == Some(0) {
            return Err(SceneError::OutOfRange { path: "fem.ramp_steps".into(), value: 0.0, range: "at least 1 step of the ramp at rest".into() });
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
        if let Some(levels) = &self.levels {
            if levels.len() < 3 {
                return Err(SceneError::OutOfRange { path: "gate.levels".into(), value: levels.len() as f64, range: "three or more levels [n_σ, n_ζ] (Richardson extrapolation of the three finest)".into() });
            }
            if let Some(k) = levels.iter().position(|&[ns, nz]| ns == 0 || nz == 0) {
                return Err(SceneError::Invalid { path: format!("gate.levels[{k}]"), reason: "n_σ and n_ζ must be at least 1".into() });
            }
        }
        if self.steps == Some(0) {
            return Err(SceneError::OutOfRange { path: "gate.steps".into(), value: 0.0, range: "at least one rotation step".into() });
        }
        if let Some(t) = self.reference_tolerance {
            check_relative_tolerance("gate.reference_tolerance", t)?;
        }
        if let Some(t) = self.bvp_tolerance {
            check_relative_tolerance("gate.bvp_tolerance", t)?;
            if let Some(r) = self.reference_tolerance.filter(|&r| r >= t) {
                return Err(SceneError::OutOfRange {
                    path: "gate.bvp_tolerance".into(),
                    value: t,
                    range: format!("above gate.reference_tolerance = {r:e} (the reference must be the tighter run)"),
                });
            }
        }
        Ok(())
    }
}

/// A relative tolerance at `path`: 0 < tolerance < 1.
fn check_relative_tolerance(path: &str, value: f64) -> Result<(), SceneError> {
    check_positive(path, value)?;
    if value >= 1.0 {
        return Err(SceneError::OutOfRange {
            path: path.into(),
            value,
            range: "a relative tolerance, 0 < tolerance < 1".into(),
        });
    }
    Ok(())
}

/// `value` must pass `holds`, else the error `variant` builds from the path and value.
fn check_that(path: &str, value: f64, holds: bool, variant: fn(String, f64) -> SceneError) -> Result<(), SceneError> {
    if holds {
        Ok(())
    } else {
        Err(variant(path.into(), value))
    }
}

/// A Poisson's ratio of a stable isotropic material: −1 < ν < 0.5.
fn check_poisson_ratio(path: &str, nu: f64) -> Result<(), SceneError> {
    if nu > -1.0 && nu < 0.5 {
        return Ok(());
    }
    Err(SceneError::OutOfRange { path: path.into(), value: nu, range: "−1 < ν < 0.5 (a stable isotropic material)".into() })
}

/// `value` must be finite.
pub(crate) fn check_finite(path: &str, value: f64) -> Result<(), SceneError> {
    check_that(path, value, value.is_finite(), |path, value| SceneError::NotFinite { path, value })
}

/// `value` must be finite and > 0.
pub(crate) fn check_positive(path: &str, value: f64) -> Result<(), SceneError> {
    check_finite(path, value)?;
    check_that(path, value, value > 0.0, |path, value| SceneError::NotPositive { path, value })
}

/// `value` must be finite and ≥ 0.
pub(crate) fn check_non_negative(path: &str, value: f64) -> Result<(), SceneError> {
    check_finite(path, value)?;
    check_that(path, value, value >= 0.0, |path, value| SceneError::Negative { path, value })
}
