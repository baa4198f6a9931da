//! `fem`: mixed Eulerian–Lagrangian (MEL) finite elements of belt drives — the second,
//! independent way beltcheck computes a scene.
//!
//! Role (DESIGN.md, "The MEL finite elements"): elements sit at fixed points of the
//! looped contour coordinate σ of [`drive::contour::Contour`] while material flows
//! through the mesh. Primary unknowns are the material coordinate s(σ) and the transverse
//! deflection ν(σ) (eq. 27), approximated by cubic Hermite functions (eq. 43); each effect
//! of a scene (strain energy, gravity, contact) is one energy term over elements,
//! assembled only when the scene calls for it; element derivatives come from
//! forward-mode AD; global systems are solved by Newton on faer's sparse LU with homotopy
//! from tight to slack configurations (§7.1). Solutions implement
//! [`drive::view::SolutionView`], so the verification harness compares them with the BVP
//! references without either crate seeing the other (`fem` never depends on `bvp`).
//! The equations, signs and measured numbers are in `docs/fem-string.md` (string) and
//! `docs/fem-rod.md` (Kirchhoff rod: bending energy, C¹ augmented approximations at the
//! Cartesian/polar transitions, contact edges and edge forces).
//!
//! # Layers (in algorithm order)
//! - [`mesh`]: nodes at fixed σ, element boundaries on the four region transitions, and
//!   meshes fitted to the contact boundaries;
//! - [`hermite`], [`quadrature`]: shape functions (eq. 43), integration rules (§7.3);
//! - [`element`]: element field layouts and dimension (1-D {s, ν}, {s, ν, θ}; 2-D
//!   {S, ν, z}), the index map, the 2-D element interface and the Bogner–Fox–Schmit
//!   rectangle for the shell;
//! - [`kinematics`]: fields, position, stretch and gap of an element (eqs. 27, 37, 38);
//! - [`formulation`]: the plug-in trait [`formulation::Formulation`], the energy terms,
//!   exact derivatives by AD, and the registry;
//! - [`dofs`], [`assembly`], [`linear`], [`newton`]: numbering with loop closure and the
//!   material gauge s(0) = 0, parallel assembly, sparse LU, Newton with line search and
//!   Levenberg–Marquardt regularisation;
//! - [`problem`]: the typed problem built once from the scene ([`FemProblem`]);
//! - [`static_homotopy`]: the static string (or Kirchhoff rod, with EI) on frictionless
//!   pulleys — tight start (F11), homotopy with step control, penalty continuation,
//!   contact fitting — generic over the element's layout;
//! - [`solution`]: the converged solution behind the common view — recovered axial force
//!   and contact pressure, contact boundaries recovered from the free spans, summary;
//! - [`stamp`]: a standalone check: the linearised rod on a rigid stamp (§6.3, Fig. 5a)
//!   against its closed form — how a penalty FE carries concentrated edge forces;
//! - [`stamp_cosserat`]: its shearable (Cosserat, Fig. 5b, check C-10) version — closed
//!   form with finite edge pressure peaks, and a locking-free Timoshenko penalty FE;
//! - [`surface`], [`analysis`]: the 2-D discretisation over (σ, ζ) (periodic BFS mesh,
//!   numbering, assembly over a surface kernel, per-point history advected along σ) and
//!   the time stepping with history and optional inertia the shell runs on
//!   (docs/fem-time-stepping.md);
//! - [`string_drive`]: the friction drive (analyses `steady`, `transient` with Coulomb
//!   contact) — quasistatic transient from the static solution, augmented Lagrangian
//!   Coulomb contact of Table 1, driven rotation with its torque balance, transport
//!   inertia, steady-state criterion, time history (docs/fem-drive.md).
//!
//! Defaults: `string-simpson`, 256 elements (the scene's `fem.elements`), penalty
//! P = 10⁵ EA/R² ([`SolverSettings`]). Measured accuracy against the BVP at 256
//! elements: heights 1e-8 m, tensions 6e-7 relative, contact angles 2e-7 rad
//! (docs/fem-string.md §12).
//!
//! # Adding an element formulation
//! No fork needed: in any crate, implement [`Formulation`] (a name, a strain energy
//! density, the integration rule of each term — or a whole element energy) against the
//! re-exports of [`formulation`] ([`formulation::ElementContext`],
//! [`formulation::TermRules`], [`formulation::Rule`], [`Scalar`],
//! [`formulation::Theory`], …) and call [`register_formulation`] once at start-up.
//! Assembly, solvers, the view and the harness need no change and find it by name; the
//! workspace's `examples/custom_formulation.rs` defines one, runs `converge` and the
//! `gate` with it. A formulation shipped with `fem` is a file in `fem/src/formulation/`
//! and one line in its built-in list; the AD-vs-finite-difference unit test covers every
//! built-in formulation automatically. An element of another 1-D layout (the Cosserat
//! rod's {s, ν, θ}, 12 unknowns) implements [`assembly::ElementKernel`] and
//! [`formulation::layout::LayoutElement`] and is registered by name with
//! [`formulation::register_element`]; the static analysis and the solution view run it
//! monomorphised for its layout (the drive analyses take the string layout only).
//!
//! # Entry points (the contract of the CLI and the verification harness)
//! [`available_formulations`] (the registry, by name), [`register_formulation`],
//! [`default_formulation`],
//! [`FemOptions::from_scene`] and [`solve_scene`] (or [`solve_scene_with`] with explicit
//! [`SolverSettings`]).
//!
//! ```no_run
//! let scene = drive::Scene::from_path(std::path::Path::new("scenes/string-hanging.json")).unwrap();
//! let opts = fem::FemOptions::from_scene(&scene, fem::default_formulation());
//! let run = fem::solve_scene(&scene, &opts).unwrap();
//! println!("{:?} ({} Newton iterations)", run.summary.tension_upper_mid, run.stats.newton_iterations);
//! ```

