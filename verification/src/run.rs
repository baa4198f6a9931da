//! A *run* = scene + method + discretisation → solution view + summary + cost
//! (DESIGN.md, "The verification harness").
//!
//! The harness reads every solution only through [`drive::view::SolutionView`]: right
//! after the solve, [`execute`] samples the view on a uniform σ grid ([`Samples`]) and
//! drops the solver's own data, so BVP and FE runs are held against each other by the
//! same numbers.
//!
//! Methods are values behind the [`Method`] trait. The built-in ones are the BVP
//! variants ([`BvpSolver`]) and every formulation in the `fem` registry
//! ([`FemFormulation`], one per name of [`fem::available_formulations`]) — including
//! formulations another crate added with [`fem::register_formulation`], which are
//! studied, reported and gated like the built-in ones; a test or an experiment can pass
//! its own implementor to a study.

use std::fmt;
use std::time::Instant;

pub use bvp::collocation::Scheme;
use bvp::scene::{BvpMethod, BvpRunOptions, SceneSolveError};
use drive::scene::{Scene, Theory};
use drive::summary::Summary;
use drive::view::{ContactState, SolutionView};
use numerics::phases::Phases;
use serde::Serialize;

/// Which of the two independent computations a method belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    /// Semi-analytic BVP reference (crate `bvp`): refined by tolerance.
    Bvp,
    /// A closed form of the model (solved to a tolerance where it is a few scalar
    /// equations): only ever a reference ([`crate::reference`]).
    ClosedForm,
    /// MEL finite elements (crate `fem`): refined by mesh.
    Fem,
}

pub use drive::result::{fmt_tolerance, Discretisation};

/// Work spent on one run. Wall time is measured by the harness around the whole
/// `solve` call (homotopy and summary included), the same way for every method.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RunCost {
    /// Wall-clock time of the solve, s.
    pub wall_seconds: f64,
    /// Newton iterations, summed over continuation steps and refinements.
    pub newton_iterations: usize,
    /// Unknowns of the final discrete system.
    pub unknowns: usize,
    /// Mesh nodes of the final collocation / shooting mesh (BVP).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh_nodes: Option<usize>,
    /// Elements (FE).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// Where the wall time went, recorded by the harness around the solve
    /// ([`solve_timed`]); `None` for runs not solved through it (a closed form, a
    /// Richardson extrapolation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phases: Option<Phases>,
}

impl RunCost {
    /// The counters every method has; mesh nodes, elements and phases absent.
    pub fn counted(wall_seconds: f64, newton_iterations: usize, unknowns: usize) -> RunCost {
        RunCost { wall_seconds, newton_iterations, unknowns, mesh_nodes: None, elements: None, phases: None }
    }

    /// The phases in the result format (`cost.phases`): exclusive seconds, `other` =
    /// wall − their sum.
    pub fn cost_phases(&self) -> Option<drive::result::CostPhases> {
        use numerics::phases::Phase;
        let p = self.phases.as_ref()?;
        Some(drive::result::CostPhases {
            assembly: p.get(Phase::Assembly),
            symbolic_factorisation: p.get(Phase::SymbolicFactorisation),
            numeric_factorisation: p.get(Phase::NumericFactorisation),
            linear_solves: p.get(Phase::LinearSolves),
            residuals: p.get(Phase::Residuals),
            integration: p.get(Phase::Integration),
            mesh_adaptation: p.get(Phase::MeshAdaptation),
            fitting: p.get(Phase::Fitting),
            other: p.other(self.wall_seconds),
            fitting_total: p.fitting_total,
            continuation_steps: p.continuation_steps,
            mesh_refinements: p.mesh_refinements,
            fitting_passes: p.fitting_passes,
        })
    }
}

