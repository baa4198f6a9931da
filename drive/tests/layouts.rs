//! The contract of issue 11 item 4: `drive.layout` (`two-pulley`, `one-pulley` of spec
//! §2.2) and the belt theories `cosserat` and `shell` (DESIGN.md "Scene format"). Each
//! scene is the spec's catalogue scene; each error is provoked by one edit of it and its
//! message is checked to name the field and the numbers. The solvers' refusal of what
//! they cannot solve yet names the issue that brings it.

use drive::{not_yet_solvable, Layout, OnePulleyLoad, Scene, SceneError, Solver, Theory};
use serde_json::{json, Value};

/// spec §2.2: the catalogue scene `cosserat-pulley`.
fn one_pulley() -> Value {
    json!({
      "name": "cosserat-pulley",
      "drive": {"layout": "one-pulley", "pulley_radius": 0.1, "end_distance": 0.5,
                "transport_rate": 2.0, "tension_in": 15.0, "tension_out": 10.0},
      "belt": {"theory": "cosserat", "axial_stiffness": 1.0e4, "bending_stiffness": 0.01,
               "shear_stiffness": 1.0e3, "mass_per_length": 0.1},
      "effects": {"inertia": true, "contact": {"coulomb": 0.3}},
      "analysis": "steady"
    })
}

/// spec §4.15 with the drive of `string-drive` (numbers of the spec's proposal).
fn shell() -> Value {
    json!({
      "name": "shell-runoff",
      "drive": {"pulley_radius": 0.5, "centre_distance": 4.0, "driver_speed": 1.0, "driven_torque": 0.0},
      "belt": {"theory": "shell", "length": 11.15, "width": 1.0, "thickness": 1.0e-3,
               "youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0,
               "camber": {"curvature": 0.0}},
      "effects": {"gravity": 9.81,
                  "contact": {"elastic_layer": {"normal_stiffness": 1.0e9, "tangential_stiffness": 1.0e8}}},
      "analysis": "transient"
    })
}

fn read(v: &Value) -> Result<Scene, SceneError> {
    Scene::from_json_str(&v.to_string())
}

fn err(v: &Value) -> SceneError {
    read(v).expect_err("must be refused")
}

/// `v` is refused as a field not allowed at `path`, the message mentioning `hint`.
fn not_allowed(v: &Value, path: &str, hint: &str) {
    let e = err(v);
    assert!(matches!(&e, SceneError::NotAllowed { path: p, .. } if p == path), "{e}");
    assert!(e.to_string().contains(hint), "{e}");
}

