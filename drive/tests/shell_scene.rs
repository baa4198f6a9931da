//! The shell-runoff scene format of spec §4.15 (issue 15): both drums at prescribed
//! speed (`drive.driven_speed` beside `drive.driver_speed`), the steering drum with
//! piecewise-linear histories of its two tilt angles (`drive.steering`), camber by
//! curvature κ_c or edge length difference ΔL = κ_c b L (spec §4.3), and the shell's
//! `fem` settings. Every error is provoked by one edit of the shipped CI scene and is
//! checked to name its field path (and the numbers where it has them); every accepted
//! form round-trips through the writer.

use drive::{Scene, SceneError, SteeringDrum};
use serde_json::{json, Value};

/// The shipped CI scene.
fn ci() -> Value {
    serde_json::from_str(include_str!("../../scenes/shell-runoff.json")).unwrap()
}

fn read(v: &Value) -> Result<Scene, SceneError> {
    Scene::from_json_str(&v.to_string())
}

/// `v` is refused at `path` with every fragment in the message.
fn refused(v: &Value, path: &str, fragments: &[&str]) {
    let e = read(v).expect_err("must be refused");
    let msg = e.to_string();
    assert_eq!(e.path(), Some(path), "{msg}");
    for f in fragments {
        assert!(msg.contains(f), "{msg:?} lacks {f:?}");
    }
}

fn roundtrip(s: &Scene) {
    let text = s.to_json_pretty();
    assert_eq!(&Scene::from_json_str(&text).unwrap(), s, "{text}");
}

#[test]
fn shipped_shell_scenes_read_and_round_trip() {
    for text in [include_str!("../../scenes/shell-runoff.json"), include_str!("../../scenes/studies/shell-runoff-study.json")] {
        let s = Scene::from_json_str(text).unwrap();
        assert_eq!(s.belt.theory, drive::Theory::Shell);
        roundtrip(&s);
        let run = s.shell_run();
        assert!(run.steps >= 1 && run.elements_zeta.is_multiple_of(2));
        // realistic proportions (issue 15): h/b ≈ 1e-3, b/H ≈ 0.2, a slack belt
        let plate = s.belt.plate().unwrap();
        let hb = plate.thickness / plate.width;
        assert!((5e-4..=2e-3).contains(&hb), "h/b = {hb}");
        let bh = plate.width / s.drive.centre_distance;
        assert!((0.1..=0.3).contains(&bh), "b/H = {bh}");
        assert!(s.slack_ratio() > 1.0, "L/L_geom = {}", s.slack_ratio());
    }
}

/// The long study scenes (docs/fem-shell.md §14) read and round-trip; the taut
/// swivel's belt is shorter than the taut loop and has no weight, so that its span
/// tensions come from the stretch alone and stay equal in rotation (§9.4); the 256 × 8
/// level is the shipped scene itself on a finer mesh over ten revolutions.
#[test]
fn study_scenes_read_and_round_trip() {
    let converged = include_str!("../../scenes/studies/shell-runoff-ten-revolutions-256x8.json");
    for text in [include_str!("../../scenes/studies/shell-runoff-ten-revolutions.json"), include_str!("../../scenes/studies/shell-runoff-taut-swivel.json"), converged] {
        let s = Scene::from_json_str(text).unwrap();
        assert_eq!(s.belt.theory, drive::Theory::Shell);
        roundtrip(&s);
        assert_eq!(s.shell_run().steps, 2000, "ten revolutions at ωΔt = π/32");
    }
    // the level the shipped scene's run-off is stated on (§14 "The shipped scene on §7 (h)"):
    // the shipped belt and imperfections, 256 × 8 on the graded ζ-mesh
    let (level, shipped) = (Scene::from_json_str(converged).unwrap(), Scene::from_json_str(include_str!("../../scenes/shell-runoff.json")).unwrap());
    let run = level.shell_run();
    assert_eq!((run.elements_sigma, run.elements_zeta, run.zeta_mesh), (256, 8, drive::scene::ShellZetaMesh::Graded));
    assert_eq!((&level.belt, &level.drive, &level.effects), (&shipped.belt, &shipped.drive, &shipped.effects));
    assert_eq!(run.time_step, shipped.shell_run().time_step);
    let taut = Scene::from_json_str(include_str!("../../scenes/studies/shell-runoff-taut-swivel.json")).unwrap();
    assert!(taut.slack_ratio() < 1.0 && taut.effects.gravity.is_none(), "L/L_geom = {}", taut.slack_ratio());
}