/// `method.solve(scene, disc)` timed by the harness: the wall time of the whole call
/// and its phases ([`numerics::phases::record`]) go into [`Solved::cost`], the same way
/// for every method. The wall clock is read outside the record, so the phases sum to at
/// most the wall time.
///
/// # Errors
/// The method's.
pub fn solve_timed(method: &dyn Method, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError> {
    let start = Instant::now();
    let (solved, phases) = numerics::phases::record(|| method.solve(scene, disc));
    let wall = start.elapsed().as_secs_f64();
    solved.map(|mut s| {
        s.cost.wall_seconds = wall;
        s.cost.phases = Some(phases);
        s
    })
}

/// What a method returns for one discretisation, before the harness samples it.
pub struct Solved {
    /// The solution behind the common view.
    pub view: Box<dyn SolutionView + Send + Sync>,
    /// Named scalars.
    pub summary: Summary,
    /// Work counters; `wall_seconds` is overwritten by the harness's own clock.
    pub cost: RunCost,
    /// Options used, serialised, so the run can be reproduced.
    pub options: serde_json::Value,
    /// The terms (effects) the method assembled or integrated, in words; empty if the
    /// method does not list them.
    pub terms: Vec<String>,
    /// Diagnostics worth keeping (homotopy steps, closure defects, …).
    pub notes: Vec<String>,
    /// Stated warnings about the result (an unresolved layer or slip zone, a fitting
    /// stopped at its pass limit): a result with warnings is not a clean one.
    pub warnings: Vec<String>,
    /// Quantities in time of a transient FE run (docs/fem-drive.md §8); `None` otherwise.
    pub history: Option<drive::result::TimeSeries>,
    /// `Some` for a transient FE run that stopped at `fem.max_steps` before its steady
    /// state (the solution is the last state, not the steady one); `None` for a run
    /// that reached what it solves for. [`execute`] turns `Some` into
    /// [`RunError::NotSteady`]; `solve` prints it and writes `"converged": false`.
    pub not_steady: Option<NotSteady>,
    /// `Some` for a static FE run whose contact fitting did not converge (the solution is
    /// the best fitted one, its boundaries off their nodes by more than the tolerance);
    /// stopped at its pass limit ([`fem::fitting::Unfitted::not_converged`]), treated as
    /// `not_steady`: [`execute`] turns it into [`RunError::Unfitted`], `solve` prints it
    /// and writes `"converged": false`; ended by a failed pass, a stated warning only.
    pub unfitted: Option<fem::fitting::Unfitted>,
}

/// How far a transient was from its steady state when `fem.max_steps` cut it off.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NotSteady {
    /// Time steps run.
    pub steps: usize,
    /// Change rate r_n of the last step, 1/rad (docs/fem-drive.md §7).
    pub rate: f64,
    /// The steady threshold on r_n (`fem.steady_tolerance`), 1/rad.
    pub tolerance: f64,
}

impl fmt::Display for NotSteady {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the transient did not reach a steady state: it stopped after {} step(s) (fem.max_steps) with change rate {} per rad above the steady threshold {} per rad; raise fem.max_steps or fem.time_step",
            self.steps,
            numerics::Sig(self.rate),
            drive::error::num(&self.tolerance)
        )
    }
}

/// Why a method produced no solution. The solvers' own errors are kept as values
/// ([`RunError::Bvp`], [`RunError::Fem`]: match on them, or follow
/// [`std::error::Error::source`]); their message is the solver's. Serialised as
/// `{"kind": "not_applicable" | "not_yet_solvable" | "failed" | "not_steady" | "not_converged", "message": "…"}`.
#[derive(Debug, Clone, thiserror::Error)]
pub enum RunError {
    /// The method has no model for this scene (e.g. a formulation for another belt
    /// theory): not a failure of the method, but nothing to compare either.
    #[error("not applicable: {0}")]
    NotApplicable(String),
    /// The scene's layout or theory is in the contract but no solver solves it yet: the
    /// refusal names the issue that brings it. Nothing was solved.
    #[error(transparent)]
    NotYetSolvable(drive::NotYetSolvable),
    /// A method outside this crate failed, or a method was given the wrong kind of
    /// discretisation.
    #[error("{0}")]
    Failed(String),
    /// The BVP solver failed (no convergence, mesh cap, a failed self-check, …).
    #[error(transparent)]
    Bvp(std::sync::Arc<SceneSolveError>),
    /// The FE solver failed.
    #[error(transparent)]
    Fem(fem::FemError),
    /// The shell's FE failed, or a self-check of its run did (docs/fem-shell.md §9).
    #[error(transparent)]
    Shell(fem::shell::ShellError),
    /// A closed-form reference does not describe the scene or did not converge.
    #[error(transparent)]
    ClosedForm(crate::closed_form::ClosedFormError),
    /// A Richardson reference could not be formed from its levels.
    #[error(transparent)]
    Richardson(Box<crate::reference::RichardsonError>),
    /// The solution's summary has a non-finite quantity.
    #[error("summary: {0}")]
    Summary(#[from] drive::error::ResultError),
    /// The solution's fields have a non-finite sample.
    #[error(transparent)]
    Sample(#[from] NonFiniteSample),
    /// A transient that stopped before its steady state: its last state is no answer
    /// to compare (issue 12: it used to count as converged).
    #[error("{0}")]
    NotSteady(NotSteady),
    /// A static FE run whose contact fitting did not converge: its best fitted solution
    /// is no converged answer to compare, as a transient cut off is none.
    #[error("{0}")]
    Unfitted(fem::fitting::Unfitted),
}

impl RunError {
    /// `not_applicable`, `not_yet_solvable`, `failed`, `not_steady` or `not_converged`:
    /// the kind written to JSON.
    pub fn kind(&self) -> &'static str {
        match self {
            RunError::NotApplicable(_) => "not_applicable",
            RunError::NotYetSolvable(_) => "not_yet_solvable",
            RunError::NotSteady(_) => "not_steady",
            RunError::Unfitted(_) => "not_converged",
            _ => "failed",
        }
    }
}

impl Serialize for RunError {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(2))?;
        m.serialize_entry("kind", self.kind())?;
        m.serialize_entry("message", &self.to_string())?;
        m.end()
    }
}

