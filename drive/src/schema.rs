//! The schema walk of a scene: the JSON value is checked against the list of
//! allowed keys of each block before serde sees it, so that every message names the
//! full field path — unknown keys (with the nearest valid name), missing required
//! fields, wrong JSON types, unknown enumeration values. Optional fields given as
//! `null` are removed (= absent, so serde fills their defaults).
//!
//! The tables below mirror the structs of [`crate::scene`]; a unit test checks that
//! every table accepts what serde writes for a fully populated scene.

use serde_json::Value;

use crate::error::SceneError;
use crate::suggest::nearest;

/// What a value must be.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Kind {
    /// A JSON number (ranges are checked later by `validate`).
    Number,
    /// A non-negative integer that fits `usize`.
    Count,
    /// `true` / `false`.
    Bool,
    /// Any string.
    Text,
    /// One of a fixed list of strings.
    Choice {
        what: &'static str,
        variants: &'static [&'static str],
    },
    /// A nested block.
    Object(&'static [Field]),
    /// An array of counts.
    CountList,
    /// An array of strings.
    TextList,
    /// An object of numbers with free keys.
    NumberMap,
    /// `effects.contact`: `"frictionless"`, `{"coulomb": μ}`, `{"elastic_layer": {..}}`.
    Contact,
    /// A history `[[t, value], …]`: an array of two-number arrays.
    History,
    /// Levels `[[n_σ, n_ζ], …]`: an array of pairs of counts.
    CountPairs,
}

impl Kind {
    fn expected(self) -> String {
        match self {
            Kind::Number => "a number".into(),
            Kind::Count => "a non-negative integer".into(),
            Kind::Bool => "true or false".into(),
            Kind::Text => "a string".into(),
            Kind::Choice { variants, .. } => {
                let v: Vec<String> = variants.iter().map(|v| format!("\"{v}\"")).collect();
                format!("one of {}", v.join(", "))
            }
            Kind::Object(_) | Kind::NumberMap => "an object".into(),
            Kind::CountList => "an array of non-negative integers".into(),
            Kind::TextList => "an array of strings".into(),
            Kind::Contact => r#""frictionless", {"coulomb": μ} or {"elastic_layer": {...}}"#.into(),
            Kind::History => "an array of [t, value] pairs of numbers".into(),
            Kind::CountPairs => "an array of [n_σ, n_ζ] pairs of non-negative integers".into(),
        }
    }
}

/// When a key may or must appear.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Need {
    /// Required in every scene.
    Always,
    /// Optional in every scene.
    Optional,
    /// Required where the condition holds, not allowed elsewhere.
    In(Cond),
    /// Optional where the condition holds, not allowed elsewhere.
    OptionalIn(Cond),
}

/// A choice of the scene that decides which fields exist.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cond {
    /// `drive.layout` is `two-pulley` (or absent).
    TwoPulley,
    /// `drive.layout` is `one-pulley`.
    OnePulley,
    /// `belt.theory` is `shell`.
    Shell,
    /// `belt.theory` is not `shell`.
    NotShell,
    /// The elastic interlayer is given by its two stiffnesses.
    LayerStiffness,
    /// The elastic interlayer is given by its material (any of `thickness`,
    /// `youngs_modulus`, `poisson_ratio` present).
    LayerMaterial,
}

impl Cond {
    fn holds(self, ctx: Ctx) -> bool {
        match self {
            Cond::TwoPulley => !ctx.one_pulley,
            Cond::OnePulley => ctx.one_pulley,
            Cond::Shell => ctx.shell,
            Cond::NotShell => !ctx.shell,
            Cond::LayerStiffness => !ctx.layer_material,
            Cond::LayerMaterial => ctx.layer_material,
        }
    }

