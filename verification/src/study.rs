//! A *study* of one scene: the BVP over a tolerance sequence per variant, and every FE
//! formulation over a mesh sequence, each run held against the tightest BVP run (the
//! reference) through the common solution view.
//!
//! The algorithm of [`Study::run`] reads as follows:
//! 1. solve the reference (collocation gauss6 at the tightest tolerance);
//! 2. for each BVP variant, each tolerance: run, errors of every quantity
//!    ([`crate::measure`]) — no orders (order against a tolerance is not meaningful);
//! 3. for each FE formulation (discovered from the `fem` registry unless named), each
//!    mesh: run, errors, observed orders p_k between successive meshes;
//! 4. for each FE formulation with three or more successful meshes: Richardson
//!    extrapolation of every quantity with its self-convergence order, and the
//!    mutual convergence |q_R − q_ref| / |q_ref|.
//!
//! Runs are executed one after another so that their wall times are comparable.

use bvp::collocation::Scheme;
use drive::result::Refinement;
use drive::scene::Scene;
use serde::Serialize;

use crate::measure::{self, Quantity, QuantityKind};
use crate::reference::{Estimate, Reference, ReferenceRun};
use crate::run::{execute, BvpSolver, BvpVariant, Discretisation, Family, FemFormulation, Method, Run, RunError, ShellFe, SHELL_FE, SHELL_FORMULATION};

/// Default σ samples of the field norms: enough that the sampling error of an L2 norm
/// (trapezoidal rule, O(n⁻²) with the kinks at contact points) stays far below the
/// errors the tables resolve.
pub const DEFAULT_SAMPLES: usize = 2048;

/// Default BVP tolerance sequence of `converge` and `report` for gauss6 and shooting.
pub const DEFAULT_TOLERANCES: [f64; 7] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

/// gauss4 stops earlier by default: its collocation residual converges at order 2, so
/// tolerances below 1e-8 need more mesh nodes than the default cap on slack scenes.
pub const DEFAULT_GAUSS4_FLOOR: f64 = 1e-8;

/// Collocation mesh cap of the studies (instead of the scene's `bvp.max_nodes`, default
/// 20 000): gauss4's residual converges at order 2 only, and on slack scenes it needs
/// more nodes than that to reach 1e-8.
pub const STUDY_MAX_NODES: usize = 100_000;

/// Tolerance of the reference run of `converge` and `report` (collocation gauss6).
pub const REFERENCE_TOLERANCE: f64 = 1e-11;

pub use drive::scene::MAX_ELEMENTS;

/// Smallest FE element count: one element per region of the contour.
pub const MIN_ELEMENTS: usize = 4;

/// Bounds of the σ samples of the field norms ([`StudyPlan::samples`]).
pub const SAMPLES_RANGE: std::ops::RangeInclusive<usize> = 16..=100_000;

/// A sweep of one BVP variant over tolerances.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BvpSweep {
    /// Collocation scheme or shooting.
    pub variant: BvpVariant,
    /// Tolerances, loosest first.
    pub tolerances: Vec<f64>,
}

/// Which FE formulations a study runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Formulations {
    /// Every formulation of [`fem::available_formulations`] (a formulation that returns
    /// "not applicable" for the scene is listed as such, not failed).
    Discovered,
    /// These names (from `--formulation` or the scene's `fem.formulations`); each must
    /// be registered, and "not applicable" counts as a failure.
    Named(Vec<String>),
}

/// Why a study that ran gives no usable answer.
#[derive(Debug, Clone, thiserror::Error)]
pub enum StudyError {
    /// The reference run failed: there is nothing to hold the other runs against.
    #[error("the reference ({method}) could not be computed")]
    ReferenceFailed {
        /// Reference method label.
        method: String,
        /// Its failure.
        source: RunError,
    },
    /// A method the study asked for failed at every discretisation.
    #[error("no successful run of {method} (all {runs} failed); first failure")]
    NoSuccessfulRun {
        /// Method label.
        method: String,
        /// Its runs, all failed.
        runs: usize,
        /// The failure of its first run.
        source: RunError,
    },
}

/// What a study runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyPlan {
    /// What the runs are held against ([`Reference`]).
    pub reference: Reference,
    /// BVP sweeps.
    pub bvp: Vec<BvpSweep>,
    /// FE formulations.
    pub formulations: Formulations,
    /// FE element counts, strictly increasing.
    pub meshes: Vec<usize>,
    /// σ samples of the field norms.
    pub samples: usize,
    /// Override of the collocation mesh cap (`None` = the scene's `bvp.max_nodes`).
    pub max_nodes: Option<usize>,
    /// A shell study also finds the compensating swivel of a cambered belt
    /// ([`Study::compensation`]); `converge` and `report` ask for it, the gate does not.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub compensate: bool,
}

