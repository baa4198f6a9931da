//! What a study holds its runs against (issue 11 item 6): a BVP run, a closed form, or —
//! for a model with no BVP, like the shell — Richardson extrapolation of the finest runs
//! of an FE study.
//!
//! Every kind yields a [`Run`] whose method label says which reference it is (tables and
//! reports print it), plus, for the Richardson kind, an error estimate per quantity:
//! - [`Reference::Bvp`]: one BVP run at a tight tolerance (the default where the model
//!   has a BVP);
//! - [`Reference::ClosedForm`]: the closed form of the scene's model
//!   ([`crate::closed_form`]; today the elastic catenary loop of `string-hanging`), solved
//!   to [`crate::closed_form::CATENARY_TOLERANCE`]; summary scalars only (no fields);
//! - [`Reference::Richardson`]: an FE formulation at three or more levels refined by one
//!   constant ratio r (1-D meshes, or 2-D meshes with their time step refined alike).
//!   Each scalar q of the three finest levels q₁, q₂, q₃ is extrapolated with the
//!   observed order p = ln(|q₂ − q₁|/|q₃ − q₂|)/ln r to q_R = q₃ + (q₃ − q₂)/(r^p − 1), and
//!   its error estimate is the correction |q_R − q₃| (in the asymptotic range the error of
//!   q_R is of higher order, so this bounds it). A quantity is **refused** (left out of
//!   the reference, with a note) when its levels are not in the asymptotic range: the
//!   differences change sign (oscillating), or |q₃ − q₂| ≥ |q₂ − q₁| (p ≤ 0, not
//!   converging). A **warning** note is written when p lies outside [0.5, 8] (no
//!   discretisation here converges so slowly or so fast: the levels are likely
//!   pre-asymptotic) or, with a fourth level, the order of the coarser triple differs
//!   from p by more than 25 %. Fields are extrapolated pointwise with the order of their
//!   L2 differences. A quantity whose two finest levels agree to round-off (1e-14
//!   relative) is taken as converged: q₃ with estimate |q₃ − q₂|.

use std::time::Instant;

use drive::scene::Scene;
use serde::Serialize;

use crate::closed_form::{CatenaryLoop, CATENARY_TOLERANCE};
use crate::measure::{self, Norm};
use crate::run::{execute, BvpSolver, BvpVariant, Discretisation, Family, FemFormulation, Run, RunCost, RunData, RunError, Samples, ShellFe, SHELL_FORMULATION};

/// The reference of a study.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Reference {
    /// A BVP run: this variant at this tolerance.
    Bvp {
        /// Collocation scheme or shooting.
        variant: BvpVariant,
        /// Relative tolerance.
        tolerance: f64,
    },
    /// The closed form of the scene's model.
    ClosedForm,
    /// Richardson extrapolation of an FE formulation over these levels (coarsest first,
    /// at least three, one constant refinement ratio over the three finest).
    Richardson {
        /// Registered FE formulation.
        formulation: String,
        /// Its discretisations, coarsest first.
        levels: Vec<Discretisation>,
    },
    /// Richardson extrapolation of runs supplied from outside (`beltcheck check` on a
    /// scene no BVP solves): the same extrapolation and checks as
    /// [`Reference::Richardson`], over results read from files rather than computed.
    Supplied {
        /// The outside code's method name, as its result files give it.
        method: String,
        /// Its discretisations, coarsest first.
        levels: Vec<Discretisation>,
    },
}

/// The extrapolated value of one scalar of a Richardson reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// Summary flat name.
    pub quantity: String,
    /// Value at the finest level.
    pub finest: f64,
    /// Extrapolated value q_R (the reference value).
    pub value: f64,
    /// Observed order p of the three finest levels (`None`: converged to round-off).
    pub order: Option<f64>,
    /// |q_R − q₃|: the stated error estimate of the reference value (absolute).
    pub error_estimate: f64,
}

