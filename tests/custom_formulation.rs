//! Element formulations from outside `fem` (issue 11 item 5; README "A new element
//! formulation"): a formulation defined in this test crate, registered through
//! `fem::register_formulation`, is studied and gated by the harness exactly like a
//! built-in one.
//!
//! What is proved here:
//! - a study of `string-hanging` that discovers formulations includes the outside one,
//!   and its error against the BVP reference decreases with every refinement at an
//!   observed order above 1 (the Hermite string converges at about 2–3);
//! - the gate checks it by name and it passes the scene's limits;
//! - a formulation registered for another theory (Kirchhoff) is "not applicable" on a
//!   string scene, with the reason, not a failure;
//! - a second registration of a name, a built-in name, an empty or malformed name and a
//!   rule that does not exist are typed [`RegistryError`]s, and refused entries leave
//!   the registry unchanged.
//!
//! The registry is process-wide and the tests of this file run in parallel: every test
//! calls [`register_once`], which registers the two formulations exactly once.
//! Run in release mode (`cargo test --release --test custom_formulation`; about 3 s).

use std::sync::Once;

use drive::scene::{Scene, Theory};
use fem::formulation::{biot_density, Formulation, Rule, Scalar, TermRules};
use fem::RegistryError;
use verification::gate;
use verification::study::{SeriesStatus, Study, StudyPlan};

/// A formulation given by value: name, theory and rules, Biot strain. Not a copy of a
/// built-in one: the contact is integrated by 4-point Gauss, strain and gravity by
/// Simpson (the string variant), or every term by Gauss 5 (the rod variant).
struct Custom {
    name: &'static str,
    theory: Theory,
    rules: TermRules,
}

impl Formulation for Custom {
    fn name(&self) -> &'static str {
        self.name
    }

    fn description(&self) -> &'static str {
        "test formulation defined outside fem"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn theory(&self) -> Theory {
        self.theory
    }

    fn rules(&self) -> TermRules {
        self.rules
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}

const STRING_NAME: &str = "outside-string";
const ROD_NAME: &str = "outside-rod";

fn string_formulation() -> Custom {
    Custom { name: STRING_NAME, theory: Theory::String, rules: TermRules { strain: Rule::Simpson, gravity: Rule::Simpson, contact: Rule::Gauss(4), bending: Rule::Gauss(3) } }
}

fn rod_formulation() -> Custom {
    let g5 = Rule::Gauss(5);
    Custom { name: ROD_NAME, theory: Theory::Kirchhoff, rules: TermRules { strain: g5, gravity: g5, contact: g5, bending: g5 } }
}

static REGISTER: Once = Once::new();

fn register_once() {
    REGISTER.call_once(|| {
        fem::register_formulation(string_formulation()).expect("first registration of the string formulation");
        fem::register_formulation(rod_formulation()).expect("first registration of the rod formulation");
    });
}

