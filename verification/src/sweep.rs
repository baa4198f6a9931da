//! Parameter studies (`beltcheck sweep`, spec §3.6): every summary output of a scene
//! against one or more numeric scene fields, by BVP natural-parameter continuation along
//! each line of the grid, FE spot checks at chosen points, and the asymptotes the model
//! has (string limit a → 0, Kirchhoff limit b₂ → ∞, the gravity-free belt-creep closed
//! form). docs/sweep.md.
//!
//! # The study
//!
//! A parameter is a scene field by its dotted path (`belt.shear_stiffness`,
//! `drive.driven_torque`, `effects.contact.coulomb`) with a range FROM:TO[:log]:N
//! ([`ParamRange`]). The first parameter runs along the *lines*; the product of the
//! others' values makes one line each. Every point's scene is the base scene with the
//! fields set, read back through [`Scene::from_json_str`] (the normal validation: an
//! invalid point is reported as [`PointStatus::InvalidScene`]).
//!
//! # Continuation along a line
//!
//! In the line coordinate t (the value, or log₁₀ of it for a log range): the first point
//! is a cold solve ([`bvp::scene::solve_scene`], the model's own homotopy); each next
//! point t_i is reached from the last converged solution by warm starts
//! ([`bvp::scene::solve_scene_from`]: the final solve from the previous solution, no
//! homotopy), with a secant predictor once two comparable points are accepted
//! ([`WarmStart::predicted`]: the last solution extrapolated along the line through the
//! one before, at most [`MAX_PREDICTOR_RATIO`] times the last step); a step that fails
//! from the predicted start is retried from the last solution itself before it counts
//! as failed (an extrapolated guess can overshoot into a topology the plain warm start
//! does not reach). A failed step is halved (Δt/2, Δt/4, … down to
//! Δt_grid / 2^[`MAX_HALVINGS`]); an accepted intermediate step doubles the next one
//! (never past t_i). When the halving runs out:
//!
//! - **fold**: the line's tangent turns — the η-component of the unit tangent
//!   (Δt, Δy)/‖(Δt, Δy)‖ of the last accepted step (y the summary scalars relative to
//!   their size, RMS) fell below [`FOLD_TANGENT`], or the secant slope ‖Δy‖/|Δt| grew by
//!   more than [`FOLD_SLOPE_GROWTH`] over the step before: the branch turns back in t,
//!   there is no solution of this branch beyond the last converged point. The line stops there ([`Fold`]) and the remaining points are
//!   [`PointStatus::BeyondFold`];
//! - otherwise a cold solve at t_i; if that fails too, the point is
//!   [`PointStatus::Failed`] with the solver's error, and the next point is tried by a
//!   cold solve only (beyond an admissibility limit of the modelled topology the
//!   halvings would fail again); once a point converges the line continues from it.
//!
//! A model without warm starts (the static loops, the one-pulley belt) is solved cold
//! at every point.

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use bvp::scene::{BvpRun, BvpRunOptions, SceneSolveError, WarmStart};
use drive::scene::{Contact, Scene, Theory};
use plotters::prelude::*;
use rayon::prelude::*;
use serde::Serialize;

use crate::run::{Discretisation, FemFormulation, Method};

/// At most this many halvings of a line's grid step before a point counts as not
/// reachable by continuation (a smallest step of Δt_grid/64).
pub const MAX_HALVINGS: u32 = 6;

/// The largest ratio of a step to the last accepted one for which the warm start is
/// the secant predictor through the last two points (beyond it: the last point).
pub const MAX_PREDICTOR_RATIO: f64 = 4.0;

/// The η-component of the unit tangent below which the branch counts as turning (a
/// fold): 0.05, the branch within 3° of vertical in (t, y) with y the relative change of
/// the summary.
pub const FOLD_TANGENT: f64 = 0.05;

/// The growth of the secant slope ‖Δy‖/|Δt| over the last step that counts as the
/// tangent turning towards a fold: 2 (on y = √(t_f − t) the slope doubles when the
/// distance to the fold t_f falls to a quarter; a smooth branch changes its slope by
/// O(Δt) per step).
pub const FOLD_SLOPE_GROWTH: f64 = 2.0;

/// Decades beyond the largest swept b₂ of the Kirchhoff-limit proxy (module docs).
pub const KIRCHHOFF_DECADES: usize = 2;

/// Most points of a line and most grid points (a sweep of 100 000 BVP solves is a
/// mistake, not a study).
pub const MAX_POINTS: usize = 100_000;

/// Why a sweep is refused before anything runs, or its output not written (exit 2).
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// `--param` not of the form NAME=FROM:TO[:log]:N.
    #[error("--param `{arg}`: {reason} (expected NAME=FROM:TO[:log]:N, e.g. belt.shear_stiffness=1e2:1e6:log:40)")]
    Syntax { arg: String, reason: String },
    /// A range that does not make a sweep.
    #[error("--param {path}: {reason}")]
    BadRange { path: String, reason: String },
    /// The dotted path names no field of the scene.
    #[error("--param {path}: the scene has no field `{path}` ({reason}); numeric fields of this scene: {known}")]
    UnknownPath { path: String, reason: String, known: String },
    /// The field is not a number.
    #[error("--param {path}: scene field `{path}` is {found}, not a number; numeric fields of this scene: {known}")]
    NotNumeric { path: String, found: String, known: String },
    /// The same field twice.
    #[error("--param {path} is given twice")]
    Duplicate { path: String },
    /// More points than [`MAX_POINTS`].
    #[error("the grid has {points} points, more than {max}")]
    TooManyPoints { points: usize, max: usize },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
    /// A file could not be written (nothing of the sweep is left behind).
    #[error(transparent)]
    Write(#[from] crate::files::WriteError),
    /// JSON serialisation.
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// One swept field: `path` from `from` to `to` in `points` values, equally spaced in the
/// value or (with `log`) in its logarithm.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamRange {
    /// Dotted path of the scene field, e.g. `belt.shear_stiffness`.
    pub path: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Equally spaced in log₁₀ (both bounds > 0).
    pub log: bool,
    /// Number of values, ≥ 2.
    pub points: usize,
}

impl FromStr for ParamRange {
    type Err = SweepError;

    /// NAME=FROM:TO[:log]:N, e.g. `belt.shear_stiffness=1e2:1e6:log:40`.
    fn from_str(arg: &str) -> Result<Self, SweepError> {
        let syntax = |reason: &str| SweepError::Syntax { arg: arg.to_string(), reason: reason.to_string() };
        let (path, range) = arg.split_once('=').ok_or_else(|| syntax("no `=`"))?;
        let path = path.trim().to_string();
        if path.is_empty() {
            return Err(syntax("no field name before `=`"));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let (from, to, log, n) = match parts[..] {
            [a, b, n] => (a, b, false, n),
            [a, b, "log", n] => (a, b, true, n),
            [_, _, x, _] => return Err(syntax(&format!("`{x}` where `log` or nothing is expected"))),
            _ => return Err(syntax(&format!("{} `:`-separated parts, 3 or 4 expected", parts.len()))),
        };
        let number = |s: &str, what: &str| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(syntax(&format!("{what} `{s}` is not a finite number"))),
        };
        let (from, to) = (number(from, "FROM")?, number(to, "TO")?);
        let points: usize = n.parse().map_err(|_| syntax(&format!("N `{n}` is not a whole number")))?;
        let bad = |reason: String| Err(SweepError::BadRange { path: path.clone(), reason });
        if points < 2 {
            return bad(format!("N = {points}: a sweep needs at least 2 points"));
        }
        if points > MAX_POINTS {
            return bad(format!("N = {points}: at most {MAX_POINTS} points"));
        }
        if from == to {
            return bad(format!("FROM = TO = {from}: an empty range"));
        }
        if log && (from <= 0.0 || to <= 0.0) {
            return bad(format!("a log range needs positive bounds, got {from} … {to}"));
        }
        Ok(ParamRange { path, from, to, log, points })
    }
}

