//! End-to-end tests of the verification harness (issue 4; DESIGN.md "The verification
//! harness"): `converge`, `report` and `gate` through the command line, and the gate's
//! verdicts on studies with a deliberately perturbed method.
//!
//! What is proved here:
//! - the gate passes on the catalogue and fails — exit status 1 with a table naming the
//!   quantity, its error and its limit — on an impossible tolerance, on a quantity that
//!   cannot be computed, on a scene without gate tolerances, and on a perturbed result;
//! - FE formulations are discovered: every name of `fem::available_formulations()`
//!   appears in a study and is gated with no harness change;
//! - no output carries NaN; an undefined number is "—" (text) or `null` (JSON).
//!
//! Run in release mode (`cargo test --release --test harness`): the studies solve BVPs.

use std::path::{Path, PathBuf};

use drive::scene::{GateSettings, Scene};
use drive::summary::Summary;
use drive::view::{ContactState, SolutionView};
use verification::gate;
use verification::run::{BvpSolver, BvpVariant, Discretisation, Family, FnMethod, Method};
use verification::study::{Study, StudyPlan};

mod common;
use common::{beltcheck, stderr, stdout};

fn temp(name: &str) -> PathBuf {
    common::temp("harness", name)
}

fn catalogue_scene(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(format!("{name}.json"))).unwrap()
}

/// A copy of `string-hanging` with another gate block, written to a temporary file.
fn scene_with_gate(file: &str, gate: serde_json::Value) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-hanging.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    if gate.is_null() {
        v.as_object_mut().unwrap().remove("gate");
    } else {
        v["gate"] = gate;
    }
    let p = temp(file);
    std::fs::write(&p, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    p
}