#[test]
fn both_drum_speeds_and_the_steering_histories_are_read() {
    let mut v = ci();
    v["drive"]["driven_speed"] = json!(2.0);
    v["drive"]["steering"] = json!({"drum": "driver", "tilt_x": [[0.0, 1e-3], [2.0, -1e-3]], "tilt_y": [[0.5, 2e-3]]});
    let s = read(&v).unwrap();
    assert_eq!(s.drive.driven_speed, Some(2.0));
    let st = s.drive.steering.as_ref().unwrap();
    assert_eq!(st.drum, SteeringDrum::Driver);
    // piecewise linear, held outside, 0 when absent
    assert_eq!(drive::Steering::angle_at(&st.tilt_x, -1.0), 1e-3);
    assert!((drive::Steering::angle_at(&st.tilt_x, 1.0) - 0.0).abs() < 1e-18);
    assert!((drive::Steering::angle_at(&st.tilt_x, 1.5) + 0.5e-3).abs() < 1e-18);
    assert_eq!(drive::Steering::angle_at(&st.tilt_x, 9.0), -1e-3);
    assert_eq!(drive::Steering::angle_at(&st.tilt_y, 0.0), 2e-3);
    assert_eq!(drive::Steering::angle_at(&[], 3.0), 0.0);
    roundtrip(&s);
    // an absent history is not written
    v["drive"]["steering"] = json!({"drum": "driven", "tilt_y": [[0.0, 1e-3]]});
    let s = read(&v).unwrap();
    assert!(!s.to_json_pretty().contains("tilt_x"));
    roundtrip(&s);
}

#[test]
fn camber_by_edge_length_difference_is_the_curvature() {
    // ΔL = κ_c b L (spec §4.3): both forms give the same κ_c, each written as given
    let mut v = ci();
    let (b, l) = (v["belt"]["width"].as_f64().unwrap(), v["belt"]["length"].as_f64().unwrap());
    let kappa = 2e-3;
    v["belt"]["camber"] = json!({"edge_length_difference": kappa * b * l});
    let s = read(&v).unwrap();
    let c = s.belt.camber.unwrap();
    assert!((c.curvature_for(b, l) - kappa).abs() < 1e-15 * kappa.max(1.0), "{}", c.curvature_for(b, l));
    assert!(s.to_json_pretty().contains("edge_length_difference"));
    roundtrip(&s);
    v["belt"]["camber"] = json!({"curvature": kappa});
    assert_eq!(read(&v).unwrap().belt.camber.unwrap().curvature_for(b, l), kappa);
    // an edge of non-positive unstressed length is impossible: |κ_c| b/2 < 1
    v["belt"]["camber"] = json!({"curvature": 2.0 / b});
    refused(&v, "belt.camber.curvature", &["|κ_c| b/2 < 1"]);
    v["belt"]["camber"] = json!({"edge_length_difference": -2.5 * l});
    refused(&v, "belt.camber.edge_length_difference", &["zero or negative length"]);
}

#[test]
fn impossible_drum_speeds_and_loads_are_refused_by_name() {
    let mut v = ci();
    v["drive"]["driven_speed"] = json!(-1.0);
    refused(&v, "drive.driven_speed", &["opposite senses"]);
    let mut v = ci();
    v["drive"]["driven_torque"] = json!(1.0);
    refused(&v, "drive.driven_torque", &["prescribed speeds", "1 N·m"]);
    let mut v = ci();
    v["drive"]["driven_damping"] = json!(0.1);
    refused(&v, "drive.driven_damping", &["prescribed speeds"]);
    // at rest both are 0
    let mut v = ci();
    v["analysis"] = json!("static");
    v["drive"]["driver_speed"] = json!(0.0);
    v["drive"]["driven_speed"] = json!(0.5);
    refused(&v, "drive.driven_speed", &["opposite senses, or over one turning drum and one at rest"]);
    // the shell's drive fields belong to the shell
    let mut rod: Value = serde_json::from_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    rod["drive"]["driven_speed"] = json!(1.0);
    refused(&rod, "drive.driven_speed", &["theory `shell`"]);
    let mut rod: Value = serde_json::from_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    rod["drive"]["steering"] = json!({"drum": "driven"});
    refused(&rod, "drive.steering", &["theory `shell`"]);
}

