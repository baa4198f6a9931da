//! The stages every belt problem runs, in order: the homotopy from a closed-form start to
//! the scene (natural continuation with the problem's acceptance test), then the final
//! solve at the requested method and tolerance, with the work of both counted in one
//! [`Stats`]. A problem feeds this machinery with its scaled problem (whose η is the
//! homotopy parameter: its path), its start and its acceptance test.

use std::time::Instant;

use crate::collocation::{self, CollocationOptions, Scheme};
use crate::continuation::{self, ContinuationOptions};
use crate::error::BvpError;
use crate::problem::Problem;
use crate::shooting::{self, ShootingOptions};
use crate::solution::{Solution, Stats};

use super::options::{BeltOptions, BvpMethod};

/// The end of a homotopy and the final solve: the solution at η = 1, the work of the
/// whole run, and the number of accepted homotopy points.
#[derive(Debug, Clone)]
pub struct Solved {
    /// The final solution (scaled variables, η = 1).
    pub solution: Solution,
    /// Work of homotopy and final solve; `wall_seconds` since the run's start.
    pub stats: Stats,
    /// Accepted homotopy points (start included).
    pub homotopy_steps: usize,
}

/// Which stage failed, and why (the caller maps it to its error with the stage name).
#[derive(Debug, Clone)]
pub enum StageError {
    /// The homotopy did not reach η = 1.
    Homotopy(BvpError),
    /// The final solve failed.
    Final(BvpError),
}

/// The collocation options of the homotopy path: gauss6 at `opts.homotopy_tolerance`
/// (gauss6, not the default gauss8: the paths, and with them the final meshes of the
/// catalogue scenes, stay those measured when gauss6 was the default).
pub fn path_options(opts: &BeltOptions) -> CollocationOptions {
    CollocationOptions {
        scheme: Scheme::Gauss6,
        tolerance: opts.homotopy_tolerance,
        max_nodes: opts.max_nodes,
        jacobian: opts.jacobian,
        ..CollocationOptions::default()
    }
}

/// The final solve of a belt problem from `guess` by `opts.method` at `opts.tolerance`
/// (collocation: `opts.scheme`, mesh cap `opts.max_nodes`; shooting:
/// `opts.shooting_intervals` per segment).
pub fn final_solve<P: Problem>(problem: &P, guess: &Solution, opts: &BeltOptions) -> Result<Solution, BvpError> {
    match opts.method {
        BvpMethod::Collocation => {
            let o = CollocationOptions {
                scheme: opts.scheme,
                tolerance: opts.tolerance,
                max_nodes: opts.max_nodes,
                jacobian: opts.jacobian,
                ..CollocationOptions::default()
            };
            collocation::solve(problem, guess, &o)
        }
        BvpMethod::Shooting => {
            let o = ShootingOptions {
                tolerance: opts.tolerance,
                intervals_per_segment: opts.shooting_intervals,
                jacobian: opts.jacobian,
                ..ShootingOptions::default()
            };
            shooting::solve(problem, guess, &o)
        }
    }
}

/// Homotopy η: 0 → 1 from `start` (natural continuation, every accepted point passing
/// `accept`), then the final solve; the run's wall time counts from `clock`.
pub fn homotopy_and_final_solve<P: Problem>(
    problem: &P,
    start: &Solution,
    opts: &BeltOptions,
    accept: impl Fn(&Solution) -> Result<(), String>,
    clock: Instant,
) -> Result<Solved, StageError> {
    let branch = continuation::natural_checked(problem, start, 0.0, 1.0, &ContinuationOptions::default(), &path_options(opts), accept)
        .map_err(StageError::Homotopy)?;
    let mut stats = Stats::default();
    stats.add_work(&branch.stats);
    let at_scene = branch.last().expect("a branch ends at its target");
    let solution = final_solve(problem, at_scene, opts).map_err(StageError::Final)?;
    stats.close_with(&solution.stats, clock);
    Ok(Solved { solution, stats, homotopy_steps: branch.points.len() })
}

/// The stages of a problem whose start is already at the scene (η = `start.eta`, no
/// homotopy needed): one collocation solve at the path tolerance from `start` (its
/// failure is reported as the homotopy stage's), then the final solve.
pub fn direct_and_final_solve<P: Problem>(problem: &P, start: &Solution, opts: &BeltOptions, clock: Instant) -> Result<Solved, StageError> {
    let path = collocation::solve(problem, start, &path_options(opts)).map_err(StageError::Homotopy)?;
    let mut stats = Stats::default();
    stats.add_work(&path.stats);
    let solution = final_solve(problem, &path, opts).map_err(StageError::Final)?;
    stats.close_with(&solution.stats, clock);
    Ok(Solved { solution, stats, homotopy_steps: 1 })
}