/// A sample of a solution field that is NaN or ±∞.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("non-finite {field} ({value}) at σ = {sigma:.6} m")]
pub struct NonFiniteSample {
    /// Field name: `x`, `y`, `deflection`, `tension`, `moment`, `contact pressure`,
    /// `friction traction`, `shear strain`.
    pub field: &'static str,
    /// The value.
    pub value: f64,
    /// Where, m.
    pub sigma: f64,
}

/// A solution method the harness can run at any discretisation of its family.
pub trait Method: Send + Sync {
    /// Label in tables and plots, e.g. `bvp-collocation gauss6` or `fem string-mel`.
    fn label(&self) -> String;
    /// BVP (refined by tolerance) or FE (refined by mesh).
    fn family(&self) -> Family;
    /// Solve `scene` at `disc` (a [`Discretisation::Tolerance`] for BVP methods, a
    /// [`Discretisation::Elements`] for FE methods).
    ///
    /// # Errors
    /// [`RunError::NotApplicable`] if the method has no model for the scene,
    /// [`RunError::Failed`] otherwise.
    fn solve(&self, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError>;
}

/// The solve function of a [`FnMethod`].
pub type SolveFn = dyn Fn(&Scene, Discretisation) -> Result<Solved, RunError> + Send + Sync;

/// A method made of a label, a family and a solve function — for a test or an
/// experiment that wraps, perturbs or stubs a method without a type of its own.
pub struct FnMethod {
    label: String,
    family: Family,
    solve: Box<SolveFn>,
}

impl FnMethod {
    /// The method `label` of `family` that solves by `solve`.
    pub fn new(label: &str, family: Family, solve: impl Fn(&Scene, Discretisation) -> Result<Solved, RunError> + Send + Sync + 'static) -> FnMethod {
        FnMethod { label: label.to_string(), family, solve: Box::new(solve) }
    }
}

impl Method for FnMethod {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn family(&self) -> Family {
        self.family
    }

    fn solve(&self, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError> {
        (self.solve)(scene, disc)
    }
}

// ---------------------------------------------------------------------------
// The built-in methods

/// A BVP variant: collocation with a given scheme, or shooting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BvpVariant {
    /// Collocation with this Gauss–Legendre scheme.
    Collocation(Scheme),
    /// Multiple shooting.
    Shooting,
}

impl BvpVariant {
    /// `bvp-collocation gauss6`, `bvp-shooting`.
    pub fn label(self) -> String {
        match self {
            BvpVariant::Collocation(s) => format!("bvp-collocation {}", s.name()),
            BvpVariant::Shooting => "bvp-shooting".to_string(),
        }
    }
}

/// A BVP method of crate `bvp`, run at a tolerance. Other options (shooting intervals,
/// Jacobians) come from the scene's `bvp` block; the collocation mesh cap is the
/// scene's `bvp.max_nodes` unless [`BvpSolver::max_nodes`] overrides it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvpSolver {
    /// Collocation scheme or shooting.
    pub variant: BvpVariant,
    /// Override of the collocation mesh cap (`None` = the scene's).
    pub max_nodes: Option<usize>,
}

impl BvpSolver {
    /// The variant with the scene's mesh cap.
    pub fn new(variant: BvpVariant) -> Self {
        BvpSolver { variant, max_nodes: None }
    }
}

impl Method for BvpSolver {
    fn label(&self) -> String {
        self.variant.label()
    }

    fn family(&self) -> Family {
        Family::Bvp
    }

