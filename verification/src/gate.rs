//! The CI gate: CI-sized studies of the catalogue, checked against each scene's `gate`
//! block ([`drive::scene::GateSettings`]).
//!
//! For each scene, [`gate_plan`] runs the reference (collocation gauss6 at
//! [`GATE_REFERENCE_TOLERANCE`] or the scene's `gate.reference_tolerance`), each other
//! BVP variant at one tolerance (`--tolerance`, else the scene's `gate.bvp_tolerance`,
//! else [`GATE_BVP_TOLERANCE`]), and every FE
//! formulation — discovered from the `fem` registry, so a newly registered
//! formulation is gated with no change here — over the scene's mesh sequence. Then
//! [`evaluate`] checks, for every studied method at its finest discretisation:
//! - every quantity of `gate.tolerances`: relative error (as defined in
//!   [`crate::measure`]) ≤ its limit — for the BVP methods the limit of
//!   `gate.bvp_tolerances` where that names the quantity, and every quantity named there
//!   only (one the FE does not produce);
//! - FE methods only, with `gate.min_order`: the observed order of every gated quantity
//!   at the last refinement ≥ `min_order`, unless both errors are below
//!   [`ORDER_FLOOR`] × its limit (at the error floor the order is noise).
//!
//! A check whose number cannot be computed (the reference failed, the run failed, the
//! quantity is absent, the order is undefined) fails: the gate never passes on a
//! missing number. A scene without gate tolerances fails too (it would check nothing).

use std::fmt;

use bvp::collocation::Scheme;
use drive::scene::{GateSettings, Scene};
use serde::Serialize;

use crate::run::{BvpVariant, Discretisation, Family};
use crate::study::{BvpSweep, Formulations, SeriesStatus, Study, StudyPlan, DEFAULT_SAMPLES, STUDY_MAX_NODES};
use crate::table::{fmt_disc, fmt_error, fmt_order, fmt_seconds, Table, NONE};

/// Reference tolerance of the gate (one decade looser than `converge`, for CI time),
/// unless the scene's `gate.reference_tolerance` sets its own.
pub const GATE_REFERENCE_TOLERANCE: f64 = 1e-10;

/// Order checks are skipped where the errors at both of the two finest meshes are below
/// `ORDER_FLOOR` × the quantity's limit: the quantity is then a thousand times inside its
/// limit, its error is at the level of the reference's and the contact penalty's own
/// errors, and its observed order is noise (the steel scene's heights: errors 5e-9
/// against a limit of 1e-3).
pub const ORDER_FLOOR: f64 = 1e-3;

/// Default tolerance of the gated BVP runs (gauss4 and shooting).
pub const GATE_BVP_TOLERANCE: f64 = 1e-8;

/// The CI-sized study of a scene: reference gauss6 at the scene's
/// `gate.reference_tolerance` (default [`GATE_REFERENCE_TOLERANCE`]); gauss4 and shooting
/// at `bvp_tolerance`; FE: the scene's `fem.formulations` (else every registered one)
/// over `meshes` (else the scene's `fem.meshes()`). The collocation mesh cap is
/// [`STUDY_MAX_NODES`].
pub fn gate_plan(scene: &Scene, bvp_tolerance: f64, meshes: Option<&[usize]>) -> StudyPlan {
    gate_plan_with(scene, Some(bvp_tolerance), meshes, None)
}

/// [`gate_plan`] with the FE formulations overridden (`Some(Named(vec![]))` = BVP only)
/// and the tolerance of the gauss4 and shooting runs `bvp_tolerance`, else the scene's
/// `gate.bvp_tolerance`, else [`GATE_BVP_TOLERANCE`].
pub fn gate_plan_with(scene: &Scene, bvp_tolerance: Option<f64>, meshes: Option<&[usize]>, formulations: Option<Formulations>) -> StudyPlan {
    if scene.belt.theory == drive::scene::Theory::Shell {
        return shell_gate_plan(scene);
    }
    let fem = scene.fem_settings();
    let gate = scene.gate_settings();
    let bvp_tolerance = bvp_tolerance.or(gate.bvp_tolerance).unwrap_or(GATE_BVP_TOLERANCE);
    let reference_tolerance = gate.reference_tolerance.unwrap_or(GATE_REFERENCE_TOLERANCE);
    let discovered = if fem.formulations.is_empty() { Formulations::Discovered } else { Formulations::Named(fem.formulations.clone()) };
    StudyPlan {
        reference: crate::reference::Reference::Bvp { variant: BvpVariant::Collocation(Scheme::Gauss6), tolerance: reference_tolerance },
        bvp: vec![
            BvpSweep { variant: BvpVariant::Collocation(Scheme::Gauss4), tolerances: vec![bvp_tolerance] },
            BvpSweep { variant: BvpVariant::Shooting, tolerances: vec![bvp_tolerance] },
        ],
        formulations: formulations.unwrap_or(discovered),
        meshes: meshes.map_or_else(|| fem.meshes(), <[usize]>::to_vec),
        samples: DEFAULT_SAMPLES,
        max_nodes: Some(STUDY_MAX_NODES),
        compensate: false,
    }
    .without_unsolvable_fem(scene)
    .without_fem_unless(gate.fem.unwrap_or(true))
}