use std::time::Instant;

use drive::scene::{Analysis, Scene, Theory};
use drive::summary::Summary;
use drive::view::SolutionView;

pub mod admissibility;
pub mod analysis;
pub mod assembly;
pub mod dofs;
pub mod element;
mod error;
pub mod fitting;
pub mod formulation;
pub mod hermite;
pub mod kinematics;
pub mod linear;
pub mod mesh;
pub mod newton;
mod options;
pub mod problem;
pub mod quadrature;
pub mod shell;
pub mod solution;
pub mod stamp;
pub mod stamp_cosserat;
pub mod string_drive;
pub mod static_homotopy;
pub mod surface;
#[cfg(test)]
mod test_rng;

pub use error::{FemError, NewtonFailure};
pub use formulation::{Formulation, RegistryError};
pub use numerics::Scalar;
pub use options::{FemOptions, SolverSettings};
pub use problem::FemProblem;
pub use solution::FemSolution;
pub use static_homotopy::{HomotopyReport, StringHanging};

/// Work of an FE run.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct FemStats {
    /// Wall time of the whole run (homotopy included), s.
    pub wall_seconds: f64,
    /// Newton iterations summed over the homotopy.
    pub newton_iterations: usize,
    /// Unknowns of the global system.
    pub unknowns: usize,
    /// Elements.
    pub elements: usize,
    /// Homotopy steps (accepted points, the start included).
    pub homotopy_steps: usize,
}

/// An FE run: the solution behind the common view, its summary and cost.
pub struct FemRun {
    /// The solution, sampled through the common view.
    pub view: Box<dyn SolutionView + Send + Sync>,
    /// The summary.
    pub summary: Summary,
    /// Work counters.
    pub stats: FemStats,
    /// Options used (for reproducibility): the [`FemOptions`] with the penalty resolved,
    /// the [`SolverSettings`], the homotopy report ([`HomotopyReport`]) and, per pulley,
    /// whether both contact boundaries were recovered from the free spans
    /// (docs/fem-string.md §10).
    pub options: serde_json::Value,
    /// The energy terms assembled (the effects simulated), e.g.
    /// "strain energy (Biot, gauss3, EA = 2.000000e4 N)".
    pub terms: Vec<String>,
    /// Time history of a drive transient (docs/fem-drive.md §8); `None` for static runs.
    pub history: Option<drive::result::History>,
    /// Stated warnings about the result (e.g. an unresolved bending layer,
    /// docs/fem-rod.md §10); empty for a clean result.
    pub notes: Vec<String>,
    /// `Some` for a static run whose contact fitting did not converge (docs/fem-string.md
    /// §5): the result is the best fitted solution, not a converged one (also one of the
    /// `notes`); `None` for the other analyses and a converged or unfitted-by-option run.
    pub unfitted: Option<fitting::Unfitted>,
}

/// Names of the registered element formulations: the built-in ones (default first), then
/// those added by [`register_formulation`] in registration order.
pub fn available_formulations() -> Vec<&'static str> {
    formulation::elements().iter().map(|k| k.name()).collect()
}