/// Why a plan cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// A formulation name that is not registered.
    #[error("formulation `{name}` is not registered (registered: {registered})")]
    UnknownFormulation {
        /// The name asked for.
        name: String,
        /// The registry, comma-separated, or "none".
        registered: String,
    },
    /// Mesh sequence not strictly increasing or outside 4 … [`MAX_ELEMENTS`].
    #[error("element counts must lie in {MIN_ELEMENTS} … {MAX_ELEMENTS} and increase strictly, got {0:?}")]
    Meshes(Vec<usize>),
    /// The levels of a shell study are not three or more 2-D meshes, each refined from
    /// the one before in one way throughout ([`drive::result::Refinement`]) by one ratio
    /// > 1, n_ζ with σ by it or held (or the plan
    /// also names BVP or 1-D FE runs, which a shell scene has none of).
    #[error("a shell study needs three or more levels n_σ × n_ζ with Δt, each refined from the one before in one way throughout — σ and Δt together, σ alone at one Δt, Δt alone on one mesh, or n_ζ alone on one σ-mesh at one Δt — by one ratio > 1 (the same ratio over the three finest, for the Richardson extrapolation), n_ζ with σ by that ratio or held, and nothing else; got {}", crate::reference::list(.0))]
    ShellLevels(Vec<Discretisation>),
    /// A shell scene with a plan that is not a shell study, or a shell study of a scene
    /// that is not a shell.
    #[error("scene theory `{theory}`: {why}")]
    ShellMismatch {
        /// The scene's belt theory.
        theory: drive::scene::Theory,
        /// What does not match.
        why: &'static str,
    },
    /// σ samples outside [`SAMPLES_RANGE`].
    #[error("{n} σ samples: the field norms take {lo} … {hi}", n = .0, lo = SAMPLES_RANGE.start(), hi = SAMPLES_RANGE.end())]
    Samples(usize),
    /// A tolerance outside (0, 1).
    #[error("tolerance {} is not in (0, 1)", drive::error::num(.0))]
    Tolerance(f64),
    /// A named formulation that discretises another belt theory than the scene's: a
    /// usage error before anything runs, as in `solve`, not a failed run (issue 12).
    #[error("formulation `{name}` discretises theory `{theory}`, the scene's belt is theory `{scene_theory}` (its formulations: {its})")]
    NotApplicable {
        /// The name asked for.
        name: String,
        /// The theory it discretises.
        theory: drive::scene::Theory,
        /// The scene's belt theory.
        scene_theory: drive::scene::Theory,
        /// The registered formulations of the scene's theory, or "none".
        its: String,
    },
}

/// How a shell study's `levels` are refined ([`Discretisation::refinement`]): the one kind
/// every level shares with the one before it, `None` when there are fewer than two levels
/// or the kinds differ (no one limit to extrapolate to).
pub fn shell_refinement(levels: &[Discretisation]) -> Option<Refinement> {
    let kinds: Vec<Option<Refinement>> = levels.windows(2).map(|w| w[0].refinement(w[1]).map(|(k, _)| k)).collect();
    let first = *kinds.first()?;
    kinds.iter().all(|&k| k == first).then_some(first).flatten()
}

/// Whether `scene` has a compensating swivel for a shell study to search
/// ([`StudyPlan::compensate`]): a shell with camber on turning drums.
pub fn has_compensating_swivel(scene: &Scene) -> bool {
    fem::shell::scene::ShellScene::from_scene(scene).is_ok_and(|shell| shell.turning && shell.camber != 0.0)
}

/// What a shell study's levels leave out of its estimates, for its notes: the error in
/// space when only Δt is refined, the step's error when only the mesh is, the errors
/// along σ and in the step when only the width is, the error across the width when n_ζ
/// is held while σ is refined.
pub fn shell_level_notes(levels: &[Discretisation]) -> Vec<String> {
    let mut notes = Vec::new();
    match (shell_refinement(levels), levels.last()) {
        (Some(Refinement::Step), Some(&Discretisation::Mesh2d { sigma, zeta, .. })) => notes.push(format!(
            "the time step alone is refined, on the mesh {sigma}×{zeta}: the sequence converges to the time-continuous limit on that mesh, so the error in space is not in the estimates (refine the mesh, --refine both or mesh, to include it)"
        )),
        (Some(Refinement::Mesh), Some(&Discretisation::Mesh2d { time_step, .. })) => notes.push(format!(
            "the mesh alone is refined, at Δt = {} s: the sequence converges to the limit in space at that step, so the step's error is not in the estimates (refine Δt too, --refine both or step, to include it)",
            drive::error::num(&time_step)
        )),
        (Some(Refinement::Width), Some(&Discretisation::Mesh2d { sigma, time_step, .. })) => notes.push(format!(
            "the width alone is refined, n_ζ on the σ-mesh of {sigma} elements at Δt = {} s: the sequence converges to the limit across the width on that σ-mesh and step, so the errors along σ and in the step are not in the estimates (--refine mesh and step measure them)",
            drive::error::num(&time_step)
        )),
        _ => {}
    }
    if let (Some(Discretisation::Mesh2d { zeta: first, sigma: s0, .. }), Some(Discretisation::Mesh2d { zeta: last, sigma: s1, .. })) = (levels.first(), levels.last()) {
        if first == last && s0 != s1 {
            notes.push(format!(
                "n_ζ is held at {last} over the levels: the sequence converges to that n_ζ's limit, so the error across the width is not in the estimates (refine ζ with σ to include it)"
            ));
        }
    }
    notes
}

