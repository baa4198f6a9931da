//! Solve time of the clamped–clamped elastica (θ_max = 90°, exact first mode) from the
//! linear-mode guess, by multiple shooting and by collocation (orders 4 and 6), at
//! tolerances 1e-6 and 1e-9 (order 4 only at 1e-6: at 1e-9 it needs ~9·10⁴ nodes and
//! ~10 s per solve, see the `elastica` example). Short runs (10 samples):
//! `cargo bench -p bvp --bench elastica`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

use bvp::analytical::elastica::{guess, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::shooting::{self, ShootingOptions};

fn elastica(c: &mut Criterion) {
    let exact = Exact::new(std::f64::consts::FRAC_1_SQRT_2).expect("valid modulus");
    let problem = exact.problem();
    let g = guess(1.0, 11);
    let mut group = c.benchmark_group("elastica");
    group.sample_size(10);
    for tol in [1e-6, 1e-9] {
        let opts = ShootingOptions {
            tolerance: tol,
            ..Default::default()
        };
        group.bench_function(format!("shooting/{tol:.0e}"), |b| {
            b.iter(|| {
                shooting::solve(black_box(&problem), black_box(&g), &opts).expect("shooting solves")
            })
        });
        let schemes: &[Scheme] = if tol >= 1e-6 {
            &[Scheme::Gauss4, Scheme::Gauss6]
        } else {
            &[Scheme::Gauss6]
        };
        for &scheme in schemes {
            let opts = CollocationOptions {
                scheme,
                tolerance: tol,
                ..Default::default()
            };
            group.bench_function(format!("collocation-{scheme:?}/{tol:.0e}"), |b| {
                b.iter(|| {
                    collocation::solve(black_box(&problem), black_box(&g), &opts)
                        .expect("collocation solves")
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, elastica);
criterion_main!(benches);
