//! The Bratu problem y'' + λ e^y = 0, y(0) = y(1) = 0 near its fold, by collocation.
//!
//! Prints, for residual tolerances 1e-3 … 1e-10 and each collocation scheme, the mesh
//! size, the error against the closed form (at the nodes and of the dense output),
//! Newton iterations and wall time, on the lower branch at λ = 3.51 (λ_c = 3.5138…);
//! then the fold located by pseudo-arclength continuation and its error.
//!
//! Run: `cargo run --release -p bvp --example bratu`

use bvp::analytical::bratu::{Bratu, BratuBranch, Exact, CRITICAL_LAMBDA};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::continuation::{self, ContinuationOptions};
use bvp::BvpError;

const LAMBDA: f64 = 3.51;

fn main() -> Result<(), BvpError> {
    let exact = Exact::new(LAMBDA, BratuBranch::Lower)?;
    // Guess: the exact shape for θ = 4 (λ ≈ 3.35), on 11 nodes, at η = 3.51.
    let mut guess = Exact::from_theta(4.0).guess(11);
    guess.eta = LAMBDA;
    println!(
        "Bratu y'' + λ e^y = 0, λ = {LAMBDA}, lower branch (θ = {:.12}), guess: θ = 4 shape on 11 nodes",
        exact.theta
    );
    println!("tolerance: RMS of the relative collocation residual per interval (see CollocationOptions::tolerance)\n");
    println!(
        "{:>8} {:>7} {:>7} {:>8} {:>11} {:>11} {:>7} {:>6} {:>10}",
        "scheme", "tol", "nodes", "unknowns", "node err", "dense err", "newton", "passes", "time [ms]"
    );
    for scheme in [Scheme::Gauss4, Scheme::Gauss6, Scheme::Gauss8] {
        for e in 3..=10 {
            let tol = 10f64.powi(-e);
            let opts = CollocationOptions { scheme, tolerance: tol, ..Default::default() };
            match collocation::solve(&Bratu, &guess, &opts) {
                Ok(sol) => println!(
                    "{:>8} {:>7.0e} {:>7} {:>8} {:>11.3e} {:>11.3e} {:>7} {:>6} {:>10.2}",
                    scheme.name(),
                    tol,
                    sol.stats.mesh_nodes,
                    sol.stats.unknowns,
                    exact.max_node_error(&sol),
                    exact.max_dense_error(&sol, 2001),
                    sol.stats.newton_iterations,
                    sol.stats.refinements,
                    sol.stats.wall_seconds * 1e3
                ),
                Err(err) => println!("{:>8} {:>7.0e}  failed: {err}", scheme.name(), tol),
            }
        }
        println!();
    }

    // Fold by pseudo-arclength continuation from λ = 1 on the lower branch.
    let opts = CollocationOptions { scheme: Scheme::Gauss6, tolerance: 1e-8, ..Default::default() };
    let copts = ContinuationOptions { initial_step: 0.2, max_step: 1.0, ..Default::default() };
    let start = Exact::new(1.0, BratuBranch::Lower)?.guess(11);
    let branch = continuation::pseudo_arclength(&Bratu, &start, 1.0, 0.5, 4.0, &copts, &opts)?;
    println!(
        "pseudo-arclength from λ = 1 (gauss6, tol 1e-8): {} points, ended {:?}, {} Newton iterations, {:.1} ms",
        branch.points.len(),
        branch.termination,
        branch.stats.newton_iterations,
        branch.stats.wall_seconds * 1e3
    );
    for fold in &branch.folds {
        println!(
            "fold: λ = {:.15}  (exact λ_c = {CRITICAL_LAMBDA:.15}, error {:.2e}); located on {} by {} evaluations, {} nodes",
            fold.eta,
            (fold.eta - CRITICAL_LAMBDA).abs(),
            fold.coordinate,
            fold.evaluations,
            fold.solution.stats.mesh_nodes
        );
    }
    if branch.folds.is_empty() {
        println!("no fold found");
    }
    Ok(())
}