/// Why a Richardson reference could not be formed.
#[derive(Debug, Clone, thiserror::Error)]
pub enum RichardsonError {
    /// Fewer than three levels.
    #[error("Richardson extrapolation needs three levels or more, got {levels}")]
    TooFewLevels {
        /// Levels given.
        levels: usize,
    },
    /// The three finest levels are not refined by one constant ratio (or mix kinds).
    #[error("the three finest levels {} are not refined in one way by one constant ratio > 1", list(.levels))]
    NotUniform {
        /// The three finest levels.
        levels: Vec<Discretisation>,
    },
    /// A level's run failed.
    #[error("level {level} failed: {source}")]
    LevelFailed {
        /// The level.
        level: Discretisation,
        /// Its failure.
        source: RunError,
    },
    /// No scalar is in the asymptotic range.
    #[error("no summary scalar is in the asymptotic range over the three finest levels ({})", .refused.join("; "))]
    NotAsymptotic {
        /// Every scalar with why it was refused.
        refused: Vec<String>,
    },
}

/// The cells of the (up to) three finest levels: `64, 128, 256`.
fn finest_cells(levels: &[Discretisation]) -> String {
    let n = levels.len().min(3);
    levels[levels.len() - n..].iter().map(|d| d.cell()).collect::<Vec<_>>().join(", ")
}

/// The levels, comma-separated, as messages print them.
pub(crate) fn list(levels: &[Discretisation]) -> String {
    levels.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
}

/// Why one quantity was not extrapolated.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum NotAsymptotic {
    /// The differences change sign.
    #[error("oscillating: q₂ − q₁ = {d21:.3e}, q₃ − q₂ = {d32:.3e}")]
    Oscillating {
        /// q₂ − q₁.
        d21: f64,
        /// q₃ − q₂.
        d32: f64,
    },
    /// The finer difference is not smaller: p ≤ 0.
    #[error("not converging: |q₃ − q₂| = {d32:.3e} ≥ |q₂ − q₁| = {d21:.3e}")]
    NotConverging {
        /// |q₂ − q₁|.
        d21: f64,
        /// |q₃ − q₂|.
        d32: f64,
    },
}

/// Richardson extrapolation of three levels q₁, q₂, q₃ (coarse to fine) at ratio r with
/// the asymptotic-range checks of the module docs: (q_R, p, |q_R − q₃|).
///
/// # Errors
/// [`NotAsymptotic`] when the levels oscillate or do not converge.
pub fn extrapolate_checked(q: [f64; 3], ratio: f64) -> Result<(f64, Option<f64>, f64), NotAsymptotic> {
    let (d21, d32) = (q[1] - q[0], q[2] - q[1]);
    if d32.abs() <= 1e-14 * q[2].abs() {
        return Ok((q[2], None, d32.abs()));
    }
    if d21 * d32 < 0.0 {
        return Err(NotAsymptotic::Oscillating { d21, d32 });
    }
    let p = measure::self_order(q[0], q[1], q[2], ratio).filter(|&p| p > 0.0);
    let value = p.and_then(|p| measure::richardson(q[1], q[2], ratio, p));
    match (p, value) {
        (Some(p), Some(v)) => Ok((v, Some(p), (v - q[2]).abs())),
        _ => Err(NotAsymptotic::NotConverging { d21: d21.abs(), d32: d32.abs() }),
    }
}

/// The reference's run, its error estimates (Richardson only) and notes for the reader.
#[derive(Debug, Clone)]
pub struct ReferenceRun {
    /// The reference as a run (its `method` is [`Reference::label`]).
    pub run: Run,
    /// Per scalar: the extrapolated value and its error estimate (Richardson only).
    pub estimates: Vec<Estimate>,
    /// Refused quantities and warnings.
    pub notes: Vec<String>,
}

