//! The harness side of issue 12 and issue 11 item 7: a gate with zero comparable FE
//! runs fails (it used to pass on the BVP rows alone), and a transient cut off by
//! `fem.max_steps` is a failed run in studies, not a converged one.

use std::path::Path;

use drive::scene::{GateSettings, Scene};
use verification::gate;
use verification::run::{execute, BvpSolver, BvpVariant, Discretisation, Family, FemFormulation, FnMethod, Method, RunError};
use verification::study::{Formulations, Study};

fn catalogue_scene(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(format!("{name}.json"))).unwrap()
}

/// An FE method with no model for any scene.
fn never_applies() -> FnMethod {
    FnMethod::new("fem never-applies", Family::Fem, |_, _| Err(RunError::NotApplicable("no model".into())))
}

/// The BVP rows pass (limit 1e-3 against errors ~1e-10 at tolerance 1e-8), every FE
/// formulation is "not applicable": the gate fails with a check naming the zero FE
/// runs. With the FE not asked for (`--bvp-only`) the same BVP rows pass.
#[test]
fn gate_with_zero_comparable_fe_runs_fails() {
    let scene = catalogue_scene("string-hanging");
    let settings = GateSettings { tolerances: [("y_upper_mid".to_string(), 1e-3)].into(), ..GateSettings::default() };
    let bvp = || -> (Box<dyn Method>, Vec<Discretisation>) { (Box::new(BvpSolver::new(BvpVariant::Shooting)), vec![Discretisation::Tolerance(1e-8)]) };

    let plan = gate::gate_plan_with(&scene, Some(1e-8), Some(&[16]), Some(Formulations::Discovered));
    let methods = vec![bvp(), (Box::new(never_applies()) as Box<dyn Method>, vec![Discretisation::Elements(16)])];
    let study = Study::run_methods(&scene, &plan, methods, false, &mut |_| {});
    let outcome = gate::evaluate(&settings, &study);
    assert!(!outcome.passed(), "{:#?}", outcome.checks);
    let failures: Vec<_> = outcome.failures().collect();
    assert_eq!(failures.len(), 1, "{failures:#?}");
    assert_eq!(failures[0].quantity, "(FE runs)");
    assert!(failures[0].reason.contains("zero comparable FE runs"), "{}", failures[0].reason);

    let plan = gate::gate_plan_with(&scene, Some(1e-8), Some(&[16]), Some(Formulations::Named(Vec::new())));
    let study = Study::run_methods(&scene, &plan, vec![bvp()], false, &mut |_| {});
    let outcome = gate::evaluate(&settings, &study);
    assert!(outcome.passed(), "{:#?}", outcome.checks);
}

/// `string-drive` as a transient stopped after one step: the harness run fails with the
/// step count and the change rate above the threshold.
#[test]
fn transient_cut_off_is_a_failed_run() {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-drive.json")).unwrap()).unwrap();
    v["analysis"] = serde_json::json!("transient");
    v.as_object_mut().unwrap().remove("bvp");
    v["fem"] = serde_json::json!({"elements": 32, "max_steps": 1});
    let scene = Scene::from_json_str(&v.to_string()).unwrap();
    let method = FemFormulation { name: "string-simpson".into(), penalty: None };
    let run = execute(&method, &scene, Discretisation::Elements(32), 64);
    match run.outcome {
        Err(RunError::NotSteady(n)) => {
            assert_eq!(n.steps, 1);
            assert!(n.rate > n.tolerance, "{n:?}");
        }
        other => panic!("expected NotSteady, got {:?}", other.map(|d| d.summary)),
    }
}

/// `cosserat-hanging` at 64 elements, where the contact fitting does not converge (its
/// boundaries still move 6.0e-5 m after 2 × 10 passes, the tolerance 1.4e-9 m): the
/// harness run fails as a transient cut off does, with the numbers (it used to count as
/// converged, the non-convergence only in its options).
#[test]
fn unconverged_contact_fitting_is_a_failed_run() {
    let scene = Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cosserat-hanging.json")).unwrap();
    let method = FemFormulation { name: "cosserat-gauss".into(), penalty: None };
    let run = execute(&method, &scene, Discretisation::Elements(64), 64);
    match &run.outcome {
        Err(e @ RunError::Unfitted(u)) => {
            assert_eq!(e.kind(), "not_converged");
            assert!(u.last_move.is_some_and(|m| m > 1e3 * u.tolerance), "{u:?}");
            assert!(e.to_string().contains("contact fitting did not converge"), "{e}");
        }
        other => panic!("expected Unfitted, got {:?}", other.as_ref().map(|d| &d.summary)),
    }
}