#[test]
fn one_pulley_scene_reads_writes_and_has_its_open_contour() {
    let scene = read(&one_pulley()).unwrap();
    assert_eq!(scene.drive.layout, Layout::OnePulley);
    assert_eq!(scene.drive.one_pulley_load(), Some(OnePulleyLoad::Tensions { tension_in: 15.0, tension_out: 10.0 }));
    // written without the two-pulley fields, read back equal
    let text = scene.to_json_pretty();
    for absent in ["centre_distance", "driver_speed", "driven_torque", "driven_damping", "\"length\""] {
        assert!(!text.contains(absent), "{absent} written for a one-pulley scene:\n{text}");
    }
    assert_eq!(Scene::from_json_str(&text).unwrap(), scene);
    let c = scene.open_contour().expect("one-pulley scenes have an open contour");
    assert!((c.length() - (2.0 * 0.5 + std::f64::consts::PI * 0.1)).abs() < 1e-15);
    assert!(scene.contour().length() > 0.0, "the loop contour of a one-pulley scene is not meaningful but never panics");
    // the two other prescriptions of spec §2.3
    let mut v = one_pulley();
    v["drive"].as_object_mut().unwrap().remove("tension_in");
    v["drive"]["stick_slip_angle"] = json!(0.5);
    assert!(matches!(read(&v).unwrap().drive.one_pulley_load(), Some(OnePulleyLoad::Transition { stick_slip_angle, driving: true, .. }) if stick_slip_angle == 0.5));
    // φ_B fixes the slip arc, not its sense: `belt_drives_pulley` chooses it, is written
    // and read back
    v["drive"]["belt_drives_pulley"] = json!(true);
    let braking = read(&v).unwrap();
    assert!(matches!(braking.drive.one_pulley_load(), Some(OnePulleyLoad::Transition { driving: false, .. })));
    assert!(braking.to_json_pretty().contains("\"belt_drives_pulley\": true"));
    assert_eq!(Scene::from_json_str(&braking.to_json_pretty()).unwrap(), braking);
    v["drive"]["belt_drives_pulley"] = json!(false);
    assert!(matches!(read(&v).unwrap().drive.one_pulley_load(), Some(OnePulleyLoad::Transition { driving: true, .. })));
    v["drive"].as_object_mut().unwrap().remove("belt_drives_pulley");
    v["drive"].as_object_mut().unwrap().remove("stick_slip_angle");
    v["drive"]["pulley_speed"] = json!(19.0);
    assert!(matches!(read(&v).unwrap().drive.one_pulley_load(), Some(OnePulleyLoad::PulleySpeed { pulley_speed, .. }) if pulley_speed == 19.0));
    // a two-pulley scene is written without `layout` (the default), as before
    let two = Scene::from_json_str(include_str!("../../scenes/string-drive.json")).unwrap();
    assert!(!two.to_json_pretty().contains("layout"));
    assert_eq!(two.drive.layout, Layout::TwoPulley);
    assert!(two.open_contour().is_none());
}

/// `belt_drives_pulley` only where it decides something: with `stick_slip_angle` on the
/// one-pulley layout (the tensions or ω decide the sense otherwise; the two-pulley loop
/// has `driven_torque`'s sign), and a boolean.
#[test]
fn belt_drives_pulley_is_refused_where_the_sense_is_given() {
    let mut v = one_pulley();
    v["drive"]["belt_drives_pulley"] = json!(true);
    not_allowed(&v, "drive.belt_drives_pulley", "sense follows from them");
    let mut v = one_pulley();
    v["drive"].as_object_mut().unwrap().remove("tension_in");
    v["drive"]["stick_slip_angle"] = json!(0.5);
    v["drive"]["belt_drives_pulley"] = json!("yes");
    let e = err(&v);
    assert!(e.to_string().contains("drive.belt_drives_pulley") && e.to_string().contains("true or false"), "{e}");
    let mut two: Value = serde_json::from_str(include_str!("../../scenes/string-drive.json")).unwrap();
    two["drive"]["belt_drives_pulley"] = json!(true);
    let e = err(&two);
    assert!(e.to_string().contains("belt_drives_pulley") && e.to_string().contains("one-pulley"), "{e}");
}

