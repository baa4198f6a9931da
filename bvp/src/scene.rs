//! From a validated scene to a BVP run: which belt problem the scene is, which method and
//! tolerance solve it, and the outcome as a [`SolutionView`] with its summary and cost.

use drive::scene::{Analysis, Contact, End, Layout, OnePulleyLoad, Scene, Theory};
use drive::summary::Summary;
use drive::view::SolutionView;
use thiserror::Error;

use crate::belt::{BeltError, BeltSolution, SectionLaw};
use crate::problem::JacobianMode;
use crate::cosserat_drive::{self, CosseratDrive, CosseratDriveSolution};
use crate::cosserat_hanging::{self, CosseratHanging};
use crate::cosserat_pulley::{self, CosseratPulley, CosseratPulleySolution, Mode};
use crate::rod_hanging::{self, RodHanging};
use crate::solution::Stats;
use crate::string_drive::{self, StringDrive, StringDriveSolution};
use crate::string_hanging::{self, StringHanging};

pub use crate::belt::{BeltOptions, BvpMethod};

/// Options of a BVP run: the one options struct of the belt problems, its defaults
/// overridden by the scene's `bvp` block ([`BeltOptions::from_scene`]).
pub type BvpRunOptions = BeltOptions;

/// Why a scene has no BVP solution.
#[derive(Debug, Error)]
pub enum SceneSolveError {
    /// The scene asks for a model the BVP crate does not have (yet).
    #[error("no BVP model for this scene: {0}")]
    Unsupported(String),
    /// A layout or theory the contract describes but the BVP does not solve yet (the
    /// issue that brings it is named).
    #[error(transparent)]
    NotYetSolvable(#[from] drive::NotYetSolvable),
    /// An option of the scene's `bvp` block is invalid.
    #[error("scene field `bvp.{field}`: {reason}")]
    InvalidOption { field: &'static str, reason: String },
    /// The belt problem failed (or has no solution of its kind).
    #[error(transparent)]
    Belt(#[from] BeltError),
    /// A one-pulley prescription the contract allows but that does not determine the
    /// solution (spec §2.3).
    #[error("one-pulley prescription `{given}` does not determine the solution: {reason}")]
    IllPosedPrescription {
        /// The prescribed pair, e.g. `pulley_speed + tension_in`.
        given: &'static str,
        /// Why.
        reason: &'static str,
    },
}

impl BeltOptions {
    /// Defaults overridden by the scene's `bvp` block.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneSolveError> {
        let b = scene.bvp_settings();
        Ok(Self {
            method: b.method,
            tolerance: b.tolerance,
            scheme: b
                .scheme
                .parse()
                .map_err(|e: String| SceneSolveError::InvalidOption { field: "scheme", reason: e })?,
            max_nodes: b.max_nodes,
            shooting_intervals: b.shooting_intervals,
            jacobian: JacobianMode::Ad,
            ..Self::default()
        })
    }
}

/// A BVP run: the solution behind the common view, its summary, cost, and diagnostics.
pub struct BvpRun {
    /// The solution, sampled through the common view.
    pub view: Box<dyn SolutionView + Send + Sync>,
    /// The summary (computed once).
    pub summary: Summary,
    /// Work counters and wall time of the whole run (homotopy included).
    pub stats: Stats,
    /// `bvp-collocation` or `bvp-shooting`.
    pub method: String,
    /// Scheme and tolerance in words.
    pub method_detail: String,
    /// Options used (written into results so a run can be reproduced).
    pub options: serde_json::Value,
    /// Diagnostics worth printing (closure defect, homotopy steps, invariant drift).
    pub notes: Vec<String>,
    /// What a nearby scene's run can start from ([`solve_scene_from`]); `None` for a
    /// model without warm starts (the static loops and the one-pulley belt: each of
    /// their runs starts from its closed form).
    pub warm: Option<WarmStart>,
}

/// The solved problem of a run, kept to start the run of a nearby scene from it (a
/// natural-parameter continuation in a scene field, `beltcheck sweep`).
#[derive(Debug, Clone)]
pub enum WarmStart {
    /// A solved steady string drive.
    StringDrive(Box<StringDriveSolution>),
    /// A solved steady Cosserat drive.
    CosseratDrive(Box<CosseratDriveSolution>),
}

impl WarmStart {
    /// The warm start of a point r steps beyond this one along a line through `older`
    /// (the previous point): this solution with the secant predictor of
    /// [`BeltSolution::predicted`] as its guess. `None` when `older` is another model or
    /// the two are not comparable (other scales or topology): then start from `self`.
    pub fn predicted(&self, older: &WarmStart, ratio: f64) -> Option<WarmStart> {
        match (self, older) {
            (WarmStart::StringDrive(a), WarmStart::StringDrive(b)) => a.predicted(b, ratio).map(|s| WarmStart::StringDrive(Box::new(s))),
            (WarmStart::CosseratDrive(a), WarmStart::CosseratDrive(b)) => a.predicted(b, ratio).map(|s| WarmStart::CosseratDrive(Box::new(s))),
            _ => None,
        }
    }
}

impl BvpRun {
    /// The run of a solved belt problem with options `opts` (as JSON: `options`) and its
    /// diagnostics `notes`.
    fn of<L: SectionLaw + 'static>(sol: BeltSolution<L>, opts: &BvpRunOptions, options: serde_json::Value, notes: Vec<String>) -> Self {
        Self {
            summary: sol.summary(),
            stats: sol.stats.clone(),
            view: Box::new(sol),
            method: opts.method.name().to_string(),
            method_detail: opts.detail(),
            options,
            notes,
            warm: None,
        }
    }
}

/// The physical data of a `string-hanging` scene.
pub fn string_hanging_data(scene: &Scene) -> StringHanging {
    StringHanging {
        radius: scene.drive.pulley_radius,
        centre_distance: scene.drive.centre_distance,
        length: scene.belt.length,
        axial_stiffness: scene.belt.axial_stiffness,
        mass_per_length: scene.belt.mass_per_length,
        gravity: scene.effects.gravity.unwrap_or(0.0),
    }
}

/// The physical data of a `rod-hanging` scene (a missing EI is NaN, refused by the
/// solver's validation).
pub fn rod_hanging_data(scene: &Scene) -> RodHanging {
    let s = string_hanging_data(scene);
    RodHanging {
        radius: s.radius,
        centre_distance: s.centre_distance,
        length: s.length,
        axial_stiffness: s.axial_stiffness,
        bending_stiffness: scene.belt.bending_stiffness.unwrap_or(f64::NAN),
        mass_per_length: s.mass_per_length,
        gravity: s.gravity,
    }
}

/// The physical data of a steady `string-drive` scene with Coulomb coefficient `mu`.
pub fn string_drive_data(scene: &Scene, mu: f64) -> StringDrive {
    StringDrive {
        belt: string_hanging_data(scene),
        inertia: scene.effects.inertia == Some(true),
        friction: mu,
        driver_speed: scene.drive.driver_speed,
        driven_torque: scene.drive.driven_torque,
        driven_damping: scene.drive.driven_damping,
    }
}

/// The physical data of a one-pulley Cosserat scene (`drive.layout: "one-pulley"`,
/// theory `cosserat`, analysis `steady`, Coulomb contact) in its prescription mode
/// (docs/cosserat-pulley.md, "Modes"): `tensions`, `transition` (φ_B and one tension;
/// the sense is the pulley driving the belt) or `pulley_speed` (ω and N_out).
///
/// # Errors
/// [`SceneSolveError::Unsupported`] for another layout, theory, analysis or contact;
/// [`SceneSolveError::IllPosedPrescription`] for `pulley_speed` with `tension_in`;
/// [`SceneSolveError::Belt`] for a prescription without a start (no positive effective
/// tension, no slip arc).
pub fn cosserat_pulley_data(scene: &Scene) -> Result<CosseratPulley, SceneSolveError> {
    let d = &scene.drive;
    let unsupported = |what: String| Err(SceneSolveError::Unsupported(what));
    if !(d.layout == Layout::OnePulley && scene.belt.theory == Theory::Cosserat && scene.analysis == Analysis::Steady) {
        return unsupported(format!(
            "layout {}, theory {}, analysis {}: the one-pulley BVP solves the Cosserat belt in steady motion",
            d.layout, scene.belt.theory, scene.analysis
        ));
    }
    let Contact::Coulomb(friction) = scene.effects.contact else {
        return unsupported(format!("contact {:?}: the one-pulley BVP has Coulomb friction (stick and slip)", scene.effects.contact));
    };
    let (tension_in, tension_out, mode) = match d.one_pulley_load() {
        Some(OnePulleyLoad::Tensions { tension_in, tension_out }) => (tension_in, tension_out, Mode::Tensions),
        Some(OnePulleyLoad::Transition { stick_slip_angle, tension: (given, n), driving }) => {
            let (tin, tout) = if given == End::In { (n, f64::NAN) } else { (f64::NAN, n) };
            (tin, tout, Mode::Transition { stick_slip_angle, given, driving })
        }
        Some(OnePulleyLoad::PulleySpeed { pulley_speed, tension: (End::Out, n) }) => (f64::NAN, n, Mode::PulleySpeed { pulley_speed }),
        Some(OnePulleyLoad::PulleySpeed { tension: (End::In, _), .. }) => {
            return Err(SceneSolveError::IllPosedPrescription { given: "pulley_speed + tension_in", reason: cosserat_pulley::PULLEY_SPEED_WITH_TENSION_IN });
        }
        None => return unsupported("a one-pulley scene without a valid prescription (validate the scene first)".to_string()),
    };
    let data = CosseratPulley {
        radius: d.pulley_radius,
        end_distance: d.end_distance.unwrap_or(f64::NAN),
        transport_rate: d.transport_rate.unwrap_or(f64::NAN),
        tension_in,
        tension_out,
        axial_stiffness: scene.belt.axial_stiffness,
        bending_stiffness: scene.belt.bending_stiffness.unwrap_or(f64::NAN),
        shear_stiffness: scene.belt.shear_stiffness.unwrap_or(f64::NAN),
        mass_per_length: scene.belt.mass_per_length,
        friction,
        inertia: scene.effects.inertia == Some(true),
        mode: Mode::Tensions,
    };
    Ok(data.with_mode(mode)?)
}

/// Solve a one-pulley Cosserat scene by the BVP method of `opts`
/// ([`cosserat_pulley_data`], [`cosserat_pulley::solve`]); [`solve_scene`] runs it for
/// `drive.layout: "one-pulley"`.
pub fn solve_one_pulley(scene: &Scene, opts: &BvpRunOptions) -> Result<CosseratPulleySolution, SceneSolveError> {
    Ok(cosserat_pulley::solve(&cosserat_pulley_data(scene)?, opts)?)
}

/// The run of a solved one-pulley scene, with its balances in `notes`.
fn one_pulley_run(sol: CosseratPulleySolution, opts: &BvpRunOptions, options: serde_json::Value) -> BvpRun {
    let [a, b, c] = sol.contact_angles();
    let d = &sol.data;
    let notes = vec![
        if sol.homotopy_steps > 1 {
            format!("homotopy: {} continuation steps in log a from the string creep solution with bending layers", sol.homotopy_steps)
        } else {
            "start: the string creep solution with bending layers at the scene's a (no homotopy needed)".to_string()
        },
        format!(
            "moment balance about the pulley centre: imbalance {:.3e} N·m (0 for the exact solution)",
            cosserat_pulley::moment_imbalance(d, |k, xi| sol.point(k, xi))
        ),
        format!("contact angles φ_A = {a:.9}, φ_B = {b:.9}, φ_C = {c:.9} rad; slip dissipation {:.6e} W", sol.dissipation()),
        format!("shear layer √(a/(b₂ − ρc²)) = {} m at the contact boundaries (no edge forces: edge pressures)", numerics::Sig(d.shear_layer())),
    ];
    BvpRun {
        summary: sol.summary(),
        stats: sol.stats.clone(),
        method: opts.method.name().to_string(),
        method_detail: opts.detail(),
        view: Box::new(sol),
        options,
        notes,
        warm: None,
    }
}

/// Solve a scene by the BVP method of `opts`: the static string (`string-hanging`), the
/// static Kirchhoff rod (`rod-hanging`) or the static Cosserat rod (`cosserat-hanging`)
/// on frictionless pulleys, the string in steady motion with Coulomb friction
/// (`string-drive`), the Cosserat belt in steady motion with Coulomb friction on two
/// pulleys (`cosserat-drive`) or over one pulley (`cosserat-pulley`, the open layout).
///
/// # Errors
/// [`SceneSolveError::NotYetSolvable`] for a layout or theory the BVP does not solve yet
/// (before anything else), [`SceneSolveError::Unsupported`] for another model it does not
/// have, else the belt problem's failure.
pub fn solve_scene(scene: &Scene, opts: &BvpRunOptions) -> Result<BvpRun, SceneSolveError> {
    if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Bvp) {
        return Err(e.into());
    }
    let static_frictionless = matches!(scene.analysis, Analysis::Static)
        && matches!(scene.effects.contact, Contact::Frictionless)
        && scene.drive.driver_speed == 0.0
        && scene.drive.driven_torque == 0.0;
    let options = serde_json::to_value(opts).unwrap_or(serde_json::Value::Null);
    if scene.drive.layout == Layout::OnePulley {
        return Ok(one_pulley_run(solve_one_pulley(scene, opts)?, opts, options));
    }
    match scene.belt.theory {
        Theory::String if static_frictionless => {
            let data = string_hanging_data(scene);
            let sol = string_hanging::solve(&data, opts)?;
            let notes = vec![
                format!("homotopy: {} continuation steps from the tight weightless loop", sol.homotopy_steps),
                format!("closure defect f = {:.3e} N (0 for the exact solution)", sol.closure_defect().unwrap_or(0.0)),
            ];
            Ok(BvpRun::of(sol, opts, options, notes))
        }
        Theory::Kirchhoff if static_frictionless => {
            let data = rod_hanging_data(scene);
            let sol = rod_hanging::solve(&data, opts)?;
            let path = if sol.problem.law.starts_at_scene() {
                direct_start("EI", data.bending_stiffness)
            } else {
                format!("{} continuation steps in log EI from EI₀ = {:.3e} N·m²", sol.homotopy_steps, sol.bending_start())
            };
            let notes = vec![
                format!("homotopy: the string, then {path}"),
                format!("closure defect f = {:.3e} N (0 for the exact solution)", sol.closure_defect().unwrap_or(0.0)),
            ];
            Ok(BvpRun::of(sol, opts, options, notes))
        }
        Theory::Cosserat if static_frictionless => {
            let data = CosseratHanging { rod: rod_hanging_data(scene), shear_stiffness: scene.belt.shear_stiffness.unwrap_or(f64::NAN) };
            let sol = cosserat_hanging::solve(&data, opts)?;
            let path = if sol.problem.law.starts_at_scene() {
                direct_start("a", data.rod.bending_stiffness)
            } else {
                format!("{} continuation steps in log a from a₀ = {} N·m²", sol.homotopy_steps, numerics::Sig(sol.bending_start()))
            };
            let notes = vec![
                format!("homotopy: the string, then {path} at b₂ = {} N", numerics::Sig(data.shear_stiffness)),
                format!("closure defect f = {:.3e} N (0 for the exact solution)", sol.closure_defect().unwrap_or(0.0)),
                format!("shear layer √(a/b₂) = {} m at the contact boundaries (no edge forces: edge pressures)", numerics::Sig(data.shear_layer())),
            ];
            Ok(BvpRun::of(sol, opts, options, notes))
        }
        Theory::String if matches!(scene.analysis, Analysis::Steady) && matches!(scene.effects.contact, Contact::Coulomb(_)) => {
            let Contact::Coulomb(mu) = scene.effects.contact else { unreachable!("matched above") };
            let sol = string_drive::solve(&string_drive_data(scene, mu), opts)?;
            Ok(string_drive_run(sol, opts, options))
        }
        Theory::Cosserat if matches!(scene.analysis, Analysis::Steady) && matches!(scene.effects.contact, Contact::Coulomb(_)) => {
            let sol = cosserat_drive::solve(&CosseratDrive::from_scene(scene)?, opts)?;
            Ok(cosserat_drive_run(sol, opts, options))
        }
        _ => Err(SceneSolveError::Unsupported(format!(
            "theory {}, analysis {}, contact {:?}: the BVP models so far are the static string, Kirchhoff rod and Cosserat rod on frictionless pulleys, and the string and the Cosserat belt in steady motion with Coulomb friction",
            scene.belt.theory, scene.analysis, scene.effects.contact
        ))),
    }
}

