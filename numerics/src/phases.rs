//! Where a solve's time goes: seconds per phase (assembly, factorisation, solves, …)
//! and work counts (Newton iterations, continuation steps, refinements, fitting passes),
//! filled by every solver of `bvp` and `fem` through the same two calls.
//!
//! A caller that wants the breakdown wraps the whole solve in [`record`]; inside it the
//! solvers mark their phases with [`timed`] and their steps with [`count`]. Outside a
//! [`record`] both are no-ops apart from one thread-local read, so a solver marks its
//! phases unconditionally.
//!
//! # What a phase's seconds are
//! *Exclusive* wall time: a phase entered inside another (the numeric LU inside the
//! Jacobian assembly of a Newton iteration, the Newton solves inside a fitting pass)
//! pauses the outer one, so the phases never count a second twice and their sum is at
//! most the wall time of the [`record`]; the rest of the wall time (set-up, summaries,
//! sampling, copies) is [`Phases::other`]. Only [`Phases::fitting_total`] is inclusive:
//! the wall time inside the mesh fitting, its Newton solves included — the price of
//! fitting the mesh.
//!
//! # Cost
//! Two `Instant::now()` and two thread-local accesses per phase entered; the solvers
//! mark phases per Newton iteration, per factorisation and per mesh pass, never per
//! element or per quadrature point. Work run on other threads (rayon's parallel element
//! loops) is timed as the wall time the calling thread spends waiting for it.

use std::cell::RefCell;
use std::time::Instant;

/// A phase of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Jacobian assembly: element / interval evaluations and their scatter (the
    /// collocation's condensation to the mesh nodes included), everything a
    /// factorisation call does besides the LU itself.
    Assembly,
    /// Symbolic sparse LU (ordering and elimination structure), once per pattern.
    SymbolicFactorisation,
    /// Numeric LU.
    NumericFactorisation,
    /// Triangular solves with a factorised Jacobian.
    LinearSolves,
    /// Residual evaluations (Newton trials) and the error estimate of mesh adaptation.
    Residuals,
    /// Integration of flows (shooting: the initial-value problems of every interval,
    /// with or without their sensitivities).
    Integration,
    /// Mesh adaptation: new meshes and the transfer of the solution onto them.
    MeshAdaptation,
    /// Mesh fitting (FE): locating breakpoints, building the fitted mesh, transferring
    /// the state — its Newton solves are in the phases above.
    Fitting,
}

impl Phase {
    /// Every phase, in the order of [`Phases::seconds`].
    pub const ALL: [Phase; 8] = [
        Phase::Assembly,
        Phase::SymbolicFactorisation,
        Phase::NumericFactorisation,
        Phase::LinearSolves,
        Phase::Residuals,
        Phase::Integration,
        Phase::MeshAdaptation,
        Phase::Fitting,
    ];

    /// Short name, as in the result's `cost.phases` (snake case).
    pub fn name(self) -> &'static str {
        match self {
            Phase::Assembly => "assembly",
            Phase::SymbolicFactorisation => "symbolic_factorisation",
            Phase::NumericFactorisation => "numeric_factorisation",
            Phase::LinearSolves => "linear_solves",
            Phase::Residuals => "residuals",
            Phase::Integration => "integration",
            Phase::MeshAdaptation => "mesh_adaptation",
            Phase::Fitting => "fitting",
        }
    }
}

/// A counted step of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// One Newton iteration (one Jacobian factorisation of an iteration).
    NewtonIteration,
    /// One accepted continuation step.
    ContinuationStep,
    /// One mesh adaptation pass (a new collocation mesh).
    MeshRefinement,
    /// One mesh fitting pass (a refit of the FE mesh to its breakpoints).
    FittingPass,
}

/// The breakdown of one recorded solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Phases {
    /// Exclusive seconds per phase, in the order of [`Phase::ALL`].
    pub seconds: [f64; 8],
    /// Wall time inside the mesh fitting, its Newton solves included, s (inclusive).
    pub fitting_total: f64,
    /// Newton iterations counted by the solvers' Newton loops.
    pub newton_iterations: usize,
    /// Accepted continuation steps.
    pub continuation_steps: usize,
    /// Mesh adaptation passes.
    pub mesh_refinements: usize,
    /// Mesh fitting passes.
    pub fitting_passes: usize,
}

impl Phases {
    /// Exclusive seconds of `phase`.
    pub fn get(&self, phase: Phase) -> f64 {
        self.seconds[phase as usize]
    }

    /// Sum of the exclusive seconds of every phase.
    pub fn timed(&self) -> f64 {
        self.seconds.iter().sum()
    }

    /// `wall − Σ phases`, s, never below 0 (the clock of the caller's wall time is read
    /// outside [`record`], so the difference can be a few ns negative).
    pub fn other(&self, wall: f64) -> f64 {
        (wall - self.timed()).max(0.0)
    }

    /// The phase with the most seconds (`None` if nothing was timed).
    pub fn dominant(&self) -> Option<Phase> {
        Phase::ALL.into_iter().filter(|&p| self.get(p) > 0.0).max_by(|&a, &b| self.get(a).total_cmp(&self.get(b)))
    }

    fn add(&mut self, phase: Phase, seconds: f64) {
        self.seconds[phase as usize] += seconds;
    }
}