/// The scene a gate studies: a shell scene with `gate.steps` runs that many rotation
/// steps at its own Δt (a CI-sized part of its `fem.steps`); every other scene as it is.
pub fn gate_scene(scene: &Scene) -> Scene {
    let mut scene = scene.clone();
    if let (drive::scene::Theory::Shell, Some(steps)) = (scene.belt.theory, scene.gate_settings().steps) {
        let mut f = scene.fem_settings();
        (f.steps, f.duration) = (Some(steps), None);
        scene.fem = Some(f);
    }
    scene
}

/// The gate's study of a shell scene ([`StudyPlan::shell`]): `gate.levels`, else the
/// scene's mesh and 2× and 4× its n_σ at its n_ζ, each with Δt scaled like the σ
/// spacing. Run it on [`gate_scene`].
pub fn shell_gate_plan(scene: &Scene) -> StudyPlan {
    // the run a solve makes (n_ζ defaulted by the edge layer)
    let own = crate::run::ShellFe::run_of(scene);
    let sizes: Vec<[usize; 2]> = scene.gate_settings().levels.unwrap_or_else(|| (0..3).map(|k| [own.elements_sigma << k, own.elements_zeta]).collect());
    StudyPlan::shell(sizes.into_iter().map(|[ns, nz]| crate::run::ShellFe::level(scene, ns, nz)).collect())
}

/// What a check compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Measure {
    /// Relative error against the reference ≤ limit.
    Error,
    /// Observed order ≥ limit.
    Order,
    /// A precondition (gate block present, reference computed).
    Setup,
}

impl fmt::Display for Measure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Measure::Error => "rel. error",
            Measure::Order => "order",
            Measure::Setup => "setup",
        })
    }
}

/// One gated number.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// Method label (`reference` for the reference, `—` for the scene).
    pub method: String,
    /// Discretisation of the checked run.
    pub discretisation: Option<Discretisation>,
    /// Quantity name.
    pub quantity: String,
    /// Error or order.
    pub measure: Measure,
    /// The measured number; `None` = not computable (a failure).
    pub value: Option<f64>,
    /// The limit from the gate block.
    pub limit: Option<f64>,
    /// Verdict.
    pub pass: bool,
    /// Why it failed (empty when it passed).
    pub reason: String,
}

impl Check {
    /// How far past its limit a failing number is: error/limit, or limit/order.
    pub fn excess(&self) -> Option<f64> {
        let (v, l) = (self.value?, self.limit?);
        match self.measure {
            Measure::Error => (l > 0.0).then(|| v / l),
            Measure::Order => (v > 0.0).then(|| l / v),
            Measure::Setup => None,
        }
    }
}

/// The gate verdict of one scene.
#[derive(Debug, Clone, Serialize)]
pub struct GateOutcome {
    /// Scene name.
    pub scene: String,
    /// Every check made.
    pub checks: Vec<Check>,
    /// Statements (methods not applicable, FE registry empty, …).
    pub notes: Vec<String>,
    /// Wall time of the scene's study, s.
    pub wall_seconds: f64,
}

impl GateOutcome {
    /// True if every check passed (and there was at least one).
    pub fn passed(&self) -> bool {
        !self.checks.is_empty() && self.checks.iter().all(|c| c.pass)
    }

    /// The failing checks.
    pub fn failures(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| !c.pass)
    }

    /// The passing error check closest to its limit.
    pub fn tightest(&self) -> Option<&Check> {
        self.checks
            .iter()
            .filter(|c| c.pass && c.measure == Measure::Error)
            .max_by(|a, b| a.excess().unwrap_or(0.0).total_cmp(&b.excess().unwrap_or(0.0)))
    }
}