/// The homotopy note of a rod whose bending layer is at least the start layer: no path
/// in the bending stiffness `name` (N·m²).
fn direct_start(name: &str, bending: f64) -> String {
    format!("the scene's {name} = {} N·m² directly (its bending layer is at least the start layer)", numerics::Sig(bending))
}

/// How a drive run reached its scene, in words: its homotopy, or a warm start.
fn path_note(homotopy: String, sol_steps: usize, warm_iterations: usize) -> String {
    if sol_steps == 0 {
        format!("warm start from the previous point of a continuation: {warm_iterations} Newton iterations, no homotopy")
    } else {
        homotopy
    }
}

/// The run of a solved string drive, with its power balance (and the belt-creep closed
/// form without gravity) in `notes`, kept as a warm start.
fn string_drive_run(sol: StringDriveSolution, opts: &BvpRunOptions, options: serde_json::Value) -> BvpRun {
    let data = sol.data;
    let (input, output, dissipation) = sol.power_balance();
    let homotopy = format!("homotopy: {} continuation steps from the tight loop at rest (torque, gravity, length, speed)", sol.homotopy_steps);
    let mut notes = vec![
        path_note(homotopy, sol.homotopy_steps, sol.stats.newton_iterations),
        format!("power: input {input:.6} W = output {output:.6} W + slip dissipation {dissipation:.6} W (imbalance {:.3e} W)", input - output - dissipation),
    ];
    if data.gravity == 0.0 {
        if let Ok(e) = data.creep() {
            notes.push(format!(
                "belt-creep closed form: T_tight {:.9} N, T_slack {:.9} N, ω₂ {:.9} rad/s, slip arc {:.9} rad",
                e.tension_tight, e.tension_slack, e.driven_speed, e.slip_arc
            ));
        }
    }
    let warm = WarmStart::StringDrive(Box::new(sol.clone()));
    BvpRun { warm: Some(warm), ..BvpRun::of(sol, opts, options, notes) }
}