impl ParamRange {
    /// The line coordinate of a value: log₁₀ v on a log range, else v.
    pub fn coordinate(&self, v: f64) -> f64 {
        if self.log { v.log10() } else { v }
    }

    /// The value of a line coordinate.
    pub fn value(&self, t: f64) -> f64 {
        if self.log { 10f64.powf(t) } else { t }
    }

    /// The values, first and last exact.
    pub fn values(&self) -> Vec<f64> {
        let (a, b) = (self.coordinate(self.from), self.coordinate(self.to));
        let n = self.points - 1;
        (0..=n)
            .map(|i| match i {
                0 => self.from,
                _ if i == n => self.to,
                _ => self.value(a + (b - a) * i as f64 / n as f64),
            })
            .collect()
    }
}

/// The numeric fields of a scene's JSON, by dotted path.
fn numeric_paths(v: &serde_json::Value, prefix: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                let p = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                numeric_paths(x, &p, out);
            }
        }
        serde_json::Value::Number(_) if !prefix.starts_with("gate.") => out.push(prefix.to_string()),
        _ => {}
    }
}

/// The field at a dotted path of a JSON value.
fn field_mut<'v>(v: &'v mut serde_json::Value, path: &str) -> Result<&'v mut serde_json::Value, String> {
    let mut here = v;
    let mut walked = String::new();
    for key in path.split('.') {
        let at = if walked.is_empty() { "the scene".to_string() } else { format!("`{walked}`") };
        here = match here {
            serde_json::Value::Object(m) => m.get_mut(key).ok_or_else(|| format!("{at} has no `{key}`"))?,
            _ => return Err(format!("{at} is not an object")),
        };
        walked = if walked.is_empty() { key.to_string() } else { format!("{walked}.{key}") };
    }
    Ok(here)
}

fn kind_of(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::Null => "null".into(),
        serde_json::Value::Bool(b) => format!("the boolean {b}"),
        serde_json::Value::String(s) => format!("the string \"{s}\""),
        serde_json::Value::Array(_) => "a list".into(),
        serde_json::Value::Object(_) => "an object".into(),
        serde_json::Value::Number(_) => "a number".into(),
    }
}

/// What a sweep runs.
#[derive(Debug, Clone, Serialize)]
pub struct SweepPlan {
    /// The swept fields; the first runs along the lines.
    pub params: Vec<ParamRange>,
    /// FE spot checks per line, evenly spaced over its points (0: none).
    pub fe_points: usize,
    /// Elements of the FE spot checks.
    pub fe_elements: usize,
    /// BVP tolerance of every point (the scene's `bvp.tolerance` by default).
    pub tolerance: f64,
    /// Draw the asymptotes (string limit, Kirchhoff limit, belt-creep closed form).
    pub asymptotes: bool,
    #[serde(skip)]
    base: serde_json::Value,
}

impl SweepPlan {
    /// A plan over `params` for `scene`: every path checked against the scene (a
    /// numeric field, given once), the grid size bounded.
    ///
    /// # Errors
    /// [`SweepError::UnknownPath`], [`SweepError::NotNumeric`], [`SweepError::Duplicate`],
    /// [`SweepError::TooManyPoints`].
    pub fn new(scene: &Scene, params: Vec<ParamRange>, fe_points: usize) -> Result<SweepPlan, SweepError> {
        let mut base: serde_json::Value = serde_json::from_str(&scene.to_json_pretty())?;
        let mut known = Vec::new();
        numeric_paths(&base, "", &mut known);
        let known = known.join(", ");
        for (i, p) in params.iter().enumerate() {
            if params[..i].iter().any(|q| q.path == p.path) {
                return Err(SweepError::Duplicate { path: p.path.clone() });
            }
            match field_mut(&mut base, &p.path) {
                Err(reason) => return Err(SweepError::UnknownPath { path: p.path.clone(), reason, known }),
                Ok(v) if !v.is_number() => return Err(SweepError::NotNumeric { path: p.path.clone(), found: kind_of(v), known }),
                Ok(_) => {}
            }
        }
        let points = params.iter().map(|p| p.points).try_fold(1usize, |a, n| a.checked_mul(n)).unwrap_or(usize::MAX);
        if points > MAX_POINTS {
            return Err(SweepError::TooManyPoints { points, max: MAX_POINTS });
        }
        let bvp = scene.bvp_settings();
        Ok(SweepPlan { params, fe_points, fe_elements: scene.fem_settings().elements, tolerance: bvp.tolerance, asymptotes: true, base })
    }

    /// The lines: for each combination of the other parameters' values, those values.
    pub fn lines(&self) -> Vec<Vec<f64>> {
        let mut lines = vec![Vec::new()];
        for p in &self.params[1..] {
            lines = lines.into_iter().flat_map(|l| p.values().into_iter().map(move |v| [l.clone(), vec![v]].concat())).collect();
        }
        lines
    }

    /// Number of BVP points.
    pub fn point_count(&self) -> usize {
        self.params.iter().map(|p| p.points).product()
    }

    /// The scene with the swept fields at `values` (one per parameter), validated.
    pub fn scene_at(&self, values: &[f64]) -> Result<Scene, String> {
        let mut v = self.base.clone();
        for (p, &x) in self.params.iter().zip(values) {
            let f = field_mut(&mut v, &p.path)?;
            *f = serde_json::Number::from_f64(x).map(serde_json::Value::Number).ok_or_else(|| format!("{} = {x} is not finite", p.path))?;
        }
        Scene::from_json_str(&v.to_string()).map_err(|e| e.to_string())
    }

    fn bvp_options(&self, scene: &Scene) -> Result<BvpRunOptions, SceneSolveError> {
        let mut o = BvpRunOptions::from_scene(scene)?;
        o.tolerance = self.tolerance;
        Ok(o)
    }
}

/// What became of one point.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum PointStatus {
    /// Solved: the summary scalars and the work.
    Solved {
        /// Summary scalars by flat name.
        summary: Vec<(String, f64)>,
        /// Warm-started from the previous point (false: the model's homotopy).
        warm: bool,
        /// Continuation steps taken to reach it (1 = no halving; intermediate points
        /// included).
        steps: usize,
        /// Newton iterations, over the accepted steps.
        newton_iterations: usize,
        /// Wall time, s, over every solve tried for the point: the accepted steps and
        /// the failed attempts (a predicted start retried from the plain one, a step
        /// halved, a continuation given up for a cold solve).
        wall_seconds: f64,
        /// Solves tried for the point that failed (their Newton iterations are not
        /// known; their wall time is in `wall_seconds`).
        failed_attempts: usize,
    },
    /// The point's scene fails validation.
    InvalidScene {
        /// The validation error.
        error: String,
    },
    /// Neither continuation nor a cold solve reached it.
    Failed {
        /// The solver's error (of the cold solve).
        error: String,
        /// Wall time, s, over every solve tried for the point (all failed).
        wall_seconds: f64,
        /// Solves tried for the point (the continuation's steps and the cold solve).
        failed_attempts: usize,
    },
    /// Beyond a fold of the line's branch (not attempted).
    BeyondFold,
}

impl PointStatus {
    /// A failed solve whose time and attempts the line adds up afterwards.
    fn failed(error: String) -> Self {
        PointStatus::Failed { error, wall_seconds: 0.0, failed_attempts: 0 }
    }
}