/// A scene that could not even be studied (unreadable, invalid plan): one failing
/// check carrying the reason.
pub fn failed_outcome(scene: &str, reason: String) -> GateOutcome {
    GateOutcome {
        scene: scene.to_string(),
        checks: vec![Check {
            method: NONE.into(),
            discretisation: None,
            quantity: "(scene)".into(),
            measure: Measure::Setup,
            value: None,
            limit: None,
            pass: false,
            reason,
        }],
        notes: Vec::new(),
        wall_seconds: 0.0,
    }
}

/// Checks `study` against `settings` (module docs).
pub fn evaluate(settings: &GateSettings, study: &Study) -> GateOutcome {
    let mut checks = Vec::new();
    let mut notes = study.notes.clone();
    if settings.fem == Some(false) {
        notes.push("FE not gated: the scene's gate block sets `fem` to false (`converge` and `report` still study the FE)".into());
    }
    let setup_fail = |quantity: &str, reason: String| Check {
        method: NONE.into(),
        discretisation: None,
        quantity: quantity.into(),
        measure: Measure::Setup,
        value: None,
        limit: None,
        pass: false,
        reason,
    };
    if settings.tolerances.is_empty() {
        checks.push(setup_fail("(gate block)", "the scene's gate block has no tolerances: nothing would be checked".into()));
    }
    if let Err(e) = &study.reference.outcome {
        checks.push(Check {
            method: "reference".into(),
            discretisation: Some(study.reference.discretisation),
            ..setup_fail("(reference)", format!("reference failed: {e}"))
        });
    }
    // a family the plan asked for with no studied method would pass on zero runs
    let asked_fem = !study.plan.fem_methods().is_empty() && !study.plan.meshes.is_empty();
    for (family, asked, what) in [(Family::Bvp, !study.plan.bvp.is_empty(), "BVP"), (Family::Fem, asked_fem, "FE")] {
        let studied = study.series.iter().filter(|s| s.family == family && s.status == SeriesStatus::Studied).count();
        if asked && studied == 0 {
            checks.push(setup_fail(
                &format!("({what} runs)"),
                format!("zero comparable {what} runs: no {what} method the gate asked for applies to this scene (see the notes); a gate that compares nothing cannot pass"),
            ));
        }
    }
    for s in &study.series {
        if let SeriesStatus::NotApplicable(why) = &s.status {
            notes.push(format!("{}: not applicable ({why}), not gated", s.method));
            continue;
        }
        let Some(row) = s.finest() else { continue };
        let n_gated = settings.tolerances.len();
        let whole_run = |reason: String, measure: Measure| Check {
            method: s.method.clone(),
            discretisation: Some(row.run.discretisation),
            quantity: format!("(all {n_gated} gated)"),
            measure,
            value: None,
            limit: None,
            pass: false,
            reason,
        };
        // One failing check covers a run without a solution or without a reference.
        if let Err(e) = &row.run.outcome {
            checks.push(whole_run(format!("run failed: {e}"), Measure::Error));
            continue;
        }
        if study.reference.data().is_none() {
            continue;
        }
        // The BVP methods may be held to their own, tighter, limit, and to quantities
        // only they produce (listed in `bvp_tolerances` alone: the Cosserat edge
        // pressures, which the FE does not write).
        let gated: Vec<(&String, f64)> = match s.family {
            Family::Bvp => {
                let mut all: Vec<(&String, f64)> = settings.tolerances.iter().map(|(n, &l)| (n, settings.bvp_tolerances.get(n).copied().unwrap_or(l))).collect();
                all.extend(settings.bvp_tolerances.iter().filter(|(n, _)| !settings.tolerances.contains_key(*n)).map(|(n, &l)| (n, l)));
                all
            }
            Family::Fem | Family::ClosedForm => settings.tolerances.iter().map(|(n, &l)| (n, l)).collect(),
        };
        for (name, limit) in gated {
            let (value, reason) = match study.quantity_index(name) {
                None => (None, "not produced by the reference for this scene".to_string()),
                Some(k) => match row.errors[k] {
                    Some(e) => (Some(e), String::new()),
                    None => (None, "not computable (absent from this method's result, or reference value 0)".into()),
                },
            };
            let pass = value.is_some_and(|e| e <= limit);
            let reason = if pass {
                String::new()
            } else if reason.is_empty() {
                format!("error {} exceeds {}", fmt_error(value), fmt_error(Some(limit)))
            } else {
                reason
            };
            checks.push(Check {
                method: s.method.clone(),
                discretisation: Some(row.run.discretisation),
                quantity: name.clone(),
                measure: Measure::Error,
                value,
                limit: Some(limit),
                pass,
                reason,
            });
        }
        if let (Family::Fem, Some(min)) = (s.family, settings.min_order) {
            let previous = s.rows.len().checked_sub(2).map(|i| &s.rows[i]);
            match previous {
                None => {
                    checks.push(Check { limit: Some(min), ..whole_run("order not computable: the mesh sequence has a single mesh".into(), Measure::Order) });
                    continue;
                }
                Some(p) if p.run.data().is_none() => {
                    checks.push(Check {
                        limit: Some(min),
                        ..whole_run(format!("order not computable: the previous mesh ({}) failed", p.run.discretisation), Measure::Order)
                    });
                    continue;
                }
                Some(_) => {}
            }
            let previous = previous.expect("checked above");
            for (name, &limit) in &settings.tolerances {
                let k = study.quantity_index(name);
                let p = k.and_then(|k| row.orders[k]);
                // At the error floor the order is noise: both errors are far inside the
                // limit, at the level of the reference's and the penalty's own errors.
                let floor = ORDER_FLOOR * limit;
                let at_floor = k.is_some_and(|k| {
                    matches!((previous.errors[k], row.errors[k]), (Some(a), Some(b)) if a <= floor && b <= floor)
                });
                let pass = at_floor || p.is_some_and(|p| p >= min);
                let reason = match p {
                    _ if at_floor => format!("not checked: errors below {ORDER_FLOOR:.0e}·limit (error floor)"),
                    _ if pass => String::new(),
                    Some(p) => format!("order {p:.2} below {min:.2}"),
                    None => "order not computable (an error is absent or 0)".into(),
                };
                checks.push(Check {
                    method: s.method.clone(),
                    discretisation: Some(row.run.discretisation),
                    quantity: name.clone(),
                    measure: Measure::Order,
                    value: p,
                    limit: Some(min),
                    pass,
                    reason,
                });
            }
        }
    }
    GateOutcome { scene: study.scene.clone(), checks, notes, wall_seconds: study.wall_seconds }
}