    fn solve(&self, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError> {
        let Discretisation::Tolerance(tolerance) = disc else {
            return Err(RunError::Failed(format!("{}: a BVP method is refined by tolerance, not by {disc}", self.label())));
        };
        let mut opts = BvpRunOptions::from_scene(scene).map_err(|e| RunError::Bvp(e.into()))?;
        opts.tolerance = tolerance;
        match self.variant {
            BvpVariant::Collocation(s) => {
                opts.method = BvpMethod::Collocation;
                opts.scheme = s;
            }
            BvpVariant::Shooting => opts.method = BvpMethod::Shooting,
        }
        if let Some(n) = self.max_nodes {
            opts.max_nodes = n;
        }
        let run = bvp::scene::solve_scene(scene, &opts).map_err(|e| match e {
            SceneSolveError::Unsupported(m) => RunError::NotApplicable(m),
            SceneSolveError::NotYetSolvable(e) => RunError::NotYetSolvable(e),
            other => RunError::Bvp(other.into()),
        })?;
        let cost = RunCost { mesh_nodes: Some(run.stats.mesh_nodes), ..RunCost::counted(run.stats.wall_seconds, run.stats.newton_iterations, run.stats.unknowns) };
        Ok(Solved {
            view: run.view,
            summary: run.summary,
            cost,
            options: run.options,
            terms: Vec::new(),
            notes: run.notes,
            warnings: Vec::new(),
            history: None,
            not_steady: None,
            unfitted: None,
        })
    }
}

/// One element formulation of the `fem` registry, by name.
#[derive(Debug, Clone, PartialEq)]
pub struct FemFormulation {
    /// Name from [`fem::available_formulations`].
    pub name: String,
    /// Contact penalty override (`None` = the scene's `fem.penalty`, else the fem
    /// crate's choice).
    pub penalty: Option<f64>,
}

impl FemFormulation {
    /// Every registered formulation, in registry order: the harness discovers them, so
    /// a newly registered formulation is studied, reported and gated with no change
    /// here.
    pub fn discovered() -> Vec<FemFormulation> {
        fem::available_formulations().into_iter().map(|n| FemFormulation { name: n.to_string(), penalty: None }).collect()
    }
}

impl Method for FemFormulation {
    fn label(&self) -> String {
        format!("fem {}", self.name)
    }

    fn family(&self) -> Family {
        Family::Fem
    }

    fn solve(&self, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError> {
        let Discretisation::Elements(elements) = disc else {
            return Err(RunError::Failed(format!("{}: an FE method is refined by mesh, not by {disc}", self.label())));
        };
        if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Fem) {
            return Err(RunError::NotYetSolvable(e));
        }
        if scene.belt.theory == Theory::Shell {
            return Err(RunError::NotApplicable(format!("formulation `{}` is a rod or string element; the shell is solved by `{SHELL_FE}` ([`ShellFe`])", self.name)));
        }
        if let Some(theory) = formulation_theory(&self.name).filter(|&t| t != scene.belt.theory) {
            return Err(RunError::NotApplicable(format!(
                "formulation `{}` discretises theory `{theory}`, the scene's belt is theory `{}` (its formulations: {})",
                self.name,
                scene.belt.theory,
                list_or_none(&fem::formulations_for(scene.belt.theory))
            )));
        }
        let opts = fem::FemOptions {
            elements,
            formulation: self.name.clone(),
            penalty: self.penalty.or(scene.fem_settings().penalty),
        };
        let run = fem::solve_scene(scene, &opts).map_err(|e| match e {
            fem::FemError::Unsupported(_) => RunError::NotApplicable(no_fe_model(scene)),
            fem::FemError::NotYetSolvable(e) => RunError::NotYetSolvable(e),
            #[allow(unreachable_patterns)]
            other => RunError::Fem(other),
        })?;
        let not_steady = fem_not_steady(&run.options);
        let cost = RunCost { elements: Some(run.stats.elements), ..RunCost::counted(run.stats.wall_seconds, run.stats.newton_iterations, run.stats.unknowns) };
        Ok(Solved {
            view: run.view,
            summary: run.summary,
            cost,
            options: run.options,
            notes: vec![format!("homotopy: {} steps", run.stats.homotopy_steps)],
            // the FE's notes are its stated warnings (an unresolved bending layer or slip zone)
            warnings: run.notes,
            terms: run.terms,
            history: run.history.map(Into::into),
            not_steady,
            unfitted: run.unfitted,
        })
    }
}

/// The Kirchhoff–Love shell's FE (Bogner–Fox–Schmit elements over (σ, ζ), stages 0–2
/// of docs/fem-shell.md §9, [`fem::shell::scene::solve`]), refined by a
/// [`Discretisation::Mesh2d`]: the scene's `fem.elements_sigma`, `fem.elements_zeta` and
/// `fem.time_step` are replaced by it (the rotation keeps its simulated time
/// `steps` × Δt of the scene).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ShellFe;

/// The method label of [`ShellFe`].
pub const SHELL_FE: &str = "fem shell-bfs";

/// The name of [`ShellFe`] as a Richardson reference names its formulation
/// ([`crate::reference::Reference::Richardson`]): the shell's element is not in the
/// `fem` registry of 1-D formulations, so a reference of this name runs [`ShellFe`].
pub const SHELL_FORMULATION: &str = "shell-bfs";

impl ShellFe {
    /// The scene with its `fem` block at `sigma` × `zeta` elements and the time step
    /// `time_step`, keeping the simulated time of the rotation (`steps` × Δt of the
    /// scene), validated.
    ///
    /// # Errors
    /// The scene's validation error at that discretisation (e.g. an odd n_ζ), or
    /// `fem.steps` when the rotation is not a whole number of the level's steps (the
    /// levels would not compare one simulated time).
    pub fn scene_at(scene: &Scene, sigma: usize, zeta: usize, time_step: f64) -> Result<Scene, drive::error::SceneError> {
        let mut scene = scene.clone();
        let own = scene.shell_run();
        let mut f = scene.fem_settings();
        let rotation = own.steps as f64 * own.time_step;
        let steps = rotation / time_step;
        if (steps - steps.round()).abs() > 1e-6 * steps.max(1.0) || steps.round() < 1.0 {
            return Err(drive::error::SceneError::Invalid {
                path: "fem.steps".into(),
                reason: format!(
                    "the rotation of {} steps of {} s is not a whole number of steps of {} s ({steps:.4}): the level would simulate another time; choose steps divisible by the σ refinement ratio",
                    own.steps,
                    drive::error::num(&own.time_step),
                    drive::error::num(&time_step)
                ),
            });
        }
        (f.elements_sigma, f.elements_zeta, f.time_step, f.duration) = (Some(sigma), Some(zeta), Some(time_step), None);
        f.steps = Some(steps.round() as usize);
        scene.fem = Some(f);
        scene.validate()?;
        Ok(scene)
    }