/// The solvers' errors reach the harness as values, not strings (issue 11 item 7): an
/// overloaded drive (M₂ = 1000 N·m against a capacity of ~21 N·m) fails in the FE with
/// `FemError::FrictionCapacityExceeded` carrying both torques, and in the BVP with the
/// BVP's own error type.
#[test]
fn solver_errors_stay_typed() {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-drive.json")).unwrap()).unwrap();
    v["drive"]["driven_torque"] = serde_json::json!(1000.0);
    let scene = Scene::from_json_str(&v.to_string()).unwrap();
    let fe = FemFormulation { name: "string-simpson".into(), penalty: None };
    match execute(&fe, &scene, Discretisation::Elements(32), 64).outcome {
        Err(RunError::Fem(fem::FemError::FrictionCapacityExceeded { torque, capacity, .. })) => {
            assert!(torque > 1000.0 && capacity < torque, "{torque} vs {capacity}");
        }
        other => panic!("expected a typed FE error, got {:?}", other.err()),
    }
    let bvp = BvpSolver::new(BvpVariant::Shooting);
    match execute(&bvp, &scene, Discretisation::Tolerance(1e-6), 64).outcome {
        Err(e @ RunError::Bvp(_)) => {
            assert!(e.to_string().contains("friction capacity"), "{e}");
            assert_eq!(e.kind(), "failed");
            let json = serde_json::to_value(&e).unwrap();
            assert_eq!(json["kind"], "failed");
            assert_eq!(json["message"], e.to_string());
        }
        other => panic!("expected a typed BVP error, got {:?}", other.err()),
    }
}

/// The gate sizes a scene's BVP runs by its `gate.reference_tolerance` and
/// `gate.bvp_tolerance` (the catalogue's `cosserat-drive`: 1e-8 and 1e-7, for CI time,
/// docs/verification.md); a tolerance given to the gate (`--tolerance`) overrides the
/// scene's, and a scene without them keeps the defaults 1e-10 and 1e-8.
#[test]
fn gate_plan_takes_the_scene_tolerances() {
    let tolerances = |plan: &verification::study::StudyPlan| {
        let verification::reference::Reference::Bvp { tolerance, .. } = plan.reference else { panic!("a BVP reference") };
        (tolerance, plan.bvp.iter().map(|s| s.tolerances.clone()).collect::<Vec<_>>())
    };
    let drive = catalogue_scene("cosserat-drive");
    assert_eq!(tolerances(&gate::gate_plan_with(&drive, None, None, None)), (1e-8, vec![vec![1e-7]; 2]));
    assert_eq!(tolerances(&gate::gate_plan_with(&drive, Some(1e-6), None, None)), (1e-8, vec![vec![1e-6]; 2]));
    let hanging = catalogue_scene("string-hanging");
    assert_eq!(tolerances(&gate::gate_plan_with(&hanging, None, None, None)), (gate::GATE_REFERENCE_TOLERANCE, vec![vec![gate::GATE_BVP_TOLERANCE]; 2]));
}

/// `gate.fem: false` (a scene whose FE the gate cannot yet hold to its limits; the
/// catalogue's `cosserat-drive` had it until its slip arcs came within 1 % at 256
/// elements, docs/fem-cosserat.md §11.1) plans no FE run even where the FE solves the
/// scene; a scene without it keeps its FE studies.
#[test]
fn gate_fem_false_plans_the_bvp_only() {
    let drive = catalogue_scene("cosserat-drive");
    assert_eq!(drive.gate_settings().fem, None, "the catalogue's cosserat-drive gates its FE");
    assert!(drive::not_yet_solvable(&drive, drive::Solver::Fem).is_none(), "the FE solves cosserat-drive");
    let mut without_fem = drive.clone();
    without_fem.gate.as_mut().expect("a gate block").fem = Some(false);
    let plan = gate::gate_plan_with(&without_fem, None, None, None);
    assert!(plan.meshes.is_empty() && plan.fem_methods().is_empty(), "gate.fem = false must plan no FE run");
    let plan = gate::gate_plan_with(&drive, None, None, None);
    assert!(!plan.meshes.is_empty() && !plan.fem_methods().is_empty(), "without gate.fem the gate studies the FE");
}