impl StudyPlan {
    /// The convergence study of `converge` and `report`: reference gauss6 at 1e-11;
    /// gauss4 over 1e-4 … 1e-8, gauss6 and shooting over 1e-4 … 1e-10; FE formulations
    /// from the scene's `fem.formulations` (else discovered) over `fem.meshes()`.
    pub fn convergence(scene: &Scene) -> StudyPlan {
        let fem = scene.fem_settings();
        let tol = DEFAULT_TOLERANCES.to_vec();
        StudyPlan {
            reference: Reference::Bvp { variant: BvpVariant::Collocation(Scheme::Gauss6), tolerance: REFERENCE_TOLERANCE },
            bvp: vec![
                BvpSweep {
                    variant: BvpVariant::Collocation(Scheme::Gauss4),
                    tolerances: tol.iter().copied().filter(|&t| t >= DEFAULT_GAUSS4_FLOOR * 0.999).collect(),
                },
                BvpSweep { variant: BvpVariant::Collocation(Scheme::Gauss6), tolerances: tol.clone() },
                BvpSweep { variant: BvpVariant::Shooting, tolerances: tol },
            ],
            formulations: if fem.formulations.is_empty() { Formulations::Discovered } else { Formulations::Named(fem.formulations.clone()) },
            meshes: fem.meshes(),
            samples: DEFAULT_SAMPLES,
            max_nodes: Some(STUDY_MAX_NODES),
            compensate: false,
        }
        .without_unsolvable_fem(scene)
    }

    /// The convergence study of a shell scene (issue 15; docs/verification.md "The
    /// shell's study"): no BVP exists, so the shell FE ([`crate::run::ShellFe`]) runs at
    /// `levels` — n_σ × n_ζ with Δt, coarsest first, refined in one way throughout by one
    /// ratio ([`shell_refinement`]: σ and Δt together, σ alone or Δt alone; n_ζ with σ by
    /// the same ratio or held) — and the reference is the Richardson
    /// extrapolation of its three finest runs ([`Reference::Richardson`] of
    /// [`SHELL_FORMULATION`]). The study computes each level once: the series is the
    /// reference's own runs, held against the extrapolated values.
    pub fn shell(levels: Vec<Discretisation>) -> StudyPlan {
        StudyPlan {
            reference: Reference::Richardson { formulation: SHELL_FORMULATION.to_string(), levels },
            bvp: Vec::new(),
            formulations: Formulations::Named(Vec::new()),
            meshes: Vec::new(),
            samples: DEFAULT_SAMPLES,
            max_nodes: None,
            compensate: false,
        }
    }

    /// This plan with the compensating swivel asked for ([`StudyPlan::compensate`]).
    pub fn with_compensation(mut self) -> StudyPlan {
        self.compensate = true;
        self
    }

    /// How the levels of a shell study are refined ([`shell_refinement`]), if this is one
    /// and they are refined in one way throughout.
    pub fn shell_refinement(&self) -> Option<Refinement> {
        self.shell_levels().and_then(shell_refinement)
    }

    /// The levels of a shell study ([`StudyPlan::shell`]), if this is one.
    pub fn shell_levels(&self) -> Option<&[Discretisation]> {
        match &self.reference {
            Reference::Richardson { formulation, levels } if formulation == SHELL_FORMULATION => Some(levels),
            _ => None,
        }
    }

    /// No FE runs for a scene the FE does not solve yet ([`drive::not_yet_solvable`], e.g.
    /// the one-pulley layout): a BVP-only plan (the study notes why), so that neither
    /// `converge` nor `gate` asks for runs that can only be refused.
    pub fn without_unsolvable_fem(mut self, scene: &Scene) -> StudyPlan {
        if drive::not_yet_solvable(scene, drive::Solver::Fem).is_some() {
            self.formulations = Formulations::Named(Vec::new());
            self.meshes = Vec::new();
        }
        self
    }

    /// A BVP-only plan unless `fem` (the scene's `gate.fem = false`: the gate holds the
    /// BVP methods only).
    pub fn without_fem_unless(mut self, fem: bool) -> StudyPlan {
        if !fem {
            self.formulations = Formulations::Named(Vec::new());
            self.meshes = Vec::new();
        }
        self
    }

    /// The same tolerance sequence for every BVP variant.
    pub fn with_tolerances(mut self, tolerances: &[f64]) -> StudyPlan {
        for s in &mut self.bvp {
            s.tolerances = tolerances.to_vec();
        }
        self
    }