    /// The scene's discretisation refined to `sigma` × `zeta` elements with the time
    /// step scaled like the σ spacing (Δt = Δt_scene · n_σ,scene / `sigma`): the levels of
    /// a shell study, where space and time are refined together.
    pub fn level(scene: &Scene, sigma: usize, zeta: usize) -> Discretisation {
        let run = scene.shell_run();
        Discretisation::Mesh2d { sigma, zeta, time_step: run.time_step * run.elements_sigma as f64 / sigma as f64 }
    }
}

impl ShellFe {
    /// The run a solve of `scene` makes: its `fem` block with the defaults, n_ζ when not
    /// given the fewest elements that resolve the belt's edge layer
    /// (`fem::shell::scene::run_of`); for a scene the shell does not model (which fails in
    /// the solve with its own error) the scene's settings.
    pub fn run_of(scene: &Scene) -> drive::ShellRun {
        fem::shell::scene::run_of(scene).unwrap_or_else(|_| scene.shell_run())
    }

    /// The scene's own discretisation ([`Self::run_of`]).
    pub fn discretisation(scene: &Scene) -> Discretisation {
        let run = ShellFe::run_of(scene);
        Discretisation::Mesh2d { sigma: run.elements_sigma, zeta: run.elements_zeta, time_step: run.time_step }
    }
}

impl Method for ShellFe {
    fn label(&self) -> String {
        SHELL_FE.to_string()
    }

    fn family(&self) -> Family {
        Family::Fem
    }

    fn solve(&self, scene: &Scene, disc: Discretisation) -> Result<Solved, RunError> {
        let Discretisation::Mesh2d { sigma, zeta, time_step } = disc else {
            return Err(RunError::Failed(format!("{SHELL_FE}: the shell is refined by a mesh over (σ, ζ) and a time step, not by {disc}")));
        };
        if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Fem) {
            return Err(RunError::NotYetSolvable(e));
        }
        if scene.belt.theory != Theory::Shell {
            return Err(RunError::NotApplicable(format!("{SHELL_FE} discretises theory `shell`, the scene's belt is theory `{}`", scene.belt.theory)));
        }
        let scene = ShellFe::scene_at(scene, sigma, zeta, time_step).map_err(|e| RunError::Failed(format!("{SHELL_FE} at {disc}: {e}")))?;
        let (rule, width_rule) = (scene.shell_run().contact_rule.label(), scene.shell_run().contact_rule_width.label());
        let run = fem::shell::scene::solve(&scene).map_err(|e| match e {
            fem::shell::ShellError::NotModelled(m) => RunError::NotApplicable(m),
            other => RunError::Shell(other),
        })?;
        let cost = RunCost { elements: Some(sigma * zeta), ..RunCost::counted(0.0, run.newton_iterations, run.unknowns) };
        let [stage0, ramp, rotation] = run.stage_seconds;
        Ok(Solved {
            view: Box::new(run.view),
            summary: run.summary,
            cost,
            options: run.options,
            terms: vec![
                "membrane (Simpson × Gauss 3, camber as intrinsic strain)".into(),
                "bending and gravity (Gauss 3 × 3)".into(),
                format!("elastic interlayer V_γ, V_⊥ with advected history ({rule} × {width_rule})"),
            ],
            notes: [vec![format!("stages: static start {stage0:.2} s, ramp {ramp:.2} s, rotation {rotation:.2} s")], run.checks.iter().map(|c| format!("check: {c}")).collect()].concat(),
            warnings: run.warnings,
            history: Some(run.history),
            not_steady: None,
            unfitted: None,
        })
    }
}

/// The belt theory a registered formulation discretises (`None` if not registered) —
/// built-in or added from outside `fem` by [`fem::register_formulation`] or
/// [`fem::formulation::register_element`] (an element of any layout).
pub fn formulation_theory(name: &str) -> Option<Theory> {
    fem::formulation::find_element(name).map(|k| k.theory())
}

