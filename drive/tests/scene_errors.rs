//! Scene contract: the DESIGN.md example is the valid baseline; every class of error
//! is provoked once by a minimal edit of it and the message is checked to name the
//! field path and, where relevant, the suggestion or the numbers.

use drive::{Analysis, Contact, Scene, SceneError, Theory};
use serde_json::{json, Value};

/// The scene example of DESIGN.md ("Scene format"), verbatim.
const DESIGN_EXAMPLE: &str = r#"{
  "name": "string-hanging",
  "description": "Extensible string hanging on two frictionless pulleys",
  "drive": {
    "pulley_radius": 0.08,
    "centre_distance": 0.45,
    "driver_speed": 0.0,
    "driven_torque": 0.0
  },
  "belt": {
    "theory": "string",
    "length": 1.41,
    "axial_stiffness": 2.0e4,
    "bending_stiffness": null,
    "shear_stiffness": null,
    "mass_per_length": 0.12
  },
  "effects": {
    "gravity": 9.81,
    "contact": "frictionless"
  },
  "analysis": "static"
}"#;

fn base() -> Value {
    serde_json::from_str(DESIGN_EXAMPLE).unwrap()
}

/// `base()` with the value at a dotted path replaced (or inserted).
fn set(mut v: Value, path: &str, new: Value) -> Value {
    let mut parts: Vec<&str> = path.split('.').collect();
    let last = parts.pop().unwrap();
    let mut cur = &mut v;
    for p in parts {
        cur = cur.get_mut(p).unwrap();
    }
    cur.as_object_mut().unwrap().insert(last.to_string(), new);
    v
}

/// `base()` with the key at a dotted path removed.
fn remove(mut v: Value, path: &str) -> Value {
    let mut parts: Vec<&str> = path.split('.').collect();
    let last = parts.pop().unwrap();
    let mut cur = &mut v;
    for p in parts {
        cur = cur.get_mut(p).unwrap();
    }
    cur.as_object_mut().unwrap().remove(last);
    v
}

fn parse(v: &Value) -> Result<Scene, SceneError> {
    Scene::from_json_str(&v.to_string())
}

/// Parses, expects an error, checks its path and that the message contains every
/// fragment; returns the message.
fn err(v: Value, path: Option<&str>, fragments: &[&str]) -> String {
    let e = parse(&v).expect_err("scene should be rejected");
    let msg = e.to_string();
    assert_eq!(e.path(), path, "path of: {msg}");
    for f in fragments {
        assert!(msg.contains(f), "message {msg:?} lacks {f:?}");
    }
    msg
}

/// `base()` with the value at `path` set to `new` is rejected at the field path `at`
/// with every fragment in its message (see [`err`]).
fn rejected(path: &str, new: Value, at: &str, fragments: &[&str]) -> String {
    err(set(base(), path, new), Some(at), fragments)
}

/// The belt made a steel shell strip (DESIGN.md: a shell gives its plate, not a section).
fn shell_belt(v: Value) -> Value {
    let mut v = set(v, "belt.theory", json!("shell"));
    for k in ["axial_stiffness", "mass_per_length", "bending_stiffness"] {
        v["belt"].as_object_mut().unwrap().remove(k);
    }
    let plate = [("width", 0.02), ("thickness", 1e-4), ("youngs_modulus", 2.1e11), ("poisson_ratio", 0.3), ("density", 7850.0)];
    for (k, x) in plate {
        v = set(v, &format!("belt.{k}"), json!(x));
    }
    v
}

/// A steady Cosserat drive with friction: the other valid baseline.
fn cosserat_drive() -> Value {
    let v = set(base(), "analysis", json!("steady"));
    let v = set(v, "belt.theory", json!("cosserat"));
    let v = set(v, "belt.bending_stiffness", json!(0.5));
    let v = set(v, "belt.shear_stiffness", json!(1.0e5));
    let v = set(v, "effects.contact", json!({"coulomb": 0.5}));
    let v = set(v, "effects.inertia", json!(true));
    let v = set(v, "drive.driver_speed", json!(30.0));
    set(v, "drive.driven_torque", json!(2.0))
}

// --- valid scenes ---------------------------------------------------------------