#[test]
fn bad_steering_histories_are_refused_by_name() {
    let with = |steering: Value| {
        let mut v = ci();
        v["drive"]["steering"] = steering;
        v
    };
    refused(&with(json!({"tilt_x": [[0.0, 0.0]]})), "drive.steering.drum", &["missing"]);
    refused(&with(json!({"drum": "left"})), "drive.steering.drum", &["`driver`, `driven`"]);
    refused(&with(json!({"drum": "driven", "tilt_z": []})), "drive.steering.tilt_z", &["unknown field"]);
    refused(&with(json!({"drum": "driven", "tilt_x": [0.0, 1e-3]})), "drive.steering.tilt_x[0]", &["pair"]);
    refused(&with(json!({"drum": "driven", "tilt_x": [[0.0, 1e-3, 2.0]]})), "drive.steering.tilt_x[0]", &["pair"]);
    refused(&with(json!({"drum": "driven", "tilt_x": "0.001"})), "drive.steering.tilt_x", &["[t, value]"]);
    refused(&with(json!({"drum": "driven", "tilt_y": [[1.0, 0.0], [1.0, 1e-3]]})), "drive.steering.tilt_y[1]", &["increase strictly"]);
    refused(&with(json!({"drum": "driven", "tilt_y": [[-1.0, 0.0]]})), "drive.steering.tilt_y[0][0]", &["-1"]);
    refused(&with(json!({"drum": "driven", "tilt_x": [[0.0, 0.9]]})), "drive.steering.tilt_x[0][1]", &["π/4"]);
}

#[test]
fn shell_fem_settings_are_checked_and_rod_settings_refused() {
    let with = |key: &str, value: Value| {
        let mut v = ci();
        v["fem"][key] = value;
        v
    };
    refused(&with("elements_zeta", json!(3)), "fem.elements_zeta", &["even"]);
    refused(&with("elements_zeta", json!(0)), "fem.elements_zeta", &["even"]);
    refused(&with("elements_sigma", json!(4)), "fem.elements_sigma", &["8 … 4096"]);
    refused(&with("steps", json!(0)), "fem.steps", &["at least 1"]);
    refused(&with("ramp_steps", json!(0)), "fem.ramp_steps", &["at least 1"]);
    refused(&with("duration", json!(-1.0)), "fem.duration", &[]);
    // steps or duration, not both
    let mut v = with("duration", json!(3.0));
    v["fem"]["steps"] = json!(4);
    refused(&v, "fem.duration", &["not both"]);
    // a duration gives ⌈duration/Δt⌉ steps
    let mut v = ci();
    v["fem"].as_object_mut().unwrap().remove("steps");
    let dt = v["fem"]["time_step"].as_f64().unwrap();
    v["fem"]["duration"] = json!(10.5 * dt);
    assert_eq!(read(&v).unwrap().shell_run().steps, 11);
    // too many steps
    let mut v = ci();
    v["fem"]["steps"] = json!(drive::scene::MAX_SHELL_STEPS + 1);
    refused(&v, "fem.steps", &["at most"]);
    // the drum turns at most π/4 per step
    refused(&with("time_step", json!(10.0)), "fem.time_step", &["π/4"]);
    // the rod and string FE settings are not read by the shell's FE: refused, not ignored
    refused(&with("penalty", json!(1e6)), "fem.penalty", &["elements_sigma"]);
    refused(&with("elements", json!(64)), "fem.elements", &["elements_sigma"]);
    refused(&with("mesh_sequence", json!([8, 16])), "fem.mesh_sequence", &["elements_sigma"]);
    // and the shell's settings belong to the shell
    let mut rod: Value = serde_json::from_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    rod["fem"] = json!({"elements_zeta": 2});
    refused(&rod, "fem.elements_zeta", &["theory `shell`"]);
    rod["fem"] = json!({"contact_rule": "simpson"});
    refused(&rod, "fem.contact_rule", &["theory `shell`"]);
    refused(&with("elements_zita", json!(2)), "fem.elements_zita", &["elements_zeta"]);
    // the interlayer's σ-rule: simpson (default) or trapezoidal, nothing else
    assert_eq!(read(&with("contact_rule", json!("trapezoidal"))).unwrap().shell_run().contact_rule, drive::scene::ShellContactRule::Trapezoidal);
    assert!(read(&with("contact_rule", json!("gauss"))).is_err());
    // its ζ-rule across the width: gauss2 (default) to gauss5, nothing else, only on a shell
    for (name, points) in [("gauss2", 2), ("gauss3", 3), ("gauss4", 4), ("gauss5", 5)] {
        assert_eq!(read(&with("contact_rule_width", json!(name))).unwrap().shell_run().contact_rule_width.points(), points);
    }
    assert!(read(&with("contact_rule_width", json!("gauss6"))).is_err());
    assert!(read(&with("contact_rule_width", json!("simpson"))).is_err());
    rod["fem"] = json!({"contact_rule_width": "gauss4"});
    refused(&rod, "fem.contact_rule_width", &["theory `shell`"]);
    // the ζ-mesh: graded (default) or uniform, nothing else, and only on a shell
    assert_eq!(read(&with("zeta_mesh", json!("uniform"))).unwrap().shell_run().zeta_mesh, drive::scene::ShellZetaMesh::Uniform);
    assert_eq!(read(&with("zeta_mesh", json!("graded"))).unwrap().shell_run().zeta_mesh, drive::scene::ShellZetaMesh::Graded);
    assert!(read(&with("zeta_mesh", json!("chebyshev"))).is_err());
    rod["fem"] = json!({"zeta_mesh": "uniform"});
    refused(&rod, "fem.zeta_mesh", &["theory `shell`"]);
    // the σ-mesh's grading towards the contact edges: either number may be left out,
    // the ratio in [0, 1000], the width in (0, 1000] ℓ_c, nothing else, only on a shell
    let grading = |g: Value| read(&with("sigma_grading", g)).ok().map(|s| s.shell_run().sigma_grading);
    let given = |ratio: f64, width: f64| Some(drive::scene::ShellSigmaGrading { ratio, width });
    assert_eq!(grading(json!({"ratio": 24.0, "width": 6.0})), given(24.0, 6.0));
    assert_eq!(grading(json!({"ratio": 24.0})), given(24.0, 2.0));
    assert_eq!(grading(json!({"width": 0.5})), given(8.0, 0.5));
    assert_eq!(grading(json!({"ratio": 0.0})), given(0.0, 2.0));
    refused(&with("sigma_grading", json!({"ratio": -1.0})), "fem.sigma_grading.ratio", &["from 0 to 1000"]);
    refused(&with("sigma_grading", json!({"ratio": 2000.0})), "fem.sigma_grading.ratio", &["from 0 to 1000"]);
    refused(&with("sigma_grading", json!({"width": 0.0})), "fem.sigma_grading.width", &["above 0", "ℓ_c"]);
    refused(&with("sigma_grading", json!({"width": 1e4})), "fem.sigma_grading.width", &["at most 1000"]);
    assert!(grading(json!({"ratio": 24.0, "sharpness": 2.0})).is_none());
    assert!(grading(json!(24.0)).is_none());
    rod["fem"] = json!({"sigma_grading": {"ratio": 24.0}});
    refused(&rod, "fem.sigma_grading", &["theory `shell`"]);
}