impl Reference {
    /// What the reference is, in words, as tables and reports print it (before the
    /// discretisation of its run: "BVP run bvp-collocation gauss6" at tol 1e-11,
    /// "Richardson extrapolation of fem string-simpson (levels 64, 128, 256), finest" at
    /// 256 el.).
    pub fn label(&self) -> String {
        match self {
            Reference::Bvp { variant, .. } => format!("BVP run {}", variant.label()),
            Reference::ClosedForm => "closed form (elastic catenary loop)".to_string(),
            Reference::Richardson { formulation, levels } => format!("Richardson extrapolation of fem {formulation} (levels {}), finest", finest_cells(levels)),
            Reference::Supplied { method, levels } => format!("Richardson extrapolation of the supplied runs of {method} (levels {}), finest", finest_cells(levels)),
        }
    }

    /// Runs the reference computes.
    pub fn run_count(&self) -> usize {
        match self {
            Reference::Bvp { .. } | Reference::ClosedForm => 1,
            Reference::Richardson { levels, .. } => levels.len(),
            Reference::Supplied { .. } => 0,
        }
    }

    /// Computes the reference of `scene`, its fields sampled at `samples` points (the
    /// BVP run's collocation cap overridden by `max_nodes` if given). A failure is the
    /// run's outcome, never a panic.
    pub fn compute(&self, scene: &Scene, samples: usize, max_nodes: Option<usize>) -> ReferenceRun {
        match self {
            Reference::Bvp { variant, tolerance } => {
                let solver = BvpSolver { variant: *variant, max_nodes };
                let mut run = execute(&solver, scene, Discretisation::Tolerance(*tolerance), samples);
                run.method = self.label();
                ReferenceRun { run, estimates: Vec::new(), notes: Vec::new() }
            }
            Reference::ClosedForm => {
                let start = Instant::now();
                let solved = CatenaryLoop::of_scene(scene);
                let wall = start.elapsed().as_secs_f64();
                let outcome = solved.map_err(RunError::ClosedForm).map(|lp| RunData {
                    summary: lp.summary(),
                    cost: RunCost::counted(wall, lp.iterations, 4),
                    options: serde_json::json!({"closed_form": "elastic catenary loop", "tolerance": CATENARY_TOLERANCE}),
                    terms: Vec::new(),
                    notes: vec!["summary scalars only: the closed form gives no fields, so no field norms are measured against it".into()],
                    warnings: Vec::new(),
                    samples: Samples::default(),
                    history: None,
                });
                let run = Run { method: self.label(), family: Family::ClosedForm, discretisation: Discretisation::Tolerance(CATENARY_TOLERANCE), wall_seconds: wall, outcome };
                ReferenceRun { run, estimates: Vec::new(), notes: Vec::new() }
            }
            Reference::Richardson { formulation, levels } => {
                let runs: Vec<Run> = if formulation == SHELL_FORMULATION {
                    levels.iter().map(|&d| execute(&ShellFe, scene, d, samples)).collect()
                } else {
                    let method = FemFormulation { name: formulation.clone(), penalty: None };
                    levels.iter().map(|&d| execute(&method, scene, d, samples)).collect()
                };
                self.richardson(&runs)
            }
            Reference::Supplied { method, .. } => {
                let why = format!("the supplied runs of {method} are not computed here: `Reference::of_supplied` extrapolates them");
                let outcome = Err(RunError::NotApplicable(why));
                let run = Run { method: self.label(), family: Family::Fem, discretisation: Discretisation::Elements(0), wall_seconds: 0.0, outcome };
                ReferenceRun { run, estimates: Vec::new(), notes: Vec::new() }
            }
        }
    }

    /// The reference [`Reference::Supplied`] formed from the supplied runs, coarsest
    /// first (each sampled on the harness's σ grid): Richardson extrapolation of the
    /// three finest, as for [`Reference::Richardson`].
    pub fn of_supplied(method: &str, runs: &[Run]) -> (Reference, ReferenceRun) {
        let reference = Reference::Supplied { method: method.to_string(), levels: runs.iter().map(|r| r.discretisation).collect() };
        let computed = reference.richardson(runs);
        (reference, computed)
    }