#[test]
fn design_example_is_valid() {
    let s = Scene::from_json_str(DESIGN_EXAMPLE).unwrap();
    assert_eq!(s.name, "string-hanging");
    assert_eq!(s.belt.theory, Theory::String);
    assert_eq!(s.belt.bending_stiffness, None);
    assert_eq!(s.effects.contact, Contact::Frictionless);
    assert_eq!(s.analysis, Analysis::Static);
    assert_eq!(s.drive.driven_damping, 0.0);
    let lg = 2.0 * 0.45 + 2.0 * std::f64::consts::PI * 0.08;
    assert!((s.geometric_length() - lg).abs() < 1e-15);
    assert!((s.slack_ratio() - 1.41 / lg).abs() < 1e-15);
    assert_eq!(s.effect_names(), vec!["gravity", "frictionless contact"]);
    assert_eq!(s.bvp_settings().tolerance, 1e-8);
    assert_eq!(s.bvp_settings().max_nodes, 20_000);
    assert_eq!(s.bvp_settings().shooting_intervals, 8);
    assert_eq!(s.fem_settings().elements, 256);
    assert_eq!(s.fem_settings().meshes(), vec![64, 128, 256]);
}

#[test]
fn cosserat_drive_is_valid_and_round_trips() {
    let v = set(
        cosserat_drive(),
        "bvp",
        json!({"method": "bvp-shooting", "tolerance": 1e-10}),
    );
    let v = set(
        v,
        "fem",
        json!({"mesh_sequence": [32, 64, 128], "formulations": ["c1-mel"], "penalty": 1e7}),
    );
    let v = set(
        v,
        "gate",
        json!({"tolerances": {"y_upper_mid": 1e-3, "driver.slip_arc": 1e-2, "moment_l2": 0.1}, "min_order": 1.5}),
    );
    let s = parse(&v).unwrap();
    assert_eq!(
        s.effect_names(),
        vec!["gravity", "transport inertia", "coulomb friction"]
    );
    assert_eq!(s.bvp_settings().scheme, "gauss8");
    let back = Scene::from_json_str(&s.to_json_pretty()).unwrap();
    assert_eq!(back, s);
    // and the baseline
    let s = Scene::from_json_str(DESIGN_EXAMPLE).unwrap();
    assert_eq!(Scene::from_json_str(&s.to_json_pretty()).unwrap(), s);
}

#[test]
fn stretched_on_and_very_slack_belts_are_valid() {
    for length in [0.5, 1.0, 2.0] {
        let s = parse(&set(base(), "belt.length", json!(length))).unwrap();
        assert!((s.slack_ratio() - length / s.geometric_length()).abs() < 1e-15);
    }
}

#[test]
fn shell_with_elastic_layer_is_valid() {
    let v = set(base(), "analysis", json!("transient"));
    let v = shell_belt(v);
    let v = set(
        v,
        "effects.contact",
        json!({"elastic_layer": {"normal_stiffness": 1e9, "tangential_stiffness": 1e8}}),
    );
    let s = parse(&v).unwrap();
    assert_eq!(
        s.effect_names(),
        vec!["gravity", "elastic interlayer contact"]
    );
}

// --- syntax and schema ----------------------------------------------------------

#[test]
fn syntax_error_gives_line_and_column() {
    let e = Scene::from_json_str("{\n  \"name\": \"x\",\n  oops\n}").unwrap_err();
    assert!(matches!(e, SceneError::Syntax { line: 3, .. }), "{e}");
    assert!(e.to_string().contains("line 3"));
}

#[test]
fn unknown_field_with_suggestion_at_every_level() {
    let msg = err(
        set(
            remove(base(), "belt.axial_stiffness"),
            "belt.axial_stifness",
            json!(2e4),
        ),
        Some("belt.axial_stifness"),
        &[],
    );
    assert_eq!(
        msg,
        "unknown field `belt.axial_stifness`; did you mean `axial_stiffness`?"
    );
    rejected("nme", json!("x"), "nme", &["did you mean `name`?"]);
    rejected("drive.pulley_radus", json!(0.1), "drive.pulley_radus", &["did you mean `pulley_radius`?"]);
    rejected("effects.gravty", json!(9.81), "effects.gravty", &["did you mean `gravity`?"]);
    rejected("bvp", json!({"tolerence": 1e-6}), "bvp.tolerence", &["did you mean `tolerance`?"]);
    rejected("fem", json!({"element": 64}), "fem.element", &["did you mean `elements`?"]);
    rejected("gate", json!({"min_ordre": 2.0}), "gate.min_ordre", &["did you mean `min_order`?"]);
    let v = set(cosserat_drive(), "analysis", json!("transient"));
    let v = shell_belt(remove(v, "belt.shear_stiffness"));
    let v = set(
        v,
        "effects.contact",
        json!({"elastic_layer": {"normal_stifness": 1e9, "tangential_stiffness": 1e8}}),
    );
    err(
        v,
        Some("effects.contact.elastic_layer.normal_stifness"),
        &["did you mean `normal_stiffness`?"],
    );
}