/// The failure table: one row per failing check — scene, method, at, quantity,
/// measure, value, limit, how far off, why.
pub fn failure_table(outcomes: &[GateOutcome]) -> Table {
    let mut t = Table::new(["scene", "method", "at", "quantity", "measure", "value", "limit", "off by", "why"]);
    t.left = vec![0, 1, 3, 4, 8];
    for o in outcomes {
        for c in o.failures() {
            let (value, limit) = match c.measure {
                Measure::Order => (fmt_order(c.value), fmt_order(c.limit)),
                _ => (fmt_error(c.value), fmt_error(c.limit)),
            };
            t.push(vec![
                o.scene.clone(),
                c.method.clone(),
                c.discretisation.map_or(NONE.into(), fmt_disc),
                c.quantity.clone(),
                c.measure.to_string(),
                value,
                limit,
                c.excess().map_or(NONE.into(), |x| format!("×{x:.3}")),
                shorten(&c.reason, 110),
            ]);
        }
    }
    t
}

/// At most `n` characters, with "…" if cut.
fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        format!("{}…", s.chars().take(n - 1).collect::<String>())
    }
}

/// The compact pass table: per scene the checks passed, the check closest to its limit
/// (quantity, method, error/limit) and the time.
pub fn summary_table(outcomes: &[GateOutcome]) -> Table {
    let mut t = Table::new(["scene", "verdict", "checks", "closest to its limit", "error / limit", "time [s]"]);
    t.left = vec![0, 1, 3];
    for o in outcomes {
        let passed = o.checks.iter().filter(|c| c.pass).count();
        let tight = o.tightest();
        t.push(vec![
            o.scene.clone(),
            if o.passed() { "pass".into() } else { "FAIL".into() },
            format!("{passed}/{}", o.checks.len()),
            tight.map_or(NONE.into(), |c| format!("{} · {}", c.quantity, c.method)),
            tight.and_then(Check::excess).map_or(NONE.into(), |x| format!("{x:.2e}")),
            fmt_seconds(Some(o.wall_seconds)),
        ]);
    }
    t
}
