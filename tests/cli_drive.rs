//! End to end: `beltcheck solve --method fem` on a friction-drive scene: `analysis:
//! transient` writes the optional `history` of the transient (docs/fem-drive.md §8)
//! beside the summary; `analysis: steady` runs the direct steady solve (§12), which has
//! no history and lands on the same state.

mod common;

use common::{beltcheck, stderr, stdout, temp};

/// `solve --method fem --elements 32` on the creep scene as a transient with `edit`
/// applied (files named after `name`): the result JSON.
fn solve_creep_transient(name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> serde_json::Value {
    let mut scene: serde_json::Value = serde_json::from_str(&std::fs::read_to_string("fem/tests/scenes/drive-creep.json").unwrap()).unwrap();
    scene["analysis"] = "transient".into();
    edit(&mut scene);
    let path = temp("cli-drive", &format!("{name}-scene.json"));
    std::fs::write(&path, serde_json::to_string(&scene).unwrap()).unwrap();
    let out = temp("cli-drive", &format!("{name}.json"));
    let o = beltcheck(&["solve", path.to_str().unwrap(), "--method", "fem", "--elements", "32", "--json", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}\n{}", stdout(&o), stderr(&o));
    serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap()
}

#[test]
fn fem_drive_writes_the_history() {
    let v = solve_creep_transient("drive", |_| ());
    let h = &v["history"];
    let n = h["time"].as_array().unwrap().len();
    assert!(n >= 3, "at least the three quiet steps of the steady criterion");
    for key in ["driven_speed", "tension_upper_mid", "tension_lower_mid", "driver_slip_arc", "driven_stick_arc", "driven_torque", "change_rate"] {
        assert_eq!(h[key].as_array().unwrap().len(), n, "history.{key}");
    }
    let s = &v["summary"];
    assert_eq!(s["driven_speed"].as_f64(), h["driven_speed"][n - 1].as_f64());
    for key in ["stick_arc", "slip_arc", "torque"] {
        assert!(s["driven"][key].is_number(), "summary.driven.{key}");
    }
    assert!(s["tension_tight"].as_f64().unwrap() > s["tension_slack"].as_f64().unwrap());
    // the steady scene: direct solve, no history, the same driven speed (the two agree
    // to 1e-6 relative at 32 elements: creep ω₂ is set by the span stretches)
    let out = temp("cli-drive", "steady.json");
    let o = beltcheck(&["solve", "fem/tests/scenes/drive-creep.json", "--method", "fem", "--elements", "32", "--json", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}\n{}", stdout(&o), stderr(&o));
    let w: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert!(w.get("history").is_none());
    let (a, b) = (w["summary"]["driven_speed"].as_f64().unwrap(), s["driven_speed"].as_f64().unwrap());
    assert!((a - b).abs() < 1e-6 * b, "steady ω₂ {a} vs transient {b}");
    // a static scene has no history
    let out = temp("cli-drive", "static.json");
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--method", "fem", "--elements", "32", "--json", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert!(v.get("history").is_none());
}

/// A counter-clockwise driver in a transient (issue 12, "four quadrants"; docs/fem-drive.md
/// §13): the scene is accepted and `solve --method fem` runs the transient to its steady
/// state — the belt runs against σ (c, ω₂ < 0 in the summary, ω₂ < 0 in every step of the
/// history) and the driver's stick zone carries the larger force.
#[test]
fn fem_drive_runs_a_counter_clockwise_transient() {
    let v = solve_creep_transient("ccw-drive", |scene| {
        scene["drive"]["driver_speed"] = (-10.0).into();
        scene["drive"]["driven_torque"] = (-2.0).into();
    });
    let s = &v["summary"];
    assert!(s["driven_speed"].as_f64().unwrap() < 0.0 && s["transport_rate"].as_f64().unwrap() < 0.0, "{s}");
    assert!(s["tension_tight"].as_f64().unwrap() > s["tension_slack"].as_f64().unwrap());
    let w2 = v["history"]["driven_speed"].as_array().unwrap();
    assert!(w2.len() >= 3 && w2.iter().all(|w| w.as_f64().unwrap() < 0.0), "{w2:?}");
}