    /// These FE element counts.
    pub fn with_meshes(mut self, meshes: &[usize]) -> StudyPlan {
        self.meshes = meshes.to_vec();
        self
    }

    /// These formulations by name.
    pub fn with_formulations(mut self, names: &[String]) -> StudyPlan {
        self.formulations = Formulations::Named(names.to_vec());
        self
    }

    /// Checks names, meshes and tolerances.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), PlanError> {
        if let Formulations::Named(names) = &self.formulations {
            let registered = fem::available_formulations();
            for n in names {
                if !registered.contains(&n.as_str()) {
                    let list = if registered.is_empty() { "none".to_string() } else { registered.join(", ") };
                    return Err(PlanError::UnknownFormulation { name: n.clone(), registered: list });
                }
            }
        }
        if self.meshes.iter().any(|n| !(MIN_ELEMENTS..=MAX_ELEMENTS).contains(n)) || self.meshes.windows(2).any(|w| w[1] <= w[0]) {
            return Err(PlanError::Meshes(self.meshes.clone()));
        }
        if !SAMPLES_RANGE.contains(&self.samples) {
            return Err(PlanError::Samples(self.samples));
        }
        let reference_tolerance = match &self.reference {
            Reference::Bvp { tolerance, .. } => Some(tolerance),
            _ => None,
        };
        if let Some(levels) = self.shell_levels() {
            let shell_levels_valid = levels.len() >= 3
                && levels.iter().all(|d| matches!(d, Discretisation::Mesh2d { .. }) && d.check().is_ok())
                && shell_refinement(levels).is_some()
                && levels.windows(3).last().is_some_and(|w| match (w[0].refinement_ratio(w[1]), w[1].refinement_ratio(w[2])) {
                    (Some(a), Some(b)) => (a - b).abs() <= 1e-9 * b,
                    _ => false,
                });
            if !shell_levels_valid {
                return Err(PlanError::ShellLevels(levels.to_vec()));
            }
            if !self.bvp.is_empty() || !self.meshes.is_empty() {
                return Err(PlanError::ShellLevels(levels.to_vec()));
            }
        } else if let Reference::Richardson { formulation, levels } = &self.reference {
            if !fem::available_formulations().contains(&formulation.as_str()) {
                return Err(PlanError::UnknownFormulation { name: formulation.clone(), registered: fem::available_formulations().join(", ") });
            }
            let elements: Vec<usize> = levels.iter().filter_map(|d| d.elements_along()).collect();
            if levels.len() < 3 || elements.len() != levels.len() || elements.windows(2).any(|w| w[1] <= w[0]) {
                return Err(PlanError::Meshes(elements));
            }
        }
        let tols = self.bvp.iter().flat_map(|s| s.tolerances.iter()).chain(reference_tolerance);
        for &t in tols {
            if !(t > 0.0 && t < 1.0) {
                return Err(PlanError::Tolerance(t));
            }
        }
        Ok(())
    }

    /// [`StudyPlan::validate`], and every formulation the plan names (for its FE runs or
    /// its Richardson reference) discretises the scene's belt theory.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate_for(&self, scene: &Scene) -> Result<(), PlanError> {
        self.validate()?;
        let shell = scene.belt.theory == drive::scene::Theory::Shell;
        match (shell, self.shell_levels().is_some()) {
            (true, false) => {
                return Err(PlanError::ShellMismatch {
                    theory: scene.belt.theory,
                    why: "no BVP exists for the shell and its element is not a 1-D formulation: its study is the shell FE over levels n_σ × n_ζ with Δt, held against their Richardson extrapolation",
                })
            }
            (false, true) => return Err(PlanError::ShellMismatch { theory: scene.belt.theory, why: "a shell study (levels n_σ × n_ζ with Δt) studies a shell scene only" }),
            _ => {}
        }
        let mut named: Vec<&String> = Vec::new();
        if let (Formulations::Named(names), false) = (&self.formulations, self.meshes.is_empty()) {
            named.extend(names);
        }
        if let Reference::Richardson { formulation, .. } = &self.reference {
            named.push(formulation);
        }
        for name in named {
            if let Some(theory) = crate::run::formulation_theory(name).filter(|&t| t != scene.belt.theory) {
                let its = fem::formulations_for(scene.belt.theory);
                let its = if its.is_empty() { "none".to_string() } else { its.join(", ") };
                return Err(PlanError::NotApplicable { name: name.clone(), theory, scene_theory: scene.belt.theory, its });
            }
        }
        Ok(())
    }

    /// The FE methods of the plan.
    pub fn fem_methods(&self) -> Vec<FemFormulation> {
        match &self.formulations {
            Formulations::Discovered => FemFormulation::discovered(),
            Formulations::Named(n) => n.iter().map(|name| FemFormulation { name: name.clone(), penalty: None }).collect(),
        }
    }

    /// Number of runs (for a progress bar).
    pub fn run_count(&self) -> usize {
        self.reference.run_count() + self.bvp.iter().map(|s| s.tolerances.len()).sum::<usize>() + self.fem_methods().len() * self.meshes.len()
    }
}