    /// The Richardson reference from the runs of its levels (coarsest first): a study
    /// whose series are those same runs (the shell's) computes them once and passes them
    /// here.
    pub(crate) fn richardson(&self, runs: &[Run]) -> ReferenceRun {
        let wall: f64 = runs.iter().map(|r| r.wall_seconds).sum();
        let finest = runs.last().map_or(Discretisation::Elements(0), |r| r.discretisation);
        let mut notes = Vec::new();
        let mut estimates = Vec::new();
        let outcome = richardson_data(runs, &mut estimates, &mut notes).map_err(|e| RunError::Richardson(Box::new(e)));
        let run = Run { method: self.label(), family: Family::Fem, discretisation: finest, wall_seconds: wall, outcome };
        ReferenceRun { run, estimates, notes }
    }
}

/// The extrapolated run data of the module docs.
fn richardson_data(runs: &[Run], estimates: &mut Vec<Estimate>, notes: &mut Vec<String>) -> Result<RunData, RichardsonError> {
    let n = runs.len();
    if n < 3 {
        return Err(RichardsonError::TooFewLevels { levels: n });
    }
    let three = &runs[n - 3..];
    let levels: Vec<Discretisation> = three.iter().map(|r| r.discretisation).collect();
    let ratio = match (levels[0].refinement(levels[1]), levels[1].refinement(levels[2])) {
        (Some((k1, a)), Some((k2, b))) if k1 == k2 && (a - b).abs() <= 1e-9 * b => b,
        _ => return Err(RichardsonError::NotUniform { levels }),
    };
    let mut data = Vec::new();
    for r in three {
        match &r.outcome {
            Ok(d) => data.push(d),
            Err(e) => return Err(RichardsonError::LevelFailed { level: r.discretisation, source: e.clone() }),
        }
    }
    // a fourth, coarser level (if it solved) checks the order
    let coarser = (n >= 4).then(|| runs[n - 4].data()).flatten();
    let coarser_ratio = (n >= 4).then(|| runs[n - 4].discretisation.refinement_ratio(levels[0])).flatten();
    let finest = data[2];
    let mut summary = drive::summary::Summary::default();
    let mut refused = Vec::new();
    for (q, q3) in finest.summary.quantities() {
        let (Some(q1), Some(q2)) = (data[0].summary.value(q), data[1].summary.value(q)) else { continue };
        match extrapolate_checked([q1, q2, q3], ratio) {
            Ok((value, order, error_estimate)) => {
                if let Some(p) = order {
                    if !(0.5..=8.0).contains(&p) {
                        notes.push(format!("warning: {q}: observed order {p:.2} outside [0.5, 8] — the three finest levels are likely not in the asymptotic range"));
                    }
                    let p0 = coarser.and_then(|d| d.summary.value(q)).zip(coarser_ratio).and_then(|(q0, r0)| measure::self_order(q0, q1, q2, r0));
                    if let Some(p0) = p0.filter(|p0| (p0 - p).abs() > 0.25 * p) {
                        notes.push(format!("warning: {q}: order {p0:.2} of the coarser triple differs from {p:.2} of the finest by more than 25 % — not yet asymptotic"));
                    }
                }
                summary.set_value(q, Some(value));
                estimates.push(Estimate { quantity: q.to_string(), finest: q3, value, order, error_estimate });
            }
            Err(why) => refused.push(format!("{q}: {why}")),
        }
    }
    for r in &refused {
        notes.push(format!("refused (left out of the reference): {r}"));
    }
    if estimates.is_empty() {
        return Err(RichardsonError::NotAsymptotic { refused });
    }
    let samples = extrapolate_samples([&data[0].samples, &data[1].samples, &finest.samples], ratio, notes);
    let cost = RunCost {
        wall_seconds: three.iter().map(|r| r.wall_seconds).sum(),
        newton_iterations: data.iter().map(|d| d.cost.newton_iterations).sum(),
        unknowns: finest.cost.unknowns,
        mesh_nodes: finest.cost.mesh_nodes,
        elements: finest.cost.elements,
        phases: None,
    };
    Ok(RunData { summary, cost, options: finest.options.clone(), terms: finest.terms.clone(), notes: finest.notes.clone(), warnings: finest.warnings.clone(), samples, history: None })
}

