//! JSON Schemas (draft 2020-12) of the two formats other tools read and write — the
//! scene ([`crate::Scene`]) and the result of a run ([`crate::RunResult`], with its
//! `discretisation`) — generated from the Rust types by `schemars`, so the schema and
//! the reader cannot drift apart. Shipped in `schemas/` (`beltcheck schema scene|result`
//! prints them; a test keeps the files in step with the types).
//!
//! The schema states the shape of a file: names, types, required fields, enumerations.
//! What depends on other fields (a one-pulley scene's loads, the fields a belt theory
//! allows) and the ranges of numbers are checked by the reader, whose errors name the
//! field path (`Scene::from_json_str`, `beltcheck check`).

use serde_json::Value;

/// Where the scene schema is shipped, relative to the repository root.
pub const SCENE_SCHEMA_FILE: &str = "schemas/scene.schema.json";

/// Where the result schema is shipped, relative to the repository root.
pub const RESULT_SCHEMA_FILE: &str = "schemas/result.schema.json";

/// The JSON Schema of the scene format.
pub fn scene_schema() -> Value {
    titled(schemars::schema_for!(crate::Scene), "beltcheck scene")
}

/// The JSON Schema of the result format.
pub fn result_schema() -> Value {
    titled(schemars::schema_for!(crate::RunResult), "beltcheck result")
}

fn titled(schema: schemars::Schema, title: &str) -> Value {
    let mut v = schema.to_value();
    if let Some(m) = v.as_object_mut() {
        m.insert("title".into(), Value::from(title));
    }
    v
}

/// Pretty JSON of a schema, with a final newline (the form of the shipped files).
pub fn to_text(schema: &Value) -> String {
    serde_json::to_string_pretty(schema).unwrap_or_default() + "\n"
}
