//! Errors of the `drive` crate.
//!
//! Every variant carries the data a user needs to fix the input: the *field path*
//! of the offending value in the scene JSON (e.g. `belt.axial_stiffness`,
//! `fem.mesh_sequence[2]`, `gate.tolerances.y_upper_mid`) and the numbers involved.
//! The root of the document is written `<scene>`.

use std::path::PathBuf;

/// Why a scene was rejected: parsing, the schema walk, or [`crate::Scene::validate`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene file `{}`: {message}", .path.display())]
    Io {
        /// File that was opened.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },

    /// The text is not JSON at all (position 1-based, as serde_json reports it).
    #[error("scene is not valid JSON (line {line}, column {column}): {message}")]
    Syntax {
        /// Line of the error (1-based).
        line: usize,
        /// Column of the error (1-based).
        column: usize,
        /// serde_json's description.
        message: String,
    },

    /// A key given twice in one JSON object (at any depth): JSON readers disagree on
    /// which one counts, so neither is taken (position 1-based, of the second one).
    #[error("duplicate key `{path}` (line {line}, column {column}): each key may appear once per object; remove one of the two")]
    DuplicateKey {
        /// Full path of the repeated key.
        path: String,
        /// Line of the second occurrence (1-based).
        line: usize,
        /// Column just after the second occurrence of the key (1-based).
        column: usize,
    },

    /// A key that the scene format does not define (every nesting level is checked).
    #[error("unknown field `{path}`{}", unknown_hint(.suggestion.as_deref(), .allowed))]
    UnknownField {
        /// Full path of the unknown key.
        path: String,
        /// The nearest valid name (a sibling name, or the full path of the same name
        /// elsewhere in the scene when the key sits in the wrong block).
        suggestion: Option<String>,
        /// The names valid at this level.
        allowed: Vec<String>,
    },

    /// A required field is absent.
    #[error("missing required field `{path}` ({what})")]
    MissingField {
        /// Full path of the missing field.
        path: String,
        /// What the field is, with its unit.
        what: String,
    },

    /// A value of the wrong JSON type (e.g. a string where a number belongs).
    #[error("`{path}`: expected {expected}, found {found}")]
    WrongType {
        /// Full path of the value.
        path: String,
        /// The JSON type the format needs.
        expected: String,
        /// What was found (type and a short rendering of the value).
        found: String,
    },

    /// A string (or single-key object) that names no variant of an enumeration
    /// (belt theory, analysis, contact model, BVP method).
    #[error("`{path}`: unknown {what} `{value}`{}", unknown_hint(.suggestion.as_deref(), .allowed))]
    UnknownVariant {
        /// Full path of the value.
        path: String,
        /// What is enumerated ("belt theory", "contact model", ...).
        what: String,
        /// The value given.
        value: String,
        /// The nearest valid variant.
        suggestion: Option<String>,
        /// All valid variants.
        allowed: Vec<String>,
    },

    /// NaN or ±∞ (only reachable for scenes built in code: JSON has no such numbers).
    #[error("`{path}` must be finite, got {}", num(.value))]
    NotFinite {
        /// Full path of the value.
        path: String,
        /// The value.
        value: f64,
    },

    /// A quantity that must be strictly positive (stiffness, length, radius, mass,
    /// tolerance, penalty) is zero or negative.
    #[error("`{path}` must be positive, got {}", num(.value))]
    NotPositive {
        /// Full path of the value.
        path: String,
        /// The value.
        value: f64,
    },

    /// A quantity that must be non-negative (gravity, friction coefficient, damping)
    /// is negative.
    #[error("`{path}` must not be negative, got {}", num(.value))]
    Negative {
        /// Full path of the value.
        path: String,
        /// The value.
        value: f64,
    },

    /// A value outside its documented range.
    #[error("`{path}` = {} is out of range: {range}", num(.value))]
    OutOfRange {
        /// Full path of the value.
        path: String,
        /// The value.
        value: f64,
        /// The valid range, in words.
        range: String,
    },

    /// A field that is optional in general but required by another choice of the
    /// scene (e.g. `belt.bending_stiffness` for theory `kirchhoff`).
    #[error("`{path}` is required {reason}")]
    Required {
        /// Full path of the field.
        path: String,
        /// Which choice needs it, and what it is.
        reason: String,
    },

    /// A field or effect that the scene's theory or analysis cannot take.
    #[error("`{path}` is not allowed: {reason}")]
    NotAllowed {
        /// Full path of the field.
        path: String,
        /// Why, and what to change.
        reason: String,
    },

    /// The two pulleys overlap: H ≤ 2R.
    #[error(
        "`drive.centre_distance` = {} m must exceed 2·`drive.pulley_radius` = 2·{} m = {} m: the pulleys would overlap",
        num(.centre_distance), num(.pulley_radius), num(&(2.0 * .pulley_radius))
    )]
    PulleysOverlap {
        /// H, m.
        centre_distance: f64,
        /// R, m.
        pulley_radius: f64,
    },

    /// A one-pulley scene must prescribe exactly two of `tension_in`, `tension_out`,
    /// `pulley_speed`, `stick_slip_angle`, at least one a tension (spec §2.3: with c given,
    /// the four are tied by two relations).
    #[error("layout `one-pulley` prescribes exactly two of `drive.tension_in`, `drive.tension_out`, `drive.pulley_speed`, `drive.stick_slip_angle`, at least one a tension; got {}", given_list(.given))]
    OnePulleyPrescription {
        /// The prescriptions given, with their values.
        given: Vec<(String, f64)>,
    },

    /// The transport rate reaches a critical speed of the belt: the stiffness named by
    /// `path` (EA, or GA of a Cosserat rod) does not exceed χ = ρc².
    #[error("`{path}` = {} N must exceed χ = ρc² = {}·{}² = {} N: the belt moves at or above its critical speed (`drive.transport_rate`)", num(.stiffness), num(.mass_per_length), num(.transport_rate), num(&(.mass_per_length * .transport_rate * .transport_rate)))]
    SpeedAtOrAboveCritical {
        /// `belt.axial_stiffness` or `belt.shear_stiffness`.
        path: String,
        /// The stiffness, N.
        stiffness: f64,
        /// ρ, kg/m.
        mass_per_length: f64,
        /// c, m/s.
        transport_rate: f64,
    },

    /// Any other inconsistency of one value (a name with forbidden characters, a
    /// mesh sequence that does not increase, ...).
    #[error("`{path}`: {reason}")]
    Invalid {
        /// Full path of the value.
        path: String,
        /// What is wrong.
        reason: String,
    },
}

