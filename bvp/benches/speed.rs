//! The three problems of the speed comparison with scipy's `solve_bvp`
//! (`docs/bvp-engine.md`, section "Speed"; best-of-N CPU times by
//! `cargo run --release -p bvp --example speed`): the `string-hanging` catalogue scene
//! from its file at tolerance 1e-8 with its default scheme (homotopy included), Bratu
//! λ = 3.51 and the clamped elastica at the loosest tolerances whose errors match
//! scipy's at tol 1e-8 (1e-8 for gauss6 and gauss8 on both, found by the `speed`
//! example). Short runs:
//! `cargo bench -p bvp --bench speed`.

use std::hint::black_box;
use std::time::Duration;

use bvp::analytical::bratu::{Bratu, Exact as BratuExact};
use bvp::analytical::elastica::{guess as elastica_guess, Exact as ElasticaExact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::scene::{solve_scene, BvpMethod, BvpRunOptions};
use criterion::{criterion_group, criterion_main, Criterion};
use drive::scene::Scene;

fn speed(c: &mut Criterion) {
    let mut g = c.benchmark_group("speed");
    g.sample_size(10).measurement_time(Duration::from_secs(4)).warm_up_time(Duration::from_millis(500));
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/string-hanging.json");
    let scene = Scene::from_path(std::path::Path::new(path)).expect("catalogue scene loads");
    let base = BvpRunOptions::from_scene(&scene).expect("scene options valid");
    let opts = BvpRunOptions { method: BvpMethod::Collocation, tolerance: 1e-8, ..base };
    g.bench_function(format!("string-hanging-scene/{}/tol=1e-8", opts.scheme.name()), |b| {
        b.iter(|| solve_scene(black_box(&scene), &opts).expect("scene solves"))
    });

    let mut guess = BratuExact::from_theta(4.0).guess(11);
    guess.eta = 3.51;
    for scheme in [Scheme::Gauss6, Scheme::Gauss8] {
        let opts = CollocationOptions { scheme, tolerance: 1e-8, ..Default::default() };
        g.bench_function(format!("bratu-3.51/{}/tol=1e-8", scheme.name()), |b| {
            b.iter(|| collocation::solve(black_box(&Bratu), black_box(&guess), &opts).expect("Bratu solves"))
        });
    }

    let problem = ElasticaExact::new(std::f64::consts::FRAC_1_SQRT_2).expect("valid modulus").problem();
    let guess = elastica_guess(1.0, 11);
    for (scheme, tol) in [(Scheme::Gauss6, 1e-8), (Scheme::Gauss8, 1e-8)] {
        let opts = CollocationOptions { scheme, tolerance: tol, ..Default::default() };
        g.bench_function(format!("elastica/{}/tol={tol:.0e}", scheme.name()), |b| {
            b.iter(|| collocation::solve(black_box(&problem), black_box(&guess), &opts).expect("elastica solves"))
        });
    }

    // The engine's cost of one mesh, without the adaptation around it: the converged
    // gauss8 elastica (213 nodes) solved again on its own mesh, mesh adaptation off —
    // one Newton iteration (the condensation, the sparse LU with its symbolic analysis
    // of a new pattern, the solves) and one residual estimate.
    let opts = CollocationOptions { scheme: Scheme::Gauss8, tolerance: 1e-8, ..Default::default() };
    let converged = collocation::solve(&problem, &guess, &opts).expect("elastica solves");
    let fixed = CollocationOptions { adapt_mesh: false, ..opts };
    g.bench_function(format!("elastica-one-mesh/gauss8/{}-nodes", converged.stats.mesh_nodes), |b| {
        b.iter(|| collocation::solve(black_box(&problem), black_box(&converged), &fixed).expect("elastica solves"))
    });
    g.finish();
}

criterion_group!(benches, speed);
criterion_main!(benches);