/// Names of the registered formulations that discretise `theory` (registry order):
/// `string-*` for strings, `rod-*` for Kirchhoff rods (docs/fem-rod.md §4).
pub fn formulations_for(theory: Theory) -> Vec<&'static str> {
    formulation::elements().iter().filter(|k| k.theory() == theory).map(|k| k.name()).collect()
}

/// Register an element formulation defined outside this crate, process-wide: from then
/// on [`solve_scene`], [`available_formulations`], [`formulations_for`] and the
/// verification harness (`converge`, `report`, `gate`) treat it like a built-in one. See
/// [`formulation::register`] (why the registry is process-wide, and the checks).
///
/// # Errors
/// [`RegistryError`]: an empty or malformed name, a name already registered, an
/// integration rule that does not exist.
pub fn register_formulation<F: formulation::Formulation>(f: F) -> Result<(), RegistryError> {
    formulation::register(f)
}

/// The default formulation (`string-simpson`: the Simpson rule samples the strain where
/// the Hermite element reproduces it best, §7.3 — its axial-force field is free of the
/// membrane locking that `string-gauss` shows where the belt wraps a pulley inside a
/// Cartesian region; docs/fem-string.md §6, §12).
pub fn default_formulation() -> &'static str {
    "string-simpson"
}

/// Solve a scene with MEL finite elements and the default [`SolverSettings`].
///
/// # Errors
/// See [`solve_scene_with`].
pub fn solve_scene(scene: &Scene, opts: &FemOptions) -> Result<FemRun, FemError> {
    solve_scene_with(scene, opts, &SolverSettings::default())
}

/// The physical data of a static string scene with the penalty resolved
/// (P = `opts.penalty` or κ EA/R²).
///
/// # Errors
/// [`FemError::Unsupported`] for any other kind of scene.
pub fn string_hanging_data(scene: &Scene, opts: &FemOptions, settings: &SolverSettings) -> Result<StringHanging, FemError> {
    FemProblem::from_scene(scene).static_data(opts, settings)
}

/// Solve a scene with MEL finite elements: the static string (`string-hanging`), or
/// the friction drive (`string-drive` with Coulomb contact: analysis `steady` by the
/// direct steady solve [`string_drive::steady::solve`], `transient` by
/// [`string_drive::solve`], with the scene's [`string_drive::DriveSettings`]).
///
/// # Errors
/// Drive scenes: [`FemError::FrictionCapacityExceeded`], [`FemError::SpeedAtOrAboveCritical`], [`FemError::EntrySlip`], [`FemError::DriveStepFailed`],
/// [`FemError::SteadyStateNotReached`] besides the static ones below.
/// [`FemError::NotYetSolvable`] (a one-pulley, Cosserat or shell scene: before anything
/// else), [`FemError::Unsupported`] (not a static string scene), [`FemError::UnknownFormulation`],
/// [`FemError::InvalidOption`], [`FemError::IllPosed`] (weightless slack loop), and the
/// solver failures [`FemError::HomotopyStalled`], [`FemError::NewtonDiverged`],
/// [`FemError::SingularTangent`], [`FemError::NonFinite`], and
/// [`FemError::InadmissibleContact`] (a static solution that is no belt-on-pulley state).
pub fn solve_scene_with(scene: &Scene, opts: &FemOptions, settings: &SolverSettings) -> Result<FemRun, FemError> {
    if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Fem) {
        return Err(e.into());
    }
    if scene.belt.theory == Theory::Shell {
        return Err(FemError::Unsupported("a shell scene is solved by `fem::shell::scene::solve` (Bogner–Fox–Schmit elements over (σ, ζ)), not by the rod and string formulations".into()));
    }
    let mut drive_settings = string_drive::DriveSettings::from_scene(scene);
    drive_settings.stop_at_steady = true;
    solve_problem(&FemProblem::from_scene(scene), opts, settings, &drive_settings)
}

