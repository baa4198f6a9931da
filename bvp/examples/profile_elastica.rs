//! The gauss8 clamped elastica (k = 1/√2, tol 1e-8: the accuracy-matched solve of the
//! `speed` example) solved N times, for instruction counts under
//! `valgrind --tool=callgrind` (load-independent; per solve = difference of two N over
//! their difference). Prints the nodes, Newton iterations and error of the last solve.
//! Run: `cargo run --release -p bvp --example profile_elastica [N]`.

use bvp::analytical::elastica::{guess, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(1), |a| a.parse())?;
    let exact = Exact::new(std::f64::consts::FRAC_1_SQRT_2)?;
    let problem = exact.problem();
    let start = guess(1.0, 11);
    let opts = CollocationOptions { scheme: Scheme::Gauss8, tolerance: 1e-8, ..Default::default() };
    let mut last = None;
    for _ in 0..n {
        last = Some(collocation::solve(&problem, &start, &opts)?);
    }
    if let Some(sol) = last {
        println!(
            "nodes {}  newton {}  error {:.6e}",
            sol.stats.mesh_nodes,
            sol.stats.newton_iterations,
            exact.max_error(&sol, 2000)
        );
    }
    Ok(())
}