/// Progress of a study, reported before each run and once at the end.
#[derive(Debug, Clone)]
pub struct Progress {
    /// Runs finished.
    pub done: usize,
    /// Runs planned.
    pub total: usize,
    /// What runs next (empty at the end).
    pub label: String,
}

/// A run with its errors and orders, aligned with [`Study::quantities`].
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// The run.
    pub run: Run,
    /// Error of each quantity against the reference (`None` = not computable).
    pub errors: Vec<Option<f64>>,
    /// Observed order against the previous level (FE only; `None` for BVP rows, the
    /// first level, and undefined orders).
    pub orders: Vec<Option<f64>>,
    /// Max of the summary-scalar errors (`None` if any is not computable).
    pub scalar_error: Option<f64>,
    /// Observed order of `scalar_error` (FE only).
    pub scalar_order: Option<f64>,
}

/// Richardson extrapolation and mutual convergence of one quantity of one FE
/// formulation.
#[derive(Debug, Clone, Serialize)]
pub struct Extrapolation {
    /// Quantity name.
    pub quantity: String,
    /// Value at the finest mesh (scalars only).
    pub finest: Option<f64>,
    /// Error at the finest mesh against the reference.
    pub finest_error: Option<f64>,
    /// Self-convergence order of the three finest meshes.
    pub order: Option<f64>,
    /// Extrapolated value (scalars only).
    pub value: Option<f64>,
    /// Error of the extrapolated value / field against the reference.
    pub mutual: Option<f64>,
}

/// Whether a method was studied.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", content = "reason", rename_all = "snake_case")]
pub enum SeriesStatus {
    /// Runs were made (some may have failed).
    Studied,
    /// The method has no model for the scene; nothing was compared.
    NotApplicable(String),
}

/// All runs of one method.
#[derive(Debug, Clone, Serialize)]
pub struct Series {
    /// Method label.
    pub method: String,
    /// BVP or FE.
    pub family: Family,
    /// Studied or not applicable.
    pub status: SeriesStatus,
    /// One row per discretisation, coarsest first.
    pub rows: Vec<Row>,
    /// Richardson extrapolation per quantity (FE with ≥ 3 meshes), aligned with
    /// [`Study::quantities`]; empty otherwise.
    pub extrapolation: Vec<Extrapolation>,
    /// Terms the method assembled (from its finest successful run).
    pub terms: Vec<String>,
}

impl Series {
    /// The finest row (last), if any.
    pub fn finest(&self) -> Option<&Row> {
        self.rows.last()
    }
}

/// A study of one scene.
#[derive(Debug, Clone, Serialize)]
pub struct Study {
    /// Scene name.
    pub scene: String,
    /// What was run.
    pub plan: StudyPlan,
    /// The quantities of the tables: the reference's summary scalars, then field norms.
    pub quantities: Vec<Quantity>,
    /// The reference, as a run whose `method` names its kind ([`Reference::label`]).
    pub reference: Run,
    /// The error estimate of each reference scalar (Richardson references only).
    pub reference_estimates: Vec<Estimate>,
    /// BVP series first, then FE series.
    pub series: Vec<Series>,
    /// Formulations in the `fem` registry when the study ran.
    pub registered_formulations: Vec<String>,
    /// Statements a reader needs (e.g. "no FE formulation registered").
    pub notes: Vec<String>,
    /// Wall time of the whole study, s.
    pub wall_seconds: f64,
    /// A shell study of a cambered belt on turning drums whose plan asks for it
    /// ([`StudyPlan::compensate`]): the steering drum's constant swivel that cancels the
    /// run-off at the coarsest level (spec E-5, a scalar root over
    /// whole solves, [`fem::shell::compensation`]); absent otherwise, or when it could not
    /// be found (a note says why).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub compensation: Option<fem::shell::compensation::Compensation>,
}

impl Study {
    /// Runs `plan` on `scene` (module docs), reporting progress to `progress`.
    ///
    /// # Errors
    /// An invalid plan. Failed runs are not errors: they are rows with a reason.
    pub fn run(scene: &Scene, plan: &StudyPlan, progress: &mut dyn FnMut(&Progress)) -> Result<Study, PlanError> {
        plan.validate_for(scene)?;
        if let Some(levels) = plan.shell_levels() {
            return Ok(Study::run_shell(scene, plan, levels, progress));
        }
        let mut bvp: Vec<(Box<dyn Method>, Vec<Discretisation>)> = Vec::new();
        for s in &plan.bvp {
            let solver = BvpSolver { variant: s.variant, max_nodes: plan.max_nodes };
            bvp.push((Box::new(solver), s.tolerances.iter().map(|&t| Discretisation::Tolerance(t)).collect()));
        }
        let meshes: Vec<Discretisation> = plan.meshes.iter().map(|&n| Discretisation::Elements(n)).collect();
        let mut methods = bvp;
        for f in plan.fem_methods() {
            methods.push((Box::new(f), meshes.clone()));
        }
        let strict = matches!(plan.formulations, Formulations::Named(_));
        Ok(Study::run_methods(scene, plan, methods, strict, progress))
    }