#[test]
fn one_pulley_errors_name_the_field_and_the_numbers() {
    let mut v = one_pulley();
    v["drive"].as_object_mut().unwrap().remove("end_distance");
    assert!(matches!(err(&v), SceneError::MissingField { path, .. } if path == "drive.end_distance"));

    let mut v = one_pulley();
    v["drive"]["centre_distance"] = json!(0.45);
    not_allowed(&v, "drive.centre_distance", "two-pulley");

    let mut v = one_pulley();
    v["belt"]["length"] = json!(1.4);
    assert!(matches!(err(&v), SceneError::NotAllowed { path, .. } if path == "belt.length"));

    let mut v = one_pulley();
    v["drive"]["pulley_speed"] = json!(20.0);
    let e = err(&v);
    assert!(matches!(&e, SceneError::OnePulleyPrescription { given } if given.len() == 3), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("got 3: `drive.tension_in` = 15, `drive.tension_out` = 10, `drive.pulley_speed` = 20"), "{msg}");

    // two prescriptions, but neither a tension
    let mut v = one_pulley();
    let d = v["drive"].as_object_mut().unwrap();
    d.remove("tension_in");
    d.remove("tension_out");
    d.insert("pulley_speed".into(), json!(20.0));
    d.insert("stick_slip_angle".into(), json!(0.3));
    assert!(matches!(err(&v), SceneError::OnePulleyPrescription { given } if given.len() == 2));

    let mut v = one_pulley();
    v["drive"]["tension_out"] = json!(-1.0);
    assert!(matches!(err(&v), SceneError::NotPositive { path, value } if path == "drive.tension_out" && value == -1.0));

    let mut v = one_pulley();
    v["drive"].as_object_mut().unwrap().remove("tension_out");
    v["drive"]["stick_slip_angle"] = json!(4.0);
    assert!(matches!(err(&v), SceneError::OutOfRange { path, value, .. } if path == "drive.stick_slip_angle" && value == 4.0));
    // off the wrapped half (|φ_B| ≥ π/2): no contact there to hold a stick → slip point
    for phi in [2.0, -1.6, std::f64::consts::FRAC_PI_2] {
        v["drive"]["stick_slip_angle"] = json!(phi);
        let e = err(&v);
        assert!(matches!(&e, SceneError::OutOfRange { path, value, .. } if path == "drive.stick_slip_angle" && *value == phi), "{e}");
        assert!(e.to_string().contains("π/2"), "{e}");
    }
    v["drive"]["stick_slip_angle"] = json!(1.5);
    assert!(Scene::from_json_str(&v.to_string()).is_ok());

    // χ = ρc² = 0.1·200² = 4000 N ≥ GA = 1000 N
    let mut v = one_pulley();
    v["drive"]["transport_rate"] = json!(200.0);
    let e = err(&v);
    assert!(matches!(&e, SceneError::SpeedAtOrAboveCritical { path, stiffness, .. } if path == "belt.shear_stiffness" && *stiffness == 1e3), "{e}");
    assert!(e.to_string().contains("`belt.shear_stiffness` = 1000 N must exceed χ = ρc² = 0.1·200² = 4000 N"), "{e}");

    // gravity: neither solver has it on this layout (the BVP ignored it before)
    let mut v = one_pulley();
    v["effects"]["gravity"] = json!(9.81);
    let e = err(&v);
    assert!(matches!(&e, SceneError::NotAllowed { path, .. } if path == "effects.gravity"), "{e}");
    assert!(e.to_string().contains("9.81"), "{e}");
    let mut v = one_pulley();
    v["effects"]["gravity"] = json!(0.0);
    assert!(read(&v).is_ok());

    let mut v = one_pulley();
    v["analysis"] = json!("transient");
    assert!(matches!(err(&v), SceneError::NotAllowed { path, .. } if path == "analysis"));

    // a one-pulley field in a two-pulley scene
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/string-drive.json")).unwrap();
    v["drive"]["tension_in"] = json!(10.0);
    not_allowed(&v, "drive.tension_in", "one-pulley");
    // an unknown layout suggests the nearest
    let mut v = one_pulley();
    v["drive"]["layout"] = json!("one-pully");
    assert!(err(&v).to_string().contains("did you mean `one-pulley`"));
}

