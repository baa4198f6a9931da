//! Cost against accuracy on the clamped–clamped elastica with its exact first mode
//! (θ_max = 90°, k = 1/√2; see `bvp::analytical::elastica`).
//!
//! For each tolerance 1e-3 … 1e-10 and each method (collocation with every scheme,
//! multiple shooting) the program solves from the linear-mode guess θ = sin 2πs,
//! P = 4π² and prints: mesh nodes of the returned solution, the max error against the
//! exact solution (`Exact::max_error`: component-wise relative to max(1, max|y_i|) on
//! 2001 dense-output points, with P relative and |Q|), the observed order
//! p = −Δlog(error)/Δlog(nodes) between successive tolerances, Newton iterations, and
//! the solve time (best of 3 runs).
//!
//! Run: `cargo run --release -p bvp --example elastica`.

use std::time::Instant;

use bvp::analytical::elastica::{guess, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::shooting::{self, ShootingOptions};
use bvp::{BvpError, Solution};

/// Tolerances of the sweep.
const TOLERANCES: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// Timed repetitions per run (the minimum is reported).
const REPEATS: usize = 3;

/// A method under test: tolerance → solution.
type Method = Box<dyn Fn(f64) -> Result<Solution, BvpError>>;

/// Runs `solve` `REPEATS` times; returns the last solution and the best wall time.
fn timed(solve: impl Fn() -> Result<Solution, BvpError>) -> Result<(Solution, f64), BvpError> {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..REPEATS {
        let t = Instant::now();
        let sol = solve()?;
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(sol);
    }
    Ok((last.expect("REPEATS ≥ 1"), best))
}

fn main() {
    let exact = Exact::new(std::f64::consts::FRAC_1_SQRT_2).expect("valid modulus");
    let problem = exact.problem();
    let [p_exact, _] = exact.params();
    println!(
        "clamped-clamped elastica: theta_max = {:.1} deg, k = {:.6}, a = {:.12}, P = 16 K^2 = {:.12}, Q = 0",
        exact.max_angle().to_degrees(),
        exact.k,
        exact.end_position(),
        p_exact
    );
    println!("guess: theta = sin(2 pi s), P = 4 pi^2 (11 nodes)\n");
    let g = guess(1.0, 11);

    let mut methods: Vec<(String, Method)> = Vec::new();
    for scheme in Scheme::ALL {
        let g = g.clone();
        methods.push((
            format!("collocation {scheme:?}"),
            Box::new(move |tol| {
                let opts = CollocationOptions {
                    scheme,
                    tolerance: tol,
                    ..Default::default()
                };
                collocation::solve(&problem, &g, &opts)
            }),
        ));
    }
    {
        let g = g.clone();
        methods.push((
            "shooting tsit45 (M = 4)".to_string(),
            Box::new(move |tol| {
                let opts = ShootingOptions {
                    tolerance: tol,
                    ..Default::default()
                };
                shooting::solve(&problem, &g, &opts)
            }),
        ));
    }

    println!(
        "{:<26} {:>8} {:>7} {:>11} {:>6} {:>7} {:>11}",
        "method", "tol", "nodes", "max error", "order", "newton", "time [ms]"
    );
    for (name, solve) in &methods {
        let mut prev: Option<(usize, f64)> = None;
        for &tol in &TOLERANCES {
            match timed(|| solve(tol)) {
                Ok((sol, secs)) => {
                    let err = exact.max_error(&sol, 2000);
                    let nodes = sol.stats.mesh_nodes;
                    let order = match prev {
                        Some((n0, e0)) if nodes != n0 => {
                            format!("{:.2}", -(err / e0).ln() / (nodes as f64 / n0 as f64).ln())
                        }
                        _ => "-".to_string(),
                    };
                    println!(
                        "{:<26} {:>8.0e} {:>7} {:>11.3e} {:>6} {:>7} {:>11.3}",
                        name,
                        tol,
                        nodes,
                        err,
                        order,
                        sol.stats.newton_iterations,
                        secs * 1e3
                    );
                    prev = Some((nodes, err));
                }
                Err(e) => println!("{name:<26} {tol:>8.0e}  failed: {e}"),
            }
        }
        println!();
    }
}