    /// The shell's study ([`StudyPlan::shell`]): each level solved once, the reference
    /// extrapolated from those runs, and the same runs held against it as the series.
    fn run_shell(scene: &Scene, plan: &StudyPlan, levels: &[Discretisation], progress: &mut dyn FnMut(&Progress)) -> Study {
        let start = std::time::Instant::now();
        let total = levels.len();
        let mut runs = Vec::with_capacity(total);
        for (done, &d) in levels.iter().enumerate() {
            progress(&Progress { done, total, label: format!("{SHELL_FE} {d}") });
            runs.push(execute(&ShellFe, scene, d, plan.samples));
        }
        progress(&Progress { done: total, total, label: String::new() });
        let mut computed = plan.reference.richardson(&runs);
        computed.notes.extend(shell_level_notes(levels));
        let mut study = Study::of_runs(scene, plan, computed, vec![(SHELL_FE.to_string(), Family::Fem, runs)]);
        if let Some(&Discretisation::Mesh2d { sigma, zeta, time_step }) = levels.first() {
            if plan.compensate && has_compensating_swivel(scene) {
                progress(&Progress { done: total, total, label: format!("the compensating swivel at {sigma}×{zeta}") });
                let found = ShellFe::scene_at(scene, sigma, zeta, time_step).map_err(|e| e.to_string()).and_then(|s| fem::shell::compensation::compensating_swivel(&s).map_err(|e| e.to_string()));
                match found {
                    Ok(c) => study.compensation = Some(c),
                    Err(e) => study.notes.push(format!("the compensating swivel (spec E-5) at the coarsest level {sigma}×{zeta} could not be found: {e}")),
                }
                progress(&Progress { done: total, total, label: String::new() });
            }
        }
        study.wall_seconds = start.elapsed().as_secs_f64();
        study
    }

    /// Runs the reference of `plan` and then `methods`, each over its discretisations
    /// (the engine of [`Study::run`]; a test passes its own methods here). With
    /// `strict_fem`, an FE method that is not applicable is studied as failed rows
    /// instead of being set aside.
    pub fn run_methods(
        scene: &Scene,
        plan: &StudyPlan,
        methods: Vec<(Box<dyn Method>, Vec<Discretisation>)>,
        strict_fem: bool,
        progress: &mut dyn FnMut(&Progress),
    ) -> Study {
        let start = std::time::Instant::now();
        let total = plan.reference.run_count() + methods.iter().map(|(_, d)| d.len()).sum::<usize>();
        let mut done = 0;
        progress(&Progress { done, total, label: format!("reference: {}", plan.reference.label()) });
        let computed = plan.reference.compute(scene, plan.samples, plan.max_nodes);
        let reference = &computed.run;
        done += plan.reference.run_count();
        let quantities = reference.data().map(Quantity::of_reference).unwrap_or_default();

        let mut series = Vec::new();
        for (method, discs) in &methods {
            let before = done;
            series.push(study_series(scene, method.as_ref(), discs, plan.samples, strict_fem, reference, &quantities, &mut |label| {
                progress(&Progress { done, total, label });
                done += 1;
            }));
            done = before + discs.len();
        }
        progress(&Progress { done: total, total, label: String::new() });
        Study::assemble(scene, plan, computed, quantities, series, start)
    }

    /// The series of the scene's own FE formulations of `plan` (those that discretise its
    /// belt theory) at `plan.meshes`, held against this study's reference and added
    /// before its series: the built-in methods beside the outside ones in the report of
    /// `beltcheck check --report`.
    pub fn with_built_in_fem(mut self, scene: &Scene) -> Study {
        if self.reference.data().is_none() {
            return self;
        }
        let meshes: Vec<Discretisation> = self.plan.meshes.iter().map(|&n| Discretisation::Elements(n)).collect();
        let mut plan = self.plan.clone();
        plan.formulations = crate::gate::gate_plan_with(scene, None, None, None).formulations;
        let mut built_in = Vec::new();
        for f in plan.fem_methods() {
            let series = study_series(scene, &f, &meshes, self.plan.samples, false, &self.reference, &self.quantities, &mut |_| {});
            if series.status == SeriesStatus::Studied {
                built_in.push(series);
            }
        }
        built_in.append(&mut self.series);
        self.series = built_in;
        self
    }