#[test]
fn unknown_field_in_the_wrong_block_names_the_right_one() {
    rejected("drive.gravity", json!(9.81), "drive.gravity", &["unknown field `drive.gravity`; did you mean `effects.gravity`?"]);
}

#[test]
fn unknown_field_without_near_name_lists_the_valid_ones() {
    rejected("belt.colour", json!("black"), "belt.colour", &["expected one of `theory`, `length`, `axial_stiffness`, `bending_stiffness`, `shear_stiffness`, `mass_per_length`"]);
}

#[test]
fn missing_required_fields() {
    err(
        remove(base(), "belt.length"),
        Some("belt.length"),
        &["missing required field `belt.length`", "m)"],
    );
    err(
        remove(base(), "drive"),
        Some("drive"),
        &["missing required field `drive`"],
    );
    err(
        remove(base(), "effects.contact"),
        Some("effects.contact"),
        &["missing required field `effects.contact`"],
    );
    err(
        remove(base(), "name"),
        Some("name"),
        &["missing required field `name`"],
    );
}

#[test]
fn wrong_types() {
    rejected("belt.length", json!("1.41"), "belt.length", &["expected a number", "a string (\"1.41\")"]);
    rejected("belt.length", Value::Null, "belt.length", &["expected a number", "found null"]);
    rejected("belt", json!([1, 2]), "belt", &["expected an object", "an array of 2 elements"]);
    rejected("effects.inertia", json!(1), "effects.inertia", &["expected true or false"]);
    rejected("fem", json!({"elements": 64.5}), "fem.elements", &["non-negative integer", "64.5"]);
    rejected("fem", json!({"mesh_sequence": [8, -16]}), "fem.mesh_sequence[1]", &["non-negative integer"]);
    err(
        set(
            base(),
            "gate",
            json!({"tolerances": {"y_upper_mid": "tight"}}),
        ),
        Some("gate.tolerances.y_upper_mid"),
        &["expected a number"],
    );
    let e = Scene::from_json_str("[1, 2]").unwrap_err();
    assert_eq!(e.path(), Some("<scene>"));
}

#[test]
fn unknown_enumeration_values() {
    rejected("belt.theory", json!("kirchoff"), "belt.theory", &["unknown belt theory `kirchoff`; did you mean `kirchhoff`?"]);
    err(
        set(base(), "analysis", json!("dynamic")),
        Some("analysis"),
        &[
            "unknown analysis `dynamic`",
            "`static`, `steady`, `transient`",
        ],
    );
    rejected("effects.contact", json!("frictonless"), "effects.contact", &["did you mean `frictionless`?"]);
    rejected("effects.contact", json!({"colomb": 0.3}), "effects.contact", &["unknown contact model `colomb`; did you mean `coulomb`?"]);
    rejected("effects.contact", json!("coulomb"), "effects.contact", &["{\"coulomb\": μ}"]);
    err(
        set(
            base(),
            "effects.contact",
            json!({"coulomb": 0.3, "elastic_layer": {}}),
        ),
        Some("effects.contact"),
        &["exactly one key"],
    );
    rejected("bvp", json!({"method": "collocation"}), "bvp.method", &["did you mean `bvp-collocation`?"]);
}

// --- values ---------------------------------------------------------------------

#[test]
fn non_finite_values_are_rejected() {
    // JSON cannot spell NaN; out-of-range literals are syntax errors...
    assert!(matches!(
        Scene::from_json_str(&DESIGN_EXAMPLE.replace("1.41", "1e999")),
        Err(SceneError::Syntax { .. })
    ));
    // ...and scenes built in code are checked by validate()
    let mut s = Scene::from_json_str(DESIGN_EXAMPLE).unwrap();
    s.belt.axial_stiffness = f64::INFINITY;
    let e = s.validate().unwrap_err();
    assert_eq!(e.path(), Some("belt.axial_stiffness"));
    assert_eq!(
        e.to_string(),
        "`belt.axial_stiffness` must be finite, got inf"
    );
    let mut s = Scene::from_json_str(DESIGN_EXAMPLE).unwrap();
    s.drive.driver_speed = f64::NAN;
    assert_eq!(s.validate().unwrap_err().path(), Some("drive.driver_speed"));
}