    /// Why a field of this condition is not allowed in the scene at hand.
    fn refusal(self) -> &'static str {
        match self {
            Cond::TwoPulley => "it belongs to layout `two-pulley` (the closed loop over two pulleys); this scene's `drive.layout` is `one-pulley` (one pulley, open ends)",
            Cond::OnePulley => "it belongs to layout `one-pulley` (one pulley, open ends); this scene's layout is `two-pulley` — set `drive.layout` to \"one-pulley\" or remove the field",
            Cond::Shell => "it belongs to theory `shell` (a plate parameter, or a setting of the shell's run-off: both drums at prescribed speed, the steering drum, the shell's mesh and time stepping); this scene's belt is a rod or string",
            Cond::LayerStiffness => "the interlayer is given by its material (`thickness`, `youngs_modulus`, `poisson_ratio`), from which P and P_⊥ are derived; give one form, not both",
            Cond::LayerMaterial => "unreachable: a material field makes the material form",
            Cond::NotShell => "theory `shell` derives it from the plate parameters (EA = E b h, EI = E b h³/(12(1 − ν²)), ρ = ρ_V b h); give `width`, `thickness`, `youngs_modulus`, `poisson_ratio`, `density` instead",
        }
    }
}

/// The choices of a scene that decide which fields exist, read before the walk.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Ctx {
    one_pulley: bool,
    shell: bool,
    layer_material: bool,
}

impl Ctx {
    fn of(root: &Value) -> Ctx {
        Ctx {
            one_pulley: root.pointer("/drive/layout").and_then(Value::as_str) == Some("one-pulley"),
            shell: root.pointer("/belt/theory").and_then(Value::as_str) == Some("shell"),
            layer_material: root
                .pointer("/effects/contact/elastic_layer")
                .and_then(Value::as_object)
                .is_some_and(|m| ["thickness", "youngs_modulus", "poisson_ratio"].iter().any(|k| m.contains_key(*k))),
        }
    }
}

/// One allowed key of a block.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Field {
    pub name: &'static str,
    pub kind: Kind,
    pub need: Need,
    /// What the field is, with unit (for "missing field" messages).
    pub what: &'static str,
}

const fn req(name: &'static str, kind: Kind, what: &'static str) -> Field {
    Field { name, kind, need: Need::Always, what }
}

const fn opt(name: &'static str, kind: Kind, what: &'static str) -> Field {
    Field { name, kind, need: Need::Optional, what }
}

/// Required where `cond` holds, not allowed elsewhere.
const fn req_in(cond: Cond, name: &'static str, kind: Kind, what: &'static str) -> Field {
    Field { name, kind, need: Need::In(cond), what }
}

/// Optional where `cond` holds, not allowed elsewhere.
const fn opt_in(cond: Cond, name: &'static str, kind: Kind, what: &'static str) -> Field {
    Field { name, kind, need: Need::OptionalIn(cond), what }
}

pub(crate) const THEORIES: &[&str] = &["string", "kirchhoff", "cosserat", "shell"];
pub(crate) const ANALYSES: &[&str] = &["static", "steady", "transient"];
pub(crate) const BVP_METHODS: &[&str] = &["bvp-collocation", "bvp-shooting"];
pub(crate) const CONTACT_MODELS: &[&str] = &["frictionless", "coulomb", "elastic_layer"];

pub(crate) const LAYOUTS: &[&str] = &["two-pulley", "one-pulley"];

pub(crate) const DRIVE: &[Field] = &[
    opt("layout", Kind::Choice { what: "drive layout", variants: LAYOUTS }, "drive layout"),
    req("pulley_radius", Kind::Number, "pulley radius R to the belt centreline, m"),
    req_in(Cond::TwoPulley, "centre_distance", Kind::Number, "centre distance H of the pulleys, m"),
    req_in(Cond::TwoPulley, "driver_speed", Kind::Number, "driver speed ω₁, rad/s, clockwise positive"),
    req_in(Cond::TwoPulley, "driven_torque", Kind::Number, "torque M₂ resisting the driven pulley, N·m"),
    opt_in(Cond::TwoPulley, "driven_damping", Kind::Number, "viscous damping of the driven pulley, N·m·s"),
    req_in(Cond::OnePulley, "end_distance", Kind::Number, "distance D of the end sections x = −D from the pulley centre, m"),
    req_in(Cond::OnePulley, "transport_rate", Kind::Number, "transport rate c, m/s"),
    opt_in(Cond::OnePulley, "tension_in", Kind::Number, "axial force at the inflow end, N"),
    opt_in(Cond::OnePulley, "tension_out", Kind::Number, "axial force at the outflow end, N"),
    opt_in(Cond::OnePulley, "pulley_speed", Kind::Number, "pulley speed ω, rad/s, clockwise positive"),
    opt_in(Cond::OnePulley, "stick_slip_angle", Kind::Number, "polar angle φ_B of the stick-to-slip transition, rad"),
    opt_in(Cond::OnePulley, "belt_drives_pulley", Kind::Bool, "with stick_slip_angle: the belt drives the pulley (N_in < N_out); default false"),
    opt_in(Cond::Shell, "driven_speed", Kind::Number, "prescribed speed ω₂ of the driven drum, rad/s (shell)"),
    opt_in(Cond::Shell, "steering", Kind::Object(STEERING), "the steering drum and its tilt histories (shell)"),
];

