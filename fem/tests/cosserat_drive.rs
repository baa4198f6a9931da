//! The two-pulley Cosserat drive in steady motion by the FE's direct steady solve
//! (docs/fem-cosserat.md §10, §11): the `string-drive` geometry with `"theory": "cosserat"`
//! (a, b₂ given), solved through `solve_scene` with the Cosserat element — the power
//! balance P_in = P_out + D and the driven pulley's torque balance to round-off, creep
//! (ω₂ < ω₁), stick and slip on both pulleys. (The gravity-free variant, and finer
//! meshes, stall in the contact fitting — docs/fem-cosserat.md §11.)

use drive::Scene;
use fem::{FemOptions, FemRun, SolverSettings};
use serde_json::{json, Value};

/// The catalogue's `string-drive` scene as a Cosserat belt with bending stiffness `a`
/// (N·m²) and shear stiffness `b2` (N); gravity as the scene's if `gravity`.
fn scene(a: f64, b2: f64, gravity: bool) -> Scene {
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/string-drive.json")).unwrap();
    v["name"] = json!("cosserat-drive-string-geometry");
    v["belt"]["theory"] = json!("cosserat");
    v["belt"]["bending_stiffness"] = json!(a);
    v["belt"]["shear_stiffness"] = json!(b2);
    if !gravity {
        v["effects"]["gravity"] = Value::Null;
    }
    v["fem"]["formulations"] = json!(["cosserat-gauss"]);
    v.as_object_mut().unwrap().remove("gate");
    Scene::from_json_str(&v.to_string()).unwrap()
}

fn solve(scene: &Scene, elements: usize, settings: &SolverSettings) -> FemRun {
    let opts = FemOptions { elements, formulation: "cosserat-gauss".into(), penalty: None };
    fem::solve_scene_with(scene, &opts, settings).unwrap_or_else(|e| panic!("{}: {e}", scene.name))
}

fn drive_option(run: &FemRun, key: &str) -> f64 {
    run.options["drive"][key].as_f64().unwrap_or_else(|| panic!("options.drive.{key}"))
}

/// Power P_in − P_out − D to 1e-9 of P_in (it follows from the c-row (DS2), as for the
/// string), the driven torque M₂ + d₂ω₂ to 1e-9 relative (the ω₂-row (DS3)), creep
/// 0 < ω₂ < ω₁ and both pulleys with stick and slip arcs.
fn check_balances(scene: &Scene, r: &FemRun) {
    let s = &r.summary;
    let (m2, d2) = (scene.drive.driven_torque, scene.drive.driven_damping);
    let w2 = s.driven_speed.unwrap();
    let load = m2 + d2 * w2;
    let (pin, pout, d) = (drive_option(r, "power_in"), drive_option(r, "power_out"), drive_option(r, "dissipation"));
    eprintln!("{}: P_in {pin} P_out {pout} D {d}, ω₂ {w2}, M₁ {:?}, M₂ {:?}", scene.name, s.driver.as_ref().unwrap().torque, s.driven.as_ref().unwrap().torque);
    assert!((pin - pout - d).abs() < 1e-9 * pin, "P_in {pin} − P_out {pout} − D {d} = {:e}", pin - pout - d);
    assert!(d > 0.0, "slip dissipates");
    let t2 = s.driven.as_ref().unwrap().torque.unwrap();
    assert!((t2 - load).abs() < 1e-9 * load, "driven torque {t2} vs M₂ + d₂ω₂ = {load}");
    assert!(w2 > 0.0 && w2 < scene.drive.driver_speed, "creep: ω₂ = {w2}");
    for p in [&s.driver, &s.driven] {
        let p = p.as_ref().unwrap();
        assert!(p.stick_arc.unwrap() > 0.1 && p.slip_arc.unwrap() > 0.1, "stick {:?} and slip {:?} arcs", p.stick_arc, p.slip_arc);
    }
}

#[test]
fn cosserat_drive_balances_power_and_torque() {
    let sc = scene(1e-3, 1e4, true);
    let r = solve(&sc, 64, &SolverSettings::default());
    check_balances(&sc, &r);
    assert!(r.summary.moment_upper_mid.is_some(), "the rod's bending moment is in the view");
}