/// Names of the registered FE formulations, default first.
pub fn registered_formulations() -> Vec<&'static str> {
    fem::available_formulations()
}

/// The default FE formulation of a scene: its first `fem.formulations`, else the first
/// registered formulation of its belt theory (a rod scene gets a rod formulation).
///
/// # Errors
/// [`RunError::NotYetSolvable`] for a layout or theory the FE does not solve yet;
/// [`RunError::NotApplicable`] if no registered formulation discretises the theory.
pub fn default_formulation(scene: &Scene) -> Result<String, RunError> {
    if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Fem) {
        return Err(RunError::NotYetSolvable(e));
    }
    if scene.belt.theory == Theory::Shell {
        return Ok(SHELL_FE.to_string());
    }
    if let Some(first) = scene.fem_settings().formulations.first() {
        return Ok(first.clone());
    }
    let theory = scene.belt.theory;
    fem::formulations_for(theory).first().map(|n| n.to_string()).ok_or_else(|| {
        RunError::NotApplicable(format!("no registered FE formulation discretises theory `{theory}` (registered: {})", list_or_none(&registered_formulations())))
    })
}

fn list_or_none(names: &[&str]) -> String {
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}

/// Why the FE has no model for a scene, in words: the scene's model and the models the
/// FE has (the `fem` crate's own message names Rust types and an older list).
fn no_fe_model(scene: &Scene) -> String {
    let contact = match scene.effects.contact {
        drive::scene::Contact::Frictionless => "frictionless contact".to_string(),
        drive::scene::Contact::Coulomb(mu) => format!("Coulomb friction (μ = {})", drive::error::num(&mu)),
        drive::scene::Contact::ElasticLayer(_) => "an elastic interlayer".to_string(),
    };
    format!(
        "no MEL finite element model for a {} belt, analysis `{}`, with {contact}; the MEL models are: the string and the Kirchhoff rod hanging on frictionless pulleys (static), and the string friction drive (steady and transient, Coulomb friction)",
        scene.belt.theory, scene.analysis
    )
}

/// A transient FE run that stopped before its steady state, read from the run's
/// options (`drive.steady`, `drive.steps`, `drive.final_change_rate`,
/// `drive.settings.steady_tolerance`, written by `fem::string_drive::solve`).
fn fem_not_steady(options: &serde_json::Value) -> Option<NotSteady> {
    let drive = options.get("drive")?;
    if drive.get("steady")?.as_bool()? {
        return None;
    }
    Some(NotSteady {
        steps: drive.get("steps").and_then(serde_json::Value::as_u64).map_or(0, |n| n as usize),
        rate: drive.get("final_change_rate").and_then(serde_json::Value::as_f64).unwrap_or(f64::INFINITY),
        tolerance: drive.pointer("/settings/steady_tolerance").and_then(serde_json::Value::as_f64).unwrap_or(f64::NAN),
    })
}

// ---------------------------------------------------------------------------
// Sampling and executing

/// A solution sampled through the common view at σ_i = i·L_geom/n, i = 0..n (uniform,
/// periodic: the rectangle rule on these points is the trapezoidal rule of the loop).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Samples {
    /// σ, m.
    pub sigma: Vec<f64>,
    /// x of r(σ), m.
    pub x: Vec<f64>,
    /// y of r(σ), m.
    pub y: Vec<f64>,
    /// Transverse deflection ν(σ), m.
    pub deflection: Vec<f64>,
    /// Axial force N(σ), N.
    pub tension: Vec<f64>,
    /// Bending moment M(σ), N·m; `None` for a string.
    pub moment: Option<Vec<f64>>,
    /// Contact state at σ.
    pub state: Vec<ContactState>,
    /// Contact pressure (normal traction) p(σ), N/m; `None` if the model has none.
    pub pressure: Option<Vec<f64>>,
    /// Friction traction τ(σ) on the belt, N/m, + along σ; `None` without friction.
    pub friction: Option<Vec<f64>>,
    /// The contact pressure and shear strain of a shear-deformable rod on a σ grid
    /// refined at the contact edges, for the plots; `None` for a model without a shear
    /// strain (string, Kirchhoff rod) or with no distributed pressure. Never used by the
    /// error norms, which stay on the uniform grid.
    pub edges: Option<EdgeDetail>,
}