pub(crate) const STEERING: &[Field] = &[
    req("drum", Kind::Choice { what: "steering drum", variants: &["driver", "driven"] }, "the steered drum, \"driver\" or \"driven\""),
    opt("tilt_x", Kind::History, "history [[t, β_x], …] of the tilt about the span direction, s and rad"),
    opt("tilt_y", Kind::History, "history [[t, β_y], …] of the swivel in the plane of the axes, s and rad"),
];

pub(crate) const CAMBER: &[Field] = &[
    opt("curvature", Kind::Number, "camber curvature κ_c, 1/m"),
    opt("edge_length_difference", Kind::Number, "length difference of the belt edges, m"),
];

pub(crate) const BELT: &[Field] = &[
    req("theory", Kind::Choice { what: "belt theory", variants: THEORIES }, "belt theory"),
    req_in(Cond::TwoPulley, "length", Kind::Number, "unstretched belt length L, m"),
    req_in(Cond::NotShell, "axial_stiffness", Kind::Number, "axial stiffness EA, N"),
    opt_in(Cond::NotShell, "bending_stiffness", Kind::Number, "bending stiffness EI, N·m²"),
    opt("shear_stiffness", Kind::Number, "shear stiffness GA, N"),
    req_in(Cond::NotShell, "mass_per_length", Kind::Number, "mass per unit length ρ, kg/m"),
    req_in(Cond::Shell, "width", Kind::Number, "shell width b, m"),
    req_in(Cond::Shell, "thickness", Kind::Number, "shell thickness h, m"),
    req_in(Cond::Shell, "youngs_modulus", Kind::Number, "Young's modulus E of the shell, Pa"),
    req_in(Cond::Shell, "poisson_ratio", Kind::Number, "Poisson's ratio ν of the shell"),
    req_in(Cond::Shell, "density", Kind::Number, "density ρ_V of the shell material, kg/m³"),
    opt_in(Cond::Shell, "camber", Kind::Object(CAMBER), "camber imperfection of the shell"),
];

pub(crate) const ELASTIC_LAYER: &[Field] = &[
    req_in(Cond::LayerStiffness, "normal_stiffness", Kind::Number, "interlayer normal stiffness P, N/m³"),
    req_in(Cond::LayerStiffness, "tangential_stiffness", Kind::Number, "interlayer tangential stiffness P_⊥, N/m³"),
    req_in(Cond::LayerMaterial, "thickness", Kind::Number, "interlayer thickness d, m"),
    req_in(Cond::LayerMaterial, "youngs_modulus", Kind::Number, "Young's modulus E_l of the interlayer, Pa"),
    req_in(Cond::LayerMaterial, "poisson_ratio", Kind::Number, "Poisson's ratio ν_l of the interlayer"),
];

pub(crate) const EFFECTS: &[Field] = &[
    opt(
        "gravity",
        Kind::Number,
        "gravitational acceleration g, m/s²",
    ),
    opt("inertia", Kind::Bool, "transport inertia of steady motion"),
    req(
        "contact",
        Kind::Contact,
        r#"contact model: "frictionless", {"coulomb": μ} or {"elastic_layer": {...}}"#,
    ),
];