/// One point of a line.
#[derive(Debug, Clone, Serialize)]
pub struct Point {
    /// The values of every parameter, in the plan's order.
    pub values: Vec<f64>,
    /// The outcome.
    #[serde(flatten)]
    pub status: PointStatus,
}

impl Point {
    /// The summary of a solved point.
    pub fn summary(&self) -> Option<&[(String, f64)]> {
        match &self.status {
            PointStatus::Solved { summary, .. } => Some(summary),
            _ => None,
        }
    }

    /// The scalar `name` of a solved point.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.summary()?.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }
}

/// A fold located on a line: the last converged value and the first value continuation
/// could not pass.
#[derive(Debug, Clone, Serialize)]
pub struct Fold {
    /// The last converged value of the line parameter.
    pub last_converged: f64,
    /// The value that was not reached (the smallest step beyond `last_converged`).
    pub not_reached: f64,
    /// η-component of the unit tangent at the last step, and one step before.
    pub tangent: (f64, f64),
    /// Why the smallest step failed (the warm solve's error).
    pub cause: String,
    /// In words.
    pub message: String,
}

/// A value of an asymptote at a line value.
#[derive(Debug, Clone, Serialize)]
pub struct AsymptotePoint {
    /// Line parameter value.
    pub value: f64,
    /// Scalars by flat name.
    pub summary: Vec<(String, f64)>,
}

/// An asymptote of a line.
#[derive(Debug, Clone, Serialize)]
pub struct Asymptote {
    /// `string limit (a → 0)`, `Kirchhoff limit (b₂ → ∞)`, `belt-creep closed form (g = 0)`.
    pub name: String,
    /// How it is computed.
    pub detail: String,
    /// Its values along the line (one value for a horizontal asymptote).
    pub points: Vec<AsymptotePoint>,
    /// Why (part of) it could not be computed.
    pub notes: Vec<String>,
}

/// One line of the grid.
#[derive(Debug, Clone, Serialize)]
pub struct Line {
    /// The values of the other parameters (the plan's 2nd, 3rd, …).
    pub fixed: Vec<f64>,
    /// Its points.
    pub points: Vec<Point>,
    /// The fold that ended it.
    pub fold: Option<Fold>,
    /// Its asymptotes.
    pub asymptotes: Vec<Asymptote>,
    /// Wall time of its BVP continuation, s.
    pub wall_seconds: f64,
}

/// An FE spot check: the FE and the BVP summary at one point.
#[derive(Debug, Clone, Serialize)]
pub struct FeCheck {
    /// Line index.
    pub line: usize,
    /// Point index on the line.
    pub point: usize,
    /// The point's parameter values.
    pub values: Vec<f64>,
    /// FE formulation.
    pub formulation: String,
    /// Elements.
    pub elements: usize,
    /// Outcome: per scalar (name, FE value, BVP value, relative difference), or the error.
    pub result: Result<Vec<(String, f64, f64, f64)>, String>,
    /// Wall time of the FE run, s.
    pub wall_seconds: f64,
}

impl FeCheck {
    /// The largest relative FE–BVP difference over the compared scalars.
    pub fn worst(&self) -> Option<(&str, f64)> {
        self.result.as_ref().ok()?.iter().map(|(n, _, _, r)| (n.as_str(), *r)).max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// A computed sweep.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    /// Scene name.
    pub scene: String,
    /// The plan.
    pub plan: SweepPlan,
    /// The lines.
    pub lines: Vec<Line>,
    /// FE spot checks.
    pub fe_checks: Vec<FeCheck>,
    /// Wall time of the whole sweep, s.
    pub wall_seconds: f64,
    /// rayon threads used.
    pub threads: usize,
}

/// Progress of a sweep: points done of the total (BVP points, then FE checks).
#[derive(Debug, Clone)]
pub struct Progress {
    /// Done.
    pub done: usize,
    /// Total.
    pub total: usize,
    /// What finished last.
    pub label: String,
}

impl Sweep {
    /// Points that did not solve (invalid, failed, beyond a fold), in words.
    pub fn failures(&self) -> Vec<String> {
        let name = &self.plan.params[0].path;
        let mut out = Vec::new();
        for line in &self.lines {
            let at = |p: &Point| {
                self.plan.params.iter().zip(&p.values).map(|(q, v)| format!("{} = {}", q.path, numerics::Sig(*v))).collect::<Vec<_>>().join(", ")
            };
            for p in &line.points {
                match &p.status {
                    PointStatus::Solved { .. } | PointStatus::BeyondFold => {}
                    PointStatus::InvalidScene { error } => out.push(format!("{}: invalid scene: {error}", at(p))),
                    PointStatus::Failed { error, .. } => out.push(format!("{}: {error}", at(p))),
                }
            }
            if let Some(f) = &line.fold {
                let beyond = line.points.iter().filter(|p| matches!(p.status, PointStatus::BeyondFold)).count();
                let fixed = if line.fixed.is_empty() { String::new() } else { format!(" (line {})", fixed_label(&self.plan, &line.fixed)) };
                out.push(format!("{name}{fixed}: {} — {beyond} point(s) not computed", f.message));
            }
        }
        for c in &self.fe_checks {
            if let Err(e) = &c.result {
                out.push(format!("FE spot check at {} = {}: {e}", name, numerics::Sig(c.values[0])));
            }
        }
        out
    }

    /// Solved points of all lines.
    pub fn solved(&self) -> usize {
        self.lines.iter().flat_map(|l| &l.points).filter(|p| p.summary().is_some()).count()
    }

