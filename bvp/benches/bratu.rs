//! Solve time of the Bratu problem at λ = 3.51 (lower branch, 0.1 % below the fold)
//! by collocation, orders 4 and 6, at tolerances 1e-6 and 1e-9, and of the
//! pseudo-arclength continuation around the fold with fold location.
//! Short runs: `cargo bench -p bvp --bench bratu`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;

use bvp::analytical::bratu::{Bratu, BratuBranch, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::continuation::{self, ContinuationOptions};

fn bratu(c: &mut Criterion) {
    let mut guess = Exact::from_theta(4.0).guess(11);
    guess.eta = 3.51;
    let mut group = c.benchmark_group("bratu");
    group.sample_size(10).measurement_time(Duration::from_secs(3));
    for tol in [1e-6, 1e-9] {
        for scheme in [Scheme::Gauss4, Scheme::Gauss6] {
            let opts = CollocationOptions { scheme, tolerance: tol, ..Default::default() };
            group.bench_function(format!("collocation-{scheme}/{tol:.0e}"), |b| {
                b.iter(|| collocation::solve(black_box(&Bratu), black_box(&guess), &opts).expect("Bratu solves"))
            });
        }
    }
    let start = Exact::new(1.0, BratuBranch::Lower).expect("λ = 1 < λ_c").guess(11);
    let opts = CollocationOptions { scheme: Scheme::Gauss6, tolerance: 1e-8, ..Default::default() };
    let copts = ContinuationOptions { initial_step: 0.2, max_step: 1.0, ..Default::default() };
    group.bench_function("pseudo-arclength-fold-gauss6/1e-8", |b| {
        b.iter(|| {
            continuation::pseudo_arclength(black_box(&Bratu), black_box(&start), 1.0, 0.5, 4.0, &copts, &opts)
                .expect("branch computed")
        })
    });
    group.finish();
}

criterion_group!(benches, bratu);
criterion_main!(benches);
