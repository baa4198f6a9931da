//! Best-of-N CPU time of the collocation solver on the three problems of the speed
//! issue, for comparison with scipy's `solve_bvp` peers (`../shared/peers/`, run in the
//! same shell run; `docs/bvp-engine.md`, section "Speed").
//!
//! - `string-hanging` scene from its file, collocation at tolerance 1e-8, default scheme
//!   (homotopy included, as `beltcheck solve … --method bvp-collocation --tolerance 1e-8`);
//! - Bratu λ = 3.51 (lower branch) and the clamped elastica (k = 1/√2): for each scheme
//!   the loosest tolerance 10⁻ᵉ whose error against the closed form is at most scipy's
//!   at tol 1e-8 (3.5e-10 and 9.6e-11, `../shared/peers/README.md`).
//!
//! With a third argument `wp` it then sweeps, for Bratu and the elastica and each
//! scheme, the tolerances 10^(-4 - k/2) down to 1e-12 (a work–precision curve: one line
//! `wp NAME SCHEME tol … nodes … newton … error … cpu … ms` per tolerance; a scheme's
//! sweep stops at its first failure or once one solve takes > 0.5 s), for
//! `speed_vs_scipy.py --wp`, which compares the times at equal error.
//!
//! Time: CPU time of this thread (`/proc/thread-self/schedstat`, nanoseconds on CPU;
//! wall time where that file is missing) per solve, best of REPEATS batches of solves
//! (≥ 0.2 s each), so that the load of a shared machine does not enter. Run:
//! `cargo run --release -p bvp --example speed [scenes/string-hanging.json] [REPEATS] [wp]`.

use std::time::Instant;

use bvp::analytical::bratu::{Bratu, BratuBranch, Exact as BratuExact};
use bvp::analytical::elastica::{guess as elastica_guess, Exact as ElasticaExact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::scene::{solve_scene, BvpMethod, BvpRunOptions};
use bvp::{BvpError, Solution};
use drive::scene::Scene;

/// Seconds this thread has been on a CPU (wall time where the kernel does not say).
fn cpu_seconds(wall: &Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|v| v.parse::<f64>().ok()))
        .map_or_else(|| wall.elapsed().as_secs_f64(), |ns| ns * 1e-9)
}

/// Best CPU time per run of `run` over `repeats` batches, and its last result. The
/// kernel updates the thread's CPU time only at scheduler ticks (≤ 4 ms apart), so a
/// batch repeats `run` until it has taken ≥ 0.2 s (calibrated by one run), keeping the
/// tick error below 2 %.
fn best_of<T>(repeats: usize, mut run: impl FnMut() -> T) -> (f64, T) {
    let wall = Instant::now();
    let t0 = wall.elapsed().as_secs_f64();
    let mut last = run();
    let once = (wall.elapsed().as_secs_f64() - t0).max(1e-6);
    let batch = ((0.2 / once).ceil() as usize).clamp(1, 10_000);
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t0 = cpu_seconds(&wall);
        for _ in 0..batch {
            last = run();
        }
        best = best.min((cpu_seconds(&wall) - t0) / batch as f64);
    }
    (best, last)
}

/// For each scheme: the loosest tolerance reaching `target` error, its nodes, Newton
/// iterations, error and best CPU time.
fn accuracy_matched(
    name: &str,
    target: f64,
    repeats: usize,
    solve: impl Fn(&CollocationOptions) -> Result<Solution, BvpError>,
    error: impl Fn(&Solution) -> f64,
) {
    for scheme in Scheme::ALL {
        let found = (6..=12).map(|e| 10f64.powi(-e)).find_map(|tol| {
            let opts = CollocationOptions { scheme, tolerance: tol, ..Default::default() };
            let sol = solve(&opts).ok()?;
            (error(&sol) <= target).then_some((tol, opts))
        });
        match found {
            Some((tol, opts)) => {
                let (cpu, sol) = best_of(repeats, || solve(&opts).expect("solved once already"));
                println!(
                    "{name:<14} {:<7} tol {tol:.0e}  nodes {:>5}  newton {:>3}  error {:.2e}  cpu {:>8.3} ms",
                    scheme.name(),
                    sol.stats.mesh_nodes,
                    sol.stats.newton_iterations,
                    error(&sol),
                    cpu * 1e3
                );
            }
            None => println!("{name:<14} {:<7} error {target:.1e} not reached by tol 1e-12", scheme.name()),
        }
    }
}

/// The tolerances of the work–precision sweep: 10^(-4 - k/2), k = 0 … 16 (1e-4 … 1e-12).
fn sweep_tolerances() -> impl Iterator<Item = f64> {
    (0..=16).map(|k| 10f64.powf(-4.0 - 0.5 * f64::from(k)))
}