#[test]
fn defaults_of_the_shell_run() {
    let mut v = ci();
    v.as_object_mut().unwrap().remove("fem");
    let s = read(&v).unwrap();
    let run = s.shell_run();
    let omega = s.drive.driver_speed;
    assert_eq!((run.elements_sigma, run.elements_zeta, run.ramp_steps, run.frame_every), (64, 2, 1, 0));
    assert_eq!(run.contact_rule, drive::scene::ShellContactRule::Simpson);
    assert_eq!(run.contact_rule_width, drive::scene::ShellWidthRule::Gauss2);
    assert_eq!(run.zeta_mesh, drive::scene::ShellZetaMesh::Graded);
    assert_eq!(run.sigma_grading, drive::scene::ShellSigmaGrading { ratio: 8.0, width: 2.0 });
    assert!((run.time_step * omega - std::f64::consts::PI / 32.0).abs() < 1e-15);
    // one revolution of the belt L/(ωR)
    let revolution = s.belt.length / (omega * s.drive.pulley_radius);
    assert_eq!(run.steps, (revolution / run.time_step).ceil() as usize);
}

/// `gate.levels` and `gate.steps` (the gate's shell study, docs/verification.md "The
/// shell's study"): read and round-tripped on a shell, checked, and refused on a rod.
#[test]
fn the_gate_block_of_a_shell_names_its_levels_and_steps() {
    let s = read(&ci()).unwrap();
    let g = s.gate_settings();
    assert_eq!(g.levels, Some(vec![[32, 8], [64, 8], [128, 8]]));
    assert_eq!(g.steps, Some(2));
    roundtrip(&s);
    let with = |key: &str, value: Value| {
        let mut v = ci();
        v["gate"][key] = value;
        v
    };
    refused(&with("levels", json!([[32, 2], [64, 2]])), "gate.levels", &["three or more levels", "2"]);
    refused(&with("levels", json!([[32, 2], [0, 2], [128, 2]])), "gate.levels[1]", &["at least 1"]);
    refused(&with("levels", json!([[32, 2], [64], [128, 2]])), "gate.levels[1]", &["[n_σ, n_ζ]"]);
    refused(&with("levels", json!([[32, 2.5], [64, 2], [128, 2]])), "gate.levels[0]", &["[n_σ, n_ζ]"]);
    refused(&with("steps", json!(0)), "gate.steps", &["at least one"]);
    let mut rod: Value = serde_json::from_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    rod["gate"]["levels"] = json!([[32, 2], [64, 2], [128, 2]]);
    refused(&rod, "gate.levels", &["theory `shell`"]);
    rod["gate"].as_object_mut().unwrap().remove("levels");
    rod["gate"]["steps"] = json!(2);
    refused(&rod, "gate.steps", &["theory `shell`"]);
}