pub(crate) const BVP: &[Field] = &[
    opt(
        "method",
        Kind::Choice {
            what: "BVP method",
            variants: BVP_METHODS,
        },
        "BVP method",
    ),
    opt("tolerance", Kind::Number, "relative tolerance"),
    opt("scheme", Kind::Text, "collocation scheme"),
    opt("max_nodes", Kind::Count, "maximum collocation nodes"),
    opt(
        "shooting_intervals",
        Kind::Count,
        "shooting intervals per segment",
    ),
];

pub(crate) const FEM: &[Field] = &[
    opt("elements", Kind::Count, "number of elements"),
    opt(
        "mesh_sequence",
        Kind::CountList,
        "element counts of a convergence study",
    ),
    opt("formulations", Kind::TextList, "element formulations"),
    opt("penalty", Kind::Number, "contact penalty factor, N/m²"),
    opt("time_step", Kind::Number, "time step of the quasistatic transient, s"),
    opt("max_steps", Kind::Count, "largest number of time steps"),
    opt("steady_tolerance", Kind::Number, "steady-state threshold per radian of driver rotation"),
    opt(
        "steady_scheme",
        Kind::Choice { what: "steady scheme", variants: &["auto", "semismooth", "paper-d"] },
        "how the steady FE finds its stick and slip zones",
    ),
    opt(
        "contact",
        Kind::Choice { what: "normal contact", variants: &["penalty", "augmented-lagrangian"] },
        "the steady FE's normal contact on one pulley",
    ),
    opt_in(Cond::Shell, "elements_sigma", Kind::Count, "shell elements round the loop"),
    opt_in(Cond::Shell, "elements_zeta", Kind::Count, "shell elements across the width (even)"),
    opt_in(Cond::Shell, "steps", Kind::Count, "time steps of the rotation"),
    opt_in(Cond::Shell, "duration", Kind::Number, "simulated time of the rotation, s"),
    opt_in(Cond::Shell, "ramp_steps", Kind::Count, "steps of the ramp of camber and tilt at rest"),
    opt_in(Cond::Shell, "frame_every", Kind::Count, "steps between frames of surface fields"),
    opt_in(Cond::Shell, "contact_rule", Kind::Choice { what: "interlayer σ-rule", variants: &["simpson", "trapezoidal"] }, "σ-rule of the elastic interlayer"),
    opt_in(Cond::Shell, "contact_rule_width", Kind::Choice { what: "interlayer ζ-rule", variants: &["gauss2", "gauss3", "gauss4", "gauss5"] }, "Gauss points per ζ-element of the elastic interlayer"),
    opt_in(Cond::Shell, "zeta_mesh", Kind::Choice { what: "ζ-mesh across the width", variants: &["graded", "uniform"] }, "ζ-nodes graded towards the belt's edges or uniform"),
    opt_in(Cond::Shell, "sigma_grading", Kind::Object(SIGMA_GRADING), "grading of the σ-mesh towards the drums' contact edges"),
];

const SIGMA_GRADING: &[Field] = &[
    opt("ratio", Kind::Number, "peak refinement at a contact edge (elements 1 + ratio times shorter; default 8)"),
    opt("width", Kind::Number, "decay length of the refinement in foundation lengths (D/P)^(1/4) (default 2)"),
];

pub(crate) const GATE: &[Field] = &[
    opt(
        "tolerances",
        Kind::NumberMap,
        "relative tolerance per quantity",
    ),
    opt(
        "bvp_tolerances",
        Kind::NumberMap,
        "relative tolerance per quantity for the BVP methods",
    ),
    opt("min_order", Kind::Number, "minimum observed order"),
    opt("reference_tolerance", Kind::Number, "tolerance of the gate's BVP reference"),
    opt("bvp_tolerance", Kind::Number, "tolerance of the gated BVP runs"),
    opt("fem", Kind::Bool, "whether the gate runs the FE studies (default true)"),
    opt_in(Cond::Shell, "levels", Kind::CountPairs, "levels [[n_σ, n_ζ], …] of the gate's shell study (shell)"),
    opt_in(Cond::Shell, "steps", Kind::Count, "rotation steps of the gate's shell runs at the scene's Δt (shell)"),
];