/// Solve a typed problem (built once from the scene by [`FemProblem::from_scene`]):
/// the static analysis, or the friction drive — analysis `steady` by the direct steady
/// solve [`string_drive::steady::solve`], `transient` by [`string_drive::solve`] with
/// `drive_settings`.
///
/// # Errors
/// As [`solve_scene_with`].
pub fn solve_problem(problem: &FemProblem, opts: &FemOptions, settings: &SolverSettings, drive_settings: &string_drive::DriveSettings) -> Result<FemRun, FemError> {
    let clock = Instant::now();
    opts.validate()?;
    settings.validate()?;
    let element = formulation::find_element(&opts.formulation).ok_or_else(|| FemError::UnknownFormulation {
        name: opts.formulation.clone(),
        available: available_formulations().iter().map(|s| s.to_string()).collect(),
    })?;
    if problem.is_string_drive() {
        // the drive analyses run on the string layout only (docs/architecture.md)
        let Some(kernel) = element.string_kernel().cloned() else {
            return Err(FemError::Unsupported(format!(
                "formulation `{}` is an element of the {:?} layout; the drive analyses (steady, transient) run on the string layout {{s, ν}} only",
                element.name(),
                element.layout().fields
            )));
        };
        // `steady`: the direct steady solve (docs/fem-drive.md §12); `transient`: the
        // quasistatic transient run to its steady state, with its history
        let run = if problem.analysis == Analysis::Steady {
            string_drive::steady::solve(problem, opts, settings, drive_settings, kernel)?
        } else {
            refuse_paper_d(drive_settings, "the quasistatic transient")?;
            string_drive::solve(problem, opts, settings, drive_settings, kernel)?
        };
        // the driven pulley's torque balance is a self-check (issue 12 item 6)
        admissibility::check_drive_torque(problem, &run.summary)?;
        return Ok(run);
    }
    if problem.is_cosserat_steady_drive() {
        // the direct steady solve, monomorphised for the Cosserat layout {s, ν, ψ}
        let formulation::RegisteredElement::Cosserat(kernel) = element else {
            return Err(FemError::Unsupported(format!(
                "formulation `{}` discretises theory `{}`, the scene's belt is theory `{}`",
                element.name(),
                element.theory(),
                problem.belt.theory
            )));
        };
        // the scene's shear stiffness b₂ (validated > 0 for theory cosserat)
        let kernel = kernel.for_belt(&problem.belt).unwrap_or(kernel);
        const NC: usize = formulation::layout::NDOF_COSSERAT;
        use string_drive::steady::{element_size, point_size};
        if problem.is_one_pulley() {
            refuse_paper_d(drive_settings, "the one-pulley layout (its transition is prescribed by mode `stick_slip_angle`)")?;
            // the open layout (docs/fem-cosserat.md §12)
            return string_drive::steady::solve_open::<NC, { point_size(NC) }, { element_size(NC) }>(problem, opts, settings, drive_settings, kernel);
        }
        let run = string_drive::steady::solve_layout::<NC, { point_size(NC) }, { element_size(NC) }, dyn formulation::layout::LayoutElement<NC>>(problem, opts, settings, drive_settings, kernel)?;
        admissibility::check_drive_torque(problem, &run.summary)?;
        return Ok(run);
    }
    let data = problem.static_data(opts, settings)?;
    // an element discretises one theory: string elements cannot carry EI, rod
    // elements need it (docs/fem-rod.md §4); the harness prints "not applicable"
    if element.theory() != problem.belt.theory {
        return Err(FemError::Unsupported(format!(
            "formulation `{}` discretises theory `{}`, the scene's belt is theory `{}`",
            element.name(),
            element.theory(),
            problem.belt.theory
        )));
    }
    // the static analysis, monomorphised for the element's layout
    match element {
        formulation::RegisteredElement::String(kernel) => solve_static(&data, kernel, opts, settings, clock, None),
        formulation::RegisteredElement::Cosserat(kernel) => {
            // the scene's shear stiffness b₂ (validated > 0 for theory cosserat)
            let kernel = kernel.for_belt(&problem.belt).unwrap_or(kernel);
            // the augmented-Lagrangian normal contact around the penalty solution
            // (docs/fem-cosserat.md §12.5): the element rebuilt with the multipliers
            let rebuild = |k: &(dyn formulation::layout::LayoutElement<{ formulation::layout::NDOF_COSSERAT }> + 'static), m| k.with_contact_multipliers(Some(m));
            let augmented = (drive_settings.normal_contact == string_drive::steady::NormalContact::AugmentedLagrangian).then_some(StaticAugmented { rebuild: &rebuild, tolerance: drive_settings.contact_tolerance, max_iterations: drive_settings.max_al_iterations });
            solve_static(&data, kernel, opts, settings, clock, augmented)
        }
    }
}

/// Paper D's scheme (`fem.steady_scheme` = `paper-d`) is the steady two-pulley solve's
/// only: refused by name for `what`.
fn refuse_paper_d(drive_settings: &string_drive::DriveSettings, what: &str) -> Result<(), FemError> {
    if drive_settings.steady_scheme == string_drive::steady::SteadyScheme::PaperD {
        return Err(FemError::InvalidOption { field: "steady_scheme", value: "paper-d".into(), reason: format!("Paper D's fixed-topology scheme solves the steady two-pulley drive; {what} has no use for it") });
    }
    Ok(())
}

/// The augmented-Lagrangian normal contact of a static run
/// ([`StringHanging::augment`]): the element with the multipliers, the tolerance
/// (× F_ref/R) and the largest number of multiplier updates.
struct StaticAugmented<'a, const N: usize, K: formulation::layout::LayoutElement<N> + ?Sized> {
    rebuild: &'a static_homotopy::WithMultipliers<K>,
    tolerance: f64,
    max_iterations: usize,
}

