//! The JSON Schemas shipped in `schemas/` are the ones generated from the types, and
//! they describe the files the project reads and writes: every catalogue scene and a
//! full result validate; a misspelt key, a missing required field or a wrong type does
//! not. (A small validator of the keywords schemars emits: `$ref`, `oneOf`/`anyOf`/
//! `allOf`, `enum`/`const`, `type`, `properties`/`required`/`additionalProperties`,
//! `items`, `minimum`.)

use std::path::Path;

use drive::schemas::{result_schema, scene_schema, to_text, RESULT_SCHEMA_FILE, SCENE_SCHEMA_FILE};
use serde_json::{json, Value};

fn repo(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

#[test]
fn shipped_schemas_are_the_generated_ones() {
    for (file, schema, what) in [(SCENE_SCHEMA_FILE, scene_schema(), "scene"), (RESULT_SCHEMA_FILE, result_schema(), "result")] {
        let shipped = std::fs::read_to_string(repo(file)).unwrap_or_default();
        assert!(
            shipped == to_text(&schema),
            "{file} is out of step with the Rust types: regenerate it with `cargo run --release -- schema {what} > {file}`"
        );
    }
}

/// `Err(path: why)` for the first violation.
fn validate(root: &Value, schema: &Value, v: &Value, path: &str) -> Result<(), String> {
    let s = match schema {
        Value::Bool(true) => return Ok(()),
        Value::Bool(false) => return Err(format!("{path}: not allowed")),
        Value::Object(s) => s,
        _ => return Err(format!("{path}: bad schema")),
    };
    if let Some(r) = s.get("$ref").and_then(Value::as_str) {
        let name = r.strip_prefix("#/$defs/").ok_or(format!("{path}: unsupported $ref {r}"))?;
        validate(root, &root["$defs"][name], v, path)?;
    }
    for key in ["oneOf", "anyOf"] {
        if let Some(branches) = s.get(key).and_then(Value::as_array) {
            let ok: Vec<_> = branches.iter().filter(|b| validate(root, b, v, path).is_ok()).collect();
            if ok.is_empty() || (key == "oneOf" && ok.len() > 1) {
                return Err(format!("{path}: {} of the {key} branches match", ok.len()));
            }
        }
    }
    if let Some(all) = s.get("allOf").and_then(Value::as_array) {
        for b in all {
            validate(root, b, v, path)?;
        }
    }
    if let Some(e) = s.get("enum").and_then(Value::as_array) {
        if !e.contains(v) {
            return Err(format!("{path}: {v} not in {e:?}"));
        }
    }
    if let Some(c) = s.get("const") {
        if c != v {
            return Err(format!("{path}: {v} is not {c}"));
        }
    }
    if let Some(t) = s.get("type") {
        let types: Vec<&str> = match t {
            Value::String(t) => vec![t.as_str()],
            Value::Array(a) => a.iter().filter_map(Value::as_str).collect(),
            _ => Vec::new(),
        };
        let is = |t: &str| match t {
            "null" => v.is_null(),
            "boolean" => v.is_boolean(),
            "integer" => v.is_u64() || v.is_i64(),
            "number" => v.is_number(),
            "string" => v.is_string(),
            "array" => v.is_array(),
            "object" => v.is_object(),
            _ => false,
        };
        if !types.iter().any(|t| is(t)) {
            return Err(format!("{path}: {v} is not of type {types:?}"));
        }
    }
    if let (Some(min), Some(x)) = (s.get("minimum").and_then(Value::as_f64), v.as_f64()) {
        if x < min {
            return Err(format!("{path}: {x} below the minimum {min}"));
        }
    }
    if let Some(obj) = v.as_object() {
        for r in s.get("required").and_then(Value::as_array).into_iter().flatten().filter_map(Value::as_str) {
            if !obj.contains_key(r) {
                return Err(format!("{path}.{r}: required"));
            }
        }
        let props = s.get("properties").and_then(Value::as_object);
        for (k, x) in obj {
            let p = format!("{path}.{k}");
            match props.and_then(|p| p.get(k)) {
                Some(ps) => validate(root, ps, x, &p)?,
                None => {
                    if let Some(extra) = s.get("additionalProperties") {
                        validate(root, extra, x, &p)?;
                    }
                }
            }
        }
    }
    if let (Some(items), Some(arr)) = (s.get("items"), v.as_array()) {
        for (i, x) in arr.iter().enumerate() {
            validate(root, items, x, &format!("{path}[{i}]"))?;
        }
    }
    Ok(())
}

#[test]
fn every_catalogue_scene_validates_and_mutations_do_not() {
    let schema = scene_schema();
    let mut n = 0;
    // the catalogue and its study scenes (scenes/studies/)
    let files = |dir: std::path::PathBuf| -> Vec<std::path::PathBuf> {
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|x| x == "json")).collect()
    };
    for path in files(repo("scenes")).into_iter().chain(files(repo("scenes").join("studies"))) {
        let v: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        validate(&schema, &schema, &v, "").unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        n += 1;

        let mut typo = v.clone();
        let stiffness = typo["belt"].as_object_mut().unwrap().remove("axial_stiffness").unwrap_or(json!(1.0));
        typo["belt"]["axial_stifness"] = stiffness;
        assert!(validate(&schema, &schema, &typo, "").unwrap_err().contains("axial_stifness"));
        let mut missing = v.clone();
        missing.as_object_mut().unwrap().remove("belt");
        assert_eq!(validate(&schema, &schema, &missing, "").unwrap_err(), ".belt: required");
        let mut wrong = v.clone();
        wrong["analysis"] = json!("quasi-static");
        assert!(validate(&schema, &schema, &wrong, "").is_err());
    }
    assert!(n >= 5, "the catalogue has {n} scenes");
}

#[test]
fn a_full_result_validates_and_mutations_do_not() {
    let schema = result_schema();
    let v = json!({
        "scene": "string-hanging", "method": "my-fd", "converged": true,
        "summary": {"y_upper_mid": 0.059, "tension_lower_mid": 1.13, "driver": {"contact_arc": 3.07}},
        "cost": {"wall_seconds": 0.1, "newton_iterations": 7, "unknowns": 128},
        "fields": {"sigma": [0.0, 0.1], "x": [-0.225, -0.125], "y": [0.08, 0.07], "tension": [1.3, 1.3]},
        "discretisation": {"elements": 64}
    });
    validate(&schema, &schema, &v, "").unwrap();
    for (k, bad) in [("discretisation", json!({"elements": -1})), ("converged", json!("yes")), ("fields", json!({"sigma": [0.0]}))] {
        let mut w = v.clone();
        w[k] = bad;
        assert!(validate(&schema, &schema, &w, "").is_err(), "{k}");
    }
}