/// One phase open on the stack: since when it runs (again), and when it was entered.
struct Open {
    phase: Phase,
    resumed: Instant,
    entered: Instant,
}

#[derive(Default)]
struct Recorder {
    phases: Phases,
    open: Vec<Open>,
}

thread_local! {
    /// The recorders of the [`record`] calls open on this thread, innermost last.
    static RECORDERS: RefCell<Vec<Recorder>> = const { RefCell::new(Vec::new()) };
}

fn with_recorder(f: impl FnOnce(&mut Recorder)) {
    RECORDERS.with(|r| {
        if let Some(rec) = r.borrow_mut().last_mut() {
            f(rec);
        }
    });
}

/// Runs `solve` and returns its value with the breakdown of the phases it marked.
/// Calls may nest: an inner [`record`] collects its own phases, the outer one sees
/// its time as its own current phase's (or as `other`).
pub fn record<T>(solve: impl FnOnce() -> T) -> (T, Phases) {
    struct Pop;
    impl Drop for Pop {
        fn drop(&mut self) {
            RECORDERS.with(|r| r.borrow_mut().pop());
        }
    }
    RECORDERS.with(|r| r.borrow_mut().push(Recorder::default()));
    let pop = Pop;
    let value = solve();
    let phases = RECORDERS.with(|r| r.borrow().last().map(|rec| rec.phases).unwrap_or_default());
    drop(pop);
    (value, phases)
}

/// Runs `f` as `phase` of the solve being recorded (see the module documentation).
pub fn timed<T>(phase: Phase, f: impl FnOnce() -> T) -> T {
    struct Close(bool);
    impl Drop for Close {
        fn drop(&mut self) {
            if self.0 {
                leave();
            }
        }
    }
    let mut entered = false;
    with_recorder(|rec| {
        let now = Instant::now();
        if let Some(outer) = rec.open.last() {
            let paused = now.duration_since(outer.resumed).as_secs_f64();
            rec.phases.add(outer.phase, paused);
        }
        rec.open.push(Open { phase, resumed: now, entered: now });
        entered = true;
    });
    let _close = Close(entered);
    f()
}

fn leave() {
    with_recorder(|rec| {
        let now = Instant::now();
        let Some(done) = rec.open.pop() else { return };
        rec.phases.add(done.phase, now.duration_since(done.resumed).as_secs_f64());
        if done.phase == Phase::Fitting && !rec.open.iter().any(|o| o.phase == Phase::Fitting) {
            rec.phases.fitting_total += now.duration_since(done.entered).as_secs_f64();
        }
        if let Some(outer) = rec.open.last_mut() {
            outer.resumed = now;
        }
    });
}

/// Counts `n` steps of kind `step` for the solve being recorded.
pub fn count(step: Step, n: usize) {
    with_recorder(|rec| {
        let c = &mut rec.phases;
        match step {
            Step::NewtonIteration => c.newton_iterations += n,
            Step::ContinuationStep => c.continuation_steps += n,
            Step::MeshRefinement => c.mesh_refinements += n,
            Step::FittingPass => c.fitting_passes += n,
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn busy(d: Duration) {
        let t = Instant::now();
        while t.elapsed() < d {}
    }

    /// Nested phases are exclusive: each transition reads the clock once and hands the
    /// same instant to the phase left and the phase resumed, so the three exclusive
    /// times add up to the inclusive fitting time to rounding (1e-12 s on a 10 ms sum:
    /// double-counting the nested 6 ms would miss it by 6e-3); their sum stays within
    /// the recorded wall. Only lower bounds on the busy waits (2, 4, 2 ms): a loaded
    /// machine stretches them.
    #[test]
    fn nested_phases_are_exclusive_and_sum_to_at_most_the_wall() {
        let t = Instant::now();
        let ((), p) = record(|| {
            timed(Phase::Fitting, || {
                busy(Duration::from_millis(2));
                timed(Phase::Assembly, || {
                    busy(Duration::from_millis(4));
                    timed(Phase::NumericFactorisation, || busy(Duration::from_millis(2)));
                });
                count(Step::FittingPass, 1);
            });
            count(Step::NewtonIteration, 3);
        });
        let wall = t.elapsed().as_secs_f64();
        let (f, a, n) = (p.get(Phase::Fitting), p.get(Phase::Assembly), p.get(Phase::NumericFactorisation));
        assert!(f >= 0.002 && a >= 0.004 && n >= 0.002, "{p:?}");
        assert!((f + a + n - p.fitting_total).abs() < 1e-12, "{p:?}");
        assert!(p.timed() <= wall, "{} > {wall}", p.timed());
        assert_eq!((p.newton_iterations, p.fitting_passes), (3, 1));
        assert_eq!(p.other(0.0), 0.0);
    }

    #[test]
    fn outside_a_record_nothing_is_kept_and_records_nest() {
        timed(Phase::Assembly, || count(Step::NewtonIteration, 1));
        let (((), inner), outer) = record(|| {
            count(Step::ContinuationStep, 1);
            record(|| count(Step::ContinuationStep, 5))
        });
        assert_eq!((outer.continuation_steps, inner.continuation_steps), (1, 5));
        assert_eq!(record(|| ()).1, Phases::default());
    }
}