/// The run of a solved Cosserat drive, with its power balance, stick stretches and shear
/// layer in `notes`, kept as a warm start.
fn cosserat_drive_run(sol: CosseratDriveSolution, opts: &BvpRunOptions, options: serde_json::Value) -> BvpRun {
    let data = sol.data;
    let (input, output, dissipation) = sol.power_balance();
    let (lambda_driver, lambda_driven) = sol.stick_stretches();
    let c = sol.transport_rate().unwrap_or(f64::NAN);
    let path = if sol.problem.law.starts_at_scene() {
        direct_start("a", data.bending_stiffness)
    } else {
        format!("{} in log a from a₀ = {} N·m²", sol.homotopy_steps, numerics::Sig(sol.bending_start()))
    };
    let homotopy = format!("homotopy: the string drive ({} continuation steps), then {path}", sol.start.homotopy_steps);
    let notes = vec![
        path_note(homotopy, sol.homotopy_steps, sol.stats.newton_iterations),
        format!("power: input {input:.6} W = output {output:.6} W + slip dissipation {dissipation:.6} W (imbalance {:.3e} W)", input - output - dissipation),
        format!("stick stretches λ₁ = {lambda_driver:.9}, λ₂ = {lambda_driven:.9} (creep ω₂/ω₁ = λ₂/λ₁)"),
        format!("shear layer √(a/(b₂ − ρc²)) = {} m at the contact boundaries (no edge forces: edge pressures)", numerics::Sig(data.shear_layer(c))),
    ];
    let warm = WarmStart::CosseratDrive(Box::new(sol.clone()));
    BvpRun { warm: Some(warm), ..BvpRun::of(sol, opts, options, notes) }
}