#[test]
fn non_positive_stiffness_length_radius_mass() {
    for field in [
        "belt.length",
        "belt.axial_stiffness",
        "belt.mass_per_length",
        "drive.pulley_radius",
    ] {
        let msg = err(
            set(base(), field, json!(-2.5)),
            Some(field),
            &["must be positive, got -2.5"],
        );
        assert!(msg.starts_with(&format!("`{field}`")), "{msg}");
    }
    rejected("belt.length", json!(0), "belt.length", &["must be positive, got 0"]);
    let v = set(cosserat_drive(), "belt.shear_stiffness", json!(0.0));
    err(v, Some("belt.shear_stiffness"), &["must be positive"]);
    let v = set(cosserat_drive(), "belt.bending_stiffness", json!(-1e-3));
    err(
        v,
        Some("belt.bending_stiffness"),
        &["must be positive, got -0.001"],
    );
}

#[test]
fn negative_gravity_friction_damping() {
    rejected("effects.gravity", json!(-9.81), "effects.gravity", &["must not be negative, got -9.81"]);
    err(
        set(
            cosserat_drive(),
            "effects.contact",
            json!({"coulomb": -0.2}),
        ),
        Some("effects.contact.coulomb"),
        &["must not be negative, got -0.2"],
    );
    err(
        set(cosserat_drive(), "drive.driven_damping", json!(-1.0)),
        Some("drive.driven_damping"),
        &["must not be negative"],
    );
}

#[test]
fn overlapping_pulleys_name_the_numbers() {
    let e = parse(&set(base(), "drive.centre_distance", json!(0.15))).unwrap_err();
    assert!(matches!(e, SceneError::PulleysOverlap { .. }));
    assert_eq!(
        e.to_string(),
        "`drive.centre_distance` = 0.15 m must exceed 2·`drive.pulley_radius` = 2·0.08 m = 0.16 m: the pulleys would overlap"
    );
}

// --- theory requirements ----------------------------------------------------------

#[test]
fn rod_theories_need_their_stiffnesses() {
    let v = set(base(), "belt.theory", json!("kirchhoff"));
    err(
        v.clone(),
        Some("belt.bending_stiffness"),
        &["is required for theory `kirchhoff`", "N·m²"],
    );
    let v = set(cosserat_drive(), "belt.shear_stiffness", Value::Null);
    err(
        v,
        Some("belt.shear_stiffness"),
        &["is required for theory `cosserat`", "GA"],
    );
    let v = set(cosserat_drive(), "belt.bending_stiffness", Value::Null);
    err(
        v,
        Some("belt.bending_stiffness"),
        &["is required for theory `cosserat`"],
    );
}

#[test]
fn string_takes_no_bending_or_shear_stiffness() {
    rejected("belt.bending_stiffness", json!(0.5), "belt.bending_stiffness", &["theory `string` has no bending stiffness", "0.5"]);
    rejected("belt.shear_stiffness", json!(1e5), "belt.shear_stiffness", &["theory `string` has no shear stiffness"]);
    let v = set(base(), "belt.theory", json!("kirchhoff"));
    let v = set(v, "belt.bending_stiffness", json!(0.5));
    let v = set(v, "belt.shear_stiffness", json!(1e5));
    err(
        v,
        Some("belt.shear_stiffness"),
        &["unshearable", "theory `cosserat`"],
    );
}

// --- effects vs analysis ----------------------------------------------------------

#[test]
fn static_analysis_takes_no_motion_effects() {
    rejected("effects.inertia", json!(true), "effects.inertia", &["needs analysis `steady` or `transient`"]);
    // inertia explicitly off is fine
    parse(&set(base(), "effects.inertia", json!(false))).unwrap();
    rejected("effects.contact", json!({"coulomb": 0.3}), "effects.contact", &["friction needs analysis `steady` or `transient`", "0.3"]);
    rejected("drive.driver_speed", json!(3.0), "drive.driver_speed", &["static", "got 3 rad/s"]);
    rejected("drive.driven_torque", json!(1.5), "drive.driven_torque", &["got 1.5 N·m"]);
}

#[test]
fn steady_analysis_needs_friction() {
    let v = set(cosserat_drive(), "effects.contact", json!("frictionless"));
    err(v, Some("effects.contact"), &["steady", "coulomb"]);
}

#[test]
fn transient_analysis_is_fe_only() {
    let v = set(cosserat_drive(), "analysis", json!("transient"));
    parse(&v).unwrap();
    let v = set(v, "bvp", json!({}));
    err(v, Some("bvp"), &["finite elements only"]);
}

