//! Natural-parameter continuation in η ∈ [0, 1] with step control — the one driver of
//! fem's homotopies (the static two-phase homotopy, docs/fem-string.md §9, and the
//! direct steady state's load continuation, docs/fem-drive.md §12). The analysis owns
//! its state and its solve ([`Homotopy`]); the driver owns η, the step and the verdict.
//!
//! From the last accepted η the driver asks for a solve at the target
//! `Homotopy::target(η, step)` (by default min(η + step, 1)). An accepted solve moves η
//! to the target and sets the next step by [`StepControl::grow`] from the step done
//! and the solve's Newton iterations; a rejected one multiplies the step by
//! [`StepControl::shrink`]. The continuation stalls when the step falls below
//! [`StepControl::min_step`] or more than [`StepControl::max_attempts`] solves were
//! tried ([`Stall`]).

/// The outcome of one solve of a continuation.
#[derive(Debug, Clone, PartialEq)]
pub enum Attempt<F> {
    /// Converged: the analysis keeps the new state.
    Accepted {
        /// Newton iterations used.
        iterations: usize,
    },
    /// Not converged: the analysis keeps the old state; the step is shortened.
    Rejected(F),
}

/// The analysis side of a continuation.
pub trait Homotopy {
    /// Why one solve failed (a rejected step).
    type Failure;
    /// An error that ends the whole continuation at once (e.g. a physical limit found
    /// on an accepted state).
    type Error;

    /// Solve at `target` starting from the last accepted point at `eta`.
    ///
    /// # Errors
    /// An error that ends the continuation.
    fn solve_at(&mut self, eta: f64, target: f64) -> Result<Attempt<Self::Failure>, Self::Error>;

    /// Where a step of length `step` from `eta` ends (a path with kinks ends it at the
    /// next kink). Default min(η + step, 1).
    fn target(&self, eta: f64, step: f64) -> f64 {
        (eta + step).min(1.0)
    }
}

/// Step control.
#[derive(Clone, Copy)]
pub struct StepControl<'a> {
    /// First step.
    pub initial: f64,
    /// Smallest step before the continuation stalls.
    pub min_step: f64,
    /// Most solves, accepted or not (`usize::MAX`: no limit).
    pub max_attempts: usize,
    /// Factor on the step after a rejected solve (< 1).
    pub shrink: f64,
    /// The next step after an accepted one, from (step done, step tried, Newton
    /// iterations).
    pub grow: &'a dyn Fn(f64, f64, usize) -> f64,
}

/// Work of a completed continuation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PathReport {
    /// Accepted solves.
    pub accepted: usize,
    /// Rejected solves.
    pub rejected: usize,
}

/// Why a continuation stopped before η = 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Stall<F> {
    /// Last accepted η.
    pub eta: f64,
    /// The step after the last rejection.
    pub step: f64,
    /// The target of the last attempt.
    pub target: f64,
    /// Accepted solves.
    pub accepted: usize,
    /// True: the attempt limit was reached; false: the step fell below its minimum.
    pub attempts_exhausted: bool,
    /// The last failed solve (none if the attempt limit came first).
    pub last: Option<F>,
}

/// Why a continuation ended before η = 1.
#[derive(Debug, Clone, PartialEq)]
pub enum Stop<F, E> {
    /// The step control gave up.
    Stalled(Stall<F>),
    /// The analysis ended it ([`Homotopy::Error`]).
    Aborted(E),
}