/// The static analysis of `data` with the element `kernel` of any 1-D layout (with
/// `augmented`, the augmented-Lagrangian normal contact around the penalty solution, the
/// penalty's with a stated warning where it fails), and the run around its solution
/// (admissibility, summary, terms, options, work).
fn solve_static<const N: usize, K: formulation::layout::LayoutElement<N> + ?Sized + 'static>(
    data: &StringHanging,
    kernel: std::sync::Arc<K>,
    opts: &FemOptions,
    settings: &SolverSettings,
    clock: Instant,
    augmented: Option<StaticAugmented<'_, N, K>>,
) -> Result<FemRun, FemError> {
    let contour = data.contour()?;
    let mesh = mesh::Mesh::new(contour, opts.elements, settings.arc_weight)?;
    let (mut solution, mut report, unknowns) = data.solve(mesh, kernel.clone(), settings)?;
    let mut warnings = Vec::new();
    let contact = augmented.map(|a| match data.augment(solution.clone(), a.rebuild, settings, (a.tolerance, a.max_iterations), &mut report) {
        Ok((s, al)) => {
            solution = s;
            al
        }
        Err((failure, al)) => {
            warnings.push(format!("the augmented Lagrangian of the normal contact did not converge ({failure}): the result is the penalty solve's (P = {} N/m²)", numerics::Sig(data.penalty.unwrap_or(f64::NAN))));
            al
        }
    });
    // a converged discrete equilibrium that is no belt-on-pulley state is an error, an
    // unresolved bending layer a warning (docs/fem-rod.md §10)
    let mut notes = admissibility::check(&solution)?;
    notes.extend(warnings);
    // a contact fitting that did not meet its tolerance: stated, and not converged
    let fitted = settings.contact_fitting && data.penalty.is_some();
    let unfitted = if fitted { report.fit.unfitted(settings.fit_tolerance * contour.length()) } else { None };
    notes.extend(unfitted.as_ref().map(ToString::to_string));
    let summary = solution.summary();
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let mut terms = kernel.term_labels(solution.params());
    if solution.kernel().contact_multipliers().is_some() {
        terms.push("normal contact by the augmented Lagrangian (Table 1; multipliers a field over σ, periodic on the loop, Uzawa updates, docs/fem-cosserat.md §12.5)".into());
    }
    let zone = |p: drive::contour::Pulley| {
        solution.zone(p).map(|z| serde_json::json!({"recovered": z.recovered, "gap_sign_intervals": z.intervals}))
    };
    let mut work = serde_json::json!({
        "homotopy": report,
        "contact_boundaries": {
            "driver": zone(drive::contour::Pulley::Driver),
            "driven": zone(drive::contour::Pulley::Driven),
        },
    });
    if let Some(al) = contact {
        work["contact"] = serde_json::json!(al);
    }
    let options = opts.record(data.penalty, settings, work);
    let stats = FemStats {
        wall_seconds: clock.elapsed().as_secs_f64(),
        newton_iterations: report.newton_iterations,
        unknowns,
        elements: opts.elements,
        homotopy_steps: report.steps,
    };
    Ok(FemRun { view: Box::new(solution), summary, stats, options, terms, history: None, notes, unfitted })
}

#[cfg(test)]
mod tests {
    #[test]
    fn registry_lists_the_shipped_formulations() {
        let names = super::available_formulations();
        assert_eq!(names, vec!["string-simpson", "string-gauss", "rod-simpson", "rod-gauss", "cosserat-gauss", "cosserat-reduced"]);
        assert_eq!(names[0], super::default_formulation());
        assert_eq!(super::formulations_for(drive::scene::Theory::Cosserat), vec!["cosserat-gauss", "cosserat-reduced"]);
    }
}