/// The fields of a shear-deformable rod that change over its shear layer √(a/b₂) at the
/// contact edges (a few mm, about the uniform sample spacing of a study), sampled where
/// they change: the uniform grid of [`Samples`] merged with, at every change of the
/// contact state found on it, the two ends of a bisected bracket of the edge (width
/// ≤ [`EdgeDetail::BRACKET`]·L) and [`EdgeDetail::CLUSTER`] points on each side at the
/// distances 2Δ·qʲ, j = 0 … CLUSTER − 1 (Δ = L/n the uniform spacing, q =
/// [`EdgeDetail::RATIO`]: from 2Δ down to about 3e-7·Δ from the edge).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct EdgeDetail {
    /// σ in [0, L], increasing, m.
    pub sigma: Vec<f64>,
    /// Contact pressure p(σ), N per metre of contour.
    pub pressure: Vec<f64>,
    /// Shear strain Γ₂(σ) (dimensionless).
    pub shear_strain: Vec<f64>,
    /// Contact state at σ.
    pub state: Vec<ContactState>,
    /// The contact-side σ of every bisected state change, in σ order, m.
    pub edges: Vec<f64>,
}

impl EdgeDetail {
    /// Points on each side of an edge.
    pub const CLUSTER: usize = 56;
    /// Ratio of successive distances from the edge.
    pub const RATIO: f64 = 0.75;
    /// Width of the bisected bracket of an edge, relative to L.
    pub const BRACKET: f64 = 1e-13;

    /// Samples `view` on the uniform grid `sigma` (with its contact states `state`)
    /// refined at the state changes; `None` if the view has no shear strain or no
    /// pressure at σ = 0.
    ///
    /// # Errors
    /// The first non-finite pressure or shear strain.
    fn of_view(view: &dyn SolutionView, sigma: &[f64], state: &[ContactState]) -> Result<Option<EdgeDetail>, NonFiniteSample> {
        let n = sigma.len();
        if n == 0 || view.shear_strain(sigma[0]).is_none() || view.contact_pressure(sigma[0]).is_none() {
            return Ok(None);
        }
        let path = view.path();
        let l = path.length();
        let h = l / n as f64;
        // (a, b): the last uniform point of one state and the first of the next; on the
        // loop the pair (σ_(n−1), L) closes it.
        let mut brackets: Vec<(f64, f64)> = (1..n).filter(|&i| state[i] != state[i - 1]).map(|i| (sigma[i - 1], sigma[i])).collect();
        if !path.is_open() && state[n - 1] != state[0] {
            brackets.push((sigma[n - 1], l));
        }
        let mut points: Vec<f64> = sigma.to_vec();
        if path.is_open() {
            points.push(l);
        }
        let mut edges = Vec::with_capacity(brackets.len());
        for (mut a, mut b) in brackets {
            let left = view.contact_state(a);
            while b - a > Self::BRACKET * l {
                let m = 0.5 * (a + b);
                if view.contact_state(path.wrap(m)) == left {
                    a = m;
                } else {
                    b = m;
                }
            }
            edges.push(if left == ContactState::Free { b } else { a });
            points.extend([a, b]);
            let mut d = 2.0 * h;
            for _ in 0..Self::CLUSTER {
                points.extend([a - d, b + d]);
                d *= Self::RATIO;
            }
        }
        // Into the domain: wrapped on the loop (σ = L is σ = 0 there), clipped on the
        // open contour.
        let mut points: Vec<f64> = if path.is_open() {
            points.into_iter().filter(|s| (0.0..=l).contains(s)).collect()
        } else {
            points.into_iter().map(|s| path.wrap(s)).filter(|&s| s < l).collect()
        };
        points.sort_by(f64::total_cmp);
        points.dedup();
        edges.iter_mut().for_each(|s| *s = path.wrap(*s));
        edges.sort_by(f64::total_cmp);
        let mut d = EdgeDetail { edges, ..EdgeDetail::default() };
        for s in points {
            let p = view.contact_pressure(s).unwrap_or(f64::NAN);
            if !p.is_finite() {
                return Err(NonFiniteSample { field: "contact pressure", value: p, sigma: s });
            }
            let g = view.shear_strain(s).unwrap_or(f64::NAN);
            if !g.is_finite() {
                return Err(NonFiniteSample { field: "shear strain", value: g, sigma: s });
            }
            d.sigma.push(s);
            d.pressure.push(p);
            d.shear_strain.push(g);
            d.state.push(view.contact_state(s));
        }
        Ok(Some(d))
    }
}

