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
    solve_refuses("bad", &cases);
}

/// Each scene text is refused by `solve --json`: exit 2, a message naming the needle, no
/// panic, and no result file left behind.
fn solve_refuses(tag: &str, cases: &[(String, &str)]) {
    for (i, (text, needle)) in cases.iter().enumerate() {
        let scene = temp(&format!("{tag}{i}.json"));
        std::fs::write(&scene, text).unwrap();
        let out = temp(&format!("{tag}{i}.out.json"));
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
    for name in ["string-hanging", "string-hanging-slack", "string-hanging-very-slack", "string-hanging-steel", "rod-hanging", "string-drive", "string-drive-exudyn"] {
        let o = beltcheck(&["solve", &format!("scenes/{name}.json")]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
    }
}

/// The steady drive (docs/string-drive.md) through the CLI: the drive quantities are
/// printed and written (tight/slack tensions, ω₂, c, stick/slip arcs, torques), with the
/// belt-on-pulley torque of the driven pulley equal to M₂ + d₂ω₂ (10 + 0.05 ω₂ N·m in
/// scenes/string-drive.json; the solve tolerance 1e-8 bounds it to ~1e-8 relative, so
/// 1e-6).
#[test]
fn steady_drive_through_the_cli() {
    let path = temp("drive.json");
    let o = beltcheck(&["solve", "scenes/string-drive.json", "--json", path.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    for needle in ["tension tight / slack", "driven speed", "transport rate", "stick arc", "slip arc", "torque on pulley", "power: input"] {
        assert!(out.contains(needle), "`{needle}` not printed: {out}");
    }
    let v = read_json(&path);
    let s = &v["summary"];
    for key in ["tension_tight", "tension_slack", "driven_speed", "transport_rate", "y_upper_mid", "tension_lower_mid"] {
        assert!(s[key].as_f64().is_some_and(f64::is_finite), "{key} missing: {s}");
    }
    for pulley in ["driver", "driven"] {
        for key in ["contact_arc", "stick_arc", "slip_arc", "torque"] {
            assert!(s[pulley][key].as_f64().is_some_and(f64::is_finite), "{pulley}.{key} missing: {s}");
        }
        assert!(s[pulley].get("edge_force_start").is_none(), "a string has no edge forces");
    }
    let omega2 = s["driven_speed"].as_f64().unwrap();
    let torque = s["driven"]["torque"].as_f64().unwrap();
    assert!((torque - (10.0 + 0.05 * omega2)).abs() < 1e-6 * torque, "driven torque {torque}, ω₂ {omega2}");
    // Input power exceeds the output by the slip losses (ω₁ = 60 rad/s in the scene).
    assert!(-s["driver"]["torque"].as_f64().unwrap() * 60.0 > torque * omega2, "the driver supplies the output and the slip losses");
    assert!(s["tension_tight"].as_f64().unwrap() > s["tension_slack"].as_f64().unwrap());
}

/// Drives with no steady solution: named errors with their numbers, exit status 2, no
/// result file — torque above the friction capacity (with and without gravity), driver
/// speed at or above critical (no gravity), no friction.
#[test]
fn drive_without_steady_solution_is_a_named_error() {
    let good = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-drive.json")).unwrap();
    let cases = [
        (good.replace("\"driven_torque\": 10.0", "\"driven_torque\": 1000.0"), "exceeds the friction capacity"),
        (good.replace("\"driven_torque\": 10.0", "\"driven_torque\": 1000.0").replace("\"gravity\": 9.81,", ""), "friction capacity 18.6"),
        (good.replace("\"driver_speed\": 60.0", "\"driver_speed\": 500.0").replace("\"gravity\": 9.81,", ""), "critical speed 189.8"),
        ({
            let mut v: serde_json::Value = serde_json::from_str(&good).unwrap();
            v["effects"]["contact"]["coulomb"] = serde_json::json!(0.0);
            v.to_string()
        }, "μ > 0"),
    ];
    solve_refuses("drive-bad", &cases);
}

/// A scene's optional `peer` block (scenes/string-drive-exudyn.json) appears in its
/// report beside the BVP reference, with the relative difference.
#[test]
fn report_shows_the_peer_results() {
    let dir = temp("peer-report");
    let o = beltcheck(&["report", "-o", dir.to_str().unwrap(), "--tolerances", "1e-6", "scenes/string-drive-exudyn.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(dir.join("string-drive-exudyn/report.md")).expect("report written");
    assert!(md.contains("## Published results of another code"), "{md}");
    for row in ["| `tension_tight` | 666.5 |", "| `tension_slack` | 186.4 |", "| `driven_speed` | 11.341 |", "| `driver.torque` | -47.72 |"] {
        assert!(md.contains(row), "`{row}` missing");
    }
}

/// `beltcheck quantities` is the glossary of the result format: every summary name
/// appears (pulley quantities once, as `<pulley>.name`) with its unit, and the
/// tight/slack tensions are defined as the axial forces in the two stick zones — the
/// definition both methods use.
#[test]
fn quantities_lists_every_summary_name_with_its_meaning() {
    let o = beltcheck(&["quantities"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    for name in drive::summary::SCALAR_NAMES {
        let listed = match name.split_once('.') {
            Some((_, q)) => format!("<pulley>.{q}"),
            None => name.to_string(),
        };
        assert!(out.lines().any(|l| l.split_whitespace().next() == Some(listed.as_str())), "{name} missing:\n{out}");
    }
    let tight = out.lines().find(|l| l.starts_with("tension_tight ")).expect("tension_tight listed");
    assert!(tight.contains(" N ") && tight.contains("driver's stick zone") && tight.contains("middle of the stick arc"), "{tight}");
    let slack = out.lines().find(|l| l.starts_with("tension_slack ")).expect("tension_slack listed");
    assert!(slack.contains("driven pulley's stick zone"), "{slack}");
    // The solve help points to the glossary.
    let help = stdout(&beltcheck(&["solve", "--help"]));
    assert!(help.contains("beltcheck quantities") && help.contains("stick"), "{help}");
}
