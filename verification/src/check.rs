//! `beltcheck check` and `beltcheck reference`: beltcheck as the referee of outside
//! codes (docs/check-your-code.md).
//!
//! [`check`] reads the result files ([`crate::outside`]), groups them by method, computes
//! the scene's reference (the gate's BVP run; the closed form on request; where no BVP
//! solves the scene, Richardson extrapolation of the supplied runs), builds one
//! [`Study`] in which each outside code is a method like a built-in formulation
//! ([`Study::of_runs`]: errors, field norms, observed orders, Richardson values, mutual
//! convergence, cost) and applies the scene's `gate` limits ([`crate::gate::evaluate`]).
//! A check with no comparable run fails.

use std::path::PathBuf;

use bvp::collocation::Scheme;
use drive::scene::Scene;
use serde::Serialize;

use crate::gate::{self, Check, GateOutcome, Measure};
use crate::measure::Quantity;
use crate::outside::{self, OutsideError, OutsideMethod, Skip};
use crate::reference::{Reference, ReferenceRun};
use crate::run::{BvpSolver, BvpVariant, Discretisation, Method, RunError, Solved};
use crate::study::{Formulations, Study, DEFAULT_SAMPLES};
use crate::table::{Table, NONE};

/// What the outside runs are held against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceChoice {
    /// The gate's BVP run; where no BVP solves the scene, Richardson extrapolation of
    /// the supplied runs (the first method with three or more).
    #[default]
    Auto,
    /// The gate's BVP run (collocation gauss6 at [`gate::GATE_REFERENCE_TOLERANCE`]).
    Bvp,
    /// The closed form of the scene's model (summary scalars only).
    ClosedForm,
    /// Richardson extrapolation of the supplied runs.
    Supplied,
}

/// The verdict of a check, with everything it measured.
#[derive(Debug, Clone, Serialize)]
pub struct Checked {
    /// The study: the reference and one series per outside method.
    pub study: Study,
    /// The gate checks of the scene's limits.
    pub gate: GateOutcome,
    /// Files set aside, with why.
    pub skipped: Vec<Skip>,
}

impl Checked {
    /// True if every check passed (and there was at least one).
    pub fn passed(&self) -> bool {
        self.gate.passed()
    }
}

/// Reads `inputs` (result files or directories of them; a directory's files that are
/// one of `exclude` — the check's own output files — are passed over) and checks them
/// against `scene` (module docs). `samples` σ points carry the field norms.
///
/// # Errors
/// The first unreadable or malformed file (nothing is computed then).
pub fn check(scene: &Scene, inputs: &[PathBuf], exclude: &[PathBuf], choice: ReferenceChoice, samples: usize) -> Result<Checked, OutsideError> {
    let files = outside::result_files(inputs, exclude)?;
    let runs = files.iter().map(|f| outside::read_result(f, scene)).collect::<Result<Vec<_>, _>>()?;
    let (methods, mut skipped) = outside::group(scene, runs)?;
    let mut plan = gate::gate_plan_with(scene, None, None, Some(Formulations::Named(Vec::new())));
    plan.bvp.clear();
    plan.samples = samples;
    let mut meshes: Vec<usize> = methods.iter().flat_map(|m| m.runs.iter().filter_map(|r| r.discretisation.elements_along())).collect();
    meshes.sort_unstable();
    meshes.dedup();
    plan.meshes = meshes;

    let computed = reference_of(scene, &mut plan, choice, &methods);
    let quantities = computed.run.data().map(Quantity::of_reference).unwrap_or_default();
    let methods = if computed.run.data().is_some() { outside::drop_incomparable(methods, &quantities, &mut skipped) } else { methods };
    let supplied = methods.iter().map(|m| (m.label(), m.family(), m.harness_runs(scene, samples))).collect();
    let study = Study::of_runs(scene, &plan, computed, supplied);
    let mut outcome = gate::evaluate(&scene.gate_settings(), &study);
    if methods.is_empty() {
        outcome.checks.push(Check {
            method: NONE.into(),
            discretisation: None,
            quantity: "(outside runs)".into(),
            measure: Measure::Setup,
            value: None,
            limit: None,
            pass: false,
            reason: format!("zero comparable runs ({} file(s) read, {} skipped): a check that compares nothing cannot pass", files.len(), skipped.len()),
        });
    }
    for s in &skipped {
        outcome.notes.push(format!("skipped {}: {}", s.file.display(), s.reason));
    }
    Ok(Checked { study, gate: outcome, skipped })
}

/// The reference of a check (sets `plan.reference` to what was used).
fn reference_of(scene: &Scene, plan: &mut crate::study::StudyPlan, choice: ReferenceChoice, methods: &[OutsideMethod]) -> ReferenceRun {
    let supplied = |plan: &mut crate::study::StudyPlan| {
        let m = methods.iter().find(|m| m.runs.len() >= 3).or(methods.first());
        let runs = m.map(|m| m.harness_runs(scene, plan.samples)).unwrap_or_default();
        let (reference, computed) = Reference::of_supplied(&m.map_or_else(|| NONE.to_string(), |m| m.label()), &runs);
        plan.reference = reference;
        computed
    };
    match choice {
        ReferenceChoice::Supplied => supplied(plan),
        ReferenceChoice::ClosedForm => {
            plan.reference = Reference::ClosedForm;
            plan.reference.compute(scene, plan.samples, plan.max_nodes)
        }
        ReferenceChoice::Bvp | ReferenceChoice::Auto => {
            let computed = plan.reference.compute(scene, plan.samples, plan.max_nodes);
            let no_bvp = matches!(computed.run.outcome, Err(RunError::NotApplicable(_) | RunError::NotYetSolvable(_)));
            if choice == ReferenceChoice::Auto && no_bvp {
                let mut fallback = supplied(plan);
                if let Err(e) = &computed.run.outcome {
                    fallback.notes.push(format!("no BVP reference for this scene ({e}): the reference is Richardson extrapolation of the supplied runs"));
                }
                fallback
            } else {
                computed
            }
        }
    }
}

/// The skipped files as a table: file, method, at, why.
pub fn skip_table(skipped: &[Skip]) -> Table {
    let mut t = Table::new(["file", "method", "at", "skipped because"]);
    t.left = vec![0, 1, 3];
    for s in skipped {
        t.push(vec![s.file.display().to_string(), s.method.clone(), s.discretisation.map_or(NONE.into(), crate::table::fmt_disc), s.reason.to_string()]);
    }
    t
}

/// The reference solution of `beltcheck reference`: the BVP run of the gate's
/// reference (collocation gauss6) at `tolerance`, with its view to sample anywhere.
///
/// # Errors
/// The BVP's failure, or [`RunError::NotApplicable`] / [`RunError::NotYetSolvable`]
/// for a scene no BVP solves.
pub fn reference_solution(scene: &Scene, tolerance: f64) -> Result<(String, Solved), RunError> {
    let solver = BvpSolver { variant: BvpVariant::Collocation(Scheme::Gauss6), max_nodes: Some(crate::study::STUDY_MAX_NODES) };
    let solved = crate::run::solve_timed(&solver, scene, Discretisation::Tolerance(tolerance))?;
    Ok((solver.label(), solved))
}

/// Default σ samples of a check's field norms (those of the studies).
pub const CHECK_SAMPLES: usize = DEFAULT_SAMPLES;