impl SceneError {
    /// The field path the error is about (`None` for I/O, syntax and the
    /// two-field geometry error, whose message names both fields).
    pub fn path(&self) -> Option<&str> {
        match self {
            SceneError::Io { .. }
            | SceneError::Syntax { .. }
            | SceneError::PulleysOverlap { .. }
            | SceneError::OnePulleyPrescription { .. } => None,
            SceneError::SpeedAtOrAboveCritical { path, .. } => Some(path),
            SceneError::UnknownField { path, .. }
            | SceneError::DuplicateKey { path, .. }
            | SceneError::MissingField { path, .. }
            | SceneError::WrongType { path, .. }
            | SceneError::UnknownVariant { path, .. }
            | SceneError::NotFinite { path, .. }
            | SceneError::NotPositive { path, .. }
            | SceneError::Negative { path, .. }
            | SceneError::OutOfRange { path, .. }
            | SceneError::Required { path, .. }
            | SceneError::NotAllowed { path, .. }
            | SceneError::Invalid { path, .. } => Some(path),
        }
    }
}

/// A number for a message: fixed notation for 1e-4 ≤ |v| < 1e7 (and 0), otherwise
/// scientific, always the shortest representation that round-trips (at most 17
/// significant digits — never the hundreds of digits of `{}` on 1e-300 or 1e300).
pub fn num(v: &f64) -> String {
    let a = v.abs();
    if *v == 0.0 || (1e-4..1e7).contains(&a) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Text from the input as it appears in a message: more than 64 characters are cut to
/// their first 40 and the count (a key or value of megabytes is not echoed whole).
pub fn clip(text: &str) -> String {
    let n = text.chars().count();
    if n > 64 {
        format!("{}…({n} characters)", text.chars().take(40).collect::<String>())
    } else {
        text.to_string()
    }
}

/// "none" or "`a` = 1, `b` = 2".
fn given_list(given: &[(String, f64)]) -> String {
    if given.is_empty() {
        return "none".into();
    }
    let items: Vec<String> = given.iter().map(|(n, v)| format!("`drive.{n}` = {}", num(v))).collect();
    format!("{}: {}", items.len(), items.join(", "))
}

impl ResultError {
    /// The same error with `prefix` before the name of the offending entry (a frame's
    /// fields report `history.frames[1].fields.x[3]`).
    pub fn within(self, prefix: &str) -> ResultError {
        match self {
            ResultError::NotFinite { quantity, value } => ResultError::NotFinite { quantity: format!("{prefix}{quantity}"), value },
            ResultError::FieldLength { field, len, expected } => ResultError::FieldLength { field: format!("{prefix}{field}"), len, expected },
            ResultError::UnknownField { field, suggestion } => ResultError::UnknownField { field: format!("{prefix}{field}"), suggestion },
            other => other,
        }
    }
}

/// "; did you mean `x`?" or "; expected one of `a`, `b`".
fn unknown_hint(suggestion: Option<&str>, allowed: &[String]) -> String {
    match suggestion {
        Some(s) => format!("; did you mean `{s}`?"),
        None if allowed.is_empty() => String::new(),
        None => {
            let list: Vec<String> = allowed.iter().map(|a| format!("`{a}`")).collect();
            format!("; expected one of {}", list.join(", "))
        }
    }
}

/// Why a result cannot be written: it would contain a non-finite number (serde_json
/// writes NaN as `null`, which readers would take for "absent") or ragged fields.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ResultError {
    /// A scalar or field sample is NaN or ±∞.
    #[error("result quantity `{quantity}` is not finite ({})", num(.value))]
    NotFinite {
        /// Name as in the result JSON, e.g. `driver.torque`, `fields.tension[12]`,
        /// `cost.wall_seconds`.
        quantity: String,
        /// The value.
        value: f64,
    },
    /// A field vector whose length differs from `fields.sigma`.
    #[error("result field `fields.{field}` has {len} samples, `fields.sigma` has {expected}")]
    FieldLength {
        /// Field name (`x`, `y`, `tension`, `moment`).
        field: String,
        /// Its length.
        len: usize,
        /// Length of `sigma`.
        expected: usize,
    },
    /// A field or channel name the result format does not define (a surface field
    /// outside [`crate::result::SURFACE_FIELD_NAMES`], a history channel that is no
    /// lowercase identifier).
    #[error("`{field}` is not a field of the result format{}", unknown_hint(.suggestion.as_deref(), &[]))]
    UnknownField {
        /// Full name, e.g. `surface.zz`.
        field: String,
        /// The nearest valid name.
        suggestion: Option<String>,
    },
    /// A discretisation outside its range (a tolerance not in (0, 1), no elements, a
    /// time step that is not > 0).
    #[error("result `{field}` = {} is out of range: expected {expected}", num(.value))]
    Discretisation {
        /// Name as in the result JSON, e.g. `discretisation.elements`.
        field: String,
        /// The value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A name that is not a summary scalar (see [`crate::summary::SCALAR_NAMES`]).
    #[error("`{name}` is not a summary quantity{}", unknown_hint(.suggestion.as_deref(), &[]))]
    UnknownQuantity {
        /// The name given.
        name: String,
        /// The nearest valid name.
        suggestion: Option<String>,
    },
}