    /// Run the sweep of `scene` by `plan`; `progress` is called from the worker threads.
    pub fn run(scene: &Scene, plan: &SweepPlan, progress: &(dyn Fn(Progress) + Sync)) -> Sweep {
        let clock = Instant::now();
        let lines_at = plan.lines();
        let fe_total = if plan.fe_points > 0 { lines_at.len() * plan.fe_points.min(plan.params[0].points) } else { 0 };
        let total = plan.point_count() + fe_total;
        let done = AtomicUsize::new(0);
        let tick = |label: String| {
            let d = done.fetch_add(1, Ordering::Relaxed) + 1;
            progress(Progress { done: d, total, label });
        };
        let lines: Vec<Line> = lines_at.par_iter().map(|fixed| run_line(scene, plan, fixed, &tick)).collect();
        let fe_checks = fe_spot_checks(scene, plan, &lines, &tick);
        Sweep { scene: scene.name.clone(), plan: plan.clone(), lines, fe_checks, wall_seconds: clock.elapsed().as_secs_f64(), threads: rayon::current_num_threads() }
    }
}

fn fixed_label(plan: &SweepPlan, fixed: &[f64]) -> String {
    plan.params[1..].iter().zip(fixed).map(|(p, v)| format!("{} = {}", p.path, numerics::Sig(*v))).collect::<Vec<_>>().join(", ")
}

/// A converged point of the continuation: its line coordinate, run and scalars.
#[derive(Clone)]
struct Converged {
    t: f64,
    warm: Option<WarmStart>,
    scalars: Vec<(String, f64)>,
}

/// The warm start of a step to `t` with the secant predictor through the last two
/// accepted points of `path` (module docs, step 2): `None` with fewer than two, when
/// they are not comparable (a cold start between them: other scales) or when the step
/// is more than [`MAX_PREDICTOR_RATIO`] times the last one (then the last point alone).
fn predictor(path: &[Converged], t: f64) -> Option<WarmStart> {
    let [.., older, here] = path else { return None };
    let ratio = (t - here.t) / (here.t - older.t);
    if !(ratio > 0.0 && ratio <= MAX_PREDICTOR_RATIO) {
        return None;
    }
    here.warm.as_ref()?.predicted(older.warm.as_ref()?, ratio)
}

/// A continuation step's solve (module docs): from the `predicted` warm start if there is
/// one, else from `plain` (the last converged solution); a predicted start that fails
/// ([`PointStatus::Failed`]) is retried from `plain` before the step counts as failed. An
/// invalid scene is not retried (no warm start changes it).
fn step_solve<R>(solve: &dyn Fn(Option<&WarmStart>) -> Result<R, PointStatus>, predicted: Option<&WarmStart>, plain: Option<&WarmStart>) -> Result<R, PointStatus> {
    match (predicted, solve(predicted.or(plain))) {
        (Some(_), Err(PointStatus::Failed { .. })) => solve(plain),
        (_, result) => result,
    }
}

/// The secant slope ‖Δy‖/|Δt| from `a` to `b`, y the summary scalars relative to
/// max(|y_a|, |y_b|, 1e-12), ‖·‖ their RMS (module docs).
fn slope(a: &Converged, b: &Converged) -> f64 {
    let dy2: Vec<f64> = a
        .scalars
        .iter()
        .filter_map(|(n, ya)| b.scalars.iter().find(|(m, _)| m == n).map(|(_, yb)| (ya, yb)))
        .map(|(ya, yb)| ((yb - ya) / ya.abs().max(yb.abs()).max(1e-12)).powi(2))
        .collect();
    (dy2.iter().sum::<f64>() / dy2.len().max(1) as f64).sqrt() / (b.t - a.t).abs()
}

/// The η-component 1/√(1 + slope²) of the unit tangent (Δt, Δy)/‖(Δt, Δy)‖.
fn tangent_eta(slope: f64) -> f64 {
    1.0 / (1.0 + slope * slope).sqrt()
}

/// The fold of a line whose continuation cannot pass beyond `path`'s last point with
/// step `h` (module docs), or `None` when the tangent did not turn.
fn fold_at(p0: &ParamRange, path: &[Converged], h: f64, grid: f64, cause: &str) -> Option<Fold> {
    let n = path.len();
    if n < 2 {
        return None;
    }
    let slope_now = slope(&path[n - 2], &path[n - 1]);
    let slope_then = if n >= 3 { slope(&path[n - 3], &path[n - 2]) } else { slope_now };
    let (now, then) = (tangent_eta(slope_now), tangent_eta(slope_then));
    if !(now < FOLD_TANGENT || slope_now > FOLD_SLOPE_GROWTH * slope_then) {
        return None;
    }
    let last = p0.value(path[n - 1].t);
    let not_reached = p0.value(path[n - 1].t + h);
    let message = format!(
        "fold/no solution beyond {} = {}: continuation could not pass to {} (smallest step {} against the grid's {} in {}), the branch's tangent turned (η-component of the unit tangent {} after {}); the last step failed: {cause}",
        p0.path,
        numerics::Sig(last),
        numerics::Sig(not_reached),
        numerics::Sig(h.abs()),
        numerics::Sig(grid.abs()),
        if p0.log { "log₁₀ of it" } else { "the value" },
        numerics::Sig(now),
        numerics::Sig(then)
    );
    Some(Fold { last_converged: last, not_reached, tangent: (now, then), cause: cause.to_string(), message })
}

/// Run one line (module docs): cold start, warm steps with halving, fold detection.
fn run_line(scene: &Scene, plan: &SweepPlan, fixed: &[f64], tick: &(dyn Fn(String) + Sync)) -> Line {
    let clock = Instant::now();
    let p0 = &plan.params[0];
    let grid = (p0.coordinate(p0.to) - p0.coordinate(p0.from)) / (p0.points - 1) as f64;
    let h_min = grid.abs() / f64::from(1u32 << MAX_HALVINGS);
    let at = |v: f64| [vec![v], fixed.to_vec()].concat();
    // the failed solves of the current point and their wall time (the accepted ones
    // carry theirs in `BvpRun::stats`)
    let failed = std::cell::Cell::new((0usize, 0.0f64));
    let solve = |v: f64, warm: Option<&WarmStart>| -> Result<BvpRun, PointStatus> {
        let s = plan.scene_at(&at(v)).map_err(|error| PointStatus::InvalidScene { error })?;
        let opts = plan.bvp_options(&s).map_err(|e| PointStatus::failed(e.to_string()))?;
        let clock = std::time::Instant::now();
        let run = match warm {
            Some(w) => bvp::scene::solve_scene_from(&s, &opts, w),
            None => bvp::scene::solve_scene(&s, &opts),
        };
        run.map_err(|e| {
            let (n, wall) = failed.get();
            failed.set((n + 1, wall + clock.elapsed().as_secs_f64()));
            PointStatus::failed(e.to_string())
        })
    };
    let mut points = Vec::new();
    let mut fold: Option<Fold> = None;
    // the accepted points of the continuation (intermediate ones included), last three
    let mut path: Vec<Converged> = Vec::new();
    for v in p0.values() {
        if fold.is_some() {
            points.push(Point { values: at(v), status: PointStatus::BeyondFold });
            tick(format!("{} = {} beyond the fold", p0.path, numerics::Sig(v)));
            continue;
        }
        let target = p0.coordinate(v);
        let (mut steps, mut newton, mut wall) = (0usize, 0usize, 0.0);
        failed.set((0, 0.0));
        let mut accept = |run: BvpRun, t: f64, path: &mut Vec<Converged>| {
            steps += 1;
            newton += run.stats.newton_iterations;
            wall += run.stats.wall_seconds;
            path.push(Converged { t, scalars: run.summary.scalars(), warm: run.warm });
            if path.len() > 3 {
                path.remove(0);
            }
        };
        let mut status: Option<PointStatus> = None;
        // after a point neither continuation nor a cold solve reached, the next is tried
        // cold only (beyond an admissibility limit the halvings would fail again)
        let after_failure = matches!(points.last(), Some(Point { status: PointStatus::Failed { .. }, .. }));
        if let Some(first) = path.last().filter(|c| c.warm.is_some() && !after_failure) {
            // natural-parameter continuation from the last converged point
            let mut h = target - first.t;
            loop {
                let here = path.last().expect("a converged point");
                let t = if (target - here.t).abs() <= h.abs() { target } else { here.t + h };
                let predicted = predictor(&path, t);
                let value = if t == target { v } else { p0.value(t) };
                match step_solve(&|warm| solve(value, warm), predicted.as_ref(), here.warm.as_ref()) {
                    Ok(run) => {
                        accept(run, t, &mut path);
                        if t == target {
                            status = Some(PointStatus::Solved { summary: path.last().map(|c| c.scalars.clone()).unwrap_or_default(), warm: true, steps: 0, newton_iterations: 0, wall_seconds: 0.0, failed_attempts: 0 });
                            break;
                        }
                        h *= 2.0;
                    }
                    Err(e @ PointStatus::InvalidScene { .. }) => {
                        status = Some(e);
                        break;
                    }
                    Err(_) if h.abs() / 2.0 >= h_min => h /= 2.0,
                    Err(e) => {
                        let cause = match &e {
                            PointStatus::Failed { error, .. } => error.as_str(),
                            _ => "",
                        };
                        fold = fold_at(p0, &path, h, grid, cause);
                        status = Some(if fold.is_some() { PointStatus::BeyondFold } else { e });
                        break;
                    }
                }
            }
        }
        // a cold solve: the first point, a model without warm starts, or a point the
        // continuation could not reach (not at a fold)
        let status = match status {
            Some(PointStatus::Solved { summary, warm, .. }) => {
                let (failed_attempts, failed_wall) = failed.get();
                PointStatus::Solved { summary, warm, steps, newton_iterations: newton, wall_seconds: wall + failed_wall, failed_attempts }
            }
            Some(s @ (PointStatus::InvalidScene { .. } | PointStatus::BeyondFold)) => s,
            None | Some(PointStatus::Failed { .. }) => match solve(v, None) {
                Ok(run) => {
                    accept(run, target, &mut path);
                    let summary = path.last().map(|c| c.scalars.clone()).unwrap_or_default();
                    let (failed_attempts, failed_wall) = failed.get();
                    PointStatus::Solved { summary, warm: false, steps, newton_iterations: newton, wall_seconds: wall + failed_wall, failed_attempts }
                }
                Err(PointStatus::Failed { error, .. }) => {
                    // a point no solve reached still reports the time its attempts took
                    let (failed_attempts, failed_wall) = failed.get();
                    PointStatus::Failed { error, wall_seconds: wall + failed_wall, failed_attempts }
                }
                Err(e) => e,
            },
        };
        tick(format!("{} = {}", p0.path, numerics::Sig(v)));
        points.push(Point { values: at(v), status });
    }
    let last = path.pop().and_then(|c| c.warm.map(|w| (p0.value(c.t), w)));
    let asymptotes = if plan.asymptotes { asymptotes(scene, plan, fixed, &points, last) } else { Vec::new() };
    Line { fixed: fixed.to_vec(), points, fold, asymptotes, wall_seconds: clock.elapsed().as_secs_f64() }
}

/// The asymptotes of a line that apply (module docs).
///
/// `last`: the line's last converged value and its warm start (the Kirchhoff limit
/// continues from it).
fn asymptotes(scene: &Scene, plan: &SweepPlan, fixed: &[f64], points: &[Point], last: Option<(f64, WarmStart)>) -> Vec<Asymptote> {
    let p0 = &plan.params[0];
    let mut out = Vec::new();
    let drive = matches!(scene.analysis, drive::scene::Analysis::Steady) && matches!(scene.effects.contact, Contact::Coulomb(_)) && scene.drive.layout == drive::scene::Layout::TwoPulley;
    // string limit: the string drive of each point's scene (a = b₂ = 0)
    if drive && scene.belt.theory != Theory::String {
        let mut a = Asymptote {
            name: "string limit (a → 0)".into(),
            detail: "the string-drive BVP of each point's scene (theory string: no bending, no shear), by warm-started continuation".into(),
            points: Vec::new(),
            notes: Vec::new(),
        };
        let mut warm: Option<WarmStart> = None;
        for p in points {
            let s = match plan.scene_at(&p.values).and_then(|s| string_of(&s)) {
                Ok(s) => s,
                Err(e) => {
                    a.notes.push(format!("{} = {}: {e}", p0.path, numerics::Sig(p.values[0])));
                    continue;
                }
            };
            let run = plan.bvp_options(&s).and_then(|o| match &warm {
                Some(w) => bvp::scene::solve_scene_from(&s, &o, w).or_else(|_| bvp::scene::solve_scene(&s, &o)),
                None => bvp::scene::solve_scene(&s, &o),
            });
            match run {
                Ok(r) => {
                    a.points.push(AsymptotePoint { value: p.values[0], summary: r.summary.scalars() });
                    warm = r.warm;
                }
                Err(e) => a.notes.push(format!("{} = {}: {e}", p0.path, numerics::Sig(p.values[0]))),
            }
        }
        out.push(a);
    }
    // Kirchhoff limit: b₂ → ∞, proxied by continuing the line in log b₂ to
    // KIRCHHOFF_DECADES decades beyond its largest value (the farthest point reached)
    if drive && scene.belt.theory == Theory::Cosserat && p0.path == "belt.shear_stiffness" {
        let mut a = Asymptote { name: "Kirchhoff limit (b₂ → ∞)".into(), detail: String::new(), points: Vec::new(), notes: Vec::new() };
        match last {
            None => a.notes.push("no converged point on the line to continue from".into()),
            Some((b_last, mut warm)) => {
                let steps = 4 * KIRCHHOFF_DECADES;
                let mut reached = None;
                for k in 1..=steps {
                    let b2 = b_last * 10f64.powf(k as f64 / 4.0);
                    let values = [vec![b2], fixed.to_vec()].concat();
                    let run = plan.scene_at(&values).map_err(|e| e.to_string()).and_then(|s| {
                        plan.bvp_options(&s).and_then(|o| bvp::scene::solve_scene_from(&s, &o, &warm)).map_err(|e| e.to_string())
                    });
                    match run {
                        Ok(r) => {
                            reached = Some((b2, r.summary.scalars()));
                            match r.warm {
                                Some(w) => warm = w,
                                None => break,
                            }
                        }
                        Err(e) => {
                            a.notes.push(format!("continuation in log b₂ stopped at b₂ = {}: {e}", numerics::Sig(b2)));
                            break;
                        }
                    }
                }
                if let Some((b2, summary)) = reached {
                    a.detail = format!(
                        "the Cosserat BVP continued in log b₂ from the line's last point to b₂ = {} N ({} × it; no Kirchhoff drive BVP exists), its values as horizontal lines",
                        numerics::Sig(b2),
                        numerics::Sig(b2 / b_last)
                    );
                    a.points.push(AsymptotePoint { value: b2, summary });
                }
            }
        }
        out.push(a);
    }
    // belt-creep closed form of each point's scene without gravity
    if drive {
        let mut a = Asymptote {
            name: "belt-creep closed form (g = 0)".into(),
            detail: "the gravity-free, bending-free closed form (bvp::analytical::belt_creep) of each point's scene".into(),
            points: Vec::new(),
            notes: Vec::new(),
        };
        for p in points {
            let Ok(s) = plan.scene_at(&p.values) else { continue };
            let Contact::Coulomb(mu) = s.effects.contact else { continue };
            match bvp::scene::string_drive_data(&s, mu).creep() {
                Ok(c) => a.points.push(AsymptotePoint {
                    value: p.values[0],
                    summary: vec![
                        ("tension_tight".into(), c.tension_tight),
                        ("tension_slack".into(), c.tension_slack),
                        ("driven_speed".into(), c.driven_speed),
                        ("transport_rate".into(), c.transport_rate),
                    ],
                }),
                Err(e) => a.notes.push(format!("{} = {}: {e}", p0.path, numerics::Sig(p.values[0]))),
            }
        }
        out.push(a);
    }
    out
}

/// The string drive of a scene: theory string, the bending and shear stiffnesses left out.
fn string_of(scene: &Scene) -> Result<Scene, String> {
    let mut v: serde_json::Value = serde_json::from_str(&scene.to_json_pretty()).map_err(|e| e.to_string())?;
    if let Some(b) = v.get_mut("belt").and_then(|b| b.as_object_mut()) {
        b.insert("theory".into(), "string".into());
        for k in ["bending_stiffness", "shear_stiffness", "thickness", "width", "youngs_modulus", "shear_modulus", "poisson_ratio"] {
            b.remove(k);
        }
    }
    if let Some(o) = v.as_object_mut() {
        o.remove("gate");
        o.remove("fem");
    }
    Scene::from_json_str(&v.to_string()).map_err(|e| e.to_string())
}

/// FE spot checks: `fe_points` evenly spaced solved points per line, in parallel.
fn fe_spot_checks(scene: &Scene, plan: &SweepPlan, lines: &[Line], tick: &(dyn Fn(String) + Sync)) -> Vec<FeCheck> {
    if plan.fe_points == 0 {
        return Vec::new();
    }
    let Ok(formulation) = crate::run::default_formulation(scene) else {
        return Vec::new();
    };
    let n = plan.params[0].points;
    let k = plan.fe_points.min(n);
    let picks: Vec<(usize, usize)> = (0..lines.len())
        .flat_map(|l| (0..k).map(move |j| (l, if k == 1 { n / 2 } else { (j * (n - 1) + (k - 1) / 2) / (k - 1) })))
        .collect();
    picks
        .par_iter()
        .map(|&(l, i)| {
            let point = &lines[l].points[i];
            let clock = Instant::now();
            let method = FemFormulation { name: formulation.clone(), penalty: None };
            let result = match point.summary() {
                None => Err("the BVP has no solution at this point".to_string()),
                Some(bvp) => plan
                    .scene_at(&point.values)
                    .and_then(|s| method.solve(&s, Discretisation::Elements(plan.fe_elements)).map_err(|e| e.to_string()))
                    .map(|fe| {
                        let fe = fe.summary.scalars();
                        bvp.iter()
                            .filter_map(|(name, b)| fe.iter().find(|(m, _)| m == name).map(|(_, f)| (name.clone(), *f, *b, (f - b).abs() / f.abs().max(b.abs()).max(1e-300))))
                            .collect()
                    }),
            };
            tick(format!("FE at {} = {}", plan.params[0].path, numerics::Sig(point.values[0])));
            FeCheck { line: l, point: i, values: point.values.clone(), formulation: formulation.clone(), elements: plan.fe_elements, result, wall_seconds: clock.elapsed().as_secs_f64() }
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Output: JSON, Markdown, SVG

/// The JSON of a sweep (every point's summary against the parameters).
pub fn sweep_json(sweep: &Sweep) -> Result<String, SweepError> {
    Ok(serde_json::to_string_pretty(sweep)? + "\n")
}

/// Every scalar name produced at any solved point, in first-seen order.
fn quantity_names(sweep: &Sweep) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for p in sweep.lines.iter().flat_map(|l| &l.points) {
        for (n, _) in p.summary().unwrap_or(&[]) {
            if !names.contains(n) {
                names.push(n.clone());
            }
        }
    }
    names
}

const LINE_COLORS: [RGBColor; 6] = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(148, 103, 189), RGBColor(255, 127, 14), RGBColor(23, 190, 207)];
const ASYMPTOTE_COLORS: [RGBColor; 3] = [RGBColor(120, 120, 120), RGBColor(0, 0, 0), RGBColor(230, 115, 0)];

/// Every scalar against the line parameter, one panel each: the BVP lines (one colour
/// per line), FE spot checks (crosses), the asymptotes dashed, folds marked.
pub fn sweep_svg(sweep: &Sweep) -> Result<String, SweepError> {
    let names = quantity_names(sweep);
    let p0 = &sweep.plan.params[0];
    let cols = 3usize;
    let rows = names.len().div_ceil(cols).max(1);
    let (w, h) = (1200u32, 300 * rows as u32 + 40);
    let mut buf = String::new();
    let draw = |buf: &mut String| -> Result<(), String> {
        let root = SVGBackend::with_string(buf, (w, h)).into_drawing_area();
        let e = |e: &dyn fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let (title, body) = root.split_vertically(40);
        title
            .draw(&Text::new(
                format!("{} — outputs against {}{} (BVP lines; FE crosses; asymptotes dashed: grey string limit, black Kirchhoff, orange creep)", sweep.scene, p0.path, if p0.log { " (log)" } else { "" }),
                (10, 12),
                ("sans-serif", 16).into_font(),
            ))
            .map_err(|x| e(&x))?;
        let panels = body.split_evenly((rows, cols));
        for (name, area) in names.iter().zip(panels.iter()) {
            let mut xs = Vec::new();
            let mut ys = Vec::new();
            let curves: Vec<Vec<(f64, f64)>> = sweep
                .lines
                .iter()
                .map(|l| l.points.iter().filter_map(|p| p.get(name).map(|y| (p0.coordinate(p.values[0]), y))).collect())
                .collect();
            let asym: Vec<(usize, Vec<(f64, f64)>)> = sweep
                .lines
                .iter()
                .flat_map(|l| l.asymptotes.iter().enumerate())
                .filter_map(|(k, a)| {
                    let pts: Vec<(f64, f64)> = a.points.iter().filter_map(|q| q.summary.iter().find(|(n, _)| n == name).map(|(_, y)| (q.value, *y))).collect();
                    match pts.len() {
                        0 => None,
                        // a horizontal asymptote across the sweep
                        1 => Some((k, vec![(p0.coordinate(p0.from), pts[0].1), (p0.coordinate(p0.to), pts[0].1)])),
                        _ => Some((k, pts.into_iter().map(|(x, y)| (p0.coordinate(x), y)).collect())),
                    }
                })
                .collect();
            let fe: Vec<(f64, f64)> = sweep
                .fe_checks
                .iter()
                .filter_map(|c| c.result.as_ref().ok()?.iter().find(|(n, ..)| n == name).map(|(_, f, ..)| (p0.coordinate(c.values[0]), *f)))
                .collect();
            for (x, y) in curves.iter().flatten().chain(asym.iter().flat_map(|(_, c)| c)).chain(&fe) {
                if x.is_finite() && y.is_finite() {
                    xs.push(*x);
                    ys.push(*y);
                }
            }
            if ys.is_empty() {
                continue;
            }
            let (x0, x1) = (p0.coordinate(p0.from).min(p0.coordinate(p0.to)), p0.coordinate(p0.from).max(p0.coordinate(p0.to)));
            let (lo, hi) = ys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| (a.min(y), b.max(y)));
            let pad = ((hi - lo) * 0.08).max(1e-9 * (1.0 + hi.abs()));
            let mut chart = ChartBuilder::on(area)
                .caption(name, ("sans-serif", 15))
                .margin(8)
                .x_label_area_size(28)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, (lo - pad)..(hi + pad))
                .map_err(|x| e(&x))?;
            let log = p0.log;
            let xfmt = move |v: &f64| if log { format!("{}", numerics::Sig(10f64.powf(*v))) } else { format!("{}", numerics::Sig(*v)) };
            let yfmt = |v: &f64| format!("{}", numerics::Sig(*v));
            chart
                .configure_mesh()
                .light_line_style(WHITE)
                .bold_line_style(RGBColor(225, 225, 225))
                .x_labels(5)
                .y_labels(5)
                .x_label_formatter(&xfmt)
                .y_label_formatter(&yfmt)
                .label_style(("sans-serif", 11))
                .draw()
                .map_err(|x| e(&x))?;
            for (k, c) in asym {
                chart.draw_series(DashedLineSeries::new(c, 6, 4, ASYMPTOTE_COLORS[k % 3].stroke_width(1))).map_err(|x| e(&x))?;
            }
            for (i, c) in curves.into_iter().enumerate() {
                let col = LINE_COLORS[i % LINE_COLORS.len()];
                chart.draw_series(LineSeries::new(c.clone(), col.stroke_width(2))).map_err(|x| e(&x))?;
                chart.draw_series(c.into_iter().map(|p| Circle::new(p, 2, col.filled()))).map_err(|x| e(&x))?;
            }
            chart.draw_series(fe.into_iter().map(|p| Cross::new(p, 5, BLACK.stroke_width(2)))).map_err(|x| e(&x))?;
            for l in &sweep.lines {
                if let Some(f) = &l.fold {
                    let x = p0.coordinate(f.last_converged);
                    chart.draw_series(DashedLineSeries::new([(x, lo - pad), (x, hi + pad)], 3, 3, RED.stroke_width(1))).map_err(|x| e(&x))?;
                }
            }
        }
        root.present().map_err(|x| e(&x))
    };
    draw(&mut buf).map_err(|message| crate::plot::PlotError { plot: "sweep", message })?;
    Ok(buf)
}

