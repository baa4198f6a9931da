//! No panic on any input: valid scenes are mutated key by key and value by value,
//! and their text byte by byte; every outcome must be `Ok` or a `SceneError` with a
//! non-empty message (a panic fails the test). Accepted scenes must round-trip and
//! their contour must be usable. Deterministic (fixed xorshift seed).

use drive::{Scene, SceneError};
use serde_json::{json, Value};

fn seeds() -> Vec<Value> {
    vec![
        json!({
          "name": "string-hanging",
          "description": "Extensible string hanging on two frictionless pulleys",
          "drive": {"pulley_radius": 0.08, "centre_distance": 0.45, "driver_speed": 0.0, "driven_torque": 0.0},
          "belt": {"theory": "string", "length": 1.41, "axial_stiffness": 2.0e4,
                   "bending_stiffness": null, "shear_stiffness": null, "mass_per_length": 0.12},
          "effects": {"gravity": 9.81, "contact": "frictionless"},
          "analysis": "static"
        }),
        json!({
          "name": "cosserat-drive",
          "drive": {"pulley_radius": 0.1, "centre_distance": 0.6, "driver_speed": 20.0, "driven_torque": 1.0,
                    "driven_damping": 0.01},
          "belt": {"theory": "cosserat", "length": 1.9, "axial_stiffness": 1e5,
                   "bending_stiffness": 0.1, "shear_stiffness": 1e4, "mass_per_length": 0.2},
          "effects": {"gravity": 9.81, "inertia": true, "contact": {"coulomb": 0.5}},
          "analysis": "steady",
          "bvp": {"method": "bvp-shooting", "tolerance": 1e-9, "scheme": "gauss4", "max_nodes": 5000, "shooting_intervals": 4},
          "fem": {"elements": 128, "mesh_sequence": [32, 64, 128], "formulations": ["a", "b"], "penalty": 1e6},
          "gate": {"tolerances": {"y_upper_mid": 1e-3, "driver.stick_arc": 1e-2}, "min_order": 2.0}
        }),
        json!({
          "name": "shell-runoff",
          "drive": {"pulley_radius": 0.1, "centre_distance": 1.0, "driver_speed": 1.0, "driven_torque": 0.0},
          "belt": {"theory": "shell", "length": 2.7, "width": 0.2, "thickness": 1e-3, "youngs_modulus": 2.1e11,
                   "poisson_ratio": 0.3, "density": 7850.0, "camber": {"curvature": 1e-3}},
          "effects": {"contact": {"elastic_layer": {"normal_stiffness": 1e9, "tangential_stiffness": 1e8}}},
          "analysis": "transient"
        }),
        json!({
          "name": "cosserat-pulley",
          "drive": {"layout": "one-pulley", "pulley_radius": 0.1, "end_distance": 0.5, "transport_rate": 2.0,
                    "tension_in": 15.0, "tension_out": 10.0},
          "belt": {"theory": "cosserat", "axial_stiffness": 1.0e4, "bending_stiffness": 0.01,
                   "shear_stiffness": 1.0e3, "mass_per_length": 0.1},
          "effects": {"inertia": true, "contact": {"coulomb": 0.3}},
          "analysis": "steady"
        }),
    ]
}

fn replacements() -> Vec<Value> {
    vec![
        Value::Null,
        json!(true),
        json!(false),
        json!(0),
        json!(-0.0),
        json!(-1),
        json!(0.5),
        json!(3),
        json!(1e308),
        json!(-1e308),
        json!(5e-324),
        json!(u64::MAX),
        json!(i64::MIN),
        json!(""),
        json!("string"),
        json!("frictionless"),
        json!("bvp-collocation"),
        json!("μ∑😀"),
        json!("x".repeat(300)),
        json!([]),
        json!([1, 2, 3]),
        json!(["a"]),
        json!({}),
        json!({"a": 1}),
        json!({"coulomb": -1}),
        json!({"coulomb": 0.3, "x": 1}),
        json!({"elastic_layer": null}),
        json!({"y_upper_mid": 1e-3}),
    ]
}

/// Every path in the document: (parent pointer, key) for object members.
fn members(v: &Value, pointer: String, out: &mut Vec<(String, String)>) {
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                out.push((pointer.clone(), k.clone()));
                members(child, format!("{pointer}/{k}"), out);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                members(child, format!("{pointer}/{i}"), out);
            }
        }
        _ => {}
    }
}

/// Runs the parser; checks the invariants of either outcome.
fn exercise(text: &str) -> bool {
    match Scene::from_json_str(text) {
        Ok(scene) => {
            let back = Scene::from_json_str(&scene.to_json_pretty())
                .expect("an accepted scene must re-parse");
            assert_eq!(back, scene);
            let c = scene.contour();
            for s in [-1.0, 0.0, 0.3, c.length(), 1e6] {
                let p = c.position(s, 0.01);
                let _ = c.sigma_nu(p);
                let _ = (c.t_g(s), c.alpha(s), c.region(s));
            }
            let _ = (scene.slack_ratio(), scene.effect_names());
            true
        }
        Err(e) => {
            let msg = e.to_string();
            assert!(!msg.is_empty());
            if let Some(p) = e.path() {
                assert!(!p.is_empty(), "{e:?}");
            }
            assert!(
                !matches!(e, SceneError::Invalid { ref path, .. } if path == "<scene>"),
                "serde disagreed with the schema: {e}"
            );
            false
        }
    }
}

