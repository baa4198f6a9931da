//! Bad input is an error value that names the problem and carries the numbers — never a
//! panic, never a NaN in an output.

mod common;

use common::*;
use fem::{FemError, FemOptions, SolverSettings};

fn opts(elements: usize) -> FemOptions {
    FemOptions { elements, formulation: fem::default_formulation().into(), penalty: None }
}

#[test]
fn registry_and_defaults() {
    assert_eq!(fem::available_formulations(), vec!["string-simpson", "string-gauss", "rod-simpson", "rod-gauss", "cosserat-gauss", "cosserat-reduced"]);
    assert_eq!(fem::formulations_for(drive::scene::Theory::String), vec!["string-simpson", "string-gauss"]);
    assert_eq!(fem::formulations_for(drive::scene::Theory::Kirchhoff), vec!["rod-simpson", "rod-gauss"]);
    assert_eq!(fem::formulations_for(drive::scene::Theory::Cosserat), vec!["cosserat-gauss", "cosserat-reduced"]);
    assert_eq!(fem::default_formulation(), "string-simpson");
    let scene = scene("string-hanging");
    let o = FemOptions::from_scene(&scene, "string-simpson");
    assert_eq!((o.elements, o.formulation.as_str(), o.penalty), (256, "string-simpson", None));
    SolverSettings::default().validate().unwrap();
}

#[test]
fn invalid_options() {
    let scene = scene("string-hanging");
    let e = fem::solve_scene(&scene, &FemOptions { formulation: "string-nonsense".into(), ..opts(64) }).err().unwrap();
    assert!(matches!(&e, FemError::UnknownFormulation { name, available } if name == "string-nonsense" && available.len() == 6), "{e}");
    for n in [0, 3, (1 << 20) + 1] {
        let e = fem::solve_scene(&scene, &opts(n)).err().unwrap();
        assert!(matches!(&e, FemError::InvalidOption { field: "elements", .. }), "{n}: {e}");
    }
    for p in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
        let e = fem::solve_scene(&scene, &FemOptions { penalty: Some(p), ..opts(64) }).err().unwrap();
        assert!(matches!(&e, FemError::InvalidOption { field: "penalty", .. }), "{p}: {e}");
    }
    let bad = SolverSettings { update_tolerance: 0.0, ..SolverSettings::default() };
    let e = fem::solve_scene_with(&scene, &opts(64), &bad).err().unwrap();
    assert!(matches!(&e, FemError::InvalidOption { field: "update_tolerance", .. }), "{e}");
    let bad = SolverSettings { arc_weight: 0.5, ..SolverSettings::default() };
    assert!(fem::solve_scene_with(&scene, &opts(64), &bad).is_err());
}

/// A weightless loop longer than the contour has no unique equilibrium: an error naming
/// L and L_geom (as the BVP), with the gravity term absent or present with g = 0.
#[test]
fn weightless_slack_loop_is_ill_posed() {
    for gravity in [None, Some(0.0)] {
        let mut scene = scene("string-hanging");
        scene.effects.gravity = gravity;
        let e = fem::solve_scene(&scene, &opts(64)).err().unwrap();
        match &e {
            FemError::IllPosed { length, geometric_length } => {
                assert_eq!(*length, 1.41);
                assert!((geometric_length - scene.geometric_length()).abs() < 1e-15);
            }
            other => panic!("{gravity:?}: {other}"),
        }
        assert!(e.to_string().contains("1.41"));
    }
}

#[test]
fn other_models_are_unsupported() {
    let rod = drive::Scene::from_json_str(
        r#"{"name": "rod", "drive": {"pulley_radius": 0.08, "centre_distance": 0.45,
            "driver_speed": 0.0, "driven_torque": 0.0},
            "belt": {"theory": "kirchhoff", "length": 1.41, "axial_stiffness": 2e4,
                     "bending_stiffness": 0.01, "mass_per_length": 0.12},
            "effects": {"gravity": 9.81, "contact": "frictionless"}, "analysis": "static"}"#,
    )
    .unwrap();
    let e = fem::solve_scene(&rod, &opts(64)).err().unwrap();
    assert!(matches!(e, FemError::Unsupported(_)), "{e}");
    assert!(e.to_string().contains("kirchhoff"));
    // and rod elements do not apply to a string (docs/fem-rod.md §4)
    let e = fem::solve_scene(&scene("string-hanging"), &FemOptions { formulation: "rod-gauss".into(), ..opts(64) }).err().unwrap();
    assert!(matches!(&e, FemError::Unsupported(m) if m.contains("rod-gauss") && m.contains("string")), "{e}");
}

/// The drive's torque balance is a self-check (issue 12 item 6, audit): `string-drive`
/// with EA = 1e50 N converged to tensions of 1.8e48 N, whose differences cannot resolve
/// the 13 N·m load — the driven pulley's torque from the tractions came out as 0 N·m at
/// 32 elements (and −2.4e20 N·m at 128), exit 0. Now a named error; the same drive at
/// EA = 1e17 N (tensions 1.8e15 N) still balances and solves.
#[test]
fn drive_torque_balance_is_checked() {
    let mut s = scene("string-drive");
    s.belt.axial_stiffness = 1e50;
    let e = fem::solve_scene(&s, &opts(32)).err().expect("EA = 1e50 N must not give a result");
    match &e {
        FemError::TorqueBalance { torque, load, limit, .. } => {
            assert!((load - 13.0).abs() < 1e-9, "load {load}");
            assert!((torque - load).abs() > 1e3 * limit, "torque {torque}, limit {limit}");
        }
        other => panic!("expected TorqueBalance, got {other:?}"),
    }
    assert!(e.to_string().contains("self-check failed"), "{e}");
    s.belt.axial_stiffness = 1e17;
    let run = fem::solve_scene(&s, &opts(32)).expect("EA = 1e17 N solves");
    let torque = run.summary.driven.unwrap().torque.unwrap();
    assert!((torque - 13.0).abs() < 1e-6 * 13.0, "{torque}");
}

/// A stalled static homotopy says which scene quantity it was switching on, the scene's
/// numbers that make it hard and what to try, with significant digits (issue 12,
/// "smaller ones", audit): `string-hanging` with R = 0.01 m at 32 elements used to say
/// only "homotopy stalled at η = 0.6194416697474341 …".
#[test]
fn stalled_static_homotopy_names_the_scene_quantity() {
    let mut s = scene("string-hanging");
    s.drive.pulley_radius = 0.01;
    let e = fem::solve_scene(&s, &opts(32)).err().expect("R = 0.01 m at 32 elements stalls");
    let text = e.to_string();
    println!("{text}");
    match &e {
        FemError::StaticHomotopyStalled { at, hard, cause } => {
            assert!(at.contains("lengthening the loop"), "{at}");
            assert!(hard.contains("L/L_geom") && hard.contains("R = 0.01 m") && hard.contains("--elements 64"), "{hard}");
            assert!(matches!(**cause, FemError::HomotopyStalled { .. }), "{cause}");
        }
        other => panic!("expected StaticHomotopyStalled, got {other:?}"),
    }
    // no η or other number with more than six significant digits
    let long_number = text.split(|c: char| !(c.is_ascii_digit() || c == '.')).any(|w| w.chars().filter(|c| c.is_ascii_digit()).count() > 9);
    assert!(!long_number, "{text}");
}