#[test]
fn elastic_layer_is_for_shells_only() {
    let v = set(
        cosserat_drive(),
        "effects.contact",
        json!({"elastic_layer": {"normal_stiffness": 1e9, "tangential_stiffness": 1e8}}),
    );
    err(
        v,
        Some("effects.contact"),
        &["theory `shell` only", "`cosserat`"],
    );
}

// --- settings -------------------------------------------------------------------

#[test]
fn settings_ranges() {
    rejected("bvp", json!({"tolerance": 2.0}), "bvp.tolerance", &["= 2 is out of range", "0 < tolerance < 1"]);
    rejected("bvp", json!({"tolerance": 0}), "bvp.tolerance", &["must be positive"]);
    rejected("bvp", json!({"max_nodes": 2}), "bvp.max_nodes", &["at least 4"]);
    rejected("bvp", json!({"scheme": ""}), "bvp.scheme", &["empty"]);
    rejected("fem", json!({"elements": 3}), "fem.elements", &["at least 4"]);
    rejected("fem", json!({"mesh_sequence": [64, 32]}), "fem.mesh_sequence[1]", &["32 follows 64"]);
    rejected("fem", json!({"formulations": ["a", "a"]}), "fem.formulations[1]", &["twice"]);
    rejected("fem", json!({"penalty": -1}), "fem.penalty", &["must be positive"]);
    rejected("gate", json!({"tolerances": {"y_uper_mid": 1e-3}}), "gate.tolerances.y_uper_mid", &["did you mean `y_upper_mid`?"]);
    rejected("gate", json!({"tolerances": {"driver.torque": 0}}), "gate.tolerances.driver.torque", &["must be positive"]);
    rejected("gate", json!({"min_order": -2}), "gate.min_order", &["must be positive"]);
    rejected("gate", json!({"reference_tolerance": 1.0}), "gate.reference_tolerance", &["0 < tolerance < 1"]);
    rejected("gate", json!({"bvp_tolerance": 0}), "gate.bvp_tolerance", &["must be positive"]);
    // the reference must be the tighter run
    rejected("gate", json!({"reference_tolerance": 1e-7, "bvp_tolerance": 1e-7}), "gate.bvp_tolerance", &["above gate.reference_tolerance = 1e-7"]);
    let ok = parse(&set(base(), "gate", json!({"tolerances": {"y_upper_mid": 1e-6}, "reference_tolerance": 1e-8, "bvp_tolerance": 1e-7}))).unwrap();
    let gate = ok.gate_settings();
    assert_eq!((gate.reference_tolerance, gate.bvp_tolerance), (Some(1e-8), Some(1e-7)));
}

#[test]
fn null_optional_settings_take_their_defaults() {
    let s = parse(&set(
        base(),
        "bvp",
        json!({"tolerance": null, "method": null}),
    ))
    .unwrap();
    assert_eq!(s.bvp_settings(), drive::BvpSettings::default());
}

#[test]
fn name_is_file_name_safe() {
    err(set(base(), "name", json!("")), Some("name"), &["empty"]);
    rejected("name", json!("../etc/x"), "name", &["'/'"]);
}

#[test]
fn from_path_reports_the_file() {
    let e = Scene::from_path(std::path::Path::new("/nonexistent/scene.json")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/scene.json"));
    let dir = std::env::temp_dir().join(format!("drive-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("s.json");
    std::fs::write(&file, DESIGN_EXAMPLE).unwrap();
    assert_eq!(Scene::from_path(&file).unwrap().name, "string-hanging");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The optional `peer` block (published results of another code, docs/string-drive.md):
/// accepted with summary names and finite values; an unknown quantity is named with the
/// nearest summary name; a missing `values` map is named.
#[test]
fn peer_block() {
    let peer = json!({"source": "Exudyn ALE-ANCF", "values": {"tension_tight": 666.5, "driver.torque": -47.72}});
    let text = set(base(), "peer", peer).to_string();
    let scene = Scene::from_json_str(&text).expect("valid peer block");
    assert_eq!(scene.peer.as_ref().unwrap().values["tension_tight"], 666.5);
    let bad = json!({"source": "x", "values": {"tension_tigth": 1.0}});
    let e = Scene::from_json_str(&set(base(), "peer", bad).to_string()).unwrap_err().to_string();
    assert!(e.contains("peer.values.tension_tigth") && e.contains("tension_tight"), "{e}");
    let missing = json!({"source": "x"});
    let e = Scene::from_json_str(&set(base(), "peer", missing).to_string()).unwrap_err().to_string();
    assert!(e.contains("values"), "{e}");
}