/// Pointwise extrapolation of the sampled fields; a field whose levels do not converge in
/// L2 is dropped (the position and force fields together, since the samples need them).
fn extrapolate_samples(s: [&Samples; 3], ratio: f64, notes: &mut Vec<String>) -> Samples {
    let field = |f: fn(&Samples) -> Option<&[f64]>| -> Option<Vec<f64>> {
        let (a, b, c) = (f(s[0])?, f(s[1])?, f(s[2])?);
        measure::richardson_field(a, b, c, ratio, Norm::L2).map(|(v, _)| v)
    };
    let core = (field(|s| Some(&s.x)), field(|s| Some(&s.y)), field(|s| Some(&s.deflection)), field(|s| Some(&s.tension)));
    let (Some(x), Some(y), Some(deflection), Some(tension)) = core else {
        notes.push("refused: the fields (position, deflection, axial force) are not in the asymptotic range; no field norms against this reference".into());
        return Samples::default();
    };
    Samples {
        sigma: s[2].sigma.clone(),
        x,
        y,
        deflection,
        tension,
        moment: field(|s| s.moment.as_deref()),
        state: s[2].state.clone(),
        pressure: field(|s| s.pressure.as_deref()),
        friction: field(|s| s.friction.as_deref()),
        // refined at each level's own contact edges: no common grid to extrapolate on
        edges: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// q(n) = 2 + 3/n² on halving meshes: the exact limit and order, and the estimate is
    /// the whole error of the finest level, |q_R − q₃| = 3/32².
    #[test]
    fn asymptotic_sequences_extrapolate_and_others_are_refused() {
        let q = |n: f64| 2.0 + 3.0 / (n * n);
        let (v, p, est) = extrapolate_checked([q(8.0), q(16.0), q(32.0)], 2.0).unwrap();
        assert!((v - 2.0).abs() < 1e-13 && (p.unwrap() - 2.0).abs() < 1e-9);
        assert!((est - 3.0 / (32.0 * 32.0)).abs() < 1e-13);
        assert!(matches!(extrapolate_checked([1.0, 1.1, 1.05], 2.0), Err(NotAsymptotic::Oscillating { .. })));
        assert!(matches!(extrapolate_checked([1.0, 1.1, 1.3], 2.0), Err(NotAsymptotic::NotConverging { .. })));
        assert_eq!(extrapolate_checked([1.0, 1.0, 1.0], 2.0).unwrap(), (1.0, None, 0.0));
    }

    #[test]
    fn levels_must_be_three_and_uniform() {
        let run = |n: usize| Run { method: "m".into(), family: Family::Fem, discretisation: Discretisation::Elements(n), wall_seconds: 0.0, outcome: Err(RunError::Failed("x".into())) };
        let (mut e, mut n) = (Vec::new(), Vec::new());
        assert!(matches!(richardson_data(&[run(8), run(16)], &mut e, &mut n), Err(RichardsonError::TooFewLevels { levels: 2 })));
        assert!(matches!(richardson_data(&[run(8), run(16), run(48)], &mut e, &mut n), Err(RichardsonError::NotUniform { .. })));
        assert!(matches!(richardson_data(&[run(8), run(16), run(32)], &mut e, &mut n), Err(RichardsonError::LevelFailed { level: Discretisation::Elements(8), .. })));
    }
}