/// Solve a scene from the run of a nearby scene (natural-parameter continuation in a
/// scene field, `beltcheck sweep`): the drive's final solve from `previous`'s solution,
/// no homotopy ([`string_drive::solve_from`], [`cosserat_drive::solve_from`], both the
/// shared [`crate::belt::solution::solve_from`]). Falls back to [`solve_scene`] (a cold
/// start, its homotopy) when `previous` cannot start this scene: another model, running
/// direction or power flow.
///
/// # Errors
/// As [`solve_scene`]; a warm solve that fails is an error (the caller decides whether
/// to retry from closer, or cold).
pub fn solve_scene_from(scene: &Scene, opts: &BvpRunOptions, previous: &WarmStart) -> Result<BvpRun, SceneSolveError> {
    if let Some(e) = drive::not_yet_solvable(scene, drive::Solver::Bvp) {
        return Err(e.into());
    }
    let options = serde_json::to_value(opts).unwrap_or(serde_json::Value::Null);
    let steady = scene.drive.layout == Layout::TwoPulley && matches!(scene.analysis, Analysis::Steady);
    match (previous, scene.belt.theory, scene.effects.contact.clone()) {
        (WarmStart::StringDrive(p), Theory::String, Contact::Coulomb(mu)) if steady => {
            if let Some(solved) = string_drive::solve_from(&string_drive_data(scene, mu), opts, p) {
                return Ok(string_drive_run(solved?, opts, options));
            }
        }
        (WarmStart::CosseratDrive(p), Theory::Cosserat, Contact::Coulomb(_)) if steady => {
            if let Some(solved) = cosserat_drive::solve_from(&CosseratDrive::from_scene(scene)?, opts, p) {
                return Ok(cosserat_drive_run(solved?, opts, options));
            }
        }
        _ => {}
    }
    solve_scene(scene, opts)
}
