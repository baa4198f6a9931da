//! End-to-end tests of the `beltcheck` command line: what a user runs, what is printed
//! and written, and that bad input gives a named error, exit status 2 and no file.

use std::path::{Path, PathBuf};

mod common;
use common::{beltcheck, stderr, stdout};

fn temp(name: &str) -> PathBuf {
    common::temp("cli", name)
}

fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("result written")).expect("valid JSON")
}

/// `beltcheck` alone solves the embedded default scene by both methods and reports their
/// agreement.
#[test]
fn no_arguments_solves_the_default_scene() {
    let o = beltcheck(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("string-hanging"), "{out}");
    assert!(out.contains("bvp-collocation") && out.contains("bvp-shooting"), "{out}");
    assert!(out.contains("contact arc"), "{out}");
    assert!(out.contains("collocation vs shooting"), "{out}");
}

/// `solve --json` writes every summary field the scene produces, and only those: a static
/// frictionless string has no moments, torques, stick/slip arcs, speeds or edge forces.
#[test]
fn solve_writes_the_result_json() {
    let path = temp("out.json");
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--json", path.to_str().unwrap(), "--fields", "64"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = read_json(&path);
    assert_eq!(v["scene"], "string-hanging");
    assert_eq!(v["method"], "bvp-collocation");
    assert_eq!(v["converged"], true);
    let s = &v["summary"];
    for key in ["y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid"] {
        assert!(s[key].as_f64().is_some_and(f64::is_finite), "{key} missing: {s}");
    }
    for pulley in ["driver", "driven"] {
        for key in ["contact_arc", "contact_start", "contact_end"] {
            assert!(s[pulley][key].as_f64().is_some_and(f64::is_finite), "{pulley}.{key} missing: {s}");
        }
        for key in ["torque", "stick_arc", "slip_arc", "edge_force_start", "edge_force_end"] {
            assert!(s[pulley].get(key).is_none(), "{pulley}.{key} must be absent: {s}");
        }
    }
    for key in ["moment_upper_mid", "moment_lower_mid", "tension_tight", "tension_slack", "driven_speed", "transport_rate"] {
        assert!(s.get(key).is_none(), "{key} must be absent: {s}");
    }
    assert!(v["cost"]["wall_seconds"].as_f64().unwrap() > 0.0);
    assert!(v["cost"]["unknowns"].as_u64().unwrap() > 0);
    let f = &v["fields"];
    assert_eq!(f["sigma"].as_array().unwrap().len(), 64);
    assert_eq!(f["tension"].as_array().unwrap().len(), 64);
    assert!(f.get("moment").is_none_or(|m| m.is_null()), "a string has no moment field");
}

/// Both methods, through the CLI, agree in every summary quantity to 1e-8 (relative to
/// the quantity, or absolute for angles in radians and positions in m of order 0.1).
#[test]
fn methods_agree_through_the_cli() {
    let a = temp("coll.json");
    let b = temp("shoot.json");
    for (m, p) in [("bvp-collocation", &a), ("bvp-shooting", &b)] {
        let o = beltcheck(&["solve", "scenes/string-hanging.json", "--method", m, "--tolerance", "1e-10", "--json", p.to_str().unwrap()]);
        assert!(o.status.success(), "{m}: {}", stderr(&o));
    }
    let (va, vb) = (read_json(&a), read_json(&b));
    fn walk(a: &serde_json::Value, b: &serde_json::Value, name: &str, n: &mut usize) {
        match (a, b) {
            (serde_json::Value::Object(ma), serde_json::Value::Object(mb)) => {
                assert_eq!(ma.len(), mb.len(), "{name}: different quantities");
                for (k, x) in ma {
                    walk(x, &mb[k], &format!("{name}.{k}"), n);
                }
            }
            _ => {
                let (x, y) = (a.as_f64().unwrap(), b.as_f64().unwrap());
                assert!((x - y).abs() < 1e-8 * x.abs().max(1.0), "{name}: {x} vs {y}");
                *n += 1;
            }
        }
    }
    let mut n = 0;
    walk(&va["summary"], &vb["summary"], "summary", &mut n);
    assert_eq!(n, 10, "4 span quantities + 3 per pulley");
}

/// Bad scene files: a named error, exit status 2, and no result file.
#[test]
fn bad_scenes_are_named_errors_and_write_nothing() {
    let good = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-hanging.json")).unwrap();
    let cases = [
        (good.replace("\"axial_stiffness\"", "\"axial_stifness\""), "axial_stiffness"),
        (good.replace("\"axial_stiffness\": 20000.0", "\"axial_stiffness\": -1.0"), "axial_stiffness"),
        (good.replace("\"gravity\": 9.81", "\"gravity\": 0.0"), "L_geom"),
        (good.replace("\"length\": 1.41", "\"length\": \"long\""), "length"),
        ("{ not json".to_string(), "scene"),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let scene = temp(&format!("bad{i}.json"));
        std::fs::write(&scene, text).unwrap();
        let out = temp(&format!("bad{i}.out.json"));
        let _ = std::fs::remove_file(&out);
        let o = beltcheck(&["solve", scene.to_str().unwrap(), "--json", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "case {i}: {}", stdout(&o));
        let err = stderr(&o);
        assert!(err.contains(needle), "case {i}: `{needle}` not named in: {err}");
        assert!(!err.contains("panicked"), "case {i}: {err}");
        assert!(!out.exists(), "case {i}: a result was written");
    }
}

/// `solve --method fem` writes the same quantities as the BVP, close to the BVP's values
/// (128 elements: the FE mesh error of the mid-span quantities is ~1e-5 relative, see
/// tests/fem_vs_bvp.rs, so 1e-3 leaves a wide margin), and an unknown formulation is a
/// named error listing the registered ones.
#[test]
fn fem_method_through_the_cli() {
    let a = temp("fem.json");
    let b = temp("bvp.json");
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--method", "fem", "--elements", "128", "--json", a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("terms assembled"), "{}", stdout(&o));
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--json", b.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (va, vb) = (read_json(&a), read_json(&b));
    assert_eq!(va["method"], "fem");
    for key in ["y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid"] {
        let (x, y) = (va["summary"][key].as_f64().unwrap(), vb["summary"][key].as_f64().unwrap());
        assert!((x - y).abs() < 1e-3 * y.abs(), "{key}: fem {x} vs bvp {y}");
    }
    for pulley in ["driver", "driven"] {
        let (x, y) = (va["summary"][pulley]["contact_arc"].as_f64().unwrap(), vb["summary"][pulley]["contact_arc"].as_f64().unwrap());
        assert!((x - y).abs() < 1e-3, "{pulley}.contact_arc: fem {x} vs bvp {y}");
    }
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--method", "fem", "--formulation", "no-such-element"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("string-gauss"), "{}", stderr(&o));
}

/// Every catalogue scene parses and solves from its file alone.
#[test]
fn every_catalogue_scene_solves() {
    for name in ["string-hanging", "string-hanging-slack", "string-hanging-very-slack", "string-hanging-steel", "rod-hanging"] {
        let o = beltcheck(&["solve", &format!("scenes/{name}.json")]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
    }
}