impl Samples {
    /// Samples `view` at `n` uniform points; the first non-finite value is an error
    /// naming the field and σ.
    ///
    /// # Errors
    /// The first non-finite sample, e.g. `non-finite tension (NaN) at σ = 0.3 m`.
    pub fn of_view(view: &dyn SolutionView, n: usize) -> Result<Samples, NonFiniteSample> {
        let l = view.path().length();
        let mut s = Samples::default();
        let mut moment = Vec::with_capacity(n);
        let mut has_moment = n > 0;
        let mut pressure = Vec::with_capacity(n);
        let mut has_pressure = n > 0;
        let mut friction = Vec::with_capacity(n);
        let mut has_friction = n > 0;
        for i in 0..n {
            let sigma = l * i as f64 / n as f64;
            let p = view.position(sigma);
            let nu = view.deflection(sigma);
            let t = view.axial_force(sigma);
            for (name, v) in [("x", p[0]), ("y", p[1]), ("deflection", nu), ("tension", t)] {
                if !v.is_finite() {
                    return Err(NonFiniteSample { field: name, value: v, sigma });
                }
            }
            match view.bending_moment(sigma) {
                Some(m) if m.is_finite() => moment.push(m),
                Some(m) => return Err(NonFiniteSample { field: "moment", value: m, sigma }),
                None => has_moment = false,
            }
            match view.contact_pressure(sigma) {
                Some(p) if p.is_finite() => pressure.push(p),
                Some(p) => return Err(NonFiniteSample { field: "contact pressure", value: p, sigma }),
                None => has_pressure = false,
            }
            match view.friction_traction(sigma) {
                Some(f) if f.is_finite() => friction.push(f),
                Some(f) => return Err(NonFiniteSample { field: "friction traction", value: f, sigma }),
                None => has_friction = false,
            }
            s.sigma.push(sigma);
            s.x.push(p[0]);
            s.y.push(p[1]);
            s.deflection.push(nu);
            s.tension.push(t);
            s.state.push(view.contact_state(sigma));
        }
        s.moment = has_moment.then_some(moment);
        s.pressure = has_pressure.then_some(pressure);
        s.friction = has_friction.then_some(friction);
        s.edges = EdgeDetail::of_view(view, &s.sigma, &s.state)?;
        Ok(s)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.sigma.len()
    }

    /// True without samples.
    pub fn is_empty(&self) -> bool {
        self.sigma.is_empty()
    }

    /// The samples of a field by its norm prefix: `deflection`, `tension`, `moment`,
    /// `pressure`, `friction`.
    pub fn field(&self, name: &str) -> Option<&[f64]> {
        match name {
            "deflection" => Some(&self.deflection),
            "tension" => Some(&self.tension),
            "moment" => self.moment.as_deref(),
            "pressure" => self.pressure.as_deref(),
            "friction" => self.friction.as_deref(),
            _ => None,
        }
    }
}

/// The outcome of a successful run, as the harness keeps it.
#[derive(Debug, Clone, Serialize)]
pub struct RunData {
    /// Named scalars.
    pub summary: Summary,
    /// Work spent.
    pub cost: RunCost,
    /// Options used.
    pub options: serde_json::Value,
    /// Terms the method assembled (FE), or empty.
    pub terms: Vec<String>,
    /// Diagnostics of the method.
    pub notes: Vec<String>,
    /// Stated warnings about the result ([`Solved::warnings`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// The solution on the harness's σ grid (not serialised: reports write the fields
    /// they plot).
    #[serde(skip)]
    pub samples: Samples,
    /// Quantities in time (a transient's channels and frames: the shell's lateral
    /// positions and surface fields), for the report's plots; not serialised.
    #[serde(skip)]
    pub history: Option<drive::result::TimeSeries>,
}

/// One run: method + discretisation → data or error.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    /// Method label.
    pub method: String,
    /// BVP or FE.
    pub family: Family,
    /// Tolerance or elements.
    pub discretisation: Discretisation,
    /// Wall time of the solve call, s — also for a run that failed (failing costs time
    /// too).
    pub wall_seconds: f64,
    /// The solution, or why there is none.
    pub outcome: Result<RunData, RunError>,
}

impl Run {
    /// The data of a successful run.
    pub fn data(&self) -> Option<&RunData> {
        self.outcome.as_ref().ok()
    }

    /// Wall time of the run, s (`None` only if the clock gave a non-finite number).
    pub fn wall_seconds(&self) -> Option<f64> {
        self.wall_seconds.is_finite().then_some(self.wall_seconds)
    }
}

/// Runs `method` on `scene` at `disc`, timing the solve and sampling the solution at
/// `samples` uniform σ points. A summary or sample that is not finite turns the run
/// into a [`RunError::Failed`] (no NaN reaches a table).
pub fn execute(method: &dyn Method, scene: &Scene, disc: Discretisation, samples: usize) -> Run {
    let start = Instant::now();
    let solved = solve_timed(method, scene, disc);
    let wall = start.elapsed().as_secs_f64();
    let outcome = solved.and_then(|s| {
        if let Some(n) = s.not_steady {
            return Err(RunError::NotSteady(n));
        }
        if let Some(u) = s.unfitted.filter(fem::fitting::Unfitted::not_converged) {
            return Err(RunError::Unfitted(u));
        }
        s.summary.check_finite()?;
        let samples = Samples::of_view(s.view.as_ref(), samples)?;
        let cost = s.cost;
        Ok(RunData { summary: s.summary, cost, options: s.options, terms: s.terms, notes: s.notes, warnings: s.warnings, samples, history: s.history })
    });
    Run { method: method.label(), family: method.family(), discretisation: disc, wall_seconds: wall, outcome }
}