pub(crate) const PEER: &[Field] = &[
    req("source", Kind::Text, "who computed the peer results and how"),
    opt("reference", Kind::Text, "where they are published"),
    req(
        "values",
        Kind::NumberMap,
        "published value per summary quantity",
    ),
    opt("note", Kind::Text, "why the results differ"),
];

pub(crate) const SCENE: &[Field] = &[
    req("name", Kind::Text, "scene name"),
    opt("description", Kind::Text, "description"),
    req("drive", Kind::Object(DRIVE), "pulley geometry and loads"),
    req("belt", Kind::Object(BELT), "belt theory and stiffnesses"),
    req("effects", Kind::Object(EFFECTS), "effects to simulate"),
    req(
        "analysis",
        Kind::Choice {
            what: "analysis",
            variants: ANALYSES,
        },
        r#""static", "steady" or "transient""#,
    ),
    opt("bvp", Kind::Object(BVP), "BVP settings"),
    opt("fem", Kind::Object(FEM), "finite element settings"),
    opt("gate", Kind::Object(GATE), "gate tolerances"),
    opt("peer", Kind::Object(PEER), "published results of another code"),
];

/// Parses scene text into a JSON value, refusing a key repeated in one object at any
/// depth ([`SceneError::DuplicateKey`] with its full path; serde_json alone keeps the
/// last one silently). A leading UTF-8 byte-order mark is accepted and skipped (editors
/// on Windows write one; it carries no content).
pub(crate) fn parse_strict(text: &str) -> Result<Value, SceneError> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    let duplicate = std::cell::RefCell::new(None);
    let mut de = serde_json::Deserializer::from_str(text);
    let parsed = serde::de::DeserializeSeed::deserialize(
        Strict {
            path: String::new(),
            duplicate: &duplicate,
        },
        &mut de,
    )
    .and_then(|v| de.end().map(|()| v));
    parsed.map_err(|e| match duplicate.into_inner() {
        Some(path) => SceneError::DuplicateKey {
            path,
            line: e.line(),
            column: e.column(),
        },
        None => SceneError::Syntax {
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        },
    })
}

/// A JSON value deserialised with its path known, so that a repeated key can be named.
struct Strict<'a> {
    path: String,
    /// Set to the path of the first repeated key (the error itself is serde_json's).
    duplicate: &'a std::cell::RefCell<Option<String>>,
}

impl<'de> serde::de::DeserializeSeed<'de> for Strict<'_> {
    type Value = Value;
    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> serde::de::Visitor<'de> for Strict<'_> {
    type Value = Value;
    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_string()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        loop {
            let path = format!("{}[{}]", shown(&self.path), items.len());
            match seq.next_element_seed(Strict {
                path,
                duplicate: self.duplicate,
            })? {
                Some(v) => items.push(v),
                None => return Ok(Value::Array(items)),
            }
        }
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            let path = join(&self.path, &key);
            if object.contains_key(&key) {
                *self.duplicate.borrow_mut() = Some(path);
                return Err(serde::de::Error::custom("duplicate key"));
            }
            let value = map.next_value_seed(Strict {
                path,
                duplicate: self.duplicate,
            })?;
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}

/// Walks a whole scene document (root path `<scene>`).
pub(crate) fn check_scene(value: &mut Value) -> Result<(), SceneError> {
    let ctx = Ctx::of(value);
    check_object(value, SCENE, "", ctx)
}

/// `path.key`; a key that is empty or has characters other than ASCII letters,
/// digits, `_`, `-`, `.` is written JSON-quoted (`belt."axial stiffness"`).
fn join(path: &str, key: &str) -> String {
    let key = &crate::error::clip(key);
    let plain = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    let key = if plain {
        key.to_string()
    } else {
        serde_json::Value::from(key.as_str()).to_string()
    };
    if path.is_empty() {
        key
    } else {
        format!("{path}.{key}")
    }
}

fn shown(path: &str) -> String {
    if path.is_empty() {
        "<scene>".to_string()
    } else {
        path.to_string()
    }
}