/// The Markdown report of a sweep: command, timing, failures and folds, the FE spot
/// checks, the asymptotes, a table of the headline outputs.
pub fn sweep_markdown(sweep: &Sweep, command: &str) -> String {
    use std::fmt::Write;
    let p0 = &sweep.plan.params[0];
    let mut md = String::new();
    let _ = writeln!(md, "# Parameter study of `{}`\n", sweep.scene);
    let _ = writeln!(md, "```\n{command}\n```\n");
    let solved = sweep.solved();
    let warm = sweep.lines.iter().flat_map(|l| &l.points).filter(|p| matches!(p.status, PointStatus::Solved { warm: true, .. })).count();
    let _ = writeln!(
        md,
        "{} line(s), {} BVP points: {solved} solved ({warm} by warm start), in {:.1} s wall on {} thread(s); BVP tolerance {}; figure: [sweep.svg](sweep.svg), every number: [sweep.json](sweep.json).\n",
        sweep.lines.len(),
        sweep.plan.point_count(),
        sweep.wall_seconds,
        sweep.threads,
        crate::run::fmt_tolerance(sweep.plan.tolerance)
    );
    for p in &sweep.plan.params {
        let _ = writeln!(md, "- `{}` = {} … {} ({} points{})", p.path, numerics::Sig(p.from), numerics::Sig(p.to), p.points, if p.log { ", log" } else { "" });
    }
    let failures = sweep.failures();
    if !failures.is_empty() {
        let _ = writeln!(md, "\n## Points without a solution ({})\n", failures.len());
        for f in &failures {
            let _ = writeln!(md, "- {f}");
        }
    }
    let headline = ["y_upper_mid", "y_lower_mid", "tension_tight", "tension_slack", "driven_speed", "transport_rate", "driver.slip_arc", "driven.slip_arc", "driver.contact_arc"];
    let names = quantity_names(sweep);
    let cols: Vec<&str> = headline.iter().copied().filter(|h| names.iter().any(|n| n == h)).collect();
    for (li, line) in sweep.lines.iter().enumerate() {
        let _ = write!(md, "\n## Line {}", li + 1);
        if !line.fixed.is_empty() {
            let _ = write!(md, ": {}", fixed_label(&sweep.plan, &line.fixed));
        }
        let _ = writeln!(md, " ({:.1} s)\n", line.wall_seconds);
        let _ = writeln!(md, "| {} | start | steps | Newton | s | {} |", p0.path, cols.join(" | "));
        let _ = writeln!(md, "|{}", "---|".repeat(5 + cols.len()));
        for p in &line.points {
            let v = numerics::Sig(p.values[0]);
            match &p.status {
                PointStatus::Solved { warm, steps, newton_iterations, wall_seconds, failed_attempts, .. } => {
                    let vals: Vec<String> = cols.iter().map(|c| p.get(c).map(|x| format!("{}", numerics::Sig(x))).unwrap_or_default()).collect();
                    let failed = if *failed_attempts > 0 { format!(" (+{failed_attempts} failed)") } else { String::new() };
                    let _ = writeln!(md, "| {v} | {} | {steps}{failed} | {newton_iterations} | {wall_seconds:.3} | {} |", if *warm { "warm" } else { "cold" }, vals.join(" | "));
                }
                PointStatus::InvalidScene { .. } => {
                    let _ = writeln!(md, "| {v} | invalid scene |{}", " |".repeat(3 + cols.len()));
                }
                PointStatus::Failed { failed_attempts, wall_seconds, .. } => {
                    let _ = writeln!(md, "| {v} | failed | ({failed_attempts} failed) | | {wall_seconds:.3} |{}", " |".repeat(cols.len()));
                }
                PointStatus::BeyondFold => {
                    let _ = writeln!(md, "| {v} | beyond fold |{}", " |".repeat(3 + cols.len()));
                }
            }
        }
        for a in &line.asymptotes {
            let _ = writeln!(md, "\nAsymptote — {}: {} ({} value(s)).", a.name, a.detail, a.points.len());
            // the same reason at many points once, with their count
            let mut reasons: Vec<(&str, usize)> = Vec::new();
            for n in &a.notes {
                let reason = n.split_once(": ").map_or(n.as_str(), |(_, r)| r);
                match reasons.iter_mut().find(|(r, _)| *r == reason) {
                    Some((_, k)) => *k += 1,
                    None => reasons.push((reason, 1)),
                }
            }
            for (r, k) in reasons {
                let _ = writeln!(md, "  - not computed at {k} point(s): {r}");
            }
        }
    }
    if !sweep.fe_checks.is_empty() {
        let _ = writeln!(md, "\n## FE spot checks\n");
        let _ = writeln!(md, "| line | {} | formulation | elements | largest relative FE–BVP difference | s |", p0.path);
        let _ = writeln!(md, "|---|---|---|---|---|---|");
        for c in &sweep.fe_checks {
            let worst = match (&c.result, c.worst()) {
                (Err(e), _) => format!("failed: {e}"),
                (Ok(_), Some((n, r))) => format!("{} ({n})", numerics::Sig(r)),
                (Ok(_), None) => "no common scalar".into(),
            };
            let _ = writeln!(md, "| {} | {} | {} | {} | {worst} | {:.2} |", c.line + 1, numerics::Sig(c.values[0]), c.formulation, c.elements, c.wall_seconds);
        }
    }
    md
}

