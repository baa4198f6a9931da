//! An element formulation defined outside `fem`, registered through the library API and
//! verified with the same harness as the built-in ones (README "A new element
//! formulation"):
//!
//! 1. `StringSimpsonGauss4` (`string-simpson-g4`) — an extensible string (Biot strain)
//!    with the strain and gravity energies by the Simpson rule (as `string-simpson`: it
//!    samples the strain where the Hermite element reproduces it best, free of membrane
//!    locking) but the penalty contact by the 4-point Gauss rule: the contact density
//!    ½P⟨−γ⟩² has a kink where the belt leaves a pulley, which more points resolve. A
//!    different discretisation of the same model (its errors differ from
//!    `string-simpson`'s), so it must converge to the BVP reference. Three tries the
//!    harness rejected, as it should: a 2-point Gauss membrane rule leaves a zero-energy
//!    mode (Newton fails at the tight start: no successful run); 4-point Gauss for every
//!    term locks in the axial force like `string-gauss` (the gate fails its
//!    `tension_max` order on `string-hanging-steel`); the gravity by a rule other than
//!    the strain's stalls `tension_lower_mid` near 1e-6 (order below 1 in the gate).
//! 2. `fem::register_formulation(StringSimpsonGauss4)` adds it to the process-wide registry.
//! 3. A `converge` study of `scenes/string-hanging.json` (every registered formulation,
//!    the new one included — discovered, not named) prints the convergence table and
//!    the observed orders of the new formulation.
//! 4. The `gate` over the catalogue `scenes/` (the same plans and limits as
//!    `beltcheck gate`) prints the checks of the new formulation and the verdict.
//!
//! Run: `cargo run --release --example custom_formulation` (from the workspace root).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use drive::scene::Scene;
use fem::formulation::{biot_density, Formulation, Rule, Scalar, TermRules};
use verification::gate;
use verification::study::{SeriesStatus, Study, StudyPlan};

/// Extensible string, Biot strain, strain and gravity energies by Simpson, penalty
/// contact by the 4-point Gauss rule.
struct StringSimpsonGauss4;

impl Formulation for StringSimpsonGauss4 {
    fn name(&self) -> &'static str {
        "string-simpson-g4"
    }

    fn description(&self) -> &'static str {
        "extensible string, Biot strain, Hermite cubics, Simpson rule for strain and gravity, 4-point Gauss for penalty contact; defined outside fem"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn rules(&self) -> TermRules {
        TermRules { strain: Rule::Simpson, gravity: Rule::Simpson, contact: Rule::Gauss(4), bending: Rule::Gauss(3) }
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}

fn load(path: &Path) -> Result<Scene> {
    Scene::from_path(path).with_context(|| format!("reading scene {}", path.display()))
}

fn main() -> Result<()> {
    fem::register_formulation(StringSimpsonGauss4)?;
    let name = StringSimpsonGauss4.name();
    let label = format!("fem {name}");
    println!("registered formulations: {}", fem::available_formulations().join(", "));

    // converge: the study `beltcheck converge scenes/string-hanging.json` runs
    let scene = load(Path::new("scenes/string-hanging.json"))?;
    let plan = StudyPlan::convergence(&scene);
    plan.validate()?;
    let study = Study::run(&scene, &plan, &mut |_| {})?;
    print!("{}", verification::table::study_text(&study));
    study.usable()?;
    let series = study.series.iter().find(|s| s.method == label).context("the study did not run the registered formulation")?;
    if let SeriesStatus::NotApplicable(why) = &series.status {
        bail!("{label} not applicable: {why}");
    }
    println!("\nobserved order of the max summary-scalar error, {label}:");
    for row in &series.rows {
        let err = row.scalar_error.map_or("—".to_string(), |e| format!("{e:.3e}"));
        let order = row.scalar_order.map_or("—".to_string(), |p| format!("{p:.2}"));
        println!("  {:>12}  error {err}  order {order}", row.run.discretisation.to_string());
    }

    // gate: the plans and limits of `beltcheck gate` over the catalogue
    let mut files: Vec<PathBuf> = std::fs::read_dir("scenes")?.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|x| x == "json")).collect();
    files.sort();
    let mut outcomes = Vec::new();
    for file in &files {
        let scene = load(file)?;
        let plan = gate::gate_plan(&scene, gate::GATE_BVP_TOLERANCE, None);
        plan.validate().with_context(|| format!("scene {}", file.display()))?;
        let study = Study::run(&scene, &plan, &mut |_| {})?;
        outcomes.push(gate::evaluate(&scene.gate_settings(), &study));
    }
    println!("\ngate over {} scene(s):", outcomes.len());
    print!("{}", gate::summary_table(&outcomes).to_text("  "));
    for o in &outcomes {
        let own: Vec<_> = o.checks.iter().filter(|c| c.method == label).collect();
        if own.is_empty() {
            let why = o.notes.iter().find(|n| n.contains(name)).map_or("not in the scene's formulations", String::as_str);
            println!("  {}: {label} not gated ({why})", o.scene);
        } else {
            let failed = own.iter().filter(|c| !c.pass).count();
            println!("  {}: {label}: {} checks, {failed} failed", o.scene, own.len());
        }
    }
    let passed = outcomes.iter().all(gate::GateOutcome::passed);
    if passed {
        println!("\ngate passed: every gated quantity within its limit, {label} included");
        Ok(())
    } else {
        print!("{}", gate::failure_table(&outcomes).to_text("  "));
        bail!("gate FAILED")
    }
}