/// A short description of a JSON value for "found ..." messages.
fn describe(v: &Value) -> String {
    fn clip(s: &str) -> String {
        if s.chars().count() > 40 {
            format!("{}…", s.chars().take(40).collect::<String>())
        } else {
            s.to_string()
        }
    }
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("a boolean ({b})"),
        Value::Number(n) => format!("a number ({})", clip(&n.to_string())),
        Value::String(s) => format!("a string ({:?})", clip(s)),
        Value::Array(a) => format!("an array of {} elements", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

fn wrong_type(path: &str, kind: Kind, v: &Value) -> SceneError {
    SceneError::WrongType {
        path: shown(path),
        expected: kind.expected(),
        found: describe(v),
    }
}

fn check_object(value: &mut Value, fields: &'static [Field], path: &str, ctx: Ctx) -> Result<(), SceneError> {
    let Value::Object(map) = value else {
        return Err(wrong_type(path, Kind::Object(fields), value));
    };
    if let Some(key) = map
        .keys()
        .find(|k| !fields.iter().any(|f| f.name == k.as_str()))
    {
        return Err(unknown_field(path, key, fields));
    }
    for f in fields {
        let p = join(path, f.name);
        let (required, allowed) = match f.need {
            Need::Always => (true, None),
            Need::Optional => (false, None),
            Need::In(c) => (c.holds(ctx), Some(c)),
            Need::OptionalIn(c) => (false, Some(c)),
        };
        match map.get(f.name) {
            None if required => {
                return Err(SceneError::MissingField {
                    path: p,
                    what: f.what.into(),
                })
            }
            None => {}
            Some(Value::Null) if required => {
                return Err(SceneError::WrongType {
                    path: p,
                    expected: f.kind.expected(),
                    found: "null".into(),
                })
            }
            Some(Value::Null) => {
                map.remove(f.name);
            }
            Some(_) if allowed.is_some_and(|c| !c.holds(ctx)) => {
                let reason = allowed.map_or("", Cond::refusal);
                return Err(SceneError::NotAllowed { path: p, reason: reason.into() });
            }
            Some(_) => {
                if let Some(v) = map.get_mut(f.name) {
                    check_value(v, f.kind, &p, ctx)?;
                }
            }
        }
    }
    Ok(())
}

fn check_value(v: &mut Value, kind: Kind, path: &str, ctx: Ctx) -> Result<(), SceneError> {
    let ok = match kind {
        Kind::Number => v.is_number(),
        Kind::Count => is_count(v),
        Kind::Bool => v.is_boolean(),
        Kind::Text => v.is_string(),
        Kind::Choice { what, variants } => {
            let Value::String(s) = v else {
                return Err(wrong_type(path, kind, v));
            };
            if variants.contains(&s.as_str()) {
                return Ok(());
            }
            return Err(unknown_variant(path, what, s, variants));
        }
        Kind::Object(fields) => return check_object(v, fields, path, ctx),
        Kind::CountList => {
            let Value::Array(items) = v else {
                return Err(wrong_type(path, kind, v));
            };
            for (i, item) in items.iter().enumerate() {
                if !is_count(item) {
                    return Err(wrong_type(&format!("{path}[{i}]"), Kind::Count, item));
                }
            }
            true
        }
        Kind::TextList => {
            let Value::Array(items) = v else {
                return Err(wrong_type(path, kind, v));
            };
            for (i, item) in items.iter().enumerate() {
                if !item.is_string() {
                    return Err(wrong_type(&format!("{path}[{i}]"), Kind::Text, item));
                }
            }
            true
        }
        Kind::NumberMap => {
            let Value::Object(map) = v else {
                return Err(wrong_type(path, kind, v));
            };
            for (key, item) in map.iter() {
                if !item.is_number() {
                    return Err(wrong_type(&join(path, key), Kind::Number, item));
                }
            }
            true
        }
        Kind::Contact => return check_contact(v, path, ctx),
        Kind::History => {
            let Value::Array(items) = v else {
                return Err(wrong_type(path, kind, v));
            };
            for (i, item) in items.iter().enumerate() {
                let pair = item.as_array().is_some_and(|p| p.len() == 2 && p.iter().all(Value::is_number));
                if !pair {
                    return Err(SceneError::WrongType { path: format!("{path}[{i}]"), expected: "a pair [t, value] of two numbers".into(), found: describe(item) });
                }
            }
            true
        }
        Kind::CountPairs => {
            let Value::Array(items) = v else {
                return Err(wrong_type(path, kind, v));
            };
            for (i, item) in items.iter().enumerate() {
                let pair = item.as_array().is_some_and(|p| p.len() == 2 && p.iter().all(is_count));
                if !pair {
                    return Err(SceneError::WrongType { path: format!("{path}[{i}]"), expected: "a level [n_σ, n_ζ] of two non-negative integers".into(), found: describe(item) });
                }
            }
            true
        }
    };
    if ok {
        Ok(())
    } else {
        Err(wrong_type(path, kind, v))
    }
}

fn is_count(v: &Value) -> bool {
    v.as_u64().is_some_and(|n| usize::try_from(n).is_ok())
}

fn check_contact(v: &mut Value, path: &str, ctx: Ctx) -> Result<(), SceneError> {
    match v {
        Value::String(s) => match s.as_str() {
            "frictionless" => Ok(()),
            "coulomb" => Err(SceneError::Invalid {
                path: path.into(),
                reason: r#"contact model `coulomb` needs its friction coefficient: {"coulomb": μ}"#.into(),
            }),
            "elastic_layer" => Err(SceneError::Invalid {
                path: path.into(),
                reason: r#"contact model `elastic_layer` needs its stiffnesses: {"elastic_layer": {"normal_stiffness": P, "tangential_stiffness": P_t}}"#.into(),
            }),
            other => Err(unknown_variant(path, "contact model", other, CONTACT_MODELS)),
        },
        Value::Object(map) => {
            if map.len() != 1 {
                return Err(SceneError::Invalid {
                    path: path.into(),
                    reason: format!(
                        r#"a contact object has exactly one key, `coulomb` or `elastic_layer`; found {} keys"#,
                        map.len()
                    ),
                });
            }
            let Some((key, inner)) = map.iter_mut().next() else { return Ok(()) };
            let p = join(path, key);
            match key.as_str() {
                "coulomb" => check_value(inner, Kind::Number, &p, Ctx::default()),
                "elastic_layer" => check_object(inner, ELASTIC_LAYER, &p, ctx),
                "frictionless" => Err(SceneError::Invalid {
                    path: path.into(),
                    reason: r#"`frictionless` takes no value: write "contact": "frictionless""#.into(),
                }),
                other => Err(unknown_variant(path, "contact model", other, CONTACT_MODELS)),
            }
        }
        _ => Err(wrong_type(path, Kind::Contact, v)),
    }
}

fn unknown_variant(path: &str, what: &str, value: &str, variants: &[&str]) -> SceneError {
    SceneError::UnknownVariant {
        path: path.into(),
        what: what.into(),
        value: crate::error::clip(value),
        suggestion: nearest(value, variants.iter().copied()),
        allowed: variants.iter().map(|s| s.to_string()).collect(),
    }
}

/// An unknown key: suggest the nearest sibling; failing that, the full path of a
/// field of that name in another block (`drive.gravity` → `effects.gravity`).
fn unknown_field(path: &str, key: &str, fields: &[Field]) -> SceneError {
    let suggestion =
        nearest(key, fields.iter().map(|f| f.name)).or_else(|| elsewhere(key, SCENE, ""));
    SceneError::UnknownField {
        path: join(path, key),
        suggestion,
        allowed: fields.iter().map(|f| f.name.to_string()).collect(),
    }
}

fn elsewhere(key: &str, fields: &[Field], path: &str) -> Option<String> {
    for f in fields {
        let p = join(path, f.name);
        if f.name.eq_ignore_ascii_case(key) {
            return Some(p);
        }
        let nested = match f.kind {
            Kind::Object(inner) => elsewhere(key, inner, &p),
            Kind::Contact => elsewhere(key, ELASTIC_LAYER, &join(&p, "elastic_layer")),
            _ => None,
        };
        if nested.is_some() {
            return nested;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrong_block_suggests_full_path() {
        let fields: &[Field] = DRIVE;
        match unknown_field("drive", "gravity", fields) {
            SceneError::UnknownField {
                path, suggestion, ..
            } => {
                assert_eq!(path, "drive.gravity");
                assert_eq!(suggestion.as_deref(), Some("effects.gravity"));
            }
            e => panic!("{e}"),
        }
    }

    #[test]
    fn null_optional_is_removed() {
        let mut v: Value = serde_json::json!({"gravity": null, "contact": "frictionless"});
        check_object(&mut v, EFFECTS, "effects", Ctx::default()).unwrap();
        assert!(v.get("gravity").is_none());
    }

    /// Everything serde writes for fully populated settings passes the walk (the
    /// tables and the structs agree).
    #[test]
    fn tables_accept_serialised_structs() {
        use crate::scene::*;
        let bvp = serde_json::to_value(BvpSettings::default()).unwrap();
        let fem = serde_json::to_value(FemSettings {
            penalty: Some(1e6),
            mesh_sequence: vec![8, 16],
            time_step: Some(1e-3),
            max_steps: Some(100),
            steady_tolerance: Some(1e-6),
            steady_scheme: Some(SteadyScheme::PaperD),
            contact: Some(NormalContact::AugmentedLagrangian),
            elements_sigma: Some(64),
            elements_zeta: Some(2),
            steps: Some(24),
            duration: Some(1.0),
            ramp_steps: Some(2),
            frame_every: Some(4),
            contact_rule: Some(crate::scene::ShellContactRule::Trapezoidal),
            contact_rule_width: Some(crate::scene::ShellWidthRule::Gauss4),
            zeta_mesh: Some(crate::scene::ShellZetaMesh::Uniform),
            sigma_grading: Some(crate::scene::ShellSigmaGrading { ratio: 24.0, width: 6.0 }),
            ..Default::default()
        })
        .unwrap();
        let shell = Ctx { shell: true, ..Ctx::default() };
        let gate = serde_json::to_value(GateSettings {
            min_order: Some(2.0),
            bvp_tolerances: [("y_upper_mid".to_string(), 1e-6)].into(),
            reference_tolerance: Some(1e-9),
            bvp_tolerance: Some(1e-7),
            fem: Some(false),
            levels: Some(vec![[32, 2], [64, 2], [128, 2]]),
            steps: Some(2),
            ..Default::default()
        })
        .unwrap();
        for (mut v, table, name) in [(bvp, BVP, "bvp"), (fem, FEM, "fem"), (gate, GATE, "gate")] {
            let n_keys = v.as_object().map_or(0, |m| m.len());
            assert_eq!(
                n_keys,
                table.len(),
                "{name}: struct and table differ in field count"
            );
            check_object(&mut v, table, name, shell).unwrap();
        }
        let mut steering = serde_json::to_value(Steering { drum: SteeringDrum::Driven, tilt_x: vec![[0.0, 1e-3]], tilt_y: vec![[0.0, 0.0], [1.0, 2e-3]] }).unwrap();
        assert_eq!(steering.as_object().map_or(0, |m| m.len()), STEERING.len());
        check_object(&mut steering, STEERING, "drive.steering", shell).unwrap();
        let layer = ElasticLayer { normal_stiffness: 1.0, tangential_stiffness: 2.0, thickness: None, youngs_modulus: None, poisson_ratio: None };
        let mut contact = serde_json::to_value(Contact::ElasticLayer(layer)).unwrap();
        check_contact(&mut contact, "effects.contact", Ctx::default()).unwrap();
        let mut contact = serde_json::to_value(Contact::Coulomb(0.3)).unwrap();
        check_contact(&mut contact, "effects.contact", Ctx::default()).unwrap();
        let mut contact = serde_json::to_value(Contact::Frictionless).unwrap();
        check_contact(&mut contact, "effects.contact", Ctx::default()).unwrap();
    }
}