/// Write the sweep's files (`sweep.md`, `sweep.svg`, `sweep.json`) into `dir`: all
/// three are rendered first, written to temporary files and renamed only when all
/// were written; on any error nothing of them is left behind.
///
/// # Errors
/// [`SweepError::Plot`], [`SweepError::Json`], [`SweepError::Write`].
pub fn write_sweep(sweep: &Sweep, command: &str, dir: &Path) -> Result<Vec<PathBuf>, SweepError> {
    let files = [("sweep.md", sweep_markdown(sweep, command)), ("sweep.svg", sweep_svg(sweep)?), ("sweep.json", sweep_json(sweep)?)];
    crate::files::create_dir(dir)?;
    let paths: Vec<PathBuf> = files.iter().map(|(name, _)| dir.join(name)).collect();
    let set: Vec<(PathBuf, &str)> = paths.iter().cloned().zip(files.iter().map(|(_, text)| text.as_str())).collect();
    crate::files::write_all(&set)?;
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(t: f64, y: f64) -> Converged {
        Converged { t, warm: None, scalars: vec![("y".into(), y), ("z".into(), 1.0)] }
    }

    /// A branch y(t) = 1 + √(1 − t) near its fold at t = 1: the tangent's η-component
    /// falls as the steps approach it, and the fold is stated with the numbers; a
    /// straight branch is not a fold.
    #[test]
    fn a_turning_tangent_is_a_fold_and_a_straight_branch_is_not() {
        let p0: ParamRange = "drive.driven_torque=0:1:3".parse().unwrap();
        let y = |t: f64| 1.0 + (1.0 - t).sqrt();
        let turning = [point(0.5, y(0.5)), point(0.9, y(0.9)), point(0.999, y(0.999))];
        let f = fold_at(&p0, &turning, 0.002, 0.5, "diverged").expect("a fold");
        assert!(f.message.starts_with("fold/no solution beyond drive.driven_torque = 0.999"), "{}", f.message);
        assert!((f.not_reached - 1.001).abs() < 1e-12 && f.tangent.0 < f.tangent.1, "{f:?}");
        let straight = [point(0.5, 1.5), point(0.9, 1.9), point(0.999, 1.999)];
        assert!(fold_at(&p0, &straight, 0.002, 0.5, "diverged").is_none());
    }

    /// The secant predictor of a line (module docs, `predictor`): none from a single
    /// point, from a point without a warm start, or for a step more than
    /// [`MAX_PREDICTOR_RATIO`] times the last; otherwise the last solution extrapolated
    /// (its parameters exactly p₁ + r(p₁ − p₀), to round-off 1e-12 of their size). A
    /// step from it reaches the solution of a plain warm start (the predictor changes the
    /// guess only: the summaries agree to 1e-7 relative, 10× the solver tolerance 1e-8
    /// for two collocation solutions on their own adapted meshes) in no more Newton
    /// iterations. Source: the catalogue's `string-drive` (cheap: a string drive) along
    /// its driven torque, 10 → 10.5 → 11 N·m.
    /// The catalogue's `string-drive` (cheap: a string drive) swept along its driven
    /// torque, 10 → 10.5 → 11 N·m.
    fn torque_line() -> SweepPlan {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/string-drive.json");
        let scene = Scene::from_path(std::path::Path::new(path)).expect("catalogue scene");
        let range: ParamRange = "drive.driven_torque=10:11:3".parse().unwrap();
        SweepPlan::new(&scene, vec![range], 0).unwrap()
    }

    /// The BVP run of `plan` at the value `v`, cold or from `warm`.
    fn run_at(plan: &SweepPlan, v: f64, warm: Option<&WarmStart>) -> Result<BvpRun, PointStatus> {
        let s = plan.scene_at(&[v]).unwrap();
        let opts = plan.bvp_options(&s).unwrap();
        match warm {
            Some(w) => bvp::scene::solve_scene_from(&s, &opts, w),
            None => bvp::scene::solve_scene(&s, &opts),
        }
        .map_err(|e| PointStatus::failed(e.to_string()))
    }

    #[test]
    fn the_secant_predictor_extrapolates_and_changes_only_the_guess() {
        let plan = torque_line();
        let run = |v: f64, warm: Option<&WarmStart>| run_at(&plan, v, warm).unwrap();
        let first = run(10.0, None);
        let second = run(10.5, first.warm.as_ref());
        let converged = |t: f64, r: &BvpRun| Converged { t, warm: r.warm.clone(), scalars: r.summary.scalars() };
        let path = vec![converged(10.0, &first), converged(10.5, &second)];
        assert!(predictor(&path[..1], 11.0).is_none(), "one point has no secant");
        assert!(predictor(&path, 12.6).is_none(), "a step of 4.2 times the last starts from the last point");
        assert!(predictor(&[path[0].clone(), point(10.5, 1.0)], 11.0).is_none(), "no warm start, no predictor");
        let predicted = predictor(&path, 11.0).expect("two comparable points");
        let params = |w: &WarmStart| match w {
            WarmStart::StringDrive(s) => s.solution.params.clone(),
            WarmStart::CosseratDrive(s) => s.solution.params.clone(),
        };
        let (p0, p1, p2) = (params(path[0].warm.as_ref().unwrap()), params(path[1].warm.as_ref().unwrap()), params(&predicted));
        for ((a, b), c) in p0.iter().zip(&p1).zip(&p2) {
            let want = b + (b - a);
            assert!((c - want).abs() <= 1e-12 * want.abs().max(1.0), "parameter {c} against {want}");
        }
        let plain = run(11.0, second.warm.as_ref());
        let secant = run(11.0, Some(&predicted));
        for ((name, a), (_, b)) in plain.summary.scalars().iter().zip(secant.summary.scalars()) {
            assert!((a - b).abs() <= 1e-7 * a.abs().max(1e-3), "{name}: {a} (plain) against {b} (predictor)");
        }
        assert!(
            secant.stats.newton_iterations <= plain.stats.newton_iterations,
            "predictor {} against plain warm start {} Newton iterations",
            secant.stats.newton_iterations,
            plain.stats.newton_iterations
        );
    }

    /// A step whose predicted warm start fails is retried from the plain warm start
    /// (`step_solve`, module docs): here the solver refuses the predicted start (as a
    /// predictor overshooting into an inadmissible topology would make it fail) and the
    /// step still solves, from the last solution, to its plain warm start's summary (the
    /// same solve: to 1e-12); without the retry the step fails. A failure of both is
    /// the step's failure (two solves); an invalid scene is not retried (one); without a
    /// predictor there is one solve from the plain start. Source: [`torque_line`].
    #[test]
    fn a_failed_predicted_start_is_retried_from_the_last_solution() {
        let plan = torque_line();
        let run = |v: f64, warm: Option<&WarmStart>| run_at(&plan, v, warm);
        let first = run(10.0, None).unwrap();
        let second = run(10.5, first.warm.as_ref()).unwrap();
        let converged = |t: f64, r: &BvpRun| Converged { t, warm: r.warm.clone(), scalars: r.summary.scalars() };
        let path = vec![converged(10.0, &first), converged(10.5, &second)];
        let predicted = predictor(&path, 11.0).expect("two comparable points");
        let plain = second.warm.as_ref();
        let calls = std::cell::RefCell::new(Vec::new());
        let refusing = |warm: Option<&WarmStart>| {
            let is_predicted = warm.is_some_and(|w| std::ptr::eq(w, &predicted));
            calls.borrow_mut().push(is_predicted);
            if is_predicted {
                Err(PointStatus::failed("refused: the predicted start".into()))
            } else {
                run(11.0, warm)
            }
        };
        let solved = step_solve(&refusing, Some(&predicted), plain).expect("retried from the plain warm start");
        assert_eq!(*calls.borrow(), vec![true, false]);
        let direct = run(11.0, plain).unwrap();
        for ((name, a), (_, b)) in solved.summary.scalars().iter().zip(direct.summary.scalars()) {
            assert!((a - b).abs() <= 1e-12 * a.abs().max(1e-3), "{name}: {a} (retried) against {b} (plain)");
        }
        // both fail: the step's failure, after two solves
        calls.borrow_mut().clear();
        let failing = |warm: Option<&WarmStart>| -> Result<BvpRun, PointStatus> {
            calls.borrow_mut().push(warm.is_some_and(|w| std::ptr::eq(w, &predicted)));
            Err(PointStatus::failed("refused".into()))
        };
        assert!(matches!(step_solve(&failing, Some(&predicted), plain), Err(PointStatus::Failed { .. })));
        assert_eq!(*calls.borrow(), vec![true, false]);
        // an invalid scene is not retried; no predictor, one solve from the plain start
        calls.borrow_mut().clear();
        let invalid = |warm: Option<&WarmStart>| -> Result<BvpRun, PointStatus> {
            calls.borrow_mut().push(warm.is_some_and(|w| std::ptr::eq(w, &predicted)));
            Err(PointStatus::InvalidScene { error: "bad".into() })
        };
        assert!(matches!(step_solve(&invalid, Some(&predicted), plain), Err(PointStatus::InvalidScene { .. })));
        assert_eq!(*calls.borrow(), vec![true]);
        calls.borrow_mut().clear();
        assert!(matches!(step_solve(&failing, None, plain), Err(PointStatus::Failed { .. })));
        assert_eq!(*calls.borrow(), vec![false]);
    }

    /// Ranges: values equally spaced in the value or its logarithm, ends exact.
    #[test]
    fn ranges_are_equally_spaced_in_their_coordinate() {
        let r: ParamRange = "belt.shear_stiffness=1e2:1e6:log:5".parse().unwrap();
        let v = r.values();
        assert_eq!((v[0], v[4]), (1e2, 1e6));
        assert!((v[2] - 1e4).abs() < 1e-9);
        let r: ParamRange = "a.b=1:2:3".parse().unwrap();
        assert_eq!(r.values(), vec![1.0, 1.5, 2.0]);
    }
}