#[test]
fn shell_scene_takes_its_plate_and_derives_the_planar_section() {
    let scene = read(&shell()).unwrap();
    assert_eq!(scene.belt.theory, Theory::Shell);
    let (b, h, e, nu, rho) = (1.0, 1.0e-3, 2.1e11, 0.3, 7850.0);
    // EA = E b h, EI = E b h³/(12(1 − ν²)), ρ = ρ_V b h
    assert!((scene.belt.axial_stiffness - e * b * h).abs() < 1e-6 * e * b * h);
    let ei = e * b * h * h * h / (12.0 * (1.0 - nu * nu));
    assert!((scene.belt.bending_stiffness.unwrap() - ei).abs() < 1e-12 * ei);
    assert!((scene.belt.mass_per_length - rho * b * h).abs() < 1e-12);
    let text = scene.to_json_pretty();
    assert!(!text.contains("axial_stiffness") && !text.contains("mass_per_length"), "{text}");
    assert_eq!(Scene::from_json_str(&text).unwrap(), scene);

    let mut v = shell();
    v["belt"]["axial_stiffness"] = json!(2.1e8);
    not_allowed(&v, "belt.axial_stiffness", "youngs_modulus");

    let mut v = shell();
    v["belt"].as_object_mut().unwrap().remove("poisson_ratio");
    assert!(matches!(err(&v), SceneError::MissingField { path, .. } if path == "belt.poisson_ratio"));

    let mut v = shell();
    v["belt"]["thickness"] = json!(2.0);
    assert!(matches!(err(&v), SceneError::OutOfRange { path, value, .. } if path == "belt.thickness" && value == 2.0));

    let mut v = shell();
    v["belt"]["poisson_ratio"] = json!(0.5);
    assert!(matches!(err(&v), SceneError::OutOfRange { path, .. } if path == "belt.poisson_ratio"));

    let mut v = shell();
    v["belt"]["camber"] = json!({"curvature": 0.1, "edge_length_difference": 0.01});
    assert!(matches!(err(&v), SceneError::Invalid { path, .. } if path == "belt.camber"));

    // the interlayer by its material (spec §4.6): d = 5 mm, E_l = 10 MPa, ν_l = 0.45
    let mut v = shell();
    v["effects"]["contact"] = json!({"elastic_layer": {"thickness": 5e-3, "youngs_modulus": 1e7, "poisson_ratio": 0.45}});
    let scene = read(&v).unwrap();
    let drive::Contact::ElasticLayer(layer) = &scene.effects.contact else { panic!("elastic layer expected") };
    let (d, el, nl) = (5e-3, 1e7, 0.45);
    let p = el * (1.0 - nl) / ((1.0 + nl) * (1.0 - 2.0 * nl) * d);
    assert!((layer.normal_stiffness - p).abs() < 1e-12 * p, "P = {} vs {p}", layer.normal_stiffness);
    assert!((layer.tangential_stiffness - el / (2.0 * (1.0 + nl) * d)).abs() < 1e-3, "P_⊥ = {}", layer.tangential_stiffness);
    let text = scene.to_json_pretty();
    assert!(!text.contains("normal_stiffness"), "the material form is written as given:\n{text}");
    assert_eq!(Scene::from_json_str(&text).unwrap(), scene);
    // one form, not both; the material complete
    v["effects"]["contact"]["elastic_layer"]["normal_stiffness"] = json!(1e9);
    not_allowed(&v, "effects.contact.elastic_layer.normal_stiffness", "one form");
    v["effects"]["contact"] = json!({"elastic_layer": {"thickness": 5e-3, "youngs_modulus": 1e7}});
    assert!(matches!(err(&v), SceneError::MissingField { path, .. } if path == "effects.contact.elastic_layer.poisson_ratio"));
    v["effects"]["contact"]["elastic_layer"]["poisson_ratio"] = json!(0.5);
    assert!(matches!(err(&v), SceneError::OutOfRange { path, .. } if path == "effects.contact.elastic_layer.poisson_ratio"));

    // plate parameters belong to the shell only
    let mut v = one_pulley();
    v["belt"]["width"] = json!(0.02);
    assert!(matches!(err(&v), SceneError::NotAllowed { path, .. } if path == "belt.width"));
}