/// Run the continuation from `eta` = 0 (the start solved by the caller) to 1.
///
/// # Errors
/// [`Stop::Stalled`] with the last accepted η, the step and the last failure;
/// [`Stop::Aborted`] with the analysis's error.
pub fn natural<H: Homotopy>(homotopy: &mut H, control: &StepControl<'_>) -> Result<PathReport, Stop<H::Failure, H::Error>> {
    let (mut eta, mut step) = (0.0f64, control.initial);
    let mut report = PathReport::default();
    let mut attempts = 0usize;
    let mut target = eta;
    let mut last = None;
    while eta < 1.0 {
        attempts += 1;
        if attempts > control.max_attempts {
            return Err(Stop::Stalled(Stall { eta, step, target, accepted: report.accepted, attempts_exhausted: true, last }));
        }
        target = homotopy.target(eta, step);
        match homotopy.solve_at(eta, target).map_err(Stop::Aborted)? {
            Attempt::Accepted { iterations } => {
                report.accepted += 1;
                let done = target - eta;
                eta = target;
                step = (control.grow)(done, step, iterations);
            }
            Attempt::Rejected(failure) => {
                report.rejected += 1;
                step *= control.shrink;
                last = Some(failure);
                if step < control.min_step {
                    return Err(Stop::Stalled(Stall { eta, step, target, accepted: report.accepted, attempts_exhausted: false, last }));
                }
            }
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A homotopy whose solves fail when the step exceeds `reach` (a stand-in for
    /// Newton's radius of convergence) and take more iterations for longer steps.
    struct Reach {
        reach: f64,
        kink: Option<f64>,
        visited: Vec<f64>,
    }

    impl Homotopy for Reach {
        type Failure = f64;
        type Error = ();
        fn solve_at(&mut self, eta: f64, target: f64) -> Result<Attempt<f64>, ()> {
            if target - eta > self.reach {
                return Ok(Attempt::Rejected(target));
            }
            self.visited.push(target);
            Ok(Attempt::Accepted { iterations: 2 + (20.0 * (target - eta) / self.reach) as usize })
        }
        fn target(&self, eta: f64, step: f64) -> f64 {
            let t = (eta + step).min(1.0);
            match self.kink {
                Some(k) if eta < k && t > k => k,
                _ => t,
            }
        }
    }

    /// η reaches 1 exactly, passes through the kink, never steps beyond the reach; the
    /// targets follow the step rule (double the step after a fast solve).
    #[test]
    fn reaches_one_through_the_kink_within_the_reach() {
        let grow = |done: f64, _step: f64, it: usize| if it <= 8 { 2.0 * done } else { done };
        let control = StepControl { initial: 0.1, min_step: 1e-3, max_attempts: 100, shrink: 0.25, grow: &grow };
        let mut h = Reach { reach: 0.3, kink: Some(0.5), visited: vec![] };
        let report = natural(&mut h, &control).unwrap();
        assert_eq!(*h.visited.last().unwrap(), 1.0);
        assert!(h.visited.contains(&0.5));
        assert!(h.visited.windows(2).all(|w| w[1] > w[0] && w[1] - w[0] <= 0.3 + 1e-15));
        assert_eq!(report.accepted, h.visited.len());
        // 0.1 (it 8: grow to 0.2), 0.3 (it 15: keep 0.2), 0.5, 0.7 (kink at 0.5 hit
        // exactly), 0.9, 1.0 — no rejection
        assert_eq!(h.visited.len(), 6, "{:?}", h.visited);
        assert_eq!(report.rejected, 0);
    }

    /// Too small a reach stalls with the step below its minimum and the last failure;
    /// an attempt limit stops earlier with `attempts_exhausted`.
    #[test]
    fn stalls_with_the_numbers() {
        let grow = |done: f64, _step: f64, _it: usize| 2.0 * done;
        let control = StepControl { initial: 0.5, min_step: 1e-3, max_attempts: usize::MAX, shrink: 0.5, grow: &grow };
        let mut h = Reach { reach: 1e-4, kink: None, visited: vec![] };
        let Err(Stop::Stalled(stall)) = natural(&mut h, &control) else { panic!("expected a stall") };
        assert_eq!(stall.eta, 0.0);
        assert!(stall.step < 1e-3 && stall.step >= 0.5e-3);
        assert!(!stall.attempts_exhausted);
        assert_eq!(stall.last, Some(stall.target));
        let limited = StepControl { max_attempts: 3, ..control };
        let Err(Stop::Stalled(stall)) = natural(&mut Reach { reach: 1e-4, kink: None, visited: vec![] }, &limited) else { panic!("expected a stall") };
        assert!(stall.attempts_exhausted);
        assert_eq!(stall.step, 0.5 * 0.5 * 0.5 * 0.5);
    }
}