#[test]
fn value_and_key_mutations_never_panic() {
    let mut accepted = 0;
    let mut rejected = 0;
    for seed in seeds() {
        assert!(exercise(&seed.to_string()), "seed must be valid");
        let mut paths = Vec::new();
        members(&seed, String::new(), &mut paths);
        for (parent, key) in &paths {
            // replace the value
            for r in replacements() {
                let mut v = seed.clone();
                if let Some(Value::Object(m)) = v.pointer_mut(parent) {
                    m.insert(key.clone(), r);
                }
                if exercise(&v.to_string()) {
                    accepted += 1
                } else {
                    rejected += 1
                }
            }
            // delete the key, misspell it, add an unknown sibling
            let variants = [
                None,
                Some(key[1..].to_string()),
                Some(format!("{key}{key}")),
                Some(key.to_uppercase()),
                Some(format!("{key}μ")),
                Some(String::new()),
            ];
            for new_key in variants {
                let mut v = seed.clone();
                if let Some(Value::Object(m)) = v.pointer_mut(parent) {
                    if let Some(val) = m.remove(key) {
                        if let Some(k) = new_key {
                            m.insert(k, val);
                        }
                    }
                }
                if exercise(&v.to_string()) {
                    accepted += 1
                } else {
                    rejected += 1
                }
            }
        }
    }
    // most mutations must be caught; some (e.g. a different valid number) pass
    assert!(
        rejected > 5 * accepted,
        "accepted {accepted}, rejected {rejected}"
    );
}

/// A deterministic xorshift* generator: `next(n)` is uniform-ish in 0..n.
fn xorshift(mut state: u64) -> impl FnMut(usize) -> usize {
    move |n: usize| {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n.max(1)
    }
}

#[test]
fn text_mutations_never_panic() {
    let mut next = xorshift(0x2545_f491_4f6c_dd1d);
    let alphabet: Vec<char> = "{}[]:,\"0123456789.-eE \nabcnulltrueμ😀\\"
        .chars()
        .collect();
    for seed in seeds() {
        let base: Vec<char> = seed.to_string().chars().collect();
        for _ in 0..1500 {
            let mut t = base.clone();
            for _ in 0..1 + next(3) {
                let i = next(t.len());
                match next(4) {
                    0 => t.truncate(i),
                    1 => t.insert(i.min(t.len()), alphabet[next(alphabet.len())]),
                    2 if !t.is_empty() => {
                        t.remove(i.min(t.len() - 1));
                    }
                    _ if t.len() > 1 => {
                        let j = next(t.len());
                        let k = i.min(t.len() - 1);
                        t.swap(k, j);
                    }
                    _ => {}
                }
            }
            exercise(&t.into_iter().collect::<String>());
        }
    }
    // pathological documents
    exercise("");
    exercise("null");
    exercise(&"[".repeat(100_000));
    exercise(&format!("{{\"name\": \"{}\"}}", "a".repeat(1_000_000)));
    exercise(&format!("{{\"{}\": 1}}", "k".repeat(100_000)));
}

/// The catalogue scenes (scenes/*.json), as text.
fn catalogue() -> Vec<(String, String)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
        .collect();
    out.sort();
    assert!(out.len() >= 7, "the catalogue has at least 7 scenes");
    out
}

/// Text mutations of every catalogue scene that a hostile or careless file carries:
/// a key repeated (with the same or another value), a byte-order mark, numbers out of
/// the f64 range or at its edges, NaN-like text, values of the wrong type. Each must be
/// accepted or a named error; the specific ones are checked for their kind.
#[test]
fn catalogue_mutations_are_named_errors() {
    let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
    let numbers = ["1e999", "-1e400", "1e308", "-1e308", "5e-324", "0", "-0", "NaN", "nan", "Infinity", "-Infinity", "\"NaN\"", "\"1.0\"", "true", "null", "[1]", "{}", "1e-400"];
    for (file, text) in catalogue() {
        assert!(exercise(&text), "{file} must parse");
        // a byte-order mark changes nothing
        let bom = Scene::from_json_str(&format!("\u{FEFF}{text}")).expect("BOM accepted");
        assert_eq!(bom, Scene::from_json_str(&text).unwrap(), "{file}");
        // every `"key": value` line repeated in place: a named duplicate
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_end_matches(',');
            if !t.trim_start().starts_with('"') || !t.contains("\": ") || t.ends_with('{') || t.ends_with('[') {
                continue;
            }
            let mut copy: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            copy.insert(i, format!("{t},"));
            let e = Scene::from_json_str(&copy.join("\n")).expect_err("a repeated key is an error");
            assert!(matches!(e, SceneError::DuplicateKey { .. }), "{file} line {i}: {e}");
            let key = t.trim_start().trim_start_matches('"').split('"').next().unwrap();
            assert!(e.path().is_some_and(|p| p.ends_with(key)), "{file}: {e}");
        }
        // numbers replaced by extreme, NaN-like or wrongly typed text
        // (values of keys only: a `: 64` inside a description string is text, and a
        // mutation there stays valid JSON)
        let spots: Vec<usize> = text
            .match_indices("\": ")
            .map(|(i, _)| i + 3)
            .filter(|&i| text[i..].starts_with(|c: char| c.is_ascii_digit() || c == '-'))
            .collect();
        for _ in 0..60 {
            let at = spots[next(spots.len())];
            let end = at + text[at..].find([',', '\n', '}', ']']).unwrap();
            let with = numbers[next(numbers.len())];
            let mutated = format!("{}{with}{}", &text[..at], &text[end..]);
            let ok = exercise(&mutated);
            if ["1e999", "-1e400", "NaN", "nan", "Infinity", "-Infinity"].contains(&with) {
                assert!(!ok, "{file}: {with} accepted");
                assert!(matches!(Scene::from_json_str(&mutated), Err(SceneError::Syntax { .. })), "{file}: {with}");
            }
        }
    }
}