#[test]
fn solvers_refuse_what_they_cannot_solve_yet_naming_the_issue() {
    let pulley = read(&one_pulley()).unwrap();
    // both solve the one-pulley Cosserat scene (the FE: docs/fem-cosserat.md §12)
    assert!(not_yet_solvable(&pulley, Solver::Bvp).is_none());
    assert!(not_yet_solvable(&pulley, Solver::Fem).is_none());
    // a one-pulley string has no model in either solver
    let mut string = one_pulley();
    string["belt"] = json!({"theory": "string", "axial_stiffness": 1.0e4, "mass_per_length": 0.1});
    let string = read(&string).unwrap();
    assert_eq!(not_yet_solvable(&string, Solver::Bvp).map(|e| e.issue), Some(13));

    // the FE solves the shell (issue 15); no BVP exists for it: a refusal that says so
    // and does not promise one
    let runoff = read(&shell()).unwrap();
    assert!(not_yet_solvable(&runoff, Solver::Fem).is_none());
    let e = not_yet_solvable(&runoff, Solver::Bvp).unwrap();
    assert_eq!(e.issue, 15);
    let msg = e.to_string();
    assert!(msg.contains("no BVP exists for theory `shell`") && msg.contains("--method fem") && !msg.contains("yet"), "{msg}");
    let mut steady = shell();
    steady["analysis"] = json!("steady");
    let e = not_yet_solvable(&read(&steady).unwrap(), Solver::Fem).unwrap();
    assert!(e.to_string().contains("theory `shell` (analysis `steady`)"), "{e}");

    let mut drive: Value = serde_json::from_str(include_str!("../../scenes/string-drive.json")).unwrap();
    assert!(not_yet_solvable(&read(&drive).unwrap(), Solver::Bvp).is_none());
    drive["belt"]["theory"] = json!("cosserat");
    drive["belt"]["bending_stiffness"] = json!(0.005);
    drive["belt"]["shear_stiffness"] = json!(1e3);
    // the steady Cosserat drive: both solve it; its transient is not there yet
    assert!(not_yet_solvable(&read(&drive).unwrap(), Solver::Fem).is_none());
    assert!(not_yet_solvable(&read(&drive).unwrap(), Solver::Bvp).is_none());
    drive["analysis"] = json!("transient");
    drive.as_object_mut().unwrap().remove("bvp");
    assert_eq!(not_yet_solvable(&read(&drive).unwrap(), Solver::Fem).unwrap().issue, 14);
    let rod = Scene::from_json_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    assert!(not_yet_solvable(&rod, Solver::Fem).is_none());
    // The static Cosserat loop: both solve it (friction at rest is a scene error).
    let mut hanging: Value = serde_json::from_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
    hanging["belt"]["theory"] = json!("cosserat");
    hanging["belt"]["shear_stiffness"] = json!(1e3);
    let frictionless = read(&hanging).unwrap();
    assert!(not_yet_solvable(&frictionless, Solver::Bvp).is_none());
    assert!(not_yet_solvable(&frictionless, Solver::Fem).is_none());
    hanging["analysis"] = json!("transient");
    hanging["effects"]["contact"] = json!({"coulomb": 0.3});
    hanging.as_object_mut().unwrap().remove("bvp");
    assert_eq!(not_yet_solvable(&read(&hanging).unwrap(), Solver::Fem).unwrap().issue, 14);
}

/// `fem.contact = "augmented-lagrangian"` is read by the steady one-pulley Cosserat solve
/// and the static Cosserat loop only: accepted there, refused by name on every other
/// scene (the two-pulley Cosserat drive, strings, rods) instead of being ignored.
#[test]
fn augmented_lagrangian_contact_only_where_it_is_built() {
    let mut v = one_pulley();
    v["fem"] = json!({"contact": "augmented-lagrangian"});
    read(&v).unwrap();
    let mut hanging: Value = serde_json::from_str(include_str!("../../scenes/cosserat-hanging.json")).unwrap();
    hanging["fem"]["contact"] = json!("augmented-lagrangian");
    read(&hanging).unwrap();
    for file in [include_str!("../../scenes/cosserat-drive.json"), include_str!("../../scenes/string-drive.json"), include_str!("../../scenes/rod-hanging.json"), include_str!("../../scenes/string-hanging.json")] {
        let mut v: Value = serde_json::from_str(file).unwrap();
        v["fem"]["contact"] = json!("augmented-lagrangian");
        not_allowed(&v, "fem.contact", "Cosserat belt's steady one-pulley solve and its static analysis");
        v["fem"]["contact"] = json!("penalty");
        read(&v).unwrap();
    }
}