    /// A study of runs made elsewhere — an outside code's results read from files
    /// (`beltcheck check`) — held against `computed`, the reference of `plan`: the same
    /// errors, orders, Richardson extrapolation and mutual convergence as [`Study::run`].
    /// Each supplied series is a method label, its family and its runs, coarsest first.
    pub fn of_runs(scene: &Scene, plan: &StudyPlan, computed: ReferenceRun, supplied: Vec<(String, Family, Vec<Run>)>) -> Study {
        let start = std::time::Instant::now();
        let quantities = computed.run.data().map(Quantity::of_reference).unwrap_or_default();
        let series = supplied
            .into_iter()
            .map(|(label, family, runs)| {
                let mut rows: Vec<Row> = Vec::new();
                for run in runs {
                    let row = make_row(run, &computed.run, &quantities, rows.last());
                    rows.push(row);
                }
                finish_series(label, family, SeriesStatus::Studied, rows, &computed.run, &quantities)
            })
            .collect();
        Study::assemble(scene, plan, computed, quantities, series, start)
    }

    /// The study of a computed reference and its series, with the notes a reader needs.
    fn assemble(scene: &Scene, plan: &StudyPlan, computed: ReferenceRun, quantities: Vec<Quantity>, series: Vec<Series>, start: std::time::Instant) -> Study {
        let reference = computed.run;
        let registered: Vec<String> = fem::available_formulations().into_iter().map(String::from).collect();
        let mut notes = computed.notes;
        if let Err(e) = &reference.outcome {
            notes.push(format!("the reference could not be computed ({e}): no errors against it"));
        }
        if let Some(d) = reference.data() {
            let r = scene.drive.pulley_radius;
            let min_nu = d.samples.deflection.iter().copied().fold(f64::INFINITY, f64::min);
            if min_nu <= -r * (1.0 - 1e-6) {
                notes.push(format!(
                    "the reference belt reaches ν = {min_nu:.4} m ≤ −R = −{r} m (a span sags past the pulley centres), where the map point → (σ, ν) of the contour is not one-to-one: fields sampled through the common view (and their norms) are not meaningful for this scene; compare its summary scalars"
                ));
            }
        }
        let fem_studied = series.iter().any(|s| s.family == Family::Fem && s.status == SeriesStatus::Studied);
        if !series.iter().any(|s| s.family == Family::Fem) {
            if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Fem) {
                notes.push(format!("BVP-only study: {e}"));
            } else if registered.is_empty() {
                notes.push("no FE formulation registered: BVP-only study (no FE rows, no mutual convergence)".to_string());
            } else {
                notes.push("no FE formulation selected: BVP-only study".to_string());
            }
        } else if !fem_studied {
            notes.push("no registered FE formulation applies to this scene: BVP-only study".to_string());
        }
        Study {
            scene: scene.name.clone(),
            plan: plan.clone(),
            quantities,
            reference,
            reference_estimates: computed.estimates,
            series,
            registered_formulations: registered,
            notes,
            wall_seconds: start.elapsed().as_secs_f64(),
            compensation: None,
        }
    }

    /// Index of a quantity by name.
    pub fn quantity_index(&self, name: &str) -> Option<usize> {
        self.quantities.iter().position(|q| q.name == name)
    }

    /// Whether the study answers what it asked: its reference solved, and every
    /// method it studied with at least one successful run (`converge` and `report`
    /// exit with status 2 otherwise, and `converge` writes no study JSON).
    ///
    /// # Errors
    /// [`StudyError::ReferenceFailed`] or [`StudyError::NoSuccessfulRun`] (the first
    /// such method).
    pub fn usable(&self) -> Result<(), StudyError> {
        if let Err(e) = &self.reference.outcome {
            return Err(StudyError::ReferenceFailed { method: self.reference.method.clone(), source: e.clone() });
        }
        for s in self.series.iter().filter(|s| s.status == SeriesStatus::Studied) {
            if s.rows.iter().all(|r| r.run.data().is_none()) {
                if let Some(first) = s.rows.first() {
                    let source = first.run.outcome.as_ref().err().cloned().unwrap_or(RunError::Failed(String::new()));
                    return Err(StudyError::NoSuccessfulRun { method: s.method.clone(), runs: s.rows.len(), source });
                }
            }
        }
        Ok(())
    }

    /// True if at least one FE series was studied.
    pub fn has_fem(&self) -> bool {
        self.series.iter().any(|s| s.family == Family::Fem && s.status == SeriesStatus::Studied)
    }
}

/// A series of rows with its Richardson extrapolation (FE) and the terms of its finest
/// successful run.
fn finish_series(method: String, family: Family, status: SeriesStatus, rows: Vec<Row>, reference: &Run, quantities: &[Quantity]) -> Series {
    let extrapolation = if family == Family::Fem { extrapolate(&rows, reference, quantities) } else { Vec::new() };
    let terms = rows.iter().rev().find_map(|r| r.run.data().map(|d| d.terms.clone())).unwrap_or_default();
    Series { method, family, status, rows, extrapolation, terms }
}