/// Work–precision sweep of every scheme: per tolerance the nodes, Newton iterations,
/// error and best CPU time; a scheme stops at its first failure or after a solve of
/// more than 0.5 s (the tighter tolerances would only take longer).
fn work_precision(
    name: &str,
    repeats: usize,
    solve: impl Fn(&CollocationOptions) -> Result<Solution, BvpError>,
    error: impl Fn(&Solution) -> f64,
) {
    for scheme in Scheme::ALL {
        for tol in sweep_tolerances() {
            let opts = CollocationOptions { scheme, tolerance: tol, ..Default::default() };
            let wall = Instant::now();
            if let Err(e) = solve(&opts) {
                println!("wp {name} {} tol {tol:.3e} failed: {e}", scheme.name());
                break;
            }
            let once = wall.elapsed().as_secs_f64();
            let (cpu, sol) = best_of(repeats, || solve(&opts).expect("solved once already"));
            println!(
                "wp {name} {} tol {tol:.3e} nodes {} newton {} error {:.4e} cpu {:.4} ms",
                scheme.name(),
                sol.stats.mesh_nodes,
                sol.stats.newton_iterations,
                error(&sol),
                cpu * 1e3
            );
            if once > 0.5 {
                break;
            }
        }
    }
}

/// Work–precision sweep of the scene for gauss6 and gauss8 (tolerances as
/// [`sweep_tolerances`], 1e-5 … 1e-12): per tolerance the nodes, Newton iterations, the
/// four mid-span values of the summary (y upper, y lower, tension upper, tension lower,
/// to 16 digits: the error is taken against a reference by `speed_vs_scipy.py --wp`) and
/// the best CPU time.
fn scene_work_precision(scene: &Scene, base: &BvpRunOptions, repeats: usize) {
    for scheme in [Scheme::Gauss6, Scheme::Gauss8] {
        for tol in sweep_tolerances().skip(2) {
            let opts = BvpRunOptions { method: BvpMethod::Collocation, tolerance: tol, scheme, ..base.clone() };
            let wall = Instant::now();
            if let Err(e) = solve_scene(scene, &opts) {
                println!("wp scene {} tol {tol:.3e} failed: {e}", scheme.name());
                break;
            }
            let once = wall.elapsed().as_secs_f64();
            let (cpu, run) = best_of(repeats, || solve_scene(scene, &opts).expect("solved once already"));
            let s = &run.summary;
            let values = [s.y_upper_mid, s.y_lower_mid, s.tension_upper_mid, s.tension_lower_mid]
                .map(|v| v.map_or_else(|| "nan".to_string(), |v| format!("{v:.16e}")))
                .join(" ");
            println!(
                "wp scene {} tol {tol:.3e} nodes {} newton {} values {values} cpu {:.4} ms",
                scheme.name(),
                run.stats.mesh_nodes,
                run.stats.newton_iterations,
                cpu * 1e3
            );
            if once > 0.5 {
                break;
            }
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("scenes/string-hanging.json", String::as_str);
    let repeats: usize = args.get(2).map_or(Ok(5), |r| r.parse())?;
    let sweep = args.get(3).is_some_and(|a| a == "wp");
    println!("CPU time per solve (this thread), best of {repeats} batches of ≥ 0.2 s\n");

    let scene = Scene::from_path(std::path::Path::new(path))?;
    let base = BvpRunOptions::from_scene(&scene)?;
    let opts = BvpRunOptions { method: BvpMethod::Collocation, tolerance: 1e-8, ..base };
    let (cpu, run) = best_of(repeats, || solve_scene(&scene, &opts).expect("scene solves"));
    println!(
        "{path} tol 1e-8 ({}): nodes {}, Newton {}, cpu {:.3} ms",
        opts.scheme.name(),
        run.stats.mesh_nodes,
        run.stats.newton_iterations,
        cpu * 1e3
    );

    let exact = BratuExact::new(3.51, BratuBranch::Lower)?;
    let mut guess = BratuExact::from_theta(4.0).guess(11);
    guess.eta = 3.51;
    let bratu_solve = |o: &CollocationOptions| collocation::solve(&Bratu, &guess, o);
    let bratu_error = |s: &Solution| exact.max_dense_error(s, 2001);
    accuracy_matched("bratu 3.51", 3.5e-10, repeats, bratu_solve, bratu_error);
    let elastica = ElasticaExact::new(std::f64::consts::FRAC_1_SQRT_2)?;
    let problem = elastica.problem();
    let start = elastica_guess(1.0, 11);
    let elastica_solve = |o: &CollocationOptions| collocation::solve(&problem, &start, o);
    let elastica_error = |s: &Solution| elastica.max_error(s, 2000);
    accuracy_matched("elastica", 9.6e-11, repeats, elastica_solve, elastica_error);
    if sweep {
        println!();
        work_precision("bratu", repeats, bratu_solve, bratu_error);
        work_precision("elastica", repeats, elastica_solve, elastica_error);
        scene_work_precision(&scene, &base, repeats);
    }
    Ok(())
}