fn scene() -> Scene {
    Scene::from_path(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/string-hanging.json"))).unwrap()
}

#[test]
fn registered_formulations_are_listed_by_theory() {
    register_once();
    let all = fem::available_formulations();
    // built-in ones first (the default stays the default), the outside ones after
    assert_eq!(all[0], fem::default_formulation());
    assert!(all.ends_with(&[STRING_NAME, ROD_NAME]), "{all:?}");
    assert!(fem::formulations_for(Theory::String).contains(&STRING_NAME));
    assert!(!fem::formulations_for(Theory::String).contains(&ROD_NAME));
    assert!(fem::formulations_for(Theory::Kirchhoff).contains(&ROD_NAME));
    assert_eq!(verification::run::formulation_theory(ROD_NAME), Some(Theory::Kirchhoff));
    assert_eq!(fem::formulation::find(STRING_NAME).unwrap().rules().contact, Rule::Gauss(4));
}

/// A discovered study runs the outside formulations: the string one converges to the
/// BVP reference, the rod one is not applicable; the gate checks the string one.
#[test]
fn a_study_and_the_gate_see_the_outside_formulation() {
    register_once();
    let scene = scene();
    let mut plan = StudyPlan::convergence(&scene).with_meshes(&[32, 64, 128]);
    plan.bvp.clear(); // only the reference: the BVP sweeps are not under test
    plan.validate().unwrap();
    let study = Study::run(&scene, &plan, &mut |_| {}).unwrap();
    study.usable().unwrap();

    let label = format!("fem {STRING_NAME}");
    let series = study.series.iter().find(|s| s.method == label).unwrap_or_else(|| panic!("{label} not studied"));
    assert_eq!(series.status, SeriesStatus::Studied);
    let errors: Vec<f64> = series.rows.iter().map(|r| r.scalar_error.expect("every mesh solved")).collect();
    assert_eq!(errors.len(), 3);
    // the max summary-scalar error falls with each refinement; at 128 elements the
    // built-in Simpson string is at 3e-6 (docs/fem-string.md §12), so 1e-4 is a loose
    // bound that still rejects a formulation converging to another answer
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "errors {errors:?}");
    assert!(errors[2] < 1e-4, "finest error {}", errors[2]);
    for row in &series.rows[1..] {
        let p = row.scalar_order.expect("order between successive meshes");
        assert!(p > 1.0, "observed order {p} at {}", row.run.discretisation);
    }
    // its own numbers: not a relabelled built-in run
    let simpson = study.series.iter().find(|s| s.method == "fem string-simpson").unwrap();
    let builtin = simpson.rows[0].scalar_error.unwrap();
    assert!((builtin - errors[0]).abs() > 1e-3 * builtin, "{builtin} vs {}", errors[0]);

    let rod = study.series.iter().find(|s| s.method == format!("fem {ROD_NAME}")).expect("the rod formulation is listed");
    match &rod.status {
        SeriesStatus::NotApplicable(why) => assert!(why.contains("kirchhoff") && why.contains(ROD_NAME), "{why}"),
        other => panic!("rod formulation on a string scene: {other:?}"),
    }

    let outcome = gate::evaluate(&scene.gate_settings(), &study);
    let own: Vec<_> = outcome.checks.iter().filter(|c| c.method == label).collect();
    assert!(!own.is_empty(), "the gate did not check {label}");
    assert!(own.iter().all(|c| c.pass), "{}", gate::failure_table(std::slice::from_ref(&outcome)).to_text(""));
    assert!(!outcome.checks.iter().any(|c| c.method == format!("fem {ROD_NAME}") && !c.pass));
}

#[test]
fn refused_registrations_are_typed_errors() {
    register_once();
    let before = fem::available_formulations();
    match fem::register_formulation(string_formulation()) {
        Err(RegistryError::Duplicate { name, registered }) => {
            assert_eq!(name, STRING_NAME);
            assert!(registered.contains(&STRING_NAME));
        }
        other => panic!("duplicate: {other:?}"),
    }
    // a built-in name cannot be shadowed
    let shadow = Custom { name: "string-simpson", ..string_formulation() };
    assert!(matches!(fem::register_formulation(shadow), Err(RegistryError::Duplicate { name: "string-simpson", .. })));
    let empty = Custom { name: "", ..string_formulation() };
    assert!(matches!(fem::register_formulation(empty), Err(RegistryError::EmptyName { .. })));
    let spaced = Custom { name: "My Element", ..string_formulation() };
    assert_eq!(fem::register_formulation(spaced), Err(RegistryError::InvalidName { name: "My Element", offending: 'M' }));
    let bad_rule = Custom { name: "outside-gauss9", rules: TermRules { contact: Rule::Gauss(9), ..string_formulation().rules }, ..string_formulation() };
    match fem::register_formulation(bad_rule) {
        Err(e @ RegistryError::InvalidRule { term: "contact", .. }) => assert!(e.to_string().contains("gauss9"), "{e}"),
        other => panic!("invalid rule: {other:?}"),
    }
    assert_eq!(fem::available_formulations(), before, "a refused registration changed the registry");
    assert!(fem::formulation::find("outside-gauss9").is_none());
}