/// No token of `text` is a non-finite number as Rust or JSON would print it.
fn assert_no_nan(what: &str, text: &str) {
    let bad = text
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '.'))
        .find(|t| matches!(t.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"));
    assert!(bad.is_none(), "{what} carries a non-finite number ({bad:?}):\n{text}");
}

/// `beltcheck gate --bvp-only` on the whole catalogue: every BVP variant within the
/// catalogue's limits.
#[test]
fn gate_passes_on_the_catalogue_for_the_bvp_methods() {
    let o = beltcheck(&["gate", "--bvp-only"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "BVP gate failed on the catalogue:\n{out}\n{}", stderr(&o));
    assert!(out.contains("passed: every gated quantity within its limit"), "{out}");
    assert!(!out.contains("fem "), "no FE run with --bvp-only:\n{out}");
}

/// `beltcheck gate` on the whole catalogue — every registered FE formulation included,
/// as `.ci/run` runs it — exits 0 with its pass table. (Its time is measured by the
/// gate's own table and the CI log, not asserted: a loaded machine is not a failure.)
#[test]
fn gate_passes_on_the_catalogue() {
    let o = beltcheck(&["gate"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "gate failed on the catalogue:\n{out}\n{}", stderr(&o));
    assert!(out.contains("passed: every gated quantity within its limit"), "{out}");
    for scene in ["string-hanging", "string-hanging-slack", "string-hanging-very-slack", "string-hanging-steel", "shell-runoff"] {
        assert!(out.contains(scene), "{scene} missing from the pass table:\n{out}");
    }
    assert_no_nan("gate output", &out);
}

/// A tolerance no method can meet: exit status 1 and a failure table naming the scene,
/// each method, the quantity, its error and the limit.
#[test]
fn gate_fails_on_an_impossible_tolerance() {
    let scene = scene_with_gate("impossible.json", serde_json::json!({"tolerances": {"tension_upper_mid": 1e-300, "y_upper_mid": 1e-3}}));
    let o = beltcheck(&["gate", scene.to_str().unwrap(), "--elements", "16,32,64"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(1), "{out}\n{}", stderr(&o));
    assert!(out.contains("FAILED"), "{out}");
    let failing: Vec<&str> = out.lines().filter(|l| l.contains("tension_upper_mid") && l.contains("exceeds")).collect();
    assert!(failing.iter().any(|l| l.contains("bvp-shooting")), "{out}");
    assert!(failing.iter().any(|l| l.contains("bvp-collocation gauss4")), "{out}");
    assert!(failing.iter().all(|l| l.contains("1.00e-300")), "the limit is shown: {out}");
    // y_upper_mid at 1e-3 holds for the BVP methods and is not listed as a failure.
    assert!(!out.lines().any(|l| l.contains("y_upper_mid") && l.contains("bvp-") && l.contains("exceeds")), "{out}");
    assert_no_nan("gate output", &out);
}

/// `gate.bvp_tolerances` holds the BVP methods to their own limit: a limit no BVP run
/// can meet (1e-300) fails gauss4 and shooting on that quantity, while the FE rows of
/// the same quantity are still judged by the shared `tolerances` limit (1e-3) and pass.
#[test]
fn bvp_tolerances_apply_to_the_bvp_methods_only() {
    // the gate (exit 1) on string-hanging with the gate block `gate`: its output and the
    // lines that report `quantity` above its limit
    let exceeding = |name: &str, gate: serde_json::Value, quantity: &str| -> (String, Vec<String>) {
        let scene = scene_with_gate(name, gate);
        let o = beltcheck(&["gate", scene.to_str().unwrap(), "--elements", "32,64"]);
        let out = stdout(&o);
        assert_eq!(o.status.code(), Some(1), "{out}\n{}", stderr(&o));
        let failing = out.lines().filter(|l| l.contains(quantity) && l.contains("exceeds")).map(String::from).collect();
        (out, failing)
    };
    let (out, failing) = exceeding("bvp-limits.json", serde_json::json!({"tolerances": {"y_upper_mid": 1e-3}, "bvp_tolerances": {"y_upper_mid": 1e-300}}), "y_upper_mid");
    assert!(failing.iter().any(|l| l.contains("bvp-shooting")), "{out}");
    assert!(failing.iter().any(|l| l.contains("bvp-collocation gauss4")), "{out}");
    assert!(!failing.iter().any(|l| l.contains("fem ")), "FE rows keep the shared limit: {out}");
    // A quantity named in `bvp_tolerances` only (one the FE may not produce, like the
    // Cosserat edge pressures) is gated for the BVP methods alone.
    let (out, failing) = exceeding("bvp-limits-only.json", serde_json::json!({"tolerances": {"y_upper_mid": 1e-3}, "bvp_tolerances": {"tension_upper_mid": 1e-300}}), "tension_upper_mid");
    assert!(failing.iter().any(|l| l.contains("bvp-shooting")) && failing.iter().any(|l| l.contains("bvp-collocation gauss4")), "{out}");
    assert!(!out.lines().any(|l| l.contains("tension_upper_mid") && l.contains("fem ")), "not gated for the FE: {out}");
    // An unknown quantity name in the block is a scene error naming the path.
    let bad = scene_with_gate("bvp-limits-typo.json", serde_json::json!({"tolerances": {"y_upper_mid": 1e-3}, "bvp_tolerances": {"y_uper_mid": 1e-6}}));
    let o = beltcheck(&["solve", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let text = stderr(&o);
    assert!(text.contains("gate.bvp_tolerances.y_uper_mid") && text.contains("y_upper_mid"), "{text}");
}

/// A gated quantity that cannot be computed (a string has no moment) is a failure, not
/// a pass; so is a scene that gates nothing.
#[test]
fn gate_fails_when_a_quantity_cannot_be_computed_or_nothing_is_gated() {
    let moment = scene_with_gate("moment.json", serde_json::json!({"tolerances": {"moment_max": 1.0}}));
    let o = beltcheck(&["gate", moment.to_str().unwrap(), "--elements", "16,32,64"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.lines().any(|l| l.contains("moment_max") && l.contains("not produced")), "{out}");
    assert!(out.contains('—'), "a missing number is shown as —: {out}");

    let none = scene_with_gate("ungated.json", serde_json::Value::Null);
    let o = beltcheck(&["gate", none.to_str().unwrap(), "--elements", "16,32,64"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("no tolerances"), "{out}");
}

/// A BVP view with its axial force (field and summary) scaled by `factor`: a method
/// whose answer has drifted by a known amount.
struct Scaled {
    inner: Box<dyn SolutionView + Send + Sync>,
    factor: f64,
}

impl SolutionView for Scaled {
    fn path(&self) -> drive::contour::Path {
        self.inner.path()
    }
    fn position(&self, sigma: f64) -> [f64; 2] {
        self.inner.position(sigma)
    }
    fn axial_force(&self, sigma: f64) -> f64 {
        self.factor * self.inner.axial_force(sigma)
    }
    fn bending_moment(&self, sigma: f64) -> Option<f64> {
        self.inner.bending_moment(sigma)
    }
    fn transverse_force(&self, sigma: f64) -> Option<f64> {
        self.inner.transverse_force(sigma)
    }
    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        self.inner.contact_pressure(sigma)
    }
    fn contact_state(&self, sigma: f64) -> ContactState {
        self.inner.contact_state(sigma)
    }
    fn material_coordinate(&self, sigma: f64) -> f64 {
        self.inner.material_coordinate(sigma)
    }
    fn summary(&self) -> Summary {
        self.inner.summary()
    }
}

/// Shooting with every axial force scaled by 1 + 1e-4.
fn perturbed_shooting() -> FnMethod {
    FnMethod::new("perturbed shooting", Family::Bvp, |scene, disc| {
        let factor = 1.0 + 1e-4;
        let mut s = BvpSolver::new(BvpVariant::Shooting).solve(scene, disc)?;
        for name in ["tension_upper_mid", "tension_lower_mid"] {
            let v = s.summary.get(name).map(|v| v * factor);
            s.summary.set(name, v).unwrap();
        }
        s.view = Box::new(Scaled { inner: s.view, factor });
        Ok(s)
    })
}

/// The gate catches a result that drifted by 1e-4 in its axial force, names exactly the
/// drifted quantities with their size (≈ 1e-4), and passes the honest method beside it.
#[test]
fn gate_fails_on_a_perturbed_result() {
    let scene = catalogue_scene("string-hanging");
    let plan = gate::gate_plan(&scene, 1e-8, Some(&[]));
    let methods: Vec<(Box<dyn Method>, Vec<Discretisation>)> = vec![
        (Box::new(BvpSolver::new(BvpVariant::Shooting)), vec![Discretisation::Tolerance(1e-8)]),
        (Box::new(perturbed_shooting()), vec![Discretisation::Tolerance(1e-8)]),
    ];
    let study = Study::run_methods(&scene, &plan, methods, false, &mut |_| {});
    // Limits 100× below the perturbation and far above the BVP error at 1e-8 (~1e-10).
    let names = ["y_upper_mid", "tension_upper_mid", "tension_lower_mid", "driver.contact_arc", "deflection_l2", "tension_max", "tension_l2"];
    let settings = GateSettings { tolerances: names.iter().map(|n| (n.to_string(), 1e-6)).collect(), min_order: None, ..GateSettings::default() };
    let outcome = gate::evaluate(&settings, &study);
    assert!(!outcome.passed());
    let failures: Vec<_> = outcome.failures().collect();
    assert!(failures.iter().all(|c| c.method == "perturbed shooting"), "{failures:#?}");
    let failed: Vec<&str> = failures.iter().map(|c| c.quantity.as_str()).collect();
    for q in ["tension_upper_mid", "tension_lower_mid", "tension_max", "tension_l2"] {
        assert!(failed.contains(&q), "{q} not caught: {failed:?}");
    }
    for q in ["y_upper_mid", "driver.contact_arc", "deflection_l2"] {
        assert!(!failed.contains(&q), "{q} was not perturbed: {failed:?}");
    }
    // The measured drift is the perturbation: relative 1e-4 (to the BVP accuracy).
    for c in &failures {
        let e = c.value.expect("a number");
        assert!((e - 1e-4).abs() < 1e-6, "{}: {e}", c.quantity);
    }
    let table = gate::failure_table(&[outcome]).to_text("");
    assert!(table.contains("perturbed shooting") && table.contains("1.00e-4"), "{table}");
}

/// Every registered FE formulation appears in a study, in `converge`'s output and in the
/// gate's checks by name, with no harness change; the JSON carries every run.
#[test]
fn formulations_are_discovered_and_converge_prints_rates() {
    let json = temp("converge.json");
    let o = beltcheck(&["converge", "scenes/string-hanging.json", "--tolerances", "1e-6,1e-8", "--elements", "32,64,128", "--json", json.to_str().unwrap()]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
    for m in ["bvp-collocation gauss4", "bvp-collocation gauss6", "bvp-shooting", "reference: BVP run bvp-collocation gauss6 at tol 1e-11"] {
        assert!(out.contains(m), "{m} missing:\n{out}");
    }
    let registered = fem::available_formulations();
    // every formulation is listed; those of the scene's theory (string) are studied, the
    // others (rod elements, docs/fem-rod.md §4) are listed as not applicable
    let applicable = fem::formulations_for(drive::scene::Theory::String);
    for f in &registered {
        assert!(out.contains(&format!("fem {f}")), "formulation {f} not studied:\n{out}");
        if applicable.contains(f) {
            assert!(out.contains(&format!("mutual convergence of fem {f}")), "{out}");
        } else {
            assert!(out.contains(&format!("fem {f} — not applicable")), "{out}");
        }
    }
    if registered.is_empty() {
        assert!(out.contains("no FE formulation registered"), "{out}");
    } else {
        assert!(out.contains("rate"), "FE rows carry rates:\n{out}");
    }
    assert_no_nan("converge output", &out);
    let text = std::fs::read_to_string(&json).unwrap();
    assert_no_nan("converge JSON", &text);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let series = v["series"].as_array().unwrap();
    assert_eq!(series.len(), 3 + registered.len());
    assert_eq!(v["reference"]["status"], "solved");
    assert!(series[0]["rows"][0]["errors"]["tension_l2"].as_f64().is_some());

    // The gate makes checks for each studied formulation, by name.
    let scene = catalogue_scene("string-hanging");
    let plan = gate::gate_plan(&scene, 1e-6, Some(&[16, 32, 64]));
    let study = Study::run(&scene, &plan, &mut |_| {}).unwrap();
    let outcome = gate::evaluate(&scene.gate_settings(), &study);
    for s in study.series.iter().filter(|s| s.family == Family::Fem) {
        if s.status == verification::study::SeriesStatus::Studied {
            assert!(outcome.checks.iter().any(|c| c.method == s.method), "{} not gated", s.method);
        }
    }
    assert_eq!(study.series.iter().filter(|s| s.family == Family::Fem).count(), registered.len());
}

/// The BVP-only study of a scene says so and makes no FE rows.
#[test]
fn a_study_without_fe_says_so() {
    let scene = catalogue_scene("string-hanging-steel");
    let plan = StudyPlan::convergence(&scene).with_tolerances(&[1e-6]).with_formulations(&[]);
    let study = Study::run(&scene, &plan, &mut |_| {}).unwrap();
    assert!(study.series.iter().all(|s| s.family == Family::Bvp));
    assert!(study.notes.iter().any(|n| n.contains("BVP-only")), "{:?}", study.notes);
    let text = verification::table::study_text(&study);
    assert!(text.contains("mutual convergence FE ↔ BVP: —"), "{text}");
    // Gate settings with a field norm on a BVP-only study: BVP rows checked, nothing FE.
    let settings = GateSettings { tolerances: [("tension_l2".to_string(), 1e-6)].into(), min_order: Some(2.0), ..GateSettings::default() };
    let outcome = gate::evaluate(&settings, &study);
    assert!(outcome.passed(), "{:#?}", outcome.checks);
    assert!(outcome.checks.iter().all(|c| c.measure == gate::Measure::Error));
}

/// `report` writes per scene a Markdown page, four SVGs and a JSON, and an index that
/// keeps the rows of earlier reports in the same directory.
#[test]
fn report_writes_markdown_svg_json_and_an_index() {
    let dir = temp("reports");
    let _ = std::fs::remove_dir_all(&dir);
    let o = beltcheck(&["report", "scenes/string-hanging-steel.json", "-o", dir.to_str().unwrap(), "--tolerances", "1e-6,1e-8", "--elements", "32,64,128"]);
    assert_eq!(o.status.code(), Some(0), "{}\n{}", stdout(&o), stderr(&o));
    let sdir = dir.join("string-hanging-steel");
    for f in ["shape.svg", "force.svg", "convergence.svg", "work-precision.svg"] {
        let svg = std::fs::read_to_string(sdir.join(f)).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{f}");
        assert_no_nan(f, &svg);
    }
    let md = std::fs::read_to_string(sdir.join("report.md")).unwrap();
    for needle in ["## Effects simulated", "gravity, frictionless contact", "not simulated: transport inertia", "![belt shape](shape.svg)", "![work–precision](work-precision.svg)", "## Scene and options used", "\"axial_stiffness\""] {
        assert!(md.contains(needle), "report lacks {needle:?}:\n{md}");
    }
    assert_no_nan("report.md", &md);
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(sdir.join("study.json")).unwrap()).unwrap();
    assert_eq!(v["scene"]["name"], "string-hanging-steel");
    assert!(v["reference_fields"]["tension"].as_array().unwrap().len() >= 256);
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(index.contains("[string-hanging-steel](string-hanging-steel/report.md)"), "{index}");
    // A second report into the same directory adds its row and keeps the first.
    let o = beltcheck(&["report", "scenes/string-hanging.json", "-o", dir.to_str().unwrap(), "--tolerances", "1e-6", "--elements", "32,64"]);
    assert_eq!(o.status.code(), Some(0), "{}\n{}", stdout(&o), stderr(&o));
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    for scene in ["string-hanging-steel", "string-hanging"] {
        assert!(index.contains(&format!("[{scene}]({scene}/report.md)")), "{scene} missing:\n{index}");
    }
    let rows: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("index.json")).unwrap()).unwrap();
    assert_eq!(rows.as_array().unwrap().len(), 2);
}