/// One method over its discretisations, held against `reference` (the loop of
/// [`Study::run_methods`]): `progress` hears each run's label before it starts. A method
/// that is not applicable at its first discretisation becomes a not-applicable series
/// (BVP methods always; FE methods unless `strict_fem`).
#[allow(clippy::too_many_arguments)]
fn study_series(
    scene: &Scene,
    method: &dyn Method,
    discs: &[Discretisation],
    samples: usize,
    strict_fem: bool,
    reference: &Run,
    quantities: &[Quantity],
    progress: &mut dyn FnMut(String),
) -> Series {
    let mut rows: Vec<Row> = Vec::new();
    let mut status = SeriesStatus::Studied;
    for (i, &disc) in discs.iter().enumerate() {
        progress(format!("{} {disc}", method.label()));
        let run = execute(method, scene, disc, samples);
        let lenient = method.family() == Family::Bvp || !strict_fem;
        if let (0, Err(RunError::NotApplicable(why)), true) = (i, &run.outcome, lenient) {
            status = SeriesStatus::NotApplicable(why.clone());
            break;
        }
        let prev = rows.last();
        rows.push(make_row(run, reference, quantities, prev));
    }
    finish_series(method.label(), method.family(), status, rows, reference, quantities)
}

/// Errors, orders and the scalar aggregate of one run.
fn make_row(run: Run, reference: &Run, quantities: &[Quantity], prev: Option<&Row>) -> Row {
    let errors: Vec<Option<f64>> = match (run.data(), reference.data()) {
        (Some(d), Some(r)) => quantities.iter().map(|q| q.error(d, r)).collect(),
        _ => vec![None; quantities.len()],
    };
    let scalar_errors: Vec<Option<f64>> = quantities.iter().zip(&errors).filter(|(q, _)| q.is_scalar()).map(|(_, e)| *e).collect();
    let scalar_error = if scalar_errors.is_empty() {
        None
    } else {
        scalar_errors.iter().copied().collect::<Option<Vec<f64>>>().map(|v| v.into_iter().fold(0.0, f64::max))
    };
    let ratio = match prev {
        Some(p) if run.family == Family::Fem => p.run.discretisation.refinement_ratio(run.discretisation),
        _ => None,
    };
    let (orders, scalar_order) = match (prev, ratio) {
        (Some(p), Some(r)) => (
            p.errors.iter().zip(&errors).map(|(a, b)| measure::observed_order(*a, *b, r)).collect(),
            measure::observed_order(p.scalar_error, scalar_error, r),
        ),
        _ => (vec![None; quantities.len()], None),
    };
    Row { run, errors, orders, scalar_error, scalar_order }
}

/// Richardson extrapolation of the three finest rows of an FE series (all three must
/// have succeeded, with a constant mesh ratio).
fn extrapolate(rows: &[Row], reference: &Run, quantities: &[Quantity]) -> Vec<Extrapolation> {
    let n = rows.len();
    let last3 = if n >= 3 { [rows[n - 3].run.data(), rows[n - 2].run.data(), rows[n - 1].run.data()] } else { [None, None, None] };
    let ratio = if n >= 3 {
        let (d1, d2, d3) = (rows[n - 3].run.discretisation, rows[n - 2].run.discretisation, rows[n - 1].run.discretisation);
        match (d1.refinement_ratio(d2), d2.refinement_ratio(d3)) {
            (Some(r1), Some(r2)) if (r1 - r2).abs() < 1e-9 * r2 => Some(r2),
            _ => None,
        }
    } else {
        None
    };
    quantities
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let finest_row = rows.last();
            let mut e = Extrapolation {
                quantity: q.name.clone(),
                finest: finest_row.and_then(|r| r.run.data()).and_then(|d| q.value(d)),
                finest_error: finest_row.and_then(|r| r.errors[k]),
                order: None,
                value: None,
                mutual: None,
            };
            let (Some(r), [Some(d1), Some(d2), Some(d3)], Some(refd)) = (ratio, last3, reference.data()) else {
                return e;
            };
            match &q.kind {
                QuantityKind::Scalar => {
                    if let (Some(q1), Some(q2), Some(q3)) = (q.value(d1), q.value(d2), q.value(d3)) {
                        e.order = measure::self_order(q1, q2, q3, r);
                        e.value = e.order.and_then(|p| measure::richardson(q2, q3, r, p));
                        e.mutual = match (e.value, q.value(refd)) {
                            (Some(v), Some(qr)) => measure::scalar_error(&q.name, v, qr),
                            _ => None,
                        };
                    }
                }
                QuantityKind::FieldNorm { norm, .. } => {
                    let fs = (measure::field_of(&d1.samples, q), measure::field_of(&d2.samples, q), measure::field_of(&d3.samples, q));
                    if let ((Some(f1), Some(f2), Some(f3)), Some(fr)) = (fs, measure::field_of(&refd.samples, q)) {
                        if let Some((fx, p)) = measure::richardson_field(f1, f2, f3, r, *norm) {
                            e.order = Some(p);
                            e.mutual = measure::field_error(&fx, fr, *norm);
                        }
                    }
                }
            }
            e
        })
        .collect()
}
